//! # eom-codegen — symbolic state-space models as specialised Rust functions
//!
//! [`emit`] lowers the expression DAG of a [`SymbolicStateSpace`] (A, B, C, D, the map to the
//! physical coordinates, and the checks that bound its validity region) to one Rust module:
//! straight-line code with one `let` per unique operation, parameters as a named struct and as
//! an array, outputs written sparsely into fixed-size arrays, `#![no_std]`-compatible (through
//! `libm`), in `f64` or `f32`. The generated functions check the validity region and the
//! finiteness of their results and return an error value instead of garbage.
//!
//! ```
//! let model = models::build("smd", &[]).unwrap();
//! let sym = eom_model::Linearizer::new(&model).symbolic().unwrap();
//! let src = eom_codegen::emit(&sym, &eom_codegen::EmitOptions::default().model_name("smd")).unwrap();
//! assert!(src.contains("pub fn eval_ab("));
//! ```
//!
//! In a build script, use the [`build::Generate`] builder:
//!
//! ```no_run
//! // build.rs
//! let model = models::build("bicycle", &[]).unwrap();
//! eom_codegen::build::Generate::new(model).f32().write_to_out_dir("bicycle.rs").unwrap();
//! // lib.rs:  include!(concat!(env!("OUT_DIR"), "/bicycle.rs"));   // defines `mod bicycle`
//! ```
//!
//! ## The generated module
//!
//! For a model `m` the file holds one item, `pub mod m { … }`, with
//! * constants: sizes (`N_STATES`, `N_INPUTS`, `N_OUTPUTS`, `N_COORDS`, `N_PARAMS`,
//!   `N_CHECKS`, `WORK_LEN`, `A_LEN`…), names (`PARAM_NAMES`, `PARAM_UNITS`, `STATE_NAMES`…),
//!   `NOMINAL`, the sparsity patterns `A_NONZEROS`…, the check descriptions `CHECKS`;
//! * `Params`: one named field per parameter, with `NOMINAL`, `to_array`, `from_array`;
//! * the kernels `eval_abcd`, `eval_ab`, `eval_cd`, `eval_phys`:
//!   `fn(p: &[Real; N_PARAMS], a: &mut [Real; A_LEN], …, work: &mut [Real; WORK_LEN]) -> Result<(), Error>`,
//!   column-major outputs, structural zeros never written;
//! * for each kernel, `eval_abcd_varying`, `eval_ab_varying`… (same signature) write only
//!   the entries that depend on the parameters, and `const fn write_abcd_constants(a, b, c,
//!   d)`, `write_ab_constants(a, b)`… the constant ones (a `1` of a kinematic row, a sign),
//!   once: the kernels for callers that keep their arrays between calls, as a controller
//!   evaluating A and B every tick (without constant entries the varying kernel is the
//!   whole one itself);
//! * `StateSpace`: A, B, C, D and the workspace in one value, constants written at
//!   construction, `evaluate(&Params)` through `eval_abcd_varying`;
//! * `Error` (`Validity { check }`, `NonFinite { matrix, row, col }`; 8 bytes, so that
//!   `Result<(), Error>` is returned in a register; `what()` gives the failing check's
//!   description).
//!
//! With [`EmitOptions::stability`] (`eom codegen --stability`) the module also has the
//! stability verdict without eigenvalues, `f64` only, for models of up to
//! [`MAX_STABILITY_STATES`] states:
//! * `characteristic_polynomial(p, c, e)`: the coefficients of `p(s)`, the closed-form
//!   characteristic polynomial `det(sI − A) = s^ZERO_ROOTS · p(s) / scale` of
//!   `eom symbolic` (from the descriptor pencil, the structural zero roots divided out), each
//!   with a bound `e[k]` on its rounding error;
//! * `stability_conditions(p, c, e)`: the Liénard–Chipart conditions (every coefficient, then
//!   the Hurwitz determinants `Δ_{d−1}, Δ_{d−3}, …`), normalised by the leading coefficient's
//!   sign, with their bounds (`CONDITIONS` names them);
//! * `stability(p) -> Result<Verdict, Error>`: `Stable` when every condition exceeds its
//!   bound, `Unstable` when one is certainly not positive (unstable or marginal),
//!   `Undecided` when one is within its bound of zero. `Verdict` is `#[repr(i8)]` (`1`, `-1`,
//!   `0`), so the function can be wrapped for a foreign caller as it is;
//! * `stability_many(points, verdicts)`: the same verdicts for many points, the first stage
//!   (below) on `LANES` points at a time in packed arithmetic, with one magnitude per block
//!   of points (the largest of the block's: a bound at least each point's own);
//! * `stability_conditions_quick(p, c, e)`: the conditions with the first stage's bounds;
//!   `stability_conditions_quick_lanes` the same for a block of `LANES` points, with the
//!   block's bounds.
//!
//! The verdict has two stages. The first computes, next to every value, a magnitude whose
//! relative error factor is a constant of the generator (an a-priori analysis, Higham,
//! *Accuracy and Stability of Numerical Algorithms*, §3.1): one more operation per operation
//! and one multiplication per condition. Only where a condition is within that bound of zero
//! does the second stage run: a running error analysis carried out next to the values (§3.3),
//! every value with a bound on its distance from the exact value of its formula, propagated
//! operation by operation — tighter where the formulas cancel, and three to four times the
//! cost. For the bicycle (27 parameters, a quartic) `stability_many` costs about 60 ns per
//! point on a loaded core (one `stability` call about 100 ns, the running bound alone about
//! 250), and at 2·10⁶ random points within ±20 % of nominal it decides every point, as the
//! eigenvalues do (`eom bench throughput`).
//!
//! ## Lowering
//!
//! One `let` per unique operation of the DAG, and beyond that:
//! * integer powers by shared multiplication chains (no `powi`), half-integer powers through
//!   one `sqrt`;
//! * one reciprocal per denominator that two or more products divide by; other divisions
//!   share one `/` per product;
//! * numeric scales (signs and coefficients) travel with values into the sums and products
//!   that use them, so `k/m`, `−k/m` and `2k/m` cost one product;
//! * `x^a·x^−a` cancels when a validity check keeps `x` away from zero (exact wherever the
//!   result is returned);
//! * `sin x` and `cos x` come from one `sincos`, the module's own: inline polynomials for
//!   |x| ≤ π/4 (`f64`: minimax, in Estrin's form for a short dependency chain; within about an
//!   ulp of the library), the math library beyond; operations
//!   on numbers are folded;
//! * pairs of operands that several products (or sums) share become one temporary (greedy);
//! * the operands of each sum and product are associated by estimated ready time (a value
//!   that waits on a division or a call joins last), not in a fixed balanced tree;
//! * the validity checks are branch-free comparisons with precomputed bounds; finiteness is
//!   tested on one sum of the *finiteness sinks* only — the entries and pivots that no other
//!   tested value depends on through NaN- and ∞-keeping operations (`+ − ·`, dividends, `√`,
//!   `sin`, …), so a non-finite entry always reaches the sum. Where every value's magnitude
//!   can be bounded (small polynomial and rational kernels such as the shimmy's), the fast
//!   path instead tests the parameters' magnitudes (two partial sums of `|p|`, ready before
//!   any arithmetic) and the divisors' distance from zero, which proves every entry finite
//!   without waiting for the last one. Both forms are tested with a single branch to a cold
//!   copy of the function that tests every check and entry one by one and names the first
//!   failure (the fast path needs no stack frame for the report).
//!
//! Large evaluations are split into `#[inline(never)]` chunks of at most
//! [`EmitOptions::max_temporaries`] temporaries that pass values through the work buffer.
//! Operands are ordered by a structural hash, so the output is a function of the model alone
//! (same model → same bytes, whatever else the expression pool holds).
//!
//! ## Speed
//!
//! The generated code is plain scalar Rust; how fast it runs depends on the instructions the
//! compiler may use, so try the crate that includes it compiled for the CPU it will run on:
//! `RUSTFLAGS="-C target-cpu=native"` for a design loop on the workstation, a level such as
//! `-C target-cpu=x86-64-v3` for a fleet of x86 machines, a microcontroller's own target (e.g.
//! `thumbv7em-none-eabihf`). On x86 the baseline target (SSE2) costs the small kernels most:
//! its two-operand instructions need a register copy for every value still used afterwards.
//! Large kernels may go the other way: from SSE3 on, LLVM's SLP vectoriser packs the bicycle's
//! operations into pairs twice as often and loses more to shuffles than it gains. Measure with
//! your model. Against PyDy's generated C in one driver, both sides compiled alike, the
//! shimmy's `eval_abcd_varying` (`--simplify`) takes about 0.86–0.92× PyDy's time and the
//! bicycle's 0.59–0.72× (baseline target and `x86-64-v3`), and the bicycle's A and B carry
//! less rounding error (1.4–1.7e-14 of the largest entry of each row at 1024 random points,
//! PyDy's 2.3e-14); the figures and the scripts that measure them are in
//! `bench/pydy/README.md`.
//!
//! No fast-math is needed or wanted: the finiteness proofs and the accuracy tests assume IEEE
//! arithmetic as written (Rust never contracts `a * b + c` into a fused multiply-add by itself).

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod build;
mod discrete;
mod error;
mod items;
mod options;
mod problem;
pub mod reduced;
mod render;
mod stability;

