//! DAG-aware extraction, costed in the pool's own terms.
//!
//! egg's [`Extractor`](egg::Extractor) minimises the *tree* cost: a subterm used twice is paid
//! twice, so it happily trades one shared node for two private ones and the generated code gets
//! slower (on `AᵀBA` the shared cost grows from 347 to 421). The ILP extractor
//! minimises the DAG cost but needs a C solver. And a cost computed on the e-graph is not the
//! cost of the result anyway: the smart constructors flatten nested sums and products, inline
//! powers and numeric coefficients into the product or sum that uses them, and collect like
//! terms. So this module costs every choice by **building it in the pool**:
//!
//! 1. **Rank.** A Knuth (generalised Dijkstra) pass over the e-graph computes tree costs with
//!    strictly positive node costs and finalises classes in increasing cost. That order is
//!    topological: every class has a node whose children all come earlier. (Costs here are a
//!    rough e-graph estimate; they only fix the order.)
//! 2. **Select.** Classes are visited in rank order. For each node whose children all come
//!    earlier (so the selection can never be cyclic), the candidate expression is built through
//!    the smart constructors from the children's chosen expressions, and costed as the tree
//!    cost of its pool DAG in which *anchored* pool nodes are free: they are computed anyway,
//!    so reusing them costs nothing. The cheapest candidate becomes the class's expression.
//! 3. **Anchors** are the pool nodes shared (two or more parents, or a root) by a reference
//!    DAG: the input, or the result of a previous selection. The caller tries a few and
//!    measures each result with [`Expr::op_count`], which is exact.

use super::CostModel;
use super::lang::{Graph, Math};
use crate::context::with_pool;
use crate::expr::{Expr, reachable};
use crate::pool::power_ops;
use crate::rational::Rational;
use egg::Id;
use hashbrown::{HashMap, HashSet};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A flat, index-based copy of the e-graph.
pub(crate) struct Index {
    /// Canonical class ids by dense index.
    pub classes: Vec<Id>,
    pos: HashMap<Id, usize>,
    /// `(class index, node)` with canonical children.
    nodes: Vec<(usize, Math)>,
    /// Distinct child class indices per node.
    kids: Vec<Vec<usize>>,
    /// Node indices per class.
    class_nodes: Vec<Vec<usize>>,
    /// Parent node indices per class.
    parents: Vec<Vec<usize>>,
    konst: Vec<Option<Rational>>,
    /// The input expression of the class, if it holds one (see [`Index::select`]).
    original: Vec<Option<Expr>>,
}

impl Index {
    /// `originals`: `(class, expression)` pairs of the input DAG.
    pub(crate) fn new(eg: &Graph, originals: &[(Id, Expr)]) -> Index {
        use egg::Language;
        let mut classes: Vec<Id> = eg.classes().map(|c| c.id).collect();
        classes.sort_unstable();
        let pos: HashMap<Id, usize> = classes.iter().enumerate().map(|(k, &c)| (c, k)).collect();
        let mut nodes = Vec::with_capacity(eg.total_number_of_nodes());
        let mut kids = Vec::with_capacity(nodes.capacity());
        let mut class_nodes = vec![Vec::new(); classes.len()];
        let mut parents = vec![Vec::new(); classes.len()];
        let mut konst = vec![None; classes.len()];
        for (k, &c) in classes.iter().enumerate() {
            let class = &eg[c];
            konst[k] = class.data.konst.clone();
            for n in &class.nodes {
                let node = n.clone().map_children(|ch| eg.find(ch));
                let mut ks: Vec<usize> = node
                    .children()
                    .iter()
                    .filter_map(|ch| pos.get(ch).copied())
                    .collect();
                ks.sort_unstable();
                ks.dedup();
                let ni = nodes.len();
                for &ch in &ks {
                    parents[ch].push(ni);
                }
                class_nodes[k].push(ni);
                nodes.push((k, node));
                kids.push(ks);
            }
        }
        let mut original = vec![None; classes.len()];
        for &(c, e) in originals {
            if let Some(&k) = pos.get(&eg.find(c)) {
                original[k] = Some(e);
            }
        }
        Index {
            classes,
            pos,
            nodes,
            kids,
            class_nodes,
            parents,
            konst,
            original,
        }
    }

