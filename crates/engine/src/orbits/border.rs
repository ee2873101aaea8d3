//! Border collisions of cycles: what happens to an (n, k) cycle when one of its impact
//! phases reaches a breakpoint of the table where f'' jumps (F_D: t̂ = 0 and ½).
//!
//! The map stays continuous there but its Jacobian jumps with f'': the cycle's
//! monodromy on the side it comes from (`near`) and on the other side (`far`) differ
//! only in the border impact's f''. The classification of border-collision
//! bifurcations of continuous piecewise-smooth planar maps (Nusse and Yorke; Banerjee
//! and Grebogi) decides from the two:
//! * det(I − J_near) and det(I − J_far) of the same sign: the cycle **persists** across
//!   the border, with the far side's stability;
//! * of opposite signs: a **border-collision fold**: the cycle meets a partner cycle
//!   (the one with that impact on the far side, which exists on the same side in α) and
//!   both cease;
//! * the far side has a multiplier below −1 and the near side none (the cycle persists,
//!   unstable): a cycle of twice the period is born at the collision, with the border
//!   impact alternately on the two sides, whose monodromy tends to J_far·J_near:
//!   **period doubling through the border**, the doubled cycle stable when that
//!   product's eigenvalues lie inside the unit circle. (In the one-dimensional normal
//!   form x ↦ μ + τ x, τ = τ_L, τ_R on either side, the alternating two-cycle exists
//!   past the border iff τ_R < −1 < τ_L; with both below −1 it does not.)
//!
//! [`collision`] computes both sides and the verdict; [`doubled_at_border`] finds the
//! doubled cycle just past the collision by Newton's method from the collision point
//! displaced along the far side's flip direction, and checks it is the doubled cycle.

use super::periodic::{solve_at, CyclePoint};
use crate::linalg::{eigenvalues_2x2, mat_mul, trace_det, Complex, Mat2, IDENTITY};
use crate::map::{EventKind, ImpactMap, State};
use crate::table::Table;
use crate::tangent::flight;
use crate::time::{signed_distance, wrap_phase};

/// What a border collision does to the cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Crossing {
    /// The cycle goes on beyond the breakpoint, stable or not.
    Persists {
        /// Stable on the far side.
        stable: bool,
    },
    /// A border-collision fold: the cycle and its partner meet and cease.
    Fold,
    /// The cycle goes on unstable (a far-side multiplier below −1) and a cycle of twice
    /// the period is born at the collision.
    Doubling {
        /// Whether the doubled cycle is stable (the eigenvalues of J_far·J_near).
        stable: bool,
    },
}

impl Crossing {
    /// Name in every output format.
    pub fn as_str(&self) -> &'static str {
        match self {
            Crossing::Persists { stable: true } => "persists_stable",
            Crossing::Persists { stable: false } => "persists_unstable",
            Crossing::Fold => "border_fold",
            Crossing::Doubling { stable: true } => "doubling_stable",
            Crossing::Doubling { stable: false } => "doubling_unstable",
        }
    }

    /// In words, for text output.
    pub fn describe(&self, n: usize, k: u32) -> String {
        match self {
            Crossing::Persists { stable: true } => "goes on beyond, stable".into(),
            Crossing::Persists { stable: false } => "goes on beyond, unstable".into(),
            Crossing::Fold => "a border-collision fold: it meets its partner and both cease".into(),
            Crossing::Doubling { stable } => format!(
                "goes on beyond unstable, and {} ({}, {}) cycle is born there (period doubling through the border)",
                if *stable { "a stable" } else { "an unstable" },
                2 * n,
                2 * k
            ),
        }
    }
}

/// A border collision, classified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision {
    /// The multipliers with the border impact's f'' from the side the branch came from.
    pub near: [Complex; 2],
    /// The multipliers with the other side's f''.
    pub far: [Complex; 2],
    /// What happens.
    pub crossing: Crossing,
}

/// The cycle's monodromy (the Jacobian of its n impacts) with f'' at impact `impact`
/// (an index into [`CyclePoint::phases`]) taken from the segment of the table on the
/// left of the breakpoint `bp` and from the one on its right: (left, right). None if
/// stepping the cycle fails.
pub fn one_sided_monodromies(
    map: &mut ImpactMap,
    p: &CyclePoint,
    impact: usize,
    bp: f64,
) -> Option<(Mat2, Mat2)> {
    map.set_alpha(p.alpha).ok()?;
    let sys = map.system().clone();
    let table: &Table = sys.table();
    let (left, right) = table.segments_around(bp);
    let (left, right) = (table.segment(left), table.segment(right));
    // The left segment ends at bp (at 1 for the breakpoint 0: its formula continues
    // there, not at 0).
    let left_at = if bp == 0.0 { 1.0 } else { bp };
    let ddf = [
        sys.alpha() * left.jet(left_at)[2],
        sys.alpha() * right.jet(bp)[2],
    ];
    let start = State::launch(&sys, 0, wrap_phase(p.t0), p.velocities[0], 0.0).ok()?;
    map.set_state(start);
    // Impact i of the cycle (phases[i]) is the landing of flight i − 1, impact 0 that
    // of the last flight.
    let border_flight = (impact + p.n - 1) % p.n;
    let mut sides = [IDENTITY, IDENTITY];
    for j in 0..p.n {
        let before = *map.state();
        let e = map.step().ok()?;
        if e.kind != EventKind::Impact {
            return None;
        }
        let fl = flight(&sys, &before, &e)?;
        for (s, m) in sides.iter_mut().enumerate() {
            let jac = if j == border_flight {
                fl.jacobian_with(ddf[s])
            } else {
                fl.jacobian()
            };
            *m = mat_mul(jac, *m);
        }
    }
    Some((sides[0], sides[1]))
}

