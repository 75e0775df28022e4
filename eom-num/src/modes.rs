//! Eigenvalues and modes of a state-space model.
//!
//! * [`eigenvalues`] — the eigenvalues of a square matrix, sorted by (real, imaginary) part;
//!   [`eigenvalues_in`] is the same with a caller-owned [`EigenvaluesWorkspace`] and no
//!   allocation, for sweeps that call it millions of times. Up to
//!   [`small_eigen::MAX_N`] states both use the stack kernel of [`small_eigen`], beyond
//!   that faer's QR algorithm ([`eigenvalues_faer_in`]).
//! * [`Modes::compute`] — per mode: eigenvalue, kind, natural frequency, damping ratio, time
//!   constant, damped period, stability, eigenvalue condition number, mode shape in physical
//!   coordinates and, per body, the instantaneous centre of rotation and rotation axis.
//!
//! # Decisions and their thresholds
//!
//! The matrix is first balanced (diagonal similarity by powers of two, so eigenvalues are
//! unchanged but accuracy does not depend on units). Each eigenvalue λᵢ then gets its own
//! tolerance
//!
//! ```text
//! tolᵢ = max(tol_factor · n · ε · ‖Ã‖_F · κᵢ,  ε · |yᵢ|ᵀ|A||xᵢ| / |yᵢᴴ xᵢ|)     κᵢ = ‖xᵢ‖ ‖yᵢ‖ / |yᵢᴴ xᵢ|
//! ```
//!
//! where Ã is the balanced matrix and xᵢ, yᵢ its right and left eigenvectors: first-order
//! perturbation theory says a backward-stable eigensolver moves λᵢ by about `ε ‖Ã‖ κᵢ`, and
//! rounding every entry of A moves it by the second term ([`error_estimate`]). This error
//! estimate is the one tolerance of every stability verdict, here and in sweeps
//! ([`stability_of`], [`eigenvalues_with_errors`]). So a
//! simple slow pole of a stiff system (|λ| = 1e-8 ‖A‖, κ ≈ 1) is *not* mistaken for zero,
//! while a rigid-body double zero, which a backward-stable solver splits into ±√ε‖A‖ with
//! κ ≈ 1/√ε, *is* recognised as zero. With `tol = tolᵢ`:
//!
//! * `|λ| ≤ tol` → [`ModeKind::Zero`] (rigid-body or integrator mode);
//! * else `|Im λ| ≤ tol` → [`ModeKind::Real`];
//! * else [`ModeKind::Oscillatory`];
//! * `|Re λ| ≤ tol` → [`Stability::Marginal`] (τ = ∞, ζ = 0 for an oscillatory mode); else
//!   the sign of Re λ decides stable/unstable.
//!
//! EoM.jl used fixed absolute thresholds (1e-7) and reported ω_n = 0, ζ = NaN for every real
//! pole; here a real pole reports its corner frequency |λ|/2π, ζ = ±1, and
//! NaN never appears.
//!
//! # Conjugate pairs
//!
//! Both members of a complex-conjugate pair are reported (one [`Mode`] per eigenvalue, n modes
//! for n states, in the same (Re, Im) order as [`eigenvalues`], so the member with negative
//! imaginary part comes first). Their real parts are bit-identical, which makes the order
//! deterministic. [`Modes::distinct`] skips the negative-frequency member.

use std::f64::consts::PI;

use faer::diag::DiagMut;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::{ComputeEigenvectors, evd_real, evd_scratch};
use faer::{MatRef, Par};
use nalgebra::{DMatrix, DVector, Vector3};
use num_complex::Complex64;

use crate::deflate;
use crate::eigen::eigen_full;
use crate::linalg::balance_in_place;
use crate::small_eigen;
use crate::statespace::{StateSpace, check_finite, in_range};
use crate::{Bound, ConvergenceError, DimensionError, NumError, OptionError};

fn cmp_re_im(a: &Complex64, b: &Complex64) -> std::cmp::Ordering {
    a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im))
}

fn check_square(a: &DMatrix<f64>, name: &'static str) -> Result<(), NumError> {
    if a.nrows() != a.ncols() {
        return Err(NumError::Dimension(DimensionError::NotSquare {
            matrix: name,
            rows: a.nrows(),
            cols: a.ncols(),
        }));
    }
    Ok(())
}

