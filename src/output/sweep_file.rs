//! The sweep file: what `sweep` writes (csv or json), what `merge` reads back, checks
//! and joins, in the part-file format of [`super::part_file`] (provenance, shard, end
//! line and checksum are there). Here: the sweep's rows and values, and what is
//! particular to a sweep: a value is one or more csv rows (one per recorded point) or
//! one json object, and belongs to a shard by its index
//! ([`Shard::holds`](bouncemap_engine::jobs::grid::Shard::holds)).
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
//! A json file has the provenance, the settings, `values` and the checksum of the
//! `values` array. Values are written in index order as they complete
//! ([`SweepWriter`]), so memory is bounded by the values in flight, not by the run.

pub use super::part_file::Layout;
use super::part_file::{clip, shard_name, FileKind, PartWriter};
use super::records::{PointRecord, SweepColumns, SweepHeader, SweepRow, SweepValue};
use bouncemap_engine::jobs::grid::{grid_value, Shard};
use bouncemap_engine::sweep::{chain_len, ValueResult, Warm};
use std::io::{self, Write};

/// The sweep file as a kind of part file.
#[derive(Clone, Copy, Debug)]
pub struct SweepFile;

impl FileKind for SweepFile {
    const KIND: &'static str = "sweep";
    const UNIT: &'static str = "values";
    const PROVENANCE: &'static [&'static str] = &["tool", "spec_hash", "shard", "values"];
    const SECTIONS: &'static [&'static str] = &["values"];
    type Header = SweepHeader;
    type Row = SweepRow;
    type Item = SweepValue;
    type Value = PartValue;

    fn header_row(h: &SweepHeader) -> String {
        let mut names: Vec<&str> = SweepFile::field_names(h);
        names[1] = &h.param;
        names.join(",")
    }

    fn field_names(h: &SweepHeader) -> Vec<&'static str> {
        SweepRow::field_names(SweepColumns::of(h))
    }

    /// A value's rows are consecutive: a row of the last value's index joins it.
    fn add_row(values: &mut Vec<PartValue>, row: SweepRow) -> Result<(), String> {
        match values.last_mut() {
            Some(PartValue::Csv { index, rows }) if *index == row.index => rows.push(row),
            _ => values.push(PartValue::Csv {
                index: row.index,
                rows: vec![row],
            }),
        }
        Ok(())
    }

    fn from_item(v: SweepValue) -> PartValue {
        PartValue::Json(v)
    }

    fn write_value<W: Write>(w: &mut PartWriter<W, SweepFile>, v: &PartValue) -> io::Result<()> {
        match v {
            PartValue::Csv { rows, .. } => w.csv(rows),
            PartValue::Json(v) => w.json(v),
        }
    }

    fn end_counts(values: usize, rows: usize) -> String {
        format!("{values} values, {rows} rows")
    }

    type Checker = SweepCheck;

    fn checker(h: &SweepHeader, shard: Option<Shard>) -> Result<SweepCheck, String> {
        let warm = Warm::from_name(&h.start).ok_or_else(|| {
            format!(
                "start '{}' is not cold, warm or warm-backward",
                clip(&h.start)
            )
        })?;
        let chain = chain_len(warm);
        Ok(SweepCheck {
            lo: h.lo,
            hi: h.hi,
            steps: h.steps,
            keep: h.keep.saturating_mul(h.starts.max(1)),
            shard,
            chain,
            expected: match shard {
                Some(s) => s.items_of(h.steps, chain),
                None => h.steps,
            },
            prev: None,
        })
    }

    fn check(c: &mut SweepCheck, v: &PartValue) -> Result<(), String> {
        c.value(v)
    }

    fn expected(c: &SweepCheck) -> usize {
        c.expected
    }

    fn stated_index(v: &PartValue) -> Option<usize> {
        Some(v.index())
    }

    fn row_index(row: &SweepRow) -> Option<usize> {
        Some(row.index)
    }

    /// A value states its index.
    fn place(_: Option<Shard>, k: usize, stated: Option<usize>) -> usize {
        stated.unwrap_or(k)
    }

    /// Checked parts hold values of their own shards, each once.
    fn complete(h: &SweepHeader, counts: &[usize]) -> Result<(), String> {
        let held: usize = counts.iter().sum();
        if held != h.steps {
            return Err(format!(
                "the parts hold {held} of the sweep's {} values",
                h.steps
            ));
        }
        Ok(())
    }
}

