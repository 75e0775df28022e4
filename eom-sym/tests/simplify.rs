//! Tests of `eom_sym::simplify`: the bounded egg pass and the rational normal form.
//!
//! Values are compared with a *running error bound* instead of a fixed tolerance: every
//! expression is evaluated in [`Bound`], an `f64` together with a rigorous bound on its
//! absolute error with respect to the exact value at the same (exact) parameter values. A
//! simplification is an identity, so the exact values of input and output agree, and the two
//! computed values must lie within the sum of their bounds. Cancellation widens the bound
//! exactly where the `f64` result deserves less trust, and nowhere else.
//!
//! Points where the **input** is undefined (division by an exact zero, or a denominator that
//! its own error bound cannot separate from zero) are skipped; points where only the output's
//! bound is unbounded are counted as unverifiable. Each property test also asserts that most
//! points were actually checked, so the comparison can never pass vacuously.

mod common;

use eom_sym::simplify::{
    Normalized, RationalNormalizer, Simplifier, StopReason, WorkLimit, normalize_rational,
};
use eom_sym::testing::{SplitMix, params, random_dag};
use eom_sym::{
    Assumption, CostModel, Elementary, Expr, ParamInfo, Rational, Scalar, SparseMatrix, SymError,
    eval_generic,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::time::Duration;

// ------------------------------------------------------------------ running error bounds

/// Twice the unit roundoff: one rounding of a basic operation, and libm's elementary functions
/// (within one ulp) with margin.
const U: f64 = f64::EPSILON;

/// A computed value `v`, a bound `e` on `|v − exact|`, and whether the exact value provably
/// does not exist (division by an exact zero and the like).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bound {
    v: f64,
    e: f64,
    undefined: bool,
}

impl Bound {
    fn exact(v: f64) -> Bound {
        Bound {
            v,
            e: 0.0,
            undefined: false,
        }
    }
    /// A rounded result: the propagated bound plus one rounding.
    fn rounded(v: f64, e: f64, inputs: &[Bound]) -> Bound {
        let undefined = inputs.iter().any(|b| b.undefined);
        let e = if v.is_finite() {
            e + U * v.abs()
        } else {
            f64::INFINITY
        };
        Bound { v, e, undefined }
    }
    fn unbounded(v: f64, inputs: &[Bound]) -> Bound {
        Bound {
            v,
            e: f64::INFINITY,
            undefined: inputs.iter().any(|b| b.undefined),
        }
    }
    fn undefined() -> Bound {
        Bound {
            v: f64::NAN,
            e: f64::INFINITY,
            undefined: true,
        }
    }
    fn trusted(&self) -> bool {
        !self.undefined && self.v.is_finite() && self.e.is_finite()
    }
}

impl Add for Bound {
    type Output = Bound;
    fn add(self, o: Bound) -> Bound {
        Bound::rounded(self.v + o.v, self.e + o.e, &[self, o])
    }
}
impl Sub for Bound {
    type Output = Bound;
    fn sub(self, o: Bound) -> Bound {
        Bound::rounded(self.v - o.v, self.e + o.e, &[self, o])
    }
}
impl Mul for Bound {
    type Output = Bound;
    fn mul(self, o: Bound) -> Bound {
        let e = self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e;
        Bound::rounded(self.v * o.v, e, &[self, o])
    }
}
impl Div for Bound {
    type Output = Bound;
    fn div(self, o: Bound) -> Bound {
        if o.v == 0.0 && o.e == 0.0 {
            return Bound::undefined();
        }
        let q = self.v / o.v;
        if o.v.abs() <= o.e {
            return Bound::unbounded(q, &[self, o]);
        }
        // |(a+δa)/(b+δb) − a/b| ≤ (|δa| + |a/b|·|δb|) / (|b| − |δb|)
        Bound::rounded(q, (self.e + q.abs() * o.e) / (o.v.abs() - o.e), &[self, o])
    }
}
impl Neg for Bound {
    type Output = Bound;
    fn neg(self) -> Bound {
        Bound { v: -self.v, ..self }
    }
}

