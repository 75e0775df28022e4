//! Generated code (eom-codegen, compiled by `build.rs` for every built-in model) against the
//! tape interpreter (`SymbolicStateSpace::evaluate`, entry by entry) and against the robust
//! SVD path (a different basis: transfer functions at a few points), at random parameter points
//! near nominal; the validity region and non-finite results reported as errors, the same way
//! the interpreter reports them; sparse outputs; determinism; one formatting snapshot; and the
//! rounding error of the generated code against a double-double evaluation of the same
//! expressions, in units of their running error bound.

use eom_model::ModelError;
use eom_model::{Linearizer, Method, SymbolicStateSpace};
use eom_num::StateSpace;
use eom_sym::SymError;
use nalgebra::DMatrix;
use num_complex::Complex64;
use proptest::prelude::*;

include!(concat!(env!("OUT_DIR"), "/generated.rs"));

/// A generated error in a common form.
#[derive(Clone, Debug, PartialEq)]
enum GenErr {
    Validity(usize, &'static str),
    NonFinite(String, usize, usize),
}

type Eval = fn(&[f64]) -> Result<Vec<Vec<f64>>, GenErr>;

/// A value no entry takes, for arrays whose untouched entries must be seen.
const SENTINEL: f64 = -3.5;

/// One generated module behind a uniform interface (`f64` in and out).
struct Gen {
    model: &'static str,
    abcd: Eval,
    /// `eval_abcd_varying`, `eval_ab_varying`, `eval_cd_varying`, `eval_phys_varying` (the
    /// order of [`KERNELS`]) into arrays filled with [`SENTINEL`].
    varying: [Eval; 4],
    /// `write_abcd_constants`… into arrays filled with [`SENTINEL`].
    constants: [fn() -> Vec<Vec<f64>>; 4],
    /// `StateSpace::new()`, then `evaluate`.
    state_space: Eval,
    ab: Eval,
    cd: Eval,
    phys: Eval,
    nonzeros: [&'static [(usize, usize)]; 5],
    checks: &'static [&'static str],
    param_names: &'static [&'static str],
}

