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
//! 5. **Inputs with rates** (`G_u u̇`) are absorbed by the state change `x̃ = x − Γu`.
//! 6. **Outputs.** Displacements and velocities directly; accelerations by differentiating the
//!    velocity output through the reduced model (`C_acc = C_vel A`, `D_acc = C_vel B`), which
//!    includes every constraint reaction — the fix of eom-method §13.8.
//!
//! Every pivot and rank decision is recorded ([`ReductionPlan`]) and can be replayed with any
//! scalar type; the pivots and the negligible entries of the rank decisions are returned as
//! [`ValidityCheck`]s, which define the region where a symbolic result is valid.

use super::assemble::{Assembled, RowLabel};
use super::eliminate::{EliminationPlan, PivotRecord, RankRecord, RowStore, Rref, rref};
use super::items::Name;
use super::items::{SensorFrame, SensorOrder};
use crate::error::ModelError;
use eom_num::{SignalNames, StateSpace};
use eom_sym::SymError;
use eom_sym::expr::Expr;
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;
use eom_sym::tape::Tape;
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
    /// Constraint rows found redundant at the nominal point.
    pub redundant: Vec<String>,
    /// Warnings.
    pub warnings: Vec<String>,
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
}

const COORD: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
const VELO: [&str; 6] = ["vx", "vy", "vz", "wx", "wy", "wz"];

fn select_rows<S: Scalar>(m: &SparseMatrix<S>, rows: &[usize]) -> SparseMatrix<S> {
    m.select_rows(rows)
}

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

