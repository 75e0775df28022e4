//! Square-root balanced truncation (Tombs & Postlethwaite 1987, "Truncated balanced
//! realization of a stable non-minimal state-space system", Int. J. Control 46:1319–1330) and
//! the singular perturbation approximation that matches the DC gain (Liu & Anderson 1989,
//! "Singular perturbation approximation of balanced systems", Int. J. Control 50:1379–1405),
//! of a stable system in real Schur form.

use nalgebra::DMatrix;

use super::lyapunov::{controllability_factor, observability_factor};
use crate::linalg::svd;
use crate::{NumError, SingularError};

/// The Hankel singular values and what the projections are made of.
#[derive(Clone, Debug)]
pub(crate) struct Hankel {
    /// σ₁ ≥ σ₂ ≥ … ≥ 0.
    pub sigma: Vec<f64>,
    /// L with `P = L Lᵀ`.
    lc: DMatrix<f64>,
    /// U with `Q = Uᵀ U`.
    uo: DMatrix<f64>,
    /// `U L = Z Σ Yᵀ`.
    z: DMatrix<f64>,
    y: DMatrix<f64>,
}

impl Hankel {
    /// The Hankel singular values of the stable `(a, b, c)`, `a` in real Schur form.
    pub(crate) fn new(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
    ) -> Result<Self, NumError> {
        let lc = controllability_factor(a, b)?;
        let uo = observability_factor(a, c)?;
        let s = svd(&(&uo * &lc))?;
        Ok(Hankel {
            sigma: s.singular_values,
            lc,
            uo,
            z: s.u,
            y: s.v,
        })
    }

    /// How many Hankel singular values are above rounding, `n·ε·σ₁` (the rest belong to
    /// states that are uncontrollable or unobservable to working precision).
    pub(crate) fn numerical_order(&self) -> usize {
        let n = self.sigma.len();
        let floor = n as f64 * f64::EPSILON * self.sigma.first().copied().unwrap_or(0.0);
        self.sigma.iter().filter(|s| **s > floor).count()
    }

    /// The bases of the balanced truncation to order r (`r ≤ numerical_order`):
    /// `V = L Y_r Σ_r^{−1/2}`, `W = Uᵀ Z_r Σ_r^{−1/2}`, `WᵀV = I`.
    pub(crate) fn bases(&self, r: usize) -> (DMatrix<f64>, DMatrix<f64>) {
        let mut v = &self.lc * self.y.columns(0, r);
        let mut w = self.uo.transpose() * self.z.columns(0, r);
        for (j, s) in self.sigma[..r].iter().enumerate() {
            let f = 1.0 / s.sqrt();
            v.column_mut(j).scale_mut(f);
            w.column_mut(j).scale_mut(f);
        }
        (v, w)
    }
}

/// The bound `2 Σ_{i>r} σᵢ` on the H∞ norm of the error of a balanced truncation (or singular
/// perturbation approximation) to order r (Glover 1984; Enns 1984). Every value counts, also
/// repeated ones, so the bound is never below the one with distinct values.
pub(crate) fn bound(sigma: &[f64], r: usize) -> f64 {
    2.0 * sigma[r.min(sigma.len())..].iter().fold(0.0, |s, x| s + x)
}

/// The reduced `(A, B, C, D)` by the singular perturbation approximation of the balanced
/// realization `(ab, bb, cb, d)` at order r: the fast states' derivatives set to zero, so that
/// the DC gain is kept, `A₁₁ − A₁₂A₂₂⁻¹A₂₁` and so on.
///
/// Errors: [`NumError::Singular`] when A₂₂ is singular (cannot happen for a stable balanced
/// system; reported rather than assumed).
pub(crate) fn singular_perturbation(
    ab: &DMatrix<f64>,
    bb: &DMatrix<f64>,
    cb: &DMatrix<f64>,
    d: &DMatrix<f64>,
    r: usize,
) -> Result<[DMatrix<f64>; 4], NumError> {
    let n = ab.nrows();
    let f = n - r;
    let a11 = ab.view((0, 0), (r, r));
    let a12 = ab.view((0, r), (r, f));
    let a21 = ab.view((r, 0), (f, r));
    let a22 = ab.view((r, r), (f, f)).clone_owned();
    let b1 = bb.rows(0, r);
    let b2 = bb.rows(r, f);
    let c1 = cb.columns(0, r);
    let c2 = cb.columns(r, f);
    let lu = a22.lu();
    let singular = || NumError::Singular(SingularError::Residualised);
    let x = lu.solve(&a21.clone_owned()).ok_or_else(singular)?;
    let y = lu.solve(&b2.clone_owned()).ok_or_else(singular)?;
    Ok([a11 - a12 * &x, b1 - a12 * &y, c1 - c2 * &x, d - c2 * &y])
}
