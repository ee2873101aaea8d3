//! The live phase plot (t̂, v): every event of the map iterated from the initial state,
//! accumulating in a hit-count grid, the most recent points highlighted, and the (1, k)
//! and (2, 2k) solutions marked where the orbit analysis finds them. Its worker runs on
//! a thread of its own (interactive work) and parks while the application is paused.

use super::diagram::v_range;
use super::{compact, panel, Component, Effect, Msg, Registered, Shared, Workers};
use crate::output::hitgrid::{HitGrid, Marker, Range};
use crate::tui::layout::plot_area_within;
use crate::tui::params::{ParamId, Touch};
use crate::tui::plot::{draw_axes, render, Axes};
use crate::tui::workers::Ticket;
use bouncemap_engine::{Event, ImpactMap, Solver, State, System};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;
use std::time::Duration;

const LABEL_W: u16 = 4;
/// Largest number of points kept (older ones are dropped from the store).
pub const PHASE_KEEP: usize = 20_000;
/// Recent points drawn highlighted.
pub const RECENT: usize = 40;
/// Pacing: a first burst, then steady chunks up to the cap, so that the plot visibly
/// accumulates and then goes idle.
pub const PHASE_BURST: usize = 1500;
pub const PHASE_CHUNK: usize = 250;
pub const PHASE_CAP: usize = 20_000;
pub const PHASE_PACE: Duration = Duration::from_millis(50);

/// A chunk of the phase plot's worker: new points, and why the orbit ended (resting,
/// no landing) if it did.
#[derive(Clone, Debug, PartialEq)]
pub struct PhasePoints {
    pub points: Vec<(f64, f64)>,
    pub done: bool,
    pub note: Option<String>,
}

/// The phase plot panel.
pub struct PhasePlot {
    pub points: Vec<(f64, f64)>,
    pub gen: u64,
    pub done: bool,
    pub note: Option<String>,
    pub grid: HitGrid,
}

impl PhasePlot {
    pub fn new(marker: Marker) -> PhasePlot {
        PhasePlot {
            points: Vec::new(),
            gen: 0,
            done: false,
            note: None,
            grid: HitGrid::new(0, 0, marker, Range::new(0.0, 1.0), Range::new(0.0, 1.0)),
        }
    }

    /// A new run started under generation `gen`.
    pub fn started(&mut self, gen: u64, shared: &Shared) {
        self.gen = gen;
        self.points.clear();
        self.done = false;
        self.note = None;
        self.rebin(shared);
    }

    fn rebin(&mut self, shared: &Shared) {
        let y = v_range(self.points.iter().map(|q| q.1), shared.params.k);
        let (w, h) = self.grid.size();
        self.grid = HitGrid::new(w, h, shared.marker, Range::new(0.0, 1.0), y);
        for &(t, v) in &self.points {
            self.grid.add(t, v);
        }
    }

    /// Take a chunk of points.
    pub fn add(&mut self, chunk: PhasePoints, shared: &Shared) {
        let mut rebin = false;
        for &(t, v) in &chunk.points {
            if !self.grid.y_range().contains(v) {
                rebin = true;
            }
            self.grid.add(t, v);
        }
        self.points.extend(chunk.points);
        if self.points.len() > PHASE_KEEP {
            let extra = self.points.len() - PHASE_KEEP;
            self.points.drain(..extra);
            rebin = true;
        }
        self.done = chunk.done;
        self.note = chunk.note;
        if rebin {
            self.rebin(shared);
        }
    }
}

impl Component for PhasePlot {
    type Msg = PhasePoints;

