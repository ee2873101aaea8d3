//! Table shapes F(t̂): the sine, the paper's piecewise-polynomial F_D, and piecewise
//! polynomials read from TOML text.
//!
//! A table is periodic with period 1 and C¹. The displacement is f(t) = α F(t); α is not
//! part of the shape (see [`super::System`]). Piecewise tables store each piece in its
//! local variable s = t̂ − start, which keeps the coefficients small and the root
//! isolation accurate. Parsing a file's text lives here; reading the file does not (the
//! engine does no I/O).

use super::error::EngineError;
use super::poly::{Poly, MAX_COEFFS};
use serde::Deserialize;
use std::f64::consts::PI;
use std::fmt;

/// Tolerance for the periodicity, continuity and C¹ checks of a table file.
pub const C1_TOLERANCE: f64 = 1e-9;

/// Highest polynomial degree accepted in a table file.
pub const MAX_TABLE_DEGREE: usize = MAX_COEFFS - 2;

/// One polynomial piece of a periodic table, on `[start, end)` in phase.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Phase where the piece starts.
    pub start: f64,
    /// Phase where the piece ends (the next piece's start, or 1).
    pub end: f64,
    /// F on the piece as a polynomial in s = t̂ − start.
    pub f: Poly,
    /// F', F'', F''' in the same variable.
    pub d1: Poly,
    pub d2: Poly,
    pub d3: Poly,
    /// Rigorous bounds of F on the closed piece (padded by a few ulps).
    pub min: f64,
    pub max: f64,
}

impl Piece {
    fn new(start: f64, end: f64, f: Poly) -> Piece {
        let d1 = f.derivative();
        let d2 = d1.derivative();
        let d3 = d2.derivative();
        let len = end - start;
        let mut lo = f.eval(0.0).min(f.eval(len));
        let mut hi = f.eval(0.0).max(f.eval(len));
        for &c in d1.roots_in(0.0, len).as_slice() {
            let v = f.eval(c);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        let pad = 1e-12 * (1.0 + lo.abs().max(hi.abs()));
        Piece {
            start,
            end,
            f,
            d1,
            d2,
            d3,
            min: lo - pad,
            max: hi + pad,
        }
    }

    /// Length of the piece in phase.
    pub fn len(&self) -> f64 {
        self.end - self.start
    }

    /// Always false: pieces have positive length.
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// The shape of the table.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// F(t) = sin 2πt.
    Sine,
    /// A C¹ periodic piecewise polynomial.
    Piecewise(Vec<Piece>),
}

/// A named table shape F(t̂).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    name: String,
    shape: Shape,
    /// D for the paper's F_D family, None otherwise.
    d: Option<f64>,
    /// An upper bound of |F''| over a period.
    accel_bound: f64,
    /// Rigorous bounds (min, max) of F over a period.
    range: (f64, f64),
    /// Highest polynomial degree among the pieces (0 for the sine, which has none).
    max_degree: usize,
}

/// What a `--table` argument names before any file is read.
#[derive(Clone, Debug, PartialEq)]
pub enum TableSpec {
    /// A table built into the engine.
    Builtin(Table),
    /// A TOML file to read and parse with [`Table::from_toml`].
    File(String),
}

