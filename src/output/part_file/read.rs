//! Reading a part file and checking it as it passes, a value at a time: its head, its
//! specification against its hash, every value where its place says, its end line or
//! checksum and its counts; kept is everything but the values ([`Part`]). The csv
//! layout is read here, the json layout in `json.rs`.

use super::json::read_json;
use super::stream::{CsvBody, FNV_START};
use super::tally::{Reading, Tally};
use super::*;

/// A part file, read and checked on its own: everything but its values, which were
/// checked one at a time as they passed and are read again from the file when they are
/// written ([`Part::reread`]).
#[derive(Clone, Debug)]
pub struct Part<K: FileKind> {
    pub name: String,
    pub layout: Layout,
    pub provenance: Provenance,
    pub header: K::Header,
    /// The shard it holds (None for a merged file).
    pub shard: Option<Shard>,
    /// The json texts of the sections before the values (`null` in a csv file).
    pub sections: Vec<String>,
    /// Values (pixels) it holds.
    pub count: usize,
    /// Where its values are in the file, as they were checked.
    pub body: Body,
}

/// Where a part's values are in its file and what they were when checked, so they can
/// be read again and a file changed since is noticed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Body {
    /// Where they start, in bytes: the csv rows (line 7 up to the end line), or the json
    /// array of values.
    pub offset: u64,
    /// Their length in bytes.
    pub len: u64,
    /// The checksum before them (of the sections before the values) and with them.
    pub(super) start: u64,
    pub(super) hash: u64,
    /// csv rows.
    pub(super) rows: usize,
    /// The longest csv line or json item, in bytes.
    pub(super) longest: usize,
}

/// Reads a stretch of the file being read a second time: `(offset, len)`.
pub type Again<'a> = dyn FnMut(u64, u64) -> io::Result<Box<dyn BufRead>> + 'a;

/// Whether the file `input` reads opens as a file of this very run would: kind `K`,
/// `layout`, this tool, the specification `header` (by its hash) and shard `shard`,
/// read from the provenance at its head only (the first lines of a csv file, the first
/// object of a json one), so a part of this run that was cut off or damaged later is
/// still recognised as its own, and anything else (another run's part, a file not
/// written by this tool) is not. At most the first MiB is read.
pub fn opens_as<K: FileKind>(
    input: impl BufRead,
    layout: Layout,
    header: &K::Header,
    shard: &str,
) -> bool {
    let hash = spec_hash(&spec_text(header));
    let mut head = input.take(1 << 20);
    match layout {
        Layout::Csv => {
            let mut lines = (&mut head).lines().map_while(Result::ok);
            let tool_line = format!("# {TOOL} {}", K::KIND);
            lines.next() == Some(tool_line)
                && lines.next().is_some_and(|l| l.starts_with("# spec "))
                && lines.next() == Some(format!("# spec-hash {hash}"))
                && lines.next() == Some(format!("# shard {shard}"))
        }
        Layout::Json => {
            let mut start = [0u8; 14];
            if head.read_exact(&mut start).is_err() || &start != b"{\"provenance\":" {
                return false;
            }
            let Some(Ok(prov)) = serde_json::Deserializer::from_reader(head)
                .into_iter::<serde_json::Value>()
                .next()
            else {
                return false;
            };
            prov["tool"] == TOOL && prov["spec_hash"] == hash.as_str() && prov["shard"] == shard
        }
    }
}

