//! Where a chaotic attractor jumps in size along a continuation: the sign of an interior
//! (or merging) crisis, which the continuation's matching cannot see. The attractor
//! goes on, matched across the jump (its point sets lie within
//! [`MATCH_DISTANCE`](super::global::MATCH_DISTANCE) of each other, on cells coarser
//! than the jump), so no change is recorded there.
//!
//! * **Size.** At every α value where a track is chaotic, an orbit from its point runs
//!   a warm-up, then a sample of events (for a crisis, the
//!   [`CrisisSpec`](super::crisis::CrisisSpec)'s); the size is the
//!   range of their launch velocities, [v_min, v_max] (phases wrap around the period,
//!   velocities do not).
//! * **Jump.** Between two neighbouring values the attractor *grows by* the larger of
//!   how far v_min falls and v_max rises. It jumps where it grows by more than
//!   [`JUMP_RATIO`] times the largest change of either end between the neighbouring
//!   pairs of values of the same track (its drift; at least one such pair must exist)
//!   and by more than [`MIN_JUMP`]. Smaller jumps, and jumps at a track's first or
//!   last pair of values with no neighbour, are not looked for.
//!
//! A jump is a candidate, not a finding: [`crises`](super::crisis::crises) locates
//! each by bisection, with the attractor's neighbourhood matched to the jump, and
//! names its saddle as for a destroyed attractor.

use super::global::Continuation;
use super::Kind;
use crate::impact::Solver;
use crate::map::{EventKind, ImpactMap, State};
use crate::system::System;

/// A jump is at least this many times the drift of the attractor's ends between
/// neighbouring values.
pub const JUMP_RATIO: f64 = 4.0;
/// Smallest jump looked for, in units of velocity.
pub const MIN_JUMP: f64 = 1e-4;

/// A range of launch velocities, (v_min, v_max).
pub type Span = (f64, f64);

/// A chaotic attractor grown abruptly between two neighbouring α values.
#[derive(Clone, Debug, PartialEq)]
pub struct Jump {
    /// Its track.
    pub track: usize,
    /// The upper of the two values: its place in [`Continuation::steps`].
    pub step: usize,
    /// Its range of launch velocities at the lower value.
    pub before: Span,
    /// At the upper value.
    pub after: Span,
    /// How far it grew (the larger of the two ends' moves outward).
    pub grows_by: f64,
    /// The largest change of either end between the neighbouring pairs of values.
    pub drift: f64,
}

/// The range of launch velocities of the attractor through `point` (a launch (t̂, v))
/// at the α of `sys`, over `sample` events after `warmup`; None where its orbit sticks,
/// halts or is cancelled (not a chaotic attractor of impacts there).
pub fn size_at(
    sys: &System,
    point: (f64, f64),
    warmup: u64,
    sample: u64,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Span> {
    let start = State::launch(sys, 0, point.0, point.1, 0.0).ok()?;
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..warmup + sample {
        if i % 65_536 == 0 && cancelled(i) {
            return None;
        }
        let e = map.step().ok()?;
        if e.kind != EventKind::Impact {
            return None;
        }
        if i >= warmup {
            lo = lo.min(e.v);
            hi = hi.max(e.v);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The size of every chaotic member of `cont` over `sample` events after `warmup`:
/// (step, track, range).
pub fn sizes(
    cont: &Continuation,
    warmup: u64,
    sample: u64,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Vec<(usize, usize, Span)> {
    let mut out = Vec::new();
    for (i, step) in cont.steps().iter().enumerate() {
        let mut sys = cont.spec().sys.clone();
        if sys.set_alpha(step.alpha).is_err() {
            continue;
        }
        for m in step.members.iter().filter(|m| m.kind == Kind::Chaotic) {
            let Some(p) = m.point else { continue };
            if let Some(s) = size_at(&sys, p, warmup, sample, cancelled) {
                out.push((i, m.track, s));
            }
        }
    }
    out
}

/// The jumps among `sizes` ((step, track, range), as [`sizes`] gives them).
pub fn jumps(sizes: &[(usize, usize, Span)]) -> Vec<Jump> {
    let mut tracks: Vec<usize> = sizes.iter().map(|s| s.1).collect();
    tracks.sort_unstable();
    tracks.dedup();
    let mut out = Vec::new();
    for t in tracks {
        let of: Vec<(usize, Span)> = sizes
            .iter()
            .filter(|s| s.1 == t)
            .map(|s| (s.0, s.2))
            .collect();
        // Pairs of neighbouring values: (upper step, before, after).
        let pairs: Vec<(usize, Span, Span)> = of
            .windows(2)
            .filter(|w| w[1].0 == w[0].0 + 1)
            .map(|w| (w[1].0, w[0].1, w[1].1))
            .collect();
        let change = |b: Span, a: Span| (a.0 - b.0).abs().max((a.1 - b.1).abs());
        for (j, &(step, before, after)) in pairs.iter().enumerate() {
            let grows_by = (before.0 - after.0).max(after.1 - before.1);
            let neighbours = [j.checked_sub(1), Some(j + 1)];
            let drift = neighbours
                .iter()
                .flatten()
                .filter_map(|&i| pairs.get(i))
                // Only pairs adjacent to this one.
                .filter(|p| p.0 + 1 == step || p.0 == step + 1)
                .map(|p| change(p.1, p.2))
                .fold(None, |m: Option<f64>, c| Some(m.map_or(c, |m| m.max(c))));
            let Some(drift) = drift else { continue };
            if grows_by > MIN_JUMP && grows_by > JUMP_RATIO * drift {
                out.push(Jump {
                    track: t,
                    step,
                    before,
                    after,
                    grows_by,
                    drift,
                });
            }
        }
    }
    out.sort_by_key(|j| (j.step, j.track));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_jump_is_growth_well_beyond_the_drift_of_its_neighbours() {
        // One track drifting by 1e-3 per value, jumping by 1e-2 between values 3 and 4.
        let mut s: Vec<(usize, usize, (f64, f64))> = (0..8)
            .map(|i| {
                let d = 1e-3 * i as f64;
                let jump = if i >= 4 { 1e-2 } else { 0.0 };
                (i, 0, (0.3 - d - jump, 0.6 + d))
            })
            .collect();
        // A second track drifting evenly: no jump; one value alone: no neighbour.
        s.extend((0..5).map(|i| (i, 1, (0.1, 0.2 + 1e-3 * i as f64))));
        s.push((9, 2, (0.0, 0.1)));
        let j = jumps(&s);
        assert_eq!(j.len(), 1, "{j:?}");
        assert_eq!((j[0].track, j[0].step), (0, 4));
        assert!((j[0].grows_by - 1.1e-2).abs() < 1e-12);
        assert!((j[0].drift - 1e-3).abs() < 1e-12);
        // A shrinking attractor does not grow; a gap in a track's values breaks the
        // pairs (no neighbour across it).
        let shrink: Vec<_> = (0..6)
            .map(|i| (i, 0, (0.3 + if i >= 3 { 1e-2 } else { 0.0 }, 0.6)))
            .collect();
        assert!(jumps(&shrink).is_empty());
        let gap = [(0, 0, (0.3, 0.6)), (1, 0, (0.29, 0.6)), (3, 0, (0.1, 0.6))];
        assert!(jumps(&gap).is_empty());
    }
}
