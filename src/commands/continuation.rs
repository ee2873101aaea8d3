//! `bouncemap continue`: periodic orbits continued in α over a window, from the (1, k)
//! solution, the (2, 2k) one, or a guessed (n, k) cycle: every branch reached (doubled
//! branches started at period doublings), its points with multipliers and stability,
//! its special points and how it ends.

use crate::config::run::ContinueRun;
use crate::config::InputError;
use crate::output::records::{
    csv_writer, failure_name, special_text, stability_name, BranchProofs, BranchRecord,
    ContinueDoc, ContinueRow,
};
use crate::output::sink::Sink;
use crate::output::text::complex;
use crate::output::Format;
use bouncemap_engine::orbits::certify::{certify_cycle, certify_special, CertifiedSpecial};
use bouncemap_engine::orbits::continuation::{branches, Branch, NoStart, Special, Start};
use bouncemap_engine::table::Table;
use bouncemap_engine::System;
use std::io::{self, Write};

pub fn run(run: &ContinueRun) -> anyhow::Result<()> {
    let ContinueRun {
        table,
        r,
        alpha,
        start,
        options,
        certify,
        format,
    } = run;
    let (r, alpha, start) = (*r, *alpha, *start);
    let k = match start {
        Start::Fixed { k } | Start::TwoCycle { k } | Start::Point { k, .. } => k,
    };
    let (found, reason) = match branches(table, r, alpha, start, *options) {
        Ok(b) => (b, None),
        Err(NoStart::Invalid(e)) => return Err(InputError::from(e).into()),
        // An unstable (1, k) solution is not a start of its own, but it can be followed
        // from one of its points.
        Err(NoStart::NotFound(why)) if matches!(start, Start::Fixed { .. }) && why.contains("no stability window") => (
            Vec::new(),
            Some(format!(
                "{why}; to follow an unstable one, start on it as a cycle: --n 1 --k {k} --t0 PHASE --v0 {v} with PHASE from `bouncemap fixed --k {k} --alpha A` at an A where it exists, and a window from A",
                v = 0.5 * k as f64
            )),
        ),
        Err(NoStart::NotFound(why)) => (Vec::new(), Some(why)),
    };
    let proofs: Vec<Option<BranchProofs>> = found
        .iter()
        .map(|b| certify.then(|| prove_branch(table, r, b)))
        .collect();
    let proof = |i: usize| proofs[i].as_ref();
    let start_text = match start {
        Start::Fixed { k } => format!("fixed (1, {k})"),
        Start::TwoCycle { k } => format!("two-cycle (2, {})", 2 * k),
        Start::Point { n, k, t0, v0 } => format!("({n}, {k}) near t0 = {t0}, v0 = {v0}"),
    };
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match format {
            Format::Json => {
                let doc = ContinueDoc {
                    table: table.name(),
                    r,
                    alpha_lo: alpha.0,
                    alpha_hi: alpha.1,
                    start: start_text,
                    found: reason.is_none(),
                    reason,
                    branches: found
                        .iter()
                        .enumerate()
                        .map(|(i, b)| BranchRecord::new(i, b, proof(i)))
                        .collect(),
                };
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &ContinueRow::HEADER)?;
                for (i, b) in found.iter().enumerate() {
                    let pr = proof(i);
                    w.serialize(ContinueRow::special(
                        i,
                        b,
                        &b.begin,
                        pr.and_then(|p| p.begin.as_ref()),
                    ))?;
                    for (j, p) in b.points.iter().enumerate() {
                        w.serialize(ContinueRow::point(
                            i,
                            b,
                            p,
                            pr.and_then(|q| q.points.get(j)),
                        ))?;
                    }
                    for (j, s) in b.specials.iter().enumerate() {
                        let sp = pr.and_then(|p| p.specials.get(j)?.as_ref());
                        w.serialize(ContinueRow::special(i, b, s, sp))?;
                    }
                    w.serialize(ContinueRow::special(
                        i,
                        b,
                        &b.end,
                        pr.and_then(|p| p.end.as_ref()),
                    ))?;
                }
                w.flush()?;
            }
            Format::Text => {
                writeln!(
                    out,
                    "table {}  r {}  alpha {}..{}  start {}",
                    table.name(),
                    r,
                    alpha.0,
                    alpha.1,
                    start_text
                )?;
                if let Some(why) = reason {
                    writeln!(out, "no branch: {why}")?;
                }
                for (i, b) in found.iter().enumerate() {
                    text_branch(&mut out, i, b, proof(i))?;
                }
            }
        }
        Ok(())
    })();
    out.end(written)
}

/// Every point of branch `b` proved at its α, and its special points as α-intervals
/// (period doublings of its own cycle and border collisions; a doubled branch's begin
/// is its parent's period doubling, proved there).
fn prove_branch(table: &Table, r: f64, b: &Branch) -> BranchProofs {
    let points = b
        .points
        .iter()
        .map(|p| {
            let sys = System::new(table.clone(), p.alpha, r).expect("a continued point's system");
            certify_cycle(&sys, p)
        })
        .collect();
    let special = |s: &Special| certify_special(table, r, s);
    BranchProofs {
        points,
        begin: if b.parent.is_some() {
            None
        } else {
            special(&b.begin)
        },
        specials: b.specials.iter().map(special).collect(),
        end: special(&b.end),
    }
}

