//! Parameter sweeps: bifurcation diagrams computed in parallel on rayon, streamed in
//! batches as values finish, refined progressively, and cancellable at once.
//!
//! A [`SweepSpec`] names the table, the swept parameter ([`SweepParam`]: α, r or D),
//! the window `lo..=hi` with `steps` values, the fixed parameters, the initial state,
//! the transient (in table periods), how many events to keep, the solver and whether
//! to warm-start. For each value the ball runs until the end of the transient T and the
//! last `keep` events before T are recorded (phase, v, event kind), unless the
//! [periodicity detector](detect) proves earlier that the orbit has settled on a cycle
//! of at most `max_period` events to within `tolerance`: then the remaining events are
//! continued cyclically (see [`run`]), which gives the same points, within the
//! tolerance, as the full transient. Orbits that stick and are released at the same
//! phase again repeat exactly, whatever their length in events; they jump ahead by
//! whole cycles to just before T (see [`run`]). Values that never settle run the full
//! transient.
//!
//! Outcomes per value ([`Outcome`]): periodic (with its cycle), unsettled (ran to T:
//! chaotic, quasi-periodic or a cycle longer than `max_period`), resting (the ball
//! rides on the table forever, [`Halt::Resting`](crate::engine::Halt::Resting)), or
//! no-landing. Stick and release events are recorded like impacts; a value whose points
//! include one is marked [`SweepBatch::sticking`].
//!
//! # Progressive passes
//! With `preview > 0` every value first runs to `preview` periods from the cold initial
//! state, in bit-reversed order over the window, so a complete rough diagram arrives
//! early (pass 0, provisional batches). Pass 1 then brings every value to the full
//! transient; a cold run simply continues where pass 0 left it, so no work is repeated
//! and the result does not depend on the preview. Batches of a later pass replace the
//! earlier ones for the same value index.
//!
//! # Warm start
//! With `warm_start`, the window is cut into chains of [`WARM_CHAIN`] consecutive
//! values; along a chain each value starts from the final state of its neighbour
//! (continuation), so branches stay continuous and transients are short. Chains start
//! cold and run in parallel. Chain boundaries depend only on the value indices, so a
//! sharded warm sweep merges into exactly the unsharded one. Cold sweeps (the default)
//! start every value from the same initial state, as the paper does.
//!
//! # Cancellation and generations
//! The caller owns an `Arc<AtomicU64>` generation counter. A sweep takes the counter's
//! value when it starts; every batch carries that generation. Workers compare the
//! counter with it every [`run::CANCEL_EVERY`] events (tens of microseconds) and stop
//! as soon as it changed, and a batch is only sent while it has not. A consumer that
//! bumps the counter and then starts the next sweep drops any batch whose generation is
//! not the counter's current value ([`SweepHandle::is_current`]), so no stale batch is
//! ever used.
//!
//! # Pause
//! [`start_pausable`] takes a [`PauseGate`]: while it is closed the workers park where
//! they test for cancellation, without spinning, and resume where they stopped. A
//! cancellation also ends a pause. [`Progress::elapsed`] leaves the paused time out.
//! Parked workers keep their threads: on the global rayon pool (`threads: None`) other
//! rayon work of the process waits until the sweep resumes or is cancelled; give the
//! sweep its own pool (`threads: Some(n)`) where that matters.
//!
//! # Examples
//! Background sweep, drained by a consumer (e.g. once per frame):
//! ```
//! use bouncemap::engine::sweep::{self, SweepParam, SweepSpec};
//! use bouncemap::engine::Table;
//! use std::sync::{atomic::AtomicU64, Arc};
//!
//! let mut spec = SweepSpec::new(Table::fd(0.1).unwrap(), SweepParam::Alpha, 0.40, 0.50, 8);
//! spec.transient = 2_000;
//! spec.keep = 10;
//! let generation = Arc::new(AtomicU64::new(0));
//! let handle = sweep::start(spec, generation.clone()).unwrap();
//! let mut finals = 0;
//! for batch in handle.receiver() {
//!     if handle.is_current(&batch) && batch.complete {
//!         finals += 1;
//!     }
//! }
//! assert_eq!(finals, 8);
//! let summary = handle.wait();
//! assert!(!summary.cancelled);
//! ```
//! Blocking, with the final result per value in index order:
//! ```
//! use bouncemap::engine::sweep::{self, Outcome, SweepParam, SweepSpec};
//! use bouncemap::engine::Table;
//!
//! let mut spec = SweepSpec::new(Table::fd(0.1).unwrap(), SweepParam::Alpha, 0.45, 0.45, 1);
//! spec.transient = 10_000;
//! let result = sweep::collect(&spec).unwrap();
//! // α = 0.45 is on the stable (1, 1) branch: one event per table period.
//! assert!(matches!(result[0].outcome, Outcome::Periodic { events: 1, periods: 1, .. }));
//! ```
//! Cancel: `handle.cancel()` (or `generation.fetch_add(1, SeqCst)` from anywhere).

