//! Power laws of the (2, 2k) branch near the period-doubling point (the paper's Fig. 4
//! and Fig. 5): least-squares fits log10 ΔT = a_T log10 Δκ + b_T and
//! log10 Δt = a_t log10 Δκ + b_t.
//!
//! Three sources: the exact (2, 2k) solutions ([`exact_fits`]), simulated orbits of the
//! impact map as in the paper ([`simulated_point`]), and the analytic intercepts
//! ([`analytic_intercepts_paper`], the printed Eqs. (bT), (bt); and
//! [`analytic_intercepts_corrected`], the corrected leading order).
//!
//! Logarithms are decimal: the intercepts of the paper's Fig. 4 caption agree with the
//! analytic ones only in base 10 (see the README).

use super::fixed::{alpha_at_delta_kappa, fixed_point_at, stability_window, WindowEnd};
use super::fixed_point_slope;
use super::two_cycle::{approximation_corrected, two_cycle, TwoCycle};
use crate::error::EngineError;
use crate::map::{ImpactMap, State};
use crate::system::{kappa_c, System};
use crate::table::Table;

/// A straight-line least-squares fit y = slope·x + intercept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Slope of the line.
    pub slope: f64,
    /// Its intercept.
    pub intercept: f64,
    /// Points fitted.
    pub points: usize,
}

/// Ordinary least squares; None with fewer than two distinct x.
pub fn least_squares(xs: &[f64], ys: &[f64]) -> Option<Fit> {
    let n = xs.len().min(ys.len());
    if n < 2 {
        return None;
    }
    let mx = xs[..n].iter().sum::<f64>() / n as f64;
    let my = ys[..n].iter().sum::<f64>() / n as f64;
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for i in 0..n {
        sxx += (xs[i] - mx) * (xs[i] - mx);
        sxy += (xs[i] - mx) * (ys[i] - my);
    }
    (sxx > 0.0).then(|| {
        let slope = sxy / sxx;
        Fit {
            slope,
            intercept: my - slope * mx,
            points: n,
        }
    })
}

/// `n` values log-spaced from `lo` to `hi` inclusive.
pub fn log_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![lo];
    }
    let (a, b) = (lo.log10(), hi.log10());
    (0..n)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
        .collect()
}

/// The exact (2, 2k) solution at Δκ past the period-doubling point of the first
/// stability window.
pub fn exact_at(table: &Table, r: f64, k: u32, delta_kappa: f64) -> Option<TwoCycle> {
    let (alpha, _) = alpha_at_delta_kappa(table, r, k, delta_kappa).ok()??;
    let sys = System::new(table.clone(), alpha, r).ok()?;
    two_cycle(&sys, k).ok()
}

/// ΔT and Δt of one exact (2, 2k) solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactPoint {
    /// Δκ = κ_c − f''(t̂*) of the solution's system.
    pub delta_kappa: f64,
    /// ΔT = t̂₁* + t̂₀* − 2t̂*.
    pub delta_big_t: f64,
    /// Δt = t̂₁* − t̂₀*.
    pub delta_t: f64,
}

/// The exact (2, 2k) solutions at the given Δκ values, with positive ΔT and Δt; values
/// without a solution are left out.
pub fn exact_points(table: &Table, r: f64, k: u32, delta_kappas: &[f64]) -> Vec<ExactPoint> {
    delta_kappas
        .iter()
        .filter_map(|&dk| exact_at(table, r, k, dk))
        .filter(|tc| tc.delta_big_t > 0.0 && tc.delta_t > 0.0)
        .map(|tc| ExactPoint {
            delta_kappa: tc.delta_kappa,
            delta_big_t: tc.delta_big_t,
            delta_t: tc.delta_t,
        })
        .collect()
}

/// Fits of log10 ΔT and log10 Δt against log10 Δκ through points (Δκ, ΔT, Δt).
pub fn fit_log_log(points: impl IntoIterator<Item = (f64, f64, f64)>) -> Option<(Fit, Fit)> {
    let mut x = Vec::new();
    let (mut yt, mut ys) = (Vec::new(), Vec::new());
    for (dk, big_t, t) in points {
        x.push(dk.log10());
        yt.push(big_t.log10());
        ys.push(t.log10());
    }
    Some((least_squares(&x, &yt)?, least_squares(&x, &ys)?))
}

