//! The corrector of one two-parameter curve: the condition G of the exactly solved
//! cycle at a point of the plane ([`Eval`]), its gradient by central differences,
//! Newton's method on (G = 0, c·y = d) with the cycle solved at fixed parameters, and
//! the extended system (the cycle's equations with the condition, in α, p, t₀, v₀) for
//! folds and where the fixed solve fails. [`super::trace`] steps along the curve with it.

use super::criticality::criticality;
use super::{CurveKind, CurvePoint, Plane, CONDITION_TOLERANCE};
use crate::linalg::solve;
use crate::orbits::periodic::{self, cycle, map_for, pass, CyclePoint, PassError};
use crate::system::System;
use crate::time::signed_distance;

/// A Newton step over this share of the one before no longer converges: the iterates
/// wander in the condition's rounding noise.
const STAGNATION: f64 = 0.5;

/// Differences of a border collision's condition that mix its two pieces are taken
/// for the point's own piece's gradient while their directions agree to within 20°
/// (this cosine).
const MIXED: f64 = 0.94;

/// The relative change of the solved variables a condition's rounding floor is taken
/// at: the cycle is solved to about 1e-14, and the point's coordinates are known to a
/// few units in the last place beyond that.
const ROUNDING: f64 = 1e-14;

/// An impact of the guessed cycle this near a breakpoint is held on its piece while the
/// cycle is solved ([`periodic::Hold`]).
const HOLD_NEAR: f64 = 1e-4;

/// The cycle and the condition at a point of the plane.
#[derive(Clone, Debug)]
pub(super) struct Eval {
    pub(super) y: [f64; 2],
    pub(super) sys: System,
    pub(super) pt: CyclePoint,
    pub(super) g: f64,
    /// G's rounding floor there, where G does not hold to [`CONDITION_TOLERANCE`]
    /// ([`CurvePoint::floor`]).
    pub(super) floor: Option<f64>,
}

pub(super) struct Tracer<'a> {
    pub(super) plane: &'a Plane,
    pub(super) kind: CurveKind,
    pub(super) n: usize,
    pub(super) k: u32,
    pub(super) jumps: Vec<f64>,
    /// Where curves of this run found no point ahead (every kind and cycle: the
    /// tracer looks for its own), shared by all its traces.
    pub(super) dead_ends: &'a std::cell::RefCell<Vec<super::DeadEnd>>,
    /// Whether the guess's impacts next to a breakpoint are held on their pieces while
    /// the cycle is solved ([`HOLD_NEAR`]).
    pub(super) hold: bool,
}

