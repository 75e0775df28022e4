//! [`Scalar`]: the number type the assembly and elimination algorithms are generic over.
//!
//! One algorithm, many scalars: run with `f64` it is the fast numeric path; run with
//! [`Expr`] it *records* the expression DAG of every result; run with [`Dd`] (double-double)
//! it is the accuracy reference. Structural decisions (which entries exist, which pivot to
//! use) are taken from [`Scalar::is_zero`] and [`Scalar::nominal`], so all three runs make the
//! same decisions and agree by construction.

use crate::dd::Dd;
use crate::expr::Expr;
use crate::rational::Rational;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Arithmetic plus the two structural queries the elimination needs.
pub trait Scalar:
    Copy
    + PartialEq
    + Debug
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Is this a symbolic type (results are expressions whose validity elsewhere must be
    /// recorded)? Numeric types evaluate at one point, where their own pivots are valid.
    const SYMBOLIC: bool = false;
    /// Is [`Scalar::sum`] the left-to-right fold of `+` (and [`Scalar::recognise_zero`] the
    /// identity), so that a sum may be accumulated term by term in the same order, with the
    /// same value wherever it is not zero? Lets numeric products use a dense accumulator
    /// instead of gathering and sorting each entry's terms.
    const FOLD_SUM: bool = false;
    /// 0.
    fn zero() -> Self;
    /// 1.
    fn one() -> Self;
    /// An integer.
    fn from_i64(n: i64) -> Self;
    /// An exact rational (rounded for floating types).
    fn from_rational(r: &Rational) -> Self;
    /// A floating-point datum.
    fn from_f64(x: f64) -> Self;
    /// π.
    fn pi() -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// The value at the nominal point: the number itself for numeric types, the nominal value
    /// of the expression for symbolic ones. Used for pivot choices and scale-aware tests.
    fn nominal(&self) -> f64;
    /// Is this a structural zero? (`== 0` for numbers; the constant 0 for expressions.)
    fn is_zero(&self) -> bool;
    /// Is this exactly one?
    fn is_one(&self) -> bool;
    /// A short text for names and messages: the number for numeric types (the nominal value,
    /// shortest round-trip form), the expression for symbolic ones.
    fn label(&self) -> String {
        format!("{}", self.nominal())
    }
    /// `1 / self`.
    fn recip(self) -> Self {
        Self::one() / self
    }
    /// `self`, or zero when it is identically zero although not structurally (symbolic types:
    /// see [`zero`](crate::zero)); numbers are returned unchanged.
    fn recognise_zero(self) -> Self {
        self
    }
    /// `Σ items` (symbolic types build one n-ary node).
    fn sum(items: &[Self]) -> Self {
        items.iter().fold(Self::zero(), |a, &b| a + b)
    }
    /// `Σ aᵢ·bᵢ`, skipping structural zeros.
    fn dot(a: &[Self], b: &[Self]) -> Self {
        let terms: Vec<Self> = a
            .iter()
            .zip(b)
            .filter(|(x, y)| !x.is_zero() && !y.is_zero())
            .map(|(&x, &y)| x * y)
            .collect();
        Self::sum(&terms)
    }
}

impl Scalar for f64 {
    const FOLD_SUM: bool = true;
    fn zero() -> f64 {
        0.0
    }
    fn one() -> f64 {
        1.0
    }
    fn from_i64(n: i64) -> f64 {
        n as f64
    }
    fn from_rational(r: &Rational) -> f64 {
        r.to_f64()
    }
    fn from_f64(x: f64) -> f64 {
        x
    }
    fn pi() -> f64 {
        std::f64::consts::PI
    }
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    // The `libm` crate's (musl's) sine and cosine: every f64 evaluation path goes through
    // these, and they are the same on every platform (the system's may differ by an ulp).
    fn sin(self) -> f64 {
        libm::sin(self)
    }
    fn cos(self) -> f64 {
        libm::cos(self)
    }
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    fn nominal(&self) -> f64 {
        *self
    }
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
    fn is_one(&self) -> bool {
        *self == 1.0
    }
    fn recip(self) -> f64 {
        1.0 / self
    }
    fn sum(items: &[f64]) -> f64 {
        items.iter().sum()
    }
    fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }
}

impl Scalar for Dd {
    fn zero() -> Dd {
        Dd::ZERO
    }
    fn one() -> Dd {
        Dd::ONE
    }
    fn from_i64(n: i64) -> Dd {
        Dd::from_i64(n)
    }
    fn from_rational(r: &Rational) -> Dd {
        match r.as_small() {
            Some((n, 1)) => Dd::from_i64(n),
            Some((n, d)) => Dd::from_i64(n) / Dd::from_i64(d),
            None => big_to_dd(r),
        }
    }
    fn from_f64(x: f64) -> Dd {
        Dd::from_f64(x)
    }
    fn pi() -> Dd {
        Dd::PI
    }
    fn sqrt(self) -> Dd {
        Dd::sqrt(self)
    }
    fn sin(self) -> Dd {
        Dd::sin(self)
    }
    fn cos(self) -> Dd {
        Dd::cos(self)
    }
    fn abs(self) -> Dd {
        Dd::abs(self)
    }
    fn nominal(&self) -> f64 {
        self.to_f64()
    }
    fn is_zero(&self) -> bool {
        self.hi == 0.0 && self.lo == 0.0
    }
    fn is_one(&self) -> bool {
        self.hi == 1.0 && self.lo == 0.0
    }
}

