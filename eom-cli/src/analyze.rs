//! `eom analyze`: the linear analysis of one model at one point — modes, the minimal
//! realization with every removed mode accounted for, steady-state gains, transmission zeros
//! and, on request, the frequency response.
//!
//! Where this differs from the EoM software's `analyze` (docs/method.md §9): the mode table is
//! that of the whole state-space model, not of its minimal realization, so no mode is hidden;
//! every mode the minimal realization removes is listed with the reason (uncontrollable or
//! unobservable) and its stability; a real pole shows its corner frequency instead of 0 Hz;
//! integrating input/output pairs are reported as such instead of by a low-frequency value.

use crate::error::CliError;
use crate::format::{ReIm, eigenvalue, g, re_im};
use crate::params::ModelChoice;
use crate::shown_warning::ShownWarning;
use crate::timing::step;
use eom_model::ModelError;
use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use eom_num::freq::{FreqOptions, FreqRange, FreqUnit, FrequencyResponse};
use eom_num::gain::{Gain, GainOptions, SteadyStateGain, steady_state_gain_with};
use eom_num::minreal::{
    MinrealOptions, MinrealReport, ModeStability, RankStage, RemovedKind,
    minimal_realization_with_eigenvalues,
};
use eom_num::modes::{Mode, ModeKind, ModeOptions, Modes, Stability};
use eom_num::zeros::transmission_zeros;
use num_complex::Complex64;
use serde::{Serialize, Serializer};

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

/// The numeric state-space matrices (rows of numbers) and the names of the states, inputs
/// and outputs that index them.
#[derive(Clone, Debug, Serialize)]
pub struct Matrices {
    /// The states (rows and columns of A, rows of B, columns of C).
    pub states: Vec<String>,
    /// The inputs (columns of B and D).
    pub inputs: Vec<String>,
    /// The outputs (rows of C and D).
    pub outputs: Vec<String>,
    /// A (states × states), one array per row.
    #[serde(rename = "A", serialize_with = "rows")]
    pub a: nalgebra::DMatrix<f64>,
    /// B (states × inputs).
    #[serde(rename = "B", serialize_with = "rows")]
    pub b: nalgebra::DMatrix<f64>,
    /// C (outputs × states).
    #[serde(rename = "C", serialize_with = "rows")]
    pub c: nalgebra::DMatrix<f64>,
    /// D (outputs × inputs).
    #[serde(rename = "D", serialize_with = "rows")]
    pub d: nalgebra::DMatrix<f64>,
}

impl Matrices {
    /// The matrices of `ss` with the signals' names as reported.
    fn of(ss: &StateSpace<f64>, inputs: &[Signal], outputs: &[Signal]) -> Matrices {
        Matrices::named_by(
            ss,
            inputs.iter().map(|s| s.name.clone()).collect(),
            outputs.iter().map(|s| s.name.clone()).collect(),
        )
    }

    /// The matrices of `ss` with its state names and the given input and output names.
    pub fn named_by(ss: &StateSpace<f64>, inputs: Vec<String>, outputs: Vec<String>) -> Matrices {
        Matrices {
            states: ss.names.states.clone(),
            inputs,
            outputs,
            a: ss.a.clone(),
            b: ss.b.clone(),
            c: ss.c.clone(),
            d: ss.d.clone(),
        }
    }

    /// For [`crate::matrices::write_matrices`]: `A`, `B`, `C`, `D` and the names.
    pub fn named(&self) -> crate::matrices::NamedMatrices<'_> {
        crate::matrices::NamedMatrices {
            matrices: vec![
                ("A", &self.a),
                ("B", &self.b),
                ("C", &self.c),
                ("D", &self.d),
            ],
            names: vec![
                ("states", &self.states),
                ("inputs", &self.inputs),
                ("outputs", &self.outputs),
            ],
        }
    }
}

fn rows<S: Serializer>(m: &nalgebra::DMatrix<f64>, s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(
        m.row_iter()
            .map(|r| r.iter().copied().collect::<Vec<f64>>()),
    )
}

