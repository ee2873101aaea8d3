//! The commands that run a job over many items (`sweep`, `plane`, `basins`,
//! `attractors`),
//! `lyapunov`, `curves`, `continue` and `cascade`, settled from their flags once: the validated specification and how the
//! run goes ([`Job`]: check only or compute, worker threads, where it writes and in
//! which layout, the text picture's size, `--resume`). The commands read these and
//! never their flags, as ripgrep's flags become one settled set of arguments before any
//! work starts.

use super::flags::{
    AttractorsArgs, AttractorsFormat, BasinsArgs, BasinsFormat, CascadeArgs, ContinueArgs,
    CurvesArgs, FromArg, LyapunovArgs, OrbitArgs, PlaneArgs, SweepArgs, TextSizeArgs,
};
use super::InputError;
use crate::output::attractors_file::AttractorsHeader;
use crate::output::part_file::Layout;
use crate::output::records::InitialRecord;
use crate::output::Format;
use bouncemap_engine::attractors::basins::BasinSpec;
use bouncemap_engine::attractors::Settle;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::orbits::continuation::{Options, Start};
use bouncemap_engine::orbits::curves::{Plane as CurvesPlane, Seeds};
use bouncemap_engine::plane::PlaneSpec;
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::start::near_fixed_point;
use bouncemap_engine::sweep::SweepSpec;
use bouncemap_engine::{Big, PreciseState, PreciseSystem, Slot, State, System, Table};
use clap::ValueEnum;

/// How a job-running command runs, settled from its flags.
#[derive(Clone, Debug)]
pub struct Job {
    /// `--check`: state the plan, compute nothing.
    pub check: bool,
    /// `--threads`, if given (resolved against the machine by [`Job::threads`]).
    requested_threads: Option<usize>,
    /// `--out`: the file written, or standard output.
    pub out: Option<String>,
    /// The file layout (csv or json), or None for the braille text picture.
    pub layout: Option<Layout>,
    /// The text picture's width and height in character cells.
    pub text: (u16, u16),
    /// `--resume`: leave a complete, verified part that is already there.
    pub resume: bool,
}

impl Job {
    /// The worker threads on this machine: `--threads`, else Slurm's CPUs for the
    /// task, else one per core (see [`super::threads`]).
    pub fn threads(&self) -> Result<usize, InputError> {
        super::threads(self.requested_threads)
    }

    /// The threads a `--check` plans for, and its plan line (a refusal on this machine
    /// is stated, not returned: the run may be meant for another one).
    pub fn threads_plan(&self) -> (usize, String) {
        super::threads_plan(self.requested_threads)
    }

    /// What the output is, for a plan line: the layout's name or `picture`.
    pub fn what<'a>(&self, picture: &'a str) -> &'a str {
        match self.layout {
            Some(l) => l.name(),
            None => picture,
        }
    }
}

/// `sweep`, settled.
#[derive(Clone, Debug)]
pub struct SweepRun {
    /// The diagram to compute, validated.
    pub spec: SweepSpec,
    /// How it runs.
    pub job: Job,
}

/// `plane`, settled.
#[derive(Clone, Debug)]
pub struct PlaneRun {
    /// The plane to compute, validated.
    pub spec: PlaneSpec,
    /// `--curves P`: the two-parameter curves to draw over the text picture, and their
    /// seeds.
    pub curves: Option<(CurvesPlane, Seeds)>,
    /// How it runs.
    pub job: Job,
}

/// `basins`, settled.
#[derive(Clone, Debug)]
pub struct BasinsRun {
    /// The basin picture to compute, validated.
    pub spec: BasinSpec,
    /// How it runs.
    pub job: Job,
    /// `--digits`: the attractors double precision does not resolve decided at any
    /// precision.
    pub digits: Option<bouncemap_engine::DigitsAsk>,
    /// With `digits`: the parameters as typed, read with every digit.
    pub written: bouncemap_engine::Written,
}

/// The layout an output format writes: csv or json (a part file), None for any other
/// (braille text).
pub fn part_layout(format: impl ValueEnum) -> Option<Layout> {
    match format.to_possible_value()?.get_name() {
        "csv" => Some(Layout::Csv),
        "json" => Some(Layout::Json),
        _ => None,
    }
}

