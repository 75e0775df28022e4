//! One test (or more) per identity of the table in the `pool` module docs: the identity
//! applies when its condition holds and is *not* applied when it does not.
//!
//! Equality of handles is the check (hash-consing: structurally equal expressions have the
//! same id), completed by `view()` where the structure itself is the point. Expected values
//! are written by hand from the definitions (exact arithmetic), never taken from the code's
//! own earlier output.

use eom_sym::{Assumption, Constant, Expr, ExprView, Func, ParamInfo, Rational};

fn r(n: i64, d: i64) -> Rational {
    Rational::new(n, d).unwrap()
}

fn q(n: i64, d: i64) -> Expr {
    Expr::rational(n, d).unwrap()
}

fn param(name: &str, nominal: f64, assume: Assumption) -> Expr {
    Expr::new_param(ParamInfo {
        name: name.into(),
        nominal,
        unit: None,
        description: None,
        assume,
    })
    .unwrap()
}

fn real(name: &str) -> Expr {
    param(name, 0.7, Assumption::Real)
}

fn positive(name: &str) -> Expr {
    param(name, 1.3, Assumption::Positive)
}

/// `(coef, factors)` of a product node; panics (test failure) for anything else.
fn product(e: Expr) -> (Expr, Vec<(Expr, Rational)>) {
    match e.view() {
        ExprView::Product { coef, factors } => (coef, factors),
        v => panic!("expected a product, got {v:?}"),
    }
}

/// `(constant, terms)` of a sum node.
fn sum(e: Expr) -> (Expr, Vec<(Expr, Expr)>) {
    match e.view() {
        ExprView::Sum { constant, terms } => (constant, terms),
        v => panic!("expected a sum, got {v:?}"),
    }
}

/// Factors sorted by base id (the canonical order), for comparisons written by hand.
fn sorted(mut v: Vec<(Expr, Rational)>) -> Vec<(Expr, Rational)> {
    v.sort_by_key(|(b, e)| (b.id(), std::cmp::Reverse(e.signum())));
    v
}

// ------------------------------------------------------------------ row 1: neutral elements

#[test]
fn zero_plus_x_is_x() {
    let x = real("x");
    assert_eq!(Expr::zero() + x, x);
    assert_eq!(x + Expr::zero(), x);
    assert_eq!(Expr::sum([Expr::zero(), x, Expr::zero()]), x);
    // A sum with a zero constant is not a sum node at all.
    assert_eq!(
        x.view(),
        ExprView::Param(x.param_index().unwrap(), x.param_info().unwrap())
    );
}

#[test]
fn one_times_x_is_x() {
    let x = real("x");
    let s = x.sin();
    assert_eq!(Expr::one() * x, x);
    assert_eq!(s * Expr::one(), s);
    assert_eq!(Expr::product([Expr::one(), x, Expr::one()]), x);
    assert_eq!(q(3, 7) * q(7, 3) * s, s);
}

#[test]
fn x_to_the_one_is_x() {
    let x = real("x");
    let y = real("y");
    let s = x + y;
    assert_eq!(x.powi(1), x);
    assert_eq!(s.pow(Expr::one()), s);
    assert_eq!(s.pow_rational(r(2, 2)), s);
    assert_eq!(x.cos().pow(q(3, 3)), x.cos());
}

#[test]
fn x_minus_x_is_zero() {
    let x = real("x");
    let y = real("y");
    assert_eq!(x - x, Expr::zero());
    assert_eq!(x * y - y * x, Expr::zero());
    assert_eq!((x + y) - (y + x), Expr::zero());
    assert_eq!(x.sin() * 3 - 3 * x.sin(), Expr::zero());
    assert_eq!((x / y) - x * y.recip(), Expr::zero());
    // Not a zero: different terms.
    let d = x - y;
    let (c0, terms) = sum(d);
    assert!(c0.is_zero());
    assert_eq!(terms.len(), 2);
}