/// The sensitivities of one eigenvalue.
#[derive(Clone, Debug, Serialize)]
pub struct SensitivityReport {
    /// The eigenvalue.
    pub eigenvalue: ReIm,
    /// Its condition number (large: nearly defective).
    pub condition: f64,
    /// `∂λ/∂p` by parameter, in catalogue order; `null` when the eigenvalue is defective or
    /// nearly so (the derivative is then unbounded).
    #[serde(serialize_with = "ordered_map_opt")]
    pub derivatives: Option<Vec<(String, ReIm)>>,
}

fn ordered_map_opt<S: serde::Serializer>(
    v: &Option<Vec<(String, ReIm)>>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match v {
        Some(v) => s.collect_map(v.iter().map(|(k, x)| (k, x))),
        None => s.serialize_none(),
    }
}

/// `∂λ/∂p` at the point, by the symbolic model reduced there (exact `∂A/∂p`).
fn sensitivity_report(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
) -> Result<Vec<SensitivityReport>, CliError> {
    let model = choice.build(overrides)?;
    let sym = Linearizer::new(&model).symbolic()?;
    let s = eom_model::sensitivities(&sym, &model.scope.nominal_values())?;
    Ok(s.eigenvalues
        .iter()
        .map(|e| SensitivityReport {
            eigenvalue: e.eigenvalue.into(),
            condition: e.condition,
            derivatives: e
                .derivatives
                .as_ref()
                .map(|d| s.params.iter().cloned().zip(re_im(d)).collect()),
        })
        .collect())
}

/// An input or output signal.
#[derive(Clone, Debug, Serialize)]
pub struct Signal {
    /// Name.
    pub name: String,
    /// Unit (may be empty).
    pub unit: String,
}

/// One mode (eigenvalue) with its modal quantities.
#[derive(Clone, Debug, Serialize)]
pub struct ModeReport {
    /// The eigenvalue in 1/s.
    pub eigenvalue: ReIm,
    /// `zero` (rigid-body or integrator mode), `real` or `oscillatory`.
    pub kind: &'static str,
    /// `|λ|/2π` in Hz (a real pole's corner frequency; 0 for a zero mode).
    pub natural_frequency_hz: f64,
    /// `−Re λ/|λ|` (±1 for a real pole; `null` for a zero mode).
    pub damping_ratio: Option<f64>,
    /// `−1/Re λ` in s (negative for a growing mode; `null` = infinite).
    pub time_constant: Option<f64>,
    /// Damped period `2π/|Im λ|` in s (EoM's "wavelength"; `null` for real and zero modes).
    pub period: Option<f64>,
    /// `stable` (Re λ < −tolerance), `marginal` (|Re λ| ≤ tolerance) or `unstable`.
    pub stability: &'static str,
    /// Whether the mode decays.
    pub stable: bool,
    /// The eigenvalue's error estimate in 1/s, the tolerance of its verdict
    /// (`eom_num::modes::error_estimate`; `eom sweep` judges by the same one).
    pub tolerance: f64,
    /// Estimated relative error of the eigenvalue from rounding the state matrix's entries
    /// (the componentwise condition number times ε; 0 for an exact zero, and where the
    /// estimate would exceed the memory limit). Above 1e-6 it is also a warning.
    pub accuracy: f64,
}

/// The minimal realization: what the inputs and outputs see.
#[derive(Clone, Debug, Serialize)]
pub struct MinimalReport {
    /// States of the minimal realization.
    pub states: usize,
    /// Its eigenvalues, sorted by (re, im).
    pub eigenvalues: Vec<ReIm>,
    /// Its modes, in the order of `eigenvalues`.
    pub modes: Vec<ModeReport>,
    /// Every mode it removed.
    pub removed: Vec<RemovedReport>,
}

