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
                } // No `SampleTime`: modules without `eval_discrete` have no such variant (the
                  // match is exhaustive without it, or this does not compile).
            }
        }
        // Nor the discrete matrices `Ad`, `Bd` (exhaustive without them).
        #[allow(dead_code)]
        fn matrix_name(m: g::Matrix) -> &'static str {
            match m {
                g::Matrix::A => "A",
                g::Matrix::B => "B",
                g::Matrix::C => "C",
                g::Matrix::D => "D",
                g::Matrix::Phys => "Phys",
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

/// Every model that `build.rs` generates (its `MODELS`), in `f64`.
fn all_f64() -> Vec<Gen> {
    include!(concat!(env!("OUT_DIR"), "/all_f64.rs"))
}

/// The same in `f32`.
fn all_f32() -> Vec<Gen> {
    include!(concat!(env!("OUT_DIR"), "/all_f32.rs"))
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
        ModelError::PivotBreakdown { check, .. } => {
            let k = g.checks.iter().position(|c| check == c)?;
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

mod accuracy;
mod hostile;
mod interpreter;
mod kernels;
mod stability;
mod text;
