//! [`Shape`]: the one definition of what a node is made of — its kind, its children in a fixed
//! order, its value given its children's, and the operations it costs. Every traversal of the
//! DAG (interning, reachability, evaluation in any scalar, operation counts, the zero test,
//! the simplifier, the lowering to straight-line code) goes through it, in the way egg's
//! `Language` trait exposes `children()` for e-nodes.

use super::{Constant, Id, MINUS_ONE, ONE, ZERO};
use crate::func::Func;
use crate::rational::Rational;
use crate::scalar::Elementary;
use std::borrow::Borrow;

/// A node: its kind and its children. `L` holds the children of sums and products (a slice
/// of the pool's argument arena, or an owned copy), `R` the value of a rational constant.
///
/// Children, in the order [`Shape::children`] lists them:
/// * sums `c₀ + Σ cᵢ·tᵢ`: `c₀`, then `tᵢ, cᵢ` pairs (coefficients are numbers);
/// * products `c · Π bᵢ^eᵢ`: `c`, then `bᵢ, eᵢ` pairs (exponents are rational numbers);
/// * `x^y` (non-rational exponent): `x, y`; `f(x)`: `x`; `atan2(y, x)`: `y, x`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Shape<L, R> {
    Num(R),
    /// A floating-point constant, by its bits (so that shapes hash and compare exactly).
    Float(u64),
    Const(Constant),
    /// Parameter number `i` of the pool.
    Param(u32),
    Add(L),
    Mul(L),
    Pow([Id; 2]),
    Func(Func, [Id; 1]),
    Atan2([Id; 2]),
    /// An operation without a real value: error number `i` of the pool.
    Invalid(u32),
}

/// A shape borrowed from a pool.
pub(crate) type ShapeRef<'a> = Shape<&'a [Id], &'a Rational>;
/// A shape that owns its children (for work that must not hold the pool).
pub(crate) type ShapeBuf = Shape<Box<[Id]>, Rational>;

/// Operation counts of straight-line code (see [`Expr::op_count`](crate::Expr::op_count)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Elementary functions and square roots.
    pub func: usize,
    /// General powers.
    pub pow: usize,
}

impl OpCount {
    /// Total number of operations.
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.func + self.pow
    }
}

impl std::ops::AddAssign for OpCount {
    fn add_assign(&mut self, o: OpCount) {
        self.add += o.add;
        self.mul += o.mul;
        self.div += o.div;
        self.func += o.func;
        self.pow += o.pow;
    }
}

/// Multiplications of a square-and-multiply chain for `x^k` (k ≥ 1).
fn pow_chain(k: u64) -> usize {
    if k <= 1 {
        return 0;
    }
    ((63 - k.leading_zeros()) + k.count_ones() - 1) as usize
}

/// The operations of `x^r` for a factor of a product: multiplications of a chain, one
/// division for a negative power (shared with the product's other divisors), a square root,
/// or a general power. The second value is 1 when the factor divides (it then takes no
/// multiplication of its own in the product).
pub(crate) fn power_ops(r: &Rational) -> (OpCount, usize) {
    let mut c = OpCount::default();
    let mut divides = 0;
    match r.as_small() {
        Some((k, 1)) if k > 0 => c.mul += pow_chain(k as u64),
        Some((k, 1)) => {
            c.div += 1;
            divides = 1;
            c.mul += pow_chain(k.unsigned_abs());
        }
        Some((1, 2)) => c.func += 1,
        _ => c.pow += 1,
    }
    (c, divides)
}

impl<L: AsRef<[Id]>, R: Borrow<Rational>> Shape<L, R> {
    /// The children in their fixed order (see [`Shape`]).
    pub(crate) fn children(&self) -> &[Id] {
        match self {
            Shape::Add(a) | Shape::Mul(a) => a.as_ref(),
            Shape::Pow(a) | Shape::Atan2(a) => a,
            Shape::Func(_, a) => a,
            Shape::Num(_) | Shape::Float(_) | Shape::Const(_) | Shape::Param(_) => &[],
            Shape::Invalid(_) => &[],
        }
    }

    /// The same shape with owned children.
    pub(crate) fn to_buf(&self) -> ShapeBuf {
        match self {
            Shape::Num(r) => Shape::Num(r.borrow().clone()),
            Shape::Float(b) => Shape::Float(*b),
            Shape::Const(c) => Shape::Const(*c),
            Shape::Param(i) => Shape::Param(*i),
            Shape::Add(a) => Shape::Add(a.as_ref().into()),
            Shape::Mul(a) => Shape::Mul(a.as_ref().into()),
            Shape::Pow(a) => Shape::Pow(*a),
            Shape::Func(f, a) => Shape::Func(*f, *a),
            Shape::Atan2(a) => Shape::Atan2(*a),
            Shape::Invalid(e) => Shape::Invalid(*e),
        }
    }

