//! Proofs of periodic orbits by interval arithmetic: an exact (n, k) cycle exists in a
//! small box, is the only one there, every landing of it is the first contact of its
//! flight, and (where the enclosure of its multipliers excludes the unit circle) it is
//! stable or unstable.
//!
//! The cycle is written as 2n equations in the launch phases φᵢ and velocities vᵢ
//! right after its n impacts (Pᵢ whole periods before impact i, Pₙ = k, φₙ = φ₀):
//!
//!   Gᵢ = f(φᵢ) − f(φᵢ₊₁) + τᵢ (vᵢ − τᵢ/2) = 0     (the ball is on the table again),
//!   Hᵢ = vᵢ₊₁ − (1 + r) f'(φᵢ₊₁) + r (vᵢ − τᵢ) = 0  (the restitution law),
//!
//! with τᵢ = Pᵢ₊₁ − Pᵢ + φᵢ₊₁ − φᵢ. Newton's solution x̃ (the map's, refined on these
//! equations) is put in a box X = x̃ ± ρ, and the Krawczyk operator
//!
//!   K(X) = x̃ − C F(x̃) + (I − C F'(X)) (X − x̃),   C ≈ F'(x̃)⁻¹,
//!
//! is evaluated in [`Interval`]s over the parameters' enclosures (α, r and the table's
//! coefficients as the decimals they are written as, `table::Enclosed`); F(x̃) is
//! taken at the middle α̃ of α's enclosure and the rest enters as (C ∂F/∂α)(α − α̃), so
//! that a wide α-interval (a special point's) keeps C F's correlations. K(X) inside
//! X's interior proves that F has exactly one zero in X, for every parameter value in
//! the enclosures; ρ grows from 1e-15 until that holds or 1e-9 fails. Each impact's box
//! must lie inside one piece of the table (f'' jumps at a breakpoint), and each flight
//! is shown to meet the table first at its landing (`flight::first_landing`).
//!
//! The multipliers: M = ∏ Jᵢ over the box (the tangent map of each impact, as
//! [`crate::tangent`] writes it), det M = r²ⁿ exactly on a cycle. Both multipliers are
//! inside the unit circle iff 1 + tr M + det M > 0 and 1 − tr M + det M > 0 (Jury's
//! conditions with 0 < det M < 1); either below zero proves a multiplier outside it.

mod flight;
mod fold;
mod special;
mod table;

pub use flight::{FlightFailure, FlightProof};
pub use fold::certify_fold;
pub use special::{
    certify_border_collision, certify_period_doubling, CertifiedSpecial, SpecialFailure,
    SpecialKind,
};

use crate::linalg::inverse;
use crate::orbits::periodic::{cycle, CyclePoint, PassError};
use crate::real::Interval;
use crate::system::System;
use crate::table::Table;
use crate::time::{phase_distance, wrap_phase};
use table::{AtBreakpoint, Enclosed};

/// How far (in phase, and in velocity relative to 1 + |v₀|) the cycle Newton's method
/// finds may lie from the guess and still be the one the guess pointed at.
pub const GUESS_DISTANCE: f64 = 0.05;
/// The box's half-widths tried, relative to max(1, |x̃ᵢ|).
const INFLATIONS: [f64; 7] = [1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9];
/// Multiples of a hint's widths a box around it is widened by.
const HINT_WIDENINGS: [f64; 4] = [0.5, 2.0, 8.0, 32.0];
/// Newton steps on the cycle's equations before the proof (the map's solution is
/// already within 1e-11; these take it to the last bits).
const REFINE_STEPS: usize = 4;

/// The outcome of a proof attempt on one (n, k) cycle.
#[derive(Clone, Debug)]
pub struct Certificate {
    /// Impacts per cycle.
    pub n: usize,
    /// Table periods per cycle.
    pub k: u32,
    /// The enclosures of α and r the statements hold for.
    pub alpha: Interval,
    /// See `alpha`.
    pub r: Interval,
    /// The cycle Newton's method found (None if it found none).
    pub cycle: Option<CyclePoint>,
    /// The box with exactly one zero of the cycle's equations (None if not shown).
    pub enclosure: Option<Enclosure>,
    /// What each flight's first-landing proof showed (as far as it got).
    pub flights: Vec<FlightProof>,
    /// The multipliers and the stability, once the orbit is proved.
    pub stability: Option<Stability>,
    /// Why the orbit is not proved (None: proved).
    pub failure: Option<Failure>,
}

