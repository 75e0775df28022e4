//! Parameter sweeps of a state matrix `A(x)`: eigenvalue branches followed continuously,
//! neutral (rigid-body) branches, stability boundaries located to a tolerance, and the
//! stable intervals of the parameter.
//!
//! # What a sweep does
//!
//! 1. Evaluates `A(x)` and its eigenvalues at every sweep value, in parallel (rayon), with
//!    the allocation-free kernel [`crate::modes::eigenvalues_in`] (faer with `Par::Seq`, one
//!    workspace per thread).
//! 2. **Follows the branches**: the eigenvalues at point `k` are assigned to the branches by
//!    an optimal assignment (Hungarian algorithm) on the squared distance to a linear
//!    prediction from points `k−1` and `k−2`, so branches that cross in real part keep their
//!    identity (sorting would swap them). Conjugate pairs stay pairs: when the assignment
//!    separates the two halves of a pair that is still complex, they are re-paired.
//! 3. **Neutral branches**: a branch with `|λ| ≤ neutral_rtol · ‖A(x)‖_F` at every point is
//!    an identically-zero eigenvalue (a rigid-body or integrator mode, e.g. a vehicle's
//!    lateral position and heading). It is reported but excluded from stability judgements.
//!    Zero rows and columns of `A` are split off first (exact zeros), and the eigenvalues
//!    of least modulus are pinned to the neutral branches before matching the rest: a real
//!    root passing through zero would otherwise tie with a neutral zero in the matching.
//!    The real part of every other branch is taken together with the real parts of the
//!    neutral branches (their sum is ≈ 0, accurately, as a trace): where a real root crosses
//!    zero next to a neutral zero, the two form a defective double eigenvalue whose members are
//!    only known to √ε, while their sum stays accurate to ε.
//! 4. **Stability per point**: a point is stable when every non-neutral branch has
//!    `Re λ < −band`, unstable when one has `Re λ > band`, marginal otherwise, with
//!    `band = marginal_rtol · ‖A(x)‖_F` (default `marginal_rtol = 100 · n · ε`): real parts
//!    inside the band are rounding noise and carry no sign.
//! 5. **Boundaries**: every sign change of the real part of a tracked branch between two
//!    points outside the band brackets a boundary, located by Brent's method (re-evaluating
//!    `A` at trial values, re-identifying the branch by an assignment against the branch
//!    values interpolated between the bracket ends) to `tolerance` in the parameter
//!    (default 1e-10, plus 4ε|x|). A conjugate pair gives one boundary, reported with the
//!    eigenvalue of non-negative imaginary part. Two crossings of one branch inside one grid
//!    cell are not seen: refine the grid if that matters.
//! 6. **Stable intervals**: the boundaries cut the sweep range into segments; a segment is
//!    stable when it has no unstable point and at least one stable one (a segment with no
//!    grid point inside is judged at its midpoint). Adjacent stable segments are merged.
//!    Endpoints are boundaries or the ends of the sweep.

use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

use crate::error::NumError;
use crate::minreal::{cser, sort_complex};
use crate::modes::{EigenvaluesWorkspace, eigenvalues_in};

/// Errors of [`Sweep::run`]: the caller's model error passed through with the parameter
/// value at which it happened, or a numeric error at a parameter value.
#[derive(Debug, thiserror::Error)]
pub enum SweepError<E> {
    /// The model function failed.
    #[error("the model failed at {param} = {value}: {source}")]
    Model {
        /// Name of the swept parameter.
        param: String,
        /// Parameter value at which it failed.
        value: f64,
        /// The caller's error.
        source: E,
    },
    /// A numeric step failed (bad shape or entries of A, no convergence).
    #[error("at {param} = {value}: {source}")]
    Numeric {
        /// Name of the swept parameter.
        param: String,
        /// Parameter value at which it failed.
        value: f64,
        /// What went wrong.
        source: NumError,
    },
    /// The sweep itself is set up wrongly (no values, non-monotone values, bad tolerance).
    #[error("invalid sweep: {0}")]
    Setup(NumError),
}

/// Stability class of a sweep point (neutral branches excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PointStability {
    /// Every non-neutral branch has `Re λ < −band`.
    Stable,
    /// No branch has `Re λ > band`, but one is inside the band (or every branch is neutral).
    Marginal,
    /// Some branch has `Re λ > band`.
    Unstable,
}

