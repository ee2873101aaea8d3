//! The screen a physicist sees first, item by item: the first view shows the period
//! doubling, presets and tables bring their own windows and a meaningful α, marks are
//! explained, lines stay visible without colour, messages fit, ranges are the command
//! line's, resizing refines instead of starting over, help fits at 80×24.

use crate::tui_common::{app, buffer_text, fill, render, size, text};
use bouncemap::config::display::ColorMode;
use bouncemap::config::table_spec::TableSpec;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect, Overlay};
use bouncemap::tui::components::legend;
use bouncemap::tui::components::phase_plot::PhasePoints;
use bouncemap::tui::components::Msg;
use bouncemap::tui::components::{Component, Target};
use bouncemap::tui::keymap::{Action, Keymap};
use bouncemap::tui::params::{ParamId, Params, StartMode};

/// The α windows the application opens F_D and the sine with.
fn window(table: &str) -> (f64, f64) {
    TableSpec::parse(table).unwrap().alpha_window()
}
use bouncemap::tui::theme::Theme;
use bouncemap_engine::jobs::Executor;
use bouncemap_engine::orbits::stability_windows;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{self};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Modifier;
use std::time::Instant;

fn alpha_pd(p: &Params) -> f64 {
    stability_windows(&p.table(), p.r, 1).unwrap()[0]
        .alpha_pd()
        .unwrap()
}

/// The first view: fd:0.1 over α ∈ [0.45, 0.60] from the paper's start, a transient of
/// 2·10⁴: its sweep at 120×40 holds the (1,1) branch, the (2,2) window and chaos, and
/// completes within 2 s.
#[test]
fn the_first_view_shows_period_one_period_two_and_chaos() {
    let mut a = app(Marker::Braille);
    assert_eq!((a.shared.params.lo, a.shared.params.hi), window("fd:0.1"));
    assert_eq!(a.shared.params.start, StartMode::NearFixedPoint);
    assert!(a.shared.params.transient >= 20_000);
    size(&mut a, 120, 40);
    let spec = a.panels.diagram.sweep_spec(&a.shared);
    let t = Instant::now();
    let res = sweep::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    let took = t.elapsed();
    let period = |n| {
        res.iter()
            .filter(|r| matches!(r.outcome, Outcome::Periodic { events, .. } if events == n))
            .count()
    };
    assert!(period(1) > 10, "period 1: {}", period(1));
    assert!(
        period(2) >= 1,
        "the (2,2) window (0.50997 to 0.51184) has a value"
    );
    let chaotic = res
        .iter()
        .filter(|r| r.outcome == Outcome::Unsettled && r.lyapunov.is_some_and(|l| l > 0.0))
        .count();
    assert!(chaotic > 3, "chaos after the window: {chaotic}");
    eprintln!("first view: {} values in {took:?}", res.len());
    assert!(took.as_secs_f64() < 2.0, "{took:?}");
}

/// Switching the table's kind brings that kind's window, with α placed just below
/// α_PD inside it; coming back restores the F_D window.
#[test]
fn a_table_of_another_kind_brings_its_window_and_alpha() {
    let mut p = Params::default();
    p.set_text(ParamId::Table, "sine").unwrap();
    assert_eq!((p.lo, p.hi), window("sine"));
    let pd = alpha_pd(&p);
    assert!(p.alpha < pd && p.alpha > p.lo, "α {} α_PD {pd}", p.alpha);
    p.nudge(ParamId::Table, 1, false).unwrap();
    assert_eq!(p.table_label(), "fd:0.1");
    assert_eq!((p.lo, p.hi), window("fd:0.1"));
    assert!(p.alpha < alpha_pd(&p) && p.alpha > p.lo);
    // A D of the same kind keeps the window the user chose.
    p.lo = 0.5;
    p.set_text(ParamId::Family(0), "0.3").unwrap();
    assert_eq!(p.lo, 0.5);
}

/// Sweeping r or D as `sweep --param` does: the window follows the parameter; D only
/// for fd:D tables.
#[test]
fn the_diagram_sweeps_r_or_d() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    for _ in 0..5 {
        a.handle(Action::Down);
    }
    assert_eq!(a.selected_param(), ParamId::Sweep);
    a.handle(Action::Right);
    let spec = a.panels.diagram.sweep_spec(&a.shared);
    assert_eq!(spec.param, bouncemap_engine::jobs::grid::SweepParam::R);
    assert_eq!((spec.lo, spec.hi), (a.shared.params.lo, a.shared.params.hi));
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    // Changing r now moves only the line; changing α restarts the sweep.
    for _ in 0..4 {
        a.handle(Action::Up);
    }
    assert_eq!(a.selected_param(), ParamId::R);
    a.handle(Action::Right);
    assert!(!a.take_effects().contains(&Effect::Start(Target::Diagram)));
    a.handle(Action::Up);
    a.handle(Action::Right);
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    let mut p = Params::default();
    p.set_text(ParamId::Table, "sine").unwrap();
    let e = p.set_text(ParamId::Sweep, "d").unwrap_err();
    assert!(e.contains("valid alpha, r"), "{e}");
}

