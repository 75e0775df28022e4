//! Lowering of the DAG to straight-line instructions: one temporary per unique operation.
//!
//! Beyond one-node-one-temporary, the lowering does what the pool's canonical form leaves to
//! the code generator:
//! * **Powers** by multiplication chains shared between products (`x²` is computed once
//!   wherever a product contains `x²` or `x³`); half-integer powers through one `sqrt`.
//!   Bases with one exponent in a product share one chain when none of their powers exists
//!   already: `m·l²·x²` is `m·(l x)²`.
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
    Prod {
        coef: f64,
        num: Vec<Operand>,
        den: Vec<Operand>,
    },
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
#[derive(Clone)]
pub(crate) struct Lowered {
    pub insts: Vec<Inst>,
    pub n_temps: u32,
    /// The value of each root: an operand, negated if the flag is set (other scales are
    /// materialised).
    pub roots: Vec<(Operand, bool)>,
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

/// A lowered value: `scale · op`. Scales are folded into the coefficients of the sums and
/// products that use the value, so `k/m`, `−k/m` and `2k/m` share one computation and a
/// negation costs nothing unless it reaches an output or a function argument.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Val {
    op: Operand,
    scale: f64,
}

impl Val {
    fn of(op: Operand) -> Val {
        Val { op, scale: 1.0 }
    }
}

/// What the first pass learns for the second: which bases share a reciprocal, which bases a
/// checked pivot keeps away from zero. Both keyed by the first pass's operand of the base
/// (its class: expressions that lower to the same value up to a scale).
#[derive(Default)]
struct Analysis {
    class: HashMap<Expr, OpKey>,
    shared_denominators: HashSet<(OpKey, bool)>,
    nonzero: HashSet<OpKey>,
}

struct Lowerer<'a> {
    dag: &'a Dag,
    insts: Vec<Inst>,
    n_temps: u32,
    memo: HashMap<Expr, Val>,
    pow_memo: HashMap<(OpKey, i64), Operand>,
    sqrt_memo: HashMap<OpKey, Operand>,
    recip_memo: HashMap<OpKey, Operand>,
    powf_memo: HashMap<(OpKey, u64), Operand>,
    call_memo: HashMap<(u8, OpKey, OpKey), Operand>,
    scaled_memo: HashMap<(OpKey, u64), Operand>,
    mono_memo: HashMap<Vec<(OpKey, Rational)>, Operand>,
    sum_memo: HashMap<(u64, Vec<(OpKey, u64)>), Operand>,
    /// The terms of every sum temporary (`c0`, terms as in its instruction), for
    /// [`Lowerer::expand_cancelling_sums`].
    sum_terms: HashMap<u32, (f64, Vec<(Operand, f64)>)>,
    sincos_memo: HashMap<OpKey, (Operand, Operand)>,
    /// Arguments of both a `sin` and a `cos`.
    sincos_args: HashSet<Expr>,
    /// From the first pass (empty during it).
    analysis: Analysis,
    /// Recorded during the first pass: uses of each denominator atom by distinct monomials,
    /// and the factors of each monomial.
    den_count: HashMap<(OpKey, bool), usize>,
    mono_factors: HashMap<OpKey, Vec<(OpKey, Rational)>>,
}

