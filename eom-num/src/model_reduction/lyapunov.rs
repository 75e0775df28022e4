//! Cholesky factors of the Gramians of a stable system in real Schur form, by Hammarling's
//! method (Hammarling 1982, "Numerical solution of the stable, non-negative definite Lyapunov
//! equation", IMA J. Numer. Anal. 2:303–323): the factor is computed directly, never the
//! Gramian, so that the small Hankel singular values keep their relative accuracy far below
//! `ε·σ₁` instead of the `√ε` a Gramian's eigenvalues would leave.
//!
//! For A upper quasi-triangular with its eigenvalues in the open left half-plane and any C,
//! [`observability_factor`] returns the upper triangular U with `AᵀX + XA + CᵀC = 0`,
//! `X = UᵀU`. Partitioned at the first diagonal block A₁₁ (size k = 1 or 2),
//! `U = [[U₁₁, U₁₂], [0, U₂₂]]`, and with C already triangular `R = [[R₁₁, R₁₂], [0, R₂₂]]`:
//!
//! * `A₁₁ᵀ U₁₁ᵀU₁₁ + U₁₁ᵀU₁₁ A₁₁ = −R₁₁ᵀR₁₁` (a scalar, or a 2 × 2 Lyapunov equation);
//! * with `M = U₁₁ A₁₁ U₁₁⁻¹` and `W = U₁₁⁻ᵀR₁₁ᵀ` (so that `M + Mᵀ = −WWᵀ`):
//!   `Mᵀ U₁₂ + U₁₂ A₂₂ = −(U₁₁A₁₂ + W R₁₂)`;
//! * the rest is the same problem for A₂₂ with `C' = [R₂₂; R₁₂ − WᵀU₁₂]` (re-triangularised
//!   by Givens rotations), since the terms of the (2,2) block add up to `(R₁₂ − WᵀU₁₂)ᵀ(…)`.
//!
//! For k = 1, `W = α = sign(r₁₁)·√(−2λ)` is known without dividing by u₁₁, so a nearly
//! unobservable mode costs no accuracy; where `R₁₁ = 0` exactly, `U₁₁ = U₁₂ = 0` and
//! `C' = [R₂₂; R₁₂]`.

use nalgebra::DMatrix;

use super::schur::blocks;
use super::small::solve_small;
use super::sylvester;
use crate::{NumError, OptionError, SingularError};

/// Adds the rows of `rows` (each of length n) to the upper triangular `r` (n × n, acting on the
/// columns from `from`) by Givens rotations: afterwards `rᵀr` has grown by `rowsᵀrows`.
fn add_rows(r: &mut DMatrix<f64>, from: usize, rows: &DMatrix<f64>) {
    let n = r.ncols();
    for k in 0..rows.nrows() {
        let mut y: Vec<f64> = (0..n).map(|j| rows[(k, j)]).collect();
        for i in from..n {
            if y[i] == 0.0 {
                continue;
            }
            let (a, b) = (r[(i, i)], y[i]);
            let h = a.hypot(b);
            let (c, s) = (a / h, b / h);
            for j in i..n {
                let (rv, yv) = (r[(i, j)], y[j]);
                r[(i, j)] = c * rv + s * yv;
                y[j] = -s * rv + c * yv;
            }
            y[i] = 0.0;
        }
    }
}

/// The 2 × 2 Lyapunov equation `AᵀX + XA = −Q` (Q symmetric), by its 3 × 3 linear system.
fn lyapunov_2x2(a: [[f64; 2]; 2], q: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let ([a11, a12], [a21, a22]) = (a[0], a[1]);
    let mut m = [
        2.0 * a11,
        2.0 * a21,
        0.0,
        a12,
        a11 + a22,
        a21,
        0.0,
        2.0 * a12,
        2.0 * a22,
    ];
    let mut rhs = [-q[0][0], -q[0][1], -q[1][1], 0.0];
    let scale = m.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    solve_small(&mut m, &mut rhs[..3], 3, f64::EPSILON * scale);
    [[rhs[0], rhs[1]], [rhs[1], rhs[2]]]
}

