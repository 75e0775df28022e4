//! [`SparseMatrix`]: a matrix over any [`Scalar`] that stores only structural non-zeros.
//!
//! Structural zeros are never materialised (for expressions: never become nodes), and the
//! sparsity pattern is visible to later stages ([`SparseMatrix::pattern`],
//! [`SparseMatrix::nnz`]), which is what lets elimination order pivots by fill-in and code
//! generation emit only the non-zeros. Products sum each entry's terms with one n-ary
//! [`Scalar::sum`], so an expression entry is a single sum node, not a chain.

use crate::error::SymError;
use crate::scalar::Scalar;
use nalgebra::DMatrix;

/// A sparse matrix in compressed-row form: the structural non-zeros of row `i` are
/// `entries[row_ptr[i]..row_ptr[i + 1]]`, sorted by column. One allocation per matrix, not
/// one per row, so numeric scalars pay little for the generic code.
#[derive(Clone, Debug, PartialEq)]
pub struct SparseMatrix<S> {
    nrows: usize,
    ncols: usize,
    row_ptr: Vec<usize>,
    entries: Vec<(usize, S)>,
}

/// Widest product that [`SparseMatrix::mul`] accumulates in stack scratch (a multiple of 64).
const SMALL_WIDTH: usize = 128;

/// A coordinate-list builder for [`SparseMatrix`]: push `(row, col, value)` in any order;
/// duplicates are summed (one n-ary [`Scalar::sum`] per entry) when the matrix is built.
#[derive(Clone, Debug)]
pub struct Triplets<S> {
    nrows: usize,
    ncols: usize,
    items: Vec<(usize, usize, S)>,
}

impl<S: Scalar> Triplets<S> {
    /// An empty builder for an `nrows × ncols` matrix.
    pub fn new(nrows: usize, ncols: usize) -> Self {
        Triplets {
            nrows,
            ncols,
            items: Vec::new(),
        }
    }
    /// An empty builder with room for `cap` entries (no reallocation while filling).
    pub fn with_capacity(nrows: usize, ncols: usize, cap: usize) -> Self {
        Triplets {
            nrows,
            ncols,
            items: Vec::with_capacity(cap),
        }
    }
    /// Add `v` at `(i, j)` (structural zeros are skipped).
    pub fn push(&mut self, i: usize, j: usize, v: S) {
        assert!(
            i < self.nrows && j < self.ncols,
            "index ({i}, {j}) out of bounds"
        );
        if !v.is_zero() {
            self.items.push((i, j, v));
        }
    }
    /// Build the matrix.
    pub fn build(self) -> SparseMatrix<S> {
        // Counting sort by row, then a stable insertion sort of each row's few entries by
        // column: the order of a stable sort by (row, column), so duplicates are summed in
        // insertion order, without a general sort's work and scratch allocation.
        let nrows = self.nrows;
        let mut row_ptr = vec![0usize; nrows + 1];
        for it in &self.items {
            row_ptr[it.0 + 1] += 1;
        }
        for i in 0..nrows {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut entries: Vec<(usize, S)> = vec![(0, S::zero()); self.items.len()];
        // `row_ptr[i]` serves as row i's insertion point, then holds the start of row i + 1.
        for &(i, j, v) in &self.items {
            entries[row_ptr[i]] = (j, v);
            row_ptr[i] += 1;
        }
        for i in (1..=nrows).rev() {
            row_ptr[i] = row_ptr[i - 1];
        }
        row_ptr[0] = 0;
        let mut terms: Vec<S> = Vec::new();
        let mut w = 0;
        for i in 0..nrows {
            let (a, b) = (row_ptr[i], row_ptr[i + 1]);
            let row = &mut entries[a..b];
            for k in 1..row.len() {
                let mut m = k;
                while m > 0 && row[m - 1].0 > row[m].0 {
                    row.swap(m - 1, m);
                    m -= 1;
                }
            }
            row_ptr[i] = w;
            // Sum duplicates, compacting in place (the write position never passes the read).
            let mut p = a;
            while p < b {
                let j = entries[p].0;
                let mut q = p + 1;
                while q < b && entries[q].0 == j {
                    q += 1;
                }
                let v = if q == p + 1 {
                    entries[p].1
                } else {
                    terms.clear();
                    terms.extend(entries[p..q].iter().map(|e| e.1));
                    S::sum(&terms).recognise_zero()
                };
                if !v.is_zero() {
                    entries[w] = (j, v);
                    w += 1;
                }
                p = q;
            }
        }
        row_ptr[nrows] = w;
        entries.truncate(w);
        SparseMatrix {
            nrows,
            ncols: self.ncols,
            row_ptr,
            entries,
        }
    }
}

/// `a·b`, skipping a multiplication by an exact one (for expressions, no new node).
#[inline]
fn times<S: Scalar>(a: S, b: S) -> S {
    if a.is_one() {
        b
    } else if b.is_one() {
        a
    } else {
        a * b
    }
}

impl<S: Scalar> SparseMatrix<S> {
    /// The `nrows × ncols` zero matrix.
    pub fn zeros(nrows: usize, ncols: usize) -> Self {
        SparseMatrix {
            nrows,
            ncols,
            row_ptr: vec![0; nrows + 1],
            entries: Vec::new(),
        }
    }

