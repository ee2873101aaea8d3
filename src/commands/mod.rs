//! The headless subcommands, one file each. Each takes its parsed arguments, builds its
//! validated specification through [`crate::config`], calls the engine and writes
//! through [`crate::output`]. Input problems are [`crate::config::InputError`]s, which
//! the binary reports with status 2. What they share: [`drive`] (an engine job run to
//! its end with [`progress`] on stderr), [`resume`] (`--resume` for the commands that
//! write part files) and the `--check` plan ([`print_plan`], [`output_plan`]): a
//! command with `--check` does everything a run does before its first computation,
//! then prints what it would do.

pub mod attractors;
pub mod basins;
pub mod bench;
pub mod cascade;
pub mod certify;
pub mod continuation;
pub mod curves;
pub mod digits;
pub mod drive;
pub mod figure;
pub mod fixed;
pub mod lyapunov;
pub mod manifolds;
pub mod merge;
pub mod orbit;
pub mod plane;
pub mod progress;
pub mod resume;
pub mod scaling;
pub mod sweep;
pub mod two_cycle;

use crate::config;
use crate::config::flags::Command;
use crate::config::InputError;
use crate::output::sink::Sink;
use std::io::Write;

/// Run one subcommand. A SIGTERM, SIGINT or SIGHUP removes any output file still being
/// written (the old one stays) and exits with 128 + the signal's number.
pub fn run(cmd: Command) -> anyhow::Result<()> {
    release_large_blocks();
    crate::output::sink::clean_up_on_signals()?;
    progress::check_environment()?;
    match cmd {
        Command::Orbit(a) => orbit::run(&a),
        Command::Fixed(a) => fixed::run(&a),
        Command::TwoCycle(a) => two_cycle::run(&a),
        Command::Scaling(a) => scaling::run(&a),
        Command::Continue(a) => continuation::run(&config::run::continuation(&a)?),
        Command::Cascade(a) => cascade::run(&config::run::cascade(&a)?),
        Command::Certify(a) => certify::run(&a),
        Command::Manifolds(a) => manifolds::run(&a),
        Command::Curves(a) => curves::run(&config::run::curves(&a)?),
        Command::Sweep(a) => sweep::run(&config::run::sweep(&a)?),
        Command::Lyapunov(a) => match config::run::lyapunov_digits(&a)? {
            Some(run) => digits::lyapunov(&run),
            None => lyapunov::run(&config::run::lyapunov(&a)?),
        },
        Command::Basins(a) => basins::run(&config::run::basins(&a)?),
        Command::Attractors(a) => attractors::run(&config::run::attractors(&a)?),
        Command::Plane(a) => plane::run(&config::run::plane(&a)?),
        Command::Merge(a) => merge::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Figure(a) => figure::run(&a),
        Command::Completions(a) => {
            use clap::CommandFactory;
            let mut cmd = crate::config::flags::Cli::command();
            // Generated into memory, then written as every command's output is: a reader
            // that goes away ends it quietly, a full disk is one line.
            let mut text = Vec::new();
            clap_complete::generate(a.shell, &mut cmd, "bouncemap", &mut text);
            let mut out = Sink::stdout();
            let written = out.write_all(&text).map_err(anyhow::Error::from);
            out.end(written)
        }
        Command::GenerateDocs(a) => {
            for path in crate::docs::write_all(&a.dir)? {
                println!("wrote {}", a.dir.join(path).display());
            }
            Ok(())
        }
    }
}

/// What a headless command's process holds besides its work, at most, in bytes: the
/// binary and its libraries, the allocator's own, the job thread, standard output's and
/// the file's buffers (7 MB measured). A part of every memory bound `--check` states.
pub const BASE_BYTES: u64 = 16 << 20;
/// What a worker thread holds besides its work, at most, in bytes: its stack and its
/// allocator arena's small blocks.
pub const THREAD_BYTES: u64 = 1 << 20;
/// What writing csv or json holds, at most, in bytes: a row or a value at a time,
/// through the writers' buffers.
pub const WRITER_BYTES: u64 = 1 << 20;

/// What drawing a text picture of `w` × `h` character cells holds, at most, in bytes:
/// its counts or classes per dot, its marks and its text.
pub fn picture_bytes(w: u16, h: u16) -> u64 {
    WRITER_BYTES + w as u64 * h as u64 * 64
}

/// Have the allocator map every large block (a value's points, a run's ring of events)
/// on its own and return it to the system when it is freed, instead of keeping it for
/// later (glibc's default, which can hold freed blocks of tens of MB in every thread's
/// arena): what the process holds is then what is live, and the memory bounds that
/// `--check` states hold.
pub fn release_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets an allocator parameter, before any thread starts.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 << 10);
    }
}

/// A `--check` plan on stdout, one `plan:` line each, then the verdict.
pub fn print_plan(lines: &[String]) -> anyhow::Result<()> {
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        for l in lines {
            writeln!(out, "plan: {l}")?;
        }
        writeln!(out, "plan: checked; nothing computed")?;
        Ok(())
    })();
    out.end(written)
}

/// Where a run would write, as a line of a `--check` plan, after checking it as the run
/// opens it (created, then removed again: nothing is left behind).
pub fn output_plan(out: Option<&str>, what: &str) -> Result<String, InputError> {
    match out {
        Some(path) => {
            drop(Sink::open(Some(path)).map_err(InputError)?);
            Ok(format!("writes {what} to {path} (checked writable)"))
        }
        None => Ok(format!("writes {what} to standard output")),
    }
}
