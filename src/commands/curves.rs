//! `bouncemap curves`: two-parameter bifurcation curves over (α, r) or (α, D), followed
//! from the special points of every branch the one-parameter continuation reaches from
//! the (1, k) solution: each curve's points with the evidence (its condition's value
//! there, the flip's criticality on a PD curve), how it ends, and the
//! codimension-two points located on it.

use super::progress::Progress;
use crate::config::run::CurvesRun;
use crate::config::InputError;
use crate::output::records::csv_writer;
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::orbits::curves::{
    curves_with_progress, Codim2, Codim2Kind, Curve, CurveKind, Curves, Plane, Seeds,
};
use serde_json::{json, Value};
use std::io::{self, Write};

pub fn run(run: &CurvesRun) -> anyhow::Result<()> {
    let CurvesRun {
        plane,
        seeds,
        r,
        out,
        format,
    } = run;
    let (plane, seeds, at) = (plane, *seeds, seeds.at());
    let mut out = Sink::open(out.as_deref()).map_err(InputError)?;
    let found =
        follow_with_progress(plane, seeds, &title(plane, &seeds)).map_err(InputError::from)?;
    let y = plane.second.as_str();
    let written = (|| -> anyhow::Result<()> {
        match format {
            Format::Text => text(&mut out, plane, &seeds, &found)?,
            Format::Csv => {
                let header = [
                    "row",
                    "curve",
                    "kind",
                    "n",
                    "k",
                    "impact",
                    "breakpoint",
                    "alpha",
                    y,
                    "condition",
                    "condition_floor",
                    "criticality",
                    "criticality_error",
                    "flip",
                    "detail",
                ];
                let mut w = csv_writer(&mut out, &header)?;
                for (i, c) in found.curves.iter().enumerate() {
                    let (impact, bp) = impact_of(c);
                    for (j, q) in c.points.iter().enumerate() {
                        let detail = match j {
                            0 => format!("end:{}", c.ends[0].as_str()),
                            _ if j + 1 == c.points.len() => format!("end:{}", c.ends[1].as_str()),
                            _ => String::new(),
                        };
                        let (cc, ce, flip) = match q.criticality {
                            Some(cr) => (num(cr.c), num(cr.error), cr.as_str().to_string()),
                            None => (String::new(), String::new(), String::new()),
                        };
                        w.write_record([
                            "point".to_string(),
                            i.to_string(),
                            c.kind.as_str().to_string(),
                            c.n.to_string(),
                            c.k.to_string(),
                            impact.clone(),
                            bp.clone(),
                            num(q.alpha),
                            num(q.p),
                            num(q.condition),
                            q.floor.map_or(String::new(), num),
                            cc,
                            ce,
                            flip,
                            detail,
                        ])?;
                    }
                }
                for p in &found.codim2 {
                    let c = &found.curves[p.curve];
                    let (impact, bp) = p.impact.map_or((String::new(), String::new()), |(i, b)| {
                        (i.to_string(), num(b))
                    });
                    w.write_record([
                        "codim2".to_string(),
                        p.curve.to_string(),
                        p.kind.as_str().to_string(),
                        c.n.to_string(),
                        c.k.to_string(),
                        impact,
                        bp,
                        num(p.alpha),
                        num(p.p),
                        num(p.condition),
                        String::new(),
                        String::new(),
                        String::new(),
                        String::new(),
                        format!("second_condition:{}", num(p.second_condition)),
                    ])?;
                }
                w.flush()?;
            }
            Format::Json => {
                let doc = json!({
                    "table": table_label(plane),
                    "r": r,
                    "alpha": [plane.alpha.0, plane.alpha.1],
                    "second": y,
                    "window": [plane.window.0, plane.window.1],
                    "start": at,
                    "k": seeds.k(),
                    "max_period": seeds.max_period(),
                    "seeds": seeds.count(),
                    "curves": found.curves.iter().enumerate().map(|(i, c)| {
                        let (impact, bp) = match c.kind {
                            CurveKind::BorderCollision { impact, breakpoint } => (Some(impact), Some(breakpoint)),
                            _ => (None, None),
                        };
                        json!({
                            "index": i,
                            "kind": c.kind.as_str(),
                            "n": c.n,
                            "k": c.k,
                            "impact": impact,
                            "breakpoint": bp,
                            "ends": [c.ends[0].as_str(), c.ends[1].as_str()],
                            "end_evidence": end_evidence(plane, c),
                            "cycle": stability(c),
                            "seed": c.seed,
                            "points": c.points.iter().map(|q| json!({
                                "alpha": q.alpha,
                                y: q.p,
                                "condition": q.condition,
                                "condition_floor": q.floor,
                                "criticality": q.criticality.map(|c| c.c).filter(|c| c.is_finite()),
                                "criticality_error": q.criticality.map(|c| c.error).filter(|c| c.is_finite()),
                                "flip": q.criticality.map(|c| c.as_str()),
                            })).collect::<Vec<_>>(),
                        })
                    }).collect::<Vec<_>>(),
                    "codim2": found.codim2.iter().map(|p| json!({
                        "kind": p.kind.as_str(),
                        "curve": p.curve,
                        "alpha": p.alpha,
                        y: p.p,
                        "condition": p.condition,
                        "second_condition": p.second_condition,
                        "impact": p.impact.map(|x| x.0),
                        "breakpoint": p.impact.map(|x| x.1),
                        "meets": p.meets,
                    })).collect::<Vec<_>>(),
                    "search_alpha": plane.search_alpha(),
                    "seeding": json!({
                        "values": found.seeding.values,
                        "level": found.seeding.level,
                        "converged": found.seeding.converged,
                        "quiet_grids": found.seeding.quiet,
                    }),
                    "unseeded": found.unseeded.iter().map(|(p, why)| json!({
                        y: p,
                        "reason": why,
                    })).collect::<Vec<_>>(),
                    "skipped": found.skipped.iter().map(|k| json!({
                        "kind": k.special.kind.as_str(),
                        "n": k.special.point.n,
                        "k": k.special.point.k,
                        "alpha": k.special.alpha,
                        "reason": k.reason,
                        "count": k.count,
                    })).collect::<Vec<_>>(),
                });
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
        }
        Ok(())
    })();
    out.end(written)
}

/// The curves of `seeds`, with a start line and progress on stderr (per seed value,
/// and the curves found so far): a long search is never silent.
fn follow_with_progress(
    plane: &Plane,
    seeds: Seeds,
    title: &str,
) -> Result<Curves, bouncemap_engine::EngineError> {
    use bouncemap_engine::jobs::Progress as JobProgress;
    let started = std::time::Instant::now();
    let mut progress: Option<Progress> = None;
    let mut last = JobProgress {
        done: 0,
        total: 0,
        events: 0,
        elapsed: Default::default(),
    };
    let found = curves_with_progress(plane, seeds, &mut |p| {
        last = JobProgress {
            done: p.seeds_done,
            total: p.seeds,
            events: 0,
            elapsed: started.elapsed(),
        };
        let shown = progress
            .get_or_insert_with(|| Progress::start_units("curves", "seed values", p.seeds, title));
        shown.update_noting(&last, &format!(", {} curves", p.curves));
    });
    if let Some(p) = progress {
        p.finish(&last);
    }
    found
}

/// The run in one line, for the log's first line.
fn title(plane: &Plane, seeds: &Seeds) -> String {
    let at = seeds.at();
    format!(
        "table {}, alpha {}..{}, {} {}..{}, started at {} = {at}, {}",
        table_label(plane),
        plane.alpha.0,
        plane.alpha.1,
        plane.second.as_str(),
        plane.window.0,
        plane.window.1,
        plane.second.as_str(),
        match *seeds {
            Seeds::Point { n, k, t0, v0, .. } => {
                format!("the ({n}, {k}) branch near t0 = {t0}, v0 = {v0}")
            }
            Seeds::FromFixed {
                k,
                max_period,
                count,
                ..
            } => format!(
                "(1, {k}) branches up to period {max_period}, seeded on grids from {count} values"
            ),
        }
    )
}

/// The table as every format names it: with a family parameter as the second axis
/// the family with it left free (F_D as `fd`), else the table's own name.
fn table_label(plane: &Plane) -> String {
    crate::output::text::table_with_free(&plane.table, &[plane.second])
}

/// The json of a curve's [`EndEvidence`](bouncemap_engine::orbits::curves::EndEvidence)
/// at each end (null where it ended otherwise).
fn end_evidence(plane: &Plane, c: &Curve) -> Value {
    json!([0, 1].map(|e| c.end_evidence(plane, e).map(|v| json!({
        "multiplier": v.multiplier,
        "monodromy": v.monodromy,
        "impact": v.nearest.map(|x| x.0),
        "breakpoint": v.nearest.map(|x| x.1),
        "distance": v.nearest.map(|x| x.2),
    }))))
}

/// A number as every csv field prints it: the shortest exact form (exponent form for
/// very small and very large magnitudes); empty for none.
fn num(x: f64) -> String {
    if x.is_finite() {
        bouncemap_engine::fmt_value(x)
    } else {
        String::new()
    }
}

fn impact_of(c: &Curve) -> (String, String) {
    match c.kind {
        CurveKind::BorderCollision { impact, breakpoint } => (impact.to_string(), num(breakpoint)),
        _ => (String::new(), String::new()),
    }
}

fn describe(kind: &CurveKind) -> String {
    match kind {
        CurveKind::PeriodDoubling => "period doubling (PD)".into(),
        CurveKind::Fold => "fold (F)".into(),
        CurveKind::BorderCollision { impact, breakpoint } => {
            format!("border collision (BC) of impact {impact} at phase {breakpoint}")
        }
        CurveKind::Grazing { landing: false } => "grazing (G)".into(),
        CurveKind::Grazing { landing: true } => "grazing at a landing (G)".into(),
        CurveKind::Birth => "birth of the pair (B, closed form)".into(),
    }
}

fn text(out: &mut impl Write, plane: &Plane, seeds: &Seeds, found: &Curves) -> io::Result<()> {
    let at = seeds.at();
    let y = plane.second.as_str();
    writeln!(
        out,
        "table {}  r {}  alpha {}..{}  {y} {}..{}  {}, started at {y} = {at}{}",
        table_label(plane),
        if y == "r" {
            "axis".to_string()
        } else {
            format!("{}", plane.r)
        },
        plane.alpha.0,
        plane.alpha.1,
        plane.window.0,
        plane.window.1,
        match *seeds {
            Seeds::Point { n, k, t0, v0, .. } => {
                format!("the ({n}, {k}) branch near t0 = {t0}, v0 = {v0}")
            }
            Seeds::FromFixed { k, max_period, .. } => {
                format!("(1, {k}) branches up to period {max_period}")
            }
        },
        match *seeds {
            Seeds::FromFixed { count, .. } if count > 1 => format!(
                " and on grids of the window from {count} values, finer until no new curve appears"
            ),
            _ => String::new(),
        }
    )?;
    writeln!(
        out,
        "{} curves, {} codimension-two points; every point's condition holds to 1e-9{} (its value is in --format csv/json)",
        found.curves.len(),
        found.codim2.len(),
        floor_text(found)
    )?;
    writeln!(out, "{}", seeding_text(&found.seeding, y))?;
    let (lo, hi) = plane.search_alpha();
    writeln!(
        out,
        "followed over alpha {}..{} (the window and half its width on either side: a curve may come in only from beyond its edge), then cut to the window",
        crate::output::text::decimals(lo, 9),
        crate::output::text::decimals(hi, 9)
    )?;
    for (i, c) in found.curves.iter().enumerate() {
        let (a0, a1) = c
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q.alpha), hi.max(q.alpha))
            });
        let (p0, p1) = c
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q.p), hi.max(q.p))
            });
        writeln!(
            out,
            "\ncurve {i}: {} of ({}, {}), {} cycle, {} points, alpha {a0:.9}..{a1:.9}, {y} {p0:.9}..{p1:.9}",
            describe(&c.kind),
            c.n,
            c.k,
            stability(c).replace('_', " "),
            c.points.len()
        )?;
        let first = &c.points[0];
        let last = &c.points[c.points.len() - 1];
        writeln!(
            out,
            "  ends: {} at (alpha {:.12}, {y} {:.12}); {} at (alpha {:.12}, {y} {:.12})",
            c.ends[0].as_str(),
            first.alpha,
            first.p,
            c.ends[1].as_str(),
            last.alpha,
            last.p
        )?;
        for e in 0..2 {
            if let Some(v) = c.end_evidence(plane, e) {
                let near = v.nearest.map_or(String::new(), |(i, b, d)| {
                    format!(", impact {i} {:.1e} from the breakpoint {b}", d.abs())
                });
                writeln!(
                    out,
                    "  at the {} end ({}): the cycle's largest multiplier |λ| {:.2e}, largest monodromy entry {:.2e}{near}",
                    ["first", "last"][e],
                    c.ends[e].as_str(),
                    v.multiplier,
                    v.monodromy
                )?;
            }
        }
        if c.kind == CurveKind::PeriodDoubling {
            let mut counts = [0usize; 3];
            for q in &c.points {
                match q.criticality.and_then(|c| c.supercritical()) {
                    Some(true) => counts[0] += 1,
                    Some(false) => counts[1] += 1,
                    None => counts[2] += 1,
                }
            }
            writeln!(
                out,
                "  flip: supercritical at {} points, subcritical at {}, undecided at {} (|c| within its error: near a border, or c ≈ 0)",
                counts[0], counts[1], counts[2]
            )?;
        }
    }
    if !found.codim2.is_empty() {
        writeln!(out, "\ncodimension-two points:")?;
        for p in &found.codim2 {
            text_codim2(out, found, p, y)?;
        }
    }
    for (p, why) in &found.unseeded {
        writeln!(out, "no branch at {y} = {p}: {why}")?;
    }
    for k in &found.skipped {
        let s = &k.special;
        let times = if k.count > 1 {
            format!(" (met {} times)", k.count)
        } else {
            String::new()
        };
        writeln!(
            out,
            "not followed: {} of ({}, {}) at alpha {:.9}: {}{times}",
            s.kind.as_str(),
            s.point.n,
            s.point.k,
            s.alpha,
            k.reason
        )?;
    }
    Ok(())
}

