//! Simplification: a bounded egg pass over a whole matrix ([`Simplifier`]) and a
//! rational-function normal form for small closed forms ([`normalize_rational`]).
//!
//! # The egg pass
//!
//! The pool's smart constructors already do what rewriting is bad at: associativity and
//! commutativity (n-ary sorted sums and products), like terms, numeric folding. The e-graph pass
//! adds what they cannot do locally — factoring, cancellation of provably nonzero factors,
//! trigonometric identities — and it does so over **all entries of a matrix at once**, so that
//! a factor found in one entry is shared with every other entry that contains it.
//!
//! 1. **Convert.** The DAG reachable from the roots becomes one multi-root e-graph (node by
//!    node in the pool's topological order, so shared nodes stay shared). The language
//!    mirrors the pool: n-ary `Add`/`Mul`, `Pow` with an exact rational exponent leaf, exact
//!    rational leaves, parameters/constants/floats as opaque leaves that keep their pool id.
//! 2. **Rewrite.** A targeted rule set (see [Rule set](self#rule-set) below) under egg's
//!    [`egg::BackoffScheduler`] and a bounded runner: node, iteration and
//!    time limits, plus a hook that stops when the extracted DAG cost has not improved for
//!    [`Simplifier::with_stall_iterations`] iterations. egg checks its limits only between
//!    rule applications, so the appliers themselves also stop adding nodes past the node
//!    limit: the overshoot is at most one proposal.
//! 3. **Extract**, DAG-aware and costed in the pool's own terms (`extract.rs`): classes are
//!    visited in a topological order, and each picks the node whose expression — built through
//!    the smart constructors from its children's choices — has the smallest tree cost when the
//!    pool nodes a reference DAG shares are free. The references tried are the input, no
//!    sharing at all, and then what the best result so far shares. (Costing on the e-graph
//!    instead misjudged the input by 25 % on random DAGs: the pool inlines powers, numeric
//!    coefficients and nested sums into each user, where an e-graph shares them.)
//! 4. **Measure.** Every candidate is already canonical (it was built through the smart
//!    constructors); measure the real shared op count of all roots ([`Expr::op_count`]) weighted by
//!    a [`CostModel`]. **The result is kept only if that cost drops**; otherwise the input
//!    roots are returned unchanged. Either way the [`SimplifyOutcome`] reports what happened.
//!
//! ## Rule set
//!
//! | rule | rewrite | condition |
//! |---|---|---|
//! | `factor` | `a·x + a·y + z → a·(x + y) + z`: the largest group of terms sharing a factor, with their whole common monomial and a common coefficient (up to sign) pulled out; the two most frequent factors are both tried, extraction picks | integer exponents of one sign (`x/a + y/a² → (x + y/a)/a` is fine: both sides are undefined at `a = 0`) |
//! | `cancel` | `x^a·x^b → x^(a+b)` inside a product, looking through nested products, e.g. `x·y·x⁻¹ → y` | `a`, `b` of the same sign, **or** `x` provably nonzero — the pool's own condition ([`Sign::is_nonzero`](crate::Sign::is_nonzero)) |
//! | `collect` | `c₁·m + c₂·m → (c₁+c₂)·m` | always |
//! | `pythagoras` | `c·r·sin²x + c·r·cos²x → c·r`, `k − k·sin²x → k·cos²x`, `k − k·cos²x → k·sin²x` | always |
//! | `angle-sum` | `c·r·(cos a·cos b ∓ sin a·sin b) → c·r·cos(a ± b)`, `c·r·(sin a·cos b ± cos a·sin b) → c·r·sin(a ± b)` | always |
//!
//! There is no distribution and there are no AC rules: AC is the pool's job, and
//! distribute-plus-factor is the pair that explodes e-graphs.
//!
//! ## Cost model
//!
//! [`CostModel`] weights the counts of [`Expr::op_count`] (each unique node once, as in
//! straight-line generated code). The default weights — add 1, mul 1, div 4, elementary
//! function or square root 8, general power 16 — are rough reciprocal-throughput ratios of
//! `f64` operations on current x86-64 and AArch64 cores; [`CostModel::OPS`] counts every
//! operation as one (`op_count().total()`).
//!
//! ## Semantics
//!
//! Every rewrite is an identity wherever the input is defined (real and finite), with the same
//! conditions as the pool's smart constructors: nothing divides by a quantity that may vanish
//! unless the input already did. In particular `x/x` cancels only for `x` provably nonzero.
//! (This is unlike [`normalize_rational`], which uses rational-function semantics.)
//!
//! Timings, e-graph sizes and costs on a 2 000-node random DAG, on `AᵀBA` (joint against entry
//! by entry) and on the rational normal form: `cargo bench -p eom-sym --bench simplify`.
//!
//! # Rational normal form
//!
//! See [`normalize_rational`] and [`RationalNormalizer`].