/// `sweep`'s flags and preset, settled. The diagram's text picture is the terminal's
/// size, COLUMNS wide if the terminal's is unknown, at least 20 × 6.
pub fn sweep(args: &SweepArgs) -> Result<SweepRun, InputError> {
    let spec = super::sweep::sweep_spec(args)?;
    let (w, h) = super::text_size(&args.run.text, || {
        std::env::var("COLUMNS").ok().and_then(|c| c.parse().ok())
    });
    let layout = part_layout(args.format);
    if spec.digits.is_some() && layout.is_none() {
        return Err(digits_in_files());
    }
    let job = Job {
        check: args.run.check.check,
        requested_threads: args.run.workers.threads,
        out: args.part.output.out.clone(),
        layout,
        text: (w.max(20), h.max(6)),
        resume: args.part.resume,
    };
    Ok(SweepRun { spec, job })
}

/// `--digits` with a braille picture, refused: its cycles are columns of the files.
fn digits_in_files() -> InputError {
    InputError(
        "--digits: the cycles decided at any precision are columns of the csv and fields of the json: valid --format csv or json".into(),
    )
}

/// `plane`'s flags, settled. `--curves` goes with the text picture only: the csv and
/// json files are the pixels (their curves' numbers come from `bouncemap curves`).
pub fn plane(args: &PlaneArgs) -> Result<PlaneRun, InputError> {
    let spec = super::plane::plane_spec(args)?;
    let layout = part_layout(args.format);
    if spec.digits.is_some() && layout.is_none() {
        return Err(digits_in_files());
    }
    let curves = match args.curves {
        Some(_) if layout.is_some() => {
            return Err(InputError(
                "--curves: the curves are drawn over the braille picture: valid with --format braille (their numbers: bouncemap curves)".into(),
            ))
        }
        Some(p) => Some(super::plane::plane_curves(&spec, 1, p, None)?),
        None => None,
    };
    let job = Job {
        check: args.run.check.check,
        requested_threads: args.run.workers.threads,
        out: args.part.output.out.clone(),
        layout,
        text: text(&args.run.text),
        resume: args.part.resume,
    };
    Ok(PlaneRun { spec, curves, job })
}

/// `basins`' flags, settled.
pub fn basins(args: &BasinsArgs) -> Result<BasinsRun, InputError> {
    let spec = super::basin_spec(&args.spec)?;
    let layout = match args.format {
        BasinsFormat::Csv => Some(Layout::Csv),
        BasinsFormat::Json => Some(Layout::Json),
        BasinsFormat::Braille => None,
    };
    let digits = super::digits::digits_ask(&args.precision)?;
    let mut written = bouncemap_engine::Written::default();
    if let Some(ask) = digits {
        if layout == Some(Layout::Csv) {
            return Err(InputError(
                "--digits: the cycles decided at any precision are in the json's attractors and under the braille picture: valid --format json or braille".into(),
            ));
        }
        super::digits::digits_take(spec.sys.table())?;
        let sys = &spec.sys;
        let system = (sys.table(), sys.alpha(), sys.r());
        written = super::digits::job_written(&args.precision.written, &[], system, ask)?;
    }
    let job = Job {
        check: args.run.check.check,
        requested_threads: args.run.workers.threads,
        out: args.output.out.clone(),
        layout,
        text: text(&args.run.text),
        resume: false,
    };
    Ok(BasinsRun {
        spec,
        job,
        digits,
        written,
    })
}

/// `attractors`, settled.
#[derive(Clone, Debug)]
pub struct AttractorsRun {
    /// The continuation to compute, validated.
    pub spec: bouncemap_engine::attractors::global::GlobalSpec,
    /// How it runs (no layout: the text report).
    pub job: Job,
    /// With `--shard` (or in a Slurm array task): the part to compute, and the run's
    /// header its part file states.
    pub part: Option<(Shard, AttractorsHeader)>,
    /// `--crises`: locate each crisis after the continuation.
    pub crises: bool,
}