/// One evaluated sweep point.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepPoint {
    /// Parameter value.
    pub value: f64,
    /// Eigenvalues in branch order (entry `j` belongs to branch `j` at every point).
    #[serde(serialize_with = "cser::many")]
    pub eigenvalues: Vec<Complex64>,
    /// Largest real part of the non-neutral branches (`None` if all are neutral), each taken
    /// together with the real parts of the neutral branches (see the module documentation).
    pub max_real: Option<f64>,
    /// Stability class.
    pub stability: PointStability,
    /// `‖A(x)‖_F`, the scale of the thresholds at this point.
    pub norm: f64,
}

/// A tracked eigenvalue branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchInfo {
    /// Index into [`SweepPoint::eigenvalues`].
    pub index: usize,
    /// Identically zero along the sweep (rigid-body / integrator mode); excluded from
    /// stability judgements.
    pub neutral: bool,
}

/// Direction of a stability boundary as the parameter increases.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Crossing {
    /// The real part goes from negative to positive.
    Destabilizing,
    /// The real part goes from positive to negative.
    Stabilizing,
}

/// A located stability boundary.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Boundary {
    /// Parameter value of the crossing.
    pub value: f64,
    /// The crossing eigenvalue there (its real part, taken with the neutral branches', is ~0).
    #[serde(serialize_with = "cser::one")]
    pub eigenvalue: Complex64,
    /// The branch that crosses.
    pub branch: usize,
    /// Direction as the parameter increases.
    pub crossing: Crossing,
    /// The final bracket `[lo, hi]` (root inside, `hi − lo ≤ tolerance + 4ε|x|` when
    /// converged).
    pub bracket: [f64; 2],
    /// Evaluations of `A` used.
    pub evaluations: usize,
    /// Whether the bracket reached the tolerance within the iteration limit.
    pub converged: bool,
}

/// A stable parameter interval `[lo, hi]` (serialized as a two-element array).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StableInterval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Serialize for StableInterval {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        [self.lo, self.hi].serialize(s)
    }
}

/// Result of [`Sweep::run`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepResult {
    /// Name of the swept parameter.
    pub param: String,
    /// The evaluated points, in the order given.
    pub points: Vec<SweepPoint>,
    /// The tracked branches.
    pub branches: Vec<BranchInfo>,
    /// Stable intervals, increasing.
    pub stable_intervals: Vec<StableInterval>,
    /// Located boundaries, by increasing value.
    pub boundaries: Vec<Boundary>,
}

/// A parameter sweep (builder). See the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    values: Vec<f64>,
    param: String,
    tolerance: f64,
    neutral_rtol: f64,
    marginal_rtol: Option<f64>,
    locate: bool,
    max_evaluations: usize,
}

impl Sweep {
    /// A sweep over the given values (strictly increasing or strictly decreasing).
    pub fn new(values: Vec<f64>) -> Self {
        Sweep {
            values,
            param: "param".into(),
            tolerance: 1e-10,
            neutral_rtol: 1e-6,
            marginal_rtol: None,
            locate: true,
            max_evaluations: 200,
        }
    }

    /// `count` equally spaced values from `start` to `stop` (both included; `count = 1` gives
    /// `start`).
    pub fn linspace(start: f64, stop: f64, count: usize) -> Self {
        let values = match count {
            0 => Vec::new(),
            1 => vec![start],
            _ => (0..count)
                .map(|i| {
                    if i + 1 == count {
                        stop
                    } else {
                        start + (stop - start) * (i as f64) / ((count - 1) as f64)
                    }
                })
                .collect(),
        };
        Sweep::new(values)
    }

    /// Name of the parameter (used in errors and in the result; default `"param"`).
    pub fn with_param_name(mut self, name: impl Into<String>) -> Self {
        self.param = name.into();
        self
    }

