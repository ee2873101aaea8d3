//! The impact map at any precision ([`Real`]), on piecewise polynomial tables of degree
//! at most 3 (F_D and its relatives, table files of that degree) and on the sine
//! (sin and cos correctly rounded at the working precision): the same events as
//! [`crate::ImpactMap`] (impact, stick, release), computed in the number type the
//! system is made in, so that two precisions can be compared event by event.
//!
//! What replaces the f64 map's specialised parts at any precision:
//! * **Landing.** On each piece the gap between ball and table is a polynomial of
//!   degree ≤ 3 in the piece's variable; its real roots are isolated exactly by the
//!   roots of its derivative (a quadratic, solved with the square root of the working
//!   precision), which split the piece into stretches where it is monotone, and the
//!   first sign change is refined by Newton's method kept inside its bracket. On the
//!   launch piece the launch root is divided out in closed form (the gap over s is
//!   w − s/2 − α Σ F⁽ᵏ⁾ sᵏ⁻¹/k!), as the f64 solver does; no double-double is needed,
//!   the working precision is the precision.
//! * **Chattering.** The accumulation time of the impacts after a slow impact, from the
//!   same series as the f64 map (see `map.rs`: on a piece of degree ≤ 3 only the terms in
//!   f''' remain), taken once the bound of the terms left out is below the precision's
//!   unit roundoff times the window; until then every impact is computed.
//! * **Release.** Where 1 + αF'' turns negative: a root of a linear polynomial on a
//!   piece, or a breakpoint where it jumps; on the sine where sin 2πt rises through
//!   1/(4π²α) (an arcsine at the working precision).
//! * **The sine's flights** replace the f64 solver's compile-time polynomial pieces and
//!   their error bounds: the gap is evaluated at the working precision (by its Taylor
//!   series near the launch), and the flight advances by safe steps to the first zero of
//!   its rigorous lower bound g + g'δ − (1 + αω²)δ²/2.

use crate::map::{EventKind, MAX_EVENT_PERIOD};
use crate::real::Real;
use crate::table::PieceIn;

/// The largest degree of a table's pieces the map at any precision takes.
pub const PRECISE_MAX_DEGREE: usize = 3;
/// Pieces a flight may cross before the map reports that the ball does not land.
const MAX_PIECES: usize = 1_000_000;
/// The longest accumulation window the map resolves in one jump (as the f64 map).
const CHATTER_WINDOW: f64 = 1e-3;

/// A system at any precision: the table's pieces, α and r in `R`.
#[derive(Clone, Debug)]
pub struct PreciseSystem<R: Real> {
    pieces: Vec<PieceIn<R>>,
    alpha: R,
    r: R,
    ctx: R::Context,
    /// The error accepted in a chattering sequence's accumulation time.
    chatter_error: R,
    /// For the sine table F = sin 2πt: 2π at the precision (no pieces then).
    omega: Option<R>,
}

/// Why a [`PreciseSystem`] cannot be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PreciseRefusal {
    /// A piece's degree is above [`PRECISE_MAX_DEGREE`].
    Degree(usize),
    /// No pieces.
    Empty,
}

impl<R: Real> PreciseSystem<R> {
    /// The system of `pieces` (as [`crate::table::Family::pieces_in`] gives them) at α
    /// and r, all at the precision of `ctx`.
    pub fn new(
        pieces: Vec<PieceIn<R>>,
        alpha: R,
        r: R,
        ctx: R::Context,
    ) -> Result<PreciseSystem<R>, PreciseRefusal> {
        if pieces.is_empty() {
            return Err(PreciseRefusal::Empty);
        }
        if let Some(p) = pieces
            .iter()
            .find(|p| p.coeffs.len() > PRECISE_MAX_DEGREE + 1)
        {
            return Err(PreciseRefusal::Degree(p.coeffs.len() - 1));
        }
        let chatter_error = R::epsilon(&ctx);
        Ok(PreciseSystem {
            pieces,
            alpha,
            r,
            ctx,
            chatter_error,
            omega: None,
        })
    }

    /// The sine table F = sin 2πt at α and r, at the precision of `ctx`: sin and cos
    /// correctly rounded at the working precision.
    pub fn sine(alpha: R, r: R, ctx: R::Context) -> PreciseSystem<R> {
        let omega = R::from_f64(2.0, &ctx) * R::pi(&ctx);
        PreciseSystem {
            pieces: Vec::new(),
            alpha,
            r,
            chatter_error: R::epsilon(&ctx),
            ctx,
            omega: Some(omega),
        }
    }

    /// The error accepted in a chattering sequence's accumulation time (by default the
    /// precision's unit roundoff). Two runs at different precisions that are to be
    /// compared event by event take the same one, so that they resolve chattering after
    /// the same impacts.
    pub fn with_chatter_error(mut self, error: R) -> PreciseSystem<R> {
        self.chatter_error = error;
        self
    }

    /// The precision.
    pub fn context(&self) -> &R::Context {
        &self.ctx
    }

