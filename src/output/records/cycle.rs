//! A sticking cycle decided at any precision ([`CycleVerdict`]), as every output writes
//! it: `lyapunov --digits`, and the `--digits` columns of `sweep` and `basins`.

use bouncemap_engine::{max_digits_for, CycleSummary, CycleVerdict, Real};
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
        let mut record = CycleRecord::of_summary(v.summary());
        if let CycleVerdict::Found(c) = v {
            record.releases = Some(c.releases);
            record.release_phase = Some(c.release_phase.to_digits(c.digits as usize));
            record.stick_after = Some(c.stick_after.to_digits(c.digits as usize));
        }
        record
    }

    /// The record of a verdict kept without its numbers of any precision (a plane's
    /// pixel): its name, length, digits agreed and needed; no releases, release phase
    /// or stick time.
    pub fn of_summary(v: CycleSummary) -> CycleRecord {
        let (verdict, periods, agreed_digits, need_digits) = match v {
            CycleSummary::Found { periods, digits } => {
                (VERDICTS[0], Some(periods), Some(digits), None)
            }
            CycleSummary::Undecided { agreed, need } => (VERDICTS[1], None, Some(agreed), need),
            CycleSummary::NoRelease => (VERDICTS[2], None, None, None),
            CycleSummary::NoReturn => (VERDICTS[3], None, None, None),
        };
        CycleRecord {
            verdict: verdict.to_string(),
            periods,
            releases: None,
            release_phase: None,
            stick_after: None,
            agreed_digits,
            need_digits,
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

/// The verdict in one line (`digits` asked for, `max_digits` the most allowed,
/// `periods` the most table periods the orbit was followed).
pub fn cycle_text(v: &CycleVerdict, digits: u32, max_digits: u32, periods: u64) -> String {
    match v {
        CycleVerdict::Found(c) => format!(
            "cycle: sticking cycle of {} table periods ({} release{} per cycle): released at phase {}, sticks {} periods after the release ({} digits; runs at {} and {} digits agree{})",
            c.periods,
            c.releases,
            if c.releases == 1 { "" } else { "s" },
            c.release_phase.to_digits(c.digits as usize),
            c.stick_after.to_digits(c.digits as usize),
            c.digits,
            c.precision.0,
            c.precision.1,
            c.earlier.map_or(String::new(), |((a, b), d)| if d > 0 {
                format!(", at {a} and {b} only to {d}")
            } else {
                format!(", at {a} and {b} not on the cycle")
            })
        ),
        CycleVerdict::NoRelease => format!(
            "cycle: no sticking cycle: the ball is not released from the table within {} periods (run without --digits for its exponents)",
            periods
        ),
        CycleVerdict::NoReturn => format!(
            "cycle: released, but not again at the same phase within {} periods: no sticking cycle found",
            periods
        ),
        CycleVerdict::Undecided { tried, agreed, need } => format!(
            "cycle: not decided within --max-digits {}: the runs at {} and {} digits {}{}",
            max_digits,
            tried.0,
            tried.1,
            if *agreed > 0 {
                format!("agree on the stick time to {agreed} digits only")
            } else {
                "disagree on the cycle".to_string()
            },
            need.map_or(String::new(), |n| format!(
                "; by the digits the path from the release loses, it needs at least about {n} digits (--max-digits {})",
                max_digits_for(digits, n)
            ))
        ),
    }
}

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
