//! `manifolds` (the unstable and stable manifolds of a saddle cycle) as a user runs it,
//! checked against `fixed`'s closed-form (1, 1) solution and its Jacobian, and bad
//! input.

use crate::cli::{json, ok, run};

const SADDLE: [&str; 5] = ["manifolds", "--table", "fd:0.1", "--alpha", "0.45"];

fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
    base.iter().chain(more).copied().collect()
}

#[test]
fn the_manifolds_leave_the_closed_form_saddle_along_its_jacobians_eigenvectors() {
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
    // The closed-form Jacobian J of the (1, 1) solution: J e = λ e for each manifold's
    // direction e, with λ = μ (unstable) or 1/μ (stable), J's eigenvalues outside and
    // inside the unit circle.
    let j = |a: usize, b: usize| s["jacobian"][a][b].as_f64().unwrap();
    let (tr, det) = (j(0, 0) + j(1, 1), j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0));
    let root = (tr * tr - 4.0 * det).sqrt();
    let (largest, smallest) = (0.5 * (tr + root), 0.5 * (tr - root));
    let ms = m["manifolds"].as_array().unwrap();
    assert_eq!(ms.len(), 2);
    for mf in ms {
        let e = [
            mf["direction"][0].as_f64().unwrap(),
            mf["direction"][1].as_f64().unwrap(),
        ];
        let mu = mf["multiplier"].as_f64().unwrap();
        let lambda = match mf["manifold"].as_str().unwrap() {
            "unstable" => {
                assert!((mu - largest).abs() < 1e-9 * largest, "{mu} {largest}");
                mu
            }
            "stable" => {
                assert!((1.0 / mu - smallest).abs() < 1e-9, "{mu} {smallest}");
                1.0 / mu
            }
            other => panic!("{other}"),
        };
        let je = [
            j(0, 0) * e[0] + j(0, 1) * e[1],
            j(1, 0) * e[0] + j(1, 1) * e[1],
        ];
        assert!((je[0] - lambda * e[0]).abs() < 1e-9 && (je[1] - lambda * e[1]).abs() < 1e-9);
        for b in mf["branches"].as_array().unwrap() {
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
    }
    // The csv holds the same points, a row each.
    let csv = ok(&with(&SADDLE, &["--length", "0.5", "--format", "csv"]));
    let rows = csv.lines().count() - 1;
    let points: usize = ms
        .iter()
        .flat_map(|mf| mf["branches"].as_array().unwrap())
        .map(|b| b["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(rows, points);
    let text = ok(&SADDLE);
    for want in [
        "unstable manifold",
        "stable manifold, grown under the inverse map",
        "branch +:",
        "branch -:",
    ] {
        assert!(text.contains(want), "{want}: {text}");
    }
    // --which picks one.
    let only = json(&with(
        &SADDLE,
        &["--length", "0.5", "--which", "stable", "--format", "json"],
    ));
    let only = only["manifolds"].as_array().unwrap();
    assert_eq!(only.len(), 1);
    assert_eq!(only[0]["manifold"], "stable");
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
    let u = &m["manifolds"][0];
    assert_eq!(u["manifold"], "unstable");
    assert_eq!(
        (u["events"].as_u64(), u["periods"].as_u64()),
        (Some(2), Some(2))
    );
    let lu = m["multipliers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z[0].as_f64().unwrap())
        .find(|x| *x < -1.0)
        .unwrap();
    assert!((u["multiplier"].as_f64().unwrap() - lu * lu).abs() < 1e-9);
    // The stable manifold under the same second iterate of the inverse: 1/λₛ².
    let s = &m["manifolds"][1];
    assert_eq!(s["manifold"], "stable");
    let ls = m["multipliers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z[0].as_f64().unwrap())
        .find(|x| x.abs() < 1.0)
        .unwrap();
    assert!(ls < 0.0);
    assert!((s["multiplier"].as_f64().unwrap() * ls * ls - 1.0).abs() < 1e-9);
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
fn figure_manifolds_draws_every_branch_and_the_saddle() {
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
    let words = svg_words(&svg);
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
    for mf in m["manifolds"].as_array().unwrap() {
        for b in mf["branches"].as_array().unwrap() {
            let side = if b["branch"] == "+" { "+" } else { "\u{2212}" };
            let want = format!(
                "{} {side}: {} points, length {:.3}",
                mf["manifold"].as_str().unwrap(),
                b["points"].as_array().unwrap().len(),
                b["length"].as_f64().unwrap()
            );
            assert!(words.contains(&want), "{want} not in {words}");
        }
    }
    assert!(words.contains("saddle (1, 1)"), "{words}");
}

#[test]
fn figure_basins_draws_the_manifolds_and_counts_the_pairs_across_the_stable_one() {
    let d = crate::scratch::dir("manifolds", "basins");
    let svg = d.join("b.svg");
    let svg_s = svg.to_str().unwrap();
    ok(&[
        "figure",
        "basins",
        "--table",
        "cubic",
        "--alpha",
        "0.47",
        "--grid",
        "100x50",
        "--manifolds",
        "--manifold-length",
        "1",
        "--out",
        svg_s,
    ]);
    let words = svg_words(&svg);
    says(
        &words,
        &[
            "stable + manifold",
            "unstable − manifold",
            "saddle (1, 1)",
            "end on different attractors in",
        ],
    );
    // The stable manifold's branches, as `manifolds` grows them.
    let m = cubic_manifolds(&["--length", "1", "--which", "stable", "--format", "json"]);
    for b in m["manifolds"][0]["branches"].as_array().unwrap() {
        let side = if b["branch"] == "+" { "+" } else { "\u{2212}" };
        let want = format!(
            "stable {side} manifold, length {:.3}",
            b["length"].as_f64().unwrap()
        );
        assert!(words.contains(&want), "{want} not in {words}");
    }
    // A saddle that is not there, or not a saddle value at all: one line, status 2.
    for (value, want) in [
        ("1:1:0.5", "is not a saddle: valid K"),
        ("0", "k: 0 is out of range"),
        ("1:1:0.15:0.5", "not a saddle"),
    ] {
        let (code, _, err) = run(&[
            "figure",
            "basins",
            "--table",
            "cubic",
            "--alpha",
            "0.47",
            "--manifolds",
            value,
            "--out",
            svg_s,
        ]);
        assert_eq!(code, 2, "{value}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{value}: {err}");
    }
}

/// Several saddles over one basins picture: each saddle's manifolds in the legend under
/// its (n, k), with the lengths `manifolds` grows for it, and its own sentence in the
/// caption; more saddles than there are colours, or one named twice, are refused.
#[test]
fn figure_basins_draws_the_manifolds_of_several_saddles() {
    let d = crate::scratch::dir("manifolds", "several");
    let svg = d.join("b.svg");
    let svg_s = svg.to_str().unwrap();
    let base = [
        "figure", "basins", "--table", "cubic", "--alpha", "0.47", "--grid", "60x30",
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        base.iter().chain(extra).map(|s| s.to_string()).collect()
    };
    let args = with(&[
        "--manifolds",
        "--manifolds",
        "2",
        "--manifold-length",
        "1",
        "--out",
        svg_s,
    ]);
    ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let words = svg_words(&svg);
    says(
        &words,
        &[
            "saddle (1, 1)",
            "saddle (1, 2)",
            "Also the manifolds of the saddle (1, 2)",
        ],
    );
    // The second saddle's branches as `manifolds --k 2` grows them.
    let m = cubic_manifolds(&["--k", "2", "--length", "1", "--format", "json"]);
    let mut seen = 0;
    for man in m["manifolds"].as_array().unwrap() {
        let kind = man["manifold"].as_str().unwrap();
        for b in man["branches"].as_array().unwrap() {
            let side = if b["branch"] == "+" { "+" } else { "\u{2212}" };
            let want = format!(
                "(1, 2) {kind} {side} manifold, length {:.3}",
                b["length"].as_f64().unwrap()
            );
            assert!(words.contains(&want), "{want} not in {words}");
            seen += 1;
        }
    }
    assert_eq!(seen, 4, "two branches of each manifold");
    for (extra, want) in [
        (
            &[
                "--manifolds",
                "1",
                "--manifolds",
                "2",
                "--manifolds",
                "3",
                "--manifolds",
                "4",
            ][..],
            "given 4 times; valid: up to 3",
        ),
        (
            &["--manifolds", "2", "--manifolds", "2"][..],
            "value 2 names a saddle already named",
        ),
    ] {
        let mut args = with(extra);
        args.extend(["--out".to_string(), svg_s.to_string()]);
        let (code, _, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(code, 2, "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{err}");
    }
}

/// The words of an SVG figure: its text nodes, joined by spaces.
fn svg_words(svg: &std::path::Path) -> String {
    let text = std::fs::read_to_string(svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    doc.descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .collect::<Vec<_>>()
        .join(" ")
}

/// Each of `wants` is among `words`.
fn says(words: &str, wants: &[&str]) {
    for want in wants {
        assert!(words.contains(want), "{want} not in {words}");
    }
}

/// `manifolds --table cubic --alpha 0.47` (the basins figures' system) with `extra`, as json.
fn cubic_manifolds(extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["manifolds", "--table", "cubic", "--alpha", "0.47"];
    args.extend_from_slice(extra);
    json(&args)
}
