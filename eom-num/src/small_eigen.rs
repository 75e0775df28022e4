//! Eigenvalues of small matrices (n ≤ [`MAX_N`]) on the stack: the kernel of sweeps that
//! need the spectrum of a 4×4 or 6×6 state matrix millions of times.
//!
//! A general dense eigensolver spends most of the time of so small a problem in set-up
//! (workspace queries, blocking decisions, dispatch); here every step works on fixed-size
//! arrays and allocates nothing:
//!
//! 1. **Structural zeros** are deflated exactly first ([`crate::deflate`]: states on which
//!    nothing depends, pairs that act only through their difference), so that the zero
//!    Jordan block of a vehicle's heading and lateral position neither costs iterations nor
//!    splits into `±√ε‖A‖` and pollutes the small roots near it;
//! 2. **balancing** of the rest by powers of two (Parlett & Reinsch 1969);
//! 3. **Hessenberg** reduction by Householder reflections;
//! 4. the **Francis double-shift QR** iteration (Francis 1961/62; Golub & Van Loan,
//!    *Matrix Computations*, 4th ed., §7.5), restricted to the unreduced window (only the
//!    eigenvalues are wanted), with the deflation test of Ahues & Tisseur (1997) that keeps
//!    small eigenvalues of graded matrices to high relative accuracy, and exceptional shifts
//!    after 10 and 20 iterations without a deflation;
//! 5. each 2×2 block's eigenvalues from a scaled, cancellation-free quadratic formula.
//!
//! The output follows [`crate::modes::eigenvalues`]: sorted by (real, imaginary) part,
//! conjugate pairs with bit-identical real parts, real eigenvalues with imaginary part
//! `+0.0`, structural zeros exactly `0`. Its accuracy against faer's solver and a
//! double-double reference is charted by `eom bench accuracy` (docs/work-precision.md).

use crate::NumError;
use crate::deflate;
use crate::linalg::balance_in_place;
use crate::statespace::check_finite_slice;
use num_complex::Complex64;

/// The largest matrix the kernel takes.
pub const MAX_N: usize = 16;

/// Iterations without a deflation after which the shifts are exceptional.
const EXCEPTIONAL: [usize; 2] = [10, 20];

/// Iterations allowed per eigenvalue (LAPACK's `dlahqr` allows 30 per row as well).
const ITERATIONS_PER_EIGENVALUE: usize = 30;

/// The eigenvalues of the n × n matrix `a` (column-major, `n ≤ MAX_N`), written to `out`
/// (length n) sorted by (real, imaginary) part; returns the number of structural zero
/// eigenvalues (exact zeros among them). Allocates nothing.
///
/// Errors: [`NumError::Dimension`] (`n` above [`MAX_N`], or slices of the wrong length),
/// [`NumError::NonFinite`] (an entry NaN or infinite), [`NumError::OutOfRange`] (beyond
/// [`crate::MAX_ENTRY`]), [`NumError::NoConvergence`].
pub fn eigenvalues_small(a: &[f64], n: usize, out: &mut [Complex64]) -> Result<usize, NumError> {
    if n > MAX_N || a.len() != n * n || out.len() != n {
        return Err(NumError::Dimension(format!(
            "eigenvalues_small: a {n}×{n} matrix (at most {MAX_N}×{MAX_N}) given {} entries \
             and an output of length {}",
            a.len(),
            out.len()
        )));
    }
    check_finite_slice(a, n, n, "A")?;
    // One working array: the deflation works on the n × n matrix, the kept block is then
    // packed in place (leading dimension m) for the rest.
    let mut w = [0.0; MAX_N * MAX_N];
    w[..n * n].copy_from_slice(a);
    let mut removed = [false; MAX_N];
    let zeros = deflate::deflate_small(&mut w[..n * n], n, &mut removed[..n]);
    let m = pack_kept(&mut w, n, &removed[..n]);
    let (mut re, mut im) = ([0.0; MAX_N], [0.0; MAX_N]);
    if m > 0 {
        let h = &mut w[..m * m];
        let mut scale = [1.0; MAX_N];
        balance_in_place(h, m, &mut scale[..m]);
        hessenberg(h, m);
        francis(h, m, &mut re, &mut im).map_err(|()| {
            NumError::NoConvergence(format!(
                "eigenvalues of a {n}×{n} matrix: the QR iteration did not converge"
            ))
        })?;
    }
    for (k, o) in out.iter_mut().enumerate() {
        // `+ 0.0` turns a −0.0 imaginary part into +0.0 so that sorting is by value.
        *o = if k < m {
            Complex64::new(re[k], im[k] + 0.0)
        } else {
            Complex64::new(0.0, 0.0)
        };
    }
    // Insertion sort: n ≤ 16, and no allocation (the standard sorts may allocate).
    for i in 1..n {
        let mut j = i;
        while j > 0 && cmp_re_im(&out[j - 1], &out[j]).is_gt() {
            out.swap(j - 1, j);
            j -= 1;
        }
    }
    Ok(zeros)
}

