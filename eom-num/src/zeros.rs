//! Transmission (invariant) zeros of `(A, B, C, D)`, square or not.
//!
//! # Algorithm (Emami-Naeini & Van Dooren, Automatica 18(4), 1982)
//!
//! The zeros are the values of λ where the system pencil `[A − λI, B; C, D]` loses rank
//! below its normal rank. Orthogonal reductions remove the parts of the pencil that do not
//! depend on λ, without changing its zeros:
//!
//! 1. `reduce`: compress the rows of `D` (SVD); the outputs with zero feedthrough `C₂`
//!    force `C₂ x = 0`. Compress `C₂`'s columns so that `C₂ V = [C₂₂ 0]` with `C₂₂` of full
//!    column rank ρ (`V` as Householder reflectors in compact WY form followed by the SVD of
//!    the small triangular factor, never formed: O(n²ρ) per step): the first ρ (rotated)
//!    states are zero on the zero directions, their state equations become new "outputs"
//!    `A₁₂ x₂ + B₁ u = 0`. Repeat until `D` has full row rank (rows of `[C₂ D₂]` that are
//!    entirely zero are dropped).
//! 2. The same on the dual (transposed) system, after which `D` is square and invertible.
//! 3. Compress the columns of `[C D]`: with `W₁` an orthonormal basis of its null space,
//!    the zeros are the generalized eigenvalues of `([A B] W₁, [I 0] W₁)`, computed by
//!    faer's QZ — or, when `B_f = [I 0] W₁` is well conditioned (σ_min ≥ 1e-2, known exactly
//!    from an r × r block, see `final_pencil`), as the eigenvalues of `B_f⁻¹ A_f` by the
//!    blocked standard eigensolver, much faster on large pencils.
//!
//! All rank decisions use one tolerance `tol = max(rtol · ‖[A B; C D]‖_F, atol)` (balanced
//! states, default `rtol = 1000 · max(n, m, p) · ε`), and are reported with their gaps.
//!
//! # Infinite eigenvalues
//!
//! After the reductions the pencil has only finite eigenvalues in exact arithmetic; an
//! eigenvalue `α/β` of the computed pencil is still declared infinite when
//! `|β| ≤ infinite_rtol · ‖B_f‖_F` — β is then below the backward error of the QZ step and
//! its sign and size carry no information. This replaces EoM.jl's absolute `|z| < 1e9`
//! cut-off, which depends on the units of the model.

use faer::Spec;
use faer::dyn_stack::{MemBuffer, MemStack};
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use crate::error::{Bound, ConvergenceError, NumError, OptionError, SingularError};
use crate::minreal::staircase::compress;
use crate::minreal::{
    MinrealOptions, RankDecision, RankStage, apply_scaling, balance_states, cser, sort_complex,
    svd_full,
};
use crate::statespace::StateSpace;

/// Options of [`transmission_zeros_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct ZerosOptions {
    /// Relative rank tolerance; `None` uses `1000 · max(n, m, p) · ε`.
    pub rtol: Option<f64>,
    /// Absolute floor of the rank tolerance (default 0).
    pub atol: f64,
    /// Balance the states first (exact power-of-two similarity; default `true`). Zeros are
    /// invariant under it.
    pub balance: bool,
    /// Relative threshold on β of the reduced pencil below which an eigenvalue counts as
    /// infinite; `None` uses the rank tolerance `rtol`.
    pub infinite_rtol: Option<f64>,
}

impl Default for ZerosOptions {
    fn default() -> Self {
        ZerosOptions {
            rtol: None,
            atol: 0.0,
            balance: true,
            infinite_rtol: None,
        }
    }
}

/// Result of [`transmission_zeros_with`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ZerosReport {
    /// The finite zeros, sorted by (re, im).
    #[serde(serialize_with = "cser::many")]
    pub zeros: Vec<Complex64>,
    /// Eigenvalues of the reduced pencil judged infinite and dropped (0 unless a rank
    /// decision on the feedthrough was close to the tolerance).
    pub infinite: usize,
    /// Order of the reduced regular pencil.
    pub reduced_order: usize,
    /// Every rank decision of the reductions.
    pub decisions: Vec<RankDecision>,
    /// The absolute rank tolerance used.
    pub tolerance: f64,
    /// The absolute threshold on |β| below which an eigenvalue was declared infinite.
    pub infinite_tolerance: f64,
    /// Smallest |β| / ‖B_f‖_F among the kept eigenvalues (1 when none): how far the finite
    /// zeros are from being declared infinite. When the zeros come from the standard
    /// eigenproblem of a well-conditioned `B_f` (see the module documentation), the lower
    /// bound σ_min(B_f) / ‖B_f‖_F of that.
    pub smallest_beta: f64,
    /// State scaling applied by balancing.
    pub scaling: Vec<f64>,
}

