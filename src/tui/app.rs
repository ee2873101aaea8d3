//! The application state and what every [`Action`] does to it. Pure: no terminal, no
//! threads. Handling an action mutates the state and queues [`Effect`]s (restart the
//! sweep, the phase plot, the orbit analysis; export) that the runtime carries out, so
//! every key's effect can be tested directly.

use super::keymap::{Action, Keymap};
use super::params::{fmt_num, ParamId, Params, Touch};
use super::plot::{HitGrid, Marker, Range};
use super::theme::Theme;
use super::workers::{Msg, OrbitInfo};
use crate::engine::sweep::{InitialSpec, SweepBatch, SweepParam, SweepSpec};
use crate::engine::{Event, Halt, ImpactMap, Solver, State, System};
use ratatui::layout::Rect;
use std::time::Instant;

/// Which panel takes the arrow keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Focus {
    Params,
    Diagram,
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

/// An overlay drawn over the panels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlay {
    None,
    Help,
    Presets { selected: usize },
}

/// Work the runtime must start or do after an action.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    RestartSweep,
    RestartPhase,
    RestartOrbits,
    Pause(bool),
    Export,
}

/// A preset: the paper's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Preset {
    pub name: String,
    pub description: String,
    pub table: String,
    pub r: f64,
    pub k: u32,
    pub lo: f64,
    pub hi: f64,
}

/// Progress of the sweep feeding the diagram.
#[derive(Clone, Debug, PartialEq)]
pub enum SweepStatus {
    Idle,
    Running,
    Done,
    Unavailable(String),
}

/// The latest batch of one swept value (a later pass replaces an earlier one).
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    pub value: f64,
    /// (phase, v) of the recorded events.
    pub points: Vec<(f64, f64)>,
    pub complete: bool,
    pub sticking: bool,
}

/// The bifurcation diagram: stored points per value (for re-binning), the grid, the
/// zoom state.
pub struct DiagramState {
    pub slots: Vec<Option<Slot>>,
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
    pub cursor: f64,
    pub mark: Option<f64>,
    pub zoom_stack: Vec<(f64, f64)>,
    pub grid: HitGrid,
    /// The plot's screen rectangle at the last layout (for the mouse).
    pub plot_area: Rect,
}

/// The live phase plot (t̂, v).
pub struct PhaseState {
    pub points: Vec<(f64, f64)>,
    pub gen: u64,
    pub done: bool,
    pub note: Option<String>,
    pub grid: HitGrid,
}

/// Single-bounce stepping with history.
pub struct BounceState {
    pub map: Option<ImpactMap>,
    /// States after each event; `history[0]` is the initial state.
    pub history: Vec<State>,
    pub events: Vec<Event>,
    pub halt: Option<Halt>,
    pub error: Option<String>,
}

/// The orbit analysis for the current parameters.
pub struct OrbitState {
    pub gen: u64,
    pub info: Option<Result<OrbitInfo, String>>,
}

/// Everything on screen.
pub struct App {
    pub params: Params,
    pub keymap: Keymap,
    pub theme: Theme,
    pub marker: Marker,
    pub fps: u32,
    pub mouse: bool,
    pub focus: Focus,
    pub selected: usize,
    pub editing: Option<String>,
    /// A one-line message (refusal, export result); true if it is an error.
    pub message: Option<(String, bool)>,
    pub overlay: Overlay,
    pub paused: bool,
    pub quit: bool,
    pub dirty: bool,
    pub presets: Vec<Preset>,
    pub diagram: DiagramState,
    pub phase: PhaseState,
    pub bounce: BounceState,
    pub orbits: OrbitState,
    effects: Vec<Effect>,
    /// Start of a mouse drag on the diagram (column).
    pub drag_from: Option<u16>,
}

/// Largest number of phase-plot points kept (older ones are dropped from the store).
pub const PHASE_KEEP: usize = 20_000;
/// Recent phase-plot points drawn highlighted.
pub const RECENT: usize = 40;
/// Largest bounce history kept for stepping back.
pub const HISTORY: usize = 10_000;

