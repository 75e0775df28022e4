//! The error type of eom-model, and how its messages name an item.

use eom_num::NumError;
use eom_sym::SymError;

/// Everything that can go wrong while building, assembling or reducing a model. Messages name
/// the item, field or parameter at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A model item or field is invalid.
    #[error("{item}{}: {problem}", field_part(field))]
    Model {
        /// The item, e.g. ``spring `front` ``.
        item: String,
        /// The field, e.g. `stiffness` (may be empty).
        field: String,
        /// What is wrong.
        problem: String,
    },
    /// A field names a body that does not exist.
    #[error("{item}, field `{field}`: unknown body `{body}`; bodies are: {}", known.join(", "))]
    UnknownBody {
        /// The item, e.g. ``spring `front` ``.
        item: String,
        /// The field.
        field: String,
        /// The name given.
        body: String,
        /// The bodies of the model (and the ground).
        known: Vec<String>,
    },
    /// A field names an item that does not exist.
    #[error("{item}, field `{field}`: unknown {kind} `{name}`; {kind}s are: {}", known.join(", "))]
    UnknownItem {
        /// The item whose field it is.
        item: String,
        /// The field.
        field: String,
        /// The kind of item it must name (`actuator`).
        kind: String,
        /// The name given.
        name: String,
        /// The items of that kind.
        known: Vec<String>,
    },
    /// An item connects a body to itself.
    #[error("{item}, field `bodies`: connects `{body}` to itself")]
    SelfConnection {
        /// The item.
        item: String,
        /// The body.
        body: String,
    },
    /// A body with a negative mass.
    #[error("{item}, field `mass`: negative mass {mass}")]
    NegativeMass {
        /// The body.
        item: String,
        /// The mass.
        mass: f64,
    },
    /// A value given that is not finite (NaN or infinite).
    #[error("{item}{}: value {value} is not finite", field_part(field))]
    NotFinite {
        /// The body or item.
        item: String,
        /// The field (may be empty).
        field: String,
        /// The value.
        value: f64,
    },
    /// A field whose expression is not finite at the parameter values given.
    #[error(
        "{item}{}: evaluates to {value} at the given parameter values",
        field_part(field)
    )]
    NotFiniteAt {
        /// The body or item.
        item: String,
        /// The field (may be empty).
        field: String,
        /// The value.
        value: f64,
    },
    /// The model is not in static equilibrium at its given geometry: the force or moment
    /// equation with a residual beyond the tolerance.
    #[error(
        "not in equilibrium: {equation}: residual {residual:.6e} (of terms summing to \
         {magnitude:.6e} in magnitude; {ratio:.1e} of the body's largest {}). The given geometry \
         is not an equilibrium with these constraints (eom uses the given geometry as the loaded \
         equilibrium: add a support, or give spring preloads that balance the loads)",
        if *length == 1.0 { "force or moment" } else { "force, or moment over the model's length scale" }
    )]
    Equilibrium {
        /// The equation (``body `frame` x force``, `known preload 2`).
        equation: String,
        /// Its residual.
        residual: f64,
        /// The sum of the magnitudes of its terms.
        magnitude: f64,
        /// The residual relative to the body's largest force or moment.
        ratio: f64,
        /// The model's length scale (moments are divided by it).
        length: f64,
    },
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

/// `, field `NAME`` (nothing for an empty field name).
fn field_part(field: &str) -> String {
    if field.is_empty() {
        String::new()
    } else {
        format!(", field `{field}`")
    }
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
