//! `attractors --shard I/N` and `merge` of its parts, as a user on a cluster runs them:
//! the parts merged are the run over the whole window (a second computation of every
//! picture, joined where the parts meet), in every format, with Slurm's `auto` part;
//! damaged, missing, doubled or foreign parts and contradicting flags are refused with
//! one line and status 2, and nothing is written.

use crate::cli::{ok, run};
use crate::scratch::{self, s};
use std::path::{Path, PathBuf};

/// The F_D table at D = 0.5 over a window with a resting ball, the (1, 1) solution and
/// its period doubling, a (1, 2) cycle, a sticking cycle and a chaotic attractor.
const RUN: [&str; 11] = [
    "attractors",
    "--table",
    "fd:0.5",
    "--alpha",
    "0.3..0.6",
    "--steps",
    "30",
    "--grid",
    "40x40",
    "--threads",
    "2",
];

fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
    base.iter().chain(more).copied().collect()
}

fn dir(name: &str) -> PathBuf {
    scratch::dir("shards", name)
}

/// The parts 1/n .. n/n of `RUN` written into `d`.
fn parts(d: &Path, n: usize) -> Vec<String> {
    (1..=n)
        .map(|i| {
            let p = d.join(format!("part{i}.json"));
            let shard = format!("{i}/{n}");
            ok(&with(&RUN, &["--shard", &shard, "--out", s(&p)]));
            s(&p).to_string()
        })
        .collect()
}

fn merge(files: &[String], more: &[&str]) -> (i32, String, String) {
    let mut args = vec!["merge"];
    args.extend(files.iter().map(String::as_str));
    args.extend(more);
    run(&args)
}

/// Exit 2 with one line of stderr containing `want`.
fn refused((code, _, err): (i32, String, String), want: &str) {
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(err.contains(want), "{err:?} lacks {want:?}");
}

#[test]
fn the_parts_merged_are_the_run_over_the_whole_window() {
    let d = dir("whole");
    let files = parts(&d, 3);
    let whole = ok(&with(&RUN, &["--format", "csv"]));
    let (code, merged, err) = merge(&files, &["--format", "csv"]);
    assert_eq!(code, 0, "{err}");
    // Row by row the same attractors, kinds, (n, k), starts, fractions, changes and
    // statistics. A point is a representative one: a cycle's event as the orbit that
    // found it first met it (the same to rounding), where the ball came to rest for
    // the resting balls (any of their places).
    let (a, b): (Vec<&str>, Vec<&str>) = (whole.lines().collect(), merged.lines().collect());
    assert_eq!(a.len(), b.len(), "{whole}\n{merged}");
    let header: Vec<&str> = a[0].split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (phase, v, lyapunov, kind) = (col("phase"), col("v"), col("lyapunov"), col("kind"));
    for (x, y) in a.iter().zip(&b) {
        let (x, y): (Vec<&str>, Vec<&str>) = (x.split(',').collect(), y.split(',').collect());
        for (c, (p, q)) in x.iter().zip(&y).enumerate() {
            if [phase, v, lyapunov].contains(&c) && p != q {
                if x[kind] != "resting" {
                    let (p, q): (f64, f64) = (p.parse().unwrap(), q.parse().unwrap());
                    assert!((p - q).abs() < 1e-12, "{x:?} {y:?}");
                }
            } else {
                assert_eq!(p, q, "column {} of {x:?} {y:?}", header[c]);
            }
        }
    }
    // The joins, in the text report and the json: both pictures at the joining
    // values count the same starts on every attractor.
    let (_, text, _) = merge(&files, &[]);
    assert!(text.contains("merged from 3 parts"), "{text}");
    assert_eq!(
        text.matches("the two pictures agree on every basin fraction")
            .count(),
        2,
        "{text}"
    );
    let (_, j, _) = merge(&files, &["--format", "json"]);
    let j: serde_json::Value = serde_json::from_str(&j).unwrap();
    let joins = j["joins"].as_array().unwrap();
    assert_eq!(joins.len(), 2);
    for join in joins {
        assert_eq!(join["fraction_difference"], 0.0, "{join}");
        assert!(join["matched"].as_u64().unwrap() >= 2, "{join}");
    }
    // The joining values are the last of shards 1 and 2: values 10 and 20 of 30.
    let alpha = |i: f64| 0.3 + 0.3 * i / 29.0;
    assert!((joins[0]["alpha"].as_f64().unwrap() - alpha(9.0)).abs() < 1e-15);
    assert!((joins[1]["alpha"].as_f64().unwrap() - alpha(19.0)).abs() < 1e-15);
    // The order of the files does not matter; a run in one part merges to itself.
    let shuffled = [files[2].clone(), files[0].clone(), files[1].clone()];
    assert_eq!(merge(&shuffled, &["--format", "csv"]).1, merged);
    let one = d.join("one.json");
    ok(&with(&RUN, &["--shard", "1/1", "--out", s(&one)]));
    assert_eq!(merge(&[s(&one).to_string()], &["--format", "csv"]).1, whole);
}

