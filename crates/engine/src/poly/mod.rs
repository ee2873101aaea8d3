//! Real polynomials of small degree and the exact isolation of their real roots.
//!
//! The impact solver reduces "when does the ball meet the table" to "where is the first
//! real root of a polynomial on an interval". Roots are isolated without any time grid:
//! the roots of the derivative (found recursively; in closed form up to degree 3, on
//! fixed-size arrays) split the interval into monotone pieces, each piece holds at most
//! one root, and a sign change is refined to full precision inside a shrinking bracket:
//! by safeguarded Halley–bisection steps in general, and for a cubic (the common case)
//! by fourth-order steps from the inverse Hermite interpolation of the segment's ends. A
//! critical point where the value is zero within its rounding bound is a touching
//! (double) root: grazing contacts are found, not skipped.

/// Largest number of coefficients a [`Poly`] holds (degree up to `MAX_COEFFS - 1`).
pub const MAX_COEFFS: usize = 8;

/// A real polynomial `c[0] + c[1] x + ... + c[len-1] x^(len-1)`, stored inline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Poly {
    c: [f64; MAX_COEFFS],
    len: usize,
}

const EPS: f64 = f64::EPSILON;

mod cubic;
use cubic::first_root_cubic;
pub use cubic::{
    first_root_cubic_from, root_after_maximum, root_before_minimum, root_falling_from_zero,
};

impl Default for Poly {
    fn default() -> Self {
        Poly::zero()
    }
}

impl Poly {
    /// The zero polynomial.
    pub const fn zero() -> Self {
        Poly {
            c: [0.0; MAX_COEFFS],
            len: 0,
        }
    }

    /// A polynomial from ascending coefficients. Panics if there are more than
    /// [`MAX_COEFFS`] coefficients (callers validate user input before this).
    pub fn new(coeffs: &[f64]) -> Self {
        assert!(coeffs.len() <= MAX_COEFFS, "polynomial degree too high");
        let mut c = [0.0; MAX_COEFFS];
        c[..coeffs.len()].copy_from_slice(coeffs);
        let mut p = Poly {
            c,
            len: coeffs.len(),
        };
        p.trim();
        p
    }

    /// A polynomial from a fixed array of ascending coefficients (the first `len`).
    #[inline]
    pub fn from_array(c: [f64; MAX_COEFFS], len: usize) -> Self {
        let mut p = Poly { c, len };
        p.trim();
        p
    }

    fn trim(&mut self) {
        while self.len > 0 && self.c[self.len - 1] == 0.0 {
            self.len -= 1;
        }
    }

    /// Ascending coefficients (no trailing zeros).
    pub fn coeffs(&self) -> &[f64] {
        &self.c[..self.len]
    }

    /// Coefficient of `x^k` (zero beyond the degree).
    pub fn coeff(&self, k: usize) -> f64 {
        if k < self.len {
            self.c[k]
        } else {
            0.0
        }
    }

    /// Degree; the zero polynomial reports degree 0.
    pub fn degree(&self) -> usize {
        self.len.saturating_sub(1)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.len == 0
    }

