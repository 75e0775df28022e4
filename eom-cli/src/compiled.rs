//! [`CompiledModel`]: the numeric half of a [`SymbolicStateSpace`], shareable between threads.
//!
//! `SymbolicStateSpace` holds expressions, which belong to the thread that built them, so it
//! cannot be used from the sweep's worker threads. Its evaluation needs only the compiled
//! [`Tape`] (plain data) and the layout of the tape's outputs, which is documented on
//! [`SymbolicStateSpace::tape`]: the entries of A, B, C, D and phys, column-major, then for
//! each validity check its value followed by the entries of its row (pivots) or scale
//! (negligible entries). This type copies exactly that and applies the same decision,
//! [`ValidityCheck::holds`]; [`CompiledModel::new`] confirms at the nominal point that it
//! reproduces `SymbolicStateSpace::evaluate` bit for bit.
//!
//! TODO(lead): once eom-sym offers a `Send + Sync` evaluator of its own (proposal in the
//! eom-cli report: `SymbolicStateSpace::compiled() -> &CompiledStateSpace`), use it and delete
//! this module.

use crate::error::CliError;
use eom_sym::SymError;
use eom_sym::Tape;
use eom_sym::model::{SymbolicStateSpace, ValidityCheck};
use nalgebra::DMatrix;

/// One validity check: where its numbers are in the tape output.
#[derive(Clone, Debug)]
struct CheckSlot {
    what: String,
    start: usize,
    len: usize,
    pivot: bool,
}

/// The state matrix A of a symbolic model as a function of the parameter values, with its
/// validity region; `Send + Sync`.
#[derive(Clone, Debug)]
pub struct CompiledModel {
    tape: Tape,
    states: usize,
    matrix_entries: usize,
    checks: Vec<CheckSlot>,
}

impl CompiledModel {
    /// Takes the tape and output layout of `sym`, and checks the copy against
    /// [`SymbolicStateSpace::evaluate`] at `nominal` (parameter values in the order of
    /// `sym.params`).
    pub fn new(sym: &SymbolicStateSpace, nominal: &[f64]) -> Result<CompiledModel, CliError> {
        let ss = sym.state_space();
        let matrix_entries = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys]
            .iter()
            .map(|m| m.len())
            .sum();
        let mut start = matrix_entries;
        let mut checks = Vec::with_capacity(sym.reduction.checks.len());
        for c in &sym.reduction.checks {
            let (len, pivot) = match c {
                ValidityCheck::Pivot { row, .. } => (1 + row.len(), true),
                ValidityCheck::Negligible { scale, .. } => (1 + scale.len(), false),
            };
            checks.push(CheckSlot {
                what: c.what().to_string(),
                start,
                len,
                pivot,
            });
            start += len;
        }
        let compiled = CompiledModel {
            tape: sym.tape().clone(),
            states: ss.a.nrows(),
            matrix_entries,
            checks,
        };
        if start != compiled.tape.n_outputs() {
            return Err(CliError::Inconsistent(format!(
                "the tape of the symbolic model has {} outputs, its matrices and checks {start}",
                compiled.tape.n_outputs()
            )));
        }
        let same = match (sym.evaluate(nominal), compiled.state_matrix(nominal)) {
            (Ok(s), Ok(a)) => {
                s.a.iter()
                    .zip(a.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            }
            (Err(e1), Err(e2)) => e1 == e2,
            _ => false,
        };
        if !same {
            return Err(CliError::Inconsistent(
                "the compiled state matrix differs from SymbolicStateSpace::evaluate at the \
                 nominal point (has the tape layout of eom-sym changed?)"
                    .into(),
            ));
        }
        Ok(compiled)
    }

    /// A at parameter values (in the order of the symbolic model's parameters). Outside the
    /// validity region: [`SymError::PivotBreakdown`] naming the check; a non-finite entry:
    /// [`SymError::EvalNonFinite`] — the same decisions as
    /// [`SymbolicStateSpace::evaluate`].
    pub fn state_matrix(&self, values: &[f64]) -> Result<DMatrix<f64>, SymError> {
        let mut out = vec![0.0; self.tape.n_outputs()];
        let mut work = vec![0.0; self.tape.work_len()];
        self.tape.eval_into(values, &mut out, &mut work)?;
        for c in &self.checks {
            let v = out[c.start];
            let others = &out[c.start + 1..c.start + c.len];
            if !ValidityCheck::<f64>::holds(v, others, c.pivot) {
                return Err(SymError::PivotBreakdown(format!(
                    "{} (value {v:.3e}, largest entry of its row {:.3e})",
                    c.what,
                    others.iter().fold(0.0f64, |a, b| a.max(b.abs()))
                )));
            }
        }
        if let Some(k) = out[..self.matrix_entries]
            .iter()
            .position(|v| !v.is_finite())
        {
            return Err(SymError::EvalNonFinite {
                what: format!("state-space entry {k}"),
                value: out[k],
            });
        }
        let n = self.states;
        Ok(DMatrix::from_column_slice(n, n, &out[..n * n]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use eom_sym::model::Linearizer;

    /// The copy must agree with the library at points inside and outside the validity region.
    #[test]
    fn agrees_with_symbolic_evaluate_inside_and_outside_the_region() {
        let model = models::build("bicycle", &[]).unwrap();
        let sym = Linearizer::new(&model).symbolic().unwrap();
        let names = model.scope.names();
        let nominal = model.scope.nominal_values();
        let compiled = CompiledModel::new(&sym, &nominal).unwrap();
        let (kc, kv) = (
            names.iter().position(|n| n == "c").unwrap(),
            names.iter().position(|n| n == "v").unwrap(),
        );
        let w = nominal[names.iter().position(|n| n == "w").unwrap()];
        let mut breakdowns = 0;
        for (c, v) in [
            (0.08, 0.0),
            (0.08, 7.5),
            (-0.5, 3.0),
            (-w, 5.0),
            (-w * (1.0 + 1e-6), 5.0),
        ] {
            let mut x = nominal.clone();
            x[kc] = c;
            x[kv] = v;
            match (sym.evaluate(&x), compiled.state_matrix(&x)) {
                (Ok(s), Ok(a)) => assert_eq!(s.a, a, "c = {c}, v = {v}"),
                (Err(e1), Err(e2)) => {
                    assert_eq!(e1, e2);
                    assert!(matches!(e2, SymError::PivotBreakdown(_)), "{e2}");
                    breakdowns += 1;
                }
                (r1, r2) => panic!("c = {c}: library {:?}, copy {:?}", r1.err(), r2.err()),
            }
        }
        // c = −w puts the rear tyre's pivot −w − c at zero.
        assert!(breakdowns >= 1);
    }
}