macro_rules! generated {
    ($model:expr, $m:path, $ty:ty) => {{
        use $m as g;
        fn conv(e: g::Error) -> GenErr {
            match e {
                g::Error::Validity { check } => {
                    GenErr::Validity(check as usize, e.what().expect("a check's description"))
                }
                g::Error::NonFinite { matrix, row, col } => {
                    GenErr::NonFinite(format!("{matrix:?}"), row as usize, col as usize)
                }
            }
        }
        fn params(p: &[f64]) -> [$ty; g::N_PARAMS] {
            core::array::from_fn(|k| p[k] as $ty)
        }
        fn back<const N: usize>(x: &[$ty; N]) -> Vec<f64> {
            x.iter().map(|&v| v as f64).collect()
        }
        Gen {
            model: $model,
            abcd: |p| {
                let (mut a, mut b, mut c, mut d, mut w) = (
                    [0.0; g::A_LEN],
                    [0.0; g::B_LEN],
                    [0.0; g::C_LEN],
                    [0.0; g::D_LEN],
                    [0.0; g::WORK_LEN],
                );
                g::eval_abcd(&params(p), &mut a, &mut b, &mut c, &mut d, &mut w).map_err(conv)?;
                Ok(vec![back(&a), back(&b), back(&c), back(&d)])
            },
            varying: [
                |p| {
                    let s = SENTINEL as $ty;
                    let (mut a, mut b, mut c, mut d, mut w) = (
                        [s; g::A_LEN],
                        [s; g::B_LEN],
                        [s; g::C_LEN],
                        [s; g::D_LEN],
                        [0.0; g::WORK_LEN],
                    );
                    g::eval_abcd_varying(&params(p), &mut a, &mut b, &mut c, &mut d, &mut w)
                        .map_err(conv)?;
                    Ok(vec![back(&a), back(&b), back(&c), back(&d)])
                },
                |p| {
                    let s = SENTINEL as $ty;
                    let (mut a, mut b, mut w) = ([s; g::A_LEN], [s; g::B_LEN], [0.0; g::WORK_LEN]);
                    g::eval_ab_varying(&params(p), &mut a, &mut b, &mut w).map_err(conv)?;
                    Ok(vec![back(&a), back(&b)])
                },
                |p| {
                    let s = SENTINEL as $ty;
                    let (mut c, mut d, mut w) = ([s; g::C_LEN], [s; g::D_LEN], [0.0; g::WORK_LEN]);
                    g::eval_cd_varying(&params(p), &mut c, &mut d, &mut w).map_err(conv)?;
                    Ok(vec![back(&c), back(&d)])
                },
                |p| {
                    let s = SENTINEL as $ty;
                    let (mut q, mut w) = ([s; g::PHYS_LEN], [0.0; g::WORK_LEN]);
                    g::eval_phys_varying(&params(p), &mut q, &mut w).map_err(conv)?;
                    Ok(vec![back(&q)])
                },
            ],
            constants: [
                || {
                    let s = SENTINEL as $ty;
                    let (mut a, mut b, mut c, mut d) =
                        ([s; g::A_LEN], [s; g::B_LEN], [s; g::C_LEN], [s; g::D_LEN]);
                    g::write_abcd_constants(&mut a, &mut b, &mut c, &mut d);
                    vec![back(&a), back(&b), back(&c), back(&d)]
                },
                || {
                    let s = SENTINEL as $ty;
                    let (mut a, mut b) = ([s; g::A_LEN], [s; g::B_LEN]);
                    g::write_ab_constants(&mut a, &mut b);
                    vec![back(&a), back(&b)]
                },
                || {
                    let s = SENTINEL as $ty;
                    let (mut c, mut d) = ([s; g::C_LEN], [s; g::D_LEN]);
                    g::write_cd_constants(&mut c, &mut d);
                    vec![back(&c), back(&d)]
                },
                || {
                    let mut q = [SENTINEL as $ty; g::PHYS_LEN];
                    g::write_phys_constants(&mut q);
                    vec![back(&q)]
                },
            ],
            state_space: |p| {
                let mut ss = g::StateSpace::new();
                ss.evaluate(&g::Params::from_array(&params(p)))
                    .map_err(conv)?;
                Ok(vec![back(ss.a()), back(ss.b()), back(ss.c()), back(ss.d())])
            },
            ab: |p| {
                let (mut a, mut b, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::WORK_LEN]);
                g::eval_ab(&params(p), &mut a, &mut b, &mut w).map_err(conv)?;
                Ok(vec![back(&a), back(&b)])
            },
            cd: |p| {
                let (mut c, mut d, mut w) = ([0.0; g::C_LEN], [0.0; g::D_LEN], [0.0; g::WORK_LEN]);
                g::eval_cd(&params(p), &mut c, &mut d, &mut w).map_err(conv)?;
                Ok(vec![back(&c), back(&d)])
            },
            phys: |p| {
                let (mut q, mut w) = ([0.0; g::PHYS_LEN], [0.0; g::WORK_LEN]);
                g::eval_phys(&params(p), &mut q, &mut w).map_err(conv)?;
                Ok(vec![back(&q)])
            },
            nonzeros: [
                &g::A_NONZEROS,
                &g::B_NONZEROS,
                &g::C_NONZEROS,
                &g::D_NONZEROS,
                &g::PHYS_NONZEROS,
            ],
            checks: &g::CHECKS,
            param_names: &g::PARAM_NAMES,
        }
    }};
}

fn all_f64() -> Vec<Gen> {
    vec![
        generated!("smd", gen64::smd, f64),
        generated!("pendulum", gen64::pendulum, f64),
        generated!("shimmy", gen64::shimmy, f64),
        generated!("bicycle", gen64::bicycle, f64),
        generated!("quarter_car", gen64::quarter_car, f64),
        generated!("top", gen64::top, f64),
        generated!("disk", gen64::disk, f64),
        generated!("chain1", gen64::chain1, f64),
        generated!("chain3", gen64::chain3, f64),
        generated!("chain50", gen64::chain50, f64),
        generated!("smd_wing", gen64::smd_wing, f64),
        generated!("shimmy_wing", gen64::shimmy_wing, f64),
    ]
}

fn all_f32() -> Vec<Gen> {
    vec![
        generated!("smd", gen32::smd, f32),
        generated!("pendulum", gen32::pendulum, f32),
        generated!("shimmy", gen32::shimmy, f32),
        generated!("bicycle", gen32::bicycle, f32),
        generated!("quarter_car", gen32::quarter_car, f32),
        generated!("top", gen32::top, f32),
        generated!("disk", gen32::disk, f32),
        generated!("chain1", gen32::chain1, f32),
        generated!("chain3", gen32::chain3, f32),
        generated!("chain50", gen32::chain50, f32),
        generated!("smd_wing", gen32::smd_wing, f32),
        generated!("shimmy_wing", gen32::shimmy_wing, f32),
    ]
}

/// Variants of the bicycle and chain with their reference model.
fn variants() -> Vec<Gen> {
    vec![
        generated!("bicycle", gen64::bicycle_std, f64),
        generated!("bicycle", gen64::bicycle_chunked, f64),
        generated!("bicycle", gen64::bicycle_simplified, f64),
        generated!("shimmy", gen64::shimmy_simplified, f64),
        generated!("chain50", gen64::chain50_chunked, f64),
    ]
}