impl Tracer<'_> {
    pub(super) fn eval(&self, y: [f64; 2], guess: &CyclePoint) -> Result<Eval, PassError> {
        let sys = self
            .plane
            .system(y[0], y[1])
            .map_err(|_| PassError::BadLaunch)?;
        let holds = if self.hold {
            self.held_impacts(&sys, guess)
        } else {
            Vec::new()
        };
        let real = || cycle(&sys, self.n, self.k, guess.t0, guess.velocities[0]);
        let pt = if holds.is_empty() {
            real()?
        } else {
            match periodic::solve_held(
                &mut periodic::map_for(&sys),
                self.n,
                self.k,
                (guess.t0, guess.velocities[0]),
                &holds,
            ) {
                Ok(pt) => pt,
                Err(first) => real().map_err(|_| first)?,
            }
        };
        // The same cycle, not another one nearby: the launch moved continuously, and a
        // doubled cycle did not fall onto the cycle of half its period run twice (next
        // to its birth Newton's method may find that one, also a cycle of n impacts).
        if moved(&pt, guess) > 0.05 || (collapsed(&pt) && !collapsed(guess)) {
            return Err(PassError::NoConvergence);
        }
        let g = self.kind.condition(&sys, &pt);
        if !g.is_finite() {
            return Err(PassError::NoConvergence);
        }
        Ok(Eval {
            y,
            sys,
            pt,
            g,
            floor: None,
        })
    }

    /// ∇G by central differences, the cycle re-solved at each.
    pub(super) fn gradient(&self, e: &Eval) -> Result<[f64; 2], PassError> {
        let border = matches!(self.kind, CurveKind::BorderCollision { .. });
        let own = border && e.g != 0.0;
        let tests = self.border_tests(&e.pt);
        // A difference is taken within the pieces of the point's cycle: every other
        // impact on its side of every breakpoint (next to a double border a step may
        // cross, and beyond, the condition is another function, whose zero set is
        // another curve), and for a border collision its own impact on the point's
        // side too (its condition has its kink on the curve itself, and across it
        // Newton's method converges only linearly).
        let keeps = |q: &Eval| {
            let crossed = self
                .border_tests(&q.pt)
                .iter()
                .zip(&tests)
                .any(|(a, b)| (a < &0.0) != (b < &0.0) && (a - b).abs() <= 0.5);
            !crossed && (!own || ((q.g < 0.0) == (e.g < 0.0) && q.g != 0.0))
        };
        let mut grad = [0.0; 2];
        // For a border collision, the side of its breakpoint (G < 0) each component's
        // difference was taken on, None where it straddles it.
        let mut sides = [None; 2];
        for (i, g) in grad.iter_mut().enumerate() {
            let h = 1e-7 * (1.0 + e.y[i].abs());
            let mut plus = e.y;
            let mut minus = e.y;
            plus[i] += h;
            minus[i] -= h;
            let valid = |y: [f64; 2]| self.plane.system(y[0], y[1]).is_ok();
            // Central where the cycle exists on both sides within its pieces; else
            // one-sided: at the end of the parameter's range (D = 0 or 1), where the
            // cycle ends on one side (at a grazing the flight would cross the table
            // beyond the curve), or where one side lies in other pieces.
            let at = |y: [f64; 2]| valid(y).then(|| self.eval(y, &e.pt).ok()).flatten();
            let difference = |p: Option<&Eval>, m: Option<&Eval>| match (p, m) {
                (Some(p), Some(m)) => Some(((p.g - m.g) / (2.0 * h), [p.g, m.g])),
                (Some(p), None) => Some(((p.g - e.g) / h, [p.g, e.g])),
                (None, Some(m)) => Some(((e.g - m.g) / h, [e.g, m.g])),
                (None, None) => None,
            };
            let (p, m) = (at(plus), at(minus));
            let (pk, mk) = (
                p.as_ref().filter(|q| keeps(q)),
                m.as_ref().filter(|q| keeps(q)),
            );
            let (d, ends) = difference(pk, mk)
                .or_else(|| difference(p.as_ref(), m.as_ref()))
                .ok_or(PassError::NoConvergence)?;
            *g = d;
            // The side of the values differenced (the point's own value, on the
            // curve, takes its partner's).
            let side = |v: f64, w: f64| if v == 0.0 { w < 0.0 } else { v < 0.0 };
            let (a, b) = (side(ends[0], ends[1]), side(ends[1], ends[0]));
            sides[i] = (a == b).then_some(a);
        }
        if !(grad[0].is_finite() && grad[1].is_finite()) || grad == [0.0, 0.0] {
            return Err(PassError::NoConvergence);
        }
        // A border collision's condition has a kink on the curve: differences that
        // straddle it in both directions average the two pieces' gradients, which share
        // the curve's tangent, and so do differences on one piece. But at a point on
        // the breakpoint exactly (G = 0, no side of its own to keep them on), one
        // direction on one piece and the other on the other (where two cycles, one on
        // either piece, meet on the border and end there, each existing on one side of
        // the curve only) mix them, and give another direction: there the gradient is
        // the point's own piece's. Unless another impact lies within 10⁻⁶ of a
        // breakpoint: the extended system's differences would straddle that one.
        let clear = tests.iter().all(|t| t.abs() > 1e-6);
        if border && clear && sides[0] != sides[1] {
            if let Ok(piece) = self.piece_gradient(e) {
                let cos = (grad[0] * piece[0] + grad[1] * piece[1]).abs()
                    / (grad[0].hypot(grad[1]) * piece[0].hypot(piece[1]));
                if cos < MIXED {
                    return Ok(piece);
                }
            }
        }
        Ok(grad)
    }

    /// ∇G on the point's own piece (for a border collision, the side of the breakpoint
    /// its impact lies on: G ≥ 0 the piece after it), from the extended system's
    /// Jacobian: G's partial derivatives less those through the cycle moving, G_x (M −
    /// I)⁻¹ A, A the cycle equations' columns in α and p.
    fn piece_gradient(&self, e: &Eval) -> Result<[f64; 2], PassError> {
        let x = [e.y[0], e.y[1], e.pt.t0, e.pt.velocities[0]];
        let (f, p) = self.fold_system(x)?;
        let j = self.extended_jacobian(x, f, &p)?;
        let a = [[j[0][2], j[0][3]], [j[1][2], j[1][3]]];
        let mut grad = [0.0; 2];
        for (i, g) in grad.iter_mut().enumerate() {
            let z = solve(a, [j[0][i], j[1][i]]).ok_or(PassError::NoConvergence)?;
            *g = j[2][i] - (j[2][2] * z[0] + j[2][3] * z[1]);
        }
        if !(grad[0].is_finite() && grad[1].is_finite()) || grad == [0.0, 0.0] {
            return Err(PassError::NoConvergence);
        }
        Ok(grad)
    }

    /// Newton's method on (G = 0, c·y = d) from `y`.
    pub(super) fn correct(
        &self,
        y: [f64; 2],
        c: [f64; 2],
        d: f64,
        guess: &CyclePoint,
    ) -> Result<(Eval, [f64; 2]), PassError> {
        let found = if self.kind == CurveKind::Fold {
            self.correct_fold(y, c, d, guess)
        } else {
            let fixed = self.correct_fixed(y, c, d, guess);
            let extended = !matches!(self.kind, CurveKind::Grazing { .. } | CurveKind::Birth);
            match fixed {
                Err(first) if extended => self.correct_fold(y, c, d, guess).map_err(|_| first),
                other => other,
            }
        };
        // A doubled cycle that has collapsed onto the one of half its period is that
        // cycle, not this curve's: the curve ends before it (a collapse). And the cycle
        // found must be the one guessed, moved on continuously, not another one the
        // extended system slid to.
        match found {
            Ok((e, _)) if collapsed(&e.pt) && !collapsed(guess) => Err(PassError::NoConvergence),
            Ok((e, _)) if moved(&e.pt, guess) > 0.05 => Err(PassError::NoConvergence),
            other => other,
        }
    }

    /// [`Self::correct`] with the cycle solved at fixed parameters at every iterate.
    pub(super) fn correct_fixed(
        &self,
        y: [f64; 2],
        c: [f64; 2],
        d: f64,
        guess: &CyclePoint,
    ) -> Result<(Eval, [f64; 2]), PassError> {
        let mut e = self.eval(y, guess)?;
        let mut last = f64::INFINITY;
        for _ in 0..20 {
            let grad = self.gradient(&e)?;
            let a = [grad, c];
            let b = [e.g, c[0] * e.y[0] + c[1] * e.y[1] - d];
            let step = solve(a, b).ok_or(PassError::NoConvergence)?;
            let size = step[0].abs().max(step[1].abs());
            if !size.is_finite() || size > 0.5 {
                return Err(PassError::NoConvergence);
            }
            // Backtracking: where the full step leaves the cycle's domain (a grazing or
            // a vanishing impact velocity beyond the curve), shorter ones approach the
            // curve from its own side.
            let mut lambda = 1.0;
            let next = loop {
                let yn = [e.y[0] - lambda * step[0], e.y[1] - lambda * step[1]];
                match self.eval(yn, &e.pt) {
                    Ok(n) => break n,
                    Err(err) if lambda < 1e-3 => return Err(err),
                    Err(_) => lambda *= 0.5,
                }
            };
            e = next;
            // Converged when the step is at rounding level, or when both equations
            // already hold to it (at a border the gradient has a kink, and Newton's
            // method creeps the last digits). The cycle is solved to about 1e-14, so G
            // is known to about 1e-13: the point is taken to 1e-12.
            // Where G is known only to more than that (a cycle whose monodromy has
            // large entries: its trace, of order one, is their small difference),
            // Newton's steps stop shrinking at G's noise: the point is taken there
            // once G holds to a tenth of the tolerance.
            let tiny = 1e-12 * (1.0 + e.y[0].abs().max(e.y[1].abs()));
            let held = e.g.abs() < 1e-12 && (c[0] * e.y[0] + c[1] * e.y[1] - d).abs() < tiny;
            let noise = lambda * size > STAGNATION * last
                && self.holds(10.0 * e.g, || self.floor_fixed(&e));
            last = lambda * size;
            if lambda * size < tiny || held || noise {
                if e.g.abs() > CONDITION_TOLERANCE {
                    let floor = self.floor_fixed(&e);
                    if e.g.abs() > floor {
                        return Err(PassError::NoConvergence);
                    }
                    e.floor = Some(floor);
                }
                let grad = self.gradient(&e)?;
                return Ok((e, grad));
            }
        }
        Err(PassError::NoConvergence)
    }

    /// The condition from a pass of the map at x = (α, p, t₀, v₀), whether or not the
    /// orbit closes yet (None for the kinds that need the closed cycle: grazing,
    /// birth).
    pub(super) fn pass_condition(
        &self,
        sys: &System,
        x: [f64; 4],
        p: &periodic::Pass,
    ) -> Option<f64> {
        let tr = p.monodromy[0][0] + p.monodromy[1][1];
        let det = sys.r().powi(2 * self.n as i32);
        match self.kind {
            CurveKind::PeriodDoubling => Some(1.0 + tr + det),
            CurveKind::Fold => Some(1.0 - tr + det),
            CurveKind::BorderCollision { impact, breakpoint } => {
                let ph = if impact == 0 {
                    crate::time::wrap_phase(x[2])
                } else {
                    *p.phases.get(impact - 1)?
                };
                Some(signed_distance(ph, breakpoint))
            }
            CurveKind::Grazing { landing: true } => Some(
                p.impact_speeds
                    .iter()
                    .cloned()
                    .fold(f64::INFINITY, f64::min),
            ),
            CurveKind::Grazing { landing: false } | CurveKind::Birth => None,
        }
    }

    /// The extended system at x = (α, p, t₀, v₀): the cycle's residual
    /// (tₙ − t₀ − k, vₙ − v₀) and the condition, with the pass.
    pub(super) fn fold_system(&self, x: [f64; 4]) -> Result<([f64; 3], periodic::Pass), PassError> {
        let sys = self
            .plane
            .system(x[0], x[1])
            .map_err(|_| PassError::BadLaunch)?;
        let mut map = map_for(&sys);
        let p = pass(&mut map, x[2], x[3], self.n, self.k)?;
        let g = self
            .pass_condition(&sys, x, &p)
            .filter(|g| g.is_finite())
            .ok_or(PassError::NoConvergence)?;
        Ok(([p.residual[0], p.residual[1], g], p))
    }

    /// The extended system's Jacobian at x (f and p its value and pass there): the
    /// map's own derivatives give the cycle equations' columns in α, t₀ and v₀; forward
    /// differences give the p column and the condition's row.
    pub(super) fn extended_jacobian(
        &self,
        x: [f64; 4],
        f: [f64; 3],
        p: &periodic::Pass,
    ) -> Result<[[f64; 4]; 3], PassError> {
        // On a border collision the point's impact lies on the breakpoint, where f''
        // jumps and the map's derivatives jump with it: the map's own derivatives are
        // those of the piece the impact's phase falls in (G ≥ 0: the one after the
        // breakpoint), and the p column must be a difference on that same side, or the
        // Jacobian, mixed from two pieces, has the wrong null vector (both pieces
        // agree along the border, so either one's gives the curve's tangent).
        let border = matches!(self.kind, CurveKind::BorderCollision { .. });
        let m = p.monodromy;
        let mut j = [
            [p.alpha_column[0], 0.0, m[0][0] - 1.0, m[0][1]],
            [p.alpha_column[1], 0.0, m[1][0], m[1][1] - 1.0],
            [0.0; 4],
        ];
        // The p column on the side of the point's own piece (a border collision).
        let mut side_column = None;
        if border {
            let h = 1e-7 * (1.0 + x[1].abs());
            let side = |g: f64| g >= 0.0;
            for s in [1.0, -1.0] {
                let mut xs = x;
                xs[1] += s * h;
                match self.fold_system(xs) {
                    Ok((fs, _)) if side(fs[2]) == side(f[2]) => {
                        side_column = Some([(fs[0] - f[0]) / (s * h), (fs[1] - f[1]) / (s * h)]);
                        break;
                    }
                    _ => {}
                }
            }
        }
        for col in 0..4 {
            let h = 1e-7 * (1.0 + x[col].abs());
            let mut xp = x;
            xp[col] += h;
            let (fp, _) = self.fold_system(xp)?;
            j[2][col] = (fp[2] - f[2]) / h;
            if col == 1 {
                let [a, b] = side_column.unwrap_or([(fp[0] - f[0]) / h, (fp[1] - f[1]) / h]);
                j[0][1] = a;
                j[1][1] = b;
            }
        }
        Ok(j)
    }

    /// Newton's method on the extended system (the cycle's equations and the
    /// condition, in α, p, t₀, v₀) with c·(α, p) = d. At a fold the cycle cannot be
    /// solved at fixed parameters (M − I is singular), so a fold curve is always solved
    /// with them; the other kinds come here where the cycle at fixed parameters cannot
    /// be solved (a curve passing where its cycle's branch folds over the parameters).
    pub(super) fn correct_fold(
        &self,
        y: [f64; 2],
        c: [f64; 2],
        d: f64,
        guess: &CyclePoint,
    ) -> Result<(Eval, [f64; 2]), PassError> {
        let x = [y[0], y[1], guess.t0, guess.velocities[0]];
        self.extended(x, [c[0], c[1], 0.0, 0.0], d)
            .map(|(e, grad, _)| (e, grad))
    }

    /// Newton's method on the extended system with row·x = d, from x = (α, p, t₀, v₀):
    /// the point, the gradient its tangent in (α, p) is orthogonal to, and the curve's
    /// tangent in all four (the Jacobian's null vector, [`null_vector`]).
    pub(super) fn extended(
        &self,
        mut x: [f64; 4],
        row: [f64; 4],
        d: f64,
    ) -> Result<(Eval, [f64; 2], [f64; 4]), PassError> {
        let mut last = f64::INFINITY;
        for _ in 0..30 {
            let (f, p) = self.fold_system(x)?;
            let j = self.extended_jacobian(x, f, &p)?;
            let a = [j[0], j[1], j[2], row];
            let b = [f[0], f[1], f[2], dot(row, x) - d];
            let step = solve(a, b).ok_or(PassError::NoConvergence)?;
            let size = step.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if !size.is_finite() || size > 0.5 {
                return Err(PassError::NoConvergence);
            }
            for i in 0..4 {
                x[i] -= step[i];
            }
            // As in [`Self::correct_fixed`]: steps that stop shrinking at the
            // condition's noise, the cycle closed and the condition held to a tenth of
            // what it must, are converged too.
            let noise = size > STAGNATION * last
                && f[0].abs().max(f[1].abs()) <= 1e-12 * (1.0 + x[3].abs())
                && self.holds(10.0 * f[2], || self.floor_extended(x));
            last = size;
            if size < 1e-12 * (1.0 + x[3].abs()) || noise {
                let (f, p) = self.fold_system(x)?;
                let floor = if f[2].abs() > CONDITION_TOLERANCE {
                    let floor = self.floor_extended(x);
                    if f[2].abs() > floor {
                        return Err(PassError::NoConvergence);
                    }
                    Some(floor)
                } else {
                    None
                };
                let j = self.extended_jacobian(x, f, &p)?;
                let sys = self
                    .plane
                    .system(x[0], x[1])
                    .map_err(|_| PassError::BadLaunch)?;
                let pt = periodic::accept(&sys, [x[0], x[2], x[3]], self.n, self.k, &p)?;
                // The curve's tangent in (α, p): the null vector of the extended
                // system's Jacobian, normalised on (α, p); returned as the gradient it is
                // orthogonal to.
                let a = [j[0], j[1], j[2], [1.0, 0.0, 0.0, 0.0]];
                let a2 = [j[0], j[1], j[2], [0.0, 1.0, 0.0, 0.0]];
                let t = solve(a, [0.0, 0.0, 0.0, 1.0])
                    .filter(|t| t.iter().all(|v| v.is_finite()))
                    .or_else(|| solve(a2, [0.0, 0.0, 0.0, 1.0]))
                    .unwrap_or([f64::NAN; 4]);
                let full = null_vector(j);
                let t = if t.iter().all(|v| v.is_finite()) {
                    t
                } else if full.iter().all(|v| v.is_finite()) && (full[0], full[1]) != (0.0, 0.0) {
                    full
                } else {
                    return Err(PassError::NoConvergence);
                };
                let e = Eval {
                    y: [x[0], x[1]],
                    sys,
                    pt,
                    g: f[2],
                    floor,
                };
                return Ok((e, [t[1], -t[0]], full));
            }
        }
        Err(PassError::NoConvergence)
    }

    /// Whether |G| holds: to [`CONDITION_TOLERANCE`], or, where it does not, to its
    /// rounding `floor` (computed only then).
    fn holds(&self, g: f64, floor: impl FnOnce() -> f64) -> bool {
        g.abs() <= CONDITION_TOLERANCE || g.abs() <= floor()
    }

    /// G's rounding floor at the point `e` of the corrector at fixed parameters: the
    /// sum over α and p of how much G changes (the cycle re-solved) when that one
    /// moves by [`ROUNDING`] of itself (plus one). Zero where a cycle there is not
    /// found.
    fn floor_fixed(&self, e: &Eval) -> f64 {
        (0..2)
            .map(|i| {
                let mut y = e.y;
                y[i] += ROUNDING * (1.0 + y[i].abs());
                self.eval(y, &e.pt).map_or(f64::NAN, |q| (q.g - e.g).abs())
            })
            .sum::<f64>()
            .max(0.0)
    }

    /// The same for the extended system at x = (α, p, t₀, v₀): G from a pass of the
    /// map, each of the four moved in turn.
    fn floor_extended(&self, x: [f64; 4]) -> f64 {
        let Ok((f, _)) = self.fold_system(x) else {
            return 0.0;
        };
        (0..4)
            .map(|i| {
                let mut xs = x;
                xs[i] += ROUNDING * (1.0 + xs[i].abs());
                self.fold_system(xs)
                    .map_or(f64::NAN, |(fs, _)| (fs[2] - f[2]).abs())
            })
            .sum::<f64>()
            .max(0.0)
    }

    /// Distances of every impact to every breakpoint, except the curve's own.
    pub(super) fn border_tests(&self, pt: &CyclePoint) -> Vec<f64> {
        let own = match self.kind {
            CurveKind::BorderCollision { impact, breakpoint } => Some((impact, breakpoint)),
            _ => None,
        };
        let mut out = Vec::with_capacity(pt.n * self.jumps.len());
        for (i, &ph) in pt.phases.iter().enumerate() {
            for &b in &self.jumps {
                out.push(if own == Some((i, b)) {
                    1.0
                } else {
                    signed_distance(ph, b)
                });
            }
        }
        out
    }

    /// The impacts of `guess` within [`HOLD_NEAR`] of a breakpoint (the curve's own on
    /// its own aside), each held on the piece it lies in.
    fn held_impacts(&self, sys: &System, guess: &CyclePoint) -> Vec<periodic::Hold> {
        let own = match self.kind {
            CurveKind::BorderCollision { impact, .. } => Some(impact),
            _ => None,
        };
        let table = sys.table();
        (0..guess.n)
            .filter(|&i| Some(i) != own)
            .filter(|&i| {
                self.jumps
                    .iter()
                    .any(|&b| signed_distance(guess.phases[i], b).abs() < HOLD_NEAR)
            })
            .map(|i| periodic::Hold {
                impact: i,
                segment: table.segment_index(guess.phases[i]),
            })
            .collect()
    }

    /// The border test of `pt` nearest zero ([`Self::border_tests`]): its index and
    /// value.
    pub(super) fn nearest_border(&self, pt: &CyclePoint) -> Option<(usize, f64)> {
        self.border_tests(pt)
            .into_iter()
            .enumerate()
            .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
    }

    pub(super) fn point(&self, e: Eval) -> CurvePoint {
        let criticality = (self.kind == CurveKind::PeriodDoubling)
            .then(|| criticality(&e.sys, &e.pt))
            .flatten();
        CurvePoint {
            alpha: e.y[0],
            p: e.y[1],
            cycle: e.pt,
            condition: e.g,
            floor: e.floor,
            criticality,
        }
    }
}

