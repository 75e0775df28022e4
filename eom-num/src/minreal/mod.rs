//! Minimal realization by orthogonal staircase reduction, with every rank decision and every
//! removed mode reported.
//!
//! # Algorithm
//!
//! 0. Change to the coordinates where the zero eigenvalues the structure proves are exact
//!    ([`crate::deflate::structural_coordinates`]: rounding residues of the elimination in a
//!    column on which nothing depends set to zero, a pair of states that acts only through
//!    its difference combined exactly). Left in, balancing scales such a column up by as much
//!    as 2²³ and its residues become couplings above every tolerance (the bicycle's heading
//!    and lateral position were kept as observable).
//! 1. Optionally balance the states (diagonal similarity by powers of two, exact in floating
//!    point) so that the rows of `[A B]` and the columns of `[A; C]` have comparable norms.
//!    Multibody models mix units (metres and radians, kN/m and N·m/rad); balancing makes the
//!    relative rank tolerance below meaningful for every state.
//! 2. **Structural reduction** ([`crate::reach`]): the states that no input reaches in the
//!    graph of the exact zeros of `(A, B)` are removed by a permutation, exactly, without a
//!    rank decision ([`MinrealReport::structurally_uncontrollable`]), their eigenvalues taken
//!    block by block on the strong components of the removed part. Left to the staircase,
//!    such an exact decoupling becomes a rounding-level coupling that the Krylov sequence
//!    amplifies step by step (15 blocks hanging on strings kept 120 states of 30), and many
//!    identical decoupled bodies cost an O(n³) staircase for nothing.
//! 3. **Controllability staircase** (Van Dooren 1981): an SVD of the input block `B` splits
//!    the state space into the directions `B` reaches (rank decision) and the rest; the
//!    orthogonal basis is applied to `A`, `B`, `C`; the next input block is the part of `A`
//!    that couples the reached directions into the rest, and so on until a block has rank
//!    zero (the remaining states are uncontrollable) or no state is left. The result is
//!    `Qᵀ A Q = [A_c *; 0 A_u]`, `Qᵀ B = [B_c; 0]`.
//! 4. **Cluster PBH pass** (below; [`MinrealOptions::cluster_pbh`]): at every cluster of
//!    eigenvalues of `A_c`, uncontrollable directions the staircase could not see are rotated
//!    out, and the staircase runs again on what is kept, until the pass removes nothing.
//! 5. **Observability**: the structural reduction, the staircase and its PBH pass on the dual
//!    `(A_cᵀ, C_cᵀ, B_cᵀ)` of the controllable part, giving `[A_o 0; * A_ū]`, `[C_o 0]`.
//! 6. The minimal system is `(A_o, B_o, C_o, D)`. Only orthogonal transformations (and exact
//!    power-of-two scalings and permutations) are used, so its transfer function equals the original one to
//!    rounding, apart from the parts below the tolerance that the rank decisions set to zero.
//!
//! # Why a PBH pass: the staircase measures Krylov rank, not distance
//!
//! The staircase decides on the subdiagonal blocks of a (block) Hessenberg form, i.e. on the
//! conditioning of the Krylov sequence `B, AB, A²B, …`. It is backward stable — its result
//! is exact for `A + E`, `‖E‖ ≈ ε‖A‖` — but for `A + E` a subdiagonal need not be small even
//! when the distance to uncontrollability, `min_λ σ_min [A − λI, B]` (Eising 1984), is of
//! the order of `‖E‖` (Paige 1981). The typical case is symmetry: a spatial chain whose
//! motion in x is uncoupled from its motion in y and has exactly the same eigenvalues. Any
//! rounding-level coupling `E` mixes two modes with coincident eigenvalues by O(1), so the
//! Krylov sequence of `A + E` reaches the x motion with O(1) subdiagonals, while the
//! Popov–Belevitch–Hautus test at the shared eigenvalue still shows a singular value of
//! `[A − λI, B]` at rounding level. The staircase remains the right tool for a mode whose
//! eigenvalue no controllable mode shares (Van Dooren 1981); the PBH pass covers the
//! coincident ones.
//!
//! The pass, on the controllable part `(A_c, B_c)` of size k:
//!
//! 1. Eigenvalues of `A_c`, grouped into clusters: eigenvalues within
//!    `cluster_rtol · ‖A‖_F` of each other, transitively; a conjugate pair of clusters is
//!    examined once, a cluster holding its own conjugates at its real mean.
//! 2. At the mean λ of every cluster of `s ≥ 2` eigenvalues: the `s` smallest singular
//!    values σ of `[A_c − λI, B_c]` and their left singular vectors `w` (complex when λ is),
//!    by block inverse iteration on `[A_c − λI, B_c][A_c − λI, B_c]ᴴ` with an LU
//!    factorization that exploits the Hessenberg form the staircase leaves (O(k²) per
//!    cluster for a single input), followed by the SVD of the `s × (k + m)` projection, so
//!    that each σ is the exact residual `‖wᴴ [A_c − λI, B_c]‖` of its `w`.
//! 3. The directions with `σ ≤ tol_c`, at most `s − 1` per cluster (a cluster the staircase
//!    kept holds at least one controllable mode: an uncontrollable one alone at its
//!    eigenvalue would have been found by the staircase), satisfy `wᴴ A_c ≈ λ wᴴ`,
//!    `wᴴ B_c ≈ 0`. The real span `Q2` of their real and imaginary parts is then left
//!    invariant and its orthogonal complement `Q1` is invariant and contains `range(B_c)`:
//!    `Qᵀ A_c Q = [A11 A12; ≈0 A22]`, `Qᵀ B_c = [B1; ≈0]` with `Q = [Q1 Q2]`. The `≈0` blocks
//!    are set to exact zeros, the eigenvalues of `A22` are reported as removed
//!    uncontrollable modes, and `(A11, B1, C_c Q1)` is kept. One rotation serves all the
//!    clusters of a pass.
//! 4. The staircase again on the kept part, then the pass again, until the pass removes
//!    nothing. A defective cluster deflates one Jordan level per pass (its PBH rank drops by
//!    the geometric multiplicity only); the next level is then an eigenvalue alone, which the
//!    staircase removes.
//!
//! Each cluster gives one [`RankDecision`] ([`RankStage::ControllabilityPbh`] or
//! [`RankStage::ObservabilityPbh`]) with its `s` singular values and the tolerance, so a
//! cluster decision near the tolerance is reported as fragile like any other. A mode that
//! the `s − 1` rule keeps although its σ is below the tolerance shows as a kept singular value
//! below it: a fragile decision (typically a mode that is only weakly controllable in the PBH
//! sense, not a twin).
//!
//! The pass costs one eigenvalue computation of the controllable part (reused for the
//! observable part when nothing was removed in between), plus O(k² (s + m)) per cluster and
//! one O(k³) rotation per pass that removes something. The eigenvalue computation is the
//! expensive part, comparable to the staircases together; when the first staircase removes
//! nothing they are those of `A`, which a caller that computes the modes anyway can hand over
//! ([`minimal_realization_with_eigenvalues`]); otherwise they are computed in parallel with
//! the observability staircase.
//!
//! References: C. C. Paige, "Properties of numerical algorithms related to computing
//! controllability", IEEE Trans. Automatic Control 26(1), 1981; R. Eising, "Between
//! controllable and uncontrollable", Systems & Control Letters 4(5), 1984; P. Van Dooren,
//! "The generalized eigenstructure problem in linear system theory", IEEE Trans. Automatic
//! Control 26(1), 1981.
//!
//! # Tolerance
//!
//! A singular value σ of a staircase block counts as non-zero when `σ > tol`, with
//!
//! ```text
//! tol_c = max(rtol · max(‖A‖_F, ‖B‖_F), atol)     (controllability stage)
//! tol_o = max(rtol · max(‖A‖_F, ‖C‖_F), atol)     (observability stage)
//! rtol  = 1000 · max(n, m, p) · ε                  (default, ε = 2.2e-16)
//! ```
//!
//! where the norms are those of the balanced matrices (see [`MinrealOptions`]). The rule is
//! relative, so multiplying the whole model by a constant, or changing the time unit, gives the
//! same decisions; an absolute tolerance (EoM.jl uses 1e-7) does not.
//!
//! # What is reported
//!
//! [`MinrealReport`] lists every rank decision with its singular values, tolerance and gap,
//! and every removed mode (eigenvalues of the uncontrollable and of the unobservable part)
//! with its kind and stability, so that a caller can say "an unstable mode the sensors cannot
//! see" instead of silently dropping it.

