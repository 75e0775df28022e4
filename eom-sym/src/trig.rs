//! `sin` and `cos` in `f64`, the ones every `f64` evaluation of eom-sym uses (the [`Scalar`]
//! implementation, [`Tape`], [`NativeTape`], nominal values), so that all of them agree bit
//! for bit.
//!
//! Why not the platform's `libm`: on arguments spread like those of a random DAG, glibc's
//! `sin` took 10.9 ns per call against 5.6 ns for this one (an interleaved loop on the 2-core
//! VM of 2026-11-21), and it is a call through the PLT for every node. This version is one
//! short path for |x| < 2²⁰·π/2 ≈ 1.6·10⁶ (the system's `sin`/`cos` beyond, and for NaN and
//! ±∞):
//!
//! 1. **Reduction** `x = n·π/2 + (y₀ + y₁)`, with π/2 split into pieces of 33 bits so that
//!    `n·piece` is exact for |n| < 2²⁰ (Cody and Waite). A second and third piece are used
//!    only when the first subtraction cancels more than 16 (then 49) bits, which happens near
//!    multiples of π/2. The tail `y₁` carries the rounding error of `y₀`.
//! 2. **Kernels** on |y| ≤ π/4: the degree-13 odd and degree-14 even minimax polynomials of
//!    sin and cos (the coefficients published with Sun's fdlibm, 1993, error below 2⁻⁵⁸ on
//!    the interval), with the first-order correction for `y₁`.
//!
//! Accuracy: within 1 ulp of the correctly rounded result; the tests compare with the
//! double-double reference ([`crate::Dd`]) on arguments from 10⁻³⁰⁰ to 10⁶, near multiples of
//! π/2 included, and with the system `sin`/`cos`.
//!
//! [`Scalar`]: crate::Scalar
//! [`Tape`]: crate::Tape
//! [`NativeTape`]: crate::NativeTape

/// Beyond this, the system's functions (full reduction).
const MEDIUM: f64 = 1_647_099.0; // < 2²⁰·π/2 = 1 647 099.3…

/// π/2 in pieces: `PIO2_1` holds its first 33 bits, `PIO2_1T` the rest; `PIO2_2` the next 33
/// bits, `PIO2_2T` the rest; `PIO2_3`, `PIO2_3T` likewise.
const PIO2_1: f64 = 1.570_796_326_734_125_6;
const PIO2_1T: f64 = 6.077_100_506_506_192e-11;
const PIO2_2: f64 = 6.077_100_506_303_966e-11;
const PIO2_2T: f64 = 2.022_266_248_795_950_6e-21;
const PIO2_3: f64 = 2.022_266_248_711_166_5e-21;
const PIO2_3T: f64 = 8.478_427_660_368_9e-32;

const S1: f64 = -1.666_666_666_666_663_2e-1;
const S2: f64 = 8.333_333_333_322_49e-3;
const S3: f64 = -1.984_126_982_985_795e-4;
const S4: f64 = 2.755_731_370_707_006_8e-6;
const S5: f64 = -2.505_076_025_340_686_3e-8;
const S6: f64 = 1.589_690_995_211_55e-10;

const C1: f64 = 4.166_666_666_666_66e-2;
const C2: f64 = -1.388_888_888_887_411e-3;
const C3: f64 = 2.480_158_728_947_673e-5;
const C4: f64 = -2.755_731_435_139_066_3e-7;
const C5: f64 = 2.087_572_321_298_175e-9;
const C6: f64 = -1.135_964_755_778_819_5e-11;

