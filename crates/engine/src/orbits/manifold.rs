//! The unstable and stable manifolds of a saddle cycle, grown from their fundamental
//! domains.
//!
//! For a saddle (n, k) cycle (real multipliers λᵤ, λₛ with |λᵤ| > 1 > |λₛ|), G is the
//! n-step map, or the 2n-step map where the multiplier is negative, so that each side
//! of the saddle is invariant. The unstable manifold is grown under G, the stable one
//! under G⁻¹ (by the inverse map, [`crate::InverseMap`]: each step back is the previous
//! launch, found exactly and checked by a forward step). μ is the growth factor along
//! the manifold's eigenvector: λᵤ (or λᵤ²) for the unstable, 1/λₛ (or 1/λₛ²) for the
//! stable manifold. Coordinates are the launch (t, v), t the time measured on from the
//! saddle's launch (not wrapped into a phase), so a branch is a continuous curve.
//!
//! Each side σ = ±1 of the eigenvector e gives a branch, the union of the images
//! Hʲ(D) (H = G or G⁻¹) of the fundamental domain D = {p + σ s e : δ ≤ s ≤ μδ}. A
//! segment of D is within O(δ²) of the manifold, and that error shrinks by λₛ/λᵤ at
//! each iteration.
//!
//! Every point of a branch is Hʲ(p + σ s e) for a level j and a parameter s, computed
//! by the exact map or its exact inverse from that start: never interpolated. A level
//! starts from the previous level's parameters. Where neighbouring points lie more than
//! the step apart, or the curve turns by more than [`MAX_ANGLE`], the parameter
//! interval is halved.
//!
//! A branch ends for a reason ([`BranchEnd`]):
//! * its arc length reaches the length asked;
//! * a point's orbit sticks to the table, grazes it, or does not land;
//! * backward, a point's orbit starts from rest on the table (a release after
//!   sticking, reached from a whole interval of states: no single preimage);
//! * a point is not a launch (v < f'(t)): the edge of the phase space;
//! * two neighbouring parameters a rounding apart still map far apart: a
//!   discontinuity (a grazing or a breakpoint between them);
//! * the most points are reached.

use super::periodic::{map_for, pass, CyclePoint, PassError};
use crate::inverse::{InverseMap, NoPreimage};
use crate::map::ImpactMap;
use crate::system::System;

/// The largest turn between neighbouring segments of a branch, in radians, before
/// the parameter interval between them is halved.
pub const MAX_ANGLE: f64 = 0.2;

/// What to grow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ManifoldSpec {
    /// Arc length of each branch, in the metric of (t, v).
    pub length: f64,
    /// Displacement of the fundamental domain's first point from the saddle, along
    /// the eigenvector.
    pub delta: f64,
    /// Largest distance between neighbouring points of a branch.
    pub max_step: f64,
    /// Most points of a branch.
    pub max_points: usize,
}

impl Default for ManifoldSpec {
    fn default() -> Self {
        ManifoldSpec {
            length: 2.0,
            delta: 1e-7,
            max_step: 0.01,
            max_points: 20_000,
        }
    }
}

/// Why a branch ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BranchEnd {
    /// Its arc length reached the length asked.
    Length,
    /// The orbit of the next point sticks to the table.
    Sticking {
        /// Where it sticks.
        phase: f64,
    },
    /// The orbit of the next point grazes the table.
    Grazing {
        /// Where it grazes.
        phase: f64,
    },
    /// The orbit of the next point does not land, or leaves the engine's ranges.
    NoLanding,
    /// Backward, the next point's orbit starts from rest on the table at this phase (a
    /// release after sticking): it has no single preimage.
    Release {
        /// Where the ball left the table.
        phase: f64,
    },
    /// The next point is not a launch (v < f'(t)): the edge of the phase space.
    Edge,
    /// Neighbouring parameters a rounding apart map further apart than the step: a
    /// jump of the manifold (a grazing or a breakpoint between them), after this point.
    Discontinuity,
    /// The most points were reached.
    Points,
}

