//! Folds (a multiplier +1) proved as α-intervals.
//!
//! At a fold the cycle is not a function of α, but it is one of its first launch phase
//! φ₀ = s. So the cycle's equations are solved for z = (φ₁ … φₙ₋₁, v₀ … vₙ₋₁, α) at a
//! given s: the Krawczyk test with α among the unknowns and s a parameter (in centred
//! form, as α is for the other special points). The fold is where 1 − tr M + det M
//! (zero exactly when a multiplier is +1, det M = r²ⁿ < 1 keeping the other inside)
//! changes sign along s: proofs at two doubles s̲ < s̄ with opposite signs
//! ([`super::special`]'s bracket), and one proof over [s̲, s̄] in a box holding both
//! ends' boxes, so one cycle depends continuously on s there and has a multiplier +1
//! at some s inside, every landing of it a first contact. The α-interval reported is
//! the enclosure of α over that box; α(s) is flat at the fold, so it is narrow.

use super::special::{sign, Bracket, CertifiedSpecial, SpecialFailure, SpecialKind};
use super::table::Enclosed;
use super::{
    candidate_boxes, flight, inverse, krawczyk_step, mids, periods_of, refine, stability, thin,
    Enclosure, Equations, Failure, Stability,
};
use crate::orbits::periodic::CyclePoint;
use crate::real::Interval;
use crate::system::System;
use crate::table::Table;

/// The cycle's equations with α an unknown and φ₀ = s given.
struct FoldSystem {
    base: Enclosed,
    n: usize,
    periods: Vec<i64>,
}

impl FoldSystem {
    /// (φ₀ … φₙ₋₁, v₀ … vₙ₋₁) from s and z, and α.
    fn split(&self, s: Interval, z: &[Interval]) -> (Vec<Interval>, Interval) {
        let n = self.n;
        let mut x = Vec::with_capacity(2 * n);
        x.push(s);
        x.extend_from_slice(&z[..2 * n - 1]);
        (x, z[2 * n - 1])
    }

    fn with<T>(
        &self,
        s: Interval,
        z: &[Interval],
        f: impl FnOnce(&Equations, &[Interval]) -> T,
    ) -> T {
        let (x, alpha) = self.split(s, z);
        let enc = self.base.clone().with_alpha(alpha);
        let eq = Equations {
            enc: &enc,
            n: self.n,
            periods: self.periods.clone(),
            forced: &[],
        };
        f(&eq, &x)
    }

    fn residual(&self, s: Interval, z: &[Interval]) -> Result<Vec<Interval>, Failure> {
        self.with(s, z, |eq, x| eq.residual(x))
    }

    /// The Jacobian in z (columns φ₁ … φₙ₋₁, v₀ … vₙ₋₁, α) and the column of s.
    fn jacobian(
        &self,
        s: Interval,
        z: &[Interval],
    ) -> Result<(Vec<Vec<Interval>>, Vec<Interval>), Failure> {
        self.with(s, z, |eq, x| {
            let j = eq.jacobian(x)?;
            let a = eq.alpha_column(x)?;
            let jz = j
                .iter()
                .zip(&a)
                .map(|(row, ai)| {
                    let mut r: Vec<Interval> = row[1..].to_vec();
                    r.push(*ai);
                    r
                })
                .collect();
            let js = j.iter().map(|row| row[0]).collect();
            Ok((jz, js))
        })
    }

    /// Newton's z at s (thin), from z0.
    fn refine(&self, s: f64, z0: &[f64]) -> Vec<f64> {
        let mut z = z0.to_vec();
        let sp = Interval::point(s);
        refine(&mut z, |zb| {
            Some((self.residual(sp, zb).ok()?, self.jacobian(sp, zb).ok()?.0))
        });
        z
    }

