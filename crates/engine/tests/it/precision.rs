//! The precision verdict on sticking cycles, against an independent computation: the
//! same release-to-stick paths followed in 16- to 800-digit arithmetic (mpmath, an exact
//! impact map written apart from this engine), which found the cycle's length converge
//! only from about as many digits as the path's growth has decades.

use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::precision::{sticking_cycle, Precision};
use bouncemap_engine::run::{Advance, OrbitRun, Outcome};
use bouncemap_engine::{ImpactMap, Solver, State, System, Table};

/// The sticking cycle the default start settles on, and its verdict.
fn verdict(table: Table, alpha: f64) -> (Outcome, Precision) {
    let sys = System::new(table, alpha, 0.8).unwrap();
    let start = State::start(&sys, 0.0, None, 0.0).unwrap();
    let mut run = OrbitRun::new(
        ImpactMap::new(sys.clone(), Solver::Exact, start),
        1,
        Some(Periodicity::default()),
    );
    let Advance::Done(outcome, _) = run.advance(20_000, 20_000, &mut |_| false) else {
        panic!("the run ends");
    };
    let Outcome::Periodic { events, .. } = outcome else {
        panic!("{outcome:?}");
    };
    let map = ImpactMap::new(sys, Solver::Exact, run.state());
    (
        outcome,
        sticking_cycle(map, events).expect("a sticking cycle"),
    )
}

#[test]
fn sticking_cycles_of_fd_tables_are_beyond_double_precision() {
    // Independent growth from the release to the last impact before the stick:
    // 10^47.6 (fd:0.1, α = 0.6) and 10^54.6 (fd:1, α = 0.59); 50 to 70 digits were
    // needed for the cycle length to converge (112 and 142 table periods).
    for (d, alpha, decades) in [(0.1, 0.6, 47.6), (1.0, 0.59, 54.6)] {
        let (outcome, p) = verdict(Table::fd(d).unwrap(), alpha);
        assert!(!p.resolved, "fd:{d} α = {alpha}: {outcome:?} {p:?}");
        // The f64 path is itself a sample; its growth per impact (0.3–0.5 decades)
        // puts it tens of decades beyond the 13 double precision can carry.
        assert!(
            p.growth_decades > 20.0,
            "fd:{d}: {p:?} (independent: {decades})"
        );
    }
}

#[test]
fn the_sine_at_0035_is_marginal_and_flagged() {
    // Independent: growth 10^13.9 over 67 impacts (0.20 decades per impact) along the
    // exact path; 10^13.9 × 1.1e-16 ≈ 9e-3, over the 1e-3 bound. The f64 path parts
    // from the exact one by 10^14 × 1e-16 at its end, so its own growth differs by a
    // decade or so.
    let (_, p) = verdict(Table::sine(), 0.035);
    assert!((p.growth_decades - 13.9).abs() < 2.0, "{p:?}");
    assert!((60..=75).contains(&p.impacts), "{p:?}");
    assert!(!p.resolved);
}

#[test]
fn a_short_sticking_cycle_is_resolved() {
    // The cubic table at α = 0.47: a stick–release cycle of one table period from the
    // default start, a few flights from release to stick.
    let (outcome, p) = verdict(Table::fd(1.0).unwrap(), 0.47);
    assert!(
        matches!(outcome, Outcome::Periodic { periods: 1, .. }),
        "{outcome:?}"
    );
    assert!(p.resolved && p.growth_decades < 6.0, "{p:?}");
}
