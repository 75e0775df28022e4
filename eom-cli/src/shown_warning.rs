//! [`ShownWarning`]: a warning as the CLI prints it — a kind, the item it is about and the
//! message. The text output prints the message; the JSON output prints the object.

use serde::Serialize;

/// An item a warning is about, as the JSON output names it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct WarnedItem {
    /// The item's kind, as messages name it (`"flex point"`).
    pub kind: String,
    /// The item's name.
    pub name: String,
}

/// A warning of a command: `kind` is a short snake-case name (the model's
/// [`eom_model::Warning::kind`], or one of the CLI's own analyses such as
/// `"steady_state_gain"`), `item` the item it is about (`null` when none), `message` what the
/// text output prints.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShownWarning {
    /// The kind of warning.
    pub kind: String,
    /// The item it is about, if any.
    pub item: Option<WarnedItem>,
    /// The message (what the text output prints).
    pub message: String,
}

impl ShownWarning {
    /// A warning of one of the CLI's own analyses, about no item.
    pub fn new(kind: &str, message: String) -> Self {
        ShownWarning {
            kind: kind.to_string(),
            item: None,
            message,
        }
    }

    /// A model warning, its message prefixed by `prefix` (`"linearization: "`, or empty).
    pub fn of_model(w: &eom_model::Warning, prefix: &str) -> Self {
        ShownWarning {
            kind: w.kind().to_string(),
            item: w.item().map(|i| WarnedItem {
                kind: i.kind.to_string(),
                name: i.name.clone(),
            }),
            message: format!("{prefix}{w}"),
        }
    }

    /// A warning of a numeric analysis, its message prefixed by `prefix`.
    pub fn of_num(w: &eom_num::NumWarning, prefix: &str) -> Self {
        ShownWarning::new(w.kind(), format!("{prefix}{w}"))
    }

    /// Model warnings, each prefixed by `prefix`.
    pub fn all_of_model(ws: &[eom_model::Warning], prefix: &str) -> Vec<Self> {
        ws.iter().map(|w| Self::of_model(w, prefix)).collect()
    }
}

impl std::fmt::Display for ShownWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}
