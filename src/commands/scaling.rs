//! `bouncemap scaling`: the paper's Fig. 4 and Fig. 5. For each D, least-squares fits
//! log10 ΔT = a_T log10 Δκ + b_T and log10 Δt = a_t log10 Δκ + b_t from (a) exact
//! (2, 2k) solutions, (b) simulated orbits, and (c) the analytic intercepts (printed and
//! corrected), beside the paper's fitted values where it gives them.

use crate::cli::ScalingArgs;
use crate::engine::orbits::scaling::{
    analytic_intercepts_corrected, analytic_intercepts_paper, exact_fits, least_squares,
    log_spaced, simulated_point, Fit, SimulatedPoint, PAPER_FIG4_FITS,
};
use crate::engine::Table;
use crate::output::{csv_row, json_num, Format};
use serde_json::{json, Value};
use std::io::{self, BufWriter, Write};

/// Δκ range and count of the exact fits.
pub const EXACT_RANGE: (f64, f64, usize) = (1e-9, 1e-7, 9);
/// Δκ range and count of the simulated fits.
pub const SIM_RANGE: (f64, f64, usize) = (1e-6, 1e-5, 5);
/// Impact budget per simulated point (the paper ran 5·10⁶ periods).
pub const SIM_BOUNCES: u64 = 5_000_000;

struct Row {
    d: f64,
    exact: Option<(Fit, Fit)>,
    sim_points: Vec<SimulatedPoint>,
    sim: Option<(Fit, Fit)>,
    paper_analytic: (f64, f64),
    corrected_analytic: Option<(f64, f64)>,
    paper_fit: Option<(f64, f64, f64, f64)>,
}

pub fn run(args: &ScalingArgs) -> anyhow::Result<()> {
    let (r, k) = (args.r, args.k);
    let mut rows = Vec::new();
    for &d in &args.d.0 {
        let table = Table::fd(d)?;
        let exact = exact_fits(
            &table,
            r,
            k,
            &log_spaced(EXACT_RANGE.0, EXACT_RANGE.1, EXACT_RANGE.2),
        );
        let sim_points: Vec<SimulatedPoint> = log_spaced(SIM_RANGE.0, SIM_RANGE.1, SIM_RANGE.2)
            .into_iter()
            .filter_map(|dk| simulated_point(&table, r, k, dk, SIM_BOUNCES))
            .filter(|p| p.delta_t > 0.0 && p.delta_big_t > 0.0)
            .collect();
        let x: Vec<f64> = sim_points.iter().map(|p| p.delta_kappa.log10()).collect();
        let yt: Vec<f64> = sim_points.iter().map(|p| p.delta_big_t.log10()).collect();
        let ys: Vec<f64> = sim_points.iter().map(|p| p.delta_t.log10()).collect();
        let sim = least_squares(&x, &yt).zip(least_squares(&x, &ys));
        let paper_fit = (r == 0.8 && k == 1)
            .then(|| {
                PAPER_FIG4_FITS
                    .iter()
                    .find(|p| (p.0 - d).abs() <= 1e-12 * d)
            })
            .flatten()
            .map(|p| (p.1, p.2, p.3, p.4));
        rows.push(Row {
            d,
            exact,
            sim_points,
            sim,
            paper_analytic: analytic_intercepts_paper(d, r, k),
            corrected_analytic: analytic_intercepts_corrected(&table, r, k)?,
            paper_fit,
        });
    }
    let mut out = BufWriter::new(io::stdout().lock());
    match args.format {
        Format::Json => writeln!(out, "{}", to_json(args, &rows))?,
        Format::Csv => {
            csv_row(
                &mut out,
                &[
                    "d",
                    "exact_a_T",
                    "exact_b_T",
                    "exact_a_t",
                    "exact_b_t",
                    "sim_a_T",
                    "sim_b_T",
                    "sim_a_t",
                    "sim_b_t",
                    "analytic_b_T",
                    "analytic_b_t",
                    "paper_analytic_b_T",
                    "paper_analytic_b_t",
                    "paper_a_T",
                    "paper_b_T",
                    "paper_a_t",
                    "paper_b_t",
                ]
                .map(String::from),
            )?;
            let o = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
            for row in &rows {
                csv_row(
                    &mut out,
                    &[
                        row.d.to_string(),
                        o(row.exact.map(|f| f.0.slope)),
                        o(row.exact.map(|f| f.0.intercept)),
                        o(row.exact.map(|f| f.1.slope)),
                        o(row.exact.map(|f| f.1.intercept)),
                        o(row.sim.map(|f| f.0.slope)),
                        o(row.sim.map(|f| f.0.intercept)),
                        o(row.sim.map(|f| f.1.slope)),
                        o(row.sim.map(|f| f.1.intercept)),
                        o(row.corrected_analytic.map(|a| a.0)),
                        o(row.corrected_analytic.map(|a| a.1)),
                        row.paper_analytic.0.to_string(),
                        row.paper_analytic.1.to_string(),
                        o(row.paper_fit.map(|p| p.0)),
                        o(row.paper_fit.map(|p| p.1)),
                        o(row.paper_fit.map(|p| p.2)),
                        o(row.paper_fit.map(|p| p.3)),
                    ],
                )?;
            }
        }
        Format::Text => {
            writeln!(out, "log10 dT = a_T log10 dkappa + b_T,  log10 dt = a_t log10 dkappa + b_t   (r = {r}, k = {k}, table fd:D)")?;
            writeln!(
                out,
                "exact:     {} exact (2,{}) solutions, dkappa log-spaced in [{:e}, {:e}]",
                EXACT_RANGE.2,
                2 * k,
                EXACT_RANGE.0,
                EXACT_RANGE.1
            )?;
            writeln!(out, "simulated: {} orbits of the exact map from the (1,{k}) solution moved by 1e-3, dkappa log-spaced in [{:e}, {:e}], up to {SIM_BOUNCES} impacts each", SIM_RANGE.2, SIM_RANGE.0, SIM_RANGE.1)?;
            writeln!(out, "analytic:  b_T, b_t of the corrected approximation (f', f''' at alpha_PD); printed: the paper's Eqs. (bT), (bt)")?;
            writeln!(
                out,
                "{:>8}  {:<11} {:>8} {:>8} {:>8} {:>8}",
                "D", "source", "a_T", "b_T", "a_t", "b_t"
            )?;
            let f = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4}"));
            for row in &rows {
                let lines: [(&str, [Option<f64>; 4]); 5] = [
                    ("exact", fits4(row.exact)),
                    ("simulated", fits4(row.sim)),
                    (
                        "analytic",
                        [
                            Some(1.0),
                            row.corrected_analytic.map(|a| a.0),
                            Some(0.5),
                            row.corrected_analytic.map(|a| a.1),
                        ],
                    ),
                    (
                        "printed",
                        [
                            Some(1.0),
                            Some(row.paper_analytic.0),
                            Some(0.5),
                            Some(row.paper_analytic.1),
                        ],
                    ),
                    (
                        "paper fit",
                        row.paper_fit
                            .map_or([None; 4], |p| [Some(p.0), Some(p.1), Some(p.2), Some(p.3)]),
                    ),
                ];
                for (name, v) in lines {
                    if name == "paper fit" && row.paper_fit.is_none() {
                        continue;
                    }
                    writeln!(
                        out,
                        "{:>8}  {:<11} {:>8} {:>8} {:>8} {:>8}",
                        row.d,
                        name,
                        f(v[0]),
                        f(v[1]),
                        f(v[2]),
                        f(v[3])
                    )?;
                }
                if let Some(worst) = row.sim_points.iter().map(|p| p.settled_to).reduce(f64::max) {
                    writeln!(
                        out,
                        "{:>8}  simulated orbits settled to {worst:.1e} in phase",
                        row.d
                    )?;
                }
            }
        }
    }
    out.flush()?;
    Ok(())
}

