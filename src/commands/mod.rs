//! The headless subcommands, one file each. Each returns `anyhow::Result`; input
//! problems are [`crate::input::InputError`]s, which the binary reports with status 2.

pub mod bench;
pub mod fixed;
pub mod merge;
pub mod orbit;
pub mod scaling;
pub mod sweep;
pub mod two_cycle;

use crate::cli::{Command, InitialArgs, SystemArgs, DEFAULT_HOP};
use crate::engine::{State, System};
use crate::input::{load_table, InputError};

/// Run one subcommand.
pub fn run(cmd: Command) -> anyhow::Result<()> {
    match cmd {
        Command::Orbit(a) => orbit::run(&a),
        Command::Fixed(a) => fixed::run(&a),
        Command::TwoCycle(a) => two_cycle::run(&a),
        Command::Scaling(a) => scaling::run(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Merge(a) => merge::run(&a),
        Command::Bench(a) => bench::run(&a),
    }
}

/// Build the system from `--table --alpha --r`.
pub fn system_from(args: &SystemArgs) -> Result<System, InputError> {
    let table = load_table(&args.table)?;
    Ok(System::new(table, args.alpha, args.r)?)
}

/// Build the initial state from `--t0 --v0 --z0`.
pub fn initial_state(sys: &System, args: &InitialArgs) -> Result<State, InputError> {
    let v0 = args.v0.unwrap_or_else(|| sys.df(args.t0) + DEFAULT_HOP);
    Ok(State::launch(sys, 0, args.t0, v0, args.z0)?)
}
