//! `bouncemap manifolds`: the unstable and stable manifolds of a saddle cycle (the
//! engine's [`bouncemap_engine::orbits::manifold`]): the unstable (1, k) solution, or
//! the (n, k) cycle Newton's method finds from `--n --t0 --v0`; both branches of each,
//! every point computed by the exact map or its exact inverse.
//!
//! text: the saddle, its multipliers, each manifold's map and direction and each
//! branch's points, length and end; csv: a row per point; json: all of it.

use crate::config::flags::{ManifoldsArgs, ManifoldsSpecArgs};
use crate::config::{self, InputError};
use crate::output::records::{csv_writer, end_text, side_name, ManifoldDoc, ManifoldRow};
use crate::output::sink::Sink;
use crate::output::Format;
use bouncemap_engine::orbits::manifold::{first_saddle, manifold, Kind, Manifold, ManifoldSpec};
use bouncemap_engine::orbits::periodic::{cycle, CyclePoint};
use bouncemap_engine::System;
use std::io::Write;

pub fn run(args: &ManifoldsArgs) -> anyhow::Result<()> {
    let (sys, saddle, ms) = compute(&args.spec)?;
    let mut out = Sink::open(args.output.out.as_deref()).map_err(InputError)?;
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                let doc = ManifoldDoc::of(sys.table().name(), sys.alpha(), sys.r(), &saddle, &ms);
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &ManifoldRow::HEADER)?;
                for m in &ms {
                    for b in &m.branches {
                        for row in ManifoldRow::of(m.kind, b) {
                            w.serialize(row)?;
                        }
                    }
                }
                w.flush()?;
            }
            Format::Text => {
                let [a, b] = saddle.multipliers;
                writeln!(
                    out,
                    "manifolds of the saddle ({}, {}) of {} at alpha {}, r {}",
                    saddle.n,
                    saddle.k,
                    sys.table().name(),
                    sys.alpha(),
                    sys.r()
                )?;
                writeln!(
                    out,
                    "  saddle: t̂ = {}, v = {}; multipliers {} and {}",
                    saddle.t0.rem_euclid(1.0),
                    saddle.velocities[0],
                    a.re,
                    b.re
                )?;
                for m in &ms {
                    let (how, factor) = match m.kind {
                        Kind::Unstable => ("the map", "multiplier"),
                        Kind::Stable => ("the inverse map", "growth 1/multiplier"),
                    };
                    writeln!(
                        out,
                        "  {} manifold, grown under {how} of {} impact{} ({} period{}): {factor} {}, direction ({:.6}, {:.6}) in (t, v)",
                        m.kind.as_str(),
                        m.events,
                        if m.events == 1 { "" } else { "s" },
                        m.periods,
                        if m.periods == 1 { "" } else { "s" },
                        m.multiplier,
                        m.direction[0],
                        m.direction[1]
                    )?;
                    for br in &m.branches {
                        let last = br.points.last().copied().unwrap_or(m.saddle);
                        writeln!(
                            out,
                            "    branch {}: {} points, arc length {:.4}, out to t̂ = {:.6}, v = {:.6}; ends: {}",
                            side_name(br.side),
                            br.points.len(),
                            br.length,
                            last[0].rem_euclid(1.0),
                            last[1],
                            end_text(&br.end)
                        )?;
                    }
                }
                writeln!(out, "every point: --format csv or json")?;
            }
        }
        Ok(())
    })();
    out.end(written)
}

/// The system, the saddle and the manifolds the flags name.
pub fn compute(
    args: &ManifoldsSpecArgs,
) -> Result<(System, CyclePoint, Vec<Manifold>), InputError> {
    let sys = config::system(&args.system)?;
    let saddle = saddle(
        &sys,
        args.k,
        args.guess
            .n
            .zip(args.guess.t0)
            .zip(args.guess.v0)
            .map(|((n, t0), v0)| (n, t0, v0)),
    )?;
    let ms = grow(&sys, &saddle, args.which.kinds(), args.length)?;
    Ok((sys, saddle, ms))
}

/// The `kinds` manifolds of `saddle`, each branch `length` long.
pub fn grow(
    sys: &System,
    saddle: &CyclePoint,
    kinds: &[Kind],
    length: f64,
) -> Result<Vec<Manifold>, InputError> {
    let spec = ManifoldSpec {
        length,
        ..ManifoldSpec::default()
    };
    kinds
        .iter()
        .map(|&kind| {
            manifold(sys, saddle, kind, &spec)
                .map_err(|e| InputError(format!("the ({}, {}) cycle is {e}", saddle.n, saddle.k)))
        })
        .collect()
}

/// The saddle a user names: the (n, k) cycle from the guess (n, t̂0, v0), or the
/// unstable (1, k) solution.
pub fn saddle(
    sys: &System,
    k: u32,
    guess: Option<(usize, f64, f64)>,
) -> Result<CyclePoint, InputError> {
    if let Some((n, t0, v0)) = guess {
        return cycle(sys, n, k, t0, v0).map_err(|e| {
            InputError(format!(
                "--n {n} --k {k} --t0 {t0} --v0 {v0}: no ({n}, {k}) cycle found from this guess ({}): valid a guess near a cycle of the exact map at this α",
                e.as_str()
            ))
        });
    }
    first_saddle(sys, k)
        .map_err(InputError::from)?
        .ok_or_else(|| {
            InputError(format!(
                "no saddle (1, {k}) solution at alpha {} (`bouncemap fixed --k {k}` lists them): valid an α where one is unstable, or a saddle (n, k) cycle by --n --t0 --v0",
                sys.alpha()
            ))
        })
}
