//! From lowered instructions to Rust tokens: function bodies, chunking through the work
//! buffer, the validity checks, the finiteness check and the sparse stores.

use crate::CodegenError;
use crate::options::{MathLib, Precision};
use crate::problem::{Check, Mat, Problem};
use eom_sym::lower::{CodeOps, Inst, Lowered, Operand, Rhs, Rounding, lower};
use eom_sym::{Call, Func};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::{HashMap, HashSet};
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
    // Estimated ready time of every temporary (values from the work buffer count as ready).
    let mut ready: Vec<u32> = vec![0; plan.lowered.n_temps as usize];
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
            let mut lets: Vec<TokenStream> = Vec::with_capacity(r.len());
            for i in &insts[r.clone()] {
                lets.push(ctx.inst(i, &mut ready)?);
            }
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
            body.extend(ctx.inst(inst, &mut ready)?);
        }
    }

    // Validity checks: identical checks are evaluated once, then one branch on all of them.
    let checks = render_checks(ctx, &plan.checks, &ctx.problem.checks, &ready)?;
    let (check_comparisons, distinct_checks) = (checks.comparisons, checks.distinct);
    body.extend(checks.lets);
    let (oks, mags) = (&checks.ok, &checks.mag);

    // Finiteness of the entries and pivots. The distinct computed entries, for the slow path
    // that names the failing one:
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
        // Row and column are `u16` in the generated `Error`.
        let row = crate::index_fits(i, u16::MAX, || format!("row of {}", m.variant()))?;
        let col = crate::index_fits(j, u16::MAX, || format!("column of {}", m.variant()))?;
        let (i, j, k) = (
            Literal::u16_unsuffixed(row),
            Literal::u16_unsuffixed(col),
            Literal::usize_unsuffixed(k),
        );
        table.push(quote!((Matrix::#mv, #i, #j, #k)));
    }
    // The slow path (a separate cold function, so the fast one needs no stack frame for the
    // failure report) computes the same values, then finds the first failure in the
    // interpreter's order, or stores the entries if there is none (the sum overflowed).
    let mut slow = body.clone();
    let slow_name = format_ident!("{}_checked", plan.name);
    let mat_args: Vec<Ident> = plan
        .mats
        .iter()
        .map(|m| Ident::new(m.lower(), Span::call_site()))
        .collect();
    // The fast path adds up only the values that no other tested value depends on through
    // operations that keep a NaN or an infinity (see [`finiteness_sinks`]), and tests the sum:
    // it is finite iff they all are, unless it overflows by itself, which the slow path sorts
    // out.
    let mut musts: Vec<Operand> = values.clone();
    musts.extend(&checks.mag_ops);
    // Finiteness by magnitude: bounded parameters and denominators bounded away from zero
    // keep every value finite, and these tests come early (no entry is waited for). Each
    // parameter costs two operations, so this pays for small functions only, whose time is
    // the latency of their longest chain (measured: shimmy 5.88 → 5.60 ns per call; the
    // bicycle's 27 parameters make it 74.6 → 81 ns, so it tests its sinks).
    let bounds =
        magnitude_bounds(insts, &musts).filter(|b| !chunked && b.params.len() + b.dens.len() <= 12);
    let mut fast_note: Option<String> = None;
    let finite = match (ctx.num.prec, bounds) {
        (Precision::F64, Some(b)) => {
            fast_note = Some(format!(
                " Fast path: where the magnitudes of the even- and of the odd-numbered parameters each sum to less than {:e} and every divisor has magnitude at least {:e}, every value is provably finite and no entry is tested; elsewhere the same values are computed again with every check and entry tested one by one (about twice the time).",
                b.hi,
                1.0 / b.hi
            ));
            let hi = ctx.num.lit(b.hi, "parameter bound")?;
            let lo = ctx.num.lit(1.0 / b.hi, "denominator bound")?;
            let mut tests: Vec<TokenStream> = Vec::new();
            if !b.params.is_empty() {
                // Two running sums, of the even- and of the odd-numbered parameters, in
                // index order, each tested: the same operations on consecutive array
                // elements, which LLVM turns into packed `andpd`/`addpd` on pairs and one
                // `cmpltpd` (shimmy, same driver: 5.26 → 4.95 ns per call against one tree
                // over all of them). A test per lane rather than of their sum is two
                // instructions fewer; with the grouped powers of the lowering (`m·(l x)²`)
                // the shimmy's varying kernel went 4.49 → 4.30 ns, though neither alone
                // measured faster by hand. Each lane below the bound bounds each parameter.
                let mut params = b.params.clone();
                params.sort_unstable();
                let mut lanes: [Vec<TokenStream>; 2] = [Vec::new(), Vec::new()];
                for &k in &params {
                    let l = ctx.param_local(k);
                    lanes[k as usize % 2].push(quote!(#l.abs()));
                }
                for (n, lane) in lanes.iter().enumerate() {
                    if lane.is_empty() {
                        continue;
                    }
                    let size = format_ident!("size{}", n);
                    let sum = join(lane, quote!(+));
                    body.extend(quote!(let #size: #ty = #sum;));
                    tests.push(quote!(#size < #hi));
                }
            }
            for d in &b.dens {
                let dv = ctx.receiver(*d)?;
                tests.push(quote!(#dv.abs() >= #lo));
            }
            for x in &b.roots {
                let xv = ctx.operand(*x)?;
                tests.push(quote!(#xv >= 0.0));
            }
            (!tests.is_empty()).then(|| {
                let all = join(&tests, quote!(&));
                quote!((#all))
            })
        }
        _ => {
            let sinks = finiteness_sinks(insts, &musts);
            let mut summands: Vec<Part> = Vec::new();
            for (k, v) in values.iter().enumerate() {
                if sinks[k] {
                    summands.push(Part::leaf(ctx.operand(*v)?, ctx.ready_of(*v, &ready)));
                }
            }
            for (k, (m, &r)) in checks.mags.iter().zip(&checks.mag_ready).enumerate() {
                if sinks[values.len() + k] {
                    summands.push(Part::leaf(quote!(#m), r));
                }
            }
            // Combined by ready time: the values that come last (after the slowest division or
            // call) join in the last additions, so the test adds little to the critical path.
            if summands.is_empty() {
                None
            } else {
                let sum = by_ready(summands, true).code;
                body.extend(quote!(let sum: #ty = #sum;));
                Some(quote!(sum.is_finite()))
            }
        }
    };
    // One branch for the validity checks and the finiteness, to the slow path that finds the
    // first failure in the interpreter's order.
    let mut conds: Vec<TokenStream> = (0..distinct_checks)
        .map(|k| {
            let i = format_ident!("ok{}", k);
            quote!(#i)
        })
        .collect();
    conds.extend(finite);
    let conds_empty = conds.is_empty();
    if !conds_empty {
        let all = join(&conds, quote!(&));
        let all = if conds.len() > 1 { quote!((#all)) } else { all };
        let vals: Vec<TokenStream> = values
            .iter()
            .map(|v| ctx.operand(*v))
            .collect::<Result<_, _>>()?;
        let tname = format_ident!("{}_ENTRIES", plan.name.to_uppercase());
        let n = Literal::usize_unsuffixed(table.len());
        let doc = format!(
            " Computed entries of [`{}`]: matrix, row, column, index of the value.",
            plan.name
        );
        items.extend(quote! {
            #[doc = #doc]
            const #tname: [(Matrix, u16, u16, usize); #n] = [#(#table),*];
        });
        slow.extend(quote! {
            if let Some(e) = failure(&[#(#oks),*], &[#(#mags),*], &[#(#vals),*], &#tname) {
                return Err(e);
            }
        });
        body.extend(quote! {
            if !#all {
                return #slow_name(p, #(#mat_args,)* work);
            }
        });
    }

    // Stores.
    let mut stores = 0;
    for &(m, i, j, o, neg) in &plan.outputs {
        let e = entry(ctx, m, i, j);
        let v = ctx.operand(o)?;
        // A negation does not change finiteness, so the check above used the plain value.
        let store = if neg {
            quote!(#e = -#v;)
        } else {
            quote!(#e = #v;)
        };
        slow.extend(store.clone());
        body.extend(store);
        if neg {
            ops.neg += 1;
        }
        stores += 1;
    }
    body.extend(quote!(Ok(())));
    slow.extend(quote!(Ok(())));

    // Signature and documentation.
    let name = Ident::new(plan.name, Span::call_site());
    let args = matrix_args(ctx, &plan.mats);
    let which: Vec<String> = plan
        .mats
        .iter()
        .map(|m| format!("`{}`", m.variant()))
        .collect();
    let mut doc = fn_doc(ctx.problem, plan, &which.join(", "), n_chunks, work_len);
    if let Some(constants) = plan.constants_written_by {
        doc.push(String::new());
        let state_space = if plan.name == "eval_abcd_varying" {
            "; [`StateSpace`] works this way"
        } else {
            ""
        };
        doc.push(format!(" Only the entries that depend on the parameters are written: the constant ones (a `1` of a kinematic row, a sign) are written once by [`{constants}`]. For callers that keep their arrays between calls, as a controller does every tick{state_space}."));
    }
    if let Some(n) = fast_note {
        doc.push(String::new());
        doc.push(n);
    }
    let docs = doc.iter().map(|l| quote!(#[doc = #l]));
    if !conds_empty {
        let doc = format!(
            " [`{}`] with every check and entry tested one by one: the slow path it takes when its fast test fails.",
            plan.name
        );
        items.extend(quote! {
            #[doc = #doc]
            #[cold]
            #[inline(never)]
            fn #slow_name(p: &[#ty; N_PARAMS], #(#args,)* work: &mut [#ty; WORK_LEN]) -> Result<(), Error> {
                #slow
            }
        });
    }
    items.extend(quote! {
        #(#docs)*
        pub fn #name(p: &[#ty; N_PARAMS], #(#args,)* work: &mut [#ty; WORK_LEN]) -> Result<(), Error> {
            #body
        }
    });
    let critical_path = plan
        .outputs
        .iter()
        .map(|o| ctx.ready_of(o.3, &ready))
        .max()
        .unwrap_or(0);
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
            critical_path,
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

/// The module's `sincos`. Model angles are small (a steer-axis tilt, a caster angle), and a
/// call of the math library costs more than the polynomial: every register live across the
/// call is spilled, and the call's latency stalls the values that wait on it. So for
/// |x| ≤ π/4 the Taylor polynomials run inline — truncated where the next term is below a
/// tenth of an ulp (`f64`: sine to x¹⁷, cosine to x¹⁶; `f32`: x⁹ and x¹⁰), in Horner form, so
/// within about an ulp of the library — and beyond it (and for NaN and ±∞) the library.
pub(crate) fn sincos_item(ctx: &Ctx) -> Result<TokenStream, CodegenError> {
    let ty = &ctx.ty;
    let (sin_top, cos_top) = match ctx.num.prec {
        Precision::F64 => (17u32, 16u32),
        Precision::F32 => (9, 10),
    };
    // (−1)^j / n! for n = 2j + 1 (sine) or 2j (cosine), as literals of this precision.
    let coef = |n: u32| -> f64 {
        let f: f64 = (1..=n).map(f64::from).product();
        if (n / 2) % 2 == 1 { -1.0 / f } else { 1.0 / f }
    };
    let horner = |degrees: Vec<u32>| -> Result<TokenStream, CodegenError> {
        let mut it = degrees.iter().rev();
        let top = ctx
            .num
            .lit(coef(*it.next().expect("terms")), "sincos coefficient")?;
        let mut acc = top;
        for &n in it {
            let c = ctx.num.lit(coef(n), "sincos coefficient")?;
            acc = quote!(#c + z * (#acc));
        }
        Ok(acc)
    };
    let sin_poly = horner((3..=sin_top).step_by(2).collect())?;
    let cos_poly = horner((2..=cos_top).step_by(2).collect())?;
    let bound = ctx.num.lit(std::f64::consts::FRAC_PI_4, "π/4")?;
    let library = match ctx.math {
        MathLib::Libm => {
            let f = ctx.libm("sincos");
            quote!(#f(x))
        }
        MathLib::Std => quote!(x.sin_cos()),
    };
    Ok(quote! {
        /// `(sin x, cos x)` as the evaluation functions compute them: inline Taylor
        /// polynomials for |x| ≤ π/4 (within about an ulp of the math library, without the
        /// cost of a call), the math library beyond.
        #[inline(always)]
        pub fn sincos(x: #ty) -> (#ty, #ty) {
            if x.abs() <= #bound {
                let z = x * x;
                (x + x * z * (#sin_poly), 1.0 + z * (#cos_poly))
            } else {
                #library
            }
        }
    })
}

/// What the fast path tests instead of the entries when every value's magnitude can be
/// bounded (see [`magnitude_bounds`]).
struct Bounds {
    /// Bound on each parameter's magnitude (a power of two), tested on two partial sums.
    hi: f64,
    /// Parameters (positions) the function reads.
    params: Vec<u32>,
    /// Divisors, each tested `|d| ≥ 1/hi`.
    dens: Vec<Operand>,
    /// Square-root arguments, each tested `x ≥ 0`.
    roots: Vec<Operand>,
}

/// A finiteness test that waits for no entry, when one exists (`f64` only).
///
/// If every parameter has |p| < 2^M and every divisor |d| ≥ 2^−M (and every square-root
/// argument is ≥ 0, NaN failing every test), then by induction over the instructions every
/// value has |v| ≤ 2^E(v), with E(param) = M, E(c·Π x / Π d) = log₂|c| + Σ E(x) + M·#d,
/// E(c₀ + Σ cᵢ xᵢ) = max(log₂|c₀|, log₂|cᵢ| + E(xᵢ)) + log₂(terms + 1), E(√x) = E(x)/2 and
/// E(sin), E(cos) = 0. When the largest E stays below 1000 (far from 1024; rounding adds
/// at most a few ulps per operation), no value overflows, no divisor is zero and no NaN can
/// arise, so every entry and pivot is finite without testing them — and the tests read
/// parameters and divisors only, which are ready long before the entries. The largest M
/// (from 60 down to 10) that passes is used; `None` (test the entries instead) when none
/// does, or the function calls anything else (`tan`, `exp`, `ln`, powers, `atan2`).
fn magnitude_bounds(insts: &[Inst], musts: &[Operand]) -> Option<Bounds> {
    let mut params: Vec<u32> = Vec::new();
    let mut dens: Vec<Operand> = Vec::new();
    let mut roots: Vec<Operand> = Vec::new();
    let note_param = |o: &Operand, params: &mut Vec<u32>| {
        if let Operand::Param(k) = o
            && !params.contains(k)
        {
            params.push(*k);
        }
    };
    for inst in insts {
        match &inst.rhs {
            Rhs::Sum { .. } | Rhs::SinCos(_) => {}
            Rhs::Prod { den, .. } => {
                for d in den {
                    if !matches!(d, Operand::Lit(_)) && !dens.contains(d) {
                        dens.push(*d);
                    }
                }
            }
            Rhs::Call1(Call::Sqrt, x) => {
                if !matches!(x, Operand::Lit(_)) && !roots.contains(x) {
                    roots.push(*x);
                }
            }
            Rhs::Call1(Call::Func(Func::Sin | Func::Cos | Func::Abs), _) => {}
            _ => return None,
        }
        for o in inst.rhs.operands() {
            note_param(&o, &mut params);
        }
    }
    for o in musts {
        note_param(o, &mut params);
    }
    params.sort_unstable();
    let log2 = |c: f64| if c == 0.0 { -1100.0 } else { c.abs().log2() };
    let fits = |m: f64| -> bool {
        let mut e: Vec<f64> = Vec::new();
        let of = |o: &Operand, e: &Vec<f64>| match o {
            Operand::Temp(t) => e.get(*t as usize).copied().unwrap_or(f64::INFINITY),
            Operand::Param(_) => m,
            Operand::Lit(c) => log2(*c),
        };
        for inst in insts {
            let v = match &inst.rhs {
                Rhs::Sum { c0, terms } => {
                    let top = terms
                        .iter()
                        .map(|(x, c)| log2(*c) + of(x, &e))
                        .fold(log2(*c0), f64::max);
                    top + ((terms.len() + 1) as f64).log2()
                }
                Rhs::Prod { coef, num, den } => {
                    log2(*coef) + num.iter().map(|x| of(x, &e)).sum::<f64>() + m * den.len() as f64
                }
                Rhs::Call1(Call::Sqrt, x) => of(x, &e) / 2.0 + 1.0,
                Rhs::Call1(Call::Func(Func::Abs), x) => of(x, &e),
                Rhs::Call1(Call::Func(Func::Sin | Func::Cos), _) | Rhs::SinCos(_) => 0.0,
                _ => return false,
            };
            if v.is_nan() || v > 1000.0 {
                return false;
            }
            for d in 0..inst.rhs.defs() {
                let t = (inst.def + d) as usize;
                if e.len() <= t {
                    e.resize(t + 1, f64::INFINITY);
                }
                e[t] = v;
            }
        }
        true
    };
    let m = [60, 50, 40, 30, 20, 16, 12, 10]
        .into_iter()
        .find(|&m| fits(f64::from(m)))?;
    Some(Bounds {
        hi: 2f64.powi(m),
        params,
        dens,
        roots,
    })
}

/// Which of `musts` (values that must be finite) the fast path has to test: `false` for a
/// value that flows into another tested value through operations that keep a NaN or an
/// infinity, since then the tested value is not finite either.
///
/// The operations that keep them (for every value of the other operands, as IEEE 754
/// arithmetic defines them): `+`, `−`, `·` (∞·0 is NaN), the dividend of `/`, `√`, `sin`,
/// `cos`, `tan`, `ln`, `|·|`, and integer powers (products). Those that may not: the divisor
/// (`x/∞ = 0`), `exp` (`exp(−∞) = 0`), general powers and `atan2`. So if every tested value
/// is finite, so is every value of `musts`: testing fewer values changes no result, it
/// shortens the fast path. Walks the instructions backwards (consumers before producers).
fn finiteness_sinks(insts: &[Inst], musts: &[Operand]) -> Vec<bool> {
    use eom_sym::lower::OpKey;
    let must: HashSet<OpKey> = musts.iter().map(|o| o.key()).collect();
    let mut covered: HashSet<OpKey> = HashSet::new();
    let mut tested: HashSet<OpKey> = HashSet::new();
    for inst in insts.iter().rev() {
        let mut live = false;
        for d in 0..inst.rhs.defs() {
            let k = OpKey::Temp(inst.def + d);
            if covered.contains(&k) {
                live = true;
            } else if must.contains(&k) {
                tested.insert(k);
                covered.insert(k);
                live = true;
            }
        }
        if !live {
            continue;
        }
        let keeps: Vec<Operand> = match &inst.rhs {
            Rhs::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
            Rhs::Prod { num, .. } => num.clone(),
            Rhs::Call1(f, x) if f.keeps_non_finite() => vec![*x],
            Rhs::Call1(..) => Vec::new(),
            Rhs::SinCos(x) => vec![*x],
            Rhs::Call2(..) => Vec::new(),
        };
        for o in keeps {
            covered.insert(o.key());
        }
    }
    musts
        .iter()
        .map(|o| match o {
            Operand::Lit(_) => false,
            Operand::Temp(_) => tested.contains(&o.key()),
            // Parameters are defined by no instruction: tested unless a tested value uses them.
            Operand::Param(_) => !covered.contains(&o.key()),
        })
        .collect()
}

/// Estimated latencies (cycles) of the operations, for ordering the operands of sums and
/// products. Only their relative sizes matter: a division or a call is much slower than an
/// addition, and everything waiting on it should be combined last.
pub(crate) mod latency {
    /// Addition, subtraction, multiplication.
    pub const ARITH: u32 = 3;
    /// Sign flip or absolute value (a bit operation).
    pub const SIGN: u32 = 1;
    /// Division (and reciprocal).
    pub const DIV: u32 = 13;
    /// Square root.
    pub const SQRT: u32 = 15;
    /// A call of an elementary function (`sin`, `sincos`, `exp`, `pow`, …).
    pub const CALL: u32 = 45;
}

/// A subtree of a sum or product being built: its code, when its value is ready, whether it
/// is compound (needs parentheses as a right operand) and, in sums, whether it enters
/// subtracted.
#[derive(Clone)]
struct Part {
    code: TokenStream,
    ready: u32,
    compound: bool,
    neg: bool,
}

impl Part {
    fn leaf(code: TokenStream, ready: u32) -> Part {
        Part {
            code,
            ready,
            compound: false,
            neg: false,
        }
    }
}

/// Combine `parts` with `op` (`+` for sums, `*` for products) by ready time: the two values
/// that are ready first are combined first (as Huffman's code combines the two rarest), so
/// a late value (after a division or a call) meets a sum of everything else in one last
/// operation, instead of sitting at the bottom of a balanced tree. Equal ready times give a
/// balanced tree. Rust keeps the written association of floating-point operations, so the
/// tree is spelt out with parentheses.
///
/// In sums, subtracted parts combine as `a − b`, `b − a` or `−(a + b)`; a sum with one added
/// term (the lowering's canonical sign guarantees one) is never negative at the root, since
/// a part containing an added term stays added. Ties keep the given order (deterministic).
fn by_ready(mut parts: Vec<Part>, sum: bool) -> Part {
    if parts.is_empty() {
        let code = if sum { quote!(0.0) } else { quote!(1.0) };
        return Part::leaf(code, 0);
    }
    // Kept sorted by ready time (stable: ties in the given order); a merged part goes after
    // the parts that are ready as early, so equal ready times give a balanced tree.
    parts.sort_by_key(|p| p.ready);
    while parts.len() > 1 {
        let (mut a, mut b) = (parts.remove(0), parts.remove(0));
        let ready = a.ready.max(b.ready) + latency::ARITH;
        // `x + (y + z)` reads better as `y + z + x`; commuting is exact in floating point.
        if b.compound && !a.compound && a.neg == b.neg {
            std::mem::swap(&mut a, &mut b);
        }
        let paren = |p: &Part| {
            let c = &p.code;
            if p.compound { quote!((#c)) } else { c.clone() }
        };
        let (code, neg) = match (sum, a.neg, b.neg) {
            (false, _, _) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l * #r), false)
            }
            (true, false, false) | (true, true, true) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l + #r), a.neg)
            }
            (true, false, true) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l - #r), false)
            }
            (true, true, false) => {
                let (l, r) = (&b.code, paren(&a));
                (quote!(#l - #r), false)
            }
        };
        let at = parts.partition_point(|p| p.ready <= ready);
        parts.insert(
            at,
            Part {
                code,
                ready,
                compound: true,
                neg,
            },
        );
    }
    let root = parts.pop().expect("one part");
    if root.neg {
        let c = &root.code;
        let code = if root.compound {
            quote!(-(#c))
        } else {
            quote!(-#c)
        };
        Part {
            code,
            ready: root.ready + latency::SIGN,
            compound: false,
            neg: false,
        }
    } else {
        root
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
    /// When each of `mags` is ready.
    mag_ready: Vec<u32>,
    /// The value of each of `mags` (whose absolute value it is).
    mag_ops: Vec<Operand>,
    comparisons: usize,
    distinct: usize,
}

/// The boolean of each distinct check (identical checks are evaluated once).
fn render_checks(
    ctx: &Ctx,
    checks: &[(Operand, Vec<Operand>)],
    specs: &[Check],
    ready: &[u32],
) -> Result<Checks, CodegenError> {
    let num = ctx.num;
    let pivot_tol = num.round(eom_model::reduce::PIVOT_TOLERANCE);
    let rank_tol = num.round(eom_model::reduce::RANK_TOLERANCE);
    let mut ts = TokenStream::new();
    let mut seen: HashMap<(bool, Vec<eom_sym::lower::OpKey>), (TokenStream, TokenStream)> =
        HashMap::new();
    let mut per_check: Vec<TokenStream> = Vec::new();
    let mut per_mag: Vec<TokenStream> = Vec::new();
    let mut mags: Vec<Ident> = Vec::new();
    let mut mag_ready: Vec<u32> = Vec::new();
    let mut mag_ops: Vec<Operand> = Vec::new();
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
                    mag_ready.push(ctx.ready_of(*v, ready) + latency::SIGN);
                    mag_ops.push(*v);
                    let tl = num.lit(pivot_tol, "tolerance")?;
                    let mut lit_max: f64 = 0.0;
                    let mut seen_r: Vec<eom_sym::lower::OpKey> = Vec::new();
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
        mag_ready,
        mag_ops,
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
