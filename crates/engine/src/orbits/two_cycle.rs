//! The (2, 2k) solutions born from a (1, k) solution at its period-doubling point.
//!
//! Unknowns: the impact phases t̂₀* < t̂₁* and the launch velocities v₀*, v₁*, with
//! ⌊t₁*⌋ − ⌊t₀*⌋ = k, so the flights last k + Δt and k − Δt (Δt = t̂₁* − t̂₀*). They
//! solve the paper's Eqs. (teq1)–(veq2). The fixed point (Δt = 0) solves them too, and
//! near the period-doubling point the Jacobian there is singular, so the equations are
//! solved in the equivalent form of the paper's Appendix B: the sum of each pair, and
//! the difference divided by Δt. In the variables m = (t̂₀* + t̂₁*)/2, η = (Δt/2)²,
//! σ = (v₀* + v₁*)/2 and u = (v₁* − v₀*)/Δt they read
//!
//! * G₁ = −k² − 4η + 2kσ − 4ηu
//! * G₂ = 2σ − 2k − ku − 2Q,  Q = (f(m + h) − f(m − h))/(2h)
//! * G₃ = 2(1 + r)σ − (1 + r)P − 2rk,  P = f'(m + h) + f'(m − h)
//! * G₄ = (1 − r)u − (1 + r)R − 2r,  R = (f'(m + h) − f'(m − h))/(2h)
//!
//! with h = √η. Q, P, R are even in h, i.e. functions of η, evaluated from the Taylor
//! coefficients of f at m (exact for polynomial pieces), so no difference quotient loses
//! digits, the trivial solution is gone, and Newton's method (analytic Jacobian) is
//! well conditioned down to Δκ → 0. Solutions with η ≤ 0 are not two-cycles.
//!
//! The table's formula on the piece holding t̂* is used on both impacts and continued
//! analytically; a solution whose phases leave that piece is reported as such (it is
//! past a border collision). The residuals of the original four equations are reported.

use crate::linalg::{eigenvalues_2x2, mat_mul, solve, Complex};
use crate::system::{kappa_c, System};
use crate::time::{normalize, wrap_phase};

const MAX_ALPHA: f64 = crate::limits::ALPHA.hi;
use super::fixed::fixed_point_slope;
use super::fixed::{fixed_points, lands_after, stability_window, FixedPoint, WindowEnd};
use super::roots::bracketed_root;
use crate::table::Table;
use crate::table::{Segment, TAYLOR_TERMS};
use std::fmt;

/// ΔT = t̂₁* + t̂₀* − 2t̂* and Δt = t̂₁* − t̂₀* of an approximation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Approximation {
    /// ΔT = t̂₁* + t̂₀* − 2t̂*.
    pub delta_big_t: f64,
    /// Δt = t̂₁* − t̂₀*.
    pub delta_t: f64,
}

/// The (2, 2k) approximation as printed in the paper, Eqs. (deltaT) and (deltat), with
/// c = f'(t̂*), j = f'''(t̂*), Δκ = κ_c − f''(t̂*). None where it has no real value.
pub fn approximation_paper(
    c: f64,
    j: f64,
    delta_kappa: f64,
    r: f64,
    k: u32,
) -> Option<Approximation> {
    let kc = kappa_c(r);
    let k2 = (k as f64) * (k as f64);
    let big_k = delta_kappa / j;
    let big = 1.0 - 4.0 * c * c / (3.0 * k2) * kc / (1.0 + kc);
    let small = (1.0 + kc) / (4.0 * c * kc) - c / (3.0 * k2);
    let dt2 = big_k / small;
    (j != 0.0 && dt2 >= 0.0 && dt2.is_finite()).then(|| Approximation {
        delta_big_t: big_k / big,
        delta_t: dt2.sqrt(),
    })
}