#[test]
fn like_terms_collect() {
    let x = real("x");
    let y = real("y");
    assert_eq!(2 * x + 3 * x, 5 * x);
    let (c, f) = product(5 * x);
    assert_eq!(c, Expr::int(5));
    assert_eq!(f, vec![(x, Rational::ONE)]);
    // With a product as the term, in any order of factors.
    assert_eq!(x * y * 2 + 3 * (y * x), 5 * x * y);
    // Rational coefficients: x/2 + x/3 = 5x/6.
    assert_eq!(x / 2 + x / 3, q(5, 6) * x);
    // Terms that differ are kept apart, each with its coefficient.
    let (c0, terms) = sum(2 * x + 3 * y + 4);
    assert_eq!(c0, Expr::int(4));
    let mut want = vec![(x, Expr::int(2)), (y, Expr::int(3))];
    want.sort_by_key(|(t, _)| t.id());
    assert_eq!(terms, want);
    // x and x² are different terms.
    assert_eq!(sum(x + x.powi(2)).1.len(), 2);
    // A partial cancellation leaves the rest: (2x + y) − 2x = y.
    assert_eq!((2 * x + y) - 2 * x, y);
}

// ------------------------------------------------------------------ row 2: 0·x

#[test]
fn zero_times_anything_is_zero() {
    let x = real("x");
    assert_eq!(Expr::zero() * x, Expr::zero());
    assert_eq!(x.sin() * Expr::zero(), Expr::zero());
    // Documented convention: even a factor that is undefined at some point (x⁻¹ at x = 0).
    assert_eq!(Expr::zero() * x.recip(), Expr::zero());
    assert_eq!(
        Expr::product([x, Expr::int(2), Expr::zero(), x.exp()]),
        Expr::zero()
    );
    // (x − x)·y: the zero is structural.
    let y = real("y");
    assert_eq!((x - x) * y, Expr::zero());
}

// ------------------------------------------------------------------ row 3: c·sin²x + c·cos²x

#[test]
fn pythagoras_with_equal_coefficients() {
    let x = real("x");
    let y = real("y");
    let (s2, c2) = (x.sin().powi(2), x.cos().powi(2));
    assert_eq!(s2 + c2, Expr::one());
    assert_eq!(c2 + s2, Expr::one());
    assert_eq!(3 * s2 + y + 3 * c2, y + 3);
    assert_eq!(q(-2, 5) * s2 + q(-2, 5) * c2, q(-2, 5));
    let a = Expr::int(2) * x + y;
    assert_eq!(a.sin().powi(2) + a.cos().powi(2) + y, y + 1);
    // Float coefficient: the constant is the float.
    let f = Expr::float(0.1).unwrap();
    assert_eq!((f * s2 + f * c2).view(), ExprView::Float(0.1));
    // Not applied: different coefficients, different arguments, or not squares.
    let e = 2 * s2 + 3 * c2;
    assert_eq!(
        sum(e),
        (Expr::zero(), {
            let mut t = vec![(s2, Expr::int(2)), (c2, Expr::int(3))];
            t.sort_by_key(|(t, _)| t.id());
            t
        })
    );
    assert_eq!(sum(s2 - c2).1.len(), 2);
    assert_eq!(sum(s2 + y.cos().powi(2)).1.len(), 2);
    assert_eq!(sum(x.sin() + x.cos()).1.len(), 2);
    assert_eq!(sum(x.sin().powi(4) + x.cos().powi(4)).1.len(), 2);
}

// ------------------------------------------------------------------ row 4: x^a·x^b

#[test]
fn same_sign_exponents_collect_for_any_base() {
    let x = real("x");
    assert_eq!(x * x, x.powi(2));
    assert_eq!(product(x * x), (Expr::one(), vec![(x, r(2, 1))]));
    assert_eq!(x.powi(2) * x.powi(3), x.powi(5));
    assert_eq!(x.recip() * x.powi(-2), x.powi(-3));
    assert_eq!(product(x.powi(-3)), (Expr::one(), vec![(x, r(-3, 1))]));
    // Two square roots: same sign, so x^(1/2)·x^(1/2) → x.
    assert_eq!(x.sqrt() * x.sqrt(), x);
}

