//! Records of `attractors`: attractors followed along α (csv rows and the json
//! document), and the words for a member and a change that the text report uses too.

use super::*;
use bouncemap_engine::attractors::crisis::{Located, Sighting};
use bouncemap_engine::attractors::global::{Cause, Change, ChangeKind, Continuation, Join, Step};

pub use bouncemap_figures::global::{cause_text, describe_member};

/// What a change was from and to, for people (None for births and deaths).
pub fn change_ends(what: &ChangeKind) -> Option<(String, String)> {
    match what {
        ChangeKind::Period { from, to } => Some((
            format!("({}, {})", from.0, from.1),
            format!("({}, {})", to.0, to.1),
        )),
        ChangeKind::Kind { from, to } => Some((from.as_str().into(), to.as_str().into())),
        ChangeKind::Birth | ChangeKind::Death { .. } => None,
    }
}

/// The track a death's points went to (attractor number, 1-based).
fn into(what: &ChangeKind) -> Option<usize> {
    match what {
        ChangeKind::Death { into } => into.map(|t| t + 1),
        _ => None,
    }
}

/// The basin statistics of one α, shared by its csv rows and its json value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepStatistics {
    /// Share of the starts not run to an attractor.
    pub not_settled: f64,
    /// S_b and S_bb (natural logarithm), boxes of 5 × 5 starts.
    pub basin_entropy: Option<f64>,
    pub boundary_entropy: Option<f64>,
    /// S_bb > ln 2: the boundary is fractal (a sufficient condition).
    pub fractal: Option<bool>,
    /// The uncertainty exponent of the boundary and its standard error.
    pub uncertainty_exponent: Option<f64>,
    pub uncertainty_error: Option<f64>,
}

impl StepStatistics {
    pub fn of(step: &Step) -> StepStatistics {
        let u = step.uncertainty.as_ref().ok();
        StepStatistics {
            not_settled: step.not_settled_fraction(),
            basin_entropy: step.entropy.map(|e| e.s_b),
            boundary_entropy: step.entropy.map(|e| e.s_bb),
            fractal: step.entropy.map(|e| e.fractal_by_log2()),
            uncertainty_exponent: u.map(|u| u.exponent),
            uncertainty_error: u.map(|u| u.error),
        }
    }
}

/// One csv row of `attractors`: an attractor at one α (or, with `change` death or
/// merge, the α where it is gone), with that α's statistics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AttractorsRow {
    pub alpha: f64,
    /// 1, 2, …: in order of appearance along α.
    pub attractor: usize,
    /// Empty on a death's row.
    pub kind: Option<&'static str>,
    pub events: Option<usize>,
    pub periods: Option<i64>,
    pub resolved: Option<bool>,
    pub phase: Option<f64>,
    pub v: Option<f64>,
    pub lyapunov: Exponent,
    pub starts: usize,
    pub fraction: f64,
    /// What changed between the previous α and this one: birth, death, merge, period,
    /// sticking, kind (several joined by `+`).
    pub change: Option<String>,
    /// For a merge: the attractor its points now go to.
    pub into: Option<usize>,
    /// For a birth or a death: what became of its cycle at the other α (unstable,
    /// gone, missed, crisis, untested).
    pub cause: Option<&'static str>,
    /// The α's statistics ([`StepStatistics`], written out: csv has no nesting).
    pub not_settled: f64,
    pub basin_entropy: Option<f64>,
    pub boundary_entropy: Option<f64>,
    pub fractal: Option<bool>,
    pub uncertainty_exponent: Option<f64>,
    pub uncertainty_error: Option<f64>,
}

impl AttractorsRow {
    pub const HEADER: [&'static str; 20] = [
        "alpha",
        "attractor",
        "kind",
        "events",
        "periods",
        "resolved",
        "phase",
        "v",
        "lyapunov",
        "starts",
        "fraction",
        "change",
        "into",
        "cause",
        "not_settled",
        "basin_entropy",
        "boundary_entropy",
        "fractal",
        "uncertainty_exponent",
        "uncertainty_error",
    ];

