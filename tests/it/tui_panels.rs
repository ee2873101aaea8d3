//! The panels a physicist reads beside the diagram: the stability panel's labelled
//! f'' line, eigenvalue moduli and (α, r) axes; the bounce panel's axes, markers,
//! legend and ball glyph (distinct without colour), the first flight before any step, a
//! chattering sequence shown as a sequence, shortest round-trip numbers; the stepped
//! state in the phase plot; the table view.

use crate::tui_common::{app, fill, render, text};
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::app::{App, Overlay};
use bouncemap::tui::components::bounce::{curves, MIN_SPAN};
use bouncemap::tui::keymap::Action;
use bouncemap::tui::params::ParamId;
use bouncemap_engine::{kappa_c, EventKind, ImpactMap, Solver, State, System, Table};

fn screen(a: &mut App, w: u16, h: u16) -> String {
    text(&render(a, w, h))
}

/// The rows of the screen between columns `x0..x1` (one panel's column).
fn column(s: &str, x0: usize, x1: usize) -> Vec<String> {
    s.lines()
        .map(|l| l.chars().skip(x0).take(x1 - x0).collect())
        .collect()
}

#[test]
fn the_stability_panel_labels_kappa_c_and_zero_and_prints_moduli() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let s = screen(&mut a, 120, 40);
    let lines: Vec<&str> = s.lines().collect();
    let band = lines
        .iter()
        .position(|l| l.contains("f'' ─"))
        .unwrap_or_else(|| panic!("no f'' line:\n{s}"));
    // Under the band line: κ_c under its bracket, 0 under the other.
    let (top, ticks) = (lines[band], lines[band + 1]);
    let col = |l: &str, pat: &str| {
        let b = l.find(pat).unwrap();
        l[..b].chars().count()
    };
    let (open, close) = (col(top, "["), col(top, "]"));
    let k = col(ticks, "κ_c");
    assert!(
        k.abs_diff(open) <= 2,
        "κ_c at {k}, bracket at {open}\n{top}\n{ticks}"
    );
    let zero = col(&ticks[ticks.find("κ_c").unwrap()..], " 0 ")
        + 1
        + ticks[..ticks.find("κ_c").unwrap()].chars().count();
    assert!(zero.abs_diff(close) <= 1, "0 at {zero}, bracket at {close}");
    // The stable (1, 1) point's eigenvalues are complex with |λ|² = det J = r²: both
    // moduli are r = 0.8 (an identity, not the program's output).
    assert!(s.contains("|λ| 0.8000, 0.8000"), "{s}");
    // The unstable one's moduli multiply to r² as well.
    let unstable = lines
        .iter()
        .skip_while(|l| !l.contains("◇ unstable"))
        .nth(1)
        .unwrap();
    let nums: Vec<f64> = unstable
        .split("|λ|")
        .nth(1)
        .unwrap()
        .split(['│', ','])
        .take(2)
        .map(|x| x.trim().parse().unwrap())
        .collect();
    assert!(
        (nums[0] * nums[1] - 0.64).abs() < 1e-3,
        "{nums:?}: product should be r² = 0.64"
    );
    // The (α, r) plane has labelled axes, both curves and the current point.
    for label in ["1.0┤", "0.0┤", "r│", "◎", "B", "P"] {
        assert!(s.contains(label), "missing {label}:\n{s}");
    }
    assert!(
        lines.iter().any(|l| l.contains('└') && l.contains(" α ")),
        "{s}"
    );
    let kc = kappa_c(0.8);
    assert!(s.contains(&format!("κ_c = {kc:.4}")));
}

#[test]
fn eigenvalues_outside_the_circle_are_placed_on_a_logarithmic_radius() {
    use bouncemap::tui::components::stability::radial;
    assert_eq!(radial(0.5), 0.5);
    assert_eq!(radial(1.0), 1.0);
    assert!((radial(10.0) - 1.5).abs() < 1e-15);
    assert!((radial(100.0) - 2.0).abs() < 1e-15);
    // Monotone, so the order of moduli is kept.
    let xs: Vec<f64> = (1..200).map(|i| radial(i as f64 * 0.37)).collect();
    assert!(xs.windows(2).all(|w| w[0] < w[1]));
}

