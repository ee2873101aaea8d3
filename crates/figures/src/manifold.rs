//! `figure manifolds`: the unstable manifold of a saddle cycle in the phase plane
//! (t̂, v): each branch a curve in its own colour (broken where it wraps around the
//! period), the saddle's impacts marked, the legend naming each branch's points,
//! arc length and why it ends.

use crate::labels::table_title;
use crate::model::{
    Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN,
};
use bouncemap_engine::fmt_value as shortest;
use bouncemap_engine::orbits::manifold::{BranchEnd, UnstableManifold};
use bouncemap_engine::orbits::periodic::CyclePoint;
use bouncemap_engine::System;

/// Why a branch ends, in a few words.
fn end_words(end: &BranchEnd) -> &'static str {
    match end {
        BranchEnd::Length => "length reached",
        BranchEnd::Sticking { .. } => "sticks",
        BranchEnd::Grazing { .. } => "grazes",
        BranchEnd::NoLanding => "no landing",
        BranchEnd::Discontinuity => "jump",
        BranchEnd::Points => "most points",
    }
}

/// A branch's points in (t̂, v), cut into unbroken pieces where the phase wraps.
fn pieces(points: &[[f64; 2]]) -> Vec<Vec<[f64; 2]>> {
    let mut out: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut last_period = None;
    for p in points {
        let period = p[0].floor();
        let q = [p[0] - period, p[1]];
        if last_period != Some(period) {
            out.push(Vec::new());
            last_period = Some(period);
        }
        out.last_mut().expect("a piece").push(q);
    }
    out
}

/// The figure of the unstable manifold `m` of the saddle `cycle` of `sys`.
pub fn manifold_figure(sys: &System, cycle: &CyclePoint, m: &UnstableManifold) -> Figure {
    let colours = [Color::BLUE, Color::RED];
    let all_v = m
        .branches
        .iter()
        .flat_map(|b| b.points.iter().map(|p| p[1]))
        .chain(cycle.velocities.iter().copied());
    let mut panel = Panel::new(
        Axis::new("$t\u{302}$", 0.0, 1.0),
        Axis::around("$v$", all_v, 0.06),
    );
    panel.title = Some(format!(
        "{}, $\u{3b1}$ = {}, $r$ = {}",
        table_title(sys.table()),
        shortest(sys.alpha()),
        shortest(sys.r())
    ));
    let mut entries = Vec::new();
    for (b, &color) in m.branches.iter().zip(&colours) {
        let side = if b.side > 0 { "+" } else { "\u{2212}" };
        panel.layers.push(Layer::Lines {
            name: format!("branch {side}"),
            lines: pieces(&b.points),
            color,
            dash: Dash::Solid,
            width: 0.8,
        });
        entries.push((
            Swatch::line(color, Dash::Solid),
            format!(
                "branch {side}: {} points, length {:.3}, {}",
                b.points.len(),
                b.length,
                end_words(&b.end)
            ),
        ));
    }
    let saddle: Vec<[f64; 2]> = cycle
        .phases
        .iter()
        .zip(&cycle.velocities)
        .map(|(&t, &v)| [t.rem_euclid(1.0), v])
        .collect();
    panel.layers.push(Layer::Markers {
        name: "saddle".into(),
        points: saddle,
        marker: Marker::Circle,
        color: Color::BLACK,
    });
    entries.push((
        Swatch::marker(Color::BLACK, Marker::Circle),
        format!("saddle ({}, {})", cycle.n, cycle.k),
    ));
    panel.beside.push(Legend {
        corner: Corner::TopRight,
        entries,
    });
    let [a, b] = cycle.multipliers;
    Figure {
        name: "manifolds".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![format!(
            "The unstable manifold of the saddle ({}, {}) (multipliers {} and {}), grown under the map of {} impact{} from its fundamental domain (every point computed by the exact map, at most 0.01 apart), in the launch phase $t\u{302}$ and velocity $v$; each side of the unstable direction a branch.",
            cycle.n,
            cycle.k,
            shortest(a.re),
            shortest(b.re),
            m.events,
            if m.events == 1 { "" } else { "s" }
        )],
        size: (COLUMN * 1.6, 3.2),
    }
}
