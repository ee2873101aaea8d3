//! Where runs start: next to the (1, 1) solution, as the paper's figures do
//! ([`near_fixed_point`]), or launched from the table at a phase with a relative
//! velocity ([`launch`]). One place for the starts that sweeps, planes and basins use.

use crate::map::State;
use crate::orbits::fixed::fixed_points;
use crate::system::System;

/// Phase offset from the (1, 1) fixed point of a `near_fixed_point` start.
pub const FIXED_POINT_OFFSET: f64 = 1e-3;

/// The phase t̂* of the (1, 1) solution: f'(t̂*) = ½(1 − r)/(1 + r) with f''(t̂*) < 0,
/// preferring one with κ_c < f''(t̂*) (stable). None if the table is too weak.
pub fn fixed_point_phase(sys: &System) -> Option<f64> {
    let candidates = fixed_points(sys, 1).ok()?;
    let kc = sys.kappa_c();
    candidates
        .iter()
        .find(|p| p.ddf < 0.0 && p.ddf > kc)
        .or_else(|| candidates.iter().find(|p| p.ddf < 0.0))
        .map(|p| p.phase)
}

/// The paper's start next to the (1, 1) solution: phase t̂* + [`FIXED_POINT_OFFSET`],
/// v = ½ (at least the table's velocity), if there is a (1, 1) solution.
pub fn near_fixed_point(sys: &System) -> Option<State> {
    let t = fixed_point_phase(sys)?;
    let (_, phase) = crate::time::normalize(0, t + FIXED_POINT_OFFSET);
    State::launch(sys, 0, phase, 0.5_f64.max(sys.df(phase)), 0.0).ok()
}

/// A ball launched from the table at phase `t0` with relative velocity `w0`.
pub fn launch(sys: &System, t0: f64, w0: f64) -> Option<State> {
    State::launch(sys, 0, t0, sys.df(t0) + w0, 0.0).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    #[test]
    fn the_near_fixed_point_start_is_on_the_closed_form_branch() {
        // fd:0.1, α = 0.45, r = 0.8: f'(t̂*) = ½(1 − r)/(1 + r) on the first piece,
        // α(3D t² − (2 + D) t + ½) = 1/18, the smaller root.
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let (a, d): (f64, f64) = (0.45, 0.1);
        let (qa, qb, qc) = (3.0 * d * a, -(2.0 + d) * a, 0.5 * a - 1.0 / 18.0);
        let t = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        assert!((fixed_point_phase(&sys).unwrap() - t).abs() < 1e-14);
    }
}
