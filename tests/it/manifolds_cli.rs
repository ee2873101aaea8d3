//! `manifolds` (the unstable manifold of a saddle cycle) as a user runs it, checked
//! against `fixed`'s closed-form (1, 1) solution and its Jacobian, and bad input.

use crate::cli::{json, ok, run};

const SADDLE: [&str; 5] = ["manifolds", "--table", "fd:0.1", "--alpha", "0.45"];

fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
    base.iter().chain(more).copied().collect()
}

#[test]
fn the_manifold_leaves_the_closed_form_saddle_along_its_jacobians_eigenvector() {
    let f = json(&[
        "fixed", "--table", "fd:0.1", "--alpha", "0.45", "--format", "json",
    ]);
    let s = f["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["classification"] != "stable")
        .unwrap()
        .clone();
    let m = json(&with(&SADDLE, &["--length", "0.5", "--format", "json"]));
    assert_eq!(m["n"], 1);
    assert_eq!(
        m["saddle"][0].as_f64().unwrap(),
        s["phase"].as_f64().unwrap()
    );
    assert_eq!(m["saddle"][1].as_f64().unwrap(), 0.5);
    // The closed-form Jacobian J of the (1, 1) solution: J e = μ e for the manifold's
    // direction e and multiplier μ, and μ is J's eigenvalue outside the unit circle.
    let j = |a: usize, b: usize| s["jacobian"][a][b].as_f64().unwrap();
    let e = [
        m["direction"][0].as_f64().unwrap(),
        m["direction"][1].as_f64().unwrap(),
    ];
    let mu = m["multiplier"].as_f64().unwrap();
    let je = [
        j(0, 0) * e[0] + j(0, 1) * e[1],
        j(1, 0) * e[0] + j(1, 1) * e[1],
    ];
    assert!((je[0] - mu * e[0]).abs() < 1e-9 && (je[1] - mu * e[1]).abs() < 1e-9);
    let (tr, det) = (j(0, 0) + j(1, 1), j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0));
    let largest = 0.5 * (tr + (tr * tr - 4.0 * det).sqrt());
    assert!((mu - largest).abs() < 1e-9 * largest, "{mu} {largest}");
    for b in m["branches"].as_array().unwrap() {
        assert_eq!(b["end"], "length");
        let pts = b["points"].as_array().unwrap();
        assert!(pts.len() > 20);
        // From the saddle out, a step at most 0.01 apart, the arc length as stated.
        let p = |i: usize| [pts[i][0].as_f64().unwrap(), pts[i][2].as_f64().unwrap()];
        let mut length = 0.0;
        for i in 1..pts.len() {
            let d = (p(i)[0] - p(i - 1)[0]).hypot(p(i)[1] - p(i - 1)[1]);
            assert!(d <= 0.01);
            length += d;
        }
        assert!((length - b["length"].as_f64().unwrap()).abs() < 1e-12);
        assert!(length <= 0.5 && length > 0.49);
    }
    // The csv holds the same points, a row each.
    let csv = ok(&with(&SADDLE, &["--length", "0.5", "--format", "csv"]));
    let rows = csv.lines().count() - 1;
    let points: usize = m["branches"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(rows, points);
    let text = ok(&SADDLE);
    assert!(
        text.contains("branch +:") && text.contains("branch -:"),
        "{text}"
    );
}

#[test]
fn a_flip_saddle_is_grown_under_the_second_iterate() {
    // Past α_PD the (1, 1) solution with f'' < 0 is a saddle with λ < −1.
    let m = json(&[
        "manifolds",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.52",
        "--n",
        "1",
        "--t0",
        "0.19",
        "--v0",
        "0.5",
        "--length",
        "0.2",
        "--format",
        "json",
    ]);
    assert_eq!(
        (m["events"].as_u64(), m["periods"].as_u64()),
        (Some(2), Some(2))
    );
    let lu = m["multipliers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z[0].as_f64().unwrap())
        .find(|x| *x < -1.0)
        .unwrap();
    assert!((m["multiplier"].as_f64().unwrap() - lu * lu).abs() < 1e-9);
}

#[test]
fn no_saddle_and_bad_input_are_refused_with_one_line() {
    for (args, want) in [
        (
            with(&SADDLE, &["--n", "1", "--t0", "0.18", "--v0", "0.5"]),
            "not a saddle",
        ),
        (
            with(&SADDLE, &["--length", "0"]),
            "--length: 0 is out of range",
        ),
        (
            vec!["manifolds", "--table", "fd:0.1", "--alpha", "0.05"],
            "no saddle (1, 1) solution at alpha 0.05",
        ),
    ] {
        let (code, _, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{err}");
    }
}

#[test]
fn figure_manifolds_draws_both_branches_and_the_saddle() {
    let d = crate::scratch::dir("manifolds", "figure");
    let svg = d.join("m.svg");
    let svg_s = svg.to_str().unwrap();
    ok(&[
        "figure",
        "manifolds",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45",
        "--length",
        "1",
        "--out",
        svg_s,
    ]);
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let words: String = doc
        .descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .collect::<Vec<_>>()
        .join(" ");
    // The legend: each branch's points and length as `manifolds` counts them.
    let m = json(&[
        "manifolds",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45",
        "--length",
        "1",
        "--format",
        "json",
    ]);
    for b in m["branches"].as_array().unwrap() {
        let side = if b["branch"] == "+" { "+" } else { "\u{2212}" };
        let want = format!(
            "branch {side}: {} points, length {:.3}",
            b["points"].as_array().unwrap().len(),
            b["length"].as_f64().unwrap()
        );
        assert!(words.contains(&want), "{want} not in {words}");
    }
    assert!(words.contains("saddle (1, 1)"), "{words}");
}
