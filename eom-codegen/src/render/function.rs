//! One generated function: its body (chunked through the work buffer when it is long), the
//! fast test of the validity checks and of finiteness, the slow path that names the failure,
//! the sparse stores, and its documentation; and the module's `sincos`.

use super::FunctionStats;
use super::checks::{Checks, render_checks};
use super::finite::{finiteness_sinks, magnitude_bounds};
use super::ready::{Part, by_ready, join};
use super::{Ctx, FnPlan, Rendered, chunks, collect_params, entry, matrix_args, param_lets};
use crate::CodegenError;
use crate::options::{MathLib, Precision};
use crate::problem::Problem;
use eom_sym::lower::{CodeOps, Operand};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// Which temporaries cross the chunks of a long function (through the work buffer), and
/// which each chunk loads.
struct Chunking {
    ranges: Vec<std::ops::Range<usize>>,
    /// The work-buffer slot of each temporary that crosses chunks.
    slot: HashMap<u32, usize>,
    /// Per chunk, and last for the epilogue (checks and stores): the temporaries it loads.
    loads: Vec<Vec<u32>>,
}

impl Chunking {
    fn new(plan: &FnPlan, max_temps: usize, epi_ops: &[Operand]) -> Chunking {
        let insts = &plan.lowered.insts;
        let ranges = chunks(insts, max_temps);
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
        if n_chunks > 1 {
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
            for o in epi_ops {
                if let Operand::Temp(t) = o {
                    mark(*t, n_chunks, &mut loads);
                }
            }
        }
        // Slots in temporary order, for readable code.
        let mut crossing: Vec<u32> = slot.keys().copied().collect();
        crossing.sort_unstable();
        let slot = crossing.iter().enumerate().map(|(k, &t)| (t, k)).collect();
        for l in &mut loads {
            l.sort_unstable();
        }
        Chunking {
            ranges,
            slot,
            loads,
        }
    }

    fn chunked(&self) -> bool {
        self.ranges.len() > 1
    }

    /// Length of the work buffer the function needs.
    fn work_len(&self) -> usize {
        if self.chunked() { self.slot.len() } else { 0 }
    }