pub mod detect;
pub mod pause;
pub mod run;

pub use detect::Periodicity;
pub use pause::PauseGate;

use crate::engine::error::EngineError;
use crate::engine::impact::Solver;
use crate::engine::map::{EventKind, ImpactMap, State};
use crate::engine::system::{check_alpha, check_r, System};
use crate::engine::table::Table;
use run::{has_sticking, Advance, ValueRun};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Consecutive values per warm-start chain.
pub const WARM_CHAIN: usize = 32;
/// Relative velocity of the default initial hop, v0 = f'(t0) + 0.5 (as `orbit`).
pub const DEFAULT_HOP: f64 = 0.5;
/// Largest number of values in one sweep.
pub const MAX_STEPS: usize = 10_000_000;
/// Largest transient, in periods.
pub const MAX_TRANSIENT: u64 = 1_000_000_000_000;
/// Largest number of kept events per value.
pub const MAX_KEEP: usize = 1_000_000;
/// The paper's transient (Fig. 3): t = 5·10⁶.
pub const PAPER_TRANSIENT: u64 = 5_000_000;
/// The paper's kept bounces per value (Fig. 3).
pub const PAPER_KEEP: usize = 100;
/// Default preview transient of pass 0, in periods.
pub const DEFAULT_PREVIEW: u64 = 1_000;

/// The swept parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SweepParam {
    /// The amplitude α.
    Alpha,
    /// The restitution coefficient r.
    R,
    /// D of the paper's F_D table.
    D,
}

impl SweepParam {
    /// Lower-case name used in every output format (`alpha`, `r`, `d`).
    pub fn as_str(self) -> &'static str {
        match self {
            SweepParam::Alpha => "alpha",
            SweepParam::R => "r",
            SweepParam::D => "d",
        }
    }

    /// Parse `alpha | r | d`.
    pub fn parse(s: &str) -> Option<SweepParam> {
        match s {
            "alpha" => Some(SweepParam::Alpha),
            "r" => Some(SweepParam::R),
            "d" | "D" => Some(SweepParam::D),
            _ => None,
        }
    }
}

/// The initial state of every cold-started value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialSpec {
    /// Initial phase in [0, 1).
    pub t0: f64,
    /// Initial velocity; None means f'(t0) + [`DEFAULT_HOP`] for each value's table.
    pub v0: Option<f64>,
    /// Initial height above the table.
    pub z0: f64,
    /// Start slightly off the (1, 1) fixed point instead (the paper's procedure):
    /// phase t̂* + [`FIXED_POINT_OFFSET`], v = ½, where f'(t̂*) = ½(1 − r)/(1 + r) and
    /// f''(t̂*) < 0 (the stable one if there is one). Falls back to t0, v0, z0 where
    /// no (1, 1) solution exists.
    pub near_fixed_point: bool,
}

/// Phase offset from the (1, 1) fixed point of a `near_fixed_point` start.
pub const FIXED_POINT_OFFSET: f64 = 1e-3;

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

