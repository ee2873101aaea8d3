//! Periodic orbits of the exact map, their continuation in α and the period-doubling
//! cascade, checked against the closed forms (`fixed`), the (2, 2k) Newton solutions
//! (`two_cycle`), the map itself (stepping and finite differences) and simulation.

use bouncemap_engine::eigenvalues_2x2;
use bouncemap_engine::orbits::border::Crossing;
use bouncemap_engine::orbits::cascade::cascade;
use bouncemap_engine::orbits::continuation::{branches, point_at, Branch, Kind, Options, Start};
use bouncemap_engine::orbits::periodic::{cycle, CyclePoint};
use bouncemap_engine::orbits::{border_collision, stability_window, two_cycle};
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::run::{Advance, OrbitRun};
use bouncemap_engine::table::Table;
use bouncemap_engine::Solver;
use bouncemap_engine::System;
use bouncemap_engine::{EventKind, ImpactMap, State};

const R: f64 = 0.8;

fn tables() -> Vec<(&'static str, Table)> {
    vec![
        ("fd:0.1", Table::fd(0.1).unwrap()),
        ("fd:1", Table::fd(1.0).unwrap()),
        ("sine", Table::sine()),
    ]
}

/// The map stepped n times from the point: (time error, velocity error), all impacts.
fn step_return(table: &Table, p: &CyclePoint) -> (f64, f64) {
    let sys = System::new(table.clone(), p.alpha, R).unwrap();
    let st = State::launch(&sys, 0, p.phases[0], p.velocities[0], 0.0).unwrap();
    let mut m = ImpactMap::new(sys, Solver::Exact, st);
    for i in 0..p.n {
        let e = m.step().unwrap();
        assert_eq!(
            e.kind,
            EventKind::Impact,
            "event {i} of the ({}, {}) cycle",
            p.n,
            p.k
        );
    }
    let s = m.state();
    let dt = (s.period() - p.k as i64) as f64 + (s.phase() - p.phases[0]);
    (dt.abs(), (s.v() - p.velocities[0]).abs())
}

#[test]
fn alpha_1_of_the_cascade_is_the_closed_form_period_doubling_point() {
    for (name, table) in tables() {
        let pd = stability_window(&table, R, 1)
            .unwrap()
            .unwrap()
            .alpha_pd()
            .unwrap();
        let c = cascade(&table, R, 1, 2).unwrap();
        assert!(
            (c.alphas[0] - pd).abs() <= 1e-10,
            "{name}: α₁ = {} vs α_PD = {pd}",
            c.alphas[0]
        );
    }
}

#[test]
fn the_two_two_branch_agrees_with_two_cycle_and_its_border_collision() {
    let table = Table::fd(0.1).unwrap();
    let bs = branches(
        &table,
        R,
        (0.45, 0.6),
        Start::TwoCycle { k: 1 },
        Options::default(),
    )
    .unwrap();
    let b = &bs[0];
    assert_eq!((b.n, b.k), (2, 2));
    let bc = border_collision(&table, R, 1).unwrap();
    // Three α between the period doubling and the border collision.
    let pd = stability_window(&table, R, 1)
        .unwrap()
        .unwrap()
        .alpha_pd()
        .unwrap();
    for s in [0.2, 0.5, 0.9] {
        let alpha = pd + s * (bc.alpha - pd);
        let p = point_at(&table, R, b, alpha).expect("a point of the branch");
        let tc = two_cycle(&System::new(table.clone(), alpha, R).unwrap(), 1).unwrap();
        let mut ph = p.phases.clone();
        let mut vs = p.velocities.clone();
        if ph[0] > ph[1] {
            ph.swap(0, 1);
            vs.swap(0, 1);
        }
        for (a, b) in [
            (ph[0], tc.phase0),
            (ph[1], tc.phase1),
            (vs[0], tc.v0),
            (vs[1], tc.v1),
        ] {
            assert!((a - b).abs() <= 1e-10, "α = {alpha}: {a} vs {b}");
        }
    }
    // The border collision: the first one along the branch, where the stable cycle
    // ends, at two_cycle's α (0.511844102519 for fd:0.1) and phase 0.
    let mut all: Vec<_> = b.specials.iter().chain([&b.begin, &b.end]).collect();
    all.retain(|s| s.kind == Kind::BorderCollision);
    let first = all
        .iter()
        .min_by(|a, b| a.alpha.total_cmp(&b.alpha))
        .expect("a border collision");
    assert!(
        (first.alpha - bc.alpha).abs() <= 1e-10,
        "{} vs {}",
        first.alpha,
        bc.alpha
    );
    assert!((first.alpha - 0.511844102519).abs() <= 1e-12);
    assert_eq!(first.phase, 0.0);
    // The branch was born at the period doubling of (1, 1).
    assert_eq!(b.begin.kind, Kind::PeriodDoubling);
    assert!(
        (b.begin.alpha - pd).abs() <= 1e-9,
        "{} vs {pd}",
        b.begin.alpha
    );
}

