//! The join of the part files of one run ([`join`]) and the file it writes
//! ([`Joined::write`]): the unsharded run's file, but for its shard line. The parts
//! must be of one run (the same tool, specification, layout and sections) with every
//! shard exactly once; that is decided on what [`read_part`](super::read_part)
//! kept of each (everything but its values). Writing reads every part's values again,
//! side by side, and merges them into index order holding one value per part, so
//! memory does not grow with the parts.

use super::reread::Next;
use super::{differing_setting, shard_name, FileKind, Layout, Part, PartWriter, Reread};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::io::{self, BufRead, Write};

/// The parts of one run joined: what the unsharded run writes.
#[derive(Clone, Debug)]
pub struct Joined<K: FileKind> {
    pub layout: Layout,
    pub header: K::Header,
    /// Shards joined (1 for a whole file).
    pub shards: usize,
    /// The json texts of the sections before the values.
    pub sections: Vec<String>,
    /// The parts, in the order of their shards.
    pub parts: Vec<Part<K>>,
    /// Values in all.
    pub count: usize,
}

/// Why a joined file could not be written: a part (changed since it was checked, or
/// unreadable), or the output.
#[derive(Debug)]
pub enum JoinError {
    Part(String),
    Write(io::Error),
}

impl<K: FileKind> Joined<K> {
    /// Write the joined file: the unsharded run's, but for its shard, which says
    /// `merged N/N` where the unsharded file says `1/1`. `open(part)` reads a part's
    /// values again (its file from `part.body.offset`, `part.body.len` bytes); they are
    /// merged into index order as they are read, holding one value per part (a csv row
    /// per part: a csv value is copied a row at a time).
    pub fn write<W: Write, R: BufRead>(
        &self,
        out: W,
        mut open: impl FnMut(&Part<K>) -> io::Result<R>,
    ) -> Result<W, JoinError> {
        let shard = if self.shards > 1 {
            format!("merged {0}/{0}", self.shards)
        } else {
            "1/1".to_string()
        };
        let mut streams = Vec::with_capacity(self.parts.len());
        for p in &self.parts {
            let body =
                open(p).map_err(|e| JoinError::Part(format!("{}: cannot read: {e}", p.name)))?;
            streams.push(p.reread(body));
        }
        let sections: Vec<&str> = self.sections.iter().map(String::as_str).collect();
        let mut w = PartWriter::<W, K>::begin(
            out,
            self.layout,
            &self.header,
            &shard,
            self.count,
            &sections,
        )
        .map_err(JoinError::Write)?;
        // What each part hands out next, and the parts by the place of that value.
        let mut heads: Vec<Option<Next<K>>> = (0..streams.len()).map(|_| None).collect();
        let mut queue = BinaryHeap::new();
        for s in 0..streams.len() {
            queue.extend(advance(s, &mut streams, &mut heads)?);
        }
        let mut written = 0usize;
        while let Some(Reverse((place, s))) = queue.pop() {
            // Checked parts hold every place once: 0, 1, 2, … in turn.
            if place != written {
                return Err(JoinError::Part(format!(
                    "{}: value {place} where value {written} belongs",
                    self.parts[s].name
                )));
            }
            match heads[s].take() {
                Some(Next::Value(v)) => w.value(&v).map_err(JoinError::Write)?,
                Some(Next::Row(row)) => {
                    w.csv_row(&row, true).map_err(JoinError::Write)?;
                    while let Some(row) = streams[s].more().map_err(JoinError::Part)? {
                        w.csv_row(&row, false).map_err(JoinError::Write)?;
                    }
                }
                None => {}
            }
            written += 1;
            queue.extend(advance(s, &mut streams, &mut heads)?);
        }
        if written != self.count {
            return Err(JoinError::Part(format!(
                "the parts held {written} of {} values when read again",
                self.count
            )));
        }
        w.end().map_err(JoinError::Write)
    }
}

