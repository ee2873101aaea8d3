//! Two-parameter bifurcation curves: the period doublings, folds, border collisions and
//! grazings of an (n, k) cycle followed through the plane of α and a second parameter
//! (r, or D of the F_D family), with the codimension-two points met on the way.
//!
//! # For front ends
//! [`curves`] takes a [`Plane`] (the table, r, the α window and the second parameter's
//! window) and a [`Seeds`] choice, runs the one-parameter continuation
//! ([`continuation::branches`]) at each seed value of the second parameter, and follows
//! every special point it finds (PD, fold, border collision, grazing) as a curve
//! ([`Curve`]: its points, how each end came about, the flip's criticality along a PD
//! curve). The codimension-two points ([`Codim2`]) are located on the curves.
//!
//! # Method
//! A codimension-one point of an (n, k) cycle is a zero of one scalar condition G on the
//! cycle solved at (α, p):
//! * period doubling: G = 1 + tr M + det M, det M = r²ⁿ (a multiplier −1);
//! * fold: G = 1 − tr M + det M (a multiplier +1; solved with the cycle, below);
//! * border collision: G = the signed phase distance of one impact to one breakpoint
//!   where f'' jumps;
//! * grazing: G = the smallest interior height of the ball above the table over the
//!   cycle's flights;
//! * onset of sticking: G = the smallest relative impact velocity of the cycle (a
//!   landing turning tangential).
//!
//! The cycle is solved exactly at each (α, p) by Newton's method on the map
//! ([`periodic::cycle`], re-verified by the 1e-11 return), warm-started from the
//! previous point, so the curve G(α, p) = 0 is a curve in the plane. It is followed by
//! pseudo-arclength continuation: a predictor along the tangent (orthogonal to ∇G, by
//! central differences of G with the cycle re-solved) and Newton's method on
//! (G = 0, τ·(y − y₀) = h). Every accepted point has |G| below [`CONDITION_TOLERANCE`]
//! (its value is kept as the evidence). A step the corrector cannot take, or one whose
//! cycle jumped (an impact phase or velocity moving far more than the step), is halved;
//! below the smallest step the curve ends with the reason the cycle gives (grazing, a
//! stick, no convergence). Where a step would leave the window, the point on the window's
//! edge is solved instead and the curve ends there.
//!
//! Between accepted points the test functions of the codimension-two points are watched
//! for a sign change and the crossing is located by a bracketed root in the arclength:
//! * on a PD or fold curve, every impact's distance to every breakpoint: the point hits
//!   the border. There f'' jumps, so the multipliers jump and the curve ends: its
//!   continuation on the far side is another curve (if any);
//! * on a PD curve, the flip's criticality coefficient c (below): a degenerate flip;
//! * on a border-collision curve, the other impacts' distances to the breakpoints: two
//!   border collisions at once.
//!
//! Fold curves are the exception: at a fold M − I is singular, so the cycle cannot be
//! solved at fixed (α, p); there the corrector solves the extended system (the cycle's
//! two equations and the fold condition in α, p, t₀, v₀, with the arclength
//! condition), the map's own derivatives giving the cycle equations' columns.
//!
//! A fold and a period doubling cannot meet on a cycle of this map: at a multiplier −1
//! the other is −r²ⁿ, never +1 for r < 1, so no such point is looked for.
//!
//! # The flip's criticality
//! On a PD curve the n-fold map P, with A = DP, Aq = −q, Aᵀp = −p, ⟨p, q⟩ = 1,
//! B and C its second and third derivatives, has the normal form η ↦ −η + c η³ with
//!
//!   c = ⟨p, C(q, q, q)⟩/6 + ⟨p, B(q, (I − A)⁻¹ B(q, q))⟩/2
//!
//! (Kuznetsov, *Elements of Applied Bifurcation Theory*, §5.4). c > 0: supercritical, the
//! doubled cycle is born stable on the side where the cycle is unstable; c < 0:
//! subcritical, it is born unstable on the stable side and the orbit jumps away. B and C
//! are central differences of P along q and w = (I − A)⁻¹B(q, q) at two step sizes, h
//! = 2·10⁻³ and 10⁻³, extrapolated; three times their difference (or the rounding error
//! of a third difference, if larger) is the reported error, and where |c| does not exceed it the sign is
//! undecided (e.g. near a border, or where f''' = 0 makes c vanish).
//!
//! # Files
//! * this file: the plane, the kinds of curves and of codimension-two points, the
//!   seeds, [`curves`] and the merging of curves found twice;
//! * [`trace`]: following one curve (the corrector, the fold's extended system, the
//!   test functions watched between points, the ends);
//! * [`criticality`](mod@criticality): the flip's normal-form coefficient.

