//! The preset picker: the paper's figures (the same presets as `sweep --preset`),
//! ↑/↓ to choose, Enter to load, Esc to close; the chosen one's description in full
//! and its settings below the list.

use super::{Overlay, Shared};
use crate::config::presets::{self, Preset};
use crate::tui::keymap::Action;
use crate::tui::params::fmt_num;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;

/// The presets on offer.
pub struct PresetPicker {
    list: Vec<(String, Preset)>,
}

impl Default for PresetPicker {
    fn default() -> Self {
        PresetPicker::new()
    }
}

impl PresetPicker {
    /// Every shipped preset.
    pub fn new() -> PresetPicker {
        PresetPicker {
            list: presets::all(),
        }
    }

    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Preset `i` with its name.
    pub fn get(&self, i: usize) -> Option<&(String, Preset)> {
        self.list.get(i)
    }

    /// An action while the picker is open with `selected` chosen: the preset to load,
    /// if Enter chose one.
    pub fn handle(&self, selected: usize, action: Action, shared: &mut Shared) -> Option<usize> {
        let n = self.list.len().max(1);
        match action {
            Action::Up => {
                shared.overlay = Overlay::Presets {
                    selected: (selected + n - 1) % n,
                }
            }
            Action::Down => {
                shared.overlay = Overlay::Presets {
                    selected: (selected + 1) % n,
                }
            }
            Action::Enter => {
                shared.overlay = Overlay::None;
                return Some(selected);
            }
            Action::Cancel | Action::Presets => shared.overlay = Overlay::None,
            _ => {}
        }
        None
    }

    pub fn draw(&self, app: &Shared, selected: usize, area: Rect, buf: &mut Buffer) {
        render(self, app, selected, area, buf)
    }
}

fn render(picker: &PresetPicker, app: &Shared, selected: usize, area: Rect, buf: &mut Buffer) {
    let mut lines: Vec<Line> = if picker.list.is_empty() {
        vec![Line::styled(" no presets available ", app.theme.dim())]
    } else {
        picker
            .list
            .iter()
            .enumerate()
            .map(|(i, (name, p))| {
                let (lo, hi) = p.window();
                let text = format!(
                    " {:<10} {:<9} r={} α∈[{}, {}]  {} ",
                    name,
                    p.table.to_string(),
                    fmt_num(p.r.unwrap_or(crate::config::rules::R.default)),
                    fmt_num(lo),
                    fmt_num(hi),
                    shorten(&p.description, 48)
                );
                if i == selected {
                    Line::styled(text, app.theme.selected())
                } else {
                    Line::from(text)
                }
            })
            .collect()
    };
    // What the selected preset shows, in full.
    if let Some((_, p)) = picker.list.get(selected) {
        let width = (area.width as usize).saturating_sub(8).clamp(30, 100);
        lines.push(Line::from(""));
        for l in wrap(&p.description, width) {
            lines.push(Line::styled(format!(" {l}"), app.theme.focus()));
        }
        lines.push(Line::styled(
            format!(
                " {} values, transient {} periods, keep {}, start {}",
                p.steps,
                p.transient,
                p.keep,
                p.sweep_spec()
                    .map(|s| if s.initial.near_fixed_point {
                        "near (1,1)"
                    } else {
                        "cold"
                    })
                    .unwrap_or("?")
            ),
            app.theme.dim(),
        ));
    }
    lines.push(Line::styled(
        " ↑/↓ choose, Enter load, Esc close",
        app.theme.dim(),
    ));
    super::overlay(app, "Presets", lines, area, buf);
}

/// `text` in lines of at most `width` characters, broken at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut out = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            out.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        out.push(line);
    }
    out
}

/// `text` cut to at most `max` characters, with an ellipsis where it was cut.
fn shorten(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let cut: String = text.chars().take(max.saturating_sub(1)).collect();
    format!("{}…", cut.trim_end())
}