/// A mode removed by the minimal realization.
#[derive(Clone, Debug, Serialize)]
pub struct RemovedReport {
    /// The eigenvalue.
    pub eigenvalue: ReIm,
    /// `uncontrollable` (the inputs cannot excite it) or `unobservable` (the outputs cannot
    /// see it).
    pub reason: &'static str,
    /// `stable`, `marginal` or `unstable`.
    pub stability: &'static str,
    /// Kind of the nearest mode of the full model (`zero`, `real`, `oscillatory`).
    pub kind: &'static str,
    /// PBH residual confirming the removal (rounding level when exactly decoupled).
    pub pbh_residual: Option<f64>,
    /// What this means, in words.
    pub note: String,
}

/// The steady-state gain of one output/input pair.
#[derive(Clone, Debug, Serialize)]
pub struct GainEntry {
    /// Output name.
    pub output: String,
    /// Input name.
    pub input: String,
    /// `output unit/input unit` (empty when both are unitless).
    pub unit: String,
    /// The finite gain `G(0)`, as computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// The error estimate of [`GainEntry::value`] (`eom_num::gain::SteadyStateGain::errors`):
    /// a value within it has no known sign and prints as 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<f64>,
    /// The output integrates a constant input.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub integrating: Option<Integrating>,
}

impl GainEntry {
    /// The finite gain as printed: 0 where it is within its error estimate (rounding of an
    /// exact 0), with the estimate to state beside it.
    pub fn shown(&self) -> Option<(f64, Option<f64>)> {
        let v = self.value?;
        Some(match self.error_estimate {
            Some(e) if v.abs() <= e => (0.0, Some(e)),
            _ => (v, None),
        })
    }
}

/// An integrating pair: `G(s)` has a pole of order `order` at 0.
#[derive(Clone, Debug, Serialize)]
pub struct Integrating {
    /// Order of the pole at s = 0 (1: a step gives a ramp).
    pub order: usize,
    /// `lim s^order G(s)` (for order 1 the ramp slope per unit step, per second).
    pub coefficient: f64,
}

/// The frequency response of every pair.
#[derive(Clone, Debug, Serialize)]
pub struct FreqReport {
    /// Frequencies in Hz.
    pub frequency_hz: Vec<f64>,
    /// Per frequency: whether jω is numerically a pole (the response is infinite there).
    pub singular: Vec<bool>,
    /// One entry per output/input pair.
    pub pairs: Vec<FreqPair>,
}

/// The frequency response of one pair.
#[derive(Clone, Debug, Serialize)]
pub struct FreqPair {
    /// Output name.
    pub output: String,
    /// Input name.
    pub input: String,
    /// `20 log10 |G|` in dB (`null` where infinite: a pole on the axis, or an exact zero).
    pub magnitude_db: Vec<Option<f64>>,
    /// Phase in degrees, unwrapped along frequency.
    pub phase_deg: Vec<f64>,
}

fn ordered_map<S: Serializer, V: Serialize>(v: &[(String, V)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

fn method_name(m: Method) -> &'static str {
    match m {
        Method::Symbolic => "symbolic",
        Method::Numeric => "numeric",
        Method::Robust => "robust",
    }
}

/// A mode's kind as the output words it.
pub(crate) fn kind_name(k: ModeKind) -> &'static str {
    match k {
        ModeKind::Zero => "zero",
        ModeKind::Real => "real",
        ModeKind::Oscillatory => "oscillatory",
    }
}

/// A stability verdict as the output words it.
pub(crate) fn stability_name(s: Stability) -> &'static str {
    match s {
        Stability::Stable => "stable",
        Stability::Marginal => "marginal",
        Stability::Unstable => "unstable",
    }
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

fn mode_report(m: &Mode) -> ModeReport {
    ModeReport {
        eigenvalue: m.eigenvalue.into(),
        kind: kind_name(m.kind),
        natural_frequency_hz: m.natural_frequency_hz,
        damping_ratio: m.damping_ratio,
        time_constant: finite(m.time_constant),
        period: finite(m.damped_period),
        stability: stability_name(m.stability),
        stable: m.stability == Stability::Stable,
        tolerance: m.tolerance,
        accuracy: m.accuracy,
    }
}