pub mod birth;
mod criticality;
mod trace;

pub use criticality::criticality;

use super::continuation::{branches, Kind, Options, Special, Start};
use super::events::jump_phases;
use super::periodic::{min_interior_gap, CyclePoint, PassError};
use crate::error::EngineError;
use crate::grid::SweepParam;
use crate::system::System;
use crate::table::Table;
use crate::time::signed_distance;
use trace::follow;

/// An accepted curve point satisfies its condition to this.
pub const CONDITION_TOLERANCE: f64 = 1e-9;
/// A curve that cannot go on with an impact this close to a breakpoint (in phase)
/// ends at that border.
pub const BORDER_REACH: f64 = 1e-5;
/// Steps per direction of one curve.
pub const MAX_STEPS: usize = 2000;

/// The plane the curves live in: α on one axis, r or D on the other.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// The table (for `second` = D, an F_D table: its D is replaced).
    pub table: Table,
    /// r (replaced when `second` is r).
    pub r: f64,
    /// The α window.
    pub alpha: (f64, f64),
    /// The second parameter: [`SweepParam::R`] or [`SweepParam::D`].
    pub second: SweepParam,
    /// Its window.
    pub window: (f64, f64),
}

impl Plane {
    /// Check the plane: windows ordered and inside the parameters' ranges, D only for an
    /// F_D table.
    pub fn check(&self) -> Result<(), EngineError> {
        let bad = EngineError::Inconsistent;
        if self.second == SweepParam::Alpha {
            return Err(bad(
                "the second parameter of a curve must be r or d, not alpha".into(),
            ));
        }
        if self.second == SweepParam::D && self.table.d().is_none() {
            return Err(bad(format!(
                "d is a parameter of the fd:D tables only, and the table is {}",
                self.table.name()
            )));
        }
        for (lim, (lo, hi)) in [
            (crate::limits::ALPHA, self.alpha),
            (self.second.limit(), self.window),
        ] {
            lim.check(lo)?;
            lim.check(hi)?;
            if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
                return Err(bad(format!("the {} window needs LO < HI", lim.name)));
            }
        }
        Ok(())
    }

    /// The system at (α, p).
    pub fn system(&self, alpha: f64, p: f64) -> Result<System, EngineError> {
        match self.second {
            SweepParam::D => System::new(Table::fd(p)?, alpha, self.r),
            _ => System::new(self.table.clone(), alpha, p),
        }
    }

    /// The phases where f'' jumps anywhere on the plane: for F_D, those of D = 0, ½
    /// and `p` (F_1 is C² at ½, the others are not).
    fn jumps(&self, p: f64) -> Vec<f64> {
        let mut out = match self.second {
            SweepParam::D => [0.0, 0.5, p]
                .iter()
                .filter_map(|&d| Table::fd(d).ok())
                .flat_map(|t| jump_phases(&t))
                .collect(),
            _ => jump_phases(&self.table),
        };
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }

    fn inside(&self, y: [f64; 2]) -> bool {
        y[0] >= self.alpha.0
            && y[0] <= self.alpha.1
            && y[1] >= self.window.0
            && y[1] <= self.window.1
    }

    fn scale(&self) -> f64 {
        (self.alpha.1 - self.alpha.0).hypot(self.window.1 - self.window.0)
    }
}

/// What a curve follows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveKind {
    /// A multiplier −1.
    PeriodDoubling,
    /// A multiplier +1.
    Fold,
    /// Impact `impact` (0 = the launch's) at the breakpoint `breakpoint`.
    BorderCollision {
        /// Which impact of the cycle.
        impact: usize,
        /// The breakpoint's phase.
        breakpoint: f64,
    },
    /// A flight touches the table at an interior point.
    Grazing,
    /// An impact's relative velocity reaches zero: the landing becomes tangential, and
    /// beyond it the ball chatters and sticks.
    StickingOnset,
    /// The (1, k) pair is born (α max F' = (k/2)(1 − r)/(1 + r)): in closed form
    /// ([`birth`]).
    Birth,
}

