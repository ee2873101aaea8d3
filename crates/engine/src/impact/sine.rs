//! The exact solver on the sine table, at the cost of a polynomial one.
//!
//! The sine S(t) = sin 2πt is replaced, piece by piece, by polynomials with rigorous
//! error bounds ([`super::sine_pieces`]: 64 pieces per period; on each, H_k of degree 9
//! with |S − H_k| ≤ e0 ≈ 1.1·10⁻¹⁶, below the rounding of f64 near 1 and better than
//! `sin` of a rounded argument 2πt, and a cubic C_k with |S − C_k| ≤ cubic_err[k] ≈
//! 3·10⁻⁸). The true gap G = ball − α S is therefore known, on piece k, to within
//! α·cubic_err[k] from the cubic and to within α e0 from H_k. A flight is searched as
//! follows; no step can pass over a contact:
//!
//! 1. **Launch.** After an impact (on the table, relative velocity w > 0) Taylor's
//!    theorem at the launch with |S⁗| ≤ (2π)⁴ gives, for every τ > 0, the lower bound
//!    G(τ)/τ ≥ ℓ(τ) = w + g₂ τ + g₃ τ² − K τ³ (g₂, g₃ from H_k at the launch, lowered by
//!    their error bounds; K = α(2π)⁴/24). No contact lies before the first root of ℓ.
//!    Almost always a single evaluation of a monotone lower bound of ℓ shows it has no
//!    root before the ball rises above the band |z| ≤ α. If ℓ has a root within 10⁻³
//!    (chattering), the flight is landed as the root of G(τ)/τ from the sine's Taylor
//!    series at the launch, where that function is proven monotone: full relative
//!    precision however small the gap. A release (w = 0) divides by τ² instead; a
//!    launch above the table needs no bound (G(0) > 0).
//! 2. **Above the band.** Between the ball's crossings of the band's top (plus a margin
//!    far above their rounding) it is above every table height: skipped in one jump,
//!    whatever the flight's length.
//! 3. **Pieces.** Between its crossings of the sine's maximum on a piece (plus the
//!    band's margin) the ball is above the table there: a piece lying between them is
//!    skipped, and on a piece it enters descending the search starts at the crossing.
//!    There the ball's state at the piece's centre is computed in double-double
//!    arithmetic, and the gap is followed by safe steps: at x, with A and B lower bounds
//!    of G(x) and G'(x), G(x + h) ≥ A + B h − M₂ h²/2 (M₂ ≥ −G'' on the piece:
//!    1 − 4π²α min S), so no contact lies before that parabola's first positive root,
//!    the next x. While the gap is large A and B come from the cubic (a few operations
//!    each).
//! 4. **Landing.** Once the next step would be below 3·10⁻⁸ (or the gap is within a few
//!    cubic bounds of zero) the steps continue with H_k. From there one step usually
//!    reaches the contact to within three error bounds (a few ulps), which an upper
//!    bound of G proves without another evaluation; the landing is refined to the
//!    computed gap's zero, and the slopes are carried there by their Taylor expansions.
//!    Near a simple contact the steps converge quadratically; a grazing pass is walked
//!    past, a tangent contact approached until its gap is within its error bound.
//!
//! The work is bounded: at most [`MAX_SINE_STEPS`] pieces and safe steps per flight.

use super::sine_pieces::{center, eval, eval_d, index, locate, L, N, SINE};
use super::{crossing_times, landing_on, FlightError, Landing, Launch, MAX_SINE_STEPS};
use crate::exact_sum::{ball_at, flight_time};
use crate::poly::first_root_low_degree;
use crate::time::normalize;
use std::f64::consts::PI;

/// Unit roundoff 2⁻⁵³.
const U: f64 = f64::EPSILON / 2.0;
/// γ₂₀ = 20u/(1 − 20u), covering Horner's scheme of degree 9 (value or derivative).
const GAMMA: f64 = 20.0 * U * (1.0 + 1e-10);

/// The constants of the search that depend on α, computed once per system.
#[derive(Clone, Debug)]
pub(super) struct Bounds {
    alpha: f64,
    /// α times the rounding bounds of H_k and H_k' by Horner's scheme, plus e0, e1.
    err0: f64,
    err1: f64,
    /// 4π²α.
    a4: f64,
    /// The launch's bounds: K = α(2π)⁴/24 ≥ |G⁗|/24, and g3_max ≥ |G‴(0)|/6.
    k: f64,
    g3_max: f64,
    /// The top of the band |z| ≤ α(1 + e0) that holds the table.
    band: f64,
    /// Per piece, the bounds that depend on α.
    pieces: [PieceBounds; N],
}

