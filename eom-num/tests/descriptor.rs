//! Descriptor → state space against hand-derived index-1 examples, singular-pencil and
//! higher-index error cases, and finite generalized eigenvalues against closed forms.

mod closed_forms;

use closed_forms::{poly, rel};
use eom_num::descriptor::{
    DescriptorOptions, GenEigOptions, descriptor_to_state_space, generalized_eigenvalues,
    generalized_eigenvalues_with,
};
use eom_num::freq::evaluate_at;
use eom_num::linalg::RankTolerance;
use eom_num::modes::eigenvalues;
use eom_num::{
    A22Rank, Descriptor, DimensionError, MatrixEntry, NonFiniteError, NumError, OptionError,
    PencilError,
};
use nalgebra::{DMatrix, dmatrix};
use num_complex::Complex64;

/// Mass m on spring k1 to a massless node y, node on spring k2 to ground; force F on the
/// mass, force F2 on the node. States (x, v, y); outputs x and y.
///
/// ```text
///   ẋ = v
/// m v̇ = −k1 (x − y) + F
///   0 = k1 (x − y) − k2 y + F2      ⇒ y = (k1 x + F2)/(k1 + k2)
/// ```
fn series_springs(m: f64, k1: f64, k2: f64) -> Descriptor<f64> {
    Descriptor::new(
        DMatrix::from_diagonal(&nalgebra::dvector![1.0, m, 0.0]),
        dmatrix![0.0, 1.0, 0.0; -k1, 0.0, k1; k1, 0.0, -(k1 + k2)],
        dmatrix![0.0, 0.0; 1.0, 0.0; 0.0, 1.0],
        dmatrix![1.0, 0.0, 0.0; 0.0, 0.0, 1.0],
        DMatrix::zeros(2, 2),
    )
    .unwrap()
}

#[test]
fn index_one_series_springs_matches_hand_solution() {
    let (m, k1, k2) = (2.0, 300.0, 100.0);
    let dss = series_springs(m, k1, k2);
    let phys = DMatrix::<f64>::identity(3, 3);
    let opts = DescriptorOptions {
        phys: Some(&phys),
        ..Default::default()
    };
    let (ss, rep) = descriptor_to_state_space(&dss, &opts).unwrap();
    assert_eq!((rep.states, rep.dynamic, rep.algebraic), (3, 2, 1));
    assert_eq!(rep.e_rank.rank, 2);
    assert!(
        rep.e_rank.gap > 1e10,
        "exact zero in E: gap {}",
        rep.e_rank.gap
    );
    assert!(rep.warnings.is_empty(), "{:?}", rep.warnings);
    assert!(rep.a22_condition >= 1.0 && rep.a22_condition.is_finite());
    assert_eq!(ss.states(), 2);

    // Eigenvalues ±i √(k_eq/m), k_eq = k1 k2/(k1 + k2).
    let keq = k1 * k2 / (k1 + k2);
    let w = (keq / m).sqrt();
    let ev = eigenvalues(&ss.a).unwrap();
    assert!(rel(ev[0], Complex64::new(0.0, -w)) < 1e-12, "{ev:?}");
    assert!(rel(ev[1], Complex64::new(0.0, w)) < 1e-12, "{ev:?}");

    // Transfer functions from Laplace of the equations above.
    let kk = k1 + k2;
    let r = k1 / kk;
    for s in [
        Complex64::new(0.3, 1.7),
        Complex64::new(-2.0, 40.0),
        Complex64::new(5.0, 0.0),
    ] {
        let g = evaluate_at(&ss, s).unwrap();
        let den = poly(&[keq, 0.0, m], s); // m s² + k_eq
        let x_f = 1.0 / den;
        let x_f2 = r / den;
        let y_f = r / den;
        let y_f2 = 1.0 / kk + r * r / den;
        for (got, want) in [
            (g[(0, 0)], x_f),
            (g[(0, 1)], x_f2),
            (g[(1, 0)], y_f),
            (g[(1, 1)], y_f2),
        ] {
            assert!(rel(got, want) < 1e-12, "s = {s}: {got} vs {want}");
        }
    }
    // Feedthrough of F2 to y is 1/(k1 + k2), through the Schur complement.
    assert!((ss.d[(1, 1)] - 1.0 / kk).abs() < 1e-15 / kk * 10.0);
    assert_eq!(ss.d[(0, 0)], 0.0);

    // phys: with u = 0 the node follows the mass, y = k1/(k1 + k2) x, in every mode.
    assert_eq!(ss.phys.shape(), (3, 2));
    for j in 0..2 {
        let (x, y) = (ss.phys[(0, j)], ss.phys[(2, j)]);
        assert!(
            (y - r * x).abs() <= 1e-14 * x.abs().max(1.0),
            "column {j}: {x} {y}"
        );
    }
}

