//! What the grid-picture panels (the basins, the plane view) have in common: a picture
//! over a grid of cells, one per column and two per row of the plot, computed by an
//! engine job coarse to fine while the panel is shown; the grid sized to the plot, the
//! job started, restarted and stopped, its chunks absorbed as they arrive, the progress
//! for the title, the refusal shown in place of the picture, and the cells drawn as an
//! upper and a lower half in colour.
//!
//! [`GridPicture`] is generic over the engine's [`Filled`] picture (what a cell holds,
//! what a chunk brings, which job computes it), so a panel keeps only what is its own: the spec it
//! asks for, its colours and text fallback, its legend and extras.

use super::{Address, Effect, JobMsg, Shared, Target, Workers};
use bouncemap_engine::jobs::picture::{Cells, Chunk, Filled};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::widgets::{Paragraph, Widget};
use std::time::Instant;

/// The chunks a picture's job streams.
pub type ChunkOf<P> = Chunk<<<P as Filled>::Cells as Cells>::Cell>;

/// A grid picture in a panel: shown or not, its job, its progress.
pub struct GridPicture<P: Filled> {
    /// Whether the panel is shown (in the place of another).
    pub shown: bool,
    /// The generation of the running job.
    pub gen: u64,
    /// What the picture shows (None before the first start).
    pub spec: Option<P::Spec>,
    pub picture: Option<P>,
    /// The job ran to its end, was refused, or the panel is hidden.
    pub done: bool,
    /// Why the last start was refused.
    pub error: Option<String>,
    pub started: Option<Instant>,
    /// Seconds since the start, at the last chunk.
    pub elapsed: f64,
    /// Cells across and up for the plot at the last layout.
    grid: (usize, usize),
}

impl<P: Filled> Default for GridPicture<P> {
    fn default() -> Self {
        GridPicture {
            shown: false,
            gen: 0,
            spec: None,
            picture: None,
            done: false,
            error: None,
            started: None,
            elapsed: 0.0,
            grid: (0, 0),
        }
    }
}

impl<P: Filled> GridPicture<P> {
    /// Cells across and up for the plot at the last layout.
    pub fn grid(&self) -> (usize, usize) {
        self.grid
    }

    /// Size the grid to `plot`: one cell per column, two per row. A new size restarts
    /// the picture (`me`'s work) if shown.
    pub fn set_plot(&mut self, plot: Rect, me: Target, shared: &mut Shared) {
        let grid = (plot.width.max(1) as usize, 2 * plot.height.max(1) as usize);
        if grid != self.grid {
            self.grid = grid;
            if self.shown {
                shared.effect(Effect::Start(me));
            }
        }
    }

    /// Show or hide the panel; either way its work (`me`'s) starts or stops.
    pub fn toggle(&mut self, me: Target, shared: &mut Shared) {
        self.shown = !self.shown;
        shared.effect(Effect::Start(me));
    }

    /// Hidden: stop the job and say so (true); shown: nothing (false).
    pub fn stop_if_hidden(&mut self, me: Target, workers: &Workers) -> bool {
        if self.shown {
            return false;
        }
        workers.cancel(me);
        self.done = true;
        true
    }

    /// Start the job for `spec` with an empty picture; if it is refused, stop the
    /// previous one and keep the reason. True if it started.
    pub fn run(
        &mut self,
        spec: P::Spec,
        at: Address<JobMsg<ChunkOf<P>>>,
        workers: &Workers,
    ) -> bool {
        match P::job(&spec) {
            Ok(job) => {
                self.gen = workers.start_job(at, job);
                self.picture = Some(P::empty(&spec));
                self.spec = Some(spec);
                self.error = None;
                self.done = false;
                self.started = Some(Instant::now());
                self.elapsed = 0.0;
                true
            }
            Err(e) => {
                workers.cancel(at.to);
                self.error = Some(e.to_string());
                self.done = true;
                false
            }
        }
    }

    /// A message of the job started under `gen`: a chunk is absorbed (its pass is
    /// returned), the end noted; messages of older jobs are dropped.
    pub fn receive(
        &mut self,
        gen: u64,
        msg: JobMsg<ChunkOf<P>>,
        shared: &mut Shared,
    ) -> Option<u32> {
        if gen != self.gen {
            return None;
        }
        let mut pass = None;
        match msg {
            JobMsg::Done => self.done = true,
            JobMsg::Batch(b) => {
                pass = Some(b.pass);
                if let Some(p) = self.picture.as_mut() {
                    p.absorb(b.data);
                }
            }
        }
        if let Some(s) = self.started {
            self.elapsed = s.elapsed().as_secs_f64();
        }
        shared.dirty = true;
        pass
    }

    /// Whether the job may still send something.
    pub fn busy(&self) -> bool {
        self.shown && !self.done
    }

    /// The progress for the title: the time it took, paused, or the share of cells done.
    pub fn progress(&self, picture: &P, shared: &Shared) -> String {
        let (nx, ny) = picture.size();
        let frac = picture.covered() as f64 / (nx * ny).max(1) as f64;
        if self.done && !shared.show_times {
            "done".into()
        } else if self.done {
            format!("done {:.1}s", self.elapsed)
        } else if shared.paused {
            "paused".into()
        } else {
            format!("{:>3.0}%", 100.0 * frac)
        }
    }

    /// The refusal in place of the picture, headed `what`; true if there was one.
    pub fn draw_error(&self, what: &str, shared: &Shared, inner: Rect, buf: &mut Buffer) -> bool {
        let Some(e) = &self.error else {
            return false;
        };
        Paragraph::new(format!("{what}: {e}"))
            .style(shared.theme.error())
            .render(inner, buf);
        true
    }
}

/// Draw a picture of `size` cells into `plot` as halves: each screen cell its upper cell
/// in the foreground (▀) and its lower one in the background, coloured by `colour` (cell
/// (i, j), j = 0 at the bottom); cells without a colour stay as they are. False, and
/// nothing drawn, unless the picture has one cell per column and two per row.
pub fn draw_halves(
    plot: Rect,
    size: (usize, usize),
    buf: &mut Buffer,
    colour: impl Fn(usize, usize) -> Option<Color>,
) -> bool {
    let (nx, ny) = size;
    if nx != plot.width as usize || ny != 2 * plot.height as usize {
        return false;
    }
    for r in 0..plot.height {
        let j_top = ny - 1 - 2 * r as usize;
        for c in 0..plot.width {
            let i = c as usize;
            let top = colour(i, j_top);
            let bottom = colour(i, j_top - 1);
            if top.is_none() && bottom.is_none() {
                continue;
            }
            let mut style = Style::new();
            if let Some(t) = top {
                style = style.fg(t);
            }
            if let Some(b) = bottom {
                style = style.bg(b);
            }
            let glyph = if top.is_some() { "▀" } else { " " };
            buf.set_string(plot.x + c, plot.y + r, glyph, style);
        }
    }
    true
}
