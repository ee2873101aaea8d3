//! Two-parameter bifurcation curves: the period doublings, folds, border collisions and
//! grazings of an (n, k) cycle followed through the plane of α and a second parameter
//! (r, or D of the F_D family), with the codimension-two points met on the way.
//!
//! # For front ends
//! [`curves`] takes a [`Plane`] (the table, r, the α window and the second parameter's
//! window) and a [`Seeds`] choice, runs the one-parameter continuation
//! ([`crate::orbits::continuation::branches`]) at each seed value of the second parameter, and follows
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
//!   cycle's flights (a flight touching the table: beyond, the cycle gains an impact),
//!   or, seen from the other side, the smallest relative impact velocity (a landing
//!   turning tangential: beyond, the cycle loses that impact).
//!
//! There is no curve of an onset of sticking. A flight touches the table tangentially
//! (at a landing, or inside it) only where its height above the table, h ≥ 0 with
//! h = h' = 0 there, has h'' = −1 − αF'' ≥ 0: where the table accelerates downwards at
//! least as fast as gravity. There the touching ball leaves the table at once; a stick
//! needs αF'' > −1. So the impact velocity of a regular (n, k) cycle vanishes only at a
//! grazing, never where a stick begins (a low hop would need a launch velocity r|u|
//! that vanishes with the landing before it, back to a flight of finite length). The
//! case αF'' = −1 exactly is of codimension two.
//!
//! The cycle is solved exactly at each (α, p) by Newton's method on the map
//! ([`crate::orbits::periodic::cycle`], re-verified by the 1e-11 return), warm-started from the
//! previous point, so the curve G(α, p) = 0 is a curve in the plane. It is followed by
//! pseudo-arclength continuation: a predictor along the tangent (orthogonal to ∇G, by
//! central differences of G with the cycle re-solved) and Newton's method on
//! (G = 0, τ·(y − y₀) = h). Every accepted point has |G| below [`CONDITION_TOLERANCE`],
//! or, where G is so steep that the numbers cannot resolve that, below its rounding
//! floor ([`CurvePoint::floor`]); both values are kept as the evidence. A step the corrector cannot take, or one whose
//! cycle jumped (an impact phase or velocity moving far more than the step), is halved;
//! below the smallest step the curve ends with the reason the cycle gives (grazing, a
//! stick, no convergence). A corrected point must be the guessed cycle moved on: not
//! the cycle of half its period run twice (a doubled cycle next to its birth), not
//! farther from the predicted point than the step (another part of the curve), and
//! not across a breakpoint whose crossing cannot be located on the curve (the other arm
//! of a cusp). The slope of G is taken within the pieces the cycle's impacts lie in:
//! next to a breakpoint a difference may cross it, and beyond, G is another function.
//! A border-collision curve reaching a double border goes on through it: the point
//! beyond, where the other impact has crossed into the next piece, is solved on small
//! circles round the corner, and the curve must get under way from there, or it ends at
//! the corner. Where a step would leave the search range (the α window widened on
//! either side), the point on its edge is solved instead and the curve ends there; the
//! set is then cut to the window, each cut end solved on the window's edge.
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
//! * this file: the plane, the kinds of curves, ends and codimension-two points, the
//!   seeds and what [`curves`] returns;
//! * `find.rs`: finding the set ([`curves`]): the seed grids refined until no new curve
//!   appears, the one-parameter continuation at each seed value, the other border
//!   collision through each double border;
//! * `merge.rs`: curves found twice made one, codimension-two points told once;
//! * `sides.rs`: the PD and fold curves ending on a border-collision curve from either
//!   side, watched for along it (one may be too short for any seed value to meet);
//! * `clip.rs`: the set, seeded and followed over the α window widened by
//!   [`SEARCH_MARGIN`] on either side ([`Plane::search_alpha`]), cut to the window;
//! * `trace.rs`: following one curve (the corrector at fixed parameters or on the
//!   extended system, the test functions watched between points, the ends);
//! * [`birth`]: the (1, k) birth line in closed form;
//! * `criticality.rs`: the flip's normal-form coefficient ([`criticality()`]).

