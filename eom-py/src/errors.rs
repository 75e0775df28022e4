//! Rust errors as the Python package's exceptions (`eom.EomError`, `eom.ModelFileError`,
//! defined in `python/eom/_errors.py`), with the Rust messages unchanged.

use eom_model::ModelError;
use eom_model::file::FileError;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// Raises `eom.EomError(message)`.
pub fn eom_error(message: impl std::fmt::Display) -> PyErr {
    let message = message.to_string();
    raise("EomError", |py| (message,).into_pyobject(py))
}

/// A model error: `eom.EomError(message)`.
pub fn model_error(e: ModelError) -> PyErr {
    eom_error(e)
}

/// A model file error: `eom.ModelFileError(message, file, line, column)` where it has a
/// position in the file, `eom.EomError` otherwise (an override of a parameter the file does
/// not declare).
pub fn file_error(e: FileError) -> PyErr {
    match e.position() {
        Some(position) => {
            let args = (
                e.to_string(),
                position.file.clone(),
                position.line,
                position.column,
            );
            raise("ModelFileError", |py| args.into_pyobject(py))
        }
        None => eom_error(e),
    }
}

/// An error of the catalogue (unknown model or parameter, a value outside a range).
pub fn catalogue_error(e: models::CatalogueError) -> PyErr {
    match e {
        models::CatalogueError::Model(m) => model_error(m),
        e => eom_error(e),
    }
}

/// An instance of the exception class `class` of `eom._errors` called with `args`.
fn raise(
    class: &str,
    args: impl for<'py> FnOnce(Python<'py>) -> PyResult<Bound<'py, PyTuple>>,
) -> PyErr {
    Python::attach(|py| {
        match py
            .import("eom._errors")
            .and_then(|m| m.getattr(class))
            .and_then(|cls| cls.call1(args(py)?))
        {
            Ok(exc) => PyErr::from_value(exc),
            Err(e) => PyRuntimeError::new_err(format!("eom: cannot raise {class}: {e}")),
        }
    })
}
