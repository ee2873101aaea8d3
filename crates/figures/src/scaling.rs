//! The power laws of the (2, 2k) branch: the lower row of the paper's Fig. 4 (ΔT and
//! Δt against Δκ, with the fits and the paper's printed fits) and its Fig. 5 (the
//! intercepts b_T and b_t against D, with the paper's analytic lines as printed and
//! corrected). The numbers are [`bouncemap_engine::orbits::scaling::scaling_row`]'s,
//! the same as `bouncemap scaling` prints.

use crate::format::fmt_fixed;
use crate::model::{
    Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN, FULL_WIDTH,
};
use bouncemap_engine::orbits::scaling::{
    analytic_intercepts_corrected, analytic_intercepts_paper, log_spaced, Fit, ScalingRow,
    EXACT_RANGE, SIM_RANGE,
};
use bouncemap_engine::{EngineError, Table};

/// The D values of Fig. 5: 13 log-spaced from 0.001 to 1 (`scaling --d 0.001..1:13`).
pub const FIG5_D: (f64, f64, usize) = (0.001, 1.0, 13);

const LOG_DK: &str = "log$_{10}$ $\u{394}\u{3ba}$";

fn line_through(fit: (f64, f64), x0: f64, x1: f64) -> Vec<[f64; 2]> {
    vec![[x0, fit.0 * x0 + fit.1], [x1, fit.0 * x1 + fit.1]]
}

fn fit_text(what: &str, a: f64, b: f64) -> String {
    format!(
        "$\u{394}{what}$: $a_{what}$ = {}, $b_{what}$ = {}",
        fmt_fixed(a, 3),
        fmt_fixed(b, 3)
    )
}

/// One panel of Fig. 4's lower row: log10 ΔT (blue) and log10 Δt (red) against
/// log10 Δκ for one D: exact (2, 2) solutions (discs), simulated orbits (circles),
/// the fit to the exact solutions (solid) and the paper's printed fit (dashed).
pub fn fig4_lower(row: &ScalingRow) -> Panel {
    let exact_t: Vec<[f64; 2]> = row
        .exact_points
        .iter()
        .map(|p| [p.delta_kappa.log10(), p.delta_big_t.log10()])
        .collect();
    let exact_s: Vec<[f64; 2]> = row
        .exact_points
        .iter()
        .map(|p| [p.delta_kappa.log10(), p.delta_t.log10()])
        .collect();
    let sim_t: Vec<[f64; 2]> = row
        .sim_points
        .iter()
        .map(|p| [p.delta_kappa.log10(), p.delta_big_t.log10()])
        .collect();
    let sim_s: Vec<[f64; 2]> = row
        .sim_points
        .iter()
        .map(|p| [p.delta_kappa.log10(), p.delta_t.log10()])
        .collect();
    let all = || exact_t.iter().chain(&exact_s).chain(&sim_t).chain(&sim_s);
    let x0 = EXACT_RANGE.0.log10().min(SIM_RANGE.0.log10()) - 0.25;
    let x1 = EXACT_RANGE.1.log10().max(SIM_RANGE.1.log10()) + 0.25;
    let ys: Vec<f64> = all().map(|p| p[1]).collect();
    let (ylo, yhi) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
            (a.min(y), b.max(y))
        });
    let (ylo, yhi) = if ylo.is_finite() {
        (ylo, yhi)
    } else {
        (-6.0, 0.0)
    };
    let span = yhi - ylo;
    // Room above the points for the legend of the fits.
    let y = Axis::new(
        "log$_{10}$ $\u{394}T$, log$_{10}$ $\u{394}t$",
        ylo - 0.08 * span,
        yhi + 0.8 * span,
    );
    let mut p = Panel::new(Axis::new(LOG_DK, x0, x1), y);
    let mut fits = Vec::new();
    let mut paper_lines = Vec::new();
    type Pair<'a> = (&'a str, Color, Option<Fit>, Option<(f64, f64)>);
    let pairs: [Pair; 2] = [
        (
            "T",
            Color::BLUE,
            row.exact.map(|f| f.0),
            row.paper_fit.map(|f| (f.0, f.1)),
        ),
        (
            "t",
            Color::RED,
            row.exact.map(|f| f.1),
            row.paper_fit.map(|f| (f.2, f.3)),
        ),
    ];
    for (what, color, fit, paper) in pairs {
        if let Some(f) = fit {
            p.layers.push(Layer::Lines {
                name: format!("fit log10 \u{394}{what}"),
                lines: vec![line_through((f.slope, f.intercept), x0, x1)],
                color,
                dash: Dash::Solid,
                width: 0.8,
            });
            fits.push((
                Swatch::line(color, Dash::Solid),
                fit_text(what, f.slope, f.intercept),
            ));
        }
        if let Some(pf) = paper {
            // Lighter, on top of the fit: the two nearly coincide.
            paper_lines.push(Layer::Lines {
                name: format!("paper's fit log10 \u{394}{what}"),
                lines: vec![line_through(pf, x0, x1)],
                color: color.tint(0.5),
                dash: Dash::Dashed,
                width: 0.9,
            });
            fits.push((
                Swatch::line(color.tint(0.5), Dash::Dashed),
                format!("paper: {}, {}", fmt_fixed(pf.0, 3), fmt_fixed(pf.1, 3)),
            ));
        }
    }
    p.layers.extend(paper_lines);
    for (name, points, marker, color) in [
        ("exact log10 \u{394}T", exact_t, Marker::Disc, Color::BLUE),
        ("exact log10 \u{394}t", exact_s, Marker::Disc, Color::RED),
        (
            "simulated log10 \u{394}T",
            sim_t,
            Marker::Circle,
            Color::BLUE,
        ),
        (
            "simulated log10 \u{394}t",
            sim_s,
            Marker::Circle,
            Color::RED,
        ),
    ] {
        p.layers.push(Layer::Markers {
            name: name.into(),
            points,
            marker,
            color,
        });
    }
    fits.push((
        Swatch::marker(Color::BLACK, Marker::Disc),
        "exact (2, 2) solutions".into(),
    ));
    fits.push((
        Swatch::marker(Color::BLACK, Marker::Circle),
        "simulated orbits".into(),
    ));
    p.legends.push(Legend {
        corner: Corner::TopLeft,
        entries: fits,
    });
    p.title = Some(format!("$D$ = {}", row.d));
    p
}

