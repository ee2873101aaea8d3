//! The panels, and the registry that lists them.
//!
//! Each stateful panel is a [`Component`]: it owns its state, handles the actions meant
//! for it, reacts to changes of the shared parameters, starts and receives its own
//! background work (its results typed as its [`Component::Msg`]), and draws itself in
//! its slot of the layout. Panels see each other only through [`Shared`]
//! ([`shared`]).
//!
//! The registry below is the one list of panels. From it (by the `registry!` macro of
//! `registry.rs`) come the [`Target`]s, the typed message enum [`Msg`], the [`Panels`]
//! struct that holds one of each, and every routing over them: the order in which
//! actions are offered, which panel each slot shows (a panel listed before another in
//! the same slot takes its place while shown: the plane view over the diagram, the
//! basins over the phase plot), the focus ring (Tab), the starts, the messages and the
//! drawing. [`crate::tui::app::App`] holds the shared state and the panels and routes
//! through the registry; it names a panel only for what is that panel's own (the
//! diagram's cursor and zoom, export).
//!
//! Adding a panel: a file here with a type implementing [`Component`] (its `Msg`, its
//! start and receive through [`Registered::ADDRESS`], `shown` if it replaces another
//! panel while shown, `focusable` if it takes the arrow keys), its `mod` line and its
//! line in the registry, and, if a key shows it, an [`crate::tui::keymap::Action`]. A
//! grid picture filling in coarse to fine is a [`grid_picture::GridPicture`].
//! Draw-only pieces (the status line, the help, legend, messages, preset and table
//! overlays, the too-small message) are plain functions.

#[macro_use]
mod registry;

pub mod basins;
pub mod bounce;
pub mod branches;
pub mod diagram;
pub mod global;
pub mod grid_picture;
pub mod help;
pub mod legend;
pub mod manifold_overlay;
pub mod messages;
pub mod parameters;
pub mod phase_plot;
pub mod plane;
pub mod plane_curves;
pub mod presets;
pub mod proofs;
pub mod shared;
pub mod stability;
pub mod status;
pub mod table_view;
pub mod too_small;
pub mod view_export;

use super::keymap::Action;
use super::layout::{Panes, Slot};
use super::params::ParamId;
use super::workers;
use basins::BasinsPanel;
use bounce::Bounce;
use bouncemap_engine::attractors::basins::Basins;
use bouncemap_engine::plane::Plane;
use branches::Branches;
use diagram::Diagram;
use global::GlobalView;
use manifold_overlay::ManifoldOverlay;
use parameters::Parameters;
use phase_plot::PhasePlot;
use plane::PlanePanel;
use plane_curves::PlaneCurves;
use proofs::Proofs;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Widget};
pub use shared::{Effect, Overlay, Shared};
use stability::Stability;
use view_export::PictureExport;
pub use workers::JobMsg;

// The panels in routing order: actions are offered in this order, and a panel listed
// before another in the same slot takes that slot while it is shown.
registry! {
    // Target   => field:      type,         slot it takes,           made from `Shared`
    Parameters  => parameters: Parameters,   slot Some(Slot::Params),    new |_| Parameters::new();
    /// The attractors along α, in the diagram's place while shown (it takes the
    /// diagram's keys, and passes its own key on so that the basins show with it).
    Global      => global:     GlobalView,   slot Some(Slot::Diagram),   new |_| GlobalView::default();
    /// The plane view, in the diagram's place while shown (it takes the diagram's keys).
    Plane       => plane:      PlanePanel,   slot Some(Slot::Diagram),   new |_| PlanePanel::default();
    Diagram     => diagram:    Diagram,      slot Some(Slot::Diagram),   new Diagram::new;
    Bounce      => bounce:     Bounce,       slot Some(Slot::Bounce),    new |s: &Shared| Bounce::new(&s.params);
    /// The basins, in the phase plot's place while shown.
    Basins      => basins:     BasinsPanel,  slot Some(Slot::Phase),     new |_| BasinsPanel::default();
    Phase       => phase:      PhasePlot,    slot Some(Slot::Phase),     new |s: &Shared| PhasePlot::new(s.marker);
    /// Runs the orbit analysis every panel marks ([`Shared::orbits`]).
    Stability   => stability:  Stability,    slot Some(Slot::Stability), new |_| Stability::default();
    /// The continued branches ([`Shared::branches`]), drawn by the diagram.
    Branches    => branches:   Branches,     slot None,                  new |_| Branches::default();
    /// A saddle's manifolds ([`Shared::manifolds`]): the cycle under the diagram's cursor,
    /// else the (1, k) one; drawn by the phase plot and the basins.
    Manifolds   => manifolds:  ManifoldOverlay, slot None,               new |_| ManifoldOverlay::default();
    /// Proofs of the cycle under the cursor and of the branches ([`Shared::proof`],
    /// [`Shared::branch_proofs`]), shown by the stability panel and the diagram.
    Proofs      => proofs:     Proofs,       slot None,                  new |_| Proofs::default();
    /// The two-parameter curves ([`Shared::plane_curves`]), drawn by the plane view.
    PlaneCurves => plane_curves: PlaneCurves, slot None,               new |_| PlaneCurves::default();
    /// `E`'s plane figure at the export's resolution ([`view_export`]).
    PlaneExport => plane_export: PictureExport<Plane>, slot None,
        new |_| PictureExport::new(<PictureExport<Plane> as Registered>::ADDRESS);
    /// `E`'s basins figure at the export's resolution.
    BasinsExport => basins_export: PictureExport<Basins>, slot None,
        new |_| PictureExport::new(<PictureExport<Basins> as Registered>::ADDRESS);
}

