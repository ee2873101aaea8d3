//! Periodicity detection for early stopping: decides when an orbit has settled on a
//! cycle so closely that running it to the end of the transient cannot move its points
//! by more than the tolerance.
//!
//! The detector keeps the last few hundred events. Every [`CHECK_EVERY`] events it looks
//! for the smallest p ≤ `max_period` such that each of the last p events matches the
//! event p before it: same kind, phase within the tolerance (measured around the circle,
//! so 0.999 999 999 999 9 and 10⁻¹³ are close) and velocity within the tolerance. A
//! match alone is not enough near a bifurcation, where the orbit creeps towards its
//! cycle at a rate close to 1 per cycle. So the detector measures that rate: d_new, the
//! largest mismatch over the latest window of h ≥ [`WINDOW`] events (a multiple of p),
//! and d_old over the window before it give a contraction ρ per cycle, and the distance
//! still to travel is bounded by the geometric tail d_new / (1 − ρ). The cycle is
//! accepted only when that bound is within the tolerance, or when the orbit repeats
//! bit for bit (the map is deterministic, so it then repeats forever). When both
//! windows are at round-off level the last reliable rate measured for this p is used;
//! if none was ever measured the orbit fell to round-off within two windows, which only
//! a strongly contracting cycle does, and it is accepted unless the mismatch grew from
//! the older window to the newer (an unstable cycle met at round-off level).

use crate::map::EventKind;

/// How often (in events) the detector looks for a cycle.
pub const CHECK_EVERY: u64 = 16;
/// Minimum number of events in each of the two windows that measure the contraction.
pub const WINDOW: usize = 64;
/// Mismatches below this are round-off: they say nothing about the contraction rate.
pub const ROUNDOFF: f64 = 1e-13;

/// Early-stop settings: the longest cycle looked for and the agreement promised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Periodicity {
    /// Longest cycle, in events, that is detected (stick and release count as events).
    pub max_period: usize,
    /// Phase and velocity tolerance: a detected cycle's points agree with the full
    /// transient's points to within this.
    pub tolerance: f64,
}

impl Periodicity {
    /// Check the longest cycle and the tolerance against their ranges.
    pub fn validate(&self) -> Result<(), crate::error::EngineError> {
        crate::limits::MAX_PERIOD.check(self.max_period as f64)?;
        crate::limits::TOLERANCE.check(self.tolerance)?;
        Ok(())
    }
}

impl Default for Periodicity {
    fn default() -> Self {
        Periodicity {
            max_period: 64,
            tolerance: 1e-11,
        }
    }
}

/// One event as the detector sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rec {
    /// Whole table periods of the event time.
    pub period: i64,
    /// Phase, in [0, 1).
    pub phase: f64,
    /// Ball velocity after the event.
    pub v: f64,
    /// Impact, stick or release.
    pub kind: EventKind,
}

impl Rec {
    /// Distance used for cycle detection: infinite across kinds, otherwise the larger
    /// of the circular phase distance and the velocity difference.
    #[inline]
    pub fn distance(&self, other: &Rec) -> f64 {
        if self.kind != other.kind {
            return f64::INFINITY;
        }
        let mut dp = (self.phase - other.phase).abs();
        if dp > 0.5 {
            dp = 1.0 - dp;
        }
        dp.max((self.v - other.v).abs())
    }
}

/// A detected cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cycle {
    /// Events per cycle as continued (the repetition that was measured).
    pub events: usize,
    /// Table periods per cycle as continued.
    pub periods: i64,
    /// The shortest divisor q of `events` whose repetition also holds within twice the
    /// tolerance: the period to report. A fixed point approached with eigenvalue
    /// near −1 converges as a 2-cycle (its mismatch after one event is large), yet its
    /// two points end up within the tolerance of each other: it is reported as 1.
    pub distinct_events: usize,
    /// Table periods per reported cycle.
    pub distinct_periods: i64,
}

