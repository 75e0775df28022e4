//! The parts of an [`Analysis`](super::Analysis) as they are serialized: the matrices, the mode,
//! gain and frequency-response entries, the signal names and units, and the names and units
//! the text and the JSON output share.

use crate::error::CliError;
use crate::format::{ReIm, re_im};
use crate::params::ModelChoice;
use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use eom_num::modes::{Mode, ModeKind, Modes, Stability};
use serde::{Serialize, Serializer};

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
    pub(super) fn of(ss: &StateSpace<f64>, inputs: &[Signal], outputs: &[Signal]) -> Matrices {
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

pub(super) fn rows<S: Serializer>(m: &nalgebra::DMatrix<f64>, s: S) -> Result<S::Ok, S::Error> {
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

pub(super) fn ordered_map_opt<S: serde::Serializer>(
    v: &Option<Vec<(String, ReIm)>>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match v {
        Some(v) => s.collect_map(v.iter().map(|(k, x)| (k, x))),
        None => s.serialize_none(),
    }
}

/// `∂λ/∂p` at the point, by the symbolic model reduced there (exact `∂A/∂p`).
pub(super) fn sensitivity_report(
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

pub(super) fn ordered_map<S: Serializer, V: Serialize>(
    v: &[(String, V)],
    s: S,
) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

pub(super) fn method_name(m: Method) -> &'static str {
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

pub(super) fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

pub(super) fn mode_report(m: &Mode) -> ModeReport {
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
pub(super) fn overall_stability(modes: &Modes, structural_zeros: usize) -> &'static str {
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

pub(super) fn signals(count: usize, names: &[String], units: &[String], what: &str) -> Vec<Signal> {
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
