//! `figure manifolds`: the unstable and stable manifolds of a saddle cycle in the phase
//! plane (t̂, v): the unstable manifold red, the stable blue, the + branch of each solid
//! and the − branch dashed (broken where they wrap around the period), the saddle's
//! impacts marked, the legend naming each branch's points, arc length and why it ends.
//! [`overlay_on_basins`] draws them over a basins figure, in the basins' coordinates.

use crate::labels::table_title;
use crate::model::{
    Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN,
};
use bouncemap_engine::attractors::separation::Separation;
use bouncemap_engine::fmt_value as shortest;
use bouncemap_engine::orbits::manifold::{Branch, BranchEnd, Kind, Manifold};
use bouncemap_engine::orbits::periodic::CyclePoint;
use bouncemap_engine::System;

/// Why a branch ends, in a few words.
fn end_words(end: &BranchEnd) -> &'static str {
    match end {
        BranchEnd::Length => "length reached",
        BranchEnd::Sticking { .. } => "sticks",
        BranchEnd::Grazing { .. } => "grazes",
        BranchEnd::NoLanding => "no landing",
        BranchEnd::Release { .. } => "no preimage (release)",
        BranchEnd::Edge => "edge v = f'",
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

/// The colour of a manifold: unstable red, stable blue.
fn colour(kind: Kind) -> Color {
    match kind {
        Kind::Unstable => Color::RED,
        Kind::Stable => Color::BLUE,
    }
}

/// The dash of a branch: + solid, − dashed.
fn dash(side: i8) -> Dash {
    if side > 0 {
        Dash::Solid
    } else {
        Dash::Dashed
    }
}

/// The branches of `ms` as line layers in (t̂, v), with a legend entry each.
pub fn manifold_layers(ms: &[Manifold]) -> (Vec<Layer>, Vec<(Swatch, String)>) {
    branch_layers(ms, colour, 0.8, pieces, |name, b| {
        format!(
            "{name}: {} points, length {:.3}, {}",
            b.points.len(),
            b.length,
            end_words(&b.end)
        )
    })
}

/// A line layer per branch of `ms`, named "kind ±", in `colour` by kind, the branch's
/// points cut into lines by `lines`; with a legend entry each, worded by `label`.
fn branch_layers(
    ms: &[Manifold],
    colour: impl Fn(Kind) -> Color,
    width: f64,
    lines: impl Fn(&[[f64; 2]]) -> Vec<Vec<[f64; 2]>>,
    label: impl Fn(&str, &Branch) -> String,
) -> (Vec<Layer>, Vec<(Swatch, String)>) {
    let mut layers = Vec::new();
    let mut entries = Vec::new();
    for m in ms {
        for b in &m.branches {
            let side = if b.side > 0 { "+" } else { "\u{2212}" };
            let name = format!("{} {side}", m.kind.as_str());
            layers.push(Layer::Lines {
                name: name.clone(),
                lines: lines(&b.points),
                color: colour(m.kind),
                dash: dash(b.side),
                width,
            });
            entries.push((Swatch::line(colour(m.kind), dash(b.side)), label(&name, b)));
        }
    }
    (layers, entries)
}

/// The figure of the manifolds `ms` of the saddle `cycle` of `sys`.
pub fn manifold_figure(sys: &System, cycle: &CyclePoint, ms: &[Manifold]) -> Figure {
    let all_v = ms
        .iter()
        .flat_map(|m| m.branches.iter())
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
    let (layers, mut entries) = manifold_layers(ms);
    panel.layers.extend(layers);
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
    let events = ms.first().map_or(cycle.n, |m| m.events);
    Figure {
        name: "manifolds".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![format!(
            "The manifolds of the saddle ({}, {}) (multipliers {} and {}) in the launch phase $t\u{302}$ and velocity $v$: the unstable manifold (red) grown under the map of {} impact{}, the stable manifold (blue) under its inverse, each from its fundamental domain, every point computed by the exact map or its exact inverse, at most 0.01 apart; each side of the eigenvector a branch (+ solid, \u{2212} dashed).",
            cycle.n,
            cycle.k,
            shortest(a.re),
            shortest(b.re),
            events,
            if events == 1 { "" } else { "s" }
        )],
        size: (COLUMN * 1.6, 3.2),
    }
}

/// How far pairs of starts across a stable manifold split, beside the baseline (see
/// [`bouncemap_engine::attractors::separation`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SplitReport {
    /// Pairs across the stable manifold.
    pub across: Separation,
    /// Pairs at places spread over the picture, at the same offset.
    pub baseline: Separation,
}

