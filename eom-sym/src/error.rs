//! The error type of eom-sym.

/// Everything that can go wrong in eom-sym. Messages name the parameter, item, field or
/// position at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SymError {
    /// A parse error: where, what was expected, what was found.
    #[error(
        "parse error at column {column}: expected {expected}, found {found}\n  {input}\n  {caret}"
    )]
    Parse {
        /// 1-based column (in characters) of the offending token.
        column: usize,
        /// What the parser expected there.
        expected: String,
        /// What it found.
        found: String,
        /// The input text.
        input: String,
        /// A caret line pointing at the column.
        caret: String,
    },
    /// Division by an expression that is structurally zero.
    #[error("division by zero: {context}")]
    DivisionByZero {
        /// Where it happened.
        context: String,
    },
    /// An exact rational result would be wider than the supported limit.
    #[error(
        "rational overflow: an exact constant would exceed {} bits",
        crate::rational::MAX_BITS
    )]
    RationalOverflow,
    /// An operation without a real value, e.g. `ln(-1)` or `(-2)^(1/2)`.
    #[error("not a real number: {what}")]
    NotReal {
        /// The offending operation.
        what: String,
    },
    /// A NaN or infinite value where a finite one is required.
    #[error("non-finite value: {what}")]
    NonFinite {
        /// What was not finite.
        what: String,
    },
    /// A product of floating-point constants fell below the normal range: folding it would
    /// change the value (the rewrite that asked for it is not made).
    #[error("a floating-point constant underflowed: {what}")]
    Underflow {
        /// The product.
        what: String,
    },
    /// A parameter was declared with an invalid name or nominal value.
    #[error("parameter `{name}`: {problem}")]
    BadParameter {
        /// The parameter's name.
        name: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A name that is not a known parameter.
    #[error(
        "unknown parameter `{name}`{}; known parameters: {}",
        eom_text::did_you_mean(name, known),
        known.join(", ")
    )]
    UnknownParameter {
        /// The unknown name.
        name: String,
        /// The names that are known in this context.
        known: Vec<String>,
    },
    /// An expression to be evaluated depends on a parameter that was not supplied.
    #[error("missing value for parameter `{name}`")]
    MissingParameter {
        /// The parameter's name.
        name: String,
    },
    /// The wrong number of values was supplied.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
    /// An evaluation produced a non-finite number.
    #[error("evaluation of {what} gave {value} at the given parameter values")]
    EvalNonFinite {
        /// Which output.
        what: String,
        /// The value obtained (NaN or ±inf).
        value: f64,
    },
    /// A model feature that this path does not support (the message says which path does).
    #[error("not supported: {0}")]
    Unsupported(String),
    /// A closed form of a model larger than the limit of [`crate::closed::ClosedForms`]
    /// (its `with_max_states`; the expansion by minors grows as `n·2ⁿ`).
    #[error("{what} of a {states}-state model: closed forms are limited to {limit} states")]
    TooManyStates {
        /// The closed form asked for.
        what: String,
        /// The model's number of states.
        states: usize,
        /// The limit in force.
        limit: usize,
    },
    /// The expression contains an operation without a value (division by zero, …).
    #[error("invalid expression: {0}")]
    Invalid(Box<SymError>),
}