/// Read and check part `name` of kind `K` from `input` (the file from its start): its
/// provenance, its specification against its hash, every row (complete, well-formed,
/// inside its shard, where its place says), its end line or checksum, and its count,
/// holding one value at a time. `again` reads a stretch of the same file a second time
/// (the values of a json part, checked once the whole file has parsed). Refusals are
/// one line naming the file (and the line); what the reader of `input` itself found
/// (a file that is not UTF-8 further on) is for the caller to say first.
pub fn read_part<K: FileKind, R: BufRead>(
    name: &str,
    mut input: R,
    again: &mut Again,
) -> Result<Part<K>, String> {
    let bad = |msg: String| format!("{name}: {msg}");
    let cannot = |e: io::Error| bad(format!("cannot read: {e}"));
    let json = match opens_with_brace(&mut input, false).map_err(cannot)? {
        Some(json) => json,
        // Only white space in the first buffer: look further in a second reading.
        None => opens_with_brace(&mut again(0, u64::MAX).map_err(cannot)?, true)
            .map_err(cannot)?
            .unwrap_or(false),
    };
    let (part, check) = if json {
        read_json::<K, R>(name, input, again).map_err(&bad)?
    } else {
        read_csv::<K, R>(name, input)?
    };
    if spec_hash(&spec_text(&part.header)) != part.provenance.spec_hash {
        return Err(bad(format!(
            "its specification does not match its hash {} (edited?)",
            part.provenance.spec_hash
        )));
    }
    let expected = check.map_err(&bad)?;
    if part.count != part.provenance.count || part.count != expected {
        return Err(bad(format!(
            "holds {} {}; its provenance says {} and its shard has {expected}",
            part.count,
            K::UNIT,
            part.provenance.count
        )));
    }
    Ok(part)
}

/// Whether the text `input` reads starts with `{` after any white space: from what is
/// buffered, without reading on (None if that is all white space), or, with `consume`,
/// reading on as far as needed.
fn opens_with_brace(input: &mut impl BufRead, consume: bool) -> io::Result<Option<bool>> {
    let mut carry: Vec<u8> = Vec::new();
    loop {
        let buf = input.fill_buf()?;
        if buf.is_empty() {
            return Ok(Some(false));
        }
        carry.extend_from_slice(buf);
        let valid = match std::str::from_utf8(&carry) {
            Ok(t) => t.len(),
            Err(e) if e.error_len().is_none() => e.valid_up_to(),
            // Not UTF-8: the file is refused as such whichever way it is read.
            Err(_) => return Ok(Some(false)),
        };
        let text = std::str::from_utf8(&carry[..valid]).unwrap_or_default();
        if let Some(c) = text.trim_start().chars().next() {
            return Ok(Some(c == '{'));
        }
        if !consume {
            return Ok(None);
        }
        let n = buf.len();
        input.consume(n);
        carry.drain(..valid);
    }
}

/// The lines of a csv part's head, counted in bytes.
struct Lines<R: BufRead> {
    input: R,
    offset: u64,
}

impl<R: BufRead> Lines<R> {
    /// Line `n` without its line end, or None at the end of the file.
    fn next(&mut self, name: &str, n: usize) -> Result<Option<String>, String> {
        let mut line = Vec::new();
        let read = self
            .input
            .read_until(b'\n', &mut line)
            .map_err(|e| format!("{name}: line {n}: cannot read: {e}"))?;
        if read == 0 {
            return Ok(None);
        }
        self.offset += read as u64;
        let text =
            String::from_utf8(line).map_err(|_| format!("{name}: line {n}: not UTF-8 text"))?;
        Ok(Some(text.trim_end_matches(['\n', '\r']).to_string()))
    }
}