use nalgebra::{DMatrix, DMatrixView};
use num_complex::Complex64;

use crate::deflate::{combine_columns, structural_coordinates};
use crate::error::{
    Bound, ConvergenceError, DimensionError, NonFiniteError, NumError, OptionError,
};
use crate::minreal::pbh::{Reduction, kept_eigenvalues};
use crate::minreal::pbh_subspace::{cluster_pbh, lower_bandwidth};
use crate::minreal::staircase::{hessenberg, staircase};
use crate::statespace::StateSpace;

mod options;
mod pbh;
mod pbh_subspace;
mod report;
pub(crate) mod staircase;

pub use options::MinrealOptions;
pub use report::{
    MinrealReport, ModeStability, RankDecision, RankStage, RemovedKind, RemovedMode, Staircase,
};

/// A tolerance that must be finite and ≥ 0 but is `value`.
fn tolerance_error(option: &'static str, value: f64) -> NumError {
    NumError::InvalidOption(OptionError::Tolerance {
        option,
        value,
        must: Bound::FiniteNonNegative,
    })
}

fn check_tol(tol: f64) -> Result<(), NumError> {
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(tolerance_error("staircase tolerance", tol));
    }
    Ok(())
}

fn check_triple(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
) -> Result<(usize, usize, usize), NumError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(NumError::Dimension(DimensionError::NotSquare {
            matrix: "A",
            rows: a.nrows(),
            cols: a.ncols(),
        }));
    }
    if b.nrows() != n {
        return Err(NumError::Dimension(DimensionError::PerState {
            matrix: "B",
            axis: "rows",
            len: b.nrows(),
            states: n,
        }));
    }
    if c.ncols() != n {
        return Err(NumError::Dimension(DimensionError::PerState {
            matrix: "C",
            axis: "columns",
            len: c.ncols(),
            states: n,
        }));
    }
    for (m, name) in [(a, "A"), (b, "B"), (c, "C")] {
        if m.iter().any(|v| !v.is_finite()) {
            return Err(NumError::NonFinite(NonFiniteError::Matrix { matrix: name }));
        }
    }
    Ok((n, b.ncols(), c.nrows()))
}

