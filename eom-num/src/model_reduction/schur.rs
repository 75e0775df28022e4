//! The real Schur form `A = Z T Zᵀ` (T upper quasi-triangular: 1 × 1 blocks for real
//! eigenvalues, 2 × 2 blocks for complex pairs), and its reordering: the blocks of chosen
//! eigenvalues moved to the top by orthogonal swaps of adjacent blocks (Bai & Demmel 1993,
//! "On swapping diagonal blocks in real Schur form", Linear Algebra Appl. 186:73–95).
//!
//! The Schur form: nalgebra's Hessenberg reduction, then the implicit double-shift QR iteration
//! written here (faer's real Schur form is not public, and nalgebra's stalls on some matrices
//! for want of exceptional shifts).

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::small::sylvester_small;
use crate::{ConvergenceError, NumError};

/// `A = Z T Zᵀ` with Z orthogonal and T upper quasi-triangular in the form the block
/// algorithms expect: a 2 × 2 diagonal block (nonzero subdiagonal entry) has a complex pair
/// of eigenvalues, every other subdiagonal entry is exactly zero.
#[derive(Clone, Debug)]
pub(crate) struct RealSchur {
    pub t: DMatrix<f64>,
    pub z: DMatrix<f64>,
}

/// The diagonal blocks of a quasi-triangular matrix: `(start, size)` in order.
pub(crate) fn blocks(t: &DMatrix<f64>) -> Vec<(usize, usize)> {
    let n = t.nrows();
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    while i < n {
        let k = if i + 1 < n && t[(i + 1, i)] != 0.0 {
            2
        } else {
            1
        };
        out.push((i, k));
        i += k;
    }
    out
}

/// The eigenvalue(s) of the diagonal block at `i` of size `k` (for a pair, the one with
/// positive imaginary part first).
pub(crate) fn block_eigenvalues(t: &DMatrix<f64>, i: usize, k: usize) -> Vec<Complex64> {
    if k == 1 {
        return vec![Complex64::new(t[(i, i)], 0.0)];
    }
    let (a, b, c, d) = (t[(i, i)], t[(i, i + 1)], t[(i + 1, i)], t[(i + 1, i + 1)]);
    let half = 0.5 * (a + d);
    let p = 0.5 * (a - d);
    let disc = p * p + b * c;
    if disc >= 0.0 {
        let r = disc.sqrt();
        return vec![Complex64::new(half + r, 0.0), Complex64::new(half - r, 0.0)];
    }
    let w = (-disc).sqrt();
    vec![Complex64::new(half, w), Complex64::new(half, -w)]
}

/// The eigenvalues of T, block by block.
pub(crate) fn eigenvalues(t: &DMatrix<f64>) -> Vec<Complex64> {
    blocks(t)
        .into_iter()
        .flat_map(|(i, k)| block_eigenvalues(t, i, k))
        .collect()
}

impl RealSchur {
    /// The real Schur form of `a` (square, finite).
    ///
    /// Errors: [`NumError::NoConvergence`] when the QR iteration does not converge within
    /// `100·n` iterations.
    pub(crate) fn new(a: &DMatrix<f64>) -> Result<Self, NumError> {
        let n = a.nrows();
        let (z, t) = if n > 2 {
            nalgebra::linalg::Hessenberg::new(a.clone()).unpack()
        } else {
            (DMatrix::identity(n, n), a.clone())
        };
        let mut s = RealSchur { t, z };
        s.francis()?;
        s.tidy();
        Ok(s)
    }

