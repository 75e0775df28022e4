//! Work-precision benchmark of every way eom offers to get a model's eigenvalues: the
//! numeric elimination (`Method::Numeric`), the robust SVD path (`Method::Robust`), the
//! symbolic reduction evaluated by the tape interpreter (`CompiledStateSpace`), and the
//! generated code (`f64`, `f32`, and the egg-simplified `f64` variant where `build.rs` makes
//! one). For each: the median time to get the state matrix A at a point, the largest
//! entry-wise relative error of A and the largest relative error of its eigenvalues against a
//! double-double reference of the same model at the same point ([`reference`]), over random
//! points within ±`spread` of nominal; for the bicycle also the largest absolute error of the
//! four lean/steer eigenvalues against the benchmark's (Meijaard et al. 2007, Table 2 speeds,
//! 17-digit values of `tests/data/bicycle_eigs_126_speeds.csv`).
//!
//! For the models of at most 16 states, two more rows compare the eigensolvers alone on the
//! reference's own A (the double-double A rounded to `f64`, so the A error is 0): the stack
//! kernel of `eom_num::small_eigen` that `eigenvalues` takes up to 16 states, and faer's QR
//! algorithm (`eigenvalues_faer_in`), each against the double-double eigenvalues, with the
//! time per eigensolve in place of the time per A.
//!
//! `eom bench accuracy -o DIR` writes the CSV, the Markdown table and the SVG chart
//! ([`output`], [`chart`]).

mod bench_models;
pub mod chart;
pub mod entries;
pub mod generated;
pub mod output;
pub mod published;
pub mod reference;
pub mod timing;

use eom_model::{EvalWorkspace, Linearizer, Method, ModelError, SymbolicStateSpace};
use eom_num::modes::{ModeOptions, Modes};
use eom_num::{NumError, StateSpace};
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::{Rng, SeedableRng, rngs::StdRng};
use reference::{Reference, ReferenceModel};
use std::time::Duration;

pub use bench_models::{MODELS, SIMPLIFIED, STABILITY};

/// What can go wrong.
#[derive(Debug, thiserror::Error)]
pub enum WorkPrecisionError {
    /// Building, reducing or evaluating a model.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Numeric analysis (eigenvalues).
    #[error(transparent)]
    Num(#[from] NumError),
    /// The double-double evaluation.
    #[error(transparent)]
    Sym(#[from] eom_sym::SymError),
    /// A built-in model that does not exist.
    #[error("model {0}: {1}")]
    Catalogue(String, String),
    /// The reference could not be formed.
    #[error("reference: {0}")]
    Reference(String),
    /// Writing the outputs.
    #[error("{0}: {1}")]
    Io(String, std::io::Error),
    /// Drawing the chart.
    #[error("chart: {0}")]
    Chart(String),
}

/// Options of [`run_model`].
#[derive(Clone, Debug)]
pub struct Options {
    /// Random parameter points per model (models with more than 40 states use at most 4:
    /// their reference refines every eigenvalue in double-double).
    pub points: usize,
    /// Each parameter is drawn uniformly within nominal × (1 ± spread) (a zero nominal within
    /// ±spread).
    pub spread: f64,
    /// Random seed.
    pub seed: u64,
    /// Minimum time spent timing each method.
    pub min_time: Duration,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            points: 64,
            spread: 0.2,
            seed: 20261121,
            min_time: Duration::from_millis(200),
        }
    }
}

/// One method on one model.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Model name.
    pub model: String,
    /// Method label.
    pub method: String,
    /// Median time to get A at one point, ns.
    pub time_ns: f64,
    /// Largest entry-wise relative error of A over the points (`|ΔA_ij| / |A_ij|`, an entry
    /// whose reference is 0 against the largest entry of A); `None` for a method whose A is in
    /// another basis (robust).
    pub matrix_err: Option<f64>,
    /// Largest eigenvalue error over the points: `|Δλ| / |λ|`, a reference eigenvalue 0 (a
    /// structural zero) against the spectral radius.
    pub eig_err: f64,
    /// The same over the non-zero reference eigenvalues only (the structural zeros left out).
    pub nonzero_eig_err: f64,
    /// Points at which the method reported a failure (outside its validity region).
    pub failures: usize,
    /// Points compared.
    pub points: usize,
    /// Largest absolute error against the published eigenvalues, where they exist.
    pub published_err: Option<f64>,
}

