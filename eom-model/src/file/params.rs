//! `[parameters]`: independent parameters with ranges, derived parameters as expressions, and
//! the conversion of field values (numbers and expression strings) to expressions.

use super::error::FileError;
use super::source::{Ctx, Table, Value, array_of, parse_integer};
use crate::Model;
use crate::error::ModelError;
use eom_sym::{Assumption, Expr, ParamInfo, Scope, SymError};
use std::collections::HashMap;
use std::ops::Range;
use toml::de::DeValue;

/// The values a parameter may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamRange {
    /// Any real number.
    Any,
    /// `> 0`.
    Positive,
    /// `>= 0`.
    Nonnegative,
    /// `!= 0`.
    Nonzero,
    /// An interval; each bound is inclusive or not.
    Interval {
        /// Lower bound.
        lo: f64,
        /// Whether `lo` belongs to the range.
        lo_closed: bool,
        /// Upper bound.
        hi: f64,
        /// Whether `hi` belongs to the range.
        hi_closed: bool,
    },
}

impl ParamRange {
    /// Whether `x` is in the range (never for a non-finite `x`).
    pub fn contains(&self, x: f64) -> bool {
        x.is_finite()
            && match *self {
                ParamRange::Any => true,
                ParamRange::Positive => x > 0.0,
                ParamRange::Nonnegative => x >= 0.0,
                ParamRange::Nonzero => x != 0.0,
                ParamRange::Interval {
                    lo,
                    lo_closed,
                    hi,
                    hi_closed,
                } => (x > lo || (lo_closed && x == lo)) && (x < hi || (hi_closed && x == hi)),
            }
    }

    /// The sign assumption the range implies (what the expression engine may use).
    pub fn assumption(&self) -> Assumption {
        match *self {
            ParamRange::Any => Assumption::Real,
            ParamRange::Positive => Assumption::Positive,
            ParamRange::Nonnegative => Assumption::Nonnegative,
            ParamRange::Nonzero => Assumption::Nonzero,
            ParamRange::Interval {
                lo, lo_closed, hi, ..
            } => {
                if lo > 0.0 || (lo == 0.0 && !lo_closed) {
                    Assumption::Positive
                } else if lo >= 0.0 {
                    Assumption::Nonnegative
                } else if hi < 0.0 {
                    Assumption::Nonzero
                } else {
                    Assumption::Real
                }
            }
        }
    }

    /// The range as written in a file.
    pub fn text(&self) -> String {
        match *self {
            ParamRange::Any => "any".into(),
            ParamRange::Positive => "> 0".into(),
            ParamRange::Nonnegative => ">= 0".into(),
            ParamRange::Nonzero => "!= 0".into(),
            ParamRange::Interval {
                lo,
                lo_closed,
                hi,
                hi_closed,
            } => format!(
                "{}{lo}, {hi}{}",
                if lo_closed { '[' } else { '(' },
                if hi_closed { ']' } else { ')' }
            ),
        }
    }

    /// The range of a sign assumption.
    pub fn of(a: Assumption) -> Self {
        match a {
            Assumption::Real => ParamRange::Any,
            Assumption::Positive => ParamRange::Positive,
            Assumption::Nonnegative => ParamRange::Nonnegative,
            Assumption::Nonzero => ParamRange::Nonzero,
        }
    }

    /// Parses `> 0`, `>= 0`, `!= 0`, `any`, `[a, b]`, `(a, b]`, ….
    pub fn parse(text: &str) -> Result<Self, String> {
        let t = text.trim();
        let compact: String = t.chars().filter(|c| !c.is_whitespace()).collect();
        match compact.as_str() {
            "any" => return Ok(ParamRange::Any),
            ">0" => return Ok(ParamRange::Positive),
            ">=0" | "≥0" => return Ok(ParamRange::Nonnegative),
            "!=0" | "≠0" => return Ok(ParamRange::Nonzero),
            _ => {}
        }
        let bad = || {
            format!(
                "`{t}` is not a range; write `> 0`, `>= 0`, `!= 0`, `any`, or an interval such as \
                 `[0, 1]` or `(0, 10]`"
            )
        };
        let lo_closed = match compact.chars().next() {
            Some('[') => true,
            Some('(') => false,
            _ => return Err(bad()),
        };
        let hi_closed = match compact.chars().last() {
            Some(']') => true,
            Some(')') => false,
            _ => return Err(bad()),
        };
        let inner = &compact[1..compact.len() - 1];
        let (a, b) = inner.split_once(',').ok_or_else(bad)?;
        let (lo, hi) = (
            a.parse::<f64>().map_err(|_| bad())?,
            b.parse::<f64>().map_err(|_| bad())?,
        );
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Err(format!(
                "`{t}`: the lower bound must be below the upper bound"
            ));
        }
        Ok(ParamRange::Interval {
            lo,
            lo_closed,
            hi,
            hi_closed,
        })
    }
}