/// Stability with the structural zero eigenvalues set apart: `stable` when every other mode
/// decays (the definition `eom sweep` uses too: a vehicle's lateral position and heading do
/// not feed back, so they neither make nor break its stability).
fn overall_stability(modes: &Modes, structural_zeros: usize) -> &'static str {
    let exact_zeros = modes
        .modes
        .iter()
        .filter(|m| m.eigenvalue == num_complex::Complex64::new(0.0, 0.0))
        .count()
        .min(structural_zeros);
    let mut skipped = 0;
    let mut others = modes.modes.iter().filter(|m| {
        if skipped < exact_zeros && m.eigenvalue == num_complex::Complex64::new(0.0, 0.0) {
            skipped += 1;
            false
        } else {
            true
        }
    });
    let rest: Vec<&Stability> = others.by_ref().map(|m| &m.stability).collect();
    if rest.iter().all(|s| **s == Stability::Stable) {
        "stable"
    } else if rest.iter().any(|s| **s == Stability::Unstable) {
        "unstable"
    } else {
        "marginal"
    }
}

fn signals(count: usize, names: &[String], units: &[String], what: &str) -> Vec<Signal> {
    (0..count)
        .map(|k| Signal {
            name: names
                .get(k)
                .filter(|n| !n.is_empty())
                .cloned()
                .unwrap_or_else(|| format!("{what} {}", k + 1)),
            unit: units.get(k).cloned().unwrap_or_default(),
        })
        .collect()
}