/// The corrected leading-order (2, 2k) solution as Δκ → 0 at fixed f''' (see the
/// README, "Corrections to the paper"):
/// ΔT = 2 (1 − (4c²/3k²) κ_c/(1 + κ_c − c j/2))⁻¹ Δκ/j and
/// Δt = ((1 + κ_c − c j/2)/(4 c κ_c) − c/(3k²))^(−1/2) (Δκ/j)^(1/2).
pub fn approximation_corrected(
    c: f64,
    j: f64,
    delta_kappa: f64,
    r: f64,
    k: u32,
) -> Option<Approximation> {
    let kc = kappa_c(r);
    let k2 = (k as f64) * (k as f64);
    let big_k = delta_kappa / j;
    let lead = 1.0 + kc - 0.5 * c * j;
    let big = 1.0 - 4.0 * c * c / (3.0 * k2) * kc / lead;
    let small = lead / (4.0 * c * kc) - c / (3.0 * k2);
    let dt2 = big_k / small;
    (j != 0.0 && dt2 >= 0.0 && dt2.is_finite()).then(|| Approximation {
        delta_big_t: 2.0 * big_k / big,
        delta_t: dt2.sqrt(),
    })
}

/// A (2, 2k) solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoCycle {
    /// Half the table periods per two-cycle: a (2, 2k) solution.
    pub k: u32,
    /// The amplitude α.
    pub alpha: f64,
    /// The (1, k) solution it surrounds.
    pub fixed: FixedPoint,
    /// Impact phases (t̂₀* < t̂₁*, wrapped into [0, 1)) and launch velocities.
    pub phase0: f64,
    /// Phase of the second impact.
    pub phase1: f64,
    /// Launch velocity after the first impact.
    pub v0: f64,
    /// Launch velocity after the second impact.
    pub v1: f64,
    /// ΔT = t̂₁* + t̂₀* − 2t̂*, Δt = t̂₁* − t̂₀*, Δκ = κ_c − f''(t̂*).
    pub delta_big_t: f64,
    /// Δt = t̂₁* − t̂₀*.
    pub delta_t: f64,
    /// Δκ = κ_c − f″(t̂*).
    pub delta_kappa: f64,
    /// Multipliers of the two-bounce map (eigenvalues of its Jacobian).
    pub multipliers: [Complex; 2],
    /// Whether both multipliers lie inside the unit circle.
    pub stable: bool,
    /// Both flights land where they should and not earlier.
    pub admissible: bool,
    /// Largest residual of the paper's Eqs. (teq1)–(veq2) at the solution.
    pub residual: f64,
    /// Newton iterations taken.
    pub newton_iterations: u32,
    /// The paper's printed approximation and the corrected one at this Δκ.
    pub paper: Option<Approximation>,
    /// The corrected approximation.
    pub corrected: Option<Approximation>,
}

/// Why no (2, 2k) solution is reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoTwoCycle {
    /// No admissible (1, k) solution with f'' < 0 exists at this α.
    NoFixedPoint,
    /// The (1, k) solution is still stable (Δκ ≤ 0): no branch has been born.
    BeforePeriodDoubling {
        /// Δκ = κ_c − f″(t̂*) (≤ 0).
        delta_kappa: f64,
    },
    /// f''' = 0 on the piece of t̂* (piecewise quadratic): by the paper's proof a
    /// (2, 2k) solution can exist only at Δκ = 0 exactly, so none is born.
    LocallyQuadratic {
        /// Δκ = κ_c − f″(t̂*).
        delta_kappa: f64,
    },
    /// Newton's method converged onto the (1, k) solution itself (Δt = 0), or to
    /// Δt² < 0: not a two-cycle.
    CollapsedOntoFixedPoint,
    /// Newton's method did not converge.
    NoConvergence,
    /// The solution's phases leave the table piece holding t̂* (past a border collision).
    LeavesPiece {
        /// Phase of the first impact.
        phase0: f64,
        /// Phase of the second impact.
        phase1: f64,
    },
}

