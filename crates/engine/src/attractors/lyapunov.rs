//! Lyapunov exponents of an orbit of the impact map, along the [tangent map](crate::tangent).
//!
//! Two methods, each where it is exact or the only one available:
//! * **Cycles** ([`cycle_spectrum`]): on a settled n-event cycle the exponents are
//!   ln|μ| / n for the eigenvalues μ of the cycle's Jacobian (the product of its n
//!   one-event Jacobians; its determinant as the product of the one-event determinants
//!   r(b − a), free of cancellation). Per table period they are ln|μ| / k.
//! * **QR** ([`Qr`]): along any other orbit, the Gram–Schmidt (QR) method: an
//!   orthonormal pair of tangent vectors is pushed through each Jacobian and
//!   re-orthonormalised; the exponents are the mean logarithmic stretches. It runs in
//!   the coordinates (|u| δt, δv) of [`Tangent::scaled`], where every one-event
//!   determinant is exactly r²: the change of coordinates is bounded along an orbit
//!   that does not graze, so the exponents are those of (δt, δv), and the sum of the two
//!   is 2 ln r per impact to round-off instead of up to a boundary term
//!   ln(|u₀|/|u_N|)/N. The convergence estimate is the standard error of the exponents
//!   over [`BLOCKS`] consecutive blocks of the measured stretch.
//!
//! A stick makes the Jacobian zero: the orbit's exponents are −∞ (superstable), reported
//! as [`Spectrum::Sticking`], never as a NaN. A landing with zero relative velocity
//! makes it unbounded: [`Spectrum::Grazing`].

use crate::linalg::{mat_mul, moduli_tr_det, Complex};
use crate::map::{Event, EventKind, ImpactMap, State};
use crate::tangent::{tangent, Tangent};

/// Blocks of the measured stretch over which the convergence estimate is taken.
pub const BLOCKS: usize = 16;

/// The exponents of an orbit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spectrum {
    /// Both exponents, finite.
    Finite(Exponents),
    /// The orbit sticks to the table in the measured stretch: both exponents −∞.
    Sticking,
    /// A landing in the measured stretch grazed the table (zero relative velocity): the
    /// Jacobian is unbounded there.
    Grazing,
}

impl Spectrum {
    /// The largest exponent per impact (−∞ for a sticking orbit, None for grazing).
    pub fn largest(&self) -> Option<f64> {
        match self {
            Spectrum::Finite(e) => Some(e.per_impact[0]),
            Spectrum::Sticking => Some(f64::NEG_INFINITY),
            Spectrum::Grazing => None,
        }
    }
}

/// How the exponents were obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Eigenvalues of a settled cycle's Jacobian: exact up to the cycle's tolerance.
    Cycle,
    /// QR along the orbit.
    Qr,
}

impl Method {
    /// Lower-case name used in outputs.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Cycle => "cycle",
            Method::Qr => "qr",
        }
    }
}

/// Both exponents, largest first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponents {
    /// Per impact.
    pub per_impact: [f64; 2],
    /// Per table period (per impact × impacts / periods).
    pub per_period: [f64; 2],
    /// Standard error of `per_impact` over [`BLOCKS`] blocks (0 for a cycle).
    pub stderr: [f64; 2],
    /// Impacts measured (a cycle: its events).
    pub impacts: u64,
    /// Table periods they took.
    pub periods: f64,
    /// How the exponents were obtained.
    pub method: Method,
}

/// The Gram–Schmidt state: two orthonormal tangent vectors and the accumulated logs.
#[derive(Clone, Debug)]
pub struct Qr {
    /// Columns q₁, q₂.
    q: [[f64; 2]; 2],
    sums: [f64; 2],
    impacts: u64,
    /// The current block's sums, and the finished blocks' means.
    block: [f64; 2],
    block_len: u64,
    in_block: u64,
    blocks: Vec<[f64; 2]>,
}

impl Qr {
    /// A fresh measurement whose blocks are `block_len` impacts long.
    pub fn new(block_len: u64) -> Qr {
        Qr {
            q: [[1.0, 0.0], [0.0, 1.0]],
            sums: [0.0; 2],
            impacts: 0,
            block: [0.0; 2],
            block_len: block_len.max(1),
            in_block: 0,
            blocks: Vec::new(),
        }
    }

    /// Push the tangent vectors through `j` (in the scaled coordinates) and count the
    /// stretches.
    pub fn push(&mut self, j: [[f64; 2]; 2]) {
        let l = self.rotate(j);
        for (i, x) in l.into_iter().enumerate() {
            self.sums[i] += x;
            self.block[i] += x;
        }
        self.impacts += 1;
        self.in_block += 1;
        if self.in_block == self.block_len {
            let n = self.in_block as f64;
            self.blocks.push([self.block[0] / n, self.block[1] / n]);
            self.block = [0.0; 2];
            self.in_block = 0;
        }
    }