/// Lower `roots` (whose DAG is `dag`). `pivots` are the values that the validity checks keep
/// away from zero: a base that is one of them (or a factor of one) cancels against itself
/// (`x²·x⁻² → 1`), which is exact wherever the checks pass.
pub(crate) fn lower(dag: &Dag, roots: &[Expr], pivots: &[Expr]) -> Result<Lowered, CodegenError> {
    let mut sin_args = HashSet::new();
    let mut cos_args = HashSet::new();
    for e in &dag.order {
        match &dag.nodes[e] {
            Node::Func(Func::Sin, a) => {
                sin_args.insert(*a);
            }
            Node::Func(Func::Cos, a) => {
                cos_args.insert(*a);
            }
            _ => {}
        }
    }
    let sincos_args: HashSet<Expr> = sin_args.intersection(&cos_args).copied().collect();

    // Pass 1: plain lowering, to learn the classes, the shared denominators and the pivots.
    let first = run(dag, sincos_args.clone(), Analysis::default())?;
    let mut analysis = Analysis::default();
    for (e, v) in &first.memo {
        if !matches!(v.op, Operand::Lit(_)) {
            analysis.class.insert(*e, v.op.key());
        }
    }
    analysis.shared_denominators = first
        .den_count
        .iter()
        .filter(|(_, n)| **n >= 2)
        .map(|(k, _)| *k)
        .collect();
    for p in pivots {
        let Some(v) = first.memo.get(p) else { continue };
        if matches!(v.op, Operand::Lit(_)) {
            continue;
        }
        analysis.nonzero.insert(v.op.key());
        // A finite nonzero product has nonzero factors (those with positive exponents).
        if let Some(f) = first.mono_factors.get(&v.op.key()) {
            for (k, r) in f {
                if !r.is_negative() {
                    analysis.nonzero.insert(*k);
                }
            }
        }
    }

    // Pass 2: with what pass 1 found.
    let mut l = run(dag, sincos_args, analysis)?;
    let mut out = Vec::with_capacity(roots.len());
    for r in roots {
        let v = l.memo[r];
        out.push(
            if v.scale == 1.0 || v.scale == -1.0 || matches!(v.op, Operand::Lit(_)) {
                match v.op {
                    Operand::Lit(x) => (Operand::Lit(x * v.scale), false),
                    op => (op, v.scale == -1.0),
                }
            } else {
                (l.materialize(v), false)
            },
        );
    }
    let mut lowered = Lowered {
        insts: l.insts,
        n_temps: l.n_temps,
        roots: out,
    };
    common_pairs(&mut lowered);
    renumber(&mut lowered);
    Ok(lowered)
}

/// The terms sorted by operand, equal operands merged (coefficients added), zero
/// coefficients dropped.
fn merge_terms(mut terms: Vec<(Operand, f64)>) -> Vec<(Operand, f64)> {
    terms.sort_by_key(|a| a.0.key());
    let mut merged: Vec<(Operand, f64)> = Vec::with_capacity(terms.len());
    for (op, c) in terms {
        match merged.last_mut() {
            Some(last) if last.0 == op => last.1 += c,
            _ => merged.push((op, c)),
        }
    }
    merged.retain(|t| t.1 != 0.0);
    merged
}

/// Work budget of [`common_pairs`] (pair occurrences counted over all iterations): bounds the
/// generation time of very large models, where the pass then stops early.
const PAIR_BUDGET: usize = 50_000_000;

/// A pair of operands that several products multiply, or several sums add with the same
/// coefficient ratio.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Pair {
    Mul(OpKey, OpKey),
    /// `a + ratio·b` (ratio as bits).
    Add(OpKey, OpKey, u64),
}

fn pairs_of(rhs: &Rhs, out: &mut Vec<Pair>) {
    out.clear();
    match rhs {
        Rhs::Prod { num, .. } if num.len() >= 2 => {
            for i in 0..num.len() {
                for j in i + 1..num.len() {
                    let (x, y) = (num[i].key(), num[j].key());
                    out.push(if x <= y {
                        Pair::Mul(x, y)
                    } else {
                        Pair::Mul(y, x)
                    });
                }
            }
        }
        Rhs::Sum { terms, .. } if terms.len() >= 2 => {
            for i in 0..terms.len() {
                for j in i + 1..terms.len() {
                    let ((x, cx), (y, cy)) = (terms[i], terms[j]);
                    let ((a, ca), (b, cb)) = if x.key() <= y.key() {
                        ((x, cx), (y, cy))
                    } else {
                        ((y, cy), (x, cx))
                    };
                    let ratio = cb / ca;
                    // Only exact ratios: `ca·(a + ratio·b)` must be `ca·a + cb·b` term by term.
                    if ratio * ca == cb && ratio.is_finite() {
                        out.push(Pair::Add(a.key(), b.key(), ratio.to_bits()));
                    }
                }
            }
        }
        _ => {}
    }
    out.sort_unstable();
    out.dedup();
}

