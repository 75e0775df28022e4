//! Frequency response `G(s) = C (sI − A)⁻¹ B + D` on the imaginary axis, for every
//! input/output pair.
//!
//! # Method
//!
//! A is balanced (diagonal similarity, powers of two) and reduced **once** to upper
//! Hessenberg form `A = Q H Qᵀ` (faer, Householder). Then `G(s) = C̃ (sI − H)⁻¹ B̃ + D` with
//! `B̃ = Qᵀ B`, `C̃ = C Q`, and each frequency costs one LU with partial pivoting of the
//! Hessenberg matrix `sI − H` (only adjacent rows are ever swapped, O(n²)), one triangular
//! solve with m right-hand sides (O(n² m)) and the product with C̃ (O(p n m)), instead of the
//! O(n³) dense LU per frequency. The bench `benches/freq.rs` measures the ratio.
//!
//! Two kernels implement this, both allocation-free with a caller-owned workspace:
//! [`HessenbergForm::evaluate_in`] (one point) and [`HessenbergForm::evaluate_batch_in`]
//! ([`LANES`] points at once, branch-free per-lane pivoting so that the lane loops vectorise;
//! compiled for AVX2 as well and selected at run time). [`FrequencyResponse::compute`] uses
//! the batched one.
//!
//! # Poles on the axis
//!
//! When a pivot of `sI − H` is below `10 · n · ε · (‖H‖_F + |s|)`, `s` is (numerically) an
//! eigenvalue: the response there is reported as `+∞` and flagged in
//! [`FrequencyResponse::singular`], never as a garbage finite number.
//!
//! # Frequency grid
//!
//! With [`FreqRange::Auto`], as in the EoM software but never failing: the nonzero eigenvalues
//! (zero ones decided scale-aware, see [`crate::modes`]) give `f = |λ|/2π`; the grid spans
//! the decades `floor(log10(f_min/2)) … ceil(log10(2 f_max))` (at least one decade), with
//! [`FreqOptions::points_per_decade`] points per decade (200 by default), endpoints included.
//! When every eigenvalue is zero (pure integrators, or no states) there is no time scale in
//! the model, and the grid is 0.01 … 100 Hz.
//!
//! Phase is **unwrapped** along frequency, per pair, in degrees: the first point lies in
//! (−180°, 180°], each next one within 180° of its predecessor.

use std::f64::consts::PI;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::hessenberg::{hessenberg_in_place, hessenberg_in_place_scratch};
use faer::linalg::householder::{
    apply_block_householder_sequence_on_the_right_in_place_scratch,
    apply_block_householder_sequence_on_the_right_in_place_with_conj,
};
use faer::{Conj, Mat};
use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::linalg::balance_in_place;
use crate::modes::{ModeKind, classify_matrix};
use crate::statespace::StateSpace;
use crate::{Bound, DimensionError, NonFiniteError, NumError, OptionError, SingularError};

/// Largest number of points of a generated grid (guards against gigabyte allocations from
/// a mistyped range or density).
pub const MAX_POINTS: usize = 10_000_000;

/// Unit of user-given frequencies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FreqUnit {
    /// Hertz (cycles per second), the default.
    #[default]
    Hz,
    /// Radians per second.
    RadPerSec,
}

impl FreqUnit {
    fn to_rad(self, f: f64) -> f64 {
        match self {
            FreqUnit::Hz => 2.0 * PI * f,
            FreqUnit::RadPerSec => f,
        }
    }
}

/// Which frequencies to evaluate.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum FreqRange {
    /// From the eigenvalues (see the module docs).
    #[default]
    Auto,
    /// Logarithmically spaced from `low` to `high` (both > 0, inclusive), with
    /// [`FreqOptions::points_per_decade`] points per decade.
    Range {
        /// Lowest frequency.
        low: f64,
        /// Highest frequency.
        high: f64,
        /// Unit of `low` and `high`.
        unit: FreqUnit,
    },
    /// Exactly these frequencies (≥ 0), in this order.
    Points {
        /// The frequencies.
        values: Vec<f64>,
        /// Their unit.
        unit: FreqUnit,
    },
}

/// Options of [`FrequencyResponse::compute`].
#[derive(Clone, Debug, PartialEq)]
pub struct FreqOptions {
    /// Frequencies (default [`FreqRange::Auto`]).
    pub range: FreqRange,
    /// Points per decade for [`FreqRange::Auto`] and [`FreqRange::Range`] (default 200).
    pub points_per_decade: usize,
}

impl Default for FreqOptions {
    fn default() -> Self {
        FreqOptions {
            range: FreqRange::Auto,
            points_per_decade: 200,
        }
    }
}

