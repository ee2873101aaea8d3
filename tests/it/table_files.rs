//! The shipped table files describe the same tables as the built-ins: orbits computed
//! from `assets/tables/fd0.toml` and `fd1.toml` match those of `quad` and `cubic`, and the
//! example file loads and runs.

use bouncemap::config::table_spec::{parse_table_file, TableSpec};
use bouncemap_engine::{Event, ImpactMap, Solver, State, System, Table};

fn load(name: &str) -> Table {
    let path = format!("{}/assets/tables/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    parse_table_file(&text, &path).unwrap()
}

fn events(table: Table, alpha: f64, r: f64, n: usize) -> Vec<Event> {
    let sys = System::new(table, alpha, r).unwrap();
    let v0 = sys.df(0.1) + 0.5;
    let start = State::launch(&sys, 0, 0.1, v0, 0.0).unwrap();
    let mut map = ImpactMap::new(sys, Solver::Exact, start);
    (0..n).map_while(|_| map.step().ok()).collect()
}

fn assert_same(a: &[Event], b: &[Event], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.kind, y.kind);
        assert_eq!(x.period, y.period, "{x:?} vs {y:?}");
        assert!((x.phase - y.phase).abs() < tol, "{x:?} vs {y:?}");
        assert!((x.v - y.v).abs() < tol, "{x:?} vs {y:?}");
    }
}

#[test]
fn files_give_the_builtin_orbits() {
    for (file, builtin) in [("fd0.toml", "quad"), ("fd1.toml", "cubic")] {
        let b = TableSpec::parse(builtin).unwrap().load().unwrap();
        // Periodic regime: identical over a long run (coefficients differ only by rounding).
        assert_same(
            &events(load(file), 0.45, 0.8, 3000),
            &events(b.clone(), 0.45, 0.8, 3000),
            1e-12,
        );
        // Chaotic regime: rounding differences grow, so compare the first events only.
        assert_same(
            &events(load(file), 0.62, 0.8, 25),
            &events(b, 0.62, 0.8, 25),
            1e-8,
        );
    }
}

#[test]
fn example_file_is_c1_with_degree_five() {
    let t = load("quintic.toml");
    assert_eq!(t.max_degree(), 5);
    // C¹ across the breakpoint 0.4 and the wrap, by evaluating each side's own formula.
    let (left, right) = (t.segment(0).jet(0.4), t.segment(1).jet(0.4));
    assert!((left[0] - right[0]).abs() < 1e-12);
    assert!((left[1] - right[1]).abs() < 1e-12);
    let (end, start) = (t.segment(1).jet(1.0), t.segment(0).jet(0.0));
    assert!((end[0] - start[0]).abs() < 1e-12);
    assert!((end[1] - start[1]).abs() < 1e-12);
    // The interpolated data of the file header.
    assert!((t.value(0.4) - 0.6).abs() < 1e-12);
    assert!((t.jet(0.0)[1] - 1.5).abs() < 1e-12);
    assert_eq!(events(t, 0.3, 0.8, 500).len(), 500);
}
