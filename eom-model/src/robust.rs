//! The robust numeric path: orthonormal (SVD) complements of the constraints and an index-1
//! descriptor reduction, with scale-aware (equilibrated) rank decisions.
//!
//! 1. **Constrained descriptor** ([`constrained_descriptor`]): the first-order model in the
//!    full state `z = [p; w; s]` (`s` the input states), projected on the right complement
//!    `R` of the position and velocity constraints and the left complement `L`, as in the
//!    descriptor construction of the EoM software (Minaker et al.), but with the rank
//!    decisions taken on equilibrated matrices (scale-aware, not dependent on units) and the
//!    complements built per block: `P = null(J)` for the positions, `W = null([J; N])` for the
//!    velocities (each per group of coordinates that the constraint rows join,
//!    [`nullspace_structured`], so that coordinates no constraint couples are never mixed and
//!    an exact decoupling of the motion stays exact in the reduced model), `R = [P 0 0; G W 0; 0 0 I]` with `G` the least-norm velocity that the
//!    position constraint's rate `J w = J V p` requires, `L = diag(P, W, I)`. A single SVD
//!    complement of the whole constraint matrix would be as valid, but it mixes positions and
//!    velocities (of different units) in every state, so the state matrix could not be
//!    balanced and its eigenvalues' condition numbers, and the tolerances of every modal
//!    decision made on them, grew by orders of magnitude (a stiff chain's slightly damped mode
//!    was called marginal).
//! 2. **Output rows** on `z`: the displacement and velocity outputs directly, and the velocity
//!    outputs that the acceleration sensors differentiate afterwards.
//! 3. **Descriptor reduction** by eom-num's scale-aware index-1 reduction
//!    ([`descriptor_to_state_space`]).
//! 4. **Outputs**: accelerations derived from the reduced model (`C_acc = C_vel A`), so that
//!    they include every constraint reaction, and the feedthrough added.
//!
//! **Lag states** of the items (`Assembled::lags`, unsteady aerodynamics) are appended to `z`
//! as `z = [p; w; s; x_a]`, unconstrained: `R` and `L` get an identity block for them, `E` an
//! identity, and their equations and force enter `A`.
//!
//! It shares nothing with the elimination path except the assembly, which makes it an
//! independent check of the symbolic-numeric reduction.

use super::assemble::Assembled;
use super::assemble::{OutputFrame, OutputOrder};
use crate::error::ModelError;
use crate::warning::Warning;
use eom_num::descriptor::{DescriptorOptions, DescriptorReport, descriptor_to_state_space};
use eom_num::linalg::{Equilibrate, RankTolerance, nullspace_equilibrated, nullspace_structured};
use eom_num::{Descriptor, SignalNames, StateSpace};
use eom_sym::matrix::SparseMatrix;
use nalgebra::DMatrix;

/// What the robust reduction decided.
#[derive(Clone, Debug)]
pub struct RobustReport {
    /// Rank of the right constraint matrix `J_r` and the gap of that decision.
    pub constraint_rank: usize,
    /// `σ_r / σ_{r+1}` of the constraint rank decision (∞ when there was nothing to decide).
    pub constraint_gap: f64,
    /// The descriptor reduction's report.
    pub descriptor: DescriptorReport,
    /// Warnings.
    pub warnings: Vec<Warning>,
}

fn dense(m: &SparseMatrix<f64>) -> DMatrix<f64> {
    m.to_dense()
}

fn put(dst: &mut DMatrix<f64>, r0: usize, c0: usize, src: &DMatrix<f64>, sign: f64) {
    for i in 0..src.nrows() {
        for j in 0..src.ncols() {
            dst[(r0 + i, c0 + j)] += sign * src[(i, j)];
        }
    }
}

