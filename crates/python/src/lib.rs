//! The extension module `bouncemap._bouncemap`: the exact engine from Python. Each
//! function takes the arguments of the command of the same name as the command line
//! gives them (the `bouncemap` package builds them from keyword arguments), so they are
//! parsed, checked and turned into the engine's specification by the one configuration
//! stage the binary uses, and refused with the binary's one-line message
//! (`ValueError`). The results come back as numpy arrays (orbits, sweeps, basin
//! labels) and as the commands' json (the package reads it into dicts; the commands
//! without arrays of their own are run whole by `run_command`, their standard
//! output captured).
//!
//! Long computations run with the GIL released, on the engine's executor where they are
//! jobs (sweep, basins: on all cores); every 50 ms the calling thread takes the GIL back
//! to check for signals, so Ctrl-C (KeyboardInterrupt) cancels the job within that.

use bouncemap::config::flags::Command;
use bouncemap::config::{self, InputError};
use bouncemap::output::records::{BasinsDoc, FixedDoc, SweepColumns, SweepRow};
use bouncemap_engine::attractors::basins::{Basins, BasinsJob};
use bouncemap_engine::jobs::{Batch, Control, Executor, Job};
use bouncemap_engine::orbits::{fixed_points, stability_windows};
use bouncemap_engine::sweep::{SweepJob, ValueResult};
use bouncemap_engine::{EventKind, ImpactMap};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::{Duration, Instant};

/// How often a running computation checks for Ctrl-C.
const SIGNALS_EVERY: Duration = Duration::from_millis(50);

/// Ctrl-C seen from work running with the GIL released: the GIL taken back at most
/// every [`SIGNALS_EVERY`] to run Python's signal handlers.
struct Signals(Instant);

impl Signals {
    fn new() -> Signals {
        Signals(Instant::now())
    }

    /// The error a signal handler raised (KeyboardInterrupt for Ctrl-C), if one ran;
    /// None until [`SIGNALS_EVERY`] has passed since the last look.
    fn check(&mut self) -> Option<PyErr> {
        if self.0.elapsed() < SIGNALS_EVERY {
            return None;
        }
        self.0 = Instant::now();
        Python::attach(|py| py.check_signals()).err()
    }
}

/// The command `argv` asks for, or its refusal as a `ValueError`.
fn command(argv: &[String]) -> PyResult<Command> {
    bouncemap::parse_command(argv).map_err(PyValueError::new_err)
}

