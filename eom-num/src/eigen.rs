//! The eigendecomposition shared by the modes, the automatic frequency grid, the time
//! horizon and the sensitivities: eigenvalues sorted by (re, im), condition numbers, and the
//! eigenvectors kept in faer's packed real form until a caller asks for them.
//!
//! faer returns the eigenvectors of a real matrix packed in real storage: a real eigenvalue
//! `λ_j` has its vector in column `j`; a complex pair `(λ_j, λ_{j+1} = conj λ_j)` with
//! `Im λ_j > 0` has `x_j = u_j + i u_{j+1}` and `x_{j+1} = conj x_j`. Keeping that form
//! halves the memory of the vectors and lets products such as `phys · X` run as one real
//! matrix product (or a sparse one) instead of n complex matrix–vector products.

use faer::diag::DiagMut;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::evd_real;
use faer::{Mat, MatRef, Par};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::NumError;
use crate::linalg::balance_in_place;
use crate::statespace::check_finite;

/// Where the eigenvector of a sorted eigenvalue lives in the packed storage.
#[derive(Clone, Copy, Debug)]
enum Slot {
    /// Column j, real.
    Real(usize),
    /// `u_j + i u_{j+1}` (positive imaginary part).
    Upper(usize),
    /// `u_j − i u_{j+1}` (the conjugate).
    Lower(usize),
}

/// Eigenvalues, condition numbers and packed eigenvectors of a real matrix.
pub(crate) struct Eigen {
    /// Eigenvalues sorted by (re, im).
    pub values: Vec<Complex64>,
    /// Eigenvalue condition numbers κᵢ (computed on the balanced matrix), in sorted order.
    pub condition: Vec<f64>,
    /// Frobenius norm of the balanced matrix.
    pub norm: f64,
    /// Packed right eigenvectors of the balanced matrix (n × n).
    right: Mat<f64>,
    /// Packed left eigenvectors of the balanced matrix (n × n, or 0 × 0 when not kept).
    left: Mat<f64>,
    /// The balancing `A = D Ã D⁻¹`.
    scale: Vec<f64>,
    /// Sorted index → packed column.
    slots: Vec<Slot>,
}

/// Bytes of the dense matrices [`eigen_full`] allocates for an n × n matrix (the balanced
/// copy, the packed vectors, faer's scratch), for predicting memory use.
pub(crate) fn eigen_bytes(n: usize) -> usize {
    8 * n * n * 4
}

/// Eigenvalues, condition numbers and eigenvectors of `a` (balanced first if asked). The
/// left eigenvectors are kept for [`Eigen::left`] only when `keep_left`.
pub(crate) fn eigen_full(
    a: &DMatrix<f64>,
    balance: bool,
    keep_left: bool,
) -> Result<Eigen, NumError> {
    if a.nrows() != a.ncols() {
        return Err(NumError::Dimension(format!(
            "A is {}×{}, expected a square matrix",
            a.nrows(),
            a.ncols()
        )));
    }
    check_finite(a, "A")?;
    let n = a.nrows();
    crate::budget::check("the eigenvectors", eigen_bytes(n))?;
    let mut ab = a.as_slice().to_vec();
    let mut scale = vec![1.0; n];
    if balance {
        balance_in_place(&mut ab, n, &mut scale);
    }
    let mut re = vec![0.0; n];
    let mut im = vec![0.0; n];
    let mut ul = Mat::<f64>::zeros(n, n);
    let mut ur = Mat::<f64>::zeros(n, n);
    if n > 0 {
        let mut buf = MemBuffer::new(crate::modes::eig_scratch(n, true));
        evd_real(
            MatRef::from_column_major_slice(&ab, n, n),
            DiagMut::from_slice_mut(&mut re),
            DiagMut::from_slice_mut(&mut im),
            Some(ul.as_mut()),
            Some(ur.as_mut()),
            Par::Seq,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|_| {
            NumError::NoConvergence(format!("eigenvalues and eigenvectors of a {n}×{n} matrix"))
        })?;
    }
    let norm = ab.iter().map(|x| x * x).sum::<f64>().sqrt();
    drop(ab);
    let mut values = Vec::with_capacity(n);
    let mut slots = Vec::with_capacity(n);
    let mut condition = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        if im[j] == 0.0 || j + 1 == n {
            values.push(Complex64::new(re[j], 0.0));
            slots.push(Slot::Real(j));
            condition.push(condition_of(&ur, &ul, j, false));
            j += 1;
        } else {
            values.push(Complex64::new(re[j], im[j]));
            values.push(Complex64::new(re[j], -im[j]));
            slots.push(Slot::Upper(j));
            slots.push(Slot::Lower(j));
            let k = condition_of(&ur, &ul, j, true);
            condition.extend([k, k]);
            j += 2;
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| cmp_re_im(&values[a], &values[b]));
    Ok(Eigen {
        values: order.iter().map(|&k| values[k]).collect(),
        condition: order.iter().map(|&k| condition[k]).collect(),
        norm,
        right: ur,
        left: if keep_left { ul } else { Mat::zeros(0, 0) },
        scale,
        slots: order.iter().map(|&k| slots[k]).collect(),
    })
}

fn cmp_re_im(a: &Complex64, b: &Complex64) -> std::cmp::Ordering {
    a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im))
}

