//! The application: what the panels share ([`Shared`]) and one of each panel, with
//! the routing of actions, changes and worker messages between them. Pure: no terminal, no threads. Handling an action mutates the state and queues
//! [`Effect`]s (start a panel's background work, pause, export) that the runtime
//! carries out, so every key's effect can be tested directly.
//!
//! `App` dereferences to its [`Shared`] state (`app.params`, `app.focus`, ...).

use super::components::basins::BasinsPanel;
use super::components::bounce::Bounce;
use super::components::branches::Branches;
use super::components::diagram::Diagram;
use super::components::parameters::Parameters;
use super::components::phase_plot::PhasePlot;
use super::components::plane::PlanePanel;
use super::components::presets::PresetPicker;
use super::components::stability::Stability;
use super::components::{help, legend, status, table_view, too_small, Component, Target};
use super::keymap::{Action, Keymap};
use super::layout::{layout, Panes};
use super::params::{ParamId, Params};
pub use super::shared::{Effect, Focus, Overlay, Shared};
use super::theme::Theme;
use super::workers::{Msg, Workers};
use crate::output::hitgrid::Marker;
use ratatui::layout::Rect;
use ratatui::Frame;
use std::ops::{Deref, DerefMut};

/// Everything on screen.
pub struct App {
    pub shared: Shared,
    pub parameters: Parameters,
    pub diagram: Diagram,
    pub phase: PhasePlot,
    pub stability: Stability,
    pub bounce: Bounce,
    pub basins: BasinsPanel,
    pub plane: PlanePanel,
    pub branches: Branches,
    pub presets: PresetPicker,
}

impl Deref for App {
    type Target = Shared;
    fn deref(&self) -> &Shared {
        &self.shared
    }
}

impl DerefMut for App {
    fn deref_mut(&mut self) -> &mut Shared {
        &mut self.shared
    }
}

impl App {
    pub fn new(params: Params, keymap: Keymap, theme: Theme, marker: Marker, fps: u32) -> App {
        let shared = Shared::new(params, keymap, theme, marker, fps);
        let mut app = App {
            parameters: Parameters::new(),
            diagram: Diagram::new(&shared),
            phase: PhasePlot::new(marker),
            stability: Stability::default(),
            bounce: Bounce::new(&shared.params),
            basins: BasinsPanel::default(),
            plane: PlanePanel::default(),
            branches: Branches::default(),
            presets: PresetPicker::new(),
            shared,
        };
        for t in [
            Target::Orbits,
            Target::Phase,
            Target::Diagram,
            Target::Branches,
        ] {
            app.shared.effect(Effect::Start(t));
        }
        app
    }

    /// The shared state and every stateful panel, in routing order.
    fn parts(&mut self) -> (&mut Shared, [&mut dyn Component; 8]) {
        let App {
            shared,
            parameters,
            diagram,
            phase,
            stability,
            bounce,
            basins,
            plane,
            branches,
            ..
        } = self;
        // The plane before the diagram: while shown, it takes the diagram's keys.
        (
            shared,
            [
                parameters, plane, diagram, bounce, phase, stability, basins, branches,
            ],
        )
    }

    /// The shared state and the panel whose background work `t` is.
    fn part(&mut self, t: Target) -> (&mut Shared, &mut dyn Component) {
        let App {
            shared,
            diagram,
            phase,
            stability,
            basins,
            plane,
            branches,
            ..
        } = self;
        let c: &mut dyn Component = match t {
            Target::Diagram => diagram,
            Target::Phase => phase,
            Target::Orbits => stability,
            Target::Basins => basins,
            Target::Plane => plane,
            Target::Branches => branches,
        };
        (shared, c)
    }

    /// Effects queued since the last call.
    pub fn take_effects(&mut self) -> Vec<Effect> {
        std::mem::take(&mut self.shared.effects)
    }

    /// The selected parameter row.
    pub fn selected_param(&self) -> ParamId {
        self.parameters.selected_param()
    }

    // ---------------------------------------------------------------- actions