/// Eigenvalues of a square matrix, sorted by (real part, imaginary part) ascending.
///
/// The matrix is balanced first. Conjugate pairs are exact conjugates (bit-identical real
/// parts); real eigenvalues have imaginary part `+0.0`.
///
/// Errors: [`NumError::Dimension`] (not square), [`NumError::NonFinite`],
/// [`NumError::NoConvergence`].
pub fn eigenvalues(a: &DMatrix<f64>) -> Result<Vec<Complex64>, NumError> {
    check_square(a, "A")?;
    if a.nrows() <= small_eigen::MAX_N {
        let mut out = vec![Complex64::new(0.0, 0.0); a.nrows()];
        small_eigen::eigenvalues_small(a.as_slice(), a.nrows(), &mut out)?;
        return Ok(out);
    }
    // One large matrix: faer's parallel kernels on the current pool (its Hessenberg
    // reduction and multishift QR), where a sweep's workspace stays sequential.
    let mut ws = EigenvaluesWorkspace::with_par(a.nrows(), crate::linalg::par(a.nrows()));
    let mut out = vec![Complex64::new(0.0, 0.0); a.nrows()];
    eigenvalues_in(a, &mut ws, &mut out)?;
    Ok(out)
}

/// Scratch space for [`eigenvalues_in`], for one matrix size.
pub struct EigenvaluesWorkspace {
    n: usize,
    a: Vec<f64>,
    b: Vec<f64>,
    removed: Vec<bool>,
    order: Vec<usize>,
    combos: Vec<deflate::Combine>,
    keys: Vec<(u64, usize)>,
    scale: Vec<f64>,
    re: Vec<f64>,
    im: Vec<f64>,
    par: Par,
    buf: MemBuffer,
}

impl std::fmt::Debug for EigenvaluesWorkspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EigenvaluesWorkspace")
            .field("n", &self.n)
            .finish_non_exhaustive()
    }
}

pub(crate) fn eig_scratch(n: usize, vectors: bool, par: Par) -> StackReq {
    let v = if vectors {
        ComputeEigenvectors::Yes
    } else {
        ComputeEigenvectors::No
    };
    evd_scratch::<f64>(n, v, v, par, Default::default())
}

/// Bytes of scratch memory an [`EigenvaluesWorkspace`] for an n × n matrix holds (faer's
/// stack requirement plus four length-n/n² buffers).
pub fn eigenvalues_workspace_bytes(n: usize) -> usize {
    eig_scratch(n, false, Par::Seq).size_bytes() + 8 * (n * n + 3 * n)
}

impl EigenvaluesWorkspace {
    /// Allocates the workspace for n × n matrices (the only allocation of the kernel).
    /// The kernel runs on the calling thread (`Par::Seq`): sweeps parallelise over their
    /// points instead.
    pub fn new(n: usize) -> Self {
        Self::with_par(n, Par::Seq)
    }

    /// The workspace for faer's kernels with parallelism `par` (its scratch depends on it).
    pub(crate) fn with_par(n: usize, par: Par) -> Self {
        EigenvaluesWorkspace {
            n,
            a: vec![0.0; n * n],
            b: vec![0.0; n * n],
            removed: vec![false; n],
            order: Vec::with_capacity(n),
            combos: Vec::with_capacity(n),
            keys: Vec::with_capacity(n),
            scale: vec![1.0; n],
            re: vec![0.0; n],
            im: vec![0.0; n],
            par,
            buf: MemBuffer::new(eig_scratch(n, false, par)),
        }
    }

    /// The matrix size this workspace serves.
    pub fn dim(&self) -> usize {
        self.n
    }
}

