//! Basins of attraction: a grid of starts over the box t̂0 ∈ [0, 1) × w0 ∈ [0, W], each
//! run to its attractor, as a [`Job`].
//!
//! Grid point (i, j) starts at t̂0 = (i + ½)/nx, w0 = W (j + ½)/ny (cell centres), with
//! v0 = f'(t̂0) + w0, on the table. The job runs coarse to fine: pass 0 the points with
//! i and j multiples of 8, then 4, 2 and 1 (each pass only the points the earlier ones
//! left out), in chunks of [`CHUNK`] points, so a viewer can draw a complete rough picture
//! early and refine it. [`Basins`] assigns attractors on the consumer's side, chunk by
//! chunk in the job's own order (not the order chunks happen to finish), so the
//! numbering does not depend on timing.

use super::{settle, Found, Registry, Settle};
use crate::error::EngineError;
use crate::jobs::{Context, Job, Pass};
use crate::limits;
use crate::run::start::launch;
use crate::system::System;
use std::collections::BTreeMap;

/// Points per work item.
pub const CHUNK: usize = 32;
/// Strides of the passes, coarse to fine.
pub const STRIDES: [usize; 4] = [8, 4, 2, 1];
/// The largest grid side, and the most grid points.
pub const MAX_SIDE: usize = 4000;
pub const MAX_POINTS: usize = 1_000_000;
/// The default grid.
pub const DEFAULT_GRID: (usize, usize) = (200, 100);

/// Everything that defines a basin picture.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinSpec {
    pub sys: System,
    /// Grid points along t̂0 and along w0.
    pub nx: usize,
    pub ny: usize,
    /// Top of the w0 range.
    pub w_max: f64,
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
                    name,
                    value: n.to_string(),
                    range: "1 ..= 4000 points",
                });
            }
        }
        if self.nx * self.ny > MAX_POINTS {
            return Err(EngineError::InvalidParameter {
                name: "grid",
                value: format!("{}x{}", self.nx, self.ny),
                range: "at most 1000000 points",
            });
        }
        if !(self.w_max > 0.0 && self.w_max <= limits::MAX_INITIAL) {
            return Err(EngineError::InvalidParameter {
                name: "w-max",
                value: crate::error::fmt_value(self.w_max),
                range: "0 < W ≤ 1000 (launch velocity relative to the table)",
            });
        }
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

    /// The grid points of pass `p`, in index order.
    fn pass_points(&self, p: usize) -> Vec<usize> {
        let s = STRIDES[p];
        let coarser = STRIDES.get(p.wrapping_sub(1)).copied().filter(|_| p > 0);
        (0..self.len())
            .filter(|&k| {
                let (i, j) = (k % self.nx, k / self.nx);
                let on = |s: usize| i % s == 0 && j % s == 0;
                on(s) && !coarser.is_some_and(on)
            })
            .collect()
    }
}

/// One grid point's attractor.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinPoint {
    pub index: usize,
    pub found: Found,
}

/// One work item's results, numbered in the job's order.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinChunk {
    /// Position of the chunk in the job (pass by pass, item by item).
    pub seq: usize,
    /// Complete results only; a start that cannot be launched is left out.
    pub points: Vec<BasinPoint>,
    /// Grid points the chunk covered (including any left out).
    pub covered: usize,
}

/// The basin picture as a job.
pub struct BasinsJob {
    spec: BasinSpec,
    passes: Vec<Vec<usize>>,
    /// Chunks before each pass.
    offsets: Vec<usize>,
}

impl BasinsJob {
    pub fn new(spec: BasinSpec) -> Result<BasinsJob, EngineError> {
        spec.validate()?;
        let passes: Vec<Vec<usize>> = (0..STRIDES.len()).map(|p| spec.pass_points(p)).collect();
        let mut offsets = Vec::new();
        let mut total = 0;
        for p in &passes {
            offsets.push(total);
            total += p.len().div_ceil(CHUNK);
        }
        Ok(BasinsJob {
            spec,
            passes,
            offsets,
        })
    }

    pub fn spec(&self) -> &BasinSpec {
        &self.spec
    }

    /// Chunks in the whole job.
    pub fn chunks(&self) -> usize {
        self.passes.iter().map(|p| p.len().div_ceil(CHUNK)).sum()
    }
}

impl Job for BasinsJob {
    type State = ();
    type Output = BasinChunk;

