//! The static preloads: the multipliers `λ_c` of the holonomic rows `J` and `λ_e` of the
//! elastic rows `H` that hold the applied loads `F` in equilibrium at the given geometry,
//! `Jᵀλ_c + Hᵀλ_e = −F`, with the springs' known preloads.
//!
//! 1. No loads and no known preloads: every preload is zero.
//! 2. **Redundant rigid rows**: a rank decision on the nondimensionalised `J` (see
//!    [`rank`](super::rank)) finds the rows that are combinations of the others (an
//!    over-constrained mechanism such as a planar loop of hinges built in 3-D). They are set
//!    aside; steps 3–5 solve the structure as if they had been removed by hand.
//! 3. **Force balance**: `[Jᵀ Hᵀ | −F]` and the known-preload rows, eliminated with the
//!    sparse elimination's own pivots when they pass a rank decision on the nondimensionalised
//!    matrix (moment equations divided by the model's length scale, columns scaled to unit
//!    size), else with pivots chosen there by complete pivoting and replayed in the scalar
//!    type. If it determines every multiplier, the structure is statically determinate.
//! 4. Otherwise **elastic compatibility**: the redundant multipliers follow from the
//!    deformation `x` of the structure, `[0 J; Jᵀ K_e] [μ; x] = [0; −F]` with the known
//!    preloads as extra unknowns (a singular system is an error naming the constraint rows);
//!    the elastic forces are `P H x` per item.
//! 5. **Minimum norm**: the multipliers of redundant rigid rows are not determined by
//!    anything (a self-stress of rigid parts); of all the solutions eom takes the one of least
//!    norm in the nondimensionalised multipliers, and warns that it is not unique (the
//!    symbolic path, whose results must hold at every parameter point, reports an error
//!    instead when the self-stress is not zero).
//! 6. **Equilibrium check**, scale-aware: the residual of each equation, moments divided by the
//!    length scale, relative to the largest such term of the same body. Up to
//!    [`EQUILIBRIUM_TOLERANCE`] it is rounding; up to [`NEAR_EQUILIBRIUM`] the geometry is
//!    taken as the equilibrium with a warning that names the residual (a negligible geometric
//!    offset, e.g. a coordinate written `0.5*sin(2π)`); beyond, it is an error.

use super::context::{BodyFrame, ItemRow, KnownPreload};
use super::rank::{
    RANK_TOLERANCE, certify_full_column_rank, complete_pivots, coordinate_weight,
    equilibrate_columns, length_scale, plan_of, rank, redundant_rows, self_stress_basis,
};
use super::{RowLabel, Statics};
use crate::eliminate::{Row, RowStore, Rref, rref};
use crate::error::ModelError;
use crate::warning::Warning;
use eom_sym::matrix::SparseMatrix;
use eom_sym::scalar::Scalar;
use nalgebra::{DMatrix, DVector};

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
    pub(crate) bodies: &'a [BodyFrame<'a, S>],
}

/// Relative residual (see the module documentation) below which an equation holds.
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-9;

/// Relative residual up to which the given geometry is accepted as the equilibrium, with a
/// warning (a geometric offset of about this fraction of the model's size).
pub const NEAR_EQUILIBRIUM: f64 = 1e-3;

/// The sparse elimination's own pivots are kept when the square matrix they select is at
/// least this fraction as well conditioned (smallest singular value, nondimensionalised) as
/// the one complete pivoting selects.
const OWN_PIVOTS: f64 = 1e-2;

/// The smallest singular value of the square submatrix of `a` at the pivots' rows and columns.
fn smallest_singular_value(a: &DMatrix<f64>, pivots: &[(usize, usize)]) -> Result<f64, ModelError> {
    let k = pivots.len();
    let sub = DMatrix::from_fn(k, k, |i, j| a[(pivots[i].0, pivots[j].1)]);
    Ok(rank(&sub)?.1.last().copied().unwrap_or(f64::INFINITY))
}

/// What the statics found.
pub(crate) struct StaticsResult<S> {
    /// The multipliers of the holonomic rows.
    pub(crate) lambda_c: Vec<S>,
    /// The multipliers of the elastic rows.
    pub(crate) lambda_e: Vec<S>,
    /// How they were found.
    pub(crate) kind: Statics,
    /// Per holonomic row: its multiplier is not determined by the statics (it takes part in a
    /// self-stress of redundant rigid rows; the minimum-norm value is used).
    pub(crate) not_unique: Vec<bool>,
    /// Warnings.
    pub(crate) warnings: Vec<Warning>,
}