impl Certificate {
    /// Nothing shown yet of the (n, k) cycle `cycle` (Newton's, if found) of `enc`.
    fn start(enc: &Enclosed, n: usize, k: u32, cycle: Option<CyclePoint>) -> Certificate {
        Certificate {
            n,
            k,
            alpha: enc.alpha,
            r: enc.r,
            cycle,
            enclosure: None,
            flights: Vec::new(),
            stability: None,
            failure: None,
        }
    }

    /// An exact (n, k) cycle of the impact map is proved in the box.
    pub fn proved(&self) -> bool {
        self.failure.is_none() && self.enclosure.is_some()
    }
}

/// The box of the cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Enclosure {
    /// The impact phases φᵢ (as reals: a box may reach just past 0 or 1).
    pub phases: Vec<Interval>,
    /// The launch velocities vᵢ after them.
    pub velocities: Vec<Interval>,
    /// Whole periods Pᵢ from the first impact to impact i.
    pub periods: Vec<i64>,
    /// The half-width of the box the Krawczyk test succeeded on, relative to
    /// max(1, |x̃ᵢ|).
    pub inflation: f64,
    /// The largest width of a phase or velocity in the box.
    pub width: f64,
}

/// The multipliers of a proved cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stability {
    /// tr M over the box.
    pub trace: Interval,
    /// det M = r²ⁿ.
    pub det: Interval,
    /// The multipliers, as far as the enclosure tells them apart.
    pub multipliers: Multipliers,
    /// Stable, unstable, or not decided.
    pub verdict: StabilityVerdict,
}

impl Stability {
    /// (1 + λ₁)(1 + λ₂) = 1 + tr M + det M: zero at a period doubling.
    pub fn pd_test(&self) -> Interval {
        Interval::point(1.0) + self.trace + self.det
    }

    /// (1 − λ₁)(1 − λ₂) = 1 − tr M + det M: zero at a fold.
    pub fn fold_test(&self) -> Interval {
        Interval::point(1.0) - self.trace + self.det
    }
}

/// Enclosures of the two multipliers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Multipliers {
    /// Two real multipliers, the larger first.
    Real([Interval; 2]),
    /// A complex pair re ± i·im.
    Complex {
        /// The real part.
        re: Interval,
        /// The imaginary part's size.
        im: Interval,
    },
    /// The discriminant's sign is not decided: both lie within `re` ± i·[0, im].
    Unresolved {
        /// tr M / 2.
        re: Interval,
        /// The largest imaginary part or real spread.
        spread: f64,
    },
}

/// What the enclosure of the multipliers proves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StabilityVerdict {
    /// Both multipliers inside the unit circle.
    Stable,
    /// A multiplier outside it.
    Unstable,
    /// A multiplier within the enclosure's width of −1 or +1.
    Undecided {
        /// Which: −1 (a period doubling near) or +1 (a fold near).
        near: Near,
    },
}

/// Which bifurcation keeps the stability from being decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Near {
    /// A multiplier at about −1.
    PeriodDoubling,
    /// A multiplier at about +1.
    Fold,
}

/// Why a cycle is not proved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Failure {
    /// Newton's method found no (n, k) cycle from the guess.
    NoCycle(PassError),
    /// The cycle found lies this far from the guess: not the one pointed at.
    FarFromGuess {
        /// Its launch phase and velocity.
        phase: f64,
        /// See `phase`.
        v: f64,
        /// The distance (phase, or velocity relative to 1 + |v₀|).
        distance: f64,
    },
    /// The box of an impact contains a breakpoint of the table.
    Breakpoint {
        /// Which impact (0 is the launch's).
        impact: usize,
        /// At about this phase.
        phase: f64,
    },
    /// No box tried was mapped into itself by the Krawczyk operator.
    NotContracting {
        /// The largest width of K(X) on the widest box tried.
        width: f64,
    },
    /// A flight's landing is not shown to be its first contact.
    Flight {
        /// Which flight (from impact `flight` to the next).
        flight: usize,
        /// What failed.
        why: FlightFailure,
    },
}

