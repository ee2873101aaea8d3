//! Where a chaotic attractor is destroyed or jumps in size, and through which saddle: a
//! boundary or interior crisis located by bisection in α and named by its saddle.
//!
//! At a boundary crisis an attractor touches the stable manifold of a saddle on its
//! basin boundary; past it, orbits on the attractor's remnant wander for a while, come
//! near the boundary, follow the stable manifold to the saddle and leave along the
//! saddle's other unstable branch, to another attractor. This module measures exactly
//! that, with the exact map:
//!
//! * **The attractor's neighbourhood.** At the last α where the attractor is seen (`lo`)
//!   an orbit from its point runs [`CrisisSpec::warmup`] events, then
//!   [`CrisisSpec::sample`] more, whose points (t̂, v) mark cells of side
//!   [`CrisisSpec::radius`]; the neighbourhood is those cells and the cells around them.
//!   [`CrisisSpec::runs`] states spread along the sampled orbit are the starts.
//! * **Stay or leave.** At an α, each start runs up to [`CrisisSpec::events`] events; it
//!   *leaves* when an event falls outside the neighbourhood (or sticks there). An
//!   attractor whose orbits all stay is there; one that any start leaves is past its
//!   crisis (a start on the attractor does not leave the neighbourhood of an attractor
//!   that still exists).
//! * **Bisection.** `lo` must be a value where every start stays (else `lo` moves down
//!   by the bracket's width, a few times) and `hi` one where a start leaves; the bracket
//!   is halved until it is at most [`CrisisSpec::tolerance`] wide. Staying is evidence,
//!   not proof: just before the crisis an orbit may need more than the events given to
//!   leave. The output says how many events each start stayed.
//! * **The saddle.** The path of a leaving orbit, from its last event in the
//!   neighbourhood on, shadows the saddle it leaves through, a saddle cycle at `hi`
//!   (real multipliers, one outside and one inside the unit circle): the saddles the
//!   path passes ([`saddles`](super::saddles)). Of the saddles found, those within [`EMBEDDED`] of
//!   the attractor's sample at `lo` lie on the attractor (its cascade's cycles). Which
//!   of the others names the crisis is decided by the tangency a boundary crisis is
//!   ([`crate::attractors::tangency`]): the unstable manifold of the shortest embedded
//!   saddle against the stable manifolds of the [`TANGENCY_CANDIDATES`] saddles nearest
//!   the attractor; those it crosses already at `lo` are in the attractor's closure, and
//!   of the rest the one it first crosses as α rises names the crisis. Where no saddle
//!   is embedded or none is crossed, the nearest the attractor does. Reported besides:
//!   the saddle's distance from the attractor's sample at `lo`, the leaving orbits'
//!   closest pass, and the sample's distance from its stable manifold. The choice is
//!   evidence, not proof: the basin boundary holds many saddles, whose stable manifolds
//!   lie close together, and finite manifolds reach only their first folds.
//!
//! [`crises`] does this for every crisis a continuation along α records, and for every
//! chaotic attractor that jumps in size there ([`jumps`](super::jumps)): an interior
//! crisis, where the attractor goes on, larger. Its neighbourhood is then made of
//! cells a third of the jump ([`jump_radius`]), so that the orbits that reach the new
//! part leave it; the rest is the same.

use crate::attractors::global::{Cause, ChangeKind, Continuation};
use crate::attractors::jumps::{jumps, sizes, Jump};
use crate::attractors::saddles::{saddles_on, same_cycle, to_cycle};
use crate::attractors::tangency::{
    continued, first_crossing, to_points, TOUCH_LENGTH, UNSTABLE_LENGTH,
};
use crate::impact::Solver;
use crate::map::{EventKind, ImpactMap, State};
use crate::orbits::manifold::Kind;
use crate::orbits::periodic::CyclePoint;
use crate::system::System;
use std::collections::HashSet;

/// Events of a leaving orbit's path kept after its last event in the neighbourhood.
const PATH_EVENTS: usize = 64;

/// How a crisis is located.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrisisSpec {
    /// Starts on the attractor.
    pub runs: usize,
    /// Events each start runs at an α before it is taken to stay.
    pub events: u64,
    /// Width of the final bracket in α.
    pub tolerance: f64,
    /// Side of the cells of (t̂, v) that make the attractor's neighbourhood.
    pub radius: f64,
    /// Events run before the attractor is sampled.
    pub warmup: u64,
    /// Events sampled.
    pub sample: u64,
}

