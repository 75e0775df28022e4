//! Evaluation: a compiled [`Tape`] for fast repeated `f64` evaluation, and
//! [`eval_generic`] for evaluation in any [`Elementary`] scalar (double-double references,
//! substitution of expressions).
//!
//! A tape is the DAG of a set of roots flattened into instructions in topological order (node
//! ids already are one): instruction `i` writes slot `i` of a work buffer. Sums and products
//! are single n-ary instructions over side tables of `(slot, coefficient)` and
//! `(slot, power)` entries, so the instruction count equals the number of unique nodes.
//! Evaluation allocates nothing; the work buffer is the caller's ([`Tape::eval_into`]) or
//! kept in a [`TapeWorkspace`].

use crate::error::SymError;
use crate::expr::{Expr, reachable};
use crate::pool::{Constant, Func, Id, Node, with_pool};
use crate::rational::Rational;
use crate::scalar::Elementary;
use hashbrown::HashMap;

/// One factor of a product instruction: the slot it reads and how: `x`, `1/x` or a power
/// from the tape's power table.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Factor {
    slot: u32,
    kind: u32,
}

impl Factor {
    const ONE: u32 = 0;
    const RECIP: u32 = 1;
    const FIRST_POWER: u32 = 2;
}

/// A power applied to one factor of a product.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Pw {
    One,
    Two,
    Three,
    Recip,
    Recip2,
    Sqrt,
    RecipSqrt,
    Int(i32),
    Real(f64),
}

