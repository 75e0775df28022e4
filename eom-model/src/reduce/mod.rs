//! Reduction of the assembled model to state space by structured elimination with pivots
//! chosen at the nominal point — the symbolic-numeric path.
//!
//! 1. **Structure first.** A holonomic constraint row with a single entry pins one coordinate;
//!    when nothing in the kinematics `ṗ = w − V p` can make that coordinate's velocity nonzero
//!    either, the coordinate is removed before any algebra (a planar model pays for its planar
//!    coordinates only).
//! 2. **Positions.** Gauss–Jordan on the remaining `J` gives the dependent coordinates in terms
//!    of the independent ones, `p = R_p x_p`.
//! 3. **Velocities.** `J w = J V p` and `N w = 0`: the same elimination of `J` is replayed
//!    first (identical operations give identical, hash-consed expressions — `J` is eliminated
//!    once), then the nonholonomic rows; this gives `w = W_p x_p + R_w x_w`.
//! 4. **Dynamics.** The equations are projected on the admissible velocities (`R_wᵀ`, which
//!    annihilates every constraint reaction), the kinematic equations are kept for the
//!    independent coordinates only (exact, since `J ṗ = 0` by construction), and the reduced
//!    mass matrix `R_wᵀ M R_w` is eliminated (Gauss–Jordan, nominal pivots).
//!    Lag states of the items (`Assembled::lags`: `ẋ_a = A_a x_a + P_a p + W_a w`, force
//!    `F_a x_a`) follow as states `x = [x_p; x_w; x_a]`: their force is projected with the
//!    dynamics, their equations by `p = P x`, `w = W x`.
//! 5. **Inputs with rates** (`G_u u̇`) are absorbed by the state change `x̃ = x − Γu`.
//! 6. **Outputs.** Displacements and velocities directly; accelerations by differentiating the
//!    velocity output through the reduced model (`C_acc = C_vel A`, `D_acc = C_vel B`), which
//!    includes every constraint reaction (an acceleration taken from the unconstrained
//!    equations, as in the EoM software, would miss the reactions).
//!
//! Every pivot and rank decision is recorded ([`ReductionPlan`]) and can be replayed with any
//! scalar type; the pivots and the negligible entries of the rank decisions are returned as
//! [`ValidityCheck`]s, which define the region where a symbolic result is valid.

mod checks;
mod matrices;
mod result;
mod steps;

pub use checks::{CheckLabel, Coord, ValidityCheck};
pub use result::{ReducedDescriptor, Reduction, ReductionPlan, ReductionReport};
pub use steps::{reduce, reduce_report};

/// Pivot ratio below which a recorded pivot counts as broken down at an evaluation point:
/// `|pivot| < PIVOT_TOLERANCE · max |entry of its row|`.
pub const PIVOT_TOLERANCE: f64 = 1e-4;

/// Relative size above which an entry that decided a rank at the nominal point invalidates
/// the decision elsewhere.
pub const RANK_TOLERANCE: f64 = 1e-8;
