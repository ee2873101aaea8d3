//! `--table`: the one parser of table names (`sine | quad | cubic | fd:D | PATH.toml`,
//! a file's parameters set as `PATH.toml:w=0.3,h=0.1`) and of table files, for the
//! command line, the config file, presets and the terminal application alike.
//!
//! A table file (a family when it declares parameters):
//! ```toml
//! name = "my table"                # optional; shown in outputs (control characters escaped)
//! variable = "t"                   # coefficients in powers of the phase t̂ (default), or
//!                                  # "s": of s = t̂ − start, the piece's own variable
//! [[param]]                        # optional, up to 8: a parameter of the family
//! name = "w"                       # a letter, then letters, digits or _ (not alpha, r, k)
//! default = 0.5
//! range = [0.2, 0.8]               # closed; the table must be C¹ at every value used
//! [[piece]]
//! start = 0.0                      # phase where the piece starts; the first must be 0
//! coeffs = [0.0, 0.5, -1.0]        # ascending powers; numbers, or expressions in the
//! [[piece]]                        # parameters: "1 - w/2", "(w - 1)^2 / 4"
//! start = "w"
//! coeffs = [0.5, -1.5, 1.0]
//! ```

use super::files::{read_text, SMALL_FILE};
use super::InputError;
pub use crate::output::text::escape;
use bouncemap_engine::table::builtin::{self, Builtin};
use bouncemap_engine::table::{Family, Param, Variable};
use bouncemap_engine::Table;
use serde::Deserialize;
use std::fmt;
use std::path::Path;
use std::sync::Arc;

/// What a `--table` argument names, before any file is read.
#[derive(Clone, Debug, PartialEq)]
pub enum TableSpec {
    /// A built-in table (the engine's list: sine, F_D, ...).
    Builtin(Builtin),
    /// A table file, with values for some of its parameters.
    File(FileSpec),
}

/// A table file and the values given for its parameters (the others at their defaults).
#[derive(Clone, Debug, PartialEq)]
pub struct FileSpec {
    /// The file's path.
    pub path: String,
    /// (name, value) as given after the path, in order.
    pub set: Vec<(String, f64)>,
}

/// The valid table names, as refusals state them.
pub fn table_range() -> String {
    format!(
        "{}, or a file PATH.toml (its parameters set as PATH.toml:NAME=VALUE,...)",
        builtin::NAMES
    )
}

impl TableSpec {
    /// Parse a built-in name (`sine | quad | cubic | fd:D`) or `PATH.toml`, optionally
    /// followed by `:NAME=VALUE,...`.
    pub fn parse(text: &str) -> Result<TableSpec, String> {
        let s = text.trim();
        if let Some(b) = Builtin::parse(s) {
            return b.map(TableSpec::Builtin);
        }
        if s.ends_with(".toml") {
            return Ok(TableSpec::File(FileSpec {
                path: s.to_string(),
                set: Vec::new(),
            }));
        }
        if let Some(i) = s.find(".toml:") {
            let (path, rest) = (&s[..i + 5], &s[i + 6..]);
            let mut set = Vec::new();
            for part in rest.split(',') {
                let bad = |m: &str| {
                    format!(
                        "table {}: {m}: valid PATH.toml:NAME=VALUE,... with each NAME a parameter the file declares",
                        crate::output::text::quoted(s)
                    )
                };
                let (name, value) = part
                    .split_once('=')
                    .ok_or_else(|| bad(&format!("'{}' is not NAME=VALUE", escape(part))))?;
                let v = value.trim().parse::<f64>().ok().filter(|v| v.is_finite());
                let v = v.ok_or_else(|| {
                    bad(&format!(
                        "the value of '{}' is not a number",
                        escape(name.trim())
                    ))
                })?;
                set.push((name.trim().to_string(), v));
            }
            return Ok(TableSpec::File(FileSpec {
                path: path.to_string(),
                set,
            }));
        }
        Err(format!(
            "unknown table {}: valid {}",
            crate::output::text::quoted(s),
            table_range()
        ))
    }

