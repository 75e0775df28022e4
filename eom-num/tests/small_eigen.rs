//! The small-matrix eigenvalue kernel (`eom_num::small_eigen`) against known eigenvalues:
//! matrices built from their eigenvalues by a random similarity, companion matrices of
//! polynomials with known roots, defective and clustered spectra, structural zeros, and
//! random matrices against faer's general solver. (The bicycle's published eigenvalues:
//! `tests/tests/bicycle.rs`.)

use eom_num::modes::Modes;
use eom_num::small_eigen::{KnownZeros, MAX_N, eigenvalues_small, eigenvalues_small_known};
use eom_num::{MatrixEntry, NonFiniteError, NumError, StateSpace};
use faer::Mat;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn small(a: &DMatrix<f64>) -> Vec<Complex64> {
    let n = a.nrows();
    let mut out = vec![Complex64::new(f64::NAN, f64::NAN); n];
    eigenvalues_small(a.as_slice(), n, &mut out).expect("eigenvalues");
    out
}

/// faer's general solver (no balancing, no deflation).
fn faer_eigenvalues(a: &DMatrix<f64>) -> Vec<Complex64> {
    let m = Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)]);
    m.eigenvalues()
        .expect("faer")
        .into_iter()
        .map(|z| Complex64::new(z.re, z.im))
        .collect()
}

/// faer's general solver on the matrix balanced as the kernel balances it.
fn faer_balanced(a: &DMatrix<f64>) -> Vec<Complex64> {
    let n = a.nrows();
    let mut b = a.clone();
    let mut scale = vec![1.0; n];
    eom_num::linalg::balance_in_place(b.as_mut_slice(), n, &mut scale);
    let m = Mat::from_fn(n, n, |i, j| b[(i, j)]);
    m.eigenvalues()
        .expect("faer")
        .into_iter()
        .map(|z| Complex64::new(z.re, z.im))
        .collect()
}

/// The largest distance from an eigenvalue of `want` to its partner in `got`, partners
/// matched greedily from the closest pair (both lists of equal length).
fn matched_error(got: &[Complex64], want: &[Complex64]) -> f64 {
    assert_eq!(got.len(), want.len());
    let mut used = vec![false; got.len()];
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, w) in want.iter().enumerate() {
        for (j, g) in got.iter().enumerate() {
            pairs.push(((w - g).norm(), i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut done = vec![false; want.len()];
    let mut worst = 0.0f64;
    for (d, i, j) in pairs {
        if !done[i] && !used[j] {
            done[i] = true;
            used[j] = true;
            worst = worst.max(d);
        }
    }
    worst
}

/// A real matrix with the given spectrum (conjugate pairs given once as `re ± i·im`):
/// a block diagonal of 1×1 and 2×2 blocks under a random similarity `X D X⁻¹` whose
/// condition number stays moderate.
fn with_spectrum(rng: &mut StdRng, real: &[f64], pairs: &[(f64, f64)]) -> DMatrix<f64> {
    let n = real.len() + 2 * pairs.len();
    let mut d = DMatrix::zeros(n, n);
    for (k, &r) in real.iter().enumerate() {
        d[(k, k)] = r;
    }
    for (k, &(re, im)) in pairs.iter().enumerate() {
        let i = real.len() + 2 * k;
        d[(i, i)] = re;
        d[(i + 1, i + 1)] = re;
        d[(i, i + 1)] = im;
        d[(i + 1, i)] = -im;
    }
    let x = DMatrix::from_fn(n, n, |i, j| {
        f64::from(u8::from(i == j)) + 0.3 * rng.random_range(-1.0..1.0)
    });
    let xi = x.clone().try_inverse().expect("invertible");
    &x * d * xi
}

fn spectrum(real: &[f64], pairs: &[(f64, f64)]) -> Vec<Complex64> {
    real.iter()
        .map(|&r| Complex64::new(r, 0.0))
        .chain(
            pairs
                .iter()
                .flat_map(|&(re, im)| [Complex64::new(re, im), Complex64::new(re, -im)]),
        )
        .collect()
}

#[test]
fn random_matrices_agree_with_faer() {
    let mut rng = StdRng::seed_from_u64(31);
    let mut worst = 0.0f64;
    for n in 1..=MAX_N {
        for _ in 0..40 {
            let a = DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0));
            let got = small(&a);
            let want = faer_eigenvalues(&a);
            let err = matched_error(&got, &want) / a.norm();
            worst = worst.max(err);
            assert!(err < 1e-11, "n = {n}: {err:e}\n{a}\n{got:?}\n{want:?}");
        }
    }
    eprintln!("random matrices: largest difference from faer {worst:.1e} of ‖A‖");
}

#[test]
fn output_is_sorted_with_exact_conjugates() {
    let mut rng = StdRng::seed_from_u64(7);
    for n in 2..=MAX_N {
        let a = DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0));
        let e = small(&a);
        for w in e.windows(2) {
            assert!(
                (w[0].re, w[0].im) <= (w[1].re, w[1].im),
                "not sorted: {e:?}"
            );
        }
        for z in e.iter().filter(|z| z.im != 0.0) {
            assert!(
                e.iter()
                    .any(|w| w.re.to_bits() == z.re.to_bits() && w.im == -z.im),
                "{z} without its exact conjugate in {e:?}"
            );
        }
        assert!(e.iter().all(|z| !(z.im == 0.0 && z.im.is_sign_negative())));
    }
}

