//! Basins of attraction: a grid of starts over the box t̂0 ∈ [0, 1) × w0 ∈ [0, W], each
//! run to its attractor, as a [`Job`](crate::jobs::Job).
//!
//! Grid point (i, j) starts at t̂0 = (i + ½)/nx, w0 = W (j + ½)/ny (cell centres), with
//! v0 = f'(t̂0) + w0, on the table. The job is a [picture](crate::jobs::picture), coarse to
//! fine: pass 0 the points with i and j multiples of 8, then 4, 2 and 1, in chunks of
//! [`CHUNK`] points, so a viewer can draw a complete rough picture early and refine it.
//! [`Basins`] assigns attractors on the consumer's side, chunk by chunk in the job's own
//! order (not the order chunks happen to finish), so the numbering does not depend on
//! timing.

use super::known::{settle_known, Known};
use super::{settle, Found, Registry, Settle};
use crate::error::EngineError;
use crate::jobs::picture::{
    Cells, Chunk, Filled, Picture, PictureJob, Sequencer, MAX_CELLS, MAX_SIDE,
};
use crate::limits;
use crate::precise::{
    decide_sticking_cycle, CycleVerdict, DigitsAsk, DigitsProgress, PreciseSetup,
};
use crate::run::start::launch;
use crate::system::System;
use std::ops::ControlFlow;

/// Points per work item.
pub const CHUNK: usize = 32;
/// The default grid.
pub const DEFAULT_GRID: (usize, usize) = (200, 100);

/// Everything that defines a basin picture.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinSpec {
    /// The system whose basins are drawn.
    pub sys: System,
    /// Grid points along t̂0 and along w0.
    pub nx: usize,
    /// Grid points along w0.
    pub ny: usize,
    /// Top of the w0 range.
    pub w_max: f64,
    /// How each start is run to its attractor.
    pub settle: Settle,
}

impl BasinSpec {
    /// The default picture of `sys`: [`DEFAULT_GRID`], W from
    /// [`default_w_max`](super::default_w_max), [`Settle::BASINS`].
    pub fn new(sys: System) -> BasinSpec {
        let w_max = super::default_w_max(&sys);
        BasinSpec {
            sys,
            nx: DEFAULT_GRID.0,
            ny: DEFAULT_GRID.1,
            w_max,
            settle: Settle::BASINS,
        }
    }

    /// Check the grid, W and the transient.
    pub fn validate(&self) -> Result<(), EngineError> {
        for (name, n) in [("grid width", self.nx), ("grid height", self.ny)] {
            if n == 0 || n > MAX_SIDE {
                return Err(EngineError::InvalidParameter {
                    name: name.into(),
                    value: n.to_string(),
                    range: "1 ..= 4000 points".into(),
                });
            }
        }
        if self.nx * self.ny > MAX_CELLS {
            return Err(EngineError::InvalidParameter {
                name: "grid".into(),
                value: format!("{}x{}", self.nx, self.ny),
                range: "at most 1000000 points".into(),
            });
        }
        limits::W_MAX.check(self.w_max)?;
        limits::TRANSIENT.check(self.settle.transient as f64)?;
        Ok(())
    }

    /// Grid points.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Whether the grid is empty (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The start (t̂0, w0) of grid point `index` = j·nx + i.
    pub fn start(&self, index: usize) -> (f64, f64) {
        let (i, j) = (index % self.nx, index / self.nx);
        (
            (i as f64 + 0.5) / self.nx as f64,
            self.w_max * (j as f64 + 0.5) / self.ny as f64,
        )
    }
}

/// One work item's results, numbered in the job's order: (grid index, attractor) of
/// complete starts; a start that cannot be launched is left out.
pub type BasinChunk = Chunk<Found>;

/// The basin picture as a job: a [`PictureJob`] over its starts.
pub type BasinsJob = PictureJob<BasinCells>;

/// What the basin picture computes per grid point: its spec, validated, and the cycles
/// known before it runs (a start that reaches one stops there).
pub struct BasinCells {
    spec: BasinSpec,
    known: Option<std::sync::Arc<Known>>,
}

impl BasinsJob {
    /// Validate `spec` and lay out its passes.
    pub fn new(spec: BasinSpec) -> Result<BasinsJob, EngineError> {
        spec.validate()?;
        Ok(PictureJob::over(BasinCells { spec, known: None }))
    }

    /// [`Self::new`] with the cycles `known` at this system: a start that reaches one
    /// stops there ([`settle_known`]).
    pub fn with_known(
        spec: BasinSpec,
        known: std::sync::Arc<Known>,
    ) -> Result<BasinsJob, EngineError> {
        spec.validate()?;
        let known = (!known.is_empty()).then_some(known);
        Ok(PictureJob::over(BasinCells { spec, known }))
    }

    /// The specification.
    pub fn spec(&self) -> &BasinSpec {
        &self.cells().spec
    }
}

impl Cells for BasinCells {
    type Cell = Found;

    fn size(&self) -> (usize, usize) {
        (self.spec.nx, self.spec.ny)
    }

    fn chunk(&self) -> usize {
        CHUNK
    }

    fn spread(&self) -> bool {
        false
    }