/// [`eigenvalues`] without allocation: `out` (length n) receives the sorted eigenvalues.
///
/// Matrices of up to [`small_eigen::MAX_N`] states go to the stack kernel
/// [`small_eigen::eigenvalues_small`] (the workspace is then not used), larger ones to
/// faer's QR algorithm ([`eigenvalues_faer_in`]); both deflate the structural zeros first and
/// balance.
///
/// Errors: [`NumError::Dimension`] when `a`, the workspace and `out` disagree in size,
/// [`NumError::NonFinite`], [`NumError::NoConvergence`].
pub fn eigenvalues_in(
    a: &DMatrix<f64>,
    ws: &mut EigenvaluesWorkspace,
    out: &mut [Complex64],
) -> Result<(), NumError> {
    if ws.n <= small_eigen::MAX_N {
        if a.nrows() != ws.n || a.ncols() != ws.n || out.len() != ws.n {
            check_eigenvalues_in(a, ws, out)?;
        }
        small_eigen::eigenvalues_small(a.as_slice(), ws.n, out)?;
        return Ok(());
    }
    eigenvalues_faer_in(a, ws, out)
}

fn check_eigenvalues_in(
    a: &DMatrix<f64>,
    ws: &EigenvaluesWorkspace,
    out: &[Complex64],
) -> Result<(), NumError> {
    let n = ws.n;
    if a.nrows() != n || a.ncols() != n || out.len() != n {
        return Err(NumError::Dimension(DimensionError::EigenWorkspace {
            rows: a.nrows(),
            cols: a.ncols(),
            workspace: n,
            out: out.len(),
        }));
    }
    if a.iter().any(|x| !in_range(*x)) {
        return check_finite(a, "A");
    }
    Ok(())
}

/// [`eigenvalues_in`] by faer's QR algorithm for every size (on the calling thread with a
/// workspace from [`EigenvaluesWorkspace::new`]): the path of the matrices above
/// [`small_eigen::MAX_N`] states, public so that the small kernel can be compared with it
/// (`eom bench accuracy`).
///
/// Errors: as [`eigenvalues_in`].
pub fn eigenvalues_faer_in(
    a: &DMatrix<f64>,
    ws: &mut EigenvaluesWorkspace,
    out: &mut [Complex64],
) -> Result<(), NumError> {
    check_eigenvalues_in(a, ws, out)?;
    let n = ws.n;
    if n == 0 {
        return Ok(());
    }
    // Structural zero eigenvalues are deflated first (see `deflate`).
    ws.b.copy_from_slice(a.as_slice());
    deflate::deflate_in_place(
        &mut ws.b,
        n,
        &mut ws.removed,
        &mut ws.order,
        &mut ws.combos,
        &mut ws.keys,
    );
    let m = deflate::kept_block(&ws.b, n, &ws.removed, &mut ws.a);
    if m > 0 {
        balance_in_place(&mut ws.a[..m * m], m, &mut ws.scale[..m]);
        evd_real(
            MatRef::from_column_major_slice(&ws.a[..m * m], m, m),
            DiagMut::from_slice_mut(&mut ws.re[..m]),
            DiagMut::from_slice_mut(&mut ws.im[..m]),
            None,
            None,
            ws.par,
            MemStack::new(&mut ws.buf),
            Default::default(),
        )
        .map_err(|_| {
            NumError::NoConvergence(ConvergenceError::Factorisation {
                step: "eigenvalues",
                rows: n,
                cols: n,
                object: "matrix",
            })
        })?;
    }
    for (k, o) in out.iter_mut().enumerate() {
        // `+ 0.0` turns a −0.0 imaginary part into +0.0 so that sorting is by value.
        *o = if k < m {
            Complex64::new(ws.re[k], ws.im[k] + 0.0)
        } else {
            Complex64::new(0.0, 0.0)
        };
    }
    out.sort_unstable_by(cmp_re_im);
    Ok(())
}

/// What kind of motion a mode is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ModeKind {
    /// λ = 0 within tolerance: a rigid-body or integrator mode (no time scale).
    Zero,
    /// A real pole: exponential decay or growth, no oscillation.
    Real,
    /// One member of a complex-conjugate pair: a damped (or growing) oscillation.
    Oscillatory,
}

/// Stability of a single mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Stability {
    /// Re λ < −tol: decays.
    Stable,
    /// |Re λ| ≤ tol: neither decays nor grows exponentially (a repeated zero or imaginary
    /// eigenvalue with a Jordan block, such as a free body's position, still grows
    /// polynomially; look at [`Mode::condition`]).
    Marginal,
    /// Re λ > tol: grows.
    Unstable,
}