    fn num(&self, x: f64) -> R {
        R::from_f64(x, &self.ctx)
    }

    /// The piece containing `phase` in [0, 1) (closed on the left).
    fn index(&self, phase: &R) -> usize {
        let mut i = 0;
        while i + 1 < self.pieces.len() && self.pieces[i + 1].start <= *phase {
            i += 1;
        }
        i
    }

    /// α F⁽ᵏ⁾/k! at local `s` of piece `j`, k = 0..=3: the Taylor coefficients of αF.
    fn taylor(&self, j: usize, s: &R) -> [R; 4] {
        let c = &self.pieces[j].coeffs;
        let coef = |k: usize| c.get(k).cloned().unwrap_or_else(|| self.num(0.0));
        // Shift the cubic c0 + c1 s + c2 s² + c3 s³ to `s`.
        let (c0, c1, c2, c3) = (coef(0), coef(1), coef(2), coef(3));
        let t0 = ((c3.clone() * s.clone() + c2.clone()) * s.clone() + c1.clone()) * s.clone() + c0;
        let t1 =
            (self.num(3.0) * c3.clone() * s.clone() + self.num(2.0) * c2.clone()) * s.clone() + c1;
        let t2 = self.num(3.0) * c3.clone() * s.clone() + c2;
        let a = self.alpha.clone();
        [a.clone() * t0, a.clone() * t1, a.clone() * t2, a * c3]
    }

    /// (f, f', f'', f''') of the table αF at `phase` in [0, 1).
    pub fn jet(&self, phase: &R) -> [R; 4] {
        if let Some(w) = &self.omega {
            let (s, c) = (w.clone() * phase.clone()).sin_cos();
            let a = self.alpha.clone();
            let w2 = w.clone() * w.clone();
            return [
                a.clone() * s.clone(),
                a.clone() * w.clone() * c.clone(),
                -(a.clone() * w2.clone() * s),
                -(a * w2 * w.clone() * c),
            ];
        }
        let j = self.index(phase);
        let s = phase.clone() - self.pieces[j].start.clone();
        let [t0, t1, t2, t3] = self.taylor(j, &s);
        [t0, t1, self.num(2.0) * t2, self.num(6.0) * t3]
    }
}

/// The ball right after an event.
#[derive(Clone, Debug, PartialEq)]
pub struct PreciseState<R> {
    /// Whole table periods of the event time.
    pub period: i64,
    /// Phase in [0, 1).
    pub phase: R,
    /// Ball velocity.
    pub v: R,
    /// Velocity relative to the table.
    pub w: R,
    /// Riding on the table.
    pub stuck: bool,
    /// After a stick of a ball launched with no relative velocity: release strictly
    /// after this instant.
    release_after: bool,
}

impl<R: Real> PreciseState<R> {
    /// A ball launched from the table at (period, phase) with relative velocity `w` ≥ 0.
    pub fn launch(sys: &PreciseSystem<R>, period: i64, phase: R, w: R) -> PreciseState<R> {
        let df = sys.jet(&phase)[1].clone();
        PreciseState {
            period,
            phase,
            v: df + w.clone(),
            w,
            stuck: false,
            release_after: false,
        }
    }
}

/// One event at any precision.
#[derive(Clone, Debug, PartialEq)]
pub struct PreciseEvent<R> {
    /// Impact, stick or release.
    pub kind: EventKind,
    /// Whole table periods of its time.
    pub period: i64,
    /// Its phase.
    pub phase: R,
    /// The ball's velocity right after it.
    pub v: R,
    /// The relative velocity of the landing (0 for a stick or a release).
    pub vrel: R,
}

/// Why the map at any precision stopped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PreciseHalt {
    /// The ball did not land within the bound on pieces crossed.
    NoLanding,
    /// The ball rests on the table for good (no release exists).
    Resting,
    /// The next event would lie beyond [`MAX_EVENT_PERIOD`] periods.
    TimeOutOfRange,
}

/// The impact map at any precision.
#[derive(Clone, Debug)]
pub struct PreciseMap<R: Real> {
    sys: PreciseSystem<R>,
    state: PreciseState<R>,
}

impl<R: Real> PreciseMap<R> {
    /// The map of `sys` from `state`.
    pub fn new(sys: PreciseSystem<R>, state: PreciseState<R>) -> PreciseMap<R> {
        PreciseMap { sys, state }
    }

    /// The state after the last event.
    pub fn state(&self) -> &PreciseState<R> {
        &self.state
    }

    /// The system.
    pub fn system(&self) -> &PreciseSystem<R> {
        &self.sys
    }

    /// The next event.
    pub fn step(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        if self.state.period.unsigned_abs() >= MAX_EVENT_PERIOD as u64 {
            return Err(PreciseHalt::TimeOutOfRange);
        }
        if self.state.stuck {
            return self.release();
        }
        if self.state.w > self.sys.num(0.0) {
            if let Some((period, phase)) = self.chatter_limit() {
                return Ok(self.stick_at(period, phase, false));
            }
        }
        self.fly()
    }

