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
/// last row: both ends always, [`end_labels`], and the ticks between that fit) around a
/// plot, with the axes' names:
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
    // Both ends first, each with the decimals the window's span needs (a zoomed
    // window shows where it is), then the ticks between that do not touch them.
    let (left, right) = end_labels(x.lo, x.hi);
    let (lw, rw) = (left.chars().count() as u16, right.chars().count() as u16);
    let right_at = (plot.x + plot.width).saturating_sub(rw);
    let ends_fit = lw + 1 + rw <= plot.width;
    if ends_fit {
        buf.set_string(plot.x, row, &left, style);
        buf.set_string(right_at, row, &right, style);
    }
    let mut free_from = if ends_fit { plot.x + lw + 1 } else { plot.x };
    let stop = if ends_fit {
        right_at.saturating_sub(1)
    } else {
        plot.x + plot.width
    };
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
        if start < free_from || start + w > stop {
            continue;
        }
        buf.set_string(start, row, &s, style);
        free_from = start + w + 1;
    }
    plot
}

/// The labels of an axis's two ends, `lo` and `hi`: as few decimals as show both to a
/// thousandth of the span (0.45 and 0.60 for 0.45..0.6; 0.55123 and 0.56340 for a zoom
/// to 0.551234..0.5634; 0.0 and 1.0 for 0..1), so a zoomed window says where it is.
pub fn end_labels(lo: f64, hi: f64) -> (String, String) {
    let tol = (hi - lo).abs() * 1e-3;
    let fits = |x: f64, d: i32| {
        let p = 10f64.powi(d);
        ((x * p).round() / p - x).abs() <= tol
    };
    let dec = (1..=10).find(|&d| fits(lo, d) && fits(hi, d)).unwrap_or(10) as usize;
    (format!("{lo:.dec$}"), format!("{hi:.dec$}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::display::ColorMode;

    #[test]
    fn both_ends_of_the_x_axis_are_labelled_in_any_window() {
        let theme = Theme::new(ColorMode::None);
        for (lo, hi, width) in [
            (0.45, 0.6, 80u16),
            (0.551_234, 0.563_4, 60),
            (0.5061, 0.506_235, 40),
            (0.45, 0.6, 200),
        ] {
            let area = Rect::new(0, 0, width, 6);
            let mut buf = Buffer::empty(area);
            let axes = Axes {
                x: Range::new(lo, hi),
                y: Range::new(0.0, 1.0),
                x_name: "α",
                y_name: "t̂",
            };
            draw_axes(area, &mut buf, axes, 5, &theme);
            let row: String = (0..width)
                .map(|c| buf[(c, 5)].symbol().to_string())
                .collect();
            let (l, r) = end_labels(lo, hi);
            assert_ne!(l, r);
            assert!(
                row[..].contains(&l) && row.trim_end().ends_with(&r),
                "{row:?}"
            );
            let at = |x: &str| row.find(x).unwrap();
            assert!(at(&l) < at(&r));
        }
        assert_eq!(end_labels(0.45, 0.6), ("0.45".into(), "0.60".into()));
        assert_eq!(
            end_labels(0.551234, 0.5634),
            ("0.55123".into(), "0.56340".into())
        );
        assert_eq!(end_labels(0.0, 1.0), ("0.0".into(), "1.0".into()));
    }

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
