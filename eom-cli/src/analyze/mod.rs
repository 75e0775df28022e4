//! `eom analyze`: the linear analysis of one model at one point — modes, the minimal
//! realization with every removed mode accounted for, steady-state gains, transmission zeros
//! and, on request, the frequency response.
//!
//! Where this differs from the EoM software's `analyze` (docs/method.md §9): the mode table is
//! that of the whole state-space model, not of its minimal realization, so no mode is hidden;
//! every mode the minimal realization removes is listed with the reason (uncontrollable or
//! unobservable) and its stability; a real pole shows its corner frequency instead of 0 Hz;
//! integrating input/output pairs are reported as such instead of by a low-frequency value.
//!
//! The steps live in submodules: [`report`] (the serialized parts), [`minimal`] (the minimal
//! realization and its removed modes), [`response`] (gains and frequency response); this file
//! holds the options, the [`Analysis`] itself and the linearize/analyze driver.

mod minimal;
mod report;
mod response;
#[cfg(test)]
mod tests;

use crate::error::CliError;
use crate::format::{ReIm, eigenvalue, g, re_im};
use crate::params::ModelChoice;
use crate::shown_warning::ShownWarning;
use crate::timing::step;
use eom_model::ModelError;
use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use eom_num::gain::{GainOptions, steady_state_gain_with};
use eom_num::minreal::{MinrealOptions, minimal_realization_with_eigenvalues};
use eom_num::modes::{ModeOptions, Modes};
use eom_num::zeros::transmission_zeros;
use minimal::minimal_view;
use num_complex::Complex64;
pub use report::*;
use response::{frequency_response, gain_entries};
use serde::Serialize;

/// Significant digits of the text tables.
pub(crate) const SIG: usize = 6;

/// Width at which lists are wrapped.
pub(crate) const WIDTH: usize = 100;

/// What to compute besides the always-present parts.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyzeOptions {
    /// Reduction method.
    pub method: Method,
    /// Frequency response, when asked for.
    pub freq: Option<FreqRequest>,
    /// Eigenvalue sensitivities to every parameter.
    pub sensitivity: bool,
}

/// The frequency grid asked for on the command line.
#[derive(Clone, Debug, PartialEq)]
pub struct FreqRequest {
    /// `LOW:HIGH` in Hz (`None`: from the eigenvalues).
    pub range: Option<(f64, f64)>,
    /// Total number of logarithmically spaced points (`None`: 200 per decade).
    pub points: Option<usize>,
}

/// Everything `eom analyze` reports; serialized as the JSON output and rendered as text.
#[derive(Clone, Debug, Serialize)]
pub struct Analysis {
    /// Model name as given.
    pub model: String,
    /// `symbolic`, `numeric` or `robust`.
    pub method: &'static str,
    /// Every parameter with the value used, in catalogue order.
    #[serde(serialize_with = "ordered_map")]
    pub parameters: Vec<(String, f64)>,
    /// Units of the parameters, in the same order.
    #[serde(serialize_with = "ordered_map")]
    pub parameter_units: Vec<(String, String)>,
    /// Number of states of the reduced state-space model.
    pub states: usize,
    /// Names of the states.
    pub state_names: Vec<String>,
    /// Inputs with units.
    pub inputs: Vec<Signal>,
    /// Outputs with units.
    pub outputs: Vec<Signal>,
    /// Every eigenvalue of the state-space model, sorted by real part, then imaginary part.
    pub eigenvalues: Vec<ReIm>,
    /// The zero eigenvalues the model's structure proves, exactly zero: what each one is (a
    /// coordinate on which nothing depends, or a pair of which only the difference acts).
    pub structural_zeros: Vec<String>,
    /// `stable` (every mode decays, the structural zeros aside), `marginal` (none grows, some
    /// do not decay) or `unstable`.
    pub stability: &'static str,
    /// Whether the model is stable in this sense (as `eom sweep` decides it).
    pub stable: bool,
    /// One entry per eigenvalue, in the order of `eigenvalues`.
    pub modes: Vec<ModeReport>,
    /// The input/output view (`null` with a warning if it could not be computed, or with
    /// `minimal_note` when there is nothing to compute).
    pub minimal: Option<MinimalReport>,
    /// Why the minimal realization was not computed although nothing failed: a model without
    /// inputs or without outputs has an empty minimal realization (every mode is hidden from
    /// them), which is said instead of listing every mode as removed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub minimal_note: Option<String>,
    /// Per output/input pair (`null` with a warning if it could not be computed).
    pub steady_state_gain: Option<Vec<GainEntry>>,
    /// Transmission zeros of the minimal realization, sorted by (re, im); `null` when not
    /// defined (no inputs or no outputs) or not computable (see `warnings`).
    pub zeros: Option<Vec<ReIm>>,
    /// Warnings of the linearization and of the analyses (JSON: objects with `kind`, `item`
    /// and `message`).
    pub warnings: Vec<ShownWarning>,
    /// The frequency response (only with `--freq`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frequency_response: Option<FreqReport>,
    /// The wings (only for models with wings): each one's damping matrix in model axes at its
    /// point and the reduced frequency β = |Im λ|·c/V of every oscillatory mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wings: Option<Vec<crate::wings::WingReport>>,
    /// `∂λ/∂p` of every eigenvalue (only with `--sensitivity`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensitivity: Option<Vec<SensitivityReport>>,
    /// The static preloads at the point: every constraint and elastic item's force and moment
    /// on its first body (`null` with a warning if they could not be computed).
    pub preloads: Option<crate::preloads::Preloads>,
    /// The state-space matrices at the point, `ẋ = A x + B u`, `y = C x + D u`, with the
    /// names of their rows and columns.
    pub matrices: Matrices,
}