/// `attractors`' flags, settled.
pub fn attractors(args: &AttractorsArgs) -> Result<AttractorsRun, InputError> {
    let spec = super::attractors_spec(&args.spec)?;
    let shard = super::sweep::shard(args.shard, |name| std::env::var(name).ok())?;
    let sharded = args.shard.is_some() || shard != Shard::WHOLE;
    if sharded {
        if let Some(f) = args.format {
            return Err(InputError(format!(
                "--format {}: a part of `attractors --shard` is a json file for `merge`; valid without --format (give it to merge)",
                f.to_possible_value().map(|v| v.get_name().to_string()).unwrap_or_default()
            )));
        }
        if shard.count > spec.steps {
            return Err(InputError(format!(
                "--shard {}/{}: {} parts of {} α values; valid at most one part per α value (N ≤ {})",
                shard.index + 1,
                shard.count,
                shard.count,
                spec.steps,
                spec.steps
            )));
        }
    }
    if args.crises && sharded {
        return Err(InputError(
            "--crises with --shard: crises are located from the whole window; valid without --shard (or on one machine over the window)"
                .into(),
        ));
    }
    if args.resume && !sharded {
        return Err(InputError(
            "--resume without --shard: valid with --shard I/N (a part file, which can be verified)"
                .into(),
        ));
    }
    if args.resume && args.output.out.is_none() {
        return Err(InputError(
            "--resume without --out: valid with --out FILE, the file to check and write".into(),
        ));
    }
    let job = Job {
        check: args.check.check,
        requested_threads: args.workers.threads,
        out: args.output.out.clone(),
        layout: match args.format {
            _ if sharded => Some(Layout::Json),
            Some(AttractorsFormat::Csv) => Some(Layout::Csv),
            Some(AttractorsFormat::Json) => Some(Layout::Json),
            Some(AttractorsFormat::Text) | None => None,
        },
        text: (0, 0),
        resume: args.resume,
    };
    let part = sharded.then(|| (shard, attractors_header(&args.spec, &spec)));
    Ok(AttractorsRun {
        spec,
        job,
        part,
        crises: args.crises,
    })
}

/// The header of the run `args` defines, whose spec is `spec` (its part files state
/// it; [`attractors_spec_of`] makes the spec from it again).
pub fn attractors_header(
    args: &super::flags::AttractorsSpecArgs,
    spec: &bouncemap_engine::attractors::global::GlobalSpec,
) -> AttractorsHeader {
    AttractorsHeader {
        table: args.table.to_string(),
        r: args.r,
        alpha: [spec.lo, spec.hi],
        steps: spec.steps,
        grid: [spec.nx, spec.ny],
        w_max: spec.w_max,
        transient: spec.settle.transient,
        full_runs: !spec.stop_at_known,
        uncertainty_starts: spec.sampled_starts,
    }
}

/// The spec of a part file's header, its table loaded as the run loaded it.
pub fn attractors_spec_of(
    h: &AttractorsHeader,
) -> Result<bouncemap_engine::attractors::global::GlobalSpec, String> {
    let args = super::flags::AttractorsSpecArgs {
        table: super::table_spec::TableSpec::parse(&h.table)?,
        r: h.r,
        alpha: (h.alpha[0], h.alpha[1]),
        steps: h.steps,
        grid: (h.grid[0], h.grid[1]),
        w_max: Some(h.w_max),
        transient: h.transient,
        full_runs: h.full_runs,
        uncertainty_starts: h.uncertainty_starts,
    };
    super::attractors_spec(&args).map_err(|e| e.0)
}

/// `lyapunov`, settled.
#[derive(Clone, Debug)]
pub struct LyapunovRun {
    /// The system.
    pub sys: System,
    /// The orbit's start.
    pub start: State,
    /// The start as the output names it.
    pub initial: InitialRecord,
    /// The transient, the early stop and the impacts measured.
    pub settle: Settle,
    /// `--check`: state the plan, compute nothing.
    pub check: bool,
    /// The output format.
    pub format: Format,
}

/// `lyapunov`'s flags, settled: `--near-fixed-point` refused where the system has no
/// (1, 1) solution.
pub fn lyapunov(args: &LyapunovArgs) -> Result<LyapunovRun, InputError> {
    let sys = super::system(&args.system)?;
    let (start, initial) = if args.near_fixed_point {
        let s = near_fixed_point(&sys).ok_or_else(|| {
            InputError(format!(
                "--near-fixed-point: table {} at alpha = {} has no (1,1) solution to start next to (valid from the birth alpha that `bouncemap fixed` prints)",
                sys.table().name(),
                sys.alpha()
            ))
        })?;
        (s, InitialRecord::Named("near-fixed-point".into()))
    } else {
        let s = super::start(&sys, &args.initial)?;
        (
            s,
            InitialRecord::State {
                t0: args.initial.t0,
                v0: args.initial.v0,
                z0: args.initial.z0,
            },
        )
    };
    let settle = Settle {
        transient: args.transient,
        periodicity: (!args.no_early_stop).then(Periodicity::default),
        sample: args.impacts,
        solver: bouncemap_engine::Solver::Exact,
    };
    Ok(LyapunovRun {
        sys,
        start,
        initial,
        settle,
        check: args.check.check,
        format: args.format,
    })
}

