//! Sparse Gauss–Jordan elimination with pivots chosen at the nominal point, recorded as a
//! plan that can be replayed with any scalar type.
//!
//! Pivot choice (when no plan is given): among the structurally non-zero entries of the
//! remaining rows whose nominal magnitude is at least [`THRESHOLD`] times the largest nominal
//! entry of their row (threshold pivoting, so the nominal elimination is stable), take the one
//! with the smallest Markowitz count `(rᵢ − 1)(cⱼ − 1)` — the fewest fill-ins — breaking ties
//! by relative magnitude and then by position (deterministic). Rows whose remaining entries
//! are all negligible at the nominal point (relative to the row's original scale) are declared
//! redundant and reported.
//!
//! Every pivot is recorded with the entries of its row at the time it was taken, so a caller
//! can check, at any other parameter point, that the pivot is still at least a fraction of its
//! row ([`PivotRecord`]): the validity region of a symbolic result.

use crate::error::SymError;
use crate::scalar::Scalar;

/// Minimum ratio `|pivot| / max |row entry|` at the nominal point for a pivot candidate.
pub const THRESHOLD: f64 = 0.1;

/// Relative size below which an entry counts as zero at the nominal point (rank decisions).
pub const NEGLIGIBLE: f64 = 1e-10;

/// A sparse row: `(column, value)` sorted by column.
pub type Row<S> = Vec<(usize, S)>;

/// The pivot sequence of an elimination, replayable with another scalar type.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct EliminationPlan {
    /// `(row, column)` of each pivot, in order.
    pub pivots: Vec<(usize, usize)>,
    /// Rows found redundant (no pivot).
    pub redundant: Vec<usize>,
}

/// A pivot as taken: its value and the other entries of its row (eligible columns) at that
/// moment, for validity checks.
#[derive(Clone, Debug)]
pub struct PivotRecord<S> {
    /// Row of the pivot.
    pub row: usize,
    /// Column of the pivot.
    pub col: usize,
    /// Its value.
    pub value: S,
    /// The other eligible entries of the row when it was taken.
    pub row_entries: Vec<S>,
}

/// An entry that was negligible at the nominal point in a row declared redundant; it must
/// stay negligible for the rank decision (and so the plan) to hold.
#[derive(Clone, Debug)]
pub struct RankRecord<S> {
    /// The redundant row.
    pub row: usize,
    /// Its remaining entry.
    pub value: S,
    /// The row's original entries (its scale).
    pub scale_entries: Vec<S>,
}

/// Result of [`rref`].
#[derive(Clone, Debug)]
pub struct Rref<S> {
    /// Number of columns eligible for pivots (the first ones); later columns are augmented
    /// right-hand sides that are transformed along.
    pub eligible: usize,
    /// The reduced rows: a pivot row has 1 at its pivot column and zeros in all other pivot
    /// columns.
    pub rows: Vec<Row<S>>,
    /// The plan (pivots in order, redundant rows).
    pub plan: EliminationPlan,
    /// Pivots with their row entries at the time.
    pub pivot_records: Vec<PivotRecord<S>>,
    /// Negligible entries of redundant rows.
    pub rank_records: Vec<RankRecord<S>>,
}

impl<S: Scalar> Rref<S> {
    /// Pivot column of each row (`None` for rows without a pivot).
    pub fn pivot_col_of_row(&self) -> Vec<Option<usize>> {
        let mut v = vec![None; self.rows.len()];
        for &(r, c) in &self.plan.pivots {
            v[r] = Some(c);
        }
        v
    }

    /// `true` for the eligible columns that are pivots (dependent variables).
    pub fn is_pivot_col(&self) -> Vec<bool> {
        let mut v = vec![false; self.eligible];
        for &(_, c) in &self.plan.pivots {
            v[c] = true;
        }
        v
    }
}

fn get<S: Scalar>(row: &Row<S>, col: usize) -> Option<S> {
    row.binary_search_by_key(&col, |e| e.0)
        .ok()
        .map(|k| row[k].1)
}

/// `target ← target − f · src` (the pivot column `skip_col` is dropped), skipping structural
/// zeros; `scratch` is reused so that repeated updates do not allocate.
fn axpy<S: Scalar>(target: &mut Row<S>, f: S, src: &Row<S>, skip_col: usize, scratch: &mut Row<S>) {
    scratch.clear();
    let (mut i, mut j) = (0, 0);
    while i < target.len() || j < src.len() {
        let ci = target.get(i).map_or(usize::MAX, |e| e.0);
        let cj = src.get(j).map_or(usize::MAX, |e| e.0);
        if ci < cj {
            scratch.push(target[i]);
            i += 1;
        } else if cj < ci {
            if cj != skip_col {
                let v = -(f * src[j].1);
                if !v.is_zero() {
                    scratch.push((cj, v));
                }
            }
            j += 1;
        } else {
            if ci != skip_col {
                let s = src[j].1;
                let v = (if s.is_one() {
                    target[i].1 - f
                } else {
                    target[i].1 - f * s
                })
                .recognise_zero();
                if !v.is_zero() {
                    scratch.push((ci, v));
                }
            }
            i += 1;
            j += 1;
        }
    }
    std::mem::swap(target, scratch);
}

fn row_scale<S: Scalar>(row: &Row<S>, eligible: usize) -> f64 {
    row.iter()
        .filter(|e| e.0 < eligible)
        .map(|e| e.1.nominal().abs())
        .fold(0.0, f64::max)
}

