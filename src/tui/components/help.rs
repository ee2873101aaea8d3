//! The `?` overlay, generated from the keymap that dispatches keys; it scrolls where it
//! does not fit (80×24).

use super::Shared;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

/// Draw the help overlay, scrolled by `scroll` lines if it does not fit.
pub fn draw(app: &Shared, scroll: usize, area: Rect, buf: &mut Buffer) {
    let help = app.keymap.help();
    let key_w = help
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(4)
        .min(24);
    let mut lines: Vec<Line<'static>> = help
        .into_iter()
        .map(|(k, d)| {
            Line::from(vec![
                Span::styled(format!(" {k:<key_w$}  "), app.theme.focus()),
                Span::raw(d),
            ])
        })
        .collect();
    // The hint where there is room for it (Enter, l and Esc are in the list anyway).
    if lines.len() < area.height.saturating_sub(2) as usize {
        lines.push(Line::styled(
            " Enter types a value in the parameters panel; l explains the marks; Esc closes.",
            app.theme.dim(),
        ));
    }
    scrolled(app, "Keys", lines, scroll, area, buf);
}

/// An overlay of `lines`, showing the window starting at `scroll` (clamped) with a
/// scroll note when they do not all fit.
pub fn scrolled(
    app: &Shared,
    title: &str,
    lines: Vec<Line<'static>>,
    scroll: usize,
    area: Rect,
    buf: &mut Buffer,
) {
    let room = area.height.saturating_sub(2) as usize;
    if lines.len() <= room {
        super::overlay(app, title, lines, area, buf);
        return;
    }
    let shown = room.saturating_sub(1).max(1);
    let first = scroll.min(lines.len() - shown);
    let mut window: Vec<Line> = lines[first..first + shown].to_vec();
    window.push(Line::styled(
        format!(
            " ↑/↓ scroll · lines {}–{} of {}",
            first + 1,
            first + shown,
            lines.len()
        ),
        app.theme.dim(),
    ));
    super::overlay(app, title, window, area, buf);
}