#[test]
fn index_one_with_mixed_scales_keeps_the_light_mass() {
    // A 1 g mass next to a 1000 t mass and stiff springs: rank E = 2 for any sensible
    // tolerance. Equilibration keeps the decision far from the threshold.
    let (m1, m2) = (1e-3, 1e6);
    let dss = Descriptor::new(
        DMatrix::from_diagonal(&nalgebra::dvector![1.0, 1.0, m1, m2, 0.0]),
        // States: x1, x2, v1, v2, node y (massless, between mass 1 and ground).
        dmatrix![
            0.0, 0.0, 1.0, 0.0, 0.0;
            0.0, 0.0, 0.0, 1.0, 0.0;
            -1e6, 0.0, 0.0, 0.0, 1e6;
            0.0, -1e9, 0.0, 0.0, 0.0;
            1e6, 0.0, 0.0, 0.0, -2e6
        ],
        DMatrix::from_fn(5, 1, |i, _| if i == 2 { 1.0 } else { 0.0 }),
        DMatrix::from_fn(1, 5, |_, j| if j == 0 { 1.0 } else { 0.0 }),
        DMatrix::zeros(1, 1),
    )
    .unwrap();
    let (ss, rep) = descriptor_to_state_space(&dss, &Default::default()).unwrap();
    assert_eq!(rep.dynamic, 4);
    assert!(rep.e_rank.margin > 1e6, "margin {}", rep.e_rank.margin);
    // Mass 1 sees k1 k2/(k1 + k2) = 5e5, mass 2 sees 1e9.
    let ev = eigenvalues(&ss.a).unwrap();
    let w1 = (5e5f64 / m1).sqrt();
    let w2 = (1e9f64 / m2).sqrt();
    let mut im: Vec<f64> = ev.iter().map(|z| z.im.abs()).collect();
    im.sort_by(f64::total_cmp);
    assert!(
        (im[0] - w2).abs() < 1e-10 * w2 && (im[2] - w1).abs() < 1e-10 * w1,
        "{ev:?}"
    );
}

