//! Table shapes F(t̂): the sine, the paper's piecewise-polynomial F_D, and piecewise
//! polynomials given by their pieces (the binary reads them from files).
//!
//! A table is periodic with period 1 and C¹. The displacement is f(t) = α F(t); α is not
//! part of the shape (see [`crate::System`]). Piecewise tables store each piece in its
//! local variable s = t̂ − start, which keeps the coefficients small and the root
//! isolation accurate.
//!
//! Everything that depends on the formula of F goes through [`Segment`], one smooth
//! stretch of the table (a polynomial piece, or the sine over its whole period), whose
//! methods match the formula exhaustively: the rest of the engine iterates segments and
//! never asks which shape it has, except the next-impact solvers, which have one exact
//! solver per shape.

pub(crate) mod release;
mod segment;

pub mod builtin;
pub mod expr;
pub mod family;

pub use family::{Family, Param, PieceIn, Variable};
pub use segment::{Formula, Segment, TAYLOR_TERMS};

use crate::error::EngineError;
use crate::limits;
use crate::poly::{Poly, MAX_COEFFS};
use std::f64::consts::PI;
use std::fmt;
use std::sync::Arc;

/// Tolerance for the periodicity, continuity and C¹ checks of a piecewise table.
pub const C1_TOLERANCE: f64 = 1e-9;

/// Largest size of F, F' or F'' on a piece (a crude bound from the coefficients)
/// for which their extrema are computed reliably in f64.
pub const MAX_COEFFICIENT_SIZE: f64 = 1e100;

/// Highest polynomial degree accepted for a piece.
pub const MAX_TABLE_DEGREE: usize = MAX_COEFFS - 2;

/// One polynomial piece of a periodic table, on `[start, end)` in phase.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Phase where the piece starts.
    pub start: f64,
    /// Phase where the piece ends (the next piece's start, or 1).
    pub end: f64,
    /// F on the piece as a polynomial in s = t̂ − start.
    pub(crate) f: Poly,
    /// F', F'', F''' in the same variable.
    pub(crate) d1: Poly,
    pub(crate) d2: Poly,
    pub(crate) d3: Poly,
    /// Rigorous bounds of F on the closed piece (padded by a few ulps).
    pub(crate) min: f64,
    pub(crate) max: f64,
}

impl Piece {
    /// The degree of F on the piece.
    pub fn degree(&self) -> usize {
        self.f.degree()
    }
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

/// Which member of which family a table is.
#[derive(Clone, Debug, PartialEq)]
struct Member {
    family: Arc<Family>,
    /// One value per parameter of the family, in its order.
    values: Vec<f64>,
}

/// A named table shape F(t̂).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    name: String,
    shape: Shape,
    /// The family and parameter values it was built from (every table but one given
    /// by its pieces alone).
    member: Option<Member>,
    /// Upper bounds of |F'| and |F''| over a period.
    velocity_bound: f64,
    accel_bound: f64,
    /// Rigorous bounds (min, max) of F over a period.
    range: (f64, f64),
    /// Highest polynomial degree among the pieces (0 for the sine, which has none).
    max_degree: usize,
}

impl Table {
    /// F(t) = sin 2πt.
    pub fn sine() -> Table {
        Table {
            name: "sine".into(),
            shape: Shape::Sine,
            member: Some(Member {
                family: Arc::clone(Family::sine()),
                values: Vec::new(),
            }),
            velocity_bound: 2.0 * PI,
            accel_bound: 4.0 * PI * PI,
            range: (-1.0, 1.0),
            max_degree: 0,
        }
    }

    /// The paper's F_D, D in [0, 1]: t̂(t̂ − ½)(D t̂ − 1) on [0, ½) and
    /// (t̂ − ½)(t̂ − 1)(D t̂ + 1 − D) on [½, 1); the member D of [`Family::fd`].
    pub fn fd(d: f64) -> Result<Table, EngineError> {
        limits::D.check(d)?;
        Family::member(Family::fd(), &[d])
    }

