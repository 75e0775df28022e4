//! Property tests of the expression core on random expressions (`common::recipe`).
//!
//! # Tolerances
//!
//! No fixed relative tolerance is used for evaluation: a random expression can cancel
//! catastrophically (`p0 − p0·(1 + 1e-12)`) and then no relative tolerance is right. Instead
//! an independent evaluator written here ([`walk`], over `Expr::view`, in double-double)
//! computes at every node a *running forward-error bound* `E` for an `f64` evaluation of that
//! node from `f64` children (Wilkinson-style first-order analysis made rigorous where cheap):
//!
//! * constants: `2u·|v|` (rounding of a rational, of π or e); floats and parameters: 0;
//! * sums `c₀ + Σcᵢtᵢ`: `Σ(|cᵢ|Eᵢ + |tᵢ|E(cᵢ) + E(cᵢ)Eᵢ) + (n+2)u·(|c₀| + Σ|cᵢtᵢ|)` (any order
//!   of summation, products included);
//! * products `c·Πbᵢ^eᵢ`: relative errors compose exactly, `(1+ρ)(1+ρ') − 1`, with
//!   `ρᵢ = max|(1±δᵢ)^eᵢ − 1|` for the relative input error `δᵢ = Eᵢ/|bᵢ|` plus the roundings
//!   of the power (`2·bits(n)+1` for an integer power by squaring, one for `sqrt`, 2 ulps plus
//!   the exponent rounding for `powf`); `δᵢ ≥ 1` gives an infinite bound;
//! * `sin`, `cos`: `|f'(a)|·E + E²/2`; `exp`: `|v|·expm1(E)`; `ln`: `−ln(1 − E/|a|)`; `abs`: `E`;
//!   `atan2`: `(|x|E_y + |y|E_x)/r² + 4(E_x+E_y)²/r²` (infinite near the branch cut or when
//!   `E_x + E_y > 10⁻⁶·r`); plus 2 ulps (`4u·|v|`) for each library function.
//!
//! The `f64` results (tape and `eval_generic::<f64>`) must lie within `2·E` of the
//! double-double reference `eval_generic::<Dd>`. The factor 2 covers the neglected
//! `O(u²)` terms and the reference's own error; it is not a fudge factor for discrepancies:
//! a real bug (a wrong coefficient, a dropped term) misses by orders of magnitude. Points where
//! the reference is not finite or `E` is infinite are skipped and counted, and each test asserts
//! that most cases were compared and that most comparisons were *sharp* (`E ≤ 10⁻¹²·|v|`), so
//! a test cannot pass by skipping.
//!
//! Double-double results are compared with each other using `DD_RATIO·E`: double-double
//! arithmetic rounds at ~2⁻¹⁰⁴ instead of 2⁻⁵³, and its elementary functions are accurate to
//! ~10⁻²⁹ instead of the 2 ulps (4.4·10⁻¹⁶) charged for libm, a ratio below 2⁻⁴⁴; `DD_RATIO =
//! 2⁻³⁶` keeps a margin of 256.
//!
//! Derivatives are checked against a fourth-order central difference of the double-double
//! evaluation (rule in [`derivative_matches_finite_differences`]).

mod common;

use common::{N_PARAMS, Recipe, build, params, recipe};
use eom_sym::{Constant, Dd, Expr, ExprView, Func, Rational, Scalar, SymError, Tape, eval_generic};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestRunner};
use std::cell::Cell;
use std::collections::HashMap;

/// Cases per property (the brief asks for at least 1 000).
const CASES: u32 = 2_000;
/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;
/// Charged for each libm function call: 2 ulps.
const FU: f64 = 4.0 * U;
/// Double-double error relative to the `f64` running bound (see the module docs).
const DD_RATIO: f64 = 1.0 / (1u64 << 36) as f64;
/// Absolute slack for results that are exactly zero (subnormal rounding).
const TINY: f64 = 1e-300;

// ================================================================== the reference walker

/// Value (double-double) and running bound of the `f64` evaluation error of one node.
#[derive(Clone, Copy, Debug)]
struct Val {
    v: Dd,
    err: f64,
}

/// The walk of a DAG at one point.
struct Walk {
    vals: HashMap<u32, Val>,
    /// Signs at the non-smooth spots (abs, ln, negative or fractional powers, atan2 cut): two
    /// points with the same signature are on the same smooth piece.
    signature: Vec<i8>,
}

impl Walk {
    fn at(&self, e: Expr) -> Val {
        self.vals[&e.id()]
    }
}

/// All nodes reachable from `roots`, in increasing id (a topological order).
fn reachable(roots: &[Expr]) -> Vec<Expr> {
    let mut seen: HashMap<u32, Expr> = HashMap::new();
    let mut stack: Vec<Expr> = roots.to_vec();
    while let Some(e) = stack.pop() {
        if seen.insert(e.id(), e).is_none() {
            stack.extend(e.children());
        }
    }
    let mut v: Vec<Expr> = seen.into_values().collect();
    v.sort_by_key(|e| e.id());
    v
}

fn sign(d: Dd) -> i8 {
    if d.hi > 0.0 {
        1
    } else if d.hi < 0.0 {
        -1
    } else {
        0
    }
}

