//! Small dense linear algebra on fixed-size arrays, for the orbits' Newton steps and
//! the multipliers of cycles: one Gaussian elimination for every N × N system, 2 × 2
//! matrix products, and the eigenvalues of a real 2 × 2 matrix (also as moduli, free of
//! cancellation), with the [`Complex`] type they are returned in.
//!
//! Nothing here knows about tables or maps; every caller in the engine uses these
//! instead of writing its own.

/// A complex number (an eigenvalue or a multiplier).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// |z|.
    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
}

/// A real 2 × 2 matrix, rows first.
pub type Mat2 = [[f64; 2]; 2];

/// The identity.
pub const IDENTITY: Mat2 = [[1.0, 0.0], [0.0, 1.0]];

/// Product of two 2 × 2 matrices, a·b.
pub fn mat_mul(a: Mat2, b: Mat2) -> Mat2 {
    [
        [
            a[0][0] * b[0][0] + a[0][1] * b[1][0],
            a[0][0] * b[0][1] + a[0][1] * b[1][1],
        ],
        [
            a[1][0] * b[0][0] + a[1][1] * b[1][0],
            a[1][0] * b[0][1] + a[1][1] * b[1][1],
        ],
    ]
}

/// Trace and determinant of a 2 × 2 matrix.
pub fn trace_det(m: Mat2) -> (f64, f64) {
    (m[0][0] + m[1][1], m[0][0] * m[1][1] - m[0][1] * m[1][0])
}

/// Eigenvalues of a real 2 × 2 matrix, the one of larger real part first.
pub fn eigenvalues_2x2(m: Mat2) -> [Complex; 2] {
    let (tr, det) = trace_det(m);
    eigenvalues_tr_det(tr, det)
}

/// Eigenvalues of a real 2 × 2 matrix with trace `tr` and determinant `det`, the one of
/// larger real part first (for a product of many matrices, pass the product of their
/// determinants: the small eigenvalue then keeps its relative precision).
pub fn eigenvalues_tr_det(tr: f64, det: f64) -> [Complex; 2] {
    let half = 0.5 * tr;
    let disc = half * half - det;
    if disc >= 0.0 {
        // Avoid cancellation: the larger-magnitude root first, the other from det.
        let s = disc.sqrt();
        let big = if half >= 0.0 { half + s } else { half - s };
        let small = if big != 0.0 { det / big } else { 0.0 };
        let (a, b) = if big >= small {
            (big, small)
        } else {
            (small, big)
        };
        [Complex { re: a, im: 0.0 }, Complex { re: b, im: 0.0 }]
    } else {
        let s = (-disc).sqrt();
        [Complex { re: half, im: s }, Complex { re: half, im: -s }]
    }
}

/// |μ₁| ≥ |μ₂| for the eigenvalues of a real 2 × 2 matrix with trace `tr` and
/// determinant `det`: those of [`eigenvalues_tr_det`] (the smaller real one from
/// det / μ₁, free of cancellation), and √|det| for both of a complex pair.
pub fn moduli_tr_det(tr: f64, det: f64) -> [f64; 2] {
    let [a, b] = eigenvalues_tr_det(tr, det);
    if a.im != 0.0 {
        let m = det.abs().sqrt();
        return [m, m];
    }
    let (x, y) = (a.re.abs(), b.re.abs());
    if x >= y {
        [x, y]
    } else {
        [y, x]
    }
}

