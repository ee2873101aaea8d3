//! Curves that end on a border-collision curve, seen from both of its sides.
//!
//! Where an impact of a cycle crosses a breakpoint, f'' jumps, and so do the cycle's
//! multipliers: the period doubling (or fold) of the cycle on one side of a
//! border-collision curve ends on it at one point (a pd_border, fold_border), that of
//! the cycle on the other side at another. A value of the second parameter seeds such
//! a curve only where its one-parameter continuation crosses it, and a short curve
//! between two borders may be crossed by no seed value. So along every
//! border-collision curve found, the cycle is solved just off it on both sides, each
//! side's PD and fold test functions are watched from point to point, and where one
//! changes sign with no curve of its kind and cycle ending there, that curve is
//! followed from a line parallel to the border-collision curve, just off it on that
//! side. Where the cycle on one side stops being solved between two points, its tests
//! are watched up to where it still is, and where it stops with its fold test closing
//! in on zero, the fold curve ending there is followed.

use super::corrector::{near_birth, Eval, Tracer};
use super::trace::{follow_from, SeedLine};
use super::*;
use crate::orbits::continuation::Kind;
use std::cell::RefCell;

/// How far off the border-collision curve the cycle is solved on each side, in the
/// plane's scale: far enough that the impact is on that side beyond rounding, close
/// enough that the cycle is the curve's.
const OFF: f64 = 1e-6;

/// The distances off the border-collision curve, in the plane's scale, of the lines a
/// curve found ending on it is solved on first, nearest first.
const SEED_LINES: [f64; 3] = [1e-6, 1e-5, 1e-4];

/// A test function's sign change along a border-collision curve is a root only where
/// the test, next to where it changes sign, is below this share of its size at the two
/// points that bracket it.
const ROOT_SHARE: f64 = 1e-3;

/// A curve ends at a point located on the border-collision curve when one of its ends
/// is a border within this (in the plane's scale) of it: at a fold that point is only
/// the nearest the cycle could be solved at fixed parameters (M − I is singular at the
/// fold itself). A curve that passes the point without ending there is another (two
/// fold curves may run within 10⁻⁴ of each other), and so is one the fold's corrector
/// slid to along the seed line.
const ENDS_WITHIN: f64 = 1e-3;

/// Where the cycle on one side of a border-collision curve ends between two of its
/// points with its fold test down to this share of its value at the last point before,
/// it ends at a fold.
const FOLD_CLOSING: f64 = 0.05;

/// The pieces [`split`] cuts a chord in where a test's sign change has no root.
const SPLIT: usize = 8;

/// Bisection steps of [`reach`]: to 2⁻⁴⁰ of the chord. Where the cycle stops at a
/// fold, its fold test falls as the square root of the distance to it, so it is then
/// about 10⁻⁶ of its size a chord away: below [`ROOT_SHARE`].
const REACH_STEPS: usize = 40;

/// The cycle off the border-collision curve at a share of a chord between two of its
/// points (from a guess, and whether to guess from the nearest point solved): where it
/// was solved on the curve, that cycle, and the one on the curve.
type OnChord<'a> = dyn Fn(f64, &CyclePoint, bool) -> Option<([f64; 2], Off, CyclePoint)> + 'a;

/// A test function of a cycle: zero on the curves of one kind.
type Test = fn(&CyclePoint) -> f64;

/// The curves looked for, with their test functions.
const TESTS: [(CurveKind, Test); 2] = [
    (CurveKind::PeriodDoubling, CyclePoint::pd_test),
    (CurveKind::Fold, CyclePoint::fold_test),
];

/// The cycle solved just off a border-collision curve, on one side.
#[derive(Clone)]
struct Off {
    /// Where it was solved.
    y: [f64; 2],
    /// The unit normal of the border-collision curve pointing to this side.
    normal: [f64; 2],
    pt: CyclePoint,
}

