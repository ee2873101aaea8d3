//! Timing of the orbit analysis the terminal application calls interactively:
//! `stability_window` (one call per r when drawing the stability region in the (α, r)
//! plane), `two_cycle` and `border_collision`. Plain `std::time` harness:
//! `cargo bench --bench orbits`.

use bouncemap_engine::orbits::{border_collision, stability_window, two_cycle};
use bouncemap_engine::{System, Table};
use std::hint::black_box;
use std::time::Instant;

fn time<F: FnMut()>(name: &str, calls: usize, mut f: F) {
    f();
    let start = Instant::now();
    for _ in 0..calls {
        f();
    }
    let per = start.elapsed().as_secs_f64() / calls as f64;
    println!("{name:<44} {:>10.2} µs/call ({calls} calls)", per * 1e6);
}

fn main() {
    let rs: Vec<f64> = (1..=200).map(|i| i as f64 / 201.0).collect();
    for (name, table) in [
        ("sine", Table::sine()),
        ("fd:0", Table::fd(0.0).unwrap()),
        ("fd:0.1", Table::fd(0.1).unwrap()),
        ("fd:1", Table::fd(1.0).unwrap()),
    ] {
        let mut i = 0;
        time(
            &format!("stability_window {name}, k=1, r sweep"),
            2000,
            || {
                let r = rs[i % rs.len()];
                i += 1;
                black_box(stability_window(&table, r, 1).unwrap());
            },
        );
        time(
            &format!("stability_window {name}, k=3, r sweep"),
            2000,
            || {
                let r = rs[i % rs.len()];
                i += 1;
                black_box(stability_window(&table, r, 3).unwrap());
            },
        );
    }
    let sys = System::new(Table::fd(0.1).unwrap(), 0.5102, 0.8).unwrap();
    time("two_cycle fd:0.1 alpha 0.5102", 2000, || {
        black_box(two_cycle(&sys, 1).unwrap());
    });
    let t = Table::fd(0.1).unwrap();
    time("border_collision fd:0.1", 200, || {
        black_box(border_collision(&t, 0.8, 1).unwrap());
    });
}