mod extract;
mod lang;
pub(crate) mod poly;
pub(crate) mod rational_fn;
mod rules;

pub use rational_fn::{
    Normalized, RationalForm, RationalNormalizer, WorkLimit, normalize_rational,
};

use crate::context::with_pool;
use crate::error::SymError;
use crate::expr::{Expr, ExprView, OpCount, reachable};
use crate::matrix::SparseMatrix;
use crate::pool::Node;
use egg::{BackoffScheduler, Id, Runner};
use extract::Index;
use hashbrown::HashSet;
use lang::{Graph, Math, Meta};
use std::time::{Duration, Instant};

/// Weights of the operation counts of [`Expr::op_count`]: the DAG cost the simplifier
/// minimises (see the module docs for the defaults).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CostModel {
    /// Addition or subtraction.
    pub add: u64,
    /// Multiplication.
    pub mul: u64,
    /// Division.
    pub div: u64,
    /// Elementary function (sin, cos, tan, exp, ln, abs, atan2) or square root.
    pub func: u64,
    /// General power.
    pub pow: u64,
}

impl CostModel {
    /// Every operation costs one: the cost is `op_count().total()`.
    pub const OPS: CostModel = CostModel {
        add: 1,
        mul: 1,
        div: 1,
        func: 1,
        pow: 1,
    };

    /// The weighted cost of an operation count.
    pub fn cost(&self, ops: &OpCount) -> u64 {
        self.add * ops.add as u64
            + self.mul * ops.mul as u64
            + self.div * ops.div as u64
            + self.func * ops.func as u64
            + self.pow * ops.pow as u64
    }

    /// The weighted shared cost of evaluating all `roots` (each unique node once).
    pub fn of(&self, roots: &[Expr]) -> u64 {
        self.cost(&Expr::op_count(roots))
    }
}

impl Default for CostModel {
    fn default() -> Self {
        CostModel {
            add: 1,
            mul: 1,
            div: 4,
            func: 8,
            pow: 16,
        }
    }
}

/// Why the rewriting stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// No rule could add anything new.
    Saturated,
    /// The iteration limit was reached.
    IterationLimit,
    /// The e-graph grew past the node limit.
    NodeLimit,
    /// The time limit was reached.
    TimeLimit,
    /// The extracted DAG cost did not improve for the configured number of iterations.
    CostStalled,
    /// There was nothing to rewrite (no roots, or no operations in them).
    NothingToDo,
}

/// What a [`Simplifier::run`] did.
#[derive(Clone, Debug)]
pub struct SimplifyOutcome {
    /// The roots to use: the simplified ones if `kept`, otherwise the input roots unchanged.
    pub roots: Vec<Expr>,
    /// Whether the rewritten roots were kept (their cost is strictly lower).
    pub kept: bool,
    /// Weighted DAG cost of the input roots.
    pub cost_before: u64,
    /// Weighted DAG cost of the best rewritten candidate (equal to `cost_before` when there was
    /// none). Larger than or equal to `cost_before` means the result was not kept.
    pub cost_after: u64,
    /// Operation counts of the input roots.
    pub ops_before: OpCount,
    /// Operation counts of the best candidate (of the input when there was none).
    pub ops_after: OpCount,
    /// E-nodes in the e-graph when the runner stopped.
    pub egraph_nodes: usize,
    /// E-classes in the e-graph when the runner stopped.
    pub egraph_classes: usize,
    /// Iterations the runner completed.
    pub iterations: usize,
    /// Why the runner stopped.
    pub stop: StopReason,
    /// Time spent in the runner (rewriting, including the stall hook).
    pub rewrite_time: Duration,
    /// Total wall time of the call (conversion, rewriting, extraction, rebuild, measurement).
    pub time: Duration,
}

/// A bounded egg simplification pass over a set of roots (typically all entries of a
/// matrix), in egg's builder style.
///
/// ```
/// use eom_sym::{Expr, simplify::Simplifier};
/// let a = Expr::param("a", 1.0).unwrap();
/// let b = Expr::param("b", 2.0).unwrap();
/// let c = Expr::param("c", 3.0).unwrap();
/// let x = Expr::param("x", 0.3).unwrap();
/// let roots = [a * b + a * c, (a * x.sin().powi(2) + a * x.cos().powi(2)) * b];
/// let out = Simplifier::default().run(&roots).unwrap();
/// assert!(out.kept && out.cost_after < out.cost_before);
/// assert_eq!(out.roots[1], a * b);
/// ```
#[derive(Clone, Debug)]
pub struct Simplifier {
    node_limit: usize,
    iter_limit: usize,
    time_limit: Duration,
    stall_iterations: usize,
    cost: CostModel,
    trig: bool,
}

