//! Where a model comes from — a built-in by name, or a model file kept as its text — and
//! building it at parameter values. The text travels with a pickled model, so a worker that
//! has no copy of the file rebuilds the same model.

use crate::errors::{catalogue_error, eom_error, file_error};
use eom_model::file::{FileError, ParamRange};
use eom_model::{Model, Warning};
use pyo3::{PyErr, PyResult};
use std::path::{Path, PathBuf};

/// The origin of a model.
#[derive(Clone, Debug)]
pub enum Source {
    /// A built-in model of the catalogue (`chain50` included).
    Builtin(String),
    /// A model file: its path as given and its text.
    File {
        /// The path as given (named in messages; AVL files it names are relative to it).
        path: String,
        /// The file's text when it was loaded.
        text: String,
    },
}

impl Source {
    /// A built-in model's name or a file path: a name ending in `.toml`, holding a `/`, or
    /// naming an existing file that is not a built-in model (as `eom` decides).
    pub fn resolve(name_or_path: &str) -> PyResult<Source> {
        let is_file = name_or_path.ends_with(".toml")
            || name_or_path.contains('/')
            || (Path::new(name_or_path).is_file() && models::find(name_or_path).is_err());
        if !is_file {
            models::find(name_or_path).map_err(catalogue_error)?;
            return Ok(Source::Builtin(name_or_path.to_string()));
        }
        let text = eom_text::read_limited(Path::new(name_or_path), eom_text::MAX_FILE_BYTES)
            .map_err(|e| {
                file_error(eom_model::file::FileError::Invalid {
                    position: eom_model::file::FilePosition::whole(name_or_path),
                    context: String::new(),
                    problem: format!("cannot be read: {e}"),
                })
            })?;
        Ok(Source::File {
            path: name_or_path.to_string(),
            text,
        })
    }

    /// The model at the defaults with `overrides` by name.
    pub fn build(&self, overrides: &[(&str, f64)]) -> Result<Model, BuildError> {
        match self {
            Source::Builtin(name) => models::build(name, overrides).map_err(BuildError::Catalogue),
            Source::File { path, text } => {
                // The file itself where it still holds the same text (its AVL files are then
                // found relative to it); else the text, as on a worker without the file.
                let p = PathBuf::from(path);
                let same =
                    eom_text::read_limited(&p, eom_text::MAX_FILE_BYTES).is_ok_and(|t| t == *text);
                let loaded = if same {
                    eom_model::file::load(&p, overrides)
                } else {
                    eom_model::file::load_str(text, path, overrides)
                };
                Ok(loaded.map_err(BuildError::File)?.model)
            }
        }
    }

    /// The allowed values of the parameters `names` (in that order): those the catalogue or
    /// the file declares. `None` when a name has no declaration.
    pub fn ranges(&self, names: &[String]) -> Option<Vec<ParamRange>> {
        let specs = match self {
            Source::Builtin(name) => models::find(name).ok()?.0.params,
            Source::File { path, text } => eom_model::file::load_str(text, path, &[]).ok()?.params,
        };
        names
            .iter()
            .map(|n| specs.iter().find(|s| s.name == *n).map(|s| s.range))
            .collect()
    }

    /// The loading warnings of a model file (none for a built-in).
    pub fn load_warnings(&self) -> Vec<WarningRow> {
        match self {
            Source::Builtin(_) => Vec::new(),
            Source::File { path, text } => eom_model::file::load_str(text, path, &[])
                .map(|l| warning_rows(&l.warnings))
                .unwrap_or_default(),
        }
    }

    /// The state a pickled model carries: `("builtin", name, "")` or `("file", path, text)`.
    pub fn state(&self) -> (String, String, String) {
        match self {
            Source::Builtin(n) => ("builtin".into(), n.clone(), String::new()),
            Source::File { path, text } => ("file".into(), path.clone(), text.clone()),
        }
    }

    /// The source back from [`Source::state`].
    pub fn from_state(kind: &str, name: String, text: String) -> PyResult<Source> {
        match kind {
            "builtin" => Ok(Source::Builtin(name)),
            "file" => Ok(Source::File { path: name, text }),
            k => Err(eom_error(format!(
                "unknown model source `{k}` in a pickled model"
            ))),
        }
    }
}

/// Why a model could not be built (no Python objects: raised on any thread).
#[derive(Debug)]
pub enum BuildError {
    /// Of the catalogue (unknown parameter, bad value).
    Catalogue(models::CatalogueError),
    /// Of a model file.
    File(FileError),
}

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BuildError::Catalogue(e) => e.fmt(f),
            BuildError::File(e) => e.fmt(f),
        }
    }
}

impl From<BuildError> for PyErr {
    fn from(e: BuildError) -> PyErr {
        match e {
            BuildError::Catalogue(e) => catalogue_error(e),
            BuildError::File(e) => file_error(e),
        }
    }
}

/// A warning as Python receives it: its kind (`"statics_redundant"`), the name of the item
/// it is about (if any) and its message.
pub type WarningRow = (&'static str, Option<String>, String);

/// `warnings` as Python receives them.
pub fn warning_rows(warnings: &[Warning]) -> Vec<WarningRow> {
    warnings
        .iter()
        .map(|w| (w.kind(), w.item().map(|i| i.name.clone()), w.to_string()))
        .collect()
}
