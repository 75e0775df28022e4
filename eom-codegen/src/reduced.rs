//! Reduced models as functions of the parameters: the projection bases of a balanced (or modal)
//! truncation computed once at the nominal point, applied to the symbolic matrices —
//! `A_r(p) = Wᵀ A(p) V`, `B_r(p) = Wᵀ B(p)`, `C_r(p) = C(p) V`, `D_r(p) = D(p)`,
//! `Phys_r(p) = Phys(p) V` (a Petrov–Galerkin projection with fixed bases, `WᵀV = I`).
//!
//! At the nominal point this is the reduction [`eom_num::model_reduction`] computes, with its
//! bound `2 Σ σ`; away from it the bases are no longer balanced for the model there, and the
//! error grows with the distance (`docs/reduction.md` measures it). The validity checks of the
//! full model's symbolic reduction stay those of the reduced code: a point outside the region
//! is reported as before. States kept whole by the reduction (structural zeros) stay exact:
//! their columns of `A(p)V` are exact sums of opposite columns.

use eom_model::{Reduction, SymbolicStateSpace};
use eom_num::StateSpace;
use eom_num::model_reduction::{ReducedModel, Reducer, ReductionMethod};
use eom_sym::Expr;
use nalgebra::DMatrix;

use crate::{CodegenError, EmitOptions, Emitted, emit_with_stats};

/// A symbolic reduced model and the numeric reduction at the nominal point it came from.
pub struct ReducedSymbolic {
    /// The reduced model with every parameter symbolic.
    pub sym: SymbolicStateSpace,
    /// The reduction at the nominal point (bases, Hankel singular values, bound, error).
    pub nominal: ReducedModel,
}

/// `M · V` with the constant `v`, skipping structural zeros.
fn times(m: &DMatrix<Expr>, v: &DMatrix<f64>) -> Result<DMatrix<Expr>, CodegenError> {
    let mut out = DMatrix::from_element(m.nrows(), v.ncols(), Expr::zero());
    for i in 0..m.nrows() {
        for j in 0..v.ncols() {
            let mut terms = Vec::new();
            for l in 0..m.ncols() {
                let (e, c) = (m[(i, l)], v[(l, j)]);
                if !e.is_zero() && c != 0.0 {
                    terms.push(if c == 1.0 { e } else { e * Expr::float(c)? });
                }
            }
            out[(i, j)] = Expr::sum(terms);
        }
    }
    Ok(out)
}

/// `Wᵀ · M` with the constant `w`.
fn left(w: &DMatrix<f64>, m: &DMatrix<Expr>) -> Result<DMatrix<Expr>, CodegenError> {
    let mt = DMatrix::from_fn(m.ncols(), m.nrows(), |i, j| m[(j, i)]);
    let p = times(&mt, w)?;
    Ok(DMatrix::from_fn(p.ncols(), p.nrows(), |i, j| p[(j, i)]))
}