/// Fits of log10 ΔT and log10 Δt against log10 Δκ from exact (2, 2k) solutions at the
/// given Δκ values. Points without a solution are left out.
pub fn exact_fits(table: &Table, r: f64, k: u32, delta_kappas: &[f64]) -> Option<(Fit, Fit)> {
    fit_log_log(
        exact_points(table, r, k, delta_kappas)
            .iter()
            .map(|p| (p.delta_kappa, p.delta_big_t, p.delta_t)),
    )
}

/// ΔT and Δt read from a simulated orbit, and how well it had settled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulatedPoint {
    /// Δκ = κ_c − f″(t̂*) of the simulated system.
    pub delta_kappa: f64,
    /// ΔT read from the orbit.
    pub delta_big_t: f64,
    /// Δt read from the orbit.
    pub delta_t: f64,
    /// |change of t̂₀ and t̂₁| over the last two-bounce return (a convergence measure).
    pub settled_to: f64,
    /// Bounces simulated.
    pub bounces: u64,
}

/// Simulate the impact map (exact solver) at Δκ past the period-doubling point, starting
/// from the (1, k) solution with its phase moved by 10⁻³, as the paper did. The impact
/// phases of the last two bounces give t̂₀ < t̂₁. At most `max_bounces` impacts; the run
/// stops early once successive two-bounce returns agree to 10⁻¹³.
pub fn simulated_point(
    table: &Table,
    r: f64,
    k: u32,
    delta_kappa: f64,
    max_bounces: u64,
) -> Option<SimulatedPoint> {
    let (alpha, phase) = alpha_at_delta_kappa(table, r, k, delta_kappa).ok()??;
    let sys = System::new(table.clone(), alpha, r).ok()?;
    let fp = fixed_point_at(&sys, k, phase);
    let start = (phase + 1e-3).min(0.999_999);
    let v = 0.5 * k as f64 + sys.df(start) - sys.df(phase);
    let state = State::launch(&sys, 0, start, v, 0.0).ok()?;
    let mut map = ImpactMap::new(sys, crate::impact::Solver::Exact, state);
    let mut last = [f64::NAN; 4];
    let mut settled = f64::INFINITY;
    let mut n = 0;
    while n < max_bounces {
        let e = map.step().ok()?;
        n += 1;
        last = [last[1], last[2], last[3], e.phase];
        if n >= 4 && n % 2 == 0 {
            settled = (last[3] - last[1]).abs().max((last[2] - last[0]).abs());
            if settled <= 1e-13 {
                break;
            }
        }
    }
    let (a, b) = (last[2], last[3]);
    let (t0, t1) = if a < b { (a, b) } else { (b, a) };
    Some(SimulatedPoint {
        delta_kappa: fp.delta_kappa,
        delta_big_t: t0 + t1 - 2.0 * phase,
        delta_t: t1 - t0,
        settled_to: settled,
        bounces: n,
    })
}

/// The paper's analytic intercepts, Eqs. (bT) and (bt) (decimal logarithms), with
/// f'''(t̂*) ≈ −3κ_c D as in its Appendix C.
pub fn analytic_intercepts_paper(d: f64, r: f64, k: u32) -> (f64, f64) {
    let c = fixed_point_slope(r, k);
    let kc = kappa_c(r);
    let k2 = (k as f64).powi(2);
    let big = 1.0 - 4.0 * c * c / (3.0 * k2) * kc / (1.0 + kc);
    let small = (1.0 + kc) / (4.0 * c * kc) - c / (3.0 * k2);
    (
        -d.log10() - (-3.0 * kc * big).log10(),
        -0.5 * d.log10() - 0.5 * (-3.0 * kc * small).log10(),
    )
}

/// The corrected analytic intercepts: the limit Δκ → 0 of log10 ΔT − log10 Δκ and
/// log10 Δt − ½ log10 Δκ from the corrected approximation, with f'(t̂*) and f'''(t̂*)
/// taken at α_PD of `table`.
pub fn analytic_intercepts_corrected(
    table: &Table,
    r: f64,
    k: u32,
) -> Result<Option<(f64, f64)>, EngineError> {
    let Some(win) = stability_window(table, r, k)? else {
        return Ok(None);
    };
    if win.end != WindowEnd::PeriodDoubling {
        return Ok(None);
    }
    let sys = System::new(table.clone(), win.alpha_end, r)?;
    let j = sys.jet(win.phase_end);
    // The approximation is exactly linear in Δκ (ΔT) and √Δκ (Δt): evaluate at Δκ = 1.
    Ok(
        approximation_corrected(fixed_point_slope(r, k), j[3], 1.0, r, k)
            .map(|a| (a.delta_big_t.log10(), a.delta_t.log10())),
    )
}

