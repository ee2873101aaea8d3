//! The basins panel: for the current table, α and r, which attractor each start
//! (t̂0, w0) ends on, over t̂0 ∈ [0, 1) and w0 = v0 − f'(t̂0) ∈ [0, W], filling in coarse
//! to fine as the engine's basins job streams its chunks; with a legend of every
//! attractor found (kind, period, largest exponent, share of the starts). It takes the
//! phase plot's place while shown (the basins key switches). The grid has one start per
//! column and two per row (each cell is drawn as an upper and a lower half in colour;
//! without colour each cell shows the texture of its most frequent attractor).

use super::{panel, Component, Effect, JobMsg, Registered, Shared, Workers};
use crate::output::basin_map::{self, describe, exponent, numbers, texture};
use crate::output::hitgrid::Range;
use crate::tui::keymap::Action;
use crate::tui::params::{ParamId, Touch};
use crate::tui::plot::draw_axes;
use bouncemap_engine::attractors::basins::{BasinChunk, BasinSpec, Basins, BasinsJob};
use bouncemap_engine::attractors::Kind;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};
use std::time::Instant;

const LABEL_W: u16 = 4;
/// Legend lines at most.
const LEGEND: u16 = 3;

/// The basins panel.
#[derive(Default)]
pub struct BasinsPanel {
    /// Whether the panel is shown (in place of the phase plot).
    pub shown: bool,
    pub gen: u64,
    pub spec: Option<BasinSpec>,
    pub basins: Option<Basins>,
    pub done: bool,
    pub error: Option<String>,
    pub started: Option<Instant>,
    pub elapsed: f64,
    /// Grid size for the pane at the last layout.
    grid: (usize, usize),
}

/// The inner area of the pane split into the picture (with axes) and the legend.
fn split(inner: Rect) -> (Rect, Rect) {
    let legend = LEGEND.min(inner.height.saturating_sub(6));
    let picture = Rect {
        height: inner.height - legend,
        ..inner
    };
    let rest = Rect {
        y: inner.y + picture.height,
        height: legend,
        ..inner
    };
    (picture, rest)
}

/// The plot rectangle inside `pane` (as [`draw_axes`] lays it out).
fn plot_rect(pane: Rect) -> Rect {
    let inner = Rect {
        x: pane.x + 1,
        y: pane.y + 1,
        width: pane.width.saturating_sub(2),
        height: pane.height.saturating_sub(2),
    };
    let (picture, _) = split(inner);
    Rect {
        x: picture.x + LABEL_W + 1,
        y: picture.y,
        width: picture.width.saturating_sub(LABEL_W + 1),
        height: picture.height.saturating_sub(1),
    }
}

impl BasinsPanel {
    /// The colour of attractor `id` (resting and escaping starts in grey).
    fn color(&self, shared: &Shared, id: u32) -> Option<Color> {
        let reg = self.basins.as_ref()?.registry();
        match reg.attractors().get(id as usize)?.kind {
            Kind::Resting | Kind::Escaping => shared.theme.nowhere(),
            _ => shared.theme.attractor_color(id as usize),
        }
    }

    fn title(&self, shared: &Shared) -> String {
        let head = " Basins t̂0×w0";
        let Some(b) = &self.basins else {
            return format!("{head} ");
        };
        let (nx, ny) = b.grid();
        let frac = b.covered() as f64 / (nx * ny).max(1) as f64;
        let n = b.registry().attractors().len();
        let state = if self.done {
            format!("done {:.1}s", self.elapsed)
        } else if shared.paused {
            "paused".into()
        } else {
            format!("{:>3.0}%", 100.0 * frac)
        };
        format!("{head} · {n} found · {state} ")
    }
}

impl Component for BasinsPanel {
    type Msg = JobMsg<BasinChunk>;

    fn shown(&self) -> bool {
        self.shown
    }

