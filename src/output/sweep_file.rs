//! The sweep file: what `sweep` writes (csv or json), what `merge` reads back, checks
//! and joins. Defined here once, writer and reader side by side.
//!
//! Every file states where it comes from (its provenance): the tool and version, the
//! full run specification (the [`SweepHeader`]) and a hash of it, the shard `I/N` it
//! holds (`merged N/N` after a merge) and its number of values. A csv file states it in
//! `#` lines before the header row and closes with an end line counting the values and
//! rows and giving a checksum of the rows, so a truncated or damaged file is recognised:
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
//! A json file has the same as a `provenance` object before the settings and `values`,
//! and the checksum of its `values` array after it. The checksum is the 64-bit FNV-1a of
//! the rows' (the array's) bytes: it catches damage, not forgery.
//! Values are written in index order as they complete ([`SweepWriter`]), so memory is
//! bounded by the values in flight, not by the run.

use super::records::{PointRecord, SweepHeader, SweepRow, SweepValue};
use bouncemap_engine::sweep::{chain_len, grid_value, Shard, SweepParam, ValueResult, Warm};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::io::{self, Write};

/// The first line of a csv sweep file, and the tool of every provenance.
pub const TOOL: &str = concat!("bouncemap ", env!("CARGO_PKG_VERSION"));

/// Where a sweep file comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// `bouncemap VERSION`.
    pub tool: String,
    /// 64-bit FNV-1a of the canonical specification ([`spec_text`]), in hex.
    pub spec_hash: String,
    /// `I/N`, or `merged N/N` for a merge of all N shards.
    pub shard: String,
    /// Values the file holds.
    pub values: usize,
}

/// The canonical text of a specification: its compact json.
pub fn spec_text(header: &SweepHeader) -> String {
    serde_json::to_string(header).expect("a sweep header serializes")
}

/// 64-bit FNV-1a of `text`, as 16 hex digits (an identity check, not a security one).
pub fn spec_hash(text: &str) -> String {
    format!("{:016x}", fnv1a(FNV_START, text.as_bytes()))
}

pub(super) const FNV_START: u64 = 0xcbf29ce484222325;

/// 64-bit FNV-1a, continued from `h`.
pub(super) fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x100000001b3);
    }
    h
}

/// A writer that hashes what passes through it.
pub(super) struct Hashing<W: Write> {
    pub(super) inner: W,
    pub(super) hash: u64,
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

/// The provenance of a file of `values` values of the sweep `header`, shard `shard`.
pub fn provenance(header: &SweepHeader, shard: &str, values: usize) -> Provenance {
    Provenance {
        tool: TOOL.to_string(),
        spec_hash: spec_hash(&spec_text(header)),
        shard: shard.to_string(),
        values,
    }
}

/// How a shard is named in a provenance.
pub fn shard_name(s: Shard) -> String {
    format!("{}/{}", s.index + 1, s.count)
}

/// The two layouts of a sweep file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    Csv,
    Json,
}

/// Writes one sweep file, value by value in index order.
pub struct SweepWriter<W: Write> {
    inner: Inner<W>,
    values: usize,
    rows: usize,
    /// The optional columns: `lyapunov`, and `attractor` (several starts).
    lyapunov: bool,
    several: bool,
}

enum Inner<W: Write> {
    Csv(Box<csv::Writer<Hashing<W>>>),
    Json { out: Hashing<W>, first: bool },
}

impl<W: Write> SweepWriter<W> {
    /// Write the provenance and the settings; `values` is how many values will follow.
    pub fn begin(
        mut out: W,
        layout: Layout,
        header: &SweepHeader,
        shard: &str,
        values: usize,
    ) -> io::Result<SweepWriter<W>> {
        let prov = provenance(header, shard, values);
        let inner = match layout {
            Layout::Csv => {
                writeln!(out, "# {TOOL} sweep")?;
                writeln!(out, "# spec {}", spec_text(header))?;
                writeln!(out, "# spec-hash {}", prov.spec_hash)?;
                writeln!(out, "# shard {}", prov.shard)?;
                writeln!(out, "# values {}", prov.values)?;
                let head = header_row(header).join(",");
                writeln!(out, "{head}")?;
                // The rows from here on are hashed.
                let out = Hashing {
                    inner: out,
                    hash: FNV_START,
                };
                Inner::Csv(Box::new(
                    csv::WriterBuilder::new()
                        .has_headers(false)
                        .from_writer(out),
                ))
            }
            Layout::Json => {
                let settings = spec_text(header);
                write!(
                    out,
                    "{{\"provenance\":{},{},\"values\":",
                    serde_json::to_string(&prov)?,
                    &settings[1..settings.len() - 1]
                )?;
                // The values array from here on is hashed.
                let mut out = Hashing {
                    inner: out,
                    hash: FNV_START,
                };
                out.write_all(b"[")?;
                Inner::Json { out, first: true }
            }
        };
        Ok(SweepWriter {
            inner,
            values: 0,
            rows: 0,
            lyapunov: header.lyapunov,
            several: header.starts > 1,
        })
    }

