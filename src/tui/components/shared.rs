//! What the panels share: the parameters, the key bindings and theme they draw with,
//! the focus, the overlay, the message line, pause, the results more than one panel
//! shows (the orbit analysis, the continued branches, the branch under the diagram's
//! cursor, the state the bounce panel stepped to), and the queues a panel writes to:
//! effects for the runtime and parameter changes to announce. Panels read and change it;
//! only [`crate::tui::app::App`] routes between them.

use super::Target;
use crate::output::hitgrid::Marker;
use crate::tui::analysis::OrbitInfo;
use crate::tui::keymap::Keymap;
use crate::tui::layout::Slot;
use crate::tui::params::{ParamId, Params};
use crate::tui::skeleton::Skeleton;
use crate::tui::theme::Theme;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::orbits::periodic::CyclePoint;
use bouncemap_engine::System;

/// An overlay drawn over the panels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlay {
    None,
    Help,
    Legend,
    /// Every message so far, in full.
    Messages,
    /// The table view: F, F′, F″ over one period.
    Table,
    Presets {
        selected: usize,
    },
}

/// Work the runtime must start or do after an action.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    /// (Re)start a panel's background work for the current parameters.
    Start(Target),
    Pause(bool),
    Export,
    /// Stop the process (as Ctrl-Z does in any full-screen program).
    Suspend,
}

/// Messages the log keeps.
pub const LOG_LEN: usize = 200;

/// What every panel may read and change.
pub struct Shared {
    pub params: Params,
    pub keymap: Keymap,
    pub theme: Theme,
    pub marker: Marker,
    /// The slot whose panel takes the arrow keys.
    pub focus: Slot,
    pub overlay: Overlay,
    /// A one-line message (refusal, export result); true if it is an error.
    pub message: Option<(String, bool)>,
    /// Every message so far (the latest [`LOG_LEN`]), for the messages overlay: the
    /// status line cuts a long one.
    pub log: std::collections::VecDeque<(String, bool)>,
    /// Under [`crate::tui::layout::FULL_W`] columns: the bottom panel left out.
    pub left_out: Slot,
    /// Whether the screen is narrow (one bottom panel left out).
    pub narrow: bool,
    pub paused: bool,
    /// Something changed on screen since the last frame.
    pub dirty: bool,
    /// The orbit analysis for the current parameters (None while it computes).
    pub orbits: Option<Result<OrbitInfo, String>>,
    /// (t̂, v) of the state the bounce panel has stepped to (None before a step).
    pub stepped: Option<(f64, f64)>,
    /// The continued branches of the current α window (None while they compute, or
    /// when the diagram sweeps r or D).
    /// The two-parameter curves over the plane view (None while they compute or when
    /// off) and whether they are shown ([`super::plane_curves`]).
    pub plane_curves: Option<Result<bouncemap_engine::orbits::curves::Curves, String>>,
    /// Whether the plane view draws the two-parameter curves.
    pub show_plane_curves: bool,
    /// The plane view's vertical parameter as chosen with `t` (None, or one the table
    /// does not have: its family's first parameter, else r).
    pub plane_y: Option<SweepParam>,
    pub branches: Option<Result<Skeleton, String>>,
    /// Whether the phase plot and the basins draw a saddle's manifolds (the cycle under
    /// the diagram's cursor when switched on, else the (1, k) one), and
    /// the manifolds (None while they compute or when off; `Ok(None)`: no saddle).
    pub show_manifolds: bool,
    pub manifolds: Option<Result<Option<super::manifold_overlay::ManifoldLines>, String>>,
    /// Whether proofs are on (`V`), the proof of the cycle asked about (None while it
    /// computes or when off), and which points of the branches are proved.
    pub show_proofs: bool,
    pub proof: Option<Result<super::proofs::ProofView, String>>,
    pub branch_proofs: Option<super::proofs::BranchMarks>,
    /// The continued branch nearest the diagram's cursor (its index) and its cycle at
    /// the cursor's α, while the diagram has the focus.
    pub under_cursor: Option<(usize, CyclePoint)>,
    /// What the diagram's value at the cursor settled on, with its precision verdict
    /// (while the diagram has the focus).
    pub at_cursor: Option<String>,
    /// The attractors-along-α view's cursor (while shown): its α and that α's
    /// attractors, by which the basins panel numbers and colours its own.
    pub along_alpha: Option<(f64, Vec<bouncemap_engine::attractors::global::Member>)>,
    /// Show how long work took ("done 1.2s", the time left). Off for the README's
    /// screenshot, which must come out the same on every run.
    pub show_times: bool,
    pub(in crate::tui) effects: Vec<Effect>,
    /// Rows changed by the action being handled, to announce to every panel.
    pub(in crate::tui) changed: Vec<ParamId>,
}

impl Shared {
    /// The shared state for `params`, nothing open, nothing queued.
    pub fn new(params: Params, keymap: Keymap, theme: Theme, marker: Marker) -> Shared {
        Shared {
            params,
            keymap,
            theme,
            marker,
            focus: Slot::Params,
            overlay: Overlay::None,
            message: None,
            log: Default::default(),
            left_out: Slot::Bounce,
            narrow: false,
            paused: false,
            dirty: true,
            orbits: None,
            stepped: None,
            branches: None,
            show_manifolds: false,
            manifolds: None,
            plane_curves: None,
            show_plane_curves: false,
            plane_y: None,
            show_proofs: false,
            proof: None,
            branch_proofs: None,
            under_cursor: None,
            at_cursor: None,
            along_alpha: None,
            show_times: true,
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

    /// A message for the user; `error` shows it as a refusal. It is kept in the log
    /// (the messages overlay shows it whole).
    pub fn say(&mut self, text: impl Into<String>, error: bool) {
        let text = text.into();
        if self.log.back() != Some(&(text.clone(), error)) {
            if self.log.len() == LOG_LEN {
                self.log.pop_front();
            }
            self.log.push_back((text.clone(), error));
        }
        self.message = Some((text, error));
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