    /// The texts given for the table's parameters in `text` (name, text): `fd:D`'s D as
    /// typed, a file's `NAME=VALUE`s; none for a name that is not valid (its refusal is
    /// [`TableSpec::parse`]'s) or sets nothing.
    pub fn parameter_texts(text: &str) -> Vec<(String, String)> {
        let s = text.trim();
        match TableSpec::parse(s) {
            Ok(TableSpec::Builtin(b)) => {
                let param = b.family().params().first().map(|p| p.name().to_string());
                match (param, s.split_once(':')) {
                    (Some(name), Some((_, arg))) => vec![(name, arg.trim().to_string())],
                    _ => Vec::new(),
                }
            }
            Ok(TableSpec::File(_)) => s
                .find(".toml:")
                .map(|i| {
                    s[i + 6..]
                        .split(',')
                        .filter_map(|part| part.split_once('='))
                        .map(|(n, v)| (n.trim().to_string(), v.trim().to_string()))
                        .collect()
                })
                .unwrap_or_default(),
            Err(_) => Vec::new(),
        }
    }

    /// F_D with this D.
    pub fn fd(d: f64) -> TableSpec {
        TableSpec::Builtin(Builtin::fd(d))
    }

    /// The table, reading the file if one is named.
    pub fn load(&self) -> Result<Table, InputError> {
        match self {
            TableSpec::Builtin(b) => Ok(b.table()?),
            TableSpec::File(f) => {
                let text = read_text(Path::new(&f.path), "table file", SMALL_FILE)
                    .map_err(|e| InputError(format!("--table: {e}")))?;
                let family = parse_family_file(&text, &f.path)
                    .map_err(|e| InputError(format!("--table: {e}")))?;
                member(&family, &f.set).map_err(|e| InputError(format!("--table {self}: {e}")))
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

    /// Whether the name itself gives a value to the parameter `name` (`fd:0.3` gives
    /// D, `a.toml:w=0.2` gives w), which an axis over that parameter would override.
    pub fn sets(&self, name: &str) -> bool {
        match self {
            TableSpec::Builtin(b) => b
                .family()
                .param_index(name)
                .is_some_and(|_| b.value().is_some()),
            TableSpec::File(f) => f.set.iter().any(|(n, _)| n.eq_ignore_ascii_case(name)),
        }
    }

    /// The same table with parameter `name` given the value `x` (`fd:x` for F_D's D;
    /// a file's list of values updated).
    pub fn with_value(&self, name: &str, x: f64) -> TableSpec {
        match self {
            TableSpec::Builtin(b) => TableSpec::Builtin(Builtin::of(b.family().name(), Some(x))),
            TableSpec::File(f) => {
                let mut set = f.set.clone();
                match set.iter_mut().find(|(n, _)| n.eq_ignore_ascii_case(name)) {
                    Some(entry) => entry.1 = x,
                    None => set.push((name.to_string(), x)),
                }
                TableSpec::File(FileSpec {
                    path: f.path.clone(),
                    set,
                })
            }
        }
    }

    /// The α window where the table's (1, 1) orbit and what follows it lie (a built-in
    /// family's own; for a file, F_D's).
    pub fn alpha_window(&self) -> (f64, f64) {
        let fd = Family::fd().alpha_window().expect("F_D has its window");
        match self {
            TableSpec::Builtin(b) => b.family().alpha_window().unwrap_or(fd),
            // A file opens where the paper's tables do.
            TableSpec::File(_) => fd,
        }
    }
}

impl fmt::Display for TableSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableSpec::Builtin(b) => write!(f, "{b}"),
            TableSpec::File(spec) => {
                f.write_str(&spec.path)?;
                for (i, (n, v)) in spec.set.iter().enumerate() {
                    let sep = if i == 0 { ':' } else { ',' };
                    write!(f, "{sep}{n}={}", bouncemap_engine::fmt_value(*v))?;
                }
                Ok(())
            }
        }
    }
}

