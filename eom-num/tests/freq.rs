//! Frequency response against closed-form transfer functions (spring–mass–damper, quarter
//! car written as polynomials), against an independent dense complex solve on random
//! systems (proptest), poles on the axis, automatic ranges and phase unwrapping.

mod closed_forms;

use std::f64::consts::PI;

use closed_forms::{poly, poly_mul, poly_sub, random_matrix, rel, rng, smd};
use eom_num::freq::{
    FreqOptions, FreqRange, FreqUnit, FrequencyResponse, HessenbergForm, LANES, SolveStatus,
    evaluate_at, freq_workspace_bytes,
};
use eom_num::{
    Bound, DimensionError, NonFiniteError, NumError, OptionError, SingularError, StateSpace,
};
use nalgebra::{DMatrix, dmatrix};
use num_complex::Complex64;
use proptest::prelude::*;
use rand::Rng;

#[test]
fn smd_matches_closed_form() {
    let (m, c, k) = (1.3, 0.7, 900.0);
    let ss = smd(m, c, k);
    let fr = FrequencyResponse::compute(&ss, &FreqOptions::default()).unwrap();
    assert!(!fr.is_empty());
    // Auto range: ω_n/2π = 4.18 Hz → decades floor(log10 2.09) = 0 … ceil(log10 8.36) = 1,
    // widened to one decade: 1 … 10 Hz, 200 points per decade, both ends included.
    assert_eq!(fr.len(), 201);
    assert!((fr.freq_hz[0] - 1.0).abs() < 1e-12 && (fr.freq_hz[200] - 10.0).abs() < 1e-11);
    for (k_, &w) in fr.omega.iter().enumerate() {
        let s = Complex64::new(0.0, w);
        let exact = 1.0 / poly(&[k, c, m], s);
        let got = fr.series(0, 0)[k_];
        assert!(rel(got, exact) < 1e-10, "ω = {w}: {got} vs {exact}");
        let db = 20.0 * exact.norm().log10();
        assert!((fr.magnitude_db_of(0, 0)[k_] - db).abs() < 1e-9);
    }
    // Phase of a second-order lag: 0 → −180 through −90 at ω_n, no wrap.
    let ph = fr.phase_deg_of(0, 0);
    assert!(ph.iter().all(|&p| (-180.0..=0.0).contains(&p)), "{ph:?}");
    assert!(!fr.singular.iter().any(|&s| s));
}

/// Quarter car: sprung mass ms, unsprung mu, suspension ks/cs, tyre kt/ct driven by the road
/// displacement zr (the tyre damper makes it a rate input). State (zs, zu, żs, w) with
/// w = żu − (ct/mu) zr so that żr does not appear; outputs zs, tyre deflection zu − zr, z̈s.
fn quarter_car(ms: f64, mu: f64, ks: f64, cs: f64, kt: f64, ct: f64) -> StateSpace<f64> {
    let g = ct / mu;
    let a = dmatrix![
        0.0, 0.0, 1.0, 0.0;
        0.0, 0.0, 0.0, 1.0;
        -ks / ms, ks / ms, -cs / ms, cs / ms;
        ks / mu, -(ks + kt) / mu, cs / mu, -(cs + ct) / mu
    ];
    let b = dmatrix![0.0; g; cs * g / ms; (-cs * g + kt - ct * g) / mu];
    let c = dmatrix![
        1.0, 0.0, 0.0, 0.0;
        0.0, 1.0, 0.0, 0.0;
        -ks / ms, ks / ms, -cs / ms, cs / ms
    ];
    let d = dmatrix![0.0; -1.0; cs * g / ms];
    StateSpace::new(a, b, c, d).unwrap()
}

