//! The (1, k) solutions: the ball bounces once every k table periods at the same phase.
//!
//! They satisfy f'(t̂*) = (k/2)(1 − r)/(1 + r) with v* = k/2. The linearised map has
//! A = [[1, 1 + r], [(1 + r) f'', (1 + r)² f'' + r²]] (det A = r²), stable iff
//! κ_c < f''(t̂*) < 0 with κ_c = −2(1 + r²)/(1 + r)². A solution is admissible only if
//! its free flight of k periods does not meet the table earlier (checked with the exact
//! next-impact solver); an inadmissible one is never called stable.
//!
//! Since f = αF, along a branch of solutions f'' = c F''/F' with c = f'(t̂*) fixed: the
//! phases where a (1, k) solution is stable do not depend on α, and each such phase t̂
//! belongs to α = c/F'(t̂). The stability windows in α are therefore the images of
//! intervals in phase, whose ends are roots of F', F'' or c F'' − κ_c F' (exact
//! polynomial root isolation on each piece, the closed form for the sine).

use super::roots::bracketed_root;
use crate::error::EngineError;
use crate::impact::{next_landing, Launch, Solver};
use crate::limits;
use crate::linalg::{eigenvalues_2x2, Complex};
use crate::system::{kappa_c, System};
use crate::table::{Segment, Table};
use crate::time::wrap_phase;

const MAX_ALPHA: f64 = limits::ALPHA.hi;

/// How a (1, k) solution behaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Classification {
    /// Both eigenvalues inside the unit circle (κ_c < f'' < 0).
    Stable,
    /// An eigenvalue at or beyond −1 (f'' ≤ κ_c): the period-doubling side.
    UnstablePeriodDoubling,
    /// An eigenvalue at or beyond +1 (f'' ≥ 0): a saddle.
    UnstableSaddle,
    /// The free flight meets the table before k periods: not a solution of the map.
    NotAdmissible,
}

impl Classification {
    /// Name used in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            Classification::Stable => "stable",
            Classification::UnstablePeriodDoubling => "unstable_period_doubling",
            Classification::UnstableSaddle => "unstable_saddle",
            Classification::NotAdmissible => "not_admissible",
        }
    }
}

/// One (1, k) solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedPoint {
    /// Table periods between bounces.
    pub k: u32,
    /// Phase t̂* in [0, 1).
    pub phase: f64,
    /// Launch velocity v* = k/2.
    pub v: f64,
    /// f'(t̂*), f''(t̂*), f'''(t̂*) (right derivatives at a breakpoint).
    pub df: f64,
    /// f′′(t̂*).
    pub ddf: f64,
    /// f′′′(t̂*).
    pub dddf: f64,
    /// Δκ = κ_c − f''(t̂*) (positive past the period-doubling point).
    pub delta_kappa: f64,
    /// The Jacobian A of the map at the solution.
    pub jacobian: [[f64; 2]; 2],
    /// Eigenvalues of A, larger real part first.
    pub eigenvalues: [Complex; 2],
    /// Duration of the free flight until the first contact (k when admissible; None if
    /// the solver found no contact).
    pub flight: Option<f64>,
    /// Whether the free flight of k periods meets the table only at its end.
    pub admissible: bool,
    /// Stable, period-doubling unstable, or fold unstable, from the eigenvalues.
    pub classification: Classification,
}

/// κ_c < f'' < 0: the stability band of the paper's Eq. (lsc).
pub fn stable_by_band(r: f64, ddf: f64) -> bool {
    kappa_c(r) < ddf && ddf < 0.0
}

/// The Jacobian of the map at a (1, k) solution with f''(t̂*) = `ddf`.
pub fn fixed_point_jacobian(r: f64, ddf: f64) -> [[f64; 2]; 2] {
    let q = 1.0 + r;
    [[1.0, q], [q * ddf, q * q * ddf + r * r]]
}