/// The next value of part `s` into `heads`, and its place in the queue (None when the
/// part has no more).
fn advance<K: FileKind, R: BufRead>(
    s: usize,
    streams: &mut [Reread<'_, K, R>],
    heads: &mut [Option<Next<K>>],
) -> Result<Option<Reverse<(usize, usize)>>, JoinError> {
    Ok(streams[s]
        .next_value()
        .map_err(JoinError::Part)?
        .map(|(place, next)| {
            heads[s] = Some(next);
            Reverse((place, s))
        }))
}

/// Join checked parts of one run: the same tool, specification, layout and sections,
/// every shard of 1..N exactly once. Refusals name the file.
pub fn join<K: FileKind>(parts: Vec<Part<K>>) -> Result<Joined<K>, String> {
    let first = parts.first().ok_or("no parts given")?;
    let count = first.shard.map_or(1, |s| s.count);
    let mut slots: Vec<Option<usize>> = vec![None; count];
    for (n, p) in parts.iter().enumerate() {
        if p.layout != first.layout {
            return Err(format!("{}: mixes csv and json parts", p.name));
        }
        if p.provenance.tool != first.provenance.tool {
            return Err(format!(
                "{}: written by {}, {} by {}: valid parts of one run",
                p.name, p.provenance.tool, first.name, first.provenance.tool
            ));
        }
        if p.provenance.spec_hash != first.provenance.spec_hash {
            return Err(format!(
                "{}: a part of another {kind} ({} differs from {}'s): valid parts of one {kind}",
                p.name,
                differing_setting(&p.header, &first.header),
                first.name,
                kind = K::KIND
            ));
        }
        let mut sections = K::SECTIONS
            .iter()
            .zip(p.sections.iter().zip(&first.sections));
        if let Some((section, _)) = sections.find(|(_, (a, b))| a != b) {
            return Err(format!(
                "{}: its {section} differ from {}'s",
                p.name, first.name
            ));
        }
        let Some(s) = p.shard else {
            return Err(format!("{}: already a merged file", p.name));
        };
        if s.count != count {
            return Err(format!(
                "{}: shard {} of a {}-part run, {} is of a {count}-part run",
                p.name,
                shard_name(s),
                s.count,
                first.name
            ));
        }
        if let Some(other) = slots[s.index] {
            return Err(format!(
                "{}: shard {} is also in {}: valid each shard once",
                p.name,
                shard_name(s),
                parts[other].name
            ));
        }
        slots[s.index] = Some(n);
    }
    let missing: Vec<String> = slots
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(i, _)| format!("{}/{count}", i + 1))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "missing shard{} {}: valid every shard 1/{count} … {count}/{count} once",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        ));
    }
    let (layout, header, sections) = (first.layout, first.header.clone(), first.sections.clone());
    let mut parts: Vec<Option<Part<K>>> = parts.into_iter().map(Some).collect();
    let parts: Vec<Part<K>> = slots
        .into_iter()
        .flatten()
        .filter_map(|n| parts[n].take())
        .collect();
    let counts: Vec<usize> = parts.iter().map(|p| p.count).collect();
    K::complete(&header, &counts)?;
    Ok(Joined {
        layout,
        header,
        shards: count,
        sections,
        count: counts.iter().sum(),
        parts,
    })
}

#[cfg(test)]
mod tests {
    use super::super::read_part;
    use super::*;
    use crate::output::sweep_file::SweepFile;
    use std::io::Cursor;

    /// Two shards of one sweep as `sweep --shard I/2` writes them, and their merge, in
    /// both layouts.
    const CSV: [&str; 2] = [
        r#"# bouncemap 0.1.0 sweep
# spec {"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11}}
# spec-hash 4c52ad78abc9befb
# shard 1/2
# values 1
index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades
0,0.45,0.18415079246689955,0.49999999997679384,impact,,,unsettled,false,,
0,0.45,0.1841507924251285,0.5000000000572495,impact,,,unsettled,false,,
# end 1 values, 2 rows, checksum 3d3d6fcae26ea9e8
"#,
        r#"# bouncemap 0.1.0 sweep
# spec {"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11}}
# spec-hash 4c52ad78abc9befb
# shard 2/2
# values 1
index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades
1,0.5,0.1903619981268693,0.49999999993172994,impact,,,unsettled,false,,
1,0.5,0.19036199800398318,0.5000000001054774,impact,,,unsettled,false,,
# end 1 values, 2 rows, checksum df591222930c0ba3
"#,
    ];
    const CSV_MERGED: &str = r#"# bouncemap 0.1.0 sweep
# spec {"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11}}
# spec-hash 4c52ad78abc9befb
# shard merged 2/2
# values 2
index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades
0,0.45,0.18415079246689955,0.49999999997679384,impact,,,unsettled,false,,
0,0.45,0.1841507924251285,0.5000000000572495,impact,,,unsettled,false,,
1,0.5,0.1903619981268693,0.49999999993172994,impact,,,unsettled,false,,
1,0.5,0.19036199800398318,0.5000000001054774,impact,,,unsettled,false,,
# end 2 values, 4 rows, checksum 53828eceb51e1e6e
"#;
    const JSON: [&str; 2] = [
        r#"{"provenance":{"tool":"bouncemap 0.1.0","spec_hash":"4c52ad78abc9befb","shard":"1/2","values":1},"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11},"values":[{"index":0,"value":0.45,"status":"unsettled","period":null,"table_periods":null,"stopped_at":null,"sticking":false,"resolved":null,"growth_decades":null,"events":100,"points":[{"phase":0.18415079246689955,"v":0.49999999997679384,"kind":"impact"},{"phase":0.1841507924251285,"v":0.5000000000572495,"kind":"impact"}]}],"checksum":"0569d459a6167811"}
"#,
        r#"{"provenance":{"tool":"bouncemap 0.1.0","spec_hash":"4c52ad78abc9befb","shard":"2/2","values":1},"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11},"values":[{"index":1,"value":0.5,"status":"unsettled","period":null,"table_periods":null,"stopped_at":null,"sticking":false,"resolved":null,"growth_decades":null,"events":100,"points":[{"phase":0.1903619981268693,"v":0.49999999993172994,"kind":"impact"},{"phase":0.19036199800398318,"v":0.5000000001054774,"kind":"impact"}]}],"checksum":"118ae704799fe437"}
"#,
    ];
    const JSON_MERGED: &str = r#"{"provenance":{"tool":"bouncemap 0.1.0","spec_hash":"4c52ad78abc9befb","shard":"merged 2/2","values":2},"table":"fd:0.1","param":"alpha","lo":0.45,"hi":0.5,"steps":2,"alpha":null,"r":0.8,"d":0.1,"transient":100,"keep":2,"solver":"exact","start":"cold","initial":{"t0":0.0,"v0":null,"z0":0.0},"early_stop":{"max_period":64,"tolerance":1e-11},"values":[{"index":0,"value":0.45,"status":"unsettled","period":null,"table_periods":null,"stopped_at":null,"sticking":false,"resolved":null,"growth_decades":null,"events":100,"points":[{"phase":0.18415079246689955,"v":0.49999999997679384,"kind":"impact"},{"phase":0.1841507924251285,"v":0.5000000000572495,"kind":"impact"}]},{"index":1,"value":0.5,"status":"unsettled","period":null,"table_periods":null,"stopped_at":null,"sticking":false,"resolved":null,"growth_decades":null,"events":100,"points":[{"phase":0.1903619981268693,"v":0.49999999993172994,"kind":"impact"},{"phase":0.19036199800398318,"v":0.5000000001054774,"kind":"impact"}]}],"checksum":"17aecd2ef7736873"}
"#;