/// Whether a resolvent solve succeeded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SolveStatus {
    /// `sI − A` was regular; the output holds `G(s)`.
    Regular,
    /// `s` is numerically an eigenvalue of A; the output holds `+∞` everywhere.
    Singular,
}

/// A state-space model reduced to Hessenberg form, ready for repeated evaluation of `G(s)`.
///
/// ```
/// # use eom_num::{StateSpace, freq::{HessenbergForm, SolveStatus}};
/// # use nalgebra::dmatrix;
/// # use num_complex::Complex64;
/// let ss = StateSpace::new(dmatrix![0.0, 1.0; -4.0, -0.4], dmatrix![0.0; 1.0],
///                          dmatrix![1.0, 0.0], dmatrix![0.0]).unwrap();
/// let form = HessenbergForm::new(&ss).unwrap();
/// let mut ws = form.workspace();
/// let mut g = [Complex64::new(0.0, 0.0); 1];
/// let s = Complex64::new(0.0, 1.0);
/// assert_eq!(form.evaluate_in(s, &mut ws, &mut g).unwrap(), SolveStatus::Regular);
/// let exact = Complex64::new(1.0, 0.0) / (s * s + 0.4 * s + 4.0);
/// assert!((g[0] - exact).norm() < 1e-14);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HessenbergForm {
    n: usize,
    m: usize,
    p: usize,
    /// H, row-major n × n (entries below the subdiagonal are zero).
    h: Vec<f64>,
    /// Qᵀ B, column-major n × m.
    bt: Vec<f64>,
    /// C Q, row-major p × n.
    ct: Vec<f64>,
    /// D, column-major p × m.
    d: Vec<f64>,
    /// ‖H‖_F, scale of the singularity test.
    hnorm: f64,
}

/// Scratch space for [`HessenbergForm::evaluate_in`].
///
/// Complex quantities are stored as separate real and imaginary arrays, which keeps the
/// inner loops plain `f64` arithmetic.
#[derive(Clone, Debug)]
pub struct FreqWorkspace {
    n: usize,
    m: usize,
    /// sI − H and then its LU factors, row-major, real and imaginary parts.
    ur: Vec<f64>,
    ui: Vec<f64>,
    /// Right-hand sides / solution, column-major n × m, real and imaginary parts.
    xr: Vec<f64>,
    xi: Vec<f64>,
    /// Reciprocals of the pivots.
    pr: Vec<f64>,
    pi: Vec<f64>,
}

impl FreqWorkspace {
    /// Workspace for `n` states and `m` inputs.
    pub fn new(n: usize, m: usize) -> Self {
        FreqWorkspace {
            n,
            m,
            ur: vec![0.0; n * n],
            ui: vec![0.0; n * n],
            xr: vec![0.0; n * m],
            xi: vec![0.0; n * m],
            pr: vec![0.0; n],
            pi: vec![0.0; n],
        }
    }
}

/// Bytes held by a [`FreqWorkspace`] for `n` states and `m` inputs.
pub fn freq_workspace_bytes(n: usize, m: usize) -> usize {
    16 * (n * n + n * m + n)
}