/// The colour of a manifold drawn over basins (whose colours are the attractors'):
/// stable black, unstable yellow.
/// A colour with its name for the caption.
type Named = (Color, &'static str);

/// How many saddles' manifolds [`overlay_on_basins`] tells apart by colour.
pub const OVERLAY_SADDLES: usize = 3;

/// The colours of the manifolds of the `which`-th saddle over the basins, (stable,
/// unstable), with their names: apart from each other and from every colour of the
/// basins' palette ([`crate::classes::PALETTE`]).
const OVERLAY_COLOURS: [(Named, Named); OVERLAY_SADDLES] = [
    ((Color::BLACK, "black"), (Color(250, 215, 0), "yellow")),
    (
        (Color(230, 0, 230), "magenta"),
        (Color(0, 210, 220), "cyan"),
    ),
    (
        (Color(70, 0, 110), "dark violet"),
        (Color(110, 220, 0), "lime"),
    ),
];

fn overlay_colour(which: usize) -> impl Fn(Kind) -> Color {
    let ((stable, _), (unstable, _)) = OVERLAY_COLOURS[which % OVERLAY_SADDLES];
    move |kind| match kind {
        Kind::Unstable => unstable,
        Kind::Stable => stable,
    }
}

/// A branch in the basins' coordinates (t̂, w = v − f'(t̂)), cut where the phase
/// wraps or the curve leaves the picture's w range.
fn basin_pieces(points: &[[f64; 2]], sys: &System, w_max: f64) -> Vec<Vec<[f64; 2]>> {
    let mut out = Vec::new();
    for piece in pieces(points) {
        let mut run: Vec<[f64; 2]> = Vec::new();
        for [t, v] in piece {
            let w = v - sys.df(t);
            if (0.0..=w_max).contains(&w) {
                run.push([t, w]);
            } else if !run.is_empty() {
                out.push(std::mem::take(&mut run));
            }
        }
        if !run.is_empty() {
            out.push(run);
        }
    }
    out
}

/// Draw the manifolds `ms` of the `which`-th saddle `cycle` (counted from 0) over the
/// basins figure `fig` of `sys` (w up to `w_max`), in that saddle's colours, with the
/// split counts `split` in the legend and caption. The first saddle's legend entries
/// are the manifolds' names alone; a later saddle's carry its (n, k).
pub fn overlay_on_basins(
    fig: &mut Figure,
    sys: &System,
    w_max: f64,
    (which, cycle): (usize, &CyclePoint),
    ms: &[Manifold],
    split: Option<&SplitReport>,
) {
    let Some(panel) = fig.panels.first_mut() else {
        return;
    };
    let ((stable, stable_name), (_, unstable_name)) = OVERLAY_COLOURS[which % OVERLAY_SADDLES];
    let tag = if which == 0 {
        String::new()
    } else {
        format!("({}, {}) ", cycle.n, cycle.k)
    };
    let (layers, mut entries) = branch_layers(
        ms,
        overlay_colour(which),
        1.0,
        |points| basin_pieces(points, sys, w_max),
        |name, b| {
            format!(
                "{tag}{name} manifold, length {:.3}, {}",
                b.length,
                end_words(&b.end)
            )
        },
    );
    let drawn = layers
        .iter()
        .any(|l| matches!(l, Layer::Lines { lines, .. } if !lines.is_empty()));
    panel.layers.extend(layers);
    let saddle: Vec<[f64; 2]> = cycle
        .phases
        .iter()
        .zip(&cycle.velocities)
        .map(|(&t, &v)| {
            let t = t.rem_euclid(1.0);
            [t, v - sys.df(t)]
        })
        .collect();
    let shown = saddle.iter().any(|&[_, w]| (0.0..=w_max).contains(&w));
    panel.layers.push(Layer::Markers {
        name: "saddle".into(),
        points: saddle,
        marker: Marker::Disc,
        color: stable,
    });
    entries.push((
        Swatch::marker(stable, Marker::Disc),
        format!("saddle ({}, {})", cycle.n, cycle.k),
    ));
    if let Some(legend) = panel.beside.first_mut() {
        // A later saddle's rows make the legend taller than the frame: the figure grows
        // by their height (rows of 1.35 times the legend's type, in inches).
        if which > 0 {
            fig.size.1 += entries.len() as f64 * 1.35 * crate::svg::LEGEND_FONT / 72.0;
        }
        legend.entries.extend(entries);
    }
    let mut text = if which == 0 {
        format!(
            "Over the basins: the manifolds of the saddle ({}, {}), stable {stable_name}, unstable {unstable_name} (+ branch solid, \u{2212} dashed), in the basins' coordinates ($t\u{302}$, $w$), every point computed by the exact map or its exact inverse.",
            cycle.n, cycle.k
        )
    } else {
        format!(
            "Also the manifolds of the saddle ({}, {}), stable {stable_name}, unstable {unstable_name}.",
            cycle.n, cycle.k
        )
    };
    if !shown {
        text.push_str(&format!(
            " Its impacts lie outside the picture's range of w (0 to {}){}.",
            bouncemap_engine::fmt_value(w_max),
            if drawn {
                ""
            } else {
                ", and so do its manifolds as far as they were grown"
            }
        ));
    }
    if let Some(s) = split {
        text.push_str(&format!(
            " Pairs of starts {} apart on either side of {} stable manifold end on different attractors in {} of {} pairs ({:.1}%); pairs the same distance apart at {} places spread over the picture in {} ({:.1}%).",
            crate::format::significant(2.0 * s.across.offset, 3),
            if which == 0 { "the" } else { "its" },
            s.across.split,
            s.across.pairs,
            100.0 * s.across.fraction(),
            s.baseline.pairs,
            s.baseline.split,
            100.0 * s.baseline.fraction()
        ));
    }
    fig.caption.push(text);
}
