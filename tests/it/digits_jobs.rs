//! `--digits` in the jobs: `sweep` (and `basins`) decide at any precision the sticking
//! cycles whose length double precision cannot, and write the verdict beside the f64
//! columns. Checked against the independent high-precision computation the
//! `lyapunov --digits` tests quote, against `lyapunov --digits` at the same value, and
//! through `merge`.

use crate::scratch::{dir, s};
use std::process::{Command, Output};

fn bouncemap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .unwrap()
}

/// The csv rows of a command that succeeds (comment lines left out), header first.
fn csv(args: &[&str]) -> Vec<Vec<String>> {
    rows_of(&stdout_of(args))
}

/// The standard output of a command that succeeds.
fn stdout_of(args: &[&str]) -> String {
    let out = bouncemap(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The csv rows of `text` (comment lines left out), header first.
fn rows_of(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

/// The lines of a part file other than its comments (provenance, end line).
fn body(p: &std::path::Path) -> Vec<String> {
    std::fs::read_to_string(p)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(String::from)
        .collect()
}

/// `merge` of the shards `parts` (in `d`) succeeds and writes the rows of `whole`.
fn merges_into(d: &std::path::Path, parts: [&std::path::Path; 2], whole: &std::path::Path) {
    let merged = d.join("merged.csv");
    let out = bouncemap(&["merge", s(parts[0]), s(parts[1]), "--out", s(&merged)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(body(&merged), body(whole));
}

/// A row's cell by its column's name.
fn cell<'a>(rows: &'a [Vec<String>], row: usize, name: &str) -> &'a str {
    let k = rows[0].iter().position(|h| h == name).unwrap_or_else(|| {
        panic!("no column {name} in {:?}", rows[0]);
    });
    &rows[row][k]
}

const SWEEP: [&str; 12] = [
    "sweep",
    "--table",
    "fd:1",
    "--alpha",
    "0.58..0.59",
    "--steps",
    "2",
    "--near-fixed-point",
    "--keep",
    "1",
    "--digits",
    "20",
];

/// fd:1 over α 0.58..0.59, where double precision decides neither sticking cycle: at
/// α = 0.59 the sweep's verdict is the independent computation's (mpmath at 300–600
/// digits: L = 78, T = 77.94380773608558746178…; for the doubles L = 142,
/// T = 141.99569712592663915833…), and at α = 0.58 it is what `lyapunov --digits`
/// finds there; the f64 columns still claim no length.
#[test]
fn a_sweep_decides_the_cycles_double_precision_cannot() {
    let decimals = csv(&SWEEP);
    let binary = csv(&[&SWEEP[..], &["--binary-params"]].concat());
    for rows in [&decimals, &binary] {
        assert_eq!(rows.len(), 3, "{rows:?}");
        for i in 1..3 {
            assert_eq!(cell(rows, i, "resolved"), "false");
            assert_eq!(cell(rows, i, "table_periods"), "");
            assert_eq!(cell(rows, i, "digits_verdict"), "found");
            assert_eq!(cell(rows, i, "agreed_digits"), "20");
            assert_eq!(cell(rows, i, "need_digits"), "");
        }
    }
    assert_eq!(cell(&decimals, 2, "digits_periods"), "78");
    // (20 digits, the last rounded: …587461|78 is …587462.)
    let t = cell(&decimals, 2, "stick_after");
    assert_eq!(t, "77.943807736085587462");
    assert_eq!(cell(&binary, 2, "digits_periods"), "142");
    let t = cell(&binary, 2, "stick_after");
    assert_eq!(t, "141.99569712592663916");
    // The same answer as `lyapunov --digits` from the same start at the same α.
    let out = bouncemap(&[
        "lyapunov",
        "--table",
        "fd:1",
        "--alpha",
        "0.58",
        "--near-fixed-point",
        "--digits",
        "20",
        "--format",
        "csv",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(row[5], "found");
    assert_eq!(cell(&decimals, 1, "digits_periods"), row[6]);
    assert_eq!(cell(&decimals, 1, "stick_after"), row[9]);
}

/// A value that double precision decides gets no verdict: its cells are empty and its
/// f64 length stands (fd:0.1 at α = 0.595, growth 10^12 from the release).
#[test]
fn a_cycle_double_precision_decides_is_not_recomputed() {
    let rows = csv(&[
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.59..0.595",
        "--steps",
        "2",
        "--near-fixed-point",
        "--keep",
        "1",
        "--digits",
        "15",
    ]);
    assert_eq!(cell(&rows, 2, "resolved"), "true");
    assert_eq!(cell(&rows, 2, "table_periods"), "22");
    for name in ["digits_verdict", "digits_periods", "stick_after"] {
        assert_eq!(cell(&rows, 2, name), "", "{name}");
    }
    assert_eq!(cell(&rows, 1, "digits_verdict"), "found");
}

/// Two shards with the `--digits` columns merge into the whole sweep, byte for byte.
#[test]
fn digits_columns_survive_shards_and_merge() {
    let d = dir("digits-jobs", "merge");
    let whole = d.join("whole.csv");
    let (a, b) = (d.join("a.csv"), d.join("b.csv"));
    let run = |extra: &[&str]| {
        let out = bouncemap(&[&SWEEP[..], extra].concat());
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&["--out", s(&whole)]);
    run(&["--shard", "1/2", "--out", s(&a)]);
    run(&["--shard", "2/2", "--out", s(&b)]);
    merges_into(&d, [&a, &b], &whole);
}

/// `--digits` where it cannot go: a braille picture (sweep and plane), too few digits,
/// and `--max-digits` without it, each one line and status 2.
#[test]
fn digits_refusals_are_one_line() {
    let base = [
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.59..0.6",
        "--steps",
        "2",
    ];
    for (extra, says) in [
        (
            &["--digits", "20", "--format", "braille"][..],
            "valid --format csv or json",
        ),
        (&["--max-digits", "100"][..], "go with --digits N"),
        (&["--digits", "9"][..], "[10, 10000]"),
    ] {
        let out = bouncemap(&[&base[..], extra].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(says), "{extra:?}: {err}");
    }
    let out = bouncemap(&[
        "plane",
        "--table",
        "fd:1",
        "--x",
        "alpha:0.58..0.59",
        "--y",
        "r:0.79..0.8",
        "--size",
        "2x2",
        "--digits",
        "15",
        "--format",
        "braille",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("valid --format csv or json"), "{err}");
}

/// `basins --digits`: fd:1 at α = 0.59, where every start sticks on one cycle double
/// precision does not resolve; its cycle decided at any precision is the independent
/// computation's (L = 78, T = 77.94380773608558746178…), in the json's attractor and
/// under the braille picture; the csv, which has no attractor list, is refused.
#[test]
fn basins_decide_their_unresolved_cycles() {
    let base = [
        "basins", "--table", "fd:1", "--alpha", "0.59", "--grid", "20x10", "--digits", "20",
    ];
    let out = bouncemap(&[&base[..], &["--format", "json"]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let a = &doc["attractors"][0];
    assert_eq!(a["resolved"], false, "{a}");
    assert_eq!(a["cycle"]["verdict"], "found", "{a}");
    assert_eq!(a["cycle"]["periods"], 78, "{a}");
    assert_eq!(a["cycle"]["stick_after"], "77.943807736085587462", "{a}");
    let out = bouncemap(&[&base[..], &["--format", "braille", "--width", "60"]].concat());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("attractor 1 at any precision, cycle: sticking cycle of 78 table periods"),
        "{text}"
    );
    let out = bouncemap(&base);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("valid --format json or braille"), "{err}");
}

/// `plane --digits`: the pixel at (α, r) = (0.59, 0.8) of fd:1 has the independent
/// computation's cycle (78 table periods), the pixel at (0.58, 0.8) the sweep's (both
/// from the start next to the (1, 1) solution), a pixel double precision resolves has
/// empty cells; two shards merge into the whole, byte for byte.
#[test]
fn a_plane_decides_its_unresolved_pixels() {
    let d = dir("digits-jobs", "plane");
    let args = [
        "plane",
        "--table",
        "fd:1",
        "--x",
        "alpha:0.58..0.59",
        "--y",
        "r:0.79..0.8",
        "--size",
        "2x2",
        "--digits",
        "15",
    ];
    let whole = d.join("whole.csv");
    let (a, b) = (d.join("a.csv"), d.join("b.csv"));
    for extra in [
        &["--out", s(&whole)][..],
        &["--shard", "1/2", "--out", s(&a)],
        &["--shard", "2/2", "--out", s(&b)],
    ] {
        let out = bouncemap(&[&args[..], extra].concat());
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let rows: Vec<Vec<String>> = body(&whole)
        .iter()
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    // Rows: (0.58, 0.79), (0.59, 0.79), (0.58, 0.8), (0.59, 0.8).
    assert_eq!(cell(&rows, 4, "digits_verdict"), "found");
    assert_eq!(cell(&rows, 4, "digits_periods"), "78");
    assert_eq!(cell(&rows, 3, "digits_periods"), "76");
    assert_eq!(cell(&rows, 4, "agreed_digits"), "15");
    for (row, _) in rows.iter().enumerate().skip(1) {
        let resolved = cell(&rows, row, "resolved") == "true";
        assert_eq!(
            resolved,
            cell(&rows, row, "digits_verdict").is_empty(),
            "{row}"
        );
    }
    merges_into(&d, [&a, &b], &whole);
}

/// `sweep`, `plane` and `basins` read their windows and parameters as typed too. On
/// fd:1 a window 0.59..0.59000000000000000001 in two steps is one double, 0.59, but two
/// systems at any precision: its first value's sticking cycle is 0.59's 78-period one,
/// its second value's the one `lyapunov --digits` finds at α = 0.59000000000000000001,
/// and a plane's two pixels on that window the same. `basins` on F_D at D =
/// 0.999999999999999999999 decides the cycle `lyapunov --digits` finds for that D (a
/// sticking cycle repeats from its release, whatever the start), not fd:1's.
#[test]
fn jobs_read_windows_and_parameters_as_typed() {
    let long = "0.59000000000000000001";
    let lyapunov_periods = |table: &str, alpha: &str| {
        let rows = csv(&[
            "lyapunov", "--table", table, "--alpha", alpha, "--r", "0.8", "--digits", "20",
            "--format", "csv",
        ]);
        cell(&rows, 1, "periods").to_string()
    };
    let typed = lyapunov_periods("fd:1", long);
    assert_ne!(typed, "78");
    let window = format!("0.59..{long}");
    // The sweep of the tests above over the typed window.
    let mut sweep = SWEEP.to_vec();
    assert_eq!(sweep[3], "--alpha");
    sweep[4] = &window;
    let text = stdout_of(&sweep);
    let rows = rows_of(&text);
    let periods = [1, 2].map(|i| cell(&rows, i, "digits_periods"));
    assert_eq!(periods, ["78", typed.as_str()], "{text}");
    assert!(
        text.contains(&format!("alpha={window}")),
        "the header names the window typed"
    );

    let rows = csv(&[
        "plane",
        "--table",
        "fd:1",
        "--x",
        &format!("alpha:{window}"),
        "--y",
        "r:0.8..0.8",
        "--size",
        "2x1",
        "--digits",
        "20",
        "--format",
        "csv",
    ]);
    let pixels = [1, 2].map(|i| cell(&rows, i, "digits_periods"));
    assert_eq!(pixels, ["78", typed.as_str()], "{rows:?}");

    let d = "fd:0.999999999999999999999";
    let want = lyapunov_periods(d, "0.59");
    assert_ne!(want, "78");
    let doc: serde_json::Value = serde_json::from_str(&stdout_of(&[
        "basins", "--table", d, "--alpha", "0.59", "--grid", "4x2", "--digits", "20", "--format",
        "json",
    ]))
    .unwrap();
    let found: Vec<String> = doc["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|a| a["cycle"]["periods"].as_i64().map(|p| p.to_string()))
        .collect();
    assert!(
        !found.is_empty() && found.iter().all(|p| *p == want),
        "{found:?} vs {want}"
    );
}
