//! The command line (clap derive): one struct per subcommand and the shared argument
//! groups; the periodic-orbit commands' in `orbits.rs`, `figure`'s and `plane`'s in
//! theirs. Every number is parsed and checked by the rule for it in
//! [`super::rules`]; the rest of [`crate::config`] turns these raw arguments into
//! engine values.

use super::display::ColorChoice;
use super::rules;
use super::table_spec::TableSpec;
use super::windows::{parse_alpha_window, parse_d_family, DFamily};
use crate::output::hitgrid::Marker;
use crate::output::text::quoted;
use crate::output::Format;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::Solver;
use clap::{Args, Parser, Subcommand, ValueEnum};

mod attractors;
mod figure;
mod orbits;
mod plane;
pub use attractors::*;
pub use figure::*;
pub use orbits::*;
pub use plane::*;

/// Explore the bouncing ball system with an exact impact map.
///
/// Without a subcommand it opens the terminal application.
#[derive(Parser, Debug)]
#[command(name = "bouncemap", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub tui: TuiArgs,
}

/// Options of the terminal application (used without a subcommand).
#[derive(Args, Debug, Clone, Default)]
pub struct TuiArgs {
    /// Start with this table: sine, quad, cubic, fd:D or PATH.toml.
    #[arg(long = "table", value_name = "TABLE", value_parser = TableSpec::parse)]
    pub tui_table: Option<TableSpec>,
    #[arg(help = rules::ALPHA.help("Start with this amplitude α"), long = "alpha", value_parser = rules::ALPHA.real(), value_name = "A")]
    pub tui_alpha: Option<f64>,
    #[arg(help = rules::R.help("Start with this restitution r"), long = "r", value_parser = rules::R.real(), value_name = "R")]
    pub tui_r: Option<f64>,
    #[arg(help = rules::FPS.help_default("Frame cap while interacting, frames per second"), long, value_parser = rules::FPS.whole::<u32>(), value_name = "N")]
    pub fps: Option<u32>,
    /// Colours: auto (NO_COLOR honoured, else 256), never, 16, 256, truecolor.
    #[arg(long, value_parser = ColorChoice::parse, value_name = "MODE")]
    pub color: Option<ColorChoice>,
    /// Plot glyphs: braille, halfblock or dot (for fonts without braille).
    #[arg(long, value_parser = Marker::parse, value_name = "MARKER")]
    pub marker: Option<Marker>,
    /// Capture the mouse: click on the diagram sets α, drag zooms.
    #[arg(long)]
    pub mouse: bool,
    /// Config file (TOML: keys and defaults); default ~/.config/bouncemap/config.toml.
    #[arg(long, value_name = "PATH")]
    pub config: Option<std::path::PathBuf>,
}

/// The headless subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Iterate the impact map and print one record per event.
    #[command(allow_negative_numbers = true)]
    Orbit(OrbitArgs),
    /// The (1, k) solutions: classification, eigenvalues, birth α and α_PD.
    Fixed(FixedArgs),
    /// The (2, 2k) solution near the (1, k) one, with the approximation beside it.
    TwoCycle(TwoCycleArgs),
    /// Power laws of the (2, 2k) branch near period doubling (the paper's Fig. 4, 5).
    Scaling(ScalingArgs),
    /// Periodic orbits continued in α: every branch, its multipliers and how it ends.
    #[command(allow_negative_numbers = true)]
    Continue(ContinueArgs),
    /// The period-doubling cascade: αₙ, the Feigenbaum ratios, how each 2ⁿ branch ends.
    Cascade(CascadeArgs),
    /// Prove an (n, k) cycle by interval arithmetic: an exact cycle in a small box, its landings first contacts, its stability where the enclosure decides it.
    #[command(allow_negative_numbers = true)]
    Certify(CertifyArgs),
    /// The unstable and stable manifolds of a saddle cycle: both branches of each, every point by the exact map or its exact inverse.
    #[command(allow_negative_numbers = true)]
    Manifolds(ManifoldsArgs),
    /// Two-parameter bifurcation curves over (α, r) or (α, D or a table file's parameter): period doublings, folds,
    /// border collisions, grazings, and their codimension-two points.
    #[command(allow_negative_numbers = true)]
    Curves(CurvesArgs),
    /// Sweep one parameter over a window: a bifurcation diagram (csv, json, braille).
    Sweep(SweepArgs),
    /// Both Lyapunov exponents of one orbit, per impact and per table period.
    #[command(allow_negative_numbers = true)]
    Lyapunov(LyapunovArgs),
    /// Basins of attraction: which attractor each start (t̂0, w0) ends on.
    #[command(allow_negative_numbers = true)]
    Basins(BasinsArgs),
    /// Attractors followed along an α window: basin fractions, births, deaths and
    /// mergers, basin entropy and the uncertainty exponent at every α.
    #[command(allow_negative_numbers = true)]
    Attractors(AttractorsArgs),
    /// A two-parameter map: every pixel one (α, r), (α, D) or (α, a table parameter) pair, coloured by its orbit.
    #[command(allow_negative_numbers = true)]
    Plane(PlaneArgs),
    /// Join `sweep --shard I/N`, `plane --shard I/N` or `attractors --shard I/N` output files into one.
    Merge(MergeArgs),
    /// Measure solver throughput (exact vs grid) and sweep timings on this machine.
    Bench(BenchArgs),
    /// The paper's figures, or any sweep, as SVG or PNG.
    Figure(FigureArgs),
    /// Shell completions for bash, zsh, fish, elvish or powershell, on stdout.
    Completions(CompletionsArgs),
    /// Write the documents made from the code (reference, man pages, keys, screenshot).
    #[command(hide = true)]
    GenerateDocs(GenerateDocsArgs),
}

