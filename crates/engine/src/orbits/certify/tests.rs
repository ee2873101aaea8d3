use super::*;
use crate::orbits::cascade::cascade;
use crate::orbits::fixed::{fixed_points, stability_window, Classification};
use crate::table::Table;

fn in_box(x: f64, i: &Interval) -> bool {
    i.contains(x) || i.contains(x + 1.0) || i.contains(x - 1.0)
}

/// The cycle of each stable level of the period-doubling cascade (from the
/// continuation: α halfway along the level, the guess its end point) is proved, in a
/// box at most 1e-12 wide holding Newton's f64 solution, and proved stable.
#[test]
fn the_cascades_stable_cycles_are_proved_stable() {
    for (table, levels) in [
        (Table::fd(1.0).unwrap(), 4),
        (Table::fd(0.5).unwrap(), 2),
        (Table::sine(), 4),
    ] {
        let c = cascade(&table, 0.8, 1, 4).unwrap();
        assert!(
            c.levels.len() >= levels,
            "{}: {} levels",
            table.name(),
            c.levels.len()
        );
        for level in &c.levels[..levels] {
            let alpha = 0.5 * (level.alpha_start + level.end.alpha);
            let sys = System::new(table.clone(), alpha, 0.8).unwrap();
            let g = &level.end.point;
            let n = level.period;
            let cert = certify(&sys, n, n as u32, g.phases[0], g.velocities[0]);
            let what = format!("{} ({n}, {n}) at {alpha}: {:?}", table.name(), cert.failure);
            assert!(cert.proved(), "{what}");
            let e = cert.enclosure.as_ref().unwrap();
            assert!(e.width <= 1e-12, "{what}: width {}", e.width);
            let pt = cert.cycle.as_ref().unwrap();
            for i in 0..n {
                assert!(in_box(pt.phases[i], &e.phases[i]), "{what}: phase {i}");
                assert!(
                    e.velocities[i].contains(pt.velocities[i]),
                    "{what}: velocity {i}"
                );
            }
            let st = cert.stability.unwrap();
            assert_eq!(st.verdict, StabilityVerdict::Stable, "{what}");
            assert_eq!(cert.flights.len(), n);
        }
    }
}

/// Beyond α_PD the (1, 1) solution is proved unstable, and its multipliers' enclosures
/// hold the closed-form eigenvalues of the paper's A = [[1, 1 + r], [(1 + r) f'',
/// (1 + r)² f'' + r²]]; at the closed-form α_PD the stability is not decided, for the
/// period doubling's reason, while the orbit itself is proved.
#[test]
fn unstable_and_undecided_stability_against_the_closed_form() {
    for table in [
        Table::sine(),
        Table::fd(0.1).unwrap(),
        Table::fd(1.0).unwrap(),
    ] {
        let w = stability_window(&table, 0.8, 1).unwrap().unwrap();
        for alpha in [w.alpha_end * 1.05, 0.5 * (w.alpha_birth + w.alpha_end)] {
            let sys = System::new(table.clone(), alpha, 0.8).unwrap();
            let fp = fixed_points(&sys, 1).unwrap();
            let p = fp
                .iter()
                .find(|p| p.classification != Classification::UnstableSaddle)
                .unwrap();
            let cert = certify(&sys, 1, 1, p.phase, p.v);
            assert!(
                cert.proved(),
                "{} at {alpha}: {:?}",
                table.name(),
                cert.failure
            );
            let st = cert.stability.unwrap();
            let want = if p.classification == Classification::Stable {
                StabilityVerdict::Stable
            } else {
                StabilityVerdict::Unstable
            };
            assert_eq!(st.verdict, want, "{} at {alpha}", table.name());
            let slack = |i: Interval| Interval::new(i.lo() - 1e-12, i.hi() + 1e-12).unwrap();
            match st.multipliers {
                Multipliers::Real(ls) => {
                    let mut want: Vec<f64> = p.eigenvalues.iter().map(|e| e.re).collect();
                    want.sort_by(|a, b| b.total_cmp(a));
                    for (l, e) in ls.iter().zip(want) {
                        assert!(slack(*l).contains(e), "{l:?} {e}");
                    }
                }
                Multipliers::Complex { re, im } => {
                    assert!(slack(re).contains(p.eigenvalues[0].re));
                    assert!(slack(im).contains(p.eigenvalues[0].im.abs()));
                }
                Multipliers::Unresolved { .. } => panic!("{} at {alpha}", table.name()),
            }
        }
        let sys = System::new(table.clone(), w.alpha_end, 0.8).unwrap();
        let cert = certify(&sys, 1, 1, w.phase_end, 0.5);
        assert!(cert.proved(), "{}: {:?}", table.name(), cert.failure);
        let st = cert.stability.unwrap();
        assert_eq!(
            st.verdict,
            StabilityVerdict::Undecided {
                near: Near::PeriodDoubling
            },
            "{}",
            table.name()
        );
        assert!(st.pd_test().contains(0.0) && st.pd_test().width() < 1e-12);
    }
}

