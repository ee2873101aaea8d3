//! Curves found twice are one: a curve that another covers is dropped, a piece that
//! runs along another and beyond one of its ends is joined to that end, and each
//! codimension-two point is told once with every curve through it.

use super::*;

/// Each codimension-two point once: points of one kind within `tol` of each other (the
/// same point located on two curves, or twice on one) are one, the best located kept
/// (the smaller condition); so are the double borders of one cycle's two impacts
/// located from its two border collisions, within ten times `tol` (the curve that
/// meets the corner at a small angle to the border locates it the less well), the one
/// with the smaller conditions kept. Each then lists every curve passing through it.
pub(super) fn codim2_once(out: &mut Curves, tol: f64) {
    doubled_at_pd_border(out, 10.0 * tol);
    let mut kept: Vec<Codim2> = Vec::new();
    for p in std::mem::take(&mut out.codim2) {
        let pair = border_pair(out, &p);
        let twin = kept.iter_mut().find(|q| {
            let d = (q.alpha - p.alpha).hypot(q.p - p.p);
            q.kind == p.kind
                && (d <= tol || (pair.is_some() && d <= 10.0 * tol && border_pair(out, q) == pair))
        });
        let off = |q: &Codim2| q.condition.abs() + q.second_condition.abs();
        match twin {
            Some(q) if pair.is_some() && border_pair(out, q) == pair => {
                if off(&p) < off(q) {
                    let meets = std::mem::take(&mut q.meets);
                    *q = p;
                    q.meets = meets;
                }
            }
            Some(q) => {
                if p.condition.abs() < q.condition.abs() {
                    let meets = std::mem::take(&mut q.meets);
                    *q = p;
                    q.meets = meets;
                }
            }
            None => kept.push(p),
        }
    }
    out.codim2 = kept;
    list_meets(out, tol);
    ends_at_codim2(out, 10.0 * tol);
}

/// A double border's cycle (n, k) and its two impacts with their breakpoints' bits, in
/// the order of the impacts.
type BorderPair = (usize, u32, [(usize, u64); 2]);

/// The [`BorderPair`] of a double border found on a border-collision curve.
fn border_pair(out: &Curves, p: &Codim2) -> Option<BorderPair> {
    if p.kind != Codim2Kind::DoubleBorder {
        return None;
    }
    let c = out.curves.get(p.curve)?;
    let CurveKind::BorderCollision { impact, breakpoint } = c.kind else {
        return None;
    };
    let (j, bp) = p.impact?;
    let mut two = [(impact, breakpoint.to_bits()), (j, bp.to_bits())];
    two.sort_unstable();
    Some((c.n, c.k, two))
}

/// A curve that stopped, for want of a next point, within `tol` of a
/// codimension-two point through it ends there: at a border (a collapse, for a
/// collapse). Its tracer may not have known the point: a curve seeded next to a double
/// border located on another curve, whose one side the corner bounds.
fn ends_at_codim2(out: &mut Curves, tol: f64) {
    for (i, c) in out.curves.iter_mut().enumerate() {
        for (e, q) in [(0, c.points.first()), (1, c.points.last())] {
            let Some(q) = q else { continue };
            if !matches!(
                c.ends[e],
                CurveEnd::NoConvergence | CurveEnd::Stalled | CurveEnd::TurnedBack
            ) {
                continue;
            }
            let end = out
                .codim2
                .iter()
                .filter(|p| p.meets.contains(&i) && (p.alpha - q.alpha).hypot(p.p - q.p) <= tol)
                .find_map(|p| p.kind.end());
            if let Some(end) = end {
                c.ends[e] = end;
            }
        }
    }
}

/// Every codimension-two point's list of the curves through it: its own first, then
/// every other curve passing within a hundred times `tol` (the tolerance it is told
/// once to).
pub(super) fn list_meets(out: &mut Curves, tol: f64) {
    for p in &mut out.codim2 {
        let mut meets = vec![p.curve];
        for (i, c) in out.curves.iter().enumerate() {
            if i != p.curve && c.passes_near(p.alpha, p.p, 100.0 * tol) {
                meets.push(i);
            }
        }
        p.meets = meets;
    }
}

/// Where a PD curve of an (n, k) cycle reaches a breakpoint, the doubled (2n, 2k)
/// cycle is born on the breakpoint: its border-collision curve ends there, collapsing
/// onto the (n, k) cycle, whose impact on the breakpoint is two of the doubled cycle's
/// (i and i + n). The tracer, closing in from the side of the doubled cycle, may see
/// that as two impacts on breakpoints before the halves have met to its tolerance. Such
/// a double border within `tol` of a pd_border of the halved cycle at the same impact
/// is the pd_border itself: it is dropped (its curve passes through the pd_border and
/// is listed there), and its curve's end there (within ten times `tol`) is a collapse.
fn doubled_at_pd_border(out: &mut Curves, tol: f64) {
    let pd: Vec<Codim2> = out
        .codim2
        .iter()
        .filter(|q| q.kind == Codim2Kind::PdBorder)
        .cloned()
        .collect();
    let curves = &mut out.curves;
    out.codim2.retain(|p| {
        if p.kind != Codim2Kind::DoubleBorder {
            return true;
        }
        let (n2, k2) = (curves[p.curve].n, curves[p.curve].k);
        let Some(centre) = pd.iter().find(|q| {
            let c = &curves[q.curve];
            let same_impact = match (p.impact, q.impact) {
                (Some((i, bp)), Some((j, bq))) => bp == bq && c.n > 0 && i % c.n == j % c.n,
                _ => false,
            };
            2 * c.n == n2
                && 2 * c.k == k2
                && same_impact
                && (q.alpha - p.alpha).hypot(q.p - p.p) <= tol
        }) else {
            return true;
        };
        // The doubled curve's end nearest the organising centre is a collapse.
        let c = &mut curves[p.curve];
        let d = |q: Option<&CurvePoint>| {
            q.map_or(f64::INFINITY, |q| {
                (q.alpha - centre.alpha).hypot(q.p - centre.p)
            })
        };
        let end = usize::from(d(c.points.last()) < d(c.points.first()));
        let near = d([c.points.first(), c.points.last()][end]) <= 10.0 * tol;
        if c.ends[end] == CurveEnd::Border && near {
            c.ends[end] = CurveEnd::Collapse;
        }
        false
    });
}

