//! Lyapunov exponents, attractors and basins against independent references: the
//! eigenvalues of the paper's (1, k) Jacobian, the determinant identity (the two
//! exponents sum to 2 ln r), a second method for the largest exponent (two nearby
//! orbits, no Jacobian at all), the (1, 1) solution's closed form f'(t̂*) = ½(1 − r)/(1 + r)
//! solved by bisection on the table itself, and the paper's α_PD.

use bouncemap_engine::attractors::basins::{self, BasinSpec};
use bouncemap_engine::attractors::lyapunov::{log_moduli, Method, Spectrum};
use bouncemap_engine::attractors::{settle, Kind, Settle};
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::Executor;
use bouncemap_engine::orbits::fixed::fixed_points;
use bouncemap_engine::run::start::near_fixed_point;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{self, SweepSpec};
use bouncemap_engine::{ImpactMap, Solver, State, System, Table};

fn never(_: u64) -> bool {
    false
}

fn exponents(sys: &System, start: State, settle_with: &Settle) -> (Kind, Spectrum) {
    let (found, ..) = settle(sys, start, settle_with, 1, &mut never).unwrap();
    (found.kind, found.spectrum.unwrap())
}

const LONG: Settle = Settle {
    transient: 200_000,
    ..Settle::BASINS
};

/// On the (1, 1) orbit both exponents are ln|μ| for the eigenvalues μ of the paper's
/// A = [[1, 1 + r], [(1 + r) f'', (1 + r)² f'' + r²]]: complex (both ln r) at α = 0.45,
/// real and distinct near α_PD.
#[test]
fn the_fixed_points_exponents_are_the_logs_of_its_eigenvalues() {
    for alpha in [0.45, 0.5, 0.509] {
        let sys = System::new(Table::fd(0.1).unwrap(), alpha, 0.8).unwrap();
        let fp = fixed_points(&sys, 1)
            .unwrap()
            .into_iter()
            .find(|p| p.admissible && p.ddf < 0.0)
            .unwrap();
        // A from its closed form, its eigenvalues from the quadratic formula.
        let r = sys.r();
        let a = [
            [1.0, 1.0 + r],
            [(1.0 + r) * fp.ddf, (1.0 + r).powi(2) * fp.ddf + r * r],
        ];
        let (tr, det) = (a[0][0] + a[1][1], a[0][0] * a[1][1] - a[0][1] * a[1][0]);
        let disc = tr * tr / 4.0 - det;
        let want = if disc < 0.0 {
            [0.5 * det.ln(); 2]
        } else {
            let (m1, m2) = (tr / 2.0 + disc.sqrt(), tr / 2.0 - disc.sqrt());
            let (x, y) = (m1.abs().ln(), m2.abs().ln());
            [x.max(y), x.min(y)]
        };
        assert_eq!(
            log_moduli(&fp.eigenvalues).map(|x| (x * 1e6).round()),
            want.map(|x| (x * 1e6).round())
        );
        let start = near_fixed_point(&sys).unwrap();
        let (kind, spectrum) = exponents(&sys, start, &LONG);
        assert_eq!(kind, Kind::Periodic, "α = {alpha}");
        let Spectrum::Finite(e) = spectrum else {
            panic!("{spectrum:?}")
        };
        assert_eq!(e.method, Method::Cycle);
        for (i, (got, want)) in e.per_impact.iter().zip(want).enumerate() {
            assert!(
                (got - want).abs() < 1e-8,
                "α = {alpha}: λ{} = {got} vs ln|μ| = {want}",
                i + 1
            );
        }
    }
}

/// A chaotic orbit of the cubic table (between the cascade's end and the sticking
/// cycles of Fig. 3(e)): positive largest exponent, sum 2 ln r over 10⁵ impacts, and
/// the largest exponent agrees with the growth of the distance between two nearby
/// orbits (Benettin's method, which uses no Jacobian).
#[test]
fn a_chaotic_orbit_sums_to_two_ln_r_and_matches_two_nearby_orbits() {
    let sys = System::new(Table::fd(1.0).unwrap(), 0.5735, 0.8).unwrap();
    let start = near_fixed_point(&sys).unwrap();
    let settle_with = Settle {
        sample: 100_000,
        ..LONG
    };
    let (found, ..) = settle(&sys, start, &settle_with, 1, &mut never).unwrap();
    assert_eq!(found.kind, Kind::Chaotic, "{found:?}");
    let Some(Spectrum::Finite(e)) = found.spectrum else {
        panic!()
    };
    assert_eq!(e.impacts, 100_000);
    let two_ln_r = 2.0 * sys.r().ln();
    let sum = e.per_impact[0] + e.per_impact[1];
    assert!(
        (sum - two_ln_r).abs() < 1e-6,
        "{sum} vs 2 ln r = {two_ln_r}"
    );
    assert!(e.per_impact[0] > 0.05, "{e:?}");

    // Two orbits 1e-9 apart, the second put back at that distance along their
    // separation after every impact.
    let (phase, v) = found.point.unwrap();
    let a0 = State::launch(&sys, 0, phase, v, 0.0).unwrap();
    let d0 = 1e-9;
    let n = 100_000;
    let mut a = ImpactMap::new(sys.clone(), Solver::Exact, a0);
    let mut b = ImpactMap::new(
        sys.clone(),
        Solver::Exact,
        State::launch(&sys, 0, phase, v + d0, 0.0).unwrap(),
    );
    let mut total = 0.0;
    for _ in 0..n {
        let ea = a.step().unwrap();
        let eb = b.step().unwrap();
        let dt = (eb.period - ea.period) as f64 + (eb.phase - ea.phase);
        let dv = eb.v - ea.v;
        let d = dt.hypot(dv);
        total += (d / d0).ln();
        // Put b back at distance d0 from a along the separation.
        let sa = *a.state();
        let (pt, pv) = (dt / d * d0, dv / d * d0);
        let t = sa.phase() + pt;
        let (per, ph) = if t >= 1.0 {
            (sa.period() + 1, t - 1.0)
        } else if t < 0.0 {
            (sa.period() - 1, t + 1.0)
        } else {
            (sa.period(), t)
        };
        // b leaves the table at its own time with the relative velocity a has plus the
        // separation: stay above the table.
        let vb = (sa.v() + pv).max(sys.df(ph));
        b.set_state(State::launch(&sys, per, ph, vb, 0.0).unwrap());
    }
    let benettin = total / n as f64;
    assert!(
        (benettin - e.per_impact[0]).abs() < 0.01,
        "two nearby orbits give {benettin}, QR {}",
        e.per_impact[0]
    );
}

