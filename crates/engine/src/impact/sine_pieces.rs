//! The sine table S(t) = sin 2πt as polynomial pieces with rigorous error bounds, built
//! at compile time.
//!
//! The period is cut into [`N`] pieces; piece k is centred at c_k = (k + ½)/N and
//! covers c_k + s with |s| ≤ [`L`] = 1/(2N). On it S is replaced by
//! H_k(s) = Σ_{j ≤ 9} h_{k,j} s^j, its Taylor polynomial of degree [`DEG`] at c_k, with
//! every coefficient (2π)^j/j! · (sin, cos, −sin, −cos)(2π c_k) computed in
//! double-double arithmetic (here, by a Taylor series of sin and cos at 0 whose terms
//! are summed to 10⁻²⁸) and rounded once to f64. For |s| ≤ L and H_k evaluated
//! exactly:
//!
//! * |S(c_k + s) − H_k(s)| ≤ [`SinePieces::e0`]: the Lagrange remainder
//!   (2π)¹⁰ L¹⁰/10! (|S⁽¹⁰⁾| ≤ (2π)¹⁰) plus Σ_j (½ ulp(h_{k,j}) + 10⁻²⁸) L^j for the
//!   rounding of the coefficients; about 1.1·10⁻¹⁶, the rounding of f64 near 1.
//! * |S'(c_k + s) − H_k'(s)| ≤ [`SinePieces::e1`], the same argument one order down
//!   (H_k' is the degree-8 Taylor polynomial of S').
//! * |S(c_k + s) − C_k(s)| ≤ [`SinePieces::cubic_err`]`[k]`, where C_k (the cubic the
//!   solver's first steps evaluate) is the Chebyshev truncation to degree 3 of the
//!   Taylor polynomial on [−L, L], computed in double-double and rounded: the bound is
//!   Σ_{m ≥ 4} |a_m| (the Chebyshev coefficients left out, |T_m| ≤ 1) plus the Taylor
//!   remainder and the rounding of C_k's coefficients; about 3·10⁻⁸, eight times less
//!   than the cubic Taylor truncation's. Its slope: |S' − C_k'| ≤
//!   [`SinePieces::cubic_derr`]`[k]` = e1 + Σ_j j |h_{k,j} − c_{k,j}| L^(j−1) (about
//!   10⁻⁴).
//! * bottom[k] ≤ S ≤ top[k] on the piece (its extremes at the ends, or ±1 where the
//!   piece holds t = ¼ or ¾).
//!
//! Every bound is rounded up generously (a relative 10⁻³); a unit test checks them
//! against an independent double-double evaluation of the sine on a fine sampling.

/// Pieces per period.
pub(super) const N: usize = 64;
/// Degree of each piece's polynomial.
pub(super) const DEG: usize = 9;
/// Half-width of a piece in phase.
pub(super) const L: f64 = 0.5 / N as f64;

/// The sine's pieces and their bounds (see the module header).
pub(super) struct SinePieces {
    /// h[k][j]: coefficient of s^j on piece k.
    pub h: [[f64; DEG + 1]; N],
    /// An upper bound of S on piece k.
    pub top: [f64; N],
    /// A lower bound of S on piece k.
    pub bottom: [f64; N],
    /// C_k: a cubic close to S on piece k (coefficients of s^0..s^3).
    pub cubic: [[f64; 4]; N],
    /// A bound of |S − C_k| on piece k.
    pub cubic_err: [f64; N],
    /// A bound of |S' − C_k'| on piece k.
    pub cubic_derr: [f64; N],
    /// Bounds of |S − H_k| and |S' − H_k'| over all pieces.
    pub e0: f64,
    pub e1: f64,
    /// Bounds of Σ_j |h_{k,j}| |s|^j and Σ_j j |h_{k,j}| |s|^(j−1) for |s| ≤ L, over all
    /// pieces (for the rounding bounds of Horner's scheme).
    pub mag0: f64,
    pub mag1: f64,
}

/// The pieces, computed once by the compiler.
pub(super) static SINE: SinePieces = build();

/// Centre c_k of piece k.
#[inline]
pub(super) fn center(k: usize) -> f64 {
    (k as f64 + 0.5) * (1.0 / N as f64)
}