impl HessenbergForm {
    /// Balances A and reduces it to Hessenberg form (O(n³), once).
    ///
    /// Errors: those of [`StateSpace::validate`].
    pub fn new(ss: &StateSpace<f64>) -> Result<Self, NumError> {
        ss.validate()?;
        let (n, m, p) = (ss.states(), ss.inputs(), ss.outputs());
        let mut a = ss.a.as_slice().to_vec();
        let mut scale = vec![1.0; n];
        balance_in_place(&mut a, n, &mut scale);
        let mut hm = Mat::<f64>::from_fn(n, n, |i, j| a[j * n + i]);
        let mut q = Mat::<f64>::identity(n, n);
        if n > 1 {
            let bs =
                faer::linalg::qr::no_pivoting::factor::recommended_block_size::<f64>(n - 1, n - 1);
            let par = crate::linalg::par(n);
            let mut householder = Mat::<f64>::zeros(bs, n - 1);
            let req = StackReq::any_of(&[
                hessenberg_in_place_scratch::<f64>(n, bs, par, Default::default()),
                apply_block_householder_sequence_on_the_right_in_place_scratch::<f64>(
                    n - 1,
                    bs,
                    n - 1,
                ),
            ]);
            let mut buf = MemBuffer::new(req);
            hessenberg_in_place(
                hm.as_mut(),
                householder.as_mut(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            );
            apply_block_householder_sequence_on_the_right_in_place_with_conj(
                hm.as_ref().submatrix(1, 0, n - 1, n - 1),
                householder.as_ref(),
                Conj::No,
                q.as_mut().submatrix_mut(1, 1, n - 1, n - 1),
                par,
                MemStack::new(&mut buf),
            );
            for j in 0..n {
                for i in j + 2..n {
                    hm[(i, j)] = 0.0;
                }
            }
        }
        // Balanced B̃ = D⁻¹B, C̃ = C D, then rotate: QᵀB̃, C̃Q.
        let mut h = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                h[i * n + j] = hm[(i, j)];
            }
        }
        let mut bt = vec![0.0; n * m];
        for i in 0..n {
            for j in 0..m {
                let mut acc = 0.0;
                for k in 0..n {
                    acc += q[(k, i)] * ss.b[(k, j)] / scale[k];
                }
                bt[j * n + i] = acc;
            }
        }
        let mut ct = vec![0.0; p * n];
        for i in 0..p {
            for j in 0..n {
                let mut acc = 0.0;
                for k in 0..n {
                    acc += ss.c[(i, k)] * scale[k] * q[(k, j)];
                }
                ct[i * n + j] = acc;
            }
        }
        let hnorm = h.iter().map(|x| x * x).sum::<f64>().sqrt();
        Ok(HessenbergForm {
            n,
            m,
            p,
            h,
            bt,
            ct,
            d: ss.d.as_slice().to_vec(),
            hnorm,
        })
    }

    /// A workspace of the right size.
    pub fn workspace(&self) -> FreqWorkspace {
        FreqWorkspace::new(self.n, self.m)
    }

    /// Numbers of states, inputs and outputs.
    pub fn dims(&self) -> (usize, usize, usize) {
        (self.n, self.m, self.p)
    }

    /// `G(s)` into `out` (p × m, column-major, length p·m), without allocation.
    ///
    /// Returns [`SolveStatus::Singular`] (and fills `out` with `+∞`) when `s` is numerically
    /// an eigenvalue of A.
    ///
    /// Errors: [`NumError::Dimension`] when the workspace or `out` has the wrong size,
    /// [`NumError::NonFinite`] for a non-finite `s`.
    pub fn evaluate_in(
        &self,
        s: Complex64,
        ws: &mut FreqWorkspace,
        out: &mut [Complex64],
    ) -> Result<SolveStatus, NumError> {
        let (n, m, p) = (self.n, self.m, self.p);
        if ws.n != n || ws.m != m || out.len() != p * m {
            return Err(NumError::Dimension(DimensionError::FreqWorkspace {
                function: "evaluate_in",
                n,
                m,
                p,
                workspace_n: ws.n,
                workspace_m: ws.m,
                out: out.len(),
                expected: p * m,
            }));
        }
        if !(s.re.is_finite() && s.im.is_finite()) {
            return Err(NumError::NonFinite(NonFiniteError::EvaluationPoint { s }));
        }
        let FreqWorkspace {
            ur,
            ui,
            xr,
            xi,
            pr,
            pi,
            ..
        } = ws;
        let h = &self.h;
        // sI − H (Hessenberg part only) and the right-hand sides.
        for i in 0..n {
            let lo = i.saturating_sub(1);
            let row = i * n;
            for (u, &hv) in ur[row + lo..row + n].iter_mut().zip(&h[row + lo..row + n]) {
                *u = -hv;
            }
            ui[row + lo..row + n].fill(0.0);
            ur[row + i] += s.re;
            ui[row + i] += s.im;
        }
        xr.copy_from_slice(&self.bt);
        xi.fill(0.0);
        // Elimination of the subdiagonal with partial pivoting between adjacent rows.
        for k in 0..n.saturating_sub(1) {
            let r0 = k * n;
            let r1 = r0 + n;
            let (top_r, bot_r) = ur.split_at_mut(r1);
            let (top_i, bot_i) = ui.split_at_mut(r1);
            let (u0r, u1r) = (&mut top_r[r0 + k..r0 + n], &mut bot_r[k..n]);
            let (u0i, u1i) = (&mut top_i[r0 + k..r0 + n], &mut bot_i[k..n]);
            if u1r[0].abs() + u1i[0].abs() > u0r[0].abs() + u0i[0].abs() {
                u0r.swap_with_slice(u1r);
                u0i.swap_with_slice(u1i);
                for c in 0..m {
                    xr.swap(c * n + k, c * n + k + 1);
                    xi.swap(c * n + k, c * n + k + 1);
                }
            }
            let (ar, ai, br, bi) = (u0r[0], u0i[0], u1r[0], u1i[0]);
            let d = ar * ar + ai * ai;
            if d == 0.0 {
                continue; // zero column below the diagonal; the singular pivot is caught below
            }
            // l = b / a
            let lr = (br * ar + bi * ai) / d;
            let li = (bi * ar - br * ai) / d;
            for (((a, b), &c), &e) in u1r[1..]
                .iter_mut()
                .zip(u1i[1..].iter_mut())
                .zip(&u0r[1..])
                .zip(&u0i[1..])
            {
                *a -= lr * c - li * e;
                *b -= lr * e + li * c;
            }
            for c in 0..m {
                let q = c * n + k;
                let (vr, vi) = (xr[q], xi[q]);
                xr[q + 1] -= lr * vr - li * vi;
                xi[q + 1] -= lr * vi + li * vr;
            }
        }
        // Pivots: a (numerically) zero one means s is an eigenvalue. Compare squares (no
        // hypot) and keep the reciprocals for the back substitution.
        let tol = 10.0 * n as f64 * f64::EPSILON * (self.hnorm + s.norm_sqr().sqrt());
        let tol2 = tol * tol;
        for i in 0..n {
            let (a, b) = (ur[i * n + i], ui[i * n + i]);
            let p2 = a * a + b * b;
            if p2.is_nan() || p2 <= tol2 {
                out.iter_mut()
                    .for_each(|o| *o = Complex64::new(f64::INFINITY, 0.0));
                return Ok(SolveStatus::Singular);
            }
            pr[i] = a / p2;
            pi[i] = -b / p2;
        }
        // Back substitution, one right-hand side at a time (contiguous dot products).
        for c in 0..m {
            let cr = &mut xr[c * n..(c + 1) * n];
            let ci = &mut xi[c * n..(c + 1) * n];
            for i in (0..n).rev() {
                let row_r = &ur[i * n + i + 1..(i + 1) * n];
                let row_i = &ui[i * n + i + 1..(i + 1) * n];
                let (mut sr, mut si) = (cr[i], ci[i]);
                for (((&a, &b), &v), &w) in
                    row_r.iter().zip(row_i).zip(&cr[i + 1..]).zip(&ci[i + 1..])
                {
                    sr -= a * v - b * w;
                    si -= a * w + b * v;
                }
                cr[i] = sr * pr[i] - si * pi[i];
                ci[i] = sr * pi[i] + si * pr[i];
            }
        }
        // G = C̃ X + D.
        for j in 0..m {
            let (cr, ci) = (&xr[j * n..(j + 1) * n], &xi[j * n..(j + 1) * n]);
            for i in 0..p {
                let crow = &self.ct[i * n..(i + 1) * n];
                let (mut gr, mut gi) = (self.d[j * p + i], 0.0);
                for ((&cv, &a), &b) in crow.iter().zip(cr).zip(ci) {
                    gr += cv * a;
                    gi += cv * b;
                }
                out[j * p + i] = Complex64::new(gr, gi);
            }
        }
        Ok(SolveStatus::Regular)
    }
}

