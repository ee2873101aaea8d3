//! The one hit-count grid behind every text picture: the terminal application's
//! diagram and phase plot, and `sweep --format braille`. Points are binned into
//! sub-cells (2×4 per character for braille, 1×2 for half blocks, 1×1 for dots) as they
//! arrive; a picture is one glyph per cell, so its cost is the number of cells, not of
//! points. Density is the log of the hit count in four levels (colour in the terminal,
//! glyph weight for dots). Also: round tick values and their labels.

use std::fmt;

/// The glyphs a plot is drawn with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Marker {
    #[default]
    Braille,
    HalfBlock,
    Dot,
}

impl Marker {
    /// Parse `braille | halfblock | dot`.
    pub fn parse(s: &str) -> Result<Marker, String> {
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

    /// `text` as a plot drawn with this marker shows it: each braille sample in it (a
    /// legend's "⣿ dots", "⠤ line") becomes that marker's glyph for as many dots (a
    /// full cell, or a line), so no braille is shown unless the marker is braille.
    pub fn samples(self, text: &str) -> String {
        text.chars()
            .map(|c| match (self, c as u32) {
                (Marker::Braille, _) | (_, 0..=0x2800) | (_, 0x2900..) => c,
                (m, code) => {
                    let full = (code - 0x2800).count_ones() >= 6;
                    match (m, full) {
                        (Marker::HalfBlock, true) => '█',
                        (Marker::HalfBlock, false) => '▀',
                        (_, true) => '●',
                        (_, false) => '•',
                    }
                }
            })
            .collect()
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
    pub fn cell(&self, col: u16, row: u16) -> (u8, u32) {
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

/// The bit of sub-cell (dx, dy) in a cell's pattern.
pub fn bit(marker: Marker, dx: usize, dy: usize) -> u8 {
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

#[cfg(test)]
mod tests {
    use super::*;

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
