//! The sweep as a [`Job`]: its items, its passes, and the work on one item.
//!
//! Without continuation an item is one value: pass 0 (the preview, if any) runs it from
//! its cold start to the preview transient and keeps the run, pass 1 continues that
//! run to the end. With continuation an item of the last pass is a chain of values, each
//! started from its neighbour's final state; the preview then runs every value cold
//! (provisional results only, nothing is kept).

use super::{chain_len, SweepSpec, Warm, LYAPUNOV_SAMPLE};
use crate::attractors::{self, box_start, default_w_max, Kind, Registry, Settle};
use crate::error::EngineError;
use crate::jobs::{Context, Job, Pass};
use crate::map::{ImpactMap, State};
use crate::precise::{decide_in_job, CycleVerdict, PreciseSetup};
use crate::run::precision::Precision;
use crate::run::start::launch;
use crate::run::{has_sticking, Advance, OrbitRun, Outcome, Point};

/// The result for one value.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueResult {
    /// Index of the value in the window, 0 ..< steps.
    pub index: usize,
    /// The swept parameter's value.
    pub value: f64,
    /// True when this is the value's final result (no later batch will replace it).
    pub complete: bool,
    /// Recorded events, oldest first.
    pub points: Vec<Point>,
    /// Periodic, unsettled, resting or no landing (of the first start).
    pub outcome: Outcome,
    /// Whether the (first start's) orbit sticks to the table in what it settled on: a
    /// cycle that includes a stick or a release, a ball at rest, a stick among the kept
    /// points or in the sample its exponent was measured on (exponent −∞). See
    /// [`OrbitRun::sticking`].
    pub sticking: bool,
    /// For a periodic outcome (final results): whether double precision decides the
    /// cycle ([`Precision`]: a sticking cycle's length may be beyond it).
    pub precision: Option<Precision>,
    /// Events computed for this value.
    pub events: u64,
    /// With [`SweepSpec::lyapunov`], the largest Lyapunov exponent per impact of the
    /// (first start's) orbit: from the eigenvalues of its cycle, −∞ when it sticks or
    /// rests, by QR over [`LYAPUNOV_SAMPLE`] impacts when unsettled; None when not
    /// asked, for provisional results, and where there is none (no landing, grazing).
    pub lyapunov: Option<f64>,
    /// With [`SweepSpec::starts`] > 1, the attractors the starts ended on, largest basin
    /// first. Each attractor's points (of the first start that found it) are
    /// `points[a.points.clone()]`; `points` is then their concatenation. Empty with one
    /// start.
    pub attractors: Vec<ValueAttractor>,
    /// With [`SweepSpec::digits`], for a sticking cycle whose length double precision
    /// cannot decide ([`Precision::resolved`] false): the cycle decided at any precision
    /// from the value's cold start ([`crate::decide_sticking_cycle`]).
    pub cycle: Option<CycleVerdict>,
}

/// One attractor found at a value of a sweep with several starts.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueAttractor {
    /// What the attractor is.
    pub kind: Kind,
    /// Events and table periods per cycle, for cycles.
    pub events: Option<usize>,
    /// Table periods per cycle, for cycles.
    pub periods: Option<i64>,
    /// The largest exponent per impact (−∞ sticking or resting; None where none).
    pub lyapunov: Option<f64>,
    /// Share of the starts that ended on it.
    pub fraction: f64,
    /// The outcome of the first start that found it.
    pub outcome: Outcome,
    /// For a cycle: whether double precision decides it.
    pub precision: Option<Precision>,
    /// With [`SweepSpec::digits`], where double precision cannot decide it: the cycle
    /// decided at any precision from the first start that found it.
    pub cycle: Option<CycleVerdict>,
    /// Its recorded points in [`ValueResult::points`].
    pub points: std::ops::Range<usize>,
}

/// A run carried from the preview pass to the final one.
pub struct Carried {
    index: usize,
    value: f64,
    run: OrbitRun,
}

/// A sweep, ready to run on an executor. Its items are the shard's chains (single
/// values without continuation), computed from their position, not stored.
pub struct SweepJob {
    spec: SweepSpec,
    /// Values and chains in the shard.
    values: usize,
    chains: usize,
    /// Hand values out in index order (for writers that stream in order) instead of
    /// spread over the window.
    in_order: bool,
    /// Transient of the provisional pass 0, in periods; 0 for none.
    preview: u64,
}

