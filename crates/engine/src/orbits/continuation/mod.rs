//! Continuation of (n, k) cycles in α: pseudo-arclength in (α, t₀, v₀) on the exact map.
//!
//! # For front ends
//! [`branches`] takes a system family (table, r), an α window and a [`Start`] and returns
//! every branch reached ([`Branch`]): its points ([`CyclePoint`]: α, impact phases,
//! launch velocities, multipliers, stable flag), its special points and how each end
//! came about ([`Special`]: period doubling PD, fold F, border collision BC, grazing,
//! leaving the window, with α, phase and the point there). The work
//! is bounded by [`Options`] (steps per branch, period, branches); the fig. 3 windows
//! take a few milliseconds to tens of milliseconds, so it can run in the background on
//! every parameter change.
//!
//! # Method
//! Each step predicts along the tangent (the null vector of [F_α | M − I]) and corrects
//! with Newton's method on the map's residual plus the arclength condition
//! ([`periodic`](super::periodic)); every accepted point is re-verified by stepping the
//! map (the 1e-11 return). Between two accepted points the test functions
//! * (1 + λ₁)(1 + λ₂) (period doubling), (1 − λ₁)(1 − λ₂) (fold),
//! * the signed phase distance of every impact to every breakpoint of the table where
//!   f'' jumps (border collision; F_D: t̂ = 0 and ½, the sine has none),
//! * α − LO and α − HI (leaving the window)
//!
//! are watched for a sign change, and the first one is located by a bracketed root in
//! the arclength (to a few ulps, far below 1e-10 in α). A step the corrector cannot take
//! is halved down to [`H_MIN`]; if even that fails the branch ends by grazing (a flight
//! touches the table, inside it or at a landing whose impact velocity vanishes; a
//! regular cycle cannot turn into a stick, see [`crate::orbits::curves`]), or as not
//! converged, whichever the last point shows. At a period
//! doubling the branch continues (unstable) and, up to [`Options::max_period`], the
//! doubled branch is started from the located point along the multiplier's eigenvector
//! (none at a degenerate period doubling, where f''' = 0). A doubled branch followed back
//! to its birth collapses onto its parent (its half-period return changes sign there):
//! that end is reported as its period doubling, at the parent's α_PD.
//!
//! At a border collision the map stays continuous but f'' jumps, so the branch's tangent
//! and multipliers jump: the cycle just beyond is solved at fixed α a little either side
//! ([`Special::persists`]: stable or unstable beyond), or the branch ends there when no
//! such cycle exists. A fold or period doubling located at a breakpoint is that
//! collision's doing and reported as it. In a cascade ([`Options::stop_at_pd`]) a branch
//! ends at its period doubling or where it loses stability at a border collision.
//!
//! # Example
//! ```
//! use bouncemap_engine::orbits::continuation::{branches, Kind, Options, Start};
//! use bouncemap_engine::orbits::stability_window;
//! use bouncemap_engine::table::Table;
//! let table = Table::fd(1.0).unwrap();
//! let bs = branches(&table, 0.8, (0.45, 0.6), Start::Fixed { k: 1 }, Options::default())
//!     .unwrap();
//! assert_eq!(bs[0].n, 1);
//! let pd = bs[0].specials.iter().find(|s| s.kind == Kind::PeriodDoubling).unwrap();
//! let closed_form = stability_window(&table, 0.8, 1).unwrap().unwrap().alpha_pd().unwrap();
//! assert!((pd.alpha - closed_form).abs() < 1e-10);
//! assert_eq!((bs[1].n, bs[1].parent), (2, Some(0)));
//! ```

use super::border;
use super::events::special;
pub use super::events::{jump_phases, Kind, Special};
use super::fixed::{fixed_points, stability_window, without_window};
use super::periodic::{correct, map_for, pass, CyclePoint, PassError};
use super::roots::bracketed_root_nan;
use super::two_cycle::two_cycle;
use crate::error::EngineError;
use crate::map::ImpactMap;
use crate::system::System;
use crate::table::Table;
use crate::time::signed_distance;

