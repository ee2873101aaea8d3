//! `bouncemap sweep`: a bifurcation diagram computed headless, written as csv
//! ([`SweepRow`]), json ([`SweepDoc`]) or braille text; presets for the paper's figures;
//! `--shard I/N` parts.

use crate::config::flags::{SweepArgs, SweepFormat};
use crate::config::{self, rules, InputError};
use crate::output::diagram::braille_diagram;
use crate::output::records::{csv_writer, SweepDoc, SweepHeader, SweepRow, SweepValue};
use bouncemap_engine::jobs::{available_cores, Control, Executor};
use bouncemap_engine::sweep::{self, SweepSpec, ValueResult};
use std::io::{self, BufWriter, IsTerminal, Write};
use std::time::Duration;

pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let spec = config::sweep::sweep_spec(args)?;
    let size = braille_size(args);
    let mut out: Box<dyn Write> = match &args.out {
        Some(path) => Box::new(BufWriter::new(
            std::fs::File::create(path)
                .map_err(|e| InputError(format!("--out: cannot create {path}: {e}")))?,
        )),
        None => Box::new(BufWriter::new(io::stdout().lock())),
    };
    let threads = args.threads.unwrap_or_else(available_cores);
    let results = compute(&spec, &Executor::new(threads)?)?;
    match args.format {
        SweepFormat::Csv => write_csv(&mut out, &spec, &results)?,
        SweepFormat::Json => {
            let doc = SweepDoc {
                header: SweepHeader::from(&spec),
                values: results.iter().map(SweepValue::from).collect(),
            };
            serde_json::to_writer(&mut out, &doc)?;
            writeln!(out)?;
        }
        SweepFormat::Braille => {
            for line in braille_diagram(&spec, &results, size.0, size.1) {
                writeln!(out, "{line}")?;
            }
        }
    }
    out.flush()?;
    Ok(())
}

/// Run the sweep, drawing a progress bar on stderr when it is a terminal.
fn compute(spec: &SweepSpec, executor: &Executor) -> anyhow::Result<Vec<ValueResult>> {
    let show = io::stderr().is_terminal();
    let handle = sweep::start(spec.clone(), executor, &Control::new())
        .map_err(|e| InputError(format!("sweep: {e}")))?;
    let mut results = Vec::new();
    loop {
        match handle.receiver().recv_timeout(Duration::from_millis(200)) {
            Ok(b) => {
                if b.complete {
                    results.push(b.data);
                }
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
        }
        if show {
            let p = handle.progress();
            let width = 30;
            let filled = (p.fraction() * width as f64) as usize;
            eprint!(
                "\r\x1b[2Ksweep [{}{}] {}/{} values  {:.2} M events/s  {:.0} s",
                "#".repeat(filled),
                "-".repeat(width - filled),
                p.done,
                p.total,
                p.events_per_second() / 1e6,
                p.elapsed.as_secs_f64()
            );
        }
    }
    if show {
        eprint!("\r\x1b[2K");
    }
    handle.wait();
    results.sort_by_key(|b| b.index);
    Ok(results)
}

fn write_csv<W: Write>(
    out: &mut W,
    spec: &SweepSpec,
    results: &[ValueResult],
) -> anyhow::Result<()> {
    let mut w = csv_writer(out, &SweepRow::header(spec.param))?;
    for r in results {
        for row in SweepRow::rows(r) {
            w.serialize(row)?;
        }
    }
    w.flush()?;
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