impl Default for Simplifier {
    /// 20 000 e-nodes, 20 iterations, 500 ms, stop after 4 iterations without improvement,
    /// default cost weights, all rules.
    fn default() -> Self {
        Simplifier {
            node_limit: 20_000,
            iter_limit: 20,
            time_limit: Duration::from_millis(500),
            stall_iterations: 4,
            cost: CostModel::default(),
            trig: true,
        }
    }
}

impl Simplifier {
    /// Stop once the e-graph holds more e-nodes than this.
    pub fn with_node_limit(mut self, n: usize) -> Self {
        self.node_limit = n;
        self
    }
    /// Stop after this many iterations.
    pub fn with_iter_limit(mut self, n: usize) -> Self {
        self.iter_limit = n;
        self
    }
    /// Stop rewriting after this much time (checked between rule applications; extraction
    /// and rebuild come on top, see [`SimplifyOutcome::time`]).
    pub fn with_time_limit(mut self, t: Duration) -> Self {
        self.time_limit = t;
        self
    }
    /// Stop when the extracted DAG cost has not improved for `k` iterations (0 disables the
    /// check). Values below 3 stop too early on textbook cases (factor, then cancel, then
    /// collect takes several iterations to pay off).
    pub fn with_stall_iterations(mut self, k: usize) -> Self {
        self.stall_iterations = k;
        self
    }
    /// The weights of the DAG cost.
    pub fn with_cost_model(mut self, c: CostModel) -> Self {
        self.cost = c;
        self
    }
    /// Enable or disable the trigonometric rules (`pythagoras`, `angle-sum`).
    pub fn with_trig_rules(mut self, on: bool) -> Self {
        self.trig = on;
        self
    }

    /// Simplify all entries of a matrix together (shared subterms are found across entries).
    /// Entries that become structural zeros are dropped from the sparsity pattern.
    pub fn run_matrix(
        &self,
        m: &SparseMatrix<Expr>,
    ) -> Result<(SparseMatrix<Expr>, SimplifyOutcome), SymError> {
        let entries: Vec<(usize, usize, Expr)> = m.iter().collect();
        let roots: Vec<Expr> = entries.iter().map(|e| e.2).collect();
        let out = self.run(&roots)?;
        let mut r = SparseMatrix::zeros(m.nrows(), m.ncols());
        for ((i, j, _), v) in entries.iter().zip(&out.roots) {
            r.set(*i, *j, *v);
        }
        Ok((r, out))
    }

    /// Simplify `roots` together. Invalid roots (operations without a value) are an error;
    /// nothing else is: limits end the rewriting and the best result found so far is used.
    pub fn run(&self, roots: &[Expr]) -> Result<SimplifyOutcome, SymError> {
        // Everything below reads and builds nodes of the roots' pool, entered as the current
        // one (the e-graph's atoms are node ids of that pool).
        let (serial, ids) = crate::context::unify(roots);
        let roots: Vec<Expr> = ids.iter().map(|&i| Expr::new(i, serial)).collect();
        match crate::ExprPool::find(serial) {
            Some(pool) => pool.enter(|| self.run_in_pool(&roots)),
            None => self.run_in_pool(&roots),
        }
    }

