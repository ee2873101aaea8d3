//! `bouncemap two-cycle`: the (2, 2k) solution near the (1, k) one (or the reason there
//! is none), with ΔT, Δt, Δκ, multipliers, a check by iterating the map, the paper's and
//! the corrected approximations beside it, and the border collision of the branch.

use crate::config;
use crate::config::flags::TwoCycleArgs;
use crate::output::records::{csv_writer, ComplexRecord, FixedSolution};
use crate::output::sink::Sink;
use crate::output::text::complex;
use crate::output::Format;
use bouncemap_engine::orbits::two_cycle::period_doubling_candidate;
use bouncemap_engine::orbits::{
    border_collision, map_check, two_cycle, Approximation, BorderCollision, NoBorderCollision,
    TwoCycle,
};
use serde::Serialize;
use std::io::{self, Write};

/// Impacts iterated to confirm a stable solution.
pub const CHECK_BOUNCES: u64 = 200_000;
/// Phase perturbation of the confirming run.
pub const CHECK_PERTURBATION: f64 = 1e-6;

pub fn run(args: &TwoCycleArgs) -> anyhow::Result<()> {
    let sys = config::system(&args.system)?;
    let fp = period_doubling_candidate(&sys, args.k);
    let result = two_cycle(&sys, args.k);
    let check = result
        .as_ref()
        .ok()
        .filter(|tc| tc.stable && tc.admissible)
        .and_then(|tc| map_check(&sys, tc, CHECK_PERTURBATION, CHECK_BOUNCES));
    let border = border_collision(sys.table(), sys.r(), args.k);
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                let doc = TwoCycleDoc {
                    table: sys.table().name(),
                    alpha: sys.alpha(),
                    r: sys.r(),
                    k: args.k,
                    kappa_c: sys.kappa_c(),
                    fixed: fp.as_ref().map(FixedSolution::from),
                    found: result.is_ok(),
                    reason: result.as_ref().err().map(|e| Reason {
                        code: e.as_str(),
                        message: e.to_string(),
                    }),
                    two_cycle: result.as_ref().ok().map(|tc| CycleRecord::new(tc, check)),
                    border_collision: BorderRecord::from(&border),
                };
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &TwoCycleRow::HEADER)?;
                w.serialize(TwoCycleRow::from(result.as_ref().ok()))?;
                w.flush()?;
            }
            Format::Text => {
                writeln!(
                    out,
                    "table {}  alpha {}  r {}  k {}  kappa_c = {:.15}",
                    sys.table().name(),
                    sys.alpha(),
                    sys.r(),
                    args.k,
                    sys.kappa_c()
                )?;
                if let Some(p) = &fp {
                    writeln!(
                    out,
                    "(1,{}) solution: phase {:.15}, f'' = {:.12}, f''' = {:.12}, delta_kappa = {:.6e} ({})",
                    args.k,
                    p.phase,
                    p.ddf,
                    p.dddf,
                    p.delta_kappa,
                    p.classification.as_str()
                )?;
                }
                match &result {
                    Ok(tc) => write_cycle_text(&mut out, tc, check)?,
                    Err(e) => writeln!(out, "no (2,{}) solution: {e}", 2 * args.k)?,
                }
                match &border {
                Ok(b) => writeln!(
                    out,
                    "border collision: the branch born at alpha_PD = {:.15} reaches t = {} at alpha = {:.15} (phases {:.12}, {:.12})",
                    b.alpha_pd, b.phase, b.alpha, b.phase0, b.phase1
                )?,
                Err(e) => writeln!(out, "border collision: none ({e})")?,
            }
            }
        }
        Ok(())
    })();
    out.end(written)
}

fn rel(approx: f64, exact: f64) -> f64 {
    (approx - exact) / exact
}

