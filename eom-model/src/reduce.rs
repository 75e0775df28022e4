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

use super::assemble::{Assembled, RowLabel};
use super::assemble::{OutputFrame, OutputOrder};
use super::eliminate::{
    EliminationPlan, PivotRecord, RankRecord, RowStore, Rref, rref, rref_keeping,
};
use crate::error::ModelError;
use crate::geometry::Name;
use crate::warning::Warning;
use eom_num::{SignalNames, StateSpace};
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;
use nalgebra::DMatrix;

/// Pivot ratio below which a recorded pivot counts as broken down at an evaluation point:
/// `|pivot| < PIVOT_TOLERANCE · max |entry of its row|`.
pub const PIVOT_TOLERANCE: f64 = 1e-4;

/// Relative size above which an entry that decided a rank at the nominal point invalidates
/// the decision elsewhere.
pub const RANK_TOLERANCE: f64 = 1e-8;

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

/// A coordinate or velocity of a body (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Coord {
    /// Body name.
    pub body: Name,
    /// 0..6: x, y, z, rx, ry, rz.
    pub dof: usize,
    /// The perturbation velocity (vx … wz) instead of the displacement.
    pub velocity: bool,
}

impl std::fmt::Display for Coord {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&coord_text(&self.body, self.dof, self.velocity))
    }
}

/// The text of a [`Coord`] (`body.x`, `body.vx`, …), built in one allocation: state names
/// are made on every reduction, and formatting machinery would grow the string piecewise.
fn coord_text(body: &str, dof: usize, velocity: bool) -> String {
    let n = if velocity { VELO[dof] } else { COORD[dof] };
    let mut s = String::with_capacity(body.len() + 1 + n.len());
    s.push_str(body);
    s.push('.');
    s.push_str(n);
    s
}

/// What a validity check guards (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CheckLabel {
    /// A pivot of the position-constraint elimination.
    PositionPivot {
        /// The dependent coordinate.
        coord: Coord,
        /// The constraint row.
        row: RowLabel,
    },
    /// A position-constraint row declared redundant.
    PositionRank {
        /// The row.
        row: RowLabel,
    },
    /// A pivot of the velocity-constraint elimination.
    VelocityPivot {
        /// The dependent velocity.
        coord: Coord,
        /// The constraint row.
        row: RowLabel,
    },
    /// A velocity-constraint row declared redundant.
    VelocityRank {
        /// The row.
        row: RowLabel,
    },
    /// The right-hand side of a redundant velocity row must vanish.
    VelocityConsistency {
        /// The row.
        row: RowLabel,
    },
    /// A pivot of the reduced mass matrix.
    MassPivot {
        /// The eliminated velocity.
        state: Coord,
        /// The equation row.
        row: Coord,
    },
    /// A reduced-mass row declared singular.
    MassRank {
        /// The row.
        row: Coord,
    },
}

impl std::fmt::Display for CheckLabel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CheckLabel::PositionPivot { coord, row } => {
                write!(f, "pivot on {coord} in position constraint {row}")
            }
            CheckLabel::PositionRank { row } => {
                write!(f, "redundancy of position constraint {row}")
            }
            CheckLabel::VelocityPivot { coord, row } => write!(
                f,
                "pivot on the velocity of {coord} in velocity constraint {row}"
            ),
            CheckLabel::VelocityRank { row } => {
                write!(f, "redundancy of velocity constraint {row}")
            }
            CheckLabel::VelocityConsistency { row } => {
                write!(f, "consistency of redundant velocity constraint {row}")
            }
            CheckLabel::MassPivot { state, row } => {
                write!(f, "reduced mass pivot of {state} (row {row})")
            }
            CheckLabel::MassRank { row } => write!(f, "redundancy of reduced mass row {row}"),
        }
    }
}

/// One condition for a symbolic result to be valid at an evaluation point.
#[derive(Clone, Debug)]
pub enum ValidityCheck<S> {
    /// `|value| ≥ PIVOT_TOLERANCE · max(|value|, |row entries|)`.
    Pivot {
        /// What the pivot eliminates.
        what: CheckLabel,
        /// The pivot.
        value: S,
        /// The other entries of its row.
        row: Vec<S>,
    },
    /// `|value| ≤ RANK_TOLERANCE · max |scale entries|`.
    Negligible {
        /// Which rank decision.
        what: CheckLabel,
        /// The entry that must stay negligible.
        value: S,
        /// The entries that set its scale.
        scale: Vec<S>,
    },
}

impl<S: Scalar> ValidityCheck<S> {
    /// Description of the check.
    pub fn what(&self) -> String {
        self.label().to_string()
    }

