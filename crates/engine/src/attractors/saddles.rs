//! The saddle cycles an orbit's path passes: every event of the path seeds Newton's
//! method for (n, k) cycles of up to [`MAX_SADDLE_EVENTS`] events, and the saddles
//! found are kept once each, at their shortest period, with the closest the path comes
//! to them. [`crisis`](super::crisis) names a crisis by one of them.

use crate::orbits::periodic::{cycle, CyclePoint};
use crate::system::System;
use crate::time::phase_distance;

/// The longest saddle cycle looked for on a leaving orbit's path, in events.
pub const MAX_SADDLE_EVENTS: usize = 8;

/// Whether two cycles are the same cycle (same (n, k), a common point).
pub(crate) fn same_cycle(a: &CyclePoint, b: &CyclePoint) -> bool {
    a.n == b.n
        && a.k == b.k
        && a.phases.iter().zip(&a.velocities).any(|(&t, &v)| {
            phase_distance(t.rem_euclid(1.0), b.phases[0].rem_euclid(1.0)) < 1e-7
                && (v - b.velocities[0]).abs() < 1e-7
        })
}

/// The saddles a leaving orbit's path passes, each with the closest the path comes to
/// one of its points. Every event of the path seeds Newton's method for (n, k) cycles,
/// n ≤ [`MAX_SADDLE_EVENTS`], k the periods the path itself takes for n events from
/// there; saddles (real multipliers, one outside and one inside the unit circle) are
/// kept, each at its shortest period.
pub(crate) fn saddles_on(sys: &System, path: &[(i64, f64, f64)]) -> Vec<(CyclePoint, f64)> {
    let mut found: Vec<CyclePoint> = Vec::new();
    for i in 0..path.len() {
        for n in 1..=MAX_SADDLE_EVENTS.min(path.len() - 1 - i) {
            let (a, b) = (path[i], path[i + n]);
            let k = ((b.0 - a.0) as f64 + (b.1 - a.1)).round();
            if !(1.0..=64.0).contains(&k) {
                continue;
            }
            let Ok(c) = cycle(sys, n, k as u32, a.1, a.2) else {
                continue;
            };
            let [x, y] = c.multipliers;
            if !(x.im == 0.0 && y.im == 0.0 && (x.re.abs() > 1.0) != (y.re.abs() > 1.0)) {
                continue;
            }
            let c = shortest(sys, c);
            if !found.iter().any(|f| same_cycle(f, &c)) {
                found.push(c);
            }
        }
    }
    found
        .into_iter()
        .map(|c| {
            let passes = to_cycle(&c, path.iter().map(|&(_, t, v)| (t, v)));
            (c, passes)
        })
        .collect()
}

/// The least distance (in (t̂, v), phases around the circle) from `points` to the
/// points of the cycle `c`.
pub(crate) fn to_cycle(c: &CyclePoint, points: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    points
        .into_iter()
        .flat_map(|(t, v)| {
            c.phases
                .iter()
                .zip(&c.velocities)
                .map(move |(&ct, &cv)| phase_distance(t, ct.rem_euclid(1.0)).hypot(v - cv))
        })
        .fold(f64::INFINITY, f64::min)
}

/// The cycle `c` as its shortest period: if its events repeat after m < n events (and
/// k·m/n periods), the (m, k·m/n) cycle through its first point.
pub(crate) fn shortest(sys: &System, c: CyclePoint) -> CyclePoint {
    for m in 1..c.n {
        if !c.n.is_multiple_of(m) || !(c.k as usize * m).is_multiple_of(c.n) {
            continue;
        }
        let repeats = (0..c.n - m).all(|i| {
            phase_distance(c.phases[i], c.phases[i + m]) < 1e-8
                && (c.velocities[i] - c.velocities[i + m]).abs() < 1e-8
        });
        if repeats {
            let km = (c.k as usize * m / c.n) as u32;
            if let Ok(s) = cycle(sys, m, km, c.phases[m - 1], c.velocities[m - 1]) {
                return s;
            }
        }
    }
    c
}
