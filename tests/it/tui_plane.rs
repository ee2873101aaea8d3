//! The plane view of the terminal application (`M`): the picture filling in coarse to
//! fine from the engine's plane job (run here), colours by class with NO_COLOR glyphs,
//! the curves over it, the axes, the legend in the border; the cursor moving the
//! application's α and D; Enter bringing the diagram back at that point; the key in the
//! help; and the first coarse picture with real workers.

use crate::tui_common::size;
use bouncemap::config::display::ColorMode;
use bouncemap::output::classes::Class;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect};
use bouncemap::tui::components::{Component, Target};
use bouncemap::tui::components::{JobMsg, Msg, Workers};
use bouncemap::tui::keymap::{Action, Keymap};
use bouncemap::tui::params::Params;
use bouncemap::tui::theme::Theme;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::plane::{curves, Plane, PlaneJob};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use std::time::{Duration, Instant};

fn app(mode: ColorMode) -> App {
    let mut params = Params::default();
    // A short transient keeps the debug build's plane quick; the picture is the same
    // in outline.
    params.transient = 3000;
    let mut a = App::new(
        params,
        Keymap::default(),
        Theme::new(mode),
        Marker::Braille,
        15,
    );
    a.take_effects();
    a
}

/// Show the plane and feed it the whole job's batches, as the workers would.
fn filled(a: &mut App, w: u16, h: u16) {
    size(a, w, h);
    a.handle(Action::TogglePlane);
    assert!(a.panels.plane.view.shown);
    let fx = a.take_effects();
    assert!(fx.contains(&Effect::Start(Target::Plane)), "{fx:?}");
    let spec = a.panels.plane.spec_for(&a.shared);
    a.panels.plane.view.picture = Some(Plane::new(&spec));
    a.panels.plane.curves = curves(&spec);
    a.panels.plane.view.spec = Some(spec.clone());
    a.panels.plane.view.gen = 7;
    a.panels.plane.place_cursor(&a.shared);
    let mut batches = Vec::new();
    Executor::new(2)
        .unwrap()
        .run(PlaneJob::new(spec).unwrap(), &Control::new(), |b| {
            batches.push(b)
        });
    for b in batches {
        a.receive(Msg::Plane(7, JobMsg::Batch(b)));
    }
    a.receive(Msg::Plane(7, JobMsg::Done));
    // A fixed clock for the title.
    a.panels.plane.view.started = None;
    a.panels.plane.view.elapsed = 1.5;
}

#[test]
fn the_plane_view_shows_classes_curves_axes_and_legend() {
    let mut a = app(ColorMode::None);
    filled(&mut a, 120, 40);
    let p = a.panels.plane.view.picture.as_ref().unwrap();
    assert!(p.complete());
    // The plane's pane alone (the other panels have their own snapshots).
    let pane = bouncemap::tui::layout::layout(
        Rect::new(0, 0, 120, 40),
        bouncemap::tui::layout::Slot::Bounce,
    )
    .unwrap()
    .diagram;
    let mut buf = Buffer::empty(Rect::new(0, 0, pane.right(), pane.bottom()));
    a.panels.plane.draw(&a.shared, pane, &mut buf);
    let s = crate::tui_common::buffer_text(&buf);
    assert!(s.contains("Plane α×D T=3000 · done 1.5s"), "{s}");
    assert!(s.contains("·1 :2 +4 *8 #n ▒stick ░stick? █chaos"), "{s}");
    assert!(
        s.contains("0.45 ") && s.contains("1.0┤") && s.contains("0.0┤"),
        "{s}"
    );
    // The α_PD curve lies on the boundary between period 1 (·) and what follows it.
    let mut on_boundary = 0;
    for line in s.lines() {
        let chars: Vec<char> = line.chars().collect();
        if let Some(k) = chars.iter().position(|c| *c == 'P') {
            if k > 0 && chars[k - 1] == '·' && chars[k + 1] != '·' {
                on_boundary += 1;
            }
        }
    }
    assert!(on_boundary >= 10, "{on_boundary}: {s}");
    insta::assert_snapshot!(s);
}

#[test]
fn with_colour_each_cell_is_two_pixels_coloured_by_class() {
    let mut a = app(ColorMode::Ansi256);
    filled(&mut a, 120, 40);
    let t = crate::tui_common::render(&mut a, 120, 40);
    let theme = Theme::new(ColorMode::Ansi256);
    let colour = |c: Class| theme.class(c).fg.unwrap();
    let buf = t.backend().buffer();
    let halves: Vec<_> = buf.content().iter().filter(|c| c.symbol() == "▀").collect();
    assert!(halves.len() > 1000, "{}", halves.len());
    for c in [Class::Period1, Class::Period2, Class::Sticking] {
        assert!(
            halves
                .iter()
                .any(|x| x.fg == colour(c) || x.bg == colour(c)),
            "{c:?}"
        );
    }
}