/// The phase t̂* of the (1, 1) solution: f'(t̂*) = ½(1 − r)/(1 + r) with f''(t̂*) < 0,
/// preferring one with κ_c < f''(t̂*) (stable). None if the table is too weak.
pub fn fixed_point_phase(sys: &System) -> Option<f64> {
    let target = 0.5 * (1.0 - sys.r) / (1.0 + sys.r);
    let mut candidates: Vec<f64> = Vec::new();
    match sys.table.shape() {
        crate::engine::table::Shape::Sine => {
            let c = target / (2.0 * std::f64::consts::PI * sys.alpha);
            if c.abs() <= 1.0 {
                // f' = 2πα cos 2πt̂, f'' < 0 where sin 2πt̂ > 0: t̂ in (0, ½).
                candidates.push(c.acos() / (2.0 * std::f64::consts::PI));
            }
        }
        crate::engine::table::Shape::Piecewise(pieces) => {
            for p in pieces {
                let g = p.d1.scale(sys.alpha);
                let g = g.with_coeff(0, g.coeff(0) - target);
                for &s in g.roots_in(0.0, p.len()).as_slice() {
                    if s < p.len() {
                        candidates.push(p.start + s);
                    }
                }
            }
        }
    }
    let kc = sys.kappa_c();
    let curv = |t: f64| sys.jet(t)[2];
    candidates
        .iter()
        .copied()
        .find(|&t| curv(t) < 0.0 && curv(t) > kc)
        .or_else(|| candidates.iter().copied().find(|&t| curv(t) < 0.0))
}

/// Which interleaved part of a sweep to compute: chains c with c % count == index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// 0-based part number, < count.
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };
}

/// Everything that defines a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSpec {
    /// The table (for a D sweep, an F_D table; its D is replaced by each value).
    pub table: Table,
    pub param: SweepParam,
    /// Window of the swept parameter, inclusive.
    pub lo: f64,
    pub hi: f64,
    /// Number of values, evenly spaced: lo + (hi − lo) i / (steps − 1).
    pub steps: usize,
    /// α when it is not swept.
    pub alpha: f64,
    /// r when it is not swept.
    pub r: f64,
    pub initial: InitialSpec,
    /// End of the transient T, in table periods: points are the last `keep` events
    /// before t = T.
    pub transient: u64,
    /// Events recorded per value.
    pub keep: usize,
    pub solver: Solver,
    /// Start each value from its neighbour's final state (see the module docs).
    pub warm_start: bool,
    /// Early stop on detected cycles; None runs every value to T (brute force).
    pub periodicity: Option<Periodicity>,
    /// Transient of the provisional pass 0, in periods; 0 for a single pass.
    pub preview: u64,
    pub shard: Shard,
    /// Worker threads; None uses rayon's global pool (all cores).
    pub threads: Option<usize>,
}

impl SweepSpec {
    /// A sweep at the paper's fidelity (T = 5·10⁶, keep 100), cold start, exact
    /// solver, early stop with the default [`Periodicity`], preview pass of
    /// [`DEFAULT_PREVIEW`] periods; α = 0.45 and r = 0.8 when not swept.
    pub fn new(table: Table, param: SweepParam, lo: f64, hi: f64, steps: usize) -> SweepSpec {
        SweepSpec {
            table,
            param,
            lo,
            hi,
            steps,
            alpha: 0.45,
            r: 0.8,
            initial: InitialSpec::default(),
            transient: PAPER_TRANSIENT,
            keep: PAPER_KEEP,
            solver: Solver::Exact,
            warm_start: false,
            periodicity: Some(Periodicity::default()),
            preview: DEFAULT_PREVIEW,
            shard: Shard::WHOLE,
            threads: None,
        }
    }

    /// The value with index `i`.
    pub fn value(&self, i: usize) -> f64 {
        if self.steps <= 1 {
            self.lo
        } else if i + 1 == self.steps {
            self.hi
        } else {
            self.lo + (self.hi - self.lo) * (i as f64) / ((self.steps - 1) as f64)
        }
    }

    /// The system at a value of the swept parameter.
    pub fn system_at(&self, value: f64) -> Result<System, EngineError> {
        match self.param {
            SweepParam::Alpha => System::new(self.table.clone(), value, self.r),
            SweepParam::R => System::new(self.table.clone(), self.alpha, value),
            SweepParam::D => System::new(Table::fd(value)?, self.alpha, self.r),
        }
    }

