//! Zero eigenvalues that the structure proves: states, or pairs of states, on which nothing
//! depends.
//!
//! A state whose column of A is exactly zero (no equation depends on it: a vehicle's lateral
//! position, say) contributes an exact zero eigenvalue. So does a pair of states on which the
//! equations depend only through their difference or sum — two columns that are exact
//! negatives (or copies) of each other, as the headings of two bodies of a vehicle when only
//! their relative yaw matters: the change of coordinates `x_j → x_j ∓ x_i` (exact, with
//! integer coefficients) turns the pair into one state with a zero column and one with the
//! combined column. Removing such states may leave further ones among the rest (the heading,
//! on which only the lateral position depended), and so on. With the states found ordered
//! last, in reverse order of finding, the transformed matrix is block lower-triangular
//! `[[A_KK, 0], [A_RK, L]]` with `L` strictly lower triangular: the eigenvalues are those of
//! `A_KK` and exactly `|R|` zeros.
//!
//! Left in the matrix, such a zero pair is defective (a Jordan block: the heading integrates
//! into the lateral position), and an eigensolver splits it into `±√ε·‖A‖`, which pollutes
//! small eigenvalues nearby (a bicycle's capsize root at 6 m/s lost three digits). Deflating
//! it first keeps every other eigenvalue to the accuracy of `A_KK`.
//!
//! A structural zero of the reduction is an exact `0.0`, or a residue of rounding below
//! [`CHOP_ULPS`]`·n·ε` times its row's largest entry, which is set to zero first. Two columns that depend on a
//! difference of coordinates are negatives of each other up to the rounding of their separate
//! computations: they count when every entry agrees to within [`PAIR_ULPS`] units in the last
//! place, with the same zeros (pairs that agree so closely in every entry by accident do not
//! occur), and are then made exact. A matrix with rounding noise above that level in its zero
//! columns (the robust path's orthonormal bases) is left as it is: its structural zeros are
//! deflated orthogonally when their number is known ([`deflate_null_directions`]).

/// Relative agreement, in units of `f64::EPSILON`, for two columns to count as equal up to sign.
pub const PAIR_ULPS: f64 = 4096.0;

/// One change of coordinates `x_j = x̃_j − s·x̃_i` (`s = ±1`): after it, state `i`'s column is
/// `col_i − s·col_j`, zero on the states still kept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Combine {
    /// The state whose column becomes zero.
    pub i: usize,
    /// The state it is combined with.
    pub j: usize,
    /// `±1`.
    pub s: f64,
}

/// The structural zero states of `a` (column-major n × n, transformed in place by the
/// combinations found): `removed` marks them, `order` lists them in the order found, and
/// `combos` the changes of coordinates applied (in order). `keys` is scratch (length n).
pub(crate) fn deflate_in_place(
    a: &mut [f64],
    n: usize,
    removed: &mut [bool],
    order: &mut Vec<usize>,
    combos: &mut Vec<Combine>,
    keys: &mut Vec<(u64, usize)>,
) {
    removed.iter_mut().for_each(|r| *r = false);
    order.clear();
    combos.clear();
    chop(a, n);
    loop {
        let before = order.len();
        remove_zero_columns(a, n, removed, |j| order.push(j));
        if let Some(c) = find_pair(a, n, removed, keys) {
            apply(a, n, c, removed);
            combos.push(c);
            // State i's column is now zero on the kept rows.
            removed[c.i] = true;
            order.push(c.i);
        }
        if order.len() == before {
            return;
        }
    }
}

/// Relative size, in units of `n·f64::EPSILON` times the largest entry of its row, below which
/// an entry counts as a rounding residue of zero (see [`chop`]).
pub const CHOP_ULPS: f64 = 8.0;

/// Entries below [`CHOP_ULPS`]`·n·ε` times the largest of their row set to exactly zero.
///
/// A reduction by floating-point elimination leaves residues of that size where the exact
/// matrix has zeros (the column of a vehicle's lateral position at parameter values whose
/// products do not cancel exactly); left in, they hide the structure. Setting them to zero is
/// a perturbation of the size the eigensolver's own backward error has anyway.
fn chop(a: &mut [f64], n: usize) {
    for i in 0..n {
        let scale = (0..n).fold(0.0f64, |m, j| m.max(a[j * n + i].abs()));
        let tol = CHOP_ULPS * n as f64 * f64::EPSILON * scale;
        for j in 0..n {
            if a[j * n + i].abs() <= tol {
                a[j * n + i] = 0.0;
            }
        }
    }
}

