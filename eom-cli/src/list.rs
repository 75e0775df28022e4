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
    /// A pattern's names at two sizes, for the text (`chain10`, `chain50`).
    #[serde(skip)]
    pub examples: Vec<String>,
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
            pattern: m.is_family(),
            examples: if m.is_family() {
                vec![m.name_at(10), m.name_at(50)]
            } else {
                Vec::new()
            },
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
            format!("{} (N ≥ 1, e.g. {})", m.name, m.examples.join(", "))
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
