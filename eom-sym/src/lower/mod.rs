//! Lowering of an expression DAG to straight-line code: one instruction per unique operation,
//! over temporaries, parameters and literals. It is shared by the evaluation [`Tape`], which
//! interprets the instructions, and by the code generator (`eom-codegen`), which renders them
//! as Rust.
//!
//! How sums and products become instructions depends on the [`Rounding`]:
//!
//! * [`Rounding::Exact`] keeps the evaluation order of [`eval_generic`] (see
//!   [`Shape::eval`](crate::pool)): sums in the pool's term order, products factor by factor,
//!   integer powers by `powi`'s squarings, `x⁻¹` as a reciprocal. A program lowered this way
//!   computes the same values bit for bit; only rewrites that change no rounding are made
//!   (common subexpressions, `sin` and `cos` of one argument from one `sincos`, operations on
//!   literals folded the way they would be computed).
//! * [`Rounding::Free`] also makes the rewrites that change rounding but remove operations,
//!   which the pool's canonical form leaves to the code generator:
//!   * **Powers** by multiplication chains shared between products (`x²` is computed once
//!     wherever a product contains `x²` or `x³`); half-integer powers through one `sqrt`.
//!     Bases with one exponent in a product share one chain when none of their powers exists
//!     already: `m·l²·x²` is `m·(l x)²`.
//!   * **Denominators**: a base that appears with a negative exponent in two or more products
//!     gets one reciprocal that every product multiplies by; a base that divides only once is
//!     divided directly, and all such factors of a product share one division.
//!   * **Monomials that differ only in their coefficient** (`k/m`, `−k/m`, `2k/m`) are
//!     computed once and scaled.
//!   * **Common pairs**: a product of two operands (a sum of two with a fixed ratio) that
//!     several instructions contain becomes one temporary.
//!   * Equal bases of one product merge (`x²·x⁻² → 1`) where a validity check (a *pivot*)
//!     keeps the base away from zero.
//!
//!   Operands of sums and products are then in an order given by the structure of the DAG
//!   (not the pool's creation order), so that generated text is a function of the model alone.
//!
//! [`Tape`]: crate::Tape
//! [`eval_generic`]: crate::eval_generic

mod dag;
mod exact;
mod free;
mod pairs;
#[cfg(test)]
mod tests;

use crate::error::SymError;
use crate::expr::Expr;
use crate::func::{Call, Func, Parity};
use crate::pool::{Id, Shape, ShapeBuf};
use crate::rational::Rational;
use dag::Dag;
use hashbrown::{HashMap, HashSet};

/// An operand: a temporary, a parameter, or a literal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Operand {
    /// The temporary defined by an instruction (numbered in order of definition).
    Temp(u32),
    /// The parameter at this position.
    Param(u32),
    /// A literal.
    Lit(f64),
}

/// Hashable identity of an operand (literals by their bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum OpKey {
    /// A temporary.
    Temp(u32),
    /// A parameter.
    Param(u32),
    /// A literal's bits.
    Lit(u64),
}

impl Operand {
    /// The operand's identity.
    pub fn key(self) -> OpKey {
        match self {
            Operand::Temp(t) => OpKey::Temp(t),
            Operand::Param(p) => OpKey::Param(p),
            Operand::Lit(x) => OpKey::Lit(x.to_bits()),
        }
    }
}

/// The right-hand side of one instruction.
#[derive(Clone, Debug, PartialEq)]
pub enum Rhs {
    /// `c0 + Σ c·x`; with [`Rounding::Exact`], evaluated left to right as
    /// `((c0 + c₁x₁) + c₂x₂) + …`, `c0` left out when it is 0 and `c·x` as `x` for `c = 1`.
    Sum {
        /// The constant term.
        c0: f64,
        /// `(operand, coefficient)` pairs.
        terms: Vec<(Operand, f64)>,
    },
    /// `coef · Π num / Π den`; with [`Rounding::Exact`], `((coef·n₁)·n₂)·…` (or `1/d` alone).
    Prod {
        /// The coefficient.
        coef: f64,
        /// Factors of the numerator.
        num: Vec<Operand>,
        /// Factors of the denominator.
        den: Vec<Operand>,
    },
    /// `f(x)` for a call of one argument.
    Call1(Call, Operand),
    /// `f(x, y)` for a call of two arguments.
    Call2(Call, Operand, Operand),
    /// `(sin x, cos x)`: defines two temporaries.
    SinCos(Operand),
}

