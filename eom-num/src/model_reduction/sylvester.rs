//! The Sylvester equation `A X − X B = C` with A and B upper quasi-triangular (real Schur
//! forms), by the Bartels–Stewart back substitution over their diagonal blocks (Bartels &
//! Stewart 1972, "Solution of the matrix equation AX + XB = C", Comm. ACM 15:820–826).

use nalgebra::DMatrix;

use super::small::sylvester_small;

/// Solves `A X − X B = C` for X (`m × n`), A (`m × m`) and B (`n × n`) quasi-triangular with
/// the diagonal blocks `a_blocks`, `b_blocks` (`(start, size)`, as [`super::schur::blocks`]
/// gives). Returns X and whether a small system was singular to working precision (an
/// eigenvalue of A equals one of B: X is then not accurate).
pub(crate) fn solve(
    a: &DMatrix<f64>,
    a_blocks: &[(usize, usize)],
    b: &DMatrix<f64>,
    b_blocks: &[(usize, usize)],
    c: &DMatrix<f64>,
) -> (DMatrix<f64>, bool) {
    let m = a.nrows();
    let mut x = c.clone();
    let mut singular = false;
    let (mut aa, mut bb, mut cc) = ([0.0; 4], [0.0; 4], [0.0; 4]);
    for &(j, q) in b_blocks {
        // Column block J: C_J + Σ_{L<J} X_L B_LJ.
        if j > 0 {
            let update = x.view((0, 0), (m, j)) * b.view((0, j), (j, q));
            let mut col = x.view_mut((0, j), (m, q));
            col += update;
        }
        for &(i, p) in a_blocks.iter().rev() {
            // Row block I: − Σ_{K>I} A_IK X_KJ.
            let below = i + p;
            if below < m {
                let update =
                    a.view((i, below), (p, m - below)) * x.view((below, j), (m - below, q));
                let mut blk = x.view_mut((i, j), (p, q));
                blk -= update;
            }
            for r in 0..p {
                for s in 0..p {
                    aa[s * p + r] = a[(i + r, i + s)];
                }
                for s in 0..q {
                    cc[s * p + r] = x[(i + r, j + s)];
                }
            }
            for r in 0..q {
                for s in 0..q {
                    bb[s * q + r] = b[(j + r, j + s)];
                }
            }
            singular |= sylvester_small(&aa, &bb, &mut cc, p, q);
            for r in 0..p {
                for s in 0..q {
                    x[(i + r, j + s)] = cc[s * p + r];
                }
            }
        }
    }
    (x, singular)
}

#[cfg(test)]
mod tests {
    use super::super::schur::{RealSchur, blocks};
    use super::*;

    #[test]
    fn residual_of_a_quasi_triangular_sylvester_equation() {
        let a0 = DMatrix::from_fn(5, 5, |i, j| {
            ((i * 5 + j) as f64 * 0.7).sin() + if i == j { 3.0 } else { 0.0 }
        });
        let b0 = DMatrix::from_fn(4, 4, |i, j| {
            ((i * 4 + j) as f64 * 1.3).cos() - if i == j { 3.0 } else { 0.0 }
        });
        let a = RealSchur::new(&a0).unwrap().t;
        let b = RealSchur::new(&b0).unwrap().t;
        let c = DMatrix::from_fn(5, 4, |i, j| (i + 2 * j) as f64 - 3.0);
        let (x, singular) = solve(&a, &blocks(&a), &b, &blocks(&b), &c);
        assert!(!singular);
        let r = &a * &x - &x * &b - &c;
        assert!(r.norm() < 1e-13 * c.norm(), "{}", r.norm());
    }
}
