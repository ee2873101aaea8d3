//! The part file: the one format of what `sweep` and `plane` write (csv or json) and
//! `merge` reads back, checks and joins. A [`FileKind`] says what is particular to one
//! kind of file (its settings, its rows, where a row belongs); everything else is here,
//! once: the provenance, the hashes, the shards, the csv and json layouts, the
//! streaming writer ([`PartWriter`]), the reader that checks a part ([`read_part`]) and
//! the join of the parts of one run ([`join`]).
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

use bouncemap_engine::grid::Shard;
use serde::de::{self, DeserializeOwned, DeserializeSeed, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::value::RawValue;
use std::fmt::{self, Debug};
use std::io::{self, Write};
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
    /// Check every value of `part` (well-formed, inside its shard, where its place
    /// says); returns how many values its shard has.
    fn check(part: &Part<Self>) -> Result<usize, String>;
    /// Every value of a run from the values of its shards 1..N (each in its file's
    /// order), in index order; refuses if some are missing.
    fn combine(
        header: &Self::Header,
        shards: Vec<Vec<Self::Value>>,
    ) -> Result<Vec<Self::Value>, String>;
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

const FNV_START: u64 = 0xcbf29ce484222325;

/// 64-bit FNV-1a, continued from `h`.
fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x100000001b3);
    }
    h
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

    /// One value's json item.
    pub fn json(&mut self, item: &K::Item) -> io::Result<()> {
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

/// A part file, read and checked on its own.
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
    pub values: Vec<K::Value>,
}

/// Whether `text` opens as a file of this very run would: kind `K`, `layout`, this
/// tool, the specification `header` (by its hash) and shard `shard`, read from the
/// provenance at its head only (the first lines of a csv file, the first object of a
/// json one), so a part of this run that was cut off or damaged later is still
/// recognised as its own, and anything else (another run's part, a file not written by
/// this tool) is not.
pub fn opens_as<K: FileKind>(text: &str, layout: Layout, header: &K::Header, shard: &str) -> bool {
    let hash = spec_hash(&spec_text(header));
    match layout {
        Layout::Csv => {
            let mut lines = text.lines();
            let tool_line = format!("# {TOOL} {}", K::KIND);
            lines.next() == Some(tool_line.as_str())
                && lines.next().is_some_and(|l| l.starts_with("# spec "))
                && lines.next() == Some(format!("# spec-hash {hash}").as_str())
                && lines.next() == Some(format!("# shard {shard}").as_str())
        }
        Layout::Json => {
            let Some(rest) = text.strip_prefix("{\"provenance\":") else {
                return false;
            };
            let Some(Ok(prov)) = serde_json::Deserializer::from_str(rest)
                .into_iter::<serde_json::Value>()
                .next()
            else {
                return false;
            };
            prov["tool"] == TOOL && prov["spec_hash"] == hash.as_str() && prov["shard"] == shard
        }
    }
}

/// Read and check part `name` of kind `K`: its provenance, its specification against
/// its hash, every row (complete, well-formed, inside its shard, where its place says),
/// its end line or checksum, and its count. Refusals are one line naming the file (and
/// the line).
pub fn read_part<K: FileKind>(name: &str, text: &str) -> Result<Part<K>, String> {
    let bad = |msg: String| format!("{name}: {msg}");
    let part = if text.trim_start().starts_with('{') {
        read_json::<K>(name, text).map_err(&bad)?
    } else {
        read_csv::<K>(name, text)?
    };
    if spec_hash(&spec_text(&part.header)) != part.provenance.spec_hash {
        return Err(bad(format!(
            "its specification does not match its hash {} (edited?)",
            part.provenance.spec_hash
        )));
    }
    let expected = K::check(&part).map_err(&bad)?;
    if part.values.len() != part.provenance.count || part.values.len() != expected {
        return Err(bad(format!(
            "holds {} {}; its provenance says {} and its shard has {expected}",
            part.values.len(),
            K::UNIT,
            part.provenance.count
        )));
    }
    Ok(part)
}

