//! `bouncemap sweep`: a bifurcation diagram computed headless, written as csv or json
//! (the sweep file of [`crate::output::sweep_file`], with its provenance) or as braille
//! text; presets for the paper's figures; `--shard I/N` parts (or the part of a Slurm
//! array task); `--resume`, which leaves a part that is already there, complete and
//! verified, as it is.
//!
//! Values are computed in index order and written as they complete, through a window
//! that keeps at most [`WINDOW_BYTES`] of results in flight (or two work items per
//! worker, if more): memory does not grow with the number of values. The run's memory
//! bound ([`budget`], refused up front beyond what the machine has, stated by
//! `--check`) is an upper bound of what it holds.

use super::drive::drive_job;
use super::progress::Progress;
use super::resume;
use super::{picture_bytes, BASE_BYTES, THREAD_BYTES, WRITER_BYTES};
use crate::config::run::SweepRun;
use crate::config::{self, check_memory, InputError};
use crate::output::diagram::BrailleDiagram;
use crate::output::part_file::{shard_name, spec_text, Layout};
use crate::output::records::SweepHeader;
use crate::output::sink::Sink;
use crate::output::sweep_file::{SweepFile, SweepWriter};
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::sweep::{chain_len, SweepJob, SweepSpec, ValueResult};
use std::collections::BTreeMap;
use std::io::Write;

/// Results held in flight at most, in bytes (the window of values ahead of the writer),
/// when the workers can be kept busy with less.
pub const WINDOW_BYTES: u64 = 64 << 20;

pub fn run(run: &SweepRun) -> anyhow::Result<()> {
    let SweepRun { spec, job } = run;
    if job.check {
        return check(run);
    }
    let threads = job.threads()?;
    let header = SweepHeader::from(spec);
    if resume::already_written::<SweepFile>(job, &header, spec.shard)? {
        return Ok(());
    }
    let (window, memory) = budget(spec, threads, writer_bytes(job.layout, job.text));
    check_memory(memory, "this sweep")?;
    let mut sink = Sink::open(job.out.as_deref()).map_err(InputError)?;
    let executor = Executor::new(threads)?;
    let result = match job.layout {
        Some(layout) => stream(spec, &executor, window, &mut sink, layout),
        None => braille(spec, &executor, window, &mut sink, job.text),
    };
    result.map_err(|e| sink.describe(e))?;
    sink.finish()
}

/// The values in flight and a bound on the run's memory, in bytes. The window counts
/// work items (chains of values with `--warm`): as many as [`WINDOW_BYTES`] of their
/// values hold, at least two per worker. The bound is what the run holds at most: every
/// item of the window finished and waiting for the writer (each value its largest
/// result, [`SweepSpec::value_bytes`]; no more values than the shard has; with `--warm`
/// whole chains, which may all finish while the writer waits for the first), each
/// worker computing at its largest besides ([`SweepSpec::worker_bytes`]: its run's ring
/// and detectors, what several starts or exponents take), the writer (a row or a point
/// at a time; the text picture for braille), and the process itself. Large blocks are
/// returned to the system as they are freed ([`super::release_large_blocks`]), so what
/// the process holds is what is live.
fn budget(spec: &SweepSpec, threads: usize, writer: u64) -> (usize, u64) {
    let value = spec.value_bytes();
    let chain = chain_len(spec.warm) as u64;
    let threads = threads as u64;
    let window = (WINDOW_BYTES / (value * chain)).clamp(2 * threads, 1 << 16);
    let held = (window * chain).min(spec.shard_values() as u64) * value;
    let workers = threads * (spec.worker_bytes() + THREAD_BYTES);
    (window as usize, BASE_BYTES + held + workers + writer)
}

/// What the writer of `format` holds at most, in bytes: a row or a point at a time for
/// csv and json; the text picture of `size` for braille.
fn writer_bytes(layout: Option<Layout>, (w, h): (u16, u16)) -> u64 {
    match layout {
        Some(_) => WRITER_BYTES,
        None => picture_bytes(w, h),
    }
}

