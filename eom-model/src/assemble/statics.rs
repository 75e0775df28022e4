//! The static preloads: the multipliers `λ_c` of the holonomic rows `J` and `λ_e` of the
//! elastic rows `H` that hold the applied loads `F` in equilibrium at the given geometry,
//! `Jᵀλ_c + Hᵀλ_e = −F`, with the springs' known preloads.
//!
//! 1. No loads and no known preloads: every preload is zero.
//! 2. **Force balance**: a Gauss–Jordan elimination of `[Jᵀ Hᵀ | −F]` and the known-preload
//!    rows. If it determines every multiplier, the structure is statically determinate.
//! 3. Otherwise **elastic compatibility**: the redundant multipliers follow from the
//!    deformation `x` of the structure, `[0 J; Jᵀ K_e] [μ; x] = [0; −F]` with the known
//!    preloads as extra unknowns (a singular system is an error naming the constraint rows,
//!    never a minimum-norm guess); the elastic forces are `P H x` per item.
//! 4. **Equilibrium check**, relative per equation: `|F_i + Σ T_ij λ_j| ≤ 10⁻⁹ (|F_i| +
//!    Σ |T_ij λ_j|)`; the given geometry must be the loaded equilibrium.

use super::context::{ItemRow, KnownPreload};
use super::{RowLabel, Statics};
use crate::eliminate::{Row, RowStore, Rref, rref};
use crate::error::ModelError;
use crate::items::Body;
use eom_sym::matrix::SparseMatrix;
use eom_sym::scalar::Scalar;

/// What the statics needs of the assembly.
pub(crate) struct StaticsProblem<'a, S> {
    /// Number of coordinates.
    pub(crate) dim: usize,
    /// Holonomic rows `J`.
    pub(crate) j_rows: &'a [ItemRow<S>],
    /// Their labels (for the message of a singular compatibility system).
    pub(crate) j_labels: &'a [RowLabel],
    /// Elastic rows `H`.
    pub(crate) h_rows: &'a [ItemRow<S>],
    /// Applied generalized forces `F`.
    pub(crate) applied: &'a [S],
    /// Springs with a known preload.
    pub(crate) known: &'a [KnownPreload<S>],
    /// The stiffness block of each elastic item and its first row.
    pub(crate) stiffness_blocks: &'a [(usize, Vec<Vec<S>>)],
    /// The elastic stiffness `K_e`.
    pub(crate) k_el: &'a SparseMatrix<S>,
    /// The bodies (for messages).
    pub(crate) bodies: &'a [Body<S>],
}

/// `λ_c`, `λ_e` and how they were found.
pub(crate) type StaticsResult<S> = (Vec<S>, Vec<S>, Statics);

/// Solve the static preloads (see the module documentation).
pub(crate) fn solve_statics<S: Scalar>(
    p: &StaticsProblem<'_, S>,
) -> Result<StaticsResult<S>, ModelError> {
    let q = p.j_rows.len();
    let s = p.h_rows.len();
    // 1. Unloaded.
    if p.applied.iter().all(Scalar::is_zero) && p.known.iter().all(|k| k.1.is_zero()) {
        return Ok((vec![S::zero(); q], vec![S::zero(); s], Statics::Unloaded));
    }
    let nu = q + s;
    // 2. Force balance.
    let red = force_balance(p)?;
    let rank = red.plan.pivots.len();
    let (lc, le, kind) = if rank == nu {
        let sol = solution(&red, nu);
        (sol[..q].to_vec(), sol[q..].to_vec(), Statics::Determinate)
    } else {
        // 3. Elastic compatibility.
        let (mu, le) = compatibility(p, rank)?;
        (mu, le, Statics::Indeterminate)
    };
    // 4. Equilibrium.
    check_equilibrium(p, &lc, &le)?;
    Ok((lc, le, kind))
}

/// Step 2: the reduced rows of `[Jᵀ Hᵀ | −F]` (one per coordinate) and of the known
/// preloads `[0 S | preload]`.
fn force_balance<S: Scalar>(p: &StaticsProblem<'_, S>) -> Result<Rref<S>, ModelError> {
    let d = p.dim;
    let q = p.j_rows.len();
    let nu = q + p.h_rows.len();
    let mut len = vec![1usize; d];
    for &(i, _) in p.j_rows.iter().chain(p.h_rows.iter()).flatten() {
        len[i] += 1;
    }
    let mut rows = RowStore::with_lengths(&len, nu + 1);
    for (c, r) in p.j_rows.iter().chain(p.h_rows.iter()).enumerate() {
        for &(i, v) in r {
            rows.push(i, (c, v));
        }
    }
    for (i, &fi) in p.applied.iter().enumerate().take(d) {
        if !fi.is_zero() {
            rows.push(i, (nu, -fi));
        }
    }
    for &(spring, pre, _) in p.known {
        let one = (q + spring, S::one());
        if pre.is_zero() {
            rows.push_row(&[one]);
        } else {
            rows.push_row(&[one, (nu, pre)]);
        }
    }
    rref(rows, nu, &[], None)
}

/// The solution of a reduced system with `n` unknowns and every unknown a pivot: the
/// right-hand side (column `n`) of each pivot row.
fn solution<S: Scalar>(red: &Rref<S>, n: usize) -> Vec<S> {
    let mut sol = vec![S::zero(); n];
    for &(r, c) in &red.plan.pivots {
        sol[c] = red.rows[r]
            .iter()
            .find(|e| e.0 == n)
            .map_or(S::zero(), |e| e.1);
    }
    sol
}

