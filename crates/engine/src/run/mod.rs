//! One orbit from one start to the end of its transient: iterate the impact map,
//! keep the last `keep` events, detect the cycle it settles on and stop early, and
//! resume across checkpoints. Below every client that runs orbits: sweeps (one run per
//! value), attractor identification and basins (one per start), planes (one per
//! pixel).
//!
//! * [`OrbitRun`]: the resumable run and its [`Advance`]; [`Outcome`]: what became of
//!   it; [`Point`]: one recorded event.
//! * [`detect`]: the periodicity detector behind the early stop.
//! * [`start`]: the starts every client uses (next to the (1, 1) solution, a launch
//!   from the table).
//!
//! Recorded points are the last `keep` events whose time is before the end of the
//! transient T (event period < T), exactly what a plain run of [`ImpactMap`] to T
//! records. When the detector accepts a cycle at event n, the events after n are not
//! computed but continued cyclically: the cycle's event i recurs every `periods` table
//! periods, which fixes by integer arithmetic which of them are the last `keep` before
//! T. Memory is the ring of `keep` events plus the detector's fixed history,
//! independent of T.
//!
//! Release cycles. The state right after a release is fixed by the release phase alone
//! (the ball leaves the table with the table's velocity), so when a release happens at
//! bit for bit the phase of an earlier release, the orbit repeats exactly from there,
//! however many events (a chattering sequence can be dozens) lie in between. The run
//! then jumps forward by whole cycles (adding cycles × periods to the state's period,
//! which the map only ever adds to) to a little before T and computes the last cycles
//! for real, so the recorded points are exactly the full run's.

pub mod detect;
pub mod precision;
pub mod start;

/// How close the latest event of a confirmed long cycle must be to the exact cycle
/// Newton's method found (the short detector's tolerance, if larger).
pub const LONG_AGREEMENT: f64 = 1e-9;

use crate::map::{Event, EventKind, Halt, ImpactMap, State};
use detect::{Detector, LongDetector, Periodicity, Rec};
use precision::Precision;
use std::collections::VecDeque;

use crate::jobs::CANCEL_EVERY;

/// What confirming a long cycle holds per event of the cycle, at most, in bytes (its
/// flights and events on the exact map, and the cycle continued): a generous bound.
const CONFIRM_BYTES_PER_EVENT: u64 = 512;

/// One recorded event of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Phase t̂ in [0, 1).
    pub phase: f64,
    /// Ball velocity after the event.
    pub v: f64,
    /// Impact, stick or release.
    pub kind: EventKind,
}

/// What became of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// Provisional (a checkpoint of a resumable run): it has reached this period and
    /// goes on.
    Running {
        /// Period of the latest recorded event.
        reached: i64,
    },
    /// Settled on a cycle of `events` events in `periods` table periods; the run
    /// stopped at period `stopped_at` and the cycle was continued to T.
    Periodic {
        /// Events per cycle (n).
        events: usize,
        /// Table periods per cycle (k).
        periods: i64,
        /// Period of the event at which the cycle was accepted.
        stopped_at: i64,
    },
    /// Ran the full transient without settling on a cycle of at most `max_period`
    /// events (chaos, a long or slowly converging cycle, or early stop switched off).
    Unsettled,
    /// The ball rides on the table forever from this time on.
    Resting {
        /// Whole table periods of the time it came to rest.
        period: i64,
        /// Its phase.
        phase: f64,
    },
    /// The ball did not land within the solver's work bound.
    NoLanding {
        /// Whole table periods of the launch that found no landing.
        period: i64,
        /// Its phase.
        phase: f64,
    },
}

impl Outcome {
    /// Lower-case name used in every output format.
    pub fn as_str(&self) -> &'static str {
        match self {
            Outcome::Running { .. } => "running",
            Outcome::Periodic { .. } => "periodic",
            Outcome::Unsettled => "unsettled",
            Outcome::Resting { .. } => "resting",
            Outcome::NoLanding { .. } => "no-landing",
        }
    }

    /// Events per detected cycle.
    pub fn period(&self) -> Option<usize> {
        match self {
            Outcome::Periodic { events, .. } => Some(*events),
            _ => None,
        }
    }

    /// Table periods per detected cycle (the k of an (n, k) orbit).
    pub fn table_periods(&self) -> Option<i64> {
        match self {
            Outcome::Periodic { periods, .. } => Some(*periods),
            _ => None,
        }
    }
}