    /// Value at `x` (Horner).
    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        let mut acc = 0.0;
        for k in (0..self.len).rev() {
            acc = acc * x + self.c[k];
        }
        acc
    }

    /// Value and derivative at `x`.
    #[inline]
    pub fn eval_d(&self, x: f64) -> (f64, f64) {
        let mut p = 0.0;
        let mut dp = 0.0;
        for k in (0..self.len).rev() {
            dp = dp * x + p;
            p = p * x + self.c[k];
        }
        (p, dp)
    }

    /// Value and first three derivatives at `x`.
    #[inline]
    pub fn eval_d3(&self, x: f64) -> [f64; 4] {
        let mut p = 0.0;
        let mut dp = 0.0;
        let mut ddp = 0.0;
        let mut dddp = 0.0;
        for k in (0..self.len).rev() {
            dddp = dddp * x + ddp;
            ddp = ddp * x + dp;
            dp = dp * x + p;
            p = p * x + self.c[k];
        }
        [p, dp, 2.0 * ddp, 6.0 * dddp]
    }

    /// Value at `x` with a bound on its rounding error (a few ulps of `sum |c_k x^k|`).
    #[inline]
    pub fn eval_with_bound(&self, x: f64) -> (f64, f64) {
        let ax = x.abs();
        let mut acc = 0.0;
        let mut mag = 0.0;
        for k in (0..self.len).rev() {
            acc = acc * x + self.c[k];
            mag = mag * ax + self.c[k].abs();
        }
        (acc, (4 * self.len.max(1)) as f64 * EPS * mag)
    }

    /// The derivative.
    pub fn derivative(&self) -> Poly {
        let mut d = Poly::zero();
        if self.len <= 1 {
            return d;
        }
        for k in 1..self.len {
            d.c[k - 1] = self.c[k] * k as f64;
        }
        d.len = self.len - 1;
        d.trim();
        d
    }

    /// `p(a + x)` as a polynomial in `x` (Taylor shift).
    pub fn shift(&self, a: f64) -> Poly {
        let mut c = self.c;
        let n = self.len;
        // Repeated synthetic division: after pass i, c[i] is the i-th Taylor coefficient.
        for i in 0..n {
            for k in (i..n - 1).rev() {
                c[k] += a * c[k + 1];
            }
        }
        let mut p = Poly { c, len: n };
        p.trim();
        p
    }

    /// `s * p`.
    pub fn scale(&self, s: f64) -> Poly {
        let mut p = *self;
        for k in 0..p.len {
            p.c[k] *= s;
        }
        p.trim();
        p
    }

    /// `p + q`.
    pub fn add(&self, q: &Poly) -> Poly {
        let mut p = Poly::zero();
        p.len = self.len.max(q.len);
        for k in 0..p.len {
            p.c[k] = self.coeff(k) + q.coeff(k);
        }
        p.trim();
        p
    }

    /// `p * q`. Panics if the product's degree exceeds the storage.
    #[cfg(test)]
    pub fn mul(&self, q: &Poly) -> Poly {
        if self.is_zero() || q.is_zero() {
            return Poly::zero();
        }
        let len = self.len + q.len - 1;
        assert!(len <= MAX_COEFFS, "polynomial degree too high");
        let mut p = Poly::zero();
        p.len = len;
        for i in 0..self.len {
            for j in 0..q.len {
                p.c[i + j] += self.c[i] * q.c[j];
            }
        }
        p.trim();
        p
    }

    /// `p(x) / x` for a polynomial whose constant term is (taken to be) zero.
    pub fn div_x(&self) -> Poly {
        let mut p = Poly::zero();
        if self.len <= 1 {
            return p;
        }
        for k in 1..self.len {
            p.c[k - 1] = self.c[k];
        }
        p.len = self.len - 1;
        p
    }

    /// Replace the constant term.
    pub fn with_coeff(&self, k: usize, value: f64) -> Poly {
        let mut p = *self;
        if k >= p.len {
            assert!(k < MAX_COEFFS, "polynomial degree too high");
            p.len = k + 1;
        }
        p.c[k] = value;
        p.trim();
        p
    }

    /// All real roots in `[lo, hi]`, ascending, each listed once. Touching roots (a
    /// critical point whose value is zero within rounding) are included.
    pub fn roots_in(&self, lo: f64, hi: f64) -> RootList {
        let mut out = RootList::default();
        self.collect_roots(lo, hi, &mut out, false);
        out
    }

    /// The smallest real root in `[lo, hi]`, including touching roots.
    pub fn first_root(&self, lo: f64, hi: f64) -> Option<f64> {
        if self.len <= 4 {
            return first_root_low_degree(&self.low_coeffs(), self.len, lo, hi);
        }
        let mut out = RootList::default();
        self.collect_roots(lo, hi, &mut out, true);
        out.as_slice().first().copied()
    }

    /// The first four coefficients (zero beyond the degree), for the fixed-size
    /// routines of polynomials of degree at most 3.
    #[inline]
    pub fn low_coeffs(&self) -> [f64; 4] {
        // Coefficients at and beyond `len` are always zero (every constructor keeps
        // them so), so no masking is needed.
        debug_assert!(self.c[self.len.min(MAX_COEFFS)..].iter().all(|&c| c == 0.0));
        [self.c[0], self.c[1], self.c[2], self.c[3]]
    }

    fn collect_roots(&self, lo: f64, hi: f64, out: &mut RootList, first_only: bool) {
        if self.len <= 1 || lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) && lo != hi {
            return;
        }
        if self.len == 2 {
            if let Some(x) = linear_root(&self.low_coeffs(), lo, hi) {
                out.push(x);
            }
            return;
        }
        if self.len == 3 {
            let (xs, n) = quadratic_roots(&self.low_coeffs(), lo, hi);
            for &x in &xs[..n] {
                out.push(x);
            }
            return;
        }
        // Critical points split [lo, hi] into monotone segments.
        let crit = self.derivative().roots_in(lo, hi);
        let mut pts = [0.0f64; MAX_COEFFS + 1];
        let mut np = 0;
        pts[np] = lo;
        np += 1;
        for &c in crit.as_slice() {
            if c > pts[np - 1] && c < hi {
                pts[np] = c;
                np += 1;
            }
        }
        if hi > pts[np - 1] {
            pts[np] = hi;
            np += 1;
        }
        let mut prev = self.eval_with_bound(pts[0]);
        if prev.0.abs() <= prev.1 {
            out.push(pts[0]);
            if first_only {
                return;
            }
        }
        for i in 1..np {
            let cur = self.eval_with_bound(pts[i]);
            let prev_zero = prev.0.abs() <= prev.1;
            let cur_zero = cur.0.abs() <= cur.1;
            if !prev_zero && !cur_zero && (prev.0 < 0.0) != (cur.0 < 0.0) {
                out.push(self.refine(pts[i - 1], pts[i], prev.0, cur.0));
                if first_only {
                    return;
                }
            }
            if cur_zero {
                out.push(pts[i]);
                if first_only {
                    return;
                }
            }
            prev = cur;
        }
    }

    /// Refine the single root in `(a, b)`, where `p(a) = pa` and `p(b) = pb` have opposite
    /// signs.
    fn refine(&self, a: f64, b: f64, pa: f64, pb: f64) -> f64 {
        refine_root(|x| self.eval_d3(x), a, b, pa, pb)
    }
}