/// `k` roundings compounded: `γ_k = k·u/(1 − k·u)`.
fn gamma(k: u32) -> f64 {
    let k = k as f64;
    k * U / (1.0 - k * U)
}

/// `(1 + a)(1 + b) − 1` without cancellation.
fn compose(a: f64, b: f64) -> f64 {
    a + b + a * b
}

/// The power as the tape and `eval_generic` compute it (reference in double-double).
fn pow_dd(b: Dd, e: &Rational) -> Dd {
    match e.as_small() {
        Some((n, 1)) => b.powi(n),
        Some((1, 2)) => b.sqrt(),
        Some((-1, 2)) => Dd::ONE / b.sqrt(),
        _ => b.powf(Dd::from_rational(e)),
    }
}

/// Relative rounding error of computing `b^e` in `f64` from an exact `b`.
fn pow_rounding(e: &Rational, b: f64) -> f64 {
    match e.as_small() {
        Some((n, 1)) => {
            let bits = 64 - n.unsigned_abs().leading_zeros();
            gamma(2 * bits + u32::from(n < 0))
        }
        Some((1, 2)) => U,
        Some((-1, 2)) => gamma(2),
        // powf (2 ulps) and the rounding of the exponent to f64: b^(e(1+u)) = b^e·b^(eu).
        _ => FU + (e.to_f64() * b.abs().ln()).abs() * U,
    }
}

/// Evaluate every node of `roots` in double-double with the running `f64` error bound.
/// `param(i)` gives the value and input error of the parameter with pool index `i`.
fn walk(roots: &[Expr], param: &dyn Fn(u32) -> Val) -> Walk {
    let mut vals: HashMap<u32, Val> = HashMap::new();
    let mut signature = Vec::new();
    for e in reachable(roots) {
        let get = |x: Expr, vals: &HashMap<u32, Val>| vals[&x.id()];
        let val = match e.view() {
            ExprView::Rational(r) => {
                let v = Dd::from_rational(&r);
                Val {
                    v,
                    err: 2.0 * U * v.to_f64().abs(),
                }
            }
            ExprView::Float(f) => Val {
                v: Dd::from_f64(f),
                err: 0.0,
            },
            ExprView::Constant(c) => {
                let v = match c {
                    Constant::Pi => Dd::PI,
                    Constant::E => Dd::E,
                };
                Val {
                    v,
                    err: 2.0 * U * v.to_f64(),
                }
            }
            ExprView::Param(i, _) => param(i),
            ExprView::Sum { constant, terms } => {
                let c0 = get(constant, &vals);
                let (mut v, mut mag, mut err) = (c0.v, c0.v.to_f64().abs(), c0.err);
                for &(t, c) in &terms {
                    let (t, c) = (get(t, &vals), get(c, &vals));
                    let p = c.v * t.v;
                    v += p;
                    mag += p.to_f64().abs();
                    let (cv, tv) = (c.v.to_f64().abs(), t.v.to_f64().abs());
                    err += cv * t.err + tv * c.err + c.err * t.err;
                }
                err += gamma(terms.len() as u32 + 2) * mag;
                Val { v, err }
            }
            ExprView::Product { coef, factors } => {
                let c = get(coef, &vals);
                let mut v = c.v;
                let mut rel = c.err / c.v.to_f64().abs();
                for (b, ex) in &factors {
                    let b = get(*b, &vals);
                    if ex.is_negative() || !ex.is_integer() {
                        signature.push(sign(b.v));
                    }
                    v *= pow_dd(b.v, ex);
                    let bv = b.v.to_f64().abs();
                    let delta = if b.err == 0.0 { 0.0 } else { b.err / bv };
                    let prop = if delta < 1.0 {
                        let ef = ex.to_f64();
                        let up = (ef * delta.ln_1p()).exp_m1().abs();
                        let down = (ef * (-delta).ln_1p()).exp_m1().abs();
                        up.max(down)
                    } else {
                        f64::INFINITY
                    };
                    rel = compose(rel, compose(prop, pow_rounding(ex, bv)));
                }
                rel = compose(rel, gamma(factors.len() as u32));
                Val {
                    v,
                    err: v.to_f64().abs() * rel,
                }
            }
            ExprView::Pow(a, b) => {
                // Not produced by the recipes; first order with a validity guard.
                let (a, b) = (get(a, &vals), get(b, &vals));
                signature.push(sign(a.v));
                let v = a.v.powf(b.v);
                let delta = a.err / a.v.to_f64().abs();
                let lna = a.v.to_f64().abs().ln().abs();
                let bf = b.v.to_f64().abs();
                let first = bf * delta + lna * b.err;
                let rel = if first < 1e-6 {
                    first * 1.001 + FU
                } else {
                    f64::INFINITY
                };
                Val {
                    v,
                    err: v.to_f64().abs() * rel,
                }
            }
            ExprView::Func(f, a) => {
                let a = get(a, &vals);
                let (x, ea) = (a.v, a.err);
                let (v, err) = match f {
                    Func::Sin => {
                        let v = x.sin();
                        (v, x.cos().to_f64().abs() * ea + ea * ea / 2.0)
                    }
                    Func::Cos => {
                        let v = x.cos();
                        (v, x.sin().to_f64().abs() * ea + ea * ea / 2.0)
                    }
                    Func::Tan => {
                        let (v, c) = (x.tan(), x.cos().to_f64().abs());
                        signature.push(sign(x.cos()));
                        let e = if ea < 1e-6 * c {
                            ea / (c * c) * 1.001
                        } else {
                            f64::INFINITY
                        };
                        (v, e)
                    }
                    Func::Exp => {
                        let v = x.exp();
                        (v, v.to_f64().abs() * ea.exp_m1())
                    }
                    Func::Ln => {
                        signature.push(sign(x));
                        let delta = ea / x.to_f64().abs();
                        let e = if delta < 1.0 {
                            -(-delta).ln_1p()
                        } else {
                            f64::INFINITY
                        };
                        (x.ln(), e)
                    }
                    Func::Abs => {
                        signature.push(sign(x));
                        (x.abs(), ea)
                    }
                };
                let lib = if f == Func::Abs {
                    0.0
                } else {
                    FU * v.to_f64().abs()
                };
                Val { v, err: err + lib }
            }
            ExprView::Atan2(y, x) => {
                let (y, x) = (get(y, &vals), get(x, &vals));
                let (yf, xf) = (y.v.to_f64(), x.v.to_f64());
                signature.push(if xf < 0.0 { sign(y.v) } else { 2 });
                let v = y.v.atan2(x.v);
                let r = xf.hypot(yf);
                let e = y.err + x.err;
                let near_cut = xf < 0.0 && yf.abs() <= y.err;
                let err = if near_cut || e > 1e-6 * r {
                    f64::INFINITY
                } else {
                    (xf.abs() * y.err + yf.abs() * x.err) / (r * r) + 4.0 * e * e / (r * r)
                };
                Val {
                    v,
                    err: err + FU * v.to_f64().abs(),
                }
            }
            ExprView::Invalid(err) => panic!("walk of an invalid node: {err}"),
        };
        vals.insert(e.id(), val);
    }
    Walk { vals, signature }
}

