//! `lyapunov`, `basins` and `sweep --lyapunov/--starts` as a user runs them: the checks
//! of the attractor features through the binary, against references computed here
//! (the eigenvalues `fixed` prints, 2 ln r, merge of sharded multi-start sweeps), and
//! bad input (one line, exit status 2).

use crate::cli::{json, run};

#[test]
fn basins_of_the_cubic_table_hold_the_fixed_point_and_the_sticking_cycle() {
    let v = json(&[
        "basins", "--table", "cubic", "--alpha", "0.47", "--r", "0.8", "--format", "json",
    ]);
    let list = v["attractors"].as_array().unwrap();
    assert!(list.len() >= 2, "{v}");
    let sum: f64 = list.iter().map(|a| a["fraction"].as_f64().unwrap()).sum();
    assert!((sum - 1.0).abs() < 1e-12);
    assert_eq!(v["starts"], 20000);
    let p11 = list
        .iter()
        .find(|a| a["kind"] == "periodic" && a["events"] == 1 && a["periods"] == 1)
        .expect("the (1,1) solution");
    assert!((p11["phase"].as_f64().unwrap() - 0.149665250704).abs() < 1e-9);
    assert!((p11["v"].as_f64().unwrap() - 0.5).abs() < 1e-9);
    let stick = list
        .iter()
        .find(|a| a["kind"] == "sticking")
        .expect("a sticking cycle");
    assert_eq!(stick["lyapunov"], "-inf");
    // The (1, 1) exponent is ln r per impact (complex multipliers of modulus r).
    assert!((p11["lyapunov"].as_f64().unwrap() - 0.8f64.ln()).abs() < 1e-9);

    // The default start's orbit is the sticking one, as a one-value sweep shows.
    let (code, out, err) = run(&[
        "lyapunov", "--table", "cubic", "--alpha", "0.47", "--r", "0.8", "--format", "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let l: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(l["kind"], "sticking");
    assert_eq!(l["lambda1"], "-inf");
}

#[test]
fn the_braille_basin_picture_shows_both_attractors_with_a_legend() {
    let (code, out, err) = run(&[
        "basins", "--table", "cubic", "--alpha", "0.47", "--r", "0.8", "--grid", "80x40",
        "--format", "braille", "--width", "60", "--height", "24",
    ]);
    assert_eq!(code, 0, "{err}");
    let legend: Vec<&str> = out.lines().filter(|l| l.contains("basin")).collect();
    assert!(legend.len() >= 2, "{out}");
    assert!(
        legend.iter().any(|l| l.contains("periodic (1, 1)")),
        "{out}"
    );
    assert!(legend.iter().any(|l| l.contains("sticking")), "{out}");
    // Each legend texture appears in the picture.
    let picture: String = out.lines().skip(1).take(18).collect();
    for l in &legend {
        let t = l.trim_start().chars().next().unwrap();
        assert!(picture.contains(t), "texture {t} missing:\n{out}");
    }
}

#[test]
fn lyapunov_on_the_fixed_point_equals_the_logs_of_fixeds_eigenvalues() {
    let args = [
        "--table", "fd:0.1", "--alpha", "0.45", "--r", "0.8", "--format", "json",
    ];
    let f = json(&[&["fixed"], &args[..]].concat());
    let sol = &f["solutions"][0];
    assert_eq!(sol["classification"], "stable");
    let moduli: Vec<f64> = sol["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| {
            z["re"]
                .as_f64()
                .unwrap()
                .hypot(z["im"].as_f64().unwrap())
                .ln()
        })
        .collect();
    let l = json(&[&["lyapunov", "--near-fixed-point"], &args[..]].concat());
    assert_eq!(l["kind"], "periodic");
    assert_eq!(l["method"], "cycle");
    assert!(
        (l["lambda1"].as_f64().unwrap() - moduli[0]).abs() < 1e-8,
        "{l}"
    );
    assert!(
        (l["lambda2"].as_f64().unwrap() - moduli[1]).abs() < 1e-8,
        "{l}"
    );
    // At the fixed point itself as a start, too.
    let t0 = sol["phase"].as_f64().unwrap().to_string();
    let l = json(&[&["lyapunov", "--t0", &t0, "--v0", "0.5"], &args[..]].concat());
    assert!(
        (l["lambda1"].as_f64().unwrap() - moduli[0]).abs() < 1e-8,
        "{l}"
    );
}

#[test]
fn lyapunov_on_a_chaotic_orbit_sums_to_two_ln_r() {
    let l = json(&[
        "lyapunov",
        "--table",
        "fd:1",
        "--alpha",
        "0.5735",
        "--r",
        "0.8",
        "--near-fixed-point",
        "--transient",
        "200000",
        "--impacts",
        "100000",
        "--format",
        "json",
    ]);
    assert_eq!(l["kind"], "chaotic");
    assert_eq!(l["method"], "qr");
    let two_ln_r = 2.0 * 0.8f64.ln();
    let sum = l["lambda1"].as_f64().unwrap() + l["lambda2"].as_f64().unwrap();
    assert!((sum - two_ln_r).abs() < 1e-6, "{l}");
    assert!(l["lambda1"].as_f64().unwrap() > 0.05, "{l}");
    assert!(l["stderr1"].as_f64().unwrap() < 0.01, "{l}");
}

#[test]
fn sweep_lyapunov_column_and_several_starts_merge_like_the_whole() {
    let dir = tempdir();
    let base = [
        "sweep",
        "--table",
        "cubic",
        "--alpha",
        "0.45..0.5",
        "--r",
        "0.8",
        "--steps",
        "6",
        "--transient",
        "20000",
        "--keep",
        "3",
        "--lyapunov",
        "--starts",
        "6",
    ];
    let (code, whole, err) = run(&base);
    assert_eq!(code, 0, "{err}");
    let header = whole.lines().find(|l| l.starts_with("index,")).unwrap();
    assert_eq!(
        header,
        "index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades,lyapunov,attractor"
    );
    // Between 0.45 and 0.48 the (1,1) branch and a sticking cycle coexist: some value
    // lists two attractors, one with exponent -inf.
    let rows: Vec<Vec<&str>> = whole
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("index"))
        .map(|l| l.split(',').collect())
        .collect();
    assert!(rows.iter().any(|r| r[12] == "2"), "{whole}");
    assert!(rows.iter().any(|r| r[11] == "-inf"), "{whole}");
    assert!(
        rows.iter()
            .any(|r| r[11].parse::<f64>().is_ok_and(|x| x < 0.0)),
        "{whole}"
    );
    // Two shards merge into the whole file (same rows, same checksum line).
    let mut parts = Vec::new();
    for s in ["1/2", "2/2"] {
        let f = dir.join(format!("part{}.csv", &s[..1]));
        let f = f.to_str().unwrap().to_string();
        let (code, _, err) = run(&[&base[..], &["--shard", s, "--out", &f]].concat());
        assert_eq!(code, 0, "{err}");
        parts.push(f);
    }
    let (code, merged, err) = run(&["merge", &parts[0], &parts[1]]);
    assert_eq!(code, 0, "{err}");
    let body = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| !l.starts_with("# shard") && !l.starts_with("# end"))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(body(&merged), body(&whole));
    // json: per-value attractor lists whose fractions sum to 1.
    let v = json(&[&base[..], &["--format", "json"]].concat());
    assert_eq!(v["starts"], 6);
    for value in v["values"].as_array().unwrap() {
        let sum: f64 = value["attractors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a["fraction"].as_f64().unwrap())
            .sum();
        assert!((sum - 1.0).abs() < 1e-12, "{value}");
        assert!(value["points"][0]["attractor"].as_u64().is_some());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn one_start_is_todays_sweep() {
    let args = [
        "sweep",
        "--alpha",
        "0.45..0.5",
        "--steps",
        "5",
        "--transient",
        "5000",
        "--keep",
        "4",
    ];
    let (_, plain, _) = run(&args);
    let (_, one, _) = run(&[&args[..], &["--starts", "1"]].concat());
    assert_eq!(plain, one);
    assert!(plain.contains(
        "index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades\n"
    ));
}

#[test]
fn bad_input_is_one_line_with_the_valid_range_and_status_2() {
    for (args, want) in [
        (vec!["basins", "--grid", "0x5"], "valid NXxNY"),
        (
            vec!["basins", "--grid", "3000x3000"],
            "at most 1000000 points",
        ),
        (vec!["basins", "--w-max", "-1"], "(0, 1000]"),
        (vec!["basins", "--w-max", "0"], "(0, 1000]"),
        (vec!["lyapunov", "--impacts", "0"], "[1, 1e10]"),
        (vec!["lyapunov", "--transient", "0"], "[1, 1e12]"),
        (
            vec![
                "lyapunov",
                "--table",
                "sine",
                "--alpha",
                "0.001",
                "--near-fixed-point",
            ],
            "no (1,1) solution",
        ),
        (
            vec!["sweep", "--alpha", "0.4..0.5", "--starts", "0"],
            "[1, 1000]",
        ),
        (
            vec!["sweep", "--alpha", "0.4..0.5", "--starts", "3", "--warm"],
            "needs cold starts",
        ),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(out.is_empty());
    }
}

fn tempdir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("bouncemap-attr-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}
