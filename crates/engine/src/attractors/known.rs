//! Cycles already known at a parameter value, and the early stop of a start that has
//! reached one: the continuation of attractors knows the cycles its seeds found at an
//! α before the grid of starts runs there, and a start need not detect such a cycle
//! again by itself.
//!
//! A start is on a known cycle
//! * of impacts (a stable cycle: every periodic attractor a simulation finds is one)
//!   when its last n events each lie within [`NEAR`] of the cycle's n consecutive
//!   events, in phase (around the circle) and velocity, with the same kinds: one whole
//!   cycle within 10⁻⁷ of a contracting cycle, where the terms the linearisation
//!   leaves out are of order 10⁻¹⁴;
//! * with sticks, when it is released at one of the cycle's release phases: a release
//!   leaves the table at rest relative to it, so the orbit from there is the cycle's.
//!   To within [`NEAR_RELEASE`] where double precision resolves the cycle
//!   ([`Precision::resolved`](crate::run::precision::Precision)); where rounding
//!   decides its length an error of 10⁻¹² at a release may lead elsewhere, and only the
//!   same double is taken: from it the run computes exactly the cycle's events (the
//!   evidence the run's own detection takes too: a release at the same double).
//!
//! The test runs every [`CHECK_EVERY`] table periods (at most that late), on the
//! events the run keeps (the longest known cycle's length) and its latest release.

use super::lyapunov::CycleEvent;
use super::{identify, Found, Kind, Settle, Signature};
use crate::map::{EventKind, ImpactMap, State};
use crate::run::{Advance, OrbitRun, Point};
use crate::system::System;
use crate::time::phase_distance;

/// Largest distance (phase, velocity) of each event of a start from a known cycle of
/// impacts for the start to be on it.
pub const NEAR: f64 = 1e-7;
/// Largest distance of a release phase from a known sticking cycle's.
pub const NEAR_RELEASE: f64 = 1e-12;
/// Table periods between two tests of a run.
pub const CHECK_EVERY: i64 = 8;

/// One known cycle: its events and what a start on it ends on.
#[derive(Clone, Debug)]
struct KnownCycle {
    events: Vec<CycleEvent>,
    /// The phases of its releases (empty for a cycle of impacts).
    releases: Vec<f64>,
    /// How far a release may be from one of them: [`NEAR_RELEASE`], or 0 where double
    /// precision does not resolve the cycle.
    release_tolerance: f64,
    found: Found,
}

/// The cycles known at one parameter value.
#[derive(Clone, Debug, Default)]
pub struct Known {
    cycles: Vec<KnownCycle>,
}

impl Known {
    /// None known.
    pub fn new() -> Known {
        Known::default()
    }

    /// Add the attractor `found` if it is a cycle (and not known yet).
    pub fn add(&mut self, found: &Found) {
        let Signature::Cycle(events) = &found.signature else {
            return;
        };
        let usable = match found.kind {
            Kind::Periodic => events.iter().all(|e| e.kind == EventKind::Impact),
            Kind::Sticking => events.iter().any(|e| e.kind == EventKind::Release),
            _ => false,
        };
        if !usable || events.is_empty() {
            return;
        }
        if self
            .cycles
            .iter()
            .any(|k| super::same_cycle(&k.events, events))
        {
            return;
        }
        let releases = events
            .iter()
            .filter(|e| e.kind == EventKind::Release)
            .map(|e| e.phase)
            .collect();
        let resolved = found.precision.is_some_and(|p| p.resolved);
        self.cycles.push(KnownCycle {
            events: events.clone(),
            releases,
            release_tolerance: if resolved { NEAR_RELEASE } else { 0.0 },
            found: found.clone(),
        });
    }

    /// Whether none is known.
    pub fn is_empty(&self) -> bool {
        self.cycles.is_empty()
    }

    /// Cycles known.
    pub fn len(&self) -> usize {
        self.cycles.len()
    }

