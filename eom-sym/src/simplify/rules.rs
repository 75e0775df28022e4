//! The rewrite rules: n-ary searchers and appliers written against the canonical sums and
//! products, instead of fixed-arity patterns plus AC rules.
//!
//! Every rule looks at one e-class at a time, reads the terms of a sum (or the factors of a
//! product) as monomials `c · Π bᵢ^eᵢ` ([`Mono`], obtained by looking through `Mul` and `Pow`
//! nodes of the child classes), and proposes a small replacement term ([`Build`]). The
//! searcher reports a class only if some proposal is not already in it (so the runner can
//! detect saturation), and the applier adds the proposals and unions them with the class.
//!
//! The rule table with conditions is in the [module docs](super).
//!
//! No rule distributes, and no rule is an AC rule: the pool already canonicalises AC, and
//! distribution plus factoring is the combination that explodes.

use super::lang::{Graph, Math};
use crate::pool::Func;
use crate::rational::Rational;
use egg::{Applier, Id, PatternAst, Rewrite, SearchMatches, Searcher, Subst, Symbol, Var};
use hashbrown::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

/// How deep [`view`] looks through nested products.
const VIEW_DEPTH: u32 = 3;
/// At most this many nodes of one class are examined per rule.
const NODES_PER_CLASS: usize = 3;
/// Candidate factors tried per sum.
const FACTOR_CANDIDATES: usize = 2;
/// Sums with more terms than this are left to the other rules (quadratic pair searches).
const MAX_PAIR_TERMS: usize = 256;

/// A term `coef · Π base^exp` (factors sorted by base id; a base may appear twice with
/// exponents of opposite signs, as in the pool).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Mono {
    pub coef: Rational,
    pub factors: Vec<(Id, Rational)>,
}

/// A replacement term to be looked up or added.
#[derive(Clone, Debug)]
pub(crate) enum Build {
    Class(Id),
    Rat(Rational),
    Add(Vec<Build>),
    Mul(Vec<Build>),
    Pow(Box<Build>, Rational),
    Func(Func, Box<Build>),
}

// ------------------------------------------------------------------ views

fn first_node<'a, T>(eg: &'a Graph, class: Id, f: impl Fn(&'a Math) -> Option<T>) -> Option<T> {
    eg[class].nodes.iter().find_map(f)
}

/// The monomial view of a class.
pub(crate) fn view(eg: &Graph, class: Id, depth: u32) -> Option<Mono> {
    let class = eg.find(class);
    let data = &eg[class].data;
    if let Some(r) = &data.konst {
        return Some(Mono {
            coef: r.clone(),
            factors: vec![],
        });
    }
    let mul = |n: &'_ Math| match n {
        Math::Mul(k) => Some(k.clone()),
        _ => None,
    };
    if let Some(kids) = (depth > 0).then(|| first_node(eg, class, mul)).flatten() {
        return view_product(eg, &kids, depth - 1);
    }
    if let Some((b, e)) = pow_of(eg, class) {
        return Some(Mono {
            coef: Rational::ONE,
            factors: vec![(eg.find(b), e)],
        });
    }
    Some(Mono {
        coef: Rational::ONE,
        factors: vec![(class, Rational::ONE)],
    })
}

/// `(base, exponent)` of the first rational power in a class.
fn pow_of(eg: &Graph, class: Id) -> Option<(Id, Rational)> {
    first_node(eg, class, |n| match n {
        Math::Pow([b, e]) => eg[*e].data.konst.clone().map(|r| (*b, r)),
        _ => None,
    })
}

/// The view of a product of classes (no merging of equal bases).
fn view_product(eg: &Graph, kids: &[Id], depth: u32) -> Option<Mono> {
    let mut coef = Rational::ONE;
    let mut factors = Vec::with_capacity(kids.len());
    for &k in kids {
        let v = view(eg, k, depth)?;
        coef = coef.mul(&v.coef).ok()?;
        factors.extend(v.factors);
    }
    factors.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.signum().cmp(&a.1.signum())));
    Some(Mono { coef, factors })
}