/// Controllability staircase of `(A, B, C)` with absolute rank tolerance `tol`: an orthogonal
/// `q` with `qᵀ A q = [A_c *; 0 A_u]`, `qᵀ B = [B_c; 0]`, `(A_c, B_c)` controllable of
/// dimension `kept`. Blocks whose singular values are all `≤ tol` are set to exact zeros.
///
/// Errors: [`NumError::Dimension`], [`NumError::NonFinite`], [`NumError::InvalidOption`]
/// (negative or non-finite `tol`), [`NumError::NoConvergence`] (SVD).
pub fn controllability_staircase(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    tol: f64,
) -> Result<Staircase, NumError> {
    check_triple(a, b, c)?;
    check_tol(tol)?;
    let s = staircase(
        a.clone(),
        b.clone(),
        c.clone(),
        tol,
        RankStage::Controllability,
    )?;
    Ok(Staircase {
        q: s.q(),
        a: s.a,
        b: s.b,
        c: s.c,
        blocks: s.blocks,
        kept: s.kept,
        decisions: s.decisions,
    })
}

/// Observability staircase of `(A, B, C)` with absolute rank tolerance `tol`: an orthogonal
/// `q` with `qᵀ A q = [A_o 0; * A_ū]`, `C q = [C_o 0]`, `(A_o, C_o)` observable of dimension
/// `kept`. Computed as the controllability staircase of the dual `(Aᵀ, Cᵀ, Bᵀ)`.
///
/// Errors: as [`controllability_staircase`].
pub fn observability_staircase(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    tol: f64,
) -> Result<Staircase, NumError> {
    check_triple(a, b, c)?;
    check_tol(tol)?;
    let s = staircase(
        a.transpose(),
        c.transpose(),
        b.transpose(),
        tol,
        RankStage::Observability,
    )?;
    Ok(Staircase {
        q: s.q(),
        a: s.a.transpose(),
        b: s.c.transpose(),
        c: s.b.transpose(),
        blocks: s.blocks,
        kept: s.kept,
        decisions: s.decisions,
    })
}