fn all_branches() -> Vec<(Table, Vec<Branch>)> {
    let mut out = Vec::new();
    for (name, table, window) in [
        ("fd:0.1", Table::fd(0.1).unwrap(), (0.45, 0.6)),
        ("fd:0.7", Table::fd(0.7).unwrap(), (0.45, 0.6)),
        ("fd:1", Table::fd(1.0).unwrap(), (0.45, 0.6)),
        ("sine", Table::sine(), (0.02, 0.032)),
    ] {
        let bs = branches(&table, R, window, Start::Fixed { k: 1 }, Options::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!bs.is_empty());
        out.push((table, bs));
    }
    out
}

#[test]
fn every_continued_point_returns_under_the_map_and_has_multipliers_multiplying_to_r_2n() {
    let mut checked = 0;
    for (table, bs) in all_branches() {
        for b in &bs {
            for p in b.points.iter().chain(b.specials.iter().map(|s| &s.point)) {
                let (dt, dv) = step_return(&table, p);
                assert!(
                    dt <= 1e-11 && dv <= 1e-11,
                    "({}, {}) at α = {}: {dt:e}, {dv:e}",
                    p.n,
                    p.k,
                    p.alpha
                );
                assert!(p.det_error.abs() < 1e-8, "det error {:e}", p.det_error);
                let prod = p.multipliers[0].re * p.multipliers[1].re
                    - p.multipliers[0].im * p.multipliers[1].im;
                let want = R.powi(2 * p.n as i32);
                assert!((prod - want).abs() <= 1e-12 * want.max(1e-300) + 1e-15);
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked}");
}

/// The n-step map by central differences in (t₀, v₀), at fixed α.
fn fd_monodromy(table: &Table, p: &CyclePoint, h: f64) -> [[f64; 2]; 2] {
    let sys = System::new(table.clone(), p.alpha, R).unwrap();
    let run = |dt: f64, dv: f64| {
        let st = State::launch(&sys, 0, p.phases[0] + dt, p.velocities[0] + dv, 0.0).unwrap();
        let mut m = ImpactMap::new(sys.clone(), Solver::Exact, st);
        for _ in 0..p.n {
            m.step().unwrap();
        }
        let s = m.state();
        (s.period() as f64 + s.phase(), s.v())
    };
    let (tp, vp) = run(h, 0.0);
    let (tm, vm) = run(-h, 0.0);
    let (tq, vq) = run(0.0, h);
    let (tr, vr) = run(0.0, -h);
    [
        [(tp - tm) / (2.0 * h), (tq - tr) / (2.0 * h)],
        [(vp - vm) / (2.0 * h), (vq - vr) / (2.0 * h)],
    ]
}

#[test]
fn multipliers_match_finite_differences_of_the_map() {
    let mut checked = 0;
    for (table, bs) in all_branches() {
        for b in bs.iter().filter(|b| b.n <= 4) {
            for p in b.points.iter().step_by(3) {
                // Away from breakpoints (the central difference would straddle a jump
                // of f'') and from phases near 0 (the difference would cross a period).
                let margin = p.phases.iter().fold(1.0f64, |m, &ph| {
                    m.min(ph).min(1.0 - ph).min((ph - 0.5).abs())
                });
                if margin < 1e-4 {
                    continue;
                }
                let m = fd_monodromy(&table, p, 1e-7);
                let fd = eigenvalues_2x2(m);
                for (a, b) in p.multipliers.iter().zip(fd.iter()) {
                    let scale = 1.0 + a.abs();
                    assert!(
                        (a.re - b.re).abs() <= 1e-6 * scale
                            && (a.im.abs() - b.im.abs()).abs() <= 1e-6 * scale,
                        "({}, {}) at α = {}: {a:?} vs {b:?}",
                        p.n,
                        p.k,
                        p.alpha
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 30, "{checked}");
}

#[test]
fn the_cascade_of_the_sine_and_fd1_reaches_period_512_with_ratios_near_feigenbaum() {
    for (name, table) in [("fd:1", Table::fd(1.0).unwrap()), ("sine", Table::sine())] {
        let c = cascade(&table, R, 1, 10).unwrap();
        assert_eq!(c.alphas.len(), 10, "{name}: {:?}", c.alphas);
        assert!(c.alphas.windows(2).all(|w| w[0] < w[1]), "{name}");
        assert_eq!(c.levels.last().unwrap().period, 512);
        // Feigenbaum's δ = 4.669201609…; δₙ approaches it from below from n = 5 on.
        let last = *c.deltas.last().unwrap();
        assert!(
            (last - 4.669_201_609).abs() < 2e-4,
            "{name}: δ = {:?}",
            c.deltas
        );
        let d = &c.deltas[3..];
        assert!(
            d.windows(2).all(|w| w[0] < w[1]),
            "{name}: δ = {:?}",
            c.deltas
        );
    }
}

/// Run the sweep's value run at α from a point near the cycle: its outcome.
fn simulate(table: &Table, alpha: f64, p: &CyclePoint) -> Outcome {
    let sys = System::new(table.clone(), alpha, R).unwrap();
    let st = State::launch(&sys, 0, p.phases[0], p.velocities[0] + 1e-9, 0.0).unwrap();
    let map = ImpactMap::new(sys, Solver::Exact, st);
    let mut run = OrbitRun::new(map, 64, Some(Periodicity::default()));
    let end = 200_000;
    match run.advance(end, end, &mut |_| false) {
        Advance::Done(o, _) => o,
        other => panic!("{other:?}"),
    }
}

/// The paper's question: for D = 0.1, 0.3, 0.5 the 2-cycle, for D = 0.68, 0.7 the
/// 4-cycle and for 0.785 the 16-cycle end by border collision; just before it the
/// simulated orbit settles on that cycle, just past it it does not (and D = 1 has no
/// border collision in the first levels; for 0.78 the cascade goes on through one, see
/// below).
#[test]
fn just_past_each_border_collision_the_simulated_orbit_is_no_longer_that_cycle() {
    for (d, period) in [
        (0.1, 2),
        (0.3, 2),
        (0.5, 2),
        (0.68, 4),
        (0.7, 4),
        (0.785, 16),
    ] {
        let table = Table::fd(d).unwrap();
        let c = cascade(&table, R, 1, 6).unwrap();
        let l = c.interrupted().expect("an interrupted cascade");
        assert_eq!(l.end.kind, Kind::BorderCollision, "D = {d}");
        assert_eq!(l.period, period, "D = {d}");
        let p = &l.end.point;
        let is_cycle = |o: Outcome| matches!(o, Outcome::Periodic { events, periods, .. } if events == p.n && periods == p.k as i64);
        // Within the branch's own α range (a 2ⁿ branch lives on a range ∝ δ⁻ⁿ).
        let off = 1e-5f64.min(0.1 * (l.end.alpha - l.alpha_start).abs());
        // Before: started on the cycle there (its basin may be small near the border);
        // after: started where the cycle was at the collision.
        let sys = System::new(table.clone(), l.end.alpha - off, R).unwrap();
        let on = cycle(&sys, p.n, p.k, p.t0, p.velocities[0]).unwrap();
        assert!(on.stable, "D = {d}");
        let before = simulate(&table, l.end.alpha - off, &on);
        assert!(is_cycle(before), "D = {d}: before {before:?}");
        let after = simulate(&table, l.end.alpha + off, p);
        assert!(!is_cycle(after), "D = {d}: after {after:?}");
    }
    let c = cascade(&Table::fd(1.0).unwrap(), R, 1, 4).unwrap();
    assert!(c.interrupted().is_none());
}

#[test]
fn the_fig3e_window_is_continued_quickly() {
    let table = Table::fd(1.0).unwrap();
    let t = std::time::Instant::now();
    let bs = branches(
        &table,
        R,
        (0.45, 0.6),
        Start::Fixed { k: 1 },
        Options::default(),
    )
    .unwrap();
    let took = t.elapsed();
    assert!(took.as_secs_f64() < 0.5, "{took:?}");
    let periods: Vec<usize> = bs.iter().map(|b| b.n).collect();
    assert_eq!(periods, vec![1, 2, 4, 8, 16]);
}

#[test]
fn bad_windows_and_starts_are_refused() {
    let table = Table::fd(0.1).unwrap();
    assert!(branches(
        &table,
        R,
        (0.6, 0.5),
        Start::Fixed { k: 1 },
        Options::default()
    )
    .is_err());
    assert!(cascade(&table, R, 1, 0).is_err());
    assert!(cascade(&table, R, 1, 13).is_err());
    // A guess far from any (3, 2) cycle.
    assert!(branches(
        &table,
        R,
        (0.45, 0.6),
        Start::Point {
            n: 3,
            k: 2,
            t0: 0.9,
            v0: 50.0
        },
        Options::default()
    )
    .is_err());
}

/// The (1, 2) branch of the sine: its fold is the solution's birth (`fixed`'s closed
/// form), and its saddle half ends by grazing, past which `fixed` finds the solution
/// no longer admissible (its flight meets the table earlier).
#[test]
fn the_fold_is_the_birth_and_the_grazing_is_where_admissibility_ends() {
    let table = Table::sine();
    let bs = branches(
        &table,
        R,
        (0.01, 3.0),
        Start::Fixed { k: 2 },
        Options {
            max_period: 1,
            ..Options::default()
        },
    )
    .unwrap();
    let b = &bs[0];
    let birth = stability_window(&table, R, 2).unwrap().unwrap().alpha_birth;
    let fold = b
        .specials
        .iter()
        .find(|s| s.kind == Kind::Fold)
        .expect("a fold");
    assert!(
        (fold.alpha - birth).abs() <= 1e-10,
        "{} vs {birth}",
        fold.alpha
    );
    let graze = [&b.begin, &b.end]
        .into_iter()
        .find(|s| s.kind == Kind::Grazing)
        .expect("a grazing end");
    let p = &graze.point;
    let sys = |a: f64| System::new(table.clone(), a, R).unwrap();
    let (gap, _) = bouncemap_engine::orbits::periodic::min_interior_gap(&sys(p.alpha), p);
    assert!(gap.abs() < 1e-6, "{gap}");
    let near = |a: f64| {
        bouncemap_engine::orbits::fixed_points(&sys(a), 2)
            .unwrap()
            .into_iter()
            .min_by(|x, y| {
                (x.phase - p.phases[0])
                    .abs()
                    .total_cmp(&(y.phase - p.phases[0]).abs())
            })
            .unwrap()
    };
    // The branch's α increases towards the grazing on the saddle half.
    assert!(near(graze.alpha - 1e-6).admissible);
    assert!(!near(graze.alpha + 1e-6).admissible);

    // Why no branch ends at the onset of a stick: a flight touches the table only where
    // the table accelerates downwards faster than gravity, α F'' < −1, so a ball
    // touching it there flies off at once. Simulated: launched there a hair above the
    // table's velocity, it flies a long flight; where α F'' > −1 it chatters and sticks.
    let acc = |phase: f64| p.alpha * table.derivative(phase, 2);
    assert!(acc(graze.phase) < -1.0, "α F'' = {}", acc(graze.phase));
    let s = sys(p.alpha);
    let first_non_impact_or_long_flight = |phase: f64| {
        let v = p.alpha * table.derivative(phase, 1) + 1e-9;
        let mut m = ImpactMap::new(
            s.clone(),
            Solver::Exact,
            State::launch(&s, 0, phase, v, 0.0).unwrap(),
        );
        for _ in 0..10_000 {
            let e = m.step().unwrap();
            let flown = e.period as f64 + e.phase - phase;
            if e.kind != EventKind::Impact || flown > 0.01 {
                return (e.kind, flown);
            }
        }
        panic!("neither a stick nor a flight");
    };
    let (kind, flown) = first_non_impact_or_long_flight(graze.phase);
    assert!(
        kind == EventKind::Impact && flown > 0.01,
        "{kind:?} after {flown}"
    );
    let sticky = 0.75; // F'' = 4π² > 0 there
    assert!(acc(sticky) > -1.0);
    assert_eq!(first_non_impact_or_long_flight(sticky).0, EventKind::Stick);
}

/// F_0.78's (8, 8) cycle meets the breakpoint ½ and a stable (16, 16) cycle is born
/// there: the cascade goes on through the border collision. Values from an independent
/// 30–40 digit computation (Newton on the exact map in mpmath, the one-sided monodromies
/// at the collision, and the doubled cycle just past it); the doubled cycle is checked
/// by simulating the map from next to it.
#[test]
fn the_cascade_of_fd078_goes_on_through_a_border_collision() {
    let table = Table::fd(0.78).unwrap();
    let c = cascade(&table, R, 1, 6).unwrap();
    assert!(c.interrupted().is_none(), "{:?}", c.interrupted());
    let l = &c.levels[3];
    assert_eq!((l.period, l.end.kind), (8, Kind::BorderCollision));
    assert!(
        (l.end.alpha - 0.592968377792713).abs() < 1e-11,
        "{}",
        l.end.alpha
    );
    let col = l.end.collision.expect("classified");
    assert_eq!(col.crossing, Crossing::Doubling { stable: true });
    let far: Vec<f64> = col.far.iter().map(|z| z.re).collect();
    assert!(
        (far[1] + 1.762761223).abs() < 1e-8 && (far[0] + 0.01596784).abs() < 1e-8,
        "{far:?}"
    );
    // The near side is a stable focus of modulus r⁸.
    assert!(col.near.iter().all(|z| (z.abs() - R.powi(8)).abs() < 1e-9));
    // The next levels: the (16, 16) born there doubles smoothly at α₅, then the (32, 32)
    // at α₆.
    assert_eq!(c.levels[4].period, 16);
    assert!(
        (c.alphas[4] - 0.593055257711907).abs() < 1e-11,
        "{:?}",
        c.alphas
    );
    assert!(
        (c.alphas[5] - 0.593076439479118).abs() < 1e-11,
        "{:?}",
        c.alphas
    );
    // Just past the collision the (16, 16) cycle is there, stable (μ₁ = 0.51255 at
    // α_BC + 10⁻⁶), and attracts a start next to it.
    let alpha = l.end.alpha + 1e-6;
    let sys = System::new(table.clone(), alpha, R).unwrap();
    let q = cycle(&sys, 16, 16, 0.024043390644516, 0.733464695509702).unwrap();
    assert!(q.stable);
    assert!(
        (q.multipliers[0].re - 0.5125501).abs() < 1e-6,
        "{:?}",
        q.multipliers
    );
    let run = simulate(&table, alpha, &q);
    assert!(
        matches!(
            run,
            Outcome::Periodic {
                events: 16,
                periods: 16,
                ..
            }
        ),
        "{run:?}"
    );
}

/// At a border-collision fold the cycle meets its partner and both cease: F_0.76's
/// (16, 16) at ½ and F_0.77's (8, 8) (an independent computation finds the partner's
/// smooth fold and the signs of det(I − J) on either side).
#[test]
fn border_collision_folds_are_reported_as_such() {
    for (d, period, alpha) in [(0.76, 16, 0.592361018205), (0.77, 8, 0.592606797279)] {
        let c = cascade(&Table::fd(d).unwrap(), R, 1, 6).unwrap();
        let l = c.interrupted().expect("the cascade stops");
        assert_eq!(
            (l.period, l.end.kind),
            (period, Kind::BorderCollision),
            "D = {d}"
        );
        assert!(
            (l.end.alpha - alpha).abs() < 1e-11,
            "D = {d}: {}",
            l.end.alpha
        );
        assert_eq!(
            l.end.collision.map(|c| c.crossing),
            Some(Crossing::Fold),
            "D = {d}"
        );
    }
}

/// The acceptance check of continuation: on the windows of the paper's tables (F_D for
/// D = 0.1, 0.3, 0.5, 0.78, 1 over 0.4..0.6, the sine over 0.025..0.033, up to period 16)
/// every special point satisfies its own condition, and no branch changes cycle between
/// two of its points. The second is checked independently of the pseudo-arclength
/// corrector: natural continuation in α (Newton's method at fixed α, 16 small steps)
/// from each point must arrive on the next one.
#[test]
fn branches_never_jump_and_special_points_hold_their_condition() {
    let cases = [
        (Table::fd(0.1).unwrap(), (0.4, 0.6)),
        (Table::fd(0.3).unwrap(), (0.4, 0.6)),
        (Table::fd(0.5).unwrap(), (0.4, 0.6)),
        (Table::fd(0.78).unwrap(), (0.4, 0.6)),
        (Table::fd(1.0).unwrap(), (0.4, 0.6)),
        (Table::sine(), (0.025, 0.033)),
    ];
    let opts = Options {
        max_period: 16,
        ..Options::default()
    };
    let (mut checked, mut segments) = (0, 0);
    for (table, window) in cases {
        let bs = branches(&table, R, window, Start::Fixed { k: 1 }, opts).unwrap();
        for b in &bs {
            for s in b.specials.iter().chain([&b.begin, &b.end]) {
                if matches!(
                    s.kind,
                    Kind::PeriodDoubling | Kind::Fold | Kind::BorderCollision
                ) {
                    let e = s.condition_error().unwrap();
                    assert!(
                        e <= 1e-8,
                        "{}: {:?} at {}: {e}",
                        table.name(),
                        s.kind,
                        s.alpha
                    );
                }
                assert_ne!(s.kind, Kind::Lost, "{}: lost at {}", table.name(), s.alpha);
            }
            let kinks: Vec<f64> = b
                .specials
                .iter()
                .chain([&b.begin, &b.end])
                .map(|s| s.alpha)
                .collect();
            for w in b.points.windows(2) {
                let (p, q) = (&w[0], &w[1]);
                // Segments at a special point (a kink, a turn, a birth) are the
                // special point's to check.
                let near_special = kinks.iter().any(|&a| {
                    (a - p.alpha).abs() < 1e-9
                        || (a - q.alpha).abs() < 1e-9
                        || (a - p.alpha) * (a - q.alpha) < 0.0
                });
                if near_special || (q.alpha - p.alpha).abs() < 1e-12 {
                    continue;
                }
                segments += 1;
                // Natural continuation in `steps` equal steps: the cycle it arrives on.
                let follow = |steps: usize| {
                    let (mut t0, mut v0) = (p.t0, p.velocities[0]);
                    let mut last = None;
                    for i in 1..=steps {
                        let a = p.alpha + (q.alpha - p.alpha) * i as f64 / steps as f64;
                        let sys = System::new(table.clone(), a, R).unwrap();
                        let c = cycle(&sys, p.n, p.k, t0, v0).ok()?;
                        (t0, v0) = (c.t0, c.velocities[0]);
                        last = Some(c);
                    }
                    last
                };
                // The same cycle up to which impact is taken as the launch.
                let same = |arrived: &CyclePoint| {
                    arrived
                        .phases
                        .iter()
                        .zip(&arrived.velocities)
                        .all(|(ph, v)| {
                            q.phases.iter().zip(&q.velocities).any(|(qp, qv)| {
                                let d = (ph - qp).abs();
                                d.min(1.0 - d) < 1e-7 && (v - qv).abs() < 1e-7
                            })
                        })
                };
                // Small steps first; much smaller ones where natural continuation
                // itself strayed (an unstable long cycle has close neighbours).
                let verdict = [16, 1024]
                    .into_iter()
                    .find_map(|steps| follow(steps).map(|c| same(&c)).filter(|&s| s));
                let Some(same) = verdict.or_else(|| follow(1024).map(|c| same(&c))) else {
                    continue;
                };
                checked += 1;
                assert!(
                    same,
                    "{}: the ({}, {}) branch jumps between alpha {} and {}",
                    table.name(),
                    p.n,
                    p.k,
                    p.alpha,
                    q.alpha
                );
            }
        }
    }
    assert!(
        checked > 200 && checked * 10 >= segments * 9,
        "{checked} of {segments}"
    );
}
