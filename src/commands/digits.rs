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
use bouncemap_engine::attractors::lyapunov::Spectrum;
use bouncemap_engine::attractors::{Found, Kind};
use bouncemap_engine::{
    cycles_near, impact_cycle_to_digits, orbit_to_digits, sticking_cycle_to_digits, Agreed, Big,
    CycleVerdict, DigitsOrbit, DigitsProgress, ImpactCycle, ImpactCycleVerdict, Real, Stability,
    CYCLE_EVENTS,
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
                run.spec.read_as(),
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
                "parameters": run.spec.parameters(),
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

/// `lyapunov --digits N`: what the orbit settles on (by the f64 run), at any precision.
/// A cycle of impacts is solved by Newton's method at two precisions
/// ([`impact_cycle_to_digits`]): its launch, multipliers and exponents to the digits both
/// agree on. Otherwise the sticking cycle is decided ([`sticking_cycle_to_digits`]):
/// its length in table periods, where it is released and how long after the release it
/// sticks; or what could not be decided, and the digits it would need.
pub fn lyapunov(run: &LyapunovDigits) -> anyhow::Result<()> {
    let spec = &run.spec;
    // Standard output is the output before the work starts: progress then knows whether
    // the results stream into another program.
    let mut out = Sink::stdout();
    let double = &run.double;
    let found = super::lyapunov::measure(&double.sys, double.start, &double.settle)?;
    if let Some((n, k, point)) = impacts_only(&found) {
        let verdict = solve_impact_cycle(run, n, k, point)?;
        let origin = "the cycle of impacts the orbit settles on (double precision)";
        return impact_cycle(run, &verdict, (n, k), origin, out);
    }
    // An orbit that did not settle in double precision but does not grow either (next
    // to a bifurcation a multiplier is near the unit circle and the orbit converges too
    // slowly): the stable cycle of impacts next to its end, if the precision decides one.
    if let (Kind::Unsettled | Kind::Converging, Some(point)) = (found.kind, found.point) {
        let mut first = None;
        for c in cycles_near(&double.sys, point.0, point.1, NEAR_EVENTS) {
            let launch = (c.phases[0], c.velocities[0]);
            let verdict = solve_impact_cycle(run, c.n, c.k, launch)?;
            let stable = matches!(&verdict, ImpactCycleVerdict::Found(f) if f.stability == Stability::Stable);
            if stable {
                first = Some((verdict, c.n, c.k, true));
                break;
            }
            if first.is_none() && matches!(verdict, ImpactCycleVerdict::Found(_)) {
                first = Some((verdict, c.n, c.k, false));
            }
        }
        if let Some((verdict, n, k, stable)) = first {
            let unsettled = format!(
                "the cycle of impacts next to the orbit's end, which double precision did not settle on ({}{})",
                found.kind.as_str(),
                found
                    .lyapunov()
                    .map_or(String::new(), |l| format!(", largest exponent by QR {}", crate::output::text::significant(l, 3)))
            );
            let origin = if stable {
                unsettled
            } else {
                format!("{unsettled}; no stable cycle of up to {NEAR_EVENTS} impacts is next to it")
            };
            return impact_cycle(run, &verdict, (n, k), &origin, out);
        }
    }
    let verdict = reported(
        CYCLE_EVENTS,
        &format!(
            "{}  alpha {}  r {}  sticking cycle to {} digits, within {CYCLE_EVENTS} events a run",
            spec.table, spec.written.0, spec.written.1, spec.digits
        ),
        |progress| {
            sticking_cycle_to_digits(
                &|bits| spec.make(bits),
                spec.digits,
                spec.max_digits,
                CYCLE_EVENTS,
                i64::try_from(run.transient).unwrap_or(i64::MAX),
                progress,
            )
        },
    )?;
    let written = (|| -> anyhow::Result<()> {
        match run.format {
            Format::Text => {
                writeln!(out, "{}", heading(spec))?;
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
                writeln!(out, "{LYAPUNOV_CSV}")?;
                let row = CycleRecord::of(&verdict);
                let cell = |x: Option<String>| x.unwrap_or_default();
                // (The columns of a cycle of impacts empty.)
                writeln!(
                    out,
                    "{},{},{},{},{},{},{},{},{},{},{},{},,,,,,,,,",
                    spec.table,
                    spec.written.0,
                    spec.written.1,
                    spec.parameters(),
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
                    "parameters": spec.parameters(),
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

/// (n, k, launch) of the cycle of impacts the f64 orbit settled on, if it did (not a
/// sticking cycle, which has no finite exponents).
fn impacts_only(found: &Found) -> Option<(usize, u32, (f64, f64))> {
    match (
        found.kind,
        found.spectrum,
        found.events,
        found.periods,
        found.point,
    ) {
        (Kind::Periodic, Some(Spectrum::Finite(_)), Some(n), Some(k), Some(point)) => {
            Some((n, u32::try_from(k).ok().filter(|k| *k > 0)?, point))
        }
        _ => None,
    }
}

/// The csv header of `lyapunov --digits`: the sticking cycle's fields, then a cycle of
/// impacts' (each filled for its own kind of verdict).
const LYAPUNOV_CSV: &str = "table,alpha,r,parameters,digits,verdict,periods,releases,release_phase,stick_after,agreed_digits,need_digits,events,phase,v,multiplier1,multiplier2,complex,lambda1,lambda2,stability";

/// The most impacts of a cycle looked for next to the end of an orbit that did not
/// settle.
const NEAR_EVENTS: usize = 64;

/// The (n, k) cycle of impacts through `point` (a double's launch) solved at two
/// precisions ([`impact_cycle_to_digits`]), with progress on stderr.
fn solve_impact_cycle(
    run: &LyapunovDigits,
    n: usize,
    k: u32,
    point: (f64, f64),
) -> anyhow::Result<ImpactCycleVerdict> {
    let spec = &run.spec;
    // What one pair of precisions computes at most: Newton's passes at both.
    let bound = 2 * (bouncemap_engine::NEWTON_STEPS as u64 + 1) * n as u64;
    reported(
        bound,
        &format!(
            "{}  alpha {}  r {}  the ({n}, {k}) cycle of impacts to {} digits",
            spec.table, spec.written.0, spec.written.1, spec.digits
        ),
        |progress| {
            impact_cycle_to_digits(
                &|bits| spec.make(bits),
                n,
                k,
                point,
                spec.digits,
                spec.max_digits,
                progress,
            )
        },
    )
}

/// `lyapunov --digits`' `work` run with its progress on stderr (`total` events at most,
/// `spec` saying what it computes): its verdict.
fn reported<T>(
    total: u64,
    spec: &str,
    work: impl FnOnce(&mut dyn FnMut(DigitsProgress) -> std::ops::ControlFlow<()>) -> Option<T>,
) -> anyhow::Result<T> {
    let mut report = Reporter::new("lyapunov", total, spec);
    let verdict = work(&mut |p| {
        report.update(p);
        std::ops::ControlFlow::Continue(())
    });
    report.finish();
    // (Only a progress report that asks to stop ends it without a verdict.)
    verdict.ok_or_else(|| anyhow::anyhow!("the run at any precision stopped without a verdict"))
}

/// `lyapunov --digits` on a cycle of impacts (`origin` says which): printed to the
/// digits the two precisions agree on, with the identity det M = r²ⁿ (the exponents' sum
/// 2 ln r) as evidence.
fn impact_cycle(
    run: &LyapunovDigits,
    verdict: &ImpactCycleVerdict,
    (n, k): (usize, u32),
    origin: &str,
    mut out: Sink,
) -> anyhow::Result<()> {
    let spec = &run.spec;
    let parameters = spec.parameters();
    let text = |a: &Agreed| a.value.to_digits(a.digits.max(1) as usize);
    // Exponents per table period: per impact times n/k.
    let per_period = |a: &Agreed| Agreed {
        value: a.value.clone() * Big::from_f64(n as f64, &a.value.context())
            / Big::from_f64(f64::from(k), &a.value.context()),
        digits: a.digits,
    };
    let stability = |c: &ImpactCycle| c.stability.as_str();
    let found = match verdict {
        ImpactCycleVerdict::Found(c) => Some(&**c),
        _ => None,
    };
    let (name, agreed, need) = match verdict {
        ImpactCycleVerdict::Found(c) => ("periodic", Some(c.digits()), None),
        ImpactCycleVerdict::Undecided { agreed, need, .. } => {
            ("periodic_undecided", Some(*agreed), Some(*need))
        }
        ImpactCycleVerdict::Lost { .. } => ("periodic_lost", None, None),
    };
    let summary = impact_text(verdict, n, k, origin, spec.digits, spec.max_digits);
    let written = (|| -> anyhow::Result<()> {
        match run.format {
            Format::Text => {
                writeln!(out, "{}", heading(spec))?;
                writeln!(out, "{summary}")?;
                if let Some(c) = found {
                    writeln!(
                        out,
                        "launch: phase {}  v {}  (right after an impact)",
                        text(&c.phase),
                        text(&c.v)
                    )?;
                    if c.complex {
                        writeln!(
                            out,
                            "multipliers: a complex pair {} ± {} i, of modulus r^{n}",
                            text(&c.multipliers[0]),
                            text(&c.multipliers[1]),
                        )?;
                    } else {
                        writeln!(
                            out,
                            "multipliers: real, {} and {}",
                            text(&c.multipliers[0]),
                            text(&c.multipliers[1])
                        )?;
                    }
                    let sign = if c.margin < 0.0 { "-" } else { "+" };
                    writeln!(
                        out,
                        "{}: the largest |multiplier| is 1 {sign} {:.2e}{}",
                        stability(c),
                        c.margin.abs(),
                        match c.stability {
                            Stability::Undecided => ", within the difference of the two runs",
                            _ => "",
                        }
                    )?;
                    writeln!(out, "exponents per impact:")?;
                    for (i, e) in c.exponents.iter().enumerate() {
                        writeln!(out, "   lambda{}  {}", i + 1, text(e))?;
                    }
                    let sum = c.exponents[0].value.clone() + c.exponents[1].value.clone();
                    let digits = c.exponents[0].digits.min(c.exponents[1].digits);
                    writeln!(
                        out,
                        "       sum  {}  (2 ln r = {})",
                        sum.to_digits(digits as usize),
                        c.two_ln_r.to_digits(digits as usize)
                    )?;
                    if n as u32 != k {
                        writeln!(out, "exponents per table period (x {n}/{k}):")?;
                        for (i, e) in c.exponents.iter().enumerate() {
                            writeln!(out, "   lambda{}  {}", i + 1, text(&per_period(e)))?;
                        }
                    }
                    writeln!(
                        out,
                        "evidence: det M / r^{} - 1 = {:.1e}; return residual {:.1e}; smallest landing speed |u| {}",
                        2 * n,
                        c.det_error,
                        c.residual,
                        crate::output::text::significant(c.min_speed, 6)
                    )?;
                }
            }
            Format::Csv => {
                writeln!(out, "{LYAPUNOV_CSV}")?;
                let cell = |x: Option<String>| x.unwrap_or_default();
                let f = |g: &dyn Fn(&ImpactCycle) -> String| cell(found.map(g));
                writeln!(
                    out,
                    "{},{},{},{parameters},{},{name},{k},,,,{},{},{n},{},{},{},{},{},{},{},{}",
                    spec.table,
                    spec.written.0,
                    spec.written.1,
                    spec.digits,
                    cell(agreed.map(|x| x.to_string())),
                    cell(need.map(|x| x.to_string())),
                    f(&|c| text(&c.phase)),
                    f(&|c| text(&c.v)),
                    f(&|c| text(&c.multipliers[0])),
                    f(&|c| text(&c.multipliers[1])),
                    f(&|c| c.complex.to_string()),
                    f(&|c| text(&c.exponents[0])),
                    f(&|c| text(&c.exponents[1])),
                    f(&|c| stability(c).to_string()),
                )?;
            }
            Format::Json => {
                let doc = json!({
                    "table": spec.table,
                    "alpha": spec.alpha,
                    "r": spec.r,
                    "alpha_written": spec.written.0,
                    "r_written": spec.written.1,
                    "parameters": parameters,
                    "digits": spec.digits,
                    "start": run.initial,
                    "verdict": name,
                    "events": n,
                    "periods": k,
                    "agreed_digits": agreed,
                    "need_digits": need,
                    "phase": found.map(|c| text(&c.phase)),
                    "v": found.map(|c| text(&c.v)),
                    "multipliers": found.map(|c| [text(&c.multipliers[0]), text(&c.multipliers[1])]),
                    "complex": found.map(|c| c.complex),
                    "lambda1": found.map(|c| text(&c.exponents[0])),
                    "lambda2": found.map(|c| text(&c.exponents[1])),
                    "lambda1_per_period": found.map(|c| text(&per_period(&c.exponents[0]))),
                    "lambda2_per_period": found.map(|c| text(&per_period(&c.exponents[1]))),
                    "two_ln_r": found.map(|c| c.two_ln_r.to_digits(spec.digits as usize)),
                    "stability": found.map(stability),
                    "margin": found.map(|c| c.margin),
                    "det_error": found.map(|c| c.det_error),
                    "residual": found.map(|c| c.residual),
                    "min_speed": found.map(|c| c.min_speed),
                    "working_digits": found.map(|c| [c.precision.0, c.precision.1]),
                    "text": summary,
                });
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
        }
        Ok(())
    })();
    out.end(written)
}

/// The verdict on a cycle of impacts in a line.
fn impact_text(
    v: &ImpactCycleVerdict,
    n: usize,
    k: u32,
    origin: &str,
    digits: u32,
    max_digits: u32,
) -> String {
    let cycle = format!("cycle: periodic ({n}, {k}), {origin}");
    match v {
        ImpactCycleVerdict::Found(c) => format!(
            "{cycle}, solved by Newton's method at any precision: the runs at {} and {} digits agree on every value below",
            c.precision.0, c.precision.1
        ),
        ImpactCycleVerdict::Undecided { tried, agreed, need } => format!(
            "{cycle}: not decided within --max-digits {max_digits}: solved at {} and {} digits, the runs agree to {agreed} digits only; it needs at least about {need} digits (--max-digits {})",
            tried.0,
            tried.1,
            bouncemap_engine::max_digits_for(digits, *need)
        ),
        ImpactCycleVerdict::Lost { digits, why } => format!(
            "{cycle}: lost at {digits} digits: {why}; no values at any precision"
        ),
    }
}

/// The first line of `lyapunov --digits`' text: the system and how it is read.
fn heading(spec: &crate::config::run::PreciseSpec) -> String {
    format!(
        "table {}  alpha {}  r {}  parameters {}  digits {}",
        spec.table,
        spec.written.0,
        spec.written.1,
        spec.read_as(),
        spec.digits
    )
}