/// `bouncemap completions SHELL`.
#[derive(Args, Debug)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

/// `bouncemap generate-docs DIR`.
#[derive(Args, Debug)]
pub struct GenerateDocsArgs {
    /// The directory to write into (the repository's docs/).
    #[arg(value_name = "DIR")]
    pub dir: std::path::PathBuf,
}

/// The physical system: table shape, amplitude and restitution.
#[derive(Args, Debug, Clone)]
pub struct SystemArgs {
    #[arg(long, help = table_help(""), default_value = rules::DEFAULT_TABLE, value_parser = TableSpec::parse, value_name = "TABLE")]
    pub table: TableSpec,
    #[arg(long, help = rules::ALPHA.help("Amplitude α of the table, f(t) = α F(t)"), default_value_t = rules::ALPHA.default, value_parser = rules::ALPHA.real(), value_name = "A")]
    pub alpha: f64,
    #[arg(help = rules::R.help("Coefficient of restitution r"), long, default_value_t = rules::R.default, value_parser = rules::R.real(), value_name = "R")]
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
    #[arg(help = rules::T0.help("Initial phase t̂0"), long, default_value_t = rules::T0.default, value_parser = rules::T0.real(), value_name = "PHASE")]
    pub t0: f64,
    #[arg(help = rules::V0.help("Initial velocity v0, at most 1000 from the table's f'(t0) (default: f'(t0) + 0.5, a short hop leaving the table)"), long, value_parser = rules::V0.real(), value_name = "V", allow_hyphen_values = true)]
    pub v0: Option<f64>,
    #[arg(help = rules::Z0.help("Initial height z0"), long, default_value_t = rules::Z0.default, value_parser = rules::Z0.real(), value_name = "Z")]
    pub z0: f64,
}

/// `bouncemap orbit`.
#[derive(Args, Debug, Clone)]
pub struct OrbitArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[command(flatten)]
    pub initial: InitialArgs,
    #[arg(help = rules::BOUNCES.help("Number of events to print"), long, default_value_t = rules::BOUNCES.default as u64, value_parser = rules::BOUNCES.whole::<u64>(), value_name = "N")]
    pub bounces: u64,
    #[arg(help = rules::SKIP.help("Number of events to compute first without printing them"), long, default_value_t = rules::SKIP.default as u64, value_parser = rules::SKIP.whole::<u64>(), value_name = "M")]
    pub skip: u64,
    /// Next-impact solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Exact)]
    pub solver: SolverArg,
    #[command(flatten)]
    pub precision: PrecisionArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// `--digits`, `--max-digits`, `--binary-params`: a run at any precision.