struct Reference {
    sym: SymbolicStateSpace,
    model: eom_model::Model,
}

fn reference(name: &str) -> Reference {
    let model = models::build(name, &[]).expect("model");
    let sym = Linearizer::new(&model).symbolic().expect("symbolic");
    Reference { sym, model }
}

fn to_vecs(ss: &StateSpace<f64>) -> Vec<Vec<f64>> {
    [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys]
        .iter()
        .map(|m| m.as_slice().to_vec())
        .collect()
}

/// Largest entry difference relative to the largest entry of the reference matrix.
fn rel_diff(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len());
    let scale = want
        .iter()
        .fold(0.0f64, |a, b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    got.iter()
        .zip(want)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()))
        / scale
}

/// The interpreter's error in the common form (`None` for other errors).
fn sym_err(e: &ModelError, g: &Gen) -> Option<GenErr> {
    match e {
        ModelError::PivotBreakdown(msg) => {
            let k = g
                .checks
                .iter()
                .position(|c| msg.starts_with(&format!("{c} (value")))?;
            Some(GenErr::Validity(k, g.checks[k]))
        }
        ModelError::Sym(SymError::EvalNonFinite { what, .. }) => {
            Some(GenErr::NonFinite(what.clone(), 0, 0))
        }
        _ => None,
    }
}

/// Compare a generated module with the interpreter at `values`: both succeed with equal
/// matrices (to `tol` relative to each matrix), or both fail on the same check.
fn compare(g: &Gen, r: &Reference, values: &[f64], tol: f64) -> Result<bool, TestCaseError> {
    let want = r.sym.evaluate(values);
    let got = (g.abcd)(values).and_then(|mut m| {
        m.extend((g.phys)(values)?);
        Ok(m)
    });
    match (got, want) {
        (Ok(got), Ok(want)) => {
            let want = to_vecs(&want);
            for (k, name) in ["A", "B", "C", "D", "Phys"].iter().enumerate() {
                let d = rel_diff(&got[k], &want[k]);
                prop_assert!(
                    d <= tol,
                    "{}: {name} differs by {d:e} at {values:?}",
                    g.model
                );
            }
            // The kernels for parts agree with the whole.
            let ab = (g.ab)(values).expect("eval_ab after eval_abcd succeeded");
            let cd = (g.cd)(values).expect("eval_cd after eval_abcd succeeded");
            for (x, y) in ab.iter().chain(&cd).zip(&got[..4]) {
                prop_assert!(
                    rel_diff(x, y) <= 1e-14,
                    "{}: partial kernels differ",
                    g.model
                );
            }
            Ok(true)
        }
        (Err(GenErr::Validity(k, what)), Err(e)) => {
            prop_assert_eq!(
                sym_err(&e, g),
                Some(GenErr::Validity(k, what)),
                "{}: different failing check",
                g.model
            );
            Ok(false)
        }
        (Err(GenErr::NonFinite(..)), Err(ModelError::Sym(SymError::EvalNonFinite { .. }))) => {
            Ok(false)
        }
        (got, want) => Err(TestCaseError::fail(format!(
            "{}: generated {:?} but the interpreter {:?} at {values:?}",
            g.model,
            got.map(|_| "succeeded"),
            want.map(|_| "succeeded")
        ))),
    }
}

/// `G(s) = C (sI − A)⁻¹ B + D`.
fn transfer(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    s: Complex64,
) -> DMatrix<Complex64> {
    let z = |m: &DMatrix<f64>| m.map(|x| Complex64::new(x, 0.0));
    let n = a.nrows();
    let x = (DMatrix::<Complex64>::identity(n, n) * s - z(a))
        .lu()
        .solve(&z(b))
        .expect("s is not a pole");
    z(c) * x + z(d)
}

