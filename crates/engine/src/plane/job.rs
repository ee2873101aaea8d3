//! The plane as a [`PictureJob`]: what one pixel computes ([`PlaneCells`]), and
//! [`Plane`], the picture as it fills in.

use super::{Pixel, PlaneSpec, CHUNK, KEEP, LYAPUNOV_SAMPLE};
use crate::attractors::{self, Settle};
use crate::error::EngineError;
use crate::jobs::grid::Shard;
use crate::jobs::picture::{Cells, Chunk, Filled, Picture, PictureJob};
use crate::jobs::{Control, Executor};
use crate::map::ImpactMap;
use crate::precise::{decide_in_job, CycleSummary, PreciseSetup};
use crate::run::{Advance, OrbitRun};

/// One work item's results: (pixel index, result); a pixel whose system or start is
/// refused is left out.
pub type PlaneChunk = Chunk<Pixel>;

/// The plane as a job: a [`PictureJob`] over its pixels.
pub type PlaneJob = PictureJob<PlaneCells>;

/// What a plane computes per pixel: its spec, validated.
pub struct PlaneCells {
    spec: PlaneSpec,
}

impl PlaneJob {
    /// Validate `spec` and lay out its passes.
    pub fn new(spec: PlaneSpec) -> Result<PlaneJob, EngineError> {
        spec.validate()?;
        Ok(PictureJob::over(PlaneCells { spec }))
    }

    /// The specification.
    pub fn spec(&self) -> &PlaneSpec {
        &self.cells().spec
    }
}

impl Cells for PlaneCells {
    type Cell = Pixel;

    fn size(&self) -> (usize, usize) {
        (self.spec.x.n, self.spec.y.n)
    }

    fn chunk(&self) -> usize {
        CHUNK
    }

    fn shard(&self) -> Shard {
        self.spec.shard
    }

    fn spread(&self) -> bool {
        true
    }

    /// One pixel from its start to the end of the transient.
    fn compute(&self, index: usize, tick: &mut dyn FnMut(u64) -> bool) -> Option<Option<Pixel>> {
        let spec = &self.spec;
        let (x, y) = spec.values(index);
        let Ok(sys) = spec.system_at(x, y) else {
            return Some(None);
        };
        let Ok(start) = spec.initial_state(&sys) else {
            return Some(None);
        };
        let map = ImpactMap::new(sys.clone(), spec.solver, start);
        let mut run = OrbitRun::new(map, KEEP, spec.periodicity);
        let end = spec.transient as i64;
        let (outcome, points) = match run.advance(end, end, tick) {
            Advance::Done(o, p) => (o, p),
            Advance::Checkpoint | Advance::Cancelled => return None,
        };
        let found = if spec.lyapunov {
            let settle = Settle {
                transient: spec.transient,
                periodicity: spec.periodicity,
                sample: LYAPUNOV_SAMPLE,
                solver: spec.solver,
            };
            Some(attractors::identify(
                &sys,
                &settle,
                &outcome,
                run.state(),
                tick,
            )?)
        } else {
            None
        };
        let lyapunov = found.as_ref().and_then(|f| f.lyapunov());
        let sticking = run.sticking(&outcome, &points) || lyapunov == Some(f64::NEG_INFINITY);
        let precision = match &found {
            Some(f) if f.precision.is_some() => f.precision,
            _ => run.precision(&outcome, sticking),
        };
        let cycle = match (spec.digits, precision.is_some_and(|p| !p.resolved)) {
            (Some(ask), true) => self.decide(index, &sys, &start, ask, tick)?,
            _ => None,
        };
        Some(Some(Pixel {
            sticking,
            outcome,
            lyapunov,
            precision,
            cycle,
        }))
    }
}

impl PlaneCells {
    /// The sticking cycle of pixel `index`'s start, decided at any precision with both
    /// axes' values the decimal grid points of their windows: Some(None) where the
    /// start is not one the map at any precision takes, None when the job was stopped.
    fn decide(
        &self,
        index: usize,
        sys: &crate::system::System,
        start: &crate::map::State,
        ask: crate::precise::DigitsAsk,
        tick: &mut dyn FnMut(u64) -> bool,
    ) -> Option<Option<CycleSummary>> {
        let spec = &self.spec;
        let Some(setup) = PreciseSetup::of_state(sys, start, ask.binary) else {
            return Some(None);
        };
        let (i, j) = (index % spec.x.n.max(1), index / spec.x.n.max(1));
        let (x, y) = spec.values(index);
        let setup = setup
            .as_written(&spec.written)
            .on_grid(spec.x.param.slot(), (spec.x.lo, spec.x.hi, spec.x.n), i, x)
            .on_grid(spec.y.param.slot(), (spec.y.lo, spec.y.hi, spec.y.n), j, y);
        let verdict = decide_in_job(&setup, ask, spec.transient, tick)?;
        Some(Some(verdict.summary()))
    }
}

/// The plane as it fills in: every pixel computed so far.
pub type Plane = Picture<Pixel>;

impl Plane {
    /// An empty picture of `spec`'s shard.
    pub fn new(spec: &PlaneSpec) -> Plane {
        Picture::blank(spec.x.n, spec.y.n, spec.shard_len())
    }

    /// Every pixel, index j·W + i.
    pub fn pixels(&self) -> &[Option<Pixel>] {
        self.cells()
    }
}

impl Filled for Plane {
    type Spec = PlaneSpec;
    type Cells = PlaneCells;

    fn job(spec: &PlaneSpec) -> Result<PlaneJob, EngineError> {
        PlaneJob::new(spec.clone())
    }

    fn empty(spec: &PlaneSpec) -> Plane {
        Plane::new(spec)
    }

    fn absorb(&mut self, chunk: PlaneChunk) {
        Picture::absorb(self, chunk);
    }

    fn size(&self) -> (usize, usize) {
        Picture::size(self)
    }

    fn covered(&self) -> usize {
        Picture::covered(self)
    }

    fn complete(&self) -> bool {
        Picture::complete(self)
    }
}

/// Run a plane to the end on `executor` (under a fresh control).
pub fn collect(spec: &PlaneSpec, executor: &Executor) -> Result<Plane, EngineError> {
    let job = PlaneJob::new(spec.clone())?;
    let mut plane = Plane::new(spec);
    executor.run(job, &Control::new(), |b| plane.absorb(b.data));
    Ok(plane)
}
