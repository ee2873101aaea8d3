//! Where an attractor's unstable manifold first crosses a saddle's stable manifold, as
//! α rises: the tangency a boundary crisis is.
//!
//! A chaotic attractor is the closure of the unstable manifold of a saddle cycle
//! embedded in it (one of its cascade's cycles). Before a boundary crisis that manifold
//! keeps off the stable manifold of every saddle on the basin boundary; at the crisis
//! it touches one, and past it crosses it (a heteroclinic tangency). With both
//! manifolds grown to a finite length ([`UNSTABLE_LENGTH`], [`TOUCH_LENGTH`] per
//! branch, through every point of each cycle) the
//! first α at which they cross is found by bisection, for several candidate saddles at
//! once: the one crossed first is the saddle the attractor collides with. Finite pieces
//! reach only the manifold's first folds, so the α found is an upper bound of the
//! crisis, which longer pieces bring down; the caller compares it with the crisis
//! located by orbits.
//!
//! Segments live in (t̂, v), a segment's first phase in [0, 1) and its second moved by
//! the same whole period; distances take phases around the circle.

use crate::orbits::manifold::{manifold, segment_distance, Kind, ManifoldSpec};
use crate::orbits::periodic::{cycle, CyclePoint};
use crate::system::System;
use rayon::prelude::*;
use std::collections::HashMap;

/// Arc length of each branch of the embedded saddle's unstable manifold.
pub const UNSTABLE_LENGTH: f64 = 12.0;
/// Arc length of each branch of a candidate's stable manifold.
pub const TOUCH_LENGTH: f64 = 1.0;
/// Distances looked at: two sets farther apart than this are "apart" with no number.
const REACH: f64 = 0.02;

/// A segment in (t̂, v).
type Segment = ([f64; 2], [f64; 2]);

/// The segments of one manifold of the cycle `c`, through each of its points, each
/// branch `length` long; None where no piece can be grown.
fn segments(sys: &System, c: &CyclePoint, kind: Kind, length: f64) -> Option<Vec<Segment>> {
    let spec = ManifoldSpec {
        length,
        ..ManifoldSpec::default()
    };
    let pieces: Vec<Vec<Segment>> = (0..c.n)
        .into_par_iter()
        .filter_map(|i| {
            // The cycle from its i-th launch: the piece through that point.
            let ci = cycle(sys, c.n, c.k, c.phases[i], c.velocities[i]).ok()?;
            let m = manifold(sys, &ci, kind, &spec).ok()?;
            Some(
                m.branches
                    .iter()
                    .flat_map(|b| b.points.windows(2))
                    .map(|w| {
                        let shift = w[0][0].floor();
                        ([w[0][0] - shift, w[0][1]], [w[1][0] - shift, w[1][1]])
                    })
                    .collect(),
            )
        })
        .collect();
    (!pieces.is_empty()).then(|| pieces.concat())
}

/// The distance between two segments (0 where they cross).
fn between_segments(a: Segment, b: Segment) -> f64 {
    let side = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| {
        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
    };
    let crosses = side(b.0, b.1, a.0) * side(b.0, b.1, a.1) < 0.0
        && side(a.0, a.1, b.0) * side(a.0, a.1, b.1) < 0.0;
    if crosses {
        return 0.0;
    }
    segment_distance(a.0, b.0, b.1)
        .min(segment_distance(a.1, b.0, b.1))
        .min(segment_distance(b.0, a.0, a.1))
        .min(segment_distance(b.1, a.0, a.1))
}

