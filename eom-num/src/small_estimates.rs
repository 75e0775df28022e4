//! Error estimates of the eigenvalues of small matrices (n ≤ [`MAX_N`]) on the stack: what
//! [`crate::modes::eigenvalues_with_errors`] returns, without faer's full eigendecomposition.
//!
//! A sweep needs the estimates only at the few points where a verdict could depend on them,
//! but there faer's eigenvectors of a 3×3 matrix cost about forty times its eigenvalues
//! (workspace set-up for a general solver). Here the eigenvalues come from the stack kernel
//! of [`crate::small_eigen`], and each eigenvalue's right and left vectors from **inverse
//! iteration** on `Ã − λI` (Ã the balanced matrix; Wilkinson, *The Algebraic Eigenvalue
//! Problem*, §9.47; the start as LAPACK's `dlaein`): an LU factorization with partial
//! pivoting, pivots below `ε‖Ã‖_F` raised to it, then `U x = e` (the first step takes the
//! vector that the smallest pivot amplifies), accepted when its residual is of the order of
//! `n ε ‖Ã‖_F`, else up to three full steps `(Ã − λI) x' = x`. The left
//! vector is the right vector of `Ãᵀ` at the same λ (conjugated; `A` is real). Since λ is
//! an eigenvalue of a matrix within `ε‖Ã‖` of Ã, the vectors have residuals of that order:
//! each is an eigenvector of a matrix as close to Ã as faer's are.
//!
//! From them the two terms of [`crate::modes::error_estimate`], on the balanced matrix as
//! faer's path computes them: the condition number `κ = ‖x‖‖y‖/|yᴴx|` (capped at 1/ε) and
//! the componentwise number `|y|ᵀ|Ã||x|/|yᴴx|` (the same for `A`: a diagonal similarity
//! cancels in it). Their agreement with faer's path on random, graded, near-defective and
//! defective matrices, and with the closed form of triangular 2×2 blocks, is tested in
//! `tests/small_estimates.rs`.
//!
//! Matrices with structural zeros ([`crate::deflate`]) are not handled here: their vectors
//! live in the transformed coordinates of the deflation, and the caller takes faer's path.

use num_complex::Complex64;

use crate::deflate;
use crate::linalg::{balance_in_place, frobenius_norm};
use crate::modes::{ModeOptions, error_estimate};
use crate::small_eigen::{self, MAX_N};
use crate::{ConvergenceError, NumError};

/// Every eigenvalue of the n × n matrix `a` (column-major, n ≤ [`MAX_N`]) with its error
/// estimate, sorted as [`crate::small_eigen::eigenvalues_small`] sorts them, written to
/// `out` (length n). `Ok(false)` (and `out` unspecified) where this path does not apply: the
/// matrix has structural zeros, or a vector overflowed; the caller then takes faer's path.
///
/// Errors: those of [`crate::small_eigen::eigenvalues_small`].
pub(crate) fn eigenvalues_with_errors_small(
    a: &[f64],
    n: usize,
    out: &mut [(Complex64, f64)],
) -> Result<bool, NumError> {
    small_eigen::check(a, n, out.len())?;
    let mut w = [0.0; MAX_N * MAX_N];
    w[..n * n].copy_from_slice(a);
    let mut removed = [false; MAX_N];
    if deflate::deflate_small(&mut w[..n * n], n, &mut removed[..n]) > 0 {
        return Ok(false);
    }
    // `w` is now the matrix the eigenvalue kernel solves (rounding residues chopped).
    let h = &mut w[..n * n];
    let mut scale = [1.0; MAX_N];
    balance_in_place(h, n, &mut scale[..n]);
    let norm = frobenius_norm(h);
    let (mut re, mut im) = ([0.0; MAX_N], [0.0; MAX_N]);
    if n > 0 {
        small_eigen::qr(h, n, &mut re, &mut im)
            .map_err(|()| NumError::NoConvergence(ConvergenceError::QrIteration { n }))?;
    }
    let tol_factor = ModeOptions::default().tol_factor;
    let mut k = 0;
    while k < n {
        let lambda = Complex64::new(re[k], im[k] + 0.0);
        let estimate = if lambda == Complex64::new(0.0, 0.0) {
            // An exact zero: estimate 0, as faer's path gives it.
            0.0
        } else {
            let Some((condition, componentwise)) = condition_numbers(h, n, norm, lambda) else {
                return Ok(false);
            };
            error_estimate(n, norm, condition, componentwise, tol_factor)
        };
        out[k] = (lambda, estimate);
        // The QR iteration stores a conjugate pair next to each other: one estimate for both.
        if im[k] != 0.0 && k + 1 < n && im[k + 1] == -im[k] && re[k + 1] == re[k] {
            out[k + 1] = (Complex64::new(re[k + 1], im[k + 1] + 0.0), estimate);
            k += 2;
        } else {
            k += 1;
        }
    }
    // Insertion sort by (real, imaginary) part, as the eigenvalue kernel sorts (no allocation).
    for i in 1..n {
        let mut j = i;
        while j > 0 && small_eigen::cmp_re_im(&out[j - 1].0, &out[j].0).is_gt() {
            out.swap(j - 1, j);
            j -= 1;
        }
    }
    Ok(true)
}