fn read_csv<K: FileKind, R: BufRead>(name: &str, input: R) -> Result<Reading<K>, String> {
    let mut lines = Lines { input, offset: 0 };
    let mut next_line = |what: &str, n: usize| -> Result<String, String> {
        lines
            .next(name, n)?
            .ok_or_else(|| format!("{name}: line {n}: missing ({what})"))
    };
    let field = |line: String, key: &str, n: usize| -> Result<String, String> {
        line.strip_prefix(&format!("# {key} "))
            .map(str::to_string)
            .ok_or_else(|| {
                format!(
                    "{name}: line {n}: expected '# {key} …', found '{}'",
                    clip(&line)
                )
            })
    };
    let (kind, unit) = (K::KIND, K::UNIT);
    let first = next_line("provenance", 1)?;
    let suffix = format!(" {kind}");
    if !(first.starts_with("# bouncemap ") && first.ends_with(&suffix)) {
        return Err(format!(
            "{name}: not a {kind} file with provenance (line 1 is '{}'; valid files start '# {TOOL} {kind}')",
            clip(&first)
        ));
    }
    let tool = first["# ".len()..first.len() - suffix.len()].to_string();
    let spec = field(next_line("spec", 2)?, "spec", 2)?;
    let hash = field(next_line("spec-hash", 3)?, "spec-hash", 3)?;
    let shard_text = field(next_line("shard", 4)?, "shard", 4)?;
    let count_text = field(next_line(unit, 5)?, unit, 5)?;
    let head = next_line("header row", 6)?;
    let header: K::Header = serde_json::from_str(&spec).map_err(|e| {
        format!(
            "{name}: line 2: not a {kind} specification ({})",
            one_line(&e.to_string())
        )
    })?;
    let count: usize = count_text
        .parse()
        .map_err(|_| format!("{name}: line 5: '{}' is not a count", clip(&count_text)))?;
    let shard = parse_shard(&shard_text).map_err(|e| format!("{name}: line 4: {e}"))?;
    let want = K::header_row(&header);
    if head != want {
        return Err(format!(
            "{name}: line 6: header '{}' is not '{want}'",
            clip(&head)
        ));
    }
    // The rows, one value at a time, then the end line.
    let offset = lines.offset;
    let names = csv::StringRecord::from(K::field_names(&header));
    let mut body = CsvBody::new(lines.input);
    let mut tally = Tally::<K>::new(&header, shard);
    let mut pending = Vec::new();
    let mut rows = 0usize;
    csv_rows(name, &mut body, &names, |row: K::Row| {
        rows += 1;
        K::add_row(&mut pending, row)?;
        // A value is complete when a row of the next one comes.
        while pending.len() > 1 {
            tally.value(&pending.remove(0));
        }
        Ok(())
    })?;
    for v in pending {
        tally.value(&v);
    }
    let sum = body.hash();
    let want_end = format!(
        "# end {}, checksum {sum:016x}",
        K::end_counts(tally.count, rows)
    );
    let end = body.end_line();
    if end != want_end {
        return Err(format!(
            "{name}: truncated or damaged: its last line is '{}', expected '{want_end}'",
            clip(&end)
        ));
    }
    let part = Part {
        name: name.to_string(),
        layout: Layout::Csv,
        provenance: Provenance {
            tool,
            spec_hash: hash,
            shard: shard_text,
            count,
        },
        header,
        shard,
        sections: vec!["null".to_string(); K::SECTIONS.len() - 1],
        count: tally.count,
        body: Body {
            offset,
            len: body.body_len(),
            start: FNV_START,
            hash: sum,
            rows,
            longest: body.longest(),
        },
    };
    Ok((part, tally.result()))
}

/// Each row read from `body` (line 7 on), exactly as wide as `names` and deserialized by
/// them, handed to `each` with its line; any failure is "{name}: line L: malformed row: …".
fn csv_rows<T: DeserializeOwned>(
    name: &str,
    body: impl Read,
    names: &csv::StringRecord,
    mut each: impl FnMut(T) -> Result<(), String>,
) -> Result<(), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(body);
    let mut rec = csv::StringRecord::new();
    for k in 0.. {
        // Rows are one line each (no field holds a newline): row k is line 7 + k.
        let line = 7 + k;
        let malformed = |what: String| format!("{name}: line {line}: malformed row: {what}");
        if !reader
            .read_record(&mut rec)
            .map_err(|e| malformed(one_line(&e.to_string())))?
        {
            break;
        }
        each(row_of(&rec, names).map_err(malformed)?).map_err(malformed)?;
    }
    Ok(())
}

/// A csv row exactly as wide as `names`, deserialized by them.
pub(super) fn row_of<T: DeserializeOwned>(
    rec: &csv::StringRecord,
    names: &csv::StringRecord,
) -> Result<T, String> {
    if rec.len() != names.len() {
        return Err(format!("{} fields, expected {}", rec.len(), names.len()));
    }
    rec.deserialize(Some(names)).map_err(|e| match e.kind() {
        csv::ErrorKind::Deserialize { err, .. } => one_line(&err.kind().to_string()),
        _ => one_line(&e.to_string()),
    })
}
