//! Sweep engine against independent computations: brute-force `ImpactMap` runs to the
//! full transient, closed-form (1, 1) fixed points, and the cancellation and pause
//! contracts.

use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{self, SweepJob, SweepSpec, ValueResult, Warm};
use bouncemap_engine::{EventKind, ImpactMap, Solver, State, System, Table};
use std::time::{Duration, Instant};

/// A private pool of two threads: parked workers of one test never hold threads away
/// from another test running meanwhile.
fn ex() -> Executor {
    Executor::new(2).unwrap()
}

const TOL: f64 = 1e-11;

/// The last `keep` events before period `end` of a plain run from the default start.
fn brute_force(sys: &System, end: i64, keep: usize) -> (Vec<(f64, f64, EventKind)>, bool) {
    let v0 = sys.df(0.0) + 0.5;
    let st = State::launch(sys, 0, 0.0, v0, 0.0).unwrap();
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
    let mut out = std::collections::VecDeque::new();
    loop {
        match map.step() {
            Ok(e) if e.period < end => {
                if out.len() == keep {
                    out.pop_front();
                }
                out.push_back((e.phase, e.v, e.kind));
            }
            Ok(_) => return (out.into(), false),
            Err(_) => return (out.into(), true),
        }
    }
}

fn circ(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

fn spec(table: Table, lo: f64, hi: f64, steps: usize, r: f64) -> SweepSpec {
    let mut s = SweepSpec::new(table, 0.45, r, SweepParam::Alpha, lo, hi, steps);
    s.transient = 20_000;
    s.keep = 50;
    s
}

fn assert_matches_brute_force(b: &ValueResult, sys: &System, end: i64, keep: usize) {
    let (bf, halted) = brute_force(sys, end, keep);
    assert_eq!(
        b.points.len(),
        bf.len(),
        "α = {}: {} points, brute force {}",
        b.value,
        b.points.len(),
        bf.len()
    );
    assert_eq!(
        halted,
        matches!(
            b.outcome,
            Outcome::Resting { .. } | Outcome::NoLanding { .. }
        )
    );
    for (p, q) in b.points.iter().zip(&bf) {
        assert_eq!(p.kind, q.2, "α = {}", b.value);
        assert!(
            circ(p.phase, q.0) <= TOL && (p.v - q.1).abs() <= TOL,
            "α = {} ({:?}): sweep ({}, {}) vs brute force ({}, {})",
            b.value,
            b.outcome,
            p.phase,
            p.v,
            q.0,
            q.1
        );
    }
}

#[test]
fn early_stopped_points_equal_brute_force_runs() {
    // fd:0.1 from the stable (1, 1) band through the period-2 window into chaos,
    // including values close to α_PD ≈ 0.50997 where convergence is slow.
    let s = spec(Table::fd(0.1).unwrap(), 0.40, 0.62, 12, 0.8);
    let result = sweep::collect(&s, &ex()).unwrap();
    assert_eq!(result.len(), 12);
    let mut periodic = 0;
    for b in &result {
        assert!(b.complete);
        let sys = s.system_at(b.value).unwrap();
        assert_matches_brute_force(b, &sys, 20_000, 50);
        if let Outcome::Periodic { stopped_at, .. } = b.outcome {
            periodic += 1;
            assert!(stopped_at < 20_000);
        }
    }
    assert!(periodic >= 6, "only {periodic} values stopped early");
}

#[test]
fn values_near_the_period_doubling_point_agree_with_brute_force() {
    let s = spec(Table::fd(1.0).unwrap(), 0.478, 0.490, 7, 0.8);
    for b in sweep::collect(&s, &ex()).unwrap() {
        let sys = s.system_at(b.value).unwrap();
        assert_matches_brute_force(&b, &sys, 20_000, 50);
    }
}

#[test]
fn sticking_values_are_computed_and_marked() {
    // quad with r = 0.5 and sine with r = 0.3: chattering, sticking and release. The
    // sticking cycles there last up to about a hundred events (on quad, which cycle the
    // transient reaches depends on rounding): 200 kept events cover whole cycles.
    let mut quad = spec(Table::fd(0.0).unwrap(), 0.69, 0.71, 3, 0.5);
    let mut sine = spec(Table::sine(), 0.3, 0.7, 2, 0.3);
    quad.keep = 200;
    sine.keep = 200;
    for s in [quad, sine] {
        for b in sweep::collect(&s, &ex()).unwrap() {
            let sys = s.system_at(b.value).unwrap();
            assert_matches_brute_force(&b, &sys, 20_000, 200);
            assert!(b.sticking, "α = {} not marked sticking", b.value);
            assert!(b.points.iter().any(|p| p.kind == EventKind::Stick));
            assert!(b.points.iter().any(|p| p.kind == EventKind::Release));
        }
    }
}

#[test]
fn long_release_cycles_jump_ahead_and_equal_brute_force() {
    // fd:0.1 past the (2, 2) window: orbits with a chattering sequence, a stick and a
    // release at phase 0 every few periods. Their cycles are far longer than 64 events;
    // the release repeats bit for bit, so the run jumps over whole cycles.
    let mut s = spec(Table::fd(0.1).unwrap(), 0.56, 0.60, 9, 0.8);
    s.transient = 30_000;
    let mut long_cycles = 0;
    for b in sweep::collect(&s, &ex()).unwrap() {
        let sys = s.system_at(b.value).unwrap();
        assert_matches_brute_force(&b, &sys, 30_000, 50);
        if let Outcome::Periodic {
            events, stopped_at, ..
        } = b.outcome
        {
            if events > 64 {
                long_cycles += 1;
                assert!(
                    stopped_at < 10_000,
                    "α = {}: no jump ({stopped_at})",
                    b.value
                );
                assert!(
                    b.events < 30_000 * events as u64 / 4,
                    "α = {}: {} events",
                    b.value,
                    b.events
                );
            }
        }
    }
    assert!(long_cycles >= 2, "only {long_cycles} long release cycles");
}

#[test]
fn resting_ball_is_reported_as_resting() {
    // sine, α = 0.02: 4π²α < 1, the table never pulls away faster than gravity, so a
    // ball that sticks stays on the table forever.
    let s = spec(Table::sine(), 0.02, 0.02, 1, 0.5);
    let b = &sweep::collect(&s, &ex()).unwrap()[0];
    assert!(
        matches!(b.outcome, Outcome::Resting { .. }),
        "{:?}",
        b.outcome
    );
    assert!(b.sticking);
    let sys = s.system_at(b.value).unwrap();
    assert_matches_brute_force(b, &sys, 20_000, 50);
}

#[test]
fn stable_fixed_point_matches_the_closed_form() {
    // F_D on [0, ½): f'(t̂) = α(3D t̂² − (2 + D) t̂ + ½) = ½ (1 − r)/(1 + r), the smaller root.
    let (d, r) = (0.1, 0.8);
    let s = spec(Table::fd(d).unwrap(), 0.42, 0.48, 4, r);
    for b in sweep::collect(&s, &ex()).unwrap() {
        let a = b.value;
        let target = 0.5 * (1.0 - r) / (1.0 + r);
        let (qa, qb, qc) = (3.0 * d * a, -(2.0 + d) * a, 0.5 * a - target);
        let t = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        assert!(
            matches!(
                b.outcome,
                Outcome::Periodic {
                    events: 1,
                    periods: 1,
                    ..
                }
            ),
            "α = {a}: {:?}",
            b.outcome
        );
        assert_eq!(b.points.len(), 50);
        for p in &b.points {
            assert!((p.phase - t).abs() < 1e-10, "α = {a}: {} vs {t}", p.phase);
            assert!((p.v - 0.5).abs() < 1e-10);
        }
    }
}

#[test]
fn near_fixed_point_start_uses_the_closed_form_fixed_point() {
    let (d, r) = (0.1, 0.8);
    let target = 0.5 * (1.0 - r) / (1.0 + r);
    for a in [0.3, 0.45, 0.5] {
        let sys = System::new(Table::fd(d).unwrap(), a, r).unwrap();
        // Quadratic formula on the first piece, the root with f'' < 0.
        let (qa, qb, qc) = (3.0 * d * a, -(2.0 + d) * a, 0.5 * a - target);
        let t = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        let got = bouncemap_engine::run::start::fixed_point_phase(&sys).unwrap();
        assert!((got - t).abs() < 1e-13, "α = {a}: {got} vs {t}");
    }
    // Sine: 2πα cos 2πt̂ = target with sin 2πt̂ > 0.
    let sys = System::new(Table::sine(), 0.03, r).unwrap();
    let got = bouncemap_engine::run::start::fixed_point_phase(&sys).unwrap();
    assert!((sys.df(got) - target).abs() < 1e-14 && sys.jet(got)[2] < 0.0);
    // Started there, the stable band below α_PD gives the (1, 1) solution everywhere,
    // where the default hop from t̂ = 0 falls on sticking orbits for some values.
    let mut s = spec(Table::fd(0.1).unwrap(), 0.45, 0.505, 40, 0.8);
    s.transient = 5_000;
    s.initial.near_fixed_point = true;
    for b in sweep::collect(&s, &ex()).unwrap() {
        assert!(
            matches!(
                b.outcome,
                Outcome::Periodic {
                    events: 1,
                    periods: 1,
                    ..
                }
            ),
            "α = {}: {:?}",
            b.value,
            b.outcome
        );
    }
}

#[test]
fn two_cycle_is_detected_with_two_events_in_two_periods() {
    let s = spec(Table::fd(1.0).unwrap(), 0.50, 0.50, 1, 0.8);
    let b = &sweep::collect(&s, &ex()).unwrap()[0];
    assert!(
        matches!(
            b.outcome,
            Outcome::Periodic {
                events: 2,
                periods: 2,
                ..
            }
        ),
        "{:?}",
        b.outcome
    );
    // Two distinct phases, alternating.
    assert!(circ(b.points[0].phase, b.points[1].phase) > 1e-3);
    assert!(circ(b.points[0].phase, b.points[2].phase) < TOL);
}

#[test]
fn without_early_stop_every_value_runs_the_full_transient() {
    let mut s = spec(Table::fd(0.1).unwrap(), 0.45, 0.45, 1, 0.8);
    s.periodicity = None;
    s.transient = 2_000;
    let b = &sweep::collect(&s, &ex()).unwrap()[0];
    assert_eq!(b.outcome, Outcome::Unsettled);
    assert!(b.events >= 1_999);
}

#[test]
fn shards_partition_the_sweep_and_agree_with_it() {
    let mut s = spec(Table::fd(0.1).unwrap(), 0.40, 0.62, 10, 0.8);
    s.transient = 3_000;
    for warm in [Warm::Off, Warm::Forward, Warm::Backward] {
        s.warm = warm;
        s.shard = Shard::WHOLE;
        let whole = sweep::collect(&s, &ex()).unwrap();
        let mut parts: Vec<ValueResult> = Vec::new();
        for i in 0..3 {
            s.shard = Shard { index: i, count: 3 };
            parts.extend(sweep::collect(&s, &ex()).unwrap());
        }
        parts.sort_by_key(|b| b.index);
        assert_eq!(parts.len(), whole.len());
        for (a, b) in parts.iter().zip(&whole) {
            assert_eq!(
                (a.index, &a.points, a.outcome),
                (b.index, &b.points, b.outcome)
            );
        }
    }
}

#[test]
fn preview_pass_covers_the_window_then_pass_one_finishes_it() {
    let mut s = spec(Table::fd(0.1).unwrap(), 0.40, 0.62, 16, 0.8);
    s.transient = 5_000;
    let mut seen = Vec::new();
    let job = SweepJob::new(s.clone()).unwrap().preview(200);
    ex().run(job, &Control::new(), |b| seen.push(b));
    let pass0: Vec<_> = seen.iter().filter(|b| b.pass == 0).collect();
    assert_eq!(pass0.len(), 16, "pass 0 reports every value");
    assert!(seen.iter().position(|b| b.pass == 1).unwrap() >= 16);
    // Final batches equal a sweep without preview.
    let mut finals: Vec<_> = seen.into_iter().filter(|b| b.complete).collect();
    finals.sort_by_key(|b| b.index);
    let direct = sweep::collect(&s, &ex()).unwrap();
    assert_eq!(finals.len(), 16);
    for (a, b) in finals.iter().zip(&direct) {
        assert_eq!((&a.points, a.outcome), (&b.points, b.outcome));
    }
}

#[test]
fn cancel_stops_workers_and_no_stale_batch_is_current() {
    // Chaotic values with a long transient: seconds of work if not cancelled.
    let mut s = spec(Table::fd(0.1).unwrap(), 0.60, 0.62, 8, 0.8);
    s.transient = 5_000_000;
    s.periodicity = None;
    let control = Control::new();
    control.cancel();
    let g0 = control.generation();
    let h = sweep::start(s, &ex(), &control).unwrap();
    std::thread::sleep(Duration::from_millis(50));
    let t = Instant::now();
    h.cancel();
    assert_eq!(control.generation(), g0 + 1);
    while !h.is_finished() {
        assert!(t.elapsed() < Duration::from_secs(2), "workers did not stop");
        std::thread::sleep(Duration::from_millis(1));
    }
    assert!(h.drain().is_empty(), "a stale batch counted as current");
    let summary = h.wait();
    assert!(summary.cancelled);
    assert_eq!(control.generation(), g0 + 1);
}

/// Start `s`, let it run 30 ms, and close the pause gate of its control.
fn start_then_pause(s: SweepSpec) -> (sweep::SweepHandle, Control) {
    let control = Control::new();
    let h = sweep::start(s, &ex(), &control).unwrap();
    std::thread::sleep(Duration::from_millis(30));
    control.gate().set(true);
    (h, control)
}

#[test]
fn a_paused_sweep_parks_then_finishes_with_the_unpaused_result() {
    // Chaotic values (no early stop) with enough transient to be mid-run when paused
    // (about 0.1 s per value on one core).
    let mut s = spec(Table::fd(0.1).unwrap(), 0.60, 0.62, 6, 0.8);
    s.transient = 1_000_000;
    s.periodicity = None;
    let reference = sweep::collect(&s, &ex()).unwrap();

    let (h, control) = start_then_pause(s);
    // Workers park at their next cancellation test, at most CANCEL_EVERY events away
    // (later if the system has not scheduled them meanwhile): give them time, then the
    // count must stand still.
    std::thread::sleep(Duration::from_millis(300));
    let parked = h.progress();
    std::thread::sleep(Duration::from_millis(400));
    let later = h.progress();
    assert_eq!(parked.events, later.events, "workers ran while paused");
    assert!(parked.done < 6, "the sweep ended before the pause");
    assert!(
        later.elapsed <= parked.elapsed + Duration::from_millis(20),
        "paused time counted as sweep time: {:?} then {:?}",
        parked.elapsed,
        later.elapsed
    );
    control.gate().set(false);
    let mut finals: Vec<ValueResult> = Vec::new();
    for b in h.receiver() {
        if h.is_current(&b) && b.complete {
            finals.push(b.data);
        }
    }
    assert!(!h.wait().cancelled);
    finals.sort_by_key(|b| b.index);
    assert_eq!(finals.len(), reference.len());
    for (a, b) in finals.iter().zip(&reference) {
        assert_eq!(
            a.points, b.points,
            "value {} differs after the pause",
            a.index
        );
    }
}

#[test]
fn cancelling_a_paused_sweep_stops_it_at_once() {
    let mut s = spec(Table::fd(0.1).unwrap(), 0.60, 0.62, 8, 0.8);
    s.transient = 5_000_000;
    s.periodicity = None;
    let (h, _control) = start_then_pause(s);
    std::thread::sleep(Duration::from_millis(50));
    let t = Instant::now();
    h.cancel();
    while !h.is_finished() {
        // The cancel wakes them (the gate's own test times that); allow for a loaded
        // machine here.
        assert!(
            t.elapsed() < Duration::from_secs(1),
            "parked workers did not stop"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    assert!(h.wait().cancelled);
}

#[test]
fn invalid_settings_are_refused_with_the_range() {
    let mut s = spec(Table::fd(0.1).unwrap(), 0.6, 0.4, 10, 0.8);
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("alpha") && e.contains("LO ≤ HI"), "{e}");
    s.lo = 0.4;
    s.hi = 0.6;
    s.periodicity = Some(Periodicity {
        max_period: 0,
        tolerance: 1e-11,
    });
    assert!(s.validate().unwrap_err().to_string().contains("max-period"));
    let mut d = SweepSpec::new(Table::sine(), 0.45, 0.8, SweepParam::D, 0.0, 1.0, 10);
    d.transient = 10;
    let e = d.validate().unwrap_err().to_string();
    assert!(e.contains("no parameter 'D'"), "{e}");
}
