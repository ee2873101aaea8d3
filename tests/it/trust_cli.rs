//! Answers that carry their evidence, as a user gets them from the binary: special
//! points that satisfy their condition, cascades through border collisions, long
//! cycles identified as such, and no cycle length claimed where double precision
//! cannot decide it. Reference values come from an independent exact impact map in
//! 40- to 800-digit arithmetic (Newton on the cycle equations, the one-sided Jacobians
//! at a border collision, the release-to-stick paths at rising precision).

use crate::cli::{json, ok};

#[test]
fn the_fd1_window_has_no_false_fold_and_every_special_point_shows_its_condition() {
    let v = json(&[
        "continue",
        "--table",
        "fd:1",
        "--alpha",
        "0.4..0.6",
        "--max-period",
        "16",
        "--format",
        "json",
    ]);
    for b in v["branches"].as_array().unwrap() {
        let specials = b["specials"]
            .as_array()
            .unwrap()
            .iter()
            .chain([&b["begin"], &b["end"]]);
        for s in specials {
            assert_ne!(s["kind"], "fold", "{s}");
            assert_ne!(s["kind"], "lost", "{s}");
            if let Some(e) = s["condition_error"].as_f64() {
                assert!(e <= 1e-8, "{s}");
            }
        }
    }
    // The (16, 16) branch leaves the window unstable, its multiplier −6585.167 at 0.6.
    let b16 = v["branches"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["n"] == 16)
        .unwrap();
    assert_eq!(b16["end"]["kind"], "window_exit");
    let mu = b16["end"]["multipliers"][1]["re"].as_f64().unwrap();
    assert!((mu + 6585.167).abs() < 0.01, "{mu}");
}

#[test]
fn the_fd078_cascade_goes_on_through_its_border_collision_to_a_stable_doubled_cycle() {
    let text = ok(&["cascade", "--table", "fd:0.78"]);
    assert!(
        text.contains("alpha_4 = 0.5929683777927")
            && text.contains("(period doubling through a border collision)"),
        "{text}"
    );
    assert!(
        text.contains("a stable (16, 16) cycle is born there"),
        "{text}"
    );
    // Just past the collision the paper's start settles on the doubled cycle.
    let alpha = format!("{}", 0.592968377792713 + 1e-6);
    let l = ok(&[
        "lyapunov",
        "--table",
        "fd:0.78",
        "--alpha",
        &alpha,
        "--near-fixed-point",
    ]);
    assert!(l.contains("orbit: periodic (16, 16)"), "{l}");
}

#[test]
fn stable_cycles_longer_than_64_events_are_periodic_with_their_n_and_k() {
    // (table, α, start, (n, k), λ₁ = ln|μ₁|/n from the independent Newton).
    let cases: [(&str, &str, &[&str], &str, f64); 3] = [
        (
            "fd:0.41",
            "0.53758",
            &["--t0", "0.026077740068654445", "--v0", "0.7047391702147028"],
            "(80, 80)",
            -0.0080523459,
        ),
        (
            "fd:1",
            "0.572329097",
            &["--near-fixed-point"],
            "(128, 128)",
            -0.014186204,
        ),
        (
            "sine",
            "0.0317093863",
            &["--near-fixed-point"],
            "(128, 128)",
            -0.014192827,
        ),
    ];
    for (table, alpha, start, nk, lambda) in cases {
        let mut args = vec![
            "lyapunov", "--table", table, "--alpha", alpha, "--format", "json",
        ];
        args.extend_from_slice(start);
        let v = json(&args);
        assert_eq!(v["kind"], "periodic", "{table} {alpha}: {v}");
        assert_eq!(format!("({}, {})", v["events"], v["periods"]), nk, "{v}");
        let l = v["lambda1"].as_f64().unwrap();
        assert!(
            (l - lambda).abs() < 1e-8,
            "{table} {alpha}: {l} vs {lambda}"
        );
    }
    // basins: the (80, 80) cycle is one attractor beside the (2, 2), none unsettled.
    let b = json(&[
        "basins", "--table", "fd:0.41", "--alpha", "0.53758", "--grid", "40x20", "--format", "json",
    ]);
    let kinds: Vec<(String, String)> = b["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| {
            (
                a["kind"].to_string(),
                format!("{},{}", a["events"], a["periods"]),
            )
        })
        .collect();
    assert_eq!(kinds.len(), 2, "{b}");
    assert!(
        kinds.contains(&("\"periodic\"".into(), "80,80".into())),
        "{kinds:?}"
    );
    // A sweep value there.
    let csv = ok(&[
        "sweep",
        "--table",
        "fd:1",
        "--alpha",
        "0.572329097..0.572329097",
        "--steps",
        "1",
        "--near-fixed-point",
        "--transient",
        "100000",
        "--keep",
        "1",
        "--format",
        "csv",
    ]);
    let row = csv.lines().rfind(|l| !l.starts_with('#')).unwrap();
    assert!(row.contains(",128,128,periodic,false,true,"), "{row}");
}

