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

/// The flight time τ = m + a − b as a double-double.
#[inline]
pub fn flight_time(m: i64, a: f64, b: f64) -> (f64, f64) {
    let (d, de) = two_sum(a, -b);
    let (s, se) = two_sum(m as f64, d);
    let (hi, lo) = two_sum(s, se + de);
    (hi, lo)
}

/// Height z0 + v τ − τ²/2 and velocity v − τ of a ball at flight time τ (a double-double),
/// each rounded once to f64.
#[inline]
pub fn ball_at(z0: f64, v: f64, tau: (f64, f64)) -> (f64, f64) {
    let (t, tl) = tau;
    // v τ
    let (p1, e1) = two_prod(v, t);
    let e1 = e1 + v * tl;
    // τ²/2
    let (p2, e2) = two_prod(t, 0.5 * t);
    let e2 = e2 + t * tl;
    let (s1, f1) = two_sum(z0, p1);
    let (s2, f2) = two_sum(s1, -p2);
    let z = s2 + (f1 + f2 + e1 - e2);
    let (vs, ve) = two_sum(v, -t);
    (z, vs + (ve - tl))
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
        // The plain f64 sum loses the low bits.
        assert_ne!(units(3.0 + a - b), exact);
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
