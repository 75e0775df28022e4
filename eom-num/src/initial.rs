//! The response to an initial state, and the initial state that starts one mode alone.
//!
//! A real system started at `x₀ = Re v`, with `v` an eigenvector of `λ = σ + iω`, moves in
//! that mode only: `x(t) = Re(v e^{λt})` (the conjugate pair shares it), a decaying or
//! growing oscillation of the mode's shape. [`mode_state`] finds `v` by inverse iteration on
//! `A − λI` (the eigenvalue is known, from [`crate::modes`]); [`initial`] runs the free
//! response on the automatic grid of [`crate::time`].

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::statespace::StateSpace;
use crate::time::{TimeOptions, TimeResponse, grid, simulate};
use crate::{DimensionError, NonFiniteError, NumError, SingularError};

/// Free response from `x0` (no input), on the grid of `opts` (automatic: from the modes).
///
/// Errors: those of [`simulate`], [`NumError::Dimension`] when `x0` does not fit.
pub fn initial(
    ss: &StateSpace<f64>,
    x0: &DVector<f64>,
    opts: &TimeOptions,
) -> Result<TimeResponse, NumError> {
    ss.validate()?;
    let (nt, dt, note) = grid(ss, opts)?;
    let u = DMatrix::zeros(ss.inputs(), nt);
    let mut r = simulate(ss, &u, dt, Some(x0), opts)?;
    if r.message.is_none() {
        r.message = note;
    }
    Ok(r)
}

