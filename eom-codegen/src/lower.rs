//! Lowering of the DAG to straight-line instructions: one temporary per unique operation.
//!
//! Beyond one-node-one-temporary, the lowering does what the pool's canonical form leaves to
//! the code generator:
//! * **Powers** by multiplication chains shared between products (`x²` is computed once
//!   wherever a product contains `x²` or `x³`); half-integer powers through one `sqrt`.
//! * **Denominators**: a base that appears with a negative exponent in two or more products
//!   gets one reciprocal that every product multiplies by; a base that divides only once is
//!   divided directly, and all such factors of a product share one division.
//! * **Monomials that differ only in their coefficient** (`k/m`, `−k/m`, `2k/m`) are computed
//!   once and scaled.
//! * `sin x` and `cos x` of the same argument come from one `sincos`.
//! * Operations on numbers only are folded at generation time.

use crate::CodegenError;
use crate::order::{Dag, Node};
use eom_sym::{Expr, Func, Rational};
use std::collections::{HashMap, HashSet};

/// An operand: a temporary, a parameter, or a literal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Operand {
    /// A temporary `tN`.
    Temp(u32),
    /// The parameter at this position.
    Param(u32),
    /// A literal.
    Lit(f64),
}

/// Hashable identity of an operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum OpKey {
    Temp(u32),
    Param(u32),
    Lit(u64),
}

impl Operand {
    pub(crate) fn key(self) -> OpKey {
        match self {
            Operand::Temp(t) => OpKey::Temp(t),
            Operand::Param(p) => OpKey::Param(p),
            Operand::Lit(x) => OpKey::Lit(x.to_bits()),
        }
    }
}

/// Functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Fn1 {
    Sqrt,
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Abs,
}

/// Functions of two arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Fn2 {
    Pow,
    Atan2,
}

/// The right-hand side of one `let`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Rhs {
    /// `c0 + Σ c·x`.
    Sum { c0: f64, terms: Vec<(Operand, f64)> },
    /// `coef · Π num / Π den`.
    Prod { coef: f64, num: Vec<Operand>, den: Vec<Operand> },
    /// `f(x)`.
    Call1(Fn1, Operand),
    /// `f(x, y)`.
    Call2(Fn2, Operand, Operand),
    /// `(sin x, cos x)`: defines two temporaries.
    SinCos(Operand),
}

impl Rhs {
    /// Operands read.
    pub(crate) fn operands(&self) -> Vec<Operand> {
        match self {
            Rhs::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
            Rhs::Prod { num, den, .. } => num.iter().chain(den).copied().collect(),
            Rhs::Call1(_, x) | Rhs::SinCos(x) => vec![*x],
            Rhs::Call2(_, x, y) => vec![*x, *y],
        }
    }
    /// Number of temporaries defined.
    pub(crate) fn defs(&self) -> u32 {
        if matches!(self, Rhs::SinCos(_)) { 2 } else { 1 }
    }
}

/// One instruction: `let t{def}[, t{def+1}] = rhs`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Inst {
    pub def: u32,
    pub rhs: Rhs,
}

/// Counts of floating-point operations in generated code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CodeOps {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions (including reciprocals).
    pub div: usize,
    /// Negations (sign flips).
    pub neg: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Calls of elementary functions (`sincos` counts once) and general powers.
    pub func: usize,
}

impl CodeOps {
    /// All arithmetic operations (negations excluded: they are sign-bit flips).
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.sqrt + self.func
    }
    pub(crate) fn count(&mut self, rhs: &Rhs) {
        match rhs {
            Rhs::Sum { c0, terms } => {
                let n = terms.len() + usize::from(*c0 != 0.0);
                self.add += n.saturating_sub(1);
                self.mul += terms.iter().filter(|t| t.1.abs() != 1.0).count();
                if *c0 == 0.0 && terms.first().is_some_and(|t| t.1 == -1.0) {
                    self.neg += 1;
                }
            }
            Rhs::Prod { coef, num, den } => {
                let n = num.len() + usize::from(coef.abs() != 1.0);
                self.mul += n.saturating_sub(1) + den.len().saturating_sub(1);
                if !den.is_empty() {
                    self.div += 1;
                }
                if *coef < 0.0 && coef.abs() == 1.0 && !num.is_empty() {
                    self.neg += 1;
                }
            }
            Rhs::Call1(Fn1::Sqrt, _) => self.sqrt += 1,
            Rhs::Call1(Fn1::Abs, _) => self.neg += 1,
            Rhs::Call1(..) | Rhs::Call2(..) | Rhs::SinCos(_) => self.func += 1,
        }
    }
}

