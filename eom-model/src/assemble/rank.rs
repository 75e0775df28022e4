//! Scale-aware rank decisions of the statics, taken in `f64` on the nominal values of a
//! nondimensionalised matrix and then replayed with any scalar type.
//!
//! The equations of the statics mix forces (N) and moments (N m), and the multipliers mix
//! forces and moments too; a relative test per row (as a sparse elimination does) takes a
//! lever arm of 1e-12 m as seriously as one of 1 m. Here every moment equation is divided by
//! the model's length scale `L` (its largest lever arm), every column is then scaled to unit
//! largest entry, and the rank is the number of singular values above [`RANK_TOLERANCE`]
//! times the largest: a decision that does not depend on the units or on a negligible
//! geometric offset.

use super::context::ItemRow;
use crate::eliminate::EliminationPlan;
use crate::error::ModelError;
use eom_sym::scalar::Scalar;
use nalgebra::DMatrix;

/// Singular values at most this fraction of the largest count as zero (rank decisions on
/// the nondimensionalised matrix).
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The model's length scale: the largest lever arm (rotational entry) of a row that also
/// acts on translations, i.e. of a force-type row; 1 when there is none.
pub(crate) fn length_scale<'a, S: Scalar>(rows: impl Iterator<Item = &'a ItemRow<S>>) -> f64 {
    let mut l = 0.0f64;
    for r in rows {
        if r.iter().any(|e| e.0 % 6 < 3 && e.1.nominal() != 0.0) {
            for e in r.iter().filter(|e| e.0 % 6 >= 3) {
                l = l.max(e.1.nominal().abs());
            }
        }
    }
    // Below the normal range 1/L overflows: such lengths are left unscaled.
    if l.is_finite() && l >= f64::MIN_POSITIVE {
        l
    } else {
        1.0
    }
}

/// Weight of equation (coordinate) `i`: 1 for a force, `1/L` for a moment.
pub(crate) fn coordinate_weight(i: usize, length: f64) -> f64 {
    if i % 6 < 3 { 1.0 } else { 1.0 / length }
}

/// Scale every column of `a` to unit largest entry; the scale factors.
pub(crate) fn equilibrate_columns(a: &mut DMatrix<f64>) -> Vec<f64> {
    (0..a.ncols())
        .map(|j| {
            let m = a.column(j).amax();
            let s = if m > 0.0 && m.is_finite() {
                1.0 / m
            } else {
                1.0
            };
            a.column_mut(j).scale_mut(s);
            s
        })
        .collect()
}

/// The numerical rank of `a` and its singular values in decreasing order. (The SVD is
/// eom-num's, whose iteration is bounded: nalgebra's did not return on subnormal entries.)
pub(crate) fn rank(a: &DMatrix<f64>) -> Result<(usize, Vec<f64>), ModelError> {
    if a.nrows() == 0 || a.ncols() == 0 {
        return Ok((0, Vec::new()));
    }
    let s = eom_num::linalg::svd(a)?.singular_values;
    let top = s.first().copied().unwrap_or(0.0);
    let r = s.iter().filter(|&&x| x > RANK_TOLERANCE * top).count();
    Ok((r, s))
}

/// `r` pivots `(row, column)` of `a` by Gaussian elimination with complete pivoting (each
/// step takes the largest remaining entry, the first in row-major order on ties): with `r`
/// the numerical rank, the pivots pick `r` independent equations and unknowns.
pub(crate) fn complete_pivots(a: &DMatrix<f64>, r: usize) -> Vec<(usize, usize)> {
    let mut w = a.clone();
    let (m, n) = w.shape();
    let mut row_done = vec![false; m];
    let mut col_done = vec![false; n];
    let mut piv = Vec::with_capacity(r);
    for _ in 0..r {
        let mut best: Option<(usize, usize, f64)> = None;
        for i in (0..m).filter(|&i| !row_done[i]) {
            for j in (0..n).filter(|&j| !col_done[j]) {
                let v = w[(i, j)].abs();
                if best.is_none_or(|b| v > b.2) {
                    best = Some((i, j, v));
                }
            }
        }
        let Some((pi, pj, pv)) = best else { break };
        if pv == 0.0 || !pv.is_finite() {
            break;
        }
        row_done[pi] = true;
        col_done[pj] = true;
        piv.push((pi, pj));
        let p = w[(pi, pj)];
        for i in (0..m).filter(|&i| !row_done[i]) {
            let f = w[(i, pj)] / p;
            if f != 0.0 {
                for j in (0..n).filter(|&j| !col_done[j]) {
                    let v = w[(pi, j)];
                    w[(i, j)] -= f * v;
                }
            }
        }
    }
    piv
}

