//! Matrix plumbing of the steps: stacking, row stores, pinned coordinates, the independent
//! columns of an elimination.

use crate::assemble::Assembled;
use crate::eliminate::{RowStore, Rref};
use crate::error::ModelError;
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;
use nalgebra::DMatrix;

pub(super) fn to_rows<S: Scalar>(m: &SparseMatrix<S>) -> RowStore<S> {
    RowStore::from_matrix(m)
}

pub(super) fn hstack<S: Scalar>(
    a: &SparseMatrix<S>,
    b: &SparseMatrix<S>,
) -> Result<SparseMatrix<S>, ModelError> {
    Ok(SparseMatrix::hcat(&[a, b])?)
}

pub(super) fn vstack<S: Scalar>(
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

/// `m` (rows × k) placed at columns `at … at + k` of a matrix of `ncols` columns.
pub(super) fn lag_columns<S: Scalar>(
    m: &SparseMatrix<S>,
    at: usize,
    ncols: usize,
) -> SparseMatrix<S> {
    let mut t = Triplets::with_capacity(m.nrows(), ncols, m.nnz());
    for (i, j, v) in m.iter() {
        t.push(i, at + j, v);
    }
    t.build()
}

/// Step 1 without a plan: a holonomic row with a single entry pins its coordinate, kept
/// pinned only if `V p` cannot make its velocity nonzero. Returns the active coordinates and
/// the holonomic rows that do not pin.
pub(super) fn find_pins<S: Scalar>(a: &Assembled<S>) -> (Vec<usize>, Vec<usize>) {
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
pub(super) fn independent<S: Scalar>(r: &Rref<S>, n: usize) -> (Vec<usize>, Vec<usize>) {
    let dep = r.is_pivot_col();
    let indep: Vec<usize> = (0..n).filter(|&c| !dep[c]).collect();
    let mut at = vec![usize::MAX; n];
    for (t, &k) in indep.iter().enumerate() {
        at[k] = t;
    }
    (indep, at)
}

/// Entries of the pivot rows of an elimination.
pub(super) fn pivot_nnz<S: Scalar>(r: &Rref<S>) -> usize {
    r.plan
        .pivots
        .iter()
        .map(|&(p, _)| r.rows[p].len())
        .sum::<usize>()
}

pub(super) fn to_dense<S: Scalar>(m: &SparseMatrix<S>) -> DMatrix<S> {
    let mut d = DMatrix::from_fn(m.nrows(), m.ncols(), |_, _| S::zero());
    for (i, j, v) in m.iter() {
        d[(i, j)] = v;
    }
    d
}

/// The reduced rows of a square elimination with its right-hand sides, pivot rows reordered
/// so that row `c` holds the solution for unknown `c`.
pub(super) fn nm_rows_to_matrix<S: Scalar>(
    r: &Rref<S>,
    nunk: usize,
    nrhs: usize,
) -> SparseMatrix<S> {
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