/// The upper triangular factor U of the observability Gramian: `AᵀX + XA + CᵀC = 0`,
/// `X = UᵀU`, for A upper quasi-triangular (n × n, a real Schur form) with every eigenvalue
/// in the open left half-plane, and C (p × n).
///
/// Errors: [`NumError::InvalidOption`] when a diagonal block of A is not stable (the caller
/// splits off the unstable and marginal part first).
pub(crate) fn observability_factor(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
) -> Result<DMatrix<f64>, NumError> {
    let n = a.nrows();
    let mut r = DMatrix::zeros(n, n);
    add_rows(&mut r, 0, c);
    let mut u = DMatrix::zeros(n, n);
    for (i, k) in blocks(a) {
        let rest = n - i - k;
        let a11 = a.view((i, i), (k, k)).clone_owned();
        let r11 = r.view((i, i), (k, k)).clone_owned();
        let r12 = r.view((i, i + k), (k, rest)).clone_owned();
        let lam_re = if k == 1 {
            a11[(0, 0)]
        } else {
            0.5 * (a11[(0, 0)] + a11[(1, 1)])
        };
        if lam_re.is_nan() || lam_re >= 0.0 {
            return Err(NumError::InvalidOption(
                OptionError::UnstableLyapunovBlock {
                    block: i,
                    real_part: lam_re,
                },
            ));
        }
        if r11.iter().all(|v| *v == 0.0) {
            // Nothing of this block is seen yet: U₁₁ = U₁₂ = 0, C' = [R₂₂; R₁₂].
            add_rows(&mut r, i + k, &widen(&r12, n, i + k));
            continue;
        }
        // U₁₁, W = U₁₁⁻ᵀR₁₁ᵀ and M = U₁₁A₁₁U₁₁⁻¹.
        let (u11, w, m) = if k == 1 {
            let lam = a11[(0, 0)];
            let r0 = r11[(0, 0)];
            let root = (-2.0 * lam).sqrt();
            let u0 = r0.abs() / root;
            let alpha = if r0 < 0.0 { -root } else { root };
            (
                DMatrix::from_element(1, 1, u0),
                DMatrix::from_element(1, 1, alpha),
                DMatrix::from_element(1, 1, lam),
            )
        } else {
            let q = r11.transpose() * &r11;
            let x = lyapunov_2x2(
                [[a11[(0, 0)], a11[(0, 1)]], [a11[(1, 0)], a11[(1, 1)]]],
                [[q[(0, 0)], q[(0, 1)]], [q[(1, 0)], q[(1, 1)]]],
            );
            let u00 = x[0][0].max(0.0).sqrt();
            let u01 = if u00 > 0.0 { x[0][1] / u00 } else { 0.0 };
            let u11v = (x[1][1] - u01 * u01).max(0.0).sqrt();
            let u11 = DMatrix::from_row_slice(2, 2, &[u00, u01, 0.0, u11v]);
            let Some(inv) = u11.clone().try_inverse() else {
                return Err(NumError::Singular(SingularError::GramianBlock { block: i }));
            };
            let w = inv.transpose() * r11.transpose();
            let m = &u11 * &a11 * &inv;
            (u11, w, m)
        };
        u.view_mut((i, i), (k, k)).copy_from(&u11);
        if rest == 0 {
            continue;
        }
        // Mᵀ S + S A₂₂ = −(U₁₁A₁₂ + W R₁₂), i.e. Mᵀ S − S (−A₂₂) = F.
        let a12 = a.view((i, i + k), (k, rest));
        let f = -(&u11 * a12 + &w * &r12);
        let a22 = a.view((i + k, i + k), (rest, rest)).clone_owned();
        let neg = -&a22;
        let nb = blocks(&a22);
        let (s, _) = sylvester::solve(&m.transpose(), &[(0, k)], &neg, &nb, &f);
        u.view_mut((i, i + k), (k, rest)).copy_from(&s);
        let y = &r12 - w.transpose() * &s;
        add_rows(&mut r, i + k, &widen(&y, n, i + k));
    }
    Ok(u)
}

/// `y` (rows of the trailing columns from `from`) as rows of length n.
fn widen(y: &DMatrix<f64>, n: usize, from: usize) -> DMatrix<f64> {
    let mut w = DMatrix::zeros(y.nrows(), n);
    w.view_mut((0, from), (y.nrows(), y.ncols())).copy_from(y);
    w
}

/// The factor L of the controllability Gramian, `AP + PAᵀ + BBᵀ = 0`, `P = LLᵀ` (L lower
/// triangular), for A as in [`observability_factor`]: the same computation on the reversed
/// transpose `J Aᵀ J` (upper quasi-triangular again), `J` the reversal permutation.
pub(crate) fn controllability_factor(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
) -> Result<DMatrix<f64>, NumError> {
    let n = a.nrows();
    let ar = DMatrix::from_fn(n, n, |i, j| a[(n - 1 - j, n - 1 - i)]);
    let cr = DMatrix::from_fn(b.ncols(), n, |i, j| b[(n - 1 - j, i)]);
    let u = observability_factor(&ar, &cr)?;
    // P = J X̂ J = (Û J)ᵀ(Û J): L = J Ûᵀ.
    Ok(DMatrix::from_fn(n, n, |i, j| u[(j, n - 1 - i)]))
}

#[cfg(test)]
mod tests {
    use super::super::schur::RealSchur;
    use super::*;

    #[test]
    fn factors_solve_their_lyapunov_equations() {
        // A stable matrix with real and complex eigenvalues, in Schur form.
        let a0 = DMatrix::from_fn(6, 6, |i, j| {
            ((i * 6 + j) as f64 * 0.9).sin() - if i == j { 2.5 } else { 0.0 }
        });
        let s = RealSchur::new(&a0).unwrap();
        let a = s.t;
        let b = DMatrix::from_fn(6, 2, |i, j| (i as f64 - 2.0 * j as f64).cos());
        let c = DMatrix::from_fn(1, 6, |_, j| j as f64 - 2.5);
        let u = observability_factor(&a, &c).unwrap();
        let x = u.transpose() * &u;
        let r = a.transpose() * &x + &x * &a + c.transpose() * &c;
        assert!(
            r.norm() < 1e-13 * x.norm().max(1.0),
            "observability residual {}",
            r.norm()
        );
        let l = controllability_factor(&a, &b).unwrap();
        let p = &l * l.transpose();
        let r = &a * &p + &p * a.transpose() + &b * b.transpose();
        assert!(
            r.norm() < 1e-13 * p.norm().max(1.0),
            "controllability residual {}",
            r.norm()
        );
    }
}
