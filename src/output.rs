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
