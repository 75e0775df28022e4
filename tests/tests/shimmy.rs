//! Shimmy (swivel wheel) eigenvalues against the closed-form characteristic cubic
//! (reference data: `data/shimmy_eigs_u10.csv`, `data/shimmy_eigs_u1.csv`, see data/README.md),
//! by all three reduction paths, to 1e-12 relative.

// Reference values are transcribed digit for digit from their sources.
#![allow(clippy::excessive_precision)]

use eom_model::{Linearizer, Method};
use num_complex::Complex64;
use tests::{max_relative_error, read_csv};

fn check(csv: &str, u: f64) {
    let model = models::build("shimmy", &[("u", u)]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let rows = read_csv(csv);
    assert_eq!(rows.len(), 151);
    let mut worst = [0.0f64; 3];
    for row in &rows {
        let x = row[0];
        let expected: Vec<Complex64> = (0..3)
            .map(|k| Complex64::new(row[1 + 2 * k], row[2 + 2 * k]))
            .collect();
        let values = model.scope.values_with(&[("x", x), ("u", u)]).unwrap();
        let paths = [
            sym.evaluate(&values).unwrap(),
            Linearizer::new(&model)
                .at(&[("x", x)])
                .method(Method::Numeric)
                .run()
                .unwrap()
                .state_space,
            Linearizer::new(&model)
                .at(&[("x", x)])
                .method(Method::Robust)
                .run()
                .unwrap()
                .state_space,
        ];
        for (k, ss) in paths.iter().enumerate() {
            let got = eom_num::modes::eigenvalues(&ss.a).unwrap();
            let err = max_relative_error(&got, &expected, 1e-300);
            worst[k] = worst[k].max(err);
            assert!(
                err <= 1e-12,
                "u = {u}, x = {x}, path {k}: relative error {err:e}\n got {got:?}\n expected {expected:?}"
            );
        }
    }
    eprintln!(
        "shimmy u = {u}: worst relative error symbolic {:.1e}, numeric {:.1e}, robust {:.1e}",
        worst[0], worst[1], worst[2]
    );
}

#[test]
fn shimmy_u10_matches_closed_form_cubic() {
    check(include_str!("../data/shimmy_eigs_u10.csv"), 10.0);
}

#[test]
fn shimmy_u1_matches_closed_form_cubic() {
    check(include_str!("../data/shimmy_eigs_u1.csv"), 1.0);
}

/// At a/l = 0.3 and 0.7 the roots are exactly −u/l and ±i√(k l/(m a)) (docs/references.md §B).
#[test]
fn shimmy_stability_boundaries_are_exact() {
    let model = models::build("shimmy", &[]).unwrap();
    for (x, w) in [(0.3, 1.0), (0.7, (3.0f64 / 7.0).sqrt())] {
        let ss = Linearizer::new(&model)
            .at(&[("x", x)])
            .run()
            .unwrap()
            .state_space;
        let got = eom_num::modes::eigenvalues(&ss.a).unwrap();
        let expected = [
            Complex64::new(-10.0, 0.0),
            Complex64::new(0.0, w),
            Complex64::new(0.0, -w),
        ];
        let err = tests::max_abs_error(&got, &expected);
        assert!(err < 1e-13, "x = {x}: {got:?}");
    }
}
