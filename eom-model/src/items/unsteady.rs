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

use crate::error::ModelError;
use crate::warning::{ItemRef, Warning};

/// The circulatory lift of a strip or wing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Unsteady {
    /// `C = 1`: the lift follows the downwash at once (no states).
    #[default]
    QuasiSteady,
    /// R. T. Jones' approximation of Wagner's function: two lag states per surface.
    Jones,
    /// Decided by the linearization ([`resolve_unsteady`](crate::resolve_unsteady)): Jones' states where a mode's
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
            _ => Err(ModelError::UnknownUnsteady {
                given: s.to_string(),
            }),
        }
    }
}

impl super::Choice for Unsteady {
    fn name(self) -> &'static str {
        self.as_str()
    }
    fn from_name(s: &str) -> Result<Self, String> {
        Unsteady::parse(s)
            .map_err(|_| format!("`{s}`: expected \"quasi-steady\", \"jones\" or \"auto\""))
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
pub(crate) fn auto_assembled(kind: &'static str, name: &str) -> Warning {
    Warning::AutoAssembled {
        item: ItemRef::new(kind, name),
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