impl Rhs {
    /// Operands read.
    pub fn operands(&self) -> Vec<Operand> {
        match self {
            Rhs::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
            Rhs::Prod { num, den, .. } => num.iter().chain(den).copied().collect(),
            Rhs::Call1(_, x) | Rhs::SinCos(x) => vec![*x],
            Rhs::Call2(_, x, y) => vec![*x, *y],
        }
    }
    /// Number of temporaries defined.
    pub fn defs(&self) -> u32 {
        if matches!(self, Rhs::SinCos(_)) { 2 } else { 1 }
    }
    /// The operands read, mutably (for renaming).
    pub(crate) fn for_each_operand(&mut self, mut f: impl FnMut(&mut Operand)) {
        match self {
            Rhs::Sum { terms, .. } => terms.iter_mut().for_each(|t| f(&mut t.0)),
            Rhs::Prod { num, den, .. } => num.iter_mut().chain(den.iter_mut()).for_each(f),
            Rhs::Call1(_, x) | Rhs::SinCos(x) => f(x),
            Rhs::Call2(_, x, y) => {
                f(x);
                f(y);
            }
        }
    }
}

/// One instruction: `let t{def}[, t{def+1}] = rhs`.
#[derive(Clone, Debug, PartialEq)]
pub struct Inst {
    /// The (first) temporary defined.
    pub def: u32,
    /// What it computes.
    pub rhs: Rhs,
}

/// Counts of floating-point operations of straight-line code.
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
    /// Adds the operations of one instruction.
    pub fn count(&mut self, rhs: &Rhs) {
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
            Rhs::Call1(Call::Sqrt, _) => self.sqrt += 1,
            Rhs::Call1(Call::Func(Func::Abs), _) => self.neg += 1,
            Rhs::Call1(..) | Rhs::Call2(..) | Rhs::SinCos(_) => self.func += 1,
        }
    }
}

/// The lowered form of a set of roots.
#[derive(Clone, Debug)]
pub struct Lowered {
    /// The instructions; each reads parameters, literals and earlier temporaries only.
    pub insts: Vec<Inst>,
    /// Number of temporaries defined.
    pub n_temps: u32,
    /// The value of each root: an operand, negated if the flag is set (other scales are
    /// computed by an instruction).
    pub roots: Vec<(Operand, bool)>,
}

/// Which rewrites the lowering may make (see the [module](self) documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Rounding {
    /// The evaluation order of [`eval_generic`](crate::eval_generic), bit for bit.
    #[default]
    Exact,
    /// Fewer operations, in another order.
    Free,
}

