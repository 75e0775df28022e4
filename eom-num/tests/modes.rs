//! Eigenvalues and modal quantities against closed forms; instantaneous centres against a
//! hand-built rigid body rotating about a known point.

mod closed_forms;

use std::f64::consts::PI;

use closed_forms::{random_similarity, rel, rng, smd};
use eom_num::modes::{
    EigenvaluesWorkspace, ModeKind, ModeOptions, Modes, Stability, eigenvalues, eigenvalues_in,
    eigenvalues_workspace_bytes,
};
use eom_num::{
    Bound, DimensionError, MatrixEntry, NonFiniteError, NumError, OptionError, SignalNames,
    StateSpace,
};
use nalgebra::{DMatrix, Vector3, dmatrix};
use num_complex::Complex64;

#[test]
fn smd_eigenvalues_frequency_and_damping() {
    let (m, c, k) = (2.0, 1.2, 800.0);
    let ss = smd(m, c, k);
    let sigma = -c / (2.0 * m);
    let wd = (k / m - c * c / (4.0 * m * m)).sqrt();
    let ev = eigenvalues(&ss.a).unwrap();
    assert!(rel(ev[0], Complex64::new(sigma, -wd)) < 1e-14, "{ev:?}");
    assert!(rel(ev[1], Complex64::new(sigma, wd)) < 1e-14, "{ev:?}");
    assert_eq!(ev[0], ev[1].conj(), "exact conjugates");

    let modes = Modes::compute(&ss).unwrap();
    let wn = (k / m).sqrt();
    let zeta = c / (2.0 * (k * m).sqrt());
    assert_eq!(modes.modes.len(), 2);
    for md in &modes.modes {
        assert_eq!(md.kind, ModeKind::Oscillatory);
        assert_eq!(md.stability, Stability::Stable);
        assert!((md.natural_frequency_hz - wn / (2.0 * PI)).abs() < 1e-14 * wn);
        assert!((md.damping_ratio.unwrap() - zeta).abs() < 1e-14);
        assert!((md.time_constant - 2.0 * m / c).abs() < 1e-13 * 2.0 * m / c);
        assert!((md.damped_period - 2.0 * PI / wd).abs() < 1e-14 * 2.0 * PI / wd);
    }
    assert_eq!(modes.distinct().count(), 1);
    assert!(modes.is_stable());
}

/// A = T diag(−2, [[−1, 2], [−2, −1]], 0) T⁻¹: a real pole, a complex pair −1 ± 2i and a zero
/// eigenvalue, hidden by a random similarity.
#[test]
fn real_pole_complex_pair_and_zero() {
    let core = dmatrix![
        -2.0, 0.0, 0.0, 0.0;
        0.0, -1.0, 2.0, 0.0;
        0.0, -2.0, -1.0, 0.0;
        0.0, 0.0, 0.0, 0.0
    ];
    let mut r = rng(7);
    let t = random_similarity(&mut r, 4);
    let a = &t * core * t.clone().try_inverse().unwrap();
    let ss = StateSpace::new(
        a,
        DMatrix::zeros(4, 0),
        DMatrix::zeros(0, 4),
        DMatrix::zeros(0, 0),
    )
    .unwrap();
    let modes = Modes::compute(&ss).unwrap();
    let kinds: Vec<ModeKind> = modes.modes.iter().map(|m| m.kind).collect();
    // Sorted by (Re, Im): −2, −1 − 2i, −1 + 2i, 0.
    assert_eq!(
        kinds,
        [
            ModeKind::Real,
            ModeKind::Oscillatory,
            ModeKind::Oscillatory,
            ModeKind::Zero
        ]
    );
    let real = &modes.modes[0];
    assert!(
        (real.natural_frequency_hz - 2.0 / (2.0 * PI)).abs() < 1e-13,
        "corner frequency"
    );
    assert_eq!(real.damping_ratio, Some(1.0));
    assert!((real.time_constant - 0.5).abs() < 1e-13);
    assert_eq!(real.damped_period, f64::INFINITY);
    assert_eq!(real.stability, Stability::Stable);

    let osc = &modes.modes[2];
    assert!(osc.eigenvalue.im > 0.0);
    assert!((osc.natural_frequency_hz - 5f64.sqrt() / (2.0 * PI)).abs() < 1e-13);
    assert!((osc.damping_ratio.unwrap() - 1.0 / 5f64.sqrt()).abs() < 1e-13);
    assert!((osc.time_constant - 1.0).abs() < 1e-13);
    assert!((osc.damped_period - PI).abs() < 1e-13);

    let zero = &modes.modes[3];
    assert_eq!(zero.natural_frequency_hz, 0.0);
    assert_eq!(zero.damping_ratio, None);
    assert_eq!(zero.time_constant, f64::INFINITY);
    assert_eq!(zero.damped_period, f64::INFINITY);
    assert_eq!(zero.stability, Stability::Marginal);
    assert!(!modes.is_stable());
    // No NaN anywhere.
    for md in &modes.modes {
        for v in [md.natural_frequency_hz, md.time_constant, md.damped_period] {
            assert!(!v.is_nan());
        }
    }
}