/// The condition number `κ` (capped at 1/ε) and the componentwise number of the eigenvalue
/// `lambda` of the balanced n × n matrix `h` of Frobenius norm `norm`; `None` when a vector
/// is not finite. One instance per size, so that nothing beyond the n × n is initialised.
fn condition_numbers(h: &[f64], n: usize, norm: f64, lambda: Complex64) -> Option<(f64, f64)> {
    macro_rules! sizes {
        ($($k:literal)*) => {
            match n {
                $($k => condition_numbers_fixed::<$k>(h, norm, lambda),)*
                _ => None,
            }
        };
    }
    sizes!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// A complex M × M matrix by columns: `m[j][i]` is row i of column j.
type Fixed<const M: usize> = [[Complex64; M]; M];

fn condition_numbers_fixed<const M: usize>(
    h: &[f64],
    norm: f64,
    lambda: Complex64,
) -> Option<(f64, f64)> {
    let x = right_vector::<M>(h, norm, lambda, false)?;
    // yᴴ Ã = λ yᴴ  ⇔  Ãᵀ ȳ = λ ȳ: the right vector of Ãᵀ is ȳ, and yᴴx = Σ ȳ_i x_i.
    let yc = right_vector::<M>(h, norm, lambda, true)?;
    let (mut xx, mut yy, mut d) = (0.0, 0.0, Complex64::new(0.0, 0.0));
    for i in 0..M {
        xx += x[i].norm_sqr();
        yy += yc[i].norm_sqr();
        d += yc[i] * x[i];
    }
    let den = d.norm();
    let kappa = (xx * yy).sqrt() / den;
    let kappa = if kappa.is_finite() {
        kappa.min(1.0 / f64::EPSILON)
    } else {
        1.0 / f64::EPSILON
    };
    // |y|ᵀ |Ã| |x|.
    let ax: [f64; M] = core::array::from_fn(|j| x[j].norm());
    let mut num = 0.0;
    for i in 0..M {
        let row: f64 = (0..M).map(|j| h[j * M + i].abs() * ax[j]).sum();
        num += yc[i].norm() * row;
    }
    let componentwise = if den > 0.0 { num / den } else { f64::INFINITY };
    Some((kappa, componentwise))
}

/// A right eigenvector of `Ã − λI` (of `Ãᵀ − λI` when `transpose`) by inverse iteration
/// (module documentation), scaled to largest entry 1; `None` when not finite.
fn right_vector<const M: usize>(
    h: &[f64],
    norm: f64,
    lambda: Complex64,
    transpose: bool,
) -> Option<[Complex64; M]> {
    // M = Ã − λI (or its transpose), by columns.
    let mut m: Fixed<M> = [[Complex64::new(0.0, 0.0); M]; M];
    for (j, col) in m.iter_mut().enumerate() {
        for (i, v) in col.iter_mut().enumerate() {
            let hij = if transpose {
                h[i * M + j]
            } else {
                h[j * M + i]
            };
            *v = Complex64::new(hij, 0.0);
        }
        col[j] -= lambda;
    }
    // The floor of the pivots: a perturbation of the size of λ's own backward error.
    let floor = (f64::EPSILON * norm).max(f64::MIN_POSITIVE / f64::EPSILON);
    let piv = lu(&mut m, floor);
    // First step: U x = e. Accepted when its residual is at the level of λ's backward
    // error; otherwise full steps `(Ã − λI) x' = x`, keeping the vector of least residual (a
    // full step from a badly placed start can lose what the first gained).
    let mut x = [Complex64::new(1.0, 0.0); M];
    back_substitute(&m, &mut x);
    normalize(&mut x)?;
    let good = ACCEPT * M as f64 * f64::EPSILON * norm;
    let mut best = (residual(h, lambda, transpose, &x), x);
    for _ in 0..FULL_STEPS {
        if best.0 <= good {
            break;
        }
        for (k, &p) in piv.iter().enumerate() {
            x.swap(k, p);
            let xk = x[k];
            for i in k + 1..M {
                x[i] -= m[k][i] * xk;
            }
        }
        back_substitute(&m, &mut x);
        normalize(&mut x)?;
        let r = residual(h, lambda, transpose, &x);
        if r < best.0 {
            best = (r, x);
        }
    }
    Some(best.1)
}

/// A vector's residual is accepted below `ACCEPT · n · ε · ‖Ã‖_F` (entries scaled to at most
/// 1).
const ACCEPT: f64 = 10.0;

/// Full inverse-iteration steps after the first, at most.
const FULL_STEPS: usize = 3;

/// `‖(Ã − λI) x‖_∞` (of `Ãᵀ` when `transpose`).
fn residual<const M: usize>(
    h: &[f64],
    lambda: Complex64,
    transpose: bool,
    x: &[Complex64; M],
) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..M {
        let mut r = -lambda * x[i];
        for (j, xj) in x.iter().enumerate() {
            let v = if transpose {
                h[i * M + j]
            } else {
                h[j * M + i]
            };
            r += xj * v;
        }
        worst = worst.max(r.re.abs() + r.im.abs());
    }
    worst
}

