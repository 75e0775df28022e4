//! Generated code against the interpreter and the robust path: values, validity region,
//! special values, variants (chunked, `f32`, partial evaluation) and errors.

use super::*;

#[test]
fn compiled_equals_interpreter_and_robust_path() {
    for g in all_f64() {
        let r = reference(g.model);
        assert_eq!(
            g.param_names.to_vec(),
            r.model
                .scope
                .names()
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
            "{}: parameter order",
            g.model
        );
        let ok = std::cell::Cell::new(0);
        let cases = if g.model == "chain50" { 8 } else { 32 };
        proptest!(config(cases), |(values in near_nominal(r.model.scope.nominal_values()))| {
            if compare(&g, &r, &values, 1e-12)? {
                ok.set(ok.get() + 1);
                // Invariants against the robust path (its own basis).
                let named: Vec<(&str, f64)> = g.param_names.iter().copied().zip(values.iter().copied()).collect();
                let robust = Linearizer::new(&r.model).at(&named).method(Method::Robust).run()
                    .map_err(|e| TestCaseError::fail(format!("{}: robust path: {e}", g.model)))?.state_space;
                let m = (g.abcd)(&values).expect("succeeded above");
                let ss = r.sym.state_space();
                let mat = |k: usize, rows: usize, cols: usize| DMatrix::from_column_slice(rows, cols, &m[k]);
                let (a, b) = (mat(0, ss.a.nrows(), ss.a.ncols()), mat(1, ss.b.nrows(), ss.b.ncols()));
                let (c, d) = (mat(2, ss.c.nrows(), ss.c.ncols()), mat(3, ss.d.nrows(), ss.d.ncols()));
                for s in [Complex64::new(0.3, 1.7), Complex64::new(-0.05, 11.0)] {
                    let g1 = transfer(&a, &b, &c, &d, s);
                    let g2 = transfer(&robust.a, &robust.b, &robust.c, &robust.d, s);
                    let scale = g2.iter().map(|z| z.norm()).fold(0.0, f64::max).max(1e-300);
                    let diff = (g1 - g2).iter().map(|z| z.norm()).fold(0.0, f64::max) / scale;
                    prop_assert!(diff <= 1e-8, "{}: transfer function at {s} differs from the robust path by {diff:e}", g.model);
                }
            }
        });
        assert!(
            ok.get() > 0,
            "{}: no random point inside the validity region",
            g.model
        );
    }
}

/// The fast path tests the finiteness of a few values only (those no other tested value
/// depends on through NaN- and ∞-keeping operations): a non-finite entry must still never
/// get through. Every parameter in turn takes values that make entries overflow, vanish,
/// divide by zero or turn NaN. Whenever the compiled code succeeds, every entry is finite;
/// for infinite, NaN and zero parameters it fails exactly where the interpreter (which
/// tests every entry) fails. (Huge and tiny finite values may overflow in one association
/// of the sums and not in another, so there only the first property is required.)
#[test]
fn special_values_never_slip_through_the_fast_test() {
    let exact = [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 0.0, -0.0];
    let huge = [1e300, -1e300, 1e-300, 1e155, f64::MAX];
    for g in all_f64().into_iter().chain(variants()) {
        let r = reference(g.model);
        let nominal = r.model.scope.nominal_values();
        let mut failed = 0;
        for k in 0..nominal.len() {
            for &x in exact.iter().chain(&huge) {
                let mut values = nominal.clone();
                values[k] = x;
                let got = (g.abcd)(&values).and_then(|mut m| {
                    m.extend((g.phys)(&values)?);
                    Ok(m)
                });
                let name = g.param_names[k];
                match &got {
                    Ok(m) => assert!(
                        m.iter().flatten().all(|v| v.is_finite()),
                        "{}: {name} = {x}: a non-finite entry got through",
                        g.model
                    ),
                    Err(_) => failed += 1,
                }
                if exact.iter().any(|e| e.to_bits() == x.to_bits()) {
                    let want = r.sym.evaluate(&values);
                    let same = match (&got, &want) {
                        (Ok(_), Ok(_)) => true,
                        (
                            Err(GenErr::NonFinite(..)),
                            Err(ModelError::Sym(SymError::EvalNonFinite { .. })),
                        ) => true,
                        (Err(e @ GenErr::Validity(..)), Err(w)) => {
                            sym_err(w, &g).as_ref() == Some(e)
                        }
                        _ => false,
                    };
                    assert!(
                        same,
                        "{}: {name} = {x}: generated {:?}, interpreter {:?}",
                        g.model,
                        got.as_ref().map(|_| "ok"),
                        want.as_ref().map(|_| "ok")
                    );
                }
            }
        }
        assert!(failed > 0, "{}: no special value failed", g.model);
    }
}

