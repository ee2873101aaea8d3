//! Property tests of the exact impact map over random tables, amplitudes, restitutions
//! and initial states.
//!
//! For every flight between two consecutive events the ball's height is recomputed here
//! from the launch state alone (z = f(t_i) + h + v τ − τ²/2) and compared with the table:
//! * dense sampling of the flight (uniform plus geometrically refined near both ends)
//!   never finds the ball below the table by more than 1e-12;
//! * at each impact the gap z − f vanishes to 1e-12.
//!
//! Random tables are C¹ periodic piecewise polynomials of degree up to 5 (cubic Hermite
//! pieces through random values and slopes, plus random bumps s²(s − L)² q(s) that keep
//! the Hermite data), plain cubic splines (the solver's fixed-size cubic path), the
//! paper's F_D with random D, and the sine.

use bouncemap_engine::{EventKind, Halt, ImpactMap, Solver, State, System, Table};
use proptest::prelude::*;

/// Polynomials in ascending powers, written out here (not the engine's) so the tables
/// are built independently of the code under test.
fn p_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

fn p_add(a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..a.len().max(b.len()))
        .map(|i| a.get(i).unwrap_or(&0.0) + b.get(i).unwrap_or(&0.0))
        .collect()
}

/// P(x + h), by Horner's scheme on polynomials: ((c_n)(x + h) + c_{n−1})(x + h) + …
fn p_shift(c: &[f64], h: f64) -> Vec<f64> {
    let mut out = vec![0.0];
    for &ci in c.iter().rev() {
        out = p_add(&p_mul(&out, &[h, 1.0]), &[ci]);
    }
    out
}

/// A random C¹ periodic piecewise polynomial, built through the checked constructor
/// (so the C¹ check of piecewise tables is exercised too).
fn random_table(knots: &[f64], values: &[f64], slopes: &[f64], bumps: &[(f64, f64)]) -> Table {
    let n = knots.len();
    let mut pieces = Vec::new();
    for i in 0..n {
        let a = knots[i];
        let b = if i + 1 < n { knots[i + 1] } else { 1.0 };
        let l = b - a;
        let (y0, y1) = (values[i], values[(i + 1) % n]);
        let (m0, m1) = (slopes[i], slopes[(i + 1) % n]);
        // Cubic Hermite in s = t̂ − a on [0, l].
        let c2 = (3.0 * (y1 - y0) / l - 2.0 * m0 - m1) / l;
        let c3 = (2.0 * (y0 - y1) / l + m0 + m1) / (l * l);
        let hermite = [y0, m0, c2, c3];
        // s²(s − l)²(p + q s) leaves values and slopes at both ends unchanged.
        let (p, q) = bumps[i];
        let sl = [-l, 1.0];
        let bump = p_mul(&p_mul(&[0.0, 0.0, 1.0], &p_mul(&sl, &sl)), &[p, q]);
        let local = p_add(&hermite, &bump);
        // Back to ascending powers of the phase: P(t̂ − a).
        let mut coeffs = p_shift(&local, -a);
        while coeffs.len() > 1 && *coeffs.last().unwrap() == 0.0 {
            coeffs.pop();
        }
        pieces.push((a, coeffs));
    }
    Table::piecewise("random", &pieces).expect("random table is C¹ by construction")
}

/// Random C¹ piecewise tables: degree 5 with `bumps`, plain cubic splines without.
fn piecewise_strategy(bumps: bool) -> impl Strategy<Value = Table> {
    let bump = if bumps { 1.0 } else { 0.0 };
    (1usize..=4)
        .prop_flat_map(move |n| {
            (
                proptest::collection::vec(0.05f64..0.95, n - 1),
                proptest::collection::vec(-1.0f64..1.0, n),
                proptest::collection::vec(-4.0f64..4.0, n),
                proptest::collection::vec(
                    (-200.0f64..200.0, -400.0f64..400.0)
                        .prop_map(move |(p, q)| (bump * p, bump * q)),
                    n,
                ),
            )
        })
        .prop_filter_map("knots too close", |(mut inner, values, slopes, bumps)| {
            inner.sort_by(|a, b| a.partial_cmp(b).unwrap());
            let mut knots = vec![0.0];
            knots.extend(inner);
            let ok =
                knots.windows(2).all(|w| w[1] - w[0] > 0.02) && 1.0 - knots.last().unwrap() > 0.02;
            ok.then(|| random_table(&knots, &values, &slopes, &bumps))
        })
}

