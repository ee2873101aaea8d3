//! [`Interval`]: a closed interval of reals with double endpoints and outward rounding,
//! the number type of proofs: every operation's result contains the exact result of
//! the operation on every pair of points of its operands.
//!
//! Each endpoint is rounded the way it must go: the rounding error of a sum, product,
//! quotient or square root is computed exactly (two-sum, Dekker's product, or the
//! remainder by a fused multiply-add), so an endpoint moves by one ulp only where the
//! double result is not exact, and exact results stay thin. Outside the range where
//! those error terms are exact (overflow, results below 2⁻⁹⁶⁰) an endpoint is moved one
//! ulp outward unconditionally, which round-to-nearest makes safe as well.
//!
//! A decimal constant (`0.6`) is enclosed by the doubles on either side of it, or is
//! the thin double it equals ([`Interval::decimal`]); the sine and cosine of 2π times a
//! phase are enclosed by their Taylor series with the remainder bounded
//! ([`Interval::sin_cos_2pi`]), not by a library's sine. It implements [`Number`], so
//! a table family's expressions evaluate to enclosures of the exact table.

use super::Number;
use crate::exact_sum::{two_prod, two_sum};
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A closed interval [lo, hi] of reals (lo ≤ hi; infinite endpoints mean unbounded).
#[derive(Clone, Copy, PartialEq)]
pub struct Interval {
    lo: f64,
    hi: f64,
}

/// Below this size the error-free transformations may lose their exactness
/// (subnormal intermediate values); an endpoint is then moved outward unconditionally.
const TINY: f64 = 1e-280;
/// Above this size a product's or quotient's parts may overflow.
const HUGE: f64 = 1e280;

fn down(x: f64) -> f64 {
    if x == f64::NEG_INFINITY {
        x
    } else {
        x.next_down()
    }
}

fn up(x: f64) -> f64 {
    if x == f64::INFINITY {
        x
    } else {
        x.next_up()
    }
}

/// The exact value is s + e: the largest double not above it, and the smallest not
/// below it (e exact unless `trusted` is false).
fn directed(s: f64, e: f64, trusted: bool) -> (f64, f64) {
    if !trusted || !s.is_finite() || !e.is_finite() {
        return (down(s), up(s));
    }
    if e > 0.0 {
        (s, up(s))
    } else if e < 0.0 {
        (down(s), s)
    } else {
        (s, s)
    }
}

fn in_range(x: f64) -> bool {
    x == 0.0 || (x.abs() > TINY && x.abs() < HUGE)
}

/// a + b rounded down and up.
fn add_rounded(a: f64, b: f64) -> (f64, f64) {
    let (s, e) = two_sum(a, b);
    directed(s, e, s.abs() < HUGE)
}

/// a · b rounded down and up.
fn mul_rounded(a: f64, b: f64) -> (f64, f64) {
    if a == 0.0 || b == 0.0 {
        return (0.0, 0.0);
    }
    let (p, e) = two_prod(a, b);
    directed(p, e, in_range(p) && in_range(a) && in_range(b))
}

/// a / b rounded down and up (b ≠ 0).
fn div_rounded(a: f64, b: f64) -> (f64, f64) {
    if a == 0.0 {
        return (0.0, 0.0);
    }
    let q = a / b;
    // a − q b exactly (the remainder of a correctly rounded quotient is a double);
    // the exact quotient is q + rem / b.
    let rem = (-q).mul_add(b, a);
    let e = if b > 0.0 { rem } else { -rem };
    directed(q, e, in_range(q) && in_range(a) && in_range(b))
}

/// √x rounded down and up (x ≥ 0).
fn sqrt_rounded(x: f64) -> (f64, f64) {
    let s = x.sqrt();
    if x == 0.0 {
        return (0.0, 0.0);
    }
    let rem = (-s).mul_add(s, x);
    let (lo, hi) = directed(s, rem, in_range(x));
    (lo.max(0.0), hi)
}

impl Interval {
    /// (−∞, ∞): what an operation returns when it cannot bound its result.
    pub const ENTIRE: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// [lo, hi]; None unless lo ≤ hi (NaN is no endpoint).
    pub fn new(lo: f64, hi: f64) -> Option<Interval> {
        (lo <= hi).then_some(Interval { lo, hi })
    }