/// `(U, σ, V)` of a full SVD.
pub(crate) type FullSvd = (DMatrix<f64>, Vec<f64>, DMatrix<f64>);

/// Full SVD `m = U Σ Vᵀ` (U and V square), singular values largest first.
pub(crate) fn svd_full(m: &DMatrix<f64>) -> Result<FullSvd, NumError> {
    let (r, c) = m.shape();
    if r == 0 || c == 0 {
        return Ok((DMatrix::identity(r, r), Vec::new(), DMatrix::identity(c, c)));
    }
    let view = faer::MatRef::from_column_major_slice(m.as_slice(), r, c);
    let svd = view.svd().map_err(|e| {
        NumError::NoConvergence(ConvergenceError::BlockSvd {
            rows: r,
            cols: c,
            detail: format!("{e:?}"),
        })
    })?;
    let (fu, fs, fv) = (svd.U(), svd.S(), svd.V());
    let u = DMatrix::from_fn(r, r, |i, j| fu[(i, j)]);
    let v = DMatrix::from_fn(c, c, |i, j| fv[(i, j)]);
    let s: Vec<f64> = (0..r.min(c)).map(|i| fs[i]).collect();
    Ok((u, s, v))
}

/// Eigenvalues of a square block sorted by (re, im).
pub(crate) fn eigenvalues_sorted(a: DMatrixView<'_, f64>) -> Result<Vec<Complex64>, NumError> {
    crate::modes::eigenvalues(&a.clone_owned())
}

/// Sorts complex numbers by real part, then imaginary part.
pub(crate) fn sort_complex(v: &mut [Complex64]) {
    v.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
}

/// Power-of-two state scaling `s` that balances the row norms of `[A B]` against the column
/// norms of `[A; C]` (diagonal of A excluded), in the manner of Parlett & Reinsch (1969).
/// The scaled system is `D⁻¹ A D`, `D⁻¹ B`, `C D` with `D = diag(s)`.
pub(crate) fn balance_states(a: &DMatrix<f64>, b: &DMatrix<f64>, c: &DMatrix<f64>) -> Vec<f64> {
    let n = a.nrows();
    let mut s = vec![1.0f64; n];
    let mut a = a.clone();
    let mut b = b.clone();
    let mut c = c.clone();
    // Bounded number of sweeps: convergence is usually reached in a few.
    for _ in 0..64 {
        let mut changed = false;
        for i in 0..n {
            let mut col = c.column(i).iter().map(|v| v.abs()).sum::<f64>();
            let mut row = b.row(i).iter().map(|v| v.abs()).sum::<f64>();
            for k in 0..n {
                if k != i {
                    col += a[(k, i)].abs();
                    row += a[(i, k)].abs();
                }
            }
            if col == 0.0 || row == 0.0 {
                continue;
            }
            // Scaling state i by f multiplies the column norm by f and divides the row norm
            // by f: f = 2^e with e the rounded half log2 of row/col.
            let e = (0.5 * (row / col).log2()).round();
            if e == 0.0 || !e.is_finite() {
                continue;
            }
            // Keep the total scaling within 2^±256 so nothing overflows.
            let total = s[i].log2() + e;
            if total.abs() > 256.0 {
                continue;
            }
            let f = 2f64.powi(e as i32);
            if col * f + row / f >= 0.95 * (col + row) {
                continue;
            }
            changed = true;
            s[i] *= f;
            a.column_mut(i).scale_mut(f);
            c.column_mut(i).scale_mut(f);
            a.row_mut(i).scale_mut(1.0 / f);
            b.row_mut(i).scale_mut(1.0 / f);
        }
        if !changed {
            break;
        }
    }
    s
}

