//! Next-impact solvers: given the ball leaving the table, find the earliest later time
//! at which it meets the table again.
//!
//! * [`Solver::Exact`] (the default) never steps time on a grid. On a piecewise
//!   polynomial table the gap z(t) − f(t) is a polynomial on each piece; its first real
//!   root is isolated exactly ([`Poly::first_root`]). The root at the launch time is
//!   divided out of the polynomial instead of nudging time. A piece is skipped only where
//!   the ball is provably above the table's maximum on it. On the sine table the solver
//!   advances by steps whose length is the first zero of a rigorous lower bound of the
//!   gap (its Taylor polynomial minus a bound on the next derivative), so no contact can
//!   lie inside a step, then the bracketed root is polished to machine precision.
//! * [`Solver::Grid`] is the paper's Section IV method, kept for comparison: a time grid
//!   of 10⁻² fixed in advance, a sign test of the gap at the grid nodes, and bisection to
//!   10⁻⁹ on the first cell where the gap turns negative.
//!
//! Time is passed as (integer period, phase in [0, 1)); flight durations are short f64s.

use super::exact_sum::{ball_at, flight_time};
use super::poly::{Poly, MAX_COEFFS};
use super::system::System;
use super::table::Shape;
use std::f64::consts::PI;

/// Which next-impact solver to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Solver {
    /// Exact root isolation (default).
    #[default]
    Exact,
    /// The paper's fixed 10⁻² time grid with bisection to 10⁻⁹.
    Grid,
}

/// Grid step of the paper's solver.
pub const GRID_STEP: f64 = 1e-2;
/// Cells per period of the paper's grid.
pub const GRID_CELLS: i64 = 100;
/// Bisection tolerance of the paper's solver.
pub const GRID_TOLERANCE: f64 = 1e-9;
/// Pieces the exact solver examines before it reports that the ball does not land.
pub const MAX_FLIGHT_PIECES: usize = 1_000_000;
/// Safe steps the sine solver takes before it reports that the ball does not land.
pub const MAX_SINE_STEPS: usize = 100_000;

/// The ball leaving the table (or starting a free flight).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Launch {
    pub period: i64,
    /// Phase in [0, 1).
    pub phase: f64,
    /// Height of the ball above the table at launch (0 after an impact or a release).
    pub height: f64,
    /// Absolute velocity of the ball.
    pub v: f64,
    /// Velocity relative to the table, v − f'(t); kept separately because it can be
    /// far smaller than v (chattering) and must not be recomputed by cancellation.
    pub w: f64,
}

/// Where and how the ball meets the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Landing {
    pub period: i64,
    pub phase: f64,
    /// Flight duration.
    pub flight: f64,
    /// Relative velocity at contact, u − f'(t) (≤ 0).
    pub vrel: f64,
    /// The table's velocity f'(t) at contact.
    pub df: f64,
}

/// Why no landing was returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlightError {
    /// The ball did not land within the documented work bound.
    NoLanding,
    /// Launched with zero relative velocity, the ball is pressed into the table at once
    /// (it is not actually released).
    NoLiftOff,
}

/// The next contact after `launch`, with the chosen solver.
pub fn next_landing(sys: &System, solver: Solver, launch: &Launch) -> Result<Landing, FlightError> {
    match (solver, sys.table.shape()) {
        (Solver::Grid, _) => grid_landing(sys, launch),
        (Solver::Exact, Shape::Sine) => sine_landing(sys, launch),
        (Solver::Exact, Shape::Piecewise(_)) => poly_landing(sys, launch),
    }
}

/// Normalise (period, phase) so the phase is in [0, 1).
#[inline]
pub fn normalize(period: i64, phase: f64) -> (i64, f64) {
    if (0.0..1.0).contains(&phase) {
        return (period, phase);
    }
    let k = phase.floor();
    let mut p = phase - k;
    let mut n = period + k as i64;
    if p >= 1.0 {
        p -= 1.0;
        n += 1;
    }
    (n, p)
}

/// Flight times at which the ball, z(τ) = z0 + vτ − τ²/2, crosses height `level`:
/// (ascending, descending). None if it stays below `level`.
fn crossing_times(z0: f64, v: f64, level: f64) -> Option<(f64, f64)> {
    let disc = v * v + 2.0 * (z0 - level);
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    Some((v - s, v + s))
}

