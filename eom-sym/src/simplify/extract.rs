//! DAG-aware extraction.
//!
//! egg's [`Extractor`](egg::Extractor) minimises the *tree* cost: a subterm used twice is paid
//! twice, so it happily trades one shared node for two private ones, and the generated code
//! gets slower (see the crate notes: `AᵀBA` went from DAG cost 347 to 421). The ILP extractor
//! minimises the DAG cost but needs a C solver. This module does what is cheap and safe:
//!
//! 1. **Rank.** A Knuth (generalised Dijkstra) pass computes the tree cost of every class with
//!    strictly positive node costs and finalises classes in increasing cost. The order in which
//!    classes are finalised is a topological order: every class has a node whose children all
//!    come earlier.
//! 2. **Select.** Classes are visited in rank order; each picks, among its nodes whose children
//!    all come earlier (so the selection can never be cyclic), the one with the smallest
//!    `op cost + Σ reference cost of its children`, where the reference cost of an *anchored*
//!    class is zero (it is computed anyway, so using it again is free) and that of any other
//!    class is its own selected cost. Anchors are the classes that are shared (≥ 2 uses or a
//!    root) in some reference selection: the input DAG, or a previous selection.
//! 3. **Measure.** The DAG cost of a selection is the sum of the op costs of the classes it
//!    reaches, each once — the same count as [`Expr::op_count`](crate::Expr::op_count),
//!    weighted by the [`CostModel`](super::CostModel).
//!
//! The final word belongs to the pool: the caller rebuilds each candidate through the smart
//! constructors and compares real op counts.

use super::CostModel;
use super::lang::{Graph, Math};
use crate::rational::Rational;
use egg::Id;
use hashbrown::HashMap;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A flat, index-based copy of the e-graph.
pub(crate) struct Index {
    /// Canonical class ids by dense index.
    pub classes: Vec<Id>,
    pos: HashMap<Id, usize>,
    /// `(class index, node)` with canonical children.
    pub nodes: Vec<(usize, Math)>,
    /// Distinct child class indices per node.
    kids: Vec<Vec<usize>>,
    /// Node indices per class.
    class_nodes: Vec<Vec<usize>>,
    /// Parent node indices per class.
    parents: Vec<Vec<usize>>,
    konst: Vec<Option<Rational>>,
}

impl Index {
    pub(crate) fn new(eg: &Graph) -> Index {
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
                let mut node = n.clone();
                node.children_mut_canonical(eg);
                let mut ks: Vec<usize> = node.kids().iter().map(|ch| pos[ch]).collect();
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
        Index { classes, pos, nodes, kids, class_nodes, parents, konst }
    }

    /// Dense index of a (canonical) class.
    pub(crate) fn class_index(&self, eg: &Graph, id: Id) -> Option<usize> {
        self.pos.get(&eg.find(id)).copied()
    }

    /// Dense index of a canonical class id (children of [`Index::nodes`] are canonical).
    pub(crate) fn index_of(&self, id: Id) -> Option<usize> {
        self.pos.get(&id).copied()
    }

    fn kid(&self, id: Id) -> usize {
        self.pos[&id]
    }

    /// The op cost of node `n`, given the selected node of each child class.
    pub(crate) fn op_cost(&self, n: usize, sel: &[usize], w: &CostModel) -> u64 {
        match &self.nodes[n].1 {
            Math::Rat(_) | Math::Atom(_) => 0,
            Math::Add(ch) => w.add * (ch.len() as u64).saturating_sub(1),
            Math::Mul(ch) => {
                let mut coef = Rational::ONE;
                let mut count: i64 = 0;
                for &c in ch.iter() {
                    let k = self.kid(c);
                    match &self.konst[k] {
                        Some(r) => coef = coef.mul(r).unwrap_or(Rational::int(2)),
                        None => {
                            count += 1;
                            if let Some(&s) = sel.get(k) {
                                if s != usize::MAX && self.is_reciprocal(s) {
                                    // x·y⁻¹ is one division, not a multiplication and a division
                                    count -= 1;
                                }
                            }
                        }
                    }
                }
                if !coef.abs().is_one() {
                    count += 1;
                }
                w.mul * (count.max(1) - 1) as u64
            }
            Math::Pow([_, e]) => match &self.konst[self.kid(*e)] {
                Some(r) => power_cost(r, w),
                None => w.pow,
            },
            Math::Func(..) | Math::Atan2(_) => w.func,
        }
    }

    fn is_reciprocal(&self, n: usize) -> bool {
        match &self.nodes[n].1 {
            Math::Pow([_, e]) => self.konst[self.kid(*e)].as_ref().is_some_and(|r| r.is_negative() && r.is_integer()),
            _ => false,
        }
    }

