//! The part file of `attractors --shard I/N`: one json document holding a part of a
//! continuation of attractors whole (every α value's attractors with their point sets,
//! the changes, the tracks), so that `merge` rebuilds the parts, joins them at the α
//! values they share ([`Continuation::join`]) and writes the report of the whole
//! window in any of `attractors`' formats.
//!
//! ```text
//! {"provenance":{"file":"attractors","tool":"bouncemap 0.1.0","spec_hash":"…","shard":"2/4","values":50},
//!  "spec":{"table":"fd:0.5","r":0.8,"alpha":[0.3,0.6],"steps":200,…},
//!  "first_value":49,"steps":[…],"changes":[…],"tracks":[…],"checksum":"…"}
//! ```
//!
//! `values` counts the α values the shard owns; `first_value` is the index of the first
//! one it computed (the last value of the shard before it, after the first shard: the
//! value the two are joined at). The checksum is the 64-bit FNV-1a of the compact json
//! of `steps`, `changes` and `tracks` (floats written to read back exactly), so damage
//! is caught; the spec hash names the run. Reading a part checks, in order: the
//! provenance, the spec against its hash, the checksum, and the part itself against the
//! spec ([`Continuation::from_parts`]: every α value where the window puts it, starts
//! and fractions that add up, tracks and changes that fit).

use super::part_file::{parse_shard, shard_name, spec_hash, TOOL};
use super::records::Exponent;
use bouncemap_engine::attractors::global::{
    Cause, Change, ChangeKind, Continuation, GlobalSpec, Member, Step, Track,
};
use bouncemap_engine::attractors::statistics::{BasinEntropy, NoExponent, Uncertainty};
use bouncemap_engine::attractors::Kind;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::run::precision::Precision;
use bouncemap_engine::Complex;
use serde::{Deserialize, Serialize};

/// The largest part read (whole, in memory), in bytes.
pub const ATTRACTORS_PART: u64 = 1 << 30;

/// The word a part's provenance names its kind by.
pub const FILE: &str = "attractors";

/// Whether `head`, the start of a file, is an `attractors` part.
pub fn is_attractors(head: &str) -> bool {
    let head: String = head.chars().take(400).collect();
    head.trim_start().starts_with('{') && head.contains("\"file\":\"attractors\"")
}

/// Everything that defines the run, as its flags give it (the table as written, so
/// `merge` loads the same table again): the spec a part states and hashes. The
/// configuration makes it from the flags and the spec from it again.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttractorsHeader {
    pub table: String,
    pub r: f64,
    pub alpha: [f64; 2],
    pub steps: usize,
    pub grid: [usize; 2],
    pub w_max: f64,
    pub transient: u64,
    pub full_runs: bool,
    pub uncertainty_starts: usize,
}

impl AttractorsHeader {
    /// Its hash, as the provenance states it.
    pub fn hash(&self) -> String {
        spec_hash(&serde_json::to_string(self).expect("a header serializes"))
    }
}

/// The α values shard `shard` owns: a contiguous run of them (the continuation goes
/// from one value to the next).
pub fn owned(steps: usize, shard: Shard) -> std::ops::Range<usize> {
    shard.index * steps / shard.count..(shard.index + 1) * steps / shard.count
}