impl CurveKind {
    /// Name in every output format.
    pub fn as_str(&self) -> &'static str {
        match self {
            CurveKind::PeriodDoubling => "period_doubling",
            CurveKind::Fold => "fold",
            CurveKind::BorderCollision { .. } => "border_collision",
            CurveKind::Grazing => "grazing",
            CurveKind::StickingOnset => "sticking_onset",
            CurveKind::Birth => "birth",
        }
    }

    /// Short label (as in the one-parameter diagrams).
    pub fn label(&self) -> &'static str {
        match self {
            CurveKind::PeriodDoubling => "PD",
            CurveKind::Fold => "F",
            CurveKind::BorderCollision { .. } => "BC",
            CurveKind::Grazing => "G",
            CurveKind::StickingOnset => "S",
            CurveKind::Birth => "B",
        }
    }

    /// The condition G at a cycle of `sys` (NaN where it is not defined).
    pub fn condition(&self, sys: &System, pt: &CyclePoint) -> f64 {
        match *self {
            CurveKind::PeriodDoubling => pt.pd_test(),
            CurveKind::Fold => pt.fold_test(),
            CurveKind::BorderCollision { impact, breakpoint } => pt
                .phases
                .get(impact)
                .map_or(f64::NAN, |&ph| signed_distance(ph, breakpoint)),
            CurveKind::StickingOnset => pt.min_impact_speed,
            CurveKind::Birth => {
                sys.alpha() * birth::max_slope(sys.table()).0 - birth::slope_at_birth(sys.r(), pt.k)
            }
            CurveKind::Grazing => {
                let g = min_interior_gap(sys, pt).0;
                if g.is_finite() {
                    g
                } else {
                    f64::NAN
                }
            }
        }
    }
}

/// The flip's normal-form coefficient at a period-doubling point, with its error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Criticality {
    /// c of η ↦ −η + c η³ (q normalised to unit length).
    pub c: f64,
    /// Three times |c(h) − c(h/2)| of the two difference steps, or the rounding
    /// error of the third difference if larger.
    pub error: f64,
}

impl Criticality {
    /// Some(true) supercritical, Some(false) subcritical, None where |c| ≤ its error.
    pub fn supercritical(&self) -> Option<bool> {
        (self.c.abs() > self.error).then_some(self.c > 0.0)
    }

    /// `supercritical`, `subcritical` or `undecided`.
    pub fn as_str(&self) -> &'static str {
        match self.supercritical() {
            Some(true) => "supercritical",
            Some(false) => "subcritical",
            None => "undecided",
        }
    }
}

/// One accepted point of a curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// α.
    pub alpha: f64,
    /// The second parameter.
    pub p: f64,
    /// The cycle there.
    pub cycle: CyclePoint,
    /// The condition's value there (the evidence: |G| ≤ [`CONDITION_TOLERANCE`]).
    pub condition: f64,
    /// On a PD curve: the flip's criticality.
    pub criticality: Option<Criticality>,
}

/// How one end of a curve came about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveEnd {
    /// It reached the window's edge.
    Window,
    /// The point reached a breakpoint (a PD or fold curve ends where its point collides
    /// with the border: the multipliers jump there).
    Border,
    /// The cycle grazes (a flight touches the table).
    Grazing,
    /// A stick or a vanishing impact velocity inside the cycle.
    Sticking,
    /// Came back to its start: a closed curve.
    Closed,
    /// The corrector could not go on, with no sign of the above.
    NoConvergence,
    /// The step bound [`MAX_STEPS`] was reached.
    StepLimit,
    /// The cycle on it stops being admissible (a flight meets the table before its end).
    Inadmissible,
    /// The cycle collapses onto the cycle of half its period (its two halves meet): a
    /// doubled cycle ends where it was born.
    Collapse,
    /// The curve turns back on itself (a cusp, or where the cycle stops existing): the
    /// tracer would retrace what it has followed, so it ends there.
    TurnedBack,
    /// Sixty steps in a row under a thousandth of the largest: the cycle changes too
    /// fast along the curve (a long, very unstable cycle) for the corrector to go on at
    /// a useful cost; the curve may go on beyond.
    Stalled,
}

impl CurveEnd {
    /// Name in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            CurveEnd::Window => "window",
            CurveEnd::Border => "border_collision",
            CurveEnd::Grazing => "grazing",
            CurveEnd::Sticking => "sticking",
            CurveEnd::Closed => "closed",
            CurveEnd::NoConvergence => "no_convergence",
            CurveEnd::StepLimit => "step_limit",
            CurveEnd::Inadmissible => "inadmissible",
            CurveEnd::Collapse => "collapse",
            CurveEnd::TurnedBack => "turned_back",
            CurveEnd::Stalled => "stalled",
        }
    }

    fn from_error(e: PassError) -> CurveEnd {
        match e {
            PassError::Grazing { .. } => CurveEnd::Grazing,
            PassError::Stick { .. } | PassError::Halt => CurveEnd::Sticking,
            _ => CurveEnd::NoConvergence,
        }
    }
}