/// Value and first three derivatives of `c[0] + c[1] x + c[2] x² + c[3] x³`.
#[inline]
fn cubic_eval_d3(c: &[f64; 4], x: f64) -> [f64; 4] {
    let p = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
    let dp = (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1];
    let ddp = 6.0 * c[3] * x + 2.0 * c[2];
    [p, dp, ddp, 6.0 * c[3]]
}

/// Value of a polynomial of degree ≤ 3 with a bound on its rounding error, as
/// [`Poly::eval_with_bound`] (`len` is the number of coefficients).
#[inline]
fn cubic_eval_with_bound(c: &[f64; 4], len: usize, x: f64) -> (f64, f64) {
    let ax = x.abs();
    let p = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
    let mag = ((c[3].abs() * ax + c[2].abs()) * ax + c[1].abs()) * ax + c[0].abs();
    (p, (4 * len.max(1)) as f64 * EPS * mag)
}

/// [`Poly::first_root`] for a polynomial of degree ≤ 3 given by its first four
/// coefficients and its length (`len` ≤ 4, no trailing zero): closed forms for the
/// linear and quadratic cases; for a cubic, the critical points in closed form split the
/// interval into monotone segments, which are scanned in order.
pub fn first_root_low_degree(c: &[f64; 4], len: usize, lo: f64, hi: f64) -> Option<f64> {
    // An empty or NaN interval holds no root.
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    match len {
        0 | 1 => None,
        2 => linear_root(c, lo, hi),
        3 => {
            if quadratic_keeps_sign([c[0], c[1], c[2]], lo, hi) {
                return None;
            }
            let (xs, n) = quadratic_roots(c, lo, hi);
            (n > 0).then(|| xs[0])
        }
        _ => first_root_cubic(c, lo, hi),
    }
}