/// Lower `roots` to straight-line code over `params` (parameter expressions; operand
/// [`Operand::Param`]`(k)` is `params[k]`). A root that depends on a parameter not in
/// `params` is an error naming it, and so is an invalid root. `pivots` are values that
/// validity checks keep away from zero: with [`Rounding::Free`], a base that is one of them
/// (or a factor of one) cancels against itself (`x²·x⁻² → 1`), which is exact wherever the
/// checks pass.
pub fn lower(
    roots: &[Expr],
    params: &[Expr],
    pivots: &[Expr],
    rounding: Rounding,
) -> Result<Lowered, SymError> {
    let mut position: HashMap<u32, u32> = HashMap::with_capacity(params.len());
    for (k, p) in params.iter().enumerate() {
        let i = p.param_index().ok_or_else(|| {
            SymError::Dimension(format!("parameter {k} (`{p}`) is not a parameter"))
        })?;
        position.insert(i, k as u32);
    }
    for r in roots {
        r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
    }
    let dag = dag::build(roots, &position, rounding == Rounding::Free)?;
    // Pivots of another pool are none of these nodes.
    let pivot_ids: Vec<Id> = pivots
        .iter()
        .filter(|p| p.pool_serial() == dag.serial)
        .map(|p| p.id())
        .collect();
    let sincos = dag.sincos_args();
    let mut l = match rounding {
        Rounding::Exact => run(&dag, sincos, Analysis::default(), true)?,
        Rounding::Free => {
            // Pass 1 learns the classes, the shared denominators and the pivots; pass 2
            // lowers with what it found.
            let first = run(&dag, sincos.clone(), Analysis::default(), false)?;
            let analysis = first.analysis(&pivot_ids);
            run(&dag, sincos, analysis, false)?
        }
    };
    let mut out = Vec::with_capacity(roots.len());
    for r in &dag.roots {
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
    if rounding == Rounding::Free {
        pairs::common_pairs(&mut lowered);
    }
    pairs::renumber(&mut lowered);
    Ok(lowered)
}

/// A lowered value: `scale · op`. With [`Rounding::Free`], scales are folded into the
/// coefficients of the sums and products that use the value, so `k/m`, `−k/m` and `2k/m`
/// share one computation and a negation costs nothing unless it reaches an output or a
/// function argument. With [`Rounding::Exact`] the scale is always 1.
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
/// (its class: nodes that lower to the same value up to a scale).
#[derive(Default)]
struct Analysis {
    class: HashMap<Id, OpKey>,
    shared_denominators: HashSet<(OpKey, bool)>,
    nonzero: HashSet<OpKey>,
}

/// The state of one pass of the lowering.
struct Lowerer<'a> {
    dag: &'a Dag,
    exact: bool,
    insts: Vec<Inst>,
    n_temps: u32,
    memo: HashMap<Id, Val>,
    /// Instructions already emitted, for common subexpressions.
    cse: HashMap<CseKey, Operand>,
    pow_memo: HashMap<(OpKey, i64), Operand>,
    mono_memo: HashMap<Vec<(OpKey, Rational)>, Operand>,
    sum_memo: HashMap<(u64, Vec<(OpKey, u64)>), Operand>,
    /// Products of [`Rounding::Exact`] by coefficient and factors.
    prod_memo: HashMap<(u64, Vec<OpKey>), Operand>,
    /// The terms of every sum temporary (`c0`, terms as in its instruction), for
    /// [`Lowerer::expand_cancelling_sums`].
    sum_terms: HashMap<u32, (f64, Vec<(Operand, f64)>)>,
    sincos_memo: HashMap<OpKey, (Operand, Operand)>,
    /// Arguments of both a `sin` and a `cos`.
    sincos_args: HashSet<Id>,
    /// From the first pass (empty during it).
    analysis: Analysis,
    /// Recorded during the first pass: uses of each denominator atom by distinct monomials,
    /// and the factors of each monomial.
    den_count: HashMap<(OpKey, bool), usize>,
    mono_factors: HashMap<OpKey, Vec<(OpKey, Rational)>>,
}

/// The identity of an instruction of one or two operands, for common subexpressions.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum CseKey {
    Call(Call, OpKey, OpKey),
    Scaled(OpKey, u64),
    Recip(OpKey),
    Mul(OpKey, OpKey),
}

fn run(
    dag: &Dag,
    sincos_args: HashSet<Id>,
    analysis: Analysis,
    exact: bool,
) -> Result<Lowerer<'_>, SymError> {
    let mut l = Lowerer {
        dag,
        exact,
        insts: Vec::new(),
        n_temps: 0,
        memo: HashMap::with_capacity(dag.order.len()),
        cse: HashMap::new(),
        pow_memo: HashMap::new(),
        mono_memo: HashMap::new(),
        sum_memo: HashMap::new(),
        prod_memo: HashMap::new(),
        sum_terms: HashMap::new(),
        sincos_memo: HashMap::new(),
        sincos_args,
        analysis,
        den_count: HashMap::new(),
        mono_factors: HashMap::new(),
    };
    for &id in &dag.order {
        let v = l.node(id)?;
        l.memo.insert(id, v);
    }
    Ok(l)
}