pub mod birth;
mod clip;
mod corrector;
mod criticality;
mod cusp;
mod ends;
mod find;
mod merge;
mod sides;
mod stops;
mod trace;

pub use criticality::criticality;
pub use ends::EndEvidence;
pub use find::{curves, curves_with_progress};

use super::continuation::Special;
use super::events::jump_phases;
use super::manifold::segment_distance;
use super::periodic::{min_interior_gap, CyclePoint, PassError};
use crate::error::EngineError;
use crate::jobs::grid::SweepParam;
use crate::system::System;
use crate::table::Table;
use crate::time::signed_distance;

/// An accepted curve point satisfies its condition to this.
pub const CONDITION_TOLERANCE: f64 = 1e-9;
/// A curve that cannot go on with an impact this close to a breakpoint (in phase)
/// ends at that border.
pub const BORDER_REACH: f64 = 1e-5;
/// Steps per direction of one curve.
pub const MAX_STEPS: usize = 2000;
/// Curves are followed over the α window widened by this share of its width on each
/// side, and cut to the window after: a curve may reach the window only through a
/// codimension-two point beyond its edge, or from a branch the continuation meets only
/// there, and a window inside another must show what the wider one shows in it.
pub const SEARCH_MARGIN: f64 = 0.5;

/// The plane the curves live in: α on one axis, r or D on the other.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// The table (for `second` a parameter of its family, that parameter is replaced).
    pub table: Table,
    /// r (replaced when `second` is r).
    pub r: f64,
    /// The α window.
    pub alpha: (f64, f64),
    /// The second parameter: [`SweepParam::R`] or a parameter of the table's family
    /// (F_D's [`SweepParam::D`]).
    pub second: SweepParam,
    /// Its window.
    pub window: (f64, f64),
}

