//! The plane as a [`Job`]: passes coarse to fine, chunks of pixels, and [`Plane`], the
//! picture as it fills in.

use super::{Pixel, PlaneSpec, CHUNK, KEEP, LYAPUNOV_SAMPLE, STRIDES};
use crate::attractors::{self, Settle};
use crate::error::EngineError;
use crate::jobs::{Context, Control, Executor, Job, Pass};
use crate::map::ImpactMap;
use crate::run::{has_sticking, Advance, OrbitRun};

/// One work item's results.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneChunk {
    /// (pixel index, result); a pixel whose system or start is refused is left out.
    pub pixels: Vec<(usize, Pixel)>,
    /// Pixels the chunk covered (including any left out).
    pub covered: usize,
}

/// The plane as a job.
pub struct PlaneJob {
    spec: PlaneSpec,
    /// The shard's pixels of each pass, in index order.
    passes: Vec<Vec<usize>>,
}

impl PlaneJob {
    pub fn new(spec: PlaneSpec) -> Result<PlaneJob, EngineError> {
        spec.validate()?;
        let passes = (0..STRIDES.len()).map(|p| pass_pixels(&spec, p)).collect();
        Ok(PlaneJob { spec, passes })
    }

    pub fn spec(&self) -> &PlaneSpec {
        &self.spec
    }

    /// One pixel from its start to the end of the transient; None if cancelled.
    fn pixel(&self, index: usize, cx: &Context<'_, PlaneChunk>) -> Option<Option<Pixel>> {
        let (x, y) = self.spec.values(index);
        let Ok(sys) = self.spec.system_at(x, y) else {
            return Some(None);
        };
        let Ok(start) = self.spec.initial_state(&sys) else {
            return Some(None);
        };
        let map = ImpactMap::new(sys.clone(), self.spec.solver, start);
        let mut run = OrbitRun::new(map, KEEP, self.spec.periodicity);
        let end = self.spec.transient as i64;
        let (outcome, points) = match run.advance(end, end, &mut |n| cx.tick(n)) {
            Advance::Done(o, p) => (o, p),
            Advance::Checkpoint | Advance::Cancelled => return None,
        };
        let lyapunov = if self.spec.lyapunov {
            let settle = Settle {
                transient: self.spec.transient,
                periodicity: self.spec.periodicity,
                sample: LYAPUNOV_SAMPLE,
                solver: self.spec.solver,
            };
            let found =
                attractors::identify(&sys, &settle, &outcome, run.state(), &mut |n| cx.tick(n))?;
            found.lyapunov()
        } else {
            None
        };
        Some(Some(Pixel {
            outcome,
            sticking: has_sticking(&points),
            lyapunov,
        }))
    }
}

/// The shard's pixels of pass `p` (on the stride-`STRIDES[p]` lattice and not on the
/// previous pass's), in index order.
fn pass_pixels(spec: &PlaneSpec, p: usize) -> Vec<usize> {
    let s = STRIDES[p];
    let coarser = (p > 0).then(|| STRIDES[p - 1]);
    (0..spec.len())
        .filter(|&k| {
            let (i, j) = spec.pixel(k);
            let on = |s: usize| i % s == 0 && j % s == 0;
            spec.holds(k) && on(s) && !coarser.is_some_and(on)
        })
        .collect()
}

impl Job for PlaneJob {
    type State = ();
    type Output = PlaneChunk;

    fn passes(&self) -> Vec<Pass> {
        self.passes
            .iter()
            .map(|p| Pass::spread(p.len().div_ceil(CHUNK)))
            .collect()
    }

    fn units(&self) -> usize {
        self.spec.shard_len()
    }

    fn work(&self, pass: usize, item: usize, _: &mut Option<()>, cx: &Context<'_, PlaneChunk>) {
        let pts = &self.passes[pass];
        let range = item * CHUNK..((item + 1) * CHUNK).min(pts.len());
        let mut out = Vec::with_capacity(range.len());
        for &index in &pts[range.clone()] {
            match self.pixel(index, cx) {
                None => return,
                Some(Some(p)) => out.push((index, p)),
                Some(None) => {}
            }
        }
        let covered = range.len();
        cx.emit_units(
            PlaneChunk {
                pixels: out,
                covered,
            },
            covered,
        );
    }
}

/// The plane as it fills in: every pixel computed so far.
#[derive(Clone, Debug)]
pub struct Plane {
    nx: usize,
    ny: usize,
    pixels: Vec<Option<Pixel>>,
    covered: usize,
    total: usize,
}

impl Plane {
    /// An empty picture of `spec`'s shard.
    pub fn new(spec: &PlaneSpec) -> Plane {
        Plane {
            nx: spec.x.n,
            ny: spec.y.n,
            pixels: vec![None; spec.len()],
            covered: 0,
            total: spec.shard_len(),
        }
    }

    /// Take a chunk.
    pub fn absorb(&mut self, chunk: PlaneChunk) {
        for (index, p) in chunk.pixels {
            if let Some(slot) = self.pixels.get_mut(index) {
                *slot = Some(p);
            }
        }
        self.covered += chunk.covered;
    }

    /// (W, H).
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Pixel (i, j), if computed.
    pub fn get(&self, i: usize, j: usize) -> Option<&Pixel> {
        if i >= self.nx || j >= self.ny {
            return None;
        }
        self.pixels[j * self.nx + i].as_ref()
    }

    /// Every pixel, index j·W + i.
    pub fn pixels(&self) -> &[Option<Pixel>] {
        &self.pixels
    }

    /// Pixels of the shard done (computed or left out).
    pub fn covered(&self) -> usize {
        self.covered
    }

    /// Whether every pixel of the shard is done.
    pub fn complete(&self) -> bool {
        self.covered >= self.total
    }

    /// What pixel (i, j) shows while the picture fills in: its own result, or that of
    /// the nearest coarser lattice point already computed (the block it lies in).
    pub fn preview(&self, i: usize, j: usize) -> Option<&Pixel> {
        STRIDES
            .iter()
            .rev()
            .find_map(|&s| self.get(i - i % s, j - j % s))
    }
}

/// Run a plane to the end on `executor` (under a fresh control).
pub fn collect(spec: &PlaneSpec, executor: &Executor) -> Result<Plane, EngineError> {
    let job = PlaneJob::new(spec.clone())?;
    let mut plane = Plane::new(spec);
    executor.run(job, &Control::new(), |b| plane.absorb(b.data));
    Ok(plane)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::Axis;
    use crate::sweep::{Shard, SweepParam};
    use crate::table::Table;

    #[test]
    fn the_passes_cover_every_pixel_of_the_shard_once() {
        for (nx, ny, count) in [(1, 1, 1), (7, 3, 2), (17, 9, 3), (64, 32, 1)] {
            let mut spec = PlaneSpec::new(
                Table::fd(0.1).unwrap(),
                Axis {
                    param: SweepParam::Alpha,
                    lo: 0.45,
                    hi: 0.6,
                    n: nx,
                },
                Axis {
                    param: SweepParam::R,
                    lo: 0.5,
                    hi: 0.9,
                    n: ny,
                },
                0.45,
                0.8,
            );
            let mut all = Vec::new();
            for index in 0..count {
                spec.shard = Shard { index, count };
                all.extend((0..4).flat_map(|p| pass_pixels(&spec, p)));
            }
            all.sort();
            assert_eq!(all, (0..nx * ny).collect::<Vec<_>>());
        }
    }
}
