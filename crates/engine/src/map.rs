//! The impact map of the paper's Eq. (map), extended through chattering and sticking.
//!
//! Each call to [`ImpactMap::step`] produces exactly one [`Event`] in bounded work:
//! * `impact`: the next contact, with the restitution law
//!   v' = (1 + r) f'(t') − r (v − (t' − t)), computed as v' = f'(t') − r u_rel.
//! * `stick`: complete chattering was detected. After an impact with relative velocity
//!   w where the table's acceleration f'' > −1, the following impacts shrink
//!   geometrically and accumulate at t + T, T ≈ T₀ = 2w / ((1 + f'')(1 − r)). The map
//!   estimates T to third order in T₀ (see [`crate::chatter`]) and, once the bound of the terms
//!   left out is below [`CHATTER_ERROR`] (10⁻¹⁷, far below the f64 resolution of time),
//!   jumps to t + T; the ball rides on the table.
//! * `release`: the ball leaves the table at the first instant after which f'' < −1
//!   (a smooth crossing, or a jump at a breakpoint of a piecewise table).
//!
//! If no release exists (f'' ≥ −1 everywhere, e.g. the sine table with 4π²α ≤ 1), the
//! ball rests on the table forever: [`Halt::Resting`]. Chattering detection belongs to
//! the exact solver; the paper's grid solver runs as the paper describes it.

use crate::chatter::ChatterSeries;
use crate::error::EngineError;
use crate::impact::{FlightError, FlightSolver, Launch, Solver};
use crate::limits;
use crate::system::System;
use crate::time::normalize;

/// The longest accumulation window the map resolves in one jump (the error bound of the
/// estimate, [`CHATTER_ERROR`], usually decides far below it).
pub const CHATTER_WINDOW: f64 = 1e-3;
/// The largest error accepted for the accumulation time of a chattering sequence: well
/// below the resolution of an f64 phase (1.1·10⁻¹⁶ near 1).
pub const CHATTER_ERROR: f64 = 1e-17;
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
    /// Impact, stick or release.
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
    Resting {
        /// Whole table periods of the time.
        period: i64,
        /// Phase, in [0, 1).
        phase: f64,
    },
    /// The ball did not land within the solver's work bound.
    NoLanding {
        /// Whole table periods of the time.
        period: i64,
        /// Phase, in [0, 1).
        phase: f64,
    },
    /// The next event would lie beyond [`MAX_EVENT_PERIOD`] periods, where (period, phase)
    /// stops being exact; never reached from accepted inputs (transients ≤ 10¹², flights
    /// bounded), but checked so time can never wrap.
    TimeOutOfRange {
        /// Whole table periods of the time.
        period: i64,
        /// Phase, in [0, 1).
        phase: f64,
    },
}

/// The largest |period| an event may have: 2⁵², so that `period as f64 + phase` and
/// every sum of periods the engine forms stay exact and far from i64 overflow.
pub const MAX_EVENT_PERIOD: i64 = 1 << 52;

/// The largest |period| a flight may start from: every flight the accepted inputs allow
/// lasts far less than 2⁴⁰ periods (velocities and heights are bounded), so its landing
/// stays within [`MAX_EVENT_PERIOD`]. One comparison per flight, on the launch.
const MAX_LAUNCH_PERIOD: i64 = MAX_EVENT_PERIOD - (1 << 40);

/// Whether an event time is inside the exact range.
fn in_range(period: i64) -> bool {
    (-MAX_EVENT_PERIOD..=MAX_EVENT_PERIOD).contains(&period)
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
            Halt::TimeOutOfRange { period, phase } => write!(
                f,
                "the event after t = {period} + {phase:.12} lies beyond 2^52 periods, where time is no longer exact"
            ),
        }
    }
}

/// Whether the ball is in flight or riding on the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// In free flight.
    Flying,
    /// Riding on the table (between a stick and its release).
    Stuck,
}

/// The state right after the last event. Its fields are read through accessors: a
/// state is made only by [`State::launch`], [`State::start`] or the map, so its phase
/// lies in [0, 1), its period within [`MAX_EVENT_PERIOD`] and its relative velocity w is
/// v − f'(t) as the map keeps it, exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub(crate) period: i64,
    pub(crate) phase: f64,
    pub(crate) v: f64,
    pub(crate) w: f64,
    pub(crate) height: f64,
    pub(crate) mode: Mode,
    /// After a failed lift-off: look for a release strictly after this instant.
    release_after: bool,
}

