//! The stability panel: κ_c for the current r, f''(t̂*) of each (1, k) solution against
//! the stable band κ_c < f'' < 0, the eigenvalues against the unit circle, and the
//! stable region of the (1, k) solution in the (α, r) plane with the current point.
//! It owns the orbit analysis (which the diagram and the phase plot also mark), run on
//! a thread of its own so it answers within milliseconds whatever a sweep is doing.

use super::{panel, Component, Target};
use crate::tui::analysis::{orbit_info, FixedPoint, OrbitInfo};
use crate::tui::params::{fmt_num, ParamId, Touch};
use crate::tui::plot::canvas_marker;
use crate::tui::shared::{Effect, Shared};
use crate::tui::workers::{Body, Workers};
use bouncemap_engine::kappa_c;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Circle, Points};
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// The stability panel; it runs the orbit analysis, whose result it puts in
/// [`Shared::orbits`] for every panel.
#[derive(Default)]
pub struct Stability {
    pub gen: u64,
    pending: bool,
}

impl Stability {
    /// A new analysis started under generation `gen`.
    pub fn started(&mut self, gen: u64, shared: &mut Shared) {
        self.gen = gen;
        self.pending = true;
        shared.orbits = None;
    }
}

impl Component for Stability {
    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if id.touches() == Touch::System {
            shared.effect(Effect::Start(Target::Orbits));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let (sys, k) = (shared.system(), shared.params.k);
        // Not paused with the rest: a few milliseconds, and the panels need it.
        let gen = workers.spawn(Target::Orbits, "orbit-analysis", move |t| {
            if !t.stale() {
                t.send(orbit_info(&sys, k));
            }
        });
        self.started(gen, shared);
    }

    fn receive(&mut self, gen: u64, body: Body, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        if let Ok(info) = body.downcast::<Result<OrbitInfo, String>>() {
            shared.orbits = Some(*info);
            self.pending = false;
            shared.dirty = true;
        }
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        render(app, area, buf);
    }
}

fn render(app: &Shared, area: Rect, buf: &mut Buffer) {
    let block = panel(app, format!(" Stability of (1, {}) ", app.params.k), false);
    let inner = block.inner(area);
    block.render(area, buf);
    if inner.height < 3 {
        return;
    }
    let kc = kappa_c(app.params.r);
    let fixed = match &app.orbits {
        Some(Ok(i)) => Some(&i.fixed[..]),
        _ => None,
    };
    let mut lines = vec![Line::from(vec![
        Span::raw("κ_c = "),
        Span::styled(format!("{kc:.4}"), app.theme.focus()),
        Span::raw(format!("  (r = {})", fmt_num(app.params.r))),
    ])];
    lines.push(band_line(
        app,
        kc,
        fixed.unwrap_or(&[]),
        inner.width as usize,
    ));
    match &app.orbits {
        None => lines.push(Line::styled("solving (1, k)…", app.theme.dim())),
        Some(Err(e)) => lines.push(Line::styled(
            format!("(1, k) analysis {e}"),
            app.theme.dim(),
        )),
        Some(Ok(i)) if i.fixed.is_empty() => lines.push(Line::styled(
            format!("no (1, {}) solution at this α", app.params.k),
            app.theme.dim(),
        )),
        Some(Ok(i)) => {
            for f in &i.fixed {
                lines.push(Line::from(vec![
                    Span::styled(
                        if f.stable {
                            "◆ stable  "
                        } else {
                            "◇ unstable"
                        },
                        app.theme.mark(),
                    ),
                    Span::raw(format!(" t̂*={:.4} f''={:.4}", f.phase, f.f2)),
                ]));
            }
        }
    }
    let text_h = (lines.len() as u16).min(inner.height);
    let [text, plots] =
        Layout::vertical([Constraint::Length(text_h), Constraint::Min(0)]).areas(inner);
    Paragraph::new(lines)
        .wrap(Wrap { trim: true })
        .render(text, buf);
    if plots.height < 4 {
        return;
    }
    let circle_w = (plots.height * 2 + 2).min(plots.width / 2);
    let [circ, region] =
        Layout::horizontal([Constraint::Length(circle_w), Constraint::Min(0)]).areas(plots);
    eigen_circle(app, fixed, circ, buf);
    region_plot(app, region, buf);
}

