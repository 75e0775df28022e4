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
//! 3. **Neutral branches**: a branch with `|λ| ≤ neutral_rtol · ‖A(x)‖_F` (A balanced) at every point is
//!    an identically-zero eigenvalue (a rigid-body or integrator mode, e.g. a vehicle's
//!    lateral position and heading). It is reported but excluded from stability judgements.
//!    Zero rows and columns of `A` are split off first (exact zeros), and the eigenvalues
//!    of least modulus are pinned to the neutral branches before matching the rest: a real
//!    root passing through zero would otherwise tie with a neutral zero in the matching.
//!    The real part of every other branch is taken together with the real parts of the
//!    neutral branches (their sum is ≈ 0, accurately, as a trace): where a real root crosses
//!    zero next to a neutral zero, the two form a defective double eigenvalue whose members are
//!    only known to √ε, while their sum stays accurate to ε.
//! 4. **Stability per point**: each branch's verdict is [`crate::modes::stability_of`] with
//!    its eigenvalue's error estimate at that point ([`crate::modes::eigenvalues_with_errors`],
//!    the tolerance `eom analyze` judges the same eigenvalue by); only where that leaves the
//!    sign open is the real part taken with the neutral branches' and judged by the sum of
//!    their estimates: a real part within its tolerance is rounding noise and carries no
//!    sign. A point is stable when every non-neutral branch is, unstable when one is,
//!    marginal otherwise. The estimates need eigenvectors (up to 16 states by inverse
//!    iteration on the stack, about three times the cost of the eigenvalues; faer's beyond),
//!    so they are computed only at points where one could change a verdict:
//!    where some real part is within [`screen_bound`] (`tol_factor · n · ε · ‖A‖_F ·`
//!    [`SCREEN_CONDITION`]), which no estimate of an eigenvalue with condition number below
//!    [`SCREEN_CONDITION`] = 1e9 exceeds, or some nonzero eigenvalue is small enough to be
//!    neutral. Elsewhere the sign
//!    decides, as the estimate would, and the point states no tolerance.
//!    [`Sweep::with_marginal_rtol`] replaces the estimates by a band `rtol · ‖A(x)‖_F`.
//! 5. **Boundaries**: every sign change of the real part of a tracked branch between two
//!    points outside the band brackets a boundary, located by Brent's method (re-evaluating
//!    `A` at trial values, re-identifying the branch by an assignment against the branch
//!    values interpolated between the bracket ends) to `tolerance` in the parameter
//!    (default 1e-10, plus 4ε|x|). A conjugate pair gives one boundary, reported with the
//!    eigenvalue of non-negative imaginary part. Two crossings of one branch inside one grid
//!    cell are not seen: refine the grid if that matters.
//! 6. **Stable intervals**: the boundaries and the marginal grid points cut the sweep range
//!    into segments; a segment is stable when it has no unstable point and at least one
//!    stable one (a segment with no grid point inside is judged at its midpoint). Adjacent
//!    stable segments are merged, but not across a marginal point. Endpoints are boundaries,
//!    marginal points or the ends of the sweep.

use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

mod assign;
mod boundary;

use crate::error::{Bound, DimensionError, NumError, OptionError};
use crate::minreal::{cser, sort_complex};
use crate::modes::{EigenvaluesWorkspace, Stability, eigenvalues_in, eigenvalues_with_errors};
use assign::assign_pinned;

/// Errors of [`Sweep::run`]: the caller's model error passed through with the parameter
/// value at which it happened, or a numeric error at a parameter value.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError<E> {
    /// The model function failed.
    #[error("the model failed at {param} = {value:?}: {source}")]
    Model {
        /// Name of the swept parameter.
        param: String,
        /// Parameter value at which it failed.
        value: f64,
        /// The caller's error.
        source: E,
    },
    /// A numeric step failed (bad shape or entries of A, no convergence).
    #[error("at {param} = {value:?}: {source}")]
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

