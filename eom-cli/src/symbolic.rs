//! `eom symbolic`: the model's state-space matrices, characteristic polynomial, transfer
//! functions and stability conditions in closed form.
//!
//! Parameters given with `--set` are substituted as exact numbers first (`0.21` is 21/100), so
//! that a user keeps only the few parameters being explored symbolic. The matrices go through
//! the bounded e-graph simplification, kept where it makes them shorter.

use crate::error::CliError;
use crate::params::ModelChoice;
use crate::report::mathml;
use eom_model::Linearizer;
use eom_sym::closed::{
    Boundary, CharacteristicPolynomial, ClosedForms, SecondOrder, StabilityCondition,
    SummaryRequest, TransferFunction, latex_boundary, latex_polynomial,
};
use eom_sym::{Expr, Latex, Scope};
use nalgebra::DMatrix;
use serde::Serialize;

/// What to compute besides the matrices.
#[derive(Clone, Debug, Default)]
pub struct SymbolicRequest {
    /// The Liénard–Chipart stability conditions.
    pub stability: bool,
    /// Solve the conditions for this parameter where they are of degree ≤ 2 in it.
    pub solve_for: Option<String>,
    /// Transfer functions of every output/input pair.
    pub transfer: bool,
    /// Largest number of states for the closed forms (default 8).
    pub max_states: Option<usize>,
}

/// One matrix: its shape and its structural non-zeros.
#[derive(Clone, Debug, Serialize)]
pub struct MatrixOut {
    /// `A`, `B`, `C` or `D`.
    pub name: &'static str,
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// `(row, column, expression)` of every entry that is not a structural zero, 0-based.
    pub entries: Vec<(usize, usize, String)>,
    #[serde(skip)]
    matrix: DMatrix<Expr>,
}

/// The characteristic polynomial as printed.
#[derive(Clone, Debug, Serialize)]
pub struct PolynomialOut {
    /// Coefficients of `s⁰ … sⁿ` of the factor left after the zero roots and the common
    /// factor are divided out.
    pub coefficients: Vec<String>,
    /// Roots at zero proved by the structure (`s^k` factor).
    pub zero_roots: usize,
    /// `det(sI − A) = s^zero_roots · p(s) / scale`.
    pub scale: String,
    /// Whether the coefficients are in normal form.
    pub normalized: bool,
}

/// A stability condition as printed.
#[derive(Clone, Debug, Serialize)]
pub struct ConditionOut {
    /// `expression > 0`.
    pub expression: String,
    /// `false` when the condition holds for no parameter values: the model is never
    /// asymptotically stable (see `never`).
    pub satisfiable: bool,
    /// Why the model is never asymptotically stable (only when `satisfiable` is false).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub never: Option<String>,
    /// `coefficient k` or `hurwitz k`.
    pub source: String,
    /// Factors of known sign divided out.
    pub divided_out: Vec<String>,
    /// The boundary solved for the requested parameter, when the condition allows it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub boundary: Option<Vec<String>>,
}

/// A transfer function as printed.
#[derive(Clone, Debug, Serialize)]
pub struct TransferOut {
    /// The output's name.
    pub output: String,
    /// The input's name.
    pub input: String,
    /// Numerator coefficients, `s⁰` first.
    pub numerator: Vec<String>,
    /// Denominator coefficients, `s⁰` first.
    pub denominator: Vec<String>,
    /// Whether common factors were cancelled.
    pub normalized: bool,
}

/// Natural frequency and damping of a two-state model.
#[derive(Clone, Debug, Serialize)]
pub struct SecondOrderOut {
    /// ωₙ in rad/s.
    pub natural_frequency: String,
    /// ζ.
    pub damping_ratio: String,
}

