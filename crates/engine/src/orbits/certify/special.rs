//! Special points of a branch proved as α-intervals [α̲, ᾱ]: a period doubling (a
//! multiplier exactly −1) and a border collision (an impact exactly on a breakpoint).
//!
//! The proof brackets the point and uses continuity:
//! 1. At α̲ and ᾱ (doubles) the cycle is proved, and the condition's enclosure has a
//!    sign, opposite at the two ends: the period-doubling test 1 + tr M + det M (zero
//!    exactly when a multiplier is −1, since det M = r²ⁿ > 0), or the impact phase
//!    minus the breakpoint.
//! 2. Over the whole interval [α̲, ᾱ] (α an interval in the Krawczyk test) the cycle's
//!    equations have exactly one solution in a box holding both ends' boxes, for every
//!    α: it depends continuously on α (its Jacobian is regular on the box), and the
//!    ends' cycles are that solution.
//! 3. So the condition, continuous in α, vanishes at some α* in (α̲, ᾱ). For the border
//!    collision the impact's equations are those of the piece on one side, continued as
//!    its polynomial past the breakpoint; at α* they are the table's (F and F' are
//!    continuous there), so the solution at α* is an orbit, and every landing of it is
//!    its flight's first contact (shown over the whole interval).
//!
//! The ends are found by bisection on the proofs themselves, down to where the
//! condition's enclosure no longer has a sign: intervals of a few 10⁻¹⁶ where the
//! condition moves by O(1) per unit of α.

use super::table::Enclosed;
use super::{prove, Certificate, Enclosure, Failure, Stability};
use crate::orbits::periodic::CyclePoint;
use crate::real::Interval;
use crate::system::System;
use crate::table::Table;

/// Which special point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpecialKind {
    /// A multiplier −1.
    PeriodDoubling,
    /// A multiplier +1 (the interval is of α over the stretch of the branch, in its
    /// first launch phase, where the fold lies).
    Fold,
    /// Impact `impact` (0 is the launch's) on the breakpoint at `breakpoint`.
    BorderCollision {
        /// Which impact.
        impact: usize,
        /// The breakpoint's phase.
        breakpoint: f64,
    },
}

/// Why a special point is not proved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpecialFailure {
    /// Proofs at α on both sides did not give the condition opposite signs within
    /// 10⁻⁵ of the point.
    NoBracket,
    /// The cycle is not proved over the α-interval.
    Cycle(Failure),
    /// On the interval's one cycle, the condition's sign at an end is not decided (or
    /// not opposite to the other end's).
    EndsUndecided,
    /// The table has no breakpoint there (a border collision on the sine).
    NoBreakpoint,
}

/// A special point proved (or not) as an α-interval.
#[derive(Clone, Debug)]
pub struct CertifiedSpecial {
    /// Which point.
    pub kind: SpecialKind,
    /// Impacts per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// The α-interval holding the point (None: not proved).
    pub alpha: Option<Interval>,
    /// The condition's enclosure at α̲ and at ᾱ (opposite signs).
    pub ends: Option<[Interval; 2]>,
    /// The cycle's box over the whole interval.
    pub enclosure: Option<Enclosure>,
    /// Why not proved.
    pub failure: Option<SpecialFailure>,
}

impl CertifiedSpecial {
    /// Nothing shown yet of the point `kind` of the (n, k) cycle.
    pub(super) fn start(kind: SpecialKind, n: usize, k: u32) -> CertifiedSpecial {
        CertifiedSpecial {
            kind,
            n,
            k,
            alpha: None,
            ends: None,
            enclosure: None,
            failure: None,
        }
    }

    /// The point `kind` of the (n, k) cycle, not proved for `why`.
    pub(super) fn not_proved(kind: SpecialKind, n: usize, k: u32, why: SpecialFailure) -> Self {
        CertifiedSpecial {
            failure: Some(why),
            ..CertifiedSpecial::start(kind, n, k)
        }
    }

    /// The point is proved in `alpha`.
    pub fn proved(&self) -> bool {
        self.failure.is_none() && self.alpha.is_some()
    }
}

