//! The orthogonal staircase kernel of [`crate::minreal`], in O(n³) for n states.
//!
//! Each step examines one block — the rows of `B` not yet settled (first step), then the
//! columns of `A` added last — and rotates the remaining coordinates so that the block's
//! range comes first. The rotation is built from the block, not as a full square factor of
//! its SVD:
//!
//! 1. Householder QR of the `r × k` block, `X = H [R; 0]` (Golub & Van Loan, *Matrix
//!    Computations*, §5.2), with the reflectors kept in compact WY form `H = I − V T Vᵀ`
//!    (Schreiber & Van Loan 1989).
//! 2. SVD of the small `R = U_R Σ V_Rᵀ`: the singular values of `R` are those of `X`, so the
//!    rank decision is the same as one on `X` itself, and it is reported the same way.
//! 3. The step's rotation is `U = H · diag(U_R, I)`; it is applied to the rows and columns of
//!    `A`, the rows of `B` and the columns of `C` with matrix products of width `k`. The rows
//!    are only updated in the columns the staircase has not yet zeroed.
//!
//! A step costs O(n · r · k), the whole staircase O(n³), instead of the O(n³) per step of a
//! square `U`.
//!
//! **Single-column blocks.** Once a step has rank one, every later block is one column, and
//! the remaining steps are exactly a Hessenberg reduction of the trailing part of `A`: the
//! reflector of a one-column block maps it onto its first row, with norm `|h|`, its only
//! singular value. That tail is done by faer's blocked Hessenberg reduction (matrix-matrix
//! products instead of one reflector at a time), and the rank decisions are read off the new
//! subdiagonal: the first `|h| ≤ tol` ends the staircase and is set to an exact zero. The
//! reductions the blocked routine carries out past that point act only within the removed
//! part, whose eigenvalues they leave unchanged.
//!
//! The orthogonal factor `Q` is not formed unless asked for ([`StaircaseForm::apply_right`],
//! [`StaircaseForm::q`]): a minimal realization that removes nothing never needs it.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::hessenberg::{hessenberg_in_place, hessenberg_in_place_scratch};
use faer::linalg::householder::{
    apply_block_householder_sequence_on_the_right_in_place_scratch,
    apply_block_householder_sequence_on_the_right_in_place_with_conj,
};
use faer::{Conj, Mat, MatMut};
use nalgebra::DMatrix;

use crate::error::NumError;
use crate::minreal::{RankDecision, RankStage, svd_full};

/// One step's rotation of the coordinates `off..`: `U = (I − V T Vᵀ) · diag(rot, I)`.
pub(crate) struct Reflectors {
    pub off: usize,
    /// Householder vectors (r × t, unit first entry, zeros above it).
    pub v: DMatrix<f64>,
    /// Upper triangular factor of the compact WY form (t × t).
    pub t: DMatrix<f64>,
    /// Left singular vectors of the small triangular factor (t × t).
    pub rot: DMatrix<f64>,
}

impl Reflectors {
    /// `M[off.., col0..] ← Uᵀ M[off.., col0..]`.
    pub fn apply_left_t(&self, m: &mut DMatrix<f64>, col0: usize) {
        let (r, w) = (m.nrows() - self.off, m.ncols() - col0);
        if w == 0 || self.v.ncols() == 0 {
            return;
        }
        let mut sub = m.view_mut((self.off, col0), (r, w));
        let vtm = self.v.tr_mul(&sub);
        let y = self.t.tr_mul(&vtm);
        sub.gemm(-1.0, &self.v, &y, 1.0);
        let k = self.rot.nrows();
        let top = self.rot.tr_mul(&sub.rows(0, k));
        sub.rows_mut(0, k).copy_from(&top);
    }

