//! Records of `lyapunov` and `basins`, and the exponent and attractor columns of
//! `sweep`: exponents (with `-inf`), attractor kinds, basin rows and documents.

use super::*;
use bouncemap_engine::run::precision::Precision;

/// A Lyapunov exponent in outputs: a number, `-inf` for a superstable (sticking or
/// resting) orbit (a string in json, which has no infinities), empty/null where the
/// orbit has none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponent(pub Option<f64>);

impl Serialize for Exponent {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            Some(x) if x == f64::NEG_INFINITY => s.serialize_str("-inf"),
            Some(x) if x.is_finite() => s.serialize_f64(x),
            _ => s.serialize_none(),
        }
    }
}

impl<'de> Deserialize<'de> for Exponent {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Exponent, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Number(f64),
            Text(String),
        }
        match Option::<Raw>::deserialize(d)? {
            None => Ok(Exponent(None)),
            Some(Raw::Number(x)) => Ok(Exponent(Some(x))),
            Some(Raw::Text(t)) if t == "-inf" => Ok(Exponent(Some(f64::NEG_INFINITY))),
            Some(Raw::Text(t)) if t.is_empty() => Ok(Exponent(None)),
            Some(Raw::Text(t)) => t
                .parse::<f64>()
                .map(|x| Exponent(Some(x)))
                .map_err(|_| serde::de::Error::custom(format!("'{t}' is not an exponent"))),
        }
    }
}

/// The engine's kind of an attractor, written by its name (`periodic`, `chaotic`, ...)
/// in every format: `#[serde(with = "kind_name")]`.
pub mod kind_name {
    use bouncemap_engine::attractors::Kind;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(k: &Kind, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(k.as_str())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Kind, D::Error> {
        let name = String::deserialize(d)?;
        Kind::ALL
            .into_iter()
            .find(|k| k.as_str() == name)
            .ok_or_else(|| {
                let all: Vec<&str> = Kind::ALL.iter().map(|k| k.as_str()).collect();
                serde::de::Error::custom(format!(
                    "unknown attractor kind '{name}': valid {}",
                    all.join(", ")
                ))
            })
    }
}

/// `lyapunov`'s result (the csv row; json adds the system and the start).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LyapunovRow {
    /// What the orbit settled on.
    #[serde(with = "kind_name")]
    pub kind: bouncemap_engine::attractors::Kind,
    /// Events and table periods per cycle, for cycles.
    pub events: Option<usize>,
    pub periods: Option<i64>,
    /// `cycle` (eigenvalues of the cycle's Jacobian) or `qr`; empty where none.
    pub method: Option<&'static str>,
    /// The exponents per impact, largest first.
    pub lambda1: Exponent,
    pub lambda2: Exponent,
    /// The exponents per table period.
    pub lambda1_per_period: Exponent,
    pub lambda2_per_period: Exponent,
    /// Standard errors per impact over the measurement's blocks (0 for a cycle).
    pub stderr1: Option<f64>,
    pub stderr2: Option<f64>,
    /// λ1 + λ2 per impact, and 2 ln r beside it.
    pub sum: Exponent,
    pub two_ln_r: f64,
    /// Impacts measured and the table periods they took.
    pub impacts: Option<u64>,
    pub measured_periods: Option<f64>,
    /// For a cycle: whether double precision decides it (false: a sticking cycle whose
    /// length rounding decides; `events` and `periods` are then empty).
    pub resolved: Option<bool>,
    /// For a sticking cycle: log₁₀ of the largest growth of a perturbation from a
    /// release to the next stick, and the impacts of that stretch.
    pub growth_decades: Option<f64>,
    pub growth_impacts: Option<usize>,
}

impl LyapunovRow {
    pub const HEADER: [&'static str; 17] = [
        "kind",
        "events",
        "periods",
        "method",
        "lambda1",
        "lambda2",
        "lambda1_per_period",
        "lambda2_per_period",
        "stderr1",
        "stderr2",
        "sum",
        "two_ln_r",
        "impacts",
        "measured_periods",
        "resolved",
        "growth_decades",
        "growth_impacts",
    ];

    pub fn new(found: &bouncemap_engine::attractors::Found, r: f64) -> LyapunovRow {
        use bouncemap_engine::attractors::lyapunov::Spectrum;
        let none = Exponent(None);
        let inf = Exponent(Some(f64::NEG_INFINITY));
        let mut row = LyapunovRow {
            kind: found.kind,
            events: found.events,
            periods: found.periods,
            method: None,
            lambda1: none,
            lambda2: none,
            lambda1_per_period: none,
            lambda2_per_period: none,
            stderr1: None,
            stderr2: None,
            sum: none,
            two_ln_r: 2.0 * r.ln(),
            impacts: None,
            measured_periods: None,
            resolved: found.precision.map(|p| p.resolved),
            growth_decades: found
                .precision
                .filter(|p| p.impacts > 0)
                .map(|p| p.growth_decades),
            growth_impacts: found.precision.filter(|p| p.impacts > 0).map(|p| p.impacts),
        };
        // No cycle length is claimed where rounding decides it.
        if row.resolved == Some(false) {
            row.events = None;
            row.periods = None;
        }
        match found.spectrum {
            Some(Spectrum::Finite(e)) => {
                row.method = Some(e.method.as_str());
                row.lambda1 = Exponent(Some(e.per_impact[0]));
                row.lambda2 = Exponent(Some(e.per_impact[1]));
                row.lambda1_per_period = Exponent(Some(e.per_period[0]));
                row.lambda2_per_period = Exponent(Some(e.per_period[1]));
                row.stderr1 = Some(e.stderr[0]).filter(|x| x.is_finite());
                row.stderr2 = Some(e.stderr[1]).filter(|x| x.is_finite());
                row.sum = Exponent(Some(e.per_impact[0] + e.per_impact[1]));
                row.impacts = Some(e.impacts);
                row.measured_periods = Some(e.periods);
            }
            Some(Spectrum::Sticking) => {
                row.lambda1 = inf;
                row.lambda2 = inf;
                row.lambda1_per_period = inf;
                row.lambda2_per_period = inf;
                row.sum = inf;
            }
            Some(Spectrum::Grazing) | None => {}
        }
        row
    }
}