/// Solve the N × N system `a x = b` by Gaussian elimination with partial pivoting; None
/// when a pivot is zero or not finite, or the solution is not finite.
pub fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    for c in 0..N {
        let p = (c..N).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c] == 0.0 || !a[p][c].is_finite() {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for i in c + 1..N {
            let f = a[i][c] / a[c][c];
            let pivot = a[c];
            for (x, p) in a[i][c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
            b[i] -= f * b[c];
        }
    }
    let mut x = [0.0; N];
    for i in (0..N).rev() {
        let s: f64 = (i + 1..N).map(|j| a[i][j] * x[j]).sum();
        x[i] = (b[i] - s) / a[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The inverse of the square matrix `a` (rows) by Gauss–Jordan elimination with partial
/// pivoting, for matrices whose size is known only at run time (the preconditioner of
/// a proof, which needs no rigour itself); None when a pivot is zero or not finite.
pub(crate) fn inverse(a: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    let mut m: Vec<Vec<f64>> = a
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut r = row.clone();
            r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
            r
        })
        .collect();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[p][c] == 0.0 || !m[p][c].is_finite() {
            return None;
        }
        m.swap(c, p);
        let pivot = m[c][c];
        for x in m[c].iter_mut() {
            *x /= pivot;
        }
        let row = m[c].clone();
        for (i, other) in m.iter_mut().enumerate() {
            if i != c && other[c] != 0.0 {
                let f = other[c];
                for (x, p) in other.iter_mut().zip(&row) {
                    *x -= f * p;
                }
            }
        }
    }
    let inv: Vec<Vec<f64>> = m.into_iter().map(|r| r[n..].to_vec()).collect();
    inv.iter().flatten().all(|v| v.is_finite()).then_some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_inverse_times_the_matrix_is_the_identity() {
        let a = vec![
            vec![2.0, 1.0, 0.0],
            vec![1.0, 3.0, 1.0],
            vec![0.0, 1.0, 4.0],
        ];
        let inv = inverse(&a).unwrap();
        for (i, row) in a.iter().enumerate() {
            for j in 0..3 {
                let p: f64 = row.iter().zip(&inv).map(|(x, r)| x * r[j]).sum();
                assert!((p - if i == j { 1.0 } else { 0.0 }).abs() < 1e-15);
            }
        }
        assert!(inverse(&[vec![1.0, 2.0], vec![2.0, 4.0]]).is_none());
    }

    #[test]
    fn eigenvalues_of_known_matrices() {
        // [[2, 1], [1, 2]]: 3 and 1.
        let e = eigenvalues_2x2([[2.0, 1.0], [1.0, 2.0]]);
        assert!((e[0].re - 3.0).abs() < 1e-15 && (e[1].re - 1.0).abs() < 1e-15);
        // Rotation by 90°: ±i.
        let e = eigenvalues_2x2([[0.0, -1.0], [1.0, 0.0]]);
        assert!(e[0].re.abs() < 1e-15 && (e[0].im.abs() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn moduli_are_those_of_the_eigenvalues_and_keep_the_small_one_exact() {
        assert_eq!(moduli_tr_det(0.0, 4.0), [2.0, 2.0]);
        // tr 3 + 1e-20, det 3e-20: eigenvalues 3 and 1e-20 (no cancellation).
        let m = moduli_tr_det(3.0 + 1e-20, 3e-20);
        assert_eq!(m[0], 3.0);
        assert!((m[1] - 1e-20).abs() < 1e-35);
        // Negative eigenvalues: moduli, larger first.
        let m = moduli_tr_det(-5.0, 4.0);
        assert_eq!(m, [4.0, 1.0]);
    }

    #[test]
    fn solve_matches_a_known_solution_and_refuses_singular_systems() {
        // The 4 × 4 Hilbert-like system with solution (1, −2, 3, −4).
        let a = [
            [4.0, 1.0, 0.5, 0.25],
            [1.0, 3.0, 1.0, 0.5],
            [0.5, 1.0, 2.0, 1.0],
            [0.25, 0.5, 1.0, 5.0],
        ];
        let x = [1.0, -2.0, 3.0, -4.0];
        let b: [f64; 4] = std::array::from_fn(|i| (0..4).map(|j| a[i][j] * x[j]).sum());
        let got = solve(a, b).unwrap();
        for i in 0..4 {
            assert!((got[i] - x[i]).abs() < 1e-14, "{got:?}");
        }
        // A pivot needs a row swap.
        assert_eq!(
            solve([[0.0, 1.0], [1.0, 0.0]], [2.0, 3.0]),
            Some([3.0, 2.0])
        );
        assert_eq!(solve([[1.0, 2.0], [2.0, 4.0]], [1.0, 2.0]), None);
    }
}
