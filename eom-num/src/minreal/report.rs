//! What the minimal realization decided and removed: its rank decisions, the removed modes
//! and the staircase forms.

use super::cser;
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

/// Which reduction a [`RankDecision`] belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum RankStage {
    /// Controllability staircase (input block `B`, then sub-diagonal blocks of `A`).
    Controllability,
    /// Observability staircase (the same on the dual system).
    Observability,
    /// PBH test of the controllable part at the mean of a cluster of `s` eigenvalues: the
    /// block is `[A_c − λI, B_c]`, and the `s` listed singular values are the residuals
    /// `‖wᴴ [A_c − λI, B_c]‖` of `s` orthonormal directions `w` found by inverse iteration
    /// (upper bounds of its `s` smallest singular values, equal to them when the iteration
    /// converged). `rank` counts the kept ones: `s − rank` directions were removed, at most
    /// `s − 1`, so a kept value may lie below the tolerance (reported as fragile).
    ControllabilityPbh,
    /// The same for observability: `[A_o − λI; C_o]` of the observable part.
    ObservabilityPbh,
    /// Transmission zeros: row compression of the feedthrough `D` (of the dual system when
    /// `dual`).
    Feedthrough {
        /// Whether the decision was taken on the dual (transposed) system.
        dual: bool,
    },
    /// Transmission zeros: compression of the output rows whose feedthrough is zero.
    OutputRows {
        /// Whether the decision was taken on the dual (transposed) system.
        dual: bool,
    },
    /// Transmission zeros: the final column compression of `[C D]`.
    FinalCompression,
}

/// One numerical rank decision: the singular values of a block and how they were split.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RankDecision {
    /// The reduction the decision belongs to.
    pub stage: RankStage,
    /// Step number within the stage (0 = first block).
    pub step: usize,
    /// Rows of the examined block.
    pub rows: usize,
    /// Columns of the examined block.
    pub cols: usize,
    /// Singular values of the block, largest first.
    pub singular_values: Vec<f64>,
    /// The tolerance used: singular values above it count.
    pub tolerance: f64,
    /// The decided rank.
    pub rank: usize,
    /// Ratio of the smallest kept to the largest dropped singular value; `None` when nothing
    /// was kept or nothing was dropped. A large gap means a clear decision.
    pub gap: Option<f64>,
}

impl RankDecision {
    pub(crate) fn new(
        stage: RankStage,
        step: usize,
        rows: usize,
        cols: usize,
        singular_values: Vec<f64>,
        tolerance: f64,
    ) -> Self {
        let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
        let gap = if rank > 0 && rank < singular_values.len() {
            Some(singular_values[rank - 1] / singular_values[rank])
        } else {
            None
        };
        RankDecision {
            stage,
            step,
            rows,
            cols,
            singular_values,
            tolerance,
            rank,
            gap,
        }
    }

    /// Smallest kept singular value (`None` if the rank is zero).
    pub fn smallest_kept(&self) -> Option<f64> {
        self.rank.checked_sub(1).map(|i| self.singular_values[i])
    }

    /// Largest dropped singular value (`None` if nothing was dropped).
    pub fn largest_dropped(&self) -> Option<f64> {
        self.singular_values.get(self.rank).copied()
    }

    /// Whether the decision would change if the tolerance were multiplied or divided by
    /// `factor` (e.g. 100): a kept singular value below `factor · tol`, or a dropped one above
    /// `tol / factor`. Such decisions deserve a look at the model.
    pub fn is_fragile(&self, factor: f64) -> bool {
        self.smallest_kept()
            .is_some_and(|s| s <= factor * self.tolerance)
            || self
                .largest_dropped()
                .is_some_and(|s| s > 0.0 && s * factor >= self.tolerance)
    }
}

/// Why a mode was removed by [`minimal_realization`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum RemovedKind {
    /// The inputs cannot excite the mode.
    Uncontrollable,
    /// The outputs cannot see the mode (it is controllable).
    Unobservable,
}

/// Stability class of a mode (see [`MinrealOptions::stability_rtol`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ModeStability {
    /// `Re λ < −threshold`.
    Stable,
    /// `|Re λ| ≤ threshold` (undamped oscillation, integrator, rigid-body mode).
    Marginal,
    /// `Re λ > threshold`.
    Unstable,
}