    /// `M[.., off..] ← M[.., off..] U`.
    pub fn apply_right(&self, m: &mut DMatrix<f64>) {
        let (rows, r) = (m.nrows(), m.ncols() - self.off);
        if rows == 0 || self.v.ncols() == 0 {
            return;
        }
        let mut sub = m.view_mut((0, self.off), (rows, r));
        let mv = &sub * &self.v;
        let y = mv * &self.t;
        sub.gemm(-1.0, &y, &self.v.transpose(), 1.0);
        let k = self.rot.nrows();
        let left = sub.columns(0, k) * &self.rot;
        sub.columns_mut(0, k).copy_from(&left);
    }
}

/// The Hessenberg tail from coordinate `p`: `diag(I_{p+1}, Q̃)` with `Q̃` faer's block
/// Householder sequence.
pub(crate) struct HessenbergTail {
    p: usize,
    /// Householder essentials ((n − p − 1) square, strictly lower part used).
    basis: Mat<f64>,
    /// Block factors.
    factor: Mat<f64>,
}

impl HessenbergTail {
    /// `M[.., p+1..] ← M[.., p+1..] Q̃`.
    pub(crate) fn apply_right(&self, m: &mut DMatrix<f64>) {
        let (rows, cols) = m.shape();
        let k = self.basis.nrows();
        if rows == 0 || k == 0 {
            return;
        }
        let bs = self.factor.nrows();
        let mut buf = MemBuffer::new(
            apply_block_householder_sequence_on_the_right_in_place_scratch::<f64>(k, bs, rows),
        );
        let full = MatMut::from_column_major_slice_mut(m.as_mut_slice(), rows, cols);
        apply_block_householder_sequence_on_the_right_in_place_with_conj(
            self.basis.as_ref(),
            self.factor.as_ref(),
            Conj::No,
            full.submatrix_mut(0, self.p + 1, rows, k),
            crate::linalg::par(rows.max(k)),
            MemStack::new(&mut buf),
        );
    }
}

enum Transform {
    Step(Reflectors),
    Tail(HessenbergTail),
}

/// A system in staircase form, `a = Qᵀ A Q`, `b = Qᵀ B`, `c = C Q`, with `Q` kept as the
/// sequence of its factors.
pub(crate) struct StaircaseForm {
    pub a: DMatrix<f64>,
    pub b: DMatrix<f64>,
    pub c: DMatrix<f64>,
    pub blocks: Vec<usize>,
    pub kept: usize,
    pub decisions: Vec<RankDecision>,
    transforms: Vec<Transform>,
}

impl StaircaseForm {
    /// `M ← M Q` for a matrix with one column per state.
    pub fn apply_right(&self, m: &mut DMatrix<f64>) {
        for t in &self.transforms {
            match t {
                Transform::Step(r) => r.apply_right(m),
                Transform::Tail(h) => h.apply_right(m),
            }
        }
    }

    /// The orthogonal factor `Q` (old state = `Q` · new state), formed explicitly.
    pub fn q(&self) -> DMatrix<f64> {
        let n = self.a.nrows();
        let mut q = DMatrix::identity(n, n);
        self.apply_right(&mut q);
        q
    }
}

