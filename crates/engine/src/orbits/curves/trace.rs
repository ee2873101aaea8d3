//! Following one two-parameter curve with the corrector of [`super::corrector`]: the
//! predictor steps and their halving, the window's edges, and the test functions of the
//! codimension-two points watched between consecutive points. Where the steps stop,
//! [`super::stops`] says why, or finds the way on ([`super::cusp`] through a fold
//! curve's cusp).

use super::corrector::{near_birth, Tracer};
use super::stops::{Arm, RETRACE};
use super::{
    Codim2, Codim2Kind, Curve, CurveEnd, CurveKind, CurvePoint, DeadEnd, Plane,
    CONDITION_TOLERANCE, MAX_STEPS,
};
use crate::orbits::continuation::Special;
use crate::orbits::periodic::{cycle, CyclePoint, PassError};
use crate::orbits::roots::bracketed_root_nan;
use crate::time::signed_distance;
use std::cell::RefCell;

/// Beyond a corner, steps under this share of the largest are not yet under way.
const CORNER_STEP: f64 = 1e-2;
/// A step under this share of the largest counts as small ...
const STALL_STEP: f64 = 1e-3;
/// ... and this many small steps in a row stall a curve ([`CurveEnd::Stalled`]).
const STALL_STEPS: usize = 60;
/// Times one direction of a curve may be taken up again past a point where its steps
/// failed ([`Tracer::ahead`]).
const MAX_RESCUES: usize = 4;

fn tangent(grad: [f64; 2], along: [f64; 2]) -> [f64; 2] {
    let s = grad[0].hypot(grad[1]);
    let t = [-grad[1] / s, grad[0] / s];
    if t[0] * along[0] + t[1] * along[1] < 0.0 {
        [-t[0], -t[1]]
    } else {
        t
    }
}

/// The line a curve's first point is solved on, c·y = d, from the point `start`.
#[derive(Clone, Copy, Debug)]
pub(super) struct SeedLine {
    pub(super) start: [f64; 2],
    pub(super) c: [f64; 2],
    pub(super) d: f64,
}

/// Follow one curve from the special point `s` found at second parameter `p` (its
/// first point solved for α at that p).
pub(super) fn follow(
    plane: &Plane,
    kind: CurveKind,
    s: &Special,
    p: f64,
    index: usize,
    dead_ends: &RefCell<Vec<DeadEnd>>,
) -> Result<(Curve, Vec<Codim2>), String> {
    let line = SeedLine {
        start: [s.alpha, p],
        c: [0.0, 1.0],
        d: p,
    };
    follow_from(plane, kind, s, line, index, dead_ends)
}

