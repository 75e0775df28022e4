//! Natural frequency and damping ratio of a second-order model in closed form.

use super::{CharacteristicPolynomial, ClosedForms};
use crate::error::SymError;
use crate::expr::Expr;
use crate::simplify::normalize_rational;

/// `a₂s² + a₁s + a₀ = a₂(s² + 2ζωₙs + ωₙ²)`.
#[derive(Clone, Debug, PartialEq)]
pub struct SecondOrder {
    /// `ωₙ² = a₀/a₂`.
    pub natural_frequency_squared: Expr,
    /// `ωₙ = √(a₀/a₂)` (rad/s).
    pub natural_frequency: Expr,
    /// `ζ = a₁/(2√(a₀a₂))`.
    pub damping_ratio: Expr,
}

impl ClosedForms {
    /// ωₙ and ζ of a characteristic polynomial of degree 2 (`None` for other degrees, or when
    /// a zero root was divided out).
    pub fn second_order(
        &self,
        p: &CharacteristicPolynomial,
    ) -> Result<Option<SecondOrder>, SymError> {
        let c = &p.polynomial.coefficients;
        if c.len() != 3 || p.zero_roots > 0 {
            return Ok(None);
        }
        let (a0, a1, a2) = (c[0], c[1], c[2]);
        let wn2 = normalize_rational(a0 / a2)?;
        let zeta = normalize_rational(a1 / (a0 * a2).sqrt() / 2i64)?;
        Ok(Some(SecondOrder {
            natural_frequency_squared: wn2,
            natural_frequency: wn2.sqrt(),
            damping_ratio: zeta,
        }))
    }
}