pub use eom_sym::lower::CodeOps;
pub use error::CodegenError;
pub use options::{DEFAULT_CHUNK, EmitOptions, Functions, MathLib, Precision};
pub use render::FunctionStats;
pub use stability::MAX_STABILITY_STATES;

use eom_model::{Linearizer, Model, SymbolicStateSpace};
use eom_sym::{Expr, OpCount};
use problem::{Mat, Problem};
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use render::{Ctx, FnSpec, Num};

/// Generated source with statistics.
#[derive(Clone, Debug)]
pub struct Emitted {
    /// The Rust source (one `pub mod`).
    pub source: String,
    /// The module name.
    pub module: String,
    /// What was generated.
    pub stats: EmitStats,
}

/// Statistics of a generated module.
#[derive(Clone, Debug)]
pub struct EmitStats {
    /// Operation counts of the expression DAG of A, B, C, D (each unique node once, as
    /// [`Expr::op_count`] counts), before lowering.
    pub dag_ops_abcd: OpCount,
    /// Unique nodes of A, B, C, D.
    pub dag_nodes_abcd: usize,
    /// Per generated function.
    pub functions: Vec<FunctionStats>,
    /// Length of the work buffer.
    pub work_len: usize,
    /// Validity checks.
    pub checks: usize,
    /// What became of the simplification.
    pub simplification: Simplification,
}

