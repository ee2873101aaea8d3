//! Proofs by interval arithmetic in the terminal application (`V`): the cycle under the
//! diagram's cursor (the continued branch nearest it, at the cursor's α), or without
//! one the (1, k) solutions at the current parameters, proved as `bouncemap certify`
//! proves them; and every point of the continued branches, so the diagram can show
//! which stretches are proved. Computed in the background when switched on and again
//! when the system or the window changes while on; the stability panel shows the
//! verdicts ([`Shared::proof`]), the diagram the branches' ([`Shared::branch_proofs`]).
//! Draw-only otherwise: it has no panel of its own.

use super::{Component, Effect, Registered, Shared, Workers};
use crate::output::records::{failure_name, stability_name};
use crate::tui::keymap::Action;
use crate::tui::params::{ParamId, Touch};
use crate::tui::skeleton::Skeleton;
use bouncemap_engine::orbits::certify::{certify, certify_cycle, Certificate};
use bouncemap_engine::orbits::fixed_points;
use bouncemap_engine::orbits::periodic::CyclePoint;
use bouncemap_engine::System;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// What was proved of the cycle(s) asked about, for the stability panel.
#[derive(Clone, Debug, PartialEq)]
pub struct ProofView {
    /// Which cycle(s): "(4, 4) at α 0.5712 under the cursor", "(1, 1) solutions".
    pub what: String,
    /// One line per cycle: its verdict.
    pub lines: Vec<String>,
}

/// Which points of the continued branches are proved (one flag per point, per branch),
/// for the skeleton of `window`.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchMarks {
    pub window: (f64, f64),
    pub proved: Vec<Vec<bool>>,
}

impl BranchMarks {
    /// The marks if they belong to `sk` (the same window, branches and points).
    pub fn of<'a>(&'a self, sk: &Skeleton) -> Option<&'a [Vec<bool>]> {
        (self.window == sk.window
            && self.proved.len() == sk.branches.len()
            && self
                .proved
                .iter()
                .zip(&sk.branches)
                .all(|(m, b)| m.len() == b.points.len()))
        .then_some(&self.proved)
    }
}

/// The background work's two results.
pub enum ProofMsg {
    /// The cycle(s) asked about.
    Cycle(Result<ProofView, String>),
    /// The branches' points.
    Branches(BranchMarks),
}

/// One line for one certificate: proved and its stability, or why not.
pub fn verdict_line(c: &Certificate) -> String {
    let what = format!("({}, {})", c.n, c.k);
    match (&c.failure, c.stability, &c.enclosure) {
        (None, Some(s), Some(e)) => format!(
            "{what} proved, {} (box {:.0e})",
            match stability_name(&s.verdict) {
                "undecided" => "stability undecided",
                other => other,
            },
            e.width
        ),
        (Some(f), _, _) => format!("{what} not proved: {}", failure_name(f).replace('_', " ")),
        _ => format!("{what} not proved"),
    }
}

/// Prove the cycle under the cursor, or the (1, k) solutions of `sys` (the worker's
/// first result).
pub fn prove_asked(
    sys: &System,
    k: u32,
    under: Option<(usize, CyclePoint)>,
) -> Result<ProofView, String> {
    if let Some((branch, pt)) = under {
        let at = System::new(sys.table().clone(), pt.alpha, sys.r()).map_err(|e| e.to_string())?;
        let c = certify_cycle(&at, &pt);
        return Ok(ProofView {
            what: format!(
                "branch {branch}'s ({}, {}) at α {:.6} under the cursor",
                pt.n, pt.k, pt.alpha
            ),
            lines: vec![verdict_line(&c)],
        });
    }
    let fps = fixed_points(sys, k).map_err(|e| e.to_string())?;
    let lines = fps
        .iter()
        .filter(|p| p.admissible)
        .map(|p| {
            let c = certify(sys, 1, k, p.phase, p.v);
            format!("t̂* {:.4}: {}", p.phase, verdict_line(&c))
        })
        .collect::<Vec<_>>();
    Ok(ProofView {
        what: format!("the (1, {k}) solutions at this α"),
        lines: if lines.is_empty() {
            vec![format!("no (1, {k}) solution to prove")]
        } else {
            lines
        },
    })
}

/// Every point of every branch of `sk` proved (or not): the worker's second result.
pub fn prove_branches(sk: &Skeleton) -> BranchMarks {
    BranchMarks {
        window: sk.window,
        proved: sk
            .branches
            .iter()
            .map(|b| {
                b.points
                    .iter()
                    .map(|p| {
                        System::new(sk.table.clone(), p.alpha, sk.r)
                            .is_ok_and(|sys| certify_cycle(&sys, p).proved())
                    })
                    .collect()
            })
            .collect(),
    }
}

/// The background proofs.
#[derive(Default)]
pub struct Proofs {
    pub gen: u64,
    pending: bool,
}

impl Component for Proofs {
    type Msg = ProofMsg;

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action != Action::Certify {
            return false;
        }
        shared.show_proofs = !shared.show_proofs;
        if shared.show_proofs {
            shared.effect(Effect::Start(Self::TARGET));
            let what = match &shared.under_cursor {
                Some((_, p)) => format!("the ({}, {}) cycle under the cursor", p.n, p.k),
                None => format!("the (1, {}) solutions", shared.params.k),
            };
            shared.say(
                format!("proving {what} and the branches by interval arithmetic (V again: off; move the cursor and press V twice for another)…"),
                false,
            );
        } else {
            shared.proof = None;
            shared.branch_proofs = None;
            shared.say("proofs off", false);
        }
        shared.dirty = true;
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        use ParamId::*;
        if shared.show_proofs && (id.touches() == Touch::System || matches!(id, Lo | Hi | Sweep)) {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if !shared.show_proofs {
            workers.cancel(Self::TARGET);
            self.pending = false;
            return;
        }
        shared.proof = None;
        let (sys, k) = (shared.system(), shared.params.k);
        let under = shared.under_cursor.clone();
        let skeleton = match &shared.branches {
            Some(Ok(sk)) => Some(sk.clone()),
            _ => None,
        };
        let gen = workers.spawn(Self::ADDRESS, "proofs", move |t| {
            if !t.wait_if_paused() {
                return;
            }
            if !t.send(ProofMsg::Cycle(prove_asked(&sys, k, under))) {
                return;
            }
            if let Some(sk) = skeleton {
                t.send(ProofMsg::Branches(prove_branches(&sk)));
            }
        });
        self.gen = gen;
        self.pending = true;
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen || !shared.show_proofs {
            return;
        }
        match msg {
            ProofMsg::Cycle(v) => {
                if let Ok(v) = &v {
                    shared.say(format!("proofs: {}: {}", v.what, v.lines.join("; ")), false);
                }
                shared.proof = Some(v);
                if !matches!(&shared.branches, Some(Ok(_))) {
                    self.pending = false;
                }
            }
            ProofMsg::Branches(m) => {
                let (all, proved) = m
                    .proved
                    .iter()
                    .flatten()
                    .fold((0, 0), |(a, p), &x| (a + 1, p + usize::from(x)));
                shared.say(
                    format!("proofs: {proved} of {all} branch points proved (stretches not proved drawn red)"),
                    false,
                );
                shared.branch_proofs = Some(m);
                self.pending = false;
            }
        }
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        self.pending.then(|| "proofs".to_string())
    }

    fn draw(&self, _app: &Shared, _area: Rect, _buf: &mut Buffer) {}
}
