//! The text report of `eom analyze`: tables of the modes (full model and minimal realization),
//! notes on removed modes, gains, zeros, the frequency response and the warnings.

use crate::analyze::{Analysis, ModeReport, SIG, Signal, WIDTH};
use crate::format::{eigenvalue, g, table, wrap_list};
use num_complex::Complex64;

fn opt(x: Option<f64>, none: &str) -> String {
    x.map_or_else(|| none.to_string(), |v| g(v, SIG))
}

/// The mode table: one row per real or zero mode and per conjugate pair.
fn mode_table(modes: &[ModeReport]) -> String {
    let mut rows = Vec::new();
    for m in modes {
        let z = shown(m);
        let pair = m.kind == "oscillatory";
        if pair && z.im < 0.0 {
            continue;
        }
        let kind = match m.kind {
            "zero" => "zero (rigid-body/integrator)",
            "real" => "real",
            _ => "oscillatory",
        };
        rows.push(vec![
            (rows.len() + 1).to_string(),
            eigenvalue(z, SIG, pair),
            g(m.natural_frequency_hz, SIG),
            opt(m.damping_ratio, "-"),
            opt(m.time_constant, "inf"),
            opt(m.period, "-"),
            kind.to_string(),
            m.stability.to_string(),
        ]);
    }
    table(
        &[
            "#",
            "eigenvalue [1/s]",
            "freq [Hz]",
            "damping",
            "tau [s]",
            "period [s]",
            "kind",
            "stability",
        ],
        &rows,
        2,
    )
}

/// The rule of the stability column, with the largest tolerance it used.
pub(crate) fn verdict_rule(modes: &[ModeReport]) -> String {
    let largest = modes.iter().map(|m| m.tolerance).fold(0.0, f64::max);
    format!(
        "  stability: stable when Re λ < −tol, marginal when |Re λ| ≤ tol, tol = the \
         eigenvalue's error estimate (here at most {} 1/s)\n",
        g(largest, 2)
    )
}

/// A mode's eigenvalue as printed: a part within the eigenvalue's error estimate is 0 (its
/// value is rounding).
pub(crate) fn shown(m: &ModeReport) -> Complex64 {
    let part = |x: f64| if x.abs() <= m.tolerance { 0.0 } else { x };
    Complex64::new(part(m.eigenvalue.re), part(m.eigenvalue.im))
}