    /// The implicit double-shift QR iteration on the Hessenberg matrix `t` (Golub & Van Loan,
    /// "Matrix Computations", Algorithm 7.5.1, applied to the whole matrix so that T and Z
    /// are the Schur form and vectors), deflating at negligible subdiagonal entries, with
    /// LAPACK's exceptional shifts after 10 and 20 iterations without deflation.
    fn francis(&mut self) -> Result<(), NumError> {
        let n = self.t.nrows();
        let norm = self.t.norm();
        let eps = f64::EPSILON;
        let mut total = 0usize;
        let mut its = 0usize;
        let mut hi = n;
        while hi > 0 {
            let m = hi - 1;
            // The start of the active window: the last negligible subdiagonal entry.
            let mut l = m;
            while l > 0 {
                let mut s = self.t[(l - 1, l - 1)].abs() + self.t[(l, l)].abs();
                if s == 0.0 {
                    s = norm;
                }
                if self.t[(l, l - 1)].abs() <= eps * s {
                    self.t[(l, l - 1)] = 0.0;
                    break;
                }
                l -= 1;
            }
            if l == m {
                hi -= 1;
                its = 0;
                continue;
            }
            if l + 1 == m {
                hi -= 2;
                its = 0;
                continue;
            }
            its += 1;
            total += 1;
            if total > 30 * n.max(10) {
                return Err(NumError::NoConvergence(ConvergenceError::Schur { n }));
            }
            let (trace, det) = if its == 10 || its == 20 {
                let (k, base) = if its == 10 { (l, l) } else { (m - 1, m) };
                let s = self.t[(k + 1, k)].abs()
                    + if its == 10 {
                        self.t[(k + 2, k + 1)].abs()
                    } else {
                        self.t[(k, k - 1)].abs()
                    };
                let h11 = 0.75 * s + self.t[(base, base)];
                let h12 = -0.4375 * s;
                (2.0 * h11, h11 * h11 - h12 * s)
            } else {
                let (a, b, c, d) = (
                    self.t[(m - 1, m - 1)],
                    self.t[(m - 1, m)],
                    self.t[(m, m - 1)],
                    self.t[(m, m)],
                );
                (a + d, a * d - b * c)
            };
            self.francis_step(l, m, trace, det);
        }
        Ok(())
    }

    /// One double-shift step on the window `l..=m` with the shifts' trace and determinant.
    fn francis_step(&mut self, l: usize, m: usize, trace: f64, det: f64) {
        let n = self.t.nrows();
        let t = &self.t;
        let mut x = t[(l, l)] * t[(l, l)] + t[(l, l + 1)] * t[(l + 1, l)] - trace * t[(l, l)] + det;
        let mut y = t[(l + 1, l)] * (t[(l, l)] + t[(l + 1, l + 1)] - trace);
        let mut z = t[(l + 1, l)] * t[(l + 2, l + 1)];
        for k in l..m - 1 {
            self.reflect(
                &[x, y, z],
                k,
                if k > l { k - 1 } else { l },
                (k + 3).min(m),
                n,
            );
            if k > l {
                self.t[(k + 1, k - 1)] = 0.0;
                self.t[(k + 2, k - 1)] = 0.0;
            }
            x = self.t[(k + 1, k)];
            y = self.t[(k + 2, k)];
            if k + 3 <= m {
                z = self.t[(k + 3, k)];
            }
        }
        self.reflect(&[x, y], m - 1, m - 2, m, n);
        self.t[(m, m - 2)] = 0.0;
    }

    /// Applies the Householder reflector that maps `u` onto a multiple of e₁ to the rows
    /// `k..k+len` of T (columns from `col`), to its columns (rows up to `row_end`) and to Z.
    fn reflect(&mut self, u: &[f64], k: usize, col: usize, row_end: usize, n: usize) {
        let len = u.len();
        let alpha = u.iter().map(|v| v * v).sum::<f64>().sqrt();
        if alpha == 0.0 {
            return;
        }
        let mut v = [0.0; 3];
        v[..len].copy_from_slice(u);
        v[0] += if u[0] >= 0.0 { alpha } else { -alpha };
        let vv: f64 = v[..len].iter().map(|x| x * x).sum();
        if vv == 0.0 {
            return;
        }
        let beta = 2.0 / vv;
        for j in col..n {
            let s: f64 = (0..len).map(|i| v[i] * self.t[(k + i, j)]).sum::<f64>() * beta;
            for (i, vi) in v[..len].iter().enumerate() {
                self.t[(k + i, j)] -= s * vi;
            }
        }
        for r in 0..=row_end {
            let s: f64 = (0..len).map(|i| v[i] * self.t[(r, k + i)]).sum::<f64>() * beta;
            for (i, vi) in v[..len].iter().enumerate() {
                self.t[(r, k + i)] -= s * vi;
            }
        }
        for r in 0..n {
            let s: f64 = (0..len).map(|i| v[i] * self.z[(r, k + i)]).sum::<f64>() * beta;
            for (i, vi) in v[..len].iter().enumerate() {
                self.z[(r, k + i)] -= s * vi;
            }
        }
    }

