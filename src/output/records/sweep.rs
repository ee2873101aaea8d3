//! The sweep's records: a csv row per recorded point ([`SweepRow`]), a json value per
//! parameter value ([`SweepValue`]), the file's settings ([`SweepHeader`]) and its
//! optional columns ([`SweepColumns`]), as `sweep` writes them and `merge` reads them
//! back.

use super::*;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::run::precision::Precision;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::run::Point as SweepPoint;
use bouncemap_engine::sweep::{SweepSpec, ValueResult, Warm};

/// What became of a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    Periodic,
    Unsettled,
    Resting,
    NoLanding,
    /// Provisional: still running (the terminal application's export only).
    Running,
}

impl From<&Outcome> for Status {
    fn from(o: &Outcome) -> Status {
        match o {
            Outcome::Running { .. } => Status::Running,
            Outcome::Periodic { .. } => Status::Periodic,
            Outcome::Unsettled => Status::Unsettled,
            Outcome::Resting { .. } => Status::Resting,
            Outcome::NoLanding { .. } => Status::NoLanding,
        }
    }
}

/// One csv row of a sweep: one recorded point of one value. A value without points
/// has one row with empty phase, v and kind. The second column is named after the
/// swept parameter ([`SweepRow::header`]). With `--lyapunov` a `lyapunov` column
/// follows, with several starts an `attractor` column (the attractor's number at this
/// value, 1 = largest basin; period, table_periods, status and sticking are then the
/// attractor's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepRow {
    pub index: usize,
    pub value: f64,
    pub phase: Option<f64>,
    pub v: Option<f64>,
    pub kind: Option<Kind>,
    pub period: Option<usize>,
    pub table_periods: Option<i64>,
    pub status: Status,
    pub sticking: bool,
    /// For a periodic value: whether double precision decides its cycle (false: a
    /// sticking cycle whose length rounding decides; `period` and `table_periods` are
    /// then empty).
    pub resolved: Option<bool>,
    /// For a sticking cycle: log₁₀ of the largest growth of a perturbation from a
    /// release to the next stick.
    pub growth_decades: Option<f64>,
    /// None: no such column.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub lyapunov: Option<Exponent>,
    /// None: no such column.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attractor: Option<usize>,
    /// With `--digits` ([`CYCLE_COLUMNS`]): the sticking cycle decided at any precision
    /// where double precision cannot decide it (empty elsewhere). None: no such columns.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub digits_verdict: Option<Option<String>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub digits_periods: Option<Option<i64>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub stick_after: Option<Option<String>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub agreed_digits: Option<Option<u32>>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub need_digits: Option<Option<u32>>,
}

/// A field that is there (even if empty or null) is `Some`.
pub fn present<'de, D, T>(d: D) -> Result<Option<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    T::deserialize(d).map(Some)
}

impl SweepRow {
    /// The csv header of a sweep of `param`, with the `lyapunov`, `attractor` and
    /// `--digits` columns when asked.
    pub fn header(param: SweepParam, columns: SweepColumns) -> Vec<String> {
        let mut h: Vec<String> = SweepRow::field_names(columns)
            .into_iter()
            .map(String::from)
            .collect();
        h[1] = param.as_str().to_string();
        h
    }

