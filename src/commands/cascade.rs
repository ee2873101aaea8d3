//! `bouncemap cascade`: the period-doubling cascade from the (1, k) solution: the
//! period-doubling points αₙ, the Feigenbaum ratios δₙ, and how each 2ⁿ branch ends
//! (period doubling, or border collision at a breakpoint of the table, ...). With
//! `--d LO..HI:N`, one row per fd:D table: the answer to the paper's open question of
//! which 2ⁿ branch ends by border collision.

use crate::config::run::{CascadeRun, CascadeTables};
use crate::config::InputError;
use crate::output::records::{
    csv_writer, special_text, CascadeDoc, FamilyDoc, FamilyRecord, FamilyRow, LevelRecord,
    FEIGENBAUM_DELTA,
};
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::orbits::cascade::{cascade, Cascade};
use bouncemap_engine::orbits::certify::{certify_special, CertifiedSpecial};
use bouncemap_engine::orbits::continuation::NoStart;
use bouncemap_engine::table::Table;
use std::io::Write;

/// The cascade of one table: Ok(Err(reason)) when it has none.
fn one(table: &Table, args: &CascadeRun) -> Result<Result<Cascade, String>, InputError> {
    match cascade(table, args.r, args.k, args.depth) {
        Ok(c) => Ok(Ok(c)),
        Err(NoStart::Invalid(e)) => Err(e.into()),
        Err(NoStart::NotFound(why)) => Ok(Err(why)),
    }
}

pub fn run(args: &CascadeRun) -> anyhow::Result<()> {
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match &args.tables {
            CascadeTables::Family(tables) => {
                let mut rows = Vec::with_capacity(tables.len());
                for (d, table) in tables {
                    let c = one(table, args)?;
                    rows.push(FamilyRecord::new(*d, c.as_ref().map_err(Clone::clone)));
                }
                family(&mut out, args, rows)?;
            }
            CascadeTables::One(table) => {
                let c = one(table, args)?;
                single(&mut out, args, table, c)?;
            }
        }
        Ok(())
    })();
    out.end(written)
}

