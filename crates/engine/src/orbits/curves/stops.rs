//! Where a curve's steps stop: the breakpoint another impact reached (a codimension-two
//! point, by extrapolation), the way on through a double border, the curve ahead in
//! other directions where the tangent was off, and the codimension-two point located
//! on the curve it ended at, and whether a way found past a corner only leads back
//! along the arm the curve came by. [`super::trace`] asks these when its steps fail or
//! stall, and as it goes on past a corner.

use super::corrector::{collapsed, Tracer};
use super::{
    Codim2, Codim2Kind, CurveEnd, CurveKind, CurvePoint, DeadEnd, BORDER_REACH, CONDITION_TOLERANCE,
};
use crate::orbits::manifold::segment_distance;
use crate::orbits::periodic::{self, CyclePoint};
use crate::time::signed_distance;

/// The directions a curve may leave a double border in, in degrees from the way it
/// came, nearest first: all round but straight back (the corner may be a cusp; the
/// arm it came along has the other impact on its own side, and is refused).
const TURNS: [f64; 23] = [
    0.0, 15.0, -15.0, 30.0, -30.0, 45.0, -45.0, 60.0, -60.0, 75.0, -75.0, 90.0, -90.0, 105.0,
    -105.0, 120.0, -120.0, 135.0, -135.0, 150.0, -150.0, 165.0, -165.0,
];
/// A point within this share of the plane of the arm a curve came to a corner by, and
/// farther from the corner than a thousand times that, has come back along it (two
/// arms that close are one to 0.06°; a corner's arms may part at a few degrees).
pub(super) const RETRACE: f64 = 1e-6;
/// A curve stopped within this share of the plane of a codimension-two point located
/// on it stopped there.
const AT_CODIM2: f64 = 1e-5;
/// A point [`Tracer::around`] found: the point, the direction whose line it was solved
/// on, its step from the centre, that step's length, and the line's distance.
struct Tried<'a> {
    q: &'a CurvePoint,
    dir: [f64; 2],
    step: [f64; 2],
    dist: f64,
    rho: f64,
}