/// A method's A and eigenvalues at a point, `None` for a reported failure of the method.
pub type Evaluated = Option<(DMatrix<f64>, Vec<Complex64>)>;

/// A method's [`Evaluated`] as a function of the parameter values.
pub type EigenvaluesAt<'a> = dyn Fn(&[f64]) -> Result<Evaluated, WorkPrecisionError> + 'a;

/// Median ns per call of a method over the points, timed for at least the duration.
type Timer<'a> = Box<dyn Fn(&[Vec<f64>], Duration) -> f64 + 'a>;

/// A way to get A at a point, with the eigenvalues a user of it sees.
struct Way<'a> {
    label: String,
    eval: Box<EigenvaluesAt<'a>>,
    time: Timer<'a>,
    /// A in the basis of the symbolic reduction (its error against the reference means
    /// something).
    same_basis: bool,
}

/// Random points within ±`spread` of nominal.
pub fn points(nominal: &[f64], n: usize, spread: f64, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            nominal
                .iter()
                .map(|&x| {
                    let f = rng.random_range(1.0 - spread..1.0 + spread);
                    if x == 0.0 { f - 1.0 } else { x * f }
                })
                .collect()
        })
        .collect()
}

/// Eigenvalues as a user of the elimination paths and generated code gets them.
fn eig(a: &DMatrix<f64>) -> Result<Vec<Complex64>, WorkPrecisionError> {
    Ok(eom_num::modes::eigenvalues(a)?)
}

/// The linearization paths at a point (`None` for a reported failure of the method).
fn linearize(
    model: &eom_model::Model,
    names: &[String],
    values: &[f64],
    method: Method,
) -> Option<eom_model::Linearization> {
    let at: Vec<(&str, f64)> = names
        .iter()
        .map(String::as_str)
        .zip(values.iter().copied())
        .collect();
    Linearizer::new(model).at(&at).method(method).run().ok()
}

/// The eigenvalues a user of the robust path sees: the structural zeros found on the
/// elimination path's matrix deflated (as `eom analyze` does).
fn robust_eigenvalues(
    lin: &eom_model::Linearization,
) -> Result<Vec<Complex64>, WorkPrecisionError> {
    let opts = ModeOptions {
        structural_zeros: lin.structural_zeros.len(),
        ..ModeOptions::default()
    };
    let modes = Modes::compute_with(&lin.state_space, &opts)?;
    Ok(modes.modes.iter().map(|m| m.eigenvalue).collect())
}

/// The timer of a method called once per point.
fn time_calls<'a>(f: impl Fn(&[f64]) + 'a) -> Timer<'a> {
    Box::new(move |pts: &[Vec<f64>], min: Duration| {
        timing::median_batch_ns(pts.len(), min, || {
            for p in pts {
                f(std::hint::black_box(p));
            }
        })
    })
}

fn ways<'a>(
    name: &str,
    model: &'a eom_model::Model,
    sym: &'a SymbolicStateSpace,
    names: &'a [String],
) -> Vec<Way<'a>> {
    let mut out = Vec::new();
    for (label, method) in [("numeric", Method::Numeric), ("robust", Method::Robust)] {
        out.push(Way {
            label: label.into(),
            eval: Box::new(move |p: &[f64]| {
                let Some(lin) = linearize(model, names, p, method) else {
                    return Ok(None);
                };
                let e = if method == Method::Robust {
                    robust_eigenvalues(&lin)?
                } else {
                    eig(&lin.state_space.a)?
                };
                Ok(Some((lin.state_space.a, e)))
            }),
            time: time_calls(move |p: &[f64]| {
                std::hint::black_box(linearize(model, names, p, method));
            }),
            same_basis: method == Method::Numeric,
        });
    }
    let compiled = sym.compiled();
    out.push(Way {
        label: "symbolic (tape)".into(),
        eval: Box::new(move |p: &[f64]| match compiled.evaluate(p) {
            Ok(ss) => {
                let e = eig(&ss.a)?;
                Ok(Some((ss.a, e)))
            }
            Err(_) => Ok(None),
        }),
        time: Box::new(move |pts: &[Vec<f64>], min: Duration| {
            let ws = std::cell::RefCell::new(EvalWorkspace::default());
            timing::median_batch_ns(pts.len(), min, || {
                for p in pts {
                    let r: Result<StateSpace<f64>, _> =
                        compiled.evaluate_with(std::hint::black_box(p), &mut ws.borrow_mut());
                    std::hint::black_box(r.ok());
                }
            })
        }),
        same_basis: true,
    });
    for k in generated::kernels(name) {
        out.push(Way {
            label: k.label.into(),
            eval: Box::new(move |p: &[f64]| match (k.a)(p) {
                Some(a) => {
                    let e = eig(&a)?;
                    Ok(Some((a, e)))
                }
                None => Ok(None),
            }),
            time: Box::new(move |pts: &[Vec<f64>], min: Duration| (k.time)(pts, min)),
            same_basis: true,
        });
    }
    out
}

