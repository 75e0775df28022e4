//! `eom sweep`: eigenvalues over a parameter grid, stability boundaries and stable intervals.
//!
//! The model is reduced symbolically **once** ([`Linearizer::symbolic`], pivots chosen at one
//! point of the range) and its state matrix is evaluated from the compiled tape at every
//! sweep value, in parallel ([`eom_num::sweep::Sweep`]: branch tracking, neutral branches,
//! boundaries located by Brent's method, stable intervals). A value outside the validity
//! region of the symbolic reduction (a recorded pivot breaks down) is evaluated by the robust
//! (SVD) path instead, and every such value is reported.
//!
//! For the built-in models whose generated code `eom` carries with the stability verdict
//! (`eom codegen --stability`: smd, shimmy, bicycle, quarter car, top, the wing models), every
//! grid value also gets the verdict without eigenvalues — the Liénard–Chipart conditions of
//! the closed-form characteristic polynomial with their rounding-error bounds — and the report
//! says where it is undecided and whether it agrees with the eigenvalues.

use crate::error::CliError;
use crate::format::{eigenvalue, g, table, wrap_list};
use crate::params::{ModelChoice, SweepSpec};
use eom_model::{Linearizer, Method, Model, ModelError};
use eom_num::sweep::{Crossing, PointStability, StableInterval, Sweep, SweepPoint, SweepResult};
use eom_sym::{Expr, SymError};
use models::CatalogueError;
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::{Serialize, Serializer};
use std::sync::Mutex;

/// Absolute tolerance in the swept parameter to which boundaries are located.
pub const BOUNDARY_TOLERANCE: f64 = 1e-10;

/// The result of `eom sweep`, serialized as its JSON output.
#[derive(Clone, Debug, Serialize)]
pub struct SweepReport {
    /// Model name as given.
    pub model: String,
    /// The sweep: `param`, `points` (value, eigenvalues in branch order, max_real, stability,
    /// norm), `branches` (neutral or not), `stable_intervals` (`[lo, hi]`), `boundaries`
    /// (value, eigenvalue, branch, crossing, bracket, evaluations, converged).
    #[serde(flatten)]
    pub result: SweepResult,
    /// First value, last value and number of values of the grid.
    pub range: Range,
    /// The other parameters with the values used, in catalogue order.
    #[serde(serialize_with = "ordered_map")]
    pub fixed: Vec<(String, f64)>,
    /// Absolute tolerance of the boundary locations in the parameter.
    pub boundary_tolerance: f64,
    /// How the state matrix was evaluated.
    pub evaluation: Evaluation,
    /// The verdict without eigenvalues at the grid values, where the model's generated code
    /// is built in.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<VerdictCheck>,
}

/// The generated stability verdict at the grid values, against the eigenvalues'.
#[derive(Clone, Debug, Default, Serialize)]
pub struct VerdictCheck {
    /// Grid values the verdict calls stable.
    pub stable: usize,
    /// Grid values it calls unstable (or marginal: not asymptotically stable).
    pub unstable: usize,
    /// Grid values where a condition is within its rounding bound of zero.
    pub undecided: Vec<f64>,
    /// Grid values outside the validity region of the generated code's rank decisions.
    pub failed: Vec<f64>,
    /// Decided grid values where the eigenvalues say the opposite (stable against unstable;
    /// a marginal point agrees with either).
    pub disagreements: Vec<f64>,
}

/// The verdict without eigenvalues at every grid value of `result` (`base`: the parameter
/// values in the model's order, `k` the swept one), for a built-in model that has it.
#[cfg(feature = "bench")]
fn verdict_check(
    choice: &ModelChoice,
    names: &[String],
    base: &[f64],
    k: usize,
    result: &SweepResult,
) -> Option<VerdictCheck> {
    if !matches!(choice.source, crate::params::Source::Builtin) {
        return None;
    }
    let gv = eom_bench::work_precision::generated::stability(&choice.name)?;
    // The generated parameters by name (the same model, so the same names).
    let order: Vec<usize> = gv
        .names
        .iter()
        .map(|n| names.iter().position(|m| m == n))
        .collect::<Option<_>>()?;
    let mut out = VerdictCheck::default();
    let points: Vec<Vec<f64>> = result
        .points
        .iter()
        .map(|pt| {
            let mut v = base.to_vec();
            v[k] = pt.value;
            order.iter().map(|&i| v[i]).collect()
        })
        .collect();
    for (pt, verdict) in result.points.iter().zip((gv.many)(&points)) {
        match verdict {
            None => out.failed.push(pt.value),
            Some(0) => out.undecided.push(pt.value),
            Some(x) => {
                let stable = x == 1;
                out.stable += usize::from(stable);
                out.unstable += usize::from(!stable);
                let opposite = match pt.stability {
                    PointStability::Stable => !stable,
                    PointStability::Unstable => stable,
                    PointStability::Marginal => false,
                };
                if opposite {
                    out.disagreements.push(pt.value);
                }
            }
        }
    }
    Some(out)
}