/// Every mark drawn on the screen is in the legend.
#[test]
fn the_legend_explains_every_mark() {
    let mut a = app(Marker::Braille);
    let all: String = legend::lines(&a.shared)
        .iter()
        .map(|l| l.to_string() + "\n")
        .collect();
    for mark in [
        "│", "┆ ┄", "┃ ━", "B  P", "◆ ◇", "✕", "▁", "λ strip", "stick", "chaos", "dense",
    ] {
        assert!(all.contains(mark), "{mark} missing:\n{all}");
    }
    a.handle(Action::Legend);
    assert_eq!(a.shared.overlay, Overlay::Legend);
    let s = text(&render(&mut a, 120, 40));
    assert!(s.contains("Legend"), "{s}");
    a.handle(Action::Cancel);
    assert_eq!(a.shared.overlay, Overlay::None);
}

/// Without colour the current-α line and the cursor stay visible over dense data
/// (reverse video).
#[test]
fn without_colour_the_lines_over_data_are_reversed() {
    let mut a = App::new(
        Params::default(),
        Keymap::default(),
        Theme::new(ColorMode::None),
        Marker::Braille,
        15,
    );
    size(&mut a, 120, 40);
    fill(&mut a);
    a.handle(Action::NextPanel);
    let t = render(&mut a, 120, 40);
    let buf = t.backend().buffer();
    let plot = a.panels.diagram.plot_area;
    let x = a.panels.diagram.grid.x_range();
    let mut crossed = 0;
    for value in [a.shared.params.alpha, a.panels.diagram.cursor] {
        let col = bouncemap::tui::components::diagram::column(x, plot, value).unwrap();
        for r in plot.y..plot.y + plot.height {
            let cell = &buf[(col, r)];
            if !matches!(cell.symbol(), "│" | "┆" | " " | "┄") {
                crossed += 1;
                assert!(cell.modifier.contains(Modifier::REVERSED), "{cell:?}");
            }
        }
    }
    assert!(crossed > 0, "the lines cross data");
}

/// A long note of the phase plot is shown whole, wrapped.
#[test]
fn the_phase_plots_note_is_not_cut() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    let note = "the ball rests on the table from t = 12 + 0.250000000000 on: f'' ≥ −1 everywhere, so it is never released";
    let shared = &a.shared;
    a.panels.phase.started(3, shared);
    a.receive(Msg::Phase(
        3,
        PhasePoints {
            points: vec![(0.1, 0.2)],
            done: true,
            note: Some(note.into()),
        },
    ));
    let area = Rect::new(0, 0, 40, 17);
    let mut buf = Buffer::empty(area);
    a.panels.phase.draw(&a.shared, area, &mut buf);
    let s = buffer_text(&buf);
    let joined: String = s
        .lines()
        .map(|l| l.trim_matches(|c| c == '│' || c == ' ').to_string())
        .collect::<Vec<_>>()
        .join(" ");
    for word in ["rests", "table", "everywhere,", "released"] {
        assert!(joined.contains(word), "{word}:\n{s}");
    }
    assert!(s.lines().next().unwrap().contains("ended"), "{s}");
}

/// The application accepts what the command line accepts, with the same messages.
#[test]
fn ranges_and_messages_are_the_command_lines() {
    let mut p = Params::default();
    p.set_text(ParamId::Transient, "1e7").unwrap();
    assert_eq!(p.transient, 10_000_000);
    let e = p.set_text(ParamId::Transient, "0").unwrap_err();
    assert!(e.contains("[1, 1e12]"), "{e}");
    p.set_text(ParamId::K, "100").unwrap();
    p.set_text(ParamId::K, "1").unwrap();
    p.set_text(ParamId::Keep, "1000000").unwrap();
    let e = p.set_text(ParamId::V0, "-5").unwrap_err();
    assert!(!e.contains("z0"), "{e}");
    assert!(e.contains("valid v0"), "{e}");
    let e = p.set_text(ParamId::Start, "sideways").unwrap_err();
    assert!(
        e.contains("near-fixed-point, cold, warm, warm-backward"),
        "{e}"
    );
}