fn cmp_re_im(a: &Complex64, b: &Complex64) -> std::cmp::Ordering {
    a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im))
}

/// Packs the kept rows and columns of the n × n matrix in `w` in place into its leading
/// m × m (leading dimension m); returns m. (Every entry moves to an index no larger than its
/// own, and the entries are visited in increasing order, so nothing is overwritten before it
/// is read.)
fn pack_kept(w: &mut [f64; MAX_N * MAX_N], n: usize, removed: &[bool]) -> usize {
    let m = removed.iter().filter(|r| !**r).count();
    if m == n {
        return m;
    }
    let mut k = 0;
    for j in (0..n).filter(|&j| !removed[j]) {
        for i in (0..n).filter(|&i| !removed[i]) {
            w[k] = w[j * n + i];
            k += 1;
        }
    }
    m
}

/// Reduces the leading m × m block to upper Hessenberg form by Householder reflections
/// `P = I − β v vᵀ` (a similarity: eigenvalues unchanged).
fn hessenberg(h: &mut [f64], m: usize) {
    for k in 0..m.saturating_sub(2) {
        // The reflection that maps h[k+1.., k] onto a multiple of e₁.
        let mut v = [0.0; MAX_N];
        let len = m - k - 1;
        let col = &h[k * m + k + 1..k * m + m];
        let big = col.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if big == 0.0 || col[1..].iter().all(|x| *x == 0.0) {
            continue;
        }
        let mut norm2 = 0.0;
        for (vi, x) in v[..len].iter_mut().zip(col) {
            *vi = x / big;
            norm2 += *vi * *vi;
        }
        let alpha = -v[0].signum() * norm2.sqrt();
        v[0] -= alpha;
        // vᵀv = ‖x‖² − 2αx₀ + α² = 2α(α − x₀) = −2αv₀.
        let beta = -1.0 / (alpha * v[0]);
        // Left: rows k+1..m, columns k..m.
        for j in k..m {
            let c = &mut h[j * m + k + 1..j * m + m];
            let s: f64 = c.iter().zip(&v[..len]).map(|(x, y)| x * y).sum::<f64>() * beta;
            for (x, y) in c.iter_mut().zip(&v[..len]) {
                *x -= s * y;
            }
        }
        // Right: rows 0..m, columns k+1..m.
        for i in 0..m {
            let mut s = 0.0;
            for (t, vt) in v[..len].iter().enumerate() {
                s += h[(k + 1 + t) * m + i] * vt;
            }
            s *= beta;
            for (t, vt) in v[..len].iter().enumerate() {
                h[(k + 1 + t) * m + i] -= s * vt;
            }
        }
        h[k * m + k + 1] = alpha * big;
        for i in k + 2..m {
            h[k * m + i] = 0.0;
        }
    }
}

/// Element (i, j) of the working array.
#[inline(always)]
fn at(m: usize, i: usize, j: usize) -> usize {
    j * m + i
}

/// The Francis double-shift QR iteration on the upper Hessenberg block `h` (m × m); its
/// eigenvalues in `re`, `im` (unsorted). `Err` when it does not converge.
fn francis(
    h: &mut [f64],
    m: usize,
    re: &mut [f64; MAX_N],
    im: &mut [f64; MAX_N],
) -> Result<(), ()> {
    let eps = f64::EPSILON;
    let small = f64::MIN_POSITIVE * (m as f64 / eps);
    let mut budget = ITERATIONS_PER_EIGENVALUE * m.max(10);
    // The active window is lo..=hi; everything below hi is done.
    let mut hi = m as isize - 1;
    let mut its = 0;
    while hi >= 0 {
        let hi_u = hi as usize;
        let lo = deflation_point(h, m, hi_u, small);
        if lo > 0 {
            h[at(m, lo, lo - 1)] = 0.0;
        }
        if lo == hi_u {
            re[hi_u] = h[at(m, hi_u, hi_u)];
            im[hi_u] = 0.0;
            hi -= 1;
            its = 0;
            continue;
        }
        if lo + 1 == hi_u {
            let (l1, l2) = block_2x2(
                h[at(m, lo, lo)],
                h[at(m, lo, hi_u)],
                h[at(m, hi_u, lo)],
                h[at(m, hi_u, hi_u)],
            );
            (re[lo], im[lo], re[hi_u], im[hi_u]) = (l1.re, l1.im, l2.re, l2.im);
            hi -= 2;
            its = 0;
            continue;
        }
        if budget == 0 {
            return Err(());
        }
        budget -= 1;
        its += 1;
        let (s, t) = shifts(h, m, lo, hi_u, its);
        sweep(h, m, lo, hi_u, s, t);
    }
    Ok(())
}