/// Merge equal bases the way the pool does: exponents of the same sign always, of opposite
/// signs only when the base is provably nonzero. Returns the merged factors and whether
/// anything changed.
fn merge_factors(eg: &Graph, factors: &[(Id, Rational)]) -> Option<(Vec<(Id, Rational)>, bool)> {
    let mut out: Vec<(Id, Rational)> = Vec::with_capacity(factors.len());
    let mut changed = false;
    for (b, e) in factors {
        let mut merged = false;
        for (ob, oe) in out.iter_mut().rev() {
            if ob != b {
                break;
            }
            if oe.signum() == e.signum() || eg[*b].data.sign.is_nonzero() {
                *oe = oe.add(e).ok()?;
                merged = true;
                break;
            }
        }
        if merged {
            changed = true;
        } else {
            out.push((*b, e.clone()));
        }
    }
    let before = out.len();
    out.retain(|(_, e)| !e.is_zero());
    changed |= out.len() != before;
    Some((out, changed))
}

// ------------------------------------------------------------------ building

fn p_pow(b: Build, e: Rational) -> Build {
    if e.is_zero() {
        Build::Rat(Rational::ONE)
    } else if e.is_one() {
        b
    } else {
        Build::Pow(Box::new(b), e)
    }
}

fn p_mono(coef: Rational, factors: Vec<(Build, Rational)>) -> Build {
    if coef.is_zero() {
        return Build::Rat(Rational::ZERO);
    }
    let mut items = Vec::with_capacity(factors.len() + 1);
    if !coef.is_one() {
        items.push(Build::Rat(coef));
    }
    for (b, e) in factors {
        match p_pow(b, e) {
            Build::Rat(r) if r.is_one() => {}
            x => items.push(x),
        }
    }
    match items.len() {
        0 => Build::Rat(Rational::ONE),
        1 => items.pop().expect("one item"),
        _ => Build::Mul(items),
    }
}

fn p_class_mono(coef: Rational, factors: &[(Id, Rational)]) -> Build {
    p_mono(
        coef,
        factors
            .iter()
            .map(|(b, e)| (Build::Class(*b), e.clone()))
            .collect(),
    )
}

fn p_add(eg: &Graph, terms: Vec<Build>) -> Option<Build> {
    let mut c = Rational::ZERO;
    let mut items = Vec::with_capacity(terms.len() + 1);
    for t in terms {
        match t {
            Build::Rat(r) => c = c.add(&r).ok()?,
            Build::Class(id) if eg[id].data.konst.is_some() => {
                c = c.add(eg[id].data.konst.as_ref().expect("constant")).ok()?
            }
            x => items.push(x),
        }
    }
    if !c.is_zero() {
        items.push(Build::Rat(c.clone()));
    }
    Some(match items.len() {
        0 => Build::Rat(c),
        1 => items.pop().expect("one item"),
        _ => Build::Add(items),
    })
}

fn sorted(mut ids: Vec<Id>) -> Box<[Id]> {
    ids.sort_unstable();
    ids.into()
}

/// Add the term to the e-graph.
pub(crate) fn materialize(eg: &mut Graph, b: &Build) -> Id {
    match b {
        Build::Class(id) => eg.find(*id),
        Build::Rat(r) => eg.add(Math::Rat(r.clone())),
        Build::Add(items) => {
            let ids = items.iter().map(|x| materialize(eg, x)).collect();
            eg.add(Math::Add(sorted(ids)))
        }
        Build::Mul(items) => {
            let ids = items.iter().map(|x| materialize(eg, x)).collect();
            eg.add(Math::Mul(sorted(ids)))
        }
        Build::Pow(base, e) => {
            let b = materialize(eg, base);
            let e = eg.add(Math::Rat(e.clone()));
            eg.add(Math::Pow([b, e]))
        }
        Build::Func(f, a) => {
            let a = materialize(eg, a);
            eg.add(Math::Func(*f, [a]))
        }
    }
}

