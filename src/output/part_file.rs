//! The part file: the one format of what `sweep` and `plane` write (csv or json) and
//! `merge` reads back, checks and joins. A [`FileKind`] says what is particular to one
//! kind of file (its settings, its rows, where a row belongs); everything else is here,
//! once: the provenance, the hashes, the shards, the csv and json layouts, the
//! streaming writer ([`PartWriter`]) and the reader that checks a part ([`read_part`])
//! and reads its values again ([`Part::values`]), both a value at a time over the
//! byte-level pieces of [`super::part_stream`]; the join of the parts of one run is
//! [`super::part_join`].
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

use super::part_stream::{fnv1a, CsvBody, Hashed, JsonItems, Place, Tap, TapMarks, FNV_START};
use bouncemap_engine::grid::Shard;
use serde::de::{self, DeserializeOwned, DeserializeSeed, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::value::RawValue;
use std::fmt::{self, Debug};
use std::io::{self, BufRead, Read, Write};
use std::marker::PhantomData;

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
fn parse_shard(s: &str) -> Result<Option<Shard>, String> {
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

// ------------------------------------------------------------------ reading

/// A part file, read and checked on its own: everything but its values, which were
/// checked one at a time as they passed and are read again from the file when they are
/// written ([`Part::values`]).
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
    start: u64,
    hash: u64,
    /// csv rows.
    rows: usize,
    /// The longest csv line or json item, in bytes.
    longest: usize,
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

/// A part as read, and the check of its values: how many its shard has, or the first
/// failure.
type Reading<K> = (Part<K>, Result<usize, String>);

/// The values of a part as they are read: counted, and checked in order, the first
/// failure kept (a later malformed row or a bad end line is reported before it).
struct Tally<K: FileKind> {
    checker: Result<K::Checker, String>,
    failure: Option<String>,
    count: usize,
}

impl<K: FileKind> Tally<K> {
    fn new(header: &K::Header, shard: Option<Shard>) -> Tally<K> {
        Tally {
            checker: K::checker(header, shard),
            failure: None,
            count: 0,
        }
    }

    fn value(&mut self, v: &K::Value) {
        self.count += 1;
        if let (Ok(c), None) = (&mut self.checker, &self.failure) {
            self.failure = K::check(c, v).err();
        }
    }

    /// How many values the shard has, or the first failure.
    fn result(self) -> Result<usize, String> {
        let c = self.checker?;
        match self.failure {
            Some(f) => Err(f),
            None => Ok(K::expected(&c)),
        }
    }
}

/// Read a json part. A json parser checks the whole file but for a large array of
/// values, which is only read past ([`Tap`]) and then read again and checked item by
/// item; a file that is not complete json where that shortcut was taken (after the
/// array, or inside it) is parsed again byte by byte, so the refusal is the one a
/// parser of the whole file gives, word for word.
fn read_json<K: FileKind, R: BufRead>(
    name: &str,
    input: R,
    again: &mut Again,
) -> Result<Reading<K>, String> {
    if let Some(reading) = parse_json::<K, R>(name, input, again, true)? {
        return Ok(reading);
    }
    let whole = again(0, u64::MAX).map_err(|e| format!("cannot read: {e}"))?;
    parse_json::<K, _>(name, whole, again, false)?.ok_or_else(|| {
        format!(
            "its {} changed while being read (their json differs from the first reading)",
            K::UNIT
        )
    })
}

/// [`read_json`], the array of values read past by the tap (`skip`) or by the parser;
/// None when the file is not complete json and only a parser reading the whole file
/// byte by byte can say where.
fn parse_json<K: FileKind, R: BufRead>(
    name: &str,
    input: R,
    again: &mut Again,
    skip: bool,
) -> Result<Option<Reading<K>>, String> {
    let tap = Tap::new(input, skip);
    let marks = tap.marks();
    let mut de = serde_json::Deserializer::from_reader(tap);
    let parsed = de
        .deserialize_map(JsonVisitor::<K> {
            marks: Some(&marks),
            skip,
            kind: PhantomData,
        })
        .and_then(|p| de.end().map(|()| p));
    let p = match parsed {
        Ok(p) => p,
        Err(e) if !skip => return Err(incomplete::<K>(&as_whole(&e, &marks))),
        Err(_) => return refusal::<K>(&marks, again).map(|()| None),
    };
    let shard = parse_shard(&p.provenance.shard);
    let mut tally = Tally::<K>::new(&p.header, shard.clone().unwrap_or(None));
    let start = p
        .sections
        .iter()
        .fold(FNV_START, |h, s| fnv1a(h, s.get().as_bytes()));
    // The values, read again: their checksum, each value parsed and checked in turn.
    let (offset, end) = p.values;
    let changed = |e: io::Error| {
        format!(
            "its {} changed while being read ({})",
            K::UNIT,
            one_line(&e.to_string())
        )
    };
    let mut region = again(offset, end - offset).map_err(changed)?;
    let (hash, malformed, longest) = if region.fill_buf().map_err(changed)?.first() == Some(&b'[') {
        let mut items = JsonItems::new(region, start, usize::MAX);
        let mut malformed = None;
        while let Some((text, at)) = items.next_item().map_err(changed)? {
            if malformed.is_none() {
                match serde_json::from_slice::<K::Item>(text) {
                    Ok(item) => {
                        tally.value(&K::from_item(item));
                        continue;
                    }
                    Err(e) => malformed = Some(placed(&e, at)),
                }
            }
            // An item that is not json at all: what a parser of the whole file says.
            if let Err(e) = serde_json::from_slice::<de::IgnoredAny>(text) {
                return item_refusal::<K>(&e, at, &marks).map(|()| None);
            }
        }
        (items.hash(), malformed, items.longest())
    } else {
        let (hash, why) = not_an_array::<K>(region, end - offset, start).map_err(changed)?;
        (hash, Some(why), 0)
    };
    if format!("{hash:016x}") != p.checksum {
        return Err(format!(
            "its {} do not match their checksum {} (damaged?)",
            K::UNIT,
            clip(&p.checksum)
        ));
    }
    if let Some(why) = malformed {
        return Err(format!("malformed {} ({why})", K::UNIT));
    }
    let shard = shard?;
    if p.file.as_deref().is_some_and(|f| f != K::KIND) {
        return Err(format!("not a {} file", K::KIND));
    }
    let count = tally.count;
    let part = Part {
        name: name.to_string(),
        layout: Layout::Json,
        provenance: p.provenance,
        header: p.header,
        shard,
        sections: p.sections.iter().map(|s| s.get().to_string()).collect(),
        count,
        body: Body {
            offset,
            len: end - offset,
            start,
            hash,
            rows: count,
            longest,
        },
    };
    Ok(Some((part, tally.result())))
}

/// A json parser's message about one item, placed in the text of the whole array as a
/// parser of the array would place it (line 1 column 1 is the `[`).
fn placed(e: &serde_json::Error, at: Place) -> String {
    let msg = e.to_string();
    if e.line() == 0 {
        return one_line(&msg);
    }
    let (line, column) = if e.line() == 1 {
        (at.line, at.column + e.column())
    } else {
        (at.line + e.line() - 1, e.column())
    };
    one_line(&at_position(e, line, column))
}

/// A json parser's message as a parser holding the whole text gives it: a control
/// character in a string is placed before it, not after it (a parser reading a stream
/// has read it by then).
fn as_whole(e: &serde_json::Error, marks: &TapMarks) -> String {
    if !e.to_string().starts_with("control character") || e.line() == 0 {
        return e.to_string();
    }
    if e.column() > 0 {
        return at_position(e, e.line(), e.column() - 1);
    }
    // The character was a newline: the end of the line before.
    match marks.line_length(e.line() - 1) {
        Some(column) => at_position(e, e.line() - 1, column),
        None => e.to_string(),
    }
}

/// The refusal of a json part that is not complete json.
fn incomplete<K: FileKind>(why: &str) -> String {
    format!("not a complete {} json file ({})", K::KIND, one_line(why))
}

/// Why a json part whose array of values was read past by the tap is not complete json,
/// in the words of a parser of the whole file: the text the parser was shown (the file,
/// the array as `[]`), parsed again whole, its position moved back over the array, unless
/// an item of the array comes first that is not json. `Ok` when only a parser reading
/// the whole file byte by byte can say (the array itself is not complete).
fn refusal<K: FileKind>(marks: &TapMarks, again: &mut Again) -> Result<(), String> {
    let Some(shown) = marks.shown() else {
        return Ok(());
    };
    let cut = marks.cut();
    if marks.skipped() && cut.is_none() {
        return Ok(());
    }
    let mut de = serde_json::Deserializer::from_slice(&shown);
    let again_parsed = de
        .deserialize_map(JsonVisitor::<K> {
            marks: None,
            skip: false,
            kind: PhantomData,
        })
        .and_then(|_| de.end());
    let Err(e) = again_parsed else {
        return Ok(());
    };
    let (Some(cut), Some((from, to))) = (cut, marks.region()) else {
        return Err(incomplete::<K>(&e.to_string()));
    };
    let (line, column) = place_in(&shown, cut.at);
    let after = e.line() > line || (e.line() == line && e.column() >= column + 2);
    if after {
        // The array comes first: any item in it that is not json is what is said.
        let region = again(from, to - from).map_err(|e| format!("cannot read: {e}"))?;
        let mut items = JsonItems::new(region, FNV_START, usize::MAX);
        loop {
            match items.next_item() {
                Ok(Some((text, at))) => {
                    if let Err(e) = serde_json::from_slice::<de::IgnoredAny>(text) {
                        return item_refusal::<K>(&e, at, marks);
                    }
                }
                Ok(None) => break,
                Err(_) => return Ok(()),
            }
        }
    }
    let moved = if !after || e.line() == 0 {
        e.to_string()
    } else {
        let column = if e.line() != line {
            e.column()
        } else if cut.newlines == 0 {
            e.column() - 2 + cut.len as usize
        } else {
            e.column() - 2 - column + cut.tail
        };
        at_position(&e, e.line() + cut.newlines, column)
    };
    Err(incomplete::<K>(&moved))
}

/// Why a json part with an item of values that is not json is refused, in the words of
/// a parser of the whole file (the item parsed alone, its position moved to the
/// file's); `Ok` when the item alone may not fail as the whole would (it ends early, or
/// is followed by more): a parser reading the whole file byte by byte says then.
fn item_refusal<K: FileKind>(
    e: &serde_json::Error,
    at: Place,
    marks: &TapMarks,
) -> Result<(), String> {
    let (Some(shown), Some(cut)) = (marks.shown(), marks.cut()) else {
        return Ok(());
    };
    if e.is_eof() || e.to_string().starts_with("trailing characters") {
        return Ok(());
    }
    let (line, column) = place_in(&shown, cut.at);
    let at = Place {
        line: line + at.line - 1,
        column: if at.line == 1 {
            column + at.column
        } else {
            at.column
        },
    };
    Err(incomplete::<K>(&placed(e, at)))
}

/// The line (from 1) and the bytes before it on its line of offset `at` of `text`.
fn place_in(text: &[u8], at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |k| k + 1);
    (
        1 + before[..start].iter().filter(|&&b| b == b'\n').count(),
        before.len() - start,
    )
}

/// A json parser's message with its position replaced.
fn at_position(e: &serde_json::Error, line: usize, column: usize) -> String {
    let msg = e.to_string();
    let bare = msg
        .strip_suffix(&format!(" at line {} column {}", e.line(), e.column()))
        .unwrap_or(&msg);
    format!("{bare} at line {line} column {column}")
}

/// The checksum of values that are not an array, and why they are malformed, as the
/// parser of a whole array says it (read whole only up to a MiB: more than that which
/// is not an array is malformed without a closer look).
fn not_an_array<K: FileKind>(
    region: impl BufRead,
    len: u64,
    start: u64,
) -> io::Result<(u64, String)> {
    const LOOK: u64 = 1 << 20;
    if len > LOOK {
        return Ok((start, "not an array".into()));
    }
    let mut bytes = Vec::new();
    region.take(LOOK).read_to_end(&mut bytes)?;
    // The stretch read may end one byte after a number: the value is what a parser
    // takes of it.
    let mut de = serde_json::Deserializer::from_slice(&bytes);
    let raw = <&RawValue>::deserialize(&mut de).map_err(io::Error::other)?;
    let why = match serde_json::from_str::<Vec<K::Item>>(raw.get()) {
        Ok(_) => "not an array".to_string(),
        Err(e) => one_line(&e.to_string()),
    };
    Ok((fnv1a(start, raw.get().as_bytes()), why))
}

/// The json layout as read: the provenance, the settings (every other key), the
/// sections before the values as their raw text, where the values are (from, to) and
/// the checksum.
struct JsonPart<K: FileKind> {
    provenance: Provenance,
    /// The kind the file names (`file`), if it names one.
    file: Option<String>,
    header: K::Header,
    sections: Vec<Box<RawValue>>,
    values: (u64, u64),
    checksum: String,
}

/// Reads the json layout, the values only marked where they are (an array of them
/// read past by the tap, with `skip`).
struct JsonVisitor<'m, K> {
    /// None: the values are only checked as json (a second parse, for its words).
    marks: Option<&'m TapMarks>,
    skip: bool,
    kind: PhantomData<K>,
}

