//! The impact map at any precision ([`Real`]), on piecewise polynomial tables of any
//! degree a table takes (F_D and its relatives, table files and families) and on the sine
//! (sin and cos correctly rounded at the working precision): the same events as
//! [`crate::ImpactMap`] (impact, stick, release), computed in the number type the
//! system is made in, so that two precisions can be compared event by event.
//!
//! What replaces the f64 map's specialised parts at any precision:
//! * **Landing.** On each piece the gap between ball and table is a polynomial in the
//!   piece's variable; its real roots are isolated exactly by the roots of its
//!   derivative (found the same way, down to a linear one), which split the piece into
//!   stretches where it is monotone, and the first sign change is refined by Newton's
//!   method kept inside its bracket. On the
//!   launch piece the launch root is divided out in closed form (the gap over s is
//!   w − s/2 − α Σ F⁽ᵏ⁾ sᵏ⁻¹/k!), as the f64 solver does; no double-double is needed,
//!   the working precision is the precision.
//! * **Chattering.** The accumulation time of the impacts after a slow impact, from the
//!   one series the f64 map uses too ([`crate::chatter`], with the bounds of |F''''| and
//!   |F⁽⁵⁾| over the pieces: zero on pieces of degree ≤ 3), taken once the bound of the
//!   terms left out is below the precision's unit roundoff; until then every impact is
//!   computed.
//! * **Release** is not specialised: the walk over the pieces from the stick on and the
//!   sine's arcsine are one generic code for both maps (`table::release`). Only
//!   the search on one piece differs: the f64 map takes [`crate::poly`]'s closed-form
//!   roots of 1 + αF'' with a rigorous sign test, this map the first sign change of that
//!   polynomial by exact isolation at the working precision.
//! * **The sine's flights** replace the f64 solver's compile-time polynomial pieces and
//!   their error bounds: the gap is evaluated at the working precision (by its Taylor
//!   series near the launch), and the flight advances by safe steps to the first zero of
//!   its rigorous lower bound g + g'δ − (1 + αω²)δ²/2.

mod cycle;
mod digits;
mod roots;
mod setup;
mod sine;

pub use cycle::{
    impact_cycle_to_digits, solve_cycle, Agreed, CycleAt, CycleLost, ImpactCycle,
    ImpactCycleVerdict, Multipliers, Stability, NEWTON_STEPS,
};
pub use digits::{
    agreeing_digits, max_digits_for, orbit_to_digits, sticking_cycle_to_digits, CycleSummary,
    CycleVerdict, DigitsOrbit, DigitsProgress, MakeBig, StickingCycle, PATH_EVENTS,
};
pub use setup::{
    check_digits, decide_in_job, decide_sticking_cycle, digits_bytes, DigitsAsk, PreciseSetup,
    Slot, Written, CYCLE_EVENTS,
};

use crate::chatter::ChatterSeries;
use crate::map::{EventKind, MAX_EVENT_PERIOD};
use crate::real::Real;
use crate::table::{release, PieceIn};
use roots::{eval, first_root, first_sign_change};

/// The largest degree of a table's pieces the map at any precision takes: every table's
/// ([`crate::table::MAX_TABLE_DEGREE`]).
pub const PRECISE_MAX_DEGREE: usize = crate::table::MAX_TABLE_DEGREE;

