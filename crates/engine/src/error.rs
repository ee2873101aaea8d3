//! The engine's error type. Messages are one line and name the offending value and the
//! valid range, so the binary can print them as they are.

use std::borrow::Cow;
use thiserror::Error;

/// Everything the engine can refuse.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EngineError {
    /// A numeric parameter outside its valid range.
    #[error("{name} = {value} is out of range: valid {range}")]
    InvalidParameter {
        /// The parameter (`alpha`, `r`, `k`, a table family's parameter ...).
        name: Cow<'static, str>,
        /// The value given, as messages print it.
        value: String,
        /// The valid range, as refusals state it.
        range: Cow<'static, str>,
    },
    /// A piecewise table that cannot be used (not C¹, bad pieces, too large).
    #[error("{0}")]
    InvalidTable(String),
    /// An initial state from which the ball would move into the table.
    #[error("initial state below the table: {0}")]
    BelowTable(String),
    /// A combination of settings that does not make sense together.
    #[error("{0}")]
    Inconsistent(String),
}

/// A number as messages print it: the shortest decimal that reads back to the same f64,
/// in exponent form for magnitudes from 10¹⁶ and below 10⁻⁵ (1e300, not three hundred
/// digits).
pub fn fmt_value(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-5..1e16).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// At most 40 characters of a user's text, for messages (`…` marks a cut).
pub fn short_text(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() <= MAX {
        text.to_string()
    } else {
        let head: String = text.chars().take(MAX - 1).collect();
        format!("{head}…")
    }
}

#[cfg(test)]
mod tests {
    use super::fmt_value;

    #[test]
    fn values_print_in_the_shorter_exact_form() {
        assert_eq!(fmt_value(0.45), "0.45");
        assert_eq!(fmt_value(1e300), "1e300");
        assert_eq!(fmt_value(1e-300), "1e-300");
        assert_eq!(fmt_value(-2.5), "-2.5");
        assert_eq!(fmt_value(123456.0), "123456");
        assert_eq!(fmt_value(2000.0), "2000");
        assert_eq!(fmt_value(2e-7), "2e-7");
        assert_eq!(fmt_value(1.5e-7).parse::<f64>().unwrap(), 1.5e-7);
    }
}
