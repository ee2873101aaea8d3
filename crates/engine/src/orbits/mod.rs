//! Periodic orbits of the impact map, their stability and their bifurcations.
//!
//! * [`fixed`]: the (1, k) solutions (one bounce every k periods), their Jacobian,
//!   eigenvalues and classification, and the α interval on which a stable one exists
//!   (its birth and its period-doubling point α_PD).
//! * [`two_cycle`]: the (2, 2k) solutions near a (1, k) one, solved exactly by Newton's
//!   method, the asymptotic approximation near the period-doubling point (the paper's
//!   printed one and the corrected one), and the border collision of the branch.
//! * [`periodic`]: (n, k) cycles of the exact map by Newton's method on n steps of it,
//!   with their multipliers; every accepted point returns within 1e-11.
//! * [`continuation`]: pseudo-arclength continuation of cycles in α with period
//!   doubling, fold, border collision, grazing, onset of sticking and window exits
//!   located, and branch switching onto doubled branches ([`continuation::branches`]).
//! * [`events`]: the special points of a branch (PD, fold, border collision, grazing,
//!   onset of sticking, window exit) and the helpers that locate them.
//! * [`cascade`]: the period-doubling cascade from a (1, k) solution: α₁ < α₂ < …, how
//!   each 2ⁿ branch ends, and the Feigenbaum ratios.
//! * [`scaling`]: the power laws ΔT ∝ Δκ and Δt ∝ Δκ^½ near the period-doubling point
//!   (the paper's Fig. 4 and Fig. 5), from exact solutions and from simulated orbits.
//!
//! Everything here is pure and synchronous like the rest of the engine. Functions that
//! the terminal application calls per frame (e.g. [`fixed::stability_window`]) do
//! bounded work and never panic.

pub mod cascade;
pub mod continuation;
pub mod events;
pub mod fixed;
pub mod periodic;
pub mod scaling;
pub mod two_cycle;

pub use fixed::{
    alpha_at_delta_kappa, fixed_points, stability_window, stability_windows, Classification,
    FixedPoint, StabilityWindow, WindowEnd,
};
pub use two_cycle::{
    approximation_corrected, approximation_paper, border_collision, map_check, two_cycle,
    two_cycle_at, Approximation, BorderCollision, NoBorderCollision, NoTwoCycle, TwoCycle,
};

/// A complex number (an eigenvalue or a multiplier).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

impl Complex {
    /// |z|.
    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
}

/// Eigenvalues of a real 2×2 matrix, the one of larger real part first.
pub fn eigenvalues_2x2(m: [[f64; 2]; 2]) -> [Complex; 2] {
    let tr = m[0][0] + m[1][1];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    eigenvalues_tr_det(tr, det)
}

/// Eigenvalues of a real 2×2 matrix with trace `tr` and determinant `det`, the one of
/// larger real part first (for a product of many matrices, pass the product of their
/// determinants: the small eigenvalue then keeps its relative precision).
pub fn eigenvalues_tr_det(tr: f64, det: f64) -> [Complex; 2] {
    let half = 0.5 * tr;
    let disc = half * half - det;
    if disc >= 0.0 {
        // Avoid cancellation: the larger-magnitude root first, the other from det.
        let s = disc.sqrt();
        let big = if half >= 0.0 { half + s } else { half - s };
        let small = if big != 0.0 { det / big } else { 0.0 };
        let (a, b) = if big >= small {
            (big, small)
        } else {
            (small, big)
        };
        [Complex { re: a, im: 0.0 }, Complex { re: b, im: 0.0 }]
    } else {
        let s = (-disc).sqrt();
        [Complex { re: half, im: s }, Complex { re: half, im: -s }]
    }
}

/// Product of two 2×2 matrices, a·b.
pub fn mat_mul(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    [
        [
            a[0][0] * b[0][0] + a[0][1] * b[1][0],
            a[0][0] * b[0][1] + a[0][1] * b[1][1],
        ],
        [
            a[1][0] * b[0][0] + a[1][1] * b[1][0],
            a[1][0] * b[0][1] + a[1][1] * b[1][1],
        ],
    ]
}