    /// The cycle proved for every s in `s` (a box of z, its landings first contacts),
    /// with its stability over the box; the boxes tried are around the hint if given.
    fn prove(
        &self,
        s: Interval,
        z0: &[f64],
        hint: Option<&[Interval]>,
    ) -> Result<(Vec<Interval>, Stability), Failure> {
        let sm = Interval::point(s.mid());
        let z = self.refine(s.mid(), z0);
        let res = self.residual(sm, &thin(&z))?;
        let (j0, _) = self.jacobian(sm, &thin(&z))?;
        let c = inverse(&mids(&j0)).ok_or(Failure::NotContracting {
            width: f64::INFINITY,
        })?;
        let boxes = candidate_boxes(&z, hint);
        let mut widest = f64::INFINITY;
        for b in boxes {
            let (jz, js) = self.jacobian(s, &b)?;
            let param = (s.width() > 0.0).then(|| (js, s - sm));
            let k = krawczyk_step(&z, &res, &c, &jz, param.as_ref(), &b);
            if !k.iter().zip(&b).all(|(ki, bi)| ki.inside(bi)) {
                widest = k.iter().map(Interval::width).fold(0.0, f64::max);
                continue;
            }
            let bx: Vec<Interval> = k
                .iter()
                .zip(&b)
                .map(|(ki, bi)| ki.intersect(bi).expect("inside"))
                .collect();
            return self.with(s, &bx, |eq, x| {
                let n = self.n;
                for i in 0..n {
                    let tau = eq.flight(x, i);
                    flight::first_landing(eq.enc, x[i], x[n + i], tau)
                        .map_err(|why| Failure::Flight { flight: i, why })?;
                }
                let st = stability(eq, x).ok_or(Failure::NotContracting { width: widest })?;
                Ok((bx.clone(), st))
            });
        }
        Err(Failure::NotContracting { width: widest })
    }
}

/// Prove the fold near the cycle `pt` (at `pt.alpha`, a multiplier near +1) of `table`
/// at restitution `r`: α over a stretch of the branch around the fold.
pub fn certify_fold(table: &Table, r: f64, pt: &CyclePoint) -> CertifiedSpecial {
    let mut out = CertifiedSpecial::start(SpecialKind::Fold, pt.n, pt.k);
    let Ok(sys) = System::new(table.clone(), pt.alpha, r) else {
        out.failure = Some(SpecialFailure::NoBracket);
        return out;
    };
    let n = pt.n;
    let fs = FoldSystem {
        // α is an unknown: its enclosure here is replaced at every evaluation.
        base: Enclosed::of(&sys),
        n,
        periods: periods_of(pt),
    };
    let mut z0: Vec<f64> = pt.phases[1..].to_vec();
    z0.extend_from_slice(&pt.velocities);
    z0.push(pt.alpha);
    let s0 = pt.phases[0];
    let at = |s: f64| fs.prove(Interval::point(s), &z0, None).ok();
    let condition_at = |s: f64| at(s).map(|(_, st)| st.fold_test());
    let bracket = Bracket {
        condition_at: &condition_at,
        center: s0,
        scale: 1.0,
    };
    let Some((a, b)) = bracket.find() else {
        out.failure = Some(SpecialFailure::NoBracket);
        return out;
    };
    let (Some((ba, sa)), Some((bb, sb))) = (at(a), at(b)) else {
        out.failure = Some(SpecialFailure::EndsUndecided);
        return out;
    };
    let (ca, cb) = (sa.fold_test(), sb.fold_test());
    if sign(&ca) == 0 || sign(&ca) != -sign(&cb) {
        out.failure = Some(SpecialFailure::EndsUndecided);
        return out;
    }
    let hint: Vec<Interval> = ba.iter().zip(&bb).map(|(x, y)| x.hull(y)).collect();
    let s = Interval::new(a, b).expect("a < b");
    match fs.prove(s, &z0, Some(&hint)) {
        Ok((bx, _)) => {
            let alpha = bx[2 * n - 1];
            out.alpha = Some(alpha);
            out.ends = Some([ca, cb]);
            let (x, _) = fs.split(s, &bx);
            let width = x.iter().map(Interval::width).fold(0.0, f64::max);
            out.enclosure = Some(Enclosure {
                phases: x[..n].to_vec(),
                velocities: x[n..].to_vec(),
                periods: fs.periods[..n].to_vec(),
                inflation: 0.0,
                width,
            });
        }
        Err(f) => out.failure = Some(SpecialFailure::Cycle(f)),
    }
    out
}
