//! The wings of a model in `eom analyze`: each wing's damping matrix in model axes and the
//! quasi-steady validity of its derivatives for every oscillatory mode (the reduced frequency
//! β = |Im λ|·c/V, warned above 0.1).

use crate::analyze::SIG;
use crate::format::{ReIm, eigenvalue, g, table};
use eom_model::Model;
use num_complex::Complex64;
use serde::Serialize;

/// One wing of the model at the analysed point.
#[derive(Clone, Debug, Serialize)]
pub struct WingReport {
    /// Name.
    pub name: String,
    /// The body it is fixed to.
    pub body: String,
    /// Its reference point (model axes).
    pub location: [f64; 3],
    /// Reference area S, chord c and span b.
    pub area: f64,
    /// Reference chord c.
    pub chord: f64,
    /// Reference span b.
    pub span: f64,
    /// Air density ρ.
    pub density: f64,
    /// Airspeed V.
    pub airspeed: f64,
    /// The damping matrix L (the aerodynamic force is −L times the point's velocities) in model
    /// axes at the point: rows X, Y, Z, L, M, N [N, N·m]; columns u, v, w [m/s], p, q, r
    /// [rad/s].
    pub damping: [[f64; 6]; 6],
    /// β = |Im λ|·c/V of every oscillatory mode (one per conjugate pair).
    pub reduced_frequencies: Vec<ReducedFrequencyReport>,
}

/// β of one mode at one wing.
#[derive(Clone, Debug, Serialize)]
pub struct ReducedFrequencyReport {
    /// The eigenvalue (positive imaginary part).
    pub eigenvalue: ReIm,
    /// β = |Im λ|·c/V.
    pub beta: f64,
    /// Whether β exceeds 0.1 (the derivatives are then doubtful for this mode).
    pub too_high: bool,
}

/// The wings of `model` (numeric, at the analysed point) and the warnings for reduced
/// frequencies above the limit; `None` for a model without wings.
pub fn wing_reports(
    model: &Model<f64>,
    eigenvalues: &[Complex64],
    warnings: &mut Vec<crate::shown_warning::ShownWarning>,
) -> Option<Vec<WingReport>> {
    let wings: Vec<_> = model.wings().collect();
    if wings.is_empty() {
        return None;
    }
    let betas = eom_model::reduced_frequencies(model, eigenvalues);
    warnings.extend(
        betas
            .iter()
            .filter_map(|b| b.warning())
            .map(|w| crate::shown_warning::ShownWarning::of_model(&w, "")),
    );
    let reports = wings
        .iter()
        .map(|w| {
            let v = model.airspeed_of(w);
            WingReport {
                name: w.name.to_string(),
                body: w.body.to_string(),
                location: w.location,
                area: w.area,
                chord: w.chord,
                span: w.span,
                density: w.density,
                airspeed: v,
                damping: w.damping(v),
                reduced_frequencies: betas
                    .iter()
                    .filter(|b| *b.wing == *w.name)
                    .map(|b| ReducedFrequencyReport {
                        eigenvalue: b.eigenvalue.into(),
                        beta: b.beta,
                        too_high: b.too_high,
                    })
                    .collect(),
            }
        })
        .collect();
    Some(reports)
}

/// The text section of the wings.
pub fn wings_text(wings: &[WingReport]) -> String {
    let mut t = String::from(
        "Wings (quasi-steady derivatives; reduced frequency β = |Im λ|·c/V, doubtful above 0.1)\n",
    );
    for w in wings {
        t.push_str(&format!(
            "  {} on {} at ({}, {}, {}): S = {}, c = {}, b = {}, ρ = {}, V = {}\n",
            w.name,
            w.body,
            g(w.location[0], SIG),
            g(w.location[1], SIG),
            g(w.location[2], SIG),
            g(w.area, SIG),
            g(w.chord, SIG),
            g(w.span, SIG),
            g(w.density, SIG),
            g(w.airspeed, SIG)
        ));
        if w.reduced_frequencies.is_empty() {
            t.push_str("    no oscillatory modes\n");
        } else {
            let rows: Vec<Vec<String>> = w
                .reduced_frequencies
                .iter()
                .map(|b| {
                    let z = Complex64::new(b.eigenvalue.re, b.eigenvalue.im);
                    vec![
                        eigenvalue(z, SIG, true),
                        g(b.beta, 4),
                        if b.too_high { "TOO HIGH" } else { "ok" }.to_string(),
                    ]
                })
                .collect();
            t.push_str(&table(&["mode [1/s]", "β", ""], &rows, 4));
        }
        t.push_str(
            "    damping L at the point, model axes (force = −L·velocity; rows X Y Z L M N, \
             columns u v w p q r):\n",
        );
        let rows: Vec<Vec<String>> = w
            .damping
            .iter()
            .zip(["X", "Y", "Z", "L", "M", "N"])
            .map(|(r, n)| {
                std::iter::once(n.to_string())
                    .chain(r.iter().map(|x| g(*x, SIG)))
                    .collect()
            })
            .collect();
        t.push_str(&table(&["", "u", "v", "w", "p", "q", "r"], &rows, 6));
    }
    t.push('\n');
    t
}
