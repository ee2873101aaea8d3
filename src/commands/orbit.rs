//! `bouncemap orbit`: iterate the impact map and print one record per event.
//!
//! Records ([`EventRecord`]): index, period (integer part of the time), phase t̂, v
//! (ball velocity after the event), vrel (relative velocity u − f'(t) at contact, ≤ 0),
//! kind (impact | stick | release). Events are written as they are computed. If the
//! ball comes to rest for good, or cannot land, a note says so on stderr and the
//! command still succeeds.

use crate::config;
use crate::config::flags::OrbitArgs;
use crate::output::records::{csv_writer, solver_name, EventRecord, OrbitHeader};
use crate::output::sink::{check_stdout, Sink};
use crate::output::text::significant;
use crate::output::Format;
use bouncemap_engine::{Event, ImpactMap};
use std::io::Write;

pub fn run(args: &OrbitArgs) -> anyhow::Result<()> {
    if let Some(run) = config::run::digits(args)? {
        return super::digits::run(&run);
    }
    let sys = config::system(&args.system)?;
    let state = config::start(&sys, &args.initial)?;
    let mut map = ImpactMap::new(sys, args.solver.into(), state);
    let mut out = Sink::stdout();
    let mut halt = None;
    // A reader that went away ends a long silent stretch too: checked between chunks,
    // so the loop over events is the map's step alone.
    let mut left = args.skip;
    'skip: while left > 0 {
        check_stdout()?;
        let chunk = left.min(1 << 20);
        for _ in 0..chunk {
            if let Err(h) = map.step() {
                halt = Some(h);
                break 'skip;
            }
        }
        left -= chunk;
    }
    let written = (|| -> anyhow::Result<()> {
        let mut records = Records::new(&mut out, args.format, &map)?;
        if halt.is_none() {
            for i in 0..args.bounces {
                match map.step() {
                    Ok(e) => records.event(args.skip + i, &e)?,
                    Err(h) => {
                        halt = Some(h);
                        break;
                    }
                }
            }
        }
        records.finish(halt.as_ref().map(|h| h.to_string()))
    })();
    out.end(written)?;
    if let Some(h) = halt {
        crate::output::to_stderr(&format!("note: {h}\n"));
    }
    Ok(())
}

/// Events in the chosen format.
enum Records<W: Write> {
    Text(W),
    Csv(Box<csv::Writer<W>>),
    Json { out: W, first: bool },
}

impl<W: Write> Records<W> {
    fn new(mut out: W, format: Format, map: &ImpactMap) -> anyhow::Result<Records<W>> {
        Ok(match format {
            Format::Text => {
                writeln!(
                    out,
                    "{:>8} {:>12} {:>18} {:>18} {:>18}  kind",
                    "index", "period", "phase", "v", "vrel"
                )?;
                Records::Text(out)
            }
            Format::Csv => Records::Csv(Box::new(csv_writer(out, &EventRecord::HEADER)?)),
            Format::Json => {
                let s = map.system();
                let head = serde_json::to_string(&OrbitHeader {
                    table: s.table().name(),
                    alpha: s.alpha(),
                    r: s.r(),
                    solver: solver_name(map.solver()),
                })?;
                // The header object, left open for the events array.
                write!(out, "{},\"events\":[", &head[..head.len() - 1])?;
                Records::Json { out, first: true }
            }
        })
    }

    fn event(&mut self, index: u64, e: &Event) -> anyhow::Result<()> {
        match self {
            Records::Text(out) => writeln!(
                out,
                "{index:>8} {:>12} {:>18.15} {:>18} {:>18}  {}",
                e.period,
                e.phase,
                significant(e.v, 15),
                significant(e.vrel, 15),
                e.kind.as_str()
            )?,
            Records::Csv(w) => w.serialize(EventRecord::new(index, e))?,
            Records::Json { out, first } => {
                if !*first {
                    out.write_all(b",")?;
                }
                *first = false;
                serde_json::to_writer(&mut *out, &EventRecord::new(index, e))?;
            }
        }
        Ok(())
    }

    fn finish(self, halt: Option<String>) -> anyhow::Result<()> {
        match self {
            Records::Text(mut out) => out.flush()?,
            Records::Csv(mut w) => w.flush()?,
            Records::Json { mut out, .. } => {
                writeln!(out, "],\"halt\":{}}}", serde_json::to_string(&halt)?)?;
                out.flush()?;
            }
        }
        Ok(())
    }
}