/// For each border-collision curve of `out` not yet in `scanned` (by its seed and
/// length: a curve a join extended is looked at again), the PD and fold curves ending on
/// it from either side that no curve found yet ends at, followed.
pub(super) fn seed_from_border_sides(
    plane: &Plane,
    out: &mut Curves,
    scanned: &mut Vec<([f64; 2], usize)>,
    dead_ends: &RefCell<Vec<DeadEnd>>,
) {
    let mut i = 0;
    while i < out.curves.len() {
        let c = &out.curves[i];
        i += 1;
        let CurveKind::BorderCollision { impact, breakpoint } = c.kind else {
            continue;
        };
        let key = (c.seed, c.points.len());
        if scanned.contains(&key) || c.points.len() < 2 {
            continue;
        }
        scanned.push(key);
        let (n, k) = (c.n, c.k);
        let tracer = Tracer {
            plane,
            kind: c.kind,
            n,
            k,
            jumps: plane.jumps(c.points[0].p),
            dead_ends,
            hold: false,
        };
        // The curve's points but its corners (where another impact lies on a
        // breakpoint, the cycle just off the curve straddles that one, and the curve's
        // normal turns).
        let points: Vec<CurvePoint> = c
            .points
            .iter()
            .filter(|q| {
                tracer
                    .border_tests(&q.cycle)
                    .iter()
                    .all(|t| t.abs() > CONDITION_TOLERANCE)
            })
            .cloned()
            .collect();
        // Each point's cycle just off the curve, by the side its impact lies on.
        let sides: Vec<[Option<Off>; 2]> = (0..points.len())
            .map(|j| {
                let mut found: [Option<Off>; 2] = [None, None];
                let Some(normal) = normal(&points, j) else {
                    return found;
                };
                let q = &points[j];
                for sign in [1.0, -1.0] {
                    let normal = [sign * normal[0], sign * normal[1]];
                    if let Some((side, off)) = off_curve(
                        &tracer,
                        [q.alpha, q.p],
                        &q.cycle,
                        normal,
                        (impact, breakpoint),
                    ) {
                        found[side] = Some(off);
                    }
                }
                found
            })
            .collect();
        let mut seeds: Vec<(CurveKind, [f64; 2], Off)> = Vec::new();
        for side in 0..2 {
            for j in 0..sides.len().saturating_sub(1) {
                let (p, q) = (&points[j], &points[j + 1]);
                // Where the cycle on this side is solved at one of the two points only
                // (it ends between them, at a fold or where it leaves its pieces), the
                // test is watched up to where it still is.
                // Only where it is solved at two points in a row on one side and at
                // none of the next two (or the curve's end) on the other: not where
                // Newton's method misses it at a point here and there (a strongly
                // unstable cycle), at the cost of a bisection each.
                let solved = |i: Option<usize>| {
                    i.and_then(|i| sides.get(i))
                        .is_some_and(|s| s[side].is_some())
                };
                let (before, after) = (solved(j.checked_sub(1)), solved(Some(j + 2)));
                // This side as seen from the cycle `a` off the curve.
                let look = |a: &Off| OneSide {
                    tracer: &tracer,
                    side,
                    normal: a.normal,
                    border: (impact, breakpoint),
                };
                let reached;
                let mut ends = false;
                let (a, b, (p, q)) = match (&sides[j][side], &sides[j + 1][side]) {
                    (Some(a), Some(b)) => (a, b, (p, q)),
                    pair => {
                        // Solved at `from` only: watched from there towards `to`.
                        let (a, from, to) = match pair {
                            (Some(a), None) if before && !after => (a, p, q),
                            (None, Some(b)) if after && !before => (b, q, p),
                            _ => continue,
                        };
                        let Some(r) = reach(look(a), (from, to)) else {
                            continue;
                        };
                        reached = r;
                        ends = true;
                        (a, &reached.1, (from, &reached.0))
                    }
                };
                for (kind, test) in TESTS {
                    let (ga, gb) = (test(&a.pt), test(&b.pt));
                    if !(ga.is_finite() && gb.is_finite()) {
                        continue;
                    }
                    // The cycle on this side ends where its fold test closes in on
                    // zero: at a fold, whose curve ends on the border collision there
                    // (followed from there, it must end there to be taken).
                    if ends
                        && kind == CurveKind::Fold
                        && (ga < 0.0) == (gb < 0.0)
                        && gb.abs() <= FOLD_CLOSING * ga.abs()
                        && !near_birth(&b.pt)
                    {
                        seeds.push((kind, [q.alpha, q.p], b.clone()));
                        continue;
                    }
                    if (ga < 0.0) == (gb < 0.0) {
                        continue;
                    }
                    match locate(look(a), (p, q), test, (ga, gb)) {
                        Some((x, off)) => seeds.push((kind, x, off)),
                        // No root where the sign changed (a jump, the cycle off the
                        // curve changing on the way): several roots and jumps may lie
                        // between two points far apart, each sought between closer ones.
                        None => {
                            for (x, off) in split(look(a), (p, q), test, (ga, gb)) {
                                seeds.push((kind, x, off));
                            }
                        }
                    }
                }
            }
        }
        let within = ENDS_WITHIN * plane.scale();
        for (kind, x, off) in seeds {
            let known = out
                .curves
                .iter()
                .any(|c| c.kind == kind && c.n == n && c.k == k && ends_near(c, x, within));
            if known || out.curves.len() >= MAX_CURVES {
                continue;
            }
            let special = Special {
                kind: match kind {
                    CurveKind::Fold => Kind::Fold,
                    _ => Kind::PeriodDoubling,
                },
                alpha: off.y[0],
                phase: off.pt.phases[0],
                impact: 0,
                point: off.pt,
                collision: None,
                last_step: None,
            };
            let index = out.curves.len();
            // On a line parallel to the border-collision curve, on the cycle's side.
            let found = SEED_LINES.iter().find_map(|&dist| {
                let dist = dist * plane.scale();
                let start = [x[0] + dist * off.normal[0], x[1] + dist * off.normal[1]];
                if !plane.inside(start) {
                    return None;
                }
                let d = off.normal[0] * start[0] + off.normal[1] * start[1];
                let line = SeedLine {
                    start,
                    c: off.normal,
                    d,
                };
                // The curve that ends there, not another the corrector slid to.
                follow_from(plane, kind, &special, line, index, dead_ends)
                    .ok()
                    .filter(|(curve, _)| curve.points.len() >= 2 && ends_near(curve, x, within))
            });
            if let Some((curve, codim2)) = found {
                out.curves.push(curve);
                out.codim2.extend(codim2);
            }
        }
    }
}