/// A refusal is one line in the status bar, not six in the parameters panel.
#[test]
fn a_long_refusal_fits_in_the_status_line() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    a.handle(Action::Enter);
    for c in "5000".chars() {
        a.edit_key(crossterm::event::KeyCode::Char(c));
    }
    a.edit_key(crossterm::event::KeyCode::Enter);
    let (msg, err) = a.shared.message.clone().unwrap();
    assert!(err && msg.contains("(0, 1000]"), "{msg}");
    let s = text(&render(&mut a, 120, 40));
    let last = s.lines().last().unwrap();
    assert!(last.contains("(0, 1000]"), "{last}");
    assert!(!s.lines().take(20).any(|l| l.contains("out of range")));
}

/// Resizing re-bins the values the diagram has; it never sweeps again.
#[test]
fn resizing_rebins_without_sweeping_again() {
    let mut a = app(Marker::Braille);
    size(&mut a, 120, 40);
    fill(&mut a);
    a.take_effects();
    let points = a.panels.diagram.grid.points();
    for (w, h) in [(80, 24), (200, 50)] {
        size(&mut a, w, h);
        assert!(a.take_effects().is_empty(), "{w}x{h} sweeps nothing");
        assert_eq!(a.panels.diagram.grid.points(), points);
    }
}

/// At 80×24 the help scrolls instead of cutting its lines.
#[test]
fn the_help_scrolls_at_80x24() {
    let mut a = app(Marker::Braille);
    a.handle(Action::Help);
    let s = text(&render(&mut a, 80, 24));
    assert!(s.contains("scroll"), "{s}");
    assert!(!s.contains('…'), "no description is cut:\n{s}");
    let first = s.clone();
    a.handle(Action::Down);
    a.handle(Action::Down);
    assert_ne!(text(&render(&mut a, 80, 24)), first);
    assert_eq!(a.shared.overlay, Overlay::Help);
    a.handle(Action::Help);
    assert_eq!(a.shared.overlay, Overlay::None);
}

/// Labels with a combining accent (t̂0) line their values up with the others.
#[test]
fn parameter_values_line_up() {
    let mut a = app(Marker::Braille);
    let s = text(&render(&mut a, 120, 40));
    let col = |label: &str| {
        let l = s.lines().find(|l| l.contains(label)).unwrap();
        let pre = &l[..l.find(label).unwrap()];
        let rest = &l[l.find(label).unwrap() + label.len()..];
        let skip = rest.chars().take_while(|c| *c == ' ').count();
        ratatui::text::Line::from(pre).width() + ratatui::text::Line::from(label).width() + skip
    };
    assert_eq!(col("t̂0"), col("v0"));
    assert_eq!(col("v0"), col("keep"));
}

/// A table file typed at run time is loaded, named in the panel, and kept in the
/// table row's cycle.
#[test]
fn table_files_load_at_run_time_and_show_their_name() {
    let mut a = app(Marker::Braille);
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/tables/quintic.toml");
    let name = bouncemap::config::table_spec::TableSpec::parse(path)
        .unwrap()
        .load()
        .unwrap()
        .name()
        .to_string();
    a.handle(Action::Up);
    a.handle(Action::Up);
    assert_eq!(a.selected_param(), ParamId::Table);
    a.handle(Action::Enter);
    for c in path.chars() {
        a.edit_key(crossterm::event::KeyCode::Char(c));
    }
    a.edit_key(crossterm::event::KeyCode::Enter);
    assert_eq!(a.shared.params.table_label(), name);
    assert!(a.take_effects().contains(&Effect::Start(Target::Diagram)));
    let s = text(&render(&mut a, 120, 40));
    assert!(s.contains(&name), "{s}");
    // sine, F_D, the file, sine …
    a.handle(Action::Right);
    assert_eq!(a.shared.params.table_label(), "sine");
    a.handle(Action::Left);
    assert_eq!(a.shared.params.table_label(), name);
    // A missing file is refused in one line, nothing changes.
    a.handle(Action::Enter);
    for c in "/nonexistent/t.toml".chars() {
        a.edit_key(crossterm::event::KeyCode::Char(c));
    }
    a.edit_key(crossterm::event::KeyCode::Enter);
    assert!(a.shared.message.as_ref().unwrap().1);
    assert_eq!(a.shared.params.table_label(), name);
}
