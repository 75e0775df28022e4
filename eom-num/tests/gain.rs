//! Steady-state gains against closed forms, including integrating outputs (single and
//! double integrators) identified exactly.

mod closed_forms;

use closed_forms::{random_similarity, rng, smd};
use eom_num::gain::{Gain, GainOptions, steady_state_gain, steady_state_gain_with};
use eom_num::linalg::RankTolerance;
use eom_num::{DimensionError, NumError, OptionError, StateSpace};
use nalgebra::{DMatrix, dmatrix};

fn close(g: Gain, want: f64) -> bool {
    match g {
        Gain::Finite(v) => (v - want).abs() <= 1e-12 * want.abs().max(1.0),
        _ => false,
    }
}

fn integrating(g: Gain, order: usize, coefficient: f64) -> bool {
    match g {
        Gain::Integrating {
            order: o,
            coefficient: c,
        } => o == order && (c - coefficient).abs() <= 1e-12 * coefficient.abs().max(1.0),
        _ => false,
    }
}

#[test]
fn regular_a_gives_the_static_compliance() {
    let k = 250.0;
    let g = steady_state_gain(&smd(3.0, 0.4, k)).unwrap();
    assert!(close(g.get(0, 0), 1.0 / k), "{:?}", g.get(0, 0));
    assert_eq!(g.zero_dimension, 0);
    assert!(!g.has_integrating());
    assert!(g.condition > 1.0 && g.condition.is_finite());
    assert!(g.warnings.is_empty(), "{:?}", g.warnings);
}

/// A clearly regular A is decided by the certificate of its inverse: the reported bounds
/// must bracket the singular values (computed here by nalgebra's SVD), and the gains match
/// `D − C A⁻¹ B` (nalgebra's LU). A regular A within reach of the threshold goes to the SVD.
#[test]
fn clearly_regular_a_is_certified_and_a_nearly_singular_one_goes_to_the_svd() {
    let mut r = rng(9);
    let n = 40;
    let a = closed_forms::random_matrix(&mut r, n, n) - DMatrix::identity(n, n) * 3.0;
    let b = closed_forms::random_matrix(&mut r, n, 2);
    let c = closed_forms::random_matrix(&mut r, 3, n);
    let ss = StateSpace::new(a.clone(), b.clone(), c.clone(), DMatrix::zeros(3, 2)).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert!(g.certificate.is_some());
    assert!(g.a_rank.margin >= 1e4, "{}", g.a_rank.margin);
    let want = -(&c * a.clone().lu().solve(&b).unwrap());
    for i in 0..3 {
        for j in 0..2 {
            assert!(
                close(g.get(i, j), want[(i, j)]),
                "{:?} {}",
                g.get(i, j),
                want[(i, j)]
            );
        }
    }
    // The bounds are those of the balanced A; a diagonal A is left as it is by balancing,
    // so its singular values (nalgebra's SVD) must lie within them.
    let d = DMatrix::from_diagonal(&nalgebra::DVector::from_fn(n, |i, _| 1.0 + i as f64));
    let ss = StateSpace::new(d.clone(), b.clone(), c.clone(), DMatrix::zeros(3, 2)).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    let cert = g.certificate.expect("clearly regular");
    let sv = d.singular_values();
    let (smax, smin) = (sv.max(), sv.min());
    assert!(cert.sigma_min_lower <= smin * (1.0 + 1e-12) && cert.sigma_max_upper >= smax);
    assert!(g.condition >= smax / smin);
    // σ_min = 1e-10 σ_max: regular by the SVD (threshold 10·n·ε·σ_max ≈ 1e-13 σ_max) but not
    // by a margin of 1e4 over the bounds — the SVD decides, with its singular values.
    let mut e = d.clone();
    e[(0, 0)] = 1e-10 * n as f64;
    let ss = StateSpace::new(e, b, c, DMatrix::zeros(3, 2)).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert!(g.certificate.is_none());
    assert_eq!(g.a_rank.rank, n);
    assert_eq!(g.a_rank.singular_values.len(), n);
}

