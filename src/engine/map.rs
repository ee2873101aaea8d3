//! The impact map of the paper's Eq. (map), extended through chattering and sticking.
//!
//! Each call to [`ImpactMap::step`] produces exactly one [`Event`] in bounded work:
//! * `impact`: the next contact, with the restitution law
//!   v' = (1 + r) f'(t') − r (v − (t' − t)), computed as v' = f'(t') − r u_rel.
//! * `stick`: complete chattering was detected. After an impact with relative velocity
//!   w where the table's acceleration f'' > −1, the following impacts shrink
//!   geometrically and accumulate at t_c ≈ t + 2w / ((1 + f'')(1 − r)). Once that
//!   window is shorter than [`CHATTER_WINDOW`] (its error is then far below the f64
//!   resolution of time) the map jumps to t_c and the ball rides on the table.
//! * `release`: the ball leaves the table at the first instant after which f'' < −1
//!   (a smooth crossing, or a jump at a breakpoint of a piecewise table).
//!
//! If no release exists (f'' ≥ −1 everywhere, e.g. the sine table with 4π²α ≤ 1), the
//! ball rests on the table forever: [`Halt::Resting`]. Chattering detection belongs to
//! the exact solver; the paper's grid solver runs as the paper describes it.

use super::error::EngineError;
use super::impact::{next_landing, normalize, FlightError, Launch, Solver};
use super::system::System;
use super::table::Shape;
use std::f64::consts::PI;

/// Chattering is resolved once the predicted accumulation window is shorter than this.
pub const CHATTER_WINDOW: f64 = 1e-8;
/// Below this relative velocity the ball is taken to be on the table whatever the window.
pub const W_FLOOR: f64 = 1e-14;
/// Largest relative velocity |v0 − f'(t0)| and initial height accepted for an initial state.
pub const MAX_INITIAL: f64 = 1e3;

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// The ball hit the table.
    Impact,
    /// Chattering accumulated: from here the ball rides on the table.
    Stick,
    /// The ball left the table it was riding on.
    Release,
}

impl EventKind {
    /// Lower-case name used in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            EventKind::Impact => "impact",
            EventKind::Stick => "stick",
            EventKind::Release => "release",
        }
    }
}

/// One event of the map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    pub kind: EventKind,
    /// Integer part of the time.
    pub period: i64,
    /// Phase t̂ in [0, 1).
    pub phase: f64,
    /// Ball velocity after the event.
    pub v: f64,
    /// Relative velocity at contact u − f'(t) (≤ 0; 0 for stick and release).
    pub vrel: f64,
}

impl Event {
    /// Absolute time as one f64, for display only (it loses phase precision at large t).
    pub fn time(&self) -> f64 {
        self.period as f64 + self.phase
    }
}

/// Why the map cannot produce another event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Halt {
    /// The ball rides on the table forever from this time: f'' ≥ −1 everywhere.
    Resting { period: i64, phase: f64 },
    /// The ball did not land within the solver's work bound.
    NoLanding { period: i64, phase: f64 },
}

impl std::fmt::Display for Halt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Halt::Resting { period, phase } => write!(
                f,
                "the ball rests on the table from t = {period} + {phase:.12} on: f'' ≥ −1 everywhere, so it is never released"
            ),
            Halt::NoLanding { period, phase } => write!(
                f,
                "the ball launched at t = {period} + {phase:.12} did not land within the solver's work bound"
            ),
        }
    }
}

/// Whether the ball is in flight or riding on the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Flying,
    Stuck,
}

/// The state right after the last event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub period: i64,
    /// Phase in [0, 1).
    pub phase: f64,
    /// Ball velocity.
    pub v: f64,
    /// Velocity relative to the table, v − f'(t), kept exactly.
    pub w: f64,
    /// Height above the table (nonzero only for an initial state).
    pub height: f64,
    pub mode: Mode,
    /// After a failed lift-off: look for a release strictly after this instant.
    release_after: bool,
}

