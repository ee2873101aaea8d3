//! The plane file: what `plane` writes (csv or json), what `merge` reads back, checks
//! and joins, in the sweep file's form (see [`super::sweep_file`]): provenance lines,
//! the specification and its hash, the shard, one row per pixel, an end line with a
//! checksum.
//!
//! ```text
//! # bouncemap 0.1.0 plane
//! # spec {"table":"fd:0.1","x":{"param":"alpha",...},"y":{...},...}
//! # spec-hash 3f0c9a1d2b7e4c55
//! # shard 2/4
//! # pixels 20000
//! alpha,d,class,period,table_periods,lyapunov,status
//! ...
//! # end 20000 pixels, checksum 9a4f0c2e71b3d855
//! ```
//!
//! Rows are the shard's pixels in index order (index j·W + i, row j = 0 at y = lo):
//! shard I/N holds the pixels whose index is I − 1 modulo N, so its k-th row is pixel
//! I − 1 + kN and a reader knows which pixel every row must be. A json file has the
//! provenance (with `"file": "plane"`), the settings, `curves` (the analytic curves,
//! null without an α axis), `pixels` and the checksum of the curves' and pixels' bytes.

use super::classes::{of_pixel, Class};
use super::records::{solver_name, EarlyStop, Exponent};
use super::sweep_file::{clip, fnv1a, one_line, parse_shard, shard_name, Hashing, FNV_START, TOOL};
use super::sweep_file::{csv_rows, spec_hash, split_csv_part, Layout};
use bouncemap_engine::plane::{Curves, Pixel, PlaneSpec};
use bouncemap_engine::sweep::{grid_value, Outcome, Shard};
use serde::{Deserialize, Serialize};
use std::io::{self, Write};

/// One axis as files state it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisRecord {
    pub param: String,
    pub lo: f64,
    pub hi: f64,
    pub n: usize,
}

impl AxisRecord {
    fn value(&self, i: usize) -> f64 {
        grid_value(self.lo, self.hi, self.n, i)
    }
}

/// The settings of a plane: its full specification (the shard is in the provenance).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneHeader {
    pub table: String,
    pub x: AxisRecord,
    pub y: AxisRecord,
    /// The fixed parameters (null for an axis; d null unless the table is F_D).
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub d: Option<f64>,
    pub transient: u64,
    /// `near-fixed-point` or `cold`.
    pub start: String,
    pub solver: String,
    pub early_stop: Option<EarlyStop>,
    pub lyapunov: bool,
}

impl From<&PlaneSpec> for PlaneHeader {
    fn from(s: &PlaneSpec) -> PlaneHeader {
        let on_axis = |name: &str| s.x.param.as_str() == name || s.y.param.as_str() == name;
        let axis = |a: &bouncemap_engine::plane::Axis| AxisRecord {
            param: a.param.as_str().to_string(),
            lo: a.lo,
            hi: a.hi,
            n: a.n,
        };
        PlaneHeader {
            table: if on_axis("d") {
                "fd".to_string()
            } else {
                s.table.name().to_string()
            },
            x: axis(&s.x),
            y: axis(&s.y),
            alpha: (!on_axis("alpha")).then_some(s.alpha),
            r: (!on_axis("r")).then_some(s.r),
            d: if on_axis("d") { None } else { s.table.d() },
            transient: s.transient,
            start: s.start.as_str().to_string(),
            solver: solver_name(s.solver).to_string(),
            early_stop: s.periodicity.map(|p| EarlyStop {
                max_period: p.max_period,
                tolerance: p.tolerance,
            }),
            lyapunov: s.lyapunov,
        }
    }
}

impl PlaneHeader {
    /// Pixels in the plane.
    pub fn len(&self) -> usize {
        self.x.n.saturating_mul(self.y.n)
    }

    /// Whether the plane has no pixel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// (x, y) of pixel `index`.
    pub fn values(&self, index: usize) -> (f64, f64) {
        let n = self.x.n.max(1);
        (self.x.value(index % n), self.y.value(index / n))
    }

    /// The csv header row.
    pub fn header_row(&self) -> String {
        format!(
            "{},{},class,period,table_periods,lyapunov,status",
            self.x.param, self.y.param
        )
    }
}

/// Where a plane file comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneProvenance {
    /// Always `plane`.
    pub file: String,
    pub tool: String,
    pub spec_hash: String,
    /// `I/N`, or `merged N/N`.
    pub shard: String,
    /// Pixels the file holds.
    pub pixels: usize,
}

