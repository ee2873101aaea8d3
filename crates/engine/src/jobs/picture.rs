//! Pictures over a W × H grid of cells, computed coarse to fine as one [`Job`]: the
//! basin picture (a start per cell) and the two-parameter plane (a system per cell)
//! are both this job with their own [`Cells`].
//!
//! Cell (i, j) has index j·W + i. The job runs in four passes: the cells whose i and j
//! are multiples of 8 ([`STRIDES`]), then of 4, of 2, and the rest (each pass only what
//! the earlier ones left out), in chunks of [`Cells::chunk`] cells, handed out in order
//! or spread over the pass. A viewer draws every cell from the nearest coarser one
//! computed so far ([`Picture::preview`]) and so has a complete rough picture after the
//! first pass (1/64 of the work). A shard ([`Cells::shard`]) computes the cells whose
//! index is I − 1 modulo N, so every shard covers the whole picture.
//!
//! Chunks carry their position in the job ([`Chunk::seq`]); a consumer whose result
//! depends on the order it takes cells in (the basins' attractor numbering) takes them
//! through a [`Sequencer`], so nothing depends on timing.

use crate::jobs::grid::Shard;
use crate::jobs::{Context, Job, Pass};
use std::collections::BTreeMap;

/// Strides of the passes, coarse to fine.
pub const STRIDES: [usize; 4] = [8, 4, 2, 1];
/// The largest side of a picture.
pub const MAX_SIDE: usize = 4000;
/// The most cells of a picture.
pub const MAX_CELLS: usize = 1_000_000;

/// What a picture computes at each of its cells.
pub trait Cells: Send + Sync + 'static {
    /// The result of one cell.
    type Cell: Send + 'static;

    /// (W, H).
    fn size(&self) -> (usize, usize);

    /// Cells per work item.
    fn chunk(&self) -> usize;

    /// The part of the picture this job computes.
    fn shard(&self) -> Shard {
        Shard::WHOLE
    }

    /// Whether the items of a pass are handed out spread over it (a preview that
    /// covers the picture early) rather than in index order.
    fn spread(&self) -> bool;

    /// Compute cell `index`, calling `tick` every few dozen events. None: cancelled
    /// (`tick` said stop); Some(None): the cell is left out (no valid system or start).
    fn compute(
        &self,
        index: usize,
        tick: &mut dyn FnMut(u64) -> bool,
    ) -> Option<Option<Self::Cell>>;
}

/// One work item's results, numbered in the job's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Chunk<T> {
    /// Position of the chunk in the job (pass by pass, item by item).
    pub seq: usize,
    /// (cell index, result); a cell left out is not here.
    pub cells: Vec<(usize, T)>,
    /// Cells the chunk covered (including any left out).
    pub covered: usize,
}

/// A picture as a job.
pub struct PictureJob<C: Cells> {
    cells: C,
    /// The shard's cells of each pass, in index order.
    passes: Vec<Vec<usize>>,
    /// Chunks before each pass.
    offsets: Vec<usize>,
}

impl<C: Cells> PictureJob<C> {
    /// Lay out the passes of `cells` (validated by the caller).
    pub fn over(cells: C) -> PictureJob<C> {
        let passes: Vec<Vec<usize>> = (0..STRIDES.len())
            .map(|p| pass_cells(cells.size(), cells.shard(), p))
            .collect();
        let mut offsets = Vec::with_capacity(passes.len());
        let mut total = 0;
        for p in &passes {
            offsets.push(total);
            total += p.len().div_ceil(cells.chunk().max(1));
        }
        PictureJob {
            cells,
            passes,
            offsets,
        }
    }

    /// What the picture computes.
    pub fn cells(&self) -> &C {
        &self.cells
    }

    /// Chunks in the whole job.
    pub fn chunks(&self) -> usize {
        let c = self.cells.chunk().max(1);
        self.passes.iter().map(|p| p.len().div_ceil(c)).sum()
    }

