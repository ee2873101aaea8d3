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

use super::continuation::{branches, Kind, Options, Special, Start};
use super::events::jump_phases;
use super::periodic::{cycle, map_for, min_interior_gap, pass, CyclePoint, PassError};
use super::roots::bracketed_root_nan;
use crate::error::EngineError;
use crate::grid::SweepParam;
use crate::linalg::solve;
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

/// The curves and their codimension-two points.
#[derive(Clone, Debug, PartialEq)]
pub struct Curves {
    /// Every curve followed.
    pub curves: Vec<Curve>,
    /// Codimension-two points located on them.
    pub codim2: Vec<Codim2>,
    /// Special points that were not followed, with the reason (a seed the corrector
    /// could not solve, e.g. a grazing cycle that cannot be solved at the grazing).
    pub skipped: Vec<(Special, String)>,
}

/// At most this many curves.
pub const MAX_CURVES: usize = 256;

/// Follow every curve reachable from `seeds` in `plane`.
pub fn curves(plane: &Plane, seeds: Seeds) -> Result<Curves, EngineError> {
    plane.check()?;
    let mut out = Curves {
        curves: Vec::new(),
        codim2: Vec::new(),
        skipped: Vec::new(),
    };
    let values: Vec<f64> = match seeds {
        Seeds::FromFixed { at, count, .. } if count <= 1 => vec![at],
        Seeds::FromFixed { at, count, .. } => std::iter::once(at)
            .chain((0..count).map(|i| {
                plane.window.0 + (plane.window.1 - plane.window.0) * i as f64 / (count - 1) as f64
            }))
            .collect(),
        Seeds::Point { at, .. } => vec![at],
    };
    for p in values {
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
        let Ok(found) = branches(&table, r, plane.alpha, start, opts) else {
            continue;
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
                    out.skipped
                        .push((s.clone(), format!("more than {MAX_CURVES} curves")));
                    continue;
                }
                let index = out.curves.len();
                match follow(plane, kind, s, p, index) {
                    Ok((curve, codim2)) => {
                        out.curves.push(curve);
                        out.codim2.extend(codim2);
                    }
                    Err(why) => out.skipped.push((s.clone(), why)),
                }
            }
        }
    }
    dedupe(&mut out, 1e-4 * plane.scale());
    Ok(out)
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

/// The cycle and the condition at a point of the plane.
#[derive(Clone, Debug)]
struct Eval {
    y: [f64; 2],
    pt: CyclePoint,
    g: f64,
}

struct Tracer<'a> {
    plane: &'a Plane,
    kind: CurveKind,
    n: usize,
    k: u32,
    jumps: Vec<f64>,
}

