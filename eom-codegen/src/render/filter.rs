//! Straight-line code that computes, next to every value, a *magnitude* whose error factor is
//! known when the code is generated: the cheap first stage of the stability verdict.
//!
//! Every value `x̂` the code computes comes with a magnitude `m` (computed at run time) and a
//! relative factor `ρ` (a constant of the generator) such that
//!
//! * `|x̂| ≤ m` and `|x̂ − x| ≤ ρ·m`, `x` the exact value of the same formula at the same
//!   (exact) parameters.
//!
//! With `u = f64::EPSILON` (twice the unit roundoff, for slack), round to nearest, no
//! underflow (as for the running bound of `bounded.rs`), and rounding monotone (so
//! `fl(|â ∘ b̂|) ≤ fl(mₐ ∘ m_b)` whenever `|â ∘ b̂| ≤ mₐ ∘ m_b`):
//!
//! * a parameter: `m = |p|`, `ρ = 0`; a literal: `m = |c|`, `ρ = 0` when exact (a dyadic
//!   rational), `u` otherwise;
//! * `a ± b`: `m = mₐ + m_b`, `ρ = (u + max(ρₐ, ρ_b))(1 + u)`;
//! * `a·b`: `m = mₐ·m_b`, `ρ = (u + ρₐ + ρ_b + ρₐρ_b)(1 + u)` (a power of two scales exactly);
//! * `a/b`: only where `|b̂| ≥ m_b/2` (a run-time test; the divisor has lost at most one bit
//!   to cancellation), then `|b| ≥ |b̂|(1 − 2ρ_b)` and `m = mₐ/|b̂|`,
//!   `ρ = (1 + u)(u + ρₐ + 2(1 + ρₐ)ρ_b/(1 − 2ρ_b))`; where the test fails, the filter gives
//!   up;
//! * `sin x`, `cos x` (1-Lipschitz, the library's own rounding `2u|r|` as in `bounded.rs`):
//!   `m = |r̂|`, `ρ = 2u` for an exact argument, else `m = |r̂| + mₓ`,
//!   `ρ = max(ρₓ, 2u)(1 + u)`; `|x|`: `m = mₓ`, `ρ = ρₓ`.
//!
//! Each step follows from `|fl(y) − y| ≤ u|fl(y)|` and `y ≤ fl(y)(1 + u)` for `y ≥ 0`. The
//! bound of a result is then `ρ'·m` with `ρ' = 1.001ρ` (covering the rounding of that product
//! and of the generator's own computation of `ρ`): one multiplication per result, where the
//! running bound costs three to eight operations per operation. Other functions (`√`, `ln`,
//! `exp`, …) have no such form here: the program then has no filter.
//!
//! In lanes (`stability_many`: `LANES` points at once) the values are per point but the
//! magnitude is one `f64` per block: a parameter's is the largest `|p|` of the block, a
//! quotient's divides by the smallest `|b̂|` of the block, `sin` and `cos` take the largest
//! `|r̂|`. Every step above is monotone in the magnitudes (rounding is monotone), so the
//! block's magnitude is at least each point's, and the same `ρ` bounds each point's error:
//! the magnitudes cost one scalar operation per operation and block instead of one per
//! point, for bounds a little looser (the spread of the block's parameters). A point whose
//! value is NaN is left out of the block's largest and smallest (it is undecided by its own
//! NaN; every other point's values, and so their magnitudes, do not depend on it).
//!
//! The magnitudes are those of the a-priori analysis (Higham, *Accuracy and Stability of
//! Numerical Algorithms*, 2nd ed., §3.1), so where the formulas cancel the bound is far
//! above the running one and the filter leaves the point to it.

use super::Ctx;
use super::fold::Fold;
use crate::CodegenError;
use eom_sym::lower::{Lowered, Operand, Rhs};
use eom_sym::{Call, Func};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

