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
//! # Poles on the axis
//!
//! When a pivot of `sI − H` is below `10 · n · ε · (‖H‖_F + |s|)`, `s` is (numerically) an
//! eigenvalue: the response there is reported as `+∞` and flagged in
//! [`FrequencyResponse::singular`], never as a garbage finite number.
//!
//! # Frequency grid
//!
//! With [`FreqRange::Auto`], as EoM.jl (§7.5) but never failing: the nonzero eigenvalues
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
use faer::{Conj, Mat, Par};
use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::NumError;
use crate::linalg::balance_in_place;
use crate::modes::{ModeKind, classify_matrix};
use crate::statespace::StateSpace;

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
    /// Qᵀ B, row-major n × m.
    bt: Vec<f64>,
    /// C Q, row-major p × n.
    ct: Vec<f64>,
    /// D, column-major p × m.
    d: Vec<f64>,
    /// ‖H‖_F, scale of the singularity test.
    hnorm: f64,
}

/// Scratch space for [`HessenbergForm::evaluate_in`].
#[derive(Clone, Debug)]
pub struct FreqWorkspace {
    n: usize,
    m: usize,
    /// sI − H, row-major.
    lu: Vec<Complex64>,
    /// Right-hand sides / solution, row-major n × m.
    x: Vec<Complex64>,
}

impl FreqWorkspace {
    /// Workspace for `n` states and `m` inputs.
    pub fn new(n: usize, m: usize) -> Self {
        FreqWorkspace {
            n,
            m,
            lu: vec![Complex64::new(0.0, 0.0); n * n],
            x: vec![Complex64::new(0.0, 0.0); n * m],
        }
    }
}

/// Bytes held by a [`FreqWorkspace`] for `n` states and `m` inputs.
pub fn freq_workspace_bytes(n: usize, m: usize) -> usize {
    16 * (n * n + n * m)
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
            let bs = faer::linalg::qr::no_pivoting::factor::recommended_block_size::<f64>(
                n - 1,
                n - 1,
            );
            let mut householder = Mat::<f64>::zeros(bs, n - 1);
            let req = StackReq::any_of(&[
                hessenberg_in_place_scratch::<f64>(n, bs, Par::Seq, Default::default()),
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
                Par::Seq,
                MemStack::new(&mut buf),
                Default::default(),
            );
            apply_block_householder_sequence_on_the_right_in_place_with_conj(
                hm.as_ref().submatrix(1, 0, n - 1, n - 1),
                householder.as_ref(),
                Conj::No,
                q.as_mut().submatrix_mut(1, 1, n - 1, n - 1),
                Par::Seq,
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
                bt[i * m + j] = acc;
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
            return Err(NumError::Dimension(format!(
                "evaluate_in: model has n = {n}, m = {m}, p = {p}; workspace is for n = {}, \
                 m = {}; output has length {} (expected {})",
                ws.n,
                ws.m,
                out.len(),
                p * m
            )));
        }
        if !(s.re.is_finite() && s.im.is_finite()) {
            return Err(NumError::NonFinite(format!("evaluation point s = {s}")));
        }
        let zero = Complex64::new(0.0, 0.0);
        let lu = &mut ws.lu;
        let x = &mut ws.x;
        // sI − H (Hessenberg part only) and the right-hand sides.
        for i in 0..n {
            let lo = i.saturating_sub(1);
            for j in lo..n {
                lu[i * n + j] = Complex64::new(-self.h[i * n + j], 0.0);
            }
            lu[i * n + i] += s;
            for j in 0..m {
                x[i * m + j] = Complex64::new(self.bt[i * m + j], 0.0);
            }
        }
        // Elimination of the subdiagonal with partial pivoting between adjacent rows.
        for k in 0..n.saturating_sub(1) {
            let (top, bot) = lu.split_at_mut((k + 1) * n);
            let rk = &mut top[k * n..];
            let rk1 = &mut bot[..n];
            if l1(rk1[k]) > l1(rk[k]) {
                for j in k..n {
                    std::mem::swap(&mut rk[j], &mut rk1[j]);
                }
                for j in 0..m {
                    x.swap(k * m + j, (k + 1) * m + j);
                }
            }
            if rk[k] == zero {
                continue; // column already zero below the diagonal; singular pivot caught below
            }
            let l = rk1[k] / rk[k];
            rk1[k] = zero;
            for j in k + 1..n {
                let v = rk[j];
                rk1[j] -= l * v;
            }
            let (xt, xb) = x.split_at_mut((k + 1) * m);
            for j in 0..m {
                xb[j] -= l * xt[k * m + j];
            }
        }
        // Back substitution, checking pivots.
        let tol = 10.0 * n as f64 * f64::EPSILON * (self.hnorm + s.norm());
        for i in (0..n).rev() {
            let piv = lu[i * n + i];
            if !(piv.norm() > tol) {
                out.iter_mut()
                    .for_each(|o| *o = Complex64::new(f64::INFINITY, 0.0));
                return Ok(SolveStatus::Singular);
            }
            let (xa, xb) = x.split_at_mut((i + 1) * m);
            let xi = &mut xa[i * m..];
            for jj in i + 1..n {
                let u = lu[i * n + jj];
                let xr = &xb[(jj - i - 1) * m..(jj - i) * m];
                for c in 0..m {
                    xi[c] -= u * xr[c];
                }
            }
            let inv = piv.inv();
            for v in xi.iter_mut() {
                *v *= inv;
            }
        }
        // G = C̃ X + D.
        for j in 0..m {
            for i in 0..p {
                let mut acc = Complex64::new(self.d[j * p + i], 0.0);
                let crow = &self.ct[i * n..(i + 1) * n];
                for k in 0..n {
                    acc += x[k * m + j] * crow[k];
                }
                out[j * p + i] = acc;
            }
        }
        Ok(SolveStatus::Regular)
    }
}

