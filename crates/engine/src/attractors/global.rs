//! Attractors continued along α (global continuation, as Attractors.jl's
//! `global_continuation` with recurrences): at each α of a window, every attractor
//! found from a grid of starts, matched to those of the previous α, with its basin
//! fraction and the picture's basin statistics.
//!
//! At each α value:
//! 1. **Seeds.** Up to [`SEED_POINTS`] points of the attractors found at the previous
//!    α (a cycle's events, spread along it; an unsettled orbit's last event; where a
//!    ball came to rest) are run at this α to their attractors: every cycle's, and
//!    those of orbits without a cycle that hold at least [`MIN_SEED_SHARE`] of the
//!    starts, at most [`MAX_SEEDED`] attractors, largest basin first. They find the
//!    continuation of each old attractor even where no start of the grid lands on it
//!    (then its basin fraction is 0), and where an old attractor is gone they say
//!    where its points now go. Seeds are not counted in the fractions.
//! 2. **The grid.** The basin picture of [`BasinSpec`] (same box of starts at every α:
//!    t̂0 ∈ [0, 1), w0 ∈ [0, W]), run as the `basins` job on the executor, its attractors
//!    numbered after the seeds' ([`Basins::seeded`]). With
//!    [`GlobalSpec::stop_at_known`], a start that reaches a cycle the seeds found stops
//!    there ([`known`](super::known)).
//! 3. **Matching.** Each attractor at this α is matched to one at the previous α by the
//!    distance between their point sets (the Hausdorff distance in the metric
//!    max(phase distance around the circle, |Δv|) that [`MATCH`](super::MATCH) uses;
//!    for an orbit identified by its cells, the cells' centres, at most [`MAX_SET`]
//!    of them): pairs are taken closest first, one to one, up to [`MATCH_DISTANCE`],
//!    a resting ball only with a resting ball and an escape only with an escape. An
//!    old attractor left unmatched is then matched to the new attractor most of its
//!    seeds went to, if that one is unmatched too (its points lie in that basin and
//!    nothing else continues either: a sticking cycle whose itinerary changed). A
//!    matched pair is one *track*, an attractor followed along α.
//! 4. **Changes** ([`Change`]) between the previous α and this one: a birth (an
//!    attractor matched to none before), a death (one before matched to none now,
//!    with the track its seeds went to, if any: a merger), a period change (the cycle's
//!    (n, k) changed, both resolved by double precision), a change of kind (e.g.
//!    periodic to chaotic), and into or out of sticking.
//! 5. **Statistics** of the picture ([`statistics`](super::statistics)): basin entropy
//!    S_b and S_bb and the uncertainty exponent, from the grid's neighbours or, with
//!    [`GlobalSpec::sampled_starts`], from sampled starts and displaced copies down to
//!    10⁻⁶ ([`sampled`](super::sampled)).
//!
//! The α values run one after the other (each seeds the next); the starts of one α run
//! in parallel. [`Continuation`] holds the results so far and is advanced one α at a
//! time ([`Continuation::prepare`], then [`Continuation::absorb`] with the picture), so
//! a caller can run the grid on its own executor, show progress and stop between
//! values; [`collect`] does it all.

use super::basins::{BasinSpec, Basins, BasinsJob};
use super::known::Known;
use super::statistics::{
    basin_entropy, uncertainty, BasinEntropy, NoExponent, Uncertainty, ENTROPY_BOX,
};
use super::{settle, Attractor, Kind, Registry, Settle};
use crate::error::EngineError;
use crate::jobs::grid::{check_window, grid_value, SweepParam};
use crate::jobs::{Control, Executor};
use crate::limits;
use crate::map::State;
use crate::run::precision::Precision;
use crate::system::System;
use crate::time::phase_distance;

/// Largest distance between the point sets of an attractor at neighbouring α values
/// for the two to be one attractor followed along α (in table periods and units of
/// velocity, the larger of the two differences).
pub const MATCH_DISTANCE: f64 = 0.05;
/// Points of each attractor run as seeds at the next α.
pub const SEED_POINTS: usize = 4;
/// Attractors seeded from, at most (largest basin first).
pub const MAX_SEEDED: usize = 32;
/// Least share of the starts an attractor without a cycle must hold to be seeded from.
pub const MIN_SEED_SHARE: f64 = 0.01;
/// Most points of a set the distance between two attractors looks at (evenly spread
/// over the set, sorted by cell).
pub const MAX_SET: usize = 512;

/// Everything that defines a continuation of attractors.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalSpec {
    /// The table and r (its α is replaced by each value of the window).
    pub sys: System,
    /// First α.
    pub lo: f64,
    /// Last α.
    pub hi: f64,
    /// α values, lo and hi included (one: lo only).
    pub steps: usize,
    /// Starts along t̂0.
    pub nx: usize,
    /// Starts along w0.
    pub ny: usize,
    /// Top of the w0 range, the same at every α.
    pub w_max: f64,
    /// How each start is run to its attractor.
    pub settle: Settle,
    /// Whether a start of the grid that reaches a cycle the seeds found stops there
    /// ([`known`](super::known)) instead of detecting it by itself.
    pub stop_at_known: bool,
    /// Starts of the sampled measurement of the uncertainty exponent at each α
    /// ([`sampled`](super::sampled)), in place of the grid's; 0: the grid's.
    pub sampled_starts: usize,
}

