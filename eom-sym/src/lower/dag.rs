//! The DAG the lowering walks: every node reachable from the roots with its shape, in an
//! evaluation order.
//!
//! With the pool's order (for [`Rounding::Exact`](super::Rounding::Exact)) nodes come by id and
//! the operands of sums and products in the pool's order, which is the order of evaluation.
//! The canonical order (for [`Rounding::Free`](super::Rounding::Free)) sorts the operands of
//! sums and products by a structural hash and lists the nodes in a post-order walk from the
//! roots: the pool numbers nodes in creation order and sorts operands by that number, so the
//! same model built after other work (another model in the same build script) can come out
//! with operands in a different order. Hashing the structure instead (parameters by their
//! position in the interface, numbers by value) makes generated text a function of the model
//! alone.

use crate::context::with_serial;
use crate::error::SymError;
use crate::expr::{Expr, reachable};
use crate::func::Func;
use crate::pool::{Id, Shape, ShapeBuf};
use crate::rational::Rational;
use hashbrown::{HashMap, HashSet};

/// The reachable DAG in an evaluation order.
pub(super) struct Dag {
    /// The pool of the nodes.
    pub serial: u32,
    /// Nodes, children before parents.
    pub order: Vec<Id>,
    /// The shape of each node (operands of sums and products in the chosen order).
    pub shapes: HashMap<Id, ShapeBuf>,
    /// The roots' ids, in the order given.
    pub roots: Vec<Id>,
    /// Interface position of each parameter (by pool index).
    position: HashMap<u32, u32>,
    /// Names of the parameters reached (for errors).
    names: HashMap<u32, String>,
}

impl Dag {
    /// The interface position of parameter `i`, or an error naming it.
    pub fn position(&self, i: u32) -> Result<u32, SymError> {
        self.position
            .get(&i)
            .copied()
            .ok_or_else(|| SymError::MissingParameter {
                name: self.names[&i].clone(),
            })
    }

    /// The rational exponent node `id` of a product holds.
    pub fn exponent(&self, id: Id) -> Rational {
        match &self.shapes[&id] {
            Shape::Num(r) => r.clone(),
            _ => unreachable!("product exponents are rational"),
        }
    }

    /// Arguments of both a `sin` and a `cos`.
    pub fn sincos_args(&self) -> HashSet<Id> {
        let (mut sin, mut cos) = (HashSet::new(), HashSet::new());
        for s in self.shapes.values() {
            match s {
                Shape::Func(Func::Sin, [a]) => sin.insert(*a),
                Shape::Func(Func::Cos, [a]) => cos.insert(*a),
                _ => false,
            };
        }
        sin.intersection(&cos).copied().collect()
    }
}

/// The DAG of `roots`, in the pool's order or in the canonical one.
pub(super) fn build(
    roots: &[Expr],
    position: &HashMap<u32, u32>,
    canonical: bool,
) -> Result<Dag, SymError> {
    let reach = reachable(roots);
    let (shapes, names) = with_serial(reach.serial, |p| {
        let mut names = HashMap::new();
        let shapes: HashMap<Id, ShapeBuf> = reach
            .ids
            .iter()
            .map(|&i| {
                let s = p.shape(i);
                if let Shape::Param(k) = s {
                    names.insert(k, p.param(k).name.clone());
                }
                (i, s.to_buf())
            })
            .collect();
        (shapes, names)
    });
    let mut dag = Dag {
        serial: reach.serial,
        order: reach.ids,
        shapes,
        roots: reach.roots,
        position: position.clone(),
        names,
    };
    if canonical {
        canonical_order(&mut dag)?;
    }
    Ok(dag)
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

/// Sorts the operands of sums and products by structural hash and lists the nodes in a
/// post-order walk from the roots (iterative: DAGs can be deep).
fn canonical_order(dag: &mut Dag) -> Result<(), SymError> {
    let value = |s: &ShapeBuf| {
        s.eval::<f64>(|_| f64::NAN, |_| Rational::ZERO)
            .unwrap_or(f64::NAN)
    };
    // Structural hashes, children first (pool ids are a topological order).
    let mut hash: HashMap<Id, u64> = HashMap::with_capacity(dag.order.len());
    for &id in &dag.order {
        let num = |i: &Id, dag: &Dag| value(&dag.shapes[i]);
        let h = match &dag.shapes[&id] {
            s @ (Shape::Num(_) | Shape::Float(_) | Shape::Const(_)) => mix(1, value(s).to_bits()),
            Shape::Param(i) => {
                let k = dag.position(*i)?;
                dag.names[i]
                    .bytes()
                    .fold(mix(2, u64::from(k)), |h, b| mix(h, u64::from(b)))
            }
            Shape::Add(a) => {
                let mut t: Vec<(u64, Id, Id, f64)> = a[1..]
                    .chunks_exact(2)
                    .map(|p| (hash[&p[0]], p[0], p[1], num(&p[1], dag)))
                    .collect();
                t.sort_by(|x, y| x.0.cmp(&y.0).then(x.3.total_cmp(&y.3)));
                let h = t.iter().fold(mix(3, num(&a[0], dag).to_bits()), |h, x| {
                    mix(mix(h, x.0), x.3.to_bits())
                });
                let sorted = std::iter::once(a[0]).chain(t.iter().flat_map(|x| [x.1, x.2]));
                dag.shapes.insert(id, Shape::Add(sorted.collect()));
                h
            }
            Shape::Mul(a) => {
                let mut f: Vec<(u64, Id, Id, Rational)> = a[1..]
                    .chunks_exact(2)
                    .map(|p| (hash[&p[0]], p[0], p[1], dag.exponent(p[1])))
                    .collect();
                f.sort_by(|x, y| x.0.cmp(&y.0).then(x.3.cmp(&y.3)));
                let h = f.iter().fold(mix(4, num(&a[0], dag).to_bits()), |h, x| {
                    mix(mix(h, x.0), x.3.to_f64().to_bits())
                });
                let sorted = std::iter::once(a[0]).chain(f.iter().flat_map(|x| [x.1, x.2]));
                dag.shapes.insert(id, Shape::Mul(sorted.collect()));
                h
            }
            Shape::Pow([a, b]) => mix(mix(5, hash[a]), hash[b]),
            Shape::Func(f, [a]) => mix(mix(6, *f as u64), hash[a]),
            Shape::Atan2([a, b]) => mix(mix(7, hash[a]), hash[b]),
            Shape::Invalid(_) => unreachable!("invalid roots are refused"),
        };
        hash.insert(id, h);
    }
    let mut order = Vec::with_capacity(dag.order.len());
    let mut done: HashSet<Id> = HashSet::with_capacity(dag.order.len());
    for &r in &dag.roots {
        let mut stack: Vec<(Id, bool)> = vec![(r, false)];
        while let Some((e, expanded)) = stack.pop() {
            if done.contains(&e) {
                continue;
            }
            if expanded {
                done.insert(e);
                order.push(e);
                continue;
            }
            stack.push((e, true));
            for &k in dag.shapes[&e].children().iter().rev() {
                if !done.contains(&k) {
                    stack.push((k, false));
                }
            }
        }
    }
    dag.order = order;
    Ok(())
}
