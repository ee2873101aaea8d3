//! The `sweep` and `merge` commands as a user runs them: presets, formats, shards
//! merged against the unsharded run, agreement with `orbit`, and bad input.

use std::process::{Command, Output};

fn bouncemap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The data of a sweep csv: the header row and the rows, without the `#` lines of
/// its provenance and its end.
fn data(text: &str) -> Vec<&str> {
    text.lines().filter(|l| !l.starts_with('#')).collect()
}

fn stdout(o: &Output) -> String {
    assert!(
        o.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn tmp(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("bouncemap-sweep-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_string_lossy().into_owned()
}

#[test]
fn every_preset_parses_and_runs() {
    for (name, _) in bouncemap::config::presets::PRESETS {
        let o = bouncemap(&[
            "sweep",
            "--preset",
            name,
            "--steps",
            "3",
            "--transient",
            "300",
            "--keep",
            "5",
        ]);
        let text = stdout(&o);
        let rows: Vec<&str> = data(&text);
        assert_eq!(
            rows[0],
            "index,alpha,phase,v,kind,period,table_periods,status,sticking,resolved,growth_decades"
        );
        let indices: std::collections::BTreeSet<&str> = rows[1..]
            .iter()
            .map(|r| r.split(',').next().unwrap())
            .collect();
        assert_eq!(indices.len(), 3, "{name}: {indices:?}");
    }
}

#[test]
fn presets_state_the_paper_fidelity() {
    for (name, text) in bouncemap::config::presets::PRESETS {
        let p = bouncemap::config::presets::preset(name).unwrap();
        assert_eq!(
            (p.steps, p.transient, p.keep),
            (1000, 5_000_000, 100),
            "{name}"
        );
        assert_eq!(p.r, Some(0.8));
        assert!(
            text.starts_with("# Fig. 3(") || text.starts_with("# Fig. 4("),
            "{name} says what it shows"
        );
        assert!(p.window[0] < p.window[1]);
    }
}

#[test]
fn sharded_runs_merge_into_the_unsharded_run() {
    let base = [
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45..0.6",
        "--steps",
        "11",
        "--transient",
        "2000",
        "--keep",
        "7",
    ];
    for format in ["csv", "json"] {
        let mut whole_args = base.to_vec();
        whole_args.extend(["--format", format]);
        let whole = stdout(&bouncemap(&whole_args));
        let mut files = Vec::new();
        for i in 1..=3 {
            let f = tmp(&format!("part{i}.{format}"));
            let shard = format!("{i}/3");
            let mut a = whole_args.clone();
            a.extend(["--shard", &shard, "--out", &f]);
            stdout(&bouncemap(&a));
            files.push(f);
        }
        let mut m = vec!["merge"];
        m.extend(files.iter().map(String::as_str));
        let merged = stdout(&bouncemap(&m));
        // The unsharded file, but for the provenance's shard: `merged 3/3` for `1/1`.
        assert_eq!(merged.replace("merged 3/3", "1/1"), whole, "{format}");
        // A missing part is refused for json, which records the number of values.
        if format == "json" {
            let o = bouncemap(&["merge", &files[0], &files[1]]);
            assert_eq!(o.status.code(), Some(2));
        }
        // The same part twice is refused.
        let o = bouncemap(&["merge", &files[0], &files[0]]);
        assert_eq!(o.status.code(), Some(2));
    }
}

#[test]
fn sweep_points_agree_with_orbit() {
    // One value, no early stop: the sweep's last 5 events before T = 300 are the
    // orbit's events with period < 300.
    let csv = stdout(&bouncemap(&[
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.6..0.6",
        "--steps",
        "1",
        "--transient",
        "300",
        "--keep",
        "5",
        "--no-early-stop",
    ]));
    let sweep_rows: Vec<Vec<String>> = data(&csv)
        .into_iter()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    let orbit = stdout(&bouncemap(&[
        "orbit",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.6",
        "--r",
        "0.8",
        "--bounces",
        "1000",
        "--format",
        "csv",
    ]));
    let before: Vec<Vec<String>> = orbit
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect::<Vec<_>>())
        .filter(|r| r[1].parse::<i64>().unwrap() < 300)
        .collect();
    let last = &before[before.len() - 5..];
    assert_eq!(sweep_rows.len(), 5);
    for (s, o) in sweep_rows.iter().zip(last) {
        assert_eq!((&s[2], &s[3], &s[4]), (&o[2], &o[3], &o[5]));
        assert_eq!(s[7], "unsettled");
    }
}

#[test]
fn braille_has_the_requested_size_and_labels() {
    let text = stdout(&bouncemap(&[
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45..0.6",
        "--steps",
        "20",
        "--transient",
        "500",
        "--keep",
        "10",
        "--format",
        "braille",
        "--width",
        "40",
        "--height",
        "12",
    ]));
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("fd:0.1"));
    assert!(lines.iter().any(|l| l.contains("alpha")));
    assert!(lines.iter().any(|l| l.starts_with(" 1.0 ┤")));
    let plot: Vec<&&str> = lines
        .iter()
        .filter(|l| l.contains('┤') || l.contains('│'))
        .collect();
    assert_eq!(
        plot.len(),
        8,
        "12 lines minus title, axis, labels and a spare"
    );
    for l in plot {
        assert_eq!(l.chars().count(), 40);
    }
    // The stable (1, 1) branch at the left edge is drawn: some dot is set.
    assert!(text.chars().any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)));
}

