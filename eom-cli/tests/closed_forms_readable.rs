//! Closed forms a user can read: coefficients and conditions factored where they factor (the
//! half car's kf·kr·(a + b)², checked by hand and with sympy's `factor`), conditions whose
//! every term is a product of parameters declared positive with a positive coefficient
//! dropped (`always`), and an undamped model said to be never asymptotically stable.

mod common;
use common::eom;

fn half_car() -> String {
    format!("{}/../models/half_car.toml", env!("CARGO_MANIFEST_DIR"))
}

fn symbolic(args: &[&str]) -> String {
    let mut all = vec!["symbolic"];
    all.extend_from_slice(args);
    all.push("--stability");
    let r = eom(&all);
    assert_eq!(r.code, 0, "{}", r.stderr);
    r.stdout
}

#[test]
fn the_half_car_polynomial_is_factored() {
    let t = symbolic(&[&half_car()]);
    assert!(t.contains("  s^0: kf*kr*(a + b)^2\n"), "{t}");
    assert!(t.contains("  s^1: (a + b)^2*(kf*cr + kr*cf)\n"), "{t}");
    // Without the front damper: stable exactly when the front and rear do not decouple,
    // I ≠ m a b (the undamped front half's mode).
    let t = symbolic(&[&half_car(), "--set", "cf=0"]);
    assert!(t.contains("  (I - m*a*b)^2 > 0      [hurwitz 3]\n"), "{t}");
}

#[test]
fn conditions_fixed_by_the_declared_signs_are_dropped() {
    // With the dampers declared positive, the coefficient conditions are sums of positive
    // terms: only the Hurwitz determinant is left to require.
    let text = std::fs::read_to_string(half_car())
        .expect("the model")
        .replace("range = \">= 0\"", "range = \"> 0\"");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("closed");
    std::fs::create_dir_all(&dir).expect("a directory");
    let file = dir.join("half_car_damped.toml");
    std::fs::write(&file, text).expect("the model file");
    let t = symbolic(&[file.to_str().expect("UTF-8")]);
    let conditions: Vec<&str> = t
        .lines()
        .skip_while(|l| !l.starts_with("asymptotically stable exactly when"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .collect();
    assert_eq!(conditions.len(), 1, "{t}");
    assert!(conditions[0].ends_with("[hurwitz 3]"), "{t}");
    // A spring–mass–damper with every parameter positive is always stable.
    let t = symbolic(&["smd"]);
    assert!(t.contains("asymptotically stable always"), "{t}");
}

#[test]
fn an_undamped_model_is_never_asymptotically_stable() {
    let t = symbolic(&["pendulum"]);
    assert!(
        t.contains("never asymptotically stable: the s^1 coefficient vanishes (no damping)"),
        "{t}"
    );
    assert!(!t.contains("0 > 0"), "{t}");
}