impl Scalar for Bound {
    fn zero() -> Bound {
        Bound::exact(0.0)
    }
    fn one() -> Bound {
        Bound::exact(1.0)
    }
    fn from_i64(n: i64) -> Bound {
        if n.unsigned_abs() <= 1 << 53 {
            Bound::exact(n as f64)
        } else {
            Bound::rounded(n as f64, 0.0, &[])
        }
    }
    fn from_rational(r: &Rational) -> Bound {
        Bound::rounded(r.to_f64(), 0.0, &[])
    }
    fn from_f64(x: f64) -> Bound {
        Bound::exact(x)
    }
    fn pi() -> Bound {
        Bound::rounded(std::f64::consts::PI, 0.0, &[])
    }
    fn sqrt(self) -> Bound {
        if self.v + self.e < 0.0 {
            return Bound::undefined();
        }
        let r = self.v.max(0.0).sqrt();
        // |√x − √y| ≤ √|x − y|, and ≤ |x − y| / (√(y − e) + √y) away from zero.
        let mut e = self.e.sqrt();
        if self.v - self.e > 0.0 {
            e = e.min(self.e / ((self.v - self.e).sqrt() + r));
        }
        Bound::rounded(self.v.sqrt(), e, &[self])
    }
    fn sin(self) -> Bound {
        Bound::rounded(self.v.sin(), self.e + U, &[self])
    }
    fn cos(self) -> Bound {
        Bound::rounded(self.v.cos(), self.e + U, &[self])
    }
    fn abs(self) -> Bound {
        Bound {
            v: self.v.abs(),
            ..self
        }
    }
    fn nominal(&self) -> f64 {
        self.v
    }
    fn is_zero(&self) -> bool {
        self.v == 0.0 && self.e == 0.0 && !self.undefined
    }
    fn is_one(&self) -> bool {
        self.v == 1.0 && self.e == 0.0 && !self.undefined
    }
}

impl Elementary for Bound {
    fn tan(self) -> Bound {
        let c = self.v.cos().abs();
        if c <= self.e + U {
            return Bound::unbounded(self.v.tan(), &[self]);
        }
        // |tan′| = sec² ≤ 1 / (|cos v| − e)² on the interval.
        Bound::rounded(self.v.tan(), self.e / (c - self.e - U).powi(2), &[self])
    }
    fn exp(self) -> Bound {
        let v = self.v.exp();
        Bound::rounded(v, v * self.e.exp_m1(), &[self])
    }
    fn ln(self) -> Bound {
        if self.v + self.e <= 0.0 {
            return Bound::undefined();
        }
        if self.v - self.e <= 0.0 {
            return Bound::unbounded(self.v.ln(), &[self]);
        }
        Bound::rounded(self.v.ln(), self.e / (self.v - self.e) + U, &[self])
    }
    fn atan2(self, x: Bound) -> Bound {
        let v = self.v.atan2(x.v);
        let r = self.v.hypot(x.v);
        let d = self.e + x.e;
        // Unbounded near the origin and across the branch cut (x < 0, y ≈ 0).
        if r <= d || (x.v < 0.0 && self.v.abs() <= self.e) {
            return Bound::unbounded(v, &[self, x]);
        }
        Bound::rounded(v, d / (r - d), &[self, x])
    }
    fn powf(self, e: Bound) -> Bound {
        let v = self.v.powf(e.v);
        if self.v - self.e <= 0.0 {
            return Bound::unbounded(v, &[self, e]);
        }
        // x^y = exp(y ln x)
        let la = self.v.ln();
        let ela = self.e / (self.v - self.e) + U;
        let ebl = e.v.abs() * ela + la.abs() * e.e + ela * e.e;
        Bound::rounded(v, v.abs() * ebl.exp_m1() + U * v.abs(), &[self, e])
    }
}