fn write_cycle_text<W: Write>(
    out: &mut W,
    tc: &TwoCycle,
    check: Option<(u64, f64)>,
) -> io::Result<()> {
    writeln!(
        out,
        "(2,{}) solution: phases {:.15}, {:.15}  v {:.15}, {:.15}",
        2 * tc.k,
        tc.phase0,
        tc.phase1,
        tc.v0,
        tc.v1
    )?;
    writeln!(
        out,
        "  delta_T = {:.12e}  delta_t = {:.12e}  delta_kappa = {:.12e}",
        tc.delta_big_t, tc.delta_t, tc.delta_kappa
    )?;
    writeln!(
        out,
        "  multipliers {}, {}: {}; {}; residual {:.1e} after {} Newton steps",
        complex(tc.multipliers[0]),
        complex(tc.multipliers[1]),
        if tc.stable { "stable" } else { "unstable" },
        if tc.admissible {
            "admissible"
        } else {
            "NOT admissible (a flight meets the table earlier)"
        },
        tc.residual,
        tc.newton_iterations
    )?;
    if let Some((n, d)) = check {
        writeln!(out, "  iterating the map from a phase {CHECK_PERTURBATION:e} away: distance {d:.1e} after {n} impacts")?;
    }
    for (name, a) in [
        ("corrected approximation", tc.corrected),
        ("paper's Eqs. (deltaT), (deltat)", tc.paper),
    ] {
        match a {
            Some(a) => writeln!(
                out,
                "  {name}: delta_T = {:.12e} (rel. err {:+.3e})  delta_t = {:.12e} (rel. err {:+.3e})",
                a.delta_big_t,
                rel(a.delta_big_t, tc.delta_big_t),
                a.delta_t,
                rel(a.delta_t, tc.delta_t)
            )?,
            None => writeln!(out, "  {name}: no real value")?,
        }
    }
    Ok(())
}

/// `two-cycle`'s json.
#[derive(Serialize)]
struct TwoCycleDoc<'a> {
    table: &'a str,
    alpha: f64,
    r: f64,
    k: u32,
    kappa_c: f64,
    fixed: Option<FixedSolution>,
    found: bool,
    reason: Option<Reason>,
    two_cycle: Option<CycleRecord>,
    border_collision: BorderRecord,
}

/// Why no (2, 2k) solution was found.
#[derive(Serialize)]
struct Reason {
    code: &'static str,
    message: String,
}

/// An approximation beside the exact solution.
#[derive(Serialize)]
struct ApproxRecord {
    #[serde(rename = "delta_T")]
    delta_big_t: f64,
    delta_t: f64,
    #[serde(rename = "rel_err_delta_T")]
    rel_err_delta_big_t: f64,
    rel_err_delta_t: f64,
}

impl ApproxRecord {
    fn new(a: Option<Approximation>, tc: &TwoCycle) -> Option<ApproxRecord> {
        a.map(|a| ApproxRecord {
            delta_big_t: a.delta_big_t,
            delta_t: a.delta_t,
            rel_err_delta_big_t: rel(a.delta_big_t, tc.delta_big_t),
            rel_err_delta_t: rel(a.delta_t, tc.delta_t),
        })
    }
}

/// The map iterated into a stable solution from a perturbed start.
#[derive(Serialize)]
struct MapCheck {
    bounces: u64,
    distance: f64,
    perturbation: f64,
}

/// The (2, 2k) solution.
#[derive(Serialize)]
struct CycleRecord {
    phase0: f64,
    phase1: f64,
    v0: f64,
    v1: f64,
    #[serde(rename = "delta_T")]
    delta_big_t: f64,
    delta_t: f64,
    delta_kappa: f64,
    multipliers: [ComplexRecord; 2],
    stable: bool,
    admissible: bool,
    residual: f64,
    newton_iterations: u32,
    map_check: Option<MapCheck>,
    approximation: Option<ApproxRecord>,
    paper_approximation: Option<ApproxRecord>,
}

