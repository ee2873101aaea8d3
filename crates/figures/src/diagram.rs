//! Bifurcation diagrams: the paper's Fig. 3 (six panels, or one), the upper row of its
//! Fig. 4, any sweep (`figure diagram`), and the terminal application's diagram view
//! ([`diagram_view`]).
//!
//! Every recorded event is a dot (t̂ or v against the swept parameter), drawn with the
//! density rendering of [`super::svg`]. A [`Diagram`] takes a sweep's values in as they
//! complete, so a figure of any sweep holds the picture, not the sweep. Values whose points include a stick or a
//! release (or whose ball comes to rest on the table) are shaded over the whole height,
//! where the paper shades its "inaccurate" region: here sticking is computed exactly,
//! so the caption says sticking. Dashed lines mark t̂ = 0 and 1, the domain of t̂.

use super::classes::{self, Class};
use super::text::plain;
use crate::format::fmt_count;
use crate::labels::{family_title, free_name, param_label, param_symbol};
use crate::model::{
    Axis, Color, Corner, Dash, DensityGrid, Figure, Layer, Legend, Marker, Panel, Swatch, COLUMN,
    FULL_WIDTH,
};
use bouncemap_engine::fmt_value as shortest;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{SweepSpec, ValueResult};

/// What the diagram's vertical axis shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DiagramAxis {
    /// The phase t̂ of each event (the paper's diagrams).
    #[default]
    Phase,
    /// The ball's velocity after each event.
    Velocity,
}

/// What a diagram's colours show (the terminal's `c` key cycles them; an export draws
/// what the screen shows).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Colouring {
    /// The class of each value's orbit (period 1, 2, 4, 8, other, sticking, chaos):
    /// [`Class::rgb`].
    #[default]
    Class,
    /// With several starts: the attractor each point lies on (1 = largest basin), in
    /// the basins' colours ([`crate::classes::attractor_colour`]).
    Attractor,
    /// Hit density only (the paper's black dots).
    Density,
}

/// Attractors coloured apart (1 … 8, the eighth shared by the rest).
pub const ATTRACTOR_LABELS: usize = 8;

impl Colouring {
    /// The next colouring (the `c` key): attractors only while all attractors are
    /// shown.
    pub fn next(self, all_attractors: bool) -> Colouring {
        match (self, all_attractors) {
            (Colouring::Class, true) => Colouring::Attractor,
            (Colouring::Class, false) | (Colouring::Attractor, _) => Colouring::Density,
            (Colouring::Density, _) => Colouring::Class,
        }
    }

    /// The colour of label `l` under this colouring (a class's index, or an attractor's
    /// rank from 0).
    pub fn colour(self, l: usize) -> Color {
        match self {
            Colouring::Class => {
                let (r, g, b) = Class::ALL[l.min(Class::ALL.len() - 1)].rgb();
                Color(r, g, b)
            }
            Colouring::Attractor => crate::classes::attractor_colour(l + 1),
            Colouring::Density => Color::BLACK,
        }
    }

    /// What label `l` means, for a legend.
    pub fn describe(self, l: usize) -> String {
        match self {
            Colouring::Class => Class::ALL[l.min(Class::ALL.len() - 1)]
                .describe()
                .to_string(),
            Colouring::Attractor if l + 1 == ATTRACTOR_LABELS => {
                format!("attractors {ATTRACTOR_LABELS} and beyond")
            }
            Colouring::Attractor if l == 0 => "attractor 1 (largest basin at its value)".into(),
            Colouring::Attractor => format!("attractor {}", l + 1),
            Colouring::Density => "events".into(),
        }
    }
}

/// The label of each of a value's points under `by` (None: drawn by density): its
/// class's index, or (with several starts) its attractor's rank.
pub fn point_labels(r: &ValueResult, by: Colouring) -> Vec<Option<u8>> {
    let n = r.points.len();
    if by == Colouring::Density {
        return vec![None; n];
    }
    if r.attractors.is_empty() {
        let l = match by {
            Colouring::Class => classes::of_value(r).map(|c| c.index() as u8),
            _ => Some(0),
        };
        return vec![l; n];
    }
    let mut out = vec![None; n];
    for (rank, a) in r.attractors.iter().enumerate() {
        let l = match by {
            Colouring::Class => classes::of_attractor(a).map(|c| c.index() as u8),
            _ => Some(rank.min(ATTRACTOR_LABELS - 1) as u8),
        };
        for slot in &mut out[a.points.clone()] {
            *slot = l;
        }
    }
    out
}

