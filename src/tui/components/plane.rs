//! The plane view: a two-parameter map in the diagram's place (the plane key switches),
//! α across and D (an fd:D table) or r (any other table) up, every pixel coloured by
//! the class of its orbit as the engine's plane job streams it coarse to fine (a pixel
//! not yet computed shows the coarser one whose block it lies in), with the analytic
//! curves over it (α_birth `B`, α_PD `P`, border collision `C`) and, switched on with
//! their key, the two-parameter curves of every branch ([`super::plane_curves`]: `•`
//! period doubling, `~` fold, `×` border collision, `¦` grazing, `◉` codimension two), axes with
//! tick labels,
//! the legend in the bottom border and a cursor. Moving the cursor moves the
//! application's α and D (or r), so the phase plot, stability and bounce panels follow;
//! Enter keeps that point and brings the diagram back, sweeping α there.
//!
//! Pixels: one per column and two per row; with colour each cell is an upper and a
//! lower half, without colour each cell shows its class's glyph (sparse to dense, as
//! `plane --format braille`). The plane runs at the diagram's α window (α's default
//! window when another parameter is swept), D ∈ [0, 1] or r ∈ [0.5, 0.95], with the
//! diagram's transient up to the plane's default (shown in the title), started next to
//! the (1, 1) solution. The job, its progress and
//! the halves are [`super::grid_picture`]'s; the spec, the classes' colours and glyphs,
//! the curves, the legend and the cursor are this panel's.

use super::grid_picture::{draw_halves, GridPicture};
use super::{is_focused, panel, Component, Effect, JobMsg, Registered, Shared, Target, Workers};
use crate::output::classes::{of_pixel, Class};
use crate::output::hitgrid::Range;
use crate::output::plane_map::{self, glyph, Cell, CURVE_MARKS};
use crate::tui::keymap::Action;
use crate::tui::layout::{plot_area_within, Slot};
use crate::tui::params::{default_window, ParamId, Params};
use crate::tui::plot::{draw_axes, Axes};
use bouncemap_engine::jobs::grid::Axis;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::plane::{curves, Curves, Plane, PlaneChunk, PlaneSpec};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;

const LABEL_W: u16 = 6;

/// The plane view.
#[derive(Default)]
pub struct PlanePanel {
    /// The picture, its job and whether it is shown (in place of the diagram).
    pub view: GridPicture<Plane>,
    /// The analytic curves of the plane shown.
    pub curves: Option<Curves>,
    /// Seconds from the start to the first complete coarse picture.
    pub first_picture: Option<f64>,
    /// The cursor's pixel (i, j), j = 0 at the bottom.
    pub cursor: (usize, usize),
}

/// The parameters the plane's vertical axis can be, for `table`: r and the table
/// family's own (F_D's D, a table file's).
pub fn vertical_params(table: &bouncemap_engine::Table) -> Vec<SweepParam> {
    let mut all: Vec<SweepParam> = SweepParam::all(table)
        .into_iter()
        .filter(|p| *p != SweepParam::Alpha)
        .collect();
    // The family's parameters first: the default is its first one.
    all.sort_by_key(|p| !p.is_table());
    all
}

/// The plane the current parameters ask for on a `grid`: α over the diagram's α window,
/// `y` up if the table has it, else the table family's first parameter (F_D's D) or r.
/// The current α, D or r are not part of it (they are the cursor).
pub fn plane_spec(params: &Params, grid: (usize, usize), y: Option<SweepParam>) -> PlaneSpec {
    let (alo, ahi) = if params.param == SweepParam::Alpha {
        (params.lo, params.hi)
    } else {
        default_window(SweepParam::Alpha, &params.table, &params.table())
    };
    let x = Axis {
        param: SweepParam::Alpha,
        lo: alo,
        hi: ahi,
        n: grid.0.max(1),
    };
    let table = params.table();
    let choices = vertical_params(&table);
    let param = y
        .filter(|p| choices.contains(p))
        .or(choices.first().copied())
        .unwrap_or(SweepParam::R);
    let (lo, hi) = default_window(param, &params.table, &table);
    // The axis's parameter at its window's start: the plane does not depend on the
    // application's own value of it (that is the cursor).
    let table = param.table(&table, lo).unwrap_or(table);
    let y = Axis {
        param,
        lo,
        hi,
        n: grid.1.max(1),
    };
    let mut spec = PlaneSpec::new(table, x, y, alo, params.r);
    // At most the plane's default transient: a preset's paper-length transient (5·10⁶)
    // over every pixel would take minutes; the title says which transient is used.
    spec.transient = params
        .transient
        .min(bouncemap_engine::plane::DEFAULT_TRANSIENT);
    spec
}

