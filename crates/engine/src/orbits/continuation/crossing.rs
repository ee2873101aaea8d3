//! Crossing a breakpoint along a branch: where an impact reaches a breakpoint of the
//! table (f'' jumps there), the collision is classified and the cycle just beyond it
//! found on the branch's continuation ([`Family::cross_border`]), or the branch ends.

use super::*;

impl Family {
    /// A border collision `sp` of the cycle at `at` (its impact on the breakpoint),
    /// reached from `side` by a cycle that was stable or not (`was_stable`): classified
    /// ([`border::collision`]), recorded, and the cycle just beyond (or its partner at a
    /// border-collision fold) found, with its tangent. None when the branch ends here
    /// (`run.end` is set): no cycle beyond, or, in a cascade, the cycle loses stability.
    pub(super) fn cross_border(
        &mut self,
        mut sp: Special,
        at: &CyclePoint,
        side: f64,
        was_stable: bool,
        run: &mut Run,
    ) -> Option<(CyclePoint, [f64; 3])> {
        let (impact, bp) = (sp.impact, sp.phase);
        sp.collision = border::collision(&mut self.map, at, impact, bp, side);
        let beyond = self.cross_kink(at, impact, bp, side);
        let loses = was_stable && sp.persists() != Some(true);
        let Some((q, tq)) = beyond.filter(|_| !(self.opts.stop_at_pd && loses)) else {
            run.end = sp;
            return None;
        };
        run.specials.push(sp);
        run.points.push(q.clone());
        Some((q, tq))
    }

    /// Whether `b`, corrected from `a` with the arclength step `h` from `x0` along
    /// `tau`, continues `a`: the point corrected at half the step lies near the middle of
    /// the chord from `a` to `b` in every impact phase and velocity and in α (within a
    /// quarter of the chord; a smooth branch deviates by its curvature times the step
    /// squared, a jump to another cycle by half the jump), and the multipliers did not
    /// pass from one real sign to the other without going through the complex pair
    /// (their product is r²ⁿ on every cycle: a jump of the trace between values beyond
    /// ±2 is a jump of cycle).
    /// A step across a breakpoint of the table, where the branch turns by a kink, is
    /// left to the border collision's location.
    pub(super) fn continuous(
        &mut self,
        a: &CyclePoint,
        b: &CyclePoint,
        x0: [f64; 3],
        tau: [f64; 3],
        h: f64,
    ) -> bool {
        let crosses = a.phases.iter().zip(&b.phases).any(|(&pa, &pb)| {
            self.jumps.iter().any(|&bp| {
                let (da, db) = (signed_distance(pa, bp), signed_distance(pb, bp));
                (da < 0.0) != (db < 0.0) && da.abs() < 0.25 && db.abs() < 0.25
            })
        });
        if crosses {
            return true;
        }
        let trace = |p: &CyclePoint| p.monodromy[0][0] + p.monodromy[1][1];
        let real = |p: &CyclePoint| p.multipliers[0].im == 0.0;
        let (ta, tb) = (trace(a), trace(b));
        if real(a) && real(b) && ta * tb < 0.0 && ta.abs().min(tb.abs()) > 2.0 {
            return false;
        }
        let Ok((m, _)) = correct(&mut self.map, a.n, a.k, x0, tau, 0.5 * h) else {
            return false;
        };
        let wrap = |d: f64| d - d.round();
        let mut dev = (m.alpha - 0.5 * (a.alpha + b.alpha)).abs();
        let mut chord = (b.alpha - a.alpha).abs();
        for i in 0..a.n {
            let (dab, dam) = (
                wrap(b.phases[i] - a.phases[i]),
                wrap(m.phases[i] - a.phases[i]),
            );
            let (vab, vam) = (
                b.velocities[i] - a.velocities[i],
                m.velocities[i] - a.velocities[i],
            );
            dev = dev
                .max((dam - 0.5 * dab).abs())
                .max((vam - 0.5 * vab).abs());
            chord = chord.max(dab.abs()).max(vab.abs());
        }
        dev <= 0.25 * chord + SAME_POINT
    }

    /// The impact and breakpoint the point sits at (within 1e-8 in phase), if any.
    pub(super) fn at_breakpoint(&self, pt: &CyclePoint) -> Option<(usize, f64)> {
        for (i, &ph) in pt.phases.iter().enumerate() {
            for &bp in &self.jumps {
                if signed_distance(ph, bp).abs() < 1e-8 {
                    return Some((i, bp));
                }
            }
        }
        None
    }

    /// The cycle just beyond the breakpoint `bp` reached by impact `i` at `pt`: Newton's
    /// method at fixed α a little either side, accepting a solution with that impact on
    /// the other side of the breakpoint, close to `pt`; with its tangent pointing away.
    pub(super) fn cross_kink(
        &mut self,
        pt: &CyclePoint,
        i: usize,
        bp: f64,
        side: f64,
    ) -> Option<(CyclePoint, [f64; 3])> {
        for eps in [1e-9, 1e-8, 1e-7, 1e-6] {
            for sign in [1.0, -1.0] {
                let a = pt.alpha + sign * eps * (1.0 + pt.alpha.abs());
                if self.map.set_alpha(a).is_err() {
                    continue;
                }
                let Ok(q) = crate::orbits::periodic::solve_at(
                    &mut self.map,
                    pt.n,
                    pt.k,
                    pt.t0,
                    pt.velocities[0],
                ) else {
                    continue;
                };
                let d = signed_distance(q.phases[i], bp);
                let near = (q.t0 - pt.t0).abs() < 1e-4
                    && (q.velocities[0] - pt.velocities[0]).abs() < 1e-4;
                if near && d * side < 0.0 {
                    let (xq, xp) = (Family::x(&q), Family::x(pt));
                    let dir = [xq[0] - xp[0], xq[1] - xp[1], xq[2] - xp[2]];
                    let t = self.tangent(&q, dir)?;
                    return Some((q, t));
                }
            }
        }
        None
    }
}