/// [`deflate_in_place`] for matrices of at most [`crate::small_eigen::MAX_N`] states, without
/// recording the changes of coordinates and without allocation: the number of structural
/// zeros (`removed` marks them; `a` is transformed as there). The same decisions in the same
/// order, found through each column's pattern of nonzero rows as a bit mask (a zero column
/// and a candidate pair are then one comparison of masks each).
pub(crate) fn deflate_small(a: &mut [f64], n: usize, removed: &mut [bool]) -> usize {
    deflate_small_recorded(a, n, removed, |_| ())
}

/// One decision of [`deflate_small`], in the order taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum DeflationStep {
    /// A state whose column is zero on the states kept at that moment.
    Zero(usize),
    /// A pair combined by the change of coordinates.
    Pair(Combine),
}

/// [`deflate_small`], telling `step` of each decision.
pub(crate) fn deflate_small_recorded(
    a: &mut [f64],
    n: usize,
    removed: &mut [bool],
    mut step: impl FnMut(DeflationStep),
) -> usize {
    debug_assert!(n <= crate::small_eigen::MAX_N && a.len() == n * n);
    removed.iter_mut().for_each(|r| *r = false);
    if n == 0 {
        return 0;
    }
    let mut masks = [0u32; crate::small_eigen::MAX_N];
    chop_with_masks(a, n, &mut masks);
    let mut kept: u32 = (1u32 << n) - 1;
    let mut count = 0;
    loop {
        let before = count;
        // Zero columns on the kept rows, repeatedly (in increasing order, as
        // `remove_zero_columns`).
        loop {
            let mut any = false;
            for j in 0..n {
                if kept & (1 << j) != 0 && masks[j] & kept == 0 {
                    kept &= !(1 << j);
                    removed[j] = true;
                    step(DeflationStep::Zero(j));
                    count += 1;
                    any = true;
                }
            }
            if !any {
                break;
            }
        }
        // The first pair (i < j) of kept columns with the same pattern that agree.
        let mut found = None;
        'search: for i in (0..n).filter(|&i| kept & (1 << i) != 0) {
            for j in (i + 1..n).filter(|&j| kept & (1 << j) != 0) {
                if masks[i] & kept == masks[j] & kept
                    && let Some(c) = pair(a, n, removed, i, j)
                {
                    found = Some(c);
                    break 'search;
                }
            }
        }
        if let Some(c) = found {
            step(DeflationStep::Pair(c));
            apply(a, n, c, removed);
            removed[c.i] = true;
            kept &= !(1 << c.i);
            count += 1;
            // The change of coordinates moved entries of row j in every column.
            for (col, m) in a.chunks_exact(n).zip(masks.iter_mut()) {
                *m = col
                    .iter()
                    .enumerate()
                    .fold(0, |m, (r, x)| if *x != 0.0 { m | (1 << r) } else { m });
            }
        }
        if count == before {
            return count;
        }
    }
}

/// Replays recorded decisions of [`deflate_small_recorded`] on another matrix of the same
/// structure: each is checked as it is taken (a zero column exactly zero on the states kept
/// at that moment, after the chop; a pair agreeing as [`find_pair`] requires) and applied.
/// `None` when one does not hold (the caller then searches afresh), else the number of
/// structural zeros. Zeros the recorded matrix did not have are not searched for.
pub(crate) fn replay_small(
    a: &mut [f64],
    n: usize,
    removed: &mut [bool],
    steps: &[DeflationStep],
) -> Option<usize> {
    removed.iter_mut().for_each(|r| *r = false);
    let mut masks = [0u32; crate::small_eigen::MAX_N];
    chop_with_masks(a, n, &mut masks);
    for s in steps {
        match *s {
            DeflationStep::Zero(j) => {
                let col = &a[j * n..(j + 1) * n];
                if removed[j] || col.iter().zip(&*removed).any(|(x, r)| !r && *x != 0.0) {
                    return None;
                }
                removed[j] = true;
            }
            DeflationStep::Pair(c) => {
                if removed[c.i] || removed[c.j] || pair(a, n, removed, c.i, c.j) != Some(c) {
                    return None;
                }
                apply(a, n, c, removed);
                removed[c.i] = true;
            }
        }
    }
    Some(steps.len())
}

