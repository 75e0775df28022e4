//! The eigendecomposition shared by the modes, the automatic frequency grid, the time
//! horizon and the sensitivities: eigenvalues sorted by (re, im), condition numbers, and the
//! eigenvectors kept in faer's packed real form until a caller asks for them.
//!
//! faer returns the eigenvectors of a real matrix packed in real storage: a real eigenvalue
//! `λ_j` has its vector in column `j`; a complex pair `(λ_j, λ_{j+1} = conj λ_j)` with
//! `Im λ_j > 0` has `x_j = u_j + i u_{j+1}` and `x_{j+1} = conj x_j`. Keeping that form
//! halves the memory of the vectors and lets products such as `phys · X` run as one real
//! matrix product (or a sparse one) instead of n complex matrix–vector products.
//!
//! Structural zero eigenvalues (see `deflate`) are deflated exactly before the eigensolve;
//! when there are any, the vectors of the kept block are lifted to the whole matrix and kept
//! as dense complex columns (such models are small: the packed form only matters for large
//! ones).

use faer::diag::DiagMut;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::evd_real;
use faer::{Mat, MatRef};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::deflate;
use crate::linalg::balance_in_place;
use crate::statespace::check_finite;
use crate::{ConvergenceError, DimensionError, NumError};

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

/// Eigenvalues, condition numbers and eigenvectors of a real matrix.
pub(crate) struct Eigen {
    /// Eigenvalues sorted by (re, im).
    pub values: Vec<Complex64>,
    /// Eigenvalue condition numbers κᵢ (computed on the balanced matrix), in sorted order.
    pub condition: Vec<f64>,
    /// Frobenius norm of the balanced matrix.
    pub norm: f64,
    vectors: Vectors,
}

/// The eigenvectors, packed (no deflation) or dense (lifted from a deflated block).
enum Vectors {
    Packed {
        /// Packed right eigenvectors of the balanced matrix (n × n).
        right: Mat<f64>,
        /// Packed left eigenvectors of the balanced matrix (n × n, or 0 × 0 when not kept).
        left: Mat<f64>,
        /// The balancing `A = D Ã D⁻¹`.
        scale: Vec<f64>,
        /// Sorted index → packed column.
        slots: Vec<Slot>,
    },
    Dense {
        /// Right eigenvectors, original coordinates, unit 2-norm, sorted order.
        right: DMatrix<Complex64>,
        /// Left eigenvectors likewise (0 × 0 when not kept).
        left: DMatrix<Complex64>,
    },
}

/// Bytes of the dense matrices [`eigen_full`] allocates for an n × n matrix (the balanced
/// copy, the packed vectors, faer's scratch), for predicting memory use.
pub(crate) fn eigen_bytes(n: usize) -> usize {
    8 * n * n * 4
}

/// Eigenvalues, condition numbers and eigenvectors of `a` (balanced first if asked), with the
/// structural zero eigenvalues deflated first (see `deflate`): their vectors are unit vectors
/// of the states found, their condition numbers 1/ε (they may be defective: a sensitivity is
/// not defined for them). The left eigenvectors are kept for [`Eigen::left`] only when
/// `keep_left`.
pub(crate) fn eigen_full(
    a: &DMatrix<f64>,
    balance: bool,
    keep_left: bool,
) -> Result<Eigen, NumError> {
    if a.nrows() != a.ncols() {
        return Err(NumError::Dimension(DimensionError::NotSquare {
            matrix: "A",
            rows: a.nrows(),
            cols: a.ncols(),
        }));
    }
    check_finite(a, "A")?;
    let n = a.nrows();
    let mut t = a.clone();
    let (mut removed, mut order, mut combos, mut keys) = (vec![false; n], vec![], vec![], vec![]);
    deflate::deflate_in_place(
        t.as_mut_slice(),
        n,
        &mut removed,
        &mut order,
        &mut combos,
        &mut keys,
    );
    if order.is_empty() {
        drop(t);
        return eigen_packed(a, balance, keep_left);
    }
    crate::budget::check("the eigenvectors", crate::budget::product(&[n, n, 16 * 4]))?;
    let kept: Vec<usize> = (0..n).filter(|&i| !removed[i]).collect();
    let sub = DMatrix::from_fn(kept.len(), kept.len(), |i, j| t[(kept[i], kept[j])]);
    let e = eigen_packed(&sub, balance, true)?;
    let mut e = lift(&t, e, &kept, &order);
    undo_combinations(&mut e, &combos);
    if !keep_left && let Vectors::Dense { left, .. } = &mut e.vectors {
        *left = DMatrix::zeros(0, 0);
    }
    Ok(e)
}

