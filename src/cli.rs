//! Command-line definitions (clap derive): one struct per subcommand, shared argument
//! groups, and value parsers that reject bad input with the valid range.

use crate::engine::impact::Solver;
use crate::engine::system;
use crate::output::Format;
use clap::{Args, Parser, Subcommand, ValueEnum};

/// Explore the bouncing ball system with an exact impact map.
///
/// Without a subcommand it opens the terminal application.
#[derive(Parser, Debug)]
#[command(name = "bouncemap", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The headless subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Iterate the impact map and print one record per event.
    #[command(allow_negative_numbers = true)]
    Orbit(OrbitArgs),
    /// Sweep one parameter over a window: a bifurcation diagram (csv, json, braille).
    Sweep(crate::commands::sweep::SweepArgs),
    /// Join `sweep --shard I/N` output files into one.
    Merge(crate::commands::merge::MergeArgs),
    /// Measure solver throughput (exact vs grid) and sweep timings on this machine.
    Bench(crate::commands::bench::BenchArgs),
}

/// The physical system: table shape, amplitude and restitution.
#[derive(Args, Debug, Clone)]
pub struct SystemArgs {
    /// Table shape: sine, quad (= fd:0), cubic (= fd:1), fd:D with D in [0, 1], or PATH.toml.
    #[arg(long, default_value = "fd:0.1", value_name = "TABLE")]
    pub table: String,
    /// Amplitude α of the table, f(t) = α F(t); valid (0, 1000].
    #[arg(long, default_value_t = 0.45, value_parser = parse_alpha, value_name = "A")]
    pub alpha: f64,
    /// Coefficient of restitution r; valid (0, 1).
    #[arg(long, default_value_t = 0.8, value_parser = parse_r, value_name = "R")]
    pub r: f64,
}

/// Next-impact solver selection.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum SolverArg {
    /// Exact root isolation (no time grid).
    #[default]
    Exact,
    /// The paper's fixed 10⁻² grid with bisection to 10⁻⁹, for comparison.
    Grid,
}

impl From<SolverArg> for Solver {
    fn from(s: SolverArg) -> Solver {
        match s {
            SolverArg::Exact => Solver::Exact,
            SolverArg::Grid => Solver::Grid,
        }
    }
}

/// Where the ball starts.
#[derive(Args, Debug, Clone)]
pub struct InitialArgs {
    /// Initial phase t̂0 in [0, 1).
    #[arg(long, default_value_t = 0.0, value_parser = parse_phase, value_name = "PHASE")]
    pub t0: f64,
    /// Initial velocity v0 (default: f'(t0) + 0.5, a short hop leaving the table).
    #[arg(long, value_name = "V")]
    pub v0: Option<f64>,
    /// Initial height above the table, ≥ 0.
    #[arg(long, default_value_t = 0.0, value_name = "Z")]
    pub z0: f64,
}

/// Relative velocity of the default initial hop.
pub const DEFAULT_HOP: f64 = 0.5;

/// `bouncemap orbit`.
#[derive(Args, Debug, Clone)]
pub struct OrbitArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[command(flatten)]
    pub initial: InitialArgs,
    /// Number of events to print.
    #[arg(long, default_value_t = 1000, value_parser = parse_count, value_name = "N")]
    pub bounces: u64,
    /// Number of events to compute first without printing them.
    #[arg(long, default_value_t = 0, value_parser = parse_count, value_name = "M")]
    pub skip: u64,
    /// Next-impact solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Exact)]
    pub solver: SolverArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// α: finite, in (0, 1000].
pub fn parse_alpha(s: &str) -> Result<f64, String> {
    let x = parse_f64(s)?;
    system::check_alpha(x).map_err(|e| e.to_string())?;
    Ok(x)
}

/// r: in (0, 1).
pub fn parse_r(s: &str) -> Result<f64, String> {
    let x = parse_f64(s)?;
    system::check_r(x).map_err(|e| e.to_string())?;
    Ok(x)
}

/// A phase in [0, 1).
pub fn parse_phase(s: &str) -> Result<f64, String> {
    let x = parse_f64(s)?;
    if (0.0..1.0).contains(&x) {
        Ok(x)
    } else {
        Err(format!("{x} is out of range: valid a phase in [0, 1)"))
    }
}

/// A count: a whole number ≥ 0.
pub fn parse_count(s: &str) -> Result<u64, String> {
    s.trim()
        .parse::<u64>()
        .map_err(|_| format!("'{s}' is not a count: valid a whole number ≥ 0"))
}

/// A finite number.
pub fn parse_f64(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{s}' is not a finite number")),
    }
}