/// How the values of `spec` were started, in words: "each started near the (1, 1)
/// solution", or with several starts "each from 8 starts: …" (the captions of the
/// figures and the header of the text diagram say the same).
pub fn starts_text(spec: &SweepSpec) -> String {
    let first = if spec.initial.near_fixed_point {
        "near the (1, 1) solution".to_string()
    } else {
        format!(
            "at t\u{302}0 = {}{}",
            spec.initial.t0,
            match spec.initial.v0 {
                Some(v) => format!(", v0 = {v}"),
                None => String::new(),
            }
        )
    };
    if spec.starts > 1 {
        let w = match spec.w_max {
            Some(w) => shortest(w),
            None => "W".into(),
        };
        format!(
            "each from {} starts (one {first}, the others spread over t\u{302}0 \u{2208} [0, 1), w0 \u{2208} [0, {w}]), every attractor found drawn",
            spec.starts
        )
    } else {
        format!("each started {first}")
    }
}

/// Values whose orbit sticks or rests, as spans of the swept parameter (each value
/// covers half the spacing on either side); `values` are (value, sticks or rests) in
/// increasing order.
fn sticking_spans(spec: &SweepSpec, values: impl Iterator<Item = (f64, bool)>) -> Vec<[f64; 2]> {
    let half = if spec.steps > 1 {
        0.5 * (spec.hi - spec.lo) / (spec.steps - 1) as f64
    } else {
        0.5 * (spec.hi - spec.lo).abs().max(1e-9)
    };
    let mut spans: Vec<[f64; 2]> = Vec::new();
    for (value, sticks) in values {
        if !sticks {
            continue;
        }
        let (a, b) = (value - half, value + half);
        match spans.last_mut() {
            Some(last) if a <= last[1] + 1e-9 * half.max(1e-300) => last[1] = b,
            _ => spans.push([a, b]),
        }
    }
    spans
}

/// Whether a value's orbit sticks or rests (shaded in a diagram).
fn sticks(v: &ValueResult) -> bool {
    v.sticking || matches!(v.outcome, Outcome::Resting { .. })
}

/// One diagram panel: the values' points against the swept parameter over `window`
/// (the sweep's window if None), coloured `by` (black dots for density), with a legend
/// of the colours beside the frame.
pub fn diagram_panel<'a>(
    spec: &SweepSpec,
    values: impl IntoIterator<Item = &'a ValueResult>,
    window: Option<(f64, f64)>,
    axis: DiagramAxis,
    by: Colouring,
) -> Panel {
    let (lo, hi) = window.unwrap_or((spec.lo, spec.hi));
    let mut values: Vec<&ValueResult> = values.into_iter().collect();
    values.sort_by(|a, b| a.value.total_cmp(&b.value));
    let inside = |x: f64| x >= lo.min(hi) && x <= hi.max(lo);
    // The points of each label (the last: none, drawn black).
    let labels = Class::ALL.len().max(ATTRACTOR_LABELS) + 1;
    let mut points: Vec<Vec<[f64; 2]>> = vec![Vec::new(); labels];
    for v in values.iter().filter(|v| inside(v.value)) {
        for (p, l) in v.points.iter().zip(point_labels(v, by)) {
            let y = match axis {
                DiagramAxis::Phase => p.phase,
                DiagramAxis::Velocity => p.v,
            };
            points[l.map_or(labels - 1, usize::from)].push([v.value, y]);
        }
    }
    let spans = sticking_spans(spec, values.iter().map(|v| (v.value, sticks(v))));
    let y = match axis {
        DiagramAxis::Phase => phase_axis(),
        DiagramAxis::Velocity => Axis::around("$v$", points.iter().flatten().map(|p| p[1]), 0.05),
    };
    let name = match axis {
        DiagramAxis::Phase => "phase",
        DiagramAxis::Velocity => "v",
    };
    let mut layers = Vec::new();
    let mut entries = Vec::new();
    for (l, pts) in points.into_iter().enumerate() {
        if pts.is_empty() {
            continue;
        }
        let (color, label) = if l + 1 == labels || by == Colouring::Density {
            (Color::BLACK, None)
        } else {
            (by.colour(l), Some(by.describe(l)))
        };
        if let Some(text) = label {
            entries.push((Swatch::marker(color, Marker::Disc), text));
        }
        layers.push(Layer::Density {
            name: format!("{name}{}", if layers.is_empty() { "" } else { "+" }),
            points: pts,
            color,
        });
    }
    let mut panel = panel_of(spec, (lo, hi), y, spans, axis, layers);
    if !entries.is_empty() {
        panel.beside.push(Legend {
            corner: Corner::TopRight,
            entries,
        });
    }
    panel
}

