//! Shared fixtures for the terminal application's tests: an app in a fixed state
#![allow(dead_code)]
//! built from deterministic data (no threads, no clock).

use bouncemap::engine::sweep::{Outcome, SweepBatch, SweepPoint};
use bouncemap::engine::EventKind;
use bouncemap::tui::analysis::EngineAnalysis;
use bouncemap::tui::app::App;
use bouncemap::tui::keymap::Keymap;
use bouncemap::tui::params::Params;
use bouncemap::tui::plot::Marker;
use bouncemap::tui::theme::{ColorMode, Theme};
use bouncemap::tui::views;
use bouncemap::tui::workers::{Analysis, Msg};
use ratatui::backend::TestBackend;
use ratatui::layout::Rect;
use ratatui::Terminal;

/// The default app with no data yet.
pub fn app(marker: Marker) -> App {
    let mut app = App::new(
        Params::default(),
        Keymap::default(),
        Theme::new(ColorMode::None),
        marker,
        15,
    );
    app.presets = bouncemap::tui::paper_presets();
    app.take_effects();
    app
}

/// Size the grids as the runtime does before drawing.
pub fn size(app: &mut App, w: u16, h: u16) {
    if let Some(p) = views::layout(Rect::new(0, 0, w, h)) {
        let (d, ph) = views::plot_areas(&p);
        app.set_plot_sizes(d, ph);
    }
}

/// Feed deterministic results: a synthetic diagram (a branch that splits in two), the
/// map's own phase points, the engine's orbit analysis, and three stepped bounces.
pub fn fill(app: &mut App) {
    let n = 120;
    app.sweep_started(1, n, Ok(()));
    let (lo, hi) = (app.params.lo, app.params.hi);
    for i in 0..n {
        let a = lo + (hi - lo) * i as f64 / (n - 1) as f64;
        let x = (a - lo) / (hi - lo);
        let branch = 0.1 + 0.3 * x;
        let split = if x > 0.6 {
            0.25 * (x - 0.6).sqrt()
        } else {
            0.0
        };
        let points = (0..20)
            .map(|j| SweepPoint {
                phase: if j % 2 == 0 {
                    branch + split
                } else {
                    branch - split
                },
                v: 0.5 + if j % 2 == 0 { split } else { -split },
                kind: EventKind::Impact,
            })
            .collect();
        app.receive(Msg::Sweep(SweepBatch {
            generation: 1,
            pass: 1,
            complete: true,
            index: i,
            value: a,
            points,
            outcome: Outcome::Unsettled,
            sticking: false,
            events: 100,
        }));
    }
    app.receive(Msg::SweepDone { gen: 1 });
    app.diagram.started = None;
    app.diagram.elapsed = 2.0;
    let sys = app.system();
    let st = app.params.initial(&sys).unwrap();
    let mut map =
        bouncemap::engine::ImpactMap::new(sys.clone(), bouncemap::engine::Solver::Exact, st);
    let pts: Vec<(f64, f64)> = (0..400)
        .map(|_| map.step().map(|e| (e.phase, e.v)).unwrap())
        .collect();
    app.phase_started(1);
    app.receive(Msg::Phase {
        gen: 1,
        points: pts,
        done: true,
        note: None,
    });
    app.orbits_started(1);
    let info = EngineAnalysis.orbits(&sys, app.params.k, (lo, hi));
    app.receive(Msg::Orbits { gen: 1, info });
    app.step(3);
}

/// Render the whole screen into a test backend.
pub fn render(app: &mut App, w: u16, h: u16) -> Terminal<TestBackend> {
    size(app, w, h);
    let mut t = Terminal::new(TestBackend::new(w, h)).unwrap();
    t.draw(|f| views::draw(f, app)).unwrap();
    t
}

/// The screen as text, one line per row.
pub fn text(t: &Terminal<TestBackend>) -> String {
    buffer_text(t.backend().buffer())
}

/// A buffer as text, one line per row, trailing blanks removed.
pub fn buffer_text(buf: &ratatui::buffer::Buffer) -> String {
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol().to_string())
                .collect::<String>()
                .trim_end()
                .to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}