impl GlobalSpec {
    /// Check the window, the number of values and the picture at every α's ends.
    pub fn validate(&self) -> Result<(), EngineError> {
        check_window(SweepParam::Alpha, self.sys.table(), self.lo, self.hi)?;
        limits::ATTRACTOR_STEPS.check(self.steps as f64)?;
        if self.steps > 1 && self.lo >= self.hi {
            return Err(EngineError::InvalidParameter {
                name: "alpha".into(),
                value: format!("{}..{}", self.lo, self.hi),
                range: "a window LO..HI with LO < HI".into(),
            });
        }
        self.basins(0)?.validate()
    }

    /// α value `i`.
    pub fn alpha(&self, i: usize) -> f64 {
        grid_value(self.lo, self.hi, self.steps, i)
    }

    /// The basin picture at α value `i`.
    pub fn basins(&self, i: usize) -> Result<BasinSpec, EngineError> {
        let sys = SweepParam::Alpha.system(
            self.sys.table(),
            self.sys.alpha(),
            self.sys.r(),
            self.alpha(i),
        )?;
        Ok(BasinSpec {
            sys,
            nx: self.nx,
            ny: self.ny,
            w_max: self.w_max,
            settle: self.settle,
        })
    }

    /// Starts per α value.
    pub fn starts(&self) -> usize {
        self.nx * self.ny
    }
}

/// An attractor at one α value, as one of a track.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The track it belongs to (0-based, in order of appearance).
    pub track: usize,
    /// What it is.
    pub kind: Kind,
    /// Events per cycle, for cycles.
    pub events: Option<usize>,
    /// Table periods per cycle, for cycles.
    pub periods: Option<i64>,
    /// A point on it.
    pub point: Option<(f64, f64)>,
    /// Its largest exponent per impact.
    pub lyapunov: Option<f64>,
    /// For a cycle: whether double precision decides it.
    pub precision: Option<Precision>,
    /// Starts of the grid that ended on it.
    pub starts: usize,
    /// Their share of the grid.
    pub fraction: f64,
    /// Points (phase, v) of it for a diagram: a cycle's events, or the centres of the
    /// cells an unsettled orbit visits, at most [`DIAGRAM_POINTS`] spread over them.
    pub points: Vec<(f64, f64)>,
}

/// Most points a member keeps for a diagram.
pub const DIAGRAM_POINTS: usize = 256;

impl Member {
    fn of(a: &Attractor, track: usize, grid: usize) -> Member {
        Member {
            track,
            kind: a.kind,
            events: a.events,
            periods: a.periods,
            point: a.point,
            lyapunov: a.lyapunov,
            precision: a.precision,
            starts: a.starts,
            fraction: a.starts as f64 / grid as f64,
            points: spread(a.points(), DIAGRAM_POINTS),
        }
    }

    /// (n, k) where double precision decides it.
    pub fn period(&self) -> Option<(usize, i64)> {
        super::resolved_period(self.events, self.periods, self.precision)
    }

    /// Whether it is a cycle whose length double precision cannot decide.
    pub fn unresolved(&self) -> bool {
        self.precision.is_some_and(|p| !p.resolved)
    }
}

/// The picture at one α value.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The α value.
    pub alpha: f64,
    /// Its attractors, by track.
    pub members: Vec<Member>,
    /// Starts of the grid.
    pub starts: usize,
    /// Starts that were not run to an attractor (a launch the table refuses): the
    /// "not settled" class, so that the fractions and this share sum to 1.
    pub not_settled: usize,
    /// The basin entropy (None when the grid holds no whole box).
    pub entropy: Option<BasinEntropy>,
    /// The uncertainty exponent, or why there is none.
    pub uncertainty: Result<Uncertainty, NoExponent>,
    /// Whether it was measured by sampled starts and displaced copies (ε in periods of
    /// t̂0) rather than from the grid's neighbours (ε in grid steps).
    pub sampled: bool,
    /// Seeds run (points of the previous α's attractors).
    pub seeds: usize,
}

impl Step {
    /// The share of not-settled starts.
    pub fn not_settled_fraction(&self) -> f64 {
        self.not_settled as f64 / self.starts as f64
    }
}

/// What changed along a track between two neighbouring α values.
#[derive(Clone, Debug, PartialEq)]
pub enum ChangeKind {
    /// An attractor with no match at the previous α.
    Birth,
    /// An attractor with no match at this α; `into`: the track its seeds went to, if
    /// they went to an attractor (a merger or a crisis), None if they did not settle.
    Death {
        /// Where its points now go.
        into: Option<usize>,
    },
    /// The cycle's (n, k) changed (both decided by double precision).
    Period {
        /// Before.
        from: (usize, i64),
        /// After.
        to: (usize, i64),
    },
    /// The kind changed; into or out of sticking when either is [`Kind::Sticking`].
    Kind {
        /// Before.
        from: Kind,
        /// After.
        to: Kind,
    },
}

impl ChangeKind {
    /// Its name in every output: birth, death, merge, period, sticking, kind.
    pub fn name(&self) -> &'static str {
        match self {
            ChangeKind::Birth => "birth",
            ChangeKind::Death { into: None } => "death",
            ChangeKind::Death { into: Some(_) } => "merge",
            ChangeKind::Period { .. } => "period",
            ChangeKind::Kind { from, to } if *from == Kind::Sticking || *to == Kind::Sticking => {
                "sticking"
            }
            ChangeKind::Kind { .. } => "kind",
        }
    }
}

