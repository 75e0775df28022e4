//! Generic assembly of the linearized equations, written once for every [`Scalar`].
//!
//! Coordinates: per body six, `p = [δx, δy, δz, θx, θy, θz]` (small global displacement of the
//! mass centre and small global rotation), and the perturbation velocities `w` in body axes.
//! The result is the set of sparse matrices of the first-order descriptor model
//! `M ẇ + C w + K p = F_u u + G_u u̇`, `ṗ = w − V p`, `J p = 0`, `N w = 0` before any
//! constraint elimination; [`reduce`](crate::reduce()) takes it from there.
//!
//! The assembly, one function per step:
//!
//! 1. **Validation** ([`Model::validate`](crate::Model::validate)): errors name the item and
//!    field; the warnings are kept in the result.
//! 2. **Item terms**: every body and then every item, in the order of
//!    [`KINDS`](crate::items::KINDS), adds its terms through the [`Assembly`] context: a body
//!    its mass and inertia, momentum and gyroscopic terms and the kinematic velocity matrix; a
//!    load the applied forces and their stiffness; a spring, flex point or beam its elastic rows
//!    `H` with their stiffness, damping and mass blocks; a link or rigid point its holonomic
//!    rows `J`, a nonholonomic point its rows `N`; an actuator a column of the input matrices,
//!    a sensor a row of the output matrices.
//! 3. **Statics** ([`statics`]): the preloads `λ_c` of the holonomic and `λ_e` of the elastic
//!    rows that hold the applied loads at the given geometry.
//! 4. **Tangent stiffness** ([`tangent`]): the geometric stiffness `K_T` of those preloads,
//!    and the preload of every item.
//! 5. **Result**: `K = K_e + K_T + K_L`, `M` plus the items' mass, `C = C_e + MV`, the
//!    constraint Jacobians, the input and output matrices.
//!
//! Deliberate differences from the EoM software of Minaker et al., each documented where it
//! happens:
//! * direction bases of 2-direction items are deterministic (a fixed construction from the
//!   axis), not an SVD null space that depends on rounding;
//! * the equilibrium check is relative per equation, not an absolute sum of squares;
//! * a statically indeterminate structure uses the elastic compatibility equations and reports
//!   the indeterminacy; only the self-stress of redundant rigid rows, which nothing
//!   determines, is chosen by minimum norm, with a warning naming the rows;
//! * rank and equilibrium decisions of the statics are made on nondimensionalised equations
//!   (moments over the model's length scale), so a negligible geometric offset is negligible;
//! * a body spinning about an axis that is not an axis of symmetry is an error (the
//!   constant-coefficient linearization in the non-spinning frame does not exist), instead of a
//!   silently incomplete gyroscopic term;
//! * a twist spring or link carrying a preload torque gets the geometric stiffness of a torque
//!   carried by the mean frame of its two bodies (like a constant-velocity joint), not the
//!   line-tension terms with the torque used as a tension;
//! * a rolling contact is recognised by a nonzero rolling axis, without exact floating-point
//!   tests on its norm.

mod context;
pub mod rank;
pub mod statics;
pub mod tangent;

pub use context::{
    Assembly, BodyFrame, ITEM_ROW, ItemRow, LagTerm, LineGeometry, PointGeometry, Reaction, Rows,
    Term,
};

use crate::error::ModelError;
use crate::geometry::{Name, Vec3};
use crate::warning::Warning;
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;
use statics::{StaticsProblem, StaticsResult, solve_statics};

/// Which row of an item a constraint or elastic row is (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RowLabel {
    /// Item kind, e.g. "rigid point".
    pub kind: &'static str,
    /// Item name.
    pub item: Name,
    /// "force", "moment", "end row" or "" for a line item's single row.
    pub part: &'static str,
    /// 1-based index within the part (0 for a single row).
    pub index: usize,
}

impl std::fmt::Display for RowLabel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} `{}`", self.kind, self.item)?;
        if !self.part.is_empty() {
            write!(f, " {} {}", self.part, self.index)?;
        }
        Ok(())
    }
}

/// What an output measures along its line: the displacement, or its first or second rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputOrder {
    /// The elongation (or twist angle).
    Displacement,
    /// Its rate.
    Velocity,
    /// Its second rate.
    Acceleration,
}

/// The axes in which an output's rates are taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFrame {
    /// Fixed (global) axes: the rates of the global displacements.
    Global,
    /// The moving bodies' axes: the body-axis velocities.
    Local,
}

/// What an output row measures: its order and the axes of its rates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputKind {
    /// Displacement, velocity or acceleration.
    pub order: OutputOrder,
    /// Global or body axes.
    pub frame: OutputFrame,
}

