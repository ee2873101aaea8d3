//! The first root of a cubic on an interval: one route per shape where the slope is
//! monotone (falling throughout, rising then falling, falling then rising), a general
//! scan between the critical points otherwise, and fourth-order steps in a shrinking
//! bracket from a start near the root. The hot path of every landing on a table of
//! degree ≤ 3.

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
    first_root_cubic_from(c, lo, hi, at_lo.0, 0.0)
}

/// [`first_root_low_degree`] for a cubic (`c[3]` ≠ 0) on `[lo, hi]` whose value at `lo`,
/// `at_lo`, is known and nonzero beyond its rounding bound (e.g. a gap that is positive
/// where the search starts).
///
/// `offset` is what the root will be added to (a piece's start phase, or 0): the root is
/// refined to a fraction of an ulp of offset + root, not of the root alone.
///
/// On a segment that begins (ends) at a critical point x_c, the slope vanishes there and
/// the refinement starts from the quadratic Taylor model at x_c,
/// x_c ± √(−2p(x_c)/p″(x_c)).
#[inline]
pub fn first_root_cubic_from(
    c: &[f64; 4],
    lo: f64,
    hi: f64,
    at_lo: f64,
    offset: f64,
) -> Option<f64> {
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
            if n == 2 {
                // No critical point inside: the slopes at the ends have one sign.
                let slope = |x: f64| (a * x + b) * x + cc;
                let (d0, d1) = (slope(x0), slope(x1));
                return Some(root_in_monotone_bracket(
                    c, x0, x1, prev.0, cur.0, d0, d1, offset,
                ));
            }
            let start = if i > 1 {
                start_beside_critical(c, x0, prev.0, 1.0)
            } else {
                start_beside_critical(c, x1, cur.0, -1.0)
            };
            return Some(steps_in_bracket(c, x0, x1, prev.0, start, offset));
        }
        if cur_zero {
            return Some(pts[i]);
        }
        prev = cur;
    }
    None
}

/// The root of a cubic in `(x0, x1)`, where it is monotone (no critical point inside)
/// with values `p0`, `p1` of opposite signs and slopes `d0`, `d1` at the ends:
/// fourth-order steps ([`steps_in_bracket`]) from the inverse-Hermite start, typically
/// within 10⁻⁴ of the root, so that one step usually suffices.
#[inline]
#[allow(clippy::too_many_arguments)]
fn root_in_monotone_bracket(
    c: &[f64; 4],
    x0: f64,
    x1: f64,
    p0: f64,
    p1: f64,
    d0: f64,
    d1: f64,
    offset: f64,
) -> f64 {
    let start = inverse_hermite(x0, x1, p0, p1, d0, d1);
    steps_in_bracket(c, x0, x1, p0, start, offset)
}

/// The root of a cubic in `(0, hi)` along which it falls from p(0) = c₀ > 0 (its slope
/// negative throughout) to a negative value at `hi`.
///
/// The start is the root of the quadratic model c₀ + c₁x + a x² (in its cancellation-
/// free form, c₁ < 0), with the cubic term folded into a = c₂ + c₃x at the estimate
/// before (from a = c₂, twice): each fold shrinks the start's error by about the relative
/// size of the cubic term, so that on the pieces of F_D one fourth-order step
/// ([`steps_in_bracket`]) usually suffices. `offset` as in [`first_root_cubic_from`].
#[inline(always)]
pub fn root_falling_from_zero(c: &[f64; 4], hi: f64, offset: f64) -> f64 {
    let mut x = 0.0;
    let mut a = c[2];
    for _ in 0..2 {
        // A model without a real root (disc < 0) gives the linear estimate −c₀/c₁.
        let disc = (c[1] * c[1] - 4.0 * a * c[0]).max(0.0);
        x = 2.0 * c[0] / (disc.sqrt() - c[1]);
        a = c[2] + c[3] * x;
    }
    steps_in_bracket(c, 0.0, hi, c[0], x, offset)
}

/// The root of a cubic in `(0, hi)` that rises from a positive value at 0 to its one
/// maximum inside and then falls to a negative value at `hi` (its slope positive at 0
/// and negative at `hi`, monotone in between). The maximum x_c comes from the slope's
/// root in closed form (the one where the slope falls through zero); the refinement
/// starts from the quadratic Taylor model there, x_c + √(−2p(x_c)/p″(x_c)). `offset` as
/// in [`first_root_cubic_from`].
#[inline]
pub fn root_after_maximum(c: &[f64; 4], hi: f64, offset: f64) -> f64 {
    let Some(xc) = critical_point_inside(c, hi) else {
        return first_root_cubic_from(c, 0.0, hi, c[0], offset).unwrap_or(hi);
    };
    let pc = ((c[3] * xc + c[2]) * xc + c[1]) * xc + c[0];
    let start = start_beside_critical(c, xc, pc, 1.0);
    steps_in_bracket(c, xc, hi, pc, start, offset)
}