    /// Push the tangent vectors through `j` without counting (aligning them with the
    /// orbit's directions before a measurement).
    pub fn align(&mut self, j: [[f64; 2]; 2]) {
        self.rotate(j);
    }

    /// Apply `j`, re-orthonormalise, and return ln r₁₁, ln r₂₂.
    fn rotate(&mut self, j: [[f64; 2]; 2]) -> [f64; 2] {
        let apply = |v: [f64; 2]| {
            [
                j[0][0] * v[0] + j[0][1] * v[1],
                j[1][0] * v[0] + j[1][1] * v[1],
            ]
        };
        let a = apply([self.q[0][0], self.q[1][0]]);
        let b = apply([self.q[0][1], self.q[1][1]]);
        let r11 = a[0].hypot(a[1]);
        let q1 = [a[0] / r11, a[1] / r11];
        let proj = q1[0] * b[0] + q1[1] * b[1];
        let c = [b[0] - proj * q1[0], b[1] - proj * q1[1]];
        let r22 = c[0].hypot(c[1]);
        let q2 = [c[0] / r22, c[1] / r22];
        self.q = [[q1[0], q2[0]], [q1[1], q2[1]]];
        [r11.ln(), r22.ln()]
    }

    /// Impacts pushed so far.
    pub fn impacts(&self) -> u64 {
        self.impacts
    }

    /// The exponents per impact so far, and their standard error over the finished
    /// blocks (infinite with fewer than two).
    pub fn estimate(&self) -> ([f64; 2], [f64; 2]) {
        let n = self.impacts.max(1) as f64;
        let mean = [self.sums[0] / n, self.sums[1] / n];
        let m = self.blocks.len();
        if m < 2 {
            return (mean, [f64::INFINITY; 2]);
        }
        let mut err = [0.0; 2];
        for (i, e) in err.iter_mut().enumerate() {
            let mu = self.blocks.iter().map(|b| b[i]).sum::<f64>() / m as f64;
            let var = self.blocks.iter().map(|b| (b[i] - mu).powi(2)).sum::<f64>() / (m - 1) as f64;
            *e = (var / m as f64).sqrt();
        }
        (mean, err)
    }
}

/// What stopped a measurement early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The cancellation test said stop.
    Cancelled,
    /// The map halted (resting or no landing).
    Halted,
}

/// Measure the exponents by QR over `impacts` events from `state`, after `warmup` events
/// that only align the tangent vectors (and are not counted). `cancelled` is asked every
/// [`crate::jobs::CANCEL_EVERY`] events with the number done since the last time.
/// `visit` sees every measured event (e.g. to collect the cells the orbit visits).
pub fn qr_spectrum(
    map: &mut ImpactMap,
    warmup: u64,
    impacts: u64,
    cancelled: &mut dyn FnMut(u64) -> bool,
    visit: &mut dyn FnMut(&Event),
) -> Result<Spectrum, Stop> {
    let sys = map.system().clone();
    let impacts = impacts.max(1);
    let mut qr = Qr::new((impacts / BLOCKS as u64).max(1));
    let mut since = 0u64;
    let mut first: Option<State> = None;
    let mut sticking = false;
    let mut grazing = false;
    let total = warmup + impacts;
    for n in 0..total {
        since += 1;
        if since == crate::jobs::CANCEL_EVERY {
            since = 0;
            if cancelled(crate::jobs::CANCEL_EVERY) {
                return Err(Stop::Cancelled);
            }
        }
        let before = *map.state();
        if n == warmup {
            first = Some(before);
        }
        let e = map.step().map_err(|_| {
            cancelled(since);
            Stop::Halted
        })?;
        let t = tangent(&sys, &before, &e);
        let measuring = n >= warmup;
        if measuring {
            visit(&e);
        }
        match t {
            Tangent::Collapse => {
                if measuring {
                    sticking = true;
                }
            }
            Tangent::Grazing => {
                if measuring {
                    grazing = true;
                }
            }
            Tangent::Flight { .. } => {
                // |u| of the landing that produced `before`: w = r|u| after an impact
                // (for a launch that did not follow an impact, any positive scale).
                let u_before = if before.w > 0.0 {
                    before.w / sys.r()
                } else {
                    1.0
                };
                if let Some(j) = t.scaled(u_before) {
                    if measuring {
                        qr.push(j);
                    } else {
                        qr.align(j);
                    }
                }
            }
        }
    }
    cancelled(since);
    if sticking {
        return Ok(Spectrum::Sticking);
    }
    if grazing || qr.impacts() == 0 {
        return Ok(Spectrum::Grazing);
    }
    let (mean, err) = qr.estimate();
    let start = first.expect("the measured stretch has a first state");
    let end = map.state();
    let periods = (end.period - start.period) as f64 + (end.phase - start.phase);
    let per = qr.impacts() as f64 / periods;
    Ok(Spectrum::Finite(Exponents {
        per_impact: mean,
        per_period: [mean[0] * per, mean[1] * per],
        stderr: err,
        impacts: qr.impacts(),
        periods,
        method: Method::Qr,
    }))
}

