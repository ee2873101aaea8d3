//! The exact solver on a piecewise polynomial table.
//!
//! On each piece the gap z(τ) − f(τ) is a polynomial in the piece's local variable; its
//! first real root is isolated exactly. The walk over pieces is written once,
//! [`piecewise_landing`], over a [`PieceGap`]: the gap polynomial on one piece, built
//! and searched either in general storage ([`Poly`], any degree the table allows) or in
//! fixed cubic storage ([`CubicGap`], for tables whose pieces are all of degree ≤ 3 such
//! as F_D). Both build the same gap polynomials (to rounding: the cubic one writes the
//! launch piece's Taylor coefficients out instead of shifting the piece) and search them
//! the same way; the cubic one only avoids the bookkeeping of variable-length
//! polynomials on the hot path. A unit test holds the two to the same contacts.
//!
//! Everything that depends only on the table and α is computed once per system
//! ([`Prepared`], built by `FlightSolver`): each piece's α-scaled gap coefficients, α
//! times its maximum (the skip bound), α times the table's range. A flight then does no
//! allocation and no dispatch: it proves the launch piece's quotient free of roots in a
//! few operations (or finds its root in closed form), skips the later pieces where the
//! ball's height at both ends is above the piece's maximum (and whole periods where it is
//! above the table's top), and isolates one cubic root on the piece where the ball lands.

use super::{crossing_times, landing_on, FlightError, Landing, Launch, MAX_FLIGHT_PIECES};
use crate::exact_sum::{ball_at, flight_time};
use crate::poly::{
    first_root_cubic_from, first_root_low_degree, root_after_maximum, root_before_minimum,
    root_falling_from_zero, Poly, MAX_COEFFS,
};
use crate::system::System;
use crate::table::Piece;
use crate::time::floor;
use std::fmt::Debug;

/// A piecewise table prepared for one α: its pieces in the form one [`PieceGap`]
/// searches, and α times the table's range.
#[derive(Clone, Debug)]
pub(super) struct Prepared<P> {
    pieces: Vec<P>,
    /// The pieces' start phases, apart for a compact search.
    starts: Vec<f64>,
    alpha: f64,
    /// α times the table's rigorous bounds (min, max).
    bottom: f64,
    top: f64,
}

impl<P: AsRef<Span>> Prepared<P> {
    /// Prepare `sys`'s pieces (its table must be piecewise) for the search `G`.
    pub(super) fn new<G: PieceGap<Piece = P>>(sys: &System) -> Prepared<P> {
        let alpha = sys.alpha();
        let (lo, hi) = sys.table().range();
        Prepared {
            pieces: sys
                .table()
                .pieces()
                .iter()
                .map(|p| G::prepare(p, alpha))
                .collect(),
            starts: sys.table().pieces().iter().map(|p| p.start).collect(),
            alpha,
            bottom: alpha * lo,
            top: alpha * hi,
        }
    }

    /// Index of the piece containing `phase` in [0, 1) (closed on the left), as
    /// [`crate::table::Table::segment_index`].
    #[inline]
    fn index(&self, phase: f64) -> usize {
        let starts = &self.starts[..];
        // Two pieces (F_D and every table of that shape): one comparison.
        if let [_, second] = starts {
            return usize::from(*second <= phase);
        }
        let mut i = 0;
        while i + 1 < starts.len() && starts[i + 1] <= phase {
            i += 1;
        }
        i
    }
}

/// Below this value of τ(|v| + τ), the ball's height at a later piece's start is taken
/// from the plain f64 evaluation z0 + τ(v − τ/2) the skip test computes anyway, and its
/// velocity as v − τ: their rounding errors are then at most u(|z0| + 5τ(|v| + τ)) and
/// 2uτ (u = 2⁻⁵³), the size of the rounding the root search makes in evaluating the gap
/// on the piece. Beyond it (long flights, where v τ and τ²/2 cancel to a small height)
/// they are computed in double-double, rounded once ([`ball_at`]).
const SHORT_FLIGHT: f64 = 2.0;

/// Where a piece lies in phase, and α times its rigorous maximum (the skip bound).
#[derive(Clone, Copy, Debug)]
pub(super) struct Span {
    start: f64,
    end: f64,
    top: f64,
}