#[test]
fn the_cursor_moves_alpha_and_d_and_enter_sweeps_alpha_there() {
    let mut a = app(ColorMode::None);
    filled(&mut a, 120, 40);
    let spec = a.panels.plane.view.spec.clone().unwrap();
    let (i0, j0) = a.panels.plane.cursor;
    assert_eq!(i0, spec.x.pixel_of(a.shared.params.alpha));
    a.handle(Action::FineRight);
    a.handle(Action::Up);
    a.handle(Action::Up);
    assert_eq!(a.panels.plane.cursor, (i0 + 1, j0 + 2));
    let want_alpha = spec.x.value(i0 + 1);
    let want_d = spec.y.value(j0 + 2);
    assert!(
        (a.shared.params.alpha - want_alpha).abs() < 1e-6,
        "{}",
        a.shared.params.alpha
    );
    assert!((a.shared.params.table.d().unwrap() - want_d).abs() < 1e-6);
    // Every panel follows: the system changed, the plane itself does not restart.
    let fx = a.take_effects();
    for t in [Target::Diagram, Target::Stability, Target::Phase] {
        assert!(fx.contains(&Effect::Start(t)), "{t:?}: {fx:?}");
    }
    assert!(!fx.contains(&Effect::Start(Target::Plane)), "{fx:?}");
    // The diagram's zoom keys do nothing while the plane is shown.
    a.handle(Action::ZoomIn);
    assert!(a.panels.plane.view.shown);
    // Enter: the diagram comes back and sweeps α at that D.
    a.handle(Action::Enter);
    assert!(!a.panels.plane.view.shown);
    assert_eq!(a.shared.params.param, SweepParam::Alpha);
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    let t = crate::tui_common::render(&mut a, 120, 40);
    assert!(crate::tui_common::text(&t).contains("Bifurcation diagram"));
}

#[test]
fn the_plane_key_is_listed_and_configurable() {
    let ev = KeyEvent::new(KeyCode::Char('M'), KeyModifiers::NONE);
    assert_eq!(Keymap::default().action(&ev), Some(Action::TogglePlane));
    assert_eq!(Action::from_name("plane"), Some(Action::TogglePlane));
    let help = Keymap::default().help();
    assert!(help
        .iter()
        .any(|(_, d)| *d == Action::TogglePlane.describe()));
}

#[test]
fn the_first_coarse_picture_arrives_within_a_second_with_real_workers() {
    let workers = Workers::new(Executor::new(bouncemap_engine::jobs::available_cores()).unwrap());
    let mut a = app(ColorMode::None);
    a.shared.params.transient = 20_000;
    size(&mut a, 120, 40);
    a.handle(Action::TogglePlane);
    a.take_effects();
    let t0 = Instant::now();
    a.start(Target::Plane, &workers);
    let wait = |a: &mut App, until: &dyn Fn(&App) -> bool| {
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(120) {
            if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(5)) {
                a.receive(m);
                if until(a) {
                    return;
                }
            }
        }
        panic!("the plane never got there");
    };
    // Every pixel of the view shows something once the first pass is in.
    wait(&mut a, &|a| a.panels.plane.first_picture.is_some());
    let first = t0.elapsed();
    let (nx, ny) = a.panels.plane.view.picture.as_ref().unwrap().size();
    let p = a.panels.plane.view.picture.as_ref().unwrap();
    assert!((0..nx).all(|i| (0..ny).all(|j| p.preview(i, j).is_some())));
    eprintln!("first coarse picture of {nx}x{ny} in {first:?}");
    if !cfg!(debug_assertions) {
        assert!(first < Duration::from_secs(1), "{first:?}");
    }
    wait(&mut a, &|a| a.panels.plane.view.done);
    assert!(a.panels.plane.view.picture.as_ref().unwrap().complete());
    eprintln!("complete in {:?}", t0.elapsed());
    workers.cancel_all();
}

#[test]
fn the_text_pictures_colours_are_the_applications_period_colours() {
    let theme = Theme::new(ColorMode::Ansi256);
    for c in Class::ALL {
        assert_eq!(
            theme.class(c).fg,
            Some(ratatui::style::Color::Indexed(c.ansi256())),
            "{c:?}"
        );
    }
}