/// Many equal singular values: ‖A‖_F = √n σ_max overestimates σ_max twenty-fold at n = 400,
/// which put σ_min = 5e-8 σ_max within the certificate's margin; the bound √(‖A‖₁‖A‖_∞)
/// does not (the threshold is 10·n·ε·σ_max ≈ 9e-13 σ_max), so the certificate decides, and
/// its bounds bracket the singular values.
#[test]
fn the_certificate_bounds_sigma_max_by_row_and_column_sums() {
    let n = 400;
    let mut a = DMatrix::<f64>::identity(n, n);
    a[(n - 1, n - 1)] = 5e-8;
    let mut b = DMatrix::<f64>::zeros(n, 1);
    b[(n - 1, 0)] = 1.0;
    let c = b.transpose();
    let ss = StateSpace::new(a.clone(), b, c, DMatrix::zeros(1, 1)).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    let cert = g.certificate.expect("certified");
    assert!(cert.sigma_max_upper >= 1.0 && cert.sigma_max_upper <= 1.0 + 1e-12);
    assert!(cert.sigma_min_lower <= 5e-8 * (1.0 + 1e-12));
    assert!(cert.sigma_min_lower >= 5e-8 * (1.0 - 1e-12));
    assert_eq!(g.a_rank.rank, n);
    assert!(close(g.get(0, 0), -1.0 / 5e-8), "{:?}", g.get(0, 0));
}

/// Modal form Λ = diag(0, −a), hidden by a random similarity T: A = T Λ T⁻¹, B = T Bm,
/// C = Cm T⁻¹. Gains follow from the modal form by hand.
#[test]
fn integrator_pairs_are_reported_as_integrating() {
    let a_ = 4.0;
    let bm = dmatrix![2.0, 0.0; 1.0, 3.0]; // input 1 does not reach the integrator
    let cm = dmatrix![1.0, 0.0; 0.0, 1.0; 1.0, 1.0];
    let d = dmatrix![0.0, 0.5; 0.0, 0.0; 0.0, 0.0];
    let mut r = rng(5);
    let t = random_similarity(&mut r, 2);
    let ti = t.clone().try_inverse().unwrap();
    let lam = dmatrix![0.0, 0.0; 0.0, -a_];
    let ss = StateSpace::new(&t * lam * &ti, &t * &bm, &cm * &ti, d).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert_eq!(g.zero_dimension, 1);
    assert_eq!(g.index, 1);
    assert_eq!(g.a_rank.rank, 1);
    // Output 0 = integrator state: input 0 integrates with slope 2 (= cm·bm), input 1 does
    // not reach it: finite D = 0.5.
    assert!(integrating(g.get(0, 0), 1, 2.0), "{:?}", g.get(0, 0));
    assert!(close(g.get(0, 1), 0.5), "{:?}", g.get(0, 1));
    // Output 1 = stable mode: 1/a · b.
    assert!(close(g.get(1, 0), 1.0 / a_), "{:?}", g.get(1, 0));
    assert!(close(g.get(1, 1), 3.0 / a_), "{:?}", g.get(1, 1));
    // Output 2 sees both: integrating from input 0, finite from input 1.
    assert!(integrating(g.get(2, 0), 1, 2.0), "{:?}", g.get(2, 0));
    assert!(close(g.get(2, 1), 3.0 / a_), "{:?}", g.get(2, 1));
    assert!(g.has_integrating());
    assert_eq!(g.get(0, 0).finite(), None);
}

#[test]
fn rigid_body_double_integrator_has_order_two() {
    // Free mass m (x'' = F/m) next to a spring–mass–damper driven by a second input.
    let (m, k, c, m2) = (2.0, 50.0, 1.0, 5.0);
    let a = dmatrix![
        0.0, 1.0, 0.0, 0.0;
        0.0, 0.0, 0.0, 0.0;
        0.0, 0.0, 0.0, 1.0;
        0.0, 0.0, -k / m2, -c / m2
    ];
    let b = dmatrix![0.0, 0.0; 1.0 / m, 0.0; 0.0, 0.0; 0.0, 1.0 / m2];
    let cc = dmatrix![
        1.0, 0.0, 0.0, 0.0; // position of the free mass
        0.0, 1.0, 0.0, 0.0; // its velocity
        0.0, 0.0, 1.0, 0.0; // spring deflection
        1.0, 0.0, 1.0, 0.0  // sum
    ];
    let mut r = rng(9);
    let t = random_similarity(&mut r, 4);
    let ti = t.clone().try_inverse().unwrap();
    let ss = StateSpace::new(&t * a * &ti, &t * b, cc * &ti, DMatrix::zeros(4, 2)).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert_eq!(g.zero_dimension, 2);
    assert_eq!(g.index, 2);
    // x = F t²/(2m): pole of order 2, lim s² G = 1/m; velocity order 1, slope 1/m.
    assert!(integrating(g.get(0, 0), 2, 1.0 / m), "{:?}", g.get(0, 0));
    assert!(integrating(g.get(1, 0), 1, 1.0 / m), "{:?}", g.get(1, 0));
    assert!(close(g.get(2, 0), 0.0), "{:?}", g.get(2, 0));
    assert!(integrating(g.get(3, 0), 2, 1.0 / m), "{:?}", g.get(3, 0));
    // The second input only reaches the spring: finite 1/k everywhere it is seen.
    assert!(close(g.get(0, 1), 0.0), "{:?}", g.get(0, 1));
    assert!(close(g.get(1, 1), 0.0), "{:?}", g.get(1, 1));
    assert!(close(g.get(2, 1), 1.0 / k), "{:?}", g.get(2, 1));
    assert!(close(g.get(3, 1), 1.0 / k), "{:?}", g.get(3, 1));
    assert!(g.separation_condition < 10.0);
}

