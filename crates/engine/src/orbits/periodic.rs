//! (n, k) solutions of the exact impact map: n impacts in k table periods.
//!
//! A cycle is given by its launch (t₀, v₀) right after an impact. One *pass* steps the
//! exact map n times from it and returns the residual
//!
//!   F(α, t₀, v₀) = (tₙ − t₀ − k, vₙ − v₀)
//!
//! (times as exact (period, phase) differences) with its Jacobian: ∂F/∂(t₀, v₀) = M − I,
//! M the product of the tangent maps of the n impacts ([`crate::tangent::Flight`]), and
//! ∂F/∂α accumulated from each impact's α column. Newton's method runs on F; a point is
//! accepted only when the map itself, stepped n times from it, returns within
//! [`RETURN_TOLERANCE`] and every event is an impact (a stick inside the cycle makes
//! it a different kind of orbit, [`PassError::Stick`]).
//!
//! The multipliers are the eigenvalues of M, from its trace and the product of the
//! flights' determinants, which is r²ⁿ on a cycle (so no Neimark–Sacker point exists;
//! [`CyclePoint::det_error`] is the check).

use crate::impact::Solver;
use crate::linalg::{eigenvalues_tr_det, mat_mul, solve, Complex};
use crate::map::{EventKind, ImpactMap, State};
use crate::system::System;
use crate::tangent::flight;
use crate::time::wrap_phase;

/// The largest return error |(tₙ − t₀ − k, vₙ − v₀)| of an accepted cycle.
pub const RETURN_TOLERANCE: f64 = 1e-11;
/// Newton's iteration bound (fixed α and each corrector step of a continuation).
pub const MAX_NEWTON: usize = 30;

/// Why a pass or a solve failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PassError {
    /// The launch is not a launch: v₀ < f'(t₀), or outside the engine's ranges.
    BadLaunch,
    /// The map halted (the ball rests for good or did not land).
    Halt,
    /// An event of the n was a stick or a release, at this phase: not an impact cycle.
    Stick {
        /// Its phase.
        phase: f64,
    },
    /// A landing with zero relative velocity: the tangent map is unbounded.
    Grazing {
        /// Its phase.
        phase: f64,
    },
    /// Newton's method did not converge within [`MAX_NEWTON`] iterations.
    NoConvergence,
    /// Converged, but the map stepped n times returns only within this distance.
    NotReturning {
        /// Largest difference of phase or velocity after n steps.
        error: f64,
    },
}

impl PassError {
    /// Name in every output format.
    pub fn as_str(&self) -> &'static str {
        match self {
            PassError::BadLaunch => "bad_launch",
            PassError::Halt => "halt",
            PassError::Stick { .. } => "stick",
            PassError::Grazing { .. } => "grazing",
            PassError::NoConvergence => "no_convergence",
            PassError::NotReturning { .. } => "not_returning",
        }
    }
}

/// n steps of the exact map from a launch, with derivatives.
#[derive(Clone, Debug)]
pub struct Pass {
    /// F = (tₙ − t₀ − k, vₙ − v₀).
    pub residual: [f64; 2],
    /// M: ∂(tₙ, vₙ)/∂(t₀, v₀).
    pub monodromy: [[f64; 2]; 2],
    /// ∂(tₙ, vₙ)/∂α.
    pub alpha_column: [f64; 2],
    /// The product of the n flights' determinants.
    pub det: f64,
    /// Impact phases t̂₁ … t̂ₙ (t̂ₙ is t̂₀ again on a cycle) and launch velocities after them.
    pub phases: Vec<f64>,
    /// Launch velocities after those impacts.
    pub velocities: Vec<f64>,
    /// Times of the impacts from the launch (continuous in the parameters).
    pub times: Vec<f64>,
    /// |u| of every landing (relative impact velocities).
    pub impact_speeds: Vec<f64>,
}