/// Everything `eom symbolic` prints.
#[derive(Clone, Debug, Serialize)]
pub struct SymbolicReport {
    /// The model.
    pub model: String,
    /// Parameters that stay symbolic.
    pub symbolic_parameters: Vec<String>,
    /// Parameters substituted by `--set`, with the exact value used.
    pub substituted: Vec<(String, String)>,
    /// A, B, C, D.
    pub matrices: Vec<MatrixOut>,
    /// `det(sI − A)`, when the model is small enough.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub characteristic_polynomial: Option<PolynomialOut>,
    /// ωₙ and ζ of a two-state model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_order: Option<SecondOrderOut>,
    /// `--stability`: the conditions, all of which must hold (empty: always stable, by the
    /// parameters' declared signs; one unsatisfiable condition: never).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability: Option<Vec<ConditionOut>>,
    /// `--stability` in words: `always`, `never: …` or `when all conditions hold`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability_verdict: Option<String>,
    /// `--transfer`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub transfer_functions: Vec<TransferOut>,
    /// What was skipped and why.
    pub notes: Vec<String>,
    #[serde(skip)]
    pub(crate) latex: LatexParts,
    /// The same parts in MathML (for `eom report`).
    #[serde(skip)]
    pub(crate) mathml: LatexParts,
}

/// The closed forms as typeset text (LaTeX, or MathML for the report).
#[derive(Clone, Debug, Default)]
pub(crate) struct LatexParts {
    pub(crate) polynomial: Option<String>,
    pub(crate) second_order: Option<(String, String)>,
    pub(crate) conditions: Vec<String>,
    pub(crate) boundaries: Vec<String>,
    pub(crate) transfer: Vec<(String, String, String)>,
}

/// Builds the report.
pub fn symbolic(
    choice: &ModelChoice,
    overrides: &[(String, String)],
    req: &SymbolicRequest,
) -> Result<SymbolicReport, CliError> {
    let numeric: Vec<(&str, f64)> = overrides
        .iter()
        .map(|(k, v)| {
            Ok((
                k.as_str(),
                crate::params::parse_number(v).map_err(|p| bad_set(k, v, p))?,
            ))
        })
        .collect::<Result<_, CliError>>()?;
    // Pivots are chosen at the point the user fixes.
    let owned: Vec<(String, f64)> = numeric.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let model = choice.build(&owned)?;
    let sym = Linearizer::new(&model).symbolic()?;
    model.in_pool(|| build_report(choice, &model, &sym, overrides, req))
}

fn bad_set(name: &str, value: &str, problem: String) -> CliError {
    CliError::BadArgument {
        argument: format!("--set {name}={value}"),
        problem,
    }
}

fn build_report(
    choice: &ModelChoice,
    model: &eom_model::Model,
    sym: &eom_model::SymbolicStateSpace,
    overrides: &[(String, String)],
    req: &SymbolicRequest,
) -> Result<SymbolicReport, CliError> {
    let mut map = Vec::new();
    let mut substituted = Vec::new();
    for (name, text) in overrides {
        let p = model.scope.lookup(name)?;
        let v =
            eom_sym::parse(text, &Scope::new()).map_err(|e| bad_set(name, text, e.to_string()))?;
        substituted.push((name.clone(), v.to_string()));
        map.push((p, v));
    }
    let ss = sym.state_space();
    let mut matrices = Vec::new();
    for (name, m) in [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d)] {
        matrices.push(matrix_out(name, m, &map)?);
    }
    let mut notes = Vec::new();
    let mut report = SymbolicReport {
        model: choice.name.clone(),
        symbolic_parameters: model
            .scope
            .names()
            .into_iter()
            .filter(|n| !overrides.iter().any(|(k, _)| k == n))
            .collect(),
        substituted,
        matrices,
        characteristic_polynomial: None,
        second_order: None,
        stability: None,
        stability_verdict: None,
        transfer_functions: Vec::new(),
        notes: Vec::new(),
        latex: LatexParts::default(),
        mathml: LatexParts::default(),
    };
    let n = ss.a.nrows();
    let limit = req.max_states.unwrap_or(8);
    if n > limit {
        notes.push(format!(
            "the model has {n} states: the characteristic polynomial, stability conditions and \
             transfer functions are computed up to {limit} states (--max-states N to raise the \
             limit; the work grows as n·2ⁿ)"
        ));
    } else {
        if req.max_states.is_some_and(|m| m > 8) && n > 8 {
            notes.push(format!(
                "{n} states: the closed forms may be large and slow to compute"
            ));
        }
        let (e, f) = sym.pencil();
        let sub = |m: DMatrix<Expr>| -> Result<DMatrix<Expr>, CliError> {
            if map.is_empty() {
                return Ok(m);
            }
            let v = eom_sym::subs_many(m.as_slice(), &map)?;
            Ok(DMatrix::from_column_slice(m.nrows(), m.ncols(), &v))
        };
        let pencil = (sub(e)?, sub(f)?);
        closed_forms(
            model,
            &ss.names,
            &pencil,
            &mut report,
            req,
            limit,
            &mut notes,
        )?;
    }
    report.notes.extend(notes);
    Ok(report)
}

