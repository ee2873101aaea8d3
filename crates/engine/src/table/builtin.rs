//! The built-in tables by name: the one list that every front end parses table names
//! against (`sine`, `quad`, `cubic`, `fd:D`), with what each name needs (a parameter,
//! its range) and the α window in which its (1, 1) orbit lives (where a view of it
//! opens). A new built-in shape is one more entry here and its constructor in
//! [`Table`].

use super::Table;
use crate::error::EngineError;
use crate::limits;
use std::fmt;

/// One family of built-in tables.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// The name (`sine`), or the prefix before `:` of a family with a parameter (`fd`).
    pub name: &'static str,
    /// The family's parameter (F_D's D), if it has one.
    pub param: Option<limits::Limit>,
    /// The α window where its (1, 1) orbit, its period doublings and the chaos after
    /// them lie at r = 0.8 (the paper's Fig. 3 windows).
    pub alpha_window: (f64, f64),
    build: fn(f64) -> Result<Table, EngineError>,
}

impl PartialEq for Family {
    fn eq(&self, other: &Family) -> bool {
        self.name == other.name
    }
}

/// Every family, in the order front ends list them.
pub const FAMILIES: [Family; 2] = [
    Family {
        name: "sine",
        param: None,
        alpha_window: (0.02, 0.04),
        build: |_| Ok(Table::sine()),
    },
    Family {
        name: "fd",
        param: Some(limits::D),
        alpha_window: (0.45, 0.6),
        build: Table::fd,
    },
];

/// Other names of members of a family: (name, family, parameter).
const ALIASES: [(&str, &str, f64); 2] = [("quad", "fd", 0.0), ("cubic", "fd", 1.0)];

/// The valid names, as refusals state them.
pub const NAMES: &str = "sine, quad, cubic, fd:D with D in [0, 1]";

/// A built-in table by name: its family and, for a family with one, the parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Builtin {
    family: &'static Family,
    value: Option<f64>,
}

impl Builtin {
    /// Parse a name: None if it names no built-in table (it may name a file); a
    /// refusal naming the valid form if it names a family with a bad parameter.
    pub fn parse(text: &str) -> Option<Result<Builtin, String>> {
        let s = text.trim();
        if let Some(&(_, fam, value)) = ALIASES.iter().find(|a| a.0 == s) {
            return Some(Ok(Builtin::of(fam, Some(value))));
        }
        let (name, arg) = match s.split_once(':') {
            Some((n, a)) => (n.trim(), Some(a.trim())),
            None => (s, None),
        };
        let family = FAMILIES.iter().find(|f| f.name == name)?;
        Some(match (family.param, arg) {
            (None, None) => Ok(Builtin {
                family,
                value: None,
            }),
            (None, Some(_)) => Err(format!("'{s}': {name} takes no parameter")),
            (Some(limit), None) => Err(format!(
                "'{s}': {name} needs its parameter: valid {name}:{} with {} in {}",
                limit.name.to_uppercase(),
                limit.name.to_uppercase(),
                limit.text
            )),
            (Some(limit), Some(a)) => {
                let upper = limit.name.to_uppercase();
                match a.parse::<f64>() {
                    Err(_) => Err(format!(
                        "'{s}': {upper} is not a number: valid {name}:{upper} with {upper} in {}",
                        limit.text
                    )),
                    Ok(x) => limit.check(x).map_err(|e| e.to_string()).map(|x| Builtin {
                        family,
                        value: Some(x),
                    }),
                }
            }
        })
    }

    /// The member `value` (None for a family without a parameter) of the family `name`.
    ///
    /// # Panics
    /// If no family has that name (a programming error: names are this module's).
    pub fn of(name: &str, value: Option<f64>) -> Builtin {
        let family = FAMILIES
            .iter()
            .find(|f| f.name == name)
            .expect("a built-in family");
        Builtin { family, value }
    }

    /// F_D with this D.
    pub fn fd(d: f64) -> Builtin {
        Builtin::of("fd", Some(d))
    }

    /// The table.
    pub fn table(&self) -> Result<Table, EngineError> {
        (self.family.build)(self.value.unwrap_or(0.0))
    }

    /// The family.
    pub fn family(&self) -> &'static Family {
        self.family
    }

    /// The parameter (F_D's D), if the family has one.
    pub fn value(&self) -> Option<f64> {
        self.value
    }

    /// D, for a member of the F_D family.
    pub fn d(&self) -> Option<f64> {
        self.value.filter(|_| self.family.name == "fd")
    }
}

impl fmt::Display for Builtin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.value {
            Some(x) => write!(f, "{}:{}", self.family.name, crate::error::fmt_value(x)),
            None => f.write_str(self.family.name),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_to_their_tables() {
        let p = |s: &str| Builtin::parse(s).unwrap().unwrap();
        assert_eq!(p("sine").table().unwrap(), Table::sine());
        assert_eq!(p(" cubic ").table().unwrap(), Table::fd(1.0).unwrap());
        assert_eq!(p("quad"), Builtin::fd(0.0));
        assert_eq!(p("fd:0.25").d(), Some(0.25));
        assert_eq!(p("fd:0.1").to_string(), "fd:0.1");
        assert!(Builtin::parse("a.toml").is_none());
        assert!(Builtin::parse("fd:1.5")
            .unwrap()
            .unwrap_err()
            .contains("[0, 1]"));
        assert!(Builtin::parse("fd:x")
            .unwrap()
            .unwrap_err()
            .contains("not a number"));
        assert!(Builtin::parse("sine:2").unwrap().is_err());
        assert!(Builtin::parse("fd").unwrap().unwrap_err().contains("fd:D"));
    }
}
