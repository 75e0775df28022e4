//! The steps of the reduction (see the [module](super) documentation), sharing one
//! [`Reducer`]: pinned coordinates, positions, velocities, dynamics, input rates, outputs.

use super::checks::{CheckLabel, Coord, ValidityCheck, coord_text, rate_check, record_checks};
use super::matrices::{
    find_pins, hstack, independent, lag_columns, nm_rows_to_matrix, pivot_nnz, to_dense, to_rows,
    vstack,
};
use super::result::{ReducedDescriptor, Reduction, ReductionPlan, ReductionReport};
use crate::assemble::Assembled;
use crate::assemble::{OutputFrame, OutputOrder};
use crate::eliminate::{Rref, rref, rref_keeping};
use crate::error::ModelError;
use crate::geometry::Name;
use crate::warning::Warning;
use eom_num::{SignalNames, StateSpace};
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;

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
pub(super) struct Reducer<'a, S> {
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
pub(super) struct Selection<S> {
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
pub(super) struct Positions<S> {
    rj: Rref<S>,
    indep_p: Vec<usize>,
    rp: SparseMatrix<S>,
}

/// Step 3: the velocity elimination and `w = W_p x_p + R_w x_w`.
pub(super) struct Velocities<S> {
    rg: Rref<S>,
    indep_w: Vec<usize>,
    rw: SparseMatrix<S>,
    wp: SparseMatrix<S>,
}

/// Step 4: the reduced model's parts.
pub(super) struct Dynamics<S> {
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
                negligible: crate::eliminate::NEGLIGIBLE,
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

/// ` − c₁·u₁ + c₂·u₂ …`: the shift `Γu` of a state `x̃ = x − Γu` (step 5), from its row of `Γ`
/// and the inputs' names; empty when the row is zero.
pub(super) fn shifted_by<S: Scalar>(row: &[(usize, S)], inputs: &[(String, String)]) -> String {
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

/// Step 5: inputs with rates absorbed by the state change `x̃ = x − Γu`:
/// `A`, `B = B_raw + A Γ` and `Γ`.
pub(super) fn absorb_input_rates<S: Scalar>(
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
pub(super) fn outputs<S: Scalar>(
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
