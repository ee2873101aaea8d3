//! The part file: the one format of what `sweep` and `plane` write (csv or json) and
//! `merge` reads back, checks and joins. A [`FileKind`] says what is particular to one
//! kind of file (its settings, its rows, where a row belongs); everything else is here,
//! once: the provenance, the hashes, the shards, the csv and json layouts, the
//! streaming writer ([`PartWriter`]) and the reader that checks a part ([`read_part`])
//! and reads its values again ([`Part::reread`]), both a value at a time over the
//! byte-level pieces of `stream.rs`; the join of the parts of one run is [`join`].
//!
//! Files: this one the format (layouts, provenance, hashes, shards, [`FileKind`]) and
//! the writer; `read.rs` reading and checking a part (its csv layout here), `json.rs`
//! its json layout, `tally.rs` what both keep of the values as they pass, `reread.rs`
//! its values read again, `stream.rs` the byte-level
//! pieces under them, `join.rs` the join of the parts of one run.
//!
//! Every file states where it comes from (its provenance): the tool and version, the
//! full specification (the kind's settings) and a hash of it, the shard `I/N` it holds
//! (`merged N/N` after a merge) and how many values (pixels) it holds. A csv file states
//! it in `#` lines before the header row and closes with an end line counting what it
//! holds and giving a checksum of the rows, so a truncated or damaged file is
//! recognised:
//!
//! ```text
//! # bouncemap 0.1.0 sweep
//! # spec {"table":"fd:0.1","param":"alpha",...}
//! # spec-hash 3f0c9a1d2b7e4c55
//! # shard 2/4
//! # values 250
//! index,alpha,phase,v,kind,period,table_periods,status,sticking
//! ...
//! # end 250 values, 25000 rows, checksum 9a4f0c2e71b3d855
//! ```
//!
//! A json file has the same as a `provenance` object, then the settings, then the
//! kind's sections ([`FileKind::SECTIONS`]: the last is the array of values or pixels)
//! and the checksum of the sections' bytes. The checksum is the 64-bit FNV-1a of the
//! rows' (the sections') bytes: it catches damage, not forgery. Every refusal is one
//! line naming the file (and the line).
//!
//! A part is never held whole: it is read as a stream and each value checked as it
//! passes, keeping only the provenance, the settings and where its values lie (a
//! [`Part`]). A json part's values are marked where they lie while a json parser checks
//! the whole file, then read again from there, item by item, for their checksum and
//! their checks; `merge` reads them a third time to write them.

mod join;
mod json;
mod read;
mod reread;
mod stream;
mod tally;

pub use join::{join, JoinError, Joined};
pub use read::{opens_as, read_part, Again, Body, Part};
pub use reread::Reread;

use bouncemap_engine::jobs::grid::Shard;
use serde::de::{self, DeserializeOwned, DeserializeSeed, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::value::RawValue;
use std::fmt::{self, Debug};
use std::io::{self, BufRead, Read, Write};
use std::marker::PhantomData;
use stream::{fnv1a, FNV_START};

/// The tool of every provenance: `bouncemap VERSION`.
pub const TOOL: &str = concat!("bouncemap ", env!("CARGO_PKG_VERSION"));

/// The two layouts of a part file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    Csv,
    Json,
}

impl Layout {
    /// `csv` or `json`.
    pub fn name(self) -> &'static str {
        match self {
            Layout::Csv => "csv",
            Layout::Json => "json",
        }
    }
}

