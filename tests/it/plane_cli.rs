//! `plane` as a user runs it: the picture of the (α, D) plane checked row by row against
//! α_PD from `fixed` and the border collision from `two-cycle` (computed here by those
//! commands, not by the plane), shards merged into the unsharded file, `merge`'s
//! refusals, the text picture, and bad input (one line, exit status 2).

use crate::cli::{json, run};
use std::process::Command;

fn tmp(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("bouncemap-plane-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_string_lossy().into_owned()
}

/// α_PD of fd:D at r = 0.8, from `fixed`.
fn alpha_pd(d: f64) -> f64 {
    let table = format!("fd:{d}");
    let v = json(&[
        "fixed", "--table", &table, "--alpha", "0.5", "--r", "0.8", "--format", "json",
    ]);
    v["alpha_pd"].as_f64().unwrap()
}

/// The border collision α of fd:D's (2, 2) branch at r = 0.8, from `two-cycle`.
fn border_collision(d: f64) -> f64 {
    let table = format!("fd:{d}");
    let v = json(&[
        "two-cycle",
        "--table",
        &table,
        "--alpha",
        "0.5",
        "--r",
        "0.8",
        "--format",
        "json",
    ]);
    v["border_collision"]["alpha"].as_f64().unwrap()
}

#[test]
fn the_alpha_d_plane_follows_alpha_pd_and_the_border_collision() {
    let v = json(&[
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.60",
        "--y",
        "d:0..1",
        "--r",
        "0.8",
        "--size",
        "150x40",
        "--format",
        "json",
    ]);
    let (nx, ny) = (150, 40);
    let pixels = v["pixels"].as_array().unwrap();
    assert_eq!(pixels.len(), nx * ny);
    let dx = 0.15 / (nx - 1) as f64;
    let mut checked_window = 0;
    let mut ended_at_collision = 0;
    let mut coexisting = Vec::new();
    for j in 0..ny {
        let row = &pixels[j * nx..(j + 1) * nx];
        let d = row[0]["y"].as_f64().unwrap();
        let x = |i: usize| row[i]["x"].as_f64().unwrap();
        let class = |i: usize| row[i]["class"].as_str().unwrap();
        let pd = alpha_pd(d);
        // The plane's own curve is the same number.
        let curve = v["curves"]["alpha_pd"][j].as_f64().unwrap();
        assert!(
            (curve - pd).abs() < 1e-12,
            "D = {d}: curve {curve}, fixed {pd}"
        );
        let first = (0..nx)
            .find(|&i| class(i) != "period-1")
            .expect("a pixel beyond period 1");
        assert!(
            (x(first) - pd).abs() <= dx * (1.0 + 1e-9),
            "D = {d}: first pixel beyond period 1 at α = {}, α_PD = {pd}",
            x(first)
        );
        if j == 0 {
            assert_eq!(d, 0.0);
            for i in 0..nx {
                if x(i) > pd && x(i) <= pd + 0.01 {
                    assert_ne!(class(i), "period-2", "D = 0, α = {}", x(i));
                }
            }
        }
        if (0.1..=0.5).contains(&d) {
            let bc = border_collision(d);
            assert_eq!(class(first), "period-2", "D = {d}");
            let last = (0..nx).rfind(|&i| class(i) == "period-2").unwrap();
            // No period-2 pixel lies beyond the collision: the branch has left its piece.
            assert!(
                x(last) <= bc + dx * (1.0 + 1e-9),
                "D = {d}: period-2 pixel at α = {} beyond the border collision {bc}",
                x(last)
            );
            if (x(last) - bc).abs() <= dx * (1.0 + 1e-9) {
                ended_at_collision += 1;
            } else {
                // The window ends early only where the start near the (1, 1) point falls
                // on another attractor while the (2, 2) cycle is still stable: `basins`
                // finds both at the first pixel after the window.
                let after = x(last + 1);
                let table = format!("fd:{d}");
                let alpha = format!("{after}");
                let b = json(&[
                    "basins",
                    "--table",
                    &table,
                    "--alpha",
                    &alpha,
                    "--r",
                    "0.8",
                    "--grid",
                    "40x20",
                    "--transient",
                    "20000",
                    "--format",
                    "json",
                ]);
                let list = b["attractors"].as_array().unwrap();
                assert!(
                    list.iter()
                        .any(|a| a["kind"] == "periodic" && a["events"] == 2),
                    "D = {d}, α = {after}: no (2, 2) attractor: {b}"
                );
                assert!(list.len() >= 2, "D = {d}, α = {after}: {b}");
                coexisting.push(d);
            }
            checked_window += 1;
        }
    }
    // Up to D = 0.4 the window ends at the collision on every row (150x40: rows
    // D = 0.103 … 0.385); above it, coexisting attractors cut it short on a few.
    assert!(
        coexisting.iter().all(|&d| d > 0.4),
        "windows ended early at D = {coexisting:?}"
    );
    assert!(ended_at_collision >= 12, "{ended_at_collision} rows");
    assert!(
        checked_window >= 15,
        "{checked_window} rows with 0.1 ≤ D ≤ 0.5"
    );
}

fn plane_args<'a>(format: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut a = vec![
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.48..0.56",
        "--y",
        "d:0..1",
        "--size",
        "23x9",
        "--transient",
        "3000",
        "--threads",
        "2",
        "--format",
        format,
    ];
    a.extend_from_slice(extra);
    a
}

