//! Records of `continue` (branches of periodic orbits) and `cascade` (period-doubling
//! points, how each 2ⁿ branch ends, one row per D of a family).

use super::{
    failure_name, special_failure_name, special_verdict_name, stability_name, verdict_name,
    BranchProofs, ComplexRecord, PointProofRecord, SpecialProofRecord,
};
use bouncemap_engine::orbits::cascade::Cascade;
use bouncemap_engine::orbits::certify::Certificate;
use bouncemap_engine::orbits::certify::CertifiedSpecial;
use bouncemap_engine::orbits::continuation::{Branch, Special};
use bouncemap_engine::orbits::periodic::CyclePoint;
use serde::Serialize;

/// Feigenbaum's δ, for comparison in outputs.
pub const FEIGENBAUM_DELTA: f64 = 4.669_201_609_102_99;

/// Numbers joined by ';' (a cycle's phases or velocities in one csv field).
fn joined(v: &[f64]) -> String {
    v.iter().map(f64::to_string).collect::<Vec<_>>().join(";")
}

/// A special point: PD, fold, border collision, grazing, window exit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpecialRecord {
    pub kind: &'static str,
    pub label: &'static str,
    pub alpha: f64,
    pub phase: f64,
    /// The impact of the cycle concerned (0 = the launch's).
    pub impact: usize,
    /// At a border collision: whether the cycle goes on beyond it stable (true),
    /// unstable (false), or ceases to exist (null).
    pub persists: Option<bool>,
    /// At a border collision: what happens (`persists_stable`, `persists_unstable`,
    /// `border_fold`, `doubling_stable`, `doubling_unstable`).
    pub crossing: Option<&'static str>,
    /// At a border collision: the multipliers with f'' of the side the branch came
    /// from, and of the other side.
    pub multipliers_near: Option<[ComplexRecord; 2]>,
    pub multipliers_far: Option<[ComplexRecord; 2]>,
    /// How far the point's defining condition is from holding there: |μ + 1| at a
    /// period doubling, |μ − 1| at a fold, the impact's phase distance from the
    /// breakpoint at a border collision.
    pub condition_error: Option<f64>,
    /// Where the branch was lost: the last arclength step tried.
    pub last_step: Option<f64>,
    pub stable: bool,
    pub multipliers: [ComplexRecord; 2],
    /// With `--certify`: the point proved as an α-interval, or why not (null for kinds
    /// no proof is made of, and without `--certify`).
    pub proof: Option<SpecialProofRecord>,
}

impl SpecialRecord {
    fn new(s: &Special, proof: Option<&CertifiedSpecial>) -> Self {
        SpecialRecord {
            kind: s.kind.as_str(),
            label: s.kind.label(),
            alpha: s.alpha,
            phase: s.phase,
            impact: s.impact,
            persists: s.persists(),
            crossing: s.collision.map(|c| c.crossing.as_str()),
            multipliers_near: s.collision.map(|c| c.near.map(ComplexRecord::from)),
            multipliers_far: s.collision.map(|c| c.far.map(ComplexRecord::from)),
            condition_error: s.condition_error(),
            last_step: s.last_step,
            stable: s.point.stable,
            multipliers: s.point.multipliers.map(ComplexRecord::from),
            proof: proof.map(SpecialProofRecord::of),
        }
    }
}

/// One point of a branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointRecord {
    pub alpha: f64,
    pub stable: bool,
    pub multipliers: [ComplexRecord; 2],
    pub phases: Vec<f64>,
    pub velocities: Vec<f64>,
    pub return_error: f64,
    /// With `--certify`: the point's proof.
    pub proof: Option<PointProofRecord>,
}

impl PointRecord {
    fn new(p: &CyclePoint, proof: Option<&Certificate>) -> Self {
        PointRecord {
            alpha: p.alpha,
            stable: p.stable,
            multipliers: p.multipliers.map(ComplexRecord::from),
            phases: p.phases.clone(),
            velocities: p.velocities.clone(),
            return_error: p.return_error,
            proof: proof.map(PointProofRecord::of),
        }
    }
}