/// Where `test` of the cycle on the side `look` vanishes on the border-collision curve
/// between its points `p` and `q` (values `ga` and `gb` there): by bisection over the
/// chord, each chord point taken onto the curve across the chord, the cycle solved
/// just off it on that side (its normal pointing there). Located, not interpolated
/// between the points: the seed must not depend on where the curve's points happen to
/// lie. None where the sign changes by a jump.
fn locate(
    look: OneSide<'_, '_>,
    (p, q): (&CurvePoint, &CurvePoint),
    test: Test,
    (ga, gb): (f64, f64),
) -> Option<([f64; 2], Off)> {
    let chord = Chord::new(look, (p, q))?;
    // The cycle on the curve guessed, first, from the nearest point solved on `p`'s
    // side of the root so far (at first `p`'s own), else from `q`; if that finds no
    // root, from the nearer of `p` and `q` (Newton's method may land on the other
    // cycle of a pair either way).
    let at = |s: f64, near: &CyclePoint, nearest: bool| -> Option<([f64; 2], Off, CyclePoint)> {
        let first = if nearest {
            near
        } else if s < 0.5 {
            &p.cycle
        } else {
            &q.cycle
        };
        let then = nearest.then_some(&q.cycle);
        let (on, off) = chord.across(s, std::iter::once(first).chain(then))?;
        Some((on.y, off, on.pt))
    };
    [true, false]
        .into_iter()
        .find_map(|nearest| bisect(&at, nearest, &p.cycle, test, (ga, gb)))
}

