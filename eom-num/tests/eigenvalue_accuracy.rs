//! `Mode::accuracy`, the estimated relative error of an eigenvalue caused by rounding every
//! entry of A, against the movement actually seen when A's entries are perturbed by at most
//! ε of themselves (random signs), on the state matrix of a chain whose spring stiffnesses
//! differ by 1e10: the estimate bounds the movement and is not vacuous (within a factor 10 of
//! the largest seen).

use eom_num::StateSpace;
use eom_num::modes::{ModeOptions, Modes};
use nalgebra::DMatrix;
use rand::{Rng, SeedableRng, rngs::StdRng};

/// State matrix of a fixed-free chain of unit masses with the given spring stiffnesses.
fn chain(k: &[f64]) -> DMatrix<f64> {
    let n = k.len();
    let mut stiff = DMatrix::zeros(n, n);
    for i in 0..n {
        stiff[(i, i)] = k[i] + if i + 1 < n { k[i + 1] } else { 0.0 };
        if i + 1 < n {
            stiff[(i, i + 1)] = -k[i + 1];
            stiff[(i + 1, i)] = -k[i + 1];
        }
    }
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -stiff[(i, j)];
        }
    }
    a
}

fn modes(a: &DMatrix<f64>) -> Modes {
    let n = a.nrows();
    let ss = StateSpace::new(
        a.clone(),
        DMatrix::zeros(n, 0),
        DMatrix::zeros(0, n),
        DMatrix::zeros(0, 0),
    )
    .expect("state space");
    let opts = ModeOptions {
        shapes: false,
        ..ModeOptions::default()
    };
    Modes::compute_with(&ss, &opts).expect("modes")
}

fn check(k: &[f64]) -> (f64, f64) {
    let a = chain(k);
    let base = modes(&a);
    let mut rng = StdRng::seed_from_u64(7);
    let mut seen = vec![0.0f64; base.modes.len()];
    for _ in 0..200 {
        let p = a.map(|x| x * (1.0 + f64::EPSILON * rng.random_range(-1.0..1.0)));
        let moved = modes(&p).eigenvalues();
        for (s, m) in seen.iter_mut().zip(&base.modes) {
            let near = moved
                .iter()
                .map(|z| (z - m.eigenvalue).norm())
                .fold(f64::INFINITY, f64::min);
            *s = s.max(near / m.eigenvalue.norm());
        }
    }
    let (mut worst_seen, mut worst_estimate) = (0.0f64, 0.0f64);
    for (s, m) in seen.iter().zip(&base.modes) {
        // The estimate bounds the movement (first order, a margin of 2 for the second), up to
        // the eigensolver's own rounding (the mode's tolerance).
        let solver = m.tolerance / m.eigenvalue.norm();
        assert!(
            *s <= 2.0 * m.accuracy + solver,
            "λ {}: moved {s:e}, estimate {:e}",
            m.eigenvalue,
            m.accuracy
        );
        worst_seen = worst_seen.max(*s);
        worst_estimate = worst_estimate.max(m.accuracy);
    }
    (worst_seen, worst_estimate)
}

#[test]
fn the_estimate_bounds_and_follows_the_movement_under_rounding() {
    for k in [[1.0, 1.0, 1e-10, 1.0], [1.0, 1.0, 1e10, 1.0]] {
        let (seen, estimate) = check(&k);
        // The slow modes really are sensitive, and the estimate says so.
        assert!(seen > 1e-7, "{k:?}: {seen:e}");
        assert!(
            estimate > 1e-6 && estimate < 10.0 * seen,
            "{k:?}: {estimate:e} vs {seen:e}"
        );
    }
    // Equal springs: every eigenvalue to about ε.
    let (seen, estimate) = check(&[1.0, 1.0, 1.0, 1.0]);
    assert!(estimate < 1e-14 && seen < 1e-14, "{estimate:e} {seen:e}");
}
