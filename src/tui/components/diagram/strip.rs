//! The Lyapunov strip under the diagram: the largest exponent per impact of every
//! finished value against the diagram's parameter axis, a dotted zero line, and a mark
//! on the bottom row for values whose exponent is −∞ (they stick). It is drawn from
//! the diagram's stored results, so it fills in with the sweep.

use crate::output::classes::Class;
use crate::output::hitgrid::{HitGrid, Marker, Range};
use crate::tui::theme::Theme;
use bouncemap_engine::sweep::ValueResult;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// Rows of the strip where the diagram has room.
pub const STRIP_ROWS: u16 = 3;
/// The diagram needs this many inner rows before it gives [`STRIP_ROWS`] to the
/// strip; from [`STRIP_MIN_FROM`] (the smallest screen's 11) it gives two.
pub const STRIP_FROM: u16 = 14;
/// Below this many inner rows there is no strip (never on a screen of 24 rows or more).
pub const STRIP_MIN_FROM: u16 = 10;

/// Rows of the strip under a diagram of `inner` rows.
pub fn rows(inner: u16) -> u16 {
    match inner {
        i if i >= STRIP_FROM => STRIP_ROWS,
        i if i >= STRIP_MIN_FROM => 2,
        _ => 0,
    }
}

/// The exponent range shown: at least [-0.1, 0.1], at most down to -1.5.
fn y_range(slots: &[Option<ValueResult>]) -> Range {
    let (mut lo, mut hi) = (-0.1f64, 0.1f64);
    for l in slots.iter().flatten().filter_map(|s| s.lyapunov) {
        if l.is_finite() {
            lo = lo.min(l);
            hi = hi.max(l);
        }
    }
    // Half the span again below, so the bottom row stays for the −∞ marks.
    let lo = lo.max(-1.5);
    Range::new(lo - 0.5 * (hi - lo), hi)
}

/// Draw the strip into `area` (the full width of the diagram's inner area, the y labels
/// in the first `label_w` columns as for the diagram, so columns line up).
pub fn draw(
    slots: &[Option<ValueResult>],
    x: Range,
    area: Rect,
    label_w: u16,
    marker: Marker,
    buf: &mut Buffer,
    theme: &Theme,
) {
    if area.width <= label_w + 2 || area.height == 0 {
        return;
    }
    let plot = Rect {
        x: area.x + label_w + 1,
        y: area.y,
        width: area.width - label_w - 1,
        height: area.height,
    };
    let y = y_range(slots);
    let mut grid = HitGrid::new(plot.width, plot.height, marker, x, y);
    let per_cell = marker.resolution().0;
    let cols = plot.width as usize;
    let mut stuck = vec![false; cols];
    let mut positive = vec![false; cols];
    for s in slots.iter().flatten() {
        match s.lyapunov {
            Some(l) if l.is_finite() => {
                grid.add(s.value, l.clamp(y.lo, y.hi));
                if l > 0.0 {
                    if let Some((i, _)) = grid.sub_cell(s.value, 0.0) {
                        positive[(i / per_cell).min(cols - 1)] = true;
                    }
                }
            }
            Some(_) => {
                if let Some((i, _)) = grid.sub_cell(s.value, y.lo) {
                    stuck[(i / per_cell).min(cols - 1)] = true;
                }
            }
            None => {}
        }
    }
    // Gutter: the top value, 0 and the bottom value.
    let zero_row =
        plot.y + (((1.0 - y.frac(0.0)) * plot.height as f64) as u16).min(plot.height - 1);
    let label = |v: f64| {
        let s = format!("{v:.2}");
        s.chars().take(label_w as usize).collect::<String>()
    };
    for row in plot.y..plot.y + plot.height {
        buf.set_string(area.x + label_w, row, "│", theme.axis());
    }
    for (row, text) in [
        (plot.y, label(y.hi)),
        (plot.y + plot.height - 1, label(y.lo)),
        (zero_row, "0".to_string()),
    ] {
        let w = text.chars().count() as u16;
        buf.set_string(area.x + label_w - w, row, &text, theme.axis());
        buf.set_string(area.x + label_w, row, "┤", theme.axis());
    }
    // The strip's name in the gutter, on a row without a tick label.
    let taken = [plot.y, plot.y + plot.height - 1, zero_row];
    // (Without such a row the caption below names the strip.)
    if let Some(r) = (plot.y..plot.y + plot.height).find(|r| !taken.contains(r)) {
        let name = "λ₁";
        let w = ratatui::text::Line::from(name).width() as u16;
        if w <= label_w {
            buf.set_string(area.x + label_w - w, r, name, theme.focus());
        }
    }
    let text = grid.to_text();
    for (r, line) in text.iter().enumerate() {
        for (c, ch) in line.chars().enumerate() {
            let (col, row) = (plot.x + c as u16, plot.y + r as u16);
            if ch != ' ' {
                let style = if positive[c] {
                    theme.class(Class::Chaotic)
                } else {
                    theme.class(Class::Period1)
                };
                buf.set_string(col, row, ch.to_string(), style);
            } else if row == zero_row {
                buf.set_string(col, row, "┄", theme.axis());
            }
        }
    }
    let bottom = plot.y + plot.height - 1;
    for (c, s) in stuck.iter().enumerate() {
        if *s {
            if let Some(cell) = buf.cell_mut((plot.x + c as u16, bottom)) {
                if matches!(cell.symbol(), " " | "┄") {
                    cell.set_symbol("▁").set_style(theme.class(Class::Sticking));
                }
            }
        }
    }
    // A caption in the bottom right corner, if nothing is drawn there.
    let caption = " λ₁ per impact, ▁ = −∞ ";
    let w = caption.chars().count() as u16;
    if plot.width > w + 2 {
        let x0 = plot.x + plot.width - w;
        let free = (x0..x0 + w).all(|c| {
            buf.cell((c, bottom))
                .is_some_and(|cell| matches!(cell.symbol(), " " | "┄"))
        });
        if free {
            buf.set_string(x0, bottom, caption, theme.dim());
        }
    }
}
