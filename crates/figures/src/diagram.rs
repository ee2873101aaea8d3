//! Bifurcation diagrams: the paper's Fig. 3 (six panels, or one), the upper row of its
//! Fig. 4, any sweep (`figure diagram`), and the terminal application's diagram view
//! ([`diagram_view`]).
//!
//! Every recorded event is a dot (t̂ or v against the swept parameter), drawn with the
//! density rendering of [`super::svg`]. Values whose points include a stick or a
//! release (or whose ball comes to rest on the table) are shaded over the whole height,
//! where the paper shades its "inaccurate" region: here sticking is computed exactly,
//! so the caption says sticking. Dashed lines mark t̂ = 0 and 1, the domain of t̂.

use super::text::plain;
use super::{fmt_count, Axis, Color, Dash, Figure, Layer, Panel, COLUMN, FULL_WIDTH};
use bouncemap_engine::grid::SweepParam;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{SweepSpec, ValueResult};
use bouncemap_engine::Table;

/// What the diagram's vertical axis shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DiagramAxis {
    /// The phase t̂ of each event (the paper's diagrams).
    #[default]
    Phase,
    /// The ball's velocity after each event.
    Velocity,
}

/// The swept parameter's symbol, in markup.
pub fn param_label(p: SweepParam) -> &'static str {
    match p {
        SweepParam::Alpha => "$\u{3b1}$",
        SweepParam::R => "$r$",
        SweepParam::D => "$D$",
    }
}

/// The table's name as the paper writes it: F_D with its D, sin 2πt, or the file's
/// name.
pub fn table_title(table: &Table) -> String {
    match table.d() {
        Some(d) => format!("$F_{{{d}}}$"),
        None if table.name() == "sine" => "$F$ = sin 2\u{3c0}$t$".into(),
        None => plain(table.name()),
    }
}

/// Values whose orbit sticks or rests, as spans of the swept parameter (each value
/// covers half the spacing on either side).
fn sticking_spans(spec: &SweepSpec, values: &[&ValueResult]) -> Vec<[f64; 2]> {
    let half = if spec.steps > 1 {
        0.5 * (spec.hi - spec.lo) / (spec.steps - 1) as f64
    } else {
        0.5 * (spec.hi - spec.lo).abs().max(1e-9)
    };
    let mut spans: Vec<[f64; 2]> = Vec::new();
    for v in values {
        if !(v.sticking || matches!(v.outcome, Outcome::Resting { .. })) {
            continue;
        }
        let (a, b) = (v.value - half, v.value + half);
        match spans.last_mut() {
            Some(last) if a <= last[1] + 1e-9 * half.max(1e-300) => last[1] = b,
            _ => spans.push([a, b]),
        }
    }
    spans
}

/// One diagram panel: the values' points against the swept parameter over `window`
/// (the sweep's window if None).
pub fn diagram_panel<'a>(
    spec: &SweepSpec,
    values: impl IntoIterator<Item = &'a ValueResult>,
    window: Option<(f64, f64)>,
    axis: DiagramAxis,
) -> Panel {
    let (lo, hi) = window.unwrap_or((spec.lo, spec.hi));
    let mut values: Vec<&ValueResult> = values.into_iter().collect();
    values.sort_by(|a, b| a.value.total_cmp(&b.value));
    let inside = |x: f64| x >= lo.min(hi) && x <= hi.max(lo);
    let points: Vec<[f64; 2]> = values
        .iter()
        .filter(|v| inside(v.value))
        .flat_map(|v| {
            v.points.iter().map(move |p| {
                [
                    v.value,
                    match axis {
                        DiagramAxis::Phase => p.phase,
                        DiagramAxis::Velocity => p.v,
                    },
                ]
            })
        })
        .collect();
    let spans = sticking_spans(spec, &values);
    let y = match axis {
        DiagramAxis::Phase => Axis::new("$t\u{302}$", -0.06, 1.06),
        DiagramAxis::Velocity => Axis::around("$v$", points.iter().map(|p| p[1]), 0.05),
    };
    let mut panel = Panel::new(Axis::new(param_label(spec.param), lo, hi), y);
    if !spans.is_empty() {
        panel.layers.push(Layer::Bands {
            name: "sticking".into(),
            spans,
            color: Color::STICKING,
        });
    }
    if axis == DiagramAxis::Phase {
        for y in [0.0, 1.0] {
            panel.layers.push(Layer::HLine {
                y,
                color: Color::GREY,
                dash: Dash::Dashed,
            });
        }
    }
    panel.layers.push(Layer::Density {
        name: match axis {
            DiagramAxis::Phase => "phase",
            DiagramAxis::Velocity => "v",
        }
        .into(),
        points,
        color: Color::BLACK,
    });
    panel.title = Some(if spec.param == SweepParam::D {
        "$F_D$".to_string()
    } else {
        table_title(&spec.table)
    });
    panel
}

/// The sweep in words: its fixed parameters, values, transient, kept events and start.
pub fn spec_caption(spec: &SweepSpec) -> String {
    let fixed = match spec.param {
        SweepParam::Alpha => format!("r = {}", spec.r),
        SweepParam::R => format!("\u{3b1} = {}", spec.alpha),
        SweepParam::D => format!("\u{3b1} = {}, r = {}", spec.alpha, spec.r),
    };
    let param = match spec.param {
        SweepParam::Alpha => "\u{3b1}",
        SweepParam::R => "r",
        SweepParam::D => "D",
    };
    let start = if spec.initial.near_fixed_point {
        "each started near the (1, 1) solution".to_string()
    } else {
        format!(
            "each started at t\u{302}0 = {}{}",
            spec.initial.t0,
            match spec.initial.v0 {
                Some(v) => format!(", v0 = {v}"),
                None => String::new(),
            }
        )
    };
    let warm = match spec.warm {
        bouncemap_engine::sweep::Warm::Off => "",
        _ => ", continued from its neighbour",
    };
    let table = if spec.param == SweepParam::D {
        "fd:D"
    } else {
        spec.table.name()
    };
    plain(&format!(
        "{table}, {fixed}: the last {} events before t = {} for each of {} values of {param} in [{}, {}], {start}{warm}.",
        spec.keep,
        fmt_count(spec.transient),
        spec.steps,
        spec.lo,
        spec.hi,
    ))
}