mod crossing;
mod locate;
use locate::BIRTH;
pub use locate::{
    condition_bound, holds, CONDITION, CONDITION_PERIOD, GRAZING_SPEED, ON_BORDER, SAME_POINT,
};

/// The smallest arclength step before a branch is declared ended.
pub const H_MIN: f64 = 1e-11;

/// One continued branch of (n, k) cycles.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch {
    /// Events per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// The branch it doubled from (index into the returned list).
    pub parent: Option<usize>,
    /// Points in arclength order.
    pub points: Vec<CyclePoint>,
    /// Special points passed on the way (period doublings, folds), in order.
    pub specials: Vec<Special>,
    /// How the branch ends at its first and last point.
    pub begin: Special,
    /// How the branch ends at its last point.
    pub end: Special,
}

/// Bounds and choices of a continuation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Steps per direction of a branch.
    pub max_steps: usize,
    /// No doubled branch is started beyond this period.
    pub max_period: usize,
    /// At most this many branches.
    pub max_branches: usize,
    /// End a branch at its first period doubling (the cascade).
    pub stop_at_pd: bool,
    /// First and largest arclength step.
    pub h_init: f64,
    /// Largest arclength step.
    pub h_max: f64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            max_steps: 4000,
            max_period: 16,
            max_branches: 64,
            stop_at_pd: false,
            h_init: 1e-3,
            h_max: 0.02,
        }
    }
}

/// Where the continuation starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Start {
    /// The (1, k) solution with f'' < 0 (at LO, or at its birth if later).
    Fixed {
        /// Table periods between bounces.
        k: u32,
    },
    /// The (2, 2k) solution just past (1, k)'s period doubling (or at LO if later).
    TwoCycle {
        /// Half the table periods of the two-cycle.
        k: u32,
    },
    /// An (n, k) cycle near the launch (t̂₀, v₀) at α = LO.
    Point {
        /// Events per cycle.
        n: usize,
        /// Table periods per cycle.
        k: u32,
        /// Phase of the launch guess.
        t0: f64,
        /// Velocity of the launch guess.
        v0: f64,
    },
}

/// Why no branch could be started.
#[derive(Clone, Debug, PartialEq)]
pub enum NoStart {
    /// The window or the settings were refused.
    Invalid(EngineError),
    /// No start of that kind in the window (the reason in words).
    NotFound(String),
}

impl std::fmt::Display for NoStart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoStart::Invalid(e) => write!(f, "{e}"),
            NoStart::NotFound(s) => write!(f, "{s}"),
        }
    }
}

/// The system family a continuation runs on.
pub(crate) struct Family {
    map: ImpactMap,
    window: (f64, f64),
    /// Breakpoints where f'' jumps.
    jumps: Vec<f64>,
    opts: Options,
}

/// Every branch reached from `start` in the window `lo..hi` for the table and r.
pub fn branches(
    table: &Table,
    r: f64,
    window: (f64, f64),
    start: Start,
    opts: Options,
) -> Result<Vec<Branch>, NoStart> {
    let mut fam = Family::new(table, r, window, opts)?;
    let seed = find_start(&mut fam, table, r, start)?;
    let mut out: Vec<Branch> = Vec::new();
    let first = fam.two_way(seed);
    out.push(first);
    // Breadth first over period doublings.
    let mut next = 0;
    while next < out.len() && out.len() < opts.max_branches {
        // Period doublings passed, and border collisions (passed or ending the branch)
        // at which a cycle of twice the period is born.
        let b = &out[next];
        let births: Vec<Special> = b
            .specials
            .iter()
            .filter(|s| s.kind == Kind::PeriodDoubling || doubles_at_border(s))
            .chain(std::iter::once(&b.end).filter(|s| doubles_at_border(s)))
            .cloned()
            .collect();
        for pd in births {
            if pd.point.n * 2 > opts.max_period || out.len() >= opts.max_branches {
                break;
            }
            let born = if pd.kind == Kind::PeriodDoubling {
                fam.doubled(&pd)
            } else {
                fam.doubled_at_border(&pd)
            };
            if let Some(mut b) = born {
                b.parent = Some(next);
                out.push(b);
            }
        }
        next += 1;
    }
    Ok(out)
}