    /// Build row by row: `f(i, out)` pushes the non-zeros of row `i`, sorted by column.
    fn from_row_fn(nrows: usize, ncols: usize, f: impl FnMut(usize, &mut Vec<(usize, S)>)) -> Self {
        Self::from_row_fn_with(nrows, ncols, 0, f)
    }

    /// [`Self::from_row_fn`] with a capacity hint for the number of non-zeros.
    fn from_row_fn_with(
        nrows: usize,
        ncols: usize,
        nnz_hint: usize,
        mut f: impl FnMut(usize, &mut Vec<(usize, S)>),
    ) -> Self {
        let mut m = SparseMatrix {
            nrows,
            ncols,
            row_ptr: Vec::with_capacity(nrows + 1),
            entries: Vec::with_capacity(nnz_hint),
        };
        m.row_ptr.push(0);
        for i in 0..nrows {
            f(i, &mut m.entries);
            m.row_ptr.push(m.entries.len());
        }
        m
    }

    /// The identity.
    pub fn identity(n: usize) -> Self {
        Self::from_row_fn(n, n, |i, out| out.push((i, S::one())))
    }

    /// From a dense matrix (structural zeros dropped).
    pub fn from_dense(d: &DMatrix<S>) -> Self
    where
        S: nalgebra::Scalar,
    {
        Self::from_row_fn(d.nrows(), d.ncols(), |i, out| {
            for j in 0..d.ncols() {
                let v = d[(i, j)];
                if !v.is_zero() {
                    out.push((j, v));
                }
            }
        })
    }

    /// From row-major nested data.
    pub fn from_rows(rows: &[Vec<S>]) -> Result<Self, SymError> {
        let ncols = rows.first().map_or(0, |r| r.len());
        if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != ncols) {
            return Err(SymError::Dimension(format!(
                "row {i} has {} entries, row 0 has {ncols}",
                r.len()
            )));
        }
        Ok(Self::from_row_fn(rows.len(), ncols, |i, out| {
            for (j, &v) in rows[i].iter().enumerate() {
                if !v.is_zero() {
                    out.push((j, v));
                }
            }
        }))
    }

