//! Periodic orbits of the impact map, their stability and their bifurcations.
//!
//! * [`fixed`]: the (1, k) solutions (one bounce every k periods), their Jacobian,
//!   eigenvalues and classification, and the α interval on which a stable one exists
//!   (its birth and its period-doubling point α_PD).
//! * [`two_cycle`]: the (2, 2k) solutions near a (1, k) one, solved exactly by Newton's
//!   method, the asymptotic approximation near the period-doubling point (the paper's
//!   printed one and the corrected one), and the border collision of the branch.
//! * [`scaling`]: the power laws ΔT ∝ Δκ and Δt ∝ Δκ^½ near the period-doubling point
//!   (the paper's Fig. 4 and Fig. 5), from exact solutions and from simulated orbits.
//!
//! Everything here is pure and synchronous like the rest of the engine. Functions that
//! the terminal application calls per frame (e.g. [`fixed::stability_window`]) do
//! bounded work and never panic.

pub mod fixed;
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

use super::table::{Shape, Table};
use std::f64::consts::PI;

/// Largest k accepted for (1, k) and (2, 2k) solutions.
pub const MAX_K: u32 = 100;

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

/// A smooth stretch of the table: one polynomial piece, or the whole sine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Segment {
    pub start: f64,
    pub end: f64,
    /// Index of the piece, None for the sine.
    pub piece: Option<usize>,
}

/// The smooth segments of a table in phase order.
pub(crate) fn segments(table: &Table) -> Vec<Segment> {
    match table.shape() {
        Shape::Sine => vec![Segment {
            start: 0.0,
            end: 1.0,
            piece: None,
        }],
        Shape::Piecewise(p) => p
            .iter()
            .enumerate()
            .map(|(i, q)| Segment {
                start: q.start,
                end: q.end,
                piece: Some(i),
            })
            .collect(),
    }
}

/// F, F', F'', F''' of the table's smooth formula on `seg` at phase `t`, continued
/// analytically outside the segment (t need not lie in [0, 1)).
pub(crate) fn seg_jet(table: &Table, seg: &Segment, t: f64) -> [f64; 4] {
    match seg.piece {
        None => {
            let w = 2.0 * PI;
            let (s, c) = (w * t).sin_cos();
            [s, w * c, -w * w * s, -w * w * w * c]
        }
        Some(i) => {
            let p = &table.pieces()[i];
            let s = t - p.start;
            [p.f.eval(s), p.d1.eval(s), p.d2.eval(s), p.d3.eval(s)]
        }
    }
}

/// Taylor coefficients b_n = F⁽ⁿ⁾(m)/n!, n = 0..N, of the smooth formula on `seg` at `m`
/// (unscaled by α). Polynomials give their exact finite expansion; the sine is expanded
/// to [`TAYLOR_TERMS`] terms (remainder below 10⁻¹⁹ for |h| ≤ ½).
pub(crate) fn seg_taylor(table: &Table, seg: &Segment, m: f64) -> [f64; TAYLOR_TERMS] {
    let mut b = [0.0; TAYLOR_TERMS];
    match seg.piece {
        None => {
            let w = 2.0 * PI;
            let (s, c) = (w * m).sin_cos();
            let cyc = [s, c, -s, -c];
            let mut fac = 1.0;
            for (n, bn) in b.iter_mut().enumerate() {
                if n > 0 {
                    fac *= w / n as f64;
                }
                *bn = fac * cyc[n % 4];
            }
        }
        Some(i) => {
            let p = &table.pieces()[i];
            let q = p.f.shift(m - p.start);
            for (n, c) in q.coeffs().iter().enumerate() {
                b[n] = *c;
            }
        }
    }
    b
}

/// Number of Taylor coefficients kept by [`seg_taylor`].
pub(crate) const TAYLOR_TERMS: usize = 44;

/// Real roots in [seg.start, seg.end] of g(t) = a0 + a1 F'(t) + a2 F''(t), ascending.
/// Polynomial pieces use exact real-root isolation; the sine uses the closed form of a
/// sinusoid's zeros.
pub(crate) fn seg_roots(table: &Table, seg: &Segment, a0: f64, a1: f64, a2: f64) -> Vec<f64> {
    match seg.piece {
        None => {
            // g = a0 + A cos θ + B sin θ with θ = 2πt.
            let w = 2.0 * PI;
            let (a, b) = (a1 * w, -a2 * w * w);
            let rr = a.hypot(b);
            if rr == 0.0 || a0.abs() > rr {
                return Vec::new();
            }
            let phi = b.atan2(a);
            let d = (-a0 / rr).clamp(-1.0, 1.0).acos();
            let mut out: Vec<f64> = [phi - d, phi + d]
                .iter()
                .map(|th| (th / w).rem_euclid(1.0))
                .map(|t| if t >= 1.0 { 0.0 } else { t })
                .collect();
            out.sort_by(f64::total_cmp);
            out.dedup();
            out
        }
        Some(i) => {
            let p = &table.pieces()[i];
            let g = p.d1.scale(a1).add(&p.d2.scale(a2));
            let g = g.with_coeff(0, g.coeff(0) + a0);
            if g.is_zero() {
                return Vec::new();
            }
            g.roots_in(0.0, p.len())
                .as_slice()
                .iter()
                .map(|s| p.start + s)
                .collect()
        }
    }
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
pub(crate) fn bracketed_root(g: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> Option<f64> {
    let mut glo = g(lo);
    let mut ghi = g(hi);
    if glo == 0.0 {
        return Some(lo);
    }
    if ghi == 0.0 {
        return Some(hi);
    }
    if !(glo.is_finite() && ghi.is_finite()) || (glo < 0.0) == (ghi < 0.0) {
        return None;
    }
    let mut side = 0;
    for i in 0..300 {
        let mut x = (lo * ghi - hi * glo) / (ghi - glo);
        if !(x > lo && x < hi) || i % 4 == 3 {
            x = 0.5 * (lo + hi);
        }
        if x <= lo || x >= hi {
            break;
        }
        let gx = g(x);
        if gx == 0.0 {
            return Some(x);
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
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()) {
            break;
        }
    }
    Some(if glo.abs() <= ghi.abs() { lo } else { hi })
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
    fn sine_taylor_matches_the_function() {
        let t = Table::sine();
        let seg = segments(&t)[0];
        let b = seg_taylor(&t, &seg, 0.3);
        for h in [-0.4, -0.1, 0.05, 0.45] {
            let sum: f64 = b.iter().rev().fold(0.0, |acc, c| acc * h + c);
            assert!((sum - (2.0 * PI * (0.3 + h)).sin()).abs() < 1e-14, "{h}");
        }
    }

    #[test]
    fn bracketed_root_finds_cube_root() {
        let r = bracketed_root(&|x| x * x * x - 2.0, 0.0, 2.0).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
        assert!(bracketed_root(&|x| x * x + 1.0, -1.0, 1.0).is_none());
    }
}
