//! The system in interval arithmetic: α, r and the table's pieces as enclosures of the
//! exact values (each parameter the decimal it is written as and its double; a family's
//! coefficients evaluated from their expressions in [`Interval`]s), and the displacement
//! f = αF with its derivatives over a box of phases.
//!
//! [`Enclosed::jet`] is for an impact: the box must lie inside one piece, since f'' jumps
//! at a breakpoint. [`Enclosed::hull`] is for a stretch of a flight: f and f' over the
//! pieces the box meets (f is C¹, so the hull is an enclosure across a breakpoint too).

use crate::real::Interval;
use crate::system::System;
use crate::table::{PieceIn, Shape};

/// A table's shape in intervals.
#[derive(Clone, Debug)]
enum Form {
    /// F = sin 2πt.
    Sine,
    /// Pieces with their coefficients in the piece's own variable.
    Pieces(Vec<PieceIn<Interval>>),
}

/// α, r and the table, each as an enclosure of the exact value.
#[derive(Clone, Debug)]
pub(crate) struct Enclosed {
    form: Form,
    /// The amplitude.
    pub alpha: Interval,
    /// The restitution.
    pub r: Interval,
    /// An upper bound of |F''| over a period.
    second: f64,
}

/// A box of phases met a breakpoint (at about this phase).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AtBreakpoint(pub f64);

impl Enclosed {
    /// The system of `sys` with α, r and the table's parameters read as the decimals
    /// they are written as (and their doubles, [`Interval::written`]).
    pub fn of(sys: &System) -> Enclosed {
        let alpha = Interval::written(sys.alpha());
        let r = Interval::written(sys.r());
        let table = sys.table();
        let form = match table.shape() {
            Shape::Sine => Form::Sine,
            Shape::Piecewise(pieces) => {
                let from_family = table.family().and_then(|(family, values)| {
                    let vals: Vec<Interval> =
                        values.iter().map(|&x| Interval::written(x)).collect();
                    family.pieces_in(&vals, &())
                });
                Form::Pieces(from_family.unwrap_or_else(|| {
                    // A table given by its pieces alone: its doubles are the table.
                    pieces
                        .iter()
                        .map(|p| PieceIn {
                            start: Interval::point(p.start),
                            end: Interval::point(p.end),
                            coeffs: p.f.coeffs().iter().map(|&c| Interval::point(c)).collect(),
                        })
                        .collect()
                }))
            }
        };
        let second = match &form {
            Form::Sine => (Interval::pi() * Interval::point(2.0)).sqr().hi(),
            Form::Pieces(ps) => ps
                .iter()
                .map(|p| {
                    let whole =
                        Interval::new(0.0, (p.end - p.start).hi()).unwrap_or(Interval::ENTIRE);
                    derivative_at(&p.coeffs, 2, whole).mag()
                })
                .fold(0.0, f64::max),
        };
        Enclosed {
            second,
            form,
            alpha,
            r,
        }
    }

    /// The same system over the amplitudes `alpha`.
    pub fn with_alpha(mut self, alpha: Interval) -> Enclosed {
        self.alpha = alpha;
        self
    }

    /// An upper bound of |f''| over a period.
    pub fn accel_bound(&self) -> f64 {
        (self.alpha * Interval::point(self.second)).hi()
    }

    /// The piece the phase `x` (any real) lies in, as (whole periods, its index); None
    /// for the sine.
    pub fn piece_at(&self, x: f64) -> Option<(f64, usize)> {
        let Form::Pieces(ps) = &self.form else {
            return None;
        };
        let whole = x.floor();
        let q = x - whole;
        let i = ps.iter().rposition(|p| p.start.mid() <= q).unwrap_or(0);
        Some((whole, i))
    }

    /// The jet of piece `index` of the period starting at `whole`, continued as its
    /// polynomial to any phase box `x` (for a border collision: the near side's
    /// equations on both sides of the breakpoint).
    pub fn jet_on(&self, x: Interval, (whole, index): (f64, usize)) -> [Interval; 3] {
        match &self.form {
            Form::Sine => self.jet(x).expect("the sine has no breakpoints"),
            Form::Pieces(ps) => {
                let p = &ps[index];
                let s = x - Interval::point(whole) - p.start;
                [0, 1, 2].map(|d| self.alpha * derivative_at(&p.coeffs, d, s))
            }
        }
    }

    /// The start of piece `index` (a breakpoint) in the period starting at `whole`, and
    /// the end of the piece.
    pub fn piece_ends(&self, (whole, index): (f64, usize)) -> Option<(Interval, Interval)> {
        let Form::Pieces(ps) = &self.form else {
            return None;
        };
        let w = Interval::point(whole);
        Some((ps[index].start + w, ps[index].end + w))
    }

    /// (f, f', f'') over the phase box `x` (any real phases), which must lie strictly
    /// inside one piece.
    pub fn jet(&self, x: Interval) -> Result<[Interval; 3], AtBreakpoint> {
        match &self.form {
            Form::Sine => {
                let (s, c) = x.sin_cos_2pi();
                let w = Interval::pi() * Interval::point(2.0);
                Ok([
                    self.alpha * s,
                    self.alpha * w * c,
                    -(self.alpha * w.sqr() * s),
                ])
            }
            Form::Pieces(ps) => {
                let (whole, q) = reduce(x).ok_or(AtBreakpoint(x.mid()))?;
                let p = ps
                    .iter()
                    .find(|p| p.start.hi() < q.lo() && q.hi() < p.end.lo())
                    .ok_or(AtBreakpoint(whole + q.mid()))?;
                let s = q - p.start;
                Ok([0, 1, 2].map(|d| self.alpha * derivative_at(&p.coeffs, d, s)))
            }
        }
    }