/// One branch, in `continue --format json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchRecord {
    pub index: usize,
    pub n: usize,
    pub k: u32,
    pub parent: Option<usize>,
    pub begin: SpecialRecord,
    pub end: SpecialRecord,
    pub specials: Vec<SpecialRecord>,
    pub points: Vec<PointRecord>,
}

impl BranchRecord {
    /// Branch `index`, with its proofs if they were made.
    pub fn new(index: usize, b: &Branch, proofs: Option<&BranchProofs>) -> Self {
        BranchRecord {
            index,
            n: b.n,
            k: b.k,
            parent: b.parent,
            begin: SpecialRecord::new(&b.begin, proofs.and_then(|p| p.begin.as_ref())),
            end: SpecialRecord::new(&b.end, proofs.and_then(|p| p.end.as_ref())),
            specials: b
                .specials
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    SpecialRecord::new(s, proofs.and_then(|p| p.specials.get(i)?.as_ref()))
                })
                .collect(),
            points: b
                .points
                .iter()
                .enumerate()
                .map(|(i, p)| PointRecord::new(p, proofs.and_then(|q| q.points.get(i))))
                .collect(),
        }
    }
}

/// `continue --format json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContinueDoc<'a> {
    pub table: &'a str,
    pub r: f64,
    pub alpha_lo: f64,
    pub alpha_hi: f64,
    pub start: String,
    pub found: bool,
    pub reason: Option<String>,
    pub branches: Vec<BranchRecord>,
}

/// `continue --format csv`: one row per point (`record` = point) and per special point
/// (`record` = its kind; begin and end included), in branch order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContinueRow {
    pub branch: usize,
    pub n: usize,
    pub k: u32,
    pub parent: Option<usize>,
    pub record: &'static str,
    pub alpha: f64,
    pub phase: Option<f64>,
    pub impact: Option<usize>,
    pub persists: Option<bool>,
    pub crossing: Option<&'static str>,
    pub condition_error: Option<f64>,
    pub stable: bool,
    pub lambda1_re: f64,
    pub lambda1_im: f64,
    pub lambda2_re: f64,
    pub lambda2_im: f64,
    pub return_error: f64,
    pub phases: String,
    pub velocities: String,
    /// With `--certify`: `proved` or `not_proved`, why not, a point's proved stability,
    /// and a special point's α-interval.
    pub proof: Option<&'static str>,
    pub proof_reason: Option<&'static str>,
    pub proved_stability: Option<&'static str>,
    pub alpha_lo: Option<f64>,
    pub alpha_hi: Option<f64>,
}

impl ContinueRow {
    pub const HEADER: [&'static str; 24] = [
        "branch",
        "n",
        "k",
        "parent",
        "record",
        "alpha",
        "phase",
        "impact",
        "persists",
        "crossing",
        "condition_error",
        "stable",
        "lambda1_re",
        "lambda1_im",
        "lambda2_re",
        "lambda2_im",
        "return_error",
        "phases",
        "velocities",
        "proof",
        "proof_reason",
        "proved_stability",
        "alpha_lo",
        "alpha_hi",
    ];

    pub fn point(branch: usize, b: &Branch, p: &CyclePoint, proof: Option<&Certificate>) -> Self {
        let [l1, l2] = p.multipliers;
        ContinueRow {
            branch,
            n: b.n,
            k: b.k,
            parent: b.parent,
            record: "point",
            alpha: p.alpha,
            phase: None,
            impact: None,
            persists: None,
            crossing: None,
            condition_error: None,
            stable: p.stable,
            lambda1_re: l1.re,
            lambda1_im: l1.im,
            lambda2_re: l2.re,
            lambda2_im: l2.im,
            return_error: p.return_error,
            phases: joined(&p.phases),
            velocities: joined(&p.velocities),
            proof: proof.map(verdict_name),
            proof_reason: proof.and_then(|c| c.failure.as_ref()).map(failure_name),
            proved_stability: proof
                .and_then(|c| c.stability)
                .map(|s| stability_name(&s.verdict)),
            alpha_lo: None,
            alpha_hi: None,
        }
    }

