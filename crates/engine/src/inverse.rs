//! The inverse of the impact map: the launch that a launch after an impact came from.
//!
//! A launch (t₁, v₁) right after an impact at t₁ came in with the relative velocity
//! u − f'(t₁) = −(v₁ − f'(t₁))/r (the restitution law solved for the incoming velocity
//! u). The flight before it is the parabola x(t) = f(t₁) + u(t − t₁) − (t − t₁)²/2,
//! followed backward to the latest earlier instant t₀ where it meets the table: the
//! previous launch, with velocity v₀ = u + (t₁ − t₀).
//!
//! Backward in time the parabola is a forward flight under the same gravity on the
//! time-reversed table G(τ) = F(c − τ) (τ = c − t; [`Table::reversed`]): it leaves the
//! table at τ₁ = c − t₁ with velocity −u, and its first landing τ₀ is c − t₀. So the
//! preimage is found by the same exact next-impact solver as the forward map, with the
//! same guarantee that no contact between is missed, and it is unique.
//!
//! There is no (single) preimage where:
//! * v₁ < f'(t₁), or v₁ = f'(t₁): not a launch after an impact ([`NoPreimage::NotALaunch`]);
//! * the backward flight meets the table with zero relative velocity (at most the
//!   forward map's [`W_FLOOR`]): the ball left
//!   the table at rest relative to it, a release after sticking, reached from a whole
//!   interval of earlier states, or it grazes there ([`NoPreimage::Release`]);
//! * the backward flight does not land within the solver's work bound, or the preimage
//!   lies outside the engine's ranges ([`NoPreimage::NoLanding`], [`NoPreimage::OutOfRange`]);
//! * the forward map, stepped once from the preimage, does not return to (t₁, v₁)
//!   within [`RETURN_TOLERANCE`] (it sees a chattering sequence there, or rounding near a
//!   grazing decides differently; [`NoPreimage::NotReturning`]).
//!
//! Every preimage is checked by that forward step: what this module returns is a launch
//! the exact forward map takes to the point asked.
//!
//! [`Table::reversed`]: crate::table::Table

use crate::impact::{FlightError, FlightSolver, Launch, Solver};
use crate::map::{EventKind, ImpactMap, State, W_FLOOR};
use crate::system::System;
use crate::time::normalize;

/// Largest difference in phase or velocity (relative to 1 + |v|) between the point asked
/// and the forward map's image of its preimage.
pub const RETURN_TOLERANCE: f64 = 1e-9;

/// The launch before a launch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preimage {
    /// Whole table periods of the previous launch's time.
    pub period: i64,
    /// Its phase, in [0, 1).
    pub phase: f64,
    /// Its velocity.
    pub v: f64,
    /// Its velocity relative to the table, v − f'(t) (> 0), without cancellation.
    pub w: f64,
    /// The flight time from it to the point asked.
    pub flight: f64,
}

/// Why a launch has no single preimage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoPreimage {
    /// v₁ ≤ f'(t₁): not the launch of an impact.
    NotALaunch,
    /// Backward, the flight meets the table at this phase with zero relative velocity:
    /// a release after sticking (or a grazing), reached from many states.
    Release {
        /// Where.
        phase: f64,
    },
    /// The backward flight did not land within the solver's work bound.
    NoLanding,
    /// The preimage lies outside the engine's ranges of velocity or time.
    OutOfRange,
    /// The forward map from the preimage does not return to the point: this far.
    NotReturning {
        /// The difference (phase, or velocity relative to 1 + |v|).
        error: f64,
    },
}

impl NoPreimage {
    /// Its name in every output.
    pub fn as_str(&self) -> &'static str {
        match self {
            NoPreimage::NotALaunch => "not_a_launch",
            NoPreimage::Release { .. } => "release",
            NoPreimage::NoLanding => "no_landing",
            NoPreimage::OutOfRange => "out_of_range",
            NoPreimage::NotReturning { .. } => "not_returning",
        }
    }
}

/// The inverse map of one system: the time-reversed table's solver, and the forward
/// map that checks each preimage.
#[derive(Clone, Debug)]
pub struct InverseMap {
    sys: System,
    reversed: System,
    shift: f64,
    backward: FlightSolver,
    forward: ImpactMap,
}

impl InverseMap {
    /// The inverse map of `sys`.
    pub fn new(sys: &System) -> InverseMap {
        let (table, shift) = sys.table().reversed();
        let reversed =
            System::new(table, sys.alpha(), sys.r()).expect("the reversed table of a valid system");
        let backward = FlightSolver::new(&reversed, Solver::Exact);
        let start = State::start(sys, 0.0, None, 0.0).expect("the default start is valid");
        let forward = ImpactMap::new(sys.clone(), Solver::Exact, start);
        InverseMap {
            sys: sys.clone(),
            reversed,
            shift,
            backward,
            forward,
        }
    }

    /// The system it inverts.
    pub fn system(&self) -> &System {
        &self.sys
    }