/// Prove the (n, k) cycle that Newton's method finds from the launch guess (t̂₀, v₀).
pub fn certify(sys: &System, n: usize, k: u32, t0: f64, v0: f64) -> Certificate {
    let enc = Enclosed::of(sys);
    let pt = match cycle(sys, n, k, t0, v0) {
        Ok(pt) => pt,
        Err(e) => {
            return Certificate {
                failure: Some(Failure::NoCycle(e)),
                ..Certificate::start(&enc, n, k, None)
            }
        }
    };
    let distance = phase_distance(pt.phases[0], wrap_phase(t0))
        .max((pt.velocities[0] - v0).abs() / (1.0 + v0.abs()));
    if distance > GUESS_DISTANCE {
        let far = Failure::FarFromGuess {
            phase: pt.phases[0],
            v: pt.velocities[0],
            distance,
        };
        return Certificate {
            failure: Some(far),
            ..Certificate::start(&enc, n, k, Some(pt))
        };
    }
    prove(&enc, &pt, &[], None)
}

/// Prove the cycle `pt` (an accepted point of [`crate::orbits::periodic`]).
pub fn certify_cycle(sys: &System, pt: &CyclePoint) -> Certificate {
    prove(&Enclosed::of(sys), pt, &[], None)
}

/// Prove the cycle near `pt` of the system `enc` (whose α may be an interval), with the
/// impacts `forced` on a piece's polynomial; the boxes tried are around the hint
/// (phases then velocities) if one is given.
fn prove(
    enc: &Enclosed,
    pt: &CyclePoint,
    forced: &[Option<(f64, usize)>],
    hint: Option<&[Interval]>,
) -> Certificate {
    let mut out = Certificate::start(enc, pt.n, pt.k, Some(pt.clone()));
    certify_with(enc, pt, forced, hint, &mut out);
    out
}

/// The special point `s` of a branch of `table` at restitution `r` proved as an
/// α-interval: a period doubling of the branch's own cycle, a fold or a border
/// collision; None for the kinds no proof is made of (grazings, window exits, ...).
pub fn certify_special(
    table: &Table,
    r: f64,
    s: &crate::orbits::events::Special,
) -> Option<CertifiedSpecial> {
    use crate::orbits::events::Kind;
    match s.kind {
        Kind::PeriodDoubling => Some(certify_period_doubling(table, r, &s.point)),
        Kind::Fold => Some(certify_fold(table, r, &s.point)),
        Kind::BorderCollision => Some(certify_border_collision(
            table, r, &s.point, s.impact, s.phase,
        )),
        _ => None,
    }
}

/// The cycle's equations at one set of boxes.
struct Equations<'a> {
    enc: &'a Enclosed,
    n: usize,
    /// Whole periods before each impact, and k after the last.
    periods: Vec<i64>,
    /// Impacts whose table is one piece's polynomial wherever the box lies (a border
    /// collision's near side): (whole periods, piece index).
    forced: &'a [Option<(f64, usize)>],
}

impl Equations<'_> {
    /// τᵢ over the boxes.
    fn flight(&self, x: &[Interval], i: usize) -> Interval {
        let j = (i + 1) % self.n;
        let whole = (self.periods[i + 1] - self.periods[i]) as f64;
        (x[j] - x[i]) + Interval::point(whole)
    }

    fn jets(&self, x: &[Interval]) -> Result<Vec<[Interval; 3]>, Failure> {
        (0..self.n)
            .map(|i| match self.forced.get(i).copied().flatten() {
                Some(piece) => Ok(self.enc.jet_on(x[i], piece)),
                None => self
                    .enc
                    .jet(x[i])
                    .map_err(|AtBreakpoint(phase)| Failure::Breakpoint { impact: i, phase }),
            })
            .collect()
    }

    /// (G₀ … Gₙ₋₁, H₀ … Hₙ₋₁).
    fn residual(&self, x: &[Interval]) -> Result<Vec<Interval>, Failure> {
        let n = self.n;
        let jets = self.jets(x)?;
        let (r, half) = (self.enc.r, Interval::point(0.5));
        let one = Interval::point(1.0);
        let mut out = vec![Interval::point(0.0); 2 * n];
        for i in 0..n {
            let j = (i + 1) % n;
            let tau = self.flight(x, i);
            let (vi, vj) = (x[n + i], x[n + j]);
            out[i] = (jets[i][0] - jets[j][0]) + tau * (vi - tau * half);
            out[n + i] = vj - (one + r) * jets[j][1] + r * (vi - tau);
        }
        Ok(out)
    }

    /// The Jacobian of the residual over the boxes (rows as `residual`, columns
    /// φ₀ … φₙ₋₁, v₀ … vₙ₋₁).
    fn jacobian(&self, x: &[Interval]) -> Result<Vec<Vec<Interval>>, Failure> {
        let n = self.n;
        let jets = self.jets(x)?;
        let r = self.enc.r;
        let one = Interval::point(1.0);
        let mut m = vec![vec![Interval::point(0.0); 2 * n]; 2 * n];
        for i in 0..n {
            let j = (i + 1) % n;
            let tau = self.flight(x, i);
            let vi = x[n + i];
            // Gᵢ: the terms add up where n = 1 (φⱼ is φᵢ).
            m[i][i] = m[i][i] + (jets[i][1] - vi + tau);
            m[i][j] = m[i][j] + (vi - tau - jets[j][1]);
            m[i][n + i] = m[i][n + i] + tau;
            // Hᵢ.
            m[n + i][n + j] = m[n + i][n + j] + one;
            m[n + i][j] = m[n + i][j] - ((one + r) * jets[j][2] + r);
            m[n + i][i] = m[n + i][i] + r;
            m[n + i][n + i] = m[n + i][n + i] + r;
        }
        Ok(m)
    }
}

