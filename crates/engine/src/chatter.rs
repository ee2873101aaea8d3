//! The accumulation of a chattering sequence, written once over the number type
//! ([`Real`]): the f64 map ([`crate::ImpactMap`]) and the map at any precision
//! ([`crate::PreciseMap`]) both jump to the accumulation time through [`ChatterSeries`].
//!
//! After an impact at t with relative velocity w, where the table's acceleration is
//! f'' > −1, the following impacts accumulate at t + T. With a = 1 + f''(t),
//! x = f'''(t)/a, y = f''''(t)/a, z = f⁽⁵⁾(t)/a and T₀ = 2w/(a(1 − r)), the flight times
//! (roots of w − aτ/2 − f'''τ²/6 − …) and the restitution law give, order by order in
//! T₀ (the sum of the series, from its functional equation T(w, t) = τ + T(w', t + τ)):
//!
//! T = T₀ [1 − (x/3) T₀ + (c₃ⱼ x² − c₃ₖ y) T₀² + (−c₄ₗ z + c₄ⱼₖ x y − c₄ⱼ x³) T₀³ + …]
//!
//! with c₃ⱼ = (2r² + 3r + 2)/(9(r² + r + 1)), c₃ₖ = (1 + r)²/(12(r² + r + 1)), and with
//! D = 540(r² + 1)(r² + r + 1): c₄ₗ = 9(r⁴ + 4r³ + 4r + 1)/D,
//! c₄ⱼₖ = 15(5r⁴ + 16r³ + 4r² + 16r + 5)/D, c₄ⱼ = 20(5r⁴ + 13r³ + 6r² + 13r + 5)/D.
//! The terms in x are used (f''' is evaluated at t); the others are bounded with the
//! table's bounds of |f''''| and |f⁽⁵⁾| (zero on pieces of degree ≤ 3), and the sum of
//! the terms left out, doubled for the orders beyond, must be within the error the
//! caller accepts: 10⁻¹⁷ for doubles, the working precision's for the map at any
//! precision.

use crate::real::Real;

/// The constants of the series for one restitution and one table.
#[derive(Clone, Copy, Debug)]
pub struct ChatterSeries<R> {
    one_minus_r: R,
    /// Bounds of |f''''| and |f⁽⁵⁾| over the table (α included).
    k4: R,
    k5: R,
    c3j: R,
    c3k: R,
    c4l: R,
    c4jk: R,
    c4j: R,
}

impl<R: Real> ChatterSeries<R> {
    /// The series for restitution `r` on a table whose |f''''| and |f⁽⁵⁾| (α included)
    /// are at most `k4` and `k5`.
    pub fn new(r: &R, k4: R, k5: R) -> ChatterSeries<R> {
        let ctx = r.context();
        let n = |x: f64| R::from_f64(x, &ctx);
        let r = r.clone();
        let r2 = r.clone() * r.clone();
        let r3 = r2.clone() * r.clone();
        let r4 = r2.clone() * r2.clone();
        let q = r2.clone() + r.clone() + n(1.0);
        let d = n(540.0) * (r2.clone() + n(1.0)) * q.clone();
        ChatterSeries {
            one_minus_r: n(1.0) - r.clone(),
            k4,
            k5,
            c3j: (n(2.0) * r2.clone() + n(3.0) * r.clone() + n(2.0)) / (n(9.0) * q.clone()),
            c3k: (n(1.0) + r.clone()) * (n(1.0) + r.clone()) / (n(12.0) * q),
            c4l: n(9.0) * (r4.clone() + n(4.0) * r3.clone() + n(4.0) * r.clone() + n(1.0))
                / d.clone(),
            c4jk: n(15.0)
                * (n(5.0) * r4.clone()
                    + n(16.0) * r3.clone()
                    + n(4.0) * r2.clone()
                    + n(16.0) * r.clone()
                    + n(5.0))
                / d.clone(),
            c4j: n(20.0) * (n(5.0) * r4 + n(13.0) * r3 + n(6.0) * r2 + n(13.0) * r + n(5.0)) / d,
        }
    }

    /// The leading order T₀ = 2w/(a(1 − r)) of the window after an impact with
    /// relative velocity `w` where 1 + f'' = `a` (> 0).
    #[inline]
    pub fn leading(&self, w: &R, a: &R) -> R {
        let two = R::from_f64(2.0, &w.context());
        two * w.clone() / (a.clone() * self.one_minus_r.clone())
    }