/// One pixel as files state it (csv: the columns are named after the axes' parameters).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PixelRow {
    pub x: f64,
    pub y: f64,
    /// A [`Class::name`], or `no-landing`.
    pub class: String,
    pub period: Option<usize>,
    pub table_periods: Option<i64>,
    pub lyapunov: Exponent,
    /// `periodic`, `unsettled`, `resting`, `no-landing`.
    pub status: String,
}

/// The class name of a pixel where the ball never lands.
pub const NO_LANDING: &str = "no-landing";
const STATUSES: [&str; 4] = ["periodic", "unsettled", "resting", "no-landing"];

impl PixelRow {
    /// The row of a computed pixel at (x, y).
    pub fn new(x: f64, y: f64, p: &Pixel) -> PixelRow {
        PixelRow {
            x,
            y,
            class: of_pixel(p).map_or(NO_LANDING, Class::name).to_string(),
            period: p.outcome.period(),
            table_periods: p.outcome.table_periods(),
            lyapunov: Exponent(p.lyapunov),
            status: p.outcome.as_str().to_string(),
        }
    }

    fn check(&self) -> Result<(), String> {
        if Class::from_name(&self.class).is_none() && self.class != NO_LANDING {
            return Err(format!(
                "class '{}' is not one of period-1, period-2, period-4, period-8, periodic, sticking, chaotic, unresolved, no-landing",
                clip(&self.class)
            ));
        }
        if !STATUSES.contains(&self.status.as_str()) {
            return Err(format!(
                "status '{}' is not periodic, unsettled, resting or no-landing",
                clip(&self.status)
            ));
        }
        let cycle = self.status == "periodic";
        if cycle != self.period.is_some() || cycle != self.table_periods.is_some() {
            return Err(
                "period and table_periods must be given exactly for periodic pixels".into(),
            );
        }
        if self.lyapunov.0.is_some_and(f64::is_nan) {
            return Err("lyapunov is not a number".into());
        }
        Ok(())
    }
}

/// The curves as json states them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurvesRecord<'a> {
    /// `x` or `y`: the axis the α values refer to.
    pub alpha_axis: &'static str,
    /// The other axis's parameter and its pixel values.
    pub along: &'static str,
    pub values: &'a [f64],
    pub alpha_birth: &'a [Option<f64>],
    pub alpha_pd: &'a [Option<f64>],
    pub border_collision: &'a [Option<f64>],
}

impl<'a> From<&'a Curves> for CurvesRecord<'a> {
    fn from(c: &'a Curves) -> CurvesRecord<'a> {
        CurvesRecord {
            alpha_axis: if c.alpha_on_x { "x" } else { "y" },
            along: c.along.as_str(),
            values: &c.values,
            alpha_birth: &c.birth,
            alpha_pd: &c.pd,
            border_collision: &c.border,
        }
    }
}

/// Write one plane file: `rows` are the file's `count` pixels in index order, made as
/// they are written (a plane's rows are never all held at once); `curves` the json
/// text of the curves (`null` without them; ignored for csv).
pub fn write<W: Write>(
    mut out: W,
    layout: Layout,
    header: &PlaneHeader,
    shard: &str,
    curves: &str,
    count: usize,
    rows: impl Iterator<Item = PixelRow>,
) -> io::Result<W> {
    let spec = spec_text(header);
    let prov = PlaneProvenance {
        file: "plane".into(),
        tool: TOOL.into(),
        spec_hash: spec_hash(&spec),
        shard: shard.into(),
        pixels: count,
    };
    match layout {
        Layout::Csv => {
            writeln!(out, "# {TOOL} plane")?;
            writeln!(out, "# spec {spec}")?;
            writeln!(out, "# spec-hash {}", prov.spec_hash)?;
            writeln!(out, "# shard {}", prov.shard)?;
            writeln!(out, "# pixels {}", prov.pixels)?;
            writeln!(out, "{}", header.header_row())?;
            let hashing = Hashing {
                inner: out,
                hash: FNV_START,
            };
            let mut w = csv::WriterBuilder::new()
                .has_headers(false)
                .from_writer(hashing);
            let mut written = 0;
            for r in rows {
                w.serialize(r)?;
                written += 1;
            }
            let Hashing { mut inner, hash } = w.into_inner().map_err(|e| e.into_error())?;
            writeln!(inner, "# end {written} pixels, checksum {hash:016x}")?;
            Ok(inner)
        }
        Layout::Json => {
            write!(
                out,
                "{{\"provenance\":{},{},\"curves\":",
                serde_json::to_string(&prov)?,
                &spec[1..spec.len() - 1]
            )?;
            let mut h = Hashing {
                inner: out,
                hash: FNV_START,
            };
            h.write_all(curves.as_bytes())?;
            h.inner.write_all(b",\"pixels\":")?;
            h.write_all(b"[")?;
            for (k, r) in rows.enumerate() {
                if k > 0 {
                    h.write_all(b",")?;
                }
                serde_json::to_writer(&mut h, &r)?;
            }
            h.write_all(b"]")?;
            let Hashing { mut inner, hash } = h;
            writeln!(inner, ",\"checksum\":\"{hash:016x}\"}}")?;
            Ok(inner)
        }
    }
}

