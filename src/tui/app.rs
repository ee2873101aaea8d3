//! The application: what the panels share ([`Shared`]) and the panels themselves
//! ([`Panels`], from the registry in [`crate::tui::components`]), with what is the
//! application's own: overlays (help, legend, table view, presets), the export prompt,
//! focus moves, quitting. Actions, parameter changes, starts and worker messages are
//! routed through the registry; the diagram is named only for its cursor (the branch
//! under it), the mouse's zoom and the zoom stack a preset clears. Pure: no terminal,
//! no threads. Handling an action mutates the state and queues [`Effect`]s (start a
//! panel's background work, pause, export) that the runtime carries out, so every
//! key's effect can be tested directly.

use super::components::presets::PresetPicker;
use super::components::shared::LOG_LEN;
use super::components::{
    help, legend, messages, status, table_view, too_small, Msg, Panels, Workers,
};
pub use super::components::{Effect, Overlay, Shared, Target};
use super::export::{free_name, ExportSizes};
use super::keymap::{Action, Keymap};
use super::layout::{layout, left_out_note, narrow, Slot, BOTTOM, FULL_W};
use super::params::{ParamId, Params};
use super::theme::Theme;
use crate::output::hitgrid::Marker;
use ratatui::layout::Rect;
use ratatui::Frame;

/// Everything on screen.
pub struct App {
    /// What the panels share.
    pub shared: Shared,
    /// One of each panel.
    pub panels: Panels,
    /// The preset picker's list (the overlay's state is [`Overlay::Presets`]).
    pub presets: PresetPicker,
    /// Frames per second at most.
    pub fps: u32,
    /// Whether the mouse is captured.
    pub mouse: bool,
    pub quit: bool,
    /// First line shown of the help or legend overlay (when it scrolls).
    pub help_scroll: usize,
    /// The file name being typed for an export (None: not typing one).
    pub export_name: Option<String>,
    /// The name an export was asked for, until the runtime writes it.
    pub export_pending: Option<String>,
    /// Whether the export being named also writes the view as figures (`E`).
    pub export_view: bool,
    /// The resolution of `E`'s plane and basins figures (`[export]` in the config).
    pub export_sizes: ExportSizes,
}

impl App {
    /// The application for `params`; every panel's background work is queued to start.
    pub fn new(params: Params, keymap: Keymap, theme: Theme, marker: Marker, fps: u32) -> App {
        let mut shared = Shared::new(params, keymap, theme, marker);
        let panels = Panels::new(&shared);
        for t in Target::ALL {
            shared.effect(Effect::Start(*t));
        }
        App {
            shared,
            panels,
            presets: PresetPicker::new(),
            fps,
            mouse: false,
            quit: false,
            help_scroll: 0,
            export_name: None,
            export_pending: None,
            export_view: false,
            export_sizes: ExportSizes::default(),
        }
    }

    /// Effects queued since the last call.
    pub fn take_effects(&mut self) -> Vec<Effect> {
        std::mem::take(&mut self.shared.effects)
    }

    /// The selected parameter row.
    pub fn selected_param(&self) -> ParamId {
        self.panels
            .parameters
            .selected_param_in(&self.shared.params.rows())
    }

    // ---------------------------------------------------------------- actions

