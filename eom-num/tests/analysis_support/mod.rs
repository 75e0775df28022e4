//! Helpers shared by the integration tests: independent transfer-function evaluation, set
//! matching of eigenvalues, random test systems.
#![allow(dead_code)]

use eom_num::StateSpace;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// `C (sI − A)⁻¹ B + D` by a plain complex LU solve (independent of the code under test).
pub fn tf(ss: &StateSpace<f64>, s: Complex64) -> DMatrix<Complex64> {
    tf_parts(&ss.a, &ss.b, &ss.c, &ss.d, s)
}

/// `C (sI − A)⁻¹ B + D` from the four matrices.
pub fn tf_parts(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    s: Complex64,
) -> DMatrix<Complex64> {
    let n = a.nrows();
    let dc = d.map(|v| Complex64::new(v, 0.0));
    if n == 0 {
        return dc;
    }
    let m = DMatrix::from_fn(n, n, |i, j| {
        let v = Complex64::new(-a[(i, j)], 0.0);
        if i == j { v + s } else { v }
    });
    let bc = b.map(|v| Complex64::new(v, 0.0));
    let cc = c.map(|v| Complex64::new(v, 0.0));
    let x = m.lu().solve(&bc).expect("test point is not a pole");
    cc * x + dc
}

/// Largest relative difference of two transfer-function values over the points, relative to
/// the norm of the reference value.
pub fn tf_rel_error(ss: &StateSpace<f64>, reference: &StateSpace<f64>, pts: &[Complex64]) -> f64 {
    pts.iter()
        .map(|&s| {
            let g = tf(reference, s);
            let h = tf(ss, s);
            (h - &g).norm() / g.norm().max(1e-300)
        })
        .fold(0.0, f64::max)
}

/// Fixed complex test points away from the poles of the test systems.
pub fn points() -> Vec<Complex64> {
    vec![
        Complex64::new(0.3, 1.1),
        Complex64::new(-0.7, 2.3),
        Complex64::new(1.9, -0.4),
        Complex64::new(0.05, 0.5),
    ]
}

/// Matches each element of `a` to a distinct nearest element of `b` (greedy, in order of
/// distance) and returns the largest distance, each divided by `max(1, |b|)`. `None` when the
/// lengths differ.
pub fn set_distance(a: &[Complex64], b: &[Complex64]) -> Option<f64> {
    if a.len() != b.len() {
        return None;
    }
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            pairs.push(((x - y).norm() / y.norm().max(1.0), i, j));
        }
    }
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut ua = vec![false; a.len()];
    let mut ub = vec![false; b.len()];
    let mut worst = 0.0f64;
    for (d, i, j) in pairs {
        if !ua[i] && !ub[j] {
            ua[i] = true;
            ub[j] = true;
            worst = worst.max(d);
        }
    }
    Some(worst)
}

/// Whether every element of `a` is within `tol · max(1, |z|)` of some element of `b`.
pub fn subset_of(a: &[Complex64], b: &[Complex64], tol: f64) -> bool {
    a.iter()
        .all(|x| b.iter().any(|y| (x - y).norm() <= tol * y.norm().max(1.0)))
}

/// Eigenvalues by nalgebra's Schur form (independent of faer, used as a cross-check).
pub fn eig_nalgebra(a: &DMatrix<f64>) -> Vec<Complex64> {
    if a.nrows() == 0 {
        return Vec::new();
    }
    let mut v: Vec<Complex64> = a.clone().complex_eigenvalues().iter().copied().collect();
    v.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    v
}

/// A seeded random generator.
pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// A matrix with entries uniform in [−1, 1].
pub fn rand_mat(rng: &mut StdRng, r: usize, c: usize) -> DMatrix<f64> {
    DMatrix::from_fn(r, c, |_, _| rng.random_range(-1.0..1.0))
}

/// A random orthogonal matrix (Q of a QR factorization).
pub fn rand_orth(rng: &mut StdRng, n: usize) -> DMatrix<f64> {
    rand_mat(rng, n, n).qr().q()
}

/// Builds a state-space model from row-major nested lists.
pub fn mat(rows: &[&[f64]]) -> DMatrix<f64> {
    let r = rows.len();
    let c = if r == 0 { 0 } else { rows[0].len() };
    DMatrix::from_fn(r, c, |i, j| rows[i][j])
}