/// The bounds of one piece that depend on α.
#[derive(Clone, Copy, Debug, Default)]
struct PieceBounds {
    /// α times the cubic's bounds (value and slope), plus the rounding of forming its
    /// α-scaled coefficients.
    err_c: f64,
    derr_c: f64,
    /// M₂ on the piece: −G'' = 1 − 4π²α S ≤ 1 − 4π²α·bottom[k], often far below the
    /// global 1 + 4π²α (near the sine's top, where the (1, 1) orbits land). Steps within
    /// the piece use it; a step reaching past the piece's end is cut there.
    m2: f64,
}

impl Bounds {
    pub(super) fn new(alpha: f64) -> Bounds {
        let t = &SINE;
        let a4 = alpha * 4.0 * PI * PI;
        Bounds {
            alpha,
            err0: alpha * (t.e0 + (GAMMA + 4.0 * U) * t.mag0),
            err1: alpha * (t.e1 + (GAMMA + 4.0 * U) * t.mag1),
            a4,
            k: alpha * 16.0 * PI.powi(4) / 24.0 * (1.0 + 1e-12),
            g3_max: a4 * 2.0 * PI * (1.0 + 1e-12) / 6.0,
            band: alpha * (1.0 + t.e0),
            pieces: std::array::from_fn(|k| PieceBounds {
                err_c: alpha * (t.cubic_err[k] + 16.0 * U),
                derr_c: alpha * (t.cubic_derr[k] + 16.0 * U),
                m2: ((1.0 - a4 * t.bottom[k]) * (1.0 + 1e-12) + a4 * 1e-15).max(1e-9),
            }),
        }
    }
}

/// The next contact on the sine table (see the module header).
pub(super) fn sine_landing(b: &Bounds, launch: &Launch) -> Result<Landing, FlightError> {
    let alpha = b.alpha;
    let phi = launch.phase;
    let v = launch.v;
    let w = launch.w;
    let h0 = launch.height;
    let (k0, x0) = locate(phi);
    let h = &SINE.h[k0];
    // sin 2πφ, within e0 + rounding.
    let s_phi = eval(h, x0);
    let z0 = alpha * s_phi + h0;
    // The band |z| ≤ α, with a margin far above the rounding of the crossing times.
    let margin = 1e-9 * (1.0 + z0.abs() + v * v);
    let (up, down) = match crossing_times(z0, v, b.band + margin) {
        Some((u, d)) if d > 0.0 => (u.max(0.0), d),
        _ => (f64::INFINITY, f64::INFINITY),
    };

    // Step 1: no contact in (0, start).
    let start = if h0 > 0.0 {
        0.0
    } else {
        // Taylor coefficients of G/τ (or G/τ²) at the launch, lowered by their error:
        // −αS''/2 = α(2π)² S/2 and −αS'''/6 = α(2π)² S'/6, with S within `es` and S'
        // within `ed` of the values from H_k (bounds that also cover the rounding of
        // the coefficients computed here).
        let a4 = b.a4;
        let es = 2.0 * (SINE.e0 + GAMMA * SINE.mag0) + 8.0 * U;
        let ed = 2.0 * (SINE.e1 + GAMMA * SINE.mag1) + 64.0 * U;
        let g2 = -0.5 + 0.5 * a4 * (s_phi - es);
        let k = b.k;
        // Most launches are cleared up to the ball's rise above the band with the bound
        // |g3| ≤ α(2π)³/6, without the table's slope at the launch.
        if w > 0.0 && up < f64::INFINITY && clears(w, g2, b.g3_max, k, up) {
            up
        } else {
            let ds_phi = eval_d(h, x0).1;
            let g3 = a4 * (ds_phi - ed) / 6.0;
            if w > 0.0 {
                let until = if up < f64::INFINITY {
                    up
                } else {
                    bottom_crossing(alpha, z0, v, margin)
                };
                let tau1 = launch_clearance(w, g2, g3, k, until);
                if tau1 < until && tau1 <= MICRO_FLIGHT {
                    if let Some((tau, vrel)) = micro_landing(alpha, w, s_phi, ds_phi, tau1) {
                        let (period, phase) = normalize(launch.period, phi + tau);
                        let (k, x) = locate(phase);
                        let df = alpha * eval_d(&SINE.h[k], x).1;
                        return Ok(Landing {
                            period,
                            phase,
                            flight: tau,
                            vrel: vrel.min(0.0),
                            df,
                        });
                    }
                }
                tau1
            } else {
                // A release (w = 0): G/τ² ≥ max(g₂, 0) + g₃ τ − K τ², the curvature
                // snapped to zero as at the release instant itself; the ball must lift
                // off before the bound's positive root, where the gap must be positive.
                let c = g2.max(0.0);
                let step = if k > 0.0 {
                    (g3 + (g3 * g3 + 4.0 * k * c).sqrt()) / (2.0 * k)
                } else {
                    0.0
                };
                if step.is_nan() || step <= 0.0 || gap_at(b, z0, v, phi, step) <= 0.0 {
                    return Err(FlightError::NoLiftOff);
                }
                step
            }
        }
    };
    search(b, launch, z0, start, up, down, margin)
}