/// Fig. 4: the enlarged diagrams `upper` (a)–(c) above the scaling panels (d)–(f);
/// `upper_caption` (markup lines) describes the diagrams.
pub fn fig4(upper: Vec<Panel>, rows: &[ScalingRow], upper_caption: Vec<String>) -> Figure {
    let mut panels = upper;
    panels.extend(rows.iter().map(fig4_lower));
    for (i, p) in panels.iter_mut().enumerate() {
        p.letter = Some(format!("({})", (b'a' + i as u8) as char));
    }
    Figure {
        name: "fig4".into(),
        panels,
        columns: 3,
        caption: upper_caption
            .into_iter()
            .chain(["(d)\u{2013}(f): $\u{394}T$ (blue) and $\u{394}t$ (red) of the (2, 2) solution against $\u{394}\u{3ba}$ = $\u{3ba}_c$ \u{2212} $f\u{308}$($t\u{302}$*), r = 0.8: exact solutions (discs, \u{394}\u{3ba} from 10\u{207b}\u{2079} to 10\u{207b}\u{2077}), orbits of the impact map (circles, 10\u{207b}\u{2076} to 10\u{207b}\u{2075}), least-squares fits log$_{10}$ $\u{394}T$ = $a_T$ log$_{10}$ $\u{394}\u{3ba}$ + $b_T$ and log$_{10}$ $\u{394}t$ = $a_t$ log$_{10}$ $\u{394}\u{3ba}$ + $b_t$ to the exact solutions (solid) and the paper's printed fits (dashed).".to_string()])
            .collect(),
        size: (FULL_WIDTH, 5.4),
    }
}