/// Substitutes and simplifies one matrix.
fn matrix_out(
    name: &'static str,
    m: &DMatrix<Expr>,
    map: &[(Expr, Expr)],
) -> Result<MatrixOut, CliError> {
    let matrix = eom_sym::closed::shown_matrix(m, map)?;
    let mut list = Vec::new();
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            let e = matrix[(i, j)];
            if !e.is_zero() {
                list.push((i, j, e.to_string()));
            }
        }
    }
    list.sort();
    Ok(MatrixOut {
        name,
        rows: m.nrows(),
        cols: m.ncols(),
        entries: list,
        matrix,
    })
}

#[allow(clippy::too_many_arguments)]
fn closed_forms(
    model: &eom_model::Model,
    names: &eom_num::SignalNames,
    (e, f): &(DMatrix<Expr>, DMatrix<Expr>),
    report: &mut SymbolicReport,
    req: &SymbolicRequest,
    limit: usize,
    notes: &mut Vec<String>,
) -> Result<(), CliError> {
    let cf = ClosedForms::default().with_max_states(limit.max(1));
    let solve_for = match &req.solve_for {
        Some(name) => Some(model.scope.lookup(name)?),
        None => None,
    };
    let m = &report.matrices;
    let summary = cf.summary(
        (e, f),
        [&m[0].matrix, &m[1].matrix, &m[2].matrix, &m[3].matrix],
        &SummaryRequest {
            stability: req.stability,
            solve_for,
            transfer: req.transfer,
        },
    )?;
    let p = &summary.polynomial;
    if !p.normalized {
        notes.push(
            "the characteristic polynomial's coefficients are exact but not in normal form (a \
             bound of the rational normal form was reached; substitute parameters with --set to \
             shrink them)"
                .into(),
        );
    }
    let shown = &summary.shown;
    report.latex.polynomial = Some(latex_polynomial(shown));
    report.mathml.polynomial = Some(mathml::polynomial(shown, "s"));
    report.characteristic_polynomial = Some(polynomial_out(p, shown));
    if let Some(so) = &summary.second_order {
        report.second_order = Some(second_order_out(so));
        report.latex.second_order = Some((
            Latex(so.natural_frequency).to_string(),
            Latex(so.damping_ratio).to_string(),
        ));
        report.mathml.second_order = Some((
            mathml::mathml(so.natural_frequency),
            mathml::mathml(so.damping_ratio),
        ));
    }
    if let Some(conds) = &summary.conditions {
        let mut out = Vec::new();
        for cs in conds {
            let c = &cs.condition;
            if let Some(never) = &cs.never {
                report
                    .latex
                    .conditions
                    .push(format!("\\text{{never: {never}}}"));
                report.mathml.conditions.push(format!(
                    "<mtext>never: {}</mtext>",
                    crate::plot::shape::escape(never)
                ));
                out.push(ConditionOut {
                    expression: c.expression.to_string(),
                    satisfiable: false,
                    never: Some(never.clone()),
                    source: c.source.to_string(),
                    divided_out: c.divided_out.iter().map(|x| x.to_string()).collect(),
                    boundary: None,
                });
                continue;
            }
            report
                .latex
                .conditions
                .push(format!("{} > 0", Latex(c.expression)));
            report.mathml.conditions.push(format!(
                "<mrow>{}<mo>&gt;</mo><mn>0</mn></mrow>",
                mathml::mathml(c.expression)
            ));
            if let Some(b) = &cs.boundary {
                report.latex.boundaries.push(latex_boundary(b));
            }
            out.push(condition_out(c, cs.boundary.as_ref()));
        }
        report.stability_verdict = summary.verdict();
        report.stability = Some(out);
    }
    let name = |v: &[String], k: usize, what: &str| {
        v.get(k)
            .cloned()
            .unwrap_or_else(|| format!("{what}{}", k + 1))
    };
    for tf in &summary.transfer_functions {
        let (o, i) = (
            name(&names.outputs, tf.output, "y"),
            name(&names.inputs, tf.input, "u"),
        );
        report.latex.transfer.push((
            o.clone(),
            i.clone(),
            format!(
                "\\frac{{{}}}{{{}}}",
                latex_polynomial(&tf.numerator.coefficients),
                latex_polynomial(&tf.denominator.coefficients)
            ),
        ));
        report.mathml.transfer.push((
            o.clone(),
            i.clone(),
            format!(
                "<mfrac>{}{}</mfrac>",
                mathml::polynomial(&tf.numerator.coefficients, "s"),
                mathml::polynomial(&tf.denominator.coefficients, "s")
            ),
        ));
        report.transfer_functions.push(transfer_out(tf, o, i));
    }
    Ok(())
}

