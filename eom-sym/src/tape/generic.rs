//! [`eval_generic`]: evaluation in any [`Elementary`] scalar, the reference the tape agrees
//! with.

use crate::context::with_serial;
use crate::error::SymError;
use crate::expr::{Expr, reachable};
use crate::pool::{Id, Shape, ShapeBuf};
use crate::scalar::Elementary;
use hashbrown::HashMap;

/// Evaluate `roots` in any [`Elementary`] scalar, with `value_of(param_index)` giving the value
/// of each parameter (pool index, see [`Expr::param_index`]); `None` is an error naming the
/// parameter. This is the "recursive" reference evaluation (each node once, memoised).
pub fn eval_generic<S: Elementary>(
    roots: &[Expr],
    value_of: impl Fn(u32) -> Option<S>,
) -> Result<Vec<S>, SymError> {
    for r in roots {
        r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
    }
    let reach = reachable(roots);
    let pos: HashMap<Id, usize> = reach.ids.iter().enumerate().map(|(k, &i)| (i, k)).collect();
    // The shapes are copied out first: the pool must not be held while the scalar arithmetic
    // runs, since `S` may itself be `Expr`.
    let (shapes, names): (Vec<ShapeBuf>, HashMap<u32, String>) = with_serial(reach.serial, |p| {
        let shapes: Vec<ShapeBuf> = reach.ids.iter().map(|&i| p.shape(i).to_buf()).collect();
        let names = shapes
            .iter()
            .filter_map(|s| match s {
                Shape::Param(i) => Some((*i, p.param(*i).name.clone())),
                _ => None,
            })
            .collect();
        (shapes, names)
    });
    let rat = |c: Id| match &shapes[pos[&c]] {
        Shape::Num(r) => r.clone(),
        _ => unreachable!("product exponents are rational"),
    };
    let mut val: Vec<S> = Vec::with_capacity(shapes.len());
    for shape in &shapes {
        let v = match shape {
            Shape::Param(i) => value_of(*i).ok_or_else(|| SymError::MissingParameter {
                name: names[i].clone(),
            })?,
            _ => shape
                .eval(|c| val[pos[&c]], rat)
                .expect("valid nodes have values"),
        };
        val.push(v);
    }
    Ok(reach.roots.iter().map(|r| val[pos[r]]).collect())
}

/// Evaluate `roots` at the nominal values of their parameters, in any [`Elementary`] scalar
/// (parameter nominal values are converted from `f64`).
pub fn eval_nominal<S: Elementary>(roots: &[Expr]) -> Result<Vec<S>, SymError> {
    let (serial, _) = crate::context::unify(roots);
    eval_generic(roots, |i| {
        crate::expr::param_in(serial, i).map(|p| S::from_f64(p.nominal()))
    })
}