/// Greedy extraction of common pairs: the pair that most instructions share becomes one
/// temporary (or reuses an instruction that computes exactly it), until no pair is shared.
/// Each step saves one multiplication or addition per sharing instruction but one.
fn common_pairs(l: &mut Lowered) {
    let mut budget = PAIR_BUDGET;
    let mut buf = Vec::new();
    let operand_of = |k: OpKey| match k {
        OpKey::Temp(t) => Operand::Temp(t),
        OpKey::Param(p) => Operand::Param(p),
        OpKey::Lit(b) => Operand::Lit(f64::from_bits(b)),
    };
    loop {
        let mut counts: HashMap<Pair, usize> = HashMap::new();
        for inst in &l.insts {
            pairs_of(&inst.rhs, &mut buf);
            budget = budget.saturating_sub(buf.len());
            for p in &buf {
                *counts.entry(*p).or_default() += 1;
            }
        }
        if budget == 0 {
            return;
        }
        let Some((&pair, _)) = counts
            .iter()
            .filter(|(_, n)| **n >= 2)
            .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        else {
            return;
        };
        let users: Vec<usize> = (0..l.insts.len())
            .filter(|&i| {
                pairs_of(&l.insts[i].rhs, &mut buf);
                buf.contains(&pair)
            })
            .collect();
        // An instruction that is exactly the pair (coefficient 1, nothing else) and comes
        // before every other user can be reused.
        let exact = users
            .iter()
            .copied()
            .find(|&i| match (&l.insts[i].rhs, pair) {
                (Rhs::Prod { coef, num, den }, Pair::Mul(..)) => {
                    *coef == 1.0 && num.len() == 2 && den.is_empty()
                }
                // `a + ratio·b` exactly: the coefficient of the lower-keyed term is 1 (then the other
                // one is `ratio`, since the instruction contains the pair).
                (Rhs::Sum { c0, terms }, Pair::Add(..)) => {
                    *c0 == 0.0 && terms.len() == 2 && {
                        let low = if terms[0].0.key() <= terms[1].0.key() {
                            terms[0]
                        } else {
                            terms[1]
                        };
                        low.1 == 1.0
                    }
                }
                _ => false,
            });
        let (target, first_user) = match exact {
            Some(i) if i == users[0] => (Operand::Temp(l.insts[i].def), 1),
            _ => {
                let def = l.n_temps;
                l.n_temps += 1;
                let rhs = match pair {
                    Pair::Mul(a, b) => Rhs::Prod {
                        coef: 1.0,
                        num: vec![operand_of(a), operand_of(b)],
                        den: vec![],
                    },
                    Pair::Add(a, b, r) => Rhs::Sum {
                        c0: 0.0,
                        terms: vec![(operand_of(a), 1.0), (operand_of(b), f64::from_bits(r))],
                    },
                };
                l.insts.insert(users[0], Inst { def, rhs });
                (Operand::Temp(def), 0)
            }
        };
        let shift = usize::from(first_user == 0);
        for (n, &u) in users.iter().enumerate() {
            if n < first_user {
                continue;
            }
            let i = u + shift;
            match (&mut l.insts[i].rhs, pair) {
                (Rhs::Prod { num, .. }, Pair::Mul(a, b)) => {
                    let ia = num.iter().position(|o| o.key() == a).expect("pair member");
                    num.remove(ia);
                    let ib = num.iter().position(|o| o.key() == b).expect("pair member");
                    num.remove(ib);
                    num.push(target);
                }
                (Rhs::Sum { terms, .. }, Pair::Add(a, b, _)) => {
                    let ia = terms
                        .iter()
                        .position(|t| t.0.key() == a)
                        .expect("pair member");
                    let ca = terms.remove(ia).1;
                    let ib = terms
                        .iter()
                        .position(|t| t.0.key() == b)
                        .expect("pair member");
                    terms.remove(ib);
                    terms.push((target, ca));
                    // Keep a positive term first (no leading negation).
                    if let Some(k) = terms.iter().position(|t| t.1 > 0.0) {
                        let t = terms.remove(k);
                        terms.insert(0, t);
                    }
                }
                _ => unreachable!("users contain the pair"),
            }
        }
    }
}