impl State {
    /// Whole table periods of the event time.
    pub fn period(&self) -> i64 {
        self.period
    }

    /// Phase in [0, 1).
    pub fn phase(&self) -> f64 {
        self.phase
    }

    /// Ball velocity.
    pub fn v(&self) -> f64 {
        self.v
    }

    /// Velocity relative to the table, v − f'(t), kept exactly.
    pub fn w(&self) -> f64 {
        self.w
    }

    /// Height above the table (nonzero only for an initial state).
    pub fn height(&self) -> f64 {
        self.height
    }

    /// In flight or riding on the table.
    pub fn mode(&self) -> Mode {
        self.mode
    }

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
                name: "v0".into(),
                value: crate::error::fmt_value(v),
                range: "|v0 − f'(t0)| ≤ 1000 (velocity relative to the table)".into(),
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
    /// What the chattering test needs of `sys`, computed once.
    chatter: Chatter,
}

impl ImpactMap {
    /// A map at `state` of `sys`, with the solver prepared once for the system.
    pub fn new(sys: System, solver: Solver, state: State) -> ImpactMap {
        let flights = FlightSolver::new(&sys, solver);
        let chatter = Chatter::new(&sys);
        ImpactMap {
            sys,
            solver,
            state,
            flights,
            chatter,
        }
    }

    /// The system it runs on.
    pub fn system(&self) -> &System {
        &self.sys
    }

    /// The next-contact solver.
    pub fn solver(&self) -> Solver {
        self.solver
    }