/// Classify the border collision of `p` (its impact `impact` on the breakpoint `bp`),
/// reached from the side `side` of it (the sign of the impact's phase minus `bp` before
/// the collision).
pub fn collision(
    map: &mut ImpactMap,
    p: &CyclePoint,
    impact: usize,
    bp: f64,
    side: f64,
) -> Option<Collision> {
    let (left, right) = one_sided_monodromies(map, p, impact, bp)?;
    let (near, far) = if side < 0.0 {
        (left, right)
    } else {
        (right, left)
    };
    let det_i_minus = |m: Mat2| {
        let (tr, det) = trace_det(m);
        1.0 - tr + det
    };
    let (mu_near, mu_far) = (eigenvalues_2x2(near), eigenvalues_2x2(far));
    let inside = |mu: &[Complex; 2]| mu.iter().all(|z| z.abs() < 1.0);
    // A multiplier crossing −1 through the border: below −1 on the far side and not on
    // the near side (a cycle flip-unstable on both sides carries the doubled cycle of
    // an earlier period doubling, born elsewhere).
    let below = |mu: &[Complex; 2]| mu.iter().any(|z| z.im == 0.0 && z.re < -1.0);
    let flips = below(&mu_far) && !below(&mu_near);
    let crossing = if det_i_minus(near) * det_i_minus(far) < 0.0 {
        Crossing::Fold
    } else if flips {
        Crossing::Doubling {
            stable: inside(&eigenvalues_2x2(mat_mul(far, near))),
        }
    } else {
        Crossing::Persists {
            stable: inside(&mu_far),
        }
    };
    Some(Collision {
        near: mu_near,
        far: mu_far,
        crossing,
    })
}

/// The (2n, 2k) cycle born at the border collision of `p` (impact `impact` on `bp`,
/// reached from `side`): Newton's method at α a little past the collision (in the
/// direction `dir` of α along the branch) from `p`'s launch displaced along the far
/// side's flip direction. Accepted only if it is a cycle of 2n impacts that is not `p`
/// traversed twice and has the border impact on both sides of `bp`.
pub fn doubled_at_border(
    map: &mut ImpactMap,
    p: &CyclePoint,
    impact: usize,
    bp: f64,
    side: f64,
    dir: f64,
) -> Option<CyclePoint> {
    let (left, right) = one_sided_monodromies(map, p, impact, bp)?;
    let far = if side < 0.0 { right } else { left };
    // The eigenvector of J_far for its multiplier below −1.
    let mu = eigenvalues_2x2(far)
        .into_iter()
        .find(|z| z.im == 0.0 && z.re < -1.0)?
        .re;
    let rows = [[far[0][0] - mu, far[0][1]], [far[1][0], far[1][1] - mu]];
    let row = if rows[0][0].hypot(rows[0][1]) >= rows[1][0].hypot(rows[1][1]) {
        rows[0]
    } else {
        rows[1]
    };
    let norm = row[0].hypot(row[1]);
    if norm == 0.0 {
        return None;
    }
    let e = [-row[1] / norm, row[0] / norm];
    let (n, k) = (2 * p.n, 2 * p.k);
    for delta in [1e-7, 1e-6, 1e-5, 1e-4] {
        let alpha = p.alpha + dir.signum() * delta * (1.0 + p.alpha.abs());
        if map.set_alpha(alpha).is_err() {
            continue;
        }
        for scale in [1.0, -1.0, 10.0, -10.0] {
            let eps = scale * delta;
            let (t0, v0) = (p.t0 + eps * e[0], p.velocities[0] + eps * e[1]);
            let Ok(q) = solve_at(map, n, k, t0, v0) else {
                continue;
            };
            // Not the n-cycle twice: its half return is not zero.
            let doubled = q
                .half_return
                .is_some_and(|h| h[0].abs().max(h[1].abs()) > 1e-9);
            // The border impact on both sides of the breakpoint.
            let sides = |i: usize| signed_distance(q.phases[i], bp);
            let (a, b) = (sides(impact), sides(impact + p.n));
            let near =
                (q.t0 - p.t0).abs() < 1e-2 && (q.velocities[0] - p.velocities[0]).abs() < 1e-2;
            if doubled && near && a * b < 0.0 {
                return Some(q);
            }
        }
    }
    None
}
