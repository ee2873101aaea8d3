//! `figure`'s flags: the options every figure shares and the figure names.

use super::*;
use bouncemap_figures::ImageFormat;

/// `bouncemap figure NAME`: options shared by every figure.
#[derive(Args, Debug, Clone)]
#[command(
    subcommand_value_name = "NAME",
    subcommand_help_heading = "Figures",
    subcommand_required = true,
    arg_required_else_help = false
)]
pub struct FigureArgs {
    #[command(subcommand)]
    pub name: FigureName,
    /// Output file, .svg (vector) or .png [default: NAME.png].
    #[arg(long, global = true, value_name = "FILE")]
    pub out: Option<String>,
    /// Output format when the file name does not say (e.g. a device) [default: from --out].
    #[arg(long, global = true, value_enum)]
    pub format: Option<ImageFormatArg>,
    /// Size WxH in inches, each side in [1, 12] [default: the figure's own, one column
    /// (3.4 in) or the page width (7 in) of a two-column paper].
    #[arg(long, global = true, value_parser = parse_size, value_name = "WxH")]
    pub size: Option<(f64, f64)>,
    #[arg(help = rules::DPI.help_default("Pixels per inch of a PNG"), long, global = true, value_parser = rules::DPI.whole::<u32>(), value_name = "N")]
    pub dpi: Option<u32>,
    /// A preview in seconds: fewer values and a shorter transient.
    #[arg(long, global = true)]
    pub quick: bool,
    /// Also write the numbers behind the figure (every series) as JSON to FILE; a
    /// diagram of more than 2²¹ points gives them as counts on a 4096 × 4096 grid
    /// (series kind density_grid).
    #[arg(long, global = true, value_name = "FILE")]
    pub data: Option<String>,
    /// Worker threads, at most 4 × the cores [default: all cores].
    #[arg(long, global = true, value_parser = rules::THREADS.whole::<usize>(), value_name = "N")]
    pub threads: Option<usize>,
}

/// `--format` of a figure: [`ImageFormat`] on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ImageFormatArg {
    /// Vector graphics, text as text.
    Svg,
    /// A bitmap at the given dpi.
    Png,
}

impl From<ImageFormatArg> for ImageFormat {
    fn from(f: ImageFormatArg) -> ImageFormat {
        match f {
            ImageFormatArg::Svg => ImageFormat::Svg,
            ImageFormatArg::Png => ImageFormat::Png,
        }
    }
}

/// The figures `bouncemap figure` draws.
#[derive(Subcommand, Debug, Clone)]
pub enum FigureName {
    /// Fig. 2: F_D, F_D', F_D'' over one period for D = 0, 0.1, 0.5, 1.
    #[command(name = "fig2")]
    Fig2,
    /// Fig. 3: the six bifurcation diagrams (a)-(f) (presets fig3a-fig3f).
    #[command(name = "fig3")]
    Fig3,
    /// Fig. 3(a): F_0.
    #[command(name = "fig3a")]
    Fig3a,
    /// Fig. 3(b): F_0.1.
    #[command(name = "fig3b")]
    Fig3b,
    /// Fig. 3(c): F_0.3.
    #[command(name = "fig3c")]
    Fig3c,
    /// Fig. 3(d): F_0.5.
    #[command(name = "fig3d")]
    Fig3d,
    /// Fig. 3(e): F_1.
    #[command(name = "fig3e")]
    Fig3e,
    /// Fig. 3(f): the sine.
    #[command(name = "fig3f")]
    Fig3f,
    /// Fig. 4: enlarged diagrams near α_PD (D = 0.001, 0.01, 0.1) and the power laws of ΔT, Δt.
    #[command(name = "fig4")]
    Fig4,
    /// Fig. 5: b_T and b_t against D, with the paper's analytic lines as printed and corrected.
    #[command(name = "fig5")]
    Fig5,
    /// Any sweep as a bifurcation diagram: takes `sweep`'s flags (--preset, --table, --alpha LO..HI, ...).
    #[command(allow_negative_numbers = true)]
    Diagram(Box<SweepSpecArgs>),
    /// A sweep's diagram with its largest Lyapunov exponent underneath: `sweep`'s flags.
    #[command(allow_negative_numbers = true)]
    Lyapunov(Box<SweepSpecArgs>),
    /// The basins of attraction of one system: `basins`' flags (--table, --alpha, --r, --grid, ...), with --manifolds the manifolds of a saddle over them.
    #[command(allow_negative_numbers = true)]
    Basins(Box<FigureBasinsArgs>),
    /// Attractors followed along α, coloured by attractor, over their stacked basin
    /// fractions: `attractors`' flags (--table, --r, --alpha LO..HI, --steps, --grid, ...).
    #[command(allow_negative_numbers = true)]
    Attractors(Box<FigureAttractorsArgs>),
    /// The unstable and stable manifolds of a saddle cycle in (t̂, v): `manifolds`' flags (--table, --alpha, --r, --k, or --n --t0 --v0, --length, --which).
    #[command(allow_negative_numbers = true)]
    Manifolds(Box<ManifoldsSpecArgs>),
    /// A two-parameter map: `plane`'s flags (--table, --x PARAM:LO..HI, --y PARAM:LO..HI, ...), the pixels as --pixels WxH.
    #[command(allow_negative_numbers = true)]
    Plane(Box<FigurePlaneArgs>),
    /// Two-parameter bifurcation curves alone: `curves`' flags (--table, --x alpha:LO..HI, --y r:LO..HI or a table parameter NAME:LO..HI, ...).
    #[command(allow_negative_numbers = true)]
    Curves(Box<CurvesSpecArgs>),
}

