//! The error type of eom-num.

/// Everything that can go wrong in a numeric analysis. Messages name the matrix, signal or
/// parameter at fault.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum NumError {
    /// Matrix dimensions do not fit together.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
    /// A matrix contains NaN or infinite entries.
    #[error("non-finite entry in {0}")]
    NonFinite(String),
    /// A matrix entry so large ([`crate::MAX_ENTRY`]) that the products inside the
    /// factorisations would overflow: the message names the entry and its value.
    #[error("entry too large: {0}")]
    OutOfRange(String),
    /// An option or argument is out of its valid range (names the parameter).
    #[error("invalid option: {0}")]
    InvalidOption(String),
    /// An iterative factorisation (eigenvalues, SVD, QZ) did not converge.
    #[error("no convergence: {0}")]
    NoConvergence(String),
    /// A matrix that must be inverted is singular to working precision (names the matrix and
    /// gives the decision margin).
    #[error("singular matrix: {0}")]
    Singular(String),
    /// The descriptor pencil `s E − A` is singular (det(sE − A) ≡ 0): the model does not
    /// determine its own motion.
    #[error("singular pencil: {0}")]
    SingularPencil(String),
    /// The descriptor pencil is regular but has index > 1 (the algebraic block A22 is
    /// singular); only index-1 pencils are reduced.
    #[error("descriptor index > 1: {0}")]
    HigherIndex(String),
    /// A rank decision that the result depends on lies so close to its tolerance that another
    /// admissible tolerance gives a different answer (the message gives both): the result
    /// cannot be trusted either way.
    #[error("ambiguous rank decision: {0}")]
    AmbiguousRank(String),
    /// The analysis would need more memory than the limit ([`crate::budget`]); the message
    /// names the step, the predicted size, the limit and how to raise it.
    #[error("too large: {0}")]
    TooLarge(String),
}
