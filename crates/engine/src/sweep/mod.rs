//! Parameter sweeps: bifurcation diagrams, one client of the [job executor](crate::jobs).
//!
//! A [`SweepSpec`] names the table, the swept parameter ([`SweepParam`]: α, r or D),
//! the window `lo..=hi` with `steps` values, the fixed parameters, the start, the
//! transient (in table periods), how many events to keep, the solver and whether to
//! continue each value from its neighbour. For each value the ball runs until the end
//! of the transient T and the last `keep` events before T are recorded (phase, v, event
//! kind), unless the [periodicity detector](crate::run::detect) proves earlier that the orbit has
//! settled on a cycle of at most `max_period` events to within `tolerance`: then the
//! remaining events are continued cyclically (see [`crate::run`]), which gives the same points,
//! within the tolerance, as the full transient. Orbits that stick and are released at
//! the same phase again repeat exactly, whatever their length in events; they jump ahead
//! by whole cycles to just before T (see [`crate::run`]). Values that never settle run the full
//! transient.
//!
//! Outcomes per value ([`Outcome`](crate::run::Outcome)): periodic (with its cycle), unsettled (ran to T:
//! chaotic, quasi-periodic or a cycle longer than `max_period`), resting (the ball
//! rides on the table forever, [`Halt::Resting`](crate::Halt::Resting)), or
//! no-landing. Stick and release events are recorded like impacts; a value whose points
//! include one is marked [`ValueResult::sticking`].
//!
//! # Progressive passes
//! With a preview ([`SweepJob::preview`], an execution choice, not part of what the
//! sweep computes) every value first runs to `preview` periods from its cold start,
//! in bit-reversed order over the window, so a complete rough diagram arrives early
//! (pass 0, provisional results). Pass 1 then brings every value to the full transient;
//! a cold run simply continues where pass 0 left it, so no work is repeated and the
//! result does not depend on the preview. Results of a later pass replace the earlier
//! ones for the same value index.
//!
//! # Continuation (warm start)
//! With [`Warm::Forward`] (or `Backward`), the window is cut into chains of
//! [`WARM_CHAIN`] consecutive values; along a chain each value starts from the final
//! state of its neighbour below (above), so branches stay continuous and transients are
//! short; forward and backward together show hysteresis. Chains start cold and run in
//! parallel. Chain boundaries depend only on the value indices, so a sharded warm sweep
//! merges into exactly the unsharded one. Cold sweeps (the default) start every value
//! from the same initial state, as the paper does.
//!
//! # Running
//! [`start`] runs a sweep in the background on an [`Executor`] under a [`Control`]
//! (generation and pause, see [`crate::jobs`]); [`collect`] runs one to the end and
//! returns the final result of every value.
//!
//! ```
//! use bouncemap_engine::jobs::{Control, Executor};
//! use bouncemap_engine::jobs::grid::SweepParam;
//! use bouncemap_engine::run::Outcome;
//! use bouncemap_engine::sweep::{self, SweepSpec};
//! use bouncemap_engine::Table;
//!
//! let table = Table::fd(0.1).unwrap();
//! let mut spec = SweepSpec::new(table, 0.45, 0.8, SweepParam::Alpha, 0.45, 0.45, 1);
//! spec.transient = 10_000;
//! let result = sweep::collect(&spec, &Executor::new(1).unwrap()).unwrap();
//! // α = 0.45 is on the stable (1, 1) branch: one event per table period.
//! assert!(matches!(result[0].outcome, Outcome::Periodic { events: 1, periods: 1, .. }));
//!
//! // In the background, results streamed as they come (drained e.g. once per frame);
//! // `control.cancel()` from anywhere stops it.
//! let control = Control::new();
//! let handle = sweep::start(spec, &Executor::new(1).unwrap(), &control).unwrap();
//! let finals = handle.receiver().iter().filter(|b| handle.is_current(b) && b.complete).count();
//! assert_eq!(finals, 1);
//! assert!(!handle.wait().cancelled);
//! ```

mod job;

pub use job::{SweepJob, ValueAttractor, ValueResult};

use crate::attractors::{self, Registry};
use crate::error::EngineError;
use crate::impact::Solver;
use crate::jobs::grid::{grid_value, Shard, SweepParam};
use crate::jobs::{Batch, Control, Executor, Handle};
use crate::limits;
use crate::map::State;
use crate::precise::{check_digits, DigitsAsk};
use crate::run::detect::Periodicity;
use crate::run::start::near_fixed_point;
use crate::run::{OrbitRun, Point};
use crate::system::System;
use crate::table::Table;
use std::mem::size_of;