/// The segments `b`, with copies a period either side, binned in cells of side
/// [`REACH`] (each in every cell within [`REACH`] of its box).
struct Binned {
    segments: Vec<Segment>,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

fn cell(x: f64) -> i64 {
    (x / REACH).floor() as i64
}

impl Binned {
    fn new(b: &[Segment]) -> Binned {
        let mut out = Binned {
            segments: Vec::new(),
            cells: HashMap::new(),
        };
        for &s in b {
            for d in [-1.0, 0.0, 1.0] {
                let t = ([s.0[0] + d, s.0[1]], [s.1[0] + d, s.1[1]]);
                let (x0, x1) = (t.0[0].min(t.1[0]) - REACH, t.0[0].max(t.1[0]) + REACH);
                if x1 < 0.0 || x0 > 1.0 + REACH {
                    continue;
                }
                let (y0, y1) = (t.0[1].min(t.1[1]) - REACH, t.0[1].max(t.1[1]) + REACH);
                let id = out.segments.len();
                out.segments.push(t);
                for i in cell(x0)..=cell(x1) {
                    for j in cell(y0)..=cell(y1) {
                        out.cells.entry((i, j)).or_default().push(id);
                    }
                }
            }
        }
        out
    }

    /// The least distance from the segments `a` to these; None beyond [`REACH`].
    fn distance(&self, a: &[Segment]) -> Option<f64> {
        let best = a
            .par_iter()
            .map(|&s| {
                let mut best = f64::INFINITY;
                let (x0, x1) = (s.0[0].min(s.1[0]), s.0[0].max(s.1[0]));
                let (y0, y1) = (s.0[1].min(s.1[1]), s.0[1].max(s.1[1]));
                for i in cell(x0)..=cell(x1) {
                    for j in cell(y0)..=cell(y1) {
                        for &id in self.cells.get(&(i, j)).into_iter().flatten() {
                            best = best.min(between_segments(s, self.segments[id]));
                        }
                    }
                }
                best
            })
            .reduce(|| f64::INFINITY, f64::min);
        (best <= REACH).then_some(best)
    }
}

/// The least distance from `points` (t̂, v) to a manifold of the cycle `c`: its piece
/// through every point of the cycle, `length` per branch. None where no piece can be
/// grown, or none comes within 0.02.
pub(crate) fn to_points(
    sys: &System,
    c: &CyclePoint,
    kind: Kind,
    length: f64,
    points: &[(f64, f64)],
) -> Option<f64> {
    let m = Binned::new(&segments(sys, c, kind, length)?);
    let points: Vec<Segment> = points.iter().map(|&(t, v)| ([t, v], [t, v])).collect();
    m.distance(&points)
}

/// Where the embedded saddle's unstable manifold first crosses a candidate's stable
/// manifold.
#[derive(Clone, Debug, PartialEq)]
pub struct Crossing {
    /// The candidates (indices into those given) first crossed, in the final bracket.
    pub first: Vec<usize>,
    /// The bracket: apart at `.0`, crossed at `.1`.
    pub between: (f64, f64),
    /// The distance between the two manifolds at the lower end, per candidate (None:
    /// beyond reach, or its cycle not found), for those not crossed there.
    pub apart: Vec<Option<f64>>,
    /// Candidates whose stable manifold the unstable manifold crosses already at the
    /// lower end: they lie in the attractor's closure, not on its boundary.
    pub in_closure: Vec<usize>,
}

/// The cycle `c` continued by Newton's method to the α of `sys`, from its launch.
pub(crate) fn continued(sys: &System, c: &CyclePoint) -> Option<CyclePoint> {
    cycle(sys, c.n, c.k, c.phases[c.n - 1], c.velocities[c.n - 1]).ok()
}

/// What the unstable manifold does with a candidate's stable manifold at one α.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Seen {
    /// The candidate's cycle is not found there.
    Lost,
    /// Apart, by this much (None: beyond 0.02).
    Apart(Option<f64>),
    /// They cross.
    Crossed,
}