/// Whether a doubled cycle has collapsed onto the cycle of half its period (its return
/// after half its impacts is zero to 1e-7).
pub(super) fn collapsed(pt: &CyclePoint) -> bool {
    pt.half_return
        .is_some_and(|[dt, dv]| dt.abs().max(dv.abs()) <= 1e-7)
}

/// Whether a doubled cycle's halves are within 10⁻² of each other: next to where it is
/// born from the cycle of half its period (by a period doubling, or on a border) and
/// collapses back onto it. There a curve that cannot go on ends, and that cycle's
/// multiplier −1 makes the doubled cycle's fold test vanish.
pub(super) fn near_birth(pt: &CyclePoint) -> bool {
    pt.half_return
        .is_some_and(|[dt, dv]| dt.abs().max(dv.abs()) <= 1e-2)
}

/// How far a cycle's launch moved from `guess`'s: in phase, and in velocity relative to
/// its size.
fn moved(pt: &CyclePoint, guess: &CyclePoint) -> f64 {
    signed_distance(pt.phases[0], guess.phases[0])
        .abs()
        .max((pt.velocities[0] - guess.velocities[0]).abs() / (1.0 + guess.velocities[0].abs()))
}

/// The dot product in (α, p, t₀, v₀).
pub(super) fn dot(a: [f64; 4], b: [f64; 4]) -> f64 {
    a.iter().zip(&b).map(|(u, v)| u * v).sum()
}

/// The null vector of a 3 × 4 matrix of rank three, of unit length: its components are
/// the signed 3 × 3 minors (the four-dimensional cross product of its rows). NaN where
/// the rank is lower.
pub(super) fn null_vector(j: [[f64; 4]; 3]) -> [f64; 4] {
    let minor = |skip: usize| {
        let c: Vec<usize> = (0..4).filter(|&i| i != skip).collect();
        let m = |r: usize, k: usize| j[r][c[k]];
        m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
    };
    let v = [minor(0), -minor(1), minor(2), -minor(3)];
    let len = v.iter().map(|a| a * a).sum::<f64>().sqrt();
    if len > 0.0 && len.is_finite() {
        v.map(|a| a / len)
    } else {
        [f64::NAN; 4]
    }
}