/// The points held to their condition's rounding floor instead of 1e-9 (where the
/// condition is steeper), in words; empty where there are none.
fn floor_text(found: &Curves) -> String {
    let (count, largest) = found
        .curves
        .iter()
        .flat_map(|c| &c.points)
        .filter_map(|q| q.floor)
        .fold((0, 0.0f64), |(n, m), f| (n + 1, m.max(f)));
    if count == 0 {
        return String::new();
    }
    format!(
        ", or, at {count} points where it is too steep for that, to its rounding floor (its change when the parameters move by 1e-14 of themselves, at most {largest:.1e}; column condition_floor): those points lie within 1e-14 of where it vanishes"
    )
}

/// How the seeds were placed, in words.
fn seeding_text(s: &bouncemap_engine::orbits::curves::Seeding, y: &str) -> String {
    match s.level {
        None => format!("seeded at the starting value of {y} only"),
        Some(l) if s.converged => format!(
            "seeded at {} values of {y} (grids of up to 2^{l} + 1); the last two finer grids found no new curve",
            s.values
        ),
        Some(l) if s.quiet == 1 => format!(
            "seeded at {} values of {y} (grids of up to 2^{l} + 1, the finest allowed); the finest found no new curve, but no second finer grid was left to confirm it",
            s.values
        ),
        Some(l) => format!(
            "seeded at {} values of {y} (grids of up to 2^{l} + 1, the finest allowed); the finest still found new curves: a finer seeding might find more",
            s.values
        ),
    }
}

