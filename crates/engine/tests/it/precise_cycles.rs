//! Cycles of impacts at any precision (Newton's method with the tangent map at the
//! working precision) against the closed form of the (1, 1) solution and of its
//! Jacobian, the determinant identity det M = r²ⁿ, central differences of the map at
//! any precision (a second method for the monodromy), and the f64 cycle solver.

use super::any_precision::sine_one_one;
use bouncemap_engine::orbits::periodic::cycle;
use bouncemap_engine::table::Family;
use bouncemap_engine::{
    bits_for_digits, impact_cycle_to_digits, solve_cycle, Big, EventKind, ImpactCycleVerdict,
    ImpactMap, Multipliers, Number, PreciseMap, PreciseState, PreciseSystem, Real, Solver,
    Stability, State, System, Table,
};

/// ln 0.8 to 70 digits (ln 4 − ln 5), from an independent multiple-precision library.
const LN_08: &str = "-0.2231435513142097557662950903098345033746010855480072136712878724873917";

/// Where the f64 orbit from a launch at phase 0 settles on the cubic table at α, r = 0.8:
/// (phase, v) after 4000 events, and the (2, 2) cycle the f64 solver finds from there.
fn cubic_attractor(alpha: f64) -> bouncemap_engine::orbits::periodic::CyclePoint {
    let sys = System::new(Table::fd(1.0).unwrap(), alpha, 0.8).unwrap();
    let st = State::launch(&sys, 0, 0.0, sys.df(0.0) + 0.8, 0.0).unwrap();
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
    for _ in 0..4000 {
        map.step().unwrap();
    }
    let s = map.state();
    let c = cycle(&sys, 2, 2, s.phase(), s.v()).expect("the (2, 2) cycle");
    assert!(c.stable);
    c
}

/// F_D at the doubles `d` and `alpha`, and r = 0.8 read as the decimal (so that 2 ln r
/// is ln 0.8's).
fn fd_big(d: f64, alpha: f64, bits: usize) -> PreciseSystem<Big> {
    PreciseSystem::new(
        Family::fd()
            .pieces_in(&[Big::from_f64(d, &bits)], &bits)
            .unwrap(),
        Big::from_f64(alpha, &bits),
        Big::from_decimal("0.8", &bits).unwrap(),
        bits,
    )
    .unwrap()
}

/// The sine's (1, 1) solutions at 60 digits: t* = ±acos(y)/ω with y = (1 − r)/(2(1 + r)αω),
/// ω = 2π, v* = ½; the Jacobian there is the paper's A = [[1, 1 + r], [(1 + r) f'',
/// (1 + r)² f'' + r²]], f'' = −αω² sin ωt*, so the multipliers have sum tr A and
/// product r². Newton's method from the double nearest each solution, moved by 1e-9,
/// lands on them to 1e-55.
#[test]
fn newton_at_any_precision_finds_the_sines_one_one_solutions_and_their_multipliers() {
    let bits = bits_for_digits(64);
    let n = |s: &str| Big::from_decimal(s, &bits).unwrap();
    let (alpha, r, one) = (n("0.025"), n("0.8"), n("1"));
    let omega = n("2") * Big::pi(&bits);
    let sys = PreciseSystem::sine(alpha.clone(), r.clone(), bits);
    let mut kinds = Vec::new();
    for t in sine_one_one(&alpha, &r) {
        let guess = Big::from_f64(t.to_f64() + 1e-9, &bits);
        let c = solve_cycle(&sys, 1, 1, guess, n("0.5000000003"), &mut |_| {}).unwrap();
        assert!(
            (c.phase.clone() - t.clone()).abs().to_f64() < 1e-55,
            "{:?}",
            c.phase
        );
        assert!((c.v.clone() - n("0.5")).abs().to_f64() < 1e-55, "{:?}", c.v);
        let (s, _) = (omega.clone() * t.clone()).sin_cos();
        let ddf = -(alpha.clone() * omega.clone() * omega.clone() * s);
        let tr = one.clone()
            + (one.clone() + r.clone()) * (one.clone() + r.clone()) * ddf
            + r.clone() * r.clone();
        let (sum, product) = match &c.multipliers {
            Multipliers::Real([a, b]) => (a.clone() + b.clone(), a.clone() * b.clone()),
            Multipliers::Complex { re, im } => (
                n("2") * re.clone(),
                re.clone() * re.clone() + im.clone() * im.clone(),
            ),
        };
        assert!((sum - tr).abs().to_f64() < 1e-50);
        assert!((product - r.clone() * r.clone()).abs().to_f64() < 1e-50);
        kinds.push(matches!(c.multipliers, Multipliers::Complex { .. }));
    }
    // One node (its multipliers real, the one beyond the table's top: a saddle) and one
    // focus at this α.
    assert_eq!(kinds.iter().filter(|k| **k).count(), 1, "{kinds:?}");
}