#[derive(Args, Debug, Clone, Default)]
pub struct PrecisionArgs {
    #[arg(help = rules::DIGITS.help(DIGITS_HELP), long_help = format!("{}\n\n{DIGITS_MORE}", rules::DIGITS.help(DIGITS_HELP)), long, value_parser = rules::DIGITS.whole::<u32>(), value_name = "N")]
    pub digits: Option<u32>,
    #[arg(help = rules::MAX_DIGITS.help("With --digits: the most digits the precision is raised to"), long, default_value_t = rules::MAX_DIGITS.default as u32, value_parser = rules::MAX_DIGITS.whole::<u32>(), value_name = "M")]
    pub max_digits: u32,
    /// With --digits: take each parameter (α, r, the table's, t0, v0) as the double the
    /// flag was read to, exactly, instead of as the decimal written.
    #[arg(long)]
    pub binary_params: bool,
    /// The texts typed for α, r, t0, v0, z0 and the table's parameters (`orbit`,
    /// `lyapunov`), kept from the
    /// command line after parsing ([`keep_written`]) so that at any precision each is
    /// read with all its digits.
    #[arg(skip)]
    pub written: bouncemap_engine::Written,
}

/// Keep in `cli` the texts typed for the parameters that a run at any precision reads
/// as written (`--alpha`, `--r`, `--t0`, `--v0`, `--z0` and `--table`'s parameters of
/// `orbit`, `lyapunov`, `sweep`, `plane` and `basins`, those each has),
/// from the parsed command line `matches`.
pub fn keep_written(cli: &mut Cli, matches: &clap::ArgMatches) {
    let (name, precision) = match &mut cli.command {
        Some(Command::Orbit(a)) => ("orbit", &mut a.precision),
        Some(Command::Lyapunov(a)) => ("lyapunov", &mut a.precision),
        Some(Command::Sweep(a)) => ("sweep", &mut a.precision),
        Some(Command::Plane(a)) => ("plane", &mut a.precision),
        Some(Command::Basins(a)) => ("basins", &mut a.precision),
        _ => return,
    };
    let Some(m) = matches.subcommand_matches(name) else {
        return;
    };
    // Only what the command line gave (not a default), its last occurrence; an id the
    // command does not have reads as nothing (a sweep's window and a plane's axes are
    // taken from their own texts, `super::sweep`, `super::plane`).
    let typed = |id: &str| -> Option<String> {
        let mut raw = m.try_get_raw(id).ok().flatten()?;
        if m.value_source(id) != Some(clap::parser::ValueSource::CommandLine) {
            return None;
        }
        raw.next_back()?.to_str().map(String::from)
    };
    precision.written = bouncemap_engine::Written {
        alpha: typed("alpha"),
        r: typed("r"),
        t0: typed("t0"),
        v0: typed("v0"),
        z0: typed("z0"),
        table: typed("table")
            .map(|t| crate::config::table_spec::TableSpec::parameter_texts(&t))
            .unwrap_or_default(),
        windows: Vec::new(),
    };
}

/// `--digits`' help: what it does.
const DIGITS_HELP: &str = "Compute at any precision and print only what holds to N significant digits: the run is repeated at twice the precision and each value printed to the digits on which the two agree (more precision is taken, up to --max-digits, where they do not); the sine and every polynomial table";
/// `--digits`' long help: how parameters are read.
const DIGITS_MORE: &str = "Parameters are taken as written: --alpha 0.6 is three fifths, rounded once to the working precision, not the double nearest it (--alpha, --r, --t0, --v0, --z0, the table's parameters and the windows of sweep and plane with every digit typed, and refused if outside their range as written; what was not typed, a default or a preset's value, as the shortest decimal of its double). --binary-params compares with the system of the doubles.";

/// `--out`: where a command writes (`sweep`, `plane`, `basins`, `merge`).
#[derive(Args, Debug, Clone, Default)]
pub struct OutArgs {
    /// Write to FILE instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<String>,
}