#[derive(Default, Debug)]
struct Tally {
    checked: usize,
    skipped: usize,
    unverifiable: usize,
}

/// Compare `a` and `b` (same length) at `points` random parameter points, magnitudes in
/// [0.25, 3), random signs unless a parameter is declared non-negative.
fn same_values(
    a: &[Expr],
    b: &[Expr],
    ps: &[Expr],
    seed: u64,
    points: usize,
    tally: &mut Tally,
) -> Result<(), String> {
    same_values_in(a, b, ps, seed, points, (0.25, 3.0), tally)
}

fn same_values_in(
    a: &[Expr],
    b: &[Expr],
    ps: &[Expr],
    seed: u64,
    points: usize,
    range: (f64, f64),
    tally: &mut Tally,
) -> Result<(), String> {
    assert_eq!(a.len(), b.len());
    let mut rng = SplitMix(seed);
    for _ in 0..points {
        let vals: Vec<(u32, f64)> = ps
            .iter()
            .map(|p| {
                let m = rng.uniform(range.0, range.1);
                let info = p.param_info().expect("parameter");
                let positive =
                    matches!(info.assume, Assumption::Positive | Assumption::Nonnegative);
                let sign = if positive || rng.below(2) == 0 {
                    1.0
                } else {
                    -1.0
                };
                (p.param_index().expect("parameter"), sign * m)
            })
            .collect();
        let value_of = |i: u32| vals.iter().find(|v| v.0 == i).map(|v| Bound::exact(v.1));
        let va = eval_generic::<Bound>(a, value_of).map_err(|e| e.to_string())?;
        let vb = eval_generic::<Bound>(b, value_of).map_err(|e| e.to_string())?;
        for (k, (x, y)) in va.iter().zip(&vb).enumerate() {
            if !x.trusted() {
                tally.skipped += 1;
                continue;
            }
            if y.undefined {
                return Err(format!(
                    "entry {k}: the result is undefined where the input is {x:?}\n  {} \n  {}",
                    a[k], b[k]
                ));
            }
            if !y.trusted() {
                tally.unverifiable += 1;
                continue;
            }
            if (x.v - y.v).abs() > x.e + y.e {
                return Err(format!(
                    "entry {k}: {} ± {:e} vs {} ± {:e} at {vals:?}\n  input  {}\n  output {}",
                    x.v, x.e, y.v, y.e, a[k], b[k]
                ));
            }
            tally.checked += 1;
        }
    }
    Ok(())
}

fn check_tally(t: &Tally, what: &str) {
    let total = t.checked + t.skipped + t.unverifiable;
    eprintln!("{what}: {t:?}");
    assert!(total > 0);
    assert!(
        t.checked * 10 >= total * 7,
        "{what}: too few points checked: {t:?}"
    );
}

// ------------------------------------------------------------------ helpers

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

/// `C = Aᵀ·B·A` for a sparse 6×6 `A` (55 % nonzeros: a parameter, a product, a sum or `−2·p`)
/// and a symmetric `B`, over 16 positive parameters, as in the crate notes.
fn atba(seed: u64) -> (SparseMatrix<Expr>, Vec<Expr>) {
    let p = params(16, seed, true);
    let mut rng = SplitMix(seed);
    let n = 6;
    let mut a = SparseMatrix::zeros(n, n);
    let mut b = SparseMatrix::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            if rng.uniform(0.0, 1.0) < 0.55 {
                let x = p[rng.below(16)];
                let y = p[rng.below(16)];
                let v = match rng.below(4) {
                    0 => x,
                    1 => x * y,
                    2 => x + y,
                    _ => -Expr::int(2) * x,
                };
                a.set(i, j, v);
            }
            if j >= i && rng.uniform(0.0, 1.0) < 0.5 {
                let v = p[rng.below(16)];
                b.set(i, j, v);
                b.set(j, i, v);
            }
        }
    }
    (a.transpose().mul(&b).unwrap().mul(&a).unwrap(), p)
}