impl Span {
    fn of(piece: &Piece, alpha: f64) -> Span {
        Span {
            start: piece.start,
            end: piece.end,
            top: alpha * piece.max,
        }
    }
}

/// A contact found on a piece: the local variable s at contact and the gap's slope there
/// (the relative velocity of the ball).
pub(super) struct Hit {
    s: f64,
    slope: f64,
}

/// The gap polynomial on one table piece.
pub(super) trait PieceGap: Sized {
    /// A table piece with what this search precomputes for it.
    type Piece: Clone + Debug + AsRef<Span>;

    /// The piece prepared for amplitude `alpha`.
    fn prepare(piece: &Piece, alpha: f64) -> Self::Piece;

    /// The search on the launch piece, whose local variable is the flight time τ:
    /// gap(τ) = h + w τ − τ²/2 − α (Q(τ) − Q(0) − Q'(0) τ) with Q = F shifted to the
    /// launch phase (`off` into the piece). Returns the first contact in (0, `len`] and
    /// Q(0), the table's height at launch over α.
    fn launch_piece(
        piece: &Self::Piece,
        alpha: f64,
        off: f64,
        len: f64,
        launch: &Launch,
    ) -> Result<(Option<Hit>, f64), FlightError>;

    /// The gap zb + vb s − s²/2 − α F(s) on a later piece, the ball at height `zb` with
    /// velocity `vb` at the piece's start.
    fn later_piece(piece: &Self::Piece, zb: f64, vb: f64) -> Self;

    /// Value at s = 0 and the rounding bound of that value (one term, exactly c0).
    fn at_start(&self) -> (f64, f64);

    /// The first root on `piece` (s in [0, its length]); the value at 0 is positive
    /// beyond its rounding bound.
    fn first_root(&self, piece: &Self::Piece) -> Option<f64>;

    /// The slope at s.
    fn slope(&self, s: f64) -> f64;

    /// The table's velocity α F'(s) on `piece` (in its local variable).
    fn table_velocity(piece: &Self::Piece, s: f64) -> f64;
}

/// A piece for the general search: its polynomials, and the α-scaled gap template of a
/// later piece (every coefficient but the two that depend on the ball).
#[derive(Clone, Debug)]
pub(super) struct GeneralPiece {
    span: Span,
    f: Poly,
    d1: Poly,
    alpha: f64,
    /// α f₀ and α f₁.
    af0: f64,
    af1: f64,
    /// −½ − α f₂, −α f₃, … (entries 0 and 1 unused), and the number of coefficients.
    gap: [f64; MAX_COEFFS],
    gap_len: usize,
}

impl AsRef<Span> for GeneralPiece {
    fn as_ref(&self) -> &Span {
        &self.span
    }
}

impl PieceGap for Poly {
    type Piece = GeneralPiece;

    fn prepare(piece: &Piece, alpha: f64) -> GeneralPiece {
        let f = piece.f;
        let fc = f.coeffs();
        let mut gap = [0.0; MAX_COEFFS];
        for k in 3..fc.len() {
            gap[k] = -alpha * fc[k];
        }
        gap[2] = -0.5 - alpha * f.coeff(2);
        let gap_len = fc.len().max(3);
        GeneralPiece {
            span: Span::of(piece, alpha),
            f,
            d1: piece.d1,
            alpha,
            af0: alpha * f.coeff(0),
            af1: alpha * f.coeff(1),
            gap,
            gap_len,
        }
    }

    fn launch_piece(
        piece: &GeneralPiece,
        alpha: f64,
        off: f64,
        len: f64,
        launch: &Launch,
    ) -> Result<(Option<Hit>, f64), FlightError> {
        general_launch_piece(&piece.f, alpha, off, len, launch)
    }

    fn later_piece(piece: &GeneralPiece, zb: f64, vb: f64) -> Self {
        let mut c = piece.gap;
        c[0] = zb - piece.af0;
        c[1] = vb - piece.af1;
        Poly::from_array(c, piece.gap_len)
    }