impl TableSpec {
    /// Parse `sine | quad | cubic | fd:D | PATH.toml`.
    pub fn parse(spec: &str) -> Result<TableSpec, EngineError> {
        let s = spec.trim();
        match s {
            "sine" => return Ok(TableSpec::Builtin(Table::sine())),
            "quad" => return Ok(TableSpec::Builtin(Table::fd(0.0)?)),
            "cubic" => return Ok(TableSpec::Builtin(Table::fd(1.0)?)),
            _ => {}
        }
        if let Some(d) = s.strip_prefix("fd:") {
            let d: f64 = d.parse().map_err(|_| EngineError::InvalidParameter {
                name: "D",
                value: d.to_string(),
                range: "a number in [0, 1]",
            })?;
            return Ok(TableSpec::Builtin(Table::fd(d)?));
        }
        if s.ends_with(".toml") {
            return Ok(TableSpec::File(s.to_string()));
        }
        Err(EngineError::UnknownTable(s.to_string()))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    name: Option<String>,
    #[allow(dead_code)]
    description: Option<String>,
    piece: Vec<PieceFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PieceFile {
    start: f64,
    coeffs: Vec<f64>,
}

impl Table {
    /// F(t) = sin 2πt.
    pub fn sine() -> Table {
        Table {
            name: "sine".into(),
            shape: Shape::Sine,
            d: None,
            accel_bound: 4.0 * PI * PI,
            range: (-1.0, 1.0),
            max_degree: 0,
        }
    }

    /// The paper's F_D, D in [0, 1]: t̂(t̂ − ½)(D t̂ − 1) on [0, ½) and
    /// (t̂ − ½)(t̂ − 1)(D t̂ + 1 − D) on [½, 1).
    pub fn fd(d: f64) -> Result<Table, EngineError> {
        if !(0.0..=1.0).contains(&d) {
            return Err(EngineError::InvalidParameter {
                name: "D",
                value: d.to_string(),
                range: "[0, 1]",
            });
        }
        let lin = |a: f64, b: f64| Poly::new(&[a, b]);
        // First piece, s = t̂: s (s − ½)(D s − 1).
        let p0 = lin(0.0, 1.0).mul(&lin(-0.5, 1.0)).mul(&lin(-1.0, d));
        // Second piece, s = t̂ − ½: s (s − ½)(D s + D/2 + 1 − D).
        let p1 = lin(0.0, 1.0)
            .mul(&lin(-0.5, 1.0))
            .mul(&lin(1.0 - 0.5 * d, d));
        let name = if d == 0.0 {
            "fd:0".to_string()
        } else {
            format!("fd:{d}")
        };
        let pieces = vec![Piece::new(0.0, 0.5, p0), Piece::new(0.5, 1.0, p1)];
        Ok(Table {
            name,
            accel_bound: accel_bound(&pieces),
            range: piece_range(&pieces),
            max_degree: max_degree(&pieces),
            shape: Shape::Piecewise(pieces),
            d: Some(d),
        })
    }

    /// A piecewise-polynomial table from TOML text. `origin` names the file in errors.
    ///
    /// ```toml
    /// name = "my table"
    /// [[piece]]
    /// start = 0.0
    /// coeffs = [0.0, 0.5, -1.0]   # ascending powers of the phase t̂
    /// [[piece]]
    /// start = 0.5
    /// coeffs = [0.5, -1.5, 1.0]
    /// ```
    pub fn from_toml(text: &str, origin: &str) -> Result<Table, EngineError> {
        let bad = |msg: String| EngineError::TableFile {
            file: origin.to_string(),
            message: msg,
        };
        let file: TableFile = toml::from_str(text)
            .map_err(|e| bad(e.message().replace('\n', " ").trim().to_string()))?;
        if file.piece.is_empty() {
            return Err(bad("no [[piece]] given (need at least one)".into()));
        }
        let mut prev = -1.0;
        for (i, p) in file.piece.iter().enumerate() {
            if !(0.0..1.0).contains(&p.start) || !p.start.is_finite() {
                return Err(bad(format!(
                    "piece {} starts at {}, outside [0, 1)",
                    i + 1,
                    p.start
                )));
            }
            if i == 0 && p.start != 0.0 {
                return Err(bad(format!(
                    "the first piece must start at 0, not {}",
                    p.start
                )));
            }
            if p.start <= prev {
                return Err(bad(format!(
                    "piece starts must increase: piece {} starts at {} after {}",
                    i + 1,
                    p.start,
                    prev
                )));
            }
            prev = p.start;
            if p.coeffs.is_empty() || p.coeffs.len() > MAX_TABLE_DEGREE + 1 {
                return Err(bad(format!(
                    "piece {} has {} coefficients; allowed 1 to {} (degree up to {})",
                    i + 1,
                    p.coeffs.len(),
                    MAX_TABLE_DEGREE + 1,
                    MAX_TABLE_DEGREE
                )));
            }
            if let Some(c) = p.coeffs.iter().find(|c| !c.is_finite()) {
                return Err(bad(format!(
                    "piece {} has a non-finite coefficient {c}",
                    i + 1
                )));
            }
        }
        let n = file.piece.len();
        let pieces: Vec<Piece> = (0..n)
            .map(|i| {
                let start = file.piece[i].start;
                let end = if i + 1 < n {
                    file.piece[i + 1].start
                } else {
                    1.0
                };
                Piece::new(start, end, Poly::new(&file.piece[i].coeffs).shift(start))
            })
            .collect();
        // Continuity and C¹ at every breakpoint, including the wrap from 1 back to 0.
        for i in 0..n {
            let left = &pieces[i];
            let right = &pieces[(i + 1) % n];
            let at = if i + 1 < n { right.start } else { 0.0 };
            for (order, (pl, pr)) in [(&left.f, &right.f), (&left.d1, &right.d1)]
                .into_iter()
                .enumerate()
            {
                let jump = pr.eval(0.0) - pl.eval(left.len());
                if jump.abs() > C1_TOLERANCE || !jump.is_finite() {
                    let what = if order == 0 {
                        "F (continuity)"
                    } else {
                        "F' (C¹)"
                    };
                    let place = if i + 1 < n {
                        format!("breakpoint t̂ = {at}")
                    } else {
                        "the wrap from t̂ = 1 to t̂ = 0 (periodicity)".to_string()
                    };
                    return Err(bad(format!(
                        "not C¹ at {place}: derivative order {order} ({what}) jumps by {jump:.3e} (tolerance {C1_TOLERANCE:e})"
                    )));
                }
            }
        }
        Ok(Table {
            name: file.name.unwrap_or_else(|| origin.to_string()),
            accel_bound: accel_bound(&pieces),
            range: piece_range(&pieces),
            max_degree: max_degree(&pieces),
            shape: Shape::Piecewise(pieces),
            d: None,
        })
    }

    /// Display name (`sine`, `fd:0.1`, or the file's name).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The shape.
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// D if this is the paper's F_D.
    pub fn d(&self) -> Option<f64> {
        self.d
    }

    /// The pieces of a piecewise table (empty for the sine).
    pub fn pieces(&self) -> &[Piece] {
        match &self.shape {
            Shape::Sine => &[],
            Shape::Piecewise(p) => p,
        }
    }

    /// Index of the piece containing `phase` in [0, 1) (pieces are closed on the left).
    #[inline]
    pub fn piece_index(&self, phase: f64) -> usize {
        let pieces = self.pieces();
        let mut i = pieces.len().saturating_sub(1);
        while i > 0 && phase < pieces[i].start {
            i -= 1;
        }
        i
    }

    /// F, F', F'', F''' at `phase` in [0, 1) (right derivatives at breakpoints).
    #[inline]
    pub fn jet(&self, phase: f64) -> [f64; 4] {
        match &self.shape {
            Shape::Sine => {
                let w = 2.0 * PI;
                let (s, c) = (w * phase).sin_cos();
                [s, w * c, -w * w * s, -w * w * w * c]
            }
            Shape::Piecewise(pieces) => {
                let p = &pieces[self.piece_index(phase)];
                let s = phase - p.start;
                [p.f.eval(s), p.d1.eval(s), p.d2.eval(s), p.d3.eval(s)]
            }
        }
    }

    /// The `order`-th derivative of F (0 to 3) at `phase`, alone (cheaper than [`Self::jet`]).
    #[inline]
    pub fn derivative(&self, phase: f64, order: usize) -> f64 {
        match &self.shape {
            Shape::Sine => {
                let w = 2.0 * PI;
                let x = w * phase;
                match order {
                    0 => x.sin(),
                    1 => w * x.cos(),
                    2 => -w * w * x.sin(),
                    _ => -w * w * w * x.cos(),
                }
            }
            Shape::Piecewise(pieces) => {
                let p = &pieces[self.piece_index(phase)];
                let s = phase - p.start;
                match order {
                    0 => p.f.eval(s),
                    1 => p.d1.eval(s),
                    2 => p.d2.eval(s),
                    _ => p.d3.eval(s),
                }
            }
        }
    }

    /// F at `phase`.
    #[inline]
    pub fn value(&self, phase: f64) -> f64 {
        self.derivative(phase, 0)
    }

    /// Rigorous bounds (min, max) of F over a period.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }

    /// An upper bound of |F''| over a period (rigorous, padded).
    pub fn accel_bound(&self) -> f64 {
        self.accel_bound
    }

    /// Highest polynomial degree among the pieces (0 for the sine, which has none).
    pub fn max_degree(&self) -> usize {
        self.max_degree
    }

    /// Phases where F is not C² (piece starts), for plots and release search.
    pub fn breakpoints(&self) -> Vec<f64> {
        self.pieces().iter().map(|p| p.start).collect()
    }
}

/// Bounds (min, max) of F over all pieces.
fn max_degree(pieces: &[Piece]) -> usize {
    pieces.iter().map(|p| p.f.degree()).max().unwrap_or(0)
}

fn piece_range(pieces: &[Piece]) -> (f64, f64) {
    pieces
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, q| {
            (a.0.min(q.min), a.1.max(q.max))
        })
}

/// Max |F''| over the pieces: endpoints and the critical points of F''.
fn accel_bound(pieces: &[Piece]) -> f64 {
    let mut m: f64 = 0.0;
    for p in pieces {
        m = m.max(p.d2.eval(0.0).abs()).max(p.d2.eval(p.len()).abs());
        for &c in p.d3.roots_in(0.0, p.len()).as_slice() {
            m = m.max(p.d2.eval(c).abs());
        }
    }
    m * (1.0 + 1e-12) + 1e-12
}

impl fmt::Display for Table {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_closed_form(d: f64, t: f64) -> f64 {
        if t < 0.5 {
            t * (t - 0.5) * (d * t - 1.0)
        } else {
            (t - 0.5) * (t - 1.0) * (d * t + 1.0 - d)
        }
    }

