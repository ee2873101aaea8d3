//! Hostile input, round two: each case of a way to abort or leave parser internals on
//! the screen, run against the real binary, with the harness those runs share (exit
//! status, output, peak memory and time of a run); and a fuzz of every subcommand's
//! flags with values no user should type, in bounded time and memory. What a run writes
//! (closed pipes, full disks, `--out` and `--resume`) is in `hostile_outputs.rs`.

use crate::scratch::s;
use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

pub(crate) fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
}

pub(crate) fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("hostile", name)
}

/// How a run ended: exit code (or the signal), stdout, stderr, peak memory in bytes and
/// wall time.
pub struct Ran {
    pub code: Option<i32>,
    pub signal: Option<i32>,
    pub out: String,
    pub err: String,
    pub max_rss: u64,
    pub took: Duration,
}

/// Run `cmd` to its end, killing it after `limit`; its peak memory from `wait4`.
pub fn run_cmd(cmd: Command, limit: Duration) -> Ran {
    run_to(cmd, limit, Stdio::piped())
}

/// [`run_cmd`] with standard output going to `stdout` (not read back unless piped).
// The child is reaped by `wait4` (for its peak memory), which clippy does not see.
#[allow(clippy::zombie_processes)]
pub fn run_to(mut cmd: Command, limit: Duration, stdout: Stdio) -> Ran {
    let t = Instant::now();
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out_pipe = child.stdout.take();
    let mut err_pipe = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut o = Vec::new();
        if let Some(p) = out_pipe.as_mut() {
            let _ = p.read_to_end(&mut o);
        }
        o
    });
    let err_reader = std::thread::spawn(move || {
        let mut e = Vec::new();
        let _ = err_pipe.read_to_end(&mut e);
        e
    });
    let pid = child.id() as libc::pid_t;
    // The peak of the program's own memory (VmHWM, sampled until it ends), not the
    // rusage maximum, which also counts the copy of this test process the child was
    // forked as before its exec.
    let mut peak = 0u64;
    let (status, rss) = loop {
        peak = peak.max(vm_hwm(pid));
        let mut status = 0;
        // SAFETY: wait4 on our own child with structures of our own.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        let r = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if r == pid {
            break (status, peak);
        }
        if t.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} ran longer than {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let exit = std::process::ExitStatus::from_raw(status);
    Ran {
        code: exit.code(),
        signal: exit.signal(),
        out: String::from_utf8_lossy(&reader.join().unwrap()).into_owned(),
        err: String::from_utf8_lossy(&err_reader.join().unwrap()).into_owned(),
        max_rss: rss,
        took: t.elapsed(),
    }
}

/// The peak resident memory of process `pid` so far, in bytes (its VmHWM; 0 once it
/// has ended).
pub fn vm_hwm(pid: libc::pid_t) -> u64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

pub(crate) fn run(args: &[&str]) -> Ran {
    let mut c = bin();
    c.args(args);
    run_cmd(c, Duration::from_secs(120))
}

/// Exit 2 with one line of stderr containing `want`, no parser internals.
pub(crate) fn refused(r: &Ran, want: &str) {
    assert_eq!(r.code, Some(2), "{}", r.err);
    assert_eq!(
        r.err.trim_end().lines().count(),
        1,
        "not one line: {}",
        r.err
    );
    assert!(r.err.contains(want), "{:?} lacks {want:?}", r.err);
    for internal in [
        "panicked",
        "invalid float literal",
        "invalid digit",
        "cannot parse",
        "number too large",
    ] {
        assert!(!r.err.contains(internal), "{}", r.err);
    }
}

// ---------------------------------------------------------------- 1. streamed exponents

