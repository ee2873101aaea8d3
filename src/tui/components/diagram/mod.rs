//! The bifurcation diagram: the hit-count grid of the sweep (phase t̂ or v against α)
//! with axes, a progress gauge and points/s in the title, the current α as a cursor
//! line, the zoom cursor and window mark, and marks at the birth and the period
//! doubling (α_PD) of the (1, k) solution. Points are coloured by the class of their
//! value's orbit, by attractor, or by density ([`colouring`], legend in the bottom
//! border), with the largest Lyapunov exponent in a strip underneath ([`strip`]). With
//! all attractors on, every value runs [`ALL_STARTS`] starts and shows each attractor
//! found. It owns its sweep: the points of every value (for re-binning on zoom, axis
//! change and resize), the zoom stack, the cursor.

mod branch_layer;
pub mod colouring;
mod eta;
mod navigation;
pub mod readout;
pub mod strip;

pub use navigation::Zoom;

use super::{compact, is_focused, panel, Component, Effect, JobMsg, Registered, Shared, Workers};
use crate::output::hitgrid::{HitGrid, Range};
use crate::tui::keymap::Action;
use crate::tui::layout::{plot_area_within, Slot};
use crate::tui::params::{fmt_num, ParamId, Params, StartMode, Touch};
use crate::tui::plot::{draw_axes, render, Axes};
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::sweep::{InitialSpec, SweepBatch, SweepJob, SweepSpec, ValueResult};
use colouring::{point_labels, Colouring, LabelGrid};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::{Paragraph, Widget, Wrap};
use std::time::Instant;

/// Width of the y tick labels.
const LABEL_W: u16 = 5;
/// Starts per value while all attractors are shown.
pub const ALL_STARTS: usize = 8;

/// The diagram's inner area split into the plot with its axes and the Lyapunov strip
/// (when there is room for both).
pub fn split(inner: Rect) -> (Rect, Option<Rect>) {
    let rows = strip::rows(inner.height);
    if rows == 0 {
        return (inner, None);
    }
    let main = Rect {
        height: inner.height - rows,
        ..inner
    };
    let strip = Rect {
        y: inner.y + main.height,
        height: rows,
        ..inner
    };
    (main, Some(strip))
}

/// The plot rectangle of the diagram pane (as [`draw_axes`] lays it out above the
/// strip).
fn plot_rect(pane: Rect) -> Rect {
    let inner_h = pane.height.saturating_sub(2);
    let (main, _) = split(Rect {
        height: inner_h,
        ..pane
    });
    let above = Rect {
        height: pane.height - (inner_h - main.height),
        ..pane
    };
    plot_area_within(above, LABEL_W)
}

/// What the diagram's vertical axis shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Phase,
    Velocity,
}

impl Axis {
    /// The coordinate this axis shows.
    pub fn pick(self, phase: f64, v: f64) -> f64 {
        match self {
            Axis::Phase => phase,
            Axis::Velocity => v,
        }
    }
}

/// Progress of the sweep feeding the diagram.
#[derive(Clone, Debug, PartialEq)]
pub enum SweepStatus {
    Idle,
    Running,
    Done,
    Unavailable(String),
}

/// The bifurcation diagram panel.
pub struct Diagram {
    /// The latest result of every value (a later pass replaces an earlier one).
    pub slots: Vec<Option<ValueResult>>,
    /// Points received in this sweep (all passes), for points/s.
    pub received: u64,
    /// Points currently plotted.
    pub plotted: usize,
    pub values_done: usize,
    pub values_total: usize,
    pub status: SweepStatus,
    pub gen: u64,
    pub started: Option<Instant>,
    pub elapsed: f64,
    pub axis: Axis,
    /// The cursor: a value of the swept parameter, and a height on the vertical axis.
    pub cursor: f64,
    pub ycursor: f64,
    /// The first corner of a window being marked (value, height).
    pub mark: Option<(f64, f64)>,
    /// The vertical window, if zoomed vertically (else the axis's full range).
    pub y_view: Option<(f64, f64)>,
    pub zoom_stack: Vec<Zoom>,
    /// The next start adds the values between the stored ones (the plot grew wider).
    pub grid: HitGrid,
    /// The plot's screen rectangle at the last layout (for the mouse).
    pub plot_area: Rect,
    /// The sweep the stored results come from.
    pub running: Option<SweepSpec>,
    /// What the colours show.
    pub color_by: Colouring,
    /// Several starts per value, every attractor drawn.
    pub all_attractors: bool,
    /// Label counts per cell of `grid`.
    pub labels: LabelGrid,
    /// The recent rate of values finished, for the time left.
    eta: eta::Eta,
}