/// `curves`, settled.
#[derive(Clone, Debug)]
pub struct CurvesRun {
    /// The plane of α and the second parameter, with its windows.
    pub plane: CurvesPlane,
    /// What the curves are started from, at the second parameter's starting value.
    pub seeds: Seeds,
    /// `--r`, as given (none with an r axis started from the window's middle).
    pub r: Option<f64>,
    /// `--out`: the file written, or standard output.
    pub out: Option<String>,
    /// The output format.
    pub format: Format,
}

/// `curves`' flags, settled.
pub fn curves(args: &CurvesArgs) -> Result<CurvesRun, InputError> {
    let (plane, seeds) = super::plane::curves_plane(&args.spec)?;
    Ok(CurvesRun {
        plane,
        seeds,
        r: args.spec.r,
        out: args.output.out.clone(),
        format: args.format,
    })
}

/// `continue`, settled.
#[derive(Clone, Debug)]
pub struct ContinueRun {
    /// The table.
    pub table: Table,
    /// Restitution.
    pub r: f64,
    /// The α window.
    pub alpha: (f64, f64),
    /// What the continuation starts from.
    pub start: Start,
    /// Its bounds.
    pub options: Options,
    /// Prove every point and special point (`--certify`).
    pub certify: bool,
    /// The output format.
    pub format: Format,
}

/// `continue`'s flags, settled: a guessed cycle (`--n`, `--t0`, `--v0`) before
/// `--from`, else the (1, k) solution.
pub fn continuation(args: &ContinueArgs) -> Result<ContinueRun, InputError> {
    let start = match (args.from, args.guess.cycle()) {
        (_, Some((n, t0, v0))) => Start::Point {
            n,
            k: args.k,
            t0,
            v0,
        },
        (Some(FromArg::TwoCycle), ..) => Start::TwoCycle { k: args.k },
        _ => Start::Fixed { k: args.k },
    };
    Ok(ContinueRun {
        table: args.table.load()?,
        r: args.r,
        alpha: args.alpha,
        start,
        options: Options {
            max_period: args.max_period,
            ..Options::default()
        },
        certify: args.certify,
        format: args.format,
    })
}

/// The tables a cascade runs on: one, or F_D at each D of `--d LO..HI:N`.
#[derive(Clone, Debug)]
pub enum CascadeTables {
    /// `--table`.
    One(Table),
    /// (D, F_D) for each D.
    Family(Vec<(f64, Table)>),
}

/// `cascade`, settled.
#[derive(Clone, Debug)]
pub struct CascadeRun {
    /// Its tables.
    pub tables: CascadeTables,
    /// Restitution.
    pub r: f64,
    /// k of the (1, k) solution it starts from.
    pub k: u32,
    /// Period doublings looked for.
    pub depth: usize,
    /// Prove each αₙ as an α-interval.
    pub certify: bool,
    /// The output format.
    pub format: Format,
}

/// `cascade`'s flags, settled.
pub fn cascade(args: &CascadeArgs) -> Result<CascadeRun, InputError> {
    let tables = match &args.d {
        Some(ds) => CascadeTables::Family(
            ds.0.iter()
                .map(|&d| Ok((d, Table::fd(d)?)))
                .collect::<Result<_, bouncemap_engine::EngineError>>()?,
        ),
        None => CascadeTables::One(args.table.load()?),
    };
    Ok(CascadeRun {
        tables,
        r: args.r,
        k: args.k,
        depth: args.depth,
        certify: args.certify,
        format: args.format,
    })
}

/// A system and a start to be made at any precision (`--digits`): the decimals the
/// flags were read to (or the doubles, with `--binary-params`), the digits asked for and
/// the most allowed.
#[derive(Clone, Debug)]
pub struct PreciseSpec {
    /// The system and the start at any precision.
    pub setup: bouncemap_engine::PreciseSetup,
    /// The table's name.
    pub table: String,
    /// α.
    pub alpha: f64,
    /// Restitution.
    pub r: f64,
    /// α and r as the run at any precision reads them: the text typed, or the double's
    /// shortest decimal (with `--binary-params`, the double's shortest decimal, which
    /// names the double read exactly).
    pub written: (String, String),
    /// Significant digits asked for.
    pub digits: u32,
    /// The most digits the precision is raised to.
    pub max_digits: u32,
    /// Each parameter the double it was read to, exactly.
    pub binary: bool,
}

impl PreciseSpec {
    /// The system and the start at `bits` ([`bouncemap_engine::PreciseSetup::make`]).
    pub fn make(&self, bits: usize) -> (PreciseSystem<Big>, PreciseState<Big>) {
        self.setup.make(bits)
    }