/// The instantaneous centre of rotation of one body in one mode.
#[derive(Clone, Debug, PartialEq)]
pub struct InstantCentre {
    /// Body name (`names.bodies`, or `"body k"` when unnamed).
    pub body: String,
    /// Vector from the mass centre to the nearest point of the instantaneous rotation axis:
    /// the minimum-norm solution of `m_trans + m_rot × r = 0`, i.e.
    /// `r = (conj(m_rot) × m_trans) / ‖m_rot‖²` (= `−pinv([m_rot]×) m_trans`). It is the
    /// same for any complex scaling of the mode. Real when the body moves in phase; an
    /// imaginary part means the centre moves during the cycle. `None` when the body does not
    /// rotate in this mode (pure translation, or at rest).
    pub radius: Option<Vector3<Complex64>>,
    /// Unit rotation direction `m_rot / ‖m_rot‖`, after multiplying the mode by the phase
    /// that makes its dominant rotation component real and positive. `None` when the body
    /// does not rotate.
    pub axis: Option<Vector3<Complex64>>,
}

/// One mode (one eigenvalue) of a state-space model.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// The eigenvalue λ as computed.
    pub eigenvalue: Complex64,
    /// Zero, real or oscillatory (see the module docs for the thresholds).
    pub kind: ModeKind,
    /// Natural frequency `|λ|/2π` in Hz. For a [`ModeKind::Real`] pole this is its corner
    /// frequency `|Re λ|/2π` (never reported as 0 Hz); for [`ModeKind::Zero`] it is 0.
    pub natural_frequency_hz: f64,
    /// Damping ratio `−Re λ / |λ|` for an oscillatory mode (0 when marginal); `+1` for a
    /// stable and `−1` for an unstable real pole; `None` for a zero mode, where it is
    /// undefined.
    pub damping_ratio: Option<f64>,
    /// Time constant `τ = −1/Re λ` in s; negative for a growing mode (the e-folding time of
    /// the growth is |τ|); `∞` when marginal or zero.
    pub time_constant: f64,
    /// Damped period `2π/|Im λ|` in s (EoM.jl's "wavelength"); `∞` for real and zero modes.
    pub damped_period: f64,
    /// Stable, marginal or unstable.
    pub stability: Stability,
    /// Eigenvalue condition number κ = ‖x‖‖y‖/|yᴴx| (on the balanced matrix); large values
    /// flag nearly defective (repeated) eigenvalues.
    pub condition: f64,
    /// The eigenvalue's error estimate in 1/s ([`error_estimate`]): the tolerance of this
    /// mode's decisions (zero, real, marginal; see the module docs).
    pub tolerance: f64,
    /// Estimated relative error of the eigenvalue caused by rounding every entry of A (as
    /// assembling a model in floating point does): `ε |y|ᵀ|A||x| / (|yᴴx| |λ|)` with x, y the
    /// right and left eigenvectors (the componentwise condition number). Large where the
    /// model's scales differ widely: e.g. a chain with one spring 1e10 times stiffer than the
    /// others loses about 1e-6 of its slow eigenvalues in the rounding of the stiffness entries,
    /// whichever method reduces it. 0 for an exact zero eigenvalue and where not estimated
    /// (modes of [`Modes::compute_with`] only).
    pub accuracy: f64,
    /// Mode shape in physical coordinates, `phys · x` scaled so that its largest entry is
    /// exactly 0.5 (real). Empty when the model has no physical map; all zero when the mode
    /// does not move any body (then [`Mode::reference_index`] is `None`).
    pub shape: DVector<Complex64>,
    /// Index of the entry of `shape` that was normalised to 0.5.
    pub reference_index: Option<usize>,
    /// Per body (six rows of `phys` each), the instantaneous centre and rotation axis. Empty
    /// when `phys` has no rows or its row count is not a multiple of six.
    pub centres: Vec<InstantCentre>,
}

/// Options of [`Modes::compute_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModeOptions {
    /// Balance A before the eigendecomposition (default `true`).
    pub balance: bool,
    /// Zero eigenvalues the model's structure proves, known from another basis of the same
    /// model (e.g. the elimination path's, for the robust path's matrix, whose orthonormal basis
    /// hides them in rounding). When `A` shows fewer exact structural zeros, this many null
    /// directions are deflated orthogonally before the eigensolve (default 0).
    pub structural_zeros: usize,
    /// The factor `tol_factor` in `tol = tol_factor · n · ε · ‖Ã‖ · κ` (default 10).
    pub tol_factor: f64,
    /// Compute the mode shapes and instantaneous centres (default `true`; without, every
    /// [`Mode::shape`] is empty and [`Mode::centres`] too, which saves a product of the
    /// physical map with every eigenvector and the memory of the shapes).
    pub shapes: bool,
}

