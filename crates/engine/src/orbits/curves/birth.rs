//! The birth line of the (1, k) pair, in closed form. A (1, k) solution has
//! f'(t̂*) = c with c = (k/2)(1 − r)/(1 + r) and v* = k/2, so the pair is born where
//! α max F' = c: α_birth = c / max F'. At a smooth maximum of F' (the sine) that is a
//! fold; at a maximum on a breakpoint (F_D's t̂ = 0, where F'' jumps) the two solutions
//! are born on the border, one on each side, and no condition of the cycle is smooth
//! there, so a traced curve breaks into pieces. The closed form needs no tracing: each
//! point of the line is α_birth at one value of the second parameter, its cycle the
//! closed-form launch (t̂ of max F', v = k/2) re-verified by the exact map's return.

use super::{Curve, CurveEnd, CurveKind, CurvePoint, Plane};
use crate::jobs::grid::SweepParam;
use crate::orbits::fixed::lands_after;
use crate::orbits::periodic::{accept, map_for, pass, CyclePoint};
use crate::system::System;
use crate::table::Table;

/// Points of a birth line across the window of the second parameter.
const POINTS: usize = 201;

/// max F' of `table` and a phase where it is taken (F' at every piece's ends and where
/// F'' vanishes inside).
pub fn max_slope(table: &Table) -> (f64, f64) {
    let mut best = (f64::NEG_INFINITY, 0.0);
    for seg in table.segments() {
        let mut at = vec![seg.start, seg.end];
        at.extend(seg.roots(0.0, 0.0, 1.0));
        for t in at {
            if t < seg.start || t > seg.end {
                continue;
            }
            let d = seg.jet(t)[1];
            if d > best.0 {
                best = (d, crate::time::wrap_phase(t));
            }
        }
    }
    best
}

/// c of the (1, k) condition f'(t̂*) = c.
pub fn slope_at_birth(r: f64, k: u32) -> f64 {
    0.5 * k as f64 * (1.0 - r) / (1.0 + r)
}

/// α_birth of the (1, k) pair of `table` at restitution `r`, and the phase it is born
/// at (None: F' is nowhere positive).
pub fn alpha_birth(table: &Table, r: f64, k: u32) -> Option<(f64, f64)> {
    let (m, phase) = max_slope(table);
    (m > 0.0 && m.is_finite()).then(|| (slope_at_birth(r, k) / m, phase))
}

/// The (1, k) solution at its birth in `sys` (α = α_birth), from the closed-form launch,
/// verified by the map's return and its admissibility (the flight of k periods lands
/// first at its end).
fn born(sys: &System, k: u32, phase: f64) -> Option<CyclePoint> {
    let v = 0.5 * k as f64;
    if !lands_after(sys, phase, v, k as f64).0 {
        return None;
    }
    let p = pass(&mut map_for(sys), phase, v, 1, k).ok()?;
    accept(sys, [sys.alpha(), phase, v], 1, k, &p).ok()
}

/// The birth line of the (1, k) pair over `plane`: one curve for each stretch of the
/// second parameter's window where α_birth lies in the α window and the born solution
/// is admissible. The condition kept at each point is α max F' − c (zero to rounding).
pub(super) fn birth_curves(plane: &Plane, k: u32) -> Vec<Curve> {
    let (lo, hi) = plane.window;
    let mut out = Vec::new();
    let mut run: Vec<CurvePoint> = Vec::new();
    let (mut start, mut last_why) = (CurveEnd::Window, CurveEnd::Window);
    let flush = |run: &mut Vec<CurvePoint>, ends: [CurveEnd; 2], out: &mut Vec<Curve>| {
        if run.len() >= 2 {
            let seed = [run[0].alpha, run[0].p];
            out.push(Curve {
                kind: CurveKind::Birth,
                n: 1,
                k,
                points: std::mem::take(run),
                ends,
                seed,
            });
        }
        run.clear();
    };
    // The point of the line at p, or why there is none there: outside the α window,
    // or not admissible.
    let at = |p: f64| -> Result<CurvePoint, CurveEnd> {
        let (table, r) = match plane.second {
            SweepParam::R => (plane.table.clone(), p),
            other => (
                other.table(&plane.table, p).map_err(|_| CurveEnd::Window)?,
                plane.r,
            ),
        };
        match alpha_birth(&table, r, k) {
            None => Err(CurveEnd::Window),
            Some((alpha, _)) if alpha < plane.alpha.0 || alpha > plane.alpha.1 => {
                Err(CurveEnd::Window)
            }
            Some((alpha, phase)) => System::new(table.clone(), alpha, r)
                .ok()
                .and_then(|sys| born(&sys, k, phase))
                .map(|cycle| CurvePoint {
                    alpha,
                    p,
                    cycle,
                    condition: alpha * max_slope(&table).0 - slope_at_birth(r, k),
                    floor: None,
                    criticality: None,
                })
                .ok_or(CurveEnd::Inadmissible),
        }
    };
    // Where the line leaves the α window between p_in (a point) and p_out (none): the
    // last point before it, to rounding (bisection).
    let edge = |p_in: f64, p_out: f64| -> Option<CurvePoint> {
        let (mut a, mut b) = (p_in, p_out);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if at(m).is_ok() {
                a = m;
            } else {
                b = m;
            }
        }
        at(a).ok()
    };
    let mut prev_p: Option<f64> = None;
    for i in 0..POINTS {
        let p = lo + (hi - lo) * i as f64 / (POINTS - 1) as f64;
        match at(p) {
            Ok(q) => {
                if run.is_empty() {
                    start = if i == 0 { CurveEnd::Window } else { last_why };
                    if let (Some(p0), CurveEnd::Window) = (prev_p, start) {
                        run.extend(edge(p, p0));
                    }
                }
                run.push(q);
            }
            Err(why) => {
                if let (Some(p0), false) = (prev_p, run.is_empty()) {
                    if why == CurveEnd::Window {
                        run.extend(edge(p0, p));
                    }
                    flush(&mut run, [start, why], &mut out);
                }
                last_why = why;
            }
        }
        prev_p = Some(p);
    }
    flush(&mut run, [start, CurveEnd::Window], &mut out);
    out
}