// ================================================================== helpers

/// The four recipe parameters and a point (values for p0..p3).
struct Point<'a> {
    p: &'a [Expr],
    x: [f64; N_PARAMS],
}

impl Point<'_> {
    fn slot(&self, index: u32) -> Option<usize> {
        self.p.iter().position(|q| q.param_index() == Some(index))
    }
    fn f64_of(&self, index: u32) -> Option<f64> {
        self.slot(index).map(|k| self.x[k])
    }
    fn dd_of(&self, index: u32) -> Option<Dd> {
        self.f64_of(index).map(Dd::from_f64)
    }
    fn val_of(&self, index: u32) -> Val {
        Val {
            v: self.dd_of(index).expect("recipe parameter"),
            err: 0.0,
        }
    }
}

fn dd_eval(e: Expr, value_of: impl Fn(u32) -> Option<Dd>) -> Dd {
    eval_generic::<Dd>(&[e], value_of).expect("valid expression")[0]
}

fn finite(d: Dd) -> bool {
    d.is_finite()
}

/// A point: four values in (−3, 3).
fn point() -> impl Strategy<Value = [f64; N_PARAMS]> {
    prop::array::uniform4(-3.0f64..3.0)
}

/// Counters of one property: how many cases were compared, skipped and why.
#[derive(Default)]
struct Stats {
    cases: Cell<u32>,
    invalid: Cell<u32>,
    undefined: Cell<u32>,
    constant: Cell<u32>,
    skipped: Cell<u32>,
    compared: Cell<u32>,
    sharp: Cell<u32>,
}

impl Stats {
    fn bump(c: &Cell<u32>) {
        c.set(c.get() + 1);
    }
    fn report(&self, name: &str) {
        eprintln!(
            "{name}: {} cases, {} invalid, {} undefined, {} constant, {} skipped, {} compared ({} sharp)",
            self.cases.get(),
            self.invalid.get(),
            self.undefined.get(),
            self.constant.get(),
            self.skipped.get(),
            self.compared.get(),
            self.sharp.get()
        );
    }
    /// The test has teeth: most generated cases were compared, most comparisons sharply.
    fn assert_coverage(&self, name: &str, min_compared: f64, min_sharp: f64) {
        self.report(name);
        let (n, c, s) = (
            self.cases.get() as f64,
            self.compared.get() as f64,
            self.sharp.get() as f64,
        );
        assert!(
            c >= min_compared * n,
            "{name}: only {c} of {n} cases compared"
        );
        assert!(
            s >= min_sharp * c,
            "{name}: only {s} of {c} comparisons sharp"
        );
    }
}

fn runner() -> TestRunner {
    TestRunner::new(Config {
        cases: CASES,
        source_file: Some(file!()),
        // Failing cases are saved next to this file (`properties.proptest-regressions`) and
        // replayed first on the next run.
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..Config::default()
    })
}

fn run<S: Strategy>(strategy: S, test: impl Fn(S::Value) -> Result<(), TestCaseError>)
where
    S::Value: std::fmt::Debug,
{
    if let Err(e) = runner().run(&strategy, test) {
        panic!("{e}");
    }
}

// ================================================================== (a) evaluation