impl SweepJob {
    /// Validate the spec and lay out the items.
    pub fn new(spec: SweepSpec) -> Result<SweepJob, EngineError> {
        spec.validate()?;
        let len = chain_len(spec.warm);
        let all_chains = spec.steps.div_ceil(len);
        let shard = spec.shard;
        let chains = all_chains / shard.count + usize::from(shard.index < all_chains % shard.count);
        let values = spec.shard_values();
        Ok(SweepJob {
            spec,
            values,
            chains,
            in_order: false,
            preview: 0,
        })
    }

    /// Run a provisional pass first: every value to `periods` (if shorter than the
    /// transient), spread over the window, so a complete rough picture arrives early.
    pub fn preview(mut self, periods: u64) -> SweepJob {
        self.preview = periods;
        self
    }

    /// Hand items out in index order (for a consumer that writes results in order
    /// with a window, see [`crate::jobs::Executor::start_windowed`]).
    pub fn in_order(mut self) -> SweepJob {
        self.in_order = true;
        self
    }

    /// The specification.
    pub fn spec(&self) -> &SweepSpec {
        &self.spec
    }

    fn pass(&self, n: usize) -> Pass {
        if self.in_order {
            Pass::natural(n)
        } else {
            Pass::spread(n)
        }
    }

    /// The value indices of the shard's chain `c`, in the order they are run.
    pub fn chain(&self, c: usize) -> Vec<usize> {
        let len = chain_len(self.spec.warm);
        let g = self.spec.shard.index + c * self.spec.shard.count;
        let range = g * len..((g + 1) * len).min(self.spec.steps);
        if self.spec.warm == Warm::Backward {
            range.rev().collect()
        } else {
            range.collect()
        }
    }

    /// The shard's value at position `p` (ascending).
    pub fn value_index(&self, p: usize) -> usize {
        let len = chain_len(self.spec.warm);
        let g = self.spec.shard.index + (p / len) * self.spec.shard.count;
        g * len + p % len
    }

    /// Values in the shard.
    pub fn values(&self) -> usize {
        self.values
    }

    fn preview_end(&self) -> Option<i64> {
        let (p, end) = (self.preview as i64, self.spec.transient as i64);
        (p > 0 && p < end && self.spec.starts == 1).then_some(p)
    }

    /// How a start is settled and identified, sampling `sample` events if unsettled.
    fn settle(&self, sample: u64) -> Settle {
        Settle {
            transient: self.spec.transient,
            periodicity: self.spec.periodicity,
            sample,
            solver: self.spec.solver,
        }
    }

    /// A value with several starts: run each to its attractor and emit them all.
    fn several_starts(&self, index: usize, cx: &Context<'_, ValueResult>) -> Option<()> {
        let value = self.spec.value(index);
        let Ok(sys) = self.spec.system_at(value) else {
            return Some(());
        };
        let w_max = self.spec.w_max.unwrap_or_else(|| default_w_max(&sys));
        let sample = if self.spec.lyapunov {
            LYAPUNOV_SAMPLE
        } else {
            Settle::BASINS.sample
        };
        let settle = self.settle(sample);
        let mut registry = Registry::new();
        // Per attractor id: the points, outcome and start of the first start that found
        // it.
        let mut first: Vec<(Vec<Point>, Outcome, State)> = Vec::new();
        let mut lead: Option<(Outcome, Option<f64>, bool, Option<Precision>)> = None;
        let mut events = 0;
        for s in 0..self.spec.starts {
            let start = if s == 0 {
                self.spec.initial_state(&sys).ok()
            } else {
                let (t0, w0) = box_start(s - 1, w_max);
                launch(&sys, t0, w0)
            };
            let Some(start) = start else { continue };
            let (found, outcome, points, n) =
                attractors::settle(&sys, start, &settle, self.spec.keep, &mut |n| cx.tick(n))?;
            events += n;
            let id = registry.assign(&found);
            if id == first.len() {
                first.push((points, outcome, start));
            }
            let sticks = matches!(found.kind, Kind::Sticking | Kind::Resting);
            lead.get_or_insert((
                outcome,
                found.lyapunov(),
                sticks || has_sticking(&first[id].0),
                found.precision,
            ));
        }
        let Some((outcome, lyapunov, sticking, precision)) = lead else {
            return Some(());
        };
        // Allocated once at its size (grown by doubling, it could take twice that).
        let mut points = Vec::with_capacity(first.iter().map(|(p, _, _)| p.len()).sum());
        let mut list = Vec::new();
        let mut lead_cycle = None;
        for id in registry.ranked() {
            let a = &registry.attractors()[id];
            let (p, o, start) = &first[id];
            let cycle = match a.unresolved() {
                true => self.decide(&sys, start, index, cx)?,
                false => None,
            };
            if id == 0 {
                lead_cycle = cycle.clone();
            }
            let from = points.len();
            points.extend_from_slice(p);
            list.push(ValueAttractor {
                kind: a.kind,
                events: a.events,
                periods: a.periods,
                lyapunov: a.lyapunov,
                fraction: registry.fraction(id),
                outcome: *o,
                precision: a.precision,
                cycle,
                points: from..points.len(),
            });
        }
        cx.emit(
            ValueResult {
                index,
                value,
                complete: true,
                sticking,
                precision,
                points,
                outcome,
                events,
                lyapunov: lyapunov.filter(|_| self.spec.lyapunov),
                attractors: list,
                cycle: lead_cycle,
            },
            true,
        );
        Some(())
    }