/// Transmission zeros of `ss`, sorted by (re, im), with default options (see the module
/// documentation).
///
/// Errors: [`NumError::Dimension`] / [`NumError::NonFinite`] for a malformed model,
/// [`NumError::NoConvergence`] if an SVD or the QZ iteration fails.
pub fn transmission_zeros(ss: &StateSpace<f64>) -> Result<Vec<Complex64>, NumError> {
    Ok(transmission_zeros_with(ss, &ZerosOptions::default())?.zeros)
}

/// Transmission zeros of `ss` with explicit options, and the report of the rank decisions.
///
/// Errors: as [`transmission_zeros`], plus [`NumError::InvalidOption`] for bad options.
pub fn transmission_zeros_with(
    ss: &StateSpace<f64>,
    opts: &ZerosOptions,
) -> Result<ZerosReport, NumError> {
    ss.validate()?;
    for (v, name) in [
        (opts.rtol, "ZerosOptions.rtol"),
        (Some(opts.atol), "ZerosOptions.atol"),
        (opts.infinite_rtol, "ZerosOptions.infinite_rtol"),
    ] {
        if let Some(v) = v
            && !(v.is_finite() && v >= 0.0)
        {
            return Err(NumError::InvalidOption(OptionError::Tolerance {
                option: name,
                value: v,
                must: Bound::FiniteNonNegative,
            }));
        }
    }
    let (n, m, p) = (ss.states(), ss.inputs(), ss.outputs());
    let rtol = opts
        .rtol
        .unwrap_or_else(|| MinrealOptions::default_rtol(n, m, p));
    let mut a = ss.a.clone();
    let mut b = ss.b.clone();
    let mut c = ss.c.clone();
    let d = ss.d.clone();
    let scaling = if opts.balance {
        balance_states(&a, &b, &c)
    } else {
        vec![1.0; n]
    };
    apply_scaling(&scaling, &mut a, &mut b, &mut c);
    let norm = (a.norm_squared() + b.norm_squared() + c.norm_squared() + d.norm_squared()).sqrt();
    let tol = (rtol * norm).max(opts.atol);

    let mut decisions = Vec::new();
    let sys = reduce((a, b, c, d), tol, false, &mut decisions)?;
    let dual = (
        sys.0.transpose(),
        sys.2.transpose(),
        sys.1.transpose(),
        sys.3.transpose(),
    );
    let dual = reduce(dual, tol, true, &mut decisions)?;
    let (a, b, c, d) = (
        dual.0.transpose(),
        dual.2.transpose(),
        dual.1.transpose(),
        dual.3.transpose(),
    );
    let nf = a.nrows();
    let r = d.nrows();
    let inf_tol_rel = opts.infinite_rtol.unwrap_or(rtol);
    if nf == 0 {
        return Ok(ZerosReport {
            zeros: Vec::new(),
            infinite: 0,
            reduced_order: 0,
            decisions,
            tolerance: tol,
            infinite_tolerance: 0.0,
            smallest_beta: 1.0,
            scaling,
        });
    }
    if d.ncols() != r {
        // Cannot happen with consistent rank decisions (see the module documentation).
        return Err(NumError::Singular(SingularError::FeedthroughNotSquare {
            rows: r,
            cols: d.ncols(),
        }));
    }
    let (af, bf, bf_sigma_min) = final_pencil(&a, &b, &c, &d, tol, &mut decisions)?;
    let bnorm = bf.norm();
    let inf_tol = inf_tol_rel * bnorm;
    let mut zeros = Vec::with_capacity(nf);
    let mut infinite = 0;
    let mut smallest_beta = 1.0f64;
    if bf_sigma_min >= STANDARD_SIGMA_MIN {
        // Every |β| of the generalized Schur form is at least σ_min(B_f): a lower bound.
        smallest_beta = bf_sigma_min / bnorm;
        zeros = standard_eigenvalues(&af, &bf)?;
    } else {
        let (alpha, beta) = qz_eigenvalues(&af, &bf)?;
        for (al, be) in alpha.iter().zip(beta.iter()) {
            if be.abs() <= inf_tol {
                infinite += 1;
            } else {
                smallest_beta = smallest_beta.min(be.abs() / bnorm);
                zeros.push(al / be);
            }
        }
    }
    sort_complex(&mut zeros);
    Ok(ZerosReport {
        zeros,
        infinite,
        reduced_order: nf,
        decisions,
        tolerance: tol,
        infinite_tolerance: inf_tol,
        smallest_beta,
        scaling,
    })
}