    /// Absolute tolerance in the parameter for locating boundaries (default 1e-10).
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Relative threshold for neutral branches: `|λ| ≤ rtol · ‖A‖_F` at every point (default
    /// 1e-6, which covers the √ε spread of a computed double zero eigenvalue).
    pub fn with_neutral_rtol(mut self, rtol: f64) -> Self {
        self.neutral_rtol = rtol;
        self
    }

    /// Relative half-width of the band around `Re λ = 0` inside which a real part has no sign
    /// (default `100 · n · ε`).
    pub fn with_marginal_rtol(mut self, rtol: f64) -> Self {
        self.marginal_rtol = Some(rtol);
        self
    }

    /// Whether to locate boundaries (default `true`); without, only the grid is evaluated and
    /// stable intervals end at the grid points next to the sign changes.
    pub fn with_boundaries(mut self, locate: bool) -> Self {
        self.locate = locate;
        self
    }

    /// Maximum evaluations of `A` per boundary (default 200).
    pub fn with_max_evaluations(mut self, max: usize) -> Self {
        self.max_evaluations = max;
        self
    }

    /// The sweep values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    fn validate(&self) -> Result<(), NumError> {
        let v = &self.values;
        if v.is_empty() {
            return Err(NumError::InvalidOption(format!(
                "sweep of {} has no values",
                self.param
            )));
        }
        if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(NumError::InvalidOption(format!(
                "sweep value {i} of {} is {x}",
                self.param
            )));
        }
        if v.len() > 1 {
            let inc = v[1] > v[0];
            for (i, w) in v.windows(2).enumerate() {
                if (inc && w[1] <= w[0]) || (!inc && w[1] >= w[0]) {
                    return Err(NumError::InvalidOption(format!(
                        "sweep values of {} must be strictly monotone (values {i} and {}: {} and {})",
                        self.param,
                        i + 1,
                        w[0],
                        w[1]
                    )));
                }
            }
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(NumError::InvalidOption(format!(
                "sweep tolerance = {} (must be finite and > 0)",
                self.tolerance
            )));
        }
        for (r, what) in [
            (Some(self.neutral_rtol), "neutral_rtol"),
            (self.marginal_rtol, "marginal_rtol"),
        ] {
            if let Some(r) = r
                && !(r.is_finite() && r >= 0.0)
            {
                return Err(NumError::InvalidOption(format!(
                    "sweep {what} = {r} (must be finite and ≥ 0)"
                )));
            }
        }
        if self.max_evaluations == 0 {
            return Err(NumError::InvalidOption(
                "sweep max_evaluations must be ≥ 1".into(),
            ));
        }
        Ok(())
    }

    /// Runs the sweep. `f(x)` returns the state matrix `A` at parameter value `x`; it is called
    /// from several threads.
    ///
    /// Errors: [`SweepError::Model`] with the parameter value when `f` fails (the first failing
    /// value in sweep order when several do), [`SweepError::Numeric`] when `A` is not square,
    /// changes size, has NaN/∞ entries or its eigenvalues do not converge,
    /// [`SweepError::Setup`] for an invalid sweep.
    pub fn run<F, E>(&self, f: F) -> Result<SweepResult, SweepError<E>>
    where
        F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
        E: Send,
    {
        self.validate().map_err(SweepError::Setup)?;
        let ctx = Ctx {
            f: &f,
            param: &self.param,
        };
        // 1. Evaluate every point in parallel; report the first failure in sweep order.
        let evals: Vec<Result<Eval, SweepError<E>>> = self
            .values
            .par_iter()
            .map_init(|| None, |ws, &x| ctx.eval(x, ws, None))
            .collect();
        let mut pts = Vec::with_capacity(evals.len());
        for e in evals {
            pts.push(e?);
        }
        let n = pts[0].eig.len();
        for (p, &x) in pts.iter().zip(&self.values) {
            if p.eig.len() != n {
                return Err(ctx.numeric(
                    x,
                    NumError::Dimension(format!(
                        "A is {0}×{0} here but {n}×{n} at {1} = {2}",
                        p.eig.len(),
                        self.param,
                        self.values[0]
                    )),
                ));
            }
        }
        let marginal_rtol = self
            .marginal_rtol
            .unwrap_or(100.0 * (n.max(1) as f64) * f64::EPSILON);

        // 2. Follow the branches.
        let xs = &self.values;
        // The eigenvalues ≈ 0 at every grid point are the neutral zeros: pinned to the first
        // branches (see `assign_pinned`).
        let z = pts
            .iter()
            .map(|p| {
                p.eig
                    .iter()
                    .filter(|l| l.norm() <= self.neutral_rtol * p.norm)
                    .count()
            })
            .min()
            .unwrap_or(0);
        let mut tracked: Vec<Vec<Complex64>> = Vec::with_capacity(pts.len());
        let mut first = assign_pinned(&pts[0].eig, &pts[0].eig, &pts[0].eig, z);
        sort_complex(&mut first[z..]);
        tracked.push(first);
        for k in 1..pts.len() {
            let prev = &tracked[k - 1];
            let pred: Vec<Complex64> = if k >= 2 {
                let t = (xs[k] - xs[k - 1]) / (xs[k - 1] - xs[k - 2]);
                prev.iter()
                    .zip(&tracked[k - 2])
                    .map(|(&p1, &p2)| p1 + (p1 - p2) * t)
                    .collect()
            } else {
                prev.clone()
            };
            let cur = assign_pinned(&pred, &pts[k].eig, prev, z);
            tracked.push(cur);
        }

        // 3. Neutral branches.
        let neutral: Vec<bool> = (0..n)
            .map(|j| {
                tracked
                    .iter()
                    .zip(&pts)
                    .all(|(t, p)| t[j].norm() <= self.neutral_rtol * p.norm)
            })
            .collect();

        // 4. Stability per point. Real parts are taken together with the neutral branches'
        // (whose sum is ≈ 0 and exact as a trace): where a real root crosses zero next to a
        // neutral zero the two form a defective double eigenvalue, each known only to √ε,
        // but their sum stays accurate.
        let neutral_idx: Vec<usize> = (0..n).filter(|&j| neutral[j]).collect();
        let band = |k: usize| marginal_rtol * pts[k].norm;
        let sign = |k: usize, j: usize| -> i8 {
            let re = effective_re(&tracked[k], j, &neutral_idx);
            if re > band(k) {
                1
            } else if re < -band(k) {
                -1
            } else {
                0
            }
        };
        let classify = |eig: &[Complex64], norm: f64| -> (Option<f64>, PointStability) {
            let b = marginal_rtol * norm;
            let mut max_re: Option<f64> = None;
            for j in (0..eig.len()).filter(|&j| !neutral[j]) {
                let re = effective_re(eig, j, &neutral_idx);
                max_re = Some(max_re.map_or(re, |m: f64| m.max(re)));
            }
            let st = match max_re {
                None => PointStability::Marginal,
                Some(m) if m > b => PointStability::Unstable,
                Some(m) if m < -b => PointStability::Stable,
                Some(_) => PointStability::Marginal,
            };
            (max_re, st)
        };
        let points: Vec<SweepPoint> = (0..pts.len())
            .map(|k| {
                let (max_real, stability) = classify(&tracked[k], pts[k].norm);
                SweepPoint {
                    value: xs[k],
                    eigenvalues: tracked[k].clone(),
                    max_real,
                    stability,
                    norm: pts[k].norm,
                }
            })
            .collect();

        // 5. Brackets of sign changes, one per conjugate pair.
        let increasing = xs.len() < 2 || xs[1] > xs[0];
        let mut brackets = Vec::new();
        for j in (0..n).filter(|&j| !neutral[j]) {
            let mut last: Option<(usize, i8)> = None;
            for k in 0..pts.len() {
                let s = sign(k, j);
                if s == 0 {
                    continue;
                }
                if let Some((kp, sp)) = last
                    && sp != s
                    && !is_lower_half_of_pair(&tracked, j, kp, k)
                {
                    brackets.push((j, kp, k));
                }
                last = Some((k, s));
            }
        }

        let mut boundaries: Vec<Boundary> = if self.locate {
            let located: Vec<Result<Boundary, SweepError<E>>> = brackets
                .par_iter()
                .map(|&(j, ka, kb)| {
                    let ends = ((xs[ka], tracked[ka].clone()), (xs[kb], tracked[kb].clone()));
                    let mut b = ctx.locate(
                        j,
                        &neutral_idx,
                        ends,
                        (self.tolerance, self.max_evaluations),
                        z,
                    )?;
                    let rising = sign(kb, j) > 0;
                    b.crossing = if rising == increasing {
                        Crossing::Destabilizing
                    } else {
                        Crossing::Stabilizing
                    };
                    Ok(b)
                })
                .collect();
            let mut out = Vec::with_capacity(located.len());
            for b in located {
                out.push(b?);
            }
            out
        } else {
            Vec::new()
        };
        boundaries.sort_by(|a, b| a.value.total_cmp(&b.value));
        dedupe_pairs(&mut boundaries, self.tolerance);

        // 6. Stable intervals.
        let (lo_all, hi_all) = if increasing {
            (xs[0], xs[xs.len() - 1])
        } else {
            (xs[xs.len() - 1], xs[0])
        };
        let mut cuts = vec![lo_all];
        if self.locate {
            cuts.extend(boundaries.iter().map(|b| b.value));
        } else {
            // Without located boundaries, cut at the grid cells where a sign changes: the
            // stable side ends at its last grid point.
            for &(_, ka, kb) in &brackets {
                cuts.push(xs[ka].min(xs[kb]));
                cuts.push(xs[ka].max(xs[kb]));
            }
            cuts.sort_by(f64::total_cmp);
        }
        cuts.push(hi_all);
        let mut stable_intervals: Vec<StableInterval> = Vec::new();
        for w in cuts.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            if hi < lo {
                continue;
            }
            // Grid points of the segment: strictly inside located boundaries (a grid point
            // within 2·tolerance of a boundary sits on it), inclusive at the sweep ends and,
            // without located boundaries, at the grid cuts.
            let margin = 2.0 * self.tolerance;
            let inside: Vec<usize> = (0..pts.len())
                .filter(|&k| {
                    let x = xs[k];
                    let above = if lo == lo_all || !self.locate {
                        x >= lo
                    } else {
                        x > lo + margin
                    };
                    let below = if hi == hi_all || !self.locate {
                        x <= hi
                    } else {
                        x < hi - margin
                    };
                    above && below
                })
                .collect();
            let stable = if inside.is_empty() {
                if hi - lo <= 2.0 * self.tolerance || !self.locate {
                    false
                } else {
                    let mid = 0.5 * (lo + hi);
                    let (eig, norm) = ctx.eval_tracked(mid, xs, &tracked, z)?;
                    classify(&eig, norm).1 == PointStability::Stable
                }
            } else {
                let any_unstable = inside
                    .iter()
                    .any(|&k| points[k].stability == PointStability::Unstable);
                let any_stable = inside
                    .iter()
                    .any(|&k| points[k].stability == PointStability::Stable);
                !any_unstable && any_stable
            };
            if stable {
                match stable_intervals.last_mut() {
                    Some(last) if last.hi == lo => last.hi = hi,
                    _ => stable_intervals.push(StableInterval { lo, hi }),
                }
            }
        }

        Ok(SweepResult {
            param: self.param.clone(),
            points,
            branches: neutral
                .iter()
                .enumerate()
                .map(|(index, &neutral)| BranchInfo { index, neutral })
                .collect(),
            stable_intervals,
            boundaries,
        })
    }
}