    /// The stretch `offset`, `len` of `text`.
    fn stretch(text: &str, offset: u64, len: u64) -> Cursor<Vec<u8>> {
        let end = offset.saturating_add(len).min(text.len() as u64);
        Cursor::new(text.as_bytes()[offset as usize..end as usize].to_vec())
    }

    fn read(name: &str, text: &str) -> Part<SweepFile> {
        let mut again = |offset, len| Ok(Box::new(stretch(text, offset, len)) as Box<dyn BufRead>);
        read_part::<SweepFile, _>(name, text.as_bytes(), &mut again).unwrap()
    }

    /// The texts, as this version of the tool writes them.
    fn ours(texts: &[&str]) -> Vec<String> {
        let tool = concat!("bouncemap ", env!("CARGO_PKG_VERSION"));
        texts
            .iter()
            .map(|t| t.replace("bouncemap 0.1.0", tool))
            .collect()
    }

    #[test]
    fn parts_read_again_merge_into_the_whole_and_a_part_changed_since_is_refused() {
        for (texts, merged) in [(CSV, CSV_MERGED), (JSON, JSON_MERGED)] {
            let (texts, merged) = (ours(&texts), ours(&[merged]).remove(0));
            // Given in the wrong order: the merge puts them in index order.
            let joined = join(vec![read("b", &texts[1]), read("a", &texts[0])]).unwrap();
            let text = |p: &Part<SweepFile>| &texts[usize::from(p.name == "b")];
            let out = joined
                .write(Vec::new(), |p| {
                    Ok(stretch(text(p), p.body.offset, p.body.len))
                })
                .unwrap();
            assert_eq!(String::from_utf8(out).unwrap(), merged);
            // One digit of part b changed after it was checked: its checksum says so at
            // its end, and the merge fails.
            let changed = texts[1].replacen("0.19036199800398318", "0.19036199800398319", 1);
            assert_ne!(changed, texts[1]);
            let written = joined.write(Vec::new(), |p| {
                let t = if p.name == "a" { &texts[0] } else { &changed };
                Ok(stretch(t, p.body.offset, p.body.len))
            });
            match written {
                Err(JoinError::Part(e)) => {
                    assert!(e.starts_with("b: changed since it was checked ("), "{e}")
                }
                other => panic!("{:?}", other.map(|_| ())),
            }
            // Its values cut short, or followed by more: refused too.
            for extra in [-5i64, 3] {
                let written = joined.write(Vec::new(), |p| {
                    let len = p.body.len as i64 + if p.name == "b" { extra } else { 0 };
                    Ok(stretch(
                        &format!("{}xyz", text(p)),
                        p.body.offset,
                        len as u64,
                    ))
                });
                assert!(matches!(written, Err(JoinError::Part(_))), "{extra}");
            }
        }
    }
}
