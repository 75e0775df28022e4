//! [`Dd`]: double-double arithmetic (about 106 significant bits, ~32 decimal digits), the
//! accuracy reference for the numeric paths.
//!
//! The algorithms are the classical error-free transformations (Knuth's two-sum, Dekker's
//! product via fused multiply-add) and Newton corrections for the division and the square root.
//! Elementary functions reduce their argument with a double-double constant and sum a Taylor
//! series; each is accurate to a few units in the last double-double place for moderate
//! arguments (|x| < 1e6), which is all a linearized model needs.

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A double-double number `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dd {
    /// Leading part.
    pub hi: f64,
    /// Trailing part.
    pub lo: f64,
}

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Dd {
    /// Zero.
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };
    /// One.
    pub const ONE: Dd = Dd { hi: 1.0, lo: 0.0 };
    /// π.
    pub const PI: Dd = Dd {
        hi: std::f64::consts::PI,
        lo: 1.2246467991473532e-16,
    };
    /// π/2.
    pub const FRAC_PI_2: Dd = Dd {
        hi: std::f64::consts::FRAC_PI_2,
        lo: 6.123233995736766e-17,
    };
    /// ln 2.
    pub const LN_2: Dd = Dd {
        hi: std::f64::consts::LN_2,
        lo: 2.3190468138462996e-17,
    };
    /// e.
    pub const E: Dd = Dd {
        hi: std::f64::consts::E,
        lo: 1.4456468917292502e-16,
    };

    /// From an `f64` (exact).
    pub const fn from_f64(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// From an `i64` (exact: split into two doubles).
    pub fn from_i64(n: i64) -> Dd {
        let hi = n as f64;
        // `n - hi` is exact in i128 and fits a double.
        let lo = (n as i128 - hi as i128) as f64;
        let (hi, lo) = quick_two_sum(hi, lo);
        Dd { hi, lo }
    }

    /// Nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// Is this NaN or infinite?
    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    /// Absolute value.
    pub fn abs(self) -> Dd {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -self
        } else {
            self
        }
    }

    /// Multiply by a power of two (exact).
    fn ldexp(self, k: i32) -> Dd {
        let f = 2f64.powi(k);
        Dd {
            hi: self.hi * f,
            lo: self.lo * f,
        }
    }

    /// `self * x` for a double `x`.
    fn mul_f64(self, x: f64) -> Dd {
        let (p, e) = two_prod(self.hi, x);
        let e = e + self.lo * x;
        let (hi, lo) = quick_two_sum(p, e);
        Dd { hi, lo }
    }

    /// Square root (Newton correction of the double result).
    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return if self.hi == 0.0 {
                Dd::ZERO
            } else {
                Dd::from_f64(f64::NAN)
            };
        }
        let y = self.hi.sqrt();
        let yy = Dd::from_f64(y) * Dd::from_f64(y);
        let r = (self - yy).hi * (0.5 / y);
        let (hi, lo) = two_sum(y, r);
        Dd { hi, lo }
    }

    /// Integer power by repeated squaring.
    pub fn powi(self, n: i64) -> Dd {
        if n == 0 {
            return Dd::ONE;
        }
        let mut base = self;
        let mut k = n.unsigned_abs();
        let mut acc = Dd::ONE;
        while k > 0 {
            if k & 1 == 1 {
                acc *= base;
            }
            base = base * base;
            k >>= 1;
        }
        if n < 0 { Dd::ONE / acc } else { acc }
    }

    /// Reduce `x = k·(π/2) + r`, `|r| ≤ π/4`; returns `(k mod 4, r)`.
    fn reduce_half_pi(self) -> (i64, Dd) {
        let k = (self.to_f64() / std::f64::consts::FRAC_PI_2).round();
        // Subtract k·π/2 with a triple-length π/2 so that moderate k lose no accuracy.
        const PIO2_3: f64 = -1.4973849048591698e-33; // third part of π/2
        let r = self - Dd::FRAC_PI_2.mul_f64(k) - Dd::from_f64(PIO2_3 * k);
        ((k as i64).rem_euclid(4), r)
    }

    fn sin_taylor(r: Dd) -> Dd {
        // sin r = r − r³/3! + r⁵/5! − …, |r| ≤ π/4: 16 terms reach 1e-34.
        let r2 = r * r;
        let mut term = r;
        let mut sum = r;
        for k in 1..=16 {
            let d = ((2 * k) * (2 * k + 1)) as f64;
            term = -(term * r2) / Dd::from_f64(d);
            sum += term;
        }
        sum
    }

    fn cos_taylor(r: Dd) -> Dd {
        let r2 = r * r;
        let mut term = Dd::ONE;
        let mut sum = Dd::ONE;
        for k in 1..=16 {
            let d = ((2 * k - 1) * (2 * k)) as f64;
            term = -(term * r2) / Dd::from_f64(d);
            sum += term;
        }
        sum
    }

    /// Sine.
    pub fn sin(self) -> Dd {
        if !self.is_finite() {
            return Dd::from_f64(f64::NAN);
        }
        let (k, r) = self.reduce_half_pi();
        match k {
            0 => Dd::sin_taylor(r),
            1 => Dd::cos_taylor(r),
            2 => -Dd::sin_taylor(r),
            _ => -Dd::cos_taylor(r),
        }
    }

    /// Cosine.
    pub fn cos(self) -> Dd {
        if !self.is_finite() {
            return Dd::from_f64(f64::NAN);
        }
        let (k, r) = self.reduce_half_pi();
        match k {
            0 => Dd::cos_taylor(r),
            1 => -Dd::sin_taylor(r),
            2 => -Dd::cos_taylor(r),
            _ => Dd::sin_taylor(r),
        }
    }

    /// Tangent.
    pub fn tan(self) -> Dd {
        self.sin() / self.cos()
    }

    /// Exponential.
    pub fn exp(self) -> Dd {
        if !self.is_finite() {
            return Dd::from_f64(self.hi.exp());
        }
        if self.hi > 709.0 {
            return Dd::from_f64(f64::INFINITY);
        }
        if self.hi < -745.0 {
            return Dd::ZERO;
        }
        // x = k ln2 + r, then r/2^10, Taylor, square ten times.
        let k = (self.hi / std::f64::consts::LN_2).round();
        let r = (self - Dd::LN_2.mul_f64(k)).ldexp(-10);
        // Carry s = exp(r) − 1 and square as (1 + s)² − 1 = 2s + s², adding the 1 only at the
        // end: squaring 1 + s itself doubled the relative error ten times (exp(1) was off by
        // 5e-30 instead of a few 1e-32).
        let mut term = r;
        let mut s = r;
        for n in 2..=12 {
            term = term * r / Dd::from_f64(n as f64);
            s += term;
        }
        for _ in 0..10 {
            s = s.ldexp(1) + s * s;
        }
        (s + Dd::ONE).ldexp(k as i32)
    }

    /// Natural logarithm (Newton on `exp`).
    pub fn ln(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::from_f64(if self.hi == 0.0 {
                f64::NEG_INFINITY
            } else {
                f64::NAN
            });
        }
        let mut y = Dd::from_f64(self.hi.ln());
        for _ in 0..2 {
            let ey = y.exp();
            y += Dd::from_f64(2.0) * (self - ey) / (self + ey);
        }
        y
    }

    /// `atan2(self, x)` (Newton correction of the double result).
    pub fn atan2(self, x: Dd) -> Dd {
        let t0 = self.to_f64().atan2(x.to_f64());
        if !t0.is_finite() {
            return Dd::from_f64(t0);
        }
        let mut t = Dd::from_f64(t0);
        for _ in 0..2 {
            let (s, c) = (t.sin(), t.cos());
            let num = self * c - x * s;
            let den = x * c + self * s;
            if den.hi == 0.0 {
                break;
            }
            t += num / den;
        }
        t
    }

    /// General power `self^e = exp(e·ln self)`.
    pub fn powf(self, e: Dd) -> Dd {
        (e * self.ln()).exp()
    }
}

impl Add for Dd {
    type Output = Dd;
    #[inline]
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        Dd { hi, lo }
    }
}
impl Sub for Dd {
    type Output = Dd;
    #[inline]
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}
impl Neg for Dd {
    type Output = Dd;
    #[inline]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}
impl Mul for Dd {
    type Output = Dd;
    #[inline]
    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        let e = e + (self.hi * o.lo + self.lo * o.hi);
        let (hi, lo) = quick_two_sum(p, e);
        Dd { hi, lo }
    }
}
impl Div for Dd {
    type Output = Dd;
    #[inline]
    fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self - o.mul_f64(q1);
        let q2 = r.hi / o.hi;
        let r = r - o.mul_f64(q2);
        let q3 = r.hi / o.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Dd { hi, lo } + Dd::from_f64(q3)
    }
}
impl AddAssign for Dd {
    fn add_assign(&mut self, o: Dd) {
        *self = *self + o;
    }
}
impl SubAssign for Dd {
    fn sub_assign(&mut self, o: Dd) {
        *self = *self - o;
    }
}
impl MulAssign for Dd {
    fn mul_assign(&mut self, o: Dd) {
        *self = *self * o;
    }
}
impl PartialOrd for Dd {
    fn partial_cmp(&self, o: &Dd) -> Option<Ordering> {
        match self.hi.partial_cmp(&o.hi) {
            Some(Ordering::Equal) => self.lo.partial_cmp(&o.lo),
            c => c,
        }
    }
}
impl fmt::Display for Dd {
    /// Prints about 32 significant digits.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.is_finite() {
            return write!(f, "{}", self.hi);
        }
        if self.hi == 0.0 {
            return write!(f, "0");
        }
        let neg = self.hi < 0.0;
        let mut x = self.abs();
        let mut exp10 = x.hi.log10().floor() as i32;
        x *= Dd::from_f64(10.0).powi(-exp10 as i64);
        if x.hi >= 10.0 {
            x = x / Dd::from_f64(10.0);
            exp10 += 1;
        } else if x.hi < 1.0 {
            x *= Dd::from_f64(10.0);
            exp10 -= 1;
        }
        let mut digits = String::new();
        for _ in 0..32 {
            let d = x.hi.floor().clamp(0.0, 9.0);
            digits.push(char::from(b'0' + d as u8));
            x = (x - Dd::from_f64(d)) * Dd::from_f64(10.0);
        }
        let sign = if neg { "-" } else { "" };
        write!(f, "{sign}{}.{}e{exp10}", &digits[..1], &digits[1..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Dd, b: Dd, tol: f64) -> bool {
        ((a - b).to_f64()).abs() <= tol * b.to_f64().abs().max(1e-300)
    }

    #[test]
    fn arithmetic_carries_extra_digits() {
        let third = Dd::ONE / Dd::from_f64(3.0);
        let back = third * Dd::from_f64(3.0);
        assert!(((back - Dd::ONE).to_f64()).abs() < 1e-31);
        let two = Dd::from_f64(2.0).sqrt();
        assert!(((two * two - Dd::from_f64(2.0)).to_f64()).abs() < 1e-31);
        assert_eq!(Dd::from_i64(i64::MAX).hi, i64::MAX as f64);
        assert_eq!(Dd::from_i64(i64::MAX).lo, -1.0);
    }

    #[test]
    fn trig_is_double_double_accurate() {
        // sin(π/10) = (√5 − 1)/4, cos(π/10) = √(10 + 2√5)/4 (exact identities).
        let x = Dd::PI / Dd::from_f64(10.0);
        let s5 = Dd::from_f64(5.0).sqrt();
        let s_exact = (s5 - Dd::ONE) / Dd::from_f64(4.0);
        let c_exact = (Dd::from_f64(10.0) + Dd::from_f64(2.0) * s5).sqrt() / Dd::from_f64(4.0);
        assert!(close(x.sin(), s_exact, 1e-30), "{}", x.sin());
        assert!(close(x.cos(), c_exact, 1e-30));
        for v in [0.1, 0.7, 2.0, -3.5, 10.0, 100.0] {
            let y = Dd::from_f64(v);
            let one = y.sin() * y.sin() + y.cos() * y.cos();
            assert!(((one - Dd::ONE).to_f64()).abs() < 1e-30, "{v}");
        }
        assert!(close(Dd::PI.sin() + Dd::PI, Dd::PI, 1e-31));
    }

    #[test]
    fn exp_ln_atan2() {
        assert!(close(Dd::ONE.exp(), Dd::E, 1e-31));
        assert!(close(Dd::E.ln(), Dd::ONE, 1e-31));
        let y = Dd::from_f64(0.3);
        assert!(close(y.exp().ln(), y, 1e-30));
        assert!(close(
            Dd::ONE.atan2(Dd::ONE) * Dd::from_f64(4.0),
            Dd::PI,
            1e-31
        ));
        assert!(close(
            Dd::from_f64(2.0).powf(Dd::from_f64(0.5)),
            Dd::from_f64(2.0).sqrt(),
            1e-30
        ));
    }

    #[test]
    fn prints_32_digits() {
        let s = format!("{}", Dd::PI);
        assert!(s.starts_with("3.14159265358979323846264338327"), "{s}");
    }
}

/// A complex double-double number `(re, im)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Cdd(Dd, Dd);