    /// A piecewise-polynomial table from its pieces: (start phase, coefficients in
    /// ascending powers of the phase t̂). The first piece starts at 0, starts increase,
    /// each piece runs to the next start (the last to 1), degrees are at most
    /// [`MAX_TABLE_DEGREE`], and the table must be continuous and C¹ at every breakpoint
    /// and across the wrap from 1 to 0 (within [`C1_TOLERANCE`]). Refusals name the
    /// piece or the breakpoint.
    pub fn piecewise(name: &str, pieces: &[(f64, Vec<f64>)]) -> Result<Table, EngineError> {
        let built = checked_pieces(pieces, Variable::Phase)?;
        Ok(Table::from_pieces(name.to_string(), built))
    }

    /// The member of this table's family with parameter `name` (exactly as spelled,
    /// else ignoring case) set to `value` and the others kept; refused if the table has
    /// no such parameter, or the value is out of its range or makes no valid table.
    pub fn with_param(&self, name: &str, value: f64) -> Result<Table, EngineError> {
        let (member, i) = self.member_param(name)?;
        let mut values = member.values.clone();
        values[i] = value;
        Family::member(&member.family, &values)
    }

    /// The declaration of parameter `name` (exactly as spelled, else ignoring case) in
    /// the table's family; refused, naming the parameters there are, if it has none.
    pub fn family_param(&self, name: &str) -> Result<&Param, EngineError> {
        let (member, i) = self.member_param(name)?;
        Ok(&member.family.params()[i])
    }

    /// The table's family membership and the index of parameter `name` in it.
    fn member_param(&self, name: &str) -> Result<(&Member, usize), EngineError> {
        let refuse = || {
            let names = self
                .member
                .as_ref()
                .map_or("none".to_string(), |m| m.family.param_names());
            EngineError::Inconsistent(format!(
                "table {} has no parameter '{}': its parameters are {names}",
                self.name,
                crate::error::short_text(name)
            ))
        };
        let member = self.member.as_ref().ok_or_else(refuse)?;
        let i = member.family.param_index(name).ok_or_else(refuse)?;
        Ok((member, i))
    }

    /// The value of parameter `name` (exactly as spelled, else ignoring case), if the
    /// table's family has it.
    pub fn param(&self, name: &str) -> Option<f64> {
        let m = self.member.as_ref()?;
        m.family.param_index(name).map(|i| m.values[i])
    }

    /// Its name with parameter `name` left free, as a caption names a sweep or plane
    /// over it (`fd:D`, `asym (w, h = 0.3)`); its own name if it has no such parameter.
    pub fn name_with_free(&self, name: &str) -> String {
        match &self.member {
            Some(m) => match m.family.param_index(name) {
                Some(i) => m.family.member_name_free(&m.values, i),
                None => self.name.clone(),
            },
            None => self.name.clone(),
        }
    }

    /// The family it is a member of, and the values of the family's parameters (None
    /// for a table given by its pieces alone).
    pub fn family(&self) -> Option<(&Arc<Family>, &[f64])> {
        self.member
            .as_ref()
            .map(|m| (&m.family, m.values.as_slice()))
    }

    /// The table run backward in time: (G, c) with G(τ) = F(c − τ) for every τ. A
    /// ball's flight followed backward from t is a forward flight on G from τ = c − t
    /// (the inverse map's solver). The sine is its own reversal shifted by half a period
    /// (sin 2π(½ − τ) = sin 2πτ), so c = ½; a piecewise table's reversal has the pieces
    /// in reverse order, each p(s) becoming p(L − s) on a piece of length L, and c = 0.
    pub(crate) fn reversed(&self) -> (Table, f64) {
        match &self.shape {
            Shape::Sine => (self.clone(), 0.5),
            Shape::Piecewise(pieces) => {
                let rev = pieces
                    .iter()
                    .rev()
                    .map(|p| {
                        // q(s) = p(L − s): shift by L, then negate the odd powers.
                        let shifted = p.f.shift(p.len());
                        let c: Vec<f64> = shifted
                            .coeffs()
                            .iter()
                            .enumerate()
                            .map(|(i, &a)| if i % 2 == 1 { -a } else { a })
                            .collect();
                        let start = if p.end >= 1.0 { 0.0 } else { 1.0 - p.end };
                        Piece::new(start, 1.0 - p.start, Poly::new(&c))
                    })
                    .collect();
                (
                    Table::from_pieces(format!("{} reversed", self.name), rev),
                    0.0,
                )
            }
        }
    }

