//! The preset picker: the paper's figures, ↑/↓ to choose, Enter to load.

use crate::tui::app::App;
use crate::tui::params::fmt_num;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;

pub fn render(app: &App, selected: usize, area: Rect, buf: &mut Buffer) {
    let mut lines: Vec<Line> = if app.presets.is_empty() {
        vec![Line::styled(" no presets available ", app.theme.dim())]
    } else {
        app.presets
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let text = format!(
                    " {:<10} {:<9} r={} α∈[{}, {}]  {} ",
                    p.name,
                    p.table,
                    fmt_num(p.r),
                    fmt_num(p.lo),
                    fmt_num(p.hi),
                    p.description
                );
                if i == selected {
                    Line::styled(text, app.theme.selected())
                } else {
                    Line::from(text)
                }
            })
            .collect()
    };
    lines.push(Line::styled(
        " ↑/↓ choose, Enter load, Esc close",
        app.theme.dim(),
    ));
    super::overlay(app, "Presets", lines, area, buf);
}