impl Lowerer<'_> {
    /// What the first pass tells the second (`pivots`: the nodes the checks keep nonzero).
    fn analysis(&self, pivots: &[Id]) -> Analysis {
        let mut analysis = Analysis::default();
        for (e, v) in &self.memo {
            if !matches!(v.op, Operand::Lit(_)) {
                analysis.class.insert(*e, v.op.key());
            }
        }
        analysis.shared_denominators = self
            .den_count
            .iter()
            .filter(|(_, n)| **n >= 2)
            .map(|(k, _)| *k)
            .collect();
        for p in pivots {
            let Some(v) = self.memo.get(p) else { continue };
            if matches!(v.op, Operand::Lit(_)) {
                continue;
            }
            analysis.nonzero.insert(v.op.key());
            // A finite nonzero product has nonzero factors (those with positive exponents).
            if let Some(f) = self.mono_factors.get(&v.op.key()) {
                for (k, r) in f {
                    if !r.is_negative() {
                        analysis.nonzero.insert(*k);
                    }
                }
            }
        }
        analysis
    }

    fn push(&mut self, rhs: Rhs) -> Operand {
        if let Some(x) = fold(&rhs) {
            return Operand::Lit(x);
        }
        let def = self.n_temps;
        self.n_temps += rhs.defs();
        self.insts.push(Inst { def, rhs });
        Operand::Temp(def)
    }

    /// `rhs`, or the temporary of the identical instruction emitted before.
    fn push_once(&mut self, key: CseKey, rhs: impl FnOnce() -> Rhs) -> Operand {
        if let Some(o) = self.cse.get(&key) {
            return *o;
        }
        let o = self.push(rhs());
        self.cse.insert(key, o);
        o
    }

    /// `scale · op` as one operand.
    fn materialize(&mut self, v: Val) -> Operand {
        if v.scale == 1.0 {
            return v.op;
        }
        if let Operand::Lit(x) = v.op {
            return Operand::Lit(x * v.scale);
        }
        self.push_once(CseKey::Scaled(v.op.key(), v.scale.to_bits()), || {
            Rhs::Prod {
                coef: v.scale,
                num: vec![v.op],
                den: vec![],
            }
        })
    }

    fn call1(&mut self, f: Call, x: Operand) -> Operand {
        self.push_once(CseKey::Call(f, x.key(), x.key()), || Rhs::Call1(f, x))
    }

    fn call2(&mut self, f: Call, x: Operand, y: Operand) -> Operand {
        self.push_once(CseKey::Call(f, x.key(), y.key()), || Rhs::Call2(f, x, y))
    }

    fn sqrt(&mut self, x: Operand) -> Operand {
        self.call1(Call::Sqrt, x)
    }

    fn recip(&mut self, x: Operand) -> Operand {
        self.push_once(CseKey::Recip(x.key()), || Rhs::Prod {
            coef: 1.0,
            num: vec![],
            den: vec![x],
        })
    }

    /// `x·y`, computed once.
    fn mul(&mut self, x: Operand, y: Operand) -> Operand {
        self.push_once(CseKey::Mul(x.key(), y.key()), || Rhs::Prod {
            coef: 1.0,
            num: vec![x, y],
            den: vec![],
        })
    }

    fn powf(&mut self, x: Operand, e: f64) -> Operand {
        self.call2(Call::Pow, x, Operand::Lit(e))
    }

    /// The value of a number node.
    fn number(shape: &ShapeBuf) -> f64 {
        shape
            .eval::<f64>(|_| unreachable!("a leaf"), |_| unreachable!("a leaf"))
            .expect("a number")
    }

    fn node(&mut self, id: Id) -> Result<Val, SymError> {
        let dag = self.dag;
        let shape = &dag.shapes[&id];
        Ok(match shape {
            Shape::Num(_) | Shape::Float(_) | Shape::Const(_) => {
                Val::of(Operand::Lit(Self::number(shape)))
            }
            Shape::Param(i) => Val::of(Operand::Param(dag.position(*i)?)),
            Shape::Add(a) => {
                let c0 = self.memo[&a[0]];
                let c0 = c0.op_lit() * c0.scale;
                let terms: Vec<(Id, f64)> = a[1..]
                    .chunks_exact(2)
                    .map(|t| {
                        let c = self.memo[&t[1]];
                        (t[0], c.op_lit() * c.scale)
                    })
                    .collect();
                if self.exact {
                    self.exact_sum(c0, &terms)
                } else {
                    self.sum(c0, &terms)
                }
            }
            Shape::Mul(a) => {
                let c = self.memo[&a[0]];
                let coef = c.op_lit() * c.scale;
                let factors: Vec<(Id, Rational)> = a[1..]
                    .chunks_exact(2)
                    .map(|t| (t[0], dag.exponent(t[1])))
                    .collect();
                if self.exact {
                    self.exact_product(coef, &factors)
                } else {
                    self.product(coef, &factors)
                }
            }
            Shape::Pow([a, b]) => {
                let (a, b) = (self.memo[a], self.memo[b]);
                let (a, b) = (self.materialize(a), self.materialize(b));
                Val::of(self.call2(Call::Pow, a, b))
            }
            Shape::Atan2([y, x]) => {
                let (y, x) = (self.memo[y], self.memo[x]);
                let (y, x) = (self.materialize(y), self.materialize(x));
                Val::of(self.call2(Call::Atan2, y, x))
            }
            Shape::Func(f, [a]) => self.func(*f, *a),
            Shape::Invalid(_) => unreachable!("invalid roots are refused"),
        })
    }

    /// `f(a)`: odd and even functions absorb a sign, `abs` any scale; `sin` and `cos` of one
    /// argument come from one `sincos`.
    fn func(&mut self, f: Func, a: Id) -> Val {
        let v = self.memo[&a];
        let (x, outer) = match (f, f.parity(), v.scale) {
            (Func::Abs, _, s) => (v.op, s.abs()),
            (_, Parity::Odd, -1.0) => (v.op, -1.0),
            (_, Parity::Even, -1.0) => (v.op, 1.0),
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
            _ => self.call1(Call::Func(f), x),
        };
        Val { op, scale: outer }
    }
}

