//! The message shown instead of a broken layout when the terminal is too small.

use super::Shared;
use crate::tui::layout::{MIN_H, MIN_W};
use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget, Wrap};

pub fn draw(app: &Shared, area: Rect, buf: &mut Buffer) {
    let lines = vec![
        Line::styled("bouncemap: terminal too small", app.theme.error()),
        Line::from(format!(
            "{}×{} here; needs at least {MIN_W}×{MIN_H}.",
            area.width, area.height
        )),
        Line::from(format!(
            "Enlarge the window, or press {} to quit.",
            app.keymap.hint(crate::tui::keymap::Action::Quit)
        )),
    ];
    let h = (lines.len() as u16).min(area.height);
    let y = area.y + area.height.saturating_sub(h) / 2;
    Paragraph::new(lines)
        .alignment(Alignment::Center)
        .wrap(Wrap { trim: true })
        .render(
            Rect {
                y,
                height: h.max(area.height - (y - area.y)),
                ..area
            },
            buf,
        );
}