/// Linearizes the model at the point.
///
/// With [`Method::Symbolic`] the model is reduced with pivots chosen at the catalogue defaults
/// and evaluated at the requested point, so a point outside the symbolic validity region is an
/// error ([`eom_model::ModelError::PivotBreakdown`]); the other methods reduce at the point.
pub fn linearize(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    method: Method,
) -> Result<eom_model::Linearization, CliError> {
    let ov: Vec<(&str, f64)> = overrides.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    // Building at the point validates the names and values (positive masses, …).
    let at_point = step("build model", || choice.build(overrides))?;
    step("linearize", || linearize_at(choice, &ov, method, at_point))
}

fn linearize_at(
    choice: &ModelChoice,
    ov: &[(&str, f64)],
    method: Method,
    at_point: eom_model::Model<eom_sym::Expr>,
) -> Result<eom_model::Linearization, CliError> {
    Ok(match method {
        Method::Symbolic => {
            let nominal = choice.build(&[])?;
            Linearizer::new(&nominal)
                .at(ov)
                .method(Method::Symbolic)
                .run()
                .map_err(|e| match e {
                    ModelError::PivotBreakdown { .. } => CliError::OutsideSymbolicRegion {
                        source: Box::new(e),
                        alternatives: working_methods(&at_point),
                    },
                    e => with_alternatives(e, Method::Symbolic, &at_point),
                })?
        }
        m => Linearizer::new(&at_point)
            .method(m)
            .run()
            .map_err(|e| with_alternatives(e, m, &at_point))?,
    })
}

/// A reduction that failed for a reason another method may not share (a singular reduced
/// mass matrix, a feature this method does not support): the error with the methods that
/// were tried at the point and work. Errors of the model itself pass unchanged.
fn with_alternatives(
    e: ModelError,
    failed: Method,
    at_point: &eom_model::Model<eom_sym::Expr>,
) -> CliError {
    if e.is_method_failure() {
        CliError::MethodFailed {
            source: Box::new(e),
            method: method_name(failed),
            alternatives: working_methods(at_point)
                .into_iter()
                .filter(|m| *m != method_name(failed))
                .collect(),
        }
    } else {
        CliError::Model(e)
    }
}

/// Every analysis of a linearization of the model at the point.
pub fn analyze_linearized(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    opts: &AnalyzeOptions,
    lin: &eom_model::Linearization,
) -> Result<Analysis, CliError> {
    let at_point = choice.build(overrides)?;
    let warnings = ShownWarning::all_of_model(&lin.warnings, "linearization: ");
    let mut r = analyze_state_space(
        &lin.state_space,
        warnings,
        opts.freq.as_ref(),
        lin.structural_zeros.len(),
    )?;
    r.structural_zeros = lin.structural_zeros.clone();
    r.model = choice.name.clone();
    r.method = method_name(lin.method);
    r.parameters = choice.values(overrides);
    r.parameter_units = choice
        .params
        .iter()
        .map(|p| (p.name.clone(), p.unit.clone()))
        .collect();
    if opts.sensitivity {
        r.sensitivity = Some(sensitivity_report(choice, overrides)?);
    }
    let eigenvalues: Vec<Complex64> = r
        .eigenvalues
        .iter()
        .map(|z| Complex64::new(z.re, z.im))
        .collect();
    let numeric = at_point.nominal()?;
    r.preloads = match eom_model::assemble(&numeric) {
        Ok(a) => Some(eom_model::preloads::Preloads::of(&numeric, &a)),
        Err(e) => {
            r.warnings.push(ShownWarning::new(
                "not_computed",
                format!("static preloads not computed: {e}"),
            ));
            None
        }
    };
    r.wings = crate::wings::wing_reports(&numeric, &eigenvalues, &mut r.warnings);
    Ok(r)
}

