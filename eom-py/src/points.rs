//! Many parameter points at once: the model's compiled tape ([`CompiledStateSpace`], the one
//! `eom sweep` evaluates) on all cores with rayon, one [`EvalWorkspace`] per thread. Each
//! point's result depends on that point alone, so it is the same whatever the chunking or the
//! number of threads (what makes a distributed sweep equal a local one bit for bit).

use crate::errors::eom_error;
use crate::source::Source;
use eom_model::compiled::{CompiledStateSpace, EvalWorkspace};
use eom_model::{Linearizer, Method, Model, ModelError, Warning};
use eom_num::SignalNames;
use eom_num::deflate::structural_zero_states;
use eom_num::small_eigen::{KnownZeros, MAX_N, eigenvalues_small, eigenvalues_small_known};
use eom_sym::SymError;
use nalgebra::DMatrix;
use num_complex::Complex64;
use pyo3::PyResult;
use rayon::prelude::*;
use std::sync::{Arc, Mutex};

/// A model's symbolic reduction, compiled, with what every point needs.
pub struct Compiled {
    css: CompiledStateSpace,
    shapes: [(usize, usize); 4],
    warnings: Vec<Warning>,
    /// The structural zeros of A at the defaults (models of at most [`MAX_N`] states).
    known: Option<KnownZeros>,
    /// Their number (on the elimination path's A at the defaults).
    zeros: usize,
}

impl Compiled {
    /// Reduces `model` symbolically (pivots at its nominal values) and compiles it.
    pub fn of(model: &Model) -> Result<Compiled, String> {
        let sym = Linearizer::new(model)
            .symbolic()
            .map_err(|e| e.to_string())?;
        let css = sym.compiled().clone();
        let nominal = css
            .evaluate(&model.scope.nominal_values())
            .map_err(|e| e.to_string())?;
        let n = nominal.a.nrows();
        let zeros = structural_zero_states(&nominal.a, &nominal.names.states).len();
        let known = (n <= MAX_N)
            .then(|| KnownZeros::of(nominal.a.as_slice(), n).ok())
            .flatten();
        let shape = |m: &DMatrix<f64>| (m.nrows(), m.ncols());
        Ok(Compiled {
            shapes: [
                shape(&nominal.a),
                shape(&nominal.b),
                shape(&nominal.c),
                shape(&nominal.d),
            ],
            warnings: sym.reduction.report.warnings.clone(),
            css,
            known,
            zeros,
        })
    }

    /// Shapes of A, B, C, D.
    pub fn shapes(&self) -> &[(usize, usize); 4] {
        &self.shapes
    }

    /// Signal names.
    pub fn names(&self) -> SignalNames {
        self.css
            .evaluate(&vec![1.0; self.css.param_names().len()])
            .map(|s| s.names)
            .unwrap_or_default()
    }

    /// Entries of A, B, C, D per point.
    pub fn abcd_len(&self) -> usize {
        self.css.abcd_len()
    }

    /// Warnings of the symbolic reduction.
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// The linearization at `values` (all parameters in model order), as
    /// `Linearizer::method(Method::Symbolic)` gives it.
    pub fn linearize(&self, values: &[f64]) -> Result<eom_model::Linearization, ModelError> {
        let ss = self.css.evaluate(values)?;
        Ok(eom_model::Linearization {
            structural_zeros: structural_zero_states(&ss.a, &ss.names.states),
            state_space: ss,
            method: Method::Symbolic,
            report: None,
            robust: None,
            warnings: self.warnings.clone(),
        })
    }
}