/// The root of `c[0] + c[1] x` in `[lo, hi]`; an end where the value is zero within
/// rounding also counts.
fn linear_root(c: &[f64; 4], lo: f64, hi: f64) -> Option<f64> {
    let x = -c[0] / c[1];
    if x >= lo && x <= hi {
        return Some(x);
    }
    [lo, hi].into_iter().find(|&e| {
        let (v, b) = cubic_eval_with_bound(c, 2, e);
        v.abs() <= b
    })
}

/// Roots of the quadratic `c[0] + c[1] x + c[2] x²` in `[lo, hi]`, ascending, in closed
/// form (the cancellation-free variant of the formula); a discriminant that is negative
/// only within rounding gives a touching root at the vertex.
fn quadratic_roots(c: &[f64; 4], lo: f64, hi: f64) -> ([f64; 2], usize) {
    let (c0, b, a) = (c[0], c[1], c[2]);
    let mut xs = [0.0; 2];
    let mut n = 0;
    let mut push_if_in = |x: f64| {
        if x >= lo && x <= hi && (n == 0 || xs[n - 1] != x) {
            xs[n] = x;
            n += 1;
        }
    };
    let disc = b * b - 4.0 * a * c0;
    let disc_err = 8.0 * EPS * (b * b + (4.0 * a * c0).abs());
    if disc < -disc_err {
        return (xs, 0);
    }
    if disc <= disc_err {
        let x = -b / (2.0 * a);
        let (v, e) = cubic_eval_with_bound(c, 3, x);
        if v.abs() <= e || disc >= 0.0 {
            push_if_in(x);
        }
        return (xs, n);
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (x1, x2) = if q != 0.0 {
        (q / a, c0 / q)
    } else {
        (0.0, 0.0)
    };
    let (x1, x2) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
    push_if_in(x1);
    push_if_in(x2);
    (xs, n)
}

/// True when the quadratic `d[0] + d[1] x + d[2] x²` provably has no root in `[lo, hi]`:
/// its values at both ends are of one sign beyond their rounding bounds, and either its
/// curvature bends it away from zero (a concave one lies above its chord, a convex one
/// below) or its slope keeps one sign too, so it is monotone there. Cheap (no square
/// root, no division); false means only "maybe a root".
#[inline]
fn quadratic_keeps_sign(d: [f64; 3], lo: f64, hi: f64) -> bool {
    let c = [d[0], d[1], d[2], 0.0];
    let (vlo, blo) = cubic_eval_with_bound(&c, 3, lo);
    let (vhi, bhi) = cubic_eval_with_bound(&c, 3, hi);
    if !(vlo.abs() > blo && vhi.abs() > bhi && (vlo > 0.0) == (vhi > 0.0)) {
        return false;
    }
    let slope = [d[1], 2.0 * d[2], 0.0, 0.0];
    let (slo, sblo) = cubic_eval_with_bound(&slope, 2, lo);
    let (shi, sbhi) = cubic_eval_with_bound(&slope, 2, hi);
    slo.abs() > sblo && shi.abs() > sbhi && (slo > 0.0) == (shi > 0.0)
}

/// Refine the single root in `(a, b)`, where `p(a) = pa` and `p(b) = pb` have opposite
/// signs, by Halley steps kept inside a shrinking bracket (bisection when a step would
/// leave it). `eval` gives p and its first three derivatives.
///
/// Halley's method converges cubically: from the secant start a landing takes two or
/// three evaluations. It stops when the step is at the rounding level of x, or when the
/// error left after the step is below half an ulp. That error is (C₂² − C₃)·step³ to
/// leading order, with C_k = p⁽ᵏ⁾/(k! p'); the estimate used, (C₂² + |C₃|)·|step|³, cannot
/// vanish by cancellation (near an inflection point, say), where the next order would
/// then decide.
#[inline]
fn refine_root(eval: impl Fn(f64) -> [f64; 4], mut a: f64, mut b: f64, pa: f64, pb: f64) -> f64 {
    let neg_at_a = pa < 0.0;
    // Start from the secant point.
    let mut x = a - pa * (b - a) / (pb - pa);
    if !(x > a && x < b) {
        x = 0.5 * (a + b);
    }
    for _ in 0..200 {
        let [v, dv, ddv, dddv] = eval(x);
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == neg_at_a {
            a = x;
        } else {
            b = x;
        }
        if b - a <= 2.0 * EPS * a.abs().max(b.abs()) || b - a <= f64::MIN_POSITIVE {
            break;
        }
        // Halley: x − 2 p p' / (2 p'² − p p''). A zero or non-finite denominator gives a
        // step outside the bracket, hence bisection.
        let next = x - 2.0 * v * dv / (2.0 * dv * dv - v * ddv);
        if next > a && next < b {
            let step = next - x;
            let left =
                (0.25 * ddv * ddv + (dv * dddv).abs() * (1.0 / 6.0)) * (step * step * step).abs();
            if step.abs() <= 4.0 * EPS * x.abs() || 2.0 * left <= EPS * next.abs() * dv * dv {
                return next;
            }
            x = next;
        } else {
            x = 0.5 * (a + b);
        }
        // Stop once the iteration no longer moves (converged to the last bit).
        if x == a || x == b {
            break;
        }
    }
    // Return the bracket end with the smaller residual.
    let (va, vb) = (eval(a)[0].abs(), eval(b)[0].abs());
    let vx = eval(x)[0];
    if vx.abs() <= va && vx.abs() <= vb && x >= a && x <= b {
        x
    } else if va <= vb {
        a
    } else {
        b
    }
}

/// A short, allocation-free list of roots.
#[derive(Clone, Copy, Debug, Default)]
pub struct RootList {
    xs: [f64; MAX_COEFFS + 2],
    n: usize,
}

impl RootList {
    fn push(&mut self, x: f64) {
        if self.n > 0 && self.xs[self.n - 1] == x {
            return;
        }
        if self.n < self.xs.len() {
            self.xs[self.n] = x;
            self.n += 1;
        }
    }

    /// The roots, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.xs[..self.n]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Xorshift;

    fn from_roots(roots: &[f64], lead: f64) -> Poly {
        let mut p = Poly::new(&[lead]);
        for &r in roots {
            p = p.mul(&Poly::new(&[-r, 1.0]));
        }
        p
    }

    #[test]
    fn finds_simple_roots_in_order() {
        let p = from_roots(&[0.1, 0.35, 0.9], 2.0);
        let r = p.roots_in(0.0, 1.0);
        assert_eq!(r.as_slice().len(), 3);
        for (got, want) in r.as_slice().iter().zip([0.1, 0.35, 0.9]) {
            assert!((got - want).abs() < 1e-15, "{got} vs {want}");
        }
        assert!((p.first_root(0.2, 1.0).unwrap() - 0.35).abs() < 1e-15);
        assert!(p.first_root(0.36, 0.89).is_none());
    }

    #[test]
    fn cubic_fast_path_agrees_with_general_isolation() {
        // Deterministic pseudo-random cubics, some built from known roots.
        let mut rng = Xorshift::new(0x9e3779b97f4a7c15);
        let mut rnd = || rng.next() * 2.0 - 1.0;
        for i in 0..20000 {
            let p = if i % 2 == 0 {
                Poly::new(&[rnd(), rnd(), rnd(), rnd() + 2.0 * rnd().signum()])
            } else {
                from_roots(&[rnd(), rnd(), rnd()], 1.0 + rnd().abs())
            };
            let (lo, hi) = (rnd().min(0.0), rnd().max(0.0) + 0.1);
            let mut general = RootList::default();
            p.collect_roots(lo, hi, &mut general, true);
            let fast = p.first_root(lo, hi);
            match (fast, general.as_slice().first()) {
                (None, None) => {}
                (Some(a), Some(&b)) => {
                    assert!((a - b).abs() < 1e-9, "{p:?} [{lo}, {hi}]: {a} vs {b}")
                }
                (a, b) => panic!("{p:?} [{lo}, {hi}]: {a:?} vs {b:?}"),
            }
        }
    }

    /// p(x) by compensated Horner: accurate to about one ulp of the value even where
    /// plain Horner loses everything to cancellation.
    fn eval_compensated(c: &[f64; 4], x: f64) -> f64 {
        use crate::exact_sum::{two_prod, two_sum};
        let mut s = c[3];
        let mut err = 0.0;
        for k in (0..3).rev() {
            let (p, pe) = two_prod(s, x);
            let (t, te) = two_sum(p, c[k]);
            s = t;
            err = err * x + (pe + te);
        }
        s + err
    }

    /// The root in [a, b] (a sign change) by bisection down to adjacent floats, with
    /// signs from the compensated evaluation: a reference independent of Halley's
    /// iteration and of its stopping rule.
    fn bisect_reference(c: &[f64; 4], mut a: f64, mut b: f64) -> f64 {
        let neg_a = eval_compensated(c, a) < 0.0;
        loop {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            if (eval_compensated(c, m) < 0.0) == neg_a {
                a = m;
            } else {
                b = m;
            }
        }
        if eval_compensated(c, a).abs() <= eval_compensated(c, b).abs() {
            a
        } else {
            b
        }
    }

    #[test]
    fn cubic_roots_are_refined_to_full_precision() {
        // Random cubics, and two families where a leading error term is zero at the
        // root, so the stopping rule relies on its guard against cancellation:
        // C₂² = C₃ (Halley's cubic term) and an inflection point (C₂ = 0).
        let mut rng = Xorshift::new(0x2545f4914f6cdd1d);
        let mut rnd = || rng.next();
        let mut worst = 0.0f64;
        for i in 0..30000 {
            let r = 0.05 + 0.9 * rnd();
            // Powers of (x − r) as polynomials in x.
            let u = Poly::new(&[-r, 1.0]);
            let (u2, u3) = (u.mul(&u), u.mul(&u).mul(&u));
            let c = match i % 3 {
                0 => from_roots(&[r, -1.0 - rnd(), 2.0 + rnd()], 0.2 + rnd()).low_coeffs(),
                1 => {
                    // (x − r) + q/2 (x − r)² + q²/4 (x − r)³, where p''² = 2/3 p' p'''.
                    let q = 2.0 + 8.0 * rnd();
                    let a = 0.25 * q * q * (1.0 + 1e-6 * (rnd() - 0.5));
                    u.add(&u2.scale(0.5 * q)).add(&u3.scale(a)).low_coeffs()
                }
                _ => {
                    // k (x − r) + a (x − r)³: inflection at the root.
                    let (k, a) = (0.01 + rnd(), 0.1 + 10.0 * rnd());
                    u.scale(k).add(&u3.scale(a)).low_coeffs()
                }
            };
            let Some(x) = first_root_low_degree(&c, 4, r - 0.04, r + 0.04) else {
                panic!("no root found for {c:?} near {r}");
            };
            let reference = bisect_reference(&c, r - 0.04, r + 0.04);
            // Allowed: the conditioning of the plain evaluation at the root, plus 2 ulps.
            let (_, bound) = cubic_eval_with_bound(&c, 4, x);
            let slope = cubic_eval_d3(&c, x)[1].abs();
            let allowed = 2.0 * EPS * x.abs() + bound / slope;
            let err = (x - reference).abs();
            worst = worst.max(err / allowed);
            assert!(
                err <= allowed,
                "{c:?}: {x} vs {reference} (allowed {allowed:e})"
            );
        }
        assert!(worst > 0.0, "the comparison must not be vacuous");
    }

    #[test]
    fn shortcut_roots_of_shaped_cubics_match_bisection() {
        // Random cubics positive at 0 whose slope is monotone on [0, hi], sorted by the
        // slopes' signs at the ends into the three shapes with a shortcut; each root (or
        // its absence) is checked against bisection with compensated signs.
        let mut rng = Xorshift::new(0x5851f42d4c957f2d);
        let mut rnd = || rng.next() * 2.0 - 1.0;
        let mut checked = [0usize; 3];
        for i in 0..60000 {
            let c = [0.05 + rnd().abs(), 2.0 * rnd(), 2.0 * rnd(), rnd()];
            let (hi, offset) = (0.2 + rnd().abs(), if i % 2 == 0 { 0.0 } else { 0.5 });
            let vertex = -c[2] / (3.0 * c[3]);
            if vertex > 0.0 && vertex < hi {
                continue;
            }
            let slope = |x: f64| cubic_eval_d3(&c, x)[1];
            let (d0, d1) = (slope(0.0), slope(hi));
            let end = eval_compensated(&c, hi);
            let allowed = |x: f64| {
                let (_, bound) = cubic_eval_with_bound(&c, 4, x);
                2.0 * EPS * (x.abs() + offset) + bound / slope(x).abs()
            };
            let check = |x: f64, reference: f64| {
                let err = (x - reference).abs();
                assert!(
                    err <= allowed(reference),
                    "{c:?} on [0, {hi}]: {x} vs {reference}"
                );
            };
            if d0 < 0.0 && d1 < 0.0 && end < -1e-6 {
                check(
                    root_falling_from_zero(&c, hi, offset),
                    bisect_reference(&c, 0.0, hi),
                );
                checked[0] += 1;
            } else if d0 > 0.0 && d1 < 0.0 && end < -1e-6 {
                check(
                    root_after_maximum(&c, hi, offset),
                    bisect_reference(&c, 0.0, hi),
                );
                checked[1] += 1;
            } else if d0 < 0.0 && d1 > 0.0 {
                // The minimum, where the slope (increasing) crosses zero, by bisection.
                let (mut a, mut b) = (0.0, hi);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if slope(m) < 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let least = eval_compensated(&c, a);
                let got = root_before_minimum(&c, hi, offset);
                if least < -1e-6 {
                    check(
                        got.expect("a root before the minimum"),
                        bisect_reference(&c, 0.0, a),
                    );
                } else if least > 1e-6 {
                    assert_eq!(got, None, "{c:?} on [0, {hi}]: minimum {least}");
                }
                checked[2] += 1;
            }
        }
        assert!(
            checked.iter().all(|&n| n > 1000),
            "each shape tested: {checked:?}"
        );
    }

    #[test]
    fn finds_touching_double_root() {
        // (x - 0.25)^2 (x + 3): touches zero at 0.25 without a sign change.
        let p = from_roots(&[0.25, 0.25, -3.0], 1.0);
        let r = p.first_root(0.0, 1.0).unwrap();
        assert!((r - 0.25).abs() < 1e-7, "{r}");
    }

    #[test]
    fn shift_is_taylor_expansion() {
        let p = Poly::new(&[1.0, -2.0, 0.5, 3.0]);
        let q = p.shift(0.7);
        for x in [-1.0, 0.0, 0.3, 2.0] {
            assert!((q.eval(x) - p.eval(0.7 + x)).abs() < 1e-13);
        }
    }

    #[test]
    fn close_roots_are_separated() {
        // The dip between the roots is 2.5e-13, far above the rounding level.
        let p = from_roots(&[0.5, 0.5 + 1e-6], 1.0);
        let r = p.roots_in(0.0, 1.0);
        assert_eq!(r.as_slice().len(), 2, "{:?}", r.as_slice());
        // Conditioning: rounding of p (~3e-15) over |p'| = 1e-6 at the root gives ~3e-9.
        assert!((r.as_slice()[0] - 0.5).abs() < 5e-9);
        assert!((r.as_slice()[1] - 0.5 - 1e-6).abs() < 5e-9);
    }
}
