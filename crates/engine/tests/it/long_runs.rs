//! A million events finish in regimes that chatter, stick and release, on every kind of
//! table, with every event finite and time strictly ordered. (No timing is asserted;
//! this guards against hangs and panics.)

use bouncemap_engine::{EventKind, Halt, ImpactMap, Solver, State, System, Table};

fn run(spec: &str, alpha: f64, r: f64, n: usize) -> (usize, [usize; 3], Option<Halt>) {
    let sys = System::new(table(spec), alpha, r).unwrap();
    let v0 = sys.df(0.0) + 0.5;
    let start = State::launch(&sys, 0, 0.0, v0, 0.0).unwrap();
    let mut map = ImpactMap::new(sys, Solver::Exact, start);
    let mut counts = [0usize; 3];
    let mut last = (map.state().period(), map.state().phase());
    for i in 0..n {
        match map.step() {
            Ok(e) => {
                assert!(
                    e.phase.is_finite() && e.v.is_finite() && e.vrel.is_finite(),
                    "{e:?}"
                );
                assert!(
                    (e.period, e.phase) >= last,
                    "time went backwards at event {i}: {e:?}"
                );
                last = (e.period, e.phase);
                counts[match e.kind {
                    EventKind::Impact => 0,
                    EventKind::Stick => 1,
                    EventKind::Release => 2,
                }] += 1;
            }
            Err(h) => return (i, counts, Some(h)),
        }
    }
    (n, counts, None)
}

fn table(spec: &str) -> Table {
    match spec {
        "sine" => Table::sine(),
        "quad" => Table::fd(0.0).unwrap(),
        "cubic" => Table::fd(1.0).unwrap(),
        _ => Table::fd(spec.strip_prefix("fd:").unwrap().parse().unwrap()).unwrap(),
    }
}

#[test]
fn fd_near_chattering_and_sticking_regimes() {
    // α = 0.12: f'' = α(6Dt̂ − 2.1) ≥ −1 everywhere, so the ball chatters to rest for good.
    let (_, counts, halt) = run("fd:0.1", 0.12, 0.8, 1_000_000);
    assert!(matches!(halt, Some(Halt::Resting { .. })), "{halt:?}");
    assert_eq!(counts[1], 1, "one stick, then rest");
    // α = 0.6, r = 0.95: chattering, sticking and release all occur; a million events finish.
    for r in [0.8, 0.95] {
        let (n, counts, halt) = run("fd:0.1", 0.6, r, 1_000_000);
        assert_eq!(n, 1_000_000, "{halt:?}");
        assert!(counts[0] > 0);
    }
    let (n, counts, _) = run("quad", 0.7, 0.95, 1_000_000);
    assert_eq!(n, 1_000_000);
    assert!(
        counts[1] > 0 && counts[2] > 0,
        "quad α = 0.7 r = 0.95 sticks and releases: {counts:?}"
    );
}

#[test]
fn sine_small_alpha_regimes() {
    // 4π²α < 1: once stuck, never released. (With r = 0.5 no (1, 1) orbit exists:
    // it needs f' = (1 − r)/(2(1 + r)) = 1/6 > max f' = 2πα ≈ 0.126.)
    let (_, _, halt) = run("sine", 0.02, 0.5, 1_000_000);
    assert!(matches!(halt, Some(Halt::Resting { .. })), "{halt:?}");
    // 4π²α slightly above 1: stick/release cycles, every one bounded.
    for (alpha, r) in [(0.05, 0.8), (0.05, 0.95), (0.03, 0.95)] {
        let (n, counts, halt) = run("sine", alpha, r, 1_000_000);
        assert_eq!(n, 1_000_000, "{halt:?}");
        assert!(counts[0] > 0);
    }
}

/// Time near the end of i64: the map stops with `TimeOutOfRange` before an event time
/// could wrap (it used to overflow in `period + k`), on every table and in flight or
/// stuck, and never reports an event beyond 2⁵² periods.
#[test]
fn time_at_the_end_of_its_range_stops_instead_of_wrapping() {
    use bouncemap_engine::MAX_EVENT_PERIOD as MAX_PERIOD;
    for (spec, alpha) in [
        ("fd:0.1", 0.45),
        ("fd:0.1", 0.6),
        ("sine", 0.03),
        ("cubic", 0.5),
    ] {
        let sys = System::new(table(spec), alpha, 0.8).unwrap();
        for period in [MAX_PERIOD - 3, i64::MAX - 1, i64::MAX] {
            let st = State::launch(&sys, period, 0.25, sys.df(0.25) + 2.0, 0.0).unwrap();
            let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
            let mut halted = None;
            for _ in 0..10_000 {
                match map.step() {
                    Ok(e) => assert!(e.period <= MAX_PERIOD, "{spec} {period}: {e:?}"),
                    Err(h) => {
                        halted = Some(h);
                        break;
                    }
                }
            }
            assert!(
                matches!(halted, Some(Halt::TimeOutOfRange { .. })),
                "{spec} from period {period}: {halted:?}"
            );
        }
    }
}