/// A number line from 1.5 κ_c to a little above 0 with the stable band and each f''.
fn band_line<'a>(app: &Shared, kc: f64, fixed: &[FixedPoint], w: usize) -> Line<'a> {
    let w = w.max(12);
    let lo = 1.5 * kc;
    let hi = -0.25 * kc;
    let col = |x: f64| {
        (((x - lo) / (hi - lo)) * (w as f64 - 1.0))
            .round()
            .clamp(0.0, w as f64 - 1.0) as usize
    };
    let mut cells: Vec<(String, Style)> =
        (0..w).map(|_| ("─".to_string(), app.theme.dim())).collect();
    let (a, b) = (col(kc), col(0.0));
    for c in cells.iter_mut().take(b + 1).skip(a) {
        *c = ("═".into(), app.theme.stable());
    }
    cells[a] = ("[".into(), app.theme.stable());
    cells[b] = ("]".into(), app.theme.stable());
    for f in fixed {
        if f.f2.is_finite() {
            cells[col(f.f2)] = (if f.stable { "◆" } else { "◇" }.into(), app.theme.mark());
        }
    }
    Line::from(
        cells
            .into_iter()
            .map(|(s, st)| Span::styled(s, st))
            .collect::<Vec<_>>(),
    )
}

fn eigen_circle(app: &Shared, fixed: Option<&[FixedPoint]>, area: Rect, buf: &mut Buffer) {
    let eig: Vec<(f64, f64)> = fixed
        .unwrap_or(&[])
        .iter()
        .flat_map(|f| f.eig)
        .map(|(re, im)| (re.clamp(-1.45, 1.45), im.clamp(-1.45, 1.45)))
        .collect();
    let theme = &app.theme;
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([-1.5, 1.5])
        .y_bounds([-1.5, 1.5])
        .paint(|ctx| {
            ctx.draw(&Circle {
                x: 0.0,
                y: 0.0,
                radius: 1.0,
                color: theme.axis().fg.unwrap_or_default(),
            });
            ctx.layer();
            ctx.draw(&Points {
                coords: &eig,
                color: theme.mark().fg.unwrap_or_default(),
            });
            ctx.print(-1.5, 1.5, Line::styled("λ", theme.dim()));
        })
        .render(area, buf);
}

fn region_plot(app: &Shared, area: Rect, buf: &mut Buffer) {
    let rows = match &app.orbits {
        Some(Ok(i)) if !i.region.is_empty() => &i.region,
        Some(Err(_)) => {
            Paragraph::new("(α, r) region not available")
                .style(app.theme.dim())
                .wrap(Wrap { trim: true })
                .render(area, buf);
            return;
        }
        _ => return,
    };
    let amax = rows
        .iter()
        .flat_map(|r| r.intervals.iter().map(|iv| iv.1))
        .fold(app.params.alpha, f64::max)
        * 1.1;
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .flat_map(|row| {
            row.intervals.iter().flat_map(move |&(a, b)| {
                (0..=40).map(move |i| (a + (b - a) * i as f64 / 40.0, row.r))
            })
        })
        .collect();
    let here = [(app.params.alpha, app.params.r)];
    let theme = &app.theme;
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([0.0, amax])
        .y_bounds([0.0, 1.0])
        .paint(|ctx| {
            ctx.draw(&Points {
                coords: &pts,
                color: theme.stable().fg.unwrap_or_default(),
            });
            ctx.layer();
            ctx.draw(&Points {
                coords: &here,
                color: theme.mark().fg.unwrap_or_default(),
            });
            ctx.print(0.0, 0.0, Line::styled("(α, r)", theme.dim()));
            ctx.print(
                app.params.alpha.min(amax),
                app.params.r,
                Line::styled("✕", theme.mark()),
            );
        })
        .render(area, buf);
}