/// The α values shard `shard` computes: those it owns, after the first shard from the
/// value before them (where it is joined to the shard before).
pub fn computed(steps: usize, shard: Shard) -> std::ops::Range<usize> {
    let own = owned(steps, shard);
    own.start.saturating_sub(1)..own.end
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Provenance {
    file: String,
    tool: String,
    spec_hash: String,
    shard: String,
    values: usize,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PrecisionRecord {
    growth_decades: f64,
    impacts: usize,
    resolved: bool,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MemberRecord {
    track: usize,
    kind: String,
    events: Option<usize>,
    periods: Option<i64>,
    point: Option<(f64, f64)>,
    lyapunov: Exponent,
    precision: Option<PrecisionRecord>,
    starts: usize,
    fraction: f64,
    points: Vec<(f64, f64)>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct EntropyRecord {
    side: usize,
    boxes: usize,
    boundary_boxes: usize,
    s_b: f64,
    s_bb: f64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct UncertaintyRecord {
    exponent: f64,
    error: f64,
    fractions: Vec<(f64, f64)>,
    starts: usize,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct StepRecord {
    alpha: f64,
    starts: usize,
    not_settled: usize,
    seeds: usize,
    sampled: bool,
    entropy: Option<EntropyRecord>,
    uncertainty: Option<UncertaintyRecord>,
    /// Why there is no exponent (the words of every output).
    no_uncertainty: Option<String>,
    members: Vec<MemberRecord>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChangeRecord {
    step: usize,
    track: usize,
    /// birth, death, merge, period, sticking, kind.
    change: String,
    into: Option<usize>,
    from_period: Option<(usize, i64)>,
    to_period: Option<(usize, i64)>,
    from_kind: Option<String>,
    to_kind: Option<String>,
    cause: Option<String>,
    /// For `unstable`: how, and the multiplier [re, im].
    bifurcation: Option<String>,
    multiplier: Option<[f64; 2]>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Body {
    steps: Vec<StepRecord>,
    changes: Vec<ChangeRecord>,
    /// (first, last) step of each track, in track order.
    tracks: Vec<(usize, usize)>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PartDoc {
    provenance: Provenance,
    spec: AttractorsHeader,
    first_value: usize,
    #[serde(flatten)]
    body: Body,
    checksum: String,
}

/// The json of the part `cont` of the run `header`, shard `shard`: checked to read back
/// to the same continuation before it is handed out.
pub fn write_part(
    header: &AttractorsHeader,
    shard: Shard,
    cont: &Continuation,
) -> Result<String, String> {
    let spec = cont.spec().clone();
    let body = Body {
        steps: cont.steps().iter().map(step_record).collect(),
        changes: cont.changes().iter().map(change_record).collect(),
        tracks: cont.tracks().iter().map(|t| (t.first, t.last)).collect(),
    };
    let doc = PartDoc {
        provenance: Provenance {
            file: FILE.into(),
            tool: TOOL.into(),
            spec_hash: header.hash(),
            shard: shard_name(shard),
            values: owned(header.steps, shard).len(),
        },
        spec: header.clone(),
        first_value: cont.values().start,
        checksum: checksum(&body),
        body,
    };
    let text = serde_json::to_string(&doc).map_err(|e| e.to_string())?;
    debug_assert!(text.starts_with(&opening(header, shard)));
    // Every number must read back as it was (a non-finite one would not).
    let again = read_part(&text, &|_| Ok(spec.clone()))
        .map_err(|e| format!("the part does not read back: {e}"))?;
    if again.cont.steps() != cont.steps()
        || again.cont.changes() != cont.changes()
        || again.cont.tracks() != cont.tracks()
    {
        return Err("the part does not read back to what was computed".into());
    }
    Ok(text)
}

/// How the part of the run `header`, shard `shard`, begins: its provenance up to its
/// shard (a file that begins so is this run's part, whole or not).
pub fn opening(header: &AttractorsHeader, shard: Shard) -> String {
    format!(
        r#"{{"provenance":{{"file":"{FILE}","tool":"{TOOL}","spec_hash":"{}","shard":"{}","#,
        header.hash(),
        shard_name(shard)
    )
}

fn checksum(body: &Body) -> String {
    spec_hash(&serde_json::to_string(body).expect("a part serializes"))
}

/// A part read back and checked.
#[derive(Debug)]
pub struct Part {
    pub header: AttractorsHeader,
    /// Its shard as stated (1-based I, N).
    pub shard: Shard,
    pub cont: Continuation,
}

/// Read and check the part `text` (see the module's header), its header made the spec
/// by `spec_of`; the refusal names what is wrong.
pub fn read_part(
    text: &str,
    spec_of: &dyn Fn(&AttractorsHeader) -> Result<GlobalSpec, String>,
) -> Result<Part, String> {
    let doc: PartDoc =
        serde_json::from_str(text).map_err(|e| format!("not an attractors part: {e}"))?;
    let p = &doc.provenance;
    if p.file != FILE {
        return Err(format!("a part of `{}`, not of `attractors`", p.file));
    }
    if p.tool != TOOL {
        return Err(format!(
            "written by {}, not by this {TOOL}: valid parts of this version",
            p.tool
        ));
    }
    if p.spec_hash != doc.spec.hash() {
        return Err(format!(
            "its spec does not match its spec_hash {} (changed after it was written)",
            p.spec_hash
        ));
    }
    if checksum(&doc.body) != doc.checksum {
        return Err(format!(
            "its checksum {} does not match what it holds (changed or damaged)",
            doc.checksum
        ));
    }
    let shard = parse_shard(&p.shard)?
        .ok_or_else(|| format!("its shard {:?} is a merged file's, not a part's", p.shard))?;
    let values = computed(doc.spec.steps, shard);
    if doc.first_value != values.start || p.values != owned(doc.spec.steps, shard).len() {
        return Err(format!(
            "shard {} of {} α values holds values {}..{}, not what it states",
            p.shard,
            doc.spec.steps,
            values.start + 1,
            values.end
        ));
    }
    let spec = spec_of(&doc.spec)?;
    let steps = doc
        .body
        .steps
        .iter()
        .map(step_of)
        .collect::<Result<Vec<_>, _>>()?;
    let changes = doc
        .body
        .changes
        .iter()
        .map(change_of)
        .collect::<Result<Vec<_>, _>>()?;
    let tracks = doc
        .body
        .tracks
        .iter()
        .enumerate()
        .map(|(id, &(first, last))| Track { id, first, last })
        .collect();
    let cont = Continuation::from_parts(spec, values, steps, changes, tracks)?;
    Ok(Part {
        header: doc.spec,
        shard,
        cont,
    })
}

fn step_record(s: &Step) -> StepRecord {
    StepRecord {
        alpha: s.alpha,
        starts: s.starts,
        not_settled: s.not_settled,
        seeds: s.seeds,
        sampled: s.sampled,
        entropy: s.entropy.map(|e| EntropyRecord {
            side: e.side,
            boxes: e.boxes,
            boundary_boxes: e.boundary_boxes,
            s_b: e.s_b,
            s_bb: e.s_bb,
        }),
        uncertainty: s.uncertainty.as_ref().ok().map(|u| UncertaintyRecord {
            exponent: u.exponent,
            error: u.error,
            fractions: u.fractions.clone(),
            starts: u.starts,
        }),
        no_uncertainty: s.uncertainty.as_ref().err().map(|e| e.as_str().into()),
        members: s.members.iter().map(member_record).collect(),
    }
}

fn member_record(m: &Member) -> MemberRecord {
    MemberRecord {
        track: m.track,
        kind: m.kind.as_str().into(),
        events: m.events,
        periods: m.periods,
        point: m.point,
        lyapunov: Exponent(m.lyapunov),
        precision: m.precision.map(|p| PrecisionRecord {
            growth_decades: p.growth_decades,
            impacts: p.impacts,
            resolved: p.resolved,
        }),
        starts: m.starts,
        fraction: m.fraction,
        points: m.points.clone(),
    }
}

fn change_record(c: &Change) -> ChangeRecord {
    let (from_period, to_period, from_kind, to_kind) = match &c.what {
        ChangeKind::Period { from, to } => (Some(*from), Some(*to), None, None),
        ChangeKind::Kind { from, to } => (
            None,
            None,
            Some(from.as_str().into()),
            Some(to.as_str().into()),
        ),
        _ => (None, None, None, None),
    };
    let (bifurcation, multiplier) = match c.cause {
        Some(Cause::Unstable { at, multiplier }) => {
            (Some(at.into()), Some([multiplier.re, multiplier.im]))
        }
        _ => (None, None),
    };
    ChangeRecord {
        step: c.step,
        track: c.track,
        change: c.what.name().into(),
        into: match c.what {
            ChangeKind::Death { into } => into,
            _ => None,
        },
        from_period,
        to_period,
        from_kind,
        to_kind,
        cause: c.cause.map(|x| x.name().into()),
        bifurcation,
        multiplier,
    }
}

fn kind_of(name: &str) -> Result<Kind, String> {
    Kind::ALL
        .into_iter()
        .find(|k| k.as_str() == name)
        .ok_or_else(|| format!("{name:?} is not a kind of attractor"))
}

fn step_of(r: &StepRecord) -> Result<Step, String> {
    const WHY: [NoExponent; 5] = [
        NoExponent::GridTooSmall,
        NoExponent::NoBoundary,
        NoExponent::TooFewUncertain,
        NoExponent::TooFewScales,
        NoExponent::NotPowerLaw,
    ];
    let uncertainty = match (&r.uncertainty, &r.no_uncertainty) {
        (Some(u), None) => Ok(Uncertainty {
            exponent: u.exponent,
            error: u.error,
            fractions: u.fractions.clone(),
            starts: u.starts,
        }),
        (None, Some(why)) => Err(WHY
            .into_iter()
            .find(|w| w.as_str() == why)
            .ok_or_else(|| format!("{why:?} is not why an exponent is missing"))?),
        _ => {
            return Err(format!(
                "α {}: an uncertainty exponent or why there is none, not both",
                r.alpha
            ))
        }
    };
    let members = r
        .members
        .iter()
        .map(|m| {
            Ok(Member {
                track: m.track,
                kind: kind_of(&m.kind)?,
                events: m.events,
                periods: m.periods,
                point: m.point,
                lyapunov: m.lyapunov.0,
                precision: m.precision.as_ref().map(|p| Precision {
                    growth_decades: p.growth_decades,
                    impacts: p.impacts,
                    resolved: p.resolved,
                }),
                starts: m.starts,
                fraction: m.fraction,
                points: m.points.clone(),
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(Step {
        alpha: r.alpha,
        members,
        starts: r.starts,
        not_settled: r.not_settled,
        entropy: r.entropy.as_ref().map(|e| BasinEntropy {
            side: e.side,
            boxes: e.boxes,
            boundary_boxes: e.boundary_boxes,
            s_b: e.s_b,
            s_bb: e.s_bb,
        }),
        uncertainty,
        sampled: r.sampled,
        seeds: r.seeds,
    })
}

fn change_of(r: &ChangeRecord) -> Result<Change, String> {
    let bad = || {
        format!(
            "change {:?} of attractor {} is not well-formed",
            r.change,
            r.track + 1
        )
    };
    let what = match (r.change.as_str(), r.into) {
        ("birth", None) => ChangeKind::Birth,
        ("death", None) => ChangeKind::Death { into: None },
        ("merge", Some(t)) => ChangeKind::Death { into: Some(t) },
        ("period", None) => ChangeKind::Period {
            from: r.from_period.ok_or_else(bad)?,
            to: r.to_period.ok_or_else(bad)?,
        },
        ("sticking" | "kind", None) => ChangeKind::Kind {
            from: kind_of(r.from_kind.as_deref().ok_or_else(bad)?)?,
            to: kind_of(r.to_kind.as_deref().ok_or_else(bad)?)?,
        },
        _ => return Err(bad()),
    };
    if what.name() != r.change {
        return Err(bad());
    }
    let cause = match r.cause.as_deref() {
        None => None,
        Some("unstable") => {
            let at = match r.bifurcation.as_deref() {
                Some("period doubling") => "period doubling",
                Some("fold") => "fold",
                Some("torus") => "torus",
                _ => return Err(bad()),
            };
            let [re, im] = r.multiplier.ok_or_else(bad)?;
            Some(Cause::Unstable {
                at,
                multiplier: Complex { re, im },
            })
        }
        Some("gone") => Some(Cause::Gone),
        Some("missed") => Some(Cause::Missed),
        Some("crisis") => Some(Cause::Crisis),
        Some("untested") => Some(Cause::Untested),
        Some(_) => return Err(bad()),
    };
    Ok(Change {
        step: r.step,
        track: r.track,
        what,
        cause,
    })
}
