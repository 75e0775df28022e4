//! Exact rational numbers with overflow promotion.
//!
//! A [`Rational`] is a reduced fraction with a positive denominator. Values that fit in `i64`
//! are stored inline; anything larger is promoted to an arbitrary-precision fraction, so
//! arithmetic never wraps. To keep a runaway computation (say `3^(10^9)`) from eating the
//! machine, results wider than [`MAX_BITS`] are refused with [`RationalOverflow`]; the
//! expression layer then keeps the operation unfolded or reports a typed error.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;

/// Largest width (in bits) of a numerator or denominator that eom will carry exactly.
pub const MAX_BITS: u64 = 4096;

/// An exact rational result would exceed [`MAX_BITS`] bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RationalOverflow;

/// An exact rational number (reduced, positive denominator).
#[derive(Clone, PartialEq, Eq, Hash)]
pub enum Rational {
    /// Fits in 64 bits: `num / den`, `den > 0`, `gcd(num, den) = 1`.
    Small(i64, i64),
    /// Arbitrary precision (only when it does not fit `Small`).
    Big(Box<BigRational>),
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational::Small(0, 1);
    /// One.
    pub const ONE: Rational = Rational::Small(1, 1);
    /// Minus one.
    pub const MINUS_ONE: Rational = Rational::Small(-1, 1);

    /// The integer `n`.
    pub fn int(n: i64) -> Self {
        Rational::Small(n, 1)
    }

    /// `num / den`, reduced. `None` if `den == 0`.
    pub fn new(num: i64, den: i64) -> Option<Self> {
        if den == 0 {
            return None;
        }
        Some(Self::from_i128(num as i128, den as i128))
    }

    fn from_i128(mut n: i128, mut d: i128) -> Self {
        debug_assert!(d != 0);
        if d < 0 {
            n = -n;
            d = -d;
        }
        // Integers need no reduction (the gcd is the costly part of small arithmetic).
        if d == 1
            && let Ok(n) = i64::try_from(n)
        {
            return Rational::Small(n, 1);
        }
        let g = n.gcd(&d);
        if g > 1 {
            n /= g;
            d /= g;
        }
        match (i64::try_from(n), i64::try_from(d)) {
            (Ok(n), Ok(d)) => Rational::Small(n, d),
            _ => Rational::Big(Box::new(BigRational::new(BigInt::from(n), BigInt::from(d)))),
        }
    }

    fn from_big(r: BigRational) -> Result<Self, RationalOverflow> {
        if r.numer().bits() > MAX_BITS || r.denom().bits() > MAX_BITS {
            return Err(RationalOverflow);
        }
        match (r.numer().to_i64(), r.denom().to_i64()) {
            (Some(n), Some(d)) => Ok(Rational::Small(n, d)),
            _ => Ok(Rational::Big(Box::new(r))),
        }
    }

    fn to_big(&self) -> BigRational {
        match self {
            Rational::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Rational::Big(b) => (**b).clone(),
        }
    }

    /// Exact conversion of a finite `f64` (every finite double is a dyadic rational).
    /// `None` for NaN or infinity, or if the exact value needs more than [`MAX_BITS`].
    pub fn from_f64_exact(x: f64) -> Option<Self> {
        if !x.is_finite() {
            return None;
        }
        BigRational::from_float(x).and_then(|r| Self::from_big(r).ok())
    }

