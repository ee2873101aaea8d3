//! The terminal application where room and glyphs are short: 80 columns (what a narrow
//! screen leaves out is announced and a key brings it back; the readout keeps the
//! orbit's class), the halfblock and dot markers (no braille anywhere), long messages
//! (the messages overlay shows them whole), the typed line's control keys, one α for
//! the cursor, the table view's breakpoints and `C` outside the plane view.

use crate::tui_common::{app, fill, render, size, text};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Overlay};
use bouncemap::tui::components::{JobMsg, Msg};
use bouncemap::tui::keymap::Action;
use bouncemap::tui::layout::Slot;
use bouncemap::tui::params::ParamId;
use bouncemap_engine::attractors::basins::{BasinSpec, Basins, BasinsJob};
use bouncemap_engine::jobs::{Control, Executor};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

/// Whether `s` holds a braille glyph (the blank pattern included).
fn has_braille(s: &str) -> bool {
    s.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c))
}

/// The basins shown and computed to the end (a small grid, on this thread).
fn with_basins(a: &mut App, w: u16, h: u16) {
    size(a, w, h);
    a.handle(Action::ToggleBasins);
    a.take_effects();
    let spec = BasinSpec {
        nx: 24,
        ny: 12,
        ..BasinSpec::new(a.shared.system())
    };
    a.panels.basins.view.picture = Some(Basins::new(&spec));
    a.panels.basins.view.spec = Some(spec.clone());
    a.panels.basins.view.gen = 3;
    let mut batches = Vec::new();
    Executor::new(2)
        .unwrap()
        .run(BasinsJob::new(spec).unwrap(), &Control::new(), |b| {
            batches.push(b)
        });
    for b in batches {
        a.receive(Msg::Basins(3, JobMsg::Batch(b)));
    }
    a.receive(Msg::Basins(3, JobMsg::Done));
}

/// Under 100 columns the bottom panel left out is named with the key that brings it
/// back; the key cycles which one it is; stepping brings the bounce panel in.
#[test]
fn a_narrow_screen_says_what_it_leaves_out_and_a_key_brings_it_back() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let t = render(&mut a, 80, 24);
    let screen = text(&t);
    let status = screen.lines().last().unwrap();
    assert!(
        status.contains("bounce panel left out: o shows it"),
        "{status}"
    );
    assert!(!screen.contains("Bounce #"), "{screen}");
    assert_eq!(a.shared.left_out, Slot::Bounce);
    // `o`: the phase plot goes, the bounce panel comes.
    a.handle(Action::CyclePanels);
    assert_eq!(a.shared.left_out, Slot::Phase);
    let screen = text(&render(&mut a, 80, 24));
    assert!(
        screen.contains("Bounce #") && !screen.contains("Phase (t̂, v)"),
        "{screen}"
    );
    assert!(screen.contains("phase plot left out"), "{screen}");
    a.handle(Action::CyclePanels);
    a.handle(Action::CyclePanels);
    assert_eq!(a.shared.left_out, Slot::Bounce);
    // A step with the bounce panel left out shows it.
    a.handle(Action::StepOne);
    assert_ne!(a.shared.left_out, Slot::Bounce);
    let screen = text(&render(&mut a, 80, 24));
    assert!(screen.contains("Bounce #"), "{screen}");
    // At full width nothing is left out, and the key says so.
    let screen = text(&render(&mut a, 120, 40));
    for p in ["Bounce #", "Phase (t̂, v)", "Stability of"] {
        assert!(screen.contains(p), "{p}");
    }
    a.handle(Action::CyclePanels);
    let (m, _) = a.shared.message.clone().unwrap();
    assert!(m.contains("all three bottom panels fit"), "{m}");
    // The λ strip is there at 24 rows too.
    assert!(text(&render(&mut a, 80, 24)).contains("λ₁ per impact"));
}

/// At 80 columns the focused diagram's readout keeps the value and its orbit's class,
/// and names the same α as the stability panel.
#[test]
fn the_readout_keeps_the_class_at_80_columns_and_one_alpha() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    size(&mut a, 80, 24);
    a.handle(Action::NextPanel);
    assert_eq!(a.shared.focus, Slot::Diagram);
    for _ in 0..7 {
        a.handle(Action::Right);
    }
    let screen = text(&render(&mut a, 80, 24));
    let title = screen.lines().next().unwrap();
    let r = bouncemap::tui::components::diagram::readout::nearest(&a.panels.diagram).unwrap();
    let status = bouncemap::tui::components::diagram::readout::status(r);
    let alpha = bouncemap::tui::params::fmt_num(r.value);
    assert!(title.contains(&format!("α={alpha} {status}")), "{title}");
    // The stability panel speaks of the same value.
    let evidence = a.shared.at_cursor.clone().unwrap();
    assert!(
        evidence.starts_with(&format!("α {alpha}: {status}")),
        "{evidence}"
    );
}

/// With `--marker halfblock` or `dot` and no colour, no braille glyph appears: not in
/// the diagram, the basins, the legend overlay nor the table view.
#[test]
fn no_braille_anywhere_without_the_braille_marker() {
    for marker in [Marker::HalfBlock, Marker::Dot] {
        let mut a = app(marker);
        fill(&mut a);
        with_basins(&mut a, 120, 40);
        let screen = text(&render(&mut a, 120, 40));
        assert!(screen.contains("Basins"), "{screen}");
        assert!(!has_braille(&screen), "{marker}: {screen}");
        for overlay in [Action::Legend, Action::TableView] {
            a.handle(overlay);
            let screen = text(&render(&mut a, 120, 40));
            assert!(!has_braille(&screen), "{marker} {overlay:?}: {screen}");
            a.handle(Action::Cancel);
        }
    }
    // With braille the same screens do use it (the check can fail).
    let mut a = app(Marker::Braille);
    fill(&mut a);
    with_basins(&mut a, 120, 40);
    assert!(has_braille(&text(&render(&mut a, 120, 40))));
}