/// Solve the static preloads (see the module documentation).
pub(crate) fn solve_statics<S: Scalar>(
    p: &StaticsProblem<'_, S>,
) -> Result<StaticsResult<S>, ModelError> {
    let q = p.j_rows.len();
    let s = p.h_rows.len();
    // 1. Unloaded.
    if p.applied.iter().all(Scalar::is_zero) && p.known.iter().all(|k| k.1.is_zero()) {
        return Ok(StaticsResult {
            lambda_c: vec![S::zero(); q],
            lambda_e: vec![S::zero(); s],
            kind: Statics::Unloaded,
            not_unique: vec![false; q],
            warnings: Vec::new(),
        });
    }
    let length = length_scale(p.j_rows.iter().chain(p.h_rows.iter()));
    // The common case, decided without an SVD.
    if let Some(red) = certified_determinate(p, length)? {
        let nu = q + s;
        let sol = solution(&red, nu);
        let (lc, le) = (sol[..q].to_vec(), sol[q..].to_vec());
        let mut warnings = Vec::new();
        check_equilibrium(p, &lc, &le, length, &mut warnings)?;
        return Ok(StaticsResult {
            lambda_c: lc,
            lambda_e: le,
            kind: Statics::Determinate,
            not_unique: vec![false; q],
            warnings,
        });
    }
    // 2. Redundant rigid rows, set aside.
    let (redundant, sv, row_weight) = redundant_rows(p.j_rows, p.dim, length)?;
    let keep: Vec<usize> = (0..q).filter(|i| !redundant.contains(i)).collect();
    let j_kept: Vec<ItemRow<S>> = keep.iter().map(|&i| p.j_rows[i]).collect();
    let labels_kept: Vec<RowLabel> = keep.iter().map(|&i| p.j_labels[i].clone()).collect();
    let sub = StaticsProblem {
        j_rows: &j_kept,
        j_labels: &labels_kept,
        ..*p
    };
    // 3.–4. The structure without them.
    let (lc_kept, le, mut kind) = determinate_or_compatible(&sub, length)?;
    let mut lc = vec![S::zero(); q];
    for (k, &i) in keep.iter().enumerate() {
        lc[i] = lc_kept[k];
    }
    let mut warnings = Vec::new();
    let mut not_unique = vec![false; q];
    // 5. Minimum norm over the self-stresses of the redundant rows.
    if !redundant.is_empty() {
        kind = Statics::Indeterminate;
        let (moved, n) = minimum_norm(p, &mut lc, &row_weight, redundant.len(), length)?;
        // The rows a self-stress moves (entries of the orthonormal basis above rounding).
        for (i, flag) in not_unique.iter_mut().enumerate() {
            *flag = n.row(i).amax() > RANK_TOLERANCE;
        }
        warnings.push(redundancy_warning(p, &redundant, &sv, moved));
    }
    // 6. Equilibrium.
    check_equilibrium(p, &lc, &le, length, &mut warnings)?;
    Ok(StaticsResult {
        lambda_c: lc,
        lambda_e: le,
        kind,
        not_unique,
        warnings,
    })
}

/// Steps 3–4 on a problem without redundant rigid rows.
fn determinate_or_compatible<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    length: f64,
) -> Result<(Vec<S>, Vec<S>, Statics), ModelError> {
    let q = p.j_rows.len();
    let nu = q + p.h_rows.len();
    let red = force_balance(p, length)?;
    let rank = red.plan.pivots.len();
    if rank == nu {
        let sol = solution(&red, nu);
        Ok((sol[..q].to_vec(), sol[q..].to_vec(), Statics::Determinate))
    } else {
        let (mu, le) = compatibility(p, rank)?;
        Ok((mu, le, Statics::Indeterminate))
    }
}

/// Step 5: move `λ_c` to the least-norm solution, `μ ← μ − N Nᵀ μ` in the nondimensionalised
/// multipliers `μ = λ / w` (`N`: orthonormal self-stresses); the largest change relative to
/// the largest multiplier, and `N`. The symbolic path cannot carry a choice made at one point.
fn minimum_norm<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    lc: &mut [S],
    row_weight: &[f64],
    count: usize,
    length: f64,
) -> Result<(f64, DMatrix<f64>), ModelError> {
    let n = self_stress_basis(p.j_rows, p.dim, length, row_weight, count)?;
    let mu = DVector::from_iterator(
        lc.len(),
        lc.iter().zip(row_weight).map(|(l, w)| l.nominal() / w),
    );
    let delta = -(&n * (n.transpose() * &mu));
    let top = mu.amax();
    let moved = if top > 0.0 { delta.amax() / top } else { 0.0 };
    if S::SYMBOLIC && moved > RANK_TOLERANCE {
        return Err(ModelError::NonUniquePreloads { moved });
    }
    if !S::SYMBOLIC {
        for (i, l) in lc.iter_mut().enumerate() {
            *l = *l + S::from_f64(delta[i] * row_weight[i]);
        }
    }
    Ok((moved, n))
}

/// The warning of step 5: which rows, why, and what was done.
fn redundancy_warning<S>(
    p: &StaticsProblem<'_, S>,
    redundant: &[usize],
    sv: &[f64],
    moved: f64,
) -> Warning {
    let rows: Vec<String> = redundant
        .iter()
        .map(|&i| p.j_labels[i].to_string())
        .collect();
    let top = sv.first().copied().unwrap_or(1.0);
    let rank = sv.len() - redundant.len().min(sv.len());
    let kept_small = sv.get(rank.saturating_sub(1)).map_or(0.0, |x| x / top);
    let dropped = sv.get(rank).map_or(0.0, |x| x / top);
    Warning::StaticsRedundant {
        rows,
        smallest_kept: kept_small,
        largest_dropped: dropped,
        threshold: RANK_TOLERANCE,
        self_stress: moved,
    }
}

