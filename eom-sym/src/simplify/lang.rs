//! The egg language of the simplifier and its e-class analysis (exact constants and sign
//! knowledge).
//!
//! The language mirrors the pool's canonical forms instead of a binary AST: sums and products
//! are n-ary, so the pool's associative–commutative canonicalisation carries over and no AC
//! rules are needed (AC is what blows e-graphs up, see the module docs of
//! [`simplify`](super)). Rational constants are exact leaves; parameters, named constants and
//! floating-point constants are opaque leaves that keep their pool id, so the rebuilt
//! expression refers to exactly the same pool nodes.

use crate::pool::{Func, Sign};
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

/// What is known about the sign of a class: a set of {negative, zero, positive}, the same
/// semantics as the pool's [`Sign`] (the values the class takes wherever it is defined).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Signs(u8);

impl Signs {
    const NEG: u8 = 1;
    const ZERO: u8 = 2;
    const POS: u8 = 4;
    pub(crate) const ANY: Signs = Signs(7);
    const POSITIVE: Signs = Signs(4);
    const NONNEG: Signs = Signs(6);

    /// From the pool's sign knowledge (the public predicates determine the set exactly).
    pub(crate) fn from_sign(s: Sign) -> Signs {
        let mut b = 0;
        if !s.is_nonneg() {
            b |= Self::NEG;
        }
        if !s.is_nonzero() {
            b |= Self::ZERO;
        }
        if !s.is_nonpos() {
            b |= Self::POS;
        }
        Signs(b)
    }

    fn of_rational(r: &Rational) -> Signs {
        match r.signum() {
            1 => Signs(Self::POS),
            -1 => Signs(Self::NEG),
            _ => Signs(Self::ZERO),
        }
    }

    /// Both facts at once; an empty intersection (a class that is nowhere defined) keeps `a`.
    pub(crate) fn intersect(a: Signs, b: Signs) -> Signs {
        let c = a.0 & b.0;
        if c == 0 { a } else { Signs(c) }
    }

    /// Provably nonzero (the condition the pool uses to cancel `x·x⁻¹`).
    pub(crate) fn is_nonzero(self) -> bool {
        self.0 & Self::ZERO == 0
    }
    fn is_nonneg(self) -> bool {
        self.0 & Self::NEG == 0
    }
    fn is_nonpos(self) -> bool {
        self.0 & Self::POS == 0
    }
    fn is_positive(self) -> bool {
        self.0 == Self::POS
    }
    fn neg(self) -> Signs {
        let mut s = self.0 & Self::ZERO;
        if self.0 & Self::NEG != 0 {
            s |= Self::POS;
        }
        if self.0 & Self::POS != 0 {
            s |= Self::NEG;
        }
        Signs(s)
    }
    fn mul(self, o: Signs) -> Signs {
        let mut s = 0;
        for a in [Self::NEG, Self::ZERO, Self::POS] {
            if self.0 & a == 0 {
                continue;
            }
            for b in [Self::NEG, Self::ZERO, Self::POS] {
                if o.0 & b == 0 {
                    continue;
                }
                s |= match (a, b) {
                    (Self::ZERO, _) | (_, Self::ZERO) => Self::ZERO,
                    (x, y) if x == y => Self::POS,
                    _ => Self::NEG,
                };
            }
        }
        Signs(s)
    }
    fn add(self, o: Signs) -> Signs {
        if self.0 == 0 || o.0 == 0 {
            return Signs::ANY;
        }
        if self.is_nonneg() && o.is_nonneg() {
            if self.is_positive() || o.is_positive() {
                Signs::POSITIVE
            } else if self.0 == Self::ZERO && o.0 == Self::ZERO {
                Signs(Self::ZERO)
            } else {
                Signs::NONNEG
            }
        } else if self.is_nonpos() && o.is_nonpos() {
            self.neg().add(o.neg()).neg()
        } else {
            Signs::ANY
        }
    }
    /// `x^e` for a rational exponent, where defined (mirrors the pool).
    fn pow(self, e: &Rational) -> Signs {
        let s = if e.is_negative() {
            // Undefined at zero; where defined, the sign of x^|e|.
            let t = Signs(self.0 & !Self::ZERO);
            if t.0 == 0 { self } else { t }
        } else {
            self
        };
        match e.as_small() {
            Some((n, 1)) if n % 2 == 0 => {
                if s.is_nonzero() {
                    Signs::POSITIVE
                } else {
                    Signs::NONNEG
                }
            }
            Some((_, 1)) => s,
            _ => {
                if s.is_positive() {
                    Signs::POSITIVE
                } else {
                    Signs::NONNEG
                }
            }
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
    pub sign: Signs,
}

/// The e-class analysis. `atom_info` is filled by the converter with the numeric flag and
/// sign of each pool leaf, so that `make` needs no access to the pool.
#[derive(Default)]
pub(crate) struct Meta {
    pub atom_info: hashbrown::HashMap<u32, (bool, Signs)>,
}

impl Analysis<Math> for Meta {
    type Data = Data;

    fn make(egraph: &mut EGraph<Math, Self>, enode: &Math, _id: Id) -> Data {
        let sign = |i: &Id| egraph[*i].data.sign;
        match enode {
            Math::Rat(r) => Data {
                konst: Some(r.clone()),
                numeric: true,
                sign: Signs::of_rational(r),
            },
            Math::Atom(a) => {
                let (numeric, sign) = egraph
                    .analysis
                    .atom_info
                    .get(a)
                    .copied()
                    .unwrap_or((false, Signs::ANY));
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
                    .reduce(Signs::add)
                    .unwrap_or(Signs(Signs::ZERO));
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
                    .reduce(Signs::mul)
                    .unwrap_or(Signs::POSITIVE);
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Pow([b, e]) => {
                let s = match &egraph[*e].data.konst {
                    Some(r) => sign(b).pow(r),
                    None if sign(b).is_positive() => Signs::POSITIVE,
                    None => Signs::ANY,
                };
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Func(f, [a]) => {
                let s = match f {
                    Func::Exp => Signs::POSITIVE,
                    Func::Abs if sign(a).is_nonzero() => Signs::POSITIVE,
                    Func::Abs => Signs::NONNEG,
                    _ => Signs::ANY,
                };
                Data {
                    konst: None,
                    numeric: false,
                    sign: s,
                }
            }
            Math::Atan2(_) => Data {
                konst: None,
                numeric: false,
                sign: Signs::ANY,
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
        let both = Signs(a.sign.0 & b.sign.0);
        if both.0 != 0 {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signs_round_trip_the_pool_sign() {
        for s in [
            Sign::ANY,
            Sign::POSITIVE,
            Sign::NEGATIVE,
            Sign::ZERO_ONLY,
            Sign::NONNEG,
            Sign::NONZERO,
        ] {
            let t = Signs::from_sign(s);
            assert_eq!(t.is_nonzero(), s.is_nonzero());
            assert_eq!(t.is_nonneg(), s.is_nonneg());
            assert_eq!(t.is_nonpos(), s.is_nonpos());
        }
        let pos = Signs::POSITIVE;
        assert!(pos.add(pos).is_positive());
        assert!(pos.mul(pos.neg()).is_nonpos());
        assert!(!Signs::ANY.pow(&Rational::int(2)).is_nonzero());
        assert!(pos.neg().pow(&Rational::int(-2)).is_positive());
    }
}