/// Consecutive values per warm-start chain.
pub const WARM_CHAIN: usize = 32;
/// The paper's transient (Fig. 3): t = 5·10⁶.
pub const PAPER_TRANSIENT: u64 = 5_000_000;
/// The paper's kept bounces per value (Fig. 3).
pub const PAPER_KEEP: usize = 100;
/// Default preview transient of pass 0, in periods.
pub const DEFAULT_PREVIEW: u64 = 1_000;
/// Impacts over which an unsettled value's exponent is measured (QR).
pub const LYAPUNOV_SAMPLE: u64 = 10_000;

/// One streamed result of a sweep.
pub type SweepBatch = Batch<ValueResult>;
/// A sweep running in the background.
pub type SweepHandle = Handle<ValueResult>;

/// Where every cold-started value begins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialSpec {
    /// Initial phase in [0, 1).
    pub t0: f64,
    /// Initial velocity; None means f'(t0) + [`DEFAULT_HOP`](crate::map::DEFAULT_HOP).
    pub v0: Option<f64>,
    /// Initial height above the table.
    pub z0: f64,
    /// Start slightly off the (1, 1) fixed point instead (the paper's procedure):
    /// phase t̂* + [`FIXED_POINT_OFFSET`](crate::run::start::FIXED_POINT_OFFSET), v = ½, where f'(t̂*) = ½(1 − r)/(1 + r) and
    /// f''(t̂*) < 0 (the stable one if there is one). Falls back to t0, v0, z0 where
    /// no (1, 1) solution exists.
    pub near_fixed_point: bool,
}

impl Default for InitialSpec {
    fn default() -> Self {
        InitialSpec {
            t0: 0.0,
            v0: None,
            z0: 0.0,
            near_fixed_point: false,
        }
    }
}

/// Continuation of each value from its neighbour (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Warm {
    /// Every value starts cold (the paper's procedure).
    #[default]
    Off,
    /// Each value starts from the final state of the value below it.
    Forward,
    /// Each value starts from the final state of the value above it.
    Backward,
}

impl Warm {
    /// Every mode, in output order.
    pub const ALL: [Warm; 3] = [Warm::Off, Warm::Forward, Warm::Backward];

    /// Name used in outputs: `cold`, `warm`, `warm-backward`.
    pub fn as_str(self) -> &'static str {
        match self {
            Warm::Off => "cold",
            Warm::Forward => "warm",
            Warm::Backward => "warm-backward",
        }
    }

    /// The mode named `name` (as [`Self::as_str`] writes it).
    pub fn from_name(name: &str) -> Option<Warm> {
        Warm::ALL.into_iter().find(|w| w.as_str() == name)
    }
}

/// Values per chain: one without continuation, [`WARM_CHAIN`] with it.
pub fn chain_len(warm: Warm) -> usize {
    if warm == Warm::Off {
        1
    } else {
        WARM_CHAIN
    }
}

/// Everything that defines a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSpec {
    /// The table (for a D sweep, an F_D table; its D is replaced by each value).
    pub table: Table,
    /// The swept parameter.
    pub param: SweepParam,
    /// Window of the swept parameter, inclusive.
    pub lo: f64,
    /// Last value of the window.
    pub hi: f64,
    /// Number of values, evenly spaced: lo + (hi − lo) i / (steps − 1).
    pub steps: usize,
    /// α when it is not swept.
    pub alpha: f64,
    /// r when it is not swept.
    pub r: f64,
    /// Where every cold-started value begins.
    pub initial: InitialSpec,
    /// End of the transient T, in table periods: points are the last `keep` events
    /// before t = T.
    pub transient: u64,
    /// Events recorded per value.
    pub keep: usize,
    /// The next-contact solver.
    pub solver: Solver,
    /// Start each value from its neighbour's final state (see the module docs).
    pub warm: Warm,
    /// Early stop on detected cycles; None runs every value to T (brute force).
    pub periodicity: Option<Periodicity>,
    /// The part of the values this sweep computes.
    pub shard: Shard,
    /// Measure each value's largest Lyapunov exponent (see [`ValueResult::lyapunov`]).
    pub lyapunov: bool,
    /// Initial conditions per value: the cold start and `starts − 1` more spread over
    /// the box t̂0 ∈ [0, 1), w0 ∈ [0, W] ([`crate::attractors::box_start`]); with more
    /// than one, each value reports its attractors ([`ValueResult::attractors`]).
    pub starts: usize,
    /// W of that box; None: [`crate::attractors::default_w_max`] of each value's system.
    pub w_max: Option<f64>,
    /// Decide at any precision the sticking cycles whose length double precision cannot
    /// ([`ValueResult::cycle`]); None: not asked.
    pub digits: Option<DigitsAsk>,
    /// With `digits`: the parameters and the window as typed, read with every digit
    /// ([`crate::Written`]; empty: each double's shortest decimal).
    pub written: crate::precise::Written,
}

