//! # A `no_std` controller on generated code
//!
//! The bicycle's linearized model depends on the forward speed `v`. A controller that runs at a
//! fixed rate re-evaluates A, B, C and D at the measured speed every tick — with the generated
//! [`bicycle::eval_abcd_varying`], which takes the parameters as an array, writes into
//! fixed-size arrays only the entries that depend on them (the constant ones are written once,
//! by [`bicycle::write_abcd_constants`]) and allocates nothing — and uses them in a fault
//! detector, and reads the lean angle through C and D:
//!
//! * steer torque by state feedback `u = −K x`;
//! * a one-step prediction `x⁺ = x + Δt (A x + B u)` whose difference from the next
//!   measurement is a fault indicator;
//! * the lean angle from the output equation `y = C x + D u`.
//!
//! If the speed or a parameter leaves the region where the generated formulas are valid (or a
//! result is not finite), [`Controller::tick`] returns the error and the caller falls back (here:
//! zero torque) instead of using garbage matrices.
//!
//! [`Predictor`] runs at 1 kHz on a reduced, discretised model: the bicycle reduced to five
//! states by balanced truncation at the nominal point (its two exact zeros kept, the fast castor
//! mode dropped), generated with `eval_discrete`, which gives `Ad = e^{A h}` and
//! `Bd = ∫₀ʰ e^{A t} dt B` at the current speed every tick without allocation; it predicts the
//! next reduced state `z⁺ = Ad z + Bd u` (`z = Wᵀ x`) exactly for the reduced model, instead of
//! the Euler step above.
//!
//! The crate is `#![no_std]` and compiles for `thumbv7em-none-eabihf` (see `check-thumbv7em.sh`).

#![no_std]
#![warn(missing_docs)]

include!(concat!(env!("OUT_DIR"), "/bicycle.rs"));
include!(concat!(env!("OUT_DIR"), "/bicycle_reduced.rs"));

#[doc(hidden)]
pub mod nostd_check;

use bicycle::{A_LEN, B_LEN, C_LEN, D_LEN, N_OUTPUTS, N_PARAMS, N_STATES, Params, WORK_LEN};

/// Index of the speed in the parameter array.
const V: usize = {
    let mut k = 0;
    while !matches!(bicycle::PARAM_NAMES[k].as_bytes(), b"v") {
        k += 1;
    }
    k
};

/// Index of the steer torque `T_delta` among the inputs (the bicycle's inputs are the
/// benchmark's `[T_phi, T_delta]`; this controller steers only).
const STEER: usize = {
    let mut k = 0;
    while !matches!(bicycle::INPUT_NAMES[k].as_bytes(), b"T_delta") {
        k += 1;
    }
    k
};

/// What one tick produces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Command {
    /// Steer torque `T_delta` (N m).
    pub torque: f32,
    /// Largest difference between the measured state and the one the model predicted at the
    /// previous tick (a fault indicator: large when the bicycle does not behave like the model).
    pub residual: f32,
    /// Lean angle `phi` (rad) from the output equation `y = C x + D u`.
    pub lean: f32,
}

/// The controller: parameters, the matrices of the current tick, the prediction, the gain.
pub struct Controller {
    params: [f32; N_PARAMS],
    a: [f32; A_LEN],
    b: [f32; B_LEN],
    c: [f32; C_LEN],
    d: [f32; D_LEN],
    work: [f32; WORK_LEN],
    predicted: Option<[f32; N_STATES]>,
    gain: [f32; N_STATES],
    dt: f32,
}

impl Controller {
    /// A controller for the bicycle with `params` (e.g. [`Params::NOMINAL`]), state feedback
    /// `u = −gain · x` (order of [`bicycle::STATE_NAMES`]), ticking every `dt` seconds.
    pub fn new(params: Params, gain: [f32; N_STATES], dt: f32) -> Self {
        let (mut a, mut b, mut c, mut d) = ([0.0; A_LEN], [0.0; B_LEN], [0.0; C_LEN], [0.0; D_LEN]);
        // The entries that are the same at every speed, once; each tick writes the others.
        bicycle::write_abcd_constants(&mut a, &mut b, &mut c, &mut d);
        Controller {
            params: params.to_array(),
            a,
            b,
            c,
            d,
            work: [0.0; WORK_LEN],
            predicted: None,
            gain,
            dt,
        }
    }