    /// (f, f') over the phase box `x`, across breakpoints.
    pub fn hull(&self, x: Interval) -> [Interval; 2] {
        match &self.form {
            Form::Sine => {
                let [f, d, _] = self.jet(x).expect("the sine has no breakpoints");
                [f, d]
            }
            Form::Pieces(ps) => {
                let mut parts = Vec::with_capacity(2);
                match reduce(x) {
                    Some((_, q)) => parts.push(q),
                    None => {
                        // Across a whole period: the part before it and the part after.
                        let k = x.lo().floor();
                        let (Some(a), Some(b)) = (
                            Interval::new(x.lo(), k + 1.0),
                            Interval::new(k + 1.0, x.hi()),
                        ) else {
                            return [Interval::ENTIRE; 2];
                        };
                        match (reduce(a), reduce(b)) {
                            (Some((_, a)), Some((_, b))) => parts.extend([a, b]),
                            _ => return [Interval::ENTIRE; 2],
                        }
                    }
                }
                let mut out: Option<[Interval; 2]> = None;
                for q in parts {
                    for p in ps {
                        let lo = q.lo().max(p.start.lo());
                        let hi = q.hi().min(p.end.hi());
                        let Some(part) = Interval::new(lo, hi) else {
                            continue;
                        };
                        let s = part - p.start;
                        let v = [0, 1].map(|d| self.alpha * derivative_at(&p.coeffs, d, s));
                        out = Some(match out {
                            None => v,
                            Some(o) => [o[0].hull(&v[0]), o[1].hull(&v[1])],
                        });
                    }
                }
                out.unwrap_or([Interval::ENTIRE; 2])
            }
        }
    }
}

/// x as (whole periods, the phase box within [0, 1]); None where it spans more than
/// one period's start, or is too wide to reduce.
fn reduce(x: Interval) -> Option<(f64, Interval)> {
    if !x.lo().is_finite() || !x.hi().is_finite() {
        return None;
    }
    let k = x.lo().floor();
    if x.hi() > k + 1.0 {
        return None;
    }
    let q = x - Interval::point(k);
    Some((k, Interval::new(q.lo().max(0.0), q.hi().min(1.0))?))
}

/// The `d`-th derivative of Σ cᵢ sⁱ over the box s (Horner in intervals).
fn derivative_at(coeffs: &[Interval], d: usize, s: Interval) -> Interval {
    let mut acc = Interval::point(0.0);
    for (i, c) in coeffs.iter().enumerate().skip(d).rev() {
        let factor = ((i - d + 1)..=i).map(|j| j as f64).product::<f64>();
        acc = acc * s + *c * Interval::point(factor);
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    /// On F_D, the sine and a file-like table, the enclosures contain the double
    /// evaluation of f, f', f'' at random phases, and are narrow.
    #[test]
    fn jets_contain_the_tables_values() {
        let tables = [
            Table::sine(),
            Table::fd(0.5).unwrap(),
            Table::fd(0.1).unwrap(),
            Table::piecewise("p", &[(0.0, vec![0.0, 0.0, 1.0, -2.0, 1.0])]).unwrap(),
        ];
        let mut rng = crate::test_rng::Xorshift::new(11);
        for table in tables {
            let sys = System::new(table, 0.37, 0.8).unwrap();
            let e = Enclosed::of(&sys);
            for _ in 0..500 {
                let t = 3.0 * rng.next();
                let phase = crate::time::wrap_phase(t);
                if sys
                    .table()
                    .breakpoints()
                    .iter()
                    .any(|b| (b - phase).abs() < 1e-9)
                    || !(1e-9..=1.0 - 1e-9).contains(&phase)
                {
                    continue;
                }
                let jet = e.jet(Interval::point(t)).unwrap();
                let want = [sys.f(phase), sys.df(phase), sys.ddf(phase)];
                for (j, w) in jet.iter().zip(want) {
                    let slack = 1e-13 * (1.0 + w.abs());
                    assert!(
                        j.lo() - slack <= w && w <= j.hi() + slack && j.width() < 1e-12,
                        "{} at {t}: {j:?} against {w}",
                        sys.table().name()
                    );
                }
                let wide = Interval::new(t - 0.01, t + 0.01).unwrap();
                let [f, d] = e.hull(wide);
                assert!(f.contains(sys.f(phase)) && d.contains(sys.df(phase)));
            }
            // The bound of |f''| holds at every sampled phase.
            let sampled = (0..4000)
                .map(|i| sys.ddf(i as f64 / 4000.0).abs())
                .fold(0.0, f64::max);
            assert!(sampled <= e.accel_bound() && e.accel_bound() < 100.0 * sampled);
        }
    }

    #[test]
    fn a_box_on_a_breakpoint_is_refused() {
        let sys = System::new(Table::fd(0.5).unwrap(), 0.4, 0.8).unwrap();
        let e = Enclosed::of(&sys);
        let across = Interval::new(0.5 - 1e-12, 0.5 + 1e-12).unwrap();
        assert!(e.jet(across).is_err());
        assert!(e
            .jet(Interval::new(2.0 - 1e-12, 2.0 + 1e-12).unwrap())
            .is_err());
        let [f, _] = e.hull(Interval::new(0.9, 1.1).unwrap());
        assert!(f.contains(sys.f(0.95)) && f.contains(sys.f(0.05)));
    }
}