struct Eval {
    /// The eigenvalues, the exact zeros of deflated zero rows and columns first.
    eig: Vec<Complex64>,
    norm: f64,
}

/// Removes zero columns of `a` (with their rows) and zero rows (with their columns) until
/// none is left: each is an exact zero eigenvalue (`A e_j = 0`: with `j` first, `A` is block
/// triangular `[0 r; 0 A']`; a zero row likewise with `j` last). Returns
/// the remaining matrix and how many were removed. States that nothing depends on (the
/// bicycle's yaw and lateral position) are such neutral zeros; computed by the eigensolver
/// they form a defective pair known only to √ε, which blurs a nearby real root (the
/// capsize mode near its crossing) and can swap branches with it.
fn deflate_zero_lines(a: &DMatrix<f64>) -> (Option<DMatrix<f64>>, usize) {
    let mut keep: Vec<usize> = (0..a.nrows()).collect();
    loop {
        let zero = keep.iter().position(|&j| {
            keep.iter().all(|&i| a[(i, j)] == 0.0) || keep.iter().all(|&i| a[(j, i)] == 0.0)
        });
        match zero {
            Some(p) => {
                keep.remove(p);
            }
            None => break,
        }
    }
    let removed = a.nrows() - keep.len();
    if removed == 0 {
        return (None, 0);
    }
    let m = keep.len();
    (
        Some(DMatrix::from_fn(m, m, |i, j| a[(keep[i], keep[j])])),
        removed,
    )
}