/// An independent parameter as declared in a file.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSpec {
    /// Its name.
    pub name: String,
    /// The value used (the file's, or an override).
    pub value: f64,
    /// The file's value.
    pub default: f64,
    /// Unit (may be empty).
    pub unit: String,
    /// Description (may be empty).
    pub description: String,
    /// Allowed values.
    pub range: ParamRange,
}

/// The parameters of a file: independent ones declared in the model, derived ones resolved.
pub(crate) struct Declarations {
    pub specs: Vec<ParamSpec>,
    pub derived_text: Vec<(String, String)>,
    /// Parse scope: the independent parameters and one placeholder per derived one.
    parse_scope: Scope,
    /// Placeholder's parameter index → the placeholder and its definition in independent
    /// parameters.
    placeholders: HashMap<u32, (Expr, Expr)>,
}

impl Declarations {
    /// The parse scope (independent parameters and derived names).
    pub fn scope(&self, _model: &mut Model) -> Result<Scope, FileError> {
        Ok(self.parse_scope.clone())
    }

    /// `text` parsed, derived names replaced by their definitions: only those it uses, so
    /// that a file with many derived parameters loads in time linear in its size.
    pub fn expr(&self, text: &str) -> Result<Expr, SymError> {
        let e = eom_sym::parse(text, &self.parse_scope)?;
        if self.placeholders.is_empty() {
            return Ok(e);
        }
        let used: Vec<(Expr, Expr)> = Expr::params_of(&[e])
            .into_iter()
            .filter_map(|k| self.placeholders.get(&k).copied())
            .collect();
        if used.is_empty() {
            Ok(e)
        } else {
            e.subs(&used)
        }
    }
}

/// Declares the parameters of `[parameters]` in `model`, with `overrides` for the values.
pub(crate) fn declare(
    root: &Table<'_>,
    model: &mut Model,
    overrides: &[(&str, f64)],
) -> Result<Declarations, FileError> {
    let mut specs: Vec<(ParamSpec, Range<usize>)> = Vec::new();
    let mut derived: Vec<(String, String, Range<usize>)> = Vec::new();
    if let Some(t) = root.table("parameters")? {
        for (name, key_span, v) in t.entries() {
            entry(&t, name, key_span, v, &mut specs, &mut derived)?;
        }
    }
    for (k, _) in overrides {
        if derived.iter().any(|d| d.0 == *k) {
            let d = derived.iter().find(|d| d.0 == *k).expect("found");
            return Err(FileError::Override(Box::new(
                ModelError::DerivedParameter {
                    name: k.to_string(),
                    definition: d.1.clone(),
                },
            )));
        }
        if !specs.iter().any(|s| s.0.name == *k) {
            let known: Vec<&str> = specs.iter().map(|s| s.0.name.as_str()).collect();
            return Err(FileError::Override(Box::new(ModelError::Sym(
                SymError::UnknownParameter {
                    name: k.to_string(),
                    known: known.iter().map(|s| s.to_string()).collect(),
                },
            ))));
        }
    }
    let mut scope_params = Vec::new();
    for (spec, span) in &mut specs {
        if let Some(&(_, v)) = overrides.iter().rev().find(|(k, _)| *k == spec.name) {
            spec.value = v;
        }
        if !spec.range.contains(spec.value) {
            return Err(root.ctx.error(
                span,
                &format!("parameter `{}`", spec.name),
                format!(
                    "value {} is outside its range {}",
                    spec.value,
                    spec.range.text()
                ),
            ));
        }
        let p = model
            .param_info(ParamInfo {
                name: spec.name.clone(),
                nominal: spec.value,
                unit: (!spec.unit.is_empty()).then(|| spec.unit.clone()),
                description: (!spec.description.is_empty()).then(|| spec.description.clone()),
                assume: spec.range.assumption(),
            })
            .map_err(|e| {
                let problem = match &e {
                    ModelError::Sym(s) => declaration_problem(s),
                    e => e.to_string(),
                };
                root.ctx
                    .error(span, &format!("parameter `{}`", spec.name), problem)
            })?;
        scope_params.push(p);
    }
    let (parse_scope, placeholders) = resolve_derived(root.ctx, model, &scope_params, &derived)?;
    let placeholders = placeholders
        .into_iter()
        .map(|(h, e)| {
            (
                h.param_index().expect("a placeholder is a parameter"),
                (h, e),
            )
        })
        .collect();
    Ok(Declarations {
        specs: specs.into_iter().map(|s| s.0).collect(),
        derived_text: derived.into_iter().map(|d| (d.0, d.1)).collect(),
        parse_scope,
        placeholders,
    })
}

