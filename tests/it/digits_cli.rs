//! `orbit --digits`: the settled (1, 1) orbit against its closed form to 60 digits
//! (computed here at 80 digits by the quadratic formula), the decimal parameters against
//! the doubles nearest them, the f64 orbit's digits, what is not printed when the
//! precision runs out, and bad input.

use bouncemap_engine::{bits_for_digits, Big, Number, Real};
use std::process::{Command, Output};

fn bouncemap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .output()
        .unwrap()
}

/// The csv rows (index, period, phase, v, vrel, kind, digits).
fn rows(out: &Output) -> Vec<Vec<String>> {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("index,period,phase,v,vrel,kind,digits"));
    lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

/// The rows of an `orbit --format csv` in double precision (no `digits` column).
fn f64_rows(args: &[&str]) -> Vec<Vec<String>> {
    let out = bouncemap(args);
    assert!(out.status.success());
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

/// `orbit` with `args` (csv) in double precision and at 25 digits with the doubles
/// (`--binary-params`): `events` events each, the same periods and kinds, each event
/// held to the 25 digits asked for, and phases and velocities within 1e-12 (the f64
/// map's error over a few events).
fn holds_to_f64(args: &[&str], events: usize) {
    let f64_rows = f64_rows(args);
    let big = rows(&bouncemap(
        &[args, &["--digits", "25", "--binary-params"]].concat(),
    ));
    assert_eq!((f64_rows.len(), big.len()), (events, events), "{args:?}");
    for (a, b) in f64_rows.iter().zip(&big) {
        assert_eq!((&a[1], &a[5]), (&b[1], &b[5]), "{args:?}: {a:?} vs {b:?}");
        assert_eq!(b[6], "25", "{args:?}: {b:?}");
        for k in [2, 3] {
            let (x, y): (f64, f64) = (a[k].parse().unwrap(), b[k].parse().unwrap());
            assert!((x - y).abs() < 1e-12, "{args:?}: {a:?} vs {b:?}");
        }
    }
}

/// The significant digits on which two decimal texts agree.
fn same_digits(a: &str, b: &str) -> usize {
    let digits = |s: &str| -> String {
        s.trim_start_matches('-')
            .chars()
            .filter(char::is_ascii_digit)
            .skip_while(|&c| c == '0')
            .collect()
    };
    digits(a)
        .chars()
        .zip(digits(b).chars())
        .take_while(|(x, y)| x == y)
        .count()
}

/// The stable (1, 1) solution of F_D (D = 0.1, α = 0.45, r = 0.8): on the first piece
/// αF' = (1 − r)/(2(1 + r)) with F' = 3D t² − (2 + D) t + ½, the smaller root, and the
/// launch velocity f'(t*) + r/(1 + r) = ½. At 80 digits.
fn closed_form() -> (Big, Big) {
    let bits = bits_for_digits(80);
    let n = |s: &str| Big::from_decimal(s, &bits).unwrap();
    let (d, alpha, r) = (n("0.1"), n("0.45"), n("0.8"));
    let c = (n("1") - r.clone()) / (n("2") * (n("1") + r.clone())) / alpha;
    let (a, b, cc) = (n("3") * d.clone(), -(n("2") + d), n("0.5") - c);
    let disc = (b.clone() * b.clone() - n("4") * a.clone() * cc).sqrt();
    let t = (-b - disc) / (n("2") * a);
    (t, n("0.5"))
}

/// Started off it, the orbit settles on the (1, 1) solution (contracting by at most
/// 0.94 per impact): after 3000 impacts its phase and velocity are the closed form's to
/// the 60 digits asked for, and the output says each holds to 60.
#[test]
fn the_settled_one_one_orbit_is_the_closed_form_to_sixty_digits() {
    let out = rows(&bouncemap(&[
        "orbit",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45",
        "--r",
        "0.8",
        "--digits",
        "60",
        "--skip",
        "3000",
        "--bounces",
        "2",
        "--format",
        "csv",
    ]));
    let (t, v) = closed_form();
    let bits = bits_for_digits(80);
    let off = |text: &str, want: &Big| {
        let x = Big::from_decimal(text, &bits).unwrap();
        ((x - want.clone()) / want.clone()).abs().to_f64()
    };
    for row in &out {
        assert_eq!(row[6], "60", "{row:?}");
        assert!(off(&row[2], &t) < 1e-59, "{} vs {t:?}", row[2]);
        assert!(off(&row[3], &v) < 1e-59, "{} vs {v:?}", row[3]);
    }
}

/// The f64 orbit's printed digits are the start of the decimal run's, and the doubles
/// nearest 0.45 and 0.8 (--binary-params) make a system whose fixed point differs from
/// the decimals' one after about 16 digits, as a change of 10⁻¹⁷ in α must.
#[test]
fn decimals_and_doubles_part_where_double_precision_ends() {
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "orbit",
            "--table",
            "fd:0.1",
            "--alpha",
            "0.45",
            "--r",
            "0.8",
            "--skip",
            "3000",
            "--bounces",
            "1",
            "--format",
            "csv",
        ];
        a.extend_from_slice(extra);
        a
    };
    let f64_row = bouncemap(&args(&[]));
    let f64_text = String::from_utf8(f64_row.stdout).unwrap();
    let f64_phase = f64_text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .nth(2)
        .unwrap()
        .to_string();
    let decimal = rows(&bouncemap(&args(&["--digits", "40"])));
    let binary = rows(&bouncemap(&args(&["--digits", "40", "--binary-params"])));
    assert!(same_digits(&f64_phase, &decimal[0][2]) >= 14);
    let parted = same_digits(&decimal[0][2], &binary[0][2]);
    assert!(
        (14..=19).contains(&parted),
        "{parted}: {} vs {}",
        decimal[0][2],
        binary[0][2]
    );
    assert_eq!(
        (&decimal[0][6], &binary[0][6]),
        (&"40".to_string(), &"40".to_string())
    );
}

