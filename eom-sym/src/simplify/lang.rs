//! The egg language of the simplifier and its e-class analysis (exact constants and sign
//! knowledge).
//!
//! The language mirrors the pool's canonical forms instead of a binary AST: sums and products
//! are n-ary, so the pool's associative–commutative canonicalisation carries over and no AC
//! rules are needed (AC is what blows e-graphs up, see the module docs of
//! [`simplify`](super)). Rational constants are exact leaves; parameters, named constants and
//! floating-point constants are opaque leaves that keep their pool id, so the rebuilt
//! expression refers to exactly the same pool nodes.

use crate::pool::{Func, Sign, pow_sign};
use crate::rational::Rational;
use egg::{Analysis, DidMerge, EGraph, Id, Language};
use std::fmt;

/// A node of the simplifier's e-graph.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Math {
    /// An exact rational constant.
    Rat(Rational),
    /// A pool leaf that rewriting treats as opaque: a parameter, a named constant or a
    /// floating-point constant (by pool id).
    Atom(u32),
    /// `Σ children`.
    Add(Box<[Id]>),
    /// `Π children`.
    Mul(Box<[Id]>),
    /// `base ^ exponent`; the exponent class holds a rational constant for the powers of the
    /// pool's products, anything else for a general power.
    Pow([Id; 2]),
    /// An elementary function.
    Func(Func, [Id; 1]),
    /// `atan2(y, x)`.
    Atan2([Id; 2]),
}

impl Language for Math {
    type Discriminant = std::mem::Discriminant<Math>;

    fn discriminant(&self) -> Self::Discriminant {
        std::mem::discriminant(self)
    }

    fn matches(&self, other: &Self) -> bool {
        match (self, other) {
            (Math::Rat(a), Math::Rat(b)) => a == b,
            (Math::Atom(a), Math::Atom(b)) => a == b,
            (Math::Add(a), Math::Add(b)) | (Math::Mul(a), Math::Mul(b)) => a.len() == b.len(),
            (Math::Pow(_), Math::Pow(_)) | (Math::Atan2(_), Math::Atan2(_)) => true,
            (Math::Func(f, _), Math::Func(g, _)) => f == g,
            _ => false,
        }
    }

    fn children(&self) -> &[Id] {
        match self {
            Math::Rat(_) | Math::Atom(_) => &[],
            Math::Add(c) | Math::Mul(c) => c,
            Math::Pow(c) | Math::Atan2(c) => c,
            Math::Func(_, c) => c,
        }
    }

    fn children_mut(&mut self) -> &mut [Id] {
        match self {
            Math::Rat(_) | Math::Atom(_) => &mut [],
            Math::Add(c) | Math::Mul(c) => c,
            Math::Pow(c) | Math::Atan2(c) => c,
            Math::Func(_, c) => c,
        }
    }
}

impl fmt::Display for Math {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Math::Rat(r) => write!(f, "{r}"),
            Math::Atom(i) => write!(f, "atom{i}"),
            Math::Add(_) => f.write_str("+"),
            Math::Mul(_) => f.write_str("*"),
            Math::Pow(_) => f.write_str("pow"),
            Math::Func(g, _) => f.write_str(g.name()),
            Math::Atan2(_) => f.write_str("atan2"),
        }
    }
}

/// Analysis data of a class.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Data {
    /// The exact value, if the class holds a rational constant.
    pub konst: Option<Rational>,
    /// A number of any kind (rational or floating-point leaf): never worth factoring out,
    /// because the pool distributes numeric coefficients over sums again.
    pub numeric: bool,
    /// Sign knowledge.
    pub sign: Sign,
}

/// The e-class analysis. `atom_info` is filled by the converter with the numeric flag and
/// sign of each pool leaf, so that `make` needs no access to the pool.
#[derive(Default)]
pub(crate) struct Meta {
    pub atom_info: hashbrown::HashMap<u32, (bool, Sign)>,
}

impl Analysis<Math> for Meta {
    type Data = Data;

    fn make(egraph: &mut EGraph<Math, Self>, enode: &Math, _id: Id) -> Data {
        let sign = |i: &Id| egraph[*i].data.sign;
        match enode {
            Math::Rat(r) => Data {
                konst: Some(r.clone()),
                numeric: true,
                sign: Sign::from_rational(r),
            },
            Math::Atom(a) => {
                let (numeric, sign) = egraph
                    .analysis
                    .atom_info
                    .get(a)
                    .copied()
                    .unwrap_or((false, Sign::ANY));
                Data {
                    konst: None,
                    numeric,
                    sign,
                }
            }
            Math::Add(c) => {
                let s = c
                    .iter()
                    .map(sign)
                    .reduce(Sign::add)
                    .unwrap_or(Sign::ZERO_ONLY);
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Mul(c) => {
                let s = c
                    .iter()
                    .map(sign)
                    .reduce(Sign::mul)
                    .unwrap_or(Sign::POSITIVE);
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Pow([b, e]) => {
                let s = match &egraph[*e].data.konst {
                    Some(r) => pow_sign(sign(b), r),
                    None if sign(b).is_positive() => Sign::POSITIVE,
                    None => Sign::ANY,
                };
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Func(f, [a]) => Data {
                konst: None,
                numeric: false,
                sign: f.sign(sign(a)),
            },
            Math::Atan2(_) => Data {
                konst: None,
                numeric: false,
                sign: Sign::ANY,
            },
        }
    }

    fn merge(&mut self, a: &mut Data, b: Data) -> DidMerge {
        let mut changed_a = false;
        let mut changed_b = false;
        if a.konst.is_none() && b.konst.is_some() {
            a.konst = b.konst.clone();
            changed_a = true;
        } else if a.konst.is_some() && b.konst.is_none() {
            changed_b = true;
        }
        if !a.numeric && b.numeric {
            a.numeric = true;
            changed_a = true;
        } else if a.numeric && !b.numeric {
            changed_b = true;
        }
        // Both are sound over-approximations of the same set of values: intersect. An empty
        // intersection can only come from a class that is nowhere defined; keep `a` then.
        if let Some(both) = a.sign.intersect(b.sign) {
            if both != a.sign {
                a.sign = both;
                changed_a = true;
            }
            if both != b.sign {
                changed_b = true;
            }
        }
        DidMerge(changed_a, changed_b)
    }
}

/// The e-graph type of the simplifier.
pub(crate) type Graph = EGraph<Math, Meta>;
