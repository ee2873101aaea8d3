//! The configuration stage: everything the user says (flags, config file, presets,
//! keys typed into the terminal application) becomes validated engine values here, in
//! one place, before any command or view runs.
//!
//! * [`flags`]: the command line (clap definitions, raw arguments), every value parsed
//!   by its rule.
//! * [`rules`]: the one table of parameter rules (name, range, default, parser), used by
//!   the clap value parsers, the config file, presets and the terminal application's
//!   parameter editor.
//! * [`table_spec`]: the one parser of `--table` (`sine | quad | cubic | fd:D | PATH.toml`)
//!   and of table files.
//! * [`presets`]: the paper's figures as typed presets, and the one function that turns
//!   a preset into a sweep specification (shared by `sweep`, `bench` and the terminal
//!   application).
//! * [`sweep`]: `sweep`'s flags (and its preset) into a [`SweepSpec`](bouncemap_engine::sweep::SweepSpec).
//! * [`plane`]: `plane`'s flags into a [`PlaneSpec`](bouncemap_engine::plane::PlaneSpec).
//! * [`digits`]: `--digits` and its companions, for every command at any precision.
//! * [`display`]: colour modes.
//! * [`files`]: the only place that reads input files: regular files only, size-capped.
//!
//! Every refusal is an [`InputError`]: one line naming the flag, setting or file, the
//! value and the valid range; the binary reports it with exit status 2.

pub mod digits;
pub mod display;
pub mod files;
pub mod flags;
pub mod plane;
pub mod presets;
pub mod rules;
pub mod run;
pub mod sweep;
pub mod table_spec;
pub mod windows;

use bouncemap_engine::{EngineError, State, System};
use flags::{InitialArgs, SystemArgs};
use std::fmt;

/// Bad input from the user (flags, files, keys, configs): exit status 2.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError(pub String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

impl From<EngineError> for InputError {
    fn from(e: EngineError) -> Self {
        InputError(e.to_string())
    }
}

/// The system of `--table --alpha --r`.
pub fn system(args: &SystemArgs) -> Result<System, InputError> {
    let table = args.table.load()?;
    Ok(System::new(table, args.alpha, args.r)?)
}

/// The start of `--t0 --v0 --z0` on `sys`.
pub fn start(sys: &System, args: &InitialArgs) -> Result<State, InputError> {
    Ok(State::start(sys, args.t0, args.v0, args.z0)?)
}

/// The basin picture `basins`' flags describe, validated.
pub fn basin_spec(
    args: &flags::BasinsSpecArgs,
) -> Result<bouncemap_engine::attractors::basins::BasinSpec, InputError> {
    use bouncemap_engine::attractors::{default_w_max, Settle};
    let sys = system(&args.system)?;
    let (nx, ny) = args.grid;
    let spec = bouncemap_engine::attractors::basins::BasinSpec {
        w_max: args.w_max.unwrap_or_else(|| default_w_max(&sys)),
        nx,
        ny,
        settle: Settle {
            transient: args.transient,
            ..Settle::BASINS
        },
        sys,
    };
    spec.validate().map_err(InputError::from)?;
    Ok(spec)
}

/// The continuation of attractors `attractors`' flags describe, validated. The box of
/// starts is the same at every α: W is the default of the window's larger α unless
/// given.
pub fn attractors_spec(
    args: &flags::AttractorsSpecArgs,
) -> Result<bouncemap_engine::attractors::global::GlobalSpec, InputError> {
    use bouncemap_engine::attractors::{default_w_max, global::GlobalSpec, Settle};
    let table = args.table.load()?;
    let (lo, hi) = args.alpha;
    let top = System::new(table, hi, args.r)?;
    let (nx, ny) = args.grid;
    let spec = GlobalSpec {
        w_max: args.w_max.unwrap_or_else(|| default_w_max(&top)),
        sys: top,
        lo,
        hi,
        steps: args.steps,
        nx,
        ny,
        settle: Settle {
            transient: args.transient,
            ..Settle::BASINS
        },
        stop_at_known: !args.full_runs,
        sampled_starts: args.uncertainty_starts,
    };
    spec.validate()?;
    Ok(spec)
}

/// Width and height in characters of a text picture (`--width`, `--height`): as given,
/// else the terminal's (less two lines, for the prompt), else `columns` wide (the
/// caller's guess: `sweep` reads COLUMNS) or the default width, and 30 lines.
pub fn text_size(args: &flags::TextSizeArgs, columns: impl FnOnce() -> Option<u16>) -> (u16, u16) {
    let term = crossterm::terminal::size().ok();
    let w = args
        .width
        .or(term.map(|t| t.0))
        .or_else(columns)
        .unwrap_or(rules::CELLS.default as u16);
    let h = args
        .height
        .or(term.map(|t| t.1.saturating_sub(2)))
        .unwrap_or(30);
    (w, h)
}

