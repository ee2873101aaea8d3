//! `figure attractors`: attractors followed along α. (a) A bifurcation diagram whose
//! points (each attractor's cycle events, or the cells an unsettled orbit visits) are
//! coloured by the attractor they belong to, not by period; (b) the basin fractions
//! stacked in the same colours, the starts not run to an attractor in grey on top, the
//! basin entropy S_b as a black line, births (filled) and deaths (open circles) on the
//! upper edge. Attractors are numbered in order of appearance along α, as
//! `bouncemap attractors` numbers them.
//! [`mark_crises`] marks located crises on it.

use crate::basins::{is_attractor, kind_text};
use crate::classes::{attractor_colour, REST};
use crate::labels::table_title;
use crate::model::{
    Axis, Color, Corner, Dash, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN,
};
use bouncemap_engine::attractors::crisis::{Crisis, Located, Sighting};
use bouncemap_engine::attractors::global::{Cause, ChangeKind, Continuation, GlobalSpec, Member};
use bouncemap_engine::fmt_value as shortest;

/// An attractor at one α for people: kind and (n, k), or that double precision leaves
/// its length open.
pub fn describe_member(m: &Member) -> String {
    kind_text(m.kind, m.period(), m.unresolved())
}

/// Decimals that show an α of `spec`'s window to one digit past the first its step
/// changes (6 for a single value): how a continuation's α values are written for
/// people (csv and json write the grid's doubles exactly).
pub fn alpha_decimals(spec: &GlobalSpec) -> usize {
    if spec.steps > 1 {
        let step = (spec.hi - spec.lo) / (spec.steps - 1) as f64;
        ((-step.log10()).ceil().max(0.0) as usize + 1).min(17)
    } else {
        6
    }
}

/// What the exact map says of an attractor's cycle at the α value where the
/// attractor is not seen, for people ("at α: …").
pub fn cause_text(c: &Cause) -> String {
    match c {
        Cause::Unstable { at, multiplier } => {
            let m = if multiplier.im == 0.0 {
                format!("{:.4}", multiplier.re)
            } else {
                format!("{:.4} \u{b1} {:.4}i", multiplier.re, multiplier.im.abs())
            };
            format!("its cycle is unstable ({at}, multiplier {m})")
        }
        Cause::Gone => "no such cycle (a fold, border collision or grazing between)".into(),
        Cause::Missed => "its cycle is stable too (missed by the grid, no bifurcation)".into(),
        Cause::Crisis => "chaotic with no local bifurcation: a crisis".into(),
        Cause::Untested => "no local test (not a cycle of impacts)".into(),
    }
}

/// Attractors the legend names at most (the largest basins); the others are summed in
/// one line.
pub const LEGEND_TRACKS: usize = 8;