    pub fn special(
        branch: usize,
        b: &Branch,
        s: &Special,
        proof: Option<&CertifiedSpecial>,
    ) -> Self {
        ContinueRow {
            record: s.kind.as_str(),
            alpha: s.alpha,
            phase: Some(s.phase),
            impact: Some(s.impact),
            persists: s.persists(),
            crossing: s.collision.map(|c| c.crossing.as_str()),
            condition_error: s.condition_error(),
            proof: proof.map(special_verdict_name),
            proof_reason: proof
                .and_then(|p| p.failure.as_ref())
                .map(special_failure_name),
            proved_stability: None,
            alpha_lo: proof.and_then(|p| p.alpha).map(|a| a.lo()),
            alpha_hi: proof.and_then(|p| p.alpha).map(|a| a.hi()),
            ..ContinueRow::point(branch, b, &s.point, None)
        }
    }
}

/// One 2ⁿ branch of a cascade: a json level and a csv row alike (`delta` is δ at the
/// αₙ where it ends by period doubling, where defined).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LevelRecord {
    pub period: usize,
    pub alpha_start: f64,
    pub end: &'static str,
    pub alpha_end: f64,
    pub phase: f64,
    pub impact: usize,
    pub persists: Option<bool>,
    /// At a border collision: what happens there (see `SpecialRecord::crossing`).
    pub crossing: Option<&'static str>,
    pub delta: Option<f64>,
    /// With `--certify`: `proved` or `not_proved` (empty where nothing was proved of
    /// this kind of end, or without `--certify`), the α-interval, and why not.
    pub proof: Option<&'static str>,
    pub alpha_lo: Option<f64>,
    pub alpha_hi: Option<f64>,
    pub proof_reason: Option<&'static str>,
}

impl LevelRecord {
    /// The csv header, in the fields' order.
    pub const HEADER: [&'static str; 13] = [
        "period",
        "alpha_start",
        "end",
        "alpha_end",
        "phase",
        "impact",
        "persists",
        "crossing",
        "delta",
        "proof",
        "alpha_lo",
        "alpha_hi",
        "proof_reason",
    ];

    /// Level `i` of the cascade (δ at αᵢ₊₁ is δ index i − 1), with the proof of its
    /// end if one was made.
    pub fn new(c: &Cascade, i: usize, proof: Option<&CertifiedSpecial>) -> Self {
        let l = &c.levels[i];
        LevelRecord {
            period: l.period,
            alpha_start: l.alpha_start,
            end: l.end.kind.as_str(),
            alpha_end: l.end.alpha,
            phase: l.end.phase,
            impact: l.end.impact,
            persists: l.end.persists(),
            crossing: l.end.collision.map(|c| c.crossing.as_str()),
            delta: i.checked_sub(1).and_then(|j| c.deltas.get(j)).copied(),
            proof: proof.map(special_verdict_name),
            alpha_lo: proof.and_then(|p| p.alpha).map(|a| a.lo()),
            alpha_hi: proof.and_then(|p| p.alpha).map(|a| a.hi()),
            proof_reason: proof
                .and_then(|p| p.failure.as_ref())
                .map(special_failure_name),
        }
    }
}

/// `cascade --format json` (one table).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CascadeDoc<'a> {
    pub table: &'a str,
    pub r: f64,
    pub k: u32,
    pub depth: usize,
    pub found: bool,
    pub reason: Option<String>,
    pub alphas: Vec<f64>,
    pub deltas: Vec<f64>,
    /// The last ratio δₙ and its uncertainty |δₙ − δₙ₋₁|.
    pub delta_estimate: Option<f64>,
    pub delta_uncertainty: Option<f64>,
    pub feigenbaum_delta: f64,
    pub levels: Vec<LevelRecord>,
    /// Why the cascade stops at its last αₙ with no doubled branch, if it does.
    pub unborn: Option<String>,
}

