//! Time responses by exact zero-order-hold discretisation.
//!
//! `Φ = e^{A Δt}` and `Γ = ∫₀^Δt e^{Aτ} dτ B` come from one matrix exponential of the
//! augmented matrix `[[A, B], [0, 0]] Δt` (nalgebra's Padé scaling-and-squaring `exp`):
//! its top blocks are `[Φ Γ]`. Then `x_{k+1} = Φ x_k + Γ u_k` is *exact* for inputs that are
//! constant over each step (steps, sampled inputs held by a ZOH), whatever Δt.
//!
//! * [`impulse`]: `u = δ(t)` on each input in turn: `x(0⁺) = B`, `y(t) = C e^{At} B` for
//!   t > 0, **plus** `D δ(t)`, which a sampled signal cannot hold; it is returned explicitly
//!   in [`TimeResponse::direct`] instead of being dropped.
//! * [`step`]: unit step on each input in turn, `y = C x + D`.
//! * [`simulate`]: one trajectory for a sampled input `u_k` held over each step, from `x₀`.
//!
//! All output storage is allocated before the stepping loop; the loop itself does not
//! allocate.
//!
//! # Automatic horizon
//!
//! From the modes (zero modes decided scale-aware, see [`crate::modes`]): every real mode
//! asks for `5|τ|` (99.3 % settled), every oscillatory one for `5|τ|` clamped to 2…50 damped
//! periods; the horizon is the largest request. The step is the smallest of `|τ|/10` (real)
//! and `period/20` (oscillatory). When that would exceed [`TimeOptions::max_steps`], the step
//! is enlarged (the result stays exact at the samples, only coarser) and
//! [`TimeResponse::message`] says so. Without any nonzero mode there is no time scale: 10 s
//! in steps of 0.01 s.
//!
//! # Unstable responses
//!
//! The response stops cleanly when an output exceeds the size limit (default
//! `1e6 ×` the reference scale of [`SizeLimit::Relative`]) or a state becomes non-finite, and
//! the partial history is returned with a [`StopReason`] and a message.

use nalgebra::{DMatrix, DMatrixView, DMatrixViewMut, DVector};

use crate::linalg::max_abs;
use crate::modes::{ModeKind, classify_matrix};
use crate::statespace::{StateSpace, check_finite};
use crate::{Bound, DimensionError, NonFiniteError, NumError, OptionError};

/// Largest number of samples of a time grid ([`Horizon::Given`], [`TimeOptions::max_steps`]):
/// guards against a typo such as a step in ms given as s allocating gigabytes.
pub const MAX_SAMPLES: usize = 50_000_000;

/// Horizon and step of a time response.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Horizon {
    /// From the eigenvalues (see the module docs).
    #[default]
    Auto,
    /// Explicit end time and step (s), both finite and > 0; the grid is
    /// `0, Δt, …, round(t_end/Δt)·Δt`.
    Given {
        /// End time in s.
        t_end: f64,
        /// Step in s.
        dt: f64,
    },
}

/// When an (unstable) response is stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeLimit {
    /// Stop when `|y| > factor × reference`. The reference is `max|C| · max|B|` for an
    /// impulse, `max|C| · max|B| · t_end + max|D|` for a step, and
    /// `max|C| · (max|B| · max|u| · t_end + max|x₀|) + max|D| · max|u|` for [`simulate`]: a
    /// bound on the early response, in the units of the outputs.
    Relative(f64),
    /// Stop when `|y|` exceeds this absolute value.
    Absolute(f64),
}

/// Options of [`impulse`], [`step`] and [`simulate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeOptions {
    /// Horizon and step (default [`Horizon::Auto`]; ignored by [`simulate`], whose grid
    /// comes from the input samples).
    pub horizon: Horizon,
    /// Size limit (default `Relative(1e6)`).
    pub size_limit: SizeLimit,
    /// Largest number of samples for [`Horizon::Auto`] (default 10 001).
    pub max_steps: usize,
}

impl Default for TimeOptions {
    fn default() -> Self {
        TimeOptions {
            horizon: Horizon::Auto,
            size_limit: SizeLimit::Relative(1e6),
            max_steps: 10_001,
        }
    }
}

