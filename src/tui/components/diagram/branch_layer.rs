//! The continued branches over the diagram (α sweeps): each impact of each cycle as a
//! curve in the plot's marker (braille dots, half blocks or dots), stable stretches
//! solid, unstable ones dotted and dim, and with proofs on (`V`) the stretches not
//! proved by interval arithmetic in the error colour; where a braille curve crosses a cell with data
//! its dots are added to the data's. Their special
//! points (PD period doubling, F fold, BC border collision) are labelled on the x
//! axis's row, beside the B and P of the (1, k) solution.

use crate::output::hitgrid::{Marker, Range};
use crate::tui::skeleton::Skeleton;
use crate::tui::theme::Theme;
use bouncemap_engine::orbits::continuation::Kind;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;

/// Braille dot bits of a 2×4 cell, (column, row) → bit.
const BITS: [[u8; 4]; 2] = [[0x01, 0x02, 0x04, 0x40], [0x08, 0x10, 0x20, 0x80]];

/// Dots of one layer, per cell.
struct Dots {
    w: usize,
    h: usize,
    bits: Vec<u8>,
}

impl Dots {
    fn new(w: usize, h: usize) -> Dots {
        Dots {
            w,
            h,
            bits: vec![0; w * h],
        }
    }

    /// Set the dot at sub-cell (i, j), j counted from the top.
    fn set(&mut self, i: usize, j: usize) {
        if i < 2 * self.w && j < 4 * self.h {
            self.bits[(j / 4) * self.w + i / 2] |= BITS[i % 2][j % 4];
        }
    }
}

/// Draw the skeleton over `plot`, whose axes are `x` (α) and `y` (t̂, or v when
/// `velocity`). Returns nothing; the axis row below `plot` gets the labels.
pub fn draw(
    sk: &Skeleton,
    proved: Option<&[Vec<bool>]>,
    (x, y, velocity): (Range, Range, bool),
    plot: Rect,
    marker: Marker,
    buf: &mut Buffer,
    theme: &Theme,
) {
    let (w, h) = (plot.width as usize, plot.height as usize);
    if w == 0 || h == 0 {
        return;
    }
    let mut stable = Dots::new(w, h);
    let mut unstable = Dots::new(w, h);
    let mut unproved = Dots::new(w, h);
    let (sx, sy) = (2.0 * w as f64, 4.0 * h as f64);
    let sub = |a: f64, v: f64| -> Option<(usize, usize)> {
        if !x.contains(a) || !y.contains(v) {
            return None;
        }
        let i = (x.frac(a) * sx).min(sx - 1.0) as usize;
        let j = ((1.0 - y.frac(v)) * sy).min(sy - 1.0) as usize;
        Some((i, j))
    };
    for (bi, b) in sk.branches.iter().enumerate() {
        for (pi, pair) in b.points.windows(2).enumerate() {
            let (p, q) = (&pair[0], &pair[1]);
            // A stretch is proved when both its ends are.
            let not_proved = proved.is_some_and(|m| !(m[bi][pi] && m[bi][pi + 1]));
            let (ys, yq) = if velocity {
                (&p.velocities, &q.velocities)
            } else {
                (&p.phases, &q.phases)
            };
            let layer = if not_proved {
                &mut unproved
            } else if p.stable && q.stable {
                &mut stable
            } else {
                &mut unstable
            };
            for (&y0, &y1) in ys.iter().zip(yq) {
                // A phase that wraps around 0/1 between two points is not a segment.
                if !velocity && (y1 - y0).abs() > 0.5 {
                    continue;
                }
                let cols = ((q.alpha - p.alpha).abs() / x.span() * sx).abs();
                let rows = ((y1 - y0).abs() / y.span() * sy).abs();
                let n = (cols.max(rows).ceil() as usize).clamp(1, 4096);
                for s in 0..=n {
                    let f = s as f64 / n as f64;
                    if let Some((i, j)) = sub(p.alpha + f * (q.alpha - p.alpha), y0 + f * (y1 - y0))
                    {
                        layer.set(i, j);
                    }
                }
            }
        }
    }
    // Unstable stretches dotted: the left dot column of each cell only.
    for bits in unstable.bits.iter_mut() {
        *bits &= 0x47;
    }
    paint(&unstable, plot, marker, buf, theme.dim());
    paint(&stable, plot, marker, buf, theme.mark2());
    paint(&unproved, plot, marker, buf, theme.error());
    labels(sk, x, plot, buf, theme);
}

