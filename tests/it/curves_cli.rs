//! The two-parameter curves as a user runs them: `curves` against `fixed`, `cascade`
//! and `two-cycle` through the binary, its formats and refusals; `figure curves`,
//! `figure plane --curves` and `plane --format braille --curves`; and the (α, D)
//! plane's period-2 pixels between the curves drawn for them.

use crate::cli::{json as run_json, run};
use crate::figure_cli::{bouncemap, dir, json, ok, s, series, Image};
use serde_json::Value;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// `curves` through the binary: the (1, 1) PD curve's points against `fixed`'s
/// closed-form α_PD at their D, every point's condition within 1e-9, json and csv
/// describing the same curves, `--out` written whole.
#[test]
fn curves_agree_with_fixed_and_their_formats_agree() {
    let args = [
        "curves",
        "--table",
        "fd:1",
        "--x",
        "alpha:0.4..0.7",
        "--y",
        "d:0..1",
        "--max-period",
        "4",
        "--seeds",
        "1",
        "--format",
        "json",
    ];
    let v = run_json(&args);
    let curves = v["curves"].as_array().unwrap();
    let pd = curves
        .iter()
        .find(|c| c["kind"] == "period_doubling" && c["n"] == 1)
        .expect("the (1, 1) PD curve");
    let pts = pd["points"].as_array().unwrap();
    for q in pts.iter().step_by(pts.len() / 10) {
        let d = f(&q["D"]);
        let table = format!("fd:{d}");
        let fx = run_json(&[
            "fixed", "--table", &table, "--alpha", "0.5", "--format", "json",
        ]);
        assert!(
            (f(&q["alpha"]) - f(&fx["alpha_pd"])).abs() < 1e-10,
            "D = {d}"
        );
    }
    for c in curves {
        for q in c["points"].as_array().unwrap() {
            assert!(f(&q["condition"]).abs() <= 1e-9);
        }
    }
    let dir = std::env::temp_dir().join(format!("bouncemap-curves-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("c.csv");
    let mut csv_args: Vec<&str> = args[..args.len() - 1].to_vec();
    csv_args.push("csv");
    csv_args.push("--out");
    csv_args.push(out.to_str().unwrap());
    let (code, _, err) = run(&csv_args);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let points = text.lines().filter(|l| l.starts_with("point,")).count();
    let total: usize = curves
        .iter()
        .map(|c| c["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(points, total);
    let codim2 = text.lines().filter(|l| l.starts_with("codim2,")).count();
    assert_eq!(codim2, v["codim2"].as_array().unwrap().len());
    assert!(codim2 >= 2);
}

#[test]
fn curves_refuse_bad_planes_with_one_line() {
    for (args, needle) in [
        (
            &["--table", "sine", "--x", "alpha:0.4..0.7", "--y", "d:0..1"][..],
            "F_D family",
        ),
        (&["--x", "r:0.2..0.9", "--y", "d:0..1"][..], "alpha:LO..HI"),
        (
            &["--x", "alpha:0.4..0.7", "--y", "alpha:0.4..0.7"][..],
            "the second parameter is one of r, D",
        ),
        (
            &[
                "--table",
                "fd:0.3",
                "--x",
                "alpha:0.4..0.7",
                "--y",
                "d:0.5..1",
            ][..],
            "outside the D window",
        ),
        (
            &["--x", "alpha:0.4..0.7", "--y", "r:0.2..0.5", "--r", "0.8"][..],
            "outside the r window",
        ),
        (
            &["--x", "alpha:0.5..0.5", "--y", "d:0..1", "--table", "fd"][..],
            "single value",
        ),
        (
            &["--x", "alpha:0.4..0.7", "--y", "d:0..1", "--seeds", "0"][..],
            "seeds",
        ),
    ] {
        let mut a = vec!["curves"];
        a.extend_from_slice(args);
        let (code, _, err) = run(&a);
        assert_eq!(code, 2, "{a:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
}

/// `curves --n 2 --k 2 --t0 --v0` from `two-cycle`'s (2, 2) cycle follows that branch's
/// curves only: its period-doubling curve reaches D = 1 at the cascade's α₂ there.
#[test]
fn curves_from_an_explicit_cycle_follow_its_branch() {
    let tc = run_json(&[
        "two-cycle",
        "--table",
        "fd:1",
        "--alpha",
        "0.52",
        "--format",
        "json",
    ]);
    let (t0, v0) = (
        format!("{}", f(&tc["two_cycle"]["phase0"])),
        format!("{}", f(&tc["two_cycle"]["v0"])),
    );
    let v = run_json(&[
        "curves",
        "--table",
        "fd:1",
        "--x",
        "alpha:0.52..0.7",
        "--y",
        "d:0..1",
        "--n",
        "2",
        "--k",
        "2",
        "--t0",
        &t0,
        "--v0",
        &v0,
        "--seeds",
        "1",
        "--format",
        "json",
    ]);
    let curves = v["curves"].as_array().unwrap();
    assert!(
        curves.iter().all(|c| c["n"] == 2),
        "only the (2, 2) branch's curves"
    );
    let pd = curves
        .iter()
        .find(|c| c["kind"] == "period_doubling")
        .unwrap();
    let at_one = pd["points"]
        .as_array()
        .unwrap()
        .iter()
        .find(|q| f(&q["D"]) == 1.0)
        .expect("a point at D = 1");
    let cascade = run_json(&[
        "cascade", "--table", "fd:1", "--depth", "2", "--format", "json",
    ]);
    let alpha2 = f(&cascade["alphas"][1]);
    assert!(
        (f(&at_one["alpha"]) - alpha2).abs() < 1e-9,
        "{} vs {alpha2}",
        at_one["alpha"]
    );
}

/// `plane --format braille --curves P` marks the two-parameter curves on the text
/// picture, with their legend; the files (csv, json) refuse it in one line.
#[test]
fn the_text_picture_marks_the_two_parameter_curves() {
    let (code, out, err) = run(&[
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.62",
        "--y",
        "d:0..1",
        "--size",
        "60x20",
        "--format",
        "braille",
        "--width",
        "80",
        "--height",
        "30",
        "--curves",
        "4",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("two-parameter curves: • period doubling"),
        "{out}"
    );
    // The (1, 1) period doubling on most rows, and codimension-two points.
    let rows_with_pd = out
        .lines()
        .filter(|l| l.contains('│') && l.contains('•'))
        .count();
    assert!(rows_with_pd >= 15, "{rows_with_pd}: {out}");
    assert!(out.contains('◉') && out.contains('×'), "{out}");
    let (code, _, err) = run(&[
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.62",
        "--y",
        "d:0..1",
        "--size",
        "6x4",
        "--format",
        "csv",
        "--curves",
        "4",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--curves") && err.trim().lines().count() == 1,
        "{err}"
    );
}

/// Whether `basins` at (α, D) finds a stable (2, 2) cycle and another attractor beside
/// it: the coexistence that lets a pixel started near the (1, 1) solution end elsewhere
/// where the (2, 2) cycle is stable.
fn two_two_coexists(alpha: f64, d: f64) -> bool {
    let table = format!("fd:{d}");
    let a = format!("{alpha}");
    let o = bouncemap(&[
        "basins", "--table", &table, "--alpha", &a, "--grid", "60x30", "--format", "json",
    ]);
    ok(&o);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let att = v["attractors"].as_array().unwrap();
    att.len() >= 2
        && att
            .iter()
            .any(|x| x["kind"] == "periodic" && x["events"] == 2 && x["periods"] == 2)
}

/// `figure plane --curves`: the period-2 pixels of the (α, D) plane lie between the
/// curves drawn for them, on every row, D < 0.25 included. On every row, between the last period-1 pixel and the first
/// (2, 2) curve (its period doubling or its border collision) after it, every pixel
/// further than a pixel and a half from the curve is period 2, or `basins` there finds
/// the (2, 2) cycle coexisting with the attractor the pixel's start went to; within five pixels beyond the curve no pixel is period 2 (or
/// `basins` confirms a coexisting one).
#[test]
fn the_period_two_region_of_the_plane_lies_between_its_curves() {
    let d = dir("plane-curves");
    let (out, data) = (d.join("p.svg"), d.join("p.json"));
    let (nx, ny) = (120usize, 41usize);
    let pixels = format!("{nx}x{ny}");
    ok(&bouncemap(&[
        "figure",
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.62",
        "--y",
        "d:0..1",
        "--pixels",
        &pixels,
        "--curves",
        "4",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let all = fig["panels"][0]["series"].as_array().unwrap();
    let dx = 0.17 / (nx - 1) as f64;
    // Every pixel's class by (column, row).
    let mut class = vec![String::new(); nx * ny];
    for sr in all.iter().filter(|s| s["kind"] == "cells") {
        for p in sr["points"].as_array().unwrap() {
            let (a, dv) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            let (i, j) = (
                ((a - 0.45) / dx).round() as usize,
                (dv * (ny - 1) as f64).round() as usize,
            );
            class[i * ny + j] = sr["name"].as_str().unwrap().to_string();
        }
    }
    // The curves of the (2, 2) cycle, as polylines.
    let curves2: Vec<Vec<(f64, f64)>> = all
        .iter()
        .filter(|s| s["name"].as_str().unwrap_or("").ends_with("of (2, 2)"))
        .flat_map(|s| s["lines"].as_array().unwrap().iter())
        .map(|l| {
            l.as_array()
                .unwrap()
                .iter()
                .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect()
        })
        .collect();
    assert!(curves2.len() >= 2, "the (2, 2) PD and BC curves");
    let at = |i: usize, j: usize| class[i * ny + j].as_str();
    let (mut rows, mut confirmed) = (0, 0);
    for j in 0..ny {
        let dval = j as f64 / (ny - 1) as f64;
        let alpha = |i: usize| 0.45 + i as f64 * dx;
        let Some(last1) = (0..nx).filter(|&i| at(i, j) == "period-1").max() else {
            continue;
        };
        let crossing = curves2
            .iter()
            .flat_map(|l| l.windows(2))
            .filter(|w| (w[0].1 - dval) * (w[1].1 - dval) <= 0.0 && w[0].1 != w[1].1)
            .map(|w| w[0].0 + (dval - w[0].1) / (w[1].1 - w[0].1) * (w[1].0 - w[0].0))
            .filter(|&a| a > alpha(last1))
            .fold(f64::INFINITY, f64::min);
        if !crossing.is_finite() {
            // No (2, 2) curve on this row: then there is no period-2 region to bound
            // (a region without its curve would be a curve missing).
            let twos = (0..nx).filter(|&i| at(i, j) == "period-2").count();
            assert!(
                twos <= 1,
                "D = {dval}: {twos} period-2 pixels and no (2, 2) curve"
            );
            continue;
        }
        // Between the (1, 1) PD (one pixel of slack after it) and the curve.
        for i in (last1 + 2)..nx {
            if alpha(i) > crossing - 1.5 * dx {
                break;
            }
            if at(i, j) != "period-2" {
                assert!(
                    two_two_coexists(alpha(i), dval),
                    "D = {dval}, α = {}: {} where the (2, 2) cycle is stable (curve at {crossing}), and basins finds no coexistence",
                    alpha(i),
                    at(i, j)
                );
                confirmed += 1;
            }
        }
        // Just beyond the curve the (2, 2) cycle is unstable or gone: no period 2.
        for i in 0..nx {
            let a = alpha(i);
            if a > crossing + 1.5 * dx && a <= crossing + 6.0 * dx && at(i, j) == "period-2" {
                assert!(
                    two_two_coexists(a, dval),
                    "D = {dval}, α = {a}: period 2 beyond the (2, 2) curve at {crossing}"
                );
                confirmed += 1;
            }
        }
        rows += 1;
    }
    // Every row but D = 0 (where the period-2 region shrinks to the (1, 1) PD point).
    assert!(rows >= ny - 2, "only {rows} rows with a period-2 run");
    assert!(confirmed <= 20, "{confirmed} pixels needed basins");
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure curves` draws what `curves` computes: one line per curve (the same points)
/// and a circle per codimension-two point; a plane without an α axis is refused for
/// `figure plane --curves`.
#[test]
fn the_curves_figure_draws_what_curves_computes() {
    let d = dir("curves");
    let (out, data) = (d.join("c.png"), d.join("c.json"));
    let flags = [
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.7",
        "--y",
        "d:0..1",
        "--max-period",
        "4",
    ];
    let mut fa = vec!["figure", "curves"];
    fa.extend_from_slice(&flags);
    fa.extend_from_slice(&["--out", s(&out), "--data", s(&data)]);
    ok(&bouncemap(&fa));
    assert!(Image::read(&out).width > 100);
    let mut ca = vec!["curves"];
    ca.extend_from_slice(&flags);
    ca.extend_from_slice(&["--format", "json"]);
    let o = bouncemap(&ca);
    ok(&o);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let fig = json(&data);
    let all = fig["panels"][0]["series"].as_array().unwrap();
    let curves = v["curves"].as_array().unwrap();
    for (i, c) in curves.iter().enumerate() {
        let name = format!(
            "curve {i}: {} of ({}, {})",
            c["kind"].as_str().unwrap(),
            c["n"],
            c["k"]
        );
        let line = &all.iter().find(|s| s["name"] == name.as_str()).unwrap()["lines"][0];
        let pts = c["points"].as_array().unwrap();
        assert_eq!(line.as_array().unwrap().len(), pts.len(), "{name}");
        assert_eq!(line[0][0].as_f64(), pts[0]["alpha"].as_f64());
        assert_eq!(line[0][1].as_f64(), pts[0]["D"].as_f64());
    }
    assert_eq!(
        series(&fig, "codimension-two points").len(),
        v["codim2"].as_array().unwrap().len()
    );
    let o = bouncemap(&[
        "figure",
        "plane",
        "--table",
        "fd",
        "--x",
        "r:0.5..0.9",
        "--y",
        "d:0..1",
        "--alpha",
        "0.5",
        "--curves",
        "4",
        "--out",
        s(&d.join("p.png")),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--curves") && err.trim().lines().count() == 1,
        "{err}"
    );
    assert!(!d.join("p.png").exists());
    std::fs::remove_dir_all(&d).unwrap();
}
