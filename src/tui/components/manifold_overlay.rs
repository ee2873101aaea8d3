//! The manifolds of a saddle over the phase plot and the basins: both manifolds of the
//! cycle of the continued branch under the diagram's cursor when there is one (solved
//! again at the current parameters: any (n, k), if it is a saddle there), else of the
//! first unstable (1, k) solution with real multipliers (the saddle `bouncemap
//! manifolds` grows by default), each branch [`LENGTH`] long, computed in the background
//! when switched on and whenever the table, α, r or k changes while on (parked while
//! the application is paused). The phase plot
//! draws them in (t̂, v), the basins in (t̂0, w0 = v − f'(t̂0)) ([`Shared::manifolds`]);
//! draw-only otherwise: it has no panel of its own.

use super::{Component, Effect, Registered, Shared, Workers};
use crate::tui::keymap::Action;
use crate::tui::params::{ParamId, Touch};
use bouncemap_engine::orbits::manifold::{first_saddle, manifold, Kind, ManifoldSpec};
use bouncemap_engine::orbits::periodic::{cycle, CyclePoint};
use bouncemap_engine::System;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// Arc length of each branch drawn.
pub const LENGTH: f64 = 2.0;

/// The manifolds to draw: points (t̂, v), t̂ in [0, 1).
#[derive(Clone, Debug, PartialEq)]
pub struct ManifoldLines {
    /// The saddle's (n, k).
    pub n: usize,
    pub k: u32,
    /// The saddle's impacts (marked ◇: the orbit analysis marks the unstable (1, k)
    /// solution so; the overlay marks a saddle from under the cursor).
    pub saddle: Vec<(f64, f64)>,
    /// The saddle is the cycle of the branch under the diagram's cursor.
    pub from_cursor: bool,
    pub unstable: Vec<(f64, f64)>,
    pub stable: Vec<(f64, f64)>,
}

/// The manifolds of the saddle of `sys`: the cycle `under` the diagram's cursor, solved
/// again by Newton's method at `sys` from its launch (an error if it is not found there
/// or is no saddle there), else the (1, k) saddle (None: there is none).
pub fn lines(
    sys: &System,
    k: u32,
    under: Option<&CyclePoint>,
) -> Result<Option<ManifoldLines>, String> {
    let at = bouncemap_engine::fmt_value(sys.alpha());
    let c = match under {
        Some(p) => cycle(sys, p.n, p.k, p.t0, p.velocities[0]).map_err(|e| {
            format!(
                "the ({}, {}) cycle under the cursor is not found at α = {at} ({})",
                p.n,
                p.k,
                e.as_str()
            )
        })?,
        None => match first_saddle(sys, k).map_err(|e| e.to_string())? {
            Some(c) => c,
            None => return Ok(None),
        },
    };
    let spec = ManifoldSpec {
        length: LENGTH,
        ..ManifoldSpec::default()
    };
    let points = |kind: Kind| -> Result<Vec<(f64, f64)>, String> {
        let m = manifold(sys, &c, kind, &spec).map_err(|e| match under {
            Some(_) => format!(
                "the ({}, {}) cycle under the cursor at α = {at}: {e}",
                c.n, c.k
            ),
            None => e.to_string(),
        })?;
        Ok(m.branches
            .iter()
            .flat_map(|b| b.points.iter().map(|p| (p[0].rem_euclid(1.0), p[1])))
            .collect())
    };
    Ok(Some(ManifoldLines {
        n: c.n,
        k: c.k,
        from_cursor: under.is_some(),
        saddle: c
            .phases
            .iter()
            .zip(&c.velocities)
            .map(|(&t, &v)| (t.rem_euclid(1.0), v))
            .collect(),
        unstable: points(Kind::Unstable)?,
        stable: points(Kind::Stable)?,
    }))
}

/// The title's note on the overlay ("" when off): ▪· and the saddle's (n, k).
pub fn title_note(app: &Shared) -> String {
    if !app.show_manifolds {
        return String::new();
    }
    match &app.manifolds {
        None => " ▪· …".into(),
        Some(Ok(Some(m))) => format!(" ▪· ({}, {})", m.n, m.k),
        Some(Ok(None)) => " no saddle".into(),
        Some(Err(_)) => " ▪· failed".into(),
    }
}

