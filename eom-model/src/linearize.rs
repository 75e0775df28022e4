//! [`Linearizer`]: one call from a model to a state-space model, by any of the three paths.
//!
//! ```
//! use eom_model::*;
//! use eom_sym::Expr;
//!
//! let mut model = Model::new("mass on a spring");
//! let m = model.param("m", 2.0).unwrap();
//! let k = model.param("k", 8.0).unwrap();
//! model.add(Body::new("block").mass(m));
//! model.add(RigidPoint::new("slider").between("block", "ground").forces(2).moments(3).axis(z_axis()));
//! model.add(FlexPoint::new("spring").between("block", "ground").forces(1).axis(z_axis()).stiffness(k, 0));
//!
//! // Symbolic: A = [[0, 1], [−k/m, 0]] as expressions, valid wherever its pivots hold.
//! let sym = Linearizer::new(&model).symbolic().unwrap();
//! assert_eq!(sym.state_space().a[(1, 0)], -k / m);
//! // Numeric at another point, by the robust path:
//! let ss = Linearizer::new(&model).at(&[("k", 18.0)]).method(Method::Robust).run().unwrap();
//! let eig = eom_num::modes::eigenvalues(&ss.state_space.a).unwrap();
//! assert!((eig[1].im - 3.0).abs() < 1e-12);
//! ```

use super::Model;
use super::compiled::SymbolicStateSpace;
use super::reduce::{ReductionReport, reduce};
use super::robust::{RobustReport, reduce_robust};
use crate::aero::resolve_unsteady;
use crate::error::ModelError;
use crate::items::ModelScalar;
use crate::model::assemble;
use crate::warning::Warning;
use eom_num::StateSpace;
use eom_num::deflate::structural_zero_states;
use eom_sym::SymError;
use eom_sym::expr::Expr;
use eom_sym::scalar::Elementary;
use eom_sym::tape::eval_generic;

/// How to reduce the model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// Symbolic-numeric elimination with pivots chosen at the nominal point, evaluated at the
    /// requested point (falls back to nothing: a breakdown is an error).
    Symbolic,
    /// The same elimination run in `f64` at the requested point, pivots chosen there.
    #[default]
    Numeric,
    /// Orthonormal (SVD) complements and descriptor reduction.
    Robust,
}

/// The outcome of [`Linearizer::run`].
#[derive(Clone, Debug)]
pub struct Linearization {
    /// The state-space model at the requested point.
    pub state_space: StateSpace<f64>,
    /// The method that produced it.
    pub method: Method,
    /// Structure report of the elimination paths.
    pub report: Option<ReductionReport>,
    /// Report of the robust path.
    pub robust: Option<RobustReport>,
    /// Warnings.
    pub warnings: Vec<Warning>,
    /// The zero eigenvalues the model's structure proves at this point, one description each
    /// (ignorable coordinates such as a vehicle's lateral position, or a pair of headings of
    /// which only the difference acts): found on the elimination path's state matrix, whose
    /// structural zeros are exact (see `eom_num::deflate`). Analyses of the robust path's
    /// matrix pass the count on (`ModeOptions::structural_zeros`), since that basis hides them
    /// in rounding.
    pub structural_zeros: Vec<String>,
}

/// Builder: `Linearizer::new(&model).at(&[("v", 6.0)]).method(Method::Robust).run()`.
pub struct Linearizer<'a> {
    model: &'a Model<Expr>,
    overrides: Vec<(String, f64)>,
    method: Method,
}

impl<'a> Linearizer<'a> {
    /// Start from a symbolic model (nominal values, numeric path).
    pub fn new(model: &'a Model<Expr>) -> Self {
        Linearizer {
            model,
            overrides: Vec::new(),
            method: Method::default(),
        }
    }

    /// Evaluate at these parameter values (by name; the rest nominal).
    pub fn at(mut self, values: &[(&str, f64)]) -> Self {
        self.overrides
            .extend(values.iter().map(|(k, v)| (k.to_string(), *v)));
        self
    }

    /// Choose the reduction method.
    pub fn method(mut self, m: Method) -> Self {
        self.method = m;
        self
    }