/// `lyapunov`'s json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LyapunovDoc<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub start: InitialRecord,
    pub transient: u64,
    #[serde(flatten)]
    pub result: LyapunovRow,
}

/// One attractor of a basin picture or of a sweep value (json).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttractorRecord {
    /// 1, 2, …: largest basin first.
    pub id: usize,
    #[serde(with = "kind_name")]
    pub kind: bouncemap_engine::attractors::Kind,
    pub events: Option<usize>,
    pub periods: Option<i64>,
    /// A point on it: phase and velocity right after an event.
    pub phase: Option<f64>,
    pub v: Option<f64>,
    /// Largest exponent per impact.
    pub lyapunov: Exponent,
    /// Share of the starts that ended on it.
    pub fraction: f64,
    /// For a cycle: whether double precision decides it (false: a sticking cycle whose
    /// length rounding decides; `events` and `periods` are then empty).
    #[serde(default)]
    pub resolved: Option<bool>,
    /// For a sticking cycle: log₁₀ of the largest growth from a release to the next
    /// stick.
    #[serde(default)]
    pub growth_decades: Option<f64>,
    /// With `--digits`, where double precision cannot decide its cycle: the cycle
    /// decided at any precision.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<super::CycleRecord>,
}

impl AttractorRecord {
    /// Attractor number `id` of this `kind` with its cycle (events, periods), a point
    /// on it, its largest exponent, its share of the starts and its precision verdict:
    /// no cycle length is claimed where rounding decides it.
    pub fn new(
        id: usize,
        kind: bouncemap_engine::attractors::Kind,
        cycle: (Option<usize>, Option<i64>),
        point: Option<(f64, f64)>,
        lyapunov: Option<f64>,
        fraction: f64,
        precision: Option<Precision>,
    ) -> AttractorRecord {
        let resolved = precision.map(|p| p.resolved);
        let claimed = resolved != Some(false);
        AttractorRecord {
            id,
            kind,
            events: cycle.0.filter(|_| claimed),
            periods: cycle.1.filter(|_| claimed),
            phase: point.map(|p| p.0),
            v: point.map(|p| p.1),
            lyapunov: Exponent(lyapunov),
            fraction,
            resolved,
            growth_decades: precision
                .filter(|p| p.impacts > 0)
                .map(|p| p.growth_decades),
            cycle: None,
        }
    }

    /// This record with its cycle decided at any precision, if there is one.
    pub fn with_cycle(mut self, cycle: Option<&bouncemap_engine::CycleVerdict>) -> AttractorRecord {
        self.cycle = cycle.map(super::CycleRecord::of);
        self
    }
}

/// One csv row of `basins`: a start and its attractor's id.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BasinRow {
    pub t0: f64,
    pub w0: f64,
    pub attractor: Option<usize>,
}

impl BasinRow {
    pub const HEADER: [&'static str; 3] = ["t0", "w0", "attractor"];
}

/// `basins`'s json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BasinsDoc<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    /// Starts along t̂0 and along w0, and the top of w0.
    pub grid: [usize; 2],
    pub w_max: f64,
    pub transient: u64,
    pub starts: usize,
    pub attractors: Vec<AttractorRecord>,
}

impl<'a> BasinsDoc<'a> {
    /// The json of the picture `basins` of `spec`, with the cycle each attractor (by
    /// id) was decided to at any precision, where `cycle` has one.
    pub fn of(
        spec: &'a bouncemap_engine::attractors::basins::BasinSpec,
        basins: &bouncemap_engine::attractors::basins::Basins,
        cycle: &dyn Fn(usize) -> Option<&'a bouncemap_engine::CycleVerdict>,
    ) -> BasinsDoc<'a> {
        let reg = basins.registry();
        let number = crate::output::basin_map::numbers(reg);
        BasinsDoc {
            table: spec.sys.table().name(),
            alpha: spec.sys.alpha(),
            r: spec.sys.r(),
            grid: [spec.nx, spec.ny],
            w_max: spec.w_max,
            transient: spec.settle.transient,
            starts: reg.starts(),
            attractors: reg
                .ranked()
                .into_iter()
                .map(|id| {
                    let a = &reg.attractors()[id];
                    AttractorRecord::new(
                        number[id],
                        a.kind,
                        (a.events, a.periods),
                        a.point,
                        a.lyapunov,
                        reg.fraction(id),
                        a.precision,
                    )
                    .with_cycle(cycle(id))
                })
                .collect(),
        }
    }
}
