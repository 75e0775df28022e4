//! [`CodegenError`]: the one error type of the crate.

use eom_sym::SymError;

/// Everything that can go wrong while generating code.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CodegenError {
    /// The symbolic side failed (building, reducing or simplifying the model), or an
    /// expression cannot be evaluated (an invalid node, a parameter missing from the list).
    #[error(transparent)]
    Sym(#[from] SymError),
    /// The model layer failed (validating, assembling or reducing the model).
    #[error(transparent)]
    Model(#[from] eom_model::ModelError),
    /// The numeric reduction of the model (`--reduce`) failed.
    #[error("reduction: {0}")]
    Num(#[from] eom_num::NumError),
    /// A numeric constant that has no finite value in the chosen precision.
    #[error("{matrix}: the constant {value:?} is not finite in {precision}")]
    NonFiniteConstant {
        /// Where the constant occurs.
        matrix: String,
        /// The constant, as an `f64`.
        value: f64,
        /// `f64` or `f32`.
        precision: &'static str,
    },
    /// An option that cannot be honoured, naming the option.
    #[error("option `{option}`: {problem}")]
    BadOption {
        /// The option.
        option: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// The model is too large for the generated `Error`, whose indices are small integers
    /// (`u32` checks, `u16` rows and columns) so that `Result<(), Error>` fits in one register.
    #[error("{what}: {count} exceeds {max}, the most the generated `Error` can index")]
    TooLarge {
        /// What is too large (the checks, the rows or columns of a matrix).
        what: String,
        /// How many there are.
        count: usize,
        /// The most there may be.
        max: u64,
    },
    /// The generated tokens do not parse as a Rust file (a bug of this crate).
    #[error("generated code does not parse: {0}")]
    Syntax(String),
    /// Reading or writing a file (the `build.rs` helper).
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// An environment variable a build script needs (`OUT_DIR`) is not set.
    #[error("environment variable `{0}` is not set (is this running inside a build script?)")]
    MissingEnv(&'static str),
}