impl Tracer<'_> {
    fn eval(&self, y: [f64; 2], guess: &CyclePoint) -> Result<Eval, PassError> {
        let sys = self
            .plane
            .system(y[0], y[1])
            .map_err(|_| PassError::BadLaunch)?;
        let pt = cycle(&sys, self.n, self.k, guess.t0, guess.velocities[0])?;
        // The same cycle, not another one nearby: the launch moved continuously.
        let moved = signed_distance(pt.phases[0], guess.phases[0]).abs().max(
            (pt.velocities[0] - guess.velocities[0]).abs() / (1.0 + guess.velocities[0].abs()),
        );
        if moved > 0.05 {
            return Err(PassError::NoConvergence);
        }
        let g = self.kind.condition(&sys, &pt);
        if !g.is_finite() {
            return Err(PassError::NoConvergence);
        }
        Ok(Eval { y, pt, g })
    }

    /// ∇G by central differences, the cycle re-solved at each.
    fn gradient(&self, e: &Eval) -> Result<[f64; 2], PassError> {
        let mut grad = [0.0; 2];
        for (i, g) in grad.iter_mut().enumerate() {
            let h = 1e-7 * (1.0 + e.y[i].abs());
            let mut plus = e.y;
            let mut minus = e.y;
            plus[i] += h;
            minus[i] -= h;
            // One-sided at the end of the parameter's range (D = 0 or 1).
            let valid = |y: [f64; 2]| self.plane.system(y[0], y[1]).is_ok();
            // A border collision's condition has its kink on the curve itself (f''
            // jumps where the impact crosses the breakpoint): its slope is taken on
            // the point's side, or Newton's method converges only linearly.
            if matches!(self.kind, CurveKind::BorderCollision { .. }) && e.g != 0.0 {
                let same = |y: [f64; 2]| -> Result<Option<f64>, PassError> {
                    if !valid(y) {
                        return Ok(None);
                    }
                    let gy = self.eval(y, &e.pt)?.g;
                    Ok(((gy < 0.0) == (e.g < 0.0) && gy != 0.0).then_some(gy))
                };
                if let Some(gp) = same(plus)? {
                    *g = (gp - e.g) / h;
                    continue;
                }
                if let Some(gm) = same(minus)? {
                    *g = (e.g - gm) / h;
                    continue;
                }
            }
            // Central where the cycle exists on both sides; one-sided at the end of the
            // parameter's range (D = 0 or 1) or where the cycle ends on one side (at a
            // grazing the flight would cross the table beyond the curve).
            let at = |y: [f64; 2]| valid(y).then(|| self.eval(y, &e.pt).ok()).flatten();
            *g = match (at(plus), at(minus)) {
                (Some(p), Some(m)) => (p.g - m.g) / (2.0 * h),
                (Some(p), None) => (p.g - e.g) / h,
                (None, Some(m)) => (e.g - m.g) / h,
                (None, None) => return Err(PassError::NoConvergence),
            };
        }
        if !(grad[0].is_finite() && grad[1].is_finite()) || grad == [0.0, 0.0] {
            return Err(PassError::NoConvergence);
        }
        Ok(grad)
    }

    /// Newton's method on (G = 0, c·y = d) from `y`.
    fn correct(
        &self,
        y: [f64; 2],
        c: [f64; 2],
        d: f64,
        guess: &CyclePoint,
    ) -> Result<(Eval, [f64; 2]), PassError> {
        if self.kind == CurveKind::Fold {
            return self.correct_fold(y, c, d, guess);
        }
        let mut e = self.eval(y, guess)?;
        for _ in 0..20 {
            let grad = self.gradient(&e)?;
            let a = [grad, c];
            let b = [e.g, c[0] * e.y[0] + c[1] * e.y[1] - d];
            let step = solve(a, b).ok_or(PassError::NoConvergence)?;
            let size = step[0].abs().max(step[1].abs());
            if !size.is_finite() || size > 0.5 {
                return Err(PassError::NoConvergence);
            }
            // Backtracking: where the full step leaves the cycle's domain (a grazing or
            // a vanishing impact velocity beyond the curve), shorter ones approach the
            // curve from its own side.
            let mut lambda = 1.0;
            let next = loop {
                let yn = [e.y[0] - lambda * step[0], e.y[1] - lambda * step[1]];
                match self.eval(yn, &e.pt) {
                    Ok(n) => break n,
                    Err(err) if lambda < 1e-3 => return Err(err),
                    Err(_) => lambda *= 0.5,
                }
            };
            e = next;
            // Converged when the step is at rounding level, or when both equations
            // already hold to it (at a border the gradient has a kink, and Newton's
            // method creeps the last digits). The cycle is solved to about 1e-14, so G
            // is known to about 1e-13: the point is taken to 1e-12.
            let tiny = 1e-12 * (1.0 + e.y[0].abs().max(e.y[1].abs()));
            let held = e.g.abs() < 1e-12 && (c[0] * e.y[0] + c[1] * e.y[1] - d).abs() < tiny;
            if lambda * size < tiny || held {
                if e.g.abs() > CONDITION_TOLERANCE {
                    return Err(PassError::NoConvergence);
                }
                let grad = self.gradient(&e)?;
                return Ok((e, grad));
            }
        }
        Err(PassError::NoConvergence)
    }

    /// The fold's extended system at x = (α, p, t₀, v₀): the cycle's residual
    /// (tₙ − t₀ − k, vₙ − v₀) and 1 − tr M + r²ⁿ, with the pass.
    fn fold_system(&self, x: [f64; 4]) -> Result<([f64; 3], super::periodic::Pass), PassError> {
        let sys = self
            .plane
            .system(x[0], x[1])
            .map_err(|_| PassError::BadLaunch)?;
        let mut map = map_for(&sys);
        let p = pass(&mut map, x[2], x[3], self.n, self.k)?;
        let tr = p.monodromy[0][0] + p.monodromy[1][1];
        let g = 1.0 - tr + sys.r().powi(2 * self.n as i32);
        Ok(([p.residual[0], p.residual[1], g], p))
    }

    /// Newton's method on the fold's extended system (the cycle's equations and the
    /// fold condition, in α, p, t₀, v₀) with c·(α, p) = d: at a fold the cycle cannot
    /// be solved at fixed parameters (M − I is singular), so it is solved with them.
    /// The map's own derivatives give the cycle equations' columns in α, t₀ and v₀;
    /// forward differences give the p column and the fold condition's row.
    fn correct_fold(
        &self,
        y: [f64; 2],
        c: [f64; 2],
        d: f64,
        guess: &CyclePoint,
    ) -> Result<(Eval, [f64; 2]), PassError> {
        let mut x = [y[0], y[1], guess.t0, guess.velocities[0]];
        let jacobian = |x: [f64; 4], f: [f64; 3], p: &super::periodic::Pass| {
            let m = p.monodromy;
            let mut j = [
                [p.alpha_column[0], 0.0, m[0][0] - 1.0, m[0][1]],
                [p.alpha_column[1], 0.0, m[1][0], m[1][1] - 1.0],
                [0.0; 4],
            ];
            for col in 0..4 {
                let h = 1e-7 * (1.0 + x[col].abs());
                let mut xp = x;
                xp[col] += h;
                let (fp, _) = self.fold_system(xp)?;
                j[2][col] = (fp[2] - f[2]) / h;
                if col == 1 {
                    j[0][1] = (fp[0] - f[0]) / h;
                    j[1][1] = (fp[1] - f[1]) / h;
                }
            }
            Ok::<_, PassError>(j)
        };
        for _ in 0..30 {
            let (f, p) = self.fold_system(x)?;
            let j = jacobian(x, f, &p)?;
            let a = [j[0], j[1], j[2], [c[0], c[1], 0.0, 0.0]];
            let b = [f[0], f[1], f[2], c[0] * x[0] + c[1] * x[1] - d];
            let step = solve(a, b).ok_or(PassError::NoConvergence)?;
            let size = step.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if !size.is_finite() || size > 0.5 {
                return Err(PassError::NoConvergence);
            }
            for i in 0..4 {
                x[i] -= step[i];
            }
            if size < 1e-12 * (1.0 + x[3].abs()) {
                let (f, p) = self.fold_system(x)?;
                if f[2].abs() > CONDITION_TOLERANCE {
                    return Err(PassError::NoConvergence);
                }
                let sys = self
                    .plane
                    .system(x[0], x[1])
                    .map_err(|_| PassError::BadLaunch)?;
                let pt = super::periodic::accept(&sys, [x[0], x[2], x[3]], self.n, self.k, &p)?;
                // The curve's tangent in (α, p): the null vector of the extended
                // system's Jacobian, normalised on (α, p); returned as the gradient it is
                // orthogonal to.
                let j = jacobian(x, f, &p)?;
                let a = [j[0], j[1], j[2], [1.0, 0.0, 0.0, 0.0]];
                let a2 = [j[0], j[1], j[2], [0.0, 1.0, 0.0, 0.0]];
                let t = solve(a, [0.0, 0.0, 0.0, 1.0])
                    .filter(|t| t.iter().all(|v| v.is_finite()))
                    .or_else(|| solve(a2, [0.0, 0.0, 0.0, 1.0]))
                    .ok_or(PassError::NoConvergence)?;
                let e = Eval {
                    y: [x[0], x[1]],
                    pt,
                    g: f[2],
                };
                return Ok((e, [t[1], -t[0]]));
            }
        }
        Err(PassError::NoConvergence)
    }

    /// Distances of every impact to every breakpoint, except the curve's own.
    fn border_tests(&self, pt: &CyclePoint) -> Vec<f64> {
        let own = match self.kind {
            CurveKind::BorderCollision { impact, breakpoint } => Some((impact, breakpoint)),
            _ => None,
        };
        let mut out = Vec::with_capacity(pt.n * self.jumps.len());
        for (i, &ph) in pt.phases.iter().enumerate() {
            for &b in &self.jumps {
                out.push(if own == Some((i, b)) {
                    1.0
                } else {
                    signed_distance(ph, b)
                });
            }
        }
        out
    }

    fn point(&self, e: Eval) -> CurvePoint {
        let criticality = (self.kind == CurveKind::PeriodDoubling)
            .then(|| self.plane.system(e.y[0], e.y[1]).ok())
            .flatten()
            .and_then(|sys| criticality(&sys, &e.pt));
        CurvePoint {
            alpha: e.y[0],
            p: e.y[1],
            cycle: e.pt,
            condition: e.g,
            criticality,
        }
    }
}