/// A change of the picture between α value `step − 1` and `step`.
#[derive(Clone, Debug, PartialEq)]
pub struct Change {
    /// The first α value (index) where it is seen.
    pub step: usize,
    /// The track it happens to.
    pub track: usize,
    /// What happened.
    pub what: ChangeKind,
    /// For a birth or a death: what the exact map says happened to the attractor's
    /// cycle between the two values ([`Cause`]).
    pub cause: Option<Cause>,
}

/// Why an attractor appears or disappears between two neighbouring α values, from its
/// cycle continued by Newton's method on the exact map to the value where it is not
/// seen (from the one where it is).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cause {
    /// The cycle is there but unstable: a multiplier crossed the unit circle between
    /// the two values. `at` names how: `period doubling` (a real multiplier below −1),
    /// `fold` (above 1), `torus` (a complex pair).
    Unstable {
        /// How it lost (or gained) stability.
        at: &'static str,
        /// Its multiplier of largest modulus there.
        multiplier: crate::linalg::Complex,
    },
    /// Newton's method finds no such cycle there: it ends (or begins) between the two
    /// values, at a fold, a border collision or a grazing.
    Gone,
    /// The cycle is there and stable as well: neither a start of the grid nor a seed
    /// landed on it at that value (a basin too small for the grid), not a bifurcation.
    Missed,
    /// A chaotic attractor that appears or disappears with no cycle to follow: where no
    /// local bifurcation explains it, a crisis.
    Crisis,
    /// No local test: a sticking cycle or one whose length double precision leaves
    /// open (the Newton corrector follows cycles of impacts only), or an unsettled
    /// orbit that is neither a cycle nor chaotic.
    Untested,
}

impl Cause {
    /// Its name in every output: unstable, gone, missed, crisis, untested.
    pub fn name(&self) -> &'static str {
        match self {
            Cause::Unstable { .. } => "unstable",
            Cause::Gone => "gone",
            Cause::Missed => "missed",
            Cause::Crisis => "crisis",
            Cause::Untested => "untested",
        }
    }
}

/// The cause of the birth or death of attractor `a`, not seen in `other` (the system
/// at the neighbouring α): its cycle continued by Newton's method from its first event
/// to `other`, accepted within [`MATCH_DISTANCE`] of it.
fn cause(a: &Attractor, other: &System) -> Cause {
    let cycle = a.cycle_points();
    if a.kind != Kind::Periodic || cycle.is_empty() || a.unresolved() {
        return if a.kind == Kind::Chaotic {
            Cause::Crisis
        } else {
            Cause::Untested
        };
    }
    let (Some(n), Some(k)) = (a.events, a.periods.and_then(|k| u32::try_from(k).ok())) else {
        return Cause::Untested;
    };
    let (t0, v0) = cycle[0];
    let Ok(cp) = crate::orbits::periodic::cycle(other, n, k, t0, v0) else {
        return Cause::Gone;
    };
    let near = phase_distance(cp.phases[0], t0).max((cp.velocities[0] - v0).abs());
    if near > MATCH_DISTANCE {
        return Cause::Gone;
    }
    if cp.stable {
        return Cause::Missed;
    }
    let [m0, m1] = cp.multipliers;
    let m = if m0.abs() >= m1.abs() { m0 } else { m1 };
    let at = if m.im != 0.0 {
        "torus"
    } else if m.re < 0.0 {
        "period doubling"
    } else {
        "fold"
    };
    Cause::Unstable { at, multiplier: m }
}

/// An attractor followed along α.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Track {
    /// Its number (0-based, in order of appearance).
    pub id: usize,
    /// The first α value (index) it is seen at.
    pub first: usize,
    /// The last α value (index) it is seen at.
    pub last: usize,
}

/// The attractors at the last α done, with their tracks: what the next α is matched
/// against and seeded from.
#[derive(Clone, Debug)]
struct Previous {
    registry: Registry,
    /// Track of each attractor id.
    tracks: Vec<usize>,
}

/// The next α value, ready to run: its picture and the attractors its seeds found.
#[derive(Clone, Debug)]
pub struct NextAlpha {
    /// Its index.
    pub index: usize,
    /// Its picture.
    pub spec: BasinSpec,
    registry: Registry,
    /// (track at the previous α, attractor id here) for every seed that settled.
    landed: Vec<(usize, usize)>,
    seeds: usize,
    /// The cycles the seeds found, where starts may stop.
    known: std::sync::Arc<Known>,
    stop_at_known: bool,
    sampled_starts: usize,
}

impl NextAlpha {
    /// The uncertainty exponent by [`sampled`](super::sampled) starts, when the spec
    /// asks for them (None otherwise, or if cancelled), after `basins` (this α's
    /// filled picture, whose attractors the samples' are numbered after).
    pub fn sample(
        &self,
        basins: &Basins,
        executor: &Executor,
        control: &Control,
    ) -> Option<Result<Uncertainty, NoExponent>> {
        if self.sampled_starts == 0 {
            return None;
        }
        let known = self.stop_at_known.then(|| self.known.clone());
        super::sampled::sampled_uncertainty(
            &self.spec,
            self.sampled_starts,
            known,
            basins.registry().clone(),
            executor,
            control,
        )
    }

    /// The job that fills in its picture (with the early stop on the seeds' cycles
    /// when the spec asks for it).
    pub fn job(&self) -> Result<BasinsJob, EngineError> {
        if self.stop_at_known {
            BasinsJob::with_known(self.spec.clone(), self.known.clone())
        } else {
            BasinsJob::new(self.spec.clone())
        }
    }

    /// The empty picture to fill in, its attractors numbered after the seeds'.
    pub fn basins(&self) -> Basins {
        Basins::seeded(&self.spec, self.registry.clone())
    }
}

