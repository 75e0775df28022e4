//! The error of a reduced model measured on a frequency grid: the largest singular value of
//! `G(jω) − G_r(jω)` over ω (a lower estimate of the H∞ norm of the error, which the a-priori
//! bound must exceed), and at ω = 0 (the error of the steady-state gain).
//!
//! The kept part of the model is the same in both, so the error system is that of the stable
//! parts alone: `E = [[A_s, 0], [0, A_r]], [B_s; B_r], [C_s, −C_r], D_s − D_r` — with no pole
//! on the imaginary axis, even where the model has integrators.

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use super::schur::eigenvalues;
use crate::freq::{HessenbergForm, SolveStatus};
use crate::statespace::StateSpace;
use crate::{NumError, SingularError};

/// The measured error of a reduction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MeasuredError {
    /// `max_ω σ_max(G(jω) − G_r(jω))` over the grid (same units as G).
    pub hinf: f64,
    /// The frequency of that maximum, Hz.
    pub at_hz: f64,
    /// `σ_max(G(0) − G_r(0))`: the error of the steady-state gain (of the finite parts where
    /// the model integrates: the kept part is the same in both).
    pub dc: f64,
    /// Frequencies evaluated.
    pub points: usize,
}

/// Largest singular value of a p × m complex matrix (column-major).
fn sigma_max(g: &[Complex64], p: usize, m: usize) -> f64 {
    if p == 0 || m == 0 {
        return 0.0;
    }
    if p == 1 || m == 1 {
        return g.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    }
    let mat = DMatrix::from_column_slice(p, m, g);
    mat.singular_values().max()
}

/// The frequencies (rad/s) where the error is evaluated: a logarithmic grid of 100 points per
/// decade from a hundredth of the slowest pole to a hundred times the fastest, ω = 0, and
/// around every lightly damped pole `ω_d(1 + t ζ)` for t in ±{0, ¼, ½, 1, 2}.
fn grid(poles: &[Complex64]) -> Vec<f64> {
    let mags: Vec<f64> = poles
        .iter()
        .map(|z| z.norm())
        .filter(|m| *m > 0.0)
        .collect();
    let lo = mags.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = mags.iter().copied().fold(0.0, f64::max);
    let (lo, hi) = if lo.is_finite() && hi > 0.0 {
        (lo / 100.0, hi * 100.0)
    } else {
        (1e-3, 1e3)
    };
    let decades = (hi / lo).log10().max(1.0);
    let count = (100.0 * decades).ceil() as usize;
    let mut w: Vec<f64> = (0..=count)
        .map(|k| lo * (hi / lo).powf(k as f64 / count as f64))
        .collect();
    w.push(0.0);
    for z in poles {
        let wd = z.im.abs();
        if wd == 0.0 {
            continue;
        }
        let zeta = (-z.re / z.norm()).abs();
        for t in [0.0, 0.25, 0.5, 1.0, 2.0] {
            for sgn in [-1.0, 1.0] {
                let f = wd * (1.0 + sgn * t * zeta);
                if f > 0.0 {
                    w.push(f);
                }
            }
        }
    }
    w.sort_by(f64::total_cmp);
    w.dedup();
    w
}

/// The error between the stable part `(a, b, c, d)` (a in real Schur form) and its reduction
/// `(ar, br, cr, dr)`.
pub(crate) fn measure(
    full: [&DMatrix<f64>; 4],
    reduced: [&DMatrix<f64>; 4],
) -> Result<MeasuredError, NumError> {
    let [a, b, c, d] = full;
    let [ar, br, cr, dr] = reduced;
    let (n, r) = (a.nrows(), ar.nrows());
    let (p, m) = (d.nrows(), d.ncols());
    let mut ae = DMatrix::zeros(n + r, n + r);
    ae.view_mut((0, 0), (n, n)).copy_from(a);
    ae.view_mut((n, n), (r, r)).copy_from(ar);
    let mut be = DMatrix::zeros(n + r, m);
    be.view_mut((0, 0), (n, m)).copy_from(b);
    be.view_mut((n, 0), (r, m)).copy_from(br);
    let mut ce = DMatrix::zeros(p, n + r);
    ce.view_mut((0, 0), (p, n)).copy_from(c);
    ce.view_mut((0, n), (p, r)).copy_from(&(-cr));
    let err = StateSpace::new(ae, be, ce, d - dr)?;
    let mut poles = eigenvalues(a);
    poles.extend(crate::modes::eigenvalues(ar)?);
    let w = grid(&poles);
    let form = HessenbergForm::new(&err)?;
    let mut ws = form.workspace();
    let mut g = vec![Complex64::new(0.0, 0.0); p * m];
    let mut out = MeasuredError {
        hinf: 0.0,
        at_hz: 0.0,
        dc: 0.0,
        points: w.len(),
    };
    for &omega in &w {
        if form.evaluate_in(Complex64::new(0.0, omega), &mut ws, &mut g)? == SolveStatus::Singular {
            return Err(NumError::Singular(SingularError::ErrorSystemPole { omega }));
        }
        let s = sigma_max(&g, p, m);
        if omega == 0.0 {
            out.dc = s;
        }
        if s > out.hinf {
            out.hinf = s;
            out.at_hz = omega / (2.0 * std::f64::consts::PI);
        }
    }
    Ok(out)
}