/// A sticking orbit loses about half a digit per event: asked for 2000 events to 30
/// digits within 100 digits of working precision, the output stops where they stop
/// holding, says so, and says how many digits all would need.
#[test]
fn what_does_not_hold_is_not_printed_and_the_need_is_stated() {
    let out = bouncemap(&[
        "orbit",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.6",
        "--digits",
        "30",
        "--max-digits",
        "100",
        "--bounces",
        "2000",
        "--format",
        "csv",
    ]);
    let printed = rows(&out);
    assert!(
        printed.len() > 20 && printed.len() < 2000,
        "{}",
        printed.len()
    );
    assert!(printed.iter().all(|r| r[6] == "30"));
    let note = String::from_utf8_lossy(&out.stderr);
    assert!(
        note.contains(&format!(
            "events from index {} on do not hold to 30 digits",
            printed.len()
        )) && note.contains("need about"),
        "{note}"
    );
}

#[test]
fn bad_digits_get_one_line_and_status_two() {
    for (args, says) in [
        (
            &["--digits", "0"][..],
            "valid a whole number in [10, 10000]",
        ),
        (
            &["--digits", "20000"][..],
            "valid a whole number in [10, 10000]",
        ),
        (&["--digits", "1.5"][..], "whole number"),
        (
            &["--digits", "60", "--max-digits", "30"][..],
            "valid --max-digits M with M ≥ N",
        ),
        (&["--binary-params"][..], "go with --digits N"),
        (
            &["--digits", "30", "--solver", "grid"][..],
            "valid --solver exact",
        ),
    ] {
        let mut all = vec!["orbit"];
        all.extend_from_slice(args);
        let out = bouncemap(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// The csv header of `lyapunov --digits`: a sticking cycle's fields, then a cycle of
/// impacts'.
const LYAPUNOV_HEADER: &str = "table,alpha,r,parameters,digits,verdict,periods,releases,release_phase,stick_after,agreed_digits,need_digits,events,phase,v,multiplier1,multiplier2,complex,lambda1,lambda2,stability";

fn lyapunov_csv(args: &[&str]) -> Vec<String> {
    let mut all = vec!["lyapunov", "--r", "0.8", "--format", "csv"];
    all.extend_from_slice(args);
    let out = bouncemap(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(LYAPUNOV_HEADER));
    lines.next().unwrap().split(',').map(String::from).collect()
}

/// fd:1 at α = 0.59, where double precision cannot decide the sticking cycle: at 60
/// digits its length and stick time, the same to 60 digits when 90 are asked for, and a
/// different cycle for the doubles nearest 0.59 and 0.8, as a change of 10⁻¹⁷ in α must
/// make where about 45 digits are lost from the release to the stick.
#[test]
fn lyapunov_decides_the_sticking_cycle_past_double_precision() {
    let base = ["--table", "fd:1", "--alpha", "0.59"];
    let at = |extra: &[&str]| {
        let mut a = base.to_vec();
        a.extend_from_slice(extra);
        lyapunov_csv(&a)
    };
    let sixty = at(&["--digits", "60"]);
    let ninety = at(&["--digits", "90", "--max-digits", "1000"]);
    let binary = at(&["--digits", "60", "--binary-params"]);
    for row in [&sixty, &ninety, &binary] {
        assert_eq!(
            (row[5].as_str(), row[7].as_str()),
            ("found", "1"),
            "{row:?}"
        );
    }
    assert_eq!(sixty[10], "60");
    assert_eq!(ninety[10], "90");
    assert_eq!(sixty[6], ninety[6]);
    assert!(
        same_digits(&sixty[9], &ninety[9]) >= 59,
        "{} vs {}",
        sixty[9],
        ninety[9]
    );
    // The stick falls inside the cycle's last period.
    let stick: f64 = sixty[9].parse().unwrap();
    let periods: f64 = sixty[6].parse().unwrap();
    assert!(
        stick > periods - 1.0 && stick < periods,
        "{stick} in {periods}"
    );
    assert_ne!(sixty[6], binary[6], "the doubles' cycle");
    // An independent computation (mpmath at 300, 400 and 600 digits, the flights'
    // cubics solved by a separate root finder, chattering followed to w < 1e-120 and
    // closed by its leading order): L = 78, T = 77.94380773608558746178295054094203725668
    // 39440626322389480440 for the decimals; L = 142, T = 141.995697125926639158332668953
    // 021186801788857516804185921560 for the doubles.
    assert_eq!(sixty[6], "78");
    assert!(
        same_digits(
            &sixty[9],
            "77.9438077360855874617829505409420372566839440626322389480440"
        ) >= 59,
        "{}",
        sixty[9]
    );
    assert_eq!(binary[6], "142");
    assert!(
        same_digits(
            &binary[9],
            "141.995697125926639158332668953021186801788857516804185921560"
        ) >= 59,
        "{}",
        binary[9]
    );
}

/// Where the path from the release loses more digits than --max-digits allows, the
/// verdict says so (exit 0) instead of printing a cycle.
#[test]
fn an_undecided_cycle_is_said_to_be_undecided() {
    let args = [
        "--table",
        "fd:0.1",
        "--alpha",
        "0.6",
        "--digits",
        "30",
        "--max-digits",
        "60",
    ];
    let row = lyapunov_csv(&args);
    assert_eq!(row[5], "undecided", "{row:?}");
    assert!(row[6].is_empty() && row[9].is_empty(), "{row:?}");
    let out = bouncemap(&[&["lyapunov"][..], &args].concat());
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("not decided within --max-digits 60"),
        "{text}"
    );
    assert!(!text.contains("sticking cycle of"), "{text}");
}

/// fd:0.1 at α = 0.6, the sticking cycle the f64 run calls beyond double precision by
/// the widest margin (a bound of 10^672 on the growth): decided at 280 and 560 digits,
/// and equal to an independent computation (mpmath at 300 and 400 digits: L = 394,
/// T = 393.746614487506653795854581821650255680023098582443769062757; for the doubles
/// nearest 0.1, 0.6 and 0.8, L = 112, T = 111.9256491383538609210920010739887099463079
/// 06701310845880452).
#[test]
fn the_widest_margin_cycle_is_decided_and_equals_an_independent_computation() {
    let base = ["--table", "fd:0.1", "--alpha", "0.6", "--digits", "60"];
    let decimal = lyapunov_csv(&base);
    let mut with_binary = base.to_vec();
    with_binary.push("--binary-params");
    let binary = lyapunov_csv(&with_binary);
    assert_eq!((decimal[5].as_str(), decimal[6].as_str()), ("found", "394"));
    assert!(
        same_digits(
            &decimal[9],
            "393.746614487506653795854581821650255680023098582443769062757"
        ) >= 59,
        "{}",
        decimal[9]
    );
    assert_eq!((binary[5].as_str(), binary[6].as_str()), ("found", "112"));
    assert!(
        same_digits(
            &binary[9],
            "111.925649138353860921092001073988709946307906701310845880452"
        ) >= 59,
        "{}",
        binary[9]
    );
}

/// The sine at α = 0.035 (sin and cos at the working precision): the sticking cycle
/// equals an independent computation (mpmath at 120, 200 and 300 digits, the gap in
/// closed form around each launch): released at t_r = 0.12878527316493914075764997846
/// 93460982239, sticking 41.71899945007246170547760624240714476808782440056 periods
/// later, L = 42.
#[test]
fn the_sines_sticking_cycle_equals_an_independent_computation() {
    let row = lyapunov_csv(&["--table", "sine", "--alpha", "0.035", "--digits", "30"]);
    assert_eq!(
        (row[5].as_str(), row[6].as_str()),
        ("found", "42"),
        "{row:?}"
    );
    assert!(
        same_digits(&row[8], "0.1287852731649391407576499784693460982239") >= 29,
        "{}",
        row[8]
    );
    assert!(
        same_digits(
            &row[9],
            "41.71899945007246170547760624240714476808782440056"
        ) >= 29,
        "{}",
        row[9]
    );
}

/// Where the two precisions part on the way to the stick, the verdict still states the
/// digits it needs, from the digits lost per event of the path, and the --max-digits
/// that reaches them; given that, the cycle is decided and is the independent
/// computation's (fd:0.1 at α = 0.6: L = 394, T = 393.74661448750665379585…).
#[test]
fn the_stated_need_is_measured_and_reaches_the_answer() {
    let base = ["--table", "fd:0.1", "--alpha", "0.6", "--digits", "20"];
    let short = lyapunov_csv(&[&base[..], &["--max-digits", "100"]].concat());
    assert_eq!(
        (short[5].as_str(), short[10].as_str()),
        ("undecided", "0"),
        "{short:?}"
    );
    let need: u32 = short[11].parse().unwrap_or_else(|_| panic!("{short:?}"));
    // More than the runs tried, and not absurdly more (the path loses ~0.2 digit an
    // event over ~1,000 events).
    assert!((120..1000).contains(&need), "{need}");
    let out = bouncemap(&[&["lyapunov"][..], &base, &["--max-digits", "100"]].concat());
    let text = String::from_utf8_lossy(&out.stdout);
    let suggested = text
        .split("(--max-digits ")
        .nth(1)
        .and_then(|t| t.split(')').next())
        .unwrap_or_else(|| panic!("{text}"))
        .to_string();
    let m: u32 = suggested.parse().unwrap();
    assert!(m >= need, "{m} < {need}");
    let decided = lyapunov_csv(&[&base[..], &["--max-digits", &suggested]].concat());
    assert_eq!(
        (decided[5].as_str(), decided[6].as_str()),
        ("found", "394"),
        "{decided:?}"
    );
    assert_eq!(decided[9], "393.7466144875066538");
}

/// A table file of degree 5 at any precision: the quintic kick's first events at 25
/// digits are the f64 map's to its error (the doubles nearest the file's decimals, as
/// `--binary-params` takes them), and agree to the 25 digits asked for.
#[test]
fn a_quintic_table_file_runs_at_any_precision() {
    let table = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/tables/quintic.toml");
    let base = [
        "orbit",
        "--table",
        table,
        "--alpha",
        "0.2",
        "--bounces",
        "3",
        "--format",
        "csv",
    ];
    holds_to_f64(&base, 3);
}

/// A start above the table (`--z0`) at any precision: the first landings of fd:0.1, the
/// sine and the quintic table file from 0.4 above the table are the f64 map's to its
/// error (with the doubles, `--binary-params`), and hold to the 25 digits asked for.
#[test]
fn a_start_above_the_table_runs_at_any_precision() {
    let quintic = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/tables/quintic.toml");
    for table in ["fd:0.1", "sine", quintic] {
        let base = [
            "orbit",
            "--table",
            table,
            "--alpha",
            "0.3",
            "--z0",
            "0.4",
            "--t0",
            "0.2",
            "--bounces",
            "2",
            "--format",
            "csv",
        ];
        holds_to_f64(&base, 2);
    }
}

/// A parameter typed with more digits than a double holds is read as written: α =
/// 0.59 + 10⁻²⁰ on fd:1 is another system than α = 0.59 (about 45 digits are lost
/// from the release to the stick, so a change in the 20th digit moves the stick: not
/// the 78-period cycle), the output names the α it used, and with `--binary-params`
/// it is the double both texts read to (the 142-period cycle of the doubles).
#[test]
fn a_parameter_with_more_digits_than_a_double_is_read_as_written() {
    let long = "0.59000000000000000001";
    let at = |alpha: &str, extra: &[&str]| {
        let mut a = vec!["--table", "fd:1", "--alpha", alpha, "--digits", "20"];
        a.extend_from_slice(extra);
        lyapunov_csv(&a)
    };
    let (short, typed) = (at("0.59", &[]), at(long, &[]));
    assert_eq!((short[5].as_str(), short[6].as_str()), ("found", "78"));
    assert_eq!(typed[1], long, "the α used, as typed");
    assert_eq!(typed[5], "found", "{typed:?}");
    assert_ne!(typed[6], "78", "{typed:?}");
    let (short_b, typed_b) = (
        at("0.59", &["--binary-params"]),
        at(long, &["--binary-params"]),
    );
    assert_eq!(typed_b[1], "0.59", "the double's shortest decimal");
    assert_eq!(
        (typed_b[6].as_str(), typed_b[9].as_str()),
        (short_b[6].as_str(), short_b[9].as_str())
    );
    assert_eq!(typed_b[6], "142");
}

/// ln 0.8 to 70 digits (ln 4 − ln 5), from an independent multiple-precision library.
const LN_08: &str = "-0.2231435513142097557662950903098345033746010855480072136712878724873917";

/// Next to the cubic table's period doubling at α ≈ 0.559466561328 the (2, 2) cycle's
/// multiplier is −1 + 2·10⁻⁹: the f64 orbit converges too slowly to settle (unsettled,
/// its QR exponent −4·10⁻⁵ ± 10⁻⁵). `lyapunov --digits 30` solves the cycle by Newton's
/// method at two precisions and prints it to 30 digits; every value holds the
/// identities of the map: μ₁μ₂ = det M = r⁴, λᵢ = ln|μᵢ|/2 per impact, λ₁ + λ₂ = 2 ln r
/// (ln 0.8 from an independent library), and asked for 50 digits it is the same to 30.
#[test]
fn lyapunov_solves_a_cycle_of_impacts_double_precision_cannot_settle() {
    let base = ["--table", "cubic", "--alpha", "0.5594665613"];
    let f64_run = bouncemap(&[&["lyapunov"], &base[..]].concat());
    let text = String::from_utf8(f64_run.stdout).unwrap();
    assert!(text.contains("orbit: unsettled"), "{text}");
    let at = |digits: &str| {
        let mut a = base.to_vec();
        a.extend_from_slice(&["--digits", digits]);
        lyapunov_csv(&a)
    };
    let (row, fifty) = (at("30"), at("50"));
    let field = |r: &[String], name: &str| {
        let i = LYAPUNOV_HEADER.split(',').position(|h| h == name).unwrap();
        r[i].clone()
    };
    for (name, want) in [
        ("verdict", "periodic"),
        ("events", "2"),
        ("periods", "2"),
        ("agreed_digits", "30"),
        ("complex", "false"),
        ("stability", "stable"),
    ] {
        assert_eq!(field(&row, name), want, "{name}: {row:?}");
    }
    let bits = bits_for_digits(60);
    let big = |s: &str| Big::from_decimal(s, &bits).unwrap();
    let digits = |a: &Big, b: &Big| bouncemap_engine::agreeing_digits(a, b, 60);
    let (m1, m2) = (
        big(&field(&row, "multiplier1")),
        big(&field(&row, "multiplier2")),
    );
    let (l1, l2) = (big(&field(&row, "lambda1")), big(&field(&row, "lambda2")));
    let r4 = big("0.4096");
    assert!(digits(&(m1.clone() * m2.clone()), &r4) >= 29);
    let two_ln_r = big("2") * big(LN_08);
    assert!(digits(&(l1.clone() + l2.clone()), &two_ln_r) >= 29);
    // λ₁ = ln|μ₁|/2 from μ₁'s 30 digits: |μ₁| − 1 ≈ 2·10⁻⁹ leaves about 21.
    assert!(digits(&(m1.abs().ln() / big("2")), &l1) >= 20);
    assert!(digits(&(m2.abs().ln() / big("2")), &l2) >= 29);
    assert!(m1.abs() < big("1") && m1.to_f64() > -1.0 + 1e-9);
    for name in ["phase", "v", "multiplier1", "lambda1"] {
        let (a, b) = (field(&row, name), field(&fifty, name));
        assert!(same_digits(&a, &b) >= 29, "{name}: {a} vs {b}");
    }
}

/// The table's parameter is read as written too: F_D at D = 1 − 10⁻²¹ is another system
/// than D = 1 (the double it rounds to), whose sticking cycle at α = 0.59 (about 45
/// digits lost from the release to the stick) is not the 78-period one; the output
/// names the table as typed, and --binary-params gives D = 1's cycle. A D typed just
/// above 1, whose double is 1, is refused as written (one line, status 2).
#[test]
fn a_table_parameter_with_more_digits_than_a_double_is_read_as_written() {
    let long = "fd:0.999999999999999999999";
    let at = |table: &str, extra: &[&str]| {
        let mut a = vec!["--table", table, "--alpha", "0.59", "--digits", "20"];
        a.extend_from_slice(extra);
        lyapunov_csv(&a)
    };
    let (one, typed, binary) = (
        at("fd:1", &[]),
        at(long, &[]),
        at(long, &["--binary-params"]),
    );
    assert_eq!((one[5].as_str(), one[6].as_str()), ("found", "78"));
    assert_eq!(typed[0], long, "the table used, as typed");
    assert_eq!(typed[5], "found", "{typed:?}");
    assert_ne!(typed[6], "78", "{typed:?}");
    assert_eq!(binary[0], "fd:1", "the double's shortest decimal");
    assert_eq!(
        (binary[6].as_str(), binary[9].as_str()),
        ("142", at("fd:1", &["--binary-params"])[9].as_str())
    );
    let out = bouncemap(&[
        "lyapunov",
        "--table",
        "fd:1.000000000000000000001",
        "--alpha",
        "0.59",
        "--digits",
        "20",
    ]);
    crate::reliability::refused(&out, "D 1.000000000000000000001");
    assert!(String::from_utf8_lossy(&out.stderr).contains("[0, 1]"));
}

/// `lyapunov --digits` on the settled (1, 1) orbit of F_D (D = 0.1, α = 0.45, r = 0.8):
/// the cycle Newton's method solves at any precision is the closed form's t* and v* = ½
/// to the 40 digits printed, and its multipliers are the paper's A's: sum 1 + r² +
/// (1 + r)² f''(t*) with f'' = α(6D t* − (2 + D)) on the first piece, product r².
#[test]
fn lyapunov_digits_on_the_one_one_cycle_is_the_closed_form() {
    let row = lyapunov_csv(&[
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45",
        "--near-fixed-point",
        "--digits",
        "40",
    ]);
    let field = |name: &str| {
        let i = LYAPUNOV_HEADER.split(',').position(|h| h == name).unwrap();
        row[i].clone()
    };
    assert_eq!(
        (field("verdict").as_str(), field("events").as_str()),
        ("periodic", "1")
    );
    let (t, v) = closed_form();
    let bits = bits_for_digits(80);
    let big = |s: &str| Big::from_decimal(s, &bits).unwrap();
    let digits = |a: &Big, b: &Big| bouncemap_engine::agreeing_digits(a, b, 80);
    assert!(
        digits(&big(&field("phase")), &t) >= 39,
        "{} vs {t:?}",
        field("phase")
    );
    assert!(digits(&big(&field("v")), &v) >= 39, "{}", field("v"));
    let (alpha, d, r, one) = (big("0.45"), big("0.1"), big("0.8"), big("1"));
    let ddf = alpha * (big("6") * d.clone() * t - (big("2") + d));
    let tr =
        one.clone() + r.clone() * r.clone() + (one.clone() + r.clone()) * (one + r.clone()) * ddf;
    let (m1, m2) = (field("multiplier1"), field("multiplier2"));
    let (sum, product) = if field("complex") == "true" {
        // Real and imaginary parts.
        let (re, im) = (big(&m1), big(&m2));
        (big("2") * re.clone(), re.clone() * re + im.clone() * im)
    } else {
        let (a, b) = (big(&m1), big(&m2));
        (a.clone() + b.clone(), a * b)
    };
    assert!(digits(&sum, &tr) >= 38, "{sum:?} vs {tr:?}");
    assert!(digits(&product, &(r.clone() * r)) >= 38);
}
