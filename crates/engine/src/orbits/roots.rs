//! Roots of one real function on a bracket, for the orbits' event location: Illinois
//! false position with a bisection safeguard, to a few ulps ([`bracketed_root`]; with
//! failed evaluations allowed, [`bracketed_root_nan`]).

/// Root of `g` in [lo, hi] where g(lo) and g(hi) differ in sign (Illinois false
/// position with bisection safeguard), to the last few ulps.
pub(crate) fn bracketed_root(g: &dyn Fn(f64) -> f64, lo: f64, hi: f64) -> Option<f64> {
    let (glo, ghi) = (g(lo), g(hi));
    if glo == 0.0 {
        return Some(lo);
    }
    if ghi == 0.0 {
        return Some(hi);
    }
    if !(glo.is_finite() && ghi.is_finite()) || (glo < 0.0) == (ghi < 0.0) {
        return None;
    }
    Some(
        match illinois(&mut |x| g(x), (lo, hi), (glo, ghi), 300, 4) {
            Illinois::Root(x) => x,
            Illinois::Bracket { lo, hi, glo, ghi } => {
                if glo.abs() <= ghi.abs() {
                    lo
                } else {
                    hi
                }
            }
        },
    )
}

/// How [`illinois`] ended: on an exact zero, or with a bracket a few ulps wide.
pub(crate) enum Illinois {
    Root(f64),
    Bracket {
        lo: f64,
        hi: f64,
        glo: f64,
        ghi: f64,
    },
}

/// Illinois false position on [lo, hi] from end values of opposite signs, a bisection
/// every `bisect_every`-th step, at most `iterations` evaluations, until the bracket is
/// a few ulps wide. A failed evaluation (NaN) moves the upper end down to it.
pub(crate) fn illinois(
    g: &mut dyn FnMut(f64) -> f64,
    (mut lo, mut hi): (f64, f64),
    (mut glo, mut ghi): (f64, f64),
    iterations: usize,
    bisect_every: usize,
) -> Illinois {
    let mut side = 0;
    for i in 0..iterations {
        let mut x = (lo * ghi - hi * glo) / (ghi - glo);
        if !(x > lo && x < hi) || i % bisect_every == bisect_every - 1 {
            x = 0.5 * (lo + hi);
        }
        if x <= lo || x >= hi {
            break;
        }
        let gx = g(x);
        if gx == 0.0 {
            return Illinois::Root(x);
        }
        if gx.is_nan() {
            hi = x;
            continue;
        }
        if (gx < 0.0) == (glo < 0.0) {
            lo = x;
            glo = gx;
            if side == 1 {
                ghi *= 0.5;
            }
            side = 1;
        } else {
            hi = x;
            ghi = gx;
            if side == -1 {
                glo *= 0.5;
            }
            side = -1;
        }
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) {
            break;
        }
    }
    Illinois::Bracket { lo, hi, glo, ghi }
}

/// A root of `g` on [lo, hi] from known end values of opposite signs, by Illinois false
/// position with bisection every few steps; a failed evaluation (NaN) halves toward
/// `lo`. To a few ulps of the arclength.
pub(crate) fn bracketed_root_nan(
    g: &mut dyn FnMut(f64) -> f64,
    lo: f64,
    hi: f64,
    glo: f64,
    ghi: f64,
) -> Option<f64> {
    Some(match illinois(g, (lo, hi), (glo, ghi), 200, 3) {
        Illinois::Root(x) => x,
        // The end past the crossing: continuing from it does not meet the same one again.
        Illinois::Bracket { hi, .. } => hi,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bracketed_root_finds_cube_root() {
        let r = bracketed_root(&|x| x * x * x - 2.0, 0.0, 2.0).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
        assert!(bracketed_root(&|x| x * x + 1.0, -1.0, 1.0).is_none());
    }
}
