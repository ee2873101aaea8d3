//! The flip's criticality coefficient at a period-doubling cycle: Kuznetsov's
//! normal-form coefficient of η ↦ −η + c η³ on the flip's direction, from second and
//! third differences of the n-fold map at two step sizes, with its error.

use super::Criticality;
use crate::linalg::solve;
use crate::orbits::periodic::{map_for, pass, CyclePoint};
use crate::system::System;

/// The flip's criticality coefficient at a period-doubling cycle of `sys`: c NaN and
/// the error infinite (undecided) where the map is not smooth on the difference
/// stencil (an impact of a stepped orbit lands on another piece of the table).
pub fn criticality(sys: &System, pt: &CyclePoint) -> Option<Criticality> {
    let (Some(c1), Some(c2)) = (
        criticality_with(sys, pt, 2e-3),
        criticality_with(sys, pt, 1e-3),
    ) else {
        // Undecided: the map is not smooth around the cycle on the stencil's scale.
        return Some(Criticality {
            c: f64::NAN,
            error: f64::INFINITY,
        });
    };
    // Central differences are O(h²): Richardson's extrapolation, and the correction
    // it made as the error.
    let c = c2 + (c2 - c1) / 3.0;
    // Rounding: the map is stepped to about 1e-15 of its scale, and the third
    // difference divides that by h³.
    let rounding = 1e-15 * (1.0 + pt.velocities[0].abs()) / 1e-9 * 10.0;
    Some(Criticality {
        c,
        error: (3.0 * (c2 - c1).abs()).max(rounding).max(1e-9 * c.abs()),
    })
}

fn criticality_with(sys: &System, pt: &CyclePoint, h: f64) -> Option<f64> {
    let mut map = map_for(sys);
    let (n, k) = (pt.n, pt.k);
    let x0 = [pt.t0, pt.velocities[0]];
    // r(x) = P(x) − x (with the k periods taken off): its second and third derivatives
    // are P's.
    // Every stepped orbit must land on the same pieces of the table as the cycle: the
    // map is smooth there only (else the stencil straddles a border, and c is not
    // defined by it).
    let table = sys.table();
    let pieces = |phases: &[f64]| -> Vec<usize> {
        phases.iter().map(|&ph| table.segment_index(ph)).collect()
    };
    let own = pieces(&pass(&mut map, x0[0], x0[1], n, k).ok()?.phases);
    let mut r = |dx: [f64; 2]| -> Option<[f64; 2]> {
        let p = pass(&mut map, x0[0] + dx[0], x0[1] + dx[1], n, k).ok()?;
        (pieces(&p.phases) == own).then_some([p.residual[0] + dx[0], p.residual[1] + dx[1]])
    };
    let a = pt.monodromy;
    let q = pt.pd_direction();
    // p: left eigenvector, (Aᵀ + I)p = 0, scaled so ⟨p, q⟩ = 1.
    let rows = [[a[0][0] + 1.0, a[1][0]], [a[0][1], a[1][1] + 1.0]];
    let row = if rows[0][0].hypot(rows[0][1]) >= rows[1][0].hypot(rows[1][1]) {
        rows[0]
    } else {
        rows[1]
    };
    let pv = [-row[1], row[0]];
    let pq = pv[0] * q[0] + pv[1] * q[1];
    if pq == 0.0 || !pq.is_finite() {
        return None;
    }
    let p = [pv[0] / pq, pv[1] / pq];
    let dot = |u: [f64; 2]| p[0] * u[0] + p[1] * u[1];
    let at = |s: f64, t: f64, w: [f64; 2]| [s * q[0] + t * w[0], s * q[1] + t * w[1]];
    let r0 = r([0.0, 0.0])?;
    let rp = r(at(h, 0.0, [0.0; 2]))?;
    let rm = r(at(-h, 0.0, [0.0; 2]))?;
    let rp2 = r(at(2.0 * h, 0.0, [0.0; 2]))?;
    let rm2 = r(at(-2.0 * h, 0.0, [0.0; 2]))?;
    let bqq = [0, 1].map(|i| (rp[i] - 2.0 * r0[i] + rm[i]) / (h * h));
    let cqqq = [0, 1].map(|i| (rp2[i] - 2.0 * rp[i] + 2.0 * rm[i] - rm2[i]) / (2.0 * h * h * h));
    // w = (I − A)⁻¹ B(q, q).
    let ia = [[1.0 - a[0][0], -a[0][1]], [-a[1][0], 1.0 - a[1][1]]];
    let w = solve(ia, bqq)?;
    let wn = w[0].hypot(w[1]);
    let bqw = if wn == 0.0 {
        [0.0, 0.0]
    } else {
        // B(q, w) by the mixed difference along q and the unit ŵ, times |w|.
        let u = [w[0] / wn, w[1] / wn];
        let pp = r(at(h, h, u))?;
        let pm = r(at(h, -h, u))?;
        let mp = r(at(-h, h, u))?;
        let mm = r(at(-h, -h, u))?;
        [0, 1].map(|i| wn * (pp[i] - pm[i] - mp[i] + mm[i]) / (4.0 * h * h))
    };
    let c = dot(cqqq) / 6.0 + dot(bqw) / 2.0;
    c.is_finite().then_some(c)
}