/// What became of the simplification ([`EmitOptions::simplify`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simplification {
    /// Not asked for.
    NotRun,
    /// The simplified expressions are used: fewer operations, and a lower
    /// [`FunctionStats::cost_estimate`] (or any, with [`EmitOptions::simplify_always`]).
    Used,
    /// The simplifier found nothing with a smaller operation count; the original is used.
    NotCheaper,
    /// The simplified expressions have fewer operations, but a dependency chain so much
    /// longer (usually from factoring a product out of a sum) that the
    /// [`FunctionStats::cost_estimate`] of the first generated function is not lower, so
    /// the original is used.
    NotFaster {
        /// Cost estimate of the simplified code.
        simplified: u64,
        /// Cost estimate of the original code.
        original: u64,
    },
}

impl Simplification {
    /// Whether the simplified expressions are used.
    pub fn used(&self) -> bool {
        matches!(self, Simplification::Used)
    }
}

/// Generate the module for a symbolic state-space model.
pub fn emit(sym: &SymbolicStateSpace, opts: &EmitOptions) -> Result<String, CodegenError> {
    Ok(emit_with_stats(sym, opts)?.source)
}

/// Build the symbolic state-space model of `model` and generate its module (named after the
/// model unless [`EmitOptions::module`] says otherwise).
pub fn emit_model(model: &Model<Expr>, opts: &EmitOptions) -> Result<Emitted, CodegenError> {
    let sym = Linearizer::new(model).symbolic()?;
    let mut o = opts.clone();
    if o.model_name.is_none() {
        o.model_name = Some(model.name.clone());
    }
    emit_with_stats(&sym, &o)
}

