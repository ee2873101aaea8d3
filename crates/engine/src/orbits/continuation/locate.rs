//! Where a branch meets a special point and what its end is: the test functions
//! watched between two accepted points and the first sign change among them, located
//! by a bracketed root in the arclength ([`Family::first_event`]); a doubled branch
//! meeting its parent; the end a failed step makes (grazing or not converged); and how
//! closely a special point's defining condition must hold ([`holds`]).

use super::*;

impl Family {
    /// The period doubling of the half cycle of `p` (a doubled branch at its birth): a
    /// secant on (1 + λ₁)(1 + λ₂) of the parent, solved at fixed α; the parent's cycle
    /// there, if its multiplier is −1 to [`CONDITION`].
    pub(super) fn parent_pd(&mut self, p: &CyclePoint) -> Option<CyclePoint> {
        let (n, k) = (p.n / 2, p.k / 2);
        let (mut t0, mut v0) = (p.t0, p.velocities[0]);
        let solve = |map: &mut ImpactMap, a: f64, t0: &mut f64, v0: &mut f64| {
            map.set_alpha(a).ok()?;
            let q = crate::orbits::periodic::solve_at(map, n, k, *t0, *v0).ok()?;
            (*t0, *v0) = (q.t0, q.velocities[0]);
            Some(q)
        };
        let (mut a0, mut a1) = (p.alpha, p.alpha + 1e-7);
        let mut g0 = solve(&mut self.map, a0, &mut t0, &mut v0)?.pd_test();
        let mut q = solve(&mut self.map, a1, &mut t0, &mut v0)?;
        let mut g1 = q.pd_test();
        for _ in 0..30 {
            if g1 == g0 {
                break;
            }
            let a2 = a1 - g1 * (a1 - a0) / (g1 - g0);
            (a0, g0) = (a1, g1);
            a1 = a2;
            q = solve(&mut self.map, a1, &mut t0, &mut v0)?;
            g1 = q.pd_test();
            if (a1 - a0).abs() < 1e-15 {
                break;
            }
        }
        let sp = special(Kind::PeriodDoubling, &q, f64::NAN, 0);
        ((a1 - p.alpha).abs() < 1e-6 && holds(&sp)).then_some(q)
    }

    /// A doubled branch meeting its parent: the half-period map returns.
    pub(super) fn is_birth(&mut self, p: &CyclePoint, tol: f64) -> bool {
        p.n.is_multiple_of(2)
            && p.k.is_multiple_of(2)
            && pass(&mut self.map, p.t0, p.velocities[0], p.n / 2, p.k / 2)
                .map(|q| q.residual[0].abs().max(q.residual[1].abs()) < tol)
                .unwrap_or(false)
    }

    pub(super) fn failure_end(&mut self, pt: &CyclePoint, e: PassError) -> Special {
        let slowest = (0..pt.n)
            .min_by(|&a, &b| {
                self.impact_speed(pt, a)
                    .total_cmp(&self.impact_speed(pt, b))
            })
            .unwrap_or(0);
        if let PassError::Grazing { phase } = e {
            return special(Kind::Grazing, pt, phase, slowest);
        }
        if pt.min_impact_speed < GRAZING_SPEED {
            return special(Kind::Grazing, pt, pt.phases[slowest], slowest);
        }
        let sys = self.map.system().clone();
        let (gap, phase) = crate::orbits::periodic::min_interior_gap(&sys, pt);
        if gap < 1e-6 {
            return special(Kind::Grazing, pt, phase, 0);
        }
        special(Kind::NoConvergence, pt, pt.phases[0], 0)
    }

    pub(super) fn impact_speed(&self, pt: &CyclePoint, i: usize) -> f64 {
        // The launch's relative velocity is r|u| of the impact before it.
        let w = pt.velocities[i] - pt.alpha * self.map.system().table().derivative(pt.phases[i], 1);
        w / self.map.system().r()
    }

