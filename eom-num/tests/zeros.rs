//! Transmission zeros against closed forms: transfer functions with known numerators,
//! `eig(A − B D⁻¹ C)` for invertible D, block-diagonal MIMO systems mixed by constant
//! input/output transformations, and non-square systems.

mod analysis_support;

use analysis_support::{eig_nalgebra, mat, rand_mat, rand_orth, rng, set_distance};
use eom_num::zeros::{ZerosOptions, transmission_zeros, transmission_zeros_with};
use eom_num::{NumError, StateSpace};
use nalgebra::DMatrix;
use num_complex::Complex64;

fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

fn ss(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>, d: DMatrix<f64>) -> StateSpace<f64> {
    StateSpace::new(a, b, c, d).unwrap()
}

/// Controllable canonical form of `num(s) / den(s)` (den monic of degree n, num of degree
/// < n; coefficients lowest power first), hidden by an orthogonal similarity.
fn siso(num: &[f64], den: &[f64], d: f64, seed: u64) -> StateSpace<f64> {
    let n = den.len() - 1;
    let mut a = DMatrix::zeros(n, n);
    for i in 0..n - 1 {
        a[(i, i + 1)] = 1.0;
    }
    for j in 0..n {
        a[(n - 1, j)] = -den[j];
    }
    let mut b = DMatrix::zeros(n, 1);
    b[(n - 1, 0)] = 1.0;
    let mut cm = DMatrix::zeros(1, n);
    for (j, &v) in num.iter().enumerate() {
        cm[(0, j)] = v;
    }
    let q = rand_orth(&mut rng(seed), n);
    ss(
        q.transpose() * a * &q,
        q.transpose() * b,
        cm * &q,
        DMatrix::from_element(1, 1, d),
    )
}

/// Polynomial coefficients (lowest power first) of ∏ (s − rᵢ).
fn poly(roots: &[f64]) -> Vec<f64> {
    let mut p = vec![1.0];
    for &r in roots {
        let mut q = vec![0.0; p.len() + 1];
        for (i, &v) in p.iter().enumerate() {
            q[i + 1] += v;
            q[i] -= r * v;
        }
        p = q;
    }
    p
}

#[test]
fn siso_zeros_are_the_roots_of_the_numerator() {
    // (s + 2)(s − 3) / ((s + 1)(s + 4)(s + 5))
    let sys = siso(&poly(&[-2.0, 3.0]), &poly(&[-1.0, -4.0, -5.0]), 0.0, 1);
    let z = transmission_zeros(&sys).unwrap();
    assert!(
        set_distance(&z, &[c(-2.0, 0.0), c(3.0, 0.0)]).unwrap() < 1e-12,
        "{z:?}"
    );
    // Relative degree 3: one finite zero, and no huge spurious ones.
    let sys = siso(&poly(&[0.5]), &poly(&[-1.0, -2.0, -3.0, -4.0]), 0.0, 2);
    let rep = transmission_zeros_with(&sys, &ZerosOptions::default()).unwrap();
    assert_eq!(rep.zeros.len(), 1, "{rep:?}");
    assert!((rep.zeros[0] - c(0.5, 0.0)).norm() < 1e-12);
    assert_eq!(rep.infinite, 0);
    // Complex zeros, with feedthrough: d + num/den = (d·den + num)/den.
    let den = poly(&[-1.0, -2.0, -6.0]);
    let num = [3.0, -1.0, 0.5];
    let sys = siso(&num, &den, 2.0, 3);
    let z = transmission_zeros(&sys).unwrap();
    // 2 s³ + (2·9 + 0.5) s² + (2·20 − 1) s + (2·12 + 3)
    let want = cubic_roots([27.0, 39.0, 18.5, 2.0]);
    assert!(
        set_distance(&z, &want).unwrap() < 1e-12,
        "{z:?} vs {want:?}"
    );
    // Zeros come sorted by (re, im).
    assert!(
        z.windows(2)
            .all(|w| (w[0].re, w[0].im) <= (w[1].re, w[1].im))
    );
}

/// Roots of c0 + c1 s + c2 s² + c3 s³ by the companion matrix (nalgebra).
fn cubic_roots(cf: [f64; 4]) -> Vec<Complex64> {
    let a = mat(&[
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[-cf[0] / cf[3], -cf[1] / cf[3], -cf[2] / cf[3]],
    ]);
    eig_nalgebra(&a)
}