    fn run_in_pool(&self, roots: &[Expr]) -> Result<SimplifyOutcome, SymError> {
        let start = Instant::now();
        for r in roots {
            r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
        }
        let ops_before = Expr::op_count(roots);
        let cost_before = self.cost.cost(&ops_before);
        let unchanged = |stop, iterations, nodes, classes, rewrite_time| SimplifyOutcome {
            roots: roots.to_vec(),
            kept: false,
            cost_before,
            cost_after: cost_before,
            ops_before,
            ops_after: ops_before,
            egraph_nodes: nodes,
            egraph_classes: classes,
            iterations,
            stop,
            rewrite_time,
            time: start.elapsed(),
        };
        if roots.is_empty() || cost_before == 0 {
            return Ok(unchanged(StopReason::NothingToDo, 0, 0, 0, Duration::ZERO));
        }

        // 1. Convert.
        let (egraph, root_ids, n_input, originals) = to_egraph(roots);
        let input_anchors = extract::shared_nodes(roots);

        // 2. Rewrite.
        let rules = rules::rules(self.node_limit, self.trig);
        let scheduler = BackoffScheduler::default().with_initial_match_limit(n_input.max(500) * 2);
        let mut runner: Runner<Math, Meta> = Runner::default()
            .with_egraph(egraph)
            .with_node_limit(self.node_limit)
            .with_iter_limit(self.iter_limit)
            .with_time_limit(self.time_limit)
            .with_scheduler(scheduler);
        runner.roots = root_ids.clone();
        if self.stall_iterations > 0 {
            let k = self.stall_iterations;
            let w = self.cost;
            let anchors = input_anchors.clone();
            let originals = originals.clone();
            let mut history: Vec<u64> = Vec::new();
            runner = runner.with_hook(move |r| {
                let c = estimate(&r.egraph, &r.roots, &anchors, &originals, &w).unwrap_or(u64::MAX);
                history.push(c);
                let n = history.len();
                if n > k && history[n - 1 - k] <= c {
                    Err(format!(
                        "the extracted DAG cost {c} has not improved for {k} iterations"
                    ))
                } else {
                    Ok(())
                }
            });
        }
        let rewrite_start = Instant::now();
        let mut runner = runner.run(&rules);
        let rewrite_time = rewrite_start.elapsed();
        runner.egraph.rebuild();
        let stop = match runner.stop_reason {
            Some(egg::StopReason::Saturated) => StopReason::Saturated,
            Some(egg::StopReason::IterationLimit(_)) => StopReason::IterationLimit,
            Some(egg::StopReason::NodeLimit(_)) => StopReason::NodeLimit,
            Some(egg::StopReason::TimeLimit(_)) => StopReason::TimeLimit,
            Some(egg::StopReason::Other(_)) => StopReason::CostStalled,
            None => StopReason::Saturated,
        };
        let iterations = runner.iterations.len();
        let eg = &runner.egraph;
        let (nodes, classes) = (eg.total_size(), eg.number_of_classes());

        // 3. Extract candidates, 4. rebuild and measure.
        let best = best_candidate(eg, &runner.roots, &input_anchors, &originals, &self.cost);
        let Some((new_roots, ops_after)) = best else {
            return Ok(unchanged(stop, iterations, nodes, classes, rewrite_time));
        };
        let cost_after = self.cost.cost(&ops_after);
        let kept = cost_after < cost_before;
        Ok(SimplifyOutcome {
            roots: if kept { new_roots } else { roots.to_vec() },
            kept,
            cost_before,
            cost_after,
            ops_before,
            ops_after,
            egraph_nodes: nodes,
            egraph_classes: classes,
            iterations,
            stop,
            rewrite_time,
            time: start.elapsed(),
        })
    }
}

