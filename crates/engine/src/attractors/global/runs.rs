//! Continuations on the cubic table at r = 0.8 (small grids: seconds in a debug
//! build), checked against the (1, k) and (2, 2k) solutions' closed forms and
//! Newton solutions, and against `basins` on the same grid.

use super::*;
use crate::attractors::basins;
use crate::attractors::Kind;
use crate::orbits::fixed::stability_window;
use crate::orbits::two_cycle::two_cycle;
use crate::table::Table;

fn spec(lo: f64, hi: f64, steps: usize, n: usize) -> GlobalSpec {
    let sys = System::new(Table::fd(1.0).unwrap(), hi, 0.8).unwrap();
    GlobalSpec {
        w_max: crate::attractors::default_w_max(&sys),
        sys,
        lo,
        hi,
        steps,
        nx: n,
        ny: n,
        settle: Settle::BASINS,
        stop_at_known: true,
        sampled_starts: 0,
    }
}

fn run(spec: GlobalSpec) -> Continuation {
    collect(
        spec,
        &Executor::new(2).unwrap(),
        &Control::new(),
        &mut |_| {},
    )
    .unwrap()
}

#[test]
fn one_stable_cycle_takes_every_start_with_no_basin_entropy() {
    // Past the (1, 1) solution's period doubling every start of the box lands on
    // the (2, 2) cycle: the one attractor, fraction 1, S_b = 0 and no boundary. Its
    // point is an impact of the (2, 2) solution found by Newton's method.
    let cont = run(spec(0.5, 0.54, 3, 20));
    assert_eq!(cont.tracks().len(), 1, "{:?}", cont.steps());
    assert!(cont.changes().is_empty());
    for s in cont.steps() {
        let m = &s.members[..];
        assert_eq!(m.len(), 1);
        assert_eq!((m[0].kind, m[0].period()), (Kind::Periodic, Some((2, 2))));
        assert_eq!((m[0].starts, m[0].fraction), (400, 1.0));
        let e = s.entropy.unwrap();
        assert_eq!((e.s_b, e.s_bb, e.boundary_boxes), (0.0, 0.0, 0));
        let sys = System::new(Table::fd(1.0).unwrap(), s.alpha, 0.8).unwrap();
        let tc = two_cycle(&sys, 1).unwrap();
        let (t, v) = m[0].point.unwrap();
        let near =
            |pt: f64, pv: f64| crate::time::phase_distance(t, pt) < 1e-9 && (v - pv).abs() < 1e-9;
        assert!(
            near(tc.phase0, tc.v0) || near(tc.phase1, tc.v1),
            "{t} {v} {tc:?}"
        );
    }
}

#[test]
fn the_period_doubling_is_seen_within_one_step_of_its_closed_form() {
    // The (1, 1) solution's α_PD from its closed-form stability window; the track
    // that holds (1, 1) holds (2, 2) from the first α past it.
    let pd = stability_window(&Table::fd(1.0).unwrap(), 0.8, 1)
        .unwrap()
        .unwrap()
        .alpha_pd()
        .unwrap();
    let cont = run(spec(0.4805, 0.4875, 8, 12));
    let steps = cont.steps();
    let doubling: Vec<&Change> = cont
        .changes()
        .iter()
        .filter(|c| {
            c.what
                == ChangeKind::Period {
                    from: (1, 1),
                    to: (2, 2),
                }
        })
        .collect();
    assert_eq!(doubling.len(), 1, "{:?}", cont.changes());
    let c = doubling[0];
    assert!(
        steps[c.step - 1].alpha < pd && pd < steps[c.step].alpha,
        "{pd} {c:?}"
    );
}

