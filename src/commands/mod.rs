//! The headless subcommands, one file each. Each takes its parsed arguments, builds its
//! validated specification through [`crate::config`], calls the engine and writes
//! through [`crate::output`]. Input problems are [`crate::config::InputError`]s, which
//! the binary reports with status 2.

pub mod basins;
pub mod bench;
pub mod cascade;
pub mod continuation;
pub mod figure;
pub mod fixed;
pub mod lyapunov;
pub mod merge;
pub mod orbit;
pub mod plane;
pub mod progress;
pub mod scaling;
pub mod sweep;
pub mod two_cycle;

use crate::config::flags::Command;

/// Run one subcommand. A SIGTERM, SIGINT or SIGHUP removes any output file still being
/// written (the old one stays) and exits with 128 + the signal's number.
pub fn run(cmd: Command) -> anyhow::Result<()> {
    crate::output::sink::clean_up_on_signals()?;
    match cmd {
        Command::Orbit(a) => orbit::run(&a),
        Command::Fixed(a) => fixed::run(&a),
        Command::TwoCycle(a) => two_cycle::run(&a),
        Command::Scaling(a) => scaling::run(&a),
        Command::Continue(a) => continuation::run(&a),
        Command::Cascade(a) => cascade::run(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Lyapunov(a) => lyapunov::run(&a),
        Command::Basins(a) => basins::run(&a),
        Command::Plane(a) => plane::run(&a),
        Command::Merge(a) => merge::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Figure(a) => figure::run(&a),
    }
}

/// The file `--resume` checks and the layout the run writes (`sweep`, `plane`):
/// `--resume` needs `--out` and a verifiable format (csv or json; `layout` None for
/// braille).
fn resume_target(
    layout: Option<crate::output::part_file::Layout>,
    out: Option<&str>,
) -> Result<(&str, crate::output::part_file::Layout), crate::config::InputError> {
    use crate::config::InputError;
    let layout = layout.ok_or_else(|| {
        InputError(
            "--resume with --format braille: valid with --format csv or json, whose files can be verified".into(),
        )
    })?;
    match out {
        Some(out) => Ok((out, layout)),
        None => Err(InputError(
            "--resume without --out: valid with --out FILE, the file to check and write".into(),
        )),
    }
}