/// Tape = `eval_generic::<f64>` = `eval_generic::<Dd>` (rounded), within the running bound.
#[test]
fn tape_recursive_and_double_double_evaluation_agree() {
    let p = params();
    let st = Stats::default();
    run((recipe(), point()), |(r, x)| {
        Stats::bump(&st.cases);
        let e = build(&r, &p);
        if e.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        let pt = Point { p: &p, x };
        let reference = dd_eval(e, |i| pt.dd_of(i));
        let w = walk(&[e], &|i| pt.val_of(i));
        let bound = w.at(e).err;
        if !finite(reference) || !bound.is_finite() {
            Stats::bump(&st.undefined);
            return Ok(());
        }
        // The independent walker and eval_generic::<Dd> agree at double-double level.
        let walked = w.at(e).v;
        let dd_tol = DD_RATIO * bound + TINY;
        prop_assert!(
            (walked - reference).to_f64().abs() <= dd_tol,
            "walker {walked} vs eval_generic::<Dd> {reference} (tol {dd_tol:e}) for {e}"
        );
        let g = eval_generic::<f64>(&[e], |i| pt.f64_of(i)).unwrap()[0];
        let tol = 2.0 * bound + TINY;
        let rf = reference.to_f64();
        // The exact tape and the reassociating one (other rounding, same bound).
        for tape in [Tape::new(&[e], &p), Tape::new_reassociating(&[e], &p)] {
            let tape = tape.expect("tape of a valid expression");
            match tape.eval_vec(&x) {
                Ok(t) => prop_assert!(
                    (Dd::from_f64(t[0]) - reference).to_f64().abs() <= tol,
                    "tape {} vs reference {reference}: error {:e} > tol {tol:e} for {e}",
                    t[0],
                    (t[0] - rf).abs()
                ),
                Err(err) => prop_assert!(
                    false,
                    "tape failed ({err}) where the reference is {reference}"
                ),
            }
        }
        prop_assert!(
            g.is_finite() && (Dd::from_f64(g) - reference).to_f64().abs() <= tol,
            "eval_generic::<f64> {g} vs reference {reference}: tol {tol:e} for {e}"
        );
        Stats::bump(&st.compared);
        if bound <= 1e-12 * rf.abs() {
            Stats::bump(&st.sharp);
        }
        Ok(())
    });
    st.assert_coverage("evaluation", 0.7, 0.5);
}

/// `eval_batch` (chunks of points in structure-of-arrays form) gives exactly the results of
/// `eval_into` point by point (the same operations per lane), and on a non-finite output
/// names the same first (point, output) pair. Batch sizes 0–39 cover full and partial chunks
/// and the point-by-point remainder.
#[test]
fn batch_evaluation_equals_pointwise_evaluation() {
    let p = params();
    run(
        (recipe(), prop::collection::vec(point(), 0..40)),
        |(r, pts)| {
            let e = build(&r, &p);
            if e.check().is_err() {
                return Ok(());
            }
            let roots = [e, e + p[0]];
            let tape = Tape::new(&roots, &p).expect("tape of a valid expression");
            let mut want = Vec::new();
            let mut first_bad = None;
            let mut work = vec![0.0; tape.work_len()];
            for (k, x) in pts.iter().enumerate() {
                let mut o = [0.0; 2];
                tape.eval_into(x, &mut o, &mut work).unwrap();
                if let (None, Some(j)) = (&first_bad, o.iter().position(|v| !v.is_finite())) {
                    first_bad = Some(format!("output {j} at point {k}"));
                }
                want.extend_from_slice(&o);
            }
            let flat: Vec<f64> = pts.iter().flatten().copied().collect();
            let mut got = vec![0.0; 2 * pts.len()];
            let res = tape.eval_batch(&flat, &mut got, &mut eom_sym::TapeWorkspace::default());
            match (res, first_bad) {
                (Ok(()), None) => {
                    for (g, w) in got.iter().zip(&want) {
                        prop_assert_eq!(
                            g.to_bits(),
                            w.to_bits(),
                            "batch {} vs pointwise {} for {}",
                            g,
                            w,
                            e
                        );
                    }
                }
                (Err(SymError::EvalNonFinite { what, .. }), Some(bad)) => {
                    prop_assert_eq!(what, bad)
                }
                (res, bad) => {
                    prop_assert!(false, "batch {res:?}, pointwise first non-finite {bad:?}")
                }
            }
            Ok(())
        },
    );
}