impl fmt::Display for NoTwoCycle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NoTwoCycle::NoFixedPoint => write!(f, "no admissible (1, k) solution with f'' < 0 exists at this alpha"),
            NoTwoCycle::BeforePeriodDoubling { delta_kappa } => write!(f, "the (1, k) solution is still stable (delta_kappa = {delta_kappa:.6e} <= 0): no (2, 2k) branch is born before the period-doubling point"),
            NoTwoCycle::LocallyQuadratic { delta_kappa } => write!(f, "f''' = 0 on the table piece of the (1, k) solution (piecewise quadratic): a (2, 2k) solution could exist only at delta_kappa = 0 exactly (here {delta_kappa:.6e}), so none is born at the crisis"),
            NoTwoCycle::CollapsedOntoFixedPoint => write!(f, "Newton's method converged onto the (1, k) solution itself (delta_t = 0) or to delta_t^2 < 0: no (2, 2k) solution"),
            NoTwoCycle::NoConvergence => write!(f, "Newton's method did not converge from the approximation or by continuation from the period-doubling point"),
            NoTwoCycle::LeavesPiece { phase0, phase1 } => write!(f, "the (2, 2k) branch has left the table piece of the (1, k) solution (phases {phase0:.9}, {phase1:.9}): it is past its border collision"),
        }
    }
}

impl NoTwoCycle {
    /// Short machine-readable name.
    pub fn as_str(&self) -> &'static str {
        match self {
            NoTwoCycle::NoFixedPoint => "no_fixed_point",
            NoTwoCycle::BeforePeriodDoubling { .. } => "before_period_doubling",
            NoTwoCycle::LocallyQuadratic { .. } => "locally_quadratic",
            NoTwoCycle::CollapsedOntoFixedPoint => "collapsed_onto_fixed_point",
            NoTwoCycle::NoConvergence => "no_convergence",
            NoTwoCycle::LeavesPiece { .. } => "leaves_piece",
        }
    }
}

/// Newton's unknowns (m, η, σ, u).
type X = [f64; 4];

/// The desingularised equations on one smooth segment.
struct Equations<'a> {
    seg: Segment<'a>,
    alpha: f64,
    r: f64,
    k: f64,
}

/// Q, Q_η, R (= Q_m), R_m, R_η, P, P_m, P_η at (m, η).
struct Sums {
    q: f64,
    q_eta: f64,
    rr: f64,
    rr_m: f64,
    rr_eta: f64,
    p: f64,
    p_m: f64,
    p_eta: f64,
}