#[test]
fn opposite_exponents_do_not_cancel_for_a_base_that_may_vanish() {
    let x = real("x");
    // x·x/x keeps x²·x⁻¹ (x = 0 is outside the domain of the original).
    let e = x * x / x;
    assert_ne!(e, x);
    assert_eq!(product(e), (Expr::one(), vec![(x, r(2, 1)), (x, r(-1, 1))]));
    // x/x is not 1.
    let e = x / x;
    assert_ne!(e, Expr::one());
    assert_eq!(product(e), (Expr::one(), vec![(x, r(1, 1)), (x, r(-1, 1))]));
    // The order of the operations does not matter: x⁻¹·x² is the same node.
    assert_eq!(x.recip() * x.powi(2), x * x / x);
    // Same-sign entries still merge on either side: x³·x⁻¹·x⁻¹ = x³·x⁻².
    assert_eq!(x.powi(3) / x / x, x.powi(3) * x.powi(-2));
    // Non-negative (may be zero) is not enough.
    let n = param("n", 0.5, Assumption::Nonnegative);
    assert_ne!(n / n, Expr::one());
    assert_eq!(product(n * n / n).1.len(), 2);
    // (x·y)/x keeps x·x⁻¹·y.
    let y = real("y");
    assert_eq!(
        sorted(product(x * y / x).1),
        sorted(vec![
            (x, Rational::ONE),
            (x, Rational::MINUS_ONE),
            (y, Rational::ONE)
        ])
    );
}

#[test]
fn opposite_exponents_cancel_for_a_provably_nonzero_base() {
    let p = positive("m");
    let z = param("z", -2.0, Assumption::Nonzero);
    for b in [p, z] {
        assert_eq!(b * b / b, b);
        assert_eq!(b / b, Expr::one());
        assert_eq!(b.powi(3) / b.powi(5), b.powi(-2));
    }
    let y = real("y");
    assert_eq!(p * y / p, y);
    // Provably nonzero expressions (not just parameters).
    let x = real("x");
    let one_plus_x2 = Expr::one() + x.powi(2);
    assert_eq!(one_plus_x2 / one_plus_x2, Expr::one());
    assert_eq!(x.exp() / x.exp(), Expr::one());
    assert_eq!(Expr::pi() / Expr::pi(), Expr::one());
    assert_eq!(Expr::int(3) / Expr::int(3), Expr::one());
    // ... but 1 + x is not provably nonzero.
    let one_plus_x = Expr::one() + x;
    assert_ne!(one_plus_x / one_plus_x, Expr::one());
}

// ------------------------------------------------------------------ row 5: integer powers

#[test]
fn integer_power_of_a_product_distributes() {
    let x = real("x");
    let y = real("y");
    let e = (x * y).powi(2);
    assert_eq!(e, x.powi(2) * y.powi(2));
    assert_eq!(
        sorted(product(e).1),
        sorted(vec![(x, r(2, 1)), (y, r(2, 1))])
    );
    assert_eq!((Expr::int(2) * x).powi(3), 8 * x.powi(3));
    assert_eq!((x / y).powi(-2), y.powi(2) / x.powi(2));
    assert_eq!((q(2, 3) * x).powi(-2), q(9, 4) * x.powi(-2));
}

#[test]
fn integer_power_of_a_power_multiplies_exponents() {
    let x = real("x");
    assert_eq!(x.powi(3).powi(2), x.powi(6));
    assert_eq!(x.powi(-2).powi(3), x.powi(-6));
    // Documented as "always" for integer n, also on top of a fractional power.
    assert_eq!(x.sqrt().powi(2), x);
    assert_eq!(x.sqrt().powi(3), x.pow_rational(r(3, 2)));
    assert_eq!(x.recip().powi(-1), x);
    // A sum is not a product: (x + y)² stays a power of the sum, nothing is expanded.
    let y = real("y");
    let s = x + y;
    assert_eq!(product(s.powi(2)), (Expr::one(), vec![(s, r(2, 1))]));
}

// ------------------------------------------------------------------ row 6: fractional powers

