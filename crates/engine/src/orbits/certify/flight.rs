//! The proof that a landing is the *first* contact of its flight.
//!
//! A ball launched at phase φ with velocity v (boxes) flies above the table while the
//! gap g(τ) = f(φ) + vτ − τ²/2 − f(φ + τ) is positive. The landing lies in a box of
//! flight times T where g has a root. The flight is split in three:
//! * **Near the launch**, g(τ) = τ(w − τ/2 − R(τ)/τ) with w = v − f'(φ) and
//!   |R(τ)| ≤ |f''|ₘₐₓ τ²/2 (f' is Lipschitz with constant |f''|ₘₐₓ), so g > 0 for
//!   0 < τ ≤ w/(1 + |f''|ₘₐₓ), half the bound where the estimate reaches zero.
//! * **Near the landing**, on [T̲ − δ, T̄], g' = v − τ − f'(φ + τ) < 0 is shown by
//!   interval evaluation: g falls strictly there, so its one root in T (the landing)
//!   is its only one, and g > 0 before it. This is the one-sided enclosure.
//! * **Between**, g > 0 by interval evaluation (the centred form g(m) + g'(τ)(τ − m),
//!   intersected with the natural one) on sub-intervals bisected until each is shown
//!   positive, within a budget.
//!
//! Everything is evaluated over the whole boxes of φ and v, so the statement holds for
//! every launch in them, the exact cycle's among them.

use super::table::Enclosed;
use crate::real::Interval;

/// Sub-intervals of a flight evaluated before giving up.
const MAX_EVALUATIONS: usize = 200_000;
/// Parts the stretch before the landing is split into to show g' < 0.
const SLOPE_PARTS: usize = 16;

/// What was shown of one flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlightProof {
    /// The relative velocity at the landing, |u| = −g'(τ) over the landing box.
    pub impact_speed: Interval,
    /// The relative launch velocity w = v − f'(φ).
    pub launch_speed: Interval,
    /// Sub-intervals evaluated.
    pub evaluations: usize,
}

/// Why a flight's landing is not shown to be its first contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FlightFailure {
    /// The relative launch velocity is not shown positive.
    NotLaunched {
        /// Its enclosure's upper end.
        w: f64,
    },
    /// The landing's relative velocity is not shown negative: the ball lands at about
    /// zero relative velocity (grazing).
    GrazingLanding {
        /// The enclosure of |u| at the landing reaches down to about this.
        speed: f64,
    },
    /// Before the landing the flight comes so close to the table that positivity of the
    /// gap could not be shown (grazing inside the flight).
    Close {
        /// Flight time where it happens.
        tau: f64,
        /// The gap there is below this.
        height: f64,
    },
    /// The flight time to the landing is not shown positive.
    NoFlight,
    /// The gap is not positive somewhere before the landing: the ball meets the table
    /// earlier.
    EarlierContact {
        /// Flight time of that point.
        tau: f64,
    },
}

/// Prove that the flight from the launch (φ, v) first meets the table at its landing,
/// whose flight time lies in `landing`.
pub fn first_landing(
    sys: &Enclosed,
    phase: Interval,
    v: Interval,
    landing: Interval,
) -> Result<FlightProof, FlightFailure> {
    if !landing.positive() {
        return Err(FlightFailure::NoFlight);
    }
    let [f0, d0] = sys.hull(phase);
    let w = v - d0;
    if !w.positive() {
        return Err(FlightFailure::NotLaunched { w: w.hi() });
    }
    let one = Interval::point(1.0);
    let launch_end = (Interval::point(w.lo()) / (one + Interval::point(sys.accel_bound()))).lo();
    let slope = |t: Interval| v - t - sys.hull(phase + t)[1];

    // Near the landing: the widest stretch [T̲ − δ, T̄] on which g' < 0.
    let mut delta = 0.25 * landing.lo();
    let mut evaluations = 0;
    let start = loop {
        let from = (landing.lo() - delta).max(0.0);
        let parts = split(
            Interval::new(from, landing.hi()).unwrap_or(landing),
            SLOPE_PARTS,
        );
        evaluations += parts.len();
        if parts.iter().all(|p| slope(*p).negative()) {
            break from;
        }
        delta *= 0.25;
        if delta < 1e-15 * (1.0 + landing.hi()) {
            let u = slope(landing);
            return Err(FlightFailure::GrazingLanding {
                speed: (-u).lo().max(0.0),
            });
        }
    };
    let impact_speed = -slope(landing);

    // Between: g > 0 on [launch_end, start].
    let gap = |t: Interval| {
        let natural = (f0 - sys.hull(phase + t)[0]) + t * (v - t * Interval::point(0.5));
        let m = Interval::point(t.mid());
        let at_m = (f0 - sys.hull(phase + m)[0]) + m * (v - m * Interval::point(0.5));
        let centred = at_m + slope(t) * (t - m);
        natural.intersect(&centred).unwrap_or(natural)
    };
    let mut stack = Vec::new();
    if launch_end < start {
        stack.push((launch_end, start));
    }
    while let Some((a, b)) = stack.pop() {
        evaluations += 1;
        let t = Interval::new(a, b).expect("ordered ends");
        let g = gap(t);
        if g.positive() {
            continue;
        }
        let m = 0.5 * (a + b);
        let at_m = gap(Interval::point(m));
        if at_m.hi() <= 0.0 {
            return Err(FlightFailure::EarlierContact { tau: m });
        }
        if b - a < 1e-13 * (1.0 + b) || evaluations > MAX_EVALUATIONS {
            return Err(FlightFailure::Close {
                tau: m,
                height: at_m.hi(),
            });
        }
        stack.push((m, b));
        stack.push((a, m));
    }
    Ok(FlightProof {
        impact_speed,
        launch_speed: w,
        evaluations,
    })
}

/// `x` in `n` equal parts (their ends rounded, the parts covering x).
fn split(x: Interval, n: usize) -> Vec<Interval> {
    let (a, b) = (x.lo(), x.hi());
    let ends: Vec<f64> = (0..=n)
        .map(|i| match i {
            0 => a,
            i if i == n => b,
            i => a + (b - a) * i as f64 / n as f64,
        })
        .collect();
    ends.windows(2)
        .filter_map(|e| Interval::new(e[0], e[1].max(e[0])))
        .collect()
}
