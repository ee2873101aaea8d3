//! The attractor views of the terminal application: period colours and their legend,
//! the Lyapunov strip, all attractors (`a`), the basins panel (`B`), their keys, and
//! the basins panel filling in and restarting with real workers. Data come from the
//! engine (sweeps and basin jobs run here), never from literals.

use crate::tui_common::{buffer_text, size, sweep_msg};
use bouncemap::config::display::ColorMode;
use bouncemap::output::classes::Class;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect};
use bouncemap::tui::components::diagram::colouring::Colouring;
use bouncemap::tui::components::diagram::ALL_STARTS;
use bouncemap::tui::components::{Component, Target};
use bouncemap::tui::components::{JobMsg, Msg, Workers};
use bouncemap::tui::keymap::{Action, Key, Keymap};
use bouncemap::tui::params::{ParamId, Params};
use bouncemap::tui::theme::Theme;
use bouncemap_engine::attractors::basins::{BasinSpec, Basins, BasinsJob};
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::sweep::{self, SweepSpec};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Modifier;
use std::time::{Duration, Instant};

fn key(a: &mut App, c: char) {
    if let Some(act) = a
        .shared
        .keymap
        .action(&KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE))
    {
        a.handle(act);
    }
}

/// The cubic table at α = 0.47, r = 0.8 (the (1,1) solution beside a sticking cycle).
fn cubic_app(mode: ColorMode) -> App {
    let mut params = Params::default();
    params.set_text(ParamId::Table, "cubic").unwrap();
    params.set_text(ParamId::Alpha, "0.47").unwrap();
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

/// Feed the diagram the results of a real sweep of the app's table over [lo, hi].
fn feed_sweep(a: &mut App, lo: f64, hi: f64, steps: usize) {
    let p = &a.shared.params;
    let mut spec = SweepSpec::new(p.table(), p.alpha, p.r, SweepParam::Alpha, lo, hi, steps);
    spec.initial.near_fixed_point = true;
    spec.transient = 200_000;
    spec.keep = 16;
    spec.lyapunov = true;
    let res = sweep::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    a.shared.params.lo = lo;
    a.shared.params.hi = hi;
    let shared = &a.shared;
    a.panels.diagram.sweep_started(1, steps, shared);
    for r in res {
        a.receive(sweep_msg(1, r));
    }
    a.receive(Msg::Diagram(1, JobMsg::Done));
    // A fixed clock for the title.
    a.panels.diagram.started = None;
    a.panels.diagram.elapsed = 2.0;
}

#[test]
fn period_colours_follow_the_class_of_each_value() {
    let mut a = cubic_app(ColorMode::Ansi256);
    size(&mut a, 120, 40);
    // fig3e's window around α_PD: period 1, then period 2.
    feed_sweep(&mut a, 0.46, 0.50, 60);
    let area = Rect::new(0, 0, 90, 24);
    let mut buf = Buffer::empty(area);
    a.panels.diagram.draw(&a.shared, area, &mut buf);
    let theme = Theme::new(ColorMode::Ansi256);
    let colour = |c: Class| theme.class(c).fg.unwrap();
    let mut seen = std::collections::BTreeSet::new();
    for cell in buf.content() {
        if ('\u{2801}'..='\u{28ff}').contains(&cell.symbol().chars().next().unwrap()) {
            for c in Class::ALL {
                if cell.fg == colour(c) {
                    seen.insert(c);
                }
            }
        }
    }
    assert!(
        seen.contains(&Class::Period1) && seen.contains(&Class::Period2),
        "{seen:?}"
    );
    let legend = buffer_text(&buf);
    assert!(
        legend.contains("period 1 2 4 8 n stick stick? chaos ?"),
        "{legend}"
    );
    // `c` switches to density colouring: no class colours left on the plot.
    key(&mut a, 'c');
    assert_eq!(a.panels.diagram.color_by, Colouring::Density);
    let mut buf = Buffer::empty(area);
    a.panels.diagram.draw(&a.shared, area, &mut buf);
    assert!(!buf
        .content()
        .iter()
        .any(|c| c.fg == colour(Class::Period2) && c.symbol() != " "));
    assert!(buffer_text(&buf).contains("density sparse"));
}

#[test]
fn without_colour_the_classes_differ_by_modifier() {
    let mut a = cubic_app(ColorMode::None);
    size(&mut a, 120, 40);
    feed_sweep(&mut a, 0.46, 0.50, 60);
    let area = Rect::new(0, 0, 90, 24);
    let mut buf = Buffer::empty(area);
    a.panels.diagram.draw(&a.shared, area, &mut buf);
    let theme = Theme::new(ColorMode::None);
    let p1 = theme.class(Class::Period1).add_modifier;
    let p2 = theme.class(Class::Period2).add_modifier;
    assert_ne!(p1, p2);
    let plot: Vec<_> = buf
        .content()
        .iter()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(&c.symbol().chars().next().unwrap()))
        .collect();
    assert!(plot.iter().any(|c| c.modifier.contains(Modifier::BOLD)));
    assert!(plot.iter().any(|c| c.modifier == p2));
    assert!(plot.iter().all(|c| c.fg == ratatui::style::Color::Reset));
}

