//! A two-parameter map on a grid of character cells: each class's glyph (densities
//! that tell the classes apart without colour) and colour slot, the curves' marks, and
//! the text picture with axes and a legend (`plane --format braille`). The terminal
//! application's plane view draws the same cells.
//!
//! Each cell shows the pixel under its centre (while the plane fills in, a pixel not yet
//! computed shows the coarser pixel whose block it lies in). A curve marks, on each row
//! (column) of cells, the cell whose α is nearest its value there.

use super::classes::{of_pixel, Class};
use super::text::significant;
use bouncemap_engine::orbits::curves::{CurveKind, Curves as TwoParameterCurves};
use bouncemap_engine::plane::{Curves, Plane, PlaneSpec};

/// The glyph of each class, from sparse to dense: period 1 lightest, chaos solid.
pub fn glyph(c: Class) -> char {
    match c {
        Class::Period1 => '·',
        Class::Period2 => ':',
        Class::Period4 => '+',
        Class::Period8 => '*',
        Class::Periodic => '#',
        Class::Sticking => '▒',
        Class::StickingUnresolved => '░',
        Class::Chaotic => '█',
        Class::Unresolved => '?',
    }
}

/// The glyph of a pixel where the ball never lands.
pub const NO_LANDING: char = 'x';

/// The curves' marks and names, in [`Curves::named`]'s order.
pub const CURVE_MARKS: [(char, &str); 3] = [
    ('B', "α_birth (1,1) born stable"),
    ('P', "α_PD period doubling"),
    ('C', "border collision of (2,2)"),
];

/// What one cell shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell {
    /// Not computed yet.
    Empty,
    /// A pixel's class (None: no landing).
    Class(Option<Class>),
    /// Curve number `n` of [`CURVE_MARKS`] (over the class beneath).
    Curve(usize, Option<Class>),
    /// A two-parameter curve's mark ([`curve_mark`], `◉` a codimension-two point)
    /// over the class beneath.
    Mark(char, Option<Class>),
}

impl Cell {
    /// The character drawn.
    pub fn glyph(self) -> char {
        match self {
            Cell::Empty => ' ',
            Cell::Class(Some(c)) => glyph(c),
            Cell::Class(None) => NO_LANDING,
            Cell::Curve(n, _) => CURVE_MARKS[n].0,
            Cell::Mark(m, _) => m,
        }
    }

    /// The class beneath (for its colour).
    pub fn class(self) -> Option<Class> {
        match self {
            Cell::Class(c) | Cell::Curve(_, c) | Cell::Mark(_, c) => c,
            Cell::Empty => None,
        }
    }
}

/// The cells of a `cols` × `rows` picture of `plane` (row 0 at the top, y = hi).
pub fn cells(
    spec: &PlaneSpec,
    plane: &Plane,
    curves: Option<&Curves>,
    cols: usize,
    rows: usize,
) -> Vec<Vec<Cell>> {
    let (nx, ny) = plane.size();
    let col_pixel = |c: usize| ((2 * c + 1) * nx / (2 * cols.max(1))).min(nx - 1);
    let row_pixel = |r: usize| ny - 1 - ((2 * r + 1) * ny / (2 * rows.max(1))).min(ny - 1);
    let mut out: Vec<Vec<Cell>> = (0..rows)
        .map(|r| {
            (0..cols)
                .map(|c| match plane.preview(col_pixel(c), row_pixel(r)) {
                    Some(p) => Cell::Class(of_pixel(p)),
                    None => Cell::Empty,
                })
                .collect()
        })
        .collect();
    if let Some(cv) = curves {
        // Along the other axis, one mark per line of cells at its pixel's value.
        let along = if cv.alpha_on_x { rows } else { cols };
        let alpha_axis = if cv.alpha_on_x { spec.x } else { spec.y };
        for l in 0..along {
            let k = if cv.alpha_on_x {
                row_pixel(l)
            } else {
                col_pixel(l)
            };
            for (n, (_, values)) in cv.named().iter().enumerate() {
                let Some(a) = values.get(k).copied().flatten() else {
                    continue;
                };
                if a < alpha_axis.lo || a > alpha_axis.hi || alpha_axis.hi <= alpha_axis.lo {
                    continue;
                }
                let span = if cv.alpha_on_x { cols } else { rows };
                let f = (a - alpha_axis.lo) / (alpha_axis.hi - alpha_axis.lo);
                let pos = ((f * span as f64) as usize).min(span - 1);
                let (r, c) = if cv.alpha_on_x {
                    (l, pos)
                } else {
                    (rows - 1 - pos, l)
                };
                out[r][c] = Cell::Curve(n, out[r][c].class());
            }
        }
    }
    out
}

