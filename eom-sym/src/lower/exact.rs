//! Sums and products of [`Rounding::Exact`](super::Rounding::Exact): the operations of
//! [`eval_generic`](crate::eval_generic) in its order, so that the program computes its
//! values bit for bit.

use super::{Lowerer, Operand, Rhs, Val};
use crate::pool::Id;
use crate::rational::Rational;

impl Lowerer<'_> {
    /// `c0 + Σ c·t` in the pool's term order (no terms merged, no sign changed).
    pub(super) fn exact_sum(&mut self, c0: f64, terms: &[(Id, f64)]) -> Val {
        let terms: Vec<(Operand, f64)> =
            terms.iter().map(|&(t, c)| (self.memo[&t].op, c)).collect();
        if c0 == 0.0 && terms.len() == 1 && terms[0].1 == 1.0 {
            return Val::of(terms[0].0);
        }
        let key = (
            c0.to_bits(),
            terms.iter().map(|t| (t.0.key(), t.1.to_bits())).collect(),
        );
        if let Some(o) = self.sum_memo.get(&key) {
            return Val::of(*o);
        }
        let o = self.push(Rhs::Sum { c0, terms });
        self.sum_memo.insert(key, o);
        Val::of(o)
    }

    /// `((coef·f₁)·f₂)·…` with `fᵢ = bᵢ^eᵢ` as [`eval_generic`](crate::eval_generic) computes
    /// it.
    pub(super) fn exact_product(&mut self, coef: f64, factors: &[(Id, Rational)]) -> Val {
        let num: Vec<Operand> = factors
            .iter()
            .map(|(b, e)| {
                let x = self.memo[b].op;
                self.exact_power(x, e)
            })
            .collect();
        if coef == 1.0 && num.len() == 1 {
            return Val::of(num[0]);
        }
        let key = (coef.to_bits(), num.iter().map(|o| o.key()).collect());
        if let Some(o) = self.prod_memo.get(&key) {
            return Val::of(*o);
        }
        let o = self.push(Rhs::Prod {
            coef,
            num,
            den: vec![],
        });
        self.prod_memo.insert(key, o);
        Val::of(o)
    }

    /// `x^e` as `Elementary::powi`, `sqrt`, `1/sqrt` or `powf` compute it for `f64`.
    fn exact_power(&mut self, x: Operand, e: &Rational) -> Operand {
        match e.as_small() {
            Some((n, 1)) => {
                // `f64::powi` takes an `i32` (`Elementary::powi` clamps).
                let n = n.clamp(i32::MIN as i64, i32::MAX as i64);
                let p = self.powi_chain(x, n.unsigned_abs());
                if n < 0 { self.recip(p) } else { p }
            }
            Some((1, 2)) => self.sqrt(x),
            Some((-1, 2)) => {
                let s = self.sqrt(x);
                self.recip(s)
            }
            _ => self.powf(x, e.to_f64()),
        }
    }

    /// `xⁿ` (n ≥ 1) with the operations of `f64::powi`: binary powering from the low bit,
    /// `r·a` where the bit is set and `a²` between, so that the values are `powi`'s bit for
    /// bit and partial powers shared by several products (`x²` of `x⁴` and `x⁶`) are
    /// computed once.
    fn powi_chain(&mut self, x: Operand, n: u64) -> Operand {
        if n == 0 {
            return Operand::Lit(1.0);
        }
        let (mut r, mut a, mut n) = (None, x, n);
        loop {
            if n & 1 == 1 {
                r = Some(match r {
                    None => a,
                    Some(r) => self.mul(r, a),
                });
            }
            n >>= 1;
            if n == 0 {
                break;
            }
            a = self.mul(a, a);
        }
        r.expect("n ≥ 1")
    }
}
