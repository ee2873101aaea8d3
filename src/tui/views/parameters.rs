//! The parameters panel: one row per value, the selected one highlighted; while typing
//! the row shows the text being typed, and a refusal shows below in the error style.

use super::{is_focused, panel};
use crate::tui::app::{App, Focus};
use crate::tui::params::ParamId;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget, Wrap};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let focused = is_focused(app, Focus::Params);
    let block = panel(app, " Parameters ".into(), focused);
    let inner = block.inner(area);
    block.render(area, buf);
    let label_w = 10usize;
    let mut lines: Vec<Line> = Vec::new();
    for (i, id) in ParamId::ALL.iter().enumerate() {
        let sel = i == app.selected;
        let value = match (&app.editing, sel) {
            (Some(text), true) => format!("{text}▏"),
            _ => app.params.show(*id),
        };
        let text = format!(
            "{}{:<label_w$}{}",
            if sel { "›" } else { " " },
            id.label(),
            value
        );
        let style = if sel && (focused || app.editing.is_some()) {
            app.theme.selected()
        } else if sel {
            app.theme.focus()
        } else {
            ratatui::style::Style::new()
        };
        let w = inner.width as usize;
        let padded: String = if sel { format!("{text:<w$}") } else { text };
        lines.push(Line::from(Span::styled(padded, style)));
    }
    let used = lines.len() as u16;
    if let Some((msg, err)) = &app.message {
        if inner.height > used {
            let style = if *err {
                app.theme.error()
            } else {
                app.theme.dim()
            };
            lines.push(Line::styled(msg.clone(), style));
        }
    } else if app.editing.is_some() && inner.height > used {
        lines.push(Line::styled(
            format!(
                "valid {}; Enter sets, Esc cancels",
                app.selected_param().range()
            ),
            app.theme.dim(),
        ));
    }
    Paragraph::new(lines)
        .wrap(Wrap { trim: false })
        .render(inner, buf);
}