/// One entry of `[parameters]`.
fn entry(
    t: &Table<'_>,
    name: &str,
    key_span: Range<usize>,
    v: &Value<'_>,
    specs: &mut Vec<(ParamSpec, Range<usize>)>,
    derived: &mut Vec<(String, String, Range<usize>)>,
) -> Result<(), FileError> {
    let context = format!("parameter `{}`", eom_text::shown(name));
    let mut spec = ParamSpec {
        name: name.to_string(),
        value: 0.0,
        default: 0.0,
        unit: String::new(),
        description: String::new(),
        range: ParamRange::Any,
    };
    let value = match v.get_ref() {
        DeValue::Table(_) => {
            let sub = Table::sub(t.ctx, v, context.clone())?;
            sub.only(&["value", "unit", "description", "range"])?;
            spec.unit = sub.string("unit")?.unwrap_or_default();
            spec.description = sub.string("description")?.unwrap_or_default();
            if let Some(r) = sub.string("range")? {
                let span = sub
                    .get("range")
                    .map(|x| x.span())
                    .unwrap_or(key_span.clone());
                spec.range =
                    ParamRange::parse(&r).map_err(|p| sub.field_error("range", &span, p))?;
            }
            sub.get("value")
                .ok_or_else(|| sub.error("a parameter table needs a `value`"))?
        }
        _ => v,
    };
    match value.get_ref() {
        DeValue::String(s) => {
            derived.push((name.to_string(), s.to_string(), value.span()));
        }
        _ => {
            let x = number(t.ctx, value, &context)?;
            spec.value = x;
            spec.default = x;
            if specs.iter().any(|s| s.0.name == name) {
                return Err(t.ctx.error(&key_span, &context, "declared twice"));
            }
            specs.push((spec, key_span));
        }
    }
    Ok(())
}

/// A finite number.
fn number(ctx: &Ctx<'_>, v: &Value<'_>, context: &str) -> Result<f64, FileError> {
    let x = match v.get_ref() {
        DeValue::Integer(i) => parse_integer(i.as_str(), i.radix()).map(|n| n as f64),
        DeValue::Float(f) => f.as_str().replace('_', "").parse::<f64>().ok(),
        other => {
            return Err(ctx.error(
                &v.span(),
                context,
                format!(
                    "expected a number or an expression string, found {}",
                    other.type_str()
                ),
            ));
        }
    };
    match x {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(ctx.error(&v.span(), context, "expected a finite number")),
    }
}

/// The parse scope with placeholders for the derived parameters, and each placeholder's
/// definition in independent parameters (in dependency order; a cycle is an error).
fn resolve_derived(
    ctx: &Ctx<'_>,
    model: &Model,
    params: &[Expr],
    derived: &[(String, String, Range<usize>)],
) -> Result<(Scope, Vec<(Expr, Expr)>), FileError> {
    let pool = model.pool();
    let mut scope = Scope::in_pool(pool.clone());
    for &p in params {
        scope
            .insert(p)
            .map_err(|e| FileError::whole(ctx.origin, e.into()))?;
    }
    let mut holders = Vec::new();
    for (name, _, span) in derived {
        if scope.get(name).is_some() {
            return Err(ctx.error(span, &format!("parameter `{name}`"), "declared twice"));
        }
        // A placeholder parameter (never part of the model's scope).
        holders.push(scope.declare(name, 0.0).map_err(|e| {
            ctx.error(
                span,
                &format!("parameter `{name}`"),
                declaration_problem(&e),
            )
        })?);
    }
    let mut parsed = Vec::new();
    for (name, text, span) in derived {
        let e = pool
            .enter(|| eom_sym::parse(text, &scope))
            .map_err(|e| string_error(ctx, span, &format!("parameter `{name}`"), text, &e))?;
        parsed.push(e);
    }
    // Resolve in dependency order (Kahn's algorithm on the placeholders each definition
    // uses), each definition substituted with the resolved definitions of its own
    // dependencies only: linear in the number of derived parameters and their sizes.
    let index_of: HashMap<u32, usize> = holders
        .iter()
        .enumerate()
        .map(|(j, h)| (h.param_index().expect("param"), j))
        .collect();
    let deps: Vec<Vec<usize>> = parsed
        .iter()
        .map(|e| {
            Expr::params_of(&[*e])
                .into_iter()
                .filter_map(|k| index_of.get(&k).copied())
                .collect()
        })
        .collect();
    let mut waiting: Vec<usize> = deps.iter().map(Vec::len).collect();
    let mut users: Vec<Vec<usize>> = vec![Vec::new(); derived.len()];
    for (k, d) in deps.iter().enumerate() {
        for &j in d {
            users[j].push(k);
        }
    }
    let mut ready: Vec<usize> = (0..derived.len())
        .rev()
        .filter(|&k| waiting[k] == 0)
        .collect();
    let mut done: Vec<Option<Expr>> = vec![None; derived.len()];
    let mut map: Vec<(Expr, Expr)> = Vec::with_capacity(derived.len());
    while let Some(k) = ready.pop() {
        let e = if deps[k].is_empty() {
            parsed[k]
        } else {
            let own: Vec<(Expr, Expr)> = deps[k]
                .iter()
                .map(|&j| (holders[j], done[j].expect("resolved first")))
                .collect();
            parsed[k]
                .subs(&own)
                .map_err(|e| FileError::whole(ctx.origin, e.into()))?
        };
        done[k] = Some(e);
        map.push((holders[k], e));
        for &u in &users[k] {
            waiting[u] -= 1;
            if waiting[u] == 0 {
                ready.push(u);
            }
        }
    }
    if let Some(k) = done.iter().position(Option::is_none) {
        let cycle: Vec<&str> = (0..derived.len())
            .filter(|&j| done[j].is_none())
            .map(|j| derived[j].0.as_str())
            .collect();
        return Err(ctx.error(
            &derived[k].2,
            &format!("parameter `{}`", derived[k].0),
            format!(
                "derived parameters depend on each other in a cycle: {}",
                cycle.join(", ")
            ),
        ));
    }
    Ok((scope, map))
}