#[test]
fn invertible_feedthrough_gives_eig_of_a_minus_b_dinv_c() {
    for seed in 0..8u64 {
        let mut r = rng(100 + seed);
        let n = 2 + (seed as usize % 6);
        let m = 1 + (seed as usize % 3);
        let a = rand_mat(&mut r, n, n);
        let b = rand_mat(&mut r, n, m);
        let cm = rand_mat(&mut r, m, n);
        let d = DMatrix::<f64>::identity(m, m) * 2.0 + rand_mat(&mut r, m, m) * 0.5;
        let want = eig_nalgebra(&(&a - &b * d.clone().try_inverse().unwrap() * &cm));
        let z = transmission_zeros(&ss(a, b, cm, d)).unwrap();
        let dist = set_distance(&z, &want).unwrap();
        assert!(dist < 1e-10, "seed {seed}: {dist:e}");
    }
}

#[test]
fn mimo_zeros_survive_input_output_mixing() {
    // diag(G1, G2), G1 = (s + 2)/((s + 1)(s + 3)), G2 = (s − 0.5)(s + 4)/((s + 2.5)(s + 1.5)(s + 6)),
    // then y = T_out G T_in u with constant invertible T's: zeros {−2, 0.5, −4}.
    let g1 = siso(&poly(&[-2.0]), &poly(&[-1.0, -3.0]), 0.0, 4);
    let g2 = siso(&poly(&[0.5, -4.0]), &poly(&[-2.5, -1.5, -6.0]), 0.0, 5);
    let mut a = DMatrix::zeros(5, 5);
    a.view_mut((0, 0), (2, 2)).copy_from(&g1.a);
    a.view_mut((2, 2), (3, 3)).copy_from(&g2.a);
    let mut b = DMatrix::zeros(5, 2);
    b.view_mut((0, 0), (2, 1)).copy_from(&g1.b);
    b.view_mut((2, 1), (3, 1)).copy_from(&g2.b);
    let mut cm = DMatrix::zeros(2, 5);
    cm.view_mut((0, 0), (1, 2)).copy_from(&g1.c);
    cm.view_mut((1, 2), (1, 3)).copy_from(&g2.c);
    let t_in = mat(&[&[1.0, 0.4], &[-0.3, 2.0]]);
    let t_out = mat(&[&[0.7, 1.0], &[1.0, -0.2]]);
    let q = rand_orth(&mut rng(6), 5);
    let sys = ss(
        q.transpose() * a * &q,
        q.transpose() * b * t_in,
        t_out * cm * &q,
        DMatrix::zeros(2, 2),
    );
    let z = transmission_zeros(&sys).unwrap();
    let want = [c(-4.0, 0.0), c(-2.0, 0.0), c(0.5, 0.0)];
    assert!(set_distance(&z, &want).unwrap() < 1e-10, "{z:?}");
}

#[test]
fn non_square_systems() {
    // Tall (2 outputs, 1 input), generic: no zeros.
    let mut r = rng(7);
    let sys = ss(
        rand_mat(&mut r, 5, 5),
        rand_mat(&mut r, 5, 1),
        rand_mat(&mut r, 2, 5),
        DMatrix::zeros(2, 1),
    );
    assert!(transmission_zeros(&sys).unwrap().is_empty());
    // Wide (1 output, 2 inputs): G = (s + 2)/(s + 1) · [1/(s + 3), 1/(s + 5)] has the
    // common zero −2. Realized as the series connection [1/(s+3), 1/(s+5)] → (s+2)/(s+1).
    let a = mat(&[&[-3.0, 0.0, 0.0], &[0.0, -5.0, 0.0], &[1.0, 1.0, -1.0]]);
    let b = mat(&[&[1.0, 0.0], &[0.0, 1.0], &[0.0, 0.0]]);
    let cm = mat(&[&[1.0, 1.0, 1.0]]);
    let q = rand_orth(&mut rng(8), 3);
    let sys = ss(
        q.transpose() * a * &q,
        q.transpose() * b,
        cm * &q,
        DMatrix::zeros(1, 2),
    );
    let z = transmission_zeros(&sys).unwrap();
    assert!(set_distance(&z, &[c(-2.0, 0.0)]).unwrap() < 1e-12, "{z:?}");
    // Tall with an unobservable (output-decoupling) mode at −7: [A − λI; C] loses column rank
    // there, so the system pencil drops below its normal rank (= number of columns).
    let mut a = DMatrix::zeros(4, 4);
    a.view_mut((0, 0), (3, 3))
        .copy_from(&rand_mat(&mut r, 3, 3));
    a[(3, 3)] = -7.0;
    a[(3, 0)] = 0.8;
    let mut b = DMatrix::zeros(4, 1);
    b.copy_from(&rand_mat(&mut r, 4, 1));
    let mut cm = DMatrix::zeros(2, 4);
    cm.view_mut((0, 0), (2, 3))
        .copy_from(&rand_mat(&mut r, 2, 3));
    let q = rand_orth(&mut rng(9), 4);
    let tall = ss(
        q.transpose() * &a * &q,
        q.transpose() * &b,
        &cm * &q,
        DMatrix::zeros(2, 1),
    );
    let z = transmission_zeros(&tall).unwrap();
    assert!(set_distance(&z, &[c(-7.0, 0.0)]).unwrap() < 1e-12, "{z:?}");
    // Its dual (wide, with an uncontrollable mode at −7) has the same zero.
    let wide = ss(
        tall.a.transpose(),
        tall.c.transpose(),
        tall.b.transpose(),
        DMatrix::zeros(1, 2),
    );
    let z = transmission_zeros(&wide).unwrap();
    assert!(set_distance(&z, &[c(-7.0, 0.0)]).unwrap() < 1e-12, "{z:?}");
}