/// The fits printed in the caption of the paper's Fig. 4 (r = 0.8, k = 1):
/// (D, a_T, b_T, a_t, b_t).
pub const PAPER_FIG4_FITS: [(f64, f64, f64, f64, f64); 3] = [
    (0.001, 1.007, 3.031, 0.503, 1.994),
    (0.01, 1.001, 1.988, 0.501, 1.462),
    (0.1, 1.001, 0.914, 0.502, 0.830),
];

/// Δκ range (min, max) and count of the exact fits of [`scaling_row`].
pub const EXACT_RANGE: (f64, f64, usize) = (1e-9, 1e-7, 9);
/// Δκ range and count of the simulated fits of [`scaling_row`].
pub const SIM_RANGE: (f64, f64, usize) = (1e-6, 1e-5, 5);
/// Impact budget per simulated point of [`scaling_row`] (the paper ran 5·10⁶ periods).
pub const SIM_BOUNCES: u64 = 5_000_000;

/// Everything the paper's Fig. 4 and 5 show for one D of F_D.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingRow {
    /// D of the F_D table.
    pub d: f64,
    /// Exact (2, 2k) solutions over [`EXACT_RANGE`], and their fits (ΔT, Δt).
    pub exact_points: Vec<ExactPoint>,
    /// Fits of log ΔT and log Δt against log Δκ over the exact solutions.
    pub exact: Option<(Fit, Fit)>,
    /// Simulated orbits over [`SIM_RANGE`], and their fits.
    pub sim_points: Vec<SimulatedPoint>,
    /// The same fits over the simulated orbits.
    pub sim: Option<(Fit, Fit)>,
    /// The printed Eqs. (bT), (bt).
    pub paper_analytic: (f64, f64),
    /// The corrected intercepts (None without a period-doubling end of the window).
    pub corrected_analytic: Option<(f64, f64)>,
    /// The fit printed in the Fig. 4 caption (r = 0.8, k = 1 and its three D only):
    /// (a_T, b_T, a_t, b_t).
    pub paper_fit: Option<(f64, f64, f64, f64)>,
}

/// The Fig. 4 and 5 data for F_D: exact and simulated points and fits, the analytic
/// intercepts, and the paper's fit where it prints one.
pub fn scaling_row(d: f64, r: f64, k: u32) -> Result<ScalingRow, EngineError> {
    let table = Table::fd(d)?;
    let exact_points = exact_points(
        &table,
        r,
        k,
        &log_spaced(EXACT_RANGE.0, EXACT_RANGE.1, EXACT_RANGE.2),
    );
    let exact = fit_log_log(
        exact_points
            .iter()
            .map(|p| (p.delta_kappa, p.delta_big_t, p.delta_t)),
    );
    let sim_points: Vec<SimulatedPoint> = log_spaced(SIM_RANGE.0, SIM_RANGE.1, SIM_RANGE.2)
        .into_iter()
        .filter_map(|dk| simulated_point(&table, r, k, dk, SIM_BOUNCES))
        .filter(|p| p.delta_t > 0.0 && p.delta_big_t > 0.0)
        .collect();
    let sim = fit_log_log(
        sim_points
            .iter()
            .map(|p| (p.delta_kappa, p.delta_big_t, p.delta_t)),
    );
    let paper_fit = (r == 0.8 && k == 1)
        .then(|| {
            PAPER_FIG4_FITS
                .iter()
                .find(|p| (p.0 - d).abs() <= 1e-12 * d)
        })
        .flatten()
        .map(|p| (p.1, p.2, p.3, p.4));
    Ok(ScalingRow {
        d,
        exact_points,
        exact,
        sim_points,
        sim,
        paper_analytic: analytic_intercepts_paper(d, r, k),
        corrected_analytic: analytic_intercepts_corrected(&table, r, k)?,
        paper_fit,
    })
}
