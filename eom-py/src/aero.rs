//! `eom.aero(path)`: the body-axis derivatives of a wing file (an AVL geometry solved by the
//! vortex lattice, or AVL's `.sb`/`.st` output), as `eom aero` prints them.

use crate::errors::eom_error;
use eom_aero::Derivatives;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The derivatives of the wing file at `path`: a dict of `file`, `source` (what the file
/// holds, as `eom aero` says it), `reference` (Sref, Cref, Bref, point), `alpha_deg`,
/// `names` and `coefficients` (6 × 6, rows CX … Cn, columns û … r̂), `unknown`, `warnings`,
/// and `dimensional` (6 × 6, SI) at `density` and `speed`.
#[pyfunction]
#[pyo3(signature = (path, alpha_deg=None, reference=None, density=1.225, speed=10.0))]
pub fn aero<'py>(
    py: Python<'py>,
    path: &str,
    alpha_deg: Option<f64>,
    reference: Option<[f64; 3]>,
    density: f64,
    speed: f64,
) -> PyResult<Bound<'py, PyDict>> {
    // Every message names the file (the readers' do; the solver's name a surface).
    let named = |e: eom_aero::AeroError| {
        let m = e.to_string();
        if m.contains(path) {
            eom_error(m)
        } else {
            eom_error(format!("{path}: {m}"))
        }
    };
    let (w, dimensional) = py.detach(|| {
        let w = eom_aero::read_wing_file(path, alpha_deg, reference).map_err(named)?;
        let dimensional = w.derivatives.dimensional(density, speed).map_err(named)?;
        Ok::<_, PyErr>((w, dimensional))
    })?;
    let r = &w.derivatives.reference;
    let d = PyDict::new(py);
    d.set_item("file", path)?;
    d.set_item("source", w.kind.description())?;
    d.set_item("reference", (r.sref, r.cref, r.bref, r.point))?;
    d.set_item("alpha_deg", w.alpha_deg)?;
    d.set_item("names", Derivatives::names())?;
    d.set_item("coefficients", w.derivatives.coefficients)?;
    d.set_item("unknown", w.unknown)?;
    d.set_item(
        "warnings",
        w.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    )?;
    d.set_item("density", density)?;
    d.set_item("speed", speed)?;
    d.set_item("dimensional", dimensional)?;
    Ok(d)
}