/// Without the `bench` feature no generated verdict is linked in: no check.
#[cfg(not(feature = "bench"))]
fn verdict_check(
    _: &ModelChoice,
    _: &[String],
    _: &[f64],
    _: usize,
    _: &SweepResult,
) -> Option<VerdictCheck> {
    None
}

/// The sweep grid.
#[derive(Clone, Debug, Serialize)]
pub struct Range {
    /// First value.
    pub start: f64,
    /// Last value.
    pub stop: f64,
    /// Number of values (both ends included).
    pub count: usize,
}

/// How the state matrix was evaluated.
#[derive(Clone, Debug, Serialize)]
pub struct Evaluation {
    /// `symbolic` (compiled once, robust fallback per point) or `robust` (every point, when
    /// the symbolic reduction is not available for this model).
    pub method: &'static str,
    /// Value of the swept parameter at which the symbolic pivots were chosen.
    pub pivots_at: f64,
    /// Why the symbolic reduction is not used (`method = robust`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub symbolic_unavailable: Option<String>,
    /// Grid values evaluated by the robust path instead of the symbolic model.
    pub fallback: Fallback,
}

/// Values where the symbolic model could not be used.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Fallback {
    /// Number of grid values evaluated by the robust path.
    pub count: usize,
    /// Those grid values, increasing.
    pub values: Vec<f64>,
    /// Further robust evaluations between grid values (while locating boundaries).
    pub off_grid: usize,
    /// The distinct reasons (the failed validity check).
    pub reasons: Vec<String>,
}