/// The two panels of a complete continuation.
pub fn attractors_figure(cont: &Continuation) -> Figure {
    let spec = cont.spec();
    let steps = cont.steps();
    let x = || Axis::new("$\u{3b1}$", spec.lo, spec.hi);
    let colour = |track: usize, m: &Member| {
        if is_attractor(m.kind) {
            attractor_colour(track + 1)
        } else {
            REST
        }
    };
    // (a) Every member's points, one layer per attractor.
    let mut top = Panel::new(x(), Axis::new("$t\u{302}$", -0.06, 1.06));
    top.letter = Some("(a)".into());
    top.title = Some(format!(
        "{}, $r$ = {}",
        table_title(spec.sys.table()),
        shortest(spec.sys.r())
    ));
    let tracks = cont.tracks();
    let mut largest = vec![0.0f64; tracks.len()];
    let mut first_kind: Vec<Option<String>> = vec![None; tracks.len()];
    let mut last_kind: Vec<Option<String>> = vec![None; tracks.len()];
    // A cycle's few events as discs; the many cells of an unsettled orbit as dots.
    let mut points: Vec<Vec<[f64; 2]>> = vec![Vec::new(); tracks.len()];
    let mut cells: Vec<Vec<[f64; 2]>> = vec![Vec::new(); tracks.len()];
    let mut colours = vec![REST; tracks.len()];
    for s in steps {
        for m in &s.members {
            let cycle = m.events.is_some() || m.precision.is_some();
            let to = if cycle { &mut points } else { &mut cells };
            to[m.track].extend(m.points.iter().map(|p| [s.alpha, p.0]));
            largest[m.track] = largest[m.track].max(m.fraction);
            first_kind[m.track].get_or_insert_with(|| describe_member(m));
            last_kind[m.track] = Some(describe_member(m));
            colours[m.track] = colour(m.track, m);
        }
    }
    for (t, (pts, dots)) in points.into_iter().zip(cells).enumerate() {
        if !dots.is_empty() {
            top.layers.push(Layer::Density {
                name: format!("attractor {} cells", t + 1),
                points: dots,
                color: colours[t],
            });
        }
        if !pts.is_empty() {
            top.layers.push(Layer::Markers {
                name: format!("attractor {}", t + 1),
                points: pts,
                marker: Marker::Disc,
                color: colours[t],
            });
        }
    }
    // (b) Fractions stacked in attractor order, then the not-settled share.
    let mut bottom = Panel::new(x(), Axis::new("basin fraction, $S_b$", 0.0, 1.12));
    bottom.letter = Some("(b)".into());
    let mut below: Vec<f64> = vec![0.0; steps.len()];
    for (t, &color) in colours.iter().enumerate() {
        let (mut lower, mut upper) = (Vec::new(), Vec::new());
        for (i, s) in steps.iter().enumerate() {
            let f: f64 = s
                .members
                .iter()
                .filter(|m| m.track == t)
                .map(|m| m.fraction)
                .sum();
            lower.push([s.alpha, below[i]]);
            below[i] += f;
            upper.push([s.alpha, below[i]]);
        }
        bottom.layers.push(Layer::Area {
            name: format!("attractor {} fraction", t + 1),
            lower,
            upper,
            color,
        });
    }
    let unsettled: Vec<f64> = steps.iter().map(|s| s.not_settled_fraction()).collect();
    if unsettled.iter().any(|&f| f > 0.0) {
        bottom.layers.push(Layer::Area {
            name: "not settled".into(),
            lower: steps
                .iter()
                .zip(&below)
                .map(|(s, &b)| [s.alpha, b])
                .collect(),
            upper: steps
                .iter()
                .zip(below.iter().zip(&unsettled))
                .map(|(s, (&b, &u))| [s.alpha, b + u])
                .collect(),
            color: Color::GREY,
        });
    }
    let entropy: Vec<[f64; 2]> = steps
        .iter()
        .filter_map(|s| s.entropy.map(|e| [s.alpha, e.s_b]))
        .collect();
    bottom.layers.push(Layer::Lines {
        name: "basin entropy S_b".into(),
        lines: vec![entropy],
        color: Color::BLACK,
        dash: Dash::Solid,
        width: 0.8,
    });
    // Births and deaths on the upper edge, at the middle of the step they fall in.
    let edge = 1.06;
    let (mut births, mut deaths) = (Vec::new(), Vec::new());
    for c in cont.changes() {
        let at = 0.5 * (steps[c.step - 1].alpha + steps[c.step].alpha);
        match c.what {
            ChangeKind::Birth => births.push([at, edge]),
            ChangeKind::Death { .. } => deaths.push([at, edge]),
            _ => {}
        }
    }
    let mut entries = vec![(
        Swatch::line(Color::BLACK, Dash::Solid),
        "basin entropy $S_b$".to_string(),
    )];
    if !births.is_empty() {
        bottom.layers.push(Layer::Markers {
            name: "births".into(),
            points: births,
            marker: Marker::Disc,
            color: Color::BLACK,
        });
        entries.push((Swatch::marker(Color::BLACK, Marker::Disc), "birth".into()));
    }
    if !deaths.is_empty() {
        bottom.layers.push(Layer::Markers {
            name: "deaths".into(),
            points: deaths,
            marker: Marker::Circle,
            color: Color::BLACK,
        });
        entries.push((
            Swatch::marker(Color::BLACK, Marker::Circle),
            "death or merger".into(),
        ));
    }
    let decimals = alpha_decimals(spec);
    let alpha = |a: f64| format!("{a:.decimals$}");
    // The attractors beside the diagram: the largest basins first.
    let mut order: Vec<usize> = (0..tracks.len()).collect();
    order.sort_by(|&a, &b| largest[b].total_cmp(&largest[a]).then(a.cmp(&b)));
    let mut named: Vec<(Swatch, String)> = order
        .iter()
        .take(LEGEND_TRACKS)
        .map(|&t| {
            let tr = &tracks[t];
            (
                Swatch::band(colours[t]),
                format!(
                    "{}: {}, {}\u{2013}{}, \u{2264}{:.0}%",
                    t + 1,
                    // What it is first, and last where that differs.
                    match (&first_kind[t], &last_kind[t]) {
                        (Some(a), Some(b)) if a != b => format!("{a} \u{2192} {b}"),
                        (a, _) => a.clone().unwrap_or_default(),
                    },
                    alpha(steps[tr.first].alpha),
                    alpha(steps[tr.last].alpha),
                    100.0 * largest[t]
                ),
            )
        })
        .collect();
    if tracks.len() > LEGEND_TRACKS {
        named.push((
            Swatch::band(Color::GREY),
            format!("{} more attractors", tracks.len() - LEGEND_TRACKS),
        ));
    }
    top.beside.push(Legend {
        corner: Corner::TopRight,
        entries: named,
    });
    bottom.beside.push(Legend {
        corner: Corner::TopRight,
        entries,
    });
    Figure {
        name: "attractors".into(),
        panels: vec![top, bottom],
        columns: 1,
        caption: vec![
            format!(
                "(a) The attractors found at {} values of $\u{3b1}$ from {}\u{d7}{} starts each (the same box at every value, transient {} table periods), each in its own colour: a cycle's impact phases, or the cells an unsettled orbit visits. Attractors at neighbouring values are one when their point sets lie within 0.05 of each other, or when the points of one lead to the other and nothing else continues either; numbered in order of appearance.",
                spec.steps, spec.nx, spec.ny, spec.settle.transient
            ),
            "(b) The share of the starts that ends on each, stacked in the same colours (grey: starts not run to an attractor), and the basin entropy $S_b$ (boxes of 5\u{d7}5 starts). Above: births (filled) and deaths or mergers (open), between the two values where they are seen.".into(),
        ],
        size: (2.0 * COLUMN, 5.6),
    }
}

