//! Keys map to the right actions, and actions change the state as documented.

use crate::tui_common::{app, fill, size};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{Effect, Overlay};
use bouncemap::tui::components::diagram::Axis;
use bouncemap::tui::components::phase_plot::PhasePoints;
use bouncemap::tui::components::Msg;
use bouncemap::tui::components::Target;
use bouncemap::tui::layout::Slot;
use bouncemap::tui::params::ParamId;
use bouncemap_engine::{ImpactMap, Solver};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

fn press(a: &mut bouncemap::tui::app::App, code: KeyCode, m: KeyModifiers) {
    if a.editing() {
        a.edit_key(code);
    } else if let Some(act) = a.shared.keymap.action(&KeyEvent::new(code, m)) {
        a.handle(act);
    }
}

fn key(a: &mut bouncemap::tui::app::App, c: char) {
    press(a, KeyCode::Char(c), KeyModifiers::NONE)
}

#[test]
fn stepping_matches_the_impact_map_exactly_and_steps_back() {
    let mut a = app(Marker::Braille);
    let sys = a.shared.system();
    let mut map = ImpactMap::new(
        sys.clone(),
        Solver::Exact,
        a.shared.params.initial(&sys).unwrap(),
    );
    key(&mut a, 'n');
    assert_eq!(a.panels.bounce.index(), 1);
    let e = map.step().unwrap();
    assert_eq!(a.panels.bounce.events[0], e);
    press(&mut a, KeyCode::Char('N'), KeyModifiers::SHIFT);
    assert_eq!(a.panels.bounce.index(), 11);
    for i in 1..11 {
        assert_eq!(a.panels.bounce.events[i], map.step().unwrap());
    }
    let stepped = a.panels.bounce.events.clone();
    key(&mut a, 'b');
    key(&mut a, 'b');
    assert_eq!(a.panels.bounce.index(), 9);
    key(&mut a, 'n');
    assert_eq!(
        a.panels.bounce.events[9], stepped[9],
        "the event stepped again is the one stepped back over"
    );
    assert_eq!(a.panels.bounce.index(), 10);
    // Stepping again after going back gives the same events as before.
    let mut fresh = ImpactMap::new(
        sys.clone(),
        Solver::Exact,
        a.shared.params.initial(&sys).unwrap(),
    );
    for e in &a.panels.bounce.events {
        assert_eq!(*e, fresh.step().unwrap());
    }
}

#[test]
fn nudging_alpha_restarts_phase_and_orbits_but_not_the_alpha_sweep() {
    let mut a = app(Marker::Braille);
    assert_eq!(a.selected_param(), ParamId::Alpha);
    press(&mut a, KeyCode::Right, KeyModifiers::NONE);
    assert!((a.shared.params.alpha - 0.46).abs() < 1e-12);
    let fx = a.take_effects();
    assert!(
        fx.contains(&Effect::Start(Target::Phase))
            && fx.contains(&Effect::Start(Target::Stability))
    );
    assert!(!fx.contains(&Effect::Start(Target::Diagram)));
    press(&mut a, KeyCode::Left, KeyModifiers::SHIFT);
    assert!((a.shared.params.alpha - 0.459).abs() < 1e-12);
}

#[test]
fn changing_r_restarts_everything() {
    let mut a = app(Marker::Braille);
    press(&mut a, KeyCode::Down, KeyModifiers::NONE);
    assert_eq!(a.selected_param(), ParamId::R);
    press(&mut a, KeyCode::Left, KeyModifiers::NONE);
    assert!((a.shared.params.r - 0.79).abs() < 1e-12);
    let fx = a.take_effects();
    for e in [
        Effect::Start(Target::Diagram),
        Effect::Start(Target::Phase),
        Effect::Start(Target::Stability),
    ] {
        assert!(fx.contains(&e), "{e:?} missing");
    }
}