    /// One start run to its attractor.
    fn compute(&self, index: usize, tick: &mut dyn FnMut(u64) -> bool) -> Option<Option<Found>> {
        let (t0, w0) = self.spec.start(index);
        let Some(start) = launch(&self.spec.sys, t0, w0) else {
            return Some(None);
        };
        let found = match &self.known {
            Some(known) => settle_known(&self.spec.sys, start, &self.spec.settle, known, tick)?.0,
            None => settle(&self.spec.sys, start, &self.spec.settle, 1, tick)?.0,
        };
        Some(Some(found))
    }
}

/// The basin picture as it fills in: the attractor of every grid point assigned so far.
#[derive(Clone, Debug)]
pub struct Basins {
    /// Attractor id per grid point.
    labels: Picture<u32>,
    registry: Registry,
    /// Chunks received ahead of their turn.
    order: Sequencer<Found>,
}

impl Basins {
    /// An empty picture of `spec`.
    pub fn new(spec: &BasinSpec) -> Basins {
        Basins {
            labels: Picture::blank(spec.nx, spec.ny, spec.len()),
            registry: Registry::new(),
            order: Sequencer::default(),
        }
    }

    /// An empty picture of `spec` whose attractors start as `registry`'s (found from
    /// seeds, with no start counted): starts that end on one of them take its id.
    pub fn seeded(spec: &BasinSpec, registry: Registry) -> Basins {
        Basins {
            registry,
            ..Basins::new(spec)
        }
    }

    /// Take a chunk; assign it and any waiting chunks whose turn it now is. Returns the
    /// grid indices newly labelled.
    pub fn absorb(&mut self, chunk: BasinChunk) -> Vec<usize> {
        let mut labelled = Vec::new();
        for c in self.order.push(chunk) {
            for (index, found) in &c.cells {
                let id = self.registry.assign(found);
                self.labels.set(*index, id as u32);
                labelled.push(*index);
            }
            self.labels.cover(c.covered);
        }
        labelled
    }

    /// The grid size (nx, ny).
    pub fn grid(&self) -> (usize, usize) {
        self.labels.size()
    }

    /// The attractor id of grid point (i, j), if assigned.
    pub fn label(&self, i: usize, j: usize) -> Option<u32> {
        self.labels.get(i, j).copied()
    }

    /// Labels of every grid point, index j·nx + i.
    pub fn labels(&self) -> &[Option<u32>] {
        self.labels.cells()
    }

    /// The attractors found so far.
    pub fn registry(&self) -> &Registry {
        &self.registry
    }

    /// Grid points done.
    pub fn covered(&self) -> usize {
        self.labels.covered()
    }

    /// Whether every grid point is done.
    pub fn complete(&self) -> bool {
        self.labels.complete()
    }

    /// With `ask`, each attractor's cycle decided at any precision where double
    /// precision does not resolve it (None elsewhere), by attractor id: the orbit of the
    /// first grid point (in index order) that ended on it (the parameters as `written`
    /// has them typed), run as
    /// [`crate::decide_sticking_cycle`] runs it, within the spec's transient.
    /// `progress` hears how far each run has got and may stop the work (then None).
    pub fn decide_cycles(
        &self,
        spec: &BasinSpec,
        ask: DigitsAsk,
        written: &crate::precise::Written,
        progress: &mut dyn FnMut(DigitsProgress) -> ControlFlow<()>,
    ) -> Option<Vec<Option<CycleVerdict>>> {
        let attractors = self.registry.attractors();
        let mut verdicts = vec![None; attractors.len()];
        let periods = i64::try_from(spec.settle.transient).unwrap_or(i64::MAX);
        for (id, a) in attractors.iter().enumerate() {
            if !a.unresolved() {
                continue;
            }
            let first = self.labels().iter().position(|l| *l == Some(id as u32));
            let Some(k) = first else { continue };
            let (t0, w0) = spec.start(k);
            let setup = launch(&spec.sys, t0, w0)
                .and_then(|st| PreciseSetup::of_state(&spec.sys, &st, ask.binary))
                .map(|s| s.as_written(written));
            let Some(setup) = setup else { continue };
            verdicts[id] = Some(decide_sticking_cycle(&setup, ask, periods, progress)?);
        }
        Some(verdicts)
    }

    /// The label shown for grid point (i, j) while the picture fills in: its own, or
    /// that of the nearest coarser grid point already assigned (the block it lies in).
    pub fn preview_label(&self, i: usize, j: usize) -> Option<u32> {
        self.labels.preview(i, j).copied()
    }
}

impl Filled for Basins {
    type Spec = BasinSpec;
    type Cells = BasinCells;

    fn job(spec: &BasinSpec) -> Result<BasinsJob, EngineError> {
        BasinsJob::new(spec.clone())
    }

    fn empty(spec: &BasinSpec) -> Basins {
        Basins::new(spec)
    }

    fn absorb(&mut self, chunk: BasinChunk) {
        Basins::absorb(self, chunk);
    }

    fn size(&self) -> (usize, usize) {
        self.grid()
    }

    fn covered(&self) -> usize {
        Basins::covered(self)
    }

    fn complete(&self) -> bool {
        Basins::complete(self)
    }
}

/// Run a basin picture to the end on `executor` (under a fresh control).
pub fn collect(spec: &BasinSpec, executor: &crate::jobs::Executor) -> Result<Basins, EngineError> {
    let job = BasinsJob::new(spec.clone())?;
    let mut basins = Basins::new(spec);
    let control = crate::jobs::Control::new();
    executor.run(job, &control, |b| {
        basins.absorb(b.data);
    });
    Ok(basins)
}