#[test]
fn unstable_real_pole_reports_negative_damping_and_growth_time() {
    let ss = StateSpace::new(dmatrix![3.0], dmatrix![1.0], dmatrix![1.0], dmatrix![0.0]).unwrap();
    let md = &Modes::compute(&ss).unwrap().modes[0];
    assert_eq!(md.kind, ModeKind::Real);
    assert_eq!(md.stability, Stability::Unstable);
    assert_eq!(md.damping_ratio, Some(-1.0));
    assert!((md.time_constant + 1.0 / 3.0).abs() < 1e-15);
    assert!((md.natural_frequency_hz - 3.0 / (2.0 * PI)).abs() < 1e-15);
}

#[test]
fn rigid_body_double_zero_is_zero_and_slow_pole_is_not() {
    // A free mass (x'' = 0, a Jordan block) next to a stiff spring–damper, mixed by a
    // similarity: the computed double zero is split at the √ε level and must still be Zero.
    let core = dmatrix![
        0.0, 1.0, 0.0, 0.0;
        0.0, 0.0, 0.0, 0.0;
        0.0, 0.0, 0.0, 1.0;
        0.0, 0.0, -1e6, -50.0
    ];
    let mut r = rng(11);
    let t = random_similarity(&mut r, 4);
    let a = &t * core * t.clone().try_inverse().unwrap();
    let ss = StateSpace::new(
        a,
        DMatrix::zeros(4, 0),
        DMatrix::zeros(0, 4),
        DMatrix::zeros(0, 0),
    )
    .unwrap();
    let modes = Modes::compute(&ss).unwrap();
    let zeros = modes
        .modes
        .iter()
        .filter(|m| m.kind == ModeKind::Zero)
        .count();
    assert_eq!(zeros, 2, "{:?}", modes.eigenvalues());

    // A genuinely slow pole −1e-9 next to −1e3: EoM.jl's absolute 1e-7 threshold would call it
    // τ = ∞; the condition-aware tolerance keeps it a real pole with τ = 1e9 s.
    let core = dmatrix![-1e-9, 0.0; 0.0, -1e3];
    let t = random_similarity(&mut r, 2);
    let a = &t * core * t.clone().try_inverse().unwrap();
    let ss = StateSpace::new(
        a,
        DMatrix::zeros(2, 0),
        DMatrix::zeros(0, 2),
        DMatrix::zeros(0, 0),
    )
    .unwrap();
    let md = &Modes::compute(&ss).unwrap().modes[1];
    assert_eq!(md.kind, ModeKind::Real);
    assert_eq!(md.stability, Stability::Stable);
    assert!(
        (md.time_constant - 1e9).abs() < 1e-4 * 1e9,
        "τ = {}",
        md.time_constant
    );
}

/// One body on a torsional pendulum: it rotates by θ about the axis `axis` through the
/// point `pivot` (relative to the mass centre). The mass centre moves by θ·axis × (−pivot).
fn pendulum_about(axis: Vector3<f64>, pivot: Vector3<f64>, damping: f64) -> StateSpace<f64> {
    let axis = axis.normalize();
    let t = axis.cross(&(-pivot));
    let mut phys = DMatrix::zeros(6, 2);
    for i in 0..3 {
        phys[(i, 0)] = t[i];
        phys[(i + 3, 0)] = axis[i];
    }
    let names = SignalNames {
        bodies: vec!["arm".into()],
        ..Default::default()
    };
    StateSpace::new(
        dmatrix![0.0, 1.0; -9.0, -damping],
        DMatrix::zeros(2, 0),
        DMatrix::zeros(0, 2),
        DMatrix::zeros(0, 0),
    )
    .unwrap()
    .with_phys(phys)
    .unwrap()
    .with_names(names)
    .unwrap()
}