impl Default for CrisisSpec {
    fn default() -> Self {
        CrisisSpec {
            runs: 4,
            events: 2_000_000,
            tolerance: 1e-6,
            radius: 0.02,
            warmup: 10_000,
            sample: 200_000,
        }
    }
}

/// The saddle a crisis happens through.
#[derive(Clone, Debug, PartialEq)]
pub struct CrisisSaddle {
    /// The cycle at the upper end of the bracket.
    pub cycle: CyclePoint,
    /// The closest a leaving orbit's path came to one of its points (in (t̂, v)).
    pub passes: f64,
    /// The least distance from the attractor's sample at the lower end to the saddle's
    /// points there.
    pub outside_by: f64,
    /// The least distance from the attractor's sample to the saddle's stable manifold
    /// (its piece through each point of the cycle, each branch [`TOUCH_LENGTH`] long):
    /// (α, distance) where the attractor was first sampled below the bracket (or one
    /// continuation step below it), then at its lower end; a value is left out where
    /// the distance exceeds 0.02.
    /// At the crisis the attractor touches the stable manifold, so the distance falls
    /// towards 0 as α nears it.
    pub to_stable_manifold: Vec<(f64, f64)>,
    /// Where the attractor's unstable manifold first crosses this saddle's stable
    /// manifold as α rises (the saddle is then the one chosen so); None where no saddle
    /// embedded in the attractor or no crossing was found, and the saddle is the one
    /// nearest the attractor.
    pub tangency: Option<Tangency>,
}

/// The tangency a saddle was chosen by: the unstable manifold of a saddle embedded in
/// the attractor ([`UNSTABLE_LENGTH`] per branch) against the stable manifolds of the
/// [`TANGENCY_CANDIDATES`] saddles nearest the attractor ([`TOUCH_LENGTH`] per branch),
/// both through every point of their cycles.
#[derive(Clone, Debug, PartialEq)]
pub struct Tangency {
    /// The embedded saddle, at the lower end.
    pub embedded: CyclePoint,
    /// The first crossing of any candidate's stable manifold: apart at `.0`, crossed
    /// at `.1` (bisected to [`TANGENCY_TOLERANCE`]).
    pub between: (f64, f64),
    /// The distance between the two manifolds at the lower end of the crisis (None:
    /// beyond 0.02).
    pub apart: Option<f64>,
    /// Other candidates crossed first in the same bracket, (n, k) each.
    pub also: Vec<(usize, u32)>,
    /// Candidates tried.
    pub tried: usize,
    /// Of them, those whose stable manifold the unstable manifold crosses already at
    /// the lower end: in the attractor's closure, not on its boundary.
    pub in_closure: usize,
}

/// Saddles nearest the attractor whose stable manifolds are tried for a tangency.
pub const TANGENCY_CANDIDATES: usize = 4;
/// Width of the bracket of the first crossing.
pub const TANGENCY_TOLERANCE: f64 = 1e-8;
/// The first crossing is looked for up to this many crisis-bracket widths above it.
pub const TANGENCY_REACH: f64 = 128.0;

/// A located crisis.
#[derive(Clone, Debug, PartialEq)]
pub struct Crisis {
    /// The bracket: at `lo` every start stayed, at `hi` a start left.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// Events every start stayed at `lo`.
    pub stayed: u64,
    /// The side of the cells of the attractor's neighbourhood ([`CrisisSpec::radius`]).
    pub radius: f64,
    /// At `hi`: after how many events each start left (None: stayed).
    pub left_after: Vec<Option<u64>>,
    /// What a leaving orbit did next: the kind of its first event outside (a stick, or
    /// an impact).
    pub left_by: EventKind,
    /// The saddle, where one was found.
    pub saddle: Option<CrisisSaddle>,
    /// Saddle cycles the leaving orbits passed (the saddle is one of them).
    pub considered: usize,
    /// α values evaluated (each up to runs × events events).
    pub evaluations: usize,
}

/// Why no crisis was located.
#[derive(Clone, Debug, PartialEq)]
pub enum NoCrisis {
    /// The attractor's orbit sticks or halts while it is sampled, at `lo` and at every
    /// α tried below it: not a chaotic attractor of impacts there.
    NotAnAttractor,
    /// Starts leave at every α tried down to this one.
    LeavesBelow(f64),
    /// No start leaves at `hi` within the events given.
    StaysAt(f64),
    /// Its orbits leave at every α down to a crisis located already, of this
    /// attractor (a track number): what was seen is a transient on that attractor's
    /// remnant, not an attractor of its own.
    Remnant(usize),
    /// The start is not a launch.
    BadStart,
    /// Cancelled.
    Cancelled,
}