/// The phase axis of a diagram: t̂ ∈ [0, 1) with a margin.
fn phase_axis() -> Axis {
    Axis::new("$t\u{302}$", -0.06, 1.06)
}

/// A diagram panel from its parts: the sticking bands, the dashed t̂ = 0 and 1 (phase),
/// the points on top, the title.
fn panel_of(
    spec: &SweepSpec,
    (lo, hi): (f64, f64),
    y: Axis,
    spans: Vec<[f64; 2]>,
    axis: DiagramAxis,
    points: Vec<Layer>,
) -> Panel {
    let mut panel = Panel::new(Axis::new(&param_label(spec.param), lo, hi), y);
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
    panel.layers.extend(points);
    panel.title = Some(family_title(&spec.table, spec.param));
    panel
}

/// Points a [`Diagram`] holds as they are (2²¹, 32 MB); beyond, it counts them on a
/// [`DensityGrid`] instead.
pub const HELD_POINTS: usize = 1 << 21;
/// Bins of that grid along each axis (finer than the dots of the largest figure).
pub const GRID_BINS: usize = 4096;

/// A sweep's diagram (phase against the swept parameter) built as its values complete,
/// in any order: each value's points are taken in as it arrives and the value itself
/// can be dropped. Memory is the picture's: the points up to [`HELD_POINTS`], then
/// counts on a [`GRID_BINS`]² grid (64 MB), plus a byte per value (whether it sticks)
/// and, for a sweep that measures them, the values' exponents.
pub struct Diagram {
    spec: SweepSpec,
    /// Points held as they are at most ([`HELD_POINTS`]).
    held: usize,
    /// Per value index: whether its orbit sticks or rests.
    sticking: Vec<bool>,
    /// Per value index: its largest exponent (NaN: none), if the sweep measures them.
    lyapunov: Vec<f64>,
    points: Points,
}

enum Points {
    Held(Vec<[f64; 2]>),
    Counted(DensityGrid),
}

impl Diagram {
    /// An empty diagram of `spec`'s sweep.
    pub fn new(spec: &SweepSpec) -> Diagram {
        Diagram {
            spec: spec.clone(),
            held: HELD_POINTS,
            sticking: vec![false; spec.steps],
            lyapunov: if spec.lyapunov {
                vec![f64::NAN; spec.steps]
            } else {
                Vec::new()
            },
            points: Points::Held(Vec::new()),
        }
    }

    /// The diagram of `values`, all at once.
    pub fn of<'a>(spec: &SweepSpec, values: impl IntoIterator<Item = &'a ValueResult>) -> Diagram {
        let mut d = Diagram::new(spec);
        for v in values {
            d.add(v);
        }
        d
    }

    /// The sweep it is of.
    pub fn spec(&self) -> &SweepSpec {
        &self.spec
    }

    /// Take in one value's result.
    pub fn add(&mut self, v: &ValueResult) {
        if let Some(s) = self.sticking.get_mut(v.index) {
            *s = sticks(v);
        }
        if let Some(l) = self.lyapunov.get_mut(v.index) {
            *l = v.lyapunov.unwrap_or(f64::NAN);
        }
        let new = v.points.iter().map(|p| [v.value, p.phase]);
        match &mut self.points {
            Points::Held(held) if held.len() + v.points.len() <= self.held => held.extend(new),
            Points::Held(held) => {
                let y = phase_axis();
                let mut grid = DensityGrid::new(
                    (self.spec.lo, self.spec.hi),
                    (y.lo, y.hi),
                    self.spec.steps.min(GRID_BINS),
                    GRID_BINS,
                );
                for q in held.drain(..).chain(new) {
                    grid.add(q);
                }
                self.points = Points::Counted(grid);
            }
            Points::Counted(grid) => new.for_each(|q| grid.add(q)),
        }
    }

    /// (value, largest exponent per impact: None where there is none) in increasing
    /// order, for a sweep that measures exponents.
    pub fn exponents(&self) -> impl Iterator<Item = (f64, Option<f64>)> + '_ {
        self.lyapunov
            .iter()
            .enumerate()
            .map(|(i, l)| (self.spec.value(i), (!l.is_nan()).then_some(*l)))
    }

    /// The panel: every point against the swept parameter over the sweep's window (the
    /// points move into it, uncopied).
    pub fn into_panel(self) -> Panel {
        let spec = &self.spec;
        let spans = sticking_spans(
            spec,
            self.sticking
                .iter()
                .enumerate()
                .map(|(i, s)| (spec.value(i), *s)),
        );
        let layer = match self.points {
            Points::Held(mut points) => {
                // In order of the swept value, each value's points in their order.
                points.sort_by(|a, b| a[0].total_cmp(&b[0]));
                Layer::Density {
                    name: "phase".into(),
                    points,
                    color: Color::BLACK,
                }
            }
            Points::Counted(grid) => Layer::Grid {
                name: "phase".into(),
                grid,
                color: Color::BLACK,
            },
        };
        panel_of(
            spec,
            (spec.lo, spec.hi),
            phase_axis(),
            spans,
            DiagramAxis::Phase,
            vec![layer],
        )
    }
}