/// Largest entry-wise relative error of `a` against `want` (an entry whose reference is 0
/// against the largest entry of `want`).
pub fn matrix_error(a: &DMatrix<f64>, want: &DMatrix<f64>) -> f64 {
    if a.shape() != want.shape() {
        return f64::INFINITY;
    }
    let scale = want
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    a.iter()
        .zip(want.iter())
        .map(|(x, y)| {
            let d = (x - y).abs();
            if d == 0.0 {
                0.0
            } else if *y == 0.0 {
                d / scale
            } else {
                d / y.abs()
            }
        })
        .fold(0.0, f64::max)
}

/// Largest eigenvalue error of `got` against the reference: `|Δλ| / |λ|`, against the
/// spectral radius where the reference eigenvalue is 0 (a structural zero); then the same over
/// the non-zero reference eigenvalues only.
pub fn eigenvalue_error(got: &[Complex64], want: &[Complex64]) -> (f64, f64) {
    if got.len() != want.len() {
        return (f64::INFINITY, f64::INFINITY);
    }
    let radius = want
        .iter()
        .fold(0.0f64, |m, z| m.max(z.norm()))
        .max(f64::MIN_POSITIVE);
    crate::compare::match_eigenvalues(got, want).iter().fold(
        (0.0f64, 0.0f64),
        |(all, nonzero), (g, e)| {
            let d = (g - e).norm();
            if d == 0.0 {
                (all, nonzero)
            } else if e.norm() == 0.0 {
                (all.max(d / radius), nonzero)
            } else {
                (all.max(d / e.norm()), nonzero.max(d / e.norm()))
            }
        },
    )
}

/// Every method on one built-in model: time per A and errors against the double-double
/// reference over random points near nominal (and against the published eigenvalues for the
/// bicycle).
pub fn run_model(name: &str, opts: &Options) -> Result<Vec<Row>, WorkPrecisionError> {
    let model = models::build(name, &[])
        .map_err(|e| WorkPrecisionError::Catalogue(name.into(), e.to_string()))?;
    let sym = Linearizer::new(&model).symbolic()?;
    let names = model.scope.names();
    let nominal = model.scope.nominal_values();
    let n_points = if sym.compiled().states() > 40 {
        opts.points.min(4)
    } else {
        opts.points
    };
    let pts = points(&nominal, n_points, opts.spread, opts.seed);
    let refm = ReferenceModel::new(&sym);
    let refs: Vec<Option<Reference>> = pts.iter().map(|p| refm.at(p).ok()).collect();
    let published = if name == "bicycle" {
        Some(published::Published::new(&model, &refm)?)
    } else {
        None
    };
    let mut rows = Vec::new();
    for way in ways(name, &model, &sym, &names) {
        let (mut m_err, mut e_err, mut nz_err) = (0.0f64, 0.0f64, 0.0f64);
        let (mut failures, mut done) = (0, 0);
        for (p, r) in pts.iter().zip(&refs) {
            let Some(r) = r else { continue };
            match (way.eval)(p)? {
                None => failures += 1,
                Some((a, e)) => {
                    m_err = m_err.max(matrix_error(&a, &r.a));
                    let (all, nonzero) = eigenvalue_error(&e, &r.eigenvalues);
                    e_err = e_err.max(all);
                    nz_err = nz_err.max(nonzero);
                    done += 1;
                }
            }
        }
        let time_ns = (way.time)(&pts, opts.min_time);
        let published_err = match &published {
            Some(p) => Some(p.error(&|v| (way.eval)(v))?),
            None => None,
        };
        rows.push(Row {
            model: name.into(),
            method: way.label,
            time_ns,
            matrix_err: way.same_basis.then_some(m_err),
            eig_err: e_err,
            nonzero_eig_err: nz_err,
            failures,
            points: done,
            published_err,
        });
    }
    if sym.compiled().states() <= eom_num::small_eigen::MAX_N {
        rows.extend(solver_rows(name, &refs, &refm, published.as_ref(), opts)?);
    }
    if let Some(p) = &published {
        rows.push(p.reference_row(name));
    }
    Ok(rows)
}