/// [`emit`], returning statistics too.
///
/// With [`EmitOptions::simplify`], the simplified expressions are used only when they have
/// fewer operations *and* a lower [`FunctionStats::cost_estimate`] (longest chain times
/// operations) of the first function; [`EmitStats::simplification`] says which. Measured in
/// one driver (`bench/pydy`): the bicycle's simplified form has 17 weighted operations fewer
/// but a chain 9 longer, and takes 80.4 ns against 68.2 ns (kept out); the shimmy's has 5
/// fewer and a chain 3 longer, and takes 4.77 against 4.94 ns (used).
pub fn emit_with_stats(
    sym: &SymbolicStateSpace,
    opts: &EmitOptions,
) -> Result<Emitted, CodegenError> {
    let first = emit_once(sym, opts)?;
    if first.stats.simplification != Simplification::Used || opts.simplify_always {
        return Ok(first);
    }
    let mut plain = opts.clone();
    plain.simplify = false;
    let original = emit_once(sym, &plain)?;
    let cost = |e: &Emitted| e.stats.functions.first().map_or(0, |f| f.cost_estimate());
    let (with, without) = (cost(&first), cost(&original));
    if with < without {
        return Ok(first);
    }
    let mut kept = original;
    kept.stats.simplification = Simplification::NotFaster {
        simplified: with,
        original: without,
    };
    Ok(kept)
}

fn emit_once(sym: &SymbolicStateSpace, opts: &EmitOptions) -> Result<Emitted, CodegenError> {
    if opts.max_temporaries == 0 {
        return Err(CodegenError::BadOption {
            option: "max_temporaries",
            problem: "must be at least 1".into(),
        });
    }
    let problem = Problem::new(sym, opts.model_name.as_deref(), opts)?;
    let module = module_name(&problem, opts)?;
    let num = Num {
        prec: opts.precision,
    };
    let ctx = Ctx {
        num,
        math: opts.math,
        problem: &problem,
        ty: Ident::new(opts.precision.type_name(), Span::call_site()),
        trig: std::cell::Cell::new(false),
    };
    let specs = fn_specs(opts.functions)?;
    let (fn_items, stats, work_len) = render_functions(&ctx, &specs, opts)?;
    let abcd_roots: Vec<Expr> = problem.mats[..4]
        .iter()
        .flat_map(|m| m.entries.iter().map(|e| e.2))
        .collect();
    let emitted_stats = EmitStats {
        dag_ops_abcd: Expr::op_count(&abcd_roots),
        dag_nodes_abcd: Expr::dag_size(&abcd_roots),
        functions: stats,
        work_len,
        checks: problem.checks.len(),
        simplification: match &problem.simplified {
            None => Simplification::NotRun,
            Some(s) if s.kept => Simplification::Used,
            Some(_) => Simplification::NotCheaper,
        },
    };

    let mut items = items::module_items(&ctx, opts, work_len)?;
    if opts.stability {
        items.extend(stability_items(sym, &ctx, &specs, opts)?);
    }
    if ctx.trig.get() {
        items.extend(render::sincos_item(&ctx)?);
    }
    let mut extra: Vec<String> = opts.extra_items.clone();
    if opts.discrete {
        if !opts.functions.ab {
            return Err(CodegenError::BadOption {
                option: "discrete",
                problem: "eval_discrete evaluates A and B through eval_ab: keep it".into(),
            });
        }
        extra.push(discrete::source(opts.precision));
    }
    for src in &extra {
        let ts: TokenStream = src
            .parse()
            .map_err(|e| CodegenError::Syntax(format!("added items: {e}")))?;
        items.extend(ts);
    }
    let docs = module_doc(&problem, opts, &emitted_stats);
    let docs = docs.iter().map(|l| quote!(#[doc = #l]));
    let modname = Ident::new(&module, Span::call_site());
    let file = quote! {
        #(#docs)*
        #[allow(
            clippy::all,
            clippy::pedantic,
            clippy::nursery,
            non_snake_case,
            non_upper_case_globals,
            unused,
            uncommon_codepoints,
            mixed_script_confusables,
            confusable_idents
        )]
        pub mod #modname {
            #items
            #fn_items
        }
    };
    let parsed: syn::File = syn::parse2(file).map_err(|e| CodegenError::Syntax(e.to_string()))?;
    let body = prettyplease::unparse(&parsed);
    let mut header = format!(
        "// @generated by eom-codegen {} from model `{}` ({}, {}) — do not edit.\n",
        env!("CARGO_PKG_VERSION"),
        problem.model, // escaped by `Problem::new`: no line break can end this comment
        opts.precision.type_name(),
        match opts.math {
            MathLib::Libm => "libm",
            MathLib::Std => "std math",
        }
    );
    header.push_str(
        "// Include it with `include!(concat!(env!(\"OUT_DIR\"), \"/<file>.rs\"));`.\n\n",
    );
    Ok(Emitted {
        source: header + &body,
        module,
        stats: emitted_stats,
    })
}

