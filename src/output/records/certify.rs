//! Records of `certify`: the proof of one cycle (json), a row per impact of its box
//! (csv), and the words for its verdict, its failure and its stability, which the text
//! output prints and the json carries.

use super::*;
use bouncemap_engine::orbits::certify::{
    Certificate, CertifiedSpecial, Failure, FlightFailure, Multipliers, Near, SpecialFailure,
    SpecialKind, StabilityVerdict,
};
use bouncemap_engine::Interval;

/// An interval as [lo, hi].
pub fn pair(i: Interval) -> [f64; 2] {
    [i.lo(), i.hi()]
}

/// `proved` or `not_proved`.
pub fn verdict_name(c: &Certificate) -> &'static str {
    if c.proved() {
        "proved"
    } else {
        "not_proved"
    }
}

/// The failure's name in every format.
pub fn failure_name(f: &Failure) -> &'static str {
    match f {
        Failure::NoCycle(_) => "no_cycle",
        Failure::FarFromGuess { .. } => "far_from_guess",
        Failure::Breakpoint { .. } => "breakpoint",
        Failure::NotContracting { .. } => "enclosure_too_wide",
        Failure::Flight { why, .. } => match why {
            FlightFailure::NotLaunched { .. } => "not_launched",
            FlightFailure::GrazingLanding { .. } => "grazing_landing",
            FlightFailure::NoFlight => "no_flight",
            FlightFailure::Close { .. } => "near_grazing",
            FlightFailure::EarlierContact { .. } => "earlier_contact",
        },
    }
}

/// Why the cycle is not proved, for people (one line).
pub fn failure_text(c: &Certificate, f: &Failure) -> String {
    let (n, k) = (c.n, c.k);
    match f {
        Failure::NoCycle(e) => format!(
            "Newton's method finds no ({n}, {k}) cycle of the map from the guess ({})",
            e.as_str()
        ),
        Failure::FarFromGuess { phase, v, distance } => format!(
            "the ({n}, {k}) cycle Newton's method reaches lies at t̂0 = {phase}, v0 = {v}, {distance:.3} from the guess (more than {}): not the cycle pointed at; `--t0 {phase} --v0 {v}` certifies that one",
            bouncemap_engine::orbits::certify::GUESS_DISTANCE
        ),
        Failure::Breakpoint { impact, phase } => format!(
            "impact {impact}'s box (0 is the launch's) reaches the table's breakpoint at phase {phase:.12}, where f'' jumps (a border collision is near)"
        ),
        Failure::NotContracting { width } => format!(
            "enclosure too wide: the Krawczyk operator maps no box up to a relative half-width of 1e-9 into itself (its image is {width:.2e} wide): a fold (multiplier +1) near, or a cycle too unstable for double precision"
        ),
        Failure::Flight { flight, why } => {
            let i = *flight;
            match why {
                FlightFailure::NotLaunched { w } => format!(
                    "the launch after impact {i} is not shown to leave the table (relative velocity up to {w:.3e})"
                ),
                FlightFailure::GrazingLanding { speed } => format!(
                    "the flight after impact {i} lands with relative velocity not shown below zero (|u| down to {speed:.3e}): a grazing landing"
                ),
                FlightFailure::NoFlight => format!(
                    "the flight after impact {i} is not shown to take a positive time"
                ),
                FlightFailure::Close { tau, height } => format!(
                    "the flight after impact {i} comes within {height:.2e} of the table {tau:.12} after its launch: near grazing, positivity of the gap cannot be shown there"
                ),
                FlightFailure::EarlierContact { tau } => format!(
                    "the flight after impact {i} is at or below the table {tau:.12} after its launch, before its landing: the solution of the cycle's equations is not an orbit of the map"
                ),
            }
        }
    }
}

/// `stable`, `unstable` or `undecided`.
pub fn stability_name(v: &StabilityVerdict) -> &'static str {
    match v {
        StabilityVerdict::Stable => "stable",
        StabilityVerdict::Unstable => "unstable",
        StabilityVerdict::Undecided { .. } => "undecided",
    }
}

/// `period_doubling` or `fold`.
pub fn near_name(n: Near) -> &'static str {
    match n {
        Near::PeriodDoubling => "period_doubling",
        Near::Fold => "fold",
    }
}

/// The multipliers' enclosures in json.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum MultipliersRecord {
    /// Two real multipliers, the larger first.
    Real { values: [[f64; 2]; 2] },
    /// re ± i·im.
    Complex { re: [f64; 2], im: [f64; 2] },
    /// Both within re ± spread (real or complex not decided).
    Unresolved { re: [f64; 2], spread: f64 },
}