/// One impact of a cycle held on a segment of the table: where its landing falls just
/// outside that segment, the restitution law and the map's derivatives there take f' and
/// f'' from the segment's formula continued beyond its end, not from the piece the
/// landing fell in. The map so held is smooth across that breakpoint (f and f' are
/// continuous there, f'' jumps), so Newton's method on it converges to the cycle of
/// that piece whichever side its iterates fall on: where two cycles, with the impact on
/// either side, meet on the border and end (a nonsmooth fold), the one asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hold {
    /// The impact, as [`CyclePoint::phases`] counts them (0 the launch's).
    pub impact: usize,
    /// The table segment it is held on ([`crate::table::Table::segment`]).
    pub segment: usize,
}

/// Step the map `n` times from the launch at time `t0` (any real; its phase is used)
/// with velocity `v0`; `map` must hold the system (α set) to use.
pub fn pass(map: &mut ImpactMap, t0: f64, v0: f64, n: usize, k: u32) -> Result<Pass, PassError> {
    pass_with(map, t0, v0, n, k, &[])
}

/// The f' and f'' of segment `segment` of `sys`'s table at `phase`, its formula
/// continued beyond its ends to the nearest of phase − 1, phase, phase + 1.
fn held_slopes(sys: &System, segment: usize, phase: f64) -> (f64, f64) {
    let seg = sys.table().segment(segment);
    let outside = |t: &f64| (seg.start - t).max(t - seg.end).max(0.0);
    let t = [phase - 1.0, phase, phase + 1.0]
        .into_iter()
        .min_by(|a, b| outside(a).total_cmp(&outside(b)))
        .unwrap_or(phase);
    let jet = seg.jet(t);
    (sys.alpha() * jet[1], sys.alpha() * jet[2])
}

/// [`pass`], with impacts held on table segments ([`Hold`]).
pub fn pass_with(
    map: &mut ImpactMap,
    t0: f64,
    v0: f64,
    n: usize,
    k: u32,
    holds: &[Hold],
) -> Result<Pass, PassError> {
    let period = t0.floor();
    let phase = wrap_phase(t0 - period);
    let sys = map.system().clone();
    let start =
        State::launch(&sys, period as i64, phase, v0, 0.0).map_err(|_| PassError::BadLaunch)?;
    if start.w <= 0.0 {
        return Err(PassError::BadLaunch);
    }
    map.set_state(start);
    let mut m = [[1.0, 0.0], [0.0, 1.0]];
    let mut col = [0.0, 0.0];
    let mut det = 1.0;
    let mut out = Pass {
        residual: [0.0; 2],
        monodromy: m,
        alpha_column: col,
        det,
        phases: Vec::with_capacity(n),
        velocities: Vec::with_capacity(n),
        times: Vec::with_capacity(n),
        impact_speeds: Vec::with_capacity(n),
    };
    // The relative launch velocity after a held landing, for the next flight's
    // derivatives (the map's own state keeps the table's).
    let mut held_w = None;
    for i in 0..n {
        let mut before = *map.state();
        if let Some(w) = held_w.take() {
            before.w = w;
        }
        let mut e = map.step().map_err(|_| PassError::Halt)?;
        if e.kind != EventKind::Impact {
            return Err(PassError::Stick { phase: e.phase });
        }
        let mut fl = flight(&sys, &before, &e).ok_or(PassError::Grazing { phase: e.phase })?;
        // Landing i is impact i + 1 of the cycle (the last one the launch's, 0). Held,
        // it leaves with vᵢ₊₁ = (1 + r) f'_held − r (v − τ), and its derivatives are
        // those of the landing on the held formula continued (u = v − τ − f'_held at
        // the landing, w = vᵢ₊₁ − f'_held after it), which the map's own landing time
        // matches to second order in the distance past the breakpoint (f and f' are
        // continuous there).
        let held = holds
            .iter()
            .find(|h| h.impact == (i + 1) % n && sys.table().segment_index(e.phase) != h.segment);
        if let Some(h) = held {
            let (df, ddf) = held_slopes(&sys, h.segment, e.phase);
            let shift = df - sys.df(e.phase);
            let u = e.vrel - shift;
            if u >= 0.0 {
                return Err(PassError::Grazing { phase: e.phase });
            }
            e.v += (1.0 + sys.r()) * shift;
            let tau = (e.period - before.period) as f64 + (e.phase - before.phase);
            let (a, b) = crate::tangent::flight_partials(before.w, tau, u);
            fl = crate::tangent::Flight {
                a,
                b,
                c: fl.c * fl.u_landing / u.abs(),
                df_alpha: df / sys.alpha(),
                ddf,
                u_landing: u.abs(),
                r: sys.r(),
            };
            let launch = State::launch(&sys, e.period, e.phase, e.v, 0.0)
                .map_err(|_| PassError::BadLaunch)?;
            map.set_state(launch);
            held_w = Some(e.v - df);
        }
        let j = fl.jacobian();
        let c = fl.alpha_column_with(fl.ddf);
        m = mat_mul(j, m);
        col = [
            j[0][0] * col[0] + j[0][1] * col[1] + c[0],
            j[1][0] * col[0] + j[1][1] * col[1] + c[1],
        ];
        det *= fl.det();
        out.phases.push(e.phase);
        out.velocities.push(e.v);
        out.times
            .push((e.period - start.period) as f64 + (e.phase - start.phase));
        out.impact_speeds.push(fl.u_landing);
    }
    let last = map.state();
    out.residual = [
        ((last.period - start.period) as f64 - k as f64) + (last.phase - start.phase),
        last.v - v0,
    ];
    out.monodromy = m;
    out.alpha_column = col;
    out.det = det;
    Ok(out)
}