    /// The rows of α value `index`: its attractors, then the attractors gone at it.
    pub fn of_step(cont: &Continuation, index: usize) -> Vec<AttractorsRow> {
        let step = &cont.steps()[index];
        let s = StepStatistics::of(step);
        // A row of this α with its statistics and nothing else.
        let blank = AttractorsRow {
            alpha: step.alpha,
            attractor: 0,
            kind: None,
            events: None,
            periods: None,
            resolved: None,
            phase: None,
            v: None,
            lyapunov: Exponent(None),
            starts: 0,
            fraction: 0.0,
            change: None,
            into: None,
            cause: None,
            not_settled: s.not_settled,
            basin_entropy: s.basin_entropy,
            boundary_entropy: s.boundary_entropy,
            fractal: s.fractal,
            uncertainty_exponent: s.uncertainty_exponent,
            uncertainty_error: s.uncertainty_error,
        };
        let here: Vec<&Change> = cont.changes().iter().filter(|c| c.step == index).collect();
        let changes_of = |track: usize| {
            let names: Vec<&str> = here
                .iter()
                .filter(|c| c.track == track)
                .map(|c| c.what.name())
                .collect();
            (!names.is_empty()).then(|| names.join("+"))
        };
        let mut rows: Vec<AttractorsRow> = step
            .members
            .iter()
            .map(|m| {
                let r = AttractorRecord::new(
                    m.track + 1,
                    m.kind,
                    (m.events, m.periods),
                    m.point,
                    m.lyapunov,
                    m.fraction,
                    m.precision,
                );
                AttractorsRow {
                    alpha: step.alpha,
                    attractor: m.track + 1,
                    kind: Some(m.kind.as_str()),
                    events: r.events,
                    periods: r.periods,
                    resolved: r.resolved,
                    phase: r.phase,
                    v: r.v,
                    lyapunov: r.lyapunov,
                    starts: m.starts,
                    fraction: m.fraction,
                    change: changes_of(m.track),
                    cause: here
                        .iter()
                        .find(|c| c.track == m.track && c.what == ChangeKind::Birth)
                        .and_then(|c| c.cause.map(|x| x.name())),
                    ..blank.clone()
                }
            })
            .collect();
        for c in here
            .iter()
            .filter(|c| matches!(c.what, ChangeKind::Death { .. }))
        {
            rows.push(AttractorsRow {
                attractor: c.track + 1,
                change: Some(c.what.name().into()),
                into: into(&c.what),
                cause: c.cause.map(|x| x.name()),
                ..blank.clone()
            });
        }
        rows
    }
}

/// An attractor followed along α (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrackRecord {
    pub attractor: usize,
    /// The first and last α it is seen at.
    pub first_alpha: f64,
    pub last_alpha: f64,
    /// Its largest basin fraction.
    pub max_fraction: f64,
}

/// A change between two neighbouring α values (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChangeRecord {
    /// It happens between these two α values.
    pub between: [f64; 2],
    pub attractor: usize,
    /// birth, death, merge, period, sticking or kind.
    pub change: &'static str,
    /// For a merge: the attractor its points now go to.
    pub into: Option<usize>,
    /// For a change of period or kind: before and after.
    pub from: Option<String>,
    pub to: Option<String>,
    /// For a birth or a death: what became of its cycle at the other α (unstable,
    /// gone, missed, crisis, untested), and for `unstable` how (`period doubling`,
    /// `fold`, `torus`) and its largest multiplier there [re, im].
    pub cause: Option<&'static str>,
    pub bifurcation: Option<&'static str>,
    pub multiplier: Option<[f64; 2]>,
}

/// The uncertainty exponent's fit (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UncertaintyRecord {
    pub exponent: f64,
    pub error: f64,
    /// Starts counted at every scale.
    pub starts: usize,
    /// (ε, fraction of ε-uncertain starts): ε in grid steps (`grid`), or in table
    /// periods of t̂0 (`sampled`).
    pub fractions: Vec<(f64, f64)>,
    /// `grid` (neighbours on the grid) or `sampled` (sampled starts and displaced
    /// copies).
    pub method: &'static str,
}

/// One α value (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ValueRecord {
    pub alpha: f64,
    /// Points of the previous α's attractors run here.
    pub seeds: usize,
    #[serde(flatten)]
    pub statistics: StepStatistics,
    pub boundary_boxes: Option<usize>,
    pub uncertainty: Option<UncertaintyRecord>,
    /// Why there is no uncertainty exponent, where there is none.
    pub no_uncertainty: Option<&'static str>,
    pub attractors: Vec<AttractorRecord>,
}

/// `attractors`' json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AttractorsDoc<'a> {
    pub table: &'a str,
    pub r: f64,
    pub alpha: [f64; 2],
    pub steps: usize,
    pub grid: [usize; 2],
    pub w_max: f64,
    pub transient: u64,
    /// The matching threshold between neighbouring α values.
    pub match_distance: f64,
    pub tracks: Vec<TrackRecord>,
    pub changes: Vec<ChangeRecord>,
    pub values: Vec<ValueRecord>,
    /// Where the parts of a merged run were joined (absent for a run in one part).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub joins: Vec<JoinRecord>,
    /// With `--crises`: each crisis located (absent without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crises: Option<Vec<CrisisRecord>>,
}

