//! Grids of parameter values and how their items are dealt out: the parameters a
//! grid can run over ([`SweepParam`]), evenly spaced values with both ends exact
//! ([`grid_value`], [`Axis`]), the window check, and shards ([`Shard`]: which part of
//! the items one process computes). Below sweeps, planes and every job over a grid.

use crate::error::{fmt_value, EngineError};
use crate::limits;
use crate::system::System;
use crate::table::family::MAX_NAME;
use crate::table::Table;
use std::fmt;

/// The name of a table family's parameter, held inline (so a [`SweepParam`] is `Copy`).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct ParamName {
    bytes: [u8; MAX_NAME],
    len: u8,
}

impl ParamName {
    /// The name `text`; None if it is longer than a parameter name can be or not ASCII
    /// (names are checked where families are made).
    pub const fn new(text: &str) -> Option<ParamName> {
        let b = text.as_bytes();
        if b.len() > MAX_NAME || !text.is_ascii() {
            return None;
        }
        let mut bytes = [0u8; MAX_NAME];
        let mut i = 0;
        while i < b.len() {
            bytes[i] = b[i];
            i += 1;
        }
        Some(ParamName {
            bytes,
            len: b.len() as u8,
        })
    }

    /// The name as text.
    pub fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..self.len as usize]).expect("names are ASCII")
    }
}

impl fmt::Debug for ParamName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

/// A parameter a grid can run over: α, r, or a parameter of the table's family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SweepParam {
    /// The amplitude α.
    Alpha,
    /// The restitution coefficient r.
    R,
    /// A parameter of the table's family, by name (F_D's D, a table file's own).
    Table(ParamName),
}

impl SweepParam {
    /// Where it sits in a system at any precision.
    pub fn slot(&self) -> crate::precise::Slot<'_> {
        match self {
            SweepParam::Alpha => crate::precise::Slot::Alpha,
            SweepParam::R => crate::precise::Slot::R,
            SweepParam::Table(name) => crate::precise::Slot::Table(name.as_str()),
        }
    }

    /// D of the paper's F_D.
    pub const D: SweepParam = match ParamName::new("D") {
        Some(n) => SweepParam::Table(n),
        None => panic!("a valid name"),
    };

    /// The parameter of the system or of `table`'s family called `text` (`alpha` or
    /// `α`, `r`, or a name the family declares; exactly as spelled, else ignoring
    /// case); the refusal lists the valid names.
    pub fn parse(text: &str, table: &Table) -> Result<SweepParam, String> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("alpha") || t == "α" {
            return Ok(SweepParam::Alpha);
        }
        if t.eq_ignore_ascii_case("r") {
            return Ok(SweepParam::R);
        }
        if let Some((fam, _)) = table.family() {
            if let Some(i) = fam.param_index(t) {
                let name = fam.params()[i].name();
                return Ok(SweepParam::Table(
                    ParamName::new(name).expect("family names fit"),
                ));
            }
        }
        Err(format!(
            "unknown parameter '{}': valid {}",
            crate::error::short_text(t),
            SweepParam::names(table)
        ))
    }

    /// The valid names for a table, as refusals state them: `alpha, r, D`.
    pub fn names(table: &Table) -> String {
        let mut v = vec!["alpha".to_string(), "r".to_string()];
        if let Some((fam, _)) = table.family() {
            v.extend(fam.params().iter().map(|p| p.name().to_string()));
        }
        v.join(", ")
    }

    /// Every parameter a grid over `table` can run over: α, r, then the family's.
    pub fn all(table: &Table) -> Vec<SweepParam> {
        let mut v = vec![SweepParam::Alpha, SweepParam::R];
        if let Some((fam, _)) = table.family() {
            v.extend(
                fam.params()
                    .iter()
                    .map(|p| SweepParam::Table(ParamName::new(p.name()).expect("fits"))),
            );
        }
        v
    }

    /// The name used in every output format: `alpha`, `r`, or the parameter's own
    /// name (`D`, `w`).
    pub fn as_str(&self) -> &str {
        match self {
            SweepParam::Alpha => "alpha",
            SweepParam::R => "r",
            SweepParam::Table(n) => n.as_str(),
        }
    }

    /// Whether it is a parameter of the table's family.
    pub fn is_table(&self) -> bool {
        matches!(self, SweepParam::Table(_))
    }

    /// Its valid range over `table` (its ends; α's and r's lower ends are open); None
    /// if the table has no such parameter.
    pub fn range(&self, table: &Table) -> Option<(f64, f64)> {
        match self {
            SweepParam::Alpha => Some((limits::ALPHA.lo, limits::ALPHA.hi)),
            SweepParam::R => Some((limits::R.lo, limits::R.hi)),
            SweepParam::Table(n) => table.family_param(n.as_str()).ok().map(|p| p.range()),
        }
    }

    /// `x` if it is a valid value over `table`, else the refusal naming the range.
    pub fn check(&self, table: &Table, x: f64) -> Result<f64, EngineError> {
        match self {
            SweepParam::Alpha => limits::ALPHA.check(x),
            SweepParam::R => limits::R.check(x),
            SweepParam::Table(n) => table.family_param(n.as_str())?.check(x),
        }
    }

    /// The system with this parameter at `value` and the others at `table`, `alpha`,
    /// `r`: the one place a grid point becomes a system.
    pub fn system(
        &self,
        table: &Table,
        alpha: f64,
        r: f64,
        value: f64,
    ) -> Result<System, EngineError> {
        match self {
            SweepParam::Alpha => System::new(table.clone(), value, r),
            SweepParam::R => System::new(table.clone(), alpha, value),
            SweepParam::Table(n) => System::new(table.with_param(n.as_str(), value)?, alpha, r),
        }
    }

    /// The table with this parameter at `value` (the table itself for α and r).
    pub fn table(&self, table: &Table, value: f64) -> Result<Table, EngineError> {
        match self {
            SweepParam::Table(n) => table.with_param(n.as_str(), value),
            _ => Ok(table.clone()),
        }
    }
}