    fn stick_at(&mut self, period: i64, phase: R, release_after: bool) -> PreciseEvent<R> {
        let df = self.sys.jet(&phase)[1].clone();
        let zero = self.sys.num(0.0);
        self.state = PreciseState {
            period,
            phase: phase.clone(),
            v: df.clone(),
            w: zero.clone(),
            stuck: true,
            release_after,
        };
        PreciseEvent {
            kind: EventKind::Stick,
            period,
            phase,
            v: df,
            vrel: zero,
        }
    }

    /// If the impacts after this (slow) launch accumulate within a resolved window, the
    /// accumulation time (see the module's header).
    fn chatter_limit(&self) -> Option<(i64, R)> {
        let sys = &self.sys;
        let st = &self.state;
        let jet = sys.jet(&st.phase);
        let one = sys.num(1.0);
        let a = one.clone() + jet[2].clone();
        if a <= sys.num(0.0) {
            return None;
        }
        let t0 = sys.num(2.0) * st.w.clone() / (a.clone() * (one.clone() - sys.r.clone()));
        if t0 > sys.num(CHATTER_WINDOW) {
            return None;
        }
        let x = jet[3].clone() / a.clone();
        let xt = (x.clone() * t0.clone()).abs();
        // Bounds of the fourth and fifth derivatives: zero on pieces of degree ≤ 3,
        // αω⁴ and αω⁵ on the sine.
        let (k4, k5) = match &sys.omega {
            Some(w) => {
                let w4 = w.clone() * w.clone() * w.clone() * w.clone();
                (
                    sys.alpha.clone() * w4.clone(),
                    sys.alpha.clone() * w4 * w.clone(),
                )
            }
            None => (sys.num(0.0), sys.num(0.0)),
        };
        let yt = k4 / a.clone() * t0.clone() * t0.clone();
        let zt = k5 / a * t0.clone() * t0.clone() * t0.clone();
        if xt > sys.num(0.1) || yt > sys.num(0.1) || zt > sys.num(0.1) {
            return None;
        }
        let r = sys.r.clone();
        let (r2, r3, r4) = (
            r.clone() * r.clone(),
            r.clone() * r.clone() * r.clone(),
            r.clone() * r.clone() * r.clone() * r.clone(),
        );
        let q = r2.clone() + r.clone() + one.clone();
        let d = sys.num(540.0) * (r2.clone() + one.clone()) * q.clone();
        let c3j = (sys.num(2.0) * r2.clone() + sys.num(3.0) * r.clone() + sys.num(2.0))
            / (sys.num(9.0) * q);
        let c3k = (one.clone() + r.clone()) * (one.clone() + r.clone())
            / (sys.num(12.0) * (r2.clone() + r.clone() + one.clone()));
        let c4l = sys.num(9.0)
            * (r4.clone() + sys.num(4.0) * r3.clone() + sys.num(4.0) * r.clone() + one.clone())
            / d.clone();
        let c4jk = sys.num(15.0)
            * (sys.num(5.0) * r4.clone()
                + sys.num(16.0) * r3.clone()
                + sys.num(4.0) * r2.clone()
                + sys.num(16.0) * r.clone()
                + sys.num(5.0))
            / d.clone();
        let c4j = sys.num(20.0)
            * (sys.num(5.0) * r4
                + sys.num(13.0) * r3
                + sys.num(6.0) * r2
                + sys.num(13.0) * r
                + sys.num(5.0))
            / d;
        // The terms left out, doubled for the orders beyond, against the precision.
        let left_out = sys.num(2.0)
            * t0.clone()
            * (c3k * yt.clone()
                + c4l * zt
                + c4jk * xt.clone() * yt
                + c4j * xt.clone() * xt.clone() * xt.clone());
        if left_out > sys.chatter_error {
            return None;
        }
        let sign = if x < sys.num(0.0) {
            -one.clone()
        } else {
            one.clone()
        };
        let window = t0 * (one.clone() - sign * xt.clone() / sys.num(3.0) + c3j * xt.clone() * xt);
        let end = st.phase.clone() + window;
        if sys.omega.is_none() && end >= sys.pieces[sys.index(&st.phase)].end {
            return None;
        }
        let (period, phase) = wrap(st.period, end, &one);
        if one + sys.jet(&phase)[2].clone() <= sys.num(0.0) {
            return None;
        }
        Some((period, phase))
    }

