//! Next-impact solvers: given the ball leaving the table, find the earliest later time
//! at which it meets the table again.
//!
//! * [`Solver::Exact`] (the default) never steps time on a grid. On a piecewise
//!   polynomial table the gap z(t) − f(t) is a polynomial on each piece; its first real
//!   root is isolated exactly ([`crate::poly::Poly::first_root`]). The root at the launch time is
//!   divided out of the polynomial instead of nudging time. A piece is skipped only where
//!   the ball is provably above the table's maximum on it. On the sine table the sine is
//!   replaced piece by piece by polynomials with rigorous error bounds, and the solver
//!   advances by safe steps to the first zero of a rigorous lower bound of the gap, so no
//!   contact can lie inside a step; the landing is proven within a few ulps of zero.
//! * [`Solver::Grid`] is the paper's Section IV method, kept for comparison: a time grid
//!   of 10⁻² fixed in advance, a sign test of the gap at the grid nodes, and bisection to
//!   10⁻⁹ on the first cell where the gap turns negative.
//!
//! Time is passed as (integer period, phase in [0, 1)); flight durations are short f64s.
//!
//! The impact map prepares its solver once per system (`FlightSolver`: the pieces
//! scaled by α, the sine's α-dependent bounds); [`next_landing`] prepares one for a
//! single flight.

mod grid;
mod piecewise;
mod sine;
mod sine_pieces;

use super::poly;
use super::system::System;
use super::table::Shape;
use crate::time::normalize;

/// Which next-impact solver to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Solver {
    /// Exact root isolation (default).
    #[default]
    Exact,
    /// The paper's fixed 10⁻² time grid with bisection to 10⁻⁹.
    Grid,
}

/// Grid step of the paper's solver.
pub const GRID_STEP: f64 = 1e-2;
/// Cells per period of the paper's grid.
pub const GRID_CELLS: i64 = 100;
/// Bisection tolerance of the paper's solver.
pub const GRID_TOLERANCE: f64 = 1e-9;
/// Pieces the exact solver examines before it reports that the ball does not land.
pub const MAX_FLIGHT_PIECES: usize = 1_000_000;
/// Safe steps the sine solver takes before it reports that the ball does not land.
pub const MAX_SINE_STEPS: usize = 100_000;

/// The ball leaving the table (or starting a free flight).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Launch {
    /// Whole table periods of the launch time.
    pub period: i64,
    /// Phase in [0, 1).
    pub phase: f64,
    /// Height of the ball above the table at launch (0 after an impact or a release).
    pub height: f64,
    /// Absolute velocity of the ball.
    pub v: f64,
    /// Velocity relative to the table, v − f'(t); kept separately because it can be
    /// far smaller than v (chattering) and must not be recomputed by cancellation.
    pub w: f64,
}

/// Where and how the ball meets the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Landing {
    /// Whole table periods of the landing time.
    pub period: i64,
    /// Phase of the landing, in [0, 1).
    pub phase: f64,
    /// Flight duration.
    pub flight: f64,
    /// Relative velocity at contact, u − f'(t) (≤ 0).
    pub vrel: f64,
    /// The table's velocity f'(t) at contact.
    pub df: f64,
}

/// Why no landing was returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlightError {
    /// The ball did not land within the documented work bound.
    NoLanding,
    /// Launched with zero relative velocity, the ball is pressed into the table at once
    /// (it is not actually released).
    NoLiftOff,
}

/// The next contact after `launch`, with the chosen solver. (The impact map prepares
/// its solver once, `FlightSolver`; this prepares one for a single flight.)
pub fn next_landing(sys: &System, solver: Solver, launch: &Launch) -> Result<Landing, FlightError> {
    FlightSolver::new(sys, solver).landing(sys, launch)
}

/// A next-impact solver prepared for one system: what depends only on the table and α
/// is computed once here, so a flight does no allocation and no dispatch beyond one
/// match on the kind.
#[derive(Clone, Debug)]
pub(crate) struct FlightSolver {
    kind: Kind,
}

#[derive(Clone, Debug)]
enum Kind {
    Grid,
    Sine(Box<sine::Bounds>),
    /// Every piece of degree ≤ 3: fixed-size storage.
    Cubic(piecewise::Prepared<piecewise::CubicPiece>),
    General(piecewise::Prepared<piecewise::GeneralPiece>),
}

impl FlightSolver {
    /// The solver `solver` prepared for `sys`.
    pub(crate) fn new(sys: &System, solver: Solver) -> FlightSolver {
        let kind = match (solver, sys.table().shape()) {
            (Solver::Grid, _) => Kind::Grid,
            (Solver::Exact, Shape::Sine) => Kind::Sine(Box::new(sine::Bounds::new(sys.alpha()))),
            (Solver::Exact, Shape::Piecewise(_)) if sys.table().max_degree() <= 3 => {
                Kind::Cubic(piecewise::Prepared::new::<piecewise::CubicGap>(sys))
            }
            (Solver::Exact, Shape::Piecewise(_)) => {
                Kind::General(piecewise::Prepared::new::<poly::Poly>(sys))
            }
        };
        FlightSolver { kind }
    }

    /// The next contact after `launch`; `sys` is the system this solver was prepared for.
    #[inline(always)]
    pub(crate) fn landing(&self, sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
        match &self.kind {
            Kind::Grid => grid::grid_landing(sys, launch),
            Kind::Sine(b) => sine::sine_landing(b, launch),
            Kind::Cubic(p) => piecewise::piecewise_landing::<piecewise::CubicGap>(p, launch),
            Kind::General(p) => piecewise::piecewise_landing::<poly::Poly>(p, launch),
        }
    }
}

/// Flight times at which the ball, z(τ) = z0 + vτ − τ²/2, crosses height `level`:
/// (ascending, descending). None if it stays below `level`.
fn crossing_times(z0: f64, v: f64, level: f64) -> Option<(f64, f64)> {
    let disc = v * v + 2.0 * (z0 - level);
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    Some((v - s, v + s))
}

fn landing_on(
    launch: &Launch,
    m: i64,
    start: f64,
    s_in_piece: f64,
    tau: f64,
    vrel: f64,
    df: f64,
) -> Landing {
    let (period, phase) = normalize(launch.period.saturating_add(m), start + s_in_piece);
    Landing {
        period,
        phase,
        flight: tau,
        vrel: vrel.min(0.0),
        df,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    #[test]
    fn quad_free_flight_closed_form() {
        // fd:0 with tiny α: the ball launched at phase 0 with v = 1 lands after ≈ 2 periods.
        // The gap at landing must vanish and no earlier contact may exist.
        let sys = System::new(Table::fd(0.0).unwrap(), 0.01, 0.5).unwrap();
        let w = 1.0 - sys.df(0.0);
        let l = Launch {
            period: 0,
            phase: 0.0,
            height: 0.0,
            v: 1.0,
            w,
        };
        for solver in [Solver::Exact, Solver::Grid] {
            let land = next_landing(&sys, solver, &l).unwrap();
            let t = land.period as f64 + land.phase;
            let z = t - 0.5 * t * t;
            assert!((z - sys.f(land.phase)).abs() < 1e-8, "{solver:?} {land:?}");
            assert!((t - 2.0).abs() < 0.02);
        }
    }
}
