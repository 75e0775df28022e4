//! The PBH test of [`crate::minreal`]'s cluster pass without a full SVD: block inverse
//! iteration on `M Mᴴ`, `M = [A − λI, B]`, finds an orthonormal basis `X` of (an
//! approximation of) the left singular subspace of the `s` smallest singular values of `M`,
//! and the SVD of the small `s × (k + m)` matrix `Xᴴ M` gives directions `w = X u` with
//! `‖wᴴ M‖ = σ`. By interlacing these σ are upper bounds of the `s` smallest singular values
//! of `M`, and every direction found with `σ ≤ tol` is an uncontrollable direction in its own
//! right (its residual is computed, not assumed), so the test removes nothing a full SVD
//! would not.
//!
//! `(M Mᴴ)⁻¹ = (N Nᴴ + B Bᴴ)⁻¹`, `N = A − λI`, is applied by the Woodbury formula
//! `N⁻ᴴ (I − Z (I + Zᴴ Z)⁻¹ Zᴴ) N⁻¹`, `Z = N⁻¹ B`, with an LU factorization of `N` that
//! exploits the (block) Hessenberg form the staircase leaves: with lower bandwidth `p` it
//! costs O(k² p), a solve O(k²), so a cluster costs O(k² (p + m + s)) instead of the O(k³)
//! of a full SVD of `M`. (Inverse iteration on `N` alone would find the cluster's invariant
//! subspace, which for a defective cluster need not contain the minimizer of `‖wᴴ M‖`.)

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{ConvergenceError, NumError};

/// Iterations of the block inverse iteration. The components outside the cluster shrink by
/// the ratio of the cluster's distance to `λ` and the next eigenvalue's, per iteration: for
/// a cluster of rounding-split eigenvalues a single iteration nearly suffices.
const ITERATIONS: usize = 4;

/// Lower bandwidth of `a`: the largest `i − j` with `a[(i, j)] ≠ 0`.
pub(crate) fn lower_bandwidth(a: &DMatrix<f64>) -> usize {
    let k = a.nrows();
    let mut p = 0;
    for j in 0..k {
        if let Some(i) = (j + p + 1..k).rev().find(|&i| a[(i, j)] != 0.0) {
            p = i - j;
        }
    }
    p
}

/// LU factorization with partial pivoting `N = P₀ L₀ P₁ L₁ ⋯ U` of `N = A − λI` with lower
/// bandwidth `p` (column-major; the multipliers of step `j` below the diagonal of column `j`).
struct BandLu {
    k: usize,
    p: usize,
    lu: Vec<Complex64>,
    piv: Vec<usize>,
}

impl BandLu {
    /// `floor` replaces an exactly zero pivot (an exactly singular `N`: inverse iteration
    /// only needs a tiny one).
    fn new(a: &DMatrix<f64>, lam: Complex64, p: usize, floor: f64) -> Self {
        let k = a.nrows();
        let mut lu: Vec<Complex64> = a.iter().map(|&v| Complex64::new(v, 0.0)).collect();
        for i in 0..k {
            lu[i + i * k] -= lam;
        }
        let mut piv = vec![0; k];
        for j in 0..k {
            let last = (j + p).min(k - 1);
            let mut best = j;
            for i in j + 1..=last {
                if lu[i + j * k].norm() > lu[best + j * k].norm() {
                    best = i;
                }
            }
            piv[j] = best;
            if best != j {
                for c in j..k {
                    lu.swap(j + c * k, best + c * k);
                }
            }
            if lu[j + j * k].norm() == 0.0 {
                lu[j + j * k] = Complex64::new(floor, 0.0);
            }
            let d = lu[j + j * k];
            for i in j + 1..=last {
                let l = lu[i + j * k] / d;
                lu[i + j * k] = l;
                if l.norm() != 0.0 {
                    for c in j + 1..k {
                        let u = lu[j + c * k];
                        lu[i + c * k] -= l * u;
                    }
                }
            }
        }
        BandLu { k, p, lu, piv }
    }

    /// `x ← N⁻¹ x`.
    fn solve(&self, x: &mut [Complex64]) {
        let (k, lu) = (self.k, &self.lu);
        for j in 0..k {
            x.swap(j, self.piv[j]);
            let last = (j + self.p).min(k - 1);
            let xj = x[j];
            for i in j + 1..=last {
                x[i] -= lu[i + j * k] * xj;
            }
        }
        for i in (0..k).rev() {
            x[i] /= lu[i + i * k];
            let xi = x[i];
            for (l, v) in x[..i].iter_mut().enumerate() {
                *v -= lu[l + i * k] * xi;
            }
        }
    }