/// The top of the unreduced window ending at `hi`: the largest `l ≤ hi` whose subdiagonal
/// entry `h[l, l−1]` is negligible (0 when none is).
fn deflation_point(h: &[f64], m: usize, hi: usize, small: f64) -> usize {
    let ulp = f64::EPSILON;
    let mut l = hi;
    while l > 0 {
        let sub = h[at(m, l, l - 1)].abs();
        if sub <= small {
            return l;
        }
        let (d0, d1) = (h[at(m, l - 1, l - 1)], h[at(m, l, l)]);
        let mut tst = d0.abs() + d1.abs();
        if tst == 0.0 {
            if l >= 2 {
                tst += h[at(m, l - 1, l - 2)].abs();
            }
            if l < hi {
                tst += h[at(m, l + 1, l)].abs();
            }
        }
        if sub <= ulp * tst {
            // Ahues & Tisseur: the subdiagonal is also compared with the local eigenvalue
            // separation, so a graded matrix keeps its small eigenvalues.
            let sup = h[at(m, l - 1, l)].abs();
            let (ab, ba) = (sub.max(sup), sub.min(sup));
            let diff = (d0 - d1).abs();
            let (aa, bb) = (d1.abs().max(diff), d1.abs().min(diff));
            let s = aa + ab;
            if ba * (ab / s) <= small.max(ulp * (bb * (aa / s))) {
                return l;
            }
        }
        l -= 1;
    }
    0
}

/// The double shift as the sum `s` and product `t` of the trailing 2×2 block's eigenvalues,
/// or an exceptional pair after [`EXCEPTIONAL`] iterations without a deflation.
fn shifts(h: &[f64], m: usize, lo: usize, hi: usize, its: usize) -> (f64, f64) {
    if EXCEPTIONAL.contains(&its) {
        // A shift unrelated to the current block breaks a cycle (the values of EISPACK's
        // `hqr` and LAPACK's `dlahqr`, w the size of the last two subdiagonals).
        let w = h[at(m, hi, hi - 1)].abs()
            + if hi >= lo + 2 {
                h[at(m, hi - 1, hi - 2)].abs()
            } else {
                0.0
            };
        let x = h[at(m, hi, hi)] + 0.75 * w;
        // The eigenvalues of [[x, −0.4375w], [w, x]]: x ± i·0.661w.
        return (2.0 * x, x * x + 0.4375 * w * w);
    }
    let (a, b, c, d) = (
        h[at(m, hi - 1, hi - 1)],
        h[at(m, hi - 1, hi)],
        h[at(m, hi, hi - 1)],
        h[at(m, hi, hi)],
    );
    (a + d, a * d - b * c)
}

/// One implicit double-shift (Francis) sweep over the window lo..=hi: the first column of
/// `(H − σ₁I)(H − σ₂I)` (`s = σ₁ + σ₂`, `t = σ₁σ₂`) starts a bulge that 3×3 reflections chase
/// down the subdiagonal. Only the window is updated (eigenvalues only).
fn sweep(h: &mut [f64], m: usize, lo: usize, hi: usize, s: f64, t: f64) {
    let h00 = h[at(m, lo, lo)];
    let h10 = h[at(m, lo + 1, lo)];
    let mut x = h00 * h00 + h[at(m, lo, lo + 1)] * h10 - s * h00 + t;
    let mut y = h10 * (h00 + h[at(m, lo + 1, lo + 1)] - s);
    let mut z = h10 * h[at(m, lo + 2, lo + 1)];
    for k in lo..hi - 1 {
        if let Some((v1, v2, tau)) = reflector3(x, y, z) {
            let first = if k > lo { k - 1 } else { lo };
            reflect_rows3(h, m, k, first, hi, v1, v2, tau);
            reflect_columns3(h, m, k, lo, (k + 3).min(hi), v1, v2, tau);
            if k > lo {
                // The bulge below the subdiagonal is now exactly zero.
                h[at(m, k + 1, k - 1)] = 0.0;
                h[at(m, k + 2, k - 1)] = 0.0;
            }
        }
        x = h[at(m, k + 1, k)];
        y = h[at(m, k + 2, k)];
        if k + 3 <= hi {
            z = h[at(m, k + 3, k)];
        }
    }
    // The last reflection is 2×2 (rows hi−1, hi).
    let k = hi - 1;
    if let Some((v1, _, tau)) = reflector3(x, y, 0.0) {
        for j in k - 1..=hi {
            let c = &mut h[j * m + k..j * m + k + 2];
            let f = tau * (c[0] + v1 * c[1]);
            c[0] -= f;
            c[1] -= f * v1;
        }
        let (a, b) = h[k * m..(k + 2) * m].split_at_mut(m);
        for (p, q) in a[lo..=hi].iter_mut().zip(&mut b[lo..=hi]) {
            let f = tau * (*p + v1 * *q);
            *p -= f;
            *q -= f * v1;
        }
        h[at(m, k + 1, k - 1)] = 0.0;
    }
}