/// The lowered form of a set of roots.
pub(crate) struct Lowered {
    pub insts: Vec<Inst>,
    pub n_temps: u32,
    /// The operand of each root.
    pub roots: Vec<Operand>,
}

#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Exponent {
    /// Integer power `k ≠ 0`.
    Int(i64),
    /// `p/2` with `p` odd: `sqrt(x)^p`.
    Half(i64),
    /// Anything else: a general power.
    Other,
}

fn classify(r: &Rational) -> Exponent {
    match r.as_small() {
        Some((k, 1)) => Exponent::Int(k),
        Some((p, 2)) => Exponent::Half(p),
        _ => Exponent::Other,
    }
}

struct Lowerer<'a> {
    dag: &'a Dag,
    insts: Vec<Inst>,
    n_temps: u32,
    memo: HashMap<Expr, Operand>,
    pow_memo: HashMap<(OpKey, i64), Operand>,
    sqrt_memo: HashMap<OpKey, Operand>,
    recip_memo: HashMap<OpKey, Operand>,
    powf_memo: HashMap<(OpKey, u64), Operand>,
    mono_memo: HashMap<Vec<(Expr, Rational)>, Operand>,
    /// Factor lists that occur with two or more distinct coefficients.
    shared_monomials: HashSet<Vec<(Expr, Rational)>>,
    /// Denominator atoms `(base, through sqrt)` used by two or more products.
    shared_denominators: HashSet<(Expr, bool)>,
    /// Arguments of both a `sin` and a `cos`.
    sincos_args: HashSet<Expr>,
    sincos_memo: HashMap<Expr, (Operand, Operand)>,
}

/// Lower `roots` (whose DAG is `dag`).
pub(crate) fn lower(dag: &Dag, roots: &[Expr]) -> Result<Lowered, CodegenError> {
    // Pre-pass: which monomials, denominators and trigonometric arguments are shared.
    let mut coefs: HashMap<Vec<(Expr, Rational)>, HashSet<u64>> = HashMap::new();
    let mut sin_args = HashSet::new();
    let mut cos_args = HashSet::new();
    for e in &dag.order {
        match &dag.nodes[e] {
            Node::Product { coef, factors } => {
                coefs.entry(factors.clone()).or_default().insert(coef.to_bits());
            }
            Node::Func(Func::Sin, a) => {
                sin_args.insert(*a);
            }
            Node::Func(Func::Cos, a) => {
                cos_args.insert(*a);
            }
            _ => {}
        }
    }
    let shared_monomials: HashSet<_> = coefs.iter().filter(|(_, c)| c.len() >= 2).map(|(k, _)| k.clone()).collect();
    let mut den_uses: HashMap<(Expr, bool), usize> = HashMap::new();
    // Each distinct factor list is lowered once (shared or not), so count per list.
    for factors in coefs.keys() {
        for (b, r) in factors {
            match classify(r) {
                Exponent::Int(k) if k < 0 => *den_uses.entry((*b, false)).or_default() += 1,
                Exponent::Half(p) if p < 0 => *den_uses.entry((*b, true)).or_default() += 1,
                _ => {}
            }
        }
    }
    let shared_denominators = den_uses.into_iter().filter(|(_, n)| *n >= 2).map(|(k, _)| k).collect();
    let sincos_args = sin_args.intersection(&cos_args).copied().collect();

    let mut l = Lowerer {
        dag,
        insts: Vec::new(),
        n_temps: 0,
        memo: HashMap::new(),
        pow_memo: HashMap::new(),
        sqrt_memo: HashMap::new(),
        recip_memo: HashMap::new(),
        powf_memo: HashMap::new(),
        mono_memo: HashMap::new(),
        shared_monomials,
        shared_denominators,
        sincos_args,
        sincos_memo: HashMap::new(),
    };
    for &e in &dag.order {
        let op = l.node(e)?;
        l.memo.insert(e, op);
    }
    let roots = roots.iter().map(|r| l.memo[r]).collect();
    Ok(Lowered { insts: l.insts, n_temps: l.n_temps, roots })
}

