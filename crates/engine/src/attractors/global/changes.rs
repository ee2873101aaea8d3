//! What changes between two neighbouring α values of a continuation ([`Change`]), and
//! why an attractor appears or disappears there ([`Cause`]): its cycle continued by
//! Newton's method on the exact map to the value where it is not seen.

use super::MATCH_DISTANCE;
use crate::attractors::{Attractor, Kind};
use crate::system::System;
use crate::time::phase_distance;

/// What changed along a track between two neighbouring α values.
#[derive(Clone, Debug, PartialEq)]
pub enum ChangeKind {
    /// An attractor with no match at the previous α.
    Birth,
    /// An attractor with no match at this α; `into`: the track its seeds went to, if
    /// they went to an attractor (a merger or a crisis), None if they did not settle.
    Death {
        /// Where its points now go.
        into: Option<usize>,
    },
    /// The cycle's (n, k) changed (both decided by double precision).
    Period {
        /// Before.
        from: (usize, i64),
        /// After.
        to: (usize, i64),
    },
    /// The kind changed; into or out of sticking when either is [`Kind::Sticking`].
    Kind {
        /// Before.
        from: Kind,
        /// After.
        to: Kind,
    },
}

impl ChangeKind {
    /// Its name in every output: birth, death, merge, period, sticking, kind.
    pub fn name(&self) -> &'static str {
        match self {
            ChangeKind::Birth => "birth",
            ChangeKind::Death { into: None } => "death",
            ChangeKind::Death { into: Some(_) } => "merge",
            ChangeKind::Period { .. } => "period",
            ChangeKind::Kind { from, to } if *from == Kind::Sticking || *to == Kind::Sticking => {
                "sticking"
            }
            ChangeKind::Kind { .. } => "kind",
        }
    }
}

/// A change of the picture between α value `step − 1` and `step`.
#[derive(Clone, Debug, PartialEq)]
pub struct Change {
    /// The first α value where it is seen: its place in [`Continuation::steps`](super::Continuation::steps).
    pub step: usize,
    /// The track it happens to.
    pub track: usize,
    /// What happened.
    pub what: ChangeKind,
    /// For a birth or a death: what the exact map says happened to the attractor's
    /// cycle between the two values ([`Cause`]).
    pub cause: Option<Cause>,
}

/// Why an attractor appears or disappears between two neighbouring α values, from its
/// cycle continued by Newton's method on the exact map to the value where it is not
/// seen (from the one where it is).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cause {
    /// The cycle is there but unstable: a multiplier crossed the unit circle between
    /// the two values. `at` names how: `period doubling` (a real multiplier below −1),
    /// `fold` (above 1), `torus` (a complex pair).
    Unstable {
        /// How it lost (or gained) stability.
        at: &'static str,
        /// Its multiplier of largest modulus there.
        multiplier: crate::linalg::Complex,
    },
    /// Newton's method finds no such cycle there: it ends (or begins) between the two
    /// values, at a fold, a border collision or a grazing.
    Gone,
    /// The cycle is there and stable as well: neither a start of the grid nor a seed
    /// landed on it at that value (a basin too small for the grid), not a bifurcation.
    Missed,
    /// A chaotic attractor that appears or disappears with no cycle to follow: where no
    /// local bifurcation explains it, a crisis.
    Crisis,
    /// No local test: a sticking cycle or one whose length double precision leaves
    /// open (the Newton corrector follows cycles of impacts only), or an unsettled
    /// orbit that is neither a cycle nor chaotic.
    Untested,
}

impl Cause {
    /// Its name in every output: unstable, gone, missed, crisis, untested.
    pub fn name(&self) -> &'static str {
        match self {
            Cause::Unstable { .. } => "unstable",
            Cause::Gone => "gone",
            Cause::Missed => "missed",
            Cause::Crisis => "crisis",
            Cause::Untested => "untested",
        }
    }
}

