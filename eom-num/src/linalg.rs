//! Dense linear-algebra helpers shared by the analyses: conversions between nalgebra and faer,
//! SVD-based rank and nullspace decisions that report their own margin, equilibration of
//! mixed-unit matrices, condition numbers and eigenvalue balancing.
//!
//! Every rank decision in eom-num goes through [`rank`] or [`nullspace`] (or their
//! equilibrated variants), so that every decision carries the singular values it was made
//! from, the threshold, and the gap `σ_r / σ_{r+1}` across the threshold. A gap close to one
//! means the decision was close and the result should be reported as fragile.
//!
//! faer runs sequentially on matrices below [`PARALLEL_MIN`] rows (threading small
//! factorisations costs more than it saves, and would fight with rayon sweeps over points),
//! in parallel above.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::svd::ComputeSvdVectors;
use faer::{Mat, MatRef, Par};
use nalgebra::{DMatrix, DVector};

use crate::statespace::check_finite;
use crate::{ConvergenceError, NumError, OptionError};

/// Copies an nalgebra matrix into a faer matrix.
pub fn to_faer(m: &DMatrix<f64>) -> Mat<f64> {
    faer_view(m).to_owned()
}

/// A zero-copy faer view of an nalgebra matrix (both store column-major).
pub fn faer_view(m: &DMatrix<f64>) -> MatRef<'_, f64> {
    MatRef::from_column_major_slice(m.as_slice(), m.nrows(), m.ncols())
}

/// Copies a faer matrix (any strides) into an nalgebra matrix.
pub fn from_faer(m: MatRef<'_, f64>) -> DMatrix<f64> {
    DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)])
}

/// Safety factor of the default rank tolerance (see [`RankTolerance::Default`]).
pub const DEFAULT_RANK_SAFETY: f64 = 10.0;

/// How small a singular value must be to count as zero in a rank decision.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum RankTolerance {
    /// `DEFAULT_RANK_SAFETY · max(m, n) · ε · σ_max` (ε = 2.2e-16).
    ///
    /// Why this value: a backward-stable SVD returns singular values with absolute error
    /// about `max(m, n) · ε · σ_max`, and matrices assembled from geometry carry a few ulps of
    /// their own error per entry (sums of products, trigonometric values at the operating
    /// point). A mathematically zero singular value is therefore seen at 1–10 times
    /// `max(m, n) · ε · σ_max`; the factor 10 covers that while staying ~13 orders of
    /// magnitude below `σ_max` for the sizes met here, far below any physical scale
    /// separation. It is deliberately looser than Julia's `min(m, n)` rule and much looser
    /// than the ULP-tight threshold of EoM.jl's `dss2ss`. Mixed units can
    /// still defeat any relative tolerance; equilibrate first ([`rank_equilibrated`]).
    #[default]
    Default,
    /// `r · σ_max` with a caller-chosen relative tolerance `r ≥ 0`.
    Relative(f64),
    /// A fixed absolute threshold `t ≥ 0` (in the units of the matrix).
    Absolute(f64),
}

impl RankTolerance {
    /// The threshold for an `nrows × ncols` matrix with largest singular value `sigma_max`.
    pub fn threshold(&self, sigma_max: f64, nrows: usize, ncols: usize) -> f64 {
        match *self {
            RankTolerance::Default => {
                DEFAULT_RANK_SAFETY * nrows.max(ncols) as f64 * f64::EPSILON * sigma_max
            }
            RankTolerance::Relative(r) => r * sigma_max,
            RankTolerance::Absolute(t) => t,
        }
    }

    /// Checks that an explicit tolerance is finite and non-negative.
    pub fn validate(&self) -> Result<(), NumError> {
        match *self {
            RankTolerance::Default => Ok(()),
            RankTolerance::Relative(v) | RankTolerance::Absolute(v) => {
                if v.is_finite() && v >= 0.0 {
                    Ok(())
                } else {
                    Err(NumError::InvalidOption(OptionError::RankTolerance {
                        tolerance: *self,
                    }))
                }
            }
        }
    }
}

