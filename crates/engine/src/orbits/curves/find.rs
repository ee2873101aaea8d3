//! Finding the set of curves: the seeds (the starting value of the second parameter,
//! then dyadic grids of its window refined until two finer grids find no new curve,
//! the other border collision through each double border, and the PD and fold curves
//! ending on each border-collision curve from either side), the one-parameter
//! continuation at each seed value and every special point it finds followed as a
//! curve, unless a curve already found passes through it.

use super::clip;
use super::merge::{codim2_once, dedupe};
use super::sides::seed_from_border_sides;

/// Two curves of one kind and cycle within this share of the plane of each other are
/// one: more than the chord error of the largest step (a tenth of a step of
/// 0.005 of the plane where the curve bends sharply), far less than two different
/// curves' distance.
const SAME_CURVE: f64 = 5e-4;
use super::trace::follow;
use super::*;
use crate::orbits::continuation::{branches, Kind, Options, Start, GRAZING_SPEED};
use std::cell::RefCell;

/// Follow every curve reachable from `seeds` in `plane`.
pub fn curves(plane: &Plane, seeds: Seeds) -> Result<Curves, EngineError> {
    curves_with_progress(plane, seeds, &mut |_| {})
}

/// [`curves`], telling `report` after each seed value's branches and after each curve.
pub fn curves_with_progress(
    plane: &Plane,
    seeds: Seeds,
    report: &mut dyn FnMut(CurvesProgress),
) -> Result<Curves, EngineError> {
    plane.check()?;
    let mut out = Curves {
        curves: Vec::new(),
        codim2: Vec::new(),
        skipped: Vec::new(),
        unseeded: Vec::new(),
        seeding: Seeding::default(),
    };
    // Where a curve's search ahead failed, for the same curve traced from other seeds.
    let dead_ends: RefCell<Vec<DeadEnd>> = Default::default();
    // The (1, k) birth line, whole, from its closed form: traced, it breaks where the
    // pair is born on a breakpoint.
    if let Seeds::FromFixed { k, .. } = seeds {
        out.curves.extend(birth::birth_curves(plane, k));
    }
    // Seeds at the starting value, then on dyadic grids of the window, finer and finer
    // (a grid of 2^L + 1 values holds the coarser ones), from the first as fine as
    // `count` asks until two finer levels in a row find no new curve: the set found does
    // not depend on `count`, only on how fine it had to go.
    let at = match seeds {
        Seeds::FromFixed { at, .. } | Seeds::Point { at, .. } => at,
    };
    let mut seeded: Vec<f64> = Vec::new();
    let mut seed = |p: f64, total: usize, out: &mut Curves| -> Result<bool, EngineError> {
        if seeded
            .iter()
            .any(|&q| (q - p).abs() <= 1e-12 * plane.scale())
        {
            return Ok(false);
        }
        let done = seeded.len();
        seeded.push(p);
        seed_at(plane, seeds, p, out, &dead_ends, &mut |curves| {
            report(CurvesProgress {
                seeds_done: done,
                seeds: total,
                curves,
            })
        })?;
        Ok(true)
    };
    // `count` 1: the starting value only (a quick look, said so in the output).
    let grids = match seeds {
        Seeds::FromFixed { count, .. } if count >= 2 => Some(count),
        _ => None,
    };
    let first = grids.map_or(0, |count| {
        ((count - 1).next_power_of_two().trailing_zeros()).min(MAX_SEED_LEVEL)
    });
    // The values planned so far: the starting one and the first grid.
    let planned = 1 + grids.map_or(0, |_| (1usize << first) + 1);
    seed(at, planned, &mut out)?;
    out.seeding = Seeding {
        values: 1,
        level: None,
        converged: true,
        quiet: 0,
    };
    if grids.is_some() {
        // The border-collision curves already looked along for curves ending on them.
        let mut scanned = Vec::new();
        let mut quiet = 0;
        let mut values = 1;
        for level in first..=MAX_SEED_LEVEL {
            let before = out.curves.len();
            let n = 1usize << level;
            let grid: Vec<f64> = (0..=n)
                .map(|i| plane.window.0 + (plane.window.1 - plane.window.0) * i as f64 / n as f64)
                .collect();
            let total = values + grid.len();
            for p in grid {
                if seed(p, total, &mut out)? {
                    values += 1;
                }
            }
            seed_at_double_borders(plane, &mut out, &dead_ends);
            dedupe(&mut out, SAME_CURVE * plane.scale());
            seed_from_border_sides(plane, &mut out, &mut scanned, &dead_ends);
            dedupe(&mut out, SAME_CURVE * plane.scale());
            // The first grid itself is not yet evidence of anything.
            if level > first {
                quiet = if out.curves.len() > before {
                    0
                } else {
                    quiet + 1
                };
            }
            out.seeding = Seeding {
                values,
                level: Some(level),
                converged: quiet >= 2,
                quiet,
            };
            if quiet >= 2 {
                break;
            }
        }
    }
    report(CurvesProgress {
        seeds_done: out.seeding.values,
        seeds: out.seeding.values,
        curves: out.curves.len(),
    });
    dedupe(&mut out, SAME_CURVE * plane.scale());
    codim2_once(&mut out, 1e-6 * plane.scale());
    clip::to_window(plane, &mut out, 1e-6 * plane.scale());
    Ok(out)
}

