//! `bouncemap sweep`: a bifurcation diagram computed headless, written as csv or json
//! (the sweep file of [`crate::output::sweep_file`], with its provenance) or as braille
//! text; presets for the paper's figures; `--shard I/N` parts.
//!
//! Values are computed in index order and written as they complete, through a window
//! that keeps at most [`WINDOW_BYTES`] of results in flight: memory does not grow with
//! the number of values.

use super::progress::Progress;
use crate::config::flags::{SweepArgs, SweepFormat};
use crate::config::{self, check_memory, rules, InputError};
use crate::output::diagram::BrailleDiagram;
use crate::output::records::SweepHeader;
use crate::output::sink::Sink;
use crate::output::sweep_file::{shard_name, Layout, SweepWriter};
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::sweep::{chain_len, SweepJob, SweepSpec, ValueResult};
use std::collections::BTreeMap;
use std::io::Write;
use std::time::Duration;

/// Results held in flight at most, in bytes (the window of values ahead of the writer).
pub const WINDOW_BYTES: u64 = 64 << 20;

/// Bytes one value's result takes: its points and their bookkeeping.
fn value_bytes(keep: usize) -> u64 {
    keep as u64 * 24 + 256
}

pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let spec = config::sweep::sweep_spec(args)?;
    let threads = config::threads(args.threads)?;
    // Values in flight: as many as the budget holds, at least two per worker.
    let per_value = value_bytes(spec.keep);
    let window = (WINDOW_BYTES / per_value).clamp(2 * threads as u64, 1 << 16) as usize;
    // Per worker: its value's ring of kept events and the periodicity detector.
    let max_period = spec.periodicity.map_or(0, |p| p.max_period) as u64;
    let per_worker =
        spec.keep as u64 * 32 + (2 * (64 + max_period) + max_period).next_power_of_two() * 32;
    check_memory(
        window as u64 * per_value + threads as u64 * per_worker,
        "this sweep",
    )?;
    let mut sink = Sink::open(args.out.as_deref()).map_err(InputError)?;
    let executor = Executor::new(threads)?;
    let result = match args.format {
        SweepFormat::Csv => stream(&spec, &executor, window, &mut sink, Layout::Csv),
        SweepFormat::Json => stream(&spec, &executor, window, &mut sink, Layout::Json),
        SweepFormat::Braille => braille(&spec, &executor, window, &mut sink, braille_size(args)),
    };
    result.map_err(|e| sink.describe(e))?;
    sink.finish()
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
        crate::output::sweep_file::spec_text(&SweepHeader::from(spec)),
        shard_name(spec.shard)
    );
    let mut progress = Progress::start("sweep", values, &spec_line);
    let mut pending: BTreeMap<usize, ValueResult> = BTreeMap::new();
    let mut next = 0usize;
    loop {
        match handle.receiver().recv_timeout(Duration::from_millis(200)) {
            Ok(b) if b.complete => {
                pending.insert(b.index, b.data);
                while next < values {
                    let Some(r) = pending.remove(&positions.value_index(next)) else {
                        break;
                    };
                    each(&r)?;
                    next += 1;
                    handle.ack(next / per_item);
                }
            }
            Ok(_) | Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
        }
        progress.update(&handle.progress());
    }
    let summary = handle.wait();
    progress.finish(&summary.progress);
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

fn braille_size(args: &SweepArgs) -> (u16, u16) {
    let term = crossterm::terminal::size().ok();
    let w = args
        .width
        .or(term.map(|t| t.0))
        .or_else(|| std::env::var("COLUMNS").ok().and_then(|c| c.parse().ok()))
        .unwrap_or(rules::CELLS.default as u16);
    let h = args
        .height
        .or(term.map(|t| t.1.saturating_sub(2)))
        .unwrap_or(30);
    (w.max(20), h.max(6))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::sweep::{SweepParam, Warm};
    use bouncemap_engine::Table;

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
