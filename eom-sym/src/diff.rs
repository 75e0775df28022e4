//! Symbolic derivatives with respect to a parameter.

use crate::error::SymError;
use crate::expr::{Expr, ExprView, reachable};
use crate::rational::Rational;
use hashbrown::HashMap;

impl Expr {
    /// `∂self/∂p` for a parameter `p`. Every unique node is differentiated once (memoised over
    /// the DAG), so the derivative of a shared DAG stays shared.
    ///
    /// ```
    /// use eom_sym::Expr;
    /// let x = Expr::param("x", 2.0).unwrap();
    /// let d = (x.powi(3) + x.sin()).diff(x).unwrap();
    /// assert!((d.nominal() - (12.0 + 2f64.cos())).abs() < 1e-15);
    /// ```
    pub fn diff(self, p: Expr) -> Result<Expr, SymError> {
        if p.param_index().is_none() {
            return Err(SymError::BadParameter {
                name: p.to_string(),
                problem: "derivatives are taken with respect to a parameter".into(),
            });
        }
        self.check()?;
        Ok(diff_many(&[self], p)[0])
    }
}

/// Derivatives of several roots with respect to the parameter `p`, sharing work.
pub fn diff_many(roots: &[Expr], p: Expr) -> Vec<Expr> {
    crate::expr::in_pool_of(roots, || diff_in_pool(roots, p))
}

fn diff_in_pool(roots: &[Expr], p: Expr) -> Vec<Expr> {
    let reach = reachable(roots);
    let (serial, ids) = (reach.serial, &reach.ids);
    let mut d: HashMap<u32, Expr> = HashMap::with_capacity(ids.len());
    let zero = Expr::zero();
    for &id in ids {
        let e = Expr::new(id, serial);
        let get = |x: Expr, d: &HashMap<u32, Expr>| d.get(&x.id()).copied().unwrap_or(zero);
        let de = match e.view() {
            ExprView::Rational(_) | ExprView::Float(_) | ExprView::Constant(_) => zero,
            ExprView::Invalid(_) => e,
            ExprView::Param(..) => {
                if e == p {
                    Expr::one()
                } else {
                    zero
                }
            }
            ExprView::Sum { terms, .. } => Expr::sum(
                terms
                    .iter()
                    .map(|&(t, c)| c * get(t, &d))
                    .filter(|x| !x.is_zero()),
            ),
            ExprView::Product { coef, factors } => {
                let mut parts = Vec::new();
                for (i, (b, ex)) in factors.iter().enumerate() {
                    let db = get(*b, &d);
                    if db.is_zero() {
                        continue;
                    }
                    let mut items = vec![coef, Expr::from_rational(ex.clone())];
                    for (j, (bj, ej)) in factors.iter().enumerate() {
                        if j != i {
                            items.push(bj.pow_rational(ej.clone()));
                        }
                    }
                    let em1 = ex.sub(&Rational::ONE).unwrap_or(Rational::ZERO);
                    items.push(b.pow_rational(em1));
                    items.push(db);
                    parts.push(Expr::product(items));
                }
                Expr::sum(parts)
            }
            ExprView::Pow(a, b) => {
                let (da, db) = (get(a, &d), get(b, &d));
                if da.is_zero() && db.is_zero() {
                    zero
                } else {
                    e * (db * a.ln() + b * da / a)
                }
            }
            ExprView::Func(f, a) => {
                let da = get(a, &d);
                if da.is_zero() {
                    zero
                } else {
                    f.derivative(a, e) * da
                }
            }
            ExprView::Atan2(y, x) => {
                let (dy, dx) = (get(y, &d), get(x, &d));
                if dy.is_zero() && dx.is_zero() {
                    zero
                } else {
                    (x * dy - y * dx) / (x.powi(2) + y.powi(2))
                }
            }
        };
        if !de.is_zero() {
            d.insert(id, de);
        }
    }
    reach
        .roots
        .iter()
        .map(|r| d.get(r).copied().unwrap_or(zero))
        .collect()
}