impl BranchEnd {
    /// Its name in every output.
    pub fn as_str(&self) -> &'static str {
        match self {
            BranchEnd::Length => "length",
            BranchEnd::Sticking { .. } => "sticking",
            BranchEnd::Grazing { .. } => "grazing",
            BranchEnd::NoLanding => "no_landing",
            BranchEnd::Release { .. } => "release",
            BranchEnd::Edge => "edge",
            BranchEnd::Discontinuity => "discontinuity",
            BranchEnd::Points => "points",
        }
    }
}

/// Which manifold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// The points whose orbits leave the saddle (grown forward).
    Unstable,
    /// The points whose orbits approach the saddle (grown backward).
    Stable,
}

impl Kind {
    /// Its name in every output.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::Unstable => "unstable",
            Kind::Stable => "stable",
        }
    }
}

/// One side of a manifold.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch {
    /// +1 or −1: the side of the eigenvector.
    pub side: i8,
    /// Its points (t, v), from the saddle outwards.
    pub points: Vec<[f64; 2]>,
    /// Each point's level j and parameter s: the point is Gʲ(p + side·s·e).
    pub params: Vec<(u32, f64)>,
    /// Its arc length.
    pub length: f64,
    /// Why it ends.
    pub end: BranchEnd,
}

/// A manifold of a saddle.
#[derive(Clone, Debug, PartialEq)]
pub struct Manifold {
    /// Unstable or stable.
    pub kind: Kind,
    /// The saddle's launch (t, v).
    pub saddle: [f64; 2],
    /// The growth factor μ along the eigenvector: λᵤ (or λᵤ² where λᵤ < 0) for the
    /// unstable, 1/λₛ (or 1/λₛ²) for the stable manifold.
    pub multiplier: f64,
    /// The unit eigenvector e (in (t, v)).
    pub direction: [f64; 2],
    /// Events of G: n, or 2n where the multiplier is negative.
    pub events: usize,
    /// Table periods of G.
    pub periods: u32,
    /// The two branches, side +1 then side −1.
    pub branches: Vec<Branch>,
}

/// Why there is no manifold to grow.
#[derive(Clone, Debug, PartialEq)]
pub enum ManifoldError {
    /// The cycle's multipliers are not a saddle's (real, one outside and one inside
    /// the unit circle): the multipliers found.
    NotSaddle([crate::linalg::Complex; 2]),
    /// The spec is out of range (its field named).
    BadSpec(&'static str),
}

impl std::fmt::Display for ManifoldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ManifoldError::NotSaddle(m) => write!(
                f,
                "not a saddle: multipliers {}{:+}i and {}{:+}i (valid: real, one outside and one inside the unit circle)",
                m[0].re, m[0].im, m[1].re, m[1].im
            ),
            ManifoldError::BadSpec(what) => write!(f, "{what} out of range"),
        }
    }
}

/// G or G⁻¹, the map a manifold is grown under.
struct Map {
    events: usize,
    periods: u32,
    forward: ImpactMap,
    /// Present for the stable manifold.
    inverse: Option<InverseMap>,
}

impl Map {
    fn new(sys: &System, events: usize, periods: u32, kind: Kind) -> Map {
        Map {
            events,
            periods,
            forward: map_for(sys),
            inverse: (kind == Kind::Stable).then(|| InverseMap::new(sys)),
        }
    }