fn read_json<K: FileKind>(name: &str, text: &str) -> Result<Part<K>, String> {
    let p: JsonPart<K> = serde_json::from_str(text).map_err(|e| {
        format!(
            "not a complete {} json file ({})",
            K::KIND,
            one_line(&e.to_string())
        )
    })?;
    let hash = p
        .sections
        .iter()
        .fold(FNV_START, |h, s| fnv1a(h, s.get().as_bytes()));
    if format!("{hash:016x}") != p.checksum {
        return Err(format!(
            "its {} do not match their checksum {} (damaged?)",
            K::UNIT,
            clip(&p.checksum)
        ));
    }
    let (values, before) = p
        .sections
        .split_last()
        .expect("a kind has the section of its values");
    let items: Vec<K::Item> = serde_json::from_str(values.get())
        .map_err(|e| format!("malformed {} ({})", K::UNIT, one_line(&e.to_string())))?;
    let shard = parse_shard(&p.provenance.shard)?;
    if p.file.as_deref().is_some_and(|f| f != K::KIND) {
        return Err(format!("not a {} file", K::KIND));
    }
    Ok(Part {
        name: name.to_string(),
        layout: Layout::Json,
        provenance: p.provenance,
        header: p.header,
        shard,
        sections: before.iter().map(|s| s.get().to_string()).collect(),
        values: items.into_iter().map(K::from_item).collect(),
    })
}

/// The json layout as read: the provenance, the settings (every other key), the
/// sections as their raw text and the checksum.
struct JsonPart<'a, K: FileKind> {
    provenance: Provenance,
    /// The kind the file names (`file`), if it names one.
    file: Option<String>,
    header: K::Header,
    sections: Vec<&'a RawValue>,
    checksum: String,
}

impl<'de, K: FileKind> Deserialize<'de> for JsonPart<'de, K> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(JsonVisitor::<K>(PhantomData))
    }
}

struct JsonVisitor<K>(PhantomData<K>);

