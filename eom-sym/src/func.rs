//! The elementary functions, with everything eom knows about each in one place: its name (text,
//! parser, LaTeX, the simplifier's e-graph), its value in any [`Elementary`] scalar (`f64`,
//! double-double, expressions), its derivative, what it keeps of its argument's sign and
//! parity, and its spelling in generated Rust.
//!
//! [`Func`] are the functions of one argument that expression nodes apply; [`Call`] adds the
//! operations that straight-line code calls like functions although they are not nodes of
//! their own (square roots are powers ½ of a product, `pow` and `atan2` have two arguments).

use crate::expr::Expr;
use crate::pool::Sign;
use crate::rational::Rational;
use crate::scalar::Elementary;

/// Elementary functions of one argument.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum Func {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Exponential.
    Exp,
    /// Natural logarithm.
    Ln,
    /// Absolute value.
    Abs,
}

/// What a function does with the sign of its argument: `f(−x) = −f(x)` (odd) or
/// `f(−x) = f(x)` (even).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Parity {
    /// `f(−x) = −f(x)`.
    Odd,
    /// `f(−x) = f(x)`.
    Even,
    /// Neither.
    None,
}

impl Func {
    /// Every function, in declaration order.
    pub const ALL: [Func; 6] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Exp,
        Func::Ln,
        Func::Abs,
    ];

    /// Whether `f(k·π)` is infinite for the exact rational `k`: `tan` at the odd multiples
    /// of π/2. Such an argument is refused like `1/0` and `ln(0)`, rather than evaluated to
    /// the 1.6e16 that `tan` gives at the rounded `f64` value of π/2.
    pub fn has_pole_at_pi_times(self, k: &Rational) -> bool {
        self == Func::Tan && k.as_small().is_some_and(|(_, d)| d == 2)
    }

    /// The name used in text, by the parser and in the simplifier's e-graph.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
        }
    }

    /// The function of this name (`log` is the natural logarithm too).
    pub fn from_name(name: &str) -> Option<Func> {
        match name {
            "log" => Some(Func::Ln),
            _ => Func::ALL.into_iter().find(|f| f.name() == name),
        }
    }

    /// The LaTeX command (`abs` is printed with bars instead, by [`display`](crate::display)).
    pub fn latex(self) -> &'static str {
        match self {
            Func::Sin => "\\sin",
            Func::Cos => "\\cos",
            Func::Tan => "\\tan",
            Func::Exp => "\\exp",
            Func::Ln => "\\ln",
            Func::Abs => "\\operatorname{abs}",
        }
    }

    /// The value in any [`Elementary`] scalar: `f64` (every `f64` evaluation path goes
    /// through here, so they agree bit for bit), double-double, or an expression.
    pub fn eval<S: Elementary>(self, x: S) -> S {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
        }
    }

    /// The value in `f64`.
    pub fn eval_f64(self, x: f64) -> f64 {
        self.eval(x)
    }

    /// [`Func::eval_f64`] as a function pointer, for loops that apply one function many times
    /// (the interpreter of the [`Tape`](crate::Tape)).
    pub fn f64_fn(self) -> fn(f64) -> f64 {
        match self {
            Func::Sin => |x| Func::Sin.eval(x),
            Func::Cos => |x| Func::Cos.eval(x),
            Func::Tan => |x| Func::Tan.eval(x),
            Func::Exp => |x| Func::Exp.eval(x),
            Func::Ln => |x| Func::Ln.eval(x),
            Func::Abs => |x| Func::Abs.eval(x),
        }
    }

    /// `f′(x)`, given `x` and `fx = f(x)` (which some derivatives reuse).
    pub fn derivative(self, x: Expr, fx: Expr) -> Expr {
        match self {
            Func::Sin => x.cos(),
            Func::Cos => -x.sin(),
            Func::Tan => Expr::one() + fx.powi(2),
            Func::Exp => fx,
            Func::Ln => x.recip(),
            Func::Abs => x / fx,
        }
    }

    /// Odd, even or neither.
    pub fn parity(self) -> Parity {
        match self {
            Func::Sin | Func::Tan => Parity::Odd,
            Func::Cos | Func::Abs => Parity::Even,
            Func::Exp | Func::Ln => Parity::None,
        }
    }

    /// What is known of the sign of `f(x)` from that of `x`.
    pub fn sign(self, arg: Sign) -> Sign {
        match self {
            Func::Exp => Sign::POSITIVE,
            Func::Abs if arg.is_nonzero() => Sign::POSITIVE,
            Func::Abs => Sign::NONNEG,
            _ => Sign::ANY,
        }
    }
}

