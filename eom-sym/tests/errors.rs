//! Bad input gets a typed error naming what is at fault, never a panic and never a silent NaN.
//!
//! Every test checks the variant *and* that the message names the thing at fault (the
//! parameter, the output, the offending operation).

use eom_sym::{
    Assumption, Expr, ParamInfo, Rational, SymError, Tape, TapeWorkspace, eval_generic,
    eval_nominal,
};

fn param(name: &str, nominal: f64, assume: Assumption) -> Result<Expr, SymError> {
    Expr::new_param(ParamInfo {
        name: name.into(),
        nominal,
        unit: None,
        description: None,
        assume,
    })
}

fn real(name: &str, nominal: f64) -> Expr {
    param(name, nominal, Assumption::Real).unwrap()
}

/// The error inside an `Invalid` wrapper (tapes and evaluators wrap the node's error).
fn inner(e: SymError) -> SymError {
    match e {
        SymError::Invalid(b) => *b,
        other => panic!("expected SymError::Invalid, got {other:?}"),
    }
}

// ------------------------------------------------------------------ division by zero

#[test]
fn division_by_a_structural_zero() {
    let x = real("x", 1.0);
    let y = real("y", 2.0);
    for divisor in [
        Expr::zero(),
        y - y,
        Expr::int(0) * x,
        x.sin() * Expr::zero(),
    ] {
        let e = x.try_div(divisor).unwrap_err();
        assert!(matches!(e, SymError::DivisionByZero { .. }), "{e:?}");
        let msg = e.to_string();
        assert!(
            msg.contains("division by zero") && msg.contains("structural zero"),
            "{msg}"
        );
    }
    // A number divided by zero, and a negative power of zero.
    let e = Expr::one().try_div(Expr::zero()).unwrap_err();
    assert!(matches!(e, SymError::DivisionByZero { .. }));
    let e = Expr::zero().powi(-2).check().unwrap_err();
    assert!(matches!(e, SymError::DivisionByZero { .. }));
    assert!(e.to_string().contains("division by zero"), "{e}");
    // A float zero (from float arithmetic) is a zero too.
    let z = Expr::float(0.1).unwrap() - Expr::float(0.1).unwrap();
    let e = x.try_div(z).unwrap_err();
    assert!(matches!(e, SymError::DivisionByZero { .. }), "{e:?}");
    // The rational constructor names the fraction.
    let e = Expr::rational(3, 0).unwrap_err();
    assert!(matches!(e, SymError::DivisionByZero { .. }));
    assert!(e.to_string().contains("3/0"), "{e}");
    // Dividing by something that is merely *not known* to be nonzero is fine.
    assert!(x.try_div(y - 2).is_ok());
}

#[test]
fn invalid_nodes_absorb_every_operation() {
    let x = real("x", 1.0);
    let y = real("y", 2.0);
    let bad = x / Expr::zero();
    let check = |e: Expr, what: &str| {
        let err = e.check().expect_err(what);
        assert!(
            matches!(err, SymError::DivisionByZero { .. }),
            "{what}: {err:?}"
        );
        assert!(e.is_invalid(), "{what}");
    };
    check(bad, "x/0");
    check(bad + y, "sum");
    check(Expr::sum([y, x, bad]), "n-ary sum");
    check(bad * y, "product");
    check(Expr::zero() * bad, "0·invalid (the zero does not win)");
    check(bad - bad, "invalid − invalid");
    check(y / bad, "division by an invalid node");
    check(bad.powi(2), "integer power");
    check(bad.powi(0), "zeroth power");
    check(bad.powi(1), "first power");
    check(bad.sqrt(), "square root");
    check(bad.recip(), "reciprocal");
    check(bad.pow(y), "general power (base)");
    check(y.pow(bad), "general power (exponent)");
    check(bad.sin(), "sin");
    check(bad.abs(), "abs");
    check(bad.ln().exp(), "exp(ln)");
    check(bad.atan2(y), "atan2 (y)");
    check(y.atan2(bad), "atan2 (x)");
    check(
        ((bad + y).sin() * Expr::int(3) + x).powi(2).sqrt(),
        "deeply nested",
    );
    // Derivatives, substitution and evaluation report the error instead of panicking.
    let deep = (y / bad).powi(2) + x;
    assert!(matches!(deep.diff(x), Err(SymError::DivisionByZero { .. })));
    assert!(matches!(
        deep.subs(&[(x, y)]).map_err(inner),
        Err(SymError::DivisionByZero { .. })
    ));
    let e = eval_generic::<f64>(&[deep], |_| Some(1.0)).unwrap_err();
    assert!(matches!(inner(e), SymError::DivisionByZero { .. }));
    let e = eval_nominal::<eom_sym::Dd>(&[y, deep]).unwrap_err();
    assert!(matches!(inner(e), SymError::DivisionByZero { .. }));
    let e = Tape::new(&[y, deep], &[x, y]).unwrap_err();
    assert!(matches!(inner(e.clone()), SymError::DivisionByZero { .. }));
    assert!(
        e.to_string()
            .contains("invalid expression: division by zero"),
        "{e}"
    );
}

