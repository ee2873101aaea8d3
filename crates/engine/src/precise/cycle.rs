//! A cycle of impacts (no stick) at any precision, and its multipliers and Lyapunov
//! exponents: Newton's method on the n-impact return map, with the tangent map written
//! once for every number type ([`crate::tangent::impact_jacobian`]) evaluated at the
//! working precision; then the same at a second, higher precision, and only the digits
//! on which the two agree are reported ([`impact_cycle_to_digits`]).
//!
//! What replaces the f64 cycle solver's tolerances at any precision: Newton's method
//! stops where its step reaches the precision's unit roundoff (or stops shrinking), and
//! the comparison of two precisions, not a tolerance, says how many digits hold. The
//! determinant of the monodromy is taken as the product of the flights' determinants
//! r wᵢ/|uᵢ₊₁| (free of cancellation); on a closed cycle it is r²ⁿ exactly, which the
//! answer states as evidence (`det_error`).

use super::digits::{agreeing_digits, DigitsProgress, MakeBig};
use super::{PreciseHalt, PreciseMap, PreciseState, PreciseSystem};
use crate::map::EventKind;
use crate::real::{bits_for_digits, Big, Real};
use crate::tangent::{flight_partials, impact_jacobian};
use std::ops::ControlFlow;

/// Newton iterations allowed at one precision (from a double's 15 digits, quadratic
/// convergence reaches thousands of digits in under ten).
pub const NEWTON_STEPS: usize = 60;

/// Why a cycle of impacts could not be solved at a precision.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CycleLost {
    /// The launch is not above the table's velocity (w ≤ 0).
    Launch,
    /// An event of the cycle is a stick or a release, not an impact.
    NotImpacts,
    /// The map stopped within the cycle.
    Halt(PreciseHalt),
    /// M − I is singular (a multiplier 1: a fold).
    Singular,
    /// Newton's method did not settle within its steps.
    NoConvergence,
}

impl std::fmt::Display for CycleLost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CycleLost::Launch => write!(f, "a launch is not above the table's velocity"),
            CycleLost::NotImpacts => write!(f, "an event of the cycle is a stick or a release"),
            CycleLost::Halt(h) => write!(f, "the map stopped within the cycle ({h:?})"),
            CycleLost::Singular => write!(f, "M − I is singular (a multiplier 1: a fold)"),
            CycleLost::NoConvergence => write!(f, "Newton's method did not settle"),
        }
    }
}

/// The multipliers of a cycle: the eigenvalues of its monodromy M.
#[derive(Clone, Debug, PartialEq)]
pub enum Multipliers<R> {
    /// Two real ones, the larger in modulus first.
    Real([R; 2]),
    /// A complex pair re ± i·im (of modulus √det M = rⁿ).
    Complex {
        /// The real part.
        re: R,
        /// The imaginary part (positive).
        im: R,
    },
}

impl<R> Multipliers<R> {
    /// The two real multipliers, or the pair's real and imaginary parts; and whether
    /// they are a complex pair.
    fn parts(&self) -> ([&R; 2], bool) {
        match self {
            Multipliers::Real([a, b]) => ([a, b], false),
            Multipliers::Complex { re, im } => ([re, im], true),
        }
    }
}

/// The larger of two values.
fn larger<R: Real>(a: R, b: R) -> R {
    if a > b {
        a
    } else {
        b
    }
}

/// An (n, k) cycle of impacts solved at one precision.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleAt<R> {
    /// The launch phase right after the cycle's first impact, in [0, 1).
    pub phase: R,
    /// The ball's velocity right after it.
    pub v: R,
    /// M: the Jacobian of the n-impact map at the launch.
    pub monodromy: [[R; 2]; 2],
    /// det M as the product of the flights' determinants.
    pub det: R,
    /// The multipliers.
    pub multipliers: Multipliers<R>,
    /// Both exponents per impact, ln|μ|/n, the larger first.
    pub exponents: [R; 2],
    /// The return's residual after the last Newton step, max(|Δt|, |Δv|).
    pub residual: R,
    /// The smallest relative landing velocity |u| of the cycle.
    pub min_speed: R,
}

