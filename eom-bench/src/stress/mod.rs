//! The failure map (`eom bench stress`): sweeps into the regions where methods break —
//! forward speed to 0 with nonholonomic contacts, stiffness ratios up to 1e±10, a nearly
//! massless body and a singular mass matrix, coalescing eigenvalues, parameters far from the
//! symbolic pivots' nominal point, geometric offsets of 1e-15…1e-3 and redundant
//! constraints ([`regions`]). At every point each method (numeric, robust, the symbolic
//! reduction formed at the region's nominal point and evaluated on the tape, and the
//! generated `f64` code where the model's code is compiled in) is classed as accurate,
//! reported failure or silently wrong against a reference ([`classify`]); [`output`] writes
//! the CSV, the Markdown table and the SVG map. See `docs/stress.md`.

pub mod chain;
pub mod classify;
pub mod models;
pub mod output;
pub mod regions;

use crate::work_precision::generated;
use crate::work_precision::reference::ReferenceModel;
use classify::{MethodResult, Outcome, classify, verdict_of};
use eom_model::{Linearizer, Method, Model, SymbolicStateSpace};
use eom_num::StateSpace;
use eom_num::modes::{ModeOptions, Modes};
use eom_sym::Expr;
use nalgebra::DMatrix;
use num_complex::Complex64;
use regions::{ReferenceKind, Region, Source};

/// The methods of the map, in column order.
pub const METHODS: [&str; 4] = ["numeric", "robust", "symbolic", "generated f64"];

/// What can go wrong in running the map (not a method's failure: those are outcomes).
#[derive(Debug, thiserror::Error)]
pub enum StressError {
    /// A region's model could not be built.
    #[error("model {0}: {1}")]
    Model(String, String),
    /// Writing the outputs.
    #[error("{0}: {1}")]
    Io(String, std::io::Error),
}

/// One method at one point.
#[derive(Clone, Debug)]
pub struct Cell {
    /// Region name.
    pub region: String,
    /// Index of the point in the region's values.
    pub point: usize,
    /// The swept parameter's value.
    pub value: f64,
    /// Method (one of [`METHODS`]).
    pub method: String,
    /// The class.
    pub outcome: Outcome,
    /// The eigenvalue error against the reference, where measured.
    pub error: Option<f64>,
    /// The reference used ("double-double", "closed form", "cross-check: numeric and robust
    /// agree", or "none").
    pub reference: String,
    /// The error message or the first doubt, shortened.
    pub note: String,
}

/// The whole map.
#[derive(Clone, Debug)]
pub struct StressMap {
    /// The regions, in row order.
    pub regions: Vec<Region>,
    /// Every cell (a method that does not apply to a region, e.g. generated code of a model
    /// that is not compiled in, has no cells there).
    pub cells: Vec<Cell>,
}

impl StressMap {
    /// Count of cells with this region, method and outcome.
    pub fn count(&self, region: &str, method: &str, outcome: Outcome) -> usize {
        self.cells
            .iter()
            .filter(|c| c.region == region && c.method == method && c.outcome == outcome)
            .count()
    }
}

/// Run every region (`quick`: the reduced CI grid); `progress` is called with each region's
/// name before it runs.
pub fn run(quick: bool, progress: &mut dyn FnMut(&str)) -> Result<StressMap, StressError> {
    let regions = regions::regions(quick);
    let mut cells = Vec::new();
    for r in &regions {
        progress(r.name);
        cells.extend(run_region(r)?);
    }
    Ok(StressMap { regions, cells })
}

/// Every method at every point of one region.
pub fn run_region(region: &Region) -> Result<Vec<Cell>, StressError> {
    let model = region.source.build(&[])?;
    let sym = Linearizer::new(&model).symbolic();
    let kernel = match region.source {
        Source::Builtin(name) => generated::kernels(name)
            .into_iter()
            .find(|k| k.label == "generated f64"),
        Source::File(..) => None,
    };
    let mut cells = Vec::new();
    for (i, &v) in region.values.iter().enumerate() {
        let at = [(region.param, v)];
        let values = model
            .scope
            .values_with(&at)
            .map_err(|e| StressError::Model(region.name.into(), e.to_string()))?;
        let mut results: Vec<(&str, MethodResult)> = vec![
            (
                "numeric",
                guarded(|| elimination(&model, &at, Method::Numeric)),
            ),
            (
                "robust",
                guarded(|| elimination(&model, &at, Method::Robust)),
            ),
            ("symbolic", guarded(|| symbolic(&sym, &values))),
        ];
        if let Some(k) = kernel {
            results.push((
                "generated f64",
                guarded(|| match (k.a)(&values) {
                    Some(a) => from_a(a, Vec::new()),
                    None => MethodResult::Failed("outside the validity region".into()),
                }),
            ));
        }
        let (reference, label) = match reference(region, v) {
            Ok(e) => (Some(e), region.reference.describe()),
            Err(why) => cross_check(&results, why),
        };
        for (method, result) in &results {
            let (outcome, error) = classify(result, reference.as_deref());
            let note = match result {
                MethodResult::Failed(e) => e.clone(),
                MethodResult::Done { doubts, .. } => doubts.first().cloned().unwrap_or_default(),
            };
            cells.push(Cell {
                region: region.name.into(),
                point: i,
                value: v,
                method: method.to_string(),
                outcome,
                error,
                reference: label.clone(),
                note: shorten(&note),
            });
        }
    }
    Ok(cells)
}

