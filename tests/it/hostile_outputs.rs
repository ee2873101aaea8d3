//! Hostile input, round two: what a run writes. A reader that closes the pipe ends every
//! writer quietly and at once; a full disk is reported by every command that writes;
//! `--out` never replaces an input of the run, and `--resume` replaces only the run's
//! own output. Each case runs against the real binary, with the harness of
//! [`crate::hostile`].

use crate::hostile::{bin, dir, refused, run, run_to};
use crate::scratch::s;
use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

// ---------------------------------------------------------------- 2. closed pipes

/// Read `first` bytes of `args`' output, close the pipe, and return how it ended.
fn reader_closes(args: &[&str], first: usize) -> (Option<i32>, Option<i32>, String, Duration) {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    {
        let mut out = child.stdout.take().unwrap();
        let mut b = vec![0u8; first];
        out.read_exact(&mut b).unwrap();
    }
    let t = Instant::now();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    (status.code(), status.signal(), err, t.elapsed())
}

#[test]
fn a_closed_pipe_ends_every_writer_quietly_and_at_once() {
    for (args, first) in [
        // Long runs: the closed pipe is noticed between batches, not at the next write.
        (&["sweep", "--alpha", "0.4..0.6"][..], 10),
        (
            &["sweep", "--alpha", "0.4..0.6", "--format", "json"][..],
            10,
        ),
        (&["orbit", "--bounces", "1e12"][..], 100),
        (&["orbit", "--bounces", "1e12", "--format", "json"][..], 100),
        (&["orbit", "--bounces", "1e12", "--format", "csv"][..], 100),
    ] {
        let (code, signal, err, took) = reader_closes(args, first);
        assert!(
            code == Some(0) || signal == Some(libc::SIGPIPE),
            "{args:?}: {code:?} {signal:?} {err}"
        );
        assert_eq!(err, "", "{args:?}");
        assert!(took < Duration::from_secs(3), "{args:?} took {took:?}");
    }
    // A computation that writes only at its end stops when its reader goes away.
    let mut child = bin()
        .args(["basins", "--grid", "1000x1000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    drop(child.stdout.take());
    let t = Instant::now();
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
    assert!(t.elapsed() < Duration::from_secs(3), "{:?}", t.elapsed());
}

// ---------------------------------------------------------------- 3. full disks

#[test]
fn every_command_that_writes_reports_a_full_disk() {
    let d = dir("full");
    let part = d.join("p.csv");
    let made = run(&[
        "sweep",
        "--alpha",
        "0.45..0.46",
        "--steps",
        "2",
        "--transient",
        "100",
        "--out",
        s(&part),
    ]);
    assert_eq!(made.code, Some(0), "{}", made.err);
    let small_sweep = [
        "--alpha",
        "0.45..0.46",
        "--steps",
        "2",
        "--transient",
        "100",
    ];
    let cases: Vec<Vec<&str>> = vec![
        vec!["orbit", "--bounces", "3"],
        vec!["fixed"],
        vec!["two-cycle", "--alpha", "0.6"],
        vec!["scaling", "--d", "0.1"],
        vec!["continue", "--alpha", "0.45..0.46"],
        vec!["cascade", "--depth", "1"],
        [&["sweep"][..], &small_sweep].concat(),
        [
            &[
                "sweep", "--format", "braille", "--width", "20", "--height", "10",
            ][..],
            &small_sweep,
        ]
        .concat(),
        vec!["lyapunov", "--impacts", "100", "--transient", "100"],
        vec!["basins", "--grid", "3x3", "--transient", "100"],
        vec![
            "plane",
            "--x",
            "alpha:0.4..0.5",
            "--y",
            "r:0.7..0.8",
            "--size",
            "3x3",
            "--transient",
            "100",
        ],
        vec!["merge", s(&part)],
        vec!["bench", "--quick"],
        vec!["sweep", "--help"],
        vec!["sweep", "--check", "--alpha", "0.4..0.5"],
    ];
    for args in cases {
        let mut c = bin();
        c.args(&args);
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let r = run_to(c, Duration::from_secs(120), full.into());
        assert_eq!(r.code, Some(1), "{args:?}: {}", r.err);
        assert!(
            r.err.trim_end().lines().last().unwrap_or("")
                == "error: cannot write standard output: No space left on device (os error 28)",
            "{args:?}: {}",
            r.err
        );
    }
    // A figure to a full device names it.
    let r = run(&["figure", "fig2", "--out", "/dev/full", "--format", "svg"]);
    assert_eq!(r.code, Some(1), "{}", r.err);
    assert!(r.err.contains("cannot write /dev/full"), "{}", r.err);
    std::fs::remove_dir_all(&d).unwrap();
}

// ---------------------------------------------------------------- 7, 8. --out and --resume

#[test]
fn out_never_replaces_an_input_of_the_run() {
    let d = dir("out");
    let sweep = |shard: &str, out: &Path| {
        let r = run(&[
            "sweep",
            "--alpha",
            "0.45..0.46",
            "--steps",
            "4",
            "--transient",
            "100",
            "--keep",
            "2",
            "--shard",
            shard,
            "--out",
            s(out),
        ]);
        assert_eq!(r.code, Some(0), "{}", r.err);
    };
    let (a, b) = (d.join("a.csv"), d.join("b.csv"));
    sweep("1/2", &a);
    sweep("2/2", &b);
    let before = std::fs::read(&a).unwrap();
    std::os::unix::fs::symlink(&a, d.join("link.csv")).unwrap();
    std::fs::hard_link(&a, d.join("hard.csv")).unwrap();
    let dot_a = format!("{}/./a.csv", s(&d));
    for out in [
        s(&a),
        &dot_a,
        s(&d.join("link.csv")),
        s(&d.join("hard.csv")),
    ] {
        let r = run(&["merge", s(&a), s(&b), "--out", out]);
        refused(&r, "an input of this run");
    }
    assert_eq!(std::fs::read(&a).unwrap(), before, "an input was changed");
    let merged = d.join("m.csv");
    assert_eq!(
        run(&["merge", s(&a), s(&b), "--out", s(&merged)]).code,
        Some(0)
    );
    // A table file is an input too; two outputs of one run are two files.
    let table = d.join("t.toml");
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/assets/tables/fd1.toml"),
        &table,
    )
    .unwrap();
    let text = std::fs::read(&table).unwrap();
    refused(
        &run(&[
            "sweep",
            "--table",
            s(&table),
            "--alpha",
            "0.4..0.5",
            "--steps",
            "2",
            "--out",
            s(&table),
        ]),
        "an input of this run",
    );
    assert_eq!(std::fs::read(&table).unwrap(), text);
    let fig = d.join("f.svg");
    refused(
        &run(&["figure", "fig2", "--out", s(&fig), "--data", s(&fig)]),
        "already an output of this run",
    );
    assert!(!fig.exists());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn resume_replaces_only_this_runs_own_output() {
    let d = dir("resume");
    let out = d.join("part.csv");
    let args = |out: &Path| {
        vec![
            "sweep".to_string(),
            "--alpha".into(),
            "0.45..0.46".into(),
            "--steps".into(),
            "4".into(),
            "--transient".into(),
            "100".into(),
            "--resume".into(),
            "--out".into(),
            s(out).into(),
        ]
    };
    let go = |out: &Path| {
        let a = args(out);
        run(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    for foreign in [
        "precious notes\n".to_string(),
        "# bouncemap 0.1.0 sweep\n# spec {}\n# spec-hash 0000000000000000\n# shard 1/1\n".into(),
    ] {
        std::fs::write(&out, &foreign).unwrap();
        let r = go(&out);
        refused(&r, "it is not this run's output, so it is left as it is");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), foreign);
    }
    // This run's own part, cut off: recomputed.
    std::fs::remove_file(&out).unwrap();
    assert_eq!(go(&out).code, Some(0));
    let whole = std::fs::read_to_string(&out).unwrap();
    std::fs::write(&out, &whole[..whole.len() - 40]).unwrap();
    let r = go(&out);
    assert_eq!(r.code, Some(0), "{}", r.err);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), whole);
    std::fs::remove_dir_all(&d).unwrap();
}
