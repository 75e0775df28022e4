//! What is to be generated, gathered from a [`SymbolicStateSpace`]: parameters with their
//! metadata, the structural non-zeros of each matrix, and the validity checks — after the
//! optional partial evaluation and simplification.

use crate::CodegenError;
use crate::options::EmitOptions;
use eom_model::{SymbolicStateSpace, ValidityCheck};
use eom_num::SignalNames;
use eom_sym::simplify::Simplifier;
use eom_sym::{Expr, subs_many};
use nalgebra::DMatrix;

/// The five matrices of a state-space model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Mat {
    A,
    B,
    C,
    D,
    Phys,
}

impl Mat {
    pub(crate) const ALL: [Mat; 5] = [Mat::A, Mat::B, Mat::C, Mat::D, Mat::Phys];
    pub(crate) fn index(self) -> usize {
        self as usize
    }
    /// Lower-case name (argument names, constants).
    pub(crate) fn lower(self) -> &'static str {
        match self {
            Mat::A => "a",
            Mat::B => "b",
            Mat::C => "c",
            Mat::D => "d",
            Mat::Phys => "phys",
        }
    }
    /// Variant name in the generated `Matrix` enum.
    pub(crate) fn variant(self) -> &'static str {
        match self {
            Mat::A => "A",
            Mat::B => "B",
            Mat::C => "C",
            Mat::D => "D",
            Mat::Phys => "Phys",
        }
    }
}

/// A parameter of the generated interface.
#[derive(Clone, Debug)]
pub(crate) struct Param {
    pub name: String,
    /// The struct field (a valid Rust identifier, raw if need be).
    pub field: String,
    /// The local variable in function bodies.
    pub local: String,
    pub nominal: f64,
    pub unit: String,
    pub description: String,
}

/// One matrix: its size and structural non-zeros, column-major.
#[derive(Clone, Debug)]
pub(crate) struct MatrixSpec {
    pub rows: usize,
    pub cols: usize,
    pub entries: Vec<(usize, usize, Expr)>,
}

/// One validity check.
#[derive(Clone, Debug)]
pub(crate) struct Check {
    pub what: String,
    pub pivot: bool,
    pub value: Expr,
    pub others: Vec<Expr>,
    /// `|value| / max |others|` at the nominal point (the margin of a pivot, or how negligible
    /// a negligible entry is).
    pub nominal_ratio: f64,
}

/// Everything the emitter needs.
pub(crate) struct Problem {
    pub model: String,
    pub params: Vec<Param>,
    /// The parameters, in interface order.
    pub param_exprs: Vec<Expr>,
    pub mats: Vec<MatrixSpec>,
    pub checks: Vec<Check>,
    pub names: SignalNames,
    /// Parameters fixed by partial evaluation, with their values.
    pub fixed: Vec<(String, f64)>,
    /// Simplification summary: op counts before and after, whether the result was kept.
    pub simplified: Option<eom_sym::SimplifyOutcome>,
}

const KEYWORDS: [&str; 51] = [
    "as",
    "break",
    "const",
    "continue",
    "else",
    "enum",
    "extern",
    "false",
    "fn",
    "for",
    "if",
    "impl",
    "in",
    "let",
    "loop",
    "match",
    "mod",
    "move",
    "mut",
    "pub",
    "ref",
    "return",
    "static",
    "struct",
    "trait",
    "true",
    "type",
    "unsafe",
    "use",
    "where",
    "while",
    "async",
    "await",
    "dyn",
    "abstract",
    "become",
    "box",
    "do",
    "final",
    "macro",
    "override",
    "priv",
    "typeof",
    "unsized",
    "virtual",
    "yield",
    "try",
    "gen",
    "union",
    "macro_rules",
    "raw",
];

/// A field name for a parameter name (already an identifier by construction of parameters).
pub(crate) fn field_ident(name: &str) -> String {
    match name {
        "self" | "Self" | "super" | "crate" => format!("{name}_"),
        "_" => "_p".to_string(),
        n if KEYWORDS.contains(&n) && !matches!(n, "union" | "macro_rules" | "raw") => {
            format!("r#{n}")
        }
        n => n.to_string(),
    }
}