/// A continuation of attractors as it advances along α.
#[derive(Clone, Debug)]
pub struct Continuation {
    spec: GlobalSpec,
    steps: Vec<Step>,
    changes: Vec<Change>,
    tracks: Vec<Track>,
    previous: Option<Previous>,
}

impl Continuation {
    /// Validate `spec`; nothing computed yet.
    pub fn new(spec: GlobalSpec) -> Result<Continuation, EngineError> {
        spec.validate()?;
        Ok(Continuation {
            spec,
            steps: Vec::new(),
            changes: Vec::new(),
            tracks: Vec::new(),
            previous: None,
        })
    }

    /// The specification.
    pub fn spec(&self) -> &GlobalSpec {
        &self.spec
    }

    /// The α values done, in order.
    pub fn steps(&self) -> &[Step] {
        &self.steps
    }

    /// The changes seen so far, in order of α.
    pub fn changes(&self) -> &[Change] {
        &self.changes
    }

    /// The tracks so far.
    pub fn tracks(&self) -> &[Track] {
        &self.tracks
    }

    /// Whether every α value is done.
    pub fn complete(&self) -> bool {
        self.steps.len() == self.spec.steps
    }

    /// The next α value: its picture, with the previous attractors' seeds run to their
    /// attractors here. None when complete or when `cancelled` stops a seed's run.
    pub fn prepare(
        &self,
        cancelled: &mut dyn FnMut(u64) -> bool,
    ) -> Option<Result<NextAlpha, EngineError>> {
        let index = self.steps.len();
        if index >= self.spec.steps {
            return None;
        }
        let spec = match self.spec.basins(index) {
            Ok(s) => s,
            Err(e) => return Some(Err(e)),
        };
        let mut registry = Registry::new();
        let mut landed = Vec::new();
        let mut seeds = 0;
        let mut known = Known::new();
        if let Some(prev) = &self.previous {
            let attractors = prev.registry.attractors();
            for id in seeded(&prev.registry, self.spec.starts()) {
                let a = &attractors[id];
                for (phase, v) in seed_points(a) {
                    let Some(start) = launch_at(&spec.sys, phase, v) else {
                        continue;
                    };
                    seeds += 1;
                    let (found, ..) = settle(&spec.sys, start, &spec.settle, 1, cancelled)?;
                    landed.push((prev.tracks[id], registry.seed(&found)));
                    known.add(&found);
                }
            }
        }
        Some(Ok(NextAlpha {
            index,
            spec,
            registry,
            landed,
            seeds,
            known: std::sync::Arc::new(known),
            stop_at_known: self.spec.stop_at_known,
            sampled_starts: self.spec.sampled_starts,
        }))
    }

    /// Take the filled picture of `next` (from [`Self::prepare`]): match its
    /// attractors, record the changes and the statistics.
    pub fn absorb(&mut self, next: NextAlpha, basins: &Basins) {
        assert_eq!(next.index, self.steps.len(), "α values in order");
        let index = next.index;
        let reg = basins.registry();
        let current = reg.attractors();
        let grid = self.spec.starts();
        let mut tracks: Vec<Option<usize>> = vec![None; current.len()];
        if let Some(prev) = self.previous.take() {
            let old = prev.registry.attractors();
            let mut pairs = match_sets(old, current);
            pairs.extend(match_by_seeds(
                old,
                current,
                &prev.tracks,
                &next.landed,
                &pairs,
            ));
            let mut matched_old = vec![false; old.len()];
            for &(o, c) in &pairs {
                matched_old[o] = true;
                let track = prev.tracks[o];
                tracks[c] = Some(track);
                if let Some(what) = change_of(
                    old[o].kind,
                    old[o].period(),
                    current[c].kind,
                    current[c].period(),
                ) {
                    self.changes.push(Change {
                        step: index,
                        track,
                        what,
                        cause: None,
                    });
                }
            }
            let before = self.spec.basins(index - 1).map(|b| b.sys);
            for (c, t) in tracks.iter_mut().enumerate() {
                if t.is_none() {
                    let id = self.new_track(index);
                    *t = Some(id);
                    self.changes.push(Change {
                        step: index,
                        track: id,
                        what: ChangeKind::Birth,
                        cause: before.as_ref().ok().map(|sys| cause(&current[c], sys)),
                    });
                }
            }
            for (o, done) in matched_old.iter().enumerate() {
                if *done {
                    continue;
                }
                let track = prev.tracks[o];
                let into = next
                    .landed
                    .iter()
                    .filter(|(t, _)| *t == track)
                    .find_map(|&(_, c)| tracks.get(c).copied().flatten())
                    .filter(|&t| t != track);
                self.changes.push(Change {
                    step: index,
                    track,
                    what: ChangeKind::Death { into },
                    cause: Some(cause(&old[o], &next.spec.sys)),
                });
            }
        } else {
            for t in tracks.iter_mut() {
                *t = Some(self.new_track(index));
            }
        }
        let tracks: Vec<usize> = tracks
            .into_iter()
            .map(|t| t.expect("every attractor has a track"))
            .collect();
        for &t in &tracks {
            self.tracks[t].last = index;
        }
        let mut members: Vec<Member> = current
            .iter()
            .zip(&tracks)
            .map(|(a, &t)| Member::of(a, t, grid))
            .collect();
        members.sort_by_key(|m| m.track);
        let labelled: usize = current.iter().map(|a| a.starts).sum();
        let (nx, ny) = basins.grid();
        let labels = basins.labels();
        self.steps.push(Step {
            alpha: self.spec.alpha(index),
            members,
            starts: grid,
            not_settled: grid - labelled,
            entropy: basin_entropy(labels, nx, ny, ENTROPY_BOX),
            uncertainty: uncertainty(labels, nx, ny),
            sampled: false,
            seeds: next.seeds,
        });
        self.previous = Some(Previous {
            registry: reg.clone(),
            tracks,
        });
    }