impl SweepSpec {
    /// The most one value's result holds, in bytes: `keep` points for each start (each
    /// may end on an attractor of its own), its attractors and the rest of the result
    /// (the bound of a memory estimate).
    pub fn value_bytes(&self) -> u64 {
        let starts = self.starts.max(1) as u64;
        let attractors = match starts {
            1 => 0,
            n => n * size_of::<ValueAttractor>() as u64,
        };
        self.keep.max(1) as u64 * starts * size_of::<Point>() as u64
            + size_of::<ValueResult>() as u64
            + attractors
    }

    /// The most a worker holds at once while it computes a value, in bytes, besides the
    /// value's result ([`Self::value_bytes`]): the run of a start ([`OrbitRun::bytes`])
    /// and what identifying its attractor takes ([`attractors::identify_bytes`]); with
    /// several starts also each start's points, the points of every attractor found so
    /// far (one per start at most) and the registry's cells ([`Registry::bytes`]); with
    /// `digits`, what deciding a cycle at any precision holds
    /// ([`crate::precise::digits_bytes`]). The bound of a memory estimate.
    pub fn worker_bytes(&self) -> u64 {
        // With `digits`, a cycle decided at any precision after the f64 run.
        let digits = self.digits.map_or(0, crate::precise::digits_bytes);
        let run = OrbitRun::bytes(self.keep, self.periodicity) + digits;
        if self.starts <= 1 {
            // The run's points are the value's.
            let exponent = match self.lyapunov {
                true => attractors::identify_bytes(LYAPUNOV_SAMPLE),
                false => 0,
            };
            return run + exponent;
        }
        let sample = match self.lyapunov {
            true => LYAPUNOV_SAMPLE,
            false => attractors::Settle::BASINS.sample,
        };
        let points = self.keep.max(1) as u64 * size_of::<Point>() as u64;
        let starts = self.starts as u64;
        run + attractors::identify_bytes(sample)
            + (starts + 1) * points
            + Registry::bytes(self.starts, sample)
    }

    /// A sweep of `param` over `lo..=hi` at the paper's fidelity (T = 5·10⁶, keep 100),
    /// cold start, exact solver, early stop with the default [`Periodicity`]; `alpha`
    /// and `r` are used where they are not swept (the swept one's slot is set to `lo`,
    /// so two specs of the same run compare equal).
    pub fn new(
        table: Table,
        alpha: f64,
        r: f64,
        param: SweepParam,
        lo: f64,
        hi: f64,
        steps: usize,
    ) -> SweepSpec {
        let (alpha, r) = match param {
            SweepParam::Alpha => (lo, r),
            SweepParam::R => (alpha, lo),
            SweepParam::Table(_) => (alpha, r),
        };
        SweepSpec {
            table,
            param,
            lo,
            hi,
            steps,
            alpha,
            r,
            initial: InitialSpec::default(),
            transient: PAPER_TRANSIENT,
            keep: PAPER_KEEP,
            solver: Solver::Exact,
            warm: Warm::Off,
            periodicity: Some(Periodicity::default()),
            shard: Shard::WHOLE,
            lyapunov: false,
            starts: 1,
            w_max: None,
            digits: None,
            written: crate::precise::Written::default(),
        }
    }

    /// The value with index `i`.
    pub fn value(&self, i: usize) -> f64 {
        grid_value(self.lo, self.hi, self.steps, i)
    }

    /// The system at a value of the swept parameter.
    pub fn system_at(&self, value: f64) -> Result<System, EngineError> {
        self.param.system(&self.table, self.alpha, self.r, value)
    }

    /// The cold initial state for a system of this sweep.
    pub fn initial_state(&self, sys: &System) -> Result<State, EngineError> {
        let i = self.initial;
        if i.near_fixed_point {
            if let Some(s) = near_fixed_point(sys) {
                return Ok(s);
            }
        }
        State::start(sys, i.t0, i.v0, i.z0)
    }