/// Follow one curve from the cycle of `s`, its first point solved on `line`.
pub(super) fn follow_from(
    plane: &Plane,
    kind: CurveKind,
    s: &Special,
    line: SeedLine,
    index: usize,
    dead_ends: &RefCell<Vec<DeadEnd>>,
) -> Result<(Curve, Vec<Codim2>), String> {
    let p = line.start[1];
    let jumps = plane.jumps(p);
    // Launch the cycle from its impact farthest from every breakpoint: at a launch on a
    // border the cycle's Jacobian jumps with f'' and Newton's method creeps.
    let clearance = |ph: f64| {
        jumps
            .iter()
            .map(|&b| signed_distance(ph, b).abs())
            .fold(f64::INFINITY, f64::min)
    };
    let n = s.point.n;
    let launch = (0..n)
        .max_by(|&a, &b| clearance(s.point.phases[a]).total_cmp(&clearance(s.point.phases[b])))
        .unwrap_or(0);
    let kind = match kind {
        CurveKind::BorderCollision { impact, breakpoint } => CurveKind::BorderCollision {
            impact: (impact + n - launch) % n,
            breakpoint,
        },
        other => other,
    };
    let guess = if launch == 0 {
        s.point.clone()
    } else {
        let sys = plane.system(line.start[0], p).map_err(|e| e.to_string())?;
        cycle(
            &sys,
            n,
            s.point.k,
            s.point.phases[launch],
            s.point.velocities[launch],
        )
        .map_err(|e| format!("the cycle could not be relaunched ({})", e.as_str()))?
    };
    let tr = Tracer {
        plane,
        kind,
        n,
        k: s.point.k,
        jumps,
        dead_ends,
        hold: true,
    };
    // The seed: solve G = 0 on the line (in α at fixed p, for a seed of the
    // continuation).
    let (e0, grad0) = tr
        .correct(line.start, line.c, line.d, &guess)
        .map_err(|e| format!("the seed could not be solved on the curve ({})", e.as_str()))?;
    let y0 = e0.y;
    let first = tr.point(e0);
    let mut halves: Vec<(Vec<CurvePoint>, CurveEnd)> = Vec::new();
    let mut codim2 = Vec::new();
    let t0 = tangent(grad0, line.c);
    let mut arms: [Vec<Arm>; 2] = Default::default();
    for (h, dir) in [1.0, -1.0].into_iter().enumerate() {
        // Behind the second half lie the first, from its far end, and the seed.
        let behind = behind(halves.first().map_or(&[], |(pts, _)| pts), &first);
        let from = Run {
            start: first.clone(),
            tau: [dir * t0[0], dir * t0[1]],
            origin: y0,
            beyond: None,
            behind: &behind,
        };
        let (pts, end) = tr.run(from, index, &mut codim2, &mut arms[h]);
        halves.push((pts, end));
    }
    // A border collision seeded on a double border (from the curve it crosses there)
    // may take no step at all one way: it goes on beyond the corner, on the other side
    // of the other impact's breakpoint from the half that got under way.
    for h in 0..2 {
        if !halves[h].0.is_empty() || halves[h].1 == CurveEnd::Window {
            continue;
        }
        // The other half's first point off the seed (not a corner vertex on it).
        let off = |q: &&CurvePoint| (q.alpha - y0[0]).hypot(q.p - y0[1]) > 1e-9 * plane.scale();
        let Some(arm) = halves[1 - h].0.iter().find(off).cloned() else {
            continue;
        };
        let Some(corner) = tr.seed_corner(&first, index) else {
            continue;
        };
        let sign = if h == 0 { 1.0 } else { -1.0 };
        let tau = [sign * t0[0], sign * t0[1]];
        if let Some((next, dir)) = tr.past_corner(Some(&arm), &first, tau, &corner) {
            let at = [corner.alpha, corner.p];
            codim2.push(corner);
            let behind = behind(&halves[1 - h].0, &first);
            let from = Run {
                start: next,
                tau: dir,
                origin: y0,
                beyond: Some(at),
                behind: &behind,
            };
            halves[h] = tr.run(from, index, &mut codim2, &mut arms[h]);
        }
    }
    // The first half did not know the second: a way it found past a corner that comes
    // back along the second half ends it at that corner.
    let tol = RETRACE * plane.scale();
    for arm in &arms[0] {
        let (fwd, back) = (&halves[0].0, &halves[1].0);
        let Some(beyond) = fwd.get(arm.at..) else {
            continue;
        };
        let back_along = beyond.iter().find_map(|q| {
            arm.comes_back([q.alpha, q.p], fwd, [&first].into_iter().chain(back), tol)
        });
        if back_along == Some(true) {
            halves[0].0.truncate(arm.at);
            halves[0].1 = CurveEnd::Border;
            break;
        }
    }
    let (back, back_end) = halves.pop().expect("two directions");
    let (fwd, fwd_end) = halves.pop().expect("two directions");
    // A closed curve found whole going one way: the other half repeats it (or part of
    // it, where a corner passed one way is not passed the other).
    let closed = fwd_end == CurveEnd::Closed || back_end == CurveEnd::Closed;
    let (back, fwd) = match (back_end, fwd_end) {
        (_, CurveEnd::Closed) => (Vec::new(), fwd),
        (CurveEnd::Closed, _) => (back, Vec::new()),
        _ => (back, fwd),
    };
    let mut points: Vec<CurvePoint> = back.into_iter().rev().collect();
    points.push(first);
    points.extend(fwd);
    let ends = if closed {
        [CurveEnd::Closed, CurveEnd::Closed]
    } else {
        [back_end, fwd_end]
    };
    Ok((
        Curve {
            kind,
            n: tr.n,
            k: tr.k,
            points,
            ends,
            seed: line.start,
        },
        codim2,
    ))
}

