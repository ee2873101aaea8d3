//! A picture of a terminal screen: a grid of character cells, each with its colours,
//! drawn as SVG (and through [`crate::raster`] as PNG) with the compiled-in DejaVu Sans
//! Mono. Braille patterns, block elements and light box-drawing lines are drawn as
//! shapes, so they join up cell to cell and need no glyph from the font (DejaVu Sans
//! Mono has no braille).

use crate::model::FigureError;
use crate::raster;
use crate::text::MONO_FAMILY;
use std::fmt::Write;

/// One character cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// What the cell shows (one character, maybe with combining marks; " " if blank).
    pub symbol: String,
    pub fg: (u8, u8, u8),
    pub bg: (u8, u8, u8),
    pub bold: bool,
    pub italic: bool,
    pub underline: bool,
}

/// A screen of `width × height` cells, row by row.
#[derive(Clone, Debug)]
pub struct Screen {
    pub width: usize,
    pub height: usize,
    pub cells: Vec<Cell>,
}

/// Font size, in pixels of the SVG.
const FONT: f64 = 14.0;
/// A cell's width (DejaVu Sans Mono's advance, 1233/2048 em) and height.
const CELL_W: f64 = FONT * 1233.0 / 2048.0;
const CELL_H: f64 = FONT * 1.25;
/// Where the baseline sits in a cell, from its top.
const BASELINE: f64 = CELL_H * 0.78;

fn hex((r, g, b): (u8, u8, u8)) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The light box-drawing lines of `c`: (left, right, up, down) arms.
fn box_arms(c: char) -> Option<(bool, bool, bool, bool)> {
    Some(match c {
        '─' => (true, true, false, false),
        '│' => (false, false, true, true),
        '┌' | '╭' => (false, true, false, true),
        '┐' | '╮' => (true, false, false, true),
        '└' | '╰' => (false, true, true, false),
        '┘' | '╯' => (true, false, true, false),
        '├' => (false, true, true, true),
        '┤' => (true, false, true, true),
        '┬' => (true, true, false, true),
        '┴' => (true, true, true, false),
        '┼' => (true, true, true, true),
        '╴' => (true, false, false, false),
        '╶' => (false, true, false, false),
        '╵' => (false, false, true, false),
        '╷' => (false, false, false, true),
        _ => return None,
    })
}

/// The filled part of block element `c`, as (x0, y0, x1, y1) fractions of the cell.
fn block(c: char) -> Option<(f64, f64, f64, f64)> {
    Some(match c {
        '█' => (0.0, 0.0, 1.0, 1.0),
        '▀' => (0.0, 0.0, 1.0, 0.5),
        '▄' => (0.0, 0.5, 1.0, 1.0),
        '▌' => (0.0, 0.0, 0.5, 1.0),
        '▐' => (0.5, 0.0, 1.0, 1.0),
        '▁' => (0.0, 7.0 / 8.0, 1.0, 1.0),
        '▂' => (0.0, 6.0 / 8.0, 1.0, 1.0),
        '▃' => (0.0, 5.0 / 8.0, 1.0, 1.0),
        '▅' => (0.0, 3.0 / 8.0, 1.0, 1.0),
        '▆' => (0.0, 2.0 / 8.0, 1.0, 1.0),
        '▇' => (0.0, 1.0 / 8.0, 1.0, 1.0),
        _ => return None,
    })
}

/// The dots of braille pattern `c`: (column 0–1, row 0–3) of each raised dot.
fn braille(c: char) -> Option<Vec<(u32, u32)>> {
    let bits = (c as u32).checked_sub(0x2800).filter(|b| *b < 0x100)?;
    // Dot numbering of the Unicode braille block: bits 0-2 and 6 are the left column's
    // rows 0-3, bits 3-5 and 7 the right column's.
    const AT: [(u32, u32); 8] = [
        (0, 0),
        (0, 1),
        (0, 2),
        (1, 0),
        (1, 1),
        (1, 2),
        (0, 3),
        (1, 3),
    ];
    Some(
        (0..8)
            .filter(|i| bits & (1 << i) != 0)
            .map(|i| AT[i])
            .collect(),
    )
}

/// The screen as an SVG document, and its size in pixels.
pub fn svg(screen: &Screen) -> (String, (f64, f64)) {
    let (w, h) = (screen.width as f64 * CELL_W, screen.height as f64 * CELL_H);
    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.2}" height="{h:.2}" viewBox="0 0 {w:.2} {h:.2}" font-family="{MONO_FAMILY}" font-size="{FONT}">"#
    );
    let background = screen.cells.first().map_or((0, 0, 0), |c| c.bg);
    let _ = write!(
        out,
        r#"<rect width="{w:.2}" height="{h:.2}" fill="{}"/>"#,
        hex(background)
    );
    for y in 0..screen.height {
        let row = &screen.cells[y * screen.width..(y + 1) * screen.width];
        // Backgrounds in runs of one colour.
        let mut x = 0;
        while x < screen.width {
            let bg = row[x].bg;
            let start = x;
            while x < screen.width && row[x].bg == bg {
                x += 1;
            }
            if bg != background {
                let _ = write!(
                    out,
                    r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}"/>"#,
                    start as f64 * CELL_W,
                    y as f64 * CELL_H,
                    (x - start) as f64 * CELL_W,
                    CELL_H,
                    hex(bg)
                );
            }
        }
        for (x, cell) in row.iter().enumerate() {
            draw_cell(&mut out, cell, x as f64 * CELL_W, y as f64 * CELL_H);
        }
    }
    out.push_str("</svg>");
    (out, (w, h))
}