fn tangent(grad: [f64; 2], along: [f64; 2]) -> [f64; 2] {
    let s = grad[0].hypot(grad[1]);
    let t = [-grad[1] / s, grad[0] / s];
    if t[0] * along[0] + t[1] * along[1] < 0.0 {
        [-t[0], -t[1]]
    } else {
        t
    }
}

/// Follow one curve from the special point `s` found at second parameter `p`.
fn follow(
    plane: &Plane,
    kind: CurveKind,
    s: &Special,
    p: f64,
    index: usize,
) -> Result<(Curve, Vec<Codim2>), String> {
    let jumps = plane.jumps(p);
    // Launch the cycle from its impact farthest from every breakpoint: at a launch on a
    // border the cycle's Jacobian jumps with f'' and Newton's method creeps.
    let clearance = |ph: f64| {
        jumps
            .iter()
            .map(|&b| signed_distance(ph, b).abs())
            .fold(f64::INFINITY, f64::min)
    };
    let n = s.point.n;
    let launch = (0..n)
        .max_by(|&a, &b| clearance(s.point.phases[a]).total_cmp(&clearance(s.point.phases[b])))
        .unwrap_or(0);
    let kind = match kind {
        CurveKind::BorderCollision { impact, breakpoint } => CurveKind::BorderCollision {
            impact: (impact + n - launch) % n,
            breakpoint,
        },
        other => other,
    };
    let guess = if launch == 0 {
        s.point.clone()
    } else {
        let sys = plane.system(s.alpha, p).map_err(|e| e.to_string())?;
        cycle(
            &sys,
            n,
            s.point.k,
            s.point.phases[launch],
            s.point.velocities[launch],
        )
        .map_err(|e| format!("the cycle could not be relaunched ({})", e.as_str()))?
    };
    let tr = Tracer {
        plane,
        kind,
        n,
        k: s.point.k,
        jumps,
    };
    // The seed: solve G = 0 in α at fixed p.
    let (e0, grad0) = tr
        .correct([s.alpha, p], [0.0, 1.0], p, &guess)
        .map_err(|e| format!("the seed could not be solved on the curve ({})", e.as_str()))?;
    let y0 = e0.y;
    let first = tr.point(e0);
    let mut halves: Vec<(Vec<CurvePoint>, CurveEnd)> = Vec::new();
    let mut codim2 = Vec::new();
    let t0 = tangent(grad0, [0.0, 1.0]);
    for dir in [1.0, -1.0] {
        let tau = [dir * t0[0], dir * t0[1]];
        let (pts, end) = tr.run(first.clone(), tau, index, &mut codim2, y0);
        halves.push((pts, end));
    }
    let (back, back_end) = halves.pop().expect("two directions");
    let (fwd, fwd_end) = halves.pop().expect("two directions");
    let closed = fwd_end == CurveEnd::Closed;
    // A closed curve was found whole going forward: the backward half repeats it.
    let mut points: Vec<CurvePoint> = if closed {
        Vec::new()
    } else {
        back.into_iter().rev().collect()
    };
    points.push(first);
    points.extend(fwd);
    let ends = if closed {
        [CurveEnd::Closed, CurveEnd::Closed]
    } else {
        [back_end, fwd_end]
    };
    Ok((
        Curve {
            kind,
            n: tr.n,
            k: tr.k,
            points,
            ends,
            seed: [s.alpha, p],
        },
        codim2,
    ))
}