/// One kind of part file: what its settings, rows and values are, how a row is checked
/// and where it belongs. The rest of the format is the same for every kind.
pub trait FileKind: Sized {
    /// The kind's name: line 1 of a csv file (`# bouncemap VERSION sweep`), and the
    /// word in messages (`a part of another sweep`).
    const KIND: &'static str;
    /// What the file counts (`values`, `pixels`): line 5 of a csv file, the count in
    /// the json provenance, the end line and messages.
    const UNIT: &'static str;
    /// The keys of the json provenance, in order: `file` (the kind's name, if the file
    /// states it), `tool`, `spec_hash`, `shard` and [`Self::UNIT`] (the count).
    const PROVENANCE: &'static [&'static str];
    /// The json sections after the settings, in order, all covered by the checksum; the
    /// last is the array of values, any before it are json a csv file leaves out
    /// (`null` there).
    const SECTIONS: &'static [&'static str];

    /// The settings: the full specification, stated in the file and hashed.
    type Header: Serialize + DeserializeOwned + Clone + Debug;
    /// One csv row.
    type Row: Serialize + DeserializeOwned;
    /// One element of the json array of values.
    type Item: Serialize + DeserializeOwned;
    /// One value of a part as read (made of one json item, or of one or more csv rows).
    type Value: Clone + Debug;

    /// Line 6 of a csv file, the header row.
    fn header_row(header: &Self::Header) -> String;
    /// The names each csv row is read with, one per column.
    fn field_names(header: &Self::Header) -> Vec<&'static str>;
    /// Add the csv row `row` to the values read so far (an error is the row's).
    fn add_row(values: &mut Vec<Self::Value>, row: Self::Row) -> Result<(), String>;
    /// The value of one json item.
    fn from_item(item: Self::Item) -> Self::Value;
    /// Write one value as read back (merge).
    fn write_value<W: Write>(w: &mut PartWriter<W, Self>, value: &Self::Value) -> io::Result<()>;
    /// The counts of the csv end line: `250 values, 25000 rows`.
    fn end_counts(values: usize, rows: usize) -> String;
    /// Checks the values of one part, in its order.
    type Checker;
    /// Start checking the values of a part of the run `header` holding `shard` (None: a
    /// merged file); a refusal here is the part's, before any value's.
    fn checker(header: &Self::Header, shard: Option<Shard>) -> Result<Self::Checker, String>;
    /// Check the part's next value: well-formed, inside its shard, where its place says.
    fn check(checker: &mut Self::Checker, value: &Self::Value) -> Result<(), String>;
    /// How many values the part's shard has.
    fn expected(checker: &Self::Checker) -> usize;
    /// The index a value states (a sweep's value does; a plane's pixel does not: its
    /// place in its shard says which it is).
    fn stated_index(value: &Self::Value) -> Option<usize>;
    /// The index a csv row states of its value: the rows of a value are consecutive and
    /// state the same (None: every row is a value of its own).
    fn row_index(row: &Self::Row) -> Option<usize>;
    /// The place in the whole run (its index) of value `k` (from 0) of a checked part
    /// holding `shard`, which states the index `stated`: the order a merge writes
    /// values in.
    fn place(shard: Option<Shard>, k: usize, stated: Option<usize>) -> usize;
    /// Refuse checked parts that do not make the whole run: `counts[s]` values in shard
    /// s + 1 of N.
    fn complete(header: &Self::Header, counts: &[usize]) -> Result<(), String>;
}

/// Where a file comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Provenance {
    /// `bouncemap VERSION`.
    pub tool: String,
    /// 64-bit FNV-1a of the canonical specification ([`spec_text`]), in hex.
    pub spec_hash: String,
    /// `I/N`, or `merged N/N` for a merge of all N shards.
    pub shard: String,
    /// Values (pixels) the file holds.
    pub count: usize,
}

/// The canonical text of a specification: its compact json.
pub fn spec_text<H: Serialize>(header: &H) -> String {
    serde_json::to_string(header).expect("a specification serializes")
}

/// 64-bit FNV-1a of `text`, as 16 hex digits (an identity check, not a security one).
pub fn spec_hash(text: &str) -> String {
    format!("{:016x}", fnv1a(FNV_START, text.as_bytes()))
}

/// A writer that hashes what passes through it.
struct Hashing<W: Write> {
    inner: W,
    hash: u64,
}