/// An expression error in a string value, positioned at the column inside the string.
pub(crate) fn string_error(
    ctx: &Ctx<'_>,
    span: &Range<usize>,
    context: &str,
    text: &str,
    e: &SymError,
) -> FileError {
    // An expression too long to repeat is cut (the column still points into it).
    let shown = format!("{}`", eom_text::shown_within(text, 80));
    let (at, problem) = match e {
        SymError::Parse {
            column,
            expected,
            found,
            ..
        } => {
            // The value's span starts at its opening quote.
            let offset: usize = text
                .chars()
                .take(column.saturating_sub(1))
                .map(char::len_utf8)
                .sum();
            (
                span.start + 1 + offset,
                format!("in `{shown}: expected {expected}, found {found}"),
            )
        }
        other => (span.start, format!("in `{shown}: {other}")),
    };
    ctx.error(&(at..at), context, problem)
}

/// A number or an expression string as an expression.
pub(crate) fn value_expr(
    ctx: &Ctx<'_>,
    decl: &Declarations,
    v: &Value<'_>,
    context: &str,
) -> Result<Expr, FileError> {
    match v.get_ref() {
        DeValue::Integer(i) => match parse_integer(i.as_str(), i.radix()) {
            Some(n) => Ok(Expr::int(n)),
            None => Err(ctx.error(&v.span(), context, "integer out of range")),
        },
        DeValue::Float(f) => {
            let text = f.as_str().replace('_', "");
            // Decimal literals are exact (0.21 is 21/100), as in expressions.
            eom_sym::parse(&text, &Scope::new()).map_err(|_| {
                ctx.error(
                    &v.span(),
                    context,
                    format!("`{text}` is not a finite number"),
                )
            })
        }
        DeValue::String(s) => decl
            .expr(s)
            .map_err(|e| string_error(ctx, &v.span(), context, s, &e)),
        other => Err(ctx.error(
            &v.span(),
            context,
            format!(
                "expected a number or an expression string, found {}",
                other.type_str()
            ),
        )),
    }
}

/// A 3-vector of numbers or expressions.
pub(crate) fn vector(
    ctx: &Ctx<'_>,
    _scope: &Scope,
    decl: &Declarations,
    v: &Value<'_>,
    context: &str,
) -> Result<[Expr; 3], FileError> {
    let t = Table {
        ctx,
        table: empty_table(),
        span: v.span(),
        context: context.to_string(),
    };
    let a = array_of(&t, "", v, 3)?;
    Ok([
        value_expr(ctx, decl, &a[0], context)?,
        value_expr(ctx, decl, &a[1], context)?,
        value_expr(ctx, decl, &a[2], context)?,
    ])
}

fn empty_table() -> &'static toml::de::DeTable<'static> {
    static EMPTY: std::sync::OnceLock<toml::de::DeTable<'static>> = std::sync::OnceLock::new();
    EMPTY.get_or_init(Default::default)
}

/// What is wrong with a declaration, without the parameter's name (the file's message names it
/// already).
fn declaration_problem(e: &eom_sym::SymError) -> String {
    match e {
        eom_sym::SymError::BadParameter { problem, .. } => problem.clone(),
        e => e.to_string(),
    }
}