impl From<Multipliers> for MultipliersRecord {
    fn from(m: Multipliers) -> Self {
        match m {
            Multipliers::Real(ls) => MultipliersRecord::Real {
                values: ls.map(pair),
            },
            Multipliers::Complex { re, im } => MultipliersRecord::Complex {
                re: pair(re),
                im: pair(im),
            },
            Multipliers::Unresolved { re, spread } => MultipliersRecord::Unresolved {
                re: pair(re),
                spread,
            },
        }
    }
}

/// The stability part of the json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StabilityRecord {
    pub verdict: &'static str,
    /// What keeps an undecided verdict open: `period_doubling` or `fold`.
    pub near: Option<&'static str>,
    pub trace: [f64; 2],
    pub det: [f64; 2],
    /// 1 + tr M + det M and 1 − tr M + det M (both positive: stable).
    pub pd_test: [f64; 2],
    pub fold_test: [f64; 2],
    pub multipliers: MultipliersRecord,
}

/// The box in json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoxRecord {
    pub phases: Vec<[f64; 2]>,
    pub velocities: Vec<[f64; 2]>,
    /// Whole periods from the first impact to each.
    pub periods: Vec<i64>,
    /// |u| at each landing (the landing after impact i is impact i + 1).
    pub impact_speeds: Vec<[f64; 2]>,
    pub inflation: f64,
    pub width: f64,
}

/// `certify --format json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CertifyDoc<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub n: usize,
    pub k: u32,
    /// The enclosures of α and r the statement holds for (the decimals as written and
    /// their doubles).
    pub alpha_enclosure: [f64; 2],
    pub r_enclosure: [f64; 2],
    /// The launch (t̂0, v0) Newton's method started from.
    pub guess: [f64; 2],
    pub verdict: &'static str,
    pub reason: Option<&'static str>,
    pub message: Option<String>,
    /// Newton's f64 solution: launch phases and velocities.
    pub cycle: Option<SolutionRecord>,
    #[serde(rename = "box")]
    pub enclosure: Option<BoxRecord>,
    pub stability: Option<StabilityRecord>,
}

/// Newton's solution in json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolutionRecord {
    pub phases: Vec<f64>,
    pub velocities: Vec<f64>,
}

impl<'a> CertifyDoc<'a> {
    pub fn of(table: &'a str, alpha: f64, r: f64, guess: [f64; 2], c: &Certificate) -> Self {
        CertifyDoc {
            table,
            alpha,
            r,
            n: c.n,
            k: c.k,
            alpha_enclosure: pair(c.alpha),
            r_enclosure: pair(c.r),
            guess,
            verdict: verdict_name(c),
            reason: c.failure.as_ref().map(failure_name),
            message: c.failure.as_ref().map(|f| failure_text(c, f)),
            cycle: c.cycle.as_ref().map(|p| SolutionRecord {
                phases: p.phases.clone(),
                velocities: p.velocities.clone(),
            }),
            enclosure: c.enclosure.as_ref().map(|e| BoxRecord {
                phases: e.phases.iter().copied().map(pair).collect(),
                velocities: e.velocities.iter().copied().map(pair).collect(),
                periods: e.periods.clone(),
                impact_speeds: c.flights.iter().map(|f| pair(f.impact_speed)).collect(),
                inflation: e.inflation,
                width: e.width,
            }),
            stability: c.stability.map(|s| StabilityRecord {
                verdict: stability_name(&s.verdict),
                near: match s.verdict {
                    StabilityVerdict::Undecided { near } => Some(near_name(near)),
                    _ => None,
                },
                trace: pair(s.trace),
                det: pair(s.det),
                pd_test: pair(s.pd_test()),
                fold_test: pair(s.fold_test()),
                multipliers: s.multipliers.into(),
            }),
        }
    }
}

/// One csv row of `certify`: an impact of the box, 0 the launch's (one row without
/// impact fields when there is no box).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CertifyRow<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub n: usize,
    pub k: u32,
    pub verdict: &'static str,
    pub reason: Option<&'static str>,
    pub stability: Option<&'static str>,
    pub impact: Option<usize>,
    pub phase_lo: Option<f64>,
    pub phase_hi: Option<f64>,
    pub v_lo: Option<f64>,
    pub v_hi: Option<f64>,
    pub impact_speed_lo: Option<f64>,
    pub impact_speed_hi: Option<f64>,
}

impl<'a> CertifyRow<'a> {
    pub const HEADER: [&'static str; 15] = [
        "table",
        "alpha",
        "r",
        "n",
        "k",
        "verdict",
        "reason",
        "stability",
        "impact",
        "phase_lo",
        "phase_hi",
        "v_lo",
        "v_hi",
        "impact_speed_lo",
        "impact_speed_hi",
    ];

