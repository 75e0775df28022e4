//! What a reduction returns: the state space, the plan of its decisions, the report.

use super::checks::ValidityCheck;
use crate::eliminate::EliminationPlan;
use crate::warning::Warning;
use eom_num::StateSpace;
use eom_sym::matrix::SparseMatrix;

/// The recorded decisions of a reduction.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct ReductionPlan {
    /// Active (kept) coordinates, as indices into the 6-per-body coordinate vector.
    pub active: Vec<usize>,
    /// Holonomic rows kept after removing the pinning rows.
    pub j_rows: Vec<usize>,
    /// Elimination of the position constraints.
    pub position: EliminationPlan,
    /// Elimination of the velocity constraints.
    pub velocity: EliminationPlan,
    /// Elimination of the reduced mass matrix.
    pub mass: EliminationPlan,
}

/// Sizes and decisions of a reduction, for reports.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReductionReport {
    /// Physical coordinates (6 per body).
    pub coordinates: usize,
    /// Coordinates removed before any algebra, with the constraint that pinned each.
    pub pinned: Vec<String>,
    /// Independent coordinates (position states).
    pub position_states: usize,
    /// Independent velocities.
    pub velocity_states: usize,
    /// Lag states of the items (unsteady aerodynamics), after the mechanical states.
    pub lag_states: usize,
    /// Constraint rows found redundant at the nominal point.
    pub redundant: Vec<String>,
    /// Warnings.
    pub warnings: Vec<Warning>,
}

/// The result of a reduction.
#[derive(Clone, Debug)]
pub struct Reduction<S: nalgebra::Scalar> {
    /// The state-space model (states `x̃ = x − Γu` when there are rate inputs).
    pub state_space: StateSpace<S>,
    /// Conditions under which the result is valid.
    pub checks: Vec<ValidityCheck<S>>,
    /// The decisions, replayable with another scalar type.
    pub plan: ReductionPlan,
    /// Sizes and decisions.
    pub report: ReductionReport,
    /// The reduced equations before the mass matrix is eliminated: `ẋ_p = K x` (the
    /// independent positions' kinematics) and `M ẋ_w = F x` (the dynamics), `x = [x_p; x_w]`.
    /// So `A = [K; M⁻¹F]`, and `det(sI − A) = det(sE − [K; F]) / det(M)` with
    /// `E = diag(I, M)`: the closed forms of a mechanical model come from this pencil, whose
    /// entries have no nested divisions by the mass matrix.
    pub descriptor: ReducedDescriptor<S>,
}

/// See [`Reduction::descriptor`].
#[derive(Clone, Debug)]
pub struct ReducedDescriptor<S> {
    /// The reduced mass matrix `M` (one row and column per independent velocity).
    pub mass: SparseMatrix<S>,
    /// `K`: the kinematic rows of the independent positions.
    pub kinematics: SparseMatrix<S>,
    /// `F`: the dynamic rows.
    pub dynamics: SparseMatrix<S>,
    /// The rows of the lag states (`ẋ_a = L x`, after the dynamic rows; empty without lag
    /// states): their rows of `E` are the identity.
    pub lags: SparseMatrix<S>,
}