    fn from_pieces(name: String, pieces: Vec<Piece>) -> Table {
        let range = pieces
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, q| {
                (a.0.min(q.min), a.1.max(q.max))
            });
        Table {
            name,
            velocity_bound: derivative_bound(&pieces, |p| (&p.d1, &p.d2)),
            accel_bound: derivative_bound(&pieces, |p| (&p.d2, &p.d3)),
            range,
            max_degree: pieces.iter().map(|p| p.f.degree()).max().unwrap_or(0),
            shape: Shape::Piecewise(pieces),
            member: None,
        }
    }

    /// Display name (`sine`, `fd:0.1`, or the name given to a piecewise table).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The shape (for the next-impact solvers, which have one exact solver per shape).
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// D if this is a member of the paper's F_D.
    pub fn d(&self) -> Option<f64> {
        let m = self.member.as_ref()?;
        Arc::ptr_eq(&m.family, Family::fd()).then(|| m.values[0])
    }

    /// The pieces of a piecewise table (empty for the sine).
    pub fn pieces(&self) -> &[Piece] {
        match &self.shape {
            Shape::Sine => &[],
            Shape::Piecewise(p) => p,
        }
    }

    /// The smooth segments in phase order: the pieces, or the sine's one period.
    pub fn segments(&self) -> impl Iterator<Item = Segment<'_>> {
        let sine = matches!(self.shape, Shape::Sine).then(Segment::sine);
        sine.into_iter()
            .chain(self.pieces().iter().map(Segment::piece))
    }

    /// The number of smooth segments.
    pub fn segment_count(&self) -> usize {
        self.pieces().len().max(1)
    }

    /// The segment with index `i` (< [`Self::segment_count`]).
    pub fn segment(&self, i: usize) -> Segment<'_> {
        match &self.shape {
            Shape::Sine => Segment::sine(),
            Shape::Piecewise(p) => Segment::piece(&p[i]),
        }
    }

    /// Index of the segment containing `phase` in [0, 1) (closed on the left).
    #[inline]
    pub fn segment_index(&self, phase: f64) -> usize {
        let pieces = self.pieces();
        let mut i = pieces.len().saturating_sub(1);
        while i > 0 && phase < pieces[i].start {
            i -= 1;
        }
        i
    }

    /// The indices of the segments on either side of the breakpoint `bp`: the one
    /// ending there (for the breakpoint 0, the last, ending at 1) and the one starting
    /// there.
    pub fn segments_around(&self, bp: f64) -> (usize, usize) {
        let after = self.segment_index(bp);
        let count = self.segment_count();
        ((after + count - 1) % count, after)
    }

    /// The segment containing `phase` in [0, 1).
    pub fn segment_at(&self, phase: f64) -> Segment<'_> {
        self.segment(self.segment_index(phase))
    }

    /// F, F', F'', F''' at `phase` in [0, 1) (right derivatives at breakpoints).
    #[inline]
    pub fn jet(&self, phase: f64) -> [f64; 4] {
        self.segment_at(phase).jet(phase)
    }

    /// The `order`-th derivative of F (0 to 3) at `phase`, alone (cheaper than [`Self::jet`]).
    #[inline]
    pub fn derivative(&self, phase: f64, order: usize) -> f64 {
        self.segment_at(phase).derivative(phase, order)
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

    /// An upper bound of |F'| over a period (rigorous, padded).
    pub fn velocity_bound(&self) -> f64 {
        self.velocity_bound
    }

    /// An upper bound of |F⁽ⁿ⁾| over a period (0 for pieces of degree below n); meant
    /// for n ≥ 3, where [`Self::accel_bound`] does not apply.
    pub fn derivative_bound(&self, n: usize) -> f64 {
        self.segments()
            .map(|s| s.derivative_bound(n))
            .fold(0.0, f64::max)
    }

    /// Highest polynomial degree among the pieces (0 for the sine, which has none).
    pub fn max_degree(&self) -> usize {
        self.max_degree
    }

    /// Phases where F may fail to be C² (piece starts), for plots and release search.
    pub fn breakpoints(&self) -> Vec<f64> {
        self.pieces().iter().map(|p| p.start).collect()
    }

    /// The first breakpoint after `phase` (at most 1, where the last piece ends), or
    /// infinity if F is smooth everywhere (the sine).
    pub fn smooth_until(&self, phase: f64) -> f64 {
        self.segment_at(phase).breaks_at()
    }

    /// The first instant from (period, phase) on after which α F'' < −1 (the table
    /// accelerates downward faster than gravity, so a ball riding on it is released),
    /// or None if there is none: the ball then rests on the table for good. With
    /// `strictly_after`, an instant equal to the start does not count.
    pub fn release_after(
        &self,
        alpha: f64,
        period: i64,
        phase: f64,
        strictly_after: bool,
    ) -> Option<(i64, f64)> {
        let j0 = self.segment_index(phase);
        release::first_release(
            self.segment_count(),
            j0,
            &phase,
            strictly_after,
            |j, from, strict| {
                let seg = self.segment(j);
                seg.release(alpha, from.copied().unwrap_or(seg.start), strict)
            },
        )
        .map(|(periods, at)| crate::time::normalize(period.saturating_add(periods), at))
    }
}