/// Flights from the table up to this long are landed from the gap's Taylor series at
/// the launch ([`micro_landing`]).
const MICRO_FLIGHT: f64 = 1e-3;

/// A short flight from the table (the launch's lower bound has its first root at
/// `tau1` ≤ [`MICRO_FLIGHT`]), landed to full relative precision however small the gap
/// is (chattering): the contact is the root of G(τ)/τ = Q(τ) = w − τ/2 −
/// α Σ_{j≥2} S⁽ʲ⁾(φ) τ^(j−1)/j!, the sine's Taylor series at the launch (S⁽ʲ⁾ from
/// S(φ) = `s` and S'(φ) = `ds`), kept to τ⁶; the rest is below α (2π)⁸ τ⁷/8! ≤ 10⁻¹⁹ α.
/// Where Q' < 0 on [0, 2 τ1] (checked with the coefficients' magnitudes), Q has a
/// single root there, at or after `tau1`, found by Newton's method from `tau1`. Returns
/// the flight time and the relative velocity G'(τ) = Q + τ Q', or None (the general
/// search takes over).
fn micro_landing(alpha: f64, w: f64, s: f64, ds: f64, tau1: f64) -> Option<(f64, f64)> {
    let c2 = 4.0 * PI * PI;
    let c4 = c2 * c2;
    let c6 = c4 * c2;
    let q = [
        w,
        -0.5 + 0.5 * alpha * c2 * s,
        alpha * c2 * ds / 6.0,
        -alpha * c4 * s / 24.0,
        -alpha * c4 * ds / 120.0,
        alpha * c6 * s / 720.0,
        alpha * c6 * ds / 5040.0,
    ];
    // Q'(τ) ≤ q1 + Σ_{i≥2} i |q_i| T^(i−1) < 0 on [0, T].
    let t_max = 2.0 * tau1;
    let mut bound = 0.0;
    for i in (2..q.len()).rev() {
        bound = bound * t_max + i as f64 * q[i].abs();
    }
    if q[1] + bound * t_max >= -1e-12 {
        return None;
    }
    let eval = |t: f64| {
        let (mut p, mut dp) = (q[6], 0.0);
        for &c in q[..6].iter().rev() {
            dp = dp * t + p;
            p = p * t + c;
        }
        (p, dp)
    };
    let mut t = tau1;
    for _ in 0..8 {
        let (p, dp) = eval(t);
        let step = p / dp;
        t -= step;
        if !(t >= tau1 * (1.0 - 1e-9) && t <= t_max) {
            return None;
        }
        if step.abs() <= 2.0 * f64::EPSILON * t {
            let (p, dp) = eval(t);
            return Some((t, p + t * dp));
        }
    }
    None
}

/// When the ball falls below the band (it surely has landed by then).
fn bottom_crossing(alpha: f64, z0: f64, v: f64, margin: f64) -> f64 {
    crossing_times(z0, v, -alpha * (1.0 + SINE.e0) - margin).map_or(0.0, |c| c.1)
}

/// Whether w − |g2| t − g3_max t² − k t³ > 0 (beyond the rounding of these few
/// operations): that cubic is decreasing and, with g3_max ≥ |g3|, below the launch's
/// lower bound ℓ on (0, t], which then has no root there.
#[inline]
fn clears(w: f64, g2: f64, g3_max: f64, k: f64, t: f64) -> bool {
    w - t * (g2.abs() + t * (g3_max + t * k)) > 16.0 * U * w
}

