//! `figure curves`: two-parameter bifurcation curves as a figure, the picture a paper
//! shows: every curve a line, its kind the pattern (period doubling solid, fold
//! dash-dotted, border collision dashed, grazing dotted), its cycle's period the colour (the diagram's
//! period colours); the codimension-two points marked with open circles. [`layers`]
//! gives the same lines for drawing over a plane (`figure plane --curves`), in black.

use super::classes::Class;
use crate::labels::param_label;
use crate::model::{Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch};
use bouncemap_engine::fmt_value as shortest;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::orbits::curves::{CurveKind, Curves, Plane};

/// The pattern of a curve's kind.
pub fn dash(kind: &CurveKind) -> Dash {
    match kind {
        CurveKind::PeriodDoubling => Dash::Solid,
        CurveKind::BorderCollision { .. } => Dash::Dashed,
        CurveKind::Grazing { .. } => Dash::Dotted,
        CurveKind::Fold | CurveKind::Birth => Dash::DashDot,
    }
}

/// The colour of a cycle of n impacts: the diagram's period colours for 1, 2, 4 and 8,
/// the colour of "another period" beyond.
pub fn period_colour(n: usize) -> Color {
    let class = match n {
        1 => Class::Period1,
        2 => Class::Period2,
        4 => Class::Period4,
        8 => Class::Period8,
        _ => Class::Periodic,
    };
    let (r, g, b) = class.rgb();
    Color(r, g, b)
}

fn kind_text(kind: &CurveKind) -> &'static str {
    match kind {
        CurveKind::PeriodDoubling => "period doubling",
        CurveKind::BorderCollision { .. } => "border collision",
        CurveKind::Grazing { .. } => "grazing",
        CurveKind::Fold => "fold",
        CurveKind::Birth => "birth of the pair",
    }
}

/// The curves as layers in a plot with α on x (or on y when `alpha_on_x` is false), and
/// their legend entries: one line layer per curve, coloured by period (or all in
/// `colour`), and one marker layer for the codimension-two points.
pub fn layers(
    c: &Curves,
    alpha_on_x: bool,
    colour: Option<Color>,
) -> (Vec<Layer>, Vec<(Swatch, String)>) {
    let place = |alpha: f64, p: f64| if alpha_on_x { [alpha, p] } else { [p, alpha] };
    let mut out = Vec::new();
    let mut kinds: Vec<&'static str> = Vec::new();
    let mut periods: Vec<usize> = Vec::new();
    for (i, cv) in c.curves.iter().enumerate() {
        let line: Vec<[f64; 2]> = cv.points.iter().map(|q| place(q.alpha, q.p)).collect();
        if line.len() < 2 {
            continue;
        }
        out.push(Layer::Lines {
            name: format!("curve {i}: {} of ({}, {})", cv.kind.as_str(), cv.n, cv.k),
            lines: vec![line],
            color: colour.unwrap_or_else(|| period_colour(cv.n)),
            dash: dash(&cv.kind),
            width: 1.0,
        });
        if !kinds.contains(&kind_text(&cv.kind)) {
            kinds.push(kind_text(&cv.kind));
        }
        if !periods.contains(&cv.n) {
            periods.push(cv.n);
        }
    }
    let mut entries: Vec<(Swatch, String)> = Vec::new();
    let ink = colour.unwrap_or(Color::BLACK);
    for (kind, d) in [
        ("period doubling", Dash::Solid),
        ("fold", Dash::DashDot),
        ("border collision", Dash::Dashed),
        ("grazing", Dash::Dotted),
    ] {
        if kinds.contains(&kind) {
            // Over a plane, beside the closed-form lines: say these are continued.
            let text = match colour {
                Some(_) => format!("{kind} (continued)"),
                None => kind.to_string(),
            };
            entries.push((Swatch::line(ink, d), text));
        }
    }
    if colour.is_none() {
        periods.sort_unstable();
        for n in periods {
            let impacts = if n == 1 { "impact" } else { "impacts" };
            entries.push((
                Swatch::band(period_colour(n)),
                format!("cycle of {n} {impacts}"),
            ));
        }
    }
    if !c.codim2.is_empty() {
        out.push(Layer::Markers {
            name: "codimension-two points".into(),
            points: c.codim2.iter().map(|p| place(p.alpha, p.p)).collect(),
            marker: Marker::Circle,
            color: ink,
        });
        entries.push((
            Swatch::marker(ink, Marker::Circle),
            "codimension-two point".into(),
        ));
    }
    (out, entries)
}

/// The curves of `plane` alone: α across, the second parameter up.
pub fn curves_figure(plane: &Plane, c: &Curves, max_period: usize) -> Figure {
    let mut panel = Panel::new(
        Axis::new(
            &param_label(SweepParam::Alpha),
            plane.alpha.0,
            plane.alpha.1,
        ),
        Axis::new(&param_label(plane.second), plane.window.0, plane.window.1),
    );
    let (layers, entries) = layers(c, true, None);
    panel.layers = layers;
    if !entries.is_empty() {
        // Beside the frame: the curves reach every corner of a plane.
        panel.beside.push(Legend {
            corner: Corner::TopRight,
            entries,
        });
    }
    let family = crate::labels::family_title(&plane.table, plane.second);
    let fixed = match plane.second {
        SweepParam::Table(_) => format!("r = {}", shortest(plane.r)),
        _ => String::new(),
    };
    panel.title = Some(family);
    let pd_border = c
        .codim2
        .iter()
        .filter(|p| p.kind.as_str() == "pd_border")
        .count();
    let mut caption = format!(
        "Two-parameter bifurcation curves of the cycles reached from the (1, 1) solution up to period {max_period}{}: each line is where a multiplier of the cycle is \u{2212}1 (period doubling) or +1 (fold), one of its impacts is at a breakpoint of the table (border collision) or a flight touches the table (grazing), followed by continuation with the cycle solved exactly at every point.",
        if fixed.is_empty() {
            String::new()
        } else {
            format!(", {fixed}")
        }
    );
    if !c.codim2.is_empty() {
        caption.push_str(&format!(
            " Circles: codimension-two points ({pd_border} where a period doubling reaches a breakpoint)."
        ));
    }
    Figure {
        name: "curves".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![caption],
        size: (6.4, 3.6),
    }
}