/// A refusal of the configuration stage or the engine: bad input, `ValueError`.
fn bad(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn input(e: InputError) -> PyErr {
    PyValueError::new_err(e.0)
}

fn wrong(name: &str) -> PyErr {
    PyValueError::new_err(format!("not a `{name}` command line"))
}

/// Run `job` on `executor` with the GIL released, handing each current batch to `on`;
/// Ctrl-C cancels it (the KeyboardInterrupt is returned). Whether it ran to its end.
fn run_job<J: Job>(
    py: Python<'_>,
    executor: &Executor,
    job: J,
    on: &mut (dyn FnMut(Batch<J::Output>) + Send),
) -> PyResult<bool>
where
    J::Output: Send,
{
    let control = Control::new();
    let mut interrupted: Option<PyErr> = None;
    let summary = py.detach(|| {
        let handle = executor.start(job, &control);
        let mut signals = Signals::new();
        loop {
            match handle.receiver().recv_timeout(SIGNALS_EVERY) {
                Ok(b) => {
                    if handle.is_current(&b) {
                        on(b);
                    }
                }
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
            }
            if let Some(e) = signals.check() {
                interrupted = Some(e);
                handle.cancel();
            }
        }
        handle.wait()
    });
    match interrupted {
        Some(e) => Err(e),
        None => Ok(!summary.cancelled),
    }
}

/// `fixed`: κ_c, the (1, k) solutions and the stability windows, as `fixed --format
/// json` writes them.
#[pyfunction]
fn fixed(argv: Vec<String>) -> PyResult<String> {
    let Command::Fixed(args) = command(&argv)? else {
        return Err(wrong("fixed"));
    };
    let sys = config::system(&args.system).map_err(input)?;
    let points = fixed_points(&sys, args.k).map_err(bad)?;
    let windows = stability_windows(sys.table(), sys.r(), args.k).map_err(bad)?;
    serde_json::to_string(&FixedDoc::of(&sys, args.k, &points, &windows))
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// The events of an orbit as arrays.
type OrbitArrays<'py> = (
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u8>>,
    Option<String>,
);

/// `orbit`: the events after `--skip`, `--bounces` of them, as (period, phase, v,
/// vrel, kind code: 0 impact, 1 stick, 2 release) and why the orbit stopped early (the
/// ball at rest for good, or no landing), if it did.
#[pyfunction]
fn orbit<'py>(py: Python<'py>, argv: Vec<String>) -> PyResult<OrbitArrays<'py>> {
    let Command::Orbit(args) = command(&argv)? else {
        return Err(wrong("orbit"));
    };
    if args.precision.digits.is_some() {
        return Err(PyValueError::new_err(
            "--digits: the orbit at any precision is the command's (bouncemap orbit --digits N); valid here without --digits",
        ));
    }
    let sys = config::system(&args.system).map_err(input)?;
    let state = config::start(&sys, &args.initial).map_err(input)?;
    let mut map = ImpactMap::new(sys, args.solver.into(), state);
    let n = usize::try_from(args.bounces).unwrap_or(usize::MAX);
    let cap = n.min(1 << 24);
    let (mut period, mut phase, mut v, mut vrel, mut kind) = (
        Vec::with_capacity(cap),
        Vec::with_capacity(cap),
        Vec::with_capacity(cap),
        Vec::with_capacity(cap),
        Vec::with_capacity(cap),
    );
    let mut interrupted: Option<PyErr> = None;
    let halt = py.detach(|| {
        let mut signals = Signals::new();
        // The skipped events, then the kept ones, in chunks with a signal check between.
        for (count, keep) in [(args.skip, false), (args.bounces, true)] {
            let mut left = count;
            while left > 0 {
                let c = left.min(1 << 16);
                left -= c;
                for _ in 0..c {
                    match map.step() {
                        Ok(e) if keep => {
                            period.push(e.period);
                            phase.push(e.phase);
                            v.push(e.v);
                            vrel.push(e.vrel);
                            kind.push(match e.kind {
                                EventKind::Impact => 0u8,
                                EventKind::Stick => 1,
                                EventKind::Release => 2,
                            });
                        }
                        Ok(_) => {}
                        Err(h) => return Some(h.to_string()),
                    }
                }
                if let Some(e) = signals.check() {
                    interrupted = Some(e);
                    return None;
                }
            }
        }
        None
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    Ok((
        period.into_pyarray(py),
        phase.into_pyarray(py),
        v.into_pyarray(py),
        vrel.into_pyarray(py),
        kind.into_pyarray(py),
        halt,
    ))
}

/// `sweep`: its csv's columns as arrays (one row per recorded point, as `sweep --format
/// csv` writes them): a dict of column name to array, with the swept parameter's
/// column under its name. Empty cells: NaN for floats, 0 for `period` and
/// `table_periods`, -1 for `resolved` and `attractor`, "" for `kind`.
#[pyfunction]
fn sweep<'py>(py: Python<'py>, argv: Vec<String>) -> PyResult<Bound<'py, PyDict>> {
    let Command::Sweep(args) = command(&argv)? else {
        return Err(wrong("sweep"));
    };
    let run = config::run::sweep(&args).map_err(input)?;
    if run.spec.digits.is_some() {
        return Err(PyValueError::new_err(
            "--digits: sticking cycles at any precision are the command's (bouncemap sweep --digits N --format csv); valid here without --digits",
        ));
    }
    if run.spec.shard != bouncemap_engine::jobs::grid::Shard::WHOLE {
        return Err(PyValueError::new_err(
            "--shard: a part of a sweep is the command's (bouncemap sweep --shard I/N --out FILE); valid here without --shard",
        ));
    }
    let threads = run.job.threads().map_err(input)?;
    let executor = Executor::new(threads).map_err(bad)?;
    let job = SweepJob::new(run.spec.clone()).map_err(bad)?.in_order();
    // Each value's final result (batches arrive as values finish), in the order the
    // command writes them (a warm sweep's chains in their direction).
    let positions = SweepJob::new(run.spec.clone()).map_err(bad)?;
    let mut found: std::collections::BTreeMap<usize, ValueResult> = Default::default();
    let complete = run_job(py, &executor, job, &mut |b| {
        if b.complete {
            found.insert(b.index, b.data);
        }
    })?;
    let values: Vec<ValueResult> = (0..positions.values())
        .filter_map(|k| found.remove(&positions.value_index(k)))
        .collect();
    if !complete || values.len() != run.spec.steps {
        return Err(PyRuntimeError::new_err(format!(
            "the sweep stopped after {} of {} values",
            values.len(),
            run.spec.steps
        )));
    }
    let columns = SweepColumns {
        lyapunov: run.spec.lyapunov,
        attractors: run.spec.starts > 1,
        digits: false,
    };
    let mut c = Columns::default();
    for r in &values {
        let _ = SweepRow::each::<std::convert::Infallible>(r, columns, |row| {
            c.push(row);
            Ok(())
        });
    }
    c.into_dict(py, run.spec.param.as_str(), columns)
}