impl Diagram {
    pub fn new(shared: &Shared) -> Diagram {
        let p = &shared.params;
        Diagram {
            slots: Vec::new(),
            received: 0,
            plotted: 0,
            values_done: 0,
            values_total: 0,
            status: SweepStatus::Idle,
            gen: 0,
            started: None,
            elapsed: 0.0,
            axis: Axis::Phase,
            cursor: p.value(p.param).unwrap_or(p.lo),
            ycursor: 0.5,
            mark: None,
            y_view: None,
            zoom_stack: Vec::new(),
            grid: HitGrid::new(
                0,
                0,
                shared.marker,
                Range::new(p.lo, p.hi),
                Range::new(0.0, 1.0),
            ),
            plot_area: Rect::default(),
            running: None,
            color_by: Colouring::Class,
            all_attractors: false,
            labels: LabelGrid::default(),
            eta: eta::Eta::default(),
        }
    }

    /// The sweep for the current parameters: the preset's number of values, or one
    /// value per sub-cell column.
    pub fn sweep_spec(&self, shared: &Shared) -> SweepSpec {
        let p = &shared.params;
        let steps = p.steps;
        let mut spec = SweepSpec::new(p.table(), p.alpha, p.r, p.param, p.lo, p.hi, steps);
        spec.initial = InitialSpec {
            t0: p.t0,
            v0: p.v0,
            z0: 0.0,
            near_fixed_point: p.start == StartMode::NearFixedPoint,
        };
        spec.warm = p.start.warm();
        spec.transient = p.transient;
        spec.keep = p.keep;
        // The strip and the period colours need every value's exponent.
        spec.lyapunov = true;
        if self.all_attractors {
            spec.starts = ALL_STARTS;
            // Several starts look for every attractor at each value: cold starts.
            spec.warm = bouncemap_engine::sweep::Warm::Off;
        }
        spec
    }

    /// The current value of the swept parameter (where its line is drawn).
    pub fn current(shared: &Shared) -> f64 {
        let p = &shared.params;
        p.value(p.param).unwrap_or(p.lo)
    }

    /// Periods of the provisional first pass: a tenth of the transient.
    fn preview(transient: u64) -> u64 {
        if transient >= 400 {
            transient / 10
        } else {
            0
        }
    }

    /// A new sweep of `values` values started under generation `gen`.
    pub fn sweep_started(&mut self, gen: u64, values: usize, shared: &Shared) {
        self.gen = gen;
        self.slots = vec![None; values];
        self.received = 0;
        self.plotted = 0;
        self.values_done = 0;
        self.values_total = values;
        self.elapsed = 0.0;
        self.started = Some(Instant::now());
        self.status = SweepStatus::Running;
        self.eta.reset();
        self.rebin(shared);
    }

    /// Points per second of the running sweep.
    pub fn sweep_rate(&self) -> f64 {
        if self.elapsed > 0.0 {
            self.received as f64 / self.elapsed
        } else {
            0.0
        }
    }

