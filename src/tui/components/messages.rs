//! The `L` overlay: every message of this session (the latest
//! [`LOG_LEN`](super::shared::LOG_LEN)), oldest
//! first, each in full and wrapped to the screen: the status line shows only the
//! latest, cut to its width.

use super::Shared;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;

/// `text` broken at spaces into lines of at most `width` characters (a word longer
/// than that is cut).
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let width = width.max(8);
    let mut out = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let (lw, ww) = (line.chars().count(), word.chars().count());
        if lw > 0 && lw + 1 + ww > width {
            out.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
        while line.chars().count() > width {
            let head: String = line.chars().take(width).collect();
            line = line.chars().skip(width).collect();
            out.push(head);
        }
    }
    if !line.is_empty() || out.is_empty() {
        out.push(line);
    }
    out
}

/// The overlay's lines at `width` columns.
pub fn lines(app: &Shared, width: usize) -> Vec<Line<'static>> {
    if app.log.is_empty() {
        return vec![Line::styled(" (no messages yet)", app.theme.dim())];
    }
    let mut out = Vec::new();
    for (text, error) in &app.log {
        let style = if *error {
            app.theme.error()
        } else {
            ratatui::style::Style::new()
        };
        for (i, l) in wrap(text, width.saturating_sub(4)).into_iter().enumerate() {
            let lead = if i == 0 { " • " } else { "   " };
            out.push(Line::styled(format!("{lead}{l}"), style));
        }
    }
    out
}

/// Draw the overlay, scrolled by `scroll` lines (the end when it is larger).
pub fn draw(app: &Shared, scroll: usize, area: Rect, buf: &mut Buffer) {
    let all = lines(app, area.width.saturating_sub(4) as usize);
    super::help::scrolled(
        app,
        "Messages, newest last (L or Esc closes)",
        all,
        scroll,
        area,
        buf,
    );
}

#[cfg(test)]
mod tests {
    use super::wrap;

    #[test]
    fn long_messages_wrap_at_spaces_and_keep_every_word() {
        let text =
            "export: wrote a.csv, a.txt, a-diagram.svg, a-diagram.png, a-phase.svg, a-phase.png";
        let lines = wrap(text, 30);
        assert!(lines.iter().all(|l| l.chars().count() <= 30), "{lines:?}");
        assert_eq!(lines.join(" "), text);
        assert_eq!(wrap(&"x".repeat(20), 8).len(), 3);
    }
}
