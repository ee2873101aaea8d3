//! `plane`'s flags, shared with `figure plane`.

use super::*;

/// Output format of `plane`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum PlaneFormat {
    /// One row per pixel: x, y, class, period, table_periods, lyapunov, status.
    #[default]
    Csv,
    /// The same per pixel, plus the analytic curves.
    Json,
    /// The picture as text: one glyph per class (sparse to dense), axes with tick
    /// labels, the curves drawn over it and a legend.
    Braille,
}

/// How each pixel's orbit starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum PlaneStartArg {
    /// Next to the (1, 1) solution where it exists (the paper's start), else cold.
    #[default]
    NearFixedPoint,
    /// t̂0 = 0, v0 = f'(0) + 0.5, on the table.
    Cold,
}

/// What a plane is of: `plane`'s and `figure plane`'s shared flags.
#[derive(Args, Debug, Clone)]
pub struct PlaneSpecArgs {
    /// Table shape: fd (the F_D family, for a D axis), fd:D, sine, quad, cubic or
    /// PATH.toml[:NAME=VALUE,...] (a file's parameter on an axis takes no value here).
    #[arg(long, default_value = "fd", value_name = "TABLE")]
    pub table: String,
    /// The horizontal axis: PARAM:LO..HI with PARAM alpha, r or a parameter of the table's family (D for fd).
    #[arg(long, value_name = "PARAM:LO..HI", allow_hyphen_values = true)]
    pub x: String,
    /// The vertical axis: PARAM:LO..HI with PARAM alpha, r or a parameter of the table's family (D for fd).
    #[arg(long, value_name = "PARAM:LO..HI", allow_hyphen_values = true)]
    pub y: String,
    #[arg(help = rules::ALPHA.help_default("Amplitude α where it is not an axis"), long, value_parser = rules::ALPHA.real(), value_name = "A")]
    pub alpha: Option<f64>,
    #[arg(help = rules::R.help_default("Restitution r where it is not an axis"), long, value_parser = rules::R.real(), value_name = "R")]
    pub r: Option<f64>,
    #[arg(help = rules::PLANE_TRANSIENT.help("End of each pixel's transient in table periods (early stop on cycles)"), long, default_value_t = rules::PLANE_TRANSIENT.default as u64, value_parser = rules::PLANE_TRANSIENT.whole::<u64>(), value_name = "PERIODS")]
    pub transient: u64,
    /// Where each pixel's orbit starts.
    #[arg(long, value_enum, default_value_t = PlaneStartArg::NearFixedPoint)]
    pub start: PlaneStartArg,
    /// Do not measure the largest Lyapunov exponent (unsettled pixels are then `unresolved`).
    #[arg(long)]
    pub no_lyapunov: bool,
}

/// `bouncemap figure plane`: the plane's flags, its pixels as `--pixels` (`--size` is
/// the figure's size there).
#[derive(Args, Debug, Clone)]
pub struct FigurePlaneArgs {
    #[command(flatten)]
    pub spec: PlaneSpecArgs,
    #[arg(help = super::grid_help("Pixels along x × along y, e.g. 400x200"), long, default_value = rules::PLANE_SIZE, value_parser = parse_plane_size, value_name = "WxH")]
    pub pixels: (usize, usize),
    #[arg(help = rules::CONTINUE_MAX_PERIOD.help("Also draw the two-parameter curves (as `bouncemap curves`) of every branch of the (1, 1) solution up to period P over the pixels, with their codimension-two points; the axes must be alpha and r or a table parameter"), long, value_parser = rules::CONTINUE_MAX_PERIOD.whole::<usize>(), value_name = "P")]
    pub curves: Option<usize>,
}

/// `bouncemap plane`.
#[derive(Args, Debug, Clone)]
#[command(
    mut_arg("shard", |a| a
        .help("Compute only the I-th of N interleaved parts (pixels whose index is I − 1 modulo N), or `auto` (the Slurm array task's part); join the parts with `merge`")
        .long_help(None)),
    mut_arg("resume", |a| a
        .help("Do nothing if --out FILE already holds this part of this plane, complete and verified (checked as `merge` checks a part); compute it if FILE is missing or this part damaged; refuse any other file")
        .long_help(None)),
    mut_arg("width", |a| a.help("Picture width in characters [default: the terminal's]")),
    mut_arg("height", |a| a.help("Picture height in lines [default: the terminal's]")),
    mut_arg("threads", |a| a.help("Worker threads [default: SLURM_CPUS_PER_TASK when set, else one per core]")),
)]
pub struct PlaneArgs {
    #[command(flatten)]
    pub spec: PlaneSpecArgs,
    #[arg(help = super::grid_help("Pixels along x × along y, e.g. 400x200"), long, default_value = rules::PLANE_SIZE, value_parser = parse_plane_size, value_name = "WxH")]
    pub size: (usize, usize),
    /// Output format.
    #[arg(long, value_enum, default_value_t = PlaneFormat::Csv)]
    pub format: PlaneFormat,
    #[command(flatten)]
    pub precision: super::PrecisionArgs,
    #[arg(help = rules::CONTINUE_MAX_PERIOD.help("With --format braille: also mark the two-parameter curves (as `bouncemap curves`) of every branch of the (1, 1) solution up to period P over the picture; the axes must be alpha and r or a table parameter"), long, value_parser = rules::CONTINUE_MAX_PERIOD.whole::<usize>(), value_name = "P")]
    pub curves: Option<usize>,
    #[command(flatten)]
    pub part: PartArgs,
    #[command(flatten)]
    pub run: RunArgs,
}

/// `WxH`: plane sides, each in 1..=4000, at most 10⁶ pixels.
pub fn parse_plane_size(s: &str) -> Result<(usize, usize), String> {
    use super::{parse_sides, SidesText};
    let text = SidesText {
        what: "a size",
        form: "WxH",
        cells: "pixels",
        example: "400x200",
    };
    parse_sides(s, text)
}