/// [`chop`], and each column's nonzero rows as a bit mask.
fn chop_with_masks(a: &mut [f64], n: usize, masks: &mut [u32]) {
    let mut row_max = [0.0f64; crate::small_eigen::MAX_N];
    for col in a.chunks_exact(n) {
        for (m, x) in row_max.iter_mut().zip(col) {
            *m = m.max(x.abs());
        }
    }
    let f = CHOP_ULPS * n as f64 * f64::EPSILON;
    for (col, mask) in a.chunks_exact_mut(n).zip(masks.iter_mut()) {
        let mut m = 0;
        for (r, (x, rm)) in col.iter_mut().zip(&row_max).enumerate() {
            if x.abs() <= f * rm {
                *x = 0.0;
            } else {
                m |= 1 << r;
            }
        }
        *mask = m;
    }
}

/// Removes states with a zero column (on the kept rows) until none is left, telling `found`
/// of each in order.
fn remove_zero_columns(a: &[f64], n: usize, removed: &mut [bool], mut found: impl FnMut(usize)) {
    loop {
        let mut any = false;
        for j in 0..n {
            if removed[j] {
                continue;
            }
            let col = &a[j * n..(j + 1) * n];
            if (0..n).all(|i| removed[i] || col[i] == 0.0) {
                removed[j] = true;
                found(j);
                any = true;
            }
        }
        if !any {
            return;
        }
    }
}

/// Two kept columns equal up to sign on the kept rows (the first such pair).
fn find_pair(
    a: &[f64],
    n: usize,
    removed: &[bool],
    keys: &mut Vec<(u64, usize)>,
) -> Option<Combine> {
    if n <= crate::small_eigen::MAX_N {
        // The same answer as the small kernel's (which has no room for keys).
        return find_pair_among_few(a, n, removed);
    }
    keys.clear();
    for j in (0..n).filter(|&j| !removed[j]) {
        keys.push((column_key(&a[j * n..(j + 1) * n], removed), j));
    }
    keys.sort_unstable();
    for w in keys.windows(2) {
        let ((k1, i), (k2, j)) = (w[0], w[1]);
        if k1 != k2 {
            continue;
        }
        if let Some(c) = pair(a, n, removed, i, j) {
            return Some(c);
        }
    }
    None
}

/// [`find_pair`] by comparing every two kept columns (i < j, the first pair in that order):
/// for a few states cheaper than hashing and sorting, and it misses no pair.
fn find_pair_among_few(a: &[f64], n: usize, removed: &[bool]) -> Option<Combine> {
    for i in (0..n).filter(|&i| !removed[i]) {
        for j in (i + 1..n).filter(|&j| !removed[j]) {
            if let Some(c) = pair(a, n, removed, i, j) {
                return Some(c);
            }
        }
    }
    None
}

/// Whether kept columns i and j agree up to sign (to [`PAIR_ULPS`], with the same zeros) on
/// the kept rows.
fn pair(a: &[f64], n: usize, removed: &[bool], i: usize, j: usize) -> Option<Combine> {
    let (ci, cj) = (&a[i * n..(i + 1) * n], &a[j * n..(j + 1) * n]);
    for s in [1.0, -1.0] {
        let same = |r: usize| {
            let (x, y) = (ci[r], s * cj[r]);
            (x == 0.0) == (y == 0.0) && (x - y).abs() <= PAIR_ULPS * f64::EPSILON * x.abs()
        };
        if (0..n).all(|r| removed[r] || same(r)) {
            return Some(Combine { i, j, s });
        }
    }
    None
}