/// A, B, C, D (row-major, in this order) at every point (`points`: rows of `n_params`
/// values) written straight into `out` (`abcd_len` entries per point), one slice per point,
/// on all cores. A point outside the validity region of the symbolic reduction is an error
/// naming the first such point (`out` is then left partly written).
pub fn evaluate_into(
    c: &Compiled,
    points: &[f64],
    n_params: usize,
    out: &mut [f64],
) -> PyResult<()> {
    let len = c.css.abcd_len();
    let np = n_params.max(1);
    let count = points.len() / np;
    if out.len() != count * len || points.len() != count * np {
        return Err(eom_error(format!(
            "evaluate: {} values for {count} points of {len} entries (points of {np} values: {})",
            out.len(),
            points.len()
        )));
    }
    // Chunks of points per task: rayon's splitting down to single points costs more than
    // the evaluation of a small model.
    const CHUNK: usize = 256;
    let failure = out
        .par_chunks_mut((len * CHUNK).max(1))
        .zip(points.par_chunks(np * CHUNK))
        .enumerate()
        .map_init(EvalWorkspace::default, |ws, (k, (o, p))| {
            o.chunks_mut(len.max(1))
                .zip(p.chunks(np))
                .enumerate()
                .find_map(|(i, (o, p))| {
                    c.css
                        .evaluate_into(p, ws, o)
                        .err()
                        .map(|e| (k * CHUNK + i, e))
                })
        })
        .flatten()
        .min_by_key(|(i, _)| *i);
    match failure {
        None => Ok(()),
        Some((i, e)) => Err(eom_error(format!(
            "point {i} ({}): {e}; the symbolic reduction (pivots chosen at the defaults) does \
             not hold there: linearize that point with method=\"numeric\" or \"robust\"",
            describe(c, &points[i * np..(i + 1) * np])
        ))),
    }
}

/// `name=value` of a point's parameters.
fn describe(c: &Compiled, p: &[f64]) -> String {
    c.css
        .param_names()
        .iter()
        .zip(p)
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Where the stability of every point goes (one entry per point each).
pub struct StabilityOut<'a> {
    /// Largest real part of the eigenvalues, structural zeros excluded.
    pub max_real: &'a mut [f64],
    /// 1 stable, -1 unstable, 0 marginal (a real part within its eigenvalue's error estimate,
    /// the rule of `eom analyze`; or no eigenvalue left).
    pub verdict: &'a mut [i8],
    /// Where the symbolic reduction broke down and the robust path gave A.
    pub fallback: &'a mut [bool],
}

/// The stability of every point, written into `out`: A from the compiled tape (the robust
/// path where the symbolic reduction breaks down, as `eom sweep` does), its eigenvalues by the
/// small-matrix kernel with the structural zeros found at the defaults (as `eom bench
/// throughput`). An error names the first point that fails.
pub fn stability_into(
    c: &Compiled,
    source: &Source,
    names: &[String],
    points: &[f64],
    out: StabilityOut<'_>,
) -> PyResult<()> {
    let np = names.len().max(1);
    let count = points.len() / np;
    if [out.max_real.len(), out.verdict.len(), out.fallback.len()] != [count; 3] {
        return Err(eom_error(format!(
            "stability: output arrays of {}, {} and {} entries for {count} points",
            out.max_real.len(),
            out.verdict.len(),
            out.fallback.len()
        )));
    }
    // Points per task (see `evaluate_into`).
    const CHUNK: usize = 64;
    let failure = out
        .max_real
        .par_chunks_mut(CHUNK)
        .zip(out.verdict.par_chunks_mut(CHUNK))
        .zip(out.fallback.par_chunks_mut(CHUNK))
        .zip(points.par_chunks(np * CHUNK))
        .enumerate()
        .map_init(
            || {
                (
                    EvalWorkspace::default(),
                    vec![Complex64::new(0.0, 0.0); MAX_N],
                )
            },
            |(ws, eig), (k, (((re, v), f), p))| {
                for (i, p) in p.chunks(np).enumerate() {
                    match point_stability(c, source, names, p, ws, eig) {
                        Ok((x, verdict, fallback)) => {
                            re[i] = x;
                            v[i] = verdict;
                            f[i] = fallback;
                        }
                        Err(e) => return Some((k * CHUNK + i, e)),
                    }
                }
                None
            },
        )
        .flatten()
        .min_by_key(|(i, _)| *i);
    match failure {
        None => Ok(()),
        Some((i, e)) => Err(eom_error(format!(
            "point {i} ({}): {e}",
            describe(c, &points[i * np..(i + 1) * np])
        ))),
    }
}