impl App {
    pub fn new(params: Params, keymap: Keymap, theme: Theme, marker: Marker, fps: u32) -> App {
        let d = Range::new(params.lo, params.hi);
        let mut app = App {
            diagram: DiagramState {
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
                cursor: params.alpha,
                mark: None,
                zoom_stack: Vec::new(),
                grid: HitGrid::new(0, 0, marker, d, Range::new(0.0, 1.0)),
                plot_area: Rect::default(),
            },
            phase: PhaseState {
                points: Vec::new(),
                gen: 0,
                done: false,
                note: None,
                grid: HitGrid::new(0, 0, marker, Range::new(0.0, 1.0), Range::new(0.0, 1.0)),
            },
            bounce: BounceState {
                map: None,
                history: Vec::new(),
                events: Vec::new(),
                halt: None,
                error: None,
            },
            orbits: OrbitState { gen: 0, info: None },
            params,
            keymap,
            theme,
            marker,
            fps,
            mouse: false,
            focus: Focus::Params,
            selected: 2,
            editing: None,
            message: None,
            overlay: Overlay::None,
            paused: false,
            quit: false,
            dirty: true,
            presets: Vec::new(),
            effects: Vec::new(),
            drag_from: None,
        };
        app.reset_bounce();
        app.effects = vec![
            Effect::RestartOrbits,
            Effect::RestartPhase,
            Effect::RestartSweep,
        ];
        app
    }

    /// Effects queued since the last call.
    pub fn take_effects(&mut self) -> Vec<Effect> {
        std::mem::take(&mut self.effects)
    }

    pub fn system(&self) -> System {
        self.params.system()
    }

    pub fn selected_param(&self) -> ParamId {
        ParamId::ALL[self.selected]
    }

    // ---------------------------------------------------------------- actions

    /// Apply one action.
    pub fn handle(&mut self, action: Action) {
        self.dirty = true;
        if action == Action::Quit {
            self.quit = true;
            return;
        }
        match self.overlay {
            Overlay::Help => {
                if matches!(action, Action::Help | Action::Cancel | Action::Enter) {
                    self.overlay = Overlay::None;
                }
                return;
            }
            Overlay::Presets { selected } => {
                let n = self.presets.len().max(1);
                match action {
                    Action::Up => {
                        self.overlay = Overlay::Presets {
                            selected: (selected + n - 1) % n,
                        }
                    }
                    Action::Down => {
                        self.overlay = Overlay::Presets {
                            selected: (selected + 1) % n,
                        }
                    }
                    Action::Enter => {
                        self.overlay = Overlay::None;
                        self.load_preset(selected);
                    }
                    Action::Cancel | Action::Presets => self.overlay = Overlay::None,
                    _ => {}
                }
                return;
            }
            Overlay::None => {}
        }
        match action {
            Action::Quit => {}
            Action::Pause => {
                self.paused = !self.paused;
                self.effects.push(Effect::Pause(self.paused));
            }
            Action::Help => self.overlay = Overlay::Help,
            Action::Presets => self.overlay = Overlay::Presets { selected: 0 },
            Action::NextPanel | Action::PrevPanel => {
                self.focus = match self.focus {
                    Focus::Params => Focus::Diagram,
                    Focus::Diagram => Focus::Params,
                };
                self.diagram.mark = None;
            }
            Action::Up if self.focus == Focus::Params => {
                self.selected = (self.selected + ParamId::ALL.len() - 1) % ParamId::ALL.len()
            }
            Action::Down if self.focus == Focus::Params => {
                self.selected = (self.selected + 1) % ParamId::ALL.len()
            }
            Action::Left | Action::Right | Action::FineLeft | Action::FineRight => {
                let dir = if matches!(action, Action::Left | Action::FineLeft) {
                    -1
                } else {
                    1
                };
                let fine = matches!(action, Action::FineLeft | Action::FineRight);
                match self.focus {
                    Focus::Params => {
                        let id = self.selected_param();
                        let before = self.params.clone();
                        let r = self.params.nudge(id, dir, fine);
                        self.after_change(id, r, before);
                    }
                    Focus::Diagram => self.move_cursor(dir, fine),
                }
            }
            Action::Enter => match self.focus {
                Focus::Params => self.editing = Some(String::new()),
                Focus::Diagram => {
                    let before = self.params.clone();
                    let a = self.diagram.cursor;
                    let r = self.params.set_text(ParamId::Alpha, &format!("{a}"));
                    self.after_change(ParamId::Alpha, r, before);
                }
            },
            Action::Cancel => {
                self.diagram.mark = None;
                self.message = None;
            }
            Action::StepOne => self.step(1),
            Action::StepTen => self.step(10),
            Action::StepBack => self.step_back(),
            Action::RestartOrbit => self.reset_bounce(),
            Action::ToggleAxis => {
                self.diagram.axis = match self.diagram.axis {
                    Axis::Phase => Axis::Velocity,
                    Axis::Velocity => Axis::Phase,
                };
                self.rebin_diagram();
            }
            Action::MarkWindow => match self.diagram.mark.take() {
                None => self.diagram.mark = Some(self.diagram.cursor),
                Some(m) => {
                    let (lo, hi) = (m.min(self.diagram.cursor), m.max(self.diagram.cursor));
                    self.zoom_to(lo, hi);
                }
            },
            Action::ZoomIn | Action::ZoomOut => {
                let f = if action == Action::ZoomIn { 0.25 } else { 1.0 };
                let c = self.diagram.cursor;
                let w = self.params.hi - self.params.lo;
                self.zoom_to(c - w * f, c + w * f);
            }
            Action::ZoomBack => match self.diagram.zoom_stack.pop() {
                Some((lo, hi)) => {
                    self.params.lo = lo;
                    self.params.hi = hi;
                    self.diagram.cursor = self.diagram.cursor.clamp(lo, hi);
                    self.window_changed();
                }
                None => self.message = Some(("zoom: already at the first window".into(), true)),
            },
            Action::Export => self.effects.push(Effect::Export),
            Action::Up | Action::Down => {}
        }
    }

