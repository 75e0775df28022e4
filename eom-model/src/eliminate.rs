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

use crate::error::ModelError;
use eom_sym::matrix::SparseMatrix;
use eom_sym::scalar::Scalar;

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
    pub rows: RowStore<S>,
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
        let mut v = vec![None; self.rows.nrows()];
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

/// The rows of an elimination, all in one buffer: row `i` is
/// `entries[start[i]..start[i] + len[i]]`, sorted by column, with room up to `cap[i]`. One
/// allocation for all rows instead of one per row (a numeric elimination is dominated by
/// such bookkeeping). Rows start packed; a row that outgrows its room moves to the end of
/// the buffer with room to double, so fill-in costs few moves and no per-row allocation.
#[derive(Clone, Debug)]
pub struct RowStore<S> {
    entries: Vec<(usize, S)>,
    start: Vec<usize>,
    len: Vec<usize>,
    cap: Vec<usize>,
    ncols: usize,
}

impl<S: Scalar> RowStore<S> {
    /// Empty rows with room for exactly `lens[i]` entries each, over `ncols` columns.
    pub fn with_lengths(lens: &[usize], ncols: usize) -> Self {
        let mut st = RowStore {
            entries: Vec::new(),
            start: Vec::with_capacity(lens.len()),
            len: Vec::with_capacity(lens.len()),
            cap: Vec::with_capacity(lens.len()),
            ncols,
        };
        let mut total = 0;
        for &n in lens {
            st.start.push(total);
            st.len.push(0);
            st.cap.push(n);
            total += n;
        }
        st.entries.reserve(Self::room(total));
        st.entries.resize(total, (0, S::zero()));
        st
    }

    /// Buffer capacity for rows of `nnz` entries: room for the moves of rows that grow with
    /// fill-in, so that the buffer itself seldom reallocates (reserved, not initialised).
    fn room(nnz: usize) -> usize {
        4 * nnz + 64
    }

    /// The rows of a matrix.
    pub fn from_matrix(m: &SparseMatrix<S>) -> Self {
        let n = m.nrows();
        let mut entries = Vec::with_capacity(Self::room(m.nnz()));
        let (mut start, mut len) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for i in 0..n {
            let r = m.row(i);
            start.push(entries.len());
            len.push(r.len());
            entries.extend_from_slice(r);
        }
        RowStore {
            entries,
            start,
            cap: len.clone(),
            len,
            ncols: m.ncols(),
        }
    }

    /// Rows given as vectors (each sorted by column).
    pub fn from_rows(rows: &[Row<S>], ncols: usize) -> Self {
        let lens: Vec<usize> = rows.iter().map(Vec::len).collect();
        let mut st = Self::with_lengths(&lens, ncols);
        for (i, r) in rows.iter().enumerate() {
            st.set(i, r);
        }
        st
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.start.len()
    }

    /// Row `i`.
    pub fn row(&self, i: usize) -> &[(usize, S)] {
        &self.entries[self.start[i]..self.start[i] + self.len[i]]
    }

    fn row_mut(&mut self, i: usize) -> &mut [(usize, S)] {
        &mut self.entries[self.start[i]..self.start[i] + self.len[i]]
    }

    /// Append `e` to row `i` (its column must exceed the row's last).
    pub fn push(&mut self, i: usize, e: (usize, S)) {
        if self.len[i] == self.cap[i] {
            self.relocate(i, self.len[i] + 1, true);
        }
        self.entries[self.start[i] + self.len[i]] = e;
        self.len[i] += 1;
    }

    /// Append a row.
    pub fn push_row(&mut self, row: &[(usize, S)]) {
        self.start.push(self.entries.len());
        self.len.push(row.len());
        self.cap.push(row.len());
        self.entries.extend_from_slice(row);
    }

    /// Replace row `i` by `row`.
    fn set(&mut self, i: usize, row: &[(usize, S)]) {
        if row.len() > self.cap[i] {
            self.relocate(i, row.len(), false);
        }
        let a = self.start[i];
        self.entries[a..a + row.len()].copy_from_slice(row);
        self.len[i] = row.len();
    }