    /// How the parameters are read, as csv and json name it: `doubles` or `decimals`.
    pub fn parameters(&self) -> &'static str {
        if self.binary {
            "doubles"
        } else {
            "decimals"
        }
    }

    /// How the parameters are read, as the text says it.
    pub fn read_as(&self) -> &'static str {
        if self.binary {
            "as doubles"
        } else {
            "as written"
        }
    }
}

/// `orbit --digits`, settled.
#[derive(Clone, Debug)]
pub struct DigitsRun {
    /// The system, the start and the digits.
    pub spec: PreciseSpec,
    /// Events to print, and to compute first.
    pub bounces: u64,
    /// See `bounces`.
    pub skip: u64,
    /// The output format.
    pub format: Format,
}

/// `orbit`'s flags with `--digits`, settled (None without it).
pub fn digits(args: &OrbitArgs) -> Result<Option<DigitsRun>, InputError> {
    if args.solver != super::flags::SolverArg::Exact && args.precision.digits.is_some() {
        return Err(InputError(
            "--solver grid with --digits: the paper's grid is f64 only: valid --solver exact"
                .into(),
        ));
    }
    let Some(spec) = precise_spec(&args.precision, &args.system, &args.initial, None)? else {
        return Ok(None);
    };
    Ok(Some(DigitsRun {
        spec,
        bounces: args.bounces,
        skip: args.skip,
        format: args.format,
    }))
}

/// The `--digits` flags with the system and the start, settled (None without
/// `--digits`): checked as the f64 run checks them, and what the map at any precision
/// does not take yet (the sine, pieces of degree above 3, a start above the table)
/// refused naming what it takes. `start` replaces `--t0 --v0` (as `--near-fixed-point`
/// does).
fn precise_spec(
    p: &super::flags::PrecisionArgs,
    system: &super::flags::SystemArgs,
    initial: &super::flags::InitialArgs,
    start: Option<(f64, f64)>,
) -> Result<Option<PreciseSpec>, InputError> {
    let Some(ask) = super::digits::digits_ask(p)? else {
        return Ok(None);
    };
    let digits = ask.digits;
    let sys = super::system(system)?;
    super::start(&sys, initial)?;
    let table = sys.table();
    super::digits::digits_take(table)?;
    // (`--near-fixed-point`'s start is on the table.)
    let (t0, v0, z0) = match start {
        Some((t0, v0)) => (t0, Some(v0), 0.0),
        None => (initial.t0, initial.v0, initial.z0),
    };
    let setup =
        bouncemap_engine::PreciseSetup::new(table, system.alpha, system.r, t0, v0, p.binary_params)
            .ok_or_else(|| super::digits::digits_refusal(table))?
            .above(z0)
            .as_written(&p.written);
    setup.check_written().map_err(InputError)?;
    let written = (setup.decimal(Slot::Alpha), setup.decimal(Slot::R));
    Ok(Some(PreciseSpec {
        table: setup.table_name(),
        setup,
        alpha: system.alpha,
        r: system.r,
        written,
        digits,
        max_digits: p.max_digits,
        binary: p.binary_params,
    }))
}

/// `lyapunov --digits`, settled: the cycle the orbit settles on (by the f64 run), at
/// any precision: a cycle of impacts solved there, a sticking cycle decided there.
#[derive(Clone, Debug)]
pub struct LyapunovDigits {
    /// The system, the start and the digits.
    pub spec: PreciseSpec,
    /// The f64 run that says what the orbit settles on.
    pub double: LyapunovRun,
    /// The most table periods the orbit is followed to find its cycle.
    pub transient: u64,
    /// How the start was given, as the output names it.
    pub initial: InitialRecord,
    /// The output format.
    pub format: Format,
}

/// `lyapunov`'s flags with `--digits`, settled (None without it): the start as the f64
/// run has it (`--near-fixed-point`'s launch read back as decimals).
pub fn lyapunov_digits(args: &LyapunovArgs) -> Result<Option<LyapunovDigits>, InputError> {
    let run = lyapunov(args)?;
    let start = args
        .near_fixed_point
        .then(|| (run.start.phase(), run.start.v()));
    let Some(spec) = precise_spec(&args.precision, &args.system, &args.initial, start)? else {
        return Ok(None);
    };
    if run.check {
        return Err(InputError(
            "--check with --digits: a run at any precision has no plan yet: valid without --check"
                .into(),
        ));
    }
    Ok(Some(LyapunovDigits {
        spec,
        transient: args.transient,
        initial: run.initial.clone(),
        format: args.format,
        double: run,
    }))
}

/// A text picture's size: the flags', else the terminal's.
fn text(args: &TextSizeArgs) -> (u16, u16) {
    super::text_size(args, || None)
}
