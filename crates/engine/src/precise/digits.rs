//! Answers to a number of digits: an orbit, or a sticking cycle, run at two precisions
//! and compared, the precision raised where they disagree.

use super::{PreciseEvent, PreciseHalt, PreciseMap, PreciseState, PreciseSystem};
use crate::map::EventKind;
use crate::real::Real;
use std::ops::ControlFlow;

/// The significant decimal digits to which `a` agrees with `b`: ⌊−log₁₀ |a − b|/|b|⌋
/// (|a − b| itself where b = 0), from 0 to `cap` (`cap` where they are equal).
pub fn agreeing_digits<R: Real>(a: &R, b: &R, cap: u32) -> u32 {
    let ctx = a.context();
    let zero = R::from_f64(0.0, &ctx);
    let mut d = (a.clone() - b.clone()).abs();
    if d == zero {
        return cap;
    }
    if *b != zero {
        d = d / b.abs();
    }
    let mut digits = 0u32;
    // Scaled up by 10^100 at a time past what a double can hold.
    while d.to_f64() < 1e-200 && digits < cap {
        // (The double nearest 10^100: a count of digits needs no more.)
        d = d * R::from_f64(1e100, &ctx);
        digits += 100;
    }
    let x = d.to_f64();
    if x >= 1.0 {
        return digits.min(cap);
    }
    (digits + (-x.log10()).floor() as u32).min(cap)
}

/// What makes the system and the start at a number of bits (the caller's parameters,
/// read at that precision).
pub type MakeBig<'a> = dyn Fn(
        usize,
    ) -> (
        PreciseSystem<crate::real::Big>,
        PreciseState<crate::real::Big>,
    ) + 'a;

/// How far a run at any precision has got, for progress reports: the digits it runs
/// at, the events done and how many it is to compute (0 where unknown: a cycle looked
/// for).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DigitsProgress {
    /// The working digits of the run.
    pub digits: u32,
    /// Events computed.
    pub done: u64,
    /// Events to compute (0: not known in advance).
    pub total: u64,
}

/// Events between progress reports.
const PROGRESS_EVENTS: u64 = 256;

/// An orbit computed at two precisions and compared event by event
/// ([`orbit_to_digits`]).
#[derive(Clone, Debug)]
pub struct DigitsOrbit {
    /// The events after the skipped ones, from the more precise run, each with the
    /// significant digits on which the two runs agree (at most the digits asked for).
    pub events: Vec<(PreciseEvent<crate::real::Big>, u32)>,
    /// The digits the compared runs were made at (the last pair tried).
    pub precision: (u32, u32),
    /// Where the less precise run stopped early, if it did.
    pub halt: Option<PreciseHalt>,
    /// Digits lost per event, from the last pair (a least-squares slope through the
    /// events whose agreement is measured), when any were lost.
    pub loss_per_event: Option<f64>,
}

impl DigitsOrbit {
    /// The first printed event that does not hold to `digits`, if any.
    pub fn first_short(&self, digits: u32) -> Option<usize> {
        self.events.iter().position(|(_, d)| *d < digits)
    }
}

