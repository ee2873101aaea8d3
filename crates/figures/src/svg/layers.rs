//! Drawing one layer of a panel inside its frame: points, density dots, lines, bands,
//! cells and reference lines.

use super::{dasharray, hundredths, marker_el, n, Frame};
use super::{DOT_ALPHA, DOT_CELL, DOT_LEVELS, DOT_RADIUS};
use crate::model::{Color, Layer, Panel};
use std::collections::BTreeMap;
use std::fmt::Write;

fn polyline(points: impl Iterator<Item = (f64, f64)>) -> String {
    let mut d = String::new();
    for (i, (x, y)) in points.enumerate() {
        let _ = write!(d, "{}{} {}", if i == 0 { "M" } else { "L" }, n(x), n(y));
    }
    d
}

/// Cells as one path: each row's runs of touching cells merged into one rectangle.
fn cells(out: &mut String, f: &Frame, p: &Panel, centres: &[[f64; 2]], size: [f64; 2], c: Color) {
    let mut sorted = centres.to_vec();
    sorted.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
    let mut d = String::new();
    let mut i = 0;
    while i < sorted.len() {
        let (y, x0) = (sorted[i][1], sorted[i][0]);
        let mut x1 = x0;
        while i + 1 < sorted.len()
            && sorted[i + 1][1] == y
            && (sorted[i + 1][0] - x1 - size[0]).abs() < 1e-9 * size[0]
        {
            i += 1;
            x1 = sorted[i][0];
        }
        let (a, b) = (
            f.px(&p.x, x0 - size[0] / 2.0),
            f.px(&p.x, x1 + size[0] / 2.0),
        );
        let (top, bottom) = (f.py(&p.y, y + size[1] / 2.0), f.py(&p.y, y - size[1] / 2.0));
        let _ = write!(d, "M{} {}H{}V{}H{}Z", n(a), n(top), n(b), n(bottom), n(a));
        i += 1;
    }
    if !d.is_empty() {
        let _ = writeln!(out, "<path d=\"{d}\" fill=\"{}\"/>", c.hex());
    }
}

/// Weighted points as density dots: counted in cells of [`DOT_CELL`] points of the
/// frame (held densely: memory for the frame's cells, whatever the number of points),
/// each cell a disc whose opacity grows with its count, one path per opacity step.
fn density(
    out: &mut String,
    f: &Frame,
    p: &Panel,
    points: impl Iterator<Item = ([f64; 2], u32)>,
    color: Color,
) {
    let cell = |v: f64| (v / DOT_CELL) as i64;
    let (i0, j0) = (cell(f.x0 - 1.0), cell(f.y0 - 1.0));
    let (ni, nj) = (
        (cell(f.x1 + 1.0) - i0 + 1).max(1) as usize,
        (cell(f.y1 + 1.0) - j0 + 1).max(1) as usize,
    );
    let mut counts = vec![0u32; ni * nj];
    for (q, w) in points {
        let (x, y) = (f.px(&p.x, q[0]), f.py(&p.y, q[1]));
        if !(x >= f.x0 - 1.0 && x <= f.x1 + 1.0 && y >= f.y0 - 1.0 && y <= f.y1 + 1.0) {
            continue;
        }
        let (i, j) = ((cell(x) - i0) as usize, (cell(y) - j0) as usize);
        if i < ni && j < nj {
            let c = &mut counts[i * nj + j];
            *c = c.saturating_add(w);
        }
    }
    // One path per opacity step; each dot a zero-length stroke with round caps (a
    // disc), moved to by whole hundredths of a point so the relative moves add up
    // exactly. Cells in order of x, then y.
    let mut levels: BTreeMap<u32, (String, (i64, i64))> = BTreeMap::new();
    for (k, &count) in counts.iter().enumerate() {
        if count == 0 {
            continue;
        }
        let (i, j) = ((k / nj) as i64 + i0, (k % nj) as i64 + j0);
        let alpha = 1.0 - (1.0 - DOT_ALPHA).powi(count.min(1000) as i32);
        let level = ((alpha * DOT_LEVELS as f64).ceil() as u32).clamp(1, DOT_LEVELS);
        let at = (
            ((i as f64 + 0.5) * DOT_CELL * 100.0).round() as i64,
            ((j as f64 + 0.5) * DOT_CELL * 100.0).round() as i64,
        );
        let (d, last) = levels.entry(level).or_default();
        let (dx, dy) = (hundredths(at.0 - last.0), hundredths(at.1 - last.1));
        let sep = if dy.starts_with('-') { "" } else { " " };
        let _ = write!(d, "m{dx}{sep}{dy}h0");
        *last = at;
    }
    for (level, (d, _)) in levels {
        let _ = writeln!(
            out,
            "<path fill=\"none\" stroke=\"{}\" stroke-opacity=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\" d=\"{d}\"/>",
            color.hex(),
            n(level as f64 / DOT_LEVELS as f64),
            n(2.0 * DOT_RADIUS)
        );
    }
}