/// A hash of a column's kept entries that is invariant under a change of sign and under
/// rounding differences below [`PAIR_ULPS`]: the zero pattern and, per entry, the sign relative
/// to the first nonzero and the binary exponent of the magnitude rounded to a multiple of 2
/// (nearly equal numbers straddling a power of two fall into neighbouring keys and are then not
/// paired: a missed pair, never a wrong one).
fn column_key(col: &[f64], removed: &[bool]) -> u64 {
    let sign = col
        .iter()
        .zip(removed)
        .find(|(x, r)| !**r && **x != 0.0)
        .map_or(1.0, |(x, _)| x.signum());
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for (x, r) in col.iter().zip(removed) {
        if !*r {
            let v = sign * x;
            let code: u64 = if v == 0.0 {
                0
            } else {
                let e = (v.abs().log2().floor() as i64).div_euclid(2) as u64;
                (e << 2) | if v > 0.0 { 1 } else { 2 }
            };
            h = (h ^ code).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// `A ← T⁻¹ A T` with `T = I − s·e_j e_iᵀ`: column i ← col_i − s·col_j, then
/// row j ← row_j + s·row_i.
fn apply(a: &mut [f64], n: usize, c: Combine, removed: &[bool]) {
    // The kept entries of column i are s·(column j) (to rounding): make them exactly so.
    for r in 0..n {
        if !removed[r] {
            a[c.i * n + r] = c.s * a[c.j * n + r];
        }
    }
    for r in 0..n {
        a[c.i * n + r] -= c.s * a[c.j * n + r];
    }
    for k in 0..n {
        let add = c.s * a[k * n + c.i];
        a[k * n + c.j] += add;
    }
}

/// Copies the kept rows and columns of `a` (column-major n × n) into `out` (m × m).
pub(crate) fn kept_block(a: &[f64], n: usize, removed: &[bool], out: &mut [f64]) -> usize {
    let kept: usize = removed.iter().filter(|r| !**r).count();
    let mut k = 0;
    for j in (0..n).filter(|&j| !removed[j]) {
        for i in (0..n).filter(|&i| !removed[i]) {
            out[k] = a[j * n + i];
            k += 1;
        }
    }
    debug_assert_eq!(k, kept * kept);
    kept
}

/// The number of zero eigenvalues the structure of `a` proves (see the module docs).
pub fn structural_zero_count(a: &nalgebra::DMatrix<f64>) -> usize {
    let n = a.nrows();
    if a.ncols() != n {
        return 0;
    }
    let mut t = a.as_slice().to_vec();
    let (mut removed, mut order, mut combos, mut keys) = (vec![false; n], vec![], vec![], vec![]);
    deflate_in_place(&mut t, n, &mut removed, &mut order, &mut combos, &mut keys);
    order.len()
}

/// A system in the coordinates that make its structural zeros exact (see
/// [`structural_coordinates`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StructuralCoordinates {
    /// `T⁻¹ A T`, with A's rounding residues of zero chopped.
    pub a: nalgebra::DMatrix<f64>,
    /// `T⁻¹ B`.
    pub b: nalgebra::DMatrix<f64>,
    /// `C T`.
    pub c: nalgebra::DMatrix<f64>,
    /// The number of structural zero eigenvalues.
    pub zeros: usize,
    /// The changes of coordinates whose product is `T`, in order.
    pub combos: Vec<Combine>,
}

/// `M ← M T` for a matrix with one column per state (an output matrix, the map to the
/// physical coordinates), `T` the product of `combos`: for each change `x_j = x̃_j − s·x̃_i`,
/// column i loses s·column j.
pub fn combine_columns(combos: &[Combine], m: &mut nalgebra::DMatrix<f64>) {
    for k in combos {
        for row in 0..m.nrows() {
            m[(row, k.i)] -= k.s * m[(row, k.j)];
        }
    }
}

/// The system in the coordinates that make its structural zeros exact: `(T⁻¹ A T, T⁻¹ B,
/// C T)` with `T` the product of the exact changes of coordinates [`deflate_in_place`] finds
/// (and A's rounding residues of zero chopped). Its transfer function is the original one; its
/// A has exactly zero columns (on the other states) where the structure proves zero
/// eigenvalues, which rank decisions then see without depending on how the rounding of a pair
/// of columns fell.
pub fn structural_coordinates(
    a: &nalgebra::DMatrix<f64>,
    b: &nalgebra::DMatrix<f64>,
    c: &nalgebra::DMatrix<f64>,
) -> StructuralCoordinates {
    let n = a.nrows();
    let mut t = a.clone();
    let (mut removed, mut order, mut combos, mut keys) = (vec![false; n], vec![], vec![], vec![]);
    deflate_in_place(
        t.as_mut_slice(),
        n,
        &mut removed,
        &mut order,
        &mut combos,
        &mut keys,
    );
    // T⁻¹ B: for each change, row j gains s·row i.
    let mut b = b.clone();
    for k in &combos {
        for col in 0..b.ncols() {
            b[(k.j, col)] += k.s * b[(k.i, col)];
        }
    }
    let mut c = c.clone();
    combine_columns(&combos, &mut c);
    StructuralCoordinates {
        a: t,
        b,
        c,
        zeros: order.len(),
        combos,
    }
}

/// `k` null directions deflated orthogonally, for a matrix whose structural zero eigenvalues
/// are known (`k` of them, from another basis of the same model) but not visible as exact
/// zeros here: each step finds the right singular vector `v` of the smallest singular value,
/// rotates it onto the first coordinate by a Householder reflection and drops that
/// coordinate. The matrix returned has the other eigenvalues; the perturbation is of the order
/// of the smallest singular value (rounding), not its square root.
pub(crate) fn deflate_null_directions(
    a: &nalgebra::DMatrix<f64>,
    k: usize,
) -> Option<nalgebra::DMatrix<f64>> {
    let mut m = a.clone();
    for _ in 0..k {
        let n = m.nrows();
        if n == 0 {
            return None;
        }
        let svd = m.clone().svd(false, true);
        let v_t = svd.v_t?;
        let (idx, _) = svd
            .singular_values
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))?;
        let v: Vec<f64> = v_t.row(idx).iter().copied().collect();
        // Householder H = I − 2 w wᵀ/(wᵀw), w = v − sign·e₁, maps v to sign·e₁.
        let sign = if v[0] >= 0.0 { -1.0 } else { 1.0 };
        let mut w = v.clone();
        w[0] -= sign;
        let ww: f64 = w.iter().map(|x| x * x).sum();
        if ww == 0.0 {
            m = m.remove_row(0).remove_column(0);
            continue;
        }
        let h = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            f64::from(u8::from(i == j)) - 2.0 * w[i] * w[j] / ww
        });
        let t = &h * &m * &h;
        m = t.remove_row(0).remove_column(0);
    }
    Some(m)
}

