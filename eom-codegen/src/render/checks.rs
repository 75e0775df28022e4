//! The validity checks of the symbolic reduction, evaluated once each.

use super::Ctx;
use super::ready::{join, latency};
use crate::CodegenError;
use crate::problem::Check;
use eom_sym::lower::{OpKey, Operand};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// The rendered validity checks.
pub(super) struct Checks {
    /// `let` statements of the distinct checks.
    pub(super) lets: TokenStream,
    /// Per check of the problem: its boolean (`okN` or `true`).
    pub(super) ok: Vec<TokenStream>,
    /// Per check: the magnitude that must also be finite (`avN` or `0.0`). Finiteness is
    /// tested together with the entries (one sum), so the fast path has no `< ∞` per pivot.
    pub(super) mag: Vec<TokenStream>,
    /// The distinct `avN`.
    pub(super) mags: Vec<Ident>,
    /// When each of `mags` is ready.
    pub(super) mag_ready: Vec<u32>,
    /// The value of each of `mags` (whose absolute value it is).
    pub(super) mag_ops: Vec<Operand>,
    pub(super) comparisons: usize,
    pub(super) distinct: usize,
}

/// The boolean of each distinct check (identical checks are evaluated once).
pub(super) fn render_checks(
    ctx: &Ctx,
    checks: &[(Operand, Vec<Operand>)],
    specs: &[Check],
    ready: &[u32],
) -> Result<Checks, CodegenError> {
    let mut out = Checks {
        lets: TokenStream::new(),
        ok: Vec::new(),
        mag: Vec::new(),
        mags: Vec::new(),
        mag_ready: Vec::new(),
        mag_ops: Vec::new(),
        comparisons: 0,
        distinct: 0,
    };
    let mut seen: HashMap<(bool, Vec<OpKey>), (TokenStream, TokenStream)> = HashMap::new();
    for ((v, others), spec) in checks.iter().zip(specs) {
        let mut key = vec![v.key()];
        key.extend(others.iter().map(|o| o.key()));
        let key = (spec.pivot, key);
        if let Some((b, m)) = seen.get(&key) {
            out.ok.push(b.clone());
            out.mag.push(m.clone());
            continue;
        }
        let (conds, mag) = if spec.pivot {
            pivot_conds(ctx, v, others, ready, &mut out)?
        } else {
            (negligible_conds(ctx, v, others)?, quote!(0.0))
        };
        // No condition: the check always holds.
        let ok = if conds.is_empty() {
            quote!(true)
        } else {
            out.comparisons += conds.len();
            let ok = format_ident!("ok{}", out.distinct);
            out.distinct += 1;
            let all = join(&conds, quote!(&));
            out.lets.extend(quote!(let #ok: bool = #all;));
            quote!(#ok)
        };
        seen.insert(key, (ok.clone(), mag.clone()));
        out.ok.push(ok);
        out.mag.push(mag);
    }
    Ok(out)
}

/// The conditions of a pivot check and the magnitude that must also be finite (recorded in
/// `out` when it is computed):
///
/// |v| ≥ tol·max(|v|, |r|…) with v finite and the maximum positive
///   ⇔ 0 < |v| < ∞ and, for every r, not (tol·|r| > |v|)  (a NaN r is ignored, as by
///   `f64::max`; rounding is monotone, so tol·max = max of tol·).
fn pivot_conds(
    ctx: &Ctx,
    v: &Operand,
    others: &[Operand],
    ready: &[u32],
    out: &mut Checks,
) -> Result<(Vec<TokenStream>, TokenStream), CodegenError> {
    let num = ctx.num;
    let pivot_tol = num.round(eom_model::reduce::PIVOT_TOLERANCE);
    let mut conds: Vec<TokenStream> = Vec::new();
    if let Operand::Lit(x) = v {
        let av = num.round(*x).abs();
        if !(av > 0.0 && av.is_finite()) {
            return Ok((vec![quote!(false)], quote!(0.0)));
        }
        let b = num.bound(pivot_tol, av);
        let bl = num.lit(b, "pivot bound")?;
        for r in others {
            match r {
                Operand::Lit(y) => {
                    if num.mul(pivot_tol, num.round(*y).abs()) > av {
                        conds.push(quote!(false));
                    }
                }
                _ => {
                    let rv = ctx.receiver(*r)?;
                    conds.push(quote!(!(#rv.abs() > #bl)));
                }
            }
        }
        return Ok((conds, quote!(0.0)));
    }
    let vv = ctx.receiver(*v)?;
    let av = format_ident!("av{}", out.distinct);
    out.lets.extend(quote!(let #av = #vv.abs();));
    out.mags.push(av.clone());
    out.mag_ready.push(ctx.ready_of(*v, ready) + latency::SIGN);
    out.mag_ops.push(*v);
    let tl = num.lit(pivot_tol, "tolerance")?;
    let mut lit_max: f64 = 0.0;
    let mut seen_r: Vec<OpKey> = Vec::new();
    for r in others {
        if seen_r.contains(&r.key()) || r.key() == v.key() {
            continue;
        }
        seen_r.push(r.key());
        match r {
            Operand::Lit(y) => lit_max = lit_max.max(num.mul(pivot_tol, num.round(*y).abs())),
            _ => {
                let rv = ctx.receiver(*r)?;
                conds.push(quote!(!(#tl * #rv.abs() > #av)));
            }
        }
    }
    // `av > 0` (the maximum is positive), implied by `av ≥ bound` when the bound is.
    if lit_max > 0.0 {
        let l = num.lit(lit_max, "pivot bound")?;
        conds.insert(0, quote!(#av >= #l));
    } else {
        conds.insert(0, quote!(#av > 0.0));
    }
    Ok((conds, quote!(#av)))
}

/// The condition of a negligibility check (none when it always holds):
/// |v| ≤ tol·max|s| or v = 0  ⇔  v = 0 or, for some s, |v| ≤ tol·|s|.
fn negligible_conds(
    ctx: &Ctx,
    v: &Operand,
    others: &[Operand],
) -> Result<Vec<TokenStream>, CodegenError> {
    let num = ctx.num;
    let rank_tol = num.round(eom_model::reduce::RANK_TOLERANCE);
    let tl = num.lit(rank_tol, "tolerance")?;
    let mut alts: Vec<TokenStream> = Vec::new();
    match v {
        Operand::Lit(x) if *x == 0.0 => return Ok(Vec::new()),
        Operand::Lit(x) => {
            let av = num.round(*x).abs();
            let al = num.lit(av, "negligible value")?;
            for s in others {
                match s {
                    Operand::Lit(y) => {
                        if av <= num.mul(rank_tol, num.round(*y).abs()) {
                            return Ok(Vec::new());
                        }
                    }
                    _ => {
                        let sv = ctx.receiver(*s)?;
                        alts.push(quote!(#al <= #tl * #sv.abs()));
                    }
                }
            }
        }
        _ => {
            let vv = ctx.receiver(*v)?;
            let vo = ctx.operand(*v)?;
            alts.push(quote!(#vo == 0.0));
            let mut lit_max: f64 = 0.0;
            for s in others {
                match s {
                    Operand::Lit(y) => {
                        lit_max = lit_max.max(num.mul(rank_tol, num.round(*y).abs()))
                    }
                    _ => {
                        let sv = ctx.receiver(*s)?;
                        alts.push(quote!(#vv.abs() <= #tl * #sv.abs()));
                    }
                }
            }
            if lit_max > 0.0 {
                let l = num.lit(lit_max, "negligible bound")?;
                alts.push(quote!(#vv.abs() <= #l));
            }
        }
    }
    Ok(vec![if alts.is_empty() {
        quote!(false)
    } else {
        join(&alts, quote!(|))
    }])
}