/// `20 / ln 10`: dB per unit of `ln |G|`.
const DB_PER_NEPER: f64 = 20.0 / std::f64::consts::LN_10;

/// Number of frequencies evaluated together by [`HessenbergForm::evaluate_batch_in`].
pub const LANES: usize = 4;
type V = [f64; LANES];

#[inline(always)]
fn splat(x: f64) -> V {
    [x; LANES]
}

/// Workspace of the batched kernel: like [`FreqWorkspace`], one value per lane.
#[derive(Clone, Debug)]
pub struct FreqBatchWorkspace {
    n: usize,
    m: usize,
    ur: Vec<V>,
    ui: Vec<V>,
    xr: Vec<V>,
    xi: Vec<V>,
    pr: Vec<V>,
    pi: Vec<V>,
}

impl FreqBatchWorkspace {
    /// Workspace for `n` states and `m` inputs.
    pub fn new(n: usize, m: usize) -> Self {
        FreqBatchWorkspace {
            n,
            m,
            ur: vec![splat(0.0); n * n],
            ui: vec![splat(0.0); n * n],
            xr: vec![splat(0.0); n * m],
            xi: vec![splat(0.0); n * m],
            pr: vec![splat(0.0); n],
            pi: vec![splat(0.0); n],
        }
    }
}