    /// One value.
    pub fn value(&mut self, r: &ValueResult) -> io::Result<()> {
        match self.inner {
            Inner::Csv(_) => self.rows(&SweepRow::rows(r, self.lyapunov, self.several)),
            Inner::Json { .. } => self.json(&SweepValue::new(r, self.lyapunov, self.several)),
        }
    }

    /// One value's csv rows.
    pub fn rows(&mut self, rows: &[SweepRow]) -> io::Result<()> {
        let Inner::Csv(csv) = &mut self.inner else {
            return Err(io::Error::other("csv rows into a json sweep file"));
        };
        for row in rows {
            csv.serialize(row)?;
        }
        self.rows += rows.len();
        self.values += 1;
        Ok(())
    }

    /// One value's json object.
    pub fn json(&mut self, v: &SweepValue) -> io::Result<()> {
        let Inner::Json { out, first } = &mut self.inner else {
            return Err(io::Error::other("a json value into a csv sweep file"));
        };
        if !*first {
            out.write_all(b",")?;
        }
        *first = false;
        serde_json::to_writer(&mut *out, v)?;
        self.values += 1;
        Ok(())
    }

    /// Close the file (csv: the end line) and hand back the writer.
    pub fn end(self) -> io::Result<W> {
        match self.inner {
            Inner::Csv(csv) => {
                let Hashing { mut inner, hash } =
                    (*csv).into_inner().map_err(|e| e.into_error())?;
                writeln!(
                    inner,
                    "# end {} values, {} rows, checksum {hash:016x}",
                    self.values, self.rows
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

/// The swept parameter a header names.
/// The csv header row of the sweep `h`.
pub fn header_row(h: &SweepHeader) -> Vec<&'static str> {
    SweepRow::header(param_of(h), h.lyapunov, h.starts > 1)
}

fn param_of(h: &SweepHeader) -> SweepParam {
    SweepParam::ALL
        .into_iter()
        .find(|p| p.as_str() == h.param)
        .unwrap_or(SweepParam::Alpha)
}

// ------------------------------------------------------------------ reading

/// One value of a part, as read.
#[derive(Clone, Debug, PartialEq)]
pub enum PartValue {
    Csv { index: usize, rows: Vec<SweepRow> },
    Json(SweepValue),
}

impl PartValue {
    pub fn index(&self) -> usize {
        match self {
            PartValue::Csv { index, .. } => *index,
            PartValue::Json(v) => v.index,
        }
    }
}

/// A part file, read and checked on its own.
#[derive(Clone, Debug)]
pub struct Part {
    pub name: String,
    pub layout: Layout,
    pub provenance: Provenance,
    pub header: SweepHeader,
    /// The shard it holds (None for a merged file).
    pub shard: Option<Shard>,
    pub values: Vec<PartValue>,
}

/// The json layout as read.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonPart<'a> {
    provenance: Provenance,
    #[serde(flatten)]
    header: SweepHeader,
    #[serde(borrow)]
    values: &'a serde_json::value::RawValue,
    checksum: String,
}

/// Read and check part `name`: its provenance, its specification against its hash,
/// every row (complete, well-formed, inside its shard, at the value its index means)
/// and its count of values. Refusals are one line naming the file (and the line).
pub fn read_part(name: &str, text: &str) -> Result<Part, String> {
    let bad = |msg: String| format!("{name}: {msg}");
    let part = if text.trim_start().starts_with('{') {
        let p: JsonPart = serde_json::from_str(text)
            .map_err(|e| bad(format!("not a complete sweep json file ({e})")))?;
        let sum = format!("{:016x}", fnv1a(FNV_START, p.values.get().as_bytes()));
        if sum != p.checksum {
            return Err(bad(format!(
                "its values do not match their checksum {} (damaged?)",
                clip(&p.checksum)
            )));
        }
        let values: Vec<SweepValue> = serde_json::from_str(p.values.get())
            .map_err(|e| bad(format!("malformed values ({e})")))?;
        Part {
            name: name.to_string(),
            layout: Layout::Json,
            shard: parse_shard(&p.provenance.shard).map_err(&bad)?,
            provenance: p.provenance,
            header: p.header,
            values: values.into_iter().map(PartValue::Json).collect(),
        }
    } else {
        read_csv(name, text)?
    };
    let spec = spec_text(&part.header);
    if spec_hash(&spec) != part.provenance.spec_hash {
        return Err(bad(format!(
            "its specification does not match its hash {} (edited?)",
            part.provenance.spec_hash
        )));
    }
    check_values(&part).map_err(&bad)?;
    Ok(part)
}

pub(super) fn parse_shard(s: &str) -> Result<Option<Shard>, String> {
    if s.starts_with("merged ") {
        return Ok(None);
    }
    let parsed = s.split_once('/').and_then(|(i, n)| {
        let (i, n): (usize, usize) = (i.parse().ok()?, n.parse().ok()?);
        (i >= 1 && i <= n).then_some(Shard {
            index: i - 1,
            count: n,
        })
    });
    parsed
        .map(Some)
        .ok_or_else(|| format!("shard '{s}' is not I/N with 1 ≤ I ≤ N"))
}

/// A csv part split into its provenance lines, header row, rows and end line.
pub(super) struct CsvPart {
    pub tool: String,
    pub spec: String,
    pub hash: String,
    pub shard_text: String,
    pub count_text: String,
    /// Line 6, the header row.
    pub head: String,
    /// The rows (line 7 on), each ending in a newline.
    pub body: String,
    /// The last line.
    pub end: String,
}

/// Split a csv part of `kind` (`sweep`, `plane`) whose line 5 is `# {count_key} N`:
/// the provenance lines checked for their keys, the rest by line.
pub(super) fn split_csv_part(
    name: &str,
    text: &str,
    kind: &str,
    count_key: &str,
) -> Result<CsvPart, String> {
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
pub(super) fn csv_rows<T: serde::de::DeserializeOwned>(
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

fn read_csv(name: &str, text: &str) -> Result<Part, String> {
    let p = split_csv_part(name, text, "sweep", "values")?;
    let header: SweepHeader = serde_json::from_str(&p.spec)
        .map_err(|e| format!("{name}: line 2: not a sweep specification ({e})"))?;
    let values: usize = p
        .count_text
        .parse()
        .map_err(|_| format!("{name}: line 5: '{}' is not a count", clip(&p.count_text)))?;
    let shard = parse_shard(&p.shard_text).map_err(|e| format!("{name}: line 4: {e}"))?;
    let columns = header_row(&header);
    let want = columns.join(",");
    if p.head != want {
        return Err(format!(
            "{name}: line 6: header '{}' is not '{want}'",
            clip(&p.head)
        ));
    }
    let mut out: Vec<PartValue> = Vec::new();
    let mut rows = 0usize;
    let names = csv::StringRecord::from(columns.clone());
    csv_rows(name, &p.body, &names, |row: SweepRow| {
        rows += 1;
        match out.last_mut() {
            Some(PartValue::Csv { index, rows }) if *index == row.index => rows.push(row),
            _ => out.push(PartValue::Csv {
                index: row.index,
                rows: vec![row],
            }),
        }
        Ok(())
    })?;
    let sum = fnv1a(FNV_START, p.body.as_bytes());
    let want_end = format!(
        "# end {} values, {rows} rows, checksum {sum:016x}",
        out.len()
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
            values,
        },
        header,
        shard,
        values: out,
    })
}

pub(super) fn one_line(s: &str) -> String {
    s.replace('\n', " ")
}

/// At most 60 characters of `s`, control characters escaped.
pub(super) fn clip(s: &str) -> String {
    let esc = super::text::escape(s);
    if esc.chars().count() > 60 {
        esc.chars().take(59).collect::<String>() + "…"
    } else {
        esc
    }
}

/// The checks on a part's values: in index order, each once, inside its shard, at the
/// value its index means, well-formed, and as many as the provenance says.
fn check_values(part: &Part) -> Result<(), String> {
    let h = &part.header;
    let warm = Warm::from_name(&h.start).ok_or_else(|| {
        format!(
            "start '{}' is not cold, warm or warm-backward",
            clip(&h.start)
        )
    })?;
    let mut prev: Option<usize> = None;
    for v in &part.values {
        let i = v.index();
        if i >= h.steps {
            return Err(format!(
                "value {i} is outside the sweep's {} values",
                h.steps
            ));
        }
        if prev.is_some_and(|p| i <= p) {
            return Err(format!("value {i} is out of order or repeated"));
        }
        prev = Some(i);
        if let Some(s) = part.shard {
            if !s.holds(i, chain_len(warm)) {
                return Err(format!(
                    "value {i} does not belong to shard {}",
                    shard_name(s)
                ));
            }
        }
        let want = grid_value(h.lo, h.hi, h.steps, i);
        check_value(v, want, h.keep.saturating_mul(h.starts.max(1)))
            .map_err(|e| format!("value {i}: {e}"))?;
    }
    let expected = match part.shard {
        Some(s) => s.items_of(h.steps, chain_len(warm)),
        None => h.steps,
    };
    if part.values.len() != part.provenance.values || part.values.len() != expected {
        return Err(format!(
            "holds {} values; its provenance says {} and its shard has {expected}",
            part.values.len(),
            part.provenance.values
        ));
    }
    Ok(())
}

fn check_point(phase: f64, v: f64) -> Result<(), String> {
    if !(phase.is_finite() && (0.0..1.0).contains(&phase)) {
        return Err(format!("phase {phase} is not in [0, 1)"));
    }
    if !v.is_finite() {
        return Err(format!("velocity {v} is not finite"));
    }
    Ok(())
}

fn check_value(v: &PartValue, want: f64, keep: usize) -> Result<(), String> {
    let (value, points) = match v {
        PartValue::Csv { rows, .. } => {
            let r0 = &rows[0];
            for r in rows {
                // Rows of one attractor (all rows, with one start) share its outcome.
                let same_attractor = rows.iter().find(|x| x.attractor == r.attractor);
                let a0 = same_attractor.unwrap_or(r0);
                if (r.period, r.table_periods, r.status, r.sticking)
                    != (a0.period, a0.table_periods, a0.status, r0.sticking)
                    || r.value.to_bits() != r0.value.to_bits()
                    || r.lyapunov.is_some() != r0.lyapunov.is_some()
                    || r.attractor.is_some() != r0.attractor.is_some()
                {
                    return Err("its rows disagree on the value's outcome".into());
                }
                match (r.phase, r.v, r.kind) {
                    (Some(p), Some(vel), Some(_)) => check_point(p, vel)?,
                    (None, None, None) if rows.len() == 1 => {}
                    _ => return Err("a row has a partial point".into()),
                }
            }
            let n = if r0.phase.is_none() { 0 } else { rows.len() };
            (r0.value, n)
        }
        PartValue::Json(s) => {
            for PointRecord { phase, v, .. } in &s.points {
                check_point(*phase, *v)?;
            }
            (s.value, s.points.len())
        }
    };
    if value.to_bits() != want.to_bits() {
        return Err(format!(
            "its parameter is {value}, but its index means {want}"
        ));
    }
    if points > keep {
        return Err(format!("{points} points, more than keep = {keep}"));
    }
    Ok(())
}

/// Join checked parts of one sweep: the same tool, specification and layout, every
/// shard of 1..N exactly once. Returns the parts' common header and the values in index
/// order; refusals name the file.
pub fn join(parts: Vec<Part>) -> Result<(Layout, SweepHeader, Vec<PartValue>), String> {
    let first = parts.first().ok_or("no parts given")?;
    let (layout, header) = (first.layout, first.header.clone());
    let count = first.shard.map_or(1, |s| s.count);
    let mut seen: Vec<Option<String>> = vec![None; count];
    for p in &parts {
        if p.layout != layout {
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
                "{}: a part of another sweep ({} differs from {}'s): valid parts of one sweep",
                p.name,
                differing_setting(&p.header, &header),
                first.name
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
        if let Some(other) = &seen[s.index] {
            return Err(format!(
                "{}: shard {} is also in {other}: valid each shard once",
                p.name,
                shard_name(s)
            ));
        }
        seen[s.index] = Some(p.name.clone());
    }
    let missing: Vec<String> = seen
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
    let mut values: Vec<PartValue> = parts.into_iter().flat_map(|p| p.values).collect();
    values.sort_by_key(PartValue::index);
    let distinct: BTreeSet<usize> = values.iter().map(PartValue::index).collect();
    if distinct.len() != header.steps || values.len() != header.steps {
        return Err(format!(
            "the parts hold {} of the sweep's {} values",
            distinct.len(),
            header.steps
        ));
    }
    Ok((layout, header, values))
}

/// The first setting in which two specifications differ, named.
pub fn differing_setting(a: &SweepHeader, b: &SweepHeader) -> String {
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