#[test]
fn zeros_scale_with_the_time_unit() {
    let base = siso(&poly(&[-2.0, 3.0]), &poly(&[-1.0, -4.0, -5.0]), 0.0, 10);
    for k in [1e-6, 1e6] {
        let sys = ss(&base.a * k, &base.b * k, base.c.clone(), base.d.clone());
        let z = transmission_zeros(&sys).unwrap();
        let want = [c(-2.0 * k, 0.0), c(3.0 * k, 0.0)];
        let dist = set_distance(&z, &want).unwrap();
        // set_distance is relative for |z| > 1 and absolute below: compare relatively.
        assert_eq!(z.len(), 2);
        for (x, y) in z.iter().zip(want.iter()) {
            assert!(
                (x - y).norm() <= 1e-12 * y.norm(),
                "k = {k}: {z:?} ({dist:e})"
            );
        }
    }
}

#[test]
fn report_lists_the_rank_decisions() {
    let sys = siso(&poly(&[-2.0, 3.0]), &poly(&[-1.0, -4.0, -5.0]), 0.0, 1);
    let rep = transmission_zeros_with(&sys, &ZerosOptions::default()).unwrap();
    assert_eq!(rep.reduced_order, 2);
    assert!(!rep.decisions.is_empty());
    assert!(rep.decisions.iter().all(|d| !d.is_fragile(1e3)));
    let json = serde_json::to_value(&rep).unwrap();
    assert!(json["zeros"][0]["re"].is_number());
}

#[test]
fn bad_input_gets_typed_errors() {
    let mut sys = ss(
        DMatrix::identity(2, 2),
        DMatrix::zeros(2, 1),
        DMatrix::zeros(1, 2),
        DMatrix::zeros(1, 1),
    );
    let opts = ZerosOptions {
        infinite_rtol: Some(f64::INFINITY),
        ..Default::default()
    };
    assert!(matches!(
        transmission_zeros_with(&sys, &opts),
        Err(NumError::InvalidOption(_))
    ));
    sys.d[(0, 0)] = f64::INFINITY;
    assert!(matches!(
        transmission_zeros(&sys),
        Err(NumError::NonFinite(_))
    ));
    sys.d = DMatrix::zeros(2, 1);
    assert!(matches!(
        transmission_zeros(&sys),
        Err(NumError::Dimension(_))
    ));
}

/// The zeros of a system of 240 states, on pools of one and of three threads (from
/// `eom_num::linalg::PARALLEL_MIN` states the pencil's eigenvalues use faer's parallel
/// kernels): with `D = I` they are the eigenvalues of `A − B C`, here chosen as those of 120
/// distinct damped oscillators hidden by a random orthogonal change of coordinates, so the
/// reference is the closed form `−ζω ± iω√(1 − ζ²)`.
#[test]
fn a_large_system_has_the_same_zeros_on_any_number_of_threads() {
    let k = 120;
    let (w, zeta) = (|i: usize| 1.0 + 0.25 * i as f64, 0.05);
    let mut m = DMatrix::zeros(2 * k, 2 * k);
    let mut want = Vec::new();
    for i in 0..k {
        m[(2 * i, 2 * i + 1)] = 1.0;
        m[(2 * i + 1, 2 * i)] = -w(i) * w(i);
        m[(2 * i + 1, 2 * i + 1)] = -2.0 * zeta * w(i);
        let wd = w(i) * (1.0 - zeta * zeta).sqrt();
        want.extend([c(-zeta * w(i), wd), c(-zeta * w(i), -wd)]);
    }
    let mut r = rng(240);
    let q = rand_orth(&mut r, 2 * k);
    let (b, cm) = (rand_mat(&mut r, 2 * k, 3), rand_mat(&mut r, 3, 2 * k));
    let a = q.transpose() * m * &q + &b * &cm;
    let sys = ss(a, b, cm, DMatrix::identity(3, 3));
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let z = pool.install(|| transmission_zeros(&sys)).unwrap();
        let dist = set_distance(&z, &want).unwrap();
        assert!(dist < 1e-10, "{threads} thread(s): {dist:e}");
    }
}