#[test]
fn bad_input_is_one_line_with_status_2() {
    let cases: [&[&str]; 8] = [
        &["sweep", "--alpha", "0.6..0.4"],
        &["sweep", "--alpha", "0.4"],
        &["sweep", "--alpha", "0.4..0.6", "--r", "1.5"],
        &["sweep", "--alpha", "0.4..0.6", "--steps", "0"],
        &["sweep", "--alpha", "0.4..0.6", "--shard", "0/3"],
        &["sweep", "--alpha", "0.4..0.6", "--r", "0.5..0.7"],
        &["sweep", "--preset", "fig9"],
        &["merge", "/nonexistent/part.csv"],
    ];
    for args in cases {
        let o = bouncemap(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(!err.contains("panicked"));
    }
    let err =
        String::from_utf8_lossy(&bouncemap(&["sweep", "--alpha", "0.4..0.6", "--r", "1.5"]).stderr)
            .to_string();
    assert!(err.contains("--r") && err.contains("(0, 1)"), "{err}");
}

#[test]
fn resting_values_are_reported_in_csv() {
    // sine, α = 0.02 < 1/(4π²), r = 0.5: the ball ends up riding the table for good.
    let csv = stdout(&bouncemap(&[
        "sweep",
        "--table",
        "sine",
        "--alpha",
        "0.02..0.02",
        "--r",
        "0.5",
        "--steps",
        "1",
        "--transient",
        "1000",
        "--keep",
        "3",
    ]));
    let last = *data(&csv).last().unwrap();
    assert!(last.ends_with(",resting,true,,"), "{last}");
}

/// With several starts each attractor's rows say whether that attractor sticks: at
/// α = 0.47 on F_1 the stable (1, 1) solution (no stick) coexists with a sticking cycle,
/// and the file still verifies (`merge` reads it back).
#[test]
fn with_several_starts_sticking_is_each_attractors() {
    let out = tmp("starts-sticking.csv");
    let o = bouncemap(&[
        "sweep",
        "--table",
        "fd:1",
        "--alpha",
        "0.47..0.48",
        "--steps",
        "2",
        "--starts",
        "4",
        "--transient",
        "5000",
        "--format",
        "csv",
        "--out",
        &out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    let rows = data(&text);
    let header: Vec<&str> = rows[0].split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (kind, period, sticking, attractor) = (
        col("kind"),
        col("period"),
        col("sticking"),
        col("attractor"),
    );
    let mut seen = [false; 2];
    // Per (value, attractor): whether any of its rows is a stick or a release.
    let mut groups: std::collections::BTreeMap<(String, String), (bool, Vec<String>)> =
        Default::default();
    for r in &rows[1..] {
        let f: Vec<&str> = r.split(',').collect();
        let g = groups
            .entry((f[0].to_string(), f[attractor].to_string()))
            .or_default();
        g.0 |= f[kind] != "impact";
        g.1.push(f[sticking].to_string());
        if f[period] == "1" {
            seen[0] = true;
        }
    }
    for ((value, a), (sticks, flags)) in &groups {
        let want = if *sticks { "true" } else { "false" };
        assert!(
            flags.iter().all(|s| s == want),
            "value {value}, attractor {a}: sticking {flags:?}"
        );
        seen[1] |= *sticks;
    }
    assert!(seen[0] && seen[1], "both a (1, 1) and a sticking attractor");
    let merged = tmp("starts-sticking-merged.csv");
    let o = bouncemap(&["merge", &out, "--out", &merged]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
