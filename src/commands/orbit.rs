//! `bouncemap orbit`: iterate the impact map and print one record per event.
//!
//! Records: index, period (integer part of the time), phase t̂, v (ball velocity after
//! the event), vrel (relative velocity u − f'(t) at contact, ≤ 0), kind
//! (impact | stick | release). If the ball comes to rest for good, or cannot land, a
//! note says so on stderr and the command still succeeds.

use super::{initial_state, system_from};
use crate::cli::OrbitArgs;
use crate::engine::{Event, Halt, ImpactMap};
use crate::output::{csv_row, json_num, significant, Format};
use std::io::{self, BufWriter, Write};

pub fn run(args: &OrbitArgs) -> anyhow::Result<()> {
    let sys = system_from(&args.system)?;
    let state = initial_state(&sys, &args.initial)?;
    let mut map = ImpactMap::new(sys, args.solver.into(), state);
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut halt = None;
    for _ in 0..args.skip {
        if let Err(h) = map.step() {
            halt = Some(h);
            break;
        }
    }
    match args.format {
        Format::Text => writeln!(
            out,
            "{:>8} {:>12} {:>18} {:>18} {:>18}  kind",
            "index", "period", "phase", "v", "vrel"
        )?,
        Format::Csv => csv_row(
            &mut out,
            &["index", "period", "phase", "v", "vrel", "kind"].map(String::from),
        )?,
        Format::Json => {
            let s = map.system();
            write!(
                out,
                "{{\"table\":{},\"alpha\":{},\"r\":{},\"solver\":\"{}\",\"events\":[",
                serde_json::Value::String(s.table.name().to_string()),
                json_num(s.alpha),
                json_num(s.r),
                if map.solver() == crate::engine::Solver::Exact {
                    "exact"
                } else {
                    "grid"
                }
            )?
        }
    }
    let mut index = args.skip;
    if halt.is_none() {
        for i in 0..args.bounces {
            match map.step() {
                Ok(e) => write_event(&mut out, args.format, index, &e, i == 0)?,
                Err(h) => {
                    halt = Some(h);
                    break;
                }
            }
            index += 1;
        }
    }
    if args.format == Format::Json {
        let h = halt.map_or(serde_json::Value::Null, |h| {
            serde_json::Value::String(h.to_string())
        });
        writeln!(out, "],\"halt\":{h}}}")?;
    }
    out.flush()?;
    if let Some(h) = halt {
        note_halt(&h);
    }
    Ok(())
}

fn note_halt(h: &Halt) {
    eprintln!("note: {h}");
}

fn write_event<W: Write>(
    out: &mut W,
    format: Format,
    index: u64,
    e: &Event,
    first: bool,
) -> io::Result<()> {
    match format {
        Format::Text => writeln!(
            out,
            "{index:>8} {:>12} {:>18.15} {:>18} {:>18}  {}",
            e.period,
            e.phase,
            significant(e.v, 15),
            significant(e.vrel, 15),
            e.kind.as_str()
        ),
        Format::Csv => csv_row(
            out,
            &[
                index.to_string(),
                e.period.to_string(),
                e.phase.to_string(),
                e.v.to_string(),
                e.vrel.to_string(),
                e.kind.as_str().to_string(),
            ],
        ),
        Format::Json => {
            let rec = serde_json::json!({
                "index": index,
                "period": e.period,
                "phase": json_num(e.phase),
                "v": json_num(e.v),
                "vrel": json_num(e.vrel),
                "kind": e.kind.as_str(),
            });
            write!(out, "{}{}", if first { "" } else { "," }, rec)
        }
    }
}