/// Fig. 5: b_T (blue) and b_t (red) against D: fits to exact solutions (discs) and to
/// simulated orbits (circles), the paper's Eqs. (bT), (bt) as printed (dashed) and
/// corrected (solid).
pub fn fig5(rows: &[ScalingRow], r: f64, k: u32) -> Result<Figure, EngineError> {
    let ds: Vec<f64> = rows.iter().map(|row| row.d).collect();
    let dmin = ds.iter().copied().fold(f64::INFINITY, f64::min).min(1.0);
    let dmax = ds.iter().copied().fold(0.0, f64::max).max(dmin);
    let (lo, hi) = (dmin / 1.6, (dmax * 1.6).max(dmin * 10.0));
    let mut layers = Vec::new();
    let mut values = Vec::new();
    let marks = |pick: fn(&ScalingRow) -> Option<(Fit, Fit)>, which: usize| -> Vec<[f64; 2]> {
        rows.iter()
            .filter_map(|row| {
                pick(row).map(|f| {
                    [
                        row.d,
                        if which == 0 {
                            f.0.intercept
                        } else {
                            f.1.intercept
                        },
                    ]
                })
            })
            .collect()
    };
    // The analytic lines over the D axis (D ≤ 1: F_D needs it).
    let grid = log_spaced(lo, hi.min(1.0), 80);
    let mut printed = [Vec::new(), Vec::new()];
    let mut corrected = [Vec::new(), Vec::new()];
    for &d in &grid {
        let (bt, bs) = analytic_intercepts_paper(d, r, k);
        printed[0].push([d, bt]);
        printed[1].push([d, bs]);
        if let Some((bt, bs)) = analytic_intercepts_corrected(&Table::fd(d)?, r, k)? {
            corrected[0].push([d, bt]);
            corrected[1].push([d, bs]);
        }
    }
    for (i, (sym, color)) in [("T", Color::BLUE), ("t", Color::RED)]
        .into_iter()
        .enumerate()
    {
        let exact = marks(|r| r.exact, i);
        let sim = marks(|r| r.sim, i);
        values.extend(exact.iter().chain(&sim).map(|p| p[1]));
        values.extend(printed[i].iter().chain(&corrected[i]).map(|p| p[1]));
        layers.push(Layer::Lines {
            name: format!("printed b_{sym}"),
            lines: vec![printed[i].clone()],
            color,
            dash: Dash::Dashed,
            width: 0.8,
        });
        layers.push(Layer::Lines {
            name: format!("corrected b_{sym}"),
            lines: vec![corrected[i].clone()],
            color,
            dash: Dash::Solid,
            width: 0.8,
        });
        layers.push(Layer::Markers {
            name: format!("exact b_{sym}"),
            points: exact,
            marker: Marker::Disc,
            color,
        });
        layers.push(Layer::Markers {
            name: format!("simulated b_{sym}"),
            points: sim,
            marker: Marker::Circle,
            color,
        });
    }
    let mut y = Axis::around("$b_T$, $b_t$", values, 0.06);
    // Room at the top right for the legend.
    y.hi += 0.3 * (y.hi - y.lo);
    let mut p = Panel::new(Axis::log("$D$", lo, hi), y);
    p.layers = layers;
    p.legends.push(Legend {
        corner: Corner::TopRight,
        entries: vec![
            (Swatch::line(Color::BLUE, Dash::Solid), "$b_T$".into()),
            (Swatch::line(Color::RED, Dash::Solid), "$b_t$".into()),
            (
                Swatch::marker(Color::BLACK, Marker::Disc),
                "exact (2, 2) solutions".into(),
            ),
            (
                Swatch::marker(Color::BLACK, Marker::Circle),
                "simulated orbits".into(),
            ),
            (
                Swatch::line(Color::BLACK, Dash::Solid),
                "Eqs. (bT), (bt) corrected".into(),
            ),
            (
                Swatch::line(Color::BLACK, Dash::Dashed),
                "Eqs. (bT), (bt) as printed".into(),
            ),
        ],
    });
    Ok(Figure {
        name: "fig5".into(),
        panels: vec![p],
        columns: 1,
        caption: vec![format!(
            "Intercepts of log$_{{10}}$ $\u{394}T$ = log$_{{10}}$ $\u{394}\u{3ba}$ + $b_T$ and log$_{{10}}$ $\u{394}t$ = \u{bd} log$_{{10}}$ $\u{394}\u{3ba}$ + $b_t$ (r = {r}, k = {k}), fitted to exact (2, 2) solutions and to orbits of the impact map; lines: the paper's analytic result, as printed (dashed) and corrected (solid)."
        )],
        size: (COLUMN, 3.0),
    })
}
