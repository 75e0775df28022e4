//! The model's matrices in closed form (as `eom symbolic` prints them): the parameters not
//! kept substituted by their default values as exact decimals, the entries through the
//! bounded e-graph simplification, as text in the parser's syntax and as LaTeX.

use crate::errors::eom_error;
use crate::source::Source;
use eom_model::Linearizer;
use eom_sym::{Expr, Scope, Simplifier};
use nalgebra::DMatrix;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// One matrix: name, shape, every entry that is not a structural zero, LaTeX.
pub struct MatrixOut {
    name: &'static str,
    rows: usize,
    cols: usize,
    entries: Vec<(usize, usize, String)>,
    latex: String,
}

/// The closed forms.
pub struct ClosedOut {
    keep: Vec<String>,
    substituted: Vec<(String, String)>,
    matrices: Vec<MatrixOut>,
}

impl ClosedOut {
    /// As a dict: `symbolic_parameters`, `substituted`, `matrices` (name → dict of
    /// `shape`, `entries`, `latex`).
    pub fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("symbolic_parameters", self.keep)?;
        d.set_item("substituted", self.substituted)?;
        let ms = PyDict::new(py);
        for m in self.matrices {
            let md = PyDict::new(py);
            md.set_item("shape", (m.rows, m.cols))?;
            md.set_item("entries", m.entries)?;
            md.set_item("latex", m.latex)?;
            ms.set_item(m.name, md)?;
        }
        d.set_item("matrices", ms)?;
        Ok(d)
    }
}

/// A, B, C, D with the parameters of `keep` symbolic and the others at their defaults.
pub fn closed_forms(source: &Source, names: &[String], keep: &[String]) -> PyResult<ClosedOut> {
    let model = source.build(&[])?;
    model.in_pool(|| {
        let sym = Linearizer::new(&model).symbolic().map_err(eom_error)?;
        let defaults = model.scope.nominal_values();
        let mut map = Vec::new();
        let mut substituted = Vec::new();
        for (name, v) in names.iter().zip(&defaults) {
            if keep.contains(name) {
                continue;
            }
            let p = model.scope.lookup(name).map_err(eom_error)?;
            // The shortest decimal that reads back as the default: exact, as `--set` takes it.
            let value = eom_sym::parse(&format!("{v:?}"), &Scope::new()).map_err(eom_error)?;
            substituted.push((name.clone(), value.to_string()));
            map.push((p, value));
        }
        let ss = sym.state_space();
        let matrices = [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d)]
            .into_iter()
            .map(|(name, m)| matrix_out(name, m, &map))
            .collect::<PyResult<Vec<_>>>()?;
        Ok(ClosedOut {
            keep: keep.to_vec(),
            substituted,
            matrices,
        })
    })
}

fn matrix_out(name: &'static str, m: &DMatrix<Expr>, map: &[(Expr, Expr)]) -> PyResult<MatrixOut> {
    let entries: Vec<Expr> = m.iter().copied().collect();
    let substituted = if map.is_empty() {
        entries
    } else {
        eom_sym::subs_many(&entries, map).map_err(eom_error)?
    };
    let simplified = if substituted.iter().all(|e| e.is_number() || e.is_zero()) {
        substituted
    } else {
        Simplifier::default()
            .run(&substituted)
            .map_err(eom_error)?
            .roots
    };
    let matrix = DMatrix::from_column_slice(m.nrows(), m.ncols(), &simplified);
    let mut list = Vec::new();
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            let e = matrix[(i, j)];
            if !e.is_zero() {
                list.push((i, j, e.to_string()));
            }
        }
    }
    Ok(MatrixOut {
        name,
        rows: m.nrows(),
        cols: m.ncols(),
        entries: list,
        latex: eom_sym::latex_matrix(&matrix),
    })
}
