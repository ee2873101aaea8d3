//! `bouncemap fixed`: κ_c, every (1, k) solution with its classification and
//! eigenvalues, and the α window(s) of stability (birth α and α_PD).

use super::system_from;
use crate::cli::FixedArgs;
use crate::engine::orbits::{
    fixed_points, stability_windows, Complex, FixedPoint, StabilityWindow,
};
use crate::output::{csv_row, json_num, Format};
use serde_json::{json, Value};
use std::io::{self, BufWriter, Write};

pub fn run(args: &FixedArgs) -> anyhow::Result<()> {
    let sys = system_from(&args.system)?;
    let points = fixed_points(&sys, args.k)?;
    let windows = stability_windows(&sys.table, sys.r, args.k)?;
    let mut out = BufWriter::new(io::stdout().lock());
    match args.format {
        Format::Json => {
            let first = windows.first();
            let v = json!({
                "table": sys.table.name(),
                "alpha": json_num(sys.alpha),
                "r": json_num(sys.r),
                "k": args.k,
                "kappa_c": json_num(sys.kappa_c()),
                "solutions": points.iter().map(point_json).collect::<Vec<_>>(),
                "alpha_birth": first.map_or(Value::Null, |w| json_num(w.alpha_birth)),
                "alpha_pd": first.and_then(|w| w.alpha_pd()).map_or(Value::Null, json_num),
                "windows": windows.iter().map(window_json).collect::<Vec<_>>(),
            });
            writeln!(out, "{v}")?;
        }
        Format::Csv => {
            csv_row(
                &mut out,
                &[
                    "phase",
                    "v",
                    "df",
                    "ddf",
                    "dddf",
                    "delta_kappa",
                    "eig1_re",
                    "eig1_im",
                    "eig2_re",
                    "eig2_im",
                    "admissible",
                    "classification",
                ]
                .map(String::from),
            )?;
            for p in &points {
                csv_row(
                    &mut out,
                    &[
                        p.phase.to_string(),
                        p.v.to_string(),
                        p.df.to_string(),
                        p.ddf.to_string(),
                        p.dddf.to_string(),
                        p.delta_kappa.to_string(),
                        p.eigenvalues[0].re.to_string(),
                        p.eigenvalues[0].im.to_string(),
                        p.eigenvalues[1].re.to_string(),
                        p.eigenvalues[1].im.to_string(),
                        p.admissible.to_string(),
                        p.classification.as_str().to_string(),
                    ],
                )?;
            }
        }
        Format::Text => {
            writeln!(
                out,
                "table {}  alpha {}  r {}  k {}",
                sys.table.name(),
                sys.alpha,
                sys.r,
                args.k
            )?;
            writeln!(
                out,
                "kappa_c = {:.15}   (1,k) solutions need f'(t*) = {:.15}, v* = {}",
                sys.kappa_c(),
                crate::engine::orbits::fixed_point_slope(sys.r, args.k),
                0.5 * args.k as f64
            )?;
            if points.is_empty() {
                writeln!(out, "no (1,{}) solution at this alpha", args.k)?;
            } else {
                writeln!(
                    out,
                    "{:>18} {:>18} {:>18} {:>18}  {:>28} {:>28}  classification",
                    "phase", "f''", "f'''", "delta_kappa", "eigenvalue 1", "eigenvalue 2"
                )?;
                for p in &points {
                    writeln!(
                        out,
                        "{:>18.15} {:>18.12} {:>18.12} {:>18.12}  {:>28} {:>28}  {}",
                        p.phase,
                        p.ddf,
                        p.dddf,
                        p.delta_kappa,
                        complex_text(p.eigenvalues[0]),
                        complex_text(p.eigenvalues[1]),
                        p.classification.as_str()
                    )?;
                }
            }
            if windows.is_empty() {
                writeln!(out, "no alpha window with a stable (1,{}) solution", args.k)?;
            }
            for w in &windows {
                writeln!(
                    out,
                    "stable for alpha in ({:.15}, {:.15}): born at phase {:.12}, ends by {} at phase {:.12}",
                    w.alpha_birth,
                    w.alpha_end,
                    w.phase_birth,
                    w.end.as_str(),
                    w.phase_end
                )?;
            }
            if let Some(pd) = windows.first().and_then(|w| w.alpha_pd()) {
                writeln!(out, "alpha_PD = {pd:.15}")?;
            }
        }
    }
    out.flush()?;
    Ok(())
}

fn complex_text(z: Complex) -> String {
    if z.im == 0.0 {
        format!("{:.12}", z.re)
    } else {
        format!("{:.12}{:+.12}i", z.re, z.im)
    }
}

/// A complex number as {"re", "im"}.
pub fn complex_json(z: Complex) -> Value {
    json!({"re": json_num(z.re), "im": json_num(z.im)})
}

/// One (1, k) solution as JSON.
pub fn point_json(p: &FixedPoint) -> Value {
    json!({
        "phase": json_num(p.phase),
        "v": json_num(p.v),
        "df": json_num(p.df),
        "ddf": json_num(p.ddf),
        "dddf": json_num(p.dddf),
        "delta_kappa": json_num(p.delta_kappa),
        "jacobian": p.jacobian.iter().map(|row| row.iter().map(|&x| json_num(x)).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "eigenvalues": p.eigenvalues.iter().map(|&z| complex_json(z)).collect::<Vec<_>>(),
        "flight": p.flight.map_or(Value::Null, json_num),
        "admissible": p.admissible,
        "classification": p.classification.as_str(),
    })
}

fn window_json(w: &StabilityWindow) -> Value {
    json!({
        "alpha_birth": json_num(w.alpha_birth),
        "phase_birth": json_num(w.phase_birth),
        "alpha_end": json_num(w.alpha_end),
        "phase_end": json_num(w.phase_end),
        "end": w.end.as_str(),
    })
}
