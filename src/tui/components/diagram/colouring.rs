//! The diagram's colour layer: for every character cell, how many points of each label
//! it holds (a label is an orbit class, or an attractor's number at its value, as the
//! figures label them: [`point_labels`]), so a cell is drawn in the style of its most
//! frequent label; and the legend that says what the styles mean.

use crate::output::classes::Class;
use crate::output::hitgrid::HitGrid;
use crate::tui::theme::Theme;
pub use bouncemap_figures::diagram::{point_labels, Colouring, ATTRACTOR_LABELS};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

/// Labels a cell counts: every class, or the attractors.
pub const LABELS: usize = if Class::ALL.len() > ATTRACTOR_LABELS {
    Class::ALL.len()
} else {
    ATTRACTOR_LABELS
};

/// Label counts per character cell of a [`HitGrid`] of the same size.
#[derive(Clone, Debug, Default)]
pub struct LabelGrid {
    cols: u16,
    rows: u16,
    counts: Vec<[u32; LABELS]>,
}

impl LabelGrid {
    pub fn new(cols: u16, rows: u16) -> LabelGrid {
        LabelGrid {
            cols,
            rows,
            counts: vec![[0; LABELS]; cols as usize * rows as usize],
        }
    }

    /// Count (`add`) or uncount a point at (x, y) of `grid` with `label`.
    pub fn count(&mut self, grid: &HitGrid, x: f64, y: f64, label: Option<u8>, add: bool) {
        let (Some(l), Some((i, j))) = (label, grid.sub_cell(x, y)) else {
            return;
        };
        let (sx, sy) = grid.marker().resolution();
        let (c, r) = (i / sx, j / sy);
        if c >= self.cols as usize || r >= self.rows as usize {
            return;
        }
        let n = &mut self.counts[r * self.cols as usize + c][l as usize];
        *n = if add { *n + 1 } else { n.saturating_sub(1) };
    }

    /// The most frequent label in cell (c, r).
    pub fn dominant(&self, c: u16, r: u16) -> Option<usize> {
        let counts = self
            .counts
            .get(r as usize * self.cols as usize + c as usize)?;
        counts
            .iter()
            .enumerate()
            .filter(|(_, &n)| n > 0)
            .max_by_key(|(l, &n)| (n, std::cmp::Reverse(*l)))
            .map(|(l, _)| l)
    }

    /// Restyle the lit cells of `plot` by their dominant label.
    pub fn paint(&self, plot: Rect, buf: &mut Buffer, theme: &Theme, by: Colouring) {
        if by == Colouring::Density {
            return;
        }
        for r in 0..self.rows.min(plot.height) {
            for c in 0..self.cols.min(plot.width) {
                let Some(l) = self.dominant(c, r) else {
                    continue;
                };
                let style = match by {
                    Colouring::Class => theme.class(Class::ALL[l]),
                    _ => theme.attractor(l),
                };
                if let Some(cell) = buf.cell_mut((plot.x + c, plot.y + r)) {
                    if cell.symbol() != " " {
                        // The class style replaces the density style entirely.
                        cell.set_style(ratatui::style::Style::reset())
                            .set_style(style);
                    }
                }
            }
        }
    }
}

/// The legend of the colours (drawn in the diagram's bottom border).
pub fn legend(by: Colouring, theme: &Theme) -> Line<'static> {
    let mut spans = vec![Span::styled(" ", theme.axis())];
    match by {
        Colouring::Class => {
            spans.push(Span::styled("period ", theme.axis()));
            for c in Class::ALL {
                spans.push(Span::styled(c.label().to_string(), theme.class(c)));
                spans.push(Span::styled(" ", theme.axis()));
            }
        }
        Colouring::Attractor => {
            spans.push(Span::styled("attractor ", theme.axis()));
            for n in 0..6 {
                spans.push(Span::styled(format!("{}", n + 1), theme.attractor(n)));
                spans.push(Span::styled(" ", theme.axis()));
            }
            spans.push(Span::styled("(1 = largest basin) ", theme.axis()));
        }
        Colouring::Density => {
            spans.push(Span::styled("density ", theme.axis()));
            for (l, t) in ["sparse", "·", "·", "dense"].into_iter().enumerate() {
                spans.push(Span::styled(t, theme.density(l)));
                spans.push(Span::styled(" ", theme.axis()));
            }
        }
    }
    Line::from(spans)
}