impl<W: Write> Hashing<W> {
    fn new(inner: W) -> Hashing<W> {
        Hashing {
            inner,
            hash: FNV_START,
        }
    }
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash = fnv1a(self.hash, &buf[..n]);
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// How a shard is named in a provenance.
pub fn shard_name(s: Shard) -> String {
    format!("{}/{}", s.index + 1, s.count)
}

/// The shard a provenance names (None for a merged file).
pub fn parse_shard(s: &str) -> Result<Option<Shard>, String> {
    if s.starts_with("merged ") {
        return Ok(None);
    }
    let parsed = s.split_once('/').and_then(|(i, n)| {
        let (i, n): (usize, usize) = (i.parse().ok()?, n.parse().ok()?);
        (i >= 1 && i <= n).then(|| Shard {
            index: i - 1,
            count: n,
        })
    });
    parsed
        .map(Some)
        .ok_or_else(|| format!("shard '{s}' is not I/N with 1 ≤ I ≤ N"))
}

/// A message from a parser as one line (a name read from the file may hold a newline).
fn one_line(s: &str) -> String {
    s.replace('\n', " ")
}

/// At most 60 characters of `s`, control characters escaped.
pub fn clip(s: &str) -> String {
    let esc = super::text::escape(s);
    if esc.chars().count() > 60 {
        esc.chars().take(59).collect::<String>() + "…"
    } else {
        esc
    }
}

/// The first setting in which two specifications differ, named.
pub fn differing_setting<H: Serialize>(a: &H, b: &H) -> String {
    let (va, vb) = (
        serde_json::to_value(a).unwrap_or_default(),
        serde_json::to_value(b).unwrap_or_default(),
    );
    if let (Some(ma), Some(mb)) = (va.as_object(), vb.as_object()) {
        for (k, x) in ma {
            if mb.get(k) != Some(x) {
                return format!("its {k} {x}");
            }
        }
    }
    "its specification".into()
}

// ------------------------------------------------------------------ writing

/// Writes one part file of kind `K`, value by value in index order (memory is bounded
/// by what the caller holds, not by the file).
pub struct PartWriter<W: Write, K: FileKind> {
    inner: Inner<W>,
    values: usize,
    rows: usize,
    kind: PhantomData<K>,
}

enum Inner<W: Write> {
    Csv(Box<csv::Writer<Hashing<W>>>),
    Json { out: Hashing<W>, first: bool },
}

impl<W: Write, K: FileKind> PartWriter<W, K> {
    /// Write the provenance and the settings of a file of shard `shard` that will hold
    /// `count` values; `sections` are the json texts of the sections before the values
    /// (ignored in csv).
    pub fn begin(
        mut out: W,
        layout: Layout,
        header: &K::Header,
        shard: &str,
        count: usize,
        sections: &[&str],
    ) -> io::Result<PartWriter<W, K>> {
        let spec = spec_text(header);
        let prov = Provenance {
            tool: TOOL.to_string(),
            spec_hash: spec_hash(&spec),
            shard: shard.to_string(),
            count,
        };
        let inner = match layout {
            Layout::Csv => {
                writeln!(out, "# {TOOL} {}", K::KIND)?;
                writeln!(out, "# spec {spec}")?;
                writeln!(out, "# spec-hash {}", prov.spec_hash)?;
                writeln!(out, "# shard {}", prov.shard)?;
                writeln!(out, "# {} {}", K::UNIT, prov.count)?;
                writeln!(out, "{}", K::header_row(header))?;
                // The rows from here on are hashed.
                Inner::Csv(Box::new(
                    csv::WriterBuilder::new()
                        .has_headers(false)
                        .from_writer(Hashing::new(out)),
                ))
            }
            Layout::Json => {
                write!(
                    out,
                    "{{\"provenance\":{},{}",
                    serde_json::to_string(&Stated::<K>(&prov, PhantomData))?,
                    &spec[1..spec.len() - 1]
                )?;
                // The sections from here on are hashed, their keys not.
                let mut out = Hashing::new(out);
                let (values, before) = K::SECTIONS
                    .split_last()
                    .expect("a kind has the section of its values");
                for (name, text) in before.iter().zip(sections) {
                    write!(out.inner, ",\"{name}\":")?;
                    out.write_all(text.as_bytes())?;
                }
                write!(out.inner, ",\"{values}\":")?;
                out.write_all(b"[")?;
                Inner::Json { out, first: true }
            }
        };
        Ok(PartWriter {
            inner,
            values: 0,
            rows: 0,
            kind: PhantomData,
        })
    }