/// The mark of a two-parameter curve's kind (the plane view and the text picture).
pub fn curve_mark(kind: &CurveKind) -> char {
    match kind {
        CurveKind::PeriodDoubling => '•',
        CurveKind::Fold | CurveKind::Birth => '~',
        CurveKind::BorderCollision { .. } => '×',
        CurveKind::Grazing { .. } => '¦',
    }
}

/// The marks of the two-parameter curves and what they mean, for legends.
pub const CURVE2_LEGEND: &str =
    "• period doubling  ~ fold  × border collision  ¦ grazing  ◉ codimension two";

/// Mark the two-parameter curves `c` on a `cells` picture of `spec`: every cell a
/// curve passes through (sampled finer than a cell along each segment), and `◉` at
/// each codimension-two point.
pub fn mark_curves(grid: &mut [Vec<Cell>], spec: &PlaneSpec, c: &TwoParameterCurves) {
    let rows = grid.len();
    let cols = grid.first().map_or(0, Vec::len);
    if rows == 0 || cols == 0 {
        return;
    }
    let alpha_on_x = spec.x.param == bouncemap_engine::jobs::grid::SweepParam::Alpha;
    let cell = |a: f64, q: f64| -> Option<(usize, usize)> {
        let (x, y) = if alpha_on_x { (a, q) } else { (q, a) };
        let fx = (x - spec.x.lo) / (spec.x.hi - spec.x.lo);
        let fy = (y - spec.y.lo) / (spec.y.hi - spec.y.lo);
        if !((0.0..=1.0).contains(&fx) && (0.0..=1.0).contains(&fy)) {
            return None;
        }
        let col = ((fx * cols as f64) as usize).min(cols - 1);
        let row = rows - 1 - ((fy * rows as f64) as usize).min(rows - 1);
        Some((row, col))
    };
    let mut put = |r: usize, c: usize, m: char| grid[r][c] = Cell::Mark(m, grid[r][c].class());
    for cv in &c.curves {
        let m = curve_mark(&cv.kind);
        for seg in cv.points.windows(2) {
            let (a, b) = (&seg[0], &seg[1]);
            let n = 2 * (cols.max(rows)) + 2;
            // Segments are short: a few samples per cell at most.
            let span = ((b.alpha - a.alpha).abs() / (spec.x.hi - spec.x.lo).abs().max(1e-300)
                + (b.p - a.p).abs() / (spec.y.hi - spec.y.lo).abs().max(1e-300))
                * n as f64;
            let steps = (span.ceil() as usize).clamp(1, 4 * n);
            for i in 0..=steps {
                let t = i as f64 / steps as f64;
                if let Some((r, col)) =
                    cell(a.alpha + t * (b.alpha - a.alpha), a.p + t * (b.p - a.p))
                {
                    put(r, col, m);
                }
            }
        }
    }
    for p in &c.codim2 {
        if let Some((r, col)) = cell(p.alpha, p.p) {
            put(r, col, '◉');
        }
    }
}

/// Tick labels of an axis: (position in 0..len, text) at both ends and the middle.
pub fn ticks(lo: f64, hi: f64, len: usize) -> Vec<(usize, String)> {
    let label = |x: f64| significant(x, 4);
    let mut t = vec![(0, label(lo))];
    if len > 24 {
        t.push(((len - 1) / 2, label(0.5 * (lo + hi))));
    }
    if len > 1 {
        t.push((len - 1, label(hi)));
    }
    t
}

/// The legend: every class's glyph and label, then the curves' marks.
pub fn legend() -> Vec<String> {
    let classes: Vec<String> = Class::ALL
        .iter()
        .map(|c| format!("{} {}", glyph(*c), c.label()))
        .collect();
    let curves: Vec<String> = CURVE_MARKS
        .iter()
        .map(|(m, name)| format!("{m} {name}"))
        .collect();
    vec![
        format!("{}  {NO_LANDING} no landing", classes.join("  ")),
        curves.join("   "),
    ]
}