    /// Dense index of a class.
    pub(crate) fn class_index(&self, eg: &Graph, id: Id) -> Option<usize> {
        self.pos.get(&eg.find(id)).copied()
    }

    /// A rough e-graph cost of one node (only used to order classes).
    fn rough_cost(&self, n: usize, w: &CostModel) -> u64 {
        match &self.nodes[n].1 {
            Math::Rat(_) | Math::Atom(_) => 0,
            Math::Add(ch) => w.add * (ch.len() as u64).saturating_sub(1),
            Math::Mul(ch) => w.mul * (ch.len() as u64).saturating_sub(1),
            Math::Pow([_, e]) => match self.pos.get(e).and_then(|&k| self.konst[k].as_ref()) {
                Some(r) => w.cost(&power_ops(r).0),
                None => w.pow,
            },
            Math::Func(..) | Math::Atan2(_) => w.func,
        }
    }

    /// Knuth's pass: the finalisation order of the classes (`usize::MAX` for classes without
    /// an acyclic term, which do not occur for e-graphs grown from a DAG).
    pub(crate) fn rank(&self, w: &CostModel) -> Vec<usize> {
        let nc = self.classes.len();
        let mut rank = vec![usize::MAX; nc];
        let mut tree = vec![0u64; nc];
        let mut pending: Vec<usize> = self.kids.iter().map(Vec::len).collect();
        let mut heap: BinaryHeap<Reverse<(u64, usize)>> = BinaryHeap::new();
        for (n, ks) in self.kids.iter().enumerate() {
            if ks.is_empty() {
                heap.push(Reverse((1 + self.rough_cost(n, w), n)));
            }
        }
        let mut next = 0;
        while let Some(Reverse((cost, n))) = heap.pop() {
            let k = self.nodes[n].0;
            if rank[k] != usize::MAX {
                continue;
            }
            rank[k] = next;
            next += 1;
            tree[k] = cost;
            for &p in &self.parents[k] {
                pending[p] -= 1;
                if pending[p] == 0 && rank[self.nodes[p].0] == usize::MAX {
                    let c = self.kids[p]
                        .iter()
                        .fold(1 + self.rough_cost(p, w), |s, &ch| {
                            s.saturating_add(tree[ch])
                        });
                    heap.push(Reverse((c, p)));
                }
            }
        }
        rank
    }

    /// The selection for one anchor set: the chosen expression of every class that has one.
    pub(crate) fn select(
        &self,
        rank: &[usize],
        anchors: &HashSet<u32>,
        w: &CostModel,
    ) -> Vec<Option<Expr>> {
        let nc = self.classes.len();
        let mut order: Vec<usize> = (0..nc).filter(|&k| rank[k] != usize::MAX).collect();
        order.sort_unstable_by_key(|&k| rank[k]);
        let mut chosen: Vec<Option<Expr>> = vec![None; nc];
        let mut tc = TreeCost {
            memo: HashMap::new(),
            anchors,
            w: *w,
        };
        for k in order {
            // Untouched by rewriting (one node, children unchanged): the input's own node,
            // without rebuilding or costing it (costs are computed lazily for parents).
            if self.class_nodes[k].len() == 1 && self.original[k].is_some() {
                let n = self.class_nodes[k][0];
                if self.kids[n]
                    .iter()
                    .all(|&ch| chosen[ch].is_some() && chosen[ch] == self.original[ch])
                {
                    chosen[k] = self.original[k];
                    continue;
                }
            }
            let eligible: Vec<usize> = self.class_nodes[k]
                .iter()
                .copied()
                .filter(|&n| self.kids[n].iter().all(|&ch| rank[ch] < rank[k]))
                .collect();
            let mut best: Option<(u64, Expr)> = None;
            for &n in &eligible {
                let get = |id: &Id| self.pos.get(id).and_then(|&c| chosen[c]);
                let Some(e) = build(&self.nodes[n].1, get) else {
                    continue;
                };
                if e.is_invalid() {
                    continue;
                }
                if eligible.len() == 1 {
                    best = Some((0, e));
                    break;
                }
                let c = tc.of(e.id());
                if best.as_ref().is_none_or(|(b, _)| c < *b) {
                    best = Some((c, e));
                }
            }
            chosen[k] = best.map(|b| b.1);
        }
        chosen
    }
}

