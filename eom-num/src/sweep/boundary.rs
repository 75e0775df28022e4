//! Step 5 of a sweep: the grid cells where a branch's real part changes sign, and the
//! boundary inside each, located by Brent's method with the branch re-identified at every
//! trial value.

use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;

use super::assign::assign_pinned;
use super::{Boundary, Branches, Crossing, Ctx, Sweep, SweepError, effective_re, errors_of};
use crate::modes::EigenvaluesWorkspace;

/// Branch values at an off-grid point, `‖A‖_F` there, and the error estimates (when asked for).
pub(super) type Tracked = (Vec<Complex64>, f64, Option<Vec<f64>>);

impl Branches {
    /// The sign changes of the non-neutral branches between grid points outside the band,
    /// as `(branch, point before, point after)`, one per conjugate pair.
    pub(super) fn brackets(&self) -> Vec<(usize, usize, usize)> {
        let mut brackets = Vec::new();
        for j in (0..self.neutral.len()).filter(|&j| !self.neutral[j]) {
            let mut last: Option<(usize, i8)> = None;
            for k in 0..self.tracked.len() {
                let s = self.sign(k, j);
                if s == 0 {
                    continue;
                }
                if let Some((kp, sp)) = last
                    && sp != s
                    && !is_lower_half_of_pair(&self.tracked, j, kp, k)
                {
                    brackets.push((j, kp, k));
                }
                last = Some((k, s));
            }
        }
        brackets
    }
}

impl Sweep {
    /// The boundary inside every bracket (in parallel), by increasing value, a conjugate
    /// pair's reported once; none unless boundaries are located.
    pub(super) fn locate_boundaries<F, E>(
        &self,
        ctx: &Ctx<'_, F>,
        br: &Branches,
        brackets: &[(usize, usize, usize)],
    ) -> Result<Vec<Boundary>, SweepError<E>>
    where
        F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
        E: Send,
    {
        if !self.locate {
            return Ok(Vec::new());
        }
        let xs = &self.values;
        let increasing = xs.len() < 2 || xs[1] > xs[0];
        let located: Vec<Result<Boundary, SweepError<E>>> = brackets
            .par_iter()
            .map(|&(j, ka, kb)| {
                let ends = (
                    (xs[ka], br.tracked[ka].clone()),
                    (xs[kb], br.tracked[kb].clone()),
                );
                let mut b = ctx.locate(
                    j,
                    &br.neutral_idx,
                    ends,
                    (self.tolerance, self.max_evaluations),
                    br.z,
                )?;
                let rising = br.sign(kb, j) > 0;
                b.crossing = if rising == increasing {
                    Crossing::Destabilizing
                } else {
                    Crossing::Stabilizing
                };
                Ok(b)
            })
            .collect();
        let mut boundaries = Vec::with_capacity(located.len());
        for b in located {
            boundaries.push(b?);
        }
        boundaries.sort_by(|a, b| a.value.total_cmp(&b.value));
        dedupe_pairs(&mut boundaries, self.tolerance);
        Ok(boundaries)
    }
}