impl Tracer<'_> {
    /// Where a curve stops short of a breakpoint (another impact within
    /// [`BORDER_REACH`] of one, closing in): the codimension-two point,
    /// by linear extrapolation of that impact's distance over the last two points. The
    /// evidence kept is the last accepted point's: its condition, and its distance to
    /// the border (the extrapolation's length is of that order, its error of its
    /// square).
    pub(super) fn border_end(
        &self,
        prev: Option<&CurvePoint>,
        cur: &CurvePoint,
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> bool {
        let Some(prev) = prev else { return false };
        let nb = self.jumps.len().max(1);
        let Some((j, dc)) = self.nearest_border(&cur.cycle) else {
            return false;
        };
        let dp = self.border_tests(&prev.cycle)[j];
        // On the border already (to rounding), or closing in on it from one side.
        let on = dc.abs() <= 1e-12;
        if !on && (dc.abs() > BORDER_REACH || dp.abs() <= dc.abs() || (dp < 0.0) != (dc < 0.0)) {
            return false;
        }
        let s = if on { 0.0 } else { dc / (dp - dc) };
        codim2.push(Codim2 {
            kind: match self.kind {
                CurveKind::Fold | CurveKind::Birth => Codim2Kind::FoldBorder,
                CurveKind::Grazing { .. } => Codim2Kind::GrazingBorder,
                CurveKind::BorderCollision { .. } if collapsed(&cur.cycle) => Codim2Kind::Collapse,
                CurveKind::BorderCollision { .. } => Codim2Kind::DoubleBorder,
                CurveKind::PeriodDoubling => Codim2Kind::PdBorder,
            },
            curve: index,
            alpha: cur.alpha + s * (cur.alpha - prev.alpha),
            p: cur.p + s * (cur.p - prev.p),
            condition: cur.condition,
            second_condition: dc,
            impact: Some((j / nb, self.jumps[j % nb])),
            meets: vec![index],
        });
        true
    }

    /// A border-collision curve stopped at a double border `corner` (another impact
    /// reaching another breakpoint): its point beyond, where that impact has crossed
    /// into the next piece, solved on circles of growing radius around the corner in
    /// the directions [`TURNS`] (the corner turns the curve, f'' jumping for the other
    /// impact), with the direction it leaves in. The way the curve came is from `cur`
    /// to the corner, or the tangent `tau` where `cur` lies too close to the corner
    /// for that difference to give a direction; the side the curve came from is that of
    /// `cur` or `prev`, whichever lies farther from the border (`cur` may lie on it to
    /// rounding).
    /// None for the other kinds (their condition is another function beyond) and where
    /// the cycle does not go on beyond the corner.
    pub(super) fn past_corner(
        &self,
        prev: Option<&CurvePoint>,
        cur: &CurvePoint,
        tau: [f64; 2],
        corner: &Codim2,
    ) -> Option<(CurvePoint, [f64; 2])> {
        if !matches!(self.kind, CurveKind::BorderCollision { .. }) {
            return None;
        }
        if corner.kind != Codim2Kind::DoubleBorder {
            return None;
        }
        let (j, bp) = corner.impact?;
        // The twin impact of a doubled cycle on the same breakpoint: the cycle
        // collapses there onto the one of half its period, which is no corner.
        if self.kind.twin(&cur.cycle, (j, bp)) {
            return None;
        }
        let side = |q: &CurvePoint| signed_distance(q.cycle.phases[j], bp) < 0.0;
        let distance = |q: &CurvePoint| signed_distance(q.cycle.phases[j], bp).abs();
        let here = side(prev.filter(|p| distance(p) > distance(cur)).unwrap_or(cur));
        let y0 = [corner.alpha, corner.p];
        let came = [y0[0] - cur.alpha, y0[1] - cur.p];
        let len = came[0].hypot(came[1]);
        if len.is_nan() {
            return None;
        }
        let came = if len > 1e-9 * self.plane.scale() {
            [came[0] / len, came[1] / len]
        } else {
            tau
        };
        let mut beyond = |t: Tried<'_>| {
            side(t.q) != here && t.dist <= 10.0 * t.rho && self.plane.inside([t.q.alpha, t.q.p])
        };
        self.around(y0, came, 180.0, &cur.cycle, &mut beyond)
            .or_else(|| {
                // Where the other impact's border is a nonsmooth fold (two cycles, with
                // it on either side, meet on it and end there), the curve goes on along
                // the other cycle's border collision, back on the same side of that
                // border: a hairpin. Newton's method from this cycle finds this one
                // again; the other is solved with the impact held on the other piece.
                let other = self.held_across(cur, j, bp, here)?;
                self.around(y0, came, 180.0, &other, &mut beyond)
            })
            .or_else(|| {
                // And where this cycle's family, held, has another real cycle across
                // (three or more cycles near the corner), the one Newton's method finds
                // unheld from this cycle.
                let free = Tracer {
                    jumps: self.jumps.clone(),
                    hold: false,
                    ..*self
                };
                free.around(y0, came, 180.0, &cur.cycle, &mut beyond)
            })
    }

    /// The cycle at `cur`'s parameters with its impact `j` on the other side of the
    /// breakpoint `bp` than `before` says (true: before it), solved with that impact
    /// held on the piece there ([`periodic::solve_held`]); None where there is none.
    fn held_across(&self, cur: &CurvePoint, j: usize, bp: f64, before: bool) -> Option<CyclePoint> {
        let sys = self.plane.system(cur.alpha, cur.p).ok()?;
        let (ending, starting) = sys.table().segments_around(bp);
        let segment = if before { starting } else { ending };
        let c = &cur.cycle;
        let hold = periodic::Hold { impact: j, segment };
        let other = periodic::solve_held(
            &mut periodic::map_for(&sys),
            c.n,
            c.k,
            (c.t0, c.velocities[0]),
            &[hold],
        )
        .ok()?;
        ((signed_distance(other.phases[j], bp) < 0.0) != before).then_some(other)
    }

    /// The double border a border-collision curve is seeded on: another impact of its
    /// first point `first` on a breakpoint (to [`CONDITION_TOLERANCE`]), as the
    /// codimension-two point there on this curve (`index`).
    pub(super) fn seed_corner(&self, first: &CurvePoint, index: usize) -> Option<Codim2> {
        if !matches!(self.kind, CurveKind::BorderCollision { .. }) {
            return None;
        }
        let nb = self.jumps.len().max(1);
        let (j, t) = self.nearest_border(&first.cycle)?;
        (t.abs() <= CONDITION_TOLERANCE)
            .then(|| self.corner(first, index, (j / nb, self.jumps[j % nb]), t))
    }

    /// The double border at the point `q` of this curve (`index`), where the impact
    /// `impact` lies `second` from the breakpoint `bp`: a collapse where the doubled
    /// cycle has collapsed onto the cycle of half its period.
    pub(super) fn corner(
        &self,
        q: &CurvePoint,
        index: usize,
        (impact, bp): (usize, f64),
        second: f64,
    ) -> Codim2 {
        Codim2 {
            kind: if collapsed(&q.cycle) {
                Codim2Kind::Collapse
            } else {
                Codim2Kind::DoubleBorder
            },
            curve: index,
            alpha: q.alpha,
            p: q.p,
            condition: q.condition,
            second_condition: second,
            impact: Some((impact, bp)),
            meets: vec![index],
        }
    }

    /// The first curve point, solved from `guess`'s cycle on the lines across the
    /// directions [`TURNS`] within `max_turn` degrees of `base` at distances of 10⁻⁶,
    /// 10⁻⁵ and 10⁻⁴ of the plane from `y0`, that `accept` takes; with the unit
    /// direction from `y0` to it.
    fn around(
        &self,
        y0: [f64; 2],
        base: [f64; 2],
        max_turn: f64,
        guess: &CyclePoint,
        accept: &mut dyn FnMut(Tried<'_>) -> bool,
    ) -> Option<(CurvePoint, [f64; 2])> {
        let scale = self.plane.scale();
        for rho in [1e-6, 1e-5, 1e-4].map(|f| f * scale) {
            for deg in TURNS.iter().filter(|d| d.abs() <= max_turn) {
                let (s, c) = deg.to_radians().sin_cos();
                let dir = [c * base[0] - s * base[1], s * base[0] + c * base[1]];
                let y = [y0[0] + rho * dir[0], y0[1] + rho * dir[1]];
                if !self.plane.inside(y) {
                    continue;
                }
                let d = dir[0] * y0[0] + dir[1] * y0[1] + rho;
                let Ok((e, _)) = self.correct(y, dir, d, guess) else {
                    continue;
                };
                let q = self.point(e);
                let step = [q.alpha - y0[0], q.p - y0[1]];
                let dist = step[0].hypot(step[1]);
                let tried = Tried {
                    q: &q,
                    dir,
                    step,
                    dist,
                    rho,
                };
                if accept(tried) {
                    return Some((q, [step[0] / dist, step[1] / dist]));
                }
            }
        }
        None
    }

    /// The curve's point ahead of `cur` where a step along the tangent `tau` failed at
    /// every length: solved on lines across the directions within 75° of `tau`
    /// ([`TURNS`]) at distances of 10⁻⁶, 10⁻⁵ and 10⁻⁴ of the plane, the same cycle
    /// (the corrector's continuity test), ahead (of the tangent and of the last step
    /// `came`) and not across a breakpoint; with the direction it lies in.
    pub(super) fn ahead(
        &self,
        cur: &CurvePoint,
        tau: [f64; 2],
        came: Option<[f64; 2]>,
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> Option<(CurvePoint, [f64; 2])> {
        let y0 = [cur.alpha, cur.p];
        let scale = self.plane.scale();
        let dead = |d: &DeadEnd| {
            (d.kind, d.n, d.k) == (self.kind, self.n, self.k)
                && (d.at[0] - y0[0]).hypot(d.at[1] - y0[1]) <= 1e-9 * scale
        };
        if self.dead_ends.borrow().iter().any(dead) {
            return None;
        }
        let found = self.around(y0, tau, 75.0, &cur.cycle, &mut |t| {
            // Ahead along the tangent and along the last step: a point back the way the
            // curve came is the curve retraced, not its continuation.
            let s = t.step;
            let forward = s[0] * tau[0] + s[1] * tau[1] > 0.0
                && came.is_none_or(|c| s[0] * c[0] + s[1] * c[1] > 0.0);
            forward
                && t.dist <= 3.0 * t.rho
                && self.plane.inside([t.q.alpha, t.q.p])
                && !self.crosses_border(cur, t.q, t.dir, index, codim2)
        });
        if found.is_none() {
            self.dead_ends.borrow_mut().push(DeadEnd {
                kind: self.kind,
                n: self.n,
                k: self.k,
                at: y0,
            });
        }
        found
    }

    /// The codimension-two points located on this curve (`index`) where it stopped at
    /// `cur`: within [`AT_CODIM2`] of the plane.
    fn codim2_at<'c>(
        &self,
        cur: &CurvePoint,
        codim2: &'c [Codim2],
        index: usize,
    ) -> impl DoubleEndedIterator<Item = &'c Codim2> {
        let tol = AT_CODIM2 * self.plane.scale();
        let at = [cur.alpha, cur.p];
        codim2
            .iter()
            .filter(move |p| p.curve == index && (p.alpha - at[0]).hypot(p.p - at[1]) <= tol)
    }

    /// The double border located on this curve where it stopped, if any.
    pub(super) fn corner_at<'c>(
        &self,
        cur: &CurvePoint,
        codim2: &'c [Codim2],
        index: usize,
    ) -> Option<&'c Codim2> {
        self.codim2_at(cur, codim2, index)
            .rfind(|p| p.kind == Codim2Kind::DoubleBorder)
    }

    /// Where the curve stopped at a codimension-two point located on it: the end it
    /// makes ([`Codim2Kind::end`]).
    pub(super) fn end_at_codim2(
        &self,
        cur: &CurvePoint,
        codim2: &[Codim2],
        index: usize,
    ) -> Option<CurveEnd> {
        self.codim2_at(cur, codim2, index)
            .find_map(|p| p.kind.end())
    }
}