/// The velocity derivative of the (1, k) solution: f'(t̂*) = (k/2)(1 − r)/(1 + r).
pub fn fixed_point_slope(r: f64, k: u32) -> f64 {
    0.5 * k as f64 * (1.0 - r) / (1.0 + r)
}

/// Wrap a phase into [0, 1).
pub(crate) fn wrap_phase(t: f64) -> f64 {
    let p = t.rem_euclid(1.0);
    if p >= 1.0 {
        0.0
    } else {
        p
    }
}

/// Root of `g` in [lo, hi] where g(lo) and g(hi) differ in sign (Illinois false
/// position with bisection safeguard), to the last few ulps.
pub(crate) fn bracketed_root(g: &dyn Fn(f64) -> f64, lo: f64, hi: f64) -> Option<f64> {
    let (glo, ghi) = (g(lo), g(hi));
    if glo == 0.0 {
        return Some(lo);
    }
    if ghi == 0.0 {
        return Some(hi);
    }
    if !(glo.is_finite() && ghi.is_finite()) || (glo < 0.0) == (ghi < 0.0) {
        return None;
    }
    Some(
        match illinois(&mut |x| g(x), (lo, hi), (glo, ghi), 300, 4) {
            Illinois::Root(x) => x,
            Illinois::Bracket { lo, hi, glo, ghi } => {
                if glo.abs() <= ghi.abs() {
                    lo
                } else {
                    hi
                }
            }
        },
    )
}

/// How [`illinois`] ended: on an exact zero, or with a bracket a few ulps wide.
pub(crate) enum Illinois {
    Root(f64),
    Bracket {
        lo: f64,
        hi: f64,
        glo: f64,
        ghi: f64,
    },
}

/// Illinois false position on [lo, hi] from end values of opposite signs, a bisection
/// every `bisect_every`-th step, at most `iterations` evaluations, until the bracket is
/// a few ulps wide. A failed evaluation (NaN) moves the upper end down to it.
pub(crate) fn illinois(
    g: &mut dyn FnMut(f64) -> f64,
    (mut lo, mut hi): (f64, f64),
    (mut glo, mut ghi): (f64, f64),
    iterations: usize,
    bisect_every: usize,
) -> Illinois {
    let mut side = 0;
    for i in 0..iterations {
        let mut x = (lo * ghi - hi * glo) / (ghi - glo);
        if !(x > lo && x < hi) || i % bisect_every == bisect_every - 1 {
            x = 0.5 * (lo + hi);
        }
        if x <= lo || x >= hi {
            break;
        }
        let gx = g(x);
        if gx == 0.0 {
            return Illinois::Root(x);
        }
        if gx.is_nan() {
            hi = x;
            continue;
        }
        if (gx < 0.0) == (glo < 0.0) {
            lo = x;
            glo = gx;
            if side == 1 {
                ghi *= 0.5;
            }
            side = 1;
        } else {
            hi = x;
            ghi = gx;
            if side == -1 {
                glo *= 0.5;
            }
            side = -1;
        }
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) {
            break;
        }
    }
    Illinois::Bracket { lo, hi, glo, ghi }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_of_known_matrices() {
        // [[2, 1], [1, 2]]: 3 and 1.
        let e = eigenvalues_2x2([[2.0, 1.0], [1.0, 2.0]]);
        assert!((e[0].re - 3.0).abs() < 1e-15 && (e[1].re - 1.0).abs() < 1e-15);
        // Rotation by 90°: ±i.
        let e = eigenvalues_2x2([[0.0, -1.0], [1.0, 0.0]]);
        assert!(e[0].re.abs() < 1e-15 && (e[0].im.abs() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bracketed_root_finds_cube_root() {
        let r = bracketed_root(&|x| x * x * x - 2.0, 0.0, 2.0).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
        assert!(bracketed_root(&|x| x * x + 1.0, -1.0, 1.0).is_none());
    }
}
