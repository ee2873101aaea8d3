//! Grids of parameter values and how their items are dealt out: the parameters a
//! grid can run over ([`SweepParam`]), evenly spaced values with both ends exact
//! ([`grid_value`], [`Axis`]), the window check, and shards ([`Shard`]: which part of
//! the items one process computes). Below sweeps, planes and every job over a grid.

use crate::error::{fmt_value, EngineError};
use crate::limits;

/// A parameter a grid can run over.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SweepParam {
    /// The amplitude α.
    Alpha,
    /// The restitution coefficient r.
    R,
    /// D of the paper's F_D table.
    D,
}

impl SweepParam {
    /// Every swept parameter.
    pub const ALL: [SweepParam; 3] = [SweepParam::Alpha, SweepParam::R, SweepParam::D];

    /// Lower-case name used in every output format (`alpha`, `r`, `d`).
    pub fn as_str(self) -> &'static str {
        match self {
            SweepParam::Alpha => "alpha",
            SweepParam::R => "r",
            SweepParam::D => "d",
        }
    }

    /// The range of the parameter.
    pub fn limit(self) -> limits::Limit {
        match self {
            SweepParam::Alpha => limits::ALPHA,
            SweepParam::R => limits::R,
            SweepParam::D => limits::D,
        }
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

/// Check a window `lo..=hi` of `param`: finite, ordered, both ends in the parameter's
/// range.
pub fn check_window(param: SweepParam, lo: f64, hi: f64) -> Result<(), EngineError> {
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return Err(EngineError::InvalidParameter {
            name: param.as_str(),
            value: format!("{}..{}", fmt_value(lo), fmt_value(hi)),
            range: "a window LO..HI with LO ≤ HI",
        });
    }
    let limit = param.limit();
    limit.check(lo)?;
    limit.check(hi)?;
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
    pub fn validate(&self, max_n: usize, what: &'static str) -> Result<(), EngineError> {
        if self.n == 0 || self.n > max_n {
            return Err(EngineError::InvalidParameter {
                name: "size",
                value: self.n.to_string(),
                range: what,
            });
        }
        check_window(self.param, self.lo, self.hi)
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
                name: "shard",
                value: format!("{}/{}", self.index + 1, self.count),
                range: "I/N with 1 ≤ I ≤ N",
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
        assert!(check_window(SweepParam::R, 0.5, 1.5).is_err());
        assert!(check_window(SweepParam::Alpha, 0.6, 0.5).is_err());
    }
}
