//! Two-parameter curves (orbits::curves) against independent results: the closed-form
//! period doubling of the (1, 1) solution, the two-cycle's own border collision, the
//! one-parameter continuation at points of each curve and on both sides of each
//! codimension-two point, and simulation of the doubled orbit past a flip.

use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::orbits::continuation::{branches, Kind, Options, Special, Start};
use bouncemap_engine::orbits::curves::{
    curves, Codim2Kind, Curve, CurvePoint, Curves, Plane, Seeds,
};
use bouncemap_engine::orbits::fixed::stability_window;
use bouncemap_engine::orbits::two_cycle::border_collision;
use bouncemap_engine::table::Table;
use bouncemap_engine::Solver;
use bouncemap_engine::System;
use bouncemap_engine::{ImpactMap, State};
use std::sync::OnceLock;

fn fd_plane() -> &'static (Plane, Curves) {
    static P: OnceLock<(Plane, Curves)> = OnceLock::new();
    P.get_or_init(|| {
        let plane = Plane {
            table: Table::fd(1.0).unwrap(),
            r: 0.8,
            alpha: (0.4, 0.7),
            second: SweepParam::D,
            window: (0.0, 1.0),
        };
        let seeds = Seeds::FromFixed {
            k: 1,
            max_period: 8,
            at: 1.0,
            count: 5,
        };
        let c = curves(&plane, seeds).unwrap();
        (plane, c)
    })
}

pub fn of<'a>(c: &'a Curves, kind: &str, n: usize) -> Vec<&'a Curve> {
    c.curves
        .iter()
        .filter(|cv| cv.kind.as_str() == kind && cv.n == n)
        .collect()
}

/// The border-collision curves of the (n, k) cycles at `breakpoint`.
pub fn border_collisions(c: &Curves, n: usize, breakpoint: f64) -> impl Iterator<Item = &Curve> {
    c.curves.iter().filter(move |cv| {
        cv.n == n
            && matches!(cv.kind, bouncemap_engine::orbits::curves::CurveKind::BorderCollision { breakpoint: b, .. } if b == breakpoint)
    })
}

/// Every point of the (1, 1) PD curve over (α, r) lies on the closed-form α_PD(r).
fn pd_curve_over_r_is_the_closed_form(table: Table, r_lo: f64) {
    let windows: Vec<f64> = (0..50)
        .map(|i| r_lo + (0.95 - r_lo) * (i as f64 + 0.5) / 50.0)
        .map(|r| {
            stability_window(&table, r, 1)
                .unwrap()
                .unwrap()
                .alpha_pd()
                .unwrap()
        })
        .collect();
    let lo = windows.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = windows.iter().cloned().fold(0.0, f64::max);
    let plane = Plane {
        table: table.clone(),
        r: 0.8,
        alpha: (0.9 * lo, 1.1 * hi),
        second: SweepParam::R,
        window: (r_lo, 0.95),
    };
    let c = curves(
        &plane,
        Seeds::FromFixed {
            k: 1,
            max_period: 1,
            at: 0.8,
            count: 1,
        },
    )
    .unwrap();
    let pd = of(&c, "period_doubling", 1);
    assert_eq!(pd.len(), 1, "{}: one (1, 1) PD curve", table.name());
    let cv = pd[0];
    // It spans the whole r window.
    let rs: Vec<f64> = cv.points.iter().map(|q| q.p).collect();
    assert!(
        rs.iter().cloned().fold(1.0, f64::min) < r_lo + 1e-9,
        "{:?}",
        cv.ends
    );
    assert!(
        rs.iter().cloned().fold(0.0, f64::max) > 0.95 - 1e-9,
        "{:?}",
        cv.ends
    );
    assert!(cv.points.len() >= 50);
    for q in &cv.points {
        let exact = stability_window(&table, q.p, 1)
            .unwrap()
            .unwrap()
            .alpha_pd()
            .unwrap();
        assert!(
            (q.alpha - exact).abs() < 1e-10,
            "{}: r = {}: curve {} closed form {}",
            table.name(),
            q.p,
            q.alpha,
            exact
        );
    }
}