/// The methods that reduce the model at the point, tried before suggesting them (a
/// suggestion that cannot work is worse than none).
fn working_methods(at_point: &eom_model::Model<eom_sym::Expr>) -> Vec<&'static str> {
    [(Method::Numeric, "numeric"), (Method::Robust, "robust")]
        .into_iter()
        .filter(|(m, _)| Linearizer::new(at_point).method(*m).run().is_ok())
        .map(|(_, name)| name)
        .collect()
}

/// Receives from `rx` without blocking a thread of the pool: while the value is not there,
/// the thread runs the pool's other jobs (the parallel kernels of the step that will send
/// it). A worker blocked in `recv` could neither help that step nor, had another worker
/// taken the wait as a job while itself inside that step, ever let it finish. `None` once
/// the sender is gone.
fn receive_helping<T>(rx: &std::sync::mpsc::Receiver<T>) -> Option<T> {
    use std::sync::mpsc::TryRecvError;
    loop {
        match rx.try_recv() {
            Ok(v) => return Some(v),
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) => {
                if rayon::yield_now() != Some(rayon::Yield::Executed) {
                    std::thread::sleep(std::time::Duration::from_micros(200));
                }
            }
        }
    }
}

/// The modes as reported: no mode shapes (nothing here shows them).
fn mode_options() -> ModeOptions {
    ModeOptions {
        shapes: false,
        ..ModeOptions::default()
    }
}