/// A corner a curve passed: where, how many of its points lie before it, and whether
/// the way on was checked against the arm it came by ([`comes_back`]).
#[derive(Clone, Copy)]
pub(super) struct Arm {
    pub(super) corner: [f64; 2],
    pub(super) at: usize,
    pub(super) checked: bool,
}

impl Arm {
    /// [`comes_back`] for `y` on the curve `out` past this corner: the arm it came by is
    /// `out`'s points before the corner, from the corner back, then `rest` (the curve
    /// behind `out`'s start, nearest first).
    pub(super) fn comes_back<'a>(
        &self,
        y: [f64; 2],
        out: &'a [CurvePoint],
        rest: impl Iterator<Item = &'a CurvePoint>,
        tol: f64,
    ) -> Option<bool> {
        let before = out[..self.at].iter().rev().chain(rest);
        comes_back(y, self.corner, before.map(|q| [q.alpha, q.p]), tol)
    }
}

/// Whether `y`, farther than a thousand times `tol` from `corner`, lies within `tol` of the
/// arm `before` that a curve came to the corner by (its points from the corner back,
/// followed at most twice `y`'s distance from the corner, the way a retrace comes): the
/// way found past the corner only led back ([`RETRACE`]). None while `y` is nearer the
/// corner than that.
fn comes_back(
    y: [f64; 2],
    corner: [f64; 2],
    before: impl Iterator<Item = [f64; 2]>,
    tol: f64,
) -> Option<bool> {
    let away = (y[0] - corner[0]).hypot(y[1] - corner[1]);
    if away <= 1e3 * tol {
        return None;
    }
    let mut arc = 0.0;
    let mut last: Option<[f64; 2]> = None;
    for b in before {
        if let Some(a) = last {
            if segment_distance(y, a, b) <= tol {
                return Some(true);
            }
            arc += (b[0] - a[0]).hypot(b[1] - a[1]);
            if arc > 2.0 * away + tol {
                break;
            }
        }
        last = Some(b);
    }
    Some(false)
}