/// Bisection steps of each search (each halves an interval of doubles).
const BISECTIONS: usize = 80;
/// The first distance either side of the point tried, relative to max(1, α).
const FIRST_STEP: f64 = 1e-11;
/// The last.
const LAST_STEP: f64 = 1e-5;

/// A special point's condition on a box of the cycle (phases then velocities) with its
/// stability: an enclosure of the condition's value.
type Condition<'a> = &'a dyn Fn(&[Interval], Option<&Stability>) -> Option<Interval>;

/// The sign of an enclosure: 1, −1, or 0 where it contains zero.
pub(super) fn sign(i: &Interval) -> i8 {
    if i.positive() {
        1
    } else if i.negative() {
        -1
    } else {
        0
    }
}

/// A value of a parameter where a condition changes sign, bracketed by proofs: the
/// nearest ends either side of `center` (steps from [`FIRST_STEP`] to [`LAST_STEP`]
/// times `scale`) with opposite signs, shrunk by bisection as far as the proofs decide
/// the sign.
pub(super) struct Bracket<'a> {
    /// The condition's enclosure at a value, from a proof there.
    pub condition_at: &'a dyn Fn(f64) -> Option<Interval>,
    pub center: f64,
    pub scale: f64,
}

impl Bracket<'_> {
    fn sign_at(&self, p: f64) -> i8 {
        (self.condition_at)(p).map_or(0, |c| sign(&c))
    }

    /// The bracket (a < b), or None.
    pub fn find(&self) -> Option<(f64, f64)> {
        let mut h = FIRST_STEP * self.scale;
        while h <= LAST_STEP * self.scale {
            let (a, b) = (self.center - h, self.center + h);
            let (sa, sb) = (self.sign_at(a), self.sign_at(b));
            if sa != 0 && sb != 0 && sa != sb {
                return Some(self.shrink((a, b)));
            }
            h *= 10.0;
        }
        None
    }

    /// The bracket shrunk by bisection as far as the signs are decided.
    fn shrink(&self, (mut a, mut b): (f64, f64)) -> (f64, f64) {
        let sa = self.sign_at(a);
        for _ in 0..BISECTIONS {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            match self.sign_at(m) {
                0 => {
                    // Undecided at m: the last decided point on each side.
                    return (self.towards(a, m, sa), self.towards(b, m, -sa));
                }
                s if s == sa => a = m,
                _ => b = m,
            }
        }
        (a, b)
    }

    /// From `from` (sign `s`) towards `to` (undecided), the last point with sign `s`.
    fn towards(&self, mut from: f64, mut to: f64, s: i8) -> f64 {
        for _ in 0..BISECTIONS {
            let m = 0.5 * (from + to);
            if m == from || m == to {
                break;
            }
            if self.sign_at(m) == s {
                from = m;
            } else {
                to = m;
            }
        }
        from
    }
}

struct Search<'a> {
    table: &'a Table,
    r: f64,
    pt: &'a CyclePoint,
    forced: Vec<Option<(f64, usize)>>,
    condition: Condition<'a>,
}

