//! Periodic orbits: (1, k) solutions, stability windows, (2, 2k) solutions, the
//! corrected approximation, border collisions and the scaling fits, checked against
//! closed forms, the impact map itself, finite differences and the paper's numbers.

use bouncemap_engine::eigenvalues_2x2;
use bouncemap_engine::orbits::fixed::{fixed_point_at, stable_by_band};
use bouncemap_engine::orbits::scaling::{exact_fits, log_spaced, PAPER_FIG4_FITS};
use bouncemap_engine::orbits::two_cycle::period_doubling_candidate;
use bouncemap_engine::orbits::*;
use bouncemap_engine::{kappa_c, ImpactMap, Solver, State, System, Table};
use std::f64::consts::PI;

fn slope(r: f64, k: u32) -> f64 {
    0.5 * k as f64 * (1.0 - r) / (1.0 + r)
}

/// α_PD of F_D from the quadratic α²(D² − 2D + 4) + 12 D c α − κ_c² = 0 (the paper's
/// Appendix C at Δκ = 0, re-derived by hand).
fn fd_alpha_pd(d: f64, r: f64, k: u32) -> f64 {
    let c = slope(r, k);
    let kc = kappa_c(r);
    let q = d * d - 2.0 * d + 4.0;
    (-6.0 * d * c + (36.0 * d * d * c * c + q * kc * kc).sqrt()) / q
}