/// The period-2 cycle of the cubic table (F_D, D = 1), r = 0.8, at α = 0.5 (a focus:
/// complex multipliers) and 0.559 (a node next to its period doubling: real ones), at 60
/// and at 300 digits: the exponents sum to 2 ln r (det M = r⁴) to the precision; the f64
/// cycle solver has the same launch, trace and determinant to 1e-10; and the monodromy
/// equals the central differences of the two-impact map at any precision (step 1e-30
/// at 300 digits: an error ~1e-60 times M's second derivatives).
#[test]
fn the_cubic_period_two_cycle_at_any_precision() {
    for (alpha, complex) in [(0.5, true), (0.559, false)] {
        let f = cubic_attractor(alpha);
        let (p0, v0) = (f.phases[0], f.velocities[0]);
        for digits in [60u32, 300] {
            let bits = bits_for_digits(digits);
            let sys = fd_big(1.0, alpha, bits);
            let c = solve_cycle(
                &sys,
                2,
                2,
                Big::from_f64(p0, &bits),
                Big::from_f64(v0, &bits),
                &mut |_| {},
            )
            .unwrap();
            let ln = Big::from_decimal(LN_08, &bits).unwrap();
            let sum = c.exponents[0].clone() + c.exponents[1].clone();
            let target = Big::from_f64(2.0, &bits) * ln;
            let tol = if digits == 60 { 1e-55 } else { 1e-65 };
            assert!((sum - target).abs().to_f64() < tol);
            assert!((c.phase.to_f64() - p0).abs() < 1e-10 && (c.v.to_f64() - v0).abs() < 1e-10);
            let (tr, det) = match &c.multipliers {
                Multipliers::Real([a, b]) => (a.clone() + b.clone(), a.clone() * b.clone()),
                Multipliers::Complex { re, im } => (
                    Big::from_f64(2.0, &bits) * re.clone(),
                    re.clone() * re.clone() + im.clone() * im.clone(),
                ),
            };
            assert_eq!(
                matches!(c.multipliers, Multipliers::Complex { .. }),
                complex
            );
            let m = f.monodromy;
            assert!((tr.to_f64() - (m[0][0] + m[1][1])).abs() < 1e-10);
            assert!((det.to_f64() - (m[0][0] * m[1][1] - m[0][1] * m[1][0])).abs() < 1e-10);
            if digits == 300 {
                // Central differences of the two-impact map.
                let h = Big::from_decimal("1e-30", &bits).unwrap();
                let two = |phase: Big, v: Big| {
                    let w = v - sys.jet(&phase)[1].clone();
                    let mut map =
                        PreciseMap::new(sys.clone(), PreciseState::launch(&sys, 0, phase, w));
                    let _ = map.step().unwrap();
                    let e = map.step().unwrap();
                    assert_eq!(e.kind, EventKind::Impact);
                    [Big::from_f64(e.period as f64, &bits) + e.phase, e.v]
                };
                let (p, v) = (c.phase.clone(), c.v.clone());
                let cols = [
                    (
                        two(p.clone() + h.clone(), v.clone()),
                        two(p.clone() - h.clone(), v.clone()),
                    ),
                    (
                        two(p.clone(), v.clone() + h.clone()),
                        two(p.clone(), v.clone() - h.clone()),
                    ),
                ];
                for (j, (plus, minus)) in cols.iter().enumerate() {
                    for i in 0..2 {
                        let d = (plus[i].clone() - minus[i].clone())
                            / (Big::from_f64(2.0, &bits) * h.clone());
                        let err = (d - c.monodromy[i][j].clone()).abs().to_f64();
                        assert!(err < 1e-50, "alpha {alpha}: M[{i}][{j}] off by {err:e}");
                    }
                }
            }
        }
    }
}

/// `impact_cycle_to_digits` on the same cycle: every value to the digits asked for, by
/// two precisions; the cycle stable (the f64 solver says so too, by far); the
/// determinant identity to the residual; and the exponents' sum 2 ln r to the digits.
#[test]
fn a_cycle_to_digits_holds_every_value_it_prints() {
    let make = |bits: usize| {
        let sys = fd_big(1.0, 0.559, bits);
        let st = PreciseState::launch(
            &sys,
            0,
            Big::from_f64(0.3, &bits),
            Big::from_f64(1.0, &bits),
        );
        (sys, st)
    };
    let f = cubic_attractor(0.559);
    let v = impact_cycle_to_digits(
        &make,
        2,
        2,
        (f.phases[0], f.velocities[0]),
        40,
        400,
        &mut |_| std::ops::ControlFlow::Continue(()),
    )
    .unwrap();
    let ImpactCycleVerdict::Found(c) = v else {
        panic!("{v:?}")
    };
    for a in c.values() {
        assert_eq!(a.digits, 40);
    }
    assert_eq!(c.stability, Stability::Stable);
    assert!(c.det_error.abs() < 1e-80, "{}", c.det_error);
    let bits = c.exponents[0].value.context();
    let sum = c.exponents[0].value.clone() + c.exponents[1].value.clone();
    let two_ln = Big::from_f64(2.0, &bits) * Big::from_decimal(LN_08, &bits).unwrap();
    assert!((sum - two_ln).abs().to_f64() < 1e-45);
}

