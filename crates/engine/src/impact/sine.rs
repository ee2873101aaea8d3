//! The exact solver on the sine table: steps whose length is the first zero of a
//! rigorous lower bound of the gap (its Taylor polynomial minus a bound on the next
//! derivative), so no contact can lie inside a step; the bracketed root is then polished
//! to machine precision. Long arcs above the band |z| ≤ α are skipped by re-anchoring
//! the ball just above it.

use super::{crossing_times, floor, normalize, FlightError, Landing, Launch, MAX_SINE_STEPS};
use crate::exact_sum::{ball_at, flight_time};
use crate::poly::Poly;
use crate::system::System;
use std::f64::consts::PI;

/// sin(2π(φ+τ)) − sin 2πφ − 2π cos(2πφ) τ, accurate also for tiny τ.
fn sine_excess(launch: &LaunchPhase, tau: f64) -> f64 {
    let w = 2.0 * PI;
    let x = w * tau;
    if x.abs() < 0.01 {
        let (s, c) = (launch.sin, launch.cos);
        let derivs = [s, c, -s, -c];
        let mut term = x;
        let mut sum = 0.0;
        for k in 2..40 {
            term *= x / k as f64;
            let add = term * derivs[k % 4];
            sum += add;
            if term.abs() < 1e-18 * sum.abs().max(f64::MIN_POSITIVE) {
                break;
            }
        }
        sum
    } else {
        // sin(θ + x) − sin θ = 2 cos(θ + x/2) sin(x/2), free of cancellation; the phase
        // of θ + x/2 is reduced first so long flights keep full precision.
        let (_, mid) = normalize(0, launch.phi + 0.5 * tau);
        2.0 * (w * mid).cos() * sin_pi(tau) - x * launch.cos
    }
}

/// The launch phase φ with sin 2πφ and cos 2πφ, computed once per flight.
#[derive(Clone, Copy, Debug)]
struct LaunchPhase {
    phi: f64,
    sin: f64,
    cos: f64,
}

impl LaunchPhase {
    fn new(phi: f64) -> LaunchPhase {
        let (sin, cos) = (2.0 * PI * phi).sin_cos();
        LaunchPhase { phi, sin, cos }
    }
}

/// sin(πτ) with the argument reduced exactly: sin(π(n + f)) = (−1)ⁿ sin(πf).
fn sin_pi(tau: f64) -> f64 {
    let n = floor(tau);
    let s = (PI * (tau - n)).sin();
    if (n as i64) % 2 == 0 {
        s
    } else {
        -s
    }
}

/// cos(2π(φ+τ)) − cos 2πφ, accurate for tiny τ.
fn cos_increment(phi: f64, tau: f64) -> f64 {
    let w = 2.0 * PI;
    let (_, mid) = normalize(0, phi + 0.5 * tau);
    -2.0 * (w * mid).sin() * sin_pi(tau)
}

/// Exact (bounded-step) solver on the sine table.
pub(super) fn sine_landing(sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
    sine_landing_from(sys, launch, true)
}

/// The ball re-launched, in flight, just before it descends into the band |z| ≤ α where
/// it can meet the table. The new launch point's time is exact (period, phase) and its
/// height above the table is computed with compensated arithmetic, so the remaining
/// flight is short and no precision is lost to the long arc above the table.
fn reanchor_above_band(sys: &System, launch: &Launch, z0: f64, down: f64) -> Launch {
    // A little before the crossing, the ball is strictly above every table height.
    let t = launch.phase + down * (1.0 - 1e-12) - 1e-12;
    let (period, phase) = normalize(launch.period, t);
    let m = period - launch.period;
    let (z, v) = ball_at(z0, launch.v, flight_time(m, phase, launch.phase));
    let height = (z - sys.f(phase)).max(0.0);
    Launch {
        period,
        phase,
        height,
        v,
        w: v - sys.df(phase),
    }
}