/// Applies the state scaling `x = diag(s) x̃` to `(A, B, C)` in place.
pub(crate) fn apply_scaling(
    s: &[f64],
    a: &mut DMatrix<f64>,
    b: &mut DMatrix<f64>,
    c: &mut DMatrix<f64>,
) {
    for (i, &f) in s.iter().enumerate() {
        if f != 1.0 {
            a.column_mut(i).scale_mut(f);
            c.column_mut(i).scale_mut(f);
            a.row_mut(i).scale_mut(1.0 / f);
            b.row_mut(i).scale_mut(1.0 / f);
        }
    }
}

fn classify(
    ev: &[Complex64],
    kind: RemovedKind,
    thr: f64,
    pbh: Option<(&DMatrix<f64>, &DMatrix<f64>)>,
    rtol: f64,
) -> Result<Vec<RemovedMode>, NumError> {
    let mut residuals = match pbh {
        Some((a, other)) if !ev.is_empty() => Some(PbhResiduals::new(a, other, kind, rtol)),
        _ => None,
    };
    let mut out: Vec<RemovedMode> = Vec::with_capacity(ev.len());
    for &eigenvalue in ev {
        let pbh_residual = match residuals.as_mut() {
            Some(r) => Some(r.at(eigenvalue)?),
            None => None,
        };
        out.push(RemovedMode {
            eigenvalue,
            kind,
            stability: if eigenvalue.re > thr {
                ModeStability::Unstable
            } else if eigenvalue.re < -thr {
                ModeStability::Stable
            } else {
                ModeStability::Marginal
            },
            pbh_residual,
        });
    }
    Ok(out)
}

/// The PBH residuals of [`RemovedMode::pbh_residual`] for one kind: `[A − λI, B]`
/// (uncontrollable) or `[Aᵀ − λI, Cᵀ]` (unobservable: the transpose of `[A − λI; C]`, with the
/// same singular values) in the coordinates where `A` (or `Aᵀ`) is upper Hessenberg, an
/// orthogonal change that leaves the singular values alone. Each residual is then one
/// inverse iteration with a banded LU, O(n²), instead of an O(n³) SVD: a model with many
/// removed modes costs O(n³) in all. Eigenvalues equal to one already examined (within
/// `n·ε·scale`, conjugates included: the data are real) reuse its residual.
///
/// The iteration's residual is an upper bound. Where it does not confirm the removal (above
/// `rtol`), the exact smallest singular value is computed by a full SVD: inside a cluster of
/// eigenvalues that a kept mode shares, split by rounding (identical bodies in coordinates
/// that mix them), the Woodbury form of the iteration cancels badly and the bound can be
/// far above the true value (7e-4 against 1e-16 for 20 mixed identical oscillators).
struct PbhResiduals<'a> {
    a: &'a DMatrix<f64>,
    other: &'a DMatrix<f64>,
    kind: RemovedKind,
    h: DMatrix<f64>,
    y: DMatrix<f64>,
    scale: f64,
    near: f64,
    rtol: f64,
    done: Vec<(Complex64, f64)>,
}

impl<'a> PbhResiduals<'a> {
    fn new(a: &'a DMatrix<f64>, other: &'a DMatrix<f64>, kind: RemovedKind, rtol: f64) -> Self {
        let n = a.nrows();
        let scale = a.norm().max(other.norm());
        let (mut h, mut y) = match kind {
            RemovedKind::Uncontrollable => (a.clone(), other.clone()),
            RemovedKind::Unobservable => (a.transpose(), other.transpose()),
        };
        if n >= 3 {
            // y ← Qᵀ y, as (yᵀ Q)ᵀ.
            let q = hessenberg(&mut h, 0);
            let mut yt = y.transpose();
            q.apply_right(&mut yt);
            y = yt.transpose();
        }
        PbhResiduals {
            a,
            other,
            kind,
            h,
            y,
            scale,
            near: n as f64 * f64::EPSILON * scale,
            rtol,
            done: Vec::new(),
        }
    }

