//! The attractors along α: in the diagram's place while shown (its key switches), the
//! attractors of the current table and r followed over the diagram's α window (α's
//! default window when another parameter is swept), as `bouncemap attractors` follows
//! them: at each α a basin picture of a small grid of starts, seeded by the α before,
//! its attractors matched to the ones before. It fills in from left to right as α
//! values complete (the continuation runs on a thread of its own, each α's picture on
//! the executor).
//!
//! Above, every attractor's points (a cycle's events, the cells an unsettled orbit
//! visits), t̂ up, in the colour (without colour: the texture) of its attractor number,
//! numbered in order of appearance; below, a strip of the basin fractions stacked in
//! the same colours, the starts not run to an attractor in grey on top. The cursor is
//! an α value: moving it moves the application's α, so the basins panel (shown with
//! this view) draws that α's picture, and the bottom border names that α's attractors,
//! their shares, S_b and what changed there; the basins panel numbers and colours that
//! picture's attractors as this view does ([`Shared::along_alpha`]). Enter brings the
//! diagram back.

use super::{is_focused, panel, Component, Effect, Registered, Shared, Workers};
use crate::output::basin_map::texture_in;
use crate::output::hitgrid::Range;
use crate::tui::keymap::Action;
use crate::tui::layout::{plot_area_within, Slot};
use crate::tui::params::{default_window, ParamId, Params};
use crate::tui::plot::{draw_axes, Axes};
use bouncemap_engine::attractors::global::{collect, Change, ChangeKind, GlobalSpec, Step, Track};
use bouncemap_engine::attractors::{default_w_max, Kind, Settle};
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::System;
use bouncemap_figures::global::{cause_text, describe_member};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::Widget;
use std::time::Instant;

const LABEL_W: u16 = 6;
/// Rows of the strip of basin fractions (with its label row above).
const STRIP: u16 = 5;
/// Starts along each axis at every α.
pub const GRID: usize = 40;
/// α values at most (one per column of the plot, up to this).
pub const MAX_STEPS: usize = 120;

/// What the continuation sends: each α value as it completes, with the changes seen
/// there and the attractors followed so far; or why it stopped.
pub enum GlobalMsg {
    Step {
        step: Box<Step>,
        changes: Vec<Change>,
        tracks: Vec<Track>,
    },
    Failed(String),
    Done,
}

/// The attractors-along-α view.
#[derive(Default)]
pub struct GlobalView {
    pub shown: bool,
    /// The continuation shown (None before the first start).
    pub spec: Option<GlobalSpec>,
    /// The α values done, the changes and the tracks so far.
    pub steps: Vec<Step>,
    pub changes: Vec<Change>,
    pub tracks: Vec<Track>,
    /// The cursor: an α value (index).
    pub cursor: usize,
    pub gen: u64,
    pub done: bool,
    pub error: Option<String>,
    started: Option<Instant>,
    elapsed: f64,
    /// Columns of the plot at the last layout.
    columns: usize,
}

/// The continuation the current parameters ask for, with `columns` α values at most:
/// the diagram's α window (or α's default one), the current table and r, a
/// [`GRID`]×[`GRID`] picture of the starts at each α.
pub fn global_spec(params: &Params, columns: usize) -> Result<GlobalSpec, String> {
    let (lo, hi) = if params.param == SweepParam::Alpha {
        (params.lo, params.hi)
    } else {
        default_window(SweepParam::Alpha, &params.table, &params.table())
    };
    let sys = System::new(params.table(), hi, params.r).map_err(|e| e.to_string())?;
    let spec = GlobalSpec {
        w_max: default_w_max(&sys),
        sys,
        lo,
        hi,
        steps: columns.clamp(2, MAX_STEPS),
        nx: GRID,
        ny: GRID,
        settle: Settle::BASINS,
        stop_at_known: true,
        sampled_starts: 0,
    };
    spec.validate().map_err(|e| e.to_string())?;
    Ok(spec)
}

