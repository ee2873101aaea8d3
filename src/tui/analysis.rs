//! The stability panel's numbers from the engine's orbit analysis: the (1, k)
//! solutions with their eigenvalues, the first stability window (birth α and α_PD),
//! the (2, 2k) solution, and the stable region in the (α, r) plane (stability windows
//! at a column of r values). A few milliseconds of work, run off the UI thread.

use bouncemap_engine::orbits::{self, Classification};
use bouncemap_engine::System;

/// Rows of r in the (α, r) region plot.
pub const REGION_ROWS: usize = 48;

/// One (1, k) solution.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedPoint {
    pub phase: f64,
    pub v: f64,
    /// f''(t̂*).
    pub f2: f64,
    /// Eigenvalues of the Jacobian as (re, im).
    pub eig: [(f64, f64); 2],
    pub stable: bool,
}

/// A slice of the stability region in the (α, r) plane: stable α intervals at one r,
/// each (α_birth, α_end, whether it ends by period doubling).
#[derive(Clone, Debug, PartialEq)]
pub struct RegionRow {
    pub r: f64,
    pub intervals: Vec<(f64, f64, bool)>,
}

/// What the orbit analysis knows for the current system and k.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OrbitInfo {
    pub fixed: Vec<FixedPoint>,
    /// Birth α of the (1, k) solution (where it first exists).
    pub birth: Option<f64>,
    /// α at which the stable (1, k) solution period-doubles (f'' = κ_c).
    pub pd: Option<f64>,
    /// The (2, 2k) solution's two points (phase, v), if it exists.
    pub two: Vec<(f64, f64)>,
    /// The stable region of the (1, k) solution in the (α, r) plane.
    pub region: Vec<RegionRow>,
}

/// The (1, k) analysis of `sys`.
pub fn orbit_info(sys: &System, k: u32) -> Result<OrbitInfo, String> {
    let fixed = orbits::fixed_points(sys, k)
        .map_err(|e| e.to_string())?
        .into_iter()
        .filter(|f| f.admissible)
        .map(|f| FixedPoint {
            phase: f.phase,
            v: f.v,
            f2: f.ddf,
            eig: f.eigenvalues.map(|c| (c.re, c.im)),
            stable: f.classification == Classification::Stable,
        })
        .collect();
    let window = orbits::stability_window(sys.table(), sys.r(), k).map_err(|e| e.to_string())?;
    let two = match orbits::two_cycle(sys, k) {
        Ok(t) if t.admissible => vec![(t.phase0, t.v0), (t.phase1, t.v1)],
        _ => Vec::new(),
    };
    let region = (0..REGION_ROWS)
        .map(|i| {
            let r = (i as f64 + 0.5) / REGION_ROWS as f64;
            let intervals = orbits::stability_windows(sys.table(), r, k)
                .map(|ws| {
                    ws.iter()
                        .map(|w| (w.alpha_birth, w.alpha_end, w.alpha_pd().is_some()))
                        .collect()
                })
                .unwrap_or_default();
            RegionRow { r, intervals }
        })
        .collect();
    Ok(OrbitInfo {
        fixed,
        birth: window.map(|w| w.alpha_birth),
        pd: window.and_then(|w| w.alpha_pd()),
        two,
        region,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::Table;

    #[test]
    fn default_system_has_a_stable_fixed_point_inside_its_window() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let info = orbit_info(&sys, 1).unwrap();
        let (b, pd) = (info.birth.unwrap(), info.pd.unwrap());
        assert!(b < 0.45 && 0.45 < pd, "birth {b}, α_PD {pd}");
        let stable: Vec<_> = info.fixed.iter().filter(|f| f.stable).collect();
        assert_eq!(stable.len(), 1);
        let kc = bouncemap_engine::kappa_c(0.8);
        assert!(kc < stable[0].f2 && stable[0].f2 < 0.0);
        assert!(stable[0].eig.iter().all(|(re, im)| re.hypot(*im) < 1.0));
        assert_eq!(info.region.len(), REGION_ROWS);
    }
}