/// Writes one sweep file, value by value in index order.
pub struct SweepWriter<W: Write> {
    part: PartWriter<W, SweepFile>,
    /// The optional columns.
    columns: SweepColumns,
}

impl<W: Write> SweepWriter<W> {
    /// Write the provenance and the settings; `values` is how many values will follow.
    pub fn begin(
        out: W,
        layout: Layout,
        header: &SweepHeader,
        shard: &str,
        values: usize,
    ) -> io::Result<SweepWriter<W>> {
        Ok(SweepWriter {
            part: PartWriter::begin(out, layout, header, shard, values, &[])?,
            columns: SweepColumns::of(header),
        })
    }

    /// One value, written as it is made (a row or a point at a time: a value of a
    /// million points is never copied whole).
    pub fn value(&mut self, r: &ValueResult) -> io::Result<()> {
        match self.part.layout() {
            Layout::Csv => {
                let mut first = true;
                SweepRow::each(r, self.columns, |row| {
                    self.part.csv_row(&row, std::mem::take(&mut first))
                })
            }
            Layout::Json => self.part.json_value(&SweepValue::new(r, self.columns)),
        }
    }

    /// One value's csv rows.
    pub fn rows(&mut self, rows: &[SweepRow]) -> io::Result<()> {
        self.part.csv(rows)
    }

    /// One value's json object.
    pub fn json(&mut self, v: &SweepValue) -> io::Result<()> {
        self.part.json(v)
    }

    /// Close the file (csv: the end line) and hand back the writer.
    pub fn end(self) -> io::Result<W> {
        self.part.end()
    }
}

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

/// The checks on a part's values, one at a time: in index order, each once, inside its
/// shard, at the value its index means, well-formed.
pub struct SweepCheck {
    lo: f64,
    hi: f64,
    steps: usize,
    /// Points a value may have: keep × starts.
    keep: usize,
    shard: Option<Shard>,
    chain: usize,
    /// Values the shard has.
    expected: usize,
    /// The index of the value before.
    prev: Option<usize>,
}

impl SweepCheck {
    fn value(&mut self, v: &PartValue) -> Result<(), String> {
        let i = v.index();
        if i >= self.steps {
            return Err(format!(
                "value {i} is outside the sweep's {} values",
                self.steps
            ));
        }
        if self.prev.is_some_and(|p| i <= p) {
            return Err(format!("value {i} is out of order or repeated"));
        }
        self.prev = Some(i);
        if let Some(s) = self.shard {
            if !s.holds(i, self.chain) {
                return Err(format!(
                    "value {i} does not belong to shard {}",
                    shard_name(s)
                ));
            }
        }
        let want = grid_value(self.lo, self.hi, self.steps, i);
        check_value(v, want, self.keep).map_err(|e| format!("value {i}: {e}"))
    }
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
                    != (a0.period, a0.table_periods, a0.status, a0.sticking)
                    || r.value.to_bits() != r0.value.to_bits()
                    || r.lyapunov.is_some() != r0.lyapunov.is_some()
                    || r.attractor.is_some() != r0.attractor.is_some()
                    || (&r.digits_verdict, r.digits_periods, &r.stick_after)
                        != (&a0.digits_verdict, a0.digits_periods, &a0.stick_after)
                {
                    return Err("its rows disagree on the value's outcome".into());
                }
                r.check_cycle()?;
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
            let cycles = s.attractors.iter().filter_map(|a| a.cycle.as_ref());
            for c in s.cycle.as_deref().into_iter().chain(cycles) {
                c.check()?;
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