    /// The first sign change of a test function between `a` and `b` (one corrector
    /// step of length `h` from `x0` along `tau`): (arclength, kind, impact, phase).
    pub(super) fn first_event(
        &mut self,
        a: &CyclePoint,
        b: &CyclePoint,
        x0: [f64; 3],
        tau: [f64; 3],
        h: f64,
    ) -> Option<(f64, Kind, usize, f64)> {
        let (lo, hi) = self.window;
        let mut tests: Vec<Test> = vec![
            (
                Kind::PeriodDoubling,
                0,
                f64::NAN,
                Box::new(|p: &CyclePoint| p.pd_test()),
            ),
            (
                Kind::Fold,
                0,
                f64::NAN,
                Box::new(|p: &CyclePoint| p.fold_test()),
            ),
            // A doubled branch through its birth: the half return changes sign.
            (
                Kind::PeriodDoubling,
                BIRTH,
                f64::NAN,
                Box::new(|p: &CyclePoint| p.half_return.map_or(f64::NAN, |h| h[0])),
            ),
            (
                Kind::WindowExit,
                0,
                f64::NAN,
                Box::new(move |p: &CyclePoint| p.alpha - lo),
            ),
            (
                Kind::WindowExit,
                0,
                f64::NAN,
                Box::new(move |p: &CyclePoint| p.alpha - hi),
            ),
        ];
        for i in 0..a.n {
            for &bp in &self.jumps {
                tests.push((
                    Kind::BorderCollision,
                    i,
                    bp,
                    Box::new(move |p: &CyclePoint| signed_distance(p.phases[i], bp)),
                ));
            }
        }
        let mut best: Option<(f64, Kind, usize, f64)> = None;
        for (kind, impact, bp, g) in &tests {
            let (ga, gb) = (g(a), g(b));
            if ga == 0.0 && *kind == Kind::WindowExit && !(lo..=hi).contains(&b.alpha) {
                best = Some((0.0, *kind, 0, f64::NAN)); // leaving from the window's edge
                continue;
            }
            if !(ga.is_finite() && gb.is_finite()) || (ga < 0.0) == (gb < 0.0) || ga == 0.0 {
                continue;
            }
            if *kind == Kind::BorderCollision && (ga.abs() > 0.25 || gb.abs() > 0.25) {
                continue; // the wrap at ±½, not a crossing
            }
            let map = &mut self.map;
            let (n, k) = (a.n, a.k);
            let mut f = |s: f64| match correct(map, n, k, x0, tau, s) {
                Ok((p, _)) => g(&p),
                Err(_) => f64::NAN,
            };
            let Some(hs) = bracketed_root_nan(&mut f, 0.0, h, ga, gb) else {
                continue;
            };
            // A border collision first among events at the same point: a multiplier
            // that jumps through ±1 at a breakpoint is the collision's doing.
            let tie = 1e-9 * h;
            let bc = *kind == Kind::BorderCollision;
            if best.is_none_or(|(s, k, ..)| {
                hs < s - tie || (bc && k != Kind::BorderCollision && hs <= s + tie)
            }) {
                let phase = if *kind == Kind::BorderCollision {
                    *bp
                } else {
                    f64::NAN
                };
                best = Some((hs, *kind, *impact, phase));
            }
        }
        best
    }
}

/// How closely a special point's defining condition must hold at the located point: a
/// multiplier within this of −1 (period doubling) or +1 (fold), for cycles up to
/// [`CONDITION_PERIOD`] impacts.
pub const CONDITION: f64 = 1e-8;
/// Beyond this period the bound grows with it: the multipliers of an n-cycle are
/// eigenvalues of a product of n Jacobians, computed in double precision to about
/// n × 10⁻¹⁰ near ±1 (measured on the cascades' 512- and 1024-cycles: 2e-8 to 3e-7).
pub const CONDITION_PERIOD: usize = 16;

/// The bound on a special point's condition error for an `n`-cycle: [`CONDITION`] up
/// to [`CONDITION_PERIOD`], growing in proportion beyond.
pub fn condition_bound(kind: Kind, n: usize) -> Option<f64> {
    match kind {
        Kind::PeriodDoubling | Kind::Fold => {
            Some(CONDITION * (n as f64 / CONDITION_PERIOD as f64).max(1.0))
        }
        Kind::BorderCollision => Some(ON_BORDER),
        _ => None,
    }
}
/// How closely a border collision's impact phase must lie on its breakpoint.
pub const ON_BORDER: f64 = 1e-8;

/// Whether a special point's defining condition holds at its point: a multiplier −1 at
/// a period doubling, +1 at a fold (to [`condition_bound`]), the impact on the
/// breakpoint at a border collision (to [`ON_BORDER`]); other kinds have none.
pub fn holds(sp: &Special) -> bool {
    match condition_bound(sp.kind, sp.point.n) {
        Some(bound) => sp.condition_error().is_some_and(|e| e <= bound),
        None => true,
    }
}

/// A branch that ends with a relative impact velocity below this ends at a grazing
/// landing (the tangent map grows as 1/|u| there).
pub const GRAZING_SPEED: f64 = 1e-6;

/// Cycle points closer than this are one (the accuracy of a long cycle's impacts,
/// below which the continuity test reads nothing).
pub const SAME_POINT: f64 = 1e-8;

/// The `impact` of the test function for a doubled branch's birth.
pub(super) const BIRTH: usize = usize::MAX;

/// A test function: its kind, the impact and breakpoint it concerns, and the function.
pub(super) type Test = (Kind, usize, f64, Box<dyn Fn(&CyclePoint) -> f64>);