    /// What the check guards.
    pub fn label(&self) -> &CheckLabel {
        match self {
            ValidityCheck::Pivot { what, .. } | ValidityCheck::Negligible { what, .. } => what,
        }
    }

    /// Test the check on numeric values (the check's expressions evaluated at a point).
    pub fn holds(value: f64, others: &[f64], pivot: bool) -> bool {
        let m = others.iter().fold(value.abs(), |a, b| a.max(b.abs()));
        if pivot {
            value.is_finite() && value.abs() >= PIVOT_TOLERANCE * m && m > 0.0
        } else {
            let s = others.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            value.abs() <= RANK_TOLERANCE * s || value == 0.0
        }
    }

    fn holds_nominal(&self) -> bool {
        match self {
            ValidityCheck::Pivot { value, row, .. } => {
                let o: Vec<f64> = row.iter().map(|x| x.nominal()).collect();
                Self::holds(value.nominal(), &o, true)
            }
            ValidityCheck::Negligible { value, scale, .. } => {
                let o: Vec<f64> = scale.iter().map(|x| x.nominal()).collect();
                Self::holds(value.nominal(), &o, false)
            }
        }
    }
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

const COORD: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
const VELO: [&str; 6] = ["vx", "vy", "vz", "wx", "wy", "wz"];

fn to_rows<S: Scalar>(m: &SparseMatrix<S>) -> RowStore<S> {
    RowStore::from_matrix(m)
}

fn hstack<S: Scalar>(
    a: &SparseMatrix<S>,
    b: &SparseMatrix<S>,
) -> Result<SparseMatrix<S>, ModelError> {
    Ok(SparseMatrix::hcat(&[a, b])?)
}

fn vstack<S: Scalar>(
    a: &SparseMatrix<S>,
    b: &SparseMatrix<S>,
) -> Result<SparseMatrix<S>, ModelError> {
    if a.nrows() == 0 {
        return Ok(b.clone());
    }
    if b.nrows() == 0 {
        return Ok(a.clone());
    }
    Ok(SparseMatrix::vcat(a, b)?)
}

fn record_checks<S: Scalar>(
    r: &Rref<S>,
    pivot_label: &dyn Fn(usize, usize) -> CheckLabel,
    rank_label: &dyn Fn(usize) -> CheckLabel,
    out: &mut Vec<ValidityCheck<S>>,
) {
    for PivotRecord {
        row,
        col,
        value,
        row_entries,
    } in &r.pivot_records
    {
        if value.is_one()
            || (row_entries.is_empty() && value.nominal() != 0.0 && is_constant(value))
        {
            continue;
        }
        out.push(ValidityCheck::Pivot {
            what: pivot_label(*row, *col),
            value: *value,
            row: row_entries.clone(),
        });
    }
    for RankRecord {
        row,
        value,
        scale_entries,
    } in &r.rank_records
    {
        out.push(ValidityCheck::Negligible {
            what: rank_label(*row),
            value: *value,
            scale: scale_entries.clone(),
        });
    }
}

/// A scalar that cannot change with the parameters (for f64 every value; for expressions the
/// numeric constants). Constant pivots need no runtime check.
fn is_constant<S: Scalar>(v: &S) -> bool {
    // A value equal to its own nominal for every type: numbers. For expressions the only way to
    // tell is through the f64 round trip of `from_f64(nominal) == v`.
    S::from_f64(v.nominal()) == *v
}

/// Reduce an assembled model to state space (see the module documentation for the steps).
/// With `plan = None` the pivots are chosen at the nominal point and recorded; with a plan
/// they are replayed (the fast numeric path), and the returned checks tell whether the plan
/// is still valid at this point.
pub fn reduce<S: Scalar>(
    a: &Assembled<S>,
    plan: Option<&ReductionPlan>,
) -> Result<Reduction<S>, ModelError> {
    let mut cx = Reducer::new(a, plan);
    let sel = cx.pin_coordinates();
    let pos = cx.eliminate_positions(&sel)?;
    let velo = cx.eliminate_velocities(&sel, &pos)?;
    let dyn_ = cx.project_dynamics(&sel, &pos, &velo)?;
    let [a_ss, b_ss, gamma] = absorb_input_rates(&pos, &dyn_)?;
    let (c_out, d_out) = outputs(a, &sel, &dyn_, &a_ss, &b_ss, &gamma)?;
    cx.finish(sel, pos, velo, dyn_, [a_ss, b_ss, c_out, d_out], &gamma)
}

/// The numeric reduction of [`reduce`] without its dense result: every step and every check
/// of the nominal point, and the report (`position_states + velocity_states` states), but no
/// dense `A` and map to the physical coordinates, whose `(2n)² + 6 b · 2n` entries (n
/// freedoms, b bodies) are what a model of many bodies cannot hold: 10 000 bodies on sliders
/// needed 15.7 GB for them (issue 27, item 7). For validating a model (`eom check`); the
/// states are `position_states + velocity_states + lag_states`.
///
/// Errors: as [`reduce`].
pub fn reduce_report(a: &Assembled<f64>) -> Result<ReductionReport, ModelError> {
    let mut cx = Reducer::new(a, None);
    let sel = cx.pin_coordinates();
    let pos = cx.eliminate_positions(&sel)?;
    let velo = cx.eliminate_velocities(&sel, &pos)?;
    let dyn_ = cx.project_dynamics(&sel, &pos, &velo)?;
    let [a_ss, b_ss, gamma] = absorb_input_rates(&pos, &dyn_)?;
    outputs(a, &sel, &dyn_, &a_ss, &b_ss, &gamma)?;
    cx.check_nominal()?;
    Ok(cx.report)
}

/// What the steps share: the assembled model, the plan to replay, the checks and the report.
struct Reducer<'a, S> {
    a: &'a Assembled<S>,
    plan: Option<&'a ReductionPlan>,
    /// Shared names for check labels, made only when a check needs one (a numeric reduction
    /// without a plan records none).
    body_names: std::cell::OnceCell<Vec<Name>>,
    checks: Vec<ValidityCheck<S>>,
    report: ReductionReport,
}

