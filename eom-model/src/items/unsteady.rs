//! [`Unsteady`]: how a lifting item's circulatory lift follows its motion, and R. T. Jones'
//! two-state approximation of Wagner's function that the lag states realise.
//!
//! Jones (NACA Report 667, 1938) fits Wagner's indicial lift by two exponentials; in the
//! non-dimensional Laplace variable `s̄ = s·b/V` (b the semichord) its transfer function is
//!
//! ```text
//! C(s̄) = 1 − 0.165 s̄/(s̄ + 0.0455) − 0.335 s̄/(s̄ + 0.3)
//!      = ½ + 0.165·β̄₁/(s̄ + β̄₁) + 0.335·β̄₂/(s̄ + β̄₂),   β̄₁ = 0.0455, β̄₂ = 0.3,
//! ```
//!
//! realised with two states per surface, `ẋᵢ = −βᵢ xᵢ + w` (`βᵢ = β̄ᵢ V/b`, w the downwash
//! that drives the lift), and `C[w] = ½ w + 0.165 β₁ x₁ + 0.335 β₂ x₂`. At `s̄ = ik` it is within
//! |ΔC| ≤ 0.0145 of Theodorsen's function for every k (docs/aero-references.md, §1).

use super::{Strip, Wing, label};
use crate::Model;
use crate::error::ModelError;
use eom_sym::Expr;
use std::borrow::Cow;

/// The circulatory lift of a strip or wing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Unsteady {
    /// `C = 1`: the lift follows the downwash at once (no states).
    #[default]
    QuasiSteady,
    /// R. T. Jones' approximation of Wagner's function: two lag states per surface.
    Jones,
    /// Decided by the linearization ([`resolve_unsteady`]): Jones' states where a mode's
    /// reduced frequency at this surface exceeds [`AUTO_REDUCED_FREQUENCY`], else
    /// quasi-steady. Assembled directly, it is quasi-steady (with a warning).
    Auto,
}

impl Unsteady {
    /// The name used in model files: `"quasi-steady"` or `"jones"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Unsteady::QuasiSteady => "quasi-steady",
            Unsteady::Jones => "jones",
            Unsteady::Auto => "auto",
        }
    }

    /// Parse a model file's name (`"quasi-steady"`, `"jones"`).
    pub fn parse(s: &str) -> Result<Self, ModelError> {
        match s {
            "quasi-steady" => Ok(Unsteady::QuasiSteady),
            "jones" => Ok(Unsteady::Jones),
            "auto" => Ok(Unsteady::Auto),
            _ => Err(ModelError::Unsupported(format!(
                "unknown unsteady aerodynamics `{s}`: expected \"quasi-steady\", \"jones\" or \"auto\""
            ))),
        }
    }
}

/// Jones' coefficients `(Aᵢ, β̄ᵢ)`: `C(s̄) = 1 − Σ Aᵢ s̄/(s̄ + β̄ᵢ)`.
pub const JONES: [(f64, f64); 2] = [(0.165, 0.0455), (0.335, 0.3)];

/// The direct part of Jones' `C` (its value at high frequency): `1 − ΣAᵢ = ½`.
pub const JONES_DIRECT: f64 = 0.5;

/// Jones' `C(s̄)` at a complex `s̄ = (re, im)`, as `(re, im)`.
pub fn jones_c(s: (f64, f64)) -> (f64, f64) {
    let mut c = (1.0, 0.0);
    for (a, b) in JONES {
        // a·s/(s + b)
        let (dr, di) = (s.0 + b, s.1);
        let den = dr * dr + di * di;
        let (nr, ni) = (s.0 * dr + s.1 * di, s.1 * dr - s.0 * di);
        c.0 -= a * nr / den;
        c.1 -= a * ni / den;
    }
    c
}

/// The reduced frequency k = ωb/V above which `unsteady = "auto"` adds Jones' states: there
/// quasi-steady lift is off by |1 − C(k)| ≥ 0.16 (Theodorsen).
pub const AUTO_REDUCED_FREQUENCY: f64 = 0.05;

/// The warning of a surface whose `auto` is assembled without a linearization to decide it.
pub(crate) fn auto_assembled(kind: &str, name: &str) -> String {
    format!(
        "{}: unsteady = \"auto\" is decided by the linearization (eom analyze, sweep, …); \
         assembled here as quasi-steady",
        label(kind, name)
    )
}

/// A surface with `unsteady = "auto"`: kind, name, semichord and airspeed at a point.
struct AutoSurface {
    kind: &'static str,
    name: String,
    semichord: f64,
    airspeed: f64,
}

fn auto_surfaces(m: &Model<f64>) -> Vec<AutoSurface> {
    let mut out = Vec::new();
    for w in m.wings().filter(|w| w.unsteady == Unsteady::Auto) {
        out.push(AutoSurface {
            kind: "wing",
            name: w.name.to_string(),
            semichord: 0.5 * w.chord,
            airspeed: m.airspeed_of(w),
        });
    }
    for s in m.strips().filter(|s| s.unsteady == Unsteady::Auto) {
        let velocity = m.body(&s.body).map_or([0.0; 3], |b| b.velocity);
        out.push(AutoSurface {
            kind: "strip",
            name: s.name.to_string(),
            semichord: s.semichord,
            airspeed: s.airspeed_with(&velocity),
        });
    }
    out
}

