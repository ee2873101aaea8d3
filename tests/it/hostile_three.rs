//! Hostile input, round three: each case of the third round run against the real
//! binary (permissions kept and refused, all of a command's outputs committed together,
//! a guess that is no cycle, the table's name, closed and full outputs for every
//! command, the progress interval, every ending signal, a long `curves` search, an r
//! axis without `--r`, huge config values, non-UTF-8 paths, `--resume` on a directory).

use crate::scratch::s;
use std::os::unix::fs::PermissionsExt;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
}

fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("hostile3", name)
}

/// Run to the end: (exit code, stdout, stderr).
fn run(cmd: &mut Command) -> (Option<i32>, String, String) {
    let o = cmd.stdin(Stdio::null()).output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Refused: exit 2, one line naming `want`, no panic.
fn refused((code, _, err): &(Option<i32>, String, String), want: &str) {
    assert_eq!(*code, Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(want), "{err:?} lacks {want:?}");
    assert!(!err.contains("panicked"), "{err}");
}

/// The temporaries left in `d` (`.NAME.PID-N.tmp`).
fn temporaries(d: &Path) -> Vec<String> {
    std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

const CURVES: [&str; 9] = [
    "curves",
    "--table",
    "fd",
    "--x",
    "alpha:0.4..0.7",
    "--y",
    "d:0..1",
    "--max-period",
    "1",
];

// ------------------------------------------------------------ 1, 2. permissions

/// An output that replaces a file keeps that file's permissions (a private file stays
/// private); a new one gets the umask's.
#[test]
fn a_replaced_output_keeps_its_permissions() {
    let d = dir("perm");
    let f = d.join("f.csv");
    std::fs::write(&f, "old\n").unwrap();
    std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o600)).unwrap();
    let r = run(bin().args(CURVES).args(["--format", "csv", "--out", s(&f)]));
    assert_eq!(r.0, Some(0), "{}", r.2);
    let mode = std::fs::metadata(&f).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600);
    assert!(std::fs::read_to_string(&f).unwrap().starts_with("row,"));
    std::fs::remove_dir_all(&d).unwrap();
}

/// A read-only output is refused (status 2, one line) for a user who may not write it,
/// and left as it was: run as `nobody` (this test runs as root in CI; as any other
/// user it drops nothing and runs as that user).
#[test]
fn a_read_only_output_is_refused_and_kept() {
    let d = dir("readonly");
    std::fs::set_permissions(&d, std::fs::Permissions::from_mode(0o777)).unwrap();
    let f = d.join("r.csv");
    std::fs::write(&f, "mine\n").unwrap();
    std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o444)).unwrap();
    let mut cmd = bin();
    cmd.args([
        "sweep", "--table", "fd:1", "--alpha", "0.5..0.6", "--steps", "4",
    ])
    .args(["--out", s(&f)]);
    if unsafe { libc::geteuid() } == 0 {
        // Drop to nobody for the run (the file stays root's).
        unsafe {
            cmd.pre_exec(|| {
                if libc::setgid(65534) != 0 || libc::setuid(65534) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
    let r = run(&mut cmd);
    refused(&r, "read-only");
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "mine\n");
    assert!(temporaries(&d).is_empty());
    std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o644)).unwrap();
    std::fs::remove_dir_all(&d).unwrap();
}

// ------------------------------------------------------------ 4. outputs together

/// `figure --out F --data D` where only the smaller file can be written (a per-file
/// size limit that the picture fits and its data does not): the run fails and neither
/// file is replaced, not the picture alone.
#[test]
fn a_failed_figure_replaces_neither_of_its_files() {
    let d = dir("together");
    let (png, json) = (d.join("f.png"), d.join("d.json"));
    std::fs::write(&png, "old picture").unwrap();
    std::fs::write(&json, "old data").unwrap();
    let mut cmd = bin();
    cmd.args([
        "figure",
        "fig2",
        "--dpi",
        "50",
        "--out",
        s(&png),
        "--data",
        s(&json),
    ]);
    // The picture is about 16 kB, its data about 118 kB: 60 kB lets only the picture be.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit {
                rlim_cur: 60_000,
                rlim_max: 60_000,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let o = cmd.stdin(Stdio::null()).output().unwrap();
    assert!(!o.status.success(), "{o:?}");
    assert!(o.status.code() == Some(1) || o.status.signal() == Some(libc::SIGXFSZ));
    assert_eq!(std::fs::read_to_string(&png).unwrap(), "old picture");
    assert_eq!(std::fs::read_to_string(&json).unwrap(), "old data");
    assert!(temporaries(&d).is_empty(), "{:?}", temporaries(&d));
    // Without the limit both are written.
    let r = run(bin().args([
        "figure",
        "fig2",
        "--dpi",
        "50",
        "--out",
        s(&png),
        "--data",
        s(&json),
    ]));
    assert_eq!(r.0, Some(0), "{}", r.2);
    assert!(std::fs::metadata(&json).unwrap().len() > 60_000);
    std::fs::remove_dir_all(&d).unwrap();
}

