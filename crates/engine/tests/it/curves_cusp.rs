//! A fold curve through a cusp: over (α, r) on F_1 the (4, 4) fold curve turns back on
//! itself tangentially, where three (4, 4) cycles coalesce. Checked with the exact map
//! alone: along the null direction of M − I the return's residual vanishes to third
//! order at the cusp (to second order at an ordinary fold point).

use super::curves_reach::fd1_over_r_to_eight;
use bouncemap_engine::orbits::curves::{Codim2Kind, CurveKind, CurvePoint, Plane};
use bouncemap_engine::orbits::periodic::{map_for, pass};

/// At the curve point q: the residual of the n-fold return F(x) = Pⁿ(x) − x from the
/// cycle's launch moved by s along the right null vector of M − I, projected on its
/// left null vector (M by central differences of the exact map), for each s.
fn along_null(plane: &Plane, q: &CurvePoint, s: &[f64]) -> Vec<f64> {
    let sys = plane.system(q.alpha, q.p).unwrap();
    let mut map = map_for(&sys);
    let (n, k) = (q.cycle.n, q.cycle.k);
    let x = [q.cycle.t0, q.cycle.velocities[0]];
    let mut f = |y: [f64; 2]| pass(&mut map, y[0], y[1], n, k).unwrap().residual;
    // A = M − I = ∂F/∂x.
    let h = 1e-6;
    let mut a = [[0.0; 2]; 2];
    for j in 0..2 {
        let (mut plus, mut minus) = (x, x);
        plus[j] += h;
        minus[j] -= h;
        let (fp, fm) = (f(plus), f(minus));
        for i in 0..2 {
            a[i][j] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    // Null vectors of the (nearly) singular A: right v ⟂ A's larger row, left w ⟂
    // A's larger column.
    let unit = |v: [f64; 2]| {
        let l = v[0].hypot(v[1]);
        [v[0] / l, v[1] / l]
    };
    let row = if a[0][0].hypot(a[0][1]) >= a[1][0].hypot(a[1][1]) {
        0
    } else {
        1
    };
    let v = unit([-a[row][1], a[row][0]]);
    let col = if a[0][0].hypot(a[1][0]) >= a[0][1].hypot(a[1][1]) {
        0
    } else {
        1
    };
    let w = unit([-a[1][col], a[0][col]]);
    s.iter()
        .map(|&s| {
            let r = f([x[0] + s * v[0], x[1] + s * v[1]]);
            w[0] * r[0] + w[1] * r[1]
        })
        .collect()
}

/// The (4, 4) fold of F_1 over (α 0.2..0.8, r 0.2..0.95) used to end `no_convergence`
/// at (0.53117, 0.68832): no point of it lies ahead there, on lines across its tangent
/// at 10⁻⁶ to 10⁻³ of the plane, and its cycle is well conditioned. It is a cusp: the
/// curve is followed through it in (α, r, t₀, v₀), where it is smooth, and goes on along
/// its other arm, back beside the first (the two arms' separation grows as the distance
/// to the power 3/2). At the cusp the return's residual along the null direction,
/// g(s) = w·F(x + s v), is odd and cubic in s (g(2s) = 8 g(s)): the zero is triple,
/// three cycles coalesce. At an ordinary point of the same curve it is even and
/// quadratic (a fold: two cycles).
#[test]
fn a_fold_curve_goes_on_through_a_cusp_where_three_cycles_coalesce() {
    let (plane, set) = fd1_over_r_to_eight();
    let cusps: Vec<_> = set
        .codim2
        .iter()
        .filter(|p| p.kind == Codim2Kind::Cusp)
        .collect();
    let at = cusps
        .iter()
        .find(|p| (p.alpha - 0.53117).abs() < 1e-4 && (p.p - 0.68832).abs() < 1e-4)
        .unwrap_or_else(|| panic!("a cusp near (0.53117, 0.68832): {cusps:?}"));
    let c = &set.curves[at.curve];
    assert!(
        c.kind == CurveKind::Fold && c.n == 4,
        "{:?} {}",
        c.kind,
        c.n
    );
    for end in c.ends {
        assert!(
            !matches!(end.as_str(), "no_convergence" | "stalled" | "step_limit"),
            "{:?}",
            c.ends
        );
    }
    // The cusp is a vertex of the curve, with points on both arms out to 10⁻³.
    let dist = |q: &CurvePoint| (q.alpha - at.alpha).hypot(q.p - at.p);
    let i = (0..c.points.len())
        .min_by(|&a, &b| dist(&c.points[a]).total_cmp(&dist(&c.points[b])))
        .unwrap();
    assert!(dist(&c.points[i]) < 1e-12, "{}", dist(&c.points[i]));
    assert!(c.points[..i].iter().any(|q| dist(q) > 1e-3));
    assert!(c.points[i..].iter().any(|q| dist(q) > 1e-3));

    let s = 5e-4;
    let g = along_null(plane, &c.points[i], &[s, -s, 2.0 * s]);
    let odd = (g[0] + g[1]).abs() / (g[0] - g[1]).abs();
    let cubic = g[2] / g[0];
    assert!(odd < 0.03, "odd part {g:?}");
    assert!((cubic - 8.0).abs() < 0.4, "g(2s)/g(s) = {cubic}");

    // An ordinary fold point of the same curve, 10⁻² from the cusp.
    let far = c
        .points
        .iter()
        .find(|q| dist(q) > 1e-2)
        .expect("a point 1e-2 from the cusp");
    let g = along_null(plane, far, &[s, -s, 2.0 * s]);
    let even = (g[0] - g[1]).abs() / (g[0] + g[1]).abs();
    assert!(even < 0.1, "even part {g:?}");
    assert!(
        (g[2] / g[0] - 4.0).abs() < 0.4,
        "g(2s)/g(s) = {}",
        g[2] / g[0]
    );
}