/// One accepted point of an (n, k) cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct CyclePoint {
    /// Events per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// The amplitude α of this point.
    pub alpha: f64,
    /// The launch time t₀ as the continuation carries it (its phase is `phases[0]`).
    pub t0: f64,
    /// The n impact phases, from the launch's, and the launch velocities after them.
    pub phases: Vec<f64>,
    /// Launch velocities after those impacts.
    pub velocities: Vec<f64>,
    /// The flight times, launch i to impact i + 1 (they sum to k).
    pub flights: Vec<f64>,
    /// The smallest relative impact velocity |u| of the cycle.
    pub min_impact_speed: f64,
    /// For even n and k: the return after n/2 impacts, (t_{n/2} − t₀ − k/2, v_{n/2} − v₀),
    /// zero where a doubled cycle collapses onto the one it doubled from.
    pub half_return: Option<[f64; 2]>,
    /// Multipliers of the cycle (eigenvalues of the n-fold map's Jacobian).
    pub multipliers: [Complex; 2],
    /// Both multipliers inside the unit circle.
    pub stable: bool,
    /// The map's return error after n steps (≤ [`RETURN_TOLERANCE`]).
    pub return_error: f64,
    /// Product of the flights' determinants / r²ⁿ − 1 (0 up to rounding on a cycle).
    pub det_error: f64,
    /// M: the Jacobian of the n-step map at the point.
    pub monodromy: [[f64; 2]; 2],
}

impl CyclePoint {
    /// (1 + λ₁)(1 + λ₂) = 1 + tr M + det M: zero at a period doubling.
    pub fn pd_test(&self) -> f64 {
        let tr = self.monodromy[0][0] + self.monodromy[1][1];
        1.0 + tr + self.r_det()
    }

    /// (1 − λ₁)(1 − λ₂) = 1 − tr M + det M: zero at a fold.
    pub fn fold_test(&self) -> f64 {
        let tr = self.monodromy[0][0] + self.monodromy[1][1];
        1.0 - tr + self.r_det()
    }

    fn r_det(&self) -> f64 {
        let [a, b] = self.multipliers;
        // λ₁λ₂ (real: = det; complex pair: |λ|²).
        a.re * b.re - a.im * b.im
    }

    /// The eigenvector of M for the multiplier nearest −1 (for switching onto the
    /// doubled branch), normalised.
    pub fn pd_direction(&self) -> [f64; 2] {
        let m = self.monodromy;
        // (M + I) e = 0: e ⟂ the larger row of M + I.
        let rows = [[m[0][0] + 1.0, m[0][1]], [m[1][0], m[1][1] + 1.0]];
        let row = if rows[0][0].hypot(rows[0][1]) >= rows[1][0].hypot(rows[1][1]) {
            rows[0]
        } else {
            rows[1]
        };
        let e = [-row[1], row[0]];
        let s = e[0].hypot(e[1]);
        if s > 0.0 {
            [e[0] / s, e[1] / s]
        } else {
            [1.0, 0.0]
        }
    }
}