#[test]
fn the_bounce_panel_has_axes_a_legend_and_a_ball_distinct_without_colour() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let s = screen(&mut a, 120, 40);
    let right = column(&s, 80, 120).join("\n");
    for label in ["z│", "┤", "└", "table", "ball", "impact", "now", "●", "▾"] {
        assert!(right.contains(label), "missing {label}:\n{right}");
    }
    // The ball's path is drawn in • dots, the table in braille: different glyphs, so the
    // two differ with NO_COLOR (the fixture has no colour).
    assert!(right.contains('•'), "{right}");
    assert!(
        right
            .chars()
            .any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)),
        "{right}"
    );
    // Half blocks: the table in ▀▄█, the ball still in dots.
    let mut h = app(Marker::HalfBlock);
    fill(&mut h);
    let s = screen(&mut h, 120, 40);
    let right = column(&s, 80, 120).join("\n");
    assert!(right.contains('•') && right.contains("▀ table"), "{right}");
}

#[test]
fn before_the_first_step_the_bounce_panel_shows_the_flight_to_come() {
    let mut a = app(Marker::Braille);
    let s = screen(&mut a, 120, 40);
    let right = column(&s, 80, 120).join("\n");
    assert!(right.contains("Bounce #0"), "{right}");
    assert!(right.contains('•') && right.contains('●'), "{right}");
    assert!(right.contains("the next flight"), "{right}");
}

#[test]
fn numbers_in_the_bounce_panel_round_trip() {
    let mut a = app(Marker::Braille);
    a.handle(Action::StepOne);
    let e = *a.panels.bounce.events.last().unwrap();
    let s = screen(&mut a, 120, 40);
    let value = |name: &str| -> f64 {
        let l = s
            .lines()
            .find(|l| l.contains(&format!("│{name} ")))
            .unwrap_or_else(|| panic!("no {name} line:\n{s}"));
        let tail = &l[l.find(&format!("│{name} ")).unwrap() + name.len() + 4..];
        tail.split('│').next().unwrap().trim().parse().unwrap()
    };
    // Shortest round-trip form: the printed text parses back to the same f64.
    assert_eq!(value("v   ").to_bits(), e.v.to_bits(), "{s}");
    assert_eq!(value("vrel").to_bits(), e.vrel.to_bits(), "{s}");
}

#[test]
fn the_stepped_state_is_marked_in_the_phase_plot() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let s = screen(&mut a, 120, 40);
    assert!(!s.contains('▣'), "nothing stepped through the keys yet");
    a.handle(Action::StepOne);
    assert_eq!(
        a.shared.stepped,
        a.panels.bounce.events.last().map(|e| (e.phase, e.v))
    );
    let s = screen(&mut a, 120, 40);
    assert!(column(&s, 0, 40).join("\n").contains('▣'), "{s}");
    // A new start forgets it.
    a.handle(Action::RestartOrbit);
    assert_eq!(a.shared.stepped, None);
}

/// During chattering the impacts come ever closer; the panel shows at least
/// `MIN_SPAN` periods, so the sequence is visible rather than one point.
#[test]
fn a_chattering_sequence_is_shown_over_at_least_a_third_of_a_period() {
    let sys = System::new(Table::fd(0.1).unwrap(), 0.6, 0.8).unwrap();
    let st = State::launch(&sys, 0, 0.0, sys.df(0.0) + 0.5, 0.0).unwrap();
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
    let mut history = vec![st];
    // Step to the first stick: the impacts before it chatter.
    loop {
        let e = map.step().unwrap();
        history.push(*map.state());
        if e.kind == EventKind::Stick {
            break;
        }
        assert!(history.len() < 100_000);
    }
    let c = curves(&sys, &history, 200).unwrap();
    assert!(c.span.1 - c.span.0 >= MIN_SPAN - 1e-12, "{:?}", c.span);
    // The four last flights alone are far shorter than that.
    let n = history.len();
    let four = (history[n - 1].period() - history[n - 5].period()) as f64
        + (history[n - 1].phase() - history[n - 5].phase());
    assert!(four < MIN_SPAN, "{four}");
}

