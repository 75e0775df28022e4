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

/// Leading dimension of the fixed-size working arrays (column-major).
const LD: usize = MAX_N;

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
    let mut full = [0.0; MAX_N * MAX_N];
    full[..n * n].copy_from_slice(a);
    let mut removed = [false; MAX_N];
    let zeros = deflate::deflate_small(&mut full[..n * n], n, &mut removed[..n]);
    let mut h = [0.0; LD * LD];
    let m = kept_block(&full[..n * n], n, &removed[..n], &mut h);
    let (mut re, mut im) = ([0.0; MAX_N], [0.0; MAX_N]);
    if m > 0 {
        balance(&mut h, m);
        hessenberg(&mut h, m);
        francis(&mut h, m, &mut re, &mut im).map_err(|()| {
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

/// Copies the kept rows and columns of `a` (n × n, leading dimension n) into `h` (leading
/// dimension [`LD`]); the size of the block.
fn kept_block(a: &[f64], n: usize, removed: &[bool], h: &mut [f64; LD * LD]) -> usize {
    let mut jj = 0;
    for j in (0..n).filter(|&j| !removed[j]) {
        let mut ii = 0;
        for i in (0..n).filter(|&i| !removed[i]) {
            h[jj * LD + ii] = a[j * n + i];
            ii += 1;
        }
        jj += 1;
    }
    jj
}

/// Balancing (powers of two) of the leading m × m block.
fn balance(h: &mut [f64; LD * LD], m: usize) {
    // `balance_in_place` works on a packed matrix: pack, balance, unpack.
    let mut packed = [0.0; MAX_N * MAX_N];
    for j in 0..m {
        packed[j * m..(j + 1) * m].copy_from_slice(&h[j * LD..j * LD + m]);
    }
    let mut scale = [1.0; MAX_N];
    balance_in_place(&mut packed[..m * m], m, &mut scale[..m]);
    for j in 0..m {
        h[j * LD..j * LD + m].copy_from_slice(&packed[j * m..(j + 1) * m]);
    }
}

/// Reduces the leading m × m block to upper Hessenberg form by Householder reflections
/// `P = I − β v vᵀ` (a similarity: eigenvalues unchanged).
fn hessenberg(h: &mut [f64; LD * LD], m: usize) {
    for k in 0..m.saturating_sub(2) {
        // The reflection that maps h[k+1.., k] onto a multiple of e₁.
        let mut v = [0.0; MAX_N];
        let len = m - k - 1;
        let col = &h[k * LD + k + 1..k * LD + m];
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
            let c = &mut h[j * LD + k + 1..j * LD + m];
            let s: f64 = c.iter().zip(&v[..len]).map(|(x, y)| x * y).sum::<f64>() * beta;
            for (x, y) in c.iter_mut().zip(&v[..len]) {
                *x -= s * y;
            }
        }
        // Right: rows 0..m, columns k+1..m.
        for i in 0..m {
            let mut s = 0.0;
            for (t, vt) in v[..len].iter().enumerate() {
                s += h[(k + 1 + t) * LD + i] * vt;
            }
            s *= beta;
            for (t, vt) in v[..len].iter().enumerate() {
                h[(k + 1 + t) * LD + i] -= s * vt;
            }
        }
        h[k * LD + k + 1] = alpha * big;
        for i in k + 2..m {
            h[k * LD + i] = 0.0;
        }
    }
}

/// Element (i, j) of the working array.
#[inline(always)]
fn at(i: usize, j: usize) -> usize {
    j * LD + i
}

/// The Francis double-shift QR iteration on the upper Hessenberg block `h` (m × m); its
/// eigenvalues in `re`, `im` (unsorted). `Err` when it does not converge.
fn francis(
    h: &mut [f64; LD * LD],
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
        let lo = deflation_point(h, hi_u, small);
        if lo > 0 {
            h[at(lo, lo - 1)] = 0.0;
        }
        if lo == hi_u {
            re[hi_u] = h[at(hi_u, hi_u)];
            im[hi_u] = 0.0;
            hi -= 1;
            its = 0;
            continue;
        }
        if lo + 1 == hi_u {
            let (l1, l2) = block_2x2(
                h[at(lo, lo)],
                h[at(lo, hi_u)],
                h[at(hi_u, lo)],
                h[at(hi_u, hi_u)],
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
        let (s, t) = shifts(h, lo, hi_u, its);
        sweep(h, lo, hi_u, s, t);
    }
    Ok(())
}

/// The top of the unreduced window ending at `hi`: the largest `l ≤ hi` whose subdiagonal
/// entry `h[l, l−1]` is negligible (0 when none is).
fn deflation_point(h: &[f64; LD * LD], hi: usize, small: f64) -> usize {
    let ulp = f64::EPSILON;
    let mut l = hi;
    while l > 0 {
        let sub = h[at(l, l - 1)].abs();
        if sub <= small {
            return l;
        }
        let (d0, d1) = (h[at(l - 1, l - 1)], h[at(l, l)]);
        let mut tst = d0.abs() + d1.abs();
        if tst == 0.0 {
            if l >= 2 {
                tst += h[at(l - 1, l - 2)].abs();
            }
            if l < hi {
                tst += h[at(l + 1, l)].abs();
            }
        }
        if sub <= ulp * tst {
            // Ahues & Tisseur: the subdiagonal is also compared with the local eigenvalue
            // separation, so a graded matrix keeps its small eigenvalues.
            let sup = h[at(l - 1, l)].abs();
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
fn shifts(h: &[f64; LD * LD], lo: usize, hi: usize, its: usize) -> (f64, f64) {
    if EXCEPTIONAL.contains(&its) {
        // A shift unrelated to the current block breaks a cycle (the values of EISPACK's
        // `hqr` and LAPACK's `dlahqr`, w the size of the last two subdiagonals).
        let w = h[at(hi, hi - 1)].abs()
            + if hi >= lo + 2 {
                h[at(hi - 1, hi - 2)].abs()
            } else {
                0.0
            };
        let x = h[at(hi, hi)] + 0.75 * w;
        // The eigenvalues of [[x, −0.4375w], [w, x]]: x ± i·0.661w.
        return (2.0 * x, x * x + 0.4375 * w * w);
    }
    let (a, b, c, d) = (
        h[at(hi - 1, hi - 1)],
        h[at(hi - 1, hi)],
        h[at(hi, hi - 1)],
        h[at(hi, hi)],
    );
    (a + d, a * d - b * c)
}

/// One implicit double-shift (Francis) sweep over the window lo..=hi: the first column of
/// `(H − σ₁I)(H − σ₂I)` (`s = σ₁ + σ₂`, `t = σ₁σ₂`) starts a bulge that 3×3 reflections chase
/// down the subdiagonal. Only the window is updated (eigenvalues only).
fn sweep(h: &mut [f64; LD * LD], lo: usize, hi: usize, s: f64, t: f64) {
    let h00 = h[at(lo, lo)];
    let h10 = h[at(lo + 1, lo)];
    let mut x = h00 * h00 + h[at(lo, lo + 1)] * h10 - s * h00 + t;
    let mut y = h10 * (h00 + h[at(lo + 1, lo + 1)] - s);
    let mut z = h10 * h[at(lo + 2, lo + 1)];
    for k in lo..hi - 1 {
        // The reflection P = I − β v vᵀ mapping (x, y, z) onto a multiple of e₁.
        let scale = x.abs() + y.abs() + z.abs();
        if scale != 0.0 {
            let (xs, ys, zs) = (x / scale, y / scale, z / scale);
            let alpha = -xs.signum() * (xs * xs + ys * ys + zs * zs).sqrt();
            let v = [xs - alpha, ys, zs];
            let beta = -1.0 / (alpha * v[0]);
            // vᵀv = 2α(α − x) = −2αv₀, so 2/vᵀv = −1/(αv₀).
            let first = if k > lo { k - 1 } else { lo };
            for j in first..=hi {
                let f =
                    beta * (v[0] * h[at(k, j)] + v[1] * h[at(k + 1, j)] + v[2] * h[at(k + 2, j)]);
                h[at(k, j)] -= f * v[0];
                h[at(k + 1, j)] -= f * v[1];
                h[at(k + 2, j)] -= f * v[2];
            }
            let last = (k + 3).min(hi);
            for i in lo..=last {
                let f =
                    beta * (h[at(i, k)] * v[0] + h[at(i, k + 1)] * v[1] + h[at(i, k + 2)] * v[2]);
                h[at(i, k)] -= f * v[0];
                h[at(i, k + 1)] -= f * v[1];
                h[at(i, k + 2)] -= f * v[2];
            }
            if k > lo {
                // The bulge below the subdiagonal is now exactly zero.
                h[at(k + 1, k - 1)] = 0.0;
                h[at(k + 2, k - 1)] = 0.0;
            }
        }
        x = h[at(k + 1, k)];
        y = h[at(k + 2, k)];
        if k + 3 <= hi {
            z = h[at(k + 3, k)];
        }
    }
    // The last reflection is 2×2 (rows hi−1, hi).
    let k = hi - 1;
    let scale = x.abs() + y.abs();
    if scale != 0.0 {
        let (xs, ys) = (x / scale, y / scale);
        let alpha = -xs.signum() * (xs * xs + ys * ys).sqrt();
        let v = [xs - alpha, ys];
        let beta = -1.0 / (alpha * v[0]);
        for j in k - 1..=hi {
            let f = beta * (v[0] * h[at(k, j)] + v[1] * h[at(k + 1, j)]);
            h[at(k, j)] -= f * v[0];
            h[at(k + 1, j)] -= f * v[1];
        }
        for i in lo..=hi {
            let f = beta * (h[at(i, k)] * v[0] + h[at(i, k + 1)] * v[1]);
            h[at(i, k)] -= f * v[0];
            h[at(i, k + 1)] -= f * v[1];
        }
        h[at(k + 1, k - 1)] = 0.0;
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