/// A full singular value decomposition `M = U diag(σ) Vᵀ` (σ non-increasing).
#[derive(Clone, Debug, PartialEq)]
pub struct Svd {
    /// Left singular vectors, m × m orthogonal.
    pub u: DMatrix<f64>,
    /// Singular values, `min(m, n)` of them, non-increasing.
    pub singular_values: Vec<f64>,
    /// Right singular vectors, n × n orthogonal.
    pub v: DMatrix<f64>,
}

/// Matrices of at least this many rows (or columns) are factorised with faer's parallel
/// kernels on the threads of the current rayon pool: a model of a thousand bodies then uses
/// every core inside each dense step. Below it the threads cost more than they save (and
/// sweeps of small models parallelise over their points instead).
pub const PARALLEL_MIN: usize = 200;

/// The parallelism of a dense step on matrices of size `n` (see [`PARALLEL_MIN`]).
pub(crate) fn par(n: usize) -> Par {
    if n >= PARALLEL_MIN && rayon::current_num_threads() > 1 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// Full SVD of `m` (faer; in parallel from [`PARALLEL_MIN`] rows or columns).
///
/// Errors: [`NumError::NonFinite`] for NaN/∞ entries, [`NumError::NoConvergence`] if the
/// iteration fails.
pub fn svd(m: &DMatrix<f64>) -> Result<Svd, NumError> {
    check_finite(m, "matrix passed to the SVD")?;
    let (r, c) = m.shape();
    let k = r.min(c);
    let par = par(r.max(c));
    let mut u = Mat::<f64>::zeros(r, r);
    let mut v = Mat::<f64>::zeros(c, c);
    let mut s = faer::diag::Diag::<f64>::zeros(k);
    if k > 0 {
        let req = faer::linalg::svd::svd_scratch::<f64>(
            r,
            c,
            ComputeSvdVectors::Full,
            ComputeSvdVectors::Full,
            par,
            Default::default(),
        );
        let mut buf = MemBuffer::new(req);
        faer::linalg::svd::svd(
            faer_view(m),
            s.as_mut(),
            Some(u.as_mut()),
            Some(v.as_mut()),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|_| {
            NumError::NoConvergence(ConvergenceError::Factorisation {
                step: "SVD",
                rows: r,
                cols: c,
                object: "matrix",
            })
        })?;
    } else {
        // Empty matrix: any orthogonal U, V will do.
        u = Mat::identity(r, r);
        v = Mat::identity(c, c);
    }
    Ok(Svd {
        u: from_faer(u.as_ref()),
        singular_values: s.column_vector().iter().copied().collect(),
        v: from_faer(v.as_ref()),
    })
}

/// Singular values of `m` only (non-increasing).
pub fn singular_values(m: &DMatrix<f64>) -> Result<Vec<f64>, NumError> {
    check_finite(m, "matrix passed to the SVD")?;
    let (r, c) = m.shape();
    let k = r.min(c);
    if k == 0 {
        return Ok(Vec::new());
    }
    let mut s = faer::diag::Diag::<f64>::zeros(k);
    let par = par(r.max(c));
    let req = faer::linalg::svd::svd_scratch::<f64>(
        r,
        c,
        ComputeSvdVectors::No,
        ComputeSvdVectors::No,
        par,
        Default::default(),
    );
    let mut buf = MemBuffer::new(req);
    faer::linalg::svd::svd(
        faer_view(m),
        s.as_mut(),
        None,
        None,
        par,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .map_err(|_| {
        NumError::NoConvergence(ConvergenceError::Factorisation {
            step: "singular values",
            rows: r,
            cols: c,
            object: "matrix",
        })
    })?;
    Ok(s.column_vector().iter().copied().collect())
}

/// A rank decision and how close it was.
#[derive(Clone, Debug, PartialEq)]
pub struct Rank {
    /// Number of singular values strictly above `threshold`.
    pub rank: usize,
    /// All singular values, non-increasing (of the equilibrated matrix when equilibrated).
    pub singular_values: Vec<f64>,
    /// The threshold the singular values were compared with.
    pub threshold: f64,
    /// `σ_r / σ_{r+1}`, the ratio across the decision (≥ 1). A missing neighbour (r = 0 or
    /// full rank) is replaced by the threshold itself, so that a full-rank matrix whose
    /// smallest singular value sits just above the threshold also shows a small gap. `∞`
    /// when the ratio is unbounded (an exact zero below, or a zero matrix).
    pub gap: f64,
    /// `min(σ_r / threshold, threshold / σ_{r+1})` (≥ 1): how far the nearest singular value
    /// is from the threshold, as a factor. `∞` for an exact decision.
    pub margin: f64,
}

impl Rank {
    /// Whether the decision lies within a factor `factor` of the threshold, i.e. whether a
    /// modest change of tolerance (or units) would flip it. Use e.g. `factor = 100`.
    pub fn is_near_tolerance(&self, factor: f64) -> bool {
        self.margin < factor
    }
}

/// A rank decision from given singular values (non-increasing) and a threshold.
pub(crate) fn decide(singular_values: Vec<f64>, threshold: f64) -> Rank {
    let rank = singular_values.iter().filter(|&&s| s > threshold).count();
    let above = if rank == 0 {
        threshold
    } else {
        singular_values[rank - 1]
    };
    let below = if rank == singular_values.len() {
        threshold
    } else {
        singular_values[rank]
    };
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::INFINITY };
    let (gap, margin) = if singular_values.is_empty() || above == 0.0 {
        // Empty or zero matrix: nothing to be close to.
        (f64::INFINITY, f64::INFINITY)
    } else {
        let m1 = if rank == 0 {
            f64::INFINITY
        } else {
            ratio(above, threshold)
        };
        let m2 = if rank == singular_values.len() {
            f64::INFINITY
        } else {
            ratio(threshold, below)
        };
        (ratio(above, below), m1.min(m2))
    };
    Rank {
        rank,
        singular_values,
        threshold,
        gap,
        margin,
    }
}

/// Numerical rank of `m` by SVD with the given tolerance.
///
/// Errors: [`NumError::InvalidOption`] for a negative or non-finite explicit tolerance,
/// [`NumError::NonFinite`], [`NumError::NoConvergence`].
pub fn rank(m: &DMatrix<f64>, tol: RankTolerance) -> Result<Rank, NumError> {
    tol.validate()?;
    let s = singular_values(m)?;
    let smax = s.first().copied().unwrap_or(0.0);
    Ok(decide(s, tol.threshold(smax, m.nrows(), m.ncols())))
}

/// An orthonormal basis of the (right) nullspace of a matrix, with the rank decision that
/// produced it.
#[derive(Clone, Debug, PartialEq)]
pub struct Nullspace {
    /// n × (n − rank), orthonormal columns spanning `{x : M x = 0}`.
    pub basis: DMatrix<f64>,
    /// Numerical rank of M.
    pub rank: usize,
    /// Singular values used for the decision (of the equilibrated matrix when equilibrated).
    pub singular_values: Vec<f64>,
    /// The threshold of the decision.
    pub threshold: f64,
    /// `σ_r / σ_{r+1}` across the decision, see [`Rank::gap`].
    pub gap: f64,
    /// Distance of the nearest singular value from the threshold, see [`Rank::margin`].
    pub margin: f64,
}

impl Nullspace {
    /// The rank decision behind this nullspace.
    pub fn decision(&self) -> Rank {
        Rank {
            rank: self.rank,
            singular_values: self.singular_values.clone(),
            threshold: self.threshold,
            gap: self.gap,
            margin: self.margin,
        }
    }
}

/// Nullspace of `m` by full SVD: the right singular vectors of the singular values at or
/// below the threshold. A matrix with no rows has the whole space as nullspace.
pub fn nullspace(m: &DMatrix<f64>, tol: RankTolerance) -> Result<Nullspace, NumError> {
    tol.validate()?;
    let n = m.ncols();
    let f = svd(m)?;
    let smax = f.singular_values.first().copied().unwrap_or(0.0);
    let d = decide(f.singular_values, tol.threshold(smax, m.nrows(), n));
    let basis = f.v.columns(d.rank, n - d.rank).into_owned();
    Ok(Nullspace {
        basis,
        rank: d.rank,
        singular_values: d.singular_values,
        threshold: d.threshold,
        gap: d.gap,
        margin: d.margin,
    })
}

/// Which sides of a matrix to scale before a rank decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Equilibrate {
    /// Scale rows (equations) only; the nullspace is unchanged by row scaling.
    Rows,
    /// Scale columns (coordinates) only.
    Columns,
    /// Scale rows, then the columns of the row-scaled matrix (the default).
    #[default]
    Both,
}