/// Classify from the eigenvalues (the admissibility verdict comes first).
pub fn classify(admissible: bool, eigenvalues: &[Complex; 2]) -> Classification {
    if !admissible {
        return Classification::NotAdmissible;
    }
    if eigenvalues.iter().all(|e| e.abs() < 1.0) {
        Classification::Stable
    } else if eigenvalues.iter().any(|e| e.im == 0.0 && e.re <= -1.0) {
        Classification::UnstablePeriodDoubling
    } else {
        Classification::UnstableSaddle
    }
}

/// Check k against [`limits::K`].
pub fn check_k(k: u32) -> Result<(), EngineError> {
    limits::K.check(k as f64).map(|_| ())
}

/// Whether a ball launched from the table at (0, `phase`) with velocity `v` first meets
/// the table after exactly `flight` (within 10⁻⁹), and the flight duration found.
pub fn lands_after(sys: &System, phase: f64, v: f64, flight: f64) -> (bool, Option<f64>) {
    let w = v - sys.df(phase);
    if w.is_nan() || w <= 0.0 {
        return (false, None);
    }
    let launch = Launch {
        period: 0,
        phase,
        height: 0.0,
        v,
        w,
    };
    match next_landing(sys, Solver::Exact, &launch) {
        Ok(l) => (
            (l.flight - flight).abs() <= 1e-9 * flight.max(1.0),
            Some(l.flight),
        ),
        Err(_) => (false, None),
    }
}

/// Every (1, k) solution of `sys`, in phase order.
pub fn fixed_points(sys: &System, k: u32) -> Result<Vec<FixedPoint>, EngineError> {
    check_k(k)?;
    let c = fixed_point_slope(sys.r(), k);
    let mut phases: Vec<f64> = Vec::new();
    for seg in sys.table().segments() {
        for t in seg.roots(-c / sys.alpha(), 1.0, 0.0) {
            let t = if t >= 1.0 { t - 1.0 } else { t };
            phases.push(t.max(0.0));
        }
    }
    phases.sort_by(f64::total_cmp);
    // A root on a breakpoint is found from both sides: keep one.
    let mut uniq: Vec<f64> = Vec::new();
    for t in phases {
        if uniq.last().is_none_or(|&u| t - u > 1e-12) {
            uniq.push(t);
        }
    }
    if uniq.len() > 1 && uniq[0] + 1.0 - uniq[uniq.len() - 1] <= 1e-12 {
        uniq.pop();
    }
    Ok(uniq
        .into_iter()
        .map(|t| fixed_point_at(sys, k, t))
        .collect())
}

/// The (1, k) data at a phase where f'(t̂) = c.
pub fn fixed_point_at(sys: &System, k: u32, phase: f64) -> FixedPoint {
    let j = sys.jet(phase);
    let v = 0.5 * k as f64;
    let jacobian = fixed_point_jacobian(sys.r(), j[2]);
    let eigenvalues = eigenvalues_2x2(jacobian);
    let (admissible, flight) = lands_after(sys, phase, v, k as f64);
    FixedPoint {
        k,
        phase,
        v,
        df: j[1],
        ddf: j[2],
        dddf: j[3],
        delta_kappa: kappa_c(sys.r()) - j[2],
        jacobian,
        eigenvalues,
        flight,
        admissible,
        classification: classify(admissible, &eigenvalues),
    }
}

/// Why a stability window ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WindowEnd {
    /// f''(t̂*) reaches κ_c: an eigenvalue −1.
    PeriodDoubling,
    /// f''(t̂*) reaches 0: an eigenvalue +1 (a fold).
    Fold,
    /// The solution crosses a breakpoint of the table where f'' jumps out of the band.
    Breakpoint,
    /// The free flight starts to meet the table earlier.
    Inadmissible,
    /// Still stable at the largest accepted α (1000).
    AlphaLimit,
}

impl WindowEnd {
    /// Name used in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            WindowEnd::PeriodDoubling => "period_doubling",
            WindowEnd::Fold => "fold",
            WindowEnd::Breakpoint => "breakpoint",
            WindowEnd::Inadmissible => "inadmissible",
            WindowEnd::AlphaLimit => "alpha_limit",
        }
    }
}