/// The pool DAG as an e-graph: the e-graph, the root classes, the number of e-nodes, and the
/// input expression of each class.
fn to_egraph(roots: &[Expr]) -> (Graph, Vec<Id>, usize, Vec<(Id, Expr)>) {
    let ids = reachable(roots).ids;
    let mut eg = Graph::new(Meta::default());
    // Leaf metadata first: the analysis reads it when the leaves are added.
    with_pool(|p| {
        for &id in &ids {
            if let Node::Param(_) | Node::Const(_) | Node::Float(_) = p.node(id) {
                let numeric = matches!(p.node(id), Node::Float(_));
                eg.analysis.atom_info.insert(id, (numeric, p.sign(id)));
            }
        }
    });
    let mut map: hashbrown::HashMap<u32, Id> = hashbrown::HashMap::with_capacity(ids.len());
    let mut originals: Vec<(Id, Expr)> = Vec::with_capacity(ids.len() * 2);
    for &id in &ids {
        let e = Expr::in_current(id);
        let node = match e.view() {
            ExprView::Rational(r) => Math::Rat(r),
            ExprView::Float(_)
            | ExprView::Constant(_)
            | ExprView::Param(..)
            | ExprView::Invalid(_) => Math::Atom(id),
            ExprView::Sum { constant, terms } => {
                let mut kids = Vec::with_capacity(terms.len() + 1);
                if !constant.is_zero() {
                    kids.push(map[&constant.id()]);
                }
                for (t, c) in terms {
                    let tid = map[&t.id()];
                    if c.is_one() {
                        kids.push(tid);
                    } else {
                        let cid = map[&c.id()];
                        let scaled = eg.add(Math::Mul(sorted_pair(cid, tid)));
                        originals.push((scaled, Expr::product([c, t])));
                        kids.push(scaled);
                    }
                }
                kids.sort_unstable();
                Math::Add(kids.into())
            }
            ExprView::Product { coef, factors } => {
                let mut kids = Vec::with_capacity(factors.len() + 1);
                if !coef.is_one() {
                    kids.push(map[&coef.id()]);
                }
                for (b, r) in factors {
                    let bid = map[&b.id()];
                    if r.is_one() {
                        kids.push(bid);
                    } else {
                        let rid = eg.add(Math::Rat(r.clone()));
                        let pow = eg.add(Math::Pow([bid, rid]));
                        originals.push((pow, b.pow_rational(r)));
                        kids.push(pow);
                    }
                }
                if kids.len() == 1 {
                    // x^e alone: the Pow node is the class.
                    map.insert(id, kids[0]);
                    originals.push((kids[0], e));
                    continue;
                }
                kids.sort_unstable();
                Math::Mul(kids.into())
            }
            ExprView::Pow(a, b) => Math::Pow([map[&a.id()], map[&b.id()]]),
            ExprView::Func(f, a) => Math::Func(f, [map[&a.id()]]),
            ExprView::Atan2(y, x) => Math::Atan2([map[&y.id()], map[&x.id()]]),
        };
        let cid = eg.add(node);
        // The pool's sign knowledge may be sharper than what `make` derives; both are sound, so
        // keep the intersection. Parents are added later and see it.
        let here = eg[cid].data.sign;
        eg[cid].data.sign = here.intersect(e.sign()).unwrap_or(here);
        map.insert(id, cid);
        originals.push((cid, e));
    }
    let root_ids: Vec<Id> = roots.iter().map(|r| map[&r.id()]).collect();
    eg.rebuild();
    let n = eg.total_size();
    (eg, root_ids, n, originals)
}

fn sorted_pair(a: Id, b: Id) -> Box<[Id]> {
    if a <= b {
        Box::new([a, b])
    } else {
        Box::new([b, a])
    }
}

/// The expressions chosen for `roots` by one selection.
fn pick(idx: &Index, eg: &Graph, roots: &[Id], chosen: &[Option<Expr>]) -> Option<Vec<Expr>> {
    roots
        .iter()
        .map(|&r| idx.class_index(eg, r).and_then(|k| chosen[k]))
        .collect()
}

/// The weighted DAG cost of the extraction anchored on the input's shared nodes (for the stall
/// hook).
fn estimate(
    eg: &Graph,
    roots: &[Id],
    anchors: &HashSet<u32>,
    originals: &[(Id, Expr)],
    w: &CostModel,
) -> Option<u64> {
    let idx = Index::new(eg, originals);
    let rank = idx.rank(w);
    let exprs = pick(&idx, eg, roots, &idx.select(&rank, anchors, w))?;
    Some(w.of(&exprs))
}

/// Extract with a few anchor sets (the input's shared nodes, none, then what the best result
/// so far shares) and return the cheapest valid result by its exact op count.
fn best_candidate(
    eg: &Graph,
    roots: &[Id],
    input_anchors: &HashSet<u32>,
    originals: &[(Id, Expr)],
    w: &CostModel,
) -> Option<(Vec<Expr>, OpCount)> {
    let idx = Index::new(eg, originals);
    let rank = idx.rank(w);
    let mut best: Option<(Vec<Expr>, OpCount, u64)> = None;
    let consider = |exprs: Option<Vec<Expr>>, best: &mut Option<(Vec<Expr>, OpCount, u64)>| {
        let Some(exprs) = exprs else { return };
        if exprs.iter().any(|e| e.is_invalid()) {
            return;
        }
        let ops = Expr::op_count(&exprs);
        let c = w.cost(&ops);
        if best.as_ref().is_none_or(|b| c < b.2) {
            *best = Some((exprs, ops, c));
        }
    };
    consider(
        pick(&idx, eg, roots, &idx.select(&rank, input_anchors, w)),
        &mut best,
    );
    consider(
        pick(&idx, eg, roots, &idx.select(&rank, &HashSet::new(), w)),
        &mut best,
    );
    let mut last: Option<HashSet<u32>> = None;
    for _ in 0..2 {
        let Some((exprs, ..)) = &best else { break };
        let anchors = extract::shared_nodes(exprs);
        if last.as_ref() == Some(&anchors) {
            break;
        }
        consider(
            pick(&idx, eg, roots, &idx.select(&rank, &anchors, w)),
            &mut best,
        );
        last = Some(anchors);
    }
    best.map(|(e, o, _)| (e, o))
}