    /// H(x), or why the orbit of x ends.
    fn apply(&mut self, x: [f64; 2]) -> Result<[f64; 2], BranchEnd> {
        match &mut self.inverse {
            None => match pass(&mut self.forward, x[0], x[1], self.events, self.periods) {
                Ok(p) => Ok([x[0] + p.residual[0], x[1] + p.residual[1]]),
                Err(PassError::Stick { phase }) => Err(BranchEnd::Sticking { phase }),
                Err(PassError::Grazing { phase }) => Err(BranchEnd::Grazing { phase }),
                Err(PassError::BadLaunch) => Err(BranchEnd::Edge),
                Err(_) => Err(BranchEnd::NoLanding),
            },
            Some(inv) => {
                // Back n launches, the time kept continuous (t − flights), then k
                // periods on so the point stays beside the saddle.
                let (mut t, mut v) = (x[0], x[1]);
                for _ in 0..self.events {
                    let period = t.floor();
                    let phase = crate::time::wrap_phase(t - period);
                    let pre = inv.previous(period as i64, phase, v).map_err(|e| match e {
                        NoPreimage::NotALaunch => BranchEnd::Edge,
                        NoPreimage::Release { phase } => BranchEnd::Release { phase },
                        NoPreimage::NoLanding | NoPreimage::OutOfRange => BranchEnd::NoLanding,
                        NoPreimage::NotReturning { .. } => BranchEnd::Discontinuity,
                    })?;
                    t -= pre.flight;
                    v = pre.v;
                }
                Ok([t + f64::from(self.periods), v])
            }
        }
    }

    /// Hʲ(x).
    fn iterate(&mut self, mut x: [f64; 2], j: u32) -> Result<[f64; 2], BranchEnd> {
        for _ in 0..j {
            x = self.apply(x)?;
        }
        Ok(x)
    }
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The distance from `y` to the segment a–b (in (t, v)).
pub(crate) fn segment_distance(y: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((y[0] - a[0]) * ab[0] + (y[1] - a[1]) * ab[1]) / len2).clamp(0.0, 1.0)
    };
    distance(y, [a[0] + t * ab[0], a[1] + t * ab[1]])
}

/// The angle between the segments a→b and b→c (0 where one is empty).
fn turn(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let (u, w) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
    let (nu, nw) = (u[0].hypot(u[1]), w[0].hypot(w[1]));
    if nu == 0.0 || nw == 0.0 {
        return 0.0;
    }
    let cos = ((u[0] * w[0] + u[1] * w[1]) / (nu * nw)).clamp(-1.0, 1.0);
    cos.acos()
}

/// The `kind` manifold of the saddle `cycle` of `sys` (a cycle found by
/// [`super::periodic::cycle`] at `sys`'s α).
pub fn manifold(
    sys: &System,
    cycle: &CyclePoint,
    kind: Kind,
    spec: &ManifoldSpec,
) -> Result<Manifold, ManifoldError> {
    if !(spec.length > 0.0 && spec.length.is_finite()) {
        return Err(ManifoldError::BadSpec("length"));
    }
    if !(spec.delta > 0.0 && spec.delta < 1e-2) {
        return Err(ManifoldError::BadSpec("delta"));
    }
    if !(spec.max_step > spec.delta && spec.max_step.is_finite()) {
        return Err(ManifoldError::BadSpec("max_step"));
    }
    if spec.max_points < 2 {
        return Err(ManifoldError::BadSpec("max_points"));
    }
    let [a, b] = cycle.multipliers;
    let real = a.im == 0.0 && b.im == 0.0;
    let (lu, ls) = if a.re.abs() >= b.re.abs() {
        (a.re, b.re)
    } else {
        (b.re, a.re)
    };
    if !real || lu.abs() <= 1.0 || ls.abs() >= 1.0 || ls == 0.0 {
        return Err(ManifoldError::NotSaddle(cycle.multipliers));
    }
    let lambda = match kind {
        Kind::Unstable => lu,
        Kind::Stable => ls,
    };
    let m = cycle.monodromy;
    // (M − λI) e = 0: e ∥ (m01, λ − m00), or (λ − m11, m10), whichever is larger.
    let e1 = [m[0][1], lambda - m[0][0]];
    let e2 = [lambda - m[1][1], m[1][0]];
    let e = if e1[0].hypot(e1[1]) >= e2[0].hypot(e2[1]) {
        e1
    } else {
        e2
    };
    let norm = e[0].hypot(e[1]);
    let direction = [e[0] / norm, e[1] / norm];
    let twice = lambda < 0.0;
    let (events, periods) = if twice {
        (2 * cycle.n, 2 * cycle.k)
    } else {
        (cycle.n, cycle.k)
    };
    let mut g = Map::new(sys, events, periods, kind);
    let growth = if twice { lambda * lambda } else { lambda };
    let mu = match kind {
        Kind::Unstable => growth,
        Kind::Stable => 1.0 / growth,
    };
    let saddle = [cycle.t0, cycle.velocities[0]];
    let branches = [1i8, -1]
        .into_iter()
        .map(|side| grow(&mut g, saddle, direction, side, mu, spec))
        .collect();
    Ok(Manifold {
        kind,
        saddle,
        multiplier: mu,
        direction,
        events,
        periods,
        branches,
    })
}