/// Sliding history of events and the cycle test.
#[derive(Clone, Debug)]
pub struct Detector {
    cfg: Periodicity,
    hist: Vec<Rec>,
    mask: usize,
    /// Events pushed so far.
    count: u64,
    /// The last contraction per cycle measured above round-off, for its cycle length.
    rate: Option<(usize, f64)>,
}

impl Detector {
    /// Events of history a detector with settings `cfg` keeps.
    pub fn capacity(cfg: Periodicity) -> usize {
        let p = cfg.max_period.max(1);
        // Two windows of at most WINDOW + p − 1 events each, plus one cycle.
        (2 * (WINDOW + p) + p).next_power_of_two()
    }

    /// A detector with no history.
    pub fn new(cfg: Periodicity) -> Detector {
        let cap = Detector::capacity(cfg);
        Detector {
            cfg,
            hist: vec![
                Rec {
                    period: 0,
                    phase: 0.0,
                    v: 0.0,
                    kind: EventKind::Impact,
                };
                cap
            ],
            mask: cap - 1,
            count: 0,
            rate: None,
        }
    }

    /// The event `back` events before the latest one (0 = the latest).
    #[inline]
    pub fn back(&self, back: usize) -> &Rec {
        debug_assert!((back as u64) < self.count && back <= self.mask);
        &self.hist[(self.count as usize).wrapping_sub(1 + back) & self.mask]
    }

    /// Add an event; every [`CHECK_EVERY`] events, test for a settled cycle.
    #[inline]
    pub fn push(&mut self, rec: Rec) -> Option<Cycle> {
        self.hist[self.count as usize & self.mask] = rec;
        self.count += 1;
        if self.count.is_multiple_of(CHECK_EVERY) {
            self.check()
        } else {
            None
        }
    }

    /// Largest mismatch between events `from..from + len` back and their p-predecessors.
    fn mismatch(&self, p: usize, from: usize, len: usize, limit: f64) -> f64 {
        let mut d: f64 = 0.0;
        for j in from..from + len {
            d = d.max(self.back(j).distance(self.back(j + p)));
            if d > limit {
                break;
            }
        }
        d
    }

    fn check(&mut self) -> Option<Cycle> {
        let tol = self.cfg.tolerance;
        let avail = self.count.min(self.mask as u64 + 1) as usize;
        let latest = self.hist[(self.count as usize).wrapping_sub(1) & self.mask].phase;
        for p in 1..=self.cfg.max_period {
            if 2 * p > avail {
                return None;
            }
            // The latest event's phase against the one p back first: one subtraction
            // rules out nearly every p of an orbit that has not settled.
            let dp = (latest - self.back(p).phase).abs();
            if dp > tol && dp < 1.0 - tol {
                continue;
            }
            if self.mismatch(p, 0, p, tol) > tol {
                continue;
            }
            // The smallest matching p is the candidate; its multiples are not tried.
            let h = p * WINDOW.div_ceil(p);
            if 2 * h + p > avail {
                return None;
            }
            let d_new = self.mismatch(p, 0, h, tol);
            if d_new > tol {
                return None;
            }
            let accept = if d_new == 0.0 {
                true
            } else {
                let d_old = self.mismatch(p, h, h, f64::INFINITY);
                if d_old >= ROUNDOFF && d_new < d_old {
                    let per_cycle = (d_new / d_old).powf(p as f64 / h as f64);
                    self.rate = Some((p, per_cycle));
                } else if d_old >= ROUNDOFF {
                    // Not contracting (yet): forget any older estimate.
                    self.rate = None;
                    return None;
                }
                match self.rate {
                    Some((q, rho)) if q == p => d_new / (1.0 - rho) <= tol,
                    _ => d_old < ROUNDOFF && d_new < ROUNDOFF && d_new <= d_old,
                }
            };
            if !accept {
                return None;
            }
            let last = self.back(0);
            let prev = self.back(p);
            let span = (last.period - prev.period) as f64 + (last.phase - prev.phase);
            let periods = span.round() as i64;
            if periods < 1 {
                return None;
            }
            let q = (1..p)
                .filter(|q| p % q == 0)
                .find(|&q| self.mismatch(q, 0, p, 2.0 * tol) <= 2.0 * tol)
                .unwrap_or(p);
            return Some(Cycle {
                events: p,
                periods,
                distinct_events: q,
                distinct_periods: periods * q as i64 / p as i64,
            });
        }
        None
    }
}

