//! `bouncemap scaling`: the paper's Fig. 4 and Fig. 5. For each D, least-squares fits
//! log10 ΔT = a_T log10 Δκ + b_T and log10 Δt = a_t log10 Δκ + b_t from (a) exact
//! (2, 2k) solutions, (b) simulated orbits, and (c) the analytic intercepts (printed and
//! corrected), beside the paper's fitted values where it gives them.

use crate::config::flags::ScalingArgs;
use crate::output::records::csv_writer;
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::orbits::scaling::{
    scaling_row, Fit, ScalingRow as Row, EXACT_RANGE, SIM_BOUNCES, SIM_RANGE,
};
use serde::Serialize;
use std::io::Write;

pub fn run(args: &ScalingArgs) -> anyhow::Result<()> {
    let (r, k) = (args.r, args.k);
    let rows: Vec<Row> = args
        .d
        .0
        .iter()
        .map(|&d| scaling_row(d, r, k))
        .collect::<Result<_, _>>()?;
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                serde_json::to_writer(&mut out, &ScalingDoc::new(args, &rows))?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &ScalingRow::HEADER)?;
                for row in &rows {
                    w.serialize(ScalingRow::from(row))?;
                }
                w.flush()?;
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
                            row.paper_fit.map_or([None; 4], |p| {
                                [Some(p.0), Some(p.1), Some(p.2), Some(p.3)]
                            }),
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
                    if let Some(worst) =
                        row.sim_points.iter().map(|p| p.settled_to).reduce(f64::max)
                    {
                        writeln!(
                            out,
                            "{:>8}  simulated orbits settled to {worst:.1e} in phase",
                            row.d
                        )?;
                    }
                }
            }
        }
        Ok(())
    })();
    out.end(written)
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

/// A pair of fits, log10 ΔT and log10 Δt against log10 Δκ.
#[derive(Serialize)]
struct FitsRecord {
    #[serde(rename = "a_T")]
    a_big_t: f64,
    #[serde(rename = "b_T")]
    b_big_t: f64,
    a_t: f64,
    b_t: f64,
    points: Option<usize>,
}

impl FitsRecord {
    fn new(f: Option<(Fit, Fit)>) -> Option<FitsRecord> {
        f.map(|(a, b)| FitsRecord {
            a_big_t: a.slope,
            b_big_t: a.intercept,
            a_t: b.slope,
            b_t: b.intercept,
            points: Some(a.points),
        })
    }
}

/// Intercepts only (the slopes are 1 and ½ by construction).
#[derive(Serialize)]
struct Intercepts {
    #[serde(rename = "b_T")]
    b_big_t: f64,
    b_t: f64,
}

/// A Δκ range of the fits.
#[derive(Serialize)]
struct Range {
    min: f64,
    max: f64,
    points: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_bounces: Option<u64>,
}

/// One simulated orbit's ΔT and Δt.
#[derive(Serialize)]
struct SimulatedRecord {
    delta_kappa: f64,
    #[serde(rename = "delta_T")]
    delta_big_t: f64,
    delta_t: f64,
    settled_to: f64,
    bounces: u64,
}

/// One D of `scaling`'s json.
#[derive(Serialize)]
struct RowRecord {
    d: f64,
    exact: Option<FitsRecord>,
    simulated: Option<FitsRecord>,
    simulated_points: Vec<SimulatedRecord>,
    analytic: Option<Intercepts>,
    paper_analytic: Intercepts,
    paper_fit: Option<FitsRecord>,
}

/// `scaling`'s json.
#[derive(Serialize)]
struct ScalingDoc {
    r: f64,
    k: u32,
    log_base: u32,
    exact_delta_kappa: Range,
    simulated_delta_kappa: Range,
    rows: Vec<RowRecord>,
}