    /// The cold initial state for a system of this sweep.
    pub fn initial_state(&self, sys: &System) -> Result<State, EngineError> {
        let i = self.initial;
        if i.near_fixed_point {
            if let Some(t) = fixed_point_phase(sys) {
                let (_, phase) = crate::engine::impact::normalize(0, t + FIXED_POINT_OFFSET);
                if let Ok(s) = State::launch(sys, 0, phase, 0.5_f64.max(sys.df(phase)), 0.0) {
                    return Ok(s);
                }
            }
        }
        let v0 = i.v0.unwrap_or_else(|| sys.df(i.t0) + DEFAULT_HOP);
        State::launch(sys, 0, i.t0, v0, i.z0)
    }

    /// Value indices of this sweep's shard, in chains of consecutive indices.
    fn chains(&self) -> Vec<Vec<usize>> {
        let len = if self.warm_start { WARM_CHAIN } else { 1 };
        (0..self.steps.div_ceil(len))
            .filter(|c| c % self.shard.count == self.shard.index)
            .map(|c| (c * len..((c + 1) * len).min(self.steps)).collect())
            .collect()
    }

    /// Check every setting; the message names the setting, the value and the range.
    pub fn validate(&self) -> Result<(), EngineError> {
        let bad = |name: &'static str, value: String, range: &'static str| {
            Err(EngineError::InvalidParameter { name, value, range })
        };
        if !(1..=MAX_STEPS).contains(&self.steps) {
            return bad("steps", self.steps.to_string(), "1 ..= 10000000");
        }
        if !(self.lo.is_finite() && self.hi.is_finite() && self.lo <= self.hi) {
            return bad(
                self.param.as_str(),
                format!("{}..{}", self.lo, self.hi),
                "a window LO..HI with LO ≤ HI",
            );
        }
        if !(1..=MAX_TRANSIENT).contains(&self.transient) {
            return bad(
                "transient",
                self.transient.to_string(),
                "1 ..= 10^12 periods",
            );
        }
        if !(1..=MAX_KEEP).contains(&self.keep) {
            return bad("keep", self.keep.to_string(), "1 ..= 1000000");
        }
        if let Some(p) = self.periodicity {
            if !(1..=4096).contains(&p.max_period) {
                return bad("max-period", p.max_period.to_string(), "1 ..= 4096");
            }
            if !(p.tolerance.is_finite() && p.tolerance > 0.0 && p.tolerance <= 1e-3) {
                return bad("tolerance", p.tolerance.to_string(), "(0, 1e-3]");
            }
        }
        if self.shard.count == 0 || self.shard.index >= self.shard.count {
            return bad(
                "shard",
                format!("{}/{}", self.shard.index + 1, self.shard.count),
                "I/N with 1 ≤ I ≤ N",
            );
        }
        if self.threads == Some(0) {
            return bad("threads", "0".into(), "at least 1");
        }
        match self.param {
            SweepParam::Alpha => check_r(self.r)?,
            SweepParam::R => check_alpha(self.alpha)?,
            SweepParam::D => {
                check_alpha(self.alpha)?;
                check_r(self.r)?;
                if self.table.d().is_none() {
                    return Err(EngineError::InvalidParameter {
                        name: "table",
                        value: self.table.name().to_string(),
                        range: "an fd:D table when D is swept",
                    });
                }
            }
        }
        // f'(t0) is affine in α and in D and does not depend on r, so checking the
        // window's ends checks every value's initial state.
        for v in [self.lo, self.hi] {
            let sys = self.system_at(v)?;
            self.initial_state(&sys)?;
        }
        Ok(())
    }
}

/// One recorded event of a value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// Phase t̂ in [0, 1).
    pub phase: f64,
    /// Ball velocity after the event.
    pub v: f64,
    pub kind: EventKind,
}