/// The first root of a cubic in `(0, hi]` that falls from a positive value at 0 to its
/// one minimum inside and then rises (its slope negative at 0 and positive at `hi`,
/// monotone in between): None when the minimum is positive beyond its rounding bound (the
/// end's value is then checked as [`first_root_cubic_from`] does), the minimum itself when
/// it is zero within that bound, else the root before it, refined from the quadratic
/// Taylor model there, x_c − √(−2p(x_c)/p″(x_c)). The same points, bounds and start as
/// [`first_root_cubic_from`], without its general scan. `offset` as there.
#[inline(never)]
pub fn root_before_minimum(c: &[f64; 4], hi: f64, offset: f64) -> Option<f64> {
    let Some(xc) = critical_point_inside(c, hi) else {
        return first_root_cubic_from(c, 0.0, hi, c[0], offset);
    };
    let (pc, bound) = cubic_eval_with_bound(c, 4, xc);
    if pc.abs() <= bound {
        return Some(xc);
    }
    if pc > 0.0 {
        let (p1, bound1) = cubic_eval_with_bound(c, 4, hi);
        return (p1 <= 0.0 || p1.abs() <= bound1).then_some(hi);
    }
    let start = start_beside_critical(c, xc, pc, -1.0);
    Some(steps_in_bracket(c, 0.0, xc, c[0], start, offset))
}

/// The one critical point of a cubic in `(0, hi)`, for a cubic whose slope changes sign
/// once there: the slope's root inside, from its closed form in the cancellation-free
/// arrangement. None if rounding leaves the slope no root inside (the general scan
/// then decides).
#[inline(always)]
fn critical_point_inside(c: &[f64; 4], hi: f64) -> Option<f64> {
    // p' = c1 + 2c2 x + 3c3 x².
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let disc = b * b - 4.0 * a * cc;
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (r1, r2) = (q / a, cc / q);
    let xc = if r1 > 0.0 && r1 < hi { r1 } else { r2 };
    (disc > 0.0 && xc > 0.0 && xc < hi).then_some(xc)
}

/// A start for the root next to a critical point x_c where the cubic has the value `pc`:
/// the root of the quadratic Taylor model there, x_c ± √(−2p(x_c)/p″(x_c)), on the side
/// `side` (1 after x_c, −1 before).
#[inline(always)]
fn start_beside_critical(c: &[f64; 4], xc: f64, pc: f64, side: f64) -> f64 {
    let curv = 2.0 * c[2] + 6.0 * c[3] * xc;
    xc + side * (-2.0 * pc / curv).sqrt()
}

/// The root of a cubic in `(x0, x1)`, where it is monotone and `p(x0) = p0` has the
/// opposite sign of `p(x1)`, by fourth-order steps from `start`.
///
/// The steps are [`refine_cubic`]'s, with the same stopping test (the first two terms
/// left out below half an ulp of offset + result), without its bracket bookkeeping: a
/// start or step outside the bracket, or slow convergence, hands over to
/// [`refine_cubic`].
#[inline(always)]
fn steps_in_bracket(c: &[f64; 4], x0: f64, x1: f64, p0: f64, start: f64, offset: f64) -> f64 {
    let mut x = start;
    for _ in 0..4 {
        if !(x > x0 && x < x1) {
            break;
        }
        let v = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
        let r = 1.0 / ((3.0 * c[3] * x + 2.0 * c[2]) * x + c[1]);
        let h = v * r;
        let a2 = (3.0 * c[3] * x + c[2]) * r;
        let a3 = c[3] * r;
        let next = x - h * (1.0 + h * (a2 + h * (2.0 * a2 * a2 - a3)));
        if fourth_order_done(h, a2, a3, next, offset) && next > x0 && next < x1 {
            return next;
        }
        x = next;
    }
    refine_cubic(c, x0, x1, p0, start, offset)
}

/// Whether a fourth-order step (see [`refine_cubic`]) with these h, a₂ and a₃ has
/// reached `next` to within half an ulp of offset + next: the first two terms left out,
/// 5|a₂|(a₂² + |a₃|) h⁴ + (14a₂⁴ + 21a₂²|a₃| + 3a₃²) |h|⁵, below that. With
/// K = a₂² + |a₃| the second bracket is at most 14K², so the two are at most
/// K h⁴ (5|a₂| + 14K|h|).
#[inline]
fn fourth_order_done(h: f64, a2: f64, a3: f64, next: f64, offset: f64) -> bool {
    let h2 = h * h;
    let k = a2 * a2 + a3.abs();
    let left = k * h2 * h2 * (5.0 * a2.abs() + 14.0 * k * h.abs());
    2.0 * left <= EPS * (next.abs() + offset.abs())
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
fn refine_cubic(c: &[f64; 4], mut a: f64, mut b: f64, pa: f64, start: f64, offset: f64) -> f64 {
    let offset = offset.abs();
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
            if (next - x).abs() <= 4.0 * EPS * (x.abs() + offset)
                || fourth_order_done(h, a2, a3, next, offset)
            {
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