#[test]
fn shards_merge_into_the_unsharded_plane() {
    for format in ["csv", "json"] {
        let whole = tmp(&format!("whole.{format}"));
        let (code, _, err) = run(&plane_args(format, &["--out", &whole]));
        assert_eq!(code, 0, "{err}");
        let mut parts = Vec::new();
        for i in 1..=3 {
            let part = tmp(&format!("part-{i}.{format}"));
            let shard = format!("{i}/3");
            let (code, _, err) = run(&plane_args(format, &["--shard", &shard, "--out", &part]));
            assert_eq!(code, 0, "{err}");
            parts.push(part);
        }
        let merged = tmp(&format!("merged.{format}"));
        // Parts in any order.
        let (code, _, err) = run(&["merge", &parts[2], &parts[0], &parts[1], "--out", &merged]);
        assert_eq!(code, 0, "{err}");
        let a = std::fs::read_to_string(&whole).unwrap();
        let b = std::fs::read_to_string(&merged).unwrap();
        let b = b.replacen("merged 3/3", "1/1", 1);
        assert_eq!(a, b, "{format}");

        // A missing shard, a shard twice, a part of another plane, a truncated part.
        let (code, _, err) = run(&["merge", &parts[0], &parts[1]]);
        assert_eq!(code, 2);
        assert!(err.contains("missing shard 3/3"), "{err}");
        let (code, _, err) = run(&["merge", &parts[0], &parts[0], &parts[1]]);
        assert_eq!(code, 2);
        assert!(err.contains("also in"), "{err}");
        let other = tmp(&format!("other.{format}"));
        let mut args = plane_args(format, &["--shard", "3/3", "--out", &other]);
        args[4] = "alpha:0.48..0.57";
        assert_eq!(run(&args).0, 0);
        let (code, _, err) = run(&["merge", &parts[0], &parts[1], &other]);
        assert_eq!(code, 2);
        assert!(err.contains("another plane"), "{err}");
        assert_eq!(err.trim().lines().count(), 1);
        let cut = tmp(&format!("cut.{format}"));
        let text = std::fs::read_to_string(&parts[2]).unwrap();
        std::fs::write(&cut, &text[..text.len() * 2 / 3]).unwrap();
        let (code, _, err) = run(&["merge", &parts[0], &parts[1], &cut]);
        assert_eq!(code, 2, "{err}");
        assert_eq!(err.trim().lines().count(), 1);
    }
}

#[test]
fn a_damaged_or_misplaced_row_is_refused() {
    let part = tmp("rows-1.csv");
    assert_eq!(
        run(&plane_args("csv", &["--shard", "1/2", "--out", &part])).0,
        0
    );
    let second = tmp("rows-2.csv");
    assert_eq!(
        run(&plane_args("csv", &["--shard", "2/2", "--out", &second])).0,
        0
    );
    let text = std::fs::read_to_string(&part).unwrap();
    // A changed class: the checksum no longer matches.
    let damaged = tmp("damaged.csv");
    std::fs::write(&damaged, text.replacen(",period-1,", ",period-2,", 1)).unwrap();
    let (code, _, err) = run(&["merge", &damaged, &second]);
    assert_eq!(code, 2);
    assert!(err.contains("truncated or damaged"), "{err}");
    // A sweep part among plane parts.
    let sweep = tmp("sweep.csv");
    let (code, _, err) = run(&[
        "sweep",
        "--alpha",
        "0.45..0.5",
        "--steps",
        "3",
        "--transient",
        "100",
        "--out",
        &sweep,
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&["merge", &part, &sweep]);
    assert_eq!(code, 2);
    assert!(err.contains("not a plane file"), "{err}");
}

#[test]
fn the_text_picture_has_axes_curves_and_a_legend() {
    let (code, out, err) = run(&plane_args("braille", &["--width", "70", "--height", "24"]));
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 24, "{out}");
    assert!(lines[1].trim_start().starts_with("1.000│"), "{out}");
    assert!(out.contains("0.4800") && out.contains("0.5600"), "{out}");
    assert!(out.contains('P'), "the α_PD curve is drawn: {out}");
    assert!(out.contains("P α_PD") && out.contains("█ chaos"), "{out}");
    for l in &lines {
        assert!(l.chars().count() <= 110, "{l}");
    }
}