/// The class of the upper and the lower pixel of every cell of a `cols` × `rows`
/// picture (two pixel rows per line of cells, row 0 at the top).
pub fn half_cells(
    plane: &Plane,
    cols: usize,
    rows: usize,
) -> Vec<Vec<(Option<Class>, Option<Class>)>> {
    let (nx, ny) = plane.size();
    let col_pixel = |c: usize| ((2 * c + 1) * nx / (2 * cols.max(1))).min(nx - 1);
    let half = |h: usize| ny - 1 - ((2 * h + 1) * ny / (4 * rows.max(1))).min(ny - 1);
    let class = |i: usize, j: usize| plane.preview(i, j).and_then(of_pixel);
    (0..rows)
        .map(|r| {
            (0..cols)
                .map(|c| {
                    let i = col_pixel(c);
                    (class(i, half(2 * r)), class(i, half(2 * r + 1)))
                })
                .collect()
        })
        .collect()
}

/// ANSI 256-colour escape for a foreground (38) or background (48) class colour.
fn ansi(layer: u8, c: Option<Class>) -> String {
    match c {
        Some(c) => format!("\x1b[{layer};5;{}m", c.ansi256()),
        None => String::new(),
    }
}

const RESET: &str = "\x1b[0m";

/// The whole picture as text: a title, the cells with the y axis's tick labels on the
/// left, the x axis's tick labels and name below, and the legend. `width` and `height`
/// are the text's size in characters. With `colour`, every cell is two pixels (upper
/// and lower half block) in the classes' 256 colours (ANSI escapes), the curves' marks
/// over them; without, one glyph per cell.
#[allow(clippy::too_many_arguments)]
pub fn lines(
    spec: &PlaneSpec,
    plane: &Plane,
    curves: Option<&Curves>,
    two_parameter: Option<&TwoParameterCurves>,
    title: &str,
    width: usize,
    height: usize,
    colour: bool,
) -> Vec<String> {
    let margin = 10;
    let cols = width.saturating_sub(margin + 1).max(4);
    let rows = height.saturating_sub(6).max(4) - usize::from(two_parameter.is_some());
    let mut grid = cells(spec, plane, curves, cols, rows);
    if let Some(c) = two_parameter {
        mark_curves(&mut grid, spec, c);
    }
    let halves = colour.then(|| half_cells(plane, cols, rows));
    let yt = ticks(spec.y.hi, spec.y.lo, rows);
    let mut out = vec![title.to_string()];
    for (r, line) in grid.iter().enumerate() {
        let label = yt
            .iter()
            .find(|(p, _)| *p == r)
            .map_or(String::new(), |(_, t)| t.clone());
        let name = if r == rows / 2 && yt.iter().all(|(p, _)| *p != r) {
            spec.y.param.as_str().to_string()
        } else {
            label
        };
        let body: String = match &halves {
            None => line.iter().map(|c| c.glyph()).collect(),
            Some(h) => line
                .iter()
                .zip(&h[r])
                .map(|(cell, (top, bottom))| match cell {
                    Cell::Curve(..) | Cell::Mark(..) => {
                        format!("{}\x1b[1;30m{}{RESET}", ansi(48, *bottom), cell.glyph())
                    }
                    _ if top.is_none() && bottom.is_none() => " ".into(),
                    _ => format!("{}{}▀{RESET}", ansi(38, *top), ansi(48, *bottom)),
                })
                .collect(),
        };
        out.push(format!("{name:>margin$}│{body}"));
    }
    out.push(format!("{:>margin$}└{}", "", "─".repeat(cols)));
    let mut axis = vec![' '; cols + 12];
    for (p, t) in ticks(spec.x.lo, spec.x.hi, cols) {
        let start = if p + 1 == cols {
            p + 1 - t.chars().count().min(p + 1)
        } else {
            p.saturating_sub(t.chars().count() / 2 * usize::from(p > 0))
        };
        for (k, ch) in t.chars().enumerate() {
            if let Some(slot) = axis.get_mut(start + k) {
                *slot = ch;
            }
        }
    }
    let axis: String = axis.into_iter().collect();
    out.push(format!("{:>margin$} {}", "", axis.trim_end()));
    out.push(format!("{:>margin$} {:^cols$}", "", spec.x.param.as_str()));
    if colour {
        let swatches: Vec<String> = Class::ALL
            .iter()
            .map(|c| format!("{}█{RESET} {}", ansi(38, Some(*c)), c.label()))
            .collect();
        out.push(swatches.join("  "));
        out.push(legend().pop().unwrap_or_default());
    } else {
        out.extend(legend());
    }
    if two_parameter.is_some() {
        out.push(format!("two-parameter curves: {CURVE2_LEGEND}"));
    }
    out
}