    fn fly(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        if self.sys.omega.is_some() {
            return self.fly_sine();
        }
        let sys = &self.sys;
        let st = self.state.clone();
        let zero = sys.num(0.0);
        let one = sys.num(1.0);
        let half = sys.num(0.5);
        let j0 = sys.index(&st.phase);
        let sig0 = st.phase.clone() - sys.pieces[j0].start.clone();
        let t = sys.taylor(j0, &sig0);
        // The launch piece: gap/s = w − (1/2 + a2) s − a3 s², on (0, end − phase].
        let c1 = -(half.clone() + t[2].clone());
        let c2 = -t[3].clone();
        let q = if st.w > zero {
            vec![st.w.clone(), c1, c2]
        } else {
            // Leaving with no relative velocity (after a release): gap/s² =
            // −(1/2 + a2) − a3 s, whose constant term is 0 to rounding at a smooth
            // release. A ball that cannot leave rides on.
            let tiny = R::epsilon(&sys.ctx) * sys.num(8.0) * (one.clone() + t[2].abs());
            let c1 = if c1.abs() <= tiny { zero.clone() } else { c1 };
            if c1 > zero {
                vec![c1, c2]
            } else if c1 == zero && c2 > zero {
                vec![c2]
            } else {
                let (period, phase) = (st.period, st.phase.clone());
                return Ok(self.stick_at(period, phase, true));
            }
        };
        let first_len = sys.pieces[j0].end.clone() - st.phase.clone();
        let found = first_root(&q, &zero, &first_len, &sys.ctx);
        // (time since launch, phase of the landing from the launch's period)
        let mut hit: Option<(R, R)> = found.map(|s| (s.clone(), st.phase.clone() + s));
        let y0 = t[0].clone();
        let v0 = st.v.clone();
        let n = sys.pieces.len();
        let mut crossed = 0;
        let (mut m, mut j) = (0i64, j0);
        while hit.is_none() {
            j += 1;
            if j == n {
                j = 0;
                m += 1;
            }
            crossed += 1;
            if crossed > MAX_PIECES || st.period.saturating_add(m) >= MAX_EVENT_PERIOD {
                return Err(PreciseHalt::NoLanding);
            }
            let p = &sys.pieces[j];
            // Time from the launch to the piece's start.
            let delta = sys.num(m as f64) + p.start.clone() - st.phase.clone();
            let c = |k: usize| {
                sys.alpha.clone() * p.coeffs.get(k).cloned().unwrap_or_else(|| zero.clone())
            };
            let g = vec![
                y0.clone() + v0.clone() * delta.clone()
                    - half.clone() * delta.clone() * delta.clone()
                    - c(0),
                v0.clone() - delta.clone() - c(1),
                -half.clone() - c(2),
                -c(3),
            ];
            let len = p.end.clone() - p.start.clone();
            let at = |sigma: R| {
                let theta = sys.num(m as f64) + p.start.clone() + sigma.clone();
                (delta.clone() + sigma, theta)
            };
            if eval(&g, &zero) <= zero {
                hit = Some(at(zero.clone()));
                break;
            }
            hit = first_root(&g, &zero, &len, &sys.ctx).map(at);
        }
        let (s, theta) = hit.expect("found above");
        // The landing: phase, table's and ball's velocities.
        let (period, phase) = wrap(st.period, theta, &one);
        let df = sys.jet(&phase)[1].clone();
        let vball = v0 - s;
        let u = vball - df.clone();
        let w = -(sys.r.clone() * u.clone());
        let v = df + w.clone();
        self.state = PreciseState {
            period,
            phase: phase.clone(),
            v: v.clone(),
            w,
            stuck: false,
            release_after: false,
        };
        Ok(PreciseEvent {
            kind: EventKind::Impact,
            period,
            phase,
            v,
            vrel: u,
        })
    }

    fn release(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        if self.sys.omega.is_some() {
            return self.release_sine();
        }
        let sys = &self.sys;
        let st = self.state.clone();
        let zero = sys.num(0.0);
        let one = sys.num(1.0);
        let n = sys.pieces.len();
        let j0 = sys.index(&st.phase);
        // 1 + αF'' on piece j as a polynomial in its variable: 1 + 2a2 + 6a3 s.
        let h = |j: usize| {
            let t = sys.taylor(j, &zero);
            vec![
                one.clone() + sys.num(2.0) * t[2].clone(),
                sys.num(6.0) * t[3].clone(),
            ]
        };
        let (mut m, mut j) = (0i64, j0);
        let mut from = st.phase.clone() - sys.pieces[j0].start.clone();
        // One period and the rest of the current piece cover every phase.
        for _ in 0..=n {
            let p = &sys.pieces[j];
            let len = p.end.clone() - p.start.clone();
            let hj = h(j);
            let at_from = eval(&hj, &from);
            let released = if at_from < zero && !(st.release_after && m == 0 && j == j0) {
                Some(from.clone())
            } else {
                first_sign_change(&hj, &from, &len, &sys.ctx)
            };
            if let Some(sigma) = released {
                let theta = sys.num(m as f64) + p.start.clone() + sigma;
                let (period, phase) = wrap(st.period, theta, &one);
                let df = sys.jet(&phase)[1].clone();
                self.state = PreciseState {
                    period,
                    phase: phase.clone(),
                    v: df.clone(),
                    w: zero.clone(),
                    stuck: false,
                    release_after: false,
                };
                return Ok(PreciseEvent {
                    kind: EventKind::Release,
                    period,
                    phase,
                    v: df,
                    vrel: zero,
                });
            }
            j += 1;
            if j == n {
                j = 0;
                m += 1;
            }
            from = zero.clone();
        }
        Err(PreciseHalt::Resting)
    }
}