    fn at_start(&self) -> (f64, f64) {
        let g0 = self.coeff(0);
        (
            g0,
            (4 * self.coeffs().len()) as f64 * f64::EPSILON * g0.abs(),
        )
    }

    fn first_root(&self, piece: &GeneralPiece) -> Option<f64> {
        Poly::first_root(self, 0.0, piece.span.end - piece.span.start)
    }

    fn slope(&self, s: f64) -> f64 {
        self.eval_d(s).1
    }

    fn table_velocity(piece: &GeneralPiece, s: f64) -> f64 {
        piece.alpha * piece.d1.eval(s)
    }
}

/// The launch-piece search in general storage (see [`PieceGap::launch_piece`]) on the
/// piece whose table polynomial is `f`.
fn general_launch_piece(
    f: &Poly,
    alpha: f64,
    off: f64,
    len: f64,
    launch: &Launch,
) -> Result<(Option<Hit>, f64), FlightError> {
    let q = f.shift(off);
    let gap = gap_with_low_terms(&q, alpha, launch.height, launch.w);
    let search = if launch.height > 0.0 {
        gap
    } else {
        lift_off_quotient(&gap, launch.w)?
    };
    let hit = first_positive_root(&search, len).map(|s| Hit {
        s,
        slope: gap.eval_d(s).1,
    });
    Ok((hit, q.coeff(0)))
}

/// The gap c0 + c1 s − s²/2 − α (f₂ s² + f₃ s³ + …) on a piece whose table polynomial
/// (in the same variable) is `f`: its two lowest coefficients are given, the others
/// come from the ball's fall and the table.
fn gap_with_low_terms(f: &Poly, alpha: f64, c0: f64, c1: f64) -> Poly {
    let fc = f.coeffs();
    let mut c = [0.0; MAX_COEFFS];
    for k in 3..fc.len() {
        c[k] = -alpha * fc[k];
    }
    c[0] = c0;
    c[1] = c1;
    c[2] = -0.5 - alpha * f.coeff(2);
    Poly::from_array(c, fc.len().max(3))
}

/// The gap on a piece of degree ≤ 3, in fixed storage: ascending coefficients and their
/// number without trailing zeros.
#[derive(Clone, Copy, Debug)]
pub(super) struct CubicGap {
    c: [f64; 4],
    len: usize,
}

impl CubicGap {
    #[inline]
    fn new(c: [f64; 4]) -> CubicGap {
        let mut len = 4;
        while len > 0 && c[len - 1] == 0.0 {
            len -= 1;
        }
        CubicGap { c, len }
    }
}

/// A piece of degree ≤ 3 for the fixed-size search: F's coefficients (in general storage
/// too, for the rare launches that take the general route) and the α-scaled ones of a
/// later piece's gap [zb − α f₀, vb − α f₁, −½ − α f₂, −α f₃].
///
/// With L the piece's length, a later piece's gap at s = L is c₀ + L c₁ + L²(g₂ + L g₃)
/// and its slope there c₁ + L(2g₂ + 3L g₃): the parts that do not depend on the ball
/// are computed here once, and so is whether the gap's slope is monotone on the piece
/// (the vertex of c₁ + 2g₂ s + 3g₃ s² lies outside (0, L)), in which case the slopes
/// at the ends alone say whether the gap is monotone. That shortcut is for true cubics
/// (g₃ ≠ 0): a gap of lower degree keeps its closed-form roots.
#[derive(Clone, Debug)]
pub(super) struct CubicPiece {
    span: Span,
    f: [f64; 4],
    poly: Poly,
    af0: f64,
    af1: f64,
    g2: f64,
    g3: f64,
    g3_times_3: f64,
    /// A bound of |g2 τ + g3 τ²| for every launch on the piece (g2 = −½ − α Q''(0)/2 at
    /// the launch, τ up to the piece's end), with a margin for rounding: a launch with a
    /// larger relative velocity w cannot meet the piece again.
    quotient_bound: f64,
    /// α F' on the piece: α f₁, 2α f₂, 3α f₃.
    velocity: [f64; 3],
    len: f64,
    /// L²(g₂ + L g₃), L²(|g₂| + L |g₃|) and L(2g₂ + 3L g₃).
    end_rest: f64,
    end_mag: f64,
    end_slope: f64,
    /// A cubic gap (g₃ ≠ 0) whose slope is monotone on the piece.
    cubic_slope_monotone: bool,
}