#[test]
fn quarter_car_matches_polynomial_transfer_functions() {
    let (ms, mu, ks, cs, kt, ct) = (400.0, 40.0, 2.0e4, 1.5e3, 2.0e5, 200.0);
    let ss = quarter_car(ms, mu, ks, cs, kt, ct);
    // Laplace of  ms z̈s = −ks(zs − zu) − cs(żs − żu),
    //             mu z̈u =  ks(zs − zu) + cs(żs − żu) − kt(zu − zr) − ct(żu − żr):
    // Zs/Zr = (cs s + ks)(ct s + kt)/Δ,  Zu/Zr = (ms s² + cs s + ks)(ct s + kt)/Δ,
    // Δ = (ms s² + cs s + ks)(mu s² + (cs + ct) s + ks + kt) − (cs s + ks)².
    let body = [ks, cs, ms];
    let wheel = [ks + kt, cs + ct, mu];
    let coupling = [ks, cs];
    let tyre = [kt, ct];
    let delta = poly_sub(&poly_mul(&body, &wheel), &poly_mul(&coupling, &coupling));
    let num_s = poly_mul(&coupling, &tyre);
    let num_u = poly_mul(&body, &tyre);
    let num_acc = poly_mul(&num_s, &[0.0, 0.0, 1.0]);
    let num_defl = poly_sub(&num_u, &delta);

    let fr = FrequencyResponse::compute(&ss, &FreqOptions::default()).unwrap();
    // Body ≈ 1.1 Hz, wheel ≈ 12 Hz → 0.1 … 100 Hz.
    assert!(
        (fr.freq_hz[0] - 0.1).abs() < 1e-13 && (fr.freq_hz[fr.len() - 1] - 100.0).abs() < 1e-10
    );
    assert_eq!(fr.len(), 3 * 200 + 1);
    let mut worst: f64 = 0.0;
    for (k, &w) in fr.omega.iter().enumerate() {
        let s = Complex64::new(0.0, w);
        let d = poly(&delta, s);
        let exact = [
            poly(&num_s, s) / d,
            poly(&num_defl, s) / d,
            poly(&num_acc, s) / d,
        ];
        for (i, e) in exact.iter().enumerate() {
            let got = fr.series(i, 0)[k];
            worst = worst.max(rel(got, *e));
        }
    }
    assert!(worst < 1e-10, "worst relative error {worst:e}");
    // z_s/z_r: phase starts at 0° and is continuous. Independent unwrap of the closed form:
    // accumulate arg(G_k / G_{k−1}) along the (fine) grid.
    let ph = fr.phase_deg_of(0, 0);
    assert!(ph[0].abs() < 1.0, "{}", ph[0]);
    let g = |w: f64| {
        let s = Complex64::new(0.0, w);
        poly(&num_s, s) / poly(&delta, s)
    };
    let mut acc = g(fr.omega[0]).arg().to_degrees();
    for (k, w) in fr.omega.windows(2).enumerate() {
        acc += (g(w[1]) / g(w[0])).arg().to_degrees();
        assert!(
            (ph[k + 1] - acc).abs() < 1e-8,
            "k = {}: {} vs {acc}",
            k + 1,
            ph[k + 1]
        );
    }
    // Past both modes (4 poles) and the zero at ks/cs, below the zero at kt/ct: about −235°.
    assert!(
        (-270.0..-180.0).contains(&ph[ph.len() - 1]),
        "{}",
        ph[ph.len() - 1]
    );
}

#[test]
fn phase_is_unwrapped_through_many_turns() {
    // Six poles at −1 (cascade of first-order lags): the phase falls to −540°, never wrapped.
    let n = 6;
    let mut a = DMatrix::<f64>::zeros(n, n);
    for i in 0..n {
        a[(i, i)] = -1.0;
        if i > 0 {
            a[(i, i - 1)] = 1.0;
        }
    }
    let mut b = DMatrix::zeros(n, 1);
    b[(0, 0)] = 1.0;
    let mut c = DMatrix::zeros(1, n);
    c[(0, n - 1)] = 1.0;
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
    let opts = FreqOptions {
        range: FreqRange::Range {
            low: 1e-3,
            high: 1e3,
            unit: FreqUnit::RadPerSec,
        },
        points_per_decade: 50,
    };
    let fr = FrequencyResponse::compute(&ss, &opts).unwrap();
    assert!((fr.omega[0] - 1e-3).abs() < 1e-15 && (fr.omega[fr.len() - 1] - 1e3).abs() < 1e-9);
    let ph = fr.phase_deg_of(0, 0);
    for (k, &w) in fr.omega.iter().enumerate() {
        let exact = -6.0 * w.atan().to_degrees();
        assert!(
            (ph[k] - exact).abs() < 1e-9,
            "ω = {w}: {} vs {exact}",
            ph[k]
        );
    }
}

