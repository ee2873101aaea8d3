//! The basins panel: for the current table, α and r, which attractor each start
//! (t̂0, w0) ends on, over t̂0 ∈ [0, 1) and w0 = v0 − f'(t̂0) ∈ [0, W], filling in coarse
//! to fine as the engine's basins job streams its chunks; with a legend of every
//! attractor found (kind, period, largest exponent, share of the starts). It takes the
//! phase plot's place while shown (the basins key switches). The grid has one start per
//! column and two per row (each cell is drawn as an upper and a lower half in colour;
//! without colour each cell shows the texture of its most frequent attractor). The job,
//! its progress and the halves are [`super::grid_picture`]'s; the spec, the colours,
//! the textures and the legend are this panel's.

use super::grid_picture::{draw_halves, GridPicture};
use super::{panel, Component, Effect, JobMsg, Registered, Shared, Workers};
use crate::output::basin_map::{self, describe, exponent, numbers, texture_in};
use crate::output::hitgrid::Range;
use crate::tui::keymap::Action;
use crate::tui::layout::plot_area_within;
use crate::tui::params::{ParamId, Touch};
use crate::tui::plot::{draw_axes, Axes};
use bouncemap_engine::attractors::basins::{BasinChunk, BasinSpec, Basins};
use bouncemap_engine::attractors::global::tracks_of;
use bouncemap_engine::attractors::{Kind, Registry};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

const LABEL_W: u16 = 4;
/// Legend lines at most.
const LEGEND: u16 = 3;

/// The basins panel.
#[derive(Default)]
pub struct BasinsPanel {
    /// The picture, its job and whether it is shown (in place of the phase plot).
    pub view: GridPicture<Basins>,
}

/// Legend rows under the picture in a pane whose inner area is `inner_h` rows high.
fn legend_rows(inner_h: u16) -> u16 {
    LEGEND.min(inner_h.saturating_sub(6))
}

