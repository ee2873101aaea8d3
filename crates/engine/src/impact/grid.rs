//! The paper's Section IV solver, kept for comparison with the exact one.

use super::{crossing_times, FlightError, Landing, Launch, GRID_CELLS, GRID_STEP, GRID_TOLERANCE};
use crate::system::System;
use crate::time::{floor, normalize};

/// The paper's solver: sign test at the nodes of a fixed 10⁻² grid, bisection to 10⁻⁹.
///
/// Nodes are the absolute times n + j/100. As in the paper, at most one impact is
/// resolved per grid cell: the search starts at the first node after the launch's cell.
/// If the ball is already below the table there, the impact is placed at that node;
/// otherwise the first later node where the gap is negative closes a bracket with the
/// node before it, and bisection narrows it to 10⁻⁹ (the midpoint is returned). Like
/// the paper's, this solver misses a contact whose gap dips below zero and back between
/// two nodes, and resolves chattering only at one impact per cell.
pub(super) fn grid_landing(sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
    let phi = launch.phase;
    let z0 = sys.f(phi) + launch.height;
    let v = launch.v;
    let gap = |tau: f64| {
        let (_, ph) = normalize(0, phi + tau);
        z0 + tau * (v - 0.5 * tau) - sys.f(ph)
    };
    let (lo_f, _) = sys.table().range();
    let last = crossing_times(z0, v, sys.alpha() * lo_f).map_or(1.0, |c| c.1) + 1.0;
    let max_nodes = ((last / GRID_STEP).ceil() as i64 + 2).min(1 << 40);
    let cell = (floor(phi * GRID_CELLS as f64) as i64).min(GRID_CELLS - 1);
    let node_tau = |i: i64| {
        let node = cell + i;
        (node / GRID_CELLS) as f64 + (node % GRID_CELLS) as f64 * GRID_STEP - phi
    };
    let land = |t: f64| {
        let (period, phase) = normalize(launch.period, phi + t);
        let vrel = (v - t) - sys.df(phase);
        Ok(Landing {
            period,
            phase,
            flight: t,
            vrel: vrel.min(0.0),
            df: sys.df(phase),
        })
    };
    let first = node_tau(1);
    if gap(first) < 0.0 {
        return land(first);
    }
    let mut prev_tau = first;
    for i in 2..=max_nodes {
        let tau = node_tau(i);
        if gap(tau) < 0.0 {
            let (mut lo, mut hi) = (prev_tau, tau);
            while hi - lo > GRID_TOLERANCE {
                let mid = 0.5 * (lo + hi);
                if gap(mid) >= 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return land(0.5 * (lo + hi));
        }
        prev_tau = tau;
    }
    Err(FlightError::NoLanding)
}
