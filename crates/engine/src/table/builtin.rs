//! The built-in tables by name: the one list that every front end parses table names
//! against (`sine`, `quad`, `cubic`, `fd:D`), with what each name needs (a parameter,
//! its range) and the α window in which its (1, 1) orbit lives (where a view of it
//! opens). A new built-in shape is one more [`Family`] and its entry in [`families`].

use super::{Family, Table};
use crate::error::EngineError;
use std::fmt;
use std::sync::Arc;

/// Every built-in family, in the order front ends list them.
pub fn families() -> [&'static Arc<Family>; 2] {
    [Family::sine(), Family::fd()]
}

/// Other names of members of a family: (name, family, parameter).
const ALIASES: [(&str, &str, f64); 2] = [("quad", "fd", 0.0), ("cubic", "fd", 1.0)];

/// The valid names, as refusals state them.
pub const NAMES: &str = "sine, quad, cubic, fd:D with D in [0, 1]";

/// A built-in table by name: its family and, for a family with one, the parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Builtin {
    family: &'static Arc<Family>,
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
        let family = families().into_iter().find(|f| f.name() == name)?;
        Some(match (family.params().first(), arg) {
            (None, None) => Ok(Builtin {
                family,
                value: None,
            }),
            (None, Some(_)) => Err(format!("'{s}': {name} takes no parameter")),
            (Some(p), None) => Err(format!(
                "'{s}': {name} needs its parameter: valid {name}:{} with {} in {}",
                p.name(),
                p.name(),
                p.range_text()
            )),
            (Some(p), Some(a)) => match a.parse::<f64>() {
                Err(_) => Err(format!(
                    "'{s}': {} is not a number: valid {name}:{} with {} in {}",
                    p.name(),
                    p.name(),
                    p.name(),
                    p.range_text()
                )),
                Ok(x) => p.check(x).map_err(|e| e.to_string()).map(|x| Builtin {
                    family,
                    value: Some(x),
                }),
            },
        })
    }

    /// The member `value` (None for a family without a parameter) of the family `name`.
    ///
    /// # Panics
    /// If no family has that name (a programming error: names are this module's).
    pub fn of(name: &str, value: Option<f64>) -> Builtin {
        let family = families()
            .into_iter()
            .find(|f| f.name() == name)
            .expect("a built-in family");
        Builtin { family, value }
    }

    /// F_D with this D.
    pub fn fd(d: f64) -> Builtin {
        Builtin::of("fd", Some(d))
    }

    /// The table.
    pub fn table(&self) -> Result<Table, EngineError> {
        let values: Vec<f64> = self.value.into_iter().collect();
        Family::member(self.family, &values)
    }

    /// The family.
    pub fn family(&self) -> &'static Arc<Family> {
        self.family
    }

    /// The parameter (F_D's D), if the family has one.
    pub fn value(&self) -> Option<f64> {
        self.value
    }

    /// D, for a member of the F_D family.
    pub fn d(&self) -> Option<f64> {
        self.value
            .filter(|_| Arc::ptr_eq(self.family, Family::fd()))
    }
}

impl fmt::Display for Builtin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let values: Vec<f64> = self.value.into_iter().collect();
        f.write_str(&self.family.member_name(&values))
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