/// `a` extended by the part of `b` beyond one of its ends, where `b` runs along `a` for
/// at least a fifth of its length and leaves it only at its own start or end, from a
/// point near an end of `a` (None otherwise: two curves that cross, or touch).
fn join(a: &Curve, b: &Curve, tol: f64) -> Option<Curve> {
    let covered: Vec<bool> = b
        .points
        .iter()
        .map(|q| a.passes_near(q.alpha, q.p, tol))
        .collect();
    // Along for a fifth of its length, not of its points: steps crowd where a curve
    // closes in on a border, and two curves ending near each other there are not one.
    let seg = |w: &[CurvePoint]| (w[1].alpha - w[0].alpha).hypot(w[1].p - w[0].p);
    let total: f64 = b.points.windows(2).map(seg).sum();
    let along: f64 = b
        .points
        .windows(2)
        .zip(covered.windows(2))
        .filter(|(_, c)| c[0] && c[1])
        .map(|(w, _)| seg(w))
        .sum();
    if along * 5.0 < total || covered.iter().all(|c| *c) {
        return None;
    }
    let first = covered.iter().position(|c| *c)?;
    let last = covered.iter().rposition(|c| *c)?;
    // Covered in one stretch: the rest is a run before it, after it, or both.
    if covered[first..=last].iter().any(|c| !c) {
        return None;
    }
    let near = |q: &CurvePoint, r: &CurvePoint| (q.alpha - r.alpha).hypot(q.p - r.p) <= 10.0 * tol;
    let mut out = a.clone();
    for (run, at_b_start) in [(&b.points[..first], true), (&b.points[last + 1..], false)] {
        if run.is_empty() {
            continue;
        }
        // The covered point next to the run, and the end of `a` it is near.
        let joint = if at_b_start {
            &b.points[first]
        } else {
            &b.points[last]
        };
        let end_kind = b.ends[if at_b_start { 0 } else { 1 }];
        // The run, ordered away from the joint.
        let away: Vec<CurvePoint> = if at_b_start {
            run.iter().rev().cloned().collect()
        } else {
            run.to_vec()
        };
        if near(joint, out.points.last()?) {
            out.points.extend(away);
            out.ends[1] = end_kind;
        } else if near(joint, &out.points[0]) {
            let mut pts: Vec<CurvePoint> = away.into_iter().rev().collect();
            pts.append(&mut out.points);
            out.points = pts;
            out.ends[0] = end_kind;
        } else {
            return None;
        }
    }
    Some(out)
}

/// Drop a curve that another of the same kind and cycle covers (seeded at two values of
/// the second parameter, the shorter may be a piece of the longer): every tenth of its
/// points lies within `tol` of the other. Its codimension-two points go to the other.
pub(super) fn dedupe(out: &mut Curves, tol: f64) {
    let n = out.curves.len();
    let mut into: Vec<Option<usize>> = vec![None; n];
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (&out.curves[i], &out.curves[j]);
            if i == j
                || into[j].is_some()
                || a.n != b.n
                || a.k != b.k
                || !a.kind.same_condition(&b.kind)
                || (b.points.len(), j) < (a.points.len(), i)
            {
                continue;
            }
            let step = (a.points.len() / 10).max(1);
            if a.points
                .iter()
                .step_by(step)
                .all(|q| b.passes_near(q.alpha, q.p, tol))
            {
                into[i] = Some(j);
                break;
            }
            // A piece that runs along the other and then beyond one of its ends (the
            // same curve followed from two seeds, each stopped elsewhere): its part
            // beyond is joined to that end.
            if let Some(joined) = join(b, a, tol) {
                out.curves[j] = joined;
                into[i] = Some(j);
                break;
            }
        }
    }
    let mut index = vec![0usize; n];
    let mut kept = 0;
    for i in 0..n {
        if into[i].is_none() {
            index[i] = kept;
            kept += 1;
        }
    }
    for p in &mut out.codim2 {
        let mut c = p.curve;
        while let Some(j) = into[c] {
            c = j;
        }
        p.curve = index[c];
    }
    let mut i = 0;
    out.curves.retain(|_| {
        i += 1;
        into[i - 1].is_none()
    });
}