impl Equations<'_> {
    fn sums(&self, m: f64, eta: f64) -> Sums {
        let b = self.seg.taylor(m);
        let a = self.alpha;
        let mut s = Sums {
            q: 0.0,
            q_eta: 0.0,
            rr: 0.0,
            rr_m: 0.0,
            rr_eta: 0.0,
            p: 0.0,
            p_m: 0.0,
            p_eta: 0.0,
        };
        // Powers η^i, i = (n − 1)/2 etc., accumulated term by term.
        for n in 1..TAYLOR_TERMS {
            let bn = a * b[n];
            let bn1 = if n + 1 < TAYLOR_TERMS {
                a * b[n + 1]
            } else {
                0.0
            };
            let nf = n as f64;
            if n % 2 == 1 {
                let i = (n - 1) / 2;
                let e = eta.powi(i as i32);
                s.q += bn * e;
                s.p += 2.0 * nf * bn * e;
                s.p_m += 2.0 * nf * (nf + 1.0) * bn1 * e;
                if i >= 1 {
                    let e1 = eta.powi(i as i32 - 1);
                    s.q_eta += i as f64 * bn * e1;
                    s.p_eta += 2.0 * nf * i as f64 * bn * e1;
                }
            } else {
                let i = (n - 2) / 2;
                let e = eta.powi(i as i32);
                s.rr += nf * bn * e;
                s.rr_m += nf * (nf + 1.0) * bn1 * e;
                if i >= 1 {
                    s.rr_eta += nf * i as f64 * bn * eta.powi(i as i32 - 1);
                }
            }
        }
        s
    }

    fn residual_and_jacobian(&self, x: &X) -> (X, [[f64; 4]; 4]) {
        let [m, eta, sigma, u] = *x;
        let (r, k) = (self.r, self.k);
        let s = self.sums(m, eta);
        let g = [
            -k * k - 4.0 * eta + 2.0 * k * sigma - 4.0 * eta * u,
            2.0 * sigma - 2.0 * k - k * u - 2.0 * s.q,
            2.0 * (1.0 + r) * sigma - (1.0 + r) * s.p - 2.0 * r * k,
            (1.0 - r) * u - (1.0 + r) * s.rr - 2.0 * r,
        ];
        let jac = [
            [0.0, -4.0 - 4.0 * u, 2.0 * k, -4.0 * eta],
            [-2.0 * s.rr, -2.0 * s.q_eta, 2.0, -k],
            [
                -(1.0 + r) * s.p_m,
                -(1.0 + r) * s.p_eta,
                2.0 * (1.0 + r),
                0.0,
            ],
            [-(1.0 + r) * s.rr_m, -(1.0 + r) * s.rr_eta, 0.0, 1.0 - r],
        ];
        (g, jac)
    }

    /// σ and u solving G₃ = G₄ = 0 for given (m, η): a consistent start for Newton.
    fn start(&self, m: f64, eta: f64) -> X {
        let s = self.sums(m, eta);
        let r = self.r;
        let sigma = (s.p * (1.0 + r) + 2.0 * r * self.k) / (2.0 * (1.0 + r));
        let u = ((1.0 + r) * s.rr + 2.0 * r) / (1.0 - r);
        [m, eta, sigma, u]
    }

    /// Newton's method with backtracking; the solution and the iterations used.
    fn solve(&self, mut x: X) -> Option<(X, u32)> {
        let norm = |g: &X| g.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let (mut g, mut jac) = self.residual_and_jacobian(&x);
        let mut gn = norm(&g);
        for it in 1..=60u32 {
            let dx = solve(jac, g.map(|v| -v))?;
            let mut lambda = 1.0;
            let mut accepted = false;
            for _ in 0..30 {
                let trial = [
                    x[0] + lambda * dx[0],
                    x[1] + lambda * dx[1],
                    x[2] + lambda * dx[2],
                    x[3] + lambda * dx[3],
                ];
                let (tg, tj) = self.residual_and_jacobian(&trial);
                let tn = norm(&tg);
                if tn.is_finite() && (tn < gn || tn <= 1e-15) {
                    x = trial;
                    g = tg;
                    jac = tj;
                    gn = tn;
                    accepted = true;
                    break;
                }
                lambda *= 0.5;
            }
            let step = dx.iter().fold(0.0f64, |a, v| a.max(v.abs())) * lambda;
            let scale = 1.0 + x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if gn <= 1e-13 * (1.0 + self.k * self.k) && step <= 1e-13 * scale {
                return Some((x, it));
            }
            if !accepted {
                // No decrease possible: converged to rounding level, or stuck.
                return (gn <= 1e-11 * (1.0 + self.k * self.k)).then_some((x, it));
            }
        }
        (gn <= 1e-11 * (1.0 + self.k * self.k)).then_some((x, 60))
    }
}

/// The (1, k) solution a (2, 2k) branch is sought around: the admissible one with
/// f'' < 0 closest to κ_c.
pub fn period_doubling_candidate(sys: &System, k: u32) -> Option<FixedPoint> {
    fixed_points(sys, k)
        .ok()?
        .into_iter()
        .filter(|p| p.admissible && p.ddf < 0.0)
        .min_by(|a, b| a.delta_kappa.abs().total_cmp(&b.delta_kappa.abs()))
}

