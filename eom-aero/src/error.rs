//! The crate's one error type.

use thiserror::Error;

/// Everything that can go wrong in eom-aero. Every variant names what is at fault: the
/// surface, section and field of a geometry, or the file, line and field of an input file.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum AeroError {
    /// A configuration-level field (reference quantities, Mach, symmetry) is invalid.
    #[error("configuration `{}`: {field} {reason}", eom_text::shown(config))]
    Configuration {
        /// The configuration's title.
        config: String,
        /// The field at fault, e.g. `Sref`.
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// A surface or one of its sections is invalid.
    #[error(
        "surface `{}`{}: {field} {reason}",
        eom_text::shown(surface),
        section_suffix(*.section)
    )]
    Geometry {
        /// The surface's name.
        surface: String,
        /// The section (0-based) at fault, if the fault is in one section.
        section: Option<usize>,
        /// The field at fault, e.g. `chord`.
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// A solver option is invalid (e.g. a non-finite angle of attack).
    #[error("solver option {option}: {reason}")]
    Option {
        /// The option at fault.
        option: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// The influence matrix could not be factored reliably (coincident or overlapping
    /// panels, e.g. a surface lying in its own `YDUPLICATE` plane).
    #[error("singular vortex-lattice influence matrix ({panels} panels): {reason}")]
    Singular {
        /// Number of panels in the lattice.
        panels: usize,
        /// What was detected.
        reason: String,
    },
    /// A quantity out of the range where the results are numbers: a dimensional matrix that
    /// overflows, a lattice beyond the panel limit or the memory limit.
    #[error("{what}: {reason}")]
    OutOfRange {
        /// What is out of range.
        what: String,
        /// Why, with the sizes.
        reason: String,
    },
    /// A syntax error in an input file.
    #[error("{file}:{line}: {message}")]
    Parse {
        /// The file (as given by the caller).
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A keyword of an `.avl` file that this crate deliberately does not honour.
    #[error(
        "{file}:{line}: keyword `{}` is not supported: {reason}",
        eom_text::shown(keyword)
    )]
    UnsupportedKeyword {
        /// The file.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The keyword as written in the file.
        keyword: String,
        /// Why it is refused.
        reason: String,
    },
    /// A value in an AVL output file that cannot be used (`***` overflow, NaN, not a number).
    #[error(
        "{file}:{line}: {} = `{}`: {reason}",
        eom_text::shown(field),
        eom_text::shown(text)
    )]
    BadValue {
        /// The file.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The field's name, e.g. `CYv`.
        field: String,
        /// The text found after `=`.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A field that the file must contain is absent.
    #[error("{file}: missing {field} ({hint})")]
    MissingField {
        /// The file.
        file: String,
        /// The field's name.
        field: String,
        /// A hint on the likely cause (truncated file, another AVL version, …).
        hint: String,
    },
    /// A file that is neither an AVL geometry nor an AVL derivative file (by its extension).
    #[error("{file}: expected an AVL geometry (.avl) or an AVL derivative file (.sb, .st)")]
    FileKind {
        /// The file.
        file: String,
    },
    /// The file cannot be read.
    #[error("cannot read {file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
}

fn section_suffix(section: Option<usize>) -> String {
    match section {
        Some(s) => format!(", section {}", s + 1),
        None => String::new(),
    }
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, AeroError>;