/// Step 1: the active coordinates, the kept holonomic rows, and the matrices restricted to
/// them.
struct Selection<S> {
    active: Vec<usize>,
    j_keep: Vec<usize>,
    /// `J` (kept rows, active columns) and `N` (active columns).
    jm: SparseMatrix<S>,
    nm: SparseMatrix<S>,
    mass: SparseMatrix<S>,
    stiff: SparseMatrix<S>,
    damp: SparseMatrix<S>,
    vel: SparseMatrix<S>,
    f_u: SparseMatrix<S>,
    g_u: SparseMatrix<S>,
    c_s: SparseMatrix<S>,
    /// The lag states' blocks on the active coordinates: `P_a`, `W_a` (columns) and `F_a`
    /// (rows).
    lag_p: SparseMatrix<S>,
    lag_w: SparseMatrix<S>,
    lag_f: SparseMatrix<S>,
}

impl<S: Scalar> Selection<S> {
    /// The inertia of each active coordinate at the nominal point (the mass matrix's
    /// diagonal): the pivot choice keeps the heavy ones independent (see [`rref`]).
    fn inertia(&self) -> Vec<f64> {
        (0..self.active.len())
            .map(|c| self.mass.get(c, c).nominal().abs())
            .collect()
    }
}

/// Step 2: the position elimination and `p = R_p x_p`.
struct Positions<S> {
    rj: Rref<S>,
    indep_p: Vec<usize>,
    rp: SparseMatrix<S>,
}

/// Step 3: the velocity elimination and `w = W_p x_p + R_w x_w`.
struct Velocities<S> {
    rg: Rref<S>,
    indep_w: Vec<usize>,
    rw: SparseMatrix<S>,
    wp: SparseMatrix<S>,
}

/// Step 4: the reduced model's parts.
struct Dynamics<S> {
    rm: Rref<S>,
    /// `w = W x`, `p = P x`, `ṗ = (W − V P) x`.
    wfull: SparseMatrix<S>,
    pfull: SparseMatrix<S>,
    kin: SparseMatrix<S>,
    /// The kinematic rows of the independent coordinates.
    a1: SparseMatrix<S>,
    /// The reduced mass matrix and the dynamic rows before its elimination.
    m_r: SparseMatrix<S>,
    rhs_a: SparseMatrix<S>,
    /// The solved dynamic rows: state, input and input-rate columns.
    xa: SparseMatrix<S>,
    /// The lag states' rows `ẋ_a = L x` (empty without lag states).
    lag: SparseMatrix<S>,
    xb: SparseMatrix<S>,
    xg: SparseMatrix<S>,
}

impl<'a, S: Scalar> Reducer<'a, S> {
    fn new(a: &'a Assembled<S>, plan: Option<&'a ReductionPlan>) -> Self {
        Reducer {
            a,
            plan,
            body_names: std::cell::OnceCell::new(),
            checks: Vec::new(),
            report: ReductionReport {
                coordinates: a.dim(),
                warnings: a.warnings.clone(),
                ..Default::default()
            },
        }
    }