/// At a double border two border-collision curves of the cycle cross (one impact on
/// each breakpoint): where only the one it was found on is known, the other is followed
/// from there too (it may be too short for any seed value's continuation to meet).
fn seed_at_double_borders(plane: &Plane, out: &mut Curves, dead_ends: &RefCell<Vec<DeadEnd>>) {
    let tol = SAME_CURVE * plane.scale();
    let mut i = 0;
    while i < out.codim2.len() {
        let p = out.codim2[i].clone();
        i += 1;
        let (Codim2Kind::DoubleBorder, Some((impact, breakpoint))) = (p.kind, p.impact) else {
            continue;
        };
        let on = &out.curves[p.curve];
        // The point of the known curve nearest the double border gives the cycle.
        let Some(q) = nearest(on, &p) else {
            continue;
        };
        // The twin impact of a doubled cycle on its own breakpoint, where the cycle
        // collapses onto the one of half its period: the "other" curve is that cycle
        // run twice.
        if on.kind.twin(&q.cycle, (impact, breakpoint)) {
            continue;
        }
        let crossing = out.curves.iter().enumerate().any(|(j, c)| {
            j != p.curve
                && c.n == on.n
                && c.k == on.k
                && c.passes_near(p.alpha, p.p, tol)
                && is_other_border(c, on, &p)
        });
        if crossing || out.curves.len() >= MAX_CURVES {
            continue;
        }
        // The other curve is solved for α at a fixed value of the second parameter,
        // from a guess of α: that point's, else values just off the double border on
        // either side from the border's α (at the border itself the impact lies on both
        // breakpoints, and the condition is not smooth there; the curve may turn there
        // in the second parameter, so that it exists on one side only).
        let near = |d: f64| {
            let at = (p.p + d * plane.scale()).clamp(plane.window.0, plane.window.1);
            (at, p.alpha)
        };
        let tries = [
            (q.p, q.alpha),
            near(-1e-5),
            near(1e-5),
            near(-1e-4),
            near(1e-4),
        ];
        let kind = CurveKind::BorderCollision { impact, breakpoint };
        let index = out.curves.len();
        let found = tries.into_iter().find_map(|(at, alpha)| {
            let special = Special {
                kind: Kind::BorderCollision,
                alpha,
                phase: breakpoint,
                impact,
                point: q.cycle.clone(),
                collision: None,
                last_step: None,
            };
            follow(plane, kind, &special, at, index, dead_ends)
                .ok()
                .filter(|(curve, _)| curve.points.len() >= 2)
        });
        if let Some((curve, codim2)) = found {
            out.curves.push(curve);
            out.codim2.extend(codim2);
        }
    }
}

/// Whether `c` is the border collision of the other impact of the double border `p`
/// found on the curve `on` (the impact `p` names, counted in `on`'s cycle), not `on`'s
/// own condition going on through the corner: at the points of the two curves nearest
/// `p`, the impact on `c`'s breakpoint is that one of `on`'s cycle, matched by phase and
/// launch velocity (both impacts may sit on the same breakpoint, so the phase alone
/// cannot tell them apart).
fn is_other_border(c: &Curve, on: &Curve, p: &Codim2) -> bool {
    let (CurveKind::BorderCollision { impact, .. }, Some((other, _))) = (c.kind, p.impact) else {
        return false;
    };
    let (Some(q), Some(r)) = (nearest(c, p), nearest(on, p)) else {
        return false;
    };
    let (phase, v) = (q.cycle.phases[impact], q.cycle.velocities[impact]);
    let apart = |i: usize| {
        signed_distance(r.cycle.phases[i], phase).abs()
            + (r.cycle.velocities[i] - v).abs() / (1.0 + v.abs())
    };
    (0..r.cycle.n).min_by(|&a, &b| apart(a).total_cmp(&apart(b))) == Some(other)
}

/// The point of `curve` nearest the codimension-two point `p`.
fn nearest<'a>(curve: &'a Curve, p: &Codim2) -> Option<&'a CurvePoint> {
    curve.points.iter().min_by(|a, b| {
        (a.alpha - p.alpha)
            .hypot(a.p - p.p)
            .total_cmp(&(b.alpha - p.alpha).hypot(b.p - p.p))
    })
}

