//! The controller on the simulated bicycle: the lean perturbation dies out over a speed ramp
//! with no evaluation error and a small prediction residual; outside the model's validity region
//! a tick reports the error and keeps the previous matrices.

use controller::nostd_check::bicycle_f64 as plant;
use controller::{Controller, bicycle};

#[test]
fn steer_into_the_lean_settles_over_a_speed_ramp() {
    let mut params = plant::Params::NOMINAL.to_array();
    let iv = plant::PARAM_NAMES
        .iter()
        .position(|n| *n == "v")
        .expect("v");
    let lean = plant::STATE_NAMES
        .iter()
        .position(|n| *n == "rear frame.rx")
        .expect("lean");
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
    x[lean] = 0.05;
    let mut gain = [0.0f32; bicycle::N_STATES];
    gain[lean] = -2.0;
    let mut ctl = Controller::new(bicycle::Params::NOMINAL, gain, 0.01);
    let mut worst_residual = 0.0f32;
    let mut first_lean = None;
    let mut last_lean = 0.0;
    for tick in 0..1000 {
        let v = 4.5 + 0.0013 * tick as f64;
        let xf: [f32; bicycle::N_STATES] = core::array::from_fn(|k| x[k] as f32);
        let cmd = ctl.tick(v as f32, &xf).expect("valid on the whole ride");
        worst_residual = worst_residual.max(cmd.residual);
        first_lean.get_or_insert(cmd.lean);
        last_lean = cmd.lean;
        params[iv] = v;
        plant::eval_ab(&params, &mut a, &mut b, &mut w).expect("plant");
        for _ in 0..10 {
            let dx: Vec<f64> = (0..plant::N_STATES)
                .map(|i| {
                    b[i + steer * plant::N_STATES] * f64::from(cmd.torque)
                        + (0..plant::N_STATES)
                            .map(|j| a[i + j * plant::N_STATES] * x[j])
                            .sum::<f64>()
                })
                .collect();
            for (xi, d) in x.iter_mut().zip(dx) {
                *xi += 0.001 * d;
            }
        }
    }
    let first = first_lean.expect("ticked");
    assert!(first.abs() > 0.01, "initial lean {first}");
    assert!(
        last_lean.abs() < 0.02 * first.abs(),
        "lean {first} → {last_lean}"
    );
    // One controller step against ten plant steps: the Euler prediction is close, not exact.
    assert!(worst_residual < 1e-3, "residual {worst_residual}");
}

#[test]
fn outside_the_validity_region_a_tick_is_an_error() {
    let mut p = bicycle::Params::NOMINAL;
    let mut ctl = Controller::new(p, [0.0; bicycle::N_STATES], 0.01);
    ctl.tick(5.0, &[0.0; bicycle::N_STATES]).expect("nominal");
    let a = *ctl.a();
    p.lambda = core::f32::consts::FRAC_PI_2;
    let mut bad = Controller::new(p, [0.0; bicycle::N_STATES], 0.01);
    // Only the constant entries, written at construction.
    let fresh = *bad.a();
    match bad.tick(5.0, &[0.0; bicycle::N_STATES]) {
        Err(e @ bicycle::Error::Validity { .. }) => {
            let what = e.what().expect("a validity error has a description");
            assert!(what.contains("steer hinge"), "{what}")
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(*bad.a(), fresh, "matrices written on error");
    assert!(fresh.contains(&1.0), "constants written at construction");
    assert_eq!(*ctl.a(), a);
}

/// The 1 kHz predictor on the reduced, discretised model against the full plant (integrated
/// with steps of 10 µs) under a steer torque: the one-step prediction of the reduced state is
/// close, over a speed ramp.
#[test]
fn reduced_discrete_predictor_at_1_khz_tracks_the_full_plant() {
    use controller::{Predictor, bicycle_reduced};
    let mut params = plant::Params::NOMINAL.to_array();
    let iv = plant::PARAM_NAMES
        .iter()
        .position(|n| *n == "v")
        .expect("v");
    let lean = plant::STATE_NAMES
        .iter()
        .position(|n| *n == "rear frame.rx")
        .expect("lean");
    let steer = plant::INPUT_NAMES
        .iter()
        .position(|n| *n == "T_delta")
        .expect("steer");
    let (mut a, mut b, mut w) = (
        [0.0; plant::A_LEN],
        [0.0; plant::B_LEN],
        [0.0; plant::WORK_LEN],
    );
    let mut x = [0.0f64; plant::N_STATES];
    x[lean] = 0.05;
    let mut pred = Predictor::new(bicycle_reduced::Params::NOMINAL);
    let (mut worst, mut size) = (0.0f32, 0.0f32);
    for tick in 0..2000 {
        let v = 4.5 + 0.0005 * tick as f64;
        let torque = 0.5 * (tick as f64 * 0.004).sin();
        let xf: [f32; bicycle_reduced::FULL_STATES] = core::array::from_fn(|k| x[k] as f32);
        let r = pred
            .tick(v as f32, &xf, torque as f32)
            .expect("valid on the ride");
        if tick > 0 {
            worst = worst.max(r);
        }
        size = size.max(
            Predictor::reduce(&xf)
                .iter()
                .fold(0.0f32, |m, z| m.max(z.abs())),
        );
        params[iv] = v;
        plant::eval_ab(&params, &mut a, &mut b, &mut w).expect("plant");
        for _ in 0..100 {
            let dx: Vec<f64> = (0..plant::N_STATES)
                .map(|i| {
                    b[i + steer * plant::N_STATES] * torque
                        + (0..plant::N_STATES)
                            .map(|j| a[i + j * plant::N_STATES] * x[j])
                            .sum::<f64>()
                })
                .collect();
            for (xi, d) in x.iter_mut().zip(dx) {
                *xi += 1e-5 * d;
            }
        }
    }
    eprintln!("largest one-step residual {worst:.3e} against reduced states up to {size:.3e}");
    assert!(worst < 1e-3 * size, "residual {worst} against {size}");
}