    /// The names a csv row is read with: the header with the swept parameter's column
    /// called `value`.
    pub fn field_names(columns: SweepColumns) -> Vec<&'static str> {
        let mut h = vec![
            "index",
            "value",
            "phase",
            "v",
            "kind",
            "period",
            "table_periods",
            "status",
            "sticking",
            "resolved",
            "growth_decades",
        ];
        if columns.lyapunov {
            h.push("lyapunov");
        }
        if columns.attractors {
            h.push("attractor");
        }
        if columns.digits {
            h.extend(CYCLE_COLUMNS);
        }
        h
    }

    /// This row with the `--digits` columns of `cycle` (empty cells where None).
    pub(super) fn with_cycle(mut self, cycle: Option<&bouncemap_engine::CycleVerdict>) -> SweepRow {
        let c = cycle.map(CycleRecord::of);
        let c = c.as_ref();
        self.digits_verdict = Some(c.map(|c| c.verdict.clone()));
        self.digits_periods = Some(c.and_then(|c| c.periods));
        self.stick_after = Some(c.and_then(|c| c.stick_after.clone()));
        self.agreed_digits = Some(c.and_then(|c| c.agreed_digits));
        self.need_digits = Some(c.and_then(|c| c.need_digits));
        self
    }

    /// Whether the `--digits` cells are those of a verdict: its name one of
    /// [`VERDICTS`], the cycle's length and stick time given exactly where found.
    pub fn check_cycle(&self) -> Result<(), String> {
        let Some(Some(verdict)) = &self.digits_verdict else {
            let any = self.digits_periods.flatten().is_some()
                || self.stick_after.as_ref().is_some_and(|s| s.is_some())
                || self.agreed_digits.flatten().is_some()
                || self.need_digits.flatten().is_some();
            return match any {
                true => Err("--digits cells without a digits_verdict".into()),
                false => Ok(()),
            };
        };
        check_verdict(
            verdict,
            &[
                self.digits_periods.flatten().is_some(),
                self.stick_after.as_ref().is_some_and(|s| s.is_some()),
            ],
        )
    }

    /// The rows of one value, with a `lyapunov` column and with an `attractor` column
    /// (for `several` starts) as asked, handed to `f` one at a time, in order, so a
    /// million of them are never held at once; the first error of `f` ends it.
    pub fn each<E>(
        r: &ValueResult,
        columns: SweepColumns,
        mut f: impl FnMut(SweepRow) -> Result<(), E>,
    ) -> Result<(), E> {
        let (lyapunov, several) = (columns.lyapunov, columns.attractors);
        let row = |p: Option<&SweepPoint>,
                   o: &Outcome,
                   l: Option<f64>,
                   precision: Option<Precision>,
                   a: Option<usize>,
                   sticking: bool,
                   cycle: Option<&bouncemap_engine::CycleVerdict>| {
            let resolved = precision.map(|p| p.resolved);
            let claimed = resolved != Some(false);
            let row = SweepRow {
                index: r.index,
                value: r.value,
                phase: p.map(|p| p.phase),
                v: p.map(|p| p.v),
                kind: p.map(|p| p.kind.into()),
                period: o.period().filter(|_| claimed),
                table_periods: o.table_periods().filter(|_| claimed),
                status: o.into(),
                sticking,
                resolved,
                growth_decades: precision
                    .filter(|p| p.impacts > 0)
                    .map(|p| p.growth_decades),
                lyapunov: lyapunov.then_some(Exponent(l)),
                attractor: a,
                digits_verdict: None,
                digits_periods: None,
                stick_after: None,
                agreed_digits: None,
                need_digits: None,
            };
            match columns.digits {
                true => row.with_cycle(cycle),
                false => row,
            }
        };
        if several && !r.attractors.is_empty() {
            for (n, a) in r.attractors.iter().enumerate() {
                let pts = &r.points[a.points.clone()];
                // Each attractor's own: a sticking or resting one, a stick or release
                // among its points, or an exponent of −∞.
                use bouncemap_engine::attractors::Kind as A;
                use bouncemap_engine::EventKind;
                let sticking = matches!(a.kind, A::Sticking | A::Resting)
                    || pts.iter().any(|p| p.kind != EventKind::Impact)
                    || a.lyapunov == Some(f64::NEG_INFINITY);
                let row = |p| {
                    row(
                        p,
                        &a.outcome,
                        a.lyapunov,
                        a.precision,
                        Some(n + 1),
                        sticking,
                        a.cycle.as_ref(),
                    )
                };
                if pts.is_empty() {
                    f(row(None))?;
                }
                for p in pts {
                    f(row(Some(p)))?;
                }
            }
            return Ok(());
        }
        let attractor = several.then_some(1);
        let row = |p| {
            row(
                p,
                &r.outcome,
                r.lyapunov,
                r.precision,
                attractor,
                r.sticking,
                r.cycle.as_ref(),
            )
        };
        if r.points.is_empty() {
            return f(row(None));
        }
        r.points.iter().try_for_each(|p| f(row(Some(p))))
    }
}

/// One recorded point in a sweep's json.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointRecord {
    pub phase: f64,
    pub v: f64,
    pub kind: Kind,
    /// With several starts: the number of the attractor the point lies on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attractor: Option<usize>,
}