/// Drop copies (`let t = u;`, left by [`common_pairs`] when a user was exactly the pair) and
/// number temporaries in order of definition.
fn renumber(l: &mut Lowered) {
    let mut alias: HashMap<u32, Operand> = HashMap::new();
    let resolve = |o: &mut Operand, alias: &HashMap<u32, Operand>| {
        while let Operand::Temp(t) = *o {
            match alias.get(&t) {
                Some(a) => *o = *a,
                None => break,
            }
        }
    };
    let mut kept = Vec::with_capacity(l.insts.len());
    for mut inst in std::mem::take(&mut l.insts) {
        match &mut inst.rhs {
            Rhs::Sum { terms, .. } => terms.iter_mut().for_each(|t| resolve(&mut t.0, &alias)),
            Rhs::Prod { num, den, .. } => num
                .iter_mut()
                .chain(den.iter_mut())
                .for_each(|o| resolve(o, &alias)),
            Rhs::Call1(_, x) | Rhs::SinCos(x) => resolve(x, &alias),
            Rhs::Call2(_, x, y) => {
                resolve(x, &alias);
                resolve(y, &alias);
            }
        }
        let copy = match &inst.rhs {
            Rhs::Prod { coef, num, den } if *coef == 1.0 && num.len() == 1 && den.is_empty() => {
                Some(num[0])
            }
            Rhs::Sum { c0, terms } if *c0 == 0.0 && terms.len() == 1 && terms[0].1 == 1.0 => {
                Some(terms[0].0)
            }
            _ => None,
        };
        match copy {
            Some(o) => {
                alias.insert(inst.def, o);
            }
            None => kept.push(inst),
        }
    }
    l.insts = kept;
    for r in l.roots.iter_mut() {
        resolve(&mut r.0, &alias);
    }
    let mut map: HashMap<u32, u32> = HashMap::with_capacity(l.n_temps as usize);
    let mut next = 0;
    for inst in &l.insts {
        for d in 0..inst.rhs.defs() {
            map.insert(inst.def + d, next + d);
        }
        next += inst.rhs.defs();
    }
    let f = |o: &mut Operand| {
        if let Operand::Temp(t) = o {
            *t = map[t];
        }
    };
    for inst in l.insts.iter_mut() {
        inst.def = map[&inst.def];
        match &mut inst.rhs {
            Rhs::Sum { terms, .. } => terms.iter_mut().for_each(|t| f(&mut t.0)),
            Rhs::Prod { num, den, .. } => num.iter_mut().chain(den.iter_mut()).for_each(f),
            Rhs::Call1(_, x) | Rhs::SinCos(x) => f(x),
            Rhs::Call2(_, x, y) => {
                f(x);
                f(y);
            }
        }
    }
    for r in l.roots.iter_mut() {
        f(&mut r.0);
    }
    l.n_temps = next;
}