/// A wide rational as `hi + lo`: `hi` its nearest double, `lo` the nearest double of the exact
/// remainder `r − hi`. (Converting the numerator and the denominator separately went through
/// `i128`, which saturates above 2¹²⁷ — 134¹⁸ came out 12 % too large — and gave `inf/inf`
/// for parts beyond the `f64` range even when the quotient is moderate.)
fn big_to_dd(r: &Rational) -> Dd {
    use num_traits::ToPrimitive;
    let hi = r.to_f64();
    if !hi.is_finite() {
        return Dd::from_f64(hi);
    }
    let (n, d) = r.to_big_parts();
    let lo = num_rational::BigRational::from_float(hi)
        .and_then(|h| (num_rational::BigRational::new(n, d) - h).to_f64())
        .unwrap_or(0.0);
    Dd::from_f64(hi) + Dd::from_f64(lo)
}

impl Scalar for Expr {
    const SYMBOLIC: bool = true;
    fn label(&self) -> String {
        self.to_string()
    }
    fn zero() -> Expr {
        Expr::zero()
    }
    fn one() -> Expr {
        Expr::one()
    }
    fn from_i64(n: i64) -> Expr {
        Expr::int(n)
    }
    fn from_rational(r: &Rational) -> Expr {
        Expr::from_rational(r.clone())
    }
    fn from_f64(x: f64) -> Expr {
        // Non-finite data is an invalid node: the error surfaces at `check`/evaluation.
        Expr::float(x).unwrap_or_else(Expr::invalid)
    }
    fn pi() -> Expr {
        Expr::pi()
    }
    fn sqrt(self) -> Expr {
        Expr::sqrt(self)
    }
    fn sin(self) -> Expr {
        Expr::sin(self)
    }
    fn cos(self) -> Expr {
        Expr::cos(self)
    }
    fn abs(self) -> Expr {
        Expr::abs(self)
    }
    fn nominal(&self) -> f64 {
        Expr::nominal(*self)
    }
    fn is_zero(&self) -> bool {
        Expr::is_zero(*self)
    }
    fn is_one(&self) -> bool {
        Expr::is_one(*self)
    }
    fn recip(self) -> Expr {
        Expr::recip(self)
    }
    fn recognise_zero(self) -> Expr {
        crate::zero::zero_if_identically_zero(self)
    }
    fn sum(items: &[Expr]) -> Expr {
        Expr::sum(items.iter().copied())
    }
}

/// The remaining elementary functions, needed to evaluate arbitrary expressions in a scalar
/// type (the assembly itself only needs [`Scalar`]).
pub trait Elementary: Scalar {
    /// Tangent.
    fn tan(self) -> Self;
    /// Exponential.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// `atan2(self, x)`.
    fn atan2(self, x: Self) -> Self;
    /// `self ^ e` for a real exponent.
    fn powf(self, e: Self) -> Self;
    /// Euler's number. The default is `exp(1)`; types with the constant itself override it
    /// (for [`Expr`], so that substitution keeps the node `e` instead of building `exp(1)`).
    fn e() -> Self {
        Self::one().exp()
    }
    /// `self ^ n` for an integer exponent.
    fn powi(self, n: i64) -> Self {
        if n == 0 {
            return Self::one();
        }
        let mut base = self;
        let mut k = n.unsigned_abs();
        let mut acc: Option<Self> = None;
        while k > 0 {
            if k & 1 == 1 {
                acc = Some(match acc {
                    Some(a) => a * base,
                    None => base,
                });
            }
            k >>= 1;
            if k > 0 {
                base = base * base;
            }
        }
        let acc = acc.unwrap_or_else(Self::one);
        if n < 0 { acc.recip() } else { acc }
    }
}

impl Elementary for f64 {
    fn tan(self) -> f64 {
        f64::tan(self)
    }
    fn exp(self) -> f64 {
        f64::exp(self)
    }
    fn ln(self) -> f64 {
        f64::ln(self)
    }
    fn atan2(self, x: f64) -> f64 {
        f64::atan2(self, x)
    }
    fn powf(self, e: f64) -> f64 {
        f64::powf(self, e)
    }
    fn powi(self, n: i64) -> f64 {
        f64::powi(self, n.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
    }
    fn e() -> f64 {
        std::f64::consts::E
    }
}

impl Elementary for Dd {
    fn tan(self) -> Dd {
        Dd::tan(self)
    }
    fn exp(self) -> Dd {
        Dd::exp(self)
    }
    fn ln(self) -> Dd {
        Dd::ln(self)
    }
    fn atan2(self, x: Dd) -> Dd {
        Dd::atan2(self, x)
    }
    fn powf(self, e: Dd) -> Dd {
        Dd::powf(self, e)
    }
    fn powi(self, n: i64) -> Dd {
        Dd::powi(self, n)
    }
    fn e() -> Dd {
        Dd::E
    }
}

impl Elementary for Expr {
    fn tan(self) -> Expr {
        Expr::tan(self)
    }
    fn exp(self) -> Expr {
        Expr::exp(self)
    }
    fn ln(self) -> Expr {
        Expr::ln(self)
    }
    fn atan2(self, x: Expr) -> Expr {
        Expr::atan2(self, x)
    }
    fn powf(self, e: Expr) -> Expr {
        Expr::pow(self, e)
    }
    fn powi(self, n: i64) -> Expr {
        Expr::powi(self, n)
    }
    fn e() -> Expr {
        Expr::e()
    }
}
