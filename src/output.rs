//! Writers for the headless commands: aligned text, CSV and JSON.
//!
//! Floating-point values in csv and json use Rust's shortest round-trip form, so a
//! script reading them gets exactly the f64 the engine computed.

use clap::ValueEnum;
use std::io::{self, Write};

/// Output format of a headless command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// Aligned columns for people.
    #[default]
    Text,
    /// Comma-separated values with a header row.
    Csv,
    /// JSON.
    Json,
}

/// A JSON number, or null for a non-finite value.
pub fn json_num(x: f64) -> serde_json::Value {
    serde_json::Number::from_f64(x).map_or(serde_json::Value::Null, serde_json::Value::Number)
}

/// Write one CSV row of already formatted fields.
pub fn csv_row<W: Write>(out: &mut W, fields: &[String]) -> io::Result<()> {
    writeln!(out, "{}", fields.join(","))
}

/// `x` with `digits` significant digits in fixed notation (scientific beyond 1e15), for
/// aligned text columns that show no digits beyond f64 precision.
pub fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x:.prec$}", prec = digits.saturating_sub(1));
    }
    let mag = x.abs().log10().floor() as i64;
    if mag >= digits as i64 {
        return format!("{x:.prec$e}", prec = digits.saturating_sub(1));
    }
    let decimals = (digits as i64 - 1 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::significant;

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.5, 15), "0.500000000000000");
        assert_eq!(significant(9_780.139_017_934_653, 15), "9780.13901793465");
        assert_eq!(significant(-0.0123, 3), "-0.0123");
        assert_eq!(significant(0.0, 4), "0.000");
    }
}