impl fmt::Display for SweepParam {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Value `i` of `steps` evenly spaced values from `lo` to `hi` (both ends exact): the
/// one rule every grid of parameter values uses.
pub fn grid_value(lo: f64, hi: f64, steps: usize, i: usize) -> f64 {
    if steps <= 1 {
        lo
    } else if i + 1 == steps {
        hi
    } else {
        lo + (hi - lo) * (i as f64) / ((steps - 1) as f64)
    }
}

/// Check a window `lo..=hi` of `param` over `table`: finite, ordered, both ends in the
/// parameter's range.
pub fn check_window(param: SweepParam, table: &Table, lo: f64, hi: f64) -> Result<(), EngineError> {
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return Err(EngineError::InvalidParameter {
            name: param.as_str().to_string().into(),
            value: format!("{}..{}", fmt_value(lo), fmt_value(hi)),
            range: "a window LO..HI with LO ≤ HI".into(),
        });
    }
    param.check(table, lo)?;
    param.check(table, hi)?;
    Ok(())
}

/// One axis of a parameter grid: `n` values of `param` from `lo` to `hi` (both ends
/// exact), e.g. a side of a plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    /// The parameter along the axis.
    pub param: SweepParam,
    /// First value.
    pub lo: f64,
    /// Last value.
    pub hi: f64,
    /// Number of values.
    pub n: usize,
}

impl Axis {
    /// Value `i`.
    pub fn value(&self, i: usize) -> f64 {
        grid_value(self.lo, self.hi, self.n, i)
    }

    /// The index of the value nearest `x` (clamped to the axis).
    pub fn pixel_of(&self, x: f64) -> usize {
        if self.n <= 1 || self.hi <= self.lo {
            return 0;
        }
        let f = (x - self.lo) / (self.hi - self.lo) * (self.n - 1) as f64;
        (f.round().max(0.0) as usize).min(self.n - 1)
    }

    /// Check the window ([`check_window`]) and 1 ≤ n ≤ `max_n`; `what` names the
    /// values in the refusal (e.g. "pixels per side").
    pub fn validate(
        &self,
        table: &Table,
        max_n: usize,
        what: &'static str,
    ) -> Result<(), EngineError> {
        if self.n == 0 || self.n > max_n {
            return Err(EngineError::InvalidParameter {
                name: "size".into(),
                value: self.n.to_string(),
                range: what.into(),
            });
        }
        check_window(self.param, table, self.lo, self.hi)
    }
}