/// The longest cycle, in events, the long-cycle stage looks for.
pub const LONG_PERIOD: usize = 4096;
/// Events a run computes before the long-cycle stage starts: the short detector
/// settles the common short cycles long before, so they never pay for it.
pub const LONG_START: u64 = 1024;
/// Distance under which a return to an earlier event makes a long-cycle candidate, to
/// be confirmed by Newton's method on the exact map (a chaotic orbit comes back this
/// close about once in 10¹² events).
pub const LONG_CANDIDATE: f64 = 1e-7;

/// The long-cycle stage: Brent's cycle detection on the events with a tolerance. A
/// saved event (the tortoise) is compared with every later one; it moves to the latest
/// event after 128, 256, … [`LONG_PERIOD`] events (and every [`LONG_PERIOD`] after
/// that), so a cycle of p ≤ [`LONG_PERIOD`] events returns to it within two of its
/// stretches once the orbit has converged. A return within [`LONG_CANDIDATE`] after
/// more than `short` events, with only impacts in between (stick–release cycles repeat
/// exactly and are caught by the run itself), is a candidate (events, table periods),
/// never a verdict: the run confirms it on the exact map. Constant memory.
#[derive(Clone, Debug)]
pub struct LongDetector {
    short: usize,
    tortoise: Option<Rec>,
    power: usize,
    lam: usize,
    impacts_only: bool,
    /// Events pushed so far.
    count: u64,
    /// No candidate before this event (after a refuted one).
    quiet_until: u64,
    /// Candidates refuted so far.
    refuted: u32,
}

impl LongDetector {
    /// A stage that looks for cycles longer than `short` events (the short
    /// detector's limit), up to [`LONG_PERIOD`].
    pub fn new(short: usize) -> LongDetector {
        LongDetector {
            short,
            tortoise: None,
            power: 128,
            lam: 0,
            impacts_only: true,
            count: 0,
            quiet_until: LONG_START,
            refuted: 0,
        }
    }

    /// Add an event; a candidate (events, table periods) when it returns to the
    /// tortoise.
    #[inline]
    pub fn push(&mut self, rec: Rec) -> Option<(usize, i64)> {
        self.count += 1;
        if self.count < LONG_START {
            return None;
        }
        let Some(t) = self.tortoise else {
            self.tortoise = Some(rec);
            return None;
        };
        self.lam += 1;
        self.impacts_only &= rec.kind == EventKind::Impact;
        let mut found = None;
        // The phase first (two comparisons rule out nearly every event), then the
        // whole distance.
        let dp = (rec.phase - t.phase).abs();
        if self.lam > self.short
            && (dp <= LONG_CANDIDATE || dp >= 1.0 - LONG_CANDIDATE)
            && self.impacts_only
            && self.count >= self.quiet_until
            && rec.distance(&t) <= LONG_CANDIDATE
        {
            let span = (rec.period - t.period) as f64 + (rec.phase - t.phase);
            let periods = span.round() as i64;
            if periods >= 1 {
                found = Some((self.lam, periods));
            }
        }
        if self.lam == self.power || found.is_some() {
            self.tortoise = Some(rec);
            self.power = (2 * self.power).min(LONG_PERIOD);
            self.lam = 0;
            self.impacts_only = true;
        }
        found
    }

