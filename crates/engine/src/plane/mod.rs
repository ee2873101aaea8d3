//! Two-parameter maps: every pixel of a W × H grid over two of α, r and D (D for the
//! F_D family) is one system, run from its start to the end of the transient (early stop
//! on cycles, as sweeps do) and summarised by what its orbit does, as a [`Job`](crate::jobs::Job).
//!
//! A [`PlaneSpec`] names the table, the two axes ([`Axis`]: the parameter, its window
//! and its number of pixels), the fixed parameter(s), the start ([`PlaneStart`]), the
//! transient, the early stop, whether the largest Lyapunov exponent is measured, and the
//! shard. Pixel (i, j) is at x = value i of the x axis and y = value j of the y axis
//! (both ends exact, as sweep values), its index is j·W + i; row j = 0 is the bottom
//! (y = lo).
//!
//! Each pixel keeps a [`Pixel`]: its outcome (cycle length n and table periods k,
//! unsettled, resting, no landing), whether its last events include a stick or a
//! release, and the largest exponent. Nothing else of the orbit is kept, so a plane's
//! memory is a few dozen bytes per pixel.
//!
//! # Coarse to fine
//! The plane is a [picture](crate::jobs::picture): four passes, the pixels whose i and j are
//! multiples of 8, then of 4, of 2, and the rest, in chunks of [`CHUNK`] pixels handed
//! out spread over the pass. A viewer draws every pixel from the nearest coarser one
//! computed so far ([`Plane::preview`]) and so has a complete rough picture after the
//! first pass (1/64 of the work).
//!
//! # Shards
//! Shard I/N holds the pixels whose index is I − 1 modulo N: every shard covers the whole
//! plane, so shards take about equally long.

mod curves;
mod job;

pub use curves::{curves, Curves};
pub use job::{collect, Plane, PlaneCells, PlaneChunk, PlaneJob};

use crate::error::EngineError;
use crate::impact::Solver;
use crate::jobs::grid::Axis;
use crate::jobs::grid::{Shard, SweepParam};
use crate::limits;
use crate::map::State;
use crate::precise::{CycleSummary, DigitsAsk};
use crate::run::detect::Periodicity;
use crate::run::precision::Precision;
use crate::run::start::near_fixed_point;
use crate::run::Outcome;
use crate::system::System;
use crate::table::Table;

/// Pixels per work item.
pub const CHUNK: usize = 16;
pub use crate::jobs::picture::STRIDES;
use crate::jobs::picture::{MAX_CELLS, MAX_SIDE};
/// The default size.
pub const DEFAULT_SIZE: (usize, usize) = (400, 200);
/// Default end of the transient, in table periods.
pub const DEFAULT_TRANSIENT: u64 = 20_000;
/// Events kept per pixel while it runs (a stick or release among them marks sticking).
pub const KEEP: usize = 64;
/// Impacts over which an unsettled pixel's exponent is measured (QR).
pub const LYAPUNOV_SAMPLE: u64 = 2_000;

/// Where each pixel's orbit starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PlaneStart {
    /// Next to the (1, 1) solution (phase t̂* + 10⁻³, v = ½) where it exists, as the
    /// paper's figures and the presets start, else the cold start.
    #[default]
    NearFixedPoint,
    /// The default hop: t̂0 = 0, v0 = f'(0) + ½, on the table.
    Cold,
}

impl PlaneStart {
    /// Every start, in output order.
    pub const ALL: [PlaneStart; 2] = [PlaneStart::NearFixedPoint, PlaneStart::Cold];

    /// Name in outputs: `near-fixed-point`, `cold`.
    pub fn as_str(self) -> &'static str {
        match self {
            PlaneStart::NearFixedPoint => "near-fixed-point",
            PlaneStart::Cold => "cold",
        }
    }

    /// The start named `name` (as [`Self::as_str`] writes it).
    pub fn from_name(name: &str) -> Option<PlaneStart> {
        PlaneStart::ALL.into_iter().find(|s| s.as_str() == name)
    }
}