/// Diagonal scalings: the equilibrated matrix is `diag(rows) · M · diag(cols)`.
///
/// All factors are powers of two, so scaling is exact in floating point.
#[derive(Clone, Debug, PartialEq)]
pub struct Scaling {
    /// Row factors (length m).
    pub rows: DVector<f64>,
    /// Column factors (length n).
    pub cols: DVector<f64>,
}

fn pow2_near(x: f64) -> f64 {
    // Nearest power of two (in log scale), clamped away from overflow.
    let e = x.log2().round().clamp(-1000.0, 1000.0);
    e.exp2()
}

/// Equilibrates `m` so that every nonzero row and/or column has largest magnitude close to
/// one (within a factor of 2), by powers of two.
///
/// The assumption behind equilibration is that each row (equation) and each column
/// (coordinate) is accurate *relative to its own size*, which is what happens when scale
/// differences come from units (translations vs rotations, kN/m vs N·m/rad). Exactly zero
/// rows and columns are left alone. A row that is merely roundoff noise from a cancellation
/// would be scaled up like any other — only the caller knows whether that can happen.
///
/// Algorithm: divide each row by its largest magnitude (rounded to a power of two); for
/// [`Equilibrate::Both`], then divide each column of the result by its largest magnitude.
/// Afterwards the scaled rows (`Rows`) or columns (`Columns`, `Both`) have their largest
/// magnitude in [1/√2, √2], and with `Both` no row maximum exceeds √2.
pub fn equilibrate(
    m: &DMatrix<f64>,
    mode: Equilibrate,
) -> Result<(DMatrix<f64>, Scaling), NumError> {
    check_finite(m, "matrix to equilibrate")?;
    let (r, c) = m.shape();
    let mut s = m.clone();
    let mut rows = DVector::from_element(r, 1.0);
    let mut cols = DVector::from_element(c, 1.0);
    let scale_rows = |s: &mut DMatrix<f64>, rows: &mut DVector<f64>| {
        for i in 0..r {
            let mx = s.row(i).iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if mx > 0.0 {
                let f = pow2_near(1.0 / mx);
                s.row_mut(i).scale_mut(f);
                rows[i] *= f;
            }
        }
    };
    let scale_cols = |s: &mut DMatrix<f64>, cols: &mut DVector<f64>| {
        for j in 0..c {
            let mx = s.column(j).iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if mx > 0.0 {
                let f = pow2_near(1.0 / mx);
                s.column_mut(j).scale_mut(f);
                cols[j] *= f;
            }
        }
    };
    match mode {
        Equilibrate::Rows => scale_rows(&mut s, &mut rows),
        Equilibrate::Columns => scale_cols(&mut s, &mut cols),
        Equilibrate::Both => {
            // Rows first, then columns of the row-scaled matrix (as LAPACK's dgeequ): no
            // column scaling is introduced where rows alone fix the scales.
            scale_rows(&mut s, &mut rows);
            scale_cols(&mut s, &mut cols);
        }
    }
    Ok((s, Scaling { rows, cols }))
}

