//! The plane file: what `plane` writes (csv or json), what `merge` reads back, checks
//! and joins, in the part-file format of [`super::part_file`] (provenance, shard, end
//! line and checksum are there). Here: the plane's settings and rows, and what is
//! particular to a plane: one row per pixel, and where each row belongs.
//!
//! ```text
//! # bouncemap 0.1.0 plane
//! # spec {"table":"fd:0.1","x":{"param":"alpha",...},"y":{...},...}
//! # spec-hash 3f0c9a1d2b7e4c55
//! # shard 2/4
//! # pixels 20000
//! alpha,d,class,period,table_periods,lyapunov,status,resolved,growth_decades
//! ...
//! # end 20000 pixels, checksum 9a4f0c2e71b3d855
//! ```
//!
//! Rows are the shard's pixels in index order (index j·W + i, row j = 0 at y = lo):
//! shard I/N holds the pixels whose index is I − 1 modulo N, so its k-th row is pixel
//! I − 1 + kN and a reader knows which pixel every row must be. A json file has the
//! provenance (with `"file": "plane"`), the settings, `curves` (the analytic curves,
//! null without an α axis), `pixels` and the checksum of the curves' and pixels' bytes.

use super::classes::{of_pixel, Class, NO_LANDING};
use super::part_file::{clip, FileKind, Layout, PartWriter};
use super::records::{
    check_verdict, present, solver_name, CycleRecord, DigitsRecord, EarlyStop, Exponent,
};
use bouncemap_engine::jobs::grid::grid_value;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::plane::{Curves, Pixel, PlaneSpec};
use bouncemap_engine::run::Outcome;
use bouncemap_engine::CycleSummary;
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
    /// `--digits`: sticking cycles beyond double precision decided at any precision
    /// (absent without).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub digits: Option<DigitsRecord>,
}

impl From<&PlaneSpec> for PlaneHeader {
    fn from(s: &PlaneSpec) -> PlaneHeader {
        let on_axis = |name: &str| s.x.param.as_str() == name || s.y.param.as_str() == name;
        let axis = |a: &bouncemap_engine::jobs::grid::Axis| AxisRecord {
            param: a.param.as_str().to_string(),
            lo: a.lo,
            hi: a.hi,
            n: a.n,
        };
        PlaneHeader {
            // A family's parameter on an axis is left free in the table's name.
            table: super::text::table_with_free(&s.table, &[s.x.param, s.y.param]),
            x: axis(&s.x),
            y: axis(&s.y),
            alpha: (!on_axis("alpha")).then_some(s.alpha),
            r: (!on_axis("r")).then_some(s.r),
            d: if on_axis("D") { None } else { s.table.d() },
            transient: s.transient,
            start: s.start.as_str().to_string(),
            solver: solver_name(s.solver).to_string(),
            early_stop: s.periodicity.map(|p| EarlyStop {
                max_period: p.max_period,
                tolerance: p.tolerance,
            }),
            lyapunov: s.lyapunov,
            digits: s.digits.map(|a| DigitsRecord::of(a, &s.written)),
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
        let mut names = PlaneFile::field_names(self);
        let (x, y) = (self.x.param.as_str(), self.y.param.as_str());
        names[0] = x;
        names[1] = y;
        names.join(",")
    }
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
    /// For a periodic pixel: whether double precision decides its cycle (false: a
    /// sticking cycle whose length rounding decides; `period` and `table_periods` are
    /// then empty, and the class is `sticking-unresolved`).
    pub resolved: Option<bool>,
    /// For a sticking cycle: log₁₀ of the largest growth of a perturbation from a
    /// release to the next stick.
    pub growth_decades: Option<f64>,
    /// With `--digits` ([`PLANE_CYCLE_COLUMNS`]): the sticking cycle decided at any
    /// precision where double precision does not resolve it (empty elsewhere). None: no
    /// such columns.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub digits_verdict: Option<Option<String>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub digits_periods: Option<Option<i64>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub agreed_digits: Option<Option<u32>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub need_digits: Option<Option<u32>>,
}

/// The `--digits` columns of a plane (a sweep's without the stick time: a picture
/// keeps each pixel's verdict, not its numbers of any precision).
pub const PLANE_CYCLE_COLUMNS: [&str; 4] = [
    "digits_verdict",
    "digits_periods",
    "agreed_digits",
    "need_digits",
];

const STATUSES: [&str; 4] = ["periodic", "unsettled", "resting", "no-landing"];

impl PixelRow {
    /// The row of a computed pixel at (x, y), with the `--digits` columns when asked.
    pub fn new(x: f64, y: f64, p: &Pixel, digits: bool) -> PixelRow {
        let resolved = p.precision.map(|p| p.resolved);
        let claimed = resolved != Some(false);
        let row = PixelRow {
            x,
            y,
            class: of_pixel(p).map_or(NO_LANDING, Class::name).to_string(),
            period: p.outcome.period().filter(|_| claimed),
            table_periods: p.outcome.table_periods().filter(|_| claimed),
            lyapunov: Exponent(p.lyapunov),
            status: p.outcome.as_str().to_string(),
            resolved,
            growth_decades: p
                .precision
                .filter(|p| p.impacts > 0)
                .map(|p| p.growth_decades),
            ..PixelRow::empty(x, y)
        };
        match digits {
            true => row.with_cycle(p.cycle),
            false => row,
        }
    }

