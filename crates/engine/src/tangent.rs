//! The tangent map: the Jacobian of one event of the impact map, from implicit
//! differentiation of the gap equation at the landing.
//!
//! After an impact at tᵢ the ball leaves with velocity vᵢ, relative velocity
//! wᵢ = vᵢ − f'(tᵢ) > 0, and lands at tᵢ₊₁ = tᵢ + τ where
//!
//!   G(tᵢ, vᵢ, tᵢ₊₁) = f(tᵢ) + vᵢ τ − τ²/2 − f(tᵢ₊₁) = 0.
//!
//! With uᵢ₊₁ = vᵢ − τ − f'(tᵢ₊₁) < 0 the relative velocity at the landing,
//! ∂G/∂tᵢ₊₁ = uᵢ₊₁, ∂G/∂tᵢ = τ − wᵢ and ∂G/∂vᵢ = τ, so
//!
//!   a = ∂tᵢ₊₁/∂tᵢ = (wᵢ − τ)/uᵢ₊₁,   b = ∂tᵢ₊₁/∂vᵢ = −τ/uᵢ₊₁,
//!
//! and from the restitution law vᵢ₊₁ = (1 + r) f'(tᵢ₊₁) − r vᵢ + r τ, with
//! s = (1 + r) f''(tᵢ₊₁) + r,
//!
//!   J = [[a, b], [s a − r, s b − r]],   det J = r (b − a) = r wᵢ / |uᵢ₊₁| = r² |uᵢ| / |uᵢ₊₁|
//!
//! (since wᵢ = r |uᵢ| after an impact). Over a run the determinants telescope: the two
//! Lyapunov exponents sum to 2 ln r per impact, and an n-cycle's multipliers multiply to
//! r²ⁿ. At a (1, k) solution (τ = k, f'(t̂*) = c, wᵢ = k/2 − c, uᵢ₊₁ = −(k/2 + c)) J is
//! the paper's A = [[1, 1 + r], [(1 + r) f'', (1 + r)² f'' + r²]].
//!
//! A stick collapses the state: where the ball is released does not depend on where it
//! stuck, so the Jacobian across a stick (and a release) is zero ([`Tangent::Collapse`]),
//! never a NaN. A landing with zero relative velocity (grazing) makes J unbounded
//! ([`Tangent::Grazing`]).

use crate::map::{Event, EventKind, State};
use crate::real::Number;
use crate::system::System;

/// ∂tᵢ₊₁/∂tᵢ = (wᵢ − τ)/uᵢ₊₁ and ∂tᵢ₊₁/∂vᵢ = −τ/uᵢ₊₁ of a flight launched with relative
/// velocity `w`, lasting `tau` and landing with relative velocity `u`: written once for
/// every number type (the f64 map's [`Flight`] and the map at any precision).
#[inline]
pub fn flight_partials<R: Number>(w: R, tau: R, u: R) -> (R, R) {
    ((w - tau.clone()) / u.clone(), -tau / u)
}

/// The Jacobian of an impact in (t, v) from the flight's partials `a`, `b` and f'' =
/// `ddf` at the landing: [[a, b], [s a − r, s b − r]] with s = (1 + r) f'' + r.
#[inline]
pub fn impact_jacobian<R: Number>(a: R, b: R, ddf: R, r: R, one: R) -> [[R; 2]; 2] {
    let s = (one + r.clone()) * ddf + r.clone();
    let (sa, sb) = (s.clone() * a.clone(), s * b.clone());
    [[a, b], [sa - r.clone(), sb - r]]
}

/// The Jacobian of one event in the coordinates (t, v) right after it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tangent {
    /// An impact after a flight: J, and |u| at the landing (for the coordinates in
    /// which det J is exactly r²; see [`Tangent::scaled`]).
    Flight {
        /// The Jacobian of the event in (t, v).
        jacobian: [[f64; 2]; 2],
        /// Relative velocity at the landing (the determinant's denominator).
        u_landing: f64,
    },
    /// A stick or a release: the state after it does not depend on the state before.
    Collapse,
    /// A landing with zero relative velocity: the Jacobian is unbounded.
    Grazing,
}