/// The rows of `[Jᵀ Hᵀ | −F]` (one per coordinate) and of the known preloads
/// `[0 S | preload]`, and the same without the right-hand side in `f64`, nondimensionalised
/// (moment equations over the length scale, columns scaled to unit largest entry): the
/// matrix of the rank decisions.
fn balance_system<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    length: f64,
) -> (RowStore<S>, DMatrix<f64>) {
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
    let nrows = rows.nrows();
    let mut a = DMatrix::<f64>::zeros(nrows, nu);
    for i in 0..nrows {
        let w = if i < d {
            coordinate_weight(i, length)
        } else {
            1.0
        };
        for &(c, v) in rows.row(i).iter().filter(|e| e.0 < nu) {
            a[(i, c)] = v.nominal() * w;
        }
    }
    equilibrate_columns(&mut a);
    (rows, a)
}

/// The common case without an SVD: the sparse elimination's own pivots determine every
/// multiplier, and a certificate ([`certify_full_column_rank`]) shows that the rank
/// decisions by SVD would agree — the holonomic rows independent (none redundant), the
/// force balance of full rank, the own pivots as well conditioned as [`OWN_PIVOTS`] asks. The
/// reduced rows then, or `None` when the certificate does not hold.
fn certified_determinate<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    length: f64,
) -> Result<Option<Rref<S>>, ModelError> {
    let (rows, a) = balance_system(p, length);
    let nu = a.ncols();
    let own = rref(rows, nu, &[], None, &[])?;
    // `a`'s columns of the holonomic rows are those rows nondimensionalised exactly as
    // `redundant_rows` scales them (padded with zero rows): full column rank of `a` with a
    // margin makes the holonomic rows independent with the same margin.
    Ok(certify_full_column_rank(&a, &own.plan.pivots, OWN_PIVOTS).then_some(own))
}

/// Step 3: the reduced rows of `[Jᵀ Hᵀ | −F]` (one per coordinate) and of the known
/// preloads `[0 S | preload]`.
fn force_balance<S: Scalar>(p: &StaticsProblem<'_, S>, length: f64) -> Result<Rref<S>, ModelError> {
    let (rows, a) = balance_system(p, length);
    let nu = a.ncols();
    let nrows = rows.nrows();
    // The pivots: complete pivoting on the nondimensionalised matrix, to its numerical rank.
    let (r, _) = rank(&a)?;
    // The sparse elimination's own pivots (fewest fill-ins, so the smallest expressions) when
    // they are as many as the numerical rank and independent on the nondimensionalised
    // matrix; otherwise (e.g. a pivot on a moment of a negligible lever arm) complete pivoting.
    let own = rref(rows.clone(), nu, &[], None, &[])?;
    let complete = complete_pivots(&a, r);
    if own.plan.pivots.len() == r
        && smallest_singular_value(&a, &own.plan.pivots)?
            >= OWN_PIVOTS * smallest_singular_value(&a, &complete)?
    {
        return Ok(own);
    }
    rref(rows, nu, &[], Some(&plan_of(complete, nrows)), &[])
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
    let tr = rref(RowStore::from_rows(&rows, n + 1), n, &[], None, &[])?;
    if tr.plan.pivots.len() < n {
        return Err(ModelError::IndeterminatePreloads {
            rank,
            unknowns: q + p.h_rows.len(),
            joints: p.j_labels.iter().map(|l| l.to_string()).collect(),
        });
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

/// Step 6: the scale-aware equilibrium check.
fn check_equilibrium<S: Scalar>(
    p: &StaticsProblem<'_, S>,
    lc: &[S],
    le: &[S],
    length: f64,
    warnings: &mut Vec<Warning>,
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
    // Each body's scale: its largest force, or moment over the length scale.
    let w = |i: usize| coordinate_weight(i, length);
    let body_scale: Vec<f64> = mag
        .chunks(6)
        .enumerate()
        .map(|(b, m)| {
            (0..m.len())
                .map(|k| m[k] * w(6 * b + k))
                .fold(0.0, f64::max)
        })
        .collect();
    let mut worst: Option<(usize, f64)> = None;
    for (i, (&res, &mag)) in res.iter().zip(&mag).enumerate() {
        let ratio = (res.abs() * w(i)) / body_scale[i / 6];
        let ratio = if res.abs() <= 1e-300 { 0.0 } else { ratio };
        if res.is_nan() || ratio.is_nan() || ratio > NEAR_EQUILIBRIUM {
            return Err(ModelError::Equilibrium {
                equation: coordinate_label(p, i),
                residual: res,
                magnitude: mag,
                ratio,
                length,
            });
        }
        if ratio > EQUILIBRIUM_TOLERANCE && worst.is_none_or(|(_, r)| ratio > r) {
            worst = Some((i, ratio));
        }
    }
    if let Some((i, ratio)) = worst {
        warnings.push(Warning::NearEquilibrium {
            equation: coordinate_label(p, i),
            residual: res[i],
            ratio,
            length,
        });
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
