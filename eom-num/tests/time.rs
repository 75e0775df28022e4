//! ZOH time responses against closed-form solutions.

mod closed_forms;

use closed_forms::smd;
use eom_num::time::{Horizon, SizeLimit, StopReason, TimeOptions, impulse, simulate, step, zoh};
use eom_num::{DimensionError, MatrixEntry, NonFiniteError, NumError, OptionError, StateSpace};
use nalgebra::{DMatrix, dmatrix, dvector};

fn first_order(tau: f64) -> StateSpace<f64> {
    StateSpace::new(
        dmatrix![-1.0 / tau],
        dmatrix![1.0 / tau],
        dmatrix![1.0],
        dmatrix![0.0],
    )
    .unwrap()
}

#[test]
fn first_order_step_is_one_minus_exponential() {
    let tau = 0.37;
    let opts = TimeOptions {
        horizon: Horizon::Given {
            t_end: 3.0,
            dt: 0.01,
        },
        ..Default::default()
    };
    let r = step(&first_order(tau), &opts).unwrap();
    assert_eq!(r.stop, StopReason::Completed);
    assert_eq!(r.len(), 301);
    assert!(r.message.is_none());
    for (k, &t) in r.t.iter().enumerate() {
        let exact = 1.0 - (-t / tau).exp();
        assert!((r.at(k)[(0, 0)] - exact).abs() < 1e-13, "t = {t}");
    }
    // Automatic horizon: 5τ with steps of τ/10.
    let r = step(&first_order(tau), &TimeOptions::default()).unwrap();
    let t_end = r.t[r.len() - 1];
    assert!((t_end - 5.0 * tau).abs() < 0.1 * tau, "t_end {t_end}");
    assert!((r.dt - tau / 10.0).abs() < 1e-15);
}

#[test]
fn smd_step_and_impulse_match_closed_form() {
    let (m, c, k) = (1.5, 0.6, 40.0);
    let ss = smd(m, c, k);
    let wn = (k / m).sqrt();
    let zeta = c / (2.0 * (k * m).sqrt());
    let wd = wn * (1.0 - zeta * zeta).sqrt();
    let opts = TimeOptions {
        horizon: Horizon::Given {
            t_end: 10.0,
            dt: 0.005,
        },
        ..Default::default()
    };
    let st = step(&ss, &opts).unwrap();
    let im = impulse(&ss, &opts).unwrap();
    assert_eq!(st.stop, StopReason::Completed);
    for (kk, &t) in st.t.iter().enumerate() {
        let e = (-zeta * wn * t).exp();
        let x_step =
            (1.0 - e * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin())) / k;
        let x_imp = e * (wd * t).sin() / (m * wd);
        assert!((st.series(0, 0)[kk] - x_step).abs() < 1e-13, "step t = {t}");
        assert!(
            (im.series(0, 0)[kk] - x_imp).abs() < 1e-13,
            "impulse t = {t}"
        );
    }
    assert_eq!(im.direct, Some(dmatrix![0.0]));
    assert_eq!(st.direct, None);
    // Automatic horizon: 5τ = 5·2m/c = 25 s (within the cap of 50 damped periods, 61 s).
    let auto = step(&ss, &TimeOptions::default()).unwrap();
    let t_end = auto.t[auto.len() - 1];
    let want = 5.0 * 2.0 * m / c;
    assert!((t_end - want).abs() <= auto.dt, "t_end {t_end} vs {want}");
    assert!(auto.dt <= 2.0 * std::f64::consts::PI / wd / 20.0 + 1e-15);
}

#[test]
fn lightly_damped_horizon_is_capped_at_fifty_periods() {
    // ζ = 0.001: 5τ would be 800 periods; the horizon stops at 50.
    let (m, k) = (1.0f64, 400.0f64);
    let c = 2.0 * 0.001 * (k * m).sqrt();
    let ss = smd(m, c, k);
    let r = step(&ss, &TimeOptions::default()).unwrap();
    let wd = (k / m - c * c / (4.0 * m * m)).sqrt();
    let period = 2.0 * std::f64::consts::PI / wd;
    let t_end = r.t[r.len() - 1];
    assert!(
        (t_end - 50.0 * period).abs() <= r.dt,
        "{t_end} vs {}",
        50.0 * period
    );
    assert!(r.dt <= period / 20.0 + 1e-15);
}