/// Smallest singular value of `B_f` above which the zeros are the eigenvalues of
/// `B_f⁻¹ A_f` (κ₂(B_f) ≤ 100: at most two digits more of rounding than the QZ step, which
/// the blocked standard eigensolver saves many times over in time on large pencils).
const STANDARD_SIGMA_MIN: f64 = 1e-2;

/// The regular pencil `(A_f, B_f) = ([A B] W₁, [I 0] W₁)` with `W₁` an orthonormal basis of
/// the null space of `[C D]` (r × (nf + r), full row rank r), and `σ_min(B_f)`.
///
/// `W = [W₀ W₁]` is the rotation that compresses the columns of `[C D]` (Householder
/// reflectors in compact WY form, never formed). `B_f` is the nf × nf block of `W` at rows
/// `0..nf`, columns `r..`; by the CS decomposition of the orthogonal `W`, its singular values
/// are 1 except r of them, which equal those of the complementary r × r block (rows `nf..`,
/// columns `..r`): σ_min(B_f) from an r × r SVD.
fn final_pencil(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: f64,
    decisions: &mut Vec<RankDecision>,
) -> Result<(DMatrix<f64>, DMatrix<f64>, f64), NumError> {
    let (nf, r) = (a.nrows(), d.nrows());
    if r == 0 {
        return Ok((a.clone(), DMatrix::identity(nf, nf), 1.0));
    }
    let mut cd = DMatrix::zeros(r, nf + r);
    cd.columns_mut(0, nf).copy_from(c);
    cd.columns_mut(nf, r).copy_from(d);
    let (refl, s) = compress(cd.transpose(), 0)?;
    let dec = RankDecision::new(RankStage::FinalCompression, 0, r, nf + r, s, tol);
    let rank = dec.rank;
    decisions.push(dec);
    if rank != r {
        return Err(NumError::Singular(SingularError::ZeroPencilRank {
            rank,
            rows: r,
        }));
    }
    let mut ab = DMatrix::zeros(nf, nf + r);
    ab.columns_mut(0, nf).copy_from(a);
    ab.columns_mut(nf, r).copy_from(b);
    refl.apply_right(&mut ab);
    let mut i0 = DMatrix::zeros(nf + r, nf + r);
    i0.fill_with_identity();
    refl.apply_right(&mut i0);
    let bf = i0.view((0, r), (nf, nf)).clone_owned();
    let corner = i0.view((nf, 0), (r, r)).clone_owned();
    let (_, sv, _) = svd_full(&corner)?;
    let sigma_min = sv.iter().copied().fold(1.0f64, f64::min);
    Ok((ab.columns(r, nf).clone_owned(), bf, sigma_min))
}