#[test]
fn the_one_one_pd_curve_over_r_is_the_closed_form_for_the_sine_and_fd_half() {
    pd_curve_over_r_is_the_closed_form(Table::sine(), 0.2);
    // Below r ≈ 0.33 the fd:0.5 window of (1, 1) does not end by period doubling.
    pd_curve_over_r_is_the_closed_form(Table::fd(0.5).unwrap(), 0.35);
}

#[test]
fn the_one_one_pd_curve_over_d_is_the_closed_form() {
    let (_, c) = fd_plane();
    let pd = of(c, "period_doubling", 1);
    assert_eq!(pd.len(), 1);
    let pts = &pd[0].points;
    assert!(pts.len() >= 50);
    assert_eq!(pd[0].ends.map(|e| e.as_str()), ["window", "window"]);
    for q in pts {
        let exact = stability_window(&Table::fd(q.p).unwrap(), 0.8, 1)
            .unwrap()
            .unwrap()
            .alpha_pd()
            .unwrap();
        assert!(
            (q.alpha - exact).abs() < 1e-10,
            "D = {}: {} vs {}",
            q.p,
            q.alpha,
            exact
        );
    }
}

/// The special points of the (n, k) branch through a curve point's cycle, continued in
/// α at second parameter `d` over α ± `half` by the one-parameter continuation (its
/// own test functions and root location).
fn one_parameter(q: &CurvePoint, d: f64, half: f64) -> Vec<Special> {
    let table = Table::fd(d).unwrap();
    let start = Start::Point {
        n: q.cycle.n,
        k: q.cycle.k,
        t0: q.cycle.phases[0],
        v0: q.cycle.velocities[0],
    };
    let opts = Options {
        max_period: q.cycle.n,
        ..Options::default()
    };
    // Windows of that half-width and ten and a hundred times narrower: a branch may
    // end at a border collision next to the point in the widest. And one from just
    // below the point: a cycle whose multiplier runs fast in α (from −0.85 to −1 over
    // 10⁻⁵) may end less than a hundredth of `half` below it, where the continuation,
    // guessed at the window's lower end, finds no cycle.
    [
        (half, half),
        (half / 10.0, half / 10.0),
        (half / 100.0, half / 100.0),
        (half / 1000.0, half / 10.0),
    ]
    .into_iter()
    .flat_map(|(below, above)| {
        let window = (q.alpha - below, q.alpha + above);
        branches(&table, 0.8, window, start, opts).unwrap_or_default()
    })
    .filter(|b| b.n == q.cycle.n)
    .flat_map(|b| b.specials.into_iter().chain([b.begin, b.end]))
    .collect()
}

/// At ten points of each PD curve of the (2, 2), (4, 4) and (8, 8) cycles, the
/// one-parameter continuation at that D finds a period doubling of that cycle at the
/// same α.
#[test]
fn pd_curves_agree_with_the_one_parameter_continuation() {
    let (_, c) = fd_plane();
    for n in [2, 4, 8] {
        let pd = of(c, "period_doubling", n);
        let mut checked = 0;
        for cv in pd {
            // Where every impact is 2e-3 or more from a breakpoint: closer, the α window
            // ±1e-3 would reach the border, where the one-parameter continuation
            // reports the collision instead (and the cycle may not exist beyond).
            let pts: Vec<&CurvePoint> = cv
                .points
                .iter()
                .filter(|q| {
                    q.cycle
                        .phases
                        .iter()
                        .all(|&ph| ph.min(1.0 - ph) > 2e-3 && (ph - 0.5).abs() > 2e-3)
                })
                .collect();
            let m = pts.len();
            if m < 10 {
                continue;
            }
            checked += 1;
            for i in 0..10 {
                let q = pts[(i * (m - 1)) / 9];
                let best = one_parameter(q, q.p, 1e-3)
                    .iter()
                    .filter(|s| s.kind == Kind::PeriodDoubling)
                    .map(|s| (s.alpha - q.alpha).abs())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    best < 1e-9,
                    "({n}, {n}) at D = {}: α {} off by {best:e}",
                    q.p,
                    q.alpha
                );
            }
        }
        assert!(checked >= 1, "no ({n}, {n}) PD curve checked");
    }
}