#[test]
fn instantaneous_centre_of_a_pure_rotation() {
    // Axis y, pivot 1.6 m above the mass centre: the centre is at (0, 0, 1.6), axis (0, 1, 0).
    let l = 1.6;
    for damping in [0.0, 0.7] {
        let ss = pendulum_about(Vector3::y(), Vector3::new(0.0, 0.0, l), damping);
        let modes = Modes::compute(&ss).unwrap();
        for md in &modes.modes {
            // Shape: x = −L θ (largest, normalised to 0.5), ry = θ.
            assert_eq!(md.reference_index, Some(0));
            assert_eq!(md.shape[0], Complex64::new(0.5, 0.0));
            assert!(
                rel(md.shape[4], Complex64::new(-0.5 / l, 0.0)) < 1e-14,
                "{}",
                md.shape
            );
            let c = &md.centres[0];
            assert_eq!(c.body, "arm");
            let r = c.radius.unwrap();
            let want = [0.0, 0.0, l];
            for i in 0..3 {
                assert!(
                    (r[i] - Complex64::new(want[i], 0.0)).norm() < 1e-14,
                    "{r:?}"
                );
            }
            let ax = c.axis.unwrap();
            assert!((ax[1] - Complex64::new(1.0, 0.0)).norm() < 1e-15, "{ax:?}");
            assert!(ax[0].norm() < 1e-15 && ax[2].norm() < 1e-15);
        }
    }
}

#[test]
fn instantaneous_centre_general_axis_is_the_perpendicular_foot() {
    // Generic axis and pivot: the minimum-norm centre is the part of the pivot vector
    // perpendicular to the axis.
    let axis = Vector3::new(0.3, -0.5, 0.81).normalize();
    let pivot = Vector3::new(0.4, 1.1, -0.25);
    let ss = pendulum_about(axis, pivot, 0.3);
    let modes = Modes::compute(&ss).unwrap();
    let want = pivot - axis * axis.dot(&pivot);
    for md in &modes.modes {
        let c = &md.centres[0];
        let r = c.radius.unwrap();
        for i in 0..3 {
            assert!(
                (r[i] - Complex64::new(want[i], 0.0)).norm() < 1e-13,
                "{r:?} vs {want:?}"
            );
        }
        let ax = c.axis.unwrap();
        // Dominant rotation component (z) real positive, direction ± axis.
        let sign = axis[2].signum();
        for i in 0..3 {
            assert!(
                (ax[i] - Complex64::new(sign * axis[i], 0.0)).norm() < 1e-13,
                "{ax:?}"
            );
        }
    }
}

#[test]
fn pure_translation_has_no_centre() {
    let mut phys = DMatrix::zeros(6, 2);
    phys[(2, 0)] = 1.0; // vertical translation only
    let ss = smd(1.0, 0.1, 4.0).with_phys(phys).unwrap();
    let modes = Modes::compute(&ss).unwrap();
    for md in &modes.modes {
        assert_eq!(md.centres.len(), 1);
        assert_eq!(md.centres[0].body, "body 1");
        assert!(md.centres[0].radius.is_none() && md.centres[0].axis.is_none());
    }
}

/// Mode shapes through a sparse map (one body coordinate per state, the product skips the
/// zeros) and through a dense one: every shape must be `phys · x` for an eigenvector x of its
/// eigenvalue. Checked independently: x recovered from the shape by least squares, then the
/// residual of `(A − λI) x`; and the largest entry is exactly 0.5.
#[test]
fn mode_shapes_are_the_map_of_an_eigenvector_sparse_and_dense() {
    let mut r = rng(17);
    let n = 24;
    let a = closed_forms::random_matrix(&mut r, n, n);
    let sparse = DMatrix::from_fn(6 * n, n, |i, j| {
        if i / 6 == j && i % 6 == j % 6 {
            1.5
        } else {
            0.0
        }
    });
    let dense = closed_forms::random_matrix(&mut r, 6 * n, n);
    for phys in [sparse, dense] {
        let ss = StateSpace::new(
            a.clone(),
            DMatrix::zeros(n, 1),
            DMatrix::zeros(1, n),
            DMatrix::zeros(1, 1),
        )
        .unwrap()
        .with_phys(phys.clone())
        .unwrap();
        let modes = Modes::compute(&ss).unwrap();
        let pc = phys.map(|v| Complex64::new(v, 0.0));
        let svd = pc.clone().svd(true, true);
        for m in &modes.modes {
            let idx = m.reference_index.expect("every mode moves a body");
            assert_eq!(m.shape[idx], Complex64::new(0.5, 0.0));
            assert!(m.shape.iter().all(|z| z.norm() <= 0.5 * (1.0 + 1e-15)));
            let x = svd.solve(&m.shape, 1e-12).unwrap();
            let fit = (&pc * &x - &m.shape).norm();
            assert!(fit < 1e-12, "shape not in the range of phys: {fit:e}");
            let ac = a.map(|v| Complex64::new(v, 0.0));
            let res = (&ac * &x - &x * m.eigenvalue).norm() / (x.norm() * ac.norm());
            assert!(res < 1e-12, "λ = {}: residual {res:e}", m.eigenvalue);
        }
    }
}

