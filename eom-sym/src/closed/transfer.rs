//! Transfer functions `G(s) = C (sI − A)⁻¹ B + D` as ratios of polynomials in `s`.

use super::{ClosedForms, FieldIn, SPolynomial, det, variable_s};
use crate::error::SymError;
use crate::expr::Expr;
use nalgebra::DMatrix;

/// `G(s) = numerator(s) / denominator(s)` from one input to one output, with the common
/// factors of numerator and denominator cancelled exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct TransferFunction {
    /// The output (row of `C`).
    pub output: usize,
    /// The input (column of `B`).
    pub input: usize,
    /// The numerator.
    pub numerator: SPolynomial,
    /// The denominator; its leading coefficient is positive where the parameters' declared
    /// signs decide it.
    pub denominator: SPolynomial,
    /// Whether the coefficients are in normal form (common factors cancelled); `false` when a
    /// bound was reached: the ratio is then `det([sI − A, B]; [−C, D]) / det(sI − A)` itself.
    pub normalized: bool,
}

impl ClosedForms {
    /// The transfer function from input `input` to output `output`.
    ///
    /// Uses `det([[sI − A, b], [−c, d]]) = det(sI − A)·(c (sI − A)⁻¹ b + d)`.
    pub fn transfer_function(
        &self,
        abcd: [&DMatrix<Expr>; 4],
        output: usize,
        input: usize,
    ) -> Result<TransferFunction, SymError> {
        let [a, b, c, d] = abcd;
        let n = a.nrows();
        if a.ncols() != n || b.nrows() != n || c.ncols() != n || input >= b.ncols() {
            return Err(SymError::Dimension(format!(
                "transfer function from input {input} to output {output} of A {}×{}, B {}×{}, \
                 C {}×{}",
                a.nrows(),
                a.ncols(),
                b.nrows(),
                b.ncols(),
                c.nrows(),
                c.ncols()
            )));
        }
        if output >= c.nrows() || d.nrows() != c.nrows() || d.ncols() != b.ncols() {
            return Err(SymError::Dimension(format!(
                "output {output} of C {}×{} with D {}×{}",
                c.nrows(),
                c.ncols(),
                d.nrows(),
                d.ncols()
            )));
        }
        // The limit is the model's size: the bordered determinant is one larger.
        self.check_size(n, "a transfer function")?;
        let entries: Vec<Expr> = a.iter().chain(b.iter()).chain(c.iter()).copied().collect();
        crate::expr::in_pool_of(&entries, || {
            let mut m = det::pencil(None, a);
            for (i, row) in m.iter_mut().enumerate() {
                row.push((b[(i, input)], Expr::zero()));
            }
            let mut last: Vec<det::Linear> =
                (0..n).map(|j| (-c[(output, j)], Expr::zero())).collect();
            last.push((d[(output, input)], Expr::zero()));
            m.push(last);
            let num = det::det_in_s(&m);
            let den = det::det_in_s(&det::pencil(None, a));
            let s = variable_s()?;
            let poly = |c: &[Expr]| {
                SPolynomial {
                    coefficients: c.to_vec(),
                }
                .to_expr(s)
            };
            match self.in_s(&[poly(&num), poly(&den)], s)? {
                Some((mut field, rfs)) => {
                    Ok(normal_ratio(&mut field, &rfs[0], &rfs[1], output, input))
                }
                None => Ok(TransferFunction {
                    output,
                    input,
                    numerator: SPolynomial { coefficients: num },
                    denominator: SPolynomial { coefficients: den },
                    normalized: false,
                }),
            }
        })
    }
}

/// The ratio of two rational functions of the field, cancelled, as polynomials in `s`.
fn normal_ratio(
    f: &mut FieldIn,
    num: &super::Rf,
    den: &super::Rf,
    output: usize,
    input: usize,
) -> TransferFunction {
    let budget = &mut f.field.budget;
    let ratio = den.powi(-1, budget).and_then(|inv| num.mul(&inv, budget));
    let Ok(ratio) = ratio else {
        // `den` (a determinant with leading term sⁿ) is never zero; a bound was reached.
        return TransferFunction {
            output,
            input,
            numerator: SPolynomial {
                coefficients: vec![],
            },
            denominator: SPolynomial {
                coefficients: vec![Expr::one()],
            },
            normalized: false,
        };
    };
    let mut top: Vec<Expr> = f.coeffs(&ratio.num).iter().map(|p| f.render(p)).collect();
    let mut bottom: Vec<Expr> = f.coeffs(&ratio.den).iter().map(|p| f.render(p)).collect();
    if bottom
        .last()
        .is_some_and(|c| c.sign().is_nonpos() && !c.is_zero())
    {
        top = top.into_iter().map(|c| -c).collect();
        bottom = bottom.into_iter().map(|c| -c).collect();
    }
    while top.len() > 1 && top.last().is_some_and(|c| c.is_zero()) {
        top.pop();
    }
    TransferFunction {
        output,
        input,
        numerator: SPolynomial { coefficients: top },
        denominator: SPolynomial {
            coefficients: bottom,
        },
        normalized: true,
    }
}
