//! Hit-count grid plots. Points are binned into sub-cells (2×4 per terminal cell for
//! braille, 1×2 for half blocks, 1×1 for dots) as they arrive, and the widget writes
//! one glyph per cell straight into the `Buffer`: the cost of a frame is the number of
//! cells, not the number of points. Density shows in the colour (log of the hit count
//! in four steps) and, without colour, in dim/bold. Also: axes with tick labels.

use super::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use std::fmt;
use std::str::FromStr;

/// The glyphs a plot is drawn with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Marker {
    #[default]
    Braille,
    HalfBlock,
    Dot,
}

impl FromStr for Marker {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "braille" => Ok(Marker::Braille),
            "halfblock" => Ok(Marker::HalfBlock),
            "dot" => Ok(Marker::Dot),
            _ => Err(format!(
                "'{s}' is not a marker: valid braille, halfblock, dot"
            )),
        }
    }
}

impl fmt::Display for Marker {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Marker::Braille => "braille",
            Marker::HalfBlock => "halfblock",
            Marker::Dot => "dot",
        })
    }
}

impl Marker {
    /// Sub-cells per terminal cell (x, y).
    pub fn resolution(self) -> (usize, usize) {
        match self {
            Marker::Braille => (2, 4),
            Marker::HalfBlock => (1, 2),
            Marker::Dot => (1, 1),
        }
    }

    /// Canvas marker for curve plots drawn with ratatui's `Canvas`.
    pub fn canvas(self) -> ratatui::symbols::Marker {
        match self {
            Marker::Braille => ratatui::symbols::Marker::Braille,
            Marker::HalfBlock => ratatui::symbols::Marker::HalfBlock,
            Marker::Dot => ratatui::symbols::Marker::Dot,
        }
    }
}

/// A closed interval of plot coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    pub lo: f64,
    pub hi: f64,
}

impl Range {
    pub fn new(lo: f64, hi: f64) -> Range {
        if hi > lo {
            Range { lo, hi }
        } else {
            // A degenerate range still maps its one value to the middle.
            let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 1e-3 };
            Range {
                lo: lo - pad,
                hi: lo + pad,
            }
        }
    }

    pub fn span(&self) -> f64 {
        self.hi - self.lo
    }

    /// Fraction of the way from lo to hi.
    pub fn frac(&self, x: f64) -> f64 {
        (x - self.lo) / self.span()
    }

    pub fn contains(&self, x: f64) -> bool {
        x >= self.lo && x <= self.hi
    }
}

/// Hit counts on a grid of sub-cells covering `cols × rows` terminal cells.
#[derive(Clone, Debug)]
pub struct HitGrid {
    cols: u16,
    rows: u16,
    marker: Marker,
    x: Range,
    y: Range,
    counts: Vec<u32>,
    points: u64,
}

impl HitGrid {
    pub fn new(cols: u16, rows: u16, marker: Marker, x: Range, y: Range) -> HitGrid {
        let (sx, sy) = marker.resolution();
        HitGrid {
            cols,
            rows,
            marker,
            x,
            y,
            counts: vec![0; cols as usize * sx * rows as usize * sy],
            points: 0,
        }
    }

    /// Width and height in sub-cells.
    pub fn sub_size(&self) -> (usize, usize) {
        let (sx, sy) = self.marker.resolution();
        (self.cols as usize * sx, self.rows as usize * sy)
    }

    pub fn size(&self) -> (u16, u16) {
        (self.cols, self.rows)
    }

    pub fn marker(&self) -> Marker {
        self.marker
    }

    pub fn x_range(&self) -> Range {
        self.x
    }

    pub fn y_range(&self) -> Range {
        self.y
    }

    /// Points binned so far (inside the ranges).
    pub fn points(&self) -> u64 {
        self.points
    }

