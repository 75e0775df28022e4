//! A deterministic view of the expression DAG: every node reachable from the roots, with the
//! operands of sums and products sorted by a structural hash and the nodes listed in a
//! post-order walk from the roots.
//!
//! The pool numbers nodes in creation order and sorts the operands of sums and products by
//! that number, so the same model built after other work (another model in the same build
//! script) can come out with operands in a different order. Hashing the structure instead
//! (parameters by their position in the interface, numbers by value) makes the generated text a
//! function of the model alone.

use crate::CodegenError;
use eom_sym::{Constant, Expr, ExprView, Func, Rational, SymError};
use std::collections::HashMap;

/// One node, with canonically ordered operands.
#[derive(Clone, Debug)]
pub(crate) enum Node {
    /// A number (rational, float or named constant).
    Number(f64),
    /// The parameter at this position of the interface.
    Param(u32),
    /// `c0 + Σ coef·term`.
    Sum { c0: f64, terms: Vec<(Expr, f64)> },
    /// `coef · Π base^exponent`.
    Product {
        coef: f64,
        factors: Vec<(Expr, Rational)>,
    },
    /// `base ^ exponent` (non-rational exponent).
    Pow(Expr, Expr),
    /// A function of one argument.
    Func(Func, Expr),
    /// `atan2(y, x)`.
    Atan2(Expr, Expr),
}

/// The reachable DAG in a deterministic topological order.
pub(crate) struct Dag {
    /// Nodes, children before parents, in a post-order walk from the roots.
    pub order: Vec<Expr>,
    /// The structure of each node.
    pub nodes: HashMap<Expr, Node>,
}