/// The largest multiplier of the (n, k) cycle through the double launch `guess` on the
/// cubic table at α (decimal text), solved at 100 digits.
fn largest_multiplier(alpha: &str, n: usize, k: u32, guess: (f64, f64)) -> Big {
    let bits = bits_for_digits(100);
    let sys = PreciseSystem::new(
        Family::fd()
            .pieces_in(&[Big::from_f64(1.0, &bits)], &bits)
            .unwrap(),
        Big::from_decimal(alpha, &bits).unwrap(),
        Big::from_decimal("0.8", &bits).unwrap(),
        bits,
    )
    .unwrap();
    let c = solve_cycle(
        &sys,
        n,
        k,
        Big::from_f64(guess.0, &bits),
        Big::from_f64(guess.1, &bits),
        &mut |_| {},
    )
    .unwrap();
    match c.multipliers {
        Multipliers::Real([a, _]) => a,
        other => panic!("complex multipliers {other:?}"),
    }
}

/// Past a supercritical period doubling the new cycle's multiplier is 1 − 4δ + O(δ²)
/// where the old cycle's is −1 − δ (the flip normal form x ↦ −(1 + δ)x + ax³: its second
/// iterate has fixed points x² = δ/a with derivative 1 + 2δ − 6δ). On the cubic table
/// the (2, 2) cycle doubles near α = 0.5594665613; past it, at α_PD + ε for ε = 10⁻⁶,
/// 10⁻⁷, 10⁻⁸, the (4, 4) that the f64 orbit approaches, solved at 100 digits, has
/// (1 − μ₄)/(−1 − μ₂) → 4, the error falling with ε. Double precision cannot do this:
/// at ε = 10⁻⁸ the multipliers differ from ±1 by about 10⁻⁷ and the orbit converges
/// too slowly to settle.
#[test]
fn past_a_period_doubling_the_new_cycles_multiplier_follows_the_normal_form() {
    // α_PD by the secant method on μ₂ + 1 at 100 digits, from the f64 (2, 2).
    let sys64 = |a: f64| System::new(Table::fd(1.0).unwrap(), a, 0.8).unwrap();
    let two = cubic_attractor(0.559);
    let g = (two.phases[0], two.velocities[0]);
    let plus_one = |a: f64| largest_multiplier(&format!("{a}"), 2, 2, g).to_f64() + 1.0;
    let (mut a0, mut a1) = (0.5594, 0.5595);
    let (mut f0, mut f1) = (plus_one(a0), plus_one(a1));
    for _ in 0..30 {
        if f1 == f0 || (a1 - a0).abs() < 1e-15 {
            break;
        }
        let a2 = a1 - f1 * (a1 - a0) / (f1 - f0);
        (a0, f0) = (a1, f1);
        a1 = a2;
        f1 = plus_one(a1);
    }
    let pd = a1;
    assert!((pd - 0.5594665613).abs() < 1e-9, "{pd}");
    let mut errors = Vec::new();
    for eps in [1e-6, 1e-7, 1e-8] {
        let alpha = pd + eps;
        let text = format!("{alpha}");
        let sys = sys64(alpha);
        let st = State::launch(&sys, 0, g.0, g.1 + 1e-3, 0.0).unwrap();
        let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
        for _ in 0..20_000 {
            map.step().unwrap();
        }
        let s = map.state();
        let four = bouncemap_engine::cycles_near(&sys, s.phase(), s.v(), 8)
            .into_iter()
            .find(|c| c.n == 4)
            .expect("the (4, 4) next to the orbit");
        let mu4 = largest_multiplier(&text, 4, 4, (four.phases[0], four.velocities[0]));
        let mu2 = largest_multiplier(&text, 2, 2, g);
        let delta = -1.0 - mu2.to_f64();
        assert!(delta > 0.0, "past the doubling at eps {eps}");
        let ratio = (1.0 - mu4.to_f64()) / delta;
        errors.push((ratio - 4.0).abs());
    }
    // O(δ): ten times closer for ε ten times smaller.
    assert!(errors[2] < 1e-4, "{errors:?}");
    assert!(
        errors[0] > 5.0 * errors[1] && errors[1] > 5.0 * errors[2],
        "{errors:?}"
    );
}
