//! The model in closed form (as `eom symbolic` computes it): the parameters not kept
//! substituted by their default values as exact decimals; the matrices through the bounded
//! e-graph simplification; the characteristic polynomial, ωₙ and ζ of a second-order model,
//! the stability conditions and the transfer functions from `eom_sym::closed::Summary`; each
//! as text in the parser's syntax and as LaTeX.

use crate::errors::eom_error;
use crate::source::Source;
use eom_model::Linearizer;
use eom_sym::closed::{
    ClosedForms, Summary, SummaryRequest, latex_boundary, latex_polynomial, shown_matrix,
};
use eom_sym::{Expr, Latex, Scope};
use nalgebra::DMatrix;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What to compute besides the matrices.
pub struct Request {
    /// The parameters kept symbolic.
    pub keep: Vec<String>,
    /// The stability conditions.
    pub stability: bool,
    /// The transfer functions.
    pub transfer: bool,
    /// Solve the conditions for this parameter.
    pub solve_for: Option<String>,
    /// The largest model (in states) for the polynomial, conditions and transfer functions.
    pub max_states: usize,
}

/// One matrix: name, shape, every entry that is not a structural zero, LaTeX.
struct MatrixOut {
    name: &'static str,
    rows: usize,
    cols: usize,
    entries: Vec<(usize, usize, String)>,
    latex: String,
}

/// The characteristic polynomial as text.
struct PolynomialOut {
    coefficients: Vec<String>,
    latex: String,
    zero_roots: usize,
    scale: String,
    scale_latex: String,
    normalized: bool,
}

/// One stability condition as text.
struct ConditionOut {
    expression: String,
    latex: String,
    satisfiable: bool,
    never: Option<String>,
    source: String,
    divided_out: Vec<String>,
    /// (parameter, roots, LaTeX).
    boundary: Option<(String, Vec<String>, String)>,
}

/// One transfer function as text.
struct TransferOut {
    output: String,
    input: String,
    numerator: Vec<String>,
    denominator: Vec<String>,
    latex: String,
    normalized: bool,
}

/// The summary as text (made inside the model's expression pool).
struct SummaryOut {
    polynomial: PolynomialOut,
    /// (ωₙ, ζ, LaTeX of ωₙ, LaTeX of ζ).
    second_order: Option<(String, String, String, String)>,
    conditions: Option<(Vec<ConditionOut>, Option<String>)>,
    transfer: Vec<TransferOut>,
}

/// The closed forms as text.
pub struct ClosedOut {
    keep: Vec<String>,
    substituted: Vec<(String, String)>,
    matrices: Vec<MatrixOut>,
    summary: Option<SummaryOut>,
    notes: Vec<String>,
}

impl ClosedOut {
    /// As a dict (see `python/eom/_model.py`, class `Symbolic`).
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
        d.set_item("notes", self.notes)?;
        if let Some(s) = self.summary {
            summary_into(py, &d, s)?;
        }
        Ok(d)
    }
}

fn texts(c: &[Expr]) -> Vec<String> {
    c.iter().map(|x| x.to_string()).collect()
}

/// The summary as text, names of the outputs and inputs given.
fn summary_out(s: &Summary, outputs: &[String], inputs: &[String]) -> SummaryOut {
    let p = &s.polynomial;
    let name = |v: &[String], k: usize, what: &str| {
        v.get(k)
            .cloned()
            .unwrap_or_else(|| format!("{what}{}", k + 1))
    };
    SummaryOut {
        polynomial: PolynomialOut {
            coefficients: texts(&s.shown),
            latex: latex_polynomial(&s.shown),
            zero_roots: p.zero_roots,
            scale: p.scale.to_string(),
            scale_latex: Latex(p.scale).to_string(),
            normalized: p.normalized,
        },
        second_order: s.second_order.as_ref().map(|so| {
            (
                so.natural_frequency.to_string(),
                so.damping_ratio.to_string(),
                Latex(so.natural_frequency).to_string(),
                Latex(so.damping_ratio).to_string(),
            )
        }),
        conditions: s.conditions.as_ref().map(|conds| {
            let out = conds
                .iter()
                .map(|cs| {
                    let c = &cs.condition;
                    ConditionOut {
                        expression: c.expression.to_string(),
                        latex: match &cs.never {
                            Some(never) => format!("\\text{{never: {never}}}"),
                            None => format!("{} > 0", Latex(c.expression)),
                        },
                        satisfiable: c.satisfiable,
                        never: cs.never.clone(),
                        source: c.source.to_string(),
                        divided_out: texts(&c.divided_out),
                        boundary: cs
                            .boundary
                            .as_ref()
                            .map(|b| (b.parameter.to_string(), texts(&b.roots), latex_boundary(b))),
                    }
                })
                .collect();
            (out, s.verdict())
        }),
        transfer: s
            .transfer_functions
            .iter()
            .map(|tf| TransferOut {
                output: name(outputs, tf.output, "y"),
                input: name(inputs, tf.input, "u"),
                numerator: texts(&tf.numerator.coefficients),
                denominator: texts(&tf.denominator.coefficients),
                latex: format!(
                    "\\frac{{{}}}{{{}}}",
                    latex_polynomial(&tf.numerator.coefficients),
                    latex_polynomial(&tf.denominator.coefficients)
                ),
                normalized: tf.normalized,
            })
            .collect(),
    }
}