/// The Jacobian of the event `e` that took the map from `before` (the state right after
/// the previous event) to the state right after `e`.
pub fn tangent(sys: &System, before: &State, e: &Event) -> Tangent {
    if e.kind != EventKind::Impact || before.w <= 0.0 {
        // A stick, a release, or a flight launched from a stuck state (w = 0): the
        // launch point is the release point, a function of nothing before it.
        return Tangent::Collapse;
    }
    match flight(sys, before, e) {
        Some(fl) => Tangent::Flight {
            jacobian: fl.jacobian(),
            u_landing: fl.u_landing,
        },
        None => Tangent::Grazing,
    }
}

/// The partial derivatives of one flight ending in an impact, from which its Jacobian is
/// assembled for any value of f'' at the landing (the one-sided values at a breakpoint
/// of the table), together with its derivative in α (f = αF):
///
///   ∂tᵢ₊₁/∂α = −(F(tᵢ) − F(tᵢ₊₁))/uᵢ₊₁ = c,
///   ∂vᵢ₊₁/∂α = (1 + r) F'(tᵢ₊₁) + s c,
///
/// from ∂G/∂α = F(tᵢ) − F(tᵢ₊₁) and the restitution law. The continuation of periodic
/// orbits builds Newton's Jacobian from these; [`tangent`] is the same matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flight {
    /// ∂tᵢ₊₁/∂tᵢ.
    pub a: f64,
    /// ∂tᵢ₊₁/∂vᵢ.
    pub b: f64,
    /// ∂tᵢ₊₁/∂α.
    pub c: f64,
    /// F'(tᵢ₊₁), the derivative of f'(tᵢ₊₁) in α at fixed time.
    pub df_alpha: f64,
    /// f''(tᵢ₊₁) (the right derivative at a breakpoint).
    pub ddf: f64,
    /// |uᵢ₊₁|, the relative velocity at the landing.
    pub u_landing: f64,
    /// The restitution coefficient.
    pub r: f64,
}

/// The partials of the impact `e` after the flight from `before`; None unless `e` is an
/// impact after a flight launched with w ≥ 0 (w = 0: a release, whose launch state is
/// the table's) and landing with u ≠ 0.
pub fn flight(sys: &System, before: &State, e: &Event) -> Option<Flight> {
    let u = e.vrel;
    if e.kind != EventKind::Impact || before.w < 0.0 || u == 0.0 {
        return None;
    }
    // The flight time, from exact (period, phase) differences.
    let tau = (e.period - before.period) as f64 + (e.phase - before.phase);
    // A start above the table (height z0) adds a constant to G: same derivatives.
    let w = before.w;
    let table = sys.table();
    let big_f = table.value(before.phase) - table.value(e.phase);
    let (a, b) = flight_partials(w, tau, u);
    Some(Flight {
        a,
        b,
        c: -big_f / u,
        df_alpha: table.derivative(e.phase, 1),
        ddf: sys.ddf(e.phase),
        u_landing: u.abs(),
        r: sys.r(),
    })
}

impl Flight {
    /// The Jacobian of the impact in (t, v).
    pub fn jacobian(&self) -> [[f64; 2]; 2] {
        self.jacobian_with(self.ddf)
    }

    /// The Jacobian with f'' = `ddf` at the landing (a one-sided value at a breakpoint).
    pub fn jacobian_with(&self, ddf: f64) -> [[f64; 2]; 2] {
        impact_jacobian(self.a, self.b, ddf, self.r, 1.0)
    }

