//! `bouncemap attractors`: the attractors of one table and r followed along an α
//! window (see [`bouncemap_engine::attractors::global`]): at each α a basin picture
//! over the same box of starts, seeded with the previous α's attractors, matched to
//! them; the changes between values; basin fractions, basin entropy and the
//! uncertainty exponent at every α.
//!
//! text: the attractors with their α ranges, the changes, and a line per α; csv: a row
//! per α and attractor; json: all of it, with the uncertainty fits.

use super::drive::drive_reporting;
use super::progress::Progress;
use crate::config::run::{attractors_spec_of, AttractorsRun};
use crate::config::{self, InputError};
use crate::output::attractors_file::{computed, owned, write_part};
use crate::output::part_file::shard_name;
use crate::output::part_file::Layout;
use crate::output::records::{
    cause_text, change_ends, csv_writer, describe_member, AttractorsDoc, AttractorsRow,
};
use crate::output::sink::Sink;
use crate::output::text::shortest;
use bouncemap_engine::attractors::crisis::{
    crises, CrisisSpec, Located, Sighting, Tangency, EMBEDDED, TANGENCY_CANDIDATES,
};
use bouncemap_engine::attractors::global::{
    ChangeKind, Continuation, GlobalSpec, Join, MATCH_DISTANCE,
};
use bouncemap_engine::attractors::jumps::JUMP_RATIO;
use bouncemap_engine::attractors::saddles::MAX_SADDLE_EVENTS;
use bouncemap_engine::attractors::tangency::UNSTABLE_LENGTH;
use bouncemap_engine::jobs::{Control, Executor, Progress as JobProgress};
use bouncemap_engine::EventKind;
use bouncemap_figures::global::alpha_decimals;
use std::io::Write;
use std::time::Instant;

pub fn run(run: &AttractorsRun) -> anyhow::Result<()> {
    let AttractorsRun {
        spec,
        job,
        part,
        crises,
    } = run;
    let values = match part {
        Some((shard, _)) => computed(spec.steps, *shard),
        None => 0..spec.steps,
    };
    if job.check {
        let (workers, threads) = job.threads_plan();
        let what = match part {
            Some((shard, _)) => format!(
                "part {} of the attractors: α values {}..{} of {}{}, {} starts each: {}",
                shard_name(*shard),
                owned(spec.steps, *shard).start + 1,
                values.end,
                spec.steps,
                if shard.index > 0 {
                    format!(
                        " (from value {}, where it joins the part before)",
                        values.start + 1
                    )
                } else {
                    String::new()
                },
                spec.starts(),
                title(spec)
            ),
            None => format!(
                "attractors at {} α values of {} starts each: {}",
                spec.steps,
                spec.starts(),
                title(spec)
            ),
        };
        return super::print_plan(&[
            what,
            threads,
            config::memory_plan(memory_bound(run, workers)),
            super::output_plan(job.out.as_deref(), job.what("text"))?,
        ]);
    }
    if let Some((shard, header)) = part {
        if super::resume::attractors_written(job, header, *shard, &attractors_spec_of)? {
            return Ok(());
        }
    }
    let threads = job.threads()?;
    let mut sink = Sink::open(job.out.as_deref()).map_err(InputError)?;
    let cont = compute(spec, values, &Executor::new(threads)?)?;
    match part {
        Some((shard, header)) => {
            let text = write_part(header, *shard, &cont).map_err(anyhow::Error::msg)?;
            writeln!(sink, "{text}").map_err(|e| sink.describe(e.into()))?;
        }
        None => {
            let located = crises.then(|| locate_crises(&cont));
            write(run.job.layout, &cont, &[], located.as_deref(), &mut sink)
                .map_err(|e| sink.describe(e))?
        }
    }
    sink.finish()
}

/// Locate every crisis of `cont` (the engine's [`crises`]), saying on stderr which.
pub fn locate_crises(cont: &Continuation) -> Vec<Located> {
    let steps = cont.steps();
    let spec = CrisisSpec::default();
    eprintln!("bouncemap: measuring the size of every chaotic attractor, for jumps");
    crises(
        cont,
        &spec,
        &mut |i, n, track, step, sighting| {
            eprintln!(
                "bouncemap: locating crisis {} of {n}: attractor {} {} between alpha {} and {}",
                i + 1,
                track + 1,
                match sighting {
                    Sighting::Destroyed { .. } => "gone",
                    Sighting::Jump(_) => "jumps in size",
                },
                shortest(steps[step - 1].alpha),
                shortest(steps[step].alpha)
            );
        },
        &mut |_| false,
    )
}

