//! The engine: the bouncing ball impact map and everything computed from it.
//!
//! Pure and synchronous: no terminal, no printing, no files, no global state. Errors are
//! [`EngineError`] values; the binary turns them into messages and exit codes.

pub mod error;
pub mod exact_sum;
pub mod impact;
pub mod map;
pub mod orbits;
pub mod poly;
pub mod sweep;
pub mod system;
pub mod table;
#[cfg(test)]
mod test_rng;

pub use error::EngineError;
pub use impact::{Landing, Launch, Solver};
pub use map::{Event, EventKind, Halt, ImpactMap, Mode, State};
pub use system::{kappa_c, System};
pub use table::{Table, TableSpec};
