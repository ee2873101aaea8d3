//! Special points of continued branches, and the helpers that locate them: what can
//! happen on a branch ([`Kind`], [`Special`]), the phases where f'' jumps (border
//! collisions), the signed phase distance to one, and a bracketed root that tolerates
//! failed evaluations.

use super::border::{Collision, Crossing};
use super::periodic::CyclePoint;
use crate::table::Table;
use crate::time::signed_distance;

/// What happens at a special point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A multiplier through −1 (or, at a doubled branch's birth, where it meets its parent).
    PeriodDoubling,
    /// A multiplier through +1.
    Fold,
    /// An impact phase reaches a breakpoint of the table where f'' jumps.
    BorderCollision,
    /// A flight touches the table (inside it, or at its landing, whose relative
    /// velocity vanishes): the impact sequence would change. A regular cycle's impact
    /// velocity vanishes only so, never at the onset of a stick (see
    /// [`crate::orbits::curves`]).
    Grazing,
    /// α reaches an end of the window.
    WindowExit,
    /// The corrector failed with no sign of the above.
    NoConvergence,
    /// Every corrected step down to the smallest one left the branch (its cycle's
    /// points jumped instead of moving continuously): the branch could not be followed
    /// further, and no special point is claimed there.
    Lost,
    /// The step bound of [`Options::max_steps`](super::continuation::Options::max_steps) was reached.
    StepLimit,
}

impl Kind {
    /// Name in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::PeriodDoubling => "period_doubling",
            Kind::Fold => "fold",
            Kind::BorderCollision => "border_collision",
            Kind::Grazing => "grazing",
            Kind::WindowExit => "window_exit",
            Kind::NoConvergence => "no_convergence",
            Kind::Lost => "lost",
            Kind::StepLimit => "step_limit",
        }
    }

    /// The short label a diagram puts at the point.
    pub fn label(self) -> &'static str {
        match self {
            Kind::PeriodDoubling => "PD",
            Kind::Fold => "F",
            Kind::BorderCollision => "BC",
            Kind::Grazing => "G",
            Kind::WindowExit => "W",
            Kind::NoConvergence => "NC",
            Kind::Lost => "?",
            Kind::StepLimit => "L",
        }
    }
}

/// A special point of a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Special {
    /// What happens there.
    pub kind: Kind,
    /// Where, in α.
    pub alpha: f64,
    /// The phase concerned: the breakpoint at a border collision, the touching phase at
    /// a grazing (the slowest impact's at a grazing landing), t̂₀ otherwise.
    pub phase: f64,
    /// Which impact of the cycle (0 = the launch's) for a border collision or a grazing landing.
    pub impact: usize,
    /// The cycle at the point (the last good one where the branch could not go on).
    pub point: CyclePoint,
    /// At a border collision: the multipliers on both sides and what happens
    /// ([`Collision`]); None elsewhere, or where the two sides could not be computed.
    pub collision: Option<Collision>,
    /// Where the branch was lost ([`Kind::Lost`]): the last arclength step tried.
    pub last_step: Option<f64>,
}

impl Special {
    /// How far its defining condition is from holding at its point, the evidence it
    /// is what it says: the distance of the nearest real multiplier from −1 (period
    /// doubling) or +1 (fold), of the impact's phase from the breakpoint (border
    /// collision); None for kinds without one.
    pub fn condition_error(&self) -> Option<f64> {
        let nearest = |target: f64| {
            self.point
                .multipliers
                .iter()
                .filter(|m| m.im == 0.0)
                .map(|m| (m.re - target).abs())
                .min_by(f64::total_cmp)
        };
        match self.kind {
            Kind::PeriodDoubling => nearest(-1.0),
            Kind::Fold => nearest(1.0),
            Kind::BorderCollision => self
                .point
                .phases
                .get(self.impact)
                .map(|&ph| signed_distance(ph, self.phase).abs()),
            _ => None,
        }
    }

    /// At a border collision: Some(stable) if the cycle goes on beyond the breakpoint
    /// (with that stability), None if it ceases there (a border-collision fold) or
    /// elsewhere.
    pub fn persists(&self) -> Option<bool> {
        match self.collision?.crossing {
            Crossing::Persists { stable } => Some(stable),
            Crossing::Doubling { .. } => Some(false),
            Crossing::Fold => None,
        }
    }
}

/// Phases in [0, 1) at which f'' jumps (the table's piece starts whose one-sided
/// second derivatives differ), the border-collision phases.
pub fn jump_phases(table: &Table) -> Vec<f64> {
    let pieces = table.pieces();
    let mut out = Vec::new();
    for (i, p) in pieces.iter().enumerate() {
        let prev = &pieces[(i + pieces.len() - 1) % pieces.len()];
        let left = prev.d2.eval(prev.end - prev.start);
        let right = p.d2.eval(0.0);
        if (left - right).abs() > 1e-12 * (1.0 + left.abs().max(right.abs())) {
            out.push(p.start);
        }
    }
    out
}

pub(crate) fn special(kind: Kind, p: &CyclePoint, phase: f64, impact: usize) -> Special {
    Special {
        kind,
        alpha: p.alpha,
        phase: if phase.is_nan() { p.phases[0] } else { phase },
        impact,
        point: p.clone(),
        collision: None,
        last_step: None,
    }
}
