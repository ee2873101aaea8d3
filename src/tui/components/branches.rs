//! The skeleton under the diagram: every periodic branch the continuation reaches in the
//! current α window from the (1, k) solution (its period doublings followed onto the
//! doubled branches), computed in the background whenever the table, r, k or the window
//! changes (not when only α moves; parked while the application is paused). The diagram draws them (stable solid, unstable
//! dotted) with their special points on the axis; the stability panel lists the branch
//! under the diagram's cursor; with proofs on, new branches start the proofs again
//! ([`super::proofs`]). Draw-only otherwise: it has no panel of its own.

use super::{Component, Effect, Registered, Shared, Workers};
use crate::tui::params::ParamId;
use crate::tui::skeleton::{compute, Skeleton};
use bouncemap_engine::jobs::grid::SweepParam;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// The background continuation.
#[derive(Default)]
pub struct Branches {
    pub gen: u64,
    pending: bool,
}

impl Component for Branches {
    type Msg = Result<Skeleton, String>;

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        use ParamId::*;
        if matches!(id, Table | Family(_) | R | K | Sweep | Lo | Hi) {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let p = &shared.params;
        if p.param != SweepParam::Alpha {
            // Branches are continued in α: other sweeps show none.
            workers.cancel(Self::TARGET);
            self.pending = false;
            shared.branches = None;
            return;
        }
        let (table, r, k, window) = (p.table(), p.r, p.k, (p.lo, p.hi));
        // Parked while paused (a continuation can take a while): a storm of changes
        // while paused leaves parked threads that end as newer ones replace them.
        let gen = workers.spawn(Self::ADDRESS, "branches", move |t| {
            if t.wait_if_paused() {
                t.send(compute(table, r, k, window));
            }
        });
        self.gen = gen;
        self.pending = true;
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        shared.branches = Some(msg);
        self.pending = false;
        shared.dirty = true;
        // New branches with proofs on: prove them too (the proofs started with the
        // change that started these had none to prove).
        if shared.show_proofs {
            shared.effect(Effect::Start(super::Target::Proofs));
        }
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn draw(&self, _app: &Shared, _area: Rect, _buf: &mut Buffer) {}
}
