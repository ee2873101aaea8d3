//! `figure plane`: a two-parameter map as a figure. Every pixel is a cell coloured by
//! its orbit's class (the diagram's period colours), the analytic curves drawn over it
//! (α_birth, α_PD of the (1, 1) solution, the (2, 2) border collision), a legend with
//! each class's share of the pixels.

use super::diagram::{param_label, table_title};
use super::{Axis, Color, Corner, Dash, Figure, Layer, Legend, Panel, Swatch};
use crate::output::classes::Class;
use crate::output::plane_file::{rows, NO_LANDING};
use crate::output::text::shortest;
use bouncemap_engine::plane::{Curves, Pixel, PlaneSpec};
use bouncemap_engine::sweep::SweepParam;

/// The colour of a class in print (period 1 to 8 in hues that stay apart, sticking
/// the paper's light blue, chaos dark).
pub fn colour(c: Class) -> Color {
    match c {
        Class::Period1 => Color(31, 89, 180),
        Class::Period2 => Color(230, 120, 20),
        Class::Period4 => Color(44, 150, 44),
        Class::Period8 => Color(204, 37, 41),
        Class::Periodic => Color(140, 86, 180),
        Class::Sticking => Color::STICKING,
        Class::Chaotic => Color(40, 40, 40),
        Class::Unresolved => Color(175, 175, 175),
    }
}

/// Where the ball never lands (or rests).
const NO_LANDING_COLOUR: Color = Color(235, 235, 235);

/// The figure of a complete plane.
pub fn plane_figure(spec: &PlaneSpec, pixels: &[Option<Pixel>], curves: Option<&Curves>) -> Figure {
    let step = |a: &bouncemap_engine::plane::Axis| {
        if a.n > 1 {
            (a.hi - a.lo) / (a.n - 1) as f64
        } else {
            (a.hi - a.lo).abs().max(1e-3)
        }
    };
    let (dx, dy) = (step(&spec.x), step(&spec.y));
    let mut by_class: Vec<(String, Vec<[f64; 2]>)> = Class::ALL
        .iter()
        .map(|c| (c.name().to_string(), Vec::new()))
        .chain([(NO_LANDING.to_string(), Vec::new())])
        .collect();
    let mut total = 0usize;
    for row in rows(spec, pixels) {
        total += 1;
        if let Some(slot) = by_class.iter_mut().find(|(n, _)| *n == row.class) {
            slot.1.push([row.x, row.y]);
        }
    }
    let mut panel = Panel::new(
        Axis::new(
            param_label(spec.x.param),
            spec.x.lo - dx / 2.0,
            spec.x.hi + dx / 2.0,
        ),
        Axis::new(
            param_label(spec.y.param),
            spec.y.lo - dy / 2.0,
            spec.y.hi + dy / 2.0,
        ),
    );
    let mut entries = Vec::new();
    for (name, centres) in by_class {
        if centres.is_empty() {
            continue;
        }
        let color = Class::from_name(&name).map_or(NO_LANDING_COLOUR, colour);
        let share = 100.0 * centres.len() as f64 / total.max(1) as f64;
        let label = match Class::from_name(&name) {
            Some(c) => describe(c),
            None => "no landing or at rest".to_string(),
        };
        entries.push((Swatch::band(color), format!("{label} ({share:.1}%)")));
        panel.layers.push(Layer::Cells {
            name,
            centres,
            size: [dx, dy],
            color,
        });
    }
    let mut curve_entries = Vec::new();
    if let Some(c) = curves {
        for ((name, values), (dash, text)) in c.named().into_iter().zip([
            (Dash::Dotted, "$\u{3b1}$ birth of (1, 1)"),
            (Dash::Solid, "$\u{3b1}_{PD}$ of (1, 1)"),
            (Dash::Dashed, "border collision of (2, 2)"),
        ]) {
            let mut lines: Vec<Vec<[f64; 2]>> = vec![Vec::new()];
            for (&other, a) in c.values.iter().zip(values) {
                match a {
                    Some(a) => {
                        let p = if c.alpha_on_x {
                            [*a, other]
                        } else {
                            [other, *a]
                        };
                        lines.last_mut().unwrap().push(p);
                    }
                    None => lines.push(Vec::new()),
                }
            }
            lines.retain(|l| l.len() > 1);
            // Only curves that pass through the picture are drawn and named.
            let (xa, ya) = (&panel.x, &panel.y);
            let inside =
                |p: &[f64; 2]| (xa.lo..=xa.hi).contains(&p[0]) && (ya.lo..=ya.hi).contains(&p[1]);
            if !lines.iter().flatten().any(inside) {
                continue;
            }
            panel.layers.push(Layer::Lines {
                name: name.to_string(),
                lines,
                color: Color::BLACK,
                dash,
                width: 0.9,
            });
            curve_entries.push((Swatch::line(Color::BLACK, dash), text.to_string()));
        }
    }
    // The classes bottom right and the curves top left: in the paper's planes those
    // corners are uniform (sticking, period 1).
    panel.legends.push(Legend {
        corner: Corner::BottomRight,
        entries,
    });
    if !curve_entries.is_empty() {
        panel.legends.push(Legend {
            corner: Corner::TopLeft,
            entries: curve_entries,
        });
    }
    panel.title = Some(match (spec.x.param, spec.y.param) {
        (SweepParam::D, _) | (_, SweepParam::D) => "$F_D$".to_string(),
        _ => table_title(&spec.table),
    });
    let fixed: Vec<String> = [SweepParam::Alpha, SweepParam::R]
        .into_iter()
        .filter(|p| *p != spec.x.param && *p != spec.y.param)
        .map(|p| match p {
            SweepParam::Alpha => format!("α = {}", shortest(spec.alpha)),
            _ => format!("r = {}", shortest(spec.r)),
        })
        .collect();
    Figure {
        name: "plane".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![format!(
            "{}\u{d7}{} pixels, {}; each pixel's orbit started {} and followed for up to {} table periods (early stop on cycles), coloured by what it settles on; chaotic: not settled with largest Lyapunov exponent above 10\u{207b}\u{00b3}. Lines: the analytic curves of the (1, 1) and (2, 2) solutions.",
            spec.x.n,
            spec.y.n,
            fixed.join(", "),
            match spec.start {
                bouncemap_engine::plane::PlaneStart::NearFixedPoint => "next to the (1, 1) solution",
                bouncemap_engine::plane::PlaneStart::Cold => "from the cold start",
            },
            spec.transient
        )],
        size: (5.0, 3.4),
    }
}

/// A class in words for the legend.
fn describe(c: Class) -> String {
    match c {
        Class::Period1 => "period 1".into(),
        Class::Period2 => "period 2".into(),
        Class::Period4 => "period 4".into(),
        Class::Period8 => "period 8".into(),
        Class::Periodic => "other periods".into(),
        Class::Sticking => "sticking".into(),
        Class::Chaotic => "chaotic".into(),
        Class::Unresolved => "unresolved".into(),
    }
}