pub(super) fn layer(out: &mut String, f: &Frame, p: &Panel, l: &Layer) {
    match l {
        Layer::Bands { spans, color, .. } => {
            let mut d = String::new();
            for s in spans {
                let (a, b) = (f.px(&p.x, s[0]), f.px(&p.x, s[1]));
                let _ = write!(
                    d,
                    "M{} {}H{}V{}H{}Z",
                    n(a.max(f.x0 - 1.0)),
                    n(f.y0),
                    n(b.min(f.x1 + 1.0)),
                    n(f.y1),
                    n(a.max(f.x0 - 1.0))
                );
            }
            if !d.is_empty() {
                let _ = writeln!(out, "<path d=\"{d}\" fill=\"{}\"/>", color.hex());
            }
        }
        Layer::Cells {
            centres,
            size,
            color,
            ..
        } => cells(out, f, p, centres, *size, *color),
        Layer::Area {
            lower,
            upper,
            color,
            ..
        } => {
            let to = |q: &[f64; 2]| (f.px(&p.x, q[0]), f.py(&p.y, q[1]));
            let mut d = String::new();
            for (i, (x, y)) in lower
                .iter()
                .map(to)
                .chain(upper.iter().rev().map(to))
                .enumerate()
            {
                let _ = write!(d, "{}{} {}", if i == 0 { "M" } else { "L" }, n(x), n(y));
            }
            if !d.is_empty() {
                let _ = writeln!(out, "<path d=\"{d}Z\" fill=\"{}\"/>", color.hex());
            }
        }
        Layer::Density { points, color, .. } => {
            density(out, f, p, points.iter().map(|q| (*q, 1)), *color);
        }
        Layer::Grid { grid, color, .. } => density(out, f, p, grid.bins(), *color),
        Layer::Lines {
            lines,
            color,
            dash,
            width,
            ..
        } => {
            for line in lines {
                let d = polyline(line.iter().map(|q| (f.px(&p.x, q[0]), f.py(&p.y, q[1]))));
                if d.is_empty() {
                    continue;
                }
                let _ = writeln!(
                    out,
                    "<path d=\"{d}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"{}/>",
                    color.hex(),
                    n(*width),
                    dasharray(*dash)
                );
            }
        }
        Layer::Markers {
            points,
            marker,
            color,
            ..
        } => {
            for q in points {
                marker_el(out, *marker, *color, f.px(&p.x, q[0]), f.py(&p.y, q[1]));
            }
        }
        Layer::HLine { y, color, dash } => {
            let yy = f.py(&p.y, *y);
            let _ = writeln!(
                out,
                "<path d=\"M{} {}H{}\" stroke=\"{}\" stroke-width=\"0.6\"{}/>",
                n(f.x0),
                n(yy),
                n(f.x1),
                color.hex(),
                dasharray(*dash)
            );
        }
        Layer::VLine { x, color, dash } => {
            let xx = f.px(&p.x, *x);
            let _ = writeln!(
                out,
                "<path d=\"M{} {}V{}\" stroke=\"{}\" stroke-width=\"0.6\"{}/>",
                n(xx),
                n(f.y0),
                n(f.y1),
                color.hex(),
                dasharray(*dash)
            );
        }
    }
}