/// An orbit to `digits` significant digits: the map run from the start `make(bits)`
/// gives, at `digits` + 10 digits and at twice that, `skip` + `count` events, compared
/// event by event (kind, period, phase, v, vrel); where a printed event agrees to fewer
/// than `digits`, both precisions are doubled and the orbit run again, while the lower
/// stays within `max_digits`. Both runs resolve chattering to the lower precision, so
/// they take the same impacts.
pub fn orbit_to_digits(
    make: &MakeBig<'_>,
    digits: u32,
    max_digits: u32,
    skip: u64,
    count: u64,
    progress: &mut dyn FnMut(DigitsProgress),
) -> DigitsOrbit {
    use crate::real::{bits_for_digits, Big, Number};
    let mut run = |work: u32, bits: usize| {
        let (sys, st) = make(bits);
        let err = Big::from_decimal(&format!("1e-{work}"), &bits).expect("a constant");
        let mut map = PreciseMap::new(sys.with_chatter_error(err), st);
        let mut events = Vec::new();
        let mut halt = None;
        let total = skip.saturating_add(count);
        let digits = (bits as f64 / std::f64::consts::LOG2_10) as u32;
        for i in 0..total {
            if i % PROGRESS_EVENTS == 0 {
                progress(DigitsProgress {
                    digits,
                    done: i,
                    total,
                });
            }
            match map.step() {
                Ok(e) => events.push(e),
                Err(h) => {
                    halt = Some(h);
                    break;
                }
            }
        }
        progress(DigitsProgress {
            digits,
            done: events.len() as u64,
            total,
        });
        (events, halt)
    };
    let mut work = digits + 10;
    loop {
        let (lo, halt) = run(work, bits_for_digits(work));
        let (hi, _) = run(work, bits_for_digits(2 * work));
        let cap = 2 * work;
        let agree = |a: &PreciseEvent<Big>, b: &PreciseEvent<Big>| -> u32 {
            if (a.kind, a.period) != (b.kind, b.period) {
                return 0;
            }
            let mut d =
                agreeing_digits(&a.phase, &b.phase, cap).min(agreeing_digits(&a.v, &b.v, cap));
            if a.kind == EventKind::Impact {
                d = d.min(agreeing_digits(&a.vrel, &b.vrel, cap));
            }
            d
        };
        let all: Vec<u32> = lo.iter().zip(hi.iter()).map(|(a, b)| agree(a, b)).collect();
        // Digits lost by event i of the lower run: work − agreement, where measured.
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for (i, &a) in all.iter().enumerate() {
            if a > 0 && a < work {
                let (x, y) = ((i + 1) as f64, (work - a) as f64);
                sxy += x * y;
                sxx += x * x;
            }
        }
        let loss_per_event = (sxx > 0.0).then(|| sxy / sxx);
        let events: Vec<(PreciseEvent<Big>, u32)> = hi
            .into_iter()
            .zip(all.iter())
            .skip(skip as usize)
            .map(|(e, &a)| (e, a.min(digits)))
            .collect();
        let done = events.iter().all(|(_, d)| *d >= digits);
        if done || 2 * work > max_digits {
            return DigitsOrbit {
                events,
                precision: (work, 2 * work),
                halt,
                loss_per_event,
            };
        }
        work *= 2;
    }
}

/// A sticking cycle found at any precision ([`sticking_cycle_to_digits`]): from a
/// release to the next release at the same phase. Releases happen where 1 + αF'' turns
/// negative, a phase fixed by the table, so the orbit from one release repeats from the
/// next: the cycle is exactly periodic, and all that must be decided is where its stick
/// falls, which the flights from the release decide with growing sensitivity.
#[derive(Clone, Debug, PartialEq)]
pub struct StickingCycle {
    /// Its length in table periods, as both precisions found it.
    pub periods: i64,
    /// The releases (and sticks) in one cycle.
    pub releases: usize,
    /// The release's phase.
    pub release_phase: crate::real::Big,
    /// The time from the release to the cycle's first stick, in table periods.
    pub stick_after: crate::real::Big,
    /// The significant digits on which the two precisions agree about the stick time
    /// (at most the digits asked for).
    pub digits: u32,
    /// The digits of the two runs that agreed.
    pub precision: (u32, u32),
    /// The digits on which the runs of the pair before disagreed, if there was one: how
    /// sensitive the path from the release is.
    pub earlier: Option<((u32, u32), u32)>,
}

/// What [`sticking_cycle_to_digits`] decided.
#[derive(Clone, Debug, PartialEq)]
pub enum CycleVerdict {
    /// The cycle, to the digits asked for.
    Found(StickingCycle),
    /// No release within the events allowed at the first precision: the orbit does not
    /// stick and get released (or not soon enough).
    NoRelease,
    /// No repeating release within the events allowed.
    NoReturn,
    /// The two precisions disagree even at the most precision allowed.
    Undecided {
        /// The digits the last pair was run at.
        tried: (u32, u32),
        /// The digits the two runs agreed on about the stick time (0 where they
        /// disagree on the cycle's length).
        agreed: u32,
        /// The digits the answer needs at least, by the loss measured, where measured:
        /// the digits asked for plus what the stick time lost, or, where the runs part
        /// on the way, the digits lost per event times the events of the cycle as the
        /// more precise run has it (the true path may be longer).
        need: Option<u32>,
    },
}