/// The (2, 2) border-collision curve through the two-cycle's own border collision
/// (`two_cycle::border_collision`) at 20 values of D.
#[test]
fn the_two_two_border_collision_curve_is_the_two_cycles() {
    let (_, c) = fd_plane();
    let bc = of(c, "border_collision", 2);
    assert!(!bc.is_empty());
    let mut checked = 0;
    for i in 0..20 {
        let d = 0.05 + 0.6 * i as f64 / 19.0;
        let Ok(exact) = border_collision(&Table::fd(d).unwrap(), 0.8, 1) else {
            continue;
        };
        // The curve's α at this D, interpolated between its two points around it and
        // corrected: the curve passes within 1e-9 of the exact point.
        let near = bc.iter().any(|cv| {
            cv.passes_near(exact.alpha, d, 1e-9) || {
                cv.points.windows(2).any(|w| {
                    let (a, b) = (&w[0], &w[1]);
                    (a.p - d) * (b.p - d) <= 0.0 && {
                        let t = (d - a.p) / (b.p - a.p);
                        let alpha = a.alpha + t * (b.alpha - a.alpha);
                        // Chord error: the points are ≤ 0.005 of the window apart.
                        (alpha - exact.alpha).abs() < 1e-5
                    }
                })
            }
        });
        assert!(near, "D = {d}: no (2, 2) BC curve near α = {}", exact.alpha);
        checked += 1;
    }
    assert!(
        checked >= 15,
        "only {checked} values of D have a border collision"
    );
    // And exactly, at the curve's own points: two_cycle's collision at that D.
    let mut exact_points = 0;
    for cv in &bc {
        for q in cv.points.iter().step_by(10) {
            if let Ok(exact) = border_collision(&Table::fd(q.p).unwrap(), 0.8, 1) {
                if (exact.alpha - q.alpha).abs() < 1e-6 {
                    assert!(
                        (exact.alpha - q.alpha).abs() < 1e-9,
                        "D = {}: {} vs {}",
                        q.p,
                        q.alpha,
                        exact.alpha
                    );
                    exact_points += 1;
                }
            }
        }
    }
    assert!(exact_points >= 10, "{exact_points}");
}

/// Each PD-at-a-border point, by the one-parameter continuation on the curve's side:
/// at D = D* + δ the cycle's branch has a period doubling and a border collision, and
/// the two close in on each other linearly as δ shrinks (the gap halves with δ), at
/// the point's α.
#[test]
fn codimension_two_points_are_confirmed_by_the_one_parameter_continuation() {
    let (_, c) = fd_plane();
    let mut checked = 0;
    for p in c.codim2.iter().filter(|p| p.kind == Codim2Kind::PdBorder) {
        let cv = &c.curves[p.curve];
        let side = cv.points[cv.points.len() / 2].p - p.p;
        let gap = |delta: f64| -> Option<(f64, f64)> {
            let target = p.p + delta.copysign(side);
            let q = cv
                .points
                .iter()
                .min_by(|a, b| (a.p - target).abs().total_cmp(&(b.p - target).abs()))?;
            let ss = one_parameter(q, q.p, 5e-3);
            let nearest = |kind: Kind| {
                ss.iter()
                    .filter(|s| s.kind == kind)
                    .map(|s| s.alpha)
                    .min_by(|a, b| (a - p.alpha).abs().total_cmp(&(b - p.alpha).abs()))
            };
            let (pd, bc) = (
                nearest(Kind::PeriodDoubling)?,
                nearest(Kind::BorderCollision)?,
            );
            assert!(
                (pd - q.alpha).abs() < 1e-9,
                "{p:?}: PD at {pd}, curve at {}",
                q.alpha
            );
            Some(((pd - bc).abs(), (q.p - p.p).abs()))
        };
        let (Some((g1, d1)), Some((g2, d2))) = (gap(2e-3), gap(1e-3)) else {
            continue;
        };
        let ratio = (g2 / d2) / (g1 / d1);
        assert!(
            (ratio - 1.0).abs() < 0.2,
            "{p:?}: gaps {g1} at {d1}, {g2} at {d2}"
        );
        checked += 1;
    }
    assert!(checked >= 2, "only {checked} PD-border points confirmed");
}