/// Reduces `sym` at its nominal point to `order` states by `method` (balanced or modal; the
/// DC-matched form is not a projection) and applies the bases to the symbolic matrices.
///
/// Errors: [`CodegenError::BadOption`] for matchdc, [`CodegenError::Num`] from the reduction
/// (an order below the kept states, …), [`CodegenError::Model`] when the nominal point is
/// outside the validity region.
pub fn reduce_symbolic(
    sym: &SymbolicStateSpace,
    order: usize,
    method: ReductionMethod,
) -> Result<ReducedSymbolic, CodegenError> {
    if method == ReductionMethod::MatchDc {
        return Err(CodegenError::BadOption {
            option: "reduce",
            problem: "the DC-matched reduction is not a projection of A(p), so it has no \
                      parametric form here: use balanced or modal"
                .into(),
        });
    }
    let nominal: Vec<f64> = sym.params.iter().map(|p| p.nominal()).collect();
    let ss = sym.evaluate(&nominal)?;
    let reduced = Reducer::new(&ss).method(method).order(order).run()?;
    let (v, w) = (&reduced.v, &reduced.w);
    let full = sym.state_space();
    let build = || -> Result<StateSpace<Expr>, CodegenError> {
        Ok(StateSpace {
            a: left(w, &times(&full.a, v)?)?,
            b: left(w, &full.b)?,
            c: times(&full.c, v)?,
            d: full.d.clone(),
            phys: times(&full.phys, v)?,
            names: eom_num::SignalNames {
                states: reduced.state_space.names.states.clone(),
                ..full.names.clone()
            },
        })
    };
    let state_space = match sym.pool() {
        Some(pool) => pool.enter(build)?,
        None => build()?,
    };
    let reduction = Reduction {
        state_space,
        ..sym.reduction.clone()
    };
    let rsym = SymbolicStateSpace::new(reduction, &sym.params)?;
    Ok(ReducedSymbolic {
        sym: rsym,
        nominal: reduced,
    })
}

fn real_array(name: &str, doc: &str, values: &[f64]) -> String {
    let list: Vec<String> = values.iter().map(|x| format!("{x:e} as Real")).collect();
    format!(
        "#[doc = {doc:?}]\npub const {name}: [Real; {}] = [{}];\n",
        values.len(),
        list.join(", ")
    )
}

/// The module of the reduced model: [`reduce_symbolic`], then [`emit_with_stats`] with the
/// reduction described in the module's documentation and its bases as constants
/// (`FULL_STATES`, `REDUCE_V`: `x ≈ V z`, `REDUCE_W`: `z = Wᵀ x`, both column-major
/// `FULL_STATES × N_STATES`, `REDUCE_BOUND`: the bound at the nominal point).
pub fn emit_reduced(
    sym: &SymbolicStateSpace,
    order: usize,
    method: ReductionMethod,
    opts: &EmitOptions,
) -> Result<(Emitted, ReducedModel), CodegenError> {
    let r = reduce_symbolic(sym, order, method)?;
    let nom = &r.nominal;
    let mut o = opts.clone();
    let bound = nom.bound.unwrap_or(f64::NAN);
    o.notes.push(format!(
        "Reduced from {} to {} states by {} truncation at the nominal point ({} kept whole: zero, marginal and unstable modes); the bases are fixed there and applied to A(p), B(p), C(p): `A_r = Wᵀ A V`, `B_r = Wᵀ B`, `C_r = C V`, `D_r = D` (`REDUCE_V`, `REDUCE_W`). At the nominal point ‖G − G_r‖∞ ≤ {} (2Σσ; measured {:e}); away from it the error grows (docs/reduction.md).",
        nom.full_states,
        nom.order(),
        method.name(),
        nom.kept,
        if bound.is_finite() { format!("{bound:e}") } else { "— (modal: no bound)".into() },
        nom.error.hinf,
    ));
    let mut items = format!(
        "/// States of the full model the reduction started from.\npub const FULL_STATES: usize = {};\n",
        nom.full_states
    );
    items.push_str(&real_array(
        "REDUCE_V",
        " `x ≈ V z`: the full state from the reduced one (column-major, `FULL_STATES × N_STATES`).",
        nom.v.as_slice(),
    ));
    items.push_str(&real_array(
        "REDUCE_W",
        " `z = Wᵀ x`: the reduced state of a full one (column-major `W`, `FULL_STATES × N_STATES`; `WᵀV = I`).",
        nom.w.as_slice(),
    ));
    if bound.is_finite() {
        items.push_str(&format!(
            "/// The bound 2Σσ on the H∞ norm of the reduction's error at the nominal point.\npub const REDUCE_BOUND: Real = {bound:e} as Real;\n"
        ));
    }
    o.extra_items.push(items);
    let e = emit_with_stats(&r.sym, &o)?;
    Ok((e, r.nominal))
}