/// One D of `cascade --d`: how far the cascade goes and how it is interrupted.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilyRecord {
    pub d: f64,
    pub found: bool,
    pub reason: Option<String>,
    /// The longest period followed.
    pub max_period: usize,
    /// The end of the first branch not ending by period doubling: its period, kind,
    /// α, phase, impact, persistence (none if every branch up to the depth doubled);
    /// `not_born` with the doubled period and αₙ where a degenerate period doubling
    /// starts no doubled branch.
    pub ends_period: Option<usize>,
    pub ends_by: Option<&'static str>,
    pub alpha_end: Option<f64>,
    pub phase: Option<f64>,
    pub impact: Option<usize>,
    pub persists: Option<bool>,
    pub alphas: Vec<f64>,
    pub deltas: Vec<f64>,
}

impl FamilyRecord {
    pub fn new(d: f64, c: Result<&Cascade, String>) -> Self {
        let empty = FamilyRecord {
            d,
            found: false,
            reason: None,
            max_period: 0,
            ends_period: None,
            ends_by: None,
            alpha_end: None,
            phase: None,
            impact: None,
            persists: None,
            alphas: Vec::new(),
            deltas: Vec::new(),
        };
        match c {
            Err(reason) => FamilyRecord {
                reason: Some(reason),
                ..empty
            },
            Ok(c) => {
                let i = c.interrupted();
                let last = c.levels.last();
                // No doubled branch born at the last αₙ: the cascade ends there.
                let unborn = (i.is_none() && c.unborn.is_some()).then(|| {
                    (
                        2 * last.map_or(1, |l| l.period),
                        "not_born",
                        last.map(|l| l.end.alpha),
                    )
                });
                FamilyRecord {
                    found: true,
                    max_period: last.map_or(0, |l| l.period),
                    ends_period: i.map(|l| l.period).or(unborn.map(|u| u.0)),
                    ends_by: i.map(|l| l.end.kind.as_str()).or(unborn.map(|u| u.1)),
                    alpha_end: i.map(|l| l.end.alpha).or(unborn.and_then(|u| u.2)),
                    phase: i.map(|l| l.end.phase),
                    impact: i.map(|l| l.end.impact),
                    persists: i.and_then(|l| l.end.persists()),
                    alphas: c.alphas.clone(),
                    deltas: c.deltas.clone(),
                    ..empty
                }
            }
        }
    }
}

/// `cascade --d --format csv`: a [`FamilyRecord`] with αₙ and δₙ joined by ';'.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilyRow {
    pub d: f64,
    pub found: bool,
    pub max_period: usize,
    pub ends_period: Option<usize>,
    pub ends_by: Option<&'static str>,
    pub alpha_end: Option<f64>,
    pub phase: Option<f64>,
    pub impact: Option<usize>,
    pub persists: Option<bool>,
    pub alphas: String,
    pub deltas: String,
    pub reason: Option<String>,
}

impl FamilyRow {
    pub const HEADER: [&'static str; 12] = [
        "d",
        "found",
        "max_period",
        "ends_period",
        "ends_by",
        "alpha_end",
        "phase",
        "impact",
        "persists",
        "alphas",
        "deltas",
        "reason",
    ];
}

impl From<&FamilyRecord> for FamilyRow {
    fn from(f: &FamilyRecord) -> Self {
        FamilyRow {
            d: f.d,
            found: f.found,
            max_period: f.max_period,
            ends_period: f.ends_period,
            ends_by: f.ends_by,
            alpha_end: f.alpha_end,
            phase: f.phase,
            impact: f.impact,
            persists: f.persists,
            alphas: joined(&f.alphas),
            deltas: joined(&f.deltas),
            reason: f.reason.clone(),
        }
    }
}

/// `cascade --d --format json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilyDoc {
    pub r: f64,
    pub k: u32,
    pub depth: usize,
    pub rows: Vec<FamilyRecord>,
}
