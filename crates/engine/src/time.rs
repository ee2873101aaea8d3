//! Absolute time as (integer period, phase in [0, 1)): normalisation with checked
//! period arithmetic, ⌊x⌋ for the solvers' hot paths, and wrapping a phase onto the
//! circle. The ground floor under tables, solvers, the map and the orbits.

/// ⌊x⌋, inline: without SSE4.1 the standard library's `floor` is a library call, and
/// this sits on the solvers' hot path. Exact for every f64 (values of magnitude 2⁵² and
/// above are already integers; NaN stays NaN).
#[inline]
pub(crate) fn floor(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        if t > x {
            t - 1.0
        } else {
            t
        }
    } else {
        x
    }
}

/// Normalise (period, phase) so the phase is in [0, 1). The period arithmetic is
/// checked: a sum beyond i64 saturates at i64::MIN or i64::MAX (never wraps), which the
/// map then reports as [`Halt::TimeOutOfRange`](crate::map::Halt::TimeOutOfRange).
#[inline]
pub fn normalize(period: i64, phase: f64) -> (i64, f64) {
    if (0.0..1.0).contains(&phase) {
        return (period, phase);
    }
    let k = floor(phase);
    let mut p = phase - k;
    // `as` saturates for phases beyond i64 (and maps NaN to 0; the solvers never
    // produce one).
    let mut n = period.saturating_add(k as i64);
    if p >= 1.0 {
        p -= 1.0;
        n = n.saturating_add(1);
    }
    (n, p)
}

/// Wrap a phase into [0, 1).
pub fn wrap_phase(t: f64) -> f64 {
    let p = t.rem_euclid(1.0);
    if p >= 1.0 {
        0.0
    } else {
        p
    }
}

/// The phase difference `phase` − `from` wrapped to [−½, ½): which side of `from`
/// (e.g. a breakpoint) `phase` lies on, and how far.
pub fn signed_distance(phase: f64, from: f64) -> f64 {
    let d = (phase - from).rem_euclid(1.0);
    if d >= 0.5 {
        d - 1.0
    } else {
        d
    }
}

/// Circular distance of two phases (at most ½).
pub fn phase_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (period, phase) normalisation saturates instead of wrapping.
    #[test]
    fn normalisation_saturates_at_the_ends_of_i64() {
        assert_eq!(normalize(i64::MAX, 2.5), (i64::MAX, 0.5));
        assert_eq!(normalize(i64::MIN, -2.5), (i64::MIN, 0.5));
        assert_eq!(normalize(5, 1e300).0, i64::MAX);
        assert_eq!(normalize(5, 2.25), (7, 0.25));
        assert_eq!(normalize(5, -0.75), (4, 0.25));
    }
}
