//! The error type of eom-model, and how its messages name an item.

use eom_num::NumError;
use eom_sym::SymError;

/// Everything that can go wrong while building, assembling or reducing a model. Messages name
/// the item, field or parameter at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A model item or field is invalid.
    #[error("{item}{}: {problem}", if field.is_empty() { String::new() } else { format!(", field `{field}`") })]
    Model {
        /// The item, e.g. ``spring `front` ``.
        item: String,
        /// The field, e.g. `stiffness` (may be empty).
        field: String,
        /// What is wrong.
        problem: String,
    },
    /// The model is not in static equilibrium at its given geometry.
    #[error("not in equilibrium: {0}")]
    Equilibrium(String),
    /// A matrix that must be invertible is singular (at the nominal point, or at the point of
    /// evaluation).
    #[error("singular: {0}")]
    Singular(String),
    /// A pivot recorded in the symbolic elimination plan broke down at the evaluation point:
    /// the symbolic result is not valid there (the numeric and robust methods reduce at the point).
    #[error("outside the validity region of the symbolic reduction: {0}")]
    PivotBreakdown(String),
    /// A model feature that this path does not support (the message says which path does).
    #[error("not supported: {0}")]
    Unsupported(String),
    /// An error of the expression layer (a parameter, an expression, an evaluation).
    #[error(transparent)]
    Sym(#[from] SymError),
    /// An error of the numeric layer.
    #[error(transparent)]
    Num(#[from] NumError),
}

/// The label of an item in messages: ``spring `front` ``. Built directly rather than by
/// `format!`: every reacting item's preload is labelled on every assembly.
pub(crate) fn label(kind: &str, name: &str) -> String {
    let name = eom_text::shown(name);
    let mut s = String::with_capacity(kind.len() + name.len() + 3);
    s.push_str(kind);
    s.push_str(" `");
    s.push_str(&name);
    s.push('`');
    s
}

/// The error of a bad field of an item.
pub(crate) fn field_error(kind: &str, name: &str, field: &str, problem: String) -> ModelError {
    ModelError::Model {
        item: label(kind, name),
        field: field.to_string(),
        problem,
    }
}
