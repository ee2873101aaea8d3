//! Hostile case 3: the memory a `--check` plan states is an upper bound of what the run
//! then holds (a Slurm `--mem` is sized from it), and not a loose one where the points
//! dominate: each configuration runs with `--check`, then for real, its peak memory
//! read as it runs.

use std::process::Command;
use std::time::Duration;

/// Run the binary to its end: its exit code, stdout, stderr and peak memory in bytes
/// (its own high-water mark, as the hostile tests read it).
fn run(args: &[&str]) -> (Option<i32>, String, String, u64) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_bouncemap"));
    cmd.args(args);
    let r = crate::hostile::run_cmd(cmd, Duration::from_secs(300));
    (r.code, r.out, r.err, r.max_rss)
}

/// The bound a `--check` plan states ("memory: about 95.4 MB at most"), in bytes.
fn stated(plan: &str) -> u64 {
    let line = plan
        .lines()
        .find_map(|l| l.strip_prefix("plan: memory: about "))
        .unwrap_or_else(|| panic!("no memory line in {plan}"));
    let mut words = line.split_whitespace();
    let n: f64 = words.next().unwrap().parse().unwrap();
    let unit = match words.next().unwrap() {
        "kB" => 1e3,
        "MB" => 1e6,
        "GB" => 1e9,
        u => panic!("unit {u} in {line}"),
    };
    (n * unit) as u64
}

/// The stated bound and the measured peak of `args` (a command writing to `--out`).
fn bound_and_peak(args: &[&str], out: &str) -> (u64, u64) {
    let mut check = args.to_vec();
    check.push("--check");
    let (code, plan, err, _) = run(&check);
    assert_eq!(code, Some(0), "{args:?}: {err}");
    let mut real = args.to_vec();
    real.extend(["--out", out]);
    let (code, _, err, peak) = run(&real);
    assert_eq!(code, Some(0), "{args:?}: {err}");
    (stated(&plan), peak)
}

#[test]
fn the_memory_check_states_is_an_upper_bound_of_the_run() {
    const MB: u64 = 1_000_000;
    let out = std::env::temp_dir().join(format!("bouncemap-check-memory-{}", std::process::id()));
    let out = out.to_str().unwrap();
    // 300 000 points a value, a short transient: the points dominate.
    let large = [
        "sweep",
        "--table",
        "fd:1",
        "--alpha",
        "0.57..0.58",
        "--steps",
        "6",
        "--transient",
        "6e5",
        "--keep",
        "3e5",
    ];
    // Many small values: the window of values waiting for the writer, and the process.
    let small = [
        "sweep",
        "--alpha",
        "0.45..0.62",
        "--steps",
        "400",
        "--transient",
        "2000",
        "--keep",
        "100",
    ];
    let plane = [
        "plane",
        "--x",
        "alpha:0.4..0.7",
        "--y",
        "r:0.5..0.9",
        "--size",
        "500x400",
        "--transient",
        "30",
        "--no-lyapunov",
    ];
    for (args, threads, format, tight) in [
        (&large[..], "1", "csv", true),
        (&large[..], "4", "json", true),
        // The text picture takes each value at once: the window seldom fills.
        (&large[..], "2", "braille", false),
        (&small[..], "4", "csv", false),
        (&plane[..], "2", "csv", false),
    ] {
        let mut a = args.to_vec();
        a.extend(["--threads", threads, "--format", format]);
        let (bound, peak) = bound_and_peak(&a, out);
        assert!(
            peak <= bound,
            "{a:?}: peaked at {} MB, more than the {} MB stated",
            peak / MB,
            bound / MB
        );
        // Where the points dominate and the writer is the slower (the window of values
        // fills), the bound is not loose either.
        if tight {
            assert!(
                bound <= 5 * peak / 2,
                "{a:?}: states {} MB for a peak of {} MB",
                bound / MB,
                peak / MB
            );
        }
    }
    let _ = std::fs::remove_file(out);
}