/// [`assign`] with the first `z` branches (the neutral zeros) pinned to the `z` eigenvalues
/// of least modulus. Matching alone cannot tell a real root passing through zero from a
/// neutral zero: near the crossing both are ≈ 0 and the costs tie (the bicycle's capsize
/// root at 6 m/s and its heading mode swapped on a 0.25 m/s grid). Pinned, the neutral
/// branch is always the eigenvalue nearest zero; where the two are closer than rounding,
/// which is which does not matter, as real parts are taken together with the neutral ones.
fn assign_pinned(
    pred: &[Complex64],
    eig: &[Complex64],
    prev: &[Complex64],
    z: usize,
) -> Vec<Complex64> {
    if z == 0 {
        return assign(pred, eig, prev);
    }
    let mut order: Vec<usize> = (0..eig.len()).collect();
    order.sort_by(|&a, &b| eig[a].norm().total_cmp(&eig[b].norm()));
    let mut pinned = vec![false; eig.len()];
    order[..z].iter().for_each(|&k| pinned[k] = true);
    let mut out: Vec<Complex64> = order[..z].iter().map(|&k| eig[k]).collect();
    let rest: Vec<Complex64> = (0..eig.len())
        .filter(|&k| !pinned[k])
        .map(|k| eig[k])
        .collect();
    out.extend(assign(&pred[z..], &rest, &prev[z..]));
    out
}

struct Ctx<'a, F> {
    f: &'a F,
    param: &'a str,
}