impl Tracer<'_> {
    /// One direction of a curve from `start` (not included in the result).
    fn run(
        &self,
        start: CurvePoint,
        tau0: [f64; 2],
        index: usize,
        codim2: &mut Vec<Codim2>,
        origin: [f64; 2],
    ) -> (Vec<CurvePoint>, CurveEnd) {
        let scale = self.plane.scale();
        let h_max = 0.005 * scale;
        let h_min = 1e-9 * scale;
        let mut h = 0.25 * h_max;
        let mut out: Vec<CurvePoint> = Vec::new();
        let mut cur = start;
        let mut prev: Option<CurvePoint> = None;
        let mut tau = tau0;
        let mut travelled = 0.0;
        for _ in 0..MAX_STEPS {
            let y = [cur.alpha, cur.p];
            let pred = [y[0] + h * tau[0], y[1] + h * tau[1]];
            let step = if self.plane.inside(pred) {
                self.correct(pred, tau, tau[0] * y[0] + tau[1] * y[1] + h, &cur.cycle)
            } else {
                // Solve the point on the window's edge the step crosses.
                let (axis, bound) = self.edge(y, pred);
                let mut c = [0.0; 2];
                c[axis] = 1.0;
                let mut start = pred;
                start[axis] = bound;
                match self.correct(start, c, bound, &cur.cycle) {
                    Ok((e, _)) if self.plane.inside(e.y) || near_edge(self.plane, e.y) => {
                        let next = self.point(e);
                        match self.watch(&cur, &next, tau, index, codim2) {
                            Some(Watch::Crossed) => Err(PassError::NoConvergence),
                            None => {
                                out.push(next);
                                return (out, CurveEnd::Window);
                            }
                        }
                    }
                    Ok(_) | Err(_) => Err(PassError::NoConvergence),
                }
            };
            match step {
                Ok((e, grad)) => {
                    let next = self.point(e);
                    if let Some(Watch::Crossed) = self.watch(&cur, &next, tau, index, codim2) {
                        h *= 0.5;
                        if h < h_min {
                            return match self.border_end(prev.as_ref(), &cur, index, codim2) {
                                true => (out, CurveEnd::Border),
                                false => (out, CurveEnd::NoConvergence),
                            };
                        }
                        continue;
                    }
                    travelled += (next.alpha - cur.alpha).hypot(next.p - cur.p);
                    tau = tangent(grad, tau);
                    prev = Some(std::mem::replace(&mut cur, next));
                    out.push(cur.clone());
                    // Back at the start: a closed curve.
                    if travelled > 4.0 * h_max
                        && (cur.alpha - origin[0]).hypot(cur.p - origin[1]) < 0.5 * h
                    {
                        return (out, CurveEnd::Closed);
                    }
                    h = (h * 1.5).min(h_max);
                }
                Err(e) => {
                    h *= 0.5;
                    if h < h_min {
                        // Approaching a breakpoint, a PD, fold or grazing curve cannot
                        // cross it (its condition is another function beyond): the
                        // steps shrink toward the codimension-two point there.
                        if self.border_end(prev.as_ref(), &cur, index, codim2) {
                            return (out, CurveEnd::Border);
                        }
                        // Stopped on the window's edge itself: it left the window.
                        if on_edge(self.plane, [cur.alpha, cur.p]) {
                            return (out, CurveEnd::Window);
                        }
                        return (out, CurveEnd::from_error(e));
                    }
                }
            }
        }
        (out, CurveEnd::StepLimit)
    }

    /// Where a curve stops short of a breakpoint (another impact within
    /// [`BORDER_REACH`] of one, closing in): the codimension-two point,
    /// by linear extrapolation of that impact's distance over the last two points. The
    /// evidence kept is the last accepted point's: its condition, and its distance to
    /// the border (the extrapolation's length is of that order, its error of its
    /// square).
    fn border_end(
        &self,
        prev: Option<&CurvePoint>,
        cur: &CurvePoint,
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> bool {
        let Some(prev) = prev else { return false };
        let nb = self.jumps.len().max(1);
        let tc = self.border_tests(&cur.cycle);
        let tp = self.border_tests(&prev.cycle);
        let Some((j, &dc)) = tc
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        else {
            return false;
        };
        let dp = tp[j];
        if dc.abs() > BORDER_REACH || dp.abs() <= dc.abs() || (dp < 0.0) != (dc < 0.0) {
            return false;
        }
        let s = dc / (dp - dc);
        codim2.push(Codim2 {
            kind: match self.kind {
                CurveKind::Fold => Codim2Kind::FoldBorder,
                CurveKind::Grazing | CurveKind::StickingOnset => Codim2Kind::GrazingBorder,
                CurveKind::BorderCollision { .. } => Codim2Kind::DoubleBorder,
                CurveKind::PeriodDoubling => Codim2Kind::PdBorder,
            },
            curve: index,
            alpha: cur.alpha + s * (cur.alpha - prev.alpha),
            p: cur.p + s * (cur.p - prev.p),
            condition: cur.condition,
            second_condition: dc,
            impact: Some((j / nb, self.jumps[j % nb])),
        });
        true
    }

    /// The window edge crossed going from `y` (inside) to `pred` (outside).
    fn edge(&self, y: [f64; 2], pred: [f64; 2]) -> (usize, f64) {
        let w = [self.plane.alpha, self.plane.window];
        let mut best = (0, w[0].0, f64::INFINITY);
        for axis in 0..2 {
            for bound in [w[axis].0, w[axis].1] {
                let d = pred[axis] - y[axis];
                if d == 0.0 {
                    continue;
                }
                let t = (bound - y[axis]) / d;
                if (0.0..=1.0).contains(&t) && t < best.2 {
                    best = (axis, bound, t);
                }
            }
        }
        (best.0, best.1)
    }

    /// Watch the test functions between `a` and `b` (consecutive points): locate the
    /// first sign change, record the codimension-two point, and return the point where
    /// the curve must end if it does (a PD or fold point at a border).
    fn watch(
        &self,
        a: &CurvePoint,
        b: &CurvePoint,
        tau: [f64; 2],
        index: usize,
        codim2: &mut Vec<Codim2>,
    ) -> Option<Watch> {
        let ta = self.border_tests(&a.cycle);
        let tb = self.border_tests(&b.cycle);
        let nb = self.jumps.len().max(1);
        let h = tau[0] * (b.alpha - a.alpha) + tau[1] * (b.p - a.p);
        // The curve at arclength s from a.
        let at = |s: f64| -> Option<CurvePoint> {
            let y = [a.alpha + s * tau[0], a.p + s * tau[1]];
            self.correct(y, tau, tau[0] * a.alpha + tau[1] * a.p + s, &a.cycle)
                .ok()
                .map(|(e, _)| self.point(e))
        };
        for (j, (&ga, &gb)) in ta.iter().zip(&tb).enumerate() {
            if (ga < 0.0) == (gb < 0.0) || (ga - gb).abs() > 0.5 {
                continue;
            }
            // Past a breakpoint f'' differs: a PD, fold or grazing condition is another
            // function there, and a point beyond is on another curve. The step is
            // refused, and the shrinking steps close in on the border ([`border_end`]).
            if !matches!(self.kind, CurveKind::BorderCollision { .. }) {
                return Some(Watch::Crossed);
            }
            let (impact, bp) = (j / nb, self.jumps[j % nb]);
            let test = |q: &CurvePoint| signed_distance(q.cycle.phases[impact], bp);
            let mut g = |s: f64| at(s).map_or(f64::NAN, |q| test(&q));
            let s = bracketed_root_nan(&mut g, 0.0, h, ga, gb)?;
            let q = at(s)?;
            let kind = Codim2Kind::DoubleBorder;
            let second = test(&q);
            // Located only where the corrector worked up to the crossing.
            if second.abs() <= CONDITION_TOLERANCE {
                codim2.push(Codim2 {
                    kind,
                    curve: index,
                    alpha: q.alpha,
                    p: q.p,
                    condition: q.condition,
                    second_condition: second,
                    impact: Some((impact, bp)),
                });
            }
        }
        if let (Some(ca), Some(cb)) = (a.criticality, b.criticality) {
            if ca.supercritical().is_some()
                && cb.supercritical().is_some()
                && ca.supercritical() != cb.supercritical()
            {
                let mut g = |s: f64| at(s).and_then(|q| q.criticality).map_or(f64::NAN, |c| c.c);
                if let Some(s) = bracketed_root_nan(&mut g, 0.0, h, ca.c, cb.c) {
                    if let Some(q) = at(s) {
                        codim2.push(Codim2 {
                            kind: Codim2Kind::DegenerateFlip,
                            curve: index,
                            alpha: q.alpha,
                            p: q.p,
                            condition: q.condition,
                            second_condition: q.criticality.map_or(f64::NAN, |c| c.c),
                            impact: None,
                        });
                    }
                }
            }
        }
        None
    }
}

