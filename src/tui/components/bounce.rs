//! Bounce stepping: one impact at a time (n, N, b, 0), exactly the events of
//! `bouncemap orbit` from the same start; the ball's flight z(t) (• dots) and the table
//! f(t) (braille line) over the last few events (at least 0.3 periods, so chattering
//! shows as a sequence) on axes of t in periods and z, with the impacts (▾), sticks
//! and releases (▪) and the ball now (●); at the start the first flight, dim. The
//! current event's numbers are printed beside them in shortest round-trip form.
//! Stepping runs on the UI thread: one step of the map is bounded, microseconds of
//! work.

use super::{panel, Component, NoWork, Shared};
use crate::output::hitgrid::Marker;
use crate::tui::keymap::Action;
use crate::tui::layout::Slot;
use crate::tui::params::{ParamId, Params, Touch};
use crate::tui::plot::canvas_marker;
use bouncemap_engine::{Event, EventKind, Halt, ImpactMap, Mode, Solver, State, System};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
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

    /// (t̂, v) of the last event, for the phase plot's ▣ (None before the first step).
    pub fn stepped(&self) -> Option<(f64, f64)> {
        self.events.last().map(|e| (e.phase, e.v))
    }

    /// Events stepped from the initial state.
    pub fn index(&self) -> usize {
        self.events.len()
    }
}

impl Component for Bounce {
    type Msg = NoWork;

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
        shared.stepped = self.stepped();
        // A narrow screen that left this panel out shows it now, in the phase plot's
        // place (the ▣ there marks the same state), and says how to go back.
        if shared.narrow && shared.left_out == Slot::Bounce {
            shared.left_out = Slot::Phase;
            let key = shared.keymap.hint(Action::CyclePanels);
            shared.say(
                format!("bounce panel shown, phase plot left out: {key} cycles them (two bottom panels fit under {} columns)", crate::tui::layout::FULL_W),
                false,
            );
        }
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if matches!(id.touches(), Touch::System | Touch::Start) {
            self.reset(&shared.params);
            shared.stepped = None;
        }
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        render(self, app, area, buf);
    }
}

/// Events shown at most (a long chattering sequence is cut here).
pub const SHOWN_MAX: usize = 400;
/// The shortest stretch of time shown, in table periods, so a chattering sequence
/// shows as a sequence and not as one dot on the table.
pub const MIN_SPAN: f64 = 0.3;

/// What the plot shows: the table and the ball's path over a stretch of time measured
/// from `base` (an integer period), the events in it, and the current state.
pub struct Curves {
    pub base: i64,
    /// (start, end) of the stretch, in periods after `base`.
    pub span: (f64, f64),
    pub table: Vec<(f64, f64)>,
    pub ball: Vec<(f64, f64)>,
    /// (t, z, kind) of each event in the stretch.
    pub events: Vec<(f64, f64, EventKind)>,
    /// Where the ball is now (the last state).
    pub now: (f64, f64),
}

/// The first state shown: at least `SHOWN` flights back and at least `MIN_SPAN`
/// periods, at most `SHOWN_MAX` events.
fn first_shown(history: &[State]) -> usize {
    let n = history.len();
    let last = &history[n - 1];
    let mut from = n - 1;
    while from > 0 && n - 1 - from < SHOWN_MAX {
        let s = &history[from];
        let span = (last.period() - s.period()) as f64 + (last.phase() - s.phase());
        if n - 1 - from >= SHOWN && span >= MIN_SPAN {
            break;
        }
        from -= 1;
    }
    from
}

