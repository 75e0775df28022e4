//! The bicycle's lean/steer eigenvalues against the benchmark (Meijaard, Papadopoulos, Ruina &
//! Schwab 2007, Proc. R. Soc. A 463:1955–1982) at the speeds of its Table 2 (v = 1…10 m/s),
//! to the 17 digits of `tests/data/bicycle_eigs_126_speeds.csv` (see `tests/data/README.md`).

use super::WorkPrecisionError;
use super::reference::ReferenceModel;
use super::{EigenvaluesAt, Row, timing::median};
use num_complex::Complex64;

/// The published points: parameter values and the four lean/steer eigenvalues.
pub struct Published {
    cases: Vec<(Vec<f64>, Vec<Complex64>)>,
    reference_err: f64,
}

/// The four eigenvalues of the largest magnitude (the lean/steer ones: the other two, heading
/// and lateral position, are structural zeros).
fn lean_steer(e: &[Complex64]) -> Vec<Complex64> {
    let mut e = e.to_vec();
    e.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
    e.truncate(4);
    e
}

impl Published {
    /// The Table 2 speeds of the bicycle (other parameters nominal), with the reference's own
    /// error against them.
    pub fn new(
        model: &eom_model::Model,
        refm: &ReferenceModel<'_>,
    ) -> Result<Self, WorkPrecisionError> {
        let names = model.scope.names();
        let speed = names.iter().position(|n| n == "v").ok_or_else(|| {
            WorkPrecisionError::Reference("the bicycle has no parameter v".into())
        })?;
        // The table is the tests crate's reference data (its README cites the source).
        let table = crate::compare::read_csv(include_str!(
            "../../../tests/data/bicycle_eigs_126_speeds.csv"
        ));
        let mut cases = Vec::new();
        for row in table.iter().filter(|r| {
            let v = r[0];
            v >= 1.0 && v.fract().abs() < 1e-9
        }) {
            let mut values = model.scope.nominal_values();
            values[speed] = row[0].round();
            let eig: Vec<Complex64> = (0..4)
                .map(|k| Complex64::new(row[1 + 2 * k], row[2 + 2 * k]))
                .collect();
            cases.push((values, eig));
        }
        let mut reference_err = 0.0f64;
        for (values, want) in &cases {
            let r = refm.at(values)?;
            reference_err = reference_err.max(crate::compare::max_abs_error(
                &lean_steer(&r.eigenvalues),
                want,
            ));
        }
        Ok(Published {
            cases,
            reference_err,
        })
    }

    /// Largest absolute error of a method's four lean/steer eigenvalues over the speeds
    /// (infinite when the method fails at one).
    pub fn error(&self, eval: &EigenvaluesAt<'_>) -> Result<f64, WorkPrecisionError> {
        let mut worst = 0.0f64;
        for (values, want) in &self.cases {
            match eval(values)? {
                Some((_, e)) => {
                    worst = worst.max(crate::compare::max_abs_error(&lean_steer(&e), want));
                }
                None => return Ok(f64::INFINITY),
            }
        }
        Ok(worst)
    }

    /// The row of the double-double reference itself (no time, no random-point errors).
    pub fn reference_row(&self, model: &str) -> Row {
        Row {
            model: model.into(),
            method: "reference (double-double)".into(),
            time_ns: median(&mut []),
            matrix_err: None,
            eig_err: 0.0,
            nonzero_eig_err: 0.0,
            failures: 0,
            points: 0,
            published_err: Some(self.reference_err),
        }
    }
}