    /// A typed character while editing (Enter commits, Esc cancels).
    pub fn edit_key(&mut self, key: crossterm::event::KeyCode) {
        use crossterm::event::KeyCode;
        self.dirty = true;
        let Some(buf) = self.editing.as_mut() else {
            return;
        };
        match key {
            KeyCode::Char(c) if buf.chars().count() < 64 => buf.push(c),
            KeyCode::Backspace => {
                buf.pop();
            }
            KeyCode::Esc => self.editing = None,
            KeyCode::Enter => {
                let text = self.editing.take().unwrap_or_default();
                if text.trim().is_empty() {
                    return;
                }
                let id = self.selected_param();
                let before = self.params.clone();
                let r = self.params.set_text(id, &text);
                self.after_change(id, r, before);
            }
            _ => {}
        }
    }

    fn after_change(&mut self, id: ParamId, r: Result<(), String>, before: Params) {
        match r {
            Err(e) => self.message = Some((e, true)),
            Ok(()) => {
                self.message = None;
                if self.params == before {
                    return;
                }
                match id.touches() {
                    Touch::System => {
                        self.diagram.cursor = self.params.alpha;
                        self.reset_bounce();
                        self.effects.extend([
                            Effect::RestartOrbits,
                            Effect::RestartPhase,
                            Effect::RestartSweep,
                        ]);
                    }
                    Touch::Start => {
                        self.reset_bounce();
                        self.effects.push(Effect::RestartPhase);
                    }
                    Touch::Sweep => {
                        self.diagram.cursor =
                            self.diagram.cursor.clamp(self.params.lo, self.params.hi);
                        self.window_changed();
                    }
                }
                // α's line in the diagram sits where the table changed only for α, r, k;
                // the sweep itself depends on everything but α.
                if id == ParamId::Alpha {
                    self.effects.retain(|e| *e != Effect::RestartSweep);
                }
            }
        }
    }