/// `--check`: what the run would do, checked as it would be, nothing computed.
fn check(run: &SweepRun) -> anyhow::Result<()> {
    let SweepRun { spec, job } = run;
    let header = SweepHeader::from(spec);
    let mut plan = vec![format!(
        "sweep of {} values (shard {} of {}): {}",
        spec.shard_values(),
        shard_name(spec.shard),
        spec.steps,
        spec_text(&header)
    )];
    let (threads, line) = job.threads_plan();
    plan.push(line);
    let writer = writer_bytes(job.layout, job.text);
    plan.push(config::memory_plan(budget(spec, threads, writer).1));
    if resume::already_written::<SweepFile>(job, &header, spec.shard)? {
        plan.push("--resume: the part is already there: nothing to compute".into());
    } else {
        plan.push(super::output_plan(
            job.out.as_deref(),
            job.what("the braille diagram"),
        )?);
    }
    super::print_plan(&plan)
}

// The tests below read back the parts a sweep writes, as `--resume` does.
#[cfg(test)]
use {crate::output::part_file::TOOL, std::path::Path};

/// Whether `path` already holds the part of `spec` this run would write, complete and
/// verified (see [`resume::check`]).
#[cfg(test)]
fn already_done(path: &Path, layout: Layout, spec: &SweepSpec) -> Result<String, String> {
    resume::check::<SweepFile>(path, layout, &SweepHeader::from(spec), spec.shard)
}

/// Run the sweep, handing each value to `each` in index order as soon as it and every
/// value before it are complete.
fn in_order(
    spec: &SweepSpec,
    executor: &Executor,
    window: usize,
    mut each: impl FnMut(&ValueResult) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let job = SweepJob::new(spec.clone())?.in_order();
    let positions = SweepJob::new(spec.clone())?;
    let values = positions.values();
    let per_item = chain_len(spec.warm);
    let handle = executor.start_windowed(job, &Control::new(), window);
    let spec_line = format!(
        "{} shard {}",
        spec_text(&SweepHeader::from(spec)),
        shard_name(spec.shard)
    );
    let progress = Progress::start("sweep", values, &spec_line);
    let mut pending: BTreeMap<usize, ValueResult> = BTreeMap::new();
    let mut next = 0usize;
    drive_job(handle, progress, |handle, b| {
        if !b.complete {
            return Ok(());
        }
        pending.insert(b.index, b.data);
        while next < values {
            let Some(r) = pending.remove(&positions.value_index(next)) else {
                break;
            };
            each(&r)?;
            next += 1;
            handle.ack(next / per_item);
        }
        Ok(())
    })?;
    if next != values {
        anyhow::bail!("the sweep stopped after {next} of {values} values");
    }
    Ok(())
}

fn stream(
    spec: &SweepSpec,
    executor: &Executor,
    window: usize,
    sink: &mut Sink,
    layout: Layout,
) -> anyhow::Result<()> {
    let header = SweepHeader::from(spec);
    let values = spec.shard_values();
    let mut w = SweepWriter::begin(&mut *sink, layout, &header, &shard_name(spec.shard), values)?;
    in_order(spec, executor, window, |r| Ok(w.value(r)?))?;
    w.end()?;
    Ok(())
}

