//! Rendering of the terminal application on ratatui's TestBackend from deterministic
//! data: the whole screen at 120×40 and 80×24, each panel, the overlays, the fallbacks
//! (half blocks, too small a terminal). Snapshots live in tests/snapshots/.

use crate::tui_common::{app, fill, render, size, text};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect, Overlay};
use bouncemap::tui::components::{status, Component, Target};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

fn panel(f: impl Fn(&App, Rect, &mut Buffer), w: u16, h: u16) -> String {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let area = Rect::new(0, 0, w, h);
    let mut buf = Buffer::empty(area);
    f(&a, area, &mut buf);
    crate::tui_common::buffer_text(&buf)
}

#[test]
fn whole_screen_120x40() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let t = render(&mut a, 120, 40);
    let s = text(&t);
    assert!(s.contains("κ_c = -1.0123"), "{s}");
    assert!(a.panels.diagram.grid.lit_cells() > 100);
    insta::assert_snapshot!(s);
}

#[test]
fn whole_screen_80x24() {
    let mut a = app(Marker::Braille);
    size(&mut a, 80, 24);
    fill(&mut a);
    let t = render(&mut a, 80, 24);
    insta::assert_snapshot!(text(&t));
}

#[test]
fn whole_screen_halfblock() {
    let mut a = app(Marker::HalfBlock);
    size(&mut a, 80, 24);
    fill(&mut a);
    let s = text(&render(&mut a, 80, 24));
    assert!(
        !s.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)),
        "braille in halfblock mode"
    );
    insta::assert_snapshot!(s);
}

#[test]
fn too_small_terminal_shows_a_message() {
    let mut a = app(Marker::Braille);
    let s = text(&render(&mut a, 60, 20));
    assert!(
        s.contains("terminal too small") && s.contains("80×24"),
        "{s}"
    );
    insta::assert_snapshot!(s);
}

#[test]
fn resize_rebins_the_plots() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let big = a.panels.diagram.grid.size();
    let points = a.panels.diagram.grid.points();
    size(&mut a, 80, 24);
    assert_ne!(a.panels.diagram.grid.size(), big);
    assert_eq!(
        a.panels.diagram.grid.points(),
        points,
        "re-binned from the stored points"
    );
}

#[test]
fn panel_parameters() {
    insta::assert_snapshot!(panel(
        |a, r, b| a.panels.parameters.draw(&a.shared, r, b),
        30,
        14
    ));
}

#[test]
fn panel_diagram() {
    insta::assert_snapshot!(panel(
        |a, r, b| a.panels.diagram.draw(&a.shared, r, b),
        90,
        22
    ));
}

#[test]
fn panel_phase_plot() {
    insta::assert_snapshot!(panel(
        |a, r, b| a.panels.phase.draw(&a.shared, r, b),
        40,
        17
    ));
}

#[test]
fn panel_stability() {
    let s = panel(|a, r, b| a.panels.stability.draw(&a.shared, r, b), 40, 17);
    assert!(s.contains("κ_c = -1.0123") && s.contains("stable"), "{s}");
    insta::assert_snapshot!(s);
}

#[test]
fn panel_bounce() {
    let s = panel(|a, r, b| a.panels.bounce.draw(&a.shared, r, b), 40, 17);
    assert!(s.contains("Bounce #3"), "{s}");
    insta::assert_snapshot!(s);
}

#[test]
fn panel_status() {
    insta::assert_snapshot!(panel(
        |a, r, b| status::draw(&a.shared, None, &a.panels.computing(&a.shared), r, b),
        120,
        1
    ));
}

#[test]
fn overlays_help_and_presets() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    a.shared.overlay = Overlay::Help;
    let help = text(&render(&mut a, 120, 40));
    for (keys, _) in a.shared.keymap.help() {
        assert!(help.contains(&keys), "help lacks {keys}");
    }
    insta::assert_snapshot!("help", help);
    a.shared.overlay = Overlay::Presets { selected: 1 };
    insta::assert_snapshot!("presets", text(&render(&mut a, 120, 40)));
}

#[test]
fn enlarging_the_terminal_sweeps_again_at_the_new_resolution() {
    // A sweep at 80×24 has one value per sub-column there; at 160×48 the diagram has
    // more columns than values, so the app asks for a new sweep.
    let mut a = app(Marker::Braille);
    size(&mut a, 80, 24);
    let n = a.panels.diagram.sweep_columns();
    let shared = &a.shared;
    a.panels.diagram.sweep_started(1, n, shared);
    a.take_effects();
    size(&mut a, 80, 24);
    assert!(a.take_effects().is_empty(), "same size: nothing to do");
    size(&mut a, 160, 48);
    assert!(a.panels.diagram.sweep_columns() > n);
    assert_eq!(a.take_effects(), vec![Effect::Start(Target::Diagram)]);
    // Shrinking keeps the values it has: more values than columns is fine.
    let (n, shared) = (a.panels.diagram.sweep_columns(), &a.shared);
    a.panels.diagram.sweep_started(2, n, shared);
    a.take_effects();
    size(&mut a, 80, 24);
    assert!(a.take_effects().is_empty());
}
