//! The attractors-along-α view of the terminal application (`A`), with real workers:
//! shown in the diagram's place with the basins beside it, filling in to the engine's
//! own continuation of the same window (computed again here), its cursor moving the
//! application's α and the basins with it, drawn at 120×40 and 80×24 without colour,
//! and put away by Enter or by the plane.

use crate::tui_common::{render, size, text};
use bouncemap::config::display::ColorMode;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect};
use bouncemap::tui::components::global::global_spec;
use bouncemap::tui::components::{Target, Workers};
use bouncemap::tui::keymap::{Action, Keymap};
use bouncemap::tui::layout::Slot;
use bouncemap::tui::params::{ParamId, Params};
use bouncemap::tui::theme::Theme;
use bouncemap_engine::attractors::global::collect;
use bouncemap_engine::jobs::{Control, Executor};
use std::time::{Duration, Instant};

/// The cubic table over α ∈ [0.46, 0.5], r = 0.8: the (1, 1) cycle beside sticking
/// cycles, then its period doubling.
fn cubic_app() -> App {
    let mut params = Params::default();
    params.set_text(ParamId::Table, "cubic").unwrap();
    params.set_text(ParamId::Lo, "0.46").unwrap();
    params.set_text(ParamId::Hi, "0.5").unwrap();
    params.set_text(ParamId::Alpha, "0.47").unwrap();
    let mut a = App::new(
        params,
        Keymap::default(),
        Theme::new(ColorMode::None),
        Marker::Braille,
        15,
    );
    a.take_effects();
    a
}

/// Carry out the starts the app asked for, then hand it messages until `until` holds
/// (at most a minute).
fn run_until(a: &mut App, workers: &Workers, until: &dyn Fn(&App) -> bool) {
    let t = Instant::now();
    while t.elapsed() < Duration::from_secs(60) {
        for e in a.take_effects() {
            if let Effect::Start(target) = e {
                a.start(target, workers);
            }
        }
        if until(a) {
            return;
        }
        if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(5)) {
            a.receive(m);
        }
    }
    panic!("the view never got there");
}