fn ordered_map<S: Serializer>(v: &[(String, f64)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

/// A at `param = x` by the robust path. The model is shared by the sweep's worker threads
/// (its expressions find their pool from any thread).
fn robust_state_matrix(model: &Model<Expr>, param: &str, x: f64) -> Result<DMatrix<f64>, CliError> {
    let lin = Linearizer::new(model)
        .at(&[(param, x)])
        .method(Method::Robust)
        .run()?;
    Ok(lin.state_space.a)
}

/// Checks every value of the range against the parameter's sign assumption, with the model
/// library's own error ([`CatalogueError::BadValue`]).
fn check_range(
    choice: &ModelChoice,
    spec: &SweepSpec,
    overrides: &[(String, f64)],
) -> Result<(), CliError> {
    let p = choice.param(&spec.name)?;
    let (lo, hi) = spec.bounds();
    if !p.range.contains(0.0)
        && p.range.contains(lo)
        && p.range.contains(hi)
        && lo <= 0.0
        && hi >= 0.0
    {
        return Err(CliError::Catalogue(CatalogueError::BadValue {
            model: choice.name.clone(),
            name: spec.name.clone(),
            value: 0.0,
            problem: format!("must not be zero, and the sweep [{lo}, {hi}] includes 0"),
        }));
    }
    // The sign assumptions are intervals: checking both ends covers the range.
    for x in [lo, hi] {
        let mut ov = overrides.to_vec();
        ov.push((spec.name.clone(), x));
        choice.build(&ov)?;
    }
    Ok(())
}

/// Runs the sweep, calling `tick` once per evaluation of the state matrix (grid values and
/// boundary refinements; from several threads).
pub fn sweep_with(
    choice: &ModelChoice,
    spec: &SweepSpec,
    overrides: &[(String, f64)],
    tick: &(dyn Fn() + Sync),
) -> Result<SweepReport, CliError> {
    let param = choice.param(&spec.name)?;
    if overrides.iter().any(|(k, _)| k == &spec.name) {
        return Err(CliError::BadArgument {
            argument: format!("--set {}", spec.name),
            problem: format!(
                "`{}` is the swept parameter (--param); it cannot also be set",
                spec.name
            ),
        });
    }
    check_range(choice, spec, overrides)?;
    let (lo, hi) = spec.bounds();
    // Pivots are chosen where the model is most likely regular: its default, when that lies in
    // the range; else the middle of the range.
    let pivots_at = if (lo..=hi).contains(&param.default) {
        param.default
    } else {
        0.5 * (lo + hi)
    };
    let mut nominal = overrides.to_vec();
    nominal.push((spec.name.clone(), pivots_at));
    let model = choice.build(&nominal)?;
    let names = model.scope.names();
    let base = model.scope.nominal_values();
    let k = names
        .iter()
        .position(|n| n == &spec.name)
        .ok_or_else(|| CliError::Inconsistent(format!("`{}` not in the model", spec.name)))?;
    let (compiled, unavailable) = match Linearizer::new(&model).symbolic() {
        Ok(sym) => (Some(sym.compiled().clone()), None),
        Err(e) => (None, Some(e.to_string())),
    };

    let used: Mutex<Vec<(f64, String)>> = Mutex::new(Vec::new());
    let record = |x: f64, why: String| {
        let mut u = used.lock().unwrap_or_else(|p| p.into_inner());
        u.push((x, why));
    };
    let grid = Sweep::linspace(spec.start, spec.stop, spec.count)
        .with_param_name(spec.name.clone())
        .with_tolerance(BOUNDARY_TOLERANCE);
    let result = grid
        .run(|x| -> Result<DMatrix<f64>, CliError> {
            tick();
            let Some(c) = &compiled else {
                return robust_state_matrix(&model, &spec.name, x);
            };
            let mut v = base.clone();
            v[k] = x;
            match c.evaluate(&v) {
                Ok(ss) => Ok(ss.a),
                Err(ModelError::PivotBreakdown {
                    check,
                    value,
                    row_max,
                }) => {
                    // The failed check, as the fallback's reasons list it.
                    record(
                        x,
                        format!(
                            "{check} (value {value:.3e}, largest entry of its row {row_max:.3e})"
                        ),
                    );
                    robust_state_matrix(&model, &spec.name, x)
                }
                Err(e @ ModelError::Sym(SymError::EvalNonFinite { .. })) => {
                    record(x, e.to_string());
                    robust_state_matrix(&model, &spec.name, x)
                }
                Err(e) => Err(e.into()),
            }
        })
        .map_err(|e| CliError::Sweep(Box::new(e)))?;

    let mut fallback = Fallback::default();
    let used = used.into_inner().unwrap_or_else(|p| p.into_inner());
    let values = grid.values();
    for (x, why) in used {
        if values.contains(&x) {
            if !fallback.values.contains(&x) {
                fallback.values.push(x);
            }
        } else {
            fallback.off_grid += 1;
        }
        if !fallback.reasons.contains(&why) {
            fallback.reasons.push(why);
        }
    }
    fallback.values.sort_by(f64::total_cmp);
    fallback.count = fallback.values.len();
    let fixed = choice
        .values(overrides)
        .into_iter()
        .filter(|(n, _)| n != &spec.name)
        .collect();
    let verdict = verdict_check(choice, &names, &base, k, &result);
    Ok(SweepReport {
        model: choice.name.clone(),
        result,
        range: Range {
            start: spec.start,
            stop: spec.stop,
            count: spec.count,
        },
        fixed,
        boundary_tolerance: BOUNDARY_TOLERANCE,
        evaluation: Evaluation {
            method: if compiled.is_some() {
                "symbolic"
            } else {
                "robust"
            },
            pivots_at,
            symbolic_unavailable: unavailable,
            fallback,
        },
        verdict,
    })
}

impl VerdictCheck {
    fn to_text(&self, p: &str) -> String {
        let list = |v: &[f64]| v.iter().map(|x| g(*x, 8)).collect::<Vec<_>>().join(", ");
        let mut t = format!(
            "\nStability without eigenvalues (the generated Liénard–Chipart verdict, \
             `eom codegen --stability`): {} stable, {} unstable or marginal, {} undecided",
            self.stable,
            self.unstable,
            self.undecided.len()
        );
        if !self.undecided.is_empty() {
            t.push_str(&format!(" ({p} = {})", list(&self.undecided)));
        }
        if !self.failed.is_empty() {
            t.push_str(&format!(
                ", outside its validity region at {p} = {}",
                list(&self.failed)
            ));
        }
        if self.disagreements.is_empty() {
            t.push_str("; it agrees with the eigenvalues wherever it decides\n");
        } else {
            t.push_str(&format!(
                "; it DISAGREES with the eigenvalues at {p} = {}\n",
                list(&self.disagreements)
            ));
        }
        t
    }
}

/// Most eigenvalues shown per row of the text table.
const SHOWN: usize = 6;

impl SweepReport {
    /// The fallback notice (also printed on standard error for CSV output).
    pub fn evaluation_note(&self) -> String {
        let e = &self.evaluation;
        let p = &self.result.param;
        let mut s = match &e.symbolic_unavailable {
            Some(why) => format!(
                "Evaluation: robust path at every value (the symbolic reduction is not available: \
                 {why})"
            ),
            None => format!(
                "Evaluation: symbolic model compiled once (pivots chosen at {p} = {}); robust \
                 fallback at {} of {} grid values",
                g(e.pivots_at, 10),
                e.fallback.count,
                self.range.count
            ),
        };
        if e.fallback.count > 0 {
            let list: Vec<String> = e.fallback.values.iter().map(|v| format!("{v}")).collect();
            s.push_str(&format!(" ({p} = {})", list.join(", ")));
        }
        if e.fallback.off_grid > 0 {
            s.push_str(&format!(
                ", and at {} value(s) between grid points",
                e.fallback.off_grid
            ));
        }
        s.push('\n');
        for r in &e.fallback.reasons {
            s.push_str(&format!("  outside the symbolic validity region: {r}\n"));
        }
        s
    }

    /// CSV: `value,re1,im1,…` with the eigenvalues in branch order (column j follows one
    /// branch along the sweep).
    pub fn to_csv(&self) -> String {
        let n = self.result.branches.len();
        let mut s = String::from("value");
        for j in 1..=n {
            s.push_str(&format!(",re{j},im{j}"));
        }
        s.push('\n');
        for p in &self.result.points {
            s.push_str(&format!("{:?}", p.value));
            for z in &p.eigenvalues {
                s.push_str(&format!(",{:?},{:?}", z.re, z.im));
            }
            s.push('\n');
        }
        s
    }

    fn eigenvalue_cell(&self, p: &SweepPoint) -> String {
        let neutral: Vec<bool> = self.result.branches.iter().map(|b| b.neutral).collect();
        let mut shown: Vec<Complex64> = p
            .eigenvalues
            .iter()
            .enumerate()
            .filter(|&(j, z)| !neutral.get(j).copied().unwrap_or(false) && z.im >= 0.0)
            .map(|(_, z)| *z)
            .collect();
        // Least stable first.
        shown.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        let more = shown.len().saturating_sub(SHOWN);
        let mut cell: Vec<String> = shown
            .iter()
            .take(SHOWN)
            .map(|z| eigenvalue(*z, 5, z.im > 0.0))
            .collect();
        if more > 0 {
            cell.push(format!("… {more} more"));
        }
        cell.join(", ")
    }

    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let r = &self.result;
        let p = &r.param;
        let mut t = format!(
            "Sweep of {p} from {} to {} ({} values), model {}\n",
            self.range.start, self.range.stop, self.range.count, self.model
        );
        if !self.fixed.is_empty() {
            let fixed: Vec<String> = self
                .fixed
                .iter()
                .map(|(n, v)| format!("{n} = {}", g(*v, 6)))
                .collect();
            t.push_str(&wrap_list("Fixed:", &fixed, 100));
        }
        t.push_str(&self.evaluation_note());
        let nn = r.branches.iter().filter(|b| b.neutral).count();
        t.push_str(&format!(
            "Branches: {} ({nn} neutral: identically zero, e.g. a vehicle's lateral position and \
             heading; excluded from stability)\n\n",
            r.branches.len()
        ));
        let rows: Vec<Vec<String>> = r
            .points
            .iter()
            .map(|pt| {
                vec![
                    g(pt.value, 8),
                    match pt.stability {
                        PointStability::Stable => "stable",
                        PointStability::Marginal => "marginal",
                        PointStability::Unstable => "unstable",
                    }
                    .to_string(),
                    match (pt.max_real, pt.tolerance) {
                        (Some(x), Some(tol)) => format!("{} ±{}", g(x, 5), g(tol, 2)),
                        (Some(x), None) => g(x, 5),
                        _ => "-".into(),
                    },
                    self.eigenvalue_cell(pt),
                ]
            })
            .collect();
        t.push_str(&table(
            &[
                p.as_str(),
                "stability",
                "max Re λ ± tol",
                "eigenvalues [1/s] (least stable first)",
            ],
            &rows,
            2,
        ));
        t.push_str(&format!(
            "  stability: stable when every branch has Re λ < −tol, marginal when one has \
             |Re λ| ≤ tol and none is unstable;\n  tol = the eigenvalue's error estimate, the \
             same rule as eom analyze (JSON: points[].tolerance); no ±tol: every |Re λ| there \
             exceeds\n  10·n·ε·‖A‖_F·{k}, beyond the estimate of any eigenvalue of condition \
             number below {k}, so none was computed\n",
            k = g(eom_num::sweep::SCREEN_CONDITION, 2)
        ));
        t.push('\n');

        t.push_str(&format!(
            "Stability boundaries (located to {} in {p})\n",
            g(self.boundary_tolerance, 3)
        ));
        if r.boundaries.is_empty() {
            t.push_str(&format!(
                "  none between the grid points: no branch changes sign from one value to the \
                 next (two crossings inside one grid step are not seen; a finer grid than \
                 {} values may find them)\n",
                self.range.count
            ));
        }
        for b in &r.boundaries {
            let dir = match b.crossing {
                Crossing::Destabilizing => "destabilizing",
                Crossing::Stabilizing => "stabilizing",
            };
            let conv = if b.converged {
                String::new()
            } else {
                format!(
                    " — NOT converged, root in [{}, {}]",
                    b.bracket[0], b.bracket[1]
                )
            };
            t.push_str(&format!(
                "  {p} = {}  {dir}  eigenvalue {} (branch {}, {} evaluations){conv}\n",
                b.value,
                eigenvalue(b.eigenvalue, 6, false),
                b.branch + 1,
                b.evaluations
            ));
        }
        t.push('\n');
        t.push_str(&format!("Stable intervals of {p}\n"));
        let marginal_count = r
            .points
            .iter()
            .filter(|pt| pt.stability == PointStability::Marginal)
            .count();
        if r.stable_intervals.is_empty() && marginal_count == r.points.len() {
            t.push_str(&format!(
                "  none: all {} values are marginal (a real part within its error estimate of \
                 0 at each, and none unstable)\n",
                self.range.count
            ));
        } else if r.stable_intervals.is_empty() {
            t.push_str(&format!(
                "  none at the grid points: all {} values are unstable or marginal (the model \
                 may be stable between them: refine the grid)\n",
                self.range.count
            ));
        }
        for i in &r.stable_intervals {
            t.push_str(&format!("  {}\n", interval_text(r, i, |x| x.to_string())));
        }
        if !r.stable_intervals.is_empty() {
            t.push_str(
                "  ( and ): the end is a boundary or a marginal point, not itself stable; [ and ]: \
                 a stable grid point (JSON: stable_intervals as [lo, hi])\n",
            );
        }
        if let Some(v) = &self.verdict {
            t.push_str(&v.to_text(p));
        }
        let marginal: Vec<String> = r
            .points
            .iter()
            .filter(|pt| pt.stability == PointStability::Marginal)
            .map(|pt| g(pt.value, 10))
            .collect();
        if !marginal.is_empty() {
            t.push_str(&wrap_list(
                &format!("  marginal (not in the intervals) at {p} ="),
                &marginal,
                100,
            ));
        }
        t
    }
}

/// A stable interval as written (`num` writes its ends): an end where stability is lost (a
/// boundary or a marginal grid point) is not in the interval and is written open, an end at
/// a stable grid point closed.
pub fn interval_text(r: &SweepResult, i: &StableInterval, num: impl Fn(f64) -> String) -> String {
    let open_at = |x: f64| {
        r.boundaries.iter().any(|b| b.value == x)
            || r.points
                .iter()
                .any(|pt| pt.value == x && pt.stability != PointStability::Stable)
    };
    format!(
        "{}{}, {}{}",
        if open_at(i.lo) { '(' } else { '[' },
        num(i.lo),
        num(i.hi),
        if open_at(i.hi) { ')' } else { ']' }
    )
}