/// The first τ up to which the launch's lower bound ℓ(τ) = w + g2 τ + g3 τ² − k τ³ of
/// G(τ)/τ stays positive, at least up to `t` (the ball's rise above the band, or the end
/// of the flight), where the search resumes.
#[inline]
fn launch_clearance(w: f64, g2: f64, g3: f64, k: f64, t: f64) -> f64 {
    if clears(w, g2, g3.abs(), k, t) {
        return t;
    }
    let c = [w, g2, g3, -k];
    match first_root_low_degree(&c, 4, 0.0, t) {
        Some(tau) if tau > 0.0 => tau,
        _ => t,
    }
}

/// The true gap's lower estimate at flight time τ from the launch (for the lift-off
/// test of a release): z0 + vτ − τ²/2 − α H(φ + τ) − its error bound.
fn gap_at(b: &Bounds, z0: f64, v: f64, phi: f64, tau: f64) -> f64 {
    let (_, phase) = normalize(0, phi + tau);
    let (k, x) = locate(phase);
    let hs = eval(&SINE.h[k], x);
    let ball = z0 + tau * (v - 0.5 * tau);
    ball - b.alpha * hs - b.err0 - 8.0 * U * (z0.abs() + (v * tau).abs() + tau * tau)
}

/// Steps 2 to 4: the pieces from flight time `start` on.
fn search(
    b: &Bounds,
    launch: &Launch,
    z0: f64,
    start: f64,
    up: f64,
    down: f64,
    margin: f64,
) -> Result<Landing, FlightError> {
    let alpha = b.alpha;
    // A guard: the ball surely lands before it falls below the band. Computed once the
    // walk is a period into the flight.
    let mut last = f64::INFINITY;
    let phi = launch.phase;
    let v = launch.v;
    // Step 2 right away when the search starts above the band.
    let mut from = if start >= up && start < down {
        down
    } else {
        start
    };
    // The piece holding φ + from: period m after the launch's, index k.
    let place = |tau: f64| {
        let (m, phase) = normalize(0, phi + tau);
        (m, index(phase))
    };
    let (mut m, mut k) = place(from);
    let mut steps = 0;
    while steps < MAX_SINE_STEPS {
        steps += 1;
        let ck = center(k);
        let tc = m as f64 + ck - phi;
        let (ta, tb) = (tc - L, tc + L);
        if ta > 1.0 && last == f64::INFINITY {
            last = bottom_crossing(alpha, z0, v, margin);
        }
        if ta > last + 1.0 {
            break;
        }
        let lo = ta.max(from);
        if lo >= up && lo < down {
            // Step 2: above the band until `down`.
            from = down;
            (m, k) = place(from);
            continue;
        }
        if tb > from {
            // Step 3: the ball is above the sine's maximum on this piece between its
            // crossings of that level (with the band's margin, far above their
            // rounding): the piece is skipped if it lies between them, and the search
            // starts at the descending crossing if the piece starts between them.
            let level = alpha * (SINE.top[k] + SINE.e0) + margin;
            let disc = v * v + 2.0 * (z0 - level);
            let mut start = lo;
            if disc >= 0.0 {
                let s = disc.sqrt();
                if lo >= v - s {
                    if v + s >= tb {
                        k += 1;
                        if k == N {
                            k = 0;
                            m += 1;
                        }
                        continue;
                    }
                    start = start.max(v + s);
                }
            }
            let (zc, vc) = ball_at(z0, v, flight_time(m, ck, phi));
            // The search starts a little before `start` (the rough centre time is off
            // by its rounding), never after it.
            let sa = ((start - tc) - 4.0 * U * (1.0 + start.abs() + tc.abs())).max(-L);
            match piece_landing(b, k, zc, vc, sa, &mut steps) {
                Ok((x, vrel, df)) => {
                    return Ok(landing_on(launch, m, ck, x, tc + x, vrel, df));
                }
                Err(cleared) => from = from.max(tc + cleared),
            }
        }
        k += 1;
        if k == N {
            k = 0;
            m += 1;
        }
    }
    Err(FlightError::NoLanding)
}