/// Draw the manifolds with `cell` mapping (t̂, v) to a character cell of the plot.
pub fn draw(app: &Shared, buf: &mut Buffer, cell: impl Fn(f64, f64) -> Option<(u16, u16)>) {
    let (true, Some(Ok(Some(m)))) = (app.show_manifolds, &app.manifolds) else {
        return;
    };
    // The orbit analysis marks the (1, k) saddle ◇ itself; another is marked here.
    let saddle: &[(f64, f64)] = if m.from_cursor { &m.saddle } else { &[] };
    for (pts, glyph, style) in [
        (&m.stable[..], "·", app.theme.focus()),
        (&m.unstable[..], "▪", app.theme.mark()),
        (saddle, "◇", app.theme.mark()),
    ] {
        for &(t, v) in pts {
            if let Some((x, y)) = cell(t, v) {
                buf.set_string(x, y, glyph, style);
            }
        }
    }
}

/// The background manifolds.
#[derive(Default)]
pub struct ManifoldOverlay {
    pub gen: u64,
    pending: bool,
    /// The cycle under the diagram's cursor when the overlay was switched on: its saddle
    /// (None: the (1, k) saddle).
    under: Option<CyclePoint>,
}

impl Component for ManifoldOverlay {
    type Msg = Result<Option<ManifoldLines>, String>;

    fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
        if action != Action::Manifolds {
            return false;
        }
        shared.show_manifolds = !shared.show_manifolds;
        if shared.show_manifolds {
            shared.effect(Effect::Start(Self::TARGET));
            // The cycle under the cursor now is the saddle while the overlay is on.
            self.under = shared.under_cursor.as_ref().map(|(_, p)| p.clone());
            let alpha = shared.system().alpha();
            let which = match &shared.under_cursor {
                Some((_, p)) if (p.alpha - alpha).abs() > 1e-12 * (1.0 + alpha.abs()) => format!(
                    "the ({}, {}) cycle under the cursor, solved at the phase plot's α = {} (Enter first takes α to the cursor's {}; W twice for another cycle)",
                    p.n,
                    p.k,
                    bouncemap_engine::fmt_value(alpha),
                    bouncemap_engine::fmt_value(p.alpha)
                ),
                Some((_, p)) => format!(
                    "the ({}, {}) cycle under the cursor (W twice for another)",
                    p.n, p.k
                ),
                None => format!("the (1, {}) saddle", shared.params.k),
            };
            shared.say(
                format!(
                    "manifolds of {which} over the phase plot and the basins: ▪ unstable · stable (the saddle is its ◇); computing…"
                ),
                false,
            );
        } else {
            shared.manifolds = None;
            self.under = None;
            shared.say("manifolds off", false);
        }
        shared.dirty = true;
        true
    }

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if shared.show_manifolds && matches!(id.touches(), Touch::System) {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        if !shared.show_manifolds {
            workers.cancel(Self::TARGET);
            self.pending = false;
            return;
        }
        shared.manifolds = None;
        let (sys, k) = (shared.system(), shared.params.k);
        let under = self.under.clone();
        let gen = workers.spawn(Self::ADDRESS, "manifolds", move |t| {
            if t.wait_if_paused() {
                t.send(lines(&sys, k, under.as_ref()));
            }
        });
        self.gen = gen;
        self.pending = true;
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen || !shared.show_manifolds {
            return;
        }
        match &msg {
            Ok(Some(m)) => shared.say(
                format!(
                    "manifolds of the ({}, {}) saddle ◇: ▪ unstable · stable ({} and {} points, each branch {LENGTH} long)",
                    m.n,
                    m.k,
                    m.unstable.len(),
                    m.stable.len()
                ),
                false,
            ),
            Ok(None) => shared.say(
                format!(
                    "manifolds: no saddle (1, {}) solution here (every one is stable or spirals)",
                    shared.params.k
                ),
                false,
            ),
            Err(e) => shared.say(format!("manifolds: {e}"), true),
        }
        shared.manifolds = Some(msg);
        self.pending = false;
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        self.pending.then(|| "manifolds".to_string())
    }

    fn draw(&self, _app: &Shared, _area: Rect, _buf: &mut Buffer) {}
}