    /// Coordinate `g` (a displacement, or its velocity) as a check label.
    fn coord(&self, g: usize, velocity: bool) -> Coord {
        let names = self.body_names.get_or_init(|| {
            self.a
                .bodies
                .iter()
                .map(|b| Name::from(b.as_str()))
                .collect()
        });
        Coord {
            body: names[g / 6].clone(),
            dof: g % 6,
            velocity,
        }
    }

    /// The name of coordinate `g` (`body.x`, or `body.vx` for its velocity).
    fn coord_name(&self, g: usize, velocity: bool) -> String {
        coord_text(&self.a.bodies[g / 6], g % 6, velocity)
    }

    /// Step 1: pinned coordinates (replayed from the plan, or found), and the matrices on the
    /// active coordinates.
    fn pin_coordinates(&mut self) -> Selection<S> {
        let a = self.a;
        let d = a.dim();
        let (active, j_keep) = match self.plan {
            Some(p) => (p.active.clone(), p.j_rows.clone()),
            None => find_pins(a),
        };
        let mut is_active = vec![false; d];
        for &g in &active {
            is_active[g] = true;
        }
        self.report.pinned = (0..d)
            .filter(|&g| !is_active[g])
            .map(|g| self.coord_name(g, false))
            .collect();
        let msel = |m: &SparseMatrix<S>| m.select(&active, &active);
        Selection {
            jm: a.holonomic.select(&j_keep, &active),
            nm: a.nonholonomic.columns_of(&active),
            mass: msel(&a.mass),
            stiff: msel(&a.stiffness),
            damp: msel(&a.damping),
            vel: msel(&a.velocity),
            f_u: a.input_force.select_rows(&active),
            g_u: a.input_rate_force.select_rows(&active),
            c_s: a.sensor_rows.columns_of(&active),
            lag_p: a.lags.position.columns_of(&active),
            lag_w: a.lags.velocity.columns_of(&active),
            lag_f: a.lags.force.select_rows(&active),
            active,
            j_keep,
        }
    }

    /// Step 2: Gauss–Jordan on the kept `J`; the dependent coordinates in terms of the
    /// independent ones, `p = R_p x_p`.
    fn eliminate_positions(&mut self, sel: &Selection<S>) -> Result<Positions<S>, ModelError> {
        let (a, n) = (self.a, sel.active.len());
        let jlabel = |r: usize| a.holonomic_rows[sel.j_keep[r]].clone();
        // The rotations of point masses kept: a pinned point mass's angle is the coordinate
        // users expect (a pendulum bob's, not its sideways position), and a rotation without
        // inertia of its own costs the reduced mass matrix nothing (the inertia tie-break
        // would eliminate it first).
        let inertia = sel.inertia();
        let keep: Vec<bool> = (sel.active.iter().zip(&inertia))
            .map(|(&g, &i)| g % 6 >= 3 && i == 0.0)
            .collect();
        let rj = rref_keeping(
            to_rows(&sel.jm),
            n,
            &[],
            self.plan.map(|p| &p.position),
            &inertia,
            &keep,
        )?;
        let mut checks = Vec::new();
        record_checks(
            &rj,
            &|r, c| CheckLabel::PositionPivot {
                coord: self.coord(sel.active[c], false),
                row: jlabel(r),
            },
            &|r| CheckLabel::PositionRank { row: jlabel(r) },
            &mut checks,
        );
        self.checks.append(&mut checks);
        for &r in &rj.plan.redundant {
            self.report.redundant.push(jlabel(r).to_string());
        }
        if !rj.plan.redundant.is_empty() {
            let rows: Vec<String> = rj
                .plan
                .redundant
                .iter()
                .map(|&r| jlabel(r).to_string())
                .collect();
            self.report.warnings.push(Warning::ReductionRedundant {
                rows,
                negligible: super::eliminate::NEGLIGIBLE,
            });
        }
        let (indep_p, indep_pos) = independent(&rj, n);
        let np = indep_p.len();
        let mut rp = Triplets::with_capacity(n, np, np + pivot_nnz(&rj));
        for (t, &k) in indep_p.iter().enumerate() {
            rp.push(k, t, S::one());
        }
        for &(r, c) in &rj.plan.pivots {
            for &(k, v) in rj.rows.row(r) {
                if k != c && k < n && indep_pos[k] != usize::MAX {
                    rp.push(c, indep_pos[k], -v);
                }
            }
        }
        Ok(Positions {
            rp: rp.build(),
            rj,
            indep_p,
        })
    }