/// How a crisis saddle was chosen by a tangency, in one line.
fn tangency_text(t: &Tangency, hi: f64) -> String {
    let e = &t.embedded;
    let also = if t.also.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = t.also.iter().map(|(n, k)| format!("({n}, {k})")).collect();
        format!(" (and, in the same bracket, that of {})", names.join(", "))
    };
    format!(
        "    the unstable manifold of the saddle ({}, {}) in the attractor (t̂ = {:.6}, v = {:.6}; each branch {} long) is {} from the saddle's stable manifold at the lower end and first crosses it at α in [{:.10}, {:.10}]{also}, {}; {}",
        e.n,
        e.k,
        e.phases[0].rem_euclid(1.0),
        e.velocities[0],
        shortest(UNSTABLE_LENGTH),
        t.apart.map_or("over 0.02".to_string(), |d| format!("{d:.1e}")),
        t.between.0,
        t.between.1,
        if t.between.1 > hi {
            format!("{:.1e} above the crisis' upper end (an upper bound: longer manifolds reach folds nearer the crisis)", t.between.1 - hi)
        } else {
            "within the crisis' bracket".to_string()
        },
        match t.in_closure {
            0 => format!("it crosses none of the {} saddles tried at the lower end", t.tried),
            1 => format!(
                "of the {} saddles tried, 1 has a stable manifold it crosses already at the lower end (in the attractor's closure, not on its boundary)",
                t.tried
            ),
            c => format!(
                "of the {} saddles tried, {c} have stable manifolds it crosses already at the lower end (in the attractor's closure, not on its boundary)",
                t.tried
            ),
        }
    )
}