/// What became of one value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// Provisional (pass 0): the run has reached this period and goes on.
    Running { reached: i64 },
    /// Settled on a cycle of `events` events in `periods` table periods; the run
    /// stopped at period `stopped_at` and the cycle was continued to T.
    Periodic {
        events: usize,
        periods: i64,
        stopped_at: i64,
    },
    /// Ran the full transient without settling on a cycle of at most `max_period`
    /// events (chaos, a long or slowly converging cycle, or early stop switched off).
    Unsettled,
    /// The ball rides on the table forever from this time on.
    Resting { period: i64, phase: f64 },
    /// The ball did not land within the solver's work bound.
    NoLanding { period: i64, phase: f64 },
}

impl Outcome {
    /// Lower-case name used in every output format.
    pub fn as_str(&self) -> &'static str {
        match self {
            Outcome::Running { .. } => "running",
            Outcome::Periodic { .. } => "periodic",
            Outcome::Unsettled => "unsettled",
            Outcome::Resting { .. } => "resting",
            Outcome::NoLanding { .. } => "no-landing",
        }
    }

    /// Events per detected cycle.
    pub fn period(&self) -> Option<usize> {
        match self {
            Outcome::Periodic { events, .. } => Some(*events),
            _ => None,
        }
    }
}

/// The result for one value, as streamed to the consumer.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepBatch {
    /// The sweep generation that produced it.
    pub generation: u64,
    /// 0 for the preview pass, 1 for the full transient.
    pub pass: u32,
    /// True when this is the value's final result (no later batch will replace it).
    pub complete: bool,
    /// Index of the value in the window, 0 ..< steps.
    pub index: usize,
    /// The swept parameter's value.
    pub value: f64,
    /// Recorded events, oldest first.
    pub points: Vec<SweepPoint>,
    pub outcome: Outcome,
    /// Whether the points include a stick or a release.
    pub sticking: bool,
    /// Events computed for this value.
    pub events: u64,
}

/// Progress counters shared with the workers.
#[derive(Debug, Default)]
struct Counters {
    values_done: AtomicUsize,
    events: AtomicU64,
    points: AtomicU64,
}

/// A snapshot of a sweep's progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Values with a final result.
    pub values_done: usize,
    /// Values in this sweep (this shard).
    pub values_total: usize,
    /// Events computed so far, all values (updated every few dozen events).
    pub events: u64,
    /// Points delivered so far (all passes).
    pub points: u64,
    pub elapsed: Duration,
}

impl Progress {
    /// Events computed per second of wall time.
    pub fn events_per_second(&self) -> f64 {
        self.events as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// Points delivered per second of wall time.
    pub fn points_per_second(&self) -> f64 {
        self.points as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// Fraction of values done, 0..=1.
    pub fn fraction(&self) -> f64 {
        if self.values_total == 0 {
            1.0
        } else {
            self.values_done as f64 / self.values_total as f64
        }
    }
}

/// How a sweep ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepSummary {
    pub generation: u64,
    /// True if the generation changed (or the handle was dropped) before the end.
    pub cancelled: bool,
    pub progress: Progress,
}

/// A running sweep.
#[derive(Debug)]
pub struct SweepHandle {
    generation: u64,
    counter: Arc<AtomicU64>,
    abandoned: Arc<AtomicBool>,
    receiver: Receiver<SweepBatch>,
    counters: Arc<Counters>,
    values_total: usize,
    started: Instant,
    pause: Arc<PauseGate>,
    thread: Option<JoinHandle<SweepSummary>>,
}

impl SweepHandle {
    /// The generation this sweep runs under.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The batch stream; it disconnects when the sweep ends or is cancelled.
    pub fn receiver(&self) -> &Receiver<SweepBatch> {
        &self.receiver
    }

    /// Whether a batch belongs to the generation that is current now.
    pub fn is_current(&self, batch: &SweepBatch) -> bool {
        batch.generation == self.counter.load(Ordering::SeqCst)
    }

    /// Every batch waiting in the channel that belongs to the current generation,
    /// without blocking.
    pub fn drain(&self) -> Vec<SweepBatch> {
        self.receiver
            .try_iter()
            .filter(|b| self.is_current(b))
            .collect()
    }

