//! The headless subcommands, one file each. Each returns `anyhow::Result`; input
//! problems are [`crate::input::InputError`]s, which the binary reports with status 2.

pub mod bench;
pub mod merge;
pub mod orbit;
pub mod sweep;

use crate::cli::{Command, InitialArgs, SystemArgs, DEFAULT_HOP};
use crate::engine::{State, System};
use crate::input::{load_table, InputError};

/// Run one subcommand.
pub fn run(cmd: Command) -> anyhow::Result<()> {
    match cmd {
        Command::Orbit(a) => orbit::run(&a),
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

/// What `bouncemap` does without a subcommand until the terminal application exists:
/// a short demonstration of the default orbit.
pub fn demo() -> anyhow::Result<()> {
    use crate::cli::{OrbitArgs, SolverArg};
    let args = OrbitArgs {
        system: SystemArgs {
            table: "fd:0.1".into(),
            alpha: 0.45,
            r: 0.8,
        },
        initial: InitialArgs {
            t0: 0.0,
            v0: None,
            z0: 0.0,
        },
        bounces: 10,
        skip: 190,
        solver: SolverArg::Exact,
        format: crate::output::Format::Text,
    };
    println!("bouncemap: fd:0.1, alpha = 0.45, r = 0.8; impacts 190..200 (see `bouncemap --help`)");
    orbit::run(&args)
}