// ------------------------------------------------------------------ values that are not real

#[test]
fn log_of_zero_and_of_negative_constants() {
    let x = real("x", 1.0);
    for (arg, name) in [
        (Expr::zero(), "ln(0)"),
        (x - x, "ln(0)"),
        (Expr::int(-2), "ln(-2)"),
    ] {
        let e = arg.ln().check().unwrap_err();
        assert!(matches!(e, SymError::NotReal { .. }), "{e:?}");
        assert!(e.to_string().contains(name), "{e}");
    }
    let e = Expr::rational(-1, 3).unwrap().ln().check().unwrap_err();
    assert!(e.to_string().contains("ln(-1/3)"), "{e}");
    let e = Expr::float(-0.3).unwrap().ln().check().unwrap_err();
    assert!(matches!(e, SymError::NotReal { .. }), "{e:?}");
    assert!(e.to_string().contains("ln(-0.3)"), "{e}");
    // ln of a parameter is fine (defined where x > 0).
    assert!(x.ln().check().is_ok());
}

#[test]
fn even_root_of_a_negative_constant() {
    let e = Expr::int(-4).sqrt().check().unwrap_err();
    assert!(matches!(e, SymError::NotReal { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("(-4)") && msg.contains("even root"), "{msg}");
    let e = Expr::int(-2)
        .pow_rational(Rational::new(3, 4).unwrap())
        .check()
        .unwrap_err();
    assert!(matches!(e, SymError::NotReal { .. }));
    assert!(e.to_string().contains("(-2) ^ (3/4)"), "{e}");
    let e = Expr::float(-0.3).unwrap().sqrt().check().unwrap_err();
    assert!(matches!(e, SymError::NotReal { .. }), "{e:?}");
    assert!(e.to_string().contains("-0.3"), "{e}");
    // Odd roots of negative constants are real: no error.
    assert_eq!(
        Expr::int(-8).pow_rational(Rational::new(1, 3).unwrap()),
        Expr::int(-2)
    );
    assert!(
        Expr::float(-0.3)
            .unwrap()
            .pow_rational(Rational::new(1, 3).unwrap())
            .check()
            .is_ok()
    );
    // Integer powers of negative constants are fine.
    assert_eq!(Expr::int(-2).powi(-2), Expr::rational(1, 4).unwrap());
}

// ------------------------------------------------------------------ rational overflow

#[test]
fn rational_overflow_is_an_error_not_a_wrap() {
    let e = Expr::int(3).powi(1_000_000_000).check().unwrap_err();
    assert_eq!(e, SymError::RationalOverflow);
    assert!(
        e.to_string()
            .contains(&format!("{} bits", eom_sym::rational::MAX_BITS)),
        "{e}"
    );
    // Products and sums past the limit: 2^3000·2^3000 needs 6001 bits; 2^4095 + 2^4095 = 2^4096
    // needs 4097 bits, one more than MAX_BITS = 4096.
    let big = Expr::int(2).powi(3000);
    assert!(
        big.check().is_ok(),
        "2^3000 has 3001 bits and is representable"
    );
    assert_eq!((big * big).check().unwrap_err(), SymError::RationalOverflow);
    let b4095 = Expr::int(2).powi(4095);
    assert!(b4095.check().is_ok());
    assert_eq!(
        (b4095 + b4095).check().unwrap_err(),
        SymError::RationalOverflow
    );
    // Also through a symbolic coefficient: 2^4095·x + 2^4095·x.
    let x = real("x", 1.0);
    assert_eq!(
        (b4095 * x + b4095 * x).check().unwrap_err(),
        SymError::RationalOverflow
    );
    // Huge exponents on a symbol are fine (the exponent is a big rational, not a power).
    assert!(x.powi(i64::MAX).check().is_ok());
    assert!((x.powi(i64::MAX) * x).check().is_ok());
}

#[test]
fn big_rationals_promote_without_error() {
    let m = Expr::int(i64::MAX);
    let s = m + m;
    assert!(s.check().is_ok());
    let (n, d) = s.as_rational().unwrap().to_big_parts();
    assert_eq!(n.to_string(), "18446744073709551614");
    assert_eq!(d.to_string(), "1");
    // And back down: (m + m) − m = m, the small representation (same node).
    assert_eq!(s - m, m);
    // 2^3000 computed two ways is one node (promotion is exact and canonical).
    assert_eq!(Expr::int(2).powi(3000), Expr::int(2).powi(1000).powi(3));
    assert_eq!(
        Expr::int(2).powi(4000) + Expr::int(2).powi(4000),
        Expr::int(2).powi(4001)
    );
    // (2^100 + 1)/2^100 evaluates close to 1 (conversion of big parts).
    let p = Expr::int(2).powi(100);
    let v = ((p + Expr::one()) / p).as_f64().unwrap();
    assert_eq!(v, 1.0);
    let v = eval_nominal::<eom_sym::Dd>(&[(p + 1) / p]).unwrap()[0];
    assert!(
        ((v - eom_sym::Dd::ONE).to_f64() - 2f64.powi(-100)).abs() < 1e-45,
        "{v}"
    );
}

#[test]
fn big_rationals_convert_to_double_double_accurately() {
    use eom_sym::Dd;
    let rel = |a: Dd, b: Dd| ((a - b) / b).to_f64().abs();
    let dd = |e: Expr| eval_nominal::<Dd>(&[e]).unwrap()[0];
    // An integer above 2^127: 134^18 (compared with repeated double-double multiplication).
    let want = Dd::from_f64(134.0).powi(18);
    assert!(
        rel(dd(Expr::int(134).powi(18)), want) < 1e-30,
        "{}",
        dd(Expr::int(134).powi(18))
    );
    assert!(rel(dd(Expr::int(-134).powi(17)), -Dd::from_f64(134.0).powi(17)) < 1e-30);
    // Parts beyond the f64 range, moderate quotient: (2/3)^1000 ≈ 8.1e-177 and
    // (3^700 + 1)/3^700 = 1 + 3^-700 (= 1 in double-double: 3^-700 underflows).
    let want = (Dd::from_f64(2.0) / Dd::from_f64(3.0)).powi(1000);
    let got = dd(Expr::rational(2, 3).unwrap().powi(1000));
    assert!(rel(got, want) < 1e-28, "{got} vs {want}");
    let t = Expr::int(3).powi(700);
    let got = dd((t + Expr::one()) / t);
    assert_eq!(got, Dd::ONE);
    assert!(Expr::rational(2, 3).unwrap().powi(1000).nominal() > 0.0);
}

// ------------------------------------------------------------------ floats

#[test]
fn non_finite_floats_are_refused() {
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = Expr::float(x).unwrap_err();
        assert!(matches!(e, SymError::NonFinite { .. }), "{e:?}");
        assert!(e.to_string().contains(&format!("the constant {x}")), "{e}");
    }
    // Float arithmetic that overflows gives an invalid node, not an infinity.
    let big = Expr::float(1.5e300).unwrap();
    let e = (big * big).check().unwrap_err();
    assert!(matches!(e, SymError::NonFinite { .. }), "{e:?}");
    assert!(e.to_string().contains("floating-point constant"), "{e}");
    let e = (Expr::float(0.1).unwrap() * Expr::int(2).powi(4000))
        .check()
        .unwrap_err();
    assert!(matches!(e, SymError::NonFinite { .. }), "{e:?}");
    let e = Expr::float(800.1).unwrap().exp().check().unwrap_err();
    assert!(e.to_string().contains("exp(800.1)"), "{e}");
    // The Scalar conversion never panics: a non-finite datum becomes an invalid node.
    let n: Expr = <Expr as eom_sym::Scalar>::from_f64(f64::NAN);
    assert!(matches!(n.check(), Err(SymError::NonFinite { .. })));
    // Substituting a non-finite value is refused, naming it.
    let x = real("x", 1.0);
    let e = x.sin().subs_values(&[(x, f64::INFINITY)]).unwrap_err();
    assert!(e.to_string().contains("inf"), "{e}");
}

// ------------------------------------------------------------------ parameters

#[test]
fn bad_parameter_names() {
    for name in [
        "", "1x", "a b", "x-y", "x.y", "pi", "e", "sin", "sqrt", "atan2",
    ] {
        let e = param(name, 1.0, Assumption::Real).unwrap_err();
        match &e {
            SymError::BadParameter { name: n, .. } => assert_eq!(n, name),
            other => panic!("{name:?}: expected BadParameter, got {other:?}"),
        }
        assert!(
            e.to_string().contains(&format!("parameter `{name}`")),
            "{e}"
        );
    }
    // Accepted: letters (any script), digits after the first, underscores.
    for name in ["x", "_x1", "IBxx", "δ", "m_2"] {
        assert!(param(name, 1.0, Assumption::Real).is_ok(), "{name}");
    }
}

#[test]
fn bad_nominal_values_and_contradicting_assumptions() {
    for v in [f64::NAN, f64::INFINITY] {
        let e = param("k", v, Assumption::Real).unwrap_err();
        assert!(
            matches!(&e, SymError::BadParameter { name, .. } if name == "k"),
            "{e:?}"
        );
        assert!(e.to_string().contains("parameter `k`") && e.to_string().contains("not finite"));
    }
    for (v, a) in [
        (0.0, Assumption::Positive),
        (-1.0, Assumption::Positive),
        (0.0, Assumption::Nonzero),
        (-0.5, Assumption::Nonnegative),
    ] {
        let e = param("m", v, a).unwrap_err();
        assert!(
            matches!(&e, SymError::BadParameter { name, .. } if name == "m"),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("parameter `m`") && msg.contains(&format!("{a:?}")),
            "{msg}"
        );
    }
    // The boundary cases that are allowed.
    assert!(param("n", 0.0, Assumption::Nonnegative).is_ok());
    assert!(param("z", -3.0, Assumption::Nonzero).is_ok());
}

#[test]
fn derivative_and_substitution_need_parameters() {
    let x = real("x", 1.0);
    let e = x.sin().diff(x + 1).unwrap_err();
    assert!(matches!(e, SymError::BadParameter { .. }), "{e:?}");
    assert!(e.to_string().contains("x + 1"), "{e}");
    let e = x.sin().subs(&[(x.sin(), x)]).unwrap_err();
    assert!(matches!(e, SymError::BadParameter { .. }), "{e:?}");
    assert!(e.to_string().contains("sin(x)"), "{e}");
}

// ------------------------------------------------------------------ tapes and evaluation

#[test]
fn tape_with_a_missing_parameter_names_it() {
    let x = real("x", 1.0);
    let y = real("y", 2.0);
    let zeta = real("zeta", 0.1);
    let e = Tape::new(&[x + y * zeta.sin()], &[x, y]).unwrap_err();
    assert_eq!(
        e,
        SymError::MissingParameter {
            name: "zeta".into()
        }
    );
    assert!(e.to_string().contains("`zeta`"), "{e}");
    // A non-parameter in the parameter list is named by position.
    let e = Tape::new(&[x], &[x, y * 2]).unwrap_err();
    assert!(matches!(e, SymError::Dimension(_)), "{e:?}");
    assert!(e.to_string().contains("tape parameter 1"), "{e}");
}

#[test]
fn tape_eval_with_wrong_lengths() {
    let x = real("x", 1.0);
    let y = real("y", 2.0);
    let t = Tape::new(&[x * y, x + y], &[x, y]).unwrap();
    let mut ws = TapeWorkspace::default();
    let mut out = [0.0; 2];
    let e = t.eval(&[1.0], &mut out, &mut ws).unwrap_err();
    assert!(matches!(e, SymError::Dimension(_)), "{e:?}");
    let msg = e.to_string();
    assert!(
        msg.contains("1 parameter values given") && msg.contains("expects 2 (x, y)"),
        "{msg}"
    );
    let e = t.eval(&[1.0, 2.0], &mut [0.0; 3], &mut ws).unwrap_err();
    assert!(
        e.to_string().contains("output buffer 3 (expected 2)"),
        "{e}"
    );
    let mut short = vec![0.0; t.work_len() - 1];
    let e = t.eval_into(&[1.0, 2.0], &mut out, &mut short).unwrap_err();
    assert!(
        e.to_string()
            .contains(&format!("work buffer {}", t.work_len() - 1)),
        "{e}"
    );
    let e = t
        .eval_batch(&[1.0, 2.0, 3.0], &mut [0.0; 2], &mut ws)
        .unwrap_err();
    assert!(matches!(e, SymError::Dimension(_)), "{e:?}");
    assert!(e.to_string().contains("3 values"), "{e}");
    // And with the right lengths it works (the error was about the lengths).
    t.eval(&[3.0, 4.0], &mut out, &mut ws).unwrap();
    assert_eq!(out, [12.0, 7.0]);
}

#[test]
fn tape_non_finite_output_names_the_output() {
    let x = real("x", 1.0);
    let t = Tape::new(&[x + 1, x.ln(), x.recip()], &[x]).unwrap();
    let mut ws = TapeWorkspace::default();
    let mut out = [0.0; 3];
    // ln(−1) = NaN: output 1.
    let e = t.eval(&[-1.0], &mut out, &mut ws).unwrap_err();
    match &e {
        SymError::EvalNonFinite { what, value } => {
            assert_eq!(what, "output 1");
            assert!(value.is_nan());
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("output 1"), "{e}");
    // x = 0: ln(0) = −inf is output 1 (the first), 1/0 = inf would be output 2.
    let e = t.eval_vec(&[0.0]).unwrap_err();
    assert_eq!(
        e,
        SymError::EvalNonFinite {
            what: "output 1".into(),
            value: f64::NEG_INFINITY
        }
    );
    let t2 = Tape::new(&[x + 1, x.recip()], &[x]).unwrap();
    let e = t2.eval_vec(&[0.0]).unwrap_err();
    assert_eq!(
        e,
        SymError::EvalNonFinite {
            what: "output 1".into(),
            value: f64::INFINITY
        }
    );
    // In a batch, the point is named too: a small batch (point by point) and a large one
    // (evaluated in chunks), where the first bad point is 13 although 17 is bad too.
    let mut out = [0.0; 6];
    let e = t.eval_batch(&[2.0, -3.0], &mut out, &mut ws).unwrap_err();
    assert!(e.to_string().contains("output 1 at point 1"), "{e}");
    let pts: Vec<f64> = (0..40)
        .map(|k| {
            if k == 13 || k == 17 {
                -1.0
            } else {
                1.0 + k as f64
            }
        })
        .collect();
    let mut out = vec![0.0; 3 * pts.len()];
    let e = t.eval_batch(&pts, &mut out, &mut ws).unwrap_err();
    match e {
        SymError::EvalNonFinite { what, value } => {
            assert_eq!(what, "output 1 at point 13");
            assert!(value.is_nan());
        }
        other => panic!("{other:?}"),
    }
    let pts: Vec<f64> = (0..40).map(|k| 1.0 + k as f64).collect();
    t.eval_batch(&pts, &mut out, &mut ws).unwrap();
    assert_eq!(out[3 * 39..], [41.0, 40f64.ln(), 1.0 / 40.0]);
    // The kernel itself does not check (documented), but does not panic either.
    let mut work = vec![0.0; t.work_len()];
    let mut out = [0.0; 3];
    t.eval_into(&[-1.0], &mut out, &mut work).unwrap();
    assert!(out[1].is_nan());
}

#[test]
fn eval_generic_with_a_missing_parameter_names_it() {
    let x = real("x", 1.0);
    let damping = real("damping", 0.3);
    let e = (x * damping.exp()).sin();
    let (ix, _) = (x.param_index().unwrap(), damping.param_index().unwrap());
    let err = eval_generic::<f64>(&[e], |i| (i == ix).then_some(2.0)).unwrap_err();
    assert_eq!(
        err,
        SymError::MissingParameter {
            name: "damping".into()
        }
    );
    assert!(err.to_string().contains("`damping`"), "{err}");
    let err = eval_generic::<eom_sym::Dd>(&[x, e], |i| (i == ix).then_some(eom_sym::Dd::ONE));
    assert!(matches!(err, Err(SymError::MissingParameter { name }) if name == "damping"));
}
