//! Comparing eigenvalues with references: reading reference tables and matching computed
//! eigenvalues to expected ones.

use num_complex::Complex64;

/// Read a CSV of numbers with a header line: rows of `f64`.
pub fn read_csv(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|x| x.trim().parse::<f64>().expect("number"))
                .collect()
        })
        .collect()
}

/// Pair every expected eigenvalue with a distinct computed one so that the largest distance
/// is minimal (exhaustive for up to 8 values, greedy beyond), and return the pairs
/// `(computed, expected)`. Panics if the counts differ.
pub fn match_eigenvalues(got: &[Complex64], expected: &[Complex64]) -> Vec<(Complex64, Complex64)> {
    assert_eq!(
        got.len(),
        expected.len(),
        "eigenvalue counts differ: got {got:?}, expected {expected:?}"
    );
    let n = got.len();
    if n <= 8 {
        let mut best: Option<(f64, Vec<usize>)> = None;
        let mut perm: Vec<usize> = (0..n).collect();
        permute(&mut perm, 0, &mut |p| {
            let cost = p
                .iter()
                .enumerate()
                .map(|(i, &j)| (got[j] - expected[i]).norm())
                .fold(0.0, f64::max);
            if best.as_ref().is_none_or(|b| cost < b.0) {
                best = Some((cost, p.to_vec()));
            }
        });
        let p = best.expect("a permutation").1;
        return (0..n).map(|i| (got[p[i]], expected[i])).collect();
    }
    let mut used = vec![false; n];
    expected
        .iter()
        .map(|e| {
            let j = (0..n)
                .filter(|&j| !used[j])
                .min_by(|&a, &b| {
                    (got[a] - e)
                        .norm()
                        .partial_cmp(&(got[b] - e).norm())
                        .expect("finite")
                })
                .expect("one left");
            used[j] = true;
            (got[j], *e)
        })
        .collect()
}

fn permute(p: &mut Vec<usize>, k: usize, f: &mut dyn FnMut(&[usize])) {
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

/// Largest `|computed − expected| / max(|expected|, floor)` over matched eigenvalues.
pub fn max_relative_error(got: &[Complex64], expected: &[Complex64], floor: f64) -> f64 {
    match_eigenvalues(got, expected)
        .iter()
        .map(|(g, e)| (g - e).norm() / e.norm().max(floor))
        .fold(0.0, f64::max)
}

/// Largest `|computed − expected|` over matched eigenvalues.
pub fn max_abs_error(got: &[Complex64], expected: &[Complex64]) -> f64 {
    match_eigenvalues(got, expected)
        .iter()
        .map(|(g, e)| (g - e).norm())
        .fold(0.0, f64::max)
}

/// Drop the eigenvalues whose magnitude is below `tol` (structural zeros), keeping the rest.
pub fn nonzero(e: &[Complex64], tol: f64) -> Vec<Complex64> {
    e.iter().copied().filter(|z| z.norm() > tol).collect()
}