/// Worker threads: `requested` (`--threads`), else `SLURM_CPUS_PER_TASK` (the CPUs
/// Slurm gave this task) when set, else one per core; at most 4 × the cores (more only
/// thrash).
pub fn threads(requested: Option<usize>) -> Result<usize, InputError> {
    threads_from(
        requested,
        std::env::var("SLURM_CPUS_PER_TASK").ok().as_deref(),
        bouncemap_engine::jobs::available_cores(),
    )
}

/// [`threads`] for `cores` cores and the value of `SLURM_CPUS_PER_TASK`.
pub fn threads_from(
    requested: Option<usize>,
    slurm_cpus: Option<&str>,
    cores: usize,
) -> Result<usize, InputError> {
    let cap = 4 * cores;
    let valid = format!("valid 1..={cap} (4 × the {cores} cores of this machine)");
    match (
        requested,
        slurm_cpus.map(str::trim).filter(|s| !s.is_empty()),
    ) {
        (Some(n), _) if n > cap => Err(InputError(format!(
            "--threads {n} is out of range: {valid}"
        ))),
        (Some(n), _) => Ok(n),
        (None, Some(s)) => match s.parse::<usize>() {
            Ok(n) if (1..=cap).contains(&n) => Ok(n),
            _ => Err(InputError(format!(
                "SLURM_CPUS_PER_TASK={} is not a thread count: {valid}; or give --threads N",
                s.escape_debug()
            ))),
        },
        (None, None) => Ok(cores),
    }
}

/// The worker threads a run would have, as a line of a `--check` plan: the count, or
/// why this machine would refuse it (not a refusal: the run may be meant for another).
pub fn threads_plan(requested: Option<usize>) -> (usize, String) {
    let cores = bouncemap_engine::jobs::available_cores();
    match threads(requested) {
        Ok(n) => (n, format!("{n} worker threads ({cores} cores here)")),
        Err(e) => (
            requested.unwrap_or(cores),
            format!("worker threads refused on this machine ({e}); checked again where it runs"),
        ),
    }
}

/// A memory bound as a line of a `--check` plan, with what this machine has.
pub fn memory_plan(estimate: u64) -> String {
    match available_memory() {
        Some(avail) if estimate > avail => format!(
            "memory: about {} at most, more than the {} available here (refused if run here)",
            bytes(estimate),
            bytes(avail)
        ),
        Some(avail) => format!(
            "memory: about {} at most ({} available here)",
            bytes(estimate),
            bytes(avail)
        ),
        None => format!("memory: about {} at most", bytes(estimate)),
    }
}

/// Memory this machine can still give, in bytes (MemAvailable of /proc/meminfo), if
/// known.
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuse, with the estimate, a run whose memory bound exceeds what the machine has.
pub fn check_memory(estimate: u64, what: &str) -> Result<(), InputError> {
    match available_memory() {
        Some(avail) if estimate > avail => Err(InputError(format!(
            "{what} needs about {} of memory and this machine has {} available: lower keep or the number of values",
            bytes(estimate),
            bytes(avail)
        ))),
        _ => Ok(()),
    }
}

/// A byte count for people: 12.3 MB, 4.1 GB.
pub fn bytes(n: u64) -> String {
    let n = n as f64;
    if n >= 1e9 {
        format!("{:.1} GB", n / 1e9)
    } else if n >= 1e6 {
        format!("{:.1} MB", n / 1e6)
    } else {
        format!("{:.0} kB", n / 1e3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_default_to_slurms_cpus_and_a_flag_wins() {
        assert_eq!(threads_from(None, None, 8), Ok(8));
        assert_eq!(threads_from(None, Some("1"), 8), Ok(1));
        assert_eq!(threads_from(None, Some("3"), 8), Ok(3));
        assert_eq!(threads_from(Some(5), Some("1"), 8), Ok(5));
        assert_eq!(threads_from(None, Some(""), 8), Ok(8));
        // The cap holds for both.
        assert_eq!(threads_from(None, Some("32"), 8), Ok(32));
        let e = threads_from(None, Some("33"), 8).unwrap_err().0;
        assert!(
            e.starts_with("SLURM_CPUS_PER_TASK=33 ") && e.contains("1..=32"),
            "{e}"
        );
        let e = threads_from(Some(33), None, 8).unwrap_err().0;
        assert!(
            e.starts_with("--threads 33 ") && e.contains("1..=32"),
            "{e}"
        );
        for bad in ["0", "two", "-1"] {
            let e = threads_from(None, Some(bad), 8).unwrap_err().0;
            assert!(e.contains(&format!("SLURM_CPUS_PER_TASK={bad} ")), "{e}");
        }
    }
}