/// The (2, 2k) solution near the (1, k) solution of `sys` that is closest to its
/// period-doubling point.
pub fn two_cycle(sys: &System, k: u32) -> Result<TwoCycle, NoTwoCycle> {
    let fp = period_doubling_candidate(sys, k).ok_or(NoTwoCycle::NoFixedPoint)?;
    two_cycle_at(sys, &fp)
}

/// The (2, 2k) solution near a given (1, k) solution.
pub fn two_cycle_at(sys: &System, fp: &FixedPoint) -> Result<TwoCycle, NoTwoCycle> {
    let k = fp.k;
    let seg = sys.table().segment_at(fp.phase);
    if seg.is_quadratic() {
        return Err(NoTwoCycle::LocallyQuadratic {
            delta_kappa: fp.delta_kappa,
        });
    }
    if fp.delta_kappa <= 0.0 {
        return Err(NoTwoCycle::BeforePeriodDoubling {
            delta_kappa: fp.delta_kappa,
        });
    }
    let eq = Equations {
        seg,
        alpha: sys.alpha(),
        r: sys.r(),
        k: k as f64,
    };
    let paper = approximation_paper(fp.df, fp.dddf, fp.delta_kappa, sys.r(), k);
    let corrected = approximation_corrected(fp.df, fp.dddf, fp.delta_kappa, sys.r(), k);
    let mut solved = None;
    if let Some(a) = corrected {
        let x0 = eq.start(fp.phase + 0.5 * a.delta_big_t, 0.25 * a.delta_t * a.delta_t);
        solved = eq.solve(x0).filter(|(x, _)| x[1] > 0.0);
    }
    if solved.is_none() {
        solved = continue_from_pd(sys.table(), sys.r(), k, sys.alpha());
    }
    let (x, iters) = solved.ok_or(NoTwoCycle::NoConvergence)?;
    finish(sys, fp, &seg, x, iters, paper, corrected)
}

/// Build the report from a converged solution (m, η, σ, u).
fn finish(
    sys: &System,
    fp: &FixedPoint,
    seg: &Segment,
    x: X,
    iters: u32,
    paper: Option<Approximation>,
    corrected: Option<Approximation>,
) -> Result<TwoCycle, NoTwoCycle> {
    let [m, eta, sigma, u] = x;
    let h = eta.sqrt();
    if eta.is_nan() || eta <= 0.0 || h <= 1e-14 * (1.0 + m.abs()) {
        return Err(NoTwoCycle::CollapsedOntoFixedPoint);
    }
    let (t0, t1) = (m - h, m + h);
    if seg.breaks_at().is_finite() && (t0 < seg.start || t1 > seg.end) {
        return Err(NoTwoCycle::LeavesPiece {
            phase0: t0,
            phase1: t1,
        });
    }
    let k = fp.k;
    let kf = k as f64;
    let dt = 2.0 * h;
    let (v0, v1) = (sigma - h * u, sigma + h * u);
    let (r, a) = (sys.r(), sys.alpha());
    let j0 = seg.jet(t0).map(|v| a * v);
    let j1 = seg.jet(t1).map(|v| a * v);
    // The paper's four equations, as a check of the transformed system.
    let e = [
        -0.5 * (kf + dt).powi(2) + v0 * (kf + dt) + j0[0] - j1[0],
        -0.5 * (kf - dt).powi(2) + v1 * (kf - dt) + j1[0] - j0[0],
        v1 - (1.0 + r) * j1[1] + r * (v0 - (kf + dt)),
        v0 - (1.0 + r) * j0[1] + r * (v1 - (kf - dt)),
    ];
    let residual = e.iter().fold(0.0f64, |acc, v| acc.max(v.abs()));
    let step = |ta: [f64; 4], va: f64, tb: [f64; 4], tau: f64| {
        let wa = va - ta[1];
        let gb = va - tau - tb[1];
        let dt_dt = (wa - tau) / gb;
        let dt_dv = -tau / gb;
        let s = (1.0 + r) * tb[2] + r;
        [[dt_dt, dt_dv], [s * dt_dt - r, s * dt_dv - r]]
    };
    let m01 = step(j0, v0, j1, kf + dt);
    let m10 = step(j1, v1, j0, kf - dt);
    let multipliers = eigenvalues_2x2(mat_mul(m10, m01));
    let stable = multipliers.iter().all(|z| z.abs() < 1.0);
    let (p0, p1) = (normalize(0, t0).1, normalize(0, t1).1);
    let admissible = lands_after(sys, p0, v0, kf + dt).0 && lands_after(sys, p1, v1, kf - dt).0;
    Ok(TwoCycle {
        k,
        alpha: sys.alpha(),
        fixed: *fp,
        phase0: p0,
        phase1: p1,
        v0,
        v1,
        delta_big_t: t0 + t1 - 2.0 * fp.phase,
        delta_t: dt,
        delta_kappa: fp.delta_kappa,
        multipliers,
        stable,
        admissible,
        residual,
        newton_iterations: iters,
        paper,
        corrected,
    })
}