    /// Knuth's pass: tree cost (each node costs its op cost plus one) and the finalisation
    /// order. Returns `(rank, tree selection)`; `rank[k] == usize::MAX` for classes without an
    /// acyclic term (none in practice).
    pub(crate) fn rank(&self, w: &CostModel) -> (Vec<usize>, Vec<usize>) {
        let nc = self.classes.len();
        let mut rank = vec![usize::MAX; nc];
        let mut sel = vec![usize::MAX; nc];
        let mut tree = vec![0u64; nc];
        let mut pending: Vec<usize> = self.kids.iter().map(Vec::len).collect();
        let mut heap: BinaryHeap<Reverse<(u64, usize)>> = BinaryHeap::new();
        for (n, ks) in self.kids.iter().enumerate() {
            if ks.is_empty() {
                heap.push(Reverse((1 + self.op_cost(n, &sel, w), n)));
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
            sel[k] = n;
            tree[k] = cost;
            for &p in &self.parents[k] {
                pending[p] -= 1;
                if pending[p] == 0 && rank[self.nodes[p].0] == usize::MAX {
                    let c = self.kids[p].iter().fold(1 + self.op_cost(p, &sel, w), |s, &ch| s.saturating_add(tree[ch]));
                    heap.push(Reverse((c, p)));
                }
            }
        }
        (rank, sel)
    }

    /// The DAG-aware selection for the given anchors (see the module docs).
    pub(crate) fn select(&self, rank: &[usize], anchored: &[bool], w: &CostModel) -> Vec<usize> {
        let nc = self.classes.len();
        let mut order: Vec<usize> = (0..nc).filter(|&k| rank[k] != usize::MAX).collect();
        order.sort_unstable_by_key(|&k| rank[k]);
        let mut sel = vec![usize::MAX; nc];
        let mut refc = vec![0u64; nc];
        for k in order {
            let mut best: Option<(u64, usize)> = None;
            for &n in &self.class_nodes[k] {
                if !self.kids[n].iter().all(|&ch| rank[ch] < rank[k]) {
                    continue;
                }
                let c = self.kids[n].iter().fold(self.op_cost(n, &sel, w), |s, &ch| s.saturating_add(refc[ch]));
                if best.is_none_or(|(b, _)| c < b) {
                    best = Some((c, n));
                }
            }
            if let Some((c, n)) = best {
                sel[k] = n;
                refc[k] = if anchored[k] { 0 } else { c };
            }
        }
        sel
    }

    /// Classes reachable from `roots` through the selection, in rank order (children first),
    /// with the number of selected parents (plus root occurrences) of each.
    pub(crate) fn reached(&self, roots: &[usize], sel: &[usize], rank: &[usize]) -> (Vec<usize>, Vec<u32>) {
        let mut uses = vec![0u32; self.classes.len()];
        let mut seen = vec![false; self.classes.len()];
        let mut stack: Vec<usize> = Vec::new();
        let mut out = Vec::new();
        for &r in roots {
            uses[r] += 1;
            stack.push(r);
        }
        while let Some(k) = stack.pop() {
            if seen[k] {
                continue;
            }
            seen[k] = true;
            out.push(k);
            if sel[k] == usize::MAX {
                continue;
            }
            for &ch in &self.kids[sel[k]] {
                uses[ch] += 1;
                if !seen[ch] {
                    stack.push(ch);
                }
            }
        }
        out.sort_unstable_by_key(|&k| rank[k]);
        (out, uses)
    }

    /// DAG cost of a selection: every reached class once.
    pub(crate) fn dag_cost(&self, roots: &[usize], sel: &[usize], rank: &[usize], w: &CostModel) -> Option<u64> {
        let (reached, _) = self.reached(roots, sel, rank);
        let mut total = 0u64;
        for k in reached {
            if sel[k] == usize::MAX {
                return None;
            }
            total = total.saturating_add(self.op_cost(sel[k], sel, w));
        }
        Some(total)
    }

    /// Anchors: classes used at least twice (or as a root) by a selection.
    pub(crate) fn shared(&self, roots: &[usize], sel: &[usize], rank: &[usize]) -> Vec<bool> {
        let (reached, uses) = self.reached(roots, sel, rank);
        let mut a = vec![false; self.classes.len()];
        for k in reached {
            a[k] = uses[k] >= 2 || roots.contains(&k);
        }
        a
    }
}

/// Cost of `x^r` as [`Expr::op_count`](crate::Expr::op_count) counts it.
pub(crate) fn power_cost(r: &Rational, w: &CostModel) -> u64 {
    match r.as_small() {
        Some((1, 1)) => 0,
        Some((k, 1)) if k > 0 => w.mul * chain(k as u64),
        Some((-1, 1)) => w.div,
        Some((k, 1)) => w.div + w.mul * chain(k.unsigned_abs()),
        Some((1, 2)) => w.func,
        _ => w.pow,
    }
}

/// Multiplications of a square-and-multiply chain for `x^k`.
fn chain(k: u64) -> u64 {
    if k <= 1 {
        return 0;
    }
    (63 - k.leading_zeros() as u64) + k.count_ones() as u64 - 1
}

trait NodeExt {
    fn children_mut_canonical(&mut self, eg: &Graph);
    fn kids(&self) -> &[Id];
}

impl NodeExt for Math {
    fn children_mut_canonical(&mut self, eg: &Graph) {
        use egg::Language;
        self.update_children(|c| eg.find(c));
    }
    fn kids(&self) -> &[Id] {
        use egg::Language;
        self.children()
    }
}
