//! Columns of a symbolic state matrix that are the negatives (or copies) of each other, made so
//! structurally.
//!
//! Where the equations depend on two states only through their difference (the headings of two
//! bodies of a vehicle when only the steer angle matters), the elimination may build the two
//! columns of A from different expressions that are equal up to sign only mathematically.
//! Evaluated, they then differ in the last bits, and the exact zero eigenvalue of the pair (which
//! the numeric analysis deflates, see eom-num) is lost in rounding. Rewriting one column as the
//! negation of the other, after proving the identity entry by entry, makes the evaluated columns
//! exact negatives.

use eom_sym::Expr;
use eom_sym::zero::is_identically_zero;
use nalgebra::DMatrix;

/// Above this many states the pairwise search is skipped (its cost grows as n³).
const MAX_STATES: usize = 300;

/// Rewrites column `j` of `a` as `s·(column i)` (`s = ±1`) wherever that identity holds.
pub(crate) fn canonical_columns(a: &mut DMatrix<Expr>) {
    let n = a.ncols();
    if n > MAX_STATES || a.nrows() != n {
        return;
    }
    // The rows that count: those of states with a (structurally) zero column among the rest
    // are removed first, as the numeric deflation does.
    let removed = zero_column_states(a);
    let rows: Vec<usize> = (0..n).filter(|&r| !removed[r]).collect();
    let nominal = DMatrix::from_fn(n, n, |r, c| a[(r, c)].nominal());
    let mut done = vec![false; n];
    for i in (0..n).filter(|&i| !removed[i]) {
        if done[i] || rows.iter().all(|&r| a[(r, i)].is_zero()) {
            continue;
        }
        for j in (i + 1..n).filter(|&j| !removed[j]) {
            if done[j] {
                continue;
            }
            for s in [-1i64, 1] {
                if nominal_match(&nominal, &rows, i, j, s as f64) && proven(a, &rows, i, j, s) {
                    for &r in &rows {
                        a[(r, j)] = if s == 1 { a[(r, i)] } else { -a[(r, i)] };
                    }
                    done[j] = true;
                    break;
                }
            }
        }
    }
}

/// States whose column is structurally zero among the states not found so far (repeatedly).
fn zero_column_states(a: &DMatrix<Expr>) -> Vec<bool> {
    let n = a.ncols();
    let mut removed = vec![false; n];
    loop {
        let mut changed = false;
        for j in 0..n {
            if !removed[j] && (0..n).all(|r| removed[r] || a[(r, j)].is_zero()) {
                removed[j] = true;
                changed = true;
            }
        }
        if !changed {
            return removed;
        }
    }
}

/// Column j equals s·column i at the nominal point on `rows`, with the same structural zeros.
fn nominal_match(nom: &DMatrix<f64>, rows: &[usize], i: usize, j: usize, s: f64) -> bool {
    rows.iter().all(|&r| {
        let (x, y) = (nom[(r, i)], nom[(r, j)]);
        (x == 0.0) == (y == 0.0) && (y - s * x).abs() <= 1e-9 * (x.abs() + y.abs())
    })
}

/// Column j equals s·column i identically on `rows`.
fn proven(a: &DMatrix<Expr>, rows: &[usize], i: usize, j: usize, s: i64) -> bool {
    rows.iter().all(|&r| {
        let (x, y) = (a[(r, i)], a[(r, j)]);
        let d = y - x * s;
        d.is_zero() || is_identically_zero(d)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opposite_columns_become_exact_negatives() {
        let k = Expr::param("k", 2.0).expect("k");
        let m = Expr::param("m", 3.0).expect("m");
        // −k/m in one column, k/m written differently in the other.
        let x = -k / m;
        let y = k * (m + 1i64) / m - k;
        let z = Expr::zero();
        let mut a = DMatrix::from_row_slice(2, 2, &[x, y, z, z]);
        assert_ne!(a[(0, 1)], -a[(0, 0)]);
        canonical_columns(&mut a);
        assert_eq!(a[(0, 1)], -a[(0, 0)]);
    }
}
