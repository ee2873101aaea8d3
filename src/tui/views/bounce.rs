//! Bounce stepping: the ball's flight z(t) and the table f(t) over the last few events
//! as curves, and the current event's numbers beside them.

use super::panel;
use crate::engine::{Mode, State, System};
use crate::tui::app::App;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::canvas::{Canvas, Points};
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// Events shown in the plot.
pub const SHOWN: usize = 4;

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

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let b = &app.bounce;
    let title = format!(" Bounce #{} ", app.bounce_index());
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
        app.keymap.hint(crate::tui::keymap::Action::StepOne),
        app.keymap.hint(crate::tui::keymap::Action::StepTen),
        app.keymap.hint(crate::tui::keymap::Action::StepBack)
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
                        crate::engine::Halt::Resting { .. } => " resting",
                        crate::engine::Halt::NoLanding { .. } => " no landing",
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
        Paragraph::new(format!(
            "{}: one impact",
            app.keymap.hint(crate::tui::keymap::Action::StepOne)
        ))
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
        .marker(app.marker.canvas())
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