/// Follow the branch in α from just past the period-doubling point to `alpha_to`.
fn continue_from_pd(table: &Table, r: f64, k: u32, alpha_to: f64) -> Option<(X, u32)> {
    let mut branch = Branch::start(table, r, k)?;
    if alpha_to < branch.alpha {
        return None;
    }
    let mut total = 0;
    while branch.alpha < alpha_to {
        let next = (branch.alpha + branch.step).min(alpha_to);
        match branch.advance(next) {
            Some(it) => total += it,
            None => {
                branch.step *= 0.25;
                if branch.step < 1e-13 * branch.alpha {
                    return None;
                }
            }
        }
        if branch.steps > MAX_CONTINUATION_STEPS {
            return None;
        }
    }
    Some((branch.x, total))
}

/// Largest number of continuation steps.
pub const MAX_CONTINUATION_STEPS: usize = 20_000;

/// A (2, 2k) branch followed in α.
struct Branch<'a> {
    seg: Segment<'a>,
    r: f64,
    k: u32,
    alpha: f64,
    x: X,
    prev: Option<(f64, X)>,
    step: f64,
    steps: usize,
}

impl<'a> Branch<'a> {
    /// The branch a little past α_PD of the first stability window.
    fn start(table: &'a Table, r: f64, k: u32) -> Option<Branch<'a>> {
        let win = stability_window(table, r, k).ok()??;
        if win.end != WindowEnd::PeriodDoubling {
            return None;
        }
        let seg = table.segment_at(win.phase_end);
        if seg.is_quadratic() {
            return None;
        }
        let c = fixed_point_slope(r, k);
        let kc = kappa_c(r);
        // f''' at the period-doubling point, and a Δκ small enough for the asymptotics.
        let mut dk = 1e-7;
        for _ in 0..6 {
            let (alpha, phase) = super::fixed::alpha_at_delta_kappa(table, r, k, dk).ok()??;
            let jet = seg.jet(phase).map(|v| alpha * v);
            let appr = approximation_corrected(c, jet[3], kc - jet[2], r, k)?;
            let eq = Equations {
                seg,
                alpha,
                r,
                k: k as f64,
            };
            let x0 = eq.start(phase + 0.5 * appr.delta_big_t, 0.25 * appr.delta_t.powi(2));
            if let Some((x, _)) = eq.solve(x0).filter(|(x, _)| x[1] > 0.0) {
                return Some(Branch {
                    seg,
                    r,
                    k,
                    alpha,
                    x,
                    prev: None,
                    step: (alpha - win.alpha_end).max(1e-12 * alpha),
                    steps: 0,
                });
            }
            dk *= 0.1;
        }
        None
    }

    fn equations(&self, alpha: f64) -> Equations<'a> {
        Equations {
            seg: self.seg,
            alpha,
            r: self.r,
            k: self.k as f64,
        }
    }

