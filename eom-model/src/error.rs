//! The error type of eom-model.

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
    /// A model file is invalid: where, about what (item and field), and what is wrong.
    #[error("{position}: {}{problem}", if context.is_empty() { String::new() } else { format!("{context}: ") })]
    File {
        /// File, line and column.
        position: crate::file::FilePosition,
        /// The item and field, e.g. ``spring `front`, field `stiffness` ``.
        context: String,
        /// What is wrong, with the valid alternatives where there is a short list.
        problem: String,
    },
    /// An error of the expression layer (a parameter, an expression, an evaluation).
    #[error(transparent)]
    Sym(#[from] SymError),
    /// An error of the numeric layer.
    #[error(transparent)]
    Num(#[from] NumError),
}
