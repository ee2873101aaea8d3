//! Cycles longer than the short detector's 64 events: found by the long-cycle stage of
//! a run and confirmed on the exact map, checked against the continuation's cycles
//! (Newton's method on the (n, k) equations, an independent computation).

use bouncemap_engine::orbits::continuation::{branches, point_at, Options, Start};
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::{Advance, OrbitRun, Outcome};
use bouncemap_engine::{ImpactMap, Solver, State, System, Table};

/// The stable (n, n) cycle of F_1's cascade at `alpha` (from continuation), a run
/// started 1e-6 off it, and what the run says.
fn run_near_cascade_cycle(n: usize, alpha: f64) -> (Outcome, f64) {
    let table = Table::fd(1.0).unwrap();
    let opts = Options {
        max_period: n,
        ..Options::default()
    };
    let bs = branches(&table, 0.8, (0.48, 0.5724), Start::Fixed { k: 1 }, opts).unwrap();
    let b = bs
        .iter()
        .find(|b| b.n == n)
        .expect("the cascade reaches the branch");
    let cp = point_at(&table, 0.8, b, alpha).expect("a point of the branch at alpha");
    assert!(
        cp.stable,
        "the ({n}, {n}) cycle at {alpha} is stable: {:?}",
        cp.multipliers
    );
    let sys = System::new(table, alpha, 0.8).unwrap();
    let start = State::launch(&sys, 0, cp.phases[0] + 1e-6, cp.velocities[0], 0.0).unwrap();
    let map = ImpactMap::new(sys, Solver::Exact, start);
    let mut run = OrbitRun::new(map, 1, Some(Periodicity::default()));
    let end = 200_000;
    let Advance::Done(outcome, points) = run.advance(end, end, &mut |_| false) else {
        panic!("the run ends");
    };
    // The recorded point is on the Newton cycle.
    let p = points[0];
    let d = cp
        .phases
        .iter()
        .zip(&cp.velocities)
        .map(|(ph, v)| {
            let dp = (p.phase - ph).abs();
            dp.min(1.0 - dp).max((p.v - v).abs())
        })
        .fold(f64::INFINITY, f64::min);
    (outcome, d)
}

#[test]
fn a_stable_128_cycle_of_the_cascade_is_found_with_its_n_and_k() {
    // (128, 128) is stable between its birth at α₇ ≈ 0.5723269 and α₈ ≈ 0.5723305.
    let (outcome, d) = run_near_cascade_cycle(128, 0.5723287);
    assert!(
        matches!(
            outcome,
            Outcome::Periodic {
                events: 128,
                periods: 128,
                ..
            }
        ),
        "{outcome:?}"
    );
    assert!(d < 1e-9, "recorded point {d} off the cycle");
}

#[test]
fn a_stable_256_cycle_of_the_cascade_is_found_with_its_n_and_k() {
    let (outcome, d) = run_near_cascade_cycle(256, 0.5723309);
    assert!(
        matches!(
            outcome,
            Outcome::Periodic {
                events: 256,
                periods: 256,
                ..
            }
        ),
        "{outcome:?}"
    );
    assert!(d < 1e-9, "recorded point {d} off the cycle");
}