impl Equations<'_> {
    /// ∂(G, H)/∂α over the boxes: F(φᵢ) − F(φᵢ₊₁) and −(1 + r) F'(φᵢ₊₁) (f = αF).
    fn alpha_column(&self, x: &[Interval]) -> Result<Vec<Interval>, Failure> {
        let n = self.n;
        let jets = self.jets(x)?;
        let a = self.enc.alpha;
        let one = Interval::point(1.0);
        let mut out = vec![Interval::point(0.0); 2 * n];
        for i in 0..n {
            let j = (i + 1) % n;
            out[i] = (jets[i][0] - jets[j][0]) / a;
            out[n + i] = -((one + self.enc.r) * jets[j][1] / a);
        }
        Ok(out)
    }
}

/// Newton's method in doubles from `x` on the equations `eval` gives at a thin box (their
/// values and Jacobian): at most [`REFINE_STEPS`] steps, stopping where they cannot be
/// evaluated or a step is not finite.
fn refine(
    x: &mut [f64],
    eval: impl Fn(&[Interval]) -> Option<(Vec<Interval>, Vec<Vec<Interval>>)>,
) {
    for _ in 0..REFINE_STEPS {
        let Some((res, jac)) = eval(&thin(x)) else {
            break;
        };
        let Some(c) = inverse(&mids(&jac)) else {
            break;
        };
        let step: Vec<f64> = c
            .iter()
            .map(|row| row.iter().zip(&res).map(|(a, b)| a * b.mid()).sum())
            .collect();
        if step.iter().any(|s| !s.is_finite()) {
            break;
        }
        for (xi, s) in x.iter_mut().zip(&step) {
            *xi -= s;
        }
    }
}

/// The boxes a Krawczyk test tries around x̃: x̃ ± ρ max(1, |x̃ᵢ|) for each of
/// [`INFLATIONS`], or the hint (with x̃) widened by each of [`HINT_WIDENINGS`] times its
/// widths.
fn candidate_boxes(x: &[f64], hint: Option<&[Interval]>) -> Vec<Vec<Interval>> {
    match hint {
        None => INFLATIONS
            .iter()
            .map(|rho| {
                x.iter()
                    .map(|&v| {
                        let rad = rho * v.abs().max(1.0);
                        Interval::new(v - rad, v + rad).expect("finite")
                    })
                    .collect()
            })
            .collect(),
        Some(h) => HINT_WIDENINGS
            .iter()
            .map(|f| {
                h.iter()
                    .zip(x)
                    .map(|(hi, &v)| {
                        let span = hi.hull(&Interval::point(v));
                        let rad = f * span.width().max(INFLATIONS[0] * v.abs().max(1.0));
                        Interval::new(span.lo() - rad, span.hi() + rad).expect("finite")
                    })
                    .collect()
            })
            .collect(),
    }
}

/// Whole periods before each impact of `pt` from its first (0), and k after its last.
fn periods_of(pt: &CyclePoint) -> Vec<i64> {
    let n = pt.n;
    let mut periods = vec![0i64];
    let mut t = pt.phases[0];
    for i in 0..n {
        t += pt.flights[i];
        periods.push(if i + 1 == n {
            pt.k as i64
        } else {
            (t - pt.phases[i + 1]).round() as i64
        });
    }
    periods
}