    /// Store one value's batch, replacing an earlier pass of the same value in the
    /// grid (its counts are taken out first).
    pub fn add_batch(&mut self, b: &SweepBatch, shared: &Shared) {
        if b.index >= self.slots.len() {
            self.slots.resize(b.index + 1, None);
            self.values_total = self.values_total.max(b.index + 1);
        }
        if let Some(old) = self.slots[b.index].take() {
            let labels = point_labels(&old, self.color_by);
            for (p, l) in old.points.iter().zip(labels) {
                let y = self.axis.pick(p.phase, p.v);
                self.labels.count(&self.grid, old.value, y, l, false);
                self.grid.remove(old.value, y);
            }
            self.plotted -= old.points.len();
            if old.complete {
                self.values_done -= 1;
            }
        }
        let mut rebin = false;
        let labels = point_labels(b, self.color_by);
        for (p, l) in b.points.iter().zip(labels) {
            let y = self.axis.pick(p.phase, p.v);
            if !self.grid.y_range().contains(y) {
                rebin = true;
            }
            self.grid.add(b.value, y);
            self.labels.count(&self.grid, b.value, y, l, true);
        }
        self.received += b.points.len() as u64;
        self.plotted += b.points.len();
        if b.complete {
            self.values_done += 1;
        }
        self.slots[b.index] = Some(b.data.clone());
        if let Some(s) = self.started {
            self.elapsed = s.elapsed().as_secs_f64();
        }
        self.eta.sample(self.elapsed, self.values_done);
        if rebin {
            self.rebin(shared);
        }
    }

    /// Re-bin from the stored points (window, axis or size changed).
    pub fn rebin(&mut self, shared: &Shared) {
        let x = Range::new(shared.params.lo, shared.params.hi);
        let y = match (self.y_view, self.axis) {
            (Some((lo, hi)), _) => Range::new(lo, hi),
            (None, Axis::Phase) => Range::new(0.0, 1.0),
            (None, Axis::Velocity) => v_range(
                self.slots
                    .iter()
                    .flatten()
                    .flat_map(|s| s.points.iter().map(|p| p.v)),
                shared.params.k,
            ),
        };
        let (w, h) = self.grid.size();
        self.grid = HitGrid::new(w, h, shared.marker, x, y);
        self.labels = LabelGrid::new(w, h);
        for s in self.slots.iter().flatten() {
            let labels = point_labels(s, self.color_by);
            for (p, l) in s.points.iter().zip(labels) {
                let y = self.axis.pick(p.phase, p.v);
                self.grid.add(s.value, y);
                self.labels.count(&self.grid, s.value, y, l, true);
            }
        }
    }
}

impl Component for Diagram {
    type Msg = JobMsg<ValueResult>;

    fn focusable(&self) -> bool {
        true
    }

