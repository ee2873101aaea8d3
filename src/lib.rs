//! bouncemap: an exact explorer for the bouncing ball system.
//!
//! * [`engine`]: the impact map and its analysis, pure and synchronous.
//! * [`cli`], [`commands`], [`input`], [`output`]: the headless command-line front end.
//! * [`tui`]: the terminal application (`bouncemap` without a subcommand).
//!
//! See ARCHITECTURE.md for the bird's-eye view.

pub mod cli;
pub mod commands;
pub mod engine;
pub mod input;
pub mod output;
pub mod tui;
