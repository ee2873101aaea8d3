//! The live phase plot (t̂, v): every event of the map iterated from the initial state,
//! accumulating in a hit-count grid, the most recent points highlighted, and the (1, k)
//! and (2, 2k) solutions marked where the orbit analysis finds them.

use super::{compact, panel};
use crate::tui::app::{App, RECENT};
use crate::tui::plot::draw_axes;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

const LABEL_W: u16 = 4;

pub fn plot_area(pane: Rect) -> Rect {
    super::plot_area_within(pane, LABEL_W)
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let p = &app.phase;
    let state = if p.note.is_some() {
        "orbit ended".to_string()
    } else if p.done {
        "done".into()
    } else if app.paused {
        "paused".into()
    } else {
        "running".into()
    };
    let title = format!(
        " Phase plot (t̂, v): {} pts, {state} ",
        compact(p.points.len() as f64)
    );
    let block = panel(app, title, false);
    let inner = block.inner(area);
    block.render(area, buf);
    let plot = draw_axes(
        inner,
        buf,
        p.grid.x_range(),
        p.grid.y_range(),
        LABEL_W,
        &app.theme,
    );
    let recent: Vec<(usize, usize)> = p
        .points
        .iter()
        .rev()
        .take(RECENT)
        .filter_map(|&(t, v)| p.grid.sub_cell(t, v))
        .collect();
    p.grid
        .render(plot, buf, &app.theme, &recent, app.theme.recent());
    // Analytic solutions: ◆ for (1, k) (filled if stable), ✕ for the (2, 2k) points.
    if let Some(Ok(info)) = &app.orbits.info {
        let marks = info
            .fixed
            .iter()
            .map(|f| {
                (
                    (f.phase, f.v),
                    if f.stable { "◆" } else { "◇" },
                    app.theme.mark(),
                )
            })
            .chain(info.two.iter().map(|&q| (q, "✕", app.theme.mark2())));
        for ((t, v), g, style) in marks {
            if let Some((i, j)) = p.grid.sub_cell(t, v) {
                let (sx, sy) = p.grid.marker().resolution();
                let (c, r) = ((i / sx) as u16, (j / sy) as u16);
                if c < plot.width && r < plot.height {
                    buf.set_string(plot.x + c, plot.y + r, g, style);
                }
            }
        }
    }
    if let Some(n) = &p.note {
        let s: String = n.chars().take(plot.width as usize).collect();
        buf.set_string(plot.x, plot.y, s, app.theme.error());
    }
}
