//! A sticking cycle decided at any precision ([`CycleVerdict`]), as every output writes
//! it: `lyapunov --digits`, and the `--digits` columns of `sweep` and `basins`.

use bouncemap_engine::{CycleVerdict, Real};
use serde::{Deserialize, Serialize};

/// The verdict's fields: its name, and where found the cycle's length in table periods,
/// its releases per cycle, the release phase and the stick time after it (each to the
/// digits both precisions agree on), the digits agreed, and where undecided the digits
/// it would need.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CycleRecord {
    /// `found`, `undecided`, `no_release` or `no_return`.
    pub verdict: String,
    pub periods: Option<i64>,
    pub releases: Option<usize>,
    pub release_phase: Option<String>,
    pub stick_after: Option<String>,
    pub agreed_digits: Option<u32>,
    pub need_digits: Option<u32>,
}

/// The verdict names, as [`CycleRecord::verdict`] has them.
pub const VERDICTS: [&str; 4] = ["found", "undecided", "no_release", "no_return"];

impl CycleRecord {
    /// The record of `v`.
    pub fn of(v: &CycleVerdict) -> CycleRecord {
        let none = |verdict: &str| CycleRecord {
            verdict: verdict.to_string(),
            periods: None,
            releases: None,
            release_phase: None,
            stick_after: None,
            agreed_digits: None,
            need_digits: None,
        };
        match v {
            CycleVerdict::Found(c) => CycleRecord {
                periods: Some(c.periods),
                releases: Some(c.releases),
                release_phase: Some(c.release_phase.to_digits(c.digits as usize)),
                stick_after: Some(c.stick_after.to_digits(c.digits as usize)),
                agreed_digits: Some(c.digits),
                ..none(VERDICTS[0])
            },
            CycleVerdict::Undecided { agreed, need, .. } => CycleRecord {
                agreed_digits: Some(*agreed),
                need_digits: *need,
                ..none(VERDICTS[1])
            },
            CycleVerdict::NoRelease => none(VERDICTS[2]),
            CycleVerdict::NoReturn => none(VERDICTS[3]),
        }
    }

    /// Whether the verdict is one of [`VERDICTS`] and its fields are those of its
    /// verdict (a found cycle has its length, releases, release phase and stick time;
    /// the others none).
    pub fn check(&self) -> Result<(), String> {
        check_verdict(
            &self.verdict,
            &[
                self.periods.is_some(),
                self.releases.is_some(),
                self.release_phase.is_some(),
                self.stick_after.is_some(),
            ],
        )
    }
}

/// Whether `verdict` is one of [`VERDICTS`] and the fields of a found cycle are `given`
/// exactly when it is `found`.
pub fn check_verdict(verdict: &str, given: &[bool]) -> Result<(), String> {
    if !VERDICTS.contains(&verdict) {
        return Err(format!(
            "verdict '{}' is not one of {}",
            crate::output::part_file::clip(verdict),
            VERDICTS.join(", ")
        ));
    }
    let found = verdict == VERDICTS[0];
    if given.iter().any(|&g| g != found) {
        return Err(format!(
            "a cycle's length and stick time must be given exactly for a found cycle (verdict {verdict})"
        ));
    }
    Ok(())
}

/// The `--digits` columns of a csv row, in order.
pub const CYCLE_COLUMNS: [&str; 5] = [
    "digits_verdict",
    "digits_periods",
    "stick_after",
    "agreed_digits",
    "need_digits",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_verdict_is_one_of_the_four_with_its_own_fields() {
        assert!(check_verdict("found", &[true, true]).is_ok());
        assert!(check_verdict("undecided", &[false, false]).is_ok());
        let bad = check_verdict("maybe", &[false]).unwrap_err();
        assert!(bad.contains("'maybe' is not one of found, undecided, no_release, no_return"));
        assert!(check_verdict("found", &[true, false]).is_err());
        assert!(check_verdict("no_release", &[true, false]).is_err());
    }
}