/// The flip's criticality against simulation: where the (1, 1) PD curve over D says
/// supercritical, the map just past α_PD, started next to the unstable (1, 1)
/// solution, settles on a two-cycle close to it (its distance ∝ √Δα).
#[test]
fn supercritical_flips_give_a_stable_doubled_orbit() {
    let (_, c) = fd_plane();
    let cv = of(c, "period_doubling", 1)[0];
    let mut checked = 0;
    for q in cv.points.iter().step_by(cv.points.len() / 8) {
        let crit = q.criticality.unwrap();
        let Some(sup) = crit.supercritical() else {
            continue;
        };
        assert!(sup, "D = {}: {:?}", q.p, crit);
        // Past α_PD by Δα and Δα/4: a two-cycle, its split halving (∝ √Δα).
        let split = |da: f64| {
            let sys = System::new(Table::fd(q.p).unwrap(), q.alpha + da, 0.8).unwrap();
            let ph = q.cycle.phases[0];
            let st = State::launch(&sys, 0, ph + 1e-3, q.cycle.velocities[0], 0.0).unwrap();
            let mut map = ImpactMap::new(sys, Solver::Exact, st);
            let mut phases = Vec::new();
            for _ in 0..100_000 {
                phases.push(map.step().unwrap().phase);
            }
            let m = phases.len();
            let (a, b, c2) = (phases[m - 3], phases[m - 2], phases[m - 1]);
            assert!(
                (a - c2).abs() < 1e-9,
                "D = {}: not period two ({a}, {b}, {c2})",
                q.p
            );
            (a - b).abs()
        };
        let (s1, s2) = (split(1e-4), split(2.5e-5));
        assert!(
            s1 < 0.2 && (s1 / s2 - 2.0).abs() < 0.1,
            "D = {}: splits {s1}, {s2}",
            q.p
        );
        checked += 1;
    }
    assert!(checked >= 5);
}

/// The sine's (α, r) plane: the (1, 1) fold curve is the closed-form birth of the
/// (1, 1) pair (where the stable one is born, by a multiplier +1), and on the (1, 1)
/// grazing curve the flight's lowest interior height above the table, found on a dense
/// grid of the flight (a second method), is zero to 1e-9.
#[test]
fn fold_and_grazing_curves_of_the_sine() {
    let plane = Plane {
        table: Table::sine(),
        r: 0.8,
        alpha: (0.005, 0.5),
        second: SweepParam::R,
        window: (0.2, 0.95),
    };
    let c = curves(
        &plane,
        Seeds::FromFixed {
            k: 1,
            max_period: 1,
            at: 0.8,
            count: 5,
        },
    )
    .unwrap();
    // The (1, 1) pair's birth, a smooth fold of the sine, is the closed-form line: on
    // the stability window's own birth, with a multiplier +1 there.
    let fold = of(&c, "birth", 1);
    assert_eq!(fold.len(), 1);
    assert!(of(&c, "fold", 1).is_empty(), "not traced a second time");
    assert!(fold[0].points.len() >= 50);
    for q in &fold[0].points {
        let w = stability_window(&Table::sine(), q.p, 1).unwrap().unwrap();
        assert!(
            (q.alpha - w.alpha_birth).abs() < 1e-10,
            "r = {}: fold at {}, birth {}",
            q.p,
            q.alpha,
            w.alpha_birth
        );
        // A multiplier +1: (1 − λ₁)(1 − λ₂) = 0.
        assert!(q.cycle.fold_test().abs() < 1e-9);
    }
    let graze = of(&c, "grazing", 1);
    assert_eq!(graze.len(), 1, "one (1, 1) grazing curve");
    assert!(graze[0].points.len() >= 50);
    for q in graze[0].points.iter().step_by(5) {
        let lowest = lowest_in_flight(&Table::sine(), q);
        assert!(lowest.abs() < 1e-9, "r = {}: lowest {lowest:e}", q.p);
    }
}