/// The index of the piece holding `phase` ∈ [0, 1). (Converted through i64, whose
/// saturating conversion is a few instructions shorter than usize's.)
#[inline]
pub(super) fn index(phase: f64) -> usize {
    ((phase * N as f64) as i64 as usize).min(N - 1)
}

/// The piece holding `phase` ∈ [0, 1) and the offset s = phase − c_k.
#[inline]
pub(super) fn locate(phase: f64) -> (usize, f64) {
    let k = index(phase);
    (k, phase - center(k))
}

/// H_k(s) by Horner's scheme.
#[inline]
pub(super) fn eval(h: &[f64; DEG + 1], s: f64) -> f64 {
    let mut p = h[DEG];
    let mut j = DEG;
    while j > 0 {
        j -= 1;
        p = p * s + h[j];
    }
    p
}

/// H_k(s) and H_k'(s) by Horner's scheme.
#[inline]
pub(super) fn eval_d(h: &[f64; DEG + 1], s: f64) -> (f64, f64) {
    let mut p = h[DEG];
    let mut dp = 0.0;
    let mut j = DEG;
    while j > 0 {
        j -= 1;
        dp = dp * s + p;
        p = p * s + h[j];
    }
    (p, dp)
}

/// A double-double number hi + lo with |lo| ≤ ½ ulp(hi).
#[derive(Clone, Copy)]
struct Dd(f64, f64);

const fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}

const fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd(s, b - (s - a))
}

/// Dekker's split: a = hi + lo with hi of 26 significant bits.
const fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

const fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    Dd(p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

const fn dd_add(a: Dd, b: Dd) -> Dd {
    let s = two_sum(a.0, b.0);
    let t = two_sum(a.1, b.1);
    let u = fast_two_sum(s.0, s.1 + t.0);
    fast_two_sum(u.0, u.1 + t.1)
}

const fn dd_mul(a: Dd, b: Dd) -> Dd {
    let p = two_prod(a.0, b.0);
    fast_two_sum(p.0, p.1 + (a.0 * b.1 + a.1 * b.0))
}

const fn dd_div(a: Dd, b: f64) -> Dd {
    let q1 = a.0 / b;
    let p = two_prod(q1, b);
    let r = ((a.0 - p.0) - p.1) + a.1;
    fast_two_sum(q1, r / b)
}

const fn dd_neg(a: Dd) -> Dd {
    Dd(-a.0, -a.1)
}

/// 2π as a double-double.
const TWO_PI: Dd = Dd(std::f64::consts::TAU, 2.449_293_598_294_706_4e-16);

/// (sin θ, cos θ) for θ = 2π · num/den (0 ≤ num ≤ den, den a power of two, so num/den
/// is exact), by their Taylor series at 0 summed until the terms fall below 10⁻³⁵; the
/// terms are at most e^{2π} in sum, so the result is good to about 10⁻²⁸.
const fn sin_cos_2pi(num: usize, den: usize) -> (Dd, Dd) {
    let theta = dd_mul(TWO_PI, Dd(num as f64 / den as f64, 0.0));
    let theta2 = dd_mul(theta, theta);
    let mut sin = theta;
    let mut cos = Dd(1.0, 0.0);
    let mut s_term = theta;
    let mut c_term = Dd(1.0, 0.0);
    let mut n = 1;
    while n < 80 {
        // c_term = (−1)^n θ^(2n)/(2n)!, s_term = (−1)^n θ^(2n+1)/(2n+1)!.
        c_term = dd_neg(dd_div(
            dd_mul(c_term, theta2),
            ((2 * n - 1) * (2 * n)) as f64,
        ));
        s_term = dd_neg(dd_div(
            dd_mul(s_term, theta2),
            ((2 * n) * (2 * n + 1)) as f64,
        ));
        cos = dd_add(cos, c_term);
        sin = dd_add(sin, s_term);
        if c_term.0.abs() < 1e-35 && s_term.0.abs() < 1e-35 {
            break;
        }
        n += 1;
    }
    (sin, cos)
}

/// x^n for a small whole n.
const fn powi(x: f64, n: usize) -> f64 {
    let mut p = 1.0;
    let mut i = 0;
    while i < n {
        p *= x;
        i += 1;
    }
    p
}

/// The binomial coefficient C(n, k), exact for the small n used here.
const fn binomial(n: usize, k: usize) -> f64 {
    let mut b = 1.0;
    let mut i = 0;
    while i < k {
        b = b * (n - i) as f64 / (i + 1) as f64;
        i += 1;
    }
    b
}

/// n!
const fn factorial(n: usize) -> f64 {
    let mut f = 1.0;
    let mut i = 2;
    while i <= n {
        f *= i as f64;
        i += 1;
    }
    f
}

const fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// Half an ulp of x (for normal x), rounded up: 2⁻⁵³ |x|.
const fn half_ulp(x: f64) -> f64 {
    x.abs() * (1.0 / 9_007_199_254_740_992.0)
}

const fn build() -> SinePieces {
    let mut h = [[0.0; DEG + 1]; N];
    let mut top = [0.0; N];
    let mut bottom = [0.0; N];
    let mut cubic = [[0.0; 4]; N];
    let mut cubic_err = [0.0; N];
    let mut cubic_derr = [0.0; N];
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut e0: f64 = 0.0;
    let mut e1: f64 = 0.0;
    let mut mag0: f64 = 0.0;
    let mut mag1: f64 = 0.0;
    // Error of a double-double coefficient before its rounding to f64.
    let dd_err = 1e-28;
    let mut k = 0;
    while k < N {
        let (s, c) = sin_cos_2pi(2 * k + 1, 2 * N);
        let cyc = [s, c, dd_neg(s), dd_neg(c)];
        // (2π)^j / j! as a double-double.
        let mut fac = Dd(1.0, 0.0);
        let mut err0 = 0.0;
        let mut err1 = 0.0;
        let mut m0 = 0.0;
        let mut m1 = 0.0;
        // Chebyshev coefficients a_m of the Taylor polynomial in u = s/L ∈ [−1, 1].
        let mut cheb = [Dd(0.0, 0.0); DEG + 1];
        let mut j = 0;
        while j <= DEG {
            if j > 0 {
                fac = dd_div(dd_mul(fac, TWO_PI), j as f64);
            }
            let coeff = dd_mul(fac, cyc[j % 4]);
            // u^j = 2^(1−j) Σ_i C(j, i) T_(j−2i) (the T_0 term halved).
            let bj = dd_mul(coeff, Dd(powi(L, j), 0.0));
            let mut i = 0;
            while 2 * i <= j {
                let m = j - 2 * i;
                let mut w = binomial(j, i) * powi(0.5, j) * 2.0;
                if m == 0 {
                    w *= 0.5;
                }
                cheb[m] = dd_add(cheb[m], dd_mul(bj, Dd(w, 0.0)));
                i += 1;
            }
            let hj = coeff.0 + coeff.1;
            h[k][j] = hj;
            let round = half_ulp(hj) + dd_err;
            err0 += round * powi(L, j);
            m0 += hj.abs() * powi(L, j);
            if j >= 1 {
                err1 += j as f64 * round * powi(L, j - 1);
                m1 += j as f64 * hj.abs() * powi(L, j - 1);
            }
            j += 1;
        }
        // C(u) = a0 + a1 u + a2 (2u² − 1) + a3 (4u³ − 3u), back in s.
        let mono = [
            dd_add(cheb[0], dd_neg(cheb[2])),
            dd_add(cheb[1], dd_neg(dd_mul(cheb[3], Dd(3.0, 0.0)))),
            dd_mul(cheb[2], Dd(2.0, 0.0)),
            dd_mul(cheb[3], Dd(4.0, 0.0)),
        ];
        let mut high = 0.0;
        let mut j = 0;
        while j < 4 {
            let cj = dd_div(mono[j], powi(L, j));
            cubic[k][j] = cj.0 + cj.1;
            high += (half_ulp(cubic[k][j]) + dd_err) * powi(L, j);
            j += 1;
        }
        let mut m = 4;
        while m <= DEG {
            high += cheb[m].0.abs() * (1.0 + 1e-12) + dd_err;
            m += 1;
        }
        // Lagrange remainders of the degree-9 Taylor polynomial and of its derivative
        // (2π is rounded up by the factor).
        let big = powi(two_pi * (1.0 + 1e-15), DEG + 1);
        err0 += big * powi(L, DEG + 1) / factorial(DEG + 1);
        err1 += big * powi(L, DEG) / factorial(DEG);
        e0 = max(e0, err0);
        e1 = max(e1, err1);
        mag0 = max(mag0, m0);
        mag1 = max(mag1, m1);
        cubic_err[k] =
            high + powi(two_pi * (1.0 + 1e-15), DEG + 1) * powi(L, DEG + 1) / factorial(DEG + 1);
        // The largest value of S on [k/N, (k+1)/N]: 1 where the piece holds ¼ (the only
        // maximum), else at an end (S is monotone between its extrema ¼ and ¾).
        let (a, _) = sin_cos_2pi(k, N);
        let (b, _) = sin_cos_2pi(k + 1, N);
        top[k] = if 4 * k <= N && N < 4 * (k + 1) {
            1.0
        } else {
            max(a.0, b.0) + 1e-15
        };
        // The smallest: −1 where the piece holds ¾, else at an end.
        bottom[k] = if 4 * k <= 3 * N && 3 * N < 4 * (k + 1) {
            -1.0
        } else {
            -max(-a.0, -b.0) - 1e-15
        };
        k += 1;
    }
    let e0 = e0 * 1.001;
    let e1 = e1 * 1.001;
    let mut k = 0;
    while k < N {
        cubic_err[k] *= 1.001;
        // |S' − C_k'| ≤ |S' − H_k'| + Σ_j j |h_j − c_j| L^(j−1) (c_j = 0 beyond 3).
        let mut d = 0.0;
        let mut j = 1;
        while j <= DEG {
            let cj = if j < 4 { cubic[k][j] } else { 0.0 };
            d += j as f64 * (h[k][j] - cj).abs() * powi(L, j - 1);
            j += 1;
        }
        cubic_derr[k] = (d + e1) * 1.001;
        k += 1;
    }
    SinePieces {
        h,
        top,
        bottom,
        cubic,
        cubic_err,
        cubic_derr,
        e0,
        e1,
        mag0: mag0 * 1.001,
        mag1: mag1 * 1.001,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sin and cos of 2π t (t a double-double) by an evaluation independent of the
    /// table's: t reduced to the nearest multiple of 1/8 (exactly), the remainder's
    /// Taylor series in double-double with the angle-addition formulas for the multiple,
    /// whose sines and cosines are known exactly or as √½.
    fn reference(t: Dd) -> (Dd, Dd) {
        let q = (t.0 * 8.0).round();
        // Exact: t.0 and q/8 are within a factor 2 of each other, or q = 0.
        let r = two_sum(t.0 - q / 8.0, t.1);
        let x = dd_mul(TWO_PI, r);
        let x2 = dd_mul(x, x);
        let (mut s, mut c) = (x, Dd(1.0, 0.0));
        let (mut st, mut ct) = (x, Dd(1.0, 0.0));
        for n in 1..30 {
            ct = dd_neg(dd_div(dd_mul(ct, x2), ((2 * n - 1) * (2 * n)) as f64));
            st = dd_neg(dd_div(dd_mul(st, x2), ((2 * n) * (2 * n + 1)) as f64));
            c = dd_add(c, ct);
            s = dd_add(s, st);
        }
        // √½ in double-double.
        let h = Dd(std::f64::consts::FRAC_1_SQRT_2, -4.833_646_656_726_457e-17);
        let zero = Dd(0.0, 0.0);
        let one = Dd(1.0, 0.0);
        let (sq, cq) = match (q as i64).rem_euclid(8) {
            0 => (zero, one),
            1 => (h, h),
            2 => (one, zero),
            3 => (h, dd_neg(h)),
            4 => (zero, dd_neg(one)),
            5 => (dd_neg(h), dd_neg(h)),
            6 => (dd_neg(one), zero),
            _ => (dd_neg(h), h),
        };
        // sin(a + b) = sin a cos b + cos a sin b; cos(a + b) = cos a cos b − sin a sin b.
        let sin = dd_add(dd_mul(sq, c), dd_mul(cq, s));
        let cos = dd_add(dd_mul(cq, c), dd_neg(dd_mul(sq, s)));
        (sin, cos)
    }

    /// H_k and H_k' evaluated in double-double, so the comparison measures the
    /// polynomial, not the rounding of its evaluation.
    fn eval_exact(h: &[f64; DEG + 1], s: f64) -> (Dd, Dd) {
        let mut p = Dd(h[DEG], 0.0);
        let mut dp = Dd(0.0, 0.0);
        for j in (0..DEG).rev() {
            dp = dd_add(dd_mul(dp, Dd(s, 0.0)), p);
            p = dd_add(dd_mul(p, Dd(s, 0.0)), Dd(h[j], 0.0));
        }
        (p, dp)
    }

    /// |a − b| of two double-doubles.
    fn dist(a: Dd, b: Dd) -> f64 {
        let d = dd_add(a, dd_neg(b));
        (d.0 + d.1).abs()
    }

    #[test]
    fn reference_is_the_sine() {
        for t in [0.0, 0.1, 0.25, 0.3, 0.77, 0.999] {
            let (s, c) = reference(Dd(t, 0.0));
            let w = 2.0 * std::f64::consts::PI * t;
            assert!(
                (s.0 - w.sin()).abs() < 1e-15 && (c.0 - w.cos()).abs() < 1e-15,
                "{t}"
            );
        }
    }

    #[test]
    fn pieces_are_within_their_bounds_on_a_fine_sampling() {
        let t = &SINE;
        // Near machine precision, as promised.
        assert!(t.e0 < 2e-16 && t.e1 < 2e-15, "{} {}", t.e0, t.e1);
        let (mut worst0, mut worst1, mut worst_cubic) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..N {
            let h = &t.h[k];
            for i in 0..=400 {
                let s = -L + 2.0 * L * i as f64 / 400.0;
                // The exact point c_k + s, as a double-double.
                let (sin, cos) = reference(two_sum(center(k), s));
                let (p, dp) = eval_exact(h, s);
                let d0 = dist(p, sin);
                let d1 = dist(dp, dd_mul(TWO_PI, cos));
                assert!(d0 <= t.e0, "piece {k} s {s}: {d0:e}");
                assert!(d1 <= t.e1, "piece {k} s {s}: {d1:e}");
                let cb = &t.cubic[k];
                let cubic = eval_exact(&[cb[0], cb[1], cb[2], cb[3], 0., 0., 0., 0., 0., 0.], s).0;
                let dc = dist(cubic, sin);
                assert!(dc <= t.cubic_err[k], "piece {k} s {s}: {dc:e}");
                assert!(sin.0 <= t.top[k] && sin.0 >= t.bottom[k], "piece {k} s {s}");
                worst0 = worst0.max(d0);
                worst1 = worst1.max(d1);
                worst_cubic = worst_cubic.max(dc / t.cubic_err[k]);
            }
        }
        // The bounds are not vacuous: the cubic's is attained within a factor of 2, and
        // it is near the best a cubic can do (equioscillation: (2π)⁴ L⁴ / (4! 2³)).
        assert!(worst_cubic > 0.5, "{worst_cubic}");
        let best = (2.0 * std::f64::consts::PI * L).powi(4) / 192.0;
        assert!(t.cubic_err.iter().all(|&e| e < 1.1 * best), "{best:e}");
        // Nor are the others far from what the sampling sees.
        assert!(
            worst0 > 0.05 * t.e0 && worst1 > 0.05 * t.e1,
            "{worst0:e} {worst1:e}"
        );
    }

    #[test]
    fn tops_and_bottoms_are_attained() {
        // The top and bottom of each piece are the sine's extremes there (at an end, or
        // ±1 at ¼ and ¾).
        for k in 0..N {
            let a = (2.0 * std::f64::consts::PI * k as f64 / N as f64).sin();
            let b = (2.0 * std::f64::consts::PI * (k + 1) as f64 / N as f64).sin();
            let top = if k == N / 4 - 1 || k == N / 4 {
                1.0
            } else {
                a.max(b)
            };
            let bottom = if k == 3 * N / 4 - 1 || k == 3 * N / 4 {
                -1.0
            } else {
                a.min(b)
            };
            assert!((SINE.top[k] - top).abs() < 1e-14, "{k}");
            assert!((SINE.bottom[k] - bottom).abs() < 1e-14, "{k}");
        }
    }
}