/// sin(x + y) for |x + y| ≤ π/4, `y` a tail below ulp(x).
#[inline(always)]
fn sin_kernel(x: f64, y: f64) -> f64 {
    let z = x * x;
    let v = z * x;
    let r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    // x + v·(S1 + z·r) + y·(1 − x²/2), arranged so that the small terms are summed first.
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// cos(x + y) for |x + y| ≤ π/4.
#[inline(always)]
fn cos_kernel(x: f64, y: f64) -> f64 {
    let z = x * x;
    let r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // 1 − z/2 + z·r − x·y, with the rounding error of `w` recovered exactly.
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// The biased exponent of `x`.
#[inline(always)]
fn exponent(x: f64) -> i64 {
    ((x.to_bits() >> 52) & 0x7ff) as i64
}

/// `x = n·π/2 + y₀ + y₁` for |x| < [`MEDIUM`]: `(n mod 4, y₀, y₁)`.
#[inline(always)]
fn reduce(x: f64) -> (u32, f64, f64) {
    // Round to nearest by adding 1.5·2⁵²: the integer lands in the low bits.
    const SHIFTER: f64 = 6_755_399_441_055_744.0;
    let t = x * std::f64::consts::FRAC_2_PI + SHIFTER;
    let n = t - SHIFTER;
    let quadrant = t.to_bits() as u32 & 3;
    let mut r = x - n * PIO2_1; // exact: n·PIO2_1 has at most 53 bits
    let mut w = n * PIO2_1T;
    let mut y0 = r - w;
    let ex = exponent(x);
    if ex - exponent(y0) > 16 {
        // Cancellation: take 33 more bits of π/2.
        let t = r;
        w = n * PIO2_2;
        r = t - w;
        w = n * PIO2_2T - ((t - r) - w);
        y0 = r - w;
        if ex - exponent(y0) > 49 {
            let t = r;
            w = n * PIO2_3;
            r = t - w;
            w = n * PIO2_3T - ((t - r) - w);
            y0 = r - w;
        }
    }
    let y1 = (r - y0) - w;
    (quadrant, y0, y1)
}

/// Sine (see the module documentation for the method and accuracy).
#[inline]
pub fn sin(x: f64) -> f64 {
    let ax = x.abs();
    if ax <= std::f64::consts::FRAC_PI_4 {
        return sin_kernel(x, 0.0);
    }
    if ax.is_nan() || ax >= MEDIUM {
        return x.sin();
    }
    let (q, y0, y1) = reduce(x);
    match q {
        0 => sin_kernel(y0, y1),
        1 => cos_kernel(y0, y1),
        2 => -sin_kernel(y0, y1),
        _ => -cos_kernel(y0, y1),
    }
}

/// Cosine (see the module documentation for the method and accuracy).
#[inline]
pub fn cos(x: f64) -> f64 {
    let ax = x.abs();
    if ax <= std::f64::consts::FRAC_PI_4 {
        return cos_kernel(x, 0.0);
    }
    if ax.is_nan() || ax >= MEDIUM {
        return x.cos();
    }
    let (q, y0, y1) = reduce(x);
    match q {
        0 => cos_kernel(y0, y1),
        1 => -sin_kernel(y0, y1),
        2 => -cos_kernel(y0, y1),
        _ => sin_kernel(y0, y1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Dd;
    use crate::testing::SplitMix;

    /// Error of `got` against the double-double `want`, in ulps of the rounded result.
    fn ulps(got: f64, want: Dd) -> f64 {
        let w = want.to_f64();
        let ulp = if w == 0.0 {
            f64::MIN_POSITIVE
        } else {
            (f64::from_bits(w.abs().to_bits() + 1) - w.abs()).max(f64::MIN_POSITIVE * f64::EPSILON)
        };
        (Dd::from_f64(got) - want).to_f64().abs() / ulp
    }

    fn arguments() -> Vec<f64> {
        let mut rng = SplitMix(42);
        let mut xs = vec![
            0.0, -0.0, 1e-300, -5e-324, 1e-9, 0.5, 0.785, 0.786, 1.0, 2.0, 3.0,
        ];
        for k in 1..2000 {
            // Near multiples of π/2, where the reduction cancels.
            let m = (Dd::PI * Dd::from_f64(0.5 * k as f64)).to_f64();
            xs.extend([m, f64::from_bits(m.to_bits() + 1), -m]);
        }
        for _ in 0..200_000 {
            let u = rng.below(1 << 30) as f64 / (1u64 << 30) as f64;
            let e = -30.0 + 36.2 * u; // 1e-30 … 1.6e6
            let s = if rng.below(2) == 0 { 1.0 } else { -1.0 };
            xs.push(s * 10f64.powf(e));
        }
        xs
    }

    /// Within 1 ulp of the double-double reference, plus the reference's own error: its
    /// reduction is good to about |x|·2⁻¹⁰⁴ absolute, which near a multiple of π/2 (a result
    /// of 10⁻¹⁵ at x = 17.3) is itself an ulp or more; those arguments are checked against
    /// the correctly rounded values below.
    #[test]
    fn within_one_ulp_of_the_double_double_reference() {
        let (mut worst_s, mut worst_c) = (0.0f64, 0.0f64);
        for x in arguments() {
            let d = Dd::from_f64(x);
            let slack = |v: f64| {
                let w = v.abs().max(f64::MIN_POSITIVE);
                x.abs() * 2f64.powi(-100) / (f64::from_bits(w.to_bits() + 1) - w)
            };
            let (s_ref, c_ref) = (d.sin(), d.cos());
            let es = ulps(sin(x), s_ref) - slack(s_ref.to_f64()).min(1e9);
            let ec = ulps(cos(x), c_ref) - slack(c_ref.to_f64()).min(1e9);
            assert!(es <= 1.0, "sin({x:e}) = {:e}: {es} ulp", sin(x));
            assert!(ec <= 1.0, "cos({x:e}) = {:e}: {ec} ulp", cos(x));
            worst_s = worst_s.max(es);
            worst_c = worst_c.max(ec);
        }
        // Far below an ulp for most arguments: a broken coefficient shows here first.
        assert!(worst_s < 0.9 && worst_c < 0.9, "{worst_s} {worst_c}");
    }

    /// Arguments closest to multiples of π/2 (k up to 10⁶, stepping by 997), where the
    /// reduction cancels 40 bits and more, with their correctly rounded sine and cosine
    /// (mpmath at 400 bits).
    #[test]
    fn hard_arguments_near_multiples_of_half_pi() {
        const CASES: [(f64, f64, f64); 9] = [
            (17.278759594743864, -1.0, 1.1028010998692062e-15),
            (931821.5137959614, 1.6947112848893244e-13, 1.0),
            (1014823.9625001305, 1.0, 2.7189763882173807e-13),
            (582584.7956633252, 1.0, 1.69964469938526e-13),
            (366465.2122449226, -1.0, -1.1899788549691999e-13),
            (258405.42053572126, 9.351459327611698e-14, -1.0),
            (150345.62882651994, 1.0, 6.803130105531397e-14),
            (1630294.9500612337, -8.483423253438493e-13, -1.0),
            (499582.3469591561, 2.714042973721445e-13, 1.0),
        ];
        let apart = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).abs();
        for (x, s, c) in CASES {
            assert!(apart(sin(x), s) <= 1, "sin({x}) = {:e}, want {s:e}", sin(x));
            assert!(apart(cos(x), c) <= 1, "cos({x}) = {:e}, want {c:e}", cos(x));
        }
    }

    #[test]
    fn special_values_and_symmetry() {
        assert_eq!(sin(0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(sin(-0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(cos(0.0), 1.0);
        assert_eq!(cos(-0.0), 1.0);
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(sin(x).is_nan() && cos(x).is_nan());
        }
        assert_eq!(sin(1e300), 1e300f64.sin());
        for x in arguments().into_iter().take(5000) {
            assert_eq!(sin(-x).to_bits(), (-sin(x)).to_bits(), "{x}");
            assert_eq!(cos(-x).to_bits(), cos(x).to_bits(), "{x}");
            // And close to the system's (both are within an ulp of the truth).
            assert!((sin(x) - x.sin()).abs() <= 2.0 * f64::EPSILON * x.sin().abs().max(1e-300));
        }
    }
}