/// Where a test of the cycle on the side `look` changes sign between the points `p` and `q`
/// of the border-collision curve (values `ga`, `gb`) but [`locate`] finds no root
/// there: the chord cut in [`SPLIT`] pieces, each inner end taken onto the curve (its
/// cycle off it solved on that side), and a root located in every piece the test
/// changes sign over (the last one solved to `q` included: past a fold the cycle there
/// is the other of the pair).
fn split(
    look: OneSide<'_, '_>,
    (p, q): (&CurvePoint, &CurvePoint),
    test: Test,
    (ga, gb): (f64, f64),
) -> Vec<([f64; 2], Off)> {
    let Some(chord) = Chord::new(look, (p, q)) else {
        return Vec::new();
    };
    // The pieces' ends solved on this side, with the test there.
    let mut ends: Vec<(CurvePoint, f64)> = vec![(p.clone(), ga)];
    for i in 1..SPLIT {
        let s = i as f64 / SPLIT as f64;
        let guess = &ends[ends.len() - 1].0.cycle;
        if let Some((on, off)) = chord.across(s, [guess, &p.cycle, &q.cycle]) {
            ends.push((look.tracer.point(on), test(&off.pt)));
        }
    }
    ends.push((q.clone(), gb));
    ends.windows(2)
        .filter(|w| w[0].1.is_finite() && w[1].1.is_finite() && (w[0].1 < 0.0) != (w[1].1 < 0.0))
        .filter_map(|w| {
            let (a, b) = (&w[0], &w[1]);
            locate(look, (&a.0, &b.0), test, (a.1, b.1))
        })
        .collect()
}

/// The bisection of [`locate`] over the chord (`at` the cycle off the curve at a share
/// of it, guessed as `nearest` says).
fn bisect(
    at: &OnChord<'_>,
    nearest: bool,
    start: &CyclePoint,
    test: Test,
    (ga, gb): (f64, f64),
) -> Option<([f64; 2], Off)> {
    // Bisection on the chord, `lo` keeping the test's sign at `p` and the cycle
    // solved: where the test is continuous this closes in on its root; at a fold, where
    // the cycle cannot be solved at fixed parameters (M − I is singular) and beyond
    // it is the other cycle of the pair, on the edge of where it is solved, next to
    // the fold, where the fold's corrector (on the extended system) starts from.
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut found: Option<([f64; 2], Off)> = None;
    let mut near = start.clone();
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        match at(mid, &near, nearest) {
            Some((y, off, on)) if (test(&off.pt) < 0.0) == (ga < 0.0) => {
                lo = mid;
                found = Some((y, off));
                near = on;
            }
            _ => hi = mid,
        }
        if hi - lo <= f64::EPSILON {
            break;
        }
    }
    // A sign change by a jump (the cycle solved off the curve changing to another one
    // on the way, or its impacts' pieces changing) is no root.
    found.filter(|f| test(&f.1.pt).abs() <= ROOT_SHARE * ga.abs().max(gb.abs()))
}