#[cfg(test)]
mod tests {
    use super::comes_back;

    /// An arm to the corner at the origin along the diagonal from (1, 1), from the
    /// corner back.
    fn arm() -> impl Iterator<Item = [f64; 2]> {
        (0..=100).map(|i| {
            let s = i as f64 / 100.0;
            [s, s]
        })
    }

    #[test]
    fn a_way_past_a_corner_that_runs_back_along_the_arm_comes_back() {
        let tol = 1e-6;
        // Back along the arm, 0.014 from the corner (rounding off it by 1e-9).
        assert_eq!(
            comes_back([0.01, 0.01 + 1e-9], [0.0; 2], arm(), tol),
            Some(true)
        );
        // An arm leaving 2.6° from it: 6.4e-4 off at that distance.
        let th = (45.0f64 + 2.6).to_radians();
        let y = [0.0141 * th.cos(), 0.0141 * th.sin()];
        assert_eq!(comes_back(y, [0.0; 2], arm(), tol), Some(false));
        // Near the corner, where arms lie close whatever their angle, it is not told.
        assert_eq!(comes_back([1e-4, 1e-4], [0.0; 2], arm(), tol), None);
        // Only the arm up to twice the distance from the corner is looked at: coming
        // back onto it after a long way round is no retrace.
        let round = [[0.0, 0.0], [3.0, 0.0], [3.0, 0.01], [0.0, 0.01]].into_iter();
        assert_eq!(comes_back([0.5, 0.01], [0.0; 2], round, tol), Some(false));
        let round = [[0.0, 0.0], [3.0, 0.0], [3.0, 0.01], [0.0, 0.01]].into_iter();
        assert_eq!(comes_back([2.9, 0.01], [0.0; 2], round, tol), Some(true));
    }
}