/// `u`: twice the unit roundoff.
const U: f64 = f64::EPSILON;

/// A value, its magnitude (as code: an `f64`, in lanes the block's) and its relative factor.
#[derive(Clone)]
struct V {
    val: TokenStream,
    mag: TokenStream,
    rho: f64,
}

/// The rendered filter: `let` statements, the divisor tests (each a `bool` expression), and
/// the value and bound of each root.
pub(crate) struct FilterCode {
    pub(crate) body: TokenStream,
    pub(crate) tests: Vec<TokenStream>,
    pub(crate) roots: Vec<(TokenStream, TokenStream)>,
}

struct Renderer<'a> {
    ctx: &'a Ctx<'a>,
    /// Whether every value is an array of `LANES` points (`[f64; LANES]`, operations through
    /// the module's `l_*` helpers) instead of one `f64`.
    lanes: bool,
    out: TokenStream,
    tests: Vec<TokenStream>,
    fresh: usize,
    /// Per temporary: its relative factor (`None` before it is defined).
    rho: Vec<Option<f64>>,
}

fn add_rho(a: f64, b: f64) -> f64 {
    (U + a.max(b)) * (1.0 + U)
}

fn mul_rho(a: f64, b: f64) -> f64 {
    (U + a + b + a * b) * (1.0 + U)
}

