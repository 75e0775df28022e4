//! The native side of the `eom` Python package (`eom._eom`): models by name or file,
//! linearization, the compiled tape evaluated over many points with the GIL released, the
//! per-point stability, modes, closed forms and code generation. The Python package
//! (`python/eom`) wraps these in `Model`, `LinearModel` and `eom.distributed`.
//!
//! Everything here calls the public API of the workspace crates (the same functions `eom
//! analyze`, `eom sweep`, `eom symbolic` and `eom codegen` call); errors become Python
//! exceptions with the Rust messages.

#![forbid(unsafe_code)]

mod aero;
mod errors;
mod model;
mod points;
mod source;
mod symbolic;

use pyo3::prelude::*;

/// The names of the built-in models, in catalogue order.
#[pyfunction(name = "models")]
fn model_names() -> Vec<String> {
    ::models::names().into_iter().map(String::from).collect()
}

/// The native module.
#[pymodule]
fn _eom(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(model_names, m)?)?;
    m.add_function(wrap_pyfunction!(model::modes, m)?)?;
    m.add_function(wrap_pyfunction!(aero::aero, m)?)?;
    m.add_class::<model::NativeModel>()?;
    m.add_class::<model::NativeLinear>()?;
    m.add("MAX_SMALL_STATES", eom_num::small_eigen::MAX_N)?;
    Ok(())
}