    /// Apply one action.
    pub fn handle(&mut self, action: Action) {
        self.shared.dirty = true;
        // A message describes the action before; the next one replaces or clears it, so
        // the status line never describes a view that is gone.
        self.shared.message = None;
        if action == Action::Quit {
            self.quit = true;
            return;
        }
        match self.shared.overlay {
            Overlay::Help | Overlay::Legend | Overlay::Messages => {
                match action {
                    Action::Up => self.help_scroll = self.help_scroll.saturating_sub(1),
                    Action::Down => self.help_scroll = (self.help_scroll + 1).min(LOG_LEN * 4),
                    Action::Help
                    | Action::Legend
                    | Action::Messages
                    | Action::Cancel
                    | Action::Enter => self.shared.overlay = Overlay::None,
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
                self.help_scroll = 0;
            }
            Action::Legend => {
                self.shared.overlay = Overlay::Legend;
                self.help_scroll = 0;
            }
            Action::Messages => {
                self.shared.overlay = Overlay::Messages;
                // The newest messages are at the end: start there.
                self.help_scroll = LOG_LEN * 4;
            }
            Action::CyclePanels => self.cycle_panels(),
            Action::TableView => self.shared.overlay = Overlay::Table,
            Action::Presets => self.shared.overlay = Overlay::Presets { selected: 0 },
            Action::Export | Action::ExportView => {
                let dir = std::env::current_dir().unwrap_or_else(|_| ".".into());
                self.export_view = action == Action::ExportView;
                self.export_name = Some(free_name(&dir, self.export_view));
            }
            Action::Suspend => self.shared.effect(Effect::Suspend),
            Action::NextPanel | Action::PrevPanel => {
                self.move_focus(action == Action::NextPanel);
            }
            _ => {
                if action == Action::Cancel {
                    self.shared.message = None;
                }
                self.panels.handle(action, &mut self.shared);
            }
        }
        self.announce();
    }

    /// Under [`FULL_W`] columns: leave out the next bottom panel instead (the one left
    /// out comes back), and say which.
    fn cycle_panels(&mut self) {
        let key = self.shared.keymap.hint(Action::CyclePanels);
        if !self.shared.narrow {
            self.shared.say(
                format!("{key}: all three bottom panels fit at this width (it cycles them under {FULL_W} columns)"),
                false,
            );
            return;
        }
        let i = BOTTOM
            .iter()
            .position(|s| *s == self.shared.left_out)
            .unwrap_or(0);
        self.shared.left_out = BOTTOM[(i + 1) % BOTTOM.len()];
        let note = left_out_note(self.shared.left_out, &key);
        self.shared.say(note, false);
    }

    /// Move the focus to the next (or previous) slot of the focus ring.
    fn move_focus(&mut self, next: bool) {
        let ring = self.panels.focus_ring();
        if let Some(&first) = ring.first() {
            let n = ring.len();
            self.shared.focus = match ring.iter().position(|s| *s == self.shared.focus) {
                Some(i) if next => ring[(i + 1) % n],
                Some(i) => ring[(i + n - 1) % n],
                None => first,
            };
        }
        self.panels.focus_moved();
    }

    /// A typed key while editing a parameter or an export's file name (Enter commits,
    /// Esc cancels; [`super::line_edit`]).
    pub fn edit_key(&mut self, key: impl Into<crossterm::event::KeyEvent>) {
        use super::line_edit::{edit, Edit};
        let key = key.into();
        self.shared.dirty = true;
        if let Some(name) = self.export_name.as_mut() {
            match edit(name, key, 200) {
                Edit::Typing => {}
                Edit::Cancel => self.export_name = None,
                Edit::Commit => {
                    self.export_pending = self.export_name.take();
                    self.shared.effect(Effect::Export);
                }
            }
            return;
        }
        self.panels.parameters.edit_key(key, &mut self.shared);
        self.announce();
    }

    /// Whether a parameter or a file name is being typed.
    pub fn editing(&self) -> bool {
        self.panels.parameters.editing.is_some() || self.export_name.is_some()
    }

    /// Tell every panel about the rows changed by the last action.
    fn announce(&mut self) {
        self.refresh_under_cursor();
        let changed = std::mem::take(&mut self.shared.changed);
        for id in changed {
            self.panels.changed(id, &mut self.shared);
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
                self.panels.diagram.zoom_stack.clear();
                self.shared.after_change(ParamId::Table, Ok(()), &before);
                self.shared.say(format!("preset: {name}"), false);
            }
            Err(e) => self.shared.say(format!("preset {name}: {e}"), true),
        }
    }