    /// Step 3: `J w = J V p` and `N w = 0`, the position elimination replayed first, then
    /// the nonholonomic rows: `w = W_p x_p + R_w x_w`.
    fn eliminate_velocities(
        &mut self,
        sel: &Selection<S>,
        pos: &Positions<S>,
    ) -> Result<Velocities<S>, ModelError> {
        let n = sel.active.len();
        let np = pos.indep_p.len();
        let rhs = sel.jm.mul(&sel.vel)?.mul(&pos.rp)?;
        let nq = sel.jm.nrows();
        // [J  J V R_p; N  0] in one pass.
        let g = SparseMatrix::block(&[vec![Some(&sel.jm), Some(&rhs)], vec![Some(&sel.nm), None]])?;
        let a = self.a;
        let g_label = |r: usize| {
            if r < nq {
                a.holonomic_rows[sel.j_keep[r]].clone()
            } else {
                a.nonholonomic_rows[r - nq].clone()
            }
        };
        let mut rg = rref(
            to_rows(&g),
            n,
            &pos.rj.plan.pivots,
            self.plan.map(|p| &p.velocity),
            &sel.inertia(),
        )?;
        // The replayed position pivots are already checked; record the new ones.
        let all_records = std::mem::take(&mut rg.pivot_records);
        rg.pivot_records = all_records
            .into_iter()
            .skip(pos.rj.plan.pivots.len())
            .collect();
        let mut checks = Vec::new();
        record_checks(
            &rg,
            &|r, c| CheckLabel::VelocityPivot {
                coord: self.coord(sel.active[c], true),
                row: g_label(r),
            },
            &|r| CheckLabel::VelocityRank { row: g_label(r) },
            &mut checks,
        );
        for &r in &rg.plan.redundant {
            if r >= nq {
                self.report.redundant.push(g_label(r).to_string());
            }
            // A redundant velocity row must also be consistent (its right-hand side negligible).
            for &(k, v) in rg.rows.row(r) {
                if k >= n {
                    checks.push(ValidityCheck::Negligible {
                        what: CheckLabel::VelocityConsistency { row: g_label(r) },
                        value: v,
                        scale: g.row(r).iter().map(|e| e.1).collect(),
                    });
                }
            }
        }
        self.checks.append(&mut checks);
        let (indep_w, indep_wpos) = independent(&rg, n);
        let nw = indep_w.len();
        let rg_nnz = pivot_nnz(&rg);
        let mut rw = Triplets::with_capacity(n, nw, nw + rg_nnz);
        let mut wp = Triplets::with_capacity(n, np, rg_nnz);
        for (t, &k) in indep_w.iter().enumerate() {
            rw.push(k, t, S::one());
        }
        for &(r, c) in &rg.plan.pivots {
            for &(k, v) in rg.rows.row(r) {
                if k < n {
                    if k != c && indep_wpos[k] != usize::MAX {
                        rw.push(c, indep_wpos[k], -v);
                    }
                } else {
                    wp.push(c, k - n, v);
                }
            }
        }
        self.report.position_states = np;
        self.report.velocity_states = nw;
        self.report.lag_states = self.a.lags.len();
        Ok(Velocities {
            rg,
            indep_w,
            rw: rw.build(),
            wp: wp.build(),
        })
    }