    /// Move row `i` to the end of the buffer with room for at least `need` entries (its
    /// entries come along when `keep`; otherwise the caller overwrites them).
    fn relocate(&mut self, i: usize, need: usize, keep: bool) {
        let c = (2 * need).min(self.ncols.max(need));
        let (a, n) = (self.start[i], self.len[i]);
        let b = self.entries.len();
        if keep {
            self.entries.extend_from_within(a..a + n);
        }
        self.entries.resize(b + c, (0, S::zero()));
        self.start[i] = b;
        self.cap[i] = c;
    }
}

impl<S: Scalar> std::ops::Index<usize> for RowStore<S> {
    type Output = [(usize, S)];
    fn index(&self, i: usize) -> &[(usize, S)] {
        self.row(i)
    }
}

fn get<S: Scalar>(row: &[(usize, S)], col: usize) -> Option<S> {
    row.binary_search_by_key(&col, |e| e.0)
        .ok()
        .map(|k| row[k].1)
}

/// `scratch ← target − f · src` (the pivot column `skip_col` is dropped), skipping structural
/// zeros; `scratch` is reused so that repeated updates do not allocate. `mark(col, present)`
/// hears of every column that enters or leaves the row's structure.
fn axpy<S: Scalar>(
    target: &[(usize, S)],
    f: S,
    src: &Row<S>,
    skip_col: usize,
    scratch: &mut Row<S>,
    mut mark: impl FnMut(usize, bool),
) {
    scratch.clear();
    let (mut i, mut j) = (0, 0);
    while i < target.len() && j < src.len() {
        let (ci, t) = target[i];
        let (cj, s) = src[j];
        if ci < cj {
            scratch.push((ci, t));
            i += 1;
        } else if cj < ci {
            if cj != skip_col {
                let v = -(f * s);
                if !v.is_zero() {
                    scratch.push((cj, v));
                    mark(cj, true);
                }
            }
            j += 1;
        } else {
            if ci != skip_col {
                let v = (if s.is_one() { t - f } else { t - f * s }).recognise_zero();
                if !v.is_zero() {
                    scratch.push((ci, v));
                } else {
                    mark(ci, false);
                }
            } else {
                mark(ci, false);
            }
            i += 1;
            j += 1;
        }
    }
    scratch.extend_from_slice(&target[i..]);
    for &(cj, s) in &src[j..] {
        if cj != skip_col {
            let v = -(f * s);
            if !v.is_zero() {
                scratch.push((cj, v));
                mark(cj, true);
            }
        }
    }
}

/// Which rows hold an entry in each eligible column (one bit per row), so that a pivot step
/// visits only the rows it changes instead of searching every row for the pivot column.
struct ColRows {
    words: usize,
    bits: Vec<u64>,
}

impl ColRows {
    fn new<S: Scalar>(rows: &RowStore<S>, eligible: usize) -> Self {
        let words = rows.nrows().div_ceil(64);
        let mut m = ColRows {
            words,
            bits: vec![0; words * eligible],
        };
        for r in 0..rows.nrows() {
            for e in eligible_part(rows.row(r), eligible) {
                m.set(e.0, r, true);
            }
        }
        m
    }

    fn set(&mut self, col: usize, row: usize, present: bool) {
        let w = &mut self.bits[col * self.words + row / 64];
        let b = 1u64 << (row % 64);
        if present { *w |= b } else { *w &= !b }
    }
}

/// The entries of a row in the eligible columns: a prefix, since rows are sorted by column.
fn eligible_part<S>(row: &[(usize, S)], eligible: usize) -> &[(usize, S)] {
    &row[..row.partition_point(|e| e.0 < eligible)]
}

fn row_scale<S: Scalar>(row: &[(usize, S)], eligible: usize) -> f64 {
    eligible_part(row, eligible)
        .iter()
        .map(|e| e.1.nominal().abs())
        .fold(0.0, f64::max)
}