fn mids(m: &[Vec<Interval>]) -> Vec<Vec<f64>> {
    m.iter()
        .map(|row| row.iter().map(Interval::mid).collect())
        .collect()
}

fn thin(x: &[f64]) -> Vec<Interval> {
    x.iter().map(|&v| Interval::point(v)).collect()
}

fn certify_with(
    enc: &Enclosed,
    pt: &CyclePoint,
    forced: &[Option<(f64, usize)>],
    hint: Option<&[Interval]>,
    out: &mut Certificate,
) {
    let n = pt.n;
    let periods = periods_of(pt);
    let eq = Equations {
        enc,
        n,
        periods: periods.clone(),
        forced,
    };
    let mut x: Vec<f64> = pt.phases.iter().chain(&pt.velocities).copied().collect();
    // Refine on the cycle's own equations.
    refine(&mut x, |xb| {
        Some((eq.residual(xb).ok()?, eq.jacobian(xb).ok()?))
    });
    let xt = thin(&x);
    // F at x̃ and at the middle α̃ of α's enclosure; the rest of α's enclosure enters
    // through F's α-column (the centred form in α keeps C F's correlations).
    let enc_mid = enc.clone().with_alpha(Interval::point(enc.alpha.mid()));
    let eq_mid = Equations {
        enc: &enc_mid,
        n,
        periods: eq.periods.clone(),
        forced,
    };
    let res = match eq_mid.residual(&xt) {
        Ok(r) => r,
        Err(f) => {
            out.failure = Some(f);
            return;
        }
    };
    let c = match eq.jacobian(&xt).map(|j| inverse(&mids(&j))) {
        Ok(Some(c)) => c,
        Ok(None) => {
            out.failure = Some(Failure::NotContracting {
                width: f64::INFINITY,
            });
            return;
        }
        Err(f) => {
            out.failure = Some(f);
            return;
        }
    };
    let boxes = candidate_boxes(&x, hint);
    let mut widest = f64::INFINITY;
    for b in boxes {
        let rho = b
            .iter()
            .zip(&x)
            .map(|(bi, &v)| 0.5 * bi.width() / v.abs().max(1.0))
            .fold(0.0, f64::max);
        let k = match krawczyk(&eq, &x, &res, &c, &b) {
            Ok(k) => k,
            Err(f) => {
                out.failure = Some(f);
                return;
            }
        };
        if k.iter().zip(&b).all(|(ki, bi)| ki.inside(bi)) {
            // The zero is in K ∩ X; K of a smaller box holding it holds it too.
            let mut bx: Vec<Interval> = k
                .iter()
                .zip(&b)
                .map(|(ki, bi)| ki.intersect(bi).expect("inside"))
                .collect();
            for _ in 0..2 {
                let Ok(k2) = krawczyk(&eq, &x, &res, &c, &bx) else {
                    break;
                };
                bx = k2
                    .iter()
                    .zip(&bx)
                    .map(|(ki, bi)| ki.intersect(bi).unwrap_or(*bi))
                    .collect();
            }
            let width = bx.iter().map(Interval::width).fold(0.0, f64::max);
            out.enclosure = Some(Enclosure {
                phases: bx[..n].to_vec(),
                velocities: bx[n..].to_vec(),
                periods: periods[..n].to_vec(),
                inflation: rho,
                width,
            });
            prove_flights_and_stability(&eq, &bx, out);
            return;
        }
        widest = k.iter().map(Interval::width).fold(0.0, f64::max);
    }
    out.failure = Some(Failure::NotContracting { width: widest });
}

/// K(X) = x̃ − C F(x̃) + (I − C F'(X))(X − x̃).
fn krawczyk(
    eq: &Equations,
    x: &[f64],
    res: &[Interval],
    c: &[Vec<f64>],
    b: &[Interval],
) -> Result<Vec<Interval>, Failure> {
    let jac = eq.jacobian(b)?;
    let alpha = eq.enc.alpha;
    let col = if alpha.width() > 0.0 {
        Some((eq.alpha_column(b)?, alpha - Interval::point(alpha.mid())))
    } else {
        None
    };
    Ok(krawczyk_step(x, res, c, &jac, col.as_ref(), b))
}