/// The inner area of the pane split into the picture (with axes) and the legend.
fn split(inner: Rect) -> (Rect, Rect) {
    let legend = legend_rows(inner.height);
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

/// The plot rectangle inside `pane` (as [`draw_axes`] lays it out above the legend).
fn plot_rect(pane: Rect) -> Rect {
    let legend = legend_rows(pane.height.saturating_sub(2));
    let above = Rect {
        height: pane.height - legend,
        ..pane
    };
    plot_area_within(above, LABEL_W)
}

impl BasinsPanel {
    /// The colour of attractor `id` (by its number, as the figures colour it: 1 = the
    /// largest basin; resting and escaping starts in the figures' grey).
    fn color(&self, shared: &Shared, id: u32, number: &[usize]) -> Option<Color> {
        let reg = self.view.picture.as_ref()?.registry();
        match reg.attractors().get(id as usize)?.kind {
            Kind::Resting | Kind::Escaping => shared.theme.nowhere(),
            _ => shared
                .theme
                .attractor_color(number.get(id as usize)?.saturating_sub(1)),
        }
    }

    /// The number of each attractor (1 = the largest basin), or, at the α the
    /// attractors-along-α view's cursor is at, that view's number for the same
    /// attractor (the others after its numbers, largest basin first).
    fn numbers(&self, shared: &Shared, reg: &Registry) -> Vec<usize> {
        let mut number = numbers(reg);
        let here = self.view.spec.as_ref().map(|s| s.sys.alpha());
        let Some((_, members)) = shared
            .along_alpha
            .as_ref()
            .filter(|(alpha, _)| Some(*alpha) == here)
        else {
            return number;
        };
        let tracks = tracks_of(reg.attractors(), members);
        let mut next = members.iter().map(|m| m.track + 1).max().unwrap_or(0);
        for id in reg.ranked() {
            number[id] = match tracks[id] {
                Some(t) => t + 1,
                None => {
                    next += 1;
                    next
                }
            };
        }
        number
    }

    fn title(&self, shared: &Shared) -> String {
        let head = " Basins t̂0×w0";
        let Some(b) = &self.view.picture else {
            return format!("{head} ");
        };
        let n = b.registry().attractors().len();
        let state = self.view.progress(b, shared);
        format!(
            "{head} · {n} found · {state}{} ",
            super::manifold_overlay::title_note(shared)
        )
    }
}

impl Component for BasinsPanel {
    type Msg = JobMsg<BasinChunk>;

    fn shown(&self) -> bool {
        self.view.shown
    }

    /// Size the grid to the pane: one start per column, two per row. A new size
    /// restarts the picture (if shown).
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        self.view.set_plot(plot_rect(pane), Self::TARGET, shared);
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action == Action::ToggleGlobal {
            // The attractors along α were just shown: their cursor's α picture here.
            if !self.view.shown {
                self.view.toggle(Self::TARGET, shared);
            }
            return true;
        }
        if action != Action::ToggleBasins {
            return false;
        }
        self.view.toggle(Self::TARGET, shared);
        if self.view.shown {
            shared.say(
                "basins: which attractor each start (t̂0, w0) ends on; the key again shows the phase plot",
                false,
            );
        }
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if self.view.shown && id.touches() == Touch::System {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if self.view.stop_if_hidden(Self::TARGET, workers) {
            return;
        }
        let (nx, ny) = self.view.grid();
        let spec = BasinSpec {
            nx: nx.max(1),
            ny: ny.max(1),
            ..BasinSpec::new(shared.system())
        };
        self.view.run(spec, Self::ADDRESS, workers);
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        self.view.receive(gen, msg, shared);
    }

    fn busy(&self) -> bool {
        self.view.busy()
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let block = panel(app, self.title(app), false);
        let inner = block.inner(area);
        block.render(area, buf);
        if self.view.draw_error("Basins", app, inner, buf) {
            return;
        }
        let (Some(b), Some(spec)) = (&self.view.picture, &self.view.spec) else {
            return;
        };
        let (picture, legend) = split(inner);
        let axes = Axes {
            x: Range::new(0.0, 1.0),
            y: Range::new(0.0, spec.w_max),
            x_name: "t̂0",
            y_name: "w0",
        };
        let plot = draw_axes(picture, buf, axes, LABEL_W, &app.theme);
        let reg = b.registry();
        let number = self.numbers(app, reg);
        let colour = app.theme.attractor_color(0).is_some();
        let halves = colour
            && draw_halves(plot, b.grid(), buf, |i, j| {
                b.preview_label(i, j)
                    .and_then(|l| self.color(app, l, &number))
            });
        if !halves {
            let cells = basin_map::cells(b, plot.width as usize, plot.height as usize);
            for (r, line) in cells.iter().enumerate() {
                for (c, l) in line.iter().enumerate() {
                    if let Some(id) = l {
                        let n = number[*id as usize];
                        buf.set_string(
                            plot.x + c as u16,
                            plot.y + r as u16,
                            texture_in(app.marker, n).to_string(),
                            app.theme.attractor(n - 1),
                        );
                    }
                }
            }
        }
        // The saddle's manifolds (when on), in (t̂0, w0 = v − f'(t̂0)).
        super::manifold_overlay::draw(app, buf, |t, v| {
            let w = v - spec.sys.df(t);
            if !(0.0..spec.w_max).contains(&w) || plot.width == 0 || plot.height == 0 {
                return None;
            }
            let c = ((t * plot.width as f64) as u16).min(plot.width - 1);
            let r = (((1.0 - w / spec.w_max) * plot.height as f64) as u16).min(plot.height - 1);
            Some((plot.x + c, plot.y + r))
        });
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
                        Style::new()
                            .fg(self.color(app, id as u32, &number).unwrap_or(Color::Reset)),
                    )
                } else {
                    Span::styled(
                        format!("{0}{0}", texture_in(app.marker, n)),
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