    /// Solve at `alpha` from a secant prediction; on success move there.
    fn advance(&mut self, alpha: f64) -> Option<u32> {
        self.steps += 1;
        let guess = match self.prev {
            Some((pa, px)) if self.alpha != pa => {
                let s = (alpha - self.alpha) / (self.alpha - pa);
                std::array::from_fn(|i| self.x[i] + s * (self.x[i] - px[i]))
            }
            _ => self.x,
        };
        let (x, it) = self
            .equations(alpha)
            .solve(guess)
            .filter(|(x, _)| x[1] > 0.0)?;
        // Reject a jump to another solution: the step must be continuous.
        let jump = (x[0] - self.x[0]).abs() + (x[1].sqrt() - self.x[1].sqrt()).abs();
        if jump > 0.05 {
            return None;
        }
        self.prev = Some((self.alpha, self.x));
        self.alpha = alpha;
        self.x = x;
        if it <= 4 {
            self.step = (self.step * 2.0).min(0.01 * alpha);
        }
        Some(it)
    }

    /// Signed distance of the branch's outer impact phases inside the segment.
    fn border_margin(&self, x: &X) -> f64 {
        let h = x[1].max(0.0).sqrt();
        (x[0] - h - self.seg.start).min(self.seg.end - (x[0] + h))
    }
}

/// Where a (2, 2k) branch collides with a breakpoint of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BorderCollision {
    /// Half the table periods per two-cycle: a (2, 2k) branch.
    pub k: u32,
    /// α at which an impact phase of the branch reaches the breakpoint.
    pub alpha: f64,
    /// The breakpoint's phase (0 for F_D's t̂ = 0).
    pub phase: f64,
    /// α_PD where the branch was born.
    pub alpha_pd: f64,
    /// The two-cycle's phases and velocities at the collision.
    pub phase0: f64,
    /// Phase of the second impact.
    pub phase1: f64,
    /// Launch velocity after the first impact.
    pub v0: f64,
    /// Launch velocity after the second impact.
    pub v1: f64,
    /// Continuation steps taken.
    pub steps: usize,
}

/// Why no border collision is reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoBorderCollision {
    /// The table has no breakpoint (the sine).
    SmoothTable,
    /// The first stability window does not end by period doubling, or the branch could
    /// not be started (e.g. a piecewise quadratic table).
    NoBranch,
    /// The continuation failed at this α (a fold of the branch or a singularity).
    BranchLost {
        /// Where.
        alpha: f64,
    },
    /// The branch stays inside its piece up to the largest accepted α.
    NotReached,
}

impl fmt::Display for NoBorderCollision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NoBorderCollision::SmoothTable => write!(f, "the table has no breakpoint, so no border collision"),
            NoBorderCollision::NoBranch => write!(f, "no (2, 2k) branch is born at a period-doubling point"),
            NoBorderCollision::BranchLost { alpha } => write!(f, "the continuation of the (2, 2k) branch failed at alpha = {alpha:.12} before any breakpoint"),
            NoBorderCollision::NotReached => write!(f, "the (2, 2k) branch stays inside its table piece up to alpha = 1000"),
        }
    }
}