#[test]
fn quad_alpha_pd_is_closed_form() {
    for r in [0.1, 0.3, 0.5, 0.8, 0.9, 0.99] {
        let w = stability_window(&Table::fd(0.0).unwrap(), r, 1)
            .unwrap()
            .unwrap();
        let want = (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
        assert_eq!(w.end, WindowEnd::PeriodDoubling);
        assert!(
            (w.alpha_end - want).abs() < 1e-12,
            "r = {r}: {} vs {want}",
            w.alpha_end
        );
        // Birth: the orbit appears at t̂ = 0 where F' = ½ is largest: α = 2c.
        assert!((w.alpha_birth - 2.0 * slope(r, 1)).abs() < 1e-12);
    }
}

#[test]
fn fd_alpha_pd_matches_appendix_c() {
    for d in [0.001, 0.01, 0.1, 0.3, 0.5, 0.77, 1.0] {
        for r in [0.5, 0.8, 0.95] {
            for k in [1, 2] {
                let t = Table::fd(d).unwrap();
                let want = fd_alpha_pd(d, r, k);
                // The solution is born at t̂ = 0 (F' = ½ largest) at α = 2c with
                // f'' = −(2 + D)α; if that is already below κ_c it is never stable.
                let birth = 2.0 * slope(r, k);
                if -(2.0 + d) * birth <= kappa_c(r) {
                    assert!(want < birth);
                    assert_eq!(stability_window(&t, r, k).unwrap(), None);
                    continue;
                }
                let w = stability_window(&t, r, k).unwrap().unwrap();
                assert_eq!(w.end, WindowEnd::PeriodDoubling, "D {d} r {r} k {k}");
                assert!(
                    (w.alpha_end - want).abs() < 1e-12,
                    "D {d} r {r} k {k}: {} vs {want}",
                    w.alpha_end
                );
            }
        }
    }
}

#[test]
fn sine_alpha_pd_is_closed_form() {
    for r in [0.3, 0.6, 0.8, 0.95] {
        for k in [1, 2, 3] {
            let kc = kappa_c(r);
            let c = slope(r, k);
            let want = ((kc / (4.0 * PI * PI)).powi(2) + (c / (2.0 * PI)).powi(2)).sqrt();
            let w = stability_window(&Table::sine(), r, k).unwrap().unwrap();
            assert!((w.alpha_end - want).abs() < 1e-12, "r {r} k {k}");
            assert!((w.alpha_birth - c / (2.0 * PI)).abs() < 1e-12);
        }
    }
}

/// The gap between ball and table along a flight, sampled on a fine grid: its minimum
/// over the open interval (0, flight).
fn min_gap(sys: &System, phase: f64, v: f64, flight: f64) -> f64 {
    let n = 20_000;
    let f0 = sys.f(phase);
    (1..n)
        .map(|i| {
            let tau = flight * i as f64 / n as f64;
            let z = f0 + v * tau - 0.5 * tau * tau;
            z - sys.f((phase + tau).rem_euclid(1.0))
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn fixed_points_are_fixed_by_the_map_and_classified_consistently() {
    let tables = [
        Table::sine(),
        Table::fd(0.0).unwrap(),
        Table::fd(0.3).unwrap(),
        Table::fd(1.0).unwrap(),
    ];
    let mut checked = 0;
    let mut inadmissible = 0;
    for table in &tables {
        let scale = if table.pieces().is_empty() { 0.05 } else { 1.0 };
        for ia in 1..=12 {
            let alpha = scale * 0.1 * ia as f64;
            for r in [0.3, 0.6, 0.85] {
                for k in 1..=3 {
                    let sys = System::new(table.clone(), alpha, r).unwrap();
                    for p in fixed_points(&sys, k).unwrap() {
                        checked += 1;
                        assert!((sys.df(p.phase) - slope(r, k)).abs() < 1e-12);
                        // det A = r².
                        let a = p.jacobian;
                        assert!((a[0][0] * a[1][1] - a[0][1] * a[1][0] - r * r).abs() < 1e-12);
                        if p.admissible {
                            assert_eq!(
                                p.classification == Classification::Stable,
                                stable_by_band(r, p.ddf),
                                "{table} α {alpha} r {r} k {k} {p:?}"
                            );
                            assert!(min_gap(&sys, p.phase, p.v, k as f64) > -1e-12);
                            // One step of the impact map returns to the solution.
                            let st = State::launch(&sys, 0, p.phase, p.v, 0.0).unwrap();
                            let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
                            let e = map.step().unwrap();
                            assert_eq!(e.period, k as i64);
                            assert!((e.phase - p.phase).abs() < 1e-10);
                            assert!((e.v - p.v).abs() < 1e-9);
                        } else {
                            inadmissible += 1;
                            assert_eq!(p.classification, Classification::NotAdmissible);
                            // The ball really meets the table before k periods.
                            assert!(
                                min_gap(&sys, p.phase, p.v, k as f64) < 0.0
                                    || p.flight.is_some_and(|f| f < k as f64)
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(checked > 200, "{checked}");
    assert!(
        inadmissible > 0,
        "the sample should contain inadmissible solutions"
    );
}

#[test]
fn classification_names_the_unstable_side() {
    let t = Table::fd(0.3).unwrap();
    let sys = System::new(t, 0.7, 0.8).unwrap();
    let pts = fixed_points(&sys, 1).unwrap();
    let pd = pts.iter().find(|p| p.ddf < 0.0).unwrap();
    assert!(pd.ddf < kappa_c(0.8));
    assert_eq!(pd.classification, Classification::UnstablePeriodDoubling);
    assert!(pd.eigenvalues[1].re < -1.0);
    let saddle = pts.iter().find(|p| p.ddf > 0.0).unwrap();
    assert_eq!(saddle.classification, Classification::UnstableSaddle);
    assert!(saddle.eigenvalues[0].re > 1.0);
}

fn cycle_at(d: f64, dk: f64) -> (System, TwoCycle) {
    let t = Table::fd(d).unwrap();
    let (alpha, _) = alpha_at_delta_kappa(&t, 0.8, 1, dk).unwrap().unwrap();
    let sys = System::new(t, alpha, 0.8).unwrap();
    let tc = two_cycle(&sys, 1).unwrap();
    (sys, tc)
}

#[test]
fn two_cycle_is_a_two_cycle_of_the_impact_map() {
    for (d, dk) in [(0.1, 1e-4), (0.5, 1e-3), (1.0, 1e-2), (0.01, 1e-6)] {
        let (sys, tc) = cycle_at(d, dk);
        assert!((tc.delta_kappa - dk).abs() < 1e-9 * dk.max(1e-6));
        assert!(tc.admissible && tc.residual < 1e-13);
        let st = State::launch(&sys, 0, tc.phase0, tc.v0, 0.0).unwrap();
        let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
        let e1 = map.step().unwrap();
        assert_eq!(e1.period, 1);
        assert!((e1.phase - tc.phase1).abs() < 1e-11, "D {d}");
        assert!((e1.v - tc.v1).abs() < 1e-10);
        let e2 = map.step().unwrap();
        assert_eq!(e2.period, 2);
        assert!((e2.phase - tc.phase0).abs() < 1e-11);
        assert!((e2.v - tc.v0).abs() < 1e-10);
        assert!(tc.delta_t > 0.0 && tc.phase0 < tc.fixed.phase && tc.fixed.phase < tc.phase1);
    }
}

#[test]
fn two_cycle_multipliers_match_finite_differences_of_the_map() {
    let (sys, tc) = cycle_at(0.5, 1e-2);
    let two_steps = |t: f64, v: f64| {
        let st = State::launch(&sys, 0, t, v, 0.0).unwrap();
        let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
        map.step().unwrap();
        let e = map.step().unwrap();
        (e.phase, e.v)
    };
    let h = 1e-6;
    let mut jac = [[0.0; 2]; 2];
    for (col, (dt, dv)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
        let p = two_steps(tc.phase0 + dt, tc.v0 + dv);
        let m = two_steps(tc.phase0 - dt, tc.v0 - dv);
        jac[0][col] = (p.0 - m.0) / (2.0 * h);
        jac[1][col] = (p.1 - m.1) / (2.0 * h);
    }
    let fd = eigenvalues_2x2(jac);
    for i in 0..2 {
        assert!(
            (fd[i].re - tc.multipliers[i].re).abs() < 1e-5,
            "{fd:?} {:?}",
            tc.multipliers
        );
        assert!((fd[i].im.abs() - tc.multipliers[i].im.abs()).abs() < 1e-5);
    }
}

#[test]
fn iterating_the_map_converges_to_a_stable_two_cycle() {
    let (sys, tc) = cycle_at(0.1, 1e-3);
    assert!(tc.stable);
    let (n, dist) = map_check(&sys, &tc, 1e-4, 100_000).unwrap();
    assert!(dist < 1e-11, "{dist} after {n}");
}

#[test]
fn corrected_approximation_error_vanishes_and_printed_one_does_not() {
    for d in [0.01, 0.1, 0.5] {
        let mut prev = f64::INFINITY;
        for dk in [1e-4, 1e-6, 1e-8] {
            let (_, tc) = cycle_at(d, dk);
            let c = tc.corrected.unwrap();
            let e_t = ((c.delta_t - tc.delta_t) / tc.delta_t).abs();
            let e_big = ((c.delta_big_t - tc.delta_big_t) / tc.delta_big_t).abs();
            let err = e_t.max(e_big);
            // The relative error falls about in proportion to Δκ.
            assert!(err < 0.05 * prev, "D {d} Δκ {dk}: {err} after {prev}");
            prev = err;
            // The printed ΔT misses a factor 2 (and Δt the −f'f'''/2 term).
            let p = tc.paper.unwrap();
            assert!(((p.delta_big_t - tc.delta_big_t) / tc.delta_big_t).abs() > 0.3);
        }
        assert!(prev < 1e-6, "D {d}: {prev}");
    }
}

#[test]
fn quad_table_has_no_two_cycle_at_the_crisis() {
    let t = Table::fd(0.0).unwrap();
    let pd = (1.0 + 0.64) / (1.8 * 1.8);
    for alpha in [pd * (1.0 + 1e-9), pd * 1.01, pd * 1.2] {
        let sys = System::new(t.clone(), alpha, 0.8).unwrap();
        match two_cycle(&sys, 1) {
            Err(NoTwoCycle::LocallyQuadratic { delta_kappa }) => assert!(delta_kappa > 0.0),
            other => panic!("α {alpha}: {other:?}"),
        }
    }
    assert_eq!(
        border_collision(&t, 0.8, 1),
        Err(NoBorderCollision::NoBranch)
    );
}

#[test]
fn no_two_cycle_before_period_doubling() {
    let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
    assert!(matches!(
        two_cycle(&sys, 1),
        Err(NoTwoCycle::BeforePeriodDoubling { .. })
    ));
    let fp = period_doubling_candidate(&sys, 1).unwrap();
    assert_eq!(fp.classification, Classification::Stable);
}

#[test]
fn border_collision_puts_an_impact_on_the_breakpoint() {
    let t = Table::fd(0.1).unwrap();
    let b = border_collision(&t, 0.8, 1).unwrap();
    assert_eq!(b.phase, 0.0);
    assert!(b.phase0.min(1.0 - b.phase0) < 1e-10, "{b:?}");
    assert!(b.alpha > b.alpha_pd);
    // Just before it the branch exists with its lower impact close above t̂ = 0 ...
    let before = System::new(t.clone(), b.alpha * (1.0 - 1e-6), 0.8).unwrap();
    let tc = two_cycle(&before, 1).unwrap();
    assert!(tc.phase0 > 0.0 && tc.phase0 < 1e-4, "{}", tc.phase0);
    assert!((tc.v0 - b.v0).abs() < 1e-3);
    // ... and just after it the branch has left the piece.
    let after = System::new(t, b.alpha * (1.0 + 1e-6), 0.8).unwrap();
    assert!(matches!(
        two_cycle(&after, 1),
        Err(NoTwoCycle::LeavesPiece { .. })
    ));
    assert!(matches!(
        border_collision(&Table::sine(), 0.8, 1),
        Err(NoBorderCollision::SmoothTable)
    ));
}

#[test]
fn exact_fits_reproduce_the_papers_fig4_for_d_001_and_01() {
    let dks = log_spaced(1e-9, 1e-7, 9);
    for &(d, a_big, b_big, a_small, b_small) in &PAPER_FIG4_FITS[1..] {
        let (ft, fs) = exact_fits(&Table::fd(d).unwrap(), 0.8, 1, &dks).unwrap();
        assert_eq!(ft.points, 9);
        assert!((ft.slope - 1.0).abs() < 0.01 && (fs.slope - 0.5).abs() < 0.01);
        assert!((ft.slope - a_big).abs() < 0.01 && (fs.slope - a_small).abs() < 0.01);
        assert!(
            (ft.intercept - b_big).abs() < 0.02,
            "D {d}: b_T {}",
            ft.intercept
        );
        assert!(
            (fs.intercept - b_small).abs() < 0.02,
            "D {d}: b_t {}",
            fs.intercept
        );
    }
}

#[test]
fn windows_never_panic_on_odd_input() {
    assert!(stability_windows(&Table::sine(), 1.5, 1).is_err());
    assert!(stability_windows(&Table::sine(), 0.5, 0).is_err());
    for r in [1e-9, 1e-3, 0.5, 0.999_999] {
        for d in [0.0, 1e-12, 1.0] {
            let _ = stability_windows(&Table::fd(d).unwrap(), r, 100).unwrap();
        }
    }
    let sys = System::new(Table::fd(0.2).unwrap(), 1000.0, 0.5).unwrap();
    let _ = fixed_points(&sys, 100).unwrap();
    let _ = two_cycle(&sys, 1);
    let fp = fixed_point_at(&sys, 1, 0.3);
    assert!(fp.eigenvalues[0].re.is_finite());
}

/// An impact held on a table piece ([`periodic::Hold`]): where its landing falls just
/// past the piece's end, f' and f'' are that piece's formula continued. Checked by
/// second methods: held on the piece the landing falls in, the pass is the map's own,
/// to the bit; held on the other, 10⁻⁶ past the breakpoint, its monodromy and α column
/// are the central differences of its own residual to 10⁻⁵ (the derivatives are the
/// held formula's, not the piece's it fell in; those of a landing on the continued
/// formula, which the map's own landing time matches to second order in the distance
/// past), and the launch velocity after the landing is the restitution law with the
/// continued formula's slope, written out here; and the held map is smooth across the
/// breakpoint: its residual's differences in t₀ agree on either side of the launch
/// where the landing crosses it, where the map's own jump with f''.
#[test]
fn a_held_impact_continues_its_piece_past_the_breakpoint() {
    use bouncemap_engine::orbits::periodic::{map_for, pass, pass_with, Hold};
    let t = Table::fd(0.5).unwrap();
    let (alpha, r) = (0.57, 0.8);
    let sys = System::new(t.clone(), alpha, r).unwrap();
    let mut map = map_for(&sys);
    let v0 = 1.2;
    // A launch whose first landing falls at phase ½ + δ (Newton's method on the landing
    // time in t₀, with ∂t₁/∂t₀ from the pass).
    let land_at = |target: f64, map: &mut ImpactMap| {
        let mut t0 = 0.1;
        for _ in 0..50 {
            let p = pass(map, t0, v0, 1, 1).unwrap();
            let miss = p.phases[0] - target;
            if miss.abs() < 1e-15 {
                break;
            }
            t0 -= miss / p.monodromy[0][0];
        }
        t0
    };
    let delta = 1e-6;
    let t0 = land_at(0.5 + delta, &mut map);
    let after = t.segment_index(0.5 + delta);
    let before = t.segment_index(0.5 - delta);
    assert_ne!(after, before);
    let own = pass(&mut map, t0, v0, 1, 1).unwrap();
    assert!((own.phases[0] - 0.5 - delta).abs() < 1e-12);
    let same = pass_with(
        &mut map,
        t0,
        v0,
        1,
        1,
        &[Hold {
            impact: 0,
            segment: after,
        }],
    )
    .unwrap();
    assert_eq!(same.residual, own.residual);
    assert_eq!(same.monodromy, own.monodromy);
    let hold = [Hold {
        impact: 0,
        segment: before,
    }];
    let held = pass_with(&mut map, t0, v0, 1, 1, &hold).unwrap();
    // The restitution law with the continued slope: v₁ = (1 + r) f'_held − r (v₀ − τ).
    let seg = t.segment(before);
    let tau = held.times[0];
    let slope = alpha * seg.jet(0.5 + delta)[1];
    let v1 = (1.0 + r) * slope - r * (v0 - tau);
    assert!(
        (held.velocities[0] - v1).abs() < 1e-12,
        "{} {v1}",
        held.velocities[0]
    );
    assert!(
        (held.velocities[0] - own.velocities[0]).abs() > 1e-6,
        "the slopes differ"
    );
    // Its derivatives: central differences of its own residual.
    let h = 1e-7;
    let res =
        |map: &mut ImpactMap, t: f64, v: f64| pass_with(map, t, v, 1, 1, &hold).unwrap().residual;
    for (col, (dt, dv)) in [(0, (h, 0.0)), (1, (0.0, h))] {
        let (p, m) = (
            res(&mut map, t0 + dt, v0 + dv),
            res(&mut map, t0 - dt, v0 - dv),
        );
        for row in 0..2 {
            // The residual is (t₁ − t₀ − k, v₁ − v₀): M − I by differences.
            let d = (p[row] - m[row]) / (2.0 * h) + if row == col { 1.0 } else { 0.0 };
            let want = held.monodromy[row][col];
            assert!(
                (d - want).abs() < 1e-6 * (1.0 + want.abs()),
                "M[{row}][{col}]: {d} against {want}"
            );
        }
    }
    let sys_at = |a: f64| System::new(t.clone(), a, r).unwrap();
    let (p, m) = (
        pass_with(&mut map_for(&sys_at(alpha + h)), t0, v0, 1, 1, &hold)
            .unwrap()
            .residual,
        pass_with(&mut map_for(&sys_at(alpha - h)), t0, v0, 1, 1, &hold)
            .unwrap()
            .residual,
    );
    for row in 0..2 {
        let d = (p[row] - m[row]) / (2.0 * h);
        let want = held.alpha_column[row];
        assert!(
            (d - want).abs() < 1e-6 * (1.0 + want.abs()),
            "α column {row}: {d} against {want}"
        );
    }
    // Smooth across: where the landing is on the breakpoint, one-sided differences in
    // t₀ of the held residual agree; the map's own differ by the jump of f''.
    let on = land_at(0.5, &mut map);
    let s = 1e-6;
    let slope_of = |map: &mut ImpactMap, holds: &[Hold], side: f64| {
        let a = pass_with(map, on + side * s, v0, 1, 1, holds)
            .unwrap()
            .residual[1];
        let b = pass_with(map, on + side * 2.0 * s, v0, 1, 1, holds)
            .unwrap()
            .residual[1];
        (b - a) / (side * s)
    };
    let (l, rr) = (
        slope_of(&mut map, &hold, -1.0),
        slope_of(&mut map, &hold, 1.0),
    );
    assert!(
        (l - rr).abs() < 1e-4 * (1.0 + l.abs()),
        "held: {l} against {rr}"
    );
    let (l, rr) = (slope_of(&mut map, &[], -1.0), slope_of(&mut map, &[], 1.0));
    assert!(
        (l - rr).abs() > 1e-2 * (1.0 + l.abs()),
        "unheld: {l} against {rr}"
    );
}
