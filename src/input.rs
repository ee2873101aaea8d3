//! Turning command-line words and files into engine values; the only place that reads
//! table files. Every failure is an [`InputError`]: one line naming the flag or file,
//! the value and the valid range, reported with exit status 2.

use crate::engine::{EngineError, Table, TableSpec};
use std::fmt;

/// Bad input from the user (flags, files, keys): exit status 2.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError(pub String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

impl From<EngineError> for InputError {
    fn from(e: EngineError) -> Self {
        InputError(e.to_string())
    }
}

/// Resolve `--table sine | quad | cubic | fd:D | PATH.toml`, reading the file if named.
pub fn load_table(spec: &str) -> Result<Table, InputError> {
    match TableSpec::parse(spec).map_err(|e| InputError(format!("--table: {e}")))? {
        TableSpec::Builtin(t) => Ok(t),
        TableSpec::File(path) => {
            let text = std::fs::read_to_string(&path)
                .map_err(|e| InputError(format!("--table: cannot read table file {path}: {e}")))?;
            Table::from_toml(&text, &path).map_err(|e| InputError(format!("--table: {e}")))
        }
    }
}