/// Householder QR of `x` (r × k) in place: returns `V` (r × t), the WY factor `T` (t × t)
/// and leaves `R` in the top `t` rows of `x` (zeros below), with `t = min(r, k)`.
pub(crate) fn householder_qr(x: &mut DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
    let (r, k) = x.shape();
    let t = r.min(k);
    let mut v = DMatrix::<f64>::zeros(r, t);
    let mut tau = vec![0.0; t];
    for j in 0..t {
        let x0 = x[(j, j)];
        let tail2: f64 = x.view((j + 1, j), (r - j - 1, 1)).norm_squared();
        v[(j, j)] = 1.0;
        if tail2 == 0.0 {
            continue; // already reduced: H = I
        }
        let norm = (x0 * x0 + tail2).sqrt();
        let beta = if x0 >= 0.0 { -norm } else { norm };
        let head = x0 - beta;
        tau[j] = (beta - x0) / beta;
        for i in j + 1..r {
            v[(i, j)] = x[(i, j)] / head;
        }
        x[(j, j)] = beta;
        x.view_mut((j + 1, j), (r - j - 1, 1)).fill(0.0);
        // The remaining columns: x ← (I − τ v vᵀ) x.
        for c in j + 1..k {
            let dot: f64 = (j..r).map(|i| v[(i, j)] * x[(i, c)]).sum();
            let s = tau[j] * dot;
            for i in j..r {
                x[(i, c)] -= s * v[(i, j)];
            }
        }
    }
    // T[j, j] = τⱼ, T[..j, j] = −τⱼ T[..j, ..j] V[.., ..j]ᵀ vⱼ.
    let mut tm = DMatrix::<f64>::zeros(t, t);
    for j in 0..t {
        tm[(j, j)] = tau[j];
        if j > 0 && tau[j] != 0.0 {
            let w = v.columns(0, j).tr_mul(&v.column(j));
            let col = tm.view((0, 0), (j, j)) * w * (-tau[j]);
            tm.view_mut((0, j), (j, 1)).copy_from(&col);
        }
    }
    (v, tm)
}

/// The rotation `U = H · diag(U_R, I)` of the rows of `x` (r × k) that puts its range first,
/// ordered by singular value, and the singular values of `x` (those of `R` in `x = H [R; 0]`):
/// `Uᵀ x = [Σ V_Rᵀ; 0]`. The rotation acts on coordinates `off..` of the matrices it is
/// applied to.
pub(crate) fn compress(
    mut x: DMatrix<f64>,
    off: usize,
) -> Result<(Reflectors, Vec<f64>), NumError> {
    let (v, t) = householder_qr(&mut x);
    let k = v.ncols();
    let (rot, s) = if k == 0 {
        (DMatrix::identity(0, 0), Vec::new())
    } else {
        let (u, s, _) = svd_full(&x.rows(0, k).clone_owned())?;
        (u, s)
    };
    Ok((Reflectors { off, v, t, rot }, s))
}

/// Below this many remaining states a single-column tail is finished step by step (the
/// blocked reduction only pays off for larger matrices).
const TAIL_MIN: usize = 16;

/// The controllability staircase of `(a, b, c)` with absolute tolerance `tol` (see the
/// module documentation). Inputs are assumed checked (square `a`, matching sizes, finite).
pub(crate) fn staircase(
    mut a: DMatrix<f64>,
    mut b: DMatrix<f64>,
    mut c: DMatrix<f64>,
    tol: f64,
    stage: RankStage,
) -> Result<StaircaseForm, NumError> {
    let n = a.nrows();
    let mut blocks = Vec::new();
    let mut decisions = Vec::new();
    let mut transforms = Vec::new();
    // Rows [0, off) are settled; the next block is rows off.. of B (first step) or of the
    // columns prev.0..prev.1 of A that were added last.
    let mut off = 0;
    let mut prev = (0, 0);
    let mut step = 0;
    while off < n {
        let r = n - off;
        if step > 0 && prev.1 - prev.0 == 1 && r >= TAIL_MIN {
            let (added, tail) = hessenberg_tail(&mut a, &mut c, prev.0, tol, stage, step)?;
            blocks.extend(std::iter::repeat_n(1, added.0));
            off += added.0;
            decisions.extend(added.1);
            transforms.push(Transform::Tail(tail));
            break;
        }
        let block: DMatrix<f64> = if step == 0 {
            b.rows(off, r).clone_owned()
        } else {
            a.view((off, prev.0), (r, prev.1 - prev.0)).clone_owned()
        };
        let width = block.ncols();
        let (refl, s) = compress(block, off)?;
        let decision = RankDecision::new(stage, step, r, width, s, tol);
        let rank = decision.rank;
        decisions.push(decision);
        if rank > 0 {
            // Rows: columns before prev.0 are zero below the settled rows already.
            refl.apply_left_t(&mut a, prev.0);
            refl.apply_right(&mut a);
            refl.apply_left_t(&mut b, 0);
            refl.apply_right(&mut c);
            transforms.push(Transform::Step(refl));
        }
        // The part of the block below its rank is zero by decision: make it exact.
        if step == 0 {
            b.rows_mut(off + rank, r - rank).fill(0.0);
        } else {
            a.view_mut((off + rank, prev.0), (r - rank, prev.1 - prev.0))
                .fill(0.0);
        }
        if rank == 0 {
            break;
        }
        blocks.push(rank);
        prev = (off, off + rank);
        off += rank;
        step += 1;
    }
    Ok(StaircaseForm {
        a,
        b,
        c,
        blocks,
        kept: off,
        decisions,
        transforms,
    })
}

