//! Why a curve stopped where it stopped for want of a next point: the evidence of its
//! last point's cycle ([`EndEvidence`]), which the output gives beside the end.

use super::{Curve, CurveEnd, CurveKind, Plane};
use crate::time::signed_distance;

/// What stood at a curve's end where it stopped for want of a next point
/// ([`CurveEnd::NoConvergence`], [`CurveEnd::Stalled`], [`CurveEnd::StepLimit`]): the
/// evidence of its last point's cycle, for the reader to weigh why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EndEvidence {
    /// The largest |λ| of the cycle's multipliers (a strongly unstable cycle is found by
    /// Newton's method only from close by).
    pub multiplier: f64,
    /// The largest entry |Mᵢⱼ| of its monodromy matrix: where it is large and the
    /// multipliers are not, the trace (of order one) is the small difference of large
    /// entries, and a period-doubling or fold condition is known only to its rounding
    /// floor.
    pub monodromy: f64,
    /// The impact nearest a breakpoint (other than a border collision's own impact on
    /// its own): its index in the cycle (counted as the curve's own impact is), the
    /// breakpoint, and its signed phase distance to it (one that close may cross it
    /// between Newton's iterates, where f'' jumps).
    pub nearest: Option<(usize, f64, f64)>,
}

impl Curve {
    /// The [`EndEvidence`] at end `e` (0 the first point, 1 the last) of a curve of
    /// `plane`, where it stopped for want of a next point; None at the other ends.
    pub fn end_evidence(&self, plane: &Plane, e: usize) -> Option<EndEvidence> {
        let end = *self.ends.get(e)?;
        if !matches!(
            end,
            CurveEnd::NoConvergence | CurveEnd::Stalled | CurveEnd::StepLimit
        ) {
            return None;
        }
        let q = if e == 0 {
            self.points.first()
        } else {
            self.points.last()
        }?;
        let own = match self.kind {
            CurveKind::BorderCollision { impact, breakpoint } => Some((impact, breakpoint)),
            _ => None,
        };
        let jumps = plane.jumps(q.p);
        let nearest = q
            .cycle
            .phases
            .iter()
            .enumerate()
            .flat_map(|(i, &ph)| {
                jumps
                    .iter()
                    .filter(move |&&b| own != Some((i, b)))
                    .map(move |&b| (i, b, signed_distance(ph, b)))
            })
            .min_by(|a, b| a.2.abs().total_cmp(&b.2.abs()));
        let multiplier = q
            .cycle
            .multipliers
            .iter()
            .map(|l| l.abs())
            .fold(0.0, f64::max);
        let monodromy = q
            .cycle
            .monodromy
            .iter()
            .flatten()
            .map(|m| m.abs())
            .fold(0.0, f64::max);
        Some(EndEvidence {
            multiplier,
            monodromy,
            nearest,
        })
    }
}