#[test]
fn fractions_at_an_alpha_are_the_basins_pictures() {
    // Coexistence on the cubic table at α = 0.47: the same grid and box as
    // `basins` give the same starts per attractor (seeds are not counted).
    let cont = run(spec(0.465, 0.47, 2, 30));
    let last = cont.steps().last().unwrap();
    let b = basins::collect(
        &basins::BasinSpec {
            nx: 30,
            ny: 30,
            ..basins::BasinSpec::new(System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap())
        },
        &Executor::new(2).unwrap(),
    )
    .unwrap();
    let mut ours: Vec<(Kind, usize)> = last.members.iter().map(|m| (m.kind, m.starts)).collect();
    let mut theirs: Vec<(Kind, usize)> = b
        .registry()
        .attractors()
        .iter()
        .map(|a| (a.kind, a.starts))
        .collect();
    ours.retain(|m| m.1 > 0);
    ours.sort();
    theirs.sort();
    assert!(ours.len() >= 2, "{ours:?}");
    assert_eq!(ours.len(), theirs.len(), "{ours:?} {theirs:?}");
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.0, b.0);
        assert!(a.1.abs_diff(b.1) <= 9, "{ours:?} {theirs:?}");
    }
    let total: usize = last.members.iter().map(|m| m.starts).sum::<usize>() + last.not_settled;
    assert_eq!(total, 900);
}

#[test]
fn halving_the_step_finds_the_same_changes() {
    // Every change of a run with step h is found with step h / 2 in the same
    // interval of the coarse grid, and the other way round; attractors are paired
    // at the shared α values by their kind and starts (the pictures there are the
    // same grid).
    let coarse = run(spec(0.478, 0.49, 7, 12));
    let fine = run(spec(0.478, 0.49, 13, 12));
    // Tracks paired by the pictures at shared α.
    let mut pair = std::collections::HashSet::new();
    for (i, s) in coarse.steps().iter().enumerate() {
        let f = &fine.steps()[2 * i];
        assert_eq!(s.alpha, f.alpha);
        for m in &s.members {
            let twin = f
                .members
                .iter()
                .find(|x| x.kind == m.kind && x.starts == m.starts && x.period() == m.period());
            let twin = twin.unwrap_or_else(|| panic!("{m:?} in {:?}", f.members));
            pair.insert((m.track, twin.track));
        }
    }
    let interval = |fine_step: usize| fine_step.div_ceil(2);
    // A sticking cycle's itinerary changes from one α to the next, and a length
    // double precision leaves open hides a change: periods of sticking cycles are
    // samples, not events to compare.
    let sampled = |cont: &Continuation, c: &Change| {
        matches!(c.what, ChangeKind::Period { .. })
            && cont.steps()[c.step]
                .members
                .iter()
                .any(|m| m.track == c.track && m.kind == Kind::Sticking)
    };
    let changes = |cont: &Continuation| -> Vec<Change> {
        cont.changes()
            .iter()
            .filter(|c| !sampled(cont, c))
            .cloned()
            .collect()
    };
    let (coarse_changes, fine_changes) = (changes(&coarse), changes(&fine));
    assert!(coarse_changes.len() >= 3, "{coarse_changes:?}");
    for c in &coarse_changes {
        let seen = fine_changes.iter().any(|f| {
            f.what.name() == c.what.name()
                && pair.contains(&(c.track, f.track))
                && interval(f.step) == c.step
        });
        assert!(seen, "{c:?} not in {fine_changes:?}");
    }
    for f in &fine_changes {
        let seen = coarse_changes.iter().any(|c| {
            f.what.name() == c.what.name()
                && pair.contains(&(c.track, f.track))
                && interval(f.step) == c.step
        });
        // A change undone within one coarse interval is not seen from its ends: an
        // attractor gone and one born (the same, found again) or a change and its
        // reverse.
        let found_again = |a: &ChangeKind, b: &ChangeKind| {
            matches!(
                (a, b),
                (ChangeKind::Birth, ChangeKind::Death { .. })
                    | (ChangeKind::Death { .. }, ChangeKind::Birth)
            )
        };
        let undone = fine_changes.iter().any(|g| {
            g.step != f.step
                && interval(g.step) == interval(f.step)
                && (g.track == f.track || found_again(&f.what, &g.what))
        });
        assert!(seen || undone, "{f:?} not in {coarse_changes:?}");
    }
}

/// The parts of `spec`'s window that shard `i` of `n` computes (from the value before
/// its own, after the first), each run by itself.
fn part(spec: &GlobalSpec, i: usize, n: usize) -> Continuation {
    let (a, b) = (i * spec.steps / n, (i + 1) * spec.steps / n);
    let mut cont = Continuation::part(spec.clone(), a.saturating_sub(1)..b).unwrap();
    let executor = Executor::new(2).unwrap();
    while let Some(next) = cont.prepare(&mut |_| false) {
        let next = next.unwrap();
        let mut basins = next.basins();
        executor.run(next.job().unwrap(), &Control::new(), |b| {
            basins.absorb(b.data);
        });
        cont.absorb(next, &basins);
    }
    cont
}