impl AsRef<Span> for CubicPiece {
    fn as_ref(&self) -> &Span {
        &self.span
    }
}

/// Whether w + g2 τ + g3 τ² (w > 0) provably keeps its sign on [0, len], in a few
/// operations: concave or linear (g3 ≤ 0), it lies above the chord between its values at
/// the ends, so a value at τ = len positive beyond its rounding bound suffices; convex and
/// increasing from τ = 0 (g3 > 0, g2 ≥ 0), it stays above w. False means only "maybe a
/// root" (the closed form decides).
#[inline]
fn quotient_keeps_sign(w: f64, g2: f64, g3: f64, len: f64) -> bool {
    if g3 <= 0.0 {
        let q = w + len * (g2 + g3 * len);
        let mag = w + len * (g2.abs() - g3 * len);
        q > 12.0 * f64::EPSILON * mag
    } else {
        g2 >= 0.0
    }
}

impl PieceGap for CubicGap {
    type Piece = CubicPiece;

    fn prepare(piece: &Piece, alpha: f64) -> CubicPiece {
        let f = piece.f.low_coeffs();
        let (g2, g3) = (-0.5 - alpha * f[2], -alpha * f[3]);
        let len = piece.end - piece.start;
        let vertex = -g2 / (3.0 * g3);
        CubicPiece {
            span: Span::of(piece, alpha),
            f,
            poly: piece.f,
            af0: alpha * f[0],
            af1: alpha * f[1],
            g2,
            g3,
            g3_times_3: 3.0 * g3,
            // g2 at the launch is linear in its offset, so |g2| is largest at an end.
            quotient_bound: (1.0 + 1e-9)
                * len
                * ((g2.abs()).max((g2 + 3.0 * g3 * len).abs()) + g3.abs() * len),
            velocity: [alpha * f[1], 2.0 * alpha * f[2], 3.0 * alpha * f[3]],
            len,
            end_rest: len * len * (g2 + len * g3),
            end_mag: len * len * (g2.abs() + len * g3.abs()),
            end_slope: len * (2.0 * g2 + 3.0 * len * g3),
            // (g3 = 0 would give an infinite or NaN vertex; such gaps are not cubic.)
            cubic_slope_monotone: g3 != 0.0 && !(vertex > 0.0 && vertex < len),
        }
    }

    #[inline]
    fn launch_piece(
        piece: &CubicPiece,
        alpha: f64,
        off: f64,
        len: f64,
        launch: &Launch,
    ) -> Result<(Option<Hit>, f64), FlightError> {
        // A launch from the table with a positive relative velocity (every impact) has
        // the simple root τ = 0, divided out in closed form below. Releases (w = 0) and
        // launches above the table take the general route.
        let from_table_moving_up = launch.height == 0.0 && launch.w > 0.0;
        if !from_table_moving_up {
            return general_launch_piece(&piece.poly, alpha, off, len, launch);
        }
        let [f0, f1, f2, f3] = piece.f;
        // Taylor coefficients of F at `off`: Q(0), and Q''(0)/2 = f2 + 3 f3 off in the
        // gap's g2 = −½ − α Q''(0)/2 (Q'''/6 = f3).
        let q0 = ((f3 * off + f2) * off + f1) * off + f0;
        // gap(τ)/τ = w + g2 τ + g3 τ², positive at τ = 0; most launches leave fast enough
        // that it stays positive on any stretch of the piece.
        let w = launch.w;
        if w > piece.quotient_bound {
            return Ok((None, q0));
        }
        let g2 = piece.g2 + piece.g3_times_3 * off;
        let g3 = piece.g3;
        if quotient_keeps_sign(w, g2, g3, len) {
            return Ok((None, q0));
        }
        let root = if g3 < 0.0 {
            // Concave and positive at 0: one positive root, in the cancellation-free
            // form of the closed formula.
            let sd = (g2 * g2 - 4.0 * g3 * w).sqrt();
            let s = if g2 <= 0.0 {
                2.0 * w / (sd - g2)
            } else {
                (g2 + sd) / (-2.0 * g3)
            };
            (s <= len).then_some(s)
        } else {
            let quotient = CubicGap::new([w, g2, g3, 0.0]);
            first_root_low_degree(&quotient.c, quotient.len, 0.0, len).filter(|&s| s > 0.0)
        };
        let hit = root.map(|s| Hit {
            s,
            slope: w + s * (2.0 * g2 + 3.0 * g3 * s),
        });
        Ok((hit, q0))
    }

