//! [`NumWarning`]: what a numeric reduction or analysis (the descriptor reduction, the
//! steady-state gains, model reduction) found doubtful but computed anyway.

use std::fmt;

/// A warning of a numeric reduction or analysis (rank decisions close to their threshold,
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
    /// Steady-state gains: A was decided to have fewer zero eigenvalues than its structure
    /// proves; decided again at a tolerance `factor` times larger.
    GainZerosRedecided {
        /// Zero eigenvalues found at the default tolerance.
        found: usize,
        /// Zero eigenvalues the structure proves.
        structural: usize,
        /// The factor the tolerance was raised by.
        factor: f64,
        /// Zero eigenvalues found at the larger tolerance.
        redecided: usize,
    },
    /// Steady-state gains: the rank of A decided within a factor 100 of its threshold.
    GainFragileRank {
        /// The rank decided.
        rank: usize,
        /// How far the nearest singular value is from the threshold, as a factor.
        margin: f64,
        /// The threshold.
        threshold: f64,
    },
    /// Steady-state gains: a nullspace decision of the zero-eigenvalue chain within a factor
    /// 100 of its threshold.
    GainFragileZeroChain {
        /// The rank decided.
        rank: usize,
        /// How far the nearest singular value is from the threshold, as a factor.
        margin: f64,
    },
    /// Steady-state gains: the zero modes are poorly separated from the others.
    GainZeroModesMixed {
        /// cond [V₀ V₁].
        condition: f64,
    },
    /// Steady-state gains: A without its zero modes is ill-conditioned.
    GainReducedIllConditioned {
        /// Its condition number.
        condition: f64,
    },
    /// Steady-state gains: A is ill-conditioned (regular A).
    GainIllConditioned {
        /// Its condition number (an upper bound when `bound`).
        condition: f64,
        /// Whether `condition` is an upper bound (A certified regular by its inverse).
        bound: bool,
    },
    /// Model reduction: stable states that no balanced model keeps (Hankel singular value
    /// below n·ε·σ₁).
    HankelNegligible {
        /// How many.
        count: usize,
        /// Of how many stable states.
        stable: usize,
    },
    /// Model reduction: a stable mode nearly shares an eigenvalue with a kept one.
    StableKeptCoupling {
        /// The norm of the Sylvester solution that splits them (infinite when singular).
        norm: f64,
    },
    /// Model reduction: a kept mode nearly shares its eigenvalue with a removed one.
    ModalTruncationIllConditioned,
    /// Generalized eigenvalues: the rank of E forces infinite eigenvalues, but QZ sees one of
    /// them with θ = |β|/‖(α, β)‖ above the tolerance.
    InfiniteCountDisagrees {
        /// The rank of E.
        e_rank: usize,
        /// The infinite eigenvalues it forces (n − rank E).
        forced: usize,
        /// The largest θ among them.
        theta: f64,
        /// The tolerance on θ.
        tolerance: f64,
    },
    /// Generalized eigenvalues: the finite/infinite split is close (the ratio of θ across it
    /// below 100).
    CloseInfiniteSplit {
        /// The ratio of θ across the split.
        gap: f64,
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
            NumWarning::GainZerosRedecided { .. } => "gain_zeros_redecided",
            NumWarning::GainFragileRank { .. } => "gain_fragile_rank",
            NumWarning::GainFragileZeroChain { .. } => "gain_fragile_zero_chain",
            NumWarning::GainZeroModesMixed { .. } => "gain_zero_modes_mixed",
            NumWarning::GainReducedIllConditioned { .. } => "gain_reduced_ill_conditioned",
            NumWarning::GainIllConditioned { .. } => "gain_ill_conditioned",
            NumWarning::HankelNegligible { .. } => "hankel_negligible",
            NumWarning::StableKeptCoupling { .. } => "stable_kept_coupling",
            NumWarning::ModalTruncationIllConditioned => "modal_truncation_ill_conditioned",
            NumWarning::InfiniteCountDisagrees { .. } => "infinite_count_disagrees",
            NumWarning::CloseInfiniteSplit { .. } => "close_infinite_split",
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
            NumWarning::GainZerosRedecided {
                found,
                structural,
                factor,
                redecided,
            } => write!(
                f,
                "A was decided to have {found} zero eigenvalue(s) at the default tolerance, \
                 fewer than the {structural} its structure proves (a defective zero pair split \
                 by rounding); decided at a tolerance {factor} times larger, which finds \
                 {redecided}"
            ),
            NumWarning::GainFragileRank {
                rank,
                margin,
                threshold,
            } => write!(
                f,
                "rank of A ({rank}) decided within a factor {margin:.3} of the threshold \
                 {threshold:.3e}"
            ),
            NumWarning::GainFragileZeroChain { rank, margin } => write!(
                f,
                "a nullspace decision of the zero-eigenvalue chain (rank {rank}) was within a \
                 factor {margin:.3} of the threshold"
            ),
            NumWarning::GainZeroModesMixed { condition } => write!(
                f,
                "the zero modes are poorly separated from the others (cond [V₀ V₁] = \
                 {condition:.3e})"
            ),
            NumWarning::GainReducedIllConditioned { condition } => write!(
                f,
                "A without its zero modes has condition number {condition:.3e}"
            ),
            NumWarning::GainIllConditioned { condition, bound } => write!(
                f,
                "A has condition number {}{condition:.3e}: the gains lose about {:.0} digits",
                if *bound { "at most " } else { "" },
                condition.log10()
            ),
            NumWarning::HankelNegligible { count, stable } => write!(
                f,
                "{count} of the {stable} stable states are uncontrollable or unobservable to \
                 working precision (Hankel singular value below n·ε·σ₁): no balanced model \
                 keeps them"
            ),
            NumWarning::StableKeptCoupling { norm } => write!(
                f,
                "a stable mode nearly shares an eigenvalue with a kept (zero, marginal or \
                 unstable) one: the Sylvester solution that splits them has norm {norm:.3e}, \
                 and the stable part carries that much amplified rounding"
            ),
            NumWarning::ModalTruncationIllConditioned => f.write_str(
                "a kept mode nearly shares its eigenvalue with a removed one: modal truncation \
                 is ill-conditioned there",
            ),
            NumWarning::InfiniteCountDisagrees {
                e_rank,
                forced,
                theta,
                tolerance,
            } => write!(
                f,
                "rank(E) = {e_rank} forces {forced} infinite eigenvalues but QZ sees one with θ = \
                 {theta:.3e} > {tolerance:.3e}: the rank decision on E and the QZ disagree"
            ),
            NumWarning::CloseInfiniteSplit { gap } => write!(
                f,
                "the finite/infinite split is close: θ ratio {gap:.3} across it"
            ),
        }
    }
}
