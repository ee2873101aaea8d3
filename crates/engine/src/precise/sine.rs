//! The sine's flights and releases at any precision (see the module above): safe steps
//! on a rigorous lower bound of the gap, the gap by its Taylor series near the launch,
//! and the release where sin 2πt rises through 1/(4π²α).

use super::{PreciseEvent, PreciseHalt, PreciseMap};
use crate::map::MAX_EVENT_PERIOD;
use crate::real::Real;

impl<R: Real> PreciseMap<R> {
    /// A flight on the sine. The gap g(s) = z(s) − αF(τ₀ + s) has |g''| ≤ M = 1 + αω²,
    /// so from s with g(s) > 0 it stays positive for δ below the root of
    /// g + g'δ − Mδ²/2 (a rigorous lower bound): the flight advances by such safe steps,
    /// which near a landing converge to it quadratically, until a step is below the
    /// precision. Near the launch the gap is summed from its Taylor series in s (the
    /// launch root divided out), free of the cancellation of sines.
    pub(super) fn fly_sine(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        let sys = &self.sys;
        let st = self.state.clone();
        let w = sys.omega.clone().expect("the sine");
        let zero = sys.num(0.0);
        let one = sys.num(1.0);
        let half = sys.num(0.5);
        let eps = R::epsilon(&sys.ctx);
        let tiny = eps.clone() * eps.clone();
        let alpha = sys.alpha.clone();
        let (s0, c0) = (w.clone() * st.phase.clone()).sin_cos();
        let v0 = st.v.clone();
        let m = one.clone() + alpha.clone() * w.clone() * w.clone();
        // α F⁽ᵏ⁾(τ₀)/k! for k ≥ 2, until below the precision's square.
        let mut taylor = Vec::new();
        let mut c = alpha.clone() * w.clone();
        for k in 2..20_000u32 {
            c = c * w.clone() / sys.num(k as f64);
            if c < tiny {
                break;
            }
            let phase_term = match k % 4 {
                0 => s0.clone(),
                1 => c0.clone(),
                2 => -s0.clone(),
                _ => -c0.clone(),
            };
            taylor.push(c.clone() * phase_term);
        }
        let series_reach = half.clone() / w.clone();
        // (g, g') at s.
        let gap = |s: &R| -> (R, R) {
            if *s <= series_reach {
                // g = z₀ + s q(s), q = w₀ − s/2 − Σ a_k s^(k−1); g' = q + s q' (z₀ the
                // height above the table at the start, zero after every event).
                let mut q = st.w.clone() - half.clone() * s.clone();
                let mut dq = -half.clone();
                let mut pow = s.clone();
                let mut dpow = one.clone();
                for (i, a) in taylor.iter().enumerate() {
                    let k1 = sys.num((i + 1) as f64);
                    q = q - a.clone() * pow.clone();
                    dq = dq - a.clone() * k1 * dpow.clone();
                    dpow = pow.clone();
                    pow = pow * s.clone();
                }
                (
                    st.height.clone() + s.clone() * q.clone(),
                    q + s.clone() * dq,
                )
            } else {
                let (sn, cs) = (w.clone() * (st.phase.clone() + s.clone())).sin_cos();
                let g = st.height.clone() + alpha.clone() * s0.clone() + v0.clone() * s.clone()
                    - half.clone() * s.clone() * s.clone()
                    - alpha.clone() * sn;
                let dg = v0.clone() - s.clone() - alpha.clone() * w.clone() * cs;
                (g, dg)
            }
        };
        let mut s = zero.clone();
        let (mut g, mut dg) = (st.height.clone(), st.w.clone());
        if st.w <= zero && st.height == zero {
            // Leaving with no relative velocity (after a release): g = c2 s² + c3 s³ + …
            // with c2 = −(1 + αF'')/2, zero to rounding at a smooth release, and
            // c3 = −αF⁽³⁾/6; the fourth derivative is at most αω⁴, so the gap stays
            // positive up to 24 c3/(αω⁴): the first step goes half way. A ball that
            // cannot leave rides on.
            let t = sys.jet(&st.phase);
            let c2 = -(one.clone() + t[2].clone()) * half.clone();
            let c3 = -t[3].clone() / sys.num(6.0);
            let slack = eps.clone() * sys.num(8.0) * m.clone();
            if c2 < -slack.clone() || (c2 <= slack && c3 <= zero) {
                let (period, phase) = (st.period, st.phase.clone());
                return Ok(self.stick_at(period, phase, true));
            }
            let w4 = w.clone() * w.clone() * w.clone() * w.clone();
            let first = sys.num(12.0) * c3 / (alpha.clone() * w4);
            s = if first < series_reach {
                first
            } else {
                half.clone() * series_reach.clone()
            };
            (g, dg) = gap(&s);
        }
        let mut landed = false;
        for _ in 0..10 * crate::impact::MAX_SINE_STEPS {
            // The safe step: the positive root of g + g'δ − Mδ²/2 (g ≥ 0).
            let gp = if g > zero { g.clone() } else { zero.clone() };
            let disc = (dg.clone() * dg.clone() + sys.num(2.0) * m.clone() * gp).sqrt();
            let delta = (dg.clone() + disc) / m.clone();
            if delta <= eps.clone() * (one.clone() + s.clone()) {
                landed = s > zero;
                break;
            }
            s = s + delta;
            (g, dg) = gap(&s);
            if g <= zero {
                landed = true;
                break;
            }
            if st.period.saturating_add(s.to_f64() as i64) >= MAX_EVENT_PERIOD {
                return Err(PreciseHalt::TimeOutOfRange);
            }
        }
        if !landed {
            return Err(PreciseHalt::NoLanding);
        }
        let theta = st.phase.clone() + s.clone();
        Ok(self.land(theta, v0 - s))
    }
}