/// [`eigen_full`] without the deflation: faer's packed vectors kept as they are.
fn eigen_packed(a: &DMatrix<f64>, balance: bool, keep_left: bool) -> Result<Eigen, NumError> {
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
        let par = crate::linalg::par(n);
        let mut buf = MemBuffer::new(crate::modes::eig_scratch(n, true, par));
        evd_real(
            MatRef::from_column_major_slice(&ab, n, n),
            DiagMut::from_slice_mut(&mut re),
            DiagMut::from_slice_mut(&mut im),
            Some(ul.as_mut()),
            Some(ur.as_mut()),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|_| {
            NumError::NoConvergence(ConvergenceError::Factorisation {
                step: "eigenvalues and eigenvectors",
                rows: n,
                cols: n,
                object: "matrix",
            })
        })?;
    }
    let norm = crate::linalg::frobenius_norm(ab.as_slice());
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
        vectors: Vectors::Packed {
            right: ur,
            left: if keep_left { ul } else { Mat::zeros(0, 0) },
            scale,
            slots: order.iter().map(|&k| slots[k]).collect(),
        },
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

    /// Packed vectors unpacked into unit columns in original coordinates.
    fn unit_columns(m: &Mat<f64>, scale: &[f64], slots: &[Slot], left: bool) -> DMatrix<Complex64> {
        let n = slots.len();
        let mut out = DMatrix::<Complex64>::zeros(n, n);
        for (k, &slot) in slots.iter().enumerate() {
            let mut col = out.column_mut(k);
            for i in 0..n {
                let f = if left { 1.0 / scale[i] } else { scale[i] };
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
        match &self.vectors {
            Vectors::Packed {
                right,
                scale,
                slots,
                ..
            } => Self::unit_columns(right, scale, slots, false),
            Vectors::Dense { right, .. } => right.clone(),
        }
    }

    /// Left eigenvectors (columns `y` with `yᴴA = λyᴴ`, original coordinates, unit 2-norm),
    /// in sorted order. Empty unless [`eigen_full`] was asked to keep them.
    pub fn left(&self) -> DMatrix<Complex64> {
        match &self.vectors {
            Vectors::Packed {
                left, scale, slots, ..
            } if left.nrows() == slots.len() => Self::unit_columns(left, scale, slots, true),
            Vectors::Packed { .. } => DMatrix::zeros(0, 0),
            Vectors::Dense { left, .. } => left.clone(),
        }
    }

    /// Componentwise condition number `|y|ᵀ|A||x| / |yᴴx|` of every sorted eigenvalue (x, y
    /// its right and left eigenvectors): to first order, `ε` times it bounds how far the
    /// eigenvalue moves when every entry of `a` is rounded (perturbed by at most `ε` of
    /// itself), as assembling the model in floating point does. 0 for an exact zero (a
    /// structural zero, exact by construction); `None` when the left vectors were not kept
    /// or the vectors would exceed the memory budget. The cost beyond the vectors is one
    /// pass over the nonzero entries of `a` per eigenvalue.
    pub fn componentwise(&self, a: &DMatrix<f64>) -> Option<Vec<f64>> {
        let n = self.len();
        crate::budget::check(
            "the accuracy estimates",
            crate::budget::product(&[n, n, 16 * 2 + 8]),
        )
        .ok()?;
        let (right, left) = (self.right(), self.left());
        if left.ncols() != n || right.ncols() != n {
            return None;
        }
        // |A| |X|, over the nonzero entries of A only (state matrices are sparse).
        let mut ax = DMatrix::<f64>::zeros(n, n);
        for j in 0..n {
            for i in 0..n {
                let aij = a[(i, j)].abs();
                if aij != 0.0 {
                    for k in 0..n {
                        ax[(i, k)] += aij * right[(j, k)].norm();
                    }
                }
            }
        }
        Some(
            (0..n)
                .map(|k| {
                    if self.values[k] == Complex64::new(0.0, 0.0) {
                        return 0.0;
                    }
                    let num: f64 = (0..n).map(|i| left[(i, k)].norm() * ax[(i, k)]).sum();
                    let den = left.column(k).dotc(&right.column(k)).norm();
                    if den > 0.0 { num / den } else { f64::INFINITY }
                })
                .collect(),
        )
    }

    /// `P · x_k` for every sorted eigenvalue k (x_k a right eigenvector in original
    /// coordinates, not normalised), for a real `P` with one column per state: one real
    /// product with the packed vectors, sparse when `P` is (a map to body coordinates usually
    /// is), then unpacked. Returns one vector per eigenvalue.
    pub fn map_right(&self, p: &DMatrix<f64>) -> Vec<DVector<Complex64>> {
        let rows = p.nrows();
        debug_assert_eq!(p.ncols(), self.len());
        match &self.vectors {
            Vectors::Packed {
                right,
                scale,
                slots,
                ..
            } => {
                let prod = scaled_product(p, scale, right.as_ref());
                slots
                    .iter()
                    .map(|&slot| {
                        DVector::from_fn(rows, |i, _| Self::packed(|r, c| prod[(r, c)], slot, i))
                    })
                    .collect()
            }
            Vectors::Dense { right, .. } => {
                let prod = p.map(|x| Complex64::new(x, 0.0)) * right;
                (0..self.len())
                    .map(|k| prod.column(k).clone_owned())
                    .collect()
            }
        }
    }

    /// Reorders the eigenvalues and their vectors: entry k becomes old entry `perm[k]`.
    fn permute(&mut self, perm: &[usize]) {
        self.values = perm.iter().map(|&k| self.values[k]).collect();
        self.condition = perm.iter().map(|&k| self.condition[k]).collect();
        match &mut self.vectors {
            Vectors::Packed { slots, .. } => *slots = perm.iter().map(|&k| slots[k]).collect(),
            Vectors::Dense { right, left } => {
                let n = perm.len();
                *right = DMatrix::from_fn(n, n, |i, j| right[(i, perm[j])]);
                if left.ncols() == n {
                    *left = DMatrix::from_fn(n, n, |i, j| left[(i, perm[j])]);
                }
            }
        }
    }

    /// Where `a` (the matrix decomposed) shows fewer exact structural zeros than `k` are
    /// known, the other eigenvalues from the orthogonally deflated matrix
    /// ([`deflate::deflate_null_directions`]), matched to the decomposition's, and the `k`
    /// nearest zero set to exactly zero (flagged as not simple).
    pub fn known_zeros(&mut self, a: &DMatrix<f64>, k: usize) -> Result<(), NumError> {
        let zero = Complex64::new(0.0, 0.0);
        let exact = self.values.iter().filter(|v| **v == zero).count();
        if k == 0 || exact >= k || k > a.nrows() {
            return Ok(());
        }
        let Some(rest) = deflate::deflate_null_directions(a, k) else {
            return Ok(());
        };
        // Values and condition numbers both from the deflated matrix: in the full one the
        // structural zeros, split by rounding, make every eigenvalue near them look
        // ill-conditioned (a small simple pole such as a bicycle's capsize would be taken for
        // zero).
        let deflated = eigen_packed(&rest, true, true)?;
        let mut others: Vec<(Complex64, f64)> = deflated
            .values
            .into_iter()
            .zip(deflated.condition)
            .collect();
        let n = self.len();
        let mut by_size: Vec<usize> = (0..n).collect();
        by_size.sort_by(|&x, &y| self.values[x].norm().total_cmp(&self.values[y].norm()));
        let mut free = vec![true; n];
        for &z in by_size.iter().take(k) {
            self.values[z] = zero;
            self.condition[z] = 1.0 / f64::EPSILON;
            free[z] = false;
        }
        // Each remaining eigenvalue takes the nearest deflated one.
        for i in (0..n).filter(|&i| free[i]) {
            let Some((j, _)) = others.iter().enumerate().min_by(|x, y| {
                (x.1.0 - self.values[i])
                    .norm()
                    .total_cmp(&(y.1.0 - self.values[i]).norm())
            }) else {
                break;
            };
            (self.values[i], self.condition[i]) = others.swap_remove(j);
        }
        let mut perm: Vec<usize> = (0..n).collect();
        perm.sort_by(|&x, &y| cmp_re_im(&self.values[x], &self.values[y]));
        self.permute(&perm);
        Ok(())
    }
}

/// The decomposition of the kept block extended to the whole (transformed) matrix `a`: the
/// rows of the removed states from `λ x_r = Σ a_rj x_j` (last found first), unit vectors
/// for the structural zeros.
fn lift(a: &DMatrix<f64>, e: Eigen, kept: &[usize], order: &[usize]) -> Eigen {
    let n = a.nrows();
    let zero = Complex64::new(0.0, 0.0);
    let (sub_right, sub_left) = (e.right(), e.left());
    let mut right = DMatrix::<Complex64>::zeros(n, n);
    let mut left = DMatrix::<Complex64>::zeros(n, n);
    let mut values = Vec::with_capacity(n);
    let mut condition = Vec::with_capacity(n);
    for k in 0..kept.len() {
        let lambda = e.values[k];
        for (i, &ki) in kept.iter().enumerate() {
            right[(ki, k)] = sub_right[(i, k)];
            left[(ki, k)] = sub_left[(i, k)];
        }
        if lambda != zero {
            for &r in order.iter().rev() {
                let s: Complex64 = (0..n).map(|j| right[(j, k)] * a[(r, j)]).sum();
                right[(r, k)] = s / lambda;
            }
        }
        let nn = right.column(k).norm();
        if nn > 0.0 {
            right.column_mut(k).unscale_mut(nn);
        }
        values.push(lambda);
        condition.push(e.condition[k]);
    }
    for (t, &r) in order.iter().enumerate() {
        let k = kept.len() + t;
        right[(r, k)] = Complex64::new(1.0, 0.0);
        left[(r, k)] = Complex64::new(1.0, 0.0);
        values.push(zero);
        condition.push(1.0 / f64::EPSILON);
    }
    let mut out = Eigen {
        values,
        condition,
        norm: e.norm,
        vectors: Vectors::Dense { right, left },
    };
    let mut perm: Vec<usize> = (0..n).collect();
    perm.sort_by(|&x, &y| cmp_re_im(&out.values[x], &out.values[y]));
    out.permute(&perm);
    out
}

/// Vectors of the transformed matrix back to the original coordinates: `x = T x̃`,
/// `y = T⁻ᴴ ỹ` for each change of coordinates, last first.
fn undo_combinations(e: &mut Eigen, combos: &[deflate::Combine]) {
    let Vectors::Dense { right, left } = &mut e.vectors else {
        return;
    };
    if combos.is_empty() {
        return;
    }
    for k in 0..right.ncols() {
        for c in combos.iter().rev() {
            let xi = right[(c.i, k)];
            right[(c.j, k)] -= xi * c.s;
            let yj = left[(c.j, k)];
            left[(c.i, k)] += yj * c.s;
        }
        for m in [&mut *right, &mut *left] {
            let nn = m.column(k).norm();
            if nn > 0.0 {
                m.column_mut(k).unscale_mut(nn);
            }
        }
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
        let par = crate::linalg::par(rows.max(n));
        faer::linalg::matmul::matmul(dst, faer::Accum::Replace, lhs, u, 1.0, par);
    }
    out
}