/// What happens at a codimension-two point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Codim2Kind {
    /// A period-doubling point reaches a breakpoint.
    PdBorder,
    /// A fold point reaches a breakpoint.
    FoldBorder,
    /// Two impacts of the cycle on breakpoints at once.
    DoubleBorder,
    /// The flip's criticality coefficient changes sign: the doubling turns from
    /// supercritical to subcritical.
    DegenerateFlip,
    /// A grazing cycle's impact reaches a breakpoint.
    GrazingBorder,
    /// The cycle collapses onto the one of half its period on a breakpoint (its two
    /// halves meet there): where a doubled cycle is born by border collision, not two
    /// independent border collisions.
    Collapse,
}

impl Codim2Kind {
    /// Name in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            Codim2Kind::PdBorder => "pd_border",
            Codim2Kind::FoldBorder => "fold_border",
            Codim2Kind::DoubleBorder => "double_border",
            Codim2Kind::DegenerateFlip => "degenerate_flip",
            Codim2Kind::GrazingBorder => "grazing_border",
            Codim2Kind::Collapse => "collapse",
        }
    }

    /// In words.
    pub fn describe(self) -> &'static str {
        match self {
            Codim2Kind::PdBorder => "period doubling at a breakpoint",
            Codim2Kind::FoldBorder => "fold at a breakpoint",
            Codim2Kind::DoubleBorder => "two impacts at breakpoints",
            Codim2Kind::DegenerateFlip => "degenerate flip (criticality changes sign)",
            Codim2Kind::GrazingBorder => "grazing at a breakpoint",
            Codim2Kind::Collapse => "the cycle collapses onto half its period on a breakpoint",
        }
    }
}

/// A codimension-two point on a curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Codim2 {
    /// What happens there.
    pub kind: Codim2Kind,
    /// The curve it was found on (index into the returned list).
    pub curve: usize,
    /// α.
    pub alpha: f64,
    /// The second parameter.
    pub p: f64,
    /// The curve's own condition there.
    pub condition: f64,
    /// The second condition there (the located test function: a phase distance, or c).
    pub second_condition: f64,
    /// The impact and the breakpoint concerned (border kinds).
    pub impact: Option<(usize, f64)>,
    /// Every curve that passes through it (indices, its own first).
    pub meets: Vec<usize>,
}

/// One curve of an (n, k) cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// What it follows.
    pub kind: CurveKind,
    /// Impacts per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// Points in order along the curve.
    pub points: Vec<CurvePoint>,
    /// How it ends at its first and at its last point.
    pub ends: [CurveEnd; 2],
    /// The seed: (α, p) of the special point it was started from.
    pub seed: [f64; 2],
}

impl Curve {
    /// Whether the curve passes within `tol` (in the plane's units) of (α, p).
    pub fn passes_near(&self, alpha: f64, p: f64, tol: f64) -> bool {
        let d = |a: &CurvePoint| (a.alpha - alpha).hypot(a.p - p);
        self.points.iter().any(|q| d(q) <= tol)
            || self.points.windows(2).any(|w| {
                // Distance to the segment.
                let (ax, ay, bx, by) = (w[0].alpha, w[0].p, w[1].alpha, w[1].p);
                let (dx, dy) = (bx - ax, by - ay);
                let l2 = dx * dx + dy * dy;
                if l2 == 0.0 {
                    return false;
                }
                let t = (((alpha - ax) * dx + (p - ay) * dy) / l2).clamp(0.0, 1.0);
                (ax + t * dx - alpha).hypot(ay + t * dy - p) <= tol
            })
    }
}

/// Where the curves start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seeds {
    /// Every special point of every branch reached from the (1, k) solution by the
    /// one-parameter continuation in α, up to `max_period`, at the second parameter's
    /// value `at` and (for `count` > 1) at `count` more values spread evenly over its
    /// window, ends included.
    FromFixed {
        /// k of the (1, k) solution.
        k: u32,
        /// No doubled branch beyond this period.
        max_period: usize,
        /// The second parameter's value for a single seed.
        at: f64,
        /// How many values of the second parameter to seed at.
        count: usize,
    },
    /// One (n, k) cycle near the launch (t̂₀, v₀) at α = LO of the window and p = `at`:
    /// its branch's special points are followed.
    Point {
        /// Impacts per cycle.
        n: usize,
        /// Table periods per cycle.
        k: u32,
        /// Launch phase guess.
        t0: f64,
        /// Launch velocity guess.
        v0: f64,
        /// The second parameter's value.
        at: f64,
    },
}