/// A crisis located (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrisisRecord {
    /// The attractor destroyed, or jumping in size.
    pub attractor: usize,
    /// What the continuation saw: `destroyed` (gone with no local bifurcation, a
    /// boundary crisis) or `jump` (grown abruptly, going on: an interior crisis).
    pub seen: &'static str,
    /// For a jump: its ranges of launch velocities at the two values.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jump: Option<JumpRecord>,
    /// The two α values of the continuation it happens between.
    pub between: [f64; 2],
    /// The side of the cells of the attractor's neighbourhood it was located with.
    pub radius: Option<f64>,
    /// Whether it was located; if not, why.
    pub located: bool,
    pub reason: Option<String>,
    /// The bracket: every orbit stays `stayed_events` events at `lo`; at `hi` they leave
    /// after `left_after` events (null: stayed).
    pub lo: Option<f64>,
    pub hi: Option<f64>,
    pub stayed_events: Option<u64>,
    pub left_after: Vec<Option<u64>>,
    /// The kind of a leaving orbit's first event outside: impact or stick.
    pub left_by: Option<&'static str>,
    pub saddle: Option<CrisisSaddleRecord>,
}

/// A jump in size (json): the attractor's range of launch velocities [min, max] at
/// the two values, how far it grew and its drift between neighbouring values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JumpRecord {
    pub before: [f64; 2],
    pub after: [f64; 2],
    pub grows_by: f64,
    pub drift: f64,
}

/// The saddle of a crisis (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrisisSaddleRecord {
    pub n: usize,
    pub k: u32,
    /// Its impact phases and launch velocities at the upper end of the bracket.
    pub phases: Vec<f64>,
    pub velocities: Vec<f64>,
    /// Its multipliers [re, im].
    pub multipliers: [[f64; 2]; 2],
    /// The closest a leaving orbit came to it.
    pub passes: f64,
    /// How far it lies from the attractor's sample at the lower end.
    pub outside_by: f64,
    /// The least distance from the attractor's sample to the saddle's stable manifold:
    /// [[α, distance], …], lower α first.
    pub to_stable_manifold: Vec<[f64; 2]>,
    /// How it was chosen: null where it is the nearest the attractor outside it, else
    /// the first crossing of its stable manifold by the attractor's unstable manifold.
    pub tangency: Option<TangencyRecord>,
}

/// The tangency a crisis saddle was chosen by (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TangencyRecord {
    /// The saddle embedded in the attractor whose unstable manifold is grown: (n, k),
    /// impact phases and launch velocities at the lower end.
    pub embedded: EmbeddedRecord,
    /// The α bracket of the first crossing: apart below, crossed above.
    pub between: [f64; 2],
    /// The distance between the two manifolds at the crisis' lower end (null: over 0.02).
    pub apart: Option<f64>,
    /// Other saddles crossed first in the same bracket, [n, k] each.
    pub also: Vec<(usize, u32)>,
    /// Saddles tried, and of them those already crossed at the lower end.
    pub tried: usize,
    pub in_closure: usize,
}

/// A cycle named by its (n, k) and points (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EmbeddedRecord {
    pub n: usize,
    pub k: u32,
    pub phases: Vec<f64>,
    pub velocities: Vec<f64>,
}

impl CrisisRecord {
    pub fn of(cont: &Continuation, l: &Located) -> CrisisRecord {
        let steps = cont.steps();
        let between = [steps[l.step - 1].alpha, steps[l.step].alpha];
        let jump = match &l.sighting {
            Sighting::Jump(j) => Some(JumpRecord {
                before: [j.before.0, j.before.1],
                after: [j.after.0, j.after.1],
                grows_by: j.grows_by,
                drift: j.drift,
            }),
            Sighting::Destroyed { .. } => None,
        };
        match &l.result {
            Ok(x) => CrisisRecord {
                attractor: l.track + 1,
                seen: l.sighting.name(),
                jump,
                radius: Some(x.radius),
                between,
                located: true,
                reason: None,
                lo: Some(x.lo),
                hi: Some(x.hi),
                stayed_events: Some(x.stayed),
                left_after: x.left_after.clone(),
                left_by: Some(x.left_by.as_str()),
                saddle: x.saddle.as_ref().map(|s| CrisisSaddleRecord {
                    n: s.cycle.n,
                    k: s.cycle.k,
                    phases: s.cycle.phases.iter().map(|t| t.rem_euclid(1.0)).collect(),
                    velocities: s.cycle.velocities.clone(),
                    multipliers: s.cycle.multipliers.map(|z| [z.re, z.im]),
                    passes: s.passes,
                    outside_by: s.outside_by,
                    to_stable_manifold: s.to_stable_manifold.iter().map(|&(a, d)| [a, d]).collect(),
                    tangency: s.tangency.as_ref().map(|t| TangencyRecord {
                        embedded: EmbeddedRecord {
                            n: t.embedded.n,
                            k: t.embedded.k,
                            phases: t
                                .embedded
                                .phases
                                .iter()
                                .map(|p| p.rem_euclid(1.0))
                                .collect(),
                            velocities: t.embedded.velocities.clone(),
                        },
                        between: [t.between.0, t.between.1],
                        apart: t.apart,
                        also: t.also.clone(),
                        tried: t.tried,
                        in_closure: t.in_closure,
                    }),
                }),
            },
            Err(e) => CrisisRecord {
                attractor: l.track + 1,
                seen: l.sighting.name(),
                jump,
                radius: None,
                between,
                located: false,
                reason: Some(e.to_string()),
                lo: None,
                hi: None,
                stayed_events: None,
                left_after: Vec::new(),
                left_by: None,
                saddle: None,
            },
        }
    }
}