/// Why [`OrbitRun::advance`] returned.
#[derive(Debug)]
pub enum Advance {
    /// The run is finished: its outcome and recorded points.
    Done(Outcome, Vec<Point>),
    /// The checkpoint was reached before the end; the run can be resumed.
    Checkpoint,
    /// The cancellation test said stop.
    Cancelled,
}

/// A resumable run of one orbit.
#[derive(Clone, Debug)]
pub struct OrbitRun {
    map: ImpactMap,
    keep: usize,
    ring: VecDeque<Rec>,
    detector: Option<Detector>,
    /// Cycles longer than the detector's, confirmed on the exact map.
    long: Option<LongDetector>,
    /// Events computed so far (including one held back at a checkpoint).
    events: u64,
    /// An event computed past a checkpoint, not yet recorded.
    pending: Option<Event>,
    /// Period of the latest event recorded.
    reached: i64,
    periodicity: Option<Periodicity>,
    /// The latest release: (phase bits, events recorded, period).
    last_release: Option<(u64, u64, i64)>,
    /// A release cycle jumped over: (events, periods, period of the jump).
    jumped: Option<(usize, i64, i64)>,
    /// The detected cycle includes a stick or a release.
    cycle_sticks: bool,
    /// The state right after the latest release.
    released: Option<State>,
}

impl OrbitRun {
    /// A run of `map` from its current state, keeping `keep` events, stopping early on
    /// cycles when `periodicity` is given.
    pub fn new(map: ImpactMap, keep: usize, periodicity: Option<Periodicity>) -> OrbitRun {
        OrbitRun {
            map,
            keep: keep.max(1),
            ring: VecDeque::with_capacity(keep.max(1)),
            detector: periodicity.map(Detector::new),
            long: periodicity.map(|p| LongDetector::new(p.max_period)),
            events: 0,
            pending: None,
            reached: 0,
            periodicity,
            last_release: None,
            jumped: None,
            cycle_sticks: false,
            released: None,
        }
    }

    /// The most a run keeping `keep` events with early stop `periodicity` holds at
    /// once, in bytes, besides the points it hands back: its ring of events, the
    /// detectors' history and what confirming a long cycle takes (the bound of a
    /// memory estimate).
    pub fn bytes(keep: usize, periodicity: Option<Periodicity>) -> u64 {
        let rec = std::mem::size_of::<Rec>() as u64;
        let detectors = periodicity.map_or(0, |p| {
            Detector::capacity(p) as u64 * rec
                + std::mem::size_of::<LongDetector>() as u64
                + detect::LONG_PERIOD as u64 * CONFIRM_BYTES_PER_EVENT
        });
        std::mem::size_of::<OrbitRun>() as u64 + keep.max(1) as u64 * rec + detectors
    }

    /// Events computed so far.
    pub fn events(&self) -> u64 {
        self.events
    }

    /// Period of the latest recorded event.
    pub fn reached(&self) -> i64 {
        self.reached
    }

    /// The system the run is on.
    pub fn system(&self) -> &crate::system::System {
        self.map.system()
    }

    /// The map's current state (after the latest computed event).
    pub fn state(&self) -> State {
        *self.map.state()
    }

    /// The recorded points so far (the last `keep` events before the latest checkpoint).
    pub fn points(&self) -> Vec<Point> {
        self.ring.iter().map(point).collect()
    }