impl<'de, K: FileKind> Visitor<'de> for JsonVisitor<K> {
    type Value = JsonPart<'de, K>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a {} file", K::KIND)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut provenance = None;
        let mut checksum: Option<String> = None;
        let mut sections: Vec<Option<&'de RawValue>> = vec![None; K::SECTIONS.len()];
        let mut settings = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if key == "provenance" {
                once(&provenance, "provenance")?;
                provenance = Some(map.next_value_seed(ProvenanceSeed::<K>(PhantomData))?);
            } else if key == "checksum" {
                once(&checksum, "checksum")?;
                checksum = Some(map.next_value()?);
            } else if let Some(k) = K::SECTIONS.iter().position(|s| *s == key) {
                once(&sections[k], K::SECTIONS[k])?;
                sections[k] = Some(map.next_value()?);
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
        Ok(JsonPart {
            provenance,
            file,
            header,
            sections,
            checksum: checksum.ok_or_else(|| de::Error::missing_field("checksum"))?,
        })
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

fn read_csv<K: FileKind>(name: &str, text: &str) -> Result<Part<K>, String> {
    let p = split_csv(name, text, K::KIND, K::UNIT)?;
    let header: K::Header = serde_json::from_str(&p.spec).map_err(|e| {
        format!(
            "{name}: line 2: not a {} specification ({})",
            K::KIND,
            one_line(&e.to_string())
        )
    })?;
    let count: usize = p
        .count_text
        .parse()
        .map_err(|_| format!("{name}: line 5: '{}' is not a count", clip(&p.count_text)))?;
    let shard = parse_shard(&p.shard_text).map_err(|e| format!("{name}: line 4: {e}"))?;
    let want = K::header_row(&header);
    if p.head != want {
        return Err(format!(
            "{name}: line 6: header '{}' is not '{want}'",
            clip(&p.head)
        ));
    }
    let names = csv::StringRecord::from(K::field_names(&header));
    let mut values = Vec::new();
    let mut rows = 0usize;
    csv_rows(name, &p.body, &names, |row: K::Row| {
        rows += 1;
        K::add_row(&mut values, row)
    })?;
    let sum = fnv1a(FNV_START, p.body.as_bytes());
    let want_end = format!(
        "# end {}, checksum {sum:016x}",
        K::end_counts(values.len(), rows)
    );
    if p.end != want_end {
        return Err(format!(
            "{name}: truncated or damaged: its last line is '{}', expected '{want_end}'",
            clip(&p.end)
        ));
    }
    Ok(Part {
        name: name.to_string(),
        layout: Layout::Csv,
        provenance: Provenance {
            tool: p.tool,
            spec_hash: p.hash,
            shard: p.shard_text,
            count,
        },
        header,
        shard,
        sections: vec!["null".to_string(); K::SECTIONS.len() - 1],
        values,
    })
}

/// A csv part split into its provenance lines, header row, rows and end line.
struct CsvPart {
    tool: String,
    spec: String,
    hash: String,
    shard_text: String,
    count_text: String,
    /// Line 6, the header row.
    head: String,
    /// The rows (line 7 on), each ending in a newline.
    body: String,
    /// The last line.
    end: String,
}

/// Split a csv part of `kind` whose line 5 is `# {count_key} N`: the provenance lines
/// checked for their keys, the rest by line.
fn split_csv(name: &str, text: &str, kind: &str, count_key: &str) -> Result<CsvPart, String> {
    let mut lines = text.split_inclusive('\n');
    let mut next_line = |what: &str, n: usize| -> Result<String, String> {
        let l = lines
            .next()
            .ok_or_else(|| format!("{name}: line {n}: missing ({what})"))?;
        Ok(l.trim_end_matches(['\n', '\r']).to_string())
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
    let count_text = field(next_line(count_key, 5)?, count_key, 5)?;
    let head = next_line("header row", 6)?;
    // The rows, then the end line.
    let rest: String = lines.collect();
    let (body, end) = match rest.trim_end_matches('\n').rsplit_once('\n') {
        Some((b, e)) => (format!("{b}\n"), e.to_string()),
        None => (String::new(), rest.trim_end_matches('\n').to_string()),
    };
    Ok(CsvPart {
        tool,
        spec,
        hash,
        shard_text,
        count_text,
        head,
        body,
        end,
    })
}

/// Each row of `body` (line 7 on), exactly as wide as `names` and deserialized by them,
/// handed to `each` with its line; any failure is "{name}: line L: malformed row: …".
fn csv_rows<T: DeserializeOwned>(
    name: &str,
    body: &str,
    names: &csv::StringRecord,
    mut each: impl FnMut(T) -> Result<(), String>,
) -> Result<(), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(body.as_bytes());
    for (k, rec) in reader.records().enumerate() {
        // Rows are one line each (no field holds a newline): row k is line 7 + k.
        let line = 7 + k;
        let malformed = |what: String| format!("{name}: line {line}: malformed row: {what}");
        let rec = rec.map_err(|e| malformed(one_line(&e.to_string())))?;
        if rec.len() != names.len() {
            return Err(malformed(format!(
                "{} fields, expected {}",
                rec.len(),
                names.len()
            )));
        }
        let row: T = rec.deserialize(Some(names)).map_err(|e| match e.kind() {
            csv::ErrorKind::Deserialize { err, .. } => malformed(one_line(&err.kind().to_string())),
            _ => malformed(one_line(&e.to_string())),
        })?;
        each(row).map_err(malformed)?;
    }
    Ok(())
}

// ------------------------------------------------------------------ joining

/// The parts of one run joined: what the unsharded run writes.
#[derive(Clone, Debug)]
pub struct Joined<K: FileKind> {
    pub layout: Layout,
    pub header: K::Header,
    /// Shards joined (1 for a whole file).
    pub shards: usize,
    /// The json texts of the sections before the values.
    pub sections: Vec<String>,
    /// Every value, in index order.
    pub values: Vec<K::Value>,
}

impl<K: FileKind> Joined<K> {
    /// Write the joined file: the unsharded run's, but for its shard, which says
    /// `merged N/N` where the unsharded file says `1/1`.
    pub fn write<W: Write>(&self, out: W) -> io::Result<W> {
        let shard = if self.shards > 1 {
            format!("merged {0}/{0}", self.shards)
        } else {
            "1/1".to_string()
        };
        let sections: Vec<&str> = self.sections.iter().map(String::as_str).collect();
        let mut w = PartWriter::<W, K>::begin(
            out,
            self.layout,
            &self.header,
            &shard,
            self.values.len(),
            &sections,
        )?;
        for v in &self.values {
            w.value(v)?;
        }
        w.end()
    }
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
    let shards = slots
        .into_iter()
        .flatten()
        .map(|n| parts[n].take().map_or_else(Vec::new, |p| p.values))
        .collect();
    Ok(Joined {
        layout,
        values: K::combine(&header, shards)?,
        header,
        shards: count,
        sections,
    })
}
