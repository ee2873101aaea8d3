//! `certify` (proofs of cycles by interval arithmetic) as a user runs it: its boxes
//! against `two-cycle`'s and `fixed`'s solutions (computed by other code: Newton's
//! method on the two-cycle's own equations, the (1, 1) closed form), its formats
//! against each other, the guesses it makes itself, answers that are not proofs, and
//! bad input.

use crate::cli::{json, ok, run};

fn pair(v: &serde_json::Value) -> (f64, f64) {
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

/// `fixed`'s closed-form α_PD of the (1, 1) solution of `table` (asked at α `alpha`).
fn fixed_alpha_pd(table: &str, alpha: &str) -> f64 {
    let f = json(&[
        "fixed", "--table", table, "--alpha", alpha, "--format", "json",
    ]);
    f["alpha_pd"].as_f64().unwrap()
}

fn inside(x: f64, v: &serde_json::Value) -> bool {
    let (lo, hi) = pair(v);
    lo <= x && x <= hi
}

/// fd:1 at α = 0.52: the box of the proved (2, 2) cycle holds `two-cycle`'s solution,
/// is under 1e-12 wide, the cycle is proved stable with `two-cycle`'s multipliers
/// inside the enclosures, and the csv's rows are the json's box.
#[test]
fn the_two_cycle_is_proved_around_two_cycles_solution() {
    let t = json(&[
        "two-cycle",
        "--table",
        "fd:1",
        "--alpha",
        "0.52",
        "--format",
        "json",
    ]);
    let tc = &t["two_cycle"];
    let (p0, v0) = (tc["phase0"].as_f64().unwrap(), tc["v0"].as_f64().unwrap());
    let (p1, v1) = (tc["phase1"].as_f64().unwrap(), tc["v1"].as_f64().unwrap());
    let base = [
        "certify", "--table", "fd:1", "--alpha", "0.52", "--n", "2", "--k", "2",
    ];
    let guess = [
        "--t0".to_string(),
        format!("{}", p0 + 0.01),
        "--v0".to_string(),
        format!("{}", v0 - 0.01),
    ];
    let args: Vec<&str> = base
        .iter()
        .copied()
        .chain(guess.iter().map(String::as_str))
        .collect();
    fn with<'a>(args: &[&'a str], fmt: &'a str) -> Vec<&'a str> {
        args.iter().copied().chain(["--format", fmt]).collect()
    }
    let c = json(&with(&args, "json"));
    assert_eq!(c["verdict"], "proved", "{c}");
    assert!(c["reason"].is_null());
    let b = &c["box"];
    assert!(b["width"].as_f64().unwrap() <= 1e-12);
    assert!(
        inside(p0, &b["phases"][0]) && inside(p1, &b["phases"][1]),
        "{b}"
    );
    assert!(
        inside(v0, &b["velocities"][0]) && inside(v1, &b["velocities"][1]),
        "{b}"
    );
    assert!(inside(0.52, &c["alpha_enclosure"]) && inside(0.8, &c["r_enclosure"]));
    let s = &c["stability"];
    assert_eq!(s["verdict"], "stable");
    assert_eq!(s["multipliers"]["kind"], "complex");
    let z = &tc["multipliers"][0];
    let slack = |v: &serde_json::Value, x: f64| {
        let (lo, hi) = pair(v);
        lo - 1e-12 <= x && x <= hi + 1e-12
    };
    assert!(
        slack(&s["multipliers"]["re"], z["re"].as_f64().unwrap()),
        "{s}"
    );
    assert!(
        slack(&s["multipliers"]["im"], z["im"].as_f64().unwrap().abs()),
        "{s}"
    );
    // det M = r⁴ on a 2-cycle.
    assert!(inside(0.8f64.powi(4), &s["det"]));

    let csv = ok(&with(&args, "csv"));
    let mut lines = csv.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("table,alpha,r,n,k,verdict"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row[5], "proved");
        assert_eq!(row[7], "stable");
        assert_eq!(row[8], i.to_string());
        let lo: f64 = row[9].parse().unwrap();
        let hi: f64 = row[10].parse().unwrap();
        assert_eq!((lo, hi), pair(&b["phases"][i]));
    }

    let text = ok(&args);
    assert!(
        text.contains("verdict: proved: exactly one (2, 2) cycle"),
        "{text}"
    );
    assert!(text.contains("stability: proved stable"), "{text}");
}