impl Seeds {
    /// The longest cycle followed: `max_period`, or the cycle's n.
    pub fn max_period(&self) -> usize {
        match *self {
            Seeds::FromFixed { max_period, .. } => max_period,
            Seeds::Point { n, .. } => n,
        }
    }
}

/// The curves and their codimension-two points.
#[derive(Clone, Debug, PartialEq)]
pub struct Curves {
    /// Every curve followed.
    pub curves: Vec<Curve>,
    /// Codimension-two points located on them.
    pub codim2: Vec<Codim2>,
    /// Special points that were not followed, each once with the reason and how many
    /// times it was met (a seed the corrector could not solve, e.g. a grazing cycle that
    /// cannot be solved at the grazing).
    pub skipped: Vec<Skipped>,
    /// Values of the second parameter where no branch could be started, with the
    /// reason (e.g. a guess near which there is no cycle).
    pub unseeded: Vec<(f64, String)>,
    /// How the seeds were placed, and whether a finer seeding stopped finding curves.
    pub seeding: Seeding,
}

/// How [`curves`] seeded: the values of the second parameter it seeded at, the finest
/// dyadic grid of the window (2^level + 1 values), and whether the last two levels
/// found no new curve (else the finest level allowed, [`MAX_SEED_LEVEL`], was reached
/// with curves still appearing, and a finer seeding might find more).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Seeding {
    /// Values seeded at.
    pub values: usize,
    /// The finest grid's level (None: the starting value alone).
    pub level: Option<u32>,
    /// Two finer levels in a row found nothing new.
    pub converged: bool,
}

/// The finest seeding grid: 2^7 + 1 = 129 values of the second parameter.
pub const MAX_SEED_LEVEL: u32 = 7;

/// A special point that was not followed.
#[derive(Clone, Debug, PartialEq)]
pub struct Skipped {
    /// The special point (the first met).
    pub special: Special,
    /// Why it was not followed.
    pub reason: String,
    /// How many seeds met it (at the same α to 1e-9, with the same reason).
    pub count: usize,
}

/// How far [`curves_with_progress`] has got.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CurvesProgress {
    /// Seed values of the second parameter whose branches are all followed.
    pub seeds_done: usize,
    /// Seed values in all.
    pub seeds: usize,
    /// Curves followed so far.
    pub curves: usize,
}

/// At most this many curves.
pub const MAX_CURVES: usize = 256;

/// Follow every curve reachable from `seeds` in `plane`.
pub fn curves(plane: &Plane, seeds: Seeds) -> Result<Curves, EngineError> {
    curves_with_progress(plane, seeds, &mut |_| {})
}