/// The inverse of the square matrix `s` (column-major, k × k) by Gauss–Jordan elimination
/// with partial pivoting; `None` when a pivot is exactly zero or an entry is not finite.
fn inverse(mut s: Vec<f64>, k: usize) -> Option<Vec<f64>> {
    let mut inv = vec![0.0; k * k];
    for i in 0..k {
        inv[i * k + i] = 1.0;
    }
    for c in 0..k {
        let p = (c..k).max_by(|&x, &y| s[c * k + x].abs().total_cmp(&s[c * k + y].abs()))?;
        let pv = s[c * k + p];
        if pv == 0.0 || !pv.is_finite() {
            return None;
        }
        if p != c {
            for j in 0..k {
                s.swap(j * k + p, j * k + c);
                inv.swap(j * k + p, j * k + c);
            }
        }
        let r = 1.0 / pv;
        for j in 0..k {
            s[j * k + c] *= r;
            inv[j * k + c] *= r;
        }
        for i in (0..k).filter(|&i| i != c) {
            let f = s[c * k + i];
            if f != 0.0 {
                for j in 0..k {
                    s[j * k + i] -= f * s[j * k + c];
                    inv[j * k + i] -= f * inv[j * k + c];
                }
            }
        }
    }
    inv.iter().all(|x| x.is_finite()).then_some(inv)
}

/// Safety factor of the certificates below over the rounding of their own arithmetic.
const CERTIFICATE_MARGIN: f64 = 4.0;

/// A certificate, without an SVD, that `a` (m × n, m ≥ n) has full column rank by the
/// decision of [`rank`] and that the square submatrix at `pivots` (n row–column pairs) is at
/// least `fraction` as well conditioned as any other square submatrix of n rows would be:
/// `σ_min(S) ≥ fraction · σ_n(a)`, which bounds the submatrix complete pivoting selects too.
///
/// The bounds: `σ_n(a) ≥ σ_min(S) ≥ 1/‖S⁻¹‖_F` (a submatrix's smallest singular value is at
/// most the whole one's), `σ_1(a) ≤ ‖a‖_F`, and `σ_n(a) ≤ ‖a x‖/‖x‖` for `x` the column of
/// `S⁻¹` of largest norm (the direction `S` stretches least). Each holds with a margin of
/// [`CERTIFICATE_MARGIN`]; when one does not, the caller decides by the SVD. The cost is one
/// inverse of an n × n matrix.
pub(crate) fn certify_full_column_rank(
    a: &DMatrix<f64>,
    pivots: &[(usize, usize)],
    fraction: f64,
) -> bool {
    let n = a.ncols();
    if pivots.len() != n || a.nrows() < n || n == 0 {
        return false;
    }
    let mut s = vec![0.0; n * n];
    for (i, &(r, _)) in pivots.iter().enumerate() {
        for (j, &(_, c)) in pivots.iter().enumerate() {
            s[j * n + i] = a[(r, c)];
        }
    }
    let Some(inv) = inverse(s, n) else {
        return false;
    };
    let inv_f = eom_num::linalg::frobenius_norm(&inv);
    let a_f = eom_num::linalg::frobenius_norm(a.as_slice());
    let lower = 1.0 / inv_f;
    // (NaN fails the comparison: no certificate.)
    let certified = lower > CERTIFICATE_MARGIN * RANK_TOLERANCE * a_f;
    if !certified {
        return false;
    }
    // The column of S⁻¹ of largest norm, as a vector over a's columns (S's columns are a's
    // columns in pivot order).
    let norms: Vec<f64> = inv
        .chunks_exact(n)
        .map(eom_num::linalg::frobenius_norm)
        .collect();
    let k = (0..n)
        .max_by(|&x, &y| norms[x].total_cmp(&norms[y]))
        .unwrap_or(0);
    let mut x = vec![0.0; n];
    for (i, &(_, c)) in pivots.iter().enumerate() {
        x[c] = inv[k * n + i];
    }
    let ax: Vec<f64> = (0..a.nrows())
        .map(|r| (0..n).map(|c| a[(r, c)] * x[c]).sum())
        .collect();
    let upper = eom_num::linalg::frobenius_norm(&ax) / eom_num::linalg::frobenius_norm(&x);
    lower >= CERTIFICATE_MARGIN * fraction * upper
}

/// An elimination plan for `nrows` rows from pivots: the rows without a pivot are redundant.
pub(crate) fn plan_of(pivots: Vec<(usize, usize)>, nrows: usize) -> EliminationPlan {
    let mut used = vec![false; nrows];
    for &(r, _) in &pivots {
        used[r] = true;
    }
    EliminationPlan {
        pivots,
        redundant: (0..nrows).filter(|&r| !used[r]).collect(),
    }
}

/// The redundant rows, the singular values of the decision and the rows' weights.
pub(crate) type Redundancy = (Vec<usize>, Vec<f64>, Vec<f64>);