    /// Resize the grid to the plot area inside `pane` (re-binning from the stored
    /// points when the size changed); sweep again if it grew wider than the sweep has
    /// values.
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        let plot = plot_rect(pane);
        self.plot_area = plot;
        if self.grid.size() != (plot.width, plot.height) || self.grid.marker() != shared.marker {
            self.grid = HitGrid::new(
                plot.width,
                plot.height,
                shared.marker,
                self.grid.x_range(),
                self.grid.y_range(),
            );
            // The data's resolution is the values parameter's, not the screen's: a
            // new size only re-bins.
            self.rebin(shared);
        }
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        let focused = shared.focus == Slot::Diagram;
        match action {
            Action::Left | Action::Right | Action::FineLeft | Action::FineRight if focused => {
                let dir = if matches!(action, Action::Left | Action::FineLeft) {
                    -1
                } else {
                    1
                };
                self.move_cursor(
                    dir,
                    matches!(action, Action::FineLeft | Action::FineRight),
                    shared,
                );
            }
            Action::Up | Action::Down if focused => {
                self.move_ycursor(if action == Action::Up { 1 } else { -1 });
            }
            Action::Enter if focused => self.set_value_to_cursor(shared),
            Action::Cancel => self.mark = None,
            Action::ToggleAxis => {
                self.axis = match self.axis {
                    Axis::Phase => Axis::Velocity,
                    Axis::Velocity => Axis::Phase,
                };
                self.y_view = None;
                self.rebin(shared);
                self.ycursor = self.grid.y_range().lo + 0.5 * self.grid.y_range().span();
            }
            Action::Colouring => {
                self.color_by = self.color_by.next(self.all_attractors);
                self.rebin(shared);
                let what = match self.color_by {
                    Colouring::Class => "colours: the class of each value's orbit",
                    Colouring::Attractor => "colours: the attractor (1 = largest basin)",
                    Colouring::Density => "colours: point density",
                };
                shared.say(what, false);
            }
            Action::AllAttractors => {
                self.all_attractors = !self.all_attractors;
                if self.all_attractors {
                    self.color_by = Colouring::Attractor;
                    shared.say(
                        format!("all attractors: {ALL_STARTS} starts per value over the basin box"),
                        false,
                    );
                } else {
                    if self.color_by == Colouring::Attractor {
                        self.color_by = Colouring::Class;
                    }
                    shared.say("one start per value", false);
                }
                shared.effect(Effect::Start(Self::TARGET));
            }
            Action::MarkWindow => self.mark_corner(shared),
            Action::ZoomIn | Action::ZoomOut => {
                let f = if action == Action::ZoomIn { 0.25 } else { 1.0 };
                let c = self.cursor;
                let w = shared.params.hi - shared.params.lo;
                self.zoom_to(c - w * f, c + w * f, shared);
            }
            Action::ZoomBack => self.zoom_back(shared),
            _ => return false,
        }
        true
    }

    /// A window being marked is dropped.
    fn focus_moved(&mut self) {
        self.mark = None;
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        let p = &shared.params;
        let swept = p.row_of(p.param);
        match id.touches() {
            Touch::System => {
                self.cursor = Diagram::current(shared);
                // A sweep does not depend on the value it sweeps: only its line moves.
                if Some(id) != swept {
                    shared.effect(Effect::Start(Self::TARGET));
                }
            }
            Touch::Start => {
                // A cold sweep starts from t̂0, v0.
                if p.start == StartMode::Cold {
                    shared.effect(Effect::Start(Self::TARGET));
                }
            }
            Touch::Sweep => {
                let (lo, hi) = (p.lo, p.hi);
                if id == ParamId::Sweep {
                    self.cursor = Diagram::current(shared);
                    self.zoom_stack.clear();
                }
                self.cursor = self.cursor.clamp(lo, hi);
                shared.say(
                    format!(
                        "sweeping {} ∈ [{}, {}], start {}",
                        Params::symbol(p.param),
                        fmt_num(lo),
                        fmt_num(hi),
                        p.start.label()
                    ),
                    false,
                );
                shared.effect(Effect::Start(Self::TARGET));
            }
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let spec = self.sweep_spec(shared);
        let steps = spec.steps;
        let preview = Self::preview(spec.transient);
        match SweepJob::new(spec.clone()) {
            Ok(job) => {
                let gen = workers.start_job(Self::ADDRESS, job.preview(preview));
                self.sweep_started(gen, steps, shared);
                self.running = Some(spec);
            }
            Err(e) => {
                workers.cancel(Self::TARGET);
                self.sweep_started(0, 0, shared);
                self.status = SweepStatus::Unavailable(e.to_string());
            }
        }
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        match msg {
            JobMsg::Batch(b) => self.add_batch(&b, shared),
            JobMsg::Done => {
                self.status = SweepStatus::Done;
                if let Some(s) = self.started {
                    self.elapsed = s.elapsed().as_secs_f64();
                }
            }
        }
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.status == SweepStatus::Running
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        (self.status == SweepStatus::Running).then(|| {
            format!(
                "sweep {}%",
                (100 * self.values_done / self.values_total.max(1)).min(100)
            )
        })
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let focused = is_focused(app, Slot::Diagram);
        // The progress always shows in full: with the cursor's readout beside it, the
        // head words go first, then the readout is cut to the room left.
        let width = area.width.saturating_sub(2) as usize;
        let with_readout = focused || self.mark.is_some();
        let mut left = title(self, app, true);
        let mut right = String::new();
        if with_readout {
            // The readout's value and orbit class come before the title's words: a
            // narrow panel shortens the title, then drops the readout's later parts.
            let w = |s: &str| ratatui::text::Line::from(s).width();
            let full = readout::text(self, app, usize::MAX);
            if w(&left) + w(&full) > width {
                left = title(self, app, false);
            }
            let mut room = width.saturating_sub(w(&left) + 1);
            let core = w(&readout::parts(self, app)[0]) + 2;
            if room < core {
                left = progress_only(self, app);
                room = width.saturating_sub(w(&left) + 1);
            }
            right = readout::text(self, app, room);
        }
        let mut block =
            panel(app, left, focused).title_bottom(colouring::legend(self.color_by, &app.theme));
        if with_readout && !right.is_empty() {
            block =
                block.title(ratatui::text::Line::styled(right, app.theme.mark2()).right_aligned());
        }
        let inner = block.inner(area);
        block.render(area, buf);
        let (main, strip_area) = split(inner);
        if let SweepStatus::Unavailable(why) = &self.status {
            Paragraph::new(format!("Bifurcation diagram: {why}."))
                .style(app.theme.dim())
                .wrap(Wrap { trim: true })
                .render(inner, buf);
            return;
        }
        let x = self.grid.x_range();
        let y = self.grid.y_range();
        let axes = Axes {
            x,
            y,
            x_name: &Params::symbol(app.params.param),
            y_name: match self.axis {
                Axis::Phase => "t̂",
                Axis::Velocity => "v",
            },
        };
        let plot = draw_axes(main, buf, axes, LABEL_W, &app.theme);
        render(&self.grid, plot, buf, &app.theme, &[], Style::new());
        self.labels.paint(plot, buf, &app.theme, self.color_by);
        // The continued branches of this window (α sweeps), under the marks below.
        if let (Some(Ok(sk)), SweepParam::Alpha) = (&app.branches, app.params.param) {
            let axes = (x, y, self.axis == Axis::Velocity);
            let proved = app
                .branch_proofs
                .as_ref()
                .filter(|_| app.show_proofs)
                .and_then(|m| m.of(sk));
            branch_layer::draw(sk, proved, axes, plot, app.marker, buf, &app.theme);
        }
        if let Some(a) = strip_area {
            strip::draw(&self.slots, x, a, LABEL_W, app.marker, buf, &app.theme);
        }
        // Marks of the (1, k) solution's birth and period doubling (α sweeps), on the
        // x axis's row so they never cover data.
        if let (Some(Ok(info)), SweepParam::Alpha) = (&app.orbits, app.params.param) {
            let axis_row = plot.y + plot.height;
            // With the continued branches shown, their PD label stands for α_PD.
            let pd = if matches!(app.branches, Some(Ok(_))) {
                None
            } else {
                info.pd
            };
            for (a, ch) in [(info.birth, "B"), (pd, "P")] {
                if let Some(col) = a.and_then(|a| column(x, plot, a)) {
                    buf.set_string(col, axis_row, ch, app.theme.mark());
                }
            }
        }
        // Vertical lines: drawn as a glyph over empty cells, as a style over data (in
        // reverse video without colour, so they stay visible in dense regions).
        let vline = |buf: &mut Buffer, a: f64, glyph: &str, style: Style| {
            if let Some(col) = column(x, plot, a) {
                for row in plot.y..plot.y + plot.height {
                    if let Some(cell) = buf.cell_mut((col, row)) {
                        if cell.symbol() == " " {
                            cell.set_symbol(glyph).set_style(style);
                        } else {
                            cell.set_style(app.theme.over_data(style));
                        }
                    }
                }
            }
        };
        let hline = |buf: &mut Buffer, v: f64, glyph: &str, style: Style| {
            if !y.contains(v) || plot.height == 0 {
                return;
            }
            let row =
                plot.y + (((1.0 - y.frac(v)) * plot.height as f64) as u16).min(plot.height - 1);
            for col in plot.x..plot.x + plot.width {
                if let Some(cell) = buf.cell_mut((col, row)) {
                    if cell.symbol() == " " {
                        cell.set_symbol(glyph).set_style(style);
                    }
                }
            }
        };
        vline(buf, Diagram::current(app), "│", app.theme.cursor());
        if focused || self.mark.is_some() {
            if (self.cursor - Diagram::current(app)).abs() > x.span() * 1e-9 {
                vline(buf, self.cursor, "┆", app.theme.mark2());
            }
            hline(buf, self.ycursor, "┄", app.theme.mark2());
            if let Some((mx, my)) = self.mark {
                vline(buf, mx, "┃", app.theme.mark2());
                hline(buf, my, "━", app.theme.mark2());
            }
        }
    }
}