    /// The residual at `lam`, relative to the scale.
    fn at(&mut self, lam: Complex64) -> Result<f64, NumError> {
        if self.scale == 0.0 || self.h.nrows() == 0 {
            return Ok(0.0);
        }
        let near = self.near;
        if let Some(&(_, r)) = self
            .done
            .iter()
            .find(|(z, _)| (z - lam).norm() <= near || (z.conj() - lam).norm() <= near)
        {
            return Ok(r);
        }
        let p = lower_bandwidth(&self.h);
        // Two directions, the smaller residual kept: at an eigenvalue that a kept mode shares
        // (a twin) the second smallest singular value is small too, and one vector alone
        // converges slowly between the two (a twin chain's residuals came out at 4e-9
        // instead of below 1e-15).
        let (_, sigma) = cluster_pbh(&self.h, &self.y, lam, 2.min(self.h.nrows()), p)?;
        let mut r = sigma.iter().copied().fold(f64::INFINITY, f64::min) / self.scale;
        if r > self.rtol {
            r = r.min(pbh_residual(self.a, self.other, lam, self.kind)?);
        }
        self.done.push((lam, r));
        Ok(r)
    }
}

/// σ_min([A − λI, B]) (uncontrollable) or σ_min([A − λI; C]) (unobservable), relative, by a
/// full SVD: O(n³), the fallback of [`PbhResiduals::at`].
fn pbh_residual(
    a: &DMatrix<f64>,
    other: &DMatrix<f64>,
    lam: Complex64,
    kind: RemovedKind,
) -> Result<f64, NumError> {
    let n = a.nrows();
    let scale = a.norm().max(other.norm());
    if scale == 0.0 || n == 0 {
        return Ok(0.0);
    }
    let entry = |i: usize, j: usize| {
        Complex64::new(a[(i, j)], 0.0)
            - if i == j {
                lam
            } else {
                Complex64::new(0.0, 0.0)
            }
    };
    let m = match kind {
        RemovedKind::Uncontrollable => {
            faer::Mat::<Complex64>::from_fn(n, n + other.ncols(), |i, j| {
                if j < n {
                    entry(i, j)
                } else {
                    Complex64::new(other[(i, j - n)], 0.0)
                }
            })
        }
        RemovedKind::Unobservable => {
            faer::Mat::<Complex64>::from_fn(n + other.nrows(), n, |i, j| {
                if i < n {
                    entry(i, j)
                } else {
                    Complex64::new(other[(i - n, j)], 0.0)
                }
            })
        }
    };
    // n singular values for both shapes (n × (n+k) or (n+k) × n).
    let sv = m.singular_values().map_err(|e| {
        NumError::NoConvergence(ConvergenceError::AtEigenvalue {
            step: "PBH test SVD",
            lambda: lam,
            detail: Some(format!("{e:?}")),
        })
    })?;
    Ok(sv.iter().copied().fold(f64::INFINITY, f64::min) / scale)
}

/// Minimal realization of `ss` by orthogonal staircase reductions (see the module
/// documentation for the algorithm and the tolerance).
///
/// The minimal system keeps `D`, the input and output names and units, and the body names.
/// Its `phys` is `phys · T`, where `T` (n × n_min, orthonormal columns up to the balancing
/// scaling) maps the minimal state into the original state space: exact for the removed
/// uncontrollable part (which stays at rest from rest), and the least-squares choice for the
/// removed unobservable part (whose motion the minimal state does not determine). The states
/// of the minimal system are new coordinates: when the input had state names they become
/// `z1, z2, …`. When nothing is removed, the input system is returned unchanged.
///
/// Errors: [`NumError::Dimension`] / [`NumError::NonFinite`] for a malformed model,
/// [`NumError::InvalidOption`] for bad options, [`NumError::NoConvergence`] if an SVD or an
/// eigenvalue computation fails.
pub fn minimal_realization(
    ss: &StateSpace<f64>,
    opts: &MinrealOptions,
) -> Result<(StateSpace<f64>, MinrealReport), NumError> {
    minimal_realization_with_eigenvalues(ss, opts, |_| None)
}