/// The constrained descriptor model on the orthonormal complements of the constraints: `E ẋ = A x + B u` with `x` the coordinates in `R = null(J_r)`, before any
/// output is attached. Returned with `R` (full state z = [p; w; s] as `R x`) and `L`.
pub struct ConstrainedDescriptor {
    /// `Lᵀ M R`.
    pub e: DMatrix<f64>,
    /// `−Lᵀ KC R`.
    pub a: DMatrix<f64>,
    /// `Lᵀ [0; 0; I]`.
    pub b: DMatrix<f64>,
    /// Right complement (columns span the admissible states).
    pub r: DMatrix<f64>,
    /// Rank of the constraint matrix.
    pub rank: usize,
    /// Gap of the constraint rank decision.
    pub gap: f64,
    /// Warnings.
    pub warnings: Vec<Warning>,
}

/// Build the [`ConstrainedDescriptor`] of a numeric assembled model.
pub fn constrained_descriptor(a: &Assembled<f64>) -> Result<ConstrainedDescriptor, ModelError> {
    let d = a.dim();
    let m = a.inputs.len();
    let na = a.lags.len();
    let nz = 2 * d + m + na;
    // Dense N × N matrices, N = 2·coordinates + inputs: the pencil (E, A) before and after
    // the projection, the complements R and L, the products' temporaries, and the
    // coordinate-sized mass, stiffness, damping and kinematic matrices: about nine at once.
    eom_num::budget::check(
        &format!(
            "the robust reduction's dense descriptor matrices ({nz} × {nz}: two per coordinate \
             of {} bodies, plus the inputs)",
            a.bodies.len()
        ),
        eom_num::budget::product(&[nz, nz, 9 * 8]),
    )?;
    let mass = dense(&a.mass);
    let k = dense(&a.stiffness);
    let c = dense(&a.damping);
    let v = dense(&a.velocity);
    let j = dense(&a.holonomic);
    let nmat = dense(&a.nonholonomic);
    let fu = dense(&a.input_force);
    let gu = dense(&a.input_rate_force);
    let q = j.nrows();
    let t = nmat.nrows();
    let id = DMatrix::<f64>::identity(d, d);

    let mut mz = DMatrix::<f64>::zeros(nz, nz);
    put(&mut mz, 0, 0, &id, 1.0);
    put(&mut mz, d, d, &mass, 1.0);
    put(&mut mz, d, 2 * d, &gu, -1.0);
    let mut kc = DMatrix::<f64>::zeros(nz, nz);
    put(&mut kc, 0, 0, &v, 1.0);
    put(&mut kc, 0, d, &id, -1.0);
    put(&mut kc, d, 0, &k, 1.0);
    put(&mut kc, d, d, &c, 1.0);
    put(&mut kc, d, 2 * d, &fu, -1.0);
    put(&mut kc, 2 * d, 2 * d, &DMatrix::identity(m, m), 1.0);
    // The lag states z_a (unconstrained): ż_a = A_a z_a + P_a p + W_a w, and their force
    // F_a z_a on the dynamic rows.
    let za = 2 * d + m;
    put(&mut mz, za, za, &DMatrix::identity(na, na), 1.0);
    put(&mut kc, za, za, &dense(&a.lags.rate), -1.0);
    put(&mut kc, za, 0, &dense(&a.lags.position), -1.0);
    put(&mut kc, za, d, &dense(&a.lags.velocity), -1.0);
    put(&mut kc, d, za, &dense(&a.lags.force), -1.0);
    let mut bz = DMatrix::<f64>::zeros(nz, m);
    put(&mut bz, 2 * d, 0, &DMatrix::identity(m, m), 1.0);

    let sc = 2 * q + t;
    let mut warnings = a.warnings.clone();
    let (r, lc, rank, gap) = if sc > 0 {
        let (r, l, rank, gap) = match complements(&j, &nmat, &v, m, &mut warnings)? {
            Some(c) => c,
            None => joint_complements(&j, &nmat, &v, m, &mut warnings)?,
        };
        (with_lags(&r, na), with_lags(&l, na), rank, gap)
    } else {
        (
            DMatrix::identity(nz, nz),
            DMatrix::identity(nz, nz),
            0,
            f64::INFINITY,
        )
    };
    Ok(ConstrainedDescriptor {
        e: lc.transpose() * &mz * &r,
        a: -(lc.transpose() * &kc * &r),
        b: lc.transpose() * &bz,
        r,
        rank,
        gap,
        warnings,
    })
}

