//! Shared fixtures for the terminal application's tests: an app in a fixed state
#![allow(dead_code)]
//! built from deterministic data (no threads, no clock).

use bouncemap::config::display::ColorMode;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::analysis::orbit_info;
use bouncemap::tui::app::App;
use bouncemap::tui::components::phase_plot::PhasePoints;
use bouncemap::tui::components::{JobMsg, Msg};
use bouncemap::tui::keymap::Keymap;
use bouncemap::tui::params::Params;
use bouncemap::tui::theme::Theme;
use bouncemap_engine::jobs::Batch;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::run::Point as SweepPoint;
use bouncemap_engine::sweep::ValueResult;
use bouncemap_engine::EventKind;
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
    app.take_effects();
    app
}

/// Size the grids as the runtime does before drawing.
pub fn size(app: &mut App, w: u16, h: u16) {
    app.set_size(Rect::new(0, 0, w, h));
}

/// A sweep batch as the executor streams it.
pub fn sweep_msg(gen: u64, data: ValueResult) -> Msg {
    Msg::Diagram(
        gen,
        JobMsg::Batch(Batch {
            generation: gen,
            pass: 1,
            data,
        }),
    )
}

/// Feed deterministic results: a synthetic diagram (a branch that splits in two), the
/// map's own phase points, the engine's orbit analysis, and three stepped bounces.
pub fn fill(app: &mut App) {
    let n = 120;
    let shared = &app.shared;
    app.panels.diagram.sweep_started(1, n, shared);
    let (lo, hi) = (app.shared.params.lo, app.shared.params.hi);
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
        app.receive(sweep_msg(
            1,
            ValueResult {
                index: i,
                value: a,
                complete: true,
                points,
                outcome: Outcome::Unsettled,
                sticking: false,
                events: 100,
                lyapunov: None,
                attractors: Vec::new(),
                precision: None,
                cycle: None,
            },
        ));
    }
    app.receive(Msg::Diagram(1, JobMsg::Done));
    app.panels.diagram.started = None;
    app.panels.diagram.elapsed = 2.0;
    let sys = app.shared.system();
    let st = app.shared.params.initial(&sys).unwrap();
    let mut map =
        bouncemap_engine::ImpactMap::new(sys.clone(), bouncemap_engine::Solver::Exact, st);
    let pts: Vec<(f64, f64)> = (0..400)
        .map(|_| map.step().map(|e| (e.phase, e.v)).unwrap())
        .collect();
    let shared = &app.shared;
    app.panels.phase.started(1, shared);
    app.receive(Msg::Phase(
        1,
        PhasePoints {
            points: pts,
            done: true,
            note: None,
        },
    ));
    app.panels.stability.started(1, &mut app.shared);
    let info = orbit_info(&sys, app.shared.params.k);
    app.receive(Msg::Stability(1, info));
    app.panels.bounce.step(3);
}

/// Render the whole screen into a test backend.
pub fn render(app: &mut App, w: u16, h: u16) -> Terminal<TestBackend> {
    size(app, w, h);
    let mut t = Terminal::new(TestBackend::new(w, h)).unwrap();
    t.draw(|f| app.draw(f)).unwrap();
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

/// `E` under the name `stem` at `sizes`, run to its end: the files written at once, and
/// the plane's or the basins' figures computed on real workers (at most a minute).
/// Returns every message the export gave, in order.
pub fn export_view_to_end(
    app: &mut App,
    sizes: bouncemap::tui::export::ExportSizes,
    stem: &std::path::Path,
) -> Result<Vec<String>, String> {
    use bouncemap::tui::components::{Effect, Workers};
    use std::time::{Duration, Instant};
    let first = bouncemap::tui::export::export_view(&mut app.shared, &mut app.panels, sizes, stem)?;
    let mut said = vec![first];
    let workers = Workers::new(bouncemap_engine::jobs::Executor::new(2).unwrap());
    for e in app.take_effects() {
        if let Effect::Start(t) = e {
            app.start(t, &workers);
        }
    }
    let start = Instant::now();
    let pending = |a: &App| {
        a.panels.plane_export.request.is_some() || a.panels.basins_export.request.is_some()
    };
    while pending(app) && start.elapsed() < Duration::from_secs(60) {
        if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(50)) {
            let before = app.shared.log.len();
            app.receive(m);
            said.extend(app.shared.log.iter().skip(before).map(|(t, _)| t.clone()));
        }
    }
    workers.cancel_all();
    assert!(!pending(app), "the view export did not finish");
    Ok(said)
}