    /// A row at (x, y) with nothing in it but its place (no `--digits` columns).
    fn empty(x: f64, y: f64) -> PixelRow {
        PixelRow {
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
            resolved: None,
            growth_decades: None,
            digits_verdict: None,
            digits_periods: None,
            agreed_digits: None,
            need_digits: None,
        }
    }

    /// This row with the `--digits` columns of `cycle` (empty cells where None).
    fn with_cycle(mut self, cycle: Option<CycleSummary>) -> PixelRow {
        let c = cycle.map(CycleRecord::of_summary);
        let c = c.as_ref();
        self.digits_verdict = Some(c.map(|c| c.verdict.clone()));
        self.digits_periods = Some(c.and_then(|c| c.periods));
        self.agreed_digits = Some(c.and_then(|c| c.agreed_digits));
        self.need_digits = Some(c.and_then(|c| c.need_digits));
        self
    }

    fn check(&self) -> Result<(), String> {
        if Class::from_name(&self.class).is_none() && self.class != NO_LANDING {
            let names: Vec<&str> = Class::ALL
                .iter()
                .map(|c| c.name())
                .chain([NO_LANDING])
                .collect();
            return Err(format!(
                "class '{}' is not one of {}",
                clip(&self.class),
                names.join(", ")
            ));
        }
        if !STATUSES.contains(&self.status.as_str()) {
            return Err(format!(
                "status '{}' is not periodic, unsettled, resting or no-landing",
                clip(&self.status)
            ));
        }
        let cycle = self.status == "periodic";
        if cycle != self.resolved.is_some() {
            return Err("resolved must be given exactly for periodic pixels".into());
        }
        let claimed = cycle && self.resolved == Some(true);
        if claimed != self.period.is_some() || claimed != self.table_periods.is_some() {
            return Err(
                "period and table_periods must be given exactly for periodic pixels whose cycle is resolved".into(),
            );
        }
        if self.growth_decades.is_some_and(|g| !g.is_finite()) {
            return Err("growth_decades is not a finite number".into());
        }
        if self.lyapunov.0.is_some_and(f64::is_nan) {
            return Err("lyapunov is not a number".into());
        }
        match &self.digits_verdict {
            Some(Some(v)) => check_verdict(v, &[self.digits_periods.flatten().is_some()]),
            _ if self.digits_periods.flatten().is_some() => {
                Err("digits_periods without a digits_verdict".into())
            }
            _ => Ok(()),
        }
    }
}

/// The curves as json states them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurvesRecord<'a> {
    /// `x` or `y`: the axis the α values refer to.
    pub alpha_axis: &'static str,
    /// The other axis's parameter and its pixel values.
    pub along: &'a str,
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

/// The plane file as a kind of part file.
#[derive(Clone, Copy, Debug)]
pub struct PlaneFile;

impl FileKind for PlaneFile {
    const KIND: &'static str = "plane";
    const UNIT: &'static str = "pixels";
    const PROVENANCE: &'static [&'static str] = &["file", "tool", "spec_hash", "shard", "pixels"];
    const SECTIONS: &'static [&'static str] = &["curves", "pixels"];
    type Header = PlaneHeader;
    type Row = PixelRow;
    type Item = PixelRow;
    type Value = PixelRow;

    fn header_row(h: &PlaneHeader) -> String {
        h.header_row()
    }

    /// The columns named after the axes' parameters are read as `x` and `y`.
    fn field_names(h: &PlaneHeader) -> Vec<&'static str> {
        let mut names = vec![
            "x",
            "y",
            "class",
            "period",
            "table_periods",
            "lyapunov",
            "status",
            "resolved",
            "growth_decades",
        ];
        if h.digits.is_some() {
            names.extend(PLANE_CYCLE_COLUMNS);
        }
        names
    }

    fn add_row(rows: &mut Vec<PixelRow>, row: PixelRow) -> Result<(), String> {
        row.check()?;
        rows.push(row);
        Ok(())
    }

    fn from_item(row: PixelRow) -> PixelRow {
        row
    }

    fn write_value<W: Write>(w: &mut PartWriter<W, PlaneFile>, row: &PixelRow) -> io::Result<()> {
        match w.layout() {
            Layout::Csv => w.csv(std::slice::from_ref(row)),
            Layout::Json => w.json(row),
        }
    }

    fn end_counts(pixels: usize, _rows: usize) -> String {
        format!("{pixels} pixels")
    }

    type Checker = PlaneCheck;

    fn checker(h: &PlaneHeader, shard: Option<Shard>) -> Result<PlaneCheck, String> {
        let total = h.len();
        Ok(PlaneCheck {
            header: h.clone(),
            shard,
            total,
            expected: match shard {
                Some(s) => total / s.count + usize::from(s.index < total % s.count),
                None => total,
            },
            k: 0,
        })
    }

    fn check(c: &mut PlaneCheck, r: &PixelRow) -> Result<(), String> {
        c.row(r)
    }

    fn expected(c: &PlaneCheck) -> usize {
        c.expected
    }

    fn stated_index(_: &PixelRow) -> Option<usize> {
        None
    }

    fn row_index(_: &PixelRow) -> Option<usize> {
        None
    }

    /// Shard I/N holds the pixels I − 1 modulo N: its row k is pixel I − 1 + kN.
    fn place(shard: Option<Shard>, k: usize, _: Option<usize>) -> usize {
        row_pixel(shard, k)
    }

    /// Pixel p is the next row of shard p mod N.
    fn complete(h: &PlaneHeader, counts: &[usize]) -> Result<(), String> {
        let n = counts.len().max(1);
        let len = h.len();
        let held: usize = counts
            .iter()
            .enumerate()
            .map(|(s, &c)| c.min(len / n + usize::from(s < len % n)))
            .sum();
        if held != len {
            return Err(format!("the parts hold {held} of the plane's {len} pixels"));
        }
        Ok(())
    }
}