/// `diag(c, I_na)`: a complement of the mechanical states extended by the (unconstrained) lag
/// states.
fn with_lags(c: &DMatrix<f64>, na: usize) -> DMatrix<f64> {
    if na == 0 {
        return c.clone();
    }
    let mut out = DMatrix::<f64>::zeros(c.nrows() + na, c.ncols() + na);
    put(&mut out, 0, 0, c, 1.0);
    put(
        &mut out,
        c.nrows(),
        c.ncols(),
        &DMatrix::identity(na, na),
        1.0,
    );
    out
}

/// How an output is read from the rows on `z` of the descriptor's outputs.
enum Post {
    /// Row `i` directly.
    Direct(usize),
    /// The derivative of velocity row `vel` through the reduced model, minus row `minus`
    /// (the `ω × v` part of a body-frame acceleration).
    Acc { vel: usize, minus: Option<usize> },
}

/// Reduce a numeric assembled model with orthonormal complements (see the module
/// documentation for the steps).
pub fn reduce_robust(a: &Assembled<f64>) -> Result<(StateSpace<f64>, RobustReport), ModelError> {
    let cd = constrained_descriptor(a)?;
    let (rows, post) = output_rows(a);
    let m = a.inputs.len();
    let phys = cd.r.rows(0, a.dim()).into_owned();
    let desc = Descriptor {
        e: cd.e,
        a: cd.a,
        b: cd.b,
        c: &rows * &cd.r,
        d: DMatrix::zeros(rows.nrows(), m),
    };
    let opts = DescriptorOptions {
        phys: Some(&phys),
        ..Default::default()
    };
    let (ss, rep) = descriptor_to_state_space(&desc, &opts)?;
    let mut warnings = cd.warnings;
    warnings.extend(rep.warnings.iter().cloned().map(Warning::Numeric));
    let (c_out, d_out) = outputs(a, &ss, &post)?;
    let n = ss.a.nrows();
    let names = SignalNames {
        states: (1..=n).map(|i| format!("x{i}")).collect(),
        inputs: a.inputs.iter().map(|x| x.0.clone()).collect(),
        input_units: a.inputs.iter().map(|x| x.1.clone()).collect(),
        outputs: a.outputs.iter().map(|x| x.0.clone()).collect(),
        output_units: a.outputs.iter().map(|x| x.1.clone()).collect(),
        bodies: a.bodies.clone(),
    };
    let out = StateSpace {
        a: ss.a,
        b: ss.b,
        c: c_out,
        d: d_out,
        phys: ss.phys,
        names,
    };
    Ok((
        out,
        RobustReport {
            constraint_rank: cd.rank,
            constraint_gap: cd.gap,
            descriptor: rep,
            warnings,
        },
    ))
}