/// The workers of the terminal application: their messages are [`Msg`]s.
pub type Workers = workers::Workers<Msg>;

/// Where a panel's background work reports, its results being `B`s.
pub type Address<B> = workers::Address<Msg, B>;

/// What a panel without background work receives: nothing.
pub enum NoWork {}

/// What the registry knows of each panel listed (implemented by it, never by hand).
pub trait Registered: Component {
    /// The panel's own target: where its restarts ([`Effect::Start`]) go.
    const TARGET: Target;
    /// Where its background work reports ([`Workers::spawn`], [`Workers::start_job`]).
    const ADDRESS: Address<Self::Msg>;
}

/// A stateful panel.
pub trait Component {
    /// What its background work sends back ([`NoWork`] if it has none).
    type Msg: Send + 'static;

    /// Whether it is shown in its slot now (a panel that replaces another while shown
    /// says when).
    fn shown(&self) -> bool {
        true
    }

    /// Whether it takes the arrow keys when its slot has the focus (Tab goes round the
    /// slots whose shown panel does).
    fn focusable(&self) -> bool {
        false
    }

    /// Its slot's rectangle at the current layout (before sweeps ask for sizes, and
    /// before drawing).
    fn set_pane(&mut self, _pane: Rect, _shared: &mut Shared) {}

    /// Handle an action (the panel checks the focus where that matters); true if it
    /// was consumed.
    fn handle(&mut self, _action: Action, _shared: &mut Shared) -> bool {
        false
    }

    /// The focus moved to another slot.
    fn focus_moved(&mut self) {}

    /// The shared parameter `id` changed (the table stands for "everything").
    fn changed(&mut self, _id: ParamId, _shared: &mut Shared) {}

    /// Start (or restart) this panel's background work for the current parameters.
    fn start(&mut self, _shared: &mut Shared, _workers: &Workers) {}

    /// A message from this panel's background work, sent under generation `gen`
    /// (stale generations are the panel's to drop).
    fn receive(&mut self, _gen: u64, _msg: Self::Msg, _shared: &mut Shared) {}

    /// Whether background work may still send something (the loop then polls more
    /// often).
    fn busy(&self) -> bool {
        false
    }

    /// What it is computing, for the status line (None: nothing to say).
    fn computing(&self, _shared: &Shared) -> Option<String> {
        None
    }

    /// Draw into `area`.
    fn draw(&self, shared: &Shared, area: Rect, buf: &mut Buffer);
}

/// A panel frame: rounded border, title, brighter when focused.
pub fn panel<'a>(shared: &Shared, title: String, focused: bool) -> Block<'a> {
    let style = if focused {
        shared.theme.focus()
    } else {
        shared.theme.axis()
    };
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(style)
        .title(ratatui::text::Span::styled(title, shared.theme.focus()))
}

/// Whether slot `f` has the focus (and no overlay hides it).
pub fn is_focused(shared: &Shared, f: Slot) -> bool {
    shared.focus == f && shared.overlay == Overlay::None
}

/// Format a count compactly: 950, 12.3k, 4.1M.
pub fn compact(n: f64) -> String {
    if n >= 1e6 {
        format!("{:.1}M", n / 1e6)
    } else if n >= 1e4 {
        format!("{:.0}k", n / 1e3)
    } else if n >= 1e3 {
        format!("{:.1}k", n / 1e3)
    } else {
        format!("{n:.0}")
    }
}

/// A bordered box with `lines`, centred over `area` and sized to its content (overlays:
/// help, presets).
pub fn overlay(shared: &Shared, title: &str, lines: Vec<Line<'_>>, area: Rect, buf: &mut Buffer) {
    let w = (lines.iter().map(|l| l.width()).max().unwrap_or(40) as u16 + 2).min(area.width);
    let h = (lines.len() as u16 + 2).min(area.height);
    let r = Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    };
    Clear.render(r, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .border_style(shared.theme.focus())
                .title(format!(" {title} ")),
        )
        .render(r, buf);
}
