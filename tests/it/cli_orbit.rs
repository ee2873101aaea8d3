//! The `orbit` command from the outside: the settled (1, 1) orbit against its closed
//! form (F_D and the sine), the grid solver against the exact one, the output formats,
//! and bad input.

use std::process::{Command, Output};

fn bouncemap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .output()
        .unwrap()
}

fn last_csv_row(out: &Output) -> Vec<String> {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("index,period,phase,v,vrel,kind"));
    lines.last().unwrap().split(',').map(String::from).collect()
}

/// Phase of the (1, 1) orbit on the first piece of F_D: α F_D'(t̂) = (1 − r)/(2(1 + r)),
/// F_D' = 3D t̂² − (2 + D) t̂ + ½ (the paper's Eq. (c1)), smaller root.
fn fixed_phase(d: f64, alpha: f64, r: f64) -> f64 {
    let c = (1.0 - r) / (2.0 * (1.0 + r)) / alpha;
    let (a, b, cc) = (3.0 * d, -(2.0 + d), 0.5 - c);
    (-b - (b * b - 4.0 * a * cc).sqrt()) / (2.0 * a)
}

#[test]
fn settles_on_the_closed_form_fixed_point() {
    let want = fixed_phase(0.1, 0.45, 0.8);
    let exact = last_csv_row(&bouncemap(&[
        "orbit", "--table", "fd:0.1", "--alpha", "0.45", "--r", "0.8", "--format", "csv",
    ]));
    let phase: f64 = exact[2].parse().unwrap();
    let v: f64 = exact[3].parse().unwrap();
    assert!((phase - want).abs() < 1e-9, "phase {phase} vs {want}");
    assert!((v - 0.5).abs() < 1e-9, "v {v}");
    assert_eq!(exact[5], "impact");
    // One impact per period on the (1, 1) orbit: the period index equals the event count.
    assert_eq!(exact[1], "1000");
    let grid = last_csv_row(&bouncemap(&[
        "orbit", "--table", "fd:0.1", "--alpha", "0.45", "--r", "0.8", "--format", "csv",
        "--solver", "grid",
    ]));
    let gphase: f64 = grid[2].parse().unwrap();
    let gv: f64 = grid[3].parse().unwrap();
    assert!(
        (gphase - phase).abs() < 1e-8 && (gv - v).abs() < 1e-8,
        "grid {gphase} {gv}"
    );
}

#[test]
fn sine_settles_on_the_closed_form_fixed_point() {
    // On the sine, α·2π cos 2πt̂* = (1 − r)/(2(1 + r)), the stable root in (0, ¼); the
    // multipliers have modulus r, so 2000 bounces from the default start are plenty.
    let (alpha, r) = (0.022, 0.8);
    let c = (1.0 - r) / (2.0 * (1.0 + r));
    let want = (c / (2.0 * std::f64::consts::PI * alpha)).acos() / (2.0 * std::f64::consts::PI);
    let row = last_csv_row(&bouncemap(&[
        "orbit",
        "--table",
        "sine",
        "--alpha",
        "0.022",
        "--r",
        "0.8",
        "--skip",
        "2000",
        "--bounces",
        "1",
        "--format",
        "csv",
    ]));
    let phase: f64 = row[2].parse().unwrap();
    let v: f64 = row[3].parse().unwrap();
    assert!((phase - want).abs() < 1e-13, "phase {phase} vs {want}");
    assert!((v - 0.5).abs() < 1e-13, "v {v}");
}

#[test]
fn json_output_has_the_documented_fields() {
    let out = bouncemap(&[
        "orbit",
        "--table",
        "sine",
        "--alpha",
        "0.3",
        "--bounces",
        "3",
        "--skip",
        "2",
        "--format",
        "json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["table"], "sine");
    assert_eq!(v["solver"], "exact");
    let events = v["events"].as_array().unwrap();
    assert_eq!(events.len(), 3);
    assert_eq!(events[0]["index"], 2);
    for e in events {
        for k in ["index", "period", "phase", "v", "vrel", "kind"] {
            assert!(e.get(k).is_some(), "missing {k} in {e}");
        }
    }
    assert!(v["halt"].is_null());
}

#[test]
fn resting_ball_is_reported_not_hung() {
    let out = bouncemap(&[
        "orbit", "--table", "fd:0.1", "--alpha", "0.12", "--format", "csv",
    ]);
    assert!(out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("rests on the table"), "{err}");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.lines().last().unwrap().ends_with(",stick"));
}

#[test]
fn bad_input_is_one_line_with_exit_status_2() {
    let dir = std::env::temp_dir().join(format!("bouncemap-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let kink = dir.join("kink.toml");
    std::fs::write(&kink, "[[piece]]\nstart = 0.0\ncoeffs = [0.0, 1.0]\n[[piece]]\nstart = 0.5\ncoeffs = [1.0, -1.0]\n").unwrap();
    let broken = dir.join("broken.toml");
    std::fs::write(&broken, "[[piece]]\nstart = 0.0\ncoeffs = [0.0, 1.0\n").unwrap();
    let kink = kink.to_str().unwrap();
    let broken = broken.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--r", "1.5"], "(0, 1)"),
        (&["--r", "0"], "(0, 1)"),
        (&["--alpha", "0"], "(0, 1000]"),
        (&["--alpha", "-1"], "(0, 1000]"),
        (&["--alpha", "nan"], "alpha"),
        (&["--alpha", "inf"], "alpha"),
        (&["--table", "fd:1.5"], "[0, 1]"),
        (&["--table", "fd:abc"], "[0, 1]"),
        (&["--table", "square"], "fd:D"),
        (&["--table", "/nonexistent/table.toml"], "cannot read"),
        (&["--table", kink], "t̂ = 0.5"),
        (&["--table", broken], "broken.toml"),
        (&["--v0", "-5"], "v0 ≥"),
        (&["--t0", "1.5"], "[0, 1)"),
        (&["--z0", "-1"], "[0, 1000]"),
        (&["--bounces", "-3"], "≥ 0"),
        (&["--skip", "x"], "≥ 0"),
        (&["--solver", "fast"], "exact, grid"),
        (&["--format", "xml"], "text, csv, json"),
    ];
    for (args, needle) in cases {
        let mut full = vec!["orbit"];
        full.extend_from_slice(args);
        let out = bouncemap(&full);
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
        assert!(
            !err.contains("panicked") && !err.contains("backtrace"),
            "{err}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