/// An α interval on which a stable, admissible (1, k) solution exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StabilityWindow {
    /// Table periods between bounces.
    pub k: u32,
    /// Where the stable solution first exists and is admissible, and its phase there.
    pub alpha_birth: f64,
    /// The phase at the birth.
    pub phase_birth: f64,
    /// Where it stops being stable, its phase there, and why.
    pub alpha_end: f64,
    /// The phase at the end.
    pub phase_end: f64,
    /// Why the window ends.
    pub end: WindowEnd,
}

impl StabilityWindow {
    /// α_PD, if the window ends by period doubling.
    pub fn alpha_pd(&self) -> Option<f64> {
        (self.end == WindowEnd::PeriodDoubling).then_some(self.alpha_end)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Cut {
    SegEdge,
    DfZero,
    DdfZero,
    PdRoot,
}

/// A phase interval inside one segment on which a stable solution lives.
#[derive(Clone, Copy, Debug)]
struct Stretch<'a> {
    lo: f64,
    hi: f64,
    seg: Segment<'a>,
    hi_cut: Cut,
}

/// Phase intervals where the (1, k) solution is stable: F' > 0, F'' < 0 and
/// c F'' − κ F' > 0 (i.e. κ < f'' < 0), grouped into connected components.
fn stable_components(table: &Table, c: f64, kappa: f64) -> Vec<Vec<Stretch<'_>>> {
    let mut stretches: Vec<Stretch> = Vec::new();
    for seg in table.segments() {
        let mut cuts: Vec<(f64, Cut)> = vec![(seg.start, Cut::SegEdge), (seg.end, Cut::SegEdge)];
        for t in seg.roots(0.0, 1.0, 0.0) {
            cuts.push((t, Cut::DfZero));
        }
        for t in seg.roots(0.0, 0.0, 1.0) {
            cuts.push((t, Cut::DdfZero));
        }
        for t in seg.roots(0.0, -kappa, c) {
            cuts.push((t, Cut::PdRoot));
        }
        cuts.retain(|(t, _)| *t >= seg.start && *t <= seg.end);
        cuts.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
        cuts.dedup_by(|b, a| b.0 - a.0 <= 1e-14);
        for w in cuts.windows(2) {
            let (lo, hi) = (w[0].0, w[1].0);
            if hi - lo <= 1e-14 {
                continue;
            }
            let j = seg.jet(0.5 * (lo + hi));
            if j[1] > 0.0 && j[2] < 0.0 && c * j[2] - kappa * j[1] > 0.0 {
                stretches.push(Stretch {
                    lo,
                    hi,
                    seg,
                    hi_cut: w[1].1,
                });
            }
        }
    }
    let mut comps: Vec<Vec<Stretch>> = Vec::new();
    for s in stretches {
        match comps.last_mut() {
            Some(comp) if comp.last().is_some_and(|p| s.lo - p.hi <= 1e-14) => comp.push(s),
            _ => comps.push(vec![s]),
        }
    }
    // A component ending at phase 1 continues into one starting at phase 0.
    if comps.len() > 1 {
        let first_starts_at_zero = comps[0][0].lo == 0.0;
        let last_ends_at_one = comps
            .last()
            .and_then(|c| c.last())
            .is_some_and(|s| s.hi >= 1.0);
        if first_starts_at_zero && last_ends_at_one {
            let first = comps.remove(0);
            if let Some(c) = comps.last_mut() {
                c.extend(first);
            }
        }
    }
    comps
}

/// The phase on a component where α F'(t̂) = c, i.e. F'(t̂) = c/α (F' decreases along
/// the component).
fn phase_on(comp: &[Stretch], target: f64) -> Option<f64> {
    for s in comp {
        let g = |t: f64| s.seg.jet(t)[1] - target;
        let (glo, ghi) = (g(s.lo), g(s.hi));
        if glo >= 0.0 && ghi <= 0.0 {
            return bracketed_root(&g, s.lo, s.hi).map(wrap_phase);
        }
    }
    None
}