// ------------------------------------------------------------ 5, 6, 11, 12. curves

/// A guess near which there is no cycle: the output says so (text and json), as
/// `continue` does, instead of "0 curves" alone.
#[test]
fn curves_from_a_guess_that_is_no_cycle_say_why() {
    let guess = ["--n", "2", "--t0", "0.2", "--v0", "0.5"];
    let (code, out, err) = run(bin().args(CURVES).args(guess));
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("0 curves"), "{out}");
    assert!(
        out.contains("no branch at D = 0.5: no (2, 1) cycle near t0 = 0.2, v0 = 0.5"),
        "{out}"
    );
    let (_, json, _) = run(bin().args(CURVES).args(guess).args(["--format", "json"]));
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    let why = doc["unseeded"][0]["reason"].as_str().unwrap();
    assert!(why.contains("bad_launch"), "{why}");
    assert_eq!(doc["unseeded"][0]["D"], 0.5);
}

/// With a d axis every format names the table as the family, `fd`.
#[test]
fn curves_name_the_family_in_every_format() {
    let (_, json, _) = run(bin().args(CURVES).args(["--format", "json"]));
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(doc["table"], "fd");
    let (_, text, _) = run(bin().args(CURVES));
    assert!(text.starts_with("table fd "), "{text}");
}

/// With an r axis `--r` is the starting value when given (and must lie in the window);
/// without it the curves start at the window's middle, not at a default the user never
/// gave.
#[test]
fn an_r_axis_starts_at_its_middle_unless_r_is_given() {
    let plane = [
        "curves",
        "--table",
        "fd:0.3",
        "--x",
        "alpha:0.4..0.7",
        "--y",
        "r:0.1..0.5",
        "--max-period",
        "1",
        "--format",
        "json",
    ];
    let (code, out, err) = run(bin().args(plane));
    assert_eq!(code, Some(0), "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(
        (doc["start"].as_f64().unwrap() - 0.3).abs() < 1e-12,
        "{out}"
    );
    refused(&run(bin().args(plane).args(["--r", "0.8"])), "--r 0.8");
    let (code, out, _) = run(bin().args(plane).args(["--r", "0.2"]));
    assert_eq!(code, Some(0));
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["start"], 0.2);
}

/// A long `curves` search is not silent: in a batch log it starts with a line stating
/// the run and reports per seed value with the curves found so far.
#[test]
fn a_curves_search_reports_its_progress() {
    let d = dir("curves-progress");
    let log = std::fs::File::create(d.join("err")).unwrap();
    let status = bin()
        .args([
            "curves",
            "--table",
            "sine",
            "--x",
            "alpha:0.01..0.5",
            "--y",
            "r:0.2..0.95",
            "--max-period",
            "8",
            "--seeds",
            "4",
            "--out",
            s(&d.join("c.txt")),
        ])
        .env("BOUNCEMAP_PROGRESS_EVERY", "0.001")
        .stderr(log)
        .status()
        .unwrap();
    assert!(status.success());
    let err = std::fs::read_to_string(d.join("err")).unwrap();
    // The starting value and the first grid of 5 (more as the grids get finer).
    assert!(err.contains("curves of 6 seed values started"), "{err}");
    assert!(err.contains("curves specification: table sine"), "{err}");
    assert!(
        err.contains("seed values") && err.contains(" curves"),
        "{err}"
    );
    assert!(err.contains("curves finished"), "{err}");
    std::fs::remove_dir_all(&d).unwrap();
}

// ------------------------------------------------------------ 7. completions

/// `completions` writes as every command does: a reader that goes away ends it quietly,
/// a full disk is one line and status 1; never a panic.
#[test]
fn completions_survive_closed_and_full_outputs() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let mut child = bin()
            .args(["completions", shell])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        {
            use std::io::Read;
            let mut out = child.stdout.take().unwrap();
            let mut b = [0u8; 10];
            out.read_exact(&mut b).unwrap();
        }
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(0), "{shell}: {o:?}");
        assert!(
            o.stderr.is_empty(),
            "{shell}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let full = std::fs::File::create("/dev/full").unwrap();
        let o = bin()
            .args(["completions", shell])
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{shell}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.contains("standard output") && !err.contains("panicked"),
            "{err}"
        );
    }
}

// ------------------------------------------------------------ 8. progress interval