    /// Run until an event at or after period `checkpoint` (≤ `end`), or the end of the
    /// transient `end`, a detected cycle, a halt, or `cancelled()` returning true.
    pub fn advance(
        &mut self,
        checkpoint: i64,
        end: i64,
        cancelled: &mut dyn FnMut(u64) -> bool,
    ) -> Advance {
        let mut since_check = 0u64;
        loop {
            let e = match self.pending.take() {
                Some(e) => e,
                None => {
                    since_check += 1;
                    if since_check == CANCEL_EVERY {
                        since_check = 0;
                        if cancelled(CANCEL_EVERY) {
                            return Advance::Cancelled;
                        }
                    }
                    match self.map.step() {
                        Ok(e) => {
                            self.events += 1;
                            e
                        }
                        Err(h) => {
                            cancelled(since_check);
                            return Advance::Done(halt_outcome(h), self.points());
                        }
                    }
                }
            };
            if e.period >= end {
                cancelled(since_check);
                let outcome = match self.jumped {
                    Some((events, periods, stopped_at)) => Outcome::Periodic {
                        events,
                        periods,
                        stopped_at,
                    },
                    None => Outcome::Unsettled,
                };
                return Advance::Done(outcome, self.points());
            }
            if e.period >= checkpoint {
                self.pending = Some(e);
                cancelled(since_check);
                return Advance::Checkpoint;
            }
            let rec = Rec {
                period: e.period,
                phase: e.phase,
                v: e.v,
                kind: e.kind,
            };
            self.reached = e.period;
            if self.ring.len() == self.keep {
                self.ring.pop_front();
            }
            self.ring.push_back(rec);
            if e.kind == EventKind::Release {
                self.released = Some(*self.map.state());
            }
            if e.kind == EventKind::Release && self.periodicity.is_some() && self.jumped.is_none() {
                self.release_cycle(&e, end);
            }
            if let Some(det) = self.detector.as_mut() {
                if let Some(cycle) = det.push(rec) {
                    let cyc: Vec<Rec> = (0..cycle.events).rev().map(|b| *det.back(b)).collect();
                    self.cycle_sticks = cyc.iter().any(|r| r.kind != EventKind::Impact);
                    let points = self.continue_cycle(&cyc, cycle.periods, end);
                    cancelled(since_check);
                    return Advance::Done(
                        Outcome::Periodic {
                            events: cycle.distinct_events,
                            periods: cycle.distinct_periods,
                            stopped_at: e.period,
                        },
                        points,
                    );
                }
            }
            let candidate = self.long.as_mut().and_then(|l| l.push(rec));
            if let Some((p, k)) = candidate {
                match self.confirm_long(&rec, p, k) {
                    Some((cyc, k)) => {
                        let points = self.continue_cycle(&cyc, k, end);
                        cancelled(since_check);
                        return Advance::Done(
                            Outcome::Periodic {
                                events: cyc.len(),
                                periods: k,
                                stopped_at: e.period,
                            },
                            points,
                        );
                    }
                    None => {
                        if let Some(l) = self.long.as_mut() {
                            l.refuted(p);
                        }
                    }
                }
            }
        }
    }

    /// At a release: if an earlier release had the same phase, jump over whole cycles
    /// to shortly before `end`.
    fn release_cycle(&mut self, e: &Event, end: i64) {
        let n = self.recorded();
        let bits = e.phase.to_bits();
        match self.last_release {
            Some((b, n0, p0)) if b == bits && e.period > p0 => {
                let events = (n - n0) as usize;
                let periods = e.period - p0;
                // Leave enough whole cycles before T to record `keep` events for real.
                // Checked: a jump that cannot be computed in i64 is not taken.
                let target = periods
                    .checked_mul((self.keep / events.max(1)) as i64 + 2)
                    .and_then(|margin| end.checked_sub(e.period)?.checked_sub(margin));
                let cycles = target.map_or(0, |t| t.div_euclid(periods));
                let shift = cycles.checked_mul(periods);
                let landed = shift.and_then(|s| self.map.state().period.checked_add(s));
                self.jumped = Some((events, periods, e.period));
                if let (true, Some(period)) = (cycles > 0, landed) {
                    let mut st = *self.map.state();
                    st.period = period;
                    self.map.set_state(st);
                    // Older history now lies a whole number of cycles back: the
                    // detector's period arithmetic would be off, so restart it.
                    self.detector = self.periodicity.map(Detector::new);
                }
            }
            _ => self.last_release = Some((bits, n, e.period)),
        }
    }

    /// A long-cycle candidate of `p` events in `k` periods ending at `last` (the latest
    /// event), confirmed on the exact map: Newton's method from `last` converges to a
    /// (p, k) cycle that returns within
    /// [`RETURN_TOLERANCE`](crate::orbits::periodic::RETURN_TOLERANCE), is stable, and
    /// has `last` within [`LONG_AGREEMENT`] of it. Returns the cycle's events ending at
    /// the event of `last`, each a whole cycle before its next repetition, and its table
    /// periods (of its own period, a divisor of `p`), or None if refuted.
    fn confirm_long(&self, last: &Rec, p: usize, k: i64) -> Option<(Vec<Rec>, i64)> {
        let tol = self.periodicity?.tolerance;
        let sys = self.map.system();
        let k32 = u32::try_from(k).ok()?;
        let cp = crate::orbits::periodic::cycle(sys, p, k32, last.phase, last.v).ok()?;
        if !cp.stable {
            return None;
        }
        let probe = Rec {
            period: last.period,
            phase: cp.phases[0],
            v: cp.velocities[0],
            kind: EventKind::Impact,
        };
        if last.distance(&probe) > tol.max(LONG_AGREEMENT) {
            return None;
        }
        // A candidate can be a multiple of a shorter cycle met before the short
        // detector accepted it (a slow approach): report the cycle's own period.
        let same = |i: usize, j: usize| {
            crate::time::phase_distance(cp.phases[i], cp.phases[j]) <= LONG_AGREEMENT
                && (cp.velocities[i] - cp.velocities[j]).abs() <= LONG_AGREEMENT
        };
        let q = (1..p)
            .filter(|&q| p.is_multiple_of(q))
            .find(|&q| (0..p - q).all(|i| same(i, i + q)))
            .unwrap_or(p);
        let (p, k) = (q, k * q as i64 / p as i64);
        // Event n + j of the orbit is the cycle's impact j (j = 0 .. p − 1); the cycle's
        // event n − p + 1 + i is its impact i + 1, one cycle (k periods) earlier. Whole
        // periods from event n to impact j: the cycle's own time from its launch less
        // the impact's phase, an integer up to rounding.
        let mut elapsed = cp.phases[0];
        let mut cyc = Vec::with_capacity(p);
        for i in 0..p {
            elapsed += cp.flights[i];
            let j = (i + 1) % p;
            let period = if j == 0 {
                last.period
            } else {
                last.period + (elapsed - cp.phases[j]).round() as i64 - k
            };
            cyc.push(Rec {
                period,
                phase: cp.phases[j],
                v: cp.velocities[j],
                kind: EventKind::Impact,
            });
        }
        Some((cyc, k))
    }