/// The reflection `P = I − τ v vᵀ`, `v = (1, v₁, v₂)`, that maps `(x, y, z)` onto a multiple
/// of `e₁` (`None` when the vector is zero).
fn reflector3(x: f64, y: f64, z: f64) -> Option<(f64, f64, f64)> {
    let scale = x.abs() + y.abs() + z.abs();
    if scale == 0.0 {
        return None;
    }
    let r = 1.0 / scale;
    let (xs, ys, zs) = (x * r, y * r, z * r);
    let alpha = -xs.signum() * (xs * xs + ys * ys + zs * zs).sqrt();
    let v0 = xs - alpha;
    // With w = (v₀, y, z): 2/wᵀw = −1/(αv₀); scaled to v = w/v₀, τ = −v₀/α.
    let r0 = 1.0 / v0;
    Some((ys * r0, zs * r0, -v0 / alpha))
}

/// `P·H` on rows k..k+3 of columns `first..=last`.
fn reflect_rows3(
    h: &mut [f64],
    m: usize,
    k: usize,
    first: usize,
    last: usize,
    v1: f64,
    v2: f64,
    tau: f64,
) {
    for j in first..=last {
        let c = &mut h[j * m + k..j * m + k + 3];
        let f = tau * (c[0] + v1 * c[1] + v2 * c[2]);
        c[0] -= f;
        c[1] -= f * v1;
        c[2] -= f * v2;
    }
}

/// `H·P` on columns k..k+3 of rows `first..=last`.
fn reflect_columns3(
    h: &mut [f64],
    m: usize,
    k: usize,
    first: usize,
    last: usize,
    v1: f64,
    v2: f64,
    tau: f64,
) {
    let (a, rest) = h[k * m..(k + 3) * m].split_at_mut(m);
    let (b, c) = rest.split_at_mut(m);
    let rows = first..=last;
    for ((p, q), r) in a[rows.clone()]
        .iter_mut()
        .zip(&mut b[rows.clone()])
        .zip(&mut c[rows])
    {
        let f = tau * (*p + v1 * *q + v2 * *r);
        *p -= f;
        *q -= f * v1;
        *r -= f * v2;
    }
}

/// The eigenvalues of `[[a, b], [c, d]]`: a real pair (the larger-magnitude root first, the
/// other from the product, no cancellation) or a conjugate pair (identical real parts,
/// negative imaginary part first).
pub(crate) fn block_2x2(a: f64, b: f64, c: f64, d: f64) -> (Complex64, Complex64) {
    if c == 0.0 || b == 0.0 {
        // Triangular.
        return (Complex64::new(a, 0.0), Complex64::new(d, 0.0));
    }
    // λ = d + p ± √(p² + bc), p = (a − d)/2, evaluated scaled so that nothing overflows.
    let p = 0.5 * (a - d);
    let bcmax = b.abs().max(c.abs());
    let bcmis = b.abs().min(c.abs()) * b.signum() * c.signum();
    let scale = p.abs().max(bcmax);
    let z = (p / scale) * p + (bcmax / scale) * bcmis;
    if z >= 0.0 {
        let root = scale.sqrt() * z.sqrt();
        let w = p + if p >= 0.0 { root } else { -root };
        let l1 = d + w;
        // The product of the roots is ad − bc: the smaller root from it, not by a
        // difference of nearly equal numbers.
        let l2 = if w == 0.0 { d } else { d - (bcmax / w) * bcmis };
        (Complex64::new(l1, 0.0), Complex64::new(l2, 0.0))
    } else {
        let mid = d + p;
        let w = scale.sqrt() * (-z).sqrt();
        (Complex64::new(mid, -w), Complex64::new(mid, w))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_by_two_blocks() {
        let (l1, l2) = block_2x2(0.0, 1.0, -4.0, 0.0);
        assert_eq!(
            (l1, l2),
            (Complex64::new(0.0, -2.0), Complex64::new(0.0, 2.0))
        );
        let (l1, l2) = block_2x2(3.0, 1.0, 0.0, 5.0);
        assert_eq!((l1.re, l2.re), (3.0, 5.0));
        // Roots 1e8 and 1e-8 of s² − (1e8 + 1e-8)s + 1: the small one to full accuracy.
        let (l1, l2) = block_2x2(1e8, 1.0, -1.0, 0.0);
        let small = if l1.re.abs() < l2.re.abs() { l1 } else { l2 };
        assert!((small.re - 1e-8).abs() < 1e-22, "{small}");
    }
}