impl<R: Real> PreciseMap<R> {
    /// A flight on the sine. The gap g(s) = z(s) − αF(τ₀ + s) has |g''| ≤ M = 1 + αω²,
    /// so from s with g(s) > 0 it stays positive for δ below the root of
    /// g + g'δ − Mδ²/2 (a rigorous lower bound): the flight advances by such safe steps,
    /// which near a landing converge to it quadratically, until a step is below the
    /// precision. Near the launch the gap is summed from its Taylor series in s (the
    /// launch root divided out), free of the cancellation of sines.
    fn fly_sine(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
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
                // g = s q(s), q = w₀ − s/2 − Σ a_k s^(k−1); g' = q + s q'.
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
                (s.clone() * q.clone(), q + s.clone() * dq)
            } else {
                let (sn, cs) = (w.clone() * (st.phase.clone() + s.clone())).sin_cos();
                let g = alpha.clone() * s0.clone() + v0.clone() * s.clone()
                    - half.clone() * s.clone() * s.clone()
                    - alpha.clone() * sn;
                let dg = v0.clone() - s.clone() - alpha.clone() * w.clone() * cs;
                (g, dg)
            }
        };
        let mut s = zero.clone();
        let (mut g, mut dg) = (zero.clone(), st.w.clone());
        if st.w <= zero {
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
        let (period, phase) = wrap(st.period, theta, &one);
        let df = sys.jet(&phase)[1].clone();
        let u = v0 - s - df.clone();
        let wout = -(sys.r.clone() * u.clone());
        let v = df + wout.clone();
        self.state = PreciseState {
            period,
            phase: phase.clone(),
            v: v.clone(),
            w: wout,
            stuck: false,
            release_after: false,
        };
        Ok(PreciseEvent {
            kind: EventKind::Impact,
            period,
            phase,
            v,
            vrel: u,
        })
    }

    /// The release on the sine: the first phase after the stick where
    /// 1 − αω² sin ωt turns negative, sin ωt rising through c = 1/(αω²): ωt = asin c
    /// (mod 2π). Resting for good if c ≥ 1.
    fn release_sine(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        let sys = &self.sys;
        let st = self.state.clone();
        let w = sys.omega.clone().expect("the sine");
        let zero = sys.num(0.0);
        let one = sys.num(1.0);
        let c = one.clone() / (sys.alpha.clone() * w.clone() * w.clone());
        if c >= one {
            return Err(PreciseHalt::Resting);
        }
        let at = c.asin() / w.clone();
        let h_now = one.clone() + sys.jet(&st.phase)[2].clone();
        let theta = if h_now < zero && !st.release_after {
            st.phase.clone()
        } else if at > st.phase {
            at
        } else {
            at + one.clone()
        };
        let (period, phase) = wrap(st.period, theta, &one);
        let df = sys.jet(&phase)[1].clone();
        self.state = PreciseState {
            period,
            phase: phase.clone(),
            v: df.clone(),
            w: zero.clone(),
            stuck: false,
            release_after: false,
        };
        Ok(PreciseEvent {
            kind: EventKind::Release,
            period,
            phase,
            v: df,
            vrel: zero,
        })
    }
}

/// The significant decimal digits to which `a` agrees with `b`: ⌊−log₁₀ |a − b|/|b|⌋
/// (|a − b| itself where b = 0), from 0 to `cap` (`cap` where they are equal).
pub fn agreeing_digits<R: Real>(a: &R, b: &R, cap: u32) -> u32 {
    let ctx = a.context();
    let zero = R::from_f64(0.0, &ctx);
    let mut d = (a.clone() - b.clone()).abs();
    if d == zero {
        return cap;
    }
    if *b != zero {
        d = d / b.abs();
    }
    let mut digits = 0u32;
    // Scaled up by 10^100 at a time past what a double can hold.
    while d.to_f64() < 1e-200 && digits < cap {
        // (The double nearest 10^100: a count of digits needs no more.)
        d = d * R::from_f64(1e100, &ctx);
        digits += 100;
    }
    let x = d.to_f64();
    if x >= 1.0 {
        return digits.min(cap);
    }
    (digits + (-x.log10()).floor() as u32).min(cap)
}

/// (period, phase) of `theta` periods after the start of `period`, phase in [0, 1).
fn wrap<R: Real>(period: i64, theta: R, one: &R) -> (i64, R) {
    let whole = theta.floor();
    let k = whole.to_f64() as i64;
    let phase = theta - whole;
    if phase >= *one {
        (period.saturating_add(k + 1), phase - one.clone())
    } else {
        (period.saturating_add(k), phase)
    }
}

/// p(x) by Horner's rule (ascending coefficients).
fn eval<R: Real>(p: &[R], x: &R) -> R {
    let mut acc = p.last().cloned().expect("a polynomial");
    for c in p.iter().rev().skip(1) {
        acc = acc * x.clone() + c.clone();
    }
    acc
}