/// The sweep in words: its fixed parameters, values, transient, kept events and start.
pub fn spec_caption(spec: &SweepSpec) -> String {
    let fixed = match spec.param {
        SweepParam::Alpha => format!("r = {}", spec.r),
        SweepParam::R => format!("\u{3b1} = {}", spec.alpha),
        SweepParam::Table(_) => format!("\u{3b1} = {}, r = {}", spec.alpha, spec.r),
    };
    let param = param_symbol(spec.param);
    let start = starts_text(spec);
    let warm = match spec.warm {
        bouncemap_engine::sweep::Warm::Off => "",
        _ => ", continued from its neighbour",
    };
    let table = free_name(&spec.table, spec.param);
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
pub fn diagram_figure(name: &str, diagram: Diagram) -> Figure {
    let spec = diagram.spec().clone();
    let spec = &spec;
    let mut panel = diagram.into_panel();
    let fixed = match spec.param {
        SweepParam::Alpha => format!("$r$ = {}", spec.r),
        SweepParam::R => format!("$\u{3b1}$ = {}", spec.alpha),
        SweepParam::Table(_) => format!("$\u{3b1}$ = {}, $r$ = {}", spec.alpha, spec.r),
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
/// (None: the sweep's), phase or velocity, coloured as the screen colours it `by`, with
/// `caption` (plain text: the parameters) below it.
pub fn diagram_view<'a>(
    spec: &SweepSpec,
    values: impl IntoIterator<Item = &'a ValueResult>,
    window: Option<(f64, f64)>,
    axis: DiagramAxis,
    by: Colouring,
    caption: &str,
) -> Figure {
    let panel = diagram_panel(spec, values, window, axis, by);
    let wide = !panel.beside.is_empty();
    let mut lines = vec![plain(caption), spec_caption(spec)];
    if axis == DiagramAxis::Phase {
        lines.push(STICKING_NOTE.into());
    }
    Figure {
        name: "diagram".into(),
        panels: vec![panel],
        columns: 1,
        caption: lines,
        // Room for the colours' legend beside the frame.
        size: (if wide { 5.4 } else { COLUMN }, 2.9),
    }
}

/// Fig. 3: the six panels (a)–(f), each a sweep's diagram.
pub fn fig3(panels: Vec<Diagram>) -> Figure {
    let first = panels.first().map(|d| d.spec().clone());
    let mut out = Vec::new();
    for (i, d) in panels.into_iter().enumerate() {
        let mut p = d.into_panel();
        p.letter = Some(format!("({})", (b'a' + i as u8) as char));
        out.push(p);
    }
    let caption = match &first {
        Some(s) => vec![
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
    use crate::labels::table_title;
    use bouncemap_engine::run::Point as SweepPoint;
    use bouncemap_engine::EventKind;
    use bouncemap_engine::Table;

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
            cycle: None,
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
        let spans = sticking_spans(&spec, vals.iter().map(|v| (v.value, sticks(v))));
        assert_eq!(spans.len(), 2);
        assert!((spans[0][0] - 0.25).abs() < 1e-12 && (spans[0][1] - 0.55).abs() < 1e-12);
        assert!((spans[1][0] - 0.75).abs() < 1e-12 && (spans[1][1] - 0.85).abs() < 1e-12);
        let p = diagram_panel(
            &spec,
            &vals,
            Some((0.2, 0.6)),
            DiagramAxis::Phase,
            Colouring::Density,
        );
        let Some(Layer::Density { points, .. }) = p.layers.last() else {
            panic!("the points come last, on top")
        };
        assert_eq!(points.len(), 5, "only the values inside the window");
    }

    /// Past its budget a diagram counts its points on a grid: the same picture (the
    /// same dots but for points within a bin of a dot's edge), every point counted.
    #[test]
    fn a_diagram_past_its_budget_counts_its_points_and_draws_the_same_picture() {
        let spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.4,
            0.6,
            200,
        );
        let vals: Vec<ValueResult> = (0..200)
            .map(|i| {
                let mut v = value(i, spec.value(i), i % 50 == 0);
                v.points = (0..40)
                    .map(|k| SweepPoint {
                        phase: ((i * 37 + k * 101) % 997) as f64 / 997.0,
                        v: 0.5,
                        kind: EventKind::Impact,
                    })
                    .collect();
                v
            })
            .collect();
        let held = Diagram::of(&spec, vals.iter().rev());
        let mut counted = Diagram::new(&spec);
        counted.held = 1000;
        for v in &vals {
            counted.add(v);
        }
        assert!(matches!(held.points, Points::Held(_)));
        assert!(matches!(counted.points, Points::Counted(_)));
        let (a, b) = (held.into_panel(), counted.into_panel());
        assert_eq!(a.layers.len(), b.layers.len(), "bands, lines and points");
        let Some(Layer::Grid { grid, .. }) = b.layers.last() else {
            panic!("the points come last, counted")
        };
        assert_eq!(
            grid.bins().map(|(_, c)| c as usize).sum::<usize>(),
            200 * 40
        );
        let dots = |p: Panel| {
            let fig = Figure {
                name: "d".into(),
                panels: vec![p],
                columns: 1,
                caption: Vec::new(),
                size: (COLUMN, 2.9),
            };
            crate::svg::to_svg(&fig, fig.size).matches("h0").count()
        };
        let (da, db) = (dots(a), dots(b));
        assert!(
            da > 1000 && da.abs_diff(db) * 50 <= da,
            "{da} dots held, {db} counted"
        );
    }

    /// A diagram coloured by class draws each class's points in that class's one
    /// colour (the terminal's), with a legend entry each, beside the frame; by density
    /// everything is black and there is no legend.
    #[test]
    fn a_coloured_diagram_takes_the_class_colours() {
        let spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.0,
            1.0,
            11,
        );
        let vals: Vec<ValueResult> = (0..11).map(|i| value(i, i as f64 / 10.0, i >= 6)).collect();
        let fig = diagram_view(
            &spec,
            &vals,
            None,
            DiagramAxis::Phase,
            Colouring::Class,
            "caption",
        );
        let p = &fig.panels[0];
        let colours: Vec<Color> = p
            .layers
            .iter()
            .filter_map(|l| match l {
                Layer::Density { color, .. } => Some(*color),
                _ => None,
            })
            .collect();
        let (r, g, b) = Class::Sticking.rgb();
        assert!(colours.contains(&Color(r, g, b)), "{colours:?}");
        assert_eq!(p.beside.len(), 1);
        assert!(p.beside[0]
            .entries
            .iter()
            .any(|(s, t)| s.color == Color(r, g, b) && t.contains("sticks")));
        let black = diagram_view(
            &spec,
            &vals,
            None,
            DiagramAxis::Phase,
            Colouring::Density,
            "caption",
        );
        assert!(black.panels[0].beside.is_empty());
        assert!(black.panels[0].layers.iter().all(|l| !matches!(
            l,
            Layer::Density { color, .. } if *color != Color::BLACK
        )));
    }

    /// Several starts are said in the caption, as the text diagram says them.
    #[test]
    fn the_caption_states_several_starts() {
        let mut spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.45,
            0.6,
            5,
        );
        spec.initial.near_fixed_point = true;
        assert!(spec_caption(&spec).contains("each started near the (1, 1) solution"));
        spec.starts = 8;
        let c = spec_caption(&spec);
        assert!(
            c.contains("each from 8 starts") && !c.contains("each started"),
            "{c}"
        );
    }

    #[test]
    fn titles_name_the_table_as_the_paper_does() {
        assert_eq!(table_title(&Table::fd(0.1).unwrap()), "$F_{0.1}$");
        assert_eq!(table_title(&Table::fd(0.0).unwrap()), "$F_{0}$");
        assert!(table_title(&Table::sine()).contains("sin"));
    }
}
