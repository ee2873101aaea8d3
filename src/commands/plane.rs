//! `bouncemap plane`: a two-parameter map (see [`bouncemap_engine::plane`]), every pixel
//! one pair of parameters classified by its orbit, with the analytic curves.
//!
//! csv: one row per pixel of the shard in index order (x, y, class, period,
//! table_periods, lyapunov, status) with the sweep file's provenance, checksum and end
//! line ([`crate::output::plane_file`]), so shards join with `merge`; json: the same plus
//! the curves; braille: the picture with axes, curves and legend.

use super::progress::Progress;
use crate::config::files::{read_text, LARGE_FILE};
use crate::config::flags::{PlaneArgs, PlaneFormat};
use crate::config::{self, rules, InputError};
use crate::output::part_file::{
    differing_setting, read_part, shard_name, Layout, PartWriter, TOOL,
};
use crate::output::plane_file::{self, CurvesRecord, PlaneFile, PlaneHeader};
use crate::output::plane_map;
use crate::output::sink::Sink;
use crate::output::text::shortest;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::plane::{curves, Plane, PlaneJob, PlaneSpec};
use std::io::Write;
use std::path::Path;
use std::time::Duration;

pub fn run(args: &PlaneArgs) -> anyhow::Result<()> {
    let spec = config::plane::plane_spec(args)?;
    let threads = config::threads(args.threads)?;
    if args.resume {
        let layout = match args.format {
            PlaneFormat::Csv => Some(Layout::Csv),
            PlaneFormat::Json => Some(Layout::Json),
            PlaneFormat::Braille => None,
        };
        let (out, layout) = super::resume_target(layout, args.out.as_deref())?;
        match already_done(Path::new(out), layout, &spec) {
            Ok(done) => {
                eprintln!("bouncemap: --resume: {done}: nothing to compute");
                return Ok(());
            }
            Err(why) => eprintln!("bouncemap: --resume: {why}; computing it"),
        }
    }
    let mut sink = Sink::open(args.out.as_deref()).map_err(InputError)?;
    let plane = compute(&spec, &Executor::new(threads)?)?;
    let curves = curves(&spec);
    let write = |sink: &mut Sink| -> anyhow::Result<()> {
        match args.format {
            PlaneFormat::Csv | PlaneFormat::Json => {
                let layout = if args.format == PlaneFormat::Csv {
                    Layout::Csv
                } else {
                    Layout::Json
                };
                let curves_text = match &curves {
                    Some(c) => serde_json::to_string(&CurvesRecord::from(c))?,
                    None => "null".to_string(),
                };
                let mut w = PartWriter::<_, PlaneFile>::begin(
                    &mut *sink,
                    layout,
                    &PlaneHeader::from(&spec),
                    &shard_name(spec.shard),
                    spec.shard_len(),
                    &[&curves_text],
                )?;
                for row in plane_file::rows(&spec, plane.pixels()) {
                    w.value(&row)?;
                }
                w.end()?;
            }
            PlaneFormat::Braille => {
                let term = crossterm::terminal::size().ok();
                let w = args
                    .width
                    .or(term.map(|t| t.0))
                    .unwrap_or(rules::CELLS.default as u16);
                let h = args
                    .height
                    .or(term.map(|t| t.1.saturating_sub(2)))
                    .unwrap_or(30);
                // Colour on a terminal unless NO_COLOR is set; glyphs in files and pipes.
                use std::io::IsTerminal;
                let colour = args.out.is_none()
                    && std::io::stdout().is_terminal()
                    && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty());
                let lines = plane_map::lines(
                    &spec,
                    &plane,
                    curves.as_ref(),
                    &title(&spec),
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

/// Whether `path` already holds the part of `spec` this run would write, complete and
/// verified (as `merge` checks a part) and of this layout, tool, specification and
/// shard. `Ok` says what is there; `Err` why it must be computed.
fn already_done(path: &Path, layout: Layout, spec: &PlaneSpec) -> Result<String, String> {
    let shown = path.display().to_string();
    if std::fs::symlink_metadata(path).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound) {
        return Err(format!("no {shown} yet"));
    }
    let text = read_text(path, "the existing file", LARGE_FILE).map_err(|e| e.0)?;
    let part = read_part::<PlaneFile>(&shown, &text)?;
    if part.layout != layout {
        return Err(format!("{shown} is a plane file of the other format"));
    }
    if part.provenance.tool != TOOL {
        return Err(format!(
            "{shown} was written by {}, not by this {TOOL}",
            part.provenance.tool
        ));
    }
    let header = PlaneHeader::from(spec);
    if part.header != header {
        return Err(format!(
            "{shown} holds another plane ({} differs from this run's)",
            differing_setting(&part.header, &header)
        ));
    }
    let shard = shard_name(spec.shard);
    if part.provenance.shard != shard {
        return Err(format!(
            "{shown} holds shard {} of this plane, not shard {shard}",
            part.provenance.shard
        ));
    }
    Ok(format!(
        "{shown} already holds shard {shard} of this plane, complete and verified ({} pixels)",
        part.values.len()
    ))
}

/// Run the plane to the end with progress on stderr.
pub fn compute(spec: &PlaneSpec, executor: &Executor) -> anyhow::Result<Plane> {
    let job = PlaneJob::new(spec.clone())?;
    let handle = executor.start(job, &Control::new());
    let mut plane = Plane::new(spec);
    let mut progress = Progress::start_units("plane", "pixels", spec.shard_len(), &title(spec));
    loop {
        match handle.receiver().recv_timeout(Duration::from_millis(200)) {
            Ok(b) => plane.absorb(b.data),
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
        }
        progress.update(&handle.progress());
    }
    let summary = handle.wait();
    progress.finish(&summary.progress);
    if !plane.complete() {
        anyhow::bail!(
            "the plane stopped after {} of {} pixels",
            plane.covered(),
            spec.shard_len()
        );
    }
    Ok(plane)
}

fn title(spec: &PlaneSpec) -> String {
    let axis = |a: &bouncemap_engine::plane::Axis| {
        format!(
            "{} ∈ [{}, {}] ({})",
            a.param.as_str(),
            shortest(a.lo),
            shortest(a.hi),
            a.n
        )
    };
    let table = if spec.table.d().is_some()
        && (spec.x.param.as_str() == "d" || spec.y.param.as_str() == "d")
    {
        "fd".to_string()
    } else {
        spec.table.name().to_string()
    };
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