/// What the watch between two points saw that stops the step.
enum Watch {
    /// An impact crossed a breakpoint on a curve that cannot cross one.
    Crossed,
}

/// Whether y lies on the window's boundary (to 1e-9 of its size).
fn on_edge(plane: &Plane, y: [f64; 2]) -> bool {
    let tol = 1e-9 * plane.scale();
    let w = [plane.alpha, plane.window];
    (0..2).any(|i| (y[i] - w[i].0).abs() <= tol || (y[i] - w[i].1).abs() <= tol)
}

fn near_edge(plane: &Plane, y: [f64; 2]) -> bool {
    let tol = 1e-9 * plane.scale();
    y[0] >= plane.alpha.0 - tol
        && y[0] <= plane.alpha.1 + tol
        && y[1] >= plane.window.0 - tol
        && y[1] <= plane.window.1 + tol
}

/// The flip's criticality coefficient at a period-doubling cycle of `sys`: c NaN and
/// the error infinite (undecided) where the map is not smooth on the difference
/// stencil (an impact of a stepped orbit lands on another piece of the table).
pub fn criticality(sys: &System, pt: &CyclePoint) -> Option<Criticality> {
    let (Some(c1), Some(c2)) = (
        criticality_with(sys, pt, 2e-3),
        criticality_with(sys, pt, 1e-3),
    ) else {
        // Undecided: the map is not smooth around the cycle on the stencil's scale.
        return Some(Criticality {
            c: f64::NAN,
            error: f64::INFINITY,
        });
    };
    // Central differences are O(h²): Richardson's extrapolation, and the correction
    // it made as the error.
    let c = c2 + (c2 - c1) / 3.0;
    // Rounding: the map is stepped to about 1e-15 of its scale, and the third
    // difference divides that by h³.
    let rounding = 1e-15 * (1.0 + pt.velocities[0].abs()) / 1e-9 * 10.0;
    Some(Criticality {
        c,
        error: (3.0 * (c2 - c1).abs()).max(rounding).max(1e-9 * c.abs()),
    })
}