impl Pw {
    fn of(e: &Rational) -> Pw {
        match e.as_small() {
            Some((1, 1)) => Pw::One,
            Some((2, 1)) => Pw::Two,
            Some((3, 1)) => Pw::Three,
            Some((-1, 1)) => Pw::Recip,
            Some((-2, 1)) => Pw::Recip2,
            Some((1, 2)) => Pw::Sqrt,
            Some((-1, 2)) => Pw::RecipSqrt,
            Some((n, 1)) if n.unsigned_abs() < i32::MAX as u64 => Pw::Int(n as i32),
            _ => Pw::Real(e.to_f64()),
        }
    }
    #[inline(always)]
    fn apply(self, x: f64) -> f64 {
        match self {
            Pw::One => x,
            Pw::Two => x * x,
            Pw::Three => x * x * x,
            Pw::Recip => 1.0 / x,
            Pw::Recip2 => 1.0 / (x * x),
            Pw::Sqrt => x.sqrt(),
            Pw::RecipSqrt => 1.0 / x.sqrt(),
            Pw::Int(n) => x.powi(n),
            Pw::Real(e) => x.powf(e),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Op {
    Const(f64),
    Param(u32),
    Lin {
        c0: f64,
        start: u32,
        len: u32,
    },
    /// `coef · Π` factors in node order; see [`Factor`].
    Prod {
        coef: f64,
        start: u32,
        len: u32,
    },
    Pow(u32, u32),
    Func(Func, u32),
    Atan2(u32, u32),
}

/// A compiled evaluation program for a set of root expressions.
#[derive(Clone, Debug)]
pub struct Tape {
    params: Vec<u32>,
    param_names: Vec<String>,
    ops: Vec<Op>,
    terms: Vec<(u32, f64)>,
    factors: Vec<Factor>,
    /// Powers other than 1 and −1, referenced by [`Factor::kind`].
    powers: Vec<Pw>,
    outputs: Vec<u32>,
}

/// Reusable work buffer for [`Tape::eval`].
#[derive(Clone, Debug, Default)]
pub struct TapeWorkspace {
    work: Vec<f64>,
    /// Structure-of-arrays buffers of [`Tape::eval_batch`]: one slot per instruction (and one
    /// per parameter) holding `LANES` points.
    lanes: Vec<[f64; LANES]>,
    lane_values: Vec<[f64; LANES]>,
}

/// Points evaluated together by [`Tape::eval_batch`]. Interpreting a tape costs mostly the
/// decoding of each instruction (mispredicted branches), not the arithmetic; decoding once per
/// chunk of points and applying the instruction to all of them in a tight loop divides that
/// cost by the chunk size.
const LANES: usize = 16;

impl Pw {
    /// `acc[l] *= self.apply(x[l])` for every lane (the same operations as the scalar path).
    #[inline(always)]
    fn apply_lanes(self, acc: &mut [f64; LANES], x: &[f64; LANES]) {
        match self {
            Pw::One => (0..LANES).for_each(|l| acc[l] *= x[l]),
            Pw::Two => (0..LANES).for_each(|l| acc[l] *= x[l] * x[l]),
            Pw::Three => (0..LANES).for_each(|l| acc[l] *= x[l] * x[l] * x[l]),
            Pw::Recip => (0..LANES).for_each(|l| acc[l] *= 1.0 / x[l]),
            Pw::Recip2 => (0..LANES).for_each(|l| acc[l] *= 1.0 / (x[l] * x[l])),
            Pw::Sqrt => (0..LANES).for_each(|l| acc[l] *= x[l].sqrt()),
            Pw::RecipSqrt => (0..LANES).for_each(|l| acc[l] *= 1.0 / x[l].sqrt()),
            Pw::Int(n) => (0..LANES).for_each(|l| acc[l] *= x[l].powi(n)),
            Pw::Real(e) => (0..LANES).for_each(|l| acc[l] *= x[l].powf(e)),
        }
    }
}

#[inline(always)]
fn lanes1(x: &[f64; LANES], f: impl Fn(f64) -> f64) -> [f64; LANES] {
    std::array::from_fn(|l| f(x[l]))
}

#[inline(always)]
fn lanes2(x: &[f64; LANES], y: &[f64; LANES], f: impl Fn(f64, f64) -> f64) -> [f64; LANES] {
    std::array::from_fn(|l| f(x[l], y[l]))
}

impl Tape {
    /// Compile `roots` for evaluation with parameter values supplied in the order of `params`
    /// (which must be parameter expressions). A root that depends on a parameter not in
    /// `params` is an error naming it; so is an invalid root.
    pub fn new(roots: &[Expr], params: &[Expr]) -> Result<Tape, SymError> {
        let mut param_slot: HashMap<u32, u32> = HashMap::new();
        let mut param_index = Vec::with_capacity(params.len());
        let mut param_names = Vec::with_capacity(params.len());
        for (k, p) in params.iter().enumerate() {
            let info = p.param_info().ok_or_else(|| {
                SymError::Dimension(format!("tape parameter {k} (`{p}`) is not a parameter"))
            })?;
            let idx = p.param_index().expect("parameter");
            param_slot.insert(idx, k as u32);
            param_index.push(idx);
            param_names.push(info.name);
        }
        for r in roots {
            r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
        }
        let ids = reachable(roots);
        with_pool(|p| {
            let mut slot: HashMap<Id, u32> = HashMap::with_capacity(ids.len());
            let mut tape = Tape {
                params: param_index,
                param_names,
                ops: Vec::with_capacity(ids.len()),
                terms: Vec::new(),
                factors: Vec::new(),
                powers: Vec::new(),
                outputs: Vec::with_capacity(roots.len()),
            };
            for &id in &ids {
                let op = match p.node(id) {
                    Node::Num(r) => Op::Const(r.to_f64()),
                    Node::Float(f) => Op::Const(*f),
                    Node::Const(c) => Op::Const(c.to_f64()),
                    Node::Param(i) => match param_slot.get(i) {
                        Some(&k) => Op::Param(k),
                        None => {
                            return Err(SymError::MissingParameter {
                                name: p.param(*i).name.clone(),
                            });
                        }
                    },
                    Node::Add(..) => {
                        let (c0, pairs) = p.add_parts(id).expect("sum");
                        let start = tape.terms.len() as u32;
                        for t in pairs.chunks_exact(2) {
                            let c = p.number(t[1]).expect("coefficient").to_f64();
                            tape.terms.push((slot[&t[0]], c));
                        }
                        Op::Lin {
                            c0: p.nominal(c0),
                            start,
                            len: (pairs.len() / 2) as u32,
                        }
                    }
                    Node::Mul(..) => {
                        let (c, pairs) = p.mul_parts(id).expect("product");
                        let start = tape.factors.len() as u32;
                        for t in pairs.chunks_exact(2) {
                            let e = p.rational_of(t[1]).expect("exponent");
                            let kind = match Pw::of(e) {
                                Pw::One => Factor::ONE,
                                Pw::Recip => Factor::RECIP,
                                pw => {
                                    tape.powers.push(pw);
                                    Factor::FIRST_POWER + tape.powers.len() as u32 - 1
                                }
                            };
                            tape.factors.push(Factor {
                                slot: slot[&t[0]],
                                kind,
                            });
                        }
                        Op::Prod {
                            coef: p.nominal(c),
                            start,
                            len: (pairs.len() / 2) as u32,
                        }
                    }
                    Node::Pow(a, b) => Op::Pow(slot[a], slot[b]),
                    Node::Func(f, a) => Op::Func(*f, slot[a]),
                    Node::Atan2(a, b) => Op::Atan2(slot[a], slot[b]),
                    Node::Invalid(e) => {
                        return Err(SymError::Invalid(Box::new(p.error(*e).clone())));
                    }
                };
                slot.insert(id, tape.ops.len() as u32);
                tape.ops.push(op);
            }
            for r in roots {
                tape.outputs.push(slot[&r.id()]);
            }
            Ok(tape)
        })
    }

    /// Number of parameters expected.
    pub fn n_params(&self) -> usize {
        self.params.len()
    }
    /// Names of the parameters, in the order values are expected.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }
    /// Number of outputs (roots).
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// Number of instructions (= unique nodes).
    pub fn len(&self) -> usize {
        self.ops.len()
    }
    /// Is the tape empty (no roots)?
    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }
    /// Length of the work buffer [`Tape::eval_into`] needs.
    pub fn work_len(&self) -> usize {
        self.ops.len()
    }

    /// The kernel: evaluate with a caller-provided work buffer, no allocation, no checks on the
    /// result. `values.len() == n_params()`, `out.len() == n_outputs()`,
    /// `work.len() >= work_len()`; otherwise an error.
    pub fn eval_into(
        &self,
        values: &[f64],
        out: &mut [f64],
        work: &mut [f64],
    ) -> Result<(), SymError> {
        if values.len() != self.params.len() {
            return Err(SymError::Dimension(format!(
                "{} parameter values given, the tape expects {} ({})",
                values.len(),
                self.params.len(),
                self.param_names.join(", ")
            )));
        }
        if out.len() != self.outputs.len() || work.len() < self.ops.len() {
            return Err(SymError::Dimension(format!(
                "output buffer {} (expected {}), work buffer {} (expected ≥ {})",
                out.len(),
                self.outputs.len(),
                work.len(),
                self.ops.len()
            )));
        }
        self.run(values, work);
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = work[s as usize];
        }
        Ok(())
    }

    #[inline]
    fn run(&self, values: &[f64], w: &mut [f64]) {
        for (i, op) in self.ops.iter().enumerate() {
            let v = match *op {
                Op::Const(c) => c,
                Op::Param(k) => values[k as usize],
                Op::Lin { c0, start, len } => {
                    let mut acc = c0;
                    for &(s, c) in &self.terms[start as usize..(start + len) as usize] {
                        acc += c * w[s as usize];
                    }
                    acc
                }
                Op::Prod { coef, start, len } => {
                    let mut acc = coef;
                    for f in &self.factors[start as usize..(start + len) as usize] {
                        let x = w[f.slot as usize];
                        // Conditional branches, not a jump table: almost every factor is a
                        // plain one, so they predict well.
                        if f.kind == Factor::ONE {
                            acc *= x;
                        } else if f.kind == Factor::RECIP {
                            // `acc * (1/x)`, not `acc / x`: the rounding of the recursive
                            // evaluator and of generated code.
                            acc *= 1.0 / x;
                        } else {
                            acc *= self.powers[(f.kind - Factor::FIRST_POWER) as usize].apply(x);
                        }
                    }
                    acc
                }
                Op::Pow(a, b) => w[a as usize].powf(w[b as usize]),
                Op::Func(f, a) => f.eval_f64(w[a as usize]),
                Op::Atan2(a, b) => w[a as usize].atan2(w[b as usize]),
            };
            w[i] = v;
        }
    }

    /// [`Tape::run`] for `LANES` points at once (`vals[k]` holds parameter `k` of each point).
    fn run_lanes(&self, vals: &[[f64; LANES]], w: &mut [[f64; LANES]]) {
        for (i, op) in self.ops.iter().enumerate() {
            let v = match *op {
                Op::Const(c) => [c; LANES],
                Op::Param(k) => vals[k as usize],
                Op::Lin { c0, start, len } => {
                    let mut acc = [c0; LANES];
                    for &(s, c) in &self.terms[start as usize..(start + len) as usize] {
                        let x = &w[s as usize];
                        (0..LANES).for_each(|l| acc[l] += c * x[l]);
                    }
                    acc
                }
                Op::Prod { coef, start, len } => {
                    // The same operations in the same order as the scalar path.
                    let mut acc = [coef; LANES];
                    for f in &self.factors[start as usize..(start + len) as usize] {
                        let x = &w[f.slot as usize];
                        if f.kind == Factor::ONE {
                            (0..LANES).for_each(|l| acc[l] *= x[l]);
                        } else if f.kind == Factor::RECIP {
                            (0..LANES).for_each(|l| acc[l] *= 1.0 / x[l]);
                        } else {
                            self.powers[(f.kind - Factor::FIRST_POWER) as usize]
                                .apply_lanes(&mut acc, x);
                        }
                    }
                    acc
                }
                Op::Pow(a, b) => lanes2(&w[a as usize], &w[b as usize], f64::powf),
                Op::Func(f, a) => {
                    let x = &w[a as usize];
                    match f {
                        Func::Sin => lanes1(x, f64::sin),
                        Func::Cos => lanes1(x, f64::cos),
                        Func::Tan => lanes1(x, f64::tan),
                        Func::Exp => lanes1(x, f64::exp),
                        Func::Ln => lanes1(x, f64::ln),
                        Func::Abs => lanes1(x, f64::abs),
                    }
                }
                Op::Atan2(a, b) => lanes2(&w[a as usize], &w[b as usize], f64::atan2),
            };
            w[i] = v;
        }
    }

    /// Evaluate, checking that every output is finite (an error names the first output that is
    /// not). The workspace grows on first use and is reused afterwards.
    pub fn eval(
        &self,
        values: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        if ws.work.len() < self.ops.len() {
            ws.work.resize(self.ops.len(), 0.0);
        }
        self.eval_into(values, out, &mut ws.work)?;
        if let Some((k, &v)) = out.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(SymError::EvalNonFinite {
                what: format!("output {k}"),
                value: v,
            });
        }
        Ok(())
    }

