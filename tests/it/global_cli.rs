//! `attractors` (attractors followed along α) as a user runs it: its fractions against
//! `basins` on the same grid, the sums every α must satisfy, the three formats saying
//! the same, `--out` and `--check`, and bad input (one line, status 2).

use crate::cli::{json, ok, run};
use crate::scratch;

/// The cubic table at r = 0.8 over a short window ending at α = 0.47, where the (1, 1)
/// solution and a sticking cycle coexist.
const CUBIC: [&str; 9] = [
    "attractors",
    "--table",
    "cubic",
    "--r",
    "0.8",
    "--alpha",
    "0.465..0.47",
    "--steps",
    "2",
];

fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
    base.iter().chain(more).copied().collect()
}

#[test]
fn fractions_at_the_last_alpha_are_basins_on_the_same_grid() {
    let v = json(&with(&CUBIC, &["--grid", "40x40", "--format", "json"]));
    let b = json(&[
        "basins", "--table", "cubic", "--r", "0.8", "--alpha", "0.47", "--grid", "40x40",
        "--format", "json",
    ]);
    assert_eq!(v["w_max"], b["w_max"]);
    let last = &v["values"][1];
    assert_eq!(last["alpha"], 0.47);
    let key = |a: &serde_json::Value| {
        (
            a["kind"].as_str().unwrap().to_string(),
            a["events"].as_u64(),
            a["periods"].as_i64(),
        )
    };
    let mut ours: Vec<_> = last["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|a| a["fraction"].as_f64().unwrap() > 0.0)
        .map(|a| (key(a), a["fraction"].as_f64().unwrap()))
        .collect();
    let mut theirs: Vec<_> = b["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| (key(a), a["fraction"].as_f64().unwrap()))
        .collect();
    ours.sort_by(|x, y| x.partial_cmp(y).unwrap());
    theirs.sort_by(|x, y| x.partial_cmp(y).unwrap());
    assert!(ours.len() >= 2, "{ours:?}");
    assert_eq!(ours.len(), theirs.len(), "{ours:?} {theirs:?}");
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.0 .0, b.0 .0);
        assert!((a.1 - b.1).abs() <= 0.01, "{ours:?} {theirs:?}");
    }
}