fn draw_cell(out: &mut String, cell: &Cell, x: f64, y: f64) {
    let mut chars = cell.symbol.chars();
    let (Some(c), rest) = (chars.next(), chars.as_str()) else {
        return;
    };
    let fg = hex(cell.fg);
    if c == ' ' && rest.is_empty() {
        return;
    }
    if rest.is_empty() {
        if let Some((l, r, u, d)) = box_arms(c) {
            let (cx, cy) = (x + CELL_W / 2.0, y + CELL_H / 2.0);
            let mut path = String::new();
            for (on, (x1, y1)) in [
                (l, (x, cy)),
                (r, (x + CELL_W, cy)),
                (u, (cx, y)),
                (d, (cx, y + CELL_H)),
            ] {
                if on {
                    let _ = write!(path, "M{cx:.2} {cy:.2}L{x1:.2} {y1:.2}");
                }
            }
            let _ = write!(
                out,
                r#"<path d="{path}" stroke="{fg}" stroke-width="1" stroke-linecap="square" fill="none"/>"#
            );
            return;
        }
        if let Some((x0, y0, x1, y1)) = block(c) {
            let _ = write!(
                out,
                r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{fg}"/>"#,
                x + x0 * CELL_W,
                y + y0 * CELL_H,
                (x1 - x0) * CELL_W,
                (y1 - y0) * CELL_H
            );
            return;
        }
        if let Some(dots) = braille(c) {
            let r = CELL_W * 0.14;
            for (col, row) in dots {
                let _ = write!(
                    out,
                    r#"<circle cx="{:.2}" cy="{:.2}" r="{r:.2}" fill="{fg}"/>"#,
                    x + CELL_W * (0.3 + 0.4 * col as f64),
                    y + CELL_H * (0.125 + 0.25 * row as f64)
                );
            }
            return;
        }
    }
    let weight = if cell.bold {
        r#" font-weight="bold""#
    } else {
        ""
    };
    let style = if cell.italic {
        r#" font-style="italic""#
    } else {
        ""
    };
    let deco = if cell.underline {
        r#" text-decoration="underline""#
    } else {
        ""
    };
    let _ = write!(
        out,
        r#"<text x="{:.2}" y="{:.2}" fill="{fg}"{weight}{style}{deco} xml:space="preserve">{}</text>"#,
        x,
        y + BASELINE,
        escape(&cell.symbol)
    );
}

/// The screen as PNG bytes, `scale` device pixels per SVG pixel.
pub fn png(screen: &Screen, scale: f64) -> Result<Vec<u8>, FigureError> {
    let (svg, (w, h)) = svg(screen);
    // raster::png takes the page in inches at a dpi: 96 SVG pixels per inch.
    let dpi = (96.0 * scale).round() as u32;
    raster::png(&svg, (w / 96.0, h / 96.0), dpi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn braille_dots_follow_the_unicode_numbering() {
        // ⠁ is dot 1 (top left), ⢀ dot 8 (bottom right), ⣿ all eight.
        assert_eq!(braille('⠁'), Some(vec![(0, 0)]));
        assert_eq!(braille('⢀'), Some(vec![(1, 3)]));
        assert_eq!(braille('⣿').map(|d| d.len()), Some(8));
        assert_eq!(braille('a'), None);
    }

    #[test]
    fn a_screen_renders_with_every_kind_of_cell() {
        let cell = |s: &str| Cell {
            symbol: s.into(),
            fg: (200, 200, 200),
            bg: (0, 0, 0),
            bold: false,
            italic: false,
            underline: false,
        };
        let cells: Vec<Cell> = ["┌", "─", "⣿", "▀", "a", "t̂", "<", " "]
            .iter()
            .map(|s| cell(s))
            .collect();
        let screen = Screen {
            width: 4,
            height: 2,
            cells,
        };
        let (svg, (w, h)) = svg(&screen);
        assert!(svg.contains("&lt;") && svg.contains("<circle") && svg.contains("<path"));
        assert!((w - 4.0 * CELL_W).abs() < 1e-9 && (h - 2.0 * CELL_H).abs() < 1e-9);
        let bytes = png(&screen, 1.0).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
    }
}
