//! Whether a cycle found in double precision is an answer or an artefact: the
//! finite-time growth of perturbations along it, and the verdict that follows.
//!
//! A cycle of impacts that an orbit converges to is resolved by construction: errors
//! shrink along it (the detector measured the contraction, or Newton's method on the
//! exact map confirmed it). A *sticking* cycle is different. The state right after a
//! release is exact (the ball leaves the table at the phase where f'' falls below −1,
//! with the table's velocity), but the path from a release to the next stick can stretch
//! the rounding error of that state by many decades: the number of flights before the
//! next stick, and so the cycle's length, is then decided by rounding, and another
//! precision (or the next double of α) gives another cycle.
//!
//! The growth is measured along each stretch from a release to the next stick: a
//! perturbation δt of the release time moves the state by (δt, f''(t̂_R) δt); it is
//! pushed through the Jacobian of every impact ([`crate::tangent::flight`]) up to the
//! last impact before the final chattering sequence (relative impact velocity above
//! [`CHATTER_SPEED`]: the accumulation point of a chattering sequence depends smoothly on
//! the state entering it). The largest stretch over the cycle, 10^G, times the relative
//! error of a double, is the size of the double-precision error where the stick
//! sequence is decided; above [`UNRESOLVED`] the cycle's length is out of reach of
//! double precision.
//!
//! G is measured along the cycle the f64 run found. Where it is unresolved that cycle
//! was chosen by rounding, and the true path from the release can be shorter or
//! longer: the map at any precision (`--digits`) measures the digits it actually loses
//! (on fd:1 at α = 0.59, G = 92.8 and about 50 are lost; on fd:0.1 at α = 0.6,
//! G = 672.5 along a 1,498-period cycle, while the true cycle is 394 periods long and
//! fewer than 280 digits are lost). G stays the verdict's measure: it is what this run
//! can know.

use crate::map::{EventKind, ImpactMap, Mode, State};
use crate::tangent::flight;

/// The relative error of a double (half an ulp of 1).
pub const F64_ERROR: f64 = f64::EPSILON / 2.0;
/// A cycle whose growth times [`F64_ERROR`] exceeds this is not resolved in double
/// precision.
pub const UNRESOLVED: f64 = 1e-3;
/// Impacts slower than this (relative velocity) belong to a chattering sequence.
pub const CHATTER_SPEED: f64 = 1e-3;

/// The finite-time growth along a cycle and the verdict.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// log₁₀ of the largest growth of a perturbation from a release to the next stick
    /// (0 for a cycle without sticks).
    pub growth_decades: f64,
    /// Impacts of that stretch (up to its final chattering sequence).
    pub impacts: usize,
    /// Whether double precision decides the cycle: growth × [`F64_ERROR`] ≤
    /// [`UNRESOLVED`] (always for a cycle without sticks, which contracts).
    pub resolved: bool,
}

impl Precision {
    /// The verdict of a cycle of impacts that an orbit converges to.
    pub const CONTRACTING: Precision = Precision {
        growth_decades: 0.0,
        impacts: 0,
        resolved: true,
    };

    /// The verdict in words, for text output.
    pub fn describe(&self) -> String {
        if self.impacts == 0 {
            "resolved (the orbit converges to it)".into()
        } else if self.resolved {
            format!(
                "resolved in double precision (growth 10^{:.1} over {} impacts from a release to the next stick)",
                self.growth_decades, self.impacts
            )
        } else {
            format!(
                "cycle length beyond double precision: along the cycle this run found, which rounding chose, an error at the release grows by 10^{:.1} over {} impacts to the next stick",
                self.growth_decades, self.impacts
            )
        }
    }
}

/// The precision of the sticking cycle of `events` events that `map`'s orbit is on
/// (its state anywhere on the cycle; right after a release saves stepping to one): up
/// to one cycle is stepped to reach a release, then one cycle measured. None if the
/// orbit halts or has no release within two cycles (not a sticking cycle).
pub fn sticking_cycle(mut map: ImpactMap, events: usize) -> Option<Precision> {
    let sys = map.system().clone();
    // To the first release, unless the state is one (a ball leaving the table with
    // its velocity).
    let released = |s: &State| s.w == 0.0 && s.height == 0.0 && s.mode == Mode::Flying;
    let mut steps = 0;
    while !released(map.state()) {
        let e = map.step().ok()?;
        steps += 1;
        if e.kind == EventKind::Release {
            break;
        }
        if steps > events {
            return None;
        }
    }
    let mut worst = (0.0f64, 0usize);
    // The stretch from the latest release.
    let mut stretch = Some(Stretch::at_release(&sys, map.state()));
    for _ in 0..events {
        let before: State = *map.state();
        let e = map.step().ok()?;
        match e.kind {
            EventKind::Release => stretch = Some(Stretch::at_release(&sys, map.state())),
            EventKind::Stick => {
                if let Some(s) = stretch.take() {
                    if s.largest > worst.0 || worst.1 == 0 {
                        worst = (s.largest, s.impacts);
                    }
                }
            }
            EventKind::Impact => {
                let Some(s) = stretch.as_mut() else { continue };
                if e.vrel.abs() <= CHATTER_SPEED {
                    continue;
                }
                if let Some(fl) = flight(&sys, &before, &e) {
                    s.push(fl.jacobian());
                }
            }
        }
    }
    let (growth_decades, impacts) = worst;
    Some(Precision {
        growth_decades,
        impacts,
        resolved: growth_decades + F64_ERROR.log10() <= UNRESOLVED.log10(),
    })
}

/// A perturbation followed from a release: its direction (unit size; the size is kept
/// apart as a logarithm, so hundreds of decades do not overflow), its log₁₀ size now
/// and at its largest, and the impacts it went through.
struct Stretch {
    d: [f64; 2],
    log: f64,
    largest: f64,
    impacts: usize,
}

impl Stretch {
    /// Right after a release at the state `s`: (δt, f''(t̂) δt).
    fn at_release(sys: &crate::system::System, s: &State) -> Stretch {
        let d = [1.0, sys.ddf(s.phase)];
        let size = d[0].hypot(d[1]);
        Stretch {
            d: [d[0] / size, d[1] / size],
            log: 0.0,
            largest: 0.0,
            impacts: 0,
        }
    }

    /// Through one impact's Jacobian `j`.
    fn push(&mut self, j: [[f64; 2]; 2]) {
        let d = self.d;
        let next = [
            j[0][0] * d[0] + j[0][1] * d[1],
            j[1][0] * d[0] + j[1][1] * d[1],
        ];
        let size = next[0].hypot(next[1]);
        if !(size.is_finite() && size > 0.0) {
            return;
        }
        self.d = [next[0] / size, next[1] / size];
        self.log += size.log10();
        self.largest = self.largest.max(self.log);
        self.impacts += 1;
    }
}