    /// The sub-cell of a point, if it falls inside; row 0 is the top.
    pub fn sub_cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        if !(x.is_finite() && y.is_finite() && self.x.contains(x) && self.y.contains(y)) {
            return None;
        }
        let (w, h) = self.sub_size();
        if w == 0 || h == 0 {
            return None;
        }
        let i = ((self.x.frac(x) * w as f64) as usize).min(w - 1);
        let j = (((1.0 - self.y.frac(y)) * h as f64) as usize).min(h - 1);
        Some((i, j))
    }

    /// Count one point.
    pub fn add(&mut self, x: f64, y: f64) {
        if let Some((i, j)) = self.sub_cell(x, y) {
            let w = self.sub_size().0;
            let c = &mut self.counts[j * w + i];
            *c = c.saturating_add(1);
            self.points += 1;
        }
    }

    /// Take one point out again (its value was replaced by a later pass).
    pub fn remove(&mut self, x: f64, y: f64) {
        if let Some((i, j)) = self.sub_cell(x, y) {
            let w = self.sub_size().0;
            let c = &mut self.counts[j * w + i];
            if *c > 0 {
                *c -= 1;
                self.points -= 1;
            }
        }
    }

    pub fn clear(&mut self) {
        self.counts.iter_mut().for_each(|c| *c = 0);
        self.points = 0;
    }

    /// Terminal cells with at least one hit.
    pub fn lit_cells(&self) -> usize {
        (0..self.rows)
            .flat_map(|r| (0..self.cols).map(move |c| (c, r)))
            .filter(|&(c, r)| self.cell(c, r).0 != 0)
            .count()
    }

    /// (sub-cell bit pattern, summed count) of one terminal cell. Bit k of the pattern
    /// is sub-cell (k % sx, k / sx) for half blocks and dots, braille's dot order for
    /// braille.
    fn cell(&self, col: u16, row: u16) -> (u8, u32) {
        let (sx, sy) = self.marker.resolution();
        let w = self.cols as usize * sx;
        let mut bits = 0u8;
        let mut sum = 0u32;
        for dy in 0..sy {
            for dx in 0..sx {
                let i = col as usize * sx + dx;
                let j = row as usize * sy + dy;
                let c = self.counts[j * w + i];
                if c > 0 {
                    bits |= bit(self.marker, dx, dy);
                    sum = sum.saturating_add(c);
                }
            }
        }
        (bits, sum)
    }

    /// The glyph for a bit pattern (None for an empty cell).
    pub fn glyph(marker: Marker, bits: u8, level: usize) -> Option<char> {
        if bits == 0 {
            return None;
        }
        Some(match marker {
            Marker::Braille => char::from_u32(0x2800 + bits as u32).unwrap_or('⣿'),
            Marker::HalfBlock => match bits & 0b11 {
                0b01 => '▀',
                0b10 => '▄',
                _ => '█',
            },
            Marker::Dot => match level {
                0 => '·',
                1 | 2 => '•',
                _ => '●',
            },
        })
    }

    /// Density level 0..4 of a count relative to the busiest cell (log scale).
    pub fn level(count: u32, max: u32) -> usize {
        if count == 0 || max <= 1 {
            return 0;
        }
        let f = (count as f64).ln() / (max as f64).ln();
        ((f * 4.0) as usize).min(3)
    }

    /// Draw into `area` (which should be `cols × rows`); `overlay` sub-cells are drawn
    /// on top with `overlay_style` (e.g. the most recent points).
    pub fn render(
        &self,
        area: Rect,
        buf: &mut Buffer,
        theme: &Theme,
        overlay: &[(usize, usize)],
        overlay_style: Style,
    ) {
        let cols = self.cols.min(area.width);
        let rows = self.rows.min(area.height);
        let max = (0..rows)
            .flat_map(|r| (0..cols).map(move |c| (c, r)))
            .map(|(c, r)| self.cell(c, r).1)
            .max()
            .unwrap_or(0);
        for r in 0..rows {
            for c in 0..cols {
                let (bits, sum) = self.cell(c, r);
                let level = Self::level(sum, max);
                if let Some(g) = Self::glyph(self.marker, bits, level) {
                    if let Some(cell) = buf.cell_mut((area.x + c, area.y + r)) {
                        cell.set_char(g).set_style(theme.density(level));
                    }
                }
            }
        }
        if overlay.is_empty() {
            return;
        }
        let (sx, sy) = self.marker.resolution();
        let mut extra: std::collections::HashMap<(u16, u16), u8> = Default::default();
        for &(i, j) in overlay {
            let (c, r) = ((i / sx) as u16, (j / sy) as u16);
            if c < cols && r < rows {
                *extra.entry((c, r)).or_default() |= bit(self.marker, i % sx, j % sy);
            }
        }
        for ((c, r), b) in extra {
            let (bits, _) = self.cell(c, r);
            if let Some(g) = Self::glyph(self.marker, bits | b, 3) {
                if let Some(cell) = buf.cell_mut((area.x + c, area.y + r)) {
                    cell.set_char(g).set_style(overlay_style);
                }
            }
        }
    }

    /// The plot as plain text lines (for export), one line per row.
    pub fn to_text(&self) -> Vec<String> {
        let mut max = 0;
        for r in 0..self.rows {
            for c in 0..self.cols {
                max = max.max(self.cell(c, r).1);
            }
        }
        (0..self.rows)
            .map(|r| {
                (0..self.cols)
                    .map(|c| {
                        let (bits, sum) = self.cell(c, r);
                        Self::glyph(self.marker, bits, Self::level(sum, max)).unwrap_or(' ')
                    })
                    .collect::<String>()
                    .trim_end()
                    .to_string()
            })
            .collect()
    }
}