/// A message longer than the status line is cut with the key of the messages overlay,
/// which shows every message whole.
#[test]
fn the_messages_overlay_shows_a_cut_message_whole() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let long = format!(
        "export: wrote {}",
        (1..=12)
            .map(|i| format!("file-{i}.png"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    a.shared.say(long.clone(), false);
    let screen = text(&render(&mut a, 80, 24));
    let status = screen.lines().last().unwrap();
    assert!(status.ends_with("… (L more)"), "{status}");
    a.handle(Action::Messages);
    assert_eq!(a.shared.overlay, Overlay::Messages);
    let screen = text(&render(&mut a, 120, 40));
    for i in 1..=12 {
        assert!(screen.contains(&format!("file-{i}.png")), "{i}: {screen}");
    }
    a.handle(Action::Messages);
    assert_eq!(a.shared.overlay, Overlay::None);
}

/// In the export prompt Ctrl-U clears the name and Ctrl-W removes its last word; no
/// control key types its letter.
#[test]
fn control_keys_edit_the_export_name() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    a.handle(Action::ExportView);
    assert!(a.editing());
    let ctrl = |c| KeyEvent::new(KeyCode::Char(c), KeyModifiers::CONTROL);
    a.edit_key(ctrl('u'));
    assert_eq!(a.export_name.as_deref(), Some(""));
    for c in "run-2".chars() {
        a.edit_key(KeyCode::Char(c));
    }
    a.edit_key(ctrl('w'));
    assert_eq!(a.export_name.as_deref(), Some("run-"));
    a.edit_key(ctrl('x'));
    assert_eq!(a.export_name.as_deref(), Some("run-"));
    // The prompt says what `E` adds, the figures included.
    let screen = text(&render(&mut a, 120, 40));
    let status = screen.lines().last().unwrap();
    assert!(status.contains("-diagram.svg/.png"), "{status}");
}

/// The table view marks the breakpoints where F″ jumps: F_0.5 has one at ½, F_1 (one
/// cubic across ½) none inside the period.
#[test]
fn the_table_view_marks_only_breakpoints_where_f2_jumps() {
    let count = |table: &str| {
        let mut a = app(Marker::Braille);
        a.shared.params.set_text(ParamId::Table, table).unwrap();
        a.handle(Action::TableView);
        let screen = text(&render(&mut a, 120, 40));
        screen
            .lines()
            .filter(|l| l.contains('│'))
            .map(|l| l.matches('┆').count())
            .max()
            .unwrap_or(0)
    };
    assert!(count("fd:0.5") >= 1, "F_0.5's f'' jumps at ½");
    assert_eq!(count("fd:1"), 0, "F_1 is one cubic across ½");
}

/// `C` outside the plane view says where the curves are drawn and how to get there,
/// and changes nothing.
#[test]
fn c_outside_the_plane_view_says_where_the_curves_are() {
    let mut a = app(Marker::Braille);
    a.handle(Action::PlaneCurves);
    assert!(!a.shared.show_plane_curves);
    let (m, _) = a.shared.message.clone().unwrap();
    assert!(m.contains("over the plane view: M shows it"), "{m}");
}

/// After `a` (every attractor, 8 starts per value) an export says so everywhere: the
/// csv's specification, the text's header and the figure's caption; the figure is
/// coloured by attractor as the screen is, with its legend.
#[test]
fn an_export_after_all_attractors_says_so_and_colours_by_attractor() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    a.handle(Action::NextPanel);
    a.handle(Action::AllAttractors);
    a.take_effects();
    let dir = std::env::temp_dir().join(format!("bouncemap-all-export-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("all");
    let sizes = bouncemap::tui::export::ExportSizes::default();
    bouncemap::tui::export::export_view(&mut a.shared, &mut a.panels, sizes, &stem).unwrap();
    let csv = std::fs::read_to_string(dir.join("all.csv")).unwrap();
    assert!(csv.contains("\"starts\":8"), "{}", &csv[..300]);
    let txt = std::fs::read_to_string(dir.join("all.txt")).unwrap();
    let head = txt.lines().next().unwrap();
    assert!(
        head.contains("every value from 8 starts") && !head.contains("every value started"),
        "{head}"
    );
    let svg = std::fs::read_to_string(dir.join("all-diagram.svg")).unwrap();
    assert!(svg.contains("each from 8 starts"), "caption");
    assert!(
        svg.contains("attractor 1 (largest basin at its value)"),
        "legend"
    );
    let blue = bouncemap_figures::classes::attractor_colour(1).hex();
    assert!(svg.contains(&blue), "attractor 1's colour {blue}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `t` shows the other coordinate of the points already computed: it re-bins them and
/// starts nothing (the sweep is not run again), focused or not.
#[test]
fn t_rebins_without_running_the_sweep_again() {
    use bouncemap::tui::components::{Effect, Target};
    let mut a = app(Marker::Braille);
    fill(&mut a);
    size(&mut a, 120, 40);
    let plotted = a.panels.diagram.plotted;
    for focus_diagram in [false, true] {
        if focus_diagram {
            a.handle(Action::NextPanel);
        }
        a.take_effects();
        a.handle(Action::ToggleAxis);
        let fx = a.take_effects();
        assert!(!fx.contains(&Effect::Start(Target::Diagram)), "{fx:?}");
        assert_eq!(
            a.panels.diagram.plotted, plotted,
            "the same points, re-binned"
        );
    }
}