/// A module name from a model name: lower-case ASCII identifier.
pub(crate) fn module_ident(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    while s.contains("__") {
        s = s.replace("__", "_");
    }
    let s = s.trim_matches('_').to_string();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        return format!("model_{s}");
    }
    if KEYWORDS.contains(&s.as_str())
        || matches!(
            s.as_str(),
            "self" | "super" | "crate" | "core" | "std" | "libm"
        )
    {
        return format!("{s}_model");
    }
    s
}

fn matrix_spec(m: &DMatrix<Expr>) -> MatrixSpec {
    let mut entries = Vec::new();
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            let e = m[(i, j)];
            if !e.is_zero() {
                entries.push((i, j, e));
            }
        }
    }
    MatrixSpec {
        rows: m.nrows(),
        cols: m.ncols(),
        entries,
    }
}

fn ratio(value: f64, others: &[f64]) -> f64 {
    let m = others.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    if m == 0.0 {
        f64::INFINITY
    } else {
        value.abs() / m
    }
}

impl Problem {
    pub(crate) fn new(
        sym: &SymbolicStateSpace,
        name: Option<&str>,
        opts: &EmitOptions,
    ) -> Result<Problem, CodegenError> {
        let ss = sym.state_space();
        let mut mats: Vec<MatrixSpec> = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys]
            .iter()
            .map(|m| matrix_spec(m))
            .collect();
        let mut checks = checks_of(sym);

        // Partial evaluation.
        let mut params: Vec<Expr> = sym.params.clone();
        let fixed = fix_parameters(sym, opts, &mut params, &mut mats, &mut checks)?;

        // Simplification (bounded egg pass over everything at once; kept only if cheaper).
        let mut simplified = None;
        if opts.simplify {
            let roots = gather(&mats, &checks);
            let out = Simplifier::default().run(&roots)?;
            if out.kept {
                scatter(&mut mats, &mut checks, &out.roots);
            }
            simplified = Some(out);
        }
        let checks = variable_checks(checks)?;
        let (params, param_exprs) = param_specs(&params)?;
        Ok(Problem {
            model: text(name.unwrap_or("model")),
            params,
            param_exprs,
            mats,
            checks,
            names: signal_names(&ss.names),
            fixed,
            simplified,
        })
    }
}

/// Text of the model (names, units, descriptions) as it may appear in generated code: every
/// character that could end a comment line or reorder what a reader sees (a line break, a
/// bidirectional override) escaped, so that text reaches the code only as text. Identifiers
/// come from parameter names, which are identifiers by construction; string literals are
/// escaped again by the token printer.
fn text(s: &str) -> String {
    eom_text::escaped(s).into_owned()
}

fn signal_names(n: &eom_num::SignalNames) -> eom_num::SignalNames {
    let all = |v: &[String]| v.iter().map(|s| text(s)).collect();
    eom_num::SignalNames {
        states: all(&n.states),
        inputs: all(&n.inputs),
        input_units: all(&n.input_units),
        outputs: all(&n.outputs),
        output_units: all(&n.output_units),
        bodies: all(&n.bodies),
    }
}

/// The reduction's validity checks.
fn checks_of(sym: &SymbolicStateSpace) -> Vec<Check> {
    sym.reduction
        .checks
        .iter()
        .map(|c| match c {
            ValidityCheck::Pivot { what, value, row } => Check {
                what: text(&what.to_string()),
                pivot: true,
                value: *value,
                others: row.clone(),
                nominal_ratio: 0.0,
            },
            ValidityCheck::Negligible { what, value, scale } => Check {
                what: text(&what.to_string()),
                pivot: false,
                value: *value,
                others: scale.clone(),
                nominal_ratio: 0.0,
            },
        })
        .collect()
}

/// Every expression, in a fixed order, for substitution and simplification.
fn gather(mats: &[MatrixSpec], checks: &[Check]) -> Vec<Expr> {
    let mut v: Vec<Expr> = mats
        .iter()
        .flat_map(|m| m.entries.iter().map(|e| e.2))
        .collect();
    for c in checks {
        v.push(c.value);
        v.extend(&c.others);
    }
    v
}

/// The inverse of [`gather`]: put `new` back in place, dropping entries that became zero.
fn scatter(mats: &mut [MatrixSpec], checks: &mut [Check], new: &[Expr]) {
    let mut k = 0;
    for m in mats.iter_mut() {
        for e in m.entries.iter_mut() {
            e.2 = new[k];
            k += 1;
        }
        m.entries.retain(|e| !e.2.is_zero());
    }
    for c in checks.iter_mut() {
        c.value = new[k];
        k += 1;
        for o in c.others.iter_mut() {
            *o = new[k];
            k += 1;
        }
    }
}