/// Steps 3 and 4 on piece k, the ball at height `zc` with velocity `vc` at its centre,
/// from offset `sa` on (no contact before it): the landing (offset, relative velocity,
/// table velocity), or the offset up to which no contact exists (past the piece's end).
///
/// At x, with A and B lower bounds of G(x) and G'(x), G(x + h) ≥ A + B h − M₂ h²/2 for
/// every h ≥ 0 (M₂ ≥ −G''): no contact lies before that parabola's first positive root,
/// the next x. A and B come first from the piece's cubic C_k (a few operations; their
/// bounds are cubic_err and cubic_derr, about 10⁻⁸ α and 10⁻⁴ α), while the gap is large
/// next to them; then from the degree-9 H_k (bounds e0, e1 and the rounding). The steps
/// converge quadratically to a simple contact; the ball lands at the first x where the
/// lower bound A from H_k is ≤ 0. A grazing pass is walked past, a tangent contact is
/// approached until its gap is within its error bound.
fn piece_landing(
    b: &Bounds,
    k: usize,
    zc: f64,
    vc: f64,
    sa: f64,
    steps: &mut usize,
) -> Result<(f64, f64, f64), f64> {
    let alpha = b.alpha;
    let mut x = sa;
    // Step 3: safe steps on the cubic gap.
    let cb = &SINE.cubic[k];
    let c = [
        zc - alpha * cb[0],
        vc - alpha * cb[1],
        -0.5 - alpha * cb[2],
        -alpha * cb[3],
    ];
    // Bounds of |G − gap with C_k| and of its slope's error, with the rounding of the
    // coefficients above and of Horner's scheme on them.
    let mag = zc.abs() + vc.abs() * L + L * L;
    let err_c = b.pieces[k].err_c + 8.0 * U * mag;
    let derr_c = b.pieces[k].derr_c + 8.0 * U * (vc.abs() + L);
    let m2 = b.pieces[k].m2;
    while *steps < MAX_SINE_STEPS {
        *steps += 1;
        let g = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
        // Within a few times its error bound of zero the cubic can say no more; once the
        // next step is below 3·10⁻⁸ one step on the degree-9 piece finishes (step 4).
        let a = g - err_c;
        let slope = (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1] - derr_c;
        if a <= 2.0 * err_c || a <= 3e-8 * slope.abs() {
            break;
        }
        let next = x + safe_step(a, slope, m2);
        if next >= L {
            return Err(L);
        }
        x = next;
    }
    // Step 4: safe steps on the true gap, from H_k.
    let h = &SINE.h[k];
    while *steps < MAX_SINE_STEPS {
        *steps += 1;
        let (hs, hd) = eval_d(h, x);
        let g = zc + x * (vc - 0.5 * x) - alpha * hs;
        let dg = vc - x - alpha * hd;
        // Bounds of the errors of G(x) and G'(x): the approximation's and the rounding.
        let err = b.err0 + 4.0 * U * (zc.abs() + (x * vc).abs() + x * x);
        let derr = b.err1 + 4.0 * U * (vc.abs() + x.abs());
        // G'' = −1 + 4π²α S, with S = hs within `es`.
        let curv = -1.0 + b.a4 * hs;
        let a = g - err;
        if a <= err {
            // The gap is within three times its error bound of zero: the contact is
            // here, refined to the computed gap's zero (at most 2·err/|G'| later).
            let newton = if g > 0.0 && dg < 0.0 { g / -dg } else { 0.0 };
            let (dg, df) = carry_slopes(b, dg, hd, hs, newton);
            return Ok((x + newton, dg, df));
        }
        let step = safe_step(a, dg - derr, m2);
        let next = x + step;
        if next >= L {
            return Err(L);
        }
        // An upper bound of G at `next`: G(x) + G'(x) h + max(G'') h²/2, with
        // max(G'') ≤ −1 + 4π²α. Within three error bounds of zero (the usual case after
        // one step from a gap near 10⁻⁸), the ball lands there, with the slopes carried
        // over by their Taylor expansions to second order (`carry_slopes`), whose
        // remainders α(2π)⁴ h³/6 are kept below the rounding of G': no second
        // evaluation.
        let upper = g + err + (dg + derr) * step + 0.5 * (b.a4 - 1.0) * step * step;
        if upper <= 3.0 * err && 4.0 * b.k * step * step * step <= 2.0 * U * dg.abs() {
            // The computed gap and slope at `next` (to second and first order: enough for
            // the Newton correction, itself of the order of the error bound).
            let g1 = g + step * (dg + 0.5 * curv * step);
            let dg1 = dg + curv * step;
            let newton = if g1 > 0.0 && dg1 < 0.0 {
                g1 / -dg1
            } else {
                0.0
            };
            let (dg, df) = carry_slopes(b, dg, hd, hs, step + newton);
            return Ok((next + newton, dg, df));
        }
        if next == x {
            // The bound's root is within rounding of x: the contact is here.
            return Ok((x, dg, alpha * hd));
        }
        x = next;
    }
    // The work bound is spent: report no contact on this piece; the caller stops.
    Err(L)
}