    pub fn rows(table: &'a str, alpha: f64, r: f64, c: &Certificate) -> Vec<CertifyRow<'a>> {
        let base = CertifyRow {
            table,
            alpha,
            r,
            n: c.n,
            k: c.k,
            verdict: verdict_name(c),
            reason: c.failure.as_ref().map(failure_name),
            stability: c.stability.map(|s| stability_name(&s.verdict)),
            impact: None,
            phase_lo: None,
            phase_hi: None,
            v_lo: None,
            v_hi: None,
            impact_speed_lo: None,
            impact_speed_hi: None,
        };
        let Some(e) = &c.enclosure else {
            return vec![base];
        };
        (0..c.n)
            .map(|i| CertifyRow {
                impact: Some(i),
                phase_lo: Some(e.phases[i].lo()),
                phase_hi: Some(e.phases[i].hi()),
                v_lo: Some(e.velocities[i].lo()),
                v_hi: Some(e.velocities[i].hi()),
                impact_speed_lo: c.flights.get(i).map(|f| f.impact_speed.lo()),
                impact_speed_hi: c.flights.get(i).map(|f| f.impact_speed.hi()),
                ..base.clone()
            })
            .collect()
    }
}

/// `proved` or `not_proved`, of a special point.
pub fn special_verdict_name(s: &CertifiedSpecial) -> &'static str {
    if s.proved() {
        "proved"
    } else {
        "not_proved"
    }
}

/// Why a special point is not proved, in every format.
pub fn special_failure_name(f: &SpecialFailure) -> &'static str {
    match f {
        SpecialFailure::NoBracket => "no_bracket",
        SpecialFailure::Cycle(f) => failure_name(f),
        SpecialFailure::EndsUndecided => "ends_undecided",
        SpecialFailure::NoBreakpoint => "no_breakpoint",
    }
}

/// A proved special point or why not, for people (one line, without the α name).
pub fn special_text(s: &CertifiedSpecial) -> String {
    let (n, k) = (s.n, s.k);
    let what = match s.kind {
        SpecialKind::PeriodDoubling => format!(
            "period doubling of the ({n}, {k}) cycle (1 + tr M + det M of opposite signs at the ends: a multiplier −1 between)"
        ),
        SpecialKind::Fold => format!(
            "fold of the ({n}, {k}) cycle (1 − tr M + det M of opposite signs along the branch: a multiplier +1 between; α over that stretch)"
        ),
        SpecialKind::BorderCollision { impact, breakpoint } => format!(
            "border collision of the ({n}, {k}) cycle's impact {impact} with the breakpoint at phase {} (its phase on opposite sides at the ends)",
            crate::output::text::shortest(breakpoint)
        ),
    };
    match (&s.failure, s.alpha) {
        (None, Some(a)) => format!(
            "in [{}, {}] (width {:.1e}): {what}",
            crate::output::text::shortest(a.lo()),
            crate::output::text::shortest(a.hi()),
            a.width()
        ),
        (Some(f), _) => format!(
            "not proved ({}): {}",
            special_failure_name(f),
            match f {
                SpecialFailure::NoBracket =>
                    "proofs within 1e-5 of the point do not give the condition opposite signs"
                        .to_string(),
                SpecialFailure::Cycle(_) => "the cycle is not proved over the interval".to_string(),
                SpecialFailure::EndsUndecided =>
                    "the condition's sign at the interval's ends is not decided".to_string(),
                SpecialFailure::NoBreakpoint => "no breakpoint of the table there".to_string(),
            }
        ),
        (None, None) => "not proved".to_string(),
    }
}

/// `continue --certify`: the proofs of one branch, beside it.
#[derive(Clone, Debug)]
pub struct BranchProofs {
    /// One per point, in the branch's order.
    pub points: Vec<Certificate>,
    /// Of its begin, its special points and its end (None: no proof of that kind).
    pub begin: Option<CertifiedSpecial>,
    pub specials: Vec<Option<CertifiedSpecial>>,
    pub end: Option<CertifiedSpecial>,
}

/// A point's proof in json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointProofRecord {
    pub verdict: &'static str,
    pub reason: Option<&'static str>,
    /// `stable`, `unstable` or `undecided` (null when not proved).
    pub stability: Option<&'static str>,
    pub width: Option<f64>,
}

impl PointProofRecord {
    pub fn of(c: &Certificate) -> Self {
        PointProofRecord {
            verdict: verdict_name(c),
            reason: c.failure.as_ref().map(failure_name),
            stability: c.stability.map(|s| stability_name(&s.verdict)),
            width: c.enclosure.as_ref().map(|e| e.width),
        }
    }
}

/// A special point's proof in json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpecialProofRecord {
    pub verdict: &'static str,
    pub reason: Option<&'static str>,
    /// The α-interval [lo, hi] holding the point.
    pub alpha: Option<[f64; 2]>,
}

impl SpecialProofRecord {
    pub fn of(s: &CertifiedSpecial) -> Self {
        SpecialProofRecord {
            verdict: special_verdict_name(s),
            reason: s.failure.as_ref().map(special_failure_name),
            alpha: s.alpha.map(pair),
        }
    }
}