    /// Value indices of this sweep's shard, in chains of consecutive indices (one value
    /// per chain without continuation), each in the order it is run.
    pub fn chains(&self) -> Vec<Vec<usize>> {
        let len = chain_len(self.warm);
        (0..self.steps.div_ceil(len))
            .filter(|c| c % self.shard.count == self.shard.index)
            .map(|c| {
                let chain = c * len..((c + 1) * len).min(self.steps);
                if self.warm == Warm::Backward {
                    chain.rev().collect()
                } else {
                    chain.collect()
                }
            })
            .collect()
    }

    /// Values in this sweep's shard.
    pub fn shard_values(&self) -> usize {
        self.shard.items_of(self.steps, chain_len(self.warm))
    }

    /// Check every setting; the message names the setting, the value and the range.
    pub fn validate(&self) -> Result<(), EngineError> {
        limits::STEPS.check(self.steps as f64)?;
        crate::jobs::grid::check_window(self.param, &self.table, self.lo, self.hi)?;
        limits::TRANSIENT.check(self.transient as f64)?;
        limits::KEEP.check(self.keep as f64)?;
        if let Some(p) = self.periodicity {
            p.validate()?;
        }
        limits::STARTS.check(self.starts as f64)?;
        if self.starts > 1 && self.warm != Warm::Off {
            return Err(EngineError::Inconsistent(format!(
                "starts = {} needs cold starts: continuation follows one orbit from value to value, several starts look for every attractor at each value",
                self.starts
            )));
        }
        if let Some(w) = self.w_max {
            limits::W_MAX.check(w)?;
        }
        if let Some(ask) = self.digits {
            check_digits(ask, &self.table)?;
        }
        self.shard.validate()?;
        match self.param {
            SweepParam::Alpha => {
                limits::R.check(self.r)?;
            }
            SweepParam::R => {
                limits::ALPHA.check(self.alpha)?;
            }
            SweepParam::Table(_) => {
                limits::ALPHA.check(self.alpha)?;
                limits::R.check(self.r)?;
            }
        }
        // f'(t0) is affine in α and in a built-in family's parameter (F_D is affine in
        // D) and does not depend on r, so checking the window's ends checks every
        // value's initial state; a file's family is checked at every value (its table
        // may stop being C¹ inside the window), refused at the first that fails.
        let every =
            self.param.is_table() && self.table.family().is_some_and(|(f, _)| !f.is_builtin());
        let ends = [0, self.steps.saturating_sub(1)];
        let indices: Box<dyn Iterator<Item = usize>> = if every {
            Box::new(0..self.steps)
        } else {
            Box::new(ends.into_iter())
        };
        for i in indices {
            let sys = self.system_at(self.value(i))?;
            self.initial_state(&sys)?;
        }
        Ok(())
    }
}

/// Start a sweep in the background (one pass, values spread over the window) on
/// `executor` under `control`'s current generation.
pub fn start(
    spec: SweepSpec,
    executor: &Executor,
    control: &Control,
) -> Result<SweepHandle, EngineError> {
    Ok(executor.start(SweepJob::new(spec)?, control))
}

/// Run a whole sweep and return the final result of every value of its shard, in index
/// order.
pub fn collect(spec: &SweepSpec, executor: &Executor) -> Result<Vec<ValueResult>, EngineError> {
    let mut out = Vec::new();
    executor.run(SweepJob::new(spec.clone())?, &Control::new(), |b| {
        if b.complete {
            out.push(b.data)
        }
    });
    out.sort_by_key(|b| b.index);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_of_a_sharded_warm_sweep_partition_the_window() {
        let mut spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.4,
            0.5,
            100,
        );
        spec.warm = Warm::Forward;
        let mut all = Vec::new();
        for i in 0..3 {
            spec.shard = Shard { index: i, count: 3 };
            for c in spec.chains() {
                assert!(c.len() <= WARM_CHAIN);
                assert_eq!(c[0] % WARM_CHAIN, 0);
                all.extend(c);
            }
        }
        all.sort();
        assert_eq!(all, (0..100).collect::<Vec<_>>());
        spec.warm = Warm::Backward;
        spec.shard = Shard::WHOLE;
        let c = spec.chains();
        assert_eq!(c[0][0], WARM_CHAIN - 1);
        assert!(c[0].windows(2).all(|w| w[0] == w[1] + 1));
    }
}