    /// A candidate of `events` events was refuted: no new one for a few of its lengths,
    /// twice as many after each refutation (an orbit shadowing unstable cycles would
    /// otherwise ask for Newton's method again and again).
    pub fn refuted(&mut self, events: usize) {
        self.quiet_until = self.count + ((4 * events as u64) << self.refuted.min(20));
        self.refuted += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(period: i64, phase: f64, v: f64) -> Rec {
        Rec {
            period,
            phase,
            v,
            kind: EventKind::Impact,
        }
    }

    #[test]
    fn circular_phase_distance() {
        let a = rec(0, 1e-13, 0.5);
        let b = rec(0, 1.0 - 1e-13, 0.5);
        assert!((a.distance(&b) - 2e-13).abs() < 1e-16);
        let mut c = b;
        c.kind = EventKind::Stick;
        assert_eq!(b.distance(&c), f64::INFINITY);
    }

    #[test]
    fn exact_two_cycle_is_found_with_its_periods() {
        let mut d = Detector::new(Periodicity::default());
        let mut found = None;
        for n in 0..10_000i64 {
            let r = if n % 2 == 0 {
                rec(n, 0.25, 0.4)
            } else {
                rec(n, 0.75, 0.6)
            };
            if let Some(c) = d.push(r) {
                found = Some((n, c));
                break;
            }
        }
        let (n, c) = found.expect("a 2-cycle");
        assert_eq!(
            c,
            Cycle {
                events: 2,
                periods: 2,
                distinct_events: 2,
                distinct_periods: 2,
            }
        );
        assert!(n < 400, "found only after {n} events");
    }

    #[test]
    fn slow_contraction_waits_for_the_tail_bound() {
        // A fixed point approached as x_n = x* + c ρⁿ with ρ = 0.99 per event: the step
        // mismatch c ρⁿ (1 − ρ) is below 1e-11 long before the distance c ρⁿ is.
        let rho: f64 = 0.99;
        let mut d = Detector::new(Periodicity::default());
        for n in 0..100_000i64 {
            let x = 0.3 + 1e-3 * rho.powi(n as i32);
            if d.push(rec(n, x, 0.5)).is_some() {
                let remaining = 1e-3 * rho.powi(n as i32);
                assert!(remaining <= 1e-11, "accepted {remaining} from the limit");
                // ...and not absurdly late: within a few windows of the tail bound.
                assert!(remaining > 1e-13, "accepted only at {remaining}");
                return;
            }
        }
        panic!("never accepted a converging orbit");
    }

    #[test]
    fn fixed_point_approached_by_alternation_is_reported_as_period_one() {
        // x_n = x* + c (−0.999)ⁿ: the one-step mismatch stays ~2|x − x*|, so the
        // two-step repetition is accepted first, with both points within 1e-11 of x*.
        let mut d = Detector::new(Periodicity::default());
        for n in 0..200_000i64 {
            let x = 0.3 + 1e-3 * (-0.999f64).powi(n as i32);
            if let Some(c) = d.push(rec(n, x, 0.5)) {
                assert_eq!((c.events, c.distinct_events, c.distinct_periods), (2, 1, 1));
                return;
            }
        }
        panic!("never accepted");
    }

    #[test]
    fn growing_oscillation_is_never_accepted() {
        let mut d = Detector::new(Periodicity::default());
        for n in 0..5_000i64 {
            let eps = 1e-14 * 1.01f64.powi(n as i32);
            let x = 0.3 + if n % 2 == 0 { eps } else { -eps };
            assert!(d.push(rec(n, x, 0.5)).is_none(), "accepted at {n}");
        }
    }

    #[test]
    fn cycle_longer_than_the_limit_is_not_reported() {
        let cfg = Periodicity {
            max_period: 4,
            tolerance: 1e-11,
        };
        let mut d = Detector::new(cfg);
        for n in 0..5_000i64 {
            let phase = (n % 5) as f64 / 5.0;
            assert!(d.push(rec(n, phase, 0.5)).is_none());
        }
    }
}
