//! The window and family arguments of `continue` and `cascade`: `--alpha LO..HI` and
//! `--d LO..HI:N`, each end checked by its rule in [`super::rules`].

use super::rules;
use crate::output::text::quoted;

/// `--alpha LO..HI` of `continue`: both in α's range, LO < HI.
pub fn parse_alpha_window(s: &str) -> Result<(f64, f64), String> {
    let (lo, hi) = s.split_once("..").ok_or_else(|| {
        format!(
            "{} is not a window: valid LO..HI, each in {}",
            quoted(s),
            rules::ALPHA.limit.text
        )
    })?;
    let lo = rules::ALPHA.parse(lo).map_err(|e| format!("LO: {e}"))?;
    let hi = rules::ALPHA.parse(hi).map_err(|e| format!("HI: {e}"))?;
    if lo >= hi {
        return Err(format!(
            "window {lo}..{hi} is empty: valid LO..HI with LO < HI"
        ));
    }
    Ok((lo, hi))
}

/// The D values of `cascade --d`.
#[derive(Clone, Debug, PartialEq)]
pub struct DFamily(pub Vec<f64>);

/// `--d LO..HI:N` of `cascade`: N equally spaced D from LO to HI, each in [0, 1].
pub fn parse_d_family(s: &str) -> Result<DFamily, String> {
    let bad = || {
        format!(
            "{} is not a family: valid LO..HI:N, D in {}, N a whole number in [1, 1000]",
            quoted(s),
            rules::D.limit.text
        )
    };
    let (lo, rest) = s.split_once("..").ok_or_else(bad)?;
    let (hi, n) = rest.split_once(':').ok_or_else(bad)?;
    let lo = rules::D.parse(lo).map_err(|e| format!("LO: {e}"))?;
    let hi = rules::D.parse(hi).map_err(|e| format!("HI: {e}"))?;
    let n = rules::D_COUNT.parse(n).map_err(|e| format!("N: {e}"))? as usize;
    if lo > hi || (lo == hi && n > 1) {
        return Err(format!(
            "range {lo}..{hi} is empty: valid LO..HI with LO < HI (or LO = HI with N = 1)"
        ));
    }
    Ok(DFamily(
        (0..n)
            .map(|i| {
                if n == 1 {
                    lo
                } else {
                    // 12 significant digits: 0.1..1:10 gives 0.3, not 0.30000000000000004.
                    let d = lo + (hi - lo) * i as f64 / (n - 1) as f64;
                    (d * 1e12).round() / 1e12
                }
            })
            .collect(),
    ))
}