    /// The thin interval [x, x] (a double is exact).
    pub fn point(x: f64) -> Interval {
        if x.is_nan() {
            Interval::ENTIRE
        } else {
            Interval { lo: x, hi: x }
        }
    }

    fn checked(lo: f64, hi: f64) -> Interval {
        if lo.is_nan() || hi.is_nan() || lo > hi {
            Interval::ENTIRE
        } else {
            Interval { lo, hi }
        }
    }

    /// The lower endpoint.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// The upper endpoint.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// hi − lo, rounded up.
    pub fn width(&self) -> f64 {
        add_rounded(self.hi, -self.lo).1
    }

    /// A double inside the interval, near its middle.
    pub fn mid(&self) -> f64 {
        if self.lo == self.hi {
            return self.lo;
        }
        if !self.lo.is_finite() || !self.hi.is_finite() {
            return if self.lo.is_finite() {
                self.lo
            } else if self.hi.is_finite() {
                self.hi
            } else {
                0.0
            };
        }
        (0.5 * self.lo + 0.5 * self.hi).clamp(self.lo, self.hi)
    }

    /// The largest |x| over the interval.
    pub fn mag(&self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// The smallest |x| over the interval (0 if it contains 0).
    pub fn mig(&self) -> f64 {
        if self.contains(0.0) {
            0.0
        } else {
            self.lo.abs().min(self.hi.abs())
        }
    }

    /// Whether x lies in the interval.
    pub fn contains(&self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// Whether this interval lies inside `other`'s interior.
    pub fn inside(&self, other: &Interval) -> bool {
        other.lo < self.lo && self.hi < other.hi
    }

    /// Every point is above 0.
    pub fn positive(&self) -> bool {
        self.lo > 0.0
    }

    /// Every point is below 0.
    pub fn negative(&self) -> bool {
        self.hi < 0.0
    }

    /// The smallest interval containing both.
    pub fn hull(&self, other: &Interval) -> Interval {
        Interval {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    /// The common part, if any.
    pub fn intersect(&self, other: &Interval) -> Option<Interval> {
        Interval::new(self.lo.max(other.lo), self.hi.min(other.hi))
    }

    /// x².
    pub fn sqr(self) -> Interval {
        if self.contains(0.0) {
            let m = self.mag();
            Interval::checked(0.0, mul_rounded(m, m).1)
        } else {
            let (a, b) = (self.mig(), self.mag());
            Interval::checked(mul_rounded(a, a).0, mul_rounded(b, b).1)
        }
    }

    /// xⁿ.
    pub fn powi(self, n: u32) -> Interval {
        let mut out = Interval::point(1.0);
        let mut base = self;
        let mut e = n;
        // Even powers through squares keep them non-negative.
        while e > 0 {
            if e & 1 == 1 {
                out = out * base;
            }
            e >>= 1;
            if e > 0 {
                base = base.sqr();
            }
        }
        out
    }

    /// √x over the non-negative part (ENTIRE if none).
    pub fn sqrt(self) -> Interval {
        if self.hi < 0.0 {
            return Interval::ENTIRE;
        }
        let lo = if self.lo <= 0.0 {
            0.0
        } else {
            sqrt_rounded(self.lo).0
        };
        Interval::checked(lo, sqrt_rounded(self.hi).1)
    }

    /// |x|.
    pub fn abs(self) -> Interval {
        Interval::checked(self.mig(), self.mag())
    }

    /// π.
    pub fn pi() -> Interval {
        // The double nearest π is below it by 1.2e-16, less than one ulp (4.4e-16).
        Interval {
            lo: std::f64::consts::PI,
            hi: std::f64::consts::PI.next_up(),
        }
    }

    /// The exact value of a decimal constant (digits, an optional fraction and an
    /// optional exponent): thin where it is a double, else the two doubles around it.
    pub fn decimal(text: &str) -> Option<Interval> {
        let x: f64 = text.trim().parse().ok()?;
        if !x.is_finite() {
            return None;
        }
        Some(if decimal_is_exact(text.trim()) == Some(true) {
            Interval::point(x)
        } else {
            Interval::checked(down(x), up(x))
        })
    }

    /// The decimal a double is written as (its shortest round-trip form) and the
    /// double itself: `0.6` read from a command line is both the double nearest three
    /// fifths and three fifths, and a proof over this interval holds for both.
    pub fn written(x: f64) -> Interval {
        Interval::decimal(&format!("{x}"))
            .map(|i| i.hull(&Interval::point(x)))
            .unwrap_or_else(|| Interval::point(x))
    }

    /// (sin 2πx, cos 2πx) over the interval: each enclosed by the values at the middle
    /// (Taylor series with a bounded remainder on a reduced argument) and the addition
    /// formula with |sin d − d| ≤ |d|³/6 and 1 − d²/2 ≤ cos d ≤ 1 for the distance d
    /// to the middle.
    pub fn sin_cos_2pi(self) -> (Interval, Interval) {
        let unit = Interval::checked(-1.0, 1.0);
        if !self.lo.is_finite() || !self.hi.is_finite() || self.width() > 0.25 {
            return (unit, unit);
        }
        let m = self.mid();
        let (s, c) = sin_cos_2pi_at(m);
        let two_pi = Interval::pi() * Interval::point(2.0);
        let d = two_pi * (self - Interval::point(m));
        let d3 = d.abs().powi(3) / Interval::point(6.0);
        let sin_d = d + Interval::checked(-d3.hi, d3.hi);
        let cos_d = Interval::checked(
            (Interval::point(1.0) - d.sqr() * Interval::point(0.5)).lo,
            1.0,
        );
        let sin = s * cos_d + c * sin_d;
        let cos = c * cos_d - s * sin_d;
        let clip = |x: Interval| x.intersect(&unit).unwrap_or(unit);
        (clip(sin), clip(cos))
    }
}

/// Whether a decimal text is a double exactly: m·10^e with m an integer equals a double
/// when (e ≥ 0) m·10^e < 2⁵³, or (e < 0) 5^−e divides m and the quotient is below 2⁵³.
/// None for texts it cannot judge (too many digits).
fn decimal_is_exact(text: &str) -> Option<bool> {
    let t = text.strip_prefix(['-', '+']).unwrap_or(text);
    let (mantissa, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().ok()?),
        None => (t, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits: String = int.chars().chain(frac.chars()).collect();
    if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let digits = digits.trim_start_matches('0');
    let mut e = exp.checked_sub(frac.len() as i32)?;
    let mut digits = digits.to_string();
    while digits.len() > 1 && digits.ends_with('0') {
        digits.pop();
        e += 1;
    }
    if digits.is_empty() || digits == "0" {
        return Some(true);
    }
    if digits.len() > 30 {
        return None;
    }
    let mut m: u128 = digits.parse().ok()?;
    // m·10^e = m·5^e·2^e: a double when the odd part of m·5^e (e ≥ 0) or of the
    // integer m/5^−e (e < 0) has at most 53 bits.
    if e >= 0 {
        for _ in 0..e {
            m = match m.checked_mul(5) {
                Some(x) => x,
                None => return Some(false),
            };
        }
    } else {
        for _ in 0..(-e) {
            if !m.is_multiple_of(5) {
                return Some(false);
            }
            m /= 5;
        }
    }
    while m > 0 && m.is_multiple_of(2) {
        m /= 2;
    }
    Some(m <= 1 << 53 && e.abs() < 1000)
}

/// Terms of the sine's and cosine's series summed (up to x²⁵ and x²⁴).
const SERIES_TERMS: u32 = 13;
/// A bound of each series' remainder on [0, π/2]: (π/2)²⁶/26! < 3e-22.
const SERIES_REMAINDER: f64 = 1e-21;

/// Enclosures of (sin 2πm, cos 2πm) for a double m: |m| reduced exactly to q ∈ [0, ¼)
/// and a quadrant j (for a ≥ 0, a − ⌊a⌋ and its difference from j/4 are exact in
/// binary), then the series at θ = 2πq ∈ [0, π/2]; sin is odd and cos even.
fn sin_cos_2pi_at(m: f64) -> (Interval, Interval) {
    if m < 0.0 {
        let (s, c) = sin_cos_2pi_at(-m);
        return (-s, c);
    }
    let p = m - m.floor();
    let j = ((4.0 * p).floor() as i32).clamp(0, 3);
    let q = p - 0.25 * j as f64;
    let theta = Interval::pi() * Interval::point(2.0 * q);
    let t2 = theta.sqr();
    let one = Interval::point(1.0);
    let rem = Interval::checked(-SERIES_REMAINDER, SERIES_REMAINDER);
    // sin θ = θ(1 − θ²/(2·3)(1 − θ²/(4·5)(…))), cos θ = 1 − θ²/(1·2)(1 − θ²/(3·4)(…)).
    let mut s = one;
    let mut c = one;
    for k in (1..SERIES_TERMS).rev() {
        let ks = (2 * k) as f64 * (2 * k + 1) as f64;
        let kc = (2 * k - 1) as f64 * (2 * k) as f64;
        s = one - t2 / Interval::point(ks) * s;
        c = one - t2 / Interval::point(kc) * c;
    }
    let s = theta * s + rem;
    let c = c + rem;
    match j {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

impl fmt::Debug for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{:e}, {:e}]", self.lo, self.hi)
    }
}

impl fmt::Display for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}, {}]", self.lo, self.hi)
    }
}