impl Default for ModeOptions {
    fn default() -> Self {
        ModeOptions {
            balance: true,
            tol_factor: 10.0,
            structural_zeros: 0,
            shapes: true,
        }
    }
}

/// All modes of a state-space model.
#[derive(Clone, Debug, PartialEq)]
pub struct Modes {
    /// One mode per eigenvalue, sorted by (Re λ, Im λ).
    pub modes: Vec<Mode>,
    /// Frobenius norm of the balanced A, the scale of the tolerances.
    pub scale: f64,
}

impl Modes {
    /// Modes with default [`ModeOptions`].
    ///
    /// Errors: those of [`StateSpace::validate`], [`NumError::NoConvergence`].
    pub fn compute(ss: &StateSpace<f64>) -> Result<Modes, NumError> {
        Self::compute_with(ss, &ModeOptions::default())
    }

    /// Modes with explicit options.
    ///
    /// Errors: [`NumError::InvalidOption`] for a non-positive or non-finite `tol_factor`,
    /// plus those of [`Modes::compute`].
    pub fn compute_with(ss: &StateSpace<f64>, opts: &ModeOptions) -> Result<Modes, NumError> {
        if !(opts.tol_factor.is_finite() && opts.tol_factor > 0.0) {
            return Err(NumError::InvalidOption(OptionError::Value {
                option: "ModeOptions::tol_factor",
                value: opts.tol_factor,
                must: Bound::FinitePositive,
            }));
        }
        ss.validate()?;
        let n = ss.states();
        let mut eig = eigen_full(&ss.a, opts.balance, true)?;
        eig.known_zeros(&ss.a, opts.structural_zeros)?;
        let componentwise = eig.componentwise(&ss.a).unwrap_or_else(|| vec![0.0; n]);
        let rows = ss.phys.nrows();
        let shapes = if opts.shapes && rows > 0 {
            crate::budget::check(
                "the mode shapes",
                crate::budget::product(&[rows, n, 16 + 8]),
            )?;
            eig.map_right(&ss.phys)
        } else {
            Vec::new()
        };
        let mut shapes = shapes.into_iter();
        let mut modes = Vec::with_capacity(n);
        for (k, comp) in componentwise.iter().enumerate() {
            let tol = estimate_of(&eig, k, *comp, opts.tol_factor);
            let mut mode = classify(eig.values[k], tol);
            mode.condition = eig.condition[k];
            let size = eig.values[k].norm();
            mode.accuracy = if size > 0.0 {
                f64::EPSILON * comp / size
            } else {
                0.0
            };
            if let Some(shape) = shapes.next() {
                set_shape(&mut mode, shape, ss, n);
            }
            modes.push(mode);
        }
        Ok(Modes {
            modes,
            scale: eig.norm,
        })
    }

    /// The eigenvalues, in mode order.
    pub fn eigenvalues(&self) -> Vec<Complex64> {
        self.modes.iter().map(|m| m.eigenvalue).collect()
    }

    /// The modes without the negative-frequency member of each oscillatory pair.
    pub fn distinct(&self) -> impl Iterator<Item = &Mode> {
        self.modes
            .iter()
            .filter(|m| !(m.kind == ModeKind::Oscillatory && m.eigenvalue.im < 0.0))
    }

    /// Whether every mode is [`Stability::Stable`].
    pub fn is_stable(&self) -> bool {
        self.modes.iter().all(|m| m.stability == Stability::Stable)
    }
}

