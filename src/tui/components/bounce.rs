//! Bounce stepping: one impact at a time (n, N, b, 0), exactly the events of
//! `bouncemap orbit` from the same start; the ball's flight z(t) and the table f(t)
//! over the last few events as curves, and the current event's numbers beside them.
//! Stepping runs on the UI thread: one step of the map is bounded, microseconds of
//! work.

use super::{panel, Component};
use crate::tui::keymap::Action;
use crate::tui::params::{ParamId, Params, Touch};
use crate::tui::plot::canvas_marker;
use crate::tui::shared::Shared;
use bouncemap_engine::{Event, Halt, ImpactMap, Mode, Solver, State, System};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::canvas::{Canvas, Points};
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// Events shown in the plot.
pub const SHOWN: usize = 4;
/// Largest history kept for stepping back.
pub const HISTORY: usize = 10_000;

/// Single-bounce stepping with history.
pub struct Bounce {
    pub map: Option<ImpactMap>,
    /// States after each event; `history[0]` is the initial state.
    pub history: Vec<State>,
    pub events: Vec<Event>,
    pub halt: Option<Halt>,
    pub error: Option<String>,
}

impl Bounce {
    /// At the initial state of `params`.
    pub fn new(params: &Params) -> Bounce {
        let mut b = Bounce {
            map: None,
            history: Vec::new(),
            events: Vec::new(),
            halt: None,
            error: None,
        };
        b.reset(params);
        b
    }

    /// Start over from the initial state.
    pub fn reset(&mut self, params: &Params) {
        let sys = params.system();
        self.history.clear();
        self.events.clear();
        self.halt = None;
        match params.initial(&sys) {
            Ok(st) => {
                self.map = Some(ImpactMap::new(sys, Solver::Exact, st));
                self.history.push(st);
                self.error = None;
            }
            Err(e) => {
                self.map = None;
                self.error = Some(e);
            }
        }
    }

    /// Step `n` events (each one step of the map: bounded work).
    pub fn step(&mut self, n: usize) {
        let Some(map) = self.map.as_mut() else { return };
        for _ in 0..n {
            if self.halt.is_some() {
                break;
            }
            match map.step() {
                Ok(e) => {
                    self.events.push(e);
                    self.history.push(*map.state());
                    if self.history.len() > HISTORY {
                        self.history.remove(0);
                        self.events.remove(0);
                    }
                }
                Err(h) => self.halt = Some(h),
            }
        }
    }

    /// Step back one event; false at the start of the history.
    pub fn step_back(&mut self) -> bool {
        if self.events.is_empty() {
            return false;
        }
        self.events.pop();
        self.history.pop();
        self.halt = None;
        if let (Some(map), Some(st)) = (self.map.as_mut(), self.history.last()) {
            map.set_state(*st);
        }
        true
    }

    /// Events stepped from the initial state.
    pub fn index(&self) -> usize {
        self.events.len()
    }
}

impl Component for Bounce {
    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        match action {
            Action::StepOne => self.step(1),
            Action::StepTen => self.step(10),
            Action::StepBack => {
                if !self.step_back() {
                    shared.say("bounce: at the start of the history", true);
                }
            }
            Action::RestartOrbit => self.reset(&shared.params),
            _ => return false,
        }
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if matches!(id.touches(), Touch::System | Touch::Start) {
            self.reset(&shared.params);
        }
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        render(self, app, area, buf);
    }
}

/// Sampled curves: (table points, ball points, time span).
pub type Curves = (Vec<(f64, f64)>, Vec<(f64, f64)>, (f64, f64));

/// Sample the curves: (table points, ball points) over the last `SHOWN` flights, with
/// time measured from the start of the window.
pub fn curves(sys: &System, history: &[State], samples: usize) -> Curves {
    let n = history.len();
    if n < 2 {
        return (Vec::new(), Vec::new(), (0.0, 1.0));
    }
    let from = n.saturating_sub(SHOWN + 1);
    let base = history[from].period;
    let t_of = |s: &State| (s.period - base) as f64 + s.phase;
    let (t_start, t_end) = (t_of(&history[from]), t_of(&history[n - 1]));
    let span = (t_end - t_start).max(1e-9);
    let mut table = Vec::with_capacity(samples);
    for i in 0..=samples {
        let t = t_start + span * i as f64 / samples as f64;
        table.push((t - t_start, sys.f(t.rem_euclid(1.0))));
    }
    let mut ball = Vec::new();
    for w in history[from..].windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (ta, tb) = (t_of(a), t_of(b));
        let m = ((tb - ta) / span * samples as f64).ceil().max(2.0) as usize;
        for i in 0..=m {
            let t = ta + (tb - ta) * i as f64 / m as f64;
            let z = match a.mode {
                Mode::Flying => {
                    let s = t - ta;
                    sys.f(a.phase) + a.height + a.v * s - s * s / 2.0
                }
                Mode::Stuck => sys.f(t.rem_euclid(1.0)),
            };
            ball.push((t - t_start, z));
        }
    }
    (table, ball, (0.0, span))
}