/// The canonical text of a specification: its compact json.
pub fn spec_text(header: &PlaneHeader) -> String {
    serde_json::to_string(header).expect("a plane header serializes")
}

/// Whether `text` is a plane file (rather than a sweep file).
pub fn is_plane(text: &str) -> bool {
    let head: String = text.chars().take(400).collect();
    let first = head.lines().next().unwrap_or("");
    (first.starts_with("# bouncemap ") && first.ends_with(" plane"))
        || (head.trim_start().starts_with('{') && head.contains("\"file\":\"plane\""))
}

// ------------------------------------------------------------------ reading

/// A plane part file, read and checked on its own.
#[derive(Clone, Debug)]
pub struct PlanePart {
    pub name: String,
    pub layout: Layout,
    pub provenance: PlaneProvenance,
    pub header: PlaneHeader,
    /// None for a merged (or whole) file.
    pub shard: Option<Shard>,
    /// The curves' json text (json files).
    pub curves: String,
    pub rows: Vec<PixelRow>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonPart<'a> {
    provenance: PlaneProvenance,
    #[serde(flatten)]
    header: PlaneHeader,
    #[serde(borrow)]
    curves: &'a serde_json::value::RawValue,
    #[serde(borrow)]
    pixels: &'a serde_json::value::RawValue,
    checksum: String,
}

/// Read and check plane part `name`: provenance, specification against its hash,
/// every row (well-formed, at the pixel its position in its shard means), the end line
/// and the count. Refusals are one line naming the file (and the line).
pub fn read_part(name: &str, text: &str) -> Result<PlanePart, String> {
    let bad = |msg: String| format!("{name}: {msg}");
    let part = if text.trim_start().starts_with('{') {
        let p: JsonPart = serde_json::from_str(text).map_err(|e| {
            bad(format!(
                "not a complete plane json file ({})",
                one_line(&e.to_string())
            ))
        })?;
        let h = fnv1a(FNV_START, p.curves.get().as_bytes());
        let sum = format!("{:016x}", fnv1a(h, p.pixels.get().as_bytes()));
        if sum != p.checksum {
            return Err(bad(format!(
                "its pixels do not match their checksum {} (damaged?)",
                clip(&p.checksum)
            )));
        }
        let rows: Vec<PixelRow> = serde_json::from_str(p.pixels.get())
            .map_err(|e| bad(format!("malformed pixels ({})", one_line(&e.to_string()))))?;
        PlanePart {
            name: name.to_string(),
            layout: Layout::Json,
            shard: parse_shard(&p.provenance.shard).map_err(&bad)?,
            provenance: p.provenance,
            header: p.header,
            curves: p.curves.get().to_string(),
            rows,
        }
    } else {
        read_csv(name, text)?
    };
    if part.provenance.file != "plane" {
        return Err(bad("not a plane file".into()));
    }
    if spec_hash(&spec_text(&part.header)) != part.provenance.spec_hash {
        return Err(bad(format!(
            "its specification does not match its hash {} (edited?)",
            part.provenance.spec_hash
        )));
    }
    check_rows(&part).map_err(&bad)?;
    Ok(part)
}

fn read_csv(name: &str, text: &str) -> Result<PlanePart, String> {
    let p = split_csv_part(name, text, "plane", "pixels")?;
    let (tool, hash, shard_text, body, end) = (p.tool, p.hash, p.shard_text, p.body, p.end);
    let header: PlaneHeader = serde_json::from_str(&p.spec).map_err(|e| {
        format!(
            "{name}: line 2: not a plane specification ({})",
            one_line(&e.to_string())
        )
    })?;
    let pixels: usize = p
        .count_text
        .parse()
        .map_err(|_| format!("{name}: line 5: '{}' is not a count", clip(&p.count_text)))?;
    let shard = parse_shard(&shard_text).map_err(|e| format!("{name}: line 4: {e}"))?;
    if p.head != header.header_row() {
        return Err(format!(
            "{name}: line 6: header '{}' is not '{}'",
            clip(&p.head),
            header.header_row()
        ));
    }
    let names = csv::StringRecord::from(vec![
        "x",
        "y",
        "class",
        "period",
        "table_periods",
        "lyapunov",
        "status",
    ]);
    let mut rows = Vec::new();
    csv_rows(name, &body, &names, |row: PixelRow| {
        row.check()?;
        rows.push(row);
        Ok(())
    })?;
    let sum = fnv1a(FNV_START, body.as_bytes());
    let want_end = format!("# end {} pixels, checksum {sum:016x}", rows.len());
    if end != want_end {
        return Err(format!(
            "{name}: truncated or damaged: its last line is '{}', expected '{want_end}'",
            clip(&end)
        ));
    }
    Ok(PlanePart {
        name: name.to_string(),
        layout: Layout::Csv,
        provenance: PlaneProvenance {
            file: "plane".into(),
            tool,
            spec_hash: hash,
            shard: shard_text,
            pixels,
        },
        header,
        shard,
        curves: "null".into(),
        rows,
    })
}

