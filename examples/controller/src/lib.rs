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
//! The crate is `#![no_std]` and compiles for `thumbv7em-none-eabihf` (see `check-thumbv7em.sh`).

#![no_std]
#![warn(missing_docs)]

include!(concat!(env!("OUT_DIR"), "/bicycle.rs"));

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