/// Step 3: `λ_c` and `λ_e` of an indeterminate structure from the compatibility equations in
/// `z = [μ; x; δ₀]` (`δ₀`: the known-preload springs' free elongations).
fn compatibility<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    rank: usize,
) -> Result<(Vec<S>, Vec<S>), ModelError> {
    let q = p.j_rows.len();
    let d = p.dim;
    let n = q + d + p.known.len();
    let rows = compatibility_rows(p);
    let tr = rref(RowStore::from_rows(&rows, n + 1), n, &[], None)?;
    if tr.plan.pivots.len() < n {
        return Err(ModelError::Singular(format!(
            "the model is statically indeterminate (rank {rank} of {} unknown preloads) and its elastic compatibility equations are singular: the preloads of redundant rigid constraints cannot be determined (add compliance, or remove a redundant joint among: {})",
            q + p.h_rows.len(),
            p.j_labels
                .iter()
                .map(|l| l.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let z = solution(&tr, n);
    let mu = z[..q].to_vec();
    let le = elastic_forces(p, &z[q..q + d], &z[q + d..]);
    Ok((mu, le))
}

/// The rows of the compatibility system `[0 J 0; Jᵀ K_e Hᵀk; 0 kH k] z = [0; −F; preload]`,
/// sorted, duplicates summed.
fn compatibility_rows<S: Scalar>(p: &StaticsProblem<'_, S>) -> Vec<Row<S>> {
    let q = p.j_rows.len();
    let d = p.dim;
    let n = q + d + p.known.len();
    let mut rows: Vec<Row<S>> = vec![Vec::new(); n];
    for (i, r) in p.j_rows.iter().enumerate() {
        for &(c, v) in r {
            rows[i].push((q + c, v));
            rows[q + c].push((i, v));
        }
    }
    for (i, j, v) in p.k_el.iter() {
        rows[q + i].push((q + j, v));
    }
    for (kk, &(spring, pre, ks)) in p.known.iter().enumerate() {
        for &(c, v) in &p.h_rows[spring] {
            // Hᵀ Sᵀ k_s column and k_s S H row.
            rows[q + c].push((q + d + kk, ks * v));
            rows[q + d + kk].push((q + c, ks * v));
        }
        rows[q + d + kk].push((q + d + kk, ks));
        if !pre.is_zero() {
            rows[q + d + kk].push((n, pre));
        }
    }
    for i in 0..d {
        if !p.applied[i].is_zero() {
            rows[q + i].push((n, -p.applied[i]));
        }
    }
    rows.into_iter()
        .map(|mut r| {
            r.sort_by_key(|e| e.0);
            let mut m: Row<S> = Vec::with_capacity(r.len());
            for (c, v) in r {
                match m.last_mut() {
                    Some(l) if l.0 == c => l.1 = l.1 + v,
                    _ => m.push((c, v)),
                }
            }
            m.retain(|e| !e.1.is_zero());
            m
        })
        .collect()
}

/// The elastic forces `P H x` of each elastic item at deformation `x`, plus `k_s δ₀` for the
/// known-preload springs.
fn elastic_forces<S: Scalar>(p: &StaticsProblem<'_, S>, x: &[S], free: &[S]) -> Vec<S> {
    let mut le = vec![S::zero(); p.h_rows.len()];
    let hx: Vec<S> = p
        .h_rows
        .iter()
        .map(|r| S::sum(&r.iter().map(|&(c, v)| v * x[c]).collect::<Vec<_>>()))
        .collect();
    for (start, blk) in p.stiffness_blocks {
        for (a, row) in blk.iter().enumerate() {
            let terms: Vec<S> = row
                .iter()
                .enumerate()
                .filter(|(_, v)| !v.is_zero())
                .map(|(b, v)| *v * hx[start + b])
                .collect();
            le[start + a] = S::sum(&terms);
        }
    }
    for (kk, &(spring, _, ks)) in p.known.iter().enumerate() {
        le[spring] = le[spring] + ks * free[kk];
    }
    le
}

/// Step 4: the relative equilibrium check per equation.
fn check_equilibrium<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    lc: &[S],
    le: &[S],
) -> Result<(), ModelError> {
    let lam: Vec<S> = lc.iter().chain(le.iter()).copied().collect();
    // Accumulated from the item rows (the columns of Tᵀ) in the order of λ, so each equation
    // sums its terms in the same order as a walk along its row would.
    let mut res: Vec<f64> = p.applied.iter().map(|x| x.nominal()).collect();
    let mut mag: Vec<f64> = res.iter().map(|x| x.abs()).collect();
    for (c, r) in p.j_rows.iter().chain(p.h_rows.iter()).enumerate() {
        let l = lam[c].nominal();
        for &(i, v) in r {
            let t = v.nominal() * l;
            res[i] += t;
            mag[i] += t.abs();
        }
    }
    for (i, (&res, &mag)) in res.iter().zip(&mag).enumerate() {
        if res.is_nan() || res.abs() > 1e-9 * mag + 1e-300 {
            return Err(ModelError::Equilibrium(format!(
                "{}: residual {res:.6e} (of terms summing to {mag:.6e} in magnitude). The given geometry is not an equilibrium with these constraints (eom uses the given geometry as the loaded equilibrium: add a support, or give spring preloads that balance the loads)",
                coordinate_label(p, i)
            )));
        }
    }
    Ok(())
}

/// An equation of the force balance: a body's force or moment component, or a known
/// preload.
fn coordinate_label<S>(p: &StaticsProblem<'_, S>, i: usize) -> String {
    if i < p.dim {
        let comp = [
            "x force", "y force", "z force", "x moment", "y moment", "z moment",
        ][i % 6];
        format!("body `{}` {comp}", p.bodies[i / 6].name)
    } else {
        format!("known preload {}", i - p.dim + 1)
    }
}