/// The model with every `auto` surface set to Jones' states when its name is in `lagged`,
/// else quasi-steady.
fn with_lags(model: &Model<Expr>, lagged: &[String]) -> Model<Expr> {
    let mut m = model.clone();
    for item in m.items_mut() {
        let any: &mut dyn std::any::Any = item.as_mut();
        let pick = |name: &str| {
            if lagged.iter().any(|n| n == name) {
                Unsteady::Jones
            } else {
                Unsteady::QuasiSteady
            }
        };
        if let Some(w) = any.downcast_mut::<Wing<Expr>>() {
            if w.unsteady == Unsteady::Auto {
                w.unsteady = pick(&w.name);
            }
        } else if let Some(s) = any.downcast_mut::<Strip<Expr>>()
            && s.unsteady == Unsteady::Auto
        {
            s.unsteady = pick(&s.name);
        }
    }
    m
}

/// Decides every `unsteady = "auto"` of `model` at the parameter `values` (scope order):
/// analyse with the undecided surfaces quasi-steady, give Jones' states to each surface at
/// which an oscillatory mode has the reduced frequency k = |Im λ|·b/V above
/// [`AUTO_REDUCED_FREQUENCY`] (b its semichord, V its airspeed), re-analyse, and repeat until
/// no surface is added. Returns the decided model (borrowed when nothing is `auto`) and one
/// line per `auto` surface saying what it got and why.
pub fn resolve_unsteady<'m>(
    model: &'m Model<Expr>,
    values: &[f64],
) -> Result<(Cow<'m, Model<Expr>>, Vec<String>), ModelError> {
    let any_auto = model
        .items()
        .iter()
        .filter(|x| matches!(x.kind(), "wing" | "strip"))
        .any(|x| {
            let any: &dyn std::any::Any = x.as_ref();
            any.downcast_ref::<Wing<Expr>>()
                .map(|w| w.unsteady == Unsteady::Auto)
                .or_else(|| {
                    any.downcast_ref::<Strip<Expr>>()
                        .map(|s| s.unsteady == Unsteady::Auto)
                })
                .unwrap_or(false)
        });
    if !any_auto {
        return Ok((Cow::Borrowed(model), Vec::new()));
    }
    let surfaces = auto_surfaces(&model.evaluate(values)?);
    let mut lagged: Vec<String> = Vec::new();
    let mut notes = Vec::new();
    loop {
        let m = with_lags(model, &lagged);
        let a = crate::assemble(&m.evaluate(values)?)?;
        let ss = match crate::reduce(&a, None) {
            Ok(r) => r.state_space,
            Err(_) => crate::reduce_robust(&a)?.0,
        };
        let eig = eom_num::modes::eigenvalues(&ss.a)?;
        let mut added = false;
        let mut rest = Vec::new();
        let pending: Vec<&AutoSurface> = surfaces
            .iter()
            .filter(|s| !lagged.contains(&s.name))
            .collect();
        for s in pending {
            let top = eig
                .iter()
                .filter(|z| z.im > 0.0)
                .map(|z| (z.im * s.semichord / s.airspeed, *z))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            match top {
                Some((k, z)) if k > AUTO_REDUCED_FREQUENCY => {
                    notes.push(format!(
                        "{}: unsteady = \"auto\": Jones' lag states added: the mode λ = {:.6} ± {:.6}i \
                         has the reduced frequency k = |Im λ|·b/V = {k:.4} > {AUTO_REDUCED_FREQUENCY} \
                         (quasi-steady lift would be off by |1 − C(k)| ≥ 0.16)",
                        label(s.kind, &s.name),
                        z.re,
                        z.im
                    ));
                    lagged.push(s.name.clone());
                    added = true;
                }
                Some((k, _)) => rest.push(format!(
                    "{}: unsteady = \"auto\": quasi-steady: every mode has k = |Im λ|·b/V ≤ \
                     {AUTO_REDUCED_FREQUENCY} (largest {k:.4})",
                    label(s.kind, &s.name)
                )),
                None => rest.push(format!(
                    "{}: unsteady = \"auto\": quasi-steady: no oscillatory mode",
                    label(s.kind, &s.name)
                )),
            }
        }
        if !added {
            notes.extend(rest);
            return Ok((Cow::Owned(m), notes));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two forms of Jones' function agree, and its direct part is ½.
    #[test]
    fn the_two_forms_agree() {
        for k in [0.0, 0.05, 0.3, 1.0, 10.0] {
            let (re, im) = jones_c((0.0, k));
            let mut alt = (JONES_DIRECT, 0.0);
            for (a, b) in JONES {
                // a·b/(ik + b)
                let den = b * b + k * k;
                alt.0 += a * b * b / den;
                alt.1 -= a * b * k / den;
            }
            assert!((re - alt.0).abs() < 1e-15 && (im - alt.1).abs() < 1e-15);
        }
        assert!((1.0 - JONES.iter().map(|x| x.0).sum::<f64>() - JONES_DIRECT).abs() < 1e-15);
    }
}