/// K(X) = x̃ − C F(x̃, p̃) − (C ∂F/∂p)(p − p̃) + (I − C J(X))(X − x̃), from F at x̃ and
/// the parameter's middle p̃ (`res`), J over the box X (`b`) and the parameter's column
/// over it with p − p̃ (`param`, if the parameter is an interval).
fn krawczyk_step(
    x: &[f64],
    res: &[Interval],
    c: &[Vec<f64>],
    jac: &[Vec<Interval>],
    param: Option<&(Vec<Interval>, Interval)>,
    b: &[Interval],
) -> Vec<Interval> {
    let m = x.len();
    let dx: Vec<Interval> = b
        .iter()
        .zip(x)
        .map(|(bi, &xi)| *bi - Interval::point(xi))
        .collect();
    let zero = Interval::point(0.0);
    (0..m)
        .map(|i| {
            let cf = (0..m).fold(zero, |s, l| s + Interval::point(c[i][l]) * res[l]);
            let mut acc = Interval::point(x[i]) - cf;
            if let Some((col, d)) = param {
                let ca = (0..m).fold(zero, |s, l| s + Interval::point(c[i][l]) * col[l]);
                acc = acc - ca * *d;
            }
            for j in 0..m {
                let cj = (0..m).fold(zero, |s, l| s + Interval::point(c[i][l]) * jac[l][j]);
                let e = if i == j {
                    Interval::point(1.0) - cj
                } else {
                    -cj
                };
                acc = acc + e * dx[j];
            }
            acc
        })
        .collect()
}

fn prove_flights_and_stability(eq: &Equations, bx: &[Interval], out: &mut Certificate) {
    let n = eq.n;
    for i in 0..n {
        let tau = eq.flight(bx, i);
        match flight::first_landing(eq.enc, bx[i], bx[n + i], tau) {
            Ok(p) => out.flights.push(p),
            Err(why) => {
                out.failure = Some(Failure::Flight { flight: i, why });
                return;
            }
        }
    }
    out.stability = stability(eq, bx);
}

/// The multipliers over the box, and what they prove.
fn stability(eq: &Equations, bx: &[Interval]) -> Option<Stability> {
    let n = eq.n;
    let jets = eq.jets(bx).ok()?;
    let r = eq.enc.r;
    let one = Interval::point(1.0);
    let mut m = [[one, Interval::point(0.0)], [Interval::point(0.0), one]];
    for i in 0..n {
        let j = (i + 1) % n;
        let tau = eq.flight(bx, i);
        let vi = bx[n + i];
        let w = vi - jets[i][1];
        let u = vi - tau - jets[j][1];
        let (a, b) = crate::tangent::flight_partials(w, tau, u);
        let ji = crate::tangent::impact_jacobian(a, b, jets[j][2], r, one);
        m = [
            [
                ji[0][0] * m[0][0] + ji[0][1] * m[1][0],
                ji[0][0] * m[0][1] + ji[0][1] * m[1][1],
            ],
            [
                ji[1][0] * m[0][0] + ji[1][1] * m[1][0],
                ji[1][0] * m[0][1] + ji[1][1] * m[1][1],
            ],
        ];
    }
    let trace = m[0][0] + m[1][1];
    let det = r.powi(2 * n as u32);
    let mut st = Stability {
        trace,
        det,
        multipliers: multipliers(trace, det),
        verdict: StabilityVerdict::Stable,
    };
    let (pd, fold) = (st.pd_test(), st.fold_test());
    st.verdict = if pd.positive() && fold.positive() {
        StabilityVerdict::Stable
    } else if pd.negative() || fold.negative() {
        StabilityVerdict::Unstable
    } else if pd.contains(0.0) {
        StabilityVerdict::Undecided {
            near: Near::PeriodDoubling,
        }
    } else {
        StabilityVerdict::Undecided { near: Near::Fold }
    };
    Some(st)
}

/// The roots of λ² − tr λ + det over the enclosures.
fn multipliers(tr: Interval, det: Interval) -> Multipliers {
    let half = Interval::point(0.5);
    let disc = tr.sqr() - Interval::point(4.0) * det;
    if disc.positive() {
        let q = disc.sqrt();
        Multipliers::Real([(tr + q) * half, (tr - q) * half])
    } else if disc.negative() {
        Multipliers::Complex {
            re: tr * half,
            im: (-disc).sqrt() * half,
        }
    } else {
        Multipliers::Unresolved {
            re: tr * half,
            spread: disc.abs().sqrt().hi() * 0.5,
        }
    }
}

#[cfg(test)]
mod tests;
