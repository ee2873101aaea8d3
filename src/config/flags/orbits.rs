//! The periodic-orbit commands' flags: `fixed`, `two-cycle`, `continue`, `curves`,
//! `cascade`, `scaling` and `manifolds`, and the (n, k) cycle guess `continue` and `curves` share.

use super::*;
use bouncemap_engine::orbits::manifold::Kind;

/// `bouncemap fixed`.
#[derive(Args, Debug, Clone)]
pub struct FixedArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[arg(help = rules::K.help("Periods per bounce of the (1, k) solution"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
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
    #[arg(help = rules::K.help("k of the (1, k) solution the (2, 2k) one surrounds"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// Where `continue` starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FromArg {
    /// The (1, k) solution with f'' < 0.
    Fixed,
    /// The (2, 2k) solution born at the (1, k) one's period doubling.
    TwoCycle,
}

/// `bouncemap continue`.
#[derive(Args, Debug, Clone)]
pub struct ContinueArgs {
    #[arg(long, help = super::table_help(""), default_value = rules::DEFAULT_TABLE, value_parser = TableSpec::parse, value_name = "TABLE")]
    pub table: TableSpec,
    #[arg(help = rules::R.help("Coefficient of restitution r"), long, default_value_t = rules::R.default, value_parser = rules::R.real(), value_name = "R")]
    pub r: f64,
    /// The α window LO..HI, each in (0, 1000], LO < HI.
    #[arg(long, value_parser = parse_alpha_window, value_name = "LO..HI")]
    pub alpha: (f64, f64),
    /// Start on the (1, k) solution or on the (2, 2k) one [default: fixed].
    #[arg(long, value_enum, conflicts_with_all = ["n", "t0", "v0"])]
    pub from: Option<FromArg>,
    #[arg(help = rules::K.help("k: of the (1, k) solution with --from, of the (n, k) cycle with --n"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    #[command(flatten)]
    pub guess: CycleGuessArgs,
    #[arg(help = rules::CONTINUE_MAX_PERIOD.help("No doubled branch is started beyond this period"), long, default_value_t = rules::CONTINUE_MAX_PERIOD.default as usize, value_parser = rules::CONTINUE_MAX_PERIOD.whole::<usize>(), value_name = "P")]
    pub max_period: usize,
    /// Prove every point by interval arithmetic (an exact cycle in a small box, its
    /// stability where decided) and each period doubling and border collision as an
    /// α-interval (see `certify`).
    #[arg(long)]
    pub certify: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// `bouncemap curves`.
#[derive(Args, Debug, Clone)]
pub struct CurvesArgs {
    #[command(flatten)]
    pub spec: CurvesSpecArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[command(flatten)]
    pub output: OutArgs,
}

/// The plane and the seeds of `curves` (and `figure curves`).
#[derive(Args, Debug, Clone)]
pub struct CurvesSpecArgs {
    #[arg(long, help = super::table_help("[:NAME=VALUE,...]; with a D axis, fd (the family) or fd:D, D the value the curves are started from (a file's parameter alike: the value it is given, else the window's middle)"), default_value = rules::DEFAULT_TABLE, value_name = "TABLE")]
    pub table: String,
    /// The horizontal axis: alpha:LO..HI (the curves are followed over it and half its width on either side, then cut to it).
    #[arg(long, value_name = "alpha:LO..HI")]
    pub x: String,
    /// The vertical axis, the second parameter: r:LO..HI, or NAME:LO..HI with NAME a parameter of the table's family (F_D's D, a table file's).
    #[arg(long, value_name = "PARAM:LO..HI")]
    pub y: String,
    #[arg(help = rules::R.help_default("Coefficient of restitution r (with an r axis, the value the curves are started from, by default the window's middle)"), long, value_parser = rules::R.real(), value_name = "R")]
    pub r: Option<f64>,
    #[arg(help = rules::K.help("k of the (1, k) solution whose branches are followed"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    #[arg(help = rules::CONTINUE_MAX_PERIOD.help("No doubled branch is started beyond this period"), long, default_value_t = rules::CONTINUE_MAX_PERIOD.default as usize, value_parser = rules::CONTINUE_MAX_PERIOD.whole::<usize>(), value_name = "P")]
    pub max_period: usize,
    #[arg(help = rules::CURVE_SEEDS.help("Besides the starting value, seed on grids of the second parameter's window, the first of about this many values, then finer (up to 129 values) until two finer grids find no new curve (1: the starting value only)"), long, default_value_t = rules::CURVE_SEEDS.default as usize, value_parser = rules::CURVE_SEEDS.whole::<usize>(), value_name = "N")]
    pub seeds: usize,
    #[command(flatten)]
    pub guess: CycleGuessArgs,
}

/// An (n, k) cycle to start on instead of the (1, k) solution (`continue`, `curves`):
/// n with a guess of its launch, at α = LO (and, for `curves`, the starting value of
/// the second parameter); k is the command's --k.
#[derive(Args, Debug, Clone, Default)]
pub struct CycleGuessArgs {
    #[arg(help = rules::CYCLE_N.help("Impacts of the (n, k) cycle to start on (with --t0 and --v0, a guess at α = LO)"), long, value_parser = rules::CYCLE_N.whole::<usize>(), value_name = "N", requires_all = ["t0", "v0"])]
    pub n: Option<usize>,
    #[arg(help = rules::T0.help("The guess's launch phase t̂0"), long, value_parser = rules::T0.real(), value_name = "PHASE", requires = "n")]
    pub t0: Option<f64>,
    #[arg(help = rules::V0.help("The guess's launch velocity v0 (right after an impact)"), long, value_parser = rules::V0.real(), value_name = "V", allow_hyphen_values = true, requires = "n")]
    pub v0: Option<f64>,
}

impl CycleGuessArgs {
    /// (n, t̂0, v0) when a cycle was given.
    pub fn cycle(&self) -> Option<(usize, f64, f64)> {
        Some((self.n?, self.t0?, self.v0?))
    }
}

/// `bouncemap certify`.
#[derive(Args, Debug, Clone)]
pub struct CertifyArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[arg(help = rules::CERTIFY_N.help("Impacts n of the (n, k) cycle to prove"), long, default_value_t = rules::CERTIFY_N.default as usize, value_parser = rules::CERTIFY_N.whole::<usize>(), value_name = "N")]
    pub n: usize,
    #[arg(help = rules::K.help("Table periods k of the (n, k) cycle"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    #[arg(help = rules::T0.help("The guess's launch phase t̂0 (without it: the stable (1, k) solution, or where the orbit from next to the (1, 1) solution settles)"), long, value_parser = rules::T0.real(), value_name = "PHASE", requires = "v0")]
    pub t0: Option<f64>,
    #[arg(help = rules::V0.help("The guess's launch velocity v0 (right after an impact)"), long, value_parser = rules::V0.real(), value_name = "V", allow_hyphen_values = true, requires = "t0")]
    pub v0: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[command(flatten)]
    pub output: OutArgs,
}

/// `bouncemap manifolds`.
#[derive(Args, Debug, Clone)]
pub struct ManifoldsArgs {
    #[command(flatten)]
    pub spec: ManifoldsSpecArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    #[command(flatten)]
    pub output: OutArgs,
}

/// Which manifold: `manifolds`' and `figure manifolds`' shared flags.
#[derive(Args, Debug, Clone)]
pub struct ManifoldsSpecArgs {
    #[command(flatten)]
    pub system: SystemArgs,
    #[arg(help = rules::K.help("k: of the unstable (1, k) solution, or of the (n, k) cycle with --n"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    #[command(flatten)]
    pub guess: SaddleGuessArgs,
    #[arg(help = rules::MANIFOLD_LENGTH.help("Arc length of each branch, in (t, v)"), long, default_value_t = rules::MANIFOLD_LENGTH.default, value_parser = rules::MANIFOLD_LENGTH.real(), value_name = "L")]
    pub length: f64,
    /// Which manifolds: the unstable (grown by the map), the stable (grown by the
    /// inverse map), or both.
    #[arg(long, value_enum, default_value_t = Which::Both)]
    pub which: Which,
}

/// `--which` of `manifolds`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Which {
    Unstable,
    Stable,
    Both,
}

impl Which {
    /// The manifolds it names, unstable first.
    pub fn kinds(self) -> &'static [Kind] {
        match self {
            Which::Unstable => &[Kind::Unstable],
            Which::Stable => &[Kind::Stable],
            Which::Both => &[Kind::Unstable, Kind::Stable],
        }
    }
}