/// A [`CycleVerdict`] without its numbers of any precision: what a picture of many
/// pixels keeps of each (a few words, where the verdict holds several numbers of any
/// precision).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CycleSummary {
    /// Found.
    Found {
        /// Its length in table periods.
        periods: i64,
        /// The digits the two precisions agree on about its stick time.
        digits: u32,
    },
    /// Undecided within the most digits allowed.
    Undecided {
        /// The digits agreed on about the stick time (0: not on the cycle).
        agreed: u32,
        /// The digits needed, where measured.
        need: Option<u32>,
    },
    /// [`CycleVerdict::NoRelease`].
    NoRelease,
    /// [`CycleVerdict::NoReturn`].
    NoReturn,
}

impl CycleVerdict {
    /// The verdict without its numbers of any precision.
    pub fn summary(&self) -> CycleSummary {
        match self {
            CycleVerdict::Found(c) => CycleSummary::Found {
                periods: c.periods,
                digits: c.digits,
            },
            CycleVerdict::Undecided { agreed, need, .. } => CycleSummary::Undecided {
                agreed: *agreed,
                need: *need,
            },
            CycleVerdict::NoRelease => CycleSummary::NoRelease,
            CycleVerdict::NoReturn => CycleSummary::NoReturn,
        }
    }
}

/// The `max_digits` with which [`sticking_cycle_to_digits`] asked for `digits` tries
/// a pair whose lower precision has at least `need` digits: the precisions it tries
/// are `digits` + 10 doubled, and the lower of a pair must be within `max_digits`.
pub fn max_digits_for(digits: u32, need: u32) -> u32 {
    let mut work = digits.saturating_add(10);
    while work < need {
        work = work.saturating_mul(2);
    }
    work
}

/// Events of the path from the first release a run of [`sticking_cycle_to_digits`] keeps,
/// to measure the digits lost per event where two runs part.
pub const PATH_EVENTS: usize = 100_000;