#[test]
fn known_spectra_under_similarity() {
    let mut rng = StdRng::seed_from_u64(11);
    // Real eigenvalues, and conjugate pairs as (re, im).
    type Spectrum = (Vec<f64>, Vec<(f64, f64)>);
    let cases: Vec<Spectrum> = vec![
        (vec![-1.0, -2.0, -3.0, -4.0], vec![]),
        (vec![-0.5], vec![(-0.1, 5.0), (0.2, 1.0)]),
        (vec![], vec![(-1.0, 1e-3), (-3.0, 40.0)]),
        // Widely spread magnitudes (a stiff model).
        (vec![-1e-4, -1e4], vec![(-2.0, 30.0), (-50.0, 900.0)]),
        (
            (1..=8).map(|k| -(k as f64)).collect(),
            vec![(-0.3, 2.0), (-1.5, 7.0), (-0.01, 0.5), (-4.0, 12.0)],
        ),
    ];
    for (real, pairs) in &cases {
        for _ in 0..20 {
            let a = with_spectrum(&mut rng, real, pairs);
            let want = spectrum(real, pairs);
            let got = small(&a);
            let faer = faer_eigenvalues(&a);
            let err = matched_error(&got, &want);
            let err_faer = matched_error(&faer, &want);
            let floor = 1e3 * a.nrows() as f64 * f64::EPSILON * a.norm();
            assert!(
                err <= (4.0 * err_faer).max(floor),
                "{real:?} {pairs:?}: error {err:e}, faer's {err_faer:e}"
            );
        }
    }
}

/// The companion matrix of the monic polynomial with the given real roots.
fn companion(roots: &[f64]) -> DMatrix<f64> {
    // Coefficients of Π(s − r), lowest first.
    let mut c = vec![1.0];
    for &r in roots {
        let mut next = vec![0.0; c.len() + 1];
        for (k, &ck) in c.iter().enumerate() {
            next[k + 1] += ck;
            next[k] -= r * ck;
        }
        c = next;
    }
    let n = roots.len();
    let mut a = DMatrix::zeros(n, n);
    for i in 1..n {
        a[(i, i - 1)] = 1.0;
    }
    for i in 0..n {
        a[(i, n - 1)] = -c[i];
    }
    a
}

