//! Eigenvalue sensitivities `∂λ/∂p` of a symbolic state-space model at a point: `∂A/∂p` is
//! exact (the symbolic derivative of every entry of A, compiled), the eigenvectors numeric.

use crate::compiled::SymbolicStateSpace;
use crate::error::ModelError;
use eom_num::sensitivity::{EigenSensitivity, eigenvalue_sensitivities};
use eom_sym::{Expr, Tape, diff_many};
use nalgebra::DMatrix;

/// The sensitivities of every eigenvalue to every parameter at one point.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensitivities {
    /// The parameters, in the order of [`EigenSensitivity::derivatives`].
    pub params: Vec<String>,
    /// One entry per eigenvalue, sorted by real then imaginary part.
    pub eigenvalues: Vec<EigenSensitivity>,
}

/// `∂λ/∂p` of every eigenvalue of `sym`'s A at `values` (in the order of `sym.params`), for
/// every parameter. An eigenvalue that is defective or nearly so (condition number above
/// [`eom_num::sensitivity::DEFECTIVE_CONDITION`]) gets no derivatives.
pub fn sensitivities(
    sym: &SymbolicStateSpace,
    values: &[f64],
) -> Result<Sensitivities, ModelError> {
    let ss = sym.state_space();
    let n = ss.a.nrows();
    if n == 0 {
        return Ok(Sensitivities {
            params: sym.params.iter().map(|p| p.to_string()).collect(),
            eigenvalues: Vec::new(),
        });
    }
    let entries: Vec<Expr> = ss.a.iter().copied().collect();
    let mut roots = Vec::with_capacity(entries.len() * sym.params.len());
    for &p in &sym.params {
        roots.extend(diff_many(&entries, p));
    }
    let tape = Tape::new(&roots, &sym.params)?;
    let d = tape.eval_vec(values)?;
    let da: Vec<DMatrix<f64>> = d
        .chunks_exact(n * n)
        .map(|c| DMatrix::from_column_slice(n, n, c))
        .collect();
    let a = sym.evaluate(values)?.a;
    Ok(Sensitivities {
        params: sym.params.iter().map(|p| p.to_string()).collect(),
        eigenvalues: eigenvalue_sensitivities(&a, &da)?,
    })
}