/// Build the accepted point from a converged pass at (α, t₀, v₀).
pub(crate) fn accept(
    sys: &System,
    x: [f64; 3],
    n: usize,
    k: u32,
    p: &Pass,
) -> Result<CyclePoint, PassError> {
    let error = p.residual[0].abs().max(p.residual[1].abs());
    if error.is_nan() || error > RETURN_TOLERANCE {
        return Err(PassError::NotReturning { error });
    }
    let r2n = sys.r().powi(2 * n as i32);
    let tr = p.monodromy[0][0] + p.monodromy[1][1];
    let multipliers = eigenvalues_tr_det(tr, r2n);
    let stable = multipliers.iter().all(|l| l.abs() < 1.0);
    let mut phases = Vec::with_capacity(n);
    phases.push(wrap_phase(x[1]));
    phases.extend_from_slice(&p.phases[..n - 1]);
    let mut velocities = Vec::with_capacity(n);
    velocities.push(x[2]);
    velocities.extend_from_slice(&p.velocities[..n - 1]);
    Ok(CyclePoint {
        n,
        k,
        alpha: x[0],
        t0: x[1],
        phases,
        velocities,
        flights: (0..n)
            .map(|i| p.times[i] - if i == 0 { 0.0 } else { p.times[i - 1] })
            .collect(),
        min_impact_speed: p
            .impact_speeds
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min),
        half_return: (n.is_multiple_of(2) && k.is_multiple_of(2)).then(|| {
            [
                p.times[n / 2 - 1] - (k / 2) as f64,
                p.velocities[n / 2 - 1] - x[2],
            ]
        }),
        multipliers,
        stable,
        return_error: error,
        det_error: p.det / r2n - 1.0,
        monodromy: p.monodromy,
    })
}

/// A map prepared for `sys` (the exact solver, any state: each pass sets its own).
pub fn map_for(sys: &System) -> ImpactMap {
    let st = State::start(sys, 0.0, None, 0.0).expect("the default start is valid");
    ImpactMap::new(sys.clone(), Solver::Exact, st)
}

/// Newton's method at fixed α (the one of `map`'s system) for the (n, k) cycle through
/// (t₀, v₀) near the guess with impacts held on table segments ([`Hold`]): the cycle
/// whose impacts lie in those segments, where it exists. The point is accepted as
/// [`solve_at`]'s is, by the map itself, unheld: where the held map's cycle has the
/// impact outside the segment beyond rounding, no such cycle exists there
/// ([`PassError::NotReturning`]).
pub fn solve_held(
    map: &mut ImpactMap,
    n: usize,
    k: u32,
    (t0, v0): (f64, f64),
    holds: &[Hold],
) -> Result<CyclePoint, PassError> {
    let mut x = [t0, v0];
    for _ in 0..MAX_NEWTON {
        let p = pass_with(map, x[0], x[1], n, k, holds)?;
        let m = p.monodromy;
        let a = [[m[0][0] - 1.0, m[0][1]], [m[1][0], m[1][1] - 1.0]];
        let d = solve(a, p.residual).ok_or(PassError::NoConvergence)?;
        if !(d[0].is_finite() && d[1].is_finite()) || d[0].abs().max(d[1].abs()) > 0.5 {
            return Err(PassError::NoConvergence);
        }
        x = [x[0] - d[0], x[1] - d[1]];
        let residual = p.residual[0].abs().max(p.residual[1].abs());
        if d[0].abs().max(d[1].abs()) < 1e-14 * (1.0 + x[1].abs()) || residual < 1e-15 {
            let p = pass(map, x[0], x[1], n, k)?;
            let sys = map.system().clone();
            return accept(&sys, [sys.alpha(), x[0], x[1]], n, k, &p);
        }
    }
    Err(PassError::NoConvergence)
}