    /// Cells this job computes (its shard's).
    pub fn len(&self) -> usize {
        self.passes.iter().map(Vec::len).sum()
    }

    /// Whether the job has no cell (never for a validated picture).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The cells of pass `p` of a `size` picture that `shard` holds (on the stride
/// `STRIDES[p]` lattice and not on the previous pass's), in index order.
pub fn pass_cells((nx, ny): (usize, usize), shard: Shard, p: usize) -> Vec<usize> {
    let s = STRIDES[p];
    let coarser = (p > 0).then(|| STRIDES[p - 1]);
    (0..nx * ny)
        .filter(|&k| {
            let (i, j) = (k % nx, k / nx);
            let on = |s: usize| i % s == 0 && j % s == 0;
            shard.holds(k, 1) && on(s) && !coarser.is_some_and(on)
        })
        .collect()
}

impl<C: Cells> Job for PictureJob<C> {
    type State = ();
    type Output = Chunk<C::Cell>;

    fn passes(&self) -> Vec<Pass> {
        let c = self.cells.chunk().max(1);
        self.passes
            .iter()
            .map(|p| Pass {
                len: p.len().div_ceil(c),
                spread: self.cells.spread(),
            })
            .collect()
    }

    fn units(&self) -> usize {
        self.len()
    }

    fn work(&self, pass: usize, item: usize, _: &mut Option<()>, cx: &Context<'_, Self::Output>) {
        let c = self.cells.chunk().max(1);
        let all = &self.passes[pass];
        let range = item * c..((item + 1) * c).min(all.len());
        let mut out = Vec::with_capacity(range.len());
        for &index in &all[range.clone()] {
            match self.cells.compute(index, &mut |n| cx.tick(n)) {
                None => return,
                Some(Some(cell)) => out.push((index, cell)),
                Some(None) => {}
            }
        }
        // Progress counts cells.
        let covered = range.len();
        cx.emit_units(
            Chunk {
                seq: self.offsets[pass] + item,
                cells: out,
                covered,
            },
            covered,
        );
    }
}

/// A picture as it fills in: every cell received so far.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture<T> {
    nx: usize,
    ny: usize,
    cells: Vec<Option<T>>,
    covered: usize,
    /// Cells of the shard.
    total: usize,
}

impl<T> Picture<T> {
    /// An empty `nx × ny` picture of which `total` cells will come (a shard's).
    pub fn blank(nx: usize, ny: usize, total: usize) -> Picture<T> {
        Picture {
            nx,
            ny,
            cells: (0..nx * ny).map(|_| None).collect(),
            covered: 0,
            total,
        }
    }

    /// Store the result of cell `index` (ignored outside the picture).
    pub fn set(&mut self, index: usize, value: T) {
        if let Some(slot) = self.cells.get_mut(index) {
            *slot = Some(value);
        }
    }

    /// Count `n` more cells as done (computed or left out).
    pub fn cover(&mut self, n: usize) {
        self.covered += n;
    }

    /// Take a chunk whose cells are stored as they are.
    pub fn absorb(&mut self, chunk: Chunk<T>) {
        for (index, value) in chunk.cells {
            self.set(index, value);
        }
        self.cover(chunk.covered);
    }

    /// (W, H).
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Cell (i, j), if computed.
    pub fn get(&self, i: usize, j: usize) -> Option<&T> {
        if i >= self.nx || j >= self.ny {
            return None;
        }
        self.cells[j * self.nx + i].as_ref()
    }

    /// Every cell, index j·W + i.
    pub fn cells(&self) -> &[Option<T>] {
        &self.cells
    }

    /// Cells of the shard done (computed or left out).
    pub fn covered(&self) -> usize {
        self.covered
    }

    /// Whether every cell of the shard is done.
    pub fn complete(&self) -> bool {
        self.covered >= self.total
    }