/// Everything that defines a plane.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneSpec {
    /// The table (with a D axis, an F_D table whose D is replaced by each pixel's).
    pub table: Table,
    /// The horizontal axis.
    pub x: Axis,
    /// The vertical axis.
    pub y: Axis,
    /// α and r where they are not on an axis.
    pub alpha: f64,
    /// r where it is not on an axis.
    pub r: f64,
    /// Where each pixel's orbit starts.
    pub start: PlaneStart,
    /// End of the transient, in table periods.
    pub transient: u64,
    /// Early stop on detected cycles; None runs every pixel to the end.
    pub periodicity: Option<Periodicity>,
    /// Measure the largest exponent of every pixel (cycles: exact; otherwise QR over
    /// [`LYAPUNOV_SAMPLE`] impacts).
    pub lyapunov: bool,
    /// The next-contact solver.
    pub solver: Solver,
    /// The part of the pixels this plane computes.
    pub shard: Shard,
    /// Decide at any precision the sticking cycles whose length double precision cannot
    /// ([`Pixel::cycle`]); None: not asked.
    pub digits: Option<DigitsAsk>,
    /// With `digits`: the parameters and the windows as typed, read with every digit
    /// ([`crate::Written`]; empty: each double's shortest decimal).
    pub written: crate::precise::Written,
}

impl PlaneSpec {
    /// The (α, D) or (α, r) plane over the given windows with the defaults: start near
    /// the fixed point, transient [`DEFAULT_TRANSIENT`], early stop, exponents.
    pub fn new(table: Table, x: Axis, y: Axis, alpha: f64, r: f64) -> PlaneSpec {
        PlaneSpec {
            table,
            x,
            y,
            alpha,
            r,
            start: PlaneStart::NearFixedPoint,
            transient: DEFAULT_TRANSIENT,
            periodicity: Some(Periodicity::default()),
            lyapunov: true,
            solver: Solver::Exact,
            shard: Shard::WHOLE,
            digits: None,
            written: crate::precise::Written::default(),
        }
    }

    /// Pixels in the plane (all shards).
    pub fn len(&self) -> usize {
        self.x.n * self.y.n
    }

    /// Whether the plane has no pixel (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// (i, j) of pixel `index`.
    pub fn pixel(&self, index: usize) -> (usize, usize) {
        (index % self.x.n, index / self.x.n)
    }

    /// (x, y) of pixel `index`.
    pub fn values(&self, index: usize) -> (f64, f64) {
        let (i, j) = self.pixel(index);
        (self.x.value(i), self.y.value(j))
    }

    /// Whether pixel `index` belongs to this spec's shard.
    pub fn holds(&self, index: usize) -> bool {
        self.shard.holds(index, 1)
    }

    /// Pixels in this spec's shard.
    pub fn shard_len(&self) -> usize {
        self.shard.items_of(self.len(), 1)
    }

    /// The value of `param` at (x, y).
    fn param_at(&self, param: SweepParam, x: f64, y: f64) -> Option<f64> {
        if self.x.param == param {
            Some(x)
        } else if self.y.param == param {
            Some(y)
        } else {
            None
        }
    }

    /// The system at (x, y).
    pub fn system_at(&self, x: f64, y: f64) -> Result<System, EngineError> {
        let alpha = self.param_at(SweepParam::Alpha, x, y).unwrap_or(self.alpha);
        let r = self.param_at(SweepParam::R, x, y).unwrap_or(self.r);
        let mut table = self.table.clone();
        for (axis, v) in [(self.x.param, x), (self.y.param, y)] {
            if axis.is_table() {
                table = axis.table(&table, v)?;
            }
        }
        System::new(table, alpha, r)
    }

    /// The start of a pixel's orbit on `sys`.
    pub fn initial_state(&self, sys: &System) -> Result<State, EngineError> {
        if self.start == PlaneStart::NearFixedPoint {
            if let Some(s) = near_fixed_point(sys) {
                return Ok(s);
            }
        }
        State::start(sys, 0.0, None, 0.0)
    }