#[test]
fn the_table_view_shows_f_and_its_derivatives_with_breakpoints() {
    let mut a = app(Marker::Braille);
    fill(&mut a);
    a.handle(Action::TableView);
    assert_eq!(a.shared.overlay, Overlay::Table);
    let s = screen(&mut a, 120, 40);
    for label in ["Table fd:0.1", "F│", "F′│", "F″│", "−1/α", "◆", "½"] {
        assert!(s.contains(label), "missing {label}:\n{s}");
    }
    // F_D's breakpoint at t̂ = ½ drawn through the plots (not only in the legend).
    let plots: String = s.lines().filter(|l| !l.contains("breakpoint")).collect();
    assert!(plots.contains('┆'), "{s}");
    a.handle(Action::TableView);
    assert_eq!(a.shared.overlay, Overlay::None);
    // The sine has no breakpoints; at α above 1/(4π²) it has a release phase.
    a.handle(Action::TableView);
    a.handle(Action::Cancel);
    assert_eq!(a.shared.overlay, Overlay::None);
    a.shared.params.set_text(ParamId::Table, "sine").unwrap();
    a.shared.params.set_text(ParamId::Alpha, "0.05").unwrap();
    a.handle(Action::TableView);
    let s = screen(&mut a, 120, 40);
    let plots: String = s.lines().filter(|l| !l.contains("breakpoint")).collect();
    assert!(s.contains("Table sine") && !plots.contains('┆'), "{s}");
    assert!(s.contains('R'), "{s}");
    // At 80×24 it still fits.
    let s = screen(&mut a, 80, 24);
    assert!(s.contains("F″│"), "{s}");
}

/// One meaning per symbol: a mark listed under two panels' headings is one of the few
/// that mean the same thing in each (birth and α_PD of (1,k), the (1,k) solution,
/// events as braille dots); the plane view's glyphs and curve marks are its own.
#[test]
fn no_legend_symbol_has_two_meanings_across_panels() {
    use bouncemap::tui::components::legend::SECTIONS;
    use std::collections::BTreeMap;
    const SAME_EVERYWHERE: [&str; 5] = ["B", "P", "◆", "◇", "⣿"];
    let mut seen: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (heading, rows) in SECTIONS {
        for (sym, _) in rows.iter() {
            // Words ("dots", "lines", "no colour") name a look, not a mark.
            for t in sym.split_whitespace() {
                if t.chars().count() > 1 && t.chars().all(|c| c.is_ascii_lowercase()) {
                    continue;
                }
                let at = seen.entry(t).or_default();
                if !at.contains(heading) {
                    at.push(heading);
                }
            }
        }
    }
    for (t, headings) in &seen {
        assert!(
            headings.len() == 1 || SAME_EVERYWHERE.contains(t),
            "'{t}' is listed under {headings:?}"
        );
    }
    let plane = seen.iter().filter(|(_, h)| h.contains(&"Plane (M)"));
    let marks: Vec<&str> = plane.map(|(t, _)| *t).collect();
    for m in ["·", ":", "+", "*", "#", "x", "B", "P", "C", "╋"] {
        assert!(
            marks.contains(&m),
            "the plane's '{m}' is not in the legend: {marks:?}"
        );
    }
}

/// Every line of the legend fits an 80-column terminal (inside the overlay's border).
#[test]
fn every_legend_line_fits_80_columns() {
    let a = app(Marker::Braille);
    for l in bouncemap::tui::components::legend::lines(&a.shared) {
        assert!(l.width() <= 78, "{} columns: {l}", l.width());
    }
}

/// `W` switches the (1, k) saddle's manifolds on over the phase plot: the work starts
/// in the background, and what it computes (both manifolds of the unstable (1, 1)
/// solution ◇, as `bouncemap manifolds` grows them) is drawn, ▪ unstable, · stable,
/// noted in the panel's title and explained on the status line; a change of α starts
/// it again; `W` again takes them off.
#[test]
fn w_draws_the_saddles_manifolds_over_the_phase_plot() {
    use bouncemap::tui::components::manifold_overlay::lines;
    use bouncemap::tui::components::{Effect, Msg, Target};
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let before = screen(&mut a, 120, 40);
    assert!(!before.contains('▪'), "{before}");
    a.handle(Action::Manifolds);
    assert!(a.shared.show_manifolds);
    let fx = a.take_effects();
    assert!(fx.contains(&Effect::Start(Target::Manifolds)), "{fx:?}");
    // What the worker computes, delivered as it would.
    let sys = a.shared.system();
    let m = lines(&sys, a.shared.params.k, None)
        .unwrap()
        .expect("a saddle at the default α");
    assert_eq!((m.n, m.k), (1, 1));
    // The saddle is the closed-form unstable (1, 1) solution: v* = ½ after the impact.
    assert!((m.saddle[0].1 - 0.5).abs() < 1e-12);
    assert!(m.unstable.len() > 50 && m.stable.len() > 50);
    a.panels.manifolds.gen = 5;
    a.receive(Msg::Manifolds(5, Ok(Some(m))));
    let s = screen(&mut a, 120, 40);
    assert!(s.contains("▪· (1, 1)"), "{s}");
    assert!(s.contains("▪ unstable · stable"), "{s}");
    assert!(s.matches('▪').count() > 10 && s.contains('◇'), "{s}");
    // A change of α starts them again.
    let before = a.shared.params.clone();
    let r = a.shared.params.set_text(ParamId::Alpha, "0.46");
    a.shared.after_change(ParamId::Alpha, r, &before);
    a.handle(Action::Cancel);
    assert!(a.take_effects().contains(&Effect::Start(Target::Manifolds)));
    a.handle(Action::Manifolds);
    assert!(!a.shared.show_manifolds && a.shared.manifolds.is_none());
    let off = screen(&mut a, 120, 40);
    assert!(!off.contains('▪') && !off.contains("▪·"), "{off}");
}

