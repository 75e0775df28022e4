//! `eom reduce`: a reduced model of the dynamics that matter, with its error — the Hankel
//! singular values, the bound `2 Σ σ` per order, the error measured on a frequency grid and at
//! DC, the modes kept (with the full model's eigenvalue each one stands for), the reduced
//! matrices.

use crate::analyze::{Matrices, SIG, kind_name, linearize, stability_name};
use crate::error::CliError;
use crate::format::{ReIm, eigenvalue, g, table};
use crate::params::ModelChoice;
use crate::shown_warning::ShownWarning;
use eom_model::Method;
use eom_num::NumError;
use eom_num::model_reduction::{MeasuredError, ReducedModel, Reducer, ReductionMethod};
use eom_num::modes::{ModeKind, ModeOptions, Modes};
use num_complex::Complex64;
use serde::Serialize;

/// What `eom reduce` was asked.
#[derive(Clone, Debug)]
pub struct ReduceRequest {
    /// How the stable part is reduced.
    pub method: ReductionMethod,
    /// States in all (`--order`).
    pub order: Option<usize>,
    /// Largest bound (`--tol`).
    pub tol: Option<f64>,
    /// Band of modal truncation in Hz (`--band`).
    pub band: Option<(f64, f64)>,
    /// The linearization's method.
    pub linearization: Method,
}

/// One mode of the reduced model.
#[derive(Clone, Debug, Serialize)]
pub struct KeptMode {
    /// Its eigenvalue in the reduced model, 1/s.
    pub eigenvalue: ReIm,
    /// The full model's eigenvalue nearest to it.
    pub full_eigenvalue: ReIm,
    /// `|λ|/2π` in Hz (of the reduced eigenvalue).
    pub natural_frequency_hz: f64,
    /// `−Re λ/|λ|`, `null` for a zero mode.
    pub damping_ratio: Option<f64>,
    /// `zero`, `real` or `oscillatory`.
    pub kind: &'static str,
    /// `stable`, `marginal` or `unstable`.
    pub stability: &'static str,
    /// `kept whole` (structural zero, zero, marginal or unstable mode) or `reduced`.
    pub origin: &'static str,
    /// The body coordinate the full model's mode moves most (`body.rx`), if any.
    pub moves_most: Option<String>,
}

/// The bound at one order.
#[derive(Clone, Debug, Serialize)]
pub struct OrderBound {
    /// States in all.
    pub states: usize,
    /// `2 Σ σ` beyond it.
    pub bound: f64,
}

/// The report of `eom reduce`.
#[derive(Clone, Debug, Serialize)]
pub struct ReduceReport {
    /// The model's name.
    pub model: String,
    /// The parameter values.
    pub parameters: Vec<(String, f64)>,
    /// `balanced`, `matchdc` or `modal`.
    pub method: ReductionMethod,
    /// States of the full model.
    pub full_states: usize,
    /// States of the reduced model.
    pub states: usize,
    /// States kept whole (zero, marginal and unstable modes).
    pub kept_whole: usize,
    /// Of those, structural zeros.
    pub structural_zeros: usize,
    /// Hankel singular values of the stable part.
    pub hankel_singular_values: Vec<f64>,
    /// Stable states above rounding.
    pub numerical_order: usize,
    /// The bound `2 Σ σ` at this order (balanced, matchdc).
    pub bound: Option<f64>,
    /// The bound at every order.
    pub bounds: Vec<OrderBound>,
    /// The error measured on a frequency grid.
    pub measured: MeasuredError,
    /// The modes of the reduced model.
    pub modes: Vec<KeptMode>,
    /// The reduced model's A, B, C, D with the state, input and output names.
    pub matrices: Matrices,
    /// Warnings of the linearization and the reduction (JSON: objects with `kind`, `item` and
    /// `message`).
    pub warnings: Vec<ShownWarning>,
}

/// Maps the reducer's option errors onto the command line's options.
fn option_error(e: NumError) -> CliError {
    match e {
        NumError::InvalidOption(problem) => CliError::BadArgument {
            argument: "--order/--tol/--band/--method".into(),
            problem: problem.to_string(),
        },
        e => e.into(),
    }
}

/// Runs the reduction of `ss` that `req` asks for.
pub fn reduce_state_space(
    ss: &eom_num::StateSpace<f64>,
    req: &ReduceRequest,
) -> Result<ReducedModel, CliError> {
    let mut r = Reducer::new(ss).method(req.method);
    if let Some(k) = req.order {
        r = r.order(k);
    }
    if let Some(t) = req.tol {
        r = r.tolerance(t);
    }
    if let Some((lo, hi)) = req.band {
        r = r.band_hz(lo, hi);
    }
    r.run().map_err(option_error)
}

