//! The panels. Each stateful panel is a [`Component`]: it owns its state, handles the
//! actions meant for it, reacts to changes of the shared parameters, starts and
//! receives its own background work, and draws itself. Panels see each other only
//! through [`Shared`]; [`crate::tui::app::App`] holds one of each and routes actions,
//! changes and messages to them.
//!
//! Adding a panel: a new file here with a type implementing [`Component`], a
//! [`Target`] variant (in `workers`) if it has background work, and its registration in `App` (a
//! field, and its place in [`crate::tui::app::App::components_mut`] and the layout).
//! Draw-only pieces (the status line, the help and preset overlays, the too-small
//! message) are plain functions.

pub mod basins;
pub mod bounce;
pub mod branches;
pub mod diagram;
pub mod help;
pub mod legend;
pub mod parameters;
pub mod phase_plot;
pub mod plane;
pub mod presets;
pub mod stability;
pub mod status;
pub mod table_view;
pub mod too_small;

use super::keymap::Action;
use super::params::ParamId;
use super::shared::{Focus, Overlay, Shared};
pub use super::workers::Target;
use super::workers::{Body, Workers};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Widget};

/// A stateful panel.
pub trait Component {
    /// Handle an action (the panel checks the focus where that matters); true if it
    /// was consumed.
    fn handle(&mut self, _action: Action, _shared: &mut Shared) -> bool {
        false
    }

    /// The shared parameter `id` changed (the table stands for "everything").
    fn changed(&mut self, _id: ParamId, _shared: &mut Shared) {}

    /// Start (or restart) this panel's background work for the current parameters.
    fn start(&mut self, _shared: &mut Shared, _workers: &Workers) {}

    /// A message from this panel's background work (stale generations are the
    /// panel's to drop).
    fn receive(&mut self, _gen: u64, _body: Body, _shared: &mut Shared) {}

    /// Whether background work may still send something (the loop then polls more
    /// often).
    fn busy(&self) -> bool {
        false
    }

    /// Draw into `area`; the whole app is readable.
    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer);
}

/// A panel frame: rounded border, title, brighter when focused.
pub fn panel<'a>(shared: &Shared, title: String, focused: bool) -> Block<'a> {
    let style = if focused {
        shared.theme.focus()
    } else {
        shared.theme.axis()
    };
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(style)
        .title(ratatui::text::Span::styled(title, shared.theme.focus()))
}

/// Whether `f` has the focus (and no overlay hides it).
pub fn is_focused(shared: &Shared, f: Focus) -> bool {
    shared.focus == f && shared.overlay == Overlay::None
}

/// Format a count compactly: 950, 12.3k, 4.1M.
pub fn compact(n: f64) -> String {
    if n >= 1e6 {
        format!("{:.1}M", n / 1e6)
    } else if n >= 1e4 {
        format!("{:.0}k", n / 1e3)
    } else if n >= 1e3 {
        format!("{:.1}k", n / 1e3)
    } else {
        format!("{n:.0}")
    }
}

/// A bordered box with `lines`, centred over `area` and sized to its content (overlays:
/// help, presets).
pub fn overlay(shared: &Shared, title: &str, lines: Vec<Line<'_>>, area: Rect, buf: &mut Buffer) {
    let w = (lines.iter().map(|l| l.width()).max().unwrap_or(40) as u16 + 2).min(area.width);
    let h = (lines.len() as u16 + 2).min(area.height);
    let r = Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    };
    Clear.render(r, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .border_style(shared.theme.focus())
                .title(format!(" {title} ")),
        )
        .render(r, buf);
}