#[test]
fn typed_values_are_set_or_refused_inline_with_the_range() {
    let mut a = app(Marker::Braille);
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    for c in "0.3".chars() {
        press(&mut a, KeyCode::Char(c), KeyModifiers::NONE);
    }
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.shared.params.alpha, 0.3);
    a.take_effects();
    let before = a.shared.params.clone();
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    for c in "2000".chars() {
        press(&mut a, KeyCode::Char(c), KeyModifiers::NONE);
    }
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.shared.params, before, "nothing else changes");
    assert!(a.take_effects().is_empty());
    let (msg, err) = a.shared.message.clone().unwrap();
    assert!(err && msg.contains("(0, 1000]"), "{msg}");
    // Text that is not a number.
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    key(&mut a, 'x');
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert!(a
        .shared
        .message
        .as_ref()
        .unwrap()
        .0
        .contains("not a number"));
    // r at its edge is refused by the nudge, unchanged.
    a.shared.params.set_text(ParamId::R, "0.995").unwrap();
    a.panels.parameters.selected = ParamId::R;
    press(&mut a, KeyCode::Right, KeyModifiers::NONE);
    assert_eq!(a.shared.params.r, 0.995);
    assert!(a.shared.message.as_ref().unwrap().0.contains("(0, 1)"));
}

#[test]
fn diagram_zoom_marks_stack_and_enter_sets_alpha() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    let (lo0, hi0) = (a.shared.params.lo, a.shared.params.hi);
    let step = (hi0 - lo0) / 20.0;
    press(&mut a, KeyCode::Tab, KeyModifiers::NONE);
    assert_eq!(a.shared.focus, Slot::Diagram);
    let c0 = a.panels.diagram.cursor;
    key(&mut a, 'm');
    press(&mut a, KeyCode::Right, KeyModifiers::NONE);
    press(&mut a, KeyCode::Right, KeyModifiers::NONE);
    key(&mut a, 'm');
    assert!(
        (a.shared.params.lo - c0).abs() < 1e-9
            && (a.shared.params.hi - (c0 + 2.0 * step)).abs() < 1e-9,
        "{:?}",
        (a.shared.params.lo, a.shared.params.hi)
    );
    assert_eq!(
        a.panels.diagram.y_view, None,
        "same height: a horizontal zoom only"
    );
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    key(&mut a, '+');
    assert!((a.shared.params.hi - a.shared.params.lo - step).abs() < 1e-9);
    key(&mut a, 'z');
    key(&mut a, 'z');
    assert_eq!((a.shared.params.lo, a.shared.params.hi), (lo0, hi0));
    key(&mut a, 'z');
    assert!(
        a.shared.message.as_ref().unwrap().1,
        "empty zoom stack is reported"
    );
    // Two corners in one column at different heights: a vertical zoom, no new sweep.
    let y_before = a.panels.diagram.ycursor;
    key(&mut a, 'm');
    for _ in 0..4 {
        press(&mut a, KeyCode::Up, KeyModifiers::NONE);
    }
    assert!(a.panels.diagram.ycursor > y_before);
    a.take_effects();
    key(&mut a, 'm');
    let (ylo, yhi) = a.panels.diagram.y_view.expect("a vertical window");
    assert!((ylo - y_before).abs() < 1e-12 && yhi > ylo);
    assert_eq!(a.panels.diagram.grid.y_range().lo, ylo);
    assert!(!a.take_effects().contains(&Effect::Start(Target::Diagram)));
    assert_eq!((a.shared.params.lo, a.shared.params.hi), (lo0, hi0));
    key(&mut a, 'z');
    assert_eq!(a.panels.diagram.y_view, None);
    assert_eq!(a.panels.diagram.grid.y_range().lo, 0.0);
    // A box: both directions at once.
    key(&mut a, 'm');
    press(&mut a, KeyCode::Right, KeyModifiers::NONE);
    press(&mut a, KeyCode::Down, KeyModifiers::NONE);
    press(&mut a, KeyCode::Down, KeyModifiers::NONE);
    key(&mut a, 'm');
    assert!(
        a.panels.diagram.y_view.is_some() && a.shared.params.hi - a.shared.params.lo < hi0 - lo0
    );
    key(&mut a, 'z');
    assert_eq!(
        (
            (a.shared.params.lo, a.shared.params.hi),
            a.panels.diagram.y_view
        ),
        ((lo0, hi0), None)
    );
    press(&mut a, KeyCode::Left, KeyModifiers::NONE);
    a.take_effects();
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert!((a.shared.params.alpha - a.panels.diagram.cursor).abs() < 1e-12);
    assert!(a.take_effects().contains(&Effect::Start(Target::Phase)));
}