/// The class of the term if it is already in the e-graph.
fn lookup(eg: &Graph, b: &Build) -> Option<Id> {
    match b {
        Build::Class(id) => Some(eg.find(*id)),
        Build::Rat(r) => eg.lookup(Math::Rat(r.clone())),
        Build::Add(items) => {
            let ids = items
                .iter()
                .map(|x| lookup(eg, x))
                .collect::<Option<Vec<_>>>()?;
            eg.lookup(Math::Add(sorted(ids)))
        }
        Build::Mul(items) => {
            let ids = items
                .iter()
                .map(|x| lookup(eg, x))
                .collect::<Option<Vec<_>>>()?;
            eg.lookup(Math::Mul(sorted(ids)))
        }
        Build::Pow(base, e) => {
            let b = lookup(eg, base)?;
            let e = eg.lookup(Math::Rat(e.clone()))?;
            eg.lookup(Math::Pow([b, e]))
        }
        Build::Func(f, a) => {
            let a = lookup(eg, a)?;
            eg.lookup(Math::Func(*f, [a]))
        }
    }
}

// ------------------------------------------------------------------ rules

/// The rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Factor,
    Cancel,
    Collect,
    Pythagoras,
    AngleSum,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Factor => "factor",
            Kind::Cancel => "cancel",
            Kind::Collect => "collect",
            Kind::Pythagoras => "pythagoras",
            Kind::AngleSum => "angle-sum",
        }
    }
}

/// Children of the sums (or products) of a class, at most [`NODES_PER_CLASS`] of them.
fn nodes_of(eg: &Graph, class: Id, sums: bool) -> Vec<Vec<Id>> {
    eg[class]
        .nodes
        .iter()
        .filter_map(|n| match (n, sums) {
            (Math::Add(k), true) | (Math::Mul(k), false) => Some(k.to_vec()),
            _ => None,
        })
        .take(NODES_PER_CLASS)
        .collect()
}

/// Views of the terms of sums, shared by the rules: during one search phase the e-graph does
/// not change, and all sum rules need the same views. The cache is cleared whenever the
/// e-graph's size changes. (A view computed before a merge is still true afterwards — classes
/// only merge — so a stale entry would be sound, only less complete.)
#[derive(Default)]
pub(crate) struct ViewCache {
    stamp: (usize, usize),
    map: HashMap<Id, Option<Mono>>,
}

pub(crate) type SharedViews = Arc<Mutex<ViewCache>>;

fn cached_view(cache: &SharedViews, eg: &Graph, class: Id) -> Option<Mono> {
    let class = eg.find(class);
    let stamp = (eg.total_size(), eg.number_of_classes());
    let mut c = cache.lock().unwrap_or_else(PoisonError::into_inner);
    if c.stamp != stamp {
        c.map.clear();
        c.stamp = stamp;
    }
    if let Some(v) = c.map.get(&class) {
        return v.clone();
    }
    let v = view(eg, class, VIEW_DEPTH);
    c.map.insert(class, v.clone());
    v
}

/// The proposals of one rule for one class.
pub(crate) fn proposals(kind: Kind, eg: &Graph, class: Id, cache: &SharedViews) -> Vec<Build> {
    let class = eg.find(class);
    let mut out = Vec::new();
    match kind {
        Kind::Cancel => {
            for kids in nodes_of(eg, class, false) {
                out.extend(cancel(eg, &kids));
            }
        }
        _ => {
            for kids in nodes_of(eg, class, true) {
                if kids.len() < 2 {
                    continue;
                }
                let views: Vec<Option<Mono>> =
                    kids.iter().map(|&k| cached_view(cache, eg, k)).collect();
                match kind {
                    Kind::Factor => out.extend(factor(eg, &kids, &views)),
                    Kind::Collect => out.extend(collect(eg, &kids, &views)),
                    Kind::Pythagoras => out.extend(pythagoras(eg, &kids, &views)),
                    Kind::AngleSum => out.extend(angle_sum(eg, &kids, &views)),
                    Kind::Cancel => {}
                }
            }
        }
    }
    out
}

