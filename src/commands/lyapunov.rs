//! `bouncemap lyapunov`: both Lyapunov exponents of one orbit, per impact and per table
//! period, with their convergence estimate, their sum beside 2 ln r, and what the orbit
//! settled on (see [`bouncemap_engine::attractors`]).
//!
//! The orbit runs to the end of the transient, stopping early once it has settled on a
//! cycle (the sweep's detector); a cycle's exponents come from the eigenvalues of its
//! Jacobian, any other orbit's from QR over `--impacts` more impacts.
//! `--no-early-stop` always measures by QR (a second method for a cycle's exponents).
//! The measurement streams (memory does not grow with `--impacts`, up to its 1e10), with
//! progress on stderr; a closed standard output or a signal stops it.

use super::progress::Progress;
use crate::config;
use crate::config::run::LyapunovRun;
use crate::output::records::{csv_writer, LyapunovDoc, LyapunovRow};
use crate::output::sink::check_stdout;
use crate::output::sink::Sink;
use crate::output::text::significant;
use crate::output::Format;
use bouncemap_engine::attractors::lyapunov::{Method, Spectrum};
use bouncemap_engine::attractors::{self, Found, Settle};
use bouncemap_engine::jobs::Progress as JobProgress;
use bouncemap_engine::run::{Advance, OrbitRun};
use bouncemap_engine::{ImpactMap, State, System};
use std::io::{self, Write};
use std::time::{Duration, Instant};

pub fn run(run: &LyapunovRun) -> anyhow::Result<()> {
    let LyapunovRun {
        sys,
        start,
        initial,
        settle,
        ..
    } = run;
    let sys = sys.clone();
    if run.check {
        return super::print_plan(&[
            format!(
                "lyapunov of one orbit of table {} at alpha {}, r {}: transient {} periods, then up to {} impacts measured by QR",
                sys.table().name(),
                sys.alpha(),
                sys.r(),
                settle.transient,
                settle.sample
            ),
            // The measurement streams: the orbit, the cells its sample visits (at most
            // a million, whatever the impacts), the process.
            config::memory_plan(
                super::BASE_BYTES
                    + super::WRITER_BYTES
                    + OrbitRun::bytes(1, settle.periodicity)
                    + attractors::identify_bytes(settle.sample),
            ),
            "writes to standard output".into(),
        ]);
    }
    // Standard output is this run's output before the measurement starts, so its
    // progress knows whether the results stream into another program.
    let mut out = Sink::stdout();
    let found = measure(&sys, *start, settle)?;
    let row = LyapunovRow::new(&found, sys.r());
    let written = (|| -> anyhow::Result<()> {
        match run.format {
            Format::Json => {
                let doc = LyapunovDoc {
                    table: sys.table().name(),
                    alpha: sys.alpha(),
                    r: sys.r(),
                    start: initial.clone(),
                    transient: settle.transient,
                    result: row,
                };
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &LyapunovRow::HEADER)?;
                w.serialize(&row)?;
                w.flush()?;
            }
            Format::Text => text(&mut out, &sys, &found, settle.transient)?,
        }
        Ok(())
    })();
    out.end(written)
}

/// Run `start` to the end of its transient, then identify what it settled on (measuring
/// an unsettled orbit by QR over `settle.sample` impacts), with progress on stderr: the
/// impacts measured (none yet during the transient) and the events per second. Memory
/// does not grow with the transient or the sample (the run keeps one point, the QR
/// measurement its sums and block means, the sample the cells it visits). A standard
/// output whose reader has gone stops it (a quiet end).
pub(super) fn measure(sys: &System, start: State, settle: &Settle) -> anyhow::Result<Found> {
    let total = settle.sample as usize;
    let spec = format!(
        "table {}  alpha {}  r {}  transient {} periods  impacts {}",
        sys.table().name(),
        sys.alpha(),
        sys.r(),
        settle.transient,
        settle.sample
    );
    let mut progress = Progress::start_units("lyapunov", "impacts", total, &spec);
    let t0 = Instant::now();
    let mut events = 0u64;
    let mut measured = 0u64;
    let mut last = Instant::now();
    let mut closed = false;
    // Counts `n` more events (measured ones when `measuring`); says whether to stop.
    let mut tick = |n: u64, measuring: bool, progress: &mut Progress| {
        events += n;
        if measuring {
            measured += n;
        }
        if last.elapsed() >= Duration::from_millis(200) {
            last = Instant::now();
            closed = check_stdout().is_err();
            progress.update(&JobProgress {
                done: (measured.min(settle.sample)) as usize,
                total,
                events,
                elapsed: t0.elapsed(),
            });
        }
        closed
    };
    let map = ImpactMap::new(sys.clone(), settle.solver, start);
    let mut run = OrbitRun::new(map, 1, settle.periodicity);
    let end = settle.transient as i64;
    let outcome = match run.advance(end, end, &mut |n| tick(n, false, &mut progress)) {
        Advance::Done(o, _) => Some(o),
        Advance::Checkpoint | Advance::Cancelled => None,
    };
    let found = outcome.and_then(|o| {
        attractors::identify(sys, settle, &o, run.state(), &mut |n| {
            tick(n, true, &mut progress)
        })
    });
    let Some(found) = found else {
        // Only a closed standard output stops the run early.
        return Err(std::io::Error::from(std::io::ErrorKind::BrokenPipe).into());
    };
    progress.finish(&JobProgress {
        done: total,
        total,
        events,
        elapsed: t0.elapsed(),
    });
    Ok(found)
}