/// Units in the last place between `a` and `b` (of `b`'s binade).
fn ulps(a: f64, b: f64, eps: f64) -> f64 {
    (a - b).abs() / (b.abs().max(f64::MIN_POSITIVE) * eps)
}

/// The generated `sincos` (inline polynomials for |x| ≤ π/4) against the standard library,
/// on a fine grid through the polynomial range and beyond it, in both precisions.
#[test]
fn generated_sincos_is_within_an_ulp_or_two_of_the_library() {
    let n = 20_000;
    let mut worst: (f64, f64) = (0.0, 0.0);
    for k in 0..=n {
        let x = -1.2 + 2.4 * f64::from(k) / f64::from(n);
        let (s, c) = gen64::bicycle::sincos(x);
        worst.0 = worst.0.max(ulps(s, x.sin(), f64::EPSILON));
        worst.1 = worst.1.max(ulps(c, x.cos(), f64::EPSILON));
        let xf = x as f32;
        let (sf, cf) = gen32::bicycle::sincos(xf);
        assert!(
            ulps(f64::from(sf), f64::from(xf.sin()), f64::from(f32::EPSILON)) <= 2.0,
            "f32 sin at {xf}"
        );
        assert!(
            ulps(f64::from(cf), f64::from(xf.cos()), f64::from(f32::EPSILON)) <= 2.0,
            "f32 cos at {xf}"
        );
    }
    assert!(
        worst.0 <= 2.0 && worst.1 <= 2.0,
        "sin, cos worst ulps {worst:?}"
    );
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (s, c) = gen64::bicycle::sincos(x);
        assert!(s.is_nan() && c.is_nan(), "sincos({x})");
    }
    let (s, c) = gen64::bicycle::sincos(0.0);
    assert_eq!((s, c), (0.0, 1.0));
}

#[test]
fn variants_equal_interpreter() {
    for g in variants() {
        let r = reference(g.model);
        proptest!(config(16), |(values in near_nominal(r.model.scope.nominal_values()))| {
            compare(&g, &r, &values, 1e-11)?;
        });
    }
}

#[test]
fn chunked_code_computes_the_same_bits() {
    let (whole, chunked) = (
        generated!("bicycle", gen64::bicycle, f64),
        generated!("bicycle", gen64::bicycle_chunked, f64),
    );
    let (cw, cc) = (
        generated!("chain50", gen64::chain50, f64),
        generated!("chain50", gen64::chain50_chunked, f64),
    );
    const {
        assert!(
            gen64::bicycle_chunked::WORK_LEN > 0 && gen64::chain50_chunked::WORK_LEN > 0,
            "chunking not exercised"
        )
    };
    for (x, y) in [(&whole, &chunked), (&cw, &cc)] {
        let r = reference(x.model);
        proptest!(config(16), |(values in near_nominal(r.model.scope.nominal_values()))| {
            prop_assert_eq!((x.abcd)(&values), (y.abcd)(&values));
            prop_assert_eq!((x.phys)(&values), (y.phys)(&values));
        });
    }
}

#[test]
fn f32_code_is_close_to_f64() {
    for g in all_f32() {
        let r = reference(g.model);
        // Round the point to f32 first, so both sides see the same parameters.
        proptest!(config(16), |(values in near_nominal(r.model.scope.nominal_values()))| {
            let values: Vec<f64> = values.iter().map(|&x| x as f32 as f64).collect();
            if let (Ok(got), Ok(want)) = ((g.abcd)(&values), r.sym.evaluate(&values)) {
                let want = to_vecs(&want);
                for k in 0..4 {
                    let d = rel_diff(&got[k], &want[k]);
                    prop_assert!(d <= 2e-4, "{} (f32): matrix {k} differs by {d:e}", g.model);
                }
            }
        });
    }
}

