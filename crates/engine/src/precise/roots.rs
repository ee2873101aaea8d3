//! Real roots of the gap's polynomials at any precision: exact isolation through the
//! roots of the derivative, and Newton's method kept inside its bracket.

use crate::real::Real;

/// p(x) by Horner's rule (ascending coefficients).
pub(super) fn eval<R: Real>(p: &[R], x: &R) -> R {
    let mut acc = p.last().cloned().expect("a polynomial");
    for c in p.iter().rev().skip(1) {
        acc = acc * x.clone() + c.clone();
    }
    acc
}

fn derivative<R: Real>(p: &[R], ctx: &R::Context) -> Vec<R> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| R::from_f64(k as f64, ctx) * c.clone())
        .collect()
}

/// The real roots of `p` in the open interval (a, b), ascending: the roots of its
/// derivative split the interval into stretches where p is monotone, and each sign
/// change is refined ([`refine`]). Any degree (the derivative's roots by the same
/// isolation, down to a linear one).
fn roots_inside<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Vec<R> {
    let zero = R::from_f64(0.0, ctx);
    if p.len() <= 1 {
        return Vec::new();
    }
    let dp = derivative(p, ctx);
    let mut cuts = vec![a.clone()];
    cuts.extend(roots_inside(&dp, a, b, ctx));
    cuts.push(b.clone());
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (x, y) = (&w[0], &w[1]);
        let (px, py) = (eval(p, x), eval(p, y));
        if py == zero && y < b {
            out.push(y.clone());
        } else if (px < zero) != (py < zero) && px != zero && py != zero {
            out.push(refine(p, x, y, ctx));
        }
    }
    out
}

/// The first root of `p` in (a, b], where p(a) > 0: the first contact of the gap.
pub(super) fn first_root<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Option<R> {
    let zero = R::from_f64(0.0, ctx);
    if let Some(r) = roots_inside(p, a, b, ctx).into_iter().next() {
        return Some(r);
    }
    (eval(p, b) <= zero).then(|| b.clone())
}

/// The first point of [a, b) after which `p` is negative (p ≥ 0 before it): a release.
pub(super) fn first_sign_change<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Option<R> {
    let zero = R::from_f64(0.0, ctx);
    let dp = derivative(p, ctx);
    roots_inside(p, a, b, ctx)
        .into_iter()
        .find(|x| eval(&dp, x) < zero)
}

/// The root of `p` between `x` and `y`, where p changes sign and is monotone: Newton's
/// method from the bracket's better end, every step kept inside the bracket (a step
/// that leaves it, or does not halve it, is a bisection), to the precision.
fn refine<R: Real>(p: &[R], x: &R, y: &R, ctx: &R::Context) -> R {
    let zero = R::from_f64(0.0, ctx);
    let half = R::from_f64(0.5, ctx);
    let eps = R::epsilon(ctx);
    let dp = derivative(p, ctx);
    let (mut lo, mut hi) = (x.clone(), y.clone());
    let lo_negative = eval(p, &lo) < zero;
    let mut t = half.clone() * (lo.clone() + hi.clone());
    // Newton converges quadratically; bisection bounds the work by the precision's bits.
    for _ in 0..4096 {
        let pt = eval(p, &t);
        if pt == zero {
            return t;
        }
        if (pt < zero) == lo_negative {
            lo = t.clone();
        } else {
            hi = t.clone();
        }
        let width = (hi.clone() - lo.clone()).abs();
        let scale = lo.abs().max_of(hi.abs());
        if width <= eps.clone() * scale.clone() * R::from_f64(4.0, ctx) || width == zero {
            return half * (lo + hi);
        }
        let d = eval(&dp, &t);
        let newton = if d == zero {
            None
        } else {
            let step = pt / d;
            // A step below the precision: t is the root to the last bit.
            if step.abs() <= eps.clone() * scale {
                return t;
            }
            Some(t.clone() - step)
        };
        let mid = half.clone() * (lo.clone() + hi.clone());
        t = match newton {
            Some(n) if n > lo && n < hi => n,
            _ => mid,
        };
    }
    t
}

/// The larger of two values.
trait MaxOf {
    fn max_of(self, other: Self) -> Self;
}

impl<R: Real> MaxOf for R {
    fn max_of(self, other: R) -> R {
        if other > self {
            other
        } else {
            self
        }
    }
}