    /// Cancel this sweep (and any other sweep of the same generation) by advancing
    /// the shared generation counter. Returns the new generation.
    pub fn cancel(&self) -> u64 {
        let _ = self.counter.compare_exchange(
            self.generation,
            self.generation + 1,
            Ordering::SeqCst,
            Ordering::SeqCst,
        );
        self.pause.wake();
        self.counter.load(Ordering::SeqCst)
    }

    /// Progress so far.
    pub fn progress(&self) -> Progress {
        Progress {
            values_done: self.counters.values_done.load(Ordering::Relaxed),
            values_total: self.values_total,
            events: self.counters.events.load(Ordering::Relaxed),
            points: self.counters.points.load(Ordering::Relaxed),
            elapsed: self
                .started
                .elapsed()
                .saturating_sub(self.pause.paused_for()),
        }
    }

    /// The gate that pauses this sweep's workers (see [`pause`]).
    pub fn pause_gate(&self) -> Arc<PauseGate> {
        self.pause.clone()
    }

    /// Whether every worker has stopped.
    pub fn is_finished(&self) -> bool {
        self.thread.as_ref().map_or(true, |t| t.is_finished())
    }

    /// Wait for the workers to stop and return the summary.
    pub fn wait(mut self) -> SweepSummary {
        let t = self.thread.take().expect("joined once");
        match t.join() {
            Ok(s) => s,
            Err(p) => std::panic::resume_unwind(p),
        }
    }
}

impl Drop for SweepHandle {
    fn drop(&mut self) {
        // Nobody will read the batches: stop the workers without touching the shared
        // counter (a newer sweep may already run under it).
        self.abandoned.store(true, Ordering::SeqCst);
        self.pause.wake();
    }
}

/// Start a sweep in the background under the counter's current generation.
pub fn start(spec: SweepSpec, counter: Arc<AtomicU64>) -> Result<SweepHandle, EngineError> {
    start_pausable(spec, counter, Arc::new(PauseGate::default()))
}

/// [`start`], with workers that park while `pause` is closed (a caller that pauses
/// several sweeps in turn keeps one gate for all of them).
pub fn start_pausable(
    spec: SweepSpec,
    counter: Arc<AtomicU64>,
    pause: Arc<PauseGate>,
) -> Result<SweepHandle, EngineError> {
    spec.validate()?;
    let generation = counter.load(Ordering::SeqCst);
    let (tx, rx) = mpsc::channel();
    let counters = Arc::new(Counters::default());
    let abandoned = Arc::new(AtomicBool::new(false));
    let values_total = spec.chains().iter().map(Vec::len).sum();
    let started = Instant::now();
    let pool = match spec.threads {
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| EngineError::InvalidParameter {
                    name: "threads",
                    value: format!("{n} ({e})"),
                    range: "a number of threads the system can start",
                })?,
        ),
        None => None,
    };
    let ctx = Ctx {
        spec,
        generation,
        counter: counter.clone(),
        abandoned: abandoned.clone(),
        counters: counters.clone(),
        pause: pause.clone(),
        tx,
    };
    let thread = std::thread::Builder::new()
        .name("sweep".into())
        .spawn(move || {
            match &pool {
                Some(p) => p.install(|| ctx.run()),
                None => ctx.run(),
            }
            SweepSummary {
                generation,
                cancelled: ctx.stopped(),
                progress: Progress {
                    values_done: ctx.counters.values_done.load(Ordering::Relaxed),
                    values_total,
                    events: ctx.counters.events.load(Ordering::Relaxed),
                    points: ctx.counters.points.load(Ordering::Relaxed),
                    elapsed: started.elapsed().saturating_sub(ctx.pause.paused_for()),
                },
            }
        })
        .map_err(|e| EngineError::InvalidParameter {
            name: "threads",
            value: e.to_string(),
            range: "a thread the system can start",
        })?;
    Ok(SweepHandle {
        generation,
        counter,
        abandoned,
        receiver: rx,
        counters,
        values_total,
        started,
        pause,
        thread: Some(thread),
    })
}

