//! What the fast path's tests cost: the simplified shimmy (`--simplify`) written by hand with
//! different tests, called from the driver next to the generated code. Not generated code and
//! not for use: a measurement.
//!
//! * `anatomy_no_tests`: the arithmetic and the stores only.
//! * `anatomy_pivot`: plus the pivot test `|I + m l² x²| ≥ 2⁻⁶⁰`, which is ready early.
//! * `anatomy_sinks`: pivot, and the finiteness of the sum of the finiteness sinks (the values
//!   no other tested value depends on), which is ready only after the last entry.
//! * `anatomy_magnitude`: pivot, and the parameters' magnitudes (`Σ|p| < 2⁶⁰`), both ready
//!   early: what the generated code did before the varying kernel.
//! * `anatomy_varying_no_tests`: the arithmetic and the varying entries' stores only (what
//!   `eval_abcd_varying` would cost without any test).
//! * `anatomy_best`: the fewest instructions found by hand with the generated code's
//!   guarantees: `m·(l x)²` with `m·l x` shared, every entry one multiplication after the
//!   division, one packed test of the two lanes' magnitudes, and the pivot test.
//!
//! See the README for the figures.

#[inline(always)]
fn values(p: &[f64; 6]) -> (f64, [f64; 8]) {
    let (m, i, k, l, x, u) = (p[0], p[1], p[2], p[3], p[4], p[5]);
    let pivot = i + m * (l * l) * (x * x);
    let r = 1.0 / pivot;
    let lr = l * r;
    let klr = k * lr;
    let lx = l * x;
    let kd = k * (lx - l);
    let a21 = kd * lr;
    let xlr = x * lr;
    let a22 = m * u * xlr;
    (pivot, [klr, u, a21, lx, a22, xlr, k, kd])
}

#[inline(always)]
fn store(v: &[f64; 8], a: &mut [f64; 9], b: &mut [f64; 3], c: &mut [f64; 6]) {
    a[2] = -v[0];
    a[3] = v[1];
    a[5] = v[2];
    a[6] = v[3];
    a[7] = 1.0;
    a[8] = -v[4];
    b[2] = -v[5];
    c[0] = -v[6];
    c[1] = -1.0;
    c[2] = v[7];
}

#[cold]
#[inline(never)]
fn failed() -> i32 {
    1
}

/// The driver's pointers as the shimmy's arrays.
///
/// # Safety
/// The pointers must point to 6, 9, 3 and 6 valid `f64`, the last three not aliased.
unsafe fn arrays<'x>(
    p: *const f64,
    a: *mut f64,
    b: *mut f64,
    c: *mut f64,
) -> (&'x [f64; 6], &'x mut [f64; 9], &'x mut [f64; 3], &'x mut [f64; 6]) {
    unsafe {
        (
            &*(p as *const [f64; 6]),
            &mut *(a as *mut [f64; 9]),
            &mut *(b as *mut [f64; 3]),
            &mut *(c as *mut [f64; 6]),
        )
    }
}

const TINY: f64 = 8.673617379884035e-19;

/// `extern "C" fn NAME(p, a, b, c, d) -> i32`: the values by `$values`, the test `$ok`, the
/// stores by `$store` (default: [`values`] and [`store`]).
macro_rules! variant {
    ($name:ident, |$q:ident, $pivot:ident, $v:ident| $ok:expr) => {
        variant!($name, values, store, |$q, $pivot, $v| $ok);
    };
    ($name:ident, $values:ident, $store:ident, |$q:ident, $pivot:ident, $v:ident| $ok:expr) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            p: *const f64,
            a: *mut f64,
            b: *mut f64,
            c: *mut f64,
            _d: *mut f64,
        ) -> i32 {
            let (p, a, b, c) = unsafe { arrays(p, a, b, c) };
            let ($pivot, $v) = $values(p);
            let $q = p;
            if !($ok) {
                return failed();
            }
            $store(&$v, a, b, c);
            0
        }
    };
}

variant!(anatomy_no_tests, |q, pivot, v| {
    let _ = (q, pivot, &v);
    true
});
variant!(anatomy_pivot, |q, pivot, v| {
    let _ = (q, &v);
    pivot.abs() >= TINY
});
variant!(anatomy_sinks, |q, pivot, v| {
    let _ = q;
    let s = (v[0] + v[2]) + (v[4] + pivot);
    (pivot.abs() >= TINY) & (s - s == 0.0)
});

const BIG: f64 = 1.152921504606847e18;

variant!(anatomy_magnitude, |q, pivot, v| {
    let _ = &v;
    let size = (q[0].abs() + q[2].abs() + q[4].abs()) + (q[1].abs() + q[3].abs() + q[5].abs());
    (size < BIG) & (pivot.abs() >= TINY)
});

/// The varying entries (no constant stores).
#[inline(always)]
fn store_varying(v: &[f64; 8], a: &mut [f64; 9], b: &mut [f64; 3], c: &mut [f64; 6]) {
    a[2] = -v[0];
    a[3] = v[1];
    a[5] = v[2];
    a[6] = v[3];
    a[8] = -v[4];
    b[2] = -v[5];
    c[0] = -v[6];
    c[2] = v[7];
}

variant!(anatomy_varying_no_tests, values, store_varying, |q, pivot, v| {
    let _ = (q, pivot, &v);
    true
});

/// Every entry one multiplication after the division, `m·l x` shared.
#[inline(always)]
fn values_best(p: &[f64; 6]) -> (f64, [f64; 8]) {
    let (m, i, k, l, x, u) = (p[0], p[1], p[2], p[3], p[4], p[5]);
    let lx = l * x;
    let mlx = m * lx;
    let pivot = i + mlx * lx;
    let r = 1.0 / pivot;
    let kd = k * (lx - l);
    (pivot, [(k * l) * r, u, (kd * l) * r, lx, (mlx * u) * r, lx * r, k, kd])
}

variant!(anatomy_best, values_best, store_varying, |q, pivot, v| {
    let _ = &v;
    let even = q[0].abs() + q[2].abs() + q[4].abs();
    let odd = q[1].abs() + q[3].abs() + q[5].abs();
    (even < BIG) & (odd < BIG) & (pivot.abs() >= TINY)
});