impl Tracer<'_> {
    /// One direction of a curve from `start` (not included in the result), or, where
    /// `start` is the curve's point just beyond the double border `beyond` it is
    /// seeded on, from that corner (`start` included). The corners it passes are added
    /// to `arms`.
    fn run(
        &self,
        from: Run<'_>,
        index: usize,
        codim2: &mut Vec<Codim2>,
        arms: &mut Vec<Arm>,
    ) -> (Vec<CurvePoint>, CurveEnd) {
        let Run {
            start,
            tau: tau0,
            origin,
            beyond,
            behind,
        } = from;
        let scale = self.plane.scale();
        let h_max = 0.005 * scale;
        let h_min = 1e-9 * scale;
        let mut h = 0.25 * h_max;
        let mut out: Vec<CurvePoint> = Vec::new();
        let mut cur = start;
        let mut prev: Option<CurvePoint> = None;
        let mut tau = tau0;
        let mut travelled = 0.0;
        let mut small = 0;
        // Points before the last corner passed while the curve is not yet under way
        // beyond it, and the short steps taken since.
        let mut corner: Option<usize> = None;
        let mut crawl = 0;
        let mut rescues = 0;
        let mut cusps = 0;
        // Corners passed, each once (a curve that came back to one it passed would
        // otherwise pass it to and fro).
        let mut passed: Vec<[f64; 2]> = Vec::new();
        if let Some(at) = beyond {
            passed.push(at);
            arms.push(Arm {
                corner: at,
                at: 0,
                checked: false,
            });
            corner = Some(0);
            out.push(cur.clone());
            h = (16.0 * h_min).max(1e-6 * scale);
        }
        // Go on from `next`, a point found off the tangent's way (beyond a corner, or
        // ahead where the steps failed), leaving in `dir` with short steps.
        macro_rules! resume_from {
            ($next:expr, $dir:expr) => {{
                tau = $dir;
                prev = None;
                cur = $next;
                out.push(cur.clone());
                h = (16.0 * h_min).max(1e-6 * scale);
                small = 0;
                continue;
            }};
        }
        // Go on beyond the corner (a double border) `at`, if the curve goes on there
        // ([`Self::past_corner`]) and did not pass it already.
        macro_rules! beyond_corner {
            ($at:expr) => {{
                let at: Option<&Codim2> = $at;
                let fresh = at.filter(|c| {
                    !passed
                        .iter()
                        .any(|q| (q[0] - c.alpha).hypot(q[1] - c.p) <= 1e-9 * scale)
                });
                if let Some(c) = fresh {
                    let y = [c.alpha, c.p];
                    if let Some((next, dir)) = self.past_corner(prev.as_ref(), &cur, tau, c) {
                        passed.push(y);
                        arms.push(Arm {
                            corner: y,
                            at: out.len(),
                            checked: false,
                        });
                        corner = Some(out.len());
                        crawl = 0;
                        resume_from!(next, dir);
                    }
                }
            }};
        }
        // Go on beyond a cusp, where a fold curve turns back on itself tangentially
        // ([`Self::past_cusp`]).
        macro_rules! beyond_cusp {
            () => {{
                if cusps < MAX_RESCUES {
                    if let Some((mut path, dir)) = self.past_cusp(&cur, tau, index, codim2) {
                        if let Some(next) = path.pop() {
                            cusps += 1;
                            out.extend(path);
                            resume_from!(next, dir);
                        }
                    }
                }
            }};
        }
        for _ in 0..MAX_STEPS {
            let y = [cur.alpha, cur.p];
            let pred = [y[0] + h * tau[0], y[1] + h * tau[1]];
            // The arclength condition, or, where the step would leave the window, the
            // point on the window's edge it crosses.
            let (start, c, d, at_edge) = if self.plane.inside(pred) {
                (pred, tau, tau[0] * y[0] + tau[1] * y[1] + h, false)
            } else {
                let (axis, bound) = self.edge(y, pred);
                let mut c = [0.0; 2];
                c[axis] = 1.0;
                let mut start = pred;
                start[axis] = bound;
                (start, c, bound, true)
            };
            // A step is refused where its point left the window or an impact crossed a
            // breakpoint the curve cannot cross.
            // The cycle guessed along the way it has been moving (a secant over the last
            // step), so an unstable cycle, which Newton's method finds only from close
            // by, is still found after a step of useful length.
            let guess = secant(
                prev.as_ref(),
                &cur,
                (start[0] - y[0]).hypot(start[1] - y[1]),
            );
            let known = codim2.len();
            let step = self.correct(start, c, d, &guess).and_then(|(e, grad)| {
                // A point outside the window is not this curve's to report, nor one
                // the corrector found far from the predicted point (on another part
                // of the curve, where it comes back close to itself).
                // A tangent off by θ puts the point h tan θ from the predicted one: a
                // step accepts up to 1.5 h (θ = 56°), and a small one, where the curve
                // may have a corner (another impact crossing a breakpoint turns it),
                // up to 2.75 h (θ = 70°).
                let off = (e.y[0] - start[0]).hypot(e.y[1] - start[1]);
                let reach = if h < STALL_STEP * h_max {
                    2.75 * h
                } else {
                    1.5 * h
                };
                let lost = !near_edge(self.plane, e.y) || off > reach;
                let next = (!lost).then(|| self.point(e));
                let corners = next
                    .as_ref()
                    .and_then(|next| self.corners_between(&cur, next, tau, index, codim2));
                match (next, corners) {
                    (Some(next), Some(corners)) => Ok((next, grad, corners)),
                    _ => Err(PassError::NoConvergence),
                }
            });
            match step {
                Ok((next, _, corners)) if at_edge => {
                    out.extend(corners);
                    out.push(next);
                    return (out, CurveEnd::Window);
                }
                Ok((next, grad, corners)) => {
                    // A step against the way the curve came: it turns back on itself.
                    if let Some(p) = &prev {
                        let back = (next.alpha - cur.alpha) * (cur.alpha - p.alpha)
                            + (next.p - cur.p) * (cur.p - p.p);
                        if back < 0.0 {
                            // Turning back where it meets a border or collapses is
                            // ending there.
                            // (A border collision goes on through a double border, as
                            // below: its last point may lie on the corner to rounding.)
                            if self.border_end(prev.as_ref(), &cur, index, codim2) {
                                beyond_corner!(codim2.last());
                                return (out, CurveEnd::Border);
                            }
                            if collapsing(&cur.cycle) {
                                return (out, CurveEnd::Collapse);
                            }
                            // At a double border located between the last points.
                            beyond_corner!(self.corner_at(&cur, codim2, index));
                            let end = self.end_at_codim2(&cur, codim2, index);
                            return (out, end.unwrap_or(CurveEnd::TurnedBack));
                        }
                    }
                    travelled += (next.alpha - cur.alpha).hypot(next.p - cur.p);
                    // A step across a double border turned the corner on the way: the
                    // curve beyond runs from the corner, not from where the step began.
                    let from = codim2[known..]
                        .iter()
                        .rfind(|q| q.curve == index && q.kind == Codim2Kind::DoubleBorder)
                        .map_or([cur.alpha, cur.p], |q| [q.alpha, q.p]);
                    tau = along_step(grad, from, &next, tau);
                    prev = Some(std::mem::replace(&mut cur, next));
                    // The corners turned on the way are the polyline's vertices.
                    out.extend(corners);
                    out.push(cur.clone());
                    // Beyond a corner, back along the arm it came by: the way found
                    // past the corner only led back, and the curve ends at the corner.
                    let y = [cur.alpha, cur.p];
                    for arm in arms.iter_mut().filter(|a| !a.checked) {
                        match arm.comes_back(y, &out, behind.iter().rev(), RETRACE * scale) {
                            Some(true) => {
                                out.truncate(arm.at);
                                return (out, CurveEnd::Border);
                            }
                            Some(false) => arm.checked = true,
                            None => {}
                        }
                    }
                    // Back at the start going the way it left: a closed curve (coming
                    // back the other way, it retraced itself).
                    if travelled > 4.0 * h_max
                        && (cur.alpha - origin[0]).hypot(cur.p - origin[1]) < 0.5 * h
                    {
                        let same = tau[0] * tau0[0] + tau[1] * tau0[1] > 0.0;
                        return (
                            out,
                            if same {
                                CurveEnd::Closed
                            } else {
                                CurveEnd::TurnedBack
                            },
                        );
                    }
                    // Past a corner the curve must get under way: steps that stay
                    // short ([`CORNER_STEP`]) for a while mean it was not found beyond
                    // after all, and it ends at the corner.
                    if let Some(at) = corner {
                        if h >= 0.1 * h_max {
                            corner = None;
                        } else if h < CORNER_STEP * h_max {
                            crawl += 1;
                            if crawl >= STALL_STEPS {
                                out.truncate(at);
                                return (out, CurveEnd::Border);
                            }
                        } else {
                            crawl = 0;
                        }
                    }
                    // Only tiny steps for a long while: the cycle changes too fast along
                    // the curve for the corrector to follow at any useful cost.
                    small = if h < STALL_STEP * h_max { small + 1 } else { 0 };
                    if small >= STALL_STEPS {
                        // Crawling toward the point where a doubled cycle is born from
                        // its parent (its halves close together) is ending there.
                        if near_birth(&cur.cycle) {
                            return (out, CurveEnd::Collapse);
                        }
                        // Crawling toward a border another impact is closing in on
                        // (f'' jumps there, and the slope of G with it) is reaching
                        // it: a border collision goes on through the corner.
                        if self.border_end(prev.as_ref(), &cur, index, codim2) {
                            beyond_corner!(codim2.last());
                            return (out, CurveEnd::Border);
                        }
                        beyond_cusp!();
                        return (out, CurveEnd::Stalled);
                    }
                    h = (h * 1.5).min(h_max);
                }
                Err(e) => {
                    h *= 0.5;
                    if h < h_min {
                        // Approaching a breakpoint, a PD, fold or grazing curve cannot
                        // cross it (its condition is another function beyond): the
                        // steps shrink toward the codimension-two point there.
                        if self.border_end(prev.as_ref(), &cur, index, codim2) {
                            // A border collision goes on through a double border:
                            // beyond the corner the other impact falls in the next
                            // piece, and the curve turns there.
                            beyond_corner!(codim2.last());
                            return (out, CurveEnd::Border);
                        }
                        // Stopped on the window's edge itself: it left the window.
                        if on_edge(self.plane, [cur.alpha, cur.p]) {
                            return (out, CurveEnd::Window);
                        }
                        // A doubled cycle whose halves are closing in: it ends where it
                        // is born from its parent.
                        if near_birth(&cur.cycle) {
                            return (out, CurveEnd::Collapse);
                        }
                        beyond_corner!(self.corner_at(&cur, codim2, index));
                        if let Some(end) = self.end_at_codim2(&cur, codim2, index) {
                            return (out, end);
                        }
                        beyond_cusp!();
                        // The step along the tangent failed at every length: the
                        // tangent may be off (at a point where the cycle's branch folds
                        // over the plane, the gradient is poorly defined). The curve
                        // ahead is looked for in other directions before it is given up.
                        if rescues < MAX_RESCUES && e == PassError::NoConvergence {
                            let came = prev.as_ref().map(|p| [cur.alpha - p.alpha, cur.p - p.p]);
                            if let Some((next, dir)) = self.ahead(&cur, tau, came, index, codim2) {
                                rescues += 1;
                                resume_from!(next, dir);
                            }
                        }
                        return (out, CurveEnd::from_error(e));
                    }
                }
            }
        }
        (out, CurveEnd::StepLimit)
    }

    /// The edge of the search range crossed going from `y` (inside) to `pred` (outside).
    fn edge(&self, y: [f64; 2], pred: [f64; 2]) -> (usize, f64) {
        let w = [self.plane.search_alpha(), self.plane.window];
        crossing(w, y, pred).map_or((0, w[0].0), |(axis, bound, _)| (axis, bound))
    }

    /// Watch the test functions between `a` and `b` (consecutive points): locate each
    /// sign change and record its codimension-two point. True where an impact crossed a
    /// breakpoint on a curve that cannot cross one (all but border collisions): the
    /// step is then refused.
    pub(super) fn crosses_border(
        &self,
        a: &CurvePoint,
        b: &CurvePoint,
        tau: [f64; 2],
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> bool {
        self.corners_between(a, b, tau, index, codim2).is_none()
    }

    /// [`Self::crosses_border`]'s watch, with the step's corners: the curve's points on
    /// the double borders it passed between `a` and `b`, in order (the vertices its
    /// polyline turns at). None where the step is refused.
    pub(super) fn corners_between(
        &self,
        a: &CurvePoint,
        b: &CurvePoint,
        tau: [f64; 2],
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> Option<Vec<CurvePoint>> {
        let mut corners: Vec<(f64, CurvePoint)> = Vec::new();
        let ta = self.border_tests(&a.cycle);
        let tb = self.border_tests(&b.cycle);
        let nb = self.jumps.len().max(1);
        let h = tau[0] * (b.alpha - a.alpha) + tau[1] * (b.p - a.p);
        // The curve at arclength s from a.
        let at = |s: f64| -> Option<CurvePoint> {
            let y = [a.alpha + s * tau[0], a.p + s * tau[1]];
            self.correct(y, tau, tau[0] * a.alpha + tau[1] * a.p + s, &a.cycle)
                .ok()
                .map(|(e, _)| self.point(e))
        };
        for (j, (&ga, &gb)) in ta.iter().zip(&tb).enumerate() {
            if (ga < 0.0) == (gb < 0.0) || (ga - gb).abs() > 0.5 {
                continue;
            }
            // Past a breakpoint f'' differs: a PD, fold or grazing condition is another
            // function there, and a point beyond is on another curve. The step is
            // refused, and the shrinking steps close in on the border ([`border_end`]).
            if !matches!(self.kind, CurveKind::BorderCollision { .. }) {
                return None;
            }
            let (impact, bp) = (j / nb, self.jumps[j % nb]);
            let test = |q: &CurvePoint| signed_distance(q.cycle.phases[impact], bp);
            let mut g = |s: f64| at(s).map_or(f64::NAN, |q| test(&q));
            // A crossing that cannot be located on the curve between the two points is
            // no crossing of this curve: the step jumped onto another curve close by
            // (two arms of a cusp, the other impact on either side of its breakpoint),
            // and is refused.
            let (s, q) =
                bracketed_root_nan(&mut g, 0.0, h, ga, gb).and_then(|s| Some((s, at(s)?)))?;
            let second = test(&q);
            if second.abs() > CONDITION_TOLERANCE {
                return None;
            }
            codim2.push(self.corner(&q, index, (impact, bp), second));
            // A vertex where the step begins or ends is that point already.
            let apart =
                |r: &CurvePoint| (q.alpha - r.alpha).hypot(q.p - r.p) > 1e-9 * self.plane.scale();
            if apart(a) && apart(b) {
                corners.push((s, q));
            }
        }
        if let (Some(ca), Some(cb)) = (a.criticality, b.criticality) {
            if ca.supercritical().is_some()
                && cb.supercritical().is_some()
                && ca.supercritical() != cb.supercritical()
            {
                let mut g = |s: f64| at(s).and_then(|q| q.criticality).map_or(f64::NAN, |c| c.c);
                if let Some(s) = bracketed_root_nan(&mut g, 0.0, h, ca.c, cb.c) {
                    if let Some(q) = at(s) {
                        codim2.push(Codim2 {
                            kind: Codim2Kind::DegenerateFlip,
                            curve: index,
                            alpha: q.alpha,
                            p: q.p,
                            condition: q.condition,
                            second_condition: q.criticality.map_or(f64::NAN, |c| c.c),
                            impact: None,
                            meets: vec![index],
                        });
                    }
                }
            }
        }
        corners.sort_by(|x, y| x.0.total_cmp(&y.0));
        Some(corners.into_iter().map(|(_, q)| q).collect())
    }
}

/// The tangent at `next` from its gradient, pointing on the way from `from` (where the
/// step began, or the corner it turned) to `next`; that direction itself where the two
/// are more than 60° apart. There the gradient is not the curve's: next to a double
/// border the differences that make it may straddle the other impact's breakpoint (f''
/// jumps there), and the step has just turned the curve's corner.
fn along_step(grad: [f64; 2], from: [f64; 2], next: &CurvePoint, tau: [f64; 2]) -> [f64; 2] {
    let chord = [next.alpha - from[0], next.p - from[1]];
    let len = chord[0].hypot(chord[1]);
    if !(len > 0.0 && len.is_finite()) {
        return tangent(grad, tau);
    }
    let chord = [chord[0] / len, chord[1] / len];
    let t = tangent(grad, chord);
    if t[0] * chord[0] + t[1] * chord[1] >= 0.5 {
        t
    } else {
        chord
    }
}

/// `cur`'s cycle moved on by `h` along the curve as it moved from `prev` (its launch
/// time and velocity extrapolated linearly; `cur`'s own without a previous point).
pub(super) fn secant(prev: Option<&CurvePoint>, cur: &CurvePoint, h: f64) -> CyclePoint {
    let mut guess = cur.cycle.clone();
    let Some(prev) = prev else { return guess };
    let last = (cur.alpha - prev.alpha).hypot(cur.p - prev.p);
    if !(last > 0.0 && h.is_finite()) {
        return guess;
    }
    let f = (h / last).min(4.0);
    let dt = cur.cycle.t0 - prev.cycle.t0;
    let dv = cur.cycle.velocities[0] - prev.cycle.velocities[0];
    // Only a launch that moved continuously (not one that jumped to another impact).
    if dt.abs() > 0.05 || dv.abs() > 0.05 * (1.0 + cur.cycle.velocities[0].abs()) {
        return guess;
    }
    guess.t0 += f * dt;
    guess.velocities[0] += f * dv;
    guess.phases[0] = crate::time::wrap_phase(guess.t0);
    guess
}

/// The points of a curve behind a half that starts at its seed `first`: the other half
/// `other` from its far end, then the seed (nearest last, as [`Run::behind`]).
fn behind(other: &[CurvePoint], first: &CurvePoint) -> Vec<CurvePoint> {
    other.iter().rev().chain([first]).cloned().collect()
}

/// Where one direction of a curve starts ([`Tracer::run`]): its first point, the way
/// it leaves, the curve's seed (to tell it closed), the double border `start` lies
/// just beyond where it is seeded on one, and the points of the curve behind `start`
/// (nearest last), which a way past a corner must not come back along.
struct Run<'a> {
    start: CurvePoint,
    tau: [f64; 2],
    origin: [f64; 2],
    beyond: Option<[f64; 2]>,
    behind: &'a [CurvePoint],
}