#[test]
fn partial_evaluation_keeps_only_the_speed() {
    use gen64::bicycle_speed as g;
    assert_eq!(g::PARAM_NAMES, ["v"]);
    let r = reference("bicycle");
    let nominal = r.model.scope.nominal_values();
    let iv = r
        .model
        .scope
        .names()
        .iter()
        .position(|n| n == "v")
        .expect("v");
    for v in [0.5, 2.0, 4.3, 6.0, 10.0] {
        let mut values = nominal.clone();
        values[iv] = v;
        let want = r.sym.evaluate(&values).expect("valid");
        let (mut a, mut b, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::WORK_LEN]);
        g::eval_ab(&[v], &mut a, &mut b, &mut w).expect("valid");
        assert!(
            rel_diff(&a, want.a.as_slice()) <= 1e-12 && rel_diff(&b, want.b.as_slice()) <= 1e-12,
            "v = {v}"
        );
    }
}

#[test]
fn outside_the_validity_region_both_refuse_with_the_same_check() {
    let gens = all_f64();
    let find = |m: &str| gens.iter().find(|g| g.model == m).expect("generated");
    // Bicycle: a vertical steer axis (λ = π/2) breaks the pivot on cos λ.
    // Shimmy: I + m l² x² = 0 breaks the reduced-mass pivot.
    // Chain: zero mass breaks the reduced-mass pivots.
    type Case<'a> = (&'a str, &'a [(&'a str, f64)], &'a str);
    let cases: [Case; 4] = [
        (
            "bicycle",
            &[("lambda", std::f64::consts::FRAC_PI_2)],
            "steer hinge",
        ),
        ("shimmy", &[("I", -5.0 * 0.25)], "reduced mass pivot"),
        ("chain3", &[("m", 0.0)], "reduced mass pivot"),
        ("smd", &[("m", 1e-300 * 1e-300)], "reduced mass pivot"),
    ];
    for (model, at, what) in cases {
        let g = find(model);
        let r = reference(model);
        let values = r.model.scope.values_with(at).expect("values");
        let e = r
            .sym
            .evaluate(&values)
            .expect_err("the interpreter refuses");
        assert!(
            matches!(e, ModelError::PivotBreakdown { .. }),
            "{model}: {e}"
        );
        // The generated code refuses with the same check, and leaves the outputs untouched.
        let got = (g.abcd)(&values).expect_err("the generated code refuses");
        assert_eq!(Some(got.clone()), sym_err(&e, g), "{model}");
        match got {
            GenErr::Validity(_, w) => assert!(w.contains(what), "{model}: {w}"),
            other => panic!("{model}: {other:?}"),
        }
        assert_eq!((g.ab)(&values).expect_err("refuses"), got);
        assert_eq!((g.cd)(&values).expect_err("refuses"), got);
        assert_eq!((g.phys)(&values).expect_err("refuses"), got);
    }
    // Untouched outputs, on the real API.
    use gen64::bicycle as b;
    let mut p = b::Params::NOMINAL;
    p.lambda = std::f64::consts::FRAC_PI_2;
    let (mut a, mut bb, mut c, mut d, mut w) = (
        [7.25; b::A_LEN],
        [7.25; b::B_LEN],
        [7.25; b::C_LEN],
        [7.25; b::D_LEN],
        [0.0; b::WORK_LEN],
    );
    let e =
        b::eval_abcd(&p.to_array(), &mut a, &mut bb, &mut c, &mut d, &mut w).expect_err("outside");
    assert!(e.to_string().contains("outside the validity region"), "{e}");
    assert!(a.iter().chain(&bb).chain(&c).chain(&d).all(|&x| x == 7.25));
    // The check by index, its description through `what` and in the message.
    let b::Error::Validity { check } = e else {
        panic!("{e:?}")
    };
    let what = e.what().expect("a validity error has a description");
    assert_eq!(what, b::CHECKS[check as usize]);
    assert_eq!(
        e.to_string(),
        format!("outside the validity region: check {check} fails ({what})")
    );
}

