//! Events per second of the impact map at any precision against the f64 map, on the
//! same orbit: fd:0.1 at α = 0.45 (the period-1 attractor, no chattering) and α = 0.6
//! (sticking: chattering resolved at the working precision, sticks and releases).
//! Medians of five runs. `cargo bench -p bouncemap-engine --bench precise`.

use bouncemap_engine::table::Family;
use bouncemap_engine::{
    bits_for_digits, Big, ImpactMap, PreciseMap, PreciseState, PreciseSystem, Real, Solver, State,
    System, Table,
};
use std::hint::black_box;
use std::time::Instant;

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Events per second of `events` steps of the map `make` builds, median of five.
fn rate(events: usize, mut run: impl FnMut(usize)) -> f64 {
    median(
        (0..5)
            .map(|_| {
                let t = Instant::now();
                run(events);
                events as f64 / t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

fn precise<R: Real>(alpha: &str, ctx: &R::Context, events: usize) {
    let n = |s: &str| R::from_decimal(s, ctx).unwrap();
    let pieces = Family::fd().pieces_in(&[n("0.1")], ctx).unwrap();
    let sys = PreciseSystem::new(pieces, n(alpha), n("0.8"), ctx.clone()).unwrap();
    let st = PreciseState::launch(&sys, 0, n("0"), n("0.5"));
    let mut map = PreciseMap::new(sys, st);
    for _ in 0..events {
        black_box(map.step().unwrap());
    }
}

fn main() {
    for alpha in ["0.45", "0.6"] {
        let f64_rate = rate(200_000, |k| {
            let sys = System::new(Table::fd(0.1).unwrap(), alpha.parse().unwrap(), 0.8).unwrap();
            let st = State::start(&sys, 0.0, None, 0.0).unwrap();
            let mut map = ImpactMap::new(sys, Solver::Exact, st);
            for _ in 0..k {
                black_box(map.step().unwrap());
            }
        });
        println!("fd:0.1 alpha {alpha}: f64 map {:>12.0} events/s", f64_rate);
        let generic = rate(20_000, |k| precise::<f64>(alpha, &(), k));
        println!(
            "fd:0.1 alpha {alpha}: generic map in f64 {:>12.0} events/s  (f64 map / this: {:.1})",
            generic,
            f64_rate / generic
        );
        for digits in [30u32, 60, 120, 300] {
            let bits = bits_for_digits(digits);
            let events = if digits <= 60 { 2000 } else { 500 };
            let r = rate(events, |k| precise::<Big>(alpha, &bits, k));
            println!(
                "fd:0.1 alpha {alpha}: {digits:>3} digits {:>12.0} events/s  (f64 map / this: {:.0})",
                r,
                f64_rate / r
            );
        }
    }
}
