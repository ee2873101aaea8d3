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
use crate::output::text::significant;
use crate::output::Format;
use bouncemap_engine::{Event, ImpactMap};
use std::io::{self, BufWriter, Write};

pub fn run(args: &OrbitArgs) -> anyhow::Result<()> {
    let sys = config::system(&args.system)?;
    let state = config::start(&sys, &args.initial)?;
    let mut map = ImpactMap::new(sys, args.solver.into(), state);
    let mut halt = None;
    for _ in 0..args.skip {
        if let Err(h) = map.step() {
            halt = Some(h);
            break;
        }
    }
    let out = BufWriter::new(io::stdout().lock());
    let mut sink = Sink::new(out, args.format, &map)?;
    if halt.is_none() {
        for i in 0..args.bounces {
            match map.step() {
                Ok(e) => sink.event(args.skip + i, &e)?,
                Err(h) => {
                    halt = Some(h);
                    break;
                }
            }
        }
    }
    sink.finish(halt.map(|h| h.to_string()))?;
    if let Some(h) = halt {
        eprintln!("note: {h}");
    }
    Ok(())
}

/// Where events go, in the chosen format.
enum Sink<W: Write> {
    Text(W),
    Csv(Box<csv::Writer<W>>),
    Json { out: W, first: bool },
}

impl<W: Write> Sink<W> {
    fn new(mut out: W, format: Format, map: &ImpactMap) -> anyhow::Result<Sink<W>> {
        Ok(match format {
            Format::Text => {
                writeln!(
                    out,
                    "{:>8} {:>12} {:>18} {:>18} {:>18}  kind",
                    "index", "period", "phase", "v", "vrel"
                )?;
                Sink::Text(out)
            }
            Format::Csv => Sink::Csv(Box::new(csv_writer(out, &EventRecord::HEADER)?)),
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
                Sink::Json { out, first: true }
            }
        })
    }

    fn event(&mut self, index: u64, e: &Event) -> anyhow::Result<()> {
        match self {
            Sink::Text(out) => writeln!(
                out,
                "{index:>8} {:>12} {:>18.15} {:>18} {:>18}  {}",
                e.period,
                e.phase,
                significant(e.v, 15),
                significant(e.vrel, 15),
                e.kind.as_str()
            )?,
            Sink::Csv(w) => w.serialize(EventRecord::new(index, e))?,
            Sink::Json { out, first } => {
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
            Sink::Text(mut out) => out.flush()?,
            Sink::Csv(mut w) => w.flush()?,
            Sink::Json { mut out, .. } => {
                writeln!(out, "],\"halt\":{}}}", serde_json::to_string(&halt)?)?;
                out.flush()?;
            }
        }
        Ok(())
    }
}