    fn move_cursor(&mut self, dir: i32, fine: bool) {
        let w = self.params.hi - self.params.lo;
        let cols = (self.diagram.grid.sub_size().0).max(1) as f64;
        let step = if fine { w / cols } else { w / 20.0 };
        self.diagram.cursor =
            (self.diagram.cursor + dir as f64 * step).clamp(self.params.lo, self.params.hi);
    }

    /// Zoom the diagram to [lo, hi] (clamped to valid α), pushing the current window.
    pub fn zoom_to(&mut self, lo: f64, hi: f64) {
        let lo = lo.max(1e-6);
        let hi = hi.min(1000.0);
        if hi - lo <= 1e-9 || hi.is_nan() || lo.is_nan() {
            self.message = Some((
                "zoom: the window is empty; mark two different α".into(),
                true,
            ));
            return;
        }
        self.diagram
            .zoom_stack
            .push((self.params.lo, self.params.hi));
        self.params.lo = lo;
        self.params.hi = hi;
        self.diagram.cursor = self.diagram.cursor.clamp(lo, hi);
        self.window_changed();
    }

    fn window_changed(&mut self) {
        self.message = Some((
            format!(
                "sweeping α ∈ [{}, {}]",
                fmt_num(self.params.lo),
                fmt_num(self.params.hi)
            ),
            false,
        ));
        self.effects.push(Effect::RestartSweep);
    }

    fn load_preset(&mut self, i: usize) {
        let Some(p) = self.presets.get(i).cloned() else {
            return;
        };
        let before = self.params.clone();
        let mut next = self.params.clone();
        let r = next
            .set_text(ParamId::Table, &p.table)
            .and_then(|_| next.set_text(ParamId::R, &p.r.to_string()))
            .and_then(|_| next.set_text(ParamId::K, &p.k.to_string()))
            .and_then(|_| {
                next.lo = p.lo;
                next.hi = p.hi;
                next.validate(ParamId::Lo)
            })
            .and_then(|_| {
                let a = next.alpha.clamp(p.lo, p.hi);
                next.set_text(ParamId::Alpha, &a.to_string())
            });
        match r {
            Ok(()) => {
                self.params = next;
                self.diagram.zoom_stack.clear();
                self.after_change(ParamId::Table, Ok(()), before);
                self.message = Some((format!("preset: {}", p.name), false));
            }
            Err(e) => self.message = Some((format!("preset {}: {e}", p.name), true)),
        }
    }

    // ---------------------------------------------------------------- bounce

    /// Start the bounce panel over from the initial state.
    pub fn reset_bounce(&mut self) {
        let sys = self.system();
        let b = &mut self.bounce;
        b.history.clear();
        b.events.clear();
        b.halt = None;
        match self.params.initial(&sys) {
            Ok(st) => {
                b.map = Some(ImpactMap::new(sys, Solver::Exact, st));
                b.history.push(st);
                b.error = None;
            }
            Err(e) => {
                b.map = None;
                b.error = Some(e);
            }
        }
    }

    /// Step `n` events (each one step of the map: bounded work).
    pub fn step(&mut self, n: usize) {
        let b = &mut self.bounce;
        let Some(map) = b.map.as_mut() else { return };
        for _ in 0..n {
            if b.halt.is_some() {
                break;
            }
            match map.step() {
                Ok(e) => {
                    b.events.push(e);
                    b.history.push(*map.state());
                    if b.history.len() > HISTORY {
                        b.history.remove(0);
                        b.events.remove(0);
                    }
                }
                Err(h) => b.halt = Some(h),
            }
        }
    }

    pub fn step_back(&mut self) {
        let b = &mut self.bounce;
        if b.events.is_empty() {
            self.message = Some(("bounce: at the start of the history".into(), true));
            return;
        }
        b.events.pop();
        b.history.pop();
        b.halt = None;
        if let (Some(map), Some(st)) = (b.map.as_mut(), b.history.last()) {
            map.set_state(*st);
        }
    }