pub(crate) fn find_start(
    fam: &mut Family,
    table: &Table,
    r: f64,
    start: Start,
) -> Result<CyclePoint, NoStart> {
    let (lo, hi) = fam.window;
    let at = |a: f64| System::new(table.clone(), a, r).map_err(NoStart::Invalid);
    match start {
        Start::Fixed { k } => {
            let w = stability_window(table, r, k)
                .map_err(NoStart::Invalid)?
                .ok_or_else(|| {
                    NoStart::NotFound(format!(
                        "{}; continuation from the (1, {k}) solution starts only where it is stable",
                        without_window(table, r, k, lo)
                    ))
                })?;
            let a = lo.max(w.alpha_birth + 1e-6 * (1.0 + w.alpha_birth));
            if a > hi {
                return Err(NoStart::NotFound(format!(
                    "the (1, {k}) solution is born at alpha = {}, after the window",
                    w.alpha_birth
                )));
            }
            let sys = at(a)?;
            let fp = fixed_points(&sys, k)
                .map_err(NoStart::Invalid)?
                .into_iter()
                .find(|p| p.admissible && p.ddf < 0.0)
                .ok_or_else(|| {
                    NoStart::NotFound(format!(
                        "no admissible (1, {k}) solution with f'' < 0 at alpha = {a}"
                    ))
                })?;
            fam.solve(&sys, 1, k, fp.phase, fp.v)
        }
        Start::TwoCycle { k } => {
            let w = stability_window(table, r, k)
                .map_err(NoStart::Invalid)?
                .and_then(|w| w.alpha_pd())
                .ok_or_else(|| {
                    NoStart::NotFound(format!(
                        "the (1, {k}) solution has no period-doubling point"
                    ))
                })?;
            let mut a = lo.max(w + 1e-4);
            for _ in 0..8 {
                if a > hi {
                    break;
                }
                let sys = at(a)?;
                if let Ok(tc) = two_cycle(&sys, k) {
                    if let Ok(pt) = fam.solve(&sys, 2, 2 * k, tc.phase0, tc.v0) {
                        return Ok(pt);
                    }
                }
                a = lo.max(w + 2.0 * (a - w));
            }
            Err(NoStart::NotFound(format!(
                "no (2, {}) solution found in the window after alpha_PD = {w}",
                2 * k
            )))
        }
        Start::Point { n, k, t0, v0 } => {
            let sys = at(lo)?;
            fam.solve(&sys, n, k, t0, v0)
        }
    }
}

