//! `bouncemap basins`: the basins of attraction of one system over a grid of starts
//! (t̂0, w0), each run to its attractor (see [`bouncemap_engine::attractors::basins`]).
//!
//! csv: one row per start (t0, w0, attractor number), w0 rows from the bottom, t0
//! fastest; json: the attractors with kinds, periods, points, exponents and basin
//! fractions; braille: the picture with one texture per attractor and a legend.
//! Attractors are numbered 1, 2, … from the largest basin down.

use super::digits::Reporter;
use super::drive::fill;
use super::progress::Progress;
use crate::config::run::BasinsRun;
use crate::config::{self, InputError};
use crate::output::basin_map;
use crate::output::part_file::Layout;
use crate::output::records::{csv_writer, cycle_text, BasinRow, BasinsDoc};
use crate::output::sink::Sink;
use crate::output::text::shortest;
use bouncemap_engine::attractors::basins::{BasinSpec, Basins, BasinsJob};
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::{CycleVerdict, DigitsAsk, CYCLE_EVENTS};
use std::io::Write;

pub fn run(run: &BasinsRun) -> anyhow::Result<()> {
    let BasinsRun { spec, job, .. } = run;
    if job.check {
        let (workers, threads) = job.threads_plan();
        return super::print_plan(&[
            format!("basins of {} starts: {}", spec.len(), title(spec)),
            threads,
            config::memory_plan(memory_bound(run, workers)),
            super::output_plan(job.out.as_deref(), job.what("the braille picture"))?,
        ]);
    }
    let threads = job.threads()?;
    let mut sink = Sink::open(job.out.as_deref()).map_err(InputError)?;
    let basins = compute(spec, &Executor::new(threads)?)?;
    let cycles = match run.digits {
        Some(ask) => decide(spec, &basins, ask, &run.written)?,
        None => Vec::new(),
    };
    write(run, &basins, &cycles, &mut sink).map_err(|e| sink.describe(e))?;
    sink.finish()
}

/// The cycles double precision does not resolve, decided at any precision, by
/// attractor id, with progress on stderr.
fn decide(
    spec: &BasinSpec,
    basins: &Basins,
    ask: DigitsAsk,
    written: &bouncemap_engine::Written,
) -> anyhow::Result<Vec<Option<CycleVerdict>>> {
    let unresolved = basins
        .registry()
        .attractors()
        .iter()
        .filter(|a| a.unresolved())
        .count();
    if unresolved == 0 {
        return Ok(Vec::new());
    }
    let mut report = Reporter::new(
        "basins",
        CYCLE_EVENTS,
        &format!(
            "{unresolved} sticking cycle{} beyond double precision to {} digits",
            if unresolved == 1 { "" } else { "s" },
            ask.digits
        ),
    );
    let verdicts = basins.decide_cycles(spec, ask, written, &mut |p| {
        report.update(p);
        std::ops::ControlFlow::Continue(())
    });
    report.finish();
    verdicts.ok_or_else(|| anyhow::anyhow!("the runs at any precision stopped without a verdict"))
}

/// A bound on the run's memory, in bytes: a label per start (or none yet) and the
/// starts listed by pass, each worker's run and what identifying its attractor takes,
/// an allowance for the attractors' cells and the results waiting their turn to be
/// numbered (a few MB measured), the writer (a row at a time, or the text picture) and
/// the process. Large blocks are returned to the system as they are freed
/// ([`super::release_large_blocks`]).
fn memory_bound(run: &BasinsRun, threads: usize) -> u64 {
    let spec = &run.spec;
    use bouncemap_engine::attractors::identify_bytes;
    use bouncemap_engine::run::OrbitRun;
    use std::mem::size_of;
    let starts = spec.len() as u64;
    let labels = starts * (size_of::<Option<u32>>() + size_of::<usize>()) as u64;
    let worker = OrbitRun::bytes(1, spec.settle.periodicity) + identify_bytes(spec.settle.sample);
    let writer = match run.job.layout {
        None => super::picture_bytes(run.job.text.0, run.job.text.1),
        Some(_) => super::WRITER_BYTES,
    };
    // Cycles at any precision are decided one at a time, after the picture.
    let digits = run.digits.map_or(0, bouncemap_engine::digits_bytes);
    super::BASE_BYTES
        + digits
        + threads as u64 * (worker + super::THREAD_BYTES)
        + labels
        + ATTRACTORS_BYTES
        + writer
}

/// The allowance for the attractors' cells and the results waiting their turn to be
/// numbered, in bytes.
const ATTRACTORS_BYTES: u64 = 64 << 20;

/// Run the picture to the end with progress on stderr.
pub fn compute(spec: &BasinSpec, executor: &Executor) -> anyhow::Result<Basins> {
    let handle = executor.start(BasinsJob::new(spec.clone())?, &Control::new());
    let progress = Progress::start_units("basins", "starts", spec.len(), &title(spec));
    fill(handle, progress, Basins::new(spec), "the basin picture")
}

fn title(spec: &BasinSpec) -> String {
    format!(
        "{}  alpha = {}  r = {}  grid {}x{}  w0 ∈ [0, {}]  T = {}",
        spec.sys.table().name(),
        shortest(spec.sys.alpha()),
        shortest(spec.sys.r()),
        spec.nx,
        spec.ny,
        shortest(spec.w_max),
        spec.settle.transient
    )
}

fn write(
    run: &BasinsRun,
    basins: &Basins,
    cycles: &[Option<CycleVerdict>],
    out: &mut Sink,
) -> anyhow::Result<()> {
    let cycle = |id: usize| cycles.get(id).and_then(|c| c.as_ref());
    let spec = &run.spec;
    let reg = basins.registry();
    let number = basin_map::numbers(reg);
    match run.job.layout {
        Some(Layout::Csv) => {
            let mut w = csv_writer(&mut *out, &BasinRow::HEADER)?;
            for (k, l) in basins.labels().iter().enumerate() {
                let (t0, w0) = spec.start(k);
                w.serialize(BasinRow {
                    t0,
                    w0,
                    attractor: l.map(|id| number[id as usize]),
                })?;
            }
            w.flush()?;
        }
        Some(Layout::Json) => {
            let doc = BasinsDoc::of(spec, basins, &cycle);
            serde_json::to_writer(&mut *out, &doc)?;
            writeln!(out)?;
        }
        None => {
            let (w, h) = run.job.text;
            for line in basin_map::lines(basins, &title(spec), spec.w_max, w as usize, h as usize) {
                writeln!(out, "{line}")?;
            }
            let (ask, periods) = (run.digits, spec.settle.transient);
            for id in reg.ranked() {
                if let (Some(c), Some(ask)) = (cycle(id), ask) {
                    let text = cycle_text(c, ask.digits, ask.max_digits, periods);
                    writeln!(out, "attractor {} at any precision, {text}", number[id])?;
                }
            }
        }
    }
    Ok(())
}