    /// `let tN = work[k];`
    fn load(&self, ctx: &Ctx, t: u32) -> TokenStream {
        let ty = &ctx.ty;
        let i = format_ident!("t{}", t);
        let s = Literal::usize_unsuffixed(self.slot[&t]);
        quote!(let #i: #ty = work[#s];)
    }
}

/// The instructions: one function per chunk (returned as items) called from the body, or all
/// of them in the body; then the parameters and values the epilogue reads. Records the ready
/// time of every temporary in `ready`.
fn render_body(
    ctx: &Ctx,
    plan: &FnPlan,
    ch: &Chunking,
    epi_ops: &[Operand],
    ready: &mut Vec<u32>,
) -> Result<(TokenStream, TokenStream), CodegenError> {
    let ty = &ctx.ty;
    let insts = &plan.lowered.insts;
    let (mut items, mut body) = (TokenStream::new(), TokenStream::new());
    if !ch.chunked() {
        let mut used = Vec::new();
        for inst in insts {
            collect_params(inst.rhs.operands(), &mut used);
        }
        collect_params(epi_ops.iter().copied(), &mut used);
        body.extend(quote!(let _ = work;));
        body.extend(param_lets(ctx, used));
        for inst in insts {
            body.extend(ctx.inst(inst, ready)?);
        }
        return Ok((items, body));
    }
    let n_chunks = ch.ranges.len();
    for (c, r) in ch.ranges.iter().enumerate() {
        let fname = format_ident!("{}_chunk{}", plan.name, c);
        let mut used = Vec::new();
        for inst in &insts[r.clone()] {
            collect_params(inst.rhs.operands(), &mut used);
        }
        let params = param_lets(ctx, used);
        let lds = ch.loads[c].iter().map(|&t| ch.load(ctx, t));
        let mut lets: Vec<TokenStream> = Vec::with_capacity(r.len());
        for i in &insts[r.clone()] {
            lets.push(ctx.inst(i, ready)?);
        }
        let mut stores = Vec::new();
        for inst in &insts[r.clone()] {
            for d in 0..inst.rhs.defs() {
                let t = inst.def + d;
                if let Some(&s) = ch.slot.get(&t) {
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
    for &t in &ch.loads[n_chunks] {
        body.extend(ch.load(ctx, t));
    }
    Ok((items, body))
}

/// The distinct computed entries (for the slow path that names the failing one) and the table
/// `(matrix, row, column, index of the value)` of every computed entry.
fn entry_table(plan: &FnPlan) -> Result<(Vec<Operand>, Vec<TokenStream>), CodegenError> {
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
    Ok((values, table))
}

/// The fast path's finiteness test (its `let`s go to `body`), and the note for the
/// documentation when it is the test by magnitudes.
///
/// The fast path adds up only the values that no other tested value depends on through
/// operations that keep a NaN or an infinity ([`finiteness_sinks`]), and tests the sum: it is
/// finite iff they all are, unless it overflows by itself, which the slow path sorts out.
/// Finiteness by magnitude instead: bounded parameters and denominators bounded away from zero
/// keep every value finite, and these tests come early (no entry is waited for). Each
/// parameter costs two operations, so this pays for small functions only, whose time is the
/// latency of their longest chain (the shimmy gains, the bicycle with its 27 parameters
/// loses; `bench/pydy/README.md`).
fn finiteness_test(
    ctx: &Ctx,
    plan: &FnPlan,
    values: &[Operand],
    checks: &Checks,
    ready: &[u32],
    chunked: bool,
    body: &mut TokenStream,
) -> Result<(Option<TokenStream>, Option<String>), CodegenError> {
    let ty = &ctx.ty;
    let insts = &plan.lowered.insts;
    let mut musts: Vec<Operand> = values.to_vec();
    musts.extend(&checks.mag_ops);
    let bounds =
        magnitude_bounds(insts, &musts).filter(|b| !chunked && b.params.len() + b.dens.len() <= 12);
    if let (Precision::F64, Some(b)) = (ctx.num.prec, bounds) {
        let note = format!(
            " Fast path: where the magnitudes of the even- and of the odd-numbered parameters each sum to less than {:e} and every divisor has magnitude at least {:e}, every value is provably finite and no entry is tested; elsewhere the same values are computed again with every check and entry tested one by one (about twice the time).",
            b.hi,
            1.0 / b.hi
        );
        let hi = ctx.num.lit(b.hi, "parameter bound")?;
        let lo = ctx.num.lit(1.0 / b.hi, "denominator bound")?;
        let mut tests: Vec<TokenStream> = Vec::new();
        if !b.params.is_empty() {
            // Two running sums, of the even- and of the odd-numbered parameters, in index
            // order, each tested: the same operations on consecutive array elements, which
            // LLVM turns into packed `andpd`/`addpd` on pairs and one `cmpltpd` (faster than
            // one tree over all of them; a test per lane rather than of their sum is two
            // instructions fewer). Each lane below the bound bounds each parameter.
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
        let test = (!tests.is_empty()).then(|| {
            let all = join(&tests, quote!(&));
            quote!((#all))
        });
        return Ok((test, Some(note)));
    }
    let sinks = finiteness_sinks(insts, &musts);
    let mut summands: Vec<Part> = Vec::new();
    for (k, v) in values.iter().enumerate() {
        if sinks[k] {
            summands.push(Part::leaf(ctx.operand(*v)?, ctx.ready_of(*v, ready)));
        }
    }
    for (k, (m, &r)) in checks.mags.iter().zip(&checks.mag_ready).enumerate() {
        if sinks[values.len() + k] {
            summands.push(Part::leaf(quote!(#m), r));
        }
    }
    // Combined by ready time: the values that come last (after the slowest division or call)
    // join in the last additions, so the test adds little to the critical path.
    if summands.is_empty() {
        return Ok((None, None));
    }
    let sum = by_ready(summands, true).code;
    body.extend(quote!(let sum: #ty = #sum;));
    Ok((Some(quote!(sum.is_finite())), None))
}

/// The function's documentation lines.
fn fn_docs(ctx: &Ctx, plan: &FnPlan, ch: &Chunking, fast_note: Option<String>) -> Vec<String> {
    let which: Vec<String> = plan
        .mats
        .iter()
        .map(|m| format!("`{}`", m.variant()))
        .collect();
    let mut doc = fn_doc(
        ctx.problem,
        plan,
        &which.join(", "),
        ch.ranges.len(),
        ch.work_len(),
    );
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
    doc
}

/// One generated function (with its chunks, its entry table and its slow path) and its
/// statistics.
pub(crate) fn render_fn(
    ctx: &Ctx,
    plan: &FnPlan,
    max_temps: usize,
) -> Result<Rendered, CodegenError> {
    let ty = &ctx.ty;
    let mut ops = CodeOps::default();
    for i in &plan.lowered.insts {
        ops.count(&i.rhs);
    }
    // Epilogue operands: check operands and outputs.
    let mut epi_ops: Vec<Operand> = plan.outputs.iter().map(|o| o.3).collect();
    for (v, o) in &plan.checks {
        epi_ops.push(*v);
        epi_ops.extend(o);
    }
    let ch = Chunking::new(plan, max_temps, &epi_ops);
    // Estimated ready time of every temporary (values from the work buffer count as ready).
    let mut ready: Vec<u32> = vec![0; plan.lowered.n_temps as usize];
    let (mut items, mut body) = render_body(ctx, plan, &ch, &epi_ops, &mut ready)?;

    // Validity checks: identical checks are evaluated once, then one branch on all of them.
    let checks = render_checks(ctx, &plan.checks, &ctx.problem.checks, &ready)?;
    body.extend(checks.lets.clone());
    let (values, table) = entry_table(plan)?;
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
    let (finite, fast_note) =
        finiteness_test(ctx, plan, &values, &checks, &ready, ch.chunked(), &mut body)?;
    let conds_empty = slow_branch(
        ctx,
        plan,
        SlowBranch {
            checks: &checks,
            finite,
            values: &values,
            table: &table,
            slow_name: &slow_name,
            mat_args: &mat_args,
        },
        &mut items,
        &mut slow,
        &mut body,
    )?;

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
    let doc = fn_docs(ctx, plan, &ch, fast_note);
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
        work_len: ch.work_len(),
        stats: FunctionStats {
            name: plan.name.to_string(),
            temporaries: plan.lowered.n_temps as usize,
            chunks: ch.ranges.len(),
            work_values: ch.work_len(),
            ops,
            check_comparisons: checks.comparisons,
            distinct_checks: checks.distinct,
            stores,
            critical_path,
        },
    })
}

/// What the branch to the slow path needs (see [`slow_branch`]).
struct SlowBranch<'a> {
    checks: &'a Checks,
    finite: Option<TokenStream>,
    values: &'a [Operand],
    table: &'a [TokenStream],
    slow_name: &'a Ident,
    mat_args: &'a [Ident],
}

/// One branch for the validity checks and the finiteness, to the slow path that finds the
/// first failure in the interpreter's order; `true` when there is nothing to check.
fn slow_branch(
    ctx: &Ctx,
    plan: &FnPlan,
    b: SlowBranch<'_>,
    items: &mut TokenStream,
    slow: &mut TokenStream,
    body: &mut TokenStream,
) -> Result<bool, CodegenError> {
    let SlowBranch {
        checks,
        finite,
        values,
        table,
        slow_name,
        mat_args,
    } = b;
    let mut conds: Vec<TokenStream> = (0..checks.distinct)
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
        let (oks, mags) = (&checks.ok, &checks.mag);
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

    Ok(conds_empty)
}

pub(super) fn fn_doc(
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
/// |x| ≤ π/4 polynomials run inline, and beyond it (and for NaN and ±∞) the library.
///
/// * `f64`: the minimax polynomials of degree 13 (sine) and 14 (cosine) on [−π/4, π/4] of
///   fdlibm's kernels (`__kernel_sin`, `__kernel_cos`; relative error of the polynomial below
///   2⁻⁵⁸), the cosine's leading `1 − z/2` summed with its rounding error recovered as those
///   kernels do. Their coefficients in `z = x²` are evaluated in Estrin's form (pairs `a + b z`
///   combined by `z²` and `z⁴`), not Horner's: the sine and cosine head the longest chain of
///   a model's code (a steer-axis tilt reaches the mass matrix through `tan λ`), and with
///   Estrin's form the sine is 9 operations deep where the Taylor polynomial to x¹⁷ in
///   Horner's form it replaces was 17 (the cosine alike). Within an ulp of the library, and
///   correctly rounded about as often as the Taylor polynomials (sine) or more often
///   (cosine); on the bicycle's generated A..D in `bench/pydy`, 44.9 → 42.5 ns per call
///   (docs/performance.md).
/// * `f32`: the Taylor polynomials, truncated where the next term is below a tenth of an ulp
///   (x⁹ and x¹⁰), in Horner form.
pub(crate) fn sincos_item(ctx: &Ctx) -> Result<TokenStream, CodegenError> {
    let ty = &ctx.ty;
    let body = match ctx.num.prec {
        Precision::F64 => sincos_f64_minimax(ctx)?,
        Precision::F32 => sincos_taylor(ctx, 9, 10)?,
    };
    let bound = ctx.num.lit(std::f64::consts::FRAC_PI_4, "π/4")?;
    let library = match ctx.math {
        MathLib::Libm => {
            let f = ctx.libm("sincos");
            quote!(#f(x))
        }
        MathLib::Std => quote!(x.sin_cos()),
    };
    Ok(quote! {
        /// `(sin x, cos x)` as the evaluation functions compute them: inline polynomials for
        /// |x| ≤ π/4 (within about an ulp of the math library, without the cost of a call),
        /// the math library beyond.
        #[inline(always)]
        pub fn sincos(x: #ty) -> (#ty, #ty) {
            if x.abs() <= #bound {
                #body
            } else {
                #library
            }
        }
    })
}

/// fdlibm's minimax coefficients (k_sin.c S1…S6, k_cos.c C1…C6), for z = x² and |x| ≤ π/4:
/// sin x = x + x·z·(S1 + z·(S2 + … + S6 z⁴)) and cos x = 1 − z/2 + z²·(C1 + … + C6 z⁵). The
/// doubles of their 21-digit decimals, written shortest.
const SIN_MINIMAX: [f64; 6] = [
    -0.16666666666666632,
    0.00833333333332249,
    -0.0001984126982985795,
    2.7557313707070068e-6,
    -2.5050760253406863e-8,
    1.58969099521155e-10,
];
const COS_MINIMAX: [f64; 6] = [
    0.0416666666666666,
    -0.001388888888887411,
    2.480158728947673e-5,
    -2.7557314351390663e-7,
    2.087572321298175e-9,
    -1.1359647557788195e-11,
];

/// The `f64` polynomial part of `sincos` (see [`sincos_item`]).
fn sincos_f64_minimax(ctx: &Ctx) -> Result<TokenStream, CodegenError> {
    let l = |x: f64| ctx.num.lit(x, "sincos coefficient");
    let s: Vec<TokenStream> = SIN_MINIMAX
        .iter()
        .map(|&c| l(c))
        .collect::<Result<_, _>>()?;
    let c: Vec<TokenStream> = COS_MINIMAX
        .iter()
        .map(|&c| l(c))
        .collect::<Result<_, _>>()?;
    let (s0, s1, s2, s3, s4, s5) = (&s[0], &s[1], &s[2], &s[3], &s[4], &s[5]);
    let (c0, c1, c2, c3, c4, c5) = (&c[0], &c[1], &c[2], &c[3], &c[4], &c[5]);
    Ok(quote! {
        let z = x * x;
        let z2 = z * z;
        let z4 = z2 * z2;
        let rs = (#s1 + z * #s2) + z2 * (#s3 + z * #s4) + z4 * #s5;
        let rc = (#c0 + z * #c1) + z2 * (#c2 + z * #c3) + z4 * (#c4 + z * #c5);
        let hz = 0.5 * z;
        let w = 1.0 - hz;
        (x + x * z * (#s0 + z * rs), w + (((1.0 - w) - hz) + z2 * rc))
    })
}

/// The Taylor polynomials of `sincos` to `x^sin_top` and `x^cos_top`, in Horner form.
fn sincos_taylor(ctx: &Ctx, sin_top: u32, cos_top: u32) -> Result<TokenStream, CodegenError> {
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
    Ok(quote! {
        let z = x * x;
        (x + x * z * (#sin_poly), 1.0 + z * (#cos_poly))
    })
}
