//! [`Scope`]: the parameters visible to the parser and to evaluation by name.

use crate::context::ExprPool;
use crate::error::SymError;
use crate::expr::Expr;
use crate::pool::ParamInfo;
use hashbrown::HashMap;

/// An ordered set of named parameters (declaration order is kept: it is the order of values
/// in evaluations and of fields in generated code).
///
/// A scope holds a handle to the pool its parameters live in, so it is `Send + Sync` and keeps
/// that pool alive: a model that carries its scope can move between threads.
#[derive(Clone, Debug, Default)]
pub struct Scope {
    by_name: HashMap<String, usize>,
    order: Vec<Expr>,
    pool: Option<ExprPool>,
}

impl Scope {
    /// An empty scope; its parameters will be declared in the pool current at the first
    /// declaration.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty scope whose parameters are declared in `pool`.
    pub fn in_pool(pool: ExprPool) -> Self {
        Scope {
            pool: Some(pool),
            ..Self::default()
        }
    }

    /// The pool of the parameters (`None` before the first declaration of a scope made with
    /// [`Scope::new`]).
    pub fn pool(&self) -> Option<&ExprPool> {
        self.pool.as_ref()
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
        let pool = self.pool.get_or_insert_with(ExprPool::current).clone();
        let e = pool.enter(|| Expr::new_param(info))?;
        self.by_name.insert(name, self.order.len());
        self.order.push(e);
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
        if self.pool.is_none() {
            self.pool = ExprPool::find(p.pool_serial());
        }
        self.by_name.insert(info.name, self.order.len());
        self.order.push(p);
        Ok(())
    }

    /// The parameter called `name`.
    pub fn get(&self, name: &str) -> Option<Expr> {
        self.by_name.get(name).map(|&k| self.order[k])
    }

    /// The parameter called `name`, or an error listing the known names.
    pub fn lookup(&self, name: &str) -> Result<Expr, SymError> {
        self.get(name).ok_or_else(|| SymError::UnknownParameter {
            name: eom_text::shown(name),
            known: self.names(),
        })
    }

    /// The parameters in declaration order.
    pub fn params(&self) -> Vec<Expr> {
        self.order.clone()
    }

    /// The names in declaration order.
    pub fn names(&self) -> Vec<String> {
        self.order
            .iter()
            .filter_map(|p| p.param_info().map(|p| p.name))
            .collect()
    }

    /// Nominal values in declaration order.
    pub fn nominal_values(&self) -> Vec<f64> {
        self.order
            .iter()
            .filter_map(|p| p.param_info().map(|p| p.nominal))
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
            let k = self.by_name[name];
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
