//! # eom-num — linear analysis engineers can trust
//!
//! eom-num takes a linear time-invariant model — a [`StateSpace`] `ẋ = A x + B u`,
//! `y = C x + D u`, or a [`Descriptor`] `E ẋ = A x + B u` with a possibly singular E — and
//! answers the questions a vehicle or machine dynamicist asks of it: which modes does it
//! have and how do they move the bodies, how does each output respond to each input across
//! frequency and in time, what does it settle to, which inputs and outputs can be dropped,
//! where are its zeros, and for which parameter values is it stable.
//!
//! It knows nothing about symbolic expressions: `eom-sym` builds the matrices (and depends
//! on this crate for [`StateSpace`]), eom-num analyses numbers.
//!
//! ## A first model
//!
//! A spring–mass–damper, `m ẍ + c ẋ + k x = F`, observed by its position:
//!
//! ```
//! use eom_num::{StateSpace, NumError};
//! use eom_num::modes::{Modes, ModeKind};
//! use eom_num::freq::{FrequencyResponse, FreqOptions};
//! use eom_num::gain::{steady_state_gain, Gain};
//! use eom_num::time::{step, TimeOptions};
//! use nalgebra::dmatrix;
//!
//! # fn main() -> Result<(), NumError> {
//! let (m, c, k) = (2.0, 4.0, 800.0);
//! let ss = StateSpace::new(
//!     dmatrix![0.0, 1.0; -k / m, -c / m],
//!     dmatrix![0.0; 1.0 / m],
//!     dmatrix![1.0, 0.0],
//!     dmatrix![0.0],
//! )?;
//!
//! // Modes: one entry per eigenvalue, with frequency, damping, time constant, period.
//! let modes = Modes::compute(&ss)?;
//! let mode = modes.distinct().next().unwrap();
//! assert_eq!(mode.kind, ModeKind::Oscillatory);
//! let wn = (k / m).sqrt();
//! assert!((mode.natural_frequency_hz - wn / (2.0 * std::f64::consts::PI)).abs() < 1e-12);
//! assert!((mode.damping_ratio.unwrap() - c / (2.0 * (k * m).sqrt())).abs() < 1e-12);
//!
//! // Frequency response on an automatic grid around the modes, 200 points per decade.
//! let fr = FrequencyResponse::compute(&ss, &FreqOptions::default())?;
//! let peak = fr.magnitude_db_of(0, 0).iter().cloned().fold(f64::MIN, f64::max);
//! assert!(peak > 20.0 * (1.0 / k).log10());
//!
//! // Steady state: the static compliance 1/k.
//! let gain = steady_state_gain(&ss)?;
//! assert!(matches!(gain.get(0, 0), Gain::Finite(g) if (g - 1.0 / k).abs() < 1e-15));
//!
//! // Step response by exact zero-order-hold discretisation.
//! let resp = step(&ss, &TimeOptions::default())?;
//! let last = resp.at(resp.len() - 1)[(0, 0)];
//! assert!((last - 1.0 / k).abs() < 0.01 / k);
//! # Ok(())
//! # }
//! ```
//!
//! ## What is where
//!
//! | module | answers |
//! |---|---|
//! | [`statespace`] | the model types [`StateSpace`] (with `phys`, the map to body coordinates, and [`SignalNames`]) and [`Descriptor`] |
//! | [`budget`] | memory predicted before large allocations, refused above a limit |
//! | [`linalg`] | SVD rank and nullspace decisions with their gap, equilibration of mixed units, condition numbers, balancing, nalgebra ↔ faer |
//! | [`descriptor`] | descriptor → state space for index-1 pencils, finite generalized eigenvalues |
//! | [`modes`] | eigenvalues (also without allocation), modal quantities, mode shapes, instantaneous centres of rotation |
//! | [`small_eigen`] | eigenvalues of matrices up to 16 × 16 on the stack (the sweeps' kernel) |
//! | [`freq`] | frequency response of every input/output pair, magnitude and unwrapped phase |
//! | [`gain`] | steady-state gains, with integrating outputs identified |
//! | [`time`] | impulse, step and sampled-input responses by exact ZOH discretisation |
//! | [`initial`] | the free response from an initial state, and the state that starts one mode alone |
//! | [`minreal`] | minimal realization (orthogonal staircase, and a PBH test at repeated eigenvalues), with the removed modes reported |
//! | [`zeros`] | transmission zeros |
//! | [`model_reduction`] | balanced truncation (with the `2Σσ` bound), DC-matched and modal reduction; unstable and marginal modes kept whole |
//! | [`sweep`] | parameter sweeps: eigenvalue branches, stability boundaries, stable intervals |
//!
//! ## Principles
//!
//! **Every decision is inspectable.** Numerical linear algebra is full of yes/no questions
//! asked of floating-point numbers: is E singular, is this eigenvalue zero, is `jω` a pole.
//! eom-num answers each with an explicit, documented, scale-aware tolerance and returns how
//! close the answer was — a [`linalg::Rank`] carries the singular values, the threshold and
//! the gap `σ_r/σ_{r+1}`; reports ([`descriptor::DescriptorReport`],
//! [`gain::SteadyStateGain`], [`minreal::MinrealReport`], …) collect warnings about
//! near-tolerance decisions and ill-conditioning instead of hiding them.
//!
//! **Tolerances follow the data.** Thresholds are relative to the norms involved, never
//! absolute constants; matrices are balanced or equilibrated (by exact powers of two)
//! before rank decisions, so that a model in mm and kN gives the same answers as one in m
//! and N. Eigenvalue classifications use each eigenvalue's own condition number, so a slow
//! pole of a stiff model is not mistaken for zero while a rigid-body double zero is.
//!
//! **Errors are values.** Bad input (mismatched shapes, NaN, bad options) and numerical
//! impossibility (a singular pencil, an index-2 descriptor, a pole on the evaluation point)
//! come back as a [`NumError`] whose message names the matrix, option or point at fault —
//! never a panic and never a silent NaN.
//!
//! **Two levels where it matters.** Easy allocating calls ([`modes::eigenvalues`],
//! [`freq::FrequencyResponse::compute`]) sit on top of kernels that take an explicit
//! workspace and do not allocate ([`modes::eigenvalues_in`],
//! [`freq::HessenbergForm::evaluate_in`], [`freq::HessenbergForm::evaluate_batch_in`]),
//! for sweeps that call them millions of times.
//!
//! **Dense algorithms from faer, public types from nalgebra.** Eigenvectors, QZ, SVD,
//! Hessenberg reductions and the eigenvalues of one large matrix ([`modes::eigenvalues`])
//! come from faer: sequential below [`linalg::PARALLEL_MIN`] states (sweeps parallelise over
//! their points, and [`modes::eigenvalues_in`] always runs on the calling thread), on every
//! thread of the current rayon pool above (a model of a thousand bodies); eigenvalues up to 16 states from the stack kernel of
//! [`small_eigen`]. `DMatrix<f64>` is the public matrix type and provides the matrix
//! exponential.
//!
//! ## Where eom-num deliberately differs from EoM.jl
//!
//! The analyses follow the reference tool EoM.jl, fixing its known weaknesses: the rank of E
//! in the descriptor reduction is decided scale-aware rather than at ULP level; infinite
//! generalized eigenvalues are recognised relative to ‖A‖/‖E‖ instead of `|λ| < 1e9`; real
//! poles report their corner frequency (not "0 Hz") and a damping ratio of ±1 (not NaN);
//! an all-zero spectrum gets a default frequency grid instead of an exception; integrating
//! outputs are reported as such instead of by a low-frequency substitute; the impulse
//! response reports the `D δ(t)` term; time responses are exact ZOH recursions that stop
//! cleanly when unstable; eigenvalue order is deterministic.

#![warn(missing_docs)]
// One exception, allowed where it is: the AVX2 frequency-response kernel (`freq`).
#![deny(unsafe_code)]

/// Largest magnitude of a matrix entry the analyses accept (about the square root of
/// `f64::MAX`, with margin): the products of two entries inside the factorisations stay
/// finite.
pub const MAX_ENTRY: f64 = 1e150;

pub mod budget;
pub mod deflate;
pub mod descriptor;
mod eigen;
pub mod error;
pub mod freq;
pub mod gain;
pub mod initial;
pub mod linalg;
pub mod minreal;
pub mod model_reduction;
pub mod modes;
pub mod reach;
pub mod sensitivity;
pub mod small_eigen;
mod small_estimates;
pub mod statespace;
pub mod sweep;
pub mod time;
pub mod warning;
pub mod zeros;

pub use error::{
    A22Rank, AmbiguousRankError, Bound, ConvergenceError, DimensionError, MatrixEntry,
    NonFiniteError, NumError, OptionError, PencilError, SingularError,
};
pub use statespace::{Descriptor, SignalNames, StateSpace};
pub use warning::NumWarning;
