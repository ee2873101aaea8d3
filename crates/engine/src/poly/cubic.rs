//! The first root of a cubic on an interval: critical points in closed form, an
//! inverse-Hermite start on a monotone stretch, fourth-order steps in a shrinking
//! bracket. The hot path of every landing on a table of degree ≤ 3.

use super::*;

/// The first root of a cubic (`c[3]` ≠ 0) in `[lo, hi]`. The critical points come from
/// the derivative in closed form (a double critical point is an inflection and splits
/// nothing), then the monotone segments are scanned in order as in the general case.
/// On a segment without critical points (the common case) the refinement starts from
/// the inverse cubic Hermite interpolation of the ends' values and slopes.
pub(super) fn first_root_cubic(c: &[f64; 4], lo: f64, hi: f64) -> Option<f64> {
    let at_lo = cubic_eval_with_bound(c, 4, lo);
    if at_lo.0.abs() <= at_lo.1 {
        return Some(lo);
    }
    first_root_cubic_from(c, lo, hi, at_lo.0)
}

/// [`first_root_low_degree`] for a cubic (`c[3]` ≠ 0) on `[lo, hi]` whose value at `lo`,
/// `at_lo`, is known and nonzero beyond its rounding bound (e.g. a gap that is positive
/// where the search starts).
#[inline]
pub fn first_root_cubic_from(c: &[f64; 4], lo: f64, hi: f64, at_lo: f64) -> Option<f64> {
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut pts = [lo, 0.0, 0.0, hi];
    let mut n = 1;
    let disc = b * b - 4.0 * a * cc;
    if disc > 0.0 {
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        let (x1, x2) = (q / a, cc / q);
        let (x1, x2) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
        for x in [x1, x2] {
            if x > pts[n - 1] && x < hi {
                pts[n] = x;
                n += 1;
            }
        }
    }
    pts[n] = hi;
    n += 1;
    let mut prev = (at_lo, 0.0);
    for i in 1..n {
        let cur = cubic_eval_with_bound(c, 4, pts[i]);
        let cur_zero = cur.0.abs() <= cur.1;
        if !cur_zero && (prev.0 < 0.0) != (cur.0 < 0.0) {
            let (x0, x1) = (pts[i - 1], pts[i]);
            let start = if n == 2 {
                // No critical point inside: the slopes at the ends have one sign.
                let slope = |x: f64| (a * x + b) * x + cc;
                inverse_hermite(x0, x1, prev.0, cur.0, slope(x0), slope(x1))
            } else {
                x0 - prev.0 * (x1 - x0) / (cur.0 - prev.0)
            };
            return Some(refine_cubic(c, x0, x1, prev.0, start));
        }
        if cur_zero {
            return Some(pts[i]);
        }
        prev = cur;
    }
    None
}

/// Where a monotone function with values `p0`, `p1` (opposite signs) and slopes `d0`,
/// `d1` at `x0`, `x1` crosses zero, by cubic Hermite interpolation of its inverse (whose
/// slopes are 1/d). Only a start for the refinement: a value outside the bracket is
/// replaced there by the bracket's midpoint.
#[inline]
fn inverse_hermite(x0: f64, x1: f64, p0: f64, p1: f64, d0: f64, d1: f64) -> f64 {
    let h = p1 - p0;
    let t = -p0 / h;
    let s = t * t * (3.0 - 2.0 * t);
    x0 + s * (x1 - x0) + h * (t * (1.0 - t) * ((1.0 - t) / d0 - t / d1))
}

/// Refine the single root of a cubic in `(a, b)`, where `p(a) = pa` and `p(b)` have
/// opposite signs, from `start`, inside a shrinking bracket (bisection when a step would
/// leave it).
///
/// Each step is the series reversion of the cubic's Taylor expansion at x, truncated
/// after the third order: with h = p/p', a₂ = p″/(2p'), a₃ = p‴/(6p'), the root is at
/// x − h − a₂ h² − (2a₂² − a₃) h³ − 5a₂(a₂² − a₃) h⁴ − (14a₂⁴ − 21a₂²a₃ + 3a₃²) h⁵ − …;
/// the step keeps the first three terms (fourth-order convergence: from a start within
/// 10⁻⁴ one step reaches the last bit). It stops when the step is at the rounding level of
/// x, or when the first two terms left out are below half an ulp; that estimate,
/// 5|a₂|(a₂² + |a₃|) h⁴ + (14a₂⁴ + 21a₂²|a₃| + 3a₃²) |h|⁵, cannot vanish by cancellation
/// (where a₂² = a₃, or at an inflection point).
#[inline]
fn refine_cubic(c: &[f64; 4], mut a: f64, mut b: f64, pa: f64, start: f64) -> f64 {
    let neg_at_a = pa < 0.0;
    let mut x = if start > a && start < b {
        start
    } else {
        0.5 * (a + b)
    };
    for _ in 0..200 {
        let v = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == neg_at_a {
            a = x;
        } else {
            b = x;
        }
        let dv = (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1];
        let r = 1.0 / dv;
        let h = v * r;
        let a2 = (3.0 * c[3] * x + c[2]) * r;
        let a3 = c[3] * r;
        let next = x - h * (1.0 + h * (a2 + h * (2.0 * a2 * a2 - a3)));
        if next > a && next < b {
            let (h2, a22, a3a) = (h * h, a2 * a2, a3.abs());
            let left = h2
                * h2
                * (5.0 * a2.abs() * (a22 + a3a)
                    + h.abs() * (14.0 * a22 * a22 + 21.0 * a22 * a3a + 3.0 * a3 * a3));
            if (next - x).abs() <= 4.0 * EPS * x.abs() || 2.0 * left <= EPS * next.abs() {
                return next;
            }
            x = next;
        } else {
            // Bisection, until the bracket is down to adjacent floats.
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            x = mid;
        }
    }
    // Return the bracket end with the smaller residual.
    if cubic_eval_d3(c, a)[0].abs() <= cubic_eval_d3(c, b)[0].abs() {
        a
    } else {
        b
    }
}