/// The mode shape `phys · x` scaled so that its largest entry is exactly 0.5, and the
/// instantaneous centre of every body (six rows of `phys` each).
fn set_shape(mode: &mut Mode, mut shape: DVector<Complex64>, ss: &StateSpace<f64>, n: usize) {
    let nb = if ss.phys.nrows().is_multiple_of(6) {
        ss.phys.nrows() / 6
    } else {
        0
    };
    let body = |b: usize| {
        ss.names
            .bodies
            .get(b)
            .cloned()
            .unwrap_or_else(|| format!("body {}", b + 1))
    };
    let (idx, big) = shape.iter().enumerate().fold((0, 0.0), |(bi, bv), (i, z)| {
        if z.norm() > bv {
            (i, z.norm())
        } else {
            (bi, bv)
        }
    });
    if big > 0.0 {
        let f = shape[idx] * 2.0;
        shape.iter_mut().for_each(|z| *z /= f);
        shape[idx] = Complex64::new(0.5, 0.0);
        mode.reference_index = Some(idx);
        for b in 0..nb {
            mode.centres.push(instant_centre(
                body(b),
                &shape.as_slice()[6 * b..6 * b + 6],
                n,
            ));
        }
    } else {
        for b in 0..nb {
            mode.centres.push(InstantCentre {
                body: body(b),
                radius: None,
                axis: None,
            });
        }
    }
    mode.shape = shape;
}

/// Modes of a bare matrix (no shapes), with default options: used for automatic frequency
/// ranges and time horizons.
pub(crate) fn classify_matrix(a: &DMatrix<f64>) -> Result<Vec<Mode>, NumError> {
    let n = a.nrows();
    let eig = eigen_full(a, true, false)?;
    let f = ModeOptions::default().tol_factor;
    Ok((0..n)
        .map(|k| {
            let tol = f * n as f64 * f64::EPSILON * eig.norm * eig.condition[k];
            let mut m = classify(eig.values[k], tol);
            m.condition = eig.condition[k];
            m
        })
        .collect())
}

/// The error estimate of eigenvalue `k` of an `n × n` matrix, in 1/s: the tolerance of every
/// decision about it (zero, real, marginal). The larger of the eigensolver's first-order
/// bound `tol_factor · n · ε · ‖Ã‖_F · κ` (Ã balanced, κ the eigenvalue's condition number)
/// and the movement caused by rounding every entry of A, `ε · |y|ᵀ|A||x| / |yᴴx|`
/// (`componentwise`, 0 where not estimated).
pub fn error_estimate(
    n: usize,
    norm: f64,
    condition: f64,
    componentwise: f64,
    tol_factor: f64,
) -> f64 {
    (tol_factor * n as f64 * f64::EPSILON * norm * condition).max(f64::EPSILON * componentwise)
}

/// The one stability verdict on an eigenvalue (modes, sweeps, stable intervals, boundaries):
/// marginal when `|Re λ|` is within the eigenvalue's error estimate `tolerance` (its sign is
/// then not known), else stable or unstable by the sign of `Re λ`.
pub fn stability_of(re: f64, tolerance: f64) -> Stability {
    if re.abs() <= tolerance {
        Stability::Marginal
    } else if re < 0.0 {
        Stability::Stable
    } else {
        Stability::Unstable
    }
}

/// Every eigenvalue of `a`, sorted by (real, imaginary) part, with its error estimate
/// ([`error_estimate`] with the default `tol_factor`): what [`Modes::compute`] decides its
/// verdicts by, for callers that need the verdicts without the modes (a sweep).
///
/// Matrices of up to [`small_eigen::MAX_N`] states without structural zeros take the stack
/// path (the kernel's eigenvalues, the vectors by inverse iteration: `small_estimates`),
/// the others faer's eigenvectors ([`eigenvalues_with_errors_faer`]).
///
/// Errors: those of [`eigenvalues`], and [`NumError::TooLarge`] beyond the memory limit for
/// the eigenvectors.
pub fn eigenvalues_with_errors(a: &DMatrix<f64>) -> Result<Vec<(Complex64, f64)>, NumError> {
    check_square(a, "A")?;
    let n = a.nrows();
    if n <= small_eigen::MAX_N {
        let mut out = vec![(Complex64::new(0.0, 0.0), 0.0); n];
        if crate::small_estimates::eigenvalues_with_errors_small(a.as_slice(), n, &mut out)? {
            return Ok(out);
        }
    }
    eigenvalues_with_errors_faer(a)
}