/// Seed at value `p` of the second parameter: the one-parameter continuation from
/// `seeds`' start there, and every special point it finds followed as a curve (unless a
/// curve already found passes through it). `report` hears how many curves there are
/// after each.
fn seed_at(
    plane: &Plane,
    seeds: Seeds,
    p: f64,
    out: &mut Curves,
    dead_ends: &RefCell<Vec<DeadEnd>>,
    report: &mut dyn FnMut(usize),
) -> Result<(), EngineError> {
    report(out.curves.len());
    plane.second.check(&plane.table, p)?;
    let (table, r) = match plane.second {
        SweepParam::R => (plane.table.clone(), p),
        other => (other.table(&plane.table, p)?, plane.r),
    };
    // The branches over the search range; a cycle's guess is one at the window's LO,
    // so its branch is continued over the window (its curves are still followed beyond).
    let (start, max_period, range) = match seeds {
        Seeds::FromFixed { k, max_period, .. } => {
            (Start::Fixed { k }, max_period, plane.search_alpha())
        }
        Seeds::Point { n, k, t0, v0, .. } => (Start::Point { n, k, t0, v0 }, n, plane.alpha),
    };
    let opts = Options {
        max_period,
        ..Options::default()
    };
    let found = match branches(&table, r, range, start, opts) {
        Ok(found) => found,
        Err(e) => {
            out.unseeded.push((p, e.to_string()));
            return Ok(());
        }
    };
    for b in &found {
        let ends = [&b.begin, &b.end];
        let specials = b.specials.iter().chain(
            ends.into_iter()
                .filter(|s| matches!(s.kind, Kind::BorderCollision | Kind::Grazing | Kind::Fold)),
        );
        for s in specials {
            let kind = match s.kind {
                Kind::PeriodDoubling => CurveKind::PeriodDoubling,
                Kind::Fold => CurveKind::Fold,
                Kind::BorderCollision => CurveKind::BorderCollision {
                    impact: s.impact,
                    breakpoint: s.phase,
                },
                // The continuation's own criterion: a landing turned tangential.
                Kind::Grazing => CurveKind::Grazing {
                    landing: s.point.min_impact_speed < GRAZING_SPEED,
                },
                _ => continue,
            };
            // A doubled branch's birth is its parent's period doubling.
            if s.kind == Kind::PeriodDoubling && s.point.n != b.n {
                continue;
            }
            // The (1, k) pair's birth is the closed-form line.
            if s.point.n == 1 && matches!(s.kind, Kind::Fold | Kind::BorderCollision) {
                let k = s.point.k;
                if let Some((ab, _)) = birth::alpha_birth(&table, r, k) {
                    if (s.alpha - ab).abs() <= 1e-7 * (1.0 + ab) {
                        if !out
                            .curves
                            .iter()
                            .any(|c| c.kind == CurveKind::Birth && c.k == k)
                        {
                            out.curves.extend(birth::birth_curves(plane, k));
                        }
                        continue;
                    }
                }
            }
            // Within the chord error of the largest step of a curve already found.
            let tol = SAME_CURVE * plane.scale();
            let same = |c: &Curve| {
                c.n == s.point.n
                    && c.k == s.point.k
                    && c.kind.same_condition(&kind)
                    && c.passes_near(s.alpha, p, tol)
            };
            if out.curves.iter().any(same) {
                continue;
            }
            if out.curves.len() >= MAX_CURVES {
                skip(
                    &mut out.skipped,
                    s,
                    format!("more than {MAX_CURVES} curves"),
                );
                continue;
            }
            let index = out.curves.len();
            match follow(plane, kind, s, p, index, dead_ends) {
                // A seed the tracer could not leave is no curve.
                Ok((curve, _)) if curve.points.len() < 2 => skip(
                    &mut out.skipped,
                    s,
                    format!(
                        "the curve could not be followed beyond its seed ({}, {})",
                        curve.ends[0].as_str(),
                        curve.ends[1].as_str()
                    ),
                ),
                Ok((curve, codim2)) => {
                    out.curves.push(curve);
                    out.codim2.extend(codim2);
                }
                Err(why) => skip(&mut out.skipped, s, why),
            }
            report(out.curves.len());
        }
    }
    Ok(())
}

/// Note a special point not followed, once per point and reason.
fn skip(list: &mut Vec<Skipped>, s: &Special, reason: String) {
    let same = |k: &Skipped| {
        k.reason == reason
            && k.special.kind == s.kind
            && k.special.point.n == s.point.n
            && k.special.point.k == s.point.k
            && (k.special.alpha - s.alpha).abs() <= 1e-9 * (1.0 + s.alpha.abs())
    };
    match list.iter_mut().find(|k| same(k)) {
        Some(k) => k.count += 1,
        None => list.push(Skipped {
            special: s.clone(),
            reason,
            count: 1,
        }),
    }
}
