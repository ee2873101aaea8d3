//! Error-free transformations (two-sum, two-product) for the few places where the ball's
//! height far from its launch must be known to the last bit.
//!
//! A long flight evaluates z(τ) = z0 + vτ − τ²/2 with terms of size v τ that cancel to
//! a height near the table's. In plain f64 that loses log2(vτ) bits; here the flight
//! time τ = m + a − b (m whole periods, a and b phases) and the height are carried as
//! unevaluated sums of two f64s, so the result is correct to about one ulp of the height.

/// `a + b` as an exact unevaluated sum `(s, e)`.
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a * b` as an exact unevaluated sum `(p, e)` (Dekker's product: exact unless a
/// product overflows or underflows, far outside the engine's ranges). Without a fused
/// multiply-add in the target's baseline instruction set, `f64::mul_add` is a library
/// call; this is a dozen inline operations with the same result.
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Veltkamp's split: a = hi + lo exactly, each with at most 26 significant bits.
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// The flight time τ = m + a − b as a double-double (m ≥ 0; a, b phases in [0, 1]).
///
/// Usually m + a is exact (few periods, or a piece start with few bits, as F_D's 0 and
/// ½) and at least b (a later piece's start): then one Fast2Sum of it and −b gives τ.
/// Fast2Sum's error term a − ((m + a) − m), exact since m ≥ |a| or m = 0, says whether
/// m + a is exact.
#[inline]
pub fn flight_time(m: i64, a: f64, b: f64) -> (f64, f64) {
    let mf = m as f64;
    let s = mf + a;
    if s - mf == a && s >= b {
        let t = s - b;
        return (t, (s - t) - b);
    }
    let (d, de) = two_sum(a, -b);
    let (s, se) = two_sum(mf, d);
    let (hi, lo) = two_sum(s, se + de);
    (hi, lo)
}

/// Height z0 + v τ − τ²/2 and velocity v − τ of a ball at flight time τ (a double-double):
/// the height rounded once to f64, the velocity to within an ulp (it enters the gap's
/// linear coefficient, which is rounded anyway).
///
/// The height is z0 + τ u with u = v − τ/2: u is a double-double (the sum v − t/2 is
/// exact as two f64s, then − tl/2), the product t·u exact, and the terms left (t·ue,
/// tl·u) are below the last bit of the sum's large parts; tl·ue and tl² are dropped.
#[inline]
pub fn ball_at(z0: f64, v: f64, tau: (f64, f64)) -> (f64, f64) {
    let (t, tl) = tau;
    let (u, ue) = two_sum(v, -0.5 * t);
    let ue = ue - 0.5 * tl;
    let (p, pe) = two_prod(t, u);
    let (s, se) = two_sum(z0, p);
    let z = s + (se + pe + t * ue + tl * u);
    (z, (v - t) - tl)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_flight_height_is_exact() {
        // z0 = 0, v = 100.25, τ = 200.5 exactly representable: z = 100.25·200.5 − 200.5²/2
        // = 20100.125 − 20100.125 = 0 exactly.
        let (z, vb) = ball_at(0.0, 100.25, flight_time(200, 0.75, 0.25));
        assert_eq!(z, 0.0);
        assert_eq!(vb, 100.25 - 200.5);
        // τ = 3 + a − b with a = fl(0.1), b = fl(0.7): every term is a multiple of
        // 2⁻⁵⁶, so the exact sum is an integer in units of 2⁻⁵⁶, computed in i128. The
        // double-double (hi, lo) must represent it exactly.
        let (a, b) = (0.1f64, 0.7f64);
        let unit = 2f64.powi(56);
        let units = |x: f64| {
            let y = x * unit;
            assert_eq!(y.fract(), 0.0, "{x} is not a multiple of 2^-56");
            y as i128
        };
        let exact = 3 * (1i128 << 56) + units(a) - units(b);
        let (hi, lo) = flight_time(3, a, b);
        assert_eq!(units(hi) + units(lo), exact);
        // A start whose sum with the period count is not exact takes the general route.
        let a = 1.0 - f64::EPSILON / 4.0;
        let exact = 3 * (1i128 << 56) + units(a) - units(b);
        let (hi, lo) = flight_time(3, a, b);
        assert_eq!(units(hi) + units(lo), exact);
        // The plain f64 sum loses the low bits.
        assert_ne!(units(3.0 + a - b), exact);
    }

    /// The ball's height against exact rational arithmetic: every input a multiple of
    /// 2⁻³⁰ (and below 2²⁰), so z0 + vτ − τ²/2 is a multiple of 2⁻⁶¹ computed exactly
    /// in i128; the result must be that value correctly rounded to within one ulp.
    #[test]
    fn ball_height_is_rounded_once() {
        let unit = 2f64.powi(30);
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            ((x >> 11) % (1 << 40)) as i64 - (1 << 39)
        };
        for _ in 0..20_000 {
            let (z0i, vi, ti) = (next() >> 8, next() >> 6, (next().abs() >> 10) + 1);
            let (z0, v, t) = (z0i as f64 / unit, vi as f64 / unit, ti as f64 / unit);
            // Exact: z0 + v t − t²/2 in units of 2⁻⁶¹.
            let exact = ((z0i as i128) << 31) + 2 * (vi as i128) * (ti as i128)
                - (ti as i128) * (ti as i128);
            let exact = exact as f64 / 2f64.powi(61);
            let (z, vb) = ball_at(z0, v, (t, 0.0));
            let ulp = f64::EPSILON * exact.abs().max(f64::MIN_POSITIVE);
            assert!((z - exact).abs() <= ulp, "{z0} {v} {t}: {z} vs {exact}");
            assert_eq!(vb, v - t);
        }
    }

    #[test]
    fn two_prod_is_exact() {
        // Against the fused multiply-add, which computes a·b − p with one rounding of an
        // exact value: the error term must be that value.
        let mut x = 0.123_456_789_f64;
        for _ in 0..10_000 {
            x = (x * 3.7 + 0.31).fract();
            let (a, b) = (x * 1e3 - 500.0, (x * 7.3).fract() * 1e-3 + 1e-9);
            let (p, e) = two_prod(a, b);
            assert_eq!(p, a * b);
            assert_eq!(e, a.mul_add(b, -p), "{a} {b}");
        }
    }
}
