//! A basin picture on a grid of character cells, and what each attractor looks like in
//! it: its texture (a braille pattern, or with another marker a block or a shape, that
//! tells attractors apart without colour) and its legend line; its number and name are the figures' ([`numbers`], [`describe`],
//! [`exponent`] from `bouncemap_figures::basins`, re-exported here). Used by `basins
//! --format braille` and by the terminal application's basins panel.
//!
//! Each character cell shows the attractor most of the grid points under it went to
//! (while the picture fills in, a point not yet computed takes the label of the coarser
//! point whose block it lies in).

use super::hitgrid::Marker;
use super::text::significant;
use bouncemap_engine::attractors::basins::Basins;
use bouncemap_engine::attractors::Registry;
pub use bouncemap_figures::basins::{describe, exponent, numbers};

/// Textures for attractor numbers 1, 2, … (the last repeats beyond), in braille.
pub const TEXTURES: [char; 8] = ['⣿', '⠶', '⢕', '⡇', '⠉', '⣀', '⠑', '⠂'];
/// The same in block elements (`--marker halfblock`).
pub const BLOCK_TEXTURES: [char; 8] = ['█', '▓', '▒', '░', '▚', '▞', '▄', '▀'];
/// The same in geometric shapes (`--marker dot`).
pub const DOT_TEXTURES: [char; 8] = ['●', '◆', '■', '▲', '○', '◇', '□', '△'];

/// The textures a plot drawn with `marker` uses (no braille unless it is braille).
pub fn textures(marker: Marker) -> &'static [char; 8] {
    match marker {
        Marker::Braille => &TEXTURES,
        Marker::HalfBlock => &BLOCK_TEXTURES,
        Marker::Dot => &DOT_TEXTURES,
    }
}

/// The braille texture of the attractor shown as number `number` (1-based).
pub fn texture(number: usize) -> char {
    texture_in(Marker::Braille, number)
}

/// The texture of attractor `number` (1-based) among `marker`'s.
pub fn texture_in(marker: Marker, number: usize) -> char {
    let t = textures(marker);
    t[number.saturating_sub(1).min(t.len() - 1)]
}

/// One legend line: texture, number, kind and period, exponent, basin share.
pub fn legend_line(reg: &Registry, id: usize, number: usize) -> String {
    let a = &reg.attractors()[id];
    let point = a
        .point
        .map(|(t, v)| format!("  t̂ {t:.6} v {}", significant(v, 6)))
        .unwrap_or_default();
    format!(
        "{} {number} {:<18} λ {:>9}  basin {:>5.1}%{point}",
        texture(number),
        describe(a),
        exponent(a.lyapunov),
        100.0 * reg.fraction(id),
    )
}

/// The attractor id shown in each of `cols` × `rows` character cells, top row (largest
/// w0) first.
pub fn cells(b: &Basins, cols: usize, rows: usize) -> Vec<Vec<Option<u32>>> {
    let (nx, ny) = b.grid();
    let mut out = vec![vec![None; cols]; rows];
    let mut counts: Vec<u32> = Vec::new();
    for (row, line) in out.iter_mut().enumerate() {
        // Grid rows under this character row (row 0 is the top: the largest w0).
        let (j0, j1) = span(rows - 1 - row, rows, ny);
        for (col, cell) in line.iter_mut().enumerate() {
            let (i0, i1) = span(col, cols, nx);
            counts.clear();
            for j in j0..j1 {
                for i in i0..i1 {
                    if let Some(l) = b.preview_label(i, j) {
                        let l = l as usize;
                        if counts.len() <= l {
                            counts.resize(l + 1, 0);
                        }
                        counts[l] += 1;
                    }
                }
            }
            *cell = counts
                .iter()
                .enumerate()
                .filter(|(_, &n)| n > 0)
                .max_by_key(|(i, &n)| (n, std::cmp::Reverse(*i)))
                .map(|(i, _)| i as u32);
        }
    }
    out
}

/// Grid indices [a, b) under cell `k` of `cells` over `n` grid points (at least one).
fn span(k: usize, cells: usize, n: usize) -> (usize, usize) {
    let a = k * n / cells;
    let b = ((k + 1) * n / cells).max(a + 1).min(n);
    (a.min(n - 1), b)
}

/// The picture as text: a title, the picture with its w0 axis, the t̂0 axis and the
/// legend.
pub fn lines(b: &Basins, title: &str, w_max: f64, width: usize, height: usize) -> Vec<String> {
    const GUTTER: usize = 7;
    let reg = b.registry();
    let number = numbers(reg);
    let cols = width.saturating_sub(GUTTER).max(4);
    let legend = reg.attractors().len();
    let rows = height.saturating_sub(4 + legend).max(4);
    let mut out = vec![title.to_string()];
    for (row, line) in cells(b, cols, rows).into_iter().enumerate() {
        let glyphs: String = line
            .iter()
            .map(|l| l.map_or(' ', |id| texture(number[id as usize])))
            .collect();
        let label = if row == 0 {
            format!("{} ┤", significant(w_max, 3))
        } else if row + 1 == rows {
            "0 ┤".to_string()
        } else if row == rows / 2 {
            "w0 │".to_string()
        } else {
            "│".to_string()
        };
        out.push(format!("{label:>GUTTER$}{glyphs}"));
    }
    out.push(format!("{:>GUTTER$}{}", "└", "─".repeat(cols)));
    let pad = cols.saturating_sub(3 + 2 + 1);
    out.push(format!(
        "{:GUTTER$}0{}t̂0{}1",
        "",
        " ".repeat(pad / 2),
        " ".repeat(pad - pad / 2)
    ));
    for id in reg.ranked() {
        out.push(format!("  {}", legend_line(reg, id, number[id])));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_tile_the_grid() {
        for (cells, n) in [(10, 200), (7, 3), (80, 80), (3, 1)] {
            let mut covered = vec![0; n];
            for k in 0..cells {
                let (a, b) = span(k, cells, n);
                assert!(a < b && b <= n);
                for c in &mut covered[a..b] {
                    *c += 1;
                }
            }
            assert!(covered.iter().all(|&c| c >= 1), "{cells} {n}");
        }
    }

    #[test]
    fn textures_are_distinct() {
        for set in [TEXTURES, BLOCK_TEXTURES, DOT_TEXTURES] {
            let mut t = set.to_vec();
            t.sort();
            t.dedup();
            assert_eq!(t.len(), TEXTURES.len());
        }
        for m in [Marker::HalfBlock, Marker::Dot] {
            assert!(textures(m)
                .iter()
                .all(|c| !('\u{2800}'..='\u{28ff}').contains(c)));
        }
        assert_eq!(texture(1), '⣿');
        assert_eq!(texture(100), '⠂');
    }
}