/// Gauss–Jordan elimination of `rows` (each a sparse row over `ncols` columns) with pivots
/// restricted to the first `eligible` columns.
///
/// * `forced`: a pivot sequence to apply first (e.g. the pivots of a sub-block eliminated
///   before, so that identical operations reuse identical expressions);
/// * `plan`: replay a complete earlier plan instead of choosing pivots (the fast numeric path
///   and the validity checks use this). In replay the pivot values are not tested here; the
///   records let the caller test them.
pub fn rref<S: Scalar>(
    mut rows: Vec<Row<S>>,
    eligible: usize,
    forced: &[(usize, usize)],
    plan: Option<&EliminationPlan>,
) -> Result<Rref<S>, SymError> {
    let nrows = rows.len();
    // Validity records are needed when the result is symbolic (valid elsewhere only if its
    // pivots hold) or replays a plan chosen elsewhere; a numeric elimination that chooses its
    // own pivots at its own point needs none.
    let record = S::SYMBOLIC || plan.is_some();
    let orig = if record { rows.clone() } else { Vec::new() };
    let scale: Vec<f64> = rows.iter().map(|r| row_scale(r, eligible)).collect();
    let mut pivoted = vec![false; nrows];
    let mut col_done = vec![false; eligible];
    let mut out_plan = EliminationPlan::default();
    let mut records = Vec::new();

    let apply = |rows: &mut Vec<Row<S>>, r: usize, c: usize| -> Result<PivotRecord<S>, SymError> {
        let p = get(&rows[r], c).ok_or_else(|| {
            SymError::Singular(format!("planned pivot ({r}, {c}) is a structural zero"))
        })?;
        let rec = PivotRecord {
            row: r,
            col: c,
            value: p,
            row_entries: if record {
                rows[r]
                    .iter()
                    .filter(|e| e.0 < eligible && e.0 != c)
                    .map(|e| e.1)
                    .collect()
            } else {
                Vec::new()
            },
        };
        // Normalise the pivot row.
        if !p.is_one() {
            let inv = p.recip();
            for e in rows[r].iter_mut() {
                e.1 = if e.0 == c { S::one() } else { e.1 * inv };
            }
        }
        let prow = std::mem::take(&mut rows[r]);
        let mut scratch = Vec::with_capacity(prow.len() * 2);
        for row in rows.iter_mut() {
            if let Some(f) = get(row, c) {
                axpy(row, f, &prow, c, &mut scratch);
            }
        }
        rows[r] = prow;
        Ok(rec)
    };

    let mut step = |rows: &mut Vec<Row<S>>,
                    r: usize,
                    c: usize,
                    pivoted: &mut Vec<bool>,
                    col_done: &mut Vec<bool>|
     -> Result<(), SymError> {
        if r >= nrows || c >= eligible || pivoted[r] || col_done[c] {
            return Err(SymError::Singular(format!(
                "invalid pivot ({r}, {c}) in an elimination plan"
            )));
        }
        let rec = apply(rows, r, c)?;
        if record {
            records.push(rec);
        }
        pivoted[r] = true;
        col_done[c] = true;
        out_plan.pivots.push((r, c));
        Ok(())
    };

    if let Some(plan) = plan {
        for &(r, c) in &plan.pivots {
            step(&mut rows, r, c, &mut pivoted, &mut col_done)?;
        }
        out_plan.redundant = plan.redundant.clone();
    } else {
        for &(r, c) in forced {
            step(&mut rows, r, c, &mut pivoted, &mut col_done)?;
        }
        loop {
            // Column counts over all rows (Gauss–Jordan fills every row).
            let mut ccount = vec![0usize; eligible];
            for row in &rows {
                for e in row.iter().filter(|e| e.0 < eligible) {
                    ccount[e.0] += 1;
                }
            }
            let mut best: Option<(usize, f64, usize, usize)> = None; // (markowitz, -ratio, r, c)
            for (r, row) in rows.iter().enumerate() {
                if pivoted[r] {
                    continue;
                }
                let eligible_entries = || {
                    row.iter()
                        .filter(|e| e.0 < eligible && !col_done[e.0])
                        .map(|e| (e.0, e.1.nominal().abs()))
                };
                let rmax = eligible_entries().map(|e| e.1).fold(0.0, f64::max);
                if rmax.is_nan() || rmax <= NEGLIGIBLE * scale[r] || !rmax.is_finite() {
                    continue;
                }
                let rc = eligible_entries()
                    .filter(|e| e.1 > NEGLIGIBLE * scale[r])
                    .count();
                for (c, v) in eligible_entries() {
                    if v < THRESHOLD * rmax {
                        continue;
                    }
                    let mk = (rc - 1) * (ccount[c] - 1);
                    let ratio = v / rmax;
                    let better = match best {
                        None => true,
                        Some((bm, br, _, _)) => mk < bm || (mk == bm && -ratio < br),
                    };
                    if better {
                        best = Some((mk, -ratio, r, c));
                    }
                }
            }
            match best {
                Some((_, _, r, c)) => step(&mut rows, r, c, &mut pivoted, &mut col_done)?,
                None => break,
            }
        }
        out_plan.redundant = (0..nrows).filter(|&r| !pivoted[r]).collect();
    }

    let mut rank_records = Vec::new();
    for &r in out_plan.redundant.iter().filter(|_| record) {
        for e in rows[r].iter().filter(|e| e.0 < eligible) {
            rank_records.push(RankRecord {
                row: r,
                value: e.1,
                scale_entries: orig[r]
                    .iter()
                    .filter(|e| e.0 < eligible)
                    .map(|e| e.1)
                    .collect(),
            });
        }
    }
    Ok(Rref {
        eligible,
        rows,
        plan: out_plan,
        pivot_records: records,
        rank_records,
    })
}
