//! What the panels share: the parameters, the focus, the overlay, the message line,
//! pause, the orbit analysis (which the diagram, the phase plot and the stability panel
//! all mark), and the effects queued for the runtime. Panels read and change it; only
//! [`crate::tui::app::App`] routes between them.

use super::analysis::OrbitInfo;
use super::keymap::Keymap;
use super::params::{ParamId, Params};
use super::theme::Theme;
use super::workers::Target;
use crate::output::hitgrid::Marker;
use bouncemap_engine::System;

/// Which panel takes the arrow keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Focus {
    Params,
    Diagram,
}

/// An overlay drawn over the panels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlay {
    None,
    Help,
    Legend,
    /// The table view: F, F′, F″ over one period.
    Table,
    Presets {
        selected: usize,
    },
}

/// Work the runtime must start or do after an action.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    /// (Re)start a target's background work for the current parameters.
    Start(Target),
    Pause(bool),
    Export,
    /// Stop the process (as Ctrl-Z does in any full-screen program).
    Suspend,
}

/// What every panel may read and change.
pub struct Shared {
    pub params: Params,
    pub keymap: Keymap,
    pub theme: Theme,
    pub marker: Marker,
    pub fps: u32,
    pub mouse: bool,
    pub focus: Focus,
    pub overlay: Overlay,
    /// A one-line message (refusal, export result); true if it is an error.
    pub message: Option<(String, bool)>,
    pub paused: bool,
    pub quit: bool,
    pub dirty: bool,
    /// First line shown of the help or legend overlay (when it scrolls).
    pub help_scroll: usize,
    /// The file name being typed for an export (None: not typing one).
    pub export_name: Option<String>,
    /// The name an export was asked for, until the runtime writes it.
    pub export_pending: Option<String>,
    /// Whether the export being named also writes the view as figures (`E`).
    pub export_view: bool,
    /// The orbit analysis for the current parameters (None while it computes).
    pub orbits: Option<Result<OrbitInfo, String>>,
    /// (t̂, v) of the state the bounce panel has stepped to (None before a step).
    pub stepped: Option<(f64, f64)>,
    /// The continued branches of the current α window (None while they compute, or
    /// when the diagram sweeps r or D).
    pub branches: Option<Result<super::skeleton::Skeleton, String>>,
    /// The diagram's cursor (swept value, height) while the diagram has the focus.
    pub cursor: Option<(f64, f64)>,
    /// The continued branch nearest the cursor (its index) and its cycle at the
    /// cursor's α.
    pub under_cursor: Option<(usize, bouncemap_engine::orbits::periodic::CyclePoint)>,
    pub(super) effects: Vec<Effect>,
    /// Rows changed by the action being handled, to announce to every panel.
    pub(super) changed: Vec<ParamId>,
}

impl Shared {
    /// The shared state for `params`, nothing open, nothing queued.
    pub fn new(params: Params, keymap: Keymap, theme: Theme, marker: Marker, fps: u32) -> Shared {
        Shared {
            params,
            keymap,
            theme,
            marker,
            fps,
            mouse: false,
            focus: Focus::Params,
            overlay: Overlay::None,
            message: None,
            paused: false,
            quit: false,
            dirty: true,
            help_scroll: 0,
            export_name: None,
            export_pending: None,
            export_view: false,
            orbits: None,
            stepped: None,
            branches: None,
            cursor: None,
            under_cursor: None,
            effects: Vec::new(),
            changed: Vec::new(),
        }
    }

    /// Queue an effect for the runtime (once).
    pub fn effect(&mut self, e: Effect) {
        if !self.effects.contains(&e) {
            self.effects.push(e);
        }
    }

    /// A message for the user; `error` shows it as a refusal.
    pub fn say(&mut self, text: impl Into<String>, error: bool) {
        self.message = Some((text.into(), error));
    }

    /// The outcome of changing row `id` (its result, and the parameters before):
    /// a refusal becomes the message; a real change is announced to every panel.
    pub fn after_change(&mut self, id: ParamId, result: Result<(), String>, before: &Params) {
        match result {
            Err(e) => self.say(e, true),
            Ok(()) => {
                self.message = None;
                if self.params != *before {
                    self.changed.push(id);
                }
            }
        }
    }

    /// The current system.
    pub fn system(&self) -> System {
        self.params.system()
    }
}