#[test]
fn square_root_of_a_square_is_abs_for_real_x() {
    let x = real("x");
    assert_eq!(x.powi(2).sqrt(), x.abs());
    assert_eq!(x.abs().view(), ExprView::Func(Func::Abs, x));
    assert_eq!(x.powi(4).pow_rational(r(1, 4)), x.abs());
    assert_eq!(x.powi(-2).sqrt(), x.abs().recip());
    // For a non-negative or positive base the abs is not needed.
    let n = param("n", 0.0, Assumption::Nonnegative);
    let p = positive("p");
    assert_eq!(n.powi(2).sqrt(), n);
    assert_eq!(p.powi(2).sqrt(), p);
}

#[test]
fn fractional_power_of_a_power_needs_a_nonnegative_base() {
    let x = real("x");
    let p = positive("p");
    // (x³)^(1/3) is not x for real x under the principal-power convention: unchanged.
    let x3 = x.powi(3);
    let e = x3.pow_rational(r(1, 3));
    assert_ne!(e, x);
    assert_eq!(product(e), (Expr::one(), vec![(x3, r(1, 3))]));
    // For a positive base the exponents multiply.
    assert_eq!(p.powi(3).pow_rational(r(1, 3)), p);
    assert_eq!(p.powi(3).sqrt(), p.pow_rational(r(3, 2)));
    assert_eq!(p.sqrt().sqrt(), p.pow_rational(r(1, 4)));
    // x^(1/2) of a real x raised to 1/2 again: base x may be negative, but x^(1/2) is
    // non-negative; the (b^e)^r rule needs b itself non-negative, so the node is kept.
    let e = x.sqrt().sqrt();
    assert_ne!(e, x.pow_rational(r(1, 4)));
}

#[test]
fn fractional_power_of_a_product_splits_only_for_nonnegative_factors() {
    let x = real("x");
    let y = real("y");
    let p = positive("p");
    let s = positive("s");
    let n = param("n", 0.0, Assumption::Nonnegative);
    // Both factors non-negative: split.
    let e = (p * s).sqrt();
    assert_eq!(e, p.sqrt() * s.sqrt());
    assert_eq!(
        sorted(product(e).1),
        sorted(vec![(p, r(1, 2)), (s, r(1, 2))])
    );
    assert_eq!((p * n).sqrt(), p.sqrt() * n.sqrt());
    // With a positive numeric coefficient: √(4ps) = 2√p√s.
    assert_eq!((Expr::int(4) * p * s).sqrt(), 2 * p.sqrt() * s.sqrt());
    // Real factors: not split.
    let xy = x * y;
    assert_eq!(product(xy.sqrt()), (Expr::one(), vec![(xy, r(1, 2))]));
    // One real factor is enough to block the split.
    let px = p * x;
    assert_eq!(product(px.sqrt()), (Expr::one(), vec![(px, r(1, 2))]));
    // A negative coefficient blocks it too.
    let m: Expr = -2 * p * s;
    assert_eq!(product(m.sqrt()), (Expr::one(), vec![(m, r(1, 2))]));
    // x²·y² is non-negative as a whole, but its bases are not: not split.
    let sq = x.powi(2) * y.powi(2);
    assert_eq!(product(sq.sqrt()), (Expr::one(), vec![(sq, r(1, 2))]));
}

// ------------------------------------------------------------------ row 7: x^0

#[test]
fn anything_to_the_zero_is_one() {
    let x = real("x");
    assert_eq!(x.powi(0), Expr::one());
    assert_eq!((x + Expr::one()).pow(Expr::zero()), Expr::one());
    assert_eq!(x.sin().pow_rational(Rational::ZERO), Expr::one());
    assert_eq!(Expr::zero().powi(0), Expr::one());
    assert_eq!((x / x).powi(0), Expr::one());
}

// ------------------------------------------------------------------ row 8: numeric folding

#[test]
fn rational_arithmetic_folds_exactly() {
    assert_eq!(Expr::int(2) * Expr::int(3), Expr::int(6));
    assert_eq!(q(1, 2) + q(1, 3), q(5, 6));
    assert_eq!(q(1, 2) - q(1, 2), Expr::zero());
    assert_eq!(q(2, 3) / q(4, 9), q(3, 2));
    assert_eq!(q(2, 3).powi(-2), q(9, 4));
    assert_eq!(Expr::int(-2).powi(3), Expr::int(-8));
    assert_eq!(Expr::rational(2, 4).unwrap(), q(1, 2));
    assert_eq!(q(5, 6).view(), ExprView::Rational(r(5, 6)));
    assert_eq!(Expr::int(7).as_rational(), Some(Rational::int(7)));
}