    /// `x ← N⁻ᴴ x`: `Uᴴ z = x`, then `x = P₀ L₀⁻ᴴ P₁ L₁⁻ᴴ ⋯ z`.
    fn solve_adjoint(&self, x: &mut [Complex64]) {
        let (k, lu) = (self.k, &self.lu);
        for i in 0..k {
            let col = &lu[i * k..i * k + i];
            let s: Complex64 = col.iter().zip(&x[..i]).map(|(u, z)| u.conj() * z).sum();
            x[i] = (x[i] - s) / lu[i + i * k].conj();
        }
        for j in (0..k).rev() {
            let last = (j + self.p).min(k - 1);
            let s: Complex64 = (j + 1..=last).map(|i| lu[i + j * k].conj() * x[i]).sum();
            x[j] -= s;
            x.swap(j, self.piv[j]);
        }
    }
}

/// Deterministic pseudo-random numbers in [−0.5, 0.5) (xorshift), for start vectors that are
/// orthogonal to no structure of the model.
struct Xorshift(u64);

impl Xorshift {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

/// Orthonormalizes the columns in place (modified Gram–Schmidt, twice). A column that (nearly)
/// lies in the span of the ones before it — inverse iteration at an exactly singular shift
/// can make all columns parallel — is replaced by a fresh pseudo-random one, so that the
/// result is always orthonormal.
fn orthonormalize(x: &mut [Vec<Complex64>], rng: &mut Xorshift) {
    for j in 0..x.len() {
        for attempt in 0..4 {
            let before = x[j].iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            for _ in 0..2 {
                for i in 0..j {
                    let (head, tail) = x.split_at_mut(j);
                    let r: Complex64 = head[i]
                        .iter()
                        .zip(&tail[0])
                        .map(|(q, v)| q.conj() * v)
                        .sum();
                    for (v, q) in tail[0].iter_mut().zip(&head[i]) {
                        *v -= r * q;
                    }
                }
            }
            let norm = x[j].iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            if norm > 1e-8 * before && norm > 0.0 {
                x[j].iter_mut().for_each(|v| *v /= norm);
                break;
            }
            debug_assert!(attempt < 3, "no independent start vector");
            x[j].iter_mut()
                .for_each(|v| *v = Complex64::new(rng.next(), 0.0));
        }
    }
}

/// The `s` directions `w` of the cluster at `λ`, orthonormal, and `σ = ‖wᴴ [A − λI, B]‖`,
/// smallest last (see the module documentation). `p` is the lower bandwidth of `a`.
pub(crate) fn cluster_pbh(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    lam: Complex64,
    s: usize,
    p: usize,
) -> Result<(Vec<Vec<Complex64>>, Vec<f64>), NumError> {
    let (k, m) = (a.nrows(), b.ncols());
    let s = s.min(k);
    let floor = f64::EPSILON * a.norm().max(1e-300);
    let lu = BandLu::new(a, lam, p, floor);
    let mut rng = Xorshift(0x9E37_79B9_7F4A_7C15);
    let mut x: Vec<Vec<Complex64>> = (0..s)
        .map(|_| (0..k).map(|_| Complex64::new(rng.next(), 0.0)).collect())
        .collect();
    orthonormalize(&mut x, &mut rng);
    // (N Nᴴ + B Bᴴ)⁻¹ = N⁻ᴴ (I − Z S⁻¹ Zᴴ) N⁻¹ with Z = N⁻¹ B, S = I + Zᴴ Z (Woodbury).
    let z: Vec<Vec<Complex64>> = (0..m)
        .map(|j| {
            let mut col: Vec<Complex64> = b.column(j).iter().map(|&v| v.into()).collect();
            lu.solve(&mut col);
            col
        })
        .collect();
    let dot = |u: &[Complex64], v: &[Complex64]| -> Complex64 {
        u.iter().zip(v).map(|(p, q)| p.conj() * q).sum()
    };
    let s_mat = DMatrix::<Complex64>::from_fn(m, m, |i, j| {
        dot(&z[i], &z[j])
            + if i == j {
                Complex64::new(1.0, 0.0)
            } else {
                Complex64::new(0.0, 0.0)
            }
    });
    let s_lu = s_mat.lu();
    for _ in 0..ITERATIONS {
        for col in x.iter_mut() {
            lu.solve(col);
            if m > 0 {
                let zt = nalgebra::DVector::from_fn(m, |i, _| dot(&z[i], col));
                let c = s_lu
                    .solve(&zt)
                    .unwrap_or_else(|| nalgebra::DVector::zeros(m));
                for (i, zi) in z.iter().enumerate() {
                    for (v, zv) in col.iter_mut().zip(zi) {
                        *v -= zv * c[i];
                    }
                }
            }
            lu.solve_adjoint(col);
        }
        if x.iter()
            .flatten()
            .any(|v| !v.re.is_finite() || !v.im.is_finite())
        {
            return Err(NumError::NoConvergence(ConvergenceError::AtEigenvalue {
                step: "inverse iteration of the PBH test",
                lambda: lam,
                detail: None,
            }));
        }
        orthonormalize(&mut x, &mut rng);
    }
    // G = Xᴴ [A − λI, B] (s × (k + m)).
    let g = faer::Mat::<Complex64>::from_fn(s, k + m, |i, j| {
        let xi = &x[i];
        if j < k {
            let av: Complex64 = (0..k).map(|l| xi[l].conj() * a[(l, j)]).sum();
            av - xi[j].conj() * lam
        } else {
            (0..k).map(|l| xi[l].conj() * b[(l, j - k)]).sum()
        }
    });
    // For a real λ everything is real (a real start, real solves): a real SVD keeps the
    // directions real, where a complex one could rotate them by a phase.
    let (u, sigma) = if lam.im == 0.0 {
        let gr = faer::Mat::<f64>::from_fn(s, k + m, |i, j| g[(i, j)].re);
        let svd = gr.thin_svd().map_err(|e| {
            NumError::NoConvergence(ConvergenceError::AtEigenvalue {
                step: "PBH SVD",
                lambda: lam,
                detail: Some(format!("{e:?}")),
            })
        })?;
        let u = svd.U();
        let u = DMatrix::from_fn(s, s, |i, j| Complex64::new(u[(i, j)], 0.0));
        (u, (0..s).map(|i| svd.S()[i]).collect::<Vec<f64>>())
    } else {
        let svd = g.thin_svd().map_err(|e| {
            NumError::NoConvergence(ConvergenceError::AtEigenvalue {
                step: "PBH SVD",
                lambda: lam,
                detail: Some(format!("{e:?}")),
            })
        })?;
        let u = svd.U();
        let u = DMatrix::from_fn(s, s, |i, j| u[(i, j)]);
        (u, (0..s).map(|i| svd.S()[i].re).collect::<Vec<f64>>())
    };
    let w = (0..s)
        .map(|j| {
            (0..k)
                .map(|l| (0..s).map(|i| x[i][l] * u[(i, j)]).sum())
                .collect()
        })
        .collect();
    Ok((w, sigma))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pseudo(k: usize, seed: u64) -> DMatrix<f64> {
        let mut s = seed;
        DMatrix::from_fn(k, k, |_, _| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
    }

    #[test]
    fn band_lu_solves_the_adjoint_system() {
        for (k, p) in [(7, 6), (9, 1), (9, 2), (1, 0)] {
            let mut a = pseudo(k, 3 + k as u64);
            for j in 0..k {
                for i in j + p + 1..k {
                    a[(i, j)] = 0.0;
                }
            }
            assert_eq!(lower_bandwidth(&a), p.min(k.saturating_sub(1)));
            let lam = Complex64::new(0.3, -0.2);
            let lu = BandLu::new(&a, lam, p, 1e-300);
            let y: Vec<Complex64> = (0..k)
                .map(|i| Complex64::new(i as f64 - 1.5, 0.5))
                .collect();
            let mut x = y.clone();
            lu.solve_adjoint(&mut x);
            // (A − λI)ᴴ x = y.
            for i in 0..k {
                let mut r: Complex64 = (0..k).map(|l| a[(l, i)] * x[l]).sum();
                r -= lam.conj() * x[i];
                assert!(
                    (r - y[i]).norm() < 1e-10,
                    "k {k} p {p} row {i}: {r} vs {}",
                    y[i]
                );
            }
        }
    }

    #[test]
    fn orthonormalize_replaces_parallel_columns() {
        // Inverse iteration at an exactly singular shift makes the columns parallel: the
        // result must still be orthonormal, never a zero column (whose residual would read 0).
        let v: Vec<Complex64> = (0..5)
            .map(|i| Complex64::new(i as f64 + 1.0, 0.0))
            .collect();
        let mut x = vec![v.clone(), v.clone(), v.iter().map(|z| z * 2.0).collect()];
        orthonormalize(&mut x, &mut Xorshift(7));
        for i in 0..3 {
            for j in 0..3 {
                let d: Complex64 = x[i].iter().zip(&x[j]).map(|(p, q)| p.conj() * q).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((d - want).norm() < 1e-12, "({i}, {j}): {d}");
            }
        }
    }
}