/// [`rank`] of the equilibrated matrix (rank is invariant under nonsingular diagonal scaling
/// in exact arithmetic; numerically, equilibration removes the dependence on units).
pub fn rank_equilibrated(
    m: &DMatrix<f64>,
    tol: RankTolerance,
    mode: Equilibrate,
) -> Result<Rank, NumError> {
    let (s, _) = equilibrate(m, mode)?;
    rank(&s, tol)
}

/// [`nullspace`] decided on the equilibrated matrix and mapped back: if `M̃ = R M C`, then
/// `M x = 0 ⇔ M̃ (C⁻¹ x) = 0`, so `x = C y` for `y` in the nullspace of `M̃`; the mapped basis
/// is re-orthonormalised (Householder QR). The singular values, threshold and gap are those
/// of the equilibrated matrix.
pub fn nullspace_equilibrated(
    m: &DMatrix<f64>,
    tol: RankTolerance,
    mode: Equilibrate,
) -> Result<Nullspace, NumError> {
    let (s, scaling) = equilibrate(m, mode)?;
    let mut ns = nullspace(&s, tol)?;
    if ns.basis.ncols() > 0 && scaling.cols.iter().any(|&f| f != 1.0) {
        let mut x = ns.basis.clone();
        for (i, mut row) in x.row_iter_mut().enumerate() {
            row.scale_mut(scaling.cols[i]);
        }
        ns.basis = orthonormalize(&x);
    }
    Ok(ns)
}