/// The crises section of the text report.
fn crisis_text(cont: &Continuation, ls: &[Located], alpha: &dyn Fn(f64) -> String) -> Vec<String> {
    let spec = CrisisSpec::default();
    let mut out = vec![String::new()];
    if ls.is_empty() {
        out.push("crises: none (no chaotic attractor is gone without a local bifurcation, and none jumps in size)".into());
        return out;
    }
    out.push(format!(
        "crises (each located by bisection in α to {}: at the lower end orbits from {} points of the attractor all stay within {} of it for {} events, at the upper end one leaves; the saddle is, of the saddle cycles the leaving orbits pass outside the attractor, the one whose stable manifold the unstable manifold of a saddle embedded in it first crosses as α rises, of the {TANGENCY_CANDIDATES} nearest it, else the nearest; a jump in size is one of the range of launch velocities of {} events by over {} times its drift between neighbouring values, located with the attractor's neighbourhood a third of the jump):",
        shortest(spec.tolerance),
        spec.runs,
        shortest(spec.radius),
        spec.events,
        spec.sample,
        shortest(JUMP_RATIO),
    ));
    let steps = cont.steps();
    for l in ls {
        let (a, b) = (steps[l.step - 1].alpha, steps[l.step].alpha);
        let n = l.track + 1;
        let seen = match &l.sighting {
            Sighting::Destroyed { .. } => format!("gone between α {} and {}", alpha(a), alpha(b)),
            Sighting::Jump(j) => format!(
                "its launch velocities span [{:.6}, {:.6}] at α {} and [{:.6}, {:.6}] at α {}: grown by {:.1e}, {:.1} times its drift between neighbouring values",
                j.before.0,
                j.before.1,
                alpha(a),
                j.after.0,
                j.after.1,
                alpha(b),
                j.grows_by,
                j.grows_by / j.drift
            ),
        };
        match &l.result {
            Err(e) => out.push(format!("  attractor {n} ({seen}): not located: {e}")),
            Ok(x) => {
                let digits = (-(x.hi - x.lo).max(1e-16).log10()).ceil() as usize + 1;
                let left: Vec<String> = x
                    .left_after
                    .iter()
                    .map(|e| e.map_or("never".to_string(), |k| k.to_string()))
                    .collect();
                let first = match x.left_by {
                    EventKind::Stick => "sticking",
                    _ => "an impact outside",
                };
                out.push(match &l.sighting {
                    Sighting::Destroyed { .. } => format!(
                        "  attractor {n}: destroyed at α in [{:.digits$}, {:.digits$}] (width {:.1e}); at the upper end its orbits leave after {} events ({first} first)",
                        x.lo,
                        x.hi,
                        x.hi - x.lo,
                        left.join(", "),
                    ),
                    Sighting::Jump(_) => format!(
                        "  attractor {n}: jumps in size at α in [{:.digits$}, {:.digits$}] (width {:.1e}), an interior crisis: it goes on, larger ({seen}); at the upper end its orbits leave its neighbourhood at the lower end (cells of {:.1e}) after {} events ({first} first)",
                        x.lo,
                        x.hi,
                        x.hi - x.lo,
                        x.radius,
                        left.join(", "),
                    ),
                });
                match &x.saddle {
                    Some(s) => {
                        let [m0, m1] = s.cycle.multipliers;
                        out.push(format!(
                            "    through the saddle ({}, {}) at t̂ = {:.6}, v = {:.6} (multipliers {} and {}): the leaving orbits pass within {:.1e} of it; of {} saddle cycles they pass, {}; at the lower end it lies {:.1e} outside the attractor's sampled points",
                            s.cycle.n,
                            s.cycle.k,
                            s.cycle.phases[0].rem_euclid(1.0),
                            s.cycle.velocities[0],
                            crate::output::text::significant(m0.re, 6),
                            crate::output::text::significant(m1.re, 6),
                            s.passes,
                            x.considered,
                            if s.tangency.is_some() {
                                "the one the attractor's unstable manifold reaches first"
                            } else {
                                "the nearest the attractor outside it"
                            },
                            s.outside_by
                        ));
                        if let Some(t) = &s.tangency {
                            out.push(tangency_text(t, x.hi));
                        }
                        if !s.to_stable_manifold.is_empty() {
                            let d: Vec<String> = s
                                .to_stable_manifold
                                .iter()
                                .map(|&(a, d)| {
                                    // α to the bracket's digits (the grid's values carry
                                    // rounding past them).
                                    let a = crate::output::text::decimals(a, digits);
                                    format!("{d:.1e} at α {a}")
                                })
                                .collect();
                            out.push(format!(
                                "    the attractor's sampled points come within {} of the saddle's stable manifold",
                                d.join(", ")
                            ));
                        }
                    }
                    None => out.push(format!(
                        "    no saddle found: of the {} saddle cycles of up to {MAX_SADDLE_EVENTS} events the leaving orbits pass, none lies {EMBEDDED:e} or more outside the attractor",
                        x.considered
                    )),
                }
            }
        }
    }
    out
}

/// A bound on the run's memory, in bytes: one basin picture at a time (its labels,
/// each worker's run, the attractors' cells), the results of every α (a few attractors
/// each), the writer and the process.
fn memory_bound(run: &AttractorsRun, threads: usize) -> u64 {
    use bouncemap_engine::attractors::identify_bytes;
    use bouncemap_engine::run::OrbitRun;
    let spec = &run.spec;
    let labels = spec.starts() as u64 * 16;
    let worker = OrbitRun::bytes(1, spec.settle.periodicity) + identify_bytes(spec.settle.sample);
    // Two registries (this α's and the previous one's) with their cells.
    let attractors = 2 * ATTRACTORS_BYTES;
    let per_value = spec.steps as u64 * 4096;
    super::BASE_BYTES
        + threads as u64 * (worker + super::THREAD_BYTES)
        + labels
        + attractors
        + per_value
        + super::WRITER_BYTES
}

/// The allowance for one picture's attractors' cells and the results waiting their
/// turn to be numbered, in bytes (as `basins`').
const ATTRACTORS_BYTES: u64 = 64 << 20;

fn title(spec: &GlobalSpec) -> String {
    format!(
        "{}  r = {}  alpha {}..{} ({} values)  grid {}x{}  w0 ∈ [0, {}]  T = {}",
        spec.sys.table().name(),
        shortest(spec.sys.r()),
        shortest(spec.lo),
        shortest(spec.hi),
        spec.steps,
        spec.nx,
        spec.ny,
        shortest(spec.w_max),
        spec.settle.transient
    )
}