    /// Resize the grid to the plot area inside `pane`.
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        let plot = plot_area_within(pane, LABEL_W);
        if self.grid.size() != (plot.width, plot.height) || self.grid.marker() != shared.marker {
            self.grid = HitGrid::new(
                plot.width,
                plot.height,
                shared.marker,
                self.grid.x_range(),
                self.grid.y_range(),
            );
            self.rebin(shared);
        }
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if matches!(id.touches(), Touch::System | Touch::Start) {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let sys = shared.system();
        if let Ok(st) = shared.params.initial(&sys) {
            let gen = workers.spawn(Self::ADDRESS, "phase-plot", move |t| {
                phase_worker(sys, st, &t)
            });
            self.started(gen, shared);
        }
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        self.add(msg, shared);
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        !self.done
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        (!self.done).then(|| "phase plot".to_string())
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let state = if self.note.is_some() {
            "ended".to_string()
        } else if self.done {
            "done".into()
        } else if app.paused {
            "paused".into()
        } else {
            "running".into()
        };
        let title = format!(
            " Phase (t̂, v) {} pts, {state}{} ",
            compact(self.points.len() as f64),
            super::manifold_overlay::title_note(app)
        );
        let block = panel(app, title, false);
        let inner = block.inner(area);
        block.render(area, buf);
        let axes = Axes {
            x: self.grid.x_range(),
            y: self.grid.y_range(),
            x_name: "t̂",
            y_name: "v",
        };
        let plot = draw_axes(inner, buf, axes, LABEL_W, &app.theme);
        let recent: Vec<(usize, usize)> = self
            .points
            .iter()
            .rev()
            .take(RECENT)
            .filter_map(|&(t, v)| self.grid.sub_cell(t, v))
            .collect();
        render(
            &self.grid,
            plot,
            buf,
            &app.theme,
            &recent,
            app.theme.recent(),
        );
        // The saddle's manifolds (when on), under the marks.
        let (sx, sy) = self.grid.marker().resolution();
        super::manifold_overlay::draw(app, buf, |t, v| {
            let (i, j) = self.grid.sub_cell(t, v)?;
            let (c, r) = ((i / sx) as u16, (j / sy) as u16);
            (c < plot.width && r < plot.height).then_some((plot.x + c, plot.y + r))
        });
        // Analytic solutions: ◆ for (1, k) (filled if stable), ✕ for the (2, 2k) points;
        // ▣ the state the bounce panel stepped to.
        let mut marks: Vec<((f64, f64), &str, ratatui::style::Style)> = Vec::new();
        if let Some(Ok(info)) = &app.orbits {
            for f in &info.fixed {
                let g = if f.stable { "◆" } else { "◇" };
                marks.push(((f.phase, f.v), g, app.theme.mark()));
            }
            for &q in &info.two {
                marks.push((q, "✕", app.theme.mark2()));
            }
        }
        if let Some(q) = app.stepped {
            marks.push((q, "▣", app.theme.focus()));
        }
        for ((t, v), g, style) in marks {
            if let Some((i, j)) = self.grid.sub_cell(t, v) {
                let (sx, sy) = self.grid.marker().resolution();
                let (c, r) = ((i / sx) as u16, (j / sy) as u16);
                if c < plot.width && r < plot.height {
                    buf.set_string(plot.x + c, plot.y + r, g, style);
                }
            }
        }
        if let Some(n) = &self.note {
            // The whole note, wrapped over the plot's top rows.
            let area = Rect {
                height: plot.height.min(4),
                ..plot
            };
            ratatui::widgets::Paragraph::new(n.as_str())
                .style(app.theme.error())
                .wrap(ratatui::widgets::Wrap { trim: true })
                .render(area, buf);
        }
    }
}

/// Iterate the map from `state`, sending (phase, v) after every event, in paced
/// chunks up to [`PHASE_CAP`] points; parks while paused, stops when stale.
pub fn phase_worker(sys: System, state: State, ticket: &Ticket<Msg, PhasePoints>) {
    let mut map = ImpactMap::new(sys, Solver::Exact, state);
    let mut sent = 0usize;
    while sent < PHASE_CAP {
        if !ticket.wait_if_paused() {
            return;
        }
        let n = if sent == 0 { PHASE_BURST } else { PHASE_CHUNK };
        let mut points = Vec::with_capacity(n);
        let mut note = None;
        for _ in 0..n {
            match map.step() {
                Ok(Event { phase, v, .. }) => points.push((phase, v)),
                Err(h) => {
                    note = Some(h.to_string());
                    break;
                }
            }
        }
        sent += points.len();
        let done = note.is_some() || sent >= PHASE_CAP;
        if !ticket.send(PhasePoints { points, done, note }) || done {
            return;
        }
        std::thread::sleep(PHASE_PACE);
    }
}
