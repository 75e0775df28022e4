//! From lowered instructions to Rust tokens: function bodies, chunking through the work
//! buffer, the validity checks, the finiteness check and the sparse stores.

use crate::CodegenError;
use crate::lower::{CodeOps, Fn1, Fn2, Inst, Lowered, Operand, Rhs};
use crate::options::{MathLib, Precision};
use crate::problem::{Check, Mat, Problem};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;
use std::str::FromStr;

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

    fn rhs(&self, rhs: &Rhs) -> Result<TokenStream, CodegenError> {
        Ok(match rhs {
            // Balanced trees: Rust keeps the written order of floating-point operations, so a
            // chain `a + b + c + d` is three dependent additions; `(a + b) + (c + d)` is two.
            Rhs::Sum { c0, terms } => {
                let mut pos: Vec<TokenStream> = Vec::new();
                let mut neg: Vec<TokenStream> = Vec::new();
                if *c0 != 0.0 {
                    let l = self.num.lit(c0.abs(), "sum")?;
                    if *c0 > 0.0 { pos.push(l) } else { neg.push(l) }
                }
                for (x, c) in terms {
                    let xv = self.operand(*x)?;
                    let mag = c.abs();
                    let term = if mag == 1.0 {
                        xv
                    } else {
                        let l = self.num.lit(mag, "coefficient")?;
                        quote!(#l * #xv)
                    };
                    if *c > 0.0 {
                        pos.push(term)
                    } else {
                        neg.push(term)
                    }
                }
                match (pos.is_empty(), neg.is_empty()) {
                    (true, true) => quote!(0.0),
                    (false, true) => balanced(&pos, quote!(+), false),
                    (true, false) => {
                        let n = balanced(&neg, quote!(+), true);
                        quote!(-#n)
                    }
                    (false, false) => {
                        let p = balanced(&pos, quote!(+), false);
                        let n = balanced(&neg, quote!(+), true);
                        quote!(#p - #n)
                    }
                }
            }
            Rhs::Prod { coef, num, den } => {
                let mut factors: Vec<TokenStream> = Vec::new();
                if coef.abs() != 1.0 {
                    factors.push(self.num.lit(coef.abs(), "coefficient")?);
                }
                for x in num {
                    factors.push(self.operand(*x)?);
                }
                let mut e = if factors.is_empty() {
                    quote!(1.0)
                } else {
                    balanced(&factors, quote!(*), false)
                };
                if !den.is_empty() {
                    let d: Vec<TokenStream> = den
                        .iter()
                        .map(|x| self.operand(*x))
                        .collect::<Result<_, _>>()?;
                    let d = balanced(&d, quote!(*), true);
                    if factors.len() > 1 {
                        e = quote!((#e));
                    }
                    e = quote!(#e / #d);
                }
                if *coef < 0.0 { quote!(-#e) } else { e }
            }
            Rhs::Call1(f, x) => {
                let xv = self.operand(*x)?;
                let rv = self.receiver(*x)?;
                match (f, self.math) {
                    (Fn1::Abs, _) => quote!(#rv.abs()),
                    (f, MathLib::Libm) => {
                        let name = match f {
                            Fn1::Sqrt => "sqrt",
                            Fn1::Sin => "sin",
                            Fn1::Cos => "cos",
                            Fn1::Tan => "tan",
                            Fn1::Exp => "exp",
                            Fn1::Ln => "log",
                            Fn1::Abs => unreachable!("handled above"),
                        };
                        let func = self.libm(name);
                        quote!(#func(#xv))
                    }
                    (f, MathLib::Std) => {
                        let name = match f {
                            Fn1::Sqrt => "sqrt",
                            Fn1::Sin => "sin",
                            Fn1::Cos => "cos",
                            Fn1::Tan => "tan",
                            Fn1::Exp => "exp",
                            Fn1::Ln => "ln",
                            Fn1::Abs => unreachable!("handled above"),
                        };
                        let m = Ident::new(name, Span::call_site());
                        quote!(#rv.#m())
                    }
                }
            }
            Rhs::Call2(f, x, y) => {
                let (xv, yv, rv) = (self.operand(*x)?, self.operand(*y)?, self.receiver(*x)?);
                match (f, self.math) {
                    (Fn2::Pow, MathLib::Libm) => {
                        let func = self.libm("pow");
                        quote!(#func(#xv, #yv))
                    }
                    (Fn2::Atan2, MathLib::Libm) => {
                        let func = self.libm("atan2");
                        quote!(#func(#xv, #yv))
                    }
                    (Fn2::Pow, MathLib::Std) => quote!(#rv.powf(#yv)),
                    (Fn2::Atan2, MathLib::Std) => quote!(#rv.atan2(#yv)),
                }
            }
            Rhs::SinCos(x) => {
                let xv = self.operand(*x)?;
                let rv = self.receiver(*x)?;
                match self.math {
                    MathLib::Libm => {
                        let func = self.libm("sincos");
                        quote!(#func(#xv))
                    }
                    MathLib::Std => quote!(#rv.sin_cos()),
                }
            }
        })
    }

    fn inst(&self, inst: &Inst) -> Result<TokenStream, CodegenError> {
        let ty = &self.ty;
        let rhs = self.rhs(&inst.rhs)?;
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
}

/// The lowered form of one function.
pub(crate) struct FnPlan {
    pub name: &'static str,
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
    let pos: HashMap<u32, u32> = problem
        .param_index
        .iter()
        .enumerate()
        .map(|(k, &i)| (i, k as u32))
        .collect();
    let dag = crate::order::build(&roots, &pos)?;
    let pivots: Vec<eom_sym::Expr> = problem
        .checks
        .iter()
        .filter(|c| c.pivot)
        .map(|c| c.value)
        .collect();
    let lowered = crate::lower::lower(&dag, &roots, &pivots)?;
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

pub(crate) fn render_fn(
    ctx: &Ctx,
    plan: &FnPlan,
    max_temps: usize,
) -> Result<Rendered, CodegenError> {
    let ty = &ctx.ty;
    let insts = &plan.lowered.insts;
    let ranges = chunks(insts, max_temps);
    let chunked = ranges.len() > 1;
    let mut ops = CodeOps::default();
    for i in insts {
        ops.count(&i.rhs);
    }

    // Epilogue operands: check operands and outputs.
    let mut epi_ops: Vec<Operand> = plan.outputs.iter().map(|o| o.3).collect();
    for (v, o) in &plan.checks {
        epi_ops.push(*v);
        epi_ops.extend(o);
    }

    // Chunk of definition of every temporary, and the values that cross chunks.
    let n_chunks = ranges.len();
    let mut def_chunk = vec![0usize; plan.lowered.n_temps as usize];
    for (c, r) in ranges.iter().enumerate() {
        for inst in &insts[r.clone()] {
            for d in 0..inst.rhs.defs() {
                def_chunk[(inst.def + d) as usize] = c;
            }
        }
    }
    let mut slot: HashMap<u32, usize> = HashMap::new();
    let mut loads: Vec<Vec<u32>> = vec![Vec::new(); n_chunks + 1];
    if chunked {
        let mut mark = |t: u32, c: usize, loads: &mut Vec<Vec<u32>>| {
            if def_chunk[t as usize] < c {
                let n = slot.len();
                slot.entry(t).or_insert(n);
                if !loads[c].contains(&t) {
                    loads[c].push(t);
                }
            }
        };
        for (c, r) in ranges.iter().enumerate() {
            for inst in &insts[r.clone()] {
                for o in inst.rhs.operands() {
                    if let Operand::Temp(t) = o {
                        mark(t, c, &mut loads);
                    }
                }
            }
        }
        for o in &epi_ops {
            if let Operand::Temp(t) = o {
                mark(*t, n_chunks, &mut loads);
            }
        }
    }
    // Slots in temporary order, for readable code.
    let mut crossing: Vec<u32> = slot.keys().copied().collect();
    crossing.sort_unstable();
    let slot: HashMap<u32, usize> = crossing.iter().enumerate().map(|(k, &t)| (t, k)).collect();
    let work_len = if chunked { slot.len() } else { 0 };

    let mut items = TokenStream::new();
    let mut body = TokenStream::new();
    let load = |t: u32| {
        let i = format_ident!("t{}", t);
        let s = Literal::usize_unsuffixed(slot[&t]);
        quote!(let #i: #ty = work[#s];)
    };
    if chunked {
        for (c, r) in ranges.iter().enumerate() {
            let fname = format_ident!("{}_chunk{}", plan.name, c);
            let mut used = Vec::new();
            for inst in &insts[r.clone()] {
                collect_params(inst.rhs.operands(), &mut used);
            }
            let params = param_lets(ctx, used);
            let mut ld = loads[c].clone();
            ld.sort_unstable();
            let lds = ld.iter().map(|&t| load(t));
            let lets: Vec<TokenStream> = insts[r.clone()]
                .iter()
                .map(|i| ctx.inst(i))
                .collect::<Result<_, _>>()?;
            let mut stores = Vec::new();
            for inst in &insts[r.clone()] {
                for d in 0..inst.rhs.defs() {
                    let t = inst.def + d;
                    if let Some(&s) = slot.get(&t) {
                        let i = format_ident!("t{}", t);
                        let s = Literal::usize_unsuffixed(s);
                        stores.push(quote!(work[#s] = #i;));
                    }
                }
            }
            let doc = format!(" Part {} of {} of [`{}`].", c + 1, n_chunks, plan.name);
            items.extend(quote! {
                #[doc = #doc]
                #[inline(never)]
                fn #fname(p: &[#ty; N_PARAMS], work: &mut [#ty; WORK_LEN]) {
                    #params
                    #(#lds)*
                    #(#lets)*
                    #(#stores)*
                }
            });
            body.extend(quote!(#fname(p, work);));
        }
        let mut used = Vec::new();
        collect_params(epi_ops.iter().copied(), &mut used);
        body.extend(param_lets(ctx, used));
        let mut ld = loads[n_chunks].clone();
        ld.sort_unstable();
        for t in ld {
            body.extend(load(t));
        }
    } else {
        let mut used = Vec::new();
        for inst in insts {
            collect_params(inst.rhs.operands(), &mut used);
        }
        collect_params(epi_ops.iter().copied(), &mut used);
        body.extend(quote!(let _ = work;));
        body.extend(param_lets(ctx, used));
        for inst in insts {
            body.extend(ctx.inst(inst)?);
        }
    }

    // Validity checks: identical checks are evaluated once, then one branch on all of them.
    let checks = render_checks(ctx, &plan.checks, &ctx.problem.checks)?;
    let (check_comparisons, distinct_checks) = (checks.comparisons, checks.distinct);
    body.extend(checks.lets);
    let (oks, mags) = (&checks.ok, &checks.mag);
    if distinct_checks > 0 {
        let all: Vec<TokenStream> = (0..distinct_checks)
            .map(|k| {
                let i = format_ident!("ok{}", k);
                quote!(#i)
            })
            .collect();
        let all = join(&all, quote!(&));
        let all = if distinct_checks > 1 {
            quote!((#all))
        } else {
            all
        };
        body.extend(quote! {
            if !#all {
                if let Some(e) = failure(&[#(#oks),*], &[#(#mags),*], &[], &[]) {
                    return Err(e);
                }
            }
        });
    }

    // Finiteness: the sum of all computed entries is finite iff every entry is, unless it
    // overflows, which the slow path sorts out.
    let mut values: Vec<Operand> = Vec::new();
    let mut table = Vec::new();
    for &(m, i, j, o, _) in &plan.outputs {
        if matches!(o, Operand::Lit(_)) {
            continue;
        }
        let k = match values.iter().position(|v| *v == o) {
            Some(k) => k,
            None => {
                values.push(o);
                values.len() - 1
            }
        };
        let mv = Ident::new(m.variant(), Span::call_site());
        let (i, j, k) = (
            Literal::usize_unsuffixed(i),
            Literal::usize_unsuffixed(j),
            Literal::usize_unsuffixed(k),
        );
        table.push(quote!((Matrix::#mv, #i, #j, #k)));
    }
    if !values.is_empty() || !checks.mags.is_empty() {
        let vals: Vec<TokenStream> = values
            .iter()
            .map(|v| ctx.operand(*v))
            .collect::<Result<_, _>>()?;
        let mut summands = vals.clone();
        summands.extend(checks.mags.iter().map(|m| quote!(#m)));
        let sum = balanced_sum(&summands);
        let tname = format_ident!("{}_ENTRIES", plan.name.to_uppercase());
        let n = Literal::usize_unsuffixed(table.len());
        let doc = format!(
            " Computed entries of [`{}`]: matrix, row, column, index of the value.",
            plan.name
        );
        items.extend(quote! {
            #[doc = #doc]
            const #tname: [(Matrix, usize, usize, usize); #n] = [#(#table),*];
        });
        body.extend(quote! {
            let sum: #ty = #sum;
            if !sum.is_finite() {
                if let Some(e) = failure(&[#(#oks),*], &[#(#mags),*], &[#(#vals),*], &#tname) {
                    return Err(e);
                }
            }
        });
    }

    // Stores.
    let mut stores = 0;
    for &(m, i, j, o, neg) in &plan.outputs {
        let arr = Ident::new(m.lower(), Span::call_site());
        let idx = Literal::usize_unsuffixed(i + j * ctx.problem.mats[m.index()].rows);
        let v = ctx.operand(o)?;
        // A negation does not change finiteness, so the check above used the plain value.
        body.extend(if neg {
            quote!(#arr[#idx] = -#v;)
        } else {
            quote!(#arr[#idx] = #v;)
        });
        if neg {
            ops.neg += 1;
        }
        stores += 1;
    }
    body.extend(quote!(Ok(())));

    // Signature and documentation.
    let name = Ident::new(plan.name, Span::call_site());
    let args = plan.mats.iter().map(|m| {
        let arr = Ident::new(m.lower(), Span::call_site());
        let len = format_ident!("{}_LEN", m.lower().to_uppercase());
        quote!(#arr: &mut [#ty; #len])
    });
    let which: Vec<String> = plan
        .mats
        .iter()
        .map(|m| format!("`{}`", m.variant()))
        .collect();
    let doc = fn_doc(ctx.problem, plan, &which.join(", "), n_chunks, work_len);
    let docs = doc.iter().map(|l| quote!(#[doc = #l]));
    items.extend(quote! {
        #(#docs)*
        pub fn #name(p: &[#ty; N_PARAMS], #(#args,)* work: &mut [#ty; WORK_LEN]) -> Result<(), Error> {
            #body
        }
    });
    Ok(Rendered {
        items,
        work_len,
        stats: FunctionStats {
            name: plan.name.to_string(),
            temporaries: plan.lowered.n_temps as usize,
            chunks: n_chunks,
            work_values: work_len,
            ops,
            check_comparisons,
            distinct_checks,
            stores,
        },
    })
}

fn fn_doc(
    problem: &Problem,
    plan: &FnPlan,
    which: &str,
    n_chunks: usize,
    work_len: usize,
) -> Vec<String> {
    let mut d = vec![format!(
        " Evaluate {which} of `{}` at the parameter values `p` (order of [`PARAM_NAMES`]; see [`Params`] for names, nominal values and units).",
        problem.model
    )];
    d.push(String::new());
    d.push(" Matrices are column-major: entry `(i, j)` of a matrix with `r` rows is at `i + j·r`. Only the".into());
    d.push(" structural non-zeros are written (see the `*_NONZEROS` constants); the other entries are never".into());
    d.push(" touched, so pass arrays that were zeroed once.".into());
    d.push(String::new());
    if problem.checks.is_empty() {
        d.push(" The formulas hold for every parameter value where they are finite.".into());
    } else {
        d.push(format!(
            " The formulas come from an elimination with pivots chosen at the nominal point: they are valid in the region where the {} checks of [`CHECKS`] hold.",
            problem.checks.len()
        ));
    }
    d.push(String::new());
    d.push(" # Errors".into());
    d.push(String::new());
    d.push(
        " * [`Error::Validity`] (naming the first failing check) outside the validity region;"
            .into(),
    );
    d.push(
        " * [`Error::NonFinite`] (naming the entry) if an entry is a NaN or an infinity.".into(),
    );
    d.push(String::new());
    d.push(" On error the output arrays are left untouched.".into());
    if n_chunks > 1 {
        d.push(String::new());
        d.push(format!(
            " The evaluation is split into {n_chunks} functions of at most a few thousand temporaries; {work_len} values pass between them through `work`."
        ));
    } else {
        d.push(String::new());
        d.push(" `work` is not used by this model (its length is the largest any function of the module needs).".into());
    }
    let _ = &plan.mats;
    d
}

/// `v[0] op v[1] op …` as a balanced tree (`(a op b) op (c op d)`); `wrap` parenthesises a
/// result of more than one operand (for use after `-` or `/`).
fn balanced(v: &[TokenStream], op: TokenStream, wrap: bool) -> TokenStream {
    fn go(v: &[TokenStream], op: &TokenStream) -> TokenStream {
        match v.len() {
            0 => quote!(0.0),
            1 => v[0].clone(),
            2 => {
                let (a, b) = (&v[0], &v[1]);
                quote!(#a #op #b)
            }
            n => {
                let (l, r) = v.split_at(n.div_ceil(2));
                let (l, r) = (go(l, op), go(r, op));
                // Left-associative: only the right operand needs parentheses when compound.
                let r = if v.len() - n.div_ceil(2) > 1 {
                    quote!((#r))
                } else {
                    r
                };
                quote!(#l #op #r)
            }
        }
    }
    let t = go(v, &op);
    if wrap && v.len() > 1 { quote!((#t)) } else { t }
}

fn balanced_sum(v: &[TokenStream]) -> TokenStream {
    match v.len() {
        0 => quote!(0.0),
        1 => v[0].clone(),
        2 => {
            let (a, b) = (&v[0], &v[1]);
            quote!(#a + #b)
        }
        n => {
            let (l, r) = v.split_at(n / 2);
            let (l, r) = (balanced_sum(l), balanced_sum(r));
            let l = if n / 2 > 1 { quote!((#l)) } else { l };
            let r = if n - n / 2 > 1 { quote!((#r)) } else { r };
            quote!(#l + #r)
        }
    }
}

/// `c0 op c1 op …` for boolean conditions with a non-short-circuit `&` or `|`, parenthesising
/// the comparisons (which bind less tightly than `&` and `|`).
fn join(conds: &[TokenStream], op: TokenStream) -> TokenStream {
    if conds.len() == 1 {
        return conds[0].clone();
    }
    let wrapped = conds.iter().map(|c| {
        let text = c.to_string();
        if text.starts_with('!') || !text.contains(['<', '>', '=', '&', '|']) {
            c.clone()
        } else {
            quote!((#c))
        }
    });
    let mut out = TokenStream::new();
    for (k, c) in wrapped.enumerate() {
        if k > 0 {
            out.extend(op.clone());
        }
        out.extend(c);
    }
    out
}

/// The rendered validity checks.
struct Checks {
    /// `let` statements of the distinct checks.
    lets: TokenStream,
    /// Per check of the problem: its boolean (`okN` or `true`).
    ok: Vec<TokenStream>,
    /// Per check: the magnitude that must also be finite (`avN` or `0.0`). Finiteness is
    /// tested together with the entries (one sum), so the fast path has no `< ∞` per pivot.
    mag: Vec<TokenStream>,
    /// The distinct `avN`.
    mags: Vec<Ident>,
    comparisons: usize,
    distinct: usize,
}

/// The boolean of each distinct check (identical checks are evaluated once).
fn render_checks(
    ctx: &Ctx,
    checks: &[(Operand, Vec<Operand>)],
    specs: &[Check],
) -> Result<Checks, CodegenError> {
    let num = ctx.num;
    let pivot_tol = num.round(eom_sym::model::reduce::PIVOT_TOLERANCE);
    let rank_tol = num.round(eom_sym::model::reduce::RANK_TOLERANCE);
    let mut ts = TokenStream::new();
    let mut seen: HashMap<(bool, Vec<crate::lower::OpKey>), (TokenStream, TokenStream)> =
        HashMap::new();
    let mut per_check: Vec<TokenStream> = Vec::new();
    let mut per_mag: Vec<TokenStream> = Vec::new();
    let mut mags: Vec<Ident> = Vec::new();
    let mut comparisons = 0;
    let mut distinct = 0;
    for ((v, others), spec) in checks.iter().zip(specs) {
        let mut key = vec![v.key()];
        key.extend(others.iter().map(|o| o.key()));
        let key = (spec.pivot, key);
        if let Some((b, m)) = seen.get(&key) {
            per_check.push(b.clone());
            per_mag.push(m.clone());
            continue;
        }
        let mut conds: Vec<TokenStream> = Vec::new();
        let mut mag = quote!(0.0);
        let mut always = false;
        if spec.pivot {
            // |v| ≥ tol·max(|v|, |r|…) with v finite and the maximum positive
            //   ⇔ 0 < |v| < ∞ and, for every r, not (tol·|r| > |v|)  (a NaN r is ignored, as
            //   by `f64::max`; rounding is monotone, so tol·max = max of tol·).
            match v {
                Operand::Lit(x) => {
                    let av = num.round(*x).abs();
                    if !(av > 0.0 && av.is_finite()) {
                        conds.push(quote!(false));
                    } else {
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
                    }
                }
                _ => {
                    let vv = ctx.receiver(*v)?;
                    let av = format_ident!("av{}", distinct);
                    ts.extend(quote!(let #av = #vv.abs();));
                    mag = quote!(#av);
                    mags.push(av.clone());
                    let tl = num.lit(pivot_tol, "tolerance")?;
                    let mut lit_max: f64 = 0.0;
                    let mut seen_r: Vec<crate::lower::OpKey> = Vec::new();
                    for r in others {
                        if seen_r.contains(&r.key()) || r.key() == v.key() {
                            continue;
                        }
                        seen_r.push(r.key());
                        match r {
                            Operand::Lit(y) => {
                                lit_max = lit_max.max(num.mul(pivot_tol, num.round(*y).abs()))
                            }
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
                }
            }
        } else {
            // |v| ≤ tol·max|s| or v = 0  ⇔  v = 0 or, for some s, |v| ≤ tol·|s|.
            let tl = num.lit(rank_tol, "tolerance")?;
            let mut alts: Vec<TokenStream> = Vec::new();
            match v {
                Operand::Lit(x) if *x == 0.0 => always = true,
                Operand::Lit(x) => {
                    let av = num.round(*x).abs();
                    let al = num.lit(av, "negligible value")?;
                    for s in others {
                        match s {
                            Operand::Lit(y) => {
                                if av <= num.mul(rank_tol, num.round(*y).abs()) {
                                    always = true;
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
            if !always {
                if alts.is_empty() {
                    conds.push(quote!(false));
                } else {
                    conds.push(join(&alts, quote!(|)));
                }
            }
        }
        if always || conds.is_empty() {
            seen.insert(key, (quote!(true), mag.clone()));
            per_check.push(quote!(true));
            per_mag.push(mag);
            continue;
        }
        comparisons += conds.len();
        let ok = format_ident!("ok{}", distinct);
        distinct += 1;
        let all = join(&conds, quote!(&));
        ts.extend(quote!(let #ok: bool = #all;));
        seen.insert(key, (quote!(#ok), mag.clone()));
        per_check.push(quote!(#ok));
        per_mag.push(mag);
    }
    Ok(Checks {
        lets: ts,
        ok: per_check,
        mag: per_mag,
        mags,
        comparisons,
        distinct,
    })
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

    #[test]
    fn balanced_trees_keep_precedence() {
        let v: Vec<TokenStream> = ["a", "b", "c", "d", "e"]
            .iter()
            .map(|s| s.parse().expect("ident"))
            .collect();
        assert_eq!(
            balanced(&v, quote!(+), false).to_string(),
            "a + b + c + (d + e)"
        );
        assert_eq!(balanced(&v[..2], quote!(*), true).to_string(), "(a * b)");
        assert_eq!(balanced(&v[..1], quote!(*), true).to_string(), "a");
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