/// Per candidate at the α of `sys`: what the unstable manifold of `embedded` does
/// with its stable manifold. None where the embedded saddle is lost.
fn crossed(
    sys: &System,
    embedded: &CyclePoint,
    length: f64,
    candidates: &[CyclePoint],
) -> Option<Vec<Seen>> {
    let e = continued(sys, embedded)?;
    let wu = Binned::new(&segments(sys, &e, Kind::Unstable, length)?);
    let seen = |c: &CyclePoint| {
        let Some(at) = continued(sys, c) else {
            return Seen::Lost;
        };
        match segments(sys, &at, Kind::Stable, TOUCH_LENGTH) {
            None => Seen::Lost,
            Some(ws) => match wu.distance(&ws) {
                Some(0.0) => Seen::Crossed,
                d => Seen::Apart(d),
            },
        }
    };
    Some(candidates.iter().map(seen).collect())
}

/// The first α above `lo` at which the unstable manifold of `embedded` (a saddle in
/// the attractor, its cycle at `lo`; each branch `length` long, [`UNSTABLE_LENGTH`]
/// for a crisis) crosses the stable manifold of one of
/// `candidates`: looked for at `hi`, then ever farther above it (the bracket's width
/// doubled, up to `reach_up`), then bisected to `tolerance`. `at(α)` is the system at
/// α. None where no candidate is crossed by `reach_up`, or the embedded saddle is lost.
pub fn first_crossing(
    at: &dyn Fn(f64) -> System,
    embedded: &CyclePoint,
    length: f64,
    candidates: &[CyclePoint],
    (lo, hi): (f64, f64),
    reach_up: f64,
    tolerance: f64,
) -> Option<Crossing> {
    let start = crossed(&at(lo), embedded, length, candidates)?;
    let in_closure: Vec<usize> = (0..candidates.len())
        .filter(|&i| start[i] == Seen::Crossed)
        .collect();
    let apart: Vec<Option<f64>> = start
        .iter()
        .map(|x| match x {
            Seen::Apart(d) => *d,
            _ => None,
        })
        .collect();
    let live: Vec<usize> = (0..candidates.len())
        .filter(|&i| matches!(start[i], Seen::Apart(_)))
        .collect();
    if live.is_empty() {
        return None;
    }
    let some: Vec<CyclePoint> = live.iter().map(|&i| candidates[i].clone()).collect();
    let which = |alpha: f64| -> Option<Vec<usize>> {
        let x = crossed(&at(alpha), embedded, length, &some)?;
        Some((0..some.len()).filter(|&i| x[i] == Seen::Crossed).collect())
    };
    let (mut a0, mut a1) = (lo, hi);
    let mut width = hi - lo;
    let mut top = which(a1)?;
    while top.is_empty() {
        a0 = a1;
        width *= 2.0;
        a1 = a0 + width;
        if a1 > hi + reach_up {
            return None;
        }
        top = which(a1)?;
    }
    while a1 - a0 > tolerance {
        let mid = 0.5 * (a0 + a1);
        let x = which(mid)?;
        if x.is_empty() {
            a0 = mid;
        } else {
            a1 = mid;
            top = x;
        }
    }
    Some(Crossing {
        first: top.into_iter().map(|i| live[i]).collect(),
        between: (a0, a1),
        apart,
        in_closure,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_that_cross_are_at_distance_zero_and_parallel_ones_at_their_gap() {
        let a = ([0.1, 0.0], [0.3, 0.2]);
        assert_eq!(between_segments(a, ([0.1, 0.2], [0.3, 0.0])), 0.0);
        let d = between_segments(([0.1, 0.5], [0.3, 0.5]), ([0.15, 0.51], [0.2, 0.51]));
        assert!((d - 0.01).abs() < 1e-15, "{d}");
        // Around the circle: 0.995 and 0.005 are 0.01 apart in phase.
        let distance = |a: &[Segment], b: &[Segment]| Binned::new(b).distance(a);
        let d = distance(
            &[([0.995, 0.4], [0.995, 0.5])],
            &[([0.005, 0.45], [0.005, 0.6])],
        );
        assert!((d.unwrap() - 0.01).abs() < 1e-12, "{d:?}");
        assert_eq!(distance(&[a], &[([0.6, 0.6], [0.7, 0.7])]), None);
    }
}