    /// The layout being written.
    pub fn layout(&self) -> Layout {
        match self.inner {
            Inner::Csv(_) => Layout::Csv,
            Inner::Json { .. } => Layout::Json,
        }
    }

    /// One value's csv rows.
    pub fn csv(&mut self, rows: &[K::Row]) -> io::Result<()> {
        let Inner::Csv(csv) = &mut self.inner else {
            return Err(io::Error::other(format!(
                "csv rows into a json {} file",
                K::KIND
            )));
        };
        for row in rows {
            csv.serialize(row)?;
        }
        self.rows += rows.len();
        self.values += 1;
        Ok(())
    }

    /// One csv row: the first of a value (`first`), or the next of the value before.
    pub fn csv_row(&mut self, row: &K::Row, first: bool) -> io::Result<()> {
        let Inner::Csv(csv) = &mut self.inner else {
            return Err(io::Error::other(format!(
                "csv rows into a json {} file",
                K::KIND
            )));
        };
        csv.serialize(row)?;
        self.rows += 1;
        self.values += usize::from(first);
        Ok(())
    }

    /// One value's json item.
    pub fn json(&mut self, item: &K::Item) -> io::Result<()> {
        self.json_value(item)
    }

    /// One value's json item, or anything that is written as one (a view of a result
    /// that makes its points as they are written).
    pub fn json_value<T: Serialize + ?Sized>(&mut self, item: &T) -> io::Result<()> {
        let Inner::Json { out, first } = &mut self.inner else {
            return Err(io::Error::other(format!(
                "a json value into a csv {} file",
                K::KIND
            )));
        };
        if !*first {
            out.write_all(b",")?;
        }
        *first = false;
        serde_json::to_writer(&mut *out, item)?;
        self.values += 1;
        Ok(())
    }

    /// One value as read back from a part.
    pub fn value(&mut self, value: &K::Value) -> io::Result<()> {
        K::write_value(self, value)
    }

    /// Close the file (csv: the end line; json: the checksum) and hand back the writer.
    pub fn end(self) -> io::Result<W> {
        match self.inner {
            Inner::Csv(csv) => {
                let Hashing { mut inner, hash } =
                    (*csv).into_inner().map_err(|e| e.into_error())?;
                writeln!(
                    inner,
                    "# end {}, checksum {hash:016x}",
                    K::end_counts(self.values, self.rows)
                )?;
                Ok(inner)
            }
            Inner::Json { mut out, .. } => {
                out.write_all(b"]")?;
                let Hashing { mut inner, hash } = out;
                writeln!(inner, ",\"checksum\":\"{hash:016x}\"}}")?;
                Ok(inner)
            }
        }
    }
}

/// A provenance as a file of kind `K` states it in json.
struct Stated<'a, K>(&'a Provenance, PhantomData<K>);

impl<K: FileKind> Serialize for Stated<'_, K> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.0;
        let mut st = s.serialize_struct("Provenance", K::PROVENANCE.len())?;
        for &key in K::PROVENANCE {
            match key {
                "file" => st.serialize_field(key, K::KIND)?,
                "tool" => st.serialize_field(key, &p.tool)?,
                "spec_hash" => st.serialize_field(key, &p.spec_hash)?,
                "shard" => st.serialize_field(key, &p.shard)?,
                _ => st.serialize_field(key, &p.count)?,
            }
        }
        st.end()
    }
}