/// The eigenvector of `A` for the eigenvalue `lambda`, scaled so that its largest entry is
/// 1 (real): two steps of inverse iteration with the shift moved off `lambda` by a relative
/// `1e-10` of `‖A‖` (so that the shifted matrix is invertible but the iteration still
/// converges in one step to the eigenvector).
///
/// Errors: [`NumError::Dimension`] for a non-square `A`, [`NumError::NonFinite`] for a
/// non-finite `lambda`, [`NumError::Singular`] when the shifted matrix cannot be factored.
pub fn mode_state(a: &DMatrix<f64>, lambda: Complex64) -> Result<DVector<Complex64>, NumError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(NumError::Dimension(DimensionError::NotSquare {
            matrix: "A",
            rows: n,
            cols: a.ncols(),
        }));
    }
    if !(lambda.re.is_finite() && lambda.im.is_finite()) {
        return Err(NumError::NonFinite(NonFiniteError::Eigenvalue { lambda }));
    }
    let scale = a.iter().fold(lambda.norm(), |m, x| m.max(x.abs())).max(1.0);
    let shift = lambda + Complex64::new(1e-10 * scale, 1e-10 * scale);
    let mut m: DMatrix<Complex64> = a.map(|x| Complex64::new(x, 0.0));
    for k in 0..n {
        m[(k, k)] -= shift;
    }
    let lu = m.lu();
    // A start with every component: no eigenvector is orthogonal to it by accident of
    // structure (a vector of ones is, for modes of antisymmetric pairs).
    let mut v = DVector::from_fn(n, |k, _| Complex64::new(1.0 + 0.1 * k as f64, 0.05));
    for _ in 0..2 {
        v = lu
            .solve(&v)
            .ok_or(NumError::Singular(SingularError::Shifted { lambda }))?;
        let big = v.iter().fold(0.0f64, |b, z| b.max(z.norm()));
        if !(big.is_finite() && big > 0.0) {
            return Err(NumError::Singular(SingularError::InverseIteration {
                lambda,
            }));
        }
        v /= Complex64::new(big, 0.0);
    }
    // Largest entry real and positive (first of equals).
    let (l, _) = v.iter().enumerate().fold((0, -1.0), |(bi, bv), (i, z)| {
        if z.norm() > bv + 1e-12 {
            (i, z.norm())
        } else {
            (bi, bv)
        }
    });
    let phase = Complex64::from_polar(1.0, -v[l].arg());
    Ok(v.map(|z| z * phase))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::Horizon;
    use nalgebra::dmatrix;

    /// Spring–mass–damper, position and velocity observed.
    fn smd(m: f64, c: f64, k: f64) -> StateSpace<f64> {
        StateSpace::new(
            dmatrix![0.0, 1.0; -k / m, -c / m],
            dmatrix![0.0; 1.0 / m],
            dmatrix![1.0, 0.0; 0.0, 1.0],
            dmatrix![0.0; 0.0],
        )
        .unwrap()
    }

    #[test]
    fn free_response_of_the_smd_is_the_closed_form() {
        // x(t) = e^{−ζωt}(x₀ cos ω_d t + (v₀ + ζω x₀)/ω_d sin ω_d t).
        let (m, c, k) = (2.0, 4.0, 800.0);
        let ss = smd(m, c, k);
        let (x0, v0) = (0.01, -0.3);
        let opts = TimeOptions {
            horizon: Horizon::Given {
                t_end: 2.0,
                dt: 1e-3,
            },
            ..TimeOptions::default()
        };
        let r = initial(&ss, &DVector::from_vec(vec![x0, v0]), &opts).unwrap();
        let wn = (k / m).sqrt();
        let zeta = c / (2.0 * (k * m).sqrt());
        let wd = wn * (1.0 - zeta * zeta).sqrt();
        let x = r.series(0, 0);
        for (t, got) in r.t.iter().zip(&x) {
            let want = (-zeta * wn * t).exp()
                * (x0 * (wd * t).cos() + (v0 + zeta * wn * x0) / wd * (wd * t).sin());
            assert!((got - want).abs() < 1e-12, "t = {t}: {got} vs {want}");
        }
    }

    #[test]
    fn a_mode_started_alone_stays_in_its_eigenvector() {
        // A 4-state model with two well separated oscillatory modes: starting at Re v of
        // one, every state follows Re(v e^{λt}).
        let a = dmatrix![
            0.0, 0.0, 1.0, 0.0;
            0.0, 0.0, 0.0, 1.0;
            -30.0, 10.0, -0.2, 0.1;
            10.0, -10.0, 0.1, -0.1
        ];
        let ss = StateSpace::new(
            a.clone(),
            DMatrix::zeros(4, 1),
            DMatrix::identity(4, 4),
            DMatrix::zeros(4, 1),
        )
        .unwrap();
        let lambdas = crate::modes::eigenvalues(&a).unwrap();
        for lambda in lambdas.iter().filter(|z| z.im > 0.0) {
            let v = mode_state(&a, *lambda).unwrap();
            // An eigenvector: ‖A v − λ v‖ at rounding level.
            let av = a.map(|x| Complex64::new(x, 0.0)) * &v;
            let res = (av - &v * *lambda).norm();
            assert!(res < 1e-10, "residual {res}");
            let x0 = v.map(|z| z.re);
            let opts = TimeOptions {
                horizon: Horizon::Given {
                    t_end: 3.0,
                    dt: 0.01,
                },
                ..TimeOptions::default()
            };
            let r = initial(&ss, &x0, &opts).unwrap();
            for (kk, t) in r.t.iter().enumerate() {
                let e = (*lambda * *t).exp();
                for i in 0..4 {
                    let want = (v[i] * e).re;
                    let got = r.at(kk)[(i, 0)];
                    assert!(
                        (got - want).abs() < 1e-9,
                        "t = {t}, state {i}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let a = dmatrix![0.0, 1.0; -1.0, 0.0];
        assert!(mode_state(&a, Complex64::new(f64::NAN, 0.0)).is_err());
        assert!(mode_state(&DMatrix::zeros(2, 3), Complex64::new(0.0, 1.0)).is_err());
        let ss = smd(1.0, 1.0, 1.0);
        assert!(initial(&ss, &DVector::zeros(3), &TimeOptions::default()).is_err());
    }
}