/// [`nullspace`] (or [`nullspace_equilibrated`] with `equilibrate`) of a matrix that
/// decouples: the columns are grouped by the rows that join them (two columns are in one
/// group when some row has exact nonzeros in both, transitively), and each group's nullspace
/// is found on its own rows, so that every basis vector lies within one group — a column on
/// which no row depends is its own unit vector. One SVD of the whole matrix would return an
/// arbitrary orthonormal basis of the whole nullspace, mixing coordinates that the equations
/// never couple; in such a basis an exact decoupling of the model (in-plane against
/// out-of-plane motion) survives only to rounding, and a minimal realization cannot see it.
///
/// The decision is the same as on the whole matrix: the singular values of a matrix that is
/// block diagonal after permutations are those of its blocks, and the threshold is taken from
/// the largest of them and the whole matrix's size. Row and column equilibration act within
/// the groups, as they would on the whole. The singular values reported are all of them, the
/// zeros of the empty rows and columns included, largest first.
///
/// Errors: as [`nullspace`].
pub fn nullspace_structured(
    m: &DMatrix<f64>,
    tol: RankTolerance,
    equilibrate_with: Option<Equilibrate>,
) -> Result<Nullspace, NumError> {
    tol.validate()?;
    check_finite(m, "matrix passed to the SVD")?;
    let (r, n) = m.shape();
    let groups = column_groups(m);
    if groups.len() <= 1 {
        return match equilibrate_with {
            Some(mode) => nullspace_equilibrated(m, tol, mode),
            None => nullspace(m, tol),
        };
    }
    // Per group: its singular values, the right singular vectors and the column scaling.
    let mut parts = Vec::with_capacity(groups.len());
    for (rows, cols) in &groups {
        let sub = DMatrix::from_fn(rows.len(), cols.len(), |i, j| m[(rows[i], cols[j])]);
        let (sub, scale) = match equilibrate_with {
            Some(mode) => {
                let (e, s) = equilibrate(&sub, mode)?;
                (e, Some(s.cols))
            }
            None => (sub, None),
        };
        let f = if rows.is_empty() {
            Svd {
                u: DMatrix::zeros(0, 0),
                singular_values: Vec::new(),
                v: DMatrix::identity(cols.len(), cols.len()),
            }
        } else {
            svd(&sub)?
        };
        parts.push((f, scale));
    }
    let smax = parts
        .iter()
        .filter_map(|(f, _)| f.singular_values.first().copied())
        .fold(0.0f64, f64::max);
    let threshold = tol.threshold(smax, r, n);
    let mut all: Vec<f64> = parts
        .iter()
        .flat_map(|(f, _)| f.singular_values.iter().copied())
        .collect();
    all.resize(r.min(n), 0.0);
    all.sort_by(|a, b| b.total_cmp(a));
    let d = decide(all, threshold);
    let mut basis = DMatrix::zeros(n, n - d.rank);
    let mut at = 0;
    for ((_, cols), (f, scale)) in groups.iter().zip(&parts) {
        let rank = f.singular_values.iter().filter(|&&s| s > threshold).count();
        let k = cols.len() - rank;
        if k == 0 {
            continue;
        }
        let mut null = f.v.columns(rank, k).into_owned();
        if let Some(sc) = scale.as_ref().filter(|sc| sc.iter().any(|&x| x != 1.0)) {
            for (i, mut row) in null.row_iter_mut().enumerate() {
                row.scale_mut(sc[i]);
            }
            null = orthonormalize(&null);
        }
        for (i, &c) in cols.iter().enumerate() {
            for j in 0..k {
                basis[(c, at + j)] = null[(i, j)];
            }
        }
        at += k;
    }
    debug_assert_eq!(at, n - d.rank);
    Ok(Nullspace {
        basis,
        rank: d.rank,
        singular_values: d.singular_values,
        threshold: d.threshold,
        gap: d.gap,
        margin: d.margin,
    })
}