impl ScalingDoc {
    fn new(args: &ScalingArgs, rows: &[Row]) -> ScalingDoc {
        ScalingDoc {
            r: args.r,
            k: args.k,
            log_base: 10,
            exact_delta_kappa: Range {
                min: EXACT_RANGE.0,
                max: EXACT_RANGE.1,
                points: EXACT_RANGE.2,
                max_bounces: None,
            },
            simulated_delta_kappa: Range {
                min: SIM_RANGE.0,
                max: SIM_RANGE.1,
                points: SIM_RANGE.2,
                max_bounces: Some(SIM_BOUNCES),
            },
            rows: rows
                .iter()
                .map(|row| RowRecord {
                    d: row.d,
                    exact: FitsRecord::new(row.exact),
                    simulated: FitsRecord::new(row.sim),
                    simulated_points: row
                        .sim_points
                        .iter()
                        .map(|p| SimulatedRecord {
                            delta_kappa: p.delta_kappa,
                            delta_big_t: p.delta_big_t,
                            delta_t: p.delta_t,
                            settled_to: p.settled_to,
                            bounces: p.bounces,
                        })
                        .collect(),
                    analytic: row.corrected_analytic.map(|a| Intercepts {
                        b_big_t: a.0,
                        b_t: a.1,
                    }),
                    paper_analytic: Intercepts {
                        b_big_t: row.paper_analytic.0,
                        b_t: row.paper_analytic.1,
                    },
                    paper_fit: row.paper_fit.map(|p| FitsRecord {
                        a_big_t: p.0,
                        b_big_t: p.1,
                        a_t: p.2,
                        b_t: p.3,
                        points: None,
                    }),
                })
                .collect(),
        }
    }
}

/// One csv row of `scaling`: one D.
#[derive(Serialize)]
struct ScalingRow {
    d: f64,
    #[serde(rename = "exact_a_T")]
    exact_a_big_t: Option<f64>,
    #[serde(rename = "exact_b_T")]
    exact_b_big_t: Option<f64>,
    exact_a_t: Option<f64>,
    exact_b_t: Option<f64>,
    #[serde(rename = "sim_a_T")]
    sim_a_big_t: Option<f64>,
    #[serde(rename = "sim_b_T")]
    sim_b_big_t: Option<f64>,
    sim_a_t: Option<f64>,
    sim_b_t: Option<f64>,
    #[serde(rename = "analytic_b_T")]
    analytic_b_big_t: Option<f64>,
    analytic_b_t: Option<f64>,
    #[serde(rename = "paper_analytic_b_T")]
    paper_analytic_b_big_t: f64,
    paper_analytic_b_t: f64,
    #[serde(rename = "paper_a_T")]
    paper_a_big_t: Option<f64>,
    #[serde(rename = "paper_b_T")]
    paper_b_big_t: Option<f64>,
    paper_a_t: Option<f64>,
    paper_b_t: Option<f64>,
}

impl ScalingRow {
    const HEADER: [&'static str; 17] = [
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
    ];
}

impl From<&Row> for ScalingRow {
    fn from(row: &Row) -> Self {
        let [ea, eb, ec, ed] = fits4(row.exact);
        let [sa, sb, sc, sd] = fits4(row.sim);
        ScalingRow {
            d: row.d,
            exact_a_big_t: ea,
            exact_b_big_t: eb,
            exact_a_t: ec,
            exact_b_t: ed,
            sim_a_big_t: sa,
            sim_b_big_t: sb,
            sim_a_t: sc,
            sim_b_t: sd,
            analytic_b_big_t: row.corrected_analytic.map(|a| a.0),
            analytic_b_t: row.corrected_analytic.map(|a| a.1),
            paper_analytic_b_big_t: row.paper_analytic.0,
            paper_analytic_b_t: row.paper_analytic.1,
            paper_a_big_t: row.paper_fit.map(|p| p.0),
            paper_b_big_t: row.paper_fit.map(|p| p.1),
            paper_a_t: row.paper_fit.map(|p| p.2),
            paper_b_t: row.paper_fit.map(|p| p.3),
        }
    }
}