/// Every α window of stability of the (1, k) solution for `table` and `r`, ordered by
/// birth. Bounded work: a few root isolations and at most a few dozen flights.
pub fn stability_windows(
    table: &Table,
    r: f64,
    k: u32,
) -> Result<Vec<StabilityWindow>, EngineError> {
    limits::R.check(r)?;
    check_k(k)?;
    let c = fixed_point_slope(r, k);
    let kappa = kappa_c(r);
    let mut sys = System::new(table.clone(), 1.0, r)?;
    let mut out = Vec::new();
    for comp in stable_components(table, c, kappa) {
        let (first, last) = (comp[0], comp[comp.len() - 1]);
        let df_lo = first.seg.jet(first.lo)[1];
        let df_hi = last.seg.jet(last.hi)[1];
        let alpha_lo = c / df_lo;
        if !(alpha_lo > 0.0 && alpha_lo <= MAX_ALPHA) {
            continue;
        }
        let (mut alpha_hi, mut end) = match last.hi_cut {
            Cut::PdRoot => (c / df_hi, WindowEnd::PeriodDoubling),
            Cut::DdfZero => (c / df_hi, WindowEnd::Fold),
            Cut::DfZero => (f64::INFINITY, WindowEnd::AlphaLimit),
            Cut::SegEdge => (c / df_hi, WindowEnd::Breakpoint),
        };
        if alpha_hi.is_nan() || alpha_hi > MAX_ALPHA {
            alpha_hi = MAX_ALPHA;
            end = WindowEnd::AlphaLimit;
        }
        // Admissibility along the window, sampled, with bisection where it changes.
        let admissible_at = |sys: &mut System, alpha: f64| -> bool {
            if sys.set_alpha(alpha).is_err() {
                return false;
            }
            match phase_on(&comp, c / alpha) {
                Some(t) => lands_after(sys, t, 0.5 * k as f64, k as f64).0,
                None => false,
            }
        };
        const SAMPLES: usize = 9;
        let span = alpha_hi - alpha_lo;
        let at = |i: usize| {
            let s = (i as f64 / (SAMPLES - 1) as f64).clamp(1e-9, 1.0 - 1e-9);
            alpha_lo + span * s
        };
        let oks: Vec<bool> = (0..SAMPLES)
            .map(|i| admissible_at(&mut sys, at(i)))
            .collect();
        let Some(i0) = oks.iter().position(|&b| b) else {
            continue;
        };
        // The admissible end of a bracket (good, bad) after 60 bisections.
        let mut boundary = |mut good: f64, mut bad: f64| {
            for _ in 0..60 {
                let mid = 0.5 * (bad + good);
                if admissible_at(&mut sys, mid) {
                    good = mid;
                } else {
                    bad = mid;
                }
            }
            good
        };
        let mut birth = alpha_lo;
        if i0 > 0 {
            birth = boundary(at(i0), at(i0 - 1));
        }
        if let Some(i1) = (i0..SAMPLES).find(|&i| !oks[i]) {
            alpha_hi = boundary(at(i1 - 1), at(i1));
            end = WindowEnd::Inadmissible;
        }
        let phase_birth = if i0 == 0 {
            wrap_phase(first.lo)
        } else {
            phase_on(&comp, c / birth).unwrap_or(first.lo)
        };
        let phase_end = match end {
            WindowEnd::Inadmissible | WindowEnd::AlphaLimit => {
                phase_on(&comp, c / alpha_hi).unwrap_or(last.hi)
            }
            _ => wrap_phase(last.hi),
        };
        out.push(StabilityWindow {
            k,
            alpha_birth: birth,
            phase_birth,
            alpha_end: alpha_hi,
            phase_end,
            end,
        });
    }
    out.sort_by(|a, b| a.alpha_birth.total_cmp(&b.alpha_birth));
    Ok(out)
}

/// The first stability window of the (1, k) solution (smallest birth α), if any.
pub fn stability_window(
    table: &Table,
    r: f64,
    k: u32,
) -> Result<Option<StabilityWindow>, EngineError> {
    Ok(stability_windows(table, r, k)?.into_iter().next())
}

