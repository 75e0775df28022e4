//! The rewrites of [`Rounding::Free`](super::Rounding::Free): sums with merged terms and a
//! canonical sign, products as shared monomials with their powers, reciprocals and square
//! roots computed once.

use super::{Lowerer, OpKey, Operand, Rhs, Val};
use crate::pool::Id;
use crate::rational::Rational;

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

impl Lowerer<'_> {
    pub(super) fn sum(&mut self, c0: f64, terms: &[(Id, f64)]) -> Val {
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

    pub(super) fn product(&mut self, coef: f64, factors: &[(Id, Rational)]) -> Val {
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
    pub(super) fn pow(&mut self, x: Operand, k: i64) -> Operand {
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
}