impl Family {
    pub(crate) fn new(
        table: &Table,
        r: f64,
        window: (f64, f64),
        opts: Options,
    ) -> Result<Family, NoStart> {
        let (lo, hi) = window;
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Err(NoStart::NotFound(format!("the window {lo}..{hi} is empty")));
        }
        let sys = System::new(table.clone(), lo, r).map_err(NoStart::Invalid)?;
        System::new(table.clone(), hi, r).map_err(NoStart::Invalid)?;
        Ok(Family {
            map: map_for(&sys),
            window,
            jumps: jump_phases(table),
            opts,
        })
    }

    fn solve(
        &mut self,
        sys: &System,
        n: usize,
        k: u32,
        t0: f64,
        v0: f64,
    ) -> Result<CyclePoint, NoStart> {
        self.map.set_alpha(sys.alpha()).map_err(NoStart::Invalid)?;
        super::periodic::solve_at(&mut self.map, n, k, t0, v0).map_err(|e| {
            NoStart::NotFound(format!(
                "no ({n}, {k}) cycle near t0 = {t0}, v0 = {v0} at alpha = {}: {}",
                sys.alpha(),
                e.as_str()
            ))
        })
    }

    fn x(p: &CyclePoint) -> [f64; 3] {
        [p.alpha, p.t0, p.velocities[0]]
    }

    /// The unit tangent at a point, oriented along `dir`.
    pub(crate) fn tangent(&mut self, p: &CyclePoint, dir: [f64; 3]) -> Option<[f64; 3]> {
        // A zero-length corrector step returns the point and its tangent.
        correct(&mut self.map, p.n, p.k, Self::x(p), dir, 0.0)
            .ok()
            .map(|(_, t)| t)
    }

    /// A branch from an interior point, followed both ways.
    pub(crate) fn two_way(&mut self, seed: CyclePoint) -> Branch {
        let t = self
            .tangent(&seed, [1.0, 0.0, 0.0])
            .unwrap_or([1.0, 0.0, 0.0]);
        let back = self.follow(seed.clone(), [-t[0], -t[1], -t[2]]);
        let fwd = self.follow(seed.clone(), t);
        let mut points: Vec<CyclePoint> = back.points.into_iter().rev().collect();
        points.push(seed.clone());
        points.extend(fwd.points);
        // A start on the window's edge is also the backward run's exit point.
        points.dedup_by(|b, a| a.alpha == b.alpha && a.t0 == b.t0);
        let mut specials: Vec<Special> = back.specials.into_iter().rev().collect();
        specials.extend(fwd.specials);
        Branch {
            n: seed.n,
            k: seed.k,
            parent: None,
            points,
            specials,
            begin: back.end,
            end: fwd.end,
        }
    }

    /// The doubled branch born at the period doubling `pd` (None if none is born).
    pub(crate) fn doubled(&mut self, pd: &Special) -> Option<Branch> {
        let p = &pd.point;
        let (n, k) = (2 * p.n, 2 * p.k);
        let e = p.pd_direction();
        let tau = [0.0, e[0], e[1]];
        let x0 = Self::x(p);
        for h in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
            let Ok((pt, t)) = correct(&mut self.map, n, k, x0, tau, h) else {
                continue;
            };
            // Collapsed onto the parent: not the doubled cycle.
            let collapsed = pass(&mut self.map, pt.t0, pt.velocities[0], p.n, p.k)
                .map(|q| q.residual[0].abs().max(q.residual[1].abs()) < 1e-9)
                .unwrap_or(false);
            if collapsed {
                continue;
            }
            // A degenerate period doubling (f''' = 0 on the piece, e.g. F_0): doubled
            // cycles exist at α_PD alone, a segment at fixed α with a multiplier +1;
            // no branch is born.
            let flat = |q: &CyclePoint| (q.alpha - p.alpha).abs() <= 1e-11 * (1.0 + p.alpha);
            if flat(&pt) {
                if let Ok((probe, _)) = correct(&mut self.map, n, k, x0, tau, 1e-3) {
                    if flat(&probe) {
                        return None;
                    }
                }
            }
            // Steps grow from the size that found the branch: a deep branch of the
            // cascade lives on a tiny α range.
            let run = self.follow_from(pt.clone(), t, (10.0 * h).min(self.opts.h_init));
            let mut points = vec![pt];
            points.extend(run.points);
            let begin = Special {
                kind: Kind::PeriodDoubling,
                ..pd.clone()
            };
            return Some(Branch {
                n,
                k,
                parent: None,
                points,
                specials: run.specials,
                begin,
                end: run.end,
            });
        }
        None
    }
}

/// Whether `s` is a border collision at which a cycle of twice the period is born.
pub fn doubles_at_border(s: &Special) -> bool {
    s.kind == Kind::BorderCollision
        && matches!(
            s.collision.map(|c| c.crossing),
            Some(border::Crossing::Doubling { .. })
        )
}