fn gauge(frac: f64, w: usize) -> String {
    let full = (frac.clamp(0.0, 1.0) * w as f64).floor() as usize;
    format!("{}{}", "█".repeat(full), "░".repeat(w - full))
}

/// A duration in words: 45s, 3m10s, 2h05m.
fn duration(secs: f64) -> String {
    let s = secs.round() as u64;
    match s {
        0..=59 => format!("{s}s"),
        60..=3599 => format!("{}m{:02}s", s / 60, s % 60),
        _ => format!("{}h{:02}m", s / 3600, (s % 3600) / 60),
    }
}

/// `text` cut to `width` display columns, ending in `…` where it was cut.
fn fit(text: &str, width: usize) -> String {
    let line = ratatui::text::Line::from(text);
    if line.width() <= width {
        return text.to_string();
    }
    if width < 2 {
        return String::new();
    }
    let mut out = String::new();
    for ch in text.chars() {
        if ratatui::text::Line::from(format!("{out}{ch}…")).width() > width {
            break;
        }
        out.push(ch);
    }
    format!("{out}…")
}

/// The panel's title: what is plotted (in words with `long`), and the sweep's progress.
pub fn title(d: &Diagram, app: &Shared, long: bool) -> String {
    let paused = app.paused;
    let axis = match d.axis {
        Axis::Phase => "t̂",
        Axis::Velocity => "v",
    };
    let sym = Params::symbol(app.params.param);
    let head = match (d.all_attractors, long) {
        (true, true) => format!(" Diagram {axis} vs {sym}, all attractors "),
        (false, true) => format!(" Bifurcation diagram: {axis} vs {sym} "),
        (true, false) => format!(" {axis} vs {sym}, all "),
        (false, false) => format!(" {axis} vs {sym} "),
    };
    match &d.status {
        SweepStatus::Running | SweepStatus::Done => {
            let frac = d.values_done as f64 / d.values_total.max(1) as f64;
            let state = if d.status == SweepStatus::Done {
                if app.show_times {
                    format!("done {:.1}s", d.elapsed)
                } else {
                    "done".into()
                }
            } else if paused {
                "paused".into()
            } else if !app.show_times {
                String::new()
            } else if let Some(left) = d
                .started
                .and_then(|s| d.eta.left(s.elapsed().as_secs_f64(), d.values_total))
            {
                // The time left at the rate of the last seconds (the values still
                // running are the slow ones).
                format!(
                    "{} pts/s, ~{} left",
                    compact(d.sweep_rate()),
                    duration(left)
                )
            } else {
                format!("{} pts/s", compact(d.sweep_rate()))
            };
            // Rounded down: 100% only once every value is done.
            format!(
                "{head}{} {:>3}% {} pts, {state} ",
                gauge(frac, 10),
                (frac * 100.0).floor() as u32,
                compact(d.plotted as f64)
            )
        }
        SweepStatus::Idle | SweepStatus::Unavailable(_) => head,
    }
}