/// One event of a cycle, as stepped from a state on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleEvent {
    /// Impact, stick or release.
    pub kind: EventKind,
    /// Phase t̂ of the event, in [0, 1).
    pub phase: f64,
    /// Ball velocity right after it.
    pub v: f64,
}

/// Step `events` events from the map's state (on a settled cycle of `periods` table
/// periods), returning the cycle's events and its exponents from the eigenvalues of the
/// cycle's Jacobian.
pub fn cycle_spectrum(
    map: &mut ImpactMap,
    events: usize,
    periods: i64,
) -> Result<(Vec<CycleEvent>, Spectrum), Stop> {
    let sys = map.system().clone();
    let mut m = [[1.0, 0.0], [0.0, 1.0]];
    let mut det = 1.0f64;
    let mut out = Vec::with_capacity(events);
    let mut spectrum = None;
    for _ in 0..events.max(1) {
        let before = *map.state();
        let e = map.step().map_err(|_| Stop::Halted)?;
        out.push(CycleEvent {
            kind: e.kind,
            phase: e.phase,
            v: e.v,
        });
        match tangent(&sys, &before, &e) {
            Tangent::Collapse => spectrum = Some(Spectrum::Sticking),
            Tangent::Grazing => {
                spectrum.get_or_insert(Spectrum::Grazing);
            }
            Tangent::Flight { jacobian: j, .. } => {
                m = mat_mul(j, m);
                det *= sys.r() * (j[0][1] - j[0][0]);
            }
        }
    }
    if let Some(s) = spectrum {
        return Ok((out, s));
    }
    let mu = moduli_tr_det(m[0][0] + m[1][1], det);
    let impacts = out.len() as u64;
    let n = impacts as f64;
    let k = periods.max(1) as f64;
    let l = [mu[0].ln(), mu[1].ln()];
    Ok((
        out,
        Spectrum::Finite(Exponents {
            per_impact: [l[0] / n, l[1] / n],
            per_period: [l[0] / k, l[1] / k],
            stderr: [0.0; 2],
            impacts,
            periods: k,
            method: Method::Cycle,
        }),
    ))
}

/// The moduli of two eigenvalues as exponents of one event: ln|μ|.
pub fn log_moduli(mu: &[Complex; 2]) -> [f64; 2] {
    let a = mu[0].abs().ln();
    let b = mu[1].abs().ln();
    if a >= b {
        [a, b]
    } else {
        [b, a]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::Solver;
    use crate::orbits::fixed::fixed_points;
    use crate::system::System;
    use crate::table::Table;

    fn never(_: u64) -> bool {
        false
    }

    /// QR and the cycle's eigenvalues are two methods for the same numbers: on a stable
    /// (1, 1) orbit with real multipliers QR converges to them quickly.
    #[test]
    fn qr_agrees_with_the_cycles_eigenvalues() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let fp = fixed_points(&sys, 1)
            .unwrap()
            .into_iter()
            .find(|p| p.admissible && p.ddf < 0.0)
            .unwrap();
        let st = State::launch(&sys, 0, fp.phase, fp.v, 0.0).unwrap();
        let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
        let (_, cycle) = cycle_spectrum(&mut map.clone(), 1, 1).unwrap();
        let Spectrum::Finite(c) = cycle else {
            panic!("{cycle:?}")
        };
        let Spectrum::Finite(q) =
            qr_spectrum(&mut map, 100, 20_000, &mut never, &mut |_| {}).unwrap()
        else {
            panic!()
        };
        // The (1, 1) multipliers from the paper's A, a third way.
        let want = log_moduli(&fp.eigenvalues);
        for i in 0..2 {
            assert!(
                (c.per_impact[i] - want[i]).abs() < 1e-10,
                "{c:?} vs {want:?}"
            );
            assert!(
                (q.per_impact[i] - want[i]).abs() < 1e-3,
                "{q:?} vs {want:?}"
            );
        }
    }
}