    /// With [`SweepSpec::digits`], the sticking cycle the ball of `start` reaches in
    /// `sys` (value `index`), decided at any precision with the swept parameter the
    /// window's decimal grid point: Some(None) when not asked (or the start is not one
    /// the map at any precision takes), None when the job was stopped.
    fn decide(
        &self,
        sys: &crate::system::System,
        start: &State,
        index: usize,
        cx: &Context<'_, ValueResult>,
    ) -> Option<Option<CycleVerdict>> {
        let Some(ask) = self.spec.digits else {
            return Some(None);
        };
        let Some(setup) = PreciseSetup::of_state(sys, start, ask.binary) else {
            return Some(None);
        };
        let spec = &self.spec;
        let setup = setup.as_written(&spec.written);
        let window = (spec.lo, spec.hi, spec.steps);
        let setup = setup.on_grid(spec.param.slot(), window, index, spec.value(index));
        // (None only where the job was stopped.)
        decide_in_job(&setup, ask, spec.transient, &mut |n| cx.tick(n)).map(Some)
    }

    fn new_run(&self, index: usize, warm_from: Option<&State>) -> Option<(f64, OrbitRun)> {
        let value = self.spec.value(index);
        let sys = self.spec.system_at(value).ok()?;
        let state = warm_from
            .and_then(|s| {
                let v = s.v.max(sys.df(s.phase));
                State::launch(&sys, 0, s.phase, v, 0.0).ok()
            })
            .or_else(|| self.spec.initial_state(&sys).ok())?;
        let map = ImpactMap::new(sys, self.spec.solver, state);
        Some((
            value,
            OrbitRun::new(map, self.spec.keep, self.spec.periodicity),
        ))
    }

    /// Advance `run` to `checkpoint` and emit what it reached: whether it can be resumed
    /// and its outcome, or None if the job was cancelled.
    fn advance(
        &self,
        index: usize,
        value: f64,
        run: &mut OrbitRun,
        checkpoint: i64,
        provisional: bool,
        cx: &Context<'_, ValueResult>,
    ) -> Option<(bool, Outcome)> {
        let end = self.spec.transient as i64;
        let adv = run.advance(checkpoint, end, &mut |n| cx.tick(n));
        let (complete, outcome, points, resumable) = match adv {
            Advance::Done(o, p) => (true, o, p, false),
            Advance::Checkpoint => (
                false,
                Outcome::Running {
                    reached: run.reached(),
                },
                run.points(),
                true,
            ),
            Advance::Cancelled => return None,
        };
        let complete = complete && !provisional;
        let found = match complete && self.spec.lyapunov {
            true => {
                let sys = run.system().clone();
                let settle = self.settle(LYAPUNOV_SAMPLE);
                Some(attractors::identify(
                    &sys,
                    &settle,
                    &outcome,
                    run.state(),
                    &mut |n| cx.tick(n),
                )?)
            }
            false => None,
        };
        let lyapunov = found.as_ref().and_then(|f| f.lyapunov());
        let sticking = run.sticking(&outcome, &points) || lyapunov == Some(f64::NEG_INFINITY);
        let precision = match (complete, &found) {
            (true, Some(f)) if f.precision.is_some() => f.precision,
            (true, _) => run.precision(&outcome, sticking),
            _ => None,
        };
        // At any precision from the value's cold start (where the orbit was warm
        // started too: a start on the table the spec states, not a state rounded on
        // the way).
        let unresolved = precision.is_some_and(|p| !p.resolved);
        let start = unresolved.then(|| self.spec.initial_state(run.system()).ok());
        let cycle = match start.flatten() {
            Some(start) => self.decide(run.system(), &start, index, cx)?,
            None => None,
        };
        cx.emit(
            ValueResult {
                index,
                value,
                complete,
                sticking,
                precision,
                points,
                outcome,
                events: run.events(),
                lyapunov,
                attractors: Vec::new(),
                cycle,
            },
            complete,
        );
        Some((resumable, outcome))
    }
}