/// Exponents of each base in a term, with bases that occur with both signs marked `None`.
fn exponents(eg: &Graph, m: &Mono) -> Option<HashMap<Id, Option<Rational>>> {
    let (merged, _) = merge_factors(eg, &m.factors)?;
    let mut map: HashMap<Id, Option<Rational>> = HashMap::with_capacity(merged.len());
    for (b, e) in merged {
        map.entry(b).and_modify(|x| *x = None).or_insert(Some(e));
    }
    Some(map)
}

fn factor(eg: &Graph, kids: &[Id], views: &[Option<Mono>]) -> Vec<Build> {
    let exps: Vec<Option<HashMap<Id, Option<Rational>>>> = views
        .iter()
        .map(|v| v.as_ref().and_then(|m| exponents(eg, m)))
        .collect();
    // Count, per (base, sign of exponent), the terms that contain it with an integer exponent.
    let mut count: HashMap<(Id, bool), usize> = HashMap::new();
    for map in exps.iter().flatten() {
        for (b, e) in map {
            if let Some(e) = e
                && e.is_integer()
                && !eg[*b].data.numeric
            {
                *count.entry((*b, e.is_negative())).or_default() += 1;
            }
        }
    }
    let mut cands: Vec<((Id, bool), usize)> = count.into_iter().filter(|(_, n)| *n >= 2).collect();
    cands.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let mut out = Vec::new();
    for ((base, neg), _) in cands.into_iter().take(FACTOR_CANDIDATES) {
        if let Some(b) = factor_by(eg, kids, views, &exps, base, neg) {
            out.push(b);
        }
    }
    out
}

