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

use crate::error::EngineError;
use crate::impact::{normalize, FlightError, FlightSolver, Launch, Solver};
use crate::limits;
use crate::system::System;

/// Chattering is resolved once the predicted accumulation window is shorter than this.
pub const CHATTER_WINDOW: f64 = 1e-8;
/// Below this relative velocity the ball is taken to be on the table whatever the window.
pub const W_FLOOR: f64 = 1e-14;
/// Relative velocity of the default start: a short hop leaving the table at t̂0 with
/// v0 = f'(t̂0) + 0.5 (every command and the terminal application start here unless told
/// otherwise).
pub const DEFAULT_HOP: f64 = 0.5;

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
        limits::PHASE.check(phase)?;
        if !(v.is_finite() && (v - sys.df(phase)).abs() <= limits::MAX_INITIAL) {
            return Err(EngineError::InvalidParameter {
                name: "v0",
                value: crate::error::fmt_value(v),
                range: "|v0 − f'(t0)| ≤ 1000 (velocity relative to the table)",
            });
        }
        limits::HEIGHT.check(height)?;
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

    /// The start at period 0: phase `t0`, velocity `v0` (default f'(t0) +
    /// [`DEFAULT_HOP`]) and height `z0` above the table, validated as [`Self::launch`].
    pub fn start(sys: &System, t0: f64, v0: Option<f64>, z0: f64) -> Result<State, EngineError> {
        limits::PHASE.check(t0)?;
        let v0 = v0.unwrap_or_else(|| sys.df(t0) + DEFAULT_HOP);
        State::launch(sys, 0, t0, v0, z0)
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
    /// The solver prepared for `sys` once.
    flights: FlightSolver,
}

impl ImpactMap {
    pub fn new(sys: System, solver: Solver, state: State) -> ImpactMap {
        let flights = FlightSolver::new(&sys, solver);
        ImpactMap {
            sys,
            solver,
            state,
            flights,
        }
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
        match self.flights.landing(&self.sys, &launch) {
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
        match self
            .sys
            .table
            .release_after(self.sys.alpha, st.period, st.phase, st.release_after)
        {
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
    let smooth_end = sys.table.smooth_until(st.phase);
    if end >= smooth_end {
        if !forced {
            return None;
        }
        end = smooth_end;
    }
    let (period, phase) = normalize(st.period, end);
    if !forced && 1.0 + sys.ddf(phase) <= 0.0 {
        return None;
    }
    Some((period, phase))
}
