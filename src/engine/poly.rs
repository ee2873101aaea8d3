//! Real polynomials of small degree and the exact isolation of their real roots.
//!
//! The impact solver reduces "when does the ball meet the table" to "where is the first
//! real root of a polynomial on an interval". Roots are isolated without any time grid:
//! the roots of the derivative (found recursively) split the interval into monotone
//! pieces, each piece holds at most one root, and a sign change is refined by a
//! safeguarded Newton–bisection iteration to full precision. A critical point where the
//! value is zero within its rounding bound is a touching (double) root: grazing contacts
//! are found, not skipped.

/// Largest number of coefficients a [`Poly`] holds (degree up to `MAX_COEFFS - 1`).
pub const MAX_COEFFS: usize = 8;

/// A real polynomial `c[0] + c[1] x + ... + c[len-1] x^(len-1)`, stored inline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Poly {
    c: [f64; MAX_COEFFS],
    len: usize,
}

const EPS: f64 = f64::EPSILON;

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

    /// Value, first and second derivative at `x`.
    #[inline]
    pub fn eval_d2(&self, x: f64) -> (f64, f64, f64) {
        let mut p = 0.0;
        let mut dp = 0.0;
        let mut ddp = 0.0;
        for k in (0..self.len).rev() {
            ddp = ddp * x + dp;
            dp = dp * x + p;
            p = p * x + self.c[k];
        }
        (p, dp, 2.0 * ddp)
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

    /// `p - q`.
    pub fn sub(&self, q: &Poly) -> Poly {
        self.add(&q.scale(-1.0))
    }

    /// `p * q`. Panics if the product's degree exceeds the storage.
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
        if self.len == 4 && lo < hi {
            return self.first_root_cubic(lo, hi);
        }
        let mut out = RootList::default();
        self.collect_roots(lo, hi, &mut out, true);
        out.as_slice().first().copied()
    }

    /// [`Self::first_root`] for a cubic: the critical points come from the derivative in
    /// closed form (a double critical point is an inflection and splits nothing), then the
    /// monotone segments are scanned in order as in the general case.
    fn first_root_cubic(&self, lo: f64, hi: f64) -> Option<f64> {
        let (a, b, c) = (3.0 * self.c[3], 2.0 * self.c[2], self.c[1]);
        let mut pts = [lo, 0.0, 0.0, hi];
        let mut n = 1;
        let disc = b * b - 4.0 * a * c;
        if disc > 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            let (x1, x2) = (q / a, c / q);
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
        let mut prev = self.eval_with_bound(pts[0]);
        if prev.0.abs() <= prev.1 {
            return Some(pts[0]);
        }
        for i in 1..n {
            let cur = self.eval_with_bound(pts[i]);
            let cur_zero = cur.0.abs() <= cur.1;
            if !cur_zero && (prev.0 < 0.0) != (cur.0 < 0.0) {
                return Some(self.refine(pts[i - 1], pts[i], prev.0, cur.0));
            }
            if cur_zero {
                return Some(pts[i]);
            }
            prev = cur;
        }
        None
    }

    fn collect_roots(&self, lo: f64, hi: f64, out: &mut RootList, first_only: bool) {
        if self.len <= 1 || lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) && lo != hi {
            return;
        }
        if self.len == 2 {
            let x = -self.c[0] / self.c[1];
            if x >= lo && x <= hi {
                out.push(x);
            } else {
                // Endpoints within rounding of zero still count.
                for e in [lo, hi] {
                    let (v, b) = self.eval_with_bound(e);
                    if v.abs() <= b {
                        out.push(e);
                        break;
                    }
                }
            }
            return;
        }
        if self.len == 3 {
            self.quadratic_roots(lo, hi, out);
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

    /// Roots of a quadratic in `[lo, hi]` in closed form (the cancellation-free variant
    /// of the formula); a discriminant that is negative only within rounding gives a
    /// touching root at the vertex.
    fn quadratic_roots(&self, lo: f64, hi: f64, out: &mut RootList) {
        let (c, b, a) = (self.c[0], self.c[1], self.c[2]);
        let disc = b * b - 4.0 * a * c;
        let disc_err = 8.0 * EPS * (b * b + (4.0 * a * c).abs());
        let push_if_in = |x: f64, out: &mut RootList| {
            if x >= lo && x <= hi {
                out.push(x);
            }
        };
        if disc < -disc_err {
            return;
        }
        if disc <= disc_err {
            let x = -b / (2.0 * a);
            let (v, e) = self.eval_with_bound(x);
            if v.abs() <= e || disc >= 0.0 {
                push_if_in(x, out);
            }
            return;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        let (x1, x2) = if q != 0.0 { (q / a, c / q) } else { (0.0, 0.0) };
        let (x1, x2) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
        push_if_in(x1, out);
        push_if_in(x2, out);
    }

    /// Refine the single root in `(a, b)`, where `p(a) = pa` and `p(b) = pb` have opposite
    /// signs, by Newton steps kept inside a shrinking bracket.
    fn refine(&self, mut a: f64, mut b: f64, pa: f64, pb: f64) -> f64 {
        let neg_at_a = pa < 0.0;
        // Start from the secant point: Newton then converges in a few steps.
        let mut x = a - pa * (b - a) / (pb - pa);
        if !(x > a && x < b) {
            x = 0.5 * (a + b);
        }
        for _ in 0..200 {
            let (v, dv, ddv) = self.eval_d2(x);
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
            let newton = x - v / dv;
            if dv != 0.0 && newton > a && newton < b {
                // Converged: the Newton correction is at the rounding level of x, or
                // the error left after this step, |p''|/(2|p'|)·step² (quadratic
                // convergence), is.
                let step = newton - x;
                if step.abs() <= 4.0 * EPS * x.abs()
                    || (ddv / dv).abs() * step * step <= 2.0 * EPS * newton.abs()
                {
                    return newton;
                }
                x = newton;
            } else {
                x = 0.5 * (a + b);
            }
            // Stop once Newton no longer moves (converged to the last bit).
            if x == a || x == b {
                break;
            }
        }
        // Return the bracket end with the smaller residual.
        let (va, vb) = (self.eval(a).abs(), self.eval(b).abs());
        let (vx, _) = self.eval_d(x);
        if vx.abs() <= va && vx.abs() <= vb && x >= a && x <= b {
            x
        } else if va <= vb {
            a
        } else {
            b
        }
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
        let mut seed = 0x9e3779b97f4a7c15u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
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