    /// Step 4: the equations projected on the admissible velocities, the kinematics of the
    /// independent coordinates, and the reduced mass matrix eliminated.
    fn project_dynamics(
        &mut self,
        sel: &Selection<S>,
        pos: &Positions<S>,
        velo: &Velocities<S>,
    ) -> Result<Dynamics<S>, ModelError> {
        let (np, nw) = (pos.indep_p.len(), velo.indep_w.len());
        let na = self.a.lags.len();
        let nx = np + nw + na;
        let (rw, wp) = (&velo.rw, &velo.wp);
        let rwt = rw.transpose();
        let rwt_m = rwt.mul(&sel.mass)?;
        let m_r = rwt_m.mul(rw)?;
        let e21 = rwt_m.mul(wp)?;
        let wfull = hstack(wp, rw)?.widen(nx); // w = Wfull x
        let pfull = pos.rp.clone().widen(nx); // p = Pfull x = [R_p 0 0] x
        let kin = wfull.sub(&sel.vel.mul(&pfull)?)?; // ṗ = (W − V P) x
        let a1 = kin.select_rows(&pos.indep_p);
        let a2 = rwt
            .mul(&sel.stiff)?
            .mul(&pfull)?
            .add(&rwt.mul(&sel.damp)?.mul(&wfull)?)?
            .neg()
            .add(&lag_columns(&rwt.mul(&sel.lag_f)?, np + nw, nx))?;
        // ẋ_a = A_a x_a + P_a p + W_a w on the states.
        let lag = sel
            .lag_p
            .mul(&pfull)?
            .add(&sel.lag_w.mul(&wfull)?)?
            .add(&lag_columns(&self.a.lags.rate, np + nw, nx))?;
        let rhs_a = a2.sub(&e21.mul(&a1)?)?;
        let b2 = rwt.mul(&sel.f_u)?;
        let g2 = rwt.mul(&sel.g_u)?;
        let m_aug = SparseMatrix::hcat(&[&m_r, &rhs_a, &b2, &g2])?;
        let rm = rref(to_rows(&m_aug), nw, &[], self.plan.map(|p| &p.mass), &[])?;
        let vcoord = |t: usize| self.coord(sel.active[velo.indep_w[t]], true);
        let mut checks = Vec::new();
        record_checks(
            &rm,
            &|r, c| CheckLabel::MassPivot {
                state: vcoord(c),
                row: vcoord(r),
            },
            &|r| CheckLabel::MassRank { row: vcoord(r) },
            &mut checks,
        );
        self.checks.append(&mut checks);
        if !rm.plan.redundant.is_empty() {
            let names: Vec<String> = (rm.plan.redundant.iter())
                .map(|&r| self.coord_name(sel.active[velo.indep_w[r]], true))
                .collect();
            return Err(ModelError::MasslessMotion {
                coordinates: names.into(),
            });
        }
        let mi = nm_rows_to_matrix(&rm, nw, nx + b2.ncols() + g2.ncols());
        let m_in = sel.f_u.ncols();
        Ok(Dynamics {
            xa: mi.columns(nw..nw + nx),
            xb: mi.columns(nw + nx..nw + nx + m_in),
            xg: mi.columns(nw + nx + m_in..nw + nx + 2 * m_in),
            lag,
            rm,
            wfull,
            pfull,
            kin,
            a1,
            m_r,
            rhs_a,
        })
    }

    /// Without a plan (pivots chosen here): every recorded decision holds at the nominal
    /// point.
    fn check_nominal(&self) -> Result<(), ModelError> {
        if self.plan.is_none()
            && let Some(bad) = self.checks.iter().find(|c| !c.holds_nominal())
        {
            return Err(ModelError::NominalCheckFails { check: bad.what() });
        }
        Ok(())
    }

    /// The result: the state names, the map back to the physical coordinates, the dense
    /// matrices, and (choosing pivots) the check that every recorded decision holds at the
    /// nominal point.
    fn finish(
        self,
        sel: Selection<S>,
        pos: Positions<S>,
        velo: Velocities<S>,
        dyn_: Dynamics<S>,
        [a_ss, b_ss, c_out, d_out]: [SparseMatrix<S>; 4],
        gamma: &SparseMatrix<S>,
    ) -> Result<Reduction<S>, ModelError> {
        let a = self.a;
        let nx = pos.indep_p.len() + velo.indep_w.len() + a.lags.len();
        let mut phys = Triplets::with_capacity(a.dim(), nx, dyn_.pfull.nnz());
        for (i, j, v) in dyn_.pfull.iter() {
            phys.push(sel.active[i], j, v);
        }
        let phys = phys.build();
        let mut states: Vec<String> = (pos.indep_p.iter())
            .map(|&k| self.coord_name(sel.active[k], false))
            .collect();
        states.extend((velo.indep_w.iter()).map(|&k| self.coord_name(sel.active[k], true)));
        states.extend(a.lags.names.iter().cloned());
        // With rate inputs the states are x̃ = x − Γu: named for what they are.
        for (i, name) in states.iter_mut().enumerate() {
            name.push_str(&shifted_by(gamma.row(i), &a.inputs));
        }
        let names = SignalNames {
            states,
            inputs: a.inputs.iter().map(|x| x.0.clone()).collect(),
            input_units: a.inputs.iter().map(|x| x.1.clone()).collect(),
            outputs: a.outputs.iter().map(|x| x.0.clone()).collect(),
            output_units: a.outputs.iter().map(|x| x.1.clone()).collect(),
            bodies: a.bodies.clone(),
        };
        let ss = StateSpace {
            a: to_dense(&a_ss),
            b: to_dense(&b_ss),
            c: to_dense(&c_out),
            d: to_dense(&d_out),
            phys: to_dense(&phys),
            names,
        };
        self.check_nominal()?;
        let plan = ReductionPlan {
            active: sel.active,
            j_rows: sel.j_keep,
            position: pos.rj.plan,
            velocity: velo.rg.plan,
            mass: dyn_.rm.plan,
        };
        Ok(Reduction {
            state_space: ss,
            checks: self.checks,
            plan,
            report: self.report,
            descriptor: ReducedDescriptor {
                mass: dyn_.m_r,
                kinematics: dyn_.a1,
                dynamics: dyn_.rhs_a,
                lags: dyn_.lag,
            },
        })
    }
}