/// The digits lost per event along two runs' paths from their first release, made at
/// `work` digits and more: a least-squares slope through the events at which the runs
/// agree to some but not all of the `work` digits (0 past the first event where they
/// differ in kind or period). None where no such event was seen.
fn loss_per_event(
    lo: &[(EventKind, i64, crate::real::Big)],
    hi: &[(EventKind, i64, crate::real::Big)],
    work: u32,
) -> Option<f64> {
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, (a, b)) in lo.iter().zip(hi).enumerate() {
        if (a.0, a.1) != (b.0, b.1) {
            break;
        }
        let d = agreeing_digits(&a.2, &b.2, work);
        if d > 0 && d < work {
            let (x, y) = ((i + 1) as f64, (work - d) as f64);
            sxy += x * y;
            sxx += x * x;
        }
    }
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The sticking cycle of the orbit `make(bits)` starts, to `digits` significant digits:
/// each precision pair (`digits` + 10 and twice that, doubled while the lower stays
/// within `max_digits`) runs the orbit to its first release and on to the next release
/// at the same phase (at most `max_events` events each, within `max_periods` table
/// periods), and the two runs must agree on the cycle's length and on its stick time to
/// `digits`. `progress` hears of the events done and may stop the work (then None).
pub fn sticking_cycle_to_digits(
    make: &MakeBig<'_>,
    digits: u32,
    max_digits: u32,
    max_events: u64,
    max_periods: i64,
    progress: &mut dyn FnMut(DigitsProgress) -> ControlFlow<()>,
) -> Option<CycleVerdict> {
    use crate::real::{bits_for_digits, Big, Number};
    // (release phase, stick time, periods, releases), or why there is none.
    // Why a run found no cycle: no release, or none again at the same phase.
    #[derive(Clone, Copy)]
    enum NoCycle {
        Release,
        Return,
        Stopped,
    }
    // Each run also keeps its path from the first release (kind, periods since the
    // release, phase; at most PATH_EVENTS events), so that where two runs part the
    // digits lost per event can be measured.
    type Path = Vec<(EventKind, i64, Big)>;
    let mut cycle =
        |work: u32, bits: usize, path: &mut Path| -> Result<(Big, Big, i64, usize), NoCycle> {
            path.clear();
            let (sys, st) = make(bits);
            let err = Big::from_decimal(&format!("1e-{work}"), &bits).expect("a constant");
            let mut map = PreciseMap::new(sys.with_chatter_error(err), st);
            let mut first: Option<PreciseEvent<Big>> = None;
            let mut stick: Option<Big> = None;
            let mut releases = 0;
            let run_digits = (bits as f64 / std::f64::consts::LOG2_10) as u32;
            for i in 0..max_events {
                if i % PROGRESS_EVENTS == 0
                    && progress(DigitsProgress {
                        digits: run_digits,
                        done: i,
                        total: 0,
                    })
                    .is_break()
                {
                    return Err(NoCycle::Stopped);
                }
                let Ok(e) = map.step() else { break };
                if e.period > max_periods {
                    break;
                }
                if let Some(r0) = first.as_ref().filter(|_| path.len() < PATH_EVENTS) {
                    path.push((e.kind, e.period - r0.period, e.phase.clone()));
                }
                match (&first, e.kind) {
                    (None, EventKind::Release) => first = Some(e),
                    (Some(r0), EventKind::Stick) if stick.is_none() => {
                        let t = Big::from_f64((e.period - r0.period) as f64, &bits)
                            + e.phase.clone()
                            - r0.phase.clone();
                        stick = Some(t);
                    }
                    (Some(r0), EventKind::Release) => {
                        releases += 1;
                        if agreeing_digits(&e.phase, &r0.phase, work) + 5 >= work {
                            return Ok((
                                r0.phase.clone(),
                                stick.expect("a stick before a release"),
                                e.period - r0.period,
                                releases,
                            ));
                        }
                    }
                    _ => {}
                }
            }
            Err(if first.is_none() {
                NoCycle::Release
            } else {
                NoCycle::Return
            })
        };
    let mut work = digits + 10;
    let mut earlier = None;
    let (mut lo_path, mut hi_path) = (Path::new(), Path::new());
    loop {
        let lo = cycle(work, bits_for_digits(work), &mut lo_path);
        let hi = cycle(work, bits_for_digits(2 * work), &mut hi_path);
        if matches!(lo, Err(NoCycle::Stopped)) || matches!(hi, Err(NoCycle::Stopped)) {
            return None;
        }
        // The cycle's length in events from the release, as the more precise run that
        // closed it has it.
        let length = match (&lo, &hi) {
            (_, Ok(_)) => Some(hi_path.len()),
            (Ok(_), _) => Some(lo_path.len()),
            _ => None,
        };
        let (same, agreed, found) = match (lo, hi) {
            (Ok(a), Ok(b)) => {
                let same = a.2 == b.2 && a.3 == b.3;
                let agreed = if same {
                    agreeing_digits(&a.1, &b.1, 2 * work)
                } else {
                    0
                };
                (same, agreed, Some(b))
            }
            // Neither run finds a cycle: the orbit has none within the events allowed.
            (Err(NoCycle::Release), Err(_)) => return Some(CycleVerdict::NoRelease),
            (Err(NoCycle::Return), Err(_)) => return Some(CycleVerdict::NoReturn),
            // One run finds it and the other not: they disagree.
            _ => (false, 0, None),
        };
        if let Some(hi) = found.filter(|_| same && agreed >= digits) {
            return Some(CycleVerdict::Found(StickingCycle {
                periods: hi.2,
                releases: hi.3,
                release_phase: hi.0,
                stick_after: hi.1,
                digits: agreed.min(digits),
                precision: (work, 2 * work),
                earlier,
            }));
        }
        earlier = Some(((work, 2 * work), agreed));
        if 2 * work > max_digits {
            // Where the runs agree on the cycle, the digits its stick time lost; where
            // they part on the way, the digits lost per event of the path times the
            // events of the cycle (as the more precise run has it).
            let need = if same && agreed > 0 {
                Some(digits + (work - agreed.min(work)) + 10)
            } else {
                let rate = loss_per_event(&lo_path, &hi_path, work);
                rate.zip(length)
                    .map(|(rate, n)| digits + (rate * n as f64).ceil() as u32 + 10)
            };
            return Some(CycleVerdict::Undecided {
                tried: (work, 2 * work),
                agreed: agreed.min(digits),
                need,
            });
        }
        work *= 2;
    }
}