/// A sweep's rows, column by column.
#[derive(Default)]
struct Columns {
    index: Vec<i64>,
    value: Vec<f64>,
    phase: Vec<f64>,
    v: Vec<f64>,
    kind: Vec<String>,
    period: Vec<i64>,
    table_periods: Vec<i64>,
    status: Vec<String>,
    sticking: Vec<bool>,
    resolved: Vec<i8>,
    growth_decades: Vec<f64>,
    lyapunov: Vec<f64>,
    attractor: Vec<i64>,
}

/// A serializable name (an enum's) as its text.
fn name<T: serde::Serialize>(x: &T) -> String {
    match serde_json::to_value(x) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(other) => other.to_string(),
        Err(_) => String::new(),
    }
}

impl Columns {
    fn push(&mut self, row: SweepRow) {
        let nan = f64::NAN;
        self.index.push(row.index as i64);
        self.value.push(row.value);
        self.phase.push(row.phase.unwrap_or(nan));
        self.v.push(row.v.unwrap_or(nan));
        self.kind
            .push(row.kind.map(|k| name(&k)).unwrap_or_default());
        self.period.push(row.period.map_or(0, |p| p as i64));
        self.table_periods.push(row.table_periods.unwrap_or(0));
        self.status.push(name(&row.status));
        self.sticking.push(row.sticking);
        self.resolved.push(row.resolved.map_or(-1, i8::from));
        self.growth_decades.push(row.growth_decades.unwrap_or(nan));
        self.lyapunov
            .push(row.lyapunov.and_then(|e| e.0).unwrap_or(nan));
        self.attractor.push(row.attractor.map_or(-1, |a| a as i64));
    }

    fn into_dict<'py>(
        self,
        py: Python<'py>,
        param: &str,
        columns: SweepColumns,
    ) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("index", self.index.into_pyarray(py))?;
        d.set_item(param, self.value.into_pyarray(py))?;
        d.set_item("phase", self.phase.into_pyarray(py))?;
        d.set_item("v", self.v.into_pyarray(py))?;
        d.set_item("kind", self.kind)?;
        d.set_item("period", self.period.into_pyarray(py))?;
        d.set_item("table_periods", self.table_periods.into_pyarray(py))?;
        d.set_item("status", self.status)?;
        d.set_item("sticking", self.sticking.into_pyarray(py))?;
        d.set_item("resolved", self.resolved.into_pyarray(py))?;
        d.set_item("growth_decades", self.growth_decades.into_pyarray(py))?;
        if columns.lyapunov {
            d.set_item("lyapunov", self.lyapunov.into_pyarray(py))?;
        }
        if columns.attractors {
            d.set_item("attractor", self.attractor.into_pyarray(py))?;
        }
        Ok(d)
    }
}

/// `basins`: the attractor of every start as a (ny, nx) array of attractor numbers
/// (1 = the largest basin, as the command numbers them; 0 where none), row j at
/// w0 = (j + ½)·W/ny, column i at t̂0 = (i + ½)/nx; and `basins --format json`'s
/// document (the attractors, their fractions).
#[pyfunction]
fn basins<'py>(
    py: Python<'py>,
    argv: Vec<String>,
) -> PyResult<(Bound<'py, numpy::PyArray2<u32>>, String)> {
    let Command::Basins(args) = command(&argv)? else {
        return Err(wrong("basins"));
    };
    let run = config::run::basins(&args).map_err(input)?;
    if run.digits.is_some() {
        return Err(PyValueError::new_err(
            "--digits: cycles at any precision are the command's (bouncemap basins --digits N); valid here without --digits",
        ));
    }
    let spec = run.spec.clone();
    let threads = run.job.threads().map_err(input)?;
    let executor = Executor::new(threads).map_err(bad)?;
    let job = BasinsJob::new(spec.clone()).map_err(bad)?;
    let mut picture = Basins::new(&spec);
    let complete = run_job(py, &executor, job, &mut |b| {
        picture.absorb(b.data);
    })?;
    if !complete || !picture.complete() {
        return Err(PyRuntimeError::new_err(format!(
            "the basins stopped after {} of {} starts",
            picture.covered(),
            spec.len()
        )));
    }
    let number = bouncemap::output::basin_map::numbers(picture.registry());
    let (nx, ny) = picture.grid();
    let labels: Vec<u32> = picture
        .labels()
        .iter()
        .map(|l| l.map_or(0, |id| number[id as usize] as u32))
        .collect();
    let doc = serde_json::to_string(&BasinsDoc::of(&spec, &picture, &|_| None))
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let grid = Array2::from_shape_vec((ny, nx), labels)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((grid.into_pyarray(py), doc))
}

