//! From lowered instructions to Rust tokens: function bodies, chunking through the work
//! buffer, the validity checks, the finiteness check and the sparse stores.

use crate::CodegenError;
use crate::options::{MathLib, Precision};
use crate::problem::{Mat, Problem};
use eom_sym::lower::{CodeOps, Inst, Lowered, Operand, Rhs, Rounding, lower};
use eom_sym::{Call, Func};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::str::FromStr;

mod bounded;
mod checks;
mod filter;
mod finite;
mod fold;
mod function;
mod ready;

pub(crate) use bounded::{BoundedCode, render_bounded};
pub(crate) use filter::{FilterCode, render_filter};
pub(crate) use function::{render_fn, sincos_item};
use ready::{Part, by_ready, latency};

/// Number formatting and arithmetic in the generated precision.
#[derive(Clone, Copy)]
pub(crate) struct Num {
    pub prec: Precision,
}

impl Num {
    /// The value as the generated code holds it.
    pub(crate) fn round(self, x: f64) -> f64 {
        match self.prec {
            Precision::F64 => x,
            Precision::F32 => x as f32 as f64,
        }
    }
    fn mul(self, a: f64, b: f64) -> f64 {
        match self.prec {
            Precision::F64 => a * b,
            Precision::F32 => ((a as f32) * (b as f32)) as f64,
        }
    }
    fn next_up(self, x: f64) -> f64 {
        match self.prec {
            Precision::F64 => x.next_up(),
            Precision::F32 => (x as f32).next_up() as f64,
        }
    }
    fn next_down(self, x: f64) -> f64 {
        match self.prec {
            Precision::F64 => x.next_down(),
            Precision::F32 => (x as f32).next_down() as f64,
        }
    }
    fn max_finite(self) -> f64 {
        match self.prec {
            Precision::F64 => f64::MAX,
            Precision::F32 => f32::MAX as f64,
        }
    }
    /// A non-negative literal with full precision (`{:?}` is the shortest text that reads
    /// back to the same value), unsuffixed.
    pub(crate) fn lit(self, x: f64, context: &str) -> Result<TokenStream, CodegenError> {
        let v = self.round(x);
        if !v.is_finite() {
            return Err(CodegenError::NonFiniteConstant {
                matrix: context.to_string(),
                value: x,
                precision: self.prec.type_name(),
            });
        }
        let text = match self.prec {
            Precision::F64 => format!("{:?}", v.abs()),
            Precision::F32 => format!("{:?}", (v as f32).abs()),
        };
        let l = Literal::from_str(&text)
            .map_err(|e| CodegenError::Syntax(format!("literal {text}: {e}")))?;
        Ok(if v < 0.0 || (v == 0.0 && v.is_sign_negative()) {
            quote!(-#l)
        } else {
            quote!(#l)
        })
    }

    /// The largest `M` with `tol · M ≤ av` in this precision (rounded products), capped at the
    /// largest finite value: `tol·|r| ≤ av ⇔ |r| ≤ M` exactly, for every `|r|`.
    fn bound(self, tol: f64, av: f64) -> f64 {
        let tol = self.round(tol);
        let mut m = self.round(av / tol);
        if !m.is_finite() {
            m = self.max_finite();
        }
        while m > 0.0 && self.mul(tol, m) > av {
            m = self.next_down(m);
        }
        loop {
            let up = self.next_up(m);
            if !up.is_finite() || up > self.max_finite() || self.mul(tol, up) > av {
                break;
            }
            m = up;
        }
        m
    }
}

/// Names and settings used while rendering one file.
pub(crate) struct Ctx<'a> {
    pub num: Num,
    pub math: MathLib,
    pub problem: &'a Problem,
    pub ty: Ident,
    /// Set when a function calls the module's `sincos` (which is then emitted).
    pub trig: std::cell::Cell<bool>,
}

impl Ctx<'_> {
    fn operand(&self, o: Operand) -> Result<TokenStream, CodegenError> {
        Ok(match o {
            Operand::Temp(t) => {
                let i = format_ident!("t{}", t);
                quote!(#i)
            }
            Operand::Param(k) => {
                let i = self.param_local(k);
                quote!(#i)
            }
            Operand::Lit(x) => self.num.lit(x, "expression")?,
        })
    }

    /// An operand in receiver position (`x.abs()`): literals need parentheses.
    fn receiver(&self, o: Operand) -> Result<TokenStream, CodegenError> {
        let t = self.operand(o)?;
        Ok(if matches!(o, Operand::Lit(_)) {
            quote!((#t))
        } else {
            t
        })
    }

    pub(crate) fn param_local(&self, k: u32) -> Ident {
        Ident::new(&self.problem.params[k as usize].local, Span::call_site())
    }

    fn libm(&self, f64_name: &str) -> TokenStream {
        let name = match self.num.prec {
            Precision::F64 => f64_name.to_string(),
            Precision::F32 => format!("{f64_name}f"),
        };
        let i = Ident::new(&name, Span::call_site());
        quote!(libm::#i)
    }

    /// When an operand's value is ready (parameters and literals at once).
    fn ready_of(&self, o: Operand, ready: &[u32]) -> u32 {
        match o {
            Operand::Temp(t) => ready.get(t as usize).copied().unwrap_or(0),
            _ => 0,
        }
    }

    /// The code of a right-hand side and when its value is ready, given the ready times of
    /// the temporaries so far. Sums and products are combined by ready time ([`by_ready`]).
    fn rhs(&self, rhs: &Rhs, ready: &[u32]) -> Result<(TokenStream, u32), CodegenError> {
        Ok(match rhs {
            Rhs::Sum { c0, terms } => {
                let mut parts: Vec<Part> = Vec::with_capacity(terms.len() + 1);
                if *c0 != 0.0 {
                    let mut p = Part::leaf(self.num.lit(c0.abs(), "sum")?, 0);
                    p.neg = *c0 < 0.0;
                    parts.push(p);
                }
                for (x, c) in terms {
                    let xv = self.operand(*x)?;
                    let mag = c.abs();
                    let mut p = if mag == 1.0 {
                        Part::leaf(xv, self.ready_of(*x, ready))
                    } else {
                        let l = self.num.lit(mag, "coefficient")?;
                        Part::leaf(quote!(#l * #xv), self.ready_of(*x, ready) + latency::ARITH)
                    };
                    p.neg = *c < 0.0;
                    parts.push(p);
                }
                let p = by_ready(parts, true);
                (p.code, p.ready)
            }
            Rhs::Prod { coef, num, den } => {
                let mut parts: Vec<Part> = Vec::with_capacity(num.len() + 1);
                if coef.abs() != 1.0 {
                    parts.push(Part::leaf(self.num.lit(coef.abs(), "coefficient")?, 0));
                }
                for x in num {
                    parts.push(Part::leaf(self.operand(*x)?, self.ready_of(*x, ready)));
                }
                let mut e = by_ready(parts, false);
                if !den.is_empty() {
                    let d: Vec<Part> = den
                        .iter()
                        .map(|x| Ok(Part::leaf(self.operand(*x)?, self.ready_of(*x, ready))))
                        .collect::<Result<_, CodegenError>>()?;
                    let d = by_ready(d, false);
                    // `a * b / c` is `(a * b) / c`: only a compound divisor needs parentheses.
                    let (n, dc) = (&e.code, &d.code);
                    let code = if d.compound {
                        quote!(#n / (#dc))
                    } else {
                        quote!(#n / #dc)
                    };
                    e = Part {
                        code,
                        ready: e.ready.max(d.ready) + latency::DIV,
                        compound: true,
                        neg: false,
                    };
                }
                let code = &e.code;
                if *coef < 0.0 {
                    (quote!(-#code), e.ready + latency::SIGN)
                } else {
                    (e.code, e.ready)
                }
            }
            call => {
                let lat = match call {
                    Rhs::Call1(Call::Func(Func::Abs), _) => latency::SIGN,
                    Rhs::Call1(Call::Sqrt, _) => latency::SQRT,
                    _ => latency::CALL,
                };
                let at = call
                    .operands()
                    .iter()
                    .map(|o| self.ready_of(*o, ready))
                    .max()
                    .unwrap_or(0);
                (self.call(call)?, at + lat)
            }
        })
    }

    /// The code of a function call.
    fn call(&self, rhs: &Rhs) -> Result<TokenStream, CodegenError> {
        Ok(match rhs {
            Rhs::Sum { .. } | Rhs::Prod { .. } => unreachable!("rendered by `rhs`"),
            // The module's `sincos`: inline polynomials for |x| ≤ π/4, the library beyond.
            Rhs::SinCos(x) => {
                self.trig.set(true);
                let xv = self.operand(*x)?;
                quote!(sincos(#xv))
            }
            Rhs::Call1(Call::Func(Func::Sin), x) => {
                self.trig.set(true);
                let xv = self.operand(*x)?;
                quote!(sincos(#xv).0)
            }
            Rhs::Call1(Call::Func(Func::Cos), x) => {
                self.trig.set(true);
                let xv = self.operand(*x)?;
                quote!(sincos(#xv).1)
            }
            Rhs::Call1(f, x) => {
                let xv = self.operand(*x)?;
                let rv = self.receiver(*x)?;
                match (f, self.math) {
                    (Call::Func(Func::Abs), _) => quote!(#rv.abs()),
                    (f, MathLib::Libm) => {
                        let func = self.libm(f.libm_name());
                        quote!(#func(#xv))
                    }
                    (f, MathLib::Std) => {
                        let m = Ident::new(f.std_method(), Span::call_site());
                        quote!(#rv.#m())
                    }
                }
            }
            Rhs::Call2(f, x, y) => {
                let (xv, yv, rv) = (self.operand(*x)?, self.operand(*y)?, self.receiver(*x)?);
                match self.math {
                    MathLib::Libm => {
                        let func = self.libm(f.libm_name());
                        quote!(#func(#xv, #yv))
                    }
                    MathLib::Std => {
                        let m = Ident::new(f.std_method(), Span::call_site());
                        quote!(#rv.#m(#yv))
                    }
                }
            }
        })
    }

    /// One `let`, recording when its value is ready in `ready` (indexed by temporary).
    fn inst(&self, inst: &Inst, ready: &mut Vec<u32>) -> Result<TokenStream, CodegenError> {
        let ty = &self.ty;
        let (rhs, at) = self.rhs(&inst.rhs, ready)?;
        for d in 0..inst.rhs.defs() {
            let t = (inst.def + d) as usize;
            if ready.len() <= t {
                ready.resize(t + 1, 0);
            }
            ready[t] = at;
        }
        Ok(if inst.rhs.defs() == 2 {
            let (s, c) = (
                format_ident!("t{}", inst.def),
                format_ident!("t{}", inst.def + 1),
            );
            quote!(let (#s, #c): (#ty, #ty) = #rhs;)
        } else {
            let t = format_ident!("t{}", inst.def);
            quote!(let #t: #ty = #rhs;)
        })
    }
}

/// A function to generate.
pub(crate) struct FnSpec {
    pub name: &'static str,
    pub mats: Vec<Mat>,
    /// The same kernel without the constant entries (`eval_ab_varying`).
    pub varying: &'static str,
    /// The `const fn` that writes the constant entries (`write_ab_constants`).
    pub constants: &'static str,
}

/// The lowered form of one function.
#[derive(Clone)]
pub(crate) struct FnPlan {
    pub name: &'static str,
    /// Writes only the entries that depend on the parameters (`eval_abcd_varying`): the
    /// constant ones are written once by the function named here (`write_abcd_constants`).
    pub constants_written_by: Option<&'static str>,
    pub mats: Vec<Mat>,
    pub lowered: Lowered,
    /// `(matrix, row, col, value, negated)`, in matrix order then column-major.
    pub outputs: Vec<(Mat, usize, usize, Operand, bool)>,
    /// Per check of the problem: `(value, others)`.
    pub checks: Vec<(Operand, Vec<Operand>)>,
}

/// Statistics of one generated function.
#[derive(Clone, Debug, PartialEq)]
pub struct FunctionStats {
    /// Function name (`eval_abcd`, …).
    pub name: String,
    /// Temporaries (`let`s of values).
    pub temporaries: usize,
    /// Chunk functions (1 when not chunked).
    pub chunks: usize,
    /// Values passed between chunks through the work buffer.
    pub work_values: usize,
    /// Operations computing the matrix entries (and the check expressions).
    pub ops: CodeOps,
    /// Comparisons of the validity checks.
    pub check_comparisons: usize,
    /// Distinct validity checks evaluated (identical checks are evaluated once).
    pub distinct_checks: usize,
    /// Entries stored per call.
    pub stores: usize,
    /// Estimated latency of the longest dependency chain from the parameters to an entry, in
    /// the renderer's latency units (about cycles: 3 for `+ − ·`, 13 for a division, 45 for
    /// a call), as the association of sums and products by ready time estimates it.
    pub critical_path: u32,
}

impl FunctionStats {
    /// Operations weighted by their throughput cost: 1 for `+ − ·`, 4 for a division, 6 for a
    /// square root, 20 for a call.
    pub fn weighted_ops(&self) -> u64 {
        let o = &self.ops;
        (o.add + o.mul + 4 * o.div + 6 * o.sqrt + 20 * o.func) as u64
    }

    /// The cost estimate that decides between simplified and original expressions:
    /// [`critical_path`](Self::critical_path) × [`weighted_ops`](Self::weighted_ops).
    ///
    /// Calls run back to back overlap only in part, so both the longest chain and the number
    /// of operations count, and in proportion: a change is judged by its relative effect on
    /// each. This is a heuristic fitted to two measurements (one driver, `bench/pydy`): the
    /// shimmy's simplified form has a chain 34 against 31 and 18 against 23 weighted
    /// operations, estimate 612 against 713, and takes 4.77 against 4.94 ns; the bicycle's
    /// has 131 against 122 and 319 against 336, estimate 41 789 against 40 992, and takes
    /// 80.4 against 68.2 ns.
    pub fn cost_estimate(&self) -> u64 {
        u64::from(self.critical_path) * self.weighted_ops()
    }
}

/// `arr[idx]`: entry `(i, j)` of matrix `m` in its column-major array.
fn entry(ctx: &Ctx, m: Mat, i: usize, j: usize) -> TokenStream {
    let arr = Ident::new(m.lower(), Span::call_site());
    let idx = Literal::usize_unsuffixed(i + j * ctx.problem.mats[m.index()].rows);
    quote!(#arr[#idx])
}

/// The array arguments `a: &mut [Real; A_LEN], …` of the matrices `mats`.
fn matrix_args(ctx: &Ctx, mats: &[Mat]) -> Vec<TokenStream> {
    let ty = &ctx.ty;
    mats.iter()
        .map(|m| {
            let arr = Ident::new(m.lower(), Span::call_site());
            let len = format_ident!("{}_LEN", m.lower().to_uppercase());
            quote!(#arr: &mut [#ty; #len])
        })
        .collect()
}

impl FnPlan {
    /// Does the function write entries that are the same for every parameter value?
    pub(crate) fn writes_constants(&self) -> bool {
        self.outputs.iter().any(|o| matches!(o.3, Operand::Lit(_)))
    }

    /// The same function without the constant entries, named `name`; `constants` writes them.
    pub(crate) fn without_constants(&self, name: &'static str, constants: &'static str) -> FnPlan {
        let mut p = self.clone();
        p.name = name;
        p.constants_written_by = Some(constants);
        p.outputs.retain(|o| !matches!(o.3, Operand::Lit(_)));
        p
    }
}

/// `const fn NAME(a, b, …)` writing the constant entries of `plan` (those
/// [`FnPlan::without_constants`] leaves out).
pub(crate) fn render_constants(
    ctx: &Ctx,
    plan: &FnPlan,
    name: &str,
    varying: &str,
) -> Result<TokenStream, CodegenError> {
    let mut stores = TokenStream::new();
    for &(m, i, j, o, neg) in &plan.outputs {
        if let Operand::Lit(x) = o {
            let e = entry(ctx, m, i, j);
            let v = ctx.num.lit(if neg { -x } else { x }, "constant entry")?;
            stores.extend(quote!(#e = #v;));
        }
    }
    let args = matrix_args(ctx, &plan.mats);
    let fname = Ident::new(name, Span::call_site());
    let which: Vec<&str> = plan.mats.iter().map(|m| m.variant()).collect();
    let which = which.join(", ");
    let doc = format!(
        " Write the entries of {which} that are the same for every parameter value: the ones [`{varying}`] leaves out. Call it once per set of arrays."
    );
    Ok(quote! {
        #[doc = #doc]
        pub const fn #fname(#(#args),*) {
            #stores
        }
    })
}

pub(crate) fn plan(spec: &FnSpec, problem: &Problem) -> Result<FnPlan, CodegenError> {
    let mut roots = Vec::new();
    let mut where_: Vec<(Mat, usize, usize)> = Vec::new();
    for &m in &spec.mats {
        for &(i, j, e) in &problem.mats[m.index()].entries {
            roots.push(e);
            where_.push((m, i, j));
        }
    }
    let n_out = roots.len();
    for c in &problem.checks {
        roots.push(c.value);
        roots.extend(&c.others);
    }
    let pivots: Vec<eom_sym::Expr> = problem
        .checks
        .iter()
        .filter(|c| c.pivot)
        .map(|c| c.value)
        .collect();
    let lowered = lower(&roots, &problem.param_exprs, &pivots, Rounding::Free)?;
    let outputs = where_
        .iter()
        .zip(&lowered.roots[..n_out])
        .map(|(&(m, i, j), &(o, neg))| (m, i, j, o, neg))
        .collect();
    let mut k = n_out;
    let mut checks = Vec::new();
    for c in &problem.checks {
        // The checks use magnitudes (and `v == 0`), so a sign does not matter.
        let v = lowered.roots[k].0;
        let o = lowered.roots[k + 1..k + 1 + c.others.len()]
            .iter()
            .map(|r| r.0)
            .collect();
        k += 1 + c.others.len();
        checks.push((v, o));
    }
    Ok(FnPlan {
        name: spec.name,
        constants_written_by: None,
        mats: spec.mats.clone(),
        lowered,
        outputs,
        checks,
    })
}

/// Split the instructions into chunks of at most `max` temporaries.
fn chunks(insts: &[Inst], max: usize) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut temps = 0;
    for (k, inst) in insts.iter().enumerate() {
        let d = inst.rhs.defs() as usize;
        if temps + d > max.max(2) && k > start {
            out.push(start..k);
            start = k;
            temps = 0;
        }
        temps += d;
    }
    if start < insts.len() || out.is_empty() {
        out.push(start..insts.len());
    }
    out
}

/// The rendered items of one function and its statistics.
pub(crate) struct Rendered {
    pub items: TokenStream,
    pub work_len: usize,
    pub stats: FunctionStats,
}

fn collect_params(ops: impl IntoIterator<Item = Operand>, used: &mut Vec<u32>) {
    for o in ops {
        if let Operand::Param(k) = o
            && !used.contains(&k)
        {
            used.push(k);
        }
    }
}

fn param_lets(ctx: &Ctx, mut used: Vec<u32>) -> TokenStream {
    used.sort_unstable();
    let ty = &ctx.ty;
    let lets = used.iter().map(|&k| {
        let l = ctx.param_local(k);
        let idx = Literal::usize_unsuffixed(k as usize);
        quote!(let #l: #ty = p[#idx];)
    });
    quote!(#(#lets)*)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `tol·|r| ≤ av ⇔ |r| ≤ bound`, exactly, around the bound and far from it.
    #[test]
    fn pivot_bound_is_exact() {
        for prec in [Precision::F64, Precision::F32] {
            let num = Num { prec };
            let tol = num.round(1e-4);
            for av in [1.0, 0.3, 7.77e-3, 123456.789, 1e-300, 3.5e300] {
                let av = num.round(av);
                let b = num.bound(tol, av);
                assert!(num.mul(tol, b) <= av, "{prec:?} {av}");
                let up = num.next_up(b);
                assert!(
                    !up.is_finite() || up > num.max_finite() || num.mul(tol, up) > av,
                    "{prec:?} {av}"
                );
                let mut r = b;
                for _ in 0..50 {
                    r = num.next_down(r);
                    assert!(num.mul(tol, r) <= av);
                }
            }
        }
    }

    fn parts(v: &[(&str, u32, bool)]) -> Vec<Part> {
        v.iter()
            .map(|&(name, ready, neg)| {
                let mut p = Part::leaf(name.parse().expect("ident"), ready);
                p.neg = neg;
                p
            })
            .collect()
    }

    #[test]
    fn equal_ready_times_give_balanced_trees() {
        let v = parts(&[
            ("a", 0, false),
            ("b", 0, false),
            ("c", 0, false),
            ("d", 0, false),
        ]);
        let p = by_ready(v, true);
        assert_eq!(p.code.to_string(), "a + b + (c + d)");
        assert_eq!(p.ready, 2 * latency::ARITH);
        let v = parts(&[("a", 0, false), ("b", 0, false)]);
        assert_eq!(by_ready(v, false).code.to_string(), "a * b");
    }

    #[test]
    fn late_values_are_combined_last() {
        // `d` comes out of a division: everything else is summed while it is computed.
        let v = parts(&[
            ("d", 20, false),
            ("a", 0, false),
            ("b", 3, false),
            ("c", 3, false),
        ]);
        let p = by_ready(v, true);
        assert_eq!(p.code.to_string(), "a + b + c + d");
        assert_eq!(p.ready, 20 + latency::ARITH);
    }

    #[test]
    fn subtracted_parts_keep_their_sign() {
        // a − b − c + d with a late `a`: (d − (b + c)) is formed first, `a` joins last.
        let v = parts(&[
            ("a", 9, false),
            ("b", 0, true),
            ("c", 0, true),
            ("d", 3, false),
        ]);
        let p = by_ready(v, true);
        assert_eq!(p.code.to_string(), "d - (b + c) + a");
        assert!(!p.neg);
        // Only subtracted parts: one negation at the root.
        let v = parts(&[("b", 0, true), ("c", 0, true)]);
        assert_eq!(by_ready(v, true).code.to_string(), "- (b + c)");
    }

    #[test]
    fn literals_are_unsuffixed_with_full_precision() {
        let num = Num {
            prec: Precision::F64,
        };
        assert_eq!(num.lit(0.1, "x").expect("finite").to_string(), "0.1");
        assert_eq!(
            num.lit(-2.5e-300, "x").expect("finite").to_string(),
            "- 2.5e-300"
        );
        assert_eq!(
            num.lit(1.0 / 3.0, "x").expect("finite").to_string(),
            "0.3333333333333333"
        );
        assert!(num.lit(f64::INFINITY, "x").is_err());
        let f32n = Num {
            prec: Precision::F32,
        };
        assert_eq!(f32n.lit(0.1, "x").expect("finite").to_string(), "0.1");
        assert!(f32n.lit(1e300, "x").is_err());
    }
}