/// `--out`, `--shard` and `--resume`: the file of a part of a run, to be joined by
/// `merge`, and left alone if it is already there (`sweep`, `plane`; the help is the
/// sweep's, `plane` words its own).
#[derive(Args, Debug, Clone, Default)]
pub struct PartArgs {
    #[command(flatten)]
    pub output: OutArgs,
    /// Compute only the I-th of N interleaved parts (1 ≤ I ≤ N), or `auto`: the part of
    /// this Slurm array task (the default in a job array); join the parts with `merge`.
    ///
    /// `auto` reads SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_MAX:
    /// N = MAX − MIN + 1 and I = ID − MIN + 1, so arrays numbered from 0 or from 1 both
    /// work (task 3 of --array=0-7 computes 4/8). The array must be a whole range
    /// (SLURM_ARRAY_TASK_COUNT = N). Without --shard, a task of a job array (where
    /// SLURM_ARRAY_TASK_ID is set) computes its `auto` part; elsewhere the whole sweep.
    #[arg(long, value_parser = parse_shard_arg, value_name = "I/N|auto")]
    pub shard: Option<ShardArg>,
    /// Do nothing if --out FILE already holds this part of this sweep, complete and
    /// verified.
    ///
    /// FILE is checked as `merge` checks a part (provenance, specification hash, values,
    /// end line, checksum) and must be of this sweep, shard, format and version: then the
    /// run exits 0 at once and leaves it untouched. A missing FILE, or one whose
    /// provenance is this run's but that was cut off or damaged, is computed, and stderr
    /// says why; any other file (not written by bouncemap, another sweep's or another
    /// shard's part, another format) is refused with status 2 and left as it is.
    /// Re-running every shard of a run with --resume recomputes only the missing ones.
    #[arg(long)]
    pub resume: bool,
}

/// `--width` and `--height`: the size of a text picture (`sweep`, `plane`, `basins`).
#[derive(Args, Debug, Clone, Default)]
pub struct TextSizeArgs {
    #[arg(help = rules::CELLS.help("Braille width (default: the terminal's)"), long, value_parser = rules::CELLS.whole::<u16>(), value_name = "COLS")]
    pub width: Option<u16>,
    #[arg(help = rules::CELLS.help("Braille height in lines (default: the terminal's)"), long, value_parser = rules::CELLS.whole::<u16>(), value_name = "LINES")]
    pub height: Option<u16>,
}

/// How a computation over a grid runs and draws: its threads, the size of its text
/// picture, and whether it only checks (`sweep`, `plane`, `basins`).
#[derive(Args, Debug, Clone, Default)]
pub struct RunArgs {
    #[command(flatten)]
    pub text: TextSizeArgs,
    #[command(flatten)]
    pub workers: ThreadsArgs,
    #[command(flatten)]
    pub check: CheckArgs,
}

/// `--check`: a dry run (`sweep`, `plane`, `basins`, `lyapunov`).
#[derive(Args, Debug, Clone, Default)]
pub struct CheckArgs {
    /// Check the command line and print the plan, computing nothing: exit 0, or 2 with
    /// the one-line refusal the run would give.
    ///
    /// Every flag, preset and table file is parsed and validated as for the run; --out
    /// is checked as the run opens it (created and removed again; never one of the
    /// run's inputs), and --resume's file as the run reads it. The plan on stdout states
    /// what would be computed (the specification, values or pixels, the shard), where
    /// it would be written, the worker threads and a bound on the memory. The threads
    /// and memory are stated against this machine but not refused, as the run may be
    /// meant for another one (a cluster's nodes: assets/slurm/submit.sh runs --check
    /// before it submits).
    #[arg(long)]
    pub check: bool,
}

/// `--threads`: the worker threads of a computation (`sweep`, `plane`, `basins`).
#[derive(Args, Debug, Clone, Default)]
pub struct ThreadsArgs {
    /// Worker threads, at most 4 × the cores [default: SLURM_CPUS_PER_TASK when set
    /// (the CPUs Slurm gave the task), else one per core].
    #[arg(long, value_parser = rules::THREADS.whole::<usize>(), value_name = "N")]
    pub threads: Option<usize>,
}

/// Output format of `sweep`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum SweepFormat {
    /// One row per recorded point.
    #[default]
    Csv,
    /// One object per value with its points.
    Json,
    /// The diagram as braille text.
    Braille,
}