/// `E` with the plane view shown and complete also writes the plane as figures.
#[test]
fn export_view_writes_the_plane_when_it_is_shown() {
    let mut a = app(ColorMode::None);
    crate::tui_common::fill(&mut a);
    filled(&mut a, 120, 40);
    let dir = std::env::temp_dir().join(format!("bouncemap-plane-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("p");
    let sizes = bouncemap::tui::export::ExportSizes {
        plane: (48, 24),
        basins: (20, 10),
    };
    let said = crate::tui_common::export_view_to_end(&mut a, sizes, &stem).unwrap();
    let all = said.join("\n");
    for f in ["p.csv", "p-diagram.svg", "p-plane.svg", "p-plane.png"] {
        assert!(all.contains(f), "{f}: {all}");
        assert!(dir.join(f).is_file(), "{f}");
    }
    // The export's resolution, not the screen's: 48 × 24 pixels in the figure's data.
    assert!(all.contains("48×24 pixels"), "{all}");
    let svg = std::fs::read_to_string(dir.join("p-plane.svg")).unwrap();
    assert!(
        svg.contains("period 1") && svg.contains("of (1, 1)"),
        "legend"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `C` switches the two-parameter curves on: the work starts in the background, and its
/// result is drawn over the plane (`•` on the (1, 1) period-doubling curve, which lies
/// at the closed-form α_PD the `P` marks show), with its legend; `C` again takes them off.
#[test]
fn the_curves_key_draws_the_two_parameter_curves_over_the_plane() {
    let mut a = app(ColorMode::None);
    filled(&mut a, 120, 40);
    a.handle(Action::PlaneCurves);
    assert!(a.shared.show_plane_curves);
    let fx = a.take_effects();
    assert!(fx.contains(&Effect::Start(Target::PlaneCurves)), "{fx:?}");
    // What the background work computes, delivered as the worker would.
    let spec =
        bouncemap::tui::components::plane::plane_spec(&a.shared.params, (2, 2), a.shared.plane_y);
    let (plane, seeds) = bouncemap::config::plane::plane_curves(&spec, 1, 4, None).unwrap();
    let found = bouncemap_engine::orbits::curves::curves(&plane, seeds).unwrap();
    assert!(found
        .curves
        .iter()
        .any(|c| c.n == 1 && c.kind.as_str() == "period_doubling"));
    a.panels.plane_curves.gen = 3;
    a.receive(Msg::PlaneCurves(3, Ok(found)));
    let pane = bouncemap::tui::layout::layout(
        Rect::new(0, 0, 120, 40),
        bouncemap::tui::layout::Slot::Bounce,
    )
    .unwrap()
    .diagram;
    let mut buf = Buffer::empty(Rect::new(0, 0, pane.right(), pane.bottom()));
    a.panels.plane.draw(&a.shared, pane, &mut buf);
    let s = crate::tui_common::buffer_text(&buf);
    assert!(s.contains("•PD ~F ×BC ◉codim2"), "{s}");
    // On most rows the (1, 1) PD curve's mark sits within a column of the closed-form
    // `P` mark of the same row (the P marks were drawn first and the • over them).
    let mut near = 0;
    for line in s.lines() {
        let chars: Vec<char> = line.chars().collect();
        if let Some(k) = chars.iter().position(|c| *c == 'P') {
            if chars[k.saturating_sub(1)..(k + 2).min(chars.len())].contains(&'•') {
                near += 1;
            }
        } else if chars.contains(&'•') {
            near += 1;
        }
    }
    assert!(near >= 10, "{near}: {s}");
    a.handle(Action::PlaneCurves);
    assert!(!a.shared.show_plane_curves && a.shared.plane_curves.is_none());
}

/// `t` in the plane view turns the vertical axis to the next parameter: F_D's D, then
/// r, then D again; with a two-parameter family file, each of its parameters and r in
/// turn. Each turn restarts the plane, whose spec then has that axis over the
/// parameter's whole range (r over its plane window).
#[test]
fn t_turns_the_planes_vertical_axis_through_r_and_the_familys_parameters() {
    let mut a = app(ColorMode::None);
    filled(&mut a, 120, 40);
    let y = |a: &App| a.panels.plane.spec_for(&a.shared).y.param;
    assert_eq!(y(&a), SweepParam::D);
    let turn = |a: &mut App| {
        a.handle(Action::ToggleAxis);
        let fx = a.take_effects();
        assert!(fx.contains(&Effect::Start(Target::Plane)), "{fx:?}");
        // As the runtime would: the plane restarted on the new spec.
        let spec = a.panels.plane.spec_for(&a.shared);
        a.panels.plane.view.spec = Some(spec.clone());
        spec
    };
    let s = turn(&mut a);
    assert_eq!(s.y.param, SweepParam::R);
    assert!(s.y.lo > 0.0 && s.y.hi < 1.0 && s.y.lo < s.y.hi);
    assert_eq!(turn(&mut a).y.param, SweepParam::D);

    let skewed = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/tables/skewed.toml");
    a.shared
        .params
        .set_text(bouncemap::tui::params::ParamId::Table, skewed)
        .unwrap();
    let table = a.shared.params.table();
    let w = SweepParam::parse("w", &table).unwrap();
    let d = SweepParam::parse("D", &table).unwrap();
    // The D chosen for F_D is the file's D too: the same name.
    assert_eq!(y(&a), d);
    let seen: Vec<SweepParam> = (0..3).map(|_| turn(&mut a).y.param).collect();
    assert_eq!(seen, [SweepParam::R, w, d]);
    let s = a.panels.plane.spec_for(&a.shared);
    assert_eq!((s.y.lo, s.y.hi), (0.0, 1.0));
    // Back to the sine, which has no family: r.
    a.shared
        .params
        .set_text(bouncemap::tui::params::ParamId::Table, "sine")
        .unwrap();
    assert_eq!(y(&a), SweepParam::R);
}