/// Newton's method at fixed α (the one of `map`'s system) for the (n, k) cycle through
/// (t₀, v₀) near the guess.
pub fn solve_at(
    map: &mut ImpactMap,
    n: usize,
    k: u32,
    t0: f64,
    v0: f64,
) -> Result<CyclePoint, PassError> {
    let mut x = [map.system().alpha(), t0, v0];
    for _ in 0..MAX_NEWTON {
        let p = pass(map, x[1], x[2], n, k)?;
        let m = p.monodromy;
        let a = [[m[0][0] - 1.0, m[0][1]], [m[1][0], m[1][1] - 1.0]];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        if det == 0.0 || !det.is_finite() {
            return Err(PassError::NoConvergence);
        }
        let f = p.residual;
        let dt = (f[0] * a[1][1] - f[1] * a[0][1]) / det;
        let dv = (a[0][0] * f[1] - a[1][0] * f[0]) / det;
        x[1] -= dt;
        x[2] -= dv;
        if dt.abs().max(dv.abs()) < 1e-14 * (1.0 + x[2].abs()) || f[0].abs().max(f[1].abs()) < 1e-15
        {
            let p = pass(map, x[1], x[2], n, k)?;
            let sys = map.system().clone();
            return accept(&sys, x, n, k, &p);
        }
    }
    Err(PassError::NoConvergence)
}

/// The (n, k) cycle of `sys` near the launch (t₀, v₀), by Newton's method at fixed α.
pub fn cycle(sys: &System, n: usize, k: u32, t0: f64, v0: f64) -> Result<CyclePoint, PassError> {
    solve_at(&mut map_for(sys), n, k, t0, v0)
}

/// The cycles of impacts of up to `max_events` impacts next to the launch (t₀, v₀)
/// (right after an impact), shortest first: for each n whose n-th event returns within
/// 0.05 of the launch in phase and in velocity (relative) after n impacts, the (n, k)
/// cycle Newton's method finds from there, k the table periods those n took (a shorter
/// cycle run several times is taken as the shorter one). Each cycle is listed once.
/// For an orbit that did not settle (converging too slowly next to a bifurcation, where
/// a multiplier is near the unit circle), these are the cycles it may be approaching.
pub fn cycles_near(sys: &System, t0: f64, v0: f64, max_events: usize) -> Vec<CyclePoint> {
    let mut out: Vec<CyclePoint> = Vec::new();
    let Ok(start) = State::launch(sys, 0, wrap_phase(t0), v0, 0.0) else {
        return out;
    };
    // Two launches (phase, v) that are one, velocities to 1e-9 of 1 + |scale|.
    let same = |(p, v): (f64, f64), (q, w): (f64, f64), scale: f64| {
        crate::time::signed_distance(p, q).abs() < 1e-9
            && (v - w).abs() < 1e-9 * (1.0 + scale.abs())
    };
    let launch = |c: &CyclePoint, i: usize| (c.phases[i], c.velocities[i]);
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    for n in 1..=max_events {
        let Ok(e) = map.step() else { break };
        if e.kind != EventKind::Impact {
            break;
        }
        let near = crate::time::signed_distance(e.phase, start.phase()).abs() <= 0.05
            && (e.v - v0).abs() <= 0.05 * (1.0 + v0.abs());
        let Ok(k) = u32::try_from(e.period) else {
            break;
        };
        if !near || k == 0 {
            continue;
        }
        let Ok(mut c) = cycle(sys, n, k, start.phase(), v0) else {
            continue;
        };
        // Newton's method may have found a shorter cycle run several times: the
        // shortest whose launch returns after d of the n impacts is the cycle.
        if let Some(d) = (1..n).find(|d| n % d == 0 && same(launch(&c, *d), launch(&c, 0), v0)) {
            let kd = k as usize * d / n;
            if kd * n != k as usize * d || kd == 0 {
                continue;
            }
            match cycle(sys, d, kd as u32, c.phases[0], c.velocities[0]) {
                Ok(shorter) => c = shorter,
                Err(_) => continue,
            }
        }
        // A repeat of a shorter cycle: its launch is on one found already.
        let repeat = out.iter().any(|o| {
            c.n % o.n == 0 && (0..o.n).any(|i| same(launch(o, i), launch(&c, 0), o.velocities[i]))
        });
        if !repeat {
            out.push(c);
        }
    }
    out
}