impl State {
    /// A ball launched from the table at (period, phase) with velocity `v`, `height`
    /// above the table. With height 0 it must not move into the table: v ≥ f'(t).
    pub fn launch(
        sys: &System,
        period: i64,
        phase: f64,
        v: f64,
        height: f64,
    ) -> Result<State, EngineError> {
        if !(phase.is_finite() && (0.0..1.0).contains(&phase)) {
            return Err(EngineError::InvalidParameter {
                name: "t0",
                value: phase.to_string(),
                range: "a phase in [0, 1)",
            });
        }
        if !(v.is_finite() && (v - sys.df(phase)).abs() <= MAX_INITIAL) {
            return Err(EngineError::InvalidParameter {
                name: "v0",
                value: v.to_string(),
                range: "|v0 − f'(t0)| ≤ 1000 (velocity relative to the table)",
            });
        }
        if !(height.is_finite() && (0.0..=MAX_INITIAL).contains(&height)) {
            return Err(EngineError::InvalidParameter {
                name: "z0",
                value: height.to_string(),
                range: "[0, 1000] (height above the table)",
            });
        }
        let df = sys.df(phase);
        let w = v - df;
        if height == 0.0 && w < 0.0 {
            return Err(EngineError::BelowTable(format!(
                "v0 = {v} is below the table's velocity f'(t0) = {df:.6} at t0 = {phase}; valid v0 ≥ {df:.6} (or give z0 > 0)"
            )));
        }
        Ok(State {
            period,
            phase,
            v,
            w,
            height,
            mode: Mode::Flying,
            release_after: false,
        })
    }

    /// Absolute time as one f64, for display only.
    pub fn time(&self) -> f64 {
        self.period as f64 + self.phase
    }
}

/// The impact map on one system with one solver.
#[derive(Clone, Debug)]
pub struct ImpactMap {
    sys: System,
    solver: Solver,
    state: State,
}

impl ImpactMap {
    pub fn new(sys: System, solver: Solver, state: State) -> ImpactMap {
        ImpactMap { sys, solver, state }
    }

    pub fn system(&self) -> &System {
        &self.sys
    }

    pub fn solver(&self) -> Solver {
        self.solver
    }

    pub fn state(&self) -> &State {
        &self.state
    }

    /// Replace the state (e.g. to step back through a history).
    pub fn set_state(&mut self, state: State) {
        self.state = state;
    }

    /// Advance by exactly one event, in bounded work.
    pub fn step(&mut self) -> Result<Event, Halt> {
        match self.state.mode {
            Mode::Flying => self.fly(),
            Mode::Stuck => self.release(),
        }
    }

    fn fly(&mut self) -> Result<Event, Halt> {
        let st = self.state;
        if self.solver == Solver::Exact && st.height == 0.0 && st.w > 0.0 {
            if let Some((period, phase)) = chatter_limit(&self.sys, &st) {
                return Ok(self.stick_at(period, phase, false));
            }
        }
        let launch = Launch {
            period: st.period,
            phase: st.phase,
            height: st.height,
            v: st.v,
            w: st.w,
        };
        match next_landing(&self.sys, self.solver, &launch) {
            Ok(l) => {
                let df = l.df;
                let w = -self.sys.r * l.vrel;
                self.state = State {
                    period: l.period,
                    phase: l.phase,
                    v: df + w,
                    w,
                    height: 0.0,
                    mode: Mode::Flying,
                    release_after: false,
                };
                Ok(Event {
                    kind: EventKind::Impact,
                    period: l.period,
                    phase: l.phase,
                    v: df + w,
                    vrel: l.vrel,
                })
            }
            Err(FlightError::NoLiftOff) => Ok(self.stick_at(st.period, st.phase, true)),
            Err(FlightError::NoLanding) => Err(Halt::NoLanding {
                period: st.period,
                phase: st.phase,
            }),
        }
    }

    fn stick_at(&mut self, period: i64, phase: f64, release_after: bool) -> Event {
        let df = self.sys.df(phase);
        self.state = State {
            period,
            phase,
            v: df,
            w: 0.0,
            height: 0.0,
            mode: Mode::Stuck,
            release_after,
        };
        Event {
            kind: EventKind::Stick,
            period,
            phase,
            v: df,
            vrel: 0.0,
        }
    }

    fn release(&mut self) -> Result<Event, Halt> {
        let st = self.state;
        match find_release(&self.sys, st.period, st.phase, st.release_after) {
            Some((period, phase)) => {
                let df = self.sys.df(phase);
                self.state = State {
                    period,
                    phase,
                    v: df,
                    w: 0.0,
                    height: 0.0,
                    mode: Mode::Flying,
                    release_after: false,
                };
                Ok(Event {
                    kind: EventKind::Release,
                    period,
                    phase,
                    v: df,
                    vrel: 0.0,
                })
            }
            None => Err(Halt::Resting {
                period: st.period,
                phase: st.phase,
            }),
        }
    }
}