/// The structural zero eigenvalues of `a` described with the state names: a state on which
/// nothing depends (`rear frame.y`), or a pair of which only the difference (or sum) acts
/// (`rear frame.rz + front frame.rz`: the heading of the pair).
pub fn structural_zero_states(a: &nalgebra::DMatrix<f64>, states: &[String]) -> Vec<String> {
    let n = a.nrows();
    if a.ncols() != n {
        return Vec::new();
    }
    let mut t = a.as_slice().to_vec();
    let (mut removed, mut order, mut combos, mut keys) = (vec![false; n], vec![], vec![], vec![]);
    deflate_in_place(&mut t, n, &mut removed, &mut order, &mut combos, &mut keys);
    let name = |k: usize| {
        states
            .get(k)
            .cloned()
            .unwrap_or_else(|| format!("x{}", k + 1))
    };
    order
        .iter()
        .map(|&k| match combos.iter().find(|c| c.i == k) {
            // x_j = x̃_j − s·x̃_i: the deflated direction is e_i − s·e_j.
            Some(c) if c.s < 0.0 => format!("{} + {}", name(c.i), name(c.j)),
            Some(c) => format!("{} − {}", name(c.i), name(c.j)),
            None => name(k),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column_major(rows: &[[f64; 4]]) -> Vec<f64> {
        let n = rows.len();
        (0..n)
            .flat_map(|j| (0..n).map(move |i| rows[i][j]))
            .collect()
    }

    #[test]
    fn a_chain_of_ignorable_states_is_found_in_order() {
        // x0 integrates x1; x2, x3 an oscillator; x0 and x1 ignorable.
        let mut a = column_major(&[
            [0.0, 1.0, 0.5, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0, 0.0, -4.0, -0.1],
        ]);
        let (mut removed, mut order, mut combos, mut keys) =
            (vec![false; 4], vec![], vec![], vec![]);
        deflate_in_place(&mut a, 4, &mut removed, &mut order, &mut combos, &mut keys);
        assert_eq!(order, vec![0, 1]);
        assert!(combos.is_empty());
        let mut block = vec![0.0; 4];
        assert_eq!(kept_block(&a, 4, &removed, &mut block), 2);
        assert_eq!(block, vec![0.0, -4.0, 1.0, -0.1]);
    }

    #[test]
    fn a_pair_that_acts_only_through_its_difference_is_combined() {
        // Rows depend on x0 − x1 (two headings whose difference is a steer angle).
        let mut a = column_major(&[
            [-2.0, 2.0, 1.0, 0.0],
            [3.0, -3.0, 0.0, 1.0],
            [-5.0, 5.0, -1.0, 0.0],
            [7.0, -7.0, 0.0, -1.0],
        ]);
        let (mut removed, mut order, mut combos, mut keys) =
            (vec![false; 4], vec![], vec![], vec![]);
        deflate_in_place(&mut a, 4, &mut removed, &mut order, &mut combos, &mut keys);
        assert_eq!(order.len(), 1, "one exact zero eigenvalue");
        assert_eq!(combos.len(), 1);
        let c = combos[0];
        assert!((0..4).all(|r| removed[r] || a[c.i * 4 + r] == 0.0));
    }
}
