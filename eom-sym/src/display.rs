//! Plain-text display of expressions (parsable by [`parse`](crate::parse)).

use crate::expr::{Expr, ExprView};
use crate::rational::Rational;
use std::fmt;

/// Binding strength of the outermost operator, for parenthesisation.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum = 1,
    Product = 2,
    Power = 3,
    Atom = 4,
}

fn prec(e: Expr) -> Prec {
    match e.view() {
        ExprView::Rational(r) => {
            if r.is_negative() {
                Prec::Sum
            } else if r.is_integer() {
                Prec::Atom
            } else {
                Prec::Product
            }
        }
        ExprView::Float(f) => {
            if f < 0.0 {
                Prec::Sum
            } else {
                Prec::Atom
            }
        }
        ExprView::Sum { .. } => Prec::Sum,
        ExprView::Product { coef, factors } => {
            if factors.len() == 1 && coef.is_one() {
                let e = &factors[0].1;
                if e.is_negative() || !e.is_integer() && *e != half() {
                    Prec::Product
                } else if *e == half() {
                    Prec::Atom
                } else {
                    Prec::Power
                }
            } else if coef.as_f64().is_some_and(|c| c < 0.0) {
                Prec::Sum
            } else {
                Prec::Product
            }
        }
        ExprView::Pow(..) => Prec::Power,
        _ => Prec::Atom,
    }
}

fn half() -> Rational {
    Rational::new(1, 2).expect("1/2")
}

fn wrap(f: &mut fmt::Formatter<'_>, e: Expr, min: Prec) -> fmt::Result {
    if prec(e) < min { write!(f, "({e})") } else { write!(f, "{e}") }
}

fn float_text(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('e') || s.contains('.') { s } else { format!("{s}.0") }
}

/// Write `Π base^exp` for positive exponents (numerator) — returns whether anything was written.
fn write_factors(
    f: &mut fmt::Formatter<'_>,
    factors: &[(Expr, Rational)],
    first: bool,
) -> Result<bool, fmt::Error> {
    let mut wrote = !first;
    for (b, e) in factors {
        if wrote {
            write!(f, "*")?;
        }
        write_power(f, *b, e)?;
        wrote = true;
    }
    Ok(wrote)
}

fn write_power(f: &mut fmt::Formatter<'_>, b: Expr, e: &Rational) -> fmt::Result {
    if e.is_one() {
        return wrap(f, b, Prec::Product.max(Prec::Power));
    }
    if *e == half() {
        return write!(f, "sqrt({b})");
    }
    wrap(f, b, Prec::Atom)?;
    if e.is_integer() && !e.is_negative() {
        write!(f, "^{e}")
    } else {
        write!(f, "^({e})")
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.view() {
            ExprView::Rational(r) => write!(f, "{r}"),
            ExprView::Float(x) => write!(f, "{}", float_text(x)),
            ExprView::Constant(c) => write!(f, "{}", c.name()),
            ExprView::Param(_, info) => write!(f, "{}", info.name),
            ExprView::Sum { constant, terms } => {
                let mut first = true;
                for (t, c) in &terms {
                    let term = *t * *c;
                    let neg = c.as_f64().is_some_and(|v| v < 0.0);
                    if first {
                        if neg {
                            write!(f, "-")?;
                            wrap(f, -term, Prec::Product)?;
                        } else {
                            wrap(f, term, Prec::Sum)?;
                        }
                    } else if neg {
                        write!(f, " - ")?;
                        wrap(f, -term, Prec::Product)?;
                    } else {
                        write!(f, " + ")?;
                        wrap(f, term, Prec::Product)?;
                    }
                    first = false;
                }
                if !constant.is_zero() {
                    let v = constant.as_f64().unwrap_or(0.0);
                    if v < 0.0 {
                        write!(f, " - {}", -constant)?;
                    } else {
                        write!(f, " + {constant}")?;
                    }
                }
                Ok(())
            }
            ExprView::Product { coef, factors } => {
                let cval = coef.as_f64().unwrap_or(1.0);
                let (num, den): (Vec<_>, Vec<_>) =
                    factors.iter().cloned().partition(|(_, e)| !e.is_negative());
                let den: Vec<(Expr, Rational)> =
                    den.into_iter().map(|(b, e)| (b, e.neg())).collect();
                let mut cnum = coef;
                let mut cden = Expr::one();
                if let Some(r) = coef.as_rational() {
                    if !r.is_integer() {
                        let (n, d) = r.to_big_parts();
                        cnum = Expr::from_rational(
                            Rational::from_decimal(&n.to_string()).unwrap_or(Rational::ONE),
                        );
                        cden = Expr::from_rational(
                            Rational::from_decimal(&d.to_string()).unwrap_or(Rational::ONE),
                        );
                    }
                }
                if cval < 0.0 {
                    write!(f, "-")?;
                    cnum = -cnum;
                }
                let mut wrote = false;
                if !cnum.is_one() || num.is_empty() {
                    write!(f, "{cnum}")?;
                    wrote = true;
                }
                write_factors(f, &num, !wrote)?;
                let nden = den.len() + usize::from(!cden.is_one());
                if nden > 0 {
                    write!(f, "/")?;
                    if nden > 1 {
                        write!(f, "(")?;
                    }
                    let mut w = false;
                    if !cden.is_one() {
                        write!(f, "{cden}")?;
                        w = true;
                    }
                    write_factors(f, &den, !w)?;
                    if nden > 1 {
                        write!(f, ")")?;
                    }
                }
                Ok(())
            }
            ExprView::Pow(b, e) => {
                wrap(f, b, Prec::Atom)?;
                write!(f, "^")?;
                wrap(f, e, Prec::Atom)
            }
            ExprView::Func(func, a) => write!(f, "{}({a})", func.name()),
            ExprView::Atan2(y, x) => write!(f, "atan2({y}, {x})"),
            ExprView::Invalid(e) => write!(f, "<invalid: {e}>"),
        }
    }
}