#[test]
fn cancelling_integrators_give_a_finite_gain() {
    // Two integrators driven equally, output their difference: G = 1/s − 1/s + 1/(s+1) → 1.
    let a = dmatrix![0.0, 0.0, 0.0; 0.0, 0.0, 0.0; 0.0, 0.0, -1.0];
    let b = dmatrix![1.0; 1.0; 1.0];
    let c = dmatrix![1.0, -1.0, 1.0];
    let mut r = rng(13);
    let t = random_similarity(&mut r, 3);
    let ti = t.clone().try_inverse().unwrap();
    let ss = StateSpace::new(&t * a * &ti, &t * b, c * &ti, dmatrix![0.0]).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert_eq!(g.zero_dimension, 2);
    assert_eq!(g.index, 1);
    assert!(close(g.get(0, 0), 1.0), "{:?}", g.get(0, 0));
}

#[test]
fn pure_integrator_system_and_static_gain() {
    let ss = StateSpace::new(dmatrix![0.0], dmatrix![3.0], dmatrix![2.0], dmatrix![1.0]).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert!(integrating(g.get(0, 0), 1, 6.0), "{:?}", g.get(0, 0));
    let ss = StateSpace::new(
        DMatrix::zeros(0, 0),
        DMatrix::zeros(0, 1),
        DMatrix::zeros(1, 0),
        dmatrix![7.0],
    )
    .unwrap();
    assert!(close(steady_state_gain(&ss).unwrap().get(0, 0), 7.0));
}

#[test]
fn gain_errors_name_the_problem() {
    let ss = smd(1.0, 1.0, 1.0);
    let bad = GainOptions {
        warn_condition: -1.0,
        ..Default::default()
    };
    assert!(matches!(
        steady_state_gain_with(&ss, &bad),
        Err(NumError::InvalidOption(OptionError::Value {
            option: "GainOptions::warn_condition",
            ..
        }))
    ));
    let bad = GainOptions {
        rank_tol: RankTolerance::Absolute(-1.0),
        ..Default::default()
    };
    assert!(matches!(
        steady_state_gain_with(&ss, &bad),
        Err(NumError::InvalidOption(OptionError::RankTolerance { .. }))
    ));
    let mut broken = ss;
    broken.d = DMatrix::zeros(2, 2);
    assert!(matches!(
        steady_state_gain(&broken),
        Err(NumError::Dimension(DimensionError::Shape {
            matrix: "D",
            rows: 2,
            cols: 2,
            ..
        }))
    ));
}