fn near_nominal(nominal: Vec<f64>) -> impl Strategy<Value = Vec<f64>> {
    let n = nominal.len();
    proptest::collection::vec(0.7f64..1.3, n).prop_map(move |f| {
        nominal
            .iter()
            .zip(&f)
            .map(|(x, s)| if *x == 0.0 { s - 1.0 } else { x * s })
            .collect()
    })
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

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
        assert!(matches!(e, ModelError::PivotBreakdown(_)), "{model}: {e}");
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

#[test]
fn only_structural_nonzeros_are_written() {
    for g in all_f64() {
        let r = reference(g.model);
        let nominal = r.model.scope.nominal_values();
        let ss = r.sym.state_space();
        let mats = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys];
        // The pattern constants are the structural non-zeros of the expressions.
        for (k, m) in mats.iter().enumerate() {
            let want: Vec<(usize, usize)> = (0..m.ncols())
                .flat_map(|j| (0..m.nrows()).map(move |i| (i, j)))
                .filter(|&(i, j)| !m[(i, j)].is_zero())
                .collect();
            assert_eq!(
                g.nonzeros[k],
                want.as_slice(),
                "{}: pattern of matrix {k}",
                g.model
            );
        }
        // A kernel writing into arrays full of a sentinel leaves the other entries alone.
        let got = (g.abcd)(&nominal).expect("nominal is valid");
        let want = r.sym.evaluate(&nominal).expect("nominal");
        for (k, m) in [&want.a, &want.b, &want.c, &want.d].iter().enumerate() {
            assert!(rel_diff(&got[k], m.as_slice()) <= 1e-12, "{}", g.model);
        }
    }
    use gen64::shimmy as s;
    let (mut a, mut b, mut c, mut d, mut w) = (
        [-3.5; s::A_LEN],
        [-3.5; s::B_LEN],
        [-3.5; s::C_LEN],
        [-3.5; s::D_LEN],
        [0.0; s::WORK_LEN],
    );
    s::eval_abcd(&s::NOMINAL, &mut a, &mut b, &mut c, &mut d, &mut w).expect("nominal");
    for (arr, nz, rows) in [
        (&a[..], &s::A_NONZEROS[..], s::N_STATES),
        (&b[..], &s::B_NONZEROS[..], s::N_STATES),
        (&c[..], &s::C_NONZEROS[..], s::N_OUTPUTS),
        (&d[..], &s::D_NONZEROS[..], s::N_OUTPUTS),
    ] {
        for (idx, x) in arr.iter().enumerate() {
            let structural = nz.contains(&(idx % rows, idx / rows));
            assert_eq!(*x == -3.5, !structural, "entry {idx}");
        }
    }
}

/// The kernels and the matrices each writes (0–3: A, B, C, D; 4: the physical coordinates).
const KERNELS: [(&str, &[usize]); 4] = [
    ("eval_abcd", &[0, 1, 2, 3]),
    ("eval_ab", &[0, 1]),
    ("eval_cd", &[2, 3]),
    ("eval_phys", &[4]),
];

/// Each `eval_X_varying` writes exactly the structural non-zeros that `write_X_constants`
/// does not, and together they give `eval_X`'s values, bit for bit; so does `StateSpace`,
/// which is built on `eval_abcd_varying`. At nominal and at random points, on every module.
#[test]
fn varying_kernels_and_constants_make_up_the_kernels() {
    let mut with_constants = [0; 4];
    for g in all_f64().into_iter().chain(all_f32()).chain(variants()) {
        let r = reference(g.model);
        let sym = r.sym.state_space();
        let rows = [&sym.a, &sym.b, &sym.c, &sym.d, &sym.phys].map(|m| m.nrows());
        let wholes = [g.abcd, g.ab, g.cd, g.phys];
        for (kernel, (name, mats)) in KERNELS.iter().enumerate() {
            let constants = (g.constants[kernel])();
            let check = |values: &[f64]| -> Result<(), TestCaseError> {
                let whole = (wholes[kernel])(values);
                let part = (g.varying[kernel])(values);
                let ss = if kernel == 0 {
                    Some((g.state_space)(values))
                } else {
                    None
                };
                let (whole, part) = match (whole, part) {
                    (Ok(w), Ok(p)) => (w, p),
                    (Err(a), Err(b)) => {
                        prop_assert_eq!(&a, &b, "{}: {}: different errors", g.model, name);
                        if let Some(s) = ss {
                            prop_assert_eq!(Err(a), s.map(|_| ()), "{}: StateSpace", g.model);
                        }
                        return Ok(());
                    }
                    (w, p) => {
                        return Err(TestCaseError::fail(format!(
                            "{}: {name} {:?}, {name}_varying {:?}",
                            g.model,
                            w.is_ok(),
                            p.is_ok(),
                        )));
                    }
                };
                let ss = match ss {
                    Some(Ok(s)) => Some(s),
                    Some(Err(e)) => {
                        return Err(TestCaseError::fail(format!(
                            "{}: StateSpace fails where eval_abcd does not: {e:?}",
                            g.model
                        )));
                    }
                    None => None,
                };
                for (n, &k) in mats.iter().enumerate() {
                    for idx in 0..whole[n].len() {
                        let structural = g.nonzeros[k].contains(&(idx % rows[k], idx / rows[k]));
                        let (c, p) = (constants[n][idx], part[n][idx]);
                        // Exactly one of the two writes each structural non-zero, neither the
                        // rest.
                        prop_assert!(
                            structural == ((c == SENTINEL) != (p == SENTINEL)),
                            "{}: {name}: matrix {k} entry {idx}: constants {c}, varying {p}",
                            g.model
                        );
                        let joined = if c == SENTINEL { p } else { c };
                        let want = if structural { whole[n][idx] } else { SENTINEL };
                        prop_assert_eq!(
                            joined.to_bits(),
                            want.to_bits(),
                            "{}: {}: matrix {} entry {}",
                            g.model,
                            name,
                            k,
                            idx
                        );
                        if let Some(ss) = &ss {
                            prop_assert_eq!(
                                ss[n][idx].to_bits(),
                                whole[n][idx].to_bits(),
                                "{}: StateSpace matrix {} entry {}",
                                g.model,
                                k,
                                idx
                            );
                        }
                    }
                }
                Ok(())
            };
            let nominal = r.model.scope.nominal_values();
            check(&nominal).expect("nominal point");
            proptest!(config(8), |(values in near_nominal(nominal.clone()))| {
                check(&values)?;
            });
            if constants.iter().flatten().any(|&x| x != SENTINEL) {
                with_constants[kernel] += 1;
            }
        }
    }
    // Every kernel of some module has constant entries, or its half of the test tests nothing.
    for (kernel, (name, _)) in KERNELS.iter().enumerate() {
        assert!(
            with_constants[kernel] > 0,
            "no module's {name} has constant entries: the test tests nothing for it"
        );
    }
}

