//! The `fixed`, `two-cycle` and `scaling` commands as a user runs them: json fields,
//! closed-form values through the binary, and bad input (one line, exit status 2).

use crate::cli::{json, run};

#[test]
fn fixed_quad_alpha_pd_through_the_binary() {
    for r in ["0.2", "0.5", "0.8"] {
        let v = json(&[
            "fixed", "--table", "quad", "--alpha", "0.3", "--r", r, "--format", "json",
        ]);
        let r: f64 = r.parse().unwrap();
        let want = (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
        assert!((v["alpha_pd"].as_f64().unwrap() - want).abs() < 1e-12);
        assert!((v["kappa_c"].as_f64().unwrap() + 2.0 * want).abs() < 1e-15);
    }
}

#[test]
fn fixed_json_lists_solutions() {
    let v = json(&[
        "fixed", "--table", "fd:0.1", "--alpha", "0.45", "--r", "0.8", "--format", "json",
    ]);
    let sols = v["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 2);
    assert_eq!(sols[0]["classification"], "stable");
    assert_eq!(sols[1]["classification"], "unstable_saddle");
    assert_eq!(sols[0]["eigenvalues"].as_array().unwrap().len(), 2);
    assert_eq!(v["windows"][0]["end"], "period_doubling");
}

#[test]
fn two_cycle_reports_none_for_quad_and_a_solution_for_cubic() {
    let v = json(&[
        "two-cycle",
        "--table",
        "quad",
        "--alpha",
        "0.6",
        "--r",
        "0.8",
        "--format",
        "json",
    ]);
    assert_eq!(v["found"], false);
    assert_eq!(v["reason"]["code"], "locally_quadratic");
    assert!(v["two_cycle"].is_null());
    let v = json(&[
        "two-cycle",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.5102",
        "--r",
        "0.8",
        "--format",
        "json",
    ]);
    assert_eq!(v["found"], true);
    let tc = &v["two_cycle"];
    assert_eq!(tc["stable"], true);
    assert!(tc["map_check"]["distance"].as_f64().unwrap() < 1e-11);
    assert!(
        tc["approximation"]["rel_err_delta_t"]
            .as_f64()
            .unwrap()
            .abs()
            < 0.01
    );
    assert!(v["border_collision"]["alpha"].as_f64().unwrap() > 0.51);
}

#[test]
fn bad_input_is_one_line_with_status_2() {
    for args in [
        vec!["fixed", "--k", "0"],
        vec!["fixed", "--k", "x"],
        vec!["fixed", "--r", "1"],
        vec!["two-cycle", "--alpha", "-1"],
        vec!["fixed", "--table", "fd:3"],
        vec!["scaling", "--d", "0"],
        vec!["scaling", "--d", "0.1..0.01"],
        vec!["scaling", "--d", "0.01..0.1:1"],
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
    }
}