impl CycleRecord {
    fn new(tc: &TwoCycle, check: Option<(u64, f64)>) -> CycleRecord {
        CycleRecord {
            phase0: tc.phase0,
            phase1: tc.phase1,
            v0: tc.v0,
            v1: tc.v1,
            delta_big_t: tc.delta_big_t,
            delta_t: tc.delta_t,
            delta_kappa: tc.delta_kappa,
            multipliers: tc.multipliers.map(Into::into),
            stable: tc.stable,
            admissible: tc.admissible,
            residual: tc.residual,
            newton_iterations: tc.newton_iterations,
            map_check: check.map(|(bounces, distance)| MapCheck {
                bounces,
                distance,
                perturbation: CHECK_PERTURBATION,
            }),
            approximation: ApproxRecord::new(tc.corrected, tc),
            paper_approximation: ApproxRecord::new(tc.paper, tc),
        }
    }
}

/// The border collision of the branch, or why there is none (`alpha` null).
#[derive(Serialize)]
#[serde(untagged)]
enum BorderRecord {
    Found {
        alpha: f64,
        phase: f64,
        alpha_pd: f64,
        phase0: f64,
        phase1: f64,
        v0: f64,
        v1: f64,
    },
    None {
        alpha: Option<f64>,
        reason: String,
    },
}

impl From<&Result<BorderCollision, NoBorderCollision>> for BorderRecord {
    fn from(b: &Result<BorderCollision, NoBorderCollision>) -> Self {
        match b {
            Ok(b) => BorderRecord::Found {
                alpha: b.alpha,
                phase: b.phase,
                alpha_pd: b.alpha_pd,
                phase0: b.phase0,
                phase1: b.phase1,
                v0: b.v0,
                v1: b.v1,
            },
            Err(e) => BorderRecord::None {
                alpha: None,
                reason: e.to_string(),
            },
        }
    }
}

/// `two-cycle`'s csv row (empty fields when no solution was found).
#[derive(Serialize, Default)]
struct TwoCycleRow {
    found: bool,
    phase0: Option<f64>,
    phase1: Option<f64>,
    v0: Option<f64>,
    v1: Option<f64>,
    #[serde(rename = "delta_T")]
    delta_big_t: Option<f64>,
    delta_t: Option<f64>,
    delta_kappa: Option<f64>,
    mult1_re: Option<f64>,
    mult1_im: Option<f64>,
    mult2_re: Option<f64>,
    mult2_im: Option<f64>,
    stable: Option<bool>,
    admissible: Option<bool>,
    #[serde(rename = "approx_delta_T")]
    approx_delta_big_t: Option<f64>,
    approx_delta_t: Option<f64>,
    #[serde(rename = "paper_delta_T")]
    paper_delta_big_t: Option<f64>,
    paper_delta_t: Option<f64>,
}

impl TwoCycleRow {
    const HEADER: [&'static str; 18] = [
        "found",
        "phase0",
        "phase1",
        "v0",
        "v1",
        "delta_T",
        "delta_t",
        "delta_kappa",
        "mult1_re",
        "mult1_im",
        "mult2_re",
        "mult2_im",
        "stable",
        "admissible",
        "approx_delta_T",
        "approx_delta_t",
        "paper_delta_T",
        "paper_delta_t",
    ];
}

impl From<Option<&TwoCycle>> for TwoCycleRow {
    fn from(tc: Option<&TwoCycle>) -> Self {
        let Some(tc) = tc else {
            return TwoCycleRow::default();
        };
        TwoCycleRow {
            found: true,
            phase0: Some(tc.phase0),
            phase1: Some(tc.phase1),
            v0: Some(tc.v0),
            v1: Some(tc.v1),
            delta_big_t: Some(tc.delta_big_t),
            delta_t: Some(tc.delta_t),
            delta_kappa: Some(tc.delta_kappa),
            mult1_re: Some(tc.multipliers[0].re),
            mult1_im: Some(tc.multipliers[0].im),
            mult2_re: Some(tc.multipliers[1].re),
            mult2_im: Some(tc.multipliers[1].im),
            stable: Some(tc.stable),
            admissible: Some(tc.admissible),
            approx_delta_big_t: tc.corrected.map(|a| a.delta_big_t),
            approx_delta_t: tc.corrected.map(|a| a.delta_t),
            paper_delta_big_t: tc.paper.map(|a| a.delta_big_t),
            paper_delta_t: tc.paper.map(|a| a.delta_t),
        }
    }
}