fn single(
    out: &mut impl Write,
    args: &CascadeRun,
    table: &Table,
    c: Result<Cascade, String>,
) -> anyhow::Result<()> {
    // With --certify: each level's end proved as an α-interval (period doublings and
    // border collisions; other ends have no proof).
    let proofs: Vec<Option<CertifiedSpecial>> = match (&c, args.certify) {
        (Ok(c), true) => c
            .levels
            .iter()
            .map(|l| certify_special(table, args.r, &l.end))
            .collect(),
        (Ok(c), false) => vec![None; c.levels.len()],
        (Err(_), _) => Vec::new(),
    };
    match args.format {
        Format::Json => {
            let doc = CascadeDoc {
                table: table.name(),
                r: args.r,
                k: args.k,
                depth: args.depth,
                found: c.is_ok(),
                reason: c.as_ref().err().cloned(),
                alphas: c.as_ref().map_or(Vec::new(), |c| c.alphas.clone()),
                deltas: c.as_ref().map_or(Vec::new(), |c| c.deltas.clone()),
                delta_estimate: c
                    .as_ref()
                    .ok()
                    .and_then(|c| c.delta_estimate())
                    .map(|e| e.0),
                delta_uncertainty: c
                    .as_ref()
                    .ok()
                    .and_then(|c| c.delta_estimate())
                    .map(|e| e.1),
                feigenbaum_delta: FEIGENBAUM_DELTA,
                levels: c.as_ref().map_or(Vec::new(), |c| {
                    proofs
                        .iter()
                        .enumerate()
                        .map(|(i, p)| LevelRecord::new(c, i, p.as_ref()))
                        .collect()
                }),
                unborn: c.as_ref().ok().and_then(|c| c.unborn.clone()),
            };
            serde_json::to_writer(&mut *out, &doc)?;
            writeln!(out)?;
        }
        Format::Csv => {
            let mut w = csv_writer(&mut *out, &LevelRecord::HEADER)?;
            if let Ok(c) = &c {
                for (i, p) in proofs.iter().enumerate() {
                    w.serialize(LevelRecord::new(c, i, p.as_ref()))?;
                }
            }
            w.flush()?;
        }
        Format::Text => {
            writeln!(
                out,
                "table {}  r {}  k {}  depth {}",
                table.name(),
                args.r,
                args.k,
                args.depth
            )?;
            let c = match c {
                Ok(c) => c,
                Err(why) => {
                    writeln!(out, "no cascade: {why}")?;
                    return Ok(());
                }
            };
            for (i, a) in c.alphas.iter().enumerate() {
                // αₙ is where level n − 1 ends: by a smooth period doubling or through
                // a border collision.
                let via = match c.levels.get(i).map(|l| l.end.kind.as_str()) {
                    Some("border_collision") => "  (period doubling through a border collision)",
                    _ => "",
                };
                writeln!(out, "alpha_{} = {a:.15}{via}", i + 1)?;
            }
            for (i, d) in c.deltas.iter().enumerate() {
                writeln!(
                    out,
                    "delta_{} = {d:.9}   (Feigenbaum {FEIGENBAUM_DELTA:.9}; difference {:+.2e})",
                    i + 2,
                    d - FEIGENBAUM_DELTA
                )?;
            }
            if let Some((d, e)) = c.delta_estimate() {
                writeln!(
                    out,
                    "delta estimate = {d:.6} ± {e:.1e}   (the last ratio, ± its last change; Feigenbaum {FEIGENBAUM_DELTA:.6} is {} it)",
                    if (d - FEIGENBAUM_DELTA).abs() <= e { "within" } else { "outside" }
                )?;
            }
            if let Some(why) = &c.unborn {
                writeln!(out, "{why}")?;
            }
            if args.certify {
                writeln!(out, "proved by interval arithmetic (--certify):")?;
                for (i, (l, p)) in c.levels.iter().zip(&proofs).enumerate() {
                    match p {
                        Some(p) => writeln!(out, "  alpha_{} {}", i + 1, special_text(p))?,
                        None => writeln!(
                            out,
                            "  the ({}, {}) branch's end ({}) has no proof",
                            l.period,
                            l.period as u32 * args.k,
                            l.end.kind.as_str()
                        )?,
                    }
                }
            }
            for l in &c.levels {
                let persists = match l.end.collision {
                    Some(col) => format!(
                        ", {}",
                        col.crossing.describe(l.period, l.period as u32 * args.k)
                    ),
                    None if l.end.kind.as_str() == "border_collision" => {
                        ", ceases to exist".to_string()
                    }
                    None => String::new(),
                };
                writeln!(
                    out,
                    "({}, {}) branch from alpha {:.12}: ends by {} at alpha {:.12}, phase {:.12}, impact {}{persists}",
                    l.period,
                    l.period as u32 * args.k,
                    l.alpha_start,
                    l.end.kind.as_str(),
                    l.end.alpha,
                    l.end.phase,
                    l.end.impact
                )?;
            }
        }
    }
    Ok(())
}

fn family(out: &mut impl Write, args: &CascadeRun, rows: Vec<FamilyRecord>) -> anyhow::Result<()> {
    match args.format {
        Format::Json => {
            let doc = FamilyDoc {
                r: args.r,
                k: args.k,
                depth: args.depth,
                rows,
            };
            serde_json::to_writer(&mut *out, &doc)?;
            writeln!(out)?;
        }
        Format::Csv => {
            let mut w = csv_writer(&mut *out, &FamilyRow::HEADER)?;
            for r in &rows {
                w.serialize(FamilyRow::from(r))?;
            }
            w.flush()?;
        }
        Format::Text => {
            writeln!(
                out,
                "fd:D tables, r {}  k {}  depth {}",
                args.r, args.k, args.depth
            )?;
            writeln!(
                out,
                "{:>8}  {:>10}  {:<34} {:>16}  {:>8}  period-doubling points",
                "D", "max period", "first branch not doubling: ends by", "alpha", "phase"
            )?;
            for r in &rows {
                let end = match (r.ends_period, r.ends_by) {
                    (Some(p), Some(k)) => format!("({p}) {k}"),
                    _ if r.found => "none up to the depth".to_string(),
                    _ => format!("no cascade: {}", r.reason.as_deref().unwrap_or("")),
                };
                let alphas = r
                    .alphas
                    .iter()
                    .map(|a| format!("{a:.12}"))
                    .collect::<Vec<_>>()
                    .join(" ");
                writeln!(
                    out,
                    "{:>8.4}  {:>10}  {:<34} {:>16}  {:>8}  {alphas}",
                    r.d,
                    r.max_period,
                    end,
                    r.alpha_end.map_or("-".into(), |a| format!("{a:.12}")),
                    r.phase.map_or("-".into(), |p| format!("{p}")),
                )?;
            }
        }
    }
    Ok(())
}