fn render(b: &Bounce, app: &Shared, area: Rect, buf: &mut Buffer) {
    let title = format!(" Bounce #{} ", b.index());
    let block = panel(app, title, false);
    let inner = block.inner(area);
    block.render(area, buf);
    if let Some(e) = &b.error {
        Paragraph::new(e.clone())
            .style(app.theme.error())
            .wrap(Wrap { trim: true })
            .render(inner, buf);
        return;
    }
    // Full precision below the plot when there is room, else a narrow column beside it.
    let below = inner.height >= 12;
    let (plot, numbers) = if below {
        let [p, n] = Layout::vertical([Constraint::Min(0), Constraint::Length(5)]).areas(inner);
        (p, n)
    } else {
        // A blank column keeps the plot's text from running into the numbers.
        let side = 13u16.min(inner.width / 2);
        let [p, n] = Layout::horizontal([Constraint::Min(0), Constraint::Length(side)])
            .spacing(1)
            .areas(inner);
        (p, n)
    };
    let (dec, gap) = if below { (15, "    ") } else { (6, " ") };
    let mut lines = Vec::new();
    let hint = format!(
        "{} +1 {} +10 {} back",
        app.keymap.hint(Action::StepOne),
        app.keymap.hint(Action::StepTen),
        app.keymap.hint(Action::StepBack)
    );
    match b.events.last() {
        Some(e) => {
            let mut head = vec![
                ratatui::text::Span::styled(e.kind.as_str().to_string(), app.theme.focus()),
                ratatui::text::Span::raw(format!(" period {}", e.period)),
            ];
            if let Some(h) = &b.halt {
                head.push(ratatui::text::Span::styled(
                    match h {
                        Halt::Resting { .. } => " resting",
                        Halt::NoLanding { .. } => " no landing",
                        Halt::TimeOutOfRange { .. } => " time out of range",
                    },
                    app.theme.error(),
                ));
            }
            lines.push(Line::from(head));
            lines.push(Line::from(format!("t̂{gap}{:.dec$}", e.phase)));
            lines.push(Line::from(format!("v{gap}{:.dec$}", e.v)));
            lines.push(Line::from(format!("vrel {:.dec$}", e.vrel)));
        }
        None => {
            let s = b.history[0];
            lines.push(Line::styled("start", app.theme.focus()));
            lines.push(Line::from(format!("t̂{gap}{:.dec$}", s.phase)));
            lines.push(Line::from(format!("v{gap}{:.dec$}", s.v)));
        }
    }
    lines.push(Line::styled(hint, app.theme.dim()));
    Paragraph::new(lines)
        .wrap(Wrap { trim: true })
        .render(numbers, buf);
    let sys = app.system();
    let (table, ball, (t0, t1)) = curves(&sys, &b.history, (plot.width as usize * 2).max(16));
    if ball.is_empty() {
        Paragraph::new(format!("{}: one impact", app.keymap.hint(Action::StepOne)))
            .style(app.theme.dim())
            .wrap(Wrap { trim: true })
            .render(plot, buf);
        return;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, z) in table.iter().chain(&ball) {
        lo = lo.min(z);
        hi = hi.max(z);
    }
    let pad = ((hi - lo) * 0.05).max(1e-6);
    let theme = &app.theme;
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([t0, t1])
        .y_bounds([lo - pad, hi + pad])
        .paint(|ctx| {
            ctx.draw(&Points {
                coords: &table,
                color: theme.table_curve().fg.unwrap_or_default(),
            });
            ctx.layer();
            ctx.draw(&Points {
                coords: &ball,
                color: theme.ball().fg.unwrap_or_default(),
            });
        })
        .render(plot, buf);
}
