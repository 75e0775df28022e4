//! The error type of eom-num: [`NumError`], whose variants carry typed payloads (one enum per
//! kind of trouble, each in its own file here).

mod convergence;
mod dimension;
mod non_finite;
mod option;
mod pencil;
mod singular;
#[cfg(test)]
mod tests;

pub use convergence::ConvergenceError;
pub use dimension::DimensionError;
pub use non_finite::NonFiniteError;
pub use option::{Bound, OptionError};
pub use pencil::{A22Rank, AmbiguousRankError, PencilError};
pub use singular::SingularError;

/// Everything that can go wrong in a numeric analysis. Messages name the matrix, signal or
/// parameter at fault.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum NumError {
    /// Matrix dimensions do not fit together (names the matrices, gives the sizes).
    #[error("dimension mismatch: {0}")]
    Dimension(DimensionError),
    /// A matrix, vector or point contains NaN or infinite entries (names it, and the entry
    /// where known).
    #[error("non-finite entry in {0}")]
    NonFinite(NonFiniteError),
    /// A matrix entry so large (beyond `max`, [`crate::MAX_ENTRY`]) that the products inside
    /// the factorisations would overflow.
    #[error(
        "entry too large: {entry}: larger in magnitude than {max:e}, beyond which the products \
         inside the factorisations overflow (express the model in other units)"
    )]
    OutOfRange {
        /// The entry.
        entry: MatrixEntry,
        /// The largest magnitude accepted.
        max: f64,
    },
    /// An option or argument is out of its valid range (names the option, gives the value).
    #[error("invalid option: {0}")]
    InvalidOption(OptionError),
    /// An iterative factorisation (eigenvalues, SVD, QZ) did not converge (names the step and
    /// the size).
    #[error("no convergence: {0}")]
    NoConvergence(ConvergenceError),
    /// A matrix that must be inverted is singular to working precision (names the matrix and
    /// gives the decision margin).
    #[error("singular matrix: {0}")]
    Singular(SingularError),
    /// The descriptor pencil `s E − A` is singular (det(sE − A) ≡ 0): the model does not
    /// determine its own motion.
    #[error("singular pencil: {0}")]
    SingularPencil(PencilError),
    /// The descriptor pencil is regular but has index > 1 (the algebraic block A22 is
    /// singular); only index-1 pencils are reduced.
    #[error(
        "descriptor index > 1: {0}; the pencil is regular, so its index is > 1 (e.g. a \
         constraint on a position without its derivative); reduce the index before calling \
         descriptor_to_state_space"
    )]
    HigherIndex(A22Rank),
    /// A rank decision that the result depends on lies so close to its tolerance that another
    /// admissible tolerance gives a different answer (the message gives both): the result
    /// cannot be trusted either way.
    #[error("ambiguous rank decision: {0}")]
    AmbiguousRank(AmbiguousRankError),
    /// The analysis would need more memory than the limit ([`crate::budget`]); the message
    /// names the step, the predicted size, the limit and how to raise it.
    #[error(
        "too large: {step} would need about {} of memory, more than the limit of {} (raise it \
         with the environment variable EOM_MEMORY_LIMIT, e.g. EOM_MEMORY_LIMIT=32G)",
        crate::budget::format_bytes(*bytes),
        crate::budget::format_bytes(*limit)
    )]
    TooLarge {
        /// The step that would allocate (`eigenvectors of a 40000×40000 matrix`).
        step: String,
        /// The predicted size in bytes.
        bytes: usize,
        /// The limit in bytes.
        limit: usize,
    },
}

/// An entry of a matrix, as an error names it: `A[1, 0] = 1e300 (3×3 matrix)`.
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixEntry {
    /// The matrix's name.
    pub matrix: String,
    /// Row index (from 0).
    pub row: usize,
    /// Column index (from 0).
    pub col: usize,
    /// The value found there.
    pub value: f64,
    /// Rows of the matrix.
    pub nrows: usize,
    /// Columns of the matrix.
    pub ncols: usize,
}

impl std::fmt::Display for MatrixEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}[{}, {}] = {:?} ({}×{} matrix)",
            self.matrix, self.row, self.col, self.value, self.nrows, self.ncols
        )
    }
}