#[test]
fn impulse_reports_the_feedthrough_delta() {
    // y = x + 2u, ẋ = −x + u: impulse response e^{−t} plus 2 δ(t).
    let ss = StateSpace::new(dmatrix![-1.0], dmatrix![1.0], dmatrix![1.0], dmatrix![2.0]).unwrap();
    let opts = TimeOptions {
        horizon: Horizon::Given {
            t_end: 2.0,
            dt: 0.1,
        },
        ..Default::default()
    };
    let r = impulse(&ss, &opts).unwrap();
    assert_eq!(r.direct, Some(dmatrix![2.0]));
    for (k, &t) in r.t.iter().enumerate() {
        assert!((r.at(k)[(0, 0)] - (-t).exp()).abs() < 1e-14, "t = {t}");
    }
    // Step includes D: y = 2 + (1 − e^{−t}).
    let s = step(&ss, &opts).unwrap();
    for (k, &t) in s.t.iter().enumerate() {
        assert!((s.at(k)[(0, 0)] - (3.0 - (-t).exp())).abs() < 1e-14);
    }
}

#[test]
fn sampled_input_is_exact_for_piecewise_constant_signals() {
    // A step of height 2 switched on at sample 3 (t = 0.3), from x0 = 0.5: the exact
    // solution is x0 e^{−t/τ} + 2 (1 − e^{−(t − 0.3)/τ}) for t ≥ 0.3.
    let tau = 0.25;
    let ss = first_order(tau);
    let dt = 0.1;
    let n = 40;
    let u = DMatrix::from_fn(1, n, |_, k| if k >= 3 { 2.0 } else { 0.0 });
    let r = simulate(&ss, &u, dt, Some(&dvector![0.5]), &TimeOptions::default()).unwrap();
    assert_eq!(r.len(), n);
    assert_eq!(r.columns, 1);
    for k in 0..n {
        let t = k as f64 * dt;
        let mut exact = 0.5 * (-t / tau).exp();
        if t >= 0.3 - 1e-12 {
            exact += 2.0 * (1.0 - (-(t - 0.3) / tau).exp());
        }
        assert!((r.at(k)[(0, 0)] - exact).abs() < 1e-13, "t = {t}");
    }
}

#[test]
fn zoh_matrices_closed_form() {
    // ẋ = a x + b u: Φ = e^{a dt}, Γ = b (e^{a dt} − 1)/a.
    let (a, b, dt) = (-3.0, 2.0, 0.2);
    let ss = StateSpace::new(dmatrix![a], dmatrix![b], dmatrix![1.0], dmatrix![0.0]).unwrap();
    let z = zoh(&ss, dt).unwrap();
    assert!((z.phi[(0, 0)] - (a * dt).exp()).abs() < 1e-15);
    assert!((z.gamma[(0, 0)] - b * ((a * dt).exp() - 1.0) / a).abs() < 1e-15);
}

#[test]
fn unstable_response_stops_cleanly() {
    let ss = StateSpace::new(dmatrix![2.0], dmatrix![1.0], dmatrix![1.0], dmatrix![0.0]).unwrap();
    let opts = TimeOptions {
        horizon: Horizon::Given {
            t_end: 100.0,
            dt: 0.01,
        },
        ..Default::default()
    };
    let r = impulse(&ss, &opts).unwrap();
    match r.stop {
        StopReason::SizeLimit { step, value, limit } => {
            assert_eq!(limit, 1e6);
            assert!(value > limit);
            assert_eq!(step, r.len() - 1);
            // e^{2t} crosses 1e6 at t = ln(1e6)/2 ≈ 6.91 s.
            let t_cross = (1e6f64).ln() / 2.0;
            assert!((r.t[step] - t_cross).abs() <= 0.011, "{}", r.t[step]);
        }
        other => panic!("expected SizeLimit, got {other:?}"),
    }
    assert!(
        r.message
            .as_deref()
            .unwrap()
            .contains("exceeds the size limit")
    );
    // History before the stop is the exact growth.
    for k in 0..r.len() {
        assert!((r.at(k)[(0, 0)] - (2.0 * r.t[k]).exp()).abs() < 1e-12 * (2.0 * r.t[k]).exp());
    }
    // An absolute limit is honoured.
    let opts = TimeOptions {
        size_limit: SizeLimit::Absolute(10.0),
        ..opts
    };
    let r = step(&ss, &opts).unwrap();
    assert!(matches!(r.stop, StopReason::SizeLimit { limit, .. } if limit == 10.0));
}

#[test]
fn unobserved_unstable_mode_stops_on_overflow() {
    // The output does not see the unstable state; the state overflows to ∞ eventually.
    let ss = StateSpace::new(
        dmatrix![50.0, 0.0; 0.0, -1.0],
        dmatrix![1.0; 1.0],
        dmatrix![0.0, 1.0],
        dmatrix![0.0],
    )
    .unwrap();
    let opts = TimeOptions {
        horizon: Horizon::Given {
            t_end: 100.0,
            dt: 0.1,
        },
        ..Default::default()
    };
    let r = impulse(&ss, &opts).unwrap();
    assert!(
        matches!(r.stop, StopReason::NonFinite { .. }),
        "{:?}",
        r.stop
    );
    assert!(r.message.as_deref().unwrap().contains("overflowed"));
    assert!(r.y.iter().all(|v| v.is_finite()));
}