fn factor_by(
    eg: &Graph,
    kids: &[Id],
    views: &[Option<Mono>],
    exps: &[Option<HashMap<Id, Option<Rational>>>],
    base: Id,
    neg: bool,
) -> Option<Build> {
    let has = |i: usize| {
        exps[i]
            .as_ref()
            .and_then(|m| m.get(&base))
            .and_then(|e| e.as_ref())
            .is_some_and(|e| e.is_integer() && e.is_negative() == neg)
    };
    let group: Vec<usize> = (0..kids.len()).filter(|&i| has(i)).collect();
    if group.len() < 2 {
        return None;
    }
    // The common monomial of the group: every base with integer exponents of one sign in all
    // terms of the group, to the smallest magnitude.
    let first = exps[group[0]].as_ref()?;
    let mut common: Vec<(Id, Rational)> = Vec::new();
    for (b, e) in first {
        let Some(e) = e else { continue };
        if !e.is_integer() || eg[*b].data.numeric {
            continue;
        }
        let mut m = e.clone();
        let mut ok = true;
        for &i in &group[1..] {
            match exps[i].as_ref()?.get(b) {
                Some(Some(f)) if f.is_integer() && f.signum() == e.signum() => {
                    if f.abs() < m.abs() {
                        m = f.clone();
                    }
                }
                _ => {
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            common.push((*b, m));
        }
    }
    common.sort_by_key(|a| a.0);
    // A common coefficient (up to sign) is pulled out too, so that the inner coefficients are
    // ±1 (free in generated code).
    let c0 = views[group[0]].as_ref()?.coef.clone();
    let same_magnitude = group
        .iter()
        .all(|&i| views[i].as_ref().is_some_and(|v| v.coef.abs() == c0.abs()));
    let pull = if same_magnitude && !c0.is_one() {
        c0
    } else {
        Rational::ONE
    };
    let mut quotients = Vec::with_capacity(group.len());
    for &i in &group {
        let v = views[i].as_ref()?;
        let (merged, _) = merge_factors(eg, &v.factors)?;
        let mut rest: Vec<(Id, Rational)> = Vec::with_capacity(merged.len());
        for (b, e) in merged {
            match common.iter().find(|(cb, _)| *cb == b) {
                Some((_, m)) if e.signum() == m.signum() => {
                    let r = e.sub(m).ok()?;
                    if !r.is_zero() {
                        rest.push((b, r));
                    }
                }
                _ => rest.push((b, e)),
            }
        }
        let coef = v.coef.div(&pull)?.ok()?;
        quotients.push(p_class_mono(coef, &rest));
    }
    let inner = p_add(eg, quotients)?;
    let mut fs: Vec<(Build, Rational)> = common
        .iter()
        .map(|(b, e)| (Build::Class(*b), e.clone()))
        .collect();
    fs.push((inner, Rational::ONE));
    let factored = p_mono(pull, fs);
    if group.len() == kids.len() {
        return Some(factored);
    }
    let mut terms: Vec<Build> = vec![factored];
    for (i, &k) in kids.iter().enumerate() {
        if !group.contains(&i) {
            terms.push(Build::Class(k));
        }
    }
    p_add(eg, terms)
}

fn cancel(eg: &Graph, kids: &[Id]) -> Option<Build> {
    let m = view_product(eg, kids, VIEW_DEPTH - 1)?;
    let (merged, changed) = merge_factors(eg, &m.factors)?;
    if !changed {
        return None;
    }
    Some(p_class_mono(m.coef, &merged))
}

fn collect(eg: &Graph, kids: &[Id], views: &[Option<Mono>]) -> Option<Build> {
    // (merged factors, summed coefficient, member terms)
    type Group = (Vec<(Id, Rational)>, Rational, Vec<usize>);
    let mut groups: Vec<Group> = Vec::new();
    let mut index: HashMap<Vec<(Id, Rational)>, usize> = HashMap::new();
    let mut constant = Rational::ZERO;
    let mut n_const = 0;
    let mut opaque = Vec::new();
    for (i, v) in views.iter().enumerate() {
        let Some(v) = v else {
            opaque.push(i);
            continue;
        };
        if v.factors.is_empty() {
            constant = constant.add(&v.coef).ok()?;
            n_const += 1;
            continue;
        }
        let (key, _) = merge_factors(eg, &v.factors)?;
        match index.get(&key) {
            Some(&g) => {
                groups[g].1 = groups[g].1.add(&v.coef).ok()?;
                groups[g].2.push(i);
            }
            None => {
                index.insert(key.clone(), groups.len());
                groups.push((key, v.coef.clone(), vec![i]));
            }
        }
    }
    if n_const < 2 && groups.iter().all(|g| g.2.len() < 2) {
        return None;
    }
    let mut terms: Vec<Build> = opaque.iter().map(|&i| Build::Class(kids[i])).collect();
    for (key, coef, members) in groups {
        if members.len() == 1 {
            terms.push(Build::Class(kids[members[0]]));
        } else {
            terms.push(p_class_mono(coef, &key));
        }
    }
    terms.push(Build::Rat(constant));
    p_add(eg, terms)
}

/// `f(x)` with `f ∈ {sin, cos}` if the class holds one: `(f, x)`.
fn trig_of(eg: &Graph, class: Id) -> Option<(Func, Id)> {
    first_node(eg, class, |n| match n {
        Math::Func(f @ (Func::Sin | Func::Cos), [x]) => Some((*f, eg.find(*x))),
        _ => None,
    })
}

/// A term split as `coef · rest · f(x)^power` for one trigonometric factor.
struct TrigTerm {
    index: usize,
    base: Id,
    func: Func,
    arg: Id,
    coef: Rational,
    rest: Vec<(Id, Rational)>,
}

/// All splittings of each term around one sin/cos factor with exponent `power`.
fn trig_terms(eg: &Graph, views: &[Option<Mono>], power: &Rational) -> Vec<TrigTerm> {
    let mut out = Vec::new();
    for (i, v) in views.iter().enumerate() {
        let Some(v) = v else { continue };
        let Some((merged, _)) = merge_factors(eg, &v.factors) else {
            continue;
        };
        for (k, (b, e)) in merged.iter().enumerate() {
            if e != power {
                continue;
            }
            if let Some((func, arg)) = trig_of(eg, *b) {
                let mut rest = merged.clone();
                rest.remove(k);
                out.push(TrigTerm {
                    index: i,
                    base: *b,
                    func,
                    arg,
                    coef: v.coef.clone(),
                    rest,
                });
            }
        }
    }
    out
}

fn pythagoras(eg: &Graph, kids: &[Id], views: &[Option<Mono>]) -> Option<Build> {
    if kids.len() > MAX_PAIR_TERMS {
        return None;
    }
    let two = Rational::int(2);
    let tt = trig_terms(eg, views, &two);
    if tt.is_empty() {
        return None;
    }
    let mut used = vec![false; kids.len()];
    let mut new_terms = Vec::new();
    for s in &tt {
        if s.func != Func::Sin || used[s.index] {
            continue;
        }
        for c in &tt {
            if c.func == Func::Cos
                && !used[c.index]
                && c.index != s.index
                && c.arg == s.arg
                && c.coef == s.coef
                && c.rest == s.rest
            {
                used[s.index] = true;
                used[c.index] = true;
                new_terms.push(p_class_mono(s.coef.clone(), &s.rest));
                break;
            }
        }
    }
    // k − k·sin²x → k·cos²x (and with sin and cos swapped).
    if let Some(ki) =
        (0..kids.len()).find(|&i| views[i].as_ref().is_some_and(|v| v.factors.is_empty()))
    {
        let k = views[ki].as_ref()?.coef.clone();
        if !used[ki] && !k.is_zero() {
            for t in &tt {
                if !used[t.index] && t.rest.is_empty() && t.coef == k.neg() {
                    used[ki] = true;
                    used[t.index] = true;
                    let other = if t.func == Func::Sin {
                        Func::Cos
                    } else {
                        Func::Sin
                    };
                    let f = Build::Func(other, Box::new(Build::Class(t.arg)));
                    new_terms.push(p_mono(k.clone(), vec![(f, two.clone())]));
                    break;
                }
            }
        }
    }
    if new_terms.is_empty() {
        return None;
    }
    let mut terms = new_terms;
    for (i, &k) in kids.iter().enumerate() {
        if !used[i] {
            terms.push(Build::Class(k));
        }
    }
    p_add(eg, terms)
}

fn angle_sum(eg: &Graph, kids: &[Id], views: &[Option<Mono>]) -> Option<Build> {
    if kids.len() > MAX_PAIR_TERMS {
        return None;
    }
    // Terms with exactly two first-power sin/cos factors of different arguments.
    struct Pair {
        index: usize,
        // (function, argument) of the two factors, sorted
        fa: (Func, Id),
        fb: (Func, Id),
        coef: Rational,
        rest: Vec<(Id, Rational)>,
    }
    let one = Rational::ONE;
    let tt = trig_terms(eg, views, &one);
    let mut pairs: Vec<Pair> = Vec::new();
    for i in 0..kids.len() {
        let mine: Vec<&TrigTerm> = tt.iter().filter(|t| t.index == i).collect();
        if mine.len() != 2 || mine[0].arg == mine[1].arg {
            continue;
        }
        let rest: Vec<(Id, Rational)> = mine[0]
            .rest
            .iter()
            .filter(|(b, _)| *b != mine[1].base)
            .cloned()
            .collect();
        let (x, y) = ((mine[0].func, mine[0].arg), (mine[1].func, mine[1].arg));
        let (fa, fb) = if x <= y { (x, y) } else { (y, x) };
        pairs.push(Pair {
            index: i,
            fa,
            fb,
            coef: mine[0].coef.clone(),
            rest,
        });
    }
    if pairs.len() < 2 {
        return None;
    }
    let mut used = vec![false; kids.len()];
    let mut new_terms = Vec::new();
    let sum = |a: Id, b: Id, minus: bool| -> Option<Build> {
        let second = if minus {
            p_mono(Rational::MINUS_ONE, vec![(Build::Class(b), one.clone())])
        } else {
            Build::Class(b)
        };
        p_add(eg, vec![Build::Class(a), second])
    };
    for i in 0..pairs.len() {
        for j in 0..pairs.len() {
            let (p, q) = (&pairs[i], &pairs[j]);
            if i == j || used[p.index] || used[q.index] || p.rest != q.rest {
                continue;
            }
            let plus = q.coef == p.coef;
            let minus = q.coef == p.coef.neg();
            if !plus && !minus {
                continue;
            }
            let (sin, cos) = (Func::Sin, Func::Cos);
            let result = match (p.fa, p.fb, q.fa, q.fb) {
                // cos a cos b with sin a sin b
                ((c1, a), (c2, b), (s1, a2), (s2, b2))
                    if c1 == cos && c2 == cos && s1 == sin && s2 == sin && {
                        let (x, y) = if a <= b { (a, b) } else { (b, a) };
                        let (u, v) = if a2 <= b2 { (a2, b2) } else { (b2, a2) };
                        (x, y) == (u, v)
                    } =>
                {
                    Some((cos, sum(a, b, plus)?))
                }
                // sin a cos b with cos a sin b: after sorting, the pair is (sin a, cos b) /
                // (sin b, cos a) — functions sort as Sin < Cos.
                ((f1, a), (f2, b), (g1, b2), (g2, a2))
                    if f1 == sin && f2 == cos && g1 == sin && g2 == cos && a == a2 && b == b2 =>
                {
                    // p = sin a cos b, q = cos a sin b
                    Some((sin, sum(a, b, minus)?))
                }
                _ => None,
            };
            if let Some((f, arg)) = result {
                used[p.index] = true;
                used[q.index] = true;
                let mut fs: Vec<(Build, Rational)> = p
                    .rest
                    .iter()
                    .map(|(b, e)| (Build::Class(*b), e.clone()))
                    .collect();
                fs.push((Build::Func(f, Box::new(arg)), one.clone()));
                new_terms.push(p_mono(p.coef.clone(), fs));
            }
        }
    }
    if new_terms.is_empty() {
        return None;
    }
    let mut terms = new_terms;
    for (i, &k) in kids.iter().enumerate() {
        if !used[i] {
            terms.push(Build::Class(k));
        }
    }
    p_add(eg, terms)
}

// ------------------------------------------------------------------ egg glue

/// One rule as an egg searcher and applier.
pub(crate) struct Rule {
    kind: Kind,
    views: SharedViews,
    /// The applier adds nothing once the e-graph holds more e-nodes than this, so one batch of
    /// applications cannot overshoot the runner's node limit by more than one proposal.
    node_cap: usize,
}

impl Searcher<Math, super::lang::Meta> for Rule {
    fn search_eclass_with_limit(
        &self,
        eg: &Graph,
        eclass: Id,
        limit: usize,
    ) -> Option<SearchMatches<'_, Math>> {
        if limit == 0 {
            return None;
        }
        let class = eg.find(eclass);
        let new = proposals(self.kind, eg, class, &self.views)
            .iter()
            .any(|b| lookup(eg, b) != Some(class));
        new.then(|| SearchMatches {
            eclass: class,
            substs: vec![Subst::default()],
            ast: None,
        })
    }

    fn vars(&self) -> Vec<Var> {
        vec![]
    }
}

impl Applier<Math, super::lang::Meta> for Rule {
    fn apply_one(
        &self,
        eg: &mut Graph,
        eclass: Id,
        _subst: &Subst,
        _ast: Option<&PatternAst<Math>>,
        _rule: Symbol,
    ) -> Vec<Id> {
        if eg.total_size() > self.node_cap {
            return vec![];
        }
        let class = eg.find(eclass);
        let mut changed = Vec::new();
        for b in proposals(self.kind, eg, class, &self.views) {
            let id = materialize(eg, &b);
            if eg.union(class, id) {
                changed.push(eg.find(class));
            }
        }
        changed
    }
}

/// The rule set, in the order the runner applies them.
pub(crate) fn rules(node_cap: usize, trig: bool) -> Vec<Rewrite<Math, super::lang::Meta>> {
    let mut kinds = vec![Kind::Cancel, Kind::Collect, Kind::Factor];
    if trig {
        kinds.extend([Kind::Pythagoras, Kind::AngleSum]);
    }
    let views = SharedViews::default();
    kinds
        .into_iter()
        .filter_map(|kind| {
            let rule = || Rule {
                kind,
                views: views.clone(),
                node_cap,
            };
            Rewrite::new(kind.name(), rule(), rule()).ok()
        })
        .collect()
}