#[inline]
fn l1(z: Complex64) -> f64 {
    z.re.abs() + z.im.abs()
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
        SolveStatus::Singular => Err(NumError::Singular(format!(
            "sI − A at s = {s} ({}×{} model): s is numerically an eigenvalue of A",
            ss.states(),
            ss.states()
        ))),
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
        let mut ws = form.workspace();
        let (_, m, p) = form.dims();
        let nf = omega.len();
        let mut values = vec![Complex64::new(0.0, 0.0); p * m * nf];
        let mut singular = vec![false; nf];
        let mut g = vec![Complex64::new(0.0, 0.0); p * m];
        for (k, &w) in omega.iter().enumerate() {
            let st = form.evaluate_in(Complex64::new(0.0, w), &mut ws, &mut g)?;
            singular[k] = st == SolveStatus::Singular;
            for j in 0..m {
                for i in 0..p {
                    values[(i * m + j) * nf + k] = g[j * p + i];
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
                let mag = z.norm();
                magnitude_db[base + k] = if singular[k] {
                    f64::INFINITY
                } else {
                    20.0 * mag.log10()
                };
                let ph = if singular[k] || mag == 0.0 {
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

/// The frequency grid in rad/s.
fn grid(ss: &StateSpace<f64>, opts: &FreqOptions) -> Result<Vec<f64>, NumError> {
    let ppd = opts.points_per_decade;
    let log_grid = |lo: f64, hi: f64| -> Vec<f64> {
        // lo, hi in log10(rad/s); inclusive, ppd points per decade.
        let steps = ((hi - lo) * ppd as f64).round().max(1.0) as usize;
        (0..=steps)
            .map(|k| 10f64.powf(lo + (hi - lo) * k as f64 / steps as f64))
            .collect()
    };
    match &opts.range {
        FreqRange::Points { values, unit } => {
            if let Some(v) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(NumError::InvalidOption(format!(
                    "FreqRange::Points contains {v}: frequencies must be finite and ≥ 0"
                )));
            }
            Ok(values.iter().map(|&f| unit.to_rad(f)).collect())
        }
        FreqRange::Range { low, high, unit } => {
            if ppd == 0 {
                return Err(NumError::InvalidOption(
                    "FreqOptions::points_per_decade = 0: must be ≥ 1".into(),
                ));
            }
            if !(low.is_finite() && high.is_finite() && *low > 0.0 && high > low) {
                return Err(NumError::InvalidOption(format!(
                    "FreqRange::Range {{ low: {low}, high: {high} }}: need 0 < low < high, finite"
                )));
            }
            Ok(log_grid(unit.to_rad(*low).log10(), unit.to_rad(*high).log10()))
        }
        FreqRange::Auto => {
            if ppd == 0 {
                return Err(NumError::InvalidOption(
                    "FreqOptions::points_per_decade = 0: must be ≥ 1".into(),
                ));
            }
            let (lo, hi) = auto_decades_hz(&ss.a)?;
            let to_w = (2.0 * PI).log10();
            Ok(log_grid(lo + to_w, hi + to_w))
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