    /// Apply one action.
    pub fn handle(&mut self, action: Action) {
        self.shared.dirty = true;
        if action == Action::Quit {
            self.shared.quit = true;
            return;
        }
        match self.shared.overlay {
            Overlay::Help | Overlay::Legend => {
                match action {
                    Action::Up => {
                        self.shared.help_scroll = self.shared.help_scroll.saturating_sub(1)
                    }
                    Action::Down => self.shared.help_scroll = (self.shared.help_scroll + 1).min(60),
                    Action::Help | Action::Legend | Action::Cancel | Action::Enter => {
                        self.shared.overlay = Overlay::None
                    }
                    _ => {}
                }
                return;
            }
            Overlay::Table => {
                if matches!(
                    action,
                    Action::TableView | Action::Cancel | Action::Enter | Action::Help
                ) {
                    self.shared.overlay = Overlay::None;
                }
                if action == Action::Help {
                    self.shared.overlay = Overlay::Help;
                }
                return;
            }
            Overlay::Presets { selected } => {
                if let Some(i) = self.presets.handle(selected, action, &mut self.shared) {
                    self.load_preset(i);
                }
                self.announce();
                return;
            }
            Overlay::None => {}
        }
        match action {
            Action::Pause => {
                self.shared.paused = !self.shared.paused;
                let p = self.shared.paused;
                self.shared.effect(Effect::Pause(p));
            }
            Action::Help => {
                self.shared.overlay = Overlay::Help;
                self.shared.help_scroll = 0;
            }
            Action::Legend => {
                self.shared.overlay = Overlay::Legend;
                self.shared.help_scroll = 0;
            }
            Action::TableView => self.shared.overlay = Overlay::Table,
            Action::Presets => self.shared.overlay = Overlay::Presets { selected: 0 },
            Action::Export | Action::ExportView => {
                let dir = std::env::current_dir().unwrap_or_else(|_| ".".into());
                let view = action == Action::ExportView;
                let (prefix, exts): (&str, &[&str]) = if view {
                    (
                        "bouncemap-view",
                        &[
                            ".csv",
                            ".txt",
                            "-diagram.svg",
                            "-diagram.png",
                            "-phase.svg",
                            "-phase.png",
                        ],
                    )
                } else {
                    ("bouncemap-diagram", &[".csv", ".txt"])
                };
                self.shared.export_view = view;
                self.shared.export_name = Some(crate::output::sink::free_stem(&dir, prefix, exts));
            }
            Action::Suspend => self.shared.effect(Effect::Suspend),
            Action::NextPanel | Action::PrevPanel => {
                self.shared.focus = match self.shared.focus {
                    Focus::Params => Focus::Diagram,
                    Focus::Diagram => Focus::Params,
                };
                self.diagram.mark = None;
            }
            _ => {
                if action == Action::Cancel {
                    self.shared.message = None;
                }
                let (shared, panels) = self.parts();
                for c in panels {
                    if c.handle(action, shared) {
                        break;
                    }
                }
            }
        }
        self.announce();
    }

    /// A typed character while editing a parameter or an export's file name (Enter
    /// commits, Esc cancels).
    pub fn edit_key(&mut self, key: crossterm::event::KeyCode) {
        use crossterm::event::KeyCode;
        self.shared.dirty = true;
        if let Some(name) = self.shared.export_name.as_mut() {
            match key {
                KeyCode::Char(c) if name.chars().count() < 200 => name.push(c),
                KeyCode::Backspace => {
                    name.pop();
                }
                KeyCode::Esc => self.shared.export_name = None,
                KeyCode::Enter => {
                    self.shared.export_pending = self.shared.export_name.take();
                    self.shared.effect(Effect::Export);
                }
                _ => {}
            }
            return;
        }
        self.parameters.edit_key(key, &mut self.shared);
        self.announce();
    }

    /// Whether a parameter or a file name is being typed.
    pub fn editing(&self) -> bool {
        self.parameters.editing.is_some() || self.shared.export_name.is_some()
    }

    /// Tell every panel about the rows changed by the last action.
    fn announce(&mut self) {
        self.refresh_under_cursor();
        let changed = std::mem::take(&mut self.shared.changed);
        for id in changed {
            let (shared, panels) = self.parts();
            for c in panels {
                c.changed(id, shared);
            }
        }
    }