/// The double-double reference itself (every tolerance above relies on it): exact identities
/// hold to ~10⁻³⁰ — `exp(x)·exp(−x) = 1`, `ln(exp x) = x`, `sin²x + cos²x = 1`,
/// `atan2(sin x, cos x) = x − 2πk`, `(√y)² = y`, `(1/y)·y = 1` — for |x| < 30.
#[test]
fn double_double_functions_satisfy_identities() {
    run(-30.0f64..30.0, |x| {
        let d = Dd::from_f64(x);
        let tol = 1e-30;
        let check = |what: &str, err: Dd, scale: f64| -> Result<(), TestCaseError> {
            let e = err.to_f64().abs();
            prop_assert!(e <= tol * scale, "{what} at x = {x}: error {e:e}");
            Ok(())
        };
        check("exp(x)·exp(−x) − 1", d.exp() * (-d).exp() - Dd::ONE, 1.0)?;
        check("ln(exp x) − x", d.exp().ln() - d, x.abs().max(1.0))?;
        let (sn, cs) = (d.sin(), d.cos());
        check("sin² + cos² − 1", sn * sn + cs * cs - Dd::ONE, 1.0)?;
        let k = (x / (2.0 * std::f64::consts::PI)).round();
        let reduced = d - Dd::PI * Dd::from_f64(2.0 * k);
        check(
            "atan2(sin x, cos x) − (x − 2πk)",
            sn.atan2(cs) - reduced,
            x.abs().max(1.0),
        )?;
        let y = d.abs() + Dd::from_f64(0.5);
        check("(√y)² − y", y.sqrt() * y.sqrt() - y, y.to_f64())?;
        check("(1/y)·y − 1", Dd::ONE / y * y - Dd::ONE, 1.0)?;
        Ok(())
    });
}

// ================================================================== (b) derivatives