    /// Parse a decimal literal such as `12`, `-1.5`, `1.5e3`, `2E-4` exactly.
    pub fn from_decimal(s: &str) -> Option<Self> {
        if let Some(rest) = s.strip_prefix('-') {
            return Self::from_decimal(rest).map(|r| r.neg());
        }
        let s = s.strip_prefix('+').unwrap_or(s);
        if s.starts_with(['-', '+']) {
            return None;
        }
        let (mant, exp) = match s.find(['e', 'E']) {
            Some(i) => (&s[..i], s[i + 1..].parse::<i64>().ok()?),
            None => (s, 0),
        };
        let (int_part, frac_part) = match mant.find('.') {
            Some(i) => (&mant[..i], &mant[i + 1..]),
            None => (mant, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        if !int_part
            .bytes()
            .chain(frac_part.bytes())
            .all(|b| b.is_ascii_digit())
        {
            return None;
        }
        let scale = exp.checked_sub(frac_part.len() as i64)?;
        // 10^|scale| must stay inside MAX_BITS (log2 10 ≈ 3.32).
        if scale.unsigned_abs() > MAX_BITS / 3 {
            return None;
        }
        // More than MAX_BITS significant digits cannot fit even after dividing by 10^|scale|:
        // refused before the (quadratic) conversion of the digits.
        let significant = (int_part.bytes().chain(frac_part.bytes()))
            .skip_while(|&b| b == b'0')
            .count();
        if significant as u64 > MAX_BITS {
            return None;
        }
        let digits = format!("{int_part}{frac_part}");
        let mut num: BigInt = digits.parse().ok()?;
        let ten = BigInt::from(10);
        let p = num_traits::pow(ten, scale.unsigned_abs() as usize);
        let r = if scale >= 0 {
            num *= p;
            BigRational::from_integer(num)
        } else {
            BigRational::new(num, p)
        };
        Self::from_big(r).ok()
    }

    /// Is this zero?
    pub fn is_zero(&self) -> bool {
        matches!(self, Rational::Small(0, _))
    }
    /// Is this one?
    pub fn is_one(&self) -> bool {
        matches!(self, Rational::Small(1, 1))
    }
    /// Is this an integer?
    pub fn is_integer(&self) -> bool {
        match self {
            Rational::Small(_, d) => *d == 1,
            Rational::Big(b) => b.is_integer(),
        }
    }
    /// The value as `i64` if it is an integer that fits.
    pub fn to_i64(&self) -> Option<i64> {
        match self {
            Rational::Small(n, 1) => Some(*n),
            _ => None,
        }
    }
    /// Sign: -1, 0 or 1.
    pub fn signum(&self) -> i32 {
        match self {
            Rational::Small(n, _) => n.signum() as i32,
            Rational::Big(b) => {
                if b.is_negative() {
                    -1
                } else if b.is_zero() {
                    0
                } else {
                    1
                }
            }
        }
    }
    /// Is this strictly negative?
    pub fn is_negative(&self) -> bool {
        self.signum() < 0
    }

    /// Numerator and denominator as small integers, if they fit.
    pub fn as_small(&self) -> Option<(i64, i64)> {
        match self {
            Rational::Small(n, d) => Some((*n, *d)),
            Rational::Big(_) => None,
        }
    }

    /// Nearest `f64` (correctly rounded for small values; big values via `BigRational`).
    pub fn to_f64(&self) -> f64 {
        match self {
            Rational::Small(n, d) => {
                if n.unsigned_abs() < (1 << 53) && d.unsigned_abs() < (1 << 53) {
                    *n as f64 / *d as f64
                } else {
                    BigRational::new_raw(BigInt::from(*n), BigInt::from(*d))
                        .to_f64()
                        .unwrap_or(f64::NAN)
                }
            }
            Rational::Big(b) => b.to_f64().unwrap_or(f64::NAN),
        }
    }

    /// Numerator and denominator as big integers.
    pub fn to_big_parts(&self) -> (BigInt, BigInt) {
        let b = self.to_big();
        (b.numer().clone(), b.denom().clone())
    }

    /// `-self`.
    pub fn neg(&self) -> Rational {
        match self {
            Rational::Small(n, d) => Rational::from_i128(-(*n as i128), *d as i128),
            Rational::Big(b) => {
                Rational::from_big(-(**b).clone()).expect("negation keeps the width")
            }
        }
    }

    /// `|self|`.
    pub fn abs(&self) -> Rational {
        if self.is_negative() {
            self.neg()
        } else {
            self.clone()
        }
    }

    /// `self + o`.
    pub fn add(&self, o: &Rational) -> Result<Rational, RationalOverflow> {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, o) {
            // Fast paths (exact): integers, and adding zero.
            if *b == 1
                && *d == 1
                && let Some(n) = a.checked_add(*c)
            {
                return Ok(Rational::Small(n, 1));
            }
            if *a == 0 {
                return Ok(o.clone());
            }
            if *c == 0 {
                return Ok(self.clone());
            }
            let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
            if let (Some(x), Some(y)) = (a.checked_mul(d), c.checked_mul(b))
                && let (Some(n), Some(den)) = (x.checked_add(y), b.checked_mul(d))
            {
                return Ok(Rational::from_i128(n, den));
            }
        }
        Self::from_big(self.to_big() + o.to_big())
    }

    /// `self - o`.
    pub fn sub(&self, o: &Rational) -> Result<Rational, RationalOverflow> {
        self.add(&o.neg())
    }

    /// `self · o`.
    pub fn mul(&self, o: &Rational) -> Result<Rational, RationalOverflow> {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, o) {
            // Fast paths (exact): integers, and multiplying by one.
            if *b == 1
                && *d == 1
                && let Some(n) = a.checked_mul(*c)
            {
                return Ok(Rational::Small(n, 1));
            }
            if *a == 1 && *b == 1 {
                return Ok(o.clone());
            }
            if *c == 1 && *d == 1 {
                return Ok(self.clone());
            }
            let n = (*a as i128) * (*c as i128);
            let den = (*b as i128) * (*d as i128);
            return Ok(Rational::from_i128(n, den));
        }
        Self::from_big(self.to_big() * o.to_big())
    }

    /// `1 / self`; `None` for zero.
    pub fn recip(&self) -> Option<Rational> {
        match self {
            Rational::Small(0, _) => None,
            Rational::Small(n, d) => Some(Rational::from_i128(*d as i128, *n as i128)),
            Rational::Big(b) => Rational::from_big(b.recip()).ok(),
        }
    }

    /// `self / o`; `None` for division by zero.
    pub fn div(&self, o: &Rational) -> Option<Result<Rational, RationalOverflow>> {
        o.recip().map(|r| self.mul(&r))
    }