/// What a sweep computes: the flags shared by `sweep` and `figure diagram`, turned into
/// a [`SweepSpec`](bouncemap_engine::sweep::SweepSpec) by
/// [`crate::config::sweep::sweep_spec_from`].
#[derive(Args, Debug, Clone)]
pub struct SweepSpecArgs {
    /// Load settings from a preset (fig3a … fig3f, fig4a … fig4c); other flags override them.
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// Table shape: sine, quad, cubic, fd:D or PATH.toml [default: fd:0.1].
    #[arg(long, value_name = "TABLE", value_parser = TableSpec::parse)]
    pub table: Option<TableSpec>,
    /// Amplitude α: a number, or the swept window LO..HI [default: 0.45].
    #[arg(long, value_name = "A|LO..HI", allow_hyphen_values = true)]
    pub alpha: Option<String>,
    /// Restitution r: a number, or the swept window LO..HI [default: 0.8].
    #[arg(long, value_name = "R|LO..HI", allow_hyphen_values = true)]
    pub r: Option<String>,
    /// D of the fd:D table: a number, or the swept window LO..HI.
    #[arg(long, value_name = "D|LO..HI", allow_hyphen_values = true)]
    pub d: Option<String>,
    /// The swept parameter: alpha, r, or a parameter of the table's family (F_D's D,
    /// one a table file declares), as NAME or NAME:LO..HI; a family's parameter is swept
    /// over its whole range unless a window is given [default: the one given as a window].
    #[arg(long, value_name = "NAME[:LO..HI]", allow_hyphen_values = true)]
    pub param: Option<String>,
    #[arg(help = rules::STEPS.help_default("Number of parameter values"), long, value_parser = rules::STEPS.whole::<usize>(), value_name = "N")]
    pub steps: Option<usize>,
    #[arg(help = rules::TRANSIENT.help_default("End of the transient T in table periods (the default is the paper's); points are the last events before T"), long, value_parser = rules::TRANSIENT.whole::<u64>(), value_name = "PERIODS")]
    pub transient: Option<u64>,
    #[arg(help = rules::KEEP.help_default("Events recorded per value"), long, value_parser = rules::KEEP.whole::<usize>(), value_name = "M")]
    pub keep: Option<usize>,
    #[command(flatten)]
    pub initial: InitialArgs,
    /// Next-impact solver [default: exact].
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Warm start: each value starts from its neighbour's final state.
    #[arg(long)]
    pub warm: bool,
    /// Start each value slightly off its (1,1) fixed point (phase t* + 0.001, v = 1/2),
    /// as the paper does, instead of --t0/--v0/--z0 (presets do this).
    #[arg(long)]
    pub near_fixed_point: bool,
    /// Run every value to the full transient (no periodicity early stop).
    #[arg(long)]
    pub no_early_stop: bool,
    #[arg(help = rules::MAX_PERIOD.help("Longest cycle (in events) the early stop detects"), long, default_value_t = rules::MAX_PERIOD.default as usize, value_parser = rules::MAX_PERIOD.whole::<usize>(), value_name = "P")]
    pub max_period: usize,
    #[arg(help = rules::TOLERANCE.help("Agreement in phase and velocity promised by the early stop"), long, default_value_t = rules::TOLERANCE.default, value_parser = rules::TOLERANCE.real(), value_name = "TOL")]
    pub tolerance: f64,
    /// Add a `lyapunov` column: the largest Lyapunov exponent per impact of each
    /// value's orbit (exact on cycles, QR over 10⁴ impacts otherwise; -inf when it sticks).
    #[arg(long)]
    pub lyapunov: bool,
    #[arg(help = rules::STARTS.help_default("Initial conditions per value: the start above and N − 1 more spread over the basin box (t̂0 ∈ [0, 1), w0 ∈ [0, W]); adds an `attractor` column"), long, value_parser = rules::STARTS.whole::<usize>(), value_name = "N")]
    pub starts: Option<usize>,
    #[arg(help = rules::W_MAX.help("Top W of the extra starts' launch velocities (default: max(1, 2α·max|F'|), clamped into the range)"), long, value_parser = rules::W_MAX.real(), value_name = "W")]
    pub w_max: Option<f64>,
}

/// `bouncemap sweep`.
#[derive(Args, Debug, Clone)]
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    #[command(flatten)]
    pub spec: SweepSpecArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = SweepFormat::Csv)]
    pub format: SweepFormat,
    #[command(flatten)]
    pub precision: PrecisionArgs,
    #[command(flatten)]
    pub part: PartArgs,
    #[command(flatten)]
    pub run: RunArgs,
}

