//! The `?` overlay, generated from the keymap that dispatches keys.

use crate::tui::shared::Shared;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

pub fn draw(app: &Shared, area: Rect, buf: &mut Buffer) {
    let help = app.keymap.help();
    let key_w = help
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(4)
        .min(24);
    let mut lines: Vec<Line> = help
        .into_iter()
        .map(|(k, d)| {
            Line::from(vec![
                Span::styled(format!(" {k:<key_w$}  "), app.theme.focus()),
                Span::raw(d),
            ])
        })
        .collect();
    lines.push(Line::styled(
        " Enter types a value in the parameters panel; Esc or ? closes this help.",
        app.theme.dim(),
    ));
    if lines.len() as u16 + 2 > area.height {
        // Short terminal: two columns, descriptions cut to fit.
        let half = lines.len().div_ceil(2);
        let col_w = (area.width.saturating_sub(3) / 2) as usize;
        let cut = |l: &Line| -> String {
            let s: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
            if s.chars().count() > col_w {
                s.chars().take(col_w.saturating_sub(1)).collect::<String>() + "…"
            } else {
                format!("{s:<col_w$}")
            }
        };
        lines = (0..half)
            .map(|i| {
                let right = lines.get(i + half).map(cut).unwrap_or_default();
                Line::from(format!("{} {}", cut(&lines[i]), right))
            })
            .collect();
    }
    super::overlay(app, "Keys", lines, area, buf);
}