/// The lowest height above the table of the first flight of a point's cycle on an (α,
/// r) plane of `table`, on a grid of 200,000 times across the flight (a second method
/// to the engine's): above the true minimum by at most (Δs)² |g''| / 8.
pub fn lowest_in_flight(table: &Table, q: &CurvePoint) -> f64 {
    let sys = System::new(table.clone(), q.alpha, q.p).unwrap();
    let (ph, v, tau) = (q.cycle.phases[0], q.cycle.velocities[0], q.cycle.flights[0]);
    let f0 = sys.f(ph);
    (1..200_000)
        .map(|j| {
            let s = tau * j as f64 / 200_000.0;
            f0 + v * s - 0.5 * s * s - sys.f((ph + s).rem_euclid(1.0))
        })
        .fold(f64::INFINITY, f64::min)
}

/// The repository's example table file, `assets/tables/quintic.toml`: two quintic
/// pieces, C² everywhere.
fn quintic() -> Table {
    Table::piecewise(
        "quintic kick",
        &[
            (0.0, vec![0.0, 1.5, 0.0, 50.0, -210.9375, 214.84375]),
            (
                0.4,
                vec![
                    1.7407407407407407,
                    -12.851851851851851,
                    58.333333333333336,
                    -121.29629629629629,
                    108.79629629629629,
                    -34.72222222222222,
                ],
            ),
        ],
    )
    .unwrap()
}