    /// Number of impacts stepped from the initial state.
    pub fn bounce_index(&self) -> usize {
        self.bounce.events.len()
    }

    // ---------------------------------------------------------------- results

    /// Values a sweep computes: one per sub-column of the diagram (at least 80).
    pub fn sweep_columns(&self) -> usize {
        self.diagram.grid.sub_size().0.max(80)
    }

    /// The sweep for the current parameters, at the diagram's full resolution (one
    /// α value per sub-cell column).
    pub fn sweep_spec(&self) -> SweepSpec {
        let cols = self.sweep_columns();
        let p = &self.params;
        let mut spec = SweepSpec::new(p.table(), SweepParam::Alpha, p.lo, p.hi, cols);
        spec.r = p.r;
        spec.alpha = p.alpha;
        spec.initial = InitialSpec {
            t0: p.t0,
            v0: p.v0,
            z0: 0.0,
            near_fixed_point: false,
        };
        spec.transient = p.transient.max(1) as u64;
        spec.keep = p.keep as usize;
        spec.preview = if p.transient >= 400 {
            (p.transient / 10) as u64
        } else {
            0
        };
        spec
    }

    /// A new sweep started (or could not start).
    pub fn sweep_started(&mut self, gen: u64, values: usize, r: Result<(), String>) {
        let d = &mut self.diagram;
        d.gen = gen;
        d.slots = vec![None; values];
        d.received = 0;
        d.plotted = 0;
        d.values_done = 0;
        d.values_total = values;
        d.elapsed = 0.0;
        d.started = Some(Instant::now());
        d.status = match r {
            Ok(()) => SweepStatus::Running,
            Err(e) => SweepStatus::Unavailable(e),
        };
        self.rebin_diagram();
        self.dirty = true;
    }

    pub fn phase_started(&mut self, gen: u64) {
        let p = &mut self.phase;
        p.gen = gen;
        p.points.clear();
        p.done = false;
        p.note = None;
        self.rebin_phase();
        self.dirty = true;
    }

    pub fn orbits_started(&mut self, gen: u64) {
        self.orbits.gen = gen;
        self.orbits.info = None;
        self.dirty = true;
    }

    /// Take one worker message; stale generations are dropped.
    pub fn receive(&mut self, msg: Msg) {
        match msg {
            Msg::Phase {
                gen,
                points,
                done,
                note,
            } if gen == self.phase.gen => {
                let mut rebin = false;
                for &(t, v) in &points {
                    if !self.phase.grid.y_range().contains(v) {
                        rebin = true;
                    }
                    self.phase.grid.add(t, v);
                }
                self.phase.points.extend(points);
                if self.phase.points.len() > PHASE_KEEP {
                    let extra = self.phase.points.len() - PHASE_KEEP;
                    self.phase.points.drain(..extra);
                    rebin = true;
                }
                self.phase.done = done;
                self.phase.note = note;
                if rebin {
                    self.rebin_phase();
                }
                self.dirty = true;
            }
            Msg::Sweep(batch) if batch.generation == self.diagram.gen => {
                self.add_batch(batch);
                self.dirty = true;
            }
            Msg::SweepDone { gen } if gen == self.diagram.gen => {
                self.diagram.status = SweepStatus::Done;
                if let Some(s) = self.diagram.started {
                    self.diagram.elapsed = s.elapsed().as_secs_f64();
                }
                self.dirty = true;
            }
            Msg::Orbits { gen, info } if gen == self.orbits.gen => {
                self.orbits.info = Some(info);
                self.dirty = true;
            }
            _ => {}
        }
    }

    /// Points per second of the running sweep.
    pub fn sweep_rate(&self) -> f64 {
        let d = &self.diagram;
        if d.elapsed > 0.0 {
            d.received as f64 / d.elapsed
        } else {
            0.0
        }
    }

    /// Whether any worker may still send something (the loop then polls more often).
    pub fn busy(&self) -> bool {
        !self.paused
            && (self.diagram.status == SweepStatus::Running
                || !self.phase.done
                || self.orbits.info.is_none())
    }

