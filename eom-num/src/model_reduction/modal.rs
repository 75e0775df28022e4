//! Modal truncation: the chosen modes of a stable system in real Schur form moved to the top
//! of the form, decoupled from the rest by a Sylvester equation, and kept with their
//! eigenvalues unchanged.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::schur::{RealSchur, blocks};
use super::sylvester;
use crate::NumError;

/// `(V, W, Wᵀ a V, singular)` of [`modal_bases`].
pub(crate) type ModalBases = (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, bool);

/// The bases `(V, W)`, `WᵀV = I`, of the modes `chosen` selects of the quasi-triangular `a`,
/// the reduced state matrix `WᵀaV` (quasi-triangular, with exactly the chosen eigenvalues) and
/// whether the decoupling was singular to working precision.
pub(crate) fn modal_bases(
    a: &DMatrix<f64>,
    chosen: impl Fn(Complex64) -> bool,
) -> Result<ModalBases, NumError> {
    let n = a.nrows();
    let mut s = RealSchur {
        t: a.clone(),
        z: DMatrix::identity(n, n),
    };
    let k = s.reorder(chosen)?;
    let t11 = s.t.view((0, 0), (k, k)).clone_owned();
    let t12 = s.t.view((0, k), (k, n - k)).clone_owned();
    let t22 = s.t.view((k, k), (n - k, n - k)).clone_owned();
    let (x, singular) = sylvester::solve(&t11, &blocks(&t11), &t22, &blocks(&t22), &(-t12));
    let v = s.z.columns(0, k).clone_owned();
    // Wᵀ = [I, −X] Zᵀ.
    let w = s.z.columns(0, k) - s.z.columns(k, n - k) * x.transpose();
    Ok((v, w, t11, singular))
}