/// Why a response ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StopReason {
    /// The whole horizon was computed.
    Completed,
    /// An output exceeded the size limit at sample `step`.
    SizeLimit {
        /// Index of the first sample over the limit (included in the history).
        step: usize,
        /// The offending |y|.
        value: f64,
        /// The limit.
        limit: f64,
    },
    /// A state became NaN or infinite at sample `step` (not included).
    NonFinite {
        /// Index of the sample that could not be computed.
        step: usize,
    },
}

/// A sampled response: per sample, a p × r block (r = inputs for impulse/step, 1 for
/// [`simulate`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TimeResponse {
    /// Sample times (s), starting at 0.
    pub t: Vec<f64>,
    /// The step Δt (s).
    pub dt: f64,
    /// Number of outputs p.
    pub outputs: usize,
    /// Number of response columns r (one per input for impulse/step, 1 for a simulation).
    pub columns: usize,
    /// Samples: index `(k·r + j)·p + i` for output i, column j, sample k (each sample a
    /// column-major p × r block, see [`TimeResponse::at`]).
    pub y: Vec<f64>,
    /// For [`impulse`]: `D`, the weight of the `D δ(t)` term of the impulse response at
    /// t = 0, which is not in the samples. `None` for other responses.
    pub direct: Option<DMatrix<f64>>,
    /// Why the response ended.
    pub stop: StopReason,
    /// Explanation when the response stopped early or the automatic step was coarsened.
    pub message: Option<String>,
}

impl TimeResponse {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Sample k as a p × r matrix view. Panics if out of range.
    pub fn at(&self, k: usize) -> DMatrixView<'_, f64> {
        let pr = self.outputs * self.columns;
        DMatrixView::from_slice(&self.y[k * pr..(k + 1) * pr], self.outputs, self.columns)
    }

    /// Output `output` for column `column` along time. Panics if out of range.
    pub fn series(&self, output: usize, column: usize) -> Vec<f64> {
        assert!(output < self.outputs && column < self.columns);
        let pr = self.outputs * self.columns;
        (0..self.len())
            .map(|k| self.y[k * pr + column * self.outputs + output])
            .collect()
    }
}

/// An exact ZOH discretisation.
#[derive(Clone, Debug, PartialEq)]
pub struct Discretization {
    /// `Φ = e^{A Δt}`, n × n.
    pub phi: DMatrix<f64>,
    /// `Γ = ∫₀^Δt e^{Aτ} dτ B`, n × m.
    pub gamma: DMatrix<f64>,
    /// The step Δt.
    pub dt: f64,
}

/// ZOH discretisation of `ss` with step `dt` (see the module docs).
///
/// Errors: those of [`StateSpace::validate`], [`NumError::InvalidOption`] for a non-positive
/// or non-finite `dt`, [`NumError::NonFinite`] when the exponential overflows.
pub fn zoh(ss: &StateSpace<f64>, dt: f64) -> Result<Discretization, NumError> {
    ss.validate()?;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(NumError::InvalidOption(OptionError::Value {
            option: "time step dt",
            value: dt,
            must: Bound::FinitePositive,
        }));
    }
    let (n, m) = (ss.states(), ss.inputs());
    let mut aug = DMatrix::<f64>::zeros(n + m, n + m);
    aug.view_mut((0, 0), (n, n)).copy_from(&(&ss.a * dt));
    aug.view_mut((0, n), (n, m)).copy_from(&(&ss.b * dt));
    let e = if n + m == 0 { aug } else { aug.exp() };
    let phi = e.view((0, 0), (n, n)).into_owned();
    let gamma = e.view((0, n), (n, m)).into_owned();
    check_finite(&phi, &format!("Φ = exp(A·{dt})"))?;
    check_finite(&gamma, &format!("Γ (ZOH input matrix, dt = {dt})"))?;
    Ok(Discretization { phi, gamma, dt })
}

