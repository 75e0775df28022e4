//! Parser for expressions as users write them (to be completed).

use crate::error::SymError;
use crate::expr::Expr;
use crate::scope::Scope;

/// Parse `input` with parameters resolved in `scope`.
pub fn parse(input: &str, scope: &Scope) -> Result<Expr, SymError> {
    let _ = scope;
    Err(SymError::Parse {
        column: 1,
        expected: "an expression".into(),
        found: input.chars().next().map(|c| format!("`{c}`")).unwrap_or_else(|| "end of input".into()),
        input: input.into(),
        caret: "^".into(),
    })
}