impl<F, E> Ctx<'_, F>
where
    F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
{
    fn numeric(&self, value: f64, source: NumError) -> SweepError<E> {
        SweepError::Numeric {
            param: self.param.to_string(),
            value,
            source,
        }
    }

    /// Evaluates A(x) and its eigenvalues; `expect` is the size A must have.
    fn eval(
        &self,
        x: f64,
        ws: &mut Option<EigenvaluesWorkspace>,
        expect: Option<usize>,
    ) -> Result<Eval, SweepError<E>> {
        let a = (self.f)(x).map_err(|source| SweepError::Model {
            param: self.param.to_string(),
            value: x,
            source,
        })?;
        if a.nrows() != a.ncols() {
            return Err(self.numeric(
                x,
                NumError::Dimension(format!("A is {}×{}, must be square", a.nrows(), a.ncols())),
            ));
        }
        let n = a.nrows();
        if let Some(e) = expect
            && e != n
        {
            return Err(self.numeric(
                x,
                NumError::Dimension(format!("A is {n}×{n} here but {e}×{e} on the sweep grid")),
            ));
        }
        let (reduced, zeros) = deflate_zero_lines(&a);
        let core = reduced.as_ref().unwrap_or(&a);
        let m = core.nrows();
        let mut eig = vec![Complex64::new(0.0, 0.0); n];
        if m > 0 {
            if ws.as_ref().is_none_or(|w| w.dim() != m) {
                *ws = Some(EigenvaluesWorkspace::new(m));
            }
            if let Some(w) = ws.as_mut() {
                eigenvalues_in(core, w, &mut eig[zeros..]).map_err(|e| self.numeric(x, e))?;
            }
        }
        Ok(Eval {
            eig,
            norm: a.norm(),
        })
    }

    /// Eigenvalues at an off-grid value, assigned to the branches by interpolating the
    /// tracked values of the neighbouring grid points.
    fn eval_tracked(
        &self,
        x: f64,
        xs: &[f64],
        tracked: &[Vec<Complex64>],
        z: usize,
    ) -> Result<(Vec<Complex64>, f64), SweepError<E>> {
        let n = tracked[0].len();
        let e = self.eval(x, &mut None, Some(n))?;
        // Neighbouring grid points (xs is monotone).
        let k = xs
            .windows(2)
            .position(|w| (w[0] - x) * (w[1] - x) <= 0.0)
            .unwrap_or(0);
        let pred = if xs.len() < 2 {
            tracked[0].clone()
        } else {
            interpolate(xs[k], &tracked[k], xs[k + 1], &tracked[k + 1], x)
        };
        Ok((assign_pinned(&pred, &e.eig, &pred, z), e.norm))
    }

    /// Brent's method on g(x) = Re λ_j(x) inside a bracket with a sign change.
    fn locate(
        &self,
        j: usize,
        neutral: &[usize],
        ends: ((f64, Vec<Complex64>), (f64, Vec<Complex64>)),
        (tol, max_evaluations): (f64, usize),
        z: usize,
    ) -> Result<Boundary, SweepError<E>> {
        let n = ends.0.1.len();
        let mut ws = Some(EigenvaluesWorkspace::new(n));
        let ((mut xa, mut va), (mut xb, mut vb)) = ends;
        let (mut fa, mut fb) = (effective_re(&va, j, neutral), effective_re(&vb, j, neutral));
        let (mut xc, mut vc, mut fc) = (xa, va.clone(), fa);
        let mut d = xb - xa;
        let mut e = d;
        let mut evaluations = 0;
        let mut converged = false;
        loop {
            if (fb > 0.0) == (fc > 0.0) {
                xc = xa;
                vc = va.clone();
                fc = fa;
                d = xb - xa;
                e = d;
            }
            if fc.abs() < fb.abs() {
                // Keep the best estimate in b.
                xa = xb;
                va = vb.clone();
                fa = fb;
                xb = xc;
                vb = vc.clone();
                fb = fc;
                xc = xa;
                vc = va.clone();
                fc = fa;
            }
            let tol1 = 2.0 * f64::EPSILON * xb.abs() + 0.5 * tol;
            let xm = 0.5 * (xc - xb);
            if xm.abs() <= tol1 || fb == 0.0 {
                converged = true;
                break;
            }
            if evaluations >= max_evaluations {
                break;
            }
            if e.abs() >= tol1 && fa.abs() > fb.abs() {
                // Interpolation step: secant or inverse quadratic.
                let s = fb / fa;
                let (mut p, mut q);
                if xa == xc {
                    p = 2.0 * xm * s;
                    q = 1.0 - s;
                } else {
                    let qq = fa / fc;
                    let r = fb / fc;
                    p = s * (2.0 * xm * qq * (qq - r) - (xb - xa) * (r - 1.0));
                    q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
                }
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                    e = d;
                    d = p / q;
                } else {
                    d = xm;
                    e = d;
                }
            } else {
                d = xm;
                e = d;
            }
            xa = xb;
            va = vb.clone();
            fa = fb;
            xb += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
            // Identify the branches at the trial value against the values interpolated
            // between the two ends of the current bracket.
            let pred = interpolate(xa, &va, xc, &vc, xb);
            let ev = self.eval(xb, &mut ws, Some(n))?;
            evaluations += 1;
            vb = assign_pinned(&pred, &ev.eig, &pred, z);
            fb = effective_re(&vb, j, neutral);
        }
        Ok(Boundary {
            value: xb,
            eigenvalue: vb[j] + Complex64::new(fb - vb[j].re, 0.0),
            branch: j,
            crossing: Crossing::Destabilizing,
            bracket: [xb.min(xc), xb.max(xc)],
            evaluations,
            converged,
        })
    }
}

