//! The uncertainty exponent below the grid's resolution, as McDonald, Grebogi, Ott and
//! Yorke measure it (Physica D 17, 125, 1985): starts spread over the box
//! ([`box_start`]), each run with two copies displaced by ±ε along t̂0 for every ε of
//! [`SCALES`] (10^−1.5 down to 10^−6 of a period); a start is ε-uncertain when a copy
//! ends on another attractor than the start. The fraction of uncertain starts against ε
//! is fitted as the grid's is ([`fit`]). Where basins are mixed at every scale a grid
//! resolves (the cubic table at α = 0.47), this measures the boundary where the grid
//! cannot.
//!
//! The runs are a [`Job`] on the executor, one item per start (its copies with it);
//! the attractors are told apart by one [`Registry`] on the consumer's side, in the
//! starts' order.

use super::basins::BasinSpec;
use super::known::{settle_known, Known};
use super::statistics::{fit, NoExponent, Uncertainty};
use super::{box_start, settle, Found, Registry};
use crate::jobs::{Context, Control, Executor, Job, Pass};
use crate::run::start::launch;
use std::sync::Arc;

/// The displacements ε along t̂0, in table periods: half decades from 10^−1.5 to 10^−6.
pub const SCALES: [f64; 10] = [
    3.162_277_660_168_38e-2,
    1e-2,
    3.162_277_660_168_38e-3,
    1e-3,
    3.162_277_660_168_38e-4,
    1e-4,
    3.162_277_660_168_38e-5,
    1e-5,
    3.162_277_660_168_38e-6,
    1e-6,
];

/// One start's runs: the start's attractor, then for each scale those of its copies at
/// −ε and +ε (None where a start cannot be launched).
pub type Sample = (usize, Vec<Option<Found>>);

/// The job: `starts` starts of the box of `spec`, each with its copies.
pub struct SampledJob {
    spec: BasinSpec,
    starts: usize,
    known: Option<Arc<Known>>,
}

impl SampledJob {
    /// `starts` starts over the box of `spec`; a run that reaches a cycle of `known`
    /// stops there.
    pub fn new(spec: BasinSpec, starts: usize, known: Option<Arc<Known>>) -> SampledJob {
        SampledJob {
            spec,
            starts,
            known,
        }
    }

    fn run(&self, t0: f64, w0: f64, tick: &mut dyn FnMut(u64) -> bool) -> Option<Option<Found>> {
        let t0 = t0.rem_euclid(1.0);
        let Some(start) = launch(&self.spec.sys, t0, w0) else {
            return Some(None);
        };
        let found = match &self.known {
            Some(k) => settle_known(&self.spec.sys, start, &self.spec.settle, k, tick)?.0,
            None => settle(&self.spec.sys, start, &self.spec.settle, 1, tick)?.0,
        };
        Some(Some(found))
    }
}

impl Job for SampledJob {
    type State = ();
    type Output = Sample;

    fn passes(&self) -> Vec<Pass> {
        vec![Pass::natural(self.starts)]
    }

    fn units(&self) -> usize {
        self.starts
    }

    fn work(&self, _: usize, item: usize, _: &mut Option<()>, cx: &Context<'_, Sample>) {
        let (t0, w0) = box_start(item, self.spec.w_max);
        let mut tick = |events: u64| cx.tick(events);
        let mut out = Vec::with_capacity(1 + 2 * SCALES.len());
        let Some(x) = self.run(t0, w0, &mut tick) else {
            return;
        };
        out.push(x);
        for eps in SCALES {
            for t in [t0 - eps, t0 + eps] {
                let Some(y) = self.run(t, w0, &mut tick) else {
                    return;
                };
                out.push(y);
            }
        }
        cx.emit((item, out), true);
    }
}

/// The uncertainty exponent of `spec`'s basins from `starts` sampled starts (the
/// registry `seeded` already holding the attractors known there, whose numbering the
/// samples join), on `executor` under `control`. None if cancelled.
pub fn sampled_uncertainty(
    spec: &BasinSpec,
    starts: usize,
    known: Option<Arc<Known>>,
    seeded: Registry,
    executor: &Executor,
    control: &Control,
    on_sample: &mut dyn FnMut(usize),
) -> Option<Result<Uncertainty, NoExponent>> {
    let job = SampledJob::new(spec.clone(), starts, known);
    let mut samples: Vec<Sample> = Vec::with_capacity(starts);
    let summary = executor.run(job, control, |b| {
        samples.push(b.data);
        on_sample(samples.len());
    });
    if summary.cancelled || samples.len() != starts {
        return None;
    }
    samples.sort_by_key(|s| s.0);
    let mut registry = seeded;
    let mut uncertain = [0usize; SCALES.len()];
    let mut counted = 0usize;
    for (_, runs) in &samples {
        let ids: Vec<Option<usize>> = runs
            .iter()
            .map(|f| f.as_ref().map(|f| registry.seed(f)))
            .collect();
        let Some(own) = ids[0] else { continue };
        counted += 1;
        for (j, u) in uncertain.iter_mut().enumerate() {
            let (a, b) = (ids[1 + 2 * j], ids[2 + 2 * j]);
            if a != Some(own) || b != Some(own) {
                *u += 1;
            }
        }
    }
    if counted == 0 {
        return Some(Err(NoExponent::NoBoundary));
    }
    let fractions = SCALES
        .iter()
        .zip(uncertain)
        .map(|(&eps, u)| (eps, u as f64 / counted as f64))
        .collect();
    Some(fit(fractions, counted))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::System;
    use crate::table::Table;

    #[test]
    fn one_basin_has_no_uncertain_start_at_any_scale() {
        // The cubic table past the (1, 1) doubling, r = 0.8: every start of the box
        // ends on the (2, 2) cycle (as the grid finds), at every displacement too.
        let sys = System::new(Table::fd(1.0).unwrap(), 0.52, 0.8).unwrap();
        let spec = BasinSpec::new(sys);
        let got = sampled_uncertainty(
            &spec,
            40,
            None,
            Registry::new(),
            &Executor::new(2).unwrap(),
            &Control::new(),
            &mut |_| {},
        );
        assert_eq!(got, Some(Err(NoExponent::NoBoundary)));
    }

    #[test]
    fn the_cubic_tables_basins_are_mixed_down_to_a_millionth() {
        // α = 0.47: the (1, 1) solution and a sticking cycle. A fifth or more of the
        // starts have a copy 10⁻⁶ of a period away that ends elsewhere, and f(ε) grows
        // only slowly with ε: an exponent well below 1 (the grid cannot measure it).
        let sys = System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap();
        let spec = BasinSpec::new(sys);
        let u = sampled_uncertainty(
            &spec,
            400,
            None,
            Registry::new(),
            &Executor::new(2).unwrap(),
            &Control::new(),
            &mut |_| {},
        )
        .unwrap()
        .unwrap();
        assert_eq!(u.fractions[0].0, 1e-6);
        assert!(u.fractions.iter().all(|f| f.1 > 0.15), "{u:?}");
        assert!(
            u.exponent > 0.0 && u.exponent < 0.3 && u.error < 0.05,
            "{u:?}"
        );
    }
}