/// The groups of [`nullspace_structured`]: `(rows, columns)`, in the order of their first
/// column; every nonzero row lies in exactly one group.
pub(crate) fn column_groups(m: &DMatrix<f64>) -> Vec<(Vec<usize>, Vec<usize>)> {
    let (r, n) = m.shape();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut row_first = vec![None; r];
    for (i, first) in row_first.iter_mut().enumerate() {
        let mut cols = (0..n).filter(|&j| m[(i, j)] != 0.0);
        if let Some(j0) = cols.next() {
            *first = Some(j0);
            for j in cols {
                let (a, b) = (root(&mut parent, j0), root(&mut parent, j));
                if a != b {
                    parent[b] = a;
                }
            }
        }
    }
    let mut group_of = vec![usize::MAX; n];
    let mut groups: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
    for j in 0..n {
        let g = root(&mut parent, j);
        if group_of[g] == usize::MAX {
            group_of[g] = groups.len();
            groups.push((Vec::new(), Vec::new()));
        }
        groups[group_of[g]].1.push(j);
    }
    for (i, first) in row_first.into_iter().enumerate() {
        if let Some(j0) = first {
            let g = root(&mut parent, j0);
            groups[group_of[g]].0.push(i);
        }
    }
    groups
}

/// Orthonormal basis of the column space of a full-column-rank matrix.
///
/// Rows (coordinates) may differ in scale by many orders of magnitude after undoing a column
/// equilibration. Plain Householder QR is only normwise stable and would lose the directions
/// carried by the small rows; with the rows sorted by decreasing size and column pivoting it
/// is row-wise backward stable (Cox & Higham, 1998), so each coordinate keeps its own
/// relative accuracy.
pub(crate) fn orthonormalize(x: &DMatrix<f64>) -> DMatrix<f64> {
    let (n, k) = x.shape();
    if k == 0 {
        return x.clone();
    }
    let size = |i: usize| x.row(i).iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| size(b).total_cmp(&size(a)));
    let xp = DMatrix::from_fn(n, k, |i, j| x[(order[i], j)]);
    let q = xp.col_piv_qr().q();
    let mut out = DMatrix::zeros(n, k);
    for (i, &o) in order.iter().enumerate() {
        for j in 0..k {
            out[(o, j)] = q[(i, j)];
        }
    }
    out
}

/// 2-norm condition number `σ_max / σ_min` (∞ if singular, 1 for an empty matrix), from the
/// singular values, so exact up to rounding. For rectangular matrices, σ_min is the
/// `min(m, n)`-th singular value.
pub fn condition_number(m: &DMatrix<f64>) -> Result<f64, NumError> {
    let s = singular_values(m)?;
    match (s.first(), s.last()) {
        (Some(&hi), Some(&lo)) => {
            if hi == 0.0 || lo == 0.0 {
                Ok(f64::INFINITY)
            } else {
                Ok(hi / lo)
            }
        }
        _ => Ok(1.0),
    }
}