/// `f` on a pool of `threads` threads (rayon's global pool, all cores, when None): a Dask
/// worker sharing its machine with other workers takes its share of the cores, not all of
/// them. Pools are kept per size (building one starts its threads).
pub fn with_threads<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> R {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    let Some(n) = threads.filter(|&n| n != rayon::current_num_threads()) else {
        return f();
    };
    let pool = {
        let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
        match pools.iter().find(|(k, _)| *k == n) {
            Some((_, p)) => Some(p.clone()),
            None => match rayon::ThreadPoolBuilder::new().num_threads(n).build() {
                Ok(p) => {
                    let p = Arc::new(p);
                    pools.push((n, p.clone()));
                    Some(p)
                }
                // No threads to be had: the global pool.
                Err(_) => None,
            },
        }
    };
    match pool {
        Some(p) => p.install(f),
        None => f(),
    }
}

fn point_stability(
    c: &Compiled,
    source: &Source,
    names: &[String],
    p: &[f64],
    ws: &mut EvalWorkspace,
    eig: &mut [Complex64],
) -> Result<(f64, i8, bool), String> {
    let (a, fallback) = match c.css.evaluate_a(p, ws) {
        Ok(a) => (a, false),
        Err(ModelError::PivotBreakdown { .. })
        | Err(ModelError::Sym(SymError::EvalNonFinite { .. })) => {
            (robust_a(source, names, p)?, true)
        }
        Err(e) => return Err(e.to_string()),
    };
    let n = a.nrows();
    let mut values: Vec<Complex64> = if n <= MAX_N {
        let out = &mut eig[..n];
        let found = match (&c.known, fallback) {
            (Some(k), false) => eigenvalues_small_known(a.as_slice(), n, k, out),
            _ => eigenvalues_small(a.as_slice(), n, out),
        };
        found.map_err(|e| e.to_string())?;
        out.to_vec()
    } else {
        eom_num::modes::eigenvalues(&a).map_err(|e| e.to_string())?
    };
    // Structural zeros out: the exact zeros, and as many more of least modulus as the
    // structure has zeros that this path left in rounding (the robust path's basis).
    let exact = values.iter().filter(|z| z.norm() == 0.0).count();
    values.retain(|z| z.norm() != 0.0);
    values.sort_by(|x, y| x.norm().total_cmp(&y.norm()));
    let skip = c.zeros.saturating_sub(exact).min(values.len());
    let rest = &values[skip..];
    let re = rest.iter().fold(f64::NEG_INFINITY, |m, z| m.max(z.re));
    let bound = eom_num::sweep::screen_bound(n, a.norm());
    let verdict = if rest.is_empty() {
        0
    } else if rest.iter().any(|z| z.re.abs() <= bound) {
        verdict_by_estimates(&a, c.zeros)?
    } else if re < 0.0 {
        1
    } else {
        -1
    };
    Ok((re, verdict, fallback))
}

/// The verdict of `eom analyze` and `eom sweep` (`eom_num::modes::stability_of`): each
/// eigenvalue judged with its error estimate, marginal (0) when a real part is within it,
/// the `zeros` structural zeros set aside. Only where a real part is near enough to zero for
/// the estimate to matter (`eom_num::sweep::screen_bound`): the estimates need eigenvectors.
fn verdict_by_estimates(a: &DMatrix<f64>, zeros: usize) -> Result<i8, String> {
    use eom_num::modes::{Stability, eigenvalues_with_errors, stability_of};
    let mut with = eigenvalues_with_errors(a).map_err(|e| e.to_string())?;
    let exact = with.iter().filter(|(z, _)| z.norm() == 0.0).count();
    with.retain(|(z, _)| z.norm() != 0.0);
    with.sort_by(|x, y| x.0.norm().total_cmp(&y.0.norm()));
    let skip = zeros.saturating_sub(exact).min(with.len());
    let verdicts = with[skip..].iter().map(|(z, e)| stability_of(z.re, *e));
    Ok(verdicts.fold(1, |v, s| match s {
        Stability::Unstable => -1,
        Stability::Marginal if v == 1 => 0,
        _ => v,
    }))
}

/// A at a point by the robust (SVD) path.
fn robust_a(source: &Source, names: &[String], p: &[f64]) -> Result<DMatrix<f64>, String> {
    let ov: Vec<(&str, f64)> = names
        .iter()
        .map(|n| n.as_str())
        .zip(p.iter().copied())
        .collect();
    let m = source.build(&ov).map_err(|e| e.to_string())?;
    let lin = Linearizer::new(&m)
        .method(Method::Robust)
        .run()
        .map_err(|e| e.to_string())?;
    Ok(lin.state_space.a)
}
