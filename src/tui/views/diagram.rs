//! The bifurcation diagram: the hit-count grid of the sweep (phase t̂ or v against α)
//! with axes, a progress gauge and points/s in the title, the current α as a cursor
//! line, the zoom cursor and window mark, and marks at the birth and the period
//! doubling (α_PD) of the (1, k) solution.

use super::{compact, is_focused, panel};
use crate::tui::app::{App, Axis, Focus, SweepStatus};
use crate::tui::params::fmt_num;
use crate::tui::plot::{draw_axes, Range};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// Width of the y tick labels.
const LABEL_W: u16 = 5;

/// The plot rectangle inside the pane (border, y labels, x labels removed).
pub fn plot_area(pane: Rect) -> Rect {
    super::plot_area_within(pane, LABEL_W)
}

fn gauge(frac: f64, w: usize) -> String {
    let full = (frac.clamp(0.0, 1.0) * w as f64).round() as usize;
    format!("{}{}", "█".repeat(full), "░".repeat(w - full))
}

pub fn title(app: &App) -> String {
    let d = &app.diagram;
    let axis = match d.axis {
        Axis::Phase => "t̂",
        Axis::Velocity => "v",
    };
    let head = format!(" Bifurcation diagram: {axis} vs α ");
    match &d.status {
        SweepStatus::Running | SweepStatus::Done => {
            let frac = d.values_done as f64 / d.values_total.max(1) as f64;
            let state = if d.status == SweepStatus::Done {
                format!("done {:.1}s", d.elapsed)
            } else if app.paused {
                "paused".into()
            } else {
                format!("{} pts/s", compact(app.sweep_rate()))
            };
            format!(
                "{head}{} {:>3}% {} pts, {state} ",
                gauge(frac, 10),
                (frac * 100.0).round() as u32,
                compact(d.plotted as f64)
            )
        }
        SweepStatus::Idle => head,
        SweepStatus::Unavailable(_) => head,
    }
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let focused = is_focused(app, Focus::Diagram);
    let block = panel(app, title(app), focused);
    let inner = block.inner(area);
    block.render(area, buf);
    let d = &app.diagram;
    if let SweepStatus::Unavailable(why) = &d.status {
        Paragraph::new(format!("Bifurcation diagram {why}."))
            .style(app.theme.dim())
            .wrap(Wrap { trim: true })
            .render(inner, buf);
        return;
    }
    let x = d.grid.x_range();
    let y = d.grid.y_range();
    let plot = draw_axes(inner, buf, x, y, LABEL_W, &app.theme);
    d.grid.render(plot, buf, &app.theme, &[], Style::new());
    // Marks of the (1, k) solution's birth and period doubling on the top row.
    if let Some(Ok(info)) = &app.orbits.info {
        for (a, ch) in [(info.birth, 'B'), (info.pd, 'P')] {
            if let Some(col) = a.and_then(|a| column(x, plot, a)) {
                buf.set_string(col, plot.y, ch.to_string(), app.theme.mark());
                if plot.height > 1 {
                    buf.set_string(col, plot.y + plot.height - 1, "╵", app.theme.mark());
                }
            }
        }
    }
    // The current α: a cursor line drawn only over empty cells so no data is hidden.
    let vline = |buf: &mut Buffer, a: f64, glyph: &str, style: Style| {
        if let Some(col) = column(x, plot, a) {
            for row in plot.y..plot.y + plot.height {
                if let Some(cell) = buf.cell_mut((col, row)) {
                    if cell.symbol() == " " {
                        cell.set_symbol(glyph).set_style(style);
                    } else {
                        cell.set_style(style);
                    }
                }
            }
        }
    };
    vline(buf, app.params.alpha, "│", app.theme.cursor());
    if focused || d.mark.is_some() {
        if (d.cursor - app.params.alpha).abs() > x.span() * 1e-9 {
            vline(buf, d.cursor, "┆", app.theme.mark2());
        }
        if let Some(m) = d.mark {
            vline(buf, m, "┃", app.theme.mark2());
        }
        let info = format!(
            " cursor α={}{} ",
            fmt_num(d.cursor),
            d.mark
                .map_or(String::new(), |m| format!(", mark {}", fmt_num(m)))
        );
        let w = info.chars().count() as u16;
        if plot.width > w {
            buf.set_string(plot.x + plot.width - w, plot.y, info, app.theme.mark2());
        }
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