// ------------------------------------------------------------------ egg pass: properties

#[test]
fn egg_pass_preserves_values_and_never_raises_the_cost() {
    let mut runner = TestRunner::new(Config {
        cases: 192,
        ..Config::default()
    });
    let strategy = (prop::collection::vec(common::recipe(), 1..5), any::<u64>());
    let tally = std::cell::RefCell::new(Tally::default());
    runner
        .run(&strategy, |(recipes, seed)| {
            let ps = common::params();
            let roots: Vec<Expr> = recipes.iter().map(|r| common::build(r, &ps)).collect();
            prop_assume!(roots.iter().all(|r| r.check().is_ok()));
            let out = Simplifier::default()
                .run(&roots)
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            let w = CostModel::default();
            prop_assert_eq!(out.cost_before, w.of(&roots));
            prop_assert_eq!(
                w.of(&out.roots),
                if out.kept {
                    out.cost_after
                } else {
                    out.cost_before
                }
            );
            if out.kept {
                prop_assert!(out.cost_after < out.cost_before);
            } else {
                prop_assert_eq!(&out.roots, &roots);
            }
            prop_assert!(out.roots.iter().all(|r| r.check().is_ok()));
            same_values(&roots, &out.roots, &ps, seed, 4, &mut tally.borrow_mut())
                .map_err(TestCaseError::fail)?;
            Ok(())
        })
        .unwrap();
    check_tally(&tally.borrow(), "egg pass on random recipes");
}

/// Sums of monomials `c·Π pᵢ^eᵢ` with exponents −2…3 over a mix of unconstrained and
/// positive parameters: this is where factoring, cancellation and collection fire most.
#[test]
fn egg_pass_on_random_laurent_sums_preserves_values() {
    let term = (-4i64..5, prop::collection::vec(-2i64..4, 5));
    let root = prop::collection::vec(term, 2..7);
    let strategy = (prop::collection::vec(root, 1..4), any::<u64>());
    let mut runner = TestRunner::new(Config {
        cases: 128,
        ..Config::default()
    });
    let tally = std::cell::RefCell::new(Tally::default());
    let kept = std::cell::Cell::new(0usize);
    runner
        .run(&strategy, |(roots, seed)| {
            let ps: Vec<Expr> = (0..5)
                .map(|i| {
                    let assume = if i < 2 {
                        Assumption::Positive
                    } else {
                        Assumption::Real
                    };
                    param(&format!("q{i}"), 0.5 + i as f64 * 0.3, assume)
                })
                .collect();
            let exprs: Vec<Expr> = roots
                .iter()
                .map(|terms| {
                    Expr::sum(terms.iter().map(|(c, es)| {
                        Expr::int(*c) * Expr::product(es.iter().zip(&ps).map(|(e, p)| p.powi(*e)))
                    }))
                })
                .collect();
            let out = Simplifier::default()
                .run(&exprs)
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert_eq!(
                CostModel::default().of(&out.roots),
                if out.kept {
                    out.cost_after
                } else {
                    out.cost_before
                }
            );
            if out.kept {
                kept.set(kept.get() + 1);
                prop_assert!(out.cost_after < out.cost_before);
            }
            same_values(&exprs, &out.roots, &ps, seed, 4, &mut tally.borrow_mut())
                .map_err(TestCaseError::fail)?;
            Ok(())
        })
        .unwrap();
    assert!(
        kept.get() >= 64,
        "only {} of 128 sums were simplified",
        kept.get()
    );
    check_tally(&tally.borrow(), "egg pass on Laurent sums");
}