/// The analyses of a state-space model (model name, method and parameters left empty).
fn analyze_state_space(
    ss: &StateSpace<f64>,
    mut warnings: Vec<ShownWarning>,
    freq: Option<&FreqRequest>,
    structural_zeros: usize,
) -> Result<Analysis, CliError> {
    let opts = ModeOptions {
        structural_zeros,
        ..mode_options()
    };
    let n = &ss.names;
    let inputs = signals(ss.inputs(), &n.inputs, &n.input_units, "input");
    let outputs = signals(ss.outputs(), &n.outputs, &n.output_units, "output");
    // Each analysis is a dense O(n³) step on a large model, and all are independent but the
    // zeros, which are those of the minimal realization: two chains, one per core, and
    // within each step faer's parallel kernels on the pool's threads (a thread whose chain
    // is done helps the other's). The minimal realization's PBH pass needs the eigenvalues
    // the modes compute: they are sent over, and waited for only after its staircases and
    // the zeros of their result (the sender is dropped, and the pass computes them itself,
    // if the modes fail).
    let (eig_tx, eig_rx) = std::sync::mpsc::channel::<Vec<Complex64>>();
    let ((modes, gain), (reduced, zeros)) = rayon::join(
        move || {
            let modes = step("modes", || Modes::compute_with(ss, &opts));
            if let Ok(m) = &modes {
                // The receiver may be gone (the pass did not need them): nothing to do then.
                let _ = eig_tx.send(m.eigenvalues());
            }
            drop(eig_tx);
            // The zero eigenvalues the structure proves (counted on the elimination path's
            // matrix) inform the rank decision on the robust path's A, which hides them in
            // rounding.
            let gain_opts = GainOptions {
                structural_zeros,
                ..GainOptions::default()
            };
            (
                modes,
                step("gains", || steady_state_gain_with(ss, &gain_opts)),
            )
        },
        move || {
            let want_zeros = ss.inputs() > 0 && ss.outputs() > 0;
            if !want_zeros {
                // The receiver is dropped: the modes' thread sends into nothing.
                return (None, None);
            }
            // While the PBH pass waits for the eigenvalues, the zeros of the staircases'
            // draft: they are the minimal system's when the pass removes nothing.
            let draft_zeros = std::sync::Mutex::new(None);
            let slot = &draft_zeros;
            let reduced = step("minimal realization", || {
                minimal_realization_with_eigenvalues(
                    ss,
                    &MinrealOptions::default(),
                    move |draft: &StateSpace<f64>| {
                        // Nothing removed yet: the result would be the model itself, whose
                        // zeros come faster than those of its staircase form.
                        let sys = if draft.states() == ss.states() {
                            ss
                        } else {
                            draft
                        };
                        let z = want_zeros.then(|| step("zeros", || transmission_zeros(sys)));
                        let ev = receive_helping(&eig_rx);
                        *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some((draft.states(), z));
                        ev
                    },
                )
            });
            let draft_zeros = draft_zeros.into_inner().unwrap_or_else(|e| e.into_inner());
            let zeros = match (draft_zeros, &reduced) {
                (Some((k, z)), Ok((m, _))) if k == m.states() => z,
                _ => want_zeros.then(|| {
                    step("zeros", || match &reduced {
                        Ok((m, _)) => transmission_zeros(m),
                        Err(e) => Err(e.clone()),
                    })
                }),
            };
            (Some(reduced), zeros)
        },
    );
    let modes = modes?;
    warnings.extend(accuracy_warnings(&modes));
    let minimal_note = reduced.is_none().then(|| no_signals_note(ss));
    let minimal = match reduced.as_ref().map(|r| {
        r.as_ref()
            .map_err(|e| CliError::Num(e.clone()))
            .and_then(|(ssm, rep)| minimal_view(ssm, rep, &modes, &mut warnings))
    }) {
        None => None,
        Some(Ok(m)) => Some(m),
        Some(Err(e)) => {
            warnings.push(ShownWarning::new(
                "not_computed",
                format!("minimal realization not computed: {e}"),
            ));
            None
        }
    };
    let steady_state_gain = match gain
        .map_err(CliError::from)
        .map(|g| gain_entries(&g, &inputs, &outputs, &mut warnings))
    {
        Ok(g) => Some(g),
        Err(e) => {
            warnings.push(ShownWarning::new(
                "not_computed",
                format!("steady-state gains not computed: {e}"),
            ));
            None
        }
    };
    let zeros = match zeros {
        None => None,
        Some(Ok(z)) => Some(re_im(&z)),
        Some(Err(e)) => {
            warnings.push(ShownWarning::new(
                "not_computed",
                format!("transmission zeros not computed: {e}"),
            ));
            None
        }
    };
    let frequency_response = match freq {
        Some(req) => Some(frequency_response(ss, req, &inputs, &outputs)?),
        None => None,
    };
    let matrices = Matrices::of(ss, &inputs, &outputs);
    Ok(Analysis {
        matrices,
        preloads: None,
        model: String::new(),
        method: "",
        parameters: Vec::new(),
        parameter_units: Vec::new(),
        states: ss.states(),
        state_names: ss.names.states.clone(),
        inputs,
        outputs,
        eigenvalues: re_im(&modes.eigenvalues()),
        stability: overall_stability(&modes, structural_zeros),
        stable: overall_stability(&modes, structural_zeros) == "stable",
        modes: modes.modes.iter().map(mode_report).collect(),
        minimal,
        minimal_note,
        steady_state_gain,
        zeros,
        warnings,
        frequency_response,
        wings: None,
        sensitivity: None,
        structural_zeros: Vec::new(),
    })
}

/// Why a model without inputs or outputs has no minimal realization to show.
fn no_signals_note(ss: &StateSpace<f64>) -> String {
    let missing = match (ss.inputs(), ss.outputs()) {
        (0, 0) => "no inputs and no outputs",
        (0, _) => "no inputs",
        _ => "no outputs",
    };
    format!(
        "not computed: the model has {missing}, so its minimal realization is empty (every one \
         of its {} states is hidden from the inputs and outputs); add an actuator and a sensor \
         to see which modes they reach",
        ss.states()
    )
}

/// Eigenvalues whose estimated relative accuracy (`Mode::accuracy`) is worse than this are
/// reported.
pub const ACCURACY_WARNING: f64 = 1e-6;

/// A warning per eigenvalue (one of each conjugate pair) that the rounding of A's entries
/// alone makes uncertain beyond [`ACCURACY_WARNING`] of itself.
fn accuracy_warnings(modes: &Modes) -> Vec<ShownWarning> {
    modes
        .distinct()
        .filter(|m| m.accuracy > ACCURACY_WARNING)
        .map(|m| {
            let message = format!(
                "eigenvalue {}: accurate to only about {} of itself: rounding the state \
                 matrix's entries alone moves it that much (scales differing widely, e.g. one \
                 element far stiffer or softer than the others)",
                eigenvalue(m.eigenvalue, 6, m.eigenvalue.im != 0.0),
                g(m.accuracy, 2)
            );
            ShownWarning::new("eigenvalue_accuracy", message)
        })
        .collect()
}