#[test]
fn pole_on_the_axis_is_flagged_not_garbage() {
    // Undamped oscillator at exactly 1 Hz, evaluated at 0.5, 1 and 2 Hz.
    let w = 2.0 * PI;
    let ss = StateSpace::new(
        dmatrix![0.0, 1.0; -w * w, 0.0],
        dmatrix![0.0; 1.0],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let opts = FreqOptions {
        range: FreqRange::Points {
            values: vec![0.5, 1.0, 2.0],
            unit: FreqUnit::Hz,
        },
        ..Default::default()
    };
    let fr = FrequencyResponse::compute(&ss, &opts).unwrap();
    assert_eq!(fr.singular, [false, true, false]);
    assert_eq!(fr.series(0, 0)[1].re, f64::INFINITY);
    assert_eq!(fr.magnitude_db_of(0, 0)[1], f64::INFINITY);
    assert!(!fr.phase_deg_of(0, 0)[1].is_nan());
    for k in [0, 2] {
        let s = Complex64::new(0.0, fr.omega[k]);
        assert!(rel(fr.series(0, 0)[k], 1.0 / (s * s + w * w)) < 1e-12);
    }
    match evaluate_at(&ss, Complex64::new(0.0, w)) {
        Err(NumError::Singular(SingularError::Eigenvalue { n: 2, .. })) => {}
        other => panic!("expected Singular, got {other:?}"),
    }
}

#[test]
fn all_zero_eigenvalues_get_a_default_range() {
    // A pure integrator: EoM.jl throws here (minimum of an empty set).
    let ss = StateSpace::new(dmatrix![0.0], dmatrix![1.0], dmatrix![1.0], dmatrix![0.0]).unwrap();
    let fr = FrequencyResponse::compute(&ss, &FreqOptions::default()).unwrap();
    assert!((fr.freq_hz[0] - 0.01).abs() < 1e-15);
    assert!((fr.freq_hz[fr.len() - 1] - 100.0).abs() < 1e-10);
    assert_eq!(fr.len(), 801);
    for (k, &w) in fr.omega.iter().enumerate() {
        let exact = Complex64::new(0.0, -1.0 / w);
        assert!(rel(fr.series(0, 0)[k], exact) < 1e-14);
        assert!((fr.phase_deg_of(0, 0)[k] + 90.0).abs() < 1e-12);
    }
    // A static gain (no states) is evaluated too.
    let ss = StateSpace::new(
        DMatrix::zeros(0, 0),
        DMatrix::zeros(0, 1),
        DMatrix::zeros(1, 0),
        dmatrix![-2.0],
    )
    .unwrap();
    let fr = FrequencyResponse::compute(&ss, &FreqOptions::default()).unwrap();
    assert!(
        fr.series(0, 0)
            .iter()
            .all(|g| *g == Complex64::new(-2.0, 0.0))
    );
    assert!(fr.phase_deg_of(0, 0).iter().all(|&p| p == 180.0));
}

#[test]
fn kernel_and_evaluate_at_agree_with_closed_form() {
    let ss = smd(2.0, 3.0, 50.0);
    let form = HessenbergForm::new(&ss).unwrap();
    assert_eq!(form.dims(), (2, 1, 1));
    let mut ws = form.workspace();
    assert_eq!(freq_workspace_bytes(2, 1), 16 * (4 + 2 + 2));
    let mut out = [Complex64::new(0.0, 0.0)];
    for s in [
        Complex64::new(-0.4, 3.0),
        Complex64::new(7.0, -1.0),
        Complex64::new(0.0, 0.0),
    ] {
        assert_eq!(
            form.evaluate_in(s, &mut ws, &mut out).unwrap(),
            SolveStatus::Regular
        );
        let exact = 1.0 / poly(&[50.0, 3.0, 2.0], s);
        assert!(rel(out[0], exact) < 1e-14, "{s}");
        assert!(rel(evaluate_at(&ss, s).unwrap()[(0, 0)], exact) < 1e-14);
    }
}

/// `C (sI − A)⁻¹ B + D` by nalgebra's dense complex LU (an independent implementation).
fn dense(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    s: Complex64,
) -> (DMatrix<Complex64>, f64) {
    let n = a.nrows();
    let m = DMatrix::from_fn(n, n, |i, j| {
        Complex64::new(
            if i == j { s.re } else { 0.0 },
            if i == j { s.im } else { 0.0 },
        ) - a[(i, j)]
    });
    let sv = m.clone().singular_values();
    let (smax, smin) = (sv.max(), sv.min());
    let x = m.lu().solve(&b.map(|v| Complex64::new(v, 0.0))).unwrap();
    let g = c.map(|v| Complex64::new(v, 0.0)) * x + d.map(|v| Complex64::new(v, 0.0));
    // Perturbation bound scale: cond(sI − A) · ‖C‖ ‖B‖ / σ_min.
    (g, smax / smin * c.norm() * b.norm() / smin)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]
    #[test]
    fn hessenberg_path_matches_dense_solve(
        seed in any::<u64>(),
        n in 1usize..13,
        m in 1usize..4,
        p in 1usize..4,
        logw in -2.0f64..2.0,
        sigma in -1.0f64..1.0,
    ) {
        let mut r = rng(seed);
        let a = random_matrix(&mut r, n, n) * 2.0;
        let b = random_matrix(&mut r, n, m);
        let c = random_matrix(&mut r, p, n);
        let d = random_matrix(&mut r, p, m);
        let s = Complex64::new(sigma, 10f64.powf(logw));
        let (g_ref, bound) = dense(&a, &b, &c, &d, s);
        // The same system in badly scaled coordinates x' = S x (S = 10^U(−3, 3)): same G(s).
        let sc: Vec<f64> = (0..n).map(|_| 10f64.powf(r.random_range(-3.0..3.0))).collect();
        let a2 = DMatrix::from_fn(n, n, |i, j| sc[i] * a[(i, j)] / sc[j]);
        let b2 = DMatrix::from_fn(n, m, |i, j| sc[i] * b[(i, j)]);
        let c2 = DMatrix::from_fn(p, n, |i, j| c[(i, j)] / sc[j]);
        for ss in [
            StateSpace::new(a.clone(), b.clone(), c.clone(), d.clone()).unwrap(),
            StateSpace::new(a2, b2, c2, d.clone()).unwrap(),
        ] {
            let form = HessenbergForm::new(&ss).unwrap();
            let mut ws = form.workspace();
            let mut out = vec![Complex64::new(0.0, 0.0); p * m];
            let st = form.evaluate_in(s, &mut ws, &mut out).unwrap();
            prop_assert_eq!(st, SolveStatus::Regular);
            let g = DMatrix::from_vec(p, m, out);
            let err = (&g - &g_ref).norm();
            let tol = 1e-13 * ((n + 1) * (n + 1)) as f64 * bound + 1e-14 * (1.0 + d.norm());
            prop_assert!(err <= tol, "n = {} err {:e} tol {:e}", n, err, tol);

            // The batched kernel (used by FrequencyResponse) on four different points, each
            // checked against its own dense solve.
            let pts = [s, s.conj(), Complex64::new(s.re, 3.0 * s.im), Complex64::new(-s.re, 0.2 * s.im)];
            let mut bws = form.batch_workspace();
            let mut bout = vec![Complex64::new(0.0, 0.0); LANES * p * m];
            let mut st = [SolveStatus::Singular; LANES];
            form.evaluate_batch_in(&pts, &mut bws, &mut bout, &mut st).unwrap();
            for (l, &pt) in pts.iter().enumerate() {
                let (gl, bl) = dense(&a, &b, &c, &d, pt);
                prop_assert_eq!(st[l], SolveStatus::Regular);
                let g = DMatrix::from_column_slice(p, m, &bout[l * p * m..(l + 1) * p * m]);
                let err = (&g - &gl).norm();
                let tol = 1e-13 * ((n + 1) * (n + 1)) as f64 * bl + 1e-14 * (1.0 + d.norm());
                prop_assert!(err <= tol, "batch lane {} n = {} err {:e} tol {:e}", l, n, err, tol);
            }
        }
    }
}