/// Reduces `a[p.., p..]` to upper Hessenberg form in place by faer's blocked reduction,
/// `a[p.., p..] ← Q̃ᵀ a[p.., p..] Q̃` with zeros below the subdiagonal, and returns `Q̃`
/// (`a` must have at least `p + 2` rows). Only that block is transformed: the caller
/// applies the rotation to the rows above and to the other matrices.
pub(crate) fn hessenberg(a: &mut DMatrix<f64>, p: usize) -> HessenbergTail {
    let n = a.nrows();
    let ns = n - p;
    let k = ns - 1;
    let bs = faer::linalg::qr::no_pivoting::factor::recommended_block_size::<f64>(k, k);
    let mut factor = Mat::<f64>::zeros(bs, k);
    let par = crate::linalg::par(ns);
    let req = StackReq::any_of(&[hessenberg_in_place_scratch::<f64>(
        ns,
        bs,
        par,
        Default::default(),
    )]);
    let mut buf = MemBuffer::new(req);
    {
        let full = MatMut::from_column_major_slice_mut(a.as_mut_slice(), n, n);
        hessenberg_in_place(
            full.submatrix_mut(p, p, ns, ns),
            factor.as_mut(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        );
    }
    // The essentials below the subdiagonal, kept for Q, then cleared.
    let basis = Mat::<f64>::from_fn(k, k, |i, j| if i > j { a[(p + 1 + i, p + j)] } else { 0.0 });
    for j in 0..k {
        a.view_mut((p + j + 2, p + j), (k - j - 1, 1)).fill(0.0);
    }
    HessenbergTail { p, basis, factor }
}

/// Steps with one-column blocks from coordinate `p` on (the last reached state), by the
/// blocked Hessenberg reduction of `a[p.., p..]`. Returns the number of states reached and
/// the decisions, and the transformation.
type TailSteps = (usize, Vec<RankDecision>);

fn hessenberg_tail(
    a: &mut DMatrix<f64>,
    c: &mut DMatrix<f64>,
    p: usize,
    tol: f64,
    stage: RankStage,
    first_step: usize,
) -> Result<(TailSteps, HessenbergTail), NumError> {
    let n = a.nrows();
    let k = n - p - 1;
    let tail = hessenberg(a, p);
    // The rows above and the outputs see the same rotation of the columns p+1...
    let mut above = a.view((0, 0), (p, n)).clone_owned();
    tail.apply_right(&mut above);
    a.view_mut((0, p + 1), (p, k))
        .copy_from(&above.columns(p + 1, k));
    tail.apply_right(c);
    let mut decisions = Vec::new();
    let mut reached = 0;
    for j in 0..k {
        let h = a[(p + j + 1, p + j)];
        let d = RankDecision::new(stage, first_step + j, k - j, 1, vec![h.abs()], tol);
        let rank = d.rank;
        decisions.push(d);
        if rank == 0 {
            a[(p + j + 1, p + j)] = 0.0;
            break;
        }
        reached += 1;
    }
    Ok(((reached, decisions), tail))
}