/// `--impacts` of `lyapunov`: what it sets, then how the measurement streams.
const IMPACTS_HELP: &str = "Impacts measured by QR on an orbit that has not settled on a cycle";
const IMPACTS_MORE: &str = "The measurement streams: memory does not grow with M (the QR sums, 16 \
    block means and the cells the orbit visits: typically a few MB, at most about 90 MB where it \
    visits a million cells, as --check states), time does (about 2 s per 10⁷ impacts on one \
    core, so 1e10 takes half an hour or more), with progress on stderr; Ctrl-C stops it.";

/// `bouncemap lyapunov`.
#[derive(Args, Debug, Clone)]
pub struct LyapunovArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[command(flatten)]
    pub initial: InitialArgs,
    /// Start slightly off the (1,1) fixed point (phase t* + 0.001, v = 1/2), as sweeps
    /// do with this flag, instead of --t0/--v0/--z0.
    #[arg(long)]
    pub near_fixed_point: bool,
    #[arg(help = rules::LYAPUNOV_TRANSIENT.help("End of the transient in table periods (an orbit that settles on a cycle earlier stops there)"), long, default_value_t = rules::LYAPUNOV_TRANSIENT.default as u64, value_parser = rules::LYAPUNOV_TRANSIENT.whole::<u64>(), value_name = "PERIODS")]
    pub transient: u64,
    #[arg(help = rules::IMPACTS.help(IMPACTS_HELP), long_help = format!("{}\n\n{IMPACTS_MORE}", rules::IMPACTS.help(IMPACTS_HELP)), long, default_value_t = rules::IMPACTS.default as u64, value_parser = rules::IMPACTS.whole::<u64>(), value_name = "M")]
    pub impacts: u64,
    /// Run the full transient and measure by QR even on a cycle (a second method).
    #[arg(long)]
    pub no_early_stop: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[command(flatten)]
    pub precision: PrecisionArgs,
    #[command(flatten)]
    pub check: CheckArgs,
}

/// Output format of `basins`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum BasinsFormat {
    /// One row per start: t0, w0, attractor.
    #[default]
    Csv,
    /// The attractors: kinds, periods, points, exponents, basin fractions.
    Json,
    /// The picture in braille with a legend.
    Braille,
}

/// What a basin picture is of: `basins`' and `figure basins`' shared flags.
#[derive(Args, Debug, Clone)]
pub struct BasinsSpecArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[arg(help = grid_help("Starts along t̂0 × along w0, e.g. 200x100"), long, default_value = rules::BASINS_GRID, value_parser = parse_grid, value_name = "NXxNY")]
    pub grid: (usize, usize),
    #[arg(help = rules::W_MAX.help("Top W of the launch velocities w0 = v0 − f'(t̂0) ∈ [0, W] (default: max(1, 2α·max|F'|), twice the table's largest velocity, clamped into the range)"), long, value_parser = rules::W_MAX.real(), value_name = "W")]
    pub w_max: Option<f64>,
    #[arg(help = rules::BASIN_TRANSIENT.help("End of each start's transient in table periods (early stop on cycles)"), long, default_value_t = rules::BASIN_TRANSIENT.default as u64, value_parser = rules::BASIN_TRANSIENT.whole::<u64>(), value_name = "PERIODS")]
    pub transient: u64,
}

/// `bouncemap basins`.
#[derive(Args, Debug, Clone)]
#[command(mut_arg("threads", |a| a.help("Worker threads [default: all cores]")))]
pub struct BasinsArgs {
    #[command(flatten)]
    pub spec: BasinsSpecArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = BasinsFormat::Csv)]
    pub format: BasinsFormat,
    #[command(flatten)]
    pub precision: PrecisionArgs,
    #[command(flatten)]
    pub output: OutArgs,
    #[command(flatten)]
    pub run: RunArgs,
}

/// How a refusal of [`parse_sides`] names what was asked for.
pub struct SidesText<'a> {
    /// The value ("a grid").
    pub what: &'a str,
    /// Its form ("NXxNY").
    pub form: &'a str,
    /// Its cells ("points").
    pub cells: &'a str,
    /// An example ("200x100").
    pub example: &'a str,
}

