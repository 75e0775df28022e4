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

    /// Entries of A, B, C, D per point.
    fn point_len(&self) -> usize {
        self.shapes.iter().map(|(r, c)| r * c).sum()
    }
}

/// A, B, C, D (row-major, in this order) at every point (`points`: rows of `n_params`
/// values). A point outside the validity region of the symbolic reduction is an error naming
/// the first such point.
pub fn evaluate(c: &Compiled, points: &[f64], n_params: usize) -> PyResult<Vec<f64>> {
    let len = c.point_len();
    let count = points.len() / n_params.max(1);
    let mut out = vec![0.0; count * len];
    let failure = out
        .par_chunks_mut(len.max(1))
        .zip(points.par_chunks(n_params.max(1)))
        .enumerate()
        .map_init(EvalWorkspace::default, |ws, (i, (o, p))| {
            match c.css.evaluate_with(p, ws) {
                Ok(ss) => {
                    let mut k = 0;
                    for m in [&ss.a, &ss.b, &ss.c, &ss.d] {
                        for r in 0..m.nrows() {
                            for col in 0..m.ncols() {
                                o[k] = m[(r, col)];
                                k += 1;
                            }
                        }
                    }
                    None
                }
                Err(e) => Some((i, e)),
            }
        })
        .flatten()
        .min_by_key(|(i, _)| *i);
    match failure {
        None => Ok(out),
        Some((i, e)) => Err(eom_error(format!(
            "point {i} ({}): {e}; the symbolic reduction (pivots chosen at the defaults) does \
             not hold there: linearize that point with method=\"numeric\" or \"robust\"",
            describe(c, &points[i * n_params..(i + 1) * n_params])
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

/// The stability of every point.
pub struct StabilityOut {
    /// Largest real part of the eigenvalues, structural zeros excluded.
    pub max_real: Vec<f64>,
    /// 1 stable, -1 unstable, 0 neither (largest real part exactly 0, or no eigenvalue left).
    pub verdict: Vec<i8>,
    /// 1 where the symbolic reduction broke down and the robust path gave A.
    pub fallback: Vec<u8>,
}

/// The stability of every point: A from the compiled tape (the robust path where the symbolic
/// reduction breaks down, as `eom sweep` does), its eigenvalues by the small-matrix kernel with
/// the structural zeros found at the defaults (as `eom bench throughput`).
pub fn stability(
    c: &Compiled,
    source: &Source,
    names: &[String],
    points: &[f64],
) -> PyResult<StabilityOut> {
    let np = names.len().max(1);
    let count = points.len() / np;
    let results: Vec<Result<(f64, i8, u8), String>> = points
        .par_chunks(np)
        .map_init(
            || {
                (
                    EvalWorkspace::default(),
                    vec![Complex64::new(0.0, 0.0); MAX_N],
                )
            },
            |(ws, eig), p| point_stability(c, source, names, p, ws, eig),
        )
        .collect();
    let mut out = StabilityOut {
        max_real: Vec::with_capacity(count),
        verdict: Vec::with_capacity(count),
        fallback: Vec::with_capacity(count),
    };
    for (i, r) in results.into_iter().enumerate() {
        let (re, v, f) = r.map_err(|e| {
            eom_error(format!(
                "point {i} ({}): {e}",
                describe(c, &points[i * np..(i + 1) * np])
            ))
        })?;
        out.max_real.push(re);
        out.verdict.push(v);
        out.fallback.push(f);
    }
    Ok(out)
}

fn point_stability(
    c: &Compiled,
    source: &Source,
    names: &[String],
    p: &[f64],
    ws: &mut EvalWorkspace,
    eig: &mut [Complex64],
) -> Result<(f64, i8, u8), String> {
    let (a, fallback) = match c.css.evaluate_a(p, ws) {
        Ok(a) => (a, false),
        Err(ModelError::PivotBreakdown(_))
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
    let verdict = if rest.is_empty() {
        0
    } else if re < 0.0 {
        1
    } else if re > 0.0 {
        -1
    } else {
        0
    };
    Ok((re, verdict, u8::from(fallback)))
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