/// [`curves`], telling `report` after each seed value's branches and after each curve.
pub fn curves_with_progress(
    plane: &Plane,
    seeds: Seeds,
    report: &mut dyn FnMut(CurvesProgress),
) -> Result<Curves, EngineError> {
    plane.check()?;
    let mut out = Curves {
        curves: Vec::new(),
        codim2: Vec::new(),
        skipped: Vec::new(),
        unseeded: Vec::new(),
        seeding: Seeding::default(),
    };
    // The (1, k) birth line, whole, from its closed form: traced, it breaks where the
    // pair is born on a breakpoint.
    if let Seeds::FromFixed { k, .. } = seeds {
        out.curves.extend(birth::birth_curves(plane, k));
    }
    // Seeds at the starting value, then on dyadic grids of the window, finer and finer
    // (a grid of 2^L + 1 values holds the coarser ones), from the first as fine as
    // `count` asks until two finer levels in a row find no new curve: the set found does
    // not depend on `count`, only on how fine it had to go.
    let at = match seeds {
        Seeds::FromFixed { at, .. } | Seeds::Point { at, .. } => at,
    };
    let mut seeded: Vec<f64> = Vec::new();
    let mut seed = |p: f64, total: usize, out: &mut Curves| -> Result<bool, EngineError> {
        if seeded
            .iter()
            .any(|&q| (q - p).abs() <= 1e-12 * plane.scale())
        {
            return Ok(false);
        }
        let done = seeded.len();
        seeded.push(p);
        seed_at(plane, seeds, p, out, &mut |curves| {
            report(CurvesProgress {
                seeds_done: done,
                seeds: total,
                curves,
            })
        })?;
        Ok(true)
    };
    // `count` 1: the starting value only (a quick look, said so in the output).
    let grids = match seeds {
        Seeds::FromFixed { count, .. } if count >= 2 => Some(count),
        _ => None,
    };
    let first = grids.map_or(0, |count| {
        ((count - 1).next_power_of_two().trailing_zeros()).min(MAX_SEED_LEVEL)
    });
    // The values planned so far: the starting one and the first grid.
    let planned = 1 + grids.map_or(0, |_| (1usize << first) + 1);
    seed(at, planned, &mut out)?;
    out.seeding = Seeding {
        values: 1,
        level: None,
        converged: true,
    };
    if grids.is_some() {
        let mut quiet = 0;
        let mut values = 1;
        for level in first..=MAX_SEED_LEVEL {
            let before = out.curves.len();
            let n = 1usize << level;
            let grid: Vec<f64> = (0..=n)
                .map(|i| plane.window.0 + (plane.window.1 - plane.window.0) * i as f64 / n as f64)
                .collect();
            let total = values + grid.len();
            for p in grid {
                if seed(p, total, &mut out)? {
                    values += 1;
                }
            }
            seed_at_double_borders(plane, &mut out);
            dedupe(&mut out, 1e-4 * plane.scale());
            // The first grid itself is not yet evidence of anything.
            if level > first {
                quiet = if out.curves.len() > before {
                    0
                } else {
                    quiet + 1
                };
            }
            out.seeding = Seeding {
                values,
                level: Some(level),
                converged: quiet >= 2,
            };
            if quiet >= 2 {
                break;
            }
        }
    }
    report(CurvesProgress {
        seeds_done: out.seeding.values,
        seeds: out.seeding.values,
        curves: out.curves.len(),
    });
    dedupe(&mut out, 1e-4 * plane.scale());
    codim2_once(&mut out, 1e-6 * plane.scale());
    Ok(out)
}

/// At a double border two border-collision curves of the cycle cross (one impact on
/// each breakpoint): where only the one it was found on is known, the other is followed
/// from there too (it may be too short for any seed value's continuation to meet).
fn seed_at_double_borders(plane: &Plane, out: &mut Curves) {
    let tol = 1e-4 * plane.scale();
    let mut i = 0;
    while i < out.codim2.len() {
        let p = out.codim2[i].clone();
        i += 1;
        let (Codim2Kind::DoubleBorder, Some((impact, breakpoint))) = (p.kind, p.impact) else {
            continue;
        };
        let on = &out.curves[p.curve];
        let crossing = out.curves.iter().enumerate().any(|(j, c)| {
            j != p.curve
                && c.n == on.n
                && c.k == on.k
                && matches!(c.kind, CurveKind::BorderCollision { .. })
                && c.passes_near(p.alpha, p.p, tol)
        });
        if crossing || out.curves.len() >= MAX_CURVES {
            continue;
        }
        // The point of the known curve nearest the double border, as the seed.
        let Some(q) = on.points.iter().min_by(|a, b| {
            (a.alpha - p.alpha)
                .hypot(a.p - p.p)
                .total_cmp(&(b.alpha - p.alpha).hypot(b.p - p.p))
        }) else {
            continue;
        };
        let special = Special {
            kind: Kind::BorderCollision,
            alpha: q.alpha,
            phase: breakpoint,
            impact,
            point: q.cycle.clone(),
            collision: None,
            last_step: None,
        };
        let kind = CurveKind::BorderCollision { impact, breakpoint };
        let index = out.curves.len();
        match follow(plane, kind, &special, q.p, index) {
            Ok((curve, codim2)) if curve.points.len() >= 2 => {
                out.curves.push(curve);
                out.codim2.extend(codim2);
            }
            _ => {}
        }
    }
}

