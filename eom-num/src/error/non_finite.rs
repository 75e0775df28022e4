//! NaN and infinite values.

use super::MatrixEntry;

/// What holds a NaN or infinite value: the payload of [`NumError::NonFinite`](super::NumError::NonFinite).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum NonFiniteError {
    /// An entry of a matrix: `A[1, 0] = NaN (3×3 matrix)`.
    #[error("{0}")]
    Entry(MatrixEntry),
    /// A matrix (entry not located).
    #[error("{matrix}")]
    Matrix {
        /// The matrix (`A`, `B`, `C`).
        matrix: &'static str,
    },
    /// A point at which a frequency response is evaluated.
    #[error("evaluation point s = {s}")]
    EvaluationPoint {
        /// The point.
        s: num_complex::Complex64,
    },
    /// A simulation's initial state.
    #[error("initial state x0")]
    InitialState,
    /// An eigenvalue whose mode shape is asked for.
    #[error("eigenvalue {lambda}")]
    Eigenvalue {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
}