fn run(
    dag: &Dag,
    sincos_args: HashSet<Expr>,
    analysis: Analysis,
) -> Result<Lowerer<'_>, CodegenError> {
    let mut l = Lowerer {
        dag,
        insts: Vec::new(),
        n_temps: 0,
        memo: HashMap::new(),
        pow_memo: HashMap::new(),
        sqrt_memo: HashMap::new(),
        recip_memo: HashMap::new(),
        powf_memo: HashMap::new(),
        call_memo: HashMap::new(),
        scaled_memo: HashMap::new(),
        mono_memo: HashMap::new(),
        sum_memo: HashMap::new(),
        sum_terms: HashMap::new(),
        sincos_memo: HashMap::new(),
        sincos_args,
        analysis,
        den_count: HashMap::new(),
        mono_factors: HashMap::new(),
    };
    for &e in &dag.order {
        let v = l.node(e)?;
        l.memo.insert(e, v);
    }
    Ok(l)
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

    /// `scale · op` as one operand.
    fn materialize(&mut self, v: Val) -> Operand {
        if v.scale == 1.0 {
            return v.op;
        }
        if let Operand::Lit(x) = v.op {
            return Operand::Lit(x * v.scale);
        }
        let key = (v.op.key(), v.scale.to_bits());
        if let Some(o) = self.scaled_memo.get(&key) {
            return *o;
        }
        let o = self.push(Rhs::Prod {
            coef: v.scale,
            num: vec![v.op],
            den: vec![],
        });
        self.scaled_memo.insert(key, o);
        o
    }

    fn call1(&mut self, f: Fn1, x: Operand) -> Operand {
        let key = (f as u8, x.key(), x.key());
        if let Some(o) = self.call_memo.get(&key) {
            return *o;
        }
        let o = self.push(Rhs::Call1(f, x));
        self.call_memo.insert(key, o);
        o
    }

    fn call2(&mut self, f: Fn2, x: Operand, y: Operand) -> Operand {
        let key = (16 + f as u8, x.key(), y.key());
        if let Some(o) = self.call_memo.get(&key) {
            return *o;
        }
        let o = self.push(Rhs::Call2(f, x, y));
        self.call_memo.insert(key, o);
        o
    }

    fn node(&mut self, e: Expr) -> Result<Val, CodegenError> {
        let node = self.dag.nodes[&e].clone();
        Ok(match node {
            Node::Number(x) => Val::of(Operand::Lit(x)),
            Node::Param(k) => Val::of(Operand::Param(k)),
            Node::Sum { c0, terms } => self.sum(c0, &terms),
            Node::Product { coef, factors } => self.product(coef, &factors),
            Node::Pow(a, b) => {
                let (a, b) = (self.memo[&a], self.memo[&b]);
                let (a, b) = (self.materialize(a), self.materialize(b));
                Val::of(self.call2(Fn2::Pow, a, b))
            }
            Node::Atan2(y, x) => {
                let (y, x) = (self.memo[&y], self.memo[&x]);
                let (y, x) = (self.materialize(y), self.materialize(x));
                Val::of(self.call2(Fn2::Atan2, y, x))
            }
            Node::Func(f, a) => {
                let v = self.memo[&a];
                // Odd and even functions absorb a sign; abs absorbs any scale.
                let (x, outer) = match (f, v.scale) {
                    (Func::Abs, s) => (v.op, s.abs()),
                    (Func::Sin | Func::Tan, -1.0) => (v.op, -1.0),
                    (Func::Cos, -1.0) => (v.op, 1.0),
                    _ => (self.materialize(v), 1.0),
                };
                let op = match f {
                    Func::Sin | Func::Cos
                        if self.sincos_args.contains(&a) && !matches!(x, Operand::Lit(_)) =>
                    {
                        let (s, c) = match self.sincos_memo.get(&x.key()) {
                            Some(sc) => *sc,
                            None => {
                                let Operand::Temp(t) = self.push(Rhs::SinCos(x)) else {
                                    unreachable!("not a literal")
                                };
                                let sc = (Operand::Temp(t), Operand::Temp(t + 1));
                                self.sincos_memo.insert(x.key(), sc);
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
                        self.call1(g, x)
                    }
                };
                Val { op, scale: outer }
            }
        })
    }

    fn sum(&mut self, c0: f64, terms: &[(Expr, f64)]) -> Val {
        let mut c0 = c0;
        let mut acc: Vec<(Operand, f64)> = Vec::with_capacity(terms.len());
        for (t, c) in terms {
            let v = self.memo[t];
            match v.op {
                Operand::Lit(x) => c0 += c * v.scale * x,
                op => acc.push((op, c * v.scale)),
            }
        }
        // Terms that became the same value (up to a scale) merge.
        let mut merged = merge_terms(acc);
        self.expand_cancelling_sums(&mut c0, &mut merged);
        if merged.is_empty() {
            return Val::of(Operand::Lit(c0));
        }
        if merged.len() == 1 && c0 == 0.0 {
            return Val {
                op: merged[0].0,
                scale: merged[0].1,
            };
        }
        // Canonical sign: the first term positive (so `a − b` and `b − a` share).
        let sign = if merged[0].1 < 0.0 { -1.0 } else { 1.0 };
        if sign < 0.0 {
            c0 = -c0;
            for t in merged.iter_mut() {
                t.1 = -t.1;
            }
        }
        // `+0.0` and `-0.0` are the same constant term.
        if c0 == 0.0 {
            c0 = 0.0;
        }
        let key = (
            c0.to_bits(),
            merged
                .iter()
                .map(|t| (t.0.key(), t.1.to_bits()))
                .collect::<Vec<_>>(),
        );
        if let Some(o) = self.sum_memo.get(&key) {
            return Val {
                op: *o,
                scale: sign,
            };
        }
        let o = self.push(Rhs::Sum {
            c0,
            terms: merged.clone(),
        });
        if let Operand::Temp(t) = o {
            self.sum_terms.insert(t, (c0, merged));
        }
        self.sum_memo.insert(key, o);
        Val { op: o, scale: sign }
    }

    /// Expands a term that is itself a sum temporary when that cancels terms, so that
    /// `a + b − (a + b − c)` is computed as `c`, not as `c` plus rounding noise. The pool
    /// flattens nested sums itself; such a term reaches the lowering as a product whose
    /// factors cancel only here (`cos λ · S / cos λ`: the pool keeps `x/x` unless `x` is
    /// provably nonzero, and the lowering cancels it when a validity check keeps `x` away from
    /// zero). Expanded only when the sum gets no more operations than before.
    fn expand_cancelling_sums(&self, c0: &mut f64, terms: &mut Vec<(Operand, f64)>) {
        let size = |c0: f64, t: &[(Operand, f64)]| t.len() + usize::from(c0 != 0.0);
        let mut k = 0;
        while k < terms.len() {
            let (op, c) = terms[k];
            let inner = match op {
                Operand::Temp(u) => self.sum_terms.get(&u),
                _ => None,
            };
            let Some((ic0, inner)) = inner else {
                k += 1;
                continue;
            };
            let cand: Vec<(Operand, f64)> = terms
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != k)
                .map(|(_, t)| *t)
                .chain(inner.iter().map(|&(o, ci)| (o, ci * c)))
                .collect();
            let unmerged = cand.len();
            let m = merge_terms(cand);
            let cc0 = *c0 + ic0 * c;
            if m.len() < unmerged && size(cc0, &m) <= size(*c0, terms) {
                *c0 = cc0;
                *terms = m;
                k = 0;
            } else {
                k += 1;
            }
        }
    }

    fn product(&mut self, coef: f64, factors: &[(Expr, Rational)]) -> Val {
        let mut coef = coef;
        // Bases with their scales folded into the coefficient where the power allows it.
        let mut items: Vec<(Operand, Rational, Option<OpKey>)> = Vec::with_capacity(factors.len());
        for (b, r) in factors {
            let v = self.memo[b];
            let class = self.analysis.class.get(b).copied();
            if let Operand::Lit(x) = v.op {
                let x = x * v.scale;
                coef *= match classify(r) {
                    Exponent::Int(k) => x.powi(k as i32),
                    _ => x.powf(r.to_f64()),
                };
                continue;
            }
            match classify(r) {
                Exponent::Int(k) => {
                    coef *= v.scale.powi(k as i32);
                    items.push((v.op, r.clone(), class));
                }
                _ if v.scale > 0.0 => {
                    coef *= v.scale.powf(r.to_f64());
                    items.push((v.op, r.clone(), class));
                }
                _ => {
                    let m = self.materialize(v);
                    items.push((m, r.clone(), class));
                }
            }
        }
        // Equal bases merge: exponents of one sign always, of both signs when a checked
        // pivot keeps the base away from zero.
        items.sort_by(|a, b| a.0.key().cmp(&b.0.key()).then(a.1.cmp(&b.1)));
        let mut merged: Vec<(Operand, Rational, Option<OpKey>)> = Vec::with_capacity(items.len());
        for it in items {
            if let Some(last) = merged.last_mut()
                && last.0 == it.0
            {
                let same_sign = last.1.is_negative() == it.1.is_negative();
                let nonzero = it.2.is_some_and(|c| self.analysis.nonzero.contains(&c))
                    || last.2.is_some_and(|c| self.analysis.nonzero.contains(&c));
                if (same_sign || nonzero)
                    && let Ok(s) = last.1.add(&it.1)
                {
                    last.1 = s;
                    continue;
                }
            }
            merged.push(it);
        }
        merged.retain(|m| !m.1.is_zero());
        if merged.is_empty() {
            return Val::of(Operand::Lit(coef));
        }
        if merged.len() == 1 && merged[0].1.is_one() {
            return Val {
                op: merged[0].0,
                scale: coef,
            };
        }
        let key: Vec<(OpKey, Rational)> = merged.iter().map(|m| (m.0.key(), m.1.clone())).collect();
        if let Some(o) = self.mono_memo.get(&key) {
            return Val {
                op: *o,
                scale: coef,
            };
        }
        let o = self.monomial(&merged);
        self.mono_memo.insert(key.clone(), o);
        if let Operand::Temp(_) = o {
            self.mono_factors.insert(o.key(), key);
        }
        Val { op: o, scale: coef }
    }

    /// `Π base^exponent` (coefficient 1).
    fn monomial(&mut self, items: &[(Operand, Rational, Option<OpKey>)]) -> Operand {
        let mut num = Vec::new();
        let mut den = Vec::new();
        let grouped = self.group_equal_powers(items);
        let items: Vec<&(Operand, Rational, Option<OpKey>)> = match &grouped {
            Some((product, k, rest)) => {
                num.push(self.pow(*product, *k));
                rest.iter().map(|&i| &items[i]).collect()
            }
            None => items.iter().collect(),
        };
        for (x, r, class) in items {
            let x = *x;
            let shared = |half: bool, l: &Self| {
                class.is_some_and(|c| l.analysis.shared_denominators.contains(&(c, half)))
            };
            match classify(r) {
                Exponent::Int(k) if k > 0 => num.push(self.pow(x, k)),
                Exponent::Int(k) => {
                    *self.den_count.entry((x.key(), false)).or_default() += 1;
                    if shared(false, self) {
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
                    } else {
                        *self.den_count.entry((x.key(), true)).or_default() += 1;
                        if shared(true, self) {
                            let rs = self.recip(s);
                            num.push(self.pow(rs, -p));
                        } else {
                            den.push(self.pow(s, -p));
                        }
                    }
                }
                Exponent::Other => num.push(self.powf(x, r.to_f64())),
            }
        }
        if num.len() == 1 && den.is_empty() {
            return num[0];
        }
        self.push(Rhs::Prod {
            coef: 1.0,
            num,
            den,
        })
    }

    /// Bases that share one integer exponent `k ≥ 2` in a monomial: `a^k·b^k = (a·b)^k`
    /// takes `n − 1` multiplications and one chain instead of `n` chains and `n − 1`
    /// multiplications (`m·l²·x²`: 3 → 2, and `l·x` is often needed anyway). Only when none
    /// of those powers exists already, since sharing them is cheaper still. Returns the
    /// product of the bases, `k`, and the positions of the other items.
    fn group_equal_powers(
        &mut self,
        items: &[(Operand, Rational, Option<OpKey>)],
    ) -> Option<(Operand, i64, Vec<usize>)> {
        let exponent = |r: &Rational| match classify(r) {
            Exponent::Int(k) if k >= 2 => Some(k),
            _ => None,
        };
        // The exponent shared by the most bases (the largest on a tie).
        let mut best: Option<(usize, i64)> = None;
        for (x, r, _) in items {
            let Some(k) = exponent(r) else { continue };
            if matches!(x, Operand::Lit(_)) || self.pow_memo.contains_key(&(x.key(), k)) {
                return None;
            }
            let n = items
                .iter()
                .filter(|(y, s, _)| !matches!(y, Operand::Lit(_)) && exponent(s) == Some(k))
                .count();
            if best.is_none_or(|(bn, bk)| (n, k) > (bn, bk)) {
                best = Some((n, k));
            }
        }
        let (n, k) = best?;
        if n < 2 {
            return None;
        }
        let (bases, rest): (Vec<usize>, Vec<usize>) =
            (0..items.len()).partition(|&i| exponent(&items[i].1) == Some(k));
        let one = Rational::int(1);
        let key: Vec<(OpKey, Rational)> = bases
            .iter()
            .map(|&i| (items[i].0.key(), one.clone()))
            .collect();
        let product = match self.mono_memo.get(&key) {
            Some(o) => *o,
            None => {
                let o = self.push(Rhs::Prod {
                    coef: 1.0,
                    num: bases.iter().map(|&i| items[i].0).collect(),
                    den: vec![],
                });
                self.mono_memo.insert(key.clone(), o);
                self.mono_factors.insert(o.key(), key);
                o
            }
        };
        Some((product, k, rest))
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
            self.push(Rhs::Prod {
                coef: 1.0,
                num: vec![h, h],
                den: vec![],
            })
        } else {
            let h = self.pow(x, k - 1);
            self.push(Rhs::Prod {
                coef: 1.0,
                num: vec![h, x],
                den: vec![],
            })
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
        let o = self.push(Rhs::Prod {
            coef: 1.0,
            num: vec![],
            den: vec![x],
        });
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Lowers `roots` over the parameters `ps` (interface positions in order), with `pivots`
    /// checked nonzero.
    fn lowered(roots: &[Expr], ps: &[Expr], pivots: &[Expr]) -> Lowered {
        let pos: HashMap<u32, u32> = ps
            .iter()
            .enumerate()
            .map(|(k, p)| (p.param_index().expect("param"), k as u32))
            .collect();
        let dag = crate::order::build(roots, &pos).expect("dag");
        lower(&dag, roots, pivots).expect("lower")
    }

    /// `a + b − cos x · (a + b − c) / cos x` is `c`: the pool keeps `cos x / cos x` (cos x may
    /// be zero), the lowering cancels it where a validity check keeps `cos x` nonzero (as in
    /// the bicycle, with `cos λ`), and then the sum must cancel too rather than compute `c`
    /// plus the rounding error of `a + b`.
    #[test]
    fn sums_that_cancel_after_a_cancelled_product_are_expanded() {
        let [a, b, c, x] = ["ea", "eb", "ec", "ex"].map(|n| Expr::param(n, 0.5).expect("param"));
        let inner = a + b - c;
        let cx = x.cos();
        let e = a + b - cx * inner * cx.recip();
        // The pool has not cancelled it (or this test tests nothing).
        assert!(e.to_string().contains("cos"), "{e}");
        let l = lowered(&[inner, e], &[a, b, c, x], &[cx]);
        let (op, neg) = l.roots[1];
        assert_eq!(op, Operand::Param(2), "{:?}", l.insts);
        assert!(!neg);
        // `a + b − c` is still computed once for the first root, and nothing else is.
        let sums = l
            .insts
            .iter()
            .filter(|i| matches!(i.rhs, Rhs::Sum { .. }))
            .count();
        assert_eq!(sums, 1, "{:?}", l.insts);
    }

    /// Expansion is refused when it would add operations: `d + cos x·(a + b + c)/cos x` keeps
    /// the shared sum as one term.
    #[test]
    fn sums_without_cancellation_are_not_expanded() {
        let [a, b, c, d, x] =
            ["fa", "fb", "fc", "fd", "fx"].map(|n| Expr::param(n, 0.5).expect("param"));
        let inner = a + b + c;
        let cx = x.cos();
        let e = d + cx * inner * cx.recip();
        let l = lowered(&[inner, e], &[a, b, c, d, x], &[cx]);
        let Operand::Temp(t) = l.roots[1].0 else {
            panic!("{:?}", l.roots)
        };
        let rhs = &l.insts.iter().find(|i| i.def == t).expect("def").rhs;
        let Rhs::Sum { terms, .. } = rhs else {
            panic!("{rhs:?}")
        };
        assert_eq!(terms.len(), 2, "{rhs:?}");
    }

    /// Multiplications of the instructions (a coefficient other than ±1 counts as one).
    fn multiplications(l: &Lowered) -> usize {
        l.insts
            .iter()
            .map(|i| match &i.rhs {
                Rhs::Prod { coef, num, den } => {
                    let factors = num.len() + den.len() + usize::from(coef.abs() != 1.0);
                    factors.saturating_sub(1)
                }
                _ => 0,
            })
            .sum()
    }

    /// `m·l²·x²` next to `l·x` (the shimmy's pivot) is `m·(l·x)²`: three multiplications in
    /// all, sharing `l·x`, where one chain per square takes four.
    #[test]
    fn equal_powers_are_grouped_and_share_their_base() {
        let [m, l, x] = ["gm", "gl", "gx"].map(|n| Expr::param(n, 0.5).expect("param"));
        let pivot = m * l.powi(2) * x.powi(2);
        let lowered = lowered(&[pivot, l * x], &[m, l, x], &[]);
        assert_eq!(multiplications(&lowered), 3, "{:?}", lowered.insts);
        let lx = |i: &Inst| {
            matches!(&i.rhs, Rhs::Prod { num, den, .. }
                if den.is_empty() && num.len() == 2 && num.contains(&Operand::Param(1))
                    && num.contains(&Operand::Param(2)))
        };
        assert_eq!(lowered.insts.iter().filter(|i| lx(i)).count(), 1);
    }

    /// A square that exists already is shared instead: `l²` then `m·l²·x²` keeps `l²`.
    #[test]
    fn equal_powers_are_not_grouped_when_a_power_exists() {
        let [m, l, x] = ["hm", "hl", "hx"].map(|n| Expr::param(n, 0.5).expect("param"));
        let square = l.powi(2);
        let lowered = lowered(&[square, m * square * x.powi(2)], &[m, l, x], &[]);
        // l², x², and the product of three: four, the same as grouping would take.
        assert_eq!(multiplications(&lowered), 4, "{:?}", lowered.insts);
        let ll = |i: &Inst| matches!(&i.rhs, Rhs::Prod { num, .. } if num == &[Operand::Param(1), Operand::Param(1)]);
        assert_eq!(
            lowered.insts.iter().filter(|i| ll(i)).count(),
            1,
            "{:?}",
            lowered.insts
        );
    }
}