/// Mark the located crises `ls` on an attractors figure `fig`: a vertical line in both
/// panels at each crisis (the middle of its bracket), dashed where an attractor is
/// destroyed and dotted where it jumps in size, a legend entry naming the attractor,
/// the bracket and the saddle, and a sentence of caption.
pub fn mark_crises(fig: &mut Figure, ls: &[Located]) {
    let found: Vec<(&Located, &Crisis)> = ls
        .iter()
        .filter_map(|l| l.result.as_ref().ok().map(|c| (l, c)))
        .collect();
    if found.is_empty() {
        return;
    }
    let jump = |l: &Located| matches!(l.sighting, Sighting::Jump(_));
    let dash = |l: &Located| if jump(l) { Dash::Dotted } else { Dash::Dashed };
    for (k, panel) in fig.panels.iter_mut().enumerate() {
        let (lo, hi) = (panel.y.lo, panel.y.hi);
        for (l, c) in &found {
            let a = 0.5 * (c.lo + c.hi);
            panel.layers.push(Layer::Lines {
                name: format!("crisis of attractor {}", l.track + 1),
                lines: vec![vec![[a, lo], [a, hi]]],
                color: Color::BLACK,
                dash: dash(l),
                width: 0.8,
            });
        }
        if k == 0 {
            if let Some(legend) = panel.beside.first_mut() {
                for (l, c) in &found {
                    let saddle = c
                        .saddle
                        .as_ref()
                        .map(|s| format!(", saddle ({}, {})", s.cycle.n, s.cycle.k))
                        .unwrap_or_default();
                    let what = if jump(l) { "jump" } else { "crisis" };
                    legend.entries.push((
                        Swatch::line(Color::BLACK, dash(l)),
                        format!("{what} of {}: {}{saddle}", l.track + 1, crisis_alpha(c)),
                    ));
                }
            }
        }
    }
    let destroyed = found.iter().filter(|(l, _)| !jump(l)).count();
    let kinds = [
        (
            destroyed,
            "dashed",
            "the crisis where a chaotic attractor is destroyed",
            "the crises where chaotic attractors are destroyed",
        ),
        (
            found.len() - destroyed,
            "dotted",
            "an interior crisis, where a chaotic attractor jumps in size and goes on",
            "interior crises, where chaotic attractors jump in size and go on",
        ),
    ];
    let what: Vec<String> = kinds
        .iter()
        .filter(|k| k.0 > 0)
        .map(|&(n, line, one, many)| format!("{line}, {}", if n == 1 { one } else { many }))
        .collect();
    fig.caption.push(format!(
        "{}; each located by bisection in $\u{3b1}$ (orbits from points of the attractor stay near it below, leave its neighbourhood above) and named by the saddle cycle the leaving orbits pass whose stable manifold the unstable manifold of a saddle in the attractor first crosses as $\u{3b1}$ rises (where none is crossed, the one nearest the attractor).",
        capitalised(&what.join("; "))
    ));
}

/// `s` with its first letter a capital.
fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}

/// A crisis's bracket for a legend: its middle, ± half its width.
fn crisis_alpha(c: &Crisis) -> String {
    let half = 0.5 * (c.hi - c.lo);
    let digits = (-(half.max(1e-16)).log10()).ceil().max(0.0) as usize + 1;
    format!(
        "$\u{3b1}$ = {:.digits$} \u{b1} {}",
        0.5 * (c.lo + c.hi),
        crate::format::significant(half, 2)
    )
}