#[test]
fn the_lyapunov_strip_shows_negative_zero_and_positive_exponents() {
    let mut params = Params::default();
    params.set_text(ParamId::Table, "cubic").unwrap();
    let mut a = App::new(
        params,
        Keymap::default(),
        Theme::new(ColorMode::None),
        Marker::Braille,
        15,
    );
    size(&mut a, 120, 40);
    // The end of the cascade: period 8, 16, 32, chaos, then sticking cycles.
    feed_sweep(&mut a, 0.570, 0.576, 49);
    let lyap: Vec<f64> = a
        .panels
        .diagram
        .slots
        .iter()
        .flatten()
        .filter_map(|s| s.lyapunov)
        .collect();
    assert!(lyap.iter().any(|&l| l > 0.02), "{lyap:?}");
    assert!(lyap.iter().any(|&l| l < 0.0 && l.is_finite()));
    assert!(lyap.contains(&f64::NEG_INFINITY));
    let area = Rect::new(0, 0, 90, 24);
    let mut buf = Buffer::empty(area);
    a.panels.diagram.draw(&a.shared, area, &mut buf);
    let s = buffer_text(&buf);
    let strip: Vec<&str> = s.lines().rev().skip(1).take(3).collect();
    assert!(strip.iter().any(|l| l.contains('┄')), "zero line:\n{s}");
    assert!(strip[0].contains('▁'), "−∞ marks on the bottom row:\n{s}");
    assert!(strip.iter().any(|l| l.contains("0┤")), "{s}");
    insta::assert_snapshot!(s);
}

#[test]
fn all_attractors_key_runs_several_starts_and_colours_by_attractor() {
    let mut a = cubic_app(ColorMode::None);
    assert!(!a.panels.diagram.all_attractors);
    key(&mut a, 'a');
    assert!(a.panels.diagram.all_attractors);
    assert_eq!(a.panels.diagram.color_by, Colouring::Attractor);
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    let spec = a.panels.diagram.sweep_spec(&a.shared);
    assert_eq!(spec.starts, ALL_STARTS);
    // Two branches between α = 0.45 and 0.50 on the cubic table: the (1,1) solution
    // and a sticking cycle, at every value.
    let mut spec = SweepSpec {
        lo: 0.45,
        hi: 0.48,
        alpha: 0.45,
        steps: 4,
        transient: 20_000,
        keep: 8,
        ..spec
    };
    spec.initial.near_fixed_point = false;
    let res = sweep::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    for r in &res {
        assert!(
            r.attractors.len() >= 2,
            "α = {}: {:?}",
            r.value,
            r.attractors
        );
    }
    // `c` cycles attractor → density → class → attractor.
    key(&mut a, 'c');
    assert_eq!(a.panels.diagram.color_by, Colouring::Density);
    key(&mut a, 'c');
    assert_eq!(a.panels.diagram.color_by, Colouring::Class);
    key(&mut a, 'c');
    assert_eq!(a.panels.diagram.color_by, Colouring::Attractor);
    key(&mut a, 'a');
    assert!(!a.panels.diagram.all_attractors);
    assert_eq!(a.panels.diagram.sweep_spec(&a.shared).starts, 1);
    assert_eq!(a.panels.diagram.color_by, Colouring::Class);
}

