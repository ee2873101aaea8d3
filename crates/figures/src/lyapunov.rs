//! `figure lyapunov`: a sweep's bifurcation diagram over its largest Lyapunov exponent
//! per impact, on one axis of the swept parameter. The exponent is a line through the
//! finite values, zero dashed; values whose exponent is −∞ (the orbit sticks: the
//! stick collapses every perturbation) are open circles on the lower edge.

use super::diagram::{spec_caption, Diagram, STICKING_NOTE};
use crate::labels::param_label;
use crate::model::{
    Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN,
};

/// The two panels: (a) the diagram, (b) λ₁ against the same parameter (the diagram's
/// sweep measures exponents).
pub fn lyapunov_figure(diagram: Diagram) -> Figure {
    let spec = diagram.spec().clone();
    let spec = &spec;
    // Runs of finite exponents become unbroken lines; −∞ and missing values break them.
    let mut lines: Vec<Vec<[f64; 2]>> = vec![Vec::new()];
    let mut minus_inf = Vec::new();
    for (value, l) in diagram.exponents() {
        match l {
            Some(l) if l.is_finite() => lines.last_mut().unwrap().push([value, l]),
            other => {
                if other == Some(f64::NEG_INFINITY) {
                    minus_inf.push(value);
                }
                if !lines.last().unwrap().is_empty() {
                    lines.push(Vec::new());
                }
            }
        }
    }
    lines.retain(|l| !l.is_empty());
    let mut top = diagram.into_panel();
    top.letter = Some("(a)".into());
    let finite = lines.iter().flatten().map(|p| p[1]);
    let mut y = Axis::around(
        "$\u{3bb}_1$ per impact",
        finite.chain([0.0, 0.05, -0.05]),
        0.08,
    );
    // Room above the data for the legend.
    y.hi += 0.45 * (y.hi - y.lo);
    let mut bottom = Panel::new(Axis::new(&param_label(spec.param), spec.lo, spec.hi), y);
    bottom.letter = Some("(b)".into());
    bottom.layers.push(Layer::HLine {
        y: 0.0,
        color: Color::GREY,
        dash: Dash::Dashed,
    });
    let floor = bottom.y.lo;
    let mut entries = vec![(
        Swatch::line(Color::BLUE, Dash::Solid),
        "largest exponent $\u{3bb}_1$".to_string(),
    )];
    bottom.layers.push(Layer::Lines {
        name: "lyapunov".into(),
        lines,
        color: Color::BLUE,
        dash: Dash::Solid,
        width: 0.7,
    });
    if !minus_inf.is_empty() {
        bottom.layers.push(Layer::Markers {
            name: "lyapunov -inf".into(),
            points: minus_inf.into_iter().map(|x| [x, floor]).collect(),
            marker: Marker::Circle,
            color: Color::RED,
        });
        entries.push((
            Swatch::marker(Color::RED, Marker::Circle),
            "$\u{3bb}_1$ = \u{2212}\u{221e} (sticks)".to_string(),
        ));
    }
    bottom.legends.push(Legend {
        corner: Corner::TopRight,
        entries,
    });
    Figure {
        name: "lyapunov".into(),
        panels: vec![top, bottom],
        columns: 1,
        caption: vec![
            spec_caption(spec),
            "(b) The largest Lyapunov exponent per impact of each value's orbit: from the eigenvalues of the cycle it settles on, or by QR over 10\u{2074} impacts when it does not settle.".into(),
            STICKING_NOTE.into(),
        ],
        size: (COLUMN, 4.6),
    }
}