    /// ∂(tᵢ₊₁, vᵢ₊₁)/∂α with f'' = `ddf` at the landing.
    pub fn alpha_column_with(&self, ddf: f64) -> [f64; 2] {
        let s = (1.0 + self.r) * ddf + self.r;
        [self.c, (1.0 + self.r) * self.df_alpha + s * self.c]
    }

    /// det J = r (b − a) = r wᵢ/|uᵢ₊₁|, free of cancellation (independent of f'').
    pub fn det(&self) -> f64 {
        self.r * (self.b - self.a)
    }
}

impl Tangent {
    /// The Jacobian in the coordinates (|u| δt, δv), u the relative velocity of the
    /// landing each state came from: J̃ = D J D⁻¹ with D = diag(|u|, 1) on either side,
    /// so det J̃ = r² exactly and the exponents are those of J (the change of
    /// coordinates is bounded along any orbit that does not graze). `u_before` is |u| of
    /// the landing that produced the state before.
    pub fn scaled(&self, u_before: f64) -> Option<[[f64; 2]; 2]> {
        match *self {
            Tangent::Flight {
                jacobian: j,
                u_landing,
            } => {
                let (p, q) = (u_landing, 1.0 / u_before);
                Some([[p * j[0][0] * q, p * j[0][1]], [j[1][0] * q, j[1][1]]])
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::Solver;
    use crate::map::ImpactMap;
    use crate::orbits::fixed::{fixed_point_jacobian, fixed_points};
    use crate::table::Table;

    /// The state after one step from a launch at (phase, v).
    fn step_from(sys: &System, phase: f64, v: f64) -> (State, Event) {
        let st = State::launch(sys, 0, phase, v, 0.0).unwrap();
        let mut m = ImpactMap::new(sys.clone(), Solver::Exact, st);
        let e = m.step().unwrap();
        (st, e)
    }

    /// Central differences of the map in (t, v) against the analytic Jacobian.
    #[test]
    fn the_jacobian_matches_finite_differences_of_the_map() {
        for (table, alpha) in [
            (Table::fd(0.1).unwrap(), 0.6),
            (Table::fd(1.0).unwrap(), 0.5),
            (Table::sine(), 0.03),
        ] {
            let sys = System::new(table, alpha, 0.8).unwrap();
            let mut checked = 0;
            for i in 0..40 {
                let phase = 0.013 + 0.0247 * i as f64;
                let v = sys.df(phase) + 0.3 + 0.02 * i as f64;
                let (st, e) = step_from(&sys, phase, v);
                let Tangent::Flight { jacobian: j, .. } = tangent(&sys, &st, &e) else {
                    continue;
                };
                let h = 1e-7;
                let time = |e: &Event| e.period as f64 + e.phase;
                let (_, ep) = step_from(&sys, phase + h, v);
                let (_, em) = step_from(&sys, phase - h, v);
                let (_, vp) = step_from(&sys, phase, v + h);
                let (_, vm) = step_from(&sys, phase, v - h);
                if [ep, em, vp, vm].iter().any(|x| x.period != e.period) {
                    continue; // a perturbation crossed a period: differences meaningless
                }
                let fd = [
                    [
                        (time(&ep) - time(&em)) / (2.0 * h),
                        (time(&vp) - time(&vm)) / (2.0 * h),
                    ],
                    [(ep.v - em.v) / (2.0 * h), (vp.v - vm.v) / (2.0 * h)],
                ];
                for r in 0..2 {
                    for c in 0..2 {
                        let scale = 1.0 + j[r][c].abs();
                        assert!(
                            (fd[r][c] - j[r][c]).abs() <= 1e-6 * scale,
                            "{} α={alpha} start ({phase}, {v}): J[{r}][{c}] = {} vs {}",
                            sys.table().name(),
                            j[r][c],
                            fd[r][c]
                        );
                    }
                }
                checked += 1;
            }
            assert!(checked > 20, "{checked} checked");
        }
    }

    /// The α column against central differences of the map in α at a fixed launch.
    #[test]
    fn the_alpha_derivative_matches_finite_differences_of_the_map() {
        for (table, alpha) in [
            (Table::fd(0.1).unwrap(), 0.6),
            (Table::fd(1.0).unwrap(), 0.5),
            (Table::sine(), 0.03),
        ] {
            let sys = System::new(table.clone(), alpha, 0.8).unwrap();
            let h = 1e-7;
            let at = |a: f64| System::new(table.clone(), a, 0.8).unwrap();
            let (sp, sm) = (at(alpha + h), at(alpha - h));
            let mut checked = 0;
            for i in 0..40 {
                let phase = 0.013 + 0.0247 * i as f64;
                let v = sys.df(phase) + 0.3 + 0.02 * i as f64;
                let (st, e) = step_from(&sys, phase, v);
                let Some(fl) = flight(&sys, &st, &e) else {
                    continue;
                };
                let (_, ep) = step_from(&sp, phase, v);
                let (_, em) = step_from(&sm, phase, v);
                if ep.period != e.period || em.period != e.period {
                    continue;
                }
                let fd = [(ep.phase - em.phase) / (2.0 * h), (ep.v - em.v) / (2.0 * h)];
                let col = fl.alpha_column_with(fl.ddf);
                for r in 0..2 {
                    assert!(
                        (fd[r] - col[r]).abs() <= 1e-6 * (1.0 + col[r].abs()),
                        "{} α={alpha} ({phase}, {v}): {col:?} vs {fd:?}",
                        sys.table().name()
                    );
                }
                checked += 1;
            }
            assert!(checked > 20, "{checked} checked");
        }
    }

    /// det J = r² |uᵢ| / |uᵢ₊₁| for every impact of a chaotic orbit, |uᵢ| from the
    /// event before (independently of the Jacobian's entries).
    #[test]
    fn the_determinant_is_r_squared_times_the_ratio_of_relative_velocities() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.6, 0.8).unwrap();
        let st = State::start(&sys, 0.0, None, 0.0).unwrap();
        let mut m = ImpactMap::new(sys.clone(), Solver::Exact, st);
        let mut prev: Option<Event> = None;
        let mut checked = 0;
        for _ in 0..20_000 {
            let before = *m.state();
            let e = m.step().unwrap();
            if let (Some(p), Tangent::Flight { jacobian: j, .. }) =
                (prev, tangent(&sys, &before, &e))
            {
                if p.kind == EventKind::Impact {
                    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                    let want = sys.r() * sys.r() * p.vrel.abs() / e.vrel.abs();
                    assert!((det - want).abs() <= 1e-9 * want, "{det} vs {want}");
                    checked += 1;
                }
            }
            prev = Some(e);
        }
        assert!(checked > 5_000);
    }

    /// At a (1, k) solution the Jacobian of one impact is the paper's A.
    #[test]
    fn at_the_fixed_point_it_is_the_papers_matrix() {
        for k in [1u32, 2] {
            let sys = System::new(Table::fd(0.3).unwrap(), 0.45 * k as f64, 0.8).unwrap();
            let fp = fixed_points(&sys, k)
                .unwrap()
                .into_iter()
                .find(|p| p.admissible && p.ddf < 0.0)
                .unwrap();
            let st = State::launch(&sys, 0, fp.phase, fp.v, 0.0).unwrap();
            let e = ImpactMap::new(sys.clone(), Solver::Exact, st)
                .step()
                .unwrap();
            let Tangent::Flight { jacobian: j, .. } = tangent(&sys, &st, &e) else {
                panic!("not a flight");
            };
            let a = fixed_point_jacobian(sys.r(), fp.ddf);
            for r in 0..2 {
                for c in 0..2 {
                    assert!((j[r][c] - a[r][c]).abs() < 1e-9, "k={k}: {j:?} vs {a:?}");
                }
            }
        }
    }
}