fn text(
    out: &mut impl Write,
    sys: &bouncemap_engine::System,
    found: &Found,
    transient: u64,
) -> io::Result<()> {
    writeln!(
        out,
        "table {}  alpha {}  r {}  transient {} periods",
        sys.table().name(),
        sys.alpha(),
        sys.r(),
        transient
    )?;
    let unresolved = found.precision.is_some_and(|p| !p.resolved);
    let period = match (found.events, found.periods) {
        // No cycle length is claimed where rounding decides it.
        _ if unresolved => String::new(),
        (Some(n), Some(k)) => format!(
            " ({n}, {k}): {n} event{} every {k} table period{}",
            if n == 1 { "" } else { "s" },
            if k == 1 { "" } else { "s" }
        ),
        _ => String::new(),
    };
    let kind = match found.kind {
        attractors::Kind::Converging => {
            "converging: periodic, period > 4096 events or transient too short (negative exponent, no cycle found)"
        }
        k => k.as_str(),
    };
    writeln!(out, "orbit: {kind}{period}")?;
    if let Some(p) = found.precision {
        writeln!(out, "cycle: {}", p.describe())?;
        // The run at any precision decides it, on the tables it takes.
        if !p.resolved && bouncemap_engine::precise_takes(sys.table()) {
            let need = (p.growth_decades.ceil() as u32 + 20).max(60);
            writeln!(
                out,
                "  (--digits 30 --max-digits {} decides it at any precision; with --binary-params for the doubles this run has)",
                (2 * need).max(400)
            )?;
        }
    }
    let two_ln_r = 2.0 * sys.r().ln();
    match found.spectrum {
        Some(Spectrum::Finite(e)) => {
            match e.method {
                Method::Cycle => writeln!(
                    out,
                    "exponents from the eigenvalues of the cycle's Jacobian (exact to the cycle's tolerance)"
                )?,
                Method::Qr => writeln!(
                    out,
                    "exponents by QR over {} impacts ({} table periods); ± one standard error over {} blocks",
                    e.impacts,
                    significant(e.periods, 6),
                    attractors::lyapunov::BLOCKS
                )?,
            }
            writeln!(out, "{:>10} {:>20} {:>20} {:>12}", "", "per impact", "per period", "±")?;
            for i in 0..2 {
                writeln!(
                    out,
                    "{:>10} {:>20} {:>20} {:>12}",
                    format!("lambda{}", i + 1),
                    significant(e.per_impact[i], 12),
                    significant(e.per_period[i], 12),
                    if e.method == Method::Qr {
                        significant(e.stderr[i], 2)
                    } else {
                        "0".into()
                    }
                )?;
            }
            writeln!(
                out,
                "{:>10} {:>20}   2 ln r = {}",
                "sum",
                significant(e.per_impact[0] + e.per_impact[1], 12),
                significant(two_ln_r, 12)
            )?;
        }
        Some(Spectrum::Sticking) => writeln!(
            out,
            "both exponents -inf: the ball sticks to the table, which forgets where it landed (superstable)"
        )?,
        Some(Spectrum::Grazing) => writeln!(
            out,
            "no exponents: a landing grazed the table (zero relative velocity), where the Jacobian is unbounded"
        )?,
        None => writeln!(out, "no exponents: the ball did not land")?,
    }
    Ok(())
}
