//! Small dense solves (at most 4 × 4) of the block algorithms: the Kronecker form of a Sylvester
//! equation between two diagonal blocks of a real Schur form, by Gaussian elimination with
//! complete pivoting.

/// Solves the `k × k` system `m x = rhs` (`m` row-major, `k ≤ 4`) by Gaussian elimination with
/// complete pivoting. A pivot below `floor` is raised to `floor` (in magnitude), as LAPACK's
/// small Sylvester solver does, so the result stays finite; the return value says whether that
/// happened (the system is singular to working precision).
pub(crate) fn solve_small(m: &mut [f64], rhs: &mut [f64], k: usize, floor: f64) -> bool {
    let mut perm: [usize; 4] = [0, 1, 2, 3];
    let mut perturbed = false;
    for col in 0..k {
        // Complete pivoting over the trailing block.
        let (mut pi, mut pj, mut best) = (col, col, -1.0);
        for i in col..k {
            for j in col..k {
                let v = m[i * k + j].abs();
                if v > best {
                    (pi, pj, best) = (i, j, v);
                }
            }
        }
        if pi != col {
            for j in 0..k {
                m.swap(pi * k + j, col * k + j);
            }
            rhs.swap(pi, col);
        }
        if pj != col {
            for i in 0..k {
                m.swap(i * k + pj, i * k + col);
            }
            perm.swap(pj, col);
        }
        if m[col * k + col].abs() < floor {
            m[col * k + col] = if m[col * k + col] < 0.0 {
                -floor
            } else {
                floor
            };
            perturbed = true;
        }
        let p = m[col * k + col];
        for i in col + 1..k {
            let f = m[i * k + col] / p;
            if f != 0.0 {
                for j in col..k {
                    m[i * k + j] -= f * m[col * k + j];
                }
                rhs[i] -= f * rhs[col];
            }
        }
    }
    let mut x = [0.0; 4];
    for i in (0..k).rev() {
        let mut s = rhs[i];
        for j in i + 1..k {
            s -= m[i * k + j] * x[j];
        }
        x[i] = s / m[i * k + i];
    }
    for (c, &p) in perm.iter().enumerate().take(k) {
        rhs[p] = x[c];
    }
    perturbed
}

/// Solves `a x − x b = c` for the small blocks `a` (`p × p`), `b` (`q × q`), `c` and `x`
/// (`p × q`), all column-major, `p, q ≤ 2`, through its Kronecker form
/// `(I ⊗ a − bᵀ ⊗ I) vec x = vec c`. Returns `x` in `c` and whether a pivot was raised (the
/// blocks share an eigenvalue to working precision).
pub(crate) fn sylvester_small(a: &[f64], b: &[f64], c: &mut [f64], p: usize, q: usize) -> bool {
    let k = p * q;
    let mut m = [0.0; 16];
    let mut scale = 0.0f64;
    for j in 0..q {
        for i in 0..p {
            let row = i + p * j;
            for l in 0..q {
                for kk in 0..p {
                    let col = kk + p * l;
                    let mut v = 0.0;
                    if l == j {
                        v += a[kk * p + i];
                    }
                    if kk == i {
                        v -= b[j * q + l];
                    }
                    m[row * k + col] = v;
                    scale = scale.max(v.abs());
                }
            }
        }
    }
    let floor = (f64::EPSILON * scale).max(f64::MIN_POSITIVE);
    solve_small(&mut m[..k * k], &mut c[..k], k, floor)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_sylvester_matches_its_definition() {
        // a 2×2 (complex pair), b 2×2, checked by the residual.
        let a = [-1.0, -3.0, 2.0, -1.0]; // column-major [[-1, 2], [-3, -1]]
        let b = [0.5, 0.0, 1.0, 2.0]; // [[0.5, 1], [0, 2]]
        let c0 = [1.0, 2.0, 3.0, 4.0];
        let mut x = c0;
        assert!(!sylvester_small(&a, &b, &mut x, 2, 2));
        for i in 0..2 {
            for j in 0..2 {
                let mut r = 0.0;
                for k in 0..2 {
                    r += a[k * 2 + i] * x[j * 2 + k] - x[k * 2 + i] * b[j * 2 + k];
                }
                assert!((r - c0[j * 2 + i]).abs() < 1e-14, "{i} {j}: {r}");
            }
        }
    }
}
