//! One smooth stretch of a table, and everything the engine computes from the formula
//! of F on it: its jet, its Taylor coefficients, the roots of a0 + a1 F' + a2 F'', and
//! where the table starts to accelerate downward faster than gravity (the release of a
//! ball riding on it). Each method matches the [`Formula`] exhaustively, so a new
//! shape is one new variant here and the compiler lists every place it must answer.

use super::Piece;
use std::f64::consts::PI;

/// Number of Taylor coefficients kept by [`Segment::taylor`].
pub const TAYLOR_TERMS: usize = 44;

/// The formula of F on a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Formula<'a> {
    /// sin 2πt̂ (one segment covers the whole period; it is smooth across the wrap).
    Sine,
    /// A polynomial piece, in its local variable s = t̂ − start.
    Poly(&'a Piece),
}

/// A smooth stretch [start, end] of the table in phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<'a> {
    /// Phase where the segment starts.
    pub start: f64,
    /// Phase where it ends.
    pub end: f64,
    /// Its formula.
    pub formula: Formula<'a>,
}

impl<'a> Segment<'a> {
    /// The sine's single segment, [0, 1].
    pub fn sine() -> Segment<'static> {
        Segment {
            start: 0.0,
            end: 1.0,
            formula: Formula::Sine,
        }
    }

    /// A polynomial piece.
    pub fn piece(p: &'a Piece) -> Segment<'a> {
        Segment {
            start: p.start,
            end: p.end,
            formula: Formula::Poly(p),
        }
    }

    /// F, F', F'', F''' of this segment's formula at phase `t`, continued analytically
    /// outside the segment (t need not lie in [0, 1)).
    #[inline]
    pub fn jet(&self, t: f64) -> [f64; 4] {
        match self.formula {
            Formula::Sine => {
                let w = 2.0 * PI;
                let (s, c) = (w * t).sin_cos();
                [s, w * c, -w * w * s, -w * w * w * c]
            }
            Formula::Poly(p) => {
                let s = t - p.start;
                [p.f.eval(s), p.d1.eval(s), p.d2.eval(s), p.d3.eval(s)]
            }
        }
    }

    /// The `order`-th derivative (0 to 3) at phase `t`, alone.
    #[inline]
    pub fn derivative(&self, t: f64, order: usize) -> f64 {
        match self.formula {
            Formula::Sine => {
                let w = 2.0 * PI;
                let x = w * t;
                match order {
                    0 => x.sin(),
                    1 => w * x.cos(),
                    2 => -w * w * x.sin(),
                    _ => -w * w * w * x.cos(),
                }
            }
            Formula::Poly(p) => {
                let s = t - p.start;
                match order {
                    0 => p.f.eval(s),
                    1 => p.d1.eval(s),
                    2 => p.d2.eval(s),
                    _ => p.d3.eval(s),
                }
            }
        }
    }

    /// Taylor coefficients b_n = F⁽ⁿ⁾(m)/n!, n = 0..N, of this segment's formula at `m`.
    /// Polynomials give their exact finite expansion; the sine is expanded to
    /// [`TAYLOR_TERMS`] terms (remainder below 10⁻¹⁹ for |h| ≤ ½).
    pub fn taylor(&self, m: f64) -> [f64; TAYLOR_TERMS] {
        let mut b = [0.0; TAYLOR_TERMS];
        match self.formula {
            Formula::Sine => {
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
            Formula::Poly(p) => {
                let q = p.f.shift(m - p.start);
                for (n, c) in q.coeffs().iter().enumerate() {
                    b[n] = *c;
                }
            }
        }
        b
    }

    /// Real roots in [start, end] of g(t) = a0 + a1 F'(t) + a2 F''(t), ascending.
    /// Polynomial pieces use exact real-root isolation; the sine the closed form of a
    /// sinusoid's zeros.
    pub fn roots(&self, a0: f64, a1: f64, a2: f64) -> Vec<f64> {
        match self.formula {
            Formula::Sine => {
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
            Formula::Poly(p) => {
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

    /// An upper bound of |F⁽ⁿ⁾| on this segment: (2π)ⁿ for the sine; for a piece,
    /// Σ_k k!/(k − n)! |f_k| len^(k−n) over its coefficients (padded; 0 beyond its
    /// degree).
    pub fn derivative_bound(&self, n: usize) -> f64 {
        match self.formula {
            Formula::Sine => (2.0 * PI).powi(n as i32) * (1.0 + 1e-12),
            Formula::Poly(p) => {
                let len = p.len();
                let mut sum = 0.0;
                for (k, c) in p.f.coeffs().iter().enumerate().skip(n) {
                    let falling: f64 = (k + 1 - n..=k).map(|i| i as f64).product();
                    sum += falling * c.abs() * len.powi((k - n) as i32);
                }
                sum * (1.0 + 1e-12)
            }
        }
    }

    /// Whether F''' ≡ 0 on this segment (a polynomial of degree at most 2).
    pub fn is_quadratic(&self) -> bool {
        match self.formula {
            Formula::Sine => false,
            Formula::Poly(p) => p.f.degree() <= 2,
        }
    }

    /// Where F'' may jump at the end of this segment: its end for a piece, infinity for
    /// the sine (smooth across the wrap).
    pub fn breaks_at(&self) -> f64 {
        match self.formula {
            Formula::Sine => f64::INFINITY,
            Formula::Poly(p) => p.end,
        }
    }

    /// The first phase in [`from`, end) after which 1 + α F'' < 0 (with
    /// `strictly_after`, `from` itself does not count), or None on this segment.
    pub fn release(&self, alpha: f64, from: f64, strictly_after: bool) -> Option<f64> {
        match self.formula {
            Formula::Sine => {
                super::release::sine_release_in(&alpha, &(2.0 * PI), &from, strictly_after, &())
            }
            Formula::Poly(p) => {
                let accel = p.d2.scale(alpha);
                let excess = accel.with_coeff(0, accel.coeff(0) + 1.0);
                let s0 = from - p.start;
                let (r0, e0) = excess.eval_with_bound(s0);
                if r0 < -e0 && !strictly_after {
                    return Some(p.start + s0);
                }
                let roots = excess.roots_in(s0, p.len());
                let rs = roots.as_slice();
                for (i, &rho) in rs.iter().enumerate() {
                    if strictly_after && rho <= s0 {
                        continue;
                    }
                    let next = rs.get(i + 1).copied().unwrap_or(p.len());
                    if next > rho && excess.eval(0.5 * (rho + next)) < 0.0 {
                        return Some(p.start + rho);
                    }
                }
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    #[test]
    fn sine_taylor_matches_the_function() {
        let seg = Segment::sine();
        let b = seg.taylor(0.3);
        for h in [-0.4, -0.1, 0.05, 0.45] {
            let sum: f64 = b.iter().rev().fold(0.0, |acc, c| acc * h + c);
            assert!((sum - (2.0 * PI * (0.3 + h)).sin()).abs() < 1e-14, "{h}");
        }
    }

    #[test]
    fn roots_of_f_prime_match_the_closed_forms() {
        // sine: F' = 2π cos 2πt̂ = 0 at ¼ and ¾.
        let r = Segment::sine().roots(0.0, 1.0, 0.0);
        assert_eq!(r.len(), 2);
        assert!((r[0] - 0.25).abs() < 1e-15 && (r[1] - 0.75).abs() < 1e-15);
        // fd:0, first piece F = t̂² − t̂/2: F' = 2t̂ − ½ = 0 at ¼.
        let t = Table::fd(0.0).unwrap();
        let r = t.segment(0).roots(0.0, 1.0, 0.0);
        assert_eq!(r.len(), 1);
        assert!((r[0] - 0.25).abs() < 1e-15);
    }
}