/// Reduce an assembled model to state space. With `plan = None` the pivots are chosen at the
/// nominal point and recorded; with a plan they are replayed (the fast numeric path), and the
/// returned checks tell whether the plan is still valid at this point.
pub fn reduce<S: Scalar>(
    a: &Assembled<S>,
    plan: Option<&ReductionPlan>,
) -> Result<Reduction<S>, ModelError> {
    let d = a.dim();
    let mut report = ReductionReport {
        coordinates: d,
        ..Default::default()
    };
    report.warnings = a.warnings.clone();
    // Shared names for check labels, made only when a check needs one (a numeric reduction
    // without a plan records none).
    let body_names: std::cell::OnceCell<Vec<Name>> = std::cell::OnceCell::new();
    let coord = |g: usize, velocity: bool| Coord {
        body: body_names.get_or_init(|| a.bodies.iter().map(|b| Name::from(b.as_str())).collect())
            [g / 6]
            .clone(),
        dof: g % 6,
        velocity,
    };
    let coord_name = |g: usize| coord_text(&a.bodies[g / 6], g % 6, false);

    // ------------------------------------------------------------ 1. pinned coordinates
    let (active, j_keep) = match plan {
        Some(p) => (p.active.clone(), p.j_rows.clone()),
        None => {
            let mut pin_row: Vec<Option<usize>> = vec![None; d];
            for i in 0..a.holonomic.nrows() {
                let row = a.holonomic.row(i);
                if row.len() == 1 && row[0].1.nominal() != 0.0 && pin_row[row[0].0].is_none() {
                    pin_row[row[0].0] = Some(i);
                }
            }
            // Keep a pin only if (V p) cannot make its velocity nonzero.
            loop {
                let mut changed = false;
                for g in 0..d {
                    if pin_row[g].is_some()
                        && a.velocity.row(g).iter().any(|&(j, _)| pin_row[j].is_none())
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
    };
    let mut is_active = vec![false; d];
    for &g in &active {
        is_active[g] = true;
    }
    report.pinned = (0..d).filter(|&g| !is_active[g]).map(coord_name).collect();
    let n = active.len();
    let jm = a.holonomic.select(&j_keep, &active);
    let nm = a.nonholonomic.columns_of(&active);
    let all_active: Vec<usize> = active.clone();
    let msel = |m: &SparseMatrix<S>| m.select(&all_active, &all_active);
    let mass = msel(&a.mass);
    let stiff = msel(&a.stiffness);
    let damp = msel(&a.damping);
    let vel = msel(&a.velocity);
    let f_u = select_rows(&a.input_force, &active);
    let g_u = select_rows(&a.input_rate_force, &active);
    let c_s = a.sensor_rows.columns_of(&active);
    let jlabel = |r: usize| a.holonomic_rows[j_keep[r]].clone();
    let mut checks = Vec::new();

    // ------------------------------------------------------------ 2. positions
    let rj = rref(to_rows(&jm), n, &[], plan.map(|p| &p.position))?;
    record_checks(
        &rj,
        &|r, c| CheckLabel::PositionPivot {
            coord: coord(active[c], false),
            row: jlabel(r),
        },
        &|r| CheckLabel::PositionRank { row: jlabel(r) },
        &mut checks,
    );
    for &r in &rj.plan.redundant {
        report.redundant.push(jlabel(r).to_string());
    }
    let dep_p = rj.is_pivot_col();
    let indep_p: Vec<usize> = (0..n).filter(|&c| !dep_p[c]).collect();
    let np = indep_p.len();
    let mut indep_pos = vec![usize::MAX; n];
    for (t, &k) in indep_p.iter().enumerate() {
        indep_pos[k] = t;
    }
    let pivot_nnz = |r: &Rref<S>| {
        r.plan
            .pivots
            .iter()
            .map(|&(p, _)| r.rows[p].len())
            .sum::<usize>()
    };
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
    let rp = rp.build();

    // ------------------------------------------------------------ 3. velocities
    let rhs = jm.mul(&vel)?.mul(&rp)?;
    let nq = jm.nrows();
    // [J  J V R_p; N  0] in one pass.
    let g = SparseMatrix::block(&[vec![Some(&jm), Some(&rhs)], vec![Some(&nm), None]])?;
    let g_label = |r: usize| {
        if r < nq {
            jlabel(r)
        } else {
            a.nonholonomic_rows[r - nq].clone()
        }
    };
    let rg = rref(to_rows(&g), n, &rj.plan.pivots, plan.map(|p| &p.velocity))?;
    // The replayed position pivots are already checked; record the new ones.
    let mut rg = rg;
    let all_records = std::mem::take(&mut rg.pivot_records);
    rg.pivot_records = all_records.into_iter().skip(rj.plan.pivots.len()).collect();
    record_checks(
        &rg,
        &|r, c| CheckLabel::VelocityPivot {
            coord: coord(active[c], true),
            row: g_label(r),
        },
        &|r| CheckLabel::VelocityRank { row: g_label(r) },
        &mut checks,
    );
    for &r in &rg.plan.redundant {
        if r >= nq {
            report.redundant.push(g_label(r).to_string());
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
    let dep_w = rg.is_pivot_col();
    let indep_w: Vec<usize> = (0..n).filter(|&c| !dep_w[c]).collect();
    let nw = indep_w.len();
    let mut indep_wpos = vec![usize::MAX; n];
    for (t, &k) in indep_w.iter().enumerate() {
        indep_wpos[k] = t;
    }
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
    let (rw, wp) = (rw.build(), wp.build());
    report.position_states = np;
    report.velocity_states = nw;

    // ------------------------------------------------------------ 4. dynamics
    let nx = np + nw;
    let rwt = rw.transpose();
    let rwt_m = rwt.mul(&mass)?;
    let m_r = rwt_m.mul(&rw)?;
    let e21 = rwt_m.mul(&wp)?;
    let wfull = hstack(&wp, &rw)?; // w = Wfull x
    let pfull = rp.widen(np + nw); // p = Pfull x = [R_p 0] x
    let kin = wfull.sub(&vel.mul(&pfull)?)?; // ṗ = (W − V P) x
    let a1 = kin.select_rows(&indep_p);
    let a2 = rwt
        .mul(&stiff)?
        .mul(&pfull)?
        .add(&rwt.mul(&damp)?.mul(&wfull)?)?
        .neg();
    let rhs_a = a2.sub(&e21.mul(&a1)?)?;
    let b2 = rwt.mul(&f_u)?;
    let g2 = rwt.mul(&g_u)?;
    let m_aug = SparseMatrix::hcat(&[&m_r, &rhs_a, &b2, &g2])?;
    let rm = rref(to_rows(&m_aug), nw, &[], plan.map(|p| &p.mass))?;
    let vcoord = |t: usize| coord(active[indep_w[t]], true);
    let vname = |t: usize| {
        let g = active[indep_w[t]];
        coord_text(&a.bodies[g / 6], g % 6, true)
    };
    record_checks(
        &rm,
        &|r, c| CheckLabel::MassPivot {
            state: vcoord(c),
            row: vcoord(r),
        },
        &|r| CheckLabel::MassRank { row: vcoord(r) },
        &mut checks,
    );
    if !rm.plan.redundant.is_empty() {
        let names: Vec<String> = rm.plan.redundant.iter().map(|&r| vname(r)).collect();
        return Err(ModelError::Unsupported(format!(
            "the reduced mass matrix is singular at the nominal point (massless motion of {}): the symbolic-numeric path needs every independent velocity to carry inertia; use the robust numeric path, which reduces index-1 descriptor models",
            names.join(", ")
        )));
    }
    let mi = nm_rows_to_matrix(&rm, nw, nx + b2.ncols() + g2.ncols());
    let xa = mi.columns(nw..nw + nx);
    let m_in = f_u.ncols();
    let xb = mi.columns(nw + nx..nw + nx + m_in);
    let xg = mi.columns(nw + nx + m_in..nw + nx + 2 * m_in);
    let a_ss = vstack(&a1, &xa)?;
    let gamma = xg.below_zero_rows(np);
    let b_raw = xb.below_zero_rows(np);
    let b_ss = b_raw.add(&a_ss.mul(&gamma)?)?;

    // ------------------------------------------------------------ 5. outputs
    let nout = c_s.nrows();
    let mut c_out = Triplets::with_capacity(nout, nx, nout * nx);
    let mut d_out = Triplets::with_capacity(
        nout,
        a.feedthrough.ncols(),
        a.feedthrough.nnz() + nout * a.feedthrough.ncols(),
    );
    for (i, j, v) in a.feedthrough.iter() {
        d_out.push(i, j, v);
    }
    for (o, &(order, frame)) in a.sensor_kinds.iter().enumerate() {
        let row = c_s.select_rows(&[o]);
        let (c_row, d_row) = match (order, frame) {
            (SensorOrder::Displacement, _) => {
                let c = row.mul(&pfull)?;
                let dr = c.mul(&gamma)?;
                (c, dr)
            }
            (SensorOrder::Velocity, SensorFrame::Global) => {
                let c = row.mul(&kin)?;
                let dr = c.mul(&gamma)?;
                (c, dr)
            }
            (SensorOrder::Velocity, SensorFrame::Local) => {
                let c = row.mul(&wfull)?;
                let dr = c.mul(&gamma)?;
                (c, dr)
            }
            (SensorOrder::Acceleration, SensorFrame::Global) => {
                let cv = row.mul(&kin)?;
                rate_check(&cv.mul(&gamma)?, &a.outputs[o].0, &a.inputs)?;
                (cv.mul(&a_ss)?, cv.mul(&b_ss)?)
            }
            (SensorOrder::Acceleration, SensorFrame::Local) => {
                let cw = row.mul(&wfull)?;
                rate_check(&cw.mul(&gamma)?, &a.outputs[o].0, &a.inputs)?;
                let cvw = row.mul(&vel)?.mul(&wfull)?;
                let c = cw.mul(&a_ss)?.sub(&cvw)?;
                let dr = cw.mul(&b_ss)?.sub(&cvw.mul(&gamma)?)?;
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

    // ------------------------------------------------------------ 6. map back and names
    let mut phys = Triplets::with_capacity(d, nx, pfull.nnz());
    for (i, j, v) in pfull.iter() {
        phys.push(active[i], j, v);
    }
    let (phys, c_out, d_out) = (phys.build(), c_out.build(), d_out.build());
    let mut states: Vec<String> = indep_p.iter().map(|&k| coord_name(active[k])).collect();
    states.extend((0..nw).map(vname));
    let names = SignalNames {
        states,
        inputs: a.inputs.iter().map(|x| x.0.clone()).collect(),
        input_units: a.inputs.iter().map(|x| x.1.clone()).collect(),
        outputs: a.outputs.iter().map(|x| x.0.clone()).collect(),
        output_units: a.outputs.iter().map(|x| x.1.clone()).collect(),
        bodies: a.bodies.clone(),
    };
    let dense = |m: &SparseMatrix<S>| -> DMatrix<S> { to_dense(m) };
    let ss = StateSpace {
        a: dense(&a_ss),
        b: dense(&b_ss),
        c: dense(&c_out),
        d: dense(&d_out),
        phys: dense(&phys),
        names,
    };
    if plan.is_none()
        && let Some(bad) = checks.iter().find(|c| !c.holds_nominal())
    {
        return Err(ModelError::Singular(format!(
            "at the nominal point: {}",
            bad.what()
        )));
    }
    let plan = ReductionPlan {
        active,
        j_rows: j_keep,
        position: rj.plan,
        velocity: rg.plan,
        mass: rm.plan,
    };
    Ok(Reduction {
        state_space: ss,
        checks,
        plan,
        report,
    })
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
        return Err(ModelError::Unsupported(format!(
            "acceleration sensor `{output}` responds to the rate of input `{}` instantly (its velocity jumps with the input): its acceleration contains the input's second derivative, which a state-space model cannot represent; measure the velocity instead, or remove the rate gain",
            inputs[j].0
        )));
    }
    Ok(())
}

/// A symbolic state-space model with its validity region, compiled for evaluation.
#[derive(Clone, Debug)]
pub struct SymbolicStateSpace {
    /// The expressions.
    pub reduction: Reduction<Expr>,
    /// Parameters in the order values are given.
    pub params: Vec<Expr>,
    compiled: CompiledStateSpace,
    /// Keeps the expressions' pool alive as long as they are.
    pool: Option<eom_sym::ExprPool>,
}

/// Size of one symbolic matrix (see [`SymbolicStateSpace::sizes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MatrixSize {
    /// "A", "B", "C", "D" or "A..D".
    pub name: &'static str,
    /// Structural non-zeros.
    pub nonzeros: usize,
    /// Unique DAG nodes.
    pub nodes: usize,
    /// Operations of straight-line code evaluating every unique node once.
    pub operations: usize,
}

/// The numeric side of a [`SymbolicStateSpace`]: a compiled tape of every entry of A, B, C,
/// D and `phys` plus the validity checks. It holds no expressions, so it is `Send + Sync`
/// and can be shared by the threads of a parallel sweep.
#[derive(Clone, Debug)]
pub struct CompiledStateSpace {
    tape: Tape,
    shapes: [(usize, usize); 5],
    n_matrix: usize,
    check_layout: Vec<(usize, usize, bool)>,
    check_labels: Vec<CheckLabel>,
    names: SignalNames,
    param_names: Vec<String>,
}

/// Formerly the evaluations after which the tape was translated to machine code; the tape is
/// always interpreted now (the translation did not pay end to end). Unused; kept until its
/// re-export goes.
pub const NATIVE_AFTER: usize = usize::MAX;

impl SymbolicStateSpace {
    /// Compile a symbolic reduction for evaluation with parameter values in the order of
    /// `params`.
    pub fn new(reduction: Reduction<Expr>, params: &[Expr]) -> Result<Self, ModelError> {
        let ss = &reduction.state_space;
        let mut roots: Vec<Expr> = Vec::new();
        let mut shapes = [(0, 0); 5];
        for (k, m) in [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys]
            .into_iter()
            .enumerate()
        {
            shapes[k] = (m.nrows(), m.ncols());
            roots.extend(m.iter().copied());
        }
        let n_matrix = roots.len();
        let mut layout = Vec::new();
        for c in &reduction.checks {
            let start = roots.len();
            match c {
                ValidityCheck::Pivot { value, row, .. } => {
                    roots.push(*value);
                    roots.extend(row.iter().copied());
                    layout.push((start, 1 + row.len(), true));
                }
                ValidityCheck::Negligible { value, scale, .. } => {
                    roots.push(*value);
                    roots.extend(scale.iter().copied());
                    layout.push((start, 1 + scale.len(), false));
                }
            }
        }
        let tape = Tape::new(&roots, params)?;
        let compiled = CompiledStateSpace {
            tape,
            shapes,
            n_matrix,
            check_layout: layout,
            check_labels: reduction.checks.iter().map(|c| c.label().clone()).collect(),
            names: ss.names.clone(),
            param_names: params.iter().map(|p| p.to_string()).collect(),
        };
        let pool = roots
            .iter()
            .chain(params)
            // 0, 1 and −1 have the same id (0, 1, 2) in every pool and name none.
            .find(|e| e.id() > 2)
            .and_then(|e| eom_sym::ExprPool::find(e.pool_serial()));
        Ok(SymbolicStateSpace {
            reduction,
            params: params.to_vec(),
            compiled,
            pool,
        })
    }

    /// The pool of the expressions (`None` when every entry is a constant 0, 1 or −1).
    pub fn pool(&self) -> Option<&eom_sym::ExprPool> {
        self.pool.as_ref()
    }

    /// The expression state-space model.
    pub fn state_space(&self) -> &StateSpace<Expr> {
        &self.reduction.state_space
    }

    /// Size of the symbolic result per matrix: `(name, structural non-zeros, unique nodes,
    /// operations)` for A, B, C, D, and the totals with sharing across matrices (`"A..D"`).
    pub fn sizes(&self) -> Vec<MatrixSize> {
        let ss = &self.reduction.state_space;
        let mut out = Vec::new();
        let mut all = Vec::new();
        for (name, m) in [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d)] {
            let roots: Vec<Expr> = m.iter().copied().filter(|e| !e.is_zero()).collect();
            all.extend(roots.iter().copied());
            out.push(MatrixSize {
                name,
                nonzeros: roots.len(),
                nodes: Expr::dag_size(&roots),
                operations: Expr::op_count(&roots).total(),
            });
        }
        out.push(MatrixSize {
            name: "A..D",
            nonzeros: all.len(),
            nodes: Expr::dag_size(&all),
            operations: Expr::op_count(&all).total(),
        });
        out
    }

    /// The compiled numeric side (shareable across threads).
    pub fn compiled(&self) -> &CompiledStateSpace {
        &self.compiled
    }

    /// The compiled tape (matrix entries of A, B, C, D, phys column-major, then the checks).
    pub fn tape(&self) -> &Tape {
        &self.compiled.tape
    }

    /// Evaluate at parameter values (in the order of [`SymbolicStateSpace::params`]). Returns
    /// [`ModelError::PivotBreakdown`] naming the first check that fails instead of numbers when
    /// the point is outside the validity region.
    pub fn evaluate(&self, values: &[f64]) -> Result<StateSpace<f64>, ModelError> {
        self.compiled.evaluate(values)
    }
}

/// Reusable buffers for [`CompiledStateSpace::evaluate_with`].
#[derive(Clone, Debug, Default)]
pub struct EvalWorkspace {
    out: Vec<f64>,
    work: Vec<f64>,
}

impl CompiledStateSpace {
    /// Parameter names in the order values are given.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }

    /// Number of states.
    pub fn states(&self) -> usize {
        self.shapes[0].0
    }

    /// Evaluate at parameter values (see [`SymbolicStateSpace::evaluate`]).
    pub fn evaluate(&self, values: &[f64]) -> Result<StateSpace<f64>, ModelError> {
        self.evaluate_with(values, &mut EvalWorkspace::default())
    }

    /// [`CompiledStateSpace::evaluate`] reusing the buffers of `ws`.
    pub fn evaluate_with(
        &self,
        values: &[f64],
        ws: &mut EvalWorkspace,
    ) -> Result<StateSpace<f64>, ModelError> {
        ws.out.resize(self.tape.n_outputs(), 0.0);
        ws.work.resize(self.tape.work_len(), 0.0);
        self.tape.eval_into(values, &mut ws.out, &mut ws.work)?;
        let out = &ws.out;
        for ((start, len, pivot), label) in self.check_layout.iter().zip(&self.check_labels) {
            let v = out[*start];
            let others = &out[start + 1..start + len];
            if !ValidityCheck::<f64>::holds(v, others, *pivot) {
                return Err(ModelError::PivotBreakdown(format!(
                    "{label} (value {v:.3e}, largest entry of its row {:.3e})",
                    others.iter().fold(0.0f64, |a, b| a.max(b.abs()))
                )));
            }
        }
        if let Some(k) = out[..self.n_matrix].iter().position(|v| !v.is_finite()) {
            return Err(SymError::EvalNonFinite {
                what: format!("state-space entry {k}"),
                value: out[k],
            }
            .into());
        }
        let mut k = 0;
        let mut take = |(r, c): (usize, usize)| {
            let m = DMatrix::from_column_slice(r, c, &out[k..k + r * c]);
            k += r * c;
            m
        };
        let a = take(self.shapes[0]);
        let b = take(self.shapes[1]);
        let c = take(self.shapes[2]);
        let d = take(self.shapes[3]);
        let phys = take(self.shapes[4]);
        Ok(StateSpace {
            a,
            b,
            c,
            d,
            phys,
            names: self.names.clone(),
        })
    }

    /// Only the state matrix A at a point, with the validity checks (the inner loop of a sweep).
    pub fn evaluate_a(
        &self,
        values: &[f64],
        ws: &mut EvalWorkspace,
    ) -> Result<DMatrix<f64>, ModelError> {
        let ss = self.evaluate_with(values, ws)?;
        Ok(ss.a)
    }
}
