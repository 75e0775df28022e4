//! Clean-up passes over lowered code: common pairs of operands extracted
//! ([`Rounding::Free`](super::Rounding::Free)), copies dropped and temporaries numbered in
//! order of definition.

use super::{Inst, Lowered, OpKey, Operand, Rhs};
use hashbrown::HashMap;

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
pub(super) fn common_pairs(l: &mut Lowered) {
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
pub(super) fn renumber(l: &mut Lowered) {
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
        inst.rhs.for_each_operand(|o| resolve(o, &alias));
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
    let f = &|o: &mut Operand| {
        if let Operand::Temp(t) = o {
            *t = map[t];
        }
    };
    for inst in l.insts.iter_mut() {
        inst.def = map[&inst.def];
        inst.rhs.for_each_operand(f);
    }
    for r in l.roots.iter_mut() {
        f(&mut r.0);
    }
    l.n_temps = next;
}