/// The saddle (n, k) cycle of `manifolds`, by a guess Newton's method starts from
/// (without: the unstable (1, k) solution).
#[derive(Args, Debug, Clone, Default)]
pub struct SaddleGuessArgs {
    #[arg(help = rules::CYCLE_N.help("Impacts of the saddle (n, k) cycle (with --t0 and --v0, a guess at this α)"), long, value_parser = rules::CYCLE_N.whole::<usize>(), value_name = "N", requires_all = ["t0", "v0"])]
    pub n: Option<usize>,
    #[arg(help = rules::T0.help("The guess's launch phase t̂0"), long, value_parser = rules::T0.real(), value_name = "PHASE", requires = "n")]
    pub t0: Option<f64>,
    #[arg(help = rules::V0.help("The guess's launch velocity v0 (right after an impact)"), long, value_parser = rules::V0.real(), value_name = "V", allow_hyphen_values = true, requires = "n")]
    pub v0: Option<f64>,
}

/// `bouncemap cascade`.
#[derive(Args, Debug, Clone)]
pub struct CascadeArgs {
    #[arg(long, help = super::table_help(""), default_value = rules::DEFAULT_TABLE, value_parser = TableSpec::parse, value_name = "TABLE", conflicts_with = "d")]
    pub table: TableSpec,
    #[arg(help = rules::R.help("Coefficient of restitution r"), long, default_value_t = rules::R.default, value_parser = rules::R.real(), value_name = "R")]
    pub r: f64,
    #[arg(help = rules::K.help("k of the (1, k) solution the cascade starts from"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    #[arg(help = rules::DEPTH.help("Period doublings looked for"), long, default_value_t = rules::DEPTH.default as usize, value_parser = rules::DEPTH.whole::<usize>(), value_name = "N")]
    pub depth: usize,
    /// A family of fd:D tables instead of --table: LO..HI:N, N equally spaced D in
    /// [0, 1] (one row per D).
    #[arg(long, value_parser = parse_d_family, value_name = "LO..HI:N")]
    pub d: Option<DFamily>,
    /// Prove each αₙ (a period doubling, or a border collision) as an α-interval by
    /// interval arithmetic (see `certify`).
    #[arg(long, conflicts_with = "d")]
    pub certify: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// `bouncemap scaling`.
#[derive(Args, Debug, Clone)]
pub struct ScalingArgs {
    #[arg(
        long,
        default_value = "0.001,0.01,0.1",
        value_parser = parse_d_list,
        value_name = "D",
        help = "Values of D for F_D: a list (0.001,0.01,0.1) or a log-spaced range LO..HI[:N] (default N = 13); each in (0, 1]"
    )]
    pub d: DList,
    #[arg(help = rules::R.help("Coefficient of restitution r"), long, default_value_t = rules::R.default, value_parser = rules::R.real(), value_name = "R")]
    pub r: f64,
    #[arg(help = rules::K.help("k of the (1, k) solution"), long, default_value_t = rules::K.default as u32, value_parser = rules::K.whole::<u32>(), value_name = "K")]
    pub k: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