/// The batched kernel: the same algorithm as `evaluate_in`, on [`LANES`] points at once.
/// Pivoting differs per lane and is done by branch-free selection, so every lane runs the
/// same instructions and the lane loops vectorise. Written once, compiled twice (baseline
/// and AVX2) by the callers below.
#[inline(always)]
fn batch_kernel(
    f: &HessenbergForm,
    s: &[Complex64; LANES],
    ws: &mut FreqBatchWorkspace,
    out: &mut [Complex64],
    singular: &mut [bool; LANES],
) {
    let (n, m, p) = (f.n, f.m, f.p);
    let FreqBatchWorkspace {
        ur,
        ui,
        xr,
        xi,
        pr,
        pi,
        ..
    } = ws;
    let sr: V = std::array::from_fn(|l| s[l].re);
    let si: V = std::array::from_fn(|l| s[l].im);
    for i in 0..n {
        let lo = i.saturating_sub(1);
        let row = i * n;
        for (u, &hv) in ur[row + lo..row + n]
            .iter_mut()
            .zip(&f.h[row + lo..row + n])
        {
            *u = splat(-hv);
        }
        ui[row + lo..row + n].fill(splat(0.0));
        for l in 0..LANES {
            ur[row + i][l] += sr[l];
        }
        ui[row + i] = si;
    }
    for (x, &b) in xr.iter_mut().zip(&f.bt) {
        *x = splat(b);
    }
    xi.fill(splat(0.0));
    for k in 0..n.saturating_sub(1) {
        let r0 = k * n;
        let r1 = r0 + n;
        let (top_r, bot_r) = ur.split_at_mut(r1);
        let (top_i, bot_i) = ui.split_at_mut(r1);
        let (u0r, u1r) = (&mut top_r[r0 + k..r0 + n], &mut bot_r[k..n]);
        let (u0i, u1i) = (&mut top_i[r0 + k..r0 + n], &mut bot_i[k..n]);
        let mut swap = [false; LANES];
        let mut lr = splat(0.0);
        let mut li = splat(0.0);
        for l in 0..LANES {
            let (ar, ai, br, bi) = (u0r[0][l], u0i[0][l], u1r[0][l], u1i[0][l]);
            swap[l] = br.abs() + bi.abs() > ar.abs() + ai.abs();
            let (pr_, pi_, or_, oi_) = if swap[l] {
                (br, bi, ar, ai)
            } else {
                (ar, ai, br, bi)
            };
            let d = pr_ * pr_ + pi_ * pi_;
            // A zero column below the diagonal: nothing to eliminate (l = 0); the singular
            // pivot is caught below.
            if d > 0.0 {
                lr[l] = (or_ * pr_ + oi_ * pi_) / d;
                li[l] = (oi_ * pr_ - or_ * pi_) / d;
            }
            u0r[0][l] = pr_;
            u0i[0][l] = pi_;
            u1r[0][l] = 0.0;
            u1i[0][l] = 0.0;
        }
        for (((a0, a1), b0), b1) in u0r[1..]
            .iter_mut()
            .zip(u1r[1..].iter_mut())
            .zip(u0i[1..].iter_mut())
            .zip(u1i[1..].iter_mut())
        {
            for l in 0..LANES {
                let (t_r, t_i, w_r, w_i) = if swap[l] {
                    (a1[l], b1[l], a0[l], b0[l])
                } else {
                    (a0[l], b0[l], a1[l], b1[l])
                };
                a0[l] = t_r;
                b0[l] = t_i;
                a1[l] = w_r - (lr[l] * t_r - li[l] * t_i);
                b1[l] = w_i - (lr[l] * t_i + li[l] * t_r);
            }
        }
        for c in 0..m {
            let q = c * n + k;
            for l in 0..LANES {
                let (t_r, t_i, w_r, w_i) = if swap[l] {
                    (xr[q + 1][l], xi[q + 1][l], xr[q][l], xi[q][l])
                } else {
                    (xr[q][l], xi[q][l], xr[q + 1][l], xi[q + 1][l])
                };
                xr[q][l] = t_r;
                xi[q][l] = t_i;
                xr[q + 1][l] = w_r - (lr[l] * t_r - li[l] * t_i);
                xi[q + 1][l] = w_i - (lr[l] * t_i + li[l] * t_r);
            }
        }
    }
    let mut tol2 = splat(0.0);
    for l in 0..LANES {
        let t = 10.0 * n as f64 * f64::EPSILON * (f.hnorm + s[l].norm_sqr().sqrt());
        tol2[l] = t * t;
        singular[l] = false;
    }
    for i in 0..n {
        for l in 0..LANES {
            let (a, b) = (ur[i * n + i][l], ui[i * n + i][l]);
            let p2 = a * a + b * b;
            if p2 > tol2[l] {
                pr[i][l] = a / p2;
                pi[i][l] = -b / p2;
            } else {
                singular[l] = true;
                pr[i][l] = 0.0;
                pi[i][l] = 0.0;
            }
        }
    }
    for c in 0..m {
        let cr = &mut xr[c * n..(c + 1) * n];
        let ci = &mut xi[c * n..(c + 1) * n];
        for i in (0..n).rev() {
            let row_r = &ur[i * n + i + 1..(i + 1) * n];
            let row_i = &ui[i * n + i + 1..(i + 1) * n];
            let (mut sr_, mut si_) = (cr[i], ci[i]);
            for (((a, b), v), w) in row_r.iter().zip(row_i).zip(&cr[i + 1..]).zip(&ci[i + 1..]) {
                for l in 0..LANES {
                    sr_[l] -= a[l] * v[l] - b[l] * w[l];
                    si_[l] -= a[l] * w[l] + b[l] * v[l];
                }
            }
            for l in 0..LANES {
                cr[i][l] = sr_[l] * pr[i][l] - si_[l] * pi[i][l];
                ci[i][l] = sr_[l] * pi[i][l] + si_[l] * pr[i][l];
            }
        }
    }
    let pm = p * m;
    for j in 0..m {
        let (cr, ci) = (&xr[j * n..(j + 1) * n], &xi[j * n..(j + 1) * n]);
        for i in 0..p {
            let crow = &f.ct[i * n..(i + 1) * n];
            let mut gr = splat(f.d[j * p + i]);
            let mut gi = splat(0.0);
            for ((&cv, a), b) in crow.iter().zip(cr).zip(ci) {
                for l in 0..LANES {
                    gr[l] += cv * a[l];
                    gi[l] += cv * b[l];
                }
            }
            for l in 0..LANES {
                out[l * pm + j * p + i] = if singular[l] {
                    Complex64::new(f64::INFINITY, 0.0)
                } else {
                    Complex64::new(gr[l], gi[l])
                };
            }
        }
    }
}