/// Static force carried by an item at the nominal configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Preload<S> {
    /// The item, e.g. ``rigid point `road` ``.
    pub item: String,
    /// Force exerted on body 1 by the item (global axes).
    pub force: Vec3<S>,
    /// Moment exerted on body 1 by the item, about the item's point (a line item: about its
    /// end on body 1).
    pub moment: Vec3<S>,
    /// For line items: the tension (twist items: the torque).
    pub tension: Option<S>,
    /// Whether the statics determines it: `false` for an item whose constraint rows take part
    /// in a self-stress of redundant rigid constraints (any multiple of the self-stress
    /// balances the loads as well; the minimum-norm preloads are used).
    pub unique: bool,
    /// Whether it is computed: `false` for a beam, whose end loads are not (it is reported as
    /// zero and adds no geometric stiffness).
    pub computed: bool,
}

/// How the static preloads were obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statics {
    /// No loads and no known preloads: all preloads are zero.
    Unloaded,
    /// Statically determinate: preloads from force balance alone.
    Determinate,
    /// Statically indeterminate: preloads from force balance and elastic compatibility.
    Indeterminate,
}

/// First-order lag states that items add to the mechanical equations (the unsteady
/// aerodynamics of a strip or wing: R. T. Jones' two states per surface):
/// `ẋ_a = A_a x_a + P_a p + W_a w`, and the force `F_a x_a` on the right-hand side of
/// `M ẇ + C w + K p = …`. Every reduction carries them as states after the mechanical ones.
#[derive(Clone, Debug)]
pub struct Lags<S> {
    /// One name per lag state (`strip.lag1`, …).
    pub names: Vec<String>,
    /// `A_a` (a × a).
    pub rate: SparseMatrix<S>,
    /// `P_a` (a × d).
    pub position: SparseMatrix<S>,
    /// `W_a` (a × d).
    pub velocity: SparseMatrix<S>,
    /// `F_a` (d × a).
    pub force: SparseMatrix<S>,
}

impl<S> Lags<S> {
    /// The number of lag states.
    pub fn len(&self) -> usize {
        self.names.len()
    }
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
}

/// The assembled (unreduced) linearized model.
#[derive(Clone, Debug)]
pub struct Assembled<S> {
    /// Model name.
    pub name: String,
    /// Body names, six coordinates each.
    pub bodies: Vec<String>,
    /// Mass-centre locations (for reports and mode shapes).
    pub locations: Vec<Vec3<S>>,
    /// `M_tot` (d × d).
    pub mass: SparseMatrix<S>,
    /// `K_tot = K_e + K_T + K_L` (d × d).
    pub stiffness: SparseMatrix<S>,
    /// `C_tot = C_e + MV` (d × d): damping plus momentum and gyroscopic terms.
    pub damping: SparseMatrix<S>,
    /// The kinematic velocity matrix `V` (`ṗ = w − V p`).
    pub velocity: SparseMatrix<S>,
    /// Holonomic constraint Jacobian `J` (q × d).
    pub holonomic: SparseMatrix<S>,
    /// Label of each row of `J`.
    pub holonomic_rows: Vec<RowLabel>,
    /// Nonholonomic constraint Jacobian `N` (t × d), acting on `w`.
    pub nonholonomic: SparseMatrix<S>,
    /// Label of each row of `N`.
    pub nonholonomic_rows: Vec<RowLabel>,
    /// Input force matrix `F_u` (d × m).
    pub input_force: SparseMatrix<S>,
    /// Input rate force matrix `G_u` (d × m).
    pub input_rate_force: SparseMatrix<S>,
    /// Sensor rows `C_s = −diag(gain)·J_s` (p × d).
    pub sensor_rows: SparseMatrix<S>,
    /// What each output row measures.
    pub output_kinds: Vec<OutputKind>,
    /// Feedthrough from sensor–actuator pairing (p × m).
    pub feedthrough: SparseMatrix<S>,
    /// Input names and units.
    pub inputs: Vec<(String, String)>,
    /// Output names and units.
    pub outputs: Vec<(String, String)>,
    /// Applied generalized forces `F` (d).
    pub applied: Vec<S>,
    /// Preloads of the constraint and elastic items.
    pub preloads: Vec<Preload<S>>,
    /// Which branch of the statics was used.
    pub statics: Statics,
    /// Lag states added by items (none for a purely mechanical model).
    pub lags: Lags<S>,
    /// Warnings from validation and assembly.
    pub warnings: Vec<Warning>,
}

impl<S: Scalar> Assembled<S> {
    /// Number of physical coordinates (6 per body).
    pub fn dim(&self) -> usize {
        6 * self.bodies.len()
    }
}