/// The stability items ([`EmitOptions::stability`]).
fn stability_items(
    sym: &SymbolicStateSpace,
    ctx: &Ctx,
    specs: &[FnSpec],
    opts: &EmitOptions,
) -> Result<TokenStream, CodegenError> {
    if opts.precision != Precision::F64 {
        return Err(CodegenError::BadOption {
            option: "stability",
            problem: "the stability verdict is generated in f64 only (its rounding bounds \
                      assume f64 arithmetic)"
                .into(),
        });
    }
    let fixed: Vec<(Expr, Expr)> = ctx
        .problem
        .fixed
        .iter()
        .map(|(name, v)| {
            let p = sym
                .params
                .iter()
                .copied()
                .find(|p| p.param_info().is_some_and(|i| &i.name == name))
                .expect("a fixed parameter is one of the model's");
            Ok((p, Expr::float(*v)?))
        })
        .collect::<Result<_, CodegenError>>()?;
    let form = stability::StabilityForm::new(sym, &fixed)?;
    // The rank decisions of the reduction must hold for the polynomial to be the model's;
    // they are tested by the first kernel, which checks them all.
    let validate = if ctx.problem.checks.iter().any(|c| !c.pivot) {
        let spec = specs.first().expect("at least one function");
        let name = Ident::new(spec.name, Span::call_site());
        let args = spec.mats.iter().map(|m| {
            let len = Ident::new(
                &format!("{}_LEN", m.lower().to_uppercase()),
                Span::call_site(),
            );
            quote!(&mut [0.0; #len])
        });
        Some(quote!(#name(p, #(#args,)* &mut [0.0; WORK_LEN])?;))
    } else {
        None
    };
    stability::render(ctx, &form, validate)
}

/// The module's name, after checking that the sizes fit the generated `Error`.
fn module_name(problem: &Problem, opts: &EmitOptions) -> Result<String, CodegenError> {
    // The generated `Error` holds a check as `u32`, a row and a column as `u16`.
    index_fits(problem.checks.len(), u32::MAX, || "validity checks".into())?;
    for m in Mat::ALL {
        let spec = &problem.mats[m.index()];
        index_fits(spec.rows, u16::MAX, || format!("rows of {}", m.variant()))?;
        index_fits(spec.cols, u16::MAX, || {
            format!("columns of {}", m.variant())
        })?;
    }
    let module = match &opts.module {
        Some(m) => {
            let id = problem::module_ident(m);
            if &id != m {
                return Err(CodegenError::BadOption {
                    option: "module",
                    problem: format!("`{m}` is not a plain lower-case identifier (try `{id}`)"),
                });
            }
            id
        }
        None => problem::module_ident(&problem.model),
    };
    Ok(module)
}

/// The functions to generate.
fn fn_specs(f: Functions) -> Result<Vec<FnSpec>, CodegenError> {
    let mut specs = Vec::new();
    if f.abcd {
        specs.push(FnSpec {
            name: "eval_abcd",
            varying: "eval_abcd_varying",
            constants: "write_abcd_constants",
            mats: vec![Mat::A, Mat::B, Mat::C, Mat::D],
        });
    }
    if f.ab {
        specs.push(FnSpec {
            name: "eval_ab",
            varying: "eval_ab_varying",
            constants: "write_ab_constants",
            mats: vec![Mat::A, Mat::B],
        });
    }
    if f.cd {
        specs.push(FnSpec {
            name: "eval_cd",
            varying: "eval_cd_varying",
            constants: "write_cd_constants",
            mats: vec![Mat::C, Mat::D],
        });
    }
    if f.phys {
        specs.push(FnSpec {
            name: "eval_phys",
            varying: "eval_phys_varying",
            constants: "write_phys_constants",
            mats: vec![Mat::Phys],
        });
    }
    if specs.is_empty() {
        return Err(CodegenError::BadOption {
            option: "functions",
            problem: "no function selected".into(),
        });
    }
    Ok(specs)
}

/// The evaluation functions (each with its constants writer and its varying kernel), their
/// statistics and the work buffer they need.
fn render_functions(
    ctx: &Ctx,
    specs: &[FnSpec],
    opts: &EmitOptions,
) -> Result<(TokenStream, Vec<FunctionStats>, usize), CodegenError> {
    let mut fn_items = TokenStream::new();
    let mut stats = Vec::new();
    let mut work_len = 0;
    // Each `eval_X_varying` leaves out the constant entries; without any, it is `eval_X`.
    let mut varying: Vec<render::FnPlan> = Vec::new();
    for spec in specs {
        let plan = render::plan(spec, ctx.problem)?;
        let r = render::render_fn(ctx, &plan, opts.max_temporaries)?;
        work_len = work_len.max(r.work_len);
        fn_items.extend(r.items);
        stats.push(r.stats);
        fn_items.extend(render::render_constants(
            ctx,
            &plan,
            spec.constants,
            spec.varying,
        )?);
        if plan.writes_constants() {
            varying.push(plan.without_constants(spec.varying, spec.constants));
        } else {
            let whole = Ident::new(spec.name, Span::call_site());
            let alias = Ident::new(spec.varying, Span::call_site());
            let doc = format!(
                " [`{}`]: this model has no constant entry there, so there is nothing to leave out.",
                spec.name
            );
            fn_items.extend(quote! {
                #[doc = #doc]
                pub use #whole as #alias;
            });
        }
    }
    for plan in varying {
        let r = render::render_fn(ctx, &plan, opts.max_temporaries)?;
        work_len = work_len.max(r.work_len);
        fn_items.extend(r.items);
        stats.push(r.stats);
    }

    Ok((fn_items, stats, work_len))
}

/// `count` as the index type `T` of the generated `Error` (`u32` or `u16`), or
/// [`CodegenError::TooLarge`] naming `what`: indices are below counts, so every index fits too.
pub(crate) fn index_fits<T: TryFrom<usize> + Into<u64>>(
    count: usize,
    max: T,
    what: impl FnOnce() -> String,
) -> Result<T, CodegenError> {
    T::try_from(count).map_err(|_| CodegenError::TooLarge {
        what: what(),
        count,
        max: max.into(),
    })
}

fn escape_md(s: &str) -> String {
    s.replace('|', "\\|")
}

/// A short rendering of an expression for documentation (long ones are summarised).
fn short(e: Expr) -> String {
    let s = e.to_string();
    if s.chars().count() <= 120 {
        format!("`{s}`")
    } else {
        format!(
            "an expression of {} operations",
            Expr::op_count(&[e]).total()
        )
    }
}

fn module_doc(p: &Problem, opts: &EmitOptions, stats: &EmitStats) -> Vec<String> {
    let n = &p.names;
    let mut d = vec![
        format!(
            " Linearized equations of motion of `{}`: `ẋ = A x + B u`, `y = C x + D u`, `q = Phys x`,",
            p.model
        ),
        format!(
            " with every parameter symbolic, in `{}` (generated by eom-codegen {}; do not edit).",
            opts.precision.type_name(),
            env!("CARGO_PKG_VERSION")
        ),
        String::new(),
    ];
    let list = |names: &[String], units: &[String]| -> String {
        names
            .iter()
            .enumerate()
            .map(|(k, s)| match units.get(k).filter(|u| !u.is_empty()) {
                Some(u) => format!("`{s}` ({u})"),
                None => format!("`{s}`"),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    d.push(format!(
        " * states ({}): {}",
        n.states.len(),
        list(&n.states, &[])
    ));
    d.push(format!(
        " * inputs ({}): {}",
        n.inputs.len(),
        list(&n.inputs, &n.input_units)
    ));
    d.push(format!(
        " * outputs ({}): {}",
        n.outputs.len(),
        list(&n.outputs, &n.output_units)
    ));
    d.push(format!(
        " * bodies ({}, six physical coordinates each): {}",
        n.bodies.len(),
        list(&n.bodies, &[])
    ));
    if !opts.notes.is_empty() {
        d.push(String::new());
        d.extend(opts.notes.iter().map(|l| format!(" {l}")));
    }
    if opts.discrete {
        d.push(String::new());
        d.push(" `eval_discrete` gives the zero-order-hold `Ad = e^{A h}`, `Bd = ∫₀ʰ e^{A t} dt B` at a sample time `h` (scaling and squaring with a Padé approximant sized by the norm, Higham 2005; no allocation, the caller's `DiscreteWork`).".into());
    }
    d.push(String::new());
    d.push(" # Parameters".into());
    d.push(String::new());
    d.extend(param_table(p));
    if !p.fixed.is_empty() {
        d.push(String::new());
        let f: Vec<String> = p
            .fixed
            .iter()
            .map(|(k, v)| format!("`{k}` = {v:?}"))
            .collect();
        d.push(format!(
            " Fixed at generation time (partial evaluation): {}.",
            f.join(", ")
        ));
    }
    d.push(String::new());
    d.push(" # Validity region".into());
    d.push(String::new());
    d.extend(validity_doc(p));
    d.push(String::new());
    d.push(" # Cost".into());
    d.push(String::new());
    d.push(format!(
        " The DAG of A, B, C, D has {} unique nodes and {} operations ({} add, {} mul, {} div, {} functions, {} powers).",
        stats.dag_nodes_abcd,
        stats.dag_ops_abcd.total(),
        stats.dag_ops_abcd.add,
        stats.dag_ops_abcd.mul,
        stats.dag_ops_abcd.div,
        stats.dag_ops_abcd.func,
        stats.dag_ops_abcd.pow
    ));
    for f in &stats.functions {
        d.push(format!(
            " * `{}`: {} operations ({} add, {} mul, {} div, {} sqrt, {} calls), {} distinct checks, {} stores, {} chunk(s).",
            f.name,
            f.ops.total(),
            f.ops.add,
            f.ops.mul,
            f.ops.div,
            f.ops.sqrt,
            f.ops.func,
            f.distinct_checks,
            f.stores,
            f.chunks
        ));
    }
    d
}

pub(crate) fn param_table(p: &Problem) -> Vec<String> {
    let mut d = vec![
        " | # | name | nominal | unit | description |".to_string(),
        " |---|---|---|---|---|".to_string(),
    ];
    for (k, q) in p.params.iter().enumerate() {
        d.push(format!(
            " | {k} | `{}` | {:?} | {} | {} |",
            q.name,
            q.nominal,
            escape_md(&q.unit),
            escape_md(&q.description)
        ));
    }
    d
}

pub(crate) fn validity_doc(p: &Problem) -> Vec<String> {
    if p.checks.is_empty() {
        return vec![
            " No pivot depends on the parameters: the formulas hold wherever they are finite."
                .into(),
        ];
    }
    let mut d = vec![
        format!(
            " The formulas come from an elimination whose pivots were chosen at the nominal point. They hold where these {} checks hold (`PIVOT_TOLERANCE` = {:e}, `RANK_TOLERANCE` = {:e}); every evaluation function tests them and returns `Error::Validity` naming the first that fails. The margin is the ratio at the nominal point.",
            p.checks.len(),
            eom_model::reduce::PIVOT_TOLERANCE,
            eom_model::reduce::RANK_TOLERANCE
        ),
        String::new(),
    ];
    for (k, c) in p.checks.iter().enumerate() {
        let kind = if c.pivot {
            format!(
                "pivot {} with {} row entr{}: `|pivot| ≥ PIVOT_TOLERANCE·max(|pivot|, |entries|)`, margin {:.3e}",
                short(c.value),
                c.others.len(),
                if c.others.len() == 1 { "y" } else { "ies" },
                c.nominal_ratio
            )
        } else {
            format!(
                "negligible {} against {} entr{}: `|value| ≤ RANK_TOLERANCE·max|entries|`, ratio {:.3e}",
                short(c.value),
                c.others.len(),
                if c.others.len() == 1 { "y" } else { "ies" },
                c.nominal_ratio
            )
        };
        d.push(format!(" {k}. {}: {kind}", c.what));
    }
    d
}

pub(crate) fn str_array(v: &[String]) -> TokenStream {
    quote!([#(#v),*])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_too_large_for_the_generated_error_are_an_error_not_a_truncation() {
        assert_eq!(
            index_fits(7, u16::MAX, || "rows of A".into()).expect("fits"),
            7u16
        );
        let max = u16::MAX as usize;
        assert_eq!(
            index_fits(max, u16::MAX, || "rows of A".into()).expect("fits"),
            u16::MAX
        );
        let e = index_fits(max + 1, u16::MAX, || "rows of A".into()).expect_err("too large");
        assert!(
            matches!(&e, CodegenError::TooLarge { what, count, max: 65535 } if what == "rows of A" && *count == max + 1),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "rows of A: 65536 exceeds 65535, the most the generated `Error` can index"
        );
        if let Some(over) = (u32::MAX as usize).checked_add(1) {
            let e = index_fits(over, u32::MAX, || "validity checks".into()).expect_err("too large");
            assert!(matches!(e, CodegenError::TooLarge { .. }), "{e:?}");
        }
    }
}