/// The complements `R`, `L` per block (see the module documentation), the total rank of the
/// constraints and the smaller gap of the two rank decisions; `None` when some admissible
/// position admits no velocity on these blocks (then [`joint_complements`] decides).
fn complements(
    j: &DMatrix<f64>,
    nmat: &DMatrix<f64>,
    v: &DMatrix<f64>,
    m: usize,
    warnings: &mut Vec<Warning>,
) -> Result<Option<Complements>, ModelError> {
    let d = j.ncols();
    let (q, t) = (j.nrows(), nmat.nrows());
    let complement = |mat: &DMatrix<f64>| -> Result<(DMatrix<f64>, f64), ModelError> {
        if mat.nrows() == 0 {
            return Ok((DMatrix::identity(d, d), f64::INFINITY));
        }
        let ns = nullspace_structured(mat, RankTolerance::Default, Some(Equilibrate::Both))?;
        Ok((ns.basis, ns.gap))
    };
    let (p, gap_p) = complement(j)?;
    let mut jn = DMatrix::<f64>::zeros(q + t, d);
    put(&mut jn, 0, 0, j, 1.0);
    put(&mut jn, q, 0, nmat, 1.0);
    let (w, gap_w) = complement(&jn)?;
    let (np, nw) = (p.ncols(), w.ncols());
    // G: w = G x_p in the row space of [J; N] with [J; N] w = [J V P x_p; 0].
    let mut rhs = DMatrix::<f64>::zeros(q + t, np);
    put(&mut rhs, 0, 0, &(j * v * &p), 1.0);
    let g = if nw < d && np > 0 {
        let rows = if nw == 0 {
            DMatrix::identity(d, d)
        } else {
            nullspace_structured(&w.transpose(), RankTolerance::Default, None)?.basis
        };
        let jr = &jn * &rows;
        let y = jr
            .clone()
            .svd(true, true)
            .solve(&rhs, 0.0)
            .map_err(|why| ModelError::VelocityComplement { why })?;
        let resid = (&jr * &y - &rhs).amax();
        let scale = rhs.amax().max(jr.amax() * y.amax()) + f64::MIN_POSITIVE;
        if resid > 1e-8 * scale {
            // Not every admissible position admits a velocity on the block complements
            // (the rank decisions of the blocks and of the whole differ): the joint one.
            return Ok(None);
        }
        &rows * y
    } else {
        DMatrix::zeros(d, np)
    };
    let ncols = np + nw + m;
    let mut r = DMatrix::<f64>::zeros(2 * d + m, ncols);
    put(&mut r, 0, 0, &p, 1.0);
    put(&mut r, d, 0, &g, 1.0);
    put(&mut r, d, np, &w, 1.0);
    put(&mut r, 2 * d, np + nw, &DMatrix::identity(m, m), 1.0);
    let mut l = DMatrix::<f64>::zeros(2 * d + m, ncols);
    put(&mut l, 0, 0, &p, 1.0);
    put(&mut l, d, np, &w, 1.0);
    put(&mut l, 2 * d, np + nw, &DMatrix::identity(m, m), 1.0);
    let sc = 2 * q + t;
    let rank = 2 * d - np - nw;
    if rank < sc {
        warnings.push(Warning::RobustRedundant {
            redundant: sc - rank,
            rows: sc,
            gap: gap_p.min(gap_w),
        });
    }
    Ok(Some((r, l, rank, gap_p.min(gap_w))))
}

/// `R`, `L`, the rank of the constraints and the gap of its decision.
type Complements = (DMatrix<f64>, DMatrix<f64>, usize, f64);

/// The complements of the whole constraint matrices at once, `R = null(J_r)`, `L = null(J_l)`
/// (used when the block construction is inconsistent).
fn joint_complements(
    j: &DMatrix<f64>,
    nmat: &DMatrix<f64>,
    v: &DMatrix<f64>,
    m: usize,
    warnings: &mut Vec<Warning>,
) -> Result<Complements, ModelError> {
    let d = j.ncols();
    let (q, t) = (j.nrows(), nmat.nrows());
    let (sc, nz) = (2 * q + t, 2 * d + m);
    let mut jr = DMatrix::<f64>::zeros(sc, nz);
    put(&mut jr, 0, 0, j, 1.0);
    put(&mut jr, q, 0, &(j * v), -1.0);
    put(&mut jr, q, d, j, 1.0);
    put(&mut jr, 2 * q, d, nmat, 1.0);
    let mut jl = DMatrix::<f64>::zeros(sc, nz);
    put(&mut jl, 0, 0, j, 1.0);
    put(&mut jl, q, d, j, 1.0);
    put(&mut jl, 2 * q, d, nmat, 1.0);
    let nr = nullspace_equilibrated(&jr, RankTolerance::Default, Equilibrate::Both)?;
    let nl = nullspace_equilibrated(&jl, RankTolerance::Default, Equilibrate::Both)?;
    if nr.basis.ncols() != nl.basis.ncols() {
        return Err(ModelError::ConstraintRanksDiffer {
            position: sc - nr.basis.ncols(),
            velocity: sc - nl.basis.ncols(),
        });
    }
    if nr.rank < sc {
        warnings.push(Warning::RobustRedundant {
            redundant: sc - nr.rank,
            rows: sc,
            gap: nr.gap,
        });
    }
    Ok((nr.basis, nl.basis, nr.rank, nr.gap))
}

