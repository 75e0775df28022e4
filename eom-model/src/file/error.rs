//! [`FileError`]: what is wrong with a model file, and where.

use super::source::FilePosition;
use crate::error::ModelError;

/// A model file that cannot be loaded: the position in the file (file, line and column), and
/// either what is wrong with the text there or the model error of the body or item defined
/// there (boxed: a file error is passed up through every reader).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// The text is invalid: an unknown key, a value of the wrong type, an expression that does
    /// not parse, a name taken twice, a body that does not exist.
    #[error("{position}: {}{problem}", if context.is_empty() { String::new() } else { format!("{context}: ") })]
    Invalid {
        /// File, line and column.
        position: FilePosition,
        /// The item and field, e.g. ``spring `front`, field `stiffness` ``.
        context: String,
        /// What is wrong, with the valid alternatives where there is a short list.
        problem: String,
    },
    /// The model the file describes is invalid: the error of its checks, positioned at the
    /// table of the body or item at fault (the file as a whole when no table defined it).
    #[error("{position}: {error}")]
    Model {
        /// File, line and column of the table at fault.
        position: FilePosition,
        /// The model's error.
        #[source]
        error: Box<ModelError>,
    },
    /// A value given with the file for a parameter it does not declare, or declares as
    /// derived: not about the text, so not positioned in it.
    #[error(transparent)]
    Override(Box<ModelError>),
}

impl FileError {
    /// Where in the file (`None` for an override).
    pub fn position(&self) -> Option<&FilePosition> {
        match self {
            FileError::Invalid { position, .. } | FileError::Model { position, .. } => {
                Some(position)
            }
            FileError::Override(_) => None,
        }
    }

    /// `error` about the file `origin` as a whole.
    pub(crate) fn whole(origin: &str, error: ModelError) -> Self {
        FileError::Model {
            position: FilePosition::whole(origin),
            error: Box::new(error),
        }
    }
}
