//! Where each panel goes: the screen's slots (parameters, diagram, phase plot,
//! stability, bounce, status line), reflowing from 120×40 down to 80×24; below that the
//! too-small message replaces everything. Under [`FULL_W`] columns the bottom row keeps
//! two of its three panels at readable widths rather than squeezing three into plots a
//! few columns wide: the one left out (`left_out` of [`layout`], the bounce panel
//! unless a key chose another) has no area, and the panels say so ([`left_out_note`]). Which
//! panel takes which slot is the panel registry's (`components`).

use ratatui::layout::{Constraint, Layout, Rect};

/// Smallest usable terminal.
pub const MIN_W: u16 = 80;
pub const MIN_H: u16 = 24;
/// The narrowest screen that shows all three bottom panels.
pub const FULL_W: u16 = 100;

/// A place on the screen that one panel at a time takes (the focus is one of them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Slot {
    Params,
    Diagram,
    Phase,
    Stability,
    Bounce,
}

/// The panels' rectangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panes {
    pub params: Rect,
    pub diagram: Rect,
    pub phase: Rect,
    pub stability: Rect,
    pub bounce: Rect,
    pub status: Rect,
}

impl Panes {
    /// The rectangle of `slot`.
    pub fn get(&self, slot: Slot) -> Rect {
        match slot {
            Slot::Params => self.params,
            Slot::Diagram => self.diagram,
            Slot::Phase => self.phase,
            Slot::Stability => self.stability,
            Slot::Bounce => self.bounce,
        }
    }
}

/// The bottom row's slots, in order: the one left out at narrow widths cycles
/// through them.
pub const BOTTOM: [Slot; 3] = [Slot::Phase, Slot::Stability, Slot::Bounce];

/// Whether a screen `width` columns wide leaves one of the bottom panels out.
pub fn narrow(width: u16) -> bool {
    width < FULL_W
}

/// What a panel's name is in messages.
pub fn slot_name(slot: Slot) -> &'static str {
    match slot {
        Slot::Params => "parameters panel",
        Slot::Diagram => "diagram",
        Slot::Phase => "phase plot",
        Slot::Stability => "stability panel",
        Slot::Bounce => "bounce panel",
    }
}

/// The note that says which bottom panel a narrow screen leaves out, and the key
/// (`key`) that brings it back.
pub fn left_out_note(left_out: Slot, key: &str) -> String {
    format!(
        "{} left out: {key} shows it (two bottom panels fit under {FULL_W} columns)",
        slot_name(left_out)
    )
}

/// Split the screen, leaving `left_out` (one of [`BOTTOM`]) out of a narrow bottom
/// row. None when it is too small.
pub fn layout(area: Rect, left_out: Slot) -> Option<Panes> {
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
    let [phase, stability, bounce] = if !narrow(area.width) {
        Layout::horizontal([
            Constraint::Ratio(1, 3),
            Constraint::Ratio(1, 3),
            Constraint::Ratio(1, 3),
        ])
        .areas(bottom)
    } else {
        // The two shown in their order, the third with no area.
        let [a, b] =
            Layout::horizontal([Constraint::Ratio(1, 2), Constraint::Ratio(1, 2)]).areas(bottom);
        let none = Rect::new(bottom.right(), bottom.y, 0, 0);
        let mut shown = [a, b].into_iter();
        BOTTOM.map(|s| {
            if s == left_out {
                none
            } else {
                shown.next().unwrap_or(none)
            }
        })
    };
    Some(Panes {
        params,
        diagram,
        phase,
        stability,
        bounce,
        status,
    })
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