#[test]
fn static_model_and_coarsened_auto_step() {
    let ss = StateSpace::new(
        DMatrix::zeros(0, 0),
        DMatrix::zeros(0, 1),
        DMatrix::zeros(1, 0),
        dmatrix![4.0],
    )
    .unwrap();
    let r = step(&ss, &TimeOptions::default()).unwrap();
    assert!(r.y.iter().all(|&v| v == 4.0));
    assert!((r.t[r.len() - 1] - 10.0).abs() < 1e-9);
    // Widely separated time scales: the step is coarsened to respect max_steps, and said so.
    let ss = StateSpace::new(
        dmatrix![-1e-2, 0.0; 0.0, -1e4],
        dmatrix![1.0; 1.0],
        dmatrix![1.0, 1.0],
        dmatrix![0.0],
    )
    .unwrap();
    let r = step(&ss, &TimeOptions::default()).unwrap();
    assert_eq!(r.len(), 10_001);
    assert!(
        r.message
            .as_deref()
            .unwrap()
            .contains("automatic step enlarged")
    );
    let t_end = r.t[r.len() - 1];
    assert!((t_end - 500.0).abs() < 1e-6, "{t_end}");
    // Still exact at the samples.
    for k in (0..r.len()).step_by(1000) {
        let t = r.t[k];
        let exact = 100.0 * (1.0 - (-1e-2 * t).exp()) + 1e-4 * (1.0 - (-1e4 * t).exp());
        assert!((r.at(k)[(0, 0)] - exact).abs() < 1e-11 * 100.0, "t = {t}");
    }
}

#[test]
fn time_errors_name_the_problem() {
    let ss = first_order(1.0);
    let bad = |h| TimeOptions {
        horizon: h,
        ..Default::default()
    };
    assert!(matches!(
        step(
            &ss,
            &bad(Horizon::Given {
                t_end: 1.0,
                dt: 0.0
            })
        ),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "Horizon::Given dt",
            value: 0.0,
            ..
        }))
    ));
    assert!(matches!(
        impulse(
            &ss,
            &bad(Horizon::Given {
                t_end: f64::NAN,
                dt: 0.1
            })
        ),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "Horizon::Given t_end",
            ..
        }))
    ));
    assert!(matches!(
        step(
            &ss,
            &bad(Horizon::Given {
                t_end: 1e6,
                dt: 1e-6
            })
        ),
        Err(NumError::InvalidOption(OptionError::TooManySamples { .. }))
    ));
    let few = TimeOptions {
        max_steps: 1,
        ..Default::default()
    };
    assert!(matches!(
        step(&ss, &few),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "TimeOptions::max_steps",
            value: 1.0,
            ..
        }))
    ));
    let lim = TimeOptions {
        size_limit: SizeLimit::Relative(-1.0),
        ..Default::default()
    };
    assert!(matches!(
        step(&ss, &lim),
        Err(NumError::InvalidOption(OptionError::SizeLimit {
            kind: "Relative",
            ..
        }))
    ));
    let lim = TimeOptions {
        size_limit: SizeLimit::Absolute(0.0),
        ..Default::default()
    };
    assert!(matches!(
        impulse(&ss, &lim),
        Err(NumError::InvalidOption(OptionError::SizeLimit {
            kind: "Absolute",
            ..
        }))
    ));
    let o = TimeOptions::default();
    assert!(matches!(
        simulate(&ss, &DMatrix::zeros(2, 5), 0.1, None, &o),
        Err(NumError::Dimension(DimensionError::InputSamples {
            rows: 2,
            ..
        }))
    ));
    assert!(matches!(
        simulate(
            &ss,
            &DMatrix::zeros(1, 5),
            0.1,
            Some(&dvector![1.0, 2.0]),
            &o
        ),
        Err(NumError::Dimension(DimensionError::InitialState {
            len: 2,
            ..
        }))
    ));
    assert!(matches!(
        simulate(&ss, &DMatrix::from_element(1, 5, f64::NAN), 0.1, None, &o),
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry { ref matrix, .. }))) if matrix == "input samples u"
    ));
    assert!(matches!(
        simulate(
            &ss,
            &DMatrix::zeros(1, 5),
            0.1,
            Some(&dvector![f64::INFINITY]),
            &o
        ),
        Err(NumError::NonFinite(NonFiniteError::InitialState))
    ));
    assert!(matches!(
        zoh(&ss, -1.0),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "time step dt",
            value: -1.0,
            ..
        }))
    ));
    // exp(A dt) overflows.
    let fast = StateSpace::new(dmatrix![1e3], dmatrix![1.0], dmatrix![1.0], dmatrix![0.0]).unwrap();
    assert!(matches!(
        zoh(&fast, 10.0),
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry { ref matrix, .. }))) if matrix.contains("Φ")
    ));
}