#[test]
fn exact_roots_fold_and_inexact_roots_stay() {
    assert_eq!(q(4, 9).sqrt(), q(2, 3));
    assert_eq!(Expr::int(8).pow_rational(r(2, 3)), Expr::int(4));
    assert_eq!(Expr::int(-8).pow_rational(r(1, 3)), Expr::int(-2));
    assert_eq!(q(27, 8).pow_rational(r(-1, 3)), q(2, 3));
    assert_eq!(Expr::int(4).pow_rational(r(-1, 2)), q(1, 2));
    assert_eq!(Expr::zero().sqrt(), Expr::zero());
    // √2 is kept exactly, as 2^(1/2), and √2·√2 = 2.
    let s2 = Expr::int(2).sqrt();
    assert_eq!(product(s2), (Expr::one(), vec![(Expr::int(2), r(1, 2))]));
    assert_eq!(s2 * s2, Expr::int(2));
    assert_eq!(s2.powi(2), Expr::int(2));
    assert_eq!(s2.powi(4), Expr::int(4));
}

#[test]
fn odd_root_of_a_negative_constant_is_real() {
    // A real odd root exists; the node must evaluate to it (not to NaN).
    let c = Expr::int(-2).pow_rational(r(1, 3));
    assert!(c.check().is_ok());
    let want = -(2f64.powf(1.0 / 3.0));
    assert!(
        (c.nominal() - want).abs() <= 4.0 * f64::EPSILON,
        "{}",
        c.nominal()
    );
    let v = eom_sym::eval_nominal::<f64>(&[c]).unwrap()[0];
    assert!((v - want).abs() <= 4.0 * f64::EPSILON, "{v}");
    assert!(c.sign().is_nonpos());
    // Squaring an odd root: ((-2)^(1/3))^2 = 2^(2/3) > 0.
    let c2 = c.powi(2);
    assert!((c2.nominal() - 2f64.powf(2.0 / 3.0)).abs() <= 4.0 * f64::EPSILON);
}

#[test]
fn functions_of_exact_constants_fold() {
    assert_eq!(Expr::zero().sin(), Expr::zero());
    assert_eq!(Expr::zero().tan(), Expr::zero());
    assert_eq!(Expr::zero().cos(), Expr::one());
    assert_eq!(Expr::zero().exp(), Expr::one());
    assert_eq!(Expr::one().ln(), Expr::zero());
    assert_eq!(q(-3, 4).abs(), q(3, 4));
    // Values that are not rational stay symbolic.
    assert_eq!(
        Expr::one().sin().view(),
        ExprView::Func(Func::Sin, Expr::one())
    );
    assert_eq!(
        Expr::int(2).ln().view(),
        ExprView::Func(Func::Ln, Expr::int(2))
    );
    assert_ne!(Expr::one().exp(), Expr::e());
}

#[test]
fn trig_of_multiples_of_pi_folds() {
    let pi = Expr::pi();
    assert_eq!(pi.view(), ExprView::Constant(Constant::Pi));
    assert_eq!(pi.sin(), Expr::zero());
    assert_eq!(pi.cos(), Expr::int(-1));
    assert_eq!((Expr::int(2) * pi).cos(), Expr::one());
    assert_eq!((Expr::int(3) * pi).cos(), Expr::int(-1));
    assert_eq!((Expr::int(-4) * pi).cos(), Expr::one());
    assert_eq!(pi.tan(), Expr::zero());
    assert_eq!((pi / Expr::int(2)).sin(), Expr::one());
    assert_eq!((pi / Expr::int(2)).cos(), Expr::zero());
    assert_eq!((Expr::int(3) * pi / Expr::int(2)).sin(), Expr::int(-1));
    assert_eq!((-pi / Expr::int(2)).sin(), Expr::int(-1));
    assert_eq!((Expr::int(5) * pi / Expr::int(2)).sin(), Expr::one());
    // π/3 has an irrational sine: not folded.
    let third = pi / 3;
    assert_eq!(
        (pi / Expr::int(3)).sin().view(),
        ExprView::Func(Func::Sin, third)
    );
}

