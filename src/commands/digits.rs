//! `orbit --digits N`: the orbit at any precision, printed only as far as it holds. The
//! engine runs it at two precisions and compares them event by event
//! ([`bouncemap_engine::orbit_to_digits`]); each event is printed from the more precise
//! run to the significant digits on which the two agree (at most N), and the output
//! stops at the first event that does not hold to N digits at the most precision
//! allowed, saying what it would need.
//!
//! The parameters are the decimals written (each flag's double read back as its shortest
//! decimal), rounded once to the working precision; with `--binary-params` the doubles
//! themselves.

use crate::config::run::DigitsRun;
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::{
    orbit_to_digits, Big, DigitsOrbit, Number, PreciseState, PreciseSystem, Real,
};
use serde_json::json;
use std::io::Write;

/// The system and start of `run` at `bits`.
fn make(run: &DigitsRun, bits: usize) -> (PreciseSystem<Big>, PreciseState<Big>) {
    let num = |x: f64| {
        if run.binary {
            Big::from_f64(x, &bits)
        } else {
            // The shortest decimal that reads back as this double: the number written.
            Big::from_decimal(&format!("{x}"), &bits).expect("a finite decimal")
        }
    };
    let params: Vec<Big> = run.params.iter().map(|&x| num(x)).collect();
    let pieces = run
        .family
        .pieces_in(&params, &bits)
        .expect("checked piecewise when settled");
    let sys = PreciseSystem::new(pieces, num(run.alpha), num(run.r), bits)
        .expect("checked of degree ≤ 3 when settled");
    let t0 = num(run.t0);
    let w = match run.v0 {
        Some(v0) => num(v0) - sys.jet(&t0)[1].clone(),
        None => num(bouncemap_engine::DEFAULT_HOP),
    };
    let st = PreciseState::launch(&sys, 0, t0, w);
    (sys, st)
}

pub fn run(run: &DigitsRun) -> anyhow::Result<()> {
    let orbit = orbit_to_digits(
        &|bits| make(run, bits),
        run.digits,
        run.max_digits,
        run.skip,
        run.bounces,
    );
    let shown = orbit.first_short(run.digits).unwrap_or(orbit.events.len());
    let mut out = Sink::stdout();
    let written = write(&mut out, run, &orbit, shown);
    out.end(written)?;
    if let Some(note) = note(run, &orbit, shown) {
        crate::output::to_stderr(&format!("note: {note}\n"));
    }
    Ok(())
}

/// What was not decided, if anything: events left out, or the map's halt.
fn note(run: &DigitsRun, orbit: &DigitsOrbit, shown: usize) -> Option<String> {
    if shown < orbit.events.len() {
        let index = run.skip + shown as u64;
        let need = orbit.loss_per_event.map_or(String::new(), |rate| {
            let total = (run.skip + run.bounces) as f64;
            format!(
                "; by the measured loss of {rate:.2} digits per event, all {} events need about {} digits",
                run.skip + run.bounces,
                (run.digits as f64 + rate * total).ceil()
            )
        });
        return Some(format!(
            "events from index {index} on do not hold to {} digits at {} digits of working precision (compared with {}), so they are not printed{need}; raise --max-digits (now {}) or ask for fewer events",
            run.digits, orbit.precision.0, orbit.precision.1, run.max_digits
        ));
    }
    orbit
        .halt
        .as_ref()
        .map(|h| format!("the orbit stops there: {h:?}"))
}

fn write(out: &mut Sink, run: &DigitsRun, orbit: &DigitsOrbit, shown: usize) -> anyhow::Result<()> {
    let events = &orbit.events[..shown];
    let text = |x: &Big, d: u32| x.to_digits(d as usize);
    let vrel = |e: &bouncemap_engine::PreciseEvent<Big>, d: u32| {
        if e.kind == bouncemap_engine::EventKind::Impact {
            text(&e.vrel, d)
        } else {
            "0".to_string()
        }
    };
    match run.format {
        Format::Text => {
            writeln!(
                out,
                "table {}  alpha {}  r {}  parameters {}  digits {} (working precision {} and {} digits)",
                run.table,
                run.alpha,
                run.r,
                if run.binary { "as doubles" } else { "as written" },
                run.digits,
                orbit.precision.0,
                orbit.precision.1
            )?;
            for (i, (e, d)) in events.iter().enumerate() {
                writeln!(
                    out,
                    "{:>8} {:>12} {:>7}  phase {}  v {}  vrel {}  ({d} digits)",
                    run.skip + i as u64,
                    e.period,
                    e.kind.as_str(),
                    text(&e.phase, *d),
                    text(&e.v, *d),
                    vrel(e, *d)
                )?;
            }
        }
        Format::Csv => {
            writeln!(out, "index,period,phase,v,vrel,kind,digits")?;
            for (i, (e, d)) in events.iter().enumerate() {
                writeln!(
                    out,
                    "{},{},{},{},{},{},{d}",
                    run.skip + i as u64,
                    e.period,
                    text(&e.phase, *d),
                    text(&e.v, *d),
                    vrel(e, *d),
                    e.kind.as_str()
                )?;
            }
        }
        Format::Json => {
            let doc = json!({
                "table": run.table,
                "alpha": run.alpha,
                "r": run.r,
                "parameters": if run.binary { "doubles" } else { "decimals" },
                "digits": run.digits,
                "working_digits": [orbit.precision.0, orbit.precision.1],
                "events": events.iter().enumerate().map(|(i, (e, d))| json!({
                    "index": run.skip + i as u64,
                    "period": e.period,
                    "phase": text(&e.phase, *d),
                    "v": text(&e.v, *d),
                    "vrel": vrel(e, *d),
                    "kind": e.kind.as_str(),
                    "digits": d,
                })).collect::<Vec<_>>(),
                "complete": shown == orbit.events.len() && orbit.halt.is_none(),
                "note": note(run, orbit, shown),
            });
            serde_json::to_writer(&mut *out, &doc)?;
            writeln!(out)?;
        }
    }
    Ok(())
}
