//! `attractors`' command line: the attractors of a system continued along an α window,
//! each α a basin picture over the same box of starts (the spec shared with `figure
//! attractors`).

use super::{parse_grid, table_help, CheckArgs, OutArgs, ThreadsArgs};
use crate::config::rules;
use crate::config::table_spec::TableSpec;
use crate::config::windows::parse_alpha_window;
use clap::{Args, ValueEnum};

/// Output format of `attractors`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum AttractorsFormat {
    /// The attractors followed along α, the changes between values, and a line per α
    /// with its fractions and basin statistics.
    #[default]
    Text,
    /// One row per α and attractor (a dying attractor's row at the α it is gone), with
    /// the α's basin statistics.
    Csv,
    /// The attractors, the changes, and every α with its attractors and statistics.
    Json,
}

/// What a continuation of attractors is of: `attractors`' and `figure attractors`'
/// shared flags.
#[derive(Args, Debug, Clone)]
pub struct AttractorsSpecArgs {
    #[arg(long, help = table_help(""), default_value = rules::DEFAULT_TABLE, value_parser = TableSpec::parse, value_name = "TABLE")]
    pub table: TableSpec,
    #[arg(help = rules::R.help("Coefficient of restitution r"), long, default_value_t = rules::R.default, value_parser = rules::R.real(), value_name = "R")]
    pub r: f64,
    /// The α window LO..HI the attractors are followed over, each end in α's range.
    #[arg(long, required = true, value_parser = parse_alpha_window, value_name = "LO..HI")]
    pub alpha: (f64, f64),
    #[arg(help = rules::ATTRACTOR_STEPS.help("Number of α values, both ends included (each a basin picture)"), long, default_value_t = rules::ATTRACTOR_STEPS.default as usize, value_parser = rules::ATTRACTOR_STEPS.whole::<usize>(), value_name = "N")]
    pub steps: usize,
    #[arg(help = super::grid_help("Starts along t̂0 × along w0 at each α, e.g. 100x100"), long, default_value = rules::ATTRACTORS_GRID, value_parser = parse_grid, value_name = "NXxNY")]
    pub grid: (usize, usize),
    #[arg(help = rules::W_MAX.help("Top W of the launch velocities w0 = v0 − f'(t̂0) ∈ [0, W], the same at every α (default: max(1, 2α·max|F'|) at the window's larger α, clamped into the range)"), long, value_parser = rules::W_MAX.real(), value_name = "W")]
    pub w_max: Option<f64>,
    #[arg(help = rules::BASIN_TRANSIENT.help("End of each start's transient in table periods (early stop on cycles)"), long, default_value_t = rules::BASIN_TRANSIENT.default as u64, value_parser = rules::BASIN_TRANSIENT.whole::<u64>(), value_name = "PERIODS")]
    pub transient: u64,
    /// Run every start until it detects its own cycle (or to the end of the
    /// transient), instead of stopping where it reaches a cycle that the previous α's
    /// attractors, run here as seeds, were found on (within 10⁻⁷ of a cycle of impacts
    /// over one whole cycle, or released at a sticking cycle's release phase); the
    /// output is the same, only slower.
    #[arg(long)]
    pub full_runs: bool,
    #[arg(help = rules::UNCERTAINTY_STARTS.help("Measure the uncertainty exponent at each α from N starts spread over the box, each with copies displaced by ±ε along t̂0 for ε = 10^-1.5 .. 10^-6 (McDonald et al.), instead of from the grid's neighbours (0); for basins mixed at every scale the grid resolves"), long, default_value_t = rules::UNCERTAINTY_STARTS.default as usize, value_parser = rules::UNCERTAINTY_STARTS.whole::<usize>(), value_name = "N")]
    pub uncertainty_starts: usize,
}

/// `bouncemap attractors`.
#[derive(Args, Debug, Clone)]
#[command(allow_negative_numbers = true)]
pub struct AttractorsArgs {
    #[command(flatten)]
    pub spec: AttractorsSpecArgs,
    /// Output format [default: text].
    #[arg(long, value_enum)]
    pub format: Option<AttractorsFormat>,
    #[command(flatten)]
    pub output: OutArgs,
    /// Compute only the I-th of N parts of the α window (1 ≤ I ≤ N ≤ the number of α
    /// values), or `auto`: the part of this Slurm array task (the default in a job
    /// array); join the parts with `merge`.
    ///
    /// The parts are runs of consecutive α values; each part after the first starts
    /// one value early, at the last value of the part before it, where `merge` matches
    /// the two parts' attractors and carries the tracks on. A part is a json file for
    /// `merge` (no --format); `merge --format` chooses the report. `auto` reads the
    /// array's variables as `sweep --shard auto` does.
    #[arg(long, value_parser = super::parse_shard_arg, value_name = "I/N|auto")]
    pub shard: Option<super::ShardArg>,
    /// Do nothing if --out FILE already holds this part of this run, complete and
    /// verified (with --shard).
    ///
    /// FILE is checked as `merge` checks a part and must be this run's, this shard's
    /// and this version's: then the run exits 0 at once and leaves it untouched. A
    /// missing FILE, or this run's part cut off or damaged, is computed (stderr says
    /// why); any other file is refused with status 2 and left as it is.
    #[arg(long)]
    pub resume: bool,
    /// Locate each crisis: where a chaotic attractor is destroyed with no local
    /// bifurcation, or jumps in size (its range of velocities grows by over 4 times its
    /// drift between neighbouring values: an interior crisis), bisect α to 1e-6 (orbits
    /// on it stay near it 2·10⁶ events below, leave above) and name the saddle the
    /// leaving orbits pass whose stable manifold the attractor's unstable manifold
    /// first crosses (text and json; not with --shard).
    #[arg(long)]
    pub crises: bool,
    #[command(flatten)]
    pub workers: ThreadsArgs,
    #[command(flatten)]
    pub check: CheckArgs,
}