    /// Zeroes what lies below the quasi-triangle and splits 2 × 2 blocks with real
    /// eigenvalues into two 1 × 1 blocks.
    fn tidy(&mut self) {
        let n = self.t.nrows();
        for j in 0..n {
            for i in j + 2..n {
                self.t[(i, j)] = 0.0;
            }
        }
        let mut i = 0;
        while i + 1 < n {
            if self.t[(i + 1, i)] == 0.0 {
                i += 1;
                continue;
            }
            // A 2×2 block must not follow another one directly.
            if i + 2 < n && self.t[(i + 2, i + 1)] != 0.0 {
                self.t[(i + 2, i + 1)] = 0.0;
            }
            self.split_if_real(i);
            i += 2;
        }
    }

    /// Rotates the 2 × 2 block at `i` to upper triangular form when its eigenvalues are
    /// real; leaves a complex pair as it is.
    fn split_if_real(&mut self, i: usize) {
        let (a, b, c, d) = (
            self.t[(i, i)],
            self.t[(i, i + 1)],
            self.t[(i + 1, i)],
            self.t[(i + 1, i + 1)],
        );
        let p = 0.5 * (a - d);
        let disc = p * p + b * c;
        if disc < 0.0 {
            return;
        }
        // Eigenvalue farther from d, then an eigenvector of the block for it.
        let r = disc.sqrt();
        let lambda = 0.5 * (a + d) + if p >= 0.0 { r } else { -r };
        let (v1, v2) = {
            let u = (b, lambda - a);
            let w = (lambda - d, c);
            if u.0.hypot(u.1) >= w.0.hypot(w.1) {
                u
            } else {
                w
            }
        };
        let h = v1.hypot(v2);
        if h == 0.0 {
            return;
        }
        let (cs, sn) = (v1 / h, v2 / h);
        let g = DMatrix::from_row_slice(2, 2, &[cs, -sn, sn, cs]);
        self.apply(i, &g);
        self.t[(i + 1, i)] = 0.0;
    }

    /// `T ← Gᵀ T G`, `Z ← Z G` for an orthogonal `G` acting on the k coordinates from `j`.
    fn apply(&mut self, j: usize, g: &DMatrix<f64>) {
        let k = g.nrows();
        let n = self.t.nrows();
        let rows = g.transpose() * self.t.view((j, 0), (k, n));
        self.t.view_mut((j, 0), (k, n)).copy_from(&rows);
        let cols = self.t.view((0, j), (n, k)) * g;
        self.t.view_mut((0, j), (n, k)).copy_from(&cols);
        let zc = self.z.view((0, j), (n, k)) * g;
        self.z.view_mut((0, j), (n, k)).copy_from(&zc);
    }

    /// Swaps the adjacent diagonal blocks at `j` (size `p`) and `j + p` (size `q`).
    ///
    /// Errors: [`NumError::NoConvergence`] when the swap would perturb T by more than a few
    /// units of rounding relative to the blocks (Bai & Demmel's stability test): the blocks'
    /// eigenvalues are too close to be separated reliably.
    fn swap(&mut self, j: usize, p: usize, q: usize) -> Result<(), NumError> {
        let k = p + q;
        let block = self.t.view((j, j), (k, k)).clone_owned();
        let a11: Vec<f64> = block.view((0, 0), (p, p)).iter().copied().collect();
        let a22: Vec<f64> = block.view((p, p), (q, q)).iter().copied().collect();
        let mut x: Vec<f64> = block.view((0, p), (p, q)).iter().copied().collect();
        // A11 X − X A22 = A12: the columns of [−X; I] span the invariant subspace of A22's
        // eigenvalues.
        sylvester_small(&a11, &a22, &mut x, p, q);
        let mut basis = DMatrix::zeros(k, q);
        for c in 0..q {
            for r in 0..p {
                basis[(r, c)] = -x[c * p + r];
            }
            basis[(p + c, c)] = 1.0;
        }
        let qr = basis.qr();
        let mut g = DMatrix::identity(k, k);
        qr.q_tr_mul(&mut g);
        let g = g.transpose();
        let swapped = g.transpose() * &block * &g;
        let scale = block.norm().max(f64::MIN_POSITIVE);
        let below = swapped.view((q, 0), (p, q)).norm();
        if below > 100.0 * f64::EPSILON * scale {
            return Err(NumError::NoConvergence(ConvergenceError::SchurSwap {
                first: block_eigenvalues(&self.t, j, p),
                second: block_eigenvalues(&self.t, j + p, q),
                perturbation: below,
                scale,
            }));
        }
        self.apply(j, &g);
        for c in j..j + q {
            for r in j + q..j + k {
                self.t[(r, c)] = 0.0;
            }
        }
        // The new blocks: exact zeros below 1×1 blocks, split 2×2 blocks that came out real.
        if q == 1 {
            self.t[(j + 1, j)] = 0.0;
        } else {
            self.split_if_real(j);
        }
        if p == 2 {
            self.split_if_real(j + q);
        }
        Ok(())
    }