impl Job for SweepJob {
    type State = Carried;
    type Output = ValueResult;

    fn units(&self) -> usize {
        self.values
    }

    fn passes(&self) -> Vec<Pass> {
        // Without continuation chains are single values, so both passes are over values.
        let last = self.pass(self.chains);
        match self.preview_end() {
            Some(_) => vec![self.pass(self.values), last],
            None => vec![last],
        }
    }

    fn work(
        &self,
        pass: usize,
        item: usize,
        state: &mut Option<Carried>,
        cx: &Context<'_, ValueResult>,
    ) {
        let end = self.spec.transient as i64;
        let warm = self.spec.warm != Warm::Off;
        if self.spec.starts > 1 {
            self.several_starts(self.value_index(item), cx);
            return;
        }
        if let (Some(preview), 0) = (self.preview_end(), pass) {
            // Pass 0: one value from its cold start to the preview transient.
            let index = self.value_index(item);
            let Some((value, mut run)) = self.new_run(index, None) else {
                return;
            };
            let reached = self.advance(index, value, &mut run, preview, warm, cx);
            if matches!(reached, Some((true, _))) && !warm {
                *state = Some(Carried { index, value, run });
            }
            return;
        }
        if warm {
            let mut prev: Option<State> = None;
            for index in self.chain(item) {
                let Some((value, mut run)) = self.new_run(index, prev.as_ref()) else {
                    return;
                };
                prev = match self.advance(index, value, &mut run, end, false, cx) {
                    None => return,
                    Some((_, Outcome::NoLanding { .. })) => None,
                    Some(_) => Some(run.state()),
                };
            }
            return;
        }
        // Cold, final pass: continue the preview's run, or start one.
        let carried = match state.take() {
            Some(c) => Some(c),
            None if self.preview_end().is_none() => {
                let index = self.value_index(item);
                self.new_run(index, None)
                    .map(|(value, run)| Carried { index, value, run })
            }
            // The preview finished this value (or could not start it).
            None => None,
        };
        if let Some(mut c) = carried {
            self.advance(c.index, c.value, &mut c.run, end, false, cx);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{Shard, SweepParam};
    use crate::table::Table;

    #[test]
    fn chains_and_positions_are_the_specs_chains() {
        for steps in [1, 5, 31, 32, 33, 100, 257] {
            for warm in Warm::ALL {
                for count in 1..=5 {
                    for index in 0..count {
                        let mut spec = SweepSpec::new(
                            Table::fd(0.1).unwrap(),
                            0.45,
                            0.8,
                            SweepParam::Alpha,
                            0.4,
                            0.5,
                            steps,
                        );
                        spec.warm = warm;
                        spec.shard = Shard { index, count };
                        let job = SweepJob::new(spec.clone()).unwrap();
                        let want = spec.chains();
                        assert_eq!(job.chains, want.len(), "{steps} {warm:?} {index}/{count}");
                        for (c, chain) in want.iter().enumerate() {
                            assert_eq!(job.chain(c), *chain);
                        }
                        let mut ascending: Vec<usize> = want.into_iter().flatten().collect();
                        ascending.sort();
                        assert_eq!(job.values(), ascending.len());
                        for (p, i) in ascending.iter().enumerate() {
                            assert_eq!(job.value_index(p), *i);
                        }
                    }
                }
            }
        }
    }
}