impl Cdd {
    fn add(self, o: Cdd) -> Cdd {
        Cdd(self.0 + o.0, self.1 + o.1)
    }
    fn sub(self, o: Cdd) -> Cdd {
        Cdd(self.0 - o.0, self.1 - o.1)
    }
    fn mul(self, o: Cdd) -> Cdd {
        Cdd(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn div(self, o: Cdd) -> Cdd {
        let d = o.0 * o.0 + o.1 * o.1;
        Cdd(
            (self.0 * o.0 + self.1 * o.1) / d,
            (self.1 * o.0 - self.0 * o.1) / d,
        )
    }
    fn abs2(self) -> f64 {
        (self.0 * self.0 + self.1 * self.1).to_f64()
    }
}

/// Refine an approximate eigenvalue `(re, im)` of the real matrix `a` (rows of double-doubles)
/// to double-double accuracy by Newton's method on `det(A − λI)`:
/// `λ ← λ + 1 / tr((A − λI)⁻¹)`. Converges quadratically for a simple eigenvalue; returns
/// `None` when the iteration does not settle (e.g. a multiple eigenvalue).
pub fn refine_eigenvalue(a: &[Vec<Dd>], approx: (f64, f64)) -> Option<(Dd, Dd)> {
    let n = a.len();
    let mut lam = Cdd(Dd::from_f64(approx.0), Dd::from_f64(approx.1));
    let mut last_step = f64::INFINITY;
    for _ in 0..30 {
        // LU with partial pivoting of M = A − λI (complex).
        let mut m: Vec<Vec<Cdd>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        let x = Cdd(a[i][j], Dd::ZERO);
                        if i == j { x.sub(lam) } else { x }
                    })
                    .collect()
            })
            .collect();
        let mut perm: Vec<usize> = (0..n).collect();
        for k in 0..n {
            let p = (k..n).max_by(|&x, &y| {
                m[x][k]
                    .abs2()
                    .partial_cmp(&m[y][k].abs2())
                    .unwrap_or(Ordering::Equal)
            })?;
            if m[p][k].abs2() == 0.0 {
                return Some((lam.0, lam.1)); // exactly singular: λ is an eigenvalue
            }
            m.swap(k, p);
            perm.swap(k, p);
            for i in k + 1..n {
                let f = m[i][k].div(m[k][k]);
                m[i][k] = f;
                let (upper, lower) = m.split_at_mut(i);
                for (a, b) in lower[0][k + 1..n].iter_mut().zip(&upper[k][k + 1..n]) {
                    *a = a.sub(f.mul(*b));
                }
            }
        }
        // tr(M⁻¹) = Σ_j (M⁻¹ e_j)_j.
        let mut tr = Cdd(Dd::ZERO, Dd::ZERO);
        for j in 0..n {
            let mut x: Vec<Cdd> = perm
                .iter()
                .map(|&p| {
                    if p == j {
                        Cdd(Dd::ONE, Dd::ZERO)
                    } else {
                        Cdd(Dd::ZERO, Dd::ZERO)
                    }
                })
                .collect();
            for i in 0..n {
                for k in 0..i {
                    let t = m[i][k].mul(x[k]);
                    x[i] = x[i].sub(t);
                }
            }
            for i in (0..n).rev() {
                for k in i + 1..n {
                    let t = m[i][k].mul(x[k]);
                    x[i] = x[i].sub(t);
                }
                x[i] = x[i].div(m[i][i]);
            }
            tr = tr.add(x[j]);
        }
        if tr.abs2() == 0.0 {
            return None;
        }
        let step = Cdd(Dd::ONE, Dd::ZERO).div(tr);
        lam = lam.add(step);
        let s = step.abs2().sqrt();
        let scale = lam.abs2().sqrt().max(1e-300);
        if s <= 1e-31 * scale || (s >= last_step && s <= 1e-26 * scale) {
            return Some((lam.0, lam.1));
        }
        last_step = s;
    }
    None
}