/// Without a guess: the stable (1, 1) solution, whose closed-form phase is in the box
/// (v* = 1/2 exactly); and for n = 8 the cycle the orbit settles on (the sine's
/// (8, 8) window after the cascade), proved stable.
#[test]
fn without_a_guess_the_attracting_cycle_is_proved() {
    let f = json(&[
        "fixed", "--table", "sine", "--alpha", "0.02", "--format", "json",
    ]);
    let stable = f["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["classification"] == "stable")
        .unwrap()
        .clone();
    let c = json(&[
        "certify", "--table", "sine", "--alpha", "0.02", "--format", "json",
    ]);
    assert_eq!(c["verdict"], "proved");
    assert!(inside(
        stable["phase"].as_f64().unwrap(),
        &c["box"]["phases"][0]
    ));
    assert!(inside(0.5, &c["box"]["velocities"][0]));
    let c = json(&[
        "certify", "--table", "sine", "--alpha", "0.0316", "--n", "8", "--k", "8", "--format",
        "json",
    ]);
    assert_eq!(c["verdict"], "proved", "{c}");
    assert_eq!(c["stability"]["verdict"], "stable");
    assert_eq!(c["box"]["phases"].as_array().unwrap().len(), 8);
}

/// A guess with no cycle near it, a guess a quarter period off, and the (1, 1) solution
/// at its closed-form period doubling: answers with status 0 that say what was not
/// proved and why.
#[test]
fn what_is_not_proved_says_why() {
    let c = json(&[
        "certify", "--table", "sine", "--alpha", "0.02", "--t0", "0.5", "--v0", "0.5", "--format",
        "json",
    ]);
    assert_eq!(c["verdict"], "not_proved");
    assert_eq!(c["reason"], "no_cycle");
    assert!(c["box"].is_null());
    let f = json(&[
        "fixed", "--table", "sine", "--alpha", "0.02", "--format", "json",
    ]);
    let phase = f["solutions"][0]["phase"].as_f64().unwrap();
    let off = format!("{}", phase + 0.25);
    let c = json(&[
        "certify", "--table", "sine", "--alpha", "0.02", "--t0", &off, "--v0", "0.5", "--format",
        "json",
    ]);
    assert_eq!(c["verdict"], "not_proved");
    assert!(
        c["reason"] == "far_from_guess" || c["reason"] == "no_cycle",
        "{c}"
    );
    // α_PD of the sine's (1, 1) solution in closed form: f'(t*) = 2πα cos 2πt* = c and
    // f''(t*) = −(2π)²α sin 2πt* = κ_c = −2(1 + r²)/(1 + r)², so
    // α = √((2πc)² + κ_c²) / (2π)² with c = ½(1 − r)/(1 + r).
    let r = 0.8f64;
    let kc = -2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
    let c0 = 0.5 * (1.0 - r) / (1.0 + r);
    let w = 2.0 * std::f64::consts::PI;
    let alpha_pd = (kc * kc + (w * c0) * (w * c0)).sqrt() / (w * w);
    let a = format!("{alpha_pd}");
    let (code, text, _) = run(&["certify", "--table", "sine", "--alpha", &a]);
    assert_eq!(code, 0);
    assert!(text.contains("verdict: proved"), "{text}");
    assert!(
        text.contains("stability: undecided, not proved")
            && text.contains("period doubling test's enclosure contains 0"),
        "{text}"
    );
}

#[test]
fn bad_input_is_one_line_with_the_valid_range() {
    for (args, needle) in [
        (vec!["certify", "--n", "65"], "[1, 64]"),
        (vec!["certify", "--t0", "0.2"], "--v0"),
        (vec!["certify", "--k", "0"], "k"),
        (vec!["certify", "--format", "yaml"], "yaml"),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked") && !err.contains("backtrace"));
    }
    // No (1, 3) solution exists at this α: a clear refusal, not a guess.
    let (code, _, err) = run(&["certify", "--table", "sine", "--alpha", "0.001", "--k", "3"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--t0 PHASE --v0 V"), "{err}");
}

/// `cascade --certify`: α₁ of fd:0.1 proved in an interval under 1e-12 holding
/// `fixed`'s closed-form α_PD, and fd:0.5's α₂ (a border collision) in one holding
/// `two-cycle`'s border collision; `--d` is refused beside it.
#[test]
fn the_cascade_proves_its_alphas() {
    let alpha_pd = fixed_alpha_pd("fd:0.1", "0.45");
    let c = json(&[
        "cascade",
        "--table",
        "fd:0.1",
        "--depth",
        "2",
        "--certify",
        "--format",
        "json",
    ]);
    let l = &c["levels"][0];
    assert_eq!(l["proof"], "proved", "{l}");
    let (lo, hi) = (
        l["alpha_lo"].as_f64().unwrap(),
        l["alpha_hi"].as_f64().unwrap(),
    );
    assert!(
        lo <= alpha_pd && alpha_pd <= hi && hi - lo <= 1e-12,
        "{lo} {hi} {alpha_pd}"
    );

    let t = json(&[
        "two-cycle",
        "--table",
        "fd:0.5",
        "--alpha",
        "0.53",
        "--format",
        "json",
    ]);
    let bc = t["border_collision"]["alpha"].as_f64().unwrap();
    let csv = ok(&[
        "cascade",
        "--table",
        "fd:0.5",
        "--certify",
        "--format",
        "csv",
    ]);
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let row: Vec<&str> = csv
        .lines()
        .find(|l| l.contains("border_collision"))
        .unwrap()
        .split(',')
        .collect();
    assert_eq!(row[col("proof")], "proved");
    let lo: f64 = row[col("alpha_lo")].parse().unwrap();
    let hi: f64 = row[col("alpha_hi")].parse().unwrap();
    assert!(lo <= bc && bc <= hi && hi - lo <= 1e-12, "{lo} {hi} {bc}");

    let (code, _, err) = run(&["cascade", "--d", "0.1..1:2", "--certify"]);
    assert_eq!(code, 2, "{err}");
}

/// `continue --certify` on the sine: every point carries its proof, a point proved
/// stable is one the continuation calls stable and one proved unstable is not, and the
/// period doubling it passes is proved in an interval holding `fixed`'s α_PD.
#[test]
fn continue_proves_its_points_and_special_points() {
    let alpha_pd = fixed_alpha_pd("sine", "0.02");
    let c = json(&[
        "continue",
        "--table",
        "sine",
        "--alpha",
        "0.01..0.03",
        "--max-period",
        "2",
        "--certify",
        "--format",
        "json",
    ]);
    let branches = c["branches"].as_array().unwrap();
    assert_eq!(branches.len(), 2);
    let mut proved = 0;
    for b in branches {
        for p in b["points"].as_array().unwrap() {
            let proof = &p["proof"];
            assert!(proof.is_object(), "{p}");
            if proof["verdict"] == "proved" {
                proved += 1;
                match proof["stability"].as_str().unwrap() {
                    "stable" => assert_eq!(p["stable"], true),
                    "unstable" => assert_eq!(p["stable"], false),
                    _ => {}
                }
            } else {
                assert!(proof["reason"].is_string());
            }
        }
    }
    assert!(proved >= 30, "{proved}");
    let pd = branches[0]["specials"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["kind"] == "period_doubling")
        .unwrap();
    assert_eq!(pd["proof"]["verdict"], "proved", "{pd}");
    let (lo, hi) = pair(&pd["proof"]["alpha"]);
    assert!(lo <= alpha_pd && alpha_pd <= hi, "{lo} {hi} {alpha_pd}");
    // Without --certify no proof is made or printed.
    let c = json(&[
        "continue",
        "--table",
        "sine",
        "--alpha",
        "0.01..0.03",
        "--max-period",
        "1",
        "--format",
        "json",
    ]);
    assert!(c["branches"][0]["points"][0]["proof"].is_null());
    let points = c["branches"][0]["points"].as_array().unwrap().len();
    let text = ok(&[
        "continue",
        "--table",
        "sine",
        "--alpha",
        "0.01..0.03",
        "--max-period",
        "1",
        "--certify",
    ]);
    assert!(
        text.contains("proved by interval arithmetic: in ["),
        "{text}"
    );
    assert!(
        text.contains(&format!("proved: {points} of {points} points")),
        "{text}"
    );
}
