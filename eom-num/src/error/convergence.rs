//! Iterations that did not converge.

/// An iterative factorisation that did not converge: the payload of
/// [`NumError::NoConvergence`](super::NumError::NoConvergence).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ConvergenceError {
    /// A factorisation of a whole matrix or pencil: `SVD of a 3×4 matrix`.
    #[error("{step} of a {rows}×{cols} {object}")]
    Factorisation {
        /// The factorisation (`SVD`, `singular values`, `eigenvalues`, `QZ`).
        step: &'static str,
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// `matrix` or `pencil`.
        object: &'static str,
    },
    /// The QR iteration of the small-matrix eigenvalue solver.
    #[error("eigenvalues of a {n}×{n} matrix: the QR iteration did not converge")]
    QrIteration {
        /// The order.
        n: usize,
    },
    /// The SVD of a block of the staircase form (`detail`: the SVD's own report).
    #[error("SVD of a {rows}×{cols} block: {detail}")]
    BlockSvd {
        /// Rows of the block.
        rows: usize,
        /// Columns of the block.
        cols: usize,
        /// The factorisation's own report.
        detail: String,
    },
    /// A step of a PBH test at an eigenvalue.
    #[error("{step} at λ = {lambda}{}", detail_suffix(detail))]
    AtEigenvalue {
        /// The step (`PBH SVD`, `inverse iteration of the PBH test`).
        step: &'static str,
        /// The eigenvalue.
        lambda: num_complex::Complex64,
        /// The factorisation's own report, if it gave one.
        detail: Option<String>,
    },
    /// The QR iteration of the real Schur form of the state matrix.
    #[error("the real Schur form of the {n}×{n} state matrix (QR iteration)")]
    Schur {
        /// The order.
        n: usize,
    },
    /// Two diagonal blocks of a real Schur form too close to swap.
    #[error(
        "reordering the real Schur form: swapping the blocks of {first:?} and {second:?} would \
         perturb them by {perturbation:.3e} relative to {scale:.3e} (eigenvalues too close to \
         separate)"
    )]
    SchurSwap {
        /// The eigenvalues of the first block.
        first: Vec<num_complex::Complex64>,
        /// The eigenvalues of the second block.
        second: Vec<num_complex::Complex64>,
        /// The size of the swap's residual.
        perturbation: f64,
        /// The blocks' norm.
        scale: f64,
    },
    /// The QZ iteration of the reduced zero pencil.
    #[error("QZ of the {n}×{n} reduced zero pencil: {detail}")]
    ZeroPencilQz {
        /// The pencil's order.
        n: usize,
        /// The factorisation's own report.
        detail: String,
    },
}

/// `: detail` where a factorisation gave its own report.
fn detail_suffix(detail: &Option<String>) -> String {
    detail
        .as_ref()
        .map(|d| format!(": {d}"))
        .unwrap_or_default()
}