/// Chooses (t_end, dt, note) from the modes.
fn auto_horizon(
    a: &DMatrix<f64>,
    max_steps: usize,
) -> Result<(f64, f64, Option<String>), NumError> {
    let modes = classify_matrix(a)?;
    let mut t_end: f64 = 0.0;
    let mut dt = f64::INFINITY;
    for md in &modes {
        match md.kind {
            ModeKind::Zero => {}
            ModeKind::Real => {
                // A real mode is never marginal unless zero, so τ is finite here.
                let tau = md.time_constant.abs();
                if tau.is_finite() {
                    t_end = t_end.max(5.0 * tau);
                    dt = dt.min(tau / 10.0);
                }
            }
            ModeKind::Oscillatory => {
                let period = md.damped_period;
                let tau = md.time_constant.abs();
                let want = if tau.is_finite() {
                    5.0 * tau
                } else {
                    f64::INFINITY
                };
                t_end = t_end.max(want.clamp(2.0 * period, 50.0 * period));
                dt = dt.min(period / 20.0);
                if tau.is_finite() {
                    dt = dt.min(tau / 10.0);
                }
            }
        }
    }
    if t_end.is_nan() || t_end <= 0.0 || !dt.is_finite() {
        return Ok((10.0, 0.01, None));
    }
    let steps = (t_end / dt).ceil() + 1.0;
    if steps > max_steps as f64 {
        let coarse = t_end / (max_steps.max(2) - 1) as f64;
        let note = format!(
            "automatic step enlarged from {dt:.3e} s to {coarse:.3e} s to keep {max_steps} \
             samples over {t_end:.3e} s (the fastest modes are under-resolved, samples stay exact)"
        );
        return Ok((t_end, coarse, Some(note)));
    }
    Ok((t_end, dt, None))
}

pub(crate) fn grid(
    ss: &StateSpace<f64>,
    opts: &TimeOptions,
) -> Result<(usize, f64, Option<String>), NumError> {
    match opts.horizon {
        Horizon::Given { t_end, dt } => {
            if !(t_end.is_finite() && t_end > 0.0) {
                return Err(NumError::InvalidOption(OptionError::Value {
                    option: "Horizon::Given t_end",
                    value: t_end,
                    must: Bound::FinitePositive,
                }));
            }
            if !(dt.is_finite() && dt > 0.0) {
                return Err(NumError::InvalidOption(OptionError::Value {
                    option: "Horizon::Given dt",
                    value: dt,
                    must: Bound::FinitePositive,
                }));
            }
            let steps = (t_end / dt).round();
            if steps > MAX_SAMPLES as f64 {
                return Err(NumError::InvalidOption(OptionError::TooManySamples {
                    t_end,
                    dt,
                    samples: steps,
                    limit: MAX_SAMPLES,
                }));
            }
            Ok(((steps as usize + 1).max(2), dt, None))
        }
        Horizon::Auto => {
            if opts.max_steps < 2 || opts.max_steps > MAX_SAMPLES {
                return Err(NumError::InvalidOption(OptionError::Value {
                    option: "TimeOptions::max_steps",
                    value: opts.max_steps as f64,
                    must: Bound::Between(2, MAX_SAMPLES),
                }));
            }
            let (t_end, dt, note) = auto_horizon(&ss.a, opts.max_steps)?;
            let nt = ((t_end / dt).round() as usize + 1).min(opts.max_steps);
            Ok((nt.max(2), dt, note))
        }
    }
}

fn limit_of(opts: &TimeOptions, reference: f64) -> Result<f64, NumError> {
    match opts.size_limit {
        SizeLimit::Relative(f) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(NumError::InvalidOption(OptionError::SizeLimit {
                    kind: "Relative",
                    value: f,
                    must: Bound::FinitePositive,
                }));
            }
            // A zero reference means y ≡ 0 (C = 0 or no input path): nothing to limit.
            Ok(if reference > 0.0 {
                f * reference
            } else {
                f64::INFINITY
            })
        }
        SizeLimit::Absolute(v) => {
            if v.is_nan() || v <= 0.0 {
                return Err(NumError::InvalidOption(OptionError::SizeLimit {
                    kind: "Absolute",
                    value: v,
                    must: Bound::Positive,
                }));
            }
            Ok(v)
        }
    }
}