    /// The last `keep` events before `end`, continuing the cycle `cyc` (the last p
    /// events, oldest first, each repeating every `k` periods).
    fn continue_cycle(&self, cyc: &[Rec], k: i64, end: i64) -> Vec<Point> {
        let p = cyc.len() as i64;
        // Events are numbered 1..=n; the cycle is events n − p + 1 ..= n.
        let n = self.recorded() as i64;
        let base = n - p + 1;
        let last = cyc
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let m = (end - 1 - c.period).div_euclid(k).max(0);
                base + i as i64 + m * p
            })
            .max()
            .unwrap_or(n);
        let first = (last - self.keep as i64 + 1).max(1);
        let ring_first = n - self.ring.len() as i64 + 1;
        (first..=last)
            .map(|j| {
                if j <= n {
                    point(&self.ring[(j - ring_first) as usize])
                } else {
                    point(&cyc[((j - base) % p) as usize])
                }
            })
            .collect()
    }

    /// Whether the run, ended with `outcome` and `points`, sticks to the table in what it
    /// settled on: a cycle that includes a stick or a release (whatever points were
    /// kept), a ball at rest, or a stick or release among the kept points. The one
    /// meaning of "sticking" every output uses.
    pub fn sticking(&self, outcome: &Outcome, points: &[Point]) -> bool {
        self.cycle_sticks
            || self.jumped.is_some()
            || matches!(outcome, Outcome::Resting { .. })
            || has_sticking(points)
    }

    /// The state right after the latest release the run recorded, if any (where a
    /// sticking cycle's precision is measured from).
    pub fn released(&self) -> Option<State> {
        self.released
    }

    /// Whether double precision decides the cycle the run ended on (`outcome`, with
    /// `sticking` from [`Self::sticking`]): a sticking cycle is measured from the run's
    /// latest release ([`precision::sticking_cycle`]), any other cycle contracts and is
    /// resolved by construction. None when it did not end on a cycle.
    pub fn precision(&self, outcome: &Outcome, sticking: bool) -> Option<Precision> {
        match *outcome {
            Outcome::Periodic { events, .. } if sticking => {
                let from = self.released.unwrap_or(self.state());
                let map = ImpactMap::new(self.system().clone(), self.map.solver(), from);
                precision::sticking_cycle(map, events)
            }
            Outcome::Periodic { .. } => Some(Precision::CONTRACTING),
            _ => None,
        }
    }

    /// Number of events recorded (pushed to the ring).
    fn recorded(&self) -> u64 {
        self.events - u64::from(self.pending.is_some())
    }
}

fn point(r: &Rec) -> Point {
    Point {
        phase: r.phase,
        v: r.v,
        kind: r.kind,
    }
}

fn halt_outcome(h: Halt) -> Outcome {
    match h {
        Halt::Resting { period, phase } => Outcome::Resting { period, phase },
        // No further event could be computed: the solver's work bound, or (never from
        // accepted inputs) a time beyond the exact range.
        Halt::NoLanding { period, phase } | Halt::TimeOutOfRange { period, phase } => {
            Outcome::NoLanding { period, phase }
        }
    }
}

/// Whether any point is a stick or a release.
pub fn has_sticking(points: &[Point]) -> bool {
    points.iter().any(|p| p.kind != EventKind::Impact)
}