#[test]
fn floats_contaminate() {
    let a = Expr::float(0.1).unwrap();
    assert_eq!(a.view(), ExprView::Float(0.1));
    // 0.1 + 1/2 is the float 0.6 (f64 sum), not a rational.
    assert_eq!((a + q(1, 2)).view(), ExprView::Float(0.1 + 0.5));
    assert_eq!((a * q(1, 3)).view(), ExprView::Float(0.1 * (1.0 / 3.0)));
    // Functions of floats are evaluated.
    assert_eq!(a.sin().view(), ExprView::Float(0.1f64.sin()));
    // Dyadic values and integers are exact rationals.
    assert_eq!(Expr::float(0.5).unwrap(), q(1, 2));
    assert_eq!(Expr::float(0.375).unwrap(), q(3, 8));
    assert_eq!(Expr::float(-3.0).unwrap(), Expr::int(-3));
    assert_eq!(Expr::float(1e10).unwrap(), Expr::int(10_000_000_000));
    assert_eq!(Expr::float(-0.0).unwrap(), Expr::zero());
    // Float arithmetic that lands on an integer or short dyadic value is exact again.
    assert_eq!(a * 10, Expr::one());
    assert_eq!(a - a, Expr::zero());
    // A float coefficient makes the collected coefficient a float.
    let x = real("x");
    let (c, f) = product(a * x + q(1, 2) * x);
    assert_eq!(c.view(), ExprView::Float(0.1 + 0.5));
    assert_eq!(f, vec![(x, Rational::ONE)]);
    // A float constant term of a sum.
    let (c0, _) = sum(x + a);
    assert_eq!(c0.view(), ExprView::Float(0.1));
}

// ------------------------------------------------------------------ row 9: odd/even functions

#[test]
fn odd_and_even_functions_of_a_negated_argument() {
    let x = real("x");
    let y = real("y");
    assert_eq!((-x).sin(), -x.sin());
    assert_eq!((-x).tan(), -x.tan());
    assert_eq!((-x).cos(), x.cos());
    assert_eq!((-x).abs(), x.abs());
    let xy = x * y;
    assert_eq!((Expr::int(-2) * xy).sin(), -(Expr::int(2) * xy).sin());
    assert_eq!((x * q(-1, 3)).cos(), (x / Expr::int(3)).cos());
    // The result is written with the positive argument.
    assert_eq!(
        product(-x.sin()),
        (Expr::int(-1), vec![(x.sin(), Rational::ONE)])
    );
    // A sum has no numeric coefficient: sin(y − x) is not rewritten as −sin(x − y).
    let d = y - x;
    assert_eq!(d.sin().view(), ExprView::Func(Func::Sin, d));
    assert_ne!(d.sin(), -(x - y).sin());
    // exp and ln are neither odd nor even.
    assert_eq!((-x).exp().view(), ExprView::Func(Func::Exp, -x));
}

// ------------------------------------------------------------------ row 10: abs of signed values

#[test]
fn abs_of_a_provably_signed_expression() {
    let x = real("x");
    let p = positive("p");
    let n = param("n", 0.0, Assumption::Nonnegative);
    assert_eq!(p.abs(), p);
    assert_eq!(n.abs(), n);
    assert_eq!((-p).abs(), p);
    assert_eq!(x.powi(2).abs(), x.powi(2));
    assert_eq!((-x.powi(2)).abs(), x.powi(2));
    assert_eq!(x.exp().abs(), x.exp());
    assert_eq!(Expr::pi().abs(), Expr::pi());
    let neg = Expr::int(-3) - x.powi(2);
    assert_eq!(neg.abs(), 3 + x.powi(2));
    assert_eq!((p + n).abs(), p + n);
    // Nothing known, or a sign that is not fixed: abs stays.
    assert_eq!(x.abs().view(), ExprView::Func(Func::Abs, x));
    let z = param("z", 1.0, Assumption::Nonzero);
    assert_eq!(z.abs().view(), ExprView::Func(Func::Abs, z));
    let pm1: Expr = p - 1;
    assert_eq!(pm1.abs().view(), ExprView::Func(Func::Abs, pm1));
    assert_eq!(x.sin().abs().view(), ExprView::Func(Func::Abs, x.sin()));
    // abs is idempotent because abs(x) is provably non-negative.
    assert_eq!(x.abs().abs(), x.abs());
}