/// Whether a doubled cycle is about to collapse (its halves within 1e-5 of each
/// other): where the steps shrink toward a collapse they cannot pass.
fn collapsing(pt: &CyclePoint) -> bool {
    pt.half_return
        .is_some_and(|[dt, dv]| dt.abs().max(dv.abs()) <= 1e-5)
}

/// The first edge of the window `w` (α range, second parameter's range) the segment
/// from `y` to `pred` crosses: its axis, its value and the share of the segment there.
pub(super) fn crossing(
    w: [(f64, f64); 2],
    y: [f64; 2],
    pred: [f64; 2],
) -> Option<(usize, f64, f64)> {
    let mut best: Option<(usize, f64, f64)> = None;
    for axis in 0..2 {
        for bound in [w[axis].0, w[axis].1] {
            let d = pred[axis] - y[axis];
            if d == 0.0 {
                continue;
            }
            let t = (bound - y[axis]) / d;
            if (0.0..=1.0).contains(&t) && best.is_none_or(|b| t < b.2) {
                best = Some((axis, bound, t));
            }
        }
    }
    best
}

/// Whether y lies on the boundary of the search range (to 1e-9 of the window's size).
fn on_edge(plane: &Plane, y: [f64; 2]) -> bool {
    let tol = 1e-9 * plane.scale();
    let w = [plane.search_alpha(), plane.window];
    (0..2).any(|i| (y[i] - w[i].0).abs() <= tol || (y[i] - w[i].1).abs() <= tol)
}

/// Whether y lies in the search range (to 1e-9 of the window's size).
fn near_edge(plane: &Plane, y: [f64; 2]) -> bool {
    plane.spans(plane.search_alpha(), y, 1e-9 * plane.scale())
}
