//! The engine's error type. Messages are one line and name the offending value and the
//! valid range, so the binary can print them as they are.

use thiserror::Error;

/// Everything the engine can refuse.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EngineError {
    /// A numeric parameter outside its valid range.
    #[error("{name} = {value} is out of range: valid {range}")]
    InvalidParameter {
        name: &'static str,
        value: String,
        range: &'static str,
    },
    /// A `--table` name that is none of the known ones.
    #[error(
        "unknown table '{0}': valid sine, quad, cubic, fd:D with D in [0, 1], or a file PATH.toml"
    )]
    UnknownTable(String),
    /// A table file that cannot be used.
    #[error("table file {file}: {message}")]
    TableFile { file: String, message: String },
    /// An initial state from which the ball would move into the table.
    #[error("initial state below the table: {0}")]
    BelowTable(String),
}