#[test]
fn params_struct_and_state_space_value() {
    use gen64::bicycle as b;
    let p = b::Params::NOMINAL;
    assert_eq!(p.to_array(), b::NOMINAL);
    assert_eq!(b::Params::from_array(&b::NOMINAL), p);
    assert_eq!(b::Params::default(), p);
    let mut ss = b::StateSpace::new();
    let mut q = p;
    q.v = 5.0;
    ss.evaluate(&q).expect("valid");
    let r = reference("bicycle");
    let want = r.sym.evaluate(&q.to_array()).expect("valid");
    assert!(rel_diff(ss.a(), want.a.as_slice()) <= 1e-12);
    assert!(rel_diff(ss.b(), want.b.as_slice()) <= 1e-12);
    assert_eq!(
        b::PARAM_UNITS[b::PARAM_NAMES.iter().position(|n| *n == "v").expect("v")],
        "m/s"
    );
}

#[test]
fn generation_is_deterministic() {
    let dir = env!("OUT_DIR");
    let first = std::fs::read_to_string(format!("{dir}/smd_first.rs")).expect("file");
    let again = std::fs::read_to_string(format!("{dir}/smd_again.rs")).expect("file");
    assert_eq!(
        first, again,
        "smd generated in a fresh pool and after other models differ"
    );
    let m = models::build("bicycle", &[]).expect("bicycle");
    let opts = eom_codegen::EmitOptions::default();
    let x = eom_codegen::emit_model(&m, &opts).expect("emit").source;
    let _other = eom_codegen::emit_model(&models::build("chain3", &[]).expect("chain"), &opts)
        .expect("emit");
    let y = eom_codegen::emit_model(&models::build("bicycle", &[]).expect("bicycle"), &opts)
        .expect("emit")
        .source;
    assert_eq!(x, y);
}

#[test]
fn generated_libm_code_uses_core_only() {
    let dir = env!("OUT_DIR");
    for entry in std::fs::read_dir(dir).expect("OUT_DIR") {
        let path = entry.expect("entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_string();
        if !name.ends_with(".rs") || name.contains("_std") || name == "generated.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(
            !text.contains("std::") && !text.contains(".sin(") && !text.contains(".sqrt("),
            "{name} needs std"
        );
    }
}

#[test]
fn bad_options_are_typed_errors_naming_the_option() {
    use eom_codegen::{CodegenError, EmitOptions, emit_model};
    let m = models::build("smd", &[]).expect("smd");
    let e = emit_model(&m, &EmitOptions::default().module("Not A Module")).expect_err("bad module");
    assert!(
        matches!(
            e,
            CodegenError::BadOption {
                option: "module",
                ..
            }
        ),
        "{e}"
    );
    let e =
        emit_model(&m, &EmitOptions::default().fix("mass", 2.0)).expect_err("unknown parameter");
    assert!(
        e.to_string().contains("mass") && e.to_string().contains("m, k, c"),
        "{e}"
    );
    let e = emit_model(&m, &EmitOptions::default().fix("m", 0.0)).expect_err("division by zero");
    assert!(
        matches!(e, CodegenError::BadOption { option: "fix", .. }),
        "{e}"
    );
    let bike = models::build("bicycle", &[]).expect("bicycle");
    let e = emit_model(
        &bike,
        &EmitOptions::default().fix("lambda", std::f64::consts::FRAC_PI_2),
    )
    .expect_err("outside");
    assert!(
        matches!(e, CodegenError::BadOption { option: "fix", .. })
            && e.to_string().contains("steer hinge"),
        "{e}"
    );
    let e = emit_model(&m, &EmitOptions::default().max_temporaries(0)).expect_err("zero chunk");
    assert!(
        matches!(
            e,
            CodegenError::BadOption {
                option: "max_temporaries",
                ..
            }
        ),
        "{e}"
    );
}