#[test]
fn kernel_matches_allocating_version() {
    let mut r = rng(3);
    let n = 9;
    let a = closed_forms::random_matrix(&mut r, n, n);
    let mut ws = EigenvaluesWorkspace::new(n);
    assert_eq!(ws.dim(), n);
    assert!(eigenvalues_workspace_bytes(n) > 8 * n * n);
    let mut out = vec![Complex64::new(0.0, 0.0); n];
    eigenvalues_in(&a, &mut ws, &mut out).unwrap();
    assert_eq!(out, eigenvalues(&a).unwrap());
    // Sum of eigenvalues = trace, product = determinant (independent invariants).
    let tr: Complex64 = out.iter().sum();
    assert!((tr.re - a.trace()).abs() < 1e-13 * n as f64);
    let det: Complex64 = out.iter().product();
    assert!((det.re - a.determinant()).abs() < 1e-12 * a.determinant().abs().max(1.0));
    // Sorted by (re, im).
    for w in out.windows(2) {
        assert!(w[0].re < w[1].re || (w[0].re == w[1].re && w[0].im <= w[1].im));
    }
}

#[test]
fn mode_errors_name_the_problem() {
    match eigenvalues(&DMatrix::zeros(2, 3)) {
        Err(NumError::Dimension(DimensionError::NotSquare {
            rows: 2, cols: 3, ..
        })) => {}
        other => panic!("expected Dimension, got {other:?}"),
    }
    match eigenvalues(&dmatrix![1.0, f64::NAN; 0.0, 1.0]) {
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry {
            ref matrix,
            row: 0,
            col: 1,
            ..
        }))) if matrix == "A" => {}
        other => panic!("expected NonFinite, got {other:?}"),
    }
    let mut ws = EigenvaluesWorkspace::new(3);
    let mut out = vec![Complex64::new(0.0, 0.0); 2];
    match eigenvalues_in(&DMatrix::identity(2, 2), &mut ws, &mut out) {
        Err(NumError::Dimension(DimensionError::EigenWorkspace { workspace: 3, .. })) => {}
        other => panic!("expected Dimension, got {other:?}"),
    }
    let ss = smd(1.0, 1.0, 1.0);
    let bad = ModeOptions {
        tol_factor: 0.0,
        ..Default::default()
    };
    match Modes::compute_with(&ss, &bad) {
        Err(NumError::InvalidOption(OptionError::Value {
            option: "ModeOptions::tol_factor",
            value: 0.0,
            must: Bound::FinitePositive,
        })) => {}
        other => panic!("expected InvalidOption, got {other:?}"),
    }
    // A hand-filled model with inconsistent fields is caught by validation.
    let mut broken = ss.clone();
    broken.c = DMatrix::zeros(1, 3);
    match Modes::compute(&broken) {
        Err(NumError::Dimension(DimensionError::Shape {
            matrix: "C",
            rows: 1,
            cols: 3,
            ..
        })) => {}
        other => panic!("expected Dimension, got {other:?}"),
    }
    // StateSpace constructors.
    assert!(matches!(
        StateSpace::new(
            DMatrix::zeros(2, 2),
            DMatrix::zeros(3, 1),
            DMatrix::zeros(1, 2),
            DMatrix::zeros(1, 1)
        ),
        Err(NumError::Dimension(DimensionError::Shape {
            matrix: "B",
            rows: 3,
            cols: 1,
            ..
        }))
    ));
    assert!(matches!(
        StateSpace::new(dmatrix![f64::INFINITY], dmatrix![1.0], dmatrix![1.0], dmatrix![0.0]),
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry {
            ref matrix,
            row: 0,
            col: 0,
            ..
        }))) if matrix == "A"
    ));
    assert!(matches!(
        ss.clone().with_phys(DMatrix::zeros(6, 3)),
        Err(NumError::Dimension(DimensionError::PhysColumns {
            rows: 6,
            cols: 3,
            ..
        }))
    ));
    let names = SignalNames {
        inputs: vec!["a".into(), "b".into()],
        ..Default::default()
    };
    assert!(matches!(
        ss.clone().with_names(names),
        Err(NumError::Dimension(DimensionError::NamesLength {
            field: "inputs",
            ..
        }))
    ));
    let names = SignalNames {
        bodies: vec!["a".into()],
        ..Default::default()
    };
    assert!(matches!(
        ss.with_names(names),
        Err(NumError::Dimension(DimensionError::BodyRows { .. }))
    ));
}