    fn passes(&self) -> Vec<Pass> {
        self.passes
            .iter()
            .map(|p| Pass::natural(p.len().div_ceil(CHUNK)))
            .collect()
    }

    fn units(&self) -> usize {
        self.spec.len()
    }

    fn work(&self, pass: usize, item: usize, _: &mut Option<()>, cx: &Context<'_, BasinChunk>) {
        let pts = &self.passes[pass];
        let range = item * CHUNK..((item + 1) * CHUNK).min(pts.len());
        let mut out = Vec::with_capacity(range.len());
        for &index in &pts[range.clone()] {
            let (t0, w0) = self.spec.start(index);
            let Some(start) = launch(&self.spec.sys, t0, w0) else {
                continue;
            };
            let Some((found, ..)) = settle(&self.spec.sys, start, &self.spec.settle, 1, &mut |n| {
                cx.tick(n)
            }) else {
                return;
            };
            out.push(BasinPoint { index, found });
        }
        // Progress counts grid points.
        let covered = range.len();
        cx.emit_units(
            BasinChunk {
                seq: self.offsets[pass] + item,
                points: out,
                covered,
            },
            covered,
        );
    }
}

/// The basin picture as it fills in: the attractor of every grid point assigned so far.
#[derive(Clone, Debug)]
pub struct Basins {
    nx: usize,
    ny: usize,
    /// Attractor id per grid point.
    labels: Vec<Option<u32>>,
    registry: Registry,
    /// Chunks received ahead of their turn.
    pending: BTreeMap<usize, BasinChunk>,
    next: usize,
    /// Grid points assigned (or left out).
    covered: usize,
}

impl Basins {
    pub fn new(spec: &BasinSpec) -> Basins {
        Basins {
            nx: spec.nx,
            ny: spec.ny,
            labels: vec![None; spec.len()],
            registry: Registry::new(),
            pending: BTreeMap::new(),
            next: 0,
            covered: 0,
        }
    }

    /// Take a chunk; assign it and any waiting chunks whose turn it now is. Returns the
    /// grid indices newly labelled.
    pub fn absorb(&mut self, chunk: BasinChunk) -> Vec<usize> {
        self.pending.insert(chunk.seq, chunk);
        let mut labelled = Vec::new();
        while let Some(c) = self.pending.remove(&self.next) {
            for p in &c.points {
                let id = self.registry.assign(&p.found);
                self.labels[p.index] = Some(id as u32);
                labelled.push(p.index);
            }
            self.covered += c.covered;
            self.next += 1;
        }
        labelled
    }

    /// The grid size (nx, ny).
    pub fn grid(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The attractor id of grid point (i, j), if assigned.
    pub fn label(&self, i: usize, j: usize) -> Option<u32> {
        self.labels.get(j * self.nx + i).copied().flatten()
    }

    /// Labels of every grid point, index j·nx + i.
    pub fn labels(&self) -> &[Option<u32>] {
        &self.labels
    }

    pub fn registry(&self) -> &Registry {
        &self.registry
    }

    /// Grid points done.
    pub fn covered(&self) -> usize {
        self.covered
    }

    /// Whether every grid point is done.
    pub fn complete(&self) -> bool {
        self.covered == self.labels.len()
    }

    /// The label shown for grid point (i, j) while the picture fills in: its own, or
    /// that of the nearest coarser grid point already assigned (the block it lies in).
    pub fn preview_label(&self, i: usize, j: usize) -> Option<u32> {
        for s in [1, 2, 4, 8] {
            let (ci, cj) = (i - i % s, j - j % s);
            if let Some(l) = self.label(ci, cj) {
                return Some(l);
            }
        }
        None
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Table;

    #[test]
    fn the_passes_cover_every_point_once() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        for (nx, ny) in [(1, 1), (7, 3), (17, 9), (64, 32)] {
            let spec = BasinSpec {
                nx,
                ny,
                ..BasinSpec::new(sys.clone())
            };
            let mut all: Vec<usize> = (0..4).flat_map(|p| spec.pass_points(p)).collect();
            all.sort();
            assert_eq!(all, (0..nx * ny).collect::<Vec<_>>());
            // Pass 0 is the stride-8 sublattice.
            assert_eq!(spec.pass_points(0).len(), nx.div_ceil(8) * ny.div_ceil(8));
        }
    }
}