/// Pivot-search statistics of a row that has not been pivoted (all its eligible entries are
/// live): the largest eligible entry
/// and the number of entries that are not negligible (`None` when the row has no usable
/// entry). They change only when the row does, so they are cached between steps.
fn row_stats<S: Scalar>(row: &[(usize, S)], scale: f64) -> Option<(f64, usize)> {
    let live = || row.iter().map(|e| e.1.nominal().abs());
    let rmax = live().fold(0.0, f64::max);
    if rmax.is_nan() || rmax <= NEGLIGIBLE * scale || !rmax.is_finite() {
        return None;
    }
    Some((rmax, live().filter(|&v| v > NEGLIGIBLE * scale).count()))
}

/// A candidate pivot's rank, compared lexicographically (smaller is better): whether its
/// column is to be kept, its Markowitz count, minus its ratio to its row's largest entry, its
/// column's inertia.
type PivotKey = (bool, usize, f64, f64);

/// Bookkeeping of one row of an elimination.
#[derive(Clone, Copy)]
struct RowState {
    pivoted: bool,
    /// `stats` and `elen` must be recomputed (pivot search only).
    dirty: bool,
    /// Cached [`row_stats`].
    stats: Option<(f64, usize)>,
    /// Length of the row's eligible part, cached with `stats`.
    elen: usize,
    /// The row's original scale ([`row_scale`], pivot search only).
    scale: f64,
}

/// Bookkeeping of one eligible column of an elimination.
#[derive(Clone, Copy)]
struct ColState {
    done: bool,
    /// Structural non-zeros over all rows (Gauss–Jordan fills every row; pivot search only).
    count: usize,
}

/// Working state of one elimination.
struct Elim<'w, S> {
    rows: RowStore<S>,
    eligible: usize,
    record: bool,
    /// Maintain column counts and per-row statistics (pivot search only).
    search: bool,
    /// Per row (one vector rather than one per field: fewer allocations).
    row_state: Vec<RowState>,
    /// Per eligible column.
    col_state: Vec<ColState>,
    cols: ColRows,
    scratch: Row<S>,
    /// The pivot row of the current step (a copy: the other rows change meanwhile).
    prow: Row<S>,
    plan: EliminationPlan,
    records: Vec<PivotRecord<S>>,
    /// Per eligible column, its inertia at the nominal point (empty: no preference).
    weights: &'w [f64],
    /// Per eligible column, whether to keep it independent rather than eliminate it when
    /// the choice is free (empty: no preference).
    keep: &'w [bool],
}

