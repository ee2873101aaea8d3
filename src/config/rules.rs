//! The one table of parameter rules: for every number a user can set, its flag and
//! config key, its label in the terminal application, its valid range (from the
//! engine's [`limits`]) and its default. The clap value parsers, the config file, the
//! presets and the terminal application's parameter editor all parse and check through
//! these, so a range or a default is stated once and every refusal reads the same.
//!
//! Refusals from [`Rule::parse`] name the value and the range but not the setting:
//! each front end puts its own name in front (`--alpha`, `defaults.alpha`, `α`).

use crate::output::text::quoted;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::limits::{self, Limit};
use bouncemap_engine::Table;

/// One settable number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rule {
    /// Flag and config-file key.
    pub key: &'static str,
    /// Label in the terminal application.
    pub label: &'static str,
    /// Accepted values.
    pub limit: Limit,
    /// The default where the setting is not given.
    pub default: f64,
}

impl Rule {
    /// Parse typed text: a decimal number (whole numbers may be written as 5e6), then
    /// check it. The one parser of every number a user types: NaN, infinities, numbers
    /// beyond f64, hexadecimal, digit separators and empty text are refused, each with
    /// the valid range; −0 is 0.
    pub fn parse(&self, text: &str) -> Result<f64, String> {
        self.check(number(text, self.limit.whole, self.limit.text)?)
    }

    /// Check a number against the range (−0 is 0).
    pub fn check(&self, x: f64) -> Result<f64, String> {
        let x = if x == 0.0 { 0.0 } else { x };
        if self.limit.contains(x) {
            Ok(x)
        } else {
            Err(format!(
                "{} is out of range: valid {}",
                bouncemap_engine::fmt_value(x),
                self.limit.text
            ))
        }
    }

    /// A flag's help text: `what` it sets, then the valid range as every refusal states
    /// it, so the help and the refusals cannot disagree.
    pub fn help(&self, what: &str) -> String {
        format!("{what}; valid {}.", self.limit.text)
    }

    /// [`Rule::help`] for a setting without a clap default (presets and the config file
    /// may set it), naming the default.
    pub fn help_default(&self, what: &str) -> String {
        format!(
            "{what}; valid {} [default: {}].",
            self.limit.text,
            bouncemap_engine::fmt_value(self.default)
        )
    }

    /// A clap value parser for an f64 setting.
    pub fn real(&'static self) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync {
        move |s| self.parse(s)
    }

    /// A clap value parser for a whole-number setting.
    pub fn whole<T: TryFrom<u64>>(
        &'static self,
    ) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync {
        move |s| {
            let x = self.parse(s)?;
            T::try_from(x as u64)
                .map_err(|_| format!("{} is out of range: valid {}", quoted(s), self.limit.text))
        }
    }
}

/// A decimal number typed as `text` (whole numbers may be written as 5e6), not yet
/// checked against a range: NaN, infinities, numbers beyond f64, hexadecimal, digit
/// separators and empty text are refused, naming the valid `range`.
fn number(text: &str, whole: bool, range: &str) -> Result<f64, String> {
    let t = text.trim();
    let what = if whole { "a whole number" } else { "a number" };
    let decimal = !t.is_empty()
        && t.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E'));
    let x: f64 = t
        .parse()
        .ok()
        .filter(|_| decimal)
        .ok_or_else(|| format!("{} is not {what}: valid {range}", quoted(t)))?;
    if !x.is_finite() {
        return Err(format!("{} is out of range: valid {range}", quoted(t)));
    }
    Ok(if x == 0.0 { 0.0 } else { x })
}

/// A value of `param` over `table` typed as `text`: α and r through their rules, a
/// parameter of the table's family through the one number parser and its declared
/// range. The refusal names the value and the range, not the setting.
pub fn param_value(param: SweepParam, table: &Table, text: &str) -> Result<f64, String> {
    match param {
        SweepParam::Alpha => ALPHA.parse(text),
        SweepParam::R => R.parse(text),
        SweepParam::Table(n) => {
            let p = table.family_param(n.as_str()).map_err(|e| e.to_string())?;
            let x = number(text, false, &p.range_text())?;
            p.check(x).map_err(|e| e.to_string())
        }
    }
}