impl Family {
    /// The doubled branch born at the border collision `bc` (one that
    /// [`doubles_at_border`]), followed away from the collision.
    pub(crate) fn doubled_at_border(&mut self, bc: &Special) -> Option<Branch> {
        let p = &bc.point;
        // The side the cycle came from is the one its impact is not on past the
        // collision: try the doubled cycle on either side of α.
        for (side, dir) in [(-1.0, 1.0), (1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            let Some(q) =
                border::doubled_at_border(&mut self.map, p, bc.impact, bc.phase, side, dir)
            else {
                continue;
            };
            let xq = Family::x(&q);
            let xp = Family::x(p);
            let away = [xq[0] - xp[0], xq[1] - xp[1], xq[2] - xp[2]];
            let t = self.tangent(&q, away)?;
            let run = self.follow_from(q.clone(), t, self.opts.h_init.min(1e-4));
            let mut points = vec![q];
            points.extend(run.points);
            return Some(Branch {
                n: 2 * p.n,
                k: 2 * p.k,
                parent: None,
                points,
                specials: run.specials,
                begin: bc.clone(),
                end: run.end,
            });
        }
        None
    }
}

/// One direction of a branch.
pub(crate) struct Run {
    pub points: Vec<CyclePoint>,
    pub specials: Vec<Special>,
    pub end: Special,
}

impl Family {
    pub(crate) fn follow(&mut self, start: CyclePoint, tau0: [f64; 3]) -> Run {
        self.follow_from(start, tau0, self.opts.h_init)
    }