/// Stability class of a sweep point (neutral branches excluded); in JSON the words of the
/// modes' verdicts (`stable`, `marginal`, `unstable`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PointStability {
    /// Every non-neutral branch has `Re λ` below minus its error estimate.
    Stable,
    /// No branch is unstable, but the real part of one is within its error estimate (or every
    /// branch is neutral).
    Marginal,
    /// Some branch has `Re λ` above its error estimate.
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
    /// `‖D⁻¹A(x)D‖_F` with `D` the balancing of `A(x)` (Parlett & Reinsch), the scale of the
    /// thresholds at this point: the eigenvalues do not change under the similarity, and a
    /// stiff model's unbalanced norm (a beam's bending slopes of small inertia put 10¹⁰ in A)
    /// would call its every low-frequency eigenvalue zero.
    pub norm: f64,
    /// The tolerance of [`SweepPoint::max_real`]'s verdict: the error estimate of the branch
    /// of largest real part (with the neutral branches'), in 1/s. `None` if all are neutral,
    /// and where the estimates were not computed because no verdict at this point could
    /// depend on them: every real part beyond [`screen_bound`] (module documentation, step 4).
    pub tolerance: Option<f64>,
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

/// Direction of a stability boundary as the parameter increases (in JSON `destabilizing`,
/// `stabilizing`, as printed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
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

    /// Relative half-width of a band `rtol · ‖A(x)‖_F` around `Re λ = 0` inside which a real
    /// part has no sign, instead of each eigenvalue's error estimate (the default, the
    /// tolerance of `Modes`; the band needs no eigenvectors, but its verdicts can differ from
    /// those of the modes at the same point).
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
            return Err(NumError::InvalidOption(OptionError::EmptySweep {
                param: self.param.clone(),
            }));
        }
        if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(NumError::InvalidOption(OptionError::SweepValue {
                param: self.param.clone(),
                index: i,
                value: *x,
            }));
        }
        if v.len() > 1 {
            let inc = v[1] > v[0];
            for (i, w) in v.windows(2).enumerate() {
                if (inc && w[1] <= w[0]) || (!inc && w[1] >= w[0]) {
                    return Err(NumError::InvalidOption(OptionError::SweepNotMonotone {
                        param: self.param.clone(),
                        index: i,
                        values: [w[0], w[1]],
                    }));
                }
            }
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(NumError::InvalidOption(OptionError::Tolerance {
                option: "sweep tolerance",
                value: self.tolerance,
                must: Bound::FinitePositive,
            }));
        }
        for (r, what) in [
            (Some(self.neutral_rtol), "sweep neutral_rtol"),
            (self.marginal_rtol, "sweep marginal_rtol"),
        ] {
            if let Some(r) = r
                && !(r.is_finite() && r >= 0.0)
            {
                return Err(NumError::InvalidOption(OptionError::Tolerance {
                    option: what,
                    value: r,
                    must: Bound::FiniteNonNegative,
                }));
            }
        }
        if self.max_evaluations == 0 {
            return Err(NumError::InvalidOption(OptionError::SweepMaxEvaluations));
        }
        Ok(())
    }

    /// Runs the sweep (see the module documentation for the steps). `f(x)` returns the state
    /// matrix `A` at parameter value `x`; it is called from several threads.
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
            neutral_rtol: self.neutral_rtol,
        };
        let pts = self.evaluate_grid(&ctx)?;
        let (tracked, z) = self.follow_branches(&pts);
        let br = self.neutral_branches(pts, tracked, z);
        let points = br.points(&self.values);
        let brackets = br.brackets();
        let boundaries = self.locate_boundaries(&ctx, &br, &brackets)?;
        let stable_intervals = self.stable_intervals(&ctx, &br, &points, &brackets, &boundaries)?;
        Ok(SweepResult {
            param: self.param.clone(),
            points,
            branches: (br.neutral.iter().enumerate())
                .map(|(index, &neutral)| BranchInfo { index, neutral })
                .collect(),
            stable_intervals,
            boundaries,
        })
    }

    /// Step 1: `A` and its eigenvalues at every sweep value, in parallel; the first failure in
    /// sweep order is reported, and `A` must keep its size.
    fn evaluate_grid<F, E>(&self, ctx: &Ctx<'_, F>) -> Result<Vec<Eval>, SweepError<E>>
    where
        F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
        E: Send,
    {
        // The first point alone: its size predicts the memory of the whole sweep (matrices
        // while evaluating, the eigenvalues of every point, the tracked branches).
        let errors = self.marginal_rtol.is_none();
        let first = ctx.eval(self.values[0], &mut None, None, errors)?;
        let n = first.eig.len();
        crate::budget::check(
            &format!(
                "a sweep of {} values of a {n}-state model",
                self.values.len()
            ),
            crate::budget::product(&[self.values.len(), n.max(1), 16 * 4]).saturating_add(
                crate::budget::product(&[rayon::current_num_threads(), n, n, 8 * 3]),
            ),
        )
        .map_err(SweepError::Setup)?;
        let evals: Vec<Result<Eval, SweepError<E>>> = self.values[1..]
            .par_iter()
            .map_init(|| None, |ws, &x| ctx.eval(x, ws, None, errors))
            .collect();
        let mut pts = Vec::with_capacity(self.values.len());
        pts.push(first);
        for e in evals {
            pts.push(e?);
        }
        for (p, &x) in pts.iter().zip(&self.values) {
            if p.eig.len() != n {
                return Err(ctx.numeric(
                    x,
                    NumError::Dimension(DimensionError::SweepOrder {
                        states: p.eig.len(),
                        first: n,
                        param: self.param.clone(),
                        value: self.values[0],
                    }),
                ));
            }
        }
        Ok(pts)
    }

    /// Step 2: the eigenvalues of every point assigned to the branches (see
    /// [`assign_pinned`]), against a linear prediction from the two points before. Returns the
    /// branch values per point and the number `z` of neutral zeros pinned to the first
    /// branches.
    fn follow_branches(&self, pts: &[Eval]) -> (Vec<Vec<Complex64>>, usize) {
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
        (tracked, z)
    }

    /// Step 3: the branches that are ≈ 0 at every point.
    fn neutral_branches(&self, pts: Vec<Eval>, tracked: Vec<Vec<Complex64>>, z: usize) -> Branches {
        let n = pts[0].eig.len();
        let neutral: Vec<bool> = (0..n)
            .map(|j| {
                tracked
                    .iter()
                    .zip(&pts)
                    .all(|(t, p)| t[j].norm() <= self.neutral_rtol * p.norm)
            })
            .collect();
        let neutral_idx: Vec<usize> = (0..n).filter(|&j| neutral[j]).collect();
        let errors = self.marginal_rtol.is_none().then(|| {
            pts.iter()
                .zip(&tracked)
                .map(|(p, t)| p.errors.as_ref().map(|e| errors_of(t, &p.eig, e)))
                .collect::<Vec<_>>()
        });
        Branches {
            norms: pts.iter().map(|p| p.norm).collect(),
            tracked,
            z,
            neutral,
            neutral_idx,
            band: match errors {
                Some(e) => Band::Errors(e),
                None => Band::Relative(
                    self.marginal_rtol
                        .unwrap_or(100.0 * n as f64 * f64::EPSILON),
                ),
            },
        }
    }

    /// Step 6: the stable intervals between the boundaries (or, without located boundaries,
    /// between the grid cells where a sign changes).
    fn stable_intervals<F, E>(
        &self,
        ctx: &Ctx<'_, F>,
        br: &Branches,
        points: &[SweepPoint],
        brackets: &[(usize, usize, usize)],
        boundaries: &[Boundary],
    ) -> Result<Vec<StableInterval>, SweepError<E>>
    where
        F: Fn(f64) -> Result<DMatrix<f64>, E> + Sync,
    {
        let xs = &self.values;
        let increasing = xs.len() < 2 || xs[1] > xs[0];
        let (lo_all, hi_all) = if increasing {
            (xs[0], xs[xs.len() - 1])
        } else {
            (xs[xs.len() - 1], xs[0])
        };
        let mut cuts = vec![lo_all];
        // Marginal grid points are not stable: they end intervals as boundaries do (a real
        // part that touches zero there without crossing it).
        let marginal: Vec<f64> = points
            .iter()
            .filter(|p| p.stability == PointStability::Marginal)
            .map(|p| p.value)
            .collect();
        if self.locate {
            cuts.extend(boundaries.iter().map(|b| b.value));
            cuts.extend(marginal.iter().copied());
            cuts.sort_by(f64::total_cmp);
        } else {
            // Without located boundaries, cut at the grid cells where a sign changes: the
            // stable side ends at its last grid point.
            for &(_, ka, kb) in brackets {
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
            let inside: Vec<usize> = (0..points.len())
                .filter(|&k| {
                    let x = xs[k];
                    let is_marginal = marginal.contains(&x);
                    let above = if (lo == lo_all && !is_marginal) || !self.locate {
                        x >= lo
                    } else {
                        x > lo + margin
                    };
                    let below = if (hi == hi_all && !is_marginal) || !self.locate {
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
                    let errors = matches!(br.band, Band::Errors(_));
                    let (eig, norm, err) = ctx.eval_tracked(mid, xs, &br.tracked, br.z, errors)?;
                    br.classify(&eig, norm, err.as_deref()).1 == PointStability::Stable
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
                    Some(last) if last.hi == lo && !marginal.contains(&lo) => last.hi = hi,
                    _ => stable_intervals.push(StableInterval { lo, hi }),
                }
            }
        }
        Ok(stable_intervals)
    }
}

/// The tracked branches after steps 1–3: their values at every grid point, which are
/// neutral, and the thresholds of step 4.
struct Branches {
    /// `‖A(x_k)‖_F`.
    norms: Vec<f64>,
    /// Branch values per grid point.
    tracked: Vec<Vec<Complex64>>,
    /// The number of neutral zeros pinned to the first branches.
    z: usize,
    neutral: Vec<bool>,
    neutral_idx: Vec<usize>,
    band: Band,
}

/// Within what a real part has no sign (step 4).
enum Band {
    /// The error estimate of every branch at every grid point (the default); `None` at a
    /// point where every real part is beyond [`screen_bound`], so that no estimate changes a
    /// sign's verdict there (not computed).
    Errors(Vec<Option<Vec<f64>>>),
    /// `rtol · ‖A(x)‖_F` ([`Sweep::with_marginal_rtol`]).
    Relative(f64),
}

/// The error estimate of each of `values` (copies of entries of `eig`, in another order),
/// looked up by its bits; a value that occurs more than once gets the largest estimate.
fn errors_of(values: &[Complex64], eig: &[Complex64], errors: &[f64]) -> Vec<f64> {
    let key = |z: &Complex64| (z.re.to_bits(), z.im.to_bits());
    let mut by_value: std::collections::HashMap<(u64, u64), f64> =
        std::collections::HashMap::with_capacity(eig.len());
    for (z, &e) in eig.iter().zip(errors) {
        let slot = by_value.entry(key(z)).or_insert(0.0);
        *slot = slot.max(e);
    }
    values
        .iter()
        .map(|z| by_value.get(&key(z)).copied().unwrap_or(f64::INFINITY))
        .collect()
}

impl Branches {
    /// Step 4: the sign of branch `j`'s real part at point `k` (0 inside the band). Real
    /// parts are taken together with the neutral branches' (whose sum is ≈ 0 and exact as a
    /// trace): where a real root crosses zero next to a neutral zero the two form a defective
    /// double eigenvalue, each known only to √ε, but their sum stays accurate.
    fn sign(&self, k: usize, j: usize) -> i8 {
        let (re, band) = match &self.band {
            Band::Errors(e) => match e[k].as_ref() {
                Some(e) => self.judged(&self.tracked[k], e, j),
                None => (effective_re(&self.tracked[k], j, &self.neutral_idx), 0.0),
            },
            Band::Relative(rtol) => (
                effective_re(&self.tracked[k], j, &self.neutral_idx),
                rtol * self.norms[k],
            ),
        };
        if re > band {
            1
        } else if re < -band {
            -1
        } else {
            0
        }
    }

    /// Branch `j`'s real part and its tolerance from the estimates `e` of every branch at one
    /// point: its own, as `eom analyze` judges the eigenvalue, where that decides the sign;
    /// otherwise taken with the neutral branches' (sum and summed estimates). Summing first
    /// would let a neutral branch's large estimate (a defective zero: a free heading) blur a
    /// root far from zero whose own estimate is tiny.
    fn judged(&self, eig: &[Complex64], e: &[f64], j: usize) -> (f64, f64) {
        let own = eig[j].re;
        if own.abs() > e[j] {
            (own, e[j])
        } else {
            (
                effective_re(eig, j, &self.neutral_idx),
                self.tolerance(e, j),
            )
        }
    }

    /// The error estimate of branch `j`'s real part taken with the neutral branches', from
    /// the estimates `e` of every branch at one point.
    fn tolerance(&self, e: &[f64], j: usize) -> f64 {
        e[j] + self
            .neutral_idx
            .iter()
            .filter(|&&k| k != j)
            .map(|&k| e[k])
            .sum::<f64>()
    }

    /// Step 4: the largest real part of the non-neutral branches, its tolerance (`None` where
    /// the estimates were not needed) and the stability class of a point with these branch
    /// values (and error estimates, unless the band is relative): every branch judged by
    /// [`crate::modes::stability_of`]. Without estimates under an error band every real part
    /// is beyond [`screen_bound`], outside any estimate it could have: its sign decides.
    fn classify(
        &self,
        eig: &[Complex64],
        norm: f64,
        errors: Option<&[f64]>,
    ) -> (Option<(f64, Option<f64>)>, PointStability) {
        let mut max_re: Option<(f64, Option<f64>)> = None;
        let (mut unstable, mut marginal) = (false, false);
        for j in (0..eig.len()).filter(|&j| !self.neutral[j]) {
            let (re, tol) = match (errors, &self.band) {
                (Some(e), _) => {
                    let (re, tol) = self.judged(eig, e, j);
                    (re, Some(tol))
                }
                (None, Band::Relative(rtol)) => {
                    (effective_re(eig, j, &self.neutral_idx), Some(rtol * norm))
                }
                // Not computed: beyond the screen, or an exact zero (estimate 0).
                (None, Band::Errors(_)) => {
                    let re = effective_re(eig, j, &self.neutral_idx);
                    (re, (re == 0.0).then_some(0.0))
                }
            };
            match crate::modes::stability_of(re, tol.unwrap_or(0.0)) {
                Stability::Unstable => unstable = true,
                Stability::Marginal => marginal = true,
                Stability::Stable => {}
            }
            if max_re.is_none_or(|(m, _)| re > m) {
                max_re = Some((re, tol));
            }
        }
        let st = if max_re.is_none() || (marginal && !unstable) {
            PointStability::Marginal
        } else if unstable {
            PointStability::Unstable
        } else {
            PointStability::Stable
        };
        (max_re, st)
    }

    /// Step 4: every grid point with its branch values and stability.
    fn points(&self, xs: &[f64]) -> Vec<SweepPoint> {
        (0..self.tracked.len())
            .map(|k| {
                let errors = match &self.band {
                    Band::Errors(e) => e[k].as_deref(),
                    Band::Relative(_) => None,
                };
                let (max, stability) = self.classify(&self.tracked[k], self.norms[k], errors);
                SweepPoint {
                    value: xs[k],
                    eigenvalues: self.tracked[k].clone(),
                    max_real: max.map(|m| m.0),
                    stability,
                    norm: self.norms[k],
                    tolerance: max.and_then(|m| m.1),
                }
            })
            .collect()
    }
}

struct Eval {
    /// The eigenvalues, the exact zeros of deflated zero rows and columns first.
    eig: Vec<Complex64>,
    /// Their error estimates (0 for the exact zeros), when asked for and needed: `None` where
    /// every real part is beyond [`screen_bound`] (see [`Ctx::needs_estimates`]).
    errors: Option<Vec<f64>>,
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

struct Ctx<'a, F> {
    f: &'a F,
    param: &'a str,
    /// [`Sweep::with_neutral_rtol`]: eigenvalues this small get their estimates (step 4).
    neutral_rtol: f64,
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

    /// Evaluates A(x) and its eigenvalues, with their error estimates when `errors`;
    /// `expect` is the size A must have.
    fn eval(
        &self,
        x: f64,
        ws: &mut Option<EigenvaluesWorkspace>,
        expect: Option<usize>,
        errors: bool,
    ) -> Result<Eval, SweepError<E>> {
        let a = (self.f)(x).map_err(|source| SweepError::Model {
            param: self.param.to_string(),
            value: x,
            source,
        })?;
        if a.nrows() != a.ncols() {
            return Err(self.numeric(
                x,
                NumError::Dimension(DimensionError::NotSquare {
                    matrix: "A",
                    rows: a.nrows(),
                    cols: a.ncols(),
                }),
            ));
        }
        let n = a.nrows();
        if let Some(e) = expect
            && e != n
        {
            return Err(self.numeric(
                x,
                NumError::Dimension(DimensionError::SweepGrid { states: n, grid: e }),
            ));
        }
        let (reduced, zeros) = deflate_zero_lines(&a);
        let core = reduced.as_ref().unwrap_or(&a);
        let m = core.nrows();
        let norm = balanced_norm(&a);
        let mut eig = vec![Complex64::new(0.0, 0.0); n];
        if m > 0 {
            if ws.as_ref().is_none_or(|w| w.dim() != m) {
                *ws = Some(EigenvaluesWorkspace::new(m));
            }
            if let Some(w) = ws.as_mut() {
                eigenvalues_in(core, w, &mut eig[zeros..]).map_err(|e| self.numeric(x, e))?;
            }
        }
        if !errors || !self.needs_estimates(&eig[zeros..], core.norm(), norm) {
            return Ok(Eval {
                eig,
                errors: None,
                norm,
            });
        }
        let mut err = vec![0.0; n];
        let with = eigenvalues_with_errors(core).map_err(|e| self.numeric(x, e))?;
        for (k, (z, e)) in with.into_iter().enumerate() {
            eig[zeros + k] = z;
            err[zeros + k] = e;
        }
        Ok(Eval {
            eig,
            errors: Some(err),
            norm,
        })
    }

    /// Whether any of the eigenvalues `eig` of a matrix of Frobenius norm `core_norm` (the
    /// state matrix, of norm `norm`, without its zero lines) could be judged differently with
    /// its error estimate than by its sign alone: a real part within [`screen_bound`], or a
    /// modulus small enough to make it a neutral branch (whose estimate every other branch's
    /// tolerance includes). An exact zero (a structural zero the eigensolver deflates) has
    /// the estimate 0 by definition ([`crate::modes::eigenvalues_with_errors`]): nothing to
    /// compute.
    fn needs_estimates(&self, eig: &[Complex64], core_norm: f64, norm: f64) -> bool {
        let bound = screen_bound(eig.len(), core_norm);
        let neutral = self.neutral_rtol * norm;
        eig.iter()
            .filter(|z| **z != Complex64::new(0.0, 0.0))
            .any(|z| z.re.abs() <= bound || z.norm() <= neutral)
    }
}

/// The condition number up to which a real part beyond [`screen_bound`] is certainly outside
/// its eigenvalue's error estimate. An eigenvalue of larger condition number κ lies within
/// about `‖A‖/κ` of a matrix with a multiple eigenvalue (Wilkinson), here `1e-9 ‖A‖`; a
/// multiple eigenvalue split by rounding has κ ≈ 1/√ε ≈ 7e7, fifteen times below. Beyond
/// it a model is defective to working precision away from `Re λ = 0` (within `1e-6 ‖A‖` of
/// zero the neutral test computes the estimates anyway), and `eom analyze` at that point
/// still judges it by its estimate.
pub const SCREEN_CONDITION: f64 = 1e9;

/// The real part beyond which an eigenvalue of an `m × m` matrix of Frobenius norm `norm`
/// with condition number below [`SCREEN_CONDITION`] keeps its sign's verdict whatever its
/// error estimate: `tol_factor · m · ε · ‖A‖_F · SCREEN_CONDITION`, above both terms of
/// [`crate::modes::error_estimate`] (the componentwise term is at most `ε ‖A‖_F κ`, and
/// balancing does not increase `‖A‖_F`).
pub fn screen_bound(m: usize, norm: f64) -> f64 {
    crate::modes::ModeOptions::default().tol_factor
        * m as f64
        * f64::EPSILON
        * norm
        * SCREEN_CONDITION
}

/// The Frobenius norm of `a` balanced by a diagonal similarity (see [`SweepPoint::norm`]).
fn balanced_norm(a: &DMatrix<f64>) -> f64 {
    let n = a.nrows();
    let mut b: Vec<f64> = a.as_slice().to_vec();
    let mut scale = vec![1.0; n];
    crate::linalg::balance_in_place(&mut b, n, &mut scale);
    let norm = crate::linalg::frobenius_norm(&b);
    if norm.is_finite() { norm } else { a.norm() }
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
