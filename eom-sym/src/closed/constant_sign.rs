//! The sign of a constant expression (no parameters), decided rigorously: the expression is
//! evaluated in interval arithmetic, every operation rounded outward and every elementary
//! function widened by a few units in the last place beyond its argument's spread, so the
//! interval holds the exact value. Its sign is decided only when the interval excludes zero.
//!
//! The closed forms meet such constants when every parameter is substituted by its exact
//! value: `sin(3/10)·…` stays an exact expression that the parameters' declared signs cannot
//! decide (issue 29, item 4).

use crate::expr::{Expr, ExprView};
use crate::func::Func;
use crate::pool::Constant;
use crate::rational::Rational;
use hashbrown::HashMap;

/// The sign of the constant `e`: `Some(true)` positive, `Some(false)` negative, `None` when
/// `e` depends on a parameter, when its interval holds zero (too close to zero to decide in
/// double precision, or exactly zero) or when an operation has no enclosure here.
pub(crate) fn constant_sign(e: Expr) -> Option<bool> {
    if !e.params().is_empty() {
        return None;
    }
    let x = enclose(e, &mut HashMap::new())?;
    if x.lo > 0.0 {
        Some(true)
    } else if x.hi < 0.0 {
        Some(false)
    } else {
        None
    }
}

/// A closed interval `[lo, hi]` of finite bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Interval {
    lo: f64,
    hi: f64,
}

/// Relative widening of an elementary function's result: libm's functions are accurate to
/// about one unit in the last place; four leave a margin.
const FUNC_ULPS: f64 = 4.0 * f64::EPSILON;

impl Interval {
    /// `[lo, hi]`, `None` unless both are finite and ordered.
    fn new(lo: f64, hi: f64) -> Option<Interval> {
        (lo.is_finite() && hi.is_finite() && lo <= hi).then_some(Interval { lo, hi })
    }

    /// The value `x` rounded once: one ulp either side.
    fn around(x: f64) -> Option<Interval> {
        Interval::new(x.next_down(), x.next_up())
    }

    /// Exactly `x`.
    fn point(x: f64) -> Option<Interval> {
        Interval::new(x, x)
    }

    fn rational(r: &Rational) -> Option<Interval> {
        match r.as_small() {
            // Exactly representable: integers below 2⁵³.
            Some((n, 1)) if n.unsigned_abs() < (1 << 53) => Interval::point(n as f64),
            // One correctly rounded division (or a conversion of a big fraction, two roundings
            // at most): two ulps either side.
            _ => {
                let x = r.to_f64();
                Interval::new(x.next_down().next_down(), x.next_up().next_up())
            }
        }
    }

    fn add(self, o: Interval) -> Option<Interval> {
        Interval::new((self.lo + o.lo).next_down(), (self.hi + o.hi).next_up())
    }

    fn mul(self, o: Interval) -> Option<Interval> {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Interval::new(lo.next_down(), hi.next_up())
    }

    fn recip(self) -> Option<Interval> {
        if self.lo <= 0.0 && self.hi >= 0.0 {
            return None;
        }
        Interval::new((1.0 / self.hi).next_down(), (1.0 / self.lo).next_up())
    }

    fn powi(self, n: i64) -> Option<Interval> {
        let base = if n < 0 { self.recip()? } else { self };
        let mut out = Interval::point(1.0)?;
        for _ in 0..n.unsigned_abs().min(64) {
            out = out.mul(base)?;
        }
        (n.unsigned_abs() <= 64).then_some(out)
    }

    /// `[f(lo), f(hi)]` of a non-decreasing `f`, widened for its rounding.
    fn monotone(self, f: impl Fn(f64) -> f64) -> Option<Interval> {
        widen(f(self.lo), f(self.hi))
    }

    /// `sin` or `cos` (1-Lipschitz): within the spread of the argument of its value at `lo`.
    fn lipschitz(self, f: impl Fn(f64) -> f64) -> Option<Interval> {
        let y = f(self.lo);
        let spread = (self.hi - self.lo).next_up();
        let lo = (y - spread).next_down().max(-1.0);
        let hi = (y + spread).next_up().min(1.0);
        widen(lo, hi)
    }