impl Plane {
    /// Check the plane: windows ordered and inside the parameters' ranges, a family
    /// parameter only of the table's family.
    pub fn check(&self) -> Result<(), EngineError> {
        let bad = EngineError::Inconsistent;
        if self.second == SweepParam::Alpha {
            return Err(bad(format!(
                "the second parameter of a curve must be one of {}, not alpha",
                SweepParam::names(&self.table).trim_start_matches("alpha, ")
            )));
        }
        // The tracer follows impacts to breakpoints at fixed phases: a parameter that
        // moves a breakpoint cannot be the second axis (yet).
        if let SweepParam::Table(n) = self.second {
            if let Some((fam, _)) = self.table.family() {
                let moved = fam
                    .param_index(n.as_str())
                    .and_then(|i| fam.breakpoint_moved_by(i));
                if let Some(piece) = moved {
                    return Err(bad(format!(
                        "curves along {n}: the table's piece {piece} starts at a phase that moves with {n}, and curves are followed with fixed breakpoints: valid a parameter the breakpoints do not depend on (sweeps and planes over {n} are exact)",
                        n = n.as_str()
                    )));
                }
            }
        }
        for (param, (lo, hi)) in [(SweepParam::Alpha, self.alpha), (self.second, self.window)] {
            param.check(&self.table, lo)?;
            param.check(&self.table, hi)?;
            if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
                return Err(bad(format!("the {param} window needs LO < HI")));
            }
        }
        // A file's family may stop being C¹ inside the window: checked at 101 values in
        // order, the first that fails refused (built-in families are C¹ throughout).
        if self.second.is_table() && self.table.family().is_some_and(|(f, _)| !f.is_builtin()) {
            let (lo, hi) = self.window;
            for i in 0..=100 {
                let v = crate::jobs::grid::grid_value(lo, hi, 101, i);
                self.second.table(&self.table, v)?;
            }
        }
        Ok(())
    }

    /// The system at (α, p).
    pub fn system(&self, alpha: f64, p: f64) -> Result<System, EngineError> {
        self.second.system(&self.table, alpha, self.r, p)
    }

    /// The phases where f'' jumps on the plane near `p`: those of the table at `p`,
    /// and for a family parameter also at the window's ends and middle (F_1 is C² at
    /// ½ where the other F_D are not: a curve crossing D = 1 still meets ½).
    fn jumps(&self, p: f64) -> Vec<f64> {
        let mut out = if self.second.is_table() {
            let (lo, hi) = self.window;
            [lo, 0.5 * (lo + hi), hi, p]
                .iter()
                .filter_map(|&v| self.second.table(&self.table, v).ok())
                .flat_map(|t| jump_phases(&t))
                .collect()
        } else {
            jump_phases(&self.table)
        };
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }

    /// Whether y lies in the range the curves are followed over (the search range).
    fn inside(&self, y: [f64; 2]) -> bool {
        self.spans(self.search_alpha(), y, 0.0)
    }

    /// Whether y lies in the α range `alpha` and the second parameter's window, to `tol`.
    fn spans(&self, alpha: (f64, f64), y: [f64; 2], tol: f64) -> bool {
        y[0] >= alpha.0 - tol
            && y[0] <= alpha.1 + tol
            && y[1] >= self.window.0 - tol
            && y[1] <= self.window.1 + tol
    }

    /// The α range curves are followed over and seeded in: the α window widened by
    /// [`SEARCH_MARGIN`] of its width on each side (not below half its lower end, nor
    /// beyond α's range); what is found is then cut to the window.
    pub fn search_alpha(&self) -> (f64, f64) {
        let (lo, hi) = self.alpha;
        let w = SEARCH_MARGIN * (hi - lo);
        (
            (lo - w).max(0.5 * lo),
            (hi + w).min(crate::limits::ALPHA.hi),
        )
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
    /// A flight touches the table: inside the flight (`landing` false: its smallest
    /// height above the table reaches zero), or at its landing (`landing` true: the
    /// relative impact velocity reaches zero). Either way α F'' ≤ −1 there, so the
    /// ball leaves the table at once (see the module's note on sticking).
    Grazing {
        /// Whether the touching is a landing turning tangential.
        landing: bool,
    },
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
            CurveKind::Grazing { .. } => "grazing",
            CurveKind::Birth => "birth",
        }
    }

    /// Whether two curves of these kinds (of one cycle) follow the same condition, so
    /// that lying close together they are one curve: the same kind, and for border
    /// collisions the same breakpoint (which impact is on it is counted from where
    /// each curve happens to launch its cycle, so it is not compared), for grazings the
    /// same flight (a landing, or one touching inside).
    pub fn same_condition(&self, other: &CurveKind) -> bool {
        match (self, other) {
            (
                CurveKind::BorderCollision { breakpoint: a, .. },
                CurveKind::BorderCollision { breakpoint: b, .. },
            ) => a == b,
            (CurveKind::Grazing { landing: a }, CurveKind::Grazing { landing: b }) => a == b,
            (a, b) => a.as_str() == b.as_str(),
        }
    }

    /// Whether impact `other` reaching the breakpoint `at` beside this border
    /// collision's impact, on its cycle `pt`, is the cycle collapsing onto the one of
    /// half its period, which is no double border: in a doubled cycle whose halves are
    /// close ([`corrector::near_birth`]), the impact half a cycle on, on the same
    /// breakpoint. (With its halves apart, the two impacts on one breakpoint are a
    /// double border like any other.)
    fn twin(&self, pt: &CyclePoint, (other, at): (usize, f64)) -> bool {
        let n = pt.n;
        matches!(*self, CurveKind::BorderCollision { impact, breakpoint }
            if breakpoint == at && n.is_multiple_of(2) && (other + n / 2) % n == impact)
            && corrector::near_birth(pt)
    }

    /// Short label (as in the one-parameter diagrams).
    pub fn label(&self) -> &'static str {
        match self {
            CurveKind::PeriodDoubling => "PD",
            CurveKind::Fold => "F",
            CurveKind::BorderCollision { .. } => "BC",
            CurveKind::Grazing { .. } => "G",
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
            CurveKind::Grazing { landing: true } => pt.min_impact_speed,
            CurveKind::Birth => {
                sys.alpha() * birth::max_slope(sys.table()).0 - birth::slope_at_birth(sys.r(), pt.k)
            }
            CurveKind::Grazing { landing: false } => {
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
    /// The condition's value there (the evidence: |G| ≤ [`CONDITION_TOLERANCE`], or
    /// ≤ `floor` where that is larger).
    pub condition: f64,
    /// Where |G| exceeds [`CONDITION_TOLERANCE`]: its rounding floor there, how much G
    /// changes when α, p (and for the extended system t₀, v₀) each move by 1e-14 of
    /// themselves (plus one), summed. Where G is that steep (a cycle whose monodromy
    /// has large entries, its trace their small difference), |G| is held to the floor
    /// instead: the point then lies within 1e-14 of itself of where G vanishes, as
    /// close as the numbers resolve. None where |G| holds to the tolerance.
    pub floor: Option<f64>,
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
    /// A fold curve turns back on itself in the plane, tangentially: two fold curves
    /// meet, and three cycles coalesce (the pair of one fold and the pair of the other
    /// share their middle cycle).
    Cusp,
}

impl Codim2Kind {
    /// The end a curve makes where it stops at such a point: a collapse there, a
    /// border at the others; none at a degenerate flip (the curve goes on through it).
    pub fn end(self) -> Option<CurveEnd> {
        match self {
            Codim2Kind::Collapse => Some(CurveEnd::Collapse),
            Codim2Kind::DegenerateFlip | Codim2Kind::Cusp => None,
            _ => Some(CurveEnd::Border),
        }
    }

    /// Name in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            Codim2Kind::PdBorder => "pd_border",
            Codim2Kind::FoldBorder => "fold_border",
            Codim2Kind::DoubleBorder => "double_border",
            Codim2Kind::DegenerateFlip => "degenerate_flip",
            Codim2Kind::GrazingBorder => "grazing_border",
            Codim2Kind::Collapse => "collapse",
            Codim2Kind::Cusp => "cusp",
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
            Codim2Kind::Cusp => "cusp (two folds meet, three cycles coalesce)",
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
        let y = [alpha, p];
        let d = |a: &CurvePoint| (a.alpha - alpha).hypot(a.p - p);
        self.points.iter().any(|q| d(q) <= tol)
            || self
                .points
                .windows(2)
                .any(|w| segment_distance(y, [w[0].alpha, w[0].p], [w[1].alpha, w[1].p]) <= tol)
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
    /// The second parameter's value the curves are started from.
    pub fn at(&self) -> f64 {
        match *self {
            Seeds::FromFixed { at, .. } | Seeds::Point { at, .. } => at,
        }
    }

    /// k of the (1, k) solution, or of the (n, k) cycle.
    pub fn k(&self) -> u32 {
        match *self {
            Seeds::FromFixed { k, .. } | Seeds::Point { k, .. } => k,
        }
    }

    /// How many values of the second parameter are seeded at (1 for a cycle's branch).
    pub fn count(&self) -> usize {
        match *self {
            Seeds::FromFixed { count, .. } => count,
            Seeds::Point { .. } => 1,
        }
    }

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

/// A point of a curve of this kind and (n, k) where its steps failed and no point
/// ahead was found (`Tracer::ahead`): the same curve traced again from another seed
/// does not search there again.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct DeadEnd {
    pub(super) kind: CurveKind,
    pub(super) n: usize,
    pub(super) k: u32,
    pub(super) at: [f64; 2],
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
    /// The finer levels at the end that found nothing new (0: the last found a curve,
    /// or no level was finer than the first).
    pub quiet: u32,
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

#[cfg(test)]
mod tests {
    use super::CurveKind;

    #[test]
    fn border_collisions_at_other_breakpoints_are_other_conditions() {
        let bc = |impact, breakpoint| CurveKind::BorderCollision { impact, breakpoint };
        // Which impact is on the breakpoint depends on where the cycle is launched.
        assert!(bc(3, 0.5).same_condition(&bc(6, 0.5)));
        // A collision with another breakpoint is another condition, however close.
        assert!(!bc(3, 0.0).same_condition(&bc(3, 0.5)));
        let graze = |landing| CurveKind::Grazing { landing };
        assert!(!graze(true).same_condition(&graze(false)));
        assert!(CurveKind::Fold.same_condition(&CurveKind::Fold));
        assert!(!CurveKind::Fold.same_condition(&CurveKind::PeriodDoubling));
    }
}