/// The member of `family` with the values `set` (by name) and the defaults elsewhere.
pub fn member(family: &Arc<Family>, set: &[(String, f64)]) -> Result<Table, String> {
    let mut values = family.defaults();
    for (name, v) in set {
        let i = family.param_index(name).ok_or_else(|| {
            format!(
                "the table has no parameter '{}': its parameters are {}",
                escape(name),
                family.param_names()
            )
        })?;
        values[i] = *v;
    }
    Family::member(family, &values).map_err(|e| e.to_string())
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    name: Option<String>,
    #[allow(dead_code)]
    description: Option<String>,
    variable: Option<String>,
    #[serde(default)]
    param: Vec<ParamFile>,
    piece: Vec<PieceFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ParamFile {
    name: String,
    default: f64,
    range: [f64; 2],
    #[allow(dead_code)]
    description: Option<String>,
}

/// A number, or an expression in the parameters.
#[derive(Deserialize)]
#[serde(untagged)]
enum Value {
    Int(i64),
    Number(f64),
    Text(String),
}

impl Value {
    /// The expression text: a number as the shortest decimal that reads back to it.
    fn text(&self) -> String {
        match self {
            Value::Int(i) => i.to_string(),
            Value::Number(x) => format!("{x:?}"),
            Value::Text(t) => t.clone(),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PieceFile {
    start: Value,
    coeffs: Vec<Value>,
}

/// The family a table file describes (without parameters, a family of one member);
/// `origin` names the file in refusals and is the family's name unless the file gives
/// one.
pub fn parse_family_file(text: &str, origin: &str) -> Result<Arc<Family>, String> {
    let bad = |msg: String| format!("table file {origin}: {msg}");
    let file: TableFile =
        toml::from_str(text).map_err(|e| bad(e.message().replace('\n', " ").trim().to_string()))?;
    let variable = match file.variable.as_deref().map(str::trim) {
        None | Some("t") => Variable::Phase,
        Some("s") => Variable::Local,
        Some(other) => {
            return Err(bad(format!(
                "variable = {}: valid \"t\" (powers of the phase t̂) or \"s\" (of s = t̂ − start)",
                crate::output::text::quoted(other)
            )))
        }
    };
    let params = file
        .param
        .iter()
        .map(|p| Param::new(p.name.trim(), p.default, p.range[0], p.range[1]))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| bad(e.to_string()))?;
    let pieces: Vec<(String, Vec<String>)> = file
        .piece
        .iter()
        .map(|p| (p.start.text(), p.coeffs.iter().map(Value::text).collect()))
        .collect();
    let name = escape(file.name.as_deref().unwrap_or(origin));
    Family::piecewise(&name, params, variable, &pieces)
        .map(Arc::new)
        .map_err(|e| bad(e.to_string()))
}

/// The table a table file describes, its parameters at their defaults.
pub fn parse_table_file(text: &str, origin: &str) -> Result<Table, String> {
    let family = parse_family_file(text, origin)?;
    member(&family, &[]).map_err(|e| format!("table file {origin}: {e}"))
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
        let file = |path: &str, set: &[(&str, f64)]| {
            TableSpec::File(FileSpec {
                path: path.into(),
                set: set.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
            })
        };
        assert_eq!(TableSpec::parse("a/b.toml"), Ok(file("a/b.toml", &[])));
        let w = TableSpec::parse("a.toml:w=0.25, h = 1e-3").unwrap();
        assert_eq!(w, file("a.toml", &[("w", 0.25), ("h", 1e-3)]));
        assert_eq!(w.to_string(), "a.toml:w=0.25,h=0.001");
        assert!(w.sets("W") && !w.sets("x"));
        assert!(TableSpec::fd(0.1).sets("D"));
        assert!(TableSpec::parse("a.toml:w")
            .unwrap_err()
            .contains("not NAME=VALUE"));
        assert!(TableSpec::parse("a.toml:w=x")
            .unwrap_err()
            .contains("not a number"));
        assert_eq!(TableSpec::fd(0.1).to_string(), "fd:0.1");
    }

    /// The texts a run at any precision reads the table's parameters from: every digit
    /// typed, none for a table without parameters set or a name that is refused.
    #[test]
    fn parameter_texts_are_the_digits_typed() {
        let pairs = |t: &str| TableSpec::parameter_texts(t);
        let one = |n: &str, v: &str| vec![(n.to_string(), v.to_string())];
        assert_eq!(
            pairs(" fd: 0.100000000000000000001 "),
            one("D", "0.100000000000000000001")
        );
        assert_eq!(pairs("cubic"), Vec::new());
        assert_eq!(pairs("sine"), Vec::new());
        assert_eq!(pairs("fd:2"), Vec::new());
        assert_eq!(
            pairs("a.toml:w=0.25000000000000000001, h = 1e-3"),
            vec![
                ("w".to_string(), "0.25000000000000000001".to_string()),
                ("h".to_string(), "1e-3".to_string())
            ]
        );
        assert_eq!(pairs("a.toml"), Vec::new());
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
