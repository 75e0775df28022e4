//! Symbolic = numeric: for every built-in model (each entry of `models::catalogue()`, the
//! families at size 8), the symbolic state space evaluated at 1 000 random parameter points
//! equals the numeric elimination replaying the same plan (same basis, so matrices compare
//! entry by entry) to 1e-10 relative, and has the invariants of the independent robust SVD
//! path (transfer function at a few frequencies, 1e-8 relative; the eigenvalues, 1e-8
//! relative, for a model without inputs or outputs, whose transfer function is empty) — while
//! the recorded pivots stay valid. Outside that region the symbolic evaluation reports the
//! failing pivot instead of returning numbers.

use eom_model::ModelError;
use eom_model::{Linearizer, assemble, reduce, reduce_robust};
use eom_num::StateSpace;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::{Rng, SeedableRng, rngs::StdRng};

/// Every catalogue entry by the name it builds under, the families at size 8.
fn models() -> Vec<String> {
    models::catalogue().iter().map(|m| m.name_at(8)).collect()
}

fn rel_diff(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    let scale = a.abs().max().max(b.abs().max()).max(f64::MIN_POSITIVE);
    (a - b).abs().max() / scale
}

/// The eigenvalues of A, a basis-independent invariant.
fn eigenvalues(ss: &StateSpace<f64>) -> Vec<Complex64> {
    eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues")
}

/// G(s) = C (sI − A)⁻¹ B + D, a basis-independent invariant.
fn transfer(ss: &StateSpace<f64>, s: Complex64) -> DMatrix<Complex64> {
    let n = ss.states();
    let a = ss.a.map(|x| Complex64::new(x, 0.0));
    let m = DMatrix::<Complex64>::identity(n, n) * s - a;
    let x = m
        .lu()
        .solve(&ss.b.map(|x| Complex64::new(x, 0.0)))
        .expect("s is not a pole");
    ss.c.map(|x| Complex64::new(x, 0.0)) * x + ss.d.map(|x| Complex64::new(x, 0.0))
}

#[test]
fn symbolic_equals_numeric_at_random_points() {
    let mut rng = StdRng::seed_from_u64(20261121);
    for name in models() {
        let name = name.as_str();
        let model = models::build(name, &[]).unwrap();
        let sym = Linearizer::new(&model).symbolic().unwrap();
        let plan = &sym.reduction.plan;
        let nominal = model.scope.nominal_values();
        let (mut worst_plan, mut worst_tf, mut compared_tf) = (0.0f64, 0.0f64, 0);
        let (mut worst_eig, mut compared_eig) = (0.0f64, 0);
        for k in 0..1000 {
            let values: Vec<f64> = nominal
                .iter()
                .map(|&x| {
                    if x == 0.0 {
                        rng.random_range(-0.2..0.2)
                    } else {
                        x * rng.random_range(0.8..1.2)
                    }
                })
                .collect();
            let s = sym
                .evaluate(&values)
                .unwrap_or_else(|e| panic!("{name} at {values:?}: {e}"));
            // The same plan replayed in f64.
            let m = model.evaluate(&values).unwrap();
            let replay = reduce(&assemble(&m).unwrap(), Some(plan))
                .unwrap()
                .state_space;
            for (x, y, what) in [
                (&s.a, &replay.a, "A"),
                (&s.b, &replay.b, "B"),
                (&s.c, &replay.c, "C"),
                (&s.d, &replay.d, "D"),
                (&s.phys, &replay.phys, "phys"),
            ] {
                let d = rel_diff(x, y);
                worst_plan = worst_plan.max(d);
                assert!(
                    d <= 1e-10,
                    "{name} point {k}: {what} differs by {d:e} (relative)"
                );
            }
            // Invariants against the robust path, on a subset (it is the slow one).
            if k % 20 == 0 {
                let robust = reduce_robust(&assemble(&m).unwrap()).unwrap().0;
                if s.b.ncols() == 0 || s.c.nrows() == 0 {
                    // No transfer function to compare: the eigenvalues are the invariant.
                    let d = tests::max_relative_error(&eigenvalues(&s), &eigenvalues(&robust), 1.0);
                    worst_eig = worst_eig.max(d);
                    compared_eig += 1;
                    assert!(
                        d <= 1e-8,
                        "{name} point {k}: eigenvalues differ by {d:e} (relative)"
                    );
                    continue;
                }
                for s_val in [Complex64::new(0.3, 1.7), Complex64::new(-0.05, 11.0)] {
                    let g1 = transfer(&s, s_val);
                    let g2 = transfer(&robust, s_val);
                    let scale = g1.iter().map(|z| z.norm()).fold(0.0, f64::max).max(1e-300);
                    let d = g1
                        .iter()
                        .zip(g2.iter())
                        .map(|(a, b)| (a - b).norm())
                        .fold(0.0, f64::max)
                        / scale;
                    worst_tf = worst_tf.max(d);
                    compared_tf += 1;
                    assert!(
                        d <= 1e-8,
                        "{name} point {k}: transfer functions differ by {d:e} (relative) at s = {s_val}"
                    );
                }
            }
        }
        assert!(
            compared_tf + compared_eig > 0,
            "{name}: no invariant compared"
        );
        eprintln!(
            "{name}: worst symbolic vs replayed numeric {worst_plan:.1e}; symbolic vs robust: transfer function {worst_tf:.1e} ({compared_tf} comparisons), eigenvalues {worst_eig:.1e} ({compared_eig})"
        );
    }
}

#[test]
fn outside_the_validity_region_is_reported() {
    // A bicycle without a wheelbase: the steer hinge's pivot vanishes.
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let values = model.scope.values_with(&[("w", 0.0)]).unwrap();
    match sym.evaluate(&values) {
        Err(ModelError::PivotBreakdown { check, .. }) => {
            assert!(check.contains("steer hinge"), "{check}")
        }
        other => panic!("expected a pivot breakdown, got {other:?}"),
    }
    // A massless block: the reduced mass pivot vanishes.
    let model = models::build("smd", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let massless = model.scope.values_with(&[("m", 0.0)]).unwrap();
    match sym.evaluate(&massless) {
        Err(ModelError::PivotBreakdown { check, .. }) => {
            assert!(check.contains("reduced mass"), "{check}")
        }
        other => panic!("expected a pivot breakdown, got {other:?}"),
    }
    // A pivot that is small but still valid gives accurate numbers (not a breakdown).
    let model = models::build("smd", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let light = model.scope.values_with(&[("m", 1e-6)]).unwrap();
    let ss = sym.evaluate(&light).unwrap();
    let k = model.scope.get("k").unwrap().nominal();
    assert!((ss.a[(1, 0)] + k / 1e-6).abs() < 1e-3);
}
