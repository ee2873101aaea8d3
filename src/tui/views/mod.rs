//! Screen layout and the top-level draw: one file per panel in this folder, each a
//! function from (&App, area, buffer) to cells. The layout reflows from 120×40 down to
//! 80×24; below that [`too_small`] replaces everything.

pub mod bounce;
pub mod diagram;
pub mod help;
pub mod parameters;
pub mod phase_plot;
pub mod presets;
pub mod stability;
pub mod status;
pub mod too_small;

use super::app::{App, Focus, Overlay};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Widget};
use ratatui::Frame;

/// Smallest usable terminal.
pub const MIN_W: u16 = 80;
pub const MIN_H: u16 = 24;

/// Where each panel goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panes {
    pub params: Rect,
    pub diagram: Rect,
    pub phase: Rect,
    pub stability: Rect,
    pub bounce: Rect,
    pub status: Rect,
}

/// Split the screen. None when it is too small.
pub fn layout(area: Rect) -> Option<Panes> {
    if area.width < MIN_W || area.height < MIN_H {
        return None;
    }
    let [main, status] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(area);
    let top_h = (main.height * 11 / 20).max(13);
    let [top, bottom] =
        Layout::vertical([Constraint::Length(top_h), Constraint::Min(0)]).areas(main);
    let pw = if area.width >= 110 { 30 } else { 26 };
    let [params, diagram] =
        Layout::horizontal([Constraint::Length(pw), Constraint::Min(0)]).areas(top);
    let [phase, stability, bounce] = Layout::horizontal([
        Constraint::Ratio(1, 3),
        Constraint::Ratio(1, 3),
        Constraint::Ratio(1, 3),
    ])
    .areas(bottom);
    Some(Panes {
        params,
        diagram,
        phase,
        stability,
        bounce,
        status,
    })
}

/// The plot rectangles inside the diagram and phase panes (grids are sized to these).
pub fn plot_areas(p: &Panes) -> (Rect, Rect) {
    (
        diagram::plot_area(p.diagram),
        phase_plot::plot_area(p.phase),
    )
}

/// Draw the whole screen. Call `App::set_plot_sizes` with [`plot_areas`] first.
pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    let buf = frame.buffer_mut();
    let Some(p) = layout(area) else {
        too_small::render(app, area, buf);
        return;
    };
    parameters::render(app, p.params, buf);
    diagram::render(app, p.diagram, buf);
    phase_plot::render(app, p.phase, buf);
    stability::render(app, p.stability, buf);
    bounce::render(app, p.bounce, buf);
    status::render(app, p.status, buf);
    match app.overlay {
        Overlay::Help => help::render(app, area, buf),
        Overlay::Presets { selected } => presets::render(app, selected, area, buf),
        Overlay::None => {}
    }
}

/// A panel frame: rounded border, title, brighter when focused.
pub fn panel<'a>(app: &App, title: String, focused: bool) -> Block<'a> {
    let style = if focused {
        app.theme.focus()
    } else {
        app.theme.axis()
    };
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(style)
        .title(ratatui::text::Span::styled(title, app.theme.focus()))
}

pub fn is_focused(app: &App, f: Focus) -> bool {
    app.focus == f && app.overlay == Overlay::None
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

/// The plot rectangle inside a bordered pane, leaving `label_w` columns (plus the axis)
/// for the y tick labels on the left and one row for the x tick labels at the bottom.
pub fn plot_area_within(pane: Rect, label_w: u16) -> Rect {
    let inner = Rect {
        x: pane.x + 1,
        y: pane.y + 1,
        width: pane.width.saturating_sub(2),
        height: pane.height.saturating_sub(2),
    };
    Rect {
        x: inner.x + label_w + 1,
        y: inner.y,
        width: inner.width.saturating_sub(label_w + 1),
        height: inner.height.saturating_sub(1),
    }
}

/// A bordered box with `lines`, centred over `area` and sized to its content (overlays:
/// help, presets).
pub fn overlay(app: &App, title: &str, lines: Vec<Line<'_>>, area: Rect, buf: &mut Buffer) {
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
                .border_style(app.theme.focus())
                .title(format!(" {title} ")),
        )
        .render(r, buf);
}
