//! Liénard–Chipart conditions whose leading coefficient has no declared sign: the polynomial
//! `m s² + c s + k` is as stable with `m, c, k < 0` as with all positive, so the conditions
//! must be `c·m > 0, k·m > 0`, not `m > 0, c > 0, k > 0`. Checked against the numeric
//! eigenvalues of the companion matrices at random points of every sign.

use eom_sym::closed::ClosedForms;
use eom_sym::{Assumption, Expr, ParamInfo, Tape};
use nalgebra::DMatrix;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn param(name: &str, assume: Assumption) -> Expr {
    Expr::new_param(ParamInfo {
        name: name.into(),
        nominal: 1.1,
        unit: None,
        description: None,
        assume,
    })
    .unwrap()
}

/// The companion matrix of `c[n] sⁿ + … + c[0]` (ascending coefficients).
fn companion(c: &[Expr]) -> DMatrix<Expr> {
    let n = c.len() - 1;
    DMatrix::from_fn(n, n, |i, j| {
        if i + 1 < n {
            if j == i + 1 {
                Expr::one()
            } else {
                Expr::zero()
            }
        } else {
            -c[j] / c[n]
        }
    })
}

/// Asserts that the conditions hold exactly where every eigenvalue of the companion matrix
/// (evaluated numerically) has a negative real part, at random points with any signs.
fn check(params: &[Expr], coefficients: &[Expr], seed: u64) -> usize {
    let cf = ClosedForms::default();
    let a = companion(coefficients);
    let p = cf.characteristic_polynomial(&a).expect("polynomial");
    let conds = cf.stability_conditions(&p).expect("conditions");
    let exprs: Vec<Expr> = conds.iter().map(|c| c.expression).collect();
    let tape = Tape::new(&exprs, params).expect("conditions tape");
    let a_tape = Tape::new(&a.iter().copied().collect::<Vec<_>>(), params).expect("A tape");
    let n = a.nrows();
    let mut rng = StdRng::seed_from_u64(seed);
    let mut stable = 0;
    for _ in 0..2000 {
        let at: Vec<f64> = params
            .iter()
            .map(|_| (0.2 + rng.random::<f64>()) * if rng.random::<bool>() { 1.0 } else { -1.0 })
            .collect();
        let entries = a_tape.eval_vec(&at).expect("A");
        let am = DMatrix::from_column_slice(n, n, &entries);
        let max_re = am
            .complex_eigenvalues()
            .iter()
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max);
        if max_re.abs() < 1e-9 {
            continue;
        }
        let v = tape.eval_vec(&at).expect("conditions");
        let holds = v.iter().all(|&c| c > 0.0);
        assert_eq!(
            holds,
            max_re < 0.0,
            "at {at:?}: {exprs:?} = {v:?}, max Re λ {max_re}"
        );
        stable += usize::from(holds);
    }
    stable
}

#[test]
fn a_quadratic_with_every_sign_open() {
    let [m, c, k] = ["m", "c", "k"].map(|x| param(x, Assumption::Real));
    let stable = check(&[m, c, k], &[k, c, m], 1);
    // All three of one sign: a quarter of the points, half of them with m < 0.
    assert!(stable > 300, "{stable} stable points");
}

#[test]
fn a_cubic_with_every_sign_open() {
    let [m, a, b, k] = ["m", "a", "b", "k"].map(|x| param(x, Assumption::Real));
    let stable = check(&[m, a, b, k], &[k, b, a, m], 2);
    assert!(stable > 50, "{stable} stable points");
}

#[test]
fn a_declared_positive_leading_coefficient_is_divided_out() {
    let m = param("m", Assumption::Positive);
    let [c, k] = ["c", "k"].map(|x| param(x, Assumption::Real));
    let cf = ClosedForms::default();
    let p = cf
        .characteristic_polynomial(&companion(&[k, c, m]))
        .expect("polynomial");
    let mut conds: Vec<String> = cf
        .stability_conditions(&p)
        .expect("conditions")
        .iter()
        .map(|c| c.expression.to_string())
        .collect();
    conds.sort();
    assert_eq!(conds, ["c", "k"]);
}

/// The verdict of `s² + c₁ s + c₀` with constant coefficients (every parameter substituted):
/// decided by the sign of the exact constants, not left as conditions to check.
fn constant_verdict(c1: Expr, c0: Expr) -> String {
    use eom_sym::closed::SummaryRequest;
    let a = companion(&[c0, c1, Expr::one()]);
    let e = DMatrix::from_fn(2, 2, |i, j| if i == j { Expr::one() } else { Expr::zero() });
    let none = |r, c| DMatrix::from_element(r, c, Expr::zero());
    let (b, c, d) = (none(2, 0), none(0, 2), none(0, 0));
    let summary = ClosedForms::default()
        .summary(
            (&e, &a),
            [&a, &b, &c, &d],
            &SummaryRequest {
                stability: true,
                ..Default::default()
            },
        )
        .expect("summary");
    summary.verdict().expect("conditions requested")
}

#[test]
fn constant_conditions_are_decided_by_their_exact_sign() {
    let r = |n, d| Expr::rational(n, d).unwrap();
    // cos(2) = −0.416: a negative damping coefficient, unstable whatever else.
    let v = constant_verdict(Expr::int(2).cos(), Expr::one());
    assert!(v.starts_with("never"), "{v}");
    // sin(3/10) = 0.2955 > 0 and 2 − e^(1/2) = 0.351 > 0: stable.
    let v = constant_verdict(r(3, 10).sin(), Expr::int(2) - r(1, 2).exp());
    assert_eq!(v, "always");
    // √(1 + 10⁻¹⁷) − 1 = 5·10⁻¹⁸ is positive, but no double-precision enclosure shows it.
    let tiny = (Expr::one() + r(1, 100_000_000_000_000_000)).sqrt() - Expr::one();
    let v = constant_verdict(tiny, Expr::one());
    assert!(v.starts_with("undecided"), "{v}");
}