/// The title at its shortest: the sweep's progress alone.
fn progress_only(d: &Diagram, app: &Shared) -> String {
    let frac = d.values_done as f64 / d.values_total.max(1) as f64;
    match d.status {
        SweepStatus::Done => " done ".into(),
        SweepStatus::Running if app.paused => " paused ".into(),
        SweepStatus::Running => format!(" {:>3}% ", (frac * 100.0).floor() as u32),
        _ => " ".into(),
    }
}

/// Screen column of α in the plot.
pub fn column(x: Range, plot: Rect, a: f64) -> Option<u16> {
    if !x.contains(a) || plot.width == 0 {
        return None;
    }
    Some(plot.x + ((x.frac(a) * plot.width as f64) as u16).min(plot.width - 1))
}

/// α at a screen column (for the mouse).
pub fn alpha_at(x: Range, plot: Rect, col: u16) -> Option<f64> {
    if col < plot.x || col >= plot.x + plot.width {
        return None;
    }
    Some(x.lo + x.span() * ((col - plot.x) as f64 + 0.5) / plot.width as f64)
}

/// A velocity range covering `vs` with a margin (and k/2, the (1, k) velocity).
pub fn v_range(vs: impl Iterator<Item = f64>, k: u32) -> Range {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in vs.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let star = k as f64 / 2.0;
    if !lo.is_finite() {
        return Range::new(0.0, (2.0 * star).max(1.0));
    }
    lo = lo.min(star);
    hi = hi.max(star);
    let pad = ((hi - lo) * 0.15).max(0.05);
    Range::new(lo - pad, hi + pad)
}