/// If the impacts following this post-impact state accumulate within
/// [`CHATTER_WINDOW`], the accumulation time.
fn chatter_limit(sys: &System, st: &State) -> Option<(i64, f64)> {
    // The window 2w/((1 + f'')(1 − r)) cannot be short while w is large compared with
    // the largest possible 1 + f'': most impacts are dismissed here without evaluating f''.
    let a_max = 1.0 + sys.alpha * sys.table.accel_bound();
    if st.w > W_FLOOR && 2.0 * st.w > CHATTER_WINDOW * a_max * (1.0 - sys.r) {
        return None;
    }
    let a = 1.0 + sys.ddf(st.phase);
    if a <= 0.0 {
        return None;
    }
    let window = 2.0 * st.w / (a * (1.0 - sys.r));
    let forced = st.w <= W_FLOOR;
    if window > CHATTER_WINDOW && !forced {
        return None;
    }
    let mut end = st.phase + window;
    if let Shape::Piecewise(pieces) = sys.table.shape() {
        let p = &pieces[sys.table.piece_index(st.phase)];
        if end >= p.end {
            if !forced {
                return None;
            }
            end = p.end;
        }
    }
    let (period, phase) = normalize(st.period, end);
    if !forced && 1.0 + sys.ddf(phase) <= 0.0 {
        return None;
    }
    Some((period, phase))
}

/// The first instant from (period, phase) on after which f'' < −1, or None if the
/// table never accelerates downward faster than gravity.
pub fn find_release(
    sys: &System,
    period: i64,
    phase: f64,
    strictly_after: bool,
) -> Option<(i64, f64)> {
    match sys.table.shape() {
        Shape::Sine => {
            let c = 4.0 * PI * PI * sys.alpha;
            if c <= 1.0 {
                return None;
            }
            let theta = (1.0 / c).asin() / (2.0 * PI);
            if !strictly_after && phase > theta && phase < 0.5 - theta {
                return Some((period, phase));
            }
            if phase < theta {
                Some((period, theta))
            } else {
                Some((period + 1, theta))
            }
        }
        Shape::Piecewise(pieces) => {
            let n = pieces.len();
            let j0 = sys.table.piece_index(phase);
            for step in 0..=n {
                let j = (j0 + step) % n;
                let per = period + ((j0 + step) / n) as i64;
                let p = &pieces[j];
                let accel = p.d2.scale(sys.alpha);
                let excess = accel.with_coeff(0, accel.coeff(0) + 1.0);
                let s0 = if step == 0 { phase - p.start } else { 0.0 };
                let skip_start = step == 0 && strictly_after;
                let (r0, e0) = excess.eval_with_bound(s0);
                if r0 < -e0 && !skip_start {
                    return Some(normalize(per, p.start + s0));
                }
                let roots = excess.roots_in(s0, p.len());
                let rs = roots.as_slice();
                for (i, &rho) in rs.iter().enumerate() {
                    if skip_start && rho <= s0 {
                        continue;
                    }
                    let next = rs.get(i + 1).copied().unwrap_or(p.len());
                    if next > rho && excess.eval(0.5 * (rho + next)) < 0.0 {
                        return Some(normalize(per, p.start + rho));
                    }
                }
            }
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::table::Table;

    #[test]
    fn quad_release_is_at_phase_zero() {
        // fd:0: f'' = −2α on [0, ½), +2α on [½, 1). With α = 0.6 the ball is released
        // where f'' jumps to −1.2 < −1, i.e. at every integer time.
        let sys = System::new(Table::fd(0.0).unwrap(), 0.6, 0.8).unwrap();
        assert_eq!(find_release(&sys, 3, 0.7, false), Some((4, 0.0)));
        // Inside the downward-accelerating half the release is immediate.
        assert_eq!(find_release(&sys, 3, 0.2, false), Some((3, 0.2)));
        // With α = 0.4 (f'' ≥ −0.8) the ball is never released.
        let calm = System::new(Table::fd(0.0).unwrap(), 0.4, 0.8).unwrap();
        assert_eq!(find_release(&calm, 0, 0.7, false), None);
    }

    #[test]
    fn sine_release_closed_form() {
        let alpha = 0.1;
        let sys = System::new(Table::sine(), alpha, 0.5).unwrap();
        let theta = (1.0 / (4.0 * PI * PI * alpha)).asin() / (2.0 * PI);
        let (n, ph) = find_release(&sys, 0, 0.6, false).unwrap();
        assert_eq!(n, 1);
        assert!((ph - theta).abs() < 1e-15);
        // −f''(θ) = 4π²α sin 2πθ = 1 exactly.
        assert!((sys.jet(ph)[2] + 1.0).abs() < 1e-12);
    }
}
