//! Where a ball riding on the table is released: the first instant after which
//! 1 + αF'' < 0, the table accelerating downward faster than gravity. Written once for
//! the f64 map ([`super::Table::release_after`]) and the map at any precision
//! ([`crate::precise`]): the walk over the pieces from the stick on, and the sine's
//! closed form over [`Real`]. What each number type brings is the search on one
//! polynomial piece: at f64 the closed-form roots of [`crate::poly`] with a rigorous sign
//! test (as its landing uses them), at any precision exact isolation by the roots of the
//! derivative.

use crate::real::Real;

/// The first release in a table of `count` pieces, for a ball stuck at `from` on piece
/// `j0`: the pieces are searched in order from there, one period and the rest of the
/// current piece, which covers every phase. `first_on(j, from, strict)` is the first
/// instant on piece j after which the excess is negative: from `from` on the stuck
/// piece (with `strict`, `from` itself does not count), from the piece's start on the
/// others (`None`). Gives the whole periods after the stick's period and what
/// `first_on` found, or None: the ball rests on the table for good.
pub(crate) fn first_release<F, T>(
    count: usize,
    j0: usize,
    from: &F,
    strictly_after: bool,
    mut first_on: impl FnMut(usize, Option<&F>, bool) -> Option<T>,
) -> Option<(i64, T)> {
    let (mut periods, mut j) = (0i64, j0);
    for step in 0..=count {
        let (from, strict) = if step == 0 {
            (Some(from), strictly_after)
        } else {
            (None, false)
        };
        if let Some(found) = first_on(j, from, strict) {
            return Some((periods, found));
        }
        j += 1;
        if j == count {
            j = 0;
            periods += 1;
        }
    }
    None
}

/// On the sine F = sin ωt̂ (ω = 2π) the excess 1 − αω² sin ωt̂ is negative on
/// (θ, ½ − θ), θ = asin(1/(αω²))/ω: the first phase in [`from`, 1) after which it is
/// negative (with `strict`, `from` itself does not count), or None. Never negative if
/// αω² ≤ 1.
pub(crate) fn sine_release_in<R: Real>(
    alpha: &R,
    omega: &R,
    from: &R,
    strict: bool,
    ctx: &R::Context,
) -> Option<R> {
    let one = R::from_f64(1.0, ctx);
    let c = omega.clone() * omega.clone() * alpha.clone();
    if c <= one {
        return None;
    }
    let theta = (one / c).asin() / omega.clone();
    let half = R::from_f64(0.5, ctx);
    if !strict && *from > theta && *from < half - theta.clone() {
        Some(from.clone())
    } else if *from < theta {
        Some(theta)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn the_walk_goes_round_once_and_counts_periods() {
        // Three pieces, a release only on piece 1 at its start: from piece 2 it is found
        // a period later; from piece 1 itself at once unless strict.
        let found = |j: usize, from: Option<&f64>, strict: bool| {
            (j == 1 && !(strict && from.is_some())).then_some(j)
        };
        assert_eq!(first_release(3, 2, &0.7, false, found), Some((1, 1)));
        assert_eq!(first_release(3, 1, &0.4, false, found), Some((0, 1)));
        assert_eq!(first_release(3, 1, &0.4, true, found), Some((1, 1)));
        assert_eq!(first_release(3, 0, &0.1, false, |_, _, _| None::<()>), None);
    }

    #[test]
    fn the_sine_releases_where_its_acceleration_passes_gravity() {
        let (alpha, omega) = (0.05, 2.0 * PI);
        let theta = sine_release_in(&alpha, &omega, &0.0, false, &()).expect("αω² > 1");
        // There 1 + αF'' = 1 − αω² sin ωθ = 0.
        assert!((1.0 - alpha * omega * omega * (omega * theta).sin()).abs() < 1e-14);
        // Inside (θ, ½ − θ) at once, unless strict; past ½ − θ not in this period.
        assert_eq!(sine_release_in(&alpha, &omega, &0.2, false, &()), Some(0.2));
        assert_eq!(sine_release_in(&alpha, &omega, &0.2, true, &()), None);
        assert_eq!(sine_release_in(&alpha, &omega, &0.6, false, &()), None);
        // αω² ≤ 1: the table never pulls away.
        assert_eq!(sine_release_in(&0.02, &omega, &0.0, false, &()), None);
    }
}
