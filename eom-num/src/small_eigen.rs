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
//!    after 10 and 20 iterations without a deflation; a 4×4 window (the bicycle after its
//!    structural zeros) takes its first shifts from a pair of roots of its characteristic
//!    quartic (Ferrari), which deflates it in 1–2 iterations instead of 5–7;
//! 5. each 2×2 block's eigenvalues from a scaled, cancellation-free quadratic formula.
//!
//! The output follows [`crate::modes::eigenvalues`]: sorted by (real, imaginary) part,
//! conjugate pairs with bit-identical real parts, real eigenvalues with imaginary part
//! `+0.0`, structural zeros exactly `0`. Its accuracy against faer's solver and a
//! double-double reference is charted by `eom bench accuracy` (docs/work-precision.md).

use crate::deflate::{self, DeflationStep};
use crate::linalg::balance_in_place;
use crate::statespace::check_finite_slice;
use crate::{ConvergenceError, DimensionError, NumError};
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
    solve(a, n, None, out)
}

/// The structural zeros of one matrix, for the next matrices of a sweep that share its
/// structure (the same model at other parameter values): [`eigenvalues_small_known`] checks
/// and applies them instead of searching for them again.
#[derive(Clone, Debug, PartialEq)]
pub struct KnownZeros {
    n: usize,
    steps: [DeflationStep; MAX_N],
    len: usize,
}

impl KnownZeros {
    /// The structural zeros of the n × n matrix `a` (column-major, n ≤ [`MAX_N`]).
    ///
    /// Errors: as [`eigenvalues_small`].
    pub fn of(a: &[f64], n: usize) -> Result<Self, NumError> {
        check(a, n, n)?;
        let mut w = [0.0; MAX_N * MAX_N];
        w[..n * n].copy_from_slice(a);
        let mut known = KnownZeros {
            n,
            steps: [DeflationStep::Zero(0); MAX_N],
            len: 0,
        };
        let mut removed = [false; MAX_N];
        deflate::deflate_small_recorded(&mut w[..n * n], n, &mut removed[..n], |s| {
            known.steps[known.len] = s;
            known.len += 1;
        });
        Ok(known)
    }

    /// The number of structural zero eigenvalues.
    pub fn count(&self) -> usize {
        self.len
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.n
    }
}

/// [`eigenvalues_small`] for a matrix with the structure of the one `known` was found on:
/// its structural zeros are checked one by one (each column still exactly zero, each pair
/// still equal up to sign) and deflated, not searched for; where one does not hold, they are
/// searched for as [`eigenvalues_small`] does. Zeros that the first matrix did not have are
/// not looked for (they are then computed as eigenvalues near zero).
///
/// Errors: as [`eigenvalues_small`], and [`NumError::Dimension`] when `known` is of another
/// size.
pub fn eigenvalues_small_known(
    a: &[f64],
    n: usize,
    known: &KnownZeros,
    out: &mut [Complex64],
) -> Result<usize, NumError> {
    if known.n != n {
        return Err(NumError::Dimension(DimensionError::KnownZeros {
            n,
            known: known.n,
        }));
    }
    solve(a, n, Some(known), out)
}

/// Checks the size and entries of the input.
pub(crate) fn check(a: &[f64], n: usize, out: usize) -> Result<(), NumError> {
    if n > MAX_N || a.len() != n * n || out != n {
        return Err(NumError::Dimension(DimensionError::SmallEigen {
            n,
            max: MAX_N,
            entries: a.len(),
            out,
        }));
    }
    // One pass without a branch per entry (NaN fails the comparison); the message, naming
    // the entry, only when something is wrong.
    if a.iter()
        .fold(true, |ok, x| ok & (x.abs() <= crate::MAX_ENTRY))
    {
        return Ok(());
    }
    check_finite_slice(a, n, n, "A")
}

