//! [`Big`]: a binary float of any precision, over `dashu-float` (pure Rust,
//! correctly rounded arithmetic, square root, sine and cosine), rounding half to even.
//!
//! A value keeps the precision it was made with; an operation rounds to the larger
//! precision of its operands. Values are made only through the context (a number of
//! bits), so every value of a computation has its working precision.

use super::{Number, Real};
use dashu_float::round::mode::HalfEven;
use dashu_float::FBig;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::str::FromStr;

type Binary = FBig<HalfEven, 2>;
type Decimal = FBig<HalfEven, 10>;

/// A binary float of any precision.
#[derive(Clone, PartialEq)]
pub struct Big(Binary);

/// Significant bits for `digits` decimal digits, with eight guard bits.
pub fn bits_for_digits(digits: u32) -> usize {
    (digits as f64 * std::f64::consts::LOG2_10).ceil() as usize + 8
}

impl Big {
    /// The value's precision in bits.
    pub fn bits(&self) -> usize {
        self.0.precision()
    }

    fn at(x: Binary, bits: &usize) -> Big {
        Big(x.with_precision(*bits).value())
    }
}

impl fmt::Debug for Big {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // The decimal digits the precision holds.
        let digits = (self.bits() as f64 / std::f64::consts::LOG2_10).floor() as usize;
        write!(f, "{}", self.to_digits(digits))
    }
}

impl fmt::Display for Big {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for Big {
            type Output = Big;
            #[inline]
            fn $method(self, other: Big) -> Big {
                Big(self.0 $op other.0)
            }
        }
    };
}
binary_op!(Add, add, +);
binary_op!(Sub, sub, -);
binary_op!(Mul, mul, *);
binary_op!(Div, div, /);

impl Neg for Big {
    type Output = Big;
    fn neg(self) -> Big {
        Big(-self.0)
    }
}

impl PartialOrd for Big {
    fn partial_cmp(&self, other: &Big) -> Option<Ordering> {
        self.0.partial_cmp(&other.0)
    }
}

impl Number for Big {
    /// The precision in bits (at least 53, so that every double is a value).
    type Context = usize;

    fn from_decimal(text: &str, bits: &usize) -> Option<Big> {
        // Read exactly in base ten, then rounded once to the working precision.
        let exact = Decimal::from_str(text.trim()).ok()?;
        Some(Big(exact.with_base_and_precision::<2>(*bits).value()))
    }

    fn one(bits: &usize) -> Big {
        Big::at(Binary::ONE, bits)
    }
}

impl Real for Big {
    fn from_f64(x: f64, bits: &usize) -> Big {
        Big::at(
            Binary::try_from(x).expect("a finite double"),
            &(*bits).max(53),
        )
    }

    fn to_f64(&self) -> f64 {
        self.0.to_f64().value()
    }

    fn abs(&self) -> Big {
        if self.0 < Binary::ZERO {
            Big(-self.0.clone())
        } else {
            self.clone()
        }
    }

    fn sqrt(&self) -> Big {
        Big(self.0.sqrt())
    }

    fn sin_cos(&self) -> (Big, Big) {
        let (s, c) = self.0.sin_cos();
        (Big(s), Big(c))
    }

    fn asin(&self) -> Big {
        Big(self.0.asin())
    }

    fn ln(&self) -> Big {
        Big(self.0.ln())
    }

    fn floor(&self) -> Big {
        Big::at(self.0.floor(), &self.bits())
    }

    fn epsilon(bits: &usize) -> Big {
        Big::at(
            Binary::from_parts(dashu_int::IBig::ONE, 1 - *bits as isize),
            bits,
        )
    }

    fn pi(bits: &usize) -> Big {
        Big(Binary::pi(*bits))
    }

    fn context(&self) -> usize {
        self.bits()
    }

    fn to_digits(&self, digits: usize) -> String {
        // Rounded straight to `digits` decimal digits (an exact conversion of the binary
        // fraction first would carry as many digits as it has bits).
        let d: Decimal = self
            .0
            .clone()
            .with_base_and_precision::<10>(digits.max(1))
            .value();
        d.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 0.6 read at 200 bits is three fifths to 2^-200: five times it is 3 to that
    /// precision, while the double nearest 0.6 is off by 2.2e-17.
    #[test]
    fn decimals_are_read_exactly_then_rounded_once() {
        let bits = 200;
        let x = Big::from_decimal("0.6", &bits).unwrap();
        let five = Big::from_decimal("5", &bits).unwrap();
        let three = Big::from_decimal("3", &bits).unwrap();
        let err = (x.clone() * five - three).abs();
        assert!(err <= Big::epsilon(&bits) * Big::from_decimal("8", &bits).unwrap());
        let double = Big::from_f64(0.6, &bits);
        let off = (double - x).abs().to_f64();
        assert!((off - 2.220446049250313e-17).abs() < 1e-30, "{off:e}");
    }

    /// √2² = 2, sin² + cos² = 1 and π's digits, each to the precision.
    #[test]
    fn roots_and_the_sine_hold_to_the_precision() {
        for bits in [64, 256, 1400] {
            let eps = Big::epsilon(&bits);
            let two = Big::from_decimal("2", &bits).unwrap();
            let r = two.sqrt();
            assert!((r.clone() * r - two).abs() <= eps.clone() * Big::from_f64(8.0, &bits));
            let x = Big::from_decimal("0.3", &bits).unwrap();
            let (s, c) = x.sin_cos();
            let one = s.clone() * s.clone() + c.clone() * c.clone() - Big::one(&bits);
            assert!(one.abs() <= eps.clone() * Big::from_f64(8.0, &bits));
            // Beside libm's, within one ulp of f64 (rounded twice at 64 bits).
            assert!((s.to_f64() - 0.3f64.sin()).abs() <= f64::EPSILON * 0.3);
            assert!((c.to_f64() - 0.3f64.cos()).abs() <= f64::EPSILON);
        }
        let pi = format!("{:?}", Big::pi(&bits_for_digits(50)));
        assert!(
            pi.starts_with("3.14159265358979323846264338327950288419716939937510"),
            "{pi}"
        );
    }

    #[test]
    fn floor_and_epsilon() {
        let bits = 128;
        let x = Big::from_decimal("-2.5", &bits).unwrap();
        assert_eq!(x.floor().to_f64(), -3.0);
        assert_eq!(Big::epsilon(&bits).to_f64(), 2f64.powi(-127));
        assert_eq!(bits_for_digits(30), 108);
    }
}