/// The glyph of a cell's dots (braille bits) in `marker`: the braille pattern, the
/// upper, lower or full half block, or a dot.
fn glyph(bits: u8, marker: Marker) -> char {
    match marker {
        Marker::Braille => char::from_u32(0x2800 + bits as u32).unwrap_or(' '),
        Marker::HalfBlock => {
            let (upper, lower) = (bits & 0x1b != 0, bits & 0xe4 != 0);
            match (upper, lower) {
                (true, true) => '█',
                (true, false) => '▀',
                _ => '▄',
            }
        }
        Marker::Dot => '•',
    }
}

/// Put a layer's dots into the buffer: on an empty cell as a glyph of `marker` in
/// `style`; on a braille cell with data, as extra dots in the data's style (other
/// markers leave cells with data as they are).
fn paint(d: &Dots, plot: Rect, marker: Marker, buf: &mut Buffer, style: Style) {
    for r in 0..d.h {
        for c in 0..d.w {
            let bits = d.bits[r * d.w + c];
            if bits == 0 {
                continue;
            }
            let Some(cell) = buf.cell_mut((plot.x + c as u16, plot.y + r as u16)) else {
                continue;
            };
            let ch = cell.symbol().chars().next().unwrap_or(' ');
            if ch == ' ' || ch == '\u{2800}' {
                cell.set_char(glyph(bits, marker)).set_style(style);
            } else if marker == Marker::Braille && ('\u{2801}'..='\u{28ff}').contains(&ch) {
                let old = ch as u32 - 0x2800;
                let glyph = char::from_u32(0x2800 + (old | bits as u32)).unwrap_or(ch);
                cell.set_char(glyph);
            }
        }
    }
}

/// PD, F and BC at their α on the axis row (the row below `plot`), first come first
/// served where labels would overlap.
fn labels(sk: &Skeleton, x: Range, plot: Rect, buf: &mut Buffer, theme: &Theme) {
    let row = plot.y + plot.height;
    let mut marks: Vec<(f64, &str)> = Vec::new();
    for b in &sk.branches {
        for s in b.specials.iter().chain([&b.begin, &b.end]) {
            let label = match s.kind {
                Kind::PeriodDoubling => "PD",
                Kind::Fold => "F",
                Kind::BorderCollision => "BC",
                _ => continue,
            };
            if !marks
                .iter()
                .any(|(a, l)| *l == label && (a - s.alpha).abs() <= 1e-9 * x.span())
            {
                marks.push((s.alpha, label));
            }
        }
    }
    marks.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Labels whose places would touch are joined ("PD,BC"), at the first one's column.
    let mut placed: Vec<(u16, String)> = Vec::new();
    for (a, label) in marks {
        if !x.contains(a) || plot.width == 0 {
            continue;
        }
        let col = plot.x + ((x.frac(a) * plot.width as f64) as u16).min(plot.width - 1);
        match placed.last_mut() {
            Some((c, text)) if col <= *c + text.chars().count() as u16 => {
                if !text.split(',').any(|t| t == label) {
                    text.push(',');
                    text.push_str(label);
                }
            }
            _ => placed.push((col, label.to_string())),
        }
    }
    // Beside the tick labels, not over them: the nearest free stretch of the row
    // within four columns (over them only where there is none).
    let right = plot.x + plot.width;
    let free = |buf: &Buffer, c: u16, n: u16| {
        c >= plot.x
            && c + n <= right
            && (c.saturating_sub(1)..(c + n + 1).min(right))
                .all(|x| buf.cell((x, row)).is_none_or(|cell| cell.symbol() == " "))
    };
    for (col, text) in placed {
        let n = text.chars().count() as u16;
        let at = [0i32, 1, -1, 2, -2, 3, -3, 4, -4]
            .into_iter()
            .map(|d| (col as i32 + d).max(0) as u16)
            .find(|&c| free(buf, c, n))
            .unwrap_or(col);
        let room = right.saturating_sub(at) as usize;
        let shown: String = text.chars().take(room).collect();
        buf.set_string(at, row, shown, theme.mark2());
    }
}