/// Step 2: the output rows on `z` and how each output is read from them.
fn output_rows(a: &Assembled<f64>) -> (DMatrix<f64>, Vec<Post>) {
    let d = a.dim();
    let nz = 2 * d + a.inputs.len() + a.lags.len();
    let v = dense(&a.velocity);
    let cs = dense(&a.sensor_rows);
    let mut rows: Vec<DMatrix<f64>> = Vec::new();
    let mut post = Vec::new();
    let push = |z: DMatrix<f64>, rows: &mut Vec<DMatrix<f64>>| {
        rows.push(z);
        rows.len() - 1
    };
    for (o, kind) in a.output_kinds.iter().enumerate() {
        let row = cs.rows(o, 1).into_owned();
        let mut z = DMatrix::<f64>::zeros(1, nz);
        match (kind.order, kind.frame) {
            (OutputOrder::Displacement, _) => {
                put(&mut z, 0, 0, &row, 1.0);
                post.push(Post::Direct(push(z, &mut rows)));
            }
            (OutputOrder::Velocity, OutputFrame::Local) => {
                put(&mut z, 0, d, &row, 1.0);
                post.push(Post::Direct(push(z, &mut rows)));
            }
            (OutputOrder::Velocity, OutputFrame::Global) => {
                put(&mut z, 0, 0, &(&row * &v), -1.0);
                put(&mut z, 0, d, &row, 1.0);
                post.push(Post::Direct(push(z, &mut rows)));
            }
            (OutputOrder::Acceleration, OutputFrame::Global) => {
                put(&mut z, 0, 0, &(&row * &v), -1.0);
                put(&mut z, 0, d, &row, 1.0);
                post.push(Post::Acc {
                    vel: push(z, &mut rows),
                    minus: None,
                });
            }
            (OutputOrder::Acceleration, OutputFrame::Local) => {
                put(&mut z, 0, d, &row, 1.0);
                let wv = push(z, &mut rows);
                let mut z2 = DMatrix::<f64>::zeros(1, nz);
                put(&mut z2, 0, d, &(&row * &v), 1.0);
                post.push(Post::Acc {
                    vel: wv,
                    minus: Some(push(z2, &mut rows)),
                });
            }
        }
    }
    let mut cz = DMatrix::<f64>::zeros(rows.len(), nz);
    for (i, row) in rows.iter().enumerate() {
        cz.set_row(i, &row.row(0));
    }
    (cz, post)
}

/// Step 4: `C` and `D` of the outputs from the reduced model's output rows.
fn outputs(
    a: &Assembled<f64>,
    ss: &StateSpace<f64>,
    post: &[Post],
) -> Result<(DMatrix<f64>, DMatrix<f64>), ModelError> {
    let m = a.inputs.len();
    let mut c_out = DMatrix::<f64>::zeros(post.len(), ss.a.nrows());
    let mut d_out = dense(&a.feedthrough);
    for (o, p) in post.iter().enumerate() {
        match *p {
            Post::Direct(i) => {
                c_out.set_row(o, &ss.c.row(i));
                let dd = ss.d.row(i).into_owned();
                for jj in 0..m {
                    d_out[(o, jj)] += dd[(0, jj)];
                }
            }
            Post::Acc { vel, minus } => {
                let cv = ss.c.rows(vel, 1).into_owned();
                let dv = ss.d.rows(vel, 1).into_owned();
                let scale = cv.abs().max() * ss.b.abs().max() + 1e-300;
                if let Some(jj) = (0..m).find(|&jj| dv[(0, jj)].abs() > 1e-12 * scale) {
                    return Err(ModelError::InputRateInAcceleration {
                        output: a.outputs[o].0.clone(),
                        input: a.inputs[jj].0.clone(),
                    });
                }
                let mut crow = &cv * &ss.a;
                let mut drow = &cv * &ss.b;
                if let Some(mi) = minus {
                    crow -= ss.c.rows(mi, 1);
                    drow -= ss.d.rows(mi, 1);
                }
                c_out.set_row(o, &crow.row(0));
                for jj in 0..m {
                    d_out[(o, jj)] += drow[(0, jj)];
                }
            }
        }
    }
    Ok((c_out, d_out))
}