impl FigureName {
    /// The name on the command line.
    pub fn as_str(&self) -> &'static str {
        match self {
            FigureName::Fig2 => "fig2",
            FigureName::Fig3 => "fig3",
            FigureName::Fig3a => "fig3a",
            FigureName::Fig3b => "fig3b",
            FigureName::Fig3c => "fig3c",
            FigureName::Fig3d => "fig3d",
            FigureName::Fig3e => "fig3e",
            FigureName::Fig3f => "fig3f",
            FigureName::Fig4 => "fig4",
            FigureName::Fig5 => "fig5",
            FigureName::Diagram(_) => "diagram",
            FigureName::Lyapunov(_) => "lyapunov",
            FigureName::Basins(_) => "basins",
            FigureName::Attractors(_) => "attractors",
            FigureName::Manifolds(_) => "manifolds",
            FigureName::Plane(_) => "plane",
            FigureName::Curves(_) => "curves",
        }
    }
}

/// `--size WxH`: width and height in inches, each checked by [`rules::FIG_SIDE`].
pub fn parse_size(s: &str) -> Result<(f64, f64), String> {
    let bad = || {
        format!(
            "{} is not a size: valid {}, e.g. 3.4x2.6",
            quoted(s),
            rules::FIG_SIDE.limit.text
        )
    };
    let (w, h) = s.trim().split_once(['x', 'X', '\u{d7}']).ok_or_else(bad)?;
    let side = |t: &str, which: &str| {
        rules::FIG_SIDE.parse(t).map_err(|e| {
            if e.contains("out of range") {
                format!("{which} {e}")
            } else {
                bad()
            }
        })
    };
    Ok((side(w, "width")?, side(h, "height")?))
}

/// `bouncemap figure basins`: the basins' flags, and a saddle whose manifolds are drawn
/// over them.
#[derive(Args, Debug, Clone)]
pub struct FigureBasinsArgs {
    #[command(flatten)]
    pub spec: BasinsSpecArgs,
    /// Draw the stable and unstable manifolds of a saddle over the basins, and count how
    /// often pairs of starts a grid cell apart across the stable manifold end on
    /// different attractors: K for the unstable (1, K) solution (--manifolds alone: K =
    /// 1), or N:K:T0:V0 for the (n, k) cycle Newton's method finds from that guess.
    /// Repeat it for up to three saddles, each in its own colours.
    #[arg(long, num_args = 0..=1, default_missing_value = "1", value_parser = parse_saddle, value_name = "K|N:K:T0:V0", action = clap::ArgAction::Append)]
    pub manifolds: Vec<SaddleChoice>,
    #[arg(help = rules::MANIFOLD_LENGTH.help("Arc length of each manifold branch drawn"), long, default_value_t = rules::MANIFOLD_LENGTH.default, value_parser = rules::MANIFOLD_LENGTH.real(), value_name = "L")]
    pub manifold_length: f64,
}

/// A saddle named on the command line: the unstable (1, k) solution, or the (n, k) cycle
/// from a guess.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaddleChoice {
    pub k: u32,
    /// (n, t̂0, v0) of a guess.
    pub guess: Option<(usize, f64, f64)>,
}

/// `K` or `N:K:T0:V0`, each number checked against its range.
pub fn parse_saddle(s: &str) -> Result<SaddleChoice, String> {
    let parts: Vec<&str> = s.split(':').collect();
    let whole = |rule: &'static rules::Rule, text: &str| -> Result<u64, String> {
        rule.whole::<u64>()(text).map_err(|e| format!("{}: {e}", rule.key))
    };
    match parts.as_slice() {
        [k] => Ok(SaddleChoice {
            k: whole(&rules::K, k)? as u32,
            guess: None,
        }),
        [n, k, t0, v0] => Ok(SaddleChoice {
            k: whole(&rules::K, k)? as u32,
            guess: Some((
                whole(&rules::CYCLE_N, n)? as usize,
                rules::T0.parse(t0).map_err(|e| format!("t0: {e}"))?,
                rules::V0.parse(v0).map_err(|e| format!("v0: {e}"))?,
            )),
        }),
        _ => Err(format!(
            "{} is not a saddle: valid K (the unstable (1, K) solution) or N:K:T0:V0 (a guess at an (n, k) cycle)",
            quoted(s)
        )),
    }
}

/// `bouncemap figure attractors`: the continuation's flags, and whether its crises are
/// located and marked.
#[derive(Args, Debug, Clone)]
pub struct FigureAttractorsArgs {
    #[command(flatten)]
    pub spec: AttractorsSpecArgs,
    /// Locate each crisis (as `attractors --crises`) and mark it: a line at its α,
    /// dashed where an attractor is destroyed, dotted where it jumps in size, named by
    /// its saddle in the legend.
    #[arg(long)]
    pub crises: bool,
}