fn derivative<R: Real>(p: &[R], ctx: &R::Context) -> Vec<R> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| R::from_f64(k as f64, ctx) * c.clone())
        .collect()
}

/// The real roots of `p` in the open interval (a, b), ascending: the roots of its
/// derivative split the interval into stretches where p is monotone, and each sign
/// change is refined ([`refine`]). Degree ≤ 3.
fn roots_inside<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Vec<R> {
    let zero = R::from_f64(0.0, ctx);
    if p.len() <= 1 {
        return Vec::new();
    }
    let dp = derivative(p, ctx);
    let mut cuts = vec![a.clone()];
    cuts.extend(roots_inside(&dp, a, b, ctx));
    cuts.push(b.clone());
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (x, y) = (&w[0], &w[1]);
        let (px, py) = (eval(p, x), eval(p, y));
        if py == zero && y < b {
            out.push(y.clone());
        } else if (px < zero) != (py < zero) && px != zero && py != zero {
            out.push(refine(p, x, y, ctx));
        }
    }
    out
}

/// The first root of `p` in (a, b], where p(a) > 0: the first contact of the gap.
fn first_root<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Option<R> {
    let zero = R::from_f64(0.0, ctx);
    if let Some(r) = roots_inside(p, a, b, ctx).into_iter().next() {
        return Some(r);
    }
    (eval(p, b) <= zero).then(|| b.clone())
}

/// The first point of [a, b) after which `p` is negative (p ≥ 0 before it): a release.
fn first_sign_change<R: Real>(p: &[R], a: &R, b: &R, ctx: &R::Context) -> Option<R> {
    let zero = R::from_f64(0.0, ctx);
    let dp = derivative(p, ctx);
    roots_inside(p, a, b, ctx)
        .into_iter()
        .find(|x| eval(&dp, x) < zero)
}

/// The root of `p` between `x` and `y`, where p changes sign and is monotone: Newton's
/// method from the bracket's better end, every step kept inside the bracket (a step
/// that leaves it, or does not halve it, is a bisection), to the precision.
fn refine<R: Real>(p: &[R], x: &R, y: &R, ctx: &R::Context) -> R {
    let zero = R::from_f64(0.0, ctx);
    let half = R::from_f64(0.5, ctx);
    let eps = R::epsilon(ctx);
    let dp = derivative(p, ctx);
    let (mut lo, mut hi) = (x.clone(), y.clone());
    let lo_negative = eval(p, &lo) < zero;
    let mut t = half.clone() * (lo.clone() + hi.clone());
    // Newton converges quadratically; bisection bounds the work by the precision's bits.
    for _ in 0..4096 {
        let pt = eval(p, &t);
        if pt == zero {
            return t;
        }
        if (pt < zero) == lo_negative {
            lo = t.clone();
        } else {
            hi = t.clone();
        }
        let width = (hi.clone() - lo.clone()).abs();
        let scale = lo.abs().max_of(hi.abs());
        if width <= eps.clone() * scale.clone() * R::from_f64(4.0, ctx) || width == zero {
            return half * (lo + hi);
        }
        let d = eval(&dp, &t);
        let newton = if d == zero {
            None
        } else {
            let step = pt / d;
            // A step below the precision: t is the root to the last bit.
            if step.abs() <= eps.clone() * scale {
                return t;
            }
            Some(t.clone() - step)
        };
        let mid = half.clone() * (lo.clone() + hi.clone());
        t = match newton {
            Some(n) if n > lo && n < hi => n,
            _ => mid,
        };
    }
    t
}

/// The larger of two values.
trait MaxOf {
    fn max_of(self, other: Self) -> Self;
}

impl<R: Real> MaxOf for R {
    fn max_of(self, other: R) -> R {
        if other > self {
            other
        } else {
            self
        }
    }
}

/// What makes the system and the start at a number of bits (the caller's parameters,
/// read at that precision).
pub type MakeBig<'a> = dyn Fn(
        usize,
    ) -> (
        PreciseSystem<crate::real::Big>,
        PreciseState<crate::real::Big>,
    ) + 'a;

/// How far a run at any precision has got, for progress reports: the digits it runs
/// at, the events done and how many it is to compute (0 where unknown: a cycle looked
/// for).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DigitsProgress {
    /// The working digits of the run.
    pub digits: u32,
    /// Events computed.
    pub done: u64,
    /// Events to compute (0: not known in advance).
    pub total: u64,
}

/// Events between progress reports.
const PROGRESS_EVENTS: u64 = 256;