    /// Load preset `i`: its table, r, window, transient, keep, values and start, so the
    /// diagram runs exactly the sweep `bouncemap sweep --preset NAME` runs.
    fn load_preset(&mut self, i: usize) {
        let Some((name, p)) = self.presets.get(i).cloned() else {
            return;
        };
        let before = self.shared.params.clone();
        match self.shared.params.with_preset(&p) {
            Ok(next) => {
                self.shared.params = next;
                self.diagram.zoom_stack.clear();
                self.shared.after_change(ParamId::Table, Ok(()), &before);
                self.shared.say(format!("preset: {name}"), false);
            }
            Err(e) => self.shared.say(format!("preset {name}: {e}"), true),
        }
    }

    /// Zoom the diagram to [lo, hi] (the mouse's drag).
    pub fn zoom_to(&mut self, lo: f64, hi: f64) {
        self.diagram.zoom_to(lo, hi, &mut self.shared);
        self.announce();
    }

    /// Set the swept parameter to the diagram's cursor (the mouse's click).
    pub fn set_value_to_cursor(&mut self) {
        self.diagram.set_value_to_cursor(&mut self.shared);
        self.announce();
    }

    // ---------------------------------------------------------------- work

    /// Start a target's background work (the runtime carries out `Effect::Start`).
    pub fn start(&mut self, t: Target, workers: &Workers) {
        let (shared, c) = self.part(t);
        c.start(shared, workers);
        shared.dirty = true;
    }

    /// Take one worker message.
    pub fn receive(&mut self, msg: Msg) {
        let Msg { to, gen, body } = msg;
        let (shared, c) = self.part(to);
        c.receive(gen, body, shared);
        if to == Target::Branches {
            self.refresh_under_cursor();
        }
    }

    /// The diagram's cursor and the continued branch under it (its cycle at the
    /// cursor's α, by Newton: microseconds), for the stability panel.
    fn refresh_under_cursor(&mut self) {
        use super::components::diagram::Axis;
        // The plane view takes the diagram's place (and its keys): no diagram cursor.
        let focused = self.shared.focus == Focus::Diagram && !self.plane.shown;
        self.shared.cursor = focused.then_some((self.diagram.cursor, self.diagram.ycursor));
        self.shared.under_cursor = match (&self.shared.branches, self.shared.cursor) {
            (Some(Ok(sk)), Some((a, y))) => sk.under(a, y, self.diagram.axis == Axis::Velocity),
            _ => None,
        };
    }

    /// Whether any worker may still send something (the loop then polls more often).
    pub fn busy(&mut self) -> bool {
        let (shared, panels) = self.parts();
        !shared.paused && panels.iter().any(|c| c.busy())
    }

    // ---------------------------------------------------------------- layout

    /// Size the plot grids to the layout of a `w × h` screen (before sweeps ask for
    /// the diagram's width, and before drawing).
    pub fn set_size(&mut self, area: Rect) {
        if let Some(p) = layout(area) {
            self.diagram.set_pane(p.diagram, &mut self.shared);
            self.phase.set_pane(p.phase, &self.shared);
            self.basins.set_pane(p.phase, &mut self.shared);
            self.plane.set_pane(p.diagram, &mut self.shared);
        }
    }

    /// Draw the whole screen (call [`Self::set_size`] first).
    pub fn draw(&self, frame: &mut Frame) {
        let area = frame.area();
        let buf = frame.buffer_mut();
        let Some(p): Option<Panes> = layout(area) else {
            too_small::draw(&self.shared, area, buf);
            return;
        };
        let s = &self.shared;
        self.parameters.draw(s, p.params, buf);
        if self.plane.shown {
            self.plane.draw(s, p.diagram, buf);
        } else {
            self.diagram.draw(s, p.diagram, buf);
        }
        if self.basins.shown {
            self.basins.draw(s, p.phase, buf);
        } else {
            self.phase.draw(s, p.phase, buf);
        }
        self.stability.draw(s, p.stability, buf);
        self.bounce.draw(s, p.bounce, buf);
        status::draw(s, &self.diagram, &self.phase, p.status, buf);
        match s.overlay {
            Overlay::Help => help::draw(s, area, buf),
            Overlay::Legend => legend::draw(s, s.help_scroll, area, buf),
            Overlay::Table => table_view::draw(s, area, buf),
            Overlay::Presets { selected } => self.presets.draw(s, selected, area, buf),
            Overlay::None => {}
        }
    }
}