impl GlobalView {
    fn spec_for(&self, shared: &Shared) -> Result<GlobalSpec, String> {
        global_spec(&shared.params, self.columns)
    }

    /// Put the cursor at the value nearest the application's α.
    fn place_cursor(&mut self, shared: &Shared) {
        if let Some(s) = &self.spec {
            let f = (shared.params.alpha - s.lo) / (s.hi - s.lo);
            self.cursor = ((f * (s.steps - 1) as f64).round().max(0.0) as usize).min(s.steps - 1);
        }
    }

    /// Move the cursor by `by` values (within those done) and the application's α to
    /// it.
    fn move_cursor(&mut self, by: i64, shared: &mut Shared) {
        if self.steps.is_empty() {
            return;
        }
        let last = self.steps.len() as i64 - 1;
        self.cursor = (self.cursor as i64 + by).clamp(0, last) as usize;
        self.publish(shared);
        let alpha = self.steps[self.cursor].alpha;
        let before = shared.params.clone();
        let r = shared
            .params
            .set_text(ParamId::Alpha, &bouncemap_engine::fmt_value(alpha));
        shared.after_change(ParamId::Alpha, r, &before);
    }

    /// Tell the other panels the cursor's α and its attractors (none while hidden).
    fn publish(&self, shared: &mut Shared) {
        shared.along_alpha = self
            .steps
            .get(self.cursor)
            .filter(|_| self.shown)
            .map(|s| (s.alpha, s.members.clone()));
    }

    fn title(&self, shared: &Shared) -> String {
        let head = " Attractors along α";
        let Some(s) = &self.spec else {
            return format!("{head} ");
        };
        let state = if let Some(e) = &self.error {
            format!("stopped: {e}")
        } else if self.done {
            if shared.show_times {
                format!("done {:.1}s", self.elapsed)
            } else {
                "done".into()
            }
        } else {
            format!("{}/{} α", self.steps.len(), s.steps)
        };
        format!(
            "{head} · {state} · {} followed · {}×{} starts, T={} ",
            self.tracks.len(),
            s.nx,
            s.ny,
            crate::tui::params::fmt_num(s.settle.transient as f64)
        )
    }

    /// The bottom border: the cursor's α, its attractors and shares, S_b, and what
    /// changed there.
    fn at_cursor(&self) -> String {
        let Some(step) = self.steps.get(self.cursor) else {
            return " computing the first α value… ".into();
        };
        let mut parts = vec![format!("α {}", bouncemap_engine::fmt_value(step.alpha))];
        for m in &step.members {
            parts.push(format!(
                "{}: {:.1}% {}",
                m.track + 1,
                100.0 * m.fraction,
                describe_member(m)
            ));
        }
        if step.not_settled > 0 {
            parts.push(format!(
                "not settled {:.1}%",
                100.0 * step.not_settled_fraction()
            ));
        }
        if let Some(e) = step.entropy {
            parts.push(format!("S_b {:.2}", e.s_b));
        }
        for c in self.changes.iter().filter(|c| c.step == self.cursor) {
            let n = c.track + 1;
            let why = c
                .cause
                .map(|x| format!(" ({})", cause_text(&x)))
                .unwrap_or_default();
            parts.push(match &c.what {
                ChangeKind::Birth => format!("{n} appears{why}"),
                ChangeKind::Death { into: Some(t) } => {
                    format!("{n} gone into {}{why}", t + 1)
                }
                ChangeKind::Death { into: None } => format!("{n} gone{why}"),
                other => format!("{n}: {}", other.name()),
            });
        }
        format!(" {} ", parts.join(" · "))
    }

    /// The style of attractor `track` of kind `kind`, and its mark without colour.
    fn style(&self, shared: &Shared, track: usize, kind: Kind) -> (Style, char) {
        let rest = matches!(kind, Kind::Resting | Kind::Escaping);
        match (rest, shared.theme.attractor_color(track)) {
            (true, Some(_)) => (
                Style::new().fg(shared.theme.nowhere().unwrap_or_default()),
                '◦',
            ),
            (false, Some(c)) => (Style::new().fg(c), '∙'),
            (_, None) => (
                shared.theme.attractor(track),
                texture_in(shared.marker, track + 1),
            ),
        }
    }
}