    /// Check every setting; the message names the setting, the value and the range.
    pub fn validate(&self) -> Result<(), EngineError> {
        self.x
            .validate(&self.table, MAX_SIDE, "1 ..= 4000 pixels per side")?;
        self.y
            .validate(&self.table, MAX_SIDE, "1 ..= 4000 pixels per side")?;
        if self.x.param == self.y.param {
            return Err(EngineError::Inconsistent(format!(
                "x and y are both {}: valid two different parameters of {}",
                self.x.param.as_str(),
                SweepParam::names(&self.table)
            )));
        }
        if self.len() > MAX_CELLS {
            return Err(EngineError::InvalidParameter {
                name: "size".into(),
                value: format!("{}x{}", self.x.n, self.y.n),
                range: "at most 1000000 pixels".into(),
            });
        }
        let on_axis = |p| self.x.param == p || self.y.param == p;
        if !on_axis(SweepParam::Alpha) {
            limits::ALPHA.check(self.alpha)?;
        }
        if !on_axis(SweepParam::R) {
            limits::R.check(self.r)?;
        }
        limits::TRANSIENT.check(self.transient as f64)?;
        if let Some(p) = self.periodicity {
            p.validate()?;
        }
        self.shard.validate()?;
        if let Some(ask) = self.digits {
            crate::precise::check_digits(ask, &self.table)?;
        }
        // A file's family may stop being C¹ inside a window: every value along an axis
        // of its parameters is checked, in order (built-in families are C¹ over their
        // whole ranges).
        for axis in [&self.x, &self.y] {
            let file_family =
                axis.param.is_table() && self.table.family().is_some_and(|(f, _)| !f.is_builtin());
            if file_family {
                for i in 0..axis.n {
                    axis.param.table(&self.table, axis.value(i))?;
                }
            }
        }
        // Every corner's system (the ranges are checked, so only a table beyond the
        // solver's bounds at the largest α can fail here).
        for (x, y) in [
            (self.x.lo, self.y.lo),
            (self.x.hi, self.y.lo),
            (self.x.lo, self.y.hi),
            (self.x.hi, self.y.hi),
        ] {
            self.system_at(x, y)?;
        }
        Ok(())
    }
}

/// What one pixel's orbit does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pixel {
    /// Periodic (n events in k periods), unsettled, resting or no landing.
    pub outcome: Outcome,
    /// Whether its orbit sticks to the table in what it settled on (see
    /// [`OrbitRun::sticking`](crate::run::OrbitRun::sticking)), or its exponent is −∞.
    pub sticking: bool,
    /// The largest exponent per impact (−∞ sticking or resting); None when not asked or
    /// where there is none (no landing, grazing).
    pub lyapunov: Option<f64>,
    /// For a cycle: whether double precision decides it (a sticking cycle's length may
    /// be decided by rounding).
    pub precision: Option<Precision>,
    /// With [`PlaneSpec::digits`], where double precision does not resolve the cycle:
    /// the cycle decided at any precision from the pixel's start, both axes' values the
    /// decimal grid points of their windows.
    pub cycle: Option<CycleSummary>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(nx: usize, ny: usize) -> PlaneSpec {
        PlaneSpec::new(
            Table::fd(0.1).unwrap(),
            Axis {
                param: SweepParam::Alpha,
                lo: 0.45,
                hi: 0.6,
                n: nx,
            },
            Axis {
                param: SweepParam::D,
                lo: 0.0,
                hi: 1.0,
                n: ny,
            },
            0.45,
            0.8,
        )
    }

    #[test]
    fn shards_partition_the_pixels() {
        let mut s = spec(7, 5);
        let mut seen = vec![0; s.len()];
        for index in 0..3 {
            s.shard = Shard { index, count: 3 };
            let held: Vec<usize> = (0..s.len()).filter(|&p| s.holds(p)).collect();
            assert_eq!(held.len(), s.shard_len());
            for p in held {
                seen[p] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
    }

    #[test]
    fn refusals_name_the_setting() {
        let mut s = spec(10, 10);
        s.y = s.x;
        assert!(s.validate().unwrap_err().to_string().contains("both alpha"));
        let mut s = spec(10, 10);
        s.table = Table::sine();
        let e = s.validate().unwrap_err().to_string();
        assert_eq!(
            e, "table sine has no parameter 'D': its parameters are none",
            "{e}"
        );
        assert!(spec(2000, 2000).validate().is_err());
        assert!(spec(0, 10).validate().is_err());
        let s = spec(10, 10);
        assert_eq!(s.values(s.len() - 1), (0.6, 1.0));
        assert_eq!(s.x.pixel_of(0.6), 9);
        assert_eq!(s.x.pixel_of(0.0), 0);
    }
}