/// With a branch under the diagram's cursor, `W` grows the manifolds of that branch's
/// cycle, solved again at the current α, whatever its (n, k): on F_0.1 past the (2, 2)
/// border collision the doubled cycle is a saddle (real multipliers, one outside the
/// unit circle), and its manifolds, not the (1, 1) one's, are drawn, its impacts marked
/// ◇; where that cycle is no saddle the status line says so.
#[test]
fn w_grows_the_manifolds_of_the_cycle_under_the_cursor() {
    use bouncemap::tui::components::manifold_overlay::lines;
    use bouncemap::tui::components::{Msg, Target};
    use bouncemap_engine::orbits::continuation::{branches, Options, Start};
    let mut a = app(Marker::Braille);
    fill(&mut a);
    let before = a.shared.params.clone();
    let r = a.shared.params.set_text(ParamId::Alpha, "0.6");
    a.shared.after_change(ParamId::Alpha, r, &before);
    let sys = a.shared.system();
    // The (2, 2) branch from the one-parameter continuation, taken at an α beside 0.6.
    let found = branches(
        sys.table(),
        sys.r(),
        (0.45, 0.7),
        Start::Fixed { k: 1 },
        Options {
            max_period: 2,
            ..Options::default()
        },
    )
    .unwrap();
    let two = found.iter().find(|b| b.n == 2).expect("the (2, 2) branch");
    let near = two
        .points
        .iter()
        .filter(|p| (p.alpha - 0.6).abs() > 1e-3)
        .min_by(|x, y| (x.alpha - 0.6).abs().total_cmp(&(y.alpha - 0.6).abs()))
        .unwrap()
        .clone();
    a.shared.under_cursor = Some((0, near.clone()));
    a.handle(Action::Manifolds);
    assert!(a
        .take_effects()
        .contains(&bouncemap::tui::components::Effect::Start(
            Target::Manifolds
        )));
    let s = screen(&mut a, 120, 40);
    assert!(s.contains("the (2, 2) cycle under the cursor"), "{s}");
    // The branch's point is not at the phase plot's α: the message says where it is
    // solved, and how to take α to the cursor.
    let said = &a.shared.message.as_ref().expect("a message").0;
    assert!(
        said.contains("solved at the phase plot's α = 0.6") && said.contains("Enter"),
        "{said}"
    );
    let m = lines(&sys, 1, Some(&near)).unwrap().expect("a saddle");
    assert_eq!((m.n, m.k), (2, 2));
    assert!(m.from_cursor);
    // Its impacts are a (2, 2) cycle at α = 0.6: the exact map, launched from each,
    // comes back to it after two impacts and two table periods.
    for &(t, v) in &m.saddle {
        let st = State::launch(&sys, 0, t, v, 0.0).unwrap();
        let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
        let mut impacts = 0;
        let e = loop {
            let e = map.step().unwrap();
            if e.kind == EventKind::Impact {
                impacts += 1;
                if impacts == 2 {
                    break e;
                }
            }
        };
        assert_eq!(e.period, 2, "({t}, {v})");
        assert!(
            (e.phase - t).abs() < 1e-9 && (e.v - v).abs() < 1e-9,
            "({t}, {v}): {e:?}"
        );
    }
    let again =
        bouncemap_engine::orbits::periodic::cycle(&sys, 2, 2, near.t0, near.velocities[0]).unwrap();
    // The saddle's multipliers: real, one outside and one inside, product r⁴ (det M).
    let [x, y] = again.multipliers;
    assert!(x.im == 0.0 && y.im == 0.0);
    assert!((x.re * y.re - 0.8f64.powi(4)).abs() < 1e-9);
    assert!(x.re.abs().max(y.re.abs()) > 1.0 && x.re.abs().min(y.re.abs()) < 1.0);
    assert!(m.unstable.len() > 20 && m.stable.len() > 20);
    a.panels.manifolds.gen = 7;
    a.receive(Msg::Manifolds(7, Ok(Some(m))));
    let s = screen(&mut a, 120, 40);
    assert!(
        s.contains("▪· (2, 2)") && s.contains("manifolds of the (2, 2) saddle"),
        "{s}"
    );
    assert!(s.matches('◇').count() >= 2, "{s}");
    // Before the border collision the (2, 2) cycle is stable: no saddle, said so.
    let stable = two.points.iter().find(|p| p.stable).unwrap();
    let at = System::new(sys.table().clone(), stable.alpha, sys.r()).unwrap();
    let e = lines(&at, 1, Some(stable)).unwrap_err();
    assert!(
        e.contains("the (2, 2) cycle under the cursor") && e.contains("saddle"),
        "{e}"
    );
}