fn bit(marker: Marker, dx: usize, dy: usize) -> u8 {
    match marker {
        Marker::Braille => match (dx, dy) {
            (0, 0) => 0x01,
            (0, 1) => 0x02,
            (0, 2) => 0x04,
            (1, 0) => 0x08,
            (1, 1) => 0x10,
            (1, 2) => 0x20,
            (0, 3) => 0x40,
            _ => 0x80,
        },
        Marker::HalfBlock => 1 << dy,
        Marker::Dot => 1,
    }
}

/// Round tick values covering `r`, about `n` of them.
pub fn ticks(r: Range, n: usize) -> Vec<f64> {
    let n = n.max(2);
    let raw = r.span() / n as f64;
    if !(raw.is_finite() && raw > 0.0) {
        return vec![r.lo];
    }
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (r.lo / step).ceil() * step;
    let mut v = Vec::new();
    let mut t = first;
    while t <= r.hi + step * 1e-9 && v.len() < 64 {
        // Round away binary noise (0.6000000000000001) so labels and tests see 0.6.
        let clean = (t / step).round() * step;
        let clean = (clean * 1e12).round() / 1e12;
        v.push(if clean.abs() < step * 1e-9 {
            0.0
        } else {
            clean
        });
        t += step;
    }
    v
}

/// A tick label with as many decimals as the tick step needs.
pub fn tick_label(x: f64, step: f64) -> String {
    let dec = if step > 0.0 {
        (-step.log10().floor()).clamp(0.0, 6.0) as usize
    } else {
        2
    };
    let dec = if step > 0.0
        && ((step * 10f64.powi(dec as i32)).round() - step * 10f64.powi(dec as i32)).abs() > 1e-6
    {
        dec + 1
    } else {
        dec
    };
    format!("{x:.dec$}")
}

/// Draw a y axis (labels on the left, `label_w` wide) and an x axis (labels on the
/// last row) around a plot; returns the plot area inside.
pub fn draw_axes(
    area: Rect,
    buf: &mut Buffer,
    x: Range,
    y: Range,
    label_w: u16,
    theme: &Theme,
) -> Rect {
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
    for t in yt {
        let row = plot.y
            + (((1.0 - y.frac(t)) * (plot.height as f64 - 1.0)).round() as u16)
                .min(plot.height - 1);
        if last_row == Some(row) {
            continue;
        }
        last_row = Some(row);
        let mut s = tick_label(t, ystep);
        s.truncate(label_w as usize);
        buf.set_string(area.x + label_w - s.chars().count() as u16, row, &s, style);
        buf.set_string(area.x + label_w, row, "┤", style);
    }
    // Horizontal axis labels on the last row.
    let row = area.y + area.height - 1;
    buf.set_string(area.x + label_w, row, "└", style);
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
        let start = col.saturating_sub(w / 2).max(plot.x);
        if start < free_from || start + w > plot.x + plot.width {
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
    use crate::tui::theme::{ColorMode, Theme};

    #[test]
    fn braille_bits_follow_the_unicode_dot_order() {
        let mut g = HitGrid::new(
            1,
            1,
            Marker::Braille,
            Range::new(0.0, 1.0),
            Range::new(0.0, 1.0),
        );
        g.add(0.0, 1.0); // top left: dot 1
        assert_eq!(g.to_text(), vec!["⠁"]);
        g.add(1.0, 0.0); // bottom right: dot 8
        assert_eq!(g.to_text(), vec!["⢁"]);
        assert_eq!(g.points(), 2);
        g.add(2.0, 0.5); // outside: ignored
        assert_eq!(g.points(), 2);
    }

    #[test]
    fn halfblock_and_dot_fallbacks() {
        let mut g = HitGrid::new(
            2,
            1,
            Marker::HalfBlock,
            Range::new(0.0, 1.0),
            Range::new(0.0, 1.0),
        );
        g.add(0.1, 0.9);
        g.add(0.9, 0.1);
        assert_eq!(g.to_text(), vec!["▀▄"]);
        let mut d = HitGrid::new(
            2,
            1,
            Marker::Dot,
            Range::new(0.0, 1.0),
            Range::new(0.0, 1.0),
        );
        d.add(0.1, 0.5);
        assert_eq!(d.to_text(), vec!["·"]);
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
        g.render(buf.area, &mut buf, &theme, &[], Style::new());
        assert_eq!(buf[(0, 0)].symbol(), "⠁");
        assert_eq!(buf[(1, 0)].symbol(), " ");
        assert_eq!(buf[(0, 0)].fg, theme.density(3).fg.unwrap());
        assert_eq!(buf[(2, 0)].fg, theme.density(0).fg.unwrap());
        assert_eq!(g.lit_cells(), 2);
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        assert_eq!(
            ticks(Range::new(0.0, 1.0), 5),
            vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
        );
        assert_eq!(ticks(Range::new(0.1, 0.7), 4), vec![0.2, 0.4, 0.6]);
        assert_eq!(tick_label(0.25, 0.25), "0.25");
        assert_eq!(tick_label(0.4, 0.2), "0.4");
    }
}