/// Sample the curves over the last flights of `history` (at least two states), with
/// `samples` points across the stretch.
pub fn curves(sys: &System, history: &[State], samples: usize) -> Option<Curves> {
    let n = history.len();
    if n < 2 {
        return None;
    }
    let from = first_shown(history);
    let base = history[from].period();
    let t_of = |s: &State| (s.period() - base) as f64 + s.phase();
    let (t_start, t_end) = (t_of(&history[from]), t_of(&history[n - 1]));
    let span = (t_end - t_start).max(1e-9);
    let mut table = Vec::with_capacity(samples + 1);
    for i in 0..=samples {
        let t = t_start + span * i as f64 / samples as f64;
        table.push((t, sys.f(t.rem_euclid(1.0))));
    }
    let mut ball = Vec::new();
    for w in history[from..].windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (ta, tb) = (t_of(a), t_of(b));
        let m = ((tb - ta) / span * samples as f64)
            .ceil()
            .clamp(2.0, 4096.0) as usize;
        for i in 0..=m {
            let t = ta + (tb - ta) * i as f64 / m as f64;
            let z = match a.mode() {
                Mode::Flying => {
                    let s = t - ta;
                    sys.f(a.phase()) + a.height() + a.v() * s - s * s / 2.0
                }
                Mode::Stuck => sys.f(t.rem_euclid(1.0)),
            };
            ball.push((t, z));
        }
    }
    let last = &history[n - 1];
    Some(Curves {
        base,
        span: (t_start, t_start + span),
        table,
        ball,
        events: Vec::new(),
        now: (t_end, sys.f(last.phase()) + last.height()),
    })
}

/// A number for the panel: shortest round-trip form where there is room, else six
/// decimals.
fn num(x: f64, wide: bool) -> String {
    if wide {
        bouncemap_engine::fmt_value(x)
    } else {
        format!("{x:.6}")
    }
}

