//! bouncemap-engine: the bouncing ball impact map, exact, and everything computed from
//! it. No terminal, no files, no printing, no global state: errors are [`EngineError`]
//! values, and everything but the executor's workers is synchronous.
//!
//! # What a library user needs
//! The face is eight modules and the items at the root; everything else is internal.
//! * **The system**, at the root: a [`Table`] (the sine, the paper's F_D, checked
//!   piecewise polynomials, families with named parameters: [`table`]) with α and r is a
//!   [`System`], validated on construction; [`limits`] holds every accepted range.
//! * **The map**, at the root: [`ImpactMap`] steps a [`State`] from event to event
//!   (impact, stick, release) exactly, with chattering and sticking handled;
//!   [`next_landing`] is one flight; [`tangent`] the Jacobian of one event; time is
//!   (period, phase), at most [`MAX_EVENT_PERIOD`] periods.
//! * **Orbits**: [`orbits`] — the (1, k) solutions and their stability windows, the
//!   (2, 2k) solutions, (n, k) cycles by Newton's method, continuation in α with its
//!   special points, two-parameter curves, the period-doubling cascade, the paper's
//!   scaling laws.
//! * **Runs and attractors**: [`run`] runs one orbit to the end of its transient and
//!   detects the cycle it settles on; [`attractors`] says what it settled on, its
//!   Lyapunov exponents, and which starts share an attractor (basins).
//! * **Computations over many items**: [`jobs`] (the executor: passes, generations,
//!   pause; [`jobs::grid`], parameter grids and shards; [`jobs::picture`],
//!   coarse-to-fine pictures over a grid), [`sweep`] (bifurcation diagrams), [`plane`]
//!   (two-parameter maps).
//!
//! ```
//! use bouncemap_engine::{ImpactMap, Solver, State, System, Table};
//! use bouncemap_engine::orbits::{fixed_points, Classification};
//!
//! // The paper's piecewise cubic table at α = 0.45, r = 0.8.
//! let sys = System::new(Table::fd(1.0).unwrap(), 0.45, 0.8).unwrap();
//! // Its (1, 1) solutions: f'(t̂*) = ½(1 − r)/(1 + r), one of them stable.
//! let stable = fixed_points(&sys, 1)
//!     .unwrap()
//!     .into_iter()
//!     .find(|p| p.classification == Classification::Stable)
//!     .unwrap();
//! // A ball launched just off it settles on it: one impact per table period.
//! let start = State::start(&sys, stable.phase + 1e-3, Some(0.5), 0.0).unwrap();
//! let mut map = ImpactMap::new(sys, Solver::Exact, start);
//! let events: Vec<_> = (0..2000).map(|_| map.step().unwrap()).collect();
//! let (a, b) = (&events[1998], &events[1999]);
//! assert_eq!(b.period - a.period, 1);
//! assert!((b.phase - stable.phase).abs() < 1e-9);
//! ```
//!
//! The solvers behind [`next_landing`] (exact root isolation per table shape, and the
//! paper's time grid for comparison), the polynomial numerics and the double-double
//! arithmetic are internal.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod attractors;
pub mod jobs;
pub mod limits;
pub mod orbits;
pub mod plane;
pub mod run;
pub mod sweep;
pub mod table;

mod chatter;
mod error;
mod exact_sum;
mod impact;
mod inverse;
mod linalg;
mod map;
mod poly;
mod precise;
mod real;
mod system;
mod tangent;
#[cfg(test)]
mod test_rng;
mod time;

pub use error::{fmt_value, short_text, EngineError};
pub use impact::{next_landing, FlightError, Landing, Launch, Solver};
pub use inverse::{InverseMap, NoPreimage, Preimage, RETURN_TOLERANCE};
pub use linalg::{eigenvalues_2x2, Complex, Mat2};
pub use map::{Event, EventKind, Halt, ImpactMap, Mode, State, DEFAULT_HOP, MAX_EVENT_PERIOD};
pub use orbits::periodic::cycles_near;
pub use precise::{
    agreeing_digits, check_digits, decide_in_job, decide_sticking_cycle, digits_bytes,
    impact_cycle_to_digits, max_digits_for, orbit_to_digits, precise_takes, solve_cycle,
    sticking_cycle_to_digits, Agreed, CycleAt, CycleLost, CycleSummary, CycleVerdict, DigitsAsk,
    DigitsOrbit, DigitsProgress, ImpactCycle, ImpactCycleVerdict, MakeBig, Multipliers,
    PreciseEvent, PreciseHalt, PreciseMap, PreciseRefusal, PreciseSetup, PreciseState,
    PreciseSystem, Slot, Stability, StickingCycle, Written, CYCLE_EVENTS, NEWTON_STEPS,
    PATH_EVENTS, PRECISE_MAX_DEGREE,
};
pub use real::{bits_for_digits, Big, Interval, Number, Real};
pub use system::{kappa_c, System};
pub use table::Table;
pub use tangent::{flight, tangent, Flight, Tangent};