    /// Put the sampled measurement `u` of the last α's uncertainty exponent in place of
    /// the grid's ([`NextAlpha::sample`]).
    pub fn set_sampled(&mut self, u: Result<Uncertainty, NoExponent>) {
        if let Some(step) = self.steps.last_mut() {
            step.uncertainty = u;
            step.sampled = true;
        }
    }

    fn new_track(&mut self, step: usize) -> usize {
        let id = self.tracks.len();
        self.tracks.push(Track {
            id,
            first: step,
            last: step,
        });
        id
    }
}

/// Run the whole continuation on `executor` under `control`; `on_step` hears each α
/// value as it is done. Returns what was done (incomplete if cancelled).
pub fn collect(
    spec: GlobalSpec,
    executor: &Executor,
    control: &Control,
    on_step: &mut dyn FnMut(&Continuation),
) -> Result<Continuation, EngineError> {
    let mut cont = Continuation::new(spec)?;
    let generation = control.generation();
    while !cont.complete() {
        let next = match cont.prepare(&mut |_| !control.is_current(generation)) {
            Some(n) => n?,
            None => break,
        };
        let mut basins = next.basins();
        let summary = executor.run(next.job()?, control, |b| {
            basins.absorb(b.data);
        });
        if summary.cancelled || !basins.complete() {
            break;
        }
        let sampled = next.sample(&basins, executor, control);
        cont.absorb(next, &basins);
        if let Some(u) = sampled {
            cont.set_sampled(u);
        }
        on_step(&cont);
    }
    Ok(cont)
}

/// The attractors of `reg` (a picture of `grid` starts) whose points are run as seeds
/// at the next α, largest basin first: every cycle, and an orbit without a cycle that
/// holds at least [`MIN_SEED_SHARE`] of the starts; at most [`MAX_SEEDED`] in all. An
/// orbit without a cycle is told apart from others by a sample of the cells it visits,
/// and a chaotic transient longer than the transient is such an orbit: one per start,
/// where transients are long, and carried on by seeds they would multiply from α to α.
fn seeded(reg: &Registry, grid: usize) -> Vec<usize> {
    let least = ((MIN_SEED_SHARE * grid as f64).ceil() as usize).max(1);
    reg.ranked()
        .into_iter()
        .filter(|&id| {
            let a = &reg.attractors()[id];
            !a.cycle_points().is_empty() || a.starts >= least
        })
        .take(MAX_SEEDED)
        .collect()
}

/// A ball leaving the table at `phase` with velocity `v` (at least the table's).
fn launch_at(sys: &System, phase: f64, v: f64) -> Option<State> {
    State::launch(sys, 0, phase, v.max(sys.df(phase)), 0.0).ok()
}

/// The points of `a` run as seeds at the next α: up to [`SEED_POINTS`] of a cycle's
/// events, spread along it; an unsettled orbit's last event; a resting ball's place.
/// None for an escape.
fn seed_points(a: &Attractor) -> Vec<(f64, f64)> {
    if a.kind == Kind::Escaping {
        return Vec::new();
    }
    let cycle = a.cycle_points();
    if cycle.is_empty() {
        return a.point.into_iter().collect();
    }
    let n = cycle.len();
    let take = n.min(SEED_POINTS);
    (0..take).map(|s| cycle[s * n / take]).collect()
}

/// The change between an attractor before and its match after, if any.
fn change_of(
    from: Kind,
    from_period: Option<(usize, i64)>,
    to: Kind,
    to_period: Option<(usize, i64)>,
) -> Option<ChangeKind> {
    if from != to {
        return Some(ChangeKind::Kind { from, to });
    }
    match (from_period, to_period) {
        (Some(a), Some(b)) if a != b => Some(ChangeKind::Period { from: a, to: b }),
        _ => None,
    }
}

/// Whether attractors of these kinds may be one attractor at neighbouring α: a
/// resting ball only with a resting ball, an escape only with an escape.
fn compatible(a: Kind, b: Kind) -> bool {
    let special = |k| matches!(k, Kind::Resting | Kind::Escaping);
    if special(a) || special(b) {
        a == b
    } else {
        true
    }
}

