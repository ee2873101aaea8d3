//! bouncemap-engine: the bouncing ball impact map, exact, and everything computed from
//! it.
//!
//! * [`table`]: table shapes behind one smooth-segment interface; [`system`]: table + α
//!   + r; [`limits`]: every accepted range; [`poly`], [`exact_sum`]: the numerics.
//! * [`impact`]: next-contact solvers (exact per shape, and the paper's grid);
//!   [`map`]: the impact map with chattering, sticking and release.
//! * [`orbits`]: (1, k) and (2, 2k) solutions, stability windows, scaling laws.
//! * [`tangent`]: the Jacobian of one event; [`attractors`]: what orbits settle on,
//!   Lyapunov exponents, basins of attraction.
//! * [`jobs`]: the executor for computations over many work items; [`sweep`]: the
//!   bifurcation diagram, its first client; [`attractors::basins`]: the basin picture;
//!   [`plane`]: two-parameter maps with their analytic curves.
//!
//! No terminal, no files, no printing, no global state: errors are [`EngineError`]
//! values; the binary turns them into messages and exit codes. Everything but the
//! executor's workers is synchronous.

pub mod attractors;
pub mod error;
pub mod exact_sum;
pub mod grid;
pub mod impact;
pub mod jobs;
pub mod limits;
pub mod linalg;
pub mod map;
pub mod orbits;
pub mod picture;
pub mod plane;
pub mod poly;
pub mod run;
pub mod sweep;
pub mod system;
pub mod table;
pub mod tangent;
#[cfg(test)]
mod test_rng;
pub mod time;

pub use error::EngineError;
pub use impact::{Landing, Launch, Solver};
pub use map::{Event, EventKind, Halt, ImpactMap, Mode, State, DEFAULT_HOP};
pub use system::{kappa_c, System};
pub use table::Table;