/// A 64-bit mixing step (SplitMix64 finaliser): stable across platforms and Rust versions.
fn mix(h: u64, x: u64) -> u64 {
    let mut z = h ^ x
        .wrapping_add(0x9e37_79b9_7f4a_7c15)
        .wrapping_add(h << 6)
        .wrapping_add(h >> 2);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn number_of(e: Expr) -> Option<f64> {
    e.as_f64()
}

/// Build the deterministic DAG of `roots`. `param_pos` maps each parameter (by pool index) to
/// its position in the generated interface; a parameter not in it is an error naming it.
pub(crate) fn build(roots: &[Expr], param_pos: &HashMap<u32, u32>) -> Result<Dag, CodegenError> {
    // 1. Everything reachable, with its view.
    let mut views: HashMap<Expr, ExprView> = HashMap::new();
    let mut stack: Vec<Expr> = roots.to_vec();
    while let Some(e) = stack.pop() {
        if views.contains_key(&e) {
            continue;
        }
        let v = e.view();
        match &v {
            ExprView::Sum { terms, .. } => stack.extend(terms.iter().map(|t| t.0)),
            ExprView::Product { factors, .. } => stack.extend(factors.iter().map(|f| f.0)),
            ExprView::Pow(a, b) | ExprView::Atan2(a, b) => stack.extend([*a, *b]),
            ExprView::Func(_, a) => stack.push(*a),
            ExprView::Invalid(err) => return Err(SymError::Invalid(Box::new(err.clone())).into()),
            _ => {}
        }
        views.insert(e, v);
    }

    // 2. Structural hashes, children first (pool ids are a topological order).
    let mut by_id: Vec<Expr> = views.keys().copied().collect();
    by_id.sort_unstable_by_key(|e| e.id());
    let mut hash: HashMap<Expr, u64> = HashMap::with_capacity(by_id.len());
    let mut nodes: HashMap<Expr, Node> = HashMap::with_capacity(by_id.len());
    for &e in &by_id {
        let (node, h) = match &views[&e] {
            ExprView::Rational(r) => (Node::Number(r.to_f64()), mix(1, r.to_f64().to_bits())),
            ExprView::Float(f) => (Node::Number(*f), mix(1, f.to_bits())),
            ExprView::Constant(c) => {
                let x = match c {
                    Constant::Pi => core::f64::consts::PI,
                    Constant::E => core::f64::consts::E,
                };
                (Node::Number(x), mix(1, x.to_bits()))
            }
            ExprView::Param(i, info) => {
                let k = *param_pos.get(i).ok_or_else(|| SymError::MissingParameter {
                    name: info.name.clone(),
                })?;
                let mut h = mix(2, u64::from(k));
                for b in info.name.bytes() {
                    h = mix(h, u64::from(b));
                }
                (Node::Param(k), h)
            }
            ExprView::Sum { constant, terms } => {
                let c0 = number_of(*constant).unwrap_or(0.0);
                let mut t: Vec<(u64, Expr, f64)> = terms
                    .iter()
                    .map(|(x, c)| (hash[x], *x, number_of(*c).unwrap_or(f64::NAN)))
                    .collect();
                t.sort_by(|a, b| a.0.cmp(&b.0).then(a.2.total_cmp(&b.2)));
                let mut h = mix(3, c0.to_bits());
                for (hx, _, c) in &t {
                    h = mix(mix(h, *hx), c.to_bits());
                }
                (
                    Node::Sum {
                        c0,
                        terms: t.into_iter().map(|(_, x, c)| (x, c)).collect(),
                    },
                    h,
                )
            }
            ExprView::Product { coef, factors } => {
                let c = number_of(*coef).unwrap_or(f64::NAN);
                let mut f: Vec<(u64, Expr, Rational)> = factors
                    .iter()
                    .map(|(b, r)| (hash[b], *b, r.clone()))
                    .collect();
                f.sort_by(|a, b| a.0.cmp(&b.0).then(a.2.cmp(&b.2)));
                let mut h = mix(4, c.to_bits());
                for (hb, _, r) in &f {
                    h = mix(mix(h, *hb), r.to_f64().to_bits());
                }
                (
                    Node::Product {
                        coef: c,
                        factors: f.into_iter().map(|(_, b, r)| (b, r)).collect(),
                    },
                    h,
                )
            }
            ExprView::Pow(a, b) => (Node::Pow(*a, *b), mix(mix(5, hash[a]), hash[b])),
            ExprView::Func(f, a) => (Node::Func(*f, *a), mix(mix(6, *f as u64), hash[a])),
            ExprView::Atan2(a, b) => (Node::Atan2(*a, *b), mix(mix(7, hash[a]), hash[b])),
            ExprView::Invalid(err) => return Err(SymError::Invalid(Box::new(err.clone())).into()),
        };
        hash.insert(e, h);
        nodes.insert(e, node);
    }

    // 3. Post-order walk from the roots, operands in canonical order (iterative: DAGs can be
    //    deep).
    let mut order = Vec::with_capacity(nodes.len());
    let mut done: HashMap<Expr, ()> = HashMap::with_capacity(nodes.len());
    for &r in roots {
        let mut stack: Vec<(Expr, bool)> = vec![(r, false)];
        while let Some((e, expanded)) = stack.pop() {
            if done.contains_key(&e) {
                continue;
            }
            if expanded {
                done.insert(e, ());
                order.push(e);
                continue;
            }
            stack.push((e, true));
            let kids = children(&nodes[&e]);
            for k in kids.into_iter().rev() {
                if !done.contains_key(&k) {
                    stack.push((k, false));
                }
            }
        }
    }
    Ok(Dag { order, nodes })
}

/// The operand nodes of a node, in evaluation order.
pub(crate) fn children(n: &Node) -> Vec<Expr> {
    match n {
        Node::Number(_) | Node::Param(_) => vec![],
        Node::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
        Node::Product { factors, .. } => factors.iter().map(|f| f.0).collect(),
        Node::Pow(a, b) | Node::Atan2(a, b) => vec![*a, *b],
        Node::Func(_, a) => vec![*a],
    }
}
