//! `eom analyze --sensitivity` against implicit differentiation of the shimmy's closed-form
//! cubic `P(s, p) = (I + m a²) s³ + m a u s² + k l² s + k l u` (a = x l):
//! `∂λ/∂p = −(∂P/∂p)/(∂P/∂s)` at each root.

mod common;
use common::{complex, eom, eom_json};
use num_complex::Complex64;

#[test]
fn shimmy_sensitivities_equal_implicit_differentiation_of_the_cubic() {
    let j = eom_json(&[
        "analyze",
        "shimmy",
        "--set",
        "x=0.4",
        "--sensitivity",
        "--format",
        "json",
    ]);
    let (m, i, k, l, x, u) = (5.0, 1.05, 1.5, 1.0, 0.4, 10.0);
    let sens = j["sensitivity"].as_array().expect("sensitivity");
    assert_eq!(sens.len(), 3);
    for e in sens {
        let (re, im) = complex(&e["eigenvalue"]);
        let s = Complex64::new(re, im);
        let a = x * l;
        let dp_ds = 3.0 * (i + m * a * a) * s * s + 2.0 * m * a * u * s + k * l * l;
        // ∂P/∂p for each parameter, with a = x l.
        let want = [
            ("m", a * a * s * s * s + a * u * s * s),
            ("I", s * s * s),
            ("k", l * l * s + l * u),
            (
                "l",
                2.0 * m * x * x * l * s * s * s + m * x * u * s * s + 2.0 * k * l * s + k * u,
            ),
            ("x", 2.0 * m * x * l * l * s * s * s + m * l * u * s * s),
            ("u", m * a * s * s + k * l),
        ];
        for (p, dp) in want {
            let d = -dp / dp_ds;
            let (gr, gi) = complex(&e["derivatives"][p]);
            let got = Complex64::new(gr, gi);
            assert!(
                (got - d).norm() <= 1e-10 * d.norm().max(1e-6),
                "∂λ/∂{p} at {s}: printed {got}, closed form {d}"
            );
        }
    }
}

#[test]
fn defective_eigenvalues_get_no_number() {
    // The bicycle's heading and lateral position: two zero eigenvalues in one Jordan block.
    let j = eom_json(&["analyze", "bicycle", "--sensitivity", "--format", "json"]);
    let sens = j["sensitivity"].as_array().expect("sensitivity");
    let flagged: Vec<_> = sens.iter().filter(|e| e["derivatives"].is_null()).collect();
    assert_eq!(flagged.len(), 2, "{sens:?}");
    for e in flagged {
        let (re, im) = complex(&e["eigenvalue"]);
        assert!(re.abs() < 1e-5 && im.abs() < 1e-5);
    }
    let text = eom(&["analyze", "bicycle", "--sensitivity"]);
    assert_eq!(text.code, 0);
    assert!(
        text.stdout.contains("the derivative is unbounded"),
        "{}",
        text.stdout
    );
}