/// The pixel index of row `k` of a file holding `shard` (None: every pixel).
fn row_pixel(shard: Option<Shard>, k: usize) -> usize {
    match shard {
        Some(s) => s.index + k * s.count,
        None => k,
    }
}

fn check_rows(part: &PlanePart) -> Result<(), String> {
    let h = &part.header;
    let total = h.len();
    let expected = match part.shard {
        Some(s) => total / s.count + usize::from(s.index < total % s.count),
        None => total,
    };
    for (k, r) in part.rows.iter().enumerate() {
        r.check().map_err(|e| format!("pixel row {}: {e}", k + 1))?;
        let p = row_pixel(part.shard, k);
        if p >= total {
            return Err(format!("holds more than its shard's {expected} pixels"));
        }
        let (x, y) = h.values(p);
        if r.x.to_bits() != x.to_bits() || r.y.to_bits() != y.to_bits() {
            return Err(format!(
                "pixel row {} is at ({}, {}), but its place means pixel {p} at ({x}, {y})",
                k + 1,
                r.x,
                r.y
            ));
        }
    }
    if part.rows.len() != part.provenance.pixels || part.rows.len() != expected {
        return Err(format!(
            "holds {} pixels; its provenance says {} and its shard has {expected}",
            part.rows.len(),
            part.provenance.pixels
        ));
    }
    Ok(())
}

/// Join checked parts of one plane: the same tool, specification, layout and curves,
/// every shard of 1..N exactly once. Returns the layout, header, curves and every pixel
/// in index order.
pub fn join(parts: Vec<PlanePart>) -> Result<(Layout, PlaneHeader, String, Vec<PixelRow>), String> {
    let first = parts.first().ok_or("no parts given")?;
    let (layout, header, curves) = (first.layout, first.header.clone(), first.curves.clone());
    let count = first.shard.map_or(1, |s| s.count);
    let mut slots: Vec<Option<usize>> = vec![None; count];
    for (n, p) in parts.iter().enumerate() {
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
                "{}: a part of another plane ({} differs from {}'s): valid parts of one plane",
                p.name,
                differing_setting(&p.header, &header),
                first.name
            ));
        }
        if p.curves != curves {
            return Err(format!(
                "{}: its curves differ from {}'s",
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
    let mut iters: Vec<_> = Vec::with_capacity(count);
    let mut parts = parts;
    let order: Vec<usize> = slots.into_iter().map(|s| s.unwrap_or(0)).collect();
    let mut taken: Vec<Option<Vec<PixelRow>>> = parts
        .iter_mut()
        .map(|p| Some(std::mem::take(&mut p.rows)))
        .collect();
    for n in order {
        iters.push(taken[n].take().unwrap_or_default().into_iter());
    }
    let rows: Vec<PixelRow> = (0..header.len())
        .filter_map(|p| iters[p % count].next())
        .collect();
    if rows.len() != header.len() {
        return Err(format!(
            "the parts hold {} of the plane's {} pixels",
            rows.len(),
            header.len()
        ));
    }
    Ok((layout, header, curves, rows))
}

pub fn differing_setting(a: &PlaneHeader, b: &PlaneHeader) -> String {
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

/// The rows of a computed plane's shard, in index order, made one by one.
pub fn rows<'a>(
    spec: &'a PlaneSpec,
    pixels: &'a [Option<Pixel>],
) -> impl Iterator<Item = PixelRow> + 'a {
    (0..spec.len()).filter(|&p| spec.holds(p)).map(move |p| {
        let (x, y) = spec.values(p);
        match &pixels[p] {
            Some(px) => PixelRow::new(x, y, px),
            None => PixelRow {
                x,
                y,
                class: NO_LANDING.into(),
                period: None,
                table_periods: None,
                lyapunov: Exponent(None),
                status: Outcome::NoLanding {
                    period: 0,
                    phase: 0.0,
                }
                .as_str()
                .into(),
            },
        }
    })
}