    /// [`Self::follow`] with a first step `h0`.
    fn follow_from(&mut self, start: CyclePoint, tau0: [f64; 3], h0: f64) -> Run {
        let mut pt = start;
        let mut tau = tau0;
        let mut h = h0;
        let mut run = Run {
            points: Vec::new(),
            specials: Vec::new(),
            end: special(Kind::StepLimit, &pt, pt.phases[0], 0),
        };
        for _ in 0..self.opts.max_steps {
            let x0 = Family::x(&pt);
            let step = correct(&mut self.map, pt.n, pt.k, x0, tau, h);
            // A corrector that lands far from its prediction has jumped to another
            // branch (long cycles have many nearby): a failed step.
            let step = step.and_then(|(p, t)| {
                let xp = Family::x(&p);
                let off = (0..3).fold(0.0f64, |m, i| m.max((xp[i] - x0[i] - h * tau[i]).abs()));
                if off <= 0.3 * h + 1e-12 {
                    Ok((p, t))
                } else {
                    Err(PassError::NoConvergence)
                }
            });
            // A corrected point must be the continuation of the last one: all its impacts
            // and velocities move continuously (see [`Family::continuous`]). A step that
            // jumped is a failed step; a branch that jumps at every step down to the
            // smallest is lost.
            let step = match step {
                Ok((p, _)) if !self.continuous(&pt, &p, x0, tau, h) => {
                    if h > H_MIN {
                        h *= 0.5;
                        continue;
                    }
                    let mut sp = special(Kind::Lost, &pt, pt.phases[0], 0);
                    sp.last_step = Some(h);
                    run.end = sp;
                    return run;
                }
                other => other,
            };
            let (next, t1) = match step {
                Ok(s) => s,
                Err(e) => {
                    if h > H_MIN {
                        h *= 0.5;
                        continue;
                    }
                    // Stopped at a breakpoint: the branch turns there (its tangent jumps
                    // with f''), or the cycle ceases to exist.
                    let recent = |s: &Special| {
                        s.kind == Kind::BorderCollision && (s.alpha - pt.alpha).abs() < 1e-6
                    };
                    if let (Some((i, bp)), false) = (
                        self.at_breakpoint(&pt),
                        run.specials.last().is_some_and(recent),
                    ) {
                        let sp = special(Kind::BorderCollision, &pt, bp, i);
                        let side = signed_distance(pt.phases[i], bp);
                        match self.cross_border(sp, &pt, side, pt.stable, &mut run) {
                            Some((q, tq)) => {
                                pt = q;
                                tau = tq;
                                h = self.opts.h_init;
                                continue;
                            }
                            None => return run,
                        }
                    }
                    run.end = self.failure_end(&pt, e);
                    return run;
                }
            };
            // Events between pt and next, the first along the arclength.
            if let Some((hs, kind, impact, phase)) = self.first_event(&pt, &next, x0, tau, h) {
                let located = correct(&mut self.map, pt.n, pt.k, x0, tau, hs);
                let (at, t_at) = located.unwrap_or_else(|_| (next.clone(), t1));
                if impact == BIRTH || kind == Kind::Fold {
                    // The birth of a doubled branch ends it; a +1 multiplier next to
                    // the birth is the birth's, not a fold.
                    let birth = self.is_birth(&at, if impact == BIRTH { 1e-6 } else { 1e-4 });
                    if birth && impact == BIRTH {
                        run.points.push(at.clone());
                        // The pitchfork of the doubled map is singular: its α is
                        // accurate to √ε only, the parent's period doubling to ε; the
                        // point reported is the parent's there (its multiplier −1).
                        let sp = match self.parent_pd(&at) {
                            Some(parent) => special(Kind::PeriodDoubling, &parent, f64::NAN, 0),
                            None => {
                                let mut sp = special(Kind::Lost, &at, f64::NAN, 0);
                                sp.last_step = Some(hs);
                                sp
                            }
                        };
                        run.end = sp;
                        return run;
                    }
                    if birth || impact == BIRTH {
                        run.points.push(next.clone());
                        pt = next;
                        tau = t1;
                        continue;
                    }
                }
                // A multiplier through ±1 located at a breakpoint jumped there: the
                // border collision's doing (its test may not have changed sign when
                // the step started on the breakpoint).
                let (kind, impact, phase) = match (kind, self.at_breakpoint(&at)) {
                    (Kind::Fold | Kind::PeriodDoubling, Some((i, bp))) => {
                        (Kind::BorderCollision, i, bp)
                    }
                    _ => (kind, impact, phase),
                };
                let mut sp = special(kind, &at, phase, impact);
                if !holds(&sp) {
                    // The test function changed sign without its condition being met at
                    // the located point (a jump the continuity test did not see): a
                    // failed step.
                    if h > H_MIN {
                        h *= 0.5;
                        continue;
                    }
                    sp.kind = Kind::Lost;
                    sp.last_step = Some(h);
                    run.end = sp;
                    return run;
                }
                let ends = match kind {
                    Kind::PeriodDoubling => self.opts.stop_at_pd,
                    Kind::Fold => false,
                    // The map is continuous: the cycle goes on beyond the breakpoint
                    // (with f'' of the other side; `at` lies just past it) unless it
                    // meets a partner there; a cascade ends where the cycle loses
                    // stability there.
                    Kind::BorderCollision => {
                        let side = signed_distance(pt.phases[impact], phase);
                        run.points.push(at.clone());
                        match self.cross_border(sp, &at, side, pt.stable, &mut run) {
                            Some((q, tq)) => {
                                pt = q;
                                tau = tq;
                                h = self.opts.h_init;
                                continue;
                            }
                            None => return run,
                        }
                    }
                    _ => true,
                };
                run.points.push(at.clone());
                if ends {
                    run.end = sp;
                    return run;
                }
                // Go on from the located point, so an event later in this step is seen.
                run.specials.push(sp);
                pt = at;
                tau = t_at;
                continue;
            }
            run.points.push(next.clone());
            pt = next;
            tau = t1;
            h = (h * 1.5).min(self.opts.h_max);
        }
        run.end = special(Kind::StepLimit, &pt, pt.phases[0], 0);
        run
    }
}

/// The branch's cycle at `alpha`: Newton's method at fixed α from the straight line
/// between the two points that bracket it (None if no two points bracket α or Newton
/// fails there; near a fold pick the bracket nearest in arclength order).
pub fn point_at(table: &Table, r: f64, branch: &Branch, alpha: f64) -> Option<CyclePoint> {
    let sys = System::new(table.clone(), alpha, r).ok()?;
    let w = branch
        .points
        .windows(2)
        .find(|w| (w[0].alpha - alpha) * (w[1].alpha - alpha) <= 0.0 && w[0].alpha != w[1].alpha)?;
    let s = (alpha - w[0].alpha) / (w[1].alpha - w[0].alpha);
    let t0 = w[0].t0 + s * (w[1].t0 - w[0].t0);
    let v0 = w[0].velocities[0] + s * (w[1].velocities[0] - w[0].velocities[0]);
    super::periodic::cycle(&sys, branch.n, branch.k, t0, v0).ok()
}