#[test]
fn every_alpha_sums_to_one_and_the_formats_agree() {
    let args = with(
        &[
            "attractors",
            "--table",
            "fd:0.1",
            "--r",
            "0.8",
            "--alpha",
            "0.46..0.52",
            "--steps",
            "4",
        ],
        &["--grid", "24x24"],
    );
    let csv = ok(&with(&args, &["--format", "csv"]));
    let doc = json(&with(&args, &["--format", "json"]));
    let text = ok(&args);
    let mut rows = csv::Reader::from_reader(csv.as_bytes());
    let header = rows.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let mut sums = std::collections::BTreeMap::<String, (f64, f64)>::new();
    let mut deaths = 0;
    for r in rows.records() {
        let r = r.unwrap();
        let alpha = r[col("alpha")].to_string();
        let e = sums
            .entry(alpha)
            .or_insert((0.0, r[col("not_settled")].parse().unwrap()));
        if r[col("kind")].is_empty() {
            // A death's row: the attractor is gone at this α.
            assert!(matches!(&r[col("change")], "death" | "merge"), "{r:?}");
            assert_eq!(r[col("fraction")].parse::<f64>().unwrap(), 0.0);
            deaths += 1;
        } else {
            e.0 += r[col("fraction")].parse::<f64>().unwrap();
        }
    }
    assert_eq!(sums.len(), 4);
    for (alpha, (attractors, not_settled)) in &sums {
        assert!(
            (attractors + not_settled - 1.0).abs() < 1e-12,
            "{alpha}: {attractors} + {not_settled}"
        );
    }
    // The json says the same: values, the same deaths among its changes, fractions
    // summing to 1, and the text names each change.
    let values = doc["values"].as_array().unwrap();
    assert_eq!(values.len(), 4);
    for v in values {
        let s: f64 = v["attractors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a["fraction"].as_f64().unwrap())
            .sum::<f64>()
            + v["not_settled"].as_f64().unwrap();
        assert!((s - 1.0).abs() < 1e-12);
    }
    let changes = doc["changes"].as_array().unwrap();
    let gone = changes
        .iter()
        .filter(|c| matches!(c["change"].as_str(), Some("death" | "merge")))
        .count();
    assert_eq!(gone, deaths);
    assert!(!changes.is_empty());
    for c in changes {
        let n = c["attractor"].as_u64().unwrap();
        assert!(text.contains(&format!("attractor {n}")), "{text}");
    }
    // The (1, 1) solution of fd:0.1 loses stability by period doubling at α_PD =
    // 0.5099652832 (`fixed`), between the last two values: the attractor that is the
    // (1, 1) cycle at α = 0.5 changes there (into the doubled cycle, or gone).
    let at_half = &values[2];
    assert_eq!(at_half["alpha"], 0.5);
    let p11 = at_half["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|a| a["kind"] == "periodic" && a["events"] == 1 && a["periods"] == 1)
        .unwrap_or_else(|| panic!("{at_half}"));
    let pd = changes
        .iter()
        .find(|c| c["attractor"] == p11["id"] && c["between"][0].as_f64().unwrap() >= 0.5)
        .unwrap_or_else(|| panic!("{changes:?}"));
    let between: Vec<f64> = pd["between"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(
        between[0] < 0.5099652832 && 0.5099652832 < between[1],
        "{pd}"
    );
    // It is gone, and Newton's method on the exact map says why: at 0.52 the (1, 1)
    // cycle is there with a multiplier below −1.
    assert!(
        matches!(pd["change"].as_str(), Some("death" | "merge")),
        "{pd}"
    );
    assert_eq!(pd["cause"], "unstable", "{pd}");
    assert_eq!(pd["bifurcation"], "period doubling", "{pd}");
    let m = &pd["multiplier"];
    assert!(
        m[0].as_f64().unwrap() < -1.0 && m[1].as_f64().unwrap() == 0.0,
        "{pd}"
    );
}

#[test]
fn out_is_written_whole_and_check_computes_nothing() {
    let dir = scratch::dir("global", "out");
    let file = dir.join("a.json");
    let args = with(
        &CUBIC,
        &[
            "--grid",
            "12x12",
            "--format",
            "json",
            "--out",
            scratch::s(&file),
        ],
    );
    let (code, out, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(out.is_empty());
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
    assert_eq!(v["steps"], 2);
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
    // --check: the plan, nothing written, the file left as it was.
    let before = std::fs::read(&file).unwrap();
    let plan = ok(&with(&args, &["--check"]));
    assert!(
        plan.contains("attractors at 2 α values of 144 starts"),
        "{plan}"
    );
    assert!(plan.contains("nothing computed"), "{plan}");
    assert_eq!(std::fs::read(&file).unwrap(), before);
}

#[test]
fn bad_input_is_one_line_with_the_valid_range_and_status_2() {
    for (args, want) in [
        (vec!["attractors", "--alpha", "0.5"], "valid LO..HI"),
        (vec!["attractors", "--alpha", "0.5..0.4"], "LO < HI"),
        (
            vec!["attractors", "--alpha", "0.4..0.5", "--steps", "0"],
            "[1, 100000]",
        ),
        (
            vec!["attractors", "--alpha", "0.4..0.5", "--grid", "0x5"],
            "valid NXxNY",
        ),
        (
            vec!["attractors", "--alpha", "0.4..0.5", "--w-max", "0"],
            "(0, 1000]",
        ),
        (
            vec!["attractors", "--alpha", "0.4..0.5", "--r", "1"],
            "(0, 1)",
        ),
        (
            vec!["attractors", "--alpha", "0.4..0.5", "--format", "braille"],
            "text, csv, json",
        ),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(out.is_empty());
    }
    // Without a window: clap's usage error, status 2.
    let (code, _, err) = run(&["attractors"]);
    assert_eq!(code, 2);
    assert!(err.contains("--alpha"), "{err}");
}

#[test]
fn stopping_at_the_seeds_cycles_changes_nothing_but_the_time() {
    // fd:0.5 past α ≈ 0.56: every start ends on one long sticking cycle, which a start
    // that reaches a release of it stops at; before, the (2, 2) cycle and a sticking
    // cycle coexist. The csv is the same byte for byte with --full-runs.
    let args = [
        "attractors",
        "--table",
        "fd:0.5",
        "--alpha",
        "0.53..0.58",
        "--steps",
        "6",
        "--grid",
        "16x16",
        "--format",
        "csv",
    ];
    let stopped = ok(&args);
    let full = ok(&with(&args, &["--full-runs"]));
    assert_eq!(stopped, full);
    assert!(stopped.lines().count() > 6, "{stopped}");
    assert!(
        stopped.contains(",sticking,") && stopped.contains(",periodic,2,2,"),
        "{stopped}"
    );
}

#[test]
fn many_one_start_attractors_are_called_likely_transients() {
    // The sine table at α = 0.45: hundreds of starts still wander at T = 5000, each a
    // one-start "attractor" by the cells it visits; the report says what they likely
    // are. The cubic table's two attractors get no such note.
    let text = ok(&[
        "attractors",
        "--table",
        "sine",
        "--alpha",
        "0.44..0.45",
        "--steps",
        "2",
        "--grid",
        "20x20",
    ]);
    let note = text
        .lines()
        .find(|l| l.starts_with("note: at 2 α values up to "))
        .unwrap_or_else(|| panic!("{text}"));
    let many: usize = note["note: at 2 α values up to ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(many >= 10, "{note}");
    assert!(
        note.contains("likely transients longer than T = 5000"),
        "{note}"
    );
    let cubic = ok(&with(&CUBIC, &["--grid", "20x20"]));
    assert!(!cubic.contains("likely transients"), "{cubic}");
}

/// `attractors --crises` on the sine (r = 0.8) over `alpha` in `steps` values, json:
/// its crises.
fn sine_crises(alpha: &str, steps: &str, grid: &str) -> Vec<serde_json::Value> {
    let d = crate::cli::json(&[
        "attractors",
        "--table",
        "sine",
        "--alpha",
        alpha,
        "--steps",
        steps,
        "--grid",
        grid,
        "--crises",
        "--format",
        "json",
    ]);
    d["crises"]
        .as_array()
        .expect("crises with --crises")
        .clone()
}

/// `orbit` of the sine (r = 0.8) at α from (t0, v0), `bounces` events, as csv.
fn sine_orbit(alpha: f64, t0: f64, v0: f64, bounces: u64) -> String {
    crate::cli::ok(&[
        "orbit",
        "--table",
        "sine",
        "--alpha",
        &alpha.to_string(),
        "--t0",
        &t0.to_string(),
        "--v0",
        &v0.to_string(),
        "--bounces",
        &bounces.to_string(),
        "--format",
        "csv",
    ])
}

/// A cycle of the output ({n, k, phases, velocities}) is a cycle of the exact map of
/// the sine at α: `orbit` from its point returns after n events, k periods on.
fn is_cycle(x: &serde_json::Value, alpha: f64) {
    let (n, k) = (x["n"].as_u64().unwrap(), x["k"].as_u64().unwrap());
    let (t0, v0) = (
        x["phases"][0].as_f64().unwrap(),
        x["velocities"][0].as_f64().unwrap(),
    );
    let csv = sine_orbit(alpha, t0, v0, n);
    let last = csv.lines().last().unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| {
        let i = header.iter().position(|h| *h == name).unwrap();
        last.split(',').nth(i).unwrap().parse::<f64>().unwrap()
    };
    // Back at its launch k periods on (the start is at period 0).
    let back = col("period") + col("phase") - t0;
    assert!((back - k as f64).abs() < 1e-9, "{last}");
    assert!((col("v") - v0).abs() < 1e-9, "{last}");
}

/// One saddle: one multiplier outside the unit circle, one inside.
fn is_saddle(x: &serde_json::Value) {
    let m: Vec<f64> = x["multipliers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z[0].as_f64().unwrap().abs())
        .collect();
    assert!((m[0] > 1.0) != (m[1] > 1.0), "{m:?}");
}

#[test]
fn attractors_crises_locate_the_sines_jump_in_size_as_an_interior_crisis() {
    // After the sine's (1, 1) cascade (r = 0.8) the chaotic attractor grows abruptly
    // between α = 0.03175 and 0.03176: its launch velocities reach 2·10⁻³ lower, and
    // it goes on (guide: saddles, manifolds and crises).
    let crises = sine_crises("0.03174..0.03177", "4", "12x12");
    let c = crises
        .iter()
        .find(|c| c["seen"] == "jump")
        .expect("a jump in size");
    assert_eq!(c["located"], true, "{c}");
    let (lo, hi) = (c["lo"].as_f64().unwrap(), c["hi"].as_f64().unwrap());
    assert!(hi - lo <= 1e-6 && lo >= 0.03175 && hi <= 0.03176, "{c}");
    let before = c["jump"]["before"][0].as_f64().unwrap();
    // A second method: the orbit from the paper's start, 2·10⁵ impacts after 2·10⁴,
    // stays above the old attractor's lowest velocity (less its drift) 2·10⁻⁶ below
    // the bracket, and reaches 10⁻³ below it 2·10⁻⁶ above.
    let lowest = |alpha: f64| {
        let csv = sine_orbit(alpha, 0.25, 0.5, 220_000);
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let (i, v) = (
            header.iter().position(|h| *h == "index").unwrap(),
            header.iter().position(|h| *h == "v").unwrap(),
        );
        csv.lines()
            .skip(1)
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|f| f[i].parse::<u64>().unwrap() >= 20_000)
            .map(|f| f[v].parse::<f64>().unwrap())
            .fold(f64::INFINITY, f64::min)
    };
    assert!(lowest(lo - 2e-6) > before - 3e-4, "{c}");
    assert!(lowest(hi + 2e-6) < before - 1e-3, "{c}");
    // Named by a saddle of the map at the upper end, outside the attractor; the
    // tangency of the embedded saddle's unstable manifold with its stable manifold lies
    // within 10⁻⁷ of the bracket (an upper bound on the crisis).
    let s = &c["saddle"];
    is_cycle(s, hi);
    is_saddle(s);
    assert!(s["outside_by"].as_f64().unwrap() >= 1e-3, "{s}");
    let t = &s["tangency"];
    let cross = t["between"][1].as_f64().unwrap();
    assert!(cross >= lo && cross - hi < 1e-7, "{t}");
    is_cycle(&t["embedded"], lo);
}

#[test]
fn attractors_crises_locate_the_sines_crisis_and_name_a_saddle_cycle_of_the_map() {
    // The sine's two-band chaotic attractor after its (1, 1) cascade is destroyed near
    // α = 0.03179 (guide: saddles, manifolds and crises).
    let crises = sine_crises("0.03177..0.03181", "5", "20x20");
    let c = crises
        .iter()
        .find(|c| c["located"] == true)
        .expect("one located");
    let (lo, hi) = (c["lo"].as_f64().unwrap(), c["hi"].as_f64().unwrap());
    assert!(hi - lo <= 1e-6 && lo > 0.03177 && hi < 0.03181, "{c}");
    // Below the value where the continuation no longer saw it (the bracket moves down
    // where the continuation's last value was a long transient already).
    let between = c["between"].as_array().unwrap();
    assert!(hi <= between[1].as_f64().unwrap(), "{c}");
    // The saddle is one at the upper end.
    let s = &c["saddle"];
    is_cycle(s, hi);
    // Outside the attractor, and a saddle: one multiplier out, one in; the attractor
    // nears its stable manifold as α nears the crisis, closer than to the saddle.
    let outside = s["outside_by"].as_f64().unwrap();
    assert!(outside >= 1e-3);
    let touch: Vec<(f64, f64)> = s["to_stable_manifold"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    assert_eq!(touch.len(), 2, "{s}");
    assert!(touch[0].0 < touch[1].0 && touch[1].0 == lo, "{s}");
    assert!(touch[1].1 < touch[0].1 && touch[1].1 < outside, "{s}");
    is_saddle(s);
    // Chosen by a tangency: the embedded saddle's unstable manifold is apart from the
    // saddle's stable manifold at the lower end, no farther than the attractor's sample
    // (the manifold lies in the attractor), and first crosses it above the bracket.
    let t = &s["tangency"];
    let apart = t["apart"].as_f64().expect("apart");
    assert!(apart > 0.0 && apart <= touch[1].1 * 1.01, "{t}");
    let cross = [
        t["between"][0].as_f64().unwrap(),
        t["between"][1].as_f64().unwrap(),
    ];
    assert!(
        cross[0] >= hi && cross[1] > cross[0] && cross[1] - hi < 1e-5,
        "{t}"
    );
    // The embedded saddle is one at the lower end.
    is_cycle(&t["embedded"], lo);
    // Without --crises there is no such field; with --shard it is refused.
    let plain = crate::cli::json(&[
        "attractors",
        "--table",
        "sine",
        "--alpha",
        "0.03177..0.03181",
        "--steps",
        "2",
        "--grid",
        "6x6",
        "--format",
        "json",
    ]);
    assert!(plain.get("crises").is_none());
    let (code, _, err) = crate::cli::run(&[
        "attractors",
        "--table",
        "sine",
        "--alpha",
        "0.03177..0.03181",
        "--steps",
        "2",
        "--grid",
        "6x6",
        "--crises",
        "--shard",
        "1/2",
        "--out",
        "/dev/null",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--crises with --shard"), "{err}");
}