/// The cubic table at α = 0.47, r = 0.8: the stable (1, 1) solution (f'(t̂*) =
/// ½(1 − r)/(1 + r), v = ½) coexists with a sticking cycle.
#[test]
fn the_cubic_tables_basins_hold_the_fixed_point_and_a_sticking_cycle() {
    let sys = System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap();
    // t̂* by bisection on f'(t) = c on the rising side before the maximum, f'' < 0.
    let c = 0.5 * (1.0 - sys.r()) / (1.0 + sys.r());
    let (mut lo, mut hi) = (0.0, 0.25);
    assert!(sys.df(lo) > c && sys.df(hi) < c);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if sys.df(mid) > c {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    assert!((lo - 0.149665250704).abs() < 1e-9, "{lo}");
    let spec = BasinSpec {
        nx: 60,
        ny: 30,
        ..BasinSpec::new(sys.clone())
    };
    let b = basins::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    assert!(b.complete());
    let reg = b.registry();
    assert!(reg.attractors().len() >= 2, "{:?}", reg.attractors());
    let total: f64 = (0..reg.attractors().len()).map(|i| reg.fraction(i)).sum();
    assert!((total - 1.0).abs() < 1e-12);
    let p11 = reg
        .attractors()
        .iter()
        .find(|a| a.kind == Kind::Periodic && a.events == Some(1) && a.periods == Some(1))
        .expect("the (1, 1) solution");
    let (phase, v) = p11.point.unwrap();
    assert!((phase - lo).abs() < 1e-9, "{phase} vs {lo}");
    assert!((v - 0.5).abs() < 1e-9, "{v}");
    assert!(reg.attractors().iter().any(|a| a.kind == Kind::Sticking));
    // The default start (t̂0 = 0, a hop of ½) ends on the sticking cycle.
    let start = State::start(&sys, 0.0, None, 0.0).unwrap();
    let (found, ..) = settle(&sys, start, &Settle::BASINS, 1, &mut never).unwrap();
    assert_eq!(found.kind, Kind::Sticking);
    assert_eq!(found.lyapunov(), Some(f64::NEG_INFINITY));
}

/// Fig. 3(e)'s window: the largest exponent is negative on the (1, 1) and (2, 2)
/// branches, reaches zero at α_PD = 0.483834 (within one step; both branches have a
/// multiplier −1 there), and is positive in the chaotic band after the cascade.
#[test]
fn the_largest_exponent_along_fig3e_touches_zero_at_alpha_pd_and_is_positive_in_chaos() {
    let alpha_pd = 0.483834;
    let (lo, hi, steps) = (0.45, 0.55, 201);
    let step = (hi - lo) / (steps - 1) as f64;
    let mut spec = SweepSpec::new(
        Table::fd(1.0).unwrap(),
        0.45,
        0.8,
        SweepParam::Alpha,
        lo,
        hi,
        steps,
    );
    spec.initial.near_fixed_point = true;
    spec.transient = 200_000;
    spec.keep = 4;
    spec.lyapunov = true;
    let res = sweep::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    let lam: Vec<(f64, f64, Option<usize>)> = res
        .iter()
        .map(|r| (r.value, r.lyapunov.unwrap(), r.outcome.period()))
        .collect();
    for &(a, l, p) in &lam {
        if (a - alpha_pd).abs() > 2.0 * step && a < 0.545 {
            assert!(l < 0.0, "α = {a}: λ = {l} on the period-{p:?} branch");
            assert!(matches!(p, Some(1) | Some(2)), "α = {a}: period {p:?}");
        }
        assert!(l < 1e-3, "α = {a}: λ = {l}");
    }
    let (a_max, l_max, _) = lam
        .iter()
        .copied()
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap();
    assert!(
        (a_max - alpha_pd).abs() <= step,
        "largest λ {l_max} at α = {a_max}"
    );
    assert!(l_max > -0.05, "{l_max}");

    // The chaotic band after the cascade 4 → 8 → 16 → 32.
    let mut spec = spec.clone();
    spec.lo = 0.5725;
    spec.hi = 0.5735;
    spec.alpha = spec.lo;
    spec.steps = 5;
    let res = sweep::collect(&spec, &Executor::new(2).unwrap()).unwrap();
    let chaotic: Vec<f64> = res
        .iter()
        .filter(|r| r.outcome == Outcome::Unsettled)
        .map(|r| r.lyapunov.unwrap())
        .collect();
    assert!(chaotic.len() >= 3, "{res:?}");
    assert!(chaotic.iter().all(|&l| l > 0.02), "{chaotic:?}");
}