/// Run a sweep to the end on the calling thread's behalf, handing each batch of the
/// current generation to `on_batch` as it arrives (on the calling thread).
pub fn run(
    spec: SweepSpec,
    counter: Arc<AtomicU64>,
    mut on_batch: impl FnMut(SweepBatch),
) -> Result<SweepSummary, EngineError> {
    let handle = start(spec, counter)?;
    for b in handle.receiver() {
        if handle.is_current(&b) {
            on_batch(b);
        }
    }
    Ok(handle.wait())
}

/// Run a whole sweep (no preview pass) and return the final batch of every value of
/// its shard, in index order.
pub fn collect(spec: &SweepSpec) -> Result<Vec<SweepBatch>, EngineError> {
    let mut spec = spec.clone();
    spec.preview = 0;
    let mut out = Vec::new();
    run(spec, Arc::new(AtomicU64::new(0)), |b| {
        if b.complete {
            out.push(b)
        }
    })?;
    out.sort_by_key(|b| b.index);
    Ok(out)
}

/// Positions 0..n in bit-reversed order: every prefix is spread over the whole range.
pub fn bit_reversed_order(n: usize) -> Vec<usize> {
    if n <= 1 {
        return (0..n).collect();
    }
    let bits = usize::BITS - (n - 1).leading_zeros();
    let mut v: Vec<usize> = (0..n).collect();
    v.sort_by_key(|&i| i.reverse_bits() >> (usize::BITS - bits));
    v
}

/// What the workers share.
struct Ctx {
    spec: SweepSpec,
    generation: u64,
    counter: Arc<AtomicU64>,
    abandoned: Arc<AtomicBool>,
    counters: Arc<Counters>,
    pause: Arc<PauseGate>,
    tx: Sender<SweepBatch>,
}

impl Ctx {
    fn stopped(&self) -> bool {
        self.counter.load(Ordering::Relaxed) != self.generation
            || self.abandoned.load(Ordering::Relaxed)
    }

    /// The cancellation test handed to value runs; it also counts events, and parks
    /// the worker while the sweep is paused.
    fn tick(&self, events: u64) -> bool {
        self.counters.events.fetch_add(events, Ordering::Relaxed);
        self.pause.wait(|| self.stopped());
        self.stopped()
    }

    fn send(&self, b: SweepBatch) {
        if self.stopped() {
            return;
        }
        if b.complete {
            self.counters.values_done.fetch_add(1, Ordering::Relaxed);
        }
        self.counters
            .points
            .fetch_add(b.points.len() as u64, Ordering::Relaxed);
        if self.tx.send(b).is_err() {
            self.abandoned.store(true, Ordering::SeqCst);
        }
    }

    /// Run `job(i)` for i in 0..n on every worker of the current pool, handing out i
    /// in order from a shared counter, until done or stopped.
    fn for_each(&self, n: usize, job: &(dyn Fn(usize) + Sync)) {
        let next = AtomicUsize::new(0);
        let workers = rayon::current_num_threads().clamp(1, n.max(1));
        rayon::scope(|s| {
            for _ in 0..workers {
                s.spawn(|_| loop {
                    if self.stopped() {
                        return;
                    }
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= n {
                        return;
                    }
                    job(i);
                });
            }
        });
    }

    fn new_run(&self, index: usize, warm_from: Option<&State>) -> Option<(f64, ValueRun)> {
        let value = self.spec.value(index);
        let sys = self.spec.system_at(value).ok()?;
        let state = warm_from
            .and_then(|s| {
                let v = s.v.max(sys.df(s.phase));
                State::launch(&sys, 0, s.phase, v, 0.0).ok()
            })
            .or_else(|| self.spec.initial_state(&sys).ok())?;
        let map = ImpactMap::new(sys, self.spec.solver, state);
        Some((
            value,
            ValueRun::new(map, self.spec.keep, self.spec.periodicity),
        ))
    }

