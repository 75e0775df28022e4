//! Helpers shared by the integration tests.
//!
//! (Reconstructed from its uses in `tests/linalg.rs` after the original was overwritten by
//! mistake; restore the original content if it differed.)
#![allow(dead_code)]

use nalgebra::DMatrix;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A seeded random generator.
pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// A matrix with entries uniform in [−1, 1].
pub fn random_matrix(rng: &mut StdRng, rows: usize, cols: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, cols, |_, _| rng.random_range(-1.0..1.0))
}