/// The holonomic rows that are linear combinations of the others, by a rank decision on
/// the nondimensionalised `J` (rotational coordinates times `L`, rows scaled to unit
/// largest entry): the rows left without a pivot by complete pivoting, with the singular
/// values of the decision (decreasing).
pub(crate) fn redundant_rows<S: Scalar>(
    rows: &[ItemRow<S>],
    dim: usize,
    length: f64,
) -> Result<Redundancy, ModelError> {
    let q = rows.len();
    // Square at least, so that a full SVD of a wide Jᵀ is not needed for the null space.
    let mut j = DMatrix::<f64>::zeros(q, dim.max(q));
    for (r, row) in rows.iter().enumerate() {
        for &(c, v) in row.iter() {
            j[(r, c)] = v.nominal() * if c % 6 < 3 { 1.0 } else { 1.0 / length };
        }
    }
    let mut row_weight = vec![1.0; q];
    for (r, w) in row_weight.iter_mut().enumerate() {
        let m = j.row(r).amax();
        if m > 0.0 && m.is_finite() {
            *w = 1.0 / m;
            j.row_mut(r).scale_mut(*w);
        }
    }
    let (r, sv) = rank(&j)?;
    let mut used = vec![false; q];
    for (_, c) in complete_pivots(&j.transpose(), r) {
        used[c] = true;
    }
    Ok(((0..q).filter(|&c| !used[c]).collect(), sv, row_weight))
}

/// An orthonormal basis (columns) of the self-stress states of the nondimensionalised rows:
/// `μ` with `Ĵᵀ μ = 0`, `Ĵ` the rows scaled as in [`redundant_rows`] (`row_weight`).
pub(crate) fn self_stress_basis<S: Scalar>(
    rows: &[ItemRow<S>],
    dim: usize,
    length: f64,
    row_weight: &[f64],
    count: usize,
) -> Result<DMatrix<f64>, ModelError> {
    let q = rows.len();
    let mut j = DMatrix::<f64>::zeros(q, dim.max(q));
    for (r, row) in rows.iter().enumerate() {
        for &(c, v) in row.iter() {
            j[(r, c)] = v.nominal() * row_weight[r] * if c % 6 < 3 { 1.0 } else { 1.0 / length };
        }
    }
    // j is q × max(dim, q): its q singular values are non-increasing, so the self-stresses
    // are the last `count` left singular vectors.
    let u = eom_num::linalg::svd(&j)?.u;
    let mut n = DMatrix::<f64>::zeros(q, count);
    for k in 0..count.min(q) {
        n.set_column(k, &u.column(q - 1 - k));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complete_pivoting_skips_a_negligible_equation() {
        // Two tensions, the z force, the y moment, and an x moment of lever 1e-12.
        let a = DMatrix::from_row_slice(3, 2, &[1.0, 1.0, 1.0, -1.0, 0.0, 1e-12]);
        let (r, _) = rank(&a).unwrap();
        assert_eq!(r, 2);
        let p = complete_pivots(&a, r);
        assert!(p.iter().all(|&(i, _)| i != 2), "{p:?}");
    }

    #[test]
    fn certificate_of_full_rank_and_good_pivots() {
        // 3 × 2, well conditioned: rows 0 and 1 are good pivots.
        let a = DMatrix::from_row_slice(3, 2, &[1.0, 0.5, -0.5, 1.0, 0.2, 0.3]);
        assert!(certify_full_column_rank(&a, &[(0, 0), (1, 1)], 1e-2));
        // The same matrix with rank 1 to within 1e-12: no certificate (the SVD decides).
        let b = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 2.0, 4.0 + 1e-12, 0.5, 1.0]);
        assert!(!certify_full_column_rank(&b, &[(0, 0), (1, 1)], 1e-2));
        // Full rank, but the chosen rows are nearly dependent while another pair is not:
        // no certificate that they are within 1e-2 of the best.
        let c = DMatrix::from_row_slice(3, 2, &[1.0, 1.0, 1.0, 1.0 + 1e-6, 0.0, 1.0]);
        assert!(!certify_full_column_rank(&c, &[(0, 0), (1, 1)], 1e-2));
        assert!(certify_full_column_rank(&c, &[(0, 0), (2, 1)], 1e-2));
        // Wrong number of pivots.
        assert!(!certify_full_column_rank(&a, &[(0, 0)], 1e-2));
    }

    #[test]
    fn rank_of_dependent_rows() {
        let a = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 2.0, 4.0, 0.0, 1.0]);
        assert_eq!(rank(&a).unwrap().0, 2);
        let b = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0 + 1e-14]);
        assert_eq!(rank(&b).unwrap().0, 1);
    }
}
