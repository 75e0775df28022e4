//! The folding of a lowered sum or product into binary steps, shared by the renderers that
//! carry more than a value per temporary (the running error bound of `bounded.rs`, the
//! magnitudes of `filter.rs`): each supplies its steps, the order of the steps is the same.

use crate::CodegenError;
use eom_sym::lower::Operand;

/// A renderer's arithmetic on its values (a value with its bound, or with its magnitude).
pub(super) trait Fold {
    /// What the renderer carries per operand.
    type V;

    /// An operand of an instruction.
    fn operand(&self, o: Operand) -> Result<Self::V, CodegenError>;
    /// `a + s·b` with `s = ±1`.
    fn add(&mut self, a: &Self::V, b: &Self::V, negate: bool) -> Result<Self::V, CodegenError>;
    /// `a·b`.
    fn mul(&mut self, a: &Self::V, b: &Self::V) -> Result<Self::V, CodegenError>;
    /// `c·a` for a literal `c`.
    fn scale(&mut self, a: &Self::V, c: f64) -> Result<Self::V, CodegenError>;
    /// `a / b`.
    fn div(&mut self, a: &Self::V, b: &Self::V) -> Result<Self::V, CodegenError>;
    /// The empty sum.
    fn zero(&mut self) -> Self::V;

    /// `c0 + Σ cᵢ·xᵢ`, left to right.
    fn sum(&mut self, c0: f64, terms: &[(Operand, f64)]) -> Result<Self::V, CodegenError> {
        let mut acc = if c0 != 0.0 {
            Some(self.operand(Operand::Lit(c0))?)
        } else {
            None
        };
        for &(x, c) in terms {
            let xv = self.operand(x)?;
            let term = if c.abs() == 1.0 {
                xv
            } else {
                self.scale(&xv, c.abs())?
            };
            acc = Some(match acc {
                None if c < 0.0 => self.scale(&term, -1.0)?,
                None => term,
                Some(a) => self.add(&a, &term, c < 0.0)?,
            });
        }
        Ok(match acc {
            Some(a) => a,
            None => self.zero(),
        })
    }

    /// `coef · Π num / Π den`: the numerator's product scaled, divided once by the
    /// denominator's product.
    fn prod(
        &mut self,
        coef: f64,
        num: &[Operand],
        den: &[Operand],
    ) -> Result<Self::V, CodegenError> {
        let n = match self.product(num)? {
            Some(a) => self.scale(&a, coef)?,
            None => self.operand(Operand::Lit(coef))?,
        };
        match self.product(den)? {
            Some(d) => self.div(&n, &d),
            None => Ok(n),
        }
    }

    /// `Π xs` left to right, `None` for no factor.
    fn product(&mut self, xs: &[Operand]) -> Result<Option<Self::V>, CodegenError> {
        let mut acc = None;
        for &x in xs {
            let xv = self.operand(x)?;
            acc = Some(match acc {
                None => xv,
                Some(a) => self.mul(&a, &xv)?,
            });
        }
        Ok(acc)
    }
}