/// A basins panel filled from the engine's job, as the runtime would feed it.
fn filled_basins(a: &mut App, w: u16, h: u16) {
    size(a, w, h);
    a.handle(Action::ToggleBasins);
    assert!(a.panels.basins.view.shown);
    let fx = a.take_effects();
    assert!(fx.contains(&Effect::Start(Target::Basins)), "{fx:?}");
    let spec = BasinSpec {
        nx: 34,
        ny: 18,
        ..BasinSpec::new(a.shared.system())
    };
    a.panels.basins.view.picture = Some(Basins::new(&spec));
    a.panels.basins.view.spec = Some(spec.clone());
    a.panels.basins.view.gen = 7;
    let ex = Executor::new(2).unwrap();
    let mut batches = Vec::new();
    ex.run(BasinsJob::new(spec).unwrap(), &Control::new(), |b| {
        batches.push(b)
    });
    for b in batches {
        a.receive(Msg::Basins(7, JobMsg::Batch(b)));
    }
    a.receive(Msg::Basins(7, JobMsg::Done));
}

#[test]
fn the_basins_panel_shows_both_attractors_with_a_legend() {
    let mut a = cubic_app(ColorMode::None);
    filled_basins(&mut a, 120, 40);
    let b = a.panels.basins.view.picture.as_ref().unwrap();
    assert!(b.complete());
    let t = crate::tui_common::render(&mut a, 120, 40);
    let s = crate::tui_common::text(&t);
    assert!(s.contains("Basins t̂0×w0 · 2 found · done"), "{s}");
    assert!(s.contains("periodic (1, 1) λ -0.2231"), "{s}");
    // A stick–release cycle of one table period; its event count includes the
    // micro-impacts before the stick is detected, so only the period is asserted.
    assert!(
        s.lines()
            .any(|l| l.contains("sticking (") && l.contains(", 1) λ -inf")),
        "{s}"
    );
    assert!(
        !s.contains("Phase plot"),
        "the basins take the phase plot's place"
    );
    // Textures of both attractors in the picture.
    assert!(s.contains('⣿') && s.contains('⠶'), "{s}");
    insta::assert_snapshot!(s);
    // B again: the phase plot is back, the basins job is stopped.
    key(&mut a, 'B');
    assert!(!a.panels.basins.view.shown);
    let s = crate::tui_common::text(&crate::tui_common::render(&mut a, 120, 40));
    assert!(s.contains("Phase (t̂, v)"));
}

#[test]
fn basins_restart_when_alpha_or_r_change_and_not_otherwise() {
    let mut a = cubic_app(ColorMode::None);
    size(&mut a, 120, 40);
    a.handle(Action::ToggleBasins);
    a.take_effects();
    // α nudged: the basins restart; a window edge of the diagram does not touch them.
    a.handle(Action::Right);
    assert!(a.take_effects().contains(&Effect::Start(Target::Basins)));
    a.shared.params.lo = 0.2;
    let before = a.shared.params.clone();
    a.shared.after_change(ParamId::Lo, Ok(()), &before);
    a.handle(Action::Down);
    a.handle(Action::Left);
    assert_eq!(a.selected_param(), ParamId::R);
    assert!(a.take_effects().contains(&Effect::Start(Target::Basins)));
    // Hidden: no restarts.
    a.handle(Action::ToggleBasins);
    a.take_effects();
    a.handle(Action::Left);
    assert!(!a.take_effects().contains(&Effect::Start(Target::Basins)));
}