/// The comparison itself can fail: a relative perturbation of 1e-12 is far outside the bound
/// of a well-conditioned expression.
#[test]
fn the_value_check_detects_small_errors() {
    let a = param("a", 1.0, Assumption::Real);
    let b = param("b", 2.0, Assumption::Real);
    let e = a * b + a.sin();
    let wrong = e * Expr::float(1.0 + 1e-12).unwrap();
    let mut tally = Tally::default();
    assert!(same_values(&[e], &[wrong], &[a, b], 1, 4, &mut tally).is_err());
    assert!(same_values(&[e], &[a.sin() + b * a], &[a, b], 1, 4, &mut tally).is_ok());
}

/// Heavily shared DAGs. Big ones overflow (repeated squaring reaches 1e165 and beyond), so
/// these are small enough for their values to stay finite near the nominal range
/// `random_dag` is designed for (parameters in [0.5, 2)).
#[test]
fn egg_pass_on_random_dags_preserves_values() {
    let mut tally = Tally::default();
    for seed in 0..8 {
        let p = params(8, seed, seed % 2 == 0);
        let roots = random_dag(&p, 250, 12, seed);
        let out = Simplifier::default().run(&roots).unwrap();
        assert!(out.cost_after < out.cost_before || !out.kept);
        assert_eq!(
            CostModel::default().of(&out.roots),
            if out.kept {
                out.cost_after
            } else {
                out.cost_before
            }
        );
        same_values_in(
            &roots,
            &out.roots,
            &p,
            100 + seed,
            6,
            (0.5, 2.0),
            &mut tally,
        )
        .unwrap();
    }
    check_tally(&tally, "egg pass on random DAGs");
}

// ------------------------------------------------------------------ egg pass: the rules

#[test]
fn factoring_and_cancellation_respect_the_pools_nonzero_condition() {
    let x = param("x", 0.7, Assumption::Real);
    let y = param("y", 1.3, Assumption::Real);
    let a = param("a", 2.0, Assumption::Positive);
    let m = param("m", 2.0, Assumption::Real);
    let k = param("k", 8.0, Assumption::Real);
    // a > 0: (a·x + a·y)/a → x + y.
    let e = (a * x + a * y) / a;
    let out = Simplifier::default().run(&[e]).unwrap();
    assert!(out.kept);
    assert_eq!(out.roots[0], x + y);
    // m may vanish: the textbook case keeps m/m (the rational normal form cancels it).
    let t = (m * k + k * m) / (Expr::int(2) * m);
    let out = Simplifier::default().run(&[t]).unwrap();
    assert_ne!(out.roots[0], k);
    let mut tally = Tally::default();
    same_values(&[t], &out.roots, &[m, k], 7, 20, &mut tally).unwrap();
    assert_eq!(normalize_rational(t).unwrap(), k);
    // Plain factoring: a·x + a·y → a·(x + y).
    let out = Simplifier::default().run(&[m * x + m * y]).unwrap();
    assert!(out.kept);
    assert_eq!(out.roots[0], m * (x + y));
    assert_eq!((out.cost_before, out.cost_after), (3, 2));
}

#[test]
fn trigonometric_rules() {
    let a = param("a", 0.3, Assumption::Real);
    let b = param("b", 1.1, Assumption::Real);
    let c = param("c", 2.0, Assumption::Real);
    let s = Simplifier::default();
    // c·sin²a + c·cos²a → c (the pool folds numeric c itself; a symbolic c needs factoring).
    let out = s
        .run(&[c * a.sin().powi(2) + c * a.cos().powi(2) + b])
        .unwrap();
    assert_eq!(out.roots[0], c + b);
    // 2 − 2·sin²a → 2·cos²a
    let out = s
        .run(&[Expr::int(2) - Expr::int(2) * a.sin().powi(2)])
        .unwrap();
    assert_eq!(out.roots[0], Expr::int(2) * a.cos().powi(2));
    // angle sums, both signs, with a common factor
    let cases = [
        (a.cos() * b.cos() - a.sin() * b.sin(), (a + b).cos()),
        (a.cos() * b.cos() + a.sin() * b.sin(), (a - b).cos()),
        (
            c * (a.sin() * b.cos() + a.cos() * b.sin()),
            c * (a + b).sin(),
        ),
        (a.sin() * b.cos() - a.cos() * b.sin(), (a - b).sin()),
    ];
    for (input, expect) in cases {
        let out = s.run(&[input]).unwrap();
        assert!(out.kept, "{input}");
        assert_eq!(out.roots[0], expect, "{input}");
        let mut tally = Tally::default();
        same_values(&[input], &out.roots, &[a, b, c], 3, 10, &mut tally).unwrap();
        assert_eq!(tally.checked, 10);
    }
    // Without the trig rules nothing of this happens.
    let input = a.cos() * b.cos() - a.sin() * b.sin();
    let out = s.clone().with_trig_rules(false).run(&[input]).unwrap();
    assert!(!out.kept);
}

