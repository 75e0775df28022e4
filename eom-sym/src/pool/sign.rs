//! [`Sign`]: what is known about the sign of a node — the one sign analysis of eom-sym.

use crate::rational::Rational;

/// Sign knowledge about a node: a set of {negative, zero, positive}.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub struct Sign(u8);

impl Sign {
    const NEG: u8 = 1;
    const ZERO: u8 = 2;
    const POS: u8 = 4;
    /// Nothing known.
    pub const ANY: Sign = Sign(7);
    /// Strictly positive.
    pub const POSITIVE: Sign = Sign(4);
    /// Strictly negative.
    pub const NEGATIVE: Sign = Sign(1);
    /// Exactly zero.
    pub const ZERO_ONLY: Sign = Sign(2);
    /// Non-negative.
    pub const NONNEG: Sign = Sign(6);
    /// Nonzero.
    pub const NONZERO: Sign = Sign(5);

    pub(crate) fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::POSITIVE
        } else if x < 0.0 {
            Sign::NEGATIVE
        } else {
            Sign::ZERO_ONLY
        }
    }
    /// Provably nonzero.
    pub fn is_nonzero(self) -> bool {
        self.0 & Self::ZERO == 0
    }
    /// Provably ≥ 0.
    pub fn is_nonneg(self) -> bool {
        self.0 & Self::NEG == 0
    }
    /// Provably ≤ 0.
    pub fn is_nonpos(self) -> bool {
        self.0 & Self::POS == 0
    }
    /// Provably > 0.
    pub fn is_positive(self) -> bool {
        self.0 == Self::POS
    }
    pub(crate) fn neg(self) -> Sign {
        let mut s = self.0 & Self::ZERO;
        if self.0 & Self::NEG != 0 {
            s |= Self::POS;
        }
        if self.0 & Self::POS != 0 {
            s |= Self::NEG;
        }
        Sign(s)
    }
    pub(crate) fn mul(self, o: Sign) -> Sign {
        let mut s = 0;
        for a in [Self::NEG, Self::ZERO, Self::POS] {
            if self.0 & a == 0 {
                continue;
            }
            for b in [Self::NEG, Self::ZERO, Self::POS] {
                if o.0 & b == 0 {
                    continue;
                }
                s |= match (a, b) {
                    (Self::ZERO, _) | (_, Self::ZERO) => Self::ZERO,
                    (x, y) if x == y => Self::POS,
                    _ => Self::NEG,
                };
            }
        }
        Sign(s)
    }
    pub(crate) fn add(self, o: Sign) -> Sign {
        // An empty set (a value defined nowhere, which only the simplifier's e-graph meets)
        // says nothing about a sum.
        if self.0 == 0 || o.0 == 0 {
            return Sign::ANY;
        }
        // Sum of sets: nonneg + nonneg is nonneg, positive if either is positive.
        if self.is_nonneg() && o.is_nonneg() {
            if self.is_positive() || o.is_positive() {
                Sign::POSITIVE
            } else if self == Sign::ZERO_ONLY && o == Sign::ZERO_ONLY {
                Sign::ZERO_ONLY
            } else {
                Sign::NONNEG
            }
        } else if self.is_nonpos() && o.is_nonpos() {
            self.neg().add(o.neg()).neg()
        } else {
            Sign::ANY
        }
    }
}

pub(crate) fn pow_sign(s: Sign, e: &Rational) -> Sign {
    let s = if e.is_negative() {
        // x^-k is undefined at 0; where defined it has the sign of x^k.
        Sign(s.0 & !Sign::ZERO).max_nonempty(s)
    } else {
        s
    };
    match e.as_small() {
        Some((n, 1)) if n % 2 == 0 => {
            if s.is_nonzero() {
                Sign::POSITIVE
            } else {
                Sign::NONNEG
            }
        }
        Some((_, 1)) => s,
        _ => {
            if s.is_positive() {
                Sign::POSITIVE
            } else {
                Sign::NONNEG
            }
        }
    }
}

impl Sign {
    pub(crate) fn from_rational(r: &Rational) -> Sign {
        match r.signum() {
            1 => Sign::POSITIVE,
            -1 => Sign::NEGATIVE,
            _ => Sign::ZERO_ONLY,
        }
    }
    /// Both facts at once: `None` when they contradict (a value defined nowhere).
    pub(crate) fn intersect(self, o: Sign) -> Option<Sign> {
        let c = self.0 & o.0;
        (c != 0).then_some(Sign(c))
    }
    fn max_nonempty(self, fallback: Sign) -> Sign {
        if self.0 == 0 { fallback } else { self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattice_operations() {
        let pos = Sign::POSITIVE;
        assert!(pos.add(pos).is_positive());
        assert!(pos.mul(pos.neg()).is_nonpos());
        assert!(!pow_sign(Sign::ANY, &Rational::int(2)).is_nonzero());
        assert!(pow_sign(pos.neg(), &Rational::int(-2)).is_positive());
        assert_eq!(Sign::POSITIVE.intersect(Sign::NEGATIVE), None);
        assert_eq!(Sign::NONNEG.intersect(Sign::NONZERO), Some(Sign::POSITIVE));
        // An empty set (a class defined nowhere) makes a sum unknown, not zero.
        assert_eq!(Sign(0).add(pos), Sign::ANY);
    }
}
