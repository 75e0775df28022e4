//! Helpers shared by the modes/freq/gain/time/descriptor/linalg tests: closed-form models,
//! polynomial arithmetic for transfer functions, seeded random matrices.
#![allow(dead_code)]

use eom_num::StateSpace;
use nalgebra::{DMatrix, dmatrix};
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Spring–mass–damper with position output: m x'' + c x' + k x = F.
pub fn smd(m: f64, c: f64, k: f64) -> StateSpace<f64> {
    StateSpace::new(
        dmatrix![0.0, 1.0; -k / m, -c / m],
        dmatrix![0.0; 1.0 / m],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap()
}

/// |a − b| / |b| (b ≠ 0).
pub fn rel(a: Complex64, b: Complex64) -> f64 {
    (a - b).norm() / b.norm().max(1e-300)
}

/// Seeded generator so that failures are reproducible.
pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// Matrix with entries uniform in (−1, 1).
pub fn random_matrix(r: &mut StdRng, rows: usize, cols: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, cols, |_, _| r.random_range(-1.0..1.0))
}

/// A well-conditioned random matrix (identity plus a small random part), for similarity
/// transforms that hide block structure without losing accuracy.
pub fn random_similarity(r: &mut StdRng, n: usize) -> DMatrix<f64> {
    DMatrix::identity(n, n) + random_matrix(r, n, n) * (0.5 / n as f64)
}

/// Evaluates a real polynomial with coefficients in ascending powers at s.
pub fn poly(coeffs: &[f64], s: Complex64) -> Complex64 {
    coeffs
        .iter()
        .rev()
        .fold(Complex64::new(0.0, 0.0), |acc, &c| acc * s + c)
}

/// Product of two polynomials (ascending coefficients).
pub fn poly_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// Difference of two polynomials (ascending coefficients).
pub fn poly_sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    let n = a.len().max(b.len());
    (0..n)
        .map(|i| a.get(i).copied().unwrap_or(0.0) - b.get(i).copied().unwrap_or(0.0))
        .collect()
}
