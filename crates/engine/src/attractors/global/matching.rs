//! Which attractor at one α value is which at the next: the Hausdorff distance of their
//! point sets ([`match_sets`]), then where the seeds of the ones left over went
//! ([`match_by_seeds`]).

use super::{MATCH_DISTANCE, MAX_SET};
use crate::attractors::{Attractor, Kind};
use crate::time::phase_distance;

/// Whether attractors of these kinds may be one attractor at neighbouring α: a
/// resting ball only with a resting ball, an escape only with an escape.
fn compatible(a: Kind, b: Kind) -> bool {
    let special = |k| matches!(k, Kind::Resting | Kind::Escaping);
    if special(a) || special(b) {
        a == b
    } else {
        true
    }
}

/// Pairs (old id, new id), closest first, one to one, within [`MATCH_DISTANCE`].
pub(super) fn match_sets(old: &[Attractor], new: &[Attractor]) -> Vec<(usize, usize)> {
    let sets = |all: &[Attractor]| -> Vec<(Kind, Vec<(f64, f64)>)> {
        all.iter()
            .map(|a| (a.kind, spread(a.points(), MAX_SET)))
            .collect()
    };
    match_point_sets(&sets(old), &sets(new))
}

/// Pairs (old, new) of point sets of attractors of the given kinds, closest first, one
/// to one, within [`MATCH_DISTANCE`]. A picture has one class of resting balls and
/// one of escapes (wherever each ball came to rest or left): each is at distance 0 of
/// its like.
pub(super) fn match_point_sets(
    old: &[(Kind, Vec<(f64, f64)>)],
    new: &[(Kind, Vec<(f64, f64)>)],
) -> Vec<(usize, usize)> {
    let mut candidates = Vec::new();
    for (o, (ka, a)) in old.iter().enumerate() {
        for (c, (kb, b)) in new.iter().enumerate() {
            if !compatible(*ka, *kb) {
                continue;
            }
            let d = if matches!(ka, Kind::Escaping | Kind::Resting) {
                Some(0.0)
            } else {
                hausdorff_within(a, b, MATCH_DISTANCE)
            };
            if let Some(d) = d {
                candidates.push((d, o, c));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let (mut used_old, mut used_new) = (vec![false; old.len()], vec![false; new.len()]);
    let mut pairs = Vec::new();
    for (_, o, c) in candidates {
        if !used_old[o] && !used_new[c] {
            used_old[o] = true;
            used_new[c] = true;
            pairs.push((o, c));
        }
    }
    pairs
}

/// Pairs (old id, new id) of the old attractors `pairs` left unmatched, each with the
/// new attractor most of its seeds went to, where that one is unmatched too and of a
/// compatible kind: the old attractor's points lie in its basin and nothing else
/// continues either (a sticking cycle whose itinerary changed, say). Where several old
/// attractors' seeds went to one new attractor, one of the same kind goes first, then
/// the one with the larger share of its seeds there.
pub(super) fn match_by_seeds(
    old: &[Attractor],
    new: &[Attractor],
    old_tracks: &[usize],
    landed: &[(usize, usize)],
    pairs: &[(usize, usize)],
) -> Vec<(usize, usize)> {
    let mut used_new: Vec<bool> = (0..new.len())
        .map(|c| pairs.iter().any(|p| p.1 == c))
        .collect();
    let mut candidates = Vec::new();
    for o in (0..old.len()).filter(|&o| pairs.iter().all(|p| p.0 != o)) {
        let mut votes = vec![0usize; new.len()];
        for &(t, c) in landed {
            if t == old_tracks[o] {
                votes[c] += 1;
            }
        }
        let seeds: usize = votes.iter().sum();
        let best = (0..new.len())
            .filter(|&c| votes[c] > 0)
            .max_by_key(|&c| (votes[c], usize::MAX - c));
        if let Some(c) = best {
            if compatible(old[o].kind, new[c].kind) {
                let share = votes[c] as f64 / seeds as f64;
                candidates.push((old[o].kind != new[c].kind, -share, o, c));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut out = Vec::new();
    for (_, _, o, c) in candidates {
        if !used_new[c] {
            used_new[c] = true;
            out.push((o, c));
        }
    }
    out
}

/// Which member of a continuation's step at this α each attractor of another picture
/// of the same system is (its track), by the distance of their point sets as
/// neighbouring α values are matched: `tracks[id]` for each attractor of `picture`,
/// None where none is within [`MATCH_DISTANCE`]. A picture of another grid at the same
/// α holds the same cycles (at distance ≈ 0) and chaotic sets close to the member's.
pub fn tracks_of(picture: &[Attractor], members: &[super::Member]) -> Vec<Option<usize>> {
    let sets: Vec<(Kind, Vec<(f64, f64)>)> = picture
        .iter()
        .map(|a| (a.kind, spread(a.points(), MAX_SET)))
        .collect();
    let theirs: Vec<(Kind, Vec<(f64, f64)>)> =
        members.iter().map(|m| (m.kind, m.points.clone())).collect();
    let mut tracks = vec![None; picture.len()];
    for (a, m) in match_point_sets(&sets, &theirs) {
        tracks[a] = Some(members[m].track);
    }
    tracks
}

/// At most `most` points of `set`, evenly spread over it.
pub(super) fn spread(set: Vec<(f64, f64)>, most: usize) -> Vec<(f64, f64)> {
    if set.len() <= most {
        return set;
    }
    let n = set.len();
    (0..most).map(|s| set[s * n / most]).collect()
}

/// The distance of two points: the larger of the phase distance around the circle and
/// the velocity difference.
fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    phase_distance(a.0, b.0).max((a.1 - b.1).abs())
}

/// The Hausdorff distance of two point sets (∞ if one is empty and the other not).
pub fn hausdorff(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    hausdorff_within(a, b, f64::INFINITY).unwrap_or(f64::INFINITY)
}

/// The Hausdorff distance of two point sets if it is at most `limit`, else None.
///
/// Cheap where sets are far apart or close: the smallest and the largest velocity of
/// two sets within `limit` differ by at most `limit` (each extreme point of one set
/// has a point of the other within `limit`), and the search for a point's nearest
/// neighbour stops at one nearer than the largest distance found so far, which that
/// point cannot raise (Taha and Hanbury's early break).
pub fn hausdorff_within(a: &[(f64, f64)], b: &[(f64, f64)], limit: f64) -> Option<f64> {
    if a.is_empty() || b.is_empty() {
        return (a.is_empty() && b.is_empty()).then_some(0.0);
    }
    let range = |s: &[(f64, f64)]| {
        s.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            })
    };
    let (ra, rb) = (range(a), range(b));
    if (ra.0 - rb.0).abs() > limit || (ra.1 - rb.1).abs() > limit {
        return None;
    }
    let one_way = |x: &[(f64, f64)], y: &[(f64, f64)], mut worst: f64| -> Option<f64> {
        for &p in x {
            let mut nearest = f64::INFINITY;
            for &q in y {
                nearest = nearest.min(distance(p, q));
                if nearest <= worst {
                    break;
                }
            }
            if nearest > limit {
                return None;
            }
            worst = worst.max(nearest);
        }
        Some(worst)
    };
    let there = one_way(a, b, 0.0)?;
    one_way(b, a, there)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hausdorff_distance_wraps_the_phase() {
        let a = [(0.01, 0.5), (0.5, 0.6)];
        let b = [(0.99, 0.5), (0.5, 0.6), (0.51, 0.62)];
        assert!((hausdorff(&a, &b) - 0.02).abs() < 1e-15);
        assert_eq!(hausdorff(&a, &a), 0.0);
        assert_eq!(hausdorff(&a, &[]), f64::INFINITY);
        // Within a limit: the same value, or None beyond it.
        assert_eq!(hausdorff_within(&a, &b, 0.05), Some(hausdorff(&a, &b)));
        assert_eq!(hausdorff_within(&a, &b, 0.01), None);
        // Against a brute-force double loop, on random sets.
        let mut rng = crate::test_rng::Xorshift::new(3);
        for _ in 0..50 {
            let mut set =
                |n| -> Vec<(f64, f64)> { (0..n).map(|_| (rng.next(), rng.next())).collect() };
            let (x, y) = (set(17), set(9));
            let brute = |p: &[(f64, f64)], q: &[(f64, f64)]| {
                p.iter()
                    .map(|&u| {
                        q.iter()
                            .map(|&w| distance(u, w))
                            .fold(f64::INFINITY, f64::min)
                    })
                    .fold(0.0, f64::max)
            };
            let h = brute(&x, &y).max(brute(&y, &x));
            assert_eq!(hausdorff(&x, &y), h);
            assert_eq!(hausdorff_within(&x, &y, h), Some(h));
            assert_eq!(hausdorff_within(&x, &y, h * 0.999), None);
        }
    }
}