impl Search<'_> {
    fn enclosed(&self, alpha: Interval) -> Option<Enclosed> {
        let sys = System::new(self.table.clone(), alpha.mid(), self.r).ok()?;
        Some(Enclosed::of(&sys).with_alpha(alpha))
    }

    /// The condition at α, from a proof there, and the proof.
    fn probe(&self, alpha: f64) -> Option<(Interval, Certificate)> {
        let enc = self.enclosed(Interval::point(alpha))?;
        let cert = prove(&enc, self.pt, &self.forced, None);
        let c = (self.condition)(&boxed(&cert)?, cert.stability.as_ref())?;
        Some((c, cert))
    }

    fn run(&self, kind: SpecialKind) -> CertifiedSpecial {
        let mut out = CertifiedSpecial::start(kind, self.pt.n, self.pt.k);
        let condition_at = |alpha: f64| self.probe(alpha).map(|(c, _)| c);
        let bracket = Bracket {
            condition_at: &condition_at,
            center: self.pt.alpha,
            scale: self.pt.alpha.abs().max(1.0),
        };
        let Some((a, b)) = bracket.find() else {
            out.failure = Some(SpecialFailure::NoBracket);
            return out;
        };
        match self.over(a, b) {
            Ok((bx, ca, cb)) => {
                out.alpha = Some(Interval::new(a, b).expect("a < b"));
                out.ends = Some([ca, cb]);
                out.enclosure = Some(bx);
            }
            Err(f) => out.failure = Some(f),
        }
        out
    }

    /// The cycle proved over [a, b] in a box holding the ends' proved boxes (so their
    /// cycles are its), and the condition at a and b.
    fn over(&self, a: f64, b: f64) -> Result<(Enclosure, Interval, Interval), SpecialFailure> {
        let (Some((ca, pa)), Some((cb, pb))) = (self.probe(a), self.probe(b)) else {
            return Err(SpecialFailure::EndsUndecided);
        };
        if sign(&ca) == 0 || sign(&ca) != -sign(&cb) {
            return Err(SpecialFailure::EndsUndecided);
        }
        let (Some(ba), Some(bb)) = (boxed(&pa), boxed(&pb)) else {
            return Err(SpecialFailure::EndsUndecided);
        };
        let hint: Vec<Interval> = ba.iter().zip(&bb).map(|(x, y)| x.hull(y)).collect();
        let alpha = Interval::new(a, b).expect("a < b");
        let enc = self.enclosed(alpha).ok_or(SpecialFailure::NoBracket)?;
        let whole = prove(&enc, self.pt, &self.forced, Some(&hint));
        if let Some(f) = whole.failure {
            return Err(SpecialFailure::Cycle(f));
        }
        let bx = whole.enclosure.ok_or(SpecialFailure::EndsUndecided)?;
        Ok((bx, ca, cb))
    }
}

/// A proof's box as one list, phases then velocities.
fn boxed(c: &Certificate) -> Option<Vec<Interval>> {
    let e = c.enclosure.as_ref()?;
    Some(e.phases.iter().chain(&e.velocities).copied().collect())
}

/// Prove the period doubling near the cycle `pt` (at `pt.alpha`, a multiplier near −1)
/// of `table` at restitution `r` as an α-interval.
pub fn certify_period_doubling(table: &Table, r: f64, pt: &CyclePoint) -> CertifiedSpecial {
    let condition = |_: &[Interval], st: Option<&Stability>| st.map(Stability::pd_test);
    Search {
        table,
        r,
        pt,
        forced: Vec::new(),
        condition: &condition,
    }
    .run(SpecialKind::PeriodDoubling)
}

/// Prove the border collision near the cycle `pt` (at `pt.alpha`, its impact `impact`,
/// 0 the launch's, near the breakpoint at phase `breakpoint`) as an α-interval.
pub fn certify_border_collision(
    table: &Table,
    r: f64,
    pt: &CyclePoint,
    impact: usize,
    breakpoint: f64,
) -> CertifiedSpecial {
    let kind = SpecialKind::BorderCollision { impact, breakpoint };
    let fail = |f| CertifiedSpecial::not_proved(kind, pt.n, pt.k, f);
    let Ok(sys) = System::new(table.clone(), pt.alpha, r) else {
        return fail(SpecialFailure::NoBracket);
    };
    let enc = Enclosed::of(&sys);
    let Some(phase) = pt.phases.get(impact).copied() else {
        return fail(SpecialFailure::NoBreakpoint);
    };
    // The side the impact is on at the point, and the breakpoint as that piece's
    // start or end (in the same period).
    let Some(piece) = enc.piece_at(phase) else {
        return fail(SpecialFailure::NoBreakpoint);
    };
    let Some((start, end)) = enc.piece_ends(piece) else {
        return fail(SpecialFailure::NoBreakpoint);
    };
    let near =
        |b: &Interval| (b.mid() - phase).abs() < 1e-6 || (b.mid() - phase - 1.0).abs() < 1e-6;
    let b = if near(&start) {
        start
    } else if near(&end) {
        end
    } else {
        // The phase sits just past a period's end: the breakpoint is the next start.
        return fail(SpecialFailure::NoBreakpoint);
    };
    let mut forced = vec![None; pt.n];
    forced[impact] = Some(piece);
    let condition = move |bx: &[Interval], _: Option<&Stability>| Some(bx[impact] - b);
    Search {
        table,
        r,
        pt,
        forced,
        condition: &condition,
    }
    .run(kind)
}