fn text_special(
    out: &mut impl Write,
    what: &str,
    s: &Special,
    proof: Option<&CertifiedSpecial>,
) -> io::Result<()> {
    let multipliers = match s.collision {
        // At a border collision the multipliers jump with f'': both sides, labelled.
        Some(c) => format!(
            "multipliers near side {}, {}; far side {}, {}  ({})",
            complex(c.near[0]),
            complex(c.near[1]),
            complex(c.far[0]),
            complex(c.far[1]),
            c.crossing.describe(s.point.n, s.point.k)
        ),
        None => format!(
            "multipliers {}, {}",
            complex(s.point.multipliers[0]),
            complex(s.point.multipliers[1])
        ),
    };
    let evidence = match (s.condition_error(), s.last_step) {
        (Some(e), _) => format!("  [condition to {e:.1e}]"),
        (None, Some(h)) => {
            format!("  [the corrector jumped off the cycle at every step down to {h:.1e}]")
        }
        _ => String::new(),
    };
    writeln!(
        out,
        "  {what:<7} {:<3} {:<16} alpha {:.12}  phase {:.12}  impact {}  {multipliers}{evidence}",
        s.kind.label(),
        s.kind.as_str(),
        s.alpha,
        s.phase,
        s.impact,
    )?;
    if let Some(p) = proof {
        writeln!(
            out,
            "          proved by interval arithmetic: {}",
            special_text(p)
        )?;
    }
    Ok(())
}

fn text_branch(
    out: &mut impl Write,
    i: usize,
    b: &Branch,
    proofs: Option<&BranchProofs>,
) -> io::Result<()> {
    let parent = b
        .parent
        .map_or(String::new(), |p| format!(", doubled from branch {p}"));
    writeln!(
        out,
        "\nbranch {i}: ({}, {}){parent}, {} points",
        b.n,
        b.k,
        b.points.len()
    )?;
    text_special(
        out,
        "begins",
        &b.begin,
        proofs.and_then(|p| p.begin.as_ref()),
    )?;
    for (j, s) in b.specials.iter().enumerate() {
        text_special(
            out,
            "passes",
            s,
            proofs.and_then(|p| p.specials.get(j)?.as_ref()),
        )?;
    }
    text_special(out, "ends", &b.end, proofs.and_then(|p| p.end.as_ref()))?;
    // With --certify, a column of what each point's proof shows.
    let proved = |j: usize| -> String {
        match proofs.and_then(|p| p.points.get(j)) {
            None => String::new(),
            Some(c) => match (&c.failure, c.stability) {
                (None, Some(s)) => format!(" {:>9}", stability_name(&s.verdict)),
                _ => format!(" {:>9}", "no"),
            },
        }
    };
    writeln!(
        out,
        "  {:>16} {:>6}{} {:>28} {:>28}  phases | velocities",
        "alpha",
        "stable",
        if proofs.is_some() {
            format!(" {:>9}", "proved")
        } else {
            String::new()
        },
        "multiplier 1",
        "multiplier 2"
    )?;
    for (j, p) in b.points.iter().enumerate() {
        let list = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.9}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        writeln!(
            out,
            "  {:>16.12} {:>6}{} {:>28} {:>28}  {} | {}",
            p.alpha,
            if p.stable { "yes" } else { "no" },
            proved(j),
            complex(p.multipliers[0]),
            complex(p.multipliers[1]),
            list(&p.phases),
            list(&p.velocities)
        )?;
    }
    if let Some(pr) = proofs {
        writeln!(out, "  {}", proof_summary(pr))?;
    }
    Ok(())
}

/// How many of a branch's points are proved, with which stability, and why the others
/// are not.
fn proof_summary(pr: &BranchProofs) -> String {
    use std::collections::BTreeMap;
    let mut proved: BTreeMap<&str, usize> = BTreeMap::new();
    let mut not: BTreeMap<&str, usize> = BTreeMap::new();
    for c in &pr.points {
        match (&c.failure, c.stability) {
            (None, Some(s)) => *proved.entry(stability_name(&s.verdict)).or_default() += 1,
            (Some(f), _) => *not.entry(failure_name(f)).or_default() += 1,
            (None, None) => *not.entry("not_proved").or_default() += 1,
        }
    }
    let list = |m: &BTreeMap<&str, usize>| {
        m.iter()
            .map(|(k, v)| format!("{v} {k}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let total: usize = proved.values().sum();
    let mut text = format!(
        "proved: {total} of {} points ({})",
        pr.points.len(),
        if total == 0 {
            "none".to_string()
        } else {
            list(&proved)
        }
    );
    if !not.is_empty() {
        text += &format!("; not proved: {}", list(&not));
    }
    text
}