#[test]
fn freq_errors_name_the_problem() {
    let ss = smd(1.0, 1.0, 1.0);
    let zero_ppd = FreqOptions {
        points_per_decade: 0,
        ..Default::default()
    };
    assert!(matches!(
        FrequencyResponse::compute(&ss, &zero_ppd),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "FreqOptions::points_per_decade",
            must: Bound::AtLeastOne,
            ..
        }))
    ));
    let bad_range = FreqOptions {
        range: FreqRange::Range {
            low: 10.0,
            high: 1.0,
            unit: FreqUnit::Hz,
        },
        ..Default::default()
    };
    assert!(matches!(
        FrequencyResponse::compute(&ss, &bad_range),
        Err(NumError::InvalidOption(OptionError::FrequencyRange { .. }))
    ));
    let huge = FreqOptions {
        range: FreqRange::Range {
            low: 1e-3,
            high: 1e3,
            unit: FreqUnit::Hz,
        },
        points_per_decade: 1_000_000_000,
    };
    assert!(matches!(
        FrequencyResponse::compute(&ss, &huge),
        Err(NumError::InvalidOption(
            OptionError::FrequencyGridTooLarge {
                per_decade: 1_000_000_000,
                ..
            }
        ))
    ));
    let bad_points = FreqOptions {
        range: FreqRange::Points {
            values: vec![1.0, -2.0],
            unit: FreqUnit::RadPerSec,
        },
        ..Default::default()
    };
    assert!(matches!(
        FrequencyResponse::compute(&ss, &bad_points),
        Err(NumError::InvalidOption(OptionError::FrequencyPoint {
            value: -2.0
        }))
    ));
    let form = HessenbergForm::new(&ss).unwrap();
    let mut ws = form.workspace();
    let mut short: [Complex64; 0] = [];
    assert!(matches!(
        form.evaluate_in(Complex64::new(0.0, 1.0), &mut ws, &mut short),
        Err(NumError::Dimension(DimensionError::FreqWorkspace {
            function: "evaluate_in",
            out: 0,
            ..
        }))
    ));
    let mut bws = form.batch_workspace();
    let mut st = [SolveStatus::Regular; LANES];
    let mut bout = vec![Complex64::new(0.0, 0.0); LANES];
    let pts = [Complex64::new(0.0, 1.0); LANES];
    form.evaluate_batch_in(&pts, &mut bws, &mut bout, &mut st)
        .unwrap();
    assert!(matches!(
        form.evaluate_batch_in(&pts, &mut bws, &mut short, &mut st),
        Err(NumError::Dimension(DimensionError::FreqWorkspace {
            function: "evaluate_batch_in",
            ..
        }))
    ));
    let mut bad = pts;
    bad[2] = Complex64::new(0.0, f64::INFINITY);
    assert!(matches!(
        form.evaluate_batch_in(&bad, &mut bws, &mut bout, &mut st),
        Err(NumError::NonFinite(_))
    ));
    assert!(matches!(
        evaluate_at(&ss, Complex64::new(f64::NAN, 1.0)),
        Err(NumError::NonFinite(NonFiniteError::EvaluationPoint { .. }))
    ));
}
