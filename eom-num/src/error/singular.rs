//! Matrices singular to working precision.

/// A matrix that must be inverted but is singular to working precision: the payload of
/// [`NumError::Singular`](super::NumError::Singular).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum SingularError {
    /// A matrix that passed its rank test but whose LU factorisation or solve then failed:
    /// `A22 (3×3) passed the rank test but its LU factorisation broke down`.
    #[error("{matrix} ({n}×{n}) {passed} but its LU {failed}")]
    LuFailed {
        /// The matrix (`A`, `E`, `A22`, `E11`).
        matrix: &'static str,
        /// Its order.
        n: usize,
        /// The test it passed (`passed the rank test`, `has full numerical rank`).
        passed: &'static str,
        /// What then failed (`factorisation broke down`, `solve is not finite`).
        failed: &'static str,
    },
    /// `sI − A` at a point that is numerically an eigenvalue of A.
    #[error("sI − A at s = {s} ({n}×{n} model): s is numerically an eigenvalue of A")]
    Eigenvalue {
        /// The point.
        s: num_complex::Complex64,
        /// The model's states.
        n: usize,
    },
    /// A 2×2 diagonal block of a Gramian's Cholesky factor that is singular.
    #[error(
        "Lyapunov equation: the Gramian's 2×2 diagonal block at {block} is singular though its \
         output is not zero"
    )]
    GramianBlock {
        /// The block's first row (from 0).
        block: usize,
    },
    /// The block A₂₂ that singular perturbation inverts.
    #[error("the residualised block A₂₂ of the balanced realization")]
    Residualised,
    /// The error system of a model reduction with a pole on the imaginary axis.
    #[error("the error system at ω = {omega} rad/s: a pole on the imaginary axis")]
    ErrorSystemPole {
        /// The frequency (rad/s).
        omega: f64,
    },
    /// The reduced feedthrough of the zero pencil is not square.
    #[error("reduced feedthrough of the zero pencil is {rows}×{cols} instead of square")]
    FeedthroughNotSquare {
        /// Its rows.
        rows: usize,
        /// Its columns.
        cols: usize,
    },
    /// `[C D]` of the reduced zero pencil without full row rank.
    #[error("[C D] of the reduced zero pencil has numerical rank {rank} < {rows}")]
    ZeroPencilRank {
        /// The numerical rank.
        rank: usize,
        /// The rows.
        rows: usize,
    },
    /// The zero pencil's `B_f` passed the conditioning test but its LU solve is not finite.
    #[error(
        "the {n}×{n} zero pencil: B_f passed the conditioning test but its LU solve is not \
         finite"
    )]
    ZeroPencilSolve {
        /// The pencil's order.
        n: usize,
    },
    /// A singular A whose zero-eigenvalue subspace the right and left chains disagree on.
    #[error(
        "A ({n}×{n}) is singular but its zero-eigenvalue subspace is ill-determined: the right \
         chain gives dimension {right} (index {right_index}), the left chain {left} (index \
         {left_index})"
    )]
    ZeroSubspace {
        /// A's order.
        n: usize,
        /// The dimension from the right chain.
        right: usize,
        /// Its index.
        right_index: usize,
        /// The dimension from the left chain.
        left: usize,
        /// Its index.
        left_index: usize,
    },
    /// The basis of the zero/nonzero eigenvalue split of A.
    #[error("the basis [V₀ V₁] of the zero/nonzero eigenvalue split of A ({n}×{n}) is singular")]
    SplitBasis {
        /// A's order.
        n: usize,
    },
    /// A restricted to its nonzero modes.
    #[error("A restricted to its nonzero modes ({n}×{n}) is singular")]
    NonzeroModes {
        /// The restriction's order.
        n: usize,
    },
    /// `A − λI` near an eigenvalue, in inverse iteration.
    #[error("A − λI near λ = {lambda}")]
    Shifted {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
    /// Inverse iteration that gave no vector.
    #[error("inverse iteration for λ = {lambda} did not give a vector")]
    InverseIteration {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
}