/// A method's result, a panic turned into a failure that says so (a bug to fix, but the
/// map goes on).
fn guarded(f: impl FnOnce() -> MethodResult) -> MethodResult {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))
        .unwrap_or_else(|_| MethodResult::Failed("panicked".into()))
}

fn shorten(s: &str) -> String {
    let one_line = s.replace(['\n', ','], " ");
    match one_line.char_indices().nth(120) {
        Some((k, _)) => format!("{}…", &one_line[..k]),
        None => one_line,
    }
}

/// The numeric or robust path at the point, eigenvalues and verdict as `eom analyze` gives
/// them (the robust path's structural zeros deflated).
fn elimination(model: &Model<Expr>, at: &[(&str, f64)], method: Method) -> MethodResult {
    let lin = match Linearizer::new(model).at(at).method(method).run() {
        Ok(l) => l,
        Err(e) => return MethodResult::Failed(e.to_string()),
    };
    let zeros = if method == Method::Robust {
        lin.structural_zeros.len()
    } else {
        0
    };
    modes(&lin.state_space, zeros, doubts(&lin.warnings), true)
}

/// The symbolic reduction formed at the region's nominal point, evaluated at the point.
fn symbolic(
    sym: &Result<SymbolicStateSpace, eom_model::ModelError>,
    values: &[f64],
) -> MethodResult {
    let sym = match sym {
        Ok(s) => s,
        Err(e) => return MethodResult::Failed(e.to_string()),
    };
    match sym.compiled().evaluate(values) {
        Ok(ss) => modes(&ss, 0, doubts(&sym.reduction.report.warnings), true),
        Err(e) => MethodResult::Failed(e.to_string()),
    }
}

/// The warnings that make a result doubtful ([`eom_model::Warning::doubts_result`]: a
/// constraint row removed as redundant by a numerical rank decision, a geometry only nearly in
/// equilibrium), as their messages.
fn doubts(warnings: &[eom_model::Warning]) -> Vec<String> {
    warnings
        .iter()
        .filter(|w| w.doubts_result())
        .map(ToString::to_string)
        .collect()
}

/// Eigenvalues and verdict of a bare state matrix (the generated code's A: its user gets A
/// only, so no accuracy estimate counts as a report).
fn from_a(a: DMatrix<f64>, doubts: Vec<String>) -> MethodResult {
    let n = a.nrows();
    match StateSpace::new(
        a,
        DMatrix::zeros(n, 0),
        DMatrix::zeros(0, n),
        DMatrix::zeros(0, 0),
    ) {
        Ok(ss) => modes(&ss, 0, doubts, false),
        Err(e) => MethodResult::Failed(e.to_string()),
    }
}

/// Eigenvalues and verdict as `eom analyze` gives them; with `accuracy_reported`, a mode
/// whose estimated relative accuracy (`Mode::accuracy`, which `eom analyze` warns about) is
/// worse than the tolerance is a doubt.
fn modes(
    ss: &StateSpace<f64>,
    structural_zeros: usize,
    mut doubts: Vec<String>,
    accuracy_reported: bool,
) -> MethodResult {
    let opts = ModeOptions {
        structural_zeros,
        shapes: false,
        ..ModeOptions::default()
    };
    match Modes::compute_with(ss, &opts) {
        Ok(m) => {
            if accuracy_reported {
                doubts.extend(
                    m.modes
                        .iter()
                        .filter(|x| x.accuracy > classify::TOLERANCE)
                        .map(|x| {
                            format!(
                                "eigenvalue {:.6e}: relative accuracy about {:.1e}",
                                x.eigenvalue, x.accuracy
                            )
                        }),
                );
            }
            MethodResult::Done {
                eigenvalues: m.eigenvalues(),
                verdict: verdict_of(m.modes.iter().map(|x| x.stability)),
                doubts,
            }
        }
        Err(e) => MethodResult::Failed(e.to_string()),
    }
}

/// The reference eigenvalues at the point, or why there are none.
fn reference(region: &Region, v: f64) -> Result<Vec<Complex64>, String> {
    match &region.reference {
        ReferenceKind::DoubleDouble => double_double(&region.source, region.param, v),
        ReferenceKind::DoubleDoubleOf(s) => double_double(s, region.param, v),
        ReferenceKind::Closed(f) => Ok(f(v)),
    }
}

/// The double-double reference of the model with the point as its nominal.
fn double_double(source: &Source, param: &str, v: f64) -> Result<Vec<Complex64>, String> {
    let model = source.build(&[(param, v)]).map_err(|e| e.to_string())?;
    let sym = Linearizer::new(&model)
        .symbolic()
        .map_err(|e| e.to_string())?;
    let r = ReferenceModel::new(&sym)
        .at(&model.scope.nominal_values())
        .map_err(|e| e.to_string())?;
    Ok(r.eigenvalues)
}

/// Without a reference: the numeric and robust paths (independent reductions) as one where
/// they agree to the tolerance, else none.
fn cross_check(results: &[(&str, MethodResult)], why: String) -> (Option<Vec<Complex64>>, String) {
    let eig = |name: &str| {
        results.iter().find_map(|(m, r)| match r {
            MethodResult::Done { eigenvalues, .. } if *m == name => Some(eigenvalues.clone()),
            _ => None,
        })
    };
    if let (Some(a), Some(b)) = (eig("numeric"), eig("robust"))
        && classify::eigenvalue_error(&a, &b) <= classify::TOLERANCE
    {
        return (
            Some(b),
            "cross-check: numeric and robust agree (no reference)".into(),
        );
    }
    (None, format!("none ({})", shorten(&why)))
}