/// Every α value of `values` (indices into the window) in turn, its picture on
/// `executor`, with progress on stderr over all the starts.
pub fn compute(
    spec: &GlobalSpec,
    values: std::ops::Range<usize>,
    executor: &Executor,
) -> anyhow::Result<Continuation> {
    // Each α's grid, then its sampled starts (each with its displaced copies).
    let total = values.len() * (spec.starts() + spec.sampled_starts);
    let mut cont = Continuation::part(spec.clone(), values)?;
    let mut progress = Progress::start_units("attractors", "starts", total, &title(spec));
    let started = Instant::now();
    let (mut done, mut events) = (0usize, 0u64);
    let at = |done: usize, events: u64| JobProgress {
        done,
        total,
        events,
        elapsed: started.elapsed(),
    };
    let control = Control::new();
    while !cont.complete() {
        let next = match cont.prepare(&mut |_| false) {
            Some(n) => n?,
            None => break,
        };
        let mut basins = next.basins();
        let handle = executor.start(next.job()?, &control);
        let report = &mut |p: &JobProgress| progress.update(&at(done + p.done, events + p.events));
        let summary = drive_reporting(handle, report, |_, b| {
            basins.absorb(b.data);
            Ok(())
        })?;
        done += summary.progress.done;
        events += summary.progress.events;
        let sampled = next.sample(&basins, executor, &control, &mut |k| {
            progress.update(&at(done + k, events))
        });
        done += spec.sampled_starts;
        if !basins.complete() {
            anyhow::bail!(
                "the attractors stopped at alpha = {} after {} of {} starts",
                shortest(next.spec.sys.alpha()),
                basins.covered(),
                spec.starts()
            );
        }
        cont.absorb(next, &basins);
        if let Some(u) = sampled {
            cont.set_sampled(u);
        }
    }
    progress.finish(&at(done, events));
    Ok(cont)
}

/// The report of `cont` in `layout` (None: text), with the joins of its parts if it was
/// merged from parts.
pub fn write(
    layout: Option<Layout>,
    cont: &Continuation,
    joins: &[Join],
    crises: Option<&[Located]>,
    out: &mut Sink,
) -> anyhow::Result<()> {
    match layout {
        Some(Layout::Csv) => {
            let mut w = csv_writer(&mut *out, &AttractorsRow::HEADER)?;
            for i in 0..cont.steps().len() {
                for row in AttractorsRow::of_step(cont, i) {
                    w.serialize(row)?;
                }
            }
            w.flush()?;
        }
        Some(Layout::Json) => {
            serde_json::to_writer(&mut *out, &AttractorsDoc::of(cont, joins, crises))?;
            writeln!(out)?;
        }
        None => {
            for line in text(cont, joins, crises) {
                writeln!(out, "{line}")?;
            }
        }
    }
    Ok(())
}