/// Formatting snapshot of a tiny model (the only exact-text test).
#[test]
fn smd_eval_ab_formatting_snapshot() {
    let m = models::build("smd", &[]).expect("smd");
    let src = eom_codegen::emit_model(&m, &eom_codegen::EmitOptions::default())
        .expect("emit")
        .source;
    let start = src.find("    pub fn eval_ab(").expect("eval_ab");
    let end = start + src[start..].find("\n    }\n").expect("end") + 7;
    let expected = SMD_EVAL_AB;
    assert_eq!(
        &src[start..end],
        expected,
        "formatting of smd's eval_ab changed:\n{}",
        &src[start..end]
    );
}

const SMD_EVAL_AB: &str = r#"    pub fn eval_ab(
        p: &[f64; N_PARAMS],
        a: &mut [f64; A_LEN],
        b: &mut [f64; B_LEN],
        work: &mut [f64; WORK_LEN],
    ) -> Result<(), Error> {
        let _ = work;
        let p_m: f64 = p[0];
        let p_k: f64 = p[1];
        let p_c: f64 = p[2];
        let t0: f64 = 1.0 / p_m;
        let t1: f64 = p_k * t0;
        let t2: f64 = p_c * t0;
        let av0 = p_m.abs();
        let ok0: bool = av0 > 0.0;
        let size0: f64 = p_m.abs() + p_c.abs();
        let size1: f64 = p_k.abs();
        if !(ok0
            & (((size0 < 1.152921504606847e18) & (size1 < 1.152921504606847e18)
                & (p_m.abs() >= 8.673617379884035e-19))))
        {
            return eval_ab_checked(p, a, b, work);
        }
        a[1] = -t1;
        a[2] = 1.0;
        a[3] = -t2;
        b[1] = t0;
        Ok(())
    }
"#;

/// `simplify` keeps the simplified expressions only when they have fewer operations and a
/// lower cost estimate (chain × operations); otherwise the output is exactly the plain one.
/// `simplify_always` keeps them on fewer operations alone.
#[test]
fn simplification_is_used_only_when_estimated_faster() {
    use eom_codegen::{EmitOptions, Simplification, emit_model};
    let mut seen_slower = Vec::new();
    let mut seen_used = Vec::new();
    for name in ["smd", "shimmy", "bicycle", "chain3"] {
        let m = models::build(name, &[]).expect("model");
        let plain = emit_model(&m, &EmitOptions::default()).expect("emit");
        assert_eq!(plain.stats.simplification, Simplification::NotRun);
        let simp = emit_model(&m, &EmitOptions::default().simplify(true)).expect("emit");
        let always = emit_model(&m, &EmitOptions::default().simplify_always(true)).expect("emit");
        let (p0, s0, a0) = (
            &plain.stats.functions[0],
            &simp.stats.functions[0],
            &always.stats.functions[0],
        );
        match simp.stats.simplification {
            Simplification::Used => {
                seen_used.push(name);
                assert!(s0.cost_estimate() < p0.cost_estimate(), "{name}");
                assert!(s0.ops.total() < p0.ops.total(), "{name}");
                assert_eq!(simp.source, always.source, "{name}");
            }
            Simplification::NotFaster {
                simplified,
                original,
            } => {
                seen_slower.push(name);
                assert!(simplified >= original, "{name}");
                assert_eq!(
                    (original, simplified),
                    (p0.cost_estimate(), a0.cost_estimate())
                );
                assert!(a0.critical_path > p0.critical_path, "{name}");
                assert_eq!(simp.source, plain.source, "{name}: not the plain code");
                assert_eq!(always.stats.simplification, Simplification::Used, "{name}");
                assert_ne!(always.source, plain.source, "{name}");
            }
            Simplification::NotCheaper => {
                assert_eq!(simp.source, plain.source, "{name}");
                assert_eq!(always.source, plain.source, "{name}");
            }
            Simplification::NotRun => panic!("{name}: simplification not run"),
        }
    }
    // The two measured cases: the bicycle's factored form is slower (83 against 75 ns per
    // call), the shimmy's faster (4.78 against 4.94 ns).
    assert_eq!(seen_slower, ["bicycle"]);
    assert_eq!(seen_used, ["shimmy"]);
}