#[test]
fn the_new_keys_are_configurable_and_listed_in_the_help() {
    let km = Keymap::with(&[(Action::AllAttractors, vec![Key::ch('Y')])]).unwrap();
    let ev = |c| KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE);
    assert_eq!(km.action(&ev('Y')), Some(Action::AllAttractors));
    assert_eq!(km.action(&ev('a')), None);
    assert_eq!(
        Keymap::default().action(&ev('B')),
        Some(Action::ToggleBasins)
    );
    assert_eq!(Keymap::default().action(&ev('c')), Some(Action::Colouring));
    let help = Keymap::default().help();
    assert_eq!(
        Keymap::default().action(&ev('A')),
        Some(Action::ToggleGlobal)
    );
    for a in [
        Action::Colouring,
        Action::AllAttractors,
        Action::ToggleBasins,
        Action::ToggleGlobal,
    ] {
        assert!(help.iter().any(|(_, d)| *d == a.describe()), "{a}");
    }
    for name in ["color_by", "all_attractors", "basins", "attractors_along"] {
        assert!(Action::from_name(name).is_some(), "{name}");
    }
}

#[test]
fn the_basins_panel_fills_in_and_restarts_with_real_workers() {
    let workers = Workers::new(Executor::new(bouncemap_engine::jobs::available_cores()).unwrap());
    let mut a = cubic_app(ColorMode::None);
    size(&mut a, 120, 40);
    a.handle(Action::ToggleBasins);
    a.take_effects();
    let t0 = Instant::now();
    a.start(Target::Basins, &workers);
    let fill = |a: &mut App, until: &dyn Fn(&App) -> bool| -> Duration {
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(20) {
            if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(5)) {
                a.receive(m);
                if until(a) {
                    return t.elapsed();
                }
            }
        }
        panic!("the basins never got there");
    };
    let done = fill(&mut a, &|a| {
        a.panels.basins.view.done && a.panels.basins.view.picture.as_ref().unwrap().complete()
    });
    eprintln!(
        "basins panel complete in {done:?} (grid {:?})",
        a.panels.basins.view.picture.as_ref().unwrap().grid()
    );
    assert!(t0.elapsed() < Duration::from_secs(2), "{:?}", t0.elapsed());
    // α changes: the old picture is dropped, a new one starts at once.
    a.handle(Action::Right);
    assert!(a.take_effects().contains(&Effect::Start(Target::Basins)));
    let old = a.panels.basins.view.gen;
    let t = Instant::now();
    a.start(Target::Basins, &workers);
    assert_ne!(a.panels.basins.view.gen, old);
    let first = fill(&mut a, &|a| {
        a.panels.basins.view.picture.as_ref().unwrap().covered() > 0
    });
    eprintln!("first chunk after the change in {:?}", t.elapsed());
    assert!(first < Duration::from_millis(500), "{first:?}");
    workers.cancel_all();
}

/// `E` with the basins panel shown also writes the basins as figures, computed again at
/// the export's resolution; the messages name every file.
#[test]
fn export_view_writes_the_basins_when_they_are_shown() {
    let mut a = cubic_app(ColorMode::None);
    crate::tui_common::fill(&mut a);
    filled_basins(&mut a, 120, 40);
    let dir = std::env::temp_dir().join(format!("bouncemap-basins-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("b");
    // At the export's own resolution, not the screen's.
    let sizes = bouncemap::tui::export::ExportSizes {
        plane: (40, 20),
        basins: (60, 30),
    };
    let said = crate::tui_common::export_view_to_end(&mut a, sizes, &stem).unwrap();
    let all = said.join("\n");
    for f in [
        "b.csv",
        "b-diagram.png",
        "b-phase.svg",
        "b-basins.svg",
        "b-basins.png",
    ] {
        assert!(all.contains(f), "{f}: {all}");
        assert!(dir.join(f).is_file(), "{f}");
    }
    assert!(all.contains("60×30 starts"), "{all}");
    let svg = std::fs::read_to_string(dir.join("b-basins.svg")).unwrap();
    assert!(
        svg.contains("periodic (1, 1)") && svg.contains("sticking"),
        "legend"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