#[test]
fn companion_matrices() {
    let cases: [&[f64]; 6] = [
        &[-1.0, -2.0, -3.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        &[-0.5, -0.25, -0.125, -0.0625],
        &[-1.0, -10.0, -100.0, -1000.0],
        &[-1.0, -2.0, -3.0, -4.0, -5.0, -6.0, -7.0, -8.0, -9.0, -10.0],
        &[
            3.0, -2.5, 0.1, 7.0, -7.5, 1.0, -1.0, 4.0, 0.5, -0.2, 2.0, -3.0,
        ],
    ];
    for roots in cases {
        let a = companion(roots);
        let n = roots.len();
        let got = small(&a);
        // Companion matrices of spread roots are ill-conditioned: each root must be within
        // the first-order bound of a backward-stable solver, 10·n·ε·‖Ã‖_F·κᵢ (Ã balanced,
        // κᵢ the root's condition number), which `Modes` computes as its tolerance.
        let ss = StateSpace::new(
            a.clone(),
            DMatrix::zeros(n, 1),
            DMatrix::zeros(1, n),
            DMatrix::zeros(1, 1),
        )
        .unwrap();
        let modes = Modes::compute(&ss).unwrap();
        for &r in roots {
            let mode = modes
                .modes
                .iter()
                .min_by(|x, y| {
                    (x.eigenvalue - r)
                        .norm()
                        .total_cmp(&(y.eigenvalue - r).norm())
                })
                .unwrap();
            let err = got
                .iter()
                .map(|z| (z - r).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                err <= mode.tolerance,
                "roots {roots:?}: root {r} found to {err:e}, bound {:e}; got {got:?}",
                mode.tolerance
            );
        }
    }
}

/// Statistically as accurate as faer's solver (balanced the same way) on companion
/// matrices of random roots: the mean of log10 of the error within 0.3 of faer's.
#[test]
fn as_accurate_as_faer_on_average() {
    let mut rng = StdRng::seed_from_u64(99);
    let (mut ours, mut theirs) = (0.0, 0.0);
    let count = 300;
    for _ in 0..count {
        let n = rng.random_range(4..12);
        let roots: Vec<f64> = (0..n).map(|_| rng.random_range(-5.0..5.0)).collect();
        let a = companion(&roots);
        let want: Vec<Complex64> = roots.iter().map(|&r| Complex64::new(r, 0.0)).collect();
        let floor = 1e-17;
        ours += matched_error(&small(&a), &want).max(floor).log10();
        theirs += matched_error(&faer_balanced(&a), &want).max(floor).log10();
    }
    let (ours, theirs) = (ours / count as f64, theirs / count as f64);
    eprintln!("companion matrices: mean log10 error {ours:.2}, faer {theirs:.2}");
    assert!(ours <= theirs + 0.3, "{ours} vs faer's {theirs}");
}

#[test]
fn defective_and_clustered() {
    // A Jordan block of size 3 at λ = 2 (plus a simple root): a backward-stable solver
    // finds the triple root to about ε^(1/3)·‖A‖, their mean to ε.
    let mut rng = StdRng::seed_from_u64(5);
    let mut j = DMatrix::zeros(4, 4);
    for i in 0..3 {
        j[(i, i)] = 2.0;
    }
    j[(0, 1)] = 1.0;
    j[(1, 2)] = 1.0;
    j[(3, 3)] = -1.0;
    let x = DMatrix::from_fn(4, 4, |i, k| {
        f64::from(u8::from(i == k)) + 0.2 * rng.random_range(-1.0..1.0)
    });
    let a = &x * j * x.clone().try_inverse().unwrap();
    let got = small(&a);
    let triple: Vec<&Complex64> = got.iter().filter(|z| (z.re - 2.0).abs() < 0.1).collect();
    assert_eq!(triple.len(), 3, "{got:?}");
    let tol = 20.0 * f64::EPSILON.cbrt() * a.norm();
    for z in &triple {
        assert!((*z - 2.0).norm() < tol, "{z} vs 2 (tol {tol:e})");
    }
    let mean = triple.iter().fold(Complex64::new(0.0, 0.0), |s, z| s + **z) / 3.0;
    assert!((mean - 2.0).norm() < 1e-12, "mean {mean}");
    assert!(got.iter().any(|z| (z - (-1.0)).norm() < 1e-12), "{got:?}");

    // Clustered: eigenvalues 1, 1 + 1e-8, 1 + 2e-8 of a normal matrix are found to ε.
    let q = {
        let m = DMatrix::from_fn(5, 5, |_, _| rng.random_range(-1.0..1.0));
        m.qr().q()
    };
    let d = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![
        1.0,
        1.0 + 1e-8,
        1.0 + 2e-8,
        -3.0,
        0.5,
    ]));
    let a = &q * d * q.transpose();
    let got = small(&a);
    let want: Vec<Complex64> = [1.0, 1.0 + 1e-8, 1.0 + 2e-8, -3.0, 0.5]
        .iter()
        .map(|&r| Complex64::new(r, 0.0))
        .collect();
    let err = matched_error(&got, &want);
    assert!(
        err < 1e-14 * 50.0,
        "clustered normal matrix: {err:e} {got:?}"
    );
}