/// One pass of n impacts from (phase, v): the return (tₙ − t₀ − k, vₙ − v₀), M, det M as
/// the flights' product and the smallest |u|.
#[allow(clippy::type_complexity)]
fn pass<R: Real>(
    sys: &PreciseSystem<R>,
    n: usize,
    k: i64,
    phase: &R,
    v: &R,
) -> Result<([R; 2], [[R; 2]; 2], R, R), CycleLost> {
    let zero = sys.num(0.0);
    let one = sys.num(1.0);
    let df = sys.jet(phase)[1].clone();
    let w = v.clone() - df;
    if w <= zero {
        return Err(CycleLost::Launch);
    }
    let mut map = PreciseMap::new(sys.clone(), PreciseState::launch(sys, 0, phase.clone(), w));
    let mut m = [[one.clone(), zero.clone()], [zero.clone(), one.clone()]];
    let mut det = one.clone();
    let mut min_speed: Option<R> = None;
    let mut last = None;
    for _ in 0..n {
        let before = map.state().clone();
        let e = map.step().map_err(CycleLost::Halt)?;
        if e.kind != EventKind::Impact || before.w <= zero {
            return Err(CycleLost::NotImpacts);
        }
        let tau =
            sys.num((e.period - before.period) as f64) + e.phase.clone() - before.phase.clone();
        let (a, b) = flight_partials(before.w.clone(), tau, e.vrel.clone());
        det = det * sys.r.clone() * (b.clone() - a.clone());
        let ddf = sys.jet(&e.phase)[2].clone();
        let j = impact_jacobian(a, b, ddf, sys.r.clone(), one.clone());
        m = mul(&j, &m);
        let speed = e.vrel.abs();
        if min_speed.as_ref().is_none_or(|s| speed < *s) {
            min_speed = Some(speed);
        }
        last = Some(e);
    }
    let e = last.ok_or(CycleLost::NotImpacts)?;
    let ret = [
        sys.num((e.period - k) as f64) + e.phase - phase.clone(),
        e.v - v.clone(),
    ];
    Ok((ret, m, det, min_speed.unwrap_or(zero)))
}

fn mul<R: Real>(a: &[[R; 2]; 2], b: &[[R; 2]; 2]) -> [[R; 2]; 2] {
    let at =
        |i: usize, j: usize| a[i][0].clone() * b[0][j].clone() + a[i][1].clone() * b[1][j].clone();
    [[at(0, 0), at(0, 1)], [at(1, 0), at(1, 1)]]
}

/// The multipliers of M with det M = `det`, and both exponents per impact.
fn spectrum<R: Real>(
    m: &[[R; 2]; 2],
    det: &R,
    n: usize,
    ctx: &R::Context,
) -> (Multipliers<R>, [R; 2]) {
    let zero = R::from_f64(0.0, ctx);
    let two = R::from_f64(2.0, ctx);
    let per = R::from_f64(n as f64, ctx);
    let tr = m[0][0].clone() + m[1][1].clone();
    let disc = tr.clone() * tr.clone() - R::from_f64(4.0, ctx) * det.clone();
    if disc < zero {
        let re = tr / two.clone();
        let im = (-disc).sqrt() / two.clone();
        // |μ|² = det M.
        let lambda = det.ln() / (two * per);
        return (Multipliers::Complex { re, im }, [lambda.clone(), lambda]);
    }
    let root = disc.sqrt();
    // The larger in modulus without cancellation; the other from the determinant.
    let big = if tr < zero {
        (tr - root) / two
    } else {
        (tr + root) / two
    };
    let small = det.clone() / big.clone();
    let exps = [big.abs().ln() / per.clone(), small.abs().ln() / per];
    (Multipliers::Real([big, small]), exps)
}