    /// One tick: the measured speed and state in, the steer torque out. The model is
    /// re-evaluated at this speed; outside its validity region the error comes back and the
    /// previous matrices stay as they were.
    pub fn tick(&mut self, speed: f32, x: &[f32; N_STATES]) -> Result<Command, bicycle::Error> {
        self.params[V] = speed;
        bicycle::eval_abcd_varying(
            &self.params,
            &mut self.a,
            &mut self.b,
            &mut self.c,
            &mut self.d,
            &mut self.work,
        )?;
        let residual = match &self.predicted {
            Some(p) => p
                .iter()
                .zip(x)
                .fold(0.0f32, |m, (p, x)| m.max(libm::fabsf(p - x))),
            None => 0.0,
        };
        let torque = -self.gain.iter().zip(x).map(|(g, x)| g * x).sum::<f32>();
        // Predict the next state with the model at this speed (explicit Euler).
        let mut next = *x;
        for (i, n) in next.iter_mut().enumerate() {
            let mut dx = self.b[i + STEER * N_STATES] * torque;
            for (j, xj) in x.iter().enumerate() {
                dx += self.a[i + j * N_STATES] * xj;
            }
            *n += self.dt * dx;
        }
        self.predicted = Some(next);
        let lean_row = bicycle::OUTPUT_NAMES
            .iter()
            .position(|n| *n == "phi")
            .unwrap_or(0);
        let mut lean = self.d[lean_row + STEER * N_OUTPUTS] * torque;
        for (j, xj) in x.iter().enumerate() {
            lean += self.c[lean_row + j * N_OUTPUTS] * xj;
        }
        Ok(Command {
            torque,
            residual,
            lean,
        })
    }

    /// A of the last successful tick (column-major).
    pub fn a(&self) -> &[f32; A_LEN] {
        &self.a
    }
}

/// Sample rate of the [`Predictor`], Hz.
pub const PREDICTOR_RATE_HZ: f32 = 1000.0;

/// Index of the speed among the reduced module's parameters.
const RV: usize = {
    let mut k = 0;
    while !matches!(bicycle_reduced::PARAM_NAMES[k].as_bytes(), b"v") {
        k += 1;
    }
    k
};

/// A one-step predictor at 1 kHz on the reduced, discretised bicycle: every tick the
/// zero-order-hold matrices at the measured speed, the prediction of the next reduced state,
/// and how far the previous prediction was from this tick's measurement.
pub struct Predictor {
    params: [f32; bicycle_reduced::N_PARAMS],
    ad: [f32; bicycle_reduced::A_LEN],
    bd: [f32; bicycle_reduced::B_LEN],
    work: bicycle_reduced::DiscreteWork,
    predicted: Option<[f32; bicycle_reduced::N_STATES]>,
}

impl Predictor {
    /// A predictor for the bicycle with `params`.
    pub fn new(params: bicycle_reduced::Params) -> Self {
        Predictor {
            params: params.to_array(),
            ad: [0.0; bicycle_reduced::A_LEN],
            bd: [0.0; bicycle_reduced::B_LEN],
            work: bicycle_reduced::DiscreteWork::new(),
            predicted: None,
        }
    }

    /// The reduced state `z = Wᵀ x` of a full state (in the order of the full model's states,
    /// [`bicycle::STATE_NAMES`]).
    pub fn reduce(x: &[f32; bicycle_reduced::FULL_STATES]) -> [f32; bicycle_reduced::N_STATES] {
        core::array::from_fn(|j| {
            (0..bicycle_reduced::FULL_STATES)
                .map(|i| bicycle_reduced::REDUCE_W[i + j * bicycle_reduced::FULL_STATES] * x[i])
                .sum()
        })
    }

    /// One tick (1 ms): the measured speed and full state, the steer torque held over the
    /// coming tick. Returns the largest difference between the reduced state and the one the
    /// previous tick predicted (0 on the first tick). Outside the validity region the error
    /// comes back and the prediction is dropped.
    pub fn tick(
        &mut self,
        speed: f32,
        x: &[f32; bicycle_reduced::FULL_STATES],
        torque: f32,
    ) -> Result<f32, bicycle_reduced::Error> {
        self.params[RV] = speed;
        let h = 1.0 / PREDICTOR_RATE_HZ;
        if let Err(e) = bicycle_reduced::eval_discrete(
            &self.params,
            h,
            &mut self.ad,
            &mut self.bd,
            &mut self.work,
        ) {
            self.predicted = None;
            return Err(e);
        }
        let n = bicycle_reduced::N_STATES;
        let z = Self::reduce(x);
        let residual = match &self.predicted {
            Some(p) => p
                .iter()
                .zip(&z)
                .fold(0.0f32, |m, (p, z)| m.max(libm::fabsf(p - z))),
            None => 0.0,
        };
        let next: [f32; bicycle_reduced::N_STATES] = core::array::from_fn(|i| {
            let mut s = self.bd[i + STEER * n] * torque;
            for (j, zj) in z.iter().enumerate() {
                s += self.ad[i + j * n] * zj;
            }
            s
        });
        self.predicted = Some(next);
        Ok(residual)
    }
}
