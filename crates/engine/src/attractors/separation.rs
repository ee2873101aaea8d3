//! Whether a manifold separates basins: pairs of starts on either side of it, each run to
//! its attractor.
//!
//! A basin boundary is the closure of a saddle's stable manifold: starts just on one
//! side of it go to one attractor, just on the other side to another. This module tests
//! that of a computed manifold: at points spread along its branches it puts two starts
//! at ± `offset` along the manifold's normal (in (t, v), the normal from the two
//! neighbouring points), runs each as the basins picture does ([`settle`] with the
//! same [`Settle`]), and counts the pairs whose starts end on different attractors.
//! Pairs with a start that is not a launch (v ≤ f'(t)) are left out and counted.
//!
//! On a fractal boundary a split also happens across no curve in particular, so the
//! count means something only beside [`baseline`]: the same pairs at places spread
//! over the box. Across a manifold that lies in the boundary the split fraction stays
//! as the offset shrinks; the baseline's falls.

use super::{settle, Registry, Settle};
use crate::orbits::manifold::Manifold;
use crate::run::start::launch;
use crate::system::System;
use crate::time::wrap_phase;

/// The pairs tested at most per manifold (spread evenly along its branches).
pub const MAX_PAIRS: usize = 400;

/// What the pairs across a manifold did.
#[derive(Clone, Debug, PartialEq)]
pub struct Separation {
    /// The distance of each start from the manifold.
    pub offset: f64,
    /// Pairs run (both starts launches).
    pub pairs: usize,
    /// Pairs whose two starts went to different attractors.
    pub split: usize,
    /// Pairs left out: a start that is not a launch.
    pub skipped: usize,
}

impl Separation {
    /// The share of the pairs run that split (0 if none were).
    pub fn fraction(&self) -> f64 {
        if self.pairs == 0 {
            0.0
        } else {
            self.split as f64 / self.pairs as f64
        }
    }
}

