//! Every range the engine accepts, in one place: the bounds that are checked and the
//! text that names them in refusals. The binary's parameter rules (command line, config
//! file, presets and the terminal application's editor) take their ranges from here, so
//! a range is stated once and every refusal quotes the same text.

use crate::error::EngineError;

/// A closed, open or half-open interval of accepted values, optionally whole numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The name used in refusals (`alpha`, `r`, `k`, ...).
    pub name: &'static str,
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// Whether the lower end is excluded.
    pub lo_open: bool,
    /// Whether the upper end is excluded.
    pub hi_open: bool,
    /// Only whole numbers are accepted.
    pub whole: bool,
    /// How refusals state the range, e.g. `(0, 1000]`.
    pub text: &'static str,
}

impl Limit {
    /// Whether `x` is accepted.
    pub fn contains(&self, x: f64) -> bool {
        x.is_finite()
            && (if self.lo_open {
                x > self.lo
            } else {
                x >= self.lo
            })
            && (if self.hi_open {
                x < self.hi
            } else {
                x <= self.hi
            })
            && (!self.whole || x.fract() == 0.0)
    }

    /// `x` if accepted, else the refusal naming the value and the range.
    pub fn check(&self, x: f64) -> Result<f64, EngineError> {
        if self.contains(x) {
            Ok(x)
        } else {
            Err(self.refuse(x))
        }
    }

    /// The refusal of `x`.
    pub fn refuse(&self, x: f64) -> EngineError {
        EngineError::InvalidParameter {
            name: self.name.into(),
            value: crate::error::fmt_value(x),
            range: self.text.into(),
        }
    }
}

const fn open_closed(name: &'static str, lo: f64, hi: f64, text: &'static str) -> Limit {
    Limit {
        name,
        lo,
        hi,
        lo_open: true,
        hi_open: false,
        whole: false,
        text,
    }
}

const fn whole(name: &'static str, lo: f64, hi: f64, text: &'static str) -> Limit {
    Limit {
        name,
        lo,
        hi,
        lo_open: false,
        hi_open: false,
        whole: true,
        text,
    }
}

/// Amplitude α of the table, f = α F. Above 1000 flights span so many periods that the
/// f64 height of the ball loses the precision the solver promises.
pub const ALPHA: Limit = open_closed("alpha", 0.0, 1000.0, "(0, 1000]");
/// The largest table the solver's guarantees are established for is the sine at
/// α = 1000: every flight then stays far inside the range where (period, phase) keeps
/// its precision and the work bounds hold. Any table, at any α, is held to the sine's
/// extremes there: α·max|F| ≤ [`MAX_DISPLACEMENT`], α·max|F'| ≤ [`MAX_VELOCITY`],
/// α·max|F''| ≤ [`MAX_ACCELERATION`].
pub const MAX_DISPLACEMENT: f64 = 1000.0;
/// See [`MAX_DISPLACEMENT`] (the sine at α = 1000: 2π·1000 = 6283.2).
pub const MAX_VELOCITY: f64 = 6300.0;
/// See [`MAX_DISPLACEMENT`] (the sine at α = 1000: 4π²·1000 = 39478.4).
pub const MAX_ACCELERATION: f64 = 40_000.0;

