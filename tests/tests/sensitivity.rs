//! Eigenvalue sensitivities `∂λ/∂p` (eigenvectors and the exact `∂A/∂p`) against central
//! finite differences of eigenvalues computed in double-double: A evaluated in double-double at
//! `p ± h`, each eigenvalue refined by Newton's method on `det(A − λI)`.

use eom_model::{Linearizer, sensitivities};
use eom_sym::{Dd, dd::refine_eigenvalue, eval_generic};
use num_complex::Complex64;

fn check(model: &str, at: &[(&str, f64)]) {
    let m = models::build(model, at).expect("model");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let values = m.scope.nominal_values();
    let s = sensitivities(&sym, &values).expect("sensitivities");
    let entries: Vec<eom_sym::Expr> = sym.state_space().a.iter().copied().collect();
    let n = sym.state_space().a.nrows();
    let a_dd = |v: &[Dd]| -> Vec<Vec<Dd>> {
        let idx: Vec<u32> = sym
            .params
            .iter()
            .map(|p| p.param_index().expect("param"))
            .collect();
        let flat = eval_generic::<Dd>(&entries, |i| idx.iter().position(|&k| k == i).map(|k| v[k]))
            .expect("A in double-double");
        // column-major to rows
        (0..n)
            .map(|i| (0..n).map(|j| flat[j * n + i]).collect())
            .collect()
    };
    let mut compared = 0;
    for e in &s.eigenvalues {
        let Some(d) = &e.derivatives else {
            // Only the structural zero pair of a vehicle may be flagged.
            assert!(
                e.eigenvalue.norm() < 1e-6,
                "{model}: {:?} flagged defective",
                e.eigenvalue
            );
            continue;
        };
        let scale = d.iter().fold(0.0f64, |a, x| a.max(x.norm()));
        for (k, dk) in d.iter().enumerate() {
            let h = 1e-7 * values[k].abs().max(1e-3);
            let eig_at = |sign: f64| -> (Dd, Dd) {
                let v: Vec<Dd> = values
                    .iter()
                    .enumerate()
                    .map(|(j, &x)| {
                        if j == k {
                            Dd::from_f64(x) + Dd::from_f64(sign * h)
                        } else {
                            Dd::from_f64(x)
                        }
                    })
                    .collect();
                let guess = e.eigenvalue + *dk * (sign * h);
                refine_eigenvalue(&a_dd(&v), (guess.re, guess.im))
                    .unwrap_or_else(|| panic!("{model}: Newton did not settle at {guess}"))
            };
            // The difference in double-double, before rounding.
            let (plus, minus) = (eig_at(1.0), eig_at(-1.0));
            let two_h = Dd::from_f64(2.0 * h);
            let fd = Complex64::new(
                ((plus.0 - minus.0) / two_h).to_f64(),
                ((plus.1 - minus.1) / two_h).to_f64(),
            );
            let err = (fd - dk).norm();
            assert!(
                err <= 1e-8 * dk.norm().max(1e-4 * scale),
                "{model}: ∂λ/∂{} at λ = {}: formula {dk}, finite difference {fd}",
                s.params[k],
                e.eigenvalue
            );
            compared += 1;
        }
    }
    assert!(compared > 0, "{model}: nothing compared");
}

#[test]
fn shimmy_sensitivities_match_finite_differences() {
    check("shimmy", &[]);
    check("shimmy", &[("x", 0.2), ("u", 3.0)]);
}

#[test]
fn quarter_car_sensitivities_match_finite_differences() {
    check("quarter_car", &[]);
}

#[test]
fn bicycle_sensitivities_match_finite_differences() {
    check("bicycle", &[("v", 5.0)]);
}