/// Which cycle a curve belongs to: on a period-doubling, fold or birth curve a
/// multiplier is on the unit circle (`marginal`: the cycle is stable on one side of the
/// curve, the other multiplier being ±r²ⁿ); elsewhere `stable`, `unstable`, or
/// `stable_and_unstable` where it changes along the curve.
fn stability(c: &Curve) -> &'static str {
    if matches!(
        c.kind,
        CurveKind::PeriodDoubling | CurveKind::Fold | CurveKind::Birth
    ) {
        return "marginal";
    }
    let stable = c.points.iter().filter(|q| q.cycle.stable).count();
    match stable {
        0 => "unstable",
        s if s == c.points.len() => "stable",
        _ => "stable_and_unstable",
    }
}

fn text_codim2(out: &mut impl Write, found: &Curves, p: &Codim2, y: &str) -> io::Result<()> {
    let c = &found.curves[p.curve];
    let at = p
        .impact
        .map_or(String::new(), |(i, b)| format!("  impact {i} at phase {b}"));
    let evidence = match p.kind {
        Codim2Kind::DegenerateFlip => {
            format!("[c = {:.1e} there]", p.second_condition)
        }
        Codim2Kind::Cusp => format!(
            "[condition {:.1e}; the tangent's share in the plane {:.1e}]",
            p.condition,
            p.second_condition.abs()
        ),
        _ => format!(
            "[condition {:.1e}; last point {:.1e} from the breakpoint]",
            p.condition,
            p.second_condition.abs()
        ),
    };
    let others: Vec<String> = p.meets.iter().skip(1).map(|i| i.to_string()).collect();
    let meets = if others.is_empty() {
        String::new()
    } else {
        format!(" (also on curve {})", others.join(", "))
    };
    writeln!(
        out,
        "  {:<16} curve {}{meets} ({}, {})  alpha {:.12}  {y} {:.12}{at}  {evidence}",
        p.kind.as_str(),
        p.curve,
        c.n,
        c.k,
        p.alpha,
        p.p
    )
}
