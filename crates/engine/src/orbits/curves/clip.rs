//! The set found over the search range (the α window widened by [`SEARCH_MARGIN`] on
//! each side: a curve may reach the window only through a codimension-two point beyond
//! its edge, a border collision turning at a double border outside and its partner
//! coming back in) cut to the window: a window nested in another shows the curves the
//! wider one shows inside it.

use super::corrector::Tracer;
use super::merge::list_meets;
use super::trace::{crossing, secant};
use super::*;
use std::cell::RefCell;

/// Cut `out`, found over the search range, to `plane`'s window: every curve to its runs of
/// points inside, each run starting and ending where the curve does or on the edge
/// where it leaves (that point solved on the edge); the birth lines of the (1, k) pair
/// drawn anew over the window; the codimension-two points and the special points not
/// followed inside it kept.
pub(super) fn to_window(plane: &Plane, out: &mut Curves, tol: f64) {
    let dead_ends = RefCell::new(Vec::new());
    let curves = std::mem::take(&mut out.curves);
    let mut pieces: Vec<Vec<usize>> = Vec::with_capacity(curves.len());
    let mut births: Vec<u32> = Vec::new();
    for c in &curves {
        let mut mine = Vec::new();
        if c.kind == CurveKind::Birth {
            if !births.contains(&c.k) {
                births.push(c.k);
                for b in birth::birth_curves(plane, c.k) {
                    mine.push(out.curves.len());
                    out.curves.push(b);
                }
            }
        } else {
            for piece in cut(plane, c, &dead_ends) {
                mine.push(out.curves.len());
                out.curves.push(piece);
            }
        }
        pieces.push(mine);
    }
    // A birth line's codimension-two points go to the line drawn anew.
    for (i, c) in curves.iter().enumerate() {
        if c.kind == CurveKind::Birth && pieces[i].is_empty() {
            pieces[i] = (0..out.curves.len())
                .filter(|&j| out.curves[j].kind == CurveKind::Birth && out.curves[j].k == c.k)
                .collect();
        }
    }
    let inside = |alpha: f64, p: f64| within(plane, [alpha, p]);
    let mut kept = Vec::new();
    for mut q in std::mem::take(&mut out.codim2) {
        if !inside(q.alpha, q.p) {
            continue;
        }
        let near = |&j: &usize| distance(&out.curves[j], q.alpha, q.p);
        let Some(&j) = pieces[q.curve]
            .iter()
            .min_by(|a, b| near(a).total_cmp(&near(b)))
        else {
            continue;
        };
        q.curve = j;
        kept.push(q);
    }
    out.codim2 = kept;
    list_meets(out, tol);
    out.skipped
        .retain(|s| s.special.alpha >= plane.alpha.0 && s.special.alpha <= plane.alpha.1);
}

/// Whether y lies in `plane`'s window, to 1e-9 of its size.
fn within(plane: &Plane, y: [f64; 2]) -> bool {
    plane.spans(plane.alpha, y, 1e-9 * plane.scale())
}

/// The distance from (α, p) to the nearest point of `c`.
fn distance(c: &Curve, alpha: f64, p: f64) -> f64 {
    c.points
        .iter()
        .map(|q| (q.alpha - alpha).hypot(q.p - p))
        .fold(f64::INFINITY, f64::min)
}

/// `c`'s runs of points inside `plane`'s window, each as a curve.
fn cut(plane: &Plane, c: &Curve, dead_ends: &RefCell<Vec<DeadEnd>>) -> Vec<Curve> {
    let inside: Vec<bool> = c
        .points
        .iter()
        .map(|q| within(plane, [q.alpha, q.p]))
        .collect();
    if inside.iter().all(|&i| i) {
        return vec![c.clone()];
    }
    // A closed curve is cut open where it is outside, so that a run does not wrap
    // round its start.
    let (points, inside, ends) = if c.ends[0] == CurveEnd::Closed {
        let first_out = inside.iter().position(|&i| !i).unwrap_or(0);
        let mut pts = c.points[first_out..].to_vec();
        pts.extend_from_slice(&c.points[..first_out]);
        let mut ins = inside[first_out..].to_vec();
        ins.extend_from_slice(&inside[..first_out]);
        (pts, ins, [CurveEnd::Window; 2])
    } else {
        (c.points.clone(), inside, c.ends)
    };
    let tr = Tracer {
        plane,
        kind: c.kind,
        n: c.n,
        k: c.k,
        jumps: plane.jumps(c.seed[1]),
        dead_ends,
        hold: false,
    };
    let m = points.len();
    let mut out = Vec::new();
    let mut i = 0;
    while i < m {
        if !inside[i] {
            i += 1;
            continue;
        }
        let a = i;
        while i < m && inside[i] {
            i += 1;
        }
        let b = i - 1;
        let mut run = Vec::new();
        let mut run_ends = [ends[0], ends[1]];
        if a > 0 {
            let before = points.get(a + 1).filter(|_| a < b);
            run.extend(on_edge(plane, &tr, before, &points[a], &points[a - 1]));
            run_ends[0] = CurveEnd::Window;
        }
        run.extend_from_slice(&points[a..=b]);
        if b + 1 < m {
            let before = (b > a).then(|| &points[b - 1]);
            run.extend(on_edge(plane, &tr, before, &points[b], &points[b + 1]));
            run_ends[1] = CurveEnd::Window;
        }
        if run.len() >= 2 {
            out.push(Curve {
                points: run,
                ends: run_ends,
                ..c.clone()
            });
        }
    }
    out
}

/// The curve's point on the edge of `plane`'s window crossed between `inside` and the
/// next point `outside` (`before` the point on the other side of `inside`, if any):
/// solved on the edge's line from the point where the chord crosses it, the cycle
/// guessed as the tracer does (moved on from `inside` along the way it was moving),
/// else as `inside`'s or `outside`'s own (None where none of them gives it, or the
/// point lies off the chord by more than its length).
fn on_edge(
    plane: &Plane,
    tr: &Tracer,
    before: Option<&CurvePoint>,
    inside: &CurvePoint,
    outside: &CurvePoint,
) -> Option<CurvePoint> {
    let y = [inside.alpha, inside.p];
    let d = [outside.alpha - y[0], outside.p - y[1]];
    let w = [plane.alpha, plane.window];
    let (axis, bound, t) = crossing(w, y, [outside.alpha, outside.p])?;
    let start = [y[0] + t * d[0], y[1] + t * d[1]];
    let mut c = [0.0; 2];
    c[axis] = 1.0;
    let len = d[0].hypot(d[1]);
    let guesses = [
        secant(before, inside, t * len),
        inside.cycle.clone(),
        outside.cycle.clone(),
    ];
    let r = guesses.iter().find_map(|guess| {
        let (e, _) = tr.correct(start, c, bound, guess).ok()?;
        let off = (e.y[0] - start[0]).hypot(e.y[1] - start[1]);
        (off <= len).then(|| tr.point(e))
    });
    r
}