// ------------------------------------------------------------------ egg pass: matrices

#[test]
fn atba_is_simplified_jointly_and_sharing_across_entries_pays() {
    let w = CostModel::default();
    for seed in 1..=3 {
        let (c, p) = atba(seed);
        let (simplified, out) = Simplifier::default().run_matrix(&c).unwrap();
        assert!(out.kept, "seed {seed}: {out:?}");
        assert!(out.cost_after < out.cost_before);
        let entries: Vec<Expr> = c.iter().map(|e| e.2).collect();
        let after: Vec<Expr> = c.iter().map(|(i, j, _)| simplified.get(i, j)).collect();
        assert_eq!(w.of(&after), out.cost_after);
        let mut tally = Tally::default();
        same_values(&entries, &after, &p, seed, 6, &mut tally).unwrap();
        check_tally(&tally, "AᵀBA");
        // Entry by entry, each entry's local optimum ignores what the others share.
        let separate: Vec<Expr> = entries
            .iter()
            .map(|&e| Simplifier::default().run(&[e]).unwrap().roots[0])
            .collect();
        let separate_cost = w.of(&separate);
        eprintln!(
            "AᵀBA seed {seed}: input {} joint {} entry-by-entry {}",
            out.cost_before, out.cost_after, separate_cost
        );
        assert!(
            out.cost_after < separate_cost,
            "seed {seed}: joint {} separate {separate_cost}",
            out.cost_after
        );
    }
}

// ------------------------------------------------------------------ egg pass: limits

#[test]
fn limits_stop_the_pass_cleanly_with_the_reason() {
    let (c, p) = atba(1);
    let roots: Vec<Expr> = c.iter().map(|e| e.2).collect();
    let full = Simplifier::default().run(&roots).unwrap();
    assert!(full.egraph_nodes > 300);
    // Node limit between the input's size and the saturated size.
    let limit = full.egraph_nodes - 100;
    let out = Simplifier::default()
        .with_node_limit(limit)
        .run(&roots)
        .unwrap();
    assert_eq!(out.stop, StopReason::NodeLimit);
    // The appliers stop adding past the limit: the overshoot is at most one proposal.
    assert!(
        out.egraph_nodes <= limit + 64,
        "{} nodes for a limit of {limit}",
        out.egraph_nodes
    );
    // Time limit zero: stops before rewriting anything.
    let out = Simplifier::default()
        .with_time_limit(Duration::ZERO)
        .run(&roots)
        .unwrap();
    assert_eq!(out.stop, StopReason::TimeLimit);
    assert!(!out.kept);
    assert_eq!(out.roots, roots);
    // Iteration limit.
    let out = Simplifier::default()
        .with_iter_limit(1)
        .run(&roots)
        .unwrap();
    assert_eq!(out.stop, StopReason::IterationLimit);
    assert_eq!(out.iterations, 1);
    // Stall hook: stop at the first iteration that does not improve the extracted cost.
    let out = Simplifier::default()
        .with_stall_iterations(1)
        .run(&roots)
        .unwrap();
    assert_eq!(out.stop, StopReason::CostStalled);
    // Whatever stopped it, the result is valid and has the input's values.
    let mut tally = Tally::default();
    same_values(&roots, &out.roots, &p, 5, 3, &mut tally).unwrap();
    // A big random DAG under a small time budget stops on time.
    let q = params(10, 9, true);
    let big = random_dag(&q, 5000, 36, 9);
    let out = Simplifier::default()
        .with_time_limit(Duration::from_millis(1))
        .run(&big)
        .unwrap();
    assert_eq!(out.stop, StopReason::TimeLimit);
    assert!(out.iterations <= 2);
}

