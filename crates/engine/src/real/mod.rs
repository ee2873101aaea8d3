//! The number types of the numeric core: [`Number`] (what a table's expressions are
//! evaluated in: arithmetic, one, exact decimal constants) and [`Real`] (what the
//! impact map needs besides: order, square roots, sine and cosine, the precision's
//! epsilon, conversion to f64), implemented by `f64` and by [`Big`], a binary float of
//! any precision.
//!
//! [`Interval`] implements [`Number`] too: an enclosure with outward rounding, in which a
//! table's expressions evaluate to intervals containing the exact table (for proofs).
//!
//! A type carries its precision in a [`Number::Context`]: nothing for f64, the number
//! of bits for [`Big`]. Constants enter through the context, so a decimal such as `0.6`
//! is three fifths rounded once to the working precision, not the double nearest it;
//! [`Real::from_f64`] takes a double exactly, for comparing a system with the double
//! nearest to its decimal parameters.

mod big;
mod interval;

pub use big::{bits_for_digits, Big};
pub use interval::Interval;

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A number type expressions can be evaluated in.
pub trait Number:
    Clone
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// What a value needs besides its digits: the working precision.
    type Context: Clone + Debug;
    /// The value of a decimal constant (digits, an optional fraction and exponent),
    /// rounded once to the context's precision; None if the type cannot hold it.
    fn from_decimal(text: &str, ctx: &Self::Context) -> Option<Self>;
    /// One, at the context's precision.
    fn one(ctx: &Self::Context) -> Self;
}

/// A real number type the impact map can run in.
pub trait Real: Number + PartialOrd + Debug {
    /// A double, exactly (every double is a value of every precision used).
    fn from_f64(x: f64, ctx: &Self::Context) -> Self;
    /// The nearest double.
    fn to_f64(&self) -> f64;
    /// |x|.
    fn abs(&self) -> Self;
    /// √x (x ≥ 0).
    fn sqrt(&self) -> Self;
    /// (sin x, cos x), correctly rounded to the precision.
    fn sin_cos(&self) -> (Self, Self);
    /// asin x, |x| ≤ 1.
    fn asin(&self) -> Self;
    /// ln x, x > 0, correctly rounded to the precision.
    fn ln(&self) -> Self;
    /// The largest integer not above x.
    fn floor(&self) -> Self;
    /// The precision's unit roundoff: the relative error of one rounding, 2^−(bits − 1)
    /// for a float of `bits` significant bits.
    fn epsilon(ctx: &Self::Context) -> Self;
    /// π at the context's precision.
    fn pi(ctx: &Self::Context) -> Self;
    /// The context (precision) this value carries.
    fn context(&self) -> Self::Context;
    /// The value in decimal with `digits` significant digits (at most what the
    /// precision holds).
    fn to_digits(&self, digits: usize) -> String;
}

impl Number for f64 {
    type Context = ();
    fn from_decimal(text: &str, _: &()) -> Option<f64> {
        text.parse::<f64>().ok().filter(|x| x.is_finite())
    }
    fn one(_: &()) -> f64 {
        1.0
    }
}

impl Real for f64 {
    fn from_f64(x: f64, _: &()) -> f64 {
        x
    }
    fn to_f64(&self) -> f64 {
        *self
    }
    fn abs(&self) -> f64 {
        f64::abs(*self)
    }
    fn sqrt(&self) -> f64 {
        f64::sqrt(*self)
    }
    fn sin_cos(&self) -> (f64, f64) {
        f64::sin_cos(*self)
    }
    fn asin(&self) -> f64 {
        f64::asin(*self)
    }
    fn ln(&self) -> f64 {
        f64::ln(*self)
    }
    fn floor(&self) -> f64 {
        f64::floor(*self)
    }
    fn epsilon(_: &()) -> f64 {
        f64::EPSILON / 2.0
    }
    fn pi(_: &()) -> f64 {
        std::f64::consts::PI
    }
    fn context(&self) {}
    fn to_digits(&self, digits: usize) -> String {
        format!("{:.*e}", digits.clamp(1, 17) - 1, self)
    }
}