#[test]
fn toggle_axis_pause_help_presets_export_quit() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let lit = a.panels.diagram.grid.lit_cells();
    key(&mut a, 't');
    assert_eq!(a.panels.diagram.axis, Axis::Velocity);
    assert_eq!(
        a.panels.diagram.grid.points() as usize,
        a.panels.diagram.plotted
    );
    key(&mut a, 't');
    assert_eq!(a.panels.diagram.grid.lit_cells(), lit);
    key(&mut a, ' ');
    assert!(a.shared.paused);
    assert_eq!(a.take_effects(), vec![Effect::Pause(true)]);
    key(&mut a, ' ');
    assert_eq!(a.take_effects(), vec![Effect::Pause(false)]);
    press(&mut a, KeyCode::Char('?'), KeyModifiers::SHIFT);
    assert_eq!(a.shared.overlay, Overlay::Help);
    key(&mut a, 'n'); // ignored under the overlay
    assert_eq!(a.panels.bounce.index(), 3);
    press(&mut a, KeyCode::Esc, KeyModifiers::NONE);
    assert_eq!(a.shared.overlay, Overlay::None);
    key(&mut a, 'p');
    press(&mut a, KeyCode::Down, KeyModifiers::NONE);
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.shared.params.table_label(), "fd:0.1");
    let last = a.presets.len() - 4;
    a.shared.overlay = Overlay::Presets { selected: last };
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.shared.params.table_label(), "sine");
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    // α is placed just below the sine's α_PD (the fixed command's value), inside the
    // preset's window, not clamped to its edge.
    let sys = a.shared.system();
    let pd = bouncemap_engine::orbits::stability_windows(sys.table(), sys.r(), 1).unwrap()[0]
        .alpha_pd()
        .unwrap();
    assert!(
        a.shared.params.alpha < pd && a.shared.params.alpha > a.shared.params.lo,
        "{} vs {pd}",
        a.shared.params.alpha
    );
    assert!(pd - a.shared.params.alpha < 0.05 * (a.shared.params.hi - a.shared.params.lo));
    key(&mut a, 'e');
    assert!(a.editing());
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.take_effects(), vec![Effect::Export]);
    press(&mut a, KeyCode::Char('c'), KeyModifiers::CONTROL);
    assert!(a.quit);
}

#[test]
fn stale_generations_are_dropped() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    let shared = &a.shared;
    a.panels.phase.started(5, shared);
    let chunk = || PhasePoints {
        points: vec![(0.5, 0.5)],
        done: true,
        note: None,
    };
    a.receive(Msg::Phase(4, chunk()));
    assert!(a.panels.phase.points.is_empty() && !a.panels.phase.done);
    a.receive(Msg::Phase(5, chunk()));
    assert_eq!(a.panels.phase.points.len(), 1);
}