impl<'de, K: FileKind> Visitor<'de> for JsonVisitor<'_, K> {
    type Value = JsonPart<K>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a {} file", K::KIND)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut provenance = None;
        let mut checksum: Option<String> = None;
        let last = K::SECTIONS.len() - 1;
        let mut sections: Vec<Option<Box<RawValue>>> = vec![None; last];
        let mut values: Option<(u64, u64)> = None;
        let mut settings = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if key == "provenance" {
                once(&provenance, "provenance")?;
                provenance = Some(map.next_value_seed(ProvenanceSeed::<K>(PhantomData))?);
            } else if key == "checksum" {
                once(&checksum, "checksum")?;
                checksum = Some(map.next_value()?);
            } else if let Some(k) = K::SECTIONS.iter().position(|s| *s == key) {
                if k == last {
                    once(&values, K::SECTIONS[k])?;
                    values = Some(match self.marks {
                        Some(marks) => map.next_value_seed(Marked(marks, self.skip))?,
                        None => map.next_value::<de::IgnoredAny>().map(|_| (0, 0))?,
                    });
                } else {
                    once(&sections[k], K::SECTIONS[k])?;
                    sections[k] = Some(map.next_value()?);
                }
            } else {
                let value: serde_json::Value = map.next_value()?;
                settings.insert(key, value);
            }
        }
        let (provenance, file) =
            provenance.ok_or_else(|| de::Error::missing_field("provenance"))?;
        let header = K::Header::deserialize(serde_json::Value::Object(settings))
            .map_err(de::Error::custom)?;
        let sections = sections
            .into_iter()
            .zip(K::SECTIONS)
            .map(|(s, name)| s.ok_or_else(|| de::Error::missing_field(name)))
            .collect::<Result<_, _>>()?;
        let values = values.ok_or_else(|| de::Error::missing_field(K::SECTIONS[last]))?;
        Ok(JsonPart {
            provenance,
            file,
            header,
            sections,
            values,
            checksum: checksum.ok_or_else(|| de::Error::missing_field("checksum"))?,
        })
    }
}