    /// Zoom the diagram to [lo, hi] (the mouse's drag).
    pub fn zoom_to(&mut self, lo: f64, hi: f64) {
        self.panels.diagram.zoom_to(lo, hi, &mut self.shared);
        self.announce();
    }

    /// Set the swept parameter to the diagram's cursor (the mouse's click).
    pub fn set_value_to_cursor(&mut self) {
        self.panels.diagram.set_value_to_cursor(&mut self.shared);
        self.announce();
    }

    // ---------------------------------------------------------------- work

    /// Start panel `t`'s background work (the runtime carries out `Effect::Start`).
    pub fn start(&mut self, t: Target, workers: &Workers) {
        self.panels.start(t, &mut self.shared, workers);
        self.shared.dirty = true;
    }

    /// Take one worker message.
    pub fn receive(&mut self, msg: Msg) {
        let to = msg.target();
        self.panels.receive(msg, &mut self.shared);
        if to == Target::Branches {
            self.refresh_under_cursor();
        }
    }

    /// The continued branch under the diagram's cursor (its cycle at the cursor's α, by
    /// Newton: microseconds), for the stability panel, while the diagram itself (not a
    /// panel in its place) has the focus.
    fn refresh_under_cursor(&mut self) {
        use super::components::diagram::Axis;
        let d = &self.panels.diagram;
        let focused = self.shared.focus == Slot::Diagram
            && self.panels.in_slot(Slot::Diagram) == Some(Target::Diagram);
        // At the value the readout describes (the nearest computed one), so the
        // screen speaks of one α.
        let at = super::components::diagram::readout::nearest(d).map_or(d.cursor, |r| r.value);
        self.shared.under_cursor = match &self.shared.branches {
            Some(Ok(sk)) if focused => sk.under(at, d.ycursor, d.axis == Axis::Velocity),
            _ => None,
        };
        self.shared.at_cursor = focused
            .then(|| super::components::diagram::readout::evidence(d, &self.shared))
            .flatten();
    }

    /// Whether any worker may still send something (the loop then polls more often).
    pub fn busy(&self) -> bool {
        !self.shared.paused && self.panels.busy()
    }

    // ---------------------------------------------------------------- layout

    /// Size the panels to the layout of a `w × h` screen (before sweeps ask for the
    /// diagram's width, and before drawing).
    pub fn set_size(&mut self, area: Rect) {
        let was = self.shared.narrow;
        self.shared.narrow = narrow(area.width);
        if self.shared.narrow && !was && layout(area, self.shared.left_out).is_some() {
            // Whatever a narrow screen leaves out is announced, with the key.
            let key = self.shared.keymap.hint(Action::CyclePanels);
            let note = left_out_note(self.shared.left_out, &key);
            self.shared.say(note, false);
        }
        if let Some(p) = layout(area, self.shared.left_out) {
            self.panels.set_panes(&p, &mut self.shared);
        }
    }

    /// Draw the whole screen (call [`Self::set_size`] first).
    pub fn draw(&self, frame: &mut Frame) {
        let area = frame.area();
        let buf = frame.buffer_mut();
        let s = &self.shared;
        let Some(p) = layout(area, s.left_out) else {
            too_small::draw(s, area, buf);
            return;
        };
        self.panels.draw(s, &p, buf);
        let computing = self.panels.computing(s);
        let note = super::export::prompt_note(self.export_view, &self.panels);
        let prompt = self.export_name.as_deref().map(|n| (n, note.as_str()));
        status::draw(s, prompt, &computing, p.status, buf);
        match s.overlay {
            Overlay::Help => help::draw(s, self.help_scroll, area, buf),
            Overlay::Legend => legend::draw(s, self.help_scroll, area, buf),
            Overlay::Messages => messages::draw(s, self.help_scroll, area, buf),
            Overlay::Table => table_view::draw(s, area, buf),
            Overlay::Presets { selected } => self.presets.draw(s, selected, area, buf),
            Overlay::None => {}
        }
    }
}