fn sine_landing_from(
    sys: &System,
    launch: &Launch,
    may_skip: bool,
) -> Result<Landing, FlightError> {
    let a = sys.alpha;
    let w2 = 2.0 * PI;
    let phi = launch.phase;
    let h0 = launch.height;
    let w = launch.w;
    let v = launch.v;
    let m3 = a * w2.powi(3);
    let m4 = a * w2.powi(4);
    let launch_phase = LaunchPhase::new(phi);
    let gap = |t: f64| h0 + w * t - 0.5 * t * t - a * sine_excess(&launch_phase, t);
    let dgap = |t: f64| w - t - a * w2 * cos_increment(phi, t);
    let ddgap = |t: f64| {
        let (_, ph) = normalize(0, phi + t);
        -1.0 + a * w2 * w2 * (w2 * ph).sin()
    };
    let tol = |t: f64| 16.0 * f64::EPSILON * (h0 + w.abs() * t + 0.5 * t * t + a * (1.0 + w2 * t));

    let mut tau = 0.0;
    if h0 == 0.0 && w <= 0.0 {
        // Release: g = g' = 0; g'' ≥ 0 (snapped), g''' = −f'''.
        let g2 = ddgap(0.0).max(0.0);
        let g3 = a * w2.powi(3) * (w2 * phi).cos();
        // Positive root of g2/2 + g3 h/6 − M4 h²/24 (the bound divided by h²).
        let (b, c, qa) = (g3 / 6.0, g2 / 2.0, m4 / 24.0);
        let step = (b + (b * b + 4.0 * qa * c).sqrt()) / (2.0 * qa);
        if step > 0.0 && gap(step.min(1.0)) > 0.0 {
            tau = step.min(1.0);
        } else {
            return Err(FlightError::NoLiftOff);
        }
    }
    let z0 = a * (w2 * phi).sin() + h0;
    let down = crossing_times(z0, v, a).map(|c| c.1);
    // The gap at the current step's start (carried over from the previous step's end).
    let mut g0 = gap(tau);
    for _ in 0..MAX_SINE_STEPS {
        if tau > 0.0 && g0 <= tol(tau) {
            return Ok(sine_landing_at(sys, launch, tau, dgap(tau)));
        }
        // Skip the stretch where the ball is above the highest table position.
        if let (true, Some(d)) = (may_skip, down) {
            let zb = z0 + tau * (v - 0.5 * tau);
            if zb > a * (1.0 + 1e-9) + 1e-9 && tau < d && d > 1.0 {
                let anchor = reanchor_above_band(sys, launch, z0, d);
                let rest = sine_landing_from(sys, &anchor, false)?;
                let m = anchor.period - launch.period;
                let (head, _) = flight_time(m, anchor.phase, launch.phase);
                return Ok(Landing {
                    flight: head + rest.flight,
                    ..rest
                });
            }
        }
        let bound = if tau == 0.0 && g0 == 0.0 {
            // Launch from the table: divide out the root at τ = 0 (g'(0) = w > 0).
            Poly::new(&[dgap(tau), 0.5 * ddgap(tau), -m3 / 6.0])
        } else {
            Poly::new(&[g0, dgap(tau), 0.5 * ddgap(tau), -m3 / 6.0])
        };
        let zero = bound.first_root(0.0, 1.0);
        let step = zero.unwrap_or(1.0);
        if step <= 0.0 {
            return Ok(sine_landing_at(sys, launch, tau, dgap(tau)));
        }
        let next = tau + step;
        // Where the lower bound reaches zero, the gap lies between 0 and that bound plus
        // M3·step³/3 (the same remainder bound taken from above). Once that is within
        // the landing tolerance the contact is here, without another evaluation.
        if zero.is_some() && m3 * step * step * step / 3.0 <= tol(next) {
            return Ok(sine_landing_at(sys, launch, next, dgap(next)));
        }
        let gn = gap(next);
        if gn < 0.0 {
            // The contact lies in (tau, next): bracketed, refine by bisection + secant.
            let root = refine_bracket(&gap, tau, next, g0, gn);
            return Ok(sine_landing_at(sys, launch, root, dgap(root)));
        }
        tau = next;
        g0 = gn;
    }
    Err(FlightError::NoLanding)
}

/// Root of `g` in [lo, hi] with g(lo) > 0 > g(hi) (Illinois false position).
fn refine_bracket(
    g: &dyn Fn(f64) -> f64,
    mut lo: f64,
    mut hi: f64,
    mut glo: f64,
    mut ghi: f64,
) -> f64 {
    let mut side = 0;
    for _ in 0..200 {
        let x = (lo * ghi - hi * glo) / (ghi - glo);
        let x = if x > lo && x < hi { x } else { 0.5 * (lo + hi) };
        if x == lo || x == hi {
            break;
        }
        let gx = g(x);
        if gx > 0.0 {
            lo = x;
            glo = gx;
            if side == 1 {
                ghi *= 0.5;
            }
            side = 1;
        } else if gx < 0.0 {
            hi = x;
            ghi = gx;
            if side == -1 {
                glo *= 0.5;
            }
            side = -1;
        } else {
            return x;
        }
        if hi - lo <= 2.0 * f64::EPSILON * hi.abs() {
            break;
        }
    }
    if glo.abs() <= ghi.abs() {
        lo
    } else {
        hi
    }
}

fn sine_landing_at(sys: &System, launch: &Launch, tau: f64, vrel: f64) -> Landing {
    let (period, phase) = normalize(launch.period, launch.phase + tau);
    Landing {
        period,
        phase,
        flight: tau,
        vrel: vrel.min(0.0),
        df: sys.df(phase),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sine_excess_matches_direct_formula() {
        for &(phi, tau) in &[(0.1, 0.03), (0.77, 0.001), (0.3, 0.2), (0.95, 0.6)] {
            let w = 2.0 * PI;
            let direct = (w * (phi + tau)).sin() - (w * phi).sin() - w * (w * phi).cos() * tau;
            assert!((sine_excess(&LaunchPhase::new(phi), tau) - direct).abs() < 1e-14);
        }
    }
}