/// An operation that straight-line code calls: an elementary function, a square root, a
/// general power or `atan2`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum Call {
    /// An elementary function of one argument.
    Func(Func),
    /// `√x`.
    Sqrt,
    /// `x^y`.
    Pow,
    /// `atan2(y, x)`.
    Atan2,
}

impl Call {
    /// Number of arguments.
    pub fn arity(self) -> usize {
        match self {
            Call::Func(_) | Call::Sqrt => 1,
            Call::Pow | Call::Atan2 => 2,
        }
    }

    /// The value in `f64` (`y` is ignored by the functions of one argument).
    pub fn eval_f64(self, x: f64, y: f64) -> f64 {
        match self {
            Call::Func(f) => f.eval_f64(x),
            Call::Sqrt => x.sqrt(),
            Call::Pow => x.powf(y),
            Call::Atan2 => x.atan2(y),
        }
    }

    /// Is the result NaN or infinite whenever the first argument is, whatever the others
    /// (as IEEE 754 defines the functions)? True for `sin`, `cos`, `tan`, `ln`, `abs` and
    /// `√`; not for `exp` (`exp(−∞) = 0`), general powers and `atan2`.
    pub fn keeps_non_finite(self) -> bool {
        match self {
            Call::Func(Func::Exp) | Call::Pow | Call::Atan2 => false,
            Call::Func(_) | Call::Sqrt => true,
        }
    }

    /// The name of the function in the `libm` crate (`f64`; the `f32` one appends `f`).
    pub fn libm_name(self) -> &'static str {
        match self {
            Call::Func(Func::Sin) => "sin",
            Call::Func(Func::Cos) => "cos",
            Call::Func(Func::Tan) => "tan",
            Call::Func(Func::Exp) => "exp",
            Call::Func(Func::Ln) => "log",
            Call::Func(Func::Abs) => "fabs",
            Call::Sqrt => "sqrt",
            Call::Pow => "pow",
            Call::Atan2 => "atan2",
        }
    }

    /// The name of the method of `f64` and `f32` in the standard library.
    pub fn std_method(self) -> &'static str {
        match self {
            Call::Func(f) => f.name(),
            Call::Sqrt => "sqrt",
            Call::Pow => "powf",
            Call::Atan2 => "atan2",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tan_at_an_exact_odd_multiple_of_half_pi_is_refused_like_a_division_by_zero() {
        let scope = crate::scope::Scope::new();
        for text in [
            "tan(pi/2)",
            "tan(-pi/2)",
            "tan(3*pi/2)",
            "tan(pi/2 + 2*pi)",
            "1 + tan(π/2)",
        ] {
            let e = crate::parse::parse(text, &scope).unwrap_err();
            assert!(e.to_string().contains("is a pole of tan"), "{text}: {e}");
        }
        for (text, value) in [
            ("tan(pi)", 0.0),
            ("tan(pi/4)", 1.0),
            ("tan(1.5707963267948966)", 1.633123935319537e16),
        ] {
            let v = crate::parse::parse(text, &scope).unwrap().nominal();
            assert!(
                (v - value).abs() <= 1e-15 * value.abs().max(1.0),
                "{text}: {v}"
            );
        }
    }

    #[test]
    fn names_round_trip() {
        for f in Func::ALL {
            assert_eq!(Func::from_name(f.name()), Some(f));
        }
        assert_eq!(Func::from_name("log"), Some(Func::Ln));
        assert_eq!(Func::from_name("sqrt"), None);
    }

    #[test]
    fn parity_matches_the_values() {
        for f in [Func::Sin, Func::Cos, Func::Tan, Func::Abs] {
            let (a, b) = (f.eval_f64(0.7), f.eval_f64(-0.7));
            match f.parity() {
                Parity::Odd => assert_eq!(a, -b, "{f:?}"),
                Parity::Even => assert_eq!(a, b, "{f:?}"),
                Parity::None => unreachable!(),
            }
        }
    }
}