/// Exact solver on a piecewise polynomial table.
fn poly_landing(sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
    let pieces = sys.table.pieces();
    let alpha = sys.alpha;
    let phi = launch.phase;
    let v = launch.v;
    let mut j = sys.table.piece_index(phi);
    let first = &pieces[j];
    let off = phi - first.start;

    // First piece: the gap in the local variable s = τ, with exactly known low-order
    // coefficients: gap(s) = h + w s − s²/2 − α (Q(s) − Q(0) − Q'(0) s).
    let q = first.f.shift(off);
    let mut c = [0.0; MAX_COEFFS];
    let len = q.coeffs().len().max(3);
    let qc = q.coeffs();
    for k in 3..qc.len() {
        c[k] = -alpha * qc[k];
    }
    c[0] = launch.height;
    c[1] = launch.w;
    c[2] = -0.5 - alpha * q.coeff(2);
    let gap = Poly::from_array(c, len);
    let search = if launch.height > 0.0 {
        gap
    } else {
        lift_off_quotient(&gap, launch.w)?
    };
    if let Some(s) = first_positive_root(&search, first.end - phi) {
        return Ok(landing_on(
            launch,
            0,
            first.start,
            off + s,
            s,
            gap.eval_d(s).1,
            alpha * first.d1.eval(off + s),
        ));
    }

    // Later pieces: gap from absolute heights, skipping where the ball is above the table.
    let z0 = alpha * q.coeff(0) + launch.height;
    let (top_lo, top_hi) = sys.table.range();
    let (up, down) = match crossing_times(z0, v, alpha * top_hi) {
        Some((u, d)) if z0 <= alpha * top_hi => (u.max(0.0), d),
        Some((_, d)) => (0.0, d),
        None => (f64::INFINITY, f64::INFINITY),
    };
    // The ball surely lands before it falls below the table's minimum.
    let last = crossing_times(z0, v, alpha * top_lo).map_or(0.0, |c| c.1);
    let mut m: i64 = 0;
    j += 1;
    for _ in 0..MAX_FLIGHT_PIECES {
        if j == pieces.len() {
            j = 0;
            m += 1;
        }
        let p = &pieces[j];
        let tau_lo = m as f64 + p.start - phi;
        let tau_hi = tau_lo + p.len();
        if tau_lo > last + 1.0 {
            break;
        }
        if tau_lo >= up && j == 0 {
            // Whole periods with the ball above every table height.
            let target = (phi + down).floor() as i64;
            if target > m {
                m = target;
                continue;
            }
        }
        let zb_rough = z0 + tau_lo * (v - 0.5 * tau_lo);
        let ze = z0 + tau_hi * (v - 0.5 * tau_hi);
        // Skip with a margin far above the rounding of the rough heights.
        let margin = 1e-9 * (1.0 + z0.abs() + (v * tau_hi).abs() + tau_hi * tau_hi);
        if zb_rough.min(ze) > alpha * p.max + margin {
            j += 1;
            continue;
        }
        let (zb, vb) = ball_at(z0, v, flight_time(m, p.start, phi));
        let fp = &p.f;
        let mut c = [0.0; MAX_COEFFS];
        let len = fp.coeffs().len().max(3);
        let fc = fp.coeffs();
        for k in 3..fc.len() {
            c[k] = -alpha * fc[k];
        }
        c[0] = zb - alpha * fp.coeff(0);
        c[1] = vb - alpha * fp.coeff(1);
        c[2] = -0.5 - alpha * fp.coeff(2);
        let g = Poly::from_array(c, len);
        // At s = 0 the value is c0 itself, its rounding bound that of one term.
        let g0 = g.coeff(0);
        let err = (4 * g.coeffs().len()) as f64 * f64::EPSILON * g0.abs();
        let root = if g0 <= err {
            Some(0.0)
        } else {
            g.first_root(0.0, p.len())
        };
        if let Some(s) = root {
            return Ok(landing_on(
                launch,
                m,
                p.start,
                s,
                tau_lo + s,
                g.eval_d(s).1,
                alpha * p.d1.eval(s),
            ));
        }
        j += 1;
    }
    Err(FlightError::NoLanding)
}

/// Divide the launch root out of the gap polynomial (whose constant term is zero).
/// With w = 0 (a release) the next coefficients may vanish too: they are divided out as
/// long as they are zero within rounding; the first one left must be positive.
fn lift_off_quotient(gap: &Poly, w: f64) -> Result<Poly, FlightError> {
    let mut q = gap.div_x();
    if w > 0.0 {
        return Ok(q);
    }
    let scale: f64 = gap.coeffs().iter().map(|c| c.abs()).sum::<f64>().max(1.0);
    let tiny = 64.0 * f64::EPSILON * scale;
    loop {
        let c0 = q.coeff(0);
        if c0 > tiny {
            return Ok(q);
        }
        if c0 < -tiny || q.degree() == 0 {
            return Err(FlightError::NoLiftOff);
        }
        q = q.div_x();
    }
}

/// First root of `q` in (0, len]; q(0) > 0 is known.
fn first_positive_root(q: &Poly, len: f64) -> Option<f64> {
    q.first_root(0.0, len)
        .filter(|&s| s > 0.0 || q.eval(0.0) <= 0.0)
}

fn landing_on(
    launch: &Launch,
    m: i64,
    start: f64,
    s_in_piece: f64,
    tau: f64,
    vrel: f64,
    df: f64,
) -> Landing {
    let (period, phase) = normalize(launch.period + m, start + s_in_piece);
    Landing {
        period,
        phase,
        flight: tau,
        vrel: vrel.min(0.0),
        df,
    }
}