/// `--table`'s help: the built-in tables, F_D's range of D from the engine's limit, then
/// `after` (what else the command accepts there).
pub fn table_help(after: &str) -> String {
    format!(
        "Table shape: sine, quad (= fd:0), cubic (= fd:1), fd:D with D in {}, or PATH.toml{after}.",
        bouncemap_engine::limits::D.text
    )
}

/// A grid flag's help: `what` it sets, then the picture's limits as the refusal states
/// them.
pub fn grid_help(what: &str) -> String {
    use bouncemap_engine::jobs::picture::{MAX_CELLS, MAX_SIDE};
    format!("{what}; each side at most {MAX_SIDE} and at most {MAX_CELLS} in all.")
}

/// `WxH`: the sides of a picture, each in 1..=`MAX_SIDE`, at most `MAX_CELLS`
/// cells; `text` names them in the refusal.
pub fn parse_sides(s: &str, text: SidesText<'_>) -> Result<(usize, usize), String> {
    use bouncemap_engine::jobs::picture::{MAX_CELLS, MAX_SIDE};
    let SidesText {
        what,
        form,
        cells,
        example,
    } = text;
    let bad = || {
        format!(
            "{} is not {what}: valid {form} with each side in 1..={MAX_SIDE} and at most {MAX_CELLS} {cells}, e.g. {example}",
            quoted(s)
        )
    };
    let (a, b) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    let nx: usize = a.trim().parse().map_err(|_| bad())?;
    let ny: usize = b.trim().parse().map_err(|_| bad())?;
    if nx == 0 || ny == 0 || nx > MAX_SIDE || ny > MAX_SIDE || nx * ny > MAX_CELLS {
        return Err(bad());
    }
    Ok((nx, ny))
}

/// `NXxNY`: grid sides, each in 1..=4000, at most 10⁶ points.
pub fn parse_grid(s: &str) -> Result<(usize, usize), String> {
    let text = SidesText {
        what: "a grid",
        form: "NXxNY",
        cells: "points",
        example: "200x100",
    };
    parse_sides(s, text)
}

/// `sweep --shard`: a part given as I/N, or `auto` (from the Slurm job array).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShardArg {
    Auto,
    Part(Shard),
}

/// `auto` or `I/N` with 1 ≤ I ≤ N.
pub fn parse_shard_arg(s: &str) -> Result<ShardArg, String> {
    if s.trim() == "auto" {
        return Ok(ShardArg::Auto);
    }
    parse_shard(s).map(ShardArg::Part).map_err(|_| {
        format!(
            "{} is not a shard: valid I/N with 1 ≤ I ≤ N, e.g. 2/8, or auto",
            quoted(s)
        )
    })
}

/// `I/N` with 1 ≤ I ≤ N.
pub fn parse_shard(s: &str) -> Result<Shard, String> {
    let bad = || {
        format!(
            "{} is not a shard: valid I/N with 1 ≤ I ≤ N, e.g. 2/8",
            quoted(s)
        )
    };
    let (i, n) = s.trim().split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i == 0 || i > n {
        return Err(bad());
    }
    Ok(Shard {
        index: i - 1,
        count: n,
    })
}

/// `bouncemap merge`.
#[derive(Args, Debug, Clone)]
pub struct MergeArgs {
    /// Part files written by `sweep --shard I/N --out FILE`, `plane --shard I/N --out
    /// FILE` (all csv or all json, all of one run) or `attractors --shard I/N --out
    /// FILE`.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<String>,
    /// For parts of `attractors`: the report's format [default: text] (parts of
    /// `sweep` and `plane` are merged into their own format).
    #[arg(long, value_enum)]
    pub format: Option<AttractorsFormat>,
    #[command(flatten)]
    pub output: OutArgs,
}

/// Output of `bench`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum BenchFormat {
    #[default]
    Text,
    Json,
}