    /// Evaluate into a new vector (allocates; convenient for one-off use).
    pub fn eval_vec(&self, values: &[f64]) -> Result<Vec<f64>, SymError> {
        let mut out = vec![0.0; self.outputs.len()];
        self.eval(values, &mut out, &mut TapeWorkspace::default())?;
        Ok(out)
    }

    /// Evaluate at many points: `points` holds `n_params()` values per point (row-major),
    /// `out` receives `n_outputs()` values per point. Non-finite outputs are an error naming
    /// the point and the output (the first in point order). Points are evaluated in chunks of
    /// 16, each instruction applied to the whole chunk; the results are identical to
    /// [`Tape::eval_into`] point by point, at a fraction of the cost per point.
    pub fn eval_batch(
        &self,
        points: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        let np = self.params.len().max(1);
        let no = self.outputs.len();
        let count = if self.params.is_empty() {
            out.len() / no.max(1)
        } else {
            points.len() / np
        };
        if (!self.params.is_empty() && points.len() != count * np) || out.len() != count * no {
            return Err(SymError::Dimension(format!(
                "batch of {} values / {} outputs does not match {} parameters and {} outputs per point",
                points.len(),
                out.len(),
                self.params.len(),
                no
            )));
        }
        if ws.lanes.len() < self.ops.len() {
            ws.lanes.resize(self.ops.len(), [0.0; LANES]);
        }
        let n_params = self.params.len();
        ws.lane_values.resize(n_params, [0.0; LANES]);
        // Chunks of LANES points; a final remainder of fewer than LANES/4 points is cheaper
        // point by point than padded to a full chunk.
        let chunked = if count % LANES < LANES / 4 {
            count - count % LANES
        } else {
            count
        };
        for first in (0..chunked).step_by(LANES) {
            let n = LANES.min(count - first);
            // Transpose the chunk; a partial chunk repeats its last point in the unused lanes.
            for (p, lane) in ws.lane_values.iter_mut().enumerate() {
                for (l, slot) in lane.iter_mut().enumerate() {
                    *slot = points[(first + l.min(n - 1)) * np + p];
                }
            }
            self.run_lanes(&ws.lane_values, &mut ws.lanes);
            for l in 0..n {
                let k = first + l;
                for (j, &s) in self.outputs.iter().enumerate() {
                    let v = ws.lanes[s as usize][l];
                    if !v.is_finite() {
                        return Err(SymError::EvalNonFinite {
                            what: format!("output {j} at point {k}"),
                            value: v,
                        });
                    }
                    out[k * no + j] = v;
                }
            }
        }
        if chunked < count && ws.work.len() < self.ops.len() {
            ws.work.resize(self.ops.len(), 0.0);
        }
        for k in chunked..count {
            let vals = if self.params.is_empty() {
                &[][..]
            } else {
                &points[k * np..(k + 1) * np]
            };
            self.run(vals, &mut ws.work);
            for (j, &s) in self.outputs.iter().enumerate() {
                let v = ws.work[s as usize];
                if !v.is_finite() {
                    return Err(SymError::EvalNonFinite {
                        what: format!("output {j} at point {k}"),
                        value: v,
                    });
                }
                out[k * no + j] = v;
            }
        }
        Ok(())
    }
}