/// [`eigenvalues_with_errors`] through faer's eigenvectors for every size: the path of
/// larger matrices and of those with structural zeros, public so that the stack path can be
/// compared with it.
///
/// Errors: as [`eigenvalues_with_errors`].
pub fn eigenvalues_with_errors_faer(a: &DMatrix<f64>) -> Result<Vec<(Complex64, f64)>, NumError> {
    check_square(a, "A")?;
    let n = a.nrows();
    let eig = eigen_full(a, true, true)?;
    let componentwise = eig.componentwise(a).unwrap_or_else(|| vec![0.0; n]);
    let f = ModeOptions::default().tol_factor;
    Ok((0..n)
        .map(|k| (eig.values[k], estimate_of(&eig, k, componentwise[k], f)))
        .collect())
}

/// [`error_estimate`] of eigenvalue `k` of a decomposition; 0 for an exact zero (a structural
/// zero deflated before the eigensolve: exact by construction, whatever the condition number
/// of its lifted vectors says).
fn estimate_of(eig: &crate::eigen::Eigen, k: usize, componentwise: f64, tol_factor: f64) -> f64 {
    if eig.values[k] == Complex64::new(0.0, 0.0) {
        return 0.0;
    }
    let n = eig.values.len();
    error_estimate(n, eig.norm, eig.condition[k], componentwise, tol_factor)
}

/// Modal quantities from one eigenvalue and its tolerance (no shape).
fn classify(lambda: Complex64, tol: f64) -> Mode {
    let (re, im) = (lambda.re, lambda.im);
    let stability = stability_of(re, tol);
    let marginal = stability == Stability::Marginal;
    let (kind, wn, zeta, tau, period) = if lambda.norm() <= tol {
        (ModeKind::Zero, 0.0, None, f64::INFINITY, f64::INFINITY)
    } else if im.abs() <= tol {
        let zeta = if re < 0.0 { 1.0 } else { -1.0 };
        let tau = if marginal { f64::INFINITY } else { -1.0 / re };
        (
            ModeKind::Real,
            re.abs() / (2.0 * PI),
            Some(zeta),
            tau,
            f64::INFINITY,
        )
    } else {
        let mag = lambda.norm();
        let (zeta, tau) = if marginal {
            (0.0, f64::INFINITY)
        } else {
            (-re / mag, -1.0 / re)
        };
        (
            ModeKind::Oscillatory,
            mag / (2.0 * PI),
            Some(zeta),
            tau,
            2.0 * PI / im.abs(),
        )
    };
    // A zero mode is marginal by definition of the tolerance.
    Mode {
        eigenvalue: lambda,
        kind,
        natural_frequency_hz: wn,
        damping_ratio: zeta,
        time_constant: tau,
        damped_period: period,
        stability,
        condition: 1.0,
        tolerance: tol,
        accuracy: 0.0,
        shape: DVector::zeros(0),
        reference_index: None,
        centres: Vec::new(),
    }
}

/// Instantaneous centre of one body from its six mode-shape entries (x, y, z, rx, ry, rz).
fn instant_centre(body: String, m: &[Complex64], n: usize) -> InstantCentre {
    let t = Vector3::new(m[0], m[1], m[2]);
    let w = Vector3::new(m[3], m[4], m[5]);
    let wn2: f64 = w.iter().map(|z| z.norm_sqr()).sum();
    let scale = m.iter().fold(0.0f64, |a, z| a.max(z.norm()));
    // A rotation at roundoff level relative to the body's own motion is no rotation.
    if wn2.sqrt() <= 10.0 * (n.max(1) as f64) * f64::EPSILON * scale || wn2 == 0.0 {
        return InstantCentre {
            body,
            radius: None,
            axis: None,
        };
    }
    let wc = w.map(|z| z.conj());
    let r = wc.cross(&t) / Complex64::new(wn2, 0.0);
    // Phase that makes the dominant rotation component real and positive (first of equals).
    let (l, _) = w.iter().enumerate().fold((0, -1.0), |(bi, bv), (i, z)| {
        if z.norm() > bv {
            (i, z.norm())
        } else {
            (bi, bv)
        }
    });
    let phase = Complex64::from_polar(1.0, -w[l].arg());
    let mut axis = w.map(|z| z * phase / wn2.sqrt());
    axis[l] = Complex64::new(axis[l].norm(), 0.0);
    InstantCentre {
        body,
        radius: Some(r),
        axis: Some(axis),
    }
}