/// `plane`: the pixels of `plane --format csv` as flat arrays in its row order
/// (index j·nx + i), with the header's json (the plane's settings, as the file states
/// them) and the analytic curves' json (`null` where there are none).
#[pyfunction]
fn plane<'py>(py: Python<'py>, argv: Vec<String>) -> PyResult<Bound<'py, PyDict>> {
    use bouncemap::output::plane_file::{self, CurvesRecord, PlaneHeader};
    use bouncemap_engine::plane::{curves, Plane, PlaneJob};
    let Command::Plane(args) = command(&argv)? else {
        return Err(wrong("plane"));
    };
    let run = config::run::plane(&args).map_err(input)?;
    let spec = run.spec.clone();
    if spec.digits.is_some() {
        return Err(PyValueError::new_err(
            "--digits: the pixels at any precision are the command's (bouncemap plane --digits N --format csv); valid here without --digits",
        ));
    }
    if spec.shard != bouncemap_engine::jobs::grid::Shard::WHOLE {
        return Err(PyValueError::new_err(
            "--shard: a part of a plane is the command's (bouncemap plane --shard I/N --out FILE); valid here without --shard",
        ));
    }
    let threads = run.job.threads().map_err(input)?;
    let executor = Executor::new(threads).map_err(bad)?;
    let job = PlaneJob::new(spec.clone()).map_err(bad)?;
    let mut picture = Plane::new(&spec);
    let complete = run_job(py, &executor, job, &mut |b| {
        bouncemap_engine::jobs::picture::Filled::absorb(&mut picture, b.data)
    })?;
    if !complete || !bouncemap_engine::jobs::picture::Filled::complete(&picture) {
        return Err(PyRuntimeError::new_err(
            "the plane stopped before its last pixel",
        ));
    }
    let nan = f64::NAN;
    let (mut x, mut y, mut class, mut status) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut period, mut table_periods) = (Vec::new(), Vec::new());
    let (mut lyapunov, mut resolved, mut growth) = (Vec::new(), Vec::new(), Vec::new());
    for row in plane_file::rows(&spec, picture.pixels()) {
        x.push(row.x);
        y.push(row.y);
        class.push(row.class);
        status.push(row.status);
        period.push(row.period.map_or(0, |p| p as i64));
        table_periods.push(row.table_periods.unwrap_or(0));
        lyapunov.push(row.lyapunov.0.unwrap_or(nan));
        resolved.push(row.resolved.map_or(-1i8, i8::from));
        growth.push(row.growth_decades.unwrap_or(nan));
    }
    let json =
        |e: serde_json::Result<String>| e.map_err(|e| PyRuntimeError::new_err(e.to_string()));
    let header = json(serde_json::to_string(&PlaneHeader::from(&spec)))?;
    let analytic = match curves(&spec) {
        Some(c) => json(serde_json::to_string(&CurvesRecord::from(&c)))?,
        None => "null".into(),
    };
    let d = PyDict::new(py);
    d.set_item("header", header)?;
    d.set_item("curves", analytic)?;
    d.set_item("x", x.into_pyarray(py))?;
    d.set_item("y", y.into_pyarray(py))?;
    d.set_item("class", class)?;
    d.set_item("status", status)?;
    d.set_item("period", period.into_pyarray(py))?;
    d.set_item("table_periods", table_periods.into_pyarray(py))?;
    d.set_item("lyapunov", lyapunov.into_pyarray(py))?;
    d.set_item("resolved", resolved.into_pyarray(py))?;
    d.set_item("growth_decades", growth.into_pyarray(py))?;
    Ok(d)
}

/// Any command whose output is text (json with `--format json`), run as the binary
/// runs it, its standard output returned: `two-cycle`, `lyapunov`, `continue`,
/// `cascade`, `curves`, ... The GIL is released while it runs; it runs to its end.
#[pyfunction]
fn run_command(py: Python<'_>, argv: Vec<String>) -> PyResult<String> {
    match py.detach(|| bouncemap::run_captured(&argv)) {
        Ok(bytes) => String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string())),
        Err(bouncemap::Refused::Input(m)) => Err(PyValueError::new_err(m)),
        Err(bouncemap::Refused::Failed(m)) => Err(PyRuntimeError::new_err(m)),
    }
}

/// The extension module.
#[pymodule]
fn _bouncemap(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fixed, m)?)?;
    m.add_function(wrap_pyfunction!(orbit, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(basins, m)?)?;
    m.add_function(wrap_pyfunction!(plane, m)?)?;
    m.add_function(wrap_pyfunction!(run_command, m)?)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add("TABLES", bouncemap_engine::table::builtin::NAMES)?;
    Ok(())
}
