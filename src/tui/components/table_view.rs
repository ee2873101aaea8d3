//! The table view (key `T`): the current table's F, F′ and F″ over one period, as the
//! paper's Fig. 2 draws F_D, with its breakpoints (┆, where F″ jumps), the phases t̂* of
//! the (1, k) solutions (◆ stable, ◇ unstable), the sticking threshold F″ = −1/α
//! (dashed) and the release phases (R), where a ball riding on the table leaves it.
//! Draw-only.

use super::Shared;
use crate::tui::params::fmt_num;
use crate::tui::plot::canvas_marker;
use bouncemap_engine::System;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::Line;
use ratatui::widgets::canvas::{Canvas, Points};
use ratatui::widgets::{Block, BorderType, Clear, Widget};

/// Left margin of each plot: its value labels.
const MARGIN: u16 = 7;

/// Phases in [0, 1) where α F″ drops below −1 (a riding ball is released there),
/// located exactly by the engine's release search from a sampled bracket.
pub fn release_phases(sys: &System) -> Vec<f64> {
    const N: usize = 4096;
    let below = |t: f64| sys.alpha() * sys.table().jet(t)[2] < -1.0;
    let mut out: Vec<f64> = Vec::new();
    let mut prev = below(1.0 - 0.5 / N as f64);
    for i in 0..N {
        let t = i as f64 / N as f64;
        let now = below(t);
        if now && !prev {
            let from = (t - 1.0 / N as f64).rem_euclid(1.0);
            if let Some((_, at)) = sys.table().release_after(sys.alpha(), 0, from, false) {
                if !out.iter().any(|&q| (q - at).abs() < 1e-9) {
                    out.push(at);
                }
            }
        }
        prev = now;
    }
    out.sort_by(f64::total_cmp);
    out
}

/// Draw the view over `area` (the whole screen).
pub fn draw(app: &Shared, area: Rect, buf: &mut Buffer) {
    let r = Rect {
        x: area.x + 1,
        y: area.y + 1,
        width: area.width.saturating_sub(2),
        height: area.height.saturating_sub(2),
    };
    Clear.render(r, buf);
    let title = format!(
        " Table {}: F, F′, F″ over one period (α = {}; T or Esc closes) ",
        app.params.table_label(),
        fmt_num(app.params.alpha)
    );
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(app.theme.focus())
        .title(title)
        .title_bottom(Line::styled(
            app.marker.samples(
                " ┆ breakpoint (F″ jumps)  ◆ ◇ t̂* of (1,k) stable, unstable  ⠒ ⠒ F″ = −1/α  R release ",
            ),
            app.theme.dim(),
        ));
    let inner = block.inner(r);
    block.render(r, buf);
    if inner.height < 10 || inner.width < MARGIN + 20 {
        buf.set_string(
            inner.x,
            inner.y,
            "(too small for the table view)",
            app.theme.dim(),
        );
        return;
    }
    let sys = app.system();
    let [p0, p1, p2, axis] = Layout::vertical([
        Constraint::Ratio(1, 3),
        Constraint::Ratio(1, 3),
        Constraint::Ratio(1, 3),
        Constraint::Length(1),
    ])
    .areas(inner);
    let fixed: Vec<(f64, bool)> = match &app.orbits {
        Some(Ok(i)) => i.fixed.iter().map(|f| (f.phase, f.stable)).collect(),
        _ => Vec::new(),
    };
    // Where f'' jumps (a piece boundary across which the table is one polynomial, as
    // F_1's at ½, is none).
    let breaks: Vec<f64> = bouncemap_engine::orbits::events::jump_phases(sys.table())
        .into_iter()
        .filter(|&b| b > 0.0 && b < 1.0)
        .collect();
    let threshold = -1.0 / sys.alpha();
    let releases = release_phases(&sys);
    for (order, area) in [p0, p1, p2].into_iter().enumerate() {
        let name = ["F", "F′", "F″"][order];
        plot(
            app,
            &sys,
            order,
            name,
            area,
            buf,
            &Marks {
                breaks: &breaks,
                fixed: if order == 1 { &[] } else { &fixed },
                threshold: (order == 2).then_some(threshold),
                releases: if order == 2 { &releases } else { &[] },
            },
        );
    }
    // The common t̂ axis.
    let w = (axis.width - MARGIN) as usize;
    let ticks = super::stability::tick_text(
        w,
        &[
            (0, "0".into()),
            (w / 2, "½".into()),
            (w - 1, "1".into()),
            (w / 4, "t̂".into()),
        ],
    );
    buf.set_string(axis.x + MARGIN - 1, axis.y, "└", app.theme.axis());
    buf.set_string(axis.x + MARGIN, axis.y, ticks, app.theme.axis());
}