/// The pieces of a piecewise table from (start, coefficients in `variable`), checked
/// as [`Table::piecewise`] states.
fn checked_pieces(
    pieces: &[(f64, Vec<f64>)],
    variable: Variable,
) -> Result<Vec<Piece>, EngineError> {
    let local = |start: f64, coeffs: &[f64]| match variable {
        Variable::Phase => Poly::new(coeffs).shift(start),
        Variable::Local => Poly::new(coeffs),
    };
    let bad = |msg: String| EngineError::InvalidTable(msg);
    if pieces.is_empty() {
        return Err(bad("no [[piece]] given (need at least one)".into()));
    }
    let mut prev = -1.0;
    for (i, (start, coeffs)) in pieces.iter().enumerate() {
        let start = *start;
        if !(0.0..1.0).contains(&start) || !start.is_finite() {
            return Err(bad(format!(
                "piece {} starts at {}, outside [0, 1)",
                i + 1,
                crate::error::fmt_value(start)
            )));
        }
        if i == 0 && start != 0.0 {
            return Err(bad(format!("the first piece must start at 0, not {start}")));
        }
        if start <= prev {
            return Err(bad(format!(
                "piece starts must increase: piece {} starts at {start} after {prev}",
                i + 1
            )));
        }
        prev = start;
        if coeffs.is_empty() || coeffs.len() > MAX_TABLE_DEGREE + 1 {
            return Err(bad(format!(
                "piece {} has {} coefficients; allowed 1 to {} (degree up to {})",
                i + 1,
                coeffs.len(),
                MAX_TABLE_DEGREE + 1,
                MAX_TABLE_DEGREE
            )));
        }
        if let Some(c) = coeffs.iter().find(|c| !c.is_finite()) {
            return Err(bad(format!(
                "piece {} has a non-finite coefficient {c}",
                i + 1
            )));
        }
    }
    let n = pieces.len();
    // Coefficients so large that the extrema of F, F', F'' cannot be computed in
    // f64 (products overflow) are refused here; the system checks the extrema.
    for (i, (start, coeffs)) in pieces.iter().enumerate() {
        let end = if i + 1 < n { pieces[i + 1].0 } else { 1.0 };
        let p = local(*start, coeffs);
        let (len, mut q) = (end - start, p);
        for order in 0..3 {
            // |q(s)| ≤ Σ |q_k| len^k on [0, len].
            let crude: f64 = q
                .coeffs()
                .iter()
                .enumerate()
                .map(|(k, c)| c.abs() * len.powi(k as i32))
                .sum();
            if crude.is_nan() || crude > MAX_COEFFICIENT_SIZE {
                return Err(bad(format!(
                    "piece {}: its derivative of order {order} reaches {} in size: valid at most {MAX_COEFFICIENT_SIZE:e}",
                    i + 1,
                    crate::error::fmt_value(crude)
                )));
            }
            q = q.derivative();
        }
    }
    let built: Vec<Piece> = (0..n)
        .map(|i| {
            let start = pieces[i].0;
            let end = if i + 1 < n { pieces[i + 1].0 } else { 1.0 };
            Piece::new(start, end, local(start, &pieces[i].1))
        })
        .collect();
    // Continuity and C¹ at every breakpoint, including the wrap from 1 back to 0.
    for i in 0..n {
        let left = &built[i];
        let right = &built[(i + 1) % n];
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
    Ok(built)
}

/// Max |G| over the pieces for a derivative G (given with its own derivative):
/// endpoints and the critical points of G, padded.
fn derivative_bound(pieces: &[Piece], of: impl Fn(&Piece) -> (&Poly, &Poly)) -> f64 {
    let mut m: f64 = 0.0;
    for p in pieces {
        let (g, dg) = of(p);
        m = m.max(g.eval(0.0).abs()).max(g.eval(p.len()).abs());
        for &c in dg.roots_in(0.0, p.len()).as_slice() {
            m = m.max(g.eval(c).abs());
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

    #[test]
    fn the_reversed_table_is_the_table_backward_in_time() {
        // G(τ) = F(c − τ) and G'(τ) = −F'(c − τ) at phases spread over a period, on both
        // sides of every breakpoint.
        for t in [
            Table::sine(),
            Table::fd(0.0).unwrap(),
            Table::fd(0.37).unwrap(),
            Table::fd(1.0).unwrap(),
        ] {
            let (g, c) = t.reversed();
            for i in 0..=200 {
                let tau = i as f64 / 200.0 * 0.999 + 0.0003;
                let back = (c - tau).rem_euclid(1.0);
                assert!(
                    (g.value(tau) - t.value(back)).abs() < 1e-14,
                    "{} at {tau}",
                    t.name()
                );
                assert!(
                    (g.derivative(tau, 1) + t.derivative(back, 1)).abs() < 1e-12,
                    "{} at {tau}",
                    t.name()
                );
            }
            // Reversed twice: H(σ) = G(c − σ) = F(σ) (c is the same both times).
            let (gg, c2) = g.reversed();
            assert_eq!(c, c2);
            for i in 0..50 {
                let tau = i as f64 / 50.0 + 0.001;
                assert!(
                    (gg.value(tau) - t.value(tau)).abs() < 1e-13,
                    "{} at {tau}",
                    t.name()
                );
            }
        }
    }

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
        assert!(Table::fd(1.5).is_err());
    }

    #[test]
    fn piecewise_rejects_a_kink_naming_the_breakpoint() {
        let e = Table::piecewise("kink", &[(0.0, vec![0.0, 1.0]), (0.5, vec![1.0, -1.0])])
            .unwrap_err()
            .to_string();
        assert!(e.contains("t̂ = 0.5") && e.contains("order 1"), "{e}");
    }

    #[test]
    fn quad_release_is_at_phase_zero() {
        // fd:0: f'' = −2α on [0, ½), +2α on [½, 1). With α = 0.6 the ball is released
        // where f'' jumps to −1.2 < −1, i.e. at every integer time.
        let t = Table::fd(0.0).unwrap();
        assert_eq!(t.release_after(0.6, 3, 0.7, false), Some((4, 0.0)));
        // Inside the downward-accelerating half the release is immediate.
        assert_eq!(t.release_after(0.6, 3, 0.2, false), Some((3, 0.2)));
        // With α = 0.4 (f'' ≥ −0.8) the ball is never released.
        assert_eq!(t.release_after(0.4, 0, 0.7, false), None);
    }

    #[test]
    fn sine_release_closed_form() {
        let alpha = 0.1;
        let t = Table::sine();
        let theta = (1.0 / (4.0 * PI * PI * alpha)).asin() / (2.0 * PI);
        let (n, ph) = t.release_after(alpha, 0, 0.6, false).unwrap();
        assert_eq!(n, 1);
        assert!((ph - theta).abs() < 1e-15);
        // −f''(θ) = 4π²α sin 2πθ = 1 exactly.
        assert!((alpha * t.jet(ph)[2] + 1.0).abs() < 1e-12);
        assert_eq!(t.smooth_until(0.3), f64::INFINITY);
        assert_eq!(Table::fd(0.1).unwrap().smooth_until(0.3), 0.5);
    }
}