/// The label of the small-matrix kernel's row.
pub const SMALL_KERNEL: &str = "eigenvalues: small kernel";
/// The label of faer's eigensolver's row.
pub const FAER_SOLVER: &str = "eigenvalues: faer";

/// The eigensolvers alone on the reference's A (see the module documentation).
fn solver_rows(
    name: &str,
    refs: &[Option<Reference>],
    refm: &ReferenceModel,
    published: Option<&published::Published>,
    opts: &Options,
) -> Result<Vec<Row>, WorkPrecisionError> {
    type Solver = fn(&DMatrix<f64>) -> Result<Vec<Complex64>, NumError>;
    fn small(a: &DMatrix<f64>) -> Result<Vec<Complex64>, NumError> {
        let mut out = vec![Complex64::new(0.0, 0.0); a.nrows()];
        eom_num::small_eigen::eigenvalues_small(a.as_slice(), a.nrows(), &mut out)?;
        Ok(out)
    }
    fn faer(a: &DMatrix<f64>) -> Result<Vec<Complex64>, NumError> {
        let mut out = vec![Complex64::new(0.0, 0.0); a.nrows()];
        let mut ws = eom_num::modes::EigenvaluesWorkspace::new(a.nrows());
        eom_num::modes::eigenvalues_faer_in(a, &mut ws, &mut out)?;
        Ok(out)
    }
    let solvers: [(&str, Solver); 2] = [(SMALL_KERNEL, small), (FAER_SOLVER, faer)];
    let mats: Vec<&DMatrix<f64>> = refs.iter().flatten().map(|r| &r.a).collect();
    let mut rows = Vec::new();
    for (label, solve) in solvers {
        let (mut e_err, mut nz_err, mut done) = (0.0f64, 0.0f64, 0);
        for r in refs.iter().flatten() {
            let (all, nonzero) = eigenvalue_error(&solve(&r.a)?, &r.eigenvalues);
            e_err = e_err.max(all);
            nz_err = nz_err.max(nonzero);
            done += 1;
        }
        // The eigensolve alone: the workspace of faer's path is part of its cost (the
        // allocating call, as `eigenvalues` makes it).
        let time_ns = timing::median_batch_ns(mats.len(), opts.min_time, || {
            for a in &mats {
                std::hint::black_box(solve(std::hint::black_box(a)).ok());
            }
        });
        let published_err = match published {
            Some(p) => Some(p.error(&|v| {
                let r = refm.at(v)?;
                Ok(Some((r.a.clone(), solve(&r.a)?)))
            })?),
            None => None,
        };
        rows.push(Row {
            model: name.into(),
            method: label.into(),
            time_ns,
            matrix_err: Some(0.0),
            eig_err: e_err,
            nonzero_eig_err: nz_err,
            failures: 0,
            points: done,
            published_err,
        });
    }
    Ok(rows)
}

/// The fastest way to A whose eigenvalue error is within `tol`, per model (the eigensolver
/// rows, timed per eigensolve, are not ways to A).
pub fn fastest_within(rows: &[Row], tol: f64) -> Vec<&Row> {
    let mut out: Vec<&Row> = Vec::new();
    for r in rows.iter().filter(|r| {
        r.eig_err <= tol
            && r.points > 0
            && r.time_ns.is_finite()
            && r.method != SMALL_KERNEL
            && r.method != FAER_SOLVER
    }) {
        match out.iter_mut().find(|b| b.model == r.model) {
            Some(b) if r.time_ns < b.time_ns => *b = r,
            Some(_) => {}
            None => out.push(r),
        }
    }
    out
}