/// Which interleaved part of a computation over many items to do: chains of items c
/// with c % count == index (a sweep deals out values or chains of values, a plane
/// pixels).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// 0-based part number, < count.
    pub index: usize,
    /// Number of parts.
    pub count: usize,
}

impl Shard {
    /// The whole computation.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Whether item `index` belongs to this part, when the items are dealt out
    /// round-robin in chains of `chain` consecutive ones (1: item by item).
    pub fn holds(&self, index: usize, chain: usize) -> bool {
        (index / chain.max(1)) % self.count == self.index
    }

    /// How many of `items` items belong to this part (chains of `chain`).
    pub fn items_of(&self, items: usize, chain: usize) -> usize {
        let c = chain.max(1);
        let chains = items.div_ceil(c);
        let mine = chains / self.count + usize::from(self.index < chains % self.count);
        if mine == 0 {
            return 0;
        }
        // Only the last chain can be short; it is this part's if its number is.
        let short = items % c;
        if short != 0 && (chains - 1) % self.count == self.index {
            (mine - 1) * c + short
        } else {
            mine * c
        }
    }

    /// Check 0 ≤ index < count.
    pub fn validate(&self) -> Result<(), EngineError> {
        if self.count == 0 || self.index >= self.count {
            return Err(EngineError::InvalidParameter {
                name: "shard".into(),
                value: format!("{}/{}", self.index + 1, self.count),
                range: "I/N with 1 ≤ I ≤ N".into(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_items_and_count_them() {
        for items in [0, 1, 5, 31, 32, 33, 100, 257] {
            for chain in [1, 3, 32] {
                for count in 1..=5 {
                    let mut seen = vec![0; items];
                    for index in 0..count {
                        let s = Shard { index, count };
                        let held: Vec<usize> = (0..items).filter(|&i| s.holds(i, chain)).collect();
                        assert_eq!(
                            held.len(),
                            s.items_of(items, chain),
                            "{items} {chain} {index}/{count}"
                        );
                        for i in held {
                            seen[i] += 1;
                        }
                    }
                    assert!(seen.iter().all(|&c| c == 1));
                }
            }
        }
    }

    #[test]
    fn parameters_are_named_by_the_table() {
        let t = Table::fd(0.1).unwrap();
        assert_eq!(SweepParam::parse("d", &t), Ok(SweepParam::D));
        assert_eq!(SweepParam::parse("α", &t), Ok(SweepParam::Alpha));
        assert_eq!(SweepParam::D.as_str(), "D");
        let e = SweepParam::parse("D", &Table::sine()).unwrap_err();
        assert_eq!(e, "unknown parameter 'D': valid alpha, r");
        assert_eq!(SweepParam::all(&t).len(), 3);
        let sys = SweepParam::D.system(&t, 0.5, 0.8, 0.7).unwrap();
        assert_eq!(sys.table(), &Table::fd(0.7).unwrap());
    }

    #[test]
    fn grid_values_have_exact_ends() {
        assert_eq!(grid_value(0.1, 0.7, 7, 6), 0.7);
        assert_eq!(grid_value(0.1, 0.7, 7, 0), 0.1);
        assert_eq!(grid_value(0.3, 0.9, 1, 0), 0.3);
        let a = Axis {
            param: SweepParam::Alpha,
            lo: 0.45,
            hi: 0.6,
            n: 10,
        };
        assert_eq!(a.pixel_of(0.6), 9);
        assert_eq!(a.pixel_of(0.0), 0);
        let t = Table::fd(0.1).unwrap();
        assert!(check_window(SweepParam::R, &t, 0.5, 1.5).is_err());
        assert!(check_window(SweepParam::Alpha, &t, 0.6, 0.5).is_err());
        assert!(check_window(SweepParam::D, &t, 0.2, 0.5).is_ok());
        let e = check_window(SweepParam::D, &t, 0.2, 1.5).unwrap_err();
        assert_eq!(e.to_string(), "D = 1.5 is out of range: valid [0, 1]");
        assert!(check_window(SweepParam::D, &Table::sine(), 0.2, 0.5).is_err());
    }
}