#[test]
fn export_writes_csv_and_braille_text_under_a_typed_name() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let dir = std::env::temp_dir().join(format!("bouncemap-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // `e` opens the name prompt with the first free default name; Esc cancels.
    key(&mut a, 'e');
    assert!(a.editing());
    assert!(a
        .export_name
        .as_ref()
        .unwrap()
        .starts_with("bouncemap-diagram-"));
    press(&mut a, KeyCode::Esc, KeyModifiers::NONE);
    assert!(!a.editing() && a.take_effects().is_empty());
    key(&mut a, 'e');
    a.export_name = Some(String::new());
    for c in dir.join("run").to_str().unwrap().chars() {
        press(&mut a, KeyCode::Char(c), KeyModifiers::NONE);
    }
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert!(a.take_effects().contains(&Effect::Export));
    assert!(!a.editing());
    let stem = std::path::PathBuf::from(a.export_pending.clone().unwrap());
    let (csv, txt) = bouncemap::tui::export::export(&a.shared, &a.panels, &stem).unwrap();
    assert_eq!(csv, dir.join("run.csv"));
    let c = std::fs::read_to_string(&csv).unwrap();
    // A sweep file as `bouncemap sweep` writes it: provenance, header row, rows, end.
    assert!(
        c.starts_with("# bouncemap ") && c.contains("\n# spec {"),
        "{c}"
    );
    let data: Vec<&str> = c.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(data.len(), 1 + a.panels.diagram.plotted);
    // The diagram measures every value's exponent (its strip), so the file has it too.
    assert_eq!(
        data[0],
        "index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades,lyapunov"
    );
    assert!(c.lines().last().unwrap().starts_with("# end 120 values"));
    // The text has a title with the window, axes and labels.
    let t = std::fs::read_to_string(&txt).unwrap();
    assert!(t.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)));
    let first = t.lines().next().unwrap();
    assert!(
        first.contains("alpha = ") && first.contains("fd:0.1"),
        "{t}"
    );
    assert!(
        t.contains("1.0 ┤") && t.contains("0.0 ┤") && t.contains("alpha"),
        "{t}"
    );
    // An existing name is refused and the files stay as they were.
    let e = bouncemap::tui::export::export(&a.shared, &a.panels, &stem).unwrap_err();
    assert!(e.contains("exists"), "{e}");
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), c);
    let next = bouncemap::tui::export::free_name(&dir, false);
    assert_eq!(next, "bouncemap-diagram-1");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn export_view_writes_the_diagram_and_phase_plot_as_figures() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    let dir = std::env::temp_dir().join(format!("bouncemap-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    press(&mut a, KeyCode::Char('E'), KeyModifiers::SHIFT);
    assert!(a.editing() && a.export_view);
    assert!(a
        .export_name
        .as_ref()
        .unwrap()
        .starts_with("bouncemap-view-"));
    a.export_name = Some(dir.join("v1.5").to_str().unwrap().to_string());
    press(&mut a, KeyCode::Enter, KeyModifiers::NONE);
    assert_eq!(a.take_effects(), vec![Effect::Export]);
    let stem = std::path::PathBuf::from(a.export_pending.clone().unwrap());
    let sizes = bouncemap::tui::export::ExportSizes::default();
    let said =
        bouncemap::tui::export::export_view(&mut a.shared, &mut a.panels, sizes, &stem).unwrap();
    let names = [
        "v1.5.csv",
        "v1.5.txt",
        "v1.5-diagram.svg",
        "v1.5-diagram.png",
        "v1.5-phase.svg",
        "v1.5-phase.png",
    ];
    let written: Vec<std::path::PathBuf> = names.iter().map(|n| dir.join(n)).collect();
    for (n, p) in names.iter().zip(&written) {
        assert!(said.contains(&p.display().to_string()), "{n}: {said}");
    }
    for p in &written {
        let bytes = std::fs::read(p).unwrap();
        if p.extension().unwrap() == "png" {
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
            assert!(bytes.len() > 5_000, "{p:?}: {} bytes", bytes.len());
        }
        if p.extension().unwrap() == "svg" {
            let t = String::from_utf8(bytes).unwrap();
            assert!(t.contains("<svg") && t.trim_end().ends_with("</svg>"));
            assert!(
                t.contains("fd:0.1") && t.contains("0.45"),
                "the caption names the parameters"
            );
        }
    }
    // Nothing is replaced: a second export under the same name is refused.
    let e = bouncemap::tui::export::export_view(&mut a.shared, &mut a.panels, sizes, &stem)
        .unwrap_err();
    assert!(e.contains("exists"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