/// An orbit computed at two precisions and compared event by event
/// ([`orbit_to_digits`]).
#[derive(Clone, Debug)]
pub struct DigitsOrbit {
    /// The events after the skipped ones, from the more precise run, each with the
    /// significant digits on which the two runs agree (at most the digits asked for).
    pub events: Vec<(PreciseEvent<crate::real::Big>, u32)>,
    /// The digits the compared runs were made at (the last pair tried).
    pub precision: (u32, u32),
    /// Where the less precise run stopped early, if it did.
    pub halt: Option<PreciseHalt>,
    /// Digits lost per event, from the last pair (a least-squares slope through the
    /// events whose agreement is measured), when any were lost.
    pub loss_per_event: Option<f64>,
}

impl DigitsOrbit {
    /// The first printed event that does not hold to `digits`, if any.
    pub fn first_short(&self, digits: u32) -> Option<usize> {
        self.events.iter().position(|(_, d)| *d < digits)
    }
}

/// An orbit to `digits` significant digits: the map run from the start `make(bits)`
/// gives, at `digits` + 10 digits and at twice that, `skip` + `count` events, compared
/// event by event (kind, period, phase, v, vrel); where a printed event agrees to fewer
/// than `digits`, both precisions are doubled and the orbit run again, while the lower
/// stays within `max_digits`. Both runs resolve chattering to the lower precision, so
/// they take the same impacts.
pub fn orbit_to_digits(
    make: &MakeBig<'_>,
    digits: u32,
    max_digits: u32,
    skip: u64,
    count: u64,
    progress: &mut dyn FnMut(DigitsProgress),
) -> DigitsOrbit {
    use crate::real::{bits_for_digits, Big, Number};
    let mut run = |work: u32, bits: usize| {
        let (sys, st) = make(bits);
        let err = Big::from_decimal(&format!("1e-{work}"), &bits).expect("a constant");
        let mut map = PreciseMap::new(sys.with_chatter_error(err), st);
        let mut events = Vec::new();
        let mut halt = None;
        let total = skip.saturating_add(count);
        let digits = (bits as f64 / std::f64::consts::LOG2_10) as u32;
        for i in 0..total {
            if i % PROGRESS_EVENTS == 0 {
                progress(DigitsProgress {
                    digits,
                    done: i,
                    total,
                });
            }
            match map.step() {
                Ok(e) => events.push(e),
                Err(h) => {
                    halt = Some(h);
                    break;
                }
            }
        }
        progress(DigitsProgress {
            digits,
            done: events.len() as u64,
            total,
        });
        (events, halt)
    };
    let mut work = digits + 10;
    loop {
        let (lo, halt) = run(work, bits_for_digits(work));
        let (hi, _) = run(work, bits_for_digits(2 * work));
        let cap = 2 * work;
        let agree = |a: &PreciseEvent<Big>, b: &PreciseEvent<Big>| -> u32 {
            if (a.kind, a.period) != (b.kind, b.period) {
                return 0;
            }
            let mut d =
                agreeing_digits(&a.phase, &b.phase, cap).min(agreeing_digits(&a.v, &b.v, cap));
            if a.kind == EventKind::Impact {
                d = d.min(agreeing_digits(&a.vrel, &b.vrel, cap));
            }
            d
        };
        let all: Vec<u32> = lo.iter().zip(hi.iter()).map(|(a, b)| agree(a, b)).collect();
        // Digits lost by event i of the lower run: work − agreement, where measured.
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for (i, &a) in all.iter().enumerate() {
            if a > 0 && a < work {
                let (x, y) = ((i + 1) as f64, (work - a) as f64);
                sxy += x * y;
                sxx += x * x;
            }
        }
        let loss_per_event = (sxx > 0.0).then(|| sxy / sxx);
        let events: Vec<(PreciseEvent<Big>, u32)> = hi
            .into_iter()
            .zip(all.iter())
            .skip(skip as usize)
            .map(|(e, &a)| (e, a.min(digits)))
            .collect();
        let done = events.iter().all(|(_, d)| *d >= digits);
        if done || 2 * work > max_digits {
            return DigitsOrbit {
                events,
                precision: (work, 2 * work),
                halt,
                loss_per_event,
            };
        }
        work *= 2;
    }
}

/// A sticking cycle found at any precision ([`sticking_cycle_to_digits`]): from a
/// release to the next release at the same phase. Releases happen where 1 + αF'' turns
/// negative, a phase fixed by the table, so the orbit from one release repeats from the
/// next: the cycle is exactly periodic, and all that must be decided is where its stick
/// falls, which the flights from the release decide with growing sensitivity.
#[derive(Clone, Debug)]
pub struct StickingCycle {
    /// Its length in table periods, as both precisions found it.
    pub periods: i64,
    /// The releases (and sticks) in one cycle.
    pub releases: usize,
    /// The release's phase.
    pub release_phase: crate::real::Big,
    /// The time from the release to the cycle's first stick, in table periods.
    pub stick_after: crate::real::Big,
    /// The significant digits on which the two precisions agree about the stick time
    /// (at most the digits asked for).
    pub digits: u32,
    /// The digits of the two runs that agreed.
    pub precision: (u32, u32),
    /// The digits on which the runs of the pair before disagreed, if there was one: how
    /// sensitive the path from the release is.
    pub earlier: Option<((u32, u32), u32)>,
}

