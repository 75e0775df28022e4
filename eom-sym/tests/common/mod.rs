//! Random expression recipes for property tests. A recipe is a plain tree (Send, shrinkable);
//! `build` turns it into an `Expr` in the test's thread.
#![allow(dead_code)]

pub mod bound;

use eom_sym::Expr;
use proptest::prelude::*;

#[derive(Clone, Debug)]
pub enum Recipe {
    Param(usize),
    Int(i64),
    Rat(i64, i64),
    Float(f64),
    Add(Box<Recipe>, Box<Recipe>),
    Sub(Box<Recipe>, Box<Recipe>),
    Mul(Box<Recipe>, Box<Recipe>),
    Div(Box<Recipe>, Box<Recipe>),
    Neg(Box<Recipe>),
    Powi(Box<Recipe>, i64),
    Sqrt(Box<Recipe>),
    Sin(Box<Recipe>),
    Cos(Box<Recipe>),
    Exp(Box<Recipe>),
    Ln(Box<Recipe>),
    Abs(Box<Recipe>),
    Atan2(Box<Recipe>, Box<Recipe>),
}

/// Number of parameters recipes refer to.
pub const N_PARAMS: usize = 4;

pub fn recipe() -> impl Strategy<Value = Recipe> {
    let leaf = prop_oneof![
        4 => (0..N_PARAMS).prop_map(Recipe::Param),
        1 => (-5i64..6).prop_map(Recipe::Int),
        1 => (-7i64..8, 1i64..6).prop_map(|(a, b)| Recipe::Rat(a, b)),
        1 => (-3.0f64..3.0).prop_map(Recipe::Float),
    ];
    leaf.prop_recursive(5, 48, 2, |inner| {
        let b = |r: Recipe| Box::new(r);
        prop_oneof![
            3 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Recipe::Add(b(x), b(y))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Recipe::Sub(b(x), b(y))),
            3 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Recipe::Mul(b(x), b(y))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(x, y)| Recipe::Div(b(x), b(y))),
            1 => inner.clone().prop_map(move |x| Recipe::Neg(b(x))),
            2 => (inner.clone(), -3i64..4).prop_map(move |(x, n)| Recipe::Powi(b(x), n)),
            1 => inner.clone().prop_map(move |x| Recipe::Sqrt(b(x))),
            1 => inner.clone().prop_map(move |x| Recipe::Sin(b(x))),
            1 => inner.clone().prop_map(move |x| Recipe::Cos(b(x))),
            1 => inner.clone().prop_map(move |x| Recipe::Exp(b(x))),
            1 => inner.clone().prop_map(move |x| Recipe::Ln(b(x))),
            1 => inner.clone().prop_map(move |x| Recipe::Abs(b(x))),
            1 => (inner.clone(), inner).prop_map(move |(x, y)| Recipe::Atan2(b(x), b(y))),
        ]
    })
}

/// Build the expression. `Sqrt` and `Ln` are applied to `|x|` and `|x| + 1/2` so that values
/// stay real; `Exp` to `x/4` to keep magnitudes moderate. The result may still be invalid
/// (division by a structural zero) — callers skip those with `prop_assume!`.
pub fn build(r: &Recipe, p: &[Expr]) -> Expr {
    match r {
        Recipe::Param(i) => p[*i],
        Recipe::Int(n) => Expr::int(*n),
        Recipe::Rat(a, b) => Expr::rational(*a, *b).unwrap(),
        Recipe::Float(x) => Expr::float(*x).unwrap(),
        Recipe::Add(a, b) => build(a, p) + build(b, p),
        Recipe::Sub(a, b) => build(a, p) - build(b, p),
        Recipe::Mul(a, b) => build(a, p) * build(b, p),
        Recipe::Div(a, b) => build(a, p) / build(b, p),
        Recipe::Neg(a) => -build(a, p),
        Recipe::Powi(a, n) => build(a, p).powi(*n),
        Recipe::Sqrt(a) => build(a, p).abs().sqrt(),
        Recipe::Sin(a) => build(a, p).sin(),
        Recipe::Cos(a) => build(a, p).cos(),
        Recipe::Exp(a) => (build(a, p) / 4i64).exp(),
        Recipe::Ln(a) => (build(a, p).abs() + Expr::rational(1, 2).unwrap()).ln(),
        Recipe::Abs(a) => build(a, p).abs(),
        Recipe::Atan2(a, b) => build(a, p).atan2(build(b, p)),
    }
}

/// Parameters p0..p3 with nominal values 0.7, 1.3, 2.1, 0.4 (no sign assumptions).
pub fn params() -> Vec<Expr> {
    [0.7, 1.3, 2.1, 0.4]
        .iter()
        .enumerate()
        .map(|(i, &v)| Expr::param(&format!("p{i}"), v).unwrap())
        .collect()
}

pub fn has_float(r: &Recipe) -> bool {
    use Recipe::*;
    match r {
        Float(_) => true,
        Param(_) | Int(_) | Rat(..) => false,
        Add(a, b) | Sub(a, b) | Mul(a, b) | Div(a, b) | Atan2(a, b) => has_float(a) || has_float(b),
        Neg(a) | Powi(a, _) | Sqrt(a) | Sin(a) | Cos(a) | Exp(a) | Ln(a) | Abs(a) => has_float(a),
    }
}