/// Note a special point not followed, once per point and reason.
/// Seed at value `p` of the second parameter: the one-parameter continuation from
/// `seeds`' start there, and every special point it finds followed as a curve (unless a
/// curve already found passes through it). `report` hears how many curves there are
/// after each.
fn seed_at(
    plane: &Plane,
    seeds: Seeds,
    p: f64,
    out: &mut Curves,
    report: &mut dyn FnMut(usize),
) -> Result<(), EngineError> {
    report(out.curves.len());
    plane.second.limit().check(p)?;
    let (table, r) = match plane.second {
        SweepParam::D => (Table::fd(p)?, plane.r),
        _ => (plane.table.clone(), p),
    };
    let (start, max_period) = match seeds {
        Seeds::FromFixed { k, max_period, .. } => (Start::Fixed { k }, max_period),
        Seeds::Point { n, k, t0, v0, .. } => (Start::Point { n, k, t0, v0 }, n),
    };
    let opts = Options {
        max_period,
        ..Options::default()
    };
    let found = match branches(&table, r, plane.alpha, start, opts) {
        Ok(found) => found,
        Err(e) => {
            out.unseeded.push((p, e.to_string()));
            return Ok(());
        }
    };
    for b in &found {
        let ends = [&b.begin, &b.end];
        let specials = b.specials.iter().chain(ends.into_iter().filter(|s| {
            matches!(
                s.kind,
                Kind::BorderCollision | Kind::Grazing | Kind::Fold | Kind::StickingOnset
            )
        }));
        for s in specials {
            let kind = match s.kind {
                Kind::PeriodDoubling => CurveKind::PeriodDoubling,
                Kind::Fold => CurveKind::Fold,
                Kind::BorderCollision => CurveKind::BorderCollision {
                    impact: s.impact,
                    breakpoint: s.phase,
                },
                Kind::Grazing => CurveKind::Grazing,
                Kind::StickingOnset => CurveKind::StickingOnset,
                _ => continue,
            };
            // A doubled branch's birth is its parent's period doubling.
            if s.kind == Kind::PeriodDoubling && s.point.n != b.n {
                continue;
            }
            // The (1, k) pair's birth is the closed-form line.
            if s.point.n == 1 && matches!(s.kind, Kind::Fold | Kind::BorderCollision) {
                let k = s.point.k;
                if let Some((ab, _)) = birth::alpha_birth(&table, r, k) {
                    if (s.alpha - ab).abs() <= 1e-7 * (1.0 + ab) {
                        if !out
                            .curves
                            .iter()
                            .any(|c| c.kind == CurveKind::Birth && c.k == k)
                        {
                            out.curves.extend(birth::birth_curves(plane, k));
                        }
                        continue;
                    }
                }
            }
            // Within the chord error of the largest step of a curve already found.
            let tol = 1e-4 * plane.scale();
            let same = |c: &Curve| {
                c.n == s.point.n
                    && c.k == s.point.k
                    && c.kind.as_str() == kind.as_str()
                    && c.passes_near(s.alpha, p, tol)
            };
            if out.curves.iter().any(same) {
                continue;
            }
            if out.curves.len() >= MAX_CURVES {
                skip(
                    &mut out.skipped,
                    s,
                    format!("more than {MAX_CURVES} curves"),
                );
                continue;
            }
            let index = out.curves.len();
            match follow(plane, kind, s, p, index) {
                // A seed the tracer could not leave is no curve.
                Ok((curve, _)) if curve.points.len() < 2 => skip(
                    &mut out.skipped,
                    s,
                    format!(
                        "the curve could not be followed beyond its seed ({}, {})",
                        curve.ends[0].as_str(),
                        curve.ends[1].as_str()
                    ),
                ),
                Ok((curve, codim2)) => {
                    out.curves.push(curve);
                    out.codim2.extend(codim2);
                }
                Err(why) => skip(&mut out.skipped, s, why),
            }
            report(out.curves.len());
        }
    }
    Ok(())
}

fn skip(list: &mut Vec<Skipped>, s: &Special, reason: String) {
    let same = |k: &Skipped| {
        k.reason == reason
            && k.special.kind == s.kind
            && k.special.point.n == s.point.n
            && k.special.point.k == s.point.k
            && (k.special.alpha - s.alpha).abs() <= 1e-9 * (1.0 + s.alpha.abs())
    };
    match list.iter_mut().find(|k| same(k)) {
        Some(k) => k.count += 1,
        None => list.push(Skipped {
            special: s.clone(),
            reason,
            count: 1,
        }),
    }
}