impl std::fmt::Display for NoCrisis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoCrisis::NotAnAttractor => f.write_str("its orbit does not stay on an attractor of impacts at the lower end"),
            NoCrisis::LeavesBelow(a) => write!(f, "orbits leave it at every α tried, down to {a}"),
            NoCrisis::StaysAt(a) => write!(f, "no orbit leaves it at {a} within the events given"),
            NoCrisis::Remnant(t) => write!(f, "its orbits leave at every α down to the crisis of attractor {}, located at lower α: a transient on that attractor's remnant", t + 1),
            NoCrisis::BadStart => f.write_str("its point is not a launch"),
            NoCrisis::Cancelled => f.write_str("cancelled"),
        }
    }
}

/// The attractor's neighbourhood: occupied cells of side `size` and their neighbours.
struct Neighbourhood {
    cells: HashSet<(i64, i64)>,
    size: f64,
}

impl Neighbourhood {
    fn key(&self, phase: f64, v: f64) -> (i64, i64) {
        (
            (phase / self.size).floor() as i64,
            (v / self.size).floor() as i64,
        )
    }

    fn mark(&mut self, phase: f64, v: f64) {
        let (a, b) = self.key(phase, v);
        let n = (1.0 / self.size).ceil() as i64;
        for da in -1..=1 {
            for db in -1..=1 {
                // Phases wrap around the period.
                self.cells.insert(((a + da).rem_euclid(n), b + db));
            }
        }
    }

    fn contains(&self, phase: f64, v: f64) -> bool {
        let (a, b) = self.key(phase, v);
        let n = (1.0 / self.size).ceil() as i64;
        self.cells.contains(&(a.rem_euclid(n), b))
    }
}

/// What one start did at one α.
enum Run {
    Stayed,
    Left {
        after: u64,
        by: EventKind,
        /// The events from the last one inside on.
        path: Vec<(i64, f64, f64)>,
    },
}

