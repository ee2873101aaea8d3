//! The terminal application's phase plot as a figure: the impacts (t̂, v) of an orbit as
//! density dots.

use super::text::plain;
use crate::model::{Axis, Color, Figure, Layer, Panel, COLUMN};

/// The phase plot of `points` (phase t̂, velocity v after the event), with `caption`
/// (plain text: the system and the orbit) below it.
pub fn phase_view(points: &[(f64, f64)], caption: &str) -> Figure {
    let pts: Vec<[f64; 2]> = points.iter().map(|&(t, v)| [t, v]).collect();
    let mut p = Panel::new(
        Axis::new("$t\u{302}$", 0.0, 1.0),
        Axis::around("$v$", pts.iter().map(|q| q[1]), 0.06),
    );
    p.layers.push(Layer::Density {
        name: "impacts".into(),
        points: pts,
        color: Color::BLACK,
    });
    Figure {
        name: "phase".into(),
        panels: vec![p],
        columns: 1,
        caption: if caption.is_empty() {
            Vec::new()
        } else {
            vec![plain(caption)]
        },
        size: (COLUMN, 2.8),
    }
}