struct Marks<'a> {
    breaks: &'a [f64],
    fixed: &'a [(f64, bool)],
    threshold: Option<f64>,
    releases: &'a [f64],
}

fn plot(
    app: &Shared,
    sys: &System,
    order: usize,
    name: &str,
    area: Rect,
    buf: &mut Buffer,
    marks: &Marks,
) {
    if area.height < 2 || area.width <= MARGIN + 2 {
        return;
    }
    let canvas = Rect {
        x: area.x + MARGIN,
        width: area.width - MARGIN,
        ..area
    };
    let n = canvas.width as usize * 2;
    let pts: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let t = (i as f64 / n as f64).min(1.0 - 1e-12);
            (t, sys.table().jet(t)[order])
        })
        .collect();
    let (mut lo, mut hi) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, y)| {
            (a.min(y), b.max(y))
        });
    if let Some(th) = marks.threshold {
        lo = lo.min(th);
        hi = hi.max(th);
    }
    let pad = ((hi - lo) * 0.08).max(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let axis = app.theme.axis();
    for dy in 0..area.height {
        let label = match dy {
            0 => format!("{:>6.6}┤", fmt_num(hi)),
            d if d == area.height - 1 => format!("{:>6.6}┤", fmt_num(lo)),
            d if d == area.height / 2 => format!("{name:>6}│"),
            _ => "      │".to_string(),
        };
        buf.set_string(area.x, area.y + dy, label, axis);
    }
    let theme = &app.theme;
    let dashed = |style: Style| style.fg.unwrap_or_default();
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([0.0, 1.0])
        .y_bounds([lo, hi])
        .paint(|ctx| {
            ctx.draw(&Points {
                coords: &pts,
                color: theme.table_curve().fg.unwrap_or_default(),
            });
            ctx.layer();
            if lo < 0.0 && hi > 0.0 {
                let zero: Vec<(f64, f64)> = (0..=40).map(|i| (i as f64 / 40.0, 0.0)).collect();
                ctx.draw(&Points {
                    coords: &zero,
                    color: dashed(theme.axis()),
                });
            }
            if let Some(th) = marks.threshold {
                let dashes: Vec<(f64, f64)> = (0..=n)
                    .filter(|i| i % 4 < 2)
                    .map(|i| (i as f64 / n as f64, th))
                    .collect();
                ctx.draw(&Points {
                    coords: &dashes,
                    color: dashed(theme.mark2()),
                });
            }
            ctx.layer();
            // Breakpoints as dashed vertical lines.
            let rows = area.height as usize;
            for &b in marks.breaks {
                for j in 0..rows {
                    let y = lo + (hi - lo) * (j as f64 + 0.5) / rows as f64;
                    ctx.print(b, y, Line::styled("┆", theme.dim()));
                }
            }
            if let Some(th) = marks.threshold {
                ctx.print(0.93, th, Line::styled("−1/α", theme.mark2()));
                for &t in marks.releases {
                    ctx.print(t, th, Line::styled("R", theme.mark2()));
                }
            }
            for &(t, stable) in marks.fixed {
                let y = sys.table().jet(t)[order];
                ctx.print(
                    t,
                    y,
                    Line::styled(if stable { "◆" } else { "◇" }, theme.mark()),
                );
            }
        })
        .render(canvas, buf);
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::Table;

    /// The sine's release phase in closed form: α F″ = −4π²α sin 2πt̂ < −1 from
    /// t̂ = asin(1/(4π²α))/(2π) on.
    #[test]
    fn the_sine_releases_where_its_closed_form_says() {
        for alpha in [0.026725, 0.03, 0.1] {
            let sys = System::new(Table::sine(), alpha, 0.8).unwrap();
            let tau = std::f64::consts::TAU;
            let want = (1.0 / (tau * tau * alpha)).asin() / tau;
            let got = release_phases(&sys);
            assert_eq!(got.len(), 1, "α {alpha}: {got:?}");
            assert!(
                (got[0] - want).abs() < 1e-12,
                "α {alpha}: {got:?} vs {want}"
            );
        }
        // Below 1/(4π²) the table never pulls away from a riding ball.
        let sys = System::new(Table::sine(), 0.02, 0.8).unwrap();
        assert!(release_phases(&sys).is_empty());
    }

    /// F_D: α F_D″ jumps below −1 at t̂ = 0 when α(2 + D) > 1 (F_D″(0⁺) = −(2 + D)).
    #[test]
    fn fd_releases_at_its_breakpoint_when_the_jump_crosses_the_threshold() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.6, 0.8).unwrap();
        let got = release_phases(&sys);
        assert!(got.iter().any(|&t| t.min(1.0 - t) < 1e-12), "{got:?}");
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        assert!(release_phases(&sys).is_empty());
    }
}
