//! `sweep` as a task of a Slurm job array (the shard and the threads from Slurm's
//! variables) and `--resume` (a part already there is left alone), against the real
//! binary. Slurm is not needed: its variables are set as Slurm sets them.

use crate::scratch::s;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Every variable these tests set, removed from what the binary inherits (the suite may
/// itself run inside a Slurm job).
const SLURM_VARS: [&str; 5] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_MAX",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_CPUS_PER_TASK",
];

fn bin(env: &[(&str, &str)]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_bouncemap"));
    for v in SLURM_VARS {
        c.env_remove(v);
    }
    c.envs(env.iter().copied());
    c
}

fn run(env: &[(&str, &str)], args: &[&str]) -> Output {
    bin(env).args(args).output().unwrap()
}

fn ok(o: &Output) {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Exit 2 with one line of stderr containing `want`.
fn refused(o: &Output, want: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(err.contains(want), "{err:?} lacks {want:?}");
}

fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("array", name)
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap()
}

/// A small sweep: 40 values of α from 0.45 to 0.6.
const SMALL: [&str; 9] = [
    "sweep",
    "--alpha",
    "0.45..0.6",
    "--steps",
    "40",
    "--transient",
    "2000",
    "--keep",
    "3",
];

fn small(extra: &[&str]) -> Vec<String> {
    SMALL.iter().chain(extra).map(|a| a.to_string()).collect()
}

fn run_small(env: &[(&str, &str)], extra: &[&str]) -> Output {
    let args = small(extra);
    run(env, &args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The `# key value` provenance line of a csv sweep file.
fn provenance<'a>(text: &'a str, key: &str) -> &'a str {
    text.lines()
        .find_map(|l| l.strip_prefix(&format!("# {key} ")))
        .unwrap_or_else(|| panic!("no '# {key}' line"))
}

/// The value indices and their α in a csv sweep file's rows.
fn rows(text: &str) -> Vec<(usize, f64)> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("index,"))
        .map(|l| {
            let mut f = l.split(',');
            let i = f.next().unwrap().parse().unwrap();
            let a = f.next().unwrap().parse().unwrap();
            (i, a)
        })
        .collect()
}

fn array(
    id: &'static str,
    min: &'static str,
    max: &'static str,
) -> Vec<(&'static str, &'static str)> {
    vec![
        ("SLURM_ARRAY_TASK_ID", id),
        ("SLURM_ARRAY_TASK_MIN", min),
        ("SLURM_ARRAY_TASK_MAX", max),
    ]
}

