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

/// A sparse matrix: each row holds its structural non-zeros sorted by column.
#[derive(Clone, Debug, PartialEq)]
pub struct SparseMatrix<S> {
    nrows: usize,
    ncols: usize,
    rows: Vec<Vec<(usize, S)>>,
}

impl<S: Scalar> SparseMatrix<S> {
    /// The `nrows × ncols` zero matrix.
    pub fn zeros(nrows: usize, ncols: usize) -> Self {
        SparseMatrix { nrows, ncols, rows: vec![Vec::new(); nrows] }
    }

    /// The identity.
    pub fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m.rows[i].push((i, S::one()));
        }
        m
    }

    /// From a dense matrix (structural zeros dropped).
    pub fn from_dense(d: &DMatrix<S>) -> Self
    where
        S: nalgebra::Scalar,
    {
        let mut m = Self::zeros(d.nrows(), d.ncols());
        for i in 0..d.nrows() {
            for j in 0..d.ncols() {
                let v = d[(i, j)];
                if !v.is_zero() {
                    m.rows[i].push((j, v));
                }
            }
        }
        m
    }

    /// From row-major nested data.
    pub fn from_rows(rows: &[Vec<S>]) -> Result<Self, SymError> {
        let ncols = rows.first().map_or(0, |r| r.len());
        let mut m = Self::zeros(rows.len(), ncols);
        for (i, r) in rows.iter().enumerate() {
            if r.len() != ncols {
                return Err(SymError::Dimension(format!(
                    "row {i} has {} entries, row 0 has {ncols}",
                    r.len()
                )));
            }
            for (j, &v) in r.iter().enumerate() {
                if !v.is_zero() {
                    m.rows[i].push((j, v));
                }
            }
        }
        Ok(m)
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
        self.rows.iter().map(Vec::len).sum()
    }

    /// Entry `(i, j)` (zero when not stored).
    pub fn get(&self, i: usize, j: usize) -> S {
        match self.rows[i].binary_search_by_key(&j, |e| e.0) {
            Ok(k) => self.rows[i][k].1,
            Err(_) => S::zero(),
        }
    }

    /// Set entry `(i, j)`; storing a structural zero removes the entry.
    pub fn set(&mut self, i: usize, j: usize, v: S) {
        assert!(i < self.nrows && j < self.ncols, "index ({i}, {j}) out of bounds");
        let row = &mut self.rows[i];
        match row.binary_search_by_key(&j, |e| e.0) {
            Ok(k) => {
                if v.is_zero() {
                    row.remove(k);
                } else {
                    row[k].1 = v;
                }
            }
            Err(k) => {
                if !v.is_zero() {
                    row.insert(k, (j, v));
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
        self.set(i, j, if cur.is_zero() { v } else { (cur + v).recognise_zero() });
    }

    /// The non-zeros of row `i`, sorted by column.
    pub fn row(&self, i: usize) -> &[(usize, S)] {
        &self.rows[i]
    }

    /// All non-zeros as `(row, col, value)`, row-major.
    pub fn iter(&self) -> impl Iterator<Item = (usize, usize, S)> + '_ {
        self.rows.iter().enumerate().flat_map(|(i, r)| r.iter().map(move |&(j, v)| (i, j, v)))
    }

    /// The sparsity pattern as `(row, col)` pairs.
    pub fn pattern(&self) -> Vec<(usize, usize)> {
        self.iter().map(|(i, j, _)| (i, j)).collect()
    }

    /// Transpose.
    pub fn transpose(&self) -> Self {
        let mut t = Self::zeros(self.ncols, self.nrows);
        for (i, j, v) in self.iter() {
            t.rows[j].push((i, v));
        }
        t
    }

    /// Apply `f` to every non-zero (results that are structural zeros are dropped).
    pub fn map<T: Scalar>(&self, mut f: impl FnMut(S) -> T) -> SparseMatrix<T> {
        let mut m = SparseMatrix::zeros(self.nrows, self.ncols);
        for (i, r) in self.rows.iter().enumerate() {
            for &(j, v) in r {
                let w = f(v);
                if !w.is_zero() {
                    m.rows[i].push((j, w));
                }
            }
        }
        m
    }

    /// `self · other`; every entry is one n-ary sum of its product terms.
    pub fn mul(&self, other: &Self) -> Result<Self, SymError> {
        if self.ncols != other.nrows {
            return Err(SymError::Dimension(format!(
                "product of {}×{} and {}×{}",
                self.nrows, self.ncols, other.nrows, other.ncols
            )));
        }
        let mut out = Self::zeros(self.nrows, other.ncols);
        let mut acc: Vec<Vec<S>> = vec![Vec::new(); other.ncols];
        let mut touched: Vec<usize> = Vec::new();
        for i in 0..self.nrows {
            for &(k, a) in &self.rows[i] {
                for &(j, b) in &other.rows[k] {
                    if acc[j].is_empty() {
                        touched.push(j);
                    }
                    acc[j].push(if a.is_one() { b } else if b.is_one() { a } else { a * b });
                }
            }
            touched.sort_unstable();
            for &j in &touched {
                let v = S::sum(&acc[j]).recognise_zero();
                acc[j].clear();
                if !v.is_zero() {
                    out.rows[i].push((j, v));
                }
            }
            touched.clear();
        }
        Ok(out)
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
        let mut out = Self::zeros(self.nrows, self.ncols);
        for i in 0..self.nrows {
            let (a, b) = (&self.rows[i], &other.rows[i]);
            let (mut p, mut q) = (0, 0);
            let row = &mut out.rows[i];
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
                    row.push((j, v));
                }
            }
        }
        Ok(out)
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
        let mut colmap = vec![usize::MAX; self.ncols];
        for (k, &c) in cols.iter().enumerate() {
            colmap[c] = k;
        }
        let mut out = Self::zeros(rows.len(), cols.len());
        for (k, &r) in rows.iter().enumerate() {
            for &(j, v) in &self.rows[r] {
                if colmap[j] != usize::MAX {
                    out.rows[k].push((colmap[j], v));
                }
            }
            out.rows[k].sort_by_key(|e| e.0);
        }
        out
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
                return Err(SymError::Dimension(format!("block row {bi} has {} blocks, expected {nbc}", row.len())));
            }
            for (bj, b) in row.iter().enumerate() {
                if let Some(b) = b {
                    for (slot, v, what) in [(&mut heights[bi], b.nrows, "height"), (&mut widths[bj], b.ncols, "width")] {
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
        let mut out = Self::zeros(heights.iter().sum(), widths.iter().sum());
        let mut r0 = 0;
        for (bi, row) in grid.iter().enumerate() {
            let mut c0 = 0;
            for (bj, b) in row.iter().enumerate() {
                if let Some(b) = b {
                    for (i, j, v) in b.iter() {
                        out.rows[r0 + i].push((c0 + j, v));
                    }
                }
                c0 += widths[bj];
            }
            for r in &mut out.rows[r0..r0 + heights[bi]] {
                r.sort_by_key(|e| e.0);
            }
            r0 += heights[bi];
        }
        Ok(out)
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