/// Coefficient of restitution r.
pub const R: Limit = Limit {
    name: "r",
    lo: 0.0,
    hi: 1.0,
    lo_open: true,
    hi_open: true,
    whole: false,
    text: "(0, 1) (open interval)",
};
/// Initial conditions per value of a sweep (`SweepSpec::starts`).
pub const STARTS: Limit = whole("starts", 1.0, 1000.0, "a whole number in [1, 1000]");
/// Impacts over which an unsettled orbit's exponents are measured.
pub const IMPACTS: Limit = whole("impacts", 1.0, 1e10, "a whole number in [1, 1e10]");
/// D of the scaling laws (the (2, 2k) branch needs f''' ≠ 0, so D > 0).
pub const SCALING_D: Limit = open_closed("D", 0.0, 1.0, "(0, 1]");
/// D of the paper's F_D.
pub const D: Limit = Limit {
    name: "D",
    lo: 0.0,
    hi: 1.0,
    lo_open: false,
    hi_open: false,
    whole: false,
    text: "[0, 1]",
};
/// An initial phase t̂0.
pub const PHASE: Limit = Limit {
    name: "t0",
    lo: 0.0,
    hi: 1.0,
    lo_open: false,
    hi_open: true,
    whole: false,
    text: "a phase in [0, 1)",
};
/// Largest relative velocity |v0 − f'(t0)| and initial height accepted for a start.
pub const MAX_INITIAL: f64 = 1e3;
/// An initial velocity v0 (a start, or a guess at a cycle's launch): at most
/// [`MAX_INITIAL`] beyond the fastest table accepted ([`MAX_VELOCITY`]); a start is
/// further held to |v0 − f'(t0)| ≤ [`MAX_INITIAL`].
pub const VELOCITY: Limit = Limit {
    name: "v0",
    lo: -(MAX_VELOCITY + MAX_INITIAL),
    hi: MAX_VELOCITY + MAX_INITIAL,
    lo_open: false,
    hi_open: false,
    whole: false,
    text: "a velocity in [-7300, 7300]",
};
/// The top W of a box of starts' launch velocities w0 = v0 − f'(t̂0) ∈ [0, W] (basins,
/// the extra starts of a sweep): a start's relative velocity is at most
/// [`MAX_INITIAL`]. The default W ([`crate::attractors::default_w_max`]) is clamped into
/// it.
pub const W_MAX: Limit = Limit {
    name: "w-max",
    lo: 0.0,
    hi: MAX_INITIAL,
    lo_open: true,
    hi_open: false,
    whole: false,
    text: "(0, 1000] (launch velocity relative to the table)",
};
/// The initial height above the table.
pub const HEIGHT: Limit = Limit {
    name: "z0",
    lo: 0.0,
    hi: MAX_INITIAL,
    lo_open: false,
    hi_open: false,
    whole: false,
    text: "[0, 1000] (height above the table)",
};
/// k of the (1, k) and (2, 2k) solutions.
pub const K: Limit = whole("k", 1.0, 100.0, "a whole number in [1, 100]");
/// Values in one sweep.
pub const STEPS: Limit = whole("steps", 1.0, 1e7, "a whole number in [1, 10000000]");
/// α values of a continuation of attractors (each a basin picture).
pub const ATTRACTOR_STEPS: Limit = whole("steps", 1.0, 1e5, "a whole number in [1, 100000]");
/// Sampled starts of the uncertainty exponent (0: none, the grid's neighbours).
pub const UNCERTAINTY_STARTS: Limit = whole(
    "uncertainty-starts",
    0.0,
    1e5,
    "a whole number in [0, 100000]",
);
/// End of a sweep's transient, in table periods.
pub const TRANSIENT: Limit = whole(
    "transient",
    1.0,
    1e12,
    "a whole number of periods in [1, 1e12] (e.g. 5e6)",
);
/// Events recorded per value of a sweep.
pub const KEEP: Limit = whole("keep", 1.0, 1e6, "a whole number in [1, 1000000]");
/// Longest cycle, in events, the early stop detects.
pub const MAX_PERIOD: Limit = whole("max-period", 1.0, 4096.0, "a whole number in [1, 4096]");
/// Agreement promised by the early stop.
/// Period doublings a cascade looks for (each doubles the cycle: 2¹² impacts at most).
pub const CASCADE_DEPTH: Limit = whole("depth", 1.0, 12.0, "a whole number in [1, 12]");
/// Values of the second parameter the two-parameter curves are seeded at.
pub const CURVE_SEEDS: Limit = whole("seeds", 1.0, 64.0, "a whole number in [1, 64]");
/// Impacts per cycle of a continued orbit.
pub const CYCLE_N: Limit = whole("n", 1.0, 1024.0, "a whole number in [1, 1024]");
/// Impacts of a cycle a proof takes (its equations are 2n × 2n, solved densely).
pub const CERTIFY_N: Limit = whole("n", 1.0, 64.0, "a whole number in [1, 64]");
/// Arc length of each branch of a manifold, in the metric of (t, v).
pub const MANIFOLD_LENGTH: Limit = open_closed("length", 0.0, 1000.0, "(0, 1000]");
/// Number of D values of a cascade over the F_D family.
pub const D_COUNT: Limit = whole("d count", 1.0, 1000.0, "a whole number in [1, 1000]");
/// Significant decimal digits of a computation at any precision (`--digits`,
/// `--max-digits`): beyond double precision, up to what takes seconds per thousand
/// events.
pub const DIGITS: Limit = whole("digits", 10.0, 10000.0, "a whole number in [10, 10000]");
/// Phase and velocity tolerance of cycle detection.
pub const TOLERANCE: Limit = open_closed("tolerance", 0.0, 1e-3, "(0, 1e-3]");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_and_openness_are_honoured() {
        assert!(!ALPHA.contains(0.0) && ALPHA.contains(1000.0) && !ALPHA.contains(1000.5));
        assert!(!R.contains(0.0) && !R.contains(1.0) && R.contains(0.5));
        assert!(D.contains(0.0) && D.contains(1.0));
        assert!(PHASE.contains(0.0) && !PHASE.contains(1.0));
        assert!(K.contains(3.0) && !K.contains(2.5) && !K.contains(101.0));
        assert!(!ALPHA.contains(f64::NAN) && !ALPHA.contains(f64::INFINITY));
        let e = ALPHA.check(1e300).unwrap_err().to_string();
        assert_eq!(e, "alpha = 1e300 is out of range: valid (0, 1000]");
    }
}