/// A value with a first-order bound of its rounding error: `v` is the exact value of the
/// formula (double-double), `e` the bound of `|fl(formula) − v|` in units of roundoff when
/// the formula is evaluated in `f64` operation by operation, as written (Higham's running
/// error bound: each operation adds its inputs' errors, propagated by its derivative, and
/// one rounding of its result). A value that cancels in the formula itself gets a large
/// bound; one that the evaluation made cancel does not.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bounded {
    v: eom_sym::Dd,
    e: f64,
}

mod bounded {
    use super::Bounded;
    use eom_sym::{Dd, Elementary, Rational, Scalar};
    use std::ops::{Add, Div, Mul, Neg, Sub};

    fn mag(x: Dd) -> f64 {
        x.to_f64().abs()
    }
    /// A result: `v` rounded once, plus the propagated error `e`.
    fn op(v: Dd, e: f64) -> Bounded {
        Bounded { v, e: e + mag(v) }
    }
    /// An exact datum (parameters and numbers that are doubles).
    fn exact(v: Dd) -> Bounded {
        Bounded { v, e: 0.0 }
    }
    /// A constant rounded once to a double (`1/3`, π).
    fn rounded(v: Dd) -> Bounded {
        let e = if v.lo == 0.0 { 0.0 } else { mag(v) };
        Bounded { v, e }
    }

    impl Add for Bounded {
        type Output = Bounded;
        fn add(self, b: Bounded) -> Bounded {
            op(self.v + b.v, self.e + b.e)
        }
    }
    impl Sub for Bounded {
        type Output = Bounded;
        fn sub(self, b: Bounded) -> Bounded {
            op(self.v - b.v, self.e + b.e)
        }
    }
    impl Mul for Bounded {
        type Output = Bounded;
        fn mul(self, b: Bounded) -> Bounded {
            op(self.v * b.v, self.e * mag(b.v) + b.e * mag(self.v))
        }
    }
    impl Div for Bounded {
        type Output = Bounded;
        fn div(self, b: Bounded) -> Bounded {
            let q = self.v / b.v;
            op(q, (self.e + mag(q) * b.e) / mag(b.v))
        }
    }
    impl Neg for Bounded {
        type Output = Bounded;
        fn neg(self) -> Bounded {
            Bounded {
                v: -self.v,
                e: self.e,
            }
        }
    }
    /// A library function with derivative `d` at the argument: one more unit for the
    /// library's own rounding.
    fn func(x: Bounded, v: Dd, d: Dd) -> Bounded {
        op(v, x.e * mag(d) + mag(v))
    }

    impl Scalar for Bounded {
        fn zero() -> Bounded {
            exact(Dd::ZERO)
        }
        fn one() -> Bounded {
            exact(Dd::ONE)
        }
        fn from_i64(n: i64) -> Bounded {
            rounded(Dd::from_i64(n))
        }
        fn from_rational(r: &Rational) -> Bounded {
            rounded(<Dd as Scalar>::from_rational(r))
        }
        fn from_f64(x: f64) -> Bounded {
            exact(Dd::from_f64(x))
        }
        fn pi() -> Bounded {
            rounded(Dd::PI)
        }
        fn sqrt(self) -> Bounded {
            let r = self.v.sqrt();
            let d = Dd::from_f64(0.5) / r;
            op(r, self.e * mag(d))
        }
        fn sin(self) -> Bounded {
            func(self, self.v.sin(), self.v.cos())
        }
        fn cos(self) -> Bounded {
            func(self, self.v.cos(), self.v.sin())
        }
        fn abs(self) -> Bounded {
            Bounded {
                v: self.v.abs(),
                e: self.e,
            }
        }
        fn nominal(&self) -> f64 {
            self.v.to_f64()
        }
        fn is_zero(&self) -> bool {
            self.v == Dd::ZERO
        }
        fn is_one(&self) -> bool {
            self.v == Dd::ONE && self.e == 0.0
        }
    }

    impl Elementary for Bounded {
        fn tan(self) -> Bounded {
            let t = self.v.tan();
            func(self, t, Dd::ONE + t * t)
        }
        fn exp(self) -> Bounded {
            let v = self.v.exp();
            func(self, v, v)
        }
        fn ln(self) -> Bounded {
            func(self, self.v.ln(), Dd::ONE / self.v)
        }
        fn atan2(self, x: Bounded) -> Bounded {
            let (y, xv) = (self.v, x.v);
            let r2 = y * y + xv * xv;
            let e = (self.e * mag(xv) + x.e * mag(y)) / mag(r2);
            op(y.atan2(xv), e + mag(y.atan2(xv)))
        }
        fn powf(self, p: Bounded) -> Bounded {
            let v = self.v.powf(p.v);
            let e = self.e * mag(p.v * v / self.v) + p.e * mag(v * self.v.ln());
            op(v, e + mag(v))
        }
    }
}