fn run(
    sys: &System,
    start: State,
    hood: &Neighbourhood,
    events: u64,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Run> {
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    let mut last_inside = (start.period(), start.phase(), start.v());
    for i in 0..events {
        if i % 65_536 == 0 && cancelled(i) {
            return None;
        }
        let Ok(e) = map.step() else {
            return Some(Run::Left {
                after: i,
                by: EventKind::Stick,
                path: vec![last_inside],
            });
        };
        let inside = e.kind == EventKind::Impact && hood.contains(e.phase, e.v);
        if inside {
            last_inside = (e.period, e.phase, e.v);
            continue;
        }
        let mut path = vec![last_inside, (e.period, e.phase, e.v)];
        for _ in 0..PATH_EVENTS {
            match map.step() {
                Ok(f) if f.kind == EventKind::Impact => path.push((f.period, f.phase, f.v)),
                _ => break,
            }
        }
        return Some(Run::Left {
            after: i,
            by: e.kind,
            path,
        });
    }
    Some(Run::Stayed)
}

fn at(sys: &System, alpha: f64) -> System {
    let mut s = sys.clone();
    s.set_alpha(alpha)
        .expect("α inside the bracket the caller checked");
    s
}

/// An attractor sampled: its neighbourhood, its points (t̂, v) and the starts spread
/// along them.
type Sampled = (Neighbourhood, Vec<(f64, f64)>, Vec<State>);

/// The attractor through `point` at the α of `sys`, sampled.
fn sample_at(
    sys: &System,
    point: (f64, f64),
    spec: &CrisisSpec,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Result<Sampled, NoCrisis> {
    let start = State::launch(sys, 0, point.0, point.1, 0.0).map_err(|_| NoCrisis::BadStart)?;
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    let mut hood = Neighbourhood {
        cells: HashSet::new(),
        size: spec.radius,
    };
    let mut sample: Vec<(f64, f64)> = Vec::with_capacity(spec.sample as usize);
    let mut starts = Vec::with_capacity(spec.runs);
    let gap = (spec.sample / spec.runs.max(1) as u64).max(1);
    for i in 0..spec.warmup + spec.sample {
        if i % 65_536 == 0 && cancelled(i) {
            return Err(NoCrisis::Cancelled);
        }
        let e = map.step().map_err(|_| NoCrisis::NotAnAttractor)?;
        if e.kind != EventKind::Impact {
            return Err(NoCrisis::NotAnAttractor);
        }
        if i >= spec.warmup {
            hood.mark(e.phase, e.v);
            sample.push((e.phase, e.v));
            if (i - spec.warmup).is_multiple_of(gap) && starts.len() < spec.runs {
                starts.push(*map.state());
            }
        }
    }
    Ok((hood, sample, starts))
}

/// Locate the crisis of the attractor through `point` (a launch (t̂, v) on it at
/// `lo`), not seen at `hi` (> lo), for the table and r of `sys`.
pub fn locate(
    sys: &System,
    point: (f64, f64),
    lo: f64,
    hi: f64,
    spec: &CrisisSpec,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Result<Crisis, NoCrisis> {
    locate_above(sys, point, lo, hi, None, spec, cancelled)
}

/// [`locate`], the bracket not moved below `floor` (the upper end of a crisis located
/// already, and its track).
fn locate_above(
    sys: &System,
    point: (f64, f64),
    lo: f64,
    hi: f64,
    floor: Option<(f64, usize)>,
    spec: &CrisisSpec,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Result<Crisis, NoCrisis> {
    let below_floor = |x: f64| {
        floor
            .filter(|&(f, _)| x < f)
            .map(|(_, t)| NoCrisis::Remnant(t))
    };
    // Sample the attractor at lo; where its orbit leaves while it is sampled, lo is
    // past the crisis already: move the bracket down by its width.
    let (mut lo, mut hi) = (lo, hi);
    let width = hi - lo;
    let mut tries = 0;
    let (hood, sample, starts) = loop {
        match sample_at(&at(sys, lo), point, spec, cancelled) {
            Err(NoCrisis::NotAnAttractor) if tries < 8 && lo - width > 0.0 => {
                if let Some(e) = below_floor(lo - width) {
                    return Err(e);
                }
                tries += 1;
                hi = lo;
                lo -= width;
            }
            other => break other?,
        }
    };
    let sampled_at = lo;
    let mut evaluations = 0;
    // Evaluate an α: every start's run.
    let evaluate = |alpha: f64,
                    evaluations: &mut usize,
                    cancelled: &mut dyn FnMut(u64) -> bool|
     -> Result<Vec<Run>, NoCrisis> {
        *evaluations += 1;
        let s = at(sys, alpha);
        starts
            .iter()
            .map(|st| {
                // The same launch on the system at this α.
                let st = State::launch(&s, st.period(), st.phase(), st.v(), 0.0)
                    .map_err(|_| NoCrisis::BadStart)?;
                run(&s, st, &hood, spec.events, cancelled).ok_or(NoCrisis::Cancelled)
            })
            .collect()
    };
    let left = |runs: &[Run]| runs.iter().any(|r| matches!(r, Run::Left { .. }));
    // lo must hold the attractor.
    while left(&evaluate(lo, &mut evaluations, cancelled)?) {
        tries += 1;
        if let Some(e) = below_floor(lo - width) {
            return Err(e);
        }
        if tries > 8 || lo - width <= 0.0 {
            return Err(NoCrisis::LeavesBelow(lo));
        }
        hi = lo;
        lo -= width;
    }
    let mut upper = evaluate(hi, &mut evaluations, cancelled)?;
    if !left(&upper) {
        return Err(NoCrisis::StaysAt(hi));
    }
    while hi - lo > spec.tolerance {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let runs = evaluate(mid, &mut evaluations, cancelled)?;
        if left(&runs) {
            hi = mid;
            upper = runs;
        } else {
            lo = mid;
        }
    }
    let left_after = upper
        .iter()
        .map(|r| match r {
            Run::Left { after, .. } => Some(*after),
            Run::Stayed => None,
        })
        .collect();
    let left_by = upper
        .iter()
        .find_map(|r| match r {
            Run::Left { by, .. } => Some(*by),
            Run::Stayed => None,
        })
        .unwrap_or(EventKind::Impact);
    let sys_hi = at(sys, hi);
    // The attractor at the final lo (where the bisection moved it up), else the first
    // sample.
    let first_sample = sample;
    let resampled = (lo > sampled_at)
        .then(|| sample_at(&at(sys, lo), point, spec, cancelled).ok())
        .flatten();
    let sample = resampled.as_ref().map_or(&first_sample, |x| &x.1);
    // Every saddle the leaving orbits pass, with the closest pass, continued to lo and
    // measured against the attractor's sample there.
    let mut candidates: Vec<(CyclePoint, f64)> = Vec::new();
    for r in &upper {
        if let Run::Left { path, .. } = r {
            for (c, passes) in saddles_on(&sys_hi, path) {
                match candidates.iter_mut().find(|(f, _)| same_cycle(f, &c)) {
                    Some(f) => f.1 = f.1.min(passes),
                    None => candidates.push((c, passes)),
                }
            }
        }
    }
    let at_lo = at(sys, lo);
    let considered = candidates.len();
    // Each at lo, with its distance from the attractor's sample there.
    let mut placed: Vec<(CyclePoint, f64, CyclePoint, f64)> = candidates
        .into_iter()
        .filter_map(|(c, passes)| {
            let cl = continued(&at_lo, &c)?;
            let outside_by = to_cycle(&cl, sample.iter().copied());
            Some((c, passes, cl, outside_by))
        })
        .collect();
    placed.sort_by(|a, b| a.3.total_cmp(&b.3));
    let split = placed.partition_point(|p| p.3 < EMBEDDED);
    let (embedded, boundary) = placed.split_at(split);
    let tangency = embedded
        .iter()
        .min_by_key(|e| e.2.n)
        .filter(|_| !boundary.is_empty())
        .and_then(|e| {
            let tried = &boundary[..boundary.len().min(TANGENCY_CANDIDATES)];
            let cands: Vec<CyclePoint> = tried.iter().map(|b| b.2.clone()).collect();
            let x = first_crossing(
                &|a| at(sys, a),
                &e.2,
                UNSTABLE_LENGTH,
                &cands,
                (lo, hi),
                TANGENCY_REACH * (hi - lo),
                TANGENCY_TOLERANCE,
            )?;
            // Of those crossed first, the shortest cycle, then the nearest.
            let chosen = *x.first.iter().min_by_key(|&&i| tried[i].2.n)?;
            let t = Tangency {
                embedded: e.2.clone(),
                between: x.between,
                apart: x.apart[chosen],
                also: x
                    .first
                    .iter()
                    .filter(|&&i| i != chosen)
                    .map(|&i| (tried[i].2.n, tried[i].2.k))
                    .collect(),
                tried: tried.len(),
                in_closure: x.in_closure.len(),
            };
            Some((chosen, t))
        });
    let saddle = match tangency {
        Some((i, t)) => Some((i, Some(t))),
        None => (!boundary.is_empty()).then_some((0, None)),
    }
    .map(|(i, tangency)| {
        let (c, passes, _, outside_by) = boundary[i].clone();
        CrisisSaddle {
            cycle: c,
            passes,
            outside_by,
            to_stable_manifold: Vec::new(),
            tangency,
        }
    });
    // How close the attractor comes to the saddle's stable manifold, at lo and one
    // continuation step below.
    let saddle = saddle.map(|mut s| {
        let at_alpha = |alpha: f64, sample: &[(f64, f64)]| {
            let sys_a = at(sys, alpha);
            let cl = continued(&sys_a, &s.cycle)?;
            to_points(&sys_a, &cl, Kind::Stable, TOUCH_LENGTH, sample).map(|d| (alpha, d))
        };
        let mut touches = Vec::new();
        if lo > sampled_at {
            touches.extend(at_alpha(sampled_at, &first_sample));
        } else if lo - width > 0.0 {
            if let Ok((_, below, _)) = sample_at(&at(sys, lo - width), point, spec, cancelled) {
                touches.extend(at_alpha(lo - width, &below));
            }
        }
        touches.extend(at_alpha(lo, sample));
        s.to_stable_manifold = touches;
        s
    });
    Ok(Crisis {
        lo,
        hi,
        stayed: spec.events,
        radius: spec.radius,
        left_after,
        left_by,
        saddle,
        considered,
        evaluations,
    })
}

/// What the continuation saw that may be a crisis.
#[derive(Clone, Debug, PartialEq)]
pub enum Sighting {
    /// A chaotic attractor gone between two values with no local bifurcation
    /// ([`Cause::Crisis`]): destroyed, a boundary crisis. Its place in
    /// [`Continuation::changes`].
    Destroyed {
        /// The change.
        change: usize,
    },
    /// A chaotic attractor that jumps in size ([`jumps`](super::jumps)), going on: an
    /// interior (or merging) crisis.
    Jump(Jump),
}

impl Sighting {
    /// Its name in every output: destroyed, jump.
    pub fn name(&self) -> &'static str {
        match self {
            Sighting::Destroyed { .. } => "destroyed",
            Sighting::Jump(_) => "jump",
        }
    }
}

/// A crisis of a continuation, located (or why not).
#[derive(Clone, Debug, PartialEq)]
pub struct Located {
    /// The track of the attractor.
    pub track: usize,
    /// The first α value past it: its place in [`Continuation::steps`].
    pub step: usize,
    /// What was seen.
    pub sighting: Sighting,
    /// The crisis.
    pub result: Result<Crisis, NoCrisis>,
}

/// The side of the neighbourhood's cells for a jump of `grows_by`: a third of it (an
/// event outside the old attractor's cells and their neighbours is then in the new
/// part), at most the spec's, and at least [`MIN_JUMP_RADIUS`].
pub fn jump_radius(grows_by: f64, spec: &CrisisSpec) -> f64 {
    (grows_by / 3.0).clamp(MIN_JUMP_RADIUS, spec.radius.max(MIN_JUMP_RADIUS))
}

/// The smallest cells an attractor's neighbourhood is made of for a jump: smaller ones
/// are not covered by the sample (its gaps would count as leaving).
pub const MIN_JUMP_RADIUS: f64 = 5e-4;

/// Locate every crisis `cont` records: each chaotic attractor gone between two α values
/// with no local bifurcation ([`Cause::Crisis`]), from its point at the last value it
/// is seen at; and each chaotic attractor that jumps in size ([`jumps`](super::jumps)),
/// from its point at the value below the jump, with the neighbourhood's cells matched
/// to the jump ([`jump_radius`]). In order of α. `starting(i, n, track, step,
/// sighting)` is told before the i-th of n.
pub fn crises(
    cont: &Continuation,
    spec: &CrisisSpec,
    starting: &mut dyn FnMut(usize, usize, usize, usize, &Sighting),
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Vec<Located> {
    let steps = cont.steps();
    let mut todo: Vec<(usize, usize, Sighting)> = cont
        .changes()
        .iter()
        .enumerate()
        .filter(|(_, c)| {
            matches!(c.what, ChangeKind::Death { .. }) && c.cause == Some(Cause::Crisis)
        })
        .map(|(i, c)| (c.track, c.step, Sighting::Destroyed { change: i }))
        .collect();
    let sizes = sizes(cont, spec.warmup, spec.sample, cancelled);
    todo.extend(
        jumps(&sizes)
            .into_iter()
            .map(|j| (j.track, j.step, Sighting::Jump(j))),
    );
    todo.sort_by_key(|t| t.1);
    let sys = &cont.spec().sys;
    let mut out: Vec<Located> = Vec::new();
    for (j, (track, step, sighting)) in todo.iter().enumerate() {
        let (track, step) = (*track, *step);
        starting(j, todo.len(), track, step, sighting);
        let (lo, hi) = (steps[step - 1].alpha, steps[step].alpha);
        let point = steps[step - 1]
            .members
            .iter()
            .find(|m| m.track == track)
            .and_then(|m| m.point);
        let result = match (point, sighting) {
            (None, _) => Err(NoCrisis::BadStart),
            (Some(p), Sighting::Destroyed { .. }) => {
                // The nearest attractor destroyed below this one.
                let floor = out
                    .iter()
                    .filter(|l| matches!(l.sighting, Sighting::Destroyed { .. }))
                    .filter_map(|l| l.result.as_ref().ok().map(|c| (c.hi, l.track)))
                    .filter(|&(h, _)| h <= lo)
                    .max_by(|a, b| a.0.total_cmp(&b.0));
                locate_above(sys, p, lo, hi, floor, spec, cancelled)
            }
            (Some(p), Sighting::Jump(jump)) => {
                let matched = CrisisSpec {
                    radius: jump_radius(jump.grows_by, spec),
                    ..*spec
                };
                locate_above(sys, p, lo, hi, None, &matched, cancelled)
            }
        };
        out.push(Located {
            track,
            step,
            sighting: sighting.clone(),
            result,
        });
    }
    out
}

/// Saddles closer than this (in (t̂, v)) to the attractor's sample at the lower end lie
/// on the attractor (embedded in it, as the cycles of its cascade are), not on its
/// basin boundary.
pub const EMBEDDED: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    #[test]
    fn the_two_band_attractor_of_the_sine_is_destroyed_at_a_saddle_on_its_tips() {
        // sin 2πt, r = 0.8: after the (1, 1) cascade a two-band chaotic attractor lives
        // around the (1, 1) flip saddle; near α = 0.03179 it is destroyed, and orbits then
        // end sticking to the table. The bracket is 1e-6 wide; the leaving orbits shadow a
        // saddle cycle next to the attractor's tips before they go.
        let sys = System::new(Table::sine(), 0.0317, 0.8).unwrap();
        let spec = CrisisSpec {
            runs: 2,
            events: 400_000,
            sample: 50_000,
            ..CrisisSpec::default()
        };
        let c = locate(&sys, (0.25, 0.5), 0.03178, 0.0318, &spec, &mut |_| false).unwrap();
        assert!(c.hi - c.lo <= 1e-6, "{c:?}");
        assert!(c.lo > 0.03178 && c.hi < 0.0318, "{c:?}");
        assert!(c.left_after.iter().any(Option::is_some));
        let s = c.saddle.as_ref().expect("a saddle");
        let [a, b] = s.cycle.multipliers;
        assert!(a.im == 0.0 && b.im == 0.0 && (a.re.abs() > 1.0) != (b.re.abs() > 1.0));
        assert!(s.passes < 0.02, "{s:?}");
        // Outside the attractor, but close to it: on its basin boundary.
        assert!(s.outside_by >= EMBEDDED && s.outside_by < 0.02, "{s:?}");
        // The attractor nears the saddle's stable manifold as α nears the crisis, and
        // comes closer to it than to the saddle itself.
        let touch = &s.to_stable_manifold;
        assert_eq!(touch.len(), 2, "{s:?}");
        assert!(
            touch[1].1 < touch[0].1 && touch[1].1 < s.outside_by,
            "{s:?}"
        );
        // Chosen by a tangency: the unstable manifold of a saddle embedded in the
        // attractor (within EMBEDDED of its sample) keeps off the chosen saddle's stable
        // manifold at the lower end, as far as the sample does, and first crosses it
        // above the bracket: finite manifolds bound the crisis from above.
        let t = s.tangency.as_ref().expect("a tangency");
        let [e0, e1] = t.embedded.multipliers;
        assert!(
            e0.im == 0.0 && (e0.re.abs() > 1.0) != (e1.re.abs() > 1.0),
            "{t:?}"
        );
        let apart = t.apart.expect("apart at the lower end");
        assert!(apart > 0.0 && apart <= touch[1].1 * 1.01, "{t:?} {touch:?}");
        assert!(t.between.0 >= c.hi && t.between.1 - t.between.0 <= 2.0 * TANGENCY_TOLERANCE);
        assert!(t.between.1 - c.hi < 1e-5, "{t:?}");
        // Shorter manifolds reach fewer folds: the bound they give is higher.
        let e = continued(&at(&sys, c.lo), &t.embedded).unwrap();
        let named = continued(&at(&sys, c.lo), &s.cycle).unwrap();
        let short = first_crossing(
            &|a| at(&sys, a),
            &e,
            UNSTABLE_LENGTH / 3.0,
            &[named],
            (c.lo, c.hi),
            TANGENCY_REACH * (c.hi - c.lo),
            TANGENCY_TOLERANCE,
        )
        .expect("a crossing with shorter manifolds");
        assert!(short.between.0 >= t.between.0, "{short:?} {t:?}");
        // A second method: orbits from the paper's start (not the sampled states), with
        // sticking as the sign of leaving (the attractor has none): below the bracket
        // none in 2·10⁶ events, above it one within them.
        let sticks = |alpha: f64| {
            let s = at(&sys, alpha);
            let st = State::launch(&s, 0, 0.25, 0.5, 0.0).unwrap();
            let mut m = ImpactMap::new(s, Solver::Exact, st);
            (0..2_000_000).any(|_| m.step().map_or(true, |e| e.kind == EventKind::Stick))
        };
        assert!(!sticks(c.lo - 5e-6));
        assert!(sticks(c.hi + 5e-6));
    }
}