/// The D values of `scaling --d`.
#[derive(Clone, Debug, PartialEq)]
pub struct DList(pub Vec<f64>);

/// `--d`: `D1,D2,...` or `LO..HI[:N]`, every D in (0, 1].
pub fn parse_d_list(s: &str) -> Result<DList, String> {
    let one = |t: &str| rules::SCALING_D.parse(t).map_err(|e| format!("D: {e}"));
    let s = s.trim();
    if let Some((lo, rest)) = s.split_once("..") {
        let (hi, n) = match rest.split_once(':') {
            Some((h, n)) => (
                h,
                rules::D_POINTS
                    .parse(n)
                    .map_err(|e| format!("point count: {e}"))? as usize,
            ),
            None => (rest, rules::D_POINTS.default as usize),
        };
        let (lo, hi) = (one(lo)?, one(hi)?);
        if lo >= hi {
            return Err(format!(
                "range {lo}..{hi} is empty: valid LO..HI with LO < HI"
            ));
        }
        return Ok(DList(bouncemap_engine::orbits::scaling::log_spaced(
            lo, hi, n,
        )));
    }
    let v: Vec<f64> = s
        .split(',')
        .map(|t| one(t.trim()))
        .collect::<Result<_, _>>()?;
    Ok(DList(v))
}
