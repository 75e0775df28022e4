//! Determinants of matrices whose entries are linear in `s`, by expansion in minors memoised
//! on the columns used.

use crate::expr::Expr;
use hashbrown::HashMap;
use nalgebra::DMatrix;

/// An entry `c₀ + c₁·s`.
pub(crate) type Linear = (Expr, Expr);

/// `sE − F` (`E = I` when `e` is `None`).
pub(crate) fn pencil(e: Option<&DMatrix<Expr>>, f: &DMatrix<Expr>) -> Vec<Vec<Linear>> {
    let n = f.nrows();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let ds = match e {
                        Some(e) => e[(i, j)],
                        None if i == j => Expr::one(),
                        None => Expr::zero(),
                    };
                    (-f[(i, j)], ds)
                })
                .collect()
        })
        .collect()
}

/// A constant matrix as linear entries.
pub(crate) fn constant(m: &[Vec<Expr>]) -> Vec<Vec<Linear>> {
    m.iter()
        .map(|r| r.iter().map(|&x| (x, Expr::zero())).collect())
        .collect()
}

/// The coefficients of `det(m)` as a polynomial in `s` (ascending powers; at most 64
/// columns).
///
/// Row `k` is expanded over the columns not yet used by rows `0..k`; the minor of the remaining
/// rows depends only on that set of columns, so each set is computed once. Structural zeros
/// are skipped, so a sparse matrix costs far less than `n·2ⁿ`. The result is division-free in
/// the entries.
pub(crate) fn det_in_s(m: &[Vec<Linear>]) -> Vec<Expr> {
    let mut memo: HashMap<u64, Vec<Expr>> = HashMap::new();
    let p = minor(m, 0, &mut memo);
    let mut p = p;
    while p.len() > 1 && p.last().is_some_and(|c| c.is_zero()) {
        p.pop();
    }
    p
}

/// `det(m)` of a constant matrix.
pub(crate) fn det(m: &[Vec<Expr>]) -> Expr {
    det_in_s(&constant(m))[0]
}

fn minor(m: &[Vec<Linear>], used: u64, memo: &mut HashMap<u64, Vec<Expr>>) -> Vec<Expr> {
    let n = m.len();
    let k = used.count_ones() as usize;
    if k == n {
        return vec![Expr::one()];
    }
    if let Some(d) = memo.get(&used) {
        return d.clone();
    }
    // terms[d]: the products that make the coefficient of sᵈ.
    let mut terms: Vec<Vec<Expr>> = vec![Vec::new(); n - k + 1];
    let mut position = 0usize;
    for j in 0..n {
        if used & (1 << j) != 0 {
            continue;
        }
        let (c0, c1) = m[k][j];
        if !(c0.is_zero() && c1.is_zero()) {
            let sub = minor(m, used | (1 << j), memo);
            let sign = if position.is_multiple_of(2) {
                1i64
            } else {
                -1i64
            };
            for (d, &x) in sub.iter().enumerate() {
                if x.is_zero() {
                    continue;
                }
                if !c0.is_zero() {
                    terms[d].push(c0 * x * sign);
                }
                if !c1.is_zero() {
                    terms[d + 1].push(c1 * x * sign);
                }
            }
        }
        position += 1;
    }
    let p: Vec<Expr> = terms.into_iter().map(Expr::sum).collect();
    memo.insert(used, p.clone());
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansion_agrees_with_the_rule_of_sarrus() {
        let p: Vec<Expr> = (0..9)
            .map(|i| Expr::param(&format!("a{i}"), 1.0 + i as f64 * 0.37).expect("param"))
            .collect();
        let m: Vec<Vec<Expr>> = (0..3).map(|i| p[3 * i..3 * i + 3].to_vec()).collect();
        let sarrus = p[0] * p[4] * p[8] + p[1] * p[5] * p[6] + p[2] * p[3] * p[7]
            - p[2] * p[4] * p[6]
            - p[1] * p[3] * p[8]
            - p[0] * p[5] * p[7];
        let d = det(&m);
        assert!(crate::zero::is_identically_zero(d - sarrus));
    }

    #[test]
    fn characteristic_polynomial_of_a_companion_matrix() {
        // A = [[0, 1], [−a0, −a1]]: det(sI − A) = s² + a1 s + a0.
        let a0 = Expr::param("a0", 2.0).expect("a0");
        let a1 = Expr::param("a1", 3.0).expect("a1");
        let a = DMatrix::from_row_slice(2, 2, &[Expr::zero(), Expr::one(), -a0, -a1]);
        assert_eq!(det_in_s(&pencil(None, &a)), vec![a0, a1, Expr::one()]);
    }
}