/// A guess a quarter period off goes to a cycle far from it and is refused as such; an
/// (n, k) that has no cycle near the guess is refused by Newton's method.
#[test]
fn wrong_guesses_are_not_certified() {
    let sys = System::new(Table::sine(), 0.02, 0.8).unwrap();
    let p = fixed_points(&sys, 1).unwrap()[0];
    let cert = certify(&sys, 1, 1, p.phase + 0.25, p.v);
    assert!(!cert.proved());
    assert!(
        matches!(
            cert.failure,
            Some(Failure::FarFromGuess { .. } | Failure::NoCycle(_))
        ),
        "{:?}",
        cert.failure
    );
    let cert = certify(&sys, 3, 1, p.phase, p.v);
    assert!(
        matches!(cert.failure, Some(Failure::NoCycle(_))),
        "{:?}",
        cert.failure
    );
}

/// The (1, 2) saddle of the sine grazes the table inside its flight at α_g, where the
/// gap g(τ) = α sin 2πt* + τ − τ²/2 − α sin 2π(t* + τ) (v = 1) has a double root. α_g
/// from that pair of equations (Newton's method in (α, τ), t* in closed form) is where
/// proofs stop: below it the cycle is proved, above it the flight of the solution of
/// the cycle's equations is shown to cross the table, and within 1e-15 of it neither.
#[test]
fn a_grazing_flight_is_not_certified() {
    let c = (1.0 - 0.8) / (1.0 + 0.8); // f'(t*) = ½(1 − r)/(1 + r)·k with k = 2
    let two_pi = 2.0 * std::f64::consts::PI;
    let t_star = |a: f64| 1.0 - (c / (two_pi * a)).acos() / two_pi;
    let eqs = |a: f64, tau: f64| {
        let t = t_star(a);
        [
            a * (two_pi * t).sin() + tau - 0.5 * tau * tau - a * (two_pi * (t + tau)).sin(),
            1.0 - tau - two_pi * a * (two_pi * (t + tau)).cos(),
        ]
    };
    let (mut a, mut tau) = (0.17186, 0.3876);
    for _ in 0..30 {
        let f = eqs(a, tau);
        let h = 1e-7;
        let fa = eqs(a + h, tau);
        let ft = eqs(a, tau + h);
        let j = [
            [(fa[0] - f[0]) / h, (ft[0] - f[0]) / h],
            [(fa[1] - f[1]) / h, (ft[1] - f[1]) / h],
        ];
        let d = crate::linalg::solve(j, f).unwrap();
        a -= d[0];
        tau -= d[1];
    }
    let alpha_g = a;
    let sine = Table::sine();
    let base = System::new(sine.clone(), 0.1718, 0.8).unwrap();
    let pt = cycle(&base, 1, 2, t_star(0.1718), 1.0).unwrap();
    let at = |a: f64| certify_cycle(&System::new(sine.clone(), a, 0.8).unwrap(), &pt);
    assert!(at(alpha_g - 1e-9).proved());
    assert!(matches!(
        at(alpha_g + 1e-9).failure,
        Some(Failure::Flight {
            why: FlightFailure::EarlierContact { .. },
            ..
        })
    ));
    // The last α proved, by bisection on the proofs.
    let (mut lo, mut hi) = (alpha_g - 1e-9, alpha_g + 1e-9);
    while hi - lo > 1e-17 {
        let m = 0.5 * (lo + hi);
        if m == lo || m == hi {
            break;
        }
        if at(m).proved() {
            lo = m
        } else {
            hi = m
        }
    }
    assert!((lo - alpha_g).abs() < 1e-13, "{lo} against {alpha_g}");
    let close = at(hi);
    assert!(
        matches!(
            close.failure,
            Some(Failure::Flight {
                why: FlightFailure::Close { .. } | FlightFailure::EarlierContact { .. },
                ..
            })
        ),
        "{:?}",
        close.failure
    );
}

/// α typed as 0.6 is enclosed with both three fifths and its double, and F_D's
/// coefficients from D = 0.3 likewise: the proof holds for the decimal system.
#[test]
fn parameters_are_enclosed_as_written() {
    let sys = System::new(Table::fd(0.3).unwrap(), 0.6, 0.8).unwrap();
    let p = fixed_points(&sys, 1).unwrap()[0];
    let cert = certify(&sys, 1, 1, p.phase, p.v);
    assert!(cert.alpha.contains(0.6) && cert.alpha.lo() < cert.alpha.hi());
    assert!((cert.alpha * Interval::point(5.0)).contains(3.0));
    assert!((cert.r * Interval::point(5.0)).contains(4.0));
    assert!(cert.proved(), "{:?}", cert.failure);
}