    #[test]
    fn fd_matches_paper_formula() {
        for d in [0.0, 0.1, 0.5, 1.0] {
            let t = Table::fd(d).unwrap();
            for i in 0..100 {
                let x = i as f64 / 100.0;
                assert!((t.value(x) - fd_closed_form(d, x)).abs() < 1e-15);
            }
            // Paper, Appendix C: F'' = 6 D t̂ − (2 + D) on the first piece.
            let j = t.jet(0.2);
            assert!((j[2] - (6.0 * d * 0.2 - (2.0 + d))).abs() < 1e-14);
            assert!((j[3] - 6.0 * d).abs() < 1e-14);
        }
    }

    #[test]
    fn fd_is_c1_and_periodic() {
        let t = Table::fd(0.3).unwrap();
        let left = t.pieces()[0].d1.eval(0.5);
        assert!((left - t.jet(0.5)[1]).abs() < 1e-15);
        let wrap = t.pieces()[1].d1.eval(0.5);
        assert!((wrap - t.jet(0.0)[1]).abs() < 1e-15);
    }

    #[test]
    fn spec_parsing() {
        assert!(matches!(
            TableSpec::parse("sine"),
            Ok(TableSpec::Builtin(_))
        ));
        assert!(matches!(
            TableSpec::parse("fd:0.25"),
            Ok(TableSpec::Builtin(t)) if t.d() == Some(0.25)
        ));
        assert!(TableSpec::parse("fd:1.5").is_err());
        assert!(TableSpec::parse("fd:x").is_err());
        assert!(TableSpec::parse("square").is_err());
        assert!(matches!(
            TableSpec::parse("a/b.toml"),
            Ok(TableSpec::File(_))
        ));
    }

    #[test]
    fn toml_rejects_a_kink_naming_the_breakpoint() {
        let text = "[[piece]]\nstart = 0.0\ncoeffs = [0.0, 1.0]\n[[piece]]\nstart = 0.5\ncoeffs = [1.0, -1.0]\n";
        let e = Table::from_toml(text, "kink.toml").unwrap_err().to_string();
        assert!(e.contains("t̂ = 0.5") && e.contains("order 1"), "{e}");
    }
}