/// The (n, k) cycle of impacts through (phase, v) solved by Newton's method at the
/// precision of `sys`, from that guess. `progress` hears of the events of each pass.
pub fn solve_cycle<R: Real>(
    sys: &PreciseSystem<R>,
    n: usize,
    k: u32,
    phase: R,
    v: R,
    progress: &mut dyn FnMut(u64),
) -> Result<CycleAt<R>, CycleLost> {
    let ctx = sys.context().clone();
    let zero = R::from_f64(0.0, &ctx);
    let one = R::from_f64(1.0, &ctx);
    let eps = R::epsilon(&ctx);
    let k = i64::from(k);
    let (mut phase, mut v) = (phase, v);
    let mut previous: Option<R> = None;
    for _ in 0..NEWTON_STEPS {
        let (f, m, _, _) = pass(sys, n, k, &phase, &v)?;
        progress(n as u64);
        // (M − I) δ = −F.
        let (a, b) = (m[0][0].clone() - one.clone(), m[0][1].clone());
        let (c, d) = (m[1][0].clone(), m[1][1].clone() - one.clone());
        let det = a.clone() * d.clone() - b.clone() * c.clone();
        if det == zero {
            return Err(CycleLost::Singular);
        }
        let dt = -(d * f[0].clone() - b * f[1].clone()) / det.clone();
        let dv = -(a * f[1].clone() - c * f[0].clone()) / det;
        phase = phase + dt.clone();
        v = v + dv.clone();
        // Kept in [0, 1): a whole period more or less is the same launch.
        let whole = phase.floor();
        phase = phase - whole;
        let size = larger(dt.abs(), dv.abs() / (one.clone() + v.abs()));
        // Settled: the step is at the precision's rounding, or it stopped shrinking
        // quadratically once small (an ill-conditioned cycle's last digits are noise,
        // which the comparison of two precisions measures).
        let at_rounding = size <= eps.clone() * R::from_f64(1024.0, &ctx);
        let stalled = previous
            .as_ref()
            .is_some_and(|p| size.clone() * R::from_f64(2.0, &ctx) > *p && *p < eps.clone().sqrt());
        if at_rounding || stalled {
            let (f, m, det, min_speed) = pass(sys, n, k, &phase, &v)?;
            progress(n as u64);
            let residual = larger(f[0].abs(), f[1].abs());
            let (multipliers, exponents) = spectrum(&m, &det, n, &ctx);
            return Ok(CycleAt {
                phase,
                v,
                monodromy: m,
                det,
                multipliers,
                exponents,
                residual,
                min_speed,
            });
        }
        previous = Some(size);
    }
    Err(CycleLost::NoConvergence)
}

/// A value of an answer with the significant digits on which two precisions agree.
#[derive(Clone, Debug, PartialEq)]
pub struct Agreed {
    /// The value, from the more precise run.
    pub value: Big,
    /// The digits the two runs agree on (at most the digits asked for).
    pub digits: u32,
}

/// Whether a cycle attracts, as far as its multipliers decide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    /// Both multipliers inside the unit circle.
    Stable,
    /// One outside.
    Unstable,
    /// The largest modulus equals 1 within the two runs' difference.
    Undecided,
}

impl Stability {
    /// Its name in outputs: `stable`, `unstable` or `undecided`.
    pub fn as_str(self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::Undecided => "undecided",
        }
    }
}

/// An (n, k) cycle of impacts to a number of digits ([`impact_cycle_to_digits`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ImpactCycle {
    /// Impacts per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// The launch phase after its first impact.
    pub phase: Agreed,
    /// The velocity there.
    pub v: Agreed,
    /// The multipliers: two real ones (larger modulus first), or a complex pair's real
    /// and imaginary parts.
    pub multipliers: [Agreed; 2],
    /// Whether the multipliers are a complex pair.
    pub complex: bool,
    /// Both exponents per impact, the larger first.
    pub exponents: [Agreed; 2],
    /// The largest multiplier's modulus minus one, from the more precise run: how far
    /// the cycle is from losing stability.
    pub margin: f64,
    /// Whether it attracts.
    pub stability: Stability,
    /// det M / r²ⁿ − 1 at the more precise run (zero on a closed cycle, up to its
    /// residual).
    pub det_error: f64,
    /// The return residual at the more precise run.
    pub residual: f64,
    /// The smallest relative landing velocity |u| (double).
    pub min_speed: f64,
    /// 2 ln r at the more precise run, which the exponents sum to.
    pub two_ln_r: Big,
    /// The digits of the two runs that agreed.
    pub precision: (u32, u32),
}

impl ImpactCycle {
    /// The values printed: launch phase and velocity, both multipliers (or the pair's
    /// parts) and both exponents.
    pub fn values(&self) -> [&Agreed; 6] {
        let (m, e) = (&self.multipliers, &self.exponents);
        [&self.phase, &self.v, &m[0], &m[1], &e[0], &e[1]]
    }

    /// The fewest digits any of its values holds to.
    pub fn digits(&self) -> u32 {
        least(self.values())
    }
}

/// The fewest digits of `values`.
fn least(values: [&Agreed; 6]) -> u32 {
    values.iter().map(|a| a.digits).min().unwrap_or(0)
}

/// What [`impact_cycle_to_digits`] decided.
#[derive(Clone, Debug, PartialEq)]
pub enum ImpactCycleVerdict {
    /// The cycle, every value to the digits asked for.
    Found(Box<ImpactCycle>),
    /// The two precisions disagree even at the most precision allowed.
    Undecided {
        /// The digits the last pair was run at.
        tried: (u32, u32),
        /// The fewest digits on which they agreed over the values.
        agreed: u32,
        /// The digits the answer needs at least, by the digits the last pair lost.
        need: u32,
    },
    /// The cycle could not be solved at a precision.
    Lost {
        /// The digits of the run that failed.
        digits: u32,
        /// Why.
        why: CycleLost,
    },
}

