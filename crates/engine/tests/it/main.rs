//! The engine's integration tests, one test binary with a module per area.

mod any_precision;
mod attractors;
mod continuation;
mod curves;
mod curves_cusp;
mod curves_reach;
mod curves_set;
mod engine_properties;
mod long_cycles;
mod long_runs;
mod orbits;
mod plane;
mod precise_cycles;
mod precision;
mod sweep;