#[test]
fn a_bad_progress_interval_is_refused_in_one_line() {
    for bad in ["1e20", "abc", "-1", "0", "inf", ""] {
        let r = run(bin()
            .args([
                "sweep", "--table", "fd:1", "--alpha", "0.5..0.6", "--steps", "4",
            ])
            .env("BOUNCEMAP_PROGRESS_EVERY", bad));
        refused(&r, "BOUNCEMAP_PROGRESS_EVERY");
        assert!(
            r.2.contains("valid seconds in [0.001, 86400]"),
            "{bad}: {}",
            r.2
        );
    }
    let r = run(bin()
        .args([
            "sweep", "--table", "fd:1", "--alpha", "0.5..0.6", "--steps", "4",
        ])
        .env("BOUNCEMAP_PROGRESS_EVERY", "2.5"));
    assert_eq!(r.0, Some(0), "{}", r.2);
}

// ------------------------------------------------------------ 9. every ending signal

/// SIGQUIT, SIGUSR1 (and any signal whose default action ends the process) during a
/// sweep into a file: the process ends by that signal, the old file is untouched and no
/// temporary is left.
#[test]
fn every_ending_signal_removes_the_temporary() {
    for sig in [libc::SIGQUIT, libc::SIGUSR1, libc::SIGUSR2, libc::SIGALRM] {
        let d = dir(&format!("signal-{sig}"));
        let out = d.join("s.csv");
        std::fs::write(&out, "old\n").unwrap();
        let mut child = bin()
            .args([
                "sweep",
                "--table",
                "fd:1",
                "--alpha",
                "0.57..0.58",
                "--steps",
                "64",
            ])
            .args(["--transient", "1e8", "--threads", "1", "--out", s(&out)])
            .stdin(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        // Wait for the temporary to exist (the run has started writing).
        let t = Instant::now();
        while temporaries(&d).is_empty() && t.elapsed() < Duration::from_secs(10) {
            std::thread::sleep(Duration::from_millis(10));
        }
        assert!(!temporaries(&d).is_empty(), "no temporary appeared");
        unsafe {
            libc::kill(child.id() as libc::pid_t, sig);
        }
        let status = child.wait().unwrap();
        assert!(
            status.signal() == Some(sig) || status.code() == Some(128 + sig),
            "{sig}: {status:?}"
        );
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
        assert!(temporaries(&d).is_empty(), "{sig}: {:?}", temporaries(&d));
        std::fs::remove_dir_all(&d).unwrap();
    }
}

// ------------------------------------------------------------ 13, 14, 15

/// A huge number in a config file is shown short in its refusal, as the flag's is.
#[test]
fn a_huge_config_value_is_shown_short() {
    let d = dir("config");
    let c = d.join("c.toml");
    std::fs::write(&c, "[defaults]\ntransient = 1e300\n").unwrap();
    let r = run(bin().args(["--config", s(&c)]));
    refused(&r, "defaults.transient = 1e300: 1e300 is out of range");
    assert!(r.2.len() < 200, "{}", r.2);
    std::fs::write(&c, format!("[defaults]\nv0 = \"{}\"\n", "9".repeat(500))).unwrap();
    let r = run(bin().args(["--config", s(&c)]));
    refused(&r, "defaults.v0");
    assert!(
        r.2.contains("(500 characters)") && r.2.len() < 400,
        "{}",
        r.2
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// A path that is not UTF-8 is refused naming its flag, for every path flag alike
/// (`--table`, `--out`, `--config`, the `--out=PATH` form).
#[test]
fn a_non_utf8_path_is_refused_naming_its_flag() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let bad = |b: &[u8]| OsStr::from_bytes(b).to_os_string();
    for (args, flag) in [
        (vec![bad(b"--table"), bad(b"\xff.toml")], "--table"),
        (
            vec![bad(b"sweep"), bad(b"--out"), bad(b"\xfe.csv")],
            "--out",
        ),
        (vec![bad(b"sweep"), bad(b"--out=\xfe.csv")], "--out"),
        (vec![bad(b"--config"), bad(b"\xfe.toml")], "--config"),
    ] {
        let r = run(bin().args(&args));
        refused(&r, &format!("{flag}: "));
        assert!(r.2.contains("is not UTF-8 text"), "{}", r.2);
    }
}

/// `--resume --out DIR` is refused before it says it will compute anything.
#[test]
fn resume_into_a_directory_is_refused_first() {
    let d = dir("resume-dir");
    let r = run(bin()
        .args([
            "sweep", "--table", "fd:1", "--alpha", "0.5..0.6", "--steps", "4",
        ])
        .args(["--resume", "--out", s(&d)]));
    refused(&r, "it is a directory");
    assert!(!r.2.contains("computing"), "{}", r.2);
    std::fs::remove_dir_all(&d).unwrap();
}