    /// The value of the node in any [`Elementary`] scalar from the values of its children
    /// (`val`) and the rational exponents of products (`rat`); `None` for parameters and
    /// invalid nodes, whose values the caller knows.
    ///
    /// This is the evaluation order that every evaluator shares, so that nominal values,
    /// [`eval_generic`](crate::eval_generic) and the zero test agree (and the tape, which
    /// keeps it, agrees bit for bit): sums `((c₀ + c₁t₁) + c₂t₂) + …` (without `c₀` when it is
    /// 0, without a coefficient 1), products `((c·f₁)·f₂)·…` with `fᵢ = bᵢ^eᵢ` by `powi`,
    /// `sqrt`, `1/sqrt` or `powf`.
    pub(crate) fn eval<S: Elementary>(
        &self,
        val: impl Fn(Id) -> S,
        rat: impl Fn(Id) -> Rational,
    ) -> Option<S> {
        Some(match self {
            Shape::Num(r) => S::from_rational(r.borrow()),
            Shape::Float(b) => S::from_f64(f64::from_bits(*b)),
            Shape::Const(Constant::Pi) => S::pi(),
            Shape::Const(Constant::E) => S::e(),
            Shape::Param(_) | Shape::Invalid(_) => return None,
            Shape::Add(a) => {
                let a = a.as_ref();
                let term = |t: &[Id]| {
                    if t[1] == ONE {
                        val(t[0])
                    } else {
                        val(t[1]) * val(t[0])
                    }
                };
                let first = (a[0] != ZERO).then(|| val(a[0]));
                let terms = a[1..].chunks_exact(2).map(term);
                if S::FOLD_SUM {
                    // The left-to-right fold, without gathering the terms.
                    let mut it = first.into_iter().chain(terms);
                    match it.next() {
                        Some(x) => it.fold(x, |acc, t| acc + t),
                        None => S::sum(&[]),
                    }
                } else {
                    S::sum(&first.into_iter().chain(terms).collect::<Vec<S>>())
                }
            }
            Shape::Mul(a) => {
                let a = a.as_ref();
                let mut acc = val(a[0]);
                for t in a[1..].chunks_exact(2) {
                    let (b, e) = (val(t[0]), rat(t[1]));
                    let f = match e.as_small() {
                        Some((n, 1)) => b.powi(n),
                        Some((1, 2)) => b.sqrt(),
                        Some((-1, 2)) => b.sqrt().recip(),
                        _ => b.powf(S::from_rational(&e)),
                    };
                    acc = if acc.is_one() { f } else { acc * f };
                }
                acc
            }
            Shape::Pow([a, b]) => val(*a).powf(val(*b)),
            Shape::Func(f, [a]) => f.eval(val(*a)),
            Shape::Atan2([y, x]) => val(*y).atan2(val(*x)),
        })
    }

    /// The operations of this node alone in straight-line code; `rat` gives the rational
    /// exponents of products. [`Expr::op_count`](crate::Expr::op_count) is their sum over a
    /// DAG, and the simplifier costs its candidates with it.
    pub(crate) fn ops(&self, rat: impl Fn(Id) -> Rational) -> OpCount {
        let mut c = OpCount::default();
        match self {
            Shape::Add(a) => {
                let a = a.as_ref();
                let n = a[1..].len() / 2 + usize::from(a[0] != ZERO);
                c.add += n.saturating_sub(1);
                c.mul += a[1..]
                    .chunks_exact(2)
                    .filter(|t| t[1] != ONE && t[1] != MINUS_ONE)
                    .count();
            }
            Shape::Mul(a) => {
                let a = a.as_ref();
                let mut n = a[1..].len() / 2 + usize::from(a[0] != ONE && a[0] != MINUS_ONE);
                for t in a[1..].chunks_exact(2) {
                    let (p, divides) = power_ops(&rat(t[1]));
                    c += p;
                    n = n.saturating_sub(divides);
                }
                c.mul += n.saturating_sub(1);
            }
            Shape::Pow(_) => c.pow += 1,
            Shape::Func(..) | Shape::Atan2(_) => c.func += 1,
            Shape::Num(_) | Shape::Float(_) | Shape::Const(_) | Shape::Param(_) => {}
            Shape::Invalid(_) => {}
        }
        c
    }
}