/// `V` switches proofs on: the work starts in the background; what it proves of the
/// (1, 1) solutions (no cursor on a branch) is shown in the stability panel, the
/// stable one (|λ| < 1 in closed form) proved stable and the saddle proved unstable;
/// the continued branches' points are proved too and counted on the status line, and
/// the marks belong to the skeleton they were made for; new branches and a change of α
/// start the work again; `V` again takes everything off.
#[test]
fn v_proves_the_solutions_and_the_branches() {
    use bouncemap::tui::components::proofs::{prove_asked, prove_branches, ProofMsg};
    use bouncemap::tui::components::{Effect, Msg, Target};
    use bouncemap::tui::skeleton::compute;
    let mut a = app(Marker::Braille);
    fill(&mut a);
    a.handle(Action::Certify);
    assert!(a.shared.show_proofs);
    let fx = a.take_effects();
    assert!(fx.contains(&Effect::Start(Target::Proofs)), "{fx:?}");
    let sys = a.shared.system();
    let k = a.shared.params.k;
    let view = prove_asked(&sys, k, None).unwrap();
    let fps = bouncemap_engine::orbits::fixed_points(&sys, k).unwrap();
    assert_eq!(view.lines.len(), fps.len());
    for (l, p) in view.lines.iter().zip(&fps) {
        let closed_form_stable = p.eigenvalues.iter().all(|e| e.abs() < 1.0);
        let want = if closed_form_stable {
            "proved, stable"
        } else {
            "proved, unstable"
        };
        assert!(l.contains(want), "{l} against {:?}", p.eigenvalues);
    }
    a.panels.proofs.gen = 7;
    a.receive(Msg::Proofs(7, ProofMsg::Cycle(Ok(view))));
    let s = screen(&mut a, 120, 40);
    assert!(s.contains("✓ t̂*") && s.contains("proved, stable"), "{s}");
    // The branches of the window, proved point by point.
    let p = &a.shared.params;
    let sk = compute(p.table(), p.r, p.k, (p.lo, p.hi)).unwrap();
    let marks = prove_branches(&sk);
    assert!(marks.of(&sk).is_some());
    let (all, proved) = marks
        .proved
        .iter()
        .flatten()
        .fold((0, 0), |(a, p), &x| (a + 1, p + usize::from(x)));
    assert!(proved > all / 2 && all > 20, "{proved} of {all}");
    // New branches with proofs on start the proofs again.
    a.take_effects();
    a.panels.branches.gen = 9;
    a.receive(Msg::Branches(9, Ok(sk)));
    assert!(a.take_effects().contains(&Effect::Start(Target::Proofs)));
    a.receive(Msg::Proofs(7, ProofMsg::Branches(marks)));
    let s = screen(&mut a, 120, 40);
    assert!(
        s.contains(&format!("proofs: {proved} of {all} branch points proved")),
        "{s}"
    );
    let before = a.shared.params.clone();
    let r = a.shared.params.set_text(ParamId::Alpha, "0.46");
    a.shared.after_change(ParamId::Alpha, r, &before);
    a.handle(Action::Cancel);
    assert!(a.take_effects().contains(&Effect::Start(Target::Proofs)));
    a.handle(Action::Certify);
    assert!(!a.shared.show_proofs && a.shared.proof.is_none() && a.shared.branch_proofs.is_none());
    let off = screen(&mut a, 120, 40);
    assert!(!off.contains("✓ t̂*"), "{off}");
}