impl PlanePanel {
    /// The plane the current parameters ask for at the pane's size.
    pub fn spec_for(&self, shared: &Shared) -> PlaneSpec {
        plane_spec(&shared.params, self.view.grid(), shared.plane_y)
    }

    /// The cursor at the application's current α and D (or r).
    pub fn place_cursor(&mut self, shared: &Shared) {
        if let Some(s) = &self.view.spec {
            let y = shared.params.value(s.y.param).unwrap_or(s.y.lo);
            self.cursor = (s.x.pixel_of(shared.params.alpha), s.y.pixel_of(y));
        }
    }

    /// Move the cursor by (di, dj) pixels and the application's α and D (or r) with it.
    fn move_cursor(&mut self, di: i64, dj: i64, shared: &mut Shared) {
        let Some(s) = &self.view.spec else { return };
        let i = (self.cursor.0 as i64 + di).clamp(0, s.x.n as i64 - 1) as usize;
        let j = (self.cursor.1 as i64 + dj).clamp(0, s.y.n as i64 - 1) as usize;
        self.cursor = (i, j);
        // Rounded to 6 decimals (the parameters panel's precision): the same pixel.
        let round = |x: f64| (x * 1e6).round() / 1e6;
        let (alpha, y) = (round(s.x.value(i)), round(s.y.value(j)));
        let Some(yid) = shared.params.row_of(s.y.param) else {
            return;
        };
        let before = shared.params.clone();
        let r = shared
            .params
            .set_text(ParamId::Alpha, &format!("{alpha}"))
            .and_then(|_| shared.params.set_text(yid, &format!("{y}")));
        match r {
            Ok(()) => {
                if shared.params != before {
                    shared.changed.push(ParamId::Alpha);
                    shared.changed.push(yid);
                }
            }
            Err(e) => {
                shared.params = before;
                shared.say(e, true);
            }
        }
    }

    fn title(&self, shared: &Shared) -> String {
        let Some(s) = &self.view.spec else {
            return " Plane ".into();
        };
        let head = format!(
            " Plane α×{} T={}",
            Params::symbol(s.y.param),
            crate::tui::params::fmt_num(s.transient as f64)
        );
        let Some(p) = &self.view.picture else {
            return format!("{head} ");
        };
        let state = self.view.progress(p, shared);
        let (i, j) = self.cursor;
        let here = match p.preview(i, j) {
            Some(px) => of_pixel(px).map_or("no landing", Class::describe),
            None => "…",
        };
        format!(
            "{head} · {state} · α {:.5} {} {:.4}: {here} ",
            s.x.value(i),
            Params::symbol(s.y.param),
            s.y.value(j)
        )
    }

    /// The legend for the bottom border.
    fn legend(&self, shared: &Shared) -> Line<'static> {
        let mut spans = vec![Span::raw(" ")];
        for c in Class::ALL {
            spans.push(Span::styled(glyph(c).to_string(), shared.theme.class(c)));
            spans.push(Span::raw(format!("{} ", c.label())));
        }
        for (m, name) in CURVE_MARKS {
            let short = name.split(' ').next().unwrap_or(name);
            spans.push(Span::styled(m.to_string(), curve_style()));
            spans.push(Span::raw(format!("{short} ")));
        }
        if shared.show_plane_curves {
            match &shared.plane_curves {
                Some(Ok(_)) => {
                    for (m, name) in [("•", "PD"), ("~", "F"), ("×", "BC"), ("◉", "codim2")] {
                        spans.push(Span::styled(m.to_string(), curve_style()));
                        spans.push(Span::raw(format!("{name} ")));
                    }
                }
                Some(Err(_)) => spans.push(Span::raw("curves: none ")),
                None => spans.push(Span::raw("curves… ")),
            }
        }
        Line::from(spans)
    }
}

fn curve_style() -> Style {
    Style::new().add_modifier(Modifier::BOLD)
}

impl Component for PlanePanel {
    type Msg = JobMsg<PlaneChunk>;

    fn shown(&self) -> bool {
        self.view.shown
    }

    fn focusable(&self) -> bool {
        true
    }