impl Component for GlobalView {
    type Msg = GlobalMsg;

    fn shown(&self) -> bool {
        self.shown
    }

    fn focusable(&self) -> bool {
        true
    }

    /// One α value per column of the plot (up to [`MAX_STEPS`]): a new width restarts
    /// the continuation (if shown).
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        let plot = plot_area_within(pane, LABEL_W);
        let columns = plot.width as usize;
        if columns != self.columns {
            self.columns = columns;
            if self.shown {
                shared.effect(Effect::Start(Self::TARGET));
            }
        }
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action == Action::ToggleGlobal {
            self.shown = !self.shown;
            shared.effect(Effect::Start(Self::TARGET));
            self.publish(shared);
            if self.shown {
                shared.focus = Slot::Diagram;
                shared.say(
                    "attractors along α: arrows move α (the basins panel shows its picture); Enter or the key again shows the diagram",
                    false,
                );
            }
            // Shown, the key goes on to the basins panel, which shows itself too.
            return !self.shown;
        }
        if action == Action::TogglePlane && self.shown {
            // The plane takes the diagram's place instead: this view steps aside.
            self.shown = false;
            self.publish(shared);
            shared.effect(Effect::Start(Self::TARGET));
            return false;
        }
        if !self.shown || shared.focus != Slot::Diagram {
            return false;
        }
        match action {
            Action::Left => self.move_cursor(-4, shared),
            Action::Right => self.move_cursor(4, shared),
            Action::FineLeft => self.move_cursor(-1, shared),
            Action::FineRight => self.move_cursor(1, shared),
            Action::Enter => {
                self.shown = false;
                self.publish(shared);
                shared.effect(Effect::Start(Self::TARGET));
                shared.say("the diagram again, at the α chosen", false);
            }
            // The diagram's other keys do nothing while this view is shown.
            Action::Up
            | Action::Down
            | Action::ToggleAxis
            | Action::ZoomIn
            | Action::ZoomOut
            | Action::ZoomBack
            | Action::MarkWindow
            | Action::Colouring
            | Action::AllAttractors => {}
            _ => return false,
        }
        true
    }

    fn changed(&mut self, _id: ParamId, shared: &mut Shared) {
        if self.shown && self.spec_for(shared).ok() != self.spec {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if !self.shown {
            workers.cancel(Self::TARGET);
            self.done = true;
            return;
        }
        let spec = match self.spec_for(shared) {
            Ok(s) => s,
            Err(e) => {
                workers.cancel(Self::TARGET);
                self.error = Some(e);
                self.done = true;
                return;
            }
        };
        if self.spec.as_ref() == Some(&spec) && self.error.is_none() {
            // The same continuation, complete or still filling in: keep it (it goes
            // on only if it was stopped by hiding the view).
            if self.done && self.steps.len() == spec.steps {
                return;
            }
        }
        self.spec = Some(spec.clone());
        self.steps.clear();
        self.changes.clear();
        self.tracks.clear();
        self.done = false;
        self.error = None;
        self.started = Some(Instant::now());
        self.place_cursor(shared);
        self.publish(shared);
        self.gen = workers.spawn_jobs(
            Self::ADDRESS,
            "attractors-along-alpha",
            move |ticket, executor| {
                let mut sent = 0;
                let result = collect(spec, &executor, ticket.control(), &mut |cont| {
                    let i = cont.steps().len() - 1;
                    sent = cont.steps().len();
                    ticket.send(GlobalMsg::Step {
                        step: Box::new(cont.steps()[i].clone()),
                        changes: cont
                            .changes()
                            .iter()
                            .filter(|c| c.step == i)
                            .cloned()
                            .collect(),
                        tracks: cont.tracks().to_vec(),
                    });
                });
                match result {
                    Err(e) => {
                        ticket.send(GlobalMsg::Failed(e.to_string()));
                    }
                    Ok(c) if c.complete() && sent == c.steps().len() => {
                        ticket.send(GlobalMsg::Done);
                    }
                    Ok(_) => {}
                }
            },
        );
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        shared.dirty = true;
        if let Some(t) = self.started {
            self.elapsed = t.elapsed().as_secs_f64();
        }
        match msg {
            GlobalMsg::Step {
                step,
                changes,
                tracks,
            } => {
                self.steps.push(*step);
                self.changes.extend(changes);
                self.tracks = tracks;
                if self.steps.len() == self.cursor + 1 {
                    self.publish(shared);
                }
            }
            GlobalMsg::Failed(e) => {
                self.error = Some(e);
                self.done = true;
            }
            GlobalMsg::Done => self.done = true,
        }
    }

    fn busy(&self) -> bool {
        self.shown && !self.done
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        let s = self.spec.as_ref()?;
        (self.shown && !self.done).then(|| format!("attractors {}/{} α", self.steps.len(), s.steps))
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let focused = is_focused(app, Slot::Diagram);
        let block = panel(app, self.title(app), focused).title_bottom(self.at_cursor());
        let inner = block.inner(area);
        block.render(area, buf);
        let Some(spec) = &self.spec else { return };
        if let Some(e) = &self.error {
            buf.set_string(inner.x + 1, inner.y, e, app.theme.error());
        }
        let strip = STRIP.min(inner.height / 3);
        let top = Rect {
            height: inner.height - strip,
            ..inner
        };
        let axes = Axes {
            x: Range::new(spec.lo, spec.hi),
            y: Range::new(0.0, 1.0),
            x_name: "α",
            y_name: "t̂",
        };
        let plot = draw_axes(top, buf, axes, LABEL_W, &app.theme);
        if plot.width == 0 || plot.height == 0 {
            return;
        }
        let column = |i: usize| -> u16 {
            let f = if spec.steps > 1 {
                i as f64 / (spec.steps - 1) as f64
            } else {
                0.0
            };
            plot.x + ((f * (plot.width - 1) as f64).round() as u16).min(plot.width - 1)
        };
        // The points: t̂ up, one cell each, in the attractor's colour.
        for (i, s) in self.steps.iter().enumerate() {
            let x = column(i);
            for m in &s.members {
                let (style, mark) = self.style(app, m.track, m.kind);
                for &(t, _) in &m.points {
                    let row = ((1.0 - t) * plot.height as f64).floor() as i64;
                    let y = plot.y + row.clamp(0, plot.height as i64 - 1) as u16;
                    buf.set_string(x, y, mark.to_string(), style);
                }
            }
        }
        // The strip: fractions stacked from the bottom, a row per 1/strip.
        if strip >= 2 {
            let label_y = top.y + top.height;
            buf.set_string(inner.x, label_y, "basin fractions", app.theme.axis());
            let rows = strip - 1;
            for (i, s) in self.steps.iter().enumerate() {
                let x = column(i);
                for r in 0..rows {
                    let centre = (r as f64 + 0.5) / rows as f64;
                    let mut below = 0.0;
                    let mut at = None;
                    for m in &s.members {
                        below += m.fraction;
                        if centre < below {
                            at = Some(m);
                            break;
                        }
                    }
                    let y = label_y + rows - r;
                    match at {
                        Some(m) => {
                            let (style, mark) = self.style(app, m.track, m.kind);
                            let glyph = if app.theme.attractor_color(0).is_some() {
                                '█'
                            } else {
                                mark
                            };
                            buf.set_string(x, y, glyph.to_string(), style);
                        }
                        None => {
                            buf.set_string(x, y, "░", app.theme.dim());
                        }
                    }
                }
            }
        }
        // The cursor: a mark above its column and under it.
        if self.cursor < spec.steps {
            let x = column(self.cursor);
            buf.set_string(x, plot.y + plot.height, "▲", app.theme.cursor());
        }
    }
}