fn table_strategy() -> impl Strategy<Value = Table> {
    prop_oneof![
        2 => piecewise_strategy(true),
        1 => piecewise_strategy(false),
        2 => (0.0f64..=1.0).prop_map(|d| Table::fd(d).unwrap()),
        1 => Just(Table::sine()),
    ]
}

/// Exact sum of two f64s as (rounded sum, error).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Height of the ball above the table at (period, phase), launched at `from`.
/// Evaluated in double-double so that long flights (v τ ≫ 1) add no rounding of their own.
fn gap(sys: &System, from: &State, period: i64, phase: f64) -> f64 {
    // τ = Δperiod + phase − phase0, exactly as (t, tl).
    let (d, de) = two_sum(phase, -from.phase());
    let (t0, te) = two_sum((period - from.period()) as f64, d);
    let (t, tl) = two_sum(t0, te + de);
    let vt = from.v() * t;
    let vt_err = from.v().mul_add(t, -vt) + from.v() * tl;
    let half_t2 = 0.5 * t * t;
    let half_t2_err = (0.5 * t).mul_add(t, -half_t2) + t * tl;
    let terms = [
        sys.f(from.phase()),
        from.height(),
        vt,
        -half_t2,
        -sys.f(phase),
    ];
    let (mut s, mut err) = (0.0, vt_err - half_t2_err);
    for x in terms {
        let (ns, e) = two_sum(s, x);
        s = ns;
        err += e;
    }
    s + err
}

fn sample_flight(sys: &System, from: &State, tau_end: f64) -> Result<(), String> {
    let mut taus: Vec<f64> = (1..200).map(|i| tau_end * i as f64 / 200.0).collect();
    for k in 1..40 {
        let h = tau_end * 0.5f64.powi(k);
        taus.push(h);
        taus.push(tau_end - h);
    }
    for tau in taus {
        if !(tau > 0.0 && tau < tau_end) {
            continue;
        }
        let t = from.phase() + tau;
        let (period, phase) = (from.period() + t.floor() as i64, t - t.floor());
        let g = gap(sys, from, period, phase);
        if g < -1e-12 {
            return Err(format!(
                "ball below the table by {g:e} at τ = {tau} of a flight of {tau_end} from {from:?}"
            ));
        }
    }
    Ok(())
}

fn check_orbit(sys: System, t0: f64, hop: f64, z0: f64, events: usize) -> Result<(), String> {
    let v0 = sys.df(t0) + hop;
    let start = State::launch(&sys, 0, t0, v0, z0).map_err(|e| e.to_string())?;
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    for _ in 0..events {
        let from = *map.state();
        let e = match map.step() {
            Ok(e) => e,
            Err(Halt::Resting { .. }) => return Ok(()),
            Err(h @ (Halt::NoLanding { .. } | Halt::TimeOutOfRange { .. })) => {
                return Err(format!("{h}"))
            }
        };
        if !(e.phase.is_finite() && e.v.is_finite() && (0.0..1.0).contains(&e.phase)) {
            return Err(format!("bad event {e:?}"));
        }
        let tau = (e.period - from.period()) as f64 + (e.phase - from.phase());
        if tau < 0.0 {
            return Err(format!("time went backwards: {from:?} -> {e:?}"));
        }
        if e.kind == EventKind::Impact {
            let g = gap(&sys, &from, e.period, e.phase);
            if g.abs() > 1e-12 {
                return Err(format!("impact gap {g:e} at {e:?} from {from:?}"));
            }
        }
        // Flights follow impacts and releases; after a stick the ball rides the table.
        if from.mode() == bouncemap_engine::Mode::Flying && e.kind != EventKind::Stick {
            sample_flight(&sys, &from, tau)?;
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        // BOUNCEMAP_PROPTEST_CASES=40000 for a deeper search.
        cases: std::env::var("BOUNCEMAP_PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(2500),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn impacts_solve_the_gap_and_the_ball_never_goes_below_the_table(
        table in table_strategy(),
        alpha in 0.02f64..1.5,
        r in 0.05f64..0.97,
        t0 in 0.0f64..1.0,
        hop in 0.0f64..2.0,
        z0 in prop_oneof![Just(0.0), 0.0f64..1.0],
    ) {
        let t0 = if t0 >= 1.0 { 0.0 } else { t0 };
        let sys = System::new(table, alpha, r).unwrap();
        check_orbit(sys, t0, hop, z0, 60).map_err(TestCaseError::fail)?;
    }
}