    #[inline]
    fn later_piece(piece: &CubicPiece, zb: f64, vb: f64) -> Self {
        let c = [zb - piece.af0, vb - piece.af1, piece.g2, piece.g3];
        if piece.g3 != 0.0 {
            CubicGap { c, len: 4 }
        } else {
            CubicGap::new(c)
        }
    }

    #[inline]
    fn at_start(&self) -> (f64, f64) {
        // The bound of four coefficients, whatever the degree.
        let g0 = self.c[0];
        (g0, 16.0 * f64::EPSILON * g0.abs())
    }

    #[inline]
    fn first_root(&self, piece: &CubicPiece) -> Option<f64> {
        // Called once the value at 0 is known to be positive beyond its rounding.
        let c = &self.c;
        let len = piece.len;
        if piece.cubic_slope_monotone {
            // The slopes at the ends bound the slope on the piece.
            let (d0, d1) = (c[1], c[1] + piece.end_slope);
            if d0 >= 0.0 && d1 >= 0.0 {
                // Nondecreasing from a positive value.
                return None;
            }
            if d1 < 0.0 && d0 != 0.0 {
                // Falling at the end, after one maximum (d0 > 0) or throughout: a root
                // exactly when the value at the end is not positive (beyond the rounding
                // bound of a cubic's evaluation, as `first_root_cubic_from`); after the
                // maximum, if there is one.
                let p1 = c[0] + (len * c[1] + piece.end_rest);
                let bound = 16.0 * f64::EPSILON * (c[0].abs() + (len * c[1].abs() + piece.end_mag));
                if p1 > bound {
                    return None;
                }
                if p1 >= -bound {
                    return Some(len);
                }
                let start = piece.span.start;
                return Some(if d0 > 0.0 {
                    root_after_maximum(c, len, start)
                } else {
                    root_falling_from_zero(c, len, start)
                });
            }
            if d0 < 0.0 && d1 > 0.0 {
                // Falling to one minimum, then rising: a root only before the minimum.
                return root_before_minimum(c, len, piece.span.start);
            }
        }
        if self.len == 4 {
            first_root_cubic_from(&self.c, 0.0, len, self.c[0], piece.span.start)
        } else {
            first_root_low_degree(&self.c, self.len, 0.0, len)
        }
    }

    #[inline]
    fn slope(&self, s: f64) -> f64 {
        let c = &self.c;
        c[1] + s * (2.0 * c[2] + 3.0 * c[3] * s)
    }

    #[inline]
    fn table_velocity(piece: &CubicPiece, s: f64) -> f64 {
        let [v0, v1, v2] = piece.velocity;
        v0 + s * (v1 + v2 * s)
    }
}