/// The expression of an e-node, built through the smart constructors from its children's.
pub(crate) fn build(node: &Math, get: impl Fn(&Id) -> Option<Expr>) -> Option<Expr> {
    Some(match node {
        Math::Rat(r) => Expr::from_rational(r.clone()),
        Math::Atom(id) => Expr::in_current(*id),
        Math::Add(ch) => Expr::sum(ch.iter().map(&get).collect::<Option<Vec<_>>>()?),
        Math::Mul(ch) => Expr::product(ch.iter().map(&get).collect::<Option<Vec<_>>>()?),
        Math::Pow([b, e]) => {
            let base = get(b)?;
            let ex = get(e)?;
            match ex.as_rational() {
                Some(r) => base.pow_rational(r),
                None => base.pow(ex),
            }
        }
        Math::Func(f, [a]) => get(a)?.apply(*f),
        Math::Atan2([y, x]) => get(y)?.atan2(get(x)?),
    })
}

/// Tree cost of pool nodes in which anchored nodes are free (memoised per anchor set).
struct TreeCost<'a> {
    memo: HashMap<u32, u64>,
    anchors: &'a HashSet<u32>,
    w: CostModel,
}

impl TreeCost<'_> {
    /// The cost of computing `id` (itself never free: it is the node being chosen).
    fn of(&mut self, id: u32) -> u64 {
        if let Some(&c) = self.memo.get(&id) {
            return c;
        }
        // Iterative post-order: the pool DAG can be deep.
        let mut stack: Vec<(u32, bool)> = vec![(id, false)];
        with_pool(|p| {
            while let Some((x, expanded)) = stack.pop() {
                if self.memo.contains_key(&x) {
                    continue;
                }
                if !expanded {
                    stack.push((x, true));
                    for &c in p.shape(x).children() {
                        if !self.anchors.contains(&c) && !self.memo.contains_key(&c) {
                            stack.push((c, false));
                        }
                    }
                    continue;
                }
                let shape = p.shape(x);
                let mut c = self.w.cost(&shape.ops(|e| p.exponent(e)));
                for ch in shape.children() {
                    if !self.anchors.contains(ch) {
                        c = c.saturating_add(self.memo.get(ch).copied().unwrap_or(0));
                    }
                }
                self.memo.insert(x, c);
            }
        });
        self.memo.get(&id).copied().unwrap_or(u64::MAX)
    }
}

/// Pool nodes with two or more parents in the DAG of `roots`, and the roots themselves.
pub(crate) fn shared_nodes(roots: &[Expr]) -> HashSet<u32> {
    let ids = reachable(roots).ids;
    let mut parents: HashMap<u32, u32> = HashMap::with_capacity(ids.len());
    with_pool(|p| {
        for &i in &ids {
            let mut seen: Vec<u32> = Vec::new();
            for &c in p.shape(i).children() {
                if !seen.contains(&c) {
                    seen.push(c);
                    *parents.entry(c).or_default() += 1;
                }
            }
        }
    });
    let mut s: HashSet<u32> = parents
        .into_iter()
        .filter(|(_, n)| *n >= 2)
        .map(|(i, _)| i)
        .collect();
    s.extend(roots.iter().map(|r| r.id()));
    s
}