/// The (n, k) cycle of impacts through the guess (phase, v) (a double's, e.g. from the
/// f64 orbit that settled on it) in the system `make(bits)` gives, to `digits`
/// significant digits: solved at `digits` + 10 digits and at twice that, doubled while
/// the lower stays within `max_digits`, until both agree on the launch, the multipliers
/// and the exponents to `digits`. `progress` hears of the events done and may stop the
/// work (then None).
pub fn impact_cycle_to_digits(
    make: &MakeBig<'_>,
    n: usize,
    k: u32,
    guess: (f64, f64),
    digits: u32,
    max_digits: u32,
    progress: &mut dyn FnMut(DigitsProgress) -> ControlFlow<()>,
) -> Option<ImpactCycleVerdict> {
    let mut work = digits + 10;
    let mut done = 0u64;
    let mut stopped = false;
    loop {
        let mut solve = |w: u32| {
            let bits = bits_for_digits(w);
            let (sys, _) = make(bits);
            let (phase, v) = (Big::from_f64(guess.0, &bits), Big::from_f64(guess.1, &bits));
            solve_cycle(&sys, n, k, phase, v, &mut |e| {
                done += e;
                stopped |= progress(DigitsProgress {
                    digits: w,
                    done,
                    total: 0,
                })
                .is_break();
            })
            .map(|c| (c, sys.r.clone()))
        };
        let lo = solve(work);
        let hi = solve(2 * work);
        if stopped {
            return None;
        }
        let (lo, (hi, r)) = match (lo, hi) {
            (Ok(lo), Ok(hi)) => (lo.0, hi),
            (Err(why), _) => return Some(ImpactCycleVerdict::Lost { digits: work, why }),
            (_, Err(why)) => {
                return Some(ImpactCycleVerdict::Lost {
                    digits: 2 * work,
                    why,
                })
            }
        };
        let cap = 2 * work;
        let agree = |a: &Big, b: &Big| Agreed {
            value: b.clone(),
            digits: agreeing_digits(a, b, cap).min(digits),
        };
        let ((a, complex_lo), (b, complex)) = (lo.multipliers.parts(), hi.multipliers.parts());
        let mult = if complex_lo == complex {
            [agree(a[0], b[0]), agree(a[1], b[1])]
        } else {
            // Real at one precision and complex at the other: a double multiplier
            // within the difference.
            b.map(|x| Agreed {
                value: x.clone(),
                digits: 0,
            })
        };
        let exponents = [
            agree(&lo.exponents[0], &hi.exponents[0]),
            agree(&lo.exponents[1], &hi.exponents[1]),
        ];
        let phase = agree(&lo.phase, &hi.phase);
        let v = agree(&lo.v, &hi.v);
        let agreed = least([&phase, &v, &mult[0], &mult[1], &exponents[0], &exponents[1]]);
        if agreed >= digits {
            let bits = hi.phase.context();
            let one = Big::from_f64(1.0, &bits);
            // The largest modulus, and how far apart the two runs have it.
            let modulus = |m: &Multipliers<Big>| match m {
                Multipliers::Real(x) => x[0].abs(),
                Multipliers::Complex { re, im } => {
                    (re.clone() * re.clone() + im.clone() * im.clone()).sqrt()
                }
            };
            let (ml, mh) = (modulus(&lo.multipliers), modulus(&hi.multipliers));
            let margin = mh.clone() - one.clone();
            let spread = (ml - mh).abs();
            let stability = if margin.abs() <= spread {
                Stability::Undecided
            } else if margin < Big::from_f64(0.0, &bits) {
                Stability::Stable
            } else {
                Stability::Unstable
            };
            let r2n = (0..2 * n).fold(one.clone(), |p, _| p * r.clone());
            let det_error = (hi.det.clone() / r2n - one).to_f64();
            let two_ln_r = Big::from_f64(2.0, &bits) * r.ln();
            return Some(ImpactCycleVerdict::Found(Box::new(ImpactCycle {
                n,
                k,
                phase,
                v,
                multipliers: mult,
                complex,
                exponents,
                margin: margin.to_f64(),
                stability,
                det_error,
                residual: hi.residual.to_f64(),
                min_speed: hi.min_speed.to_f64(),
                two_ln_r,
                precision: (work, 2 * work),
            })));
        }
        if 2 * work > max_digits {
            return Some(ImpactCycleVerdict::Undecided {
                tried: (work, 2 * work),
                agreed,
                need: digits + (work - agreed.min(work)) + 10,
            });
        }
        work *= 2;
    }
}