    /// The state after the latest event.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Change α (validated as by [`System::set_alpha`]) and prepare the solver and the
    /// chattering test for it again (both hold α-scaled data); set a state afterwards,
    /// since the current one's relative velocity belongs to the old α.
    pub fn set_alpha(&mut self, alpha: f64) -> Result<(), EngineError> {
        self.sys.set_alpha(alpha)?;
        self.flights = FlightSolver::new(&self.sys, self.solver);
        self.chatter = Chatter::new(&self.sys);
        Ok(())
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
        if st.period.unsigned_abs() > MAX_LAUNCH_PERIOD as u64 {
            return Err(Halt::TimeOutOfRange {
                period: st.period,
                phase: st.phase,
            });
        }
        // Most impacts leave faster than any resolvable chattering sequence starts: one
        // comparison dismisses them.
        if st.w <= self.chatter.w_max
            && self.solver == Solver::Exact
            && st.height == 0.0
            && st.w > 0.0
        {
            if let Some((period, phase)) = chatter_limit(&self.sys, &self.chatter, &st) {
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
                let w = -self.sys.r() * l.vrel;
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

    // Out of line, as `release` and `chatter_limit`: rarer than impacts, they would only
    // lengthen the impact path's prologue.
    #[inline(never)]
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

    #[inline(never)]
    fn release(&mut self) -> Result<Event, Halt> {
        let st = self.state;
        match self.sys.table().release_after(
            self.sys.alpha(),
            st.period,
            st.phase,
            st.release_after,
        ) {
            Some((period, _)) if !in_range(period) => Err(Halt::TimeOutOfRange {
                period: st.period,
                phase: st.phase,
            }),
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

/// The chattering test for one system: the series of [`crate::chatter`] at f64, and
/// the relative velocity above which no resolvable sequence starts.
#[derive(Clone, Copy, Debug)]
struct Chatter {
    /// Above this relative velocity no resolvable sequence starts (the window exceeds
    /// [`CHATTER_WINDOW`] even for the largest 1 + f''): the map dismisses such an impact
    /// with this one comparison.
    w_max: f64,
    series: ChatterSeries<f64>,
}

impl Chatter {
    fn new(sys: &System) -> Chatter {
        let r = sys.r();
        let a_max = 1.0 + sys.alpha() * sys.table().accel_bound();
        Chatter {
            w_max: (0.5 * CHATTER_WINDOW * a_max * (1.0 - r)).max(W_FLOOR),
            series: ChatterSeries::new(
                &r,
                sys.alpha() * sys.table().derivative_bound(4),
                sys.alpha() * sys.table().derivative_bound(5),
            ),
        }
    }
}

/// The accumulation window T of the impacts following this post-impact state
/// ([`ChatterSeries::window`] within [`CHATTER_WINDOW`] and [`CHATTER_ERROR`]), when it
/// is resolved. Below [`W_FLOOR`] the leading order is taken whatever its window
/// ("forced").
fn chatter_window(sys: &System, c: &Chatter, st: &State) -> Option<(f64, bool)> {
    // (Above `c.w_max` the window exceeds CHATTER_WINDOW; the map tests that before it
    // calls here.)
    let jet = sys.jet(st.phase);
    let a = 1.0 + jet[2];
    if a <= 0.0 {
        return None;
    }
    let t0 = c.series.leading(&st.w, &a);
    if st.w <= W_FLOOR {
        return Some((t0, true));
    }
    c.series
        .window(&t0, &a, &jet[3], &CHATTER_WINDOW, &CHATTER_ERROR)
        .map(|t| (t, false))
}

/// If the impacts following this post-impact state accumulate within a resolved window
/// ([`chatter_window`]), the accumulation time; the ball then rides on the table. The
/// accumulation must lie before the end of the table's smooth stretch and where the
/// table still accelerates downward slower than gravity.
#[inline(never)]
fn chatter_limit(sys: &System, c: &Chatter, st: &State) -> Option<(i64, f64)> {
    let (window, forced) = chatter_window(sys, c, st)?;
    let mut end = st.phase + window;
    let smooth_end = sys.table().smooth_until(st.phase);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    /// The accumulation time of a chattering sequence, by brute force: every impact
    /// resolved by the exact solver until the window left is below 10⁻¹³ (its own
    /// leading-order estimate then errs by less than 10⁻²⁵), the flights summed.
    fn brute_force(sys: &System, phase: f64, w: f64) -> f64 {
        let solver = FlightSolver::new(sys, Solver::Exact);
        let (mut period, mut phase, mut w) = (0i64, phase, w);
        let mut sum = 0.0;
        for _ in 0..10_000 {
            let a = 1.0 + sys.ddf(phase);
            let left = 2.0 * w / (a * (1.0 - sys.r()));
            if left < 1e-13 {
                return sum + left;
            }
            let launch = Launch {
                period,
                phase,
                height: 0.0,
                v: sys.df(phase) + w,
                w,
            };
            let l = solver.landing(sys, &launch).unwrap();
            sum += l.flight;
            (period, phase, w) = (l.period, l.phase, -sys.r() * l.vrel);
        }
        panic!("no accumulation");
    }

    /// The estimate against the micro-impacts on tables where f''' is large (F_1, whose
    /// f'''' vanishes, and the sine, where the f''''-term is bounded), at the longest
    /// window each accepts: within the accepted error (plus the rounding of the sum),
    /// while the leading-order estimate 2w/((1 + f'')(1 − r)) is off by far more.
    #[test]
    fn chattering_estimate_matches_the_micro_impacts() {
        for (table, alpha, phase) in [
            (Table::fd(1.0).unwrap(), 0.6, 0.7),
            (Table::fd(0.1).unwrap(), 0.6, 0.8),
            (Table::sine(), 0.03, 0.6),
            (Table::sine(), 0.05, 0.55),
        ] {
            for r in [0.5, 0.8, 0.95] {
                let sys = System::new(table.clone(), alpha, r).unwrap();
                let c = Chatter::new(&sys);
                // The largest relative velocity whose sequence is resolved, to 1 %.
                let mut w = c.w_max;
                let state = |w: f64| State {
                    period: 0,
                    phase,
                    v: sys.df(phase) + w,
                    w,
                    height: 0.0,
                    mode: Mode::Flying,
                    release_after: false,
                };
                while chatter_window(&sys, &c, &state(w)).is_none() {
                    w *= 0.99;
                }
                let (estimate, forced) = chatter_window(&sys, &c, &state(w)).unwrap();
                assert!(!forced);
                let brute = brute_force(&sys, phase, w);
                let err = (estimate - brute).abs();
                assert!(
                    err <= CHATTER_ERROR + 8.0 * f64::EPSILON * brute,
                    "{table} α {alpha} r {r}: window {estimate:e}, brute force {brute:e}"
                );
                let leading = 2.0 * w / ((1.0 + sys.ddf(phase)) * (1.0 - r));
                assert!(
                    (leading - brute).abs() > 1e4 * err.max(1e-19),
                    "{table} α {alpha} r {r}: the correction should matter"
                );
                // Far more than the 10⁻⁸ window of the leading order alone.
                assert!(estimate > 1e-7, "{table} α {alpha} r {r}: {estimate:e}");
            }
        }
    }
}