/// LU factorization with partial pivoting in place (`L` unit lower, below the diagonal; `U`
/// on and above); returns the pivots (row `k` swapped with row `piv[k]` at step k). Pivots
/// smaller than `floor` in modulus are replaced by `floor` (the matrix is singular to
/// working precision by construction: λ is an eigenvalue).
fn lu<const M: usize>(m: &mut Fixed<M>, floor: f64) -> [usize; M] {
    let size = |z: Complex64| z.re.abs() + z.im.abs();
    let mut piv = [0usize; M];
    for k in 0..M {
        let p = (k..M)
            .max_by(|&i, &j| size(m[k][i]).total_cmp(&size(m[k][j])))
            .unwrap_or(k);
        piv[k] = p;
        if p != k {
            for col in m.iter_mut() {
                col.swap(k, p);
            }
        }
        if m[k][k].norm() < floor {
            m[k][k] = Complex64::new(floor, 0.0);
        }
        let r = 1.0 / m[k][k];
        let (left, right) = m.split_at_mut(k + 1);
        let lcol = &mut left[k];
        for v in &mut lcol[k + 1..] {
            *v *= r;
        }
        for col in right.iter_mut() {
            let ukj = col[k];
            if ukj == Complex64::new(0.0, 0.0) {
                continue;
            }
            for (v, l) in col[k + 1..].iter_mut().zip(&lcol[k + 1..]) {
                *v -= l * ukj;
            }
        }
    }
    piv
}

/// Solves `U x = b` in place (`U` the upper triangle of `m`).
fn back_substitute<const M: usize>(m: &Fixed<M>, x: &mut [Complex64; M]) {
    for k in (0..M).rev() {
        let xk = x[k] / m[k][k];
        x[k] = xk;
        for (xi, u) in x[..k].iter_mut().zip(&m[k][..k]) {
            *xi -= u * xk;
        }
    }
}

/// Scales `x` to largest entry (by `|re| + |im|`) 1; `None` when it is zero or not finite.
fn normalize<const M: usize>(x: &mut [Complex64; M]) -> Option<()> {
    let big = x.iter().fold(0.0f64, |b, z| b.max(z.re.abs() + z.im.abs()));
    if !(big.is_finite() && big > 0.0) {
        return None;
    }
    let r = 1.0 / big;
    x.iter_mut().for_each(|z| *z *= r);
    Some(())
}
