//! Nothing lost, nothing wrong, never stuck: each reproduction of a way to lose data, to
//! get a wrong merged file with status 0, or to hang, run against the real binary.

use crate::scratch::s;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("rel", name)
}

/// Exit 2 with one line of stderr containing `want`.
pub(crate) fn refused(o: &Output, want: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(err.contains(want), "{err:?} lacks {want:?}");
    assert!(!err.contains("panicked"), "{err}");
}

fn files_in(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn an_interrupted_sweep_leaves_the_old_file_and_no_temporary() {
    let d = dir("sigterm");
    let prev = d.join("prev.csv");
    std::fs::write(&prev, "data\n").unwrap();
    let mut child = bin()
        .args(["sweep", "--preset", "fig3b", "--out", s(&prev)])
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(1));
    assert!(Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap()
        .success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(143));
    assert_eq!(std::fs::read_to_string(&prev).unwrap(), "data\n");
    assert_eq!(
        files_in(&d),
        vec!["prev.csv"],
        "a temporary was left behind"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn two_writers_of_one_file_leave_one_complete_file() {
    let d = dir("race");
    let out = d.join("out.csv");
    let spawn = |keep: &str| {
        bin()
            .args([
                "sweep",
                "--alpha",
                "0.45..0.6",
                "--steps",
                "300",
                "--transient",
                "20000",
                "--keep",
                keep,
                "--out",
                s(&out),
            ])
            .stderr(Stdio::null())
            .spawn()
            .unwrap()
    };
    let (mut a, mut b) = (spawn("10"), spawn("20"));
    assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
    // Whichever finished last wins, whole: its end line is there and it checks out.
    let merged = run(&["merge", s(&out)]);
    assert!(
        merged.status.success(),
        "{}",
        String::from_utf8_lossy(&merged.stderr)
    );
    assert_eq!(files_in(&d), vec!["out.csv"]);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_full_disk_names_the_file_and_exits_1() {
    let o = run(&[
        "sweep",
        "--alpha",
        "0.45..0.5",
        "--steps",
        "5",
        "--transient",
        "1000",
        "--out",
        "/dev/full",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.lines()
            .last()
            .unwrap()
            .contains("cannot write /dev/full"),
        "{err}"
    );
    let o = run(&[
        "sweep",
        "--alpha",
        "0.45..0.5",
        "--out",
        "/nonexistent-dir/x.csv",
    ]);
    refused(&o, "/nonexistent-dir/x.csv");
}

/// Shards 1..=n of one small sweep, and the unsharded file.
fn shards(d: &Path, extra: &[&str], n: usize, ext: &str) -> (Vec<PathBuf>, PathBuf) {
    let keep = if extra.contains(&"--keep") {
        &[][..]
    } else {
        &["--keep", "4"][..]
    };
    let base: Vec<&str> = [
        "sweep",
        "--preset",
        "fig3b",
        "--steps",
        "12",
        "--transient",
        "2000",
    ]
    .into_iter()
    .chain(keep.iter().copied())
    .collect();
    let mut parts = Vec::new();
    for i in 1..=n {
        let p = d.join(format!("p{i}{}.{ext}", extra.join("")));
        let shard = format!("{i}/{n}");
        let mut args: Vec<&str> = base.clone();
        args.extend_from_slice(extra);
        args.extend(["--shard", &shard, "--format", ext, "--out", s(&p)]);
        assert!(run(&args).status.success());
        parts.push(p);
    }
    let whole = d.join(format!("whole.{ext}"));
    let mut args: Vec<&str> = base;
    args.extend_from_slice(extra);
    args.extend(["--format", ext, "--out", s(&whole)]);
    assert!(run(&args).status.success());
    (parts, whole)
}

fn merge(parts: &[&Path]) -> Output {
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(|p| s(p)));
    run(&args)
}

/// The merged file is the unsharded one; only the provenance's shard differs.
fn same_but_shard(merged: &str, whole: &str) {
    let strip = |t: &str| -> String {
        t.lines()
            .filter(|l| !l.starts_with("# shard "))
            .map(|l| {
                // json: the provenance's shard field.
                match l.find("\"shard\":\"") {
                    Some(i) => {
                        let end = l[i + 9..].find('"').unwrap() + i + 10;
                        format!("{}{}", &l[..i], &l[end..])
                    }
                    None => l.to_string(),
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(strip(merged), strip(whole));
}

#[test]
fn merges_check_their_parts_and_refuse_any_bad_one_naming_it() {
    let d = dir("merge");
    let (p, whole) = shards(&d, &[], 3, "csv");
    let ok = merge(&[&p[0], &p[1], &p[2]]);
    assert!(ok.status.success());
    let merged = String::from_utf8(ok.stdout).unwrap();
    same_but_shard(&merged, &std::fs::read_to_string(&whole).unwrap());
    assert!(merged.contains("# shard merged 3/3"));
    let part1 = std::fs::read_to_string(&p[1]).unwrap();
    let write = |name: &str, text: &str| {
        let f = d.join(name);
        std::fs::write(&f, text).unwrap();
        f
    };
    // A truncated row (5 of 9 fields).
    let lines: Vec<&str> = part1.lines().collect();
    let fields: Vec<&str> = lines[7].split(',').collect();
    let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    edited[7] = fields[..5].join(",");
    let short = edited.join("\n") + "\n";
    refused(
        &merge(&[&p[0], &write("short.csv", &short), &p[2]]),
        "short.csv: line 8",
    );
    // A part cut off mid-file.
    let cut = write("cut.csv", &part1[..part1.len() / 2]);
    refused(&merge(&[&p[0], &cut, &p[2]]), "cut.csv");
    // kind=garbage, a NaN phase.
    let garbage = write("garbage.csv", &part1.replacen(",impact,", ",garbage,", 1));
    refused(&merge(&[&p[0], &garbage, &p[2]]), "garbage.csv");
    let phase = fields[2];
    let nan = write("nan.csv", &part1.replacen(phase, "NaN", 1));
    refused(&merge(&[&p[0], &nan, &p[2]]), "nan.csv");
    // A missing part file; a missing shard; a duplicated shard.
    refused(&merge(&[&p[0], &d.join("nope.csv"), &p[2]]), "nope.csv");
    refused(&merge(&[&p[0], &p[2]]), "missing shard 2/3");
    refused(
        &merge(&[&p[0], &p[1], &p[1], &p[2]]),
        "shard 2/3 is also in",
    );
    // Parts of other sweeps: another r, another keep.
    let (r7, _) = shards(&d, &["--r", "0.7"], 3, "csv");
    refused(&merge(&[&p[0], &r7[1], &p[2]]), "a part of another sweep");
    let (k5, _) = shards(&d, &["--keep", "5"], 3, "csv");
    refused(&merge(&[&p[0], &k5[1], &p[2]]), "a part of another sweep");
    // An edited specification no longer matches its hash.
    let edited = write(
        "edited.csv",
        &part1.replacen("\"keep\":4", "\"keep\":40", 1),
    );
    refused(&merge(&[&p[0], &edited, &p[2]]), "does not match its hash");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn json_merges_check_indices_and_values() {
    let d = dir("merge-json");
    let (p, whole) = shards(&d, &[], 2, "json");
    let ok = merge(&[&p[0], &p[1]]);
    assert!(ok.status.success());
    same_but_shard(
        &String::from_utf8(ok.stdout).unwrap(),
        &std::fs::read_to_string(&whole).unwrap(),
    );
    let part = std::fs::read_to_string(&p[1]).unwrap();
    let write = |name: &str, text: String| {
        let f = d.join(name);
        std::fs::write(&f, text).unwrap();
        f
    };
    let outside = write(
        "outside.json",
        part.replacen("\"index\":1,", "\"index\":99,", 1),
    );
    refused(&merge(&[&p[0], &outside]), "outside.json");
    let i = part.find("\"value\":").unwrap() + 8;
    let j = i + part[i..].find(',').unwrap();
    let abc = write("abc.json", format!("{}\"abc\"{}", &part[..i], &part[j..]));
    refused(&merge(&[&p[0], &abc]), "abc.json");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_table_beyond_the_proven_range_is_refused_naming_the_bound() {
    let d = dir("huge");
    for (c, want) in [
        ("1e15", "valid at most 1000"),
        ("1e200", "valid at most 1e100"),
    ] {
        let f = d.join("huge.toml");
        std::fs::write(
            &f,
            format!(
                "name = \"huge\"\n[[piece]]\nstart = 0.0\ncoeffs = [0.0, 0.0, {c}, -2{c}, {c}]\n"
            )
            .replace("-21e", "-2e"),
        )
        .unwrap();
        refused(&run(&["orbit", "--table", s(&f), "--bounces", "3"]), want);
        refused(
            &run(&["sweep", "--table", s(&f), "--alpha", "0.4..0.5"]),
            want,
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn fifos_devices_and_huge_files_are_refused_at_once() {
    let d = dir("fifo");
    let fifo = d.join("t.toml");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let zero = d.join("zero.toml");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let t = Instant::now();
    refused(&run(&["orbit", "--table", s(&fifo)]), "not a regular file");
    refused(&run(&["orbit", "--table", s(&zero)]), "not a regular file");
    refused(&run(&["merge", s(&fifo)]), "not a regular file");
    refused(
        &bin()
            .args(["--config", s(&fifo)])
            .stdin(Stdio::null())
            .output()
            .unwrap(),
        "not a regular file",
    );
    let big = d.join("big.toml");
    std::fs::write(&big, vec![b'#'; 2 << 20]).unwrap();
    refused(&run(&["orbit", "--table", s(&big)]), "too large");
    assert!(t.elapsed() < Duration::from_secs(10), "a read blocked");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn small_ones() {
    // Negative-looking windows are parsed, then refused with the range.
    refused(
        &run(&["sweep", "--alpha", "-0.5..0.6"]),
        "-0.5 is out of range: valid (0, 1000]",
    );
    // The missing argument is named.
    refused(&run(&["merge"]), "<FILE>");
    // The flag the user typed is the one blamed.
    refused(
        &run(&["bench", "--panel", "fig3z"]),
        "--panel: unknown preset 'fig3z'",
    );
    refused(
        &run(&[
            "sweep", "--preset", "fig3f", "--param", "d", "--d", "0.1..0.2",
        ]),
        "--preset fig3f: its table sine has no such parameter: valid alpha, r",
    );
    // Huge and tiny numbers in shortest or exponent form.
    let o = run(&["orbit", "--alpha", "1e300"]);
    refused(&o, "1e300");
    // Too many threads.
    refused(
        &run(&["sweep", "--alpha", "0.4..0.5", "--threads", "4000"]),
        "--threads 4000 is out of range: valid 1..=",
    );
    // A table name with escape codes is printed escaped.
    let d = dir("name");
    let f = d.join("n.toml");
    std::fs::write(
        &f,
        "name = \"a\\u001b[2Jb\\nc\"\n[[piece]]\nstart = 0.0\ncoeffs = [0.0]\n",
    )
    .unwrap();
    let o = run(&[
        "orbit",
        "--table",
        s(&f),
        "--bounces",
        "0",
        "--format",
        "json",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        !text.contains('\u{1b}') && text.contains("a\\\\u{1b}[2Jb\\\\nc"),
        "{text}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bench_on_a_closed_pipe_ends_quietly() {
    let mut child = bin()
        .args(["bench", "--quick"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read one byte, then close the pipe.
    {
        use std::io::Read;
        let mut out = child.stdout.take().unwrap();
        let mut b = [0u8; 1];
        out.read_exact(&mut b).unwrap();
    }
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(o.status.code(), Some(0), "{err}");
}