/// κ = ‖x‖‖y‖/|yᴴx| of the packed pair at column j (complex when `pair`), capped at 1/ε (an
/// exactly defective eigenvalue gives yᴴx = 0: fully undetermined).
fn condition_of(ur: &Mat<f64>, ul: &Mat<f64>, j: usize, pair: bool) -> f64 {
    let n = ur.nrows();
    let (mut xx, mut yy, mut dr, mut di) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        let (xr, yr) = (ur[(i, j)], ul[(i, j)]);
        let (xi, yi) = if pair {
            (ur[(i, j + 1)], ul[(i, j + 1)])
        } else {
            (0.0, 0.0)
        };
        xx += xr * xr + xi * xi;
        yy += yr * yr + yi * yi;
        // conj(y) x
        dr += yr * xr + yi * xi;
        di += yr * xi - yi * xr;
    }
    let c = (xx * yy).sqrt() / dr.hypot(di);
    if c.is_finite() {
        c.min(1.0 / f64::EPSILON)
    } else {
        1.0 / f64::EPSILON
    }
}

impl Eigen {
    /// Number of eigenvalues.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Entry i of a packed vector, `m(i, j)` reading the packed storage.
    fn packed(m: impl Fn(usize, usize) -> f64, slot: Slot, i: usize) -> Complex64 {
        match slot {
            Slot::Real(j) => Complex64::new(m(i, j), 0.0),
            Slot::Upper(j) => Complex64::new(m(i, j), m(i, j + 1)),
            Slot::Lower(j) => Complex64::new(m(i, j), -m(i, j + 1)),
        }
    }

    fn unit_columns(&self, m: &Mat<f64>, left: bool) -> DMatrix<Complex64> {
        let n = self.len();
        let mut out = DMatrix::<Complex64>::zeros(n, n);
        for (k, &slot) in self.slots.iter().enumerate() {
            let mut col = out.column_mut(k);
            for i in 0..n {
                let f = if left {
                    1.0 / self.scale[i]
                } else {
                    self.scale[i]
                };
                col[i] = Self::packed(|r, c| m[(r, c)], slot, i) * f;
            }
            let nn = col.norm();
            if nn > 0.0 {
                col.unscale_mut(nn);
            }
        }
        out
    }

    /// Right eigenvectors (columns, original coordinates, unit 2-norm), in sorted order.
    pub fn right(&self) -> DMatrix<Complex64> {
        self.unit_columns(&self.right, false)
    }

    /// Left eigenvectors (columns `y` with `yᴴA = λyᴴ`, original coordinates, unit 2-norm),
    /// in sorted order. Empty unless [`eigen_full`] was asked to keep them.
    pub fn left(&self) -> DMatrix<Complex64> {
        if self.left.nrows() != self.len() {
            return DMatrix::zeros(0, 0);
        }
        self.unit_columns(&self.left, true)
    }

    /// `P · x_k` for every sorted eigenvalue k (x_k a right eigenvector in original
    /// coordinates, not normalised), for a real `P` with one column per state: one real
    /// product with the packed vectors, sparse when `P` is (a map to body coordinates usually
    /// is), then unpacked. Returns one vector per eigenvalue.
    pub fn map_right(&self, p: &DMatrix<f64>) -> Vec<DVector<Complex64>> {
        let n = self.len();
        let rows = p.nrows();
        debug_assert_eq!(p.ncols(), n);
        let prod = scaled_product(p, &self.scale, self.right.as_ref());
        self.slots
            .iter()
            .map(|&slot| DVector::from_fn(rows, |i, _| Self::packed(|r, c| prod[(r, c)], slot, i)))
            .collect()
    }
}

/// `P · diag(scale) · U`, exploiting the zeros of `P` when there are many.
fn scaled_product(p: &DMatrix<f64>, scale: &[f64], u: MatRef<'_, f64>) -> DMatrix<f64> {
    let (rows, n) = p.shape();
    let cols = u.ncols();
    let nnz = p.iter().filter(|&&v| v != 0.0).count();
    let mut out = DMatrix::<f64>::zeros(rows, cols);
    if nnz * 8 <= rows * n {
        // Column k of P as its nonzero entries.
        let sparse: Vec<Vec<(usize, f64)>> = (0..n)
            .map(|k| {
                (0..rows)
                    .filter(|&i| p[(i, k)] != 0.0)
                    .map(|i| (i, p[(i, k)] * scale[k]))
                    .collect()
            })
            .collect();
        for j in 0..cols {
            let mut col = out.column_mut(j);
            for (k, entries) in sparse.iter().enumerate() {
                let ukj = u[(k, j)];
                if ukj != 0.0 {
                    for &(i, v) in entries {
                        col[i] += v * ukj;
                    }
                }
            }
        }
    } else {
        let mut pd = p.clone();
        for (k, &s) in scale.iter().enumerate() {
            pd.column_mut(k).scale_mut(s);
        }
        let lhs = MatRef::from_column_major_slice(pd.as_slice(), rows, n);
        let dst = faer::MatMut::from_column_major_slice_mut(out.as_mut_slice(), rows, cols);
        faer::linalg::matmul::matmul(dst, faer::Accum::Replace, lhs, u, 1.0, Par::Seq);
    }
    out
}