fn criticality_with(sys: &System, pt: &CyclePoint, h: f64) -> Option<f64> {
    let mut map = map_for(sys);
    let (n, k) = (pt.n, pt.k);
    let x0 = [pt.t0, pt.velocities[0]];
    // r(x) = P(x) − x (with the k periods taken off): its second and third derivatives
    // are P's.
    // Every stepped orbit must land on the same pieces of the table as the cycle: the
    // map is smooth there only (else the stencil straddles a border, and c is not
    // defined by it).
    let table = sys.table();
    let pieces = |phases: &[f64]| -> Vec<usize> {
        phases.iter().map(|&ph| table.segment_index(ph)).collect()
    };
    let own = pieces(&pass(&mut map, x0[0], x0[1], n, k).ok()?.phases);
    let mut r = |dx: [f64; 2]| -> Option<[f64; 2]> {
        let p = pass(&mut map, x0[0] + dx[0], x0[1] + dx[1], n, k).ok()?;
        (pieces(&p.phases) == own).then_some([p.residual[0] + dx[0], p.residual[1] + dx[1]])
    };
    let a = pt.monodromy;
    let q = pt.pd_direction();
    // p: left eigenvector, (Aᵀ + I)p = 0, scaled so ⟨p, q⟩ = 1.
    let rows = [[a[0][0] + 1.0, a[1][0]], [a[0][1], a[1][1] + 1.0]];
    let row = if rows[0][0].hypot(rows[0][1]) >= rows[1][0].hypot(rows[1][1]) {
        rows[0]
    } else {
        rows[1]
    };
    let pv = [-row[1], row[0]];
    let pq = pv[0] * q[0] + pv[1] * q[1];
    if pq == 0.0 || !pq.is_finite() {
        return None;
    }
    let p = [pv[0] / pq, pv[1] / pq];
    let dot = |u: [f64; 2]| p[0] * u[0] + p[1] * u[1];
    let at = |s: f64, t: f64, w: [f64; 2]| [s * q[0] + t * w[0], s * q[1] + t * w[1]];
    let r0 = r([0.0, 0.0])?;
    let rp = r(at(h, 0.0, [0.0; 2]))?;
    let rm = r(at(-h, 0.0, [0.0; 2]))?;
    let rp2 = r(at(2.0 * h, 0.0, [0.0; 2]))?;
    let rm2 = r(at(-2.0 * h, 0.0, [0.0; 2]))?;
    let bqq = [0, 1].map(|i| (rp[i] - 2.0 * r0[i] + rm[i]) / (h * h));
    let cqqq = [0, 1].map(|i| (rp2[i] - 2.0 * rp[i] + 2.0 * rm[i] - rm2[i]) / (2.0 * h * h * h));
    // w = (I − A)⁻¹ B(q, q).
    let ia = [[1.0 - a[0][0], -a[0][1]], [-a[1][0], 1.0 - a[1][1]]];
    let w = solve(ia, bqq)?;
    let wn = w[0].hypot(w[1]);
    let bqw = if wn == 0.0 {
        [0.0, 0.0]
    } else {
        // B(q, w) by the mixed difference along q and the unit ŵ, times |w|.
        let u = [w[0] / wn, w[1] / wn];
        let pp = r(at(h, h, u))?;
        let pm = r(at(h, -h, u))?;
        let mp = r(at(-h, h, u))?;
        let mm = r(at(-h, -h, u))?;
        [0, 1].map(|i| wn * (pp[i] - pm[i] - mp[i] + mm[i]) / (4.0 * h * h))
    };
    let c = dot(cqqq) / 6.0 + dot(bqw) / 2.0;
    c.is_finite().then_some(c)
}