/// Two headings on which the equations depend only through their difference: their columns
/// are negatives of each other, here to 1–3 ulps (as two separately rounded reductions give
/// them), not exactly; and a lateral position that integrates the first heading, on which
/// nothing depends but rounding residues of the elimination (the bicycle's `rear frame.y`,
/// `rear frame.rz`, `front frame.rz`, whose A at 2 m/s has 9e-16 and −7e-15 in the
/// position's column). Left so, A is regular and `C A⁻¹ B` amplifies those residues into the
/// gains (the bicycle's were 0 instead of 5e-4); in the coordinates where the structural
/// zeros are exact the gain is the closed form. States
/// x1, x2 (headings), x3 (a rate), x4 (position); z = x1 − x2: ż = x3/2 + 2z,
/// ẋ3 = −3z − x3 + u, y = z; at rest x3 = −4z and z = −u: gain −1.
#[test]
fn a_heading_pair_rounded_apart_gives_the_closed_form_gain() {
    let ulp = |x: f64, k: i64| f64::from_bits((x.to_bits() as i64 + k) as u64);
    let a = dmatrix![
        0.0, 0.0, 1.0, 0.0;
        -2.0, ulp(2.0, 1), 0.5, 9e-16;
        -3.0, ulp(3.0, 3), -1.0, -7e-15;
        2.0, 0.0, 0.0, 0.0
    ];
    let b = dmatrix![0.0; 0.0; 1.0; 0.0];
    let c = dmatrix![1.0, -1.0, 0.0, 0.0];
    let d = DMatrix::zeros(1, 1);
    let ss = StateSpace::new(a, b, c, d).unwrap();
    let g = steady_state_gain(&ss).unwrap();
    assert!(
        close(g.get(0, 0), -1.0),
        "{:?} {:?}",
        g.get(0, 0),
        g.warnings
    );
    assert_eq!(g.zero_dimension, 2, "{g:?}");
}

/// Integer systems whose exact gain is 0 but whose computed gain is rounding: A (3×3,
/// integer, |det| > 1 so that A⁻¹b is not exact in binary), b integer and c = (adj(A) b) × w
/// (a cross product with an integer w), so that c·A⁻¹b = c·adj(A)b / det = 0 exactly. The
/// error estimate holds every computed gain (the exact value is 0), is not vacuous (at most
/// 1e-9 |c||A⁻¹b|), and the computed gains are not all exactly 0 (rounding happened).
#[test]
fn gains_that_are_exactly_zero_are_within_their_error_estimate() {
    use rand::Rng;
    let mut r = rng(26);
    let (mut nonzero, mut cases) = (0, 0);
    while cases < 200 {
        let m: [[i64; 3]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.random_range(-9..=9)));
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if det.abs() < 2 {
            continue;
        }
        cases += 1;
        // adj(A)ᵢⱼ = cofactor of (j, i).
        let cof = |i: usize, j: usize| {
            let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
            let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let b: [i64; 3] = std::array::from_fn(|_| r.random_range(-9..=9));
        let adj_b: [i64; 3] = std::array::from_fn(|i| (0..3).map(|k| cof(k, i) * b[k]).sum());
        let w: [i64; 3] = std::array::from_fn(|_| r.random_range(-9..=9));
        let c = [
            adj_b[1] * w[2] - adj_b[2] * w[1],
            adj_b[2] * w[0] - adj_b[0] * w[2],
            adj_b[0] * w[1] - adj_b[1] * w[0],
        ];
        assert_eq!((0..3).map(|i| c[i] * adj_b[i]).sum::<i64>(), 0);
        let f = |v: i64| v as f64;
        let ss = StateSpace::new(
            DMatrix::from_fn(3, 3, |i, j| f(m[i][j])),
            DMatrix::from_fn(3, 1, |i, _| f(b[i])),
            DMatrix::from_fn(1, 3, |_, j| f(c[j])),
            DMatrix::zeros(1, 1),
        )
        .expect("a valid model");
        let g = steady_state_gain(&ss).expect("a regular A");
        let (Gain::Finite(v), err) = (g.get(0, 0), g.errors[(0, 0)]) else {
            panic!("finite gain expected");
        };
        let scale: f64 = (0..3)
            .map(|i| f(c[i]).abs() * f(adj_b[i]).abs())
            .sum::<f64>()
            / f(det).abs();
        assert!(v.abs() <= err, "case {cases}: gain {v:e}, estimate {err:e}");
        assert!(
            err <= 1e-9 * scale.max(1.0),
            "case {cases}: estimate {err:e}, scale {scale}"
        );
        nonzero += usize::from(v != 0.0);
    }
    assert!(nonzero >= 10, "{nonzero} of 200 gains were not exactly 0");
}

/// A gain well away from 0 is far outside its estimate (it is not printed as 0).
#[test]
fn a_nonzero_gain_is_far_outside_its_error_estimate() {
    let g = steady_state_gain(&smd(2.0, 3.0, 5.0)).expect("gain");
    let (Gain::Finite(v), err) = (g.get(0, 0), g.errors[(0, 0)]) else {
        panic!("finite gain expected");
    };
    assert!(err > 0.0 && err < 1e-12 * v.abs(), "{v} ± {err}");
}