    /// Events a run must keep for the test: the longest known cycle of impacts.
    fn keep(&self) -> usize {
        self.cycles
            .iter()
            .filter(|k| k.releases.is_empty())
            .map(|k| k.events.len())
            .max()
            .unwrap_or(1)
    }

    /// The known cycle a run whose latest events are `points` (oldest first) and whose
    /// latest release (if any) was at phase `release` is on.
    fn reached(&self, points: &[Point], release: Option<f64>) -> Option<&Found> {
        self.cycles.iter().find_map(|k| {
            let on = if k.releases.is_empty() {
                on_cycle(points, &k.events)
            } else {
                release.is_some_and(|p| {
                    k.releases
                        .iter()
                        .any(|&q| phase_distance(p, q) <= k.release_tolerance)
                })
            };
            on.then_some(&k.found)
        })
    }
}

/// Whether the last n = `cycle.len()` of `points` lie within [`NEAR`] of n consecutive
/// events of `cycle`, kinds equal.
fn on_cycle(points: &[Point], cycle: &[CycleEvent]) -> bool {
    let n = cycle.len();
    if points.len() < n {
        return false;
    }
    let near = |p: &Point, e: &CycleEvent| {
        p.kind == e.kind && phase_distance(p.phase, e.phase) <= NEAR && (p.v - e.v).abs() <= NEAR
    };
    let last = &points[points.len() - 1];
    (0..n)
        .filter(|&j| near(last, &cycle[j]))
        .any(|j| (1..n).all(|b| near(&points[points.len() - 1 - b], &cycle[(j + n - b) % n])))
}

/// [`super::settle`] with an early stop on the cycles of `known`: what the start ended
/// on and the events it took. None if cancelled.
pub fn settle_known(
    sys: &System,
    start: State,
    settle: &Settle,
    known: &Known,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<(Found, u64)> {
    let map = ImpactMap::new(sys.clone(), settle.solver, start);
    let mut run = OrbitRun::new(map, known.keep(), settle.periodicity);
    let end = settle.transient as i64;
    let mut checkpoint = CHECK_EVERY;
    loop {
        match run.advance(checkpoint.min(end), end, cancelled) {
            Advance::Done(outcome, _) => {
                let found = identify(sys, settle, &outcome, run.state(), cancelled)?;
                return Some((found, run.events()));
            }
            Advance::Checkpoint => {
                let release = run.released().map(|s| s.phase);
                if let Some(found) = known.reached(&run.points(), release) {
                    return Some((found.clone(), run.events()));
                }
                checkpoint = checkpoint.saturating_add(CHECK_EVERY);
            }
            Advance::Cancelled => return None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::start::launch;
    use crate::table::Table;

    #[test]
    fn a_start_stops_on_a_known_cycle_with_the_attractor_it_would_find() {
        // F_1 at α = 0.47: the (1, 1) solution and a sticking cycle. Each start of a
        // small grid ends on the same attractor with and without the early stop, and
        // the early stop takes fewer events in all.
        let sys = System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap();
        let settle_all = |known: &Known| {
            let mut out = Vec::new();
            for i in 0..36 {
                let (t0, w0) = ((i % 6) as f64 / 6.0 + 0.05, (i / 6) as f64 / 6.0 + 0.05);
                let st = launch(&sys, t0, w0).unwrap();
                out.push(settle_known(&sys, st, &Settle::BASINS, known, &mut |_| false).unwrap());
            }
            out
        };
        let plain = settle_all(&Known::new());
        let mut known = Known::new();
        for (f, _) in &plain {
            known.add(f);
        }
        assert!(known.len() >= 2, "{known:?}");
        let stopped = settle_all(&known);
        let (mut before, mut after) = (0, 0);
        for ((a, ea), (b, eb)) in plain.iter().zip(&stopped) {
            assert_eq!((a.kind, a.events, a.periods), (b.kind, b.events, b.periods));
            if let (Signature::Cycle(x), Signature::Cycle(y)) = (&a.signature, &b.signature) {
                assert!(super::super::same_cycle(x, y));
            }
            before += ea;
            after += eb;
        }
        assert!(after < before, "{after} {before}");
    }
}
