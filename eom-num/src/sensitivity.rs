//! Eigenvalue sensitivities: `∂λ/∂p = yᴴ (∂A/∂p) x / (yᴴ x)` for a simple eigenvalue λ with
//! right and left eigenvectors `x`, `y`.
//!
//! Near a repeated eigenvalue the derivative grows without bound (at a defective one it does
//! not exist: the eigenvalue moves like the square root of the parameter change). The
//! eigenvalue condition number `κ = ‖x‖‖y‖/|yᴴx|` measures this; where it exceeds
//! [`DEFECTIVE_CONDITION`] no number is given.

use crate::eigen::eigen_full;
use crate::error::{DimensionError, NumError};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Above this eigenvalue condition number an eigenvalue is treated as (nearly) defective: its
/// sensitivity is reported as unbounded instead of as a number (a relative error of about
/// `κ²·ε` would make the number meaningless).
pub const DEFECTIVE_CONDITION: f64 = 1e6;

/// The sensitivities of one eigenvalue.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenSensitivity {
    /// The eigenvalue.
    pub eigenvalue: Complex64,
    /// Its condition number κ.
    pub condition: f64,
    /// `∂λ/∂pₖ` for each matrix of `∂A/∂pₖ` given; `None` when κ exceeds
    /// [`DEFECTIVE_CONDITION`].
    pub derivatives: Option<Vec<Complex64>>,
}

/// The sensitivities of every eigenvalue of `a` (sorted by real, then imaginary part) to the
/// parameters whose derivatives `∂A/∂pₖ` are given.
pub fn eigenvalue_sensitivities(
    a: &DMatrix<f64>,
    da: &[DMatrix<f64>],
) -> Result<Vec<EigenSensitivity>, NumError> {
    if let Some(k) = da.iter().position(|d| d.shape() != a.shape()) {
        return Err(NumError::Dimension(DimensionError::Derivative {
            parameter: k,
            rows: da[k].nrows(),
            cols: da[k].ncols(),
            a_rows: a.nrows(),
            a_cols: a.ncols(),
        }));
    }
    let e = eigen_full(a, true, true)?;
    let (right, left) = (e.right(), e.left());
    let n = a.nrows();
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let (x, y) = (right.column(k), left.column(k));
        let dot: Complex64 = y.iter().zip(x.iter()).map(|(a, b)| a.conj() * b).sum();
        let condition = e.condition[k];
        let derivatives = (condition <= DEFECTIVE_CONDITION && dot.norm() > 0.0).then(|| {
            da.iter()
                .map(|d| {
                    let mut s = Complex64::new(0.0, 0.0);
                    for i in 0..n {
                        let yi = y[i].conj();
                        if yi == Complex64::new(0.0, 0.0) {
                            continue;
                        }
                        let row: Complex64 = (0..n).map(|j| x[j] * d[(i, j)]).sum();
                        s += yi * row;
                    }
                    s / dot
                })
                .collect()
        });
        out.push(EigenSensitivity {
            eigenvalue: e.values[k],
            condition,
            derivatives,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangular_matrix_has_the_diagonal_derivatives() {
        // λ of an upper-triangular matrix are its diagonal entries: ∂λᵢ/∂aᵢᵢ = 1.
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 5.0, 0.0, 3.0]);
        let d11 = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 0.0]);
        let d12 = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let s = eigenvalue_sensitivities(&a, &[d11, d12]).expect("sensitivities");
        let d = s[0].derivatives.as_ref().expect("simple");
        assert!((d[0] - Complex64::new(1.0, 0.0)).norm() < 1e-14);
        assert!(d[1].norm() < 1e-14);
    }

    #[test]
    fn a_jordan_block_gets_no_number() {
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let d = DMatrix::from_element(2, 2, 1.0);
        let s = eigenvalue_sensitivities(&a, &[d]).expect("sensitivities");
        assert!(s.iter().all(|e| e.derivatives.is_none()), "{s:?}");
    }
}