    /// The launch that the exact map takes to the launch (period, phase, v) after an
    /// impact, checked by one forward step.
    pub fn previous(&mut self, period: i64, phase: f64, v: f64) -> Result<Preimage, NoPreimage> {
        let df1 = self.sys.df(phase);
        let w1 = v - df1;
        if w1.is_nan() || w1 <= 0.0 || !v.is_finite() {
            return Err(NoPreimage::NotALaunch);
        }
        // The incoming relative velocity, and the incoming velocity.
        let u_rel = -w1 / self.sys.r();
        let u = df1 + u_rel;
        // τ₁ = c − t₁, leaving the reversed table with velocity −u (relative −u_rel).
        let (rp, rphase) = normalize(
            period.checked_neg().ok_or(NoPreimage::OutOfRange)?,
            self.shift - phase,
        );
        let launch = Launch {
            period: rp,
            phase: rphase,
            height: 0.0,
            v: -u,
            w: -u_rel,
        };
        let landing = match self.backward.landing(&self.reversed, &launch) {
            Ok(l) => l,
            Err(FlightError::NoLanding) => return Err(NoPreimage::NoLanding),
            Err(FlightError::NoLiftOff) => return Err(NoPreimage::NotALaunch),
        };
        // t₀ = c − τ₀.
        let (p0, phase0) = normalize(
            landing.period.checked_neg().ok_or(NoPreimage::OutOfRange)?,
            self.shift - landing.phase,
        );
        // Backward the landing's relative velocity is −(v₀ − f'(t₀)).
        let w0 = -landing.vrel;
        if w0 <= W_FLOOR {
            return Err(NoPreimage::Release { phase: phase0 });
        }
        let v0 = u + landing.flight;
        let pre = Preimage {
            period: p0,
            phase: phase0,
            v: v0,
            w: w0,
            flight: landing.flight,
        };
        self.check(&pre, period, phase, v)?;
        Ok(pre)
    }

    /// One forward step from `pre` must be an impact at (period, phase) with velocity v.
    fn check(&mut self, pre: &Preimage, period: i64, phase: f64, v: f64) -> Result<(), NoPreimage> {
        let st = State::launch(&self.sys, pre.period, pre.phase, pre.v, 0.0)
            .map_err(|_| NoPreimage::OutOfRange)?;
        self.forward.set_state(st);
        let e = self.forward.step().map_err(|_| NoPreimage::NoLanding)?;
        if e.kind != EventKind::Impact {
            return Err(NoPreimage::NotReturning {
                error: f64::INFINITY,
            });
        }
        let dt = (e.period - period) as f64 + (e.phase - phase);
        let dv = (e.v - v) / (1.0 + v.abs());
        let error = dt.abs().max(dv.abs());
        if error.is_finite() && error <= RETURN_TOLERANCE {
            Ok(())
        } else {
            Err(NoPreimage::NotReturning { error })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;
    use crate::test_rng::Xorshift;

    /// Forward then backward: random launches of several tables step once forward, and
    /// the inverse of the image is the launch again.
    #[test]
    fn the_inverse_undoes_the_map() {
        let tables = [
            (Table::sine(), 0.3),
            (Table::fd(0.1).unwrap(), 0.45),
            (Table::fd(0.5).unwrap(), 0.55),
            (Table::fd(1.0).unwrap(), 0.6),
            // One piece of degree 5, 40 t̂²(1 − t̂)²(t̂ − ½): the general solver.
            (
                Table::piecewise(
                    "quintic",
                    &[(0.0, vec![0.0, 0.0, -20.0, 80.0, -100.0, 40.0])],
                )
                .unwrap(),
                0.4,
            ),
        ];
        let mut rng = Xorshift::new(7);
        for (table, alpha) in tables {
            let name = table.name().to_string();
            let sys = System::new(table, alpha, 0.8).unwrap();
            let mut inv = InverseMap::new(&sys);
            let mut map = ImpactMap::new(
                sys.clone(),
                Solver::Exact,
                State::start(&sys, 0.0, None, 0.0).unwrap(),
            );
            let mut checked = 0;
            for _ in 0..300 {
                let phase = rng.next();
                let w = 0.05 + 2.95 * rng.next();
                let period = (10.0 * rng.next()) as i64 - 5;
                let v = sys.df(phase) + w;
                map.set_state(State::launch(&sys, period, phase, v, 0.0).unwrap());
                let e = map.step().unwrap();
                if e.kind != EventKind::Impact {
                    continue;
                }
                let pre = inv.previous(e.period, e.phase, e.v).unwrap_or_else(|err| {
                    panic!("{name}: no preimage of the image of ({period}, {phase}, {v}): {err:?}")
                });
                let dt = (pre.period - period) as f64 + (pre.phase - phase);
                assert!(dt.abs() < 1e-10, "{name}: time off by {dt}");
                assert!(
                    (pre.v - v).abs() < 1e-10 * (1.0 + v.abs()),
                    "{name}: v {} vs {v}",
                    pre.v
                );
                checked += 1;
            }
            assert!(checked > 200, "{name}: {checked}");
        }
    }

    #[test]
    fn a_launch_from_rest_on_the_table_has_no_single_preimage() {
        // Backward from a launch whose incoming flight is the release of a ball riding
        // the table: a ball released at t_r with v = f'(t_r) lands at t₁; the launch after
        // that impact comes back to the release, where the relative velocity is zero.
        let sys = System::new(Table::fd(0.5).unwrap(), 0.6, 0.8).unwrap();
        let release = (0..1000)
            .map(|i| 0.05 + i as f64 / 1000.0)
            .find(|&t| sys.ddf(t) < -1.0 && sys.ddf(t - 1e-3) < -1.0)
            .unwrap();
        let mut map = ImpactMap::new(
            sys.clone(),
            Solver::Exact,
            State::start(&sys, release, Some(sys.df(release) + 1e-300), 0.0).unwrap(),
        );
        let e = map.step().unwrap();
        assert_eq!(e.kind, EventKind::Impact);
        let mut inv = InverseMap::new(&sys);
        match inv.previous(e.period, e.phase, e.v) {
            Err(NoPreimage::Release { phase }) => assert!((phase - release).abs() < 1e-9),
            other => panic!("{other:?}"),
        }
        // Not a launch at all: below the table's velocity.
        assert_eq!(
            inv.previous(0, 0.3, sys.df(0.3) - 0.1),
            Err(NoPreimage::NotALaunch)
        );
    }
}