/// How far an orbit started next to the (n, n) cycle of the curve point `q`, at α a
/// little past its period doubling on the side where the cycle is unstable, ends from
/// the cycle: the largest phase distance of its last 200 impacts to the nearest of the
/// cycle's impact phases.
fn drift_past_the_flip(table: &Table, q: &CurvePoint, delta: f64) -> f64 {
    let n = q.cycle.n;
    let side = [1.0, -1.0]
        .into_iter()
        .find(|s| {
            let sys = System::new(table.clone(), q.alpha + s * delta, q.p).unwrap();
            bouncemap_engine::orbits::periodic::cycle(
                &sys,
                n,
                q.cycle.k,
                q.cycle.t0,
                q.cycle.velocities[0],
            )
            .is_ok_and(|c| !c.stable)
        })
        .expect("the cycle is unstable on one side");
    let sys = System::new(table.clone(), q.alpha + side * delta, q.p).unwrap();
    let cyc = bouncemap_engine::orbits::periodic::cycle(
        &sys,
        n,
        q.cycle.k,
        q.cycle.t0,
        q.cycle.velocities[0],
    )
    .unwrap();
    let st = State::launch(&sys, 0, cyc.phases[0] + 1e-5, cyc.velocities[0], 0.0).unwrap();
    let mut map = ImpactMap::new(sys, Solver::Exact, st);
    let mut phases = Vec::new();
    for _ in 0..20_000 {
        match map.step() {
            Ok(e) => phases.push(e.phase),
            Err(_) => return f64::INFINITY,
        }
    }
    phases[phases.len() - 200..]
        .iter()
        .map(|&ph| {
            cyc.phases
                .iter()
                .map(|&c| (ph - c).rem_euclid(1.0).min((c - ph).rem_euclid(1.0)))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// The flip's criticality against simulation where both kinds occur: on the (2, 2)
/// period-doubling curve of the quintic table over (α, r), supercritical near r = 0.5
/// and subcritical near r = 0.97 with a degenerate flip between. Just past each
/// supercritical doubling the orbit started next to the (2, 2) cycle stays within a
/// distance that halves when Δα is quartered (the doubled cycle, ∝ √Δα); just past each
/// subcritical one it leaves the cycle's neighbourhood.
#[test]
fn subcritical_flips_lose_the_orbit_and_supercritical_ones_keep_it() {
    let table = quintic();
    let plane = Plane {
        table: table.clone(),
        r: 0.8,
        alpha: (0.005, 1.5),
        second: SweepParam::R,
        window: (0.1, 0.98),
    };
    let (sup, sub) = flips_against_simulation(&plane, 0.8);
    assert!(
        sup >= 10 && sub >= 1,
        "checked {sup} supercritical, {sub} subcritical"
    );
}

/// The sine, a built-in table, has a subcritical flip too: its (2, 2) period doubling
/// turns subcritical near r = 0.98 (a degenerate flip between), and simulation agrees
/// on both sides.
#[test]
fn the_sine_has_a_subcritical_flip_near_r_one() {
    let plane = Plane {
        table: Table::sine(),
        r: 0.8,
        alpha: (0.01, 0.5),
        second: SweepParam::R,
        window: (0.9, 0.99),
    };
    let (sup, sub) = flips_against_simulation(&plane, 0.95);
    assert!(
        sup >= 5 && sub >= 1,
        "checked {sup} supercritical, {sub} subcritical"
    );
}

/// Every fourth decided point of the (2, 2) period-doubling curves of `plane` (seeded
/// at `at`) against simulation; returns how many supercritical and subcritical points
/// were checked.
fn flips_against_simulation(plane: &Plane, at: f64) -> (usize, usize) {
    let table = plane.table.clone();
    let c = curves(
        plane,
        Seeds::FromFixed {
            k: 1,
            max_period: 4,
            at,
            count: 5,
        },
    )
    .unwrap();
    let (mut sup, mut sub) = (0, 0);
    for (i, cv) in c.curves.iter().enumerate() {
        if cv.n != 2 || cv.kind.as_str() != "period_doubling" {
            continue;
        }
        // Near a degenerate flip c → 0 and the cubic normal form holds only for Δα ≪ c²:
        // the fixed steps of the simulation below are not small enough there.
        let degenerate: Vec<f64> = c
            .codim2
            .iter()
            .filter(|p| p.kind == Codim2Kind::DegenerateFlip && p.meets.contains(&i))
            .map(|p| p.p)
            .collect();
        for q in cv.points.iter().step_by(4) {
            let Some(kind) = q.criticality.and_then(|c| c.supercritical()) else {
                continue;
            };
            if degenerate.iter().any(|&p| (q.p - p).abs() < 0.005) {
                continue;
            }
            let d1 = drift_past_the_flip(&table, q, 1e-4);
            if kind {
                let d2 = drift_past_the_flip(&table, q, 2.5e-5);
                assert!(
                    d1 < 0.05 && (d1 / d2 - 2.0).abs() < 0.3,
                    "supercritical at α = {}, r = {}: drifts {d1}, {d2}",
                    q.alpha,
                    q.p
                );
                sup += 1;
            } else {
                assert!(
                    d1 > 0.1,
                    "subcritical at α = {}, r = {}: drift {d1}",
                    q.alpha,
                    q.p
                );
                sub += 1;
            }
        }
        // Where the criticality changes sign on this curve, a degenerate flip is
        // reported between.
        let signs: Vec<bool> = cv
            .points
            .iter()
            .filter_map(|q| q.criticality.and_then(|c| c.supercritical()))
            .collect();
        if signs.windows(2).any(|w| w[0] != w[1]) {
            assert!(
                c.codim2
                    .iter()
                    .any(|p| p.meets.contains(&i) && p.kind == Codim2Kind::DegenerateFlip),
                "curve {i} changes criticality without a degenerate flip"
            );
        }
    }
    (sup, sub)
}