#[test]
fn degenerate_inputs() {
    let s = Simplifier::default();
    let out = s.run(&[]).unwrap();
    assert_eq!(out.stop, StopReason::NothingToDo);
    let a = param("a", 1.0, Assumption::Real);
    let out = s.run(&[a, Expr::int(3)]).unwrap();
    assert_eq!(out.stop, StopReason::NothingToDo);
    assert_eq!(out.roots, vec![a, Expr::int(3)]);
    let bad = a / Expr::zero();
    assert!(matches!(s.run(&[a, bad]), Err(SymError::Invalid(_))));
    assert!(matches!(normalize_rational(bad), Err(SymError::Invalid(_))));
}

// ------------------------------------------------------------------ rational normal form

#[test]
fn rational_normal_form_textbook_cases() {
    let m = param("m", 2.0, Assumption::Real);
    let k = param("k", 8.0, Assumption::Real);
    let a = param("a", 1.5, Assumption::Real);
    let b = param("b", 0.5, Assumption::Real);
    assert_eq!(
        normalize_rational((m * k + k * m) / (Expr::int(2) * m)).unwrap(),
        k
    );
    assert_eq!(
        normalize_rational((a.powi(2) - b.powi(2)) / (a - b)).unwrap(),
        a + b
    );
    assert_eq!(
        normalize_rational(a.recip() + b.recip()).unwrap(),
        (a + b) / (a * b)
    );
    // Opaque atoms: (sin²x − 1)/(sin x − 1) = sin x + 1.
    let x = param("x", 0.2, Assumption::Real);
    assert_eq!(
        normalize_rational((x.sin().powi(2) - 1) / (x.sin() - 1)).unwrap(),
        x.sin() + 1
    );
    // Rational powers: with s = |a|^(1/2) the pool writes s² as |a|, so |a| and s must be one
    // atom: (s³ − s)/(s² − 1) = s.
    let s = a.abs().sqrt();
    assert_eq!(
        normalize_rational((s.powi(3) - s) / (s.powi(2) - 1)).unwrap(),
        s
    );
    // A denominator that vanishes identically is an error, not a silent result.
    let zero_den = ((a + b).powi(2) - a.powi(2) - Expr::int(2) * a * b - b.powi(2)).recip();
    assert!(matches!(
        normalize_rational(zero_den),
        Err(SymError::DivisionByZero { .. })
    ));
    // Normalised leading coefficient: the denominator is monic, the numerator carries the
    // constant.
    let e =
        (Expr::int(6) * a + Expr::int(3) * b) / (Expr::int(4) * a * b + Expr::int(2) * b.powi(2));
    match RationalNormalizer::default().normalize(e).unwrap() {
        Normalized::Form(f) => {
            assert_eq!(f.to_expr(), Expr::rational(3, 2).unwrap() / b);
            assert_eq!(f.denominator, b);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn rational_normal_form_bounds_are_reported_promptly() {
    let v: Vec<Expr> = (0..4)
        .map(|i| param(&format!("v{i}"), 1.0 + i as f64, Assumption::Real))
        .collect();
    let big = Expr::sum(v.iter().copied()).powi(30) / (v[0] - v[1]);
    let start = std::time::Instant::now();
    let r = RationalNormalizer::default()
        .with_max_terms(200)
        .normalize(big)
        .unwrap();
    assert_eq!(r, Normalized::TooLarge(WorkLimit::Terms));
    assert_eq!(
        normalize_rational(big).unwrap(),
        big,
        "the default bounds also refuse it"
    );
    let r = RationalNormalizer::default()
        .with_max_degree(10)
        .normalize(big)
        .unwrap();
    assert_eq!(r, Normalized::TooLarge(WorkLimit::Degree));
    let r = RationalNormalizer::default()
        .with_max_work(100)
        .normalize((v[0] + v[1] + v[2]).powi(8) * (v[2] - v[3]).recip())
        .unwrap();
    assert_eq!(r, Normalized::TooLarge(WorkLimit::Work));
    let r = RationalNormalizer::default()
        .with_max_atoms(3)
        .normalize(big)
        .unwrap();
    assert_eq!(r, Normalized::TooLarge(WorkLimit::Atoms));
    assert!(start.elapsed() < Duration::from_secs(5));
}

#[test]
fn rational_normal_form_preserves_values() {
    let mut runner = TestRunner::new(Config {
        cases: 256,
        ..Config::default()
    });
    let strategy = (common::recipe(), any::<u64>());
    let tally = std::cell::RefCell::new(Tally::default());
    let formed = std::cell::Cell::new(0usize);
    runner
        .run(&strategy, |(recipe, seed)| {
            let ps = common::params();
            let e = common::build(&recipe, &ps);
            prop_assume!(e.check().is_ok());
            let n = match RationalNormalizer::default().normalize(e) {
                Ok(Normalized::Form(f)) => {
                    formed.set(formed.get() + 1);
                    f.to_expr()
                }
                Ok(Normalized::TooLarge(_)) => return Ok(()),
                // The input is nowhere defined as a rational function: check that it really
                // has no value at the points (its denominator vanishes identically).
                Err(SymError::DivisionByZero { .. }) => {
                    let mut rng = SplitMix(seed);
                    for _ in 0..4 {
                        let vals: Vec<(u32, f64)> = ps
                            .iter()
                            .map(|p| (p.param_index().unwrap(), rng.uniform(-3.0, 3.0)))
                            .collect();
                        let v = eval_generic::<Bound>(&[e], |i| {
                            vals.iter().find(|v| v.0 == i).map(|v| Bound::exact(v.1))
                        });
                        prop_assert!(
                            v.map_or(true, |v| !v[0].trusted()),
                            "{} has a trusted value at {:?}",
                            e,
                            vals
                        );
                    }
                    return Ok(());
                }
                Err(other) => return Err(TestCaseError::fail(other.to_string())),
            };
            prop_assert!(n.check().is_ok());
            same_values(&[e], &[n], &ps, seed, 4, &mut tally.borrow_mut())
                .map_err(TestCaseError::fail)?;
            Ok(())
        })
        .unwrap();
    let formed = formed.get();
    assert!(formed > 200, "only {formed} of 256 inputs were normalised");
    check_tally(&tally.borrow(), "rational normal form");
}

/// Textbook check of the gcd through the public API: `(x + y)·(x − 2y)² / ((x − 2y)·(x² + y))`
/// cancels exactly one factor.
#[test]
fn rational_normal_form_cancels_multivariate_common_factors() {
    let x = param("x", 0.4, Assumption::Real);
    let y = param("y", 1.7, Assumption::Real);
    let z = param("z", -0.6, Assumption::Real);
    let f = x - Expr::int(2) * y + z;
    let num = (x + y) * f.powi(2) * (z.powi(2) + 3);
    let den = f * (x.powi(2) + y) * (z.powi(2) + 3);
    let n = normalize_rational(num / den).unwrap();
    let expect = normalize_rational((x + y) * f / (x.powi(2) + y)).unwrap();
    assert_eq!(n, expect);
    let mut tally = Tally::default();
    same_values(&[num / den], &[n], &[x, y, z], 11, 20, &mut tally).unwrap();
    assert!(tally.checked >= 18, "{tally:?}");
}
