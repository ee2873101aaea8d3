//! The parameters panel: one row per value (the table family's own parameters below
//! the table: F_D's D, a table file's), the selected one highlighted; ↑/↓ select,
//! ←/→ nudge, Enter types an exact value (the row shows the text being typed, and the
//! valid range below it). Refusals and notes go to the status line, which has the
//! screen's width. When the rows do not fit (80×24) the panel scrolls with the
//! selection.

use super::{is_focused, panel, Component, NoWork, Shared};
use crate::tui::keymap::Action;
use crate::tui::layout::Slot;
use crate::tui::params::ParamId;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// The selected row and the text being typed.
pub struct Parameters {
    /// The selected row (kept when the rows change with the table: a family parameter
    /// that is gone leaves the table row selected).
    pub selected: ParamId,
    pub editing: Option<String>,
}

impl Default for Parameters {
    fn default() -> Self {
        Parameters::new()
    }
}

impl Parameters {
    /// α selected, nothing typed.
    pub fn new() -> Parameters {
        Parameters {
            selected: ParamId::Alpha,
            editing: None,
        }
    }

    /// The selected row, if the current table has it (else the table row).
    pub fn selected_param_in(&self, rows: &[ParamId]) -> ParamId {
        if rows.contains(&self.selected) {
            self.selected
        } else {
            ParamId::Table
        }
    }

    /// The index of the selected row among `rows`.
    fn selected_index(&self, rows: &[ParamId]) -> usize {
        rows.iter().position(|r| *r == self.selected).unwrap_or(0)
    }

    /// A typed key while editing (Enter commits, Esc cancels;
    /// [`crate::tui::line_edit`]).
    pub fn edit_key(&mut self, key: crossterm::event::KeyEvent, shared: &mut Shared) {
        use crate::tui::line_edit::{edit, Edit};
        let Some(buf) = self.editing.as_mut() else {
            return;
        };
        match edit(buf, key, 64) {
            Edit::Typing => {}
            Edit::Cancel => self.editing = None,
            Edit::Commit => {
                let text = self.editing.take().unwrap_or_default();
                if text.trim().is_empty() {
                    return;
                }
                let id = self.selected_param_in(&shared.params.rows());
                let before = shared.params.clone();
                let r = shared.params.set_text(id, &text);
                shared.after_change(id, r, &before);
            }
        }
    }
}

impl Component for Parameters {
    type Msg = NoWork;

    fn focusable(&self) -> bool {
        true
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if shared.focus != Slot::Params {
            return false;
        }
        let rows = shared.params.rows();
        let n = rows.len();
        let i = self.selected_index(&rows);
        match action {
            Action::Up => self.selected = rows[(i + n - 1) % n],
            Action::Down => self.selected = rows[(i + 1) % n],
            Action::Left | Action::Right | Action::FineLeft | Action::FineRight => {
                let dir = if matches!(action, Action::Left | Action::FineLeft) {
                    -1
                } else {
                    1
                };
                let fine = matches!(action, Action::FineLeft | Action::FineRight);
                let id = self.selected_param_in(&rows);
                let before = shared.params.clone();
                let r = shared.params.nudge(id, dir, fine);
                shared.after_change(id, r, &before);
            }
            Action::Enter => self.editing = Some(String::new()),
            _ => return false,
        }
        true
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let focused = is_focused(app, Slot::Params);
        // Rows shown: all if they fit, else a window that keeps the selected one visible
        // (one row is kept for the hint while typing); the borders say how many rows
        // are above and below it.
        let hint = self.editing.is_some();
        let room = (area.height.saturating_sub(2) as usize)
            .saturating_sub(usize::from(hint))
            .max(1);
        let rows = app.params.rows();
        let n = rows.len();
        let selected = self.selected_index(&rows);
        let first = if n <= room {
            0
        } else {
            selected.saturating_sub(room / 2).min(n - room)
        };
        let below = n.saturating_sub(first + room);
        let mut block = panel(app, " Parameters ".into(), focused);
        if first > 0 {
            block = block
                .title(Line::styled(format!(" ▲ {first} more "), app.theme.dim()).right_aligned());
        }
        if below > 0 {
            block = block.title_bottom(
                Line::styled(format!(" ▼ {below} more (↑↓) "), app.theme.dim()).right_aligned(),
            );
        }
        let inner = block.inner(area);
        block.render(area, buf);
        let label_w = 10usize;
        let w = inner.width as usize;
        let mut lines: Vec<Line> = Vec::new();
        for (i, id) in rows.iter().enumerate().skip(first).take(room) {
            let sel = i == selected;
            let value = match (&self.editing, sel) {
                (Some(text), true) => format!("{text}▏"),
                _ => app.params.show(*id),
            };
            // The sweep window's rows name the swept parameter.
            let label = match id {
                ParamId::Lo | ParamId::Hi => format!(
                    "{}{}",
                    crate::tui::params::Params::symbol(app.params.param),
                    id.label()
                ),
                _ => app.params.label(*id),
            };
            // Pad by display width (t̂ is two characters in one column).
            let pad = label_w.saturating_sub(Line::from(label.as_str()).width());
            let marker = if sel { "›" } else { " " };
            let text = format!("{marker}{label}{}{value}", " ".repeat(pad));
            let style = if sel && (focused || self.editing.is_some()) {
                app.theme.selected()
            } else if sel {
                app.theme.focus()
            } else {
                ratatui::style::Style::new()
            };
            let padded: String = if sel { format!("{text:<w$}") } else { text };
            lines.push(Line::from(Span::styled(padded, style)));
        }
        if hint {
            lines.push(Line::styled(
                format!(
                    "valid {}; Enter sets, Esc cancels",
                    app.params.range_of(self.selected_param_in(&rows))
                ),
                app.theme.dim(),
            ));
        }
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .render(inner, buf);
    }
}