fn batch_baseline(
    f: &HessenbergForm,
    s: &[Complex64; LANES],
    ws: &mut FreqBatchWorkspace,
    out: &mut [Complex64],
    singular: &mut [bool; LANES],
) {
    batch_kernel(f, s, ws, out, singular)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn batch_avx2(
    f: &HessenbergForm,
    s: &[Complex64; LANES],
    ws: &mut FreqBatchWorkspace,
    out: &mut [Complex64],
    singular: &mut [bool; LANES],
) {
    batch_kernel(f, s, ws, out, singular)
}

impl HessenbergForm {
    /// A workspace for [`HessenbergForm::evaluate_batch_in`].
    pub fn batch_workspace(&self) -> FreqBatchWorkspace {
        FreqBatchWorkspace::new(self.n, self.m)
    }

    /// `G(sₗ)` for [`LANES`] points at once, without allocation: `out` (length
    /// `LANES·p·m`) receives one column-major p × m block per point; `status[l]` tells
    /// whether point l was regular (see [`HessenbergForm::evaluate_in`], whose results this
    /// reproduces up to rounding). Uses AVX2 when the CPU has it.
    ///
    /// Errors: [`NumError::Dimension`] for a wrong workspace or `out` size,
    /// [`NumError::NonFinite`] for a non-finite point.
    pub fn evaluate_batch_in(
        &self,
        s: &[Complex64; LANES],
        ws: &mut FreqBatchWorkspace,
        out: &mut [Complex64],
        status: &mut [SolveStatus; LANES],
    ) -> Result<(), NumError> {
        let (n, m, p) = (self.n, self.m, self.p);
        if ws.n != n || ws.m != m || out.len() != LANES * p * m {
            return Err(NumError::Dimension(DimensionError::FreqWorkspace {
                function: "evaluate_batch_in",
                n,
                m,
                p,
                workspace_n: ws.n,
                workspace_m: ws.m,
                out: out.len(),
                expected: LANES * p * m,
            }));
        }
        if let Some(z) = s.iter().find(|z| !(z.re.is_finite() && z.im.is_finite())) {
            return Err(NumError::NonFinite(NonFiniteError::EvaluationPoint {
                s: *z,
            }));
        }
        let mut singular = [false; LANES];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2 (checked just above).
                #[allow(unsafe_code)]
                unsafe {
                    batch_avx2(self, s, ws, out, &mut singular)
                };
            } else {
                batch_baseline(self, s, ws, out, &mut singular);
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        batch_baseline(self, s, ws, out, &mut singular);
        for (st, &sg) in status.iter_mut().zip(&singular) {
            *st = if sg {
                SolveStatus::Singular
            } else {
                SolveStatus::Regular
            };
        }
        Ok(())
    }
}

/// `G(s)` at one complex point (allocating convenience).
///
/// Errors: those of [`StateSpace::validate`], [`NumError::NonFinite`] for a non-finite `s`,
/// [`NumError::Singular`] when `s` is numerically an eigenvalue of A.
pub fn evaluate_at(ss: &StateSpace<f64>, s: Complex64) -> Result<DMatrix<Complex64>, NumError> {
    let form = HessenbergForm::new(ss)?;
    let mut ws = form.workspace();
    let (_, m, p) = form.dims();
    let mut out = vec![Complex64::new(0.0, 0.0); p * m];
    match form.evaluate_in(s, &mut ws, &mut out)? {
        SolveStatus::Regular => Ok(DMatrix::from_vec(p, m, out)),
        SolveStatus::Singular => Err(NumError::Singular(SingularError::Eigenvalue {
            s,
            n: ss.states(),
        })),
    }
}

/// Frequency response of every input/output pair on a frequency grid.
#[derive(Clone, Debug, PartialEq)]
pub struct FrequencyResponse {
    /// Frequencies in Hz.
    pub freq_hz: Vec<f64>,
    /// The same frequencies in rad/s.
    pub omega: Vec<f64>,
    /// Number of outputs p.
    pub outputs: usize,
    /// Number of inputs m.
    pub inputs: usize,
    /// `G(jω)`, stored per pair along frequency: index `(i·m + j)·nf + k` for output i,
    /// input j, frequency k. Use [`FrequencyResponse::series`].
    pub values: Vec<Complex64>,
    /// `20 log10 |G|` in dB, same layout (`+∞` at flagged poles, `−∞` for an exact zero).
    pub magnitude_db: Vec<f64>,
    /// Unwrapped phase in degrees, same layout. At a flagged pole or an exact zero of G,
    /// where the phase is undefined, the previous value is carried (0 at the first point).
    pub phase_deg: Vec<f64>,
    /// Per frequency: `true` when jω is numerically an eigenvalue of A (values are `+∞`).
    pub singular: Vec<bool>,
}

impl FrequencyResponse {
    /// Evaluates the response (see the module docs).
    ///
    /// Errors: those of [`StateSpace::validate`]; [`NumError::InvalidOption`] for a bad
    /// range (non-positive or non-finite limits, `low ≥ high`, negative points) or zero
    /// points per decade; [`NumError::NoConvergence`] from the eigenvalues of
    /// [`FreqRange::Auto`].
    pub fn compute(ss: &StateSpace<f64>, opts: &FreqOptions) -> Result<Self, NumError> {
        ss.validate()?;
        let omega = grid(ss, opts)?;
        let form = HessenbergForm::new(ss)?;
        let mut ws = form.batch_workspace();
        let (_, m, p) = form.dims();
        let nf = omega.len();
        let pm = p * m;
        // Complex values, magnitudes and phases of every pair at every frequency.
        crate::budget::check(
            "the frequency response",
            crate::budget::product(&[pm.max(1), nf, 16 + 8 + 8]),
        )?;
        let mut values = vec![Complex64::new(0.0, 0.0); pm * nf];
        let mut singular = vec![false; nf];
        let mut g = vec![Complex64::new(0.0, 0.0); LANES * pm];
        let mut status = [SolveStatus::Regular; LANES];
        for k0 in (0..nf).step_by(LANES) {
            // The last batch is padded by repeating its last point.
            let pts: [Complex64; LANES] =
                std::array::from_fn(|l| Complex64::new(0.0, omega[(k0 + l).min(nf - 1)]));
            form.evaluate_batch_in(&pts, &mut ws, &mut g, &mut status)?;
            for l in 0..LANES.min(nf - k0) {
                let k = k0 + l;
                singular[k] = status[l] == SolveStatus::Singular;
                for j in 0..m {
                    for i in 0..p {
                        values[(i * m + j) * nf + k] = g[l * pm + j * p + i];
                    }
                }
            }
        }
        let mut magnitude_db = vec![0.0; values.len()];
        let mut phase_deg = vec![0.0; values.len()];
        for pair in 0..p * m {
            let base = pair * nf;
            let mut prev: Option<f64> = None;
            for k in 0..nf {
                let z = values[base + k];
                // |G| by `hypot`, not |G|²: the square of a magnitude below 1e-162 underflows
                // to zero (a velocity's response at 1e-170 Hz is −3404 dB, not −∞ and 0°).
                let zero = z.re == 0.0 && z.im == 0.0;
                magnitude_db[base + k] = if singular[k] {
                    f64::INFINITY
                } else {
                    DB_PER_NEPER * z.norm().ln()
                };
                let ph = if singular[k] || zero {
                    prev.unwrap_or(0.0)
                } else {
                    let raw = z.arg().to_degrees();
                    match prev {
                        None => raw,
                        Some(q) => raw + 360.0 * ((q - raw) / 360.0).round(),
                    }
                };
                phase_deg[base + k] = ph;
                prev = Some(ph);
            }
        }
        Ok(FrequencyResponse {
            freq_hz: omega.iter().map(|w| w / (2.0 * PI)).collect(),
            omega,
            outputs: p,
            inputs: m,
            values,
            magnitude_db,
            phase_deg,
            singular,
        })
    }

    /// Number of frequencies.
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// Whether the grid is empty.
    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    fn range(&self, output: usize, input: usize) -> std::ops::Range<usize> {
        assert!(
            output < self.outputs && input < self.inputs,
            "pair ({output}, {input}) out of range ({} outputs, {} inputs)",
            self.outputs,
            self.inputs
        );
        let nf = self.len();
        let base = (output * self.inputs + input) * nf;
        base..base + nf
    }

    /// `G_{output,input}(jω)` along frequency. Panics if the pair is out of range.
    pub fn series(&self, output: usize, input: usize) -> &[Complex64] {
        &self.values[self.range(output, input)]
    }

    /// Magnitude in dB of one pair along frequency. Panics if the pair is out of range.
    pub fn magnitude_db_of(&self, output: usize, input: usize) -> &[f64] {
        &self.magnitude_db[self.range(output, input)]
    }

    /// Unwrapped phase in degrees of one pair along frequency. Panics if out of range.
    pub fn phase_deg_of(&self, output: usize, input: usize) -> &[f64] {
        &self.phase_deg[self.range(output, input)]
    }
}

/// The error for `FreqOptions::points_per_decade = 0`.
fn no_points_per_decade() -> NumError {
    NumError::InvalidOption(OptionError::Value {
        option: "FreqOptions::points_per_decade",
        value: 0.0,
        must: Bound::AtLeastOne,
    })
}

/// The frequency grid in rad/s.
fn grid(ss: &StateSpace<f64>, opts: &FreqOptions) -> Result<Vec<f64>, NumError> {
    let ppd = opts.points_per_decade;
    let log_grid = |lo: f64, hi: f64| -> Result<Vec<f64>, NumError> {
        // lo, hi in log10(rad/s); inclusive, ppd points per decade.
        let steps = ((hi - lo) * ppd as f64).round().max(1.0);
        if steps > MAX_POINTS as f64 {
            return Err(NumError::InvalidOption(
                OptionError::FrequencyGridTooLarge {
                    points: steps,
                    decades: hi - lo,
                    per_decade: ppd,
                    limit: MAX_POINTS,
                },
            ));
        }
        let steps = steps as usize;
        Ok((0..=steps)
            .map(|k| 10f64.powf(lo + (hi - lo) * k as f64 / steps as f64))
            .collect())
    };
    match &opts.range {
        FreqRange::Points { values, unit } => {
            if let Some(v) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(NumError::InvalidOption(OptionError::FrequencyPoint {
                    value: *v,
                }));
            }
            Ok(values.iter().map(|&f| unit.to_rad(f)).collect())
        }
        FreqRange::Range { low, high, unit } => {
            if ppd == 0 {
                return Err(no_points_per_decade());
            }
            if !(low.is_finite() && high.is_finite() && *low > 0.0 && high > low) {
                return Err(NumError::InvalidOption(OptionError::FrequencyRange {
                    low: *low,
                    high: *high,
                }));
            }
            log_grid(unit.to_rad(*low).log10(), unit.to_rad(*high).log10())
        }
        FreqRange::Auto => {
            if ppd == 0 {
                return Err(no_points_per_decade());
            }
            let (lo, hi) = auto_decades_hz(&ss.a)?;
            let to_w = (2.0 * PI).log10();
            log_grid(lo + to_w, hi + to_w)
        }
    }
}

/// Decades (log10 Hz, integers) of the automatic grid.
pub(crate) fn auto_decades_hz(a: &DMatrix<f64>) -> Result<(f64, f64), NumError> {
    let modes = classify_matrix(a)?;
    let f: Vec<f64> = modes
        .iter()
        .filter(|m| m.kind != ModeKind::Zero)
        .map(|m| m.eigenvalue.norm() / (2.0 * PI))
        .collect();
    if f.is_empty() {
        return Ok((-2.0, 2.0));
    }
    let fmin = f.iter().cloned().fold(f64::INFINITY, f64::min);
    let fmax = f.iter().cloned().fold(0.0, f64::max);
    let mut lo = (0.5 * fmin).log10().floor();
    let hi = (2.0 * fmax).log10().ceil();
    if hi - lo < 1.0 {
        lo = hi - 1.0;
    }
    Ok((lo, hi))
}