    /// Size the grid to the pane: one start per column, two per row. A new size
    /// restarts the picture (if shown).
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        let plot = plot_rect(pane);
        let grid = (plot.width.max(1) as usize, 2 * plot.height.max(1) as usize);
        if grid != self.grid {
            self.grid = grid;
            if self.shown {
                shared.effect(Effect::Start(Self::TARGET));
            }
        }
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action != Action::ToggleBasins {
            return false;
        }
        self.shown = !self.shown;
        shared.effect(Effect::Start(Self::TARGET));
        if self.shown {
            shared.say(
                "basins: which attractor each start (t̂0, w0) ends on; the key again shows the phase plot",
                false,
            );
        }
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if self.shown && id.touches() == Touch::System {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if !self.shown {
            workers.cancel(Self::TARGET);
            self.done = true;
            return;
        }
        let sys = shared.system();
        let spec = BasinSpec {
            nx: self.grid.0.max(1),
            ny: self.grid.1.max(1),
            ..BasinSpec::new(sys)
        };
        match BasinsJob::new(spec.clone()) {
            Ok(job) => {
                self.gen = workers.start_job(Self::ADDRESS, job);
                self.basins = Some(Basins::new(&spec));
                self.spec = Some(spec);
                self.error = None;
                self.done = false;
                self.started = Some(Instant::now());
                self.elapsed = 0.0;
            }
            Err(e) => {
                workers.cancel(Self::TARGET);
                self.error = Some(e.to_string());
                self.done = true;
            }
        }
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        match msg {
            JobMsg::Done => self.done = true,
            JobMsg::Batch(b) => {
                if let Some(basins) = self.basins.as_mut() {
                    basins.absorb(b.data);
                }
            }
        }
        if let Some(s) = self.started {
            self.elapsed = s.elapsed().as_secs_f64();
        }
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.shown && !self.done
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let block = panel(app, self.title(app), false);
        let inner = block.inner(area);
        block.render(area, buf);
        if let Some(e) = &self.error {
            Paragraph::new(format!("Basins: {e}"))
                .style(app.theme.error())
                .render(inner, buf);
            return;
        }
        let (Some(b), Some(spec)) = (&self.basins, &self.spec) else {
            return;
        };
        let (picture, legend) = split(inner);
        let plot = draw_axes(
            picture,
            buf,
            Range::new(0.0, 1.0),
            Range::new(0.0, spec.w_max),
            LABEL_W,
            &app.theme,
        );
        let (nx, ny) = b.grid();
        let reg = b.registry();
        let number = numbers(reg);
        let colour = app.theme.attractor_color(0).is_some();
        if colour && nx == plot.width as usize && ny == 2 * plot.height as usize {
            for r in 0..plot.height {
                let j_top = ny - 1 - 2 * r as usize;
                for c in 0..plot.width {
                    let i = c as usize;
                    let top = b.preview_label(i, j_top).and_then(|l| self.color(app, l));
                    let bottom = b
                        .preview_label(i, j_top - 1)
                        .and_then(|l| self.color(app, l));
                    if top.is_none() && bottom.is_none() {
                        continue;
                    }
                    let mut style = Style::new();
                    if let Some(t) = top {
                        style = style.fg(t);
                    }
                    if let Some(bt) = bottom {
                        style = style.bg(bt);
                    }
                    let glyph = if top.is_some() { "▀" } else { " " };
                    buf.set_string(plot.x + c, plot.y + r, glyph, style);
                }
            }
        } else {
            let cells = basin_map::cells(b, plot.width as usize, plot.height as usize);
            for (r, line) in cells.iter().enumerate() {
                for (c, l) in line.iter().enumerate() {
                    if let Some(id) = l {
                        let n = number[*id as usize];
                        buf.set_string(
                            plot.x + c as u16,
                            plot.y + r as u16,
                            texture(n).to_string(),
                            app.theme.attractor(n - 1),
                        );
                    }
                }
            }
        }
        // The legend: largest basins first.
        let lines: Vec<Line> = reg
            .ranked()
            .into_iter()
            .take(legend.height as usize)
            .map(|id| {
                let a = &reg.attractors()[id];
                let n = number[id];
                let swatch = if colour {
                    Span::styled(
                        "██",
                        Style::new().fg(self.color(app, id as u32).unwrap_or(Color::Reset)),
                    )
                } else {
                    Span::styled(
                        format!("{}{}", texture(n), texture(n)),
                        app.theme.attractor(n - 1),
                    )
                };
                Line::from(vec![
                    swatch,
                    Span::raw(format!(
                        " {:>5.1}% {} λ {}",
                        100.0 * reg.fraction(id),
                        describe(a),
                        exponent(a.lyapunov),
                    )),
                ])
            })
            .collect();
        Paragraph::new(lines).render(legend, buf);
    }
}
