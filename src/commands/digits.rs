//! `orbit --digits N` and `lyapunov --digits N`: the orbit at any precision, printed only as far as it holds. The
//! engine runs it at two precisions and compares them event by event
//! ([`bouncemap_engine::orbit_to_digits`]); each event is printed from the more precise
//! run to the significant digits on which the two agree (at most N), and the output
//! stops at the first event that does not hold to N digits at the most precision
//! allowed, saying what it would need.
//!
//! The parameters are the decimals written (the texts typed for α, r and the start, the
//! other flags' doubles read back as their shortest decimals), rounded once to the
//! working precision; with `--binary-params` the doubles themselves.

use super::progress::Progress;
use crate::config::run::{DigitsRun, LyapunovDigits};
use crate::output::records::{cycle_text, CycleRecord};
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::{
    orbit_to_digits, sticking_cycle_to_digits, Big, CycleVerdict, DigitsOrbit, DigitsProgress,
    Real, CYCLE_EVENTS,
};
use serde_json::json;
use std::io::Write;

pub fn run(run: &DigitsRun) -> anyhow::Result<()> {
    let total = run.skip.saturating_add(run.bounces);
    // Standard output is the output before the work starts: progress then knows whether
    // the results stream into another program.
    let mut out = Sink::stdout();
    let mut report = Reporter::new(
        "orbit",
        total,
        &format!(
            "{}  alpha {}  r {}  {} events to {} digits",
            run.spec.table, run.spec.written.0, run.spec.written.1, total, run.spec.digits
        ),
    );
    let orbit = orbit_to_digits(
        &|bits| run.spec.make(bits),
        run.spec.digits,
        run.spec.max_digits,
        run.skip,
        run.bounces,
        &mut |p| report.update(p),
    );
    report.finish();
    let shown = orbit
        .first_short(run.spec.digits)
        .unwrap_or(orbit.events.len());
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
                (run.spec.digits as f64 + rate * total).ceil()
            )
        });
        return Some(format!(
            "events from index {index} on do not hold to {} digits at {} digits of working precision (compared with {}), so they are not printed{need}; raise --max-digits (now {}) or ask for fewer events",
            run.spec.digits, orbit.precision.0, orbit.precision.1, run.spec.max_digits
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
                run.spec.table,
                run.spec.written.0,
                run.spec.written.1,
                if run.spec.binary { "as doubles" } else { "as written" },
                run.spec.digits,
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
                "table": run.spec.table,
                "alpha": run.spec.alpha,
                "r": run.spec.r,
                "alpha_written": run.spec.written.0,
                "r_written": run.spec.written.1,
                "parameters": if run.spec.binary { "doubles" } else { "decimals" },
                "digits": run.spec.digits,
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

/// Progress on stderr as the runs go (the bar on a terminal, lines in a batch log): the
/// events of the run and the digits it runs at. `total` is what a run computes at most.
pub(super) struct Reporter {
    progress: Progress,
    start: std::time::Instant,
    total: u64,
    last: Option<bouncemap_engine::jobs::Progress>,
}

impl Reporter {
    pub(super) fn new(what: &'static str, total: u64, spec: &str) -> Reporter {
        Reporter {
            progress: Progress::start_units(what, "events", total as usize, spec),
            start: std::time::Instant::now(),
            total,
            last: None,
        }
    }

    pub(super) fn update(&mut self, p: DigitsProgress) {
        let job = bouncemap_engine::jobs::Progress {
            done: p.done as usize,
            total: if p.total == 0 { self.total } else { p.total } as usize,
            events: p.done,
            elapsed: self.start.elapsed(),
        };
        self.progress
            .update_noting(&job, &format!("  at {} digits", p.digits));
        self.last = Some(job);
    }

    pub(super) fn finish(self) {
        if let Some(mut last) = self.last {
            // What was computed is all there was to compute.
            last.total = last.done;
            self.progress.finish(&last);
        }
    }
}

/// `lyapunov --digits N`: the sticking cycle of the orbit decided at any precision
/// ([`sticking_cycle_to_digits`]): its length in table periods, where it is released
/// and how long after the release it sticks, to the digits the two precisions agree on;
/// or what could not be decided, and the digits it would need.
pub fn lyapunov(run: &LyapunovDigits) -> anyhow::Result<()> {
    let spec = &run.spec;
    // Standard output is the output before the work starts: progress then knows whether
    // the results stream into another program.
    let mut out = Sink::stdout();
    let mut report = Reporter::new(
        "lyapunov",
        CYCLE_EVENTS,
        &format!(
            "{}  alpha {}  r {}  sticking cycle to {} digits, within {CYCLE_EVENTS} events a run",
            spec.table, spec.written.0, spec.written.1, spec.digits
        ),
    );
    let verdict = sticking_cycle_to_digits(
        &|bits| spec.make(bits),
        spec.digits,
        spec.max_digits,
        CYCLE_EVENTS,
        i64::try_from(run.transient).unwrap_or(i64::MAX),
        &mut |p| {
            report.update(p);
            std::ops::ControlFlow::Continue(())
        },
    );
    report.finish();
    // (Only a progress report that asks to stop ends it without a verdict.)
    let Some(verdict) = verdict else {
        anyhow::bail!("the run at any precision stopped without a verdict");
    };
    let params = if spec.binary {
        "as doubles"
    } else {
        "as written"
    };
    let written = (|| -> anyhow::Result<()> {
        match run.format {
            Format::Text => {
                writeln!(
                    out,
                    "table {}  alpha {}  r {}  parameters {params}  digits {}",
                    spec.table, spec.written.0, spec.written.1, spec.digits
                )?;
                writeln!(
                    out,
                    "{}",
                    cycle_text(&verdict, spec.digits, spec.max_digits, run.transient)
                )?;
                if matches!(verdict, CycleVerdict::Found(_)) {
                    writeln!(
                        out,
                        "both exponents -inf: the ball sticks to the table, which forgets where it landed (superstable)"
                    )?;
                }
            }
            Format::Csv => {
                writeln!(
                    out,
                    "table,alpha,r,parameters,digits,verdict,periods,releases,release_phase,stick_after,agreed_digits,need_digits"
                )?;
                let row = CycleRecord::of(&verdict);
                let cell = |x: Option<String>| x.unwrap_or_default();
                writeln!(
                    out,
                    "{},{},{},{},{},{},{},{},{},{},{},{}",
                    spec.table,
                    spec.written.0,
                    spec.written.1,
                    if spec.binary { "doubles" } else { "decimals" },
                    spec.digits,
                    row.verdict,
                    cell(row.periods.map(|x| x.to_string())),
                    cell(row.releases.map(|x| x.to_string())),
                    cell(row.release_phase),
                    cell(row.stick_after),
                    cell(row.agreed_digits.map(|x| x.to_string())),
                    cell(row.need_digits.map(|x| x.to_string()))
                )?;
            }
            Format::Json => {
                let row = CycleRecord::of(&verdict);
                let doc = json!({
                    "table": spec.table,
                    "alpha": spec.alpha,
                    "r": spec.r,
                    "alpha_written": spec.written.0,
                    "r_written": spec.written.1,
                    "parameters": if spec.binary { "doubles" } else { "decimals" },
                    "digits": spec.digits,
                    "start": run.initial,
                    "verdict": row.verdict,
                    "periods": row.periods,
                    "releases": row.releases,
                    "release_phase": row.release_phase,
                    "stick_after": row.stick_after,
                    "agreed_digits": row.agreed_digits,
                    "need_digits": row.need_digits,
                    "text": cycle_text(&verdict, spec.digits, spec.max_digits, run.transient),
                });
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
        }
        Ok(())
    })();
    out.end(written)
}