/// Run pairs of starts ± `offset` across `m` (at most [`MAX_PAIRS`], the saddle
/// itself left out) to their attractors, registered in `registry`. None if cancelled.
pub fn separation(
    sys: &System,
    m: &Manifold,
    offset: f64,
    how: &Settle,
    registry: &mut Registry,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Separation> {
    // (point, normal) at every interior point of every branch.
    let mut sites = Vec::new();
    for b in &m.branches {
        for w in b.points.windows(3) {
            let d = [w[2][0] - w[0][0], w[2][1] - w[0][1]];
            let len = d[0].hypot(d[1]);
            if len > 0.0 {
                sites.push((w[1], [-d[1] / len, d[0] / len]));
            }
        }
    }
    let stride = sites.len().div_ceil(MAX_PAIRS).max(1);
    let sites = sites.into_iter().step_by(stride);
    pairs(sys, sites, offset, how, registry, cancelled)
}

/// The same test at `count` places spread over the launch box t̂ ∈ [0, 1), w ∈ (0, w_max]
/// (a low-discrepancy sequence, each pair across a direction of its own): what pairs
/// that straddle no particular curve do, the baseline a manifold's pairs are compared
/// with. On a smooth boundary it falls in proportion to the offset, on a fractal one as
/// a power of it (the uncertainty exponent). None if cancelled.
pub fn baseline(
    sys: &System,
    w_max: f64,
    count: usize,
    offset: f64,
    how: &Settle,
    registry: &mut Registry,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Separation> {
    // The R₃ sequence (Roberts): fractional parts of i·(1/φ₃, 1/φ₃², 1/φ₃³).
    const G: f64 = 1.220_744_084_605_759_5;
    let a = [1.0 / G, 1.0 / (G * G), 1.0 / (G * G * G)];
    let sites = (1..=count).map(|i| {
        let x = a.map(|c| (0.5 + c * i as f64).fract());
        let (t, w) = (x[0], w_max * x[1]);
        let angle = std::f64::consts::TAU * x[2];
        // The place in (t, v), and a direction of its own.
        ([t, sys.df(t) + w], [angle.cos(), angle.sin()])
    });
    pairs(sys, sites, offset, how, registry, cancelled)
}

/// Run the pair of starts ± `offset` along `n` from each place `p` (in (t, v)) to
/// their attractors, registered in `registry`, and count the pairs that split. None if
/// cancelled.
fn pairs(
    sys: &System,
    sites: impl Iterator<Item = ([f64; 2], [f64; 2])>,
    offset: f64,
    how: &Settle,
    registry: &mut Registry,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Separation> {
    let mut out = Separation {
        offset,
        pairs: 0,
        split: 0,
        skipped: 0,
    };
    for (p, n) in sites {
        let mut ids = [0usize; 2];
        let mut launched = true;
        for (id, sign) in ids.iter_mut().zip([1.0, -1.0]) {
            let t = wrap_phase(p[0] + sign * offset * n[0]);
            let v = p[1] + sign * offset * n[1];
            let w = v - sys.df(t);
            let Some(start) = (w > 0.0).then(|| launch(sys, t, w)).flatten() else {
                launched = false;
                break;
            };
            let (found, ..) = settle(sys, start, how, 1, cancelled)?;
            *id = registry.assign(&found);
        }
        if !launched {
            out.skipped += 1;
            continue;
        }
        out.pairs += 1;
        if ids[0] != ids[1] {
            out.split += 1;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::orbits::fixed::fixed_points;
    use crate::orbits::manifold::{manifold, Kind, ManifoldSpec};
    use crate::orbits::periodic::cycle;
    use crate::table::Table;

    /// The cubic table at α = 0.47, r = 0.8: the stable (1, 1) focus and a sticking
    /// cycle coexist; the (1, 1) saddle.
    fn saddle_and_system() -> (System, crate::orbits::periodic::CyclePoint) {
        let sys = System::new(Table::fd(1.0).unwrap(), 0.47, 0.8).unwrap();
        let c = fixed_points(&sys, 1)
            .unwrap()
            .iter()
            .filter_map(|fp| cycle(&sys, 1, 1, fp.phase, fp.v).ok())
            .find(|c| !c.stable)
            .unwrap();
        (sys, c)
    }

    #[test]
    fn the_stable_manifold_lies_in_the_fractal_basin_boundary() {
        // The basin boundary of the cubic table at α = 0.47 is fractal: the unstable
        // manifold of the (1, 1) saddle runs into both basins at every scale, so pairs
        // across its stable manifold split about as often as a coin toss, at every
        // offset. Pairs at places that straddle no particular curve split less and less
        // often as the offset shrinks (a power law: the uncertainty exponent). The
        // manifold's pairs keep splitting: it lies in the boundary.
        let (sys, c) = saddle_and_system();
        let spec = ManifoldSpec {
            length: 2.0,
            ..ManifoldSpec::default()
        };
        let how = Settle::BASINS;
        let stable = manifold(&sys, &c, Kind::Stable, &spec).unwrap();
        let mut reg = Registry::new();
        let mut base = Vec::new();
        for offset in [1e-2, 1e-5, 1e-8] {
            let s = separation(&sys, &stable, offset, &how, &mut reg, &mut |_| false).unwrap();
            let b = baseline(&sys, 1.0, 400, offset, &how, &mut reg, &mut |_| false).unwrap();
            assert!(s.pairs > 200 && b.pairs > 350, "{s:?} {b:?}");
            assert!(s.fraction() > 0.4, "{s:?}");
            base.push(b.fraction());
            if offset < 1e-4 {
                assert!(s.fraction() > 2.0 * b.fraction(), "{s:?} {b:?}");
            }
        }
        assert!(base[0] > base[1] && base[1] > base[2], "{base:?}");
        // Two attractors only: the (1, 1) focus and a sticking cycle.
        assert_eq!(reg.attractors().len(), 2);
    }
}
