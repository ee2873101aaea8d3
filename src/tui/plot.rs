//! Drawing the shared [`HitGrid`] and plot axes into a ratatui `Buffer`: one glyph per
//! cell written straight into the buffer, coloured by density level (dim/bold without
//! colour), with an overlay of highlighted sub-cells (e.g. the most recent points).

use super::theme::Theme;
use crate::output::hitgrid::{bit, tick_label, ticks, HitGrid, Marker, Range};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;

/// Canvas marker for curve plots drawn with ratatui's `Canvas`.
pub fn canvas_marker(m: Marker) -> ratatui::symbols::Marker {
    match m {
        Marker::Braille => ratatui::symbols::Marker::Braille,
        Marker::HalfBlock => ratatui::symbols::Marker::HalfBlock,
        Marker::Dot => ratatui::symbols::Marker::Dot,
    }
}

/// Draw `grid` into `area` (which should be its size); `overlay` sub-cells are drawn
/// on top with `overlay_style`.
pub fn render(
    grid: &HitGrid,
    area: Rect,
    buf: &mut Buffer,
    theme: &Theme,
    overlay: &[(usize, usize)],
    overlay_style: Style,
) {
    let cols = grid.size().0.min(area.width);
    let rows = grid.size().1.min(area.height);
    let max = (0..rows)
        .flat_map(|r| (0..cols).map(move |c| (c, r)))
        .map(|(c, r)| grid.cell(c, r).1)
        .max()
        .unwrap_or(0);
    for r in 0..rows {
        for c in 0..cols {
            let (bits, sum) = grid.cell(c, r);
            let level = HitGrid::level(sum, max);
            if let Some(g) = HitGrid::glyph(grid.marker(), bits, level) {
                if let Some(cell) = buf.cell_mut((area.x + c, area.y + r)) {
                    cell.set_char(g).set_style(theme.density(level));
                }
            }
        }
    }
    if overlay.is_empty() {
        return;
    }
    let (sx, sy) = grid.marker().resolution();
    let mut extra: std::collections::HashMap<(u16, u16), u8> = Default::default();
    for &(i, j) in overlay {
        let (c, r) = ((i / sx) as u16, (j / sy) as u16);
        if c < cols && r < rows {
            *extra.entry((c, r)).or_default() |= bit(grid.marker(), i % sx, j % sy);
        }
    }
    for ((c, r), b) in extra {
        let (bits, _) = grid.cell(c, r);
        if let Some(g) = HitGrid::glyph(grid.marker(), bits | b, 3) {
            if let Some(cell) = buf.cell_mut((area.x + c, area.y + r)) {
                cell.set_char(g).set_style(overlay_style);
            }
        }
    }
}

/// The axes of a plot: their ranges and names (`t̂`, `v`, `α`, …).
#[derive(Clone, Copy, Debug)]
pub struct Axes<'a> {
    pub x: Range,
    pub y: Range,
    pub x_name: &'a str,
    pub y_name: &'a str,
}

/// Draw a y axis (labels on the left, `label_w` wide) and an x axis (labels on the
/// last row, both ends labelled where they fit) around a plot, with the axes' names:
/// the y name in the label column beside the plot's middle (or the nearest row free of
/// tick labels), the x name at the left end of the x axis's row. Returns the plot area
/// inside.
pub fn draw_axes(
    area: Rect,
    buf: &mut Buffer,
    axes: Axes<'_>,
    label_w: u16,
    theme: &Theme,
) -> Rect {
    let Axes {
        x,
        y,
        x_name,
        y_name,
    } = axes;
    if area.width <= label_w + 2 || area.height < 3 {
        return area;
    }
    let plot = Rect {
        x: area.x + label_w + 1,
        y: area.y,
        width: area.width - label_w - 1,
        height: area.height - 1,
    };
    let style = theme.axis();
    // Vertical axis line and y ticks.
    for j in 0..plot.height {
        buf.set_string(area.x + label_w, plot.y + j, "│", style);
    }
    let ny = (plot.height as usize / 3).clamp(2, 6);
    let yt = ticks(y, ny);
    let ystep = if yt.len() > 1 {
        yt[1] - yt[0]
    } else {
        y.span()
    };
    let mut last_row = None;
    let mut labelled = Vec::new();
    for t in yt {
        let row = plot.y
            + (((1.0 - y.frac(t)) * (plot.height as f64 - 1.0)).round() as u16)
                .min(plot.height - 1);
        if last_row == Some(row) {
            continue;
        }
        last_row = Some(row);
        labelled.push(row);
        let mut s = tick_label(t, ystep);
        s.truncate(label_w as usize);
        buf.set_string(area.x + label_w - s.chars().count() as u16, row, &s, style);
        buf.set_string(area.x + label_w, row, "┤", style);
    }
    // The y axis's name beside the middle, or the nearest row without a tick label.
    let middle = plot.y + plot.height / 2;
    let free = (0..plot.height)
        .flat_map(|d| [middle.checked_sub(d), Some(middle + d)])
        .flatten()
        .find(|r| (plot.y..plot.y + plot.height).contains(r) && !labelled.contains(r));
    if let Some(r) = free {
        let w = ratatui::text::Line::from(y_name).width() as u16;
        if w <= label_w {
            buf.set_string(area.x + label_w - w, r, y_name, theme.focus());
        }
    }
    // Horizontal axis labels on the last row.
    let row = area.y + area.height - 1;
    buf.set_string(area.x + label_w, row, "└", style);
    let w = ratatui::text::Line::from(x_name).width() as u16;
    if w <= label_w {
        buf.set_string(area.x + label_w - w, row, x_name, theme.focus());
    }
    let nx = (plot.width as usize / 12).clamp(2, 8);
    let xt = ticks(x, nx);
    let xstep = if xt.len() > 1 {
        xt[1] - xt[0]
    } else {
        x.span()
    };
    let mut free_from = plot.x;
    for t in xt {
        let col =
            plot.x + ((x.frac(t) * (plot.width as f64 - 1.0)).round() as u16).min(plot.width - 1);
        let s = tick_label(t, xstep);
        let w = s.chars().count() as u16;
        // Centred on its column, pushed inside at the ends (so the last tick shows).
        let start = col
            .saturating_sub(w / 2)
            .max(plot.x)
            .min((plot.x + plot.width).saturating_sub(w));
        if start < free_from {
            continue;
        }
        buf.set_string(start, row, &s, style);
        free_from = start + w + 1;
    }
    plot
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::display::ColorMode;

    #[test]
    fn render_writes_one_glyph_per_lit_cell_with_density_levels() {
        let mut g = HitGrid::new(
            3,
            1,
            Marker::Braille,
            Range::new(0.0, 3.0),
            Range::new(0.0, 1.0),
        );
        for _ in 0..100 {
            g.add(0.1, 0.9);
        }
        g.add(2.5, 0.5);
        let mut buf = Buffer::empty(Rect::new(0, 0, 3, 1));
        let theme = Theme::new(ColorMode::Ansi256);
        render(&g, buf.area, &mut buf, &theme, &[], Style::new());
        assert_eq!(buf[(0, 0)].symbol(), "⠁");
        assert_eq!(buf[(1, 0)].symbol(), " ");
        assert_eq!(buf[(0, 0)].fg, theme.density(3).fg.unwrap());
        assert_eq!(buf[(2, 0)].fg, theme.density(0).fg.unwrap());
        assert_eq!(g.lit_cells(), 2);
    }
}