/// Where the cycle on the side `look` is solved off the border-collision curve at its point
/// `from` but not at the next point `to`: the point of the curve between them nearest
/// `to` where it still is (marching and then bisecting over the chord, each chord point
/// taken onto the curve across it), with that cycle.
fn reach(
    look: OneSide<'_, '_>,
    (from, to): (&CurvePoint, &CurvePoint),
) -> Option<(CurvePoint, Off)> {
    let chord = Chord::new(look, (from, to))?;
    let at = |s: f64, guess: &CyclePoint| -> Option<(CurvePoint, Off)> {
        let (on, off) = chord.across(s, [guess])?;
        Some((look.tracer.point(on), off))
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut found: Option<(CurvePoint, Off)> = None;
    // First in [`SPLIT`] pieces, each from the cycle of the one before (from `from`'s
    // own, a chord point far along may take Newton's method to another cycle's border
    // collision close by), then by bisection within the last piece it is solved in.
    for i in 1..SPLIT {
        let s = i as f64 / SPLIT as f64;
        let guess = found.as_ref().map_or(&from.cycle, |f| &f.0.cycle);
        match at(s, guess) {
            Some(f) => {
                lo = s;
                found = Some(f);
            }
            None => {
                hi = s;
                break;
            }
        }
    }
    for _ in 0..REACH_STEPS {
        let mid = 0.5 * (lo + hi);
        let guess = found.as_ref().map_or(&from.cycle, |f| &f.0.cycle);
        match at(mid, guess) {
            Some(f) => {
                lo = mid;
                found = Some(f);
            }
            None => hi = mid,
        }
    }
    found
}

/// One side of a border-collision curve, as the searches along a stretch of it see it.
#[derive(Clone, Copy)]
struct OneSide<'t, 'p> {
    /// The border-collision curve's tracer.
    tracer: &'t Tracer<'p>,
    side: usize,
    /// The curve's normal pointing to `side` (at the stretch's first point).
    normal: [f64; 2],
    /// The curve's impact and breakpoint.
    border: (usize, f64),
}

/// The chord between two points of a border-collision curve, and the cycle on one side
/// of the curve across it.
struct Chord<'t, 'p> {
    look: OneSide<'t, 'p>,
    from: [f64; 2],
    chord: [f64; 2],
    /// The chord's unit direction.
    u: [f64; 2],
}

impl<'t, 'p> Chord<'t, 'p> {
    /// The chord from `from` to `to` (None where they coincide).
    fn new(look: OneSide<'t, 'p>, (from, to): (&CurvePoint, &CurvePoint)) -> Option<Self> {
        let chord = [to.alpha - from.alpha, to.p - from.p];
        let len = chord[0].hypot(chord[1]);
        (len > 0.0 && len.is_finite()).then(|| Chord {
            look,
            from: [from.alpha, from.p],
            chord,
            u: [chord[0] / len, chord[1] / len],
        })
    }

    /// The chord's point at share `s` taken onto the curve across the chord (its cycle
    /// from the first of `guesses` that gives it), and the cycle solved just off the
    /// curve there, where that lies on this side.
    fn across<'g>(
        &self,
        s: f64,
        guesses: impl IntoIterator<Item = &'g CyclePoint>,
    ) -> Option<(Eval, Off)> {
        let (from, chord, u, look) = (self.from, self.chord, self.u, self.look);
        let c = [from[0] + s * chord[0], from[1] + s * chord[1]];
        let (on, _) = guesses.into_iter().find_map(|guess| {
            look.tracer
                .correct(c, u, u[0] * c[0] + u[1] * c[1], guess)
                .ok()
        })?;
        let (here, off) = off_curve(look.tracer, on.y, &on.pt, look.normal, look.border)?;
        (here == look.side).then_some((on, off))
    }
}

/// The cycle solved [`OFF`] off the border-collision curve at its point `on` (cycle
/// `guess`), along `normal`, with the side of the breakpoint its impact lies on
/// (`border`: the curve's impact and breakpoint; 1 past the breakpoint).
fn off_curve(
    tracer: &Tracer<'_>,
    on: [f64; 2],
    guess: &CyclePoint,
    normal: [f64; 2],
    (impact, breakpoint): (usize, f64),
) -> Option<(usize, Off)> {
    let off = OFF * tracer.plane.scale();
    let y = [on[0] + off * normal[0], on[1] + off * normal[1]];
    if !tracer.plane.inside(y) {
        return None;
    }
    let e = tracer.eval(y, guess).ok()?;
    let side = usize::from(signed_distance(e.pt.phases[impact], breakpoint) > 0.0);
    Some((
        side,
        Off {
            y,
            normal,
            pt: e.pt,
        },
    ))
}

/// Whether `curve` ends at a border within `within` of `x`.
fn ends_near(curve: &Curve, x: [f64; 2], within: f64) -> bool {
    let ends = [curve.points.first(), curve.points.last()];
    curve.ends.iter().zip(ends).any(|(end, q)| {
        *end == CurveEnd::Border && q.is_some_and(|q| (q.alpha - x[0]).hypot(q.p - x[1]) <= within)
    })
}

/// The unit normal of the curve through `points` at point `j` (of the chord between
/// its neighbours); None where they coincide.
fn normal(points: &[CurvePoint], j: usize) -> Option<[f64; 2]> {
    let a = &points[j.saturating_sub(1)];
    let b = &points[(j + 1).min(points.len() - 1)];
    let t = [b.alpha - a.alpha, b.p - a.p];
    let len = t[0].hypot(t[1]);
    (len > 0.0 && len.is_finite()).then(|| [-t[1] / len, t[0] / len])
}