/// Any json value, checked as json and skipped (an array, with `skip`, read past by the
/// tap); where it lies is marked by the tap.
struct Marked<'m>(&'m TapMarks, bool);

impl<'de> DeserializeSeed<'de> for Marked<'_> {
    type Value = (u64, u64);

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        self.0.arm(self.1);
        de::IgnoredAny::deserialize(d)?;
        self.0
            .disarm()
            .ok_or_else(|| de::Error::custom("a value without a first byte"))
    }
}

/// A field seen a second time is refused.
fn once<T, E: de::Error>(slot: &Option<T>, name: &'static str) -> Result<(), E> {
    match slot {
        Some(_) => Err(E::duplicate_field(name)),
        None => Ok(()),
    }
}

/// Reads a json provenance of kind `K` (exactly its keys), with the kind it names.
struct ProvenanceSeed<K>(PhantomData<K>);

impl<'de, K: FileKind> DeserializeSeed<'de> for ProvenanceSeed<K> {
    type Value = (Provenance, Option<String>);

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_struct("Provenance", K::PROVENANCE, self)
    }
}

impl<'de, K: FileKind> Visitor<'de> for ProvenanceSeed<K> {
    type Value = (Provenance, Option<String>);

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("struct Provenance")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let (mut file, mut tool, mut spec_hash, mut shard) = (None, None, None, None);
        let mut count: Option<usize> = None;
        while let Some(key) = map.next_key::<String>()? {
            let Some(&known) = K::PROVENANCE.iter().find(|k| **k == key) else {
                return Err(de::Error::unknown_field(&key, K::PROVENANCE));
            };
            let slot: &mut Option<String> = match known {
                "file" => &mut file,
                "tool" => &mut tool,
                "spec_hash" => &mut spec_hash,
                "shard" => &mut shard,
                _ => {
                    once(&count, known)?;
                    count = Some(map.next_value()?);
                    continue;
                }
            };
            once(slot, known)?;
            *slot = Some(map.next_value()?);
        }
        // Missing keys are named in the order the file states them.
        if K::PROVENANCE.contains(&"file") && file.is_none() {
            return Err(de::Error::missing_field("file"));
        }
        let missing = de::Error::missing_field;
        let provenance = Provenance {
            tool: tool.ok_or_else(|| missing("tool"))?,
            spec_hash: spec_hash.ok_or_else(|| missing("spec_hash"))?,
            shard: shard.ok_or_else(|| missing("shard"))?,
            count: count.ok_or_else(|| missing(K::UNIT))?,
        };
        Ok((provenance, file))
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
fn row_of<T: DeserializeOwned>(
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

// ------------------------------------------------------------------ reading again

impl<K: FileKind> Part<K> {
    /// Its values read again from `body` (its file from [`Body::offset`], [`Body::len`]
    /// bytes), in order, one at a time ([`Reread`]). Anything that differs from what was
    /// checked (the file changed since) is an error naming the file, and so is a
    /// checksum or a count at the end that differs.
    pub fn reread<R: BufRead>(&self, body: R) -> Reread<'_, K, R> {
        let b = &self.body;
        let source = match self.layout {
            Layout::Csv => Source::Csv(CsvSource {
                rows: csv::ReaderBuilder::new()
                    .has_headers(false)
                    .flexible(true)
                    .from_reader(Hashed::new(body, b.start, b.longest)),
                names: csv::StringRecord::from(K::field_names(&self.header)),
                record: csv::StringRecord::new(),
                ahead: None,
                index: None,
                read: 0,
            }),
            Layout::Json => Source::Json(JsonItems::new(body, b.start, b.longest)),
        };
        Reread {
            part: self,
            source,
            k: 0,
        }
    }
}

/// What a part read again hands out next: a json value whole, or the first csv row of a
/// value (the value's other rows follow from [`Reread::more`]).
pub enum Next<K: FileKind> {
    Value(K::Value),
    Row(K::Row),
}

/// A part's values read again ([`Part::reread`]): a json value at a time, or a csv row
/// at a time (a value of a sweep may have a million rows).
pub struct Reread<'a, K: FileKind, R: BufRead> {
    part: &'a Part<K>,
    source: Source<K, R>,
    /// Values begun.
    k: usize,
}