/// Pairs (old id, new id), closest first, one to one, within [`MATCH_DISTANCE`].
fn match_sets(old: &[Attractor], new: &[Attractor]) -> Vec<(usize, usize)> {
    let old_sets: Vec<Vec<(f64, f64)>> = old.iter().map(|a| spread(a.points(), MAX_SET)).collect();
    let new_sets: Vec<Vec<(f64, f64)>> = new.iter().map(|a| spread(a.points(), MAX_SET)).collect();
    let mut candidates = Vec::new();
    for (o, a) in old.iter().enumerate() {
        for (c, b) in new.iter().enumerate() {
            if !compatible(a.kind, b.kind) {
                continue;
            }
            let d = if a.kind == Kind::Escaping {
                Some(0.0)
            } else {
                hausdorff_within(&old_sets[o], &new_sets[c], MATCH_DISTANCE)
            };
            if let Some(d) = d {
                candidates.push((d, o, c));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let (mut used_old, mut used_new) = (vec![false; old.len()], vec![false; new.len()]);
    let mut pairs = Vec::new();
    for (_, o, c) in candidates {
        if !used_old[o] && !used_new[c] {
            used_old[o] = true;
            used_new[c] = true;
            pairs.push((o, c));
        }
    }
    pairs
}

/// Pairs (old id, new id) of the old attractors `pairs` left unmatched, each with the
/// new attractor most of its seeds went to, where that one is unmatched too and of a
/// compatible kind: the old attractor's points lie in its basin and nothing else
/// continues either (a sticking cycle whose itinerary changed, say). Where several old
/// attractors' seeds went to one new attractor, one of the same kind goes first, then
/// the one with the larger share of its seeds there.
fn match_by_seeds(
    old: &[Attractor],
    new: &[Attractor],
    old_tracks: &[usize],
    landed: &[(usize, usize)],
    pairs: &[(usize, usize)],
) -> Vec<(usize, usize)> {
    let mut used_new: Vec<bool> = (0..new.len())
        .map(|c| pairs.iter().any(|p| p.1 == c))
        .collect();
    let mut candidates = Vec::new();
    for o in (0..old.len()).filter(|&o| pairs.iter().all(|p| p.0 != o)) {
        let mut votes = vec![0usize; new.len()];
        for &(t, c) in landed {
            if t == old_tracks[o] {
                votes[c] += 1;
            }
        }
        let seeds: usize = votes.iter().sum();
        let best = (0..new.len())
            .filter(|&c| votes[c] > 0)
            .max_by_key(|&c| (votes[c], usize::MAX - c));
        if let Some(c) = best {
            if compatible(old[o].kind, new[c].kind) {
                let share = votes[c] as f64 / seeds as f64;
                candidates.push((old[o].kind != new[c].kind, -share, o, c));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut out = Vec::new();
    for (_, _, o, c) in candidates {
        if !used_new[c] {
            used_new[c] = true;
            out.push((o, c));
        }
    }
    out
}

/// At most `most` points of `set`, evenly spread over it.
fn spread(set: Vec<(f64, f64)>, most: usize) -> Vec<(f64, f64)> {
    if set.len() <= most {
        return set;
    }
    let n = set.len();
    (0..most).map(|s| set[s * n / most]).collect()
}

/// The distance of two points: the larger of the phase distance around the circle and
/// the velocity difference.
fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    phase_distance(a.0, b.0).max((a.1 - b.1).abs())
}

/// The Hausdorff distance of two point sets (∞ if one is empty and the other not).
pub fn hausdorff(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    hausdorff_within(a, b, f64::INFINITY).unwrap_or(f64::INFINITY)
}

/// The Hausdorff distance of two point sets if it is at most `limit`, else None.
///
/// Cheap where sets are far apart or close: the smallest and the largest velocity of
/// two sets within `limit` differ by at most `limit` (each extreme point of one set
/// has a point of the other within `limit`), and the search for a point's nearest
/// neighbour stops at one nearer than the largest distance found so far, which that
/// point cannot raise (Taha and Hanbury's early break).
pub fn hausdorff_within(a: &[(f64, f64)], b: &[(f64, f64)], limit: f64) -> Option<f64> {
    if a.is_empty() || b.is_empty() {
        return (a.is_empty() && b.is_empty()).then_some(0.0);
    }
    let range = |s: &[(f64, f64)]| {
        s.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            })
    };
    let (ra, rb) = (range(a), range(b));
    if (ra.0 - rb.0).abs() > limit || (ra.1 - rb.1).abs() > limit {
        return None;
    }
    let one_way = |x: &[(f64, f64)], y: &[(f64, f64)], mut worst: f64| -> Option<f64> {
        for &p in x {
            let mut nearest = f64::INFINITY;
            for &q in y {
                nearest = nearest.min(distance(p, q));
                if nearest <= worst {
                    break;
                }
            }
            if nearest > limit {
                return None;
            }
            worst = worst.max(nearest);
        }
        Some(worst)
    };
    let there = one_way(a, b, 0.0)?;
    one_way(b, a, there)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hausdorff_distance_wraps_the_phase() {
        let a = [(0.01, 0.5), (0.5, 0.6)];
        let b = [(0.99, 0.5), (0.5, 0.6), (0.51, 0.62)];
        assert!((hausdorff(&a, &b) - 0.02).abs() < 1e-15);
        assert_eq!(hausdorff(&a, &a), 0.0);
        assert_eq!(hausdorff(&a, &[]), f64::INFINITY);
        // Within a limit: the same value, or None beyond it.
        assert_eq!(hausdorff_within(&a, &b, 0.05), Some(hausdorff(&a, &b)));
        assert_eq!(hausdorff_within(&a, &b, 0.01), None);
        // Against a brute-force double loop, on random sets.
        let mut rng = crate::test_rng::Xorshift::new(3);
        for _ in 0..50 {
            let mut set =
                |n| -> Vec<(f64, f64)> { (0..n).map(|_| (rng.next(), rng.next())).collect() };
            let (x, y) = (set(17), set(9));
            let brute = |p: &[(f64, f64)], q: &[(f64, f64)]| {
                p.iter()
                    .map(|&u| {
                        q.iter()
                            .map(|&w| distance(u, w))
                            .fold(f64::INFINITY, f64::min)
                    })
                    .fold(0.0, f64::max)
            };
            let h = brute(&x, &y).max(brute(&y, &x));
            assert_eq!(hausdorff(&x, &y), h);
            assert_eq!(hausdorff_within(&x, &y, h), Some(h));
            assert_eq!(hausdorff_within(&x, &y, h * 0.999), None);
        }
    }

    #[test]
    fn a_cycles_cause_is_read_from_newton_at_the_other_alpha() {
        // fd:0.1, r = 0.8: the (1, 2) solution is stable on (2/9, 0.5014376751)
        // (`fixed`'s closed form). Found at α = 0.5 by a run: at 0.51 Newton's method
        // finds it unstable with a multiplier below −1 (its period doubling between),
        // at 0.5 itself stable (missed, were it not seen), at 0.2 gone (before its
        // birth at 2/9).
        use crate::orbits::fixed::fixed_points;
        use crate::table::Table;
        let at = |a: f64| System::new(Table::fd(0.1).unwrap(), a, 0.8).unwrap();
        let sys = at(0.5);
        let fp = fixed_points(&sys, 2)
            .unwrap()
            .into_iter()
            .find(|p| p.ddf < 0.0)
            .unwrap();
        let start = State::launch(&sys, 0, fp.phase + 1e-3, 1.0, 0.0).unwrap();
        let (found, ..) = settle(&sys, start, &Settle::BASINS, 1, &mut |_| false).unwrap();
        assert_eq!(
            (found.kind, found.events, found.periods),
            (Kind::Periodic, Some(1), Some(2))
        );
        let mut reg = Registry::new();
        let id = reg.assign(&found);
        let a = &reg.attractors()[id];
        match cause(a, &at(0.51)) {
            Cause::Unstable { at, multiplier } => {
                assert_eq!(at, "period doubling");
                assert!(
                    multiplier.im == 0.0 && multiplier.re < -1.0,
                    "{multiplier:?}"
                );
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(cause(a, &sys), Cause::Missed);
        assert_eq!(cause(a, &at(0.2)), Cause::Gone);
    }

    #[test]
    fn changes_name_what_changed() {
        let c = change_of(Kind::Periodic, Some((1, 1)), Kind::Periodic, Some((2, 2)));
        assert_eq!(
            c,
            Some(ChangeKind::Period {
                from: (1, 1),
                to: (2, 2)
            })
        );
        assert_eq!(
            change_of(Kind::Periodic, Some((1, 1)), Kind::Periodic, Some((1, 1))),
            None
        );
        // An undecided length is no change of period.
        assert_eq!(
            change_of(Kind::Sticking, None, Kind::Sticking, Some((8, 9))),
            None
        );
        let c = change_of(Kind::Periodic, Some((4, 4)), Kind::Sticking, None).unwrap();
        assert_eq!(c.name(), "sticking");
        let c = change_of(Kind::Periodic, Some((4, 4)), Kind::Chaotic, None).unwrap();
        assert_eq!(c.name(), "kind");
        assert_eq!(ChangeKind::Death { into: Some(2) }.name(), "merge");
    }
}

#[cfg(test)]
mod runs {
    //! Continuations on the cubic table at r = 0.8 (small grids: seconds in a debug
    //! build), checked against the (1, k) and (2, 2k) solutions' closed forms and
    //! Newton solutions, and against `basins` on the same grid.
    use super::*;
    use crate::attractors::basins;
    use crate::orbits::fixed::stability_window;
    use crate::orbits::two_cycle::two_cycle;
    use crate::table::Table;

    fn spec(lo: f64, hi: f64, steps: usize, n: usize) -> GlobalSpec {
        let sys = System::new(Table::fd(1.0).unwrap(), hi, 0.8).unwrap();
        GlobalSpec {
            w_max: crate::attractors::default_w_max(&sys),
            sys,
            lo,
            hi,
            steps,
            nx: n,
            ny: n,
            settle: Settle::BASINS,
            stop_at_known: true,
            sampled_starts: 0,
        }
    }

    fn run(spec: GlobalSpec) -> Continuation {
        collect(
            spec,
            &Executor::new(2).unwrap(),
            &Control::new(),
            &mut |_| {},
        )
        .unwrap()
    }

    #[test]
    fn one_stable_cycle_takes_every_start_with_no_basin_entropy() {
        // Past the (1, 1) solution's period doubling every start of the box lands on
        // the (2, 2) cycle: the one attractor, fraction 1, S_b = 0 and no boundary. Its
        // point is an impact of the (2, 2) solution found by Newton's method.
        let cont = run(spec(0.5, 0.54, 3, 20));
        assert_eq!(cont.tracks().len(), 1, "{:?}", cont.steps());
        assert!(cont.changes().is_empty());
        for s in cont.steps() {
            let m = &s.members[..];
            assert_eq!(m.len(), 1);
            assert_eq!((m[0].kind, m[0].period()), (Kind::Periodic, Some((2, 2))));
            assert_eq!((m[0].starts, m[0].fraction), (400, 1.0));
            let e = s.entropy.unwrap();
            assert_eq!((e.s_b, e.s_bb, e.boundary_boxes), (0.0, 0.0, 0));
            let sys = System::new(Table::fd(1.0).unwrap(), s.alpha, 0.8).unwrap();
            let tc = two_cycle(&sys, 1).unwrap();
            let (t, v) = m[0].point.unwrap();
            let near = |pt: f64, pv: f64| {
                crate::time::phase_distance(t, pt) < 1e-9 && (v - pv).abs() < 1e-9
            };
            assert!(
                near(tc.phase0, tc.v0) || near(tc.phase1, tc.v1),
                "{t} {v} {tc:?}"
            );
        }
    }

    #[test]
    fn the_period_doubling_is_seen_within_one_step_of_its_closed_form() {
        // The (1, 1) solution's α_PD from its closed-form stability window; the track
        // that holds (1, 1) holds (2, 2) from the first α past it.
        let pd = stability_window(&Table::fd(1.0).unwrap(), 0.8, 1)
            .unwrap()
            .unwrap()
            .alpha_pd()
            .unwrap();
        let cont = run(spec(0.4805, 0.4875, 8, 12));
        let steps = cont.steps();
        let doubling: Vec<&Change> = cont
            .changes()
            .iter()
            .filter(|c| {
                c.what
                    == ChangeKind::Period {
                        from: (1, 1),
                        to: (2, 2),
                    }
            })
            .collect();
        assert_eq!(doubling.len(), 1, "{:?}", cont.changes());
        let c = doubling[0];
        assert!(
            steps[c.step - 1].alpha < pd && pd < steps[c.step].alpha,
            "{pd} {c:?}"
        );
    }

    #[test]
    fn fractions_at_an_alpha_are_the_basins_pictures() {
        // Coexistence on the cubic table at α = 0.47: the same grid and box as
        // `basins` give the same starts per attractor (seeds are not counted).
        let cont = run(spec(0.465, 0.47, 2, 30));
        let last = cont.steps().last().unwrap();
        let b = basins::collect(
            &basins::BasinSpec {
                nx: 30,
                ny: 30,
                ..basins::BasinSpec::new(System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap())
            },
            &Executor::new(2).unwrap(),
        )
        .unwrap();
        let mut ours: Vec<(Kind, usize)> =
            last.members.iter().map(|m| (m.kind, m.starts)).collect();
        let mut theirs: Vec<(Kind, usize)> = b
            .registry()
            .attractors()
            .iter()
            .map(|a| (a.kind, a.starts))
            .collect();
        ours.retain(|m| m.1 > 0);
        ours.sort();
        theirs.sort();
        assert!(ours.len() >= 2, "{ours:?}");
        assert_eq!(ours.len(), theirs.len(), "{ours:?} {theirs:?}");
        for (a, b) in ours.iter().zip(&theirs) {
            assert_eq!(a.0, b.0);
            assert!(a.1.abs_diff(b.1) <= 9, "{ours:?} {theirs:?}");
        }
        let total: usize = last.members.iter().map(|m| m.starts).sum::<usize>() + last.not_settled;
        assert_eq!(total, 900);
    }

    #[test]
    fn halving_the_step_finds_the_same_changes() {
        // Every change of a run with step h is found with step h / 2 in the same
        // interval of the coarse grid, and the other way round; attractors are paired
        // at the shared α values by their kind and starts (the pictures there are the
        // same grid).
        let coarse = run(spec(0.478, 0.49, 7, 12));
        let fine = run(spec(0.478, 0.49, 13, 12));
        // Tracks paired by the pictures at shared α.
        let mut pair = std::collections::HashSet::new();
        for (i, s) in coarse.steps().iter().enumerate() {
            let f = &fine.steps()[2 * i];
            assert_eq!(s.alpha, f.alpha);
            for m in &s.members {
                let twin = f
                    .members
                    .iter()
                    .find(|x| x.kind == m.kind && x.starts == m.starts && x.period() == m.period());
                let twin = twin.unwrap_or_else(|| panic!("{m:?} in {:?}", f.members));
                pair.insert((m.track, twin.track));
            }
        }
        let interval = |fine_step: usize| fine_step.div_ceil(2);
        // A sticking cycle's itinerary changes from one α to the next, and a length
        // double precision leaves open hides a change: periods of sticking cycles are
        // samples, not events to compare.
        let sampled = |cont: &Continuation, c: &Change| {
            matches!(c.what, ChangeKind::Period { .. })
                && cont.steps()[c.step]
                    .members
                    .iter()
                    .any(|m| m.track == c.track && m.kind == Kind::Sticking)
        };
        let changes = |cont: &Continuation| -> Vec<Change> {
            cont.changes()
                .iter()
                .filter(|c| !sampled(cont, c))
                .cloned()
                .collect()
        };
        let (coarse_changes, fine_changes) = (changes(&coarse), changes(&fine));
        assert!(coarse_changes.len() >= 3, "{coarse_changes:?}");
        for c in &coarse_changes {
            let seen = fine_changes.iter().any(|f| {
                f.what.name() == c.what.name()
                    && pair.contains(&(c.track, f.track))
                    && interval(f.step) == c.step
            });
            assert!(seen, "{c:?} not in {fine_changes:?}");
        }
        for f in &fine_changes {
            let seen = coarse_changes.iter().any(|c| {
                f.what.name() == c.what.name()
                    && pair.contains(&(c.track, f.track))
                    && interval(f.step) == c.step
            });
            // A change undone within one coarse interval is not seen from its ends: an
            // attractor gone and one born (the same, found again) or a change and its
            // reverse.
            let found_again = |a: &ChangeKind, b: &ChangeKind| {
                matches!(
                    (a, b),
                    (ChangeKind::Birth, ChangeKind::Death { .. })
                        | (ChangeKind::Death { .. }, ChangeKind::Birth)
                )
            };
            let undone = fine_changes.iter().any(|g| {
                g.step != f.step
                    && interval(g.step) == interval(f.step)
                    && (g.track == f.track || found_again(&f.what, &g.what))
            });
            assert!(seen || undone, "{f:?} not in {coarse_changes:?}");
        }
    }
}
