//! `bouncemap two-cycle`: the (2, 2k) solution near the (1, k) one (or the reason there
//! is none), with ΔT, Δt, Δκ, multipliers, a check by iterating the map, the paper's and
//! the corrected approximations beside it, and the border collision of the branch.

use super::fixed::{complex_json, point_json};
use super::system_from;
use crate::cli::TwoCycleArgs;
use crate::engine::orbits::two_cycle::period_doubling_candidate;
use crate::engine::orbits::{
    border_collision, map_check, two_cycle, Approximation, BorderCollision, NoBorderCollision,
    TwoCycle,
};
use crate::output::{csv_row, json_num, Format};
use serde_json::{json, Value};
use std::io::{self, BufWriter, Write};

/// Impacts iterated to confirm a stable solution.
pub const CHECK_BOUNCES: u64 = 200_000;
/// Phase perturbation of the confirming run.
pub const CHECK_PERTURBATION: f64 = 1e-6;

pub fn run(args: &TwoCycleArgs) -> anyhow::Result<()> {
    let sys = system_from(&args.system)?;
    let fp = period_doubling_candidate(&sys, args.k);
    let result = two_cycle(&sys, args.k);
    let check = result
        .as_ref()
        .ok()
        .filter(|tc| tc.stable && tc.admissible)
        .and_then(|tc| map_check(&sys, tc, CHECK_PERTURBATION, CHECK_BOUNCES));
    let border = border_collision(&sys.table, sys.r, args.k);
    let mut out = BufWriter::new(io::stdout().lock());
    match args.format {
        Format::Json => {
            let v = json!({
                "table": sys.table.name(),
                "alpha": json_num(sys.alpha),
                "r": json_num(sys.r),
                "k": args.k,
                "kappa_c": json_num(sys.kappa_c()),
                "fixed": fp.as_ref().map_or(Value::Null, point_json),
                "found": result.is_ok(),
                "reason": match &result {
                    Ok(_) => Value::Null,
                    Err(e) => json!({"code": e.as_str(), "message": e.to_string()}),
                },
                "two_cycle": result.as_ref().map_or(Value::Null, |tc| cycle_json(tc, check)),
                "border_collision": border_json(&border),
            });
            writeln!(out, "{v}")?;
        }
        Format::Csv => {
            csv_row(
                &mut out,
                &[
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
                ]
                .map(String::from),
            )?;
            let f = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
            match &result {
                Ok(tc) => csv_row(
                    &mut out,
                    &[
                        "true".into(),
                        tc.phase0.to_string(),
                        tc.phase1.to_string(),
                        tc.v0.to_string(),
                        tc.v1.to_string(),
                        tc.delta_big_t.to_string(),
                        tc.delta_t.to_string(),
                        tc.delta_kappa.to_string(),
                        tc.multipliers[0].re.to_string(),
                        tc.multipliers[0].im.to_string(),
                        tc.multipliers[1].re.to_string(),
                        tc.multipliers[1].im.to_string(),
                        tc.stable.to_string(),
                        tc.admissible.to_string(),
                        f(tc.corrected.map(|a| a.delta_big_t)),
                        f(tc.corrected.map(|a| a.delta_t)),
                        f(tc.paper.map(|a| a.delta_big_t)),
                        f(tc.paper.map(|a| a.delta_t)),
                    ],
                )?,
                Err(_) => {
                    let mut row = vec!["false".to_string()];
                    row.resize(18, String::new());
                    csv_row(&mut out, &row)?
                }
            }
        }
        Format::Text => {
            writeln!(
                out,
                "table {}  alpha {}  r {}  k {}  kappa_c = {:.15}",
                sys.table.name(),
                sys.alpha,
                sys.r,
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
    out.flush()?;
    Ok(())
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
    let m = |z: crate::engine::orbits::Complex| {
        if z.im == 0.0 {
            format!("{:.12}", z.re)
        } else {
            format!("{:.12}{:+.12}i", z.re, z.im)
        }
    };
    writeln!(
        out,
        "  multipliers {}, {}: {}; {}; residual {:.1e} after {} Newton steps",
        m(tc.multipliers[0]),
        m(tc.multipliers[1]),
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

fn approx_json(a: Option<Approximation>, tc: &TwoCycle) -> Value {
    a.map_or(Value::Null, |a| {
        json!({
            "delta_T": json_num(a.delta_big_t),
            "delta_t": json_num(a.delta_t),
            "rel_err_delta_T": json_num(rel(a.delta_big_t, tc.delta_big_t)),
            "rel_err_delta_t": json_num(rel(a.delta_t, tc.delta_t)),
        })
    })
}

fn cycle_json(tc: &TwoCycle, check: Option<(u64, f64)>) -> Value {
    json!({
        "phase0": json_num(tc.phase0),
        "phase1": json_num(tc.phase1),
        "v0": json_num(tc.v0),
        "v1": json_num(tc.v1),
        "delta_T": json_num(tc.delta_big_t),
        "delta_t": json_num(tc.delta_t),
        "delta_kappa": json_num(tc.delta_kappa),
        "multipliers": tc.multipliers.iter().map(|&z| complex_json(z)).collect::<Vec<_>>(),
        "stable": tc.stable,
        "admissible": tc.admissible,
        "residual": json_num(tc.residual),
        "newton_iterations": tc.newton_iterations,
        "map_check": check.map_or(Value::Null, |(n, d)| json!({"bounces": n, "distance": json_num(d), "perturbation": json_num(CHECK_PERTURBATION)})),
        "approximation": approx_json(tc.corrected, tc),
        "paper_approximation": approx_json(tc.paper, tc),
    })
}

fn border_json(b: &Result<BorderCollision, NoBorderCollision>) -> Value {
    match b {
        Ok(b) => json!({
            "alpha": json_num(b.alpha),
            "phase": json_num(b.phase),
            "alpha_pd": json_num(b.alpha_pd),
            "phase0": json_num(b.phase0),
            "phase1": json_num(b.phase1),
            "v0": json_num(b.v0),
            "v1": json_num(b.v1),
        }),
        Err(e) => json!({"alpha": null, "reason": e.to_string()}),
    }
}