    /// Store one value's batch, replacing an earlier pass of the same value in the
    /// grid (its counts are taken out first).
    pub fn add_batch(&mut self, b: SweepBatch) {
        let d = &mut self.diagram;
        if b.index >= d.slots.len() {
            d.slots.resize(b.index + 1, None);
            d.values_total = d.values_total.max(b.index + 1);
        }
        if let Some(old) = d.slots[b.index].take() {
            for &(t, v) in &old.points {
                d.grid.remove(old.value, d.axis.pick(t, v));
            }
            d.plotted -= old.points.len();
            if old.complete {
                d.values_done -= 1;
            }
        }
        let mut rebin = false;
        let points: Vec<(f64, f64)> = b.points.iter().map(|p| (p.phase, p.v)).collect();
        for &(t, v) in &points {
            let y = d.axis.pick(t, v);
            if !d.grid.y_range().contains(y) {
                rebin = true;
            }
            d.grid.add(b.value, y);
        }
        d.received += points.len() as u64;
        d.plotted += points.len();
        if b.complete {
            d.values_done += 1;
        }
        d.slots[b.index] = Some(Slot {
            value: b.value,
            points,
            complete: b.complete,
            sticking: b.sticking,
        });
        if let Some(s) = d.started {
            d.elapsed = s.elapsed().as_secs_f64();
        }
        if rebin {
            self.rebin_diagram();
        }
    }

    // ---------------------------------------------------------------- layout

    /// Resize the grids to the plot areas of the current layout (re-binning from the
    /// stored points when the size changed).
    pub fn set_plot_sizes(&mut self, diagram: Rect, phase: Rect) {
        self.diagram.plot_area = diagram;
        if self.diagram.grid.size() != (diagram.width, diagram.height)
            || self.diagram.grid.marker() != self.marker
        {
            self.diagram.grid = HitGrid::new(
                diagram.width,
                diagram.height,
                self.marker,
                self.diagram.grid.x_range(),
                self.diagram.grid.y_range(),
            );
            self.rebin_diagram();
            // Grown wider than the sweep has values (a terminal enlarged, or one too
            // small at start): sweep again at the new resolution, or every other
            // column would stay empty.
            let values = self.diagram.values_total;
            if values > 0 && self.sweep_columns() > values {
                self.effects.push(Effect::RestartSweep);
            }
        }
        if self.phase.grid.size() != (phase.width, phase.height) {
            self.phase.grid = HitGrid::new(
                phase.width,
                phase.height,
                self.marker,
                self.phase.grid.x_range(),
                self.phase.grid.y_range(),
            );
            self.rebin_phase();
        }
    }

    /// Re-bin the diagram from its stored points (window, axis or size changed).
    pub fn rebin_diagram(&mut self) {
        let d = &mut self.diagram;
        let x = Range::new(self.params.lo, self.params.hi);
        let y = match d.axis {
            Axis::Phase => Range::new(0.0, 1.0),
            Axis::Velocity => v_range(
                d.slots
                    .iter()
                    .flatten()
                    .flat_map(|s| s.points.iter().map(|p| p.1)),
                self.params.k,
            ),
        };
        let (w, h) = d.grid.size();
        d.grid = HitGrid::new(w, h, self.marker, x, y);
        for s in d.slots.iter().flatten() {
            for &(t, v) in &s.points {
                d.grid.add(s.value, d.axis.pick(t, v));
            }
        }
    }

    pub fn rebin_phase(&mut self) {
        let p = &mut self.phase;
        let y = v_range(p.points.iter().map(|q| q.1), self.params.k);
        let (w, h) = p.grid.size();
        p.grid = HitGrid::new(w, h, self.marker, Range::new(0.0, 1.0), y);
        for &(t, v) in &p.points {
            p.grid.add(t, v);
        }
    }
}

/// A velocity range covering `vs` with a margin (and k/2, the (1, k) velocity).
fn v_range(vs: impl Iterator<Item = f64>, k: u32) -> Range {
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
