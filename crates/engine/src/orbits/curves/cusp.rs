//! Cusps of fold curves: where a fold curve's steps in the plane fail because the
//! curve turns back on itself tangentially. In (α, p, t₀, v₀) the fold curve is smooth
//! there; only its shadow in the plane has a cusp (its tangent there has no component
//! in the plane: the null vector of M − I, along which the cycle's two equations and
//! the fold's condition all stay put). So the curve is followed through it with
//! arclength in all four, and the cusp is located where the tangent's component along
//! the way the curve came changes sign. [`super::trace`] asks this where a fold
//! curve's steps fail or stall, before it looks ahead in other directions.

use super::corrector::{dot, Eval, Tracer};
use super::{Codim2, Codim2Kind, CurveKind, CurvePoint};
use crate::orbits::roots::bracketed_root_nan;
use crate::time::signed_distance;

/// Steps of the arclength in all four a cusp is looked for within.
const CUSP_STEPS: usize = 60;
/// Beyond the cusp, the curve is handed back to the steps in the plane once its
/// tangent's share in the plane is this large (there the plane's arclength is a good
/// parameter again) ...
const PLANE_SHARE: f64 = 0.2;
/// ... or once it lies this share of the plane from the cusp.
const BEYOND: f64 = 1e-4;

/// A point of the fold curve in all four: the corrector's point and the unit tangent
/// there.
struct Along {
    e: Eval,
    t: [f64; 4],
}

impl Along {
    /// x = (α, p, t₀, v₀).
    fn x(&self) -> [f64; 4] {
        let e = &self.e;
        [e.y[0], e.y[1], e.pt.t0, e.pt.velocities[0]]
    }
}

impl Tracer<'_> {
    /// Where a fold curve's steps along `tau` stopped at `cur`: if the curve turns
    /// back there tangentially, the cusp (recorded in `codim2`) and the curve's points
    /// from `cur` (not included) to beyond it on its other arm, the cusp among them,
    /// with the direction the last one leaves in (back along the way it came, on the
    /// other arm). None for the other kinds, and where the curve does not turn within
    /// [`CUSP_STEPS`] steps.
    pub(super) fn past_cusp(
        &self,
        cur: &CurvePoint,
        tau: [f64; 2],
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> Option<(Vec<CurvePoint>, [f64; 2])> {
        if self.kind != CurveKind::Fold {
            return None;
        }
        let scale = self.plane.scale();
        let x0 = [cur.alpha, cur.p, cur.cycle.t0, cur.cycle.velocities[0]];
        let row = [tau[0], tau[1], 0.0, 0.0];
        let (e, _, t) = self.extended(x0, row, dot(row, x0)).ok()?;
        // Oriented the way the curve came.
        let forward = |t: [f64; 4]| t[0] * tau[0] + t[1] * tau[1];
        let t = if forward(t) < 0.0 { t.map(|v| -v) } else { t };
        let mut at = Along { e, t };
        let mut last = self.point(at.e.clone());
        let mut sigma = 1e-6;
        let mut cusp: Option<[f64; 2]> = None;
        let mut path = Vec::new();
        for _ in 0..CUSP_STEPS {
            let Some(next) = self.step_along(&at, sigma) else {
                sigma *= 0.25;
                if sigma < 1e-12 {
                    return None;
                }
                continue;
            };
            // A fold curve cannot cross a breakpoint (its condition is another
            // function beyond).
            let b = self.point(next.e.clone());
            if !self.plane.inside(next.e.y) || self.crosses_border(&last, &b, tau, index, codim2) {
                return None;
            }
            if cusp.is_none() && forward(next.t) < 0.0 {
                // The tangent's share along the way the curve came changed sign: the
                // cusp lies between, where it is zero.
                let mut share = |s: f64| self.step_along(&at, s).map_or(f64::NAN, |q| forward(q.t));
                let s = bracketed_root_nan(&mut share, 0.0, sigma, forward(at.t), forward(next.t))?;
                let q = self.step_along(&at, s)?;
                let y = q.e.y;
                codim2.push(Codim2 {
                    kind: Codim2Kind::Cusp,
                    curve: index,
                    alpha: y[0],
                    p: y[1],
                    condition: q.e.g,
                    second_condition: forward(q.t),
                    impact: None,
                    meets: vec![index],
                });
                cusp = Some(y);
                path.push(self.point(q.e));
            }
            path.push(b.clone());
            last = b;
            at = next;
            if let Some(c) = cusp {
                let plane = at.t[0].hypot(at.t[1]);
                let away = (at.e.y[0] - c[0]).hypot(at.e.y[1] - c[1]);
                if plane >= PLANE_SHARE || away >= BEYOND * scale {
                    let dir = [at.t[0] / plane, at.t[1] / plane];
                    return Some((path, dir));
                }
            }
            sigma = (sigma * 2.0).min(1e-3);
        }
        None
    }

    /// The fold curve's point `sigma` on from `at` along its tangent in all four (the
    /// arclength condition t·(x − x_at) = σ), with its tangent oriented as `at`'s; None
    /// where it is not found, or is another cycle than `at`'s moved on.
    fn step_along(&self, at: &Along, sigma: f64) -> Option<Along> {
        let x = at.x();
        let guess: [f64; 4] = std::array::from_fn(|i| x[i] + sigma * at.t[i]);
        let (e, _, t) = self.extended(guess, at.t, dot(at.t, x) + sigma).ok()?;
        if !t.iter().all(|v| v.is_finite()) {
            return None;
        }
        // The same cycle moved on: its launch within a few steps of the guess.
        let moved = signed_distance(e.pt.phases[0], at.e.pt.phases[0])
            .abs()
            .max((e.pt.velocities[0] - x[3]).abs());
        if moved > 4.0 * sigma + 1e-9 {
            return None;
        }
        let t = if dot(t, at.t) < 0.0 { t.map(|v| -v) } else { t };
        Some(Along { e, t })
    }
}