/// Accuracy of the generated code against the formula it was generated from: at points
/// within ±20 % of nominal, every entry's error against a double-double evaluation of the
/// same expressions, in units of the running error bound of evaluating those expressions in
/// `f64` as the pool holds them ([`Bounded`]). The interpreter evaluates them that way and
/// stays below one bound. The generated code evaluates a rewritten formula (sums
/// reassociated by ready time, `x·x⁻¹` cancelled, common factors pulled out), so it may
/// exceed the bound by the factor reassociation allows, but a rewrite that creates a
/// cancellation the formula does not have (an `a + b − (a + b − c)` computed as written) costs
/// many bounds. Entries that cancel in the physics (near-zero rows of the bicycle's A) have
/// a large bound and are judged fairly.
#[test]
fn generated_code_is_accurate_against_double_double() {
    use eom_sym::tape::eval_generic;
    use rand::{Rng, SeedableRng, rngs::StdRng};
    let eps = f64::EPSILON;
    // In units of the bound, which counts a full `eps` per operation where rounding costs at
    // most half of it, so a formula evaluated as written stays below 0.5 (measured: 0.50,
    // the same entries in the interpreter). Reassociating an n-term sum can multiply the bound
    // of the sum by a small factor; a cancellation the formula lacks costs thousands (checked
    // by computing every quotient's numerator as `(n + 1e8) − 1e8` in the renderer: the
    // bicycle then fails at 18 000).
    let allowed = 4.0;
    let mut report = String::new();
    for g in all_f64().into_iter().chain(variants()) {
        let r = reference(g.model);
        let ss = r.sym.state_space();
        let mats = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys];
        let roots: Vec<eom_sym::Expr> = mats.iter().flat_map(|m| m.iter().copied()).collect();
        let pos: std::collections::HashMap<u32, usize> = r
            .sym
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| (p.param_index().expect("a parameter"), k))
            .collect();
        let nominal = r.model.scope.nominal_values();
        let mut rng = StdRng::seed_from_u64(20261121);
        let points = if g.model == "chain50" { 4 } else { 48 };
        let (mut worst_gen, mut worst_int, mut done) = (0.0f64, 0.0f64, 0);
        for _ in 0..points {
            let values: Vec<f64> = nominal
                .iter()
                .map(|&x| {
                    let f = rng.random_range(0.8..1.2);
                    if x == 0.0 { f - 1.0 } else { x * f }
                })
                .collect();
            let Ok(mut got) = (g.abcd)(&values) else {
                continue;
            };
            got.extend((g.phys)(&values).expect("eval_phys after eval_abcd succeeded"));
            let interp = to_vecs(&r.sym.evaluate(&values).expect("interpreter"));
            let exact = eval_generic::<Bounded>(&roots, |i| {
                pos.get(&i).map(|&k| Bounded {
                    v: eom_sym::Dd::from_f64(values[k]),
                    e: 0.0,
                })
            })
            .expect("double-double evaluation");
            let (got, interp): (Vec<f64>, Vec<f64>) = (got.concat(), interp.concat());
            for (k, x) in exact.iter().enumerate() {
                let want = x.v.to_f64();
                // Units of the bound (in `eps`); an entry computed without rounding must be exact.
                let units = |y: f64| {
                    let d = (y - want).abs();
                    if d == 0.0 { 0.0 } else { d / (eps * x.e) }
                };
                let (ug, ui) = (units(got[k]), units(interp[k]));
                assert!(
                    ug.is_finite(),
                    "{}: entry {k} (column-major over A, B, C, D, Phys) is computed without rounding in the formula but differs by {:e}",
                    g.model,
                    got[k] - want
                );
                worst_gen = worst_gen.max(ug);
                worst_int = worst_int.max(ui);
            }
            done += 1;
        }
        assert!(done > 0, "{}: no point inside the validity region", g.model);
        report.push_str(&format!(
            "{:12} worst error in bounds: generated {worst_gen:.3}, interpreter {worst_int:.3}\n",
            g.model
        ));
        assert!(
            worst_gen <= allowed,
            "{}: generated code is {worst_gen} running-error bounds off (interpreter {worst_int})\n{report}",
            g.model
        );
    }
    eprint!("{report}");
}