fn signal_list(s: &[Signal]) -> String {
    if s.is_empty() {
        return "none".into();
    }
    s.iter()
        .map(|x| {
            if x.unit.is_empty() {
                x.name.clone()
            } else {
                format!("{} [{}]", x.name, x.unit)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

impl Analysis {
    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let mut t = self.header_text();
        t.push_str(&self.modes_text());
        t.push_str(&self.minimal_text());
        t.push_str(&self.gains_text());
        t.push_str(&self.zeros_text());
        t.push_str(&self.frequency_text());
        if let Some(w) = &self.wings {
            t.push_str(&crate::wings::wings_text(w));
        }

        if let Some(sens) = &self.sensitivity {
            t.push_str(&sensitivity_text(sens));
        }
        if let Some(p) = &self.preloads {
            t.push_str(&crate::preloads::to_text(p));
        }

        t.push_str("Warnings\n");
        if self.warnings.is_empty() {
            t.push_str("  none\n");
        }
        for w in &self.warnings {
            t.push_str(&format!("  - {w}\n"));
        }
        t
    }

    /// The model, its parameters and signals, and the states' names.
    fn header_text(&self) -> String {
        let mut t = String::new();
        let units = |k: usize| {
            let u = &self.parameter_units[k].1;
            if u.is_empty() {
                String::new()
            } else {
                format!(" {u}")
            }
        };
        t.push_str(&format!("Model {} (method: {})\n", self.model, self.method));
        let params: Vec<String> = self
            .parameters
            .iter()
            .enumerate()
            .map(|(k, (n, v))| format!("{n} = {}{}", g(*v, SIG), units(k)))
            .collect();
        t.push_str(&wrap_list("Parameters:", &params, WIDTH));
        t.push_str(&format!(
            "Inputs: {}\nOutputs: {}\n\n",
            signal_list(&self.inputs),
            signal_list(&self.outputs)
        ));

        t.push_str(&wrap_list(
            &format!("Modes of the state-space model ({} states:", self.states),
            &self.state_names,
            WIDTH,
        ));
        t.pop();
        t.push_str(")\n");
        t
    }

    /// The modes table and the stability verdict.
    fn modes_text(&self) -> String {
        let mut t = String::new();
        t.push_str(&mode_table(&self.modes));
        t.push_str(
            "  freq = |λ|/2π (a real pole's corner frequency); damping = −Re λ/|λ| (±1 for a real \
             pole);\n  tau = −1/Re λ (negative: e-folding time of growth); period = 2π/|Im λ| \
             (damped period, EoM's \"wavelength\")\n",
        );
        t.push_str(&verdict_rule(&self.modes));
        let unstable = self
            .modes
            .iter()
            .filter(|m| m.stability == "unstable")
            .count();
        let marginal = self
            .modes
            .iter()
            .filter(|m| m.stability == "marginal")
            .count();
        t.push_str(&match self.stability {
            "stable" if !self.structural_zeros.is_empty() => {
                "  The model is stable: every mode decays, the structural zeros below aside (they \
                 do not feed back).\n"
                    .to_string()
            }
            "stable" => "  The model is stable: every mode decays.\n".to_string(),
            "unstable" => format!(
                "  The model is UNSTABLE: {unstable} eigenvalue(s) with positive real part.\n"
            ),
            _ => format!(
                "  The model is marginally stable: {marginal} eigenvalue(s) on the imaginary axis \
                 (zero or undamped modes), none growing exponentially.\n"
            ),
        });
        if !self.structural_zeros.is_empty() {
            t.push_str(&format!(
                "  {} zero eigenvalue(s) proved by the structure (exactly 0): {}.\n",
                self.structural_zeros.len(),
                self.structural_zeros
                    .iter()
                    .map(|s| if s.contains(['+', '−']) {
                        format!("{s} (only the difference of the two acts)")
                    } else {
                        format!("{s} (nothing depends on it)")
                    })
                    .collect::<Vec<_>>()
                    .join("; ")
            ));
        }
        t.push('\n');
        t
    }

    /// The modes of the minimal realization and what it removed.
    fn minimal_text(&self) -> String {
        let mut t = String::new();
        match &self.minimal {
            Some(m) => {
                t.push_str(&format!(
                    "Modes seen from the inputs and outputs (minimal realization: {} of {} states)\n",
                    m.states, self.states
                ));
                if m.states > 0 {
                    t.push_str(&mode_table(&m.modes));
                } else {
                    t.push_str("  (none: no input reaches an output through the dynamics)\n");
                }
                if m.removed.is_empty() {
                    t.push_str("  Every mode is controllable and observable: none removed.\n");
                } else {
                    t.push_str(&format!(
                        "  Removed by the minimal realization ({}):\n",
                        m.removed.len()
                    ));
                    for r in &m.removed {
                        t.push_str(&format!("    - {}\n", r.note));
                    }
                }
            }
            None => match &self.minimal_note {
                Some(note) => t.push_str(&format!("Minimal realization: {note}\n")),
                None => t.push_str("Minimal realization: not computed (see the warnings)\n"),
            },
        }
        t.push('\n');
        t
    }

    /// The steady-state gains.
    fn gains_text(&self) -> String {
        let mut t = String::new();
        t.push_str("Steady-state gains (response to a constant input)\n");
        match &self.steady_state_gain {
            Some(gs) if gs.is_empty() => t.push_str("  (no input/output pairs)\n"),
            Some(gs) => {
                let rows: Vec<Vec<String>> = gs
                    .iter()
                    .map(|e| {
                        let unit = if e.unit.is_empty() {
                            String::new()
                        } else {
                            format!(" {}", e.unit)
                        };
                        let v = match (e.shown(), &e.integrating) {
                            (Some((v, None)), _) => format!("{}{unit}", g(v, SIG)),
                            (Some((v, Some(err))), _) => format!(
                                "{}{unit} (computed {} within its error estimate {})",
                                g(v, SIG),
                                g(e.value.unwrap_or(v), 3),
                                g(err, 2)
                            ),
                            (None, Some(i)) if i.order == 1 => format!(
                                "integrating: a unit step gives a ramp of slope {}{unit} per s",
                                g(i.coefficient, SIG)
                            ),
                            (None, Some(i)) => format!(
                                "integrating (pole of order {} at s = 0): lim s^{} G(s) = {}{unit}",
                                i.order,
                                i.order,
                                g(i.coefficient, SIG)
                            ),
                            (None, None) => "-".into(),
                        };
                        vec![format!("{} / {}", e.output, e.input), v]
                    })
                    .collect();
                t.push_str(&table(&["output / input", "gain"], &rows, 2));
            }
            None => t.push_str("  not computed (see the warnings)\n"),
        }
        t.push('\n');
        t
    }

    /// The transmission zeros.
    fn zeros_text(&self) -> String {
        let mut t = String::new();
        t.push_str("Transmission zeros (of the minimal realization)\n");
        match &self.zeros {
            None if self.inputs.is_empty() || self.outputs.is_empty() => {
                t.push_str("  not defined: the model has no inputs or no outputs\n")
            }
            None => t.push_str("  not computed (see the warnings)\n"),
            Some(z) if z.is_empty() => t.push_str("  none\n"),
            Some(z) => {
                let rows: Vec<Vec<String>> = z
                    .iter()
                    .filter(|z| z.im >= 0.0)
                    .map(|z| {
                        let c = Complex64::new(z.re, z.im);
                        vec![
                            eigenvalue(c, SIG, z.im > 0.0),
                            g(c.norm() / (2.0 * std::f64::consts::PI), SIG),
                        ]
                    })
                    .collect();
                t.push_str(&table(&["zero [1/s]", "|z|/2π [Hz]"], &rows, 2));
            }
        }
        t.push('\n');
        t
    }

    /// The frequency response table, if one was asked for.
    fn frequency_text(&self) -> String {
        let mut t = String::new();
        if let Some(fr) = &self.frequency_response {
            t.push_str(&format!(
                "Frequency response ({} points; magnitude in dB, unwrapped phase in degrees)\n",
                fr.frequency_hz.len()
            ));
            let mut header = vec!["freq [Hz]".to_string()];
            for p in &fr.pairs {
                header.push(format!("{}/{} [dB]", p.output, p.input));
                header.push("[deg]".to_string());
            }
            let rows: Vec<Vec<String>> = (0..fr.frequency_hz.len())
                .map(|k| {
                    let mut r = vec![g(fr.frequency_hz[k], SIG)];
                    for p in &fr.pairs {
                        r.push(opt(p.magnitude_db[k], "inf"));
                        r.push(g(p.phase_deg[k], SIG));
                    }
                    r
                })
                .collect();
            let h: Vec<&str> = header.iter().map(String::as_str).collect();
            t.push_str(&table(&h, &rows, 2));
            t.push('\n');
        }
        t
    }
}

/// The sensitivities as one table per eigenvalue of each conjugate pair (upper member).
fn sensitivity_text(sens: &[crate::analyze::SensitivityReport]) -> String {
    let mut t =
        String::from("Eigenvalue sensitivities ∂λ/∂p (exact ∂A/∂p, numeric eigenvectors)\n");
    for s in sens.iter().filter(|s| s.eigenvalue.im >= 0.0) {
        let l = Complex64::new(s.eigenvalue.re, s.eigenvalue.im);
        t.push_str(&format!(
            "  λ = {}\n",
            eigenvalue(l, SIG, s.eigenvalue.im > 0.0)
        ));
        match &s.derivatives {
            None => t.push_str(&format!(
                "    defective or nearly so (condition number {}): the derivative is unbounded\n",
                g(s.condition, 3)
            )),
            Some(d) => {
                let rows: Vec<Vec<String>> = d
                    .iter()
                    .map(|(p, z)| vec![format!("    {p}"), g(z.re, SIG), g(z.im, SIG)])
                    .collect();
                t.push_str(&table(&["    parameter", "Re ∂λ/∂p", "Im ∂λ/∂p"], &rows, 2));
            }
        }
    }
    t.push('\n');
    t
}