#[test]
fn structural_zeros_are_exact() {
    // x0 integrates x1 − x2 … : a column of zeros and a pair acting through its difference.
    let a = DMatrix::from_row_slice(
        5,
        5,
        &[
            0.0, 1.0, -1.0, 0.0, 0.0, //
            0.0, -2.0, 2.0, 1.0, 0.0, //
            0.0, 3.0, -3.0, 0.0, 1.0, //
            0.0, -5.0, 5.0, -0.1, 0.3, //
            0.0, 7.0, -7.0, 0.2, -0.4, //
        ],
    );
    let mut out = vec![Complex64::new(0.0, 0.0); 5];
    let zeros = eigenvalues_small(a.as_slice(), 5, &mut out).unwrap();
    assert_eq!(zeros, 2, "{out:?}");
    assert_eq!(
        out.iter()
            .filter(|z| **z == Complex64::new(0.0, 0.0))
            .count(),
        2,
        "{out:?}"
    );
    let faer = faer_eigenvalues(&a);
    let nonzero_faer: Vec<Complex64> = faer.iter().copied().filter(|z| z.norm() > 1e-6).collect();
    let nonzero: Vec<Complex64> = out.iter().copied().filter(|z| z.norm() > 0.0).collect();
    assert!(matched_error(&nonzero, &nonzero_faer) < 1e-12);
}

#[test]
fn bad_input_is_an_error_naming_the_entry() {
    let mut out = vec![Complex64::new(0.0, 0.0); 2];
    let e = eigenvalues_small(&[1.0, f64::NAN, 0.0, 1.0], 2, &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            NumError::NonFinite(NonFiniteError::Entry(MatrixEntry { row: 1, col: 0, ref matrix, .. })) if matrix == "A"
        ),
        "{e}"
    );
    let e = eigenvalues_small(&[1.0, 1e200, 0.0, 1.0], 2, &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            NumError::OutOfRange { ref entry, max }
                if (entry.matrix.as_str(), entry.row, entry.col, entry.value) == ("A", 1, 0, 1e200)
                    && max == eom_num::MAX_ENTRY
        ),
        "{e}"
    );
    let e =
        eigenvalues_small(&[1.0; 17 * 17], 17, &mut [Complex64::new(0.0, 0.0); 17]).unwrap_err();
    assert!(matches!(e, NumError::Dimension(_)), "{e}");
    let e = eigenvalues_small(&[1.0; 3], 2, &mut out).unwrap_err();
    assert!(matches!(e, NumError::Dimension(_)), "{e}");
    // Empty and 1×1.
    assert_eq!(eigenvalues_small(&[], 0, &mut []).unwrap(), 0);
    let mut one = [Complex64::new(0.0, 0.0)];
    eigenvalues_small(&[-4.5], 1, &mut one).unwrap();
    assert_eq!(one[0], Complex64::new(-4.5, 0.0));
}

#[test]
fn known_zeros_are_replayed_and_checked() {
    // The matrix of `structural_zeros_are_exact` at other values: the same structure.
    let at = |p: f64| {
        DMatrix::from_row_slice(
            5,
            5,
            &[
                0.0,
                1.0,
                -1.0,
                0.0,
                0.0, //
                0.0,
                -2.0 * p,
                2.0 * p,
                1.0,
                0.0, //
                0.0,
                3.0,
                -3.0,
                0.0,
                1.0, //
                0.0,
                -5.0,
                5.0,
                -0.1 * p,
                0.3, //
                0.0,
                7.0 * p,
                -7.0 * p,
                0.2,
                -0.4, //
            ],
        )
    };
    let known = KnownZeros::of(at(1.0).as_slice(), 5).unwrap();
    assert_eq!((known.count(), known.dim()), (2, 5));
    for p in [0.5, 1.3, 2.0] {
        let a = at(p);
        let mut replayed = vec![Complex64::new(0.0, 0.0); 5];
        let zeros = eigenvalues_small_known(a.as_slice(), 5, &known, &mut replayed).unwrap();
        assert_eq!(zeros, 2);
        assert_eq!(replayed, small(&a), "p = {p}");
    }
    // A matrix without that structure: the check fails and the zeros are searched afresh.
    let mut other = at(1.0);
    other[(3, 0)] = 0.5;
    let mut out = vec![Complex64::new(0.0, 0.0); 5];
    let zeros = eigenvalues_small_known(other.as_slice(), 5, &known, &mut out).unwrap();
    let mut fresh = vec![Complex64::new(0.0, 0.0); 5];
    assert_eq!(
        zeros,
        eigenvalues_small(other.as_slice(), 5, &mut fresh).unwrap()
    );
    assert_eq!(out, fresh);
    assert!(zeros < 2, "{out:?}");
    // Another size is an error.
    let e = eigenvalues_small_known(&[1.0; 4], 2, &known, &mut out[..2]).unwrap_err();
    assert!(matches!(e, NumError::Dimension(_)), "{e}");
}