/// Why no (1, k) solution of `table` at restitution `r` has a stability window, in
/// words for a refusal: where (1, k) solutions exist (from `from` on, up to α's limit)
/// and what each is there (phase, f'', classification), or that none exists. For
/// clients that start on the stable (1, k) solution and found no window.
pub fn without_window(table: &Table, r: f64, k: u32, from: f64) -> String {
    let c = fixed_point_slope(r, k);
    let at = |a: f64| {
        System::new(table.clone(), a, r)
            .ok()
            .and_then(|s| fixed_points(&s, k).ok())
            .unwrap_or_default()
    };
    let none = format!(
        "no (1, {k}) solution exists for alpha up to {} (one needs f'(t*) = {}, more than the table's slope reaches)",
        MAX_ALPHA,
        crate::error::fmt_value(c)
    );
    let from = from.clamp(1e-6, MAX_ALPHA);
    // Solutions exist from the α where α·max F' reaches c on (and on to the limit).
    let (a, points) = if !at(from).is_empty() {
        (from, at(from))
    } else if at(MAX_ALPHA).is_empty() {
        return none;
    } else {
        let (mut lo, mut hi) = (from, MAX_ALPHA);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if at(mid).is_empty() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (hi, at(hi))
    };
    let list: Vec<String> = points
        .iter()
        .map(|p| {
            format!(
                "phase {} with f'' = {} ({})",
                crate::error::fmt_value((p.phase * 1e6).round() / 1e6),
                crate::error::fmt_value((p.ddf * 1e4).round() / 1e4),
                p.classification.as_str()
            )
        })
        .collect();
    let shown = crate::error::fmt_value((a * 1e6).round() / 1e6);
    let since = if a > from {
        format!("(1, {k}) solutions exist only from alpha = {shown} on")
    } else {
        format!("at alpha = {shown} the (1, {k}) solutions are")
    };
    format!(
        "no (1, {k}) solution is stable at any alpha up to {MAX_ALPHA} (no stability window); {since}: {}",
        if a > from {
            format!("there, {}", list.join(" and "))
        } else {
            list.join(" and ")
        }
    )
}

/// The α (and phase) at which the solution that loses stability at the end of the first
/// stability window has f''(t̂*) = κ_c − Δκ, following the same branch (F' > 0,
/// F'' < 0) beyond α_PD for Δκ > 0. None if the window does not end by period doubling
/// or the branch ends first.
pub fn alpha_at_delta_kappa(
    table: &Table,
    r: f64,
    k: u32,
    delta_kappa: f64,
) -> Result<Option<(f64, f64)>, EngineError> {
    let Some(win) = stability_window(table, r, k)? else {
        return Ok(None);
    };
    if win.end != WindowEnd::PeriodDoubling {
        return Ok(None);
    }
    if delta_kappa == 0.0 {
        return Ok(Some((win.alpha_end, win.phase_end)));
    }
    let c = fixed_point_slope(r, k);
    let target = kappa_c(r) - delta_kappa;
    let pd = win.phase_end;
    let mut best: Option<(f64, f64, Segment)> = None;
    for seg in table.segments() {
        // Only the segment holding the period-doubling phase (approached from the left).
        let holds = (pd > seg.start && pd <= seg.end) || (pd == 0.0 && seg.start == 0.0);
        if !holds {
            continue;
        }
        for t in seg.roots(0.0, -target, c) {
            let j = seg.jet(t);
            if j[1] > 0.0 && j[2] < 0.0 {
                let d = (t - pd).abs();
                if best.is_none_or(|(bd, _, _)| d < bd) {
                    best = Some((d, t, seg));
                }
            }
        }
    }
    Ok(best.and_then(|(_, t, seg)| {
        let j = seg.jet(t);
        let alpha = c / j[1];
        (alpha > 0.0 && alpha <= MAX_ALPHA).then_some((alpha, wrap_phase(t)))
    }))
}
/// The velocity derivative of the (1, k) solution: f'(t̂*) = (k/2)(1 − r)/(1 + r).
pub fn fixed_point_slope(r: f64, k: u32) -> f64 {
    0.5 * k as f64 * (1.0 - r) / (1.0 + r)
}