/// `bouncemap bench`.
#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    /// A few seconds instead of a couple of minutes (shorter runs, noisier figures).
    #[arg(long)]
    pub quick: bool,
    /// Also time this preset (fig3a … fig3f) at its full paper fidelity (can be long).
    #[arg(long, value_name = "PRESET")]
    pub panel: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = BenchFormat::Text)]
    pub format: BenchFormat,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every "valid ..." in a flag's help is a range some rule states, so the help and
    /// the refusals read the same: a range written by hand into a help text fails here.
    #[test]
    fn help_ranges_are_the_rules_ranges() {
        use clap::CommandFactory;
        let texts: Vec<&str> = [
            rules::ALPHA,
            rules::R,
            rules::D,
            rules::K,
            rules::T0,
            rules::V0,
            rules::Z0,
            rules::STEPS,
            rules::TRANSIENT,
            rules::KEEP,
            rules::MAX_PERIOD,
            rules::TOLERANCE,
            rules::IMPACTS,
            rules::W_MAX,
            rules::STARTS,
            rules::BOUNCES,
            rules::THREADS,
            rules::FPS,
            rules::CELLS,
            rules::CYCLE_N,
            rules::CURVE_SEEDS,
            rules::DEPTH,
            rules::D_COUNT,
            rules::SCALING_D,
            rules::D_POINTS,
            rules::FIG_SIDE,
            rules::DPI,
            rules::DIGITS,
            rules::ATTRACTOR_STEPS,
            rules::UNCERTAINTY_STARTS,
        ]
        .iter()
        .map(|rule| rule.limit.text)
        .collect();
        fn walk(cmd: &clap::Command, texts: &[&str], seen: &mut usize) {
            for arg in cmd.get_arguments() {
                let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
                if let Some((_, range)) = help.split_once("; valid ") {
                    *seen += 1;
                    assert!(
                        texts.iter().any(|t| range.starts_with(t)),
                        "--{} of {}: \"{range}\" is not a rule's range",
                        arg.get_id(),
                        cmd.get_name()
                    );
                }
            }
            for sub in cmd.get_subcommands() {
                walk(sub, texts, seen);
            }
        }
        let mut seen = 0;
        walk(&Cli::command(), &texts, &mut seen);
        assert!(seen > 40, "only {seen} ranged flags found");
    }

    #[test]
    fn shard_parsing_is_one_based() {
        assert_eq!(parse_shard("1/4"), Ok(Shard { index: 0, count: 4 }));
        assert_eq!(parse_shard("4/4"), Ok(Shard { index: 3, count: 4 }));
        assert!(parse_shard("0/4").is_err());
        assert!(parse_shard("5/4").is_err());
        assert!(parse_shard("x").is_err());
        assert_eq!(parse_shard_arg("auto"), Ok(ShardArg::Auto));
        assert_eq!(
            parse_shard_arg("2/8"),
            Ok(ShardArg::Part(Shard { index: 1, count: 8 }))
        );
        assert!(parse_shard_arg("Auto").unwrap_err().contains("or auto"));
    }

    #[test]
    fn grids_are_sides_within_range() {
        assert_eq!(parse_grid("200x100"), Ok((200, 100)));
        assert_eq!(parse_grid(" 3X4 "), Ok((3, 4)));
        for bad in ["200", "0x10", "4001x1", "2000x2000", "ax1", "1x"] {
            assert!(
                parse_grid(bad).unwrap_err().contains("valid NXxNY"),
                "{bad}"
            );
        }
    }

    #[test]
    fn d_lists_and_ranges() {
        assert_eq!(parse_d_list("0.1,0.5"), Ok(DList(vec![0.1, 0.5])));
        let r = parse_d_list("0.001..0.1:3").unwrap().0;
        assert_eq!(r.len(), 3);
        assert!((r[1] - 0.01).abs() < 1e-15);
        assert!(parse_d_list("0").unwrap_err().contains("(0, 1]"));
        assert!(parse_d_list("0.1..0.01").unwrap_err().contains("empty"));
    }

    #[test]
    fn sizes_are_inches_within_their_range() {
        assert_eq!(parse_size("3.4x2.6"), Ok((3.4, 2.6)));
        assert_eq!(parse_size("7X5"), Ok((7.0, 5.0)));
        let e = parse_size("0.5x2").unwrap_err();
        assert!(
            e.contains("width 0.5 is out of range") && e.contains("[1, 12]"),
            "{e}"
        );
        let e = parse_size("3x40").unwrap_err();
        assert!(e.starts_with("height 40"), "{e}");
        assert!(parse_size("3").unwrap_err().contains("e.g. 3.4x2.6"));
        assert!(parse_size("ax3").unwrap_err().contains("not a size"));
    }

    #[test]
    fn the_command_line_is_well_formed() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
