//! Singular and higher-index descriptor pencils, and rank decisions too close to call.

/// The rank decision on a descriptor model's algebraic block A22 that found it singular.
#[derive(Debug, Clone, PartialEq)]
pub struct A22Rank {
    /// The numerical rank of E.
    pub e_rank: usize,
    /// The pencil's order.
    pub n: usize,
    /// The order of A22 (the algebraic equations).
    pub k: usize,
    /// The numerical rank of A22.
    pub a22_rank: usize,
    /// The smallest singular value of the equilibrated A22.
    pub smallest: f64,
    /// The rank threshold it fell below.
    pub threshold: f64,
}

impl std::fmt::Display for A22Rank {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let A22Rank {
            e_rank,
            n,
            k,
            a22_rank,
            smallest,
            threshold,
        } = self;
        write!(
            f,
            "E has rank {e_rank} of {n}; the algebraic block A22 ({k}×{k}) has rank {a22_rank} \
             (smallest singular value of the equilibrated A22 {smallest:.3e} ≤ threshold \
             {threshold:.3e})"
        )
    }
}

/// A descriptor pencil `s E − A` that is singular: the payload of
/// [`NumError::SingularPencil`](super::NumError::SingularPencil).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PencilError {
    /// A22 is singular and so is `s E − A` at generic points.
    #[error(
        "{0}, and sE − A is rank deficient at generic s: the equations do not determine the \
         motion (missing equation or redundant coordinate)"
    )]
    RankDeficient(A22Rank),
    /// QZ found an eigenvalue with α ≈ β ≈ 0: det(sE − A) vanishes identically.
    #[error(
        "QZ returned α ≈ β ≈ 0 (|α|/‖A‖ = {alpha:.2e}, |β|/‖E‖ = {beta:.2e}) for eigenvalue \
         {index}: det(sE − A) vanishes identically ({n}×{n} pencil, rank E = {e_rank})"
    )]
    VanishingEigenvalue {
        /// |α| relative to ‖A‖.
        alpha: f64,
        /// |β| relative to ‖E‖.
        beta: f64,
        /// The eigenvalue's index (from 0).
        index: usize,
        /// The pencil's order.
        n: usize,
        /// The numerical rank of E.
        e_rank: usize,
    },
}

/// A rank decision on A that the steady-state gains depend on but that lies too close to its
/// threshold: the payload of [`NumError::AmbiguousRank`](super::NumError::AmbiguousRank).
/// `factor` below is [`crate::gain::AMBIGUITY_FACTOR`].
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum AmbiguousRankError {
    /// Both decisions find fewer zero eigenvalues than the model's structure proves.
    #[error(
        "the structure of the model proves {structural} zero eigenvalue(s), but the rank \
         decisions on A ({n}×{n}) find {first} at the default threshold and {second} at one {} \
         times larger: the gains would amplify rounding",
        crate::gain::AMBIGUITY_FACTOR
    )]
    StructuralZeros {
        /// The zero eigenvalues the structure proves.
        structural: usize,
        /// A's order.
        n: usize,
        /// The zero eigenvalues found at the default threshold.
        first: usize,
        /// Those found at the raised threshold.
        second: usize,
    },
    /// The two decisions give different gains.
    #[error(
        "the rank of A ({n}×{n}) was decided within a factor {margin:.3} of its threshold, and \
         a threshold {} times larger ({second} zero eigenvalue(s) instead of {first}) gives \
         other gains ({} instead of {})",
        crate::gain::AMBIGUITY_FACTOR,
        crate::gain::describe(second_gains),
        crate::gain::describe(first_gains)
    )]
    Gains {
        /// A's order.
        n: usize,
        /// The decision's margin to its threshold.
        margin: f64,
        /// The zero eigenvalues found at the default threshold.
        first: usize,
        /// Those found at the raised threshold.
        second: usize,
        /// The gains at the default threshold (column-major).
        first_gains: Vec<crate::gain::Gain>,
        /// The gains at the raised threshold (column-major).
        second_gains: Vec<crate::gain::Gain>,
    },
}