/// The cause of the birth or death of attractor `a`, not seen in `other` (the system
/// at the neighbouring α): its cycle continued by Newton's method from its first event
/// to `other`, accepted within [`MATCH_DISTANCE`] of it.
pub(super) fn cause(a: &Attractor, other: &System) -> Cause {
    let cycle = a.cycle_points();
    if a.kind != Kind::Periodic || cycle.is_empty() || a.unresolved() {
        return if a.kind == Kind::Chaotic {
            Cause::Crisis
        } else {
            Cause::Untested
        };
    }
    let (Some(n), Some(k)) = (a.events, a.periods.and_then(|k| u32::try_from(k).ok())) else {
        return Cause::Untested;
    };
    let (t0, v0) = cycle[0];
    let Ok(cp) = crate::orbits::periodic::cycle(other, n, k, t0, v0) else {
        return Cause::Gone;
    };
    let near = phase_distance(cp.phases[0], t0).max((cp.velocities[0] - v0).abs());
    if near > MATCH_DISTANCE {
        return Cause::Gone;
    }
    if cp.stable {
        return Cause::Missed;
    }
    let [m0, m1] = cp.multipliers;
    let m = if m0.abs() >= m1.abs() { m0 } else { m1 };
    let at = if m.im != 0.0 {
        "torus"
    } else if m.re < 0.0 {
        "period doubling"
    } else {
        "fold"
    };
    Cause::Unstable { at, multiplier: m }
}

/// The change between an attractor before and its match after, if any.
pub(super) fn change_of(
    from: Kind,
    from_period: Option<(usize, i64)>,
    to: Kind,
    to_period: Option<(usize, i64)>,
) -> Option<ChangeKind> {
    if from != to {
        return Some(ChangeKind::Kind { from, to });
    }
    match (from_period, to_period) {
        (Some(a), Some(b)) if a != b => Some(ChangeKind::Period { from: a, to: b }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attractors::{settle, Registry, Settle};
    use crate::map::State;

    #[test]
    fn a_cycles_cause_is_read_from_newton_at_the_other_alpha() {
        // fd:0.1, r = 0.8: the (1, 2) solution is stable on (2/9, 0.5014376751)
        // (`fixed`'s closed form). Found at α = 0.5 by a run: at 0.51 Newton's method
        // finds it unstable with a multiplier below −1 (its period doubling between),
        // at 0.5 itself stable (missed, were it not seen), at 0.2 gone (before its
        // birth at 2/9).
        use crate::orbits::fixed::fixed_points;
        use crate::table::Table;
        let at = |a: f64| System::new(Table::fd(0.1).unwrap(), a, 0.8).unwrap();
        let sys = at(0.5);
        let fp = fixed_points(&sys, 2)
            .unwrap()
            .into_iter()
            .find(|p| p.ddf < 0.0)
            .unwrap();
        let start = State::launch(&sys, 0, fp.phase + 1e-3, 1.0, 0.0).unwrap();
        let (found, ..) = settle(&sys, start, &Settle::BASINS, 1, &mut |_| false).unwrap();
        assert_eq!(
            (found.kind, found.events, found.periods),
            (Kind::Periodic, Some(1), Some(2))
        );
        let mut reg = Registry::new();
        let id = reg.assign(&found);
        let a = &reg.attractors()[id];
        match cause(a, &at(0.51)) {
            Cause::Unstable { at, multiplier } => {
                assert_eq!(at, "period doubling");
                assert!(
                    multiplier.im == 0.0 && multiplier.re < -1.0,
                    "{multiplier:?}"
                );
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(cause(a, &sys), Cause::Missed);
        assert_eq!(cause(a, &at(0.2)), Cause::Gone);
    }

    #[test]
    fn changes_name_what_changed() {
        let c = change_of(Kind::Periodic, Some((1, 1)), Kind::Periodic, Some((2, 2)));
        assert_eq!(
            c,
            Some(ChangeKind::Period {
                from: (1, 1),
                to: (2, 2)
            })
        );
        assert_eq!(
            change_of(Kind::Periodic, Some((1, 1)), Kind::Periodic, Some((1, 1))),
            None
        );
        // An undecided length is no change of period.
        assert_eq!(
            change_of(Kind::Sticking, None, Kind::Sticking, Some((8, 9))),
            None
        );
        let c = change_of(Kind::Periodic, Some((4, 4)), Kind::Sticking, None).unwrap();
        assert_eq!(c.name(), "sticking");
        let c = change_of(Kind::Periodic, Some((4, 4)), Kind::Chaotic, None).unwrap();
        assert_eq!(c.name(), "kind");
        assert_eq!(ChangeKind::Death { into: Some(2) }.name(), "merge");
    }
}