impl<S: Scalar> Assembly<'_, S> {
    /// Steps 3 to 5, once every body and item has added its terms: the static preloads, their
    /// geometric stiffness, and the matrices of the assembled model `name`.
    pub(crate) fn finish(mut self, name: &str) -> Result<Assembled<S>, ModelError> {
        let k_el = std::mem::replace(&mut self.stiffness, Triplets::new(0, 0)).build();
        let st = statics(&self, &k_el)?;
        self.warnings.extend(st.warnings);
        let (k_t, mut preloads) = tangent_stiffness(&self, &st.lambda_c, &st.lambda_e);
        // Holonomic items come first, in the order of their rows.
        let mut start = 0;
        for (r, p) in self.holonomic.reactions.iter().zip(preloads.iter_mut()) {
            p.unique = !st.not_unique[start..start + r.rows].iter().any(|&x| x);
            start += r.rows;
        }
        result(name, self, k_el, k_t, preloads, st.kind)
    }
}

/// Step 3: the static preloads.
fn statics<S: Scalar>(
    cx: &Assembly<'_, S>,
    k_el: &SparseMatrix<S>,
) -> Result<StaticsResult<S>, ModelError> {
    solve_statics(&StaticsProblem {
        dim: cx.dim(),
        j_rows: &cx.holonomic.rows,
        j_labels: &cx.holonomic.labels,
        h_rows: &cx.elastic.rows,
        applied: &cx.applied,
        known: &cx.known,
        stiffness_blocks: &cx.stiffness_blocks,
        k_el,
        bodies: &cx.bodies,
    })
}

/// Step 4: the geometric stiffness of the preloads, and the preload of every item
/// (holonomic items first, in the order of their multipliers).
fn tangent_stiffness<S: Scalar>(
    cx: &Assembly<'_, S>,
    lambda_c: &[S],
    lambda_e: &[S],
) -> (Triplets<S>, Vec<Preload<S>>) {
    let d = cx.dim();
    let mut k_t = Triplets::with_capacity(d, d, 4 * d);
    let mut preloads = Vec::new();
    tangent::add_reactions(&mut k_t, &cx.holonomic.reactions, lambda_c, &mut preloads);
    tangent::add_reactions(&mut k_t, &cx.elastic.reactions, lambda_e, &mut preloads);
    (k_t, preloads)
}

/// Step 5: the matrices of the assembled model.
fn result<S: Scalar>(
    name: &str,
    cx: Assembly<'_, S>,
    k_el: SparseMatrix<S>,
    k_t: Triplets<S>,
    preloads: Vec<Preload<S>>,
    statics: Statics,
) -> Result<Assembled<S>, ModelError> {
    let d = cx.dim();
    let stiffness = k_el.add(&k_t.build())?.add(&cx.load_stiffness.build())?;
    let s = cx.signals;
    let (nin, nout) = (s.inputs.len(), s.outputs.len());
    let matrix = |nrows, ncols, entries: Vec<(usize, usize, S)>| {
        let mut t = Triplets::with_capacity(nrows, ncols, entries.len());
        for (i, j, v) in entries {
            t.push(i, j, v);
        }
        t.build()
    };
    let na = cx.lags.names.len();
    let lags = Lags {
        rate: matrix(na, na, cx.lags.rate),
        position: matrix(na, d, cx.lags.position),
        velocity: matrix(na, d, cx.lags.velocity),
        force: matrix(d, na, cx.lags.force),
        names: cx.lags.names,
    };
    Ok(Assembled {
        name: name.to_string(),
        bodies: cx.bodies.iter().map(|b| b.name.to_string()).collect(),
        locations: cx.bodies.iter().map(|b| b.location).collect(),
        mass: cx.mass.build().add(&cx.item_mass.build())?,
        stiffness,
        damping: cx.damping.build().add(&cx.momentum.build())?,
        velocity: cx.velocity.build(),
        holonomic: SparseMatrix::from_sparse_rows(&cx.holonomic.rows, d),
        holonomic_rows: cx.holonomic.labels,
        nonholonomic: SparseMatrix::from_sparse_rows(&cx.nonholonomic.rows, d),
        nonholonomic_rows: cx.nonholonomic.labels,
        input_force: matrix(d, nin, s.input_force),
        input_rate_force: matrix(d, nin, s.input_rate_force),
        sensor_rows: matrix(nout, d, s.sensor_rows),
        output_kinds: s.output_kinds,
        feedthrough: matrix(nout, nin, s.feedthrough),
        inputs: s.inputs,
        outputs: s.outputs,
        applied: cx.applied,
        preloads,
        statics,
        lags,
        warnings: cx.warnings,
    })
}