    /// What cell (i, j) shows while the picture fills in: its own result, or that of
    /// the nearest coarser lattice point already computed (the block it lies in).
    pub fn preview(&self, i: usize, j: usize) -> Option<&T> {
        STRIDES
            .iter()
            .rev()
            .find_map(|&s| self.get(i - i % s, j - j % s))
    }
}

/// A picture over a grid as its job fills it in: what every front end that starts,
/// fills and draws one (the basins, the plane) needs, whatever the picture.
pub trait Filled: Sized {
    /// What is computed (the grid's size is part of it).
    type Spec: Clone + PartialEq;
    /// What one cell computes.
    type Cells: Cells;

    /// The job for `spec`, validated.
    fn job(spec: &Self::Spec) -> Result<PictureJob<Self::Cells>, crate::error::EngineError>;
    /// An empty picture of `spec`.
    fn empty(spec: &Self::Spec) -> Self;
    /// Take a chunk of the job.
    fn absorb(&mut self, chunk: Chunk<<Self::Cells as Cells>::Cell>);
    /// Cells across and up.
    fn size(&self) -> (usize, usize);
    /// Cells done (computed or left out).
    fn covered(&self) -> usize;
    /// Whether every cell of the job is done.
    fn complete(&self) -> bool;
}

/// Puts chunks back in the job's order, whatever order they arrive in.
#[derive(Clone, Debug, PartialEq)]
pub struct Sequencer<T> {
    pending: BTreeMap<usize, Chunk<T>>,
    next: usize,
}

impl<T> Default for Sequencer<T> {
    fn default() -> Self {
        Sequencer {
            pending: BTreeMap::new(),
            next: 0,
        }
    }
}

impl<T> Sequencer<T> {
    /// Take `chunk`; return it and any waiting chunks whose turn it now is, in order.
    pub fn push(&mut self, chunk: Chunk<T>) -> Vec<Chunk<T>> {
        self.pending.insert(chunk.seq, chunk);
        let mut ready = Vec::new();
        while let Some(c) = self.pending.remove(&self.next) {
            ready.push(c);
            self.next += 1;
        }
        ready
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_passes_cover_every_cell_of_every_shard_once() {
        for (nx, ny, count) in [(1, 1, 1), (7, 3, 2), (17, 9, 3), (64, 32, 1)] {
            let mut all = Vec::new();
            for index in 0..count {
                let shard = Shard { index, count };
                all.extend((0..4).flat_map(|p| pass_cells((nx, ny), shard, p)));
            }
            all.sort();
            assert_eq!(all, (0..nx * ny).collect::<Vec<_>>());
            // Pass 0 is the stride-8 sublattice.
            assert_eq!(
                pass_cells((nx, ny), Shard::WHOLE, 0).len(),
                nx.div_ceil(8) * ny.div_ceil(8)
            );
        }
    }

    #[test]
    fn the_sequencer_releases_chunks_in_order() {
        let chunk = |seq| Chunk {
            seq,
            cells: vec![(seq, ())],
            covered: 1,
        };
        let mut s = Sequencer::default();
        assert!(s.push(chunk(2)).is_empty());
        assert!(s.push(chunk(1)).is_empty());
        let seqs: Vec<usize> = s.push(chunk(0)).iter().map(|c| c.seq).collect();
        assert_eq!(seqs, vec![0, 1, 2]);
        assert_eq!(s.push(chunk(3)).len(), 1);
    }

    #[test]
    fn the_preview_shows_the_nearest_coarser_cell() {
        let mut p: Picture<u32> = Picture::blank(10, 10, 100);
        p.set(0, 7);
        assert_eq!(p.preview(5, 5), Some(&7));
        assert_eq!(p.preview(9, 9), None);
        p.set(8 * 10 + 8, 3);
        assert_eq!(p.preview(9, 9), Some(&3));
        assert!(!p.complete());
        p.cover(100);
        assert!(p.complete());
    }
}