/// The walk over pieces: the launch piece first, then later pieces in time order,
/// skipping a piece only where the ball is provably above the table's maximum on it and
/// whole periods where it is above every table height.
pub(super) fn piecewise_landing<G: PieceGap>(
    prep: &Prepared<G::Piece>,
    launch: &Launch,
) -> Result<Landing, FlightError> {
    let pieces = &prep.pieces[..];
    let alpha = prep.alpha;
    let phi = launch.phase;
    let v = launch.v;
    let mut j = prep.index(phi);
    let first = &pieces[j];
    let span = first.as_ref();
    let off = phi - span.start;

    let (hit, q0) = G::launch_piece(first, alpha, off, span.end - phi, launch)?;
    if let Some(Hit { s, slope }) = hit {
        return Ok(landing_on(
            launch,
            0,
            span.start,
            off + s,
            s,
            slope,
            G::table_velocity(first, off + s),
        ));
    }

    // Later pieces: gap from absolute heights, skipping where the ball is above the table.
    let z0 = alpha * q0 + launch.height;
    // The ball's height in plain f64, for the skip tests: they keep a margin far above
    // its rounding for every τ ≤ `reach`. The first margin covers the next two periods;
    // a walk that goes on computes when the ball falls below the table's minimum
    // (`last`: it surely lands before, and the walk stops a period after it) and extends
    // the margin to there.
    let height = |tau: f64| z0 + tau * (v - 0.5 * tau);
    let margin_to = |reach: f64| 1e-9 * (1.0 + z0.abs() + reach * (v.abs() + reach));
    let mut reach = 2.0;
    let mut margin = margin_to(reach);
    // The walk stops a period after `last`.
    let mut stop = f64::INFINITY;
    // Whole periods m (also as f64) and the pieces walked, for the work bound.
    let mut m: i64 = 0;
    let mut mf = 0.0;
    let mut walked = 0;
    // The height at the start of the next piece is carried over from the end of the one
    // before.
    let mut tau_lo = span.end - phi;
    let mut z_lo = height(tau_lo);
    j += 1;
    loop {
        if j == pieces.len() {
            j = 0;
            m += 1;
            mf = m as f64;
            walked += pieces.len();
            if walked > MAX_FLIGHT_PIECES {
                break;
            }
            if mf + 1.0 > reach {
                let last = descent_below_cold(z0, v, prep.bottom);
                stop = last + 1.0;
                reach = last + 2.0;
                margin = margin_to(reach);
            }
            // Whole periods are skipped where the ball is above the table's top at both
            // ends of the period (its path is concave, so in between too), up to the
            // period in which it falls below the top again.
            let top = prep.top + margin;
            if z_lo > top && height(mf + 1.0 - phi) > top {
                let target = floor(phi + descent_below_cold(z0, v, prep.top)) as i64;
                if target > m {
                    m = target;
                    mf = m as f64;
                    tau_lo = mf - phi;
                    z_lo = height(tau_lo);
                }
            }
        }
        if tau_lo > stop {
            break;
        }
        let p = &pieces[j];
        let span = p.as_ref();
        let tau_hi = mf + span.end - phi;
        let z_hi = height(tau_hi);
        let above = span.top + margin;
        if !(z_lo > above && z_hi > above) {
            let (zb, vb) = if tau_lo * (v.abs() + tau_lo) <= SHORT_FLIGHT {
                (z_lo, v - tau_lo)
            } else {
                ball_at(z0, v, flight_time(m, span.start, phi))
            };
            let g = G::later_piece(p, zb, vb);
            // At s = 0 the value is c0 itself, its rounding bound that of one term.
            let (g0, err) = g.at_start();
            let root = if g0 <= err {
                Some(0.0)
            } else {
                g.first_root(p)
            };
            if let Some(s) = root {
                return Ok(landing_on(
                    launch,
                    m,
                    span.start,
                    s,
                    tau_lo + s,
                    g.slope(s),
                    G::table_velocity(p, s),
                ));
            }
        }
        tau_lo = tau_hi;
        z_lo = z_hi;
        j += 1;
    }
    Err(FlightError::NoLanding)
}

/// When the ball, at height z0 with velocity v at τ = 0, falls below `level` (0 if it
/// is never above it). Out of line: needed only for flights that span periods.
#[cold]
#[inline(never)]
fn descent_below_cold(z0: f64, v: f64, level: f64) -> f64 {
    crossing_times(z0, v, level).map_or(0.0, |c| c.1)
}

/// Divide the launch root out of the gap polynomial (whose constant term is zero).
/// With w = 0 (a release) the next coefficients may vanish too: they are divided out as
/// long as they are zero within rounding; the first one left must be positive.
fn lift_off_quotient(gap: &Poly, w: f64) -> Result<Poly, FlightError> {
    let mut q = gap.div_x();
    if w > 0.0 {
        return Ok(q);
    }
    let scale: f64 = gap.coeffs().iter().map(|c| c.abs()).sum::<f64>().max(1.0);
    let tiny = 64.0 * f64::EPSILON * scale;
    loop {
        let c0 = q.coeff(0);
        if c0 > tiny {
            return Ok(q);
        }
        if c0 < -tiny || q.degree() == 0 {
            return Err(FlightError::NoLiftOff);
        }
        q = q.div_x();
    }
}