/// Whether the map at any precision takes `table`: the sine, or a member of a family
/// whose pieces are polynomials of degree at most [`PRECISE_MAX_DEGREE`].
pub fn precise_takes(table: &crate::table::Table) -> bool {
    table.family().is_some_and(|(family, values)| {
        std::sync::Arc::ptr_eq(family, crate::table::Family::sine())
            || family
                .pieces_in::<f64>(values, &())
                .is_some_and(|ps| ps.iter().all(|p| p.coeffs.len() <= PRECISE_MAX_DEGREE + 1))
    })
}

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
    /// The chattering series' constants for this r and table.
    chatter: ChatterSeries<R>,
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
        // The fourth and fifth derivatives' bounds (zero on pieces of degree ≤ 3).
        let k4 = Self::derivative_bound(&pieces, &alpha, 4, &ctx);
        let k5 = Self::derivative_bound(&pieces, &alpha, 5, &ctx);
        Ok(PreciseSystem {
            pieces,
            chatter: ChatterSeries::new(&r, k4, k5),
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
        // |f''''| ≤ αω⁴ and |f⁽⁵⁾| ≤ αω⁵.
        let w4 = omega.clone() * omega.clone() * omega.clone() * omega.clone();
        let k4 = alpha.clone() * w4.clone();
        let k5 = k4.clone() * omega.clone();
        PreciseSystem {
            pieces: Vec::new(),
            chatter: ChatterSeries::new(&r, k4, k5),
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

    /// α F⁽ᵏ⁾/k! at local `s` of piece `j`, k = 0, 1, …: the Taylor coefficients of αF
    /// there (at least four, zeros past the piece's degree).
    fn taylor(&self, j: usize, s: &R) -> Vec<R> {
        let mut t = self.pieces[j].coeffs.clone();
        while t.len() < 4 {
            t.push(self.num(0.0));
        }
        // The Taylor shift by Horner's scheme: c(s + x) in powers of x.
        let n = t.len();
        for i in 0..n - 1 {
            for k in (i..n - 1).rev() {
                t[k] = t[k].clone() + s.clone() * t[k + 1].clone();
            }
        }
        t.into_iter().map(|c| self.alpha.clone() * c).collect()
    }

    /// Bounds of α|F⁽ᵈ⁾| over every piece (zero for pieces of degree below d): on a
    /// piece of length L, Σₖ k!/(k − d)! |aₖ| Lᵏ⁻ᵈ, in its own variable s ∈ [0, L].
    fn derivative_bound(pieces: &[PieceIn<R>], alpha: &R, d: usize, ctx: &R::Context) -> R {
        let zero = R::from_f64(0.0, ctx);
        let mut most = zero.clone();
        for p in pieces {
            let len = p.end.clone() - p.start.clone();
            let mut sum = zero.clone();
            let mut power = R::from_f64(1.0, ctx);
            for (k, c) in p.coeffs.iter().enumerate().skip(d) {
                let falling: f64 = (k - d + 1..=k).map(|x| x as f64).product();
                sum = sum + R::from_f64(falling, ctx) * c.abs() * power.clone();
                power = power * len.clone();
            }
            if sum > most {
                most = sum;
            }
        }
        alpha.abs() * most
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
        let t = self.taylor(j, &s);
        [
            t[0].clone(),
            t[1].clone(),
            self.num(2.0) * t[2].clone(),
            self.num(6.0) * t[3].clone(),
        ]
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
    /// Height above the table (zero after every event; above zero only at a start
    /// above the table).
    height: R,
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
            height: sys.num(0.0),
        }
    }

    /// A ball `height` ≥ 0 above the table at (period, phase) with velocity `v` (as
    /// [`crate::State::launch`]: on the table, `v` must be at least the table's).
    pub fn above(
        sys: &PreciseSystem<R>,
        period: i64,
        phase: R,
        v: R,
        height: R,
    ) -> PreciseState<R> {
        let df = sys.jet(&phase)[1].clone();
        PreciseState {
            period,
            phase,
            w: v.clone() - df,
            v,
            stuck: false,
            release_after: false,
            height,
        }
    }

    /// The height above the table.
    pub fn height(&self) -> &R {
        &self.height
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
        let zero = self.sys.num(0.0);
        if self.state.w > zero && self.state.height == zero {
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
            height: zero.clone(),
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
        let t0 = sys.chatter.leading(&st.w, &a);
        let window = sys.chatter.window(
            &t0,
            &a,
            &jet[3],
            &sys.num(CHATTER_WINDOW),
            &sys.chatter_error,
        )?;
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
        // The launch piece: gap/s = w − (1/2 + a2) s − a3 s² − a4 s³ − …, on
        // (0, end − phase].
        let mut higher: Vec<R> = vec![-(half.clone() + t[2].clone())];
        higher.extend(t[3..].iter().map(|a| -a.clone()));
        let q = if st.height > zero {
            // Above the table: the gap itself, height + w s − (1/2 + a2) s² − ….
            let mut q = vec![st.height.clone(), st.w.clone()];
            q.extend(higher);
            q
        } else if st.w > zero {
            let mut q = vec![st.w.clone()];
            q.extend(higher);
            q
        } else {
            // Leaving with no relative velocity (after a release): gap/s² =
            // −(1/2 + a2) − a3 s − …, whose constant term is 0 to rounding at a smooth
            // release. The ball leaves where the first term that is not zero is
            // positive; a ball that cannot leave rides on.
            let tiny = R::epsilon(&sys.ctx) * sys.num(8.0) * (one.clone() + t[2].abs());
            if higher[0].abs() <= tiny {
                higher[0] = zero.clone();
            }
            match higher.iter().position(|c| *c != zero) {
                Some(i) if higher[i] > zero => higher.split_off(i),
                _ => {
                    let (period, phase) = (st.period, st.phase.clone());
                    return Ok(self.stick_at(period, phase, true));
                }
            }
        };
        let first_len = sys.pieces[j0].end.clone() - st.phase.clone();
        let found = first_root(&q, &zero, &first_len, &sys.ctx);
        // (time since launch, phase of the landing from the launch's period)
        let mut hit: Option<(R, R)> = found.map(|s| (s.clone(), st.phase.clone() + s));
        let y0 = t[0].clone() + st.height.clone();
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
            let mut g = vec![
                y0.clone() + v0.clone() * delta.clone()
                    - half.clone() * delta.clone() * delta.clone()
                    - c(0),
                v0.clone() - delta.clone() - c(1),
                -half.clone() - c(2),
            ];
            g.extend((3..p.coeffs.len().max(4)).map(|k| -c(k)));
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
        Ok(self.land(theta, v0 - s))
    }

    /// The landing `theta` periods after the start of the state's period, the ball
    /// arriving with velocity `vball`: the restitution law, the new state and its event.
    fn land(&mut self, theta: R, vball: R) -> PreciseEvent<R> {
        let sys = &self.sys;
        let (period, phase) = wrap(self.state.period, theta, &sys.num(1.0));
        let df = sys.jet(&phase)[1].clone();
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
            height: sys.num(0.0),
        };
        PreciseEvent {
            kind: EventKind::Impact,
            period,
            phase,
            v,
            vrel: u,
        }
    }

    /// The release `theta` periods after the start of the state's period: the ball
    /// leaves with the table's velocity.
    fn release_at(&mut self, theta: R) -> PreciseEvent<R> {
        let sys = &self.sys;
        let zero = sys.num(0.0);
        let (period, phase) = wrap(self.state.period, theta, &sys.num(1.0));
        let df = sys.jet(&phase)[1].clone();
        self.state = PreciseState {
            period,
            phase: phase.clone(),
            v: df.clone(),
            w: zero.clone(),
            stuck: false,
            release_after: false,
            height: zero.clone(),
        };
        PreciseEvent {
            kind: EventKind::Release,
            period,
            phase,
            v: df,
            vrel: zero,
        }
    }

    /// The release after a stick (`table::release`: the walk over the pieces
    /// written once for both maps), or resting for good.
    fn release(&mut self) -> Result<PreciseEvent<R>, PreciseHalt> {
        let sys = &self.sys;
        let st = &self.state;
        let zero = sys.num(0.0);
        let one = sys.num(1.0);
        // 1 + αF'' on piece j as a polynomial in its variable: 1 + 2a2 + 6a3 s + 12a4 s²
        // + ….
        let excess = |j: usize| {
            let t = sys.taylor(j, &zero);
            let mut h: Vec<R> = (2..t.len())
                .map(|k| sys.num((k * (k - 1)) as f64) * t[k].clone())
                .collect();
            h[0] = one.clone() + h[0].clone();
            h
        };
        // The first phase on piece j from `from` (its start if None) after which the
        // excess is negative.
        let first_on = |j: usize, from: Option<&R>, strict: bool| match &sys.omega {
            Some(w) => {
                let from = from.cloned().unwrap_or_else(|| zero.clone());
                release::sine_release_in(&sys.alpha, w, &from, strict, &sys.ctx)
            }
            None => {
                let p = &sys.pieces[j];
                let from = from.map_or_else(|| zero.clone(), |f| f.clone() - p.start.clone());
                let h = excess(j);
                let sigma = if !strict && eval(&h, &from) < zero {
                    Some(from)
                } else {
                    first_sign_change(&h, &from, &(p.end.clone() - p.start.clone()), &sys.ctx)
                };
                sigma.map(|s| p.start.clone() + s)
            }
        };
        let count = sys.pieces.len().max(1);
        let j0 = if sys.omega.is_some() {
            0
        } else {
            sys.index(&st.phase)
        };
        match release::first_release(count, j0, &st.phase, st.release_after, first_on) {
            Some((periods, at)) => {
                let theta = sys.num(periods as f64) + at;
                Ok(self.release_at(theta))
            }
            None => Err(PreciseHalt::Resting),
        }
    }
}

/// (period, phase) of `theta` periods after the start of `period`, phase in [0, 1).
pub(super) fn wrap<R: Real>(period: i64, theta: R, one: &R) -> (i64, R) {
    let whole = theta.floor();
    let k = whole.to_f64() as i64;
    let phase = theta - whole;
    if phase >= *one {
        (period.saturating_add(k + 1), phase - one.clone())
    } else {
        (period.saturating_add(k), phase)
    }
}