/// The text report: the attractors, the changes, a line per α.
fn text(cont: &Continuation, joins: &[Join], crises: Option<&[Located]>) -> Vec<String> {
    let spec = cont.spec();
    let steps = cont.steps();
    let decimals = alpha_decimals(spec);
    let shortest = |x: f64| crate::output::text::decimals(x, decimals);
    let mut out = vec![format!("attractors along alpha: {}", title(spec))];
    if !joins.is_empty() {
        out.push(format!(
            "merged from {} parts, each after the first computed afresh from the last α value of the one before and joined there:",
            joins.len() + 1
        ));
        for j in joins {
            out.push(format!("  {}", join_text(j, &shortest)));
        }
    }
    out.push(String::new());
    out.push(format!("{} attractor{} followed (matched between neighbouring α within {MATCH_DISTANCE} in phase and velocity):", cont.tracks().len(), if cont.tracks().len() == 1 { "" } else { "s" }));
    for t in cont.tracks() {
        let members: Vec<_> = steps[t.first..=t.last]
            .iter()
            .flat_map(|s| s.members.iter().filter(|m| m.track == t.id))
            .collect();
        let mut kinds: Vec<String> = Vec::new();
        for m in &members {
            let d = describe_member(m);
            if kinds.last() != Some(&d) {
                kinds.push(d);
            }
        }
        if kinds.len() > 4 {
            let n = kinds.len();
            kinds.truncate(3);
            kinds.push(format!("… ({} more)", n - 3));
        }
        let max = members.iter().map(|m| m.fraction).fold(0.0, f64::max);
        out.push(format!(
            "  {:>3}  α {} .. {}  basin up to {:5.1}%  {}",
            t.id + 1,
            shortest(steps[t.first].alpha),
            shortest(steps[t.last].alpha),
            100.0 * max,
            kinds.join(" → ")
        ));
    }
    out.push(String::new());
    // A sticking cycle's (n, k) changes with its itinerary from one α to the next:
    // counted per attractor here, listed one by one in csv and json.
    let itinerary = |c: &&bouncemap_engine::attractors::global::Change| {
        matches!(c.what, ChangeKind::Period { .. })
            && steps[c.step].members.iter().any(|m| {
                m.track == c.track && m.kind == bouncemap_engine::attractors::Kind::Sticking
            })
    };
    let (sticking, listed): (Vec<_>, Vec<_>) = cont.changes().iter().partition(itinerary);
    if listed.is_empty() {
        out.push(
            "no births, deaths or changes of kind or period between neighbouring α values".into(),
        );
    } else {
        out.push("changes (each between the two α values named):".into());
    }
    for c in listed {
        let (a, b) = (steps[c.step - 1].alpha, steps[c.step].alpha);
        let n = c.track + 1;
        let why = |at: f64| {
            c.cause
                .map(|x| format!(" [at {}: {}]", shortest(at), cause_text(&x)))
                .unwrap_or_default()
        };
        let what = match &c.what {
            ChangeKind::Birth => format!("attractor {n} appears{}", why(a)),
            ChangeKind::Death { into: Some(t) } => format!(
                "attractor {n} is gone{}; its points now go to attractor {}",
                why(b),
                t + 1
            ),
            ChangeKind::Death { into: None } => format!("attractor {n} is gone{}", why(b)),
            other => {
                let (from, to) = change_ends(other).unwrap_or_default();
                format!("attractor {n}: {} {from} → {to}", other.name())
            }
        };
        out.push(format!("  α {} .. {}  {what}", shortest(a), shortest(b)));
    }
    for t in cont.tracks() {
        let n = sticking.iter().filter(|c| c.track == t.id).count();
        if n > 0 {
            out.push(format!(
                "  attractor {}: its sticking cycle's (n, k) changes {n} time{} (the itinerary between sticks; listed in csv and json)",
                t.id + 1,
                if n == 1 { "" } else { "s" }
            ));
        }
    }
    if let Some(ls) = crises {
        out.extend(crisis_text(cont, ls, &shortest));
    }
    out.push(String::new());
    out.push(
        "      alpha  attractors (number: basin %)              not settled   S_b    S_bb   uncertainty exponent"
            .into(),
    );
    for s in steps {
        let shares = shares(&s.members);
        let (sb, sbb) = match s.entropy {
            Some(e) => (
                format!("{:.3}", e.s_b),
                format!(
                    "{:.3}{}",
                    e.s_bb,
                    if e.fractal_by_log2() { "*" } else { " " }
                ),
            ),
            None => ("—".into(), "— ".into()),
        };
        let u = match &s.uncertainty {
            Ok(u) => format!("{:.3} ± {:.3}", u.exponent, u.error),
            Err(e) => format!("— ({})", e.as_str()),
        };
        out.push(format!(
            "  {:>9}  {:<40}  {:>9.1}%  {sb:>6}  {sbb:>6}  {u}",
            shortest(s.alpha),
            shares,
            100.0 * s.not_settled_fraction()
        ));
    }
    out.push(String::new());
    out.push("S_b, S_bb: basin entropy and boundary basin entropy in boxes of 5x5 starts (* S_bb > ln 2: a fractal boundary).".into());
    if let Some(line) = transients(cont) {
        out.push(line);
    }
    let first = steps
        .iter()
        .find_map(|s| s.uncertainty.as_ref().ok().map(|u| (u, s.sampled)));
    let scales = first.map(|(u, sampled)| {
        let k = |i: usize| bouncemap_engine::fmt_value(u.fractions[i].0);
        let (lo, hi) = (k(0), k(u.fractions.len() - 1));
        if sampled {
            format!(
                " (measured from {} sampled starts, each with copies ε = {lo} .. {hi} periods away along t̂0, fitted where 25 or more and at most half of the starts are uncertain)",
                u.starts
            )
        } else {
            format!(
                " (measured at ε = {lo} .. {hi} grid steps, fitted where 25 or more and at most half of the starts are uncertain)"
            )
        }
    });
    out.push(format!(
        "uncertainty exponent a: the share of starts whose neighbours ε away go elsewhere, ∝ ε^a{}; 1 for a smooth boundary, below 1 for a fractal one.",
        scales.unwrap_or_default()
    ));
    out
}