/// sin(2π(φ+τ)) − sin 2πφ − 2π cos(2πφ) τ, accurate also for tiny τ.
fn sine_excess(phi: f64, tau: f64) -> f64 {
    let w = 2.0 * PI;
    let x = w * tau;
    let th = w * phi;
    if x.abs() < 0.01 {
        let (s, c) = th.sin_cos();
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
        let (_, mid) = normalize(0, phi + 0.5 * tau);
        2.0 * (w * mid).cos() * sin_pi(tau) - x * th.cos()
    }
}

/// sin(πτ) with the argument reduced exactly: sin(π(n + f)) = (−1)ⁿ sin(πf).
fn sin_pi(tau: f64) -> f64 {
    let n = tau.floor();
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
fn sine_landing(sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
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
    let gap = |t: f64| h0 + w * t - 0.5 * t * t - a * sine_excess(phi, t);
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
    for _ in 0..MAX_SINE_STEPS {
        let g0 = gap(tau);
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
        let step = bound.first_root(0.0, 1.0).unwrap_or(1.0);
        if step <= 0.0 {
            return Ok(sine_landing_at(sys, launch, tau, dgap(tau)));
        }
        let next = tau + step;
        let gn = gap(next);
        if gn < 0.0 {
            // The contact lies in (tau, next): bracketed, refine by bisection + secant.
            let root = refine_bracket(&gap, tau, next, g0, gn);
            return Ok(sine_landing_at(sys, launch, root, dgap(root)));
        }
        tau = next;
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

/// The paper's solver: sign test at the nodes of a fixed 10⁻² grid, bisection to 10⁻⁹.
///
/// Nodes are the absolute times n + j/100. As in the paper, at most one impact is
/// resolved per grid cell: the search starts at the first node after the launch's cell.
/// If the ball is already below the table there, the impact is placed at that node;
/// otherwise the first later node where the gap is negative closes a bracket with the
/// node before it, and bisection narrows it to 10⁻⁹ (the midpoint is returned). Like
/// the paper's, this solver misses a contact whose gap dips below zero and back between
/// two nodes, and resolves chattering only at one impact per cell.
fn grid_landing(sys: &System, launch: &Launch) -> Result<Landing, FlightError> {
    let phi = launch.phase;
    let z0 = sys.f(phi) + launch.height;
    let v = launch.v;
    let gap = |tau: f64| {
        let (_, ph) = normalize(0, phi + tau);
        z0 + tau * (v - 0.5 * tau) - sys.f(ph)
    };
    let (lo_f, _) = sys.table.range();
    let last = crossing_times(z0, v, sys.alpha * lo_f).map_or(1.0, |c| c.1) + 1.0;
    let max_nodes = ((last / GRID_STEP).ceil() as i64 + 2).min(1 << 40);
    let cell = ((phi * GRID_CELLS as f64).floor() as i64).min(GRID_CELLS - 1);
    let node_tau = |i: i64| {
        let node = cell + i;
        (node / GRID_CELLS) as f64 + (node % GRID_CELLS) as f64 * GRID_STEP - phi
    };
    let land = |t: f64| {
        let (period, phase) = normalize(launch.period, phi + t);
        let vrel = (v - t) - sys.df(phase);
        Ok(Landing {
            period,
            phase,
            flight: t,
            vrel: vrel.min(0.0),
            df: sys.df(phase),
        })
    };
    let first = node_tau(1);
    if gap(first) < 0.0 {
        return land(first);
    }
    let mut prev_tau = first;
    for i in 2..=max_nodes {
        let tau = node_tau(i);
        if gap(tau) < 0.0 {
            let (mut lo, mut hi) = (prev_tau, tau);
            while hi - lo > GRID_TOLERANCE {
                let mid = 0.5 * (lo + hi);
                if gap(mid) >= 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return land(0.5 * (lo + hi));
        }
        prev_tau = tau;
    }
    Err(FlightError::NoLanding)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::table::Table;

    #[test]
    fn sine_excess_matches_direct_formula() {
        for &(phi, tau) in &[(0.1, 0.03), (0.77, 0.001), (0.3, 0.2), (0.95, 0.6)] {
            let w = 2.0 * PI;
            let direct = (w * (phi + tau)).sin() - (w * phi).sin() - w * (w * phi).cos() * tau;
            assert!((sine_excess(phi, tau) - direct).abs() < 1e-14);
        }
    }

    #[test]
    fn quad_free_flight_closed_form() {
        // fd:0 with tiny α: the ball launched at phase 0 with v = 1 lands after ≈ 2 periods.
        // The gap at landing must vanish and no earlier contact may exist.
        let sys = System::new(Table::fd(0.0).unwrap(), 0.01, 0.5).unwrap();
        let w = 1.0 - sys.df(0.0);
        let l = Launch {
            period: 0,
            phase: 0.0,
            height: 0.0,
            v: 1.0,
            w,
        };
        for solver in [Solver::Exact, Solver::Grid] {
            let land = next_landing(&sys, solver, &l).unwrap();
            let t = land.period as f64 + land.phase;
            let z = t - 0.5 * t * t;
            assert!((z - sys.f(land.phase)).abs() < 1e-8, "{solver:?} {land:?}");
            assert!((t - 2.0).abs() < 0.02);
        }
    }
}