    /// Size the grid to the pane: one pixel per column, two per row. A new size restarts
    /// the plane (if shown).
    fn set_pane(&mut self, pane: Rect, shared: &mut Shared) {
        self.view
            .set_plot(plot_area_within(pane, LABEL_W), Self::TARGET, shared);
    }

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action == Action::TogglePlane {
            self.view.toggle(Self::TARGET, shared);
            if self.view.shown {
                shared.focus = Slot::Diagram;
                shared.say(
                    "plane: arrows move α and D (or r) for every panel; Enter sweeps α there; the key again shows the diagram",
                    false,
                );
            }
            return true;
        }
        if action == Action::PlaneCurves && !self.view.shown {
            // The curves are drawn over the plane only: say so rather than switch
            // something that does not show.
            let (plane, curves) = (
                shared.keymap.hint(Action::TogglePlane),
                shared.keymap.hint(Action::PlaneCurves),
            );
            shared.say(
                format!("{curves}: the two-parameter curves are drawn over the plane view: {plane} shows it, then {curves}"),
                false,
            );
            return true;
        }
        if !self.view.shown || shared.focus != Slot::Diagram {
            return false;
        }
        match action {
            Action::Left => self.move_cursor(-4, 0, shared),
            Action::Right => self.move_cursor(4, 0, shared),
            Action::FineLeft => self.move_cursor(-1, 0, shared),
            Action::FineRight => self.move_cursor(1, 0, shared),
            Action::Up => self.move_cursor(0, 1, shared),
            Action::Down => self.move_cursor(0, -1, shared),
            Action::Enter => {
                // The point is already the application's; the diagram sweeps α there.
                let before = shared.params.clone();
                let r = if shared.params.param == SweepParam::Alpha {
                    Ok(())
                } else {
                    shared.params.set_param(SweepParam::Alpha)
                };
                shared.after_change(ParamId::Sweep, r, &before);
                self.view.shown = false;
                shared.effect(Effect::Start(Self::TARGET));
                shared.effect(Effect::Start(Target::Diagram));
                shared.say("plane: the diagram sweeps α at the point chosen", false);
            }
            Action::ToggleAxis => {
                // The next vertical parameter: r and the family's own, in turn.
                let table = shared.params.table();
                let choices = vertical_params(&table);
                let now = self.view.spec.as_ref().map(|s| s.y.param);
                let at = choices.iter().position(|p| Some(*p) == now);
                let next = choices[at.map_or(0, |i| (i + 1) % choices.len())];
                shared.plane_y = Some(next);
                shared.effect(Effect::Start(Self::TARGET));
                if shared.show_plane_curves {
                    shared.effect(Effect::Start(Target::PlaneCurves));
                }
                shared.say(
                    format!("plane: {} up (t: the next parameter)", next.as_str()),
                    false,
                );
            }
            // The diagram's other keys do nothing while the plane is shown.
            Action::ZoomIn
            | Action::ZoomOut
            | Action::ZoomBack
            | Action::MarkWindow
            | Action::Colouring
            | Action::AllAttractors => {}
            _ => return false,
        }
        true
    }

    fn changed(&mut self, _id: ParamId, shared: &mut Shared) {
        if !self.view.shown {
            return;
        }
        let next = self.spec_for(shared);
        if self.view.spec.as_ref() != Some(&next) {
            shared.effect(Effect::Start(Self::TARGET));
        } else {
            self.place_cursor(shared);
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if self.view.stop_if_hidden(Self::TARGET, workers) {
            return;
        }
        let spec = self.spec_for(shared);
        let complete = self.view.picture.as_ref().is_some_and(Plane::complete);
        if self.view.spec.as_ref() == Some(&spec) && (complete || !self.view.done) {
            // The same plane, complete or still filling in: keep it.
            self.place_cursor(shared);
            return;
        }
        if self.view.run(spec, Self::ADDRESS, workers) {
            self.curves = self.view.spec.as_ref().and_then(curves);
            self.place_cursor(shared);
            self.first_picture = None;
        }
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        let pass = self.view.receive(gen, msg, shared);
        // The first pass done: every pixel shows its coarse block.
        if pass.is_some_and(|p| p > 0) && self.first_picture.is_none() {
            self.first_picture = self.view.started.map(|s| s.elapsed().as_secs_f64());
        }
    }

    fn busy(&self) -> bool {
        self.view.busy()
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        let focused = is_focused(app, Slot::Diagram);
        let block = panel(app, self.title(app), focused).title_bottom(self.legend(app));
        let inner = block.inner(area);
        block.render(area, buf);
        if self.view.draw_error("Plane", app, inner, buf) {
            return;
        }
        let (Some(p), Some(spec)) = (&self.view.picture, &self.view.spec) else {
            return;
        };
        let axes = Axes {
            x: Range::new(spec.x.lo, spec.x.hi),
            y: Range::new(spec.y.lo, spec.y.hi),
            x_name: &crate::tui::params::Params::symbol(spec.x.param),
            y_name: &crate::tui::params::Params::symbol(spec.y.param),
        };
        let plot = draw_axes(inner, buf, axes, LABEL_W, &app.theme);
        let (nx, ny) = p.size();
        let colour = app.theme.class(Class::Period1).fg.is_some();
        let fg = |c: Option<Class>| c.and_then(|c| app.theme.class(c).fg);
        let halves = colour
            && draw_halves(plot, (nx, ny), buf, |i, j| {
                p.preview(i, j).map(of_pixel).and_then(fg)
            });
        if !halves {
            let cells = plane_map::cells(spec, p, None, plot.width as usize, plot.height as usize);
            for (r, line) in cells.iter().enumerate() {
                for (c, cell) in line.iter().enumerate() {
                    if let Cell::Class(Some(k)) = cell {
                        buf.set_string(
                            plot.x + c as u16,
                            plot.y + r as u16,
                            glyph(*k).to_string(),
                            app.theme.class(*k),
                        );
                    } else if *cell != Cell::Empty {
                        buf.set_string(
                            plot.x + c as u16,
                            plot.y + r as u16,
                            cell.glyph().to_string(),
                            app.theme.dim(),
                        );
                    }
                }
            }
        }
        // The curves over the picture, one mark per row of cells.
        if let Some(cv) = &self.curves {
            let marks =
                plane_map::cells(spec, p, Some(cv), plot.width as usize, plot.height as usize);
            for (r, line) in marks.iter().enumerate() {
                for (c, cell) in line.iter().enumerate() {
                    if let Cell::Curve(n, _) = cell {
                        let x = plot.x + c as u16;
                        let y = plot.y + r as u16;
                        let style = match buf.cell((x, y)) {
                            Some(under) => {
                                Style::new().bg(under.fg).fg(ratatui::style::Color::Black)
                            }
                            None => Style::new(),
                        };
                        let style = if colour { style } else { curve_style() };
                        buf.set_string(
                            x,
                            y,
                            CURVE_MARKS[*n].0.to_string(),
                            style.add_modifier(Modifier::BOLD),
                        );
                    }
                }
            }
        }
        // The two-parameter curves, when on: a mark per cell a curve passes through.
        if let (true, Some(Ok(c))) = (app.show_plane_curves, &app.plane_curves) {
            let (w, h) = (plot.width as f64, plot.height as f64);
            let cell = |a: f64, q: f64| -> Option<(u16, u16)> {
                let fx = (a - spec.x.lo) / (spec.x.hi - spec.x.lo);
                let fy = (q - spec.y.lo) / (spec.y.hi - spec.y.lo);
                if !((0.0..=1.0).contains(&fx) && (0.0..=1.0).contains(&fy)) {
                    return None;
                }
                let col = ((fx * w) as u16).min(plot.width.saturating_sub(1));
                let row = plot.height - 1 - ((fy * h) as u16).min(plot.height.saturating_sub(1));
                Some((plot.x + col, plot.y + row))
            };
            let mut mark = |x: u16, y: u16, m: &str| {
                let style = match (colour, buf.cell((x, y))) {
                    (true, Some(under)) => {
                        Style::new().bg(under.bg).fg(ratatui::style::Color::Black)
                    }
                    _ => Style::new(),
                };
                buf.set_string(x, y, m, style.add_modifier(Modifier::BOLD));
            };
            for cv in &c.curves {
                let m = plane_map::curve_mark(&cv.kind).to_string();
                for seg in cv.points.windows(2) {
                    let (a, b) = (&seg[0], &seg[1]);
                    // Enough samples that no cell along the segment is skipped.
                    let span_x = ((b.alpha - a.alpha) / (spec.x.hi - spec.x.lo) * w).abs();
                    let span_y = ((b.p - a.p) / (spec.y.hi - spec.y.lo) * h).abs();
                    let n = (2.0 * span_x.max(span_y)).ceil().clamp(1.0, 4000.0) as usize;
                    for i in 0..=n {
                        let t = i as f64 / n as f64;
                        if let Some((x, y)) =
                            cell(a.alpha + t * (b.alpha - a.alpha), a.p + t * (b.p - a.p))
                        {
                            mark(x, y, &m);
                        }
                    }
                }
            }
            for p2 in &c.codim2 {
                if let Some((x, y)) = cell(p2.alpha, p2.p) {
                    mark(x, y, "◉");
                }
            }
        }
        // The cursor: the cell holding its pixel.
        let (i, j) = self.cursor;
        if i < nx && j < ny && plot.width > 0 && plot.height > 0 {
            let c = (i * plot.width as usize / nx.max(1)) as u16;
            let r = plot.height - 1 - (j * plot.height as usize / ny.max(1)) as u16;
            buf.set_string(plot.x + c, plot.y + r, "╋", app.theme.cursor());
        }
    }
}