    /// Moves the blocks whose eigenvalues `chosen` selects to the top, keeping the order
    /// within each group. Returns how many eigenvalues were chosen (a pair counts two).
    pub(crate) fn reorder(
        &mut self,
        chosen: impl Fn(Complex64) -> bool,
    ) -> Result<usize, NumError> {
        let mut top = 0;
        loop {
            // The first chosen block at or below `top`.
            let bl = blocks(&self.t);
            let Some(&(start, size)) = bl
                .iter()
                .find(|&&(s, k)| s >= top && chosen(block_eigenvalues(&self.t, s, k)[0]))
            else {
                return Ok(top);
            };
            let mut pos = start;
            let k = size;
            while pos > top {
                // The block just above.
                let above = if pos >= 2 && self.t[(pos - 1, pos - 2)] != 0.0 {
                    2
                } else {
                    1
                };
                self.swap(pos - above, above, k)?;
                pos -= above;
                // (A 2×2 block that came out with real eigenvalues was split; the swaps
                // move its two 1×1 blocks together.)
            }
            top = pos + k;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(a: &DMatrix<f64>, s: &RealSchur) {
        let back = &s.z * &s.t * s.z.transpose();
        assert!((back - a).norm() < 1e-12 * a.norm(), "A = Z T Zᵀ");
        let ortho = s.z.transpose() * &s.z - DMatrix::identity(a.nrows(), a.nrows());
        assert!(ortho.norm() < 1e-13, "Z orthogonal");
        for j in 0..a.nrows() {
            for i in j + 2..a.nrows() {
                assert_eq!(s.t[(i, j)], 0.0);
            }
        }
    }

    #[test]
    fn reordering_moves_the_chosen_eigenvalues_up_and_keeps_the_similarity() {
        // Eigenvalues: 2 ± 3i, −1, 0.5, −4 ± i, −0.2 in a random basis.
        let d = DMatrix::from_row_slice(
            7,
            7,
            &[
                2.0, 3.0, 0.3, 0.1, 0.2, 0.0, 0.5, //
                -3.0, 2.0, 0.1, 0.0, 0.1, 0.4, 0.0, //
                0.0, 0.0, -1.0, 0.7, 0.3, 0.1, 0.2, //
                0.0, 0.0, 0.0, 0.5, 0.2, 0.1, 0.9, //
                0.0, 0.0, 0.0, 0.0, -4.0, 1.0, 0.3, //
                0.0, 0.0, 0.0, 0.0, -1.0, -4.0, 0.1, //
                0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.2,
            ],
        );
        let q = DMatrix::from_fn(7, 7, |i, j| ((i * 7 + j) as f64 * 0.37).sin())
            .qr()
            .q();
        let a = &q * &d * q.transpose();
        let mut s = RealSchur::new(&a).expect("schur");
        check(&a, &s);
        let stable = |z: Complex64| z.re < 0.0;
        let top = s.reorder(stable).expect("reorder");
        assert_eq!(top, 4);
        check(&a, &s);
        let ev = eigenvalues(&s.t);
        assert!(ev[..4].iter().all(|z| z.re < 0.0), "{ev:?}");
        assert!(ev[4..].iter().all(|z| z.re > 0.0), "{ev:?}");
    }
}