impl<S: Scalar> Elim<'_, S> {
    /// Take pivot `(r, c)`: normalise its row and eliminate column `c` from every other row.
    fn step(&mut self, r: usize, c: usize) -> Result<(), ModelError> {
        let (nrows, eligible) = (self.rows.nrows(), self.eligible);
        if r >= nrows || c >= eligible || self.row_state[r].pivoted || self.col_state[c].done {
            return Err(ModelError::InvalidPivot { row: r, col: c });
        }
        let p = get(&self.rows[r], c).ok_or(ModelError::StructuralZeroPivot { row: r, col: c })?;
        if self.record {
            self.records.push(PivotRecord {
                row: r,
                col: c,
                value: p,
                row_entries: eligible_part(&self.rows[r], eligible)
                    .iter()
                    .filter(|e| e.0 != c)
                    .map(|e| e.1)
                    .collect(),
            });
        }
        // Normalise the pivot row.
        if !p.is_one() {
            let inv = p.recip();
            for e in self.rows.row_mut(r).iter_mut() {
                e.1 = if e.0 == c { S::one() } else { e.1 * inv };
            }
        }
        let mut prow = std::mem::take(&mut self.prow);
        prow.clear();
        prow.extend_from_slice(&self.rows[r]);
        // Only the rows holding column `c` change; a word is read before its rows are updated
        // (which clear their bit of column `c`).
        for w in 0..self.cols.words {
            let mut bits = self.cols.bits[c * self.cols.words + w];
            while bits != 0 {
                let k = 64 * w + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if k == r {
                    continue;
                }
                let Some(f) = get(&self.rows[k], c) else {
                    continue;
                };
                let (cols, col_state, search) = (&mut self.cols, &mut self.col_state, self.search);
                axpy(
                    &self.rows[k],
                    f,
                    &prow,
                    c,
                    &mut self.scratch,
                    |j, present| {
                        if j < eligible {
                            cols.set(j, k, present);
                            // The column counts change exactly where the structure does.
                            if search {
                                if present {
                                    col_state[j].count += 1;
                                } else {
                                    col_state[j].count -= 1;
                                }
                            }
                        }
                    },
                );
                self.rows.set(k, &self.scratch);
                if self.search {
                    self.row_state[k].dirty = true;
                }
            }
        }
        self.prow = prow;
        self.row_state[r].pivoted = true;
        self.col_state[c].done = true;
        self.plan.pivots.push((r, c));
        Ok(())
    }

    /// The next pivot: among the entries of the remaining rows at least [`THRESHOLD`] times
    /// their row's largest, the smallest Markowitz count, then the largest ratio, then the
    /// column of least inertia (when weights are given), then the first in row-major order.
    fn choose(&mut self) -> Option<(usize, usize)> {
        // The best candidate so far, by the key (kept, Markowitz count, −ratio, inertia)
        // compared lexicographically, and its position.
        let mut best: Option<(PivotKey, usize, usize)> = None;
        for r in 0..self.row_state.len() {
            let st = &mut self.row_state[r];
            if st.pivoted {
                continue;
            }
            if st.dirty {
                let row = eligible_part(&self.rows[r], self.eligible);
                st.stats = row_stats(row, st.scale);
                st.elen = row.len();
                st.dirty = false;
            }
            let Some((rmax, rc)) = st.stats else {
                continue;
            };
            // A row without a pivot has no entry in a pivot column (each step clears its
            // column from every other row), so all its eligible entries are live.
            let row = &self.rows[r][..st.elen];
            debug_assert!(row.iter().all(|e| !self.col_state[e.0].done));
            for e in row {
                let (c, v) = (e.0, e.1.nominal().abs());
                if v < THRESHOLD * rmax {
                    continue;
                }
                let mk = (rc - 1) * (self.col_state[c].count - 1);
                let ratio = v / rmax;
                let kept = self.keep.get(c).copied().unwrap_or(false);
                let weight = self.weights.get(c).copied().unwrap_or(0.0);
                let key = (kept, mk, -ratio, weight);
                if best.is_none_or(|b| key < b.0) {
                    best = Some((key, r, c));
                    // No fill-in at the row's largest entry in a column not to keep cannot
                    // be beaten, and ties go to the first found: stop searching (unless a
                    // lighter column may tie).
                    if mk == 0 && ratio == 1.0 && self.weights.is_empty() && !kept {
                        return Some((r, c));
                    }
                }
            }
        }
        best.map(|b| (b.1, b.2))
    }
}

/// Gauss–Jordan elimination of `rows` (each a sparse row over `ncols` columns) with pivots
/// restricted to the first `eligible` columns.
///
/// * `forced`: a pivot sequence to apply first (e.g. the pivots of a sub-block eliminated
///   before, so that identical operations reuse identical expressions);
/// * `plan`: replay a complete earlier plan instead of choosing pivots (the fast numeric path
///   and the validity checks use this). In replay the pivot values are not tested here; the
///   records let the caller test them.
/// * `weights`: the inertia of each eligible column at the nominal point, or empty. Between
///   otherwise equal pivots the column of least inertia is eliminated, so that the heavy
///   bodies' coordinates stay independent: their inertia then enters the reduced mass
///   matrix unmixed, instead of as large rank-one terms that cancel in its inverse and in
///   `M⁻¹K`. On the bicycle (rear frame and rider 85 kg, front frame 4 kg) eliminating the
///   rear frame's lean and yaw made the rounding error of the generated A and B seven times
///   larger (`bench/pydy/README.md`, "Accuracy").
pub fn rref<S: Scalar>(
    rows: RowStore<S>,
    eligible: usize,
    forced: &[(usize, usize)],
    plan: Option<&EliminationPlan>,
    weights: &[f64],
) -> Result<Rref<S>, ModelError> {
    rref_keeping(rows, eligible, forced, plan, weights, &[])
}