    /// From sparse rows (each sorted by column).
    pub fn from_sparse_rows<R: AsRef<[(usize, S)]>>(rows: &[R], ncols: usize) -> Self {
        let nnz = rows.iter().map(|r| r.as_ref().len()).sum();
        Self::from_row_fn_with(rows.len(), ncols, nnz, |i, out| {
            out.extend(rows[i].as_ref().iter().copied().filter(|e| !e.1.is_zero()))
        })
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }
    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }
    /// Number of structural non-zeros.
    pub fn nnz(&self) -> usize {
        self.entries.len()
    }

    /// The non-zeros of row `i`, sorted by column.
    pub fn row(&self, i: usize) -> &[(usize, S)] {
        &self.entries[self.row_ptr[i]..self.row_ptr[i + 1]]
    }

    /// Entry `(i, j)` (zero when not stored).
    pub fn get(&self, i: usize, j: usize) -> S {
        let r = self.row(i);
        match r.binary_search_by_key(&j, |e| e.0) {
            Ok(k) => r[k].1,
            Err(_) => S::zero(),
        }
    }

    /// Set entry `(i, j)`; storing a structural zero removes the entry. (Linear in the number
    /// of non-zeros: build with [`Triplets`] when setting many entries.)
    pub fn set(&mut self, i: usize, j: usize, v: S) {
        assert!(
            i < self.nrows && j < self.ncols,
            "index ({i}, {j}) out of bounds"
        );
        let (a, b) = (self.row_ptr[i], self.row_ptr[i + 1]);
        match self.entries[a..b].binary_search_by_key(&j, |e| e.0) {
            Ok(k) => {
                if v.is_zero() {
                    self.entries.remove(a + k);
                    self.row_ptr[i + 1..].iter_mut().for_each(|p| *p -= 1);
                } else {
                    self.entries[a + k].1 = v;
                }
            }
            Err(k) => {
                if !v.is_zero() {
                    self.entries.insert(a + k, (j, v));
                    self.row_ptr[i + 1..].iter_mut().for_each(|p| *p += 1);
                }
            }
        }
    }

    /// `self[(i, j)] += v`.
    pub fn add_to(&mut self, i: usize, j: usize, v: S) {
        if v.is_zero() {
            return;
        }
        let cur = self.get(i, j);
        self.set(
            i,
            j,
            if cur.is_zero() {
                v
            } else {
                (cur + v).recognise_zero()
            },
        );
    }

    /// All non-zeros as `(row, col, value)`, row-major.
    pub fn iter(&self) -> impl Iterator<Item = (usize, usize, S)> + '_ {
        (0..self.nrows).flat_map(move |i| self.row(i).iter().map(move |&(j, v)| (i, j, v)))
    }

    /// The sparsity pattern as `(row, col)` pairs.
    pub fn pattern(&self) -> Vec<(usize, usize)> {
        self.iter().map(|(i, j, _)| (i, j)).collect()
    }

    /// Transpose.
    pub fn transpose(&self) -> Self {
        // Counting sort by column keeps each new row sorted.
        let mut count = vec![0usize; self.ncols + 1];
        for &(j, _) in &self.entries {
            count[j + 1] += 1;
        }
        for j in 0..self.ncols {
            count[j + 1] += count[j];
        }
        let row_ptr = count.clone();
        let mut next = count;
        let mut entries: Vec<(usize, S)> = Vec::with_capacity(self.entries.len());
        // SAFETY-free fill: place into a vector of options, then unwrap.
        let mut slots: Vec<Option<(usize, S)>> = vec![None; self.entries.len()];
        for (i, j, v) in self.iter() {
            slots[next[j]] = Some((i, v));
            next[j] += 1;
        }
        entries.extend(slots.into_iter().map(|e| e.expect("every slot filled")));
        SparseMatrix {
            nrows: self.ncols,
            ncols: self.nrows,
            row_ptr,
            entries,
        }
    }

    /// Apply `f` to every non-zero (results that are structural zeros are dropped).
    pub fn map<T: Scalar>(&self, mut f: impl FnMut(S) -> T) -> SparseMatrix<T> {
        SparseMatrix::from_row_fn_with(self.nrows, self.ncols, self.nnz(), |i, out| {
            for &(j, v) in self.row(i) {
                let w = f(v);
                if !w.is_zero() {
                    out.push((j, w));
                }
            }
        })
    }

    /// `self · other`; every entry is one n-ary sum of its product terms.
    pub fn mul(&self, other: &Self) -> Result<Self, SymError> {
        if self.ncols != other.nrows {
            return Err(SymError::Dimension(format!(
                "product of {}×{} and {}×{}",
                self.nrows, self.ncols, other.nrows, other.ncols
            )));
        }
        // Flat accumulator: (column, product) pairs of one row, grouped by column; sized for
        // the row with the most products so that it never grows.
        let (mut products, mut row_max) = (0, 0);
        for i in 0..self.nrows {
            let p: usize = self
                .row(i)
                .iter()
                .map(|&(k, _)| other.row_ptr[k + 1] - other.row_ptr[k])
                .sum();
            products += p;
            row_max = row_max.max(p);
        }
        let nnz_hint = products.min(self.nrows * other.ncols);
        if S::FOLD_SUM {
            if other.ncols <= SMALL_WIDTH {
                return Ok(self.mul_small(other, nnz_hint));
            }
            return Ok(self.mul_dense_acc(other, row_max, nnz_hint));
        }
        let mut acc: Vec<(usize, S)> = Vec::with_capacity(row_max);
        let mut terms: Vec<S> = Vec::with_capacity(row_max.min(self.ncols));
        Ok(Self::from_row_fn_with(
            self.nrows,
            other.ncols,
            nnz_hint,
            |i, out| {
                acc.clear();
                for &(k, a) in self.row(i) {
                    for &(j, b) in other.row(k) {
                        acc.push((j, times(a, b)));
                    }
                }
                acc.sort_by_key(|e| e.0);
                let mut p = 0;
                while p < acc.len() {
                    let j = acc[p].0;
                    terms.clear();
                    while p < acc.len() && acc[p].0 == j {
                        terms.push(acc[p].1);
                        p += 1;
                    }
                    let v = if terms.len() == 1 {
                        terms[0]
                    } else {
                        S::sum(&terms).recognise_zero()
                    };
                    if !v.is_zero() {
                        out.push((j, v));
                    }
                }
            },
        ))
    }

    /// [`Self::mul_dense_acc`] for products at most [`SMALL_WIDTH`] columns wide: the dense
    /// row lives on the stack and a bit mask marks the touched columns, which also lists them
    /// in order without a sort. Same terms in the same order, so the same values; what it
    /// saves is the scratch allocations (most products of a reduction are this narrow).
    fn mul_small(&self, other: &Self, nnz_hint: usize) -> Self {
        let mut dense = [S::zero(); SMALL_WIDTH];
        let mut mask = [0u64; SMALL_WIDTH / 64];
        Self::from_row_fn_with(self.nrows, other.ncols, nnz_hint, |i, out| {
            for &(k, a) in self.row(i) {
                for &(j, b) in other.row(k) {
                    let p = times(a, b);
                    let (w, bit) = (j / 64, 1u64 << (j % 64));
                    if mask[w] & bit == 0 {
                        mask[w] |= bit;
                        dense[j] = p;
                    } else {
                        dense[j] = dense[j] + p;
                    }
                }
            }
            for (w, m) in mask.iter_mut().enumerate() {
                while *m != 0 {
                    let j = 64 * w + m.trailing_zeros() as usize;
                    *m &= *m - 1;
                    let v = dense[j];
                    if !v.is_zero() {
                        out.push((j, v));
                    }
                }
            }
        })
    }

    /// [`Self::mul`] for scalars whose sums are folds: each entry is accumulated in a dense
    /// row in the order its terms arise, which is the order `mul` would sum them in (the
    /// value differs only in the sign of a zero result, which is dropped either way).
    fn mul_dense_acc(&self, other: &Self, row_max: usize, nnz_hint: usize) -> Self {
        let mut dense = vec![S::zero(); other.ncols];
        // Row (plus one) that last touched each column: no clearing between rows.
        let mut stamp = vec![0usize; other.ncols];
        let mut cols: Vec<usize> = Vec::with_capacity(row_max.min(other.ncols));
        Self::from_row_fn_with(self.nrows, other.ncols, nnz_hint, |i, out| {
            cols.clear();
            for &(k, a) in self.row(i) {
                for &(j, b) in other.row(k) {
                    let p = times(a, b);
                    if stamp[j] != i + 1 {
                        stamp[j] = i + 1;
                        dense[j] = p;
                        cols.push(j);
                    } else {
                        dense[j] = dense[j] + p;
                    }
                }
            }
            cols.sort_unstable();
            for &j in &cols {
                let v = dense[j];
                if !v.is_zero() {
                    out.push((j, v));
                }
            }
        })
    }

    /// `self + other`.
    pub fn add(&self, other: &Self) -> Result<Self, SymError> {
        self.combine(other, false)
    }
    /// `self − other`.
    pub fn sub(&self, other: &Self) -> Result<Self, SymError> {
        self.combine(other, true)
    }

    fn combine(&self, other: &Self, negate: bool) -> Result<Self, SymError> {
        if self.nrows != other.nrows || self.ncols != other.ncols {
            return Err(SymError::Dimension(format!(
                "sum of {}×{} and {}×{}",
                self.nrows, self.ncols, other.nrows, other.ncols
            )));
        }
        Ok(Self::from_row_fn_with(
            self.nrows,
            self.ncols,
            self.nnz() + other.nnz(),
            |i, out| {
                let (a, b) = (self.row(i), other.row(i));
                let (mut p, mut q) = (0, 0);
                while p < a.len() || q < b.len() {
                    let ja = a.get(p).map_or(usize::MAX, |e| e.0);
                    let jb = b.get(q).map_or(usize::MAX, |e| e.0);
                    let (j, v) = if ja < jb {
                        p += 1;
                        (ja, a[p - 1].1)
                    } else if jb < ja {
                        q += 1;
                        (jb, if negate { -b[q - 1].1 } else { b[q - 1].1 })
                    } else {
                        p += 1;
                        q += 1;
                        let (x, y) = (a[p - 1].1, b[q - 1].1);
                        (ja, (if negate { x - y } else { x + y }).recognise_zero())
                    };
                    if !v.is_zero() {
                        out.push((j, v));
                    }
                }
            },
        ))
    }

    /// `c · self`.
    pub fn scale(&self, c: S) -> Self {
        if c.is_zero() {
            return Self::zeros(self.nrows, self.ncols);
        }
        self.map(|v| c * v)
    }

    /// `−self`.
    pub fn neg(&self) -> Self {
        self.map(|v| -v)
    }

    /// Rows `rows` and columns `cols` (in the given order).
    pub fn select(&self, rows: &[usize], cols: &[usize]) -> Self {
        self.select_with(rows.len(), |k| rows[k], cols)
    }

    /// Every row, columns `cols` (in the given order).
    pub fn columns_of(&self, cols: &[usize]) -> Self {
        self.select_with(self.nrows, |k| k, cols)
    }

    fn select_with(&self, nrows: usize, row_of: impl Fn(usize) -> usize, cols: &[usize]) -> Self {
        let mut colmap = vec![usize::MAX; self.ncols];
        for (k, &c) in cols.iter().enumerate() {
            colmap[c] = k;
        }
        let monotone = cols.windows(2).all(|w| w[0] < w[1]);
        Self::from_row_fn_with(
            nrows,
            cols.len(),
            self.nnz().min(nrows * cols.len()),
            |k, out| {
                let start = out.len();
                for &(j, v) in self.row(row_of(k)) {
                    if colmap[j] != usize::MAX {
                        out.push((colmap[j], v));
                    }
                }
                if !monotone {
                    out[start..].sort_by_key(|e| e.0);
                }
            },
        )
    }

    /// Rows `rows` (in the given order), every column: [`Self::select`] without a column map.
    pub fn select_rows(&self, rows: &[usize]) -> Self {
        let nnz = rows.iter().map(|&i| self.row(i).len()).sum();
        Self::from_row_fn_with(rows.len(), self.ncols, nnz, |k, out| {
            out.extend_from_slice(self.row(rows[k]))
        })
    }

    /// The contiguous columns `cols`, every row.
    pub fn columns(&self, cols: std::ops::Range<usize>) -> Self {
        assert!(cols.end <= self.ncols, "columns {cols:?} out of bounds");
        let nnz = (0..self.nrows)
            .map(|i| {
                let r = self.row(i);
                r.partition_point(|e| e.0 < cols.end) - r.partition_point(|e| e.0 < cols.start)
            })
            .sum();
        Self::from_row_fn_with(self.nrows, cols.len(), nnz, |i, out| {
            let r = self.row(i);
            let a = r.partition_point(|e| e.0 < cols.start);
            let b = r.partition_point(|e| e.0 < cols.end);
            out.extend(r[a..b].iter().map(|&(j, v)| (j - cols.start, v)));
        })
    }

    /// `[b₀ b₁ …]`: blocks side by side (all of the same height). The direct form of a
    /// one-row [`Self::block`], without its bookkeeping.
    pub fn hcat(blocks: &[&Self]) -> Result<Self, SymError> {
        let nrows = blocks.first().map_or(0, |b| b.nrows);
        if let Some(b) = blocks.iter().find(|b| b.nrows != nrows) {
            return Err(SymError::Dimension(format!(
                "side-by-side blocks of heights {nrows} and {}",
                b.nrows
            )));
        }
        let ncols = blocks.iter().map(|b| b.ncols).sum();
        let nnz = blocks.iter().map(|b| b.nnz()).sum();
        Ok(Self::from_row_fn_with(nrows, ncols, nnz, |i, out| {
            let mut c0 = 0;
            for b in blocks {
                out.extend(b.row(i).iter().map(|&(j, v)| (c0 + j, v)));
                c0 += b.ncols;
            }
        }))
    }

    /// `[self 0]`: the same rows, widened to `ncols` columns by zero columns on the right
    /// (no copy: the entries are unchanged).
    pub fn widen(mut self, ncols: usize) -> Self {
        assert!(ncols >= self.ncols, "cannot widen to fewer columns");
        self.ncols = ncols;
        self
    }

    /// `[0; self]`: `k` zero rows above the same rows (the entries are not copied).
    pub fn below_zero_rows(mut self, k: usize) -> Self {
        let mut row_ptr = Vec::with_capacity(k + self.row_ptr.len());
        row_ptr.resize(k, 0);
        row_ptr.extend_from_slice(&self.row_ptr);
        self.row_ptr = row_ptr;
        self.nrows += k;
        self
    }

    /// `[a; b]`: `a` above `b` (of the same width).
    pub fn vcat(a: &Self, b: &Self) -> Result<Self, SymError> {
        if a.ncols != b.ncols {
            return Err(SymError::Dimension(format!(
                "stacked blocks of widths {} and {}",
                a.ncols, b.ncols
            )));
        }
        let mut row_ptr = Vec::with_capacity(a.nrows + b.nrows + 1);
        row_ptr.extend_from_slice(&a.row_ptr);
        let off = a.entries.len();
        row_ptr.extend(b.row_ptr[1..].iter().map(|p| p + off));
        let mut entries = Vec::with_capacity(a.nnz() + b.nnz());
        entries.extend_from_slice(&a.entries);
        entries.extend_from_slice(&b.entries);
        Ok(SparseMatrix {
            nrows: a.nrows + b.nrows,
            ncols: a.ncols,
            row_ptr,
            entries,
        })
    }

    /// Assemble a block matrix from a grid of optional blocks (`None` = zero block). Every
    /// block row needs at least one block to fix its height, every block column likewise.
    pub fn block(grid: &[Vec<Option<&SparseMatrix<S>>>]) -> Result<Self, SymError> {
        let nbr = grid.len();
        let nbc = grid.first().map_or(0, Vec::len);
        let mut heights = vec![None; nbr];
        let mut widths = vec![None; nbc];
        for (bi, row) in grid.iter().enumerate() {
            if row.len() != nbc {
                return Err(SymError::Dimension(format!(
                    "block row {bi} has {} blocks, expected {nbc}",
                    row.len()
                )));
            }
            for (bj, b) in row.iter().enumerate() {
                if let Some(b) = b {
                    for (slot, v, what) in [
                        (&mut heights[bi], b.nrows, "height"),
                        (&mut widths[bj], b.ncols, "width"),
                    ] {
                        match *slot {
                            None => *slot = Some(v),
                            Some(h) if h != v => {
                                return Err(SymError::Dimension(format!(
                                    "block ({bi}, {bj}) has {what} {v}, its neighbours {h}"
                                )));
                            }
                            _ => {}
                        }
                    }
                }
            }
        }
        let heights: Vec<usize> = heights.into_iter().map(|h| h.unwrap_or(0)).collect();
        let widths: Vec<usize> = widths.into_iter().map(|w| w.unwrap_or(0)).collect();
        let mut col0 = vec![0; nbc];
        for bj in 1..nbc {
            col0[bj] = col0[bj - 1] + widths[bj - 1];
        }
        let mut rowmap = Vec::with_capacity(heights.iter().sum());
        for (bi, &h) in heights.iter().enumerate() {
            for i in 0..h {
                rowmap.push((bi, i));
            }
        }
        let nnz: usize = grid.iter().flatten().flatten().map(|b| b.nnz()).sum();
        Ok(Self::from_row_fn_with(
            rowmap.len(),
            widths.iter().sum(),
            nnz,
            |r, out| {
                let (bi, i) = rowmap[r];
                for (bj, b) in grid[bi].iter().enumerate() {
                    if let Some(b) = b {
                        out.extend(b.row(i).iter().map(|&(j, v)| (col0[bj] + j, v)));
                    }
                }
            },
        ))
    }

    /// Dense copy.
    pub fn to_dense(&self) -> DMatrix<S>
    where
        S: nalgebra::Scalar,
    {
        let mut d = DMatrix::from_element(self.nrows, self.ncols, S::zero());
        for (i, j, v) in self.iter() {
            d[(i, j)] = v;
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Expr;

    #[test]
    fn products_and_blocks_keep_zeros_structural() {
        let a = Expr::param("a", 1.0).unwrap();
        let b = Expr::param("b", 2.0).unwrap();
        let m = SparseMatrix::from_rows(&[vec![a, Expr::zero()], vec![Expr::zero(), b]]).unwrap();
        assert_eq!(m.nnz(), 2);
        let p = m.mul(&m.transpose()).unwrap();
        assert_eq!(p.nnz(), 2);
        assert_eq!(p.get(0, 0), a * a);
        let blk = SparseMatrix::block(&[vec![Some(&m), None], vec![None, Some(&m)]]).unwrap();
        assert_eq!((blk.nrows(), blk.ncols(), blk.nnz()), (4, 4, 4));
        assert_eq!(blk.get(3, 3), b);
        let d = m.sub(&m).unwrap();
        assert_eq!(d.nnz(), 0);
        assert!(m.mul(&SparseMatrix::zeros(3, 1)).is_err());
    }
}
