//! Substitution of parameters by expressions or values.

use crate::error::SymError;
use crate::expr::Expr;
use crate::tape::eval_generic;
use hashbrown::HashMap;

impl Expr {
    /// Replace parameters by expressions: `map` pairs a parameter with its replacement. The
    /// result is rebuilt through the smart constructors, so it is canonical (and folds what
    /// becomes constant).
    pub fn subs(self, map: &[(Expr, Expr)]) -> Result<Expr, SymError> {
        Ok(subs_many(&[self], map)?[0])
    }

    /// Replace parameters by numeric values (exact when the value is an integer or a short
    /// dyadic fraction, a float constant otherwise).
    pub fn subs_values(self, map: &[(Expr, f64)]) -> Result<Expr, SymError> {
        let m: Vec<(Expr, Expr)> = map
            .iter()
            .map(|&(p, v)| Ok((p, Expr::float(v)?)))
            .collect::<Result<_, SymError>>()?;
        self.subs(&m)
    }
}

/// [`Expr::subs`] for several roots at once, sharing the rebuilt DAG.
pub fn subs_many(roots: &[Expr], map: &[(Expr, Expr)]) -> Result<Vec<Expr>, SymError> {
    let mut by_index: HashMap<u32, Expr> = HashMap::new();
    for &(p, r) in map {
        let idx = p.param_index().ok_or_else(|| SymError::BadParameter {
            name: p.to_string(),
            problem: "only parameters can be substituted".into(),
        })?;
        by_index.insert(idx, r);
    }
    let (serial, _) = crate::context::unify(roots);
    crate::expr::in_pool_of(roots, || {
        eval_generic::<Expr>(roots, |i| {
            by_index
                .get(&i)
                .copied()
                .or_else(|| crate::expr::param_in(serial, i))
        })
    })
}