/// [`rref`] that eliminates the columns not marked in `keep` first, among all pivots that pass
/// the threshold (before the fill-in, the ratio and the inertia decide): the position
/// constraints keep the rotations of pinned point masses as the independent coordinates (a
/// pendulum bob's angle rather than its sideways position), whatever the lengths.
pub fn rref_keeping<S: Scalar>(
    rows: RowStore<S>,
    eligible: usize,
    forced: &[(usize, usize)],
    plan: Option<&EliminationPlan>,
    weights: &[f64],
    keep: &[bool],
) -> Result<Rref<S>, ModelError> {
    let nrows = rows.nrows();
    // Validity records are needed when the result is symbolic (valid elsewhere only if its
    // pivots hold) or replays a plan chosen elsewhere; a numeric elimination that chooses its
    // own pivots at its own point needs none.
    let record = S::SYMBOLIC || plan.is_some();
    // The original entries of the rows that may end up redundant (their scale): with a plan
    // those are known in advance.
    let orig: Vec<Option<Row<S>>> = match plan {
        _ if !record => Vec::new(),
        Some(p) => {
            let mut o = vec![None; nrows];
            for &r in &p.redundant {
                if r < nrows {
                    o[r] = Some(eligible_part(&rows[r], eligible).to_vec());
                }
            }
            o
        }
        None => (0..nrows)
            .map(|r| Some(eligible_part(&rows[r], eligible).to_vec()))
            .collect(),
    };
    let search = plan.is_none();
    let row_state: Vec<RowState> = (0..nrows)
        .map(|r| RowState {
            pivoted: false,
            dirty: true,
            stats: None,
            elen: 0,
            scale: if search {
                row_scale(&rows[r], eligible)
            } else {
                0.0
            },
        })
        .collect();
    let mut col_state = vec![
        ColState {
            done: false,
            count: 0
        };
        eligible
    ];
    if search {
        for r in 0..nrows {
            for e in eligible_part(&rows[r], eligible) {
                col_state[e.0].count += 1;
            }
        }
    }
    // No row outgrows the width, so buffers of that size never reallocate.
    let width = rows
        .ncols
        .max((0..nrows).map(|r| rows[r].len()).max().unwrap_or(0));
    let cols = ColRows::new(&rows, eligible);
    let mut el = Elim {
        rows,
        eligible,
        record,
        search,
        row_state,
        col_state,
        cols,
        scratch: Vec::with_capacity(width),
        prow: Vec::with_capacity(width),
        plan: EliminationPlan {
            pivots: Vec::with_capacity(nrows.min(eligible)),
            redundant: Vec::new(),
        },
        records: Vec::new(),
        weights,
        keep,
    };

    if let Some(plan) = plan {
        for &(r, c) in &plan.pivots {
            el.step(r, c)?;
        }
        el.plan.redundant = plan.redundant.clone();
    } else {
        for &(r, c) in forced {
            el.step(r, c)?;
        }
        while let Some((r, c)) = el.choose() {
            el.step(r, c)?;
        }
        el.plan.redundant = (0..nrows).filter(|&r| !el.row_state[r].pivoted).collect();
    }

    let mut rank_records = Vec::new();
    if record {
        for &r in &el.plan.redundant {
            if r >= nrows {
                continue;
            }
            for e in eligible_part(&el.rows[r], eligible) {
                rank_records.push(RankRecord {
                    row: r,
                    value: e.1,
                    scale_entries: orig[r]
                        .as_ref()
                        .map_or_else(Vec::new, |o| o.iter().map(|e| e.1).collect()),
                });
            }
        }
    }
    Ok(Rref {
        eligible,
        rows: el.rows,
        plan: el.plan,
        pivot_records: el.records,
        rank_records,
    })
}
