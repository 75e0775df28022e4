//! A simulated ride: the plant is the bicycle's linear model (the generated `f64` module,
//! evaluated at the current speed, integrated with small Euler steps), the controller is the
//! `no_std` crate in `f32` ticking at 100 Hz while the speed ramps from 4.5 to 5.8 m/s (with
//! "steer into the lean" feedback). Prints time, speed,
//! lean, torque and the prediction residual every half second.
//!
//! `cargo run -p controller --bin ride --release`

use controller::nostd_check::bicycle_f64 as plant;
use controller::{Controller, bicycle};

fn main() {
    let last = ride(|t| 4.5 + 0.13 * t, true);
    println!("final lean {last:+.2e} rad");
}

/// Ride for 10 s with the speed profile `speed(t)`; returns the final lean angle.
fn ride(speed: impl Fn(f64) -> f64, print: bool) -> f32 {
    let mut last = f32::NAN;
    let mut params = plant::Params::NOMINAL.to_array();
    let iv = plant::PARAM_NAMES
        .iter()
        .position(|n| *n == "v")
        .expect("speed parameter");
    let lean_state = plant::STATE_NAMES
        .iter()
        .position(|n| *n == "rear frame.rx")
        .expect("lean state");
    let steer = plant::INPUT_NAMES
        .iter()
        .position(|n| *n == "T_delta")
        .expect("steer torque input");
    let (mut a, mut b, mut w) = (
        [0.0; plant::A_LEN],
        [0.0; plant::B_LEN],
        [0.0; plant::WORK_LEN],
    );
    let mut x = [0.0f64; plant::N_STATES];
    x[lean_state] = 0.05;
    // Steer into the lean: torque = 2 N m/rad · lean.
    let mut gain = [0.0f32; bicycle::N_STATES];
    gain[lean_state] = -2.0;
    let mut ctl = Controller::new(bicycle::Params::NOMINAL, gain, 0.01);
    for tick in 0..1000 {
        let t = tick as f64 * 0.01;
        let v = speed(t);
        let xf: [f32; bicycle::N_STATES] = core::array::from_fn(|k| x[k] as f32);
        let cmd = match ctl.tick(v as f32, &xf) {
            Ok(c) => c,
            Err(e) => {
                eprintln!("t = {t:.2}: {e}; no torque");
                controller::Command {
                    torque: 0.0,
                    residual: f32::NAN,
                    lean: f32::NAN,
                }
            }
        };
        last = cmd.lean;
        if print && tick % 50 == 0 {
            println!(
                "t = {t:5.2} s  v = {v:4.2} m/s  lean = {:+.5} rad  torque = {:+.5} N m  residual = {:.2e}",
                cmd.lean, cmd.torque, cmd.residual
            );
        }
        params[iv] = v;
        plant::eval_ab(&params, &mut a, &mut b, &mut w).expect("plant model valid on the ride");
        for _ in 0..10 {
            let mut dx = [0.0; plant::N_STATES];
            for (i, d) in dx.iter_mut().enumerate() {
                *d = b[i + steer * plant::N_STATES] * f64::from(cmd.torque)
                    + (0..plant::N_STATES)
                        .map(|j| a[i + j * plant::N_STATES] * x[j])
                        .sum::<f64>();
            }
            for (xi, d) in x.iter_mut().zip(dx) {
                *xi += 0.001 * d;
            }
        }
    }
    last
}