enum Source<K: FileKind, R: BufRead> {
    Csv(CsvSource<K, R>),
    Json(JsonItems<R>),
}

struct CsvSource<K: FileKind, R: BufRead> {
    rows: csv::Reader<Hashed<R>>,
    names: csv::StringRecord,
    record: csv::StringRecord,
    /// A row read past the end of a value: the next value's first.
    ahead: Option<K::Row>,
    /// The index the rows of the value being read state.
    index: Option<usize>,
    /// Rows read.
    read: usize,
}

impl<K: FileKind, R: BufRead> CsvSource<K, R> {
    /// The next row, or None at the end.
    fn row(&mut self) -> Result<Option<K::Row>, String> {
        if !self
            .rows
            .read_record(&mut self.record)
            .map_err(|e| one_line(&e.to_string()))?
        {
            return Ok(None);
        }
        self.read += 1;
        row_of(&self.record, &self.names).map(Some)
    }
}

/// A part that no longer reads as it did when checked.
fn changed(name: &str, why: &str) -> String {
    format!("{name}: changed since it was checked ({why}): valid parts left as they are until merge ends")
}

impl<K: FileKind, R: BufRead> Reread<'_, K, R> {
    /// The next value (json) or the first row of the next value (csv), with its place in
    /// the whole run; None after the last.
    pub fn next_value(&mut self) -> Result<Option<(usize, Next<K>)>, String> {
        let (part, k) = (self.part, self.k);
        let body = &part.body;
        let differs = |what: &str| Err(format!("its {what} differ from what was checked"));
        let next = match &mut self.source {
            Source::Csv(c) => {
                let row = match c.ahead.take() {
                    Some(row) => Ok(Some(row)),
                    None => c.row(),
                };
                match row {
                    Ok(Some(row)) => {
                        c.index = K::row_index(&row);
                        Ok(Some((c.index, Next::Row(row))))
                    }
                    Ok(None) if c.rows.get_ref().hash() != body.hash || c.read != body.rows => {
                        differs("rows")
                    }
                    Ok(None) if k != part.count => differs(K::UNIT),
                    other => other.map(|_| None),
                }
            }
            Source::Json(items) => match items.next_item() {
                Ok(Some((text, _))) => serde_json::from_slice::<K::Item>(text)
                    .map(|item| {
                        let v = K::from_item(item);
                        Some((K::stated_index(&v), Next::Value(v)))
                    })
                    .map_err(|e| one_line(&e.to_string())),
                Ok(None) => Ok(None),
                Err(e) => Err(one_line(&e.to_string())),
            }
            .and_then(|next| match next {
                None if items.hash() != body.hash || items.count() != part.count => {
                    differs(K::UNIT)
                }
                next => Ok(next),
            }),
        };
        match next.map_err(|e| changed(&part.name, &e))? {
            Some((stated, next)) => {
                self.k += 1;
                Ok(Some((K::place(part.shard, k, stated), next)))
            }
            None => Ok(None),
        }
    }

    /// The next csv row of the value begun last, or None when it has no more (a json
    /// value has none).
    pub fn more(&mut self) -> Result<Option<K::Row>, String> {
        let Source::Csv(c) = &mut self.source else {
            return Ok(None);
        };
        if c.ahead.is_some() {
            return Ok(None);
        }
        match c.row() {
            Ok(Some(row)) if c.index.is_some() && K::row_index(&row) == c.index => Ok(Some(row)),
            Ok(Some(row)) => {
                c.ahead = Some(row);
                Ok(None)
            }
            Ok(None) => Ok(None),
            Err(e) => Err(changed(&self.part.name, &e)),
        }
    }
}