fn fits4(f: Option<(Fit, Fit)>) -> [Option<f64>; 4] {
    match f {
        Some((a, b)) => [
            Some(a.slope),
            Some(a.intercept),
            Some(b.slope),
            Some(b.intercept),
        ],
        None => [None; 4],
    }
}

fn fit_json(f: Option<(Fit, Fit)>) -> Value {
    f.map_or(Value::Null, |(a, b)| {
        json!({"a_T": json_num(a.slope), "b_T": json_num(a.intercept), "a_t": json_num(b.slope), "b_t": json_num(b.intercept), "points": a.points})
    })
}

fn to_json(args: &ScalingArgs, rows: &[Row]) -> Value {
    json!({
        "r": json_num(args.r),
        "k": args.k,
        "log_base": 10,
        "exact_delta_kappa": {"min": json_num(EXACT_RANGE.0), "max": json_num(EXACT_RANGE.1), "points": EXACT_RANGE.2},
        "simulated_delta_kappa": {"min": json_num(SIM_RANGE.0), "max": json_num(SIM_RANGE.1), "points": SIM_RANGE.2, "max_bounces": SIM_BOUNCES},
        "rows": rows.iter().map(|row| json!({
            "d": json_num(row.d),
            "exact": fit_json(row.exact),
            "simulated": fit_json(row.sim),
            "simulated_points": row.sim_points.iter().map(|p| json!({
                "delta_kappa": json_num(p.delta_kappa), "delta_T": json_num(p.delta_big_t),
                "delta_t": json_num(p.delta_t), "settled_to": json_num(p.settled_to), "bounces": p.bounces,
            })).collect::<Vec<_>>(),
            "analytic": row.corrected_analytic.map_or(Value::Null, |a| json!({"b_T": json_num(a.0), "b_t": json_num(a.1)})),
            "paper_analytic": json!({"b_T": json_num(row.paper_analytic.0), "b_t": json_num(row.paper_analytic.1)}),
            "paper_fit": row.paper_fit.map_or(Value::Null, |p| json!({"a_T": json_num(p.0), "b_T": json_num(p.1), "a_t": json_num(p.2), "b_t": json_num(p.3)})),
        })).collect::<Vec<_>>(),
    })
}
