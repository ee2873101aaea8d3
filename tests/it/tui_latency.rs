//! Interactive work never waits behind a sweep: the orbit analysis for the stability
//! panel answers within 100 ms while a sweep keeps every core of the executor busy, and
//! while that sweep is paused (its workers parked on their threads).

use crate::tui_common::app;
use bouncemap::output::hitgrid::Marker;
use bouncemap::tui::components::diagram::Diagram;
use bouncemap::tui::components::{Registered, Target, Workers};
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::Executor;
use bouncemap_engine::sweep::{SweepJob, SweepSpec};
use bouncemap_engine::Table;
use std::time::{Duration, Instant};

/// Start the orbit analysis through the app and time it until its answer arrives.
fn analysis_time(a: &mut bouncemap::tui::app::App, workers: &Workers) -> Duration {
    let t = Instant::now();
    a.start(Target::Stability, workers);
    let deadline = t + Duration::from_secs(10);
    while Instant::now() < deadline {
        if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(5)) {
            a.receive(m);
            if a.shared.orbits.is_some() {
                return t.elapsed();
            }
        }
    }
    panic!("the orbit analysis never answered");
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

#[test]
fn orbit_analysis_answers_within_100_ms_beside_a_running_or_paused_sweep() {
    let cores = bouncemap_engine::jobs::available_cores();
    let workers = Workers::new(Executor::new(cores).unwrap());
    let mut a = app(Marker::Braille);
    // Chaotic values without early stop: minutes of work on every core.
    let mut spec = SweepSpec::new(
        Table::fd(0.1).unwrap(),
        0.45,
        0.8,
        SweepParam::Alpha,
        0.58,
        0.62,
        64,
    );
    spec.transient = 1_000_000_000;
    spec.periodicity = None;
    workers.start_job(Diagram::ADDRESS, SweepJob::new(spec).unwrap());
    std::thread::sleep(Duration::from_millis(200));
    let running: Vec<Duration> = (0..5).map(|_| analysis_time(&mut a, &workers)).collect();
    workers.pause(true);
    std::thread::sleep(Duration::from_millis(300));
    let paused: Vec<Duration> = (0..5).map(|_| analysis_time(&mut a, &workers)).collect();
    workers.cancel_all();
    let (r, p) = (median(running.clone()), median(paused.clone()));
    eprintln!("orbit analysis: {r:?} beside a running sweep, {p:?} beside a paused one");
    assert!(
        r < Duration::from_millis(100),
        "while the sweep runs: {running:?}"
    );
    assert!(
        p < Duration::from_millis(100),
        "while the sweep is paused: {paused:?}"
    );
}