/// The (1, 1) period doubling of fd:0.1, fd:0.5, fd:1 and the sine is proved in an
/// α-interval at most 1e-12 wide that holds the closed-form α_PD (f''(t̂*) = κ_c), with
/// the period-doubling test of opposite signs at its ends; the (2, 2) border
/// collision is proved in one that holds `two_cycle`'s (found by continuing the
/// two-cycle's own equations).
#[test]
fn period_doublings_and_border_collisions_are_proved_as_alpha_intervals() {
    for table in [
        Table::fd(0.1).unwrap(),
        Table::fd(0.5).unwrap(),
        Table::fd(1.0).unwrap(),
        Table::sine(),
    ] {
        let w = stability_window(&table, 0.8, 1).unwrap().unwrap();
        let sys = System::new(table.clone(), w.alpha_end, 0.8).unwrap();
        let pt = cycle(&sys, 1, 1, w.phase_end, 0.5).unwrap();
        let c = certify_period_doubling(&table, 0.8, &pt);
        let what = format!("{}: {:?} {:?}", table.name(), c.alpha, c.failure);
        assert!(c.proved(), "{what}");
        let a = c.alpha.unwrap();
        assert!(a.contains(w.alpha_end) && a.width() <= 1e-12, "{what}");
        let [lo, hi] = c.ends.unwrap();
        assert!(
            lo.positive() && hi.negative(),
            "{what}: stable below, unstable above"
        );
        if table.breakpoints().is_empty() {
            continue;
        }
        let bc = crate::orbits::two_cycle::border_collision(&table, 0.8, 1).unwrap();
        let sys = System::new(table.clone(), bc.alpha, 0.8).unwrap();
        let pt = cycle(&sys, 2, 2, bc.phase0, bc.v0).unwrap();
        let j = (0..2)
            .min_by(|&x, &y| {
                let d = |i: usize| crate::time::phase_distance(pt.phases[i], bc.phase);
                d(x).total_cmp(&d(y))
            })
            .unwrap();
        let c = certify_border_collision(&table, 0.8, &pt, j, bc.phase);
        let what = format!(
            "{} BC: {:?} {:?} against {}",
            table.name(),
            c.alpha,
            c.failure,
            bc.alpha
        );
        assert!(c.proved(), "{what}");
        let a = c.alpha.unwrap();
        assert!(a.contains(bc.alpha) && a.width() <= 1e-12, "{what}");
        let [lo, hi] = c.ends.unwrap();
        assert!(lo.positive() != hi.positive() && !lo.contains(0.0) && !hi.contains(0.0));
    }
}

/// The cascade's α₂ and α₃ (period doublings of the (2, 2) and (4, 4) cycles, located
/// by the continuation's test function) lie within 1e-11 of proved intervals; the sine
/// has no breakpoint to collide with, and away from a period doubling no bracket is
/// found.
#[test]
fn higher_period_doublings_and_refusals() {
    for table in [Table::fd(1.0).unwrap(), Table::sine()] {
        let c = cascade(&table, 0.8, 1, 3).unwrap();
        for level in &c.levels[1..3] {
            let end = &level.end;
            let p = certify_period_doubling(&table, 0.8, &end.point);
            let what = format!(
                "{} ({}): {:?} {:?} against {}",
                table.name(),
                level.period,
                p.alpha,
                p.failure,
                end.alpha
            );
            assert!(p.proved(), "{what}");
            let a = p.alpha.unwrap();
            assert!(
                a.width() <= 1e-12 && (a.mid() - end.alpha).abs() < 1e-11,
                "{what}"
            );
        }
    }
    let sys = System::new(Table::sine(), 0.02, 0.8).unwrap();
    let p = fixed_points(&sys, 1).unwrap()[0];
    let pt = cycle(&sys, 1, 1, p.phase, p.v).unwrap();
    let c = certify_period_doubling(&Table::sine(), 0.8, &pt);
    assert_eq!(c.failure, Some(SpecialFailure::NoBracket));
    let c = certify_border_collision(&Table::sine(), 0.8, &pt, 0, 0.0);
    assert_eq!(c.failure, Some(SpecialFailure::NoBreakpoint));
}

/// The sine's (1, k) solutions are born in a fold at α_birth = c/(2π), c = k(1 − r)/
/// (2(1 + r)) (where f'(t̂*) = c first has a solution, at t̂* = 0): the fold is proved in
/// an α-interval holding it, under 1e-12 wide.
#[test]
fn the_sines_births_are_proved_folds() {
    for k in [1u32, 2] {
        let c = crate::orbits::fixed::fixed_point_slope(0.8, k);
        let alpha_birth = c / (2.0 * std::f64::consts::PI);
        let alpha = alpha_birth * (1.0 + 1e-9);
        let sys = System::new(Table::sine(), alpha, 0.8).unwrap();
        let p = fixed_points(&sys, k).unwrap()[0];
        let pt = cycle(&sys, 1, k, p.phase, p.v).unwrap();
        let f = certify_fold(&Table::sine(), 0.8, &pt);
        let what = format!("k {k}: {:?} {:?} against {alpha_birth}", f.alpha, f.failure);
        assert!(f.proved(), "{what}");
        let a = f.alpha.unwrap();
        assert!(a.contains(alpha_birth) && a.width() <= 1e-12, "{what}");
    }
}