/// Real part of branch `j` plus those of the neutral branches (see step 4 of `run`).
fn effective_re(values: &[Complex64], j: usize, neutral: &[usize]) -> f64 {
    values[j].re
        + neutral
            .iter()
            .filter(|&&k| k != j)
            .map(|&k| values[k].re)
            .sum::<f64>()
}

fn interpolate(x0: f64, v0: &[Complex64], x1: f64, v1: &[Complex64], x: f64) -> Vec<Complex64> {
    let t = if x1 == x0 { 0.0 } else { (x - x0) / (x1 - x0) };
    v0.iter().zip(v1).map(|(&a, &b)| a + (b - a) * t).collect()
}

/// Whether branch `j` is the lower (negative imaginary part) half of a conjugate pair at both
/// grid points `ka` and `kb`: its partner then brackets the same boundary.
fn is_lower_half_of_pair(tracked: &[Vec<Complex64>], j: usize, ka: usize, kb: usize) -> bool {
    let (za, zb) = (tracked[ka][j], tracked[kb][j]);
    if za.im >= 0.0 || zb.im >= 0.0 {
        return false;
    }
    (0..tracked[ka].len())
        .any(|i| i != j && tracked[ka][i] == za.conj() && tracked[kb][i] == zb.conj())
}

/// Removes the second of two boundaries at the same value whose eigenvalues are conjugate
/// (a pair tracked as two branches that both bracketed it), keeping Im ≥ 0.
fn dedupe_pairs(b: &mut Vec<Boundary>, tol: f64) {
    let mut i = 0;
    while i + 1 < b.len() {
        let (x, y) = (&b[i], &b[i + 1]);
        let scale = x.eigenvalue.norm().max(y.eigenvalue.norm()).max(1e-300);
        if (x.value - y.value).abs() <= 10.0 * tol
            && (x.eigenvalue - y.eigenvalue.conj()).norm() <= 1e-6 * scale
            && x.eigenvalue.im != 0.0
        {
            let drop = if x.eigenvalue.im < 0.0 { i } else { i + 1 };
            b.remove(drop);
        } else {
            i += 1;
        }
    }
}

/// Assigns the eigenvalues `eig` to branches with predicted values `pred` (optimal assignment
/// on squared distance), then re-pairs conjugates: branches that were a conjugate pair in
/// `prev` and are complex now get a conjugate pair.
fn assign(pred: &[Complex64], eig: &[Complex64], prev: &[Complex64]) -> Vec<Complex64> {
    let n = pred.len();
    let mut cost = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            cost[i * n + j] = (pred[i] - eig[j]).norm_sqr();
        }
    }
    // Fast path: when every prediction's nearest eigenvalue is a different one, that
    // assignment reaches the lower bound Σ row minima and is optimal.
    let mut col: Vec<usize> = (0..n)
        .map(|i| {
            (0..n)
                .min_by(|&a, &b| cost[i * n + a].total_cmp(&cost[i * n + b]))
                .unwrap_or(0)
        })
        .collect();
    let mut taken = vec![false; n];
    let is_perm = col.iter().all(|&j| !std::mem::replace(&mut taken[j], true));
    if !is_perm {
        col = hungarian(&cost, n);
    }
    let mut cur: Vec<Complex64> = col.iter().map(|&j| eig[j]).collect();
    // Conjugate partners in `prev`, each lower half used once (repeated pairs are possible).
    let mut used = vec![false; n];
    let mut pairs = Vec::new();
    for i in 0..n {
        if prev[i].im > 0.0
            && let Some(k) = (0..n).find(|&k| !used[k] && k != i && prev[k] == prev[i].conj())
        {
            used[k] = true;
            pairs.push((i, k));
        }
    }
    let mut locked = vec![false; n];
    for (i, partner) in pairs {
        if cur[i].im != 0.0 {
            let want = cur[i].conj();
            if cur[partner] != want
                && let Some(holder) =
                    (0..n).find(|&k| k != i && k != partner && !locked[k] && cur[k] == want)
            {
                cur.swap(partner, holder);
            }
        }
        locked[i] = true;
        locked[partner] = true;
    }
    cur
}