const fn rule(key: &'static str, label: &'static str, limit: Limit, default: f64) -> Rule {
    Rule {
        key,
        label,
        limit,
        default,
    }
}

/// The table when none is given.
pub const DEFAULT_TABLE: &str = "fd:0.1";
/// Pixels of a plane when none are asked for (`plane --size`, `figure plane --size`,
/// the terminal application's exported plane).
pub const PLANE_SIZE: &str = "400x200";
/// Starts of a basin picture when none are asked for (`basins --grid`, `figure basins
/// --grid`, the terminal application's exported basins).
pub const BASINS_GRID: &str = "200x100";
/// `attractors --grid`'s default.
pub const ATTRACTORS_GRID: &str = "100x100";

/// Amplitude α.
pub const ALPHA: Rule = rule("alpha", "α", limits::ALPHA, 0.45);
/// Restitution r.
pub const R: Rule = rule("r", "r", limits::R, 0.8);
/// D of F_D (the default table is fd:0.1).
pub const D: Rule = rule("d", "D", limits::D, 0.1);
/// k of the (1, k) solution.
pub const K: Rule = rule("k", "k", limits::K, 1.0);
/// Initial phase t̂0.
pub const T0: Rule = rule("t0", "t̂0", limits::PHASE, 0.0);
/// Initial velocity v0 (its default, f'(t0) + 0.5, depends on the table; this one is
/// only for completeness).
pub const V0: Rule = rule("v0", "v0", limits::VELOCITY, 0.5);
/// Initial height above the table.
pub const Z0: Rule = rule("z0", "z0", limits::HEIGHT, 0.0);
/// Values in a sweep (the paper's 1000).
pub const STEPS: Rule = rule("steps", "values", limits::STEPS, 1000.0);
/// Sampled starts of `attractors`' uncertainty exponent.
pub const UNCERTAINTY_STARTS: Rule = rule(
    "uncertainty-starts",
    "sampled starts",
    limits::UNCERTAINTY_STARTS,
    0.0,
);
/// α values of `attractors`.
pub const ATTRACTOR_STEPS: Rule = rule("steps", "α values", limits::ATTRACTOR_STEPS, 101.0);
/// End of a sweep's transient (the paper's T = 5·10⁶).
pub const TRANSIENT: Rule = rule("transient", "transient", limits::TRANSIENT, 5e6);
/// Events recorded per value (the paper's 100).
pub const KEEP: Rule = rule("keep", "keep", limits::KEEP, 100.0);
/// Longest cycle the early stop detects.
pub const MAX_PERIOD: Rule = rule("max-period", "max period", limits::MAX_PERIOD, 64.0);
/// Agreement promised by the early stop.
pub const TOLERANCE: Rule = rule("tolerance", "tolerance", limits::TOLERANCE, 1e-11);
/// End of `lyapunov`'s transient, in table periods.
pub const LYAPUNOV_TRANSIENT: Rule = rule("transient", "transient", limits::TRANSIENT, 1e4);
/// Impacts over which `lyapunov` measures an unsettled orbit.
pub const IMPACTS: Rule = rule("impacts", "impacts", limits::IMPACTS, 1e5);
/// End of each basin start's transient, in table periods.
pub const BASIN_TRANSIENT: Rule = rule("transient", "transient", limits::TRANSIENT, 5e3);
/// End of each pixel's transient of a plane, in table periods.
pub const PLANE_TRANSIENT: Rule = rule(
    "transient",
    "transient",
    limits::TRANSIENT,
    bouncemap_engine::plane::DEFAULT_TRANSIENT as f64,
);
/// Top W of the launch velocities of basins and of sweep starts (the default is
/// computed per system: max(1, 2α·max|F'|), clamped into the range).
pub const W_MAX: Rule = rule("w-max", "W", limits::W_MAX, 1.0);
/// Initial conditions per value of a sweep.
pub const STARTS: Rule = rule("starts", "starts", limits::STARTS, 1.0);
/// Events `orbit` prints.
pub const BOUNCES: Rule = rule("bounces", "bounces", COUNT, 1000.0);
/// Events `orbit` computes first without printing.
pub const SKIP: Rule = rule("skip", "skip", COUNT, 0.0);
/// Worker threads.
pub const THREADS: Rule = rule(
    "threads",
    "threads",
    Limit {
        name: "threads",
        lo: 1.0,
        hi: 4096.0,
        lo_open: false,
        hi_open: false,
        whole: true,
        text: "a whole number in [1, 4096]",
    },
    1.0,
);
/// Frame cap of the terminal application.
pub const FPS: Rule = rule(
    "fps",
    "fps",
    Limit {
        name: "fps",
        lo: 1.0,
        hi: 60.0,
        lo_open: false,
        hi_open: false,
        whole: true,
        text: "a whole number in 1..=60",
    },
    15.0,
);
/// Width or height of a text picture, in characters.
pub const CELLS: Rule = rule(
    "cells",
    "cells",
    Limit {
        name: "cells",
        lo: 10.0,
        hi: 2000.0,
        lo_open: false,
        hi_open: false,
        whole: true,
        text: "a whole number of characters in [10, 2000]",
    },
    100.0,
);
/// Significant digits asked of a run at any precision (`--digits`; no default: without
/// it runs are in f64).
pub const DIGITS: Rule = rule("digits", "digits", limits::DIGITS, 60.0);
/// The most digits a run at any precision raises its precision to (`--max-digits`).
pub const MAX_DIGITS: Rule = rule("max-digits", "max digits", limits::DIGITS, 400.0);
/// Impacts of a cycle `continue` starts on.
pub const CYCLE_N: Rule = rule("n", "n", limits::CYCLE_N, 1.0);
/// Impacts of the cycle `certify` proves.
pub const CERTIFY_N: Rule = rule("n", "n", limits::CERTIFY_N, 1.0);
/// The longest period `continue` starts doubled branches up to.
pub const CONTINUE_MAX_PERIOD: Rule = rule("max-period", "max period", limits::MAX_PERIOD, 16.0);
/// Values of the second parameter `curves` seeds at.
pub const CURVE_SEEDS: Rule = rule("seeds", "seeds", limits::CURVE_SEEDS, 5.0);
/// Arc length of each branch of a manifold.
pub const MANIFOLD_LENGTH: Rule = rule("length", "length", limits::MANIFOLD_LENGTH, 2.0);
/// Period doublings a cascade looks for.
pub const DEPTH: Rule = rule("depth", "depth", limits::CASCADE_DEPTH, 6.0);
/// D values of `cascade --d LO..HI:N`.
pub const D_COUNT: Rule = rule("d count", "D values", limits::D_COUNT, 1.0);
/// D of `scaling` (the (2, 2k) branch needs f''' ≠ 0, so D > 0).
pub const SCALING_D: Rule = rule("d", "D", limits::SCALING_D, 0.1);
/// Points of a log-spaced D range.
pub const D_POINTS: Rule = rule(
    "points",
    "points",
    Limit {
        name: "points",
        lo: 2.0,
        hi: 1000.0,
        lo_open: false,
        hi_open: false,
        whole: true,
        text: "a whole number in [2, 1000]",
    },
    13.0,
);