impl Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::checked(add_rounded(self.lo, o.lo).0, add_rounded(self.hi, o.hi).1)
    }
}

impl Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        self + (-o)
    }
}

impl Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

impl Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for a in [self.lo, self.hi] {
            for b in [o.lo, o.hi] {
                let (l, h) = mul_rounded(a, b);
                if l.is_nan() || h.is_nan() {
                    return Interval::ENTIRE;
                }
                lo = lo.min(l);
                hi = hi.max(h);
            }
        }
        Interval::checked(lo, hi)
    }
}

impl Div for Interval {
    type Output = Interval;
    fn div(self, o: Interval) -> Interval {
        if o.contains(0.0) {
            return Interval::ENTIRE;
        }
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for a in [self.lo, self.hi] {
            for b in [o.lo, o.hi] {
                let (l, h) = div_rounded(a, b);
                if l.is_nan() || h.is_nan() {
                    return Interval::ENTIRE;
                }
                lo = lo.min(l);
                hi = hi.max(h);
            }
        }
        Interval::checked(lo, hi)
    }
}

impl Number for Interval {
    type Context = ();
    fn from_decimal(text: &str, _: &()) -> Option<Interval> {
        Interval::decimal(text)
    }
    fn one(_: &()) -> Interval {
        Interval::point(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::{Big, Real};
    use proptest::prelude::*;

    const BITS: usize = 400;

    fn big(x: f64) -> Big {
        Big::from_f64(x, &BITS)
    }

    /// The exact (or 400-bit) value lies in the enclosure, and so does the double
    /// result of the same operation.
    fn encloses(i: Interval, exact: Big, double: f64) {
        assert!(
            big(i.lo()) <= exact && exact <= big(i.hi()),
            "{i:?} misses {exact:?}"
        );
        assert!(i.contains(double), "{i:?} misses the double {double:e}");
        // At most one ulp each way for an operation on thin operands.
        assert!(
            i.lo() >= down(double) && i.hi() <= up(double),
            "{i:?} {double:e}"
        );
    }

    proptest! {
        #[test]
        fn arithmetic_encloses_the_exact_result(
            a in -1e6f64..1e6, b in -1e6f64..1e6, ea in -20i32..20, eb in -20i32..20
        ) {
            let (a, b) = (a * 2f64.powi(ea), b * 2f64.powi(eb));
            let (ia, ib) = (Interval::point(a), Interval::point(b));
            encloses(ia + ib, big(a) + big(b), a + b);
            encloses(ia - ib, big(a) - big(b), a - b);
            encloses(ia * ib, big(a) * big(b), a * b);
            if b != 0.0 {
                encloses(ia / ib, big(a) / big(b), a / b);
            }
            let sa = a.abs();
            encloses(Interval::point(sa).sqrt(), big(sa).sqrt(), sa.sqrt());
        }

        #[test]
        fn wide_operands_enclose_every_pair_of_points(
            a in -10f64..10.0, wa in 0f64..1.0, b in -10f64..10.0, wb in 0f64..1.0,
            s in 0f64..1.0, t in 0f64..1.0
        ) {
            let ia = Interval::new(a, a + wa).unwrap();
            let ib = Interval::new(b, b + wb).unwrap();
            let (x, y) = (a + s * wa, b + t * wb);
            let (x, y) = (x.min(ia.hi()), y.min(ib.hi()));
            for (i, exact) in [
                (ia + ib, big(x) + big(y)),
                (ia - ib, big(x) - big(y)),
                (ia * ib, big(x) * big(y)),
                (ia.sqr(), big(x) * big(x)),
                (ia.powi(3), big(x) * big(x) * big(x)),
            ] {
                prop_assert!(big(i.lo()) <= exact.clone() && exact <= big(i.hi()));
            }
            if !ib.contains(0.0) {
                let q = ia / ib;
                let exact = big(x) / big(y);
                prop_assert!(big(q.lo()) <= exact.clone() && exact <= big(q.hi()));
            }
        }

        /// sin 2πx and cos 2πx at 400 bits lie in the enclosures of thin and wide
        /// phases, which are a few 1e-16 wide when thin; the double sin(2πx) of the
        /// rounded argument is within an ulp of the thin enclosure.
        #[test]
        fn sine_and_cosine_enclose_the_high_precision_values(
            x in -3f64..3.0, w in 0f64..0.01, frac in 0f64..1.0
        ) {
            let two_pi = Big::pi(&BITS) * big(2.0);
            let (s, c) = Interval::point(x).sin_cos_2pi();
            let (bs, bc) = (two_pi.clone() * big(x)).sin_cos();
            prop_assert!(big(s.lo()) <= bs.clone() && bs <= big(s.hi()), "{s:?}");
            prop_assert!(big(c.lo()) <= bc.clone() && bc <= big(c.hi()), "{c:?}");
            prop_assert!(s.width() < 4e-15 && c.width() < 4e-15, "{s:?} {c:?}");
            let libm = (2.0 * std::f64::consts::PI * x).sin();
            prop_assert!((libm - s.mid()).abs() < 1e-14 * (1.0 + x.abs()));
            let wide = Interval::new(x, x + w).unwrap();
            let y = (x + frac * w).min(wide.hi());
            let (s, c) = wide.sin_cos_2pi();
            let (bs, bc) = (two_pi * big(y)).sin_cos();
            prop_assert!(big(s.lo()) <= bs.clone() && bs <= big(s.hi()));
            prop_assert!(big(c.lo()) <= bc.clone() && bc <= big(c.hi()));
        }

        /// A decimal's enclosure contains its exact value (read in base ten at 400
        /// bits) and the double it parses to.
        #[test]
        fn decimals_are_enclosed(m in 0u64..10_000_000_000, e in -30i32..10) {
            let text = format!("{m}e{e}");
            let i = Interval::decimal(&text).unwrap();
            let exact = Big::from_decimal(&text, &BITS).unwrap();
            prop_assert!(big(i.lo()) <= exact.clone() && exact <= big(i.hi()));
            prop_assert!(i.contains(text.parse::<f64>().unwrap()));
        }
    }

    #[test]
    fn exact_decimals_are_thin_and_others_two_ulps() {
        for t in ["0.5", "2", "0.375", "-1.25e2", "1e22", "0.0", "3.0"] {
            let i = Interval::decimal(t).unwrap();
            assert_eq!(i.lo(), i.hi(), "{t}");
        }
        for t in ["0.6", "0.1", "1e23", "0.8"] {
            let i = Interval::decimal(t).unwrap();
            assert!(
                i.lo() < i.hi() && i.hi() == i.lo().next_up().next_up(),
                "{t} {i:?}"
            );
        }
        // 0.6 typed: both three fifths and the double nearest it.
        let w = Interval::written(0.6);
        let five = Interval::point(5.0);
        assert!((w * five).contains(3.0) && w.contains(0.6));
    }

    #[test]
    fn pi_is_enclosed_and_zero_divisors_give_everything() {
        let pi = Big::pi(&BITS);
        let i = Interval::pi();
        assert!(big(i.lo()) < pi && pi < big(i.hi()));
        let x = Interval::point(1.0) / Interval::new(-1.0, 1.0).unwrap();
        assert_eq!(x, Interval::ENTIRE);
        assert_eq!(
            Interval::new(-2.0, 3.0).unwrap().sqr(),
            Interval::new(0.0, 9.0).unwrap()
        );
    }
}