    fn batch(
        &self,
        pass: u32,
        index: usize,
        value: f64,
        run: &ValueRun,
        adv: Advance,
    ) -> Option<SweepBatch> {
        let (complete, outcome, points) = match adv {
            Advance::Done(o, p) => (true, o, p),
            Advance::Checkpoint => (
                false,
                Outcome::Running {
                    reached: run.reached(),
                },
                run.points(),
            ),
            Advance::Cancelled => return None,
        };
        Some(SweepBatch {
            generation: self.generation,
            pass,
            complete,
            index,
            value,
            sticking: has_sticking(&points),
            points,
            outcome,
            events: run.events(),
        })
    }

    fn run(&self) {
        let end = self.spec.transient as i64;
        let chains = self.spec.chains();
        let preview = self.spec.preview as i64;
        let mut cold_runs: Vec<Mutex<Option<(usize, f64, ValueRun)>>> = Vec::new();
        if preview > 0 && preview < end {
            // Pass 0: every value from the cold state to `preview`, spread over the window.
            let values: Vec<usize> = chains.iter().flatten().copied().collect();
            let order = bit_reversed_order(values.len());
            cold_runs = (0..values.len()).map(|_| Mutex::new(None)).collect();
            let keep_runs = !self.spec.warm_start;
            self.for_each(order.len(), &|k| {
                let pos = order[k];
                let index = values[pos];
                let Some((value, mut run)) = self.new_run(index, None) else {
                    return;
                };
                let adv = run.advance(preview, end, &mut |n| self.tick(n));
                let resumable = matches!(adv, Advance::Checkpoint);
                if let Some(mut b) = self.batch(0, index, value, &run, adv) {
                    if !keep_runs {
                        b.complete = false;
                    } else if resumable {
                        *cold_runs[pos].lock().expect("no panics under the lock") =
                            Some((index, value, run));
                    }
                    self.send(b);
                }
            });
            if self.stopped() {
                return;
            }
        }
        if self.spec.warm_start {
            let order = bit_reversed_order(chains.len());
            self.for_each(order.len(), &|k| {
                let mut prev: Option<State> = None;
                for &index in &chains[order[k]] {
                    let Some((value, mut run)) = self.new_run(index, prev.as_ref()) else {
                        return;
                    };
                    let adv = run.advance(end, end, &mut |n| self.tick(n));
                    prev = match adv {
                        Advance::Done(Outcome::NoLanding { .. }, _) => None,
                        _ => Some(run.state()),
                    };
                    match self.batch(1, index, value, &run, adv) {
                        Some(b) => self.send(b),
                        None => return,
                    }
                }
            });
        } else if !cold_runs.is_empty() {
            let order = bit_reversed_order(cold_runs.len());
            self.for_each(order.len(), &|k| {
                let slot = cold_runs[order[k]]
                    .lock()
                    .expect("no panics under the lock")
                    .take();
                if let Some((index, value, mut run)) = slot {
                    let adv = run.advance(end, end, &mut |n| self.tick(n));
                    if let Some(b) = self.batch(1, index, value, &run, adv) {
                        self.send(b);
                    }
                }
            });
        } else if preview <= 0 || preview >= end {
            let values: Vec<usize> = chains.iter().flatten().copied().collect();
            let order = bit_reversed_order(values.len());
            self.for_each(order.len(), &|k| {
                let index = values[order[k]];
                if let Some((value, mut run)) = self.new_run(index, None) {
                    let adv = run.advance(end, end, &mut |n| self.tick(n));
                    if let Some(b) = self.batch(1, index, value, &run, adv) {
                        self.send(b);
                    }
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_reversed_order_is_a_permutation_that_spreads() {
        let o = bit_reversed_order(10);
        let mut s = o.clone();
        s.sort();
        assert_eq!(s, (0..10).collect::<Vec<_>>());
        assert_eq!(&o[..4], &[0, 8, 4, 2]);
    }

    #[test]
    fn default_hop_matches_the_cli() {
        assert_eq!(DEFAULT_HOP, crate::cli::DEFAULT_HOP);
    }

    #[test]
    fn chains_of_a_sharded_warm_sweep_partition_the_window() {
        let mut spec = SweepSpec::new(Table::fd(0.1).unwrap(), SweepParam::Alpha, 0.4, 0.5, 100);
        spec.warm_start = true;
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
    }
}