fn polynomial_out(p: &CharacteristicPolynomial, shown: &[Expr]) -> PolynomialOut {
    PolynomialOut {
        coefficients: shown.iter().map(|c| c.to_string()).collect(),
        zero_roots: p.zero_roots,
        scale: p.scale.to_string(),
        normalized: p.normalized,
    }
}

fn second_order_out(so: &SecondOrder) -> SecondOrderOut {
    SecondOrderOut {
        natural_frequency: so.natural_frequency.to_string(),
        damping_ratio: so.damping_ratio.to_string(),
    }
}

fn condition_out(c: &StabilityCondition, b: Option<&Boundary>) -> ConditionOut {
    ConditionOut {
        expression: c.expression.to_string(),
        satisfiable: true,
        never: None,
        source: c.source.to_string(),
        divided_out: c.divided_out.iter().map(|x| x.to_string()).collect(),
        boundary: b.map(|b| b.roots.iter().map(|r| r.to_string()).collect()),
    }
}

fn transfer_out(tf: &TransferFunction, output: String, input: String) -> TransferOut {
    TransferOut {
        output,
        input,
        numerator: tf
            .numerator
            .coefficients
            .iter()
            .map(|c| c.to_string())
            .collect(),
        denominator: tf
            .denominator
            .coefficients
            .iter()
            .map(|c| c.to_string())
            .collect(),
        normalized: tf.normalized,
    }
}