/// The stepping loop shared by impulse and step: X ← Φ X + G (G optional), Y = C X + F.
/// Writes samples 0..nt into `y`; returns the number of samples kept and the stop reason.
#[allow(clippy::too_many_arguments)]
fn run(
    phi: &DMatrix<f64>,
    forcing: Option<&DMatrix<f64>>,
    c: &DMatrix<f64>,
    feed: Option<&DMatrix<f64>>,
    x0: DMatrix<f64>,
    nt: usize,
    limit: f64,
    y: &mut [f64],
) -> (usize, StopReason) {
    let (p, r) = (c.nrows(), x0.ncols());
    let pr = p * r;
    let mut x = x0;
    let mut xn = x.clone();
    for k in 0..nt {
        if x.iter().any(|v| !v.is_finite()) {
            return (k, StopReason::NonFinite { step: k });
        }
        let mut yk = DMatrixViewMut::from_slice(&mut y[k * pr..(k + 1) * pr], p, r);
        match feed {
            Some(f) => yk.copy_from(f),
            None => yk.fill(0.0),
        }
        yk.gemm(1.0, c, &x, 1.0);
        let big = yk.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if big > limit || !big.is_finite() {
            return (
                k + 1,
                StopReason::SizeLimit {
                    step: k,
                    value: big,
                    limit,
                },
            );
        }
        if k + 1 < nt {
            match forcing {
                Some(g) => xn.copy_from(g),
                None => xn.fill(0.0),
            }
            xn.gemm(1.0, phi, &x, 1.0);
            std::mem::swap(&mut x, &mut xn);
        }
    }
    (nt, StopReason::Completed)
}

#[allow(clippy::too_many_arguments)]
fn finish(
    nt_kept: usize,
    nt: usize,
    dt: f64,
    p: usize,
    r: usize,
    mut y: Vec<f64>,
    direct: Option<DMatrix<f64>>,
    stop: StopReason,
    note: Option<String>,
) -> TimeResponse {
    y.truncate(nt_kept * p * r);
    let t = (0..nt_kept).map(|k| k as f64 * dt).collect();
    let why = match stop {
        StopReason::Completed => None,
        StopReason::SizeLimit { step, value, limit } => Some(format!(
            "stopped at t = {:.6e} s (sample {step} of {nt}): |y| = {value:.3e} exceeds the \
             size limit {limit:.3e}; the response is unstable or the limit too small",
            step as f64 * dt
        )),
        StopReason::NonFinite { step } => Some(format!(
            "stopped at t = {:.6e} s (sample {step} of {nt}): the state overflowed (an \
             unobserved unstable mode?)",
            step as f64 * dt
        )),
    };
    let message = match (why, note) {
        (Some(a), Some(b)) => Some(format!("{a}; {b}")),
        (a, b) => a.or(b),
    };
    TimeResponse {
        t,
        dt,
        outputs: p,
        columns: r,
        y,
        direct,
        stop,
        message,
    }
}

/// Impulse response of every input (see the module docs). Sample k is `C Φᵏ B`; the
/// `D δ(t)` term is in [`TimeResponse::direct`].
///
/// Errors: those of [`StateSpace::validate`], [`NumError::InvalidOption`] for bad options,
/// [`NumError::NonFinite`] when the exponential overflows, [`NumError::NoConvergence`].
pub fn impulse(ss: &StateSpace<f64>, opts: &TimeOptions) -> Result<TimeResponse, NumError> {
    ss.validate()?;
    let (nt, dt, note) = grid(ss, opts)?;
    let dz = zoh(ss, dt)?;
    let (p, m) = (ss.outputs(), ss.inputs());
    let limit = limit_of(opts, max_abs(&ss.c) * max_abs(&ss.b))?;
    let mut y = vec![0.0; nt * p * m];
    let (kept, stop) = run(&dz.phi, None, &ss.c, None, ss.b.clone(), nt, limit, &mut y);
    Ok(finish(
        kept,
        nt,
        dt,
        p,
        m,
        y,
        Some(ss.d.clone()),
        stop,
        note,
    ))
}