/// Exponents need no history: 2·10⁷ impacts (160 MB at 8 bytes each) in a few MB.
#[test]
fn lyapunov_measures_any_number_of_impacts_in_bounded_memory() {
    let r = run(&[
        "lyapunov",
        "--table",
        "fd:1",
        "--alpha",
        "0.5735",
        "--impacts",
        "2e7",
        "--format",
        "json",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.err);
    let doc: serde_json::Value = serde_json::from_str(&r.out).unwrap();
    assert_eq!(doc["impacts"], 20_000_000, "{}", r.out);
    assert!(r.max_rss < 60 << 20, "{} MB", r.max_rss >> 20);
}

/// The largest run the help allows starts, reports progress in a batch log and stops
/// at once on SIGINT (130).
#[test]
fn the_longest_lyapunov_run_shows_progress_and_is_cancellable() {
    let d = dir("lyap-cancel");
    let log = std::fs::File::create(d.join("err")).unwrap();
    let out = std::fs::File::create(d.join("out")).unwrap();
    let mut child = bin()
        .args(["lyapunov", "--table", "fd:1", "--alpha", "0.5735"])
        .args(["--impacts", "1e10"])
        .env("BOUNCEMAP_PROGRESS_EVERY", "0.2")
        .stdout(out)
        .stderr(log)
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let t = Instant::now();
    assert!(Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap()
        .success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
    let err = std::fs::read_to_string(d.join("err")).unwrap();
    assert!(
        err.contains("lyapunov of 10000000000 impacts started") && err.contains("M events/s"),
        "{err}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

// ---------------------------------------------------------------- 4. computed defaults

#[test]
fn a_default_computed_from_the_system_is_always_in_range() {
    for (table, alpha) in [("sine", "100"), ("fd:1", "1000"), ("sine", "1000")] {
        let r = run(&[
            "basins",
            "--table",
            table,
            "--alpha",
            alpha,
            "--grid",
            "2x2",
            "--transient",
            "10",
            "--format",
            "json",
        ]);
        assert_eq!(r.code, Some(0), "{table} {alpha}: {}", r.err);
        let doc: serde_json::Value = serde_json::from_str(&r.out).unwrap();
        assert_eq!(doc["w_max"], 1000.0, "{table} {alpha}");
    }
}

// ---------------------------------------------------------------- 5. figure memory

/// 10⁷ points drawn as values complete: the picture's memory, not the points' (held,
/// they took 400 MB).
#[test]
fn a_diagram_of_many_points_needs_memory_for_the_picture_only() {
    let d = dir("figure");
    let out = d.join("d.svg");
    let r = run(&[
        "figure",
        "diagram",
        "--table",
        "fd:1",
        "--alpha",
        "0.4..0.6",
        "--steps",
        "50000",
        "--keep",
        "200",
        "--transient",
        "200",
        "--out",
        s(&out),
    ]);
    assert_eq!(r.code, Some(0), "{}", r.err);
    assert!(r.max_rss < 200 << 20, "{} MB", r.max_rss >> 20);
    assert!(std::fs::read_to_string(&out).unwrap().contains("<svg"));
    std::fs::remove_dir_all(&d).unwrap();
}

// ---------------------------------------------------------------- 6, 9. numbers

#[test]
fn absurd_numbers_are_refused_with_the_range_and_malformed_ones_name_their_flag() {
    for v in ["nan", "inf", "-inf", "1e300", "NaN"] {
        let r = run(&[
            "continue", "--table", "fd:1", "--alpha", "0.4..0.6", "--n", "2", "--t0", "0.1",
            "--v0", v,
        ]);
        refused(&r, "--v0: ");
        assert!(
            r.err.contains("valid a velocity in [-7300, 7300]"),
            "{}",
            r.err
        );
    }
    for (args, want) in [
        (
            &["orbit", "--alpha="][..],
            "--alpha: '' is not a number: valid (0, 1000]",
        ),
        (
            &["orbit", "--alpha"][..],
            "--alpha needs a value: valid (0, 1000]",
        ),
        (
            &["orbit", "--v0", "0x10"][..],
            "--v0: '0x10' is not a number",
        ),
        (
            &["orbit", "--bounces", "1_000"][..],
            "--bounces: '1_000' is not a whole number",
        ),
        (
            &["sweep", "--alpha", "0.4..nan"][..],
            "--alpha '0.4..nan': 'nan' is not a number",
        ),
        (
            &["sweep", "--steps="][..],
            "--steps: '' is not a whole number",
        ),
        (
            &["sweep", "--format", "xml"][..],
            "--format: 'xml' is not a possible value: valid csv, json, braille",
        ),
        (
            &["plane", "--x", "alpha:0x1..2", "--y", "r:0.1..0.2"][..],
            "--x 'alpha:0x1..2'",
        ),
        (
            &["sweep", "--stpes", "5"][..],
            "a similar argument exists: '--steps'",
        ),
        (
            &["figure", "diagram", "--alpha", "0.4..0.5", "--size", "inf"][..],
            "--size: 'inf' is not a size",
        ),
    ] {
        refused(&run(args), want);
    }
    // Very long values are quoted in part, on one short line.
    let long = "9".repeat(100_000);
    let r = run(&["orbit", "--alpha", &long]);
    refused(&r, "(100000 characters) is out of range: valid (0, 1000]");
    assert!(r.err.len() < 200, "{}", r.err.len());
}

// ---------------------------------------------------------------- 11. --check

#[test]
fn check_validates_everything_and_computes_nothing() {
    let d = dir("check");
    let out = d.join("p.csv");
    let r = run(&[
        "sweep",
        "--preset",
        "fig3b",
        "--shard",
        "2/4",
        "--out",
        s(&out),
        "--check",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.err);
    assert!(
        r.out
            .contains("plan: sweep of 250 values (shard 2/4 of 1000)"),
        "{}",
        r.out
    );
    assert!(
        r.out.contains("plan: checked; nothing computed"),
        "{}",
        r.out
    );
    assert!(r.took < Duration::from_secs(2));
    assert!(
        std::fs::read_dir(&d).unwrap().next().is_none(),
        "a file was left"
    );
    refused(
        &run(&["sweep", "--preset", "fig3b", "--steps", "0", "--check"]),
        "--steps: 0 is out of range",
    );
    refused(
        &run(&[
            "sweep",
            "--preset",
            "fig3b",
            "--out",
            "/nonexistent/x.csv",
            "--check",
        ]),
        "/nonexistent/x.csv",
    );
    for args in [
        &[
            "plane",
            "--x",
            "alpha:0.4..0.5",
            "--y",
            "r:0.7..0.8",
            "--check",
        ][..],
        &["basins", "--check"][..],
        &["lyapunov", "--impacts", "1e10", "--check"][..],
    ] {
        let r = run(args);
        assert_eq!(r.code, Some(0), "{args:?}: {}", r.err);
        assert!(
            r.out.ends_with("plan: checked; nothing computed\n"),
            "{}",
            r.out
        );
        assert!(r.took < Duration::from_secs(2), "{args:?}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// submit.sh refuses abbreviated and unknown sbatch options, and bouncemap arguments
/// that `--check` refuses, before anything reaches sbatch (here a stand-in that fails
/// loudly if it is ever called).
#[test]
fn submit_refuses_bad_options_and_arguments_before_queueing() {
    let d = dir("submit");
    let fake = d.join("bin");
    std::fs::create_dir_all(&fake).unwrap();
    let sbatch = fake.join("sbatch");
    std::fs::write(
        &sbatch,
        "#!/bin/sh\necho 'sbatch was called' >&2\nexit 99\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/slurm/submit.sh");
    let path = format!("{}:{}", s(&fake), std::env::var("PATH").unwrap_or_default());
    let submit = |args: &[&str]| {
        let mut c = Command::new("bash");
        c.arg(script)
            .arg(d.join("runs"))
            .args(args)
            .env("PATH", &path)
            .env("BOUNCEMAP", env!("CARGO_BIN_EXE_bouncemap"))
            .env("PARTS", "2");
        run_cmd(c, Duration::from_secs(30))
    };
    for (args, want) in [
        (
            &["--part=debug", "--", "sweep", "--preset", "fig3b"][..],
            "'--part' is not an sbatch option written in full",
        ),
        (
            &["--arr=1-3", "--", "sweep", "--preset", "fig3b"][..],
            "is not an sbatch option written in full",
        ),
        (
            &["--out", "x", "--", "sweep", "--preset", "fig3b"][..],
            "not an sbatch option written in full",
        ),
        (
            &["--nosuch", "--", "sweep", "--preset", "fig3b"][..],
            "not an sbatch option written in full",
        ),
        (
            &["-Z", "--", "sweep", "--preset", "fig3b"][..],
            "sbatch option '-Z'",
        ),
        (
            &["--time", "--", "sweep", "--preset", "fig3b"][..],
            "sbatch option '--time' needs a value",
        ),
        (
            &["--", "sweep", "--preset", "fig3b", "--stpes", "5"][..],
            "bouncemap refused the arguments",
        ),
        (
            &["--", "sweep", "--preset", "fig3b", "--steps", "nan"][..],
            "--steps: 'nan' is not a whole number",
        ),
        (
            &["--", "plane", "--x", "alpha:0.4..0.5"][..],
            "bouncemap refused the arguments",
        ),
    ] {
        let r = submit(args);
        assert_eq!(r.code, Some(2), "{args:?}: {}", r.err);
        assert!(r.err.contains(want), "{args:?}: {}", r.err);
        assert!(!r.err.contains("sbatch was called"), "{args:?}: {}", r.err);
    }
    // Full names and short options with their values pass the checks and reach sbatch.
    let r = submit(&[
        "--partition=debug",
        "--time",
        "1:00:00",
        "-c",
        "2",
        "--exclusive",
        "--",
        "sweep",
        "--preset",
        "fig3b",
    ]);
    assert!(r.err.contains("sbatch was called"), "{}", r.err);
    assert!(
        r.out
            .contains("plan: sweep of 500 values (shard 1/2 of 1000)"),
        "{}",
        r.out
    );
    std::fs::remove_dir_all(&d).unwrap();
}

// ---------------------------------------------------------------- 12. what exists

#[test]
fn continue_says_what_exists_when_no_solution_is_stable() {
    let r = run(&[
        "continue", "--table", "fd:1", "--alpha", "0.4..0.6", "--k", "10",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.err);
    assert!(
        r.out.contains("no (1, 10) solution is stable at any alpha")
            && r.out.contains("exist only from alpha = 1.111111 on")
            && r.out.contains("unstable_period_doubling")
            && r.out.contains("--n 1 --k 10 --t0 PHASE --v0 5"),
        "{}",
        r.out
    );
}

// ---------------------------------------------------------------- the fuzz

/// Every value-taking flag of every subcommand, as its `--help` lists them.
fn value_flags(sub: &[&str]) -> Vec<String> {
    let o = bin().args(sub).arg("--help").output().unwrap();
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| {
            let mut t = l.trim_start();
            // "-h, --help": the long form.
            if t.starts_with('-') && !t.starts_with("--") {
                t = t.split_once(", ")?.1;
            }
            let (flag, rest) = t.split_once(' ')?;
            (flag.starts_with("--") && rest.starts_with('<')).then(|| flag.to_string())
        })
        .collect()
}

/// Every subcommand's flags with NaN, ±inf, 1e308, −0, nothing, hex, digit separators
/// and a very long number: exit 0 or 2, one line on stderr for 2, no panic, each run
/// within 30 s and 1 GB.
#[test]
fn every_flag_of_every_command_survives_hostile_values() {
    let d = dir("fuzz");
    let long = "9".repeat(20_000);
    let values: Vec<&str> = vec![
        "nan", "NaN", "inf", "-inf", "1e308", "-1e308", "-0", "", "0x10", "1_000", &long,
    ];
    // Small settings for the runs that are accepted, so each ends quickly.
    let subs: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["orbit"], vec!["--bounces", "5"]),
        (vec!["fixed"], vec![]),
        (vec!["two-cycle"], vec![]),
        (vec!["scaling"], vec!["--d", "0.1"]),
        (vec!["continue"], vec!["--alpha", "0.45..0.46"]),
        (vec!["cascade"], vec!["--depth", "1"]),
        (
            vec!["sweep"],
            vec![
                "--alpha",
                "0.45..0.46",
                "--steps",
                "2",
                "--transient",
                "100",
                "--keep",
                "2",
            ],
        ),
        (
            vec!["lyapunov"],
            vec!["--impacts", "100", "--transient", "100"],
        ),
        (vec!["basins"], vec!["--grid", "2x2", "--transient", "100"]),
        (
            vec!["plane"],
            vec![
                "--x",
                "alpha:0.4..0.5",
                "--y",
                "r:0.7..0.8",
                "--size",
                "2x2",
                "--transient",
                "100",
            ],
        ),
        (vec!["merge"], vec![]),
        (vec!["bench"], vec!["--panel", "nope"]),
        (vec!["figure", "fig2"], vec!["--format", "svg"]),
        (
            vec!["figure", "diagram"],
            vec![
                "--alpha",
                "0.45..0.46",
                "--steps",
                "2",
                "--transient",
                "100",
                "--keep",
                "2",
            ],
        ),
        (
            vec!["figure", "lyapunov"],
            vec![
                "--alpha",
                "0.45..0.46",
                "--steps",
                "2",
                "--transient",
                "100",
                "--keep",
                "2",
            ],
        ),
        (
            vec!["figure", "basins"],
            vec!["--grid", "2x2", "--transient", "100"],
        ),
        (
            vec!["figure", "plane"],
            vec![
                "--x",
                "alpha:0.4..0.5",
                "--y",
                "r:0.7..0.8",
                "--pixels",
                "2x2",
                "--transient",
                "100",
            ],
        ),
    ];
    let mut runs = 0;
    for (sub, base) in &subs {
        let flags = value_flags(sub);
        assert!(!flags.is_empty(), "{sub:?} lists no flags");
        for flag in &flags {
            for v in &values {
                let mut c = bin();
                c.current_dir(&d).args(sub).args(base);
                if sub[0] == "merge" {
                    c.arg("nothing.csv");
                }
                c.arg(format!("{flag}={v}"));
                let r = run_cmd(c, Duration::from_secs(30));
                runs += 1;
                let what = format!("{sub:?} {flag}={}", &v[..v.len().min(12)]);
                assert!(r.signal.is_none(), "{what}: killed by {:?}", r.signal);
                assert!(
                    matches!(r.code, Some(0) | Some(2)),
                    "{what}: {:?} {}",
                    r.code,
                    r.err
                );
                assert!(!r.err.contains("panicked"), "{what}: {}", r.err);
                if r.code == Some(2) {
                    assert_eq!(r.err.trim_end().lines().count(), 1, "{what}: {}", r.err);
                    assert!(r.err.len() < 1000, "{what}: {} bytes", r.err.len());
                }
                assert!(r.max_rss < 1 << 30, "{what}: {} MB", r.max_rss >> 20);
            }
        }
    }
    assert!(runs > 1000, "{runs} runs");
    std::fs::remove_dir_all(&d).unwrap();
}