#[test]
fn the_view_fills_in_to_the_engines_continuation_and_its_cursor_moves_alpha() {
    let workers = Workers::new(Executor::new(2).unwrap());
    let mut a = cubic_app();
    size(&mut a, 120, 40);
    a.handle(Action::ToggleGlobal);
    // In the diagram's place, with the basins in the phase plot's.
    assert_eq!(a.panels.in_slot(Slot::Diagram), Some(Target::Global));
    assert_eq!(a.panels.in_slot(Slot::Phase), Some(Target::Basins));
    let t = Instant::now();
    run_until(&mut a, &workers, &|a| a.panels.global.done);
    eprintln!(
        "attractors along α: {} values in {:?}",
        a.panels.global.steps.len(),
        t.elapsed()
    );
    let g = &a.panels.global;
    assert_eq!(g.error, None);
    let spec = g.spec.clone().unwrap();
    assert_eq!(spec, global_spec(&a.shared.params, spec.steps).unwrap());
    assert!(spec.steps >= 60, "one value per column: {}", spec.steps);
    assert_eq!((spec.lo, spec.hi), (0.46, 0.5));
    // The same continuation computed again, here: what the view holds.
    let again = collect(
        spec.clone(),
        &Executor::new(2).unwrap(),
        &Control::new(),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(g.steps, again.steps());
    assert_eq!(g.changes, again.changes());
    assert_eq!(g.tracks, again.tracks());
    assert!(again.changes().iter().any(|c| c.what.name() == "period"));
    // The cursor starts at the application's α and moves it, and the basins with it.
    let at = |a: &App| a.panels.global.steps[a.panels.global.cursor].alpha;
    assert!((at(&a) - 0.47).abs() <= (spec.hi - spec.lo) / (spec.steps - 1) as f64);
    let before = a.panels.global.cursor;
    a.handle(Action::Right);
    assert_eq!(a.panels.global.cursor, before + 4);
    assert_eq!(a.shared.params.alpha, at(&a));
    assert!(a.take_effects().contains(&Effect::Start(Target::Basins)));
    a.handle(Action::FineLeft);
    assert_eq!(a.panels.global.cursor, before + 3);
    assert_eq!(a.shared.params.alpha, at(&a));
    // Moving α does not restart the view; changing r does.
    assert!(!a.take_effects().contains(&Effect::Start(Target::Global)));
    a.shared.focus = Slot::Params;
    a.shared.params.set_text(ParamId::R, "0.79").unwrap();
    a.panels.changed(ParamId::R, &mut a.shared);
    assert!(a.take_effects().contains(&Effect::Start(Target::Global)));
    workers.cancel_all();
}

#[test]
fn the_view_draws_its_points_fractions_and_cursor_at_both_sizes() {
    let workers = Workers::new(Executor::new(2).unwrap());
    for (w, h) in [(120, 40), (80, 24)] {
        let mut a = cubic_app();
        size(&mut a, w, h);
        a.handle(Action::ToggleGlobal);
        run_until(&mut a, &workers, &|a| a.panels.global.done);
        let screen = text(&render(&mut a, w, h));
        assert!(screen.contains("Attractors along α · done"), "{screen}");
        assert!(screen.contains("basin fractions"), "{screen}");
        assert!(screen.contains("Basins t̂0×w0"), "{screen}");
        // The bottom border names the cursor's α and its attractors with their shares.
        let g = &a.panels.global;
        let step = &g.steps[g.cursor];
        let alpha = format!("α {}", bouncemap_engine::fmt_value(step.alpha));
        assert!(screen.contains(&alpha), "{alpha} {screen}");
        let first = format!(
            "{}: {:.1}%",
            step.members[0].track + 1,
            100.0 * step.members[0].fraction
        );
        assert!(screen.contains(&first), "{first} {screen}");
        assert!(screen.contains('▲'), "the cursor: {screen}");
        // Enter brings the diagram back; `A` again and then the plane key put it away too.
        a.handle(Action::Enter);
        assert_eq!(a.panels.in_slot(Slot::Diagram), Some(Target::Diagram));
        a.handle(Action::ToggleGlobal);
        assert_eq!(a.panels.in_slot(Slot::Diagram), Some(Target::Global));
        a.handle(Action::TogglePlane);
        assert_eq!(a.panels.in_slot(Slot::Diagram), Some(Target::Plane));
    }
    workers.cancel_all();
}

#[test]
fn export_view_draws_the_attractors_along_alpha() {
    // `E` with the view shown writes `figure attractors` of the values done, with the
    // diagram and the phase plot, all at once.
    let workers = Workers::new(Executor::new(2).unwrap());
    let mut a = cubic_app();
    size(&mut a, 100, 30);
    crate::tui_common::fill(&mut a);
    a.handle(Action::ToggleGlobal);
    run_until(&mut a, &workers, &|a| a.panels.global.done);
    workers.cancel_all();
    a.handle(Action::ToggleBasins); // the basins' own figure is another test's
    let d = crate::scratch::dir("global", "export");
    let stem = d.join("view");
    assert!(bouncemap::tui::export::prompt_note(true, &a.panels).contains("-attractors.svg/.png"));
    let said = crate::tui_common::export_view_to_end(&mut a, Default::default(), &stem).unwrap();
    assert!(said[0].contains("view-attractors.svg"), "{said:?}");
    let svg = std::fs::read_to_string(d.join("view-attractors.svg")).unwrap();
    // The legend names the view's attractors by their numbers, kinds and α ranges.
    let g = &a.panels.global;
    assert!(g.tracks.len() >= 2);
    for t in &g.tracks[..2] {
        let first = g.steps[t.first]
            .members
            .iter()
            .find(|m| m.track == t.id)
            .unwrap();
        let label = format!(
            "{}: {}",
            t.id + 1,
            bouncemap_figures::global::describe_member(first)
        );
        assert!(svg.contains(&label), "{label}");
    }
    let png = std::fs::read(d.join("view-attractors.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}