impl Lowerer<'_> {
    fn push(&mut self, rhs: Rhs) -> Operand {
        if let Some(x) = fold(&rhs) {
            return Operand::Lit(x);
        }
        let def = self.n_temps;
        self.n_temps += rhs.defs();
        self.insts.push(Inst { def, rhs });
        Operand::Temp(def)
    }

    fn node(&mut self, e: Expr) -> Result<Operand, CodegenError> {
        let node = self.dag.nodes[&e].clone();
        Ok(match node {
            Node::Number(x) => Operand::Lit(x),
            Node::Param(k) => Operand::Param(k),
            Node::Sum { c0, terms } => {
                let terms = terms.iter().map(|(x, c)| (self.memo[x], *c)).collect();
                self.push(Rhs::Sum { c0, terms })
            }
            Node::Product { coef, factors } => {
                if self.shared_monomials.contains(&factors) {
                    let m = self.monomial(&factors);
                    if coef == 1.0 { m } else { self.push(Rhs::Prod { coef, num: vec![m], den: vec![] }) }
                } else {
                    self.product(coef, &factors)
                }
            }
            Node::Pow(a, b) => {
                let (a, b) = (self.memo[&a], self.memo[&b]);
                self.push(Rhs::Call2(Fn2::Pow, a, b))
            }
            Node::Atan2(y, x) => {
                let (y, x) = (self.memo[&y], self.memo[&x]);
                self.push(Rhs::Call2(Fn2::Atan2, y, x))
            }
            Node::Func(f, a) => {
                let x = self.memo[&a];
                match f {
                    Func::Sin | Func::Cos if self.sincos_args.contains(&a) && !matches!(x, Operand::Lit(_)) => {
                        let (s, c) = match self.sincos_memo.get(&a) {
                            Some(sc) => *sc,
                            None => {
                                let Operand::Temp(t) = self.push(Rhs::SinCos(x)) else { unreachable!("not a literal") };
                                let sc = (Operand::Temp(t), Operand::Temp(t + 1));
                                self.sincos_memo.insert(a, sc);
                                sc
                            }
                        };
                        if f == Func::Sin { s } else { c }
                    }
                    _ => {
                        let g = match f {
                            Func::Sin => Fn1::Sin,
                            Func::Cos => Fn1::Cos,
                            Func::Tan => Fn1::Tan,
                            Func::Exp => Fn1::Exp,
                            Func::Ln => Fn1::Ln,
                            Func::Abs => Fn1::Abs,
                        };
                        self.push(Rhs::Call1(g, x))
                    }
                }
            }
        })
    }

    fn monomial(&mut self, factors: &[(Expr, Rational)]) -> Operand {
        if let Some(m) = self.mono_memo.get(factors) {
            return *m;
        }
        let m = self.product(1.0, factors);
        self.mono_memo.insert(factors.to_vec(), m);
        m
    }

    fn product(&mut self, coef: f64, factors: &[(Expr, Rational)]) -> Operand {
        let mut coef = coef;
        let mut num = Vec::new();
        let mut den = Vec::new();
        for (b, r) in factors {
            let x = self.memo[b];
            match classify(r) {
                Exponent::Int(k) if k > 0 => num.push(self.pow(x, k)),
                Exponent::Int(k) => {
                    if self.shared_denominators.contains(&(*b, false)) {
                        let rx = self.recip(x);
                        num.push(self.pow(rx, -k));
                    } else {
                        den.push(self.pow(x, -k));
                    }
                }
                Exponent::Half(p) => {
                    let s = self.sqrt(x);
                    if p > 0 {
                        num.push(self.pow(s, p));
                    } else if self.shared_denominators.contains(&(*b, true)) {
                        let rs = self.recip(s);
                        num.push(self.pow(rs, -p));
                    } else {
                        den.push(self.pow(s, -p));
                    }
                }
                Exponent::Other => num.push(self.powf(x, r.to_f64())),
            }
        }
        // Numbers go into the coefficient.
        num.retain(|o| match o {
            Operand::Lit(v) => {
                coef *= v;
                false
            }
            _ => true,
        });
        den.retain(|o| match o {
            Operand::Lit(v) => {
                coef /= v;
                false
            }
            _ => true,
        });
        if num.len() == 1 && den.is_empty() && coef == 1.0 {
            return num[0];
        }
        if num.is_empty() && den.is_empty() {
            return Operand::Lit(coef);
        }
        self.push(Rhs::Prod { coef, num, den })
    }

    /// `x^k`, `k ≥ 1`, by a shared square-and-multiply chain.
    fn pow(&mut self, x: Operand, k: i64) -> Operand {
        if k == 1 {
            return x;
        }
        if let Operand::Lit(v) = x {
            return Operand::Lit(v.powi(k as i32));
        }
        if let Some(o) = self.pow_memo.get(&(x.key(), k)) {
            return *o;
        }
        let o = if k % 2 == 0 {
            let h = self.pow(x, k / 2);
            self.push(Rhs::Prod { coef: 1.0, num: vec![h, h], den: vec![] })
        } else {
            let h = self.pow(x, k - 1);
            self.push(Rhs::Prod { coef: 1.0, num: vec![h, x], den: vec![] })
        };
        self.pow_memo.insert((x.key(), k), o);
        o
    }

    fn sqrt(&mut self, x: Operand) -> Operand {
        if let Some(o) = self.sqrt_memo.get(&x.key()) {
            return *o;
        }
        let o = self.push(Rhs::Call1(Fn1::Sqrt, x));
        self.sqrt_memo.insert(x.key(), o);
        o
    }

    fn recip(&mut self, x: Operand) -> Operand {
        if let Some(o) = self.recip_memo.get(&x.key()) {
            return *o;
        }
        let o = self.push(Rhs::Prod { coef: 1.0, num: vec![], den: vec![x] });
        self.recip_memo.insert(x.key(), o);
        o
    }

    fn powf(&mut self, x: Operand, e: f64) -> Operand {
        if let Some(o) = self.powf_memo.get(&(x.key(), e.to_bits())) {
            return *o;
        }
        let o = self.push(Rhs::Call2(Fn2::Pow, x, Operand::Lit(e)));
        self.powf_memo.insert((x.key(), e.to_bits()), o);
        o
    }
}