/// Attractors without a cycle that hold one start each, at least
/// [`MANY_SINGLES`] of them at one α: orbits still wandering at the end of the
/// transient are told apart by the cells they visit, so long transients show as many
/// one-start "attractors". Said, with where, rather than left to be read as many
/// attractors.
fn transients(cont: &Continuation) -> Option<String> {
    let singles = |s: &bouncemap_engine::attractors::global::Step| {
        s.members
            .iter()
            .filter(|m| m.starts == 1 && m.events.is_none())
            .count()
    };
    let (worst, at) = cont
        .steps()
        .iter()
        .map(|s| (singles(s), s.alpha))
        .max_by(|a, b| a.0.cmp(&b.0))?;
    if worst < MANY_SINGLES {
        return None;
    }
    let values = cont
        .steps()
        .iter()
        .filter(|s| singles(s) >= MANY_SINGLES)
        .count();
    Some(format!(
        "note: at {values} α value{} up to {worst} attractors without a cycle hold one start each (α = {}): likely transients longer than T = {}, each told apart by the cells it visits; a longer --transient settles more of them.",
        if values == 1 { "" } else { "s" },
        shortest(at),
        cont.spec().settle.transient
    ))
}

/// One-start attractors without a cycle at one α from which [`transients`] speaks.
const MANY_SINGLES: usize = 10;

/// How a join held, in words.
fn join_text(j: &Join, alpha: &dyn Fn(f64) -> String) -> String {
    let agree = if j.fraction_difference == 0.0 {
        "the two pictures agree on every basin fraction".to_string()
    } else {
        format!(
            "the two pictures' basin fractions differ by up to {:.2}%",
            100.0 * j.fraction_difference
        )
    };
    let mut extra = Vec::new();
    if j.only_before > 0 {
        extra.push(format!(
            "{} attractor{} only the seeds of the part before found there, not carried on",
            j.only_before,
            if j.only_before == 1 { "" } else { "s" }
        ));
    }
    if j.only_after > 0 {
        extra.push(format!(
            "{} only in the part after, carried on without a birth",
            j.only_after
        ));
    }
    let extra = if extra.is_empty() {
        String::new()
    } else {
        format!("; {}", extra.join("; "))
    };
    format!(
        "α {}: {} attractor{} matched, {agree}{extra}",
        alpha(j.alpha),
        j.matched,
        if j.matched == 1 { "" } else { "s" }
    )
}

/// Most attractors a line per α names; the rest are summed.
const SHOWN: usize = 6;

/// "number: basin %" of the largest [`SHOWN`] basins (in attractor order), the rest
/// summed.
fn shares(members: &[bouncemap_engine::attractors::global::Member]) -> String {
    let mut order: Vec<usize> = (0..members.len()).collect();
    order.sort_by(|&a, &b| members[b].starts.cmp(&members[a].starts).then(a.cmp(&b)));
    let mut shown: Vec<usize> = order.iter().copied().take(SHOWN).collect();
    shown.sort_unstable();
    let mut parts: Vec<String> = shown
        .iter()
        .map(|&i| {
            format!(
                "{}: {:.1}",
                members[i].track + 1,
                100.0 * members[i].fraction
            )
        })
        .collect();
    if members.len() > SHOWN {
        let rest: f64 = order[SHOWN..].iter().map(|&i| members[i].fraction).sum();
        parts.push(format!(
            "+{} more: {:.1}",
            members.len() - SHOWN,
            100.0 * rest
        ));
    }
    parts.join("  ")
}