/// Unit-step response of every input (see the module docs): `x₀ = 0`, `y = C x + D`.
///
/// Errors: as [`impulse`].
pub fn step(ss: &StateSpace<f64>, opts: &TimeOptions) -> Result<TimeResponse, NumError> {
    ss.validate()?;
    let (nt, dt, note) = grid(ss, opts)?;
    let dz = zoh(ss, dt)?;
    let (n, p, m) = (ss.states(), ss.outputs(), ss.inputs());
    let t_end = (nt - 1) as f64 * dt;
    let limit = limit_of(
        opts,
        max_abs(&ss.c) * max_abs(&ss.b) * t_end + max_abs(&ss.d),
    )?;
    let mut y = vec![0.0; nt * p * m];
    let (kept, stop) = run(
        &dz.phi,
        Some(&dz.gamma),
        &ss.c,
        Some(&ss.d),
        DMatrix::zeros(n, m),
        nt,
        limit,
        &mut y,
    );
    Ok(finish(kept, nt, dt, p, m, y, None, stop, note))
}

/// Response to a sampled input held over each step (ZOH): `u` is m × N (column k is the
/// input on `[k Δt, (k+1) Δt)`), `x0` the initial state (zero if `None`). Returns N samples
/// `y_k = C x_k + D u_k`. Only [`TimeOptions::size_limit`] is used from `opts`.
///
/// Errors: those of [`StateSpace::validate`], [`NumError::Dimension`] when `u` or `x0` do
/// not fit, [`NumError::NonFinite`] for non-finite samples, [`NumError::InvalidOption`] for
/// a bad `dt` or limit.
pub fn simulate(
    ss: &StateSpace<f64>,
    u: &DMatrix<f64>,
    dt: f64,
    x0: Option<&DVector<f64>>,
    opts: &TimeOptions,
) -> Result<TimeResponse, NumError> {
    ss.validate()?;
    let (n, p, m) = (ss.states(), ss.outputs(), ss.inputs());
    if u.nrows() != m {
        return Err(NumError::Dimension(DimensionError::InputSamples {
            rows: u.nrows(),
            inputs: m,
        }));
    }
    check_finite(u, "input samples u")?;
    let x = match x0 {
        Some(v) => {
            if v.len() != n {
                return Err(NumError::Dimension(DimensionError::InitialState {
                    len: v.len(),
                    states: n,
                }));
            }
            if v.iter().any(|z| !z.is_finite()) {
                return Err(NumError::NonFinite(NonFiniteError::InitialState));
            }
            v.clone()
        }
        None => DVector::zeros(n),
    };
    let dz = zoh(ss, dt)?;
    let nt = u.ncols();
    let umax = max_abs(u);
    let x0max = x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let t_end = nt.saturating_sub(1) as f64 * dt;
    let reference =
        max_abs(&ss.c) * (max_abs(&ss.b) * umax * t_end + x0max) + max_abs(&ss.d) * umax;
    let limit = limit_of(opts, reference)?;
    let mut y = vec![0.0; nt * p];
    let mut x = x;
    let mut xn = x.clone();
    let mut kept = nt;
    let mut stop = StopReason::Completed;
    for k in 0..nt {
        if x.iter().any(|v| !v.is_finite()) {
            kept = k;
            stop = StopReason::NonFinite { step: k };
            break;
        }
        let uk = u.column(k);
        let mut yk = DMatrixViewMut::from_slice(&mut y[k * p..(k + 1) * p], p, 1);
        yk.gemm(1.0, &ss.d, &uk, 0.0);
        yk.gemm(1.0, &ss.c, &x, 1.0);
        let big = yk.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if big > limit || !big.is_finite() {
            kept = k + 1;
            stop = StopReason::SizeLimit {
                step: k,
                value: big,
                limit,
            };
            break;
        }
        xn.gemv(1.0, &dz.gamma, &uk, 0.0);
        xn.gemv(1.0, &dz.phi, &x, 1.0);
        std::mem::swap(&mut x, &mut xn);
    }
    Ok(finish(kept, nt, dt, p, 1, y, None, stop, None))
}
