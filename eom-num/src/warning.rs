//! [`NumWarning`]: what a numeric reduction found doubtful but computed anyway.

use std::fmt;

/// A warning of a numeric reduction (rank decisions close to their threshold,
/// ill-conditioning, entries treated as rounding noise), with the values that triggered it.
/// `Display` gives the message.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum NumWarning {
    /// A row or column of E at the rounding level of ‖E‖, treated as exactly zero.
    RoundingNoise {
        /// `"row"` or `"column"`.
        line: &'static str,
        /// Its index (from 0).
        index: usize,
        /// Its largest entry in magnitude.
        largest: f64,
        /// The rounding level it was compared with.
        noise: f64,
    },
    /// A rank decision within a factor 100 of its threshold.
    FragileRank {
        /// The decision (`"rank of E"`, `"invertibility of A22"`).
        what: &'static str,
        /// The rank decided.
        rank: usize,
        /// How far the nearest singular value is from the threshold, as a factor.
        margin: f64,
        /// The threshold.
        threshold: f64,
        /// The ratio of the singular values across the decision.
        gap: f64,
    },
    /// The kept part of E is ill-conditioned: the reduced model is stiff.
    StiffE {
        /// `σ_1/σ_r` of E.
        condition: f64,
    },
    /// The algebraic block A22 is ill-conditioned.
    IllConditionedA22 {
        /// Its size.
        size: usize,
        /// Its condition number (equilibrated).
        condition: f64,
    },
    /// A22's smallest singular value is near the rounding level of A and E's nullspace is
    /// not structural: the pencil may have index > 1.
    A22NearNoise {
        /// A22's smallest singular value.
        smallest: f64,
        /// The rounding level of A.
        noise: f64,
    },
}

impl NumWarning {
    /// The kind of warning, as a short snake-case name (`"fragile_rank"`).
    pub fn kind(&self) -> &'static str {
        match self {
            NumWarning::RoundingNoise { .. } => "rounding_noise",
            NumWarning::FragileRank { .. } => "fragile_rank",
            NumWarning::StiffE { .. } => "stiff_e",
            NumWarning::IllConditionedA22 { .. } => "ill_conditioned_a22",
            NumWarning::A22NearNoise { .. } => "a22_near_noise",
        }
    }
}

impl fmt::Display for NumWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumWarning::RoundingNoise {
                line,
                index,
                largest,
                noise,
            } => write!(
                f,
                "{line} {index} of E (largest entry {largest:.1e}) is rounding noise (≤ \
                 {noise:.1e}): treated as zero"
            ),
            NumWarning::FragileRank {
                what,
                rank,
                margin,
                threshold,
                gap,
            } => write!(
                f,
                "{what}: rank {rank} decided within a factor {margin:.3} of the threshold \
                 {threshold:.3e} (gap {gap:.3e}); the decision is fragile"
            ),
            NumWarning::StiffE { condition } => write!(
                f,
                "the kept part of E has condition number {condition:.3e} (σ_1/σ_r): the reduced \
                 model is stiff (nearly massless coordinates kept as dynamic)"
            ),
            NumWarning::IllConditionedA22 { size, condition } => write!(
                f,
                "A22 ({size}×{size}) has condition number {condition:.3e} (equilibrated): the \
                 elimination of the algebraic states loses about {:.0} digits",
                condition.log10()
            ),
            NumWarning::A22NearNoise { smallest, noise } => write!(
                f,
                "A22 (σ_min {smallest:.3e}) is within a factor 100 of the rounding level of A \
                 ({noise:.3e}) and E's nullspace is not structural: the pencil may have index > 1"
            ),
        }
    }
}