/// Largest absolute entry.
pub(crate) fn max_abs(m: &DMatrix<f64>) -> f64 {
    m.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// Below this, a plain sum of squares may have lost entries to underflow (for up to 10¹⁰⁰
/// entries each below `f64::MIN_POSITIVE`, less than ε of it): [`frobenius_norm`] rescales.
const PLAIN_SUM_FLOOR: f64 = 1e-190;

/// The 2-norm of `x` (a matrix's Frobenius norm, given its entries) without overflow or
/// underflow: the squares are summed relative to the largest entry, so entries up to
/// `f64::MAX` give a finite norm (a plain sum of squares overflows from about 1e154).
pub fn frobenius_norm(x: &[f64]) -> f64 {
    // The plain sum of squares first (no division per entry): when it neither overflowed nor
    // came near the underflow range, every square that did underflow contributes less than
    // ε relative to it, and the plain result is as accurate as the scaled one.
    let plain: f64 = x.iter().map(|v| v * v).sum();
    if plain.is_finite() && plain > PLAIN_SUM_FLOOR {
        return plain.sqrt();
    }
    let big = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    big * x.iter().map(|v| (v / big) * (v / big)).sum::<f64>().sqrt()
}

/// Balances a square matrix in place by a diagonal similarity `D⁻¹ A D` (powers of two,
/// Parlett & Reinsch 1969), so that each row and column have comparable norms. Eigenvalues
/// are unchanged; eigenvalue accuracy improves for badly scaled (mixed-unit) matrices.
///
/// `scale` (length n) receives `D`: an eigenvector `x̃` of the balanced matrix maps back to
/// `x = D x̃`. No allocation.
pub fn balance_in_place(a: &mut [f64], n: usize, scale: &mut [f64]) {
    debug_assert_eq!(a.len(), n * n);
    debug_assert_eq!(scale.len(), n);
    scale.iter_mut().for_each(|s| *s = 1.0);
    if n < 2 {
        return;
    }
    const RADIX: f64 = 2.0;
    const MAX_FACTOR: f64 = 1e150;
    let mut converged = false;
    let mut sweeps = 0;
    while !converged && sweeps < 100 {
        converged = true;
        sweeps += 1;
        for i in 0..n {
            // Off-diagonal 1-norms of column i and row i (column-major storage).
            let mut c = 0.0;
            let mut r = 0.0;
            for k in 0..n {
                if k != i {
                    c += a[i * n + k].abs();
                    r += a[k * n + i].abs();
                }
            }
            // A norm that overflowed (entries near f64::MAX) cannot be balanced: with an
            // infinite norm the loops below would never end.
            if c == 0.0 || r == 0.0 || !(c + r).is_finite() {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let (mut cc, mut rr) = (c, r);
            // The factor stays within the exponent range, so the scaled entries stay finite
            // and nonzero.
            while cc < rr / RADIX && f < MAX_FACTOR {
                cc *= RADIX;
                rr /= RADIX;
                f *= RADIX;
            }
            while cc >= rr * RADIX && f > 1.0 / MAX_FACTOR {
                cc /= RADIX;
                rr *= RADIX;
                f /= RADIX;
            }
            if cc + rr < 0.95 * s {
                converged = false;
                scale[i] *= f;
                // Column i times f, row i divided by f.
                for k in 0..n {
                    a[i * n + k] *= f;
                    a[k * n + i] /= f;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balancing_ends_when_a_norm_overflows() {
        // Column 0's off-diagonal norm overflows to ∞ (two entries near f64::MAX).
        let n = 3;
        let mut a = vec![0.0, 1e308, 1e308, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0];
        let mut scale = vec![0.0; n];
        balance_in_place(&mut a, n, &mut scale);
        assert!(a.iter().all(|x| x.is_finite()) && scale.iter().all(|s| *s > 0.0));
        // Extreme but finite: balanced within the exponent range, the product kept.
        let mut b = vec![0.0, 1e-300, 1e300, 0.0];
        balance_in_place(&mut b, 2, &mut scale[..2]);
        assert!(b.iter().all(|x| x.is_finite()), "{b:?}");
        assert!((b[1] * b[2] - 1.0).abs() < 1e-12, "{b:?}");
    }

    #[test]
    fn frobenius_norm_of_huge_and_tiny_entries() {
        assert!((frobenius_norm(&[3e200, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
        assert!((frobenius_norm(&[3e-200, -4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
        assert_eq!(frobenius_norm(&[]), 0.0);
        assert!(frobenius_norm(&[1e308, 1e308]).is_finite());
    }

    #[test]
    fn decide_conventions() {
        let d = decide(vec![3.0, 1e-20], 1e-10);
        assert_eq!(d.rank, 1);
        assert!((d.gap - 3e20).abs() / 3e20 < 1e-12);
        assert!((d.margin - 1e10).abs() / 1e10 < 1e-12);
        let full = decide(vec![3.0, 2e-10], 1e-10);
        assert_eq!(full.rank, 2);
        assert!((full.gap - 2.0).abs() < 1e-12);
        let zero = decide(vec![0.0, 0.0], 0.0);
        assert_eq!(zero.rank, 0);
        assert!(zero.gap.is_infinite());
    }
}