/// Evaluate `roots` in any [`Elementary`] scalar, with `value_of(param_index)` giving the value
/// of each parameter (pool index, see [`Expr::param_index`]); `None` is an error naming the
/// parameter. This is the "recursive" reference evaluation (each node once, memoised).
pub fn eval_generic<S: Elementary>(
    roots: &[Expr],
    value_of: impl Fn(u32) -> Option<S>,
) -> Result<Vec<S>, SymError> {
    for r in roots {
        r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
    }
    let ids = reachable(roots);
    // Gather node structure first (the pool must not be borrowed while scalar arithmetic runs,
    // since `S` may itself be `Expr`).
    enum G {
        Num(Rational),
        Float(f64),
        Const(Constant),
        Param(u32, String),
        Add(Rational, Vec<(usize, Option<Rational>, f64)>, Option<f64>),
        Mul(Option<Rational>, f64, Vec<(usize, Rational)>),
        Pow(usize, usize),
        Func(Func, usize),
        Atan2(usize, usize),
    }
    let nodes: Vec<G> = with_pool(|p| {
        let pos: HashMap<Id, usize> = ids.iter().enumerate().map(|(k, &i)| (i, k)).collect();
        ids.iter()
            .map(|&id| match p.node(id) {
                Node::Num(r) => G::Num(r.clone()),
                Node::Float(f) => G::Float(*f),
                Node::Const(c) => G::Const(*c),
                Node::Param(i) => G::Param(*i, p.param(*i).name.clone()),
                Node::Add(..) => {
                    let (c0, pairs) = p.add_parts(id).expect("sum");
                    let c0r = p.rational_of(c0).cloned();
                    let c0f = if c0r.is_none() {
                        Some(p.nominal(c0))
                    } else {
                        None
                    };
                    G::Add(
                        c0r.unwrap_or(Rational::ZERO),
                        pairs
                            .chunks_exact(2)
                            .map(|t| (pos[&t[0]], p.rational_of(t[1]).cloned(), p.nominal(t[1])))
                            .collect(),
                        c0f,
                    )
                }
                Node::Mul(..) => {
                    let (c, pairs) = p.mul_parts(id).expect("product");
                    G::Mul(
                        p.rational_of(c).cloned(),
                        p.nominal(c),
                        pairs
                            .chunks_exact(2)
                            .map(|t| (pos[&t[0]], p.rational_of(t[1]).expect("exp").clone()))
                            .collect(),
                    )
                }
                Node::Pow(a, b) => G::Pow(pos[a], pos[b]),
                Node::Func(f, a) => G::Func(*f, pos[a]),
                Node::Atan2(a, b) => G::Atan2(pos[a], pos[b]),
                Node::Invalid(_) => unreachable!("checked above"),
            })
            .collect()
    });
    let num = |r: &Rational| S::from_rational(r);
    let coef = |r: &Option<Rational>, f: f64| match r {
        Some(r) => S::from_rational(r),
        None => S::from_f64(f),
    };
    let mut val: Vec<S> = Vec::with_capacity(nodes.len());
    for g in &nodes {
        let v = match g {
            G::Num(r) => num(r),
            G::Float(f) => S::from_f64(*f),
            G::Const(Constant::Pi) => S::pi(),
            G::Const(Constant::E) => S::e(),
            G::Param(i, name) => {
                value_of(*i).ok_or_else(|| SymError::MissingParameter { name: name.clone() })?
            }
            G::Add(c0, terms, c0f) => {
                let mut items: Vec<S> = Vec::with_capacity(terms.len() + 1);
                match c0f {
                    Some(f) => items.push(S::from_f64(*f)),
                    None if !c0.is_zero() => items.push(num(c0)),
                    None => {}
                }
                for (k, cr, cf) in terms {
                    let c = coef(cr, *cf);
                    items.push(if c.is_one() { val[*k] } else { c * val[*k] });
                }
                S::sum(&items)
            }
            G::Mul(cr, cf, factors) => {
                let mut acc = coef(cr, *cf);
                for (k, e) in factors {
                    let b = val[*k];
                    let f = match e.as_small() {
                        Some((n, 1)) => b.powi(n),
                        Some((1, 2)) => b.sqrt(),
                        Some((-1, 2)) => b.sqrt().recip(),
                        _ => b.powf(num(e)),
                    };
                    acc = if acc.is_one() { f } else { acc * f };
                }
                acc
            }
            G::Pow(a, b) => val[*a].powf(val[*b]),
            G::Func(f, a) => {
                let x = val[*a];
                match f {
                    Func::Sin => x.sin(),
                    Func::Cos => x.cos(),
                    Func::Tan => x.tan(),
                    Func::Exp => x.exp(),
                    Func::Ln => x.ln(),
                    Func::Abs => x.abs(),
                }
            }
            G::Atan2(a, b) => val[*a].atan2(val[*b]),
        };
        val.push(v);
    }
    let pos: HashMap<Id, usize> = ids.iter().enumerate().map(|(k, &i)| (i, k)).collect();
    Ok(roots.iter().map(|r| val[pos[&r.id()]]).collect())
}

/// Evaluate `roots` at the nominal values of their parameters, in any [`Elementary`] scalar
/// (parameter nominal values are converted from `f64`).
pub fn eval_nominal<S: Elementary>(roots: &[Expr]) -> Result<Vec<S>, SymError> {
    eval_generic(roots, |i| {
        crate::pool::ExprPool::param_info(i).map(|p| S::from_f64(p.nominal))
    })
}