#[test]
fn full_rank_e_keeps_coordinates() {
    let (m, c, k) = (3.0, 0.6, 12.0);
    let dss = Descriptor::new(
        dmatrix![1.0, 0.0; 0.0, m],
        dmatrix![0.0, 1.0; -k, -c],
        dmatrix![0.0; 1.0],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let phys = dmatrix![1.0, 0.0];
    let opts = DescriptorOptions {
        phys: Some(&phys),
        ..Default::default()
    };
    let (ss, rep) = descriptor_to_state_space(&dss, &opts).unwrap();
    assert_eq!(rep.algebraic, 0);
    let want = dmatrix![0.0, 1.0; -k / m, -c / m];
    assert!((&ss.a - want).norm() < 1e-15 * 10.0, "{}", ss.a);
    assert!((&ss.b - dmatrix![0.0; 1.0 / m]).norm() < 1e-16 * 10.0);
    assert_eq!(ss.phys, phys);
}

#[test]
fn singular_pencil_is_a_typed_error() {
    // Two identical algebraic equations: det(sE − A) ≡ 0.
    let dss = Descriptor::new(
        DMatrix::from_diagonal(&nalgebra::dvector![1.0, 0.0, 0.0]),
        dmatrix![-1.0, 0.0, 0.0; 0.0, 1.0, 1.0; 0.0, 1.0, 1.0],
        dmatrix![1.0; 0.0; 0.0],
        dmatrix![1.0, 0.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    match descriptor_to_state_space(&dss, &Default::default()) {
        Err(NumError::SingularPencil(PencilError::RankDeficient(A22Rank {
            k: 2,
            a22_rank: 1,
            ..
        }))) => {}
        other => panic!("expected SingularPencil, got {other:?}"),
    }
    match generalized_eigenvalues(&dss) {
        Err(NumError::SingularPencil(PencilError::VanishingEigenvalue { .. })) => {}
        other => panic!("expected SingularPencil, got {other:?}"),
    }
}

#[test]
fn index_two_is_a_typed_error() {
    // ẋ1 = x2, 0 = x1 − u: regular pencil (det(sE − A) = −1), index 2.
    let dss = Descriptor::new(
        dmatrix![1.0, 0.0; 0.0, 0.0],
        dmatrix![0.0, 1.0; 1.0, 0.0],
        dmatrix![0.0; -1.0],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    match descriptor_to_state_space(&dss, &Default::default()) {
        Err(NumError::HigherIndex(A22Rank {
            k: 1, a22_rank: 0, ..
        })) => {}
        other => panic!("expected HigherIndex, got {other:?}"),
    }
    // All eigenvalues are infinite.
    let ge = generalized_eigenvalues_with(&dss, &Default::default()).unwrap();
    assert!(ge.finite.is_empty(), "{:?}", ge.finite);
    assert_eq!(ge.infinite, 2);
}

#[test]
fn generalized_eigenvalues_of_smd_with_an_algebraic_force() {
    // m v̇ = −k x − c v + f_s, 0 = −f_s + 0 (a trivially algebraic state): finite
    // eigenvalues are those of the smd, one infinite.
    let (m, c, k) = (1.5, 0.9, 60.0);
    let dss = Descriptor::new(
        DMatrix::from_diagonal(&nalgebra::dvector![1.0, m, 0.0]),
        dmatrix![0.0, 1.0, 0.0; -k, -c, 1.0; 0.0, 0.0, -1.0],
        dmatrix![0.0; 0.0; 1.0],
        dmatrix![1.0, 0.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let ge = generalized_eigenvalues_with(&dss, &GenEigOptions::default()).unwrap();
    assert_eq!(ge.infinite, 1);
    let sigma = -c / (2.0 * m);
    let wd = (k / m - sigma * sigma).sqrt();
    assert_eq!(ge.finite.len(), 2);
    assert!(
        rel(ge.finite[0], Complex64::new(sigma, -wd)) < 1e-12,
        "{:?}",
        ge.finite
    );
    assert!(
        rel(ge.finite[1], Complex64::new(sigma, wd)) < 1e-12,
        "{:?}",
        ge.finite
    );
    assert_eq!(ge.finite[0], ge.finite[1].conj());
    assert!(ge.gap > 1e6);
}

#[test]
fn large_finite_eigenvalue_is_kept_scale_aware() {
    // det(sE − A) = (s + 1)(1e-10 s + 1)·1: eigenvalues −1 and −1e10, and one infinite.
    // EoM.jl's fixed |λ| < 1e9 filter would drop the genuine −1e10.
    let dss = Descriptor::new(
        DMatrix::from_diagonal(&nalgebra::dvector![1.0, 1e-10, 0.0]),
        DMatrix::from_diagonal(&nalgebra::dvector![-1.0, -1.0, 1.0]),
        DMatrix::zeros(3, 1),
        DMatrix::zeros(1, 3),
        DMatrix::zeros(1, 1),
    )
    .unwrap();
    let fin = generalized_eigenvalues(&dss).unwrap();
    assert_eq!(fin.len(), 2, "{fin:?}");
    assert!(rel(fin[0], Complex64::new(-1e10, 0.0)) < 1e-12, "{fin:?}");
    assert!(rel(fin[1], Complex64::new(-1.0, 0.0)) < 1e-12, "{fin:?}");
}

#[test]
fn descriptor_errors_name_the_problem() {
    let dss = series_springs(1.0, 1.0, 1.0);
    let wrong = DMatrix::<f64>::identity(3, 2);
    let opts = DescriptorOptions {
        phys: Some(&wrong),
        ..Default::default()
    };
    match descriptor_to_state_space(&dss, &opts) {
        Err(NumError::Dimension(DimensionError::PhysColumns {
            rows: 3,
            cols: 2,
            descriptor: true,
            ..
        })) => {}
        other => panic!("expected Dimension, got {other:?}"),
    }
    let nan = DMatrix::from_element(1, 3, f64::NAN);
    let opts = DescriptorOptions {
        phys: Some(&nan),
        ..Default::default()
    };
    assert!(matches!(
        descriptor_to_state_space(&dss, &opts),
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry { ref matrix, .. }))) if matrix.contains("phys")
    ));
    let opts = DescriptorOptions {
        warn_condition: 0.0,
        ..Default::default()
    };
    assert!(matches!(
        descriptor_to_state_space(&dss, &opts),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "DescriptorOptions::warn_condition",
            ..
        }))
    ));
    let opts = DescriptorOptions {
        rank_tol: RankTolerance::Relative(f64::INFINITY),
        ..Default::default()
    };
    assert!(matches!(
        descriptor_to_state_space(&dss, &opts),
        Err(NumError::InvalidOption(_))
    ));
    let g = GenEigOptions {
        infinite_tol: -1.0,
        ..Default::default()
    };
    assert!(matches!(
        generalized_eigenvalues_with(&dss, &g),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "GenEigOptions::infinite_tol",
            ..
        }))
    ));
    // Malformed descriptor: E of the wrong size, NaN in A.
    match Descriptor::new(
        DMatrix::identity(2, 2),
        DMatrix::identity(3, 3),
        DMatrix::zeros(3, 1),
        DMatrix::zeros(1, 3),
        DMatrix::zeros(1, 1),
    ) {
        Err(NumError::Dimension(DimensionError::Shape {
            matrix: "E",
            rows: 2,
            cols: 2,
            ..
        })) => {}
        other => panic!("expected Dimension, got {other:?}"),
    }
    let mut bad = dss.clone();
    bad.a[(1, 1)] = f64::INFINITY;
    match descriptor_to_state_space(&bad, &Default::default()) {
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry {
            ref matrix,
            row: 1,
            col: 1,
            ..
        }))) if matrix == "A" => {}
        other => panic!("expected NonFinite, got {other:?}"),
    }
}

