//! The eigenvalue error estimates of small matrices (`eigenvalues_with_errors` below 17
//! states: the stack kernel's eigenvalues, the vectors by inverse iteration) against faer's
//! eigenvectors (`eigenvalues_with_errors_faer`) on random, graded, complex, near-defective
//! and defective matrices, and against the closed form of a triangular 2×2 block.

use eom_num::modes::{ModeOptions, eigenvalues_with_errors, eigenvalues_with_errors_faer};
use eom_num::small_eigen::MAX_N;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Each `(λ, e)` of `got` paired with the closest eigenvalue of `want` (greedy from the
/// closest pair): the pairs `(got, want)`.
fn matched(
    got: &[(Complex64, f64)],
    want: &[(Complex64, f64)],
) -> Vec<((Complex64, f64), (Complex64, f64))> {
    assert_eq!(got.len(), want.len());
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, g) in got.iter().enumerate() {
        for (j, w) in want.iter().enumerate() {
            pairs.push(((g.0 - w.0).norm(), i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut gi, mut wj) = (vec![false; got.len()], vec![false; want.len()]);
    let mut out = Vec::new();
    for (_, i, j) in pairs {
        if !gi[i] && !wj[j] {
            gi[i] = true;
            wj[j] = true;
            out.push((got[i], want[j]));
        }
    }
    out
}

/// The largest relative difference between the stack path's estimates and faer's.
fn worst_ratio(a: &DMatrix<f64>) -> f64 {
    let got = eigenvalues_with_errors(a).expect("stack path");
    let want = eigenvalues_with_errors_faer(a).expect("faer path");
    matched(&got, &want)
        .iter()
        .map(|((_, eg), (_, ew))| {
            if eg == ew {
                0.0
            } else {
                (eg - ew).abs() / ew.abs().max(eg.abs())
            }
        })
        .fold(0.0, f64::max)
}

fn random(rng: &mut StdRng, n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0))
}

#[test]
fn random_matrices_agree_with_faer() {
    let mut rng = StdRng::seed_from_u64(7);
    let mut worst = 0.0f64;
    for n in 1..=MAX_N {
        for _ in 0..30 {
            let a = random(&mut rng, n);
            let r = worst_ratio(&a);
            worst = worst.max(r);
            assert!(r < 1e-6, "n = {n}: estimates differ by {r:e}\n{a}");
        }
    }
    eprintln!("random matrices: estimates within {worst:.1e} of faer's");
}

#[test]
fn graded_matrices_agree_with_faer() {
    // D A D⁻¹ with D spanning twelve decades: the balancing undoes it, on both paths.
    let mut rng = StdRng::seed_from_u64(8);
    let mut worst = 0.0f64;
    for n in [3, 4, 6, 9] {
        for _ in 0..20 {
            let a = random(&mut rng, n);
            let d: Vec<f64> = (0..n)
                .map(|_| 10f64.powf(rng.random_range(-6.0..6.0)))
                .collect();
            let g = DMatrix::from_fn(n, n, |i, j| d[i] * a[(i, j)] / d[j]);
            let r = worst_ratio(&g);
            worst = worst.max(r);
            assert!(r < 1e-6, "n = {n}: estimates differ by {r:e}\n{g}");
        }
    }
    eprintln!("graded matrices: estimates within {worst:.1e} of faer's");
}

/// `[[a, t], [0, b]]`: κ = √(1 + t²/(a − b)²) for both eigenvalues (no balancing: a zero
/// off-diagonal entry), the componentwise number |a| and |b|, so the estimate is
/// `max(20 ε ‖A‖_F κ, ε |λ|)`.
#[test]
fn triangular_blocks_match_the_closed_form() {
    let f = ModeOptions::default().tol_factor;
    for gap in [1.0f64, 1e-2, 1e-4, 1e-6, 1e-7] {
        for t in [1.0f64, -3.0, 1e3] {
            let (a, b) = (-0.5, -0.5 + gap);
            let m = DMatrix::from_row_slice(2, 2, &[a, t, 0.0, b]);
            let kappa = (1.0 + (t / gap).powi(2)).sqrt();
            let norm = m.norm();
            let got = eigenvalues_with_errors(&m).unwrap();
            for (z, e) in &got {
                let want = (f * 2.0 * f64::EPSILON * norm * kappa).max(f64::EPSILON * z.norm());
                let rel = (e - want).abs() / want;
                // The vectors of eigenvalues a gap apart are determined to ε/gap.
                let tol = 1e-12 / gap;
                assert!(
                    rel < tol,
                    "gap {gap:e}, t {t}: λ = {z}, estimate {e:e}, closed form {want:e} ({rel:e})"
                );
            }
        }
    }
}

/// Spectra with conjugate pairs under a random similarity.
#[test]
fn complex_pairs_agree_with_faer() {
    let mut rng = StdRng::seed_from_u64(9);
    for n in [2usize, 4, 5, 8] {
        for _ in 0..20 {
            // Companion matrices of random polynomials: mostly complex roots, graded.
            let mut a = DMatrix::zeros(n, n);
            for i in 1..n {
                a[(i, i - 1)] = 1.0;
            }
            for i in 0..n {
                a[(i, n - 1)] = rng.random_range(-3.0..3.0);
            }
            let r = worst_ratio(&a);
            assert!(
                r < 1e-6,
                "companion n = {n}: estimates differ by {r:e}\n{a}"
            );
            let got = eigenvalues_with_errors(&a).unwrap();
            for w in got.windows(2) {
                if w[0].0.im != 0.0 && w[0].0.re == w[1].0.re {
                    assert_eq!(w[0].1, w[1].1, "a conjugate pair has one estimate");
                }
            }
        }
    }
}

/// A Jordan block of size 2 split by `δ`, under a random similarity: the condition number
/// grows like 1/δ on both paths, and the two agree to the accuracy of vectors δ apart.
#[test]
fn near_defective_agree_with_faer() {
    let mut rng = StdRng::seed_from_u64(10);
    for delta in [1e-3, 1e-5, 1e-7] {
        for n in [3usize, 4, 6] {
            let mut j = DMatrix::zeros(n, n);
            j[(0, 0)] = 1.0;
            j[(1, 1)] = 1.0 + delta;
            j[(0, 1)] = 1.0;
            for i in 2..n {
                j[(i, i)] = -1.0 - i as f64;
            }
            let x = DMatrix::from_fn(n, n, |i, k| {
                f64::from(u8::from(i == k)) + 0.3 * rng.random_range(-1.0..1.0)
            });
            let a = &x * j * x.clone().try_inverse().unwrap();
            let r = worst_ratio(&a);
            // Vectors of eigenvalues δ apart are known to about ε/δ, and their product yᴴx
            // (of size δ) then to ε/δ² relative: so is the estimate, on either path.
            assert!(
                r < 1e-14 / (delta * delta),
                "δ = {delta:e}, n = {n}: estimates differ by {r:e}"
            );
            let got = eigenvalues_with_errors(&a).unwrap();
            let pair_estimate = got
                .iter()
                .filter(|(z, _)| (z.re - 1.0).abs() < 0.01)
                .map(|(_, e)| *e)
                .fold(0.0, f64::max);
            // κ ≥ 1/(2δ) or so (t = 1): the estimate is at least 10·n·ε·‖A‖/(4δ).
            let floor = 10.0 * n as f64 * f64::EPSILON / (4.0 * delta);
            assert!(
                pair_estimate > floor,
                "δ = {delta:e}: estimate {pair_estimate:e} below {floor:e}"
            );
        }
    }
}

/// An exactly defective eigenvalue: the condition number near 1/ε on both paths alone
/// (triangular, exact eigenvalues), or hidden by a similarity (split by rounding to about
/// √ε; the vectors then nearly parallel, κ ≈ 1/√ε, known to a factor).
#[test]
fn defective_agree_with_faer() {
    let f = ModeOptions::default().tol_factor;
    let m = DMatrix::from_row_slice(3, 3, &[2.0, 1.0, 0.5, 0.0, 2.0, 1.0, 0.0, 0.0, -1.0]);
    let got = eigenvalues_with_errors(&m).unwrap();
    let want = eigenvalues_with_errors_faer(&m).unwrap();
    let capped = f * 3.0 * m.norm();
    for ((zg, eg), (_, ew)) in matched(&got, &want) {
        if (zg.re - 2.0).abs() < 1e-12 {
            // κ beyond 1e-3/ε on both: the eigenvalue undetermined (neither path's vectors
            // are exactly parallel, so neither reaches the cap exactly).
            assert!(
                eg > 1e-3 * capped && ew > 1e-3 * capped,
                "{zg}: {eg:e}, faer {ew:e}, cap {capped:e}"
            );
        }
    }
    let mut rng = StdRng::seed_from_u64(11);
    for _ in 0..10 {
        let x = DMatrix::from_fn(4, 4, |i, k| {
            f64::from(u8::from(i == k)) + 0.3 * rng.random_range(-1.0..1.0)
        });
        let mut j =
            DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![0.5, 0.5, -2.0, -3.0]));
        j[(0, 1)] = 1.0;
        let a = &x * j * x.clone().try_inverse().unwrap();
        let got = eigenvalues_with_errors(&a).unwrap();
        let want = eigenvalues_with_errors_faer(&a).unwrap();
        for ((zg, eg), (_, ew)) in matched(&got, &want) {
            if (zg.re - 0.5).abs() < 0.01 {
                // κ ≥ 1e6 on both (about 1/√ε), and within a factor 10 of each other.
                let floor = f * 4.0 * f64::EPSILON * a.norm() * 1e6;
                assert!(eg > floor && ew > floor, "{zg}: {eg:e}, faer {ew:e}");
                assert!(
                    eg / ew < 10.0 && ew / eg < 10.0,
                    "{zg}: {eg:e}, faer {ew:e}"
                );
            }
        }
    }
}

/// A matrix with structural zeros takes faer's path: the same numbers.
#[test]
fn structural_zeros_take_faers_path() {
    let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.3, 0.0, -2.0, 1.0, 0.0, -1.0, -0.5]);
    assert_eq!(
        eigenvalues_with_errors(&a).unwrap(),
        eigenvalues_with_errors_faer(&a).unwrap()
    );
}