#[test]
fn an_array_task_computes_its_part_numbered_from_zero_or_one() {
    let d = dir("part");
    // Task 3 of --array=0-7: the fourth of eight interleaved parts, values 3, 11, ...
    let f = d.join("task3.csv");
    ok(&run_small(&array("3", "0", "7"), &["--out", s(&f)]));
    let text = read(&f);
    assert_eq!(provenance(&text, "shard"), "4/8");
    let got: BTreeSet<usize> = rows(&text).iter().map(|r| r.0).collect();
    assert_eq!(got, (0..40).filter(|i| i % 8 == 3).collect());
    for (i, a) in rows(&text) {
        assert!(
            (a - (0.45 + 0.15 * i as f64 / 39.0)).abs() < 1e-12,
            "{i} {a}"
        );
    }
    // The same file as the part named by hand, with --shard auto or without --shard.
    let by_hand = d.join("by-hand.csv");
    ok(&run_small(&[], &["--shard", "4/8", "--out", s(&by_hand)]));
    assert_eq!(read(&by_hand), text);
    let auto = d.join("auto.csv");
    let mut env = array("3", "0", "7");
    env.push(("SLURM_ARRAY_TASK_COUNT", "8"));
    ok(&run_small(&env, &["--shard", "auto", "--out", s(&auto)]));
    assert_eq!(read(&auto), text);
    // An explicit part wins over the array's.
    let explicit = d.join("explicit.csv");
    ok(&run_small(&env, &["--shard", "4/8", "--out", s(&explicit)]));
    assert_eq!(read(&explicit), text);
    // Task 3 of --array=1-8 is the third part.
    let one_based = d.join("one-based.csv");
    ok(&run_small(&array("3", "1", "8"), &["--out", s(&one_based)]));
    assert_eq!(provenance(&read(&one_based), "shard"), "3/8");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn the_tasks_of_an_array_merge_into_the_unsharded_sweep() {
    let d = dir("merge");
    let ids = ["0", "1", "2", "3", "4"];
    let mut parts = Vec::new();
    for id in ids {
        let f = d.join(format!("task{id}.csv"));
        ok(&run_small(&array(id, "0", "4"), &["--out", s(&f)]));
        parts.push(f);
    }
    let whole = d.join("whole.csv");
    ok(&run_small(&[], &["--out", s(&whole)]));
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(|p| s(p)));
    let merged = run(&[], &args);
    ok(&merged);
    let merged = String::from_utf8(merged.stdout).unwrap();
    let whole = read(&whole);
    assert_eq!(provenance(&merged, "shard"), "merged 5/5");
    assert_eq!(provenance(&whole, "shard"), "1/1");
    let without_shard = |t: &str| -> String {
        t.lines()
            .filter(|l| !l.starts_with("# shard "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(without_shard(&merged), without_shard(&whole));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn inconsistent_array_variables_are_refused_in_one_line() {
    let out = ["--out", "/nonexistent-dir/never.csv"];
    refused(
        &run_small(&[], &["--shard", "auto"]),
        "SLURM_ARRAY_TASK_ID is not set",
    );
    refused(
        &run_small(&[("SLURM_ARRAY_TASK_ID", "3")], &out),
        "SLURM_ARRAY_TASK_MIN is not set",
    );
    refused(
        &run_small(&array("9", "0", "7"), &out),
        "SLURM_ARRAY_TASK_ID=9 is not in SLURM_ARRAY_TASK_MIN..SLURM_ARRAY_TASK_MAX = 0..7",
    );
    refused(
        &run_small(&array("0", "1", "8"), &["--shard", "auto"]),
        "= 1..8",
    );
    let mut stepped = array("3", "1", "7");
    stepped.push(("SLURM_ARRAY_TASK_COUNT", "4"));
    refused(&run_small(&stepped, &out), "SLURM_ARRAY_TASK_COUNT=4");
    refused(&run_small(&[], &["--shard", "aut"]), "or auto");
    refused(
        &run_small(&[("SLURM_CPUS_PER_TASK", "0")], &[]),
        "SLURM_CPUS_PER_TASK=0",
    );
    refused(&run_small(&[], &["--resume"]), "--resume without --out");
    refused(
        &run_small(&[], &["--resume", "--format", "braille", "--out", "x.txt"]),
        "--resume with --format braille",
    );
}

/// The most threads the running sweep had at once, from /proc.
fn peak_threads(env: &[(&str, &str)], extra: &[&str]) -> usize {
    let mut args = vec![
        "sweep",
        "--preset",
        "fig3b",
        "--steps",
        "30",
        "--out",
        "/dev/null",
    ];
    args.extend_from_slice(extra);
    let mut child = bin(env).args(&args).stderr(Stdio::null()).spawn().unwrap();
    let status = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    while child.try_wait().unwrap().is_none() {
        if let Ok(text) = std::fs::read_to_string(&status) {
            if let Some(n) = text
                .lines()
                .find_map(|l| l.strip_prefix("Threads:"))
                .and_then(|n| n.trim().parse().ok())
            {
                peak = peak.max(n);
            }
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    peak
}

#[test]
fn worker_threads_default_to_the_cpus_slurm_gave_the_task() {
    if !Path::new("/proc/self/status").exists() {
        return;
    }
    let one = peak_threads(&[("SLURM_CPUS_PER_TASK", "1")], &[]);
    let three = peak_threads(&[("SLURM_CPUS_PER_TASK", "3")], &[]);
    assert_eq!(three, one + 2, "1 cpu: {one} threads, 3 cpus: {three}");
    // --threads wins over the variable.
    let flag = peak_threads(&[("SLURM_CPUS_PER_TASK", "3")], &["--threads", "2"]);
    assert_eq!(flag, one + 1, "1 cpu: {one} threads, --threads 2: {flag}");
}

fn modified(p: &Path) -> (std::time::SystemTime, u64) {
    use std::os::unix::fs::MetadataExt;
    let m = std::fs::metadata(p).unwrap();
    (m.modified().unwrap(), m.ino())
}

#[test]
fn a_resumed_part_is_left_alone_if_complete_computed_if_damaged_refused_if_foreign() {
    let d = dir("resume");
    let f = d.join("part.csv");
    // A part that takes a while: fig3b at full transient, 40 values, shard 2/2.
    let args = |extra: &[&str]| -> Vec<String> {
        [
            "sweep", "--preset", "fig3b", "--steps", "40", "--shard", "2/2",
        ]
        .iter()
        .chain(extra)
        .map(|a| a.to_string())
        .collect()
    };
    let go = |extra: &[&str]| -> (Output, Duration) {
        let a = args(extra);
        let t = Instant::now();
        let o = run(&[], &a.iter().map(String::as_str).collect::<Vec<_>>());
        ok(&o);
        (o, t.elapsed())
    };
    let (first, computed) = go(&["--resume", "--out", s(&f)]);
    let err = String::from_utf8_lossy(&first.stderr);
    assert!(
        err.contains("no ") && err.contains("part.csv yet; computing it"),
        "{err}"
    );
    let original = read(&f);
    let before = modified(&f);
    std::thread::sleep(Duration::from_millis(20));
    // Resumed: the file is untouched (same inode and time: not even rewritten) and
    // nothing was computed (no sweep started), in a fraction of the time.
    let (again, resumed) = go(&["--resume", "--out", s(&f)]);
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        err.contains("already holds shard 2/2 of this sweep"),
        "{err}"
    );
    assert!(!err.contains("started"), "{err}");
    assert_eq!(modified(&f), before);
    assert_eq!(read(&f), original);
    assert!(
        resumed < computed / 4,
        "resumed in {resumed:?}, computed in {computed:?}"
    );
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        1,
        "a temporary was left"
    );
    // Without --resume the part is computed again.
    let (fresh, _) = go(&["--out", s(&f)]);
    assert!(String::from_utf8_lossy(&fresh.stderr).contains("started"));
    assert_ne!(modified(&f), before);
    // A damaged part (its end line cut off) is computed again, and says why.
    let cut = original.trim_end().rsplit_once('\n').unwrap().0.to_string() + "\n";
    std::fs::write(&f, cut).unwrap();
    let (repaired, _) = go(&["--resume", "--out", s(&f)]);
    let err = String::from_utf8_lossy(&repaired.stderr);
    assert!(
        err.contains("truncated or damaged") && err.contains("computing it"),
        "{err}"
    );
    assert_eq!(read(&f), original);
    // The part of another sweep or another shard is not this run's: refused, left as
    // it is.
    let g = d.join("other.csv");
    for (other, why) in [
        (
            vec!["--shard", "2/2", "--keep", "5"],
            "another sweep (its keep 5 differs",
        ),
        (
            vec!["--shard", "1/2"],
            "holds shard 1/2 of this sweep, not shard 2/2",
        ),
    ] {
        let mut a: Vec<&str> = vec!["sweep", "--preset", "fig3b", "--steps", "40"];
        a.extend(&other);
        a.extend(["--out", s(&g)]);
        ok(&run(&[], &a));
        let theirs = read(&g);
        let resume = args(&["--resume", "--out", s(&g)]);
        let o = run(&[], &resume.iter().map(String::as_str).collect::<Vec<_>>());
        refused(&o, why);
        assert!(
            String::from_utf8_lossy(&o.stderr).contains("it is not this run's output"),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(read(&g), theirs);
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// A json part that does not parse (a key holding a newline, a shard 0/1) is reported in
/// one line by `--resume` and refused in one line by `merge`, for a sweep and a plane
/// alike: both are read by the one part-file reader. `--resume` computes the first
/// again (its provenance is this run's) and refuses the second (its shard is not).
#[test]
fn a_malformed_json_part_is_reported_in_one_line_for_sweeps_and_planes() {
    let d = dir("malformed");
    let plane = [
        "plane",
        "--x",
        "alpha:0.4..0.5",
        "--y",
        "r:0.6..0.9",
        "--size",
        "6x3",
        "--transient",
        "500",
    ];
    for (kind, args) in [("sweep", &SMALL[..]), ("plane", &plane[..])] {
        let f = d.join(format!("{kind}.json"));
        let mut a: Vec<&str> = args.to_vec();
        a.extend(["--format", "json", "--shard", "1/2", "--out", s(&f)]);
        ok(&run(&[], &a));
        let text = read(&f);
        let cases = [
            (
                text.replacen("\"table\":", "\"ta\\nble\":0,\"table\":", 1),
                format!("not a complete {kind} json file (unknown field `ta ble`"),
                true,
            ),
            (
                text.replacen("\"shard\":\"1/2\"", "\"shard\":\"0/1\"", 1),
                "shard '0/1' is not I/N with 1 ≤ I ≤ N".to_string(),
                false,
            ),
        ];
        for (damaged, why, own) in cases {
            assert_ne!(damaged, text, "{kind}: {why}");
            std::fs::write(&f, &damaged).unwrap();
            refused(&run(&[], &["merge", s(&f)]), &format!("{}: {why}", s(&f)));
            let mut resume = a.clone();
            resume.push("--resume");
            let o = run(&[], &resume);
            if !own {
                refused(&o, &format!("--resume: {}: {why}", s(&f)));
                assert_eq!(read(&f), damaged, "{kind}: a refused file was changed");
                continue;
            }
            ok(&o);
            let err = String::from_utf8_lossy(&o.stderr);
            let line = err.lines().next().unwrap_or_default();
            assert!(
                line.starts_with("bouncemap: --resume: ") && line.ends_with("; computing it"),
                "{kind}: {err}"
            );
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}
