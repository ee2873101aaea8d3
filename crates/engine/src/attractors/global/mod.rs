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
//!    the resting balls only with the resting balls and the escapes only with the
//!    escapes (one class each in a picture, wherever the balls rest: always a pair). An
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
//!
//! A window may be computed in parts ([`Continuation::part`]), each starting one α
//! value before its own, and the parts joined at those values
//! ([`Continuation::join`]).
//!
//! Here the specification, the pictures per α and the advance from one α to the next
//! (seeds, the early stop's known cycles, the statistics); `matching.rs` which
//! attractor is which from one α to the next; `changes.rs` what changed and why;
//! `join.rs` parts joined into the whole;
//! `runs.rs` the continuation's tests against closed forms and `basins`.

mod changes;
mod join;
mod matching;

pub use changes::{Cause, Change, ChangeKind};
pub use join::Join;
pub use matching::{hausdorff, hausdorff_within, tracks_of};

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
use changes::{cause, change_of};
use matching::{match_by_seeds, match_sets, spread};

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

/// An attractor followed along α.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Track {
    /// Its number (0-based, in order of appearance).
    pub id: usize,
    /// The first α value it is seen at (its place in [`Continuation::steps`]).
    pub first: usize,
    /// The last α value it is seen at (its place in [`Continuation::steps`]).
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
    /// filled picture, whose attractors the samples' are numbered after);
    /// `on_sample` hears how many samples are done as they come in.
    pub fn sample(
        &self,
        basins: &Basins,
        executor: &Executor,
        control: &Control,
        on_sample: &mut dyn FnMut(usize),
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
            on_sample,
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
    /// The α values (indices) it computes: `from..to` (the whole window, or a part of
    /// it: [`Continuation::part`]).
    from: usize,
    to: usize,
    steps: Vec<Step>,
    changes: Vec<Change>,
    tracks: Vec<Track>,
    previous: Option<Previous>,
}

impl Continuation {
    /// Validate `spec`; nothing computed yet.
    pub fn new(spec: GlobalSpec) -> Result<Continuation, EngineError> {
        let steps = spec.steps;
        Continuation::part(spec, 0..steps)
    }

    /// Validate `spec`; the continuation of the α values `values` only (indices into
    /// the window), started afresh at the first of them: a part of a run, to be joined
    /// to the others by [`Continuation::join`].
    pub fn part(
        spec: GlobalSpec,
        values: std::ops::Range<usize>,
    ) -> Result<Continuation, EngineError> {
        spec.validate()?;
        if values.is_empty() || values.end > spec.steps {
            return Err(EngineError::InvalidParameter {
                name: "α values".into(),
                value: format!("{}..{}", values.start, values.end),
                range: format!("a non-empty range within 0..{}", spec.steps).into(),
            });
        }
        Ok(Continuation {
            spec,
            from: values.start,
            to: values.end,
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

    /// The α values it computes (indices into the window; `steps()[i]` is value
    /// `values().start + i`).
    pub fn values(&self) -> std::ops::Range<usize> {
        self.from..self.to
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
        self.from + self.steps.len() == self.to
    }

    /// The next α value: its picture, with the previous attractors' seeds run to their
    /// attractors here. None when complete or when `cancelled` stops a seed's run.
    pub fn prepare(
        &self,
        cancelled: &mut dyn FnMut(u64) -> bool,
    ) -> Option<Result<NextAlpha, EngineError>> {
        let index = self.from + self.steps.len();
        if index >= self.to {
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
        assert_eq!(
            next.index,
            self.from + self.steps.len(),
            "α values in order"
        );
        // Changes and tracks count α values from the first computed here.
        let index = next.index - self.from;
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
            let before = self.spec.basins(next.index - 1).map(|b| b.sys);
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
            alpha: self.spec.alpha(next.index),
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
        let sampled = next.sample(&basins, executor, control, &mut |_| {});
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

#[cfg(test)]
mod runs;
