//! The continued branches in the terminal application: computed for the α window when
//! the table, r, k or the window change (not α), drawn over the diagram with PD and BC
//! on the axis where `fixed` and `two-cycle` put them, and the branch under the
//! diagram's cursor listed in the stability panel with its multipliers.

use crate::tui_common::{app, fill, render, text};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Effect};
use bouncemap::tui::components::Msg;
use bouncemap::tui::components::Target;
use bouncemap::tui::keymap::Action;
use bouncemap::tui::layout::Slot;
use bouncemap::tui::params::ParamId;
use bouncemap::tui::skeleton::compute;
use bouncemap_engine::orbits::stability_windows;
use bouncemap_engine::orbits::two_cycle::{border_collision, two_cycle};
use bouncemap_engine::{System, Table};

/// Change a parameter row as typing it does.
fn set(a: &mut App, id: ParamId, value: &str) {
    let before = a.shared.params.clone();
    let r = a.shared.params.set_text(id, value);
    a.shared.after_change(id, r, &before);
}

fn alpha_pd(table: &Table, r: f64) -> f64 {
    stability_windows(table, r, 1).unwrap()[0]
        .alpha_pd()
        .unwrap()
}

/// The app with the skeleton of its window delivered as the worker would.
fn with_branches(a: &mut App) {
    let p = &a.shared.params;
    let sk = compute(p.table(), p.r, p.k, (p.lo, p.hi));
    let gen = a.panels.branches.gen;
    a.receive(Msg::Branches(gen, sk));
}

#[test]
fn the_skeleton_is_recomputed_for_the_window_not_for_alpha() {
    let mut a = app(Marker::Braille);
    set(&mut a, ParamId::R, "0.7");
    a.handle(Action::Cancel);
    assert!(a.take_effects().contains(&Effect::Start(Target::Branches)));
    set(&mut a, ParamId::Alpha, "0.5");
    a.handle(Action::Cancel);
    assert!(!a.take_effects().contains(&Effect::Start(Target::Branches)));
}

#[test]
fn pd_and_bc_are_marked_where_fixed_and_two_cycle_put_them() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    // Zoom the window to α_PD … a little past the border collision, so the two marks
    // are apart by many columns.
    let table = a.shared.params.table();
    let (pd, bc) = (
        alpha_pd(&table, 0.8),
        border_collision(&table, 0.8, 1).unwrap().alpha,
    );
    let (lo, hi) = (pd - 0.002, bc + 0.002);
    a.shared
        .params
        .set_text(ParamId::Lo, &lo.to_string())
        .unwrap();
    a.shared
        .params
        .set_text(ParamId::Hi, &hi.to_string())
        .unwrap();
    with_branches(&mut a);
    let s = text(&render(&mut a, 120, 40));
    let axis = s
        .lines()
        .find(|l| l.contains('└'))
        .unwrap_or_else(|| panic!("{s}"));
    // Columns of the plot: from the axis corner to the panel's border.
    let start = axis.chars().position(|c| c == '└').unwrap() + 1;
    let width = axis.chars().count() - start - 1;
    let col_of = |x: f64| start + ((x - lo) / (hi - lo) * width as f64) as usize;
    let find = |label: &str| {
        let b = axis
            .find(label)
            .unwrap_or_else(|| panic!("no {label}:\n{axis}"));
        axis[..b].chars().count()
    };
    // Each label starts at its column, or up to four columns aside where a tick label
    // is in the way.
    assert!(find("PD").abs_diff(col_of(pd)) <= 5, "{axis}");
    assert!(find("BC").abs_diff(col_of(bc)) <= 5, "{axis}");
    assert!(find("PD") < find("BC"));
}

#[test]
fn the_branch_under_the_cursor_is_the_two_cycle_with_its_multipliers() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    with_branches(&mut a);
    let table = a.shared.params.table();
    let (pd, bc) = (
        alpha_pd(&table, 0.8),
        border_collision(&table, 0.8, 1).unwrap().alpha,
    );
    let alpha = 0.5 * (pd + bc);
    // The branch is described at the value the readout describes: the computed value
    // nearest the cursor (one α on the screen).
    a.shared.focus = Slot::Diagram;
    a.panels.diagram.cursor = alpha;
    let at = bouncemap::tui::components::diagram::readout::nearest(&a.panels.diagram)
        .map_or(alpha, |r| r.value);
    assert!((at - alpha).abs() < 0.25 * (bc - pd), "{at} {alpha}");
    let sys = System::new(table, at, 0.8).unwrap();
    let two = two_cycle(&sys, 1).unwrap();
    // Put the diagram's cursor on the 2-cycle's first phase at that α.
    a.panels.diagram.ycursor = two.phase0;
    a.handle(Action::Cancel);
    let (i, p) = a
        .shared
        .under_cursor
        .clone()
        .expect("a branch under the cursor");
    let sk = a.shared.branches.clone().unwrap().unwrap();
    assert_eq!((sk.branches[i].n, sk.branches[i].k), (2, 2));
    // The same cycle as the paper's (2, 2) equations solved by Newton in `two-cycle`.
    let near = |x: f64, ys: &[f64]| ys.iter().any(|&y| (x - y).abs() < 1e-9);
    assert!(
        near(two.phase0, &p.phases) && near(two.phase1, &p.phases),
        "{p:?}"
    );
    assert!(p.stable);
    // Multipliers: the same pair (their product is det = r⁴ either way).
    let m = |c: [bouncemap_engine::Complex; 2]| {
        let mut v: Vec<(f64, f64)> = c.iter().map(|z| (z.re, z.im.abs())).collect();
        v.sort_by(|x, y| x.partial_cmp(y).unwrap());
        v
    };
    for (x, y) in m(p.multipliers).iter().zip(m(two.multipliers)) {
        assert!(
            (x.0 - y.0).abs() < 1e-7 && (x.1 - y.1).abs() < 1e-7,
            "{x:?} {y:?}"
        );
    }
    let s = text(&render(&mut a, 120, 40));
    assert!(s.contains("branch (2, 2) at α"), "{s}");
    assert!(s.contains("stable") && s.contains("μ "), "{s}");
    // Without the focus on the diagram, nothing is listed.
    a.shared.focus = Slot::Params;
    a.handle(Action::Cancel);
    assert!(a.shared.under_cursor.is_none());
}

#[test]
fn r_and_d_sweeps_show_no_branches() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    with_branches(&mut a);
    assert!(matches!(a.shared.branches, Some(Ok(_))));
    set(&mut a, ParamId::Sweep, "r");
    a.handle(Action::Cancel);
    assert!(a.take_effects().contains(&Effect::Start(Target::Branches)));
}
