//! `bouncemap plane`: a two-parameter map (see [`bouncemap_engine::plane`]), every pixel
//! one pair of parameters classified by its orbit, with the analytic curves.
//!
//! csv: one row per pixel of the shard in index order (x, y, class, period,
//! table_periods, lyapunov, status) with the sweep file's provenance, checksum and end
//! line ([`crate::output::plane_file`]), so shards join with `merge`; json: the same plus
//! the curves; braille: the picture with axes, curves and legend.

use super::drive::fill;
use super::progress::Progress;
use super::resume;
use super::{picture_bytes, BASE_BYTES, THREAD_BYTES, WRITER_BYTES};
use crate::config::run::PlaneRun;
use crate::config::{self, InputError};
use crate::output::part_file::{shard_name, PartWriter};
use crate::output::plane_file::{self, CurvesRecord, PlaneFile, PlaneHeader};
use crate::output::plane_map;
use crate::output::sink::Sink;
use crate::output::text::shortest;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::plane::{curves, Plane, PlaneJob, PlaneSpec};
use std::io::Write;

pub fn run(run: &PlaneRun) -> anyhow::Result<()> {
    let PlaneRun { spec, job, .. } = run;
    if job.check {
        return check(run);
    }
    let threads = job.threads()?;
    let header = PlaneHeader::from(spec);
    if resume::already_written::<PlaneFile>(job, &header, spec.shard)? {
        return Ok(());
    }
    config::check_memory(memory_bound(run, threads), "this plane")?;
    let mut sink = Sink::open(job.out.as_deref()).map_err(InputError)?;
    let plane = compute(spec, &Executor::new(threads)?)?;
    let curves = curves(spec);
    let two_parameter = match &run.curves {
        Some((cplane, seeds)) => Some(
            bouncemap_engine::orbits::curves::curves(cplane, *seeds).map_err(InputError::from)?,
        ),
        None => None,
    };
    let write = |sink: &mut Sink| -> anyhow::Result<()> {
        match job.layout {
            Some(layout) => {
                let curves_text = match &curves {
                    Some(c) => serde_json::to_string(&CurvesRecord::from(c))?,
                    None => "null".to_string(),
                };
                let mut w = PartWriter::<_, PlaneFile>::begin(
                    &mut *sink,
                    layout,
                    &PlaneHeader::from(spec),
                    &shard_name(spec.shard),
                    spec.shard_len(),
                    &[&curves_text],
                )?;
                for row in plane_file::rows(spec, plane.pixels()) {
                    w.value(&row)?;
                }
                w.end()?;
            }
            None => {
                let (w, h) = job.text;
                // Colour on a terminal unless NO_COLOR is set; glyphs in files and pipes.
                use std::io::IsTerminal;
                let colour = job.out.is_none()
                    && std::io::stdout().is_terminal()
                    && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty());
                let lines = plane_map::lines(
                    spec,
                    &plane,
                    curves.as_ref(),
                    two_parameter.as_ref(),
                    &title(spec),
                    w as usize,
                    h as usize,
                    colour,
                );
                for line in lines {
                    writeln!(sink, "{line}")?;
                }
            }
        }
        Ok(())
    };
    write(&mut sink).map_err(|e| sink.describe(e))?;
    sink.finish()
}

/// `--check`: what the run would do, checked as it would be, nothing computed.
fn check(run: &PlaneRun) -> anyhow::Result<()> {
    let PlaneRun { spec, job, .. } = run;
    let mut plan = vec![format!(
        "plane of {} pixels (shard {} of {}): {}",
        spec.shard_len(),
        shard_name(spec.shard),
        spec.x.n * spec.y.n,
        title(spec)
    )];
    let (threads, line) = job.threads_plan();
    plan.push(line);
    plan.push(config::memory_plan(memory_bound(run, threads)));
    let header = PlaneHeader::from(spec);
    if resume::already_written::<PlaneFile>(job, &header, spec.shard)? {
        plan.push("--resume: the part is already there: nothing to compute".into());
    } else {
        plan.push(super::output_plan(
            job.out.as_deref(),
            job.what("the braille picture"),
        )?);
    }
    super::print_plan(&plan)
}

/// A bound on the run's memory, in bytes: the picture (a pixel's result, or none, for
/// every pixel of the plane, whatever the shard), the shard's pixels listed by pass,
/// every result of the shard in flight to the picture at once, each worker's run and
/// what measuring its exponent (and deciding a cycle at any precision) takes, the
/// two-parameter curves, the writer (a row at a
/// time, or the text picture) and the process. Large blocks are returned to the system
/// as they are freed ([`super::release_large_blocks`]).
fn memory_bound(run: &PlaneRun, threads: usize) -> u64 {
    let spec = &run.spec;
    use bouncemap_engine::plane::{Pixel, KEEP, LYAPUNOV_SAMPLE};
    use bouncemap_engine::run::{OrbitRun, Point};
    use std::mem::size_of;
    let all = spec.len() as u64;
    let shard = spec.shard_len() as u64;
    let picture = all * size_of::<Option<Pixel>>() as u64;
    let passes = shard * size_of::<usize>() as u64;
    let in_flight = shard * size_of::<(usize, Pixel)>() as u64;
    let exponent = match spec.lyapunov {
        true => bouncemap_engine::attractors::identify_bytes(LYAPUNOV_SAMPLE),
        false => 0,
    };
    let worker = OrbitRun::bytes(KEEP, spec.periodicity)
        + KEEP as u64 * size_of::<Point>() as u64
        + exponent
        + spec.digits.map_or(0, bouncemap_engine::digits_bytes);
    let writer = match run.job.layout {
        Some(_) => WRITER_BYTES,
        None => picture_bytes(run.job.text.0, run.job.text.1),
    };
    let curves = if run.curves.is_some() {
        CURVES_BYTES
    } else {
        0
    };
    BASE_BYTES
        + threads as u64 * (worker + THREAD_BYTES)
        + picture
        + passes
        + in_flight
        + curves
        + writer
}

/// What the two-parameter curves over the text picture hold, at most, in bytes: a few
/// curves of at most some thousands of points each (2 MB measured).
const CURVES_BYTES: u64 = 32 << 20;

/// Run the plane to the end with progress on stderr.
pub fn compute(spec: &PlaneSpec, executor: &Executor) -> anyhow::Result<Plane> {
    let handle = executor.start(PlaneJob::new(spec.clone())?, &Control::new());
    let progress = Progress::start_units("plane", "pixels", spec.shard_len(), &title(spec));
    fill(handle, progress, Plane::new(spec), "the plane")
}

fn title(spec: &PlaneSpec) -> String {
    let axis = |a: &bouncemap_engine::jobs::grid::Axis| {
        format!(
            "{} ∈ [{}, {}] ({})",
            a.param.as_str(),
            shortest(a.lo),
            shortest(a.hi),
            a.n
        )
    };
    let table = crate::output::text::table_with_free(&spec.table, &[spec.x.param, spec.y.param]);
    let mut fixed = String::new();
    for p in ["alpha", "r"] {
        if spec.x.param.as_str() != p && spec.y.param.as_str() != p {
            let v = if p == "alpha" { spec.alpha } else { spec.r };
            fixed.push_str(&format!("  {p} = {}", shortest(v)));
        }
    }
    format!(
        "{table}  x {}  y {}{fixed}  T = {}  start {}  shard {}",
        axis(&spec.x),
        axis(&spec.y),
        spec.transient,
        spec.start.as_str(),
        shard_name(spec.shard)
    )
}