/// The corrector of pseudo-arclength continuation: the (n, k) cycle with
/// τ·(x − x₀) = h, started from x₀ + hτ.
pub(crate) fn correct(
    map: &mut ImpactMap,
    n: usize,
    k: u32,
    x0: [f64; 3],
    tau: [f64; 3],
    h: f64,
) -> Result<(CyclePoint, [f64; 3]), PassError> {
    let mut x = [x0[0] + h * tau[0], x0[1] + h * tau[1], x0[2] + h * tau[2]];
    for it in 0..MAX_NEWTON {
        map.set_alpha(x[0]).map_err(|_| PassError::BadLaunch)?;
        let p = pass(map, x[1], x[2], n, k)?;
        let m = p.monodromy;
        let a = [
            [p.alpha_column[0], m[0][0] - 1.0, m[0][1]],
            [p.alpha_column[1], m[1][0], m[1][1] - 1.0],
            tau,
        ];
        let g = (0..3).map(|i| tau[i] * (x[i] - x0[i])).sum::<f64>() - h;
        let b = [p.residual[0], p.residual[1], g];
        let d = solve(a, b).ok_or(PassError::NoConvergence)?;
        for i in 0..3 {
            x[i] -= d[i];
        }
        let step = d.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        if step < 1e-13 || (it > 0 && p.residual[0].abs().max(p.residual[1].abs()) < 1e-15) {
            map.set_alpha(x[0]).map_err(|_| PassError::BadLaunch)?;
            let p = pass(map, x[1], x[2], n, k)?;
            let sys = map.system().clone();
            let pt = accept(&sys, x, n, k, &p)?;
            // The tangent: the null vector of [F_α | M − I].
            let m = p.monodromy;
            let r0 = [p.alpha_column[0], m[0][0] - 1.0, m[0][1]];
            let r1 = [p.alpha_column[1], m[1][0], m[1][1] - 1.0];
            let mut t = cross(r0, r1);
            let s = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
            if !(s > 0.0 && s.is_finite()) {
                return Err(PassError::NoConvergence);
            }
            let sign = if t.iter().zip(tau).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
                -1.0
            } else {
                1.0
            };
            for v in t.iter_mut() {
                *v *= sign / s;
            }
            return Ok((pt, t));
        }
        if !step.is_finite() || step > 1.0 {
            return Err(PassError::NoConvergence);
        }
    }
    Err(PassError::NoConvergence)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The smallest height of the ball above the table at an interior local minimum of the
/// gap over the cycle's flights (infinity if no flight has one), with its phase: zero
/// where a flight grazes the table, so the impact sequence would change.
pub fn min_interior_gap(sys: &System, pt: &CyclePoint) -> (f64, f64) {
    const SAMPLES: usize = 64;
    let mut best = (f64::INFINITY, f64::NAN);
    for i in 0..pt.n {
        let (ph, v, tau) = (pt.phases[i], pt.velocities[i], pt.flights[i]);
        let f0 = sys.f(ph);
        let gap = |s: f64| f0 + v * s - 0.5 * s * s - sys.f(wrap_phase(ph + s));
        let g: Vec<f64> = (0..=SAMPLES)
            .map(|j| gap(tau * j as f64 / SAMPLES as f64))
            .collect();
        for j in 1..SAMPLES {
            if !(g[j] < g[j - 1] && g[j] <= g[j + 1]) {
                continue;
            }
            // Newton on g'(s) = v − s − f'(t̂ + s), from the sample.
            let mut s = tau * j as f64 / SAMPLES as f64;
            for _ in 0..20 {
                let q = wrap_phase(ph + s);
                let d1 = v - s - sys.df(q);
                let d2 = -1.0 - sys.ddf(q);
                if d2 <= 0.0 {
                    break;
                }
                let next = (s - d1 / d2).clamp(0.0, tau);
                if (next - s).abs() < 1e-15 {
                    break;
                }
                s = next;
            }
            let m = gap(s).min(g[j]);
            if m < best.0 {
                best = (m, wrap_phase(ph + s));
            }
        }
    }
    best
}