/// What [`sticking_cycle_to_digits`] decided.
#[derive(Clone, Debug)]
pub enum CycleVerdict {
    /// The cycle, to the digits asked for.
    Found(StickingCycle),
    /// No release within the events allowed at the first precision: the orbit does not
    /// stick and get released (or not soon enough).
    NoRelease,
    /// No repeating release within the events allowed.
    NoReturn,
    /// The two precisions disagree even at the most precision allowed.
    Undecided {
        /// The digits the last pair was run at.
        tried: (u32, u32),
        /// The digits the two runs agreed on about the stick time (0 where they
        /// disagree on the cycle's length).
        agreed: u32,
        /// The digits the answer needs by the loss measured, where measured: the digits
        /// asked for plus what the path from the release loses.
        need: Option<u32>,
    },
}

/// The sticking cycle of the orbit `make(bits)` starts, to `digits` significant digits:
/// each precision pair (`digits` + 10 and twice that, doubled while the lower stays
/// within `max_digits`) runs the orbit to its first release and on to the next release
/// at the same phase (at most `max_events` events each, within `max_periods` table
/// periods), and the two runs must agree on the cycle's length and on its stick time to
/// `digits`.
pub fn sticking_cycle_to_digits(
    make: &MakeBig<'_>,
    digits: u32,
    max_digits: u32,
    max_events: u64,
    max_periods: i64,
    progress: &mut dyn FnMut(DigitsProgress),
) -> CycleVerdict {
    use crate::real::{bits_for_digits, Big, Number};
    // (release phase, stick time, periods, releases), or why there is none.
    // Why a run found no cycle: no release, or none again at the same phase.
    #[derive(Clone, Copy)]
    enum NoCycle {
        Release,
        Return,
    }
    let mut cycle = |work: u32, bits: usize| -> Result<(Big, Big, i64, usize), NoCycle> {
        let (sys, st) = make(bits);
        let err = Big::from_decimal(&format!("1e-{work}"), &bits).expect("a constant");
        let mut map = PreciseMap::new(sys.with_chatter_error(err), st);
        let mut first: Option<PreciseEvent<Big>> = None;
        let mut stick: Option<Big> = None;
        let mut releases = 0;
        let run_digits = (bits as f64 / std::f64::consts::LOG2_10) as u32;
        for i in 0..max_events {
            if i % PROGRESS_EVENTS == 0 {
                progress(DigitsProgress {
                    digits: run_digits,
                    done: i,
                    total: 0,
                });
            }
            let Ok(e) = map.step() else { break };
            if e.period > max_periods {
                break;
            }
            match (&first, e.kind) {
                (None, EventKind::Release) => first = Some(e),
                (Some(r0), EventKind::Stick) if stick.is_none() => {
                    let t = Big::from_f64((e.period - r0.period) as f64, &bits) + e.phase.clone()
                        - r0.phase.clone();
                    stick = Some(t);
                }
                (Some(r0), EventKind::Release) => {
                    releases += 1;
                    if agreeing_digits(&e.phase, &r0.phase, work) + 5 >= work {
                        return Ok((
                            r0.phase.clone(),
                            stick.expect("a stick before a release"),
                            e.period - r0.period,
                            releases,
                        ));
                    }
                }
                _ => {}
            }
        }
        Err(if first.is_none() {
            NoCycle::Release
        } else {
            NoCycle::Return
        })
    };
    let mut work = digits + 10;
    let mut earlier = None;
    loop {
        let lo = cycle(work, bits_for_digits(work));
        let hi = cycle(work, bits_for_digits(2 * work));
        let (same, agreed, found) = match (lo, hi) {
            (Ok(a), Ok(b)) => {
                let same = a.2 == b.2 && a.3 == b.3;
                let agreed = if same {
                    agreeing_digits(&a.1, &b.1, 2 * work)
                } else {
                    0
                };
                (same, agreed, Some(b))
            }
            // Neither run finds a cycle: the orbit has none within the events allowed.
            (Err(NoCycle::Release), Err(_)) => return CycleVerdict::NoRelease,
            (Err(NoCycle::Return), Err(_)) => return CycleVerdict::NoReturn,
            // One run finds it and the other not: they disagree.
            _ => (false, 0, None),
        };
        if let Some(hi) = found.filter(|_| same && agreed >= digits) {
            return CycleVerdict::Found(StickingCycle {
                periods: hi.2,
                releases: hi.3,
                release_phase: hi.0,
                stick_after: hi.1,
                digits: agreed.min(digits),
                precision: (work, 2 * work),
                earlier,
            });
        }
        earlier = Some(((work, 2 * work), agreed));
        if 2 * work > max_digits {
            let need = (same && agreed > 0).then(|| digits + (work - agreed.min(work)) + 10);
            return CycleVerdict::Undecided {
                tried: (work, 2 * work),
                agreed: agreed.min(digits),
                need,
            };
        }
        work *= 2;
    }
}