/// One value in a sweep's json: its points a list (`P`, as read back), or written
/// straight from a result ([`PointsOf`], not copied).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepValue<P = Vec<PointRecord>> {
    pub index: usize,
    pub value: f64,
    pub status: Status,
    pub period: Option<usize>,
    pub table_periods: Option<i64>,
    /// Period at which the early stop happened.
    pub stopped_at: Option<i64>,
    pub sticking: bool,
    /// For a periodic value: whether double precision decides its cycle (false: the
    /// period and table periods are then empty).
    pub resolved: Option<bool>,
    /// For a sticking cycle: log₁₀ of the largest growth from a release to the next
    /// stick.
    pub growth_decades: Option<f64>,
    /// Events computed.
    pub events: u64,
    /// With `--lyapunov`: the largest exponent per impact (`"-inf"` when it sticks).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "present"
    )]
    pub lyapunov: Option<Exponent>,
    /// With several starts: the attractors, largest basin first (numbered from 1).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attractors: Vec<AttractorRecord>,
    /// With `--digits`, where double precision cannot decide the cycle: the cycle
    /// decided at any precision.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<Box<CycleRecord>>,
    pub points: P,
}

/// The points of a result as json writes them (a list of [`PointRecord`]), made one at
/// a time as they are written.
#[derive(Clone, Copy, Debug)]
pub struct PointsOf<'a> {
    r: &'a ValueResult,
    several: bool,
}

impl Serialize for PointsOf<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let r = self.r;
        let attractor_of = |i: usize| {
            r.attractors
                .iter()
                .position(|a| a.points.contains(&i))
                .map(|n| n + 1)
        };
        s.collect_seq(r.points.iter().enumerate().map(|(i, p)| PointRecord {
            phase: p.phase,
            v: p.v,
            kind: p.kind.into(),
            attractor: if self.several { attractor_of(i) } else { None },
        }))
    }
}

impl<'a> SweepValue<PointsOf<'a>> {
    /// The json of one value, with its exponent, attractors and cycle at any precision
    /// as asked.
    pub fn new(r: &'a ValueResult, columns: SweepColumns) -> SweepValue<PointsOf<'a>> {
        let (lyapunov, several) = (columns.lyapunov, columns.attractors);
        let resolved = r.precision.map(|p| p.resolved);
        let claimed = resolved != Some(false);
        SweepValue {
            index: r.index,
            value: r.value,
            status: (&r.outcome).into(),
            period: r.outcome.period().filter(|_| claimed),
            table_periods: r.outcome.table_periods().filter(|_| claimed),
            resolved,
            growth_decades: r
                .precision
                .filter(|p| p.impacts > 0)
                .map(|p| p.growth_decades),
            stopped_at: match r.outcome {
                Outcome::Periodic { stopped_at, .. } => Some(stopped_at),
                _ => None,
            },
            sticking: r.sticking,
            events: r.events,
            lyapunov: lyapunov.then_some(Exponent(r.lyapunov)),
            attractors: r
                .attractors
                .iter()
                .enumerate()
                .map(|(n, a)| {
                    AttractorRecord::new(
                        n + 1,
                        a.kind,
                        (a.events, a.periods),
                        r.points.get(a.points.start).map(|p| (p.phase, p.v)),
                        a.lyapunov,
                        a.fraction,
                        a.precision,
                    )
                    .with_cycle(a.cycle.as_ref())
                })
                .collect(),
            cycle: r.cycle.as_ref().map(|c| Box::new(CycleRecord::of(c))),
            points: PointsOf { r, several },
        }
    }
}

/// The optional columns of a sweep file (and fields of its json), as its header
/// states them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepColumns {
    /// `lyapunov`.
    pub lyapunov: bool,
    /// `attractor` (several starts).
    pub attractors: bool,
    /// The `--digits` columns ([`CYCLE_COLUMNS`]).
    pub digits: bool,
}

impl SweepColumns {
    /// The columns of the file `h` heads.
    pub fn of(h: &SweepHeader) -> SweepColumns {
        SweepColumns {
            lyapunov: h.lyapunov,
            attractors: h.starts > 1,
            digits: h.digits.is_some(),
        }
    }
}

/// `--digits`, as a sweep's header records it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DigitsRecord {
    pub digits: u32,
    pub max_digits: u32,
    /// `decimals` (as written) or `doubles` (`--binary-params`).
    pub parameters: Parameters,
    /// The parameters and windows typed, as `NAME=TEXT` and `NAME=LO..HI` (absent where
    /// none was): every digit of them is read, so two runs that typed them differently
    /// are different runs even where their doubles agree.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub typed: Vec<String>,
}

