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
    #[command(flatten)]
    pub tui: TuiArgs,
}

/// Options of the terminal application (used without a subcommand).
#[derive(Args, Debug, Clone, Default)]
pub struct TuiArgs {
    /// Start with this table: sine, quad, cubic, fd:D or PATH.toml.
    #[arg(long = "table", value_name = "TABLE")]
    pub tui_table: Option<String>,
    /// Start with this amplitude α; valid (0, 1000].
    #[arg(long = "alpha", value_parser = parse_alpha, value_name = "A")]
    pub tui_alpha: Option<f64>,
    /// Start with this restitution r; valid (0, 1).
    #[arg(long = "r", value_parser = parse_r, value_name = "R")]
    pub tui_r: Option<f64>,
    /// Frame cap while interacting, frames per second; valid 1..=60 [default: 15].
    #[arg(long, value_parser = parse_fps, value_name = "N")]
    pub fps: Option<u32>,
    /// Colours: auto (NO_COLOR honoured, else 256), never, 16, 256, truecolor.
    #[arg(long, value_parser = parse_color, value_name = "MODE")]
    pub color: Option<crate::tui::theme::ColorChoice>,
    /// Plot glyphs: braille, halfblock or dot (for fonts without braille).
    #[arg(long, value_parser = parse_marker, value_name = "MARKER")]
    pub marker: Option<crate::tui::plot::Marker>,
    /// Capture the mouse: click on the diagram sets α, drag zooms.
    #[arg(long)]
    pub mouse: bool,
    /// Config file (TOML: keys and defaults); default ~/.config/bouncemap/config.toml.
    #[arg(long, value_name = "PATH")]
    pub config: Option<std::path::PathBuf>,
}

/// --fps: 1..=60.
pub fn parse_fps(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(n) if (1..=60).contains(&n) => Ok(n),
        _ => Err(format!(
            "'{s}' is out of range: valid a whole number in 1..=60"
        )),
    }
}

/// --color.
pub fn parse_color(s: &str) -> Result<crate::tui::theme::ColorChoice, String> {
    s.parse()
}

/// --marker.
pub fn parse_marker(s: &str) -> Result<crate::tui::plot::Marker, String> {
    s.parse()
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

/// `bouncemap fixed`.
#[derive(Args, Debug, Clone)]
pub struct FixedArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    /// Periods per bounce of the (1, k) solution; valid 1 to 100.
    #[arg(long, default_value_t = 1, value_parser = parse_k, value_name = "K")]
    pub k: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// `bouncemap two-cycle`.
#[derive(Args, Debug, Clone)]
pub struct TwoCycleArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    /// k of the (1, k) solution the (2, 2k) one surrounds; valid 1 to 100.
    #[arg(long, default_value_t = 1, value_parser = parse_k, value_name = "K")]
    pub k: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// `bouncemap scaling`.
#[derive(Args, Debug, Clone)]
pub struct ScalingArgs {
    /// Values of D for F_D: a list (0.001,0.01,0.1) or a log-spaced range LO..HI[:N]
    /// (default N = 13); each in (0, 1].
    #[arg(long, default_value = "0.001,0.01,0.1", value_parser = parse_d_list, value_name = "D")]
    pub d: DList,
    /// Coefficient of restitution r; valid (0, 1).
    #[arg(long, default_value_t = 0.8, value_parser = parse_r, value_name = "R")]
    pub r: f64,
    /// k of the (1, k) solution; valid 1 to 100.
    #[arg(long, default_value_t = 1, value_parser = parse_k, value_name = "K")]
    pub k: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// The D values of `scaling --d`.
#[derive(Clone, Debug, PartialEq)]
pub struct DList(pub Vec<f64>);

/// k: a whole number in [1, 100].
pub fn parse_k(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(k) if (1..=100).contains(&k) => Ok(k),
        _ => Err(format!(
            "'{s}' is out of range: valid a whole number in [1, 100]"
        )),
    }
}

/// `--d`: D1,D2,... or LO..HI[:N], every D in (0, 1].
pub fn parse_d_list(s: &str) -> Result<DList, String> {
    let one = |t: &str| -> Result<f64, String> {
        let x = parse_f64(t)?;
        if x > 0.0 && x <= 1.0 {
            Ok(x)
        } else {
            Err(format!("D = {x} is out of range: valid (0, 1]"))
        }
    };
    let s = s.trim();
    if let Some((lo, rest)) = s.split_once("..") {
        let (hi, n) = match rest.split_once(':') {
            Some((h, n)) => (
                h,
                n.trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (2..=1000).contains(n))
                    .ok_or_else(|| {
                        format!("'{n}' is not a point count: valid a whole number in [2, 1000]")
                    })?,
            ),
            None => (rest, 13),
        };
        let (lo, hi) = (one(lo)?, one(hi)?);
        if lo >= hi {
            return Err(format!(
                "range {lo}..{hi} is empty: valid LO..HI with LO < HI"
            ));
        }
        let (a, b) = (lo.log10(), hi.log10());
        return Ok(DList(
            (0..n)
                .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
                .collect(),
        ));
    }
    let v: Vec<f64> = s
        .split(',')
        .map(|t| one(t.trim()))
        .collect::<Result<_, _>>()?;
    if v.is_empty() {
        return Err("no D given: valid a list like 0.001,0.01,0.1 or a range LO..HI[:N]".into());
    }
    Ok(DList(v))
}
