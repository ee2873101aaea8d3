//! The two-parameter curves over the plane view: the period doublings, folds, border
//! collisions and grazings of every branch of the (1, k) solution up to period
//! [`MAX_PERIOD`], followed over the plane's (α, D) or (α, r) window as
//! `bouncemap curves` follows them, computed in the background when switched on and
//! whenever the plane's window, table, r or k changes while on (parked while the
//! application is paused). The plane view draws them ([`Shared::plane_curves`]);
//! draw-only otherwise: it has no panel of its own.

use super::plane::plane_spec;
use super::{Component, Effect, Registered, Shared, Workers};
use crate::tui::keymap::Action;
use crate::tui::params::ParamId;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::orbits::curves::curves;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// Doubled branches are followed up to this period.
pub const MAX_PERIOD: usize = 16;

/// The background curves.
#[derive(Default)]
pub struct PlaneCurves {
    pub gen: u64,
    pending: bool,
}

impl Component for PlaneCurves {
    type Msg = Result<bouncemap_engine::orbits::curves::Curves, String>;

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action != Action::PlaneCurves {
            return false;
        }
        shared.show_plane_curves = !shared.show_plane_curves;
        if shared.show_plane_curves {
            shared.effect(Effect::Start(Self::TARGET));
            shared.say(
                format!("curves: • PD ~ fold × BC ¦ grazing ◉ codim-2; computing those of the branches up to period {MAX_PERIOD}…"),
                false,
            );
        } else {
            shared.plane_curves = None;
            shared.say("plane: curves off", false);
        }
        shared.dirty = true;
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        use ParamId::*;
        if shared.show_plane_curves && matches!(id, Table | R | K | Sweep | Lo | Hi) {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if !shared.show_plane_curves {
            workers.cancel(Self::TARGET);
            self.pending = false;
            return;
        }
        let spec = plane_spec(&shared.params, (2, 2), shared.plane_y);
        // Started from the application's own D (or r) where it lies in the window.
        let current = match spec.y.param {
            SweepParam::Table(n) => shared.params.table().param(n.as_str()),
            _ => Some(shared.params.r),
        };
        shared.plane_curves = None;
        let (plane, seeds) =
            match crate::config::plane::plane_curves(&spec, shared.params.k, MAX_PERIOD, current) {
                Ok(p) => p,
                Err(e) => {
                    shared.plane_curves = Some(Err(e.to_string()));
                    self.pending = false;
                    return;
                }
            };
        let gen = workers.spawn(Self::ADDRESS, "plane-curves", move |t| {
            if t.wait_if_paused() {
                t.send(curves(&plane, seeds).map_err(|e| e.to_string()));
            }
        });
        self.gen = gen;
        self.pending = true;
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen || !shared.show_plane_curves {
            return;
        }
        let text = match &msg {
            Ok(c) => format!(
                "curves: • PD ~ fold × BC ¦ grazing ◉ codim-2; {} two-parameter curves, {} codimension-two points",
                c.curves.len(),
                c.codim2.len()
            ),
            Err(e) => format!("plane curves: {e}"),
        };
        shared.say(text, msg.is_err());
        shared.plane_curves = Some(msg);
        self.pending = false;
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn draw(&self, _app: &Shared, _area: Rect, _buf: &mut Buffer) {}
}