/// The first unstable (1, k) solution of `sys` with real multipliers (a saddle, whose
/// manifolds [`manifold`] grows), in the order [`super::fixed::fixed_points`] lists them;
/// None if every (1, k) solution is stable or has complex multipliers.
pub fn first_saddle(sys: &System, k: u32) -> Result<Option<CyclePoint>, crate::error::EngineError> {
    Ok(super::fixed::fixed_points(sys, k)?
        .iter()
        .filter_map(|fp| super::periodic::cycle(sys, 1, k, fp.phase, fp.v).ok())
        .find(|c| !c.stable && c.multipliers.iter().all(|z| z.im == 0.0)))
}

/// Samples of the fundamental domain at the start: this many, spread evenly in s.
const DOMAIN_SAMPLES: usize = 16;

/// One branch: the fundamental domain's images, level by level, refined.
fn grow(g: &mut Map, p: [f64; 2], e: [f64; 2], side: i8, mu: f64, spec: &ManifoldSpec) -> Branch {
    let sigma = f64::from(side);
    let start = |s: f64| [p[0] + sigma * s * e[0], p[1] + sigma * s * e[1]];
    let (lo, hi) = (spec.delta, spec.delta * mu);
    let mut branch = Branch {
        side,
        points: vec![p],
        params: vec![(0, 0.0)],
        length: 0.0,
        end: BranchEnd::Points,
    };
    // The parameters of the level being computed, and the level.
    let mut params: Vec<f64> = (0..DOMAIN_SAMPLES)
        .map(|i| lo + (hi - lo) * i as f64 / (DOMAIN_SAMPLES - 1) as f64)
        .collect();
    let mut level = 0u32;
    loop {
        // This level's points, from its first parameter on; the last of a level is
        // the first of the next (G(p + δe) ≈ p + μδe), so it is left out there.
        let mut i = 0;
        let mut pts: Vec<[f64; 2]> = Vec::with_capacity(params.len());
        for &s in &params {
            match g.iterate(start(s), level) {
                Ok(x) => pts.push(x),
                Err(end) => {
                    branch.end = end;
                    params.truncate(pts.len());
                    break;
                }
            }
        }
        let ended = pts.len() < params.len() || branch.end != BranchEnd::Points;
        // Refine: halve a parameter interval whose images lie too far apart or turn
        // too sharply.
        while i + 1 < pts.len() {
            let far = distance(pts[i], pts[i + 1]) > spec.max_step;
            let sharp = i >= 1
                && distance(pts[i], pts[i + 1]) > spec.delta
                && turn(pts[i - 1], pts[i], pts[i + 1]) > MAX_ANGLE;
            if !(far || sharp) {
                i += 1;
                continue;
            }
            let mid = 0.5 * (params[i] + params[i + 1]);
            if mid <= params[i] || mid >= params[i + 1] {
                if far {
                    // A rounding apart and still far: a jump.
                    params.truncate(i + 1);
                    pts.truncate(i + 1);
                    branch.end = BranchEnd::Discontinuity;
                    break;
                }
                i += 1;
                continue;
            }
            match g.iterate(start(mid), level) {
                Ok(x) => {
                    params.insert(i + 1, mid);
                    pts.insert(i + 1, x);
                }
                Err(end) => {
                    params.truncate(i + 1);
                    pts.truncate(i + 1);
                    branch.end = end;
                    break;
                }
            }
            if branch.points.len() + pts.len() > spec.max_points {
                break;
            }
        }
        // Append this level (its last point is the next level's first).
        let take = if ended || branch.end != BranchEnd::Points {
            pts.len()
        } else {
            pts.len().saturating_sub(1)
        };
        for (k, x) in pts.iter().take(take).enumerate() {
            let last = *branch.points.last().expect("the saddle first");
            let step = distance(last, *x);
            if branch.length + step >= spec.length {
                branch.end = BranchEnd::Length;
                return branch;
            }
            if branch.points.len() >= spec.max_points {
                branch.end = BranchEnd::Points;
                return branch;
            }
            branch.length += step;
            branch.points.push(*x);
            branch.params.push((level, params[k]));
        }
        if branch.end != BranchEnd::Points || ended {
            return branch;
        }
        level += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::orbits::fixed::fixed_points;
    use crate::orbits::periodic::cycle;
    use crate::table::Table;

    /// The unstable (1, 1) solution of F_D at D = 0.1, α = 0.45, r = 0.8 (a saddle,
    /// multipliers 4.395 and 0.146), and the stable one beside it (a focus).
    fn saddle() -> (System, CyclePoint, CyclePoint) {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let fps = fixed_points(&sys, 1).unwrap();
        let cycles: Vec<CyclePoint> = fps
            .iter()
            .map(|fp| cycle(&sys, 1, 1, fp.phase, fp.v).unwrap())
            .collect();
        let saddle = cycles.iter().find(|c| !c.stable).unwrap().clone();
        let sink = cycles.iter().find(|c| c.stable).unwrap().clone();
        (sys, saddle, sink)
    }

    /// Past the period doubling (α_PD ≈ 0.506 at D = 0.1, r = 0.8) at α = 0.52: the (1, 1)
    /// solution with f'' < 0, a saddle with λᵤ < −1.
    fn flip_saddle() -> (System, CyclePoint) {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.52, 0.8).unwrap();
        let fp = fixed_points(&sys, 1)
            .unwrap()
            .into_iter()
            .min_by(|a, b| a.phase.total_cmp(&b.phase))
            .unwrap();
        let c = cycle(&sys, 1, 1, fp.phase, fp.v).unwrap();
        (sys, c)
    }

    fn map_of(sys: &System, m: &Manifold) -> Map {
        Map::new(sys, m.events, m.periods, m.kind)
    }

    fn unstable_manifold(
        sys: &System,
        c: &CyclePoint,
        spec: &ManifoldSpec,
    ) -> Result<Manifold, ManifoldError> {
        manifold(sys, c, Kind::Unstable, spec)
    }

    /// The distance from `y` to the polyline `pts`.
    fn to_polyline(y: [f64; 2], pts: &[[f64; 2]]) -> f64 {
        pts.windows(2)
            .map(|s| segment_distance(y, s[0], s[1]))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_branches_leave_along_the_eigenvector_and_join_their_levels() {
        let (sys, c, _) = saddle();
        let spec = ManifoldSpec {
            length: 1.0,
            ..ManifoldSpec::default()
        };
        let m = unstable_manifold(&sys, &c, &spec).unwrap();
        // M e = λ e, from the monodromy of the Newton solution.
        let (mm, e) = (c.monodromy, m.direction);
        let me = [
            mm[0][0] * e[0] + mm[0][1] * e[1],
            mm[1][0] * e[0] + mm[1][1] * e[1],
        ];
        assert_eq!((m.events, m.periods), (1, 1), "λ > 0: G = F");
        assert!((m.multiplier - 4.395087772098843).abs() < 1e-9);
        assert!((me[0] - m.multiplier * e[0]).abs() < 1e-9);
        assert!((me[1] - m.multiplier * e[1]).abs() < 1e-9);
        let mut g = map_of(&sys, &m);
        for b in &m.branches {
            assert_eq!(b.end, BranchEnd::Length);
            assert!(b.length <= spec.length && b.length > spec.length - spec.max_step);
            // Near the saddle the branch lies along ±e.
            let d = [b.points[1][0] - m.saddle[0], b.points[1][1] - m.saddle[1]];
            assert!((d[0] * e[1] - d[1] * e[0]).abs() / d[0].hypot(d[1]) < 1e-6);
            assert!((d[0] * e[0] + d[1] * e[1]) * f64::from(b.side) > 0.0);
            // The fundamental domain's image joins its end: G(p + δe) = p + μδe up to
            // the second order in δ.
            let s = f64::from(b.side);
            let at = |x: f64| [m.saddle[0] + s * x * e[0], m.saddle[1] + s * x * e[1]];
            let joined = distance(
                g.apply(at(spec.delta)).unwrap(),
                at(spec.delta * m.multiplier),
            );
            assert!(joined < 1e-12, "{joined}");
            // Neighbouring points at most a step apart.
            for w in b.points.windows(2) {
                assert!(distance(w[0], w[1]) <= spec.max_step);
            }
        }
    }

    #[test]
    fn between_its_points_the_manifold_is_within_the_chord_bound() {
        // The exact point at the parameter halfway between two neighbouring points of a
        // level lies within max_step · MAX_ANGLE of the polyline.
        let (sys, c, _) = saddle();
        let spec = ManifoldSpec {
            length: 2.0,
            ..ManifoldSpec::default()
        };
        let m = unstable_manifold(&sys, &c, &spec).unwrap();
        let mut g = map_of(&sys, &m);
        let e = m.direction;
        let mut checked = 0;
        for b in &m.branches {
            let s = f64::from(b.side);
            for k in (1..b.points.len() - 1).step_by(5) {
                let ((j, a), (j2, z)) = (b.params[k], b.params[k + 1]);
                if j != j2 {
                    continue;
                }
                let h = 0.5 * (a + z);
                let x0 = [m.saddle[0] + s * h * e[0], m.saddle[1] + s * h * e[1]];
                let Ok(x) = g.iterate(x0, j) else { continue };
                let off = to_polyline(x, &b.points);
                assert!(off < spec.max_step * MAX_ANGLE, "{off} at {k}");
                checked += 1;
            }
        }
        assert!(checked > 50, "{checked}");
    }

    #[test]
    fn a_finer_computation_gives_the_same_curve() {
        // A second computation with δ ten times smaller and steps five times shorter:
        // every point of the first lies on the second's polyline, within the first's
        // chord bound, over the first unit of arc length.
        let (sys, c, _) = saddle();
        let coarse = ManifoldSpec {
            length: 1.0,
            ..ManifoldSpec::default()
        };
        let fine = ManifoldSpec {
            length: 1.2,
            delta: 1e-8,
            max_step: 0.002,
            max_points: 100_000,
        };
        let a = unstable_manifold(&sys, &c, &coarse).unwrap();
        let b = unstable_manifold(&sys, &c, &fine).unwrap();
        for (x, y) in a.branches.iter().zip(&b.branches) {
            assert_eq!(x.side, y.side);
            let worst = x
                .points
                .iter()
                .map(|&p| to_polyline(p, &y.points))
                .fold(0.0, f64::max);
            assert!(worst < fine.max_step * MAX_ANGLE, "{worst}");
        }
    }

    #[test]
    fn a_flip_saddle_grows_each_side_under_the_second_iterate() {
        // Past the period doubling (α_PD ≈ 0.506 at D = 0.1) the (1, 1) solution is a
        // saddle with λᵤ < −1: G = F², μ = λᵤ², and each side is invariant under G.
        let (sys, c) = flip_saddle();
        let lu = c.multipliers[0].re.abs().max(c.multipliers[1].re.abs());
        let spec = ManifoldSpec {
            length: 0.3,
            ..ManifoldSpec::default()
        };
        let m = unstable_manifold(&sys, &c, &spec).unwrap();
        assert_eq!((m.events, m.periods), (2, 2));
        assert!((m.multiplier - lu * lu).abs() < 1e-9 * m.multiplier);
        let mut g = map_of(&sys, &m);
        let e = m.direction;
        for b in &m.branches {
            assert!(b.points.len() > 10, "{:?}", b.end);
            let s = f64::from(b.side);
            let at = |x: f64| [m.saddle[0] + s * x * e[0], m.saddle[1] + s * x * e[1]];
            assert!(
                distance(
                    g.apply(at(spec.delta)).unwrap(),
                    at(spec.delta * m.multiplier)
                ) < 1e-12
            );
        }
    }

    #[test]
    fn the_stable_manifold_returns_to_the_saddle_under_the_map() {
        // Each point of the stable manifold is G⁻ʲ(p + σ s e) by the inverse map: the
        // forward map takes it back within 1e-9 to the local stable segment, G once takes
        // it to the point of level j − 1 with the same s, and near the saddle the branch
        // leaves along the stable eigenvector (M e = λₛ e).
        let (sys, c, _) = saddle();
        let spec = ManifoldSpec {
            length: 1.5,
            ..ManifoldSpec::default()
        };
        let m = manifold(&sys, &c, Kind::Stable, &spec).unwrap();
        let (mm, e) = (c.monodromy, m.direction);
        let ls = c.multipliers[0].re.min(c.multipliers[1].re);
        assert!((m.multiplier - 1.0 / ls).abs() < 1e-9 * m.multiplier);
        assert!((mm[0][0] * e[0] + mm[0][1] * e[1] - ls * e[0]).abs() < 1e-9);
        assert!((mm[1][0] * e[0] + mm[1][1] * e[1] - ls * e[1]).abs() < 1e-9);
        let mut forward = Map::new(&sys, m.events, m.periods, Kind::Unstable);
        let mut checked = 0;
        for b in &m.branches {
            assert!(b.points.len() > 20, "{:?}", b.end);
            let sigma = f64::from(b.side);
            let at = |x: f64| {
                [
                    m.saddle[0] + sigma * x * e[0],
                    m.saddle[1] + sigma * x * e[1],
                ]
            };
            for (k, (&x, &(j, s))) in b.points.iter().zip(&b.params).enumerate().skip(1) {
                let back = forward.iterate(x, j).unwrap();
                let off = distance(back, at(s));
                assert!(off < 1e-9, "{k}: level {j}, {off}");
                if j >= 1 {
                    let once = forward.apply(x).unwrap();
                    let mut g = map_of(&sys, &m);
                    let previous = g.iterate(at(s), j - 1).unwrap();
                    assert!(
                        distance(once, previous) < 1e-9,
                        "{k}: {}",
                        distance(once, previous)
                    );
                }
                checked += 1;
            }
        }
        assert!(checked > 50, "{checked}");
    }

    #[test]
    fn the_two_manifolds_cross_only_transversally_at_the_saddle() {
        // The stable and unstable eigenvectors differ, and both manifolds of the flip
        // saddle grow under the second iterate.
        let (sys, c) = flip_saddle();
        let spec = ManifoldSpec {
            length: 0.3,
            ..ManifoldSpec::default()
        };
        let u = manifold(&sys, &c, Kind::Unstable, &spec).unwrap();
        let s = manifold(&sys, &c, Kind::Stable, &spec).unwrap();
        assert_eq!((s.events, s.periods), (2, 2));
        let cross = u.direction[0] * s.direction[1] - u.direction[1] * s.direction[0];
        assert!(cross.abs() > 1e-3, "{cross}");
        for b in &s.branches {
            assert!(b.points.len() > 5, "{:?}", b.end);
        }
    }

    #[test]
    fn only_a_saddle_has_an_unstable_manifold_to_grow() {
        let (sys, saddle, sink) = saddle();
        assert!(matches!(
            unstable_manifold(&sys, &sink, &ManifoldSpec::default()),
            Err(ManifoldError::NotSaddle(_))
        ));
        for bad in [
            ManifoldSpec {
                length: 0.0,
                ..ManifoldSpec::default()
            },
            ManifoldSpec {
                delta: 0.5,
                ..ManifoldSpec::default()
            },
            ManifoldSpec {
                max_step: 1e-9,
                ..ManifoldSpec::default()
            },
        ] {
            assert!(matches!(
                unstable_manifold(&sys, &saddle, &bad),
                Err(ManifoldError::BadSpec(_))
            ));
        }
    }
}