#[test]
fn a_slurm_array_task_computes_its_part() {
    // Task 1 of --array=0-2 is part 2/3, as `--shard 2/3` computes it.
    let d = dir("auto");
    let auto = d.join("auto.json");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(with(&RUN, &["--out", s(&auto)]))
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_TASK_MIN", "0")
        .env("SLURM_ARRAY_TASK_MAX", "2")
        .env_remove("SLURM_ARRAY_TASK_COUNT")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let given = d.join("given.json");
    ok(&with(&RUN, &["--shard", "2/3", "--out", s(&given)]));
    assert_eq!(
        std::fs::read(&auto).unwrap(),
        std::fs::read(&given).unwrap()
    );
}

#[test]
fn bad_parts_and_flags_are_refused_with_one_line() {
    let d = dir("bad");
    let files = parts(&d, 3);
    let out = d.join("merged.txt");
    std::fs::write(&out, "kept").unwrap();
    let o = ["--out", s(&out)];
    refused(merge(&files[..2], &o), "shard 3/3 is missing");
    refused(
        merge(&[files[0].clone(), files[2].clone()], &o),
        "shard 2/3 is missing",
    );
    refused(
        merge(&[files[0].clone(), files[1].clone(), files[1].clone()], &o),
        "shard 2/3 is given twice",
    );
    // A part of another run (another grid).
    let other = d.join("other.json");
    let mut args = with(&RUN, &["--shard", "3/3", "--out", s(&other)]);
    let g = args.iter().position(|a| *a == "40x40").unwrap();
    args[g] = "40x41";
    ok(&args);
    refused(
        merge(&[files[0].clone(), files[1].clone(), s(&other).into()], &o),
        "a part of another attractors run",
    );
    // A value changed by hand: the checksum no longer holds.
    let text = std::fs::read_to_string(&files[1]).unwrap();
    let edited = d.join("edited.json");
    let changed = text.replacen("\"starts\":1600", "\"starts\":1601", 1);
    assert_ne!(changed, text);
    std::fs::write(&edited, changed).unwrap();
    refused(
        merge(&[files[0].clone(), s(&edited).into(), files[2].clone()], &o),
        "checksum",
    );
    // The spec changed by hand: its hash no longer holds.
    let respec = d.join("respec.json");
    std::fs::write(&respec, text.replacen("\"r\":0.8", "\"r\":0.7", 1)).unwrap();
    refused(
        merge(&[files[0].clone(), s(&respec).into(), files[2].clone()], &o),
        "spec_hash",
    );
    // Cut short.
    let cut = d.join("cut.json");
    std::fs::write(&cut, &text[..text.len() / 2]).unwrap();
    refused(
        merge(&[files[0].clone(), s(&cut).into(), files[2].clone()], &o),
        "not an attractors part",
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "kept");
    // Flags that contradict a part.
    refused(
        run(&with(&RUN, &["--shard", "1/3", "--format", "csv"])),
        "--format csv: a part of `attractors --shard` is a json file",
    );
    refused(
        run(&with(&RUN, &["--shard", "2/31"])),
        "valid at most one part per α value",
    );
    refused(run(&with(&RUN, &["--shard", "4/3"])), "not a shard");
    let sweep = d.join("sweep.csv");
    ok(&[
        "sweep",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.4..0.5",
        "--steps",
        "4",
        "--shard",
        "1/1",
        "--out",
        s(&sweep),
    ]);
    refused(
        merge(&[s(&sweep).into()], &["--format", "text"]),
        "valid only for parts of `attractors`",
    );
}

#[test]
fn the_check_states_the_part() {
    let plan = ok(&with(&RUN, &["--shard", "2/3", "--check"]));
    assert!(
        plan.contains("part 2/3 of the attractors: α values 11..20 of 30 (from value 10"),
        "{plan}"
    );
}

#[test]
fn resume_leaves_a_verified_part_and_recomputes_a_damaged_one() {
    let d = dir("resume");
    let p = d.join("part2.json");
    let args = with(&RUN, &["--shard", "2/3", "--resume", "--out", s(&p)]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("no "), "{err}");
    let written = std::fs::read(&p).unwrap();
    let modified = std::fs::metadata(&p).unwrap().modified().unwrap();
    // Complete and verified: nothing computed, the file untouched.
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("nothing to compute"), "{err}");
    assert!(!err.contains("starts/s"), "{err}");
    assert_eq!(std::fs::metadata(&p).unwrap().modified().unwrap(), modified);
    // This run's part cut short: computed again, the same.
    std::fs::write(&p, &written[..written.len() / 3]).unwrap();
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("computing it"), "{err}");
    assert_eq!(std::fs::read(&p).unwrap(), written);
    // Another shard's part, or a file of someone else's: refused and left as it is.
    let (code, _, err) = run(&with(&RUN, &["--shard", "1/3", "--resume", "--out", s(&p)]));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("not shard 1/3"), "{err}");
    assert_eq!(std::fs::read(&p).unwrap(), written);
    let notes = d.join("notes.json");
    std::fs::write(&notes, "{\"mine\": 1}").unwrap();
    refused(
        run(&with(
            &RUN,
            &["--shard", "1/3", "--resume", "--out", s(&notes)],
        )),
        "it is not this run's output",
    );
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "{\"mine\": 1}");
    refused(
        run(&with(&RUN, &["--resume", "--out", s(&notes)])),
        "--resume without --shard",
    );
}