/// `m` (rows × k) placed at columns `at … at + k` of a matrix of `ncols` columns.
fn lag_columns<S: Scalar>(m: &SparseMatrix<S>, at: usize, ncols: usize) -> SparseMatrix<S> {
    let mut t = Triplets::with_capacity(m.nrows(), ncols, m.nnz());
    for (i, j, v) in m.iter() {
        t.push(i, at + j, v);
    }
    t.build()
}

/// ` − c₁·u₁ + c₂·u₂ …`: the shift `Γu` of a state `x̃ = x − Γu` (step 5), from its row of `Γ`
/// and the inputs' names; empty when the row is zero.
fn shifted_by<S: Scalar>(row: &[(usize, S)], inputs: &[(String, String)]) -> String {
    let mut t = String::new();
    for (j, c) in row.iter().filter(|e| !e.1.is_zero()) {
        let label = c.label();
        let (sign, coef) = match label.strip_prefix('-') {
            Some(rest) => ("+", rest.to_string()),
            None => ("−", label),
        };
        let coef = if coef == "1" {
            String::new()
        } else if coef.contains(['+', '-', '*', '/', ' ', '^']) {
            format!("({coef})·")
        } else {
            format!("{coef}·")
        };
        let input = inputs.get(*j).map_or("u", |x| x.0.as_str());
        t.push_str(&format!(" {sign} {coef}{input}"));
    }
    t
}