#[test]
fn parts_joined_are_the_whole_window() {
    // Across the coexistence of the (1, 1) cycle and the (2, 2) cycle born at its
    // period doubling, and the (1, 1) cycle's death: the window in three parts, each
    // started afresh one value early, joined, is the run over the whole window (a
    // second computation of every picture, matched at the joining values).
    let spec = spec(0.44, 0.5, 13, 16);
    let whole = run(spec.clone());
    assert!(!whole.changes().is_empty(), "{:?}", whole.steps());
    let (mut joined, mut joins) = (part(&spec, 0, 3), Vec::new());
    for i in 1..3 {
        let (j, how) = joined.join(part(&spec, i, 3)).unwrap();
        joined = j;
        joins.push(how);
    }
    assert_eq!(joined.steps(), whole.steps());
    assert_eq!(joined.changes(), whole.changes());
    assert_eq!(joined.tracks(), whole.tracks());
    for j in &joins {
        assert_eq!((j.only_before, j.only_after), (0, 0), "{j:?}");
        assert_eq!(j.fraction_difference, 0.0, "{j:?}");
        assert_eq!(j.alpha, whole.steps()[j.step].alpha);
    }
    // Parts that do not meet at one value, or of another window, are refused.
    assert!(part(&spec, 0, 3).join(part(&spec, 2, 3)).is_err());
    let other = GlobalSpec {
        hi: 0.51,
        ..spec.clone()
    };
    assert!(part(&spec, 0, 3).join(part(&other, 1, 3)).is_err());
}

#[test]
fn a_part_is_rebuilt_from_what_it_keeps_and_checked() {
    let spec = spec(0.47, 0.49, 4, 10);
    let p = part(&spec, 1, 2);
    let rebuilt = |steps: Vec<Step>| {
        Continuation::from_parts(
            spec.clone(),
            p.values(),
            steps,
            p.changes().to_vec(),
            p.tracks().to_vec(),
        )
    };
    let again = rebuilt(p.steps().to_vec()).unwrap();
    assert_eq!(
        (again.steps(), again.changes(), again.tracks()),
        (p.steps(), p.changes(), p.tracks())
    );
    // An α value moved, a start lost, a fraction changed: each refused.
    let mut moved = p.steps().to_vec();
    moved[1].alpha += 1e-12;
    assert!(rebuilt(moved).unwrap_err().contains("not value"));
    let mut lost = p.steps().to_vec();
    lost[0].members[0].starts -= 1;
    assert!(rebuilt(lost).unwrap_err().contains("starts"));
    let mut share = p.steps().to_vec();
    share[0].members[0].fraction *= 0.5;
    assert!(rebuilt(share).is_err());
    assert!(rebuilt(p.steps()[1..].to_vec()).is_err());
}

#[test]
fn another_picture_at_a_value_finds_its_attractors_tracks() {
    // A finer picture at an α of the continuation (another grid of starts): each of
    // its cycles is the member of the same kind and (n, k), and every member is found.
    let spec = spec(0.46, 0.48, 3, 16);
    let cont = run(spec.clone());
    let step = &cont.steps()[1];
    let picture = basins::collect(
        &BasinSpec {
            nx: 27,
            ny: 23,
            ..spec.basins(1).unwrap()
        },
        &Executor::new(2).unwrap(),
    )
    .unwrap();
    let attractors = picture.registry().attractors();
    let tracks = tracks_of(attractors, &step.members);
    assert!(step.members.len() >= 2, "{:?}", step.members);
    for m in &step.members {
        let found: Vec<usize> = (0..attractors.len())
            .filter(|&i| tracks[i] == Some(m.track))
            .collect();
        assert_eq!(found.len(), 1, "{m:?} {tracks:?}");
        let a = &attractors[found[0]];
        assert_eq!((a.kind, a.period()), (m.kind, m.period()), "{m:?}");
    }
}