/// The α at which the (2, 2k) branch born at α_PD of the first stability window first
/// reaches a breakpoint of the table (for F_D: t̂ = 0), by continuation of the exact
/// solution in α and a bracketed root of the border margin.
pub fn border_collision(
    table: &Table,
    r: f64,
    k: u32,
) -> Result<BorderCollision, NoBorderCollision> {
    if table.breakpoints().is_empty() {
        return Err(NoBorderCollision::SmoothTable);
    }
    let mut b = Branch::start(table, r, k).ok_or(NoBorderCollision::NoBranch)?;
    let alpha_pd = stability_window(table, r, k)
        .ok()
        .flatten()
        .map_or(f64::NAN, |w| w.alpha_end);
    let mut margin = b.border_margin(&b.x);
    while margin > 0.0 {
        if b.alpha >= MAX_ALPHA {
            return Err(NoBorderCollision::NotReached);
        }
        if b.steps > MAX_CONTINUATION_STEPS {
            return Err(NoBorderCollision::BranchLost { alpha: b.alpha });
        }
        let (a0, x0) = (b.alpha, b.x);
        let next = (b.alpha + b.step).min(MAX_ALPHA);
        if b.advance(next).is_none() {
            b.step *= 0.25;
            if b.step < 1e-13 * b.alpha {
                return Err(NoBorderCollision::BranchLost { alpha: b.alpha });
            }
            continue;
        }
        let m1 = b.border_margin(&b.x);
        if m1 <= 0.0 {
            // Bracketed: refine α on [a0, b.alpha] with warm-started solves.
            let (a1, x1) = (b.alpha, b.x);
            let eqs = |alpha: f64| b.equations(alpha);
            let solve_at = |alpha: f64| -> Option<X> {
                let s = (alpha - a0) / (a1 - a0);
                let guess = std::array::from_fn(|i| x0[i] + s * (x1[i] - x0[i]));
                eqs(alpha).solve(guess).map(|(x, _)| x)
            };
            let g = |alpha: f64| solve_at(alpha).map_or(f64::NAN, |x| b.border_margin(&x));
            let alpha =
                bracketed_root(&g, a0, a1).ok_or(NoBorderCollision::BranchLost { alpha: a0 })?;
            let x = solve_at(alpha).ok_or(NoBorderCollision::BranchLost { alpha })?;
            let h = x[1].sqrt();
            let low = (x[0] - h - b.seg.start).abs() <= (b.seg.end - x[0] - h).abs();
            // The colliding impact is on the breakpoint (the condition located, to the
            // last bits): its phase is the breakpoint's, not 1 − 10⁻¹⁶ printed as 1.
            let border = wrap_phase(if low { b.seg.start } else { b.seg.end });
            let (phase0, phase1) = if low {
                (border, wrap_phase(x[0] + h))
            } else {
                (wrap_phase(x[0] - h), border)
            };
            return Ok(BorderCollision {
                k,
                alpha,
                phase: border,
                alpha_pd,
                phase0,
                phase1,
                v0: x[2] - h * x[3],
                v1: x[2] + h * x[3],
                steps: b.steps,
            });
        }
        margin = m1;
    }
    Err(NoBorderCollision::BranchLost { alpha: b.alpha })
}

/// Iterate the impact map (exact solver) from the two-cycle's first impact with its
/// phase moved by `perturbation`, for at most `max_bounces` impacts; stops once the last
/// two impact phases match (t̂₀*, t̂₁*) within 10⁻¹². Returns the bounces made and that
/// final distance (max over both phases), or None if the map halted.
pub fn map_check(
    sys: &System,
    tc: &TwoCycle,
    perturbation: f64,
    max_bounces: u64,
) -> Option<(u64, f64)> {
    use crate::map::{ImpactMap, State};
    let start = wrap_phase(tc.phase0 + perturbation);
    let v = tc.v0 + sys.df(start) - sys.df(tc.phase0);
    let state = State::launch(sys, 0, start, v, 0.0).ok()?;
    let mut map = ImpactMap::new(sys.clone(), crate::impact::Solver::Exact, state);
    let mut prev = f64::NAN;
    let mut dist = f64::INFINITY;
    for n in 1..=max_bounces {
        let e = map.step().ok()?;
        let (a, b) = if prev < e.phase {
            (prev, e.phase)
        } else {
            (e.phase, prev)
        };
        prev = e.phase;
        if n >= 2 {
            dist = (a - tc.phase0).abs().max((b - tc.phase1).abs());
            if dist <= 1e-12 {
                return Some((n, dist));
            }
        }
    }
    Some((max_bounces, dist))
}
