//! `--table`: the one parser of table names (`sine | quad | cubic | fd:D | PATH.toml`)
//! and of table files, for the command line, the config file, presets and the terminal
//! application alike.
//!
//! A table file:
//! ```toml
//! name = "my table"                # optional; shown in outputs (control characters escaped)
//! [[piece]]
//! start = 0.0                      # phase where the piece starts; the first must be 0
//! coeffs = [0.0, 0.5, -1.0]        # ascending powers of the phase t̂
//! [[piece]]
//! start = 0.5
//! coeffs = [0.5, -1.5, 1.0]
//! ```

use super::files::{read_text, SMALL_FILE};
use super::InputError;
pub use crate::output::text::escape;
use bouncemap_engine::table::builtin::{self, Builtin};
use bouncemap_engine::Table;
use serde::Deserialize;
use std::fmt;
use std::path::Path;

/// What a `--table` argument names, before any file is read.
#[derive(Clone, Debug, PartialEq)]
pub enum TableSpec {
    /// A built-in table (the engine's list: sine, F_D, ...).
    Builtin(Builtin),
    /// A table file.
    File(String),
}

/// The valid table names, as refusals state them.
pub fn table_range() -> String {
    format!("{}, or a file PATH.toml", builtin::NAMES)
}

impl TableSpec {
    /// Parse a built-in name (`sine | quad | cubic | fd:D`) or `PATH.toml`.
    pub fn parse(text: &str) -> Result<TableSpec, String> {
        let s = text.trim();
        if let Some(b) = Builtin::parse(s) {
            return b.map(TableSpec::Builtin);
        }
        if s.ends_with(".toml") {
            return Ok(TableSpec::File(s.to_string()));
        }
        Err(format!(
            "unknown table {}: valid {}",
            crate::output::text::quoted(s),
            table_range()
        ))
    }

    /// F_D with this D.
    pub fn fd(d: f64) -> TableSpec {
        TableSpec::Builtin(Builtin::fd(d))
    }

    /// The table, reading the file if one is named.
    pub fn load(&self) -> Result<Table, InputError> {
        match self {
            TableSpec::Builtin(b) => Ok(b.table()?),
            TableSpec::File(path) => {
                let text = read_text(Path::new(path), "table file", SMALL_FILE)
                    .map_err(|e| InputError(format!("--table: {e}")))?;
                parse_table_file(&text, path).map_err(|e| InputError(format!("--table: {e}")))
            }
        }
    }

    /// D, if this is an F_D table.
    pub fn d(&self) -> Option<f64> {
        match self {
            TableSpec::Builtin(b) => b.d(),
            TableSpec::File(_) => None,
        }
    }

    /// The α window where the table's (1, 1) orbit and what follows it lie (a built-in
    /// family's own; for a file, F_D's).
    pub fn alpha_window(&self) -> (f64, f64) {
        match self {
            TableSpec::Builtin(b) => b.family().alpha_window,
            // A file opens where the paper's tables do.
            TableSpec::File(_) => Builtin::fd(0.0).family().alpha_window,
        }
    }
}

impl fmt::Display for TableSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableSpec::Builtin(b) => write!(f, "{b}"),
            TableSpec::File(p) => f.write_str(p),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    name: Option<String>,
    #[allow(dead_code)]
    description: Option<String>,
    piece: Vec<PieceFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PieceFile {
    start: f64,
    coeffs: Vec<f64>,
}

/// A table from the text of a table file; `origin` names the file in refusals and is
/// the table's name unless the file gives one.
pub fn parse_table_file(text: &str, origin: &str) -> Result<Table, String> {
    let bad = |msg: String| format!("table file {origin}: {msg}");
    let file: TableFile =
        toml::from_str(text).map_err(|e| bad(e.message().replace('\n', " ").trim().to_string()))?;
    let pieces: Vec<(f64, Vec<f64>)> = file
        .piece
        .into_iter()
        .map(|p| (p.start, p.coeffs))
        .collect();
    let name = escape(file.name.as_deref().unwrap_or(origin));
    Table::piecewise(&name, &pieces).map_err(|e| bad(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_to_one_spec_each() {
        assert_eq!(
            TableSpec::parse("sine"),
            Ok(TableSpec::Builtin(Builtin::of("sine", None)))
        );
        assert_eq!(TableSpec::parse("quad"), Ok(TableSpec::fd(0.0)));
        assert_eq!(TableSpec::parse(" cubic "), Ok(TableSpec::fd(1.0)));
        assert_eq!(TableSpec::parse("fd:0.25"), Ok(TableSpec::fd(0.25)));
        assert!(TableSpec::parse("fd:1.5").unwrap_err().contains("[0, 1]"));
        assert!(TableSpec::parse("fd:x")
            .unwrap_err()
            .contains("not a number"));
        assert!(TableSpec::parse("square")
            .unwrap_err()
            .contains("valid sine"));
        assert_eq!(
            TableSpec::parse("a/b.toml"),
            Ok(TableSpec::File("a/b.toml".into()))
        );
        assert_eq!(TableSpec::fd(0.1).to_string(), "fd:0.1");
    }

    #[test]
    fn a_file_name_with_escape_codes_is_escaped() {
        let t = parse_table_file(
            "name = \"x\\u001b[2Jy\\nz\"\n[[piece]]\nstart = 0.0\ncoeffs = [0.0]\n",
            "f.toml",
        )
        .unwrap();
        assert_eq!(t.name(), "x\\u{1b}[2Jy\\nz");
    }

    #[test]
    fn a_kink_is_refused_naming_the_file_and_the_breakpoint() {
        let text = "[[piece]]\nstart = 0.0\ncoeffs = [0.0, 1.0]\n[[piece]]\nstart = 0.5\ncoeffs = [1.0, -1.0]\n";
        let e = parse_table_file(text, "kink.toml").unwrap_err();
        assert!(
            e.starts_with("table file kink.toml: not C¹ at breakpoint t̂ = 0.5"),
            "{e}"
        );
    }
}