/// Eigenvalues of `B⁻¹ A` (B well conditioned), by an LU solve and the standard eigensolver.
fn standard_eigenvalues(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Result<Vec<Complex64>, NumError> {
    let n = a.nrows();
    let lu = crate::linalg::faer_view(b).partial_piv_lu();
    let x = faer::linalg::solvers::Solve::solve(&lu, crate::linalg::faer_view(a));
    let m = DMatrix::from_fn(n, n, |i, j| x[(i, j)]);
    if m.iter().any(|v| !v.is_finite()) {
        return Err(NumError::Singular(SingularError::ZeroPencilSolve { n }));
    }
    crate::modes::eigenvalues(&m)
}

type System = (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, DMatrix<f64>);

/// The `reduce` procedure: returns a system with the same zeros and `D` of full row rank.
fn reduce(
    sys: System,
    tol: f64,
    dual: bool,
    decisions: &mut Vec<RankDecision>,
) -> Result<System, NumError> {
    let (mut a, mut b, mut c, mut d) = sys;
    let mut step = 0;
    loop {
        let (n, m, p) = (a.nrows(), b.ncols(), c.nrows());
        if p == 0 {
            return Ok((a, b, c, d));
        }
        // Row compression of D: W D = [D₁; 0].
        let sigma = if m == 0 {
            0
        } else {
            let (u, s, _) = svd_full(&d)?;
            let dec = RankDecision::new(RankStage::Feedthrough { dual }, step, p, m, s, tol);
            let sigma = dec.rank;
            decisions.push(dec);
            let ut = u.transpose();
            d = &ut * d;
            c = &ut * c;
            d.rows_mut(sigma, p - sigma).fill(0.0);
            sigma
        };
        if sigma == p {
            return Ok((a, b, c, d));
        }
        // Column compression of C₂ by Householder reflectors: C₂ V = [C₂₂ 0] with the range
        // in the first ρ rotated states (V never formed).
        let c2 = c.rows(sigma, p - sigma).clone_owned();
        let (refl, rho) = if n == 0 {
            (None, 0)
        } else {
            let (refl, s) = compress(c2.transpose(), 0)?;
            let dec = RankDecision::new(RankStage::OutputRows { dual }, step, p - sigma, n, s, tol);
            let rho = dec.rank;
            decisions.push(dec);
            (Some(refl), rho)
        };
        let Some(refl) = refl.filter(|_| rho > 0) else {
            // The remaining rows of [C D] are zero: they do not constrain the pencil.
            c = c.rows(0, sigma).clone_owned();
            d = d.rows(0, sigma).clone_owned();
            return Ok((a, b, c, d));
        };
        // The range states become the new "outputs": their state equations must vanish.
        let k = n - rho;
        refl.apply_left_t(&mut a, 0);
        refl.apply_right(&mut a);
        refl.apply_left_t(&mut b, 0);
        let mut c1 = c.rows(0, sigma).clone_owned();
        refl.apply_right(&mut c1);
        let mut cn = DMatrix::zeros(rho + sigma, k);
        cn.rows_mut(0, rho).copy_from(&a.view((0, rho), (rho, k)));
        cn.rows_mut(rho, sigma).copy_from(&c1.columns(rho, k));
        let mut dn = DMatrix::zeros(rho + sigma, m);
        dn.rows_mut(0, rho).copy_from(&b.rows(0, rho));
        dn.rows_mut(rho, sigma).copy_from(&d.rows(0, sigma));
        a = a.view((rho, rho), (k, k)).clone_owned();
        b = b.rows(rho, k).clone_owned();
        c = cn;
        d = dn;
        step += 1;
    }
}

/// Generalized eigenvalues (α, β) of the real pencil `(A, B)` by faer's QZ, sequentially.
fn qz_eigenvalues(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
) -> Result<(Vec<Complex64>, Vec<f64>), NumError> {
    let n = a.nrows();
    let mut fa = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]);
    let mut fb = faer::Mat::<f64>::from_fn(n, n, |i, j| b[(i, j)]);
    let mut s_re = faer::diag::Diag::<f64>::zeros(n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(n);
    let mut beta = faer::diag::Diag::<f64>::zeros(n);
    let par = crate::linalg::par(n);
    let mut mem = MemBuffer::new(faer::linalg::gevd::gevd_scratch::<f64>(
        n,
        faer::linalg::evd::ComputeEigenvectors::No,
        faer::linalg::evd::ComputeEigenvectors::No,
        par,
        Spec::default(),
    ));
    faer::linalg::gevd::gevd_real(
        fa.as_mut(),
        fb.as_mut(),
        s_re.as_mut(),
        s_im.as_mut(),
        beta.as_mut(),
        None,
        None,
        par,
        MemStack::new(&mut mem),
        Spec::default(),
    )
    .map_err(|e| {
        NumError::NoConvergence(ConvergenceError::ZeroPencilQz {
            n,
            detail: format!("{e:?}"),
        })
    })?;
    // A complex pair occupies two slots; as in faer's own high-level API, the first slot
    // defines it and the second is its conjugate.
    let mut alpha = Vec::with_capacity(n);
    let mut b = Vec::with_capacity(n);
    let mut i = 0;
    while i < n {
        let z = Complex64::new(s_re[i], s_im[i]);
        alpha.push(z);
        b.push(beta[i]);
        if s_im[i] != 0.0 && i + 1 < n {
            alpha.push(z.conj());
            b.push(beta[i]);
            i += 2;
        } else {
            i += 1;
        }
    }
    Ok((alpha, b))
}