/// [`minimal_realization`] with the eigenvalues of `ss.a` supplied by the caller, who has
/// often computed them anyway (the modes). The cluster PBH pass needs the eigenvalues of the
/// controllable part, which are those of `A` when the first staircase removes nothing; then,
/// and only then, `eigenvalues` is called — after both staircases, so that a caller computing
/// the modes concurrently is waited for as late as possible. It is given the draft: the
/// system the two staircases leave (`D` included, no physical map), which is the result
/// whenever the PBH pass then removes nothing, so that the caller can start work on it
/// (the transmission zeros) while it waits. It returns the eigenvalues in any order, or
/// `None` (they are then computed here, as they are when the list has the wrong length).
///
/// Errors: as [`minimal_realization`].
pub fn minimal_realization_with_eigenvalues(
    ss: &StateSpace<f64>,
    opts: &MinrealOptions,
    eigenvalues: impl FnOnce(&StateSpace<f64>) -> Option<Vec<Complex64>> + Send,
) -> Result<(StateSpace<f64>, MinrealReport), NumError> {
    ss.validate()?;
    opts.validate()?;
    let (n, m, p) = (ss.states(), ss.inputs(), ss.outputs());
    let rtol = opts
        .rtol
        .unwrap_or_else(|| MinrealOptions::default_rtol(n, m, p));
    // In the coordinates where the structural zeros are exact (the rounding residues of an
    // elimination in a column on which nothing depends would otherwise be balanced up and
    // counted as couplings).
    let st = structural_coordinates(&ss.a, &ss.b, &ss.c);
    let (mut a, mut b, mut c, combos) = (st.a, st.b, st.c, st.combos);
    let scaling = if opts.balance {
        balance_states(&a, &b, &c)
    } else {
        vec![1.0; n]
    };
    apply_scaling(&scaling, &mut a, &mut b, &mut c);
    let (na, nb, nc_) = (a.norm(), b.norm(), c.norm());
    let (a0, b0, c0) = (a.clone(), b.clone(), c.clone());
    let tol_c = (rtol * na.max(nb)).max(opts.atol);
    let tol_o = (rtol * na.max(nc_)).max(opts.atol);
    let stability_threshold = opts.stability_rtol * na;

    let dist = opts.cluster_pbh.then_some(opts.cluster_rtol * na);
    let (mut rc, mut ro) = reduce_both(
        Reduction::new(a, b, c),
        (tol_c, tol_o),
        dist,
        &ss.d,
        eigenvalues,
    )?;
    let nc = rc.a.nrows();
    let no = ro.a.nrows();
    sort_complex(&mut rc.removed);
    sort_complex(&mut ro.removed);

    let mut removed = classify(
        &rc.removed,
        RemovedKind::Uncontrollable,
        stability_threshold,
        opts.pbh_check.then_some((&a0, &b0)),
        rtol,
    )?;
    removed.extend(classify(
        &ro.removed,
        RemovedKind::Unobservable,
        stability_threshold,
        opts.pbh_check.then_some((&a0, &c0)),
        rtol,
    )?);
    let mut decisions = rc.decisions.clone();
    decisions.extend(ro.decisions.iter().cloned());
    let report = MinrealReport {
        states_in: n,
        states_out: no,
        uncontrollable: n - nc,
        unobservable: nc - no,
        structurally_uncontrollable: rc.structural,
        structurally_unobservable: ro.structural,
        removed,
        decisions,
        rtol,
        controllability_tolerance: tol_c,
        observability_tolerance: tol_o,
        stability_threshold,
        scaling,
    };
    if no == n {
        return Ok((ss.clone(), report));
    }

    let out = minimal_system(ss, &rc, &ro, &combos, &report.scaling);
    Ok((out, report))
}

