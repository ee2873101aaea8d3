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
//! * [`display`]: colour modes.
//! * [`files`]: the only place that reads input files: regular files only, size-capped.
//!
//! Every refusal is an [`InputError`]: one line naming the flag, setting or file, the
//! value and the valid range; the binary reports it with exit status 2.

pub mod display;
pub mod files;
pub mod flags;
pub mod presets;
pub mod rules;
pub mod sweep;
pub mod table_spec;

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