/// The generated `Error` is compact: `Result<(), Error>` fits in one register, which the Rust
/// ABI returns it in (a larger one goes through a hidden pointer, and the fast path of a small
/// function then moves every argument to call its slow path).
#[test]
fn generated_error_is_compact() {
    use std::mem::size_of;
    let sizes = [
        ("smd", size_of::<Result<(), gen64::smd::Error>>()),
        ("shimmy", size_of::<Result<(), gen64::shimmy::Error>>()),
        ("bicycle", size_of::<Result<(), gen64::bicycle::Error>>()),
        (
            "bicycle f32",
            size_of::<Result<(), gen32::bicycle::Error>>(),
        ),
    ];
    println!("size_of::<Result<(), Error>>(): {sizes:?}");
    for (model, size) in sizes {
        assert!(size <= 8, "{model}: Result<(), Error> is {size} bytes");
    }
    assert_eq!(size_of::<gen64::shimmy::Matrix>(), 1);
    let e = gen64::smd::Error::NonFinite {
        matrix: gen64::smd::Matrix::A,
        row: 1,
        col: 0,
    };
    assert_eq!(e.what(), None);
    assert_eq!(e.to_string(), "entry (1, 0) of A is not finite");
}

#[test]
fn non_finite_entries_are_errors_but_overflowing_sums_are_not() {
    use gen64::smd as g;
    let r = reference("smd");
    // k = ∞: A(1, 0) = −k/m is infinite; the interpreter refuses too.
    let p = [1.0, f64::INFINITY, 0.1];
    assert!(matches!(
        r.sym.evaluate(&p),
        Err(ModelError::Sym(SymError::EvalNonFinite { .. }))
    ));
    let (mut a, mut b, mut c, mut d, mut w) = (
        [0.0; g::A_LEN],
        [0.0; g::B_LEN],
        [0.0; g::C_LEN],
        [0.0; g::D_LEN],
        [0.0; g::WORK_LEN],
    );
    assert_eq!(
        g::eval_abcd(&p, &mut a, &mut b, &mut c, &mut d, &mut w),
        Err(g::Error::NonFinite {
            matrix: g::Matrix::A,
            row: 1,
            col: 0
        })
    );
    // NaN stiffness, same.
    assert!(g::eval_ab(&[1.0, f64::NAN, 0.1], &mut a, &mut b, &mut w).is_err());
    // Entries near the largest float: their sum overflows, each entry is finite.
    let p = [1.0, 1.5e308, 1.5e308];
    g::eval_abcd(&p, &mut a, &mut b, &mut c, &mut d, &mut w).expect("finite entries");
    let want = r.sym.evaluate(&p).expect("finite");
    assert_eq!(a.as_slice(), want.a.as_slice());
}

/// The models with wings at 1 000 random points near nominal each: the `f64` code equals the
/// interpreter entry by entry (1e-12 of each matrix's largest entry), the `no_std` `f32` code
/// (elementary functions from `libm`) to single-precision rounding (2e-4, as for every model).
#[test]
fn wing_models_generated_code_equals_the_interpreter_at_1000_points() {
    let pairs = [
        (
            generated!("smd_wing", gen64::smd_wing, f64),
            generated!("smd_wing", gen32::smd_wing, f32),
        ),
        (
            generated!("shimmy_wing", gen64::shimmy_wing, f64),
            generated!("shimmy_wing", gen32::shimmy_wing, f32),
        ),
    ];
    for (g64, g32) in pairs {
        let r = reference(g64.model);
        let compared = std::cell::Cell::new(0);
        proptest!(config(1000), |(values in near_nominal(r.model.scope.nominal_values()))| {
            prop_assert!(compare(&g64, &r, &values, 1e-12)?, "{}: outside the validity region", g64.model);
            let values: Vec<f64> = values.iter().map(|&x| x as f32 as f64).collect();
            let got = (g32.abcd)(&values).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let want = to_vecs(&r.sym.evaluate(&values).map_err(|e| TestCaseError::fail(e.to_string()))?);
            for k in 0..4 {
                let d = rel_diff(&got[k], &want[k]);
                prop_assert!(d <= 2e-4, "{} (f32): matrix {k} differs by {d:e}", g32.model);
            }
            compared.set(compared.get() + 1);
        });
        assert_eq!(compared.get(), 1000, "{}", g64.model);
    }
}