/// The summary's parts into `d`: `characteristic_polynomial`, `second_order`, `stability`,
/// `stability_verdict`, `transfer_functions`.
fn summary_into(py: Python<'_>, d: &Bound<'_, PyDict>, s: SummaryOut) -> PyResult<()> {
    let p = s.polynomial;
    let pd = PyDict::new(py);
    pd.set_item("coefficients", p.coefficients)?;
    pd.set_item("latex", p.latex)?;
    pd.set_item("zero_roots", p.zero_roots)?;
    pd.set_item("scale", p.scale)?;
    pd.set_item("scale_latex", p.scale_latex)?;
    pd.set_item("normalized", p.normalized)?;
    d.set_item("characteristic_polynomial", pd)?;
    if let Some((wn, z, wn_latex, z_latex)) = s.second_order {
        let sd = PyDict::new(py);
        sd.set_item("natural_frequency", wn)?;
        sd.set_item("damping_ratio", z)?;
        sd.set_item("latex", (wn_latex, z_latex))?;
        d.set_item("second_order", sd)?;
    }
    if let Some((conds, verdict)) = s.conditions {
        let mut out = Vec::new();
        for c in conds {
            let cd = PyDict::new(py);
            cd.set_item("expression", c.expression)?;
            cd.set_item("latex", c.latex)?;
            cd.set_item("satisfiable", c.satisfiable)?;
            cd.set_item("never", c.never)?;
            cd.set_item("source", c.source)?;
            cd.set_item("divided_out", c.divided_out)?;
            cd.set_item("boundary", c.boundary)?;
            out.push(cd);
        }
        d.set_item("stability", out)?;
        d.set_item("stability_verdict", verdict)?;
    }
    let mut tfs = Vec::new();
    for tf in s.transfer {
        let td = PyDict::new(py);
        td.set_item("output", tf.output)?;
        td.set_item("input", tf.input)?;
        td.set_item("numerator", tf.numerator)?;
        td.set_item("denominator", tf.denominator)?;
        td.set_item("latex", tf.latex)?;
        td.set_item("normalized", tf.normalized)?;
        tfs.push(td);
    }
    d.set_item("transfer_functions", tfs)?;
    Ok(())
}

/// The closed forms with the parameters of `req.keep` symbolic and the others at their
/// defaults.
pub fn closed_forms(source: &Source, names: &[String], req: &Request) -> PyResult<ClosedOut> {
    let model = source.build(&[])?;
    model.in_pool(|| {
        let sym = Linearizer::new(&model).symbolic().map_err(eom_error)?;
        let defaults = model.scope.nominal_values();
        let mut map = Vec::new();
        let mut substituted = Vec::new();
        for (name, v) in names.iter().zip(&defaults) {
            if req.keep.contains(name) {
                continue;
            }
            let p = model.scope.lookup(name).map_err(eom_error)?;
            // The shortest decimal that reads back as the default: exact, as `--set` takes it.
            let value = eom_sym::parse(&format!("{v:?}"), &Scope::new()).map_err(eom_error)?;
            substituted.push((name.clone(), value.to_string()));
            map.push((p, value));
        }
        let ss = sym.state_space();
        let shown = [&ss.a, &ss.b, &ss.c, &ss.d].map(|m| shown_matrix(m, &map).map_err(eom_error));
        let [a, b, c, d] = shown;
        let (a, b, c, d) = (a?, b?, c?, d?);
        let matrices = [("A", &a), ("B", &b), ("C", &c), ("D", &d)]
            .into_iter()
            .map(|(name, m)| matrix_out(name, m))
            .collect();
        let mut notes = Vec::new();
        let n = a.nrows();
        let summary = if n > req.max_states {
            notes.push(format!(
                "the model has {n} states: the characteristic polynomial, stability conditions \
                 and transfer functions are computed up to max_states = {} (the work grows as \
                 n·2ⁿ)",
                req.max_states
            ));
            None
        } else {
            let (e, f) = sym.pencil();
            let sub = |m: DMatrix<Expr>| -> PyResult<DMatrix<Expr>> {
                if map.is_empty() {
                    return Ok(m);
                }
                let v = eom_sym::subs_many(m.as_slice(), &map).map_err(eom_error)?;
                Ok(DMatrix::from_column_slice(m.nrows(), m.ncols(), &v))
            };
            let (e, f) = (sub(e)?, sub(f)?);
            let solve_for = match &req.solve_for {
                Some(name) => Some(model.scope.lookup(name).map_err(eom_error)?),
                None => None,
            };
            let s = ClosedForms::default()
                .with_max_states(req.max_states.max(1))
                .summary(
                    (&e, &f),
                    [&a, &b, &c, &d],
                    &SummaryRequest {
                        stability: req.stability,
                        solve_for,
                        transfer: req.transfer,
                    },
                )
                .map_err(eom_error)?;
            if !s.polynomial.normalized {
                notes.push(
                    "the characteristic polynomial's coefficients are exact but not in normal \
                     form (a bound of the rational normal form was reached; keep fewer \
                     parameters symbolic to shrink them)"
                        .into(),
                );
            }
            Some(summary_out(&s, &ss.names.outputs, &ss.names.inputs))
        };
        Ok(ClosedOut {
            keep: req.keep.clone(),
            substituted,
            matrices,
            summary,
            notes,
        })
    })
}

fn matrix_out(name: &'static str, m: &DMatrix<Expr>) -> MatrixOut {
    let mut list = Vec::new();
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            let e = m[(i, j)];
            if !e.is_zero() {
                list.push((i, j, e.to_string()));
            }
        }
    }
    MatrixOut {
        name,
        rows: m.nrows(),
        cols: m.ncols(),
        entries: list,
        latex: eom_sym::latex_matrix(m),
    }
}