/// The value of an instruction whose operands are all literals (evaluated in `f64` at
/// generation time), if it defines a single value.
fn fold(rhs: &Rhs) -> Option<f64> {
    let lit = |o: &Operand| match o {
        Operand::Lit(v) => Some(*v),
        _ => None,
    };
    match rhs {
        Rhs::Sum { c0, terms } => {
            let mut acc = *c0;
            for (x, c) in terms {
                acc += c * lit(x)?;
            }
            Some(acc)
        }
        Rhs::Prod { coef, num, den } => {
            let mut n = *coef;
            for x in num {
                n *= lit(x)?;
            }
            let mut d = 1.0;
            for x in den {
                d *= lit(x)?;
            }
            Some(n / d)
        }
        Rhs::Call1(f, x) => {
            let x = lit(x)?;
            Some(match f {
                Fn1::Sqrt => x.sqrt(),
                Fn1::Sin => x.sin(),
                Fn1::Cos => x.cos(),
                Fn1::Tan => x.tan(),
                Fn1::Exp => x.exp(),
                Fn1::Ln => x.ln(),
                Fn1::Abs => x.abs(),
            })
        }
        Rhs::Call2(f, x, y) => {
            let (x, y) = (lit(x)?, lit(y)?);
            Some(match f {
                Fn2::Pow => x.powf(y),
                Fn2::Atan2 => x.atan2(y),
            })
        }
        Rhs::SinCos(_) => None,
    }
}