#[test]
fn sticking_cycles_beyond_double_precision_claim_no_length() {
    for (table, alpha) in [("fd:0.1", "0.6"), ("fd:1", "0.59")] {
        let text = ok(&["lyapunov", "--table", table, "--alpha", alpha]);
        assert!(text.contains("orbit: sticking\n"), "{text}");
        assert!(
            text.contains("cycle length beyond double precision: along the cycle this run found, which rounding chose, an error at the release grows by 10^"),
            "{text}"
        );
        let v = json(&[
            "lyapunov", "--table", table, "--alpha", alpha, "--format", "json",
        ]);
        assert_eq!(v["resolved"], false, "{v}");
        assert!(v["events"].is_null() && v["periods"].is_null(), "{v}");
        assert!(v["growth_decades"].as_f64().unwrap() > 20.0, "{v}");
    }
    // A short stick–release cycle is resolved and keeps its length.
    let v = json(&[
        "lyapunov", "--table", "cubic", "--alpha", "0.47", "--format", "json",
    ]);
    assert_eq!(
        (v["kind"].as_str(), v["resolved"].as_bool()),
        (Some("sticking"), Some(true)),
        "{v}"
    );
    assert_eq!(v["periods"], 1);
}

/// The plane and the basins say what `lyapunov` says of the same sticking cycles:
/// no length where double precision cannot decide it.
#[test]
fn planes_and_basin_legends_claim_no_length_rounding_decides() {
    let csv = ok(&[
        "plane",
        "--table",
        "fd:0.1",
        "--x",
        "alpha:0.599..0.6",
        "--y",
        "r:0.79..0.8",
        "--size",
        "2x2",
        "--format",
        "csv",
    ]);
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        rows[0],
        "alpha,r,class,period,table_periods,lyapunov,status,resolved,growth_decades"
    );
    // At α 0.6, r 0.8 (the case `lyapunov` refuses a length for above).
    let last = rows.iter().find(|r| r.starts_with("0.6,0.8,")).unwrap();
    let cells: Vec<&str> = last.split(',').collect();
    assert_eq!(
        cells[2..8],
        ["sticking-unresolved", "", "", "-inf", "periodic", "false"],
        "{last}"
    );
    assert!(cells[8].parse::<f64>().unwrap() > 20.0, "{last}");
    // A basins legend does not print the length of such a cycle either.
    let text = ok(&[
        "basins", "--table", "fd:0.1", "--alpha", "0.6", "--grid", "8x4", "--format", "braille",
        "--width", "16", "--height", "10",
    ]);
    let legend: Vec<&str> = text.lines().filter(|l| l.contains(" basin ")).collect();
    assert!(!legend.is_empty(), "{text}");
    for l in legend {
        if l.contains("sticking") {
            assert!(l.contains("sticking (length unresolved)"), "{l}");
        }
    }
}
