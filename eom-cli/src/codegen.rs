//! `eom codegen`: the symbolic state-space model of a built-in model as a Rust module, by
//! `eom_codegen::emit_model` (cargo feature `codegen`, on by default). A build without the
//! feature has the subcommand, which then reports that code generation is not available.

use crate::error::CliError;
use crate::params::ModelChoice;
use std::path::Path;

/// What to generate.
#[derive(Clone, Debug, PartialEq)]
pub struct CodegenRequest {
    /// `f32` instead of `f64`.
    pub f32: bool,
    /// Code that compiles under `#![no_std]` (elementary functions from `libm`); otherwise the
    /// inherent `std` methods are used.
    pub no_std: bool,
    /// Run the bounded simplification before lowering.
    pub simplify: bool,
    /// Use the simplification whenever it has fewer operations.
    pub simplify_always: bool,
    /// Name of the generated module (default: from the model name).
    pub module: Option<String>,
    /// Also emit the stability verdict without eigenvalues (`--stability`).
    pub stability: bool,
    /// Reduce to this many states first (bases at the nominal point, applied to A(p)…).
    pub reduce: Option<usize>,
    /// Modal instead of balanced truncation for `reduce`.
    pub reduce_modal: bool,
    /// Also emit `eval_discrete` (zero-order hold at a sample time).
    pub discrete: bool,
}

/// Generates the module for the model (with `overrides` as the nominal values, where the
/// pivots are chosen and the default of `Params::NOMINAL`), writes it to `path` (only when its
/// content changes, see [`crate::output::write_output`]) and returns the summary to print on
/// standard error.
#[cfg(feature = "codegen")]
pub fn codegen(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    req: &CodegenRequest,
    path: &Path,
) -> Result<String, CliError> {
    use eom_codegen::EmitOptions;
    let model = choice.build(overrides)?;
    let mut opts = EmitOptions::default()
        .simplify(req.simplify)
        .simplify_always(req.simplify_always)
        .stability(req.stability);
    if req.f32 {
        opts = opts.f32();
    }
    if !req.no_std {
        opts = opts.std_math();
    }
    if let Some(m) = &req.module {
        opts = opts.module(m);
    }
    opts = opts.discrete(req.discrete);
    let (emitted, note) = match req.reduce {
        None => (eom_codegen::emit_model(&model, &opts)?, String::new()),
        Some(r) => {
            use eom_num::model_reduction::ReductionMethod;
            let sym = eom_model::Linearizer::new(&model).symbolic()?;
            if opts.model_name.is_none() {
                opts.model_name = Some(model.name.clone());
            }
            let method = if req.reduce_modal {
                ReductionMethod::Modal
            } else {
                ReductionMethod::Balanced
            };
            let (e, nominal) = eom_codegen::reduced::emit_reduced(&sym, r, method, &opts).map_err(
                |e| match e {
                    eom_codegen::CodegenError::Num(eom_num::NumError::InvalidOption(problem)) => {
                        CliError::BadArgument {
                            argument: format!("--reduce {r}"),
                            problem: problem.to_string(),
                        }
                    }
                    e => e.into(),
                },
            )?;
            let note = format!(
                "reduced at the nominal point from {} to {} states by {} truncation ({} kept \
                 whole); bound 2·Σσ = {}, measured {:e}\n",
                nominal.full_states,
                nominal.order(),
                method.name(),
                nominal.kept,
                nominal.bound.map_or("none".into(), |b| format!("{b:e}")),
                nominal.error.hinf
            );
            (e, note)
        }
    };
    let written = crate::output::write_output(path, &emitted.source)?;
    Ok(summary(&emitted, path, req, written) + &note)
}

/// Without the `codegen` feature: checks the model and parameters (so that usage errors are
/// reported as such), then reports that code generation is not available.
#[cfg(not(feature = "codegen"))]
pub fn codegen(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    _req: &CodegenRequest,
    path: &Path,
) -> Result<String, CliError> {
    choice.build(overrides)?;
    Err(CliError::Unavailable(format!(
        "code generation is not available in this build of eom (built without the cargo \
         feature `codegen`, which links the eom-codegen crate); nothing was written to {}. \
         Rebuild with `cargo build -p eom-cli --features codegen`.",
        path.display()
    )))
}

/// The summary printed after writing.
#[cfg(feature = "codegen")]
fn summary(
    e: &eom_codegen::Emitted,
    path: &Path,
    req: &CodegenRequest,
    written: crate::output::Written,
) -> String {
    use eom_codegen::Simplification;
    let s = &e.stats;
    let lines = e.source.lines().count();
    let math = if req.no_std {
        "no_std, elementary functions from libm (which the consuming crate then needs)"
    } else {
        "std math"
    };
    let status = crate::output::status_line(path, written);
    let mut t = format!(
        "{}: {lines} lines, module `{}`, {}, {math}, {} validity check(s)\n",
        status.trim_end(),
        e.module,
        if req.f32 { "f32" } else { "f64" },
        s.checks,
    );
    match s.simplification {
        Simplification::Used if req.simplify_always => {
            t.push_str("simplification: used (fewer operations)\n")
        }
        Simplification::Used => {
            t.push_str("simplification: used (fewer operations, estimated faster)\n")
        }
        Simplification::NotCheaper => {
            t.push_str("simplification: run, original kept (no fewer operations)\n")
        }
        Simplification::NotFaster {
            simplified,
            original,
        } => t.push_str(&format!(
            "simplification: run, original kept (fewer operations, but a longer dependency \
             chain: cost estimate {simplified} against {original})\n"
        )),
        Simplification::NotRun => {}
    }
    if req.stability {
        t.push_str(&format!(
            "stability: `{}::stability(&p)` (Stable / Unstable / Undecided) from the \
             Liénard–Chipart conditions with rounding-error bounds\n",
            e.module
        ));
    }
    t.push_str(&format!(
        "use it with: include!(\"{}\");  // then `{}::StateSpace`, `{}::Params`, …\n",
        path.display(),
        e.module,
        e.module
    ));
    t
}
