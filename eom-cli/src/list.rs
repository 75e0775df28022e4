//! `eom list`: the built-in models and their parameters.

use crate::format::{g, table};
use serde::Serialize;

/// One model of the catalogue.
#[derive(Clone, Debug, Serialize)]
pub struct ModelEntry {
    /// Name (`chainN` is a pattern: `chain10`, `chain50`, …).
    pub name: String,
    /// Whether the name is a pattern with a size N.
    pub pattern: bool,
    /// One-line description.
    pub description: String,
    /// Parameters.
    pub parameters: Vec<ParamEntry>,
}

/// One parameter.
#[derive(Clone, Debug, Serialize)]
pub struct ParamEntry {
    /// Name.
    pub name: String,
    /// Default value.
    pub default: f64,
    /// Unit.
    pub unit: String,
    /// Allowed values as a model file writes them: `> 0`, `>= 0`, `!= 0`, `any` or an
    /// interval.
    pub allowed: String,
    /// Description.
    pub description: String,
}

/// The catalogue.
pub fn entries() -> Vec<ModelEntry> {
    models::catalogue()
        .into_iter()
        .map(|m| ModelEntry {
            name: m.name.to_string(),
            // A catalogue name that cannot be looked up as such is a pattern (`chainN`).
            pattern: models::find(m.name).is_err(),
            description: m.description,
            parameters: m
                .params
                .iter()
                .map(|p| ParamEntry {
                    name: p.name.clone(),
                    default: p.default,
                    unit: p.unit.clone(),
                    allowed: p.range.text(),
                    description: p.description.clone(),
                })
                .collect(),
        })
        .collect()
}

/// The catalogue as text.
pub fn to_text(entries: &[ModelEntry]) -> String {
    let mut t = String::from(
        "Built-in models (use: eom analyze MODEL --set NAME=VALUE …; parameters not set take \
         their defaults)\n",
    );
    for m in entries {
        let name = if m.pattern {
            let stem = m.name.trim_end_matches('N');
            format!("{} (N ≥ 1, e.g. {stem}10, {stem}50)", m.name)
        } else {
            m.name.clone()
        };
        t.push_str(&format!("\n{name} — {}\n", m.description));
        let rows: Vec<Vec<String>> = m
            .parameters
            .iter()
            .map(|p| {
                vec![
                    p.name.clone(),
                    g(p.default, 6),
                    p.unit.clone(),
                    p.allowed.clone(),
                    p.description.clone(),
                ]
            })
            .collect();
        t.push_str(&table(
            &["parameter", "default", "unit", "allowed", "description"],
            &rows,
            2,
        ));
    }
    t
}
