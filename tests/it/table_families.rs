//! Table families as a user runs them: F_D written as a file with D declared gives
//! every output of the built-in fd:D to the last digit (orbits, fixed points, a plane,
//! the (1, 1) and (2, 2) curves); the shipped two-parameter family is F_0 where it
//! should be, sweeps, planes and curves run over its parameters, and its α_PD follows
//! the closed form where F'' is constant; a family that stops being C¹ inside a window
//! is refused at the first value that is not, and bad expressions name their column.

use crate::cli::run;

fn asset(name: &str) -> String {
    format!("{}/assets/tables/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// stdout of a successful run.
fn out(args: &[&str]) -> String {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// The output with the table's name replaced and the lines that hash it (the spec,
/// which states the name) dropped: what must agree between two names of one table.
fn numbers(text: &str, names: &[&str]) -> String {
    let mut t = text.to_string();
    for n in names {
        t = t.replace(n, "<table>");
    }
    t.lines()
        .filter(|l| !l.starts_with("# spec"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Run `args` with `--table` each of `tables`, and check the outputs agree but for the
/// table's names.
fn same_outputs(args: &[&str], tables: [(&str, &[&str]); 2]) {
    let texts: Vec<String> = tables
        .iter()
        .map(|(t, names)| {
            let mut a = args.to_vec();
            a.extend(["--table", t]);
            numbers(&out(&a), names)
        })
        .collect();
    assert!(texts[0].len() > 100, "{args:?}: {}", texts[0]);
    assert_eq!(texts[0], texts[1], "{args:?}");
}

#[test]
fn fd_written_as_a_file_is_the_builtin_to_the_last_digit() {
    let file = asset("fd_family.toml");
    for d in ["0", "0.1", "0.37", "1"] {
        let member = format!("{file}:D={d}");
        let builtin = format!("fd:{d}");
        let file_name = format!("F_D (as a file) (D = {d})");
        let tables: [(&str, &[&str]); 2] = [
            (&builtin, &[builtin.as_str()]),
            (&member, &[file_name.as_str()]),
        ];
        same_outputs(
            &[
                "orbit",
                "--alpha",
                "0.5",
                "--bounces",
                "400",
                "--format",
                "csv",
            ],
            tables,
        );
        same_outputs(&["fixed", "--alpha", "0.5", "--format", "json"], tables);
        same_outputs(
            &[
                "plane",
                "--x",
                "alpha:0.45..0.6",
                "--y",
                "r:0.5..0.9",
                "--size",
                "6x4",
            ],
            tables,
        );
    }
    // Over D itself: the family on an axis, and the (1, 1) and (2, 2) curves.
    let free: [(&str, &[&str]); 2] = [("fd", &["fd"]), (&file, &["F_D (as a file) (D)"])];
    same_outputs(
        &[
            "plane",
            "--x",
            "alpha:0.45..0.6",
            "--y",
            "D:0..1",
            "--size",
            "6x5",
        ],
        free,
    );
    for k in ["1", "2"] {
        same_outputs(
            &[
                "curves",
                "--x",
                "alpha:0.4..0.7",
                "--y",
                "D:0..1",
                "--max-period",
                "2",
                "--k",
                k,
                "--seeds",
                "1",
                "--format",
                "json",
            ],
            free,
        );
    }
}

#[test]
fn the_skewed_family_is_quad_at_its_middle_and_sweeps_over_both_parameters() {
    let file = asset("skewed.toml");
    let middle = format!("{file}:w=0.5,D=0");
    let name = "skewed wave (w = 0.5, D = 0)";
    same_outputs(
        &[
            "orbit",
            "--alpha",
            "0.55",
            "--bounces",
            "300",
            "--format",
            "csv",
        ],
        [("quad", &["fd:0"]), (&middle, &[name])],
    );
    // sweep --param over each parameter: the header names it, the values span its range
    // (the whole declared range by default).
    for (param, lo, hi) in [("w", "0.2", "0.8"), ("D", "0", "1")] {
        let text = out(&[
            "sweep",
            "--table",
            &file,
            "--param",
            param,
            "--alpha",
            "0.3",
            "--steps",
            "3",
            "--transient",
            "500",
            "--keep",
            "1",
        ]);
        let header = text.lines().find(|l| l.starts_with("index,")).unwrap();
        assert!(header.starts_with(&format!("index,{param},")), "{header}");
        let spec = text.lines().find(|l| l.starts_with("# spec ")).unwrap();
        assert!(
            spec.contains(&format!("\"lo\":{lo}")) || spec.contains(&format!("\"lo\":{lo}.0")),
            "{spec}"
        );
        assert!(spec.contains(&format!("\"param\":\"{param}\"")), "{spec}");
        let _ = hi;
    }
    // A plane over w runs, and names the family with w left free.
    let text = out(&[
        "plane",
        "--table",
        &file,
        "--x",
        "alpha:0.2..0.6",
        "--y",
        "w:0.2..0.8",
        "--size",
        "4x3",
    ]);
    assert!(
        text.contains("\"table\":\"skewed wave (w, D = 0)\""),
        "{text}"
    );
    assert!(text.contains("alpha,w,class"), "{text}");
}

/// With D = 0 the rising piece is the parabola s (w − s) for every w: F'' = −2 there,
/// so the (1, 1) solution doubles at the α_PD of F_0, (1 + r²)/(1 + r)², whatever w.
/// With D > 0 it does not: the family's own parameters are really used.
#[test]
fn the_skewed_family_doubles_where_the_closed_form_says() {
    let file = asset("skewed.toml");
    let r: f64 = 0.8;
    let closed = (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
    let pd = |table: &str| -> f64 {
        let text = out(&["fixed", "--table", table, "--alpha", "0.45", "--r", "0.8"]);
        let line = text
            .lines()
            .find(|l| l.starts_with("alpha_PD = "))
            .unwrap_or_else(|| panic!("{text}"));
        line["alpha_PD = ".len()..].trim().parse().unwrap()
    };
    for w in ["0.3", "0.45", "0.5", "0.7"] {
        let a = pd(&format!("{file}:w={w}"));
        assert!((a - closed).abs() < 1e-12, "w = {w}: {a} vs {closed}");
    }
    let sharpened = pd(&format!("{file}:w=0.5,D=0.5"));
    assert!((sharpened - closed).abs() > 1e-3, "{sharpened}");
    // The curves over D start from that closed form at D = 0 (breakpoints do not move
    // with D); over w they are refused, the breakpoint moving with it.
    let v: serde_json::Value = serde_json::from_str(&out(&[
        "curves",
        "--table",
        &format!("{file}:w=0.4"),
        "--x",
        "alpha:0.2..0.7",
        "--y",
        "D:0..1",
        "--max-period",
        "1",
        "--seeds",
        "1",
        "--format",
        "json",
    ]))
    .unwrap();
    let pd_curve = v["curves"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["kind"] == "period_doubling" && c["n"] == 1)
        .expect("the (1, 1) PD curve");
    let at_zero = pd_curve["points"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["D"] == 0.0)
        .expect("a point at D = 0");
    let a = at_zero["alpha"].as_f64().unwrap();
    assert!((a - closed).abs() < 1e-9, "{a} vs {closed}");
    let (code, _, err) = run(&[
        "curves",
        "--table",
        &file,
        "--x",
        "alpha:0.2..0.7",
        "--y",
        "w:0.2..0.8",
    ]);
    assert_eq!(code, 2);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("moves with w"), "{err}");
}

/// `text` written to a file of its own scratch directory: its path.
fn tmp_file(name: &str, text: &str) -> String {
    let p = crate::scratch::dir("families", name).join(name);
    std::fs::write(&p, text).unwrap();
    crate::scratch::s(&p).to_string()
}

/// The skewed parabola with the wrong factor on its falling piece: C¹ only at w = ½.
const BROKEN: &str = r#"
name = "broken"
variable = "s"
[[param]]
name = "w"
default = 0.5
range = [0.3, 0.7]
[[piece]]
start = 0
coeffs = ["0", "w", "-1"]
[[piece]]
start = "w"
coeffs = ["0", "-(1 - w)", "1"]
"#;

#[test]
fn a_family_that_stops_being_c1_is_refused_at_the_first_value_that_is_not() {
    let file = tmp_file("broken.toml", BROKEN);
    // The default (w = ½) is C¹: the file loads and runs.
    out(&["fixed", "--table", &file, "--alpha", "0.45"]);
    // A sweep from ½ upward: refused at its second value, named.
    let (code, o, err) = run(&[
        "sweep",
        "--table",
        &file,
        "--param",
        "w:0.5..0.7",
        "--steps",
        "5",
        "--alpha",
        "0.45",
        "--transient",
        "100",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(o.is_empty());
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("at w = 0.55: not C¹ at breakpoint"), "{err}");
    // A plane over w: the same.
    let (code, _, err) = run(&[
        "plane",
        "--table",
        &file,
        "--x",
        "alpha:0.4..0.5",
        "--y",
        "w:0.5..0.7",
        "--size",
        "3x5",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("at w = 0.55: not C¹"), "{err}");
    // A value given with the table.
    let (code, _, err) = run(&["fixed", "--table", &format!("{file}:w=0.6")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("at w = 0.6: not C¹"), "{err}");
}

#[test]
fn bad_family_files_get_one_line_with_the_place() {
    for (text, want) in [
        (
            BROKEN.replace("\"-(1 - w)\"", "\"-(1 - w\""),
            "piece 2 coefficient 2: '-(1 - w' at column 2: this '(' is not closed",
        ),
        (
            BROKEN.replace("\"w\", \"-1\"", "\"v\", \"-1\""),
            "piece 1 coefficient 2: 'v' at column 1: unknown name 'v': valid the parameters w",
        ),
        (
            BROKEN.replace("range = [0.3, 0.7]", "range = [0.6, 0.7]"),
            "parameter 'w': default 0.5 lies outside its range [0.6, 0.7]",
        ),
        (
            BROKEN.replace("name = \"w\"", "name = \"r\""),
            "parameter 'r': the name is taken",
        ),
        (
            BROKEN.replace("default = 0.5", "default = 0.6"),
            "at w = 0.6: not C¹ at breakpoint t̂ = 0.6",
        ),
        (
            BROKEN.replace("variable = \"s\"", "variable = \"x\""),
            "variable = 'x': valid \"t\"",
        ),
    ] {
        let file = tmp_file("bad.toml", &text);
        let (code, o, err) = run(&["fixed", "--table", &file]);
        assert_eq!(code, 2, "{err}");
        assert!(o.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{err:?} lacks {want:?}");
    }
    // A value for a parameter the file does not declare.
    let file = tmp_file("ok.toml", BROKEN);
    let (code, _, err) = run(&["fixed", "--table", &format!("{file}:v=0.4")]);
    assert_eq!(code, 2);
    assert!(
        err.contains("has no parameter 'v': its parameters are w"),
        "{err}"
    );
}

/// The terminal application lists a file family's parameters below the table, edits
/// them (range-checked, the table rebuilt), and sweeps over them.
#[test]
fn the_parameter_panel_lists_and_edits_a_familys_parameters() {
    use bouncemap::tui::params::{ParamId, Params};
    use bouncemap_engine::jobs::grid::SweepParam;
    let mut p = Params::default();
    // F_D: its D is the row below the table.
    assert_eq!(p.rows()[1], ParamId::Family(0));
    assert_eq!(p.label(ParamId::Family(0)), "D");
    p.set_text(ParamId::Table, &asset("skewed.toml")).unwrap();
    let rows = p.rows();
    assert_eq!(
        &rows[..4],
        &[
            ParamId::Table,
            ParamId::Family(0),
            ParamId::Family(1),
            ParamId::Alpha
        ]
    );
    assert_eq!(p.label(ParamId::Family(0)), "w");
    assert_eq!(p.show(ParamId::Family(0)), "0.5");
    p.set_text(ParamId::Family(0), "0.3").unwrap();
    assert_eq!(p.table().param("w"), Some(0.3));
    assert_eq!(p.table().name(), "skewed wave (w = 0.3, D = 0)");
    // Out of range: refused naming the range, nothing changed.
    let e = p.set_text(ParamId::Family(1), "2").unwrap_err();
    assert!(e.contains("[0, 1]"), "{e}");
    assert_eq!(p.table().param("D"), Some(0.0));
    // A nudge moves by a tenth of the range.
    p.nudge(ParamId::Family(1), 1, false).unwrap();
    assert_eq!(p.table().param("D"), Some(0.1));
    // Sweeping w: its whole range, the table's value kept.
    p.set_text(ParamId::Sweep, "w").unwrap();
    assert_eq!(p.param, SweepParam::parse("w", &p.table()).unwrap());
    assert_eq!((p.lo, p.hi), (0.2, 0.8));
    // Back to the sine: no family rows, and the sweep falls back to α.
    p.set_text(ParamId::Table, "sine").unwrap();
    assert_eq!(p.rows()[1], ParamId::Alpha);
    assert_eq!(p.param, SweepParam::Alpha);
}