impl DigitsRecord {
    /// The record of `ask` with the texts `written` kept that say more than their
    /// doubles (a text that is its double's shortest decimal is the setting the header
    /// already has).
    pub fn of(
        ask: bouncemap_engine::DigitsAsk,
        written: &bouncemap_engine::Written,
    ) -> DigitsRecord {
        let more = |t: &str| t.parse::<f64>().map_or(true, |x| format!("{x}") != t);
        let mut typed: Vec<String> = Vec::new();
        for (name, text) in [("alpha", &written.alpha), ("r", &written.r)] {
            if let Some(t) = text.as_deref().filter(|t| more(t)) {
                typed.push(format!("{name}={t}"));
            }
        }
        typed.extend(
            written
                .table
                .iter()
                .filter(|(_, t)| more(t))
                .map(|(n, t)| format!("{n}={t}")),
        );
        typed.extend(
            written
                .windows
                .iter()
                .filter(|(_, a, b)| more(a) || more(b))
                .map(|(n, a, b)| format!("{n}={a}..{b}")),
        );
        DigitsRecord {
            typed,
            ..DigitsRecord::from(ask)
        }
    }
}

/// How the parameters are read at any precision.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Parameters {
    /// Each the decimal written.
    Decimals,
    /// Each the double it was read to.
    Doubles,
}

impl From<bouncemap_engine::DigitsAsk> for DigitsRecord {
    fn from(a: bouncemap_engine::DigitsAsk) -> DigitsRecord {
        DigitsRecord {
            digits: a.digits,
            max_digits: a.max_digits,
            parameters: match a.binary {
                true => Parameters::Doubles,
                false => Parameters::Decimals,
            },
            typed: Vec::new(),
        }
    }
}

/// How the values of a sweep start.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum InitialRecord {
    /// `"near-fixed-point"`.
    Named(String),
    /// The state every value starts from (v0 null: f'(t0) + 0.5).
    State { t0: f64, v0: Option<f64>, z0: f64 },
}

/// The early-stop settings of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EarlyStop {
    pub max_period: usize,
    pub tolerance: f64,
}

/// The settings of a sweep: its full specification, as its files state it (the shard
/// is in the file's provenance, see [`crate::output::sweep_file`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepHeader {
    pub table: String,
    pub param: String,
    pub lo: f64,
    pub hi: f64,
    pub steps: usize,
    /// The fixed parameters (null for the swept one; d null unless the table is F_D).
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub d: Option<f64>,
    pub transient: u64,
    pub keep: usize,
    pub solver: String,
    /// `cold`, `warm` or `warm-backward`.
    pub start: String,
    pub initial: InitialRecord,
    pub early_stop: Option<EarlyStop>,
    /// A `lyapunov` column (absent from files without one).
    #[serde(default, skip_serializing_if = "is_false")]
    pub lyapunov: bool,
    /// Initial conditions per value (absent when 1).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub starts: usize,
    /// W of the extra starts' box (absent: the default of each value's system).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub w_max: Option<f64>,
    /// `--digits`: sticking cycles beyond double precision decided at any precision
    /// (absent without).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub digits: Option<DigitsRecord>,
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn one() -> usize {
    1
}

fn is_one(n: &usize) -> bool {
    *n == 1
}

impl From<&SweepSpec> for SweepHeader {
    fn from(spec: &SweepSpec) -> SweepHeader {
        let fixed = |p: SweepParam, x: f64| (spec.param != p).then_some(x);
        SweepHeader {
            table: crate::output::text::table_with_free(&spec.table, &[spec.param]),
            param: spec.param.as_str().to_string(),
            lo: spec.lo,
            hi: spec.hi,
            steps: spec.steps,
            alpha: fixed(SweepParam::Alpha, spec.alpha),
            r: fixed(SweepParam::R, spec.r),
            d: match spec.param {
                SweepParam::D => None,
                _ => spec.table.d(),
            },
            transient: spec.transient,
            keep: spec.keep,
            solver: solver_name(spec.solver).to_string(),
            start: match spec.warm {
                Warm::Off => "cold",
                w => w.as_str(),
            }
            .to_string(),
            initial: if spec.initial.near_fixed_point {
                InitialRecord::Named("near-fixed-point".into())
            } else {
                InitialRecord::State {
                    t0: spec.initial.t0,
                    v0: spec.initial.v0,
                    z0: spec.initial.z0,
                }
            },
            early_stop: spec.periodicity.map(|p| EarlyStop {
                max_period: p.max_period,
                tolerance: p.tolerance,
            }),
            lyapunov: spec.lyapunov,
            starts: spec.starts,
            w_max: spec.w_max,
            digits: spec.digits.map(|a| DigitsRecord::of(a, &spec.written)),
        }
    }
}