/// Minimum-cost perfect assignment of an `n × n` cost matrix (row-major) by the Hungarian
/// method with potentials (Kuhn 1955, Munkres 1957), O(n³). Returns the column of each row.
fn hungarian(cost: &[f64], n: usize) -> Vec<usize> {
    // 1-based internally; index 0 is a virtual column.
    let mut u = vec![0.0f64; n + 1];
    let mut v = vec![0.0f64; n + 1];
    let mut owner = vec![0usize; n + 1];
    let mut way = vec![0usize; n + 1];
    let mut minv = vec![0.0f64; n + 1];
    let mut used = vec![false; n + 1];
    for row in 1..=n {
        owner[0] = row;
        let mut j0 = 0;
        minv.iter_mut().for_each(|m| *m = f64::INFINITY);
        used.iter_mut().for_each(|u| *u = false);
        loop {
            used[j0] = true;
            let i0 = owner[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0;
            for j in 1..=n {
                if !used[j] {
                    let c = cost[(i0 - 1) * n + (j - 1)] - u[i0] - v[j];
                    if c < minv[j] {
                        minv[j] = c;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            if j1 == 0 {
                // Only possible with non-finite costs: take any free column.
                j1 = (1..=n).find(|&j| !used[j]).unwrap_or(0);
                if j1 == 0 {
                    break;
                }
                delta = 0.0;
            }
            for j in 0..=n {
                if used[j] {
                    u[owner[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if owner[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            owner[j0] = owner[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut col = vec![0usize; n];
    for j in 1..=n {
        if owner[j] > 0 {
            col[owner[j] - 1] = j - 1;
        }
    }
    col
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hungarian_finds_the_optimum_of_small_problems_by_brute_force() {
        // Compare with enumeration of all permutations for 5×5 pseudo-random costs.
        let n = 5;
        let mut seed = 12345u64;
        for _ in 0..50 {
            let cost: Vec<f64> = (0..n * n)
                .map(|_| {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    ((seed >> 11) as f64) / ((1u64 << 53) as f64)
                })
                .collect();
            let col = hungarian(&cost, n);
            let got: f64 = (0..n).map(|i| cost[i * n + col[i]]).sum();
            let mut perm: Vec<usize> = (0..n).collect();
            let mut best = f64::INFINITY;
            permute(&mut perm, 0, &mut |p| {
                let c: f64 = (0..n).map(|i| cost[i * n + p[i]]).sum();
                best = best.min(c);
            });
            assert!((got - best).abs() <= 1e-12, "{got} vs {best}");
            let mut seen = col.clone();
            seen.sort();
            assert_eq!(seen, (0..n).collect::<Vec<_>>());
        }
    }

    #[test]
    fn assign_falls_back_to_the_optimal_assignment() {
        // Both predictions are nearest to 0.05: greedy nearest is not a permutation.
        let c = |re: f64| Complex64::new(re, 0.0);
        let pred = [c(0.0), c(0.1)];
        let eig = [c(1.0), c(0.05)];
        let got = assign(&pred, &eig, &pred);
        assert_eq!(got, vec![c(0.05), c(1.0)]);
    }

    #[test]
    fn assign_keeps_conjugate_pairs_together() {
        // A double pair ±1i splitting into −0.1 ± 1i and 0.1 ± 1i: every assignment of
        // upper halves to upper halves costs the same, pairs must still come out as pairs.
        let z = Complex64::new(0.0, 1.0);
        let prev = [z, z.conj(), z, z.conj()];
        let (w, v) = (Complex64::new(0.1, 1.0), Complex64::new(-0.1, 1.0));
        for eig in [
            [w, w.conj(), v, v.conj()],
            [w, v.conj(), v, w.conj()],
            [v.conj(), w, w.conj(), v],
        ] {
            let got = assign(&prev, &eig, &prev);
            assert_eq!(got[1], got[0].conj(), "{got:?}");
            assert_eq!(got[3], got[2].conj(), "{got:?}");
            assert!(got[0].im > 0.0 && got[2].im > 0.0);
        }
    }

    fn permute(p: &mut Vec<usize>, k: usize, f: &mut impl FnMut(&[usize])) {
        if k == p.len() {
            f(p);
            return;
        }
        for i in k..p.len() {
            p.swap(k, i);
            permute(p, k + 1, f);
            p.swap(k, i);
        }
    }
}