impl Renderer<'_> {
    /// The type of a value.
    fn ty(&self) -> TokenStream {
        if self.lanes {
            quote!([f64; LANES])
        } else {
            quote!(f64)
        }
    }

    /// A literal (or literal code) as a value.
    fn lit(&self, x: TokenStream) -> TokenStream {
        if self.lanes { quote!([#x; LANES]) } else { x }
    }

    /// `a ∘ b` for `∘` one of `+ - * /`.
    fn op(&self, op: char, a: &TokenStream, b: &TokenStream) -> TokenStream {
        match (self.lanes, op) {
            (false, '+') => quote!(#a + #b),
            (false, '-') => quote!(#a - #b),
            (false, '*') => quote!(#a * #b),
            (false, _) => quote!(#a / #b),
            (true, '+') => quote!(l_add(#a, #b)),
            (true, '-') => quote!(l_sub(#a, #b)),
            (true, '*') => quote!(l_mul(#a, #b)),
            (true, _) => quote!(l_div(#a, #b)),
        }
    }

    /// `a ∘ b` on magnitudes: one `f64` per block of lanes (block magnitudes), so plain
    /// scalar arithmetic in both modes.
    fn mop(&self, op: char, a: &TokenStream, b: &TokenStream) -> TokenStream {
        match op {
            '+' => quote!(#a + #b),
            '*' => quote!(#a * #b),
            _ => quote!(#a / #b),
        }
    }

    /// The magnitude of a computed value: `|x|`, or in lanes the largest `|x|` of the block.
    fn mag_of(&self, a: &TokenStream) -> TokenStream {
        if self.lanes {
            quote!(l_max_abs(#a))
        } else {
            quote!(#a.abs())
        }
    }

    fn abs(&self, a: &TokenStream) -> TokenStream {
        if self.lanes {
            quote!(l_abs(#a))
        } else {
            quote!(#a.abs())
        }
    }

    fn neg(&self, a: &TokenStream) -> TokenStream {
        if self.lanes {
            quote!(l_neg(#a))
        } else {
            quote!((-#a))
        }
    }

    fn name(&mut self) -> (Ident, Ident) {
        self.fresh += 1;
        (
            format_ident!("x{}", self.fresh),
            format_ident!("m{}", self.fresh),
        )
    }

    /// Binds a value and its magnitude to fresh names.
    fn bind(&mut self, val: TokenStream, mag: TokenStream, rho: f64) -> V {
        let (v, m) = self.name();
        let ty = self.ty();
        self.out
            .extend(quote!(let #v: #ty = #val; let #m: f64 = #mag;));
        V {
            val: quote!(#v),
            mag: quote!(#m),
            rho,
        }
    }

    fn set(&mut self, t: u32, v: V) {
        let (ti, mi) = (format_ident!("t{}", t), format_ident!("m{}_", t));
        let (val, mag, ty) = (v.val, v.mag, self.ty());
        self.out
            .extend(quote!(let #ti: #ty = #val; let #mi: f64 = #mag;));
        self.rho[t as usize] = Some(v.rho);
    }

    /// One instruction; `false` when it has no form here.
    fn inst(&mut self, def: u32, rhs: &Rhs) -> Result<bool, CodegenError> {
        match rhs {
            Rhs::Sum { c0, terms } => {
                let v = self.sum(*c0, terms)?;
                self.set(def, v);
            }
            Rhs::Prod { coef, num, den } => {
                let v = self.prod(*coef, num, den)?;
                self.set(def, v);
            }
            Rhs::SinCos(x) => {
                let xv = self.operand(*x)?;
                let code = self.ctx.call(rhs)?;
                let code = if self.lanes {
                    let x = &xv.val;
                    quote!(l_sincos(#x))
                } else {
                    code
                };
                let (s, c) = (format_ident!("t{}", def), format_ident!("t{}", def + 1));
                let ty = self.ty();
                self.out.extend(quote!(let (#s, #c): (#ty, #ty) = #code;));
                for t in [def, def + 1] {
                    let (ti, mi) = (format_ident!("t{}", t), format_ident!("m{}_", t));
                    let ta = self.mag_of(&quote!(#ti));
                    let (mag, rho) = if xv.rho == 0.0 {
                        (ta, 2.0 * U)
                    } else {
                        (self.mop('+', &ta, &xv.mag), xv.rho.max(2.0 * U) * (1.0 + U))
                    };
                    self.out.extend(quote!(let #mi: f64 = #mag;));
                    self.rho[t as usize] = Some(rho);
                }
            }
            Rhs::Call1(Call::Func(Func::Abs), x) => {
                let xv = self.operand(*x)?;
                let code = self.abs(&xv.val);
                self.set(
                    def,
                    V {
                        val: code,
                        mag: xv.mag,
                        rho: xv.rho,
                    },
                );
            }
            Rhs::Call1(..) | Rhs::Call2(..) => return Ok(false),
        }
        Ok(true)
    }
}

impl Fold for Renderer<'_> {
    type V = V;

    fn operand(&self, o: Operand) -> Result<V, CodegenError> {
        Ok(match o {
            Operand::Temp(t) => {
                let (v, m) = (format_ident!("t{}", t), format_ident!("m{}_", t));
                V {
                    val: quote!(#v),
                    mag: quote!(#m),
                    rho: self.rho[t as usize].expect("defined before use"),
                }
            }
            Operand::Param(k) => {
                let p = self.ctx.param_local(k);
                V {
                    val: quote!(#p),
                    mag: self.mag_of(&quote!(#p)),
                    rho: 0.0,
                }
            }
            Operand::Lit(x) => {
                let exact = super::bounded::exact_literal(x);
                V {
                    val: self.lit(self.ctx.operand(o)?),
                    mag: self.ctx.num.lit(x.abs(), "literal")?,
                    rho: if exact { 0.0 } else { U },
                }
            }
        })
    }

    fn add(&mut self, a: &V, b: &V, negate: bool) -> Result<V, CodegenError> {
        let (av, bv, am, bm) = (&a.val, &b.val, &a.mag, &b.mag);
        let val = self.op(if negate { '-' } else { '+' }, av, bv);
        let mag = self.mop('+', am, bm);
        Ok(self.bind(val, mag, add_rho(a.rho, b.rho)))
    }

    fn mul(&mut self, a: &V, b: &V) -> Result<V, CodegenError> {
        let (av, bv, am, bm) = (&a.val, &b.val, &a.mag, &b.mag);
        let (val, mag) = (self.op('*', av, bv), self.mop('*', am, bm));
        Ok(self.bind(val, mag, mul_rho(a.rho, b.rho)))
    }

    /// `c·a` for a literal `c` (as `bounded.rs` renders it).
    fn scale(&mut self, a: &V, c: f64) -> Result<V, CodegenError> {
        if c == 1.0 {
            return Ok(a.clone());
        }
        let av = &a.val;
        if c == -1.0 {
            return Ok(V {
                val: self.neg(av),
                ..a.clone()
            });
        }
        let c_lit = self.ctx.num.lit(c.abs(), "coefficient")?;
        let lit = self.lit(c_lit.clone());
        let val = self.op('*', &lit, av);
        let val = if c < 0.0 { self.neg(&val) } else { val };
        let am = &a.mag;
        let rho = if c.abs().log2().fract() == 0.0 {
            a.rho
        } else {
            let rc = if super::bounded::exact_literal(c) {
                0.0
            } else {
                U
            };
            mul_rho(a.rho, rc)
        };
        let mag = self.mop('*', &c_lit, am);
        Ok(self.bind(val, mag, rho))
    }

    fn div(&mut self, a: &V, b: &V) -> Result<V, CodegenError> {
        let (av, bv, am, bm) = (&a.val, &b.val, &a.mag, &b.mag);
        if b.rho > 0.0 {
            self.tests.push(if self.lanes {
                quote!(l_ge_half(#bv, #bm))
            } else {
                quote!((#bv.abs() >= 0.5 * #bm))
            });
        }
        let (ra, rb) = (a.rho, b.rho);
        let rho = (1.0 + U) * (U + ra + 2.0 * (1.0 + ra) * rb / (1.0 - 2.0 * rb));
        // In lanes: the block's magnitude over the smallest `|b̂|` of the block.
        let den = if self.lanes {
            quote!(l_min_abs(#bv))
        } else {
            quote!(#bv.abs())
        };
        let (val, mag) = (self.op('/', av, bv), self.mop('/', am, &den));
        Ok(self.bind(val, mag, rho))
    }

    fn zero(&mut self) -> V {
        V {
            val: self.lit(quote!(0.0)),
            mag: quote!(0.0),
            rho: 0.0,
        }
    }
}

/// The filter of a lowered program (`f64` only), or `None` when the program calls a function
/// that has no magnitude form here.
pub(crate) fn render_filter(
    ctx: &Ctx,
    l: &Lowered,
    lanes: bool,
) -> Result<Option<FilterCode>, CodegenError> {
    let mut r = Renderer {
        ctx,
        lanes,
        out: TokenStream::new(),
        tests: Vec::new(),
        fresh: 0,
        rho: vec![None; l.n_temps as usize],
    };
    for inst in &l.insts {
        if !r.inst(inst.def, &inst.rhs)? {
            return Ok(None);
        }
    }
    let mut roots = Vec::with_capacity(l.roots.len());
    for &(op, negated) in &l.roots {
        let v = r.operand(op)?;
        let val = if negated { r.neg(&v.val) } else { v.val };
        let bound = if v.rho == 0.0 {
            r.lit(quote!(0.0))
        } else {
            let k = ctx.num.lit(v.rho * 1.001, "relative bound")?;
            let m = &v.mag;
            r.lit(quote!(#k * #m))
        };
        roots.push((val, bound));
    }
    Ok(Some(FilterCode {
        body: r.out,
        tests: r.tests,
        roots,
    }))
}

#[cfg(test)]
mod tests {
    use super::{U, add_rho, mul_rho};

    #[test]
    fn factors_grow_as_the_analysis_says() {
        assert_eq!(add_rho(0.0, 0.0), U * (1.0 + U));
        assert!(mul_rho(U, U) > 3.0 * U && mul_rho(U, U) < 3.01 * U);
    }
}