impl Val {
    /// The literal of a number node's value.
    fn op_lit(self) -> f64 {
        match self.op {
            Operand::Lit(x) => x,
            _ => unreachable!("coefficients are numbers"),
        }
    }
}

/// The value of an instruction whose operands are all literals (computed in `f64` the way
/// the instruction would compute it), if it defines a single value.
fn fold(rhs: &Rhs) -> Option<f64> {
    let lit = |o: &Operand| match o {
        Operand::Lit(v) => Some(*v),
        _ => None,
    };
    match rhs {
        Rhs::Sum { c0, terms } => {
            let mut acc = (*c0 != 0.0).then_some(*c0);
            for (x, c) in terms {
                let t = if *c == 1.0 { lit(x)? } else { c * lit(x)? };
                acc = Some(acc.map_or(t, |a| a + t));
            }
            Some(acc.unwrap_or(0.0))
        }
        Rhs::Prod { coef, num, den } => {
            let mut n: Option<f64> = (*coef != 1.0).then_some(*coef);
            for x in num {
                let x = lit(x)?;
                n = Some(n.map_or(x, |a| a * x));
            }
            if den.is_empty() {
                return Some(n.unwrap_or(1.0));
            }
            let mut d: Option<f64> = None;
            for x in den {
                let x = lit(x)?;
                d = Some(d.map_or(x, |a| a * x));
            }
            let d = d.expect("a denominator");
            Some(match n {
                Some(n) => n / d,
                None => 1.0 / d,
            })
        }
        Rhs::Call1(f, x) => Some(f.eval_f64(lit(x)?, 0.0)),
        Rhs::Call2(f, x, y) => Some(f.eval_f64(lit(x)?, lit(y)?)),
        Rhs::SinCos(_) => None,
    }
}
