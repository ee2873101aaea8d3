//! The `continue` and `cascade` commands as a user runs them: their numbers against
//! `fixed` and `two-cycle` through the binary, the formats, and bad input (one line
//! with the valid range, exit status 2).

use crate::cli::{json, run};
use serde_json::Value;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn alpha_1_of_cascade_is_alpha_pd_of_fixed() {
    for table in ["fd:0.1", "fd:1", "sine"] {
        let c = json(&[
            "cascade", "--table", table, "--r", "0.8", "--depth", "2", "--format", "json",
        ]);
        let fx = json(&[
            "fixed", "--table", table, "--alpha", "0.03", "--r", "0.8", "--format", "json",
        ]);
        let (a1, pd) = (f(&c["alphas"][0]), f(&fx["alpha_pd"]));
        assert!((a1 - pd).abs() <= 1e-10, "{table}: {a1} vs {pd}");
    }
}

#[test]
fn the_two_two_branch_of_continue_agrees_with_two_cycle() {
    let v = json(&[
        "continue",
        "--table",
        "fd:0.1",
        "--r",
        "0.8",
        "--alpha",
        "0.5..0.52",
        "--from",
        "two-cycle",
        "--format",
        "json",
    ]);
    let b = &v["branches"][0];
    assert_eq!((b["n"].as_u64(), b["k"].as_u64()), (Some(2), Some(2)));
    let tc0 = json(&[
        "two-cycle",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.511",
        "--r",
        "0.8",
        "--format",
        "json",
    ]);
    let bc = f(&tc0["border_collision"]["alpha"]);
    // The branch's border collision is two-cycle's.
    let specials = b["specials"].as_array().unwrap();
    let s = specials
        .iter()
        .find(|s| s["kind"] == "border_collision")
        .expect("a border collision");
    assert!(
        (f(&s["alpha"]) - bc).abs() <= 1e-10,
        "{} vs {bc}",
        s["alpha"]
    );
    assert_eq!(s["persists"], Value::Bool(false));
    // Three of its points (stable ones, before the collision) against two-cycle there.
    let pts: Vec<&Value> = b["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| f(&p["alpha"]) > 0.5100 && f(&p["alpha"]) < bc - 1e-4)
        .collect();
    assert!(pts.len() >= 3, "{}", pts.len());
    for p in [pts[0], pts[pts.len() / 2], pts[pts.len() - 1]] {
        let a = f(&p["alpha"]).to_string();
        let tc = json(&[
            "two-cycle",
            "--table",
            "fd:0.1",
            "--alpha",
            &a,
            "--r",
            "0.8",
            "--format",
            "json",
        ]);
        let t = &tc["two_cycle"];
        let mut ph = [f(&p["phases"][0]), f(&p["phases"][1])];
        let mut vs = [f(&p["velocities"][0]), f(&p["velocities"][1])];
        if ph[0] > ph[1] {
            ph.swap(0, 1);
            vs.swap(0, 1);
        }
        for (x, y) in [
            (ph[0], &t["phase0"]),
            (ph[1], &t["phase1"]),
            (vs[0], &t["v0"]),
            (vs[1], &t["v1"]),
        ] {
            assert!((x - f(y)).abs() <= 1e-10, "α = {a}: {x} vs {y}");
        }
        assert!(f(&p["return_error"]) <= 1e-11);
    }
}

#[test]
fn the_papers_question_is_answered_by_one_command() {
    let v = json(&["cascade", "--d", "0.1..0.5:3", "--format", "json"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for (row, d) in rows.iter().zip([0.1, 0.3, 0.5]) {
        assert_eq!(f(&row["d"]), d);
        assert_eq!(row["ends_by"], "border_collision", "{row}");
        assert_eq!(row["ends_period"].as_u64(), Some(2), "{row}");
        assert_eq!(f(&row["phase"]), 0.0);
    }
    let (code, out, _) = run(&["cascade", "--d", "0.1..1:10", "--format", "csv"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 11);
    assert!(lines[0].starts_with("d,found,max_period,ends_period,ends_by,"));
    assert!(
        lines[3].starts_with("0.3,true,2,2,border_collision,"),
        "{}",
        lines[3]
    );
    // D = 1: no border collision through period 32.
    assert!(lines[10].starts_with("1.0,true,32,,,"), "{}", lines[10]);
}

#[test]
fn csv_and_text_formats() {
    let (code, out, err) = run(&[
        "continue",
        "--table",
        "cubic",
        "--alpha",
        "0.45..0.6",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let mut lines = out.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("branch,n,k,parent,record,alpha,phase,"));
    let kinds: Vec<&str> = lines.map(|l| l.split(',').nth(4).unwrap()).collect();
    assert!(kinds.contains(&"period_doubling") && kinds.contains(&"window_exit"));
    let (code, out, _) = run(&["cascade", "--table", "cubic", "--depth", "4"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("alpha_4 = ") && out.contains("delta_3 = "),
        "{out}"
    );
    let (code, out, _) = run(&["cascade", "--table", "quad"]);
    assert_eq!(code, 0);
    assert!(out.contains("no (2, 2) branch is born"), "{out}");
}

#[test]
fn bad_input_is_one_line_with_the_valid_range_and_status_2() {
    for (args, range) in [
        (vec!["continue", "--alpha", "0.6..0.5"], "LO < HI"),
        (vec!["continue", "--alpha", "0..0.5"], "(0, 1000]"),
        (vec!["continue", "--alpha", "0.5"], "LO..HI"),
        (
            vec!["continue", "--alpha", "0.4..0.5", "--n", "2", "--t0", "0.1"],
            "--v0",
        ),
        (
            vec![
                "continue", "--alpha", "0.4..0.5", "--n", "0", "--t0", "0.1", "--v0", "1",
            ],
            "[1, 1024]",
        ),
        (
            vec![
                "continue", "--alpha", "0.4..0.5", "--from", "fixed", "--n", "2",
            ],
            "--n",
        ),
        (vec!["cascade", "--depth", "0"], "[1, 12]"),
        (vec!["cascade", "--depth", "13"], "[1, 12]"),
        (vec!["cascade", "--d", "0..2:3"], "[0, 1]"),
        (vec!["cascade", "--d", "0.1..0.5"], "LO..HI:N"),
        (vec!["cascade", "--d", "0.1..0.5:0"], "[1, 1000]"),
        (vec!["cascade", "--r", "1"], "(0, 1)"),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(range), "{args:?}: {err}");
    }
}