/// The unit of a ratio `out/inp` (`inp` parenthesized when compound; empty when both are).
pub(crate) fn ratio_unit(out: &str, inp: &str) -> String {
    let den = if inp.contains([' ', '/', '*']) {
        format!("({inp})")
    } else {
        inp.to_string()
    };
    match (out.is_empty(), inp.is_empty()) {
        (true, true) => String::new(),
        (false, true) => out.to_string(),
        (true, false) => format!("1/{den}"),
        (false, false) => format!("{out}/{den}"),
    }
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

fn minimal_view(
    ssm: &StateSpace<f64>,
    rep: &MinrealReport,
    modes: &Modes,
    warnings: &mut Vec<ShownWarning>,
) -> Result<MinimalReport, CliError> {
    for d in rep.fragile_decisions(100.0) {
        let stage = match d.stage {
            RankStage::Controllability => "controllability",
            RankStage::Observability => "observability",
            RankStage::ControllabilityPbh => "controllability (PBH test at repeated eigenvalues)",
            RankStage::ObservabilityPbh => "observability (PBH test at repeated eigenvalues)",
            _ => "rank",
        };
        let message = format!(
            "minimal realization: the {stage} rank decision at step {} is within a factor 100 of \
             its tolerance {} (singular values {}): another choice of units could change which \
             modes count as removed",
            d.step,
            g(d.tolerance, 3),
            d.singular_values
                .iter()
                .map(|s| g(*s, 3))
                .collect::<Vec<_>>()
                .join(", ")
        );
        warnings.push(ShownWarning::new("fragile_minimal_realization", message));
    }
    // Nothing removed: the same model, the same modes.
    let mmodes = if rep.states_out == rep.states_in {
        modes.clone()
    } else {
        Modes::compute_with(ssm, &mode_options())?
    };
    let removed = rep
        .removed
        .iter()
        .map(|r| {
            // The nearest mode of the full model: its kind, and its verdict (one verdict per
            // eigenvalue, by its error estimate, wherever it is shown).
            let nearest = modes.modes.iter().min_by(|a, b| {
                (a.eigenvalue - r.eigenvalue)
                    .norm()
                    .total_cmp(&(b.eigenvalue - r.eigenvalue).norm())
            });
            let kind = nearest.map_or(ModeKind::Real, |m| m.kind);
            let reason = match r.kind {
                RemovedKind::Uncontrollable => "uncontrollable",
                RemovedKind::Unobservable => "unobservable",
            };
            let verdict = nearest.map_or(
                match r.stability {
                    ModeStability::Stable => Stability::Stable,
                    ModeStability::Marginal => Stability::Marginal,
                    ModeStability::Unstable => Stability::Unstable,
                },
                |m| m.stability,
            );
            let stability = stability_name(verdict);
            RemovedReport {
                eigenvalue: r.eigenvalue.into(),
                reason,
                stability,
                kind: kind_name(kind),
                pbh_residual: r.pbh_residual,
                note: removed_note(r.eigenvalue, r.kind, verdict, kind),
            }
        })
        .collect();
    Ok(MinimalReport {
        states: ssm.states(),
        eigenvalues: re_im(&mmodes.eigenvalues()),
        modes: mmodes.modes.iter().map(mode_report).collect(),
        removed,
    })
}

fn removed_note(z: Complex64, why: RemovedKind, st: Stability, kind: ModeKind) -> String {
    let what = match kind {
        ModeKind::Zero => "zero (rigid-body/integrator) mode",
        ModeKind::Real => "real mode",
        ModeKind::Oscillatory => "oscillatory mode",
    };
    let cause = match why {
        RemovedKind::Uncontrollable => "the inputs cannot excite it",
        RemovedKind::Unobservable => "the outputs cannot see it",
    };
    let lam = eigenvalue(z, SIG, false);
    match st {
        Stability::Unstable => format!(
            "UNSTABLE {what} {lam} is {}: {cause}, yet it grows in the physical system",
            if why == RemovedKind::Uncontrollable {
                "uncontrollable"
            } else {
                "unobservable"
            }
        ),
        Stability::Marginal => format!(
            "marginal {what} {lam} is {}: {cause}; it does not decay",
            if why == RemovedKind::Uncontrollable {
                "uncontrollable"
            } else {
                "unobservable"
            }
        ),
        Stability::Stable => format!(
            "stable {what} {lam} is {}: {cause}",
            if why == RemovedKind::Uncontrollable {
                "uncontrollable"
            } else {
                "unobservable"
            }
        ),
    }
}

fn gain_entries(
    gain: &SteadyStateGain,
    inputs: &[Signal],
    outputs: &[Signal],
    warnings: &mut Vec<ShownWarning>,
) -> Vec<GainEntry> {
    warnings.extend(
        gain.warnings
            .iter()
            .map(|w| ShownWarning::of_num(w, "steady-state gain: ")),
    );
    let mut out = Vec::with_capacity(inputs.len() * outputs.len());
    for (i, o) in outputs.iter().enumerate() {
        for (j, u) in inputs.iter().enumerate() {
            let (value, error_estimate, integrating) = match gain.get(i, j) {
                Gain::Finite(v) => (Some(v), Some(gain.errors[(i, j)]), None),
                Gain::Integrating { order, coefficient } => {
                    (None, None, Some(Integrating { order, coefficient }))
                }
            };
            out.push(GainEntry {
                output: o.name.clone(),
                input: u.name.clone(),
                unit: ratio_unit(&o.unit, &u.unit),
                value,
                error_estimate,
                integrating,
            });
        }
    }
    out
}

/// `n` logarithmically spaced values from `lo` to `hi`, both included.
fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![lo];
    }
    let (a, b) = (lo.log10(), hi.log10());
    (0..n)
        .map(|k| {
            if k + 1 == n {
                hi
            } else {
                10f64.powf(a + (b - a) * k as f64 / (n - 1) as f64)
            }
        })
        .collect()
}