    /// Parameter values in scope order.
    pub fn values(&self) -> Result<Vec<f64>, ModelError> {
        let o: Vec<(&str, f64)> = self
            .overrides
            .iter()
            .map(|(k, v)| (k.as_str(), *v))
            .collect();
        Ok(self.model.scope.values_with(&o)?)
    }

    /// The symbolic state-space model (independent of [`Linearizer::at`]): assembled and
    /// reduced with expressions, compiled for evaluation.
    ///
    /// `unsteady = "auto"` surfaces are decided at the nominal point ([`resolve_unsteady`]);
    /// what they got is among the reduction report's warnings.
    pub fn symbolic(&self) -> Result<SymbolicStateSpace, ModelError> {
        self.model.in_pool(|| {
            let (model, notes) = resolve_unsteady(self.model, &self.model.scope.nominal_values())?;
            let a = assemble(&model)?;
            let mut r = reduce(&a, None)?;
            r.report.warnings.extend(notes);
            SymbolicStateSpace::new(r, &self.model.scope.params())
        })
    }

    /// Run the chosen method at the chosen point.
    pub fn run(&self) -> Result<Linearization, ModelError> {
        self.model.in_pool(|| self.run_in_pool())
    }

    fn run_in_pool(&self) -> Result<Linearization, ModelError> {
        let values = self.values()?;
        if self.method == Method::Symbolic {
            // `auto` decided at the nominal point, by `symbolic`.
            return self.run_method(self.model, values);
        }
        // `auto` decided at this point.
        let (resolved, notes) = resolve_unsteady(self.model, &values)?;
        let mut lin = self.run_method(&resolved, values)?;
        lin.warnings.extend(notes);
        Ok(lin)
    }

    fn run_method(
        &self,
        model: &Model<Expr>,
        values: Vec<f64>,
    ) -> Result<Linearization, ModelError> {
        match self.method {
            Method::Symbolic => {
                let sym = self.symbolic()?;
                let ss = sym.evaluate(&values)?;
                let report = sym.reduction.report.clone();
                Ok(Linearization {
                    warnings: report.warnings.clone(),
                    structural_zeros: structural_zero_states(&ss.a, &ss.names.states),
                    state_space: ss,
                    method: self.method,
                    report: Some(report),
                    robust: None,
                })
            }
            Method::Numeric => {
                let m = model.evaluate(&values)?;
                let a = assemble(&m)?;
                let r = reduce(&a, None)?;
                Ok(Linearization {
                    warnings: r.report.warnings.clone(),
                    structural_zeros: structural_zero_states(
                        &r.state_space.a,
                        &r.state_space.names.states,
                    ),
                    state_space: r.state_space,
                    method: self.method,
                    report: Some(r.report),
                    robust: None,
                })
            }
            Method::Robust => {
                let m = model.evaluate(&values)?;
                let a = assemble(&m)?;
                let (ss, rep) = reduce_robust(&a)?;
                // Counted on the elimination path's matrix at the same point (when it can
                // reduce this model).
                let structural_zeros = reduce(&a, None)
                    .map(|r| structural_zero_states(&r.state_space.a, &r.state_space.names.states))
                    .unwrap_or_default();
                Ok(Linearization {
                    structural_zeros,
                    warnings: rep.warnings.clone(),
                    state_space: ss,
                    method: self.method,
                    report: None,
                    robust: Some(rep),
                })
            }
        }
    }
}

impl Model<Expr> {
    /// The model with every field evaluated in another scalar type (e.g. double-double for
    /// reference computations), with parameter values given in that type in scope order.
    pub fn evaluate_in<S: Elementary + ModelScalar>(
        &self,
        values: &[S],
    ) -> Result<Model<S>, ModelError> {
        let params = self.scope.params();
        if values.len() != params.len() {
            return Err(SymError::Dimension(format!(
                "{} values for the {} parameters of model `{}`",
                values.len(),
                params.len(),
                self.name
            ))
            .into());
        }
        let fields: Vec<Expr> = self.field_values();
        let index: Vec<u32> = params
            .iter()
            .map(|p| p.param_index().expect("parameter"))
            .collect();
        let vals = eval_generic::<S>(&fields, |i| {
            index.iter().position(|&k| k == i).map(|k| values[k])
        })?;
        let mut k = 0;
        Ok(self.map(&mut |_| {
            k += 1;
            vals[k - 1]
        }))
    }
}