/// First root of `q` in (0, len]; q(0) > 0 is known.
fn first_positive_root(q: &Poly, len: f64) -> Option<f64> {
    q.first_root(0.0, len)
        .filter(|&s| s > 0.0 || q.eval(0.0) <= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;
    use crate::test_rng::Xorshift;

    /// A C¹ periodic cubic spline through `values` with `slopes` at `knots` (knots[0] = 0).
    fn cubic_spline(knots: &[f64], values: &[f64], slopes: &[f64]) -> Table {
        let n = knots.len();
        let pieces: Vec<(f64, Vec<f64>)> = (0..n)
            .map(|i| {
                let a = knots[i];
                let l = if i + 1 < n { knots[i + 1] } else { 1.0 } - a;
                let (y0, y1) = (values[i], values[(i + 1) % n]);
                let (m0, m1) = (slopes[i], slopes[(i + 1) % n]);
                let c2 = (3.0 * (y1 - y0) / l - 2.0 * m0 - m1) / l;
                let c3 = (2.0 * (y0 - y1) / l + m0 + m1) / (l * l);
                let global = Poly::new(&[y0, m0, c2, c3]).shift(-a);
                (a, global.coeffs().to_vec())
            })
            .collect();
        Table::piecewise("spline", &pieces).unwrap()
    }

    /// The fixed-size cubic path and the general one are two implementations of the same
    /// search: on cubic tables they must find the same contact for every launch.
    #[test]
    fn cubic_path_agrees_with_general_path() {
        let mut rng = Xorshift::new(0x853c49e6748fea9b);
        let mut rnd = || rng.next();
        let mut compared = 0;
        for i in 0..4000 {
            let table = if i % 2 == 0 {
                Table::fd(rnd()).unwrap()
            } else {
                let n = 1 + (4.0 * rnd()) as usize;
                let mut knots: Vec<f64> = (0..n)
                    .map(|k| (k as f64 + 0.2 + 0.6 * rnd()) / n as f64)
                    .collect();
                knots[0] = 0.0;
                let values: Vec<f64> = (0..n).map(|_| 2.0 * rnd() - 1.0).collect();
                let slopes: Vec<f64> = (0..n).map(|_| 8.0 * rnd() - 4.0).collect();
                cubic_spline(&knots, &values, &slopes)
            };
            assert!(table.max_degree() <= 3);
            let sys = System::new(table, 0.05 + 1.45 * rnd(), 0.5).unwrap();
            let cubic = Prepared::new::<CubicGap>(&sys);
            let any = Prepared::new::<Poly>(&sys);
            for _ in 0..10 {
                let phase = rnd();
                let (height, w) = match (8.0 * rnd()) as u32 {
                    0 => (0.0, 0.0),
                    1 | 2 => (0.5 * rnd(), 3.0 * rnd() - 1.0),
                    _ => (0.0, 1e-6 + 3.0 * rnd()),
                };
                let launch = Launch {
                    period: 7,
                    phase,
                    height,
                    v: sys.df(phase) + w,
                    w,
                };
                let fast = piecewise_landing::<CubicGap>(&cubic, &launch);
                let general = piecewise_landing::<Poly>(&any, &launch);
                match (fast, general) {
                    (Ok(a), Ok(b)) => {
                        let ta = a.period as f64 - 7.0 + a.phase;
                        let tb = b.period as f64 - 7.0 + b.phase;
                        assert!((ta - tb).abs() <= 1e-12, "{launch:?}: {a:?} vs {b:?}");
                        assert!(
                            (a.vrel - b.vrel).abs() <= 1e-10,
                            "{launch:?}: {a:?} vs {b:?}"
                        );
                        assert!((a.df - b.df).abs() <= 1e-10, "{launch:?}: {a:?} vs {b:?}");
                        compared += 1;
                    }
                    (a, b) => assert_eq!(a, b, "{launch:?}"),
                }
            }
        }
        assert!(compared > 30_000, "{compared} landings compared");
    }
}
