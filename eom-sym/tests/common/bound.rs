//! The reference of the evaluation properties: a double-double walk of a DAG with a running
//! bound of the error of an `f64` evaluation, and the runner that counts compared cases.
//!
//! No fixed relative tolerance is used for evaluation: a random expression can cancel
//! catastrophically (`p0 − p0·(1 + 1e-12)`) and then no relative tolerance is right. Instead
//! an independent evaluator written here (`walk`, over `Expr::view`, in double-double)
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
//! evaluation (rule in the test `derivative_matches_finite_differences`).

use super::N_PARAMS;
use eom_sym::{Constant, Dd, Expr, ExprView, Func, Rational, Scalar, eval_generic};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestRunner};
use std::cell::Cell;
use std::collections::HashMap;

/// Cases per property (the brief asks for at least 1 000).
pub const CASES: u32 = 2_000;
/// Unit roundoff of `f64`.
pub const U: f64 = f64::EPSILON / 2.0;
/// Charged for each libm function call: 2 ulps.
pub const FU: f64 = 4.0 * U;
/// Double-double error relative to the `f64` running bound (see the module docs).
pub const DD_RATIO: f64 = 1.0 / (1u64 << 36) as f64;
/// Absolute slack for results that are exactly zero (subnormal rounding).
pub const TINY: f64 = 1e-300;

// ================================================================== the reference walker

/// Value (double-double) and running bound of the `f64` evaluation error of one node.
#[derive(Clone, Copy, Debug)]
pub struct Val {
    pub v: Dd,
    pub err: f64,
}

/// The walk of a DAG at one point.
pub struct Walk {
    pub vals: HashMap<u32, Val>,
    /// Signs at the non-smooth spots (abs, ln, negative or fractional powers, atan2 cut): two
    /// points with the same signature are on the same smooth piece.
    pub signature: Vec<i8>,
}

impl Walk {
    pub fn at(&self, e: Expr) -> Val {
        self.vals[&e.id()]
    }
}

/// All nodes reachable from `roots`, in increasing id (a topological order).
pub fn reachable(roots: &[Expr]) -> Vec<Expr> {
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

pub fn sign(d: Dd) -> i8 {
    if d.hi > 0.0 {
        1
    } else if d.hi < 0.0 {
        -1
    } else {
        0
    }
}

/// `k` roundings compounded: `γ_k = k·u/(1 − k·u)`.
pub fn gamma(k: u32) -> f64 {
    let k = k as f64;
    k * U / (1.0 - k * U)
}

/// `(1 + a)(1 + b) − 1` without cancellation.
pub fn compose(a: f64, b: f64) -> f64 {
    a + b + a * b
}

/// The power as the tape and `eval_generic` compute it (reference in double-double).
pub fn pow_dd(b: Dd, e: &Rational) -> Dd {
    match e.as_small() {
        Some((n, 1)) => b.powi(n),
        Some((1, 2)) => b.sqrt(),
        Some((-1, 2)) => Dd::ONE / b.sqrt(),
        _ => b.powf(Dd::from_rational(e)),
    }
}

/// Relative rounding error of computing `b^e` in `f64` from an exact `b`.
pub fn pow_rounding(e: &Rational, b: f64) -> f64 {
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
pub fn walk(roots: &[Expr], param: &dyn Fn(u32) -> Val) -> Walk {
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
pub struct Point<'a> {
    pub p: &'a [Expr],
    pub x: [f64; N_PARAMS],
}

impl Point<'_> {
    pub fn slot(&self, index: u32) -> Option<usize> {
        self.p.iter().position(|q| q.param_index() == Some(index))
    }
    pub fn f64_of(&self, index: u32) -> Option<f64> {
        self.slot(index).map(|k| self.x[k])
    }
    pub fn dd_of(&self, index: u32) -> Option<Dd> {
        self.f64_of(index).map(Dd::from_f64)
    }
    pub fn val_of(&self, index: u32) -> Val {
        Val {
            v: self.dd_of(index).expect("recipe parameter"),
            err: 0.0,
        }
    }
}

pub fn dd_eval(e: Expr, value_of: impl Fn(u32) -> Option<Dd>) -> Dd {
    eval_generic::<Dd>(&[e], value_of).expect("valid expression")[0]
}

pub fn finite(d: Dd) -> bool {
    d.is_finite()
}

/// A point: four values in (−3, 3).
pub fn point() -> impl Strategy<Value = [f64; N_PARAMS]> {
    prop::array::uniform4(-3.0f64..3.0)
}

/// Counters of one property: how many cases were compared, skipped and why.
#[derive(Default)]
pub struct Stats {
    pub cases: Cell<u32>,
    pub invalid: Cell<u32>,
    pub undefined: Cell<u32>,
    pub constant: Cell<u32>,
    pub skipped: Cell<u32>,
    pub compared: Cell<u32>,
    pub sharp: Cell<u32>,
}

impl Stats {
    pub fn bump(c: &Cell<u32>) {
        c.set(c.get() + 1);
    }
    pub fn report(&self, name: &str) {
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
    pub fn assert_coverage(&self, name: &str, min_compared: f64, min_sharp: f64) {
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

pub fn runner() -> TestRunner {
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

pub fn run<S: Strategy>(strategy: S, test: impl Fn(S::Value) -> Result<(), TestCaseError>)
where
    S::Value: std::fmt::Debug,
{
    if let Err(e) = runner().run(&strategy, test) {
        panic!("{e}");
    }
}

// ================================================================== (a) evaluation