/// Step 1 without a plan: a holonomic row with a single entry pins its coordinate, kept
/// pinned only if `V p` cannot make its velocity nonzero. Returns the active coordinates and
/// the holonomic rows that do not pin.
fn find_pins<S: Scalar>(a: &Assembled<S>) -> (Vec<usize>, Vec<usize>) {
    let d = a.dim();
    let mut pin_row: Vec<Option<usize>> = vec![None; d];
    for i in 0..a.holonomic.nrows() {
        let row = a.holonomic.row(i);
        if row.len() == 1 && row[0].1.nominal() != 0.0 && pin_row[row[0].0].is_none() {
            pin_row[row[0].0] = Some(i);
        }
    }
    loop {
        let mut changed = false;
        for g in 0..d {
            if pin_row[g].is_some() && a.velocity.row(g).iter().any(|&(j, _)| pin_row[j].is_none())
            {
                pin_row[g] = None;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut pinning = vec![false; a.holonomic.nrows()];
    for &r in pin_row.iter().flatten() {
        pinning[r] = true;
    }
    let active: Vec<usize> = (0..d).filter(|&g| pin_row[g].is_none()).collect();
    let j_keep: Vec<usize> = (0..a.holonomic.nrows()).filter(|&r| !pinning[r]).collect();
    (active, j_keep)
}

/// The columns of an elimination over `n` unknowns that are not pivots, and the position of
/// each among them (`usize::MAX` for a pivot column).
fn independent<S: Scalar>(r: &Rref<S>, n: usize) -> (Vec<usize>, Vec<usize>) {
    let dep = r.is_pivot_col();
    let indep: Vec<usize> = (0..n).filter(|&c| !dep[c]).collect();
    let mut at = vec![usize::MAX; n];
    for (t, &k) in indep.iter().enumerate() {
        at[k] = t;
    }
    (indep, at)
}

/// Entries of the pivot rows of an elimination.
fn pivot_nnz<S: Scalar>(r: &Rref<S>) -> usize {
    r.plan
        .pivots
        .iter()
        .map(|&(p, _)| r.rows[p].len())
        .sum::<usize>()
}

/// Step 5: inputs with rates absorbed by the state change `x̃ = x − Γu`:
/// `A`, `B = B_raw + A Γ` and `Γ`.
fn absorb_input_rates<S: Scalar>(
    pos: &Positions<S>,
    dyn_: &Dynamics<S>,
) -> Result<[SparseMatrix<S>; 3], ModelError> {
    let np = pos.indep_p.len();
    let a_ss = vstack(&vstack(&dyn_.a1, &dyn_.xa)?, &dyn_.lag)?;
    // The lag states are not shifted by the inputs (Γ's and B's rows are zero there).
    let na = dyn_.lag.nrows();
    let below = |m: &SparseMatrix<S>| -> Result<SparseMatrix<S>, ModelError> {
        vstack(
            &m.clone().below_zero_rows(np),
            &SparseMatrix::zeros(na, m.ncols()),
        )
    };
    let gamma = below(&dyn_.xg)?;
    let b_raw = below(&dyn_.xb)?;
    let b_ss = b_raw.add(&a_ss.mul(&gamma)?)?;
    Ok([a_ss, b_ss, gamma])
}

/// Step 6: the output rows `C`, `D`: displacements and velocities directly, accelerations
/// through the reduced model.
fn outputs<S: Scalar>(
    a: &Assembled<S>,
    sel: &Selection<S>,
    dyn_: &Dynamics<S>,
    a_ss: &SparseMatrix<S>,
    b_ss: &SparseMatrix<S>,
    gamma: &SparseMatrix<S>,
) -> Result<(SparseMatrix<S>, SparseMatrix<S>), ModelError> {
    let nx = a_ss.ncols();
    let nout = sel.c_s.nrows();
    let mut c_out = Triplets::with_capacity(nout, nx, nout * nx);
    let mut d_out = Triplets::with_capacity(
        nout,
        a.feedthrough.ncols(),
        a.feedthrough.nnz() + nout * a.feedthrough.ncols(),
    );
    for (i, j, v) in a.feedthrough.iter() {
        d_out.push(i, j, v);
    }
    let (kin, wfull) = (&dyn_.kin, &dyn_.wfull);
    for (o, kind) in a.output_kinds.iter().enumerate() {
        let row = sel.c_s.select_rows(&[o]);
        let (c_row, d_row) = match (kind.order, kind.frame) {
            (OutputOrder::Displacement, _) => {
                let c = row.mul(&dyn_.pfull)?;
                let dr = c.mul(gamma)?;
                (c, dr)
            }
            (OutputOrder::Velocity, OutputFrame::Global) => {
                let c = row.mul(kin)?;
                let dr = c.mul(gamma)?;
                (c, dr)
            }
            (OutputOrder::Velocity, OutputFrame::Local) => {
                let c = row.mul(wfull)?;
                let dr = c.mul(gamma)?;
                (c, dr)
            }
            (OutputOrder::Acceleration, OutputFrame::Global) => {
                let cv = row.mul(kin)?;
                rate_check(&cv.mul(gamma)?, &a.outputs[o].0, &a.inputs)?;
                (cv.mul(a_ss)?, cv.mul(b_ss)?)
            }
            (OutputOrder::Acceleration, OutputFrame::Local) => {
                let cw = row.mul(wfull)?;
                rate_check(&cw.mul(gamma)?, &a.outputs[o].0, &a.inputs)?;
                let cvw = row.mul(&sel.vel)?.mul(wfull)?;
                let c = cw.mul(a_ss)?.sub(&cvw)?;
                let dr = cw.mul(b_ss)?.sub(&cvw.mul(gamma)?)?;
                (c, dr)
            }
        };
        for (_, j, v) in c_row.iter() {
            c_out.push(o, j, v);
        }
        for (_, j, v) in d_row.iter() {
            d_out.push(o, j, v);
        }
    }
    Ok((c_out.build(), d_out.build()))
}

fn to_dense<S: Scalar>(m: &SparseMatrix<S>) -> DMatrix<S> {
    let mut d = DMatrix::from_fn(m.nrows(), m.ncols(), |_, _| S::zero());
    for (i, j, v) in m.iter() {
        d[(i, j)] = v;
    }
    d
}

/// The reduced rows of a square elimination with its right-hand sides, pivot rows reordered
/// so that row `c` holds the solution for unknown `c`.
fn nm_rows_to_matrix<S: Scalar>(r: &Rref<S>, nunk: usize, nrhs: usize) -> SparseMatrix<S> {
    let nnz = r
        .plan
        .pivots
        .iter()
        .map(|&(row, _)| r.rows[row].len())
        .sum();
    let mut m = Triplets::with_capacity(nunk, nunk + nrhs, nnz);
    for &(row, c) in &r.plan.pivots {
        for &(k, v) in r.rows.row(row) {
            m.push(c, k, v);
        }
    }
    m.build()
}

fn rate_check<S: Scalar>(
    cg: &SparseMatrix<S>,
    output: &str,
    inputs: &[(String, String)],
) -> Result<(), ModelError> {
    if let Some((_, j, _)) = cg.iter().find(|(_, _, v)| v.nominal() != 0.0) {
        return Err(ModelError::InputRateInAcceleration {
            output: output.to_string(),
            input: inputs[j].0.clone(),
        });
    }
    Ok(())
}
