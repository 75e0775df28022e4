//! [`Scope`]: the parameters visible to the parser and to evaluation by name.

use crate::error::SymError;
use crate::expr::Expr;
use crate::pool::{ExprPool, ParamInfo};
use hashbrown::HashMap;

/// An ordered set of named parameters (declaration order is kept: it is the order of values
/// in evaluations and of fields in generated code).
///
/// A scope stores parameter indices of the pool, not expressions, so it is plain data
/// (`Send + Sync`): a numeric model that carries its scope can move between threads. The
/// expressions it hands out belong to the thread whose pool declared the parameters.
#[derive(Clone, Debug, Default)]
pub struct Scope {
    by_name: HashMap<String, u32>,
    order: Vec<u32>,
}

fn expr_of(index: u32) -> Expr {
    Expr::from_param_index(index).expect("a scope refers to parameters of this thread's pool")
}

impl Scope {
    /// An empty scope.
    pub fn new() -> Self {
        Self::default()
    }

    /// Declare a new parameter with a nominal value. A duplicate name is an error.
    pub fn declare(&mut self, name: &str, nominal: f64) -> Result<Expr, SymError> {
        self.declare_info(ParamInfo {
            name: name.to_string(),
            nominal,
            unit: None,
            description: None,
            assume: Default::default(),
        })
    }

    /// Declare a new parameter from full metadata. A duplicate name is an error.
    pub fn declare_info(&mut self, info: ParamInfo) -> Result<Expr, SymError> {
        if self.by_name.contains_key(&info.name) {
            return Err(SymError::BadParameter {
                name: info.name,
                problem: "declared twice".into(),
            });
        }
        let name = info.name.clone();
        let e = Expr::new_param(info)?;
        let index = e.param_index().expect("a new parameter");
        self.by_name.insert(name, index);
        self.order.push(index);
        Ok(e)
    }

    /// Add an existing parameter expression. A duplicate name or a non-parameter is an error.
    pub fn insert(&mut self, p: Expr) -> Result<(), SymError> {
        let info = p.param_info().ok_or_else(|| SymError::BadParameter {
            name: p.to_string(),
            problem: "is not a parameter".into(),
        })?;
        if self.by_name.contains_key(&info.name) {
            return Err(SymError::BadParameter {
                name: info.name,
                problem: "declared twice".into(),
            });
        }
        let index = p.param_index().expect("checked above");
        self.by_name.insert(info.name, index);
        self.order.push(index);
        Ok(())
    }

    /// The parameter called `name`.
    pub fn get(&self, name: &str) -> Option<Expr> {
        self.by_name.get(name).map(|&i| expr_of(i))
    }

    /// The parameter called `name`, or an error listing the known names.
    pub fn lookup(&self, name: &str) -> Result<Expr, SymError> {
        self.get(name).ok_or_else(|| SymError::UnknownParameter {
            name: name.to_string(),
            known: self.names(),
        })
    }

    /// The parameters in declaration order.
    pub fn params(&self) -> Vec<Expr> {
        self.order.iter().map(|&i| expr_of(i)).collect()
    }

    /// The names in declaration order.
    pub fn names(&self) -> Vec<String> {
        self.order
            .iter()
            .filter_map(|&i| ExprPool::param_info(i).map(|p| p.name))
            .collect()
    }

    /// Nominal values in declaration order.
    pub fn nominal_values(&self) -> Vec<f64> {
        self.order
            .iter()
            .filter_map(|&i| ExprPool::param_info(i).map(|p| p.nominal))
            .collect()
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Is the scope empty?
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Values for all parameters: the nominal values, overridden by `overrides` (by name).
    /// An unknown name is an error listing the known ones.
    pub fn values_with(&self, overrides: &[(&str, f64)]) -> Result<Vec<f64>, SymError> {
        let mut v = self.nominal_values();
        for &(name, x) in overrides {
            self.lookup(name)?;
            let index = self.by_name[name];
            let k = self
                .order
                .iter()
                .position(|&q| q == index)
                .expect("in scope");
            if !x.is_finite() {
                return Err(SymError::BadParameter {
                    name: name.to_string(),
                    problem: format!("value {x} is not finite"),
                });
            }
            v[k] = x;
        }
        Ok(v)
    }
}