    fn func(self, f: Func) -> Option<Interval> {
        match f {
            Func::Sin => self.lipschitz(f64::sin),
            Func::Cos => self.lipschitz(f64::cos),
            // Increasing between poles: only where cos keeps its sign.
            Func::Tan => {
                let c = self.lipschitz(f64::cos)?;
                (c.lo > 0.0 || c.hi < 0.0).then_some(())?;
                self.monotone(f64::tan)
            }
            Func::Exp => self.monotone(f64::exp),
            Func::Ln => (self.lo > 0.0).then(|| self.monotone(f64::ln))?,
            Func::Abs => {
                if self.lo >= 0.0 {
                    Some(self)
                } else if self.hi <= 0.0 {
                    Interval::new(-self.hi, -self.lo)
                } else {
                    Interval::new(0.0, self.hi.max(-self.lo))
                }
            }
        }
    }

    /// `selfᵉ` for a positive base (`exp(e·ln self)`).
    fn powf(self, e: Interval) -> Option<Interval> {
        (self.lo > 0.0).then_some(())?;
        self.func(Func::Ln)?.mul(e)?.func(Func::Exp)
    }
}

/// `[lo, hi]` widened by [`FUNC_ULPS`] of its magnitude and the smallest normal number.
fn widen(lo: f64, hi: f64) -> Option<Interval> {
    let pad = |x: f64| x.abs() * FUNC_ULPS + f64::MIN_POSITIVE;
    Interval::new(lo - pad(lo), hi + pad(hi))
}

/// An interval holding the exact value of the constant `e` (memoised over the DAG).
fn enclose(e: Expr, memo: &mut HashMap<Expr, Interval>) -> Option<Interval> {
    if let Some(x) = memo.get(&e) {
        return Some(*x);
    }
    let x = match e.view() {
        ExprView::Rational(r) => Interval::rational(&r)?,
        ExprView::Float(x) => Interval::point(x)?,
        ExprView::Constant(Constant::Pi) => Interval::around(std::f64::consts::PI)?,
        ExprView::Constant(Constant::E) => Interval::around(std::f64::consts::E)?,
        ExprView::Sum { constant, terms } => {
            let mut acc = enclose(constant, memo)?;
            for (t, c) in terms {
                acc = acc.add(enclose(t, memo)?.mul(enclose(c, memo)?)?)?;
            }
            acc
        }
        ExprView::Product { coef, factors } => {
            let mut acc = enclose(coef, memo)?;
            for (base, exponent) in factors {
                let b = enclose(base, memo)?;
                let p = match exponent.to_i64() {
                    Some(n) => b.powi(n)?,
                    None => b.powf(Interval::rational(&exponent)?)?,
                };
                acc = acc.mul(p)?;
            }
            acc
        }
        ExprView::Pow(base, exponent) => enclose(base, memo)?.powf(enclose(exponent, memo)?)?,
        ExprView::Func(f, arg) => enclose(arg, memo)?.func(f)?,
        ExprView::Param(..) | ExprView::Atan2(..) | ExprView::Invalid(_) => return None,
    };
    memo.insert(e, x);
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: i64) -> Expr {
        Expr::rational(n, d).unwrap()
    }

    #[test]
    fn signs_of_trigonometric_constants() {
        // sin(3/10) = 0.29552…, cos(2) = −0.41614…, sin(π) = 1.2e-16 in doubles but 0 exactly.
        assert_eq!(constant_sign(r(3, 10).sin()), Some(true));
        assert_eq!(constant_sign(Expr::int(2).cos()), Some(false));
        assert_eq!(constant_sign(Expr::pi().sin()), None);
        // sin²(x) + cos²(x) − 1 is exactly 0: never decided, whatever the rounding.
        let x = r(7, 3);
        let zero = x.sin().powi(2) + x.cos().powi(2) - Expr::one();
        assert_eq!(constant_sign(zero), None);
        // A difference far below the double's precision of its terms: undecided.
        let tiny = (r(1, 1) + r(1, 10_i64.pow(17))).sqrt() - Expr::one();
        assert_eq!(constant_sign(tiny), None);
        // 1/3 − sin(1/3): positive (sin x < x), by 6.2e-3.
        assert_eq!(constant_sign(r(1, 3) - r(1, 3).sin()), Some(true));
        // e^(−1) − ln(2)... negative: 0.3679 − 0.6931.
        assert_eq!(
            constant_sign((-Expr::one()).exp() - Expr::int(2).ln()),
            Some(false)
        );
    }

    #[test]
    fn a_parameter_is_not_a_constant() {
        let m = Expr::param("m_constant_sign", 1.0).unwrap();
        assert_eq!(constant_sign(m * r(3, 10).sin()), None);
    }
}