fn render(b: &Bounce, app: &Shared, area: Rect, buf: &mut Buffer) {
    let title = format!(" Bounce #{} ", b.index());
    let (table_glyph, ball_glyph, ball_marker) = glyphs(app.marker);
    let legend = Line::from(vec![
        Span::styled(format!(" {table_glyph} table"), app.theme.table_curve()),
        Span::styled(format!(" {ball_glyph} ball"), app.theme.ball()),
        Span::styled(" ▾ impact", app.theme.mark()),
        Span::styled(" ● now ", app.theme.mark()),
    ]);
    let block = panel(app, title, false).title_bottom(legend);
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
    let gap = if below { "    " } else { " " };
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
                Span::styled(e.kind.as_str().to_string(), app.theme.focus()),
                Span::raw(format!(" period {}", e.period)),
            ];
            if let Some(h) = &b.halt {
                head.push(Span::styled(
                    match h {
                        Halt::Resting { .. } => " resting",
                        Halt::NoLanding { .. } => " no landing",
                        Halt::TimeOutOfRange { .. } => " time out of range",
                    },
                    app.theme.error(),
                ));
            }
            lines.push(Line::from(head));
            lines.push(Line::from(format!("t̂{gap}{}", num(e.phase, below))));
            lines.push(Line::from(format!("v{gap}{}", num(e.v, below))));
            lines.push(Line::from(format!("vrel {}", num(e.vrel, below))));
        }
        None => {
            let s = b.history[0];
            lines.push(Line::from(vec![
                Span::styled("start", app.theme.focus()),
                Span::styled(" (dim: the next flight)", app.theme.dim()),
            ]));
            lines.push(Line::from(format!("t̂{gap}{}", num(s.phase(), below))));
            lines.push(Line::from(format!("v{gap}{}", num(s.v(), below))));
        }
    }
    lines.push(Line::styled(hint, app.theme.dim()));
    Paragraph::new(lines)
        .wrap(Wrap { trim: true })
        .render(numbers, buf);
    let sys = app.system();
    // At the start, the flight the first step will make (one bounded step of a copy).
    let mut shown: Vec<State> = b.history.clone();
    let preview = b.events.is_empty();
    if preview {
        if let Some(mut m) = b.map.clone() {
            if m.step().is_ok() {
                shown.push(*m.state());
            }
        }
    }
    const MARGIN: u16 = 6;
    if plot.width <= MARGIN + 4 || plot.height < 3 {
        return;
    }
    let canvas = Rect {
        x: plot.x + MARGIN,
        y: plot.y,
        width: plot.width - MARGIN,
        height: plot.height - 1,
    };
    let Some(mut c) = curves(&sys, &shown, (canvas.width as usize * 2).max(16)) else {
        Paragraph::new(format!("{}: one impact", app.keymap.hint(Action::StepOne)))
            .style(app.theme.dim())
            .wrap(Wrap { trim: true })
            .render(plot, buf);
        return;
    };
    let t0 = c.span.0;
    for e in b.events.iter().rev() {
        let t = (e.period - c.base) as f64 + e.phase;
        if t < t0 - 1e-12 {
            break;
        }
        c.events.push((t, sys.f(e.phase), e.kind));
    }
    if preview {
        c.now = c.ball.first().copied().unwrap_or(c.now);
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, z) in c.table.iter().chain(&c.ball) {
        lo = lo.min(z);
        hi = hi.max(z);
    }
    let pad = ((hi - lo) * 0.05).max(1e-6);
    let (lo, hi) = (lo - pad, hi + pad);
    let theme = &app.theme;
    // Axes: z in the margin, t (in periods) along the bottom.
    for dy in 0..canvas.height {
        let label = match dy {
            0 => format!("{:>5.5}┤", short(hi)),
            d if d == canvas.height - 1 => format!("{:>5.5}┤", short(lo)),
            d if d == canvas.height / 2 => "    z│".to_string(),
            _ => "     │".to_string(),
        };
        buf.set_string(plot.x, plot.y + dy, label, theme.axis());
    }
    let w = canvas.width as usize;
    let ticks = super::stability::tick_text(
        w,
        &[
            (0, short(c.base as f64 + c.span.0)),
            (w - 1, short(c.base as f64 + c.span.1)),
            (w / 2, "t".to_string()),
        ],
    );
    let bottom = plot.y + plot.height - 1;
    buf.set_string(plot.x + MARGIN - 1, bottom, "└", theme.axis());
    buf.set_string(canvas.x, bottom, ticks, theme.axis());
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([c.span.0, c.span.1])
        .y_bounds([lo, hi])
        .paint(|ctx| {
            ctx.draw(&Points {
                coords: &c.table,
                color: theme.table_curve().fg.unwrap_or_default(),
            });
        })
        .render(canvas, buf);
    // The ball over the table, in its own glyph (distinct without colour).
    let ball_style = if preview { theme.dim() } else { theme.ball() };
    Canvas::default()
        .marker(ball_marker)
        .x_bounds([c.span.0, c.span.1])
        .y_bounds([lo, hi])
        .paint(|ctx| {
            ctx.draw(&Points {
                coords: &c.ball,
                color: ball_style.fg.unwrap_or_default(),
            });
            ctx.layer();
            for &(t, z, kind) in &c.events {
                let g = if kind == EventKind::Impact {
                    "▾"
                } else {
                    "▪"
                };
                ctx.print(t, z, Line::styled(g, theme.mark()));
            }
            ctx.print(c.now.0, c.now.1, Line::styled("●", theme.mark()));
        })
        .render(canvas, buf);
}

/// The glyphs of the table's curve and the ball's path in the legend, and the marker
/// that draws the ball: always different from the table's, so the two differ without
/// colour.
fn glyphs(m: Marker) -> (&'static str, &'static str, ratatui::symbols::Marker) {
    match m {
        Marker::Braille => ("⠤", "•", ratatui::symbols::Marker::Dot),
        Marker::HalfBlock => ("▀", "•", ratatui::symbols::Marker::Dot),
        Marker::Dot => ("•", "▄", ratatui::symbols::Marker::Bar),
    }
}

/// A tick label of at most five characters.
fn short(x: f64) -> String {
    let a = x.abs();
    if a >= 1e5 || (a != 0.0 && a < 1e-3) {
        format!("{x:.0e}")
    } else if a >= 100.0 {
        format!("{x:.0}")
    } else if a >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}