    /// The accumulation window T after an impact with relative velocity `w` where
    /// 1 + f'' = `a` and f''' = `f3`, when it is resolved: its leading order T₀ = `t0`
    /// ([`Self::leading`]) within `window_max`, the series in its range (each order
    /// below a tenth of the one before: |x| T₀, |y| T₀², |z| T₀³ ≤ 0.1) and the bound
    /// of the terms left out within `error`. None where a ≤ 0 (no chattering there).
    #[inline]
    pub fn window(&self, t0: &R, a: &R, f3: &R, window_max: &R, error: &R) -> Option<R> {
        let ctx = a.context();
        let n = |x: f64| R::from_f64(x, &ctx);
        if *a <= n(0.0) || *t0 > *window_max {
            return None;
        }
        let t0 = t0.clone();
        let x = f3.clone() / a.clone();
        let xt = (x.clone() * t0.clone()).abs();
        let yt = self.k4.clone() / a.clone() * t0.clone() * t0.clone();
        let zt = self.k5.clone() / a.clone() * t0.clone() * t0.clone() * t0.clone();
        let tenth = n(0.1);
        if xt > tenth || yt > tenth || zt > tenth {
            return None;
        }
        let left_out = t0.clone()
            * (self.c3k.clone() * yt.clone()
                + self.c4l.clone() * zt
                + self.c4jk.clone() * xt.clone() * yt
                + self.c4j.clone() * xt.clone() * xt.clone() * xt.clone());
        if n(2.0) * left_out > *error {
            return None;
        }
        let signed = if x < n(0.0) { -xt.clone() } else { xt.clone() };
        Some(t0 * (n(1.0) - signed / n(3.0) + self.c3j.clone() * xt.clone() * xt))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::{bits_for_digits, Big};

    /// On a table without curvature change (f''' = 0, no higher derivatives) the
    /// flights after an impact at relative velocity w are 2w rᵏ/a, a geometric series
    /// whose sum is T₀ exactly: the window is its leading order.
    #[test]
    fn without_jerk_the_window_is_the_geometric_sum() {
        let s = ChatterSeries::new(&0.8, 0.0, 0.0);
        let (w, a) = (1e-6, 1.5);
        let t0 = s.leading(&w, &a);
        let sum: f64 = (0..400).map(|k| 2.0 * w * 0.8f64.powi(k) / a).sum();
        assert!((t0 - sum).abs() <= 1e-15 * sum, "{t0} vs {sum}");
        assert_eq!(s.window(&t0, &a, &0.0, &1e-3, &1e-17), Some(t0));
    }

    /// One series over both number types: the f64 window and the window at 60 digits
    /// agree to the f64 rounding for a spread of states, and refuse the same ones.
    #[test]
    fn the_window_is_the_same_series_in_f64_and_at_any_precision() {
        let bits = bits_for_digits(60);
        let big = |x: f64| Big::from_f64(x, &bits);
        let mut resolved = 0;
        for (k, r) in [0.3, 0.5, 0.8, 0.95].into_iter().enumerate() {
            let f = ChatterSeries::new(&r, 3.0, 20.0);
            let b = ChatterSeries::new(&big(r), big(3.0), big(20.0));
            let states = [
                (1e-7, 0.5, 2.0),
                (1e-9, 1.3, -40.0),
                (2e-6, 0.9, 5.0),
                (1e-4, 0.5, 2.0),
            ];
            for (w, a, f3) in states {
                let (t0, t0b) = (f.leading(&w, &a), b.leading(&big(w), &big(a)));
                let wf = f.window(&t0, &a, &f3, &1e-3, &1e-12);
                let wb = b.window(&t0b, &big(a), &big(f3), &big(1e-3), &big(1e-12));
                assert_eq!(wf.is_some(), wb.is_some(), "case {k}: {w} {a} {f3}");
                if let (Some(x), Some(y)) = (wf, wb) {
                    resolved += 1;
                    let d = (y.to_f64() - x).abs();
                    assert!(d <= 4.0 * f64::EPSILON * x, "case {k}: {x} vs {y:?}");
                }
            }
        }
        // Both outcomes are exercised.
        assert!(resolved > 0 && resolved < 16, "{resolved} of 16 resolved");
    }
}