// ------------------------------------------------------------------ row 11: exp/ln

#[test]
fn exp_of_ln_and_ln_of_exp() {
    let x = real("x");
    let y = real("y");
    assert_eq!(x.ln().exp(), x);
    assert_eq!(x.exp().ln(), x);
    let s = x * y + Expr::one();
    assert_eq!(s.ln().exp(), s);
    assert_eq!(s.exp().ln(), s);
    // Not a direct composition: unchanged.
    let e = (Expr::int(2) * x.ln()).exp();
    assert_eq!(e.view(), ExprView::Func(Func::Exp, 2 * x.ln()));
    let l = (x.exp() + Expr::one()).ln();
    assert_eq!(l.view(), ExprView::Func(Func::Ln, x.exp() + 1));
}

// ------------------------------------------------------------------ canonical forms

#[test]
fn sums_are_flat_and_ordered() {
    let a = real("a");
    let b = real("b");
    let c = real("c");
    assert_eq!(a + b, b + a);
    assert_eq!((a + b) + c, a + (b + c));
    assert_eq!((a + b) + c, (c + a) + b);
    assert_eq!(Expr::sum([c, b, a]), a + b + c);
    let (c0, terms) = sum(c + a + b);
    assert!(c0.is_zero());
    // Flat: three terms, unit coefficients, sorted by id.
    assert_eq!(terms.len(), 3);
    assert!(terms.windows(2).all(|w| w[0].0.id() < w[1].0.id()));
    assert!(terms.iter().all(|(_, k)| k.is_one()));
    // A term is never a number, a sum, or a product with a coefficient ≠ 1.
    let (c0, terms) = sum(2 * (a * b) + (c + 5));
    assert_eq!(c0, Expr::int(5));
    for (t, _) in &terms {
        assert!(!t.is_number());
        assert!(!matches!(t.view(), ExprView::Sum { .. }));
        if let ExprView::Product { coef, .. } = t.view() {
            assert!(coef.is_one());
        }
    }
}

#[test]
fn products_are_flat_and_ordered() {
    let a = real("a");
    let b = real("b");
    let c = real("c");
    assert_eq!(a * b, b * a);
    assert_eq!((a * b) * c, a * (b * c));
    assert_eq!(Expr::product([c, a, b]), a * b * c);
    let (k, f) = product(c * (2 * a) * b);
    assert_eq!(k, Expr::int(2));
    assert_eq!(f.len(), 3);
    assert!(f.windows(2).all(|w| w[0].0.id() < w[1].0.id()));
    // Children come before parents (ids are a topological order).
    let e = (a + b).sin() * c;
    for ch in e.children() {
        assert!(ch.id() < e.id());
    }
}

#[test]
fn fractional_powers_of_a_product_that_merge_to_an_integer_are_flattened() {
    // √(2x²) is kept as (2x²)^(1/2) for real x (the base is not split); its square must be
    // the flat product 2x², whether written a·a or a².
    let x = real("x");
    let r2 = (Expr::int(2) * x.powi(2)).sqrt();
    let (_, f) = product(r2);
    assert_eq!(f.len(), 1);
    assert!(matches!(f[0].0.view(), ExprView::Product { .. }));
    assert_eq!(r2 * r2, Expr::int(2) * x.powi(2));
    let a = x * r2;
    assert_eq!(a * a, a.powi(2));
    assert_eq!(a * a, Expr::int(2) * x.powi(4));
    // Three halves merge to 3/2: still a fractional power of the product, kept.
    let (_, f) = product(r2 * r2 * r2 / r2.powi(2) * r2.powi(2));
    assert!(
        f.iter()
            .all(|(b, e)| !matches!(b.view(), ExprView::Product { .. }) || !e.is_integer())
    );
}

