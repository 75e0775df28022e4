//! [`CliError`]: the one error type of the `eom` binary, and its exit codes.

use eom_model::ModelError;
use eom_model::file::FileError;
use eom_num::NumError;
use eom_num::sweep::SweepError;
use eom_sym::SymError;
use models::CatalogueError;

/// Exit code of a usage error: unknown model or parameter, malformed argument (the same code
/// clap uses for its own argument errors).
pub const EXIT_USAGE: u8 = 2;

/// Exit code of every other failure (numerical trouble, I/O, code generation).
pub const EXIT_FAILURE: u8 = 1;

/// Everything that can go wrong in a command. Messages name the argument, parameter, model or
/// point at fault and, for unknown names, list the valid ones.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The model library rejected the model, a parameter name or a parameter value.
    #[error(transparent)]
    Catalogue(#[from] CatalogueError),
    /// A malformed command-line argument (`--set`, `--param`, `--freq-range`, …).
    #[error("argument `{argument}`: {problem}")]
    BadArgument {
        /// The argument as given (with its option).
        argument: String,
        /// What is wrong with it, and what is expected.
        problem: String,
    },
    /// Building, reducing or evaluating the model failed.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A model file is invalid (the message names the file, line and column), or an override
    /// names a parameter it does not declare.
    #[error(transparent)]
    File(#[from] FileError),
    /// An expression could not be built or evaluated.
    #[error(transparent)]
    Sym(#[from] SymError),
    /// `--method symbolic` at a point outside the validity region of the symbolic reduction.
    #[error(
        "{source}\n  (--method symbolic reduces the model with pivots chosen at its default \
             parameter values and evaluates the result at the point; {})",
        suggestion(alternatives)
    )]
    OutsideSymbolicRegion {
        /// The failed validity check.
        source: Box<ModelError>,
        /// The methods that were tried and reduce the model at this point.
        alternatives: Vec<&'static str>,
    },
    /// The reduction method asked for failed at the point for a reason of its own.
    #[error("{source}\n  (with --method {method}; {})", suggestion(alternatives))]
    MethodFailed {
        /// Why.
        source: Box<ModelError>,
        /// The method that failed.
        method: &'static str,
        /// The other methods that were tried and reduce the model at this point.
        alternatives: Vec<&'static str>,
    },
    /// A wing file could not be read or solved (the message names the file, line and field).
    #[error(transparent)]
    Aero(#[from] eom_aero::AeroError),
    /// A numeric analysis failed.
    #[error(transparent)]
    Num(#[from] NumError),
    /// A parameter sweep failed (the message names the parameter value).
    #[error(transparent)]
    Sweep(#[from] Box<SweepError<CliError>>),
    /// Code generation failed.
    #[cfg(feature = "codegen")]
    #[error(transparent)]
    Codegen(#[from] eom_codegen::CodegenError),
    /// A feature this build does not include.
    #[cfg(any(not(feature = "codegen"), not(feature = "bench")))]
    #[error("{0}")]
    Unavailable(String),
    /// A picture that this model cannot give (no mode moves a body, no map to the bodies).
    #[error("{0}")]
    NothingToDraw(String),
    /// Two computations that must agree do not (a bug, or an interface that changed under
    /// this crate).
    #[error("internal inconsistency: {0}")]
    Inconsistent(String),
    /// JSON serialization failed.
    #[error("writing JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// Drawing a plot failed (before anything was written).
    #[error("drawing the plot: {0}")]
    Plot(String),
    /// A plot file cannot be written (its directory does not exist, it is a directory, no
    /// permission, …).
    #[error("cannot write the plot `{path}` ({option}): {source}")]
    PlotFile {
        /// The option that named the file (`--plot`, `--plot-poles`).
        option: String,
        /// The file.
        path: String,
        /// Why not.
        source: std::io::Error,
    },
    /// A benchmark of `eom bench` could not be run (its reference could not be formed, or
    /// its chart drawn).
    #[cfg(feature = "bench")]
    #[error("bench: {0}")]
    Bench(String),
    /// Reading or writing a file or a stream.
    #[error("{path}: {source}")]
    Io {
        /// The file (or `standard output`).
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
}

impl CliError {
    /// The process exit code for this error: [`EXIT_USAGE`] for unknown names and malformed
    /// arguments, [`EXIT_FAILURE`] otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Catalogue(
                CatalogueError::UnknownModel { .. }
                | CatalogueError::ChainTooLong { .. }
                | CatalogueError::UnknownParameter { .. }
                | CatalogueError::BadValue { .. },
            )
            | CliError::BadArgument { .. }
            | CliError::File(FileError::Invalid { .. } | FileError::Model { .. })
            | CliError::Aero(
                eom_aero::AeroError::Parse { .. }
                | eom_aero::AeroError::UnsupportedKeyword { .. }
                | eom_aero::AeroError::BadValue { .. }
                | eom_aero::AeroError::MissingField { .. }
                | eom_aero::AeroError::OutOfRange { .. }
                // A geometry, reference or option given that the lattice cannot take (e.g.
                // `--ref 1e308,0,0`): the input's fault.
                | eom_aero::AeroError::Configuration { .. }
                | eom_aero::AeroError::Geometry { .. }
                | eom_aero::AeroError::Option { .. }
                | eom_aero::AeroError::FileKind { .. }
                | eom_aero::AeroError::Io { .. },
            ) => EXIT_USAGE,
            // A model beyond the memory limit: the size of the input, not a failure.
            CliError::Num(NumError::TooLarge { .. })
            | CliError::Model(ModelError::Num(NumError::TooLarge { .. })) => EXIT_USAGE,
            CliError::Sweep(e) if matches!(**e, SweepError::Setup(NumError::TooLarge { .. })) => {
                EXIT_USAGE
            }
            _ => EXIT_FAILURE,
        }
    }
}

/// The advice after a symbolic reduction failed: only methods that were tried and work.
fn suggestion(alternatives: &[&str]) -> String {
    match alternatives {
        [] => "no other method reduces the model at this point either".into(),
        [one] => format!("here --method {one} works"),
        _ => format!(
            "here use --method {}, which choose the pivots at the point",
            alternatives.join(" or --method ")
        ),
    }
}