/// Partial evaluation: substitute the fixed parameters' values everywhere and drop them from
/// `params`; returns the fixed names and values.
fn fix_parameters(
    sym: &SymbolicStateSpace,
    opts: &EmitOptions,
    params: &mut Vec<Expr>,
    mats: &mut [MatrixSpec],
    checks: &mut [Check],
) -> Result<Vec<(String, f64)>, CodegenError> {
    let mut fixed = Vec::new();
    if opts.fixed.is_empty() {
        return Ok(fixed);
    }
    let mut map = Vec::new();
    for (n, v) in &opts.fixed {
        let p = params
            .iter()
            .copied()
            .find(|p| p.param_info().is_some_and(|i| &i.name == n))
            .ok_or_else(|| CodegenError::BadOption {
                option: "fix",
                problem: format!(
                    "no parameter `{n}`; parameters are: {}",
                    sym.params
                        .iter()
                        .filter_map(|p| p.param_info())
                        .map(|i| i.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })?;
        if !v.is_finite() {
            return Err(CodegenError::BadOption {
                option: "fix",
                problem: format!("`{n}` = {v} is not finite"),
            });
        }
        map.push((p, Expr::float(*v)?));
        fixed.push((n.clone(), *v));
    }
    let invalid = |e: eom_sym::SymError| CodegenError::BadOption {
        option: "fix",
        problem: format!("the fixed values leave an expression without a value: {e}"),
    };
    let new = subs_many(&gather(mats, checks), &map).map_err(invalid)?;
    for e in &new {
        e.check().map_err(invalid)?;
    }
    scatter(mats, checks, &new);
    params.retain(|p| !map.iter().any(|(q, _)| q == p));
    Ok(fixed)
}

/// The checks that depend on the parameters: those that hold whatever the parameters (all
/// numbers) are dropped; a constant check that fails means the fixed values are outside the
/// validity region.
fn variable_checks(checks: Vec<Check>) -> Result<Vec<Check>, CodegenError> {
    let mut kept = Vec::new();
    for mut c in checks {
        let v = c.value.nominal();
        let o: Vec<f64> = c.others.iter().map(|x| x.nominal()).collect();
        c.nominal_ratio = ratio(v, &o);
        let constant = c.value.is_number() && c.others.iter().all(|x| x.is_number());
        if constant {
            if ValidityCheck::<Expr>::holds(v, &o, c.pivot) {
                continue;
            }
            return Err(CodegenError::BadOption {
                option: "fix",
                problem: format!(
                    "the fixed values leave the validity region: {} fails",
                    c.what
                ),
            });
        }
        kept.push(c);
    }
    Ok(kept)
}

/// The generated code's parameters (unique field names) and their expressions.
fn param_specs(params: &[Expr]) -> Result<(Vec<Param>, Vec<Expr>), CodegenError> {
    let mut out_params = Vec::new();
    let mut param_exprs = Vec::new();
    let mut fields: Vec<String> = Vec::new();
    for p in params {
        let info = p.param_info().ok_or_else(|| CodegenError::BadOption {
            option: "params",
            problem: format!("`{p}` is not a parameter"),
        })?;
        let mut field = field_ident(&info.name);
        while fields.contains(&field) {
            field.push('_');
        }
        fields.push(field.clone());
        out_params.push(Param {
            local: format!("p_{}", info.name),
            name: info.name.clone(),
            field,
            nominal: p.nominal(),
            unit: text(&info.unit.clone().unwrap_or_default()),
            description: text(&info.description.clone().unwrap_or_default()),
        });
        param_exprs.push(*p);
    }
    Ok((out_params, param_exprs))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers() {
        assert_eq!(field_ident("m"), "m");
        assert_eq!(field_ident("type"), "r#type");
        assert_eq!(field_ident("self"), "self_");
        assert_eq!(field_ident("_"), "_p");
        assert_eq!(module_ident("quarter_car"), "quarter_car");
        assert_eq!(module_ident("Mass on a spring"), "mass_on_a_spring");
        assert_eq!(module_ident("2dof"), "model_2dof");
        assert_eq!(module_ident("fn"), "fn_model");
    }
}
