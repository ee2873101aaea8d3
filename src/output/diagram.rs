//! A bifurcation diagram as text: the shared [`HitGrid`] drawn in braille with a title
//! line, a phase axis, the swept parameter's axis and a line marking columns with
//! sticking (`s`) or resting (`r`) values. Used by `sweep --format braille`.

use super::hitgrid::{HitGrid, Marker, Range};
use super::text::shortest;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{SweepSpec, ValueResult, Warm};

/// Width of the phase labels left of the plot.
const GUTTER: usize = 6;

/// The diagram `width` characters wide and `height` lines high, phase t̂ ∈ [0, 1)
/// upwards against the swept parameter, binned as values arrive (nothing else is kept).
pub struct BrailleDiagram {
    grid: HitGrid,
    marks: Vec<char>,
    cols: usize,
    rows: usize,
}

impl BrailleDiagram {
    pub fn new(spec: &SweepSpec, width: u16, height: u16) -> BrailleDiagram {
        let cols = (width as usize).saturating_sub(GUTTER).max(4);
        let rows = (height as usize).saturating_sub(4).max(2);
        BrailleDiagram {
            grid: HitGrid::new(
                cols as u16,
                rows as u16,
                Marker::Braille,
                Range::new(spec.lo, spec.hi),
                Range::new(0.0, 1.0),
            ),
            marks: vec![' '; cols],
            cols,
            rows,
        }
    }

    /// Bin one value's points, and mark its column if it sticks or rests.
    pub fn add(&mut self, b: &ValueResult) {
        for p in &b.points {
            self.grid.add(b.value, p.phase);
        }
        if let Some((i, _)) = self.grid.sub_cell(b.value, 0.5) {
            let m = &mut self.marks[i / 2];
            if matches!(b.outcome, Outcome::Resting { .. }) {
                *m = 'r';
            } else if b.sticking && *m != 'r' {
                *m = 's';
            }
        }
    }

    /// The picture: a title, the plot with its phase axis, the parameter's axis and the
    /// sticking/resting marks.
    pub fn lines(&self, spec: &SweepSpec) -> Vec<String> {
        let (cols, rows) = (self.cols, self.rows);
        // Where each value's orbit starts: the same initial state for every value (the
        // paper's procedure), or the last state of the neighbouring value.
        let at = if spec.initial.near_fixed_point {
            "near (1,1)".to_string()
        } else {
            match spec.initial.v0 {
                Some(v0) => format!(
                    "at t0 = {}, v0 = {}",
                    shortest(spec.initial.t0),
                    shortest(v0)
                ),
                None => format!(
                    "at t0 = {}, v0 = f'(t0) + {}",
                    shortest(spec.initial.t0),
                    shortest(bouncemap_engine::DEFAULT_HOP)
                ),
            }
        };
        let start = match spec.warm {
            // Several starts per value look for every attractor (they are cold).
            _ if spec.starts > 1 => format!(
                "every value from {} starts (one {at}, the others spread over t0 in [0, 1), w0 in [0, {}]), every attractor found drawn",
                spec.starts,
                spec.w_max.map_or("W".to_string(), shortest)
            ),
            Warm::Off => format!("every value started {at}"),
            Warm::Forward => format!("each value from the one below, the first {at}"),
            Warm::Backward => format!("each value from the one above, the first {at}"),
        };
        let title = format!(
            "{}  {} = {}..{}  {}  T = {}  keep {}  {start}",
            spec.table.name(),
            spec.param.as_str(),
            shortest(spec.lo),
            shortest(spec.hi),
            fixed_params(spec),
            spec.transient,
            spec.keep,
        );
        let mut lines = vec![title];
        for (row, text) in self.grid.to_text().into_iter().enumerate() {
            // Empty cells as the blank braille pattern, so every row is `cols` wide.
            let glyphs: String = text
                .chars()
                .map(|c| if c == ' ' { '\u{2800}' } else { c })
                .chain(std::iter::repeat('\u{2800}'))
                .take(cols)
                .collect();
            let label = if row == 0 {
                "1.0 ┤"
            } else if row == rows / 2 {
                "0.5 ┤"
            } else if row + 1 == rows {
                "0.0 ┤"
            } else {
                "    │"
            };
            lines.push(format!("{label:>GUTTER$}{glyphs}"));
        }
        lines.push(format!("{:>GUTTER$}{}", "└", "─".repeat(cols)));
        let lo = shortest(spec.lo);
        let hi = shortest(spec.hi);
        let name = spec.param.as_str();
        let pad = cols.saturating_sub(lo.len() + hi.len() + name.len());
        let left = pad / 2;
        lines.push(format!(
            "{:GUTTER$}{lo}{}{name}{}{hi}",
            "",
            " ".repeat(left),
            " ".repeat(pad - left)
        ));
        if self.marks.iter().any(|&m| m != ' ') {
            lines.push(format!(
                "{:>GUTTER$}{}",
                "s/r ",
                self.marks.iter().collect::<String>()
            ));
        }
        lines
    }
}

fn fixed_params(spec: &SweepSpec) -> String {
    match spec.param {
        SweepParam::Alpha => format!("r = {}", shortest(spec.r)),
        SweepParam::R => format!("alpha = {}", shortest(spec.alpha)),
        SweepParam::Table(_) => {
            format!("alpha = {}  r = {}", shortest(spec.alpha), shortest(spec.r))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::run::Point as SweepPoint;
    use bouncemap_engine::{EventKind, Table};

    #[test]
    fn a_point_lands_in_its_braille_dot() {
        let spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.0,
            1.0,
            2,
        );
        // One point at the top left (α = 0, t̂ just below 1): braille dot 1 of the
        // first cell of the first plot row.
        let r = ValueResult {
            index: 0,
            value: 0.0,
            complete: true,
            points: vec![SweepPoint {
                phase: 0.999,
                v: 0.5,
                kind: EventKind::Impact,
            }],
            outcome: Outcome::Unsettled,
            sticking: false,
            events: 1,
            lyapunov: None,
            attractors: Vec::new(),
            precision: None,
            cycle: None,
        };
        let mut d = BrailleDiagram::new(&spec, 30, 10);
        d.add(&r);
        let lines = d.lines(&spec);
        assert_eq!(lines.len(), 1 + 6 + 2);
        assert!(lines[1].starts_with(" 1.0 ┤⠁"), "{:?}", lines[1]);
        assert!(lines[8].contains("alpha"));
    }
}