impl<F, E> Ctx<'_, F>
where
    F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
{
    /// Eigenvalues at an off-grid value, assigned to the branches by interpolating the
    /// tracked values of the neighbouring grid points.
    pub(super) fn eval_tracked(
        &self,
        x: f64,
        xs: &[f64],
        tracked: &[Vec<Complex64>],
        z: usize,
        errors: bool,
    ) -> Result<Tracked, SweepError<E>> {
        let n = tracked[0].len();
        let e = self.eval(x, &mut None, Some(n), errors)?;
        // Neighbouring grid points (xs is monotone).
        let k = xs
            .windows(2)
            .position(|w| (w[0] - x) * (w[1] - x) <= 0.0)
            .unwrap_or(0);
        let pred = if xs.len() < 2 {
            tracked[0].clone()
        } else {
            interpolate(xs[k], &tracked[k], xs[k + 1], &tracked[k + 1], x)
        };
        let values = assign_pinned(&pred, &e.eig, &pred, z);
        let errors = e.errors.as_ref().map(|err| errors_of(&values, &e.eig, err));
        Ok((values, e.norm, errors))
    }

    /// Brent's method on g(x) = Re λ_j(x) inside a bracket with a sign change.
    fn locate(
        &self,
        j: usize,
        neutral: &[usize],
        ends: ((f64, Vec<Complex64>), (f64, Vec<Complex64>)),
        (tol, max_evaluations): (f64, usize),
        z: usize,
    ) -> Result<Boundary, SweepError<E>> {
        let n = ends.0.1.len();
        let mut ws = Some(EigenvaluesWorkspace::new(n));
        let ((mut xa, mut va), (mut xb, mut vb)) = ends;
        let (mut fa, mut fb) = (effective_re(&va, j, neutral), effective_re(&vb, j, neutral));
        let (mut xc, mut vc, mut fc) = (xa, va.clone(), fa);
        let mut d = xb - xa;
        let mut e = d;
        let mut evaluations = 0;
        let mut converged = false;
        loop {
            if (fb > 0.0) == (fc > 0.0) {
                xc = xa;
                vc = va.clone();
                fc = fa;
                d = xb - xa;
                e = d;
            }
            if fc.abs() < fb.abs() {
                // Keep the best estimate in b.
                xa = xb;
                va = vb.clone();
                fa = fb;
                xb = xc;
                vb = vc.clone();
                fb = fc;
                xc = xa;
                vc = va.clone();
                fc = fa;
            }
            let tol1 = 2.0 * f64::EPSILON * xb.abs() + 0.5 * tol;
            let xm = 0.5 * (xc - xb);
            if xm.abs() <= tol1 || fb == 0.0 {
                converged = true;
                break;
            }
            if evaluations >= max_evaluations {
                break;
            }
            if e.abs() >= tol1 && fa.abs() > fb.abs() {
                // Interpolation step: secant or inverse quadratic.
                let s = fb / fa;
                let (mut p, mut q);
                if xa == xc {
                    p = 2.0 * xm * s;
                    q = 1.0 - s;
                } else {
                    let qq = fa / fc;
                    let r = fb / fc;
                    p = s * (2.0 * xm * qq * (qq - r) - (xb - xa) * (r - 1.0));
                    q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
                }
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                    e = d;
                    d = p / q;
                } else {
                    d = xm;
                    e = d;
                }
            } else {
                d = xm;
                e = d;
            }
            xa = xb;
            va = vb.clone();
            fa = fb;
            xb += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
            // Identify the branches at the trial value against the values interpolated
            // between the two ends of the current bracket.
            let pred = interpolate(xa, &va, xc, &vc, xb);
            let ev = self.eval(xb, &mut ws, Some(n), false)?;
            evaluations += 1;
            vb = assign_pinned(&pred, &ev.eig, &pred, z);
            fb = effective_re(&vb, j, neutral);
        }
        Ok(Boundary {
            value: xb,
            eigenvalue: vb[j] + Complex64::new(fb - vb[j].re, 0.0),
            branch: j,
            crossing: Crossing::Destabilizing,
            bracket: [xb.min(xc), xb.max(xc)],
            evaluations,
            converged,
        })
    }
}

fn interpolate(x0: f64, v0: &[Complex64], x1: f64, v1: &[Complex64], x: f64) -> Vec<Complex64> {
    let t = if x1 == x0 { 0.0 } else { (x - x0) / (x1 - x0) };
    v0.iter().zip(v1).map(|(&a, &b)| a + (b - a) * t).collect()
}

/// Whether branch `j` is the lower (negative imaginary part) half of a conjugate pair at both
/// grid points `ka` and `kb`: its partner then brackets the same boundary.
fn is_lower_half_of_pair(tracked: &[Vec<Complex64>], j: usize, ka: usize, kb: usize) -> bool {
    let (za, zb) = (tracked[ka][j], tracked[kb][j]);
    if za.im >= 0.0 || zb.im >= 0.0 {
        return false;
    }
    (0..tracked[ka].len())
        .any(|i| i != j && tracked[ka][i] == za.conj() && tracked[kb][i] == zb.conj())
}

/// Removes the second of two boundaries at the same value whose eigenvalues are conjugate
/// (a pair tracked as two branches that both bracketed it), keeping Im ≥ 0.
fn dedupe_pairs(b: &mut Vec<Boundary>, tol: f64) {
    let mut i = 0;
    while i + 1 < b.len() {
        let (x, y) = (&b[i], &b[i + 1]);
        let scale = x.eigenvalue.norm().max(y.eigenvalue.norm()).max(1e-300);
        if (x.value - y.value).abs() <= 10.0 * tol
            && (x.eigenvalue - y.eigenvalue.conj()).norm() <= 1e-6 * scale
            && x.eigenvalue.im != 0.0
        {
            let drop = if x.eigenvalue.im < 0.0 { i } else { i + 1 };
            b.remove(drop);
        } else {
            i += 1;
        }
    }
}