/// Each codimension-two point once: points of one kind within `tol` of each other (the
/// same point located on two curves, or twice on one) are one, the best located kept
/// (the smaller condition); each then lists every curve passing through it.
fn codim2_once(out: &mut Curves, tol: f64) {
    let mut kept: Vec<Codim2> = Vec::new();
    for p in std::mem::take(&mut out.codim2) {
        let twin = kept
            .iter_mut()
            .find(|q| q.kind == p.kind && (q.alpha - p.alpha).hypot(q.p - p.p) <= tol);
        match twin {
            Some(q) => {
                if p.condition.abs() < q.condition.abs() {
                    let meets = std::mem::take(&mut q.meets);
                    *q = p;
                    q.meets = meets;
                }
            }
            None => kept.push(p),
        }
    }
    for p in &mut kept {
        let mut meets = vec![p.curve];
        for (i, c) in out.curves.iter().enumerate() {
            if i != p.curve && c.passes_near(p.alpha, p.p, 100.0 * tol) {
                meets.push(i);
            }
        }
        p.meets = meets;
    }
    out.codim2 = kept;
}

/// `a` extended by the part of `b` beyond one of its ends, where `b` runs along `a` for
/// at least a fifth of its points and leaves it only at its own start or end, from a
/// point near an end of `a` (None otherwise: two curves that cross, or touch).
fn join(a: &Curve, b: &Curve, tol: f64) -> Option<Curve> {
    let covered: Vec<bool> = b
        .points
        .iter()
        .map(|q| a.passes_near(q.alpha, q.p, tol))
        .collect();
    let count = covered.iter().filter(|c| **c).count();
    if count * 5 < b.points.len() || count == b.points.len() {
        return None;
    }
    let first = covered.iter().position(|c| *c)?;
    let last = covered.iter().rposition(|c| *c)?;
    // Covered in one stretch: the rest is a run before it, after it, or both.
    if covered[first..=last].iter().any(|c| !c) {
        return None;
    }
    let near = |q: &CurvePoint, r: &CurvePoint| (q.alpha - r.alpha).hypot(q.p - r.p) <= 10.0 * tol;
    let mut out = a.clone();
    for (run, at_b_start) in [(&b.points[..first], true), (&b.points[last + 1..], false)] {
        if run.is_empty() {
            continue;
        }
        // The covered point next to the run, and the end of `a` it is near.
        let joint = if at_b_start {
            &b.points[first]
        } else {
            &b.points[last]
        };
        let end_kind = b.ends[if at_b_start { 0 } else { 1 }];
        // The run, ordered away from the joint.
        let away: Vec<CurvePoint> = if at_b_start {
            run.iter().rev().cloned().collect()
        } else {
            run.to_vec()
        };
        if near(joint, out.points.last()?) {
            out.points.extend(away);
            out.ends[1] = end_kind;
        } else if near(joint, &out.points[0]) {
            let mut pts: Vec<CurvePoint> = away.into_iter().rev().collect();
            pts.append(&mut out.points);
            out.points = pts;
            out.ends[0] = end_kind;
        } else {
            return None;
        }
    }
    Some(out)
}

/// Drop a curve that another of the same kind and cycle covers (seeded at two values of
/// the second parameter, the shorter may be a piece of the longer): every tenth of its
/// points lies within `tol` of the other. Its codimension-two points go to the other.
fn dedupe(out: &mut Curves, tol: f64) {
    let n = out.curves.len();
    let mut into: Vec<Option<usize>> = vec![None; n];
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (&out.curves[i], &out.curves[j]);
            if i == j
                || into[j].is_some()
                || a.n != b.n
                || a.k != b.k
                || a.kind.as_str() != b.kind.as_str()
                || (b.points.len(), j) < (a.points.len(), i)
            {
                continue;
            }
            let step = (a.points.len() / 10).max(1);
            if a.points
                .iter()
                .step_by(step)
                .all(|q| b.passes_near(q.alpha, q.p, tol))
            {
                into[i] = Some(j);
                break;
            }
            // A piece that runs along the other and then beyond one of its ends (the
            // same curve followed from two seeds, each stopped elsewhere): its part
            // beyond is joined to that end.
            if let Some(joined) = join(b, a, tol) {
                out.curves[j] = joined;
                into[i] = Some(j);
                break;
            }
        }
    }
    let mut index = vec![0usize; n];
    let mut kept = 0;
    for i in 0..n {
        if into[i].is_none() {
            index[i] = kept;
            kept += 1;
        }
    }
    for p in &mut out.codim2 {
        let mut c = p.curve;
        while let Some(j) = into[c] {
            c = j;
        }
        p.curve = index[c];
    }
    let mut i = 0;
    out.curves.retain(|_| {
        i += 1;
        into[i - 1].is_none()
    });
}