/// One side of a figure, in inches (`figure --size WxH`).
pub const FIG_SIDE: Rule = rule(
    "size",
    "size",
    Limit {
        name: "size",
        lo: 1.0,
        hi: 12.0,
        lo_open: false,
        hi_open: false,
        whole: false,
        text: "WxH in inches, each side in [1, 12]",
    },
    3.4,
);
/// Pixels per inch of a PNG figure (`figure --dpi`).
pub const DPI: Rule = rule(
    "dpi",
    "dpi",
    Limit {
        name: "dpi",
        lo: 50.0,
        hi: 600.0,
        lo_open: false,
        hi_open: false,
        whole: true,
        text: "a whole number in [50, 600]",
    },
    300.0,
);

/// Seconds between the progress lines of a batch log (`BOUNCEMAP_PROGRESS_EVERY`).
pub const PROGRESS_EVERY: Rule = rule(
    "BOUNCEMAP_PROGRESS_EVERY",
    "progress interval",
    Limit {
        name: "BOUNCEMAP_PROGRESS_EVERY",
        lo: 0.001,
        hi: 86400.0,
        lo_open: false,
        hi_open: false,
        whole: false,
        text: "seconds in [0.001, 86400]",
    },
    30.0,
);

const COUNT: Limit = Limit {
    name: "count",
    lo: 0.0,
    hi: 1e15,
    lo_open: false,
    hi_open: false,
    whole: true,
    text: "a whole number ≥ 0 (at most 1e15)",
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_parsed_and_checked_against_the_engine_ranges() {
        assert_eq!(ALPHA.parse(" 0.5 "), Ok(0.5));
        assert_eq!(
            ALPHA.parse("2000"),
            Err("2000 is out of range: valid (0, 1000]".into())
        );
        assert_eq!(
            ALPHA.parse("1e300"),
            Err("1e300 is out of range: valid (0, 1000]".into())
        );
        assert!(ALPHA
            .parse("abc")
            .unwrap_err()
            .starts_with("'abc' is not a number"));
        // Whole numbers may use exponent notation; fractions are refused.
        assert_eq!(TRANSIENT.parse("1e7"), Ok(1e7));
        // Not numbers, or beyond every range, each refused with the range.
        for bad in [
            "nan", "NaN", "inf", "-inf", "infinity", "", " ", "0x10", "1_000", "1,5", "+",
        ] {
            let e = ALPHA.parse(bad).unwrap_err();
            assert!(e.contains("is not a number: valid (0, 1000]"), "{bad}: {e}");
        }
        for big in ["1e400", "-1e400"] {
            let e = ALPHA.parse(big).unwrap_err();
            assert!(e.contains("is out of range: valid (0, 1000]"), "{big}: {e}");
        }
        let long = "9".repeat(5000);
        let e = ALPHA.parse(&long).unwrap_err();
        assert!(e.len() < 120 && e.contains("(5000 characters)"), "{e}");
        // −0 is 0: refused where 0 is, accepted as +0 where it is.
        assert_eq!(T0.parse("-0").map(f64::to_bits), Ok(0f64.to_bits()));
        assert!(ALPHA
            .parse("-0")
            .unwrap_err()
            .starts_with("0 is out of range"));
        assert!(TRANSIENT.parse("2.5").is_err());
        assert!(K.parse("0").is_err() && K.parse("100").is_ok() && K.parse("101").is_err());
        let whole = TRANSIENT.whole::<u64>();
        assert_eq!(whole("5e6"), Ok(5_000_000));
    }

    #[test]
    fn defaults_lie_in_their_ranges() {
        for r in [
            ALPHA,
            R,
            D,
            K,
            T0,
            V0,
            Z0,
            STEPS,
            TRANSIENT,
            KEEP,
            MAX_PERIOD,
            TOLERANCE,
            BOUNCES,
            SKIP,
            THREADS,
            FPS,
            CELLS,
            SCALING_D,
            CURVE_SEEDS,
            D_POINTS,
            LYAPUNOV_TRANSIENT,
            IMPACTS,
            BASIN_TRANSIENT,
            ATTRACTOR_STEPS,
            UNCERTAINTY_STARTS,
            W_MAX,
            STARTS,
            FIG_SIDE,
            DPI,
            PROGRESS_EVERY,
        ] {
            assert!(r.limit.contains(r.default), "{}", r.key);
        }
    }
}