impl SymbolicReport {
    /// Plain text for a terminal.
    pub fn to_text(&self) -> String {
        let mut t = format!("model: {}\n", self.model);
        if !self.substituted.is_empty() {
            let s: Vec<String> = self
                .substituted
                .iter()
                .map(|(k, v)| format!("{k} = {v}"))
                .collect();
            t.push_str(&format!("substituted: {}\n", s.join(", ")));
        }
        t.push_str(&format!(
            "symbolic: {}\n",
            self.symbolic_parameters.join(", ")
        ));
        for m in &self.matrices {
            t.push_str(&format!("\n{} ({}×{}):\n", m.name, m.rows, m.cols));
            t.push_str(&matrix_text(m));
        }
        if let Some(p) = &self.characteristic_polynomial {
            t.push_str("\ncharacteristic polynomial: det(sI − A) = ");
            if p.zero_roots > 0 {
                t.push_str(&format!("s^{} · ", p.zero_roots));
            }
            t.push_str("p(s)");
            if p.scale != "1" {
                t.push_str(&format!(" / ({})", p.scale));
            }
            t.push_str(", p(s) =\n");
            for (k, c) in p.coefficients.iter().enumerate().rev() {
                t.push_str(&format!("  s^{k}: {c}\n"));
            }
        }
        if let Some(so) = &self.second_order {
            t.push_str(&format!(
                "\nωn = {}\nζ = {}\n",
                so.natural_frequency, so.damping_ratio
            ));
        }
        if let Some(conds) = &self.stability {
            if let Some(c) = conds.iter().find(|c| !c.satisfiable) {
                t.push_str(&format!(
                    "\nnever asymptotically stable: {}\n",
                    c.never.as_deref().unwrap_or_default()
                ));
            } else if conds.is_empty() {
                t.push_str(
                    "\nasymptotically stable always: every condition holds by the parameters' \
                     declared signs\n",
                );
            } else {
                t.push_str("\nasymptotically stable exactly when (all of):\n");
                for c in conds {
                    t.push_str(&format!("  {} > 0      [{}]\n", c.expression, c.source));
                    if let Some(b) = &c.boundary {
                        t.push_str(&format!("    boundary: {}\n", b.join(", ")));
                    }
                }
            }
        }
        for tf in &self.transfer_functions {
            t.push_str(&format!("\n{} / {}:\n", tf.output, tf.input));
            t.push_str(&format!(
                "  numerator (s^0 first): {}\n",
                tf.numerator.join(", ")
            ));
            t.push_str(&format!(
                "  denominator (s^0 first): {}\n",
                tf.denominator.join(", ")
            ));
        }
        for n in &self.notes {
            t.push_str(&format!("\nnote: {n}\n"));
        }
        t
    }

    /// LaTeX for papers: one `align*` block.
    pub fn to_latex(&self) -> String {
        let mut t = String::from("\\begin{align*}\n");
        let mut lines: Vec<String> = self
            .matrices
            .iter()
            .map(|m| format!("{} &= {}", m.name, eom_sym::latex_matrix(&m.matrix)))
            .collect();
        if let (Some(p), Some(l)) = (&self.characteristic_polynomial, &self.latex.polynomial) {
            let z = if p.zero_roots > 0 {
                format!("s^{{{}}}\\,", p.zero_roots)
            } else {
                String::new()
            };
            lines.push(format!("\\det(sI - A) &= {z}\\left({l}\\right)"));
        }
        if let Some((wn, z)) = &self.latex.second_order {
            lines.push(format!("\\omega_n &= {wn}"));
            lines.push(format!("\\zeta &= {z}"));
        }
        lines.extend(self.latex.conditions.iter().map(|c| format!("& {c}")));
        lines.extend(self.latex.boundaries.iter().map(|b| format!("& {b}")));
        lines.extend(
            self.latex
                .transfer
                .iter()
                .map(|(o, i, f)| format!("G_{{{o},{i}}}(s) &= {f}")),
        );
        t.push_str(&lines.join(" \\\\\n"));
        t.push_str("\n\\end{align*}\n");
        t
    }
}

fn matrix_text(m: &MatrixOut) -> String {
    let wide = m.entries.iter().any(|e| e.2.chars().count() > 40) || m.cols > 8;
    if !wide {
        return format!("{}\n", eom_sym::display_matrix(&m.matrix));
    }
    let mut t = String::new();
    for (i, j, e) in &m.entries {
        t.push_str(&format!("  {}({},{}) = {e}\n", m.name, i + 1, j + 1));
    }
    t.push_str("  (all other entries are structural zeros)\n");
    t
}
