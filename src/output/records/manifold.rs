//! Records of `manifolds`: a point of a branch (csv) and the whole manifold (json).

use super::*;
use bouncemap_engine::orbits::manifold::{Branch, BranchEnd, Kind, Manifold};
use bouncemap_engine::orbits::periodic::CyclePoint;

/// One csv row of `manifolds`: a point of a branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ManifoldRow {
    /// `unstable` or `stable`.
    pub manifold: &'static str,
    /// `+` or `-`: the side of the eigenvector.
    pub branch: &'static str,
    pub index: usize,
    /// The point is Gʲ(saddle + side·s·e) (G⁻ʲ on the stable manifold): j and s.
    pub level: u32,
    pub s: f64,
    /// The launch time from the saddle's own (not wrapped), its phase, and the launch
    /// velocity.
    pub t: f64,
    pub phase: f64,
    pub v: f64,
}

impl ManifoldRow {
    pub const HEADER: [&'static str; 8] = [
        "manifold", "branch", "index", "level", "s", "t", "phase", "v",
    ];

    /// The rows of branch `b` of a `kind` manifold.
    pub fn of(kind: Kind, b: &Branch) -> impl Iterator<Item = ManifoldRow> + '_ {
        b.points
            .iter()
            .zip(&b.params)
            .enumerate()
            .map(move |(i, (x, &(level, s)))| ManifoldRow {
                manifold: kind.as_str(),
                branch: side_name(b.side),
                index: i,
                level,
                s,
                t: x[0],
                phase: x[0].rem_euclid(1.0),
                v: x[1],
            })
    }
}

/// `+` or `-`.
pub fn side_name(side: i8) -> &'static str {
    if side > 0 {
        "+"
    } else {
        "-"
    }
}

/// Why a branch ends, for people.
pub fn end_text(end: &BranchEnd) -> String {
    match end {
        BranchEnd::Length => "the length asked is reached".into(),
        BranchEnd::Sticking { phase } => {
            format!("the next point's orbit sticks to the table (at t̂ = {phase})")
        }
        BranchEnd::Grazing { phase } => {
            format!("the next point's orbit grazes the table (at t̂ = {phase})")
        }
        BranchEnd::NoLanding => {
            "the next point's orbit does not land, or leaves the engine's ranges".into()
        }
        BranchEnd::Release { phase } => format!(
            "backward, the next point's orbit starts from rest on the table (a release after sticking, at t̂ = {phase}): no single preimage"
        ),
        BranchEnd::Edge => "the next point is not a launch (v < f'(t)): the edge of the phase space".into(),
        BranchEnd::Discontinuity => {
            "neighbouring parameters a rounding apart map apart: a jump (a grazing or a breakpoint between them)".into()
        }
        BranchEnd::Points => "the most points are reached".into(),
    }
}

/// A branch (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ManifoldBranchRecord {
    pub branch: &'static str,
    /// length, sticking, grazing, no_landing, release, edge, discontinuity, points.
    pub end: &'static str,
    /// Where the orbit sticks, grazes or was released, for those ends.
    pub end_phase: Option<f64>,
    pub length: f64,
    /// (t, phase, v) of every point, from the saddle out.
    pub points: Vec<[f64; 3]>,
}

/// One manifold (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ManifoldRecord {
    /// `unstable` or `stable`.
    pub manifold: &'static str,
    /// The map the manifold is grown under (G, or G⁻¹ for the stable one): its events
    /// and periods (n, k, or 2n, 2k for a flip saddle), its growth factor along the
    /// unit eigenvector.
    pub events: usize,
    pub periods: u32,
    pub multiplier: f64,
    pub direction: [f64; 2],
    pub branches: Vec<ManifoldBranchRecord>,
}

/// `manifolds`' json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ManifoldDoc<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub n: usize,
    pub k: u32,
    /// The saddle's launch: phase and velocity.
    pub saddle: [f64; 2],
    /// Both multipliers of the cycle.
    pub multipliers: [[f64; 2]; 2],
    pub manifolds: Vec<ManifoldRecord>,
}

impl<'a> ManifoldDoc<'a> {
    pub fn of(table: &'a str, alpha: f64, r: f64, c: &CyclePoint, ms: &[Manifold]) -> Self {
        ManifoldDoc {
            table,
            alpha,
            r,
            n: c.n,
            k: c.k,
            saddle: [c.t0.rem_euclid(1.0), c.velocities[0]],
            multipliers: c.multipliers.map(|z| [z.re, z.im]),
            manifolds: ms.iter().map(ManifoldRecord::of).collect(),
        }
    }
}

impl ManifoldRecord {
    fn of(m: &Manifold) -> Self {
        ManifoldRecord {
            manifold: m.kind.as_str(),
            events: m.events,
            periods: m.periods,
            multiplier: m.multiplier,
            direction: m.direction,
            branches: m
                .branches
                .iter()
                .map(|b| ManifoldBranchRecord {
                    branch: side_name(b.side),
                    end: b.end.as_str(),
                    end_phase: match b.end {
                        BranchEnd::Sticking { phase }
                        | BranchEnd::Grazing { phase }
                        | BranchEnd::Release { phase } => Some(phase),
                        _ => None,
                    },
                    length: b.length,
                    points: b
                        .points
                        .iter()
                        .map(|x| [x[0], x[0].rem_euclid(1.0), x[1]])
                        .collect(),
                })
                .collect(),
        }
    }
}