    /// `self^e` for an integer exponent. `None` for `0^negative`.
    pub fn powi(&self, e: i64) -> Option<Result<Rational, RationalOverflow>> {
        if e == 0 {
            return Some(Ok(Rational::ONE));
        }
        if self.is_zero() {
            return if e > 0 {
                Some(Ok(Rational::ZERO))
            } else {
                None
            };
        }
        let base = if e < 0 { self.recip()? } else { self.clone() };
        let k = e.unsigned_abs();
        let (n, d) = base.to_big_parts();
        // Refuse before computing only when the result is certainly too wide: for a part of
        // b ≥ 2 bits, k·(b − 1) < bits(part^k) ≤ k·b. (Refusing on the upper bound k·b refused
        // 2^3000, which has 3001 bits, while (2^1000)^3 was accepted.) Otherwise the result has
        // at most about 2·MAX_BITS bits; compute it and let `from_big` check the exact width.
        let bits = n.bits().max(d.bits());
        let trivial = n.magnitude().is_one() && d.is_one();
        if !trivial && k.saturating_mul(bits.saturating_sub(1)) >= MAX_BITS {
            return Some(Err(RationalOverflow));
        }
        let r = BigRational::new(
            num_traits::pow(n, k as usize),
            num_traits::pow(d, k as usize),
        );
        Some(Self::from_big(r))
    }

    /// Exact `q`-th root for small values (`self^(1/q)`) when the result is rational.
    pub fn exact_root(&self, q: u32) -> Option<Rational> {
        let (n, d) = self.as_small()?;
        if n < 0 && q.is_multiple_of(2) {
            return None;
        }
        let rn = int_root(n.unsigned_abs(), q)?;
        let rd = int_root(d.unsigned_abs(), q)?;
        let rn = if n < 0 { -(rn as i64) } else { rn as i64 };
        Rational::new(rn, rd as i64)
    }
}

fn int_root(x: u64, q: u32) -> Option<u64> {
    if x < 2 {
        return Some(x);
    }
    let guess = (x as f64).powf(1.0 / q as f64).round() as u64;
    (guess.saturating_sub(1)..=guess + 1).find(|&c| c.checked_pow(q) == Some(x))
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, other) {
            return ((*a as i128) * (*d as i128)).cmp(&((*c as i128) * (*b as i128)));
        }
        self.to_big().cmp(&other.to_big())
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rational::Small(n, 1) => write!(f, "{n}"),
            Rational::Small(n, d) => write!(f, "{n}/{d}"),
            Rational::Big(b) if b.is_integer() => write!(f, "{}", b.numer()),
            Rational::Big(b) => write!(f, "{}/{}", b.numer(), b.denom()),
        }
    }
}
impl fmt::Debug for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: i64) -> Rational {
        Rational::new(n, d).unwrap()
    }

    #[test]
    fn reduces_and_normalises_sign() {
        assert_eq!(r(2, -4), r(-1, 2));
        assert_eq!(r(0, -5), Rational::ZERO);
        assert!(Rational::new(1, 0).is_none());
    }

    #[test]
    fn promotes_instead_of_wrapping() {
        let big = Rational::int(i64::MAX);
        let s = big.add(&big).unwrap();
        assert!(matches!(s, Rational::Big(_)));
        assert_eq!(s.to_f64(), 2.0 * i64::MAX as f64);
        // and demotes back when the result fits
        let back = s.sub(&big).unwrap();
        assert_eq!(back, Rational::int(i64::MAX));
        let p = Rational::int(i64::MIN).mul(&Rational::int(-1)).unwrap();
        assert!(matches!(p, Rational::Big(_)));
    }

    #[test]
    fn overflow_is_refused_not_wrapped() {
        assert_eq!(
            Rational::int(3).powi(1_000_000_000),
            Some(Err(RationalOverflow))
        );
        assert_eq!(
            Rational::int(-1).powi(1_000_000_001),
            Some(Ok(Rational::int(-1)))
        );
        assert!(Rational::ZERO.powi(-1).is_none());
        assert_eq!(r(2, 3).powi(-2), Some(Ok(r(9, 4))));
    }

    #[test]
    fn decimals_are_exact() {
        assert_eq!(Rational::from_decimal("0.21"), Some(r(21, 100)));
        assert_eq!(Rational::from_decimal("1.5e3"), Some(Rational::int(1500)));
        assert_eq!(Rational::from_decimal("2E-4"), Some(r(1, 5000)));
        assert_eq!(Rational::from_decimal(".5"), Some(r(1, 2)));
        assert_eq!(Rational::from_decimal("5."), Some(Rational::int(5)));
        assert_eq!(Rational::from_decimal("1e999999"), None);
        assert_eq!(Rational::from_decimal("."), None);
    }

    #[test]
    fn exact_f64_and_roots() {
        assert_eq!(Rational::from_f64_exact(0.5), Some(r(1, 2)));
        assert_eq!(Rational::from_f64_exact(f64::NAN), None);
        assert_eq!(r(4, 9).exact_root(2), Some(r(2, 3)));
        assert_eq!(r(-8, 27).exact_root(3), Some(r(-2, 3)));
        assert_eq!(r(2, 1).exact_root(2), None);
        assert!(r(1, 3) < r(1, 2));
    }
}