#[test]
fn the_alpha_r_plane_of_the_sine_runs_and_has_its_alpha_pd_curve() {
    let v = json(&[
        "plane",
        "--table",
        "sine",
        "--x",
        "alpha:0.02..0.04",
        "--y",
        "r:0.5..0.9",
        "--size",
        "12x5",
        "--transient",
        "2000",
        "--format",
        "json",
    ]);
    assert_eq!(v["pixels"].as_array().unwrap().len(), 60);
    assert_eq!(v["curves"]["along"], "r");
    // α_PD of the sine: √((κ_c/4π²)² + (c/2π)²), κ_c = −2(1 + r²)/(1 + r)², c = ½(1 − r)/(1 + r).
    let r = 0.9;
    let kc = -2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
    let c = 0.5 * (1.0 - r) / (1.0 + r);
    let tau = std::f64::consts::TAU;
    let want = ((kc / (tau * tau)).powi(2) + (c / tau).powi(2)).sqrt();
    let got = v["curves"]["alpha_pd"][4].as_f64().unwrap();
    assert!((got - want).abs() < 1e-10, "{got} {want}");
    assert!(v["curves"]["border_collision"][4].is_null());
}

#[test]
fn bad_input_is_one_line_with_status_2() {
    for (args, needle) in [
        (
            vec!["--x", "beta:0..1", "--y", "d:0..1"],
            "unknown parameter",
        ),
        (vec!["--x", "alpha:0.6..0.5", "--y", "d:0..1"], "empty"),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "d:0..2"],
            "out of range",
        ),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "alpha:0.4..0.5"],
            "both alpha",
        ),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "d:0..1", "--size", "0x5"],
            "not a size",
        ),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "d:0..1", "--table", "sine"],
            "F_D family",
        ),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "r:0.5..0.9", "--r", "0.8"],
            "axis",
        ),
        (
            vec!["--x", "alpha:0.45..0.6", "--y", "d:0..1", "--shard", "4/3"],
            "shard",
        ),
        (vec!["--x", "alpha0.45", "--y", "d:0..1"], "not an axis"),
    ] {
        let mut a = vec!["plane"];
        a.extend(args);
        let (code, out, err) = run(&a);
        assert_eq!(code, 2, "{a:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
}

#[test]
fn resume_leaves_a_complete_part_and_refuses_a_foreign_one() {
    let part = tmp("resume-1-of-2.csv");
    let _ = std::fs::remove_file(&part);
    let args = plane_args("csv", &["--shard", "1/2", "--resume", "--out", &part]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("no ") && err.contains("computing it"), "{err}");
    let before = std::fs::read_to_string(&part).unwrap();
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("already holds shard 1/2 of this plane"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&part).unwrap(), before);
    // Another shard's file at that path is not this run's: refused, left as it is.
    let args = plane_args("csv", &["--shard", "2/2", "--resume", "--out", &part]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("holds shard 1/2 of this plane, not shard 2/2")
            && err.contains("it is not this run's output"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&part).unwrap(), before);
}

#[test]
fn a_slurm_array_task_computes_its_part() {
    let out = Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(plane_args("csv", &[]))
        .env("SLURM_ARRAY_TASK_ID", "5")
        .env("SLURM_ARRAY_TASK_MIN", "4")
        .env("SLURM_ARRAY_TASK_MAX", "6")
        .env_remove("SLURM_ARRAY_TASK_COUNT")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("\n# shard 2/3\n"), "{text}");
    // 23 × 9 = 207 pixels, 69 of them in the part.
    assert!(text.contains("\n# pixels 69\n"), "{text}");
}

/// A d axis takes the F_D family: another table, or an F_D table with its own D (which
/// the axis would replace), is refused with one line naming the valid form.
#[test]
fn a_d_axis_takes_the_family_not_one_table() {
    for table in ["fd:0.1", "cubic", "sine"] {
        let (code, _, err) = crate::cli::run(&[
            "plane",
            "--table",
            table,
            "--x",
            "alpha:0.45..0.6",
            "--y",
            "d:0..1",
            "--size",
            "4x4",
        ]);
        assert_eq!(code, 2, "{table}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("valid --table fd"), "{table}: {err}");
    }
    let (code, _, err) = crate::cli::run(&[
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.6",
        "--y",
        "d:0..1",
        "--size",
        "4x4",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
}
