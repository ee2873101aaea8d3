//! Rendering of the terminal application on ratatui's TestBackend from deterministic
//! data: the whole screen at 120×40 and 80×24, each panel, the overlays, the fallbacks
//! (half blocks, too small a terminal). Snapshots live in tests/snapshots/.

use crate::tui_common::{app, fill, render, size, text};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Overlay};
use bouncemap::tui::components::{status, Component};
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
fn the_diagram_sweeps_the_values_parameter_whatever_the_screen() {
    // The data's resolution is the `values` row (exports have as many values), not
    // the screen's: every size sweeps the same values, and a new size only re-bins.
    let mut a = app(Marker::Braille);
    for (w, h) in [(80, 24), (200, 60)] {
        size(&mut a, w, h);
        let spec = a.panels.diagram.sweep_spec(&a.shared);
        assert_eq!(spec.steps, a.shared.params.steps);
    }
    assert_eq!(a.shared.params.steps, 1000, "the sweep command's default");
    a.take_effects();
    size(&mut a, 80, 24);
    size(&mut a, 160, 48);
    assert!(a.take_effects().is_empty(), "a new size sweeps nothing");
}