/// Where two parts of a merged run were joined (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JoinRecord {
    /// The α value both parts computed.
    pub alpha: f64,
    /// Attractors of the two pictures there matched to each other.
    pub matched: usize,
    /// Attractors only the earlier part's picture holds there (found by its seeds).
    pub only_before: usize,
    /// Attractors only the later part's picture holds there.
    pub only_after: usize,
    /// The largest difference of basin fraction between the two pictures.
    pub fraction_difference: f64,
}

impl<'a> AttractorsDoc<'a> {
    pub fn of(
        cont: &'a Continuation,
        joins: &[Join],
        crises: Option<&[Located]>,
    ) -> AttractorsDoc<'a> {
        use bouncemap_engine::attractors::global::MATCH_DISTANCE;
        let spec = cont.spec();
        let steps = cont.steps();
        let tracks = cont
            .tracks()
            .iter()
            .map(|t| TrackRecord {
                attractor: t.id + 1,
                first_alpha: steps[t.first].alpha,
                last_alpha: steps[t.last].alpha,
                max_fraction: steps[t.first..=t.last]
                    .iter()
                    .flat_map(|s| s.members.iter().filter(|m| m.track == t.id))
                    .map(|m| m.fraction)
                    .fold(0.0, f64::max),
            })
            .collect();
        let changes = cont
            .changes()
            .iter()
            .map(|c| {
                let ends = change_ends(&c.what);
                ChangeRecord {
                    between: [steps[c.step - 1].alpha, steps[c.step].alpha],
                    attractor: c.track + 1,
                    change: c.what.name(),
                    into: into(&c.what),
                    from: ends.as_ref().map(|e| e.0.clone()),
                    to: ends.map(|e| e.1),
                    cause: c.cause.map(|x| x.name()),
                    bifurcation: match c.cause {
                        Some(Cause::Unstable { at, .. }) => Some(at),
                        _ => None,
                    },
                    multiplier: match c.cause {
                        Some(Cause::Unstable { multiplier, .. }) => {
                            Some([multiplier.re, multiplier.im])
                        }
                        _ => None,
                    },
                }
            })
            .collect();
        let values = steps
            .iter()
            .map(|s| ValueRecord {
                alpha: s.alpha,
                seeds: s.seeds,
                statistics: StepStatistics::of(s),
                boundary_boxes: s.entropy.map(|e| e.boundary_boxes),
                uncertainty: s.uncertainty.as_ref().ok().map(|u| UncertaintyRecord {
                    exponent: u.exponent,
                    error: u.error,
                    starts: u.starts,
                    fractions: u.fractions.clone(),
                    method: if s.sampled { "sampled" } else { "grid" },
                }),
                no_uncertainty: s.uncertainty.as_ref().err().map(|e| e.as_str()),
                attractors: s
                    .members
                    .iter()
                    .map(|m| {
                        AttractorRecord::new(
                            m.track + 1,
                            m.kind,
                            (m.events, m.periods),
                            m.point,
                            m.lyapunov,
                            m.fraction,
                            m.precision,
                        )
                    })
                    .collect(),
            })
            .collect();
        AttractorsDoc {
            table: spec.sys.table().name(),
            r: spec.sys.r(),
            alpha: [spec.lo, spec.hi],
            steps: spec.steps,
            grid: [spec.nx, spec.ny],
            w_max: spec.w_max,
            transient: spec.settle.transient,
            match_distance: MATCH_DISTANCE,
            tracks,
            changes,
            values,
            joins: joins
                .iter()
                .map(|j| JoinRecord {
                    alpha: j.alpha,
                    matched: j.matched,
                    only_before: j.only_before,
                    only_after: j.only_after,
                    fraction_difference: j.fraction_difference,
                })
                .collect(),
            crises: crises.map(|ls| ls.iter().map(|l| CrisisRecord::of(cont, l)).collect()),
        }
    }
}