/// The line explaining the shading and the dashed lines.
pub const STICKING_NOTE: &str = "Shaded: values whose orbit sticks to the table (stick and release are computed exactly). Dashed: $t\u{302}$ = 0 and 1, the domain of $t\u{302}$.";

/// One sweep as a one-column figure (`figure diagram`, `figure fig3a` …).
pub fn diagram_figure(name: &str, spec: &SweepSpec, values: &[ValueResult]) -> Figure {
    let mut panel = diagram_panel(spec, values, None, DiagramAxis::Phase);
    let fixed = match spec.param {
        SweepParam::Alpha => format!("$r$ = {}", spec.r),
        SweepParam::R => format!("$\u{3b1}$ = {}", spec.alpha),
        SweepParam::D => format!("$\u{3b1}$ = {}, $r$ = {}", spec.alpha, spec.r),
    };
    if let Some(t) = &panel.title {
        panel.title = Some(format!("{t}, {fixed}"));
    }
    Figure {
        name: name.into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![spec_caption(spec), STICKING_NOTE.into()],
        size: (COLUMN, 2.9),
    }
}

/// The terminal application's diagram as it is on screen: `values` over `window`
/// (None: the sweep's), phase or velocity, with `caption` (plain text: the parameters)
/// below it.
pub fn diagram_view<'a>(
    spec: &SweepSpec,
    values: impl IntoIterator<Item = &'a ValueResult>,
    window: Option<(f64, f64)>,
    axis: DiagramAxis,
    caption: &str,
) -> Figure {
    let panel = diagram_panel(spec, values, window, axis);
    let mut lines = vec![plain(caption), spec_caption(spec)];
    if axis == DiagramAxis::Phase {
        lines.push(STICKING_NOTE.into());
    }
    Figure {
        name: "diagram".into(),
        panels: vec![panel],
        columns: 1,
        caption: lines,
        size: (COLUMN, 2.9),
    }
}

/// Fig. 3: the six panels (a)–(f), each a sweep with its results.
pub fn fig3(panels: &[(SweepSpec, Vec<ValueResult>)]) -> Figure {
    let mut out = Vec::new();
    for (i, (spec, values)) in panels.iter().enumerate() {
        let mut p = diagram_panel(spec, values, None, DiagramAxis::Phase);
        p.letter = Some(format!("({})", (b'a' + i as u8) as char));
        out.push(p);
    }
    let caption = match panels.first() {
        Some((s, _)) => vec![
            plain(&format!(
                "Bifurcation diagrams, r = {}: the last {} events before t = {} for each of {} values of \u{3b1}, each started near the (1, 1) solution.",
                s.r,
                s.keep,
                fmt_count(s.transient),
                s.steps
            )),
            STICKING_NOTE.into(),
        ],
        None => Vec::new(),
    };
    Figure {
        name: "fig3".into(),
        panels: out,
        columns: 3,
        caption,
        size: (FULL_WIDTH, 4.8),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::map::EventKind;
    use bouncemap_engine::run::Point as SweepPoint;

    fn value(index: usize, value: f64, sticking: bool) -> ValueResult {
        ValueResult {
            index,
            value,
            complete: true,
            points: vec![SweepPoint {
                phase: 0.25,
                v: 0.5,
                kind: if sticking {
                    EventKind::Stick
                } else {
                    EventKind::Impact
                },
            }],
            outcome: Outcome::Unsettled,
            sticking,
            events: 1,
            lyapunov: None,
            attractors: Vec::new(),
            precision: None,
        }
    }

    #[test]
    fn sticking_values_make_joined_bands() {
        let spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.0,
            1.0,
            11,
        );
        let vals: Vec<ValueResult> = (0..11)
            .map(|i| value(i, i as f64 / 10.0, (3..=5).contains(&i) || i == 8))
            .collect();
        let refs: Vec<&ValueResult> = vals.iter().collect();
        let spans = sticking_spans(&spec, &refs);
        assert_eq!(spans.len(), 2);
        assert!((spans[0][0] - 0.25).abs() < 1e-12 && (spans[0][1] - 0.55).abs() < 1e-12);
        assert!((spans[1][0] - 0.75).abs() < 1e-12 && (spans[1][1] - 0.85).abs() < 1e-12);
        let p = diagram_panel(&spec, &vals, Some((0.2, 0.6)), DiagramAxis::Phase);
        let Some(Layer::Density { points, .. }) = p.layers.last() else {
            panic!("the points come last, on top")
        };
        assert_eq!(points.len(), 5, "only the values inside the window");
    }

    #[test]
    fn titles_name_the_table_as_the_paper_does() {
        assert_eq!(table_title(&Table::fd(0.1).unwrap()), "$F_{0.1}$");
        assert_eq!(table_title(&Table::fd(0.0).unwrap()), "$F_{0}$");
        assert!(table_title(&Table::sine()).contains("sin"));
    }
}