fn solve(
    a: &[f64],
    n: usize,
    known: Option<&KnownZeros>,
    out: &mut [Complex64],
) -> Result<usize, NumError> {
    check(a, n, out.len())?;
    // One working array: the deflation works on the n × n matrix, the kept block is then
    // packed in place (leading dimension m) for the rest.
    let mut w = [0.0; MAX_N * MAX_N];
    w[..n * n].copy_from_slice(a);
    let mut removed = [false; MAX_N];
    let replayed = known.and_then(|k| {
        deflate::replay_small(&mut w[..n * n], n, &mut removed[..n], &k.steps[..k.len])
    });
    let zeros = match replayed {
        Some(z) => z,
        None => {
            w[..n * n].copy_from_slice(a);
            deflate::deflate_small(&mut w[..n * n], n, &mut removed[..n])
        }
    };
    let m = pack_kept(&mut w, n, &removed[..n]);
    let (mut re, mut im) = ([0.0; MAX_N], [0.0; MAX_N]);
    if m > 0 {
        let h = &mut w[..m * m];
        let mut scale = [1.0; MAX_N];
        balance_in_place(h, m, &mut scale[..m]);
        qr(h, m, &mut re, &mut im)
            .map_err(|()| NumError::NoConvergence(ConvergenceError::QrIteration { n }))?;
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

pub(crate) fn cmp_re_im(a: &Complex64, b: &Complex64) -> std::cmp::Ordering {
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

/// The eigenvalues of the packed m × m matrix `w` (already deflated and balanced), in
/// `re`, `im` (unsorted): the Hessenberg reduction and the QR iteration on a fixed-size copy,
/// one instance per size, so that loop bounds and indices are known to the compiler.
pub(crate) fn qr(
    w: &[f64],
    m: usize,
    re: &mut [f64; MAX_N],
    im: &mut [f64; MAX_N],
) -> Result<(), ()> {
    macro_rules! sizes {
        ($($k:literal)*) => {
            match m {
                $($k => qr_fixed::<$k>(w, re, im),)*
                _ => Err(()),
            }
        };
    }
    sizes!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// A fixed-size matrix by columns: `h[j][i]` is row i of column j.
type Fixed<const M: usize> = [[f64; M]; M];

fn qr_fixed<const M: usize>(
    w: &[f64],
    re: &mut [f64; MAX_N],
    im: &mut [f64; MAX_N],
) -> Result<(), ()> {
    let mut h: Fixed<M> = [[0.0; M]; M];
    for (col, src) in h.iter_mut().zip(w.chunks_exact(M)) {
        col.copy_from_slice(src);
    }
    hessenberg(&mut h);
    francis(&mut h, re, im)
}

/// Reduces `h` to upper Hessenberg form by Householder reflections `P = I − β v vᵀ` (a
/// similarity: eigenvalues unchanged).
fn hessenberg<const M: usize>(h: &mut Fixed<M>) {
    for k in 0..M.saturating_sub(2) {
        // The reflection that maps h[k+1.., k] onto a multiple of e₁.
        let mut v = [0.0; M];
        let len = M - k - 1;
        let col = &h[k][k + 1..];
        let big = col.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if big == 0.0 || col[1..].iter().all(|x| *x == 0.0) {
            continue;
        }
        let r = 1.0 / big;
        let mut norm2 = 0.0;
        for (vi, x) in v[..len].iter_mut().zip(col) {
            *vi = x * r;
            norm2 += *vi * *vi;
        }
        let alpha = norm2.sqrt().copysign(-v[0]);
        v[0] -= alpha;
        // vᵀv = ‖x‖² − 2αx₀ + α² = 2α(α − x₀) = −2αv₀.
        let beta = -1.0 / (alpha * v[0]);
        let v = &v[..len];
        // Left: rows k+1.., columns k...
        for col in h[k..].iter_mut() {
            let c = &mut col[k + 1..];
            let s = c.iter().zip(v).map(|(x, y)| x * y).sum::<f64>() * beta;
            for (x, y) in c.iter_mut().zip(v) {
                *x -= s * y;
            }
        }
        // Right: every row, columns k+1...
        let mut s = [0.0; M];
        for (col, vt) in h[k + 1..].iter().zip(v) {
            for (si, x) in s.iter_mut().zip(col) {
                *si += x * vt;
            }
        }
        for (col, vt) in h[k + 1..].iter_mut().zip(v) {
            for (x, si) in col.iter_mut().zip(&s) {
                *x -= beta * si * vt;
            }
        }
        h[k][k + 1] = alpha * big;
        for x in &mut h[k][k + 2..] {
            *x = 0.0;
        }
    }
}

/// The Francis double-shift QR iteration on the upper Hessenberg matrix `h`; its eigenvalues
/// in `re`, `im` (unsorted). `Err` when it does not converge.
fn francis<const M: usize>(
    h: &mut Fixed<M>,
    re: &mut [f64; MAX_N],
    im: &mut [f64; MAX_N],
) -> Result<(), ()> {
    let small = f64::MIN_POSITIVE * (M as f64 / f64::EPSILON);
    let mut budget = ITERATIONS_PER_EIGENVALUE * M.max(10);
    // The active window is lo..=hi; the rows below hi are done.
    let mut top = M;
    let mut its = 0;
    while top > 0 {
        let hi = (top - 1).min(M - 1);
        let lo = deflation_point(h, hi, small);
        if lo > 0 {
            h[lo - 1][lo] = 0.0;
        }
        if lo == hi {
            re[hi] = h[hi][hi];
            im[hi] = 0.0;
            top -= 1;
            its = 0;
            continue;
        }
        if lo + 1 == hi {
            let (l1, l2) = block_2x2(h[lo][lo], h[hi][lo], h[lo][hi], h[hi][hi]);
            (re[lo], im[lo], re[hi], im[hi]) = (l1.re, l1.im, l2.re, l2.im);
            top -= 2;
            its = 0;
            continue;
        }
        if budget == 0 {
            return Err(());
        }
        budget -= 1;
        its += 1;
        let (s, t) = shifts(h, lo, hi, its);
        sweep(h, lo, hi, s, t);
    }
    Ok(())
}

/// The top of the unreduced window ending at `hi`: the largest `l ≤ hi` whose subdiagonal
/// entry `h[l, l−1]` is negligible (0 when none is).
fn deflation_point<const M: usize>(h: &Fixed<M>, hi: usize, small: f64) -> usize {
    let ulp = f64::EPSILON;
    let hi = hi.min(M - 1);
    let mut l = hi;
    while l > 0 {
        let sub = h[l - 1][l].abs();
        if sub <= small {
            return l;
        }
        let (d0, d1) = (h[l - 1][l - 1], h[l][l]);
        let mut tst = d0.abs() + d1.abs();
        if tst == 0.0 {
            if l >= 2 {
                tst += h[l - 2][l - 1].abs();
            }
            if l < hi {
                tst += h[l][l + 1].abs();
            }
        }
        if sub <= ulp * tst {
            // Ahues & Tisseur: the subdiagonal is also compared with the local eigenvalue
            // separation, so a graded matrix keeps its small eigenvalues.
            let sup = h[l][l - 1].abs();
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
fn shifts<const M: usize>(h: &Fixed<M>, lo: usize, hi: usize, its: usize) -> (f64, f64) {
    let hi = hi.min(M - 1);
    if EXCEPTIONAL.contains(&its) {
        // A shift unrelated to the current block breaks a cycle (the values of EISPACK's
        // `hqr` and LAPACK's `dlahqr`, w the size of the last two subdiagonals).
        let w = h[hi - 1][hi].abs()
            + if hi >= lo + 2 {
                h[hi - 2][hi - 1].abs()
            } else {
                0.0
            };
        let x = h[hi][hi] + 0.75 * w;
        // The eigenvalues of [[x, −0.4375w], [w, x]]: x ± i·0.661w.
        return (2.0 * x, x * x + 0.4375 * w * w);
    }
    if its == 1
        && hi == lo + 3
        && let Some(pair) = quartic_pair(h, lo)
    {
        return pair;
    }
    let (a, b, c, d) = (h[hi - 1][hi - 1], h[hi][hi - 1], h[hi - 1][hi], h[hi][hi]);
    (a + d, a * d - b * c)
}

/// A pair of eigenvalues of the 4×4 window at `lo` (as their sum and product), from its
/// characteristic polynomial by Ferrari's method: the first shifts of a 4×4 window, where
/// the trailing 2×2 block of a fresh Hessenberg form is a poor guess (its shifts took 4–7
/// iterations to the first deflation on the bicycle; shifts near an eigenvalue pair deflate
/// it in one or two). Only the shifts come from the polynomial — the eigenvalues are still
/// those of the QR iteration, so a poor root costs iterations, not accuracy. `None` where
/// the construction breaks down (a biquadratic, overflow): the usual shifts then.
fn quartic_pair<const M: usize>(h: &Fixed<M>, lo: usize) -> Option<(f64, f64)> {
    // det(λI − H) of the upper Hessenberg window by the recurrence on its leading blocks:
    // p_k = (λ − h_kk)·p_{k−1} − Σ_{i<k} h_ik·(h_{i+1,i}···h_{k,k−1})·p_{i−1}.
    let e = |i: usize, j: usize| h[lo + j][lo + i];
    let mut p = [[0.0f64; 5]; 5];
    p[0][0] = 1.0;
    for k in 1..=4 {
        let d = e(k - 1, k - 1);
        let (done, rest) = p.split_at_mut(k);
        let cur = &mut rest[0];
        for (c, x) in done[k - 1][..k].iter().enumerate() {
            cur[c + 1] += x;
            cur[c] -= d * x;
        }
        let mut prod = 1.0;
        for i in (1..k).rev() {
            prod *= e(i, i - 1);
            let f = e(i - 1, k - 1) * prod;
            for (x, y) in cur[..i].iter_mut().zip(&done[i - 1][..i]) {
                *x -= f * y;
            }
        }
    }
    let [d, c, b, a, _] = p[4];
    // λ = y − a/4: y⁴ + P y² + Q y + R.
    let a2 = a * a;
    let pp = b - 0.375 * a2;
    let q = c - 0.5 * a * b + 0.125 * a2 * a;
    let r = d - 0.25 * a * c + a2 * b / 16.0 - 3.0 * a2 * a2 / 256.0;
    // y⁴ + Py² + Qy + R = (y² + m)² − (sy − Q/2s)², s² = 2m − P, where m is the largest
    // root of the resolvent m³ − (P/2)m² − Rm + (PR/2 − Q²/8) (at least P/2).
    let m = largest_cubic_root(-0.5 * pp, -r, 0.5 * pp * r - 0.125 * q * q)?;
    let s2 = 2.0 * m - pp;
    // Near a biquadratic (Q → 0) s² is the difference of nearly equal numbers and Q/2s
    // undetermined: no pair then.
    let floor = 1e-8 * m.abs().max(pp.abs());
    if s2.partial_cmp(&floor) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let s = s2.sqrt();
    // The factor y² − sy + (m + Q/2s), in λ: λ² − (s − a/2)λ + (a²/16 − sa/4 + m + Q/2s).
    let sum = s - 0.5 * a;
    let prod = a2 / 16.0 - 0.25 * s * a + m + q / (2.0 * s);
    (sum.is_finite() && prod.is_finite()).then_some((sum, prod))
}

/// The largest real root of `m³ + e2·m² + e1·m + e0` (Cardano, or the trigonometric form
/// where all three roots are real); `None` where it is not finite.
fn largest_cubic_root(e2: f64, e1: f64, e0: f64) -> Option<f64> {
    // m = u − e2/3: u³ + pu + q.
    let third = e2 / 3.0;
    let p = e1 - e2 * third;
    let q = (2.0 * third * third - e1) * third + e0;
    let half = 0.5 * q;
    let cub = p / 3.0;
    let disc = half * half + cub * cub * cub;
    let u = if disc >= 0.0 {
        // One real root: A + B with A = −sign(q)·∛(|q|/2 + √disc), B = −p/(3A).
        let big = -(half.abs() + disc.sqrt()).cbrt().copysign(half);
        if big == 0.0 { 0.0 } else { big - cub / big }
    } else {
        // Three real roots (p < 0): the largest is 2√(−p/3)·cos(θ/3).
        let rad = (-cub).sqrt();
        let cos = (-half / (rad * rad * rad)).clamp(-1.0, 1.0);
        2.0 * rad * (cos.acos() / 3.0).cos()
    };
    let m = u - third;
    m.is_finite().then_some(m)
}

/// One implicit double-shift (Francis) sweep over the window lo..=hi: the first column of
/// `(H − σ₁I)(H − σ₂I)` (`s = σ₁ + σ₂`, `t = σ₁σ₂`) starts a bulge that 3×3 reflections chase
/// down the subdiagonal. Only the window is updated (eigenvalues only).
fn sweep<const M: usize>(h: &mut Fixed<M>, lo: usize, hi: usize, s: f64, t: f64) {
    let hi = hi.min(M - 1);
    let h00 = h[lo][lo];
    let h10 = h[lo][lo + 1];
    let mut x = h00 * h00 + h[lo + 1][lo] * h10 - s * h00 + t;
    let mut y = h10 * (h00 + h[lo + 1][lo + 1] - s);
    let mut z = h10 * h[lo + 1][lo + 2];
    for k in lo..hi - 1 {
        if let Some((v1, v2, tau)) = reflector3(x, y, z) {
            // P·H on rows k..k+3, H·P on columns k..k+3.
            for col in &mut h[if k > lo { k - 1 } else { lo }..=hi] {
                let c = &mut col[k..k + 3];
                let f = tau * (c[0] + v1 * c[1] + v2 * c[2]);
                c[0] -= f;
                c[1] -= f * v1;
                c[2] -= f * v2;
            }
            let last = (k + 3).min(hi);
            let (a, rest) = h[k..].split_at_mut(1);
            let (b, c) = rest.split_at_mut(1);
            for ((p, q), r) in a[0][lo..=last]
                .iter_mut()
                .zip(&mut b[0][lo..=last])
                .zip(&mut c[0][lo..=last])
            {
                let f = tau * (*p + v1 * *q + v2 * *r);
                *p -= f;
                *q -= f * v1;
                *r -= f * v2;
            }
            if k > lo {
                // The bulge below the subdiagonal is now exactly zero.
                h[k - 1][k + 1] = 0.0;
                h[k - 1][k + 2] = 0.0;
            }
        }
        x = h[k][k + 1];
        y = h[k][k + 2];
        if k + 3 <= hi {
            z = h[k][k + 3];
        }
    }
    // The last reflection is 2×2 (rows hi−1, hi).
    let k = hi - 1;
    if let Some((v1, _, tau)) = reflector3(x, y, 0.0) {
        for col in &mut h[k - 1..=hi] {
            let c = &mut col[k..k + 2];
            let f = tau * (c[0] + v1 * c[1]);
            c[0] -= f;
            c[1] -= f * v1;
        }
        let (a, b) = h[k..].split_at_mut(1);
        for (p, q) in a[0][lo..=hi].iter_mut().zip(&mut b[0][lo..=hi]) {
            let f = tau * (*p + v1 * *q);
            *p -= f;
            *q -= f * v1;
        }
        h[k - 1][k + 1] = 0.0;
    }
}

/// The reflection `P = I − τ v vᵀ`, `v = (1, v₁, v₂)`, that maps `(x, y, z)` onto a multiple
/// of `e₁` (`None` when the vector is zero).
fn reflector3(x: f64, y: f64, z: f64) -> Option<(f64, f64, f64)> {
    let norm2 = x * x + y * y + z * z;
    // Scaled first only where the squares leave the normal range (the result is the same up
    // to rounding; the division by the scale is one more step on the critical path).
    let (x, y, z, norm2) = if (1e-290..1e290).contains(&norm2) {
        (x, y, z, norm2)
    } else {
        let scale = x.abs() + y.abs() + z.abs();
        if scale == 0.0 {
            return None;
        }
        let r = 1.0 / scale;
        let (x, y, z) = (x * r, y * r, z * r);
        (x, y, z, x * x + y * y + z * z)
    };
    let alpha = norm2.sqrt().copysign(-x);
    let v0 = x - alpha;
    // With w = (v₀, y, z): 2/wᵀw = −1/(αv₀); scaled to v = w/v₀, τ = −v₀/α.
    let r0 = 1.0 / v0;
    Some((y * r0, z * r0, -v0 / alpha))
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

    /// A 4×4 upper Hessenberg matrix with characteristic polynomial
    /// `(λ² − s₁λ + t₁)(λ² − s₂λ + t₂)`: two companion blocks `[[0, −t], [1, s]]` on the
    /// diagonal, an upper triangle above them and a zero subdiagonal between them.
    fn blocks(s1: f64, t1: f64, s2: f64, t2: f64) -> Fixed<4> {
        [
            [0.0, 1.0, 0.0, 0.0],
            [-t1, s1, 0.0, 0.0],
            [0.7, -1.3, 0.0, 1.0],
            [0.2, 0.4, -t2, s2],
        ]
    }

    #[test]
    fn quartic_shifts_are_an_eigenvalue_pair() {
        // A complex pair −0.5 ± 3i (s = −1, t = 9.25) and the reals −2, −14 (s = −16,
        // t = 28); two real pairs; a pair 1e4 apart in size from the other.
        for (s1, t1, s2, t2) in [
            (-1.0, 9.25, -16.0, 28.0),
            (-16.0, 28.0, -1.0, 9.25),
            (3.0, 2.0, -0.1, 0.0016),
            (-2e3, 2e6, -0.4, 0.05),
        ] {
            let (s, t) = quartic_pair(&blocks(s1, t1, s2, t2), 0).expect("shifts");
            // The sum and product of one of the two pairs.
            let err = |(ss, tt): (f64, f64)| {
                ((s - ss).abs() / (1.0 + ss.abs())).max((t - tt).abs() / (1.0 + tt.abs()))
            };
            let e = err((s1, t1)).min(err((s2, t2)));
            assert!(
                e < 1e-9,
                "{s} {t} against ({s1}, {t1}) or ({s2}, {t2}): {e:e}"
            );
        }
    }

    #[test]
    fn cubic_roots() {
        // (m − 1)(m − 2)(m + 3) = m³ − 7m + 6: three real roots, the largest 2.
        assert!((largest_cubic_root(0.0, -7.0, 6.0).unwrap() - 2.0).abs() < 1e-14);
        // (m − 4)(m² + 1) = m³ − 4m² + m − 4: one real root.
        assert!((largest_cubic_root(-4.0, 1.0, -4.0).unwrap() - 4.0).abs() < 1e-14);
        // A triple root at 0.5: (m − 0.5)³.
        let m = largest_cubic_root(-1.5, 0.75, -0.125).unwrap();
        assert!((m - 0.5).abs() < 1e-5, "{m}");
        assert_eq!(largest_cubic_root(f64::MAX, f64::MAX, 1.0), None);
    }

    #[test]
    fn biquadratic_falls_back() {
        // λ⁴ + 5λ² + 4 = (λ² + 1)(λ² + 4): Q = 0 and s² = 2m − P may vanish; the shifts are
        // then a pair or the usual ones, and the eigenvalues ±i, ±2i either way.
        // Its companion matrix (unreduced Hessenberg), by columns.
        let h: Fixed<4> = [
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [-4.0, 0.0, -5.0, 0.0],
        ];
        assert!(quartic_pair(&h, 0).is_none_or(
            |(s, t)| s.abs() < 1e-12 && ((t - 1.0).abs() < 1e-12 || (t - 4.0).abs() < 1e-12)
        ));
        let mut out = [Complex64::new(0.0, 0.0); 4];
        let a: Vec<f64> = h.iter().flatten().copied().collect();
        eigenvalues_small(&a, 4, &mut out).unwrap();
        let mut mags: Vec<f64> = out.iter().map(|z| z.im.abs()).collect();
        mags.sort_by(f64::total_cmp);
        for (m, e) in mags.iter().zip([1.0, 1.0, 2.0, 2.0]) {
            assert!((m - e).abs() < 1e-13, "{out:?}");
        }
    }

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