fn frequency_response(
    ss: &StateSpace<f64>,
    req: &FreqRequest,
    inputs: &[Signal],
    outputs: &[Signal],
) -> Result<FreqReport, CliError> {
    let range = match (req.range, req.points) {
        (None, None) => FreqRange::Auto,
        (Some((low, high)), None) => FreqRange::Range {
            low,
            high,
            unit: FreqUnit::Hz,
        },
        (Some((lo, hi)), Some(n)) => FreqRange::Points {
            values: logspace(lo, hi, n),
            unit: FreqUnit::Hz,
        },
        (None, Some(n)) => {
            // The automatic range (whole decades around the modes), then n points across it.
            let probe = FrequencyResponse::compute(
                ss,
                &FreqOptions {
                    range: FreqRange::Auto,
                    points_per_decade: 1,
                },
            )?;
            let lo = probe.freq_hz.first().copied().unwrap_or(0.01);
            let hi = probe.freq_hz.last().copied().unwrap_or(100.0);
            FreqRange::Points {
                values: logspace(lo, hi, n),
                unit: FreqUnit::Hz,
            }
        }
    };
    let fr = FrequencyResponse::compute(
        ss,
        &FreqOptions {
            range,
            ..FreqOptions::default()
        },
    )?;
    let mut pairs = Vec::with_capacity(inputs.len() * outputs.len());
    for (i, o) in outputs.iter().enumerate() {
        for (j, u) in inputs.iter().enumerate() {
            pairs.push(FreqPair {
                output: o.name.clone(),
                input: u.name.clone(),
                magnitude_db: fr
                    .magnitude_db_of(i, j)
                    .iter()
                    .map(|&x| finite(x))
                    .collect(),
                phase_deg: fr.phase_deg_of(i, j).to_vec(),
            });
        }
    }
    Ok(FreqReport {
        frequency_hz: fr.freq_hz.clone(),
        singular: fr.singular.clone(),
        pairs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::dmatrix;

    /// A double integrator `ÿ = u` observed by y: G(s) = 1/s², an integrating pair of order 2
    /// with coefficient 1, and a double zero mode.
    #[test]
    fn integrating_pairs_are_reported_as_such() {
        let ss = StateSpace::new(
            dmatrix![0.0, 1.0; 0.0, 0.0],
            dmatrix![0.0; 1.0],
            dmatrix![1.0, 0.0; 0.0, 1.0],
            dmatrix![0.0; 0.0],
        )
        .unwrap();
        let r = analyze_state_space(&ss, Vec::new(), None, 0).unwrap();
        let g = r.steady_state_gain.as_ref().unwrap();
        let i = g[0]
            .integrating
            .as_ref()
            .expect("position integrates twice");
        assert_eq!(i.order, 2);
        assert!((i.coefficient - 1.0).abs() < 1e-12, "{}", i.coefficient);
        let i = g[1].integrating.as_ref().expect("velocity integrates once");
        assert_eq!(i.order, 1);
        assert!((i.coefficient - 1.0).abs() < 1e-12, "{}", i.coefficient);
        assert!(g.iter().all(|e| e.value.is_none()));
        assert!(
            r.modes
                .iter()
                .all(|m| m.kind == "zero" && m.stability == "marginal")
        );
        let text = r.to_text();
        assert!(
            text.contains("integrating (pole of order 2 at s = 0)"),
            "{text}"
        );
        assert!(
            text.contains("a unit step gives a ramp of slope 1"),
            "{text}"
        );
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["steady_state_gain"][0]["integrating"]["order"], 2);
        assert!(json["steady_state_gain"][0].get("value").is_none());
    }

    /// An unstable mode that the output cannot see must be listed, never hidden.
    #[test]
    fn unobservable_unstable_modes_are_reported() {
        // ẋ1 = −x1 + u, ẋ2 = 0.5 x2 + u, y = x1: the growing x2 is invisible at the output.
        let ss = StateSpace::new(
            dmatrix![-1.0, 0.0; 0.0, 0.5],
            dmatrix![1.0; 1.0],
            dmatrix![1.0, 0.0],
            dmatrix![0.0],
        )
        .unwrap();
        let r = analyze_state_space(&ss, Vec::new(), None, 0).unwrap();
        assert_eq!(r.stability, "unstable");
        let m = r.minimal.as_ref().unwrap();
        assert_eq!(m.states, 1);
        assert_eq!(m.removed.len(), 1);
        let rm = &m.removed[0];
        assert_eq!(
            (rm.reason, rm.stability, rm.kind),
            ("unobservable", "unstable", "real")
        );
        assert!((rm.eigenvalue.re - 0.5).abs() < 1e-12);
        assert!(
            r.to_text()
                .contains("UNSTABLE real mode 0.5 is unobservable"),
            "{}",
            r.to_text()
        );
    }
}