/// The gap's slope G' and the table's f' at x + h from their values `dg` and α `hd` at
/// x, with S(x) = `hs`, S'(x) = `hd`, by Taylor's formula to second order:
/// G'' = −1 + 4π²α S, G''' = 4π²α S', f'' = −4π²α S, f''' = −4π²α S'; the remainders are
/// below α(2π)⁴ h³/6 (callers keep h small enough for that to be below the rounding).
#[inline]
fn carry_slopes(b: &Bounds, dg: f64, hd: f64, hs: f64, h: f64) -> (f64, f64) {
    let (curv, jerk) = (b.a4 * hs, b.a4 * hd);
    (
        dg + h * (curv - 1.0 + 0.5 * jerk * h),
        b.alpha * hd - h * (curv + 0.5 * jerk * h),
    )
}

/// The first positive root of a + slope·h − m2 h²/2 (a > 0), in the form free of
/// cancellation, shortened by more than the rounding of its computation.
#[inline]
fn safe_step(a: f64, slope: f64, m2: f64) -> f64 {
    let root = (slope * slope + 2.0 * m2 * a).sqrt();
    let step = if slope < 0.0 {
        2.0 * a / (root - slope)
    } else {
        (slope + root) / m2
    };
    step * (1.0 - 16.0 * U)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sin 2πt in plain f64 with the argument reduced exactly (t ∈ [0, 1)).
    fn sin2pi(t: f64) -> f64 {
        (2.0 * PI * t).sin()
    }

    /// The first contact by brute force: the gap (with libm's sine) sampled every 2·10⁻⁵
    /// and bisected where it turns negative.
    fn brute_force(alpha: f64, phi: f64, w: f64, horizon: f64) -> Option<f64> {
        let v = alpha * 2.0 * PI * (2.0 * PI * phi).cos() + w;
        let z0 = alpha * sin2pi(phi);
        let gap =
            |tau: f64| z0 + tau * (v - 0.5 * tau) - alpha * sin2pi((phi + tau).rem_euclid(1.0));
        let n = (horizon / 2e-5) as usize;
        let mut prev = 2e-5;
        for i in 2..n {
            let tau = i as f64 * 2e-5;
            if gap(tau) < 0.0 {
                let (mut lo, mut hi) = (prev, tau);
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if gap(mid) >= 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return Some(lo);
            }
            prev = tau;
        }
        None
    }

    #[test]
    fn landings_agree_with_brute_force_sampling() {
        let mut rng = crate::test_rng::Xorshift::new(0x1234_5678_9abc_def1);
        let mut compared = 0;
        for _ in 0..600 {
            let alpha = 0.01 + 0.3 * rng.next();
            let phi = rng.next();
            let w = 0.01 + 1.5 * rng.next();
            let v = alpha * 2.0 * PI * (2.0 * PI * phi).cos() + w;
            let launch = Launch {
                period: 3,
                phase: phi,
                height: 0.0,
                v,
                w,
            };
            let got = sine_landing(&Bounds::new(alpha), &launch)
                .unwrap_or_else(|e| panic!("{alpha} {launch:?}: {e:?}"));
            let reference = brute_force(alpha, phi, w, got.flight + 0.01);
            // Sampling can miss a dip shallower than about α (2π)² 10⁻¹⁰: then
            // the solver's contact is the earlier one.
            match reference {
                Some(t) if (t - got.flight).abs() > 1e-9 => {
                    assert!(got.flight < t, "{launch:?}: {got:?} vs {t}");
                }
                Some(_) => compared += 1,
                None => panic!("{launch:?}: no contact by sampling, solver {got:?}"),
            }
        }
        assert!(compared > 580, "{compared}");
    }
}