/// A mode removed by [`minimal_realization`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RemovedMode {
    /// The eigenvalue.
    #[serde(serialize_with = "cser::one")]
    pub eigenvalue: Complex64,
    /// Uncontrollable or unobservable.
    pub kind: RemovedKind,
    /// Stability class.
    pub stability: ModeStability,
    /// Independent (basis-free) confirmation of the removal, the Popov–Belevitch–Hautus
    /// residual: the smallest singular value of `[A − λI, B]` (uncontrollable) or
    /// `[A − λI; C]` (unobservable) of the full (balanced) system, divided by
    /// `max(‖A‖_F, ‖B‖_F)` or `max(‖A‖_F, ‖C‖_F)` — computed as the residual `‖wᴴ [A − λI, B]‖`
    /// of the direction `w` that inverse iteration finds, which is an upper bound of that
    /// singular value and equal to it once converged (a small value is a proof either way). Rounding level (≈1e-15) when the mode is
    /// exactly decoupled; a value near the rank tolerance means the mode is only weakly
    /// coupled and removing it changed the transfer function by about that much. `None` when
    /// [`MinrealOptions::pbh_check`] is off.
    pub pbh_residual: Option<f64>,
}

/// What [`minimal_realization`] did.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MinrealReport {
    /// States of the input system.
    pub states_in: usize,
    /// States of the minimal system.
    pub states_out: usize,
    /// Number of uncontrollable states removed.
    pub uncontrollable: usize,
    /// Number of unobservable (but controllable) states removed.
    pub unobservable: usize,
    /// How many of the uncontrollable states no input reaches in the graph of the exact
    /// zeros of `(A, B)` ([`crate::reach`]): removed exactly, without a rank decision.
    pub structurally_uncontrollable: usize,
    /// The same for the unobservable states: no path to an output.
    pub structurally_unobservable: usize,
    /// The removed modes, uncontrollable ones first, each group sorted by (re, im).
    pub removed: Vec<RemovedMode>,
    /// Every rank decision, in the order taken.
    pub decisions: Vec<RankDecision>,
    /// Relative tolerance used.
    pub rtol: f64,
    /// Absolute rank tolerance of the controllability stage.
    pub controllability_tolerance: f64,
    /// Absolute rank tolerance of the observability stage.
    pub observability_tolerance: f64,
    /// Threshold on `|Re λ|` used to classify removed modes.
    pub stability_threshold: f64,
    /// The state scaling applied by balancing (`x = diag(scaling) · x̃`), all 1 without it.
    pub scaling: Vec<f64>,
}

impl MinrealReport {
    /// Removed modes that are unstable or marginal: modes the minimal model cannot show but
    /// that still move the physical system.
    pub fn removed_not_stable(&self) -> impl Iterator<Item = &RemovedMode> {
        self.removed
            .iter()
            .filter(|r| r.stability != ModeStability::Stable)
    }

    /// Whether an unstable mode was removed.
    pub fn removed_unstable(&self) -> bool {
        self.removed
            .iter()
            .any(|r| r.stability == ModeStability::Unstable)
    }

    /// Decisions that would flip if the tolerance changed by `factor` (see
    /// [`RankDecision::is_fragile`]).
    pub fn fragile_decisions(&self, factor: f64) -> Vec<&RankDecision> {
        self.decisions
            .iter()
            .filter(|d| d.is_fragile(factor))
            .collect()
    }
}

/// A system in staircase form: `a = qᵀ A q`, `b = qᵀ B`, `c = C q`, where the leading `kept`
/// states are the controllable (for [`controllability_staircase`]) or observable (for
/// [`observability_staircase`]) part.
#[derive(Clone, Debug, PartialEq)]
pub struct Staircase {
    /// Transformed state matrix.
    pub a: DMatrix<f64>,
    /// Transformed input matrix.
    pub b: DMatrix<f64>,
    /// Transformed output matrix.
    pub c: DMatrix<f64>,
    /// The orthogonal transformation (old state = `q` · new state).
    pub q: DMatrix<f64>,
    /// Sizes of the staircase blocks (their sum is `kept`).
    pub blocks: Vec<usize>,
    /// Dimension of the controllable (observable) part.
    pub kept: usize,
    /// The rank decisions taken.
    pub decisions: Vec<RankDecision>,
}