/// `eom reduce MODEL`.
pub fn reduce(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    req: &ReduceRequest,
) -> Result<(ReduceReport, ReducedModel), CliError> {
    let lin = linearize(choice, overrides, req.linearization)?;
    report_of(choice, overrides, &lin, req)
}

/// The reduction of a linearization and its report (`eom reduce`, `eom analyze --reduce`,
/// the report's section).
pub fn report_of(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    lin: &eom_model::Linearization,
    req: &ReduceRequest,
) -> Result<(ReduceReport, ReducedModel), CliError> {
    let ss = &lin.state_space;
    let red = reduce_state_space(ss, req)?;
    let full = Modes::compute_with(
        ss,
        &ModeOptions {
            structural_zeros: lin.structural_zeros.len(),
            ..ModeOptions::default()
        },
    )?;
    let reduced = Modes::compute_with(
        &red.state_space,
        &ModeOptions {
            shapes: false,
            ..ModeOptions::default()
        },
    )?;
    let modes = kept_modes(&red, &full, &reduced, ss);
    let mut warnings = ShownWarning::all_of_model(&lin.warnings, "");
    warnings.extend(red.warnings.iter().map(|w| ShownWarning::of_num(w, "")));
    let parameters = choice
        .params
        .iter()
        .map(|p| {
            let v = overrides
                .iter()
                .rev()
                .find(|(k, _)| *k == p.name)
                .map_or(p.default, |x| x.1);
            (p.name.clone(), v)
        })
        .collect();
    let rs = &red.state_space;
    let report = ReduceReport {
        model: choice.name.clone(),
        parameters,
        method: red.method,
        full_states: red.full_states,
        states: red.order(),
        kept_whole: red.kept,
        structural_zeros: red.structural_zeros,
        hankel_singular_values: red.hankel.clone(),
        numerical_order: red.numerical_order,
        bound: red.bound,
        bounds: red
            .bounds()
            .into_iter()
            .map(|(states, bound)| OrderBound { states, bound })
            .collect(),
        measured: red.error,
        modes,
        matrices: Matrices::named_by(rs, ss.names.inputs.clone(), ss.names.outputs.clone()),
        warnings,
    };
    Ok((report, red))
}

/// The reduced model's modes, each with the nearest mode of the full model (the kept ones are
/// the full model's own) and the body coordinate that mode moves most.
fn kept_modes(
    red: &ReducedModel,
    full: &Modes,
    reduced: &Modes,
    ss: &eom_num::StateSpace<f64>,
) -> Vec<KeptMode> {
    let kept_eigs: Vec<Complex64> = {
        let a = red
            .state_space
            .a
            .view((0, 0), (red.kept, red.kept))
            .clone_owned();
        eom_num::modes::eigenvalues(&a).unwrap_or_default()
    };
    let mut used = vec![false; full.modes.len()];
    let mut out = Vec::new();
    for m in reduced.distinct() {
        let z = m.eigenvalue;
        let nearest = full
            .modes
            .iter()
            .enumerate()
            .filter(|(k, f)| !used[*k] && f.eigenvalue.im >= 0.0)
            .min_by(|a, b| {
                (a.1.eigenvalue - z)
                    .norm()
                    .total_cmp(&(b.1.eigenvalue - z).norm())
            });
        let (fz, moves) = match nearest {
            Some((k, f)) => {
                used[k] = true;
                let coord = f.reference_index.and_then(|i| {
                    let body = ss.names.bodies.get(i / 6)?;
                    Some(format!(
                        "{body}.{}",
                        ["x", "y", "z", "rx", "ry", "rz"][i % 6]
                    ))
                });
                (f.eigenvalue, coord)
            }
            None => (Complex64::new(f64::NAN, f64::NAN), None),
        };
        let kept = kept_eigs
            .iter()
            .any(|k| (k - z).norm() <= 1e-9 * z.norm().max(1e-300))
            || (m.kind == ModeKind::Zero && red.kept > 0);
        out.push(KeptMode {
            eigenvalue: z.into(),
            full_eigenvalue: fz.into(),
            natural_frequency_hz: m.natural_frequency_hz,
            damping_ratio: m.damping_ratio,
            kind: kind_name(m.kind),
            stability: stability_name(m.stability),
            origin: if kept { "kept whole" } else { "reduced" },
            moves_most: moves,
        });
    }
    out
}

