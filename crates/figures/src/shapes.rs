//! The paper's Fig. 2: F_D, Ḟ_D and F̈_D over one period for representative D, with
//! the breakpoint t̂ = ½ dashed. Each piece is drawn on its own, so the jump of F̈_D at
//! t̂ = 0 and ½ shows as a jump, not as a steep line.

use crate::model::{Axis, Color, Corner, Dash, Figure, Layer, Legend, Panel, Swatch, FULL_WIDTH};
use bouncemap_engine::{EngineError, Table};

/// The values of D shown.
pub const FIG2_D: [f64; 4] = [0.0, 0.1, 0.5, 1.0];
/// Their colours.
const COLORS: [Color; 4] = [Color::BLUE, Color::ORANGE, Color::GREEN, Color::RED];
/// Samples per piece.
const SAMPLES: usize = 200;

/// The polylines of the `order`-th derivative of `table` over [0, 1], one per piece.
pub fn derivative_lines(table: &Table, order: usize) -> Vec<Vec<[f64; 2]>> {
    table
        .pieces()
        .iter()
        .map(|p| {
            (0..=SAMPLES)
                .map(|i| {
                    let t = p.start + (p.end - p.start) * i as f64 / SAMPLES as f64;
                    // The piece's own formula up to its right end.
                    let t_in = if i == SAMPLES { p.end - 1e-12 } else { t };
                    [t, table.jet(t_in)[order]]
                })
                .collect()
        })
        .collect()
}

/// Fig. 2.
pub fn fig2() -> Result<Figure, EngineError> {
    let names = ["$F_D$", "$\u{1e1e}_D$", "$F\u{308}_D$"];
    let tables: Vec<Table> = FIG2_D
        .iter()
        .map(|&d| Table::fd(d))
        .collect::<Result<_, _>>()?;
    let mut panels = Vec::new();
    for (order, name) in names.iter().enumerate() {
        let mut layers = Vec::new();
        let mut ys = Vec::new();
        for ((table, d), color) in tables.iter().zip(FIG2_D).zip(COLORS) {
            let lines = derivative_lines(table, order);
            ys.extend(lines.iter().flatten().map(|q| q[1]));
            layers.push(Layer::Lines {
                name: format!("{} D={d}", ["F_D", "F_D'", "F_D''"][order]),
                lines,
                color,
                dash: Dash::Solid,
                width: 1.0,
            });
        }
        layers.push(Layer::VLine {
            x: 0.5,
            color: Color::BLACK,
            dash: Dash::Dashed,
        });
        let mut panel = Panel::new(
            Axis::new("$t\u{302}$", 0.0, 1.0),
            Axis::around(name, ys, 0.08),
        );
        panel.letter = Some(format!("({})", (b'a' + order as u8) as char));
        panel.layers = layers;
        if order == 0 {
            panel.legends.push(Legend {
                corner: Corner::BottomLeft,
                entries: FIG2_D
                    .iter()
                    .zip(COLORS)
                    .map(|(d, c)| (Swatch::line(c, Dash::Solid), format!("$D$ = {d}")))
                    .collect(),
            });
        }
        panels.push(panel);
    }
    Ok(Figure {
        name: "fig2".into(),
        panels,
        columns: 3,
        caption: vec![
            "$F_D$ and its first and second derivatives over one period for $D$ = 0, 0.1, 0.5 and 1 (piecewise quadratic at $D$ = 0, piecewise cubic otherwise). Dashed: $t\u{302}$ = 1/2."
                .into(),
        ],
        size: (FULL_WIDTH, 2.4),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curves_are_the_paper_formula() {
        // F_D = t̂(t̂ − ½)(D t̂ − 1) on [0, ½), (t̂ − ½)(t̂ − 1)(D t̂ + 1 − D) on [½, 1).
        let d = 0.5;
        let t = Table::fd(d).unwrap();
        let f = |x: f64| {
            if x < 0.5 {
                x * (x - 0.5) * (d * x - 1.0)
            } else {
                (x - 0.5) * (x - 1.0) * (d * x + 1.0 - d)
            }
        };
        for line in derivative_lines(&t, 0) {
            for q in line {
                assert!((q[1] - f(q[0])).abs() < 1e-12, "{q:?}");
            }
        }
        // F'' on the first piece: 6 D t̂ − (2 + D); it jumps at ½.
        let dd = derivative_lines(&t, 2);
        assert_eq!(dd.len(), 2);
        let end = dd[0].last().unwrap();
        assert!((end[1] - (6.0 * d * 0.5 - (2.0 + d))).abs() < 1e-9);
        assert!(
            (dd[1][0][1] - end[1]).abs() > 1.0,
            "the jump at ½ stays a jump"
        );
    }
}