fn braille(
    spec: &SweepSpec,
    executor: &Executor,
    window: usize,
    sink: &mut Sink,
    (w, h): (u16, u16),
) -> anyhow::Result<()> {
    let mut d = BrailleDiagram::new(spec, w, h);
    in_order(spec, executor, window, |r| {
        d.add(r);
        Ok(())
    })?;
    for line in d.lines(spec) {
        writeln!(sink, "{line}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::jobs::grid::Shard;
    use bouncemap_engine::jobs::grid::SweepParam;
    use bouncemap_engine::sweep::Warm;
    use bouncemap_engine::Table;

    fn small(keep: usize, shard: Shard) -> SweepSpec {
        let mut spec = SweepSpec::new(
            Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.45,
            0.6,
            12,
        );
        spec.transient = 2000;
        spec.keep = keep;
        spec.shard = shard;
        spec
    }

    /// `spec`'s file, written as `sweep --out` writes it.
    fn write(path: &Path, spec: &SweepSpec, layout: Layout) {
        let ex = Executor::new(1).unwrap();
        let mut sink = Sink::open(Some(path.to_str().unwrap())).unwrap();
        stream(spec, &ex, 4, &mut sink, layout).unwrap();
        sink.finish().unwrap();
    }

    #[test]
    fn resume_accepts_only_this_very_part_complete_and_verified() {
        let d = std::env::temp_dir().join(format!("bouncemap-resume-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        let two_of_three = Shard { index: 1, count: 3 };
        let spec = small(4, two_of_three);
        let f = d.join("part.csv");
        assert_eq!(
            already_done(&f, Layout::Csv, &spec).unwrap_err(),
            format!("no {} yet", f.display())
        );
        write(&f, &spec, Layout::Csv);
        // Shard 2/3 of 12 values holds 1, 4, 7, 10.
        let done = already_done(&f, Layout::Csv, &spec).unwrap();
        assert!(
            done.contains("shard 2/3") && done.contains("(4 values)"),
            "{done}"
        );
        let why = |spec: &SweepSpec, layout: Layout| already_done(&f, layout, spec).unwrap_err();
        assert!(why(&spec, Layout::Json).contains("is a csv sweep file and this run writes json"));
        assert!(why(&small(5, two_of_three), Layout::Csv).contains("another sweep (its keep"));
        assert!(why(&small(4, Shard { index: 0, count: 3 }), Layout::Csv)
            .contains("holds shard 2/3 of this sweep, not shard 1/3"));
        assert!(why(&small(4, Shard::WHOLE), Layout::Csv).contains("not shard 1/1"));
        // Damage: the last line cut off; one digit of a row changed.
        let text = std::fs::read_to_string(&f).unwrap();
        let cut = text.trim_end().rsplit_once('\n').unwrap().0;
        std::fs::write(&f, format!("{cut}\n")).unwrap();
        assert!(why(&spec, Layout::Csv).contains("truncated or damaged"));
        let row = text.lines().nth(6).unwrap();
        let changed = row.replacen(",0.", ",1.", 1);
        assert_ne!(row, changed);
        std::fs::write(&f, text.replacen(row, &changed, 1)).unwrap();
        assert!(why(&spec, Layout::Csv).contains(&f.display().to_string()));
        // Another tool version.
        std::fs::write(&f, text.replacen(TOOL, "bouncemap 0.0.9", 2)).unwrap();
        assert!(why(&spec, Layout::Csv).contains("written by bouncemap 0.0.9"));
        // Not a regular file.
        std::fs::remove_file(&f).unwrap();
        std::fs::create_dir(&f).unwrap();
        assert!(why(&spec, Layout::Csv).contains("not a regular file"));
        // json files are checked the same way.
        let j = d.join("part.json");
        write(&j, &spec, Layout::Json);
        assert!(already_done(&j, Layout::Json, &spec).is_ok());
        let text = std::fs::read_to_string(&j).unwrap();
        std::fs::write(&j, &text[..text.len() - 30]).unwrap();
        assert!(already_done(&j, Layout::Json, &spec)
            .unwrap_err()
            .contains("not a complete sweep json file"));
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// The file written value by value through a small window equals the one written
    /// from every result held in memory at once.
    #[test]
    fn streaming_writes_the_file_a_held_in_memory_writer_writes() {
        for (layout, warm) in [
            (Layout::Csv, Warm::Off),
            (Layout::Json, Warm::Off),
            (Layout::Csv, Warm::Backward),
        ] {
            let mut spec = SweepSpec::new(
                Table::fd(0.1).unwrap(),
                0.45,
                0.8,
                SweepParam::Alpha,
                0.45,
                0.62,
                70,
            );
            spec.transient = 3000;
            spec.keep = 7;
            spec.warm = warm;
            let ex = Executor::new(2).unwrap();
            let header = SweepHeader::from(&spec);
            let mut streamed = SweepWriter::begin(Vec::new(), layout, &header, "1/1", 70).unwrap();
            in_order(&spec, &ex, 3, |r| Ok(streamed.value(r)?)).unwrap();
            let streamed = streamed.end().unwrap();
            let all = bouncemap_engine::sweep::collect(&spec, &ex).unwrap();
            let mut held = SweepWriter::begin(Vec::new(), layout, &header, "1/1", 70).unwrap();
            for r in &all {
                held.value(r).unwrap();
            }
            let held = held.end().unwrap();
            assert_eq!(
                String::from_utf8(streamed).unwrap(),
                String::from_utf8(held).unwrap(),
                "{layout:?} {warm:?}"
            );
        }
    }
}
