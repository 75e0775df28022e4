//! Step 2 of a sweep: the eigenvalues at a point assigned to the branches, by an optimal
//! assignment (the Hungarian method) on the distance to the predicted branch values, with
//! conjugate pairs kept together and the neutral zeros pinned.

use num_complex::Complex64;

/// [`assign`] with the first `z` branches (the neutral zeros) pinned to the `z` eigenvalues
/// of least modulus. Matching alone cannot tell a real root passing through zero from a
/// neutral zero: near the crossing both are ≈ 0 and the costs tie (the bicycle's capsize
/// root at 6 m/s and its heading mode swapped on a 0.25 m/s grid). Pinned, the neutral
/// branch is always the eigenvalue nearest zero; where the two are closer than rounding,
/// which is which does not matter, as real parts are taken together with the neutral ones.
pub(super) fn assign_pinned(
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