/// Whether `text` is a plane file (rather than a sweep file).
pub fn is_plane(text: &str) -> bool {
    let head: String = text.chars().take(400).collect();
    let first = head.lines().next().unwrap_or("");
    (first.starts_with("# bouncemap ") && first.ends_with(" plane"))
        || (head.trim_start().starts_with('{') && head.contains("\"file\":\"plane\""))
}

/// The pixel index of row `k` of a file holding `shard` (None: every pixel).
fn row_pixel(shard: Option<Shard>, k: usize) -> usize {
    match shard {
        Some(s) => s.index + k * s.count,
        None => k,
    }
}

/// The checks on a part's rows, one at a time: each well-formed and at the pixel its
/// place in the shard means.
pub struct PlaneCheck {
    header: PlaneHeader,
    shard: Option<Shard>,
    total: usize,
    /// Pixels the shard has.
    expected: usize,
    /// Rows checked.
    k: usize,
}

impl PlaneCheck {
    fn row(&mut self, r: &PixelRow) -> Result<(), String> {
        let k = self.k;
        self.k += 1;
        r.check().map_err(|e| format!("pixel row {}: {e}", k + 1))?;
        let p = row_pixel(self.shard, k);
        if p >= self.total {
            return Err(format!(
                "holds more than its shard's {} pixels",
                self.expected
            ));
        }
        let (x, y) = self.header.values(p);
        if r.x.to_bits() != x.to_bits() || r.y.to_bits() != y.to_bits() {
            return Err(format!(
                "pixel row {} is at ({}, {}), but its place means pixel {p} at ({x}, {y})",
                k + 1,
                r.x,
                r.y
            ));
        }
        Ok(())
    }
}

/// The rows of a computed plane's shard, in index order, made one by one.
pub fn rows<'a>(
    spec: &'a PlaneSpec,
    pixels: &'a [Option<Pixel>],
) -> impl Iterator<Item = PixelRow> + 'a {
    let digits = spec.digits.is_some();
    (0..spec.len()).filter(|&p| spec.holds(p)).map(move |p| {
        let (x, y) = spec.values(p);
        match &pixels[p] {
            Some(px) => PixelRow::new(x, y, px, digits),
            None if digits => PixelRow::empty(x, y).with_cycle(None),
            None => PixelRow::empty(x, y),
        }
    })
}