/// The controllability reduction of `rc`, then the observability reduction of its result (on
/// the dual), each a staircase followed by the cluster PBH pass when `dist` (the clustering
/// distance) is given; `eigenvalues` as in [`minimal_realization_with_eigenvalues`].
fn reduce_both(
    mut rc: Reduction,
    (tol_c, tol_o): (f64, f64),
    dist: Option<f64>,
    d: &DMatrix<f64>,
    eigenvalues: impl FnOnce(&StateSpace<f64>) -> Option<Vec<Complex64>> + Send,
) -> Result<(Reduction, Reduction), NumError> {
    let n = rc.a.nrows();
    let c_stages = (RankStage::Controllability, RankStage::ControllabilityPbh);
    let o_stages = (RankStage::Observability, RankStage::ObservabilityPbh);
    rc.structural()?;
    rc.staircase(tol_c, c_stages.0)?;
    let nc_krylov = rc.a.nrows();
    // The observability reduction is the controllability reduction of the dual. Its
    // staircase does not wait for the eigenvalues of the controllable part: it is redone
    // only if the PBH pass removes something.
    let observability = |rc: &Reduction| {
        let mut ro = rc.dual();
        ro.structural()?;
        ro.staircase(tol_o, o_stages.0).map(|_| ro)
    };
    let Some(dist) = dist else {
        let ro = observability(&rc)?;
        return Ok((rc, ro));
    };
    let (ev, ro) = if nc_krylov == n {
        let ro = observability(&rc)?;
        // The draft: the system the staircases leave, back from the dual.
        let draft = StateSpace::new(
            ro.a.transpose(),
            ro.c.transpose(),
            ro.b.transpose(),
            d.clone(),
        )?;
        let ev = match eigenvalues(&draft).filter(|e| e.len() == n) {
            Some(mut e) => {
                sort_complex(&mut e);
                Ok(e)
            }
            None => kept_eigenvalues(&rc),
        };
        (ev, Ok(ro))
    } else {
        rayon::join(|| kept_eigenvalues(&rc), || observability(&rc))
    };
    rc.finish(tol_c, dist, c_stages, Some(ev?))?;
    let mut ro = if rc.a.nrows() == nc_krylov {
        ro?
    } else {
        observability(&rc)?
    };
    // Nothing removed since the controllable part's eigenvalues: they are A_o's.
    let ev = rc.eigenvalues.clone().filter(|e| e.len() == ro.a.nrows());
    ro.finish(tol_o, dist, o_stages, ev)?;
    Ok((rc, ro))
}

/// The minimal system from the two reductions: back from the dual, `D`, the names, and the
/// physical map `phys · T · diag(s) · Q_c · Q_o` applied factor by factor (the staircases'
/// Q's are never formed).
fn minimal_system(
    ss: &StateSpace<f64>,
    rc: &Reduction,
    ro: &Reduction,
    combos: &[crate::deflate::Combine],
    scaling: &[f64],
) -> StateSpace<f64> {
    let no = ro.a.nrows();
    let mut phys = ss.phys.clone();
    combine_columns(combos, &mut phys);
    for (j, &f) in scaling.iter().enumerate() {
        phys.column_mut(j).scale_mut(f);
    }
    let phys = ro.apply_right(rc.apply_right(phys));
    let mut names = ss.names.clone();
    names.states = if ss.names.states.is_empty() {
        Vec::new()
    } else {
        (1..=no).map(|i| format!("z{i}")).collect()
    };
    StateSpace {
        a: ro.a.transpose(),
        b: ro.c.transpose(),
        c: ro.b.transpose(),
        d: ss.d.clone(),
        phys,
        names,
    }
}

/// Serialization of complex numbers as `{re, im}`.
pub(crate) mod cser {
    use num_complex::Complex64;
    use serde::Serialize;
    use serde::ser::{SerializeSeq, Serializer};

    #[derive(Serialize)]
    struct ReIm {
        re: f64,
        im: f64,
    }

    /// One complex number as `{re, im}`.
    pub(crate) fn one<S: Serializer>(z: &Complex64, s: S) -> Result<S::Ok, S::Error> {
        ReIm { re: z.re, im: z.im }.serialize(s)
    }

    /// A list of complex numbers as `[{re, im}, …]`.
    pub(crate) fn many<S: Serializer>(v: &[Complex64], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(v.len()))?;
        for z in v {
            seq.serialize_element(&ReIm { re: z.re, im: z.im })?;
        }
        seq.end()
    }
}
