//! Curves found twice are one: a curve that another covers is dropped, a piece that
//! runs along another and beyond one of its ends is joined to that end, and each
//! codimension-two point is told once with every curve through it.

use super::*;

/// Each codimension-two point once: points of one kind within `tol` of each other (the
/// same point located on two curves, or twice on one) are one, the best located kept
/// (the smaller condition); each then lists every curve passing through it.
pub(super) fn codim2_once(out: &mut Curves, tol: f64) {
    let mut kept: Vec<Codim2> = Vec::new();
    for p in std::mem::take(&mut out.codim2) {
        let twin = kept
            .iter_mut()
            .find(|q| q.kind == p.kind && (q.alpha - p.alpha).hypot(q.p - p.p) <= tol);
        match twin {
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
    for p in &mut kept {
        let mut meets = vec![p.curve];
        for (i, c) in out.curves.iter().enumerate() {
            if i != p.curve && c.passes_near(p.alpha, p.p, 100.0 * tol) {
                meets.push(i);
            }
        }
        p.meets = meets;
    }
    out.codim2 = kept;
}

/// `a` extended by the part of `b` beyond one of its ends, where `b` runs along `a` for
/// at least a fifth of its points and leaves it only at its own start or end, from a
/// point near an end of `a` (None otherwise: two curves that cross, or touch).
fn join(a: &Curve, b: &Curve, tol: f64) -> Option<Curve> {
    let covered: Vec<bool> = b
        .points
        .iter()
        .map(|q| a.passes_near(q.alpha, q.p, tol))
        .collect();
    let count = covered.iter().filter(|c| **c).count();
    if count * 5 < b.points.len() || count == b.points.len() {
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
                || a.kind.as_str() != b.kind.as_str()
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