impl ReduceReport {
    /// The table of the reduced model's modes.
    pub fn modes_table(&self) -> (Vec<&'static str>, Vec<Vec<String>>) {
        let rows = self
            .modes
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let pair = m.kind == "oscillatory";
                let z = Complex64::new(m.eigenvalue.re, m.eigenvalue.im);
                let f = Complex64::new(m.full_eigenvalue.re, m.full_eigenvalue.im);
                vec![
                    (k + 1).to_string(),
                    eigenvalue(z, SIG, pair),
                    g(m.natural_frequency_hz, SIG),
                    m.damping_ratio.map_or("-".into(), |d| g(d, SIG)),
                    format!("{} {}", m.stability, m.kind),
                    m.origin.to_string(),
                    eigenvalue(f, SIG, pair),
                    m.moves_most.clone().unwrap_or_else(|| "-".into()),
                ]
            })
            .collect();
        (
            vec![
                "#",
                "eigenvalue [1/s]",
                "freq [Hz]",
                "damping",
                "kind",
                "origin",
                "full model's",
                "moves most",
            ],
            rows,
        )
    }

    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let mut t = format!(
            "Model {} reduced by {} from {} to {} states\n",
            self.model,
            match self.method {
                ReductionMethod::Balanced => "balanced truncation",
                ReductionMethod::MatchDc => "balanced singular perturbation (DC gain matched)",
                ReductionMethod::Modal => "modal truncation",
            },
            self.full_states,
            self.states
        );
        let params: Vec<String> = self
            .parameters
            .iter()
            .map(|(n, v)| format!("{n} = {}", g(*v, SIG)))
            .collect();
        t.push_str(&crate::format::wrap_list(
            "Parameters:",
            &params,
            crate::analyze::WIDTH,
        ));
        t.push_str(&format!(
            "Kept whole: {} state(s) — zero, marginal and unstable modes ({} structural zero(s)); \
             the stable part ({} states) is reduced\n\n",
            self.kept_whole,
            self.structural_zeros,
            self.full_states - self.kept_whole
        ));
        t.push_str(&self.hankel_text());
        t.push_str(&self.error_text());
        t.push_str("Modes of the reduced model\n");
        let (head, rows) = self.modes_table();
        t.push_str(&table(&head, &rows, 2));
        t.push_str(&format!(
            "\nReduced states: {}\n\nWarnings\n",
            self.matrices.states.join(", ")
        ));
        if self.warnings.is_empty() {
            t.push_str("  none\n");
        }
        for w in &self.warnings {
            t.push_str(&format!("  - {w}\n"));
        }
        t
    }

    fn hankel_text(&self) -> String {
        let s = &self.hankel_singular_values;
        let mut t = format!(
            "Hankel singular values of the stable part ({}, {} above rounding n·ε·σ₁)\n",
            s.len(),
            self.numerical_order
        );
        let shown = self.numerical_order.min(s.len());
        let rows: Vec<Vec<String>> = self
            .bounds
            .iter()
            .skip(1)
            .take(shown)
            .enumerate()
            .map(|(i, b)| {
                let mark = if b.states == self.states { " <" } else { "" };
                vec![
                    (i + 1).to_string(),
                    g(s[i], SIG),
                    format!("{}{mark}", b.states),
                    g(b.bound, SIG),
                ]
            })
            .collect();
        t.push_str(&table(
            &["#", "sigma", "order", "bound 2·Σσ beyond"],
            &rows,
            2,
        ));
        if s.len() > shown {
            t.push_str(&format!(
                "  ({} more below rounding: uncontrollable or unobservable to working precision)\n",
                s.len() - shown
            ));
        }
        t.push('\n');
        t
    }

    fn error_text(&self) -> String {
        let e = &self.measured;
        let mut t = String::from("Error of the reduced model (G − G_r, largest singular value)\n");
        match self.bound {
            Some(b) => t.push_str(&format!("  bound 2·Σσ beyond the order: {}\n", g(b, SIG))),
            None => t.push_str("  bound: none (modal truncation has no a-priori bound)\n"),
        }
        t.push_str(&format!(
            "  measured H∞: {} at {} Hz ({} frequencies)\n  DC gain error: {}\n",
            g(e.hinf, SIG),
            g(e.at_hz, SIG),
            e.points,
            g(e.dc, SIG)
        ));
        if let Some(s1) = self.hankel_singular_values.first().filter(|s| **s > 0.0) {
            t.push_str(&format!(
                "  relative to σ₁ = {}: measured {}\n",
                g(*s1, SIG),
                g(e.hinf / s1, 3)
            ));
        }
        t.push('\n');
        t
    }
}