/// `diff` evaluated in double-double agrees with a fourth-order central difference
/// `D(h) = [f(x−2h) − 8f(x−h) + 8f(x+h) − f(x+2h)]/(12h)` of the double-double evaluation.
///
/// * `h = 10⁻⁴·max(|x|, 1/4)`; the shifted points `x ± kh` are exact in double-double, so only
///   the truncation error (`O(h⁴)`) and the evaluation noise (`≈ 3·DD_RATIO·E_f/h`, with `E_f`
///   the running bound of `f`) matter.
/// * Richardson check: if `|D(h) − D(h/2)| > 10⁻⁹·max|D(·)|` (plus noise) the difference is not
///   resolved at this step (a pole or a kink nearby): skipped. Otherwise the error of `D(h/2)`
///   is about `|D(h) − D(h/2)|/15 ≤ 10⁻¹⁰·|D|`.
/// * Non-smooth spots: the signs of every `abs`/`ln` argument, every base with a negative or
///   fractional exponent and the `atan2` cut must be the same (and nonzero) at all stencil
///   points, else skipped.
/// * Then `|diff − D(h/2)| ≤ 10⁻⁸·max(|diff|, |D|) + 4·noise + DD_RATIO·E_diff`, where
///   `E_diff` is the running bound of the derivative. When the recipe has float constants,
///   `diff` folds new float coefficients in `f64` (`c·c/2` in `d√|c·x|/dx`), so `2·E_diff`
///   replaces `DD_RATIO·E_diff` (as for substitution).
/// * A parameter the expression does not depend on must give a structural zero.
#[test]
fn derivative_matches_finite_differences() {
    let p = params();
    let st = Stats::default();
    run((recipe(), point(), 0..N_PARAMS), |(r, x, j)| {
        Stats::bump(&st.cases);
        let e = build(&r, &p);
        if e.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        // Differentiate with respect to a parameter the expression depends on (the others give
        // a structural zero).
        let deps = e.params();
        for q in &p {
            if !deps.contains(&q.param_index().unwrap()) {
                prop_assert!(e.diff(*q).unwrap().is_zero(), "d/d{q} of {e} is not 0");
            }
        }
        let on: Vec<usize> = (0..N_PARAMS)
            .filter(|&k| deps.contains(&p[k].param_index().unwrap()))
            .collect();
        if on.is_empty() {
            Stats::bump(&st.constant);
            return Ok(());
        }
        let j = on[j % on.len()];
        let d = e.diff(p[j]).expect("derivative of a valid expression");
        prop_assert!(
            d.check().is_ok(),
            "the derivative of {e} is invalid: {:?}",
            d.check()
        );
        let pj = p[j].param_index().unwrap();
        let x0 = x[j];
        let h = 1e-4 * x0.abs().max(0.25);
        let pt = Point { p: &p, x };
        let pt = &pt;
        let at = |k: f64| {
            let shifted = Dd::from_f64(x0) + Dd::from_f64(k * h);
            move |i: u32| if i == pj { Some(shifted) } else { pt.dd_of(i) }
        };
        let offsets = [-2.0, -1.0, -0.5, 0.5, 1.0, 2.0];
        let f: Vec<Dd> = offsets.iter().map(|&k| dd_eval(e, at(k))).collect();
        let w0 = walk(&[e, d], &|i| pt.val_of(i));
        let (ef, ed) = (w0.at(e).err, w0.at(d).err);
        let ds = dd_eval(d, |i| pt.dd_of(i));
        if !f.iter().all(|v| finite(*v)) || !finite(ds) || !ef.is_finite() || !ed.is_finite() {
            Stats::bump(&st.undefined);
            return Ok(());
        }
        // Same smooth piece at every stencil point.
        let sig0 = walk(&[e], &|i| pt.val_of(i)).signature;
        let smooth = !sig0.contains(&0)
            && offsets.iter().all(|&k| {
                let shifted = Dd::from_f64(x0) + Dd::from_f64(k * h);
                let shifted = Val {
                    v: shifted,
                    err: 0.0,
                };
                let wk = walk(&[e], &|i| if i == pj { shifted } else { pt.val_of(i) });
                wk.signature == sig0
            });
        if !smooth {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        let d_h = (f[0] - Dd::from_f64(8.0) * f[1] + Dd::from_f64(8.0) * f[4] - f[5])
            / Dd::from_f64(12.0 * h);
        let d_h2 = (f[1] - Dd::from_f64(8.0) * f[2] + Dd::from_f64(8.0) * f[3] - f[4])
            / Dd::from_f64(6.0 * h);
        let noise = 3.0 * DD_RATIO * ef / h;
        let scale = ds.to_f64().abs().max(d_h2.to_f64().abs());
        // Resolution is judged on the differences alone, never on the value under test: with
        // `scale` here, a huge symbolic derivative made two random difference quotients of a
        // wildly oscillating function look converged (cos(27/p³) near p = −3·10⁻⁴).
        // Written so that NaN (a difference quotient that overflowed: `inf − x` is NaN in
        // double-double) counts as unresolved.
        let fd_scale = d_h.to_f64().abs().max(d_h2.to_f64().abs());
        let resolved = (d_h - d_h2).to_f64().abs() <= 1e-9 * fd_scale + 2.0 * noise;
        if !(finite(d_h) && finite(d_h2) && resolved) {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        // A derivative of an expression with float constants has float coefficients folded in
        // f64 at construction (c·c/2 for d√|c·x|): allow its own f64 running bound then.
        let folded = if has_float(&r) {
            2.0 * ed
        } else {
            DD_RATIO * ed
        };
        let tol = 1e-8 * scale + 4.0 * noise + folded + TINY;
        let miss = (ds - d_h2).to_f64().abs();
        prop_assert!(
            miss <= tol,
            "d/d{} of {e} = {d}: symbolic {ds} vs finite difference {d_h2}, miss {miss:e} > {tol:e}",
            p[j]
        );
        Stats::bump(&st.compared);
        // Sharp: the tolerance is the 1e-8 relative term, not the noise allowance.
        if 4.0 * noise + folded <= 1e-10 * scale {
            Stats::bump(&st.sharp);
        }
        Ok(())
    });
    st.assert_coverage("derivative", 0.6, 0.5);
}

// ================================================================== (c) substitution

/// A substituted value: an exact dyadic (folds as rationals) or a general float (folds in
/// `f64`).
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![(-24i32..25).prop_map(|k| k as f64 / 8.0), -3.0f64..3.0]
}

/// `subs_values(p_j → v)` evaluated = the original evaluated with `p_j = v`.
///
/// `subs` rebuilds through the smart constructors, so float constants fold in `f64` at
/// construction: the two sides legitimately differ by `f64` rounding errors of the
/// original's operations, bounded by the original's running bound `E` (every folded constant
/// is computed by the same operations the bound charges, in some order — the sum and product
/// bounds hold for any order). Tolerance `2·E + DD_RATIO·E_subs`. Where the original is
/// finite (and `E` finite) the substituted expression must be valid.
#[test]
fn substituting_a_value_equals_evaluating_with_it() {
    let p = params();
    let st = Stats::default();
    run(
        (recipe(), point(), 0..N_PARAMS, value()),
        |(r, mut x, j, v)| {
            Stats::bump(&st.cases);
            let e = build(&r, &p);
            if e.check().is_err() {
                Stats::bump(&st.invalid);
                return Ok(());
            }
            x[j] = v;
            let pt = Point { p: &p, x };
            let s = e
                .subs_values(&[(p[j], v)])
                .expect("subs of a valid expression");
            let orig = dd_eval(e, |i| pt.dd_of(i));
            let bound = walk(&[e], &|i| pt.val_of(i)).at(e).err;
            if !finite(orig) || !bound.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            match s.check() {
                Ok(_) => {}
                Err(SymError::RationalOverflow) => {
                    Stats::bump(&st.skipped);
                    return Ok(());
                }
                Err(err) => {
                    return Err(TestCaseError::fail(format!(
                        "{e} with {} = {v}: subs gave an error ({err}) where the value is {orig}",
                        p[j]
                    )));
                }
            }
            let pj = p[j].param_index().unwrap();
            prop_assert!(!s.params().contains(&pj), "{s} still depends on {}", p[j]);
            let subst = dd_eval(s, |i| pt.dd_of(i));
            let sb = walk(&[s], &|i| pt.val_of(i)).at(s).err;
            let tol = 2.0 * bound + DD_RATIO * sb + TINY;
            let miss = (subst - orig).to_f64().abs();
            prop_assert!(
                miss <= tol,
                "{e} with {} = {v} is {s} = {subst}, evaluation gives {orig}: miss {miss:e} > {tol:e}",
                p[j]
            );
            Stats::bump(&st.compared);
            if bound <= 1e-12 * orig.to_f64().abs() {
                Stats::bump(&st.sharp);
            }
            Ok(())
        },
    );
    st.assert_coverage("subs value", 0.7, 0.5);
}

/// `subs(p_j → r)` with an expression `r` (another recipe, which may itself contain `p_j`:
/// substitution is simultaneous) evaluated = the original evaluated with `p_j = r(x)`.
///
/// Without float constants everything stays symbolic except exact rational folding, so both
/// sides are double-double evaluations of the same function: tolerance `DD_RATIO·(E +
/// E_subs)`, where `E` includes the propagation of `r`'s own error. With float constants,
/// new float coefficients fold in `f64` (`3·(0.61/p0) → 1.84/p0`), so the tolerance is
/// `2·E + DD_RATIO·E_subs` as for values.
#[test]
fn substituting_an_expression_equals_evaluating_with_its_value() {
    let p = params();
    let st = Stats::default();
    run(
        (recipe(), recipe(), point(), 0..N_PARAMS),
        |(r1, r2, x, j)| {
            Stats::bump(&st.cases);
            let (e, rep) = (build(&r1, &p), build(&r2, &p));
            if e.check().is_err() || rep.check().is_err() {
                Stats::bump(&st.invalid);
                return Ok(());
            }
            let pt = Point { p: &p, x };
            let pj = p[j].param_index().unwrap();
            let rv = walk(&[rep], &|i| pt.val_of(i)).at(rep);
            let rdd = dd_eval(rep, |i| pt.dd_of(i));
            if !finite(rdd) || !rv.err.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            let with_r = |i: u32| if i == pj { Some(rdd) } else { pt.dd_of(i) };
            let orig = dd_eval(e, with_r);
            let bound = walk(&[e], &|i| {
                if i == pj {
                    Val {
                        v: rdd,
                        err: rv.err,
                    }
                } else {
                    pt.val_of(i)
                }
            })
            .at(e)
            .err;
            if !finite(orig) || !bound.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            let s = e.subs(&[(p[j], rep)]).expect("subs of valid expressions");
            match s.check() {
                Ok(_) => {}
                Err(SymError::RationalOverflow) => {
                    Stats::bump(&st.skipped);
                    return Ok(());
                }
                Err(err) => {
                    return Err(TestCaseError::fail(format!(
                        "{e} with {} → {rep}: subs gave an error ({err}) where the value is {orig}",
                        p[j]
                    )));
                }
            }
            let subst = dd_eval(s, |i| pt.dd_of(i));
            let sb = walk(&[s], &|i| pt.val_of(i)).at(s).err;
            let exact = !has_float(&r1) && !has_float(&r2);
            let tol = if exact { DD_RATIO * bound } else { 2.0 * bound } + DD_RATIO * sb + TINY;
            let miss = (subst - orig).to_f64().abs();
            prop_assert!(
                miss <= tol,
                "{e} with {} → {rep} is {s} = {subst}, evaluation gives {orig}: miss {miss:e} > {tol:e}",
                p[j]
            );
            Stats::bump(&st.compared);
            if exact && DD_RATIO * (bound + sb) <= 1e-20 * orig.to_f64().abs() {
                Stats::bump(&st.sharp);
            }
            Ok(())
        },
    );
    st.assert_coverage("subs expression", 0.6, 0.2);
}

// ================================================================== (d) hash-consing

/// Unique non-numeric nodes the smart constructors may add for one recipe step (see the
/// derivation in [`dag_size_is_bounded_by_the_recipe`]).
fn new_nodes(r: &Recipe) -> usize {
    use Recipe::*;
    let own = match r {
        Param(_) => 1,
        Int(_) | Rat(..) | Float(_) => 0,
        Add(..) | Sub(..) => 3,
        Mul(..) | Div(..) | Neg(_) | Powi(..) | Atan2(..) => 1,
        Sqrt(_) | Ln(_) => 4,
        Sin(_) => 3,
        Cos(_) | Exp(_) | Abs(_) => 2,
    };
    let kids: usize = match r {
        Param(_) | Int(_) | Rat(..) | Float(_) => 0,
        Add(a, b) | Sub(a, b) | Mul(a, b) | Div(a, b) | Atan2(a, b) => new_nodes(a) + new_nodes(b),
        Neg(a) | Powi(a, _) | Sqrt(a) | Sin(a) | Cos(a) | Exp(a) | Ln(a) | Abs(a) => new_nodes(a),
    };
    own + kids
}

/// Unique reachable nodes that are not numbers.
fn non_numeric(e: Expr) -> usize {
    reachable(&[e]).iter().filter(|n| !n.is_number()).count()
}

/// The recipe with every float constant replaced by a nearby exact rational (k/8).
fn exact(r: &Recipe) -> Recipe {
    use Recipe::*;
    let b = |x: &Recipe| Box::new(exact(x));
    match r {
        Float(x) => Rat((x * 8.0).round() as i64, 8),
        Param(_) | Int(_) | Rat(..) => r.clone(),
        Add(x, y) => Add(b(x), b(y)),
        Sub(x, y) => Sub(b(x), b(y)),
        Mul(x, y) => Mul(b(x), b(y)),
        Div(x, y) => Div(b(x), b(y)),
        Atan2(x, y) => Atan2(b(x), b(y)),
        Neg(x) => Neg(b(x)),
        Powi(x, n) => Powi(b(x), *n),
        Sqrt(x) => Sqrt(b(x)),
        Sin(x) => Sin(b(x)),
        Cos(x) => Cos(b(x)),
        Exp(x) => Exp(b(x)),
        Ln(x) => Ln(b(x)),
        Abs(x) => Abs(b(x)),
    }
}

fn has_float(r: &Recipe) -> bool {
    use Recipe::*;
    match r {
        Float(_) => true,
        Param(_) | Int(_) | Rat(..) => false,
        Add(a, b) | Sub(a, b) | Mul(a, b) | Div(a, b) | Atan2(a, b) => has_float(a) || has_float(b),
        Neg(a) | Powi(a, _) | Sqrt(a) | Sin(a) | Cos(a) | Exp(a) | Ln(a) | Abs(a) => has_float(a),
    }
}

/// `x` and `y` are the same node, or both invalid with the same error (invalid nodes carry
/// their own error and are not hash-consed).
fn same(x: Expr, y: Expr) -> Result<(), TestCaseError> {
    match (x.check(), y.check()) {
        (Ok(_), Ok(_)) => prop_assert_eq!(x, y),
        (Err(ex), Err(ey)) => prop_assert_eq!(ex, ey),
        (ex, ey) => prop_assert!(false, "one side invalid: {:?} vs {:?}", ex, ey),
    }
    Ok(())
}

/// Building a recipe twice gives the same node, and shared structure is stored once.
#[test]
fn building_twice_gives_the_same_node() {
    let p = params();
    run(recipe(), |r| {
        let a = build(&r, &p);
        let b = build(&r, &p);
        if a.check().is_err() {
            // Invalid nodes each carry their own error: not hash-consed, but both invalid.
            prop_assert!(b.is_invalid());
            return Ok(());
        }
        prop_assert_eq!(a, b);
        // Twice the same subexpression is stored once: a + a and a·a add at most one
        // non-numeric node (and new coefficients or exponents).
        // (A large float constant may overflow: then both sides are the same error.)
        let n = non_numeric(a);
        let twice = a + a;
        same(twice, Expr::int(2) * a)?;
        if twice.check().is_ok() {
            prop_assert!(non_numeric(twice) <= n + 1, "{a} + {a}");
        }
        let sq = a * a;
        same(sq, a.powi(2))?;
        if sq.check().is_ok() {
            prop_assert!(non_numeric(sq) <= n + 1, "{a}·{a}");
        }
        prop_assert_eq!(a - a, Expr::zero());
        prop_assert_eq!(a + Expr::zero(), a);
        prop_assert_eq!(a * Expr::one(), a);
        Ok(())
    });
}

/// `dag_size` counts unique reachable nodes (checked against a DFS here), and the non-numeric
/// ones are bounded by the recipe: each recipe step adds its result node plus at most a fixed
/// number of auxiliary nodes — a unit product for each operand of a sum that carries a
/// coefficient (≤ 2, so `+`/`−` ≤ 3); the positive form of a negated argument and the negated
/// result of an odd function (`sin` ≤ 3); `abs` of a negated argument (≤ 2), then for `sqrt` the
/// `abs` of a base with an even power (`sqrt` ≤ 4); `ln(|a| + 1/2)` ≤ 4 (abs ≤ 2, a unit
/// product, the sum, the ln). Everything else that is built along the way (intermediate
/// powers, `−b` inside `a − b`) is flattened into the result and no longer reachable. Numbers
/// (coefficients, exponents, constants) are counted separately.
#[test]
fn dag_size_is_bounded_by_the_recipe() {
    let p = params();
    run(recipe(), |r| {
        let e = build(&r, &p);
        if e.check().is_err() {
            return Ok(());
        }
        let nodes = reachable(&[e]);
        prop_assert_eq!(Expr::dag_size(&[e]), nodes.len());
        let count = non_numeric(e);
        let bound = new_nodes(&r);
        prop_assert!(count <= bound, "{e}: {count} non-numeric nodes > {bound}");
        Ok(())
    });
}

/// Canonical forms do not depend on the order of operations: `a + b = b + a`, `a·b = b·a`,
/// and, with the float constants replaced by exact ones (float arithmetic is not associative:
/// a folded coefficient depends on the order), `(a + b) + c = a + (b + c)` and
/// `(a·b)·c = a·(b·c)`; the latter only
/// when no operand or partial product is a number (a number times a sum is distributed, a
/// number times a product is not: `(2·s)·x ≠ 2·(s·x)` for a sum `s`, a known limitation).
#[test]
fn canonical_forms_are_order_independent() {
    let p = params();
    let st = Stats::default();
    run((recipe(), recipe(), recipe()), |(ra, rb, rc)| {
        Stats::bump(&st.cases);
        let (a, b, c) = (build(&ra, &p), build(&rb, &p), build(&rc, &p));
        if a.check().is_err() || b.check().is_err() || c.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        same(a + b, b + a)?;
        same(a * b, b * a)?;
        // Associativity on the exact versions of the recipes.
        let (a, b, c) = (
            build(&exact(&ra), &p),
            build(&exact(&rb), &p),
            build(&exact(&rc), &p),
        );
        if a.check().is_err() || b.check().is_err() || c.check().is_err() {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        same((a + b) + c, a + (b + c))?;
        same(Expr::sum([a, b, c]), (c + a) + b)?;
        let numeric = [a, b, c, a * b, b * c].iter().any(|x| x.is_number());
        if !numeric {
            same((a * b) * c, a * (b * c))?;
            Stats::bump(&st.compared);
        }
        Ok(())
    });
    st.report("canonical");
}