#[test]
fn numeric_coefficient_distributes_over_a_sum_only() {
    let a = real("a");
    let b = real("b");
    let x = real("x");
    let s = a + b;
    assert_eq!(2 * s, 2 * a + 2 * b);
    assert_eq!(s * 2, 2 * a + 2 * b);
    assert_eq!(-s, -a - b);
    assert_eq!(s / 2, a / 2 + b / 2);
    assert_eq!(3 * (s + 1), 3 * a + 3 * b + 3);
    let (c0, terms) = sum(2 * s);
    assert!(c0.is_zero());
    assert!(terms.iter().all(|(_, k)| *k == Expr::int(2)));
    // A symbolic factor is not distributed: x·(a + b) stays a product.
    let e = x * s;
    assert_eq!(
        sorted(product(e).1),
        sorted(vec![(x, Rational::ONE), (s, Rational::ONE)])
    );
    assert_ne!(e, x * a + x * b);
    // Nor is a coefficient when the product has other factors.
    let (k, f) = product(2 * (s * x));
    assert_eq!(k, Expr::int(2));
    assert_eq!(f.len(), 2);
    // Nor a power of a sum: 2(a+b)² is a product.
    let (k, f) = product(2 * s.powi(2));
    assert_eq!(k, Expr::int(2));
    assert_eq!(f, vec![(s, r(2, 1))]);
}

#[test]
fn hash_consing_gives_equal_ids_for_equal_structure() {
    let x = real("x");
    let y = real("y");
    assert_eq!(Expr::int(5), Expr::int(5));
    assert_eq!(Expr::float(0.1).unwrap(), Expr::float(0.1).unwrap());
    assert_eq!(x.sin(), x.sin());
    assert_eq!((x * y + Expr::one()).exp(), (Expr::one() + y * x).exp());
    // Two parameters with the same name are distinct.
    let x2 = real("x");
    assert_ne!(x, x2);
    assert_ne!(x - x2, Expr::zero());
    // The nominal value is computed when the node is created.
    let p = param("p", 2.0, Assumption::Real);
    let k = param("k", 8.0, Assumption::Real);
    assert_eq!(((p * k + k * p) / (Expr::int(2) * p)).nominal(), 8.0);
}

#[test]
fn substitution_keeps_named_constants() {
    // Rebuilding through `subs` must give the same canonical node for the constants π and e.
    let x = real("x");
    let y = real("y");
    for c in [Expr::pi(), Expr::e()] {
        let e = c * x + c.sin();
        assert_eq!(e.subs(&[(x, y)]).unwrap(), c * y + c.sin());
        assert_eq!(c.subs(&[]).unwrap(), c);
    }
}

/// Folding float constants must not change a value: a rewrite whose coefficient would underflow
/// (distributing `float(1e-200)` over `m + 1e-200`, or pulling the content 1e-303 of a sum
/// into `float(1.2e-289)`) is not made, and a product of float constants that underflows is
/// an error, not a silent 0.
#[test]
fn float_folds_never_underflow_silently() {
    use eom_sym::{Scope, parse};
    let mut scope = Scope::new();
    let m = scope.declare("m", -1e-200).expect("m");
    scope.declare("x", 0.5).expect("x");
    scope.declare("d", 1.0).expect("d");
    // m + 1e-200 is exactly zero at m = −1e-200 (both are the same double only in the sum's
    // exact arithmetic; the direct value is (−1e-200 + 1e-200)·1e-200 = 0).
    let e = parse("float(1e-200)*(m+1e-200)", &scope).expect("parses");
    let direct = 1e-200 * (m.nominal() + 1e-200);
    assert_eq!(e.nominal(), direct, "{e}");
    let e = parse("float(12e-290)*x*(385^x+1e-303*d)", &scope).expect("parses");
    let direct = 12e-290 * 0.5 * (385f64.powf(0.5) + 1e-303);
    assert!(direct != 0.0);
    assert!(
        ((e.nominal() - direct) / direct).abs() < 1e-14,
        "{e}: {} vs {direct}",
        e.nominal()
    );
    let err = parse("float(1e-200)*float(1e-200)*m", &scope).expect_err("underflows");
    assert!(err.to_string().contains("underflow"), "{err}");
}