/// An input-state row of E that is rounding noise (as after orthonormal projections) must be
/// treated as zero, not equilibrated up to an O(1) "equation": the reduced transfer function
/// must equal the descriptor's own `C (sE − A)⁻¹ B + D`.
#[test]
fn noise_level_row_of_e_is_not_amplified() {
    use nalgebra::DMatrix;
    use num_complex::Complex64;
    // x1' = x2, 2 x2' = −3 x1 − 0.4 x2 + x3, 0 = −x3 + u (x3 is the input state), y = x1.
    let mut e = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0]);
    // Rounding residue in the algebraic row, the column stays exactly zero.
    e[(2, 0)] = 8.7e-17;
    e[(2, 1)] = -3.1e-17;
    let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, -3.0, -0.4, 1.0, 0.0, 0.0, -1.0]);
    let b = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 1.0]);
    let c = DMatrix::from_row_slice(1, 3, &[1.0, 0.0, 0.0]);
    let d = eom_num::Descriptor {
        e,
        a,
        b,
        c,
        d: DMatrix::zeros(1, 1),
    };
    let (ss, rep) =
        eom_num::descriptor::descriptor_to_state_space(&d, &Default::default()).unwrap();
    assert_eq!((rep.dynamic, rep.algebraic), (2, 1));
    assert!(
        rep.warnings
            .iter()
            .any(|w| matches!(w, eom_num::NumWarning::RoundingNoise { .. })),
        "{:?}",
        rep.warnings
    );
    for s in [Complex64::new(0.3, 1.7), Complex64::new(-0.2, 0.4)] {
        // Exact: 1 / (2 s² + 0.4 s + 3).
        let exact = Complex64::new(1.0, 0.0) / (s * s * 2.0 + s * 0.4 + 3.0);
        let g = eom_num::freq::evaluate_at(&ss, s).unwrap()[(0, 0)];
        assert!((g - exact).norm() < 1e-13 * exact.norm(), "{g} vs {exact}");
    }
}
