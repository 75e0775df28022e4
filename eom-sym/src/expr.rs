//! [`Expr`]: a handle to a node of the current thread's expression pool.

use crate::error::SymError;
use crate::pool::{
    Assumption, Constant, ExprPool, Func, Id, MINUS_ONE, Node, ONE, ParamInfo, Sign, ZERO,
    with_pool,
};
use crate::rational::Rational;
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A symbolic expression: a 4-byte handle to a unique node of the expression pool of the
/// current thread.
///
/// Expressions are built with ordinary operators and the methods below; the smart
/// constructors keep every node in canonical form (see the [`pool`](crate::pool) module for the
/// identities applied). Equal handles mean structurally equal expressions.
///
/// An `Expr` belongs to the thread that created it (it is neither `Send` nor `Sync`); the
/// compiled [`Tape`](crate::Tape) of an expression can be sent anywhere.
///
/// ```
/// use eom_sym::Expr;
/// let m = Expr::param("m", 2.0).unwrap();
/// let k = Expr::param("k", 8.0).unwrap();
/// let e = (m * k + k * m) / (Expr::int(2) * m);
/// assert_eq!(e.nominal(), 8.0);
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Expr {
    id: Id,
    _thread_bound: PhantomData<*const ()>,
}

/// The structure of one node, for code that walks expressions (display, code generation,
/// simplification).
#[derive(Clone, Debug, PartialEq)]
pub enum ExprView {
    /// An exact rational constant.
    Rational(Rational),
    /// A floating-point constant (measured data).
    Float(f64),
    /// A named constant (π, e).
    Constant(Constant),
    /// A parameter: its index in the pool and its metadata.
    Param(u32, ParamInfo),
    /// `constant + Σ coef·term`; coefficients are numeric expressions.
    Sum {
        /// Numeric constant term (possibly zero).
        constant: Expr,
        /// `(term, coefficient)` pairs.
        terms: Vec<(Expr, Expr)>,
    },
    /// `coef · Π base^exponent` with rational exponents.
    Product {
        /// Numeric coefficient.
        coef: Expr,
        /// `(base, exponent)` pairs.
        factors: Vec<(Expr, Rational)>,
    },
    /// `base ^ exponent` with a non-rational exponent.
    Pow(Expr, Expr),
    /// A function of one argument.
    Func(Func, Expr),
    /// `atan2(y, x)`.
    Atan2(Expr, Expr),
    /// An operation without a value, with the reason.
    Invalid(SymError),
}

impl Expr {
    pub(crate) fn from_id(id: Id) -> Expr {
        Expr {
            id,
            _thread_bound: PhantomData,
        }
    }
    /// The node id in the pool (ids are a topological order: children before parents).
    pub fn id(self) -> u32 {
        self.id
    }

    // ------------------------------------------------------------ constructors

    /// The constant 0.
    pub fn zero() -> Expr {
        Expr::from_id(ZERO)
    }
    /// The constant 1.
    pub fn one() -> Expr {
        Expr::from_id(ONE)
    }
    /// An integer constant.
    pub fn int(n: i64) -> Expr {
        Expr::from_rational(Rational::int(n))
    }
    /// The exact rational `num/den`.
    pub fn rational(num: i64, den: i64) -> Result<Expr, SymError> {
        Rational::new(num, den)
            .map(Expr::from_rational)
            .ok_or_else(|| SymError::DivisionByZero {
                context: format!("the rational {num}/{den}"),
            })
    }
    /// An exact rational constant.
    pub fn from_rational(r: Rational) -> Expr {
        Expr::from_id(with_pool(|p| p.rational(r)))
    }
    /// A floating-point constant (measured data). Integers and short dyadic fractions such as
    /// 0.5 or 0.375 become exact rationals; other values stay floats. Non-finite values are an
    /// error.
    pub fn float(x: f64) -> Result<Expr, SymError> {
        if !x.is_finite() {
            return Err(SymError::NonFinite {
                what: format!("the constant {x}"),
            });
        }
        Ok(Expr::from_id(with_pool(|p| match crate::pool::dyadic(x) {
            Some(r) => p.rational(r),
            None => p.float(x),
        })))
    }
    /// π.
    pub fn pi() -> Expr {
        Expr::from_id(with_pool(|p| p.constant(Constant::Pi)))
    }
    /// Euler's number.
    pub fn e() -> Expr {
        Expr::from_id(with_pool(|p| p.constant(Constant::E)))
    }

    /// Declare a new parameter with a name and a nominal value (no unit, no assumption).
    /// Each call creates a distinct parameter, even if the name was used before.
    pub fn param(name: &str, nominal: f64) -> Result<Expr, SymError> {
        Expr::new_param(ParamInfo {
            name: name.to_string(),
            nominal,
            unit: None,
            description: None,
            assume: Assumption::Real,
        })
    }

    /// Declare a new parameter from full metadata.
    pub fn new_param(info: ParamInfo) -> Result<Expr, SymError> {
        if !is_identifier(&info.name) {
            return Err(SymError::BadParameter {
                name: info.name,
                problem: "a name must start with a letter or `_` and contain only letters, \
                          digits and `_`"
                    .into(),
            });
        }
        if matches!(
            info.name.as_str(),
            "pi" | "e" | "sin" | "cos" | "tan" | "exp" | "ln" | "abs" | "sqrt" | "atan2"
        ) {
            return Err(SymError::BadParameter {
                name: info.name,
                problem: "the name is reserved for a constant or function".into(),
            });
        }
        if !info.nominal.is_finite() {
            return Err(SymError::BadParameter {
                problem: format!("nominal value {} is not finite", info.nominal),
                name: info.name,
            });
        }
        let bad = match info.assume {
            Assumption::Positive => info.nominal <= 0.0,
            Assumption::Nonzero => info.nominal == 0.0,
            Assumption::Nonnegative => info.nominal < 0.0,
            Assumption::Real => false,
        };
        if bad {
            return Err(SymError::BadParameter {
                problem: format!(
                    "nominal value {} contradicts the assumption {:?}",
                    info.nominal, info.assume
                ),
                name: info.name,
            });
        }
        Ok(Expr::from_id(with_pool(|p| p.new_param(info))))
    }

    /// `Σ items` as one n-ary sum (faster than repeated `+`).
    pub fn sum<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let ids: Vec<Id> = items.into_iter().map(|e| e.id).collect();
        Expr::from_id(with_pool(|p| p.add_n(&ids)))
    }
    /// `Π items` as one n-ary product.
    pub fn product<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let ids: Vec<Id> = items.into_iter().map(|e| e.id).collect();
        Expr::from_id(with_pool(|p| p.mul_n(&ids)))
    }

    // ------------------------------------------------------------ operations

    /// `self ^ e`.
    pub fn pow(self, e: Expr) -> Expr {
        Expr::from_id(with_pool(|p| p.pow(self.id, e.id)))
    }
    /// `self ^ n` for an integer `n`.
    pub fn powi(self, n: i64) -> Expr {
        Expr::from_id(with_pool(|p| p.pow_rational(self.id, Rational::int(n))))
    }
    /// `self ^ r` for a rational `r`.
    pub fn pow_rational(self, r: Rational) -> Expr {
        Expr::from_id(with_pool(|p| p.pow_rational(self.id, r)))
    }
    /// `1 / self`.
    pub fn recip(self) -> Expr {
        self.powi(-1)
    }
    /// Square root (`self ^ (1/2)`).
    pub fn sqrt(self) -> Expr {
        self.pow_rational(Rational::new(1, 2).expect("1/2"))
    }
    /// Apply a function.
    pub fn apply(self, f: Func) -> Expr {
        Expr::from_id(with_pool(|p| p.func(f, self.id)))
    }
    /// Sine.
    pub fn sin(self) -> Expr {
        self.apply(Func::Sin)
    }
    /// Cosine.
    pub fn cos(self) -> Expr {
        self.apply(Func::Cos)
    }
    /// Tangent.
    pub fn tan(self) -> Expr {
        self.apply(Func::Tan)
    }
    /// Exponential.
    pub fn exp(self) -> Expr {
        self.apply(Func::Exp)
    }
    /// Natural logarithm.
    pub fn ln(self) -> Expr {
        self.apply(Func::Ln)
    }
    /// Absolute value.
    pub fn abs(self) -> Expr {
        self.apply(Func::Abs)
    }
    /// `atan2(self, x)`.
    pub fn atan2(self, x: Expr) -> Expr {
        Expr::from_id(with_pool(|p| p.atan2(self.id, x.id)))
    }

    /// `self / o`, with division by a structural zero reported as an error.
    pub fn try_div(self, o: Expr) -> Result<Expr, SymError> {
        (self / o).check()
    }

    /// `Ok(self)` unless this is an invalid node (an operation without a value), in which case
    /// the reason. Invalid nodes absorb every operation, so checking the final result of a
    /// computation is enough.
    pub fn check(self) -> Result<Expr, SymError> {
        with_pool(|p| match p.invalid_of(self.id) {
            Some(e) => Err(p.error(e).clone()),
            None => Ok(self),
        })
    }

    // ------------------------------------------------------------ inspection

    /// The value at the nominal point (computed once, when the node was created).
    pub fn nominal(self) -> f64 {
        with_pool(|p| p.nominal(self.id))
    }
    /// What is known about the sign.
    pub fn sign(self) -> Sign {
        with_pool(|p| p.sign(self.id))
    }
    /// Is this the constant 0 (a structural zero)?
    pub fn is_zero(self) -> bool {
        self.id == ZERO
    }
    /// Is this the constant 1?
    pub fn is_one(self) -> bool {
        self.id == ONE
    }
    /// Is this the constant −1?
    pub fn is_minus_one(self) -> bool {
        self.id == MINUS_ONE
    }
    /// Is this a numeric constant (rational or float)?
    pub fn is_number(self) -> bool {
        with_pool(|p| p.is_number(self.id))
    }
    /// The exact value, if this is a rational constant.
    pub fn as_rational(self) -> Option<Rational> {
        with_pool(|p| p.rational_of(self.id).cloned())
    }
    /// The value, if this is a numeric constant (rational or float).
    pub fn as_f64(self) -> Option<f64> {
        with_pool(|p| p.number(self.id).map(|n| n.to_f64()))
    }
    /// The parameter metadata, if this is a parameter.
    pub fn param_info(self) -> Option<ParamInfo> {
        with_pool(|p| match p.node(self.id) {
            Node::Param(i) => Some(p.param(*i).clone()),
            _ => None,
        })
    }
    /// The parameter index, if this is a parameter.
    pub fn param_index(self) -> Option<u32> {
        with_pool(|p| match p.node(self.id) {
            Node::Param(i) => Some(*i),
            _ => None,
        })
    }
    /// Is this an invalid node?
    pub fn is_invalid(self) -> bool {
        with_pool(|p| p.invalid_of(self.id).is_some())
    }

    /// The structure of this node.
    pub fn view(self) -> ExprView {
        with_pool(|p| {
            let e = Expr::from_id;
            match p.node(self.id) {
                Node::Num(r) => ExprView::Rational(r.clone()),
                Node::Float(f) => ExprView::Float(*f),
                Node::Const(c) => ExprView::Constant(*c),
                Node::Param(i) => ExprView::Param(*i, p.param(*i).clone()),
                Node::Add(..) => {
                    let (c0, pairs) = p.add_parts(self.id).expect("sum");
                    ExprView::Sum {
                        constant: e(c0),
                        terms: pairs.chunks_exact(2).map(|t| (e(t[0]), e(t[1]))).collect(),
                    }
                }
                Node::Mul(..) => {
                    let (c, pairs) = p.mul_parts(self.id).expect("product");
                    ExprView::Product {
                        coef: e(c),
                        factors: pairs
                            .chunks_exact(2)
                            .map(|t| (e(t[0]), p.rational_of(t[1]).expect("exp").clone()))
                            .collect(),
                    }
                }
                Node::Pow(a, b) => ExprView::Pow(e(*a), e(*b)),
                Node::Func(f, a) => ExprView::Func(*f, e(*a)),
                Node::Atan2(a, b) => ExprView::Atan2(e(*a), e(*b)),
                Node::Invalid(i) => ExprView::Invalid(p.error(*i).clone()),
            }
        })
    }

    /// The direct children (operands, coefficients and exponents included).
    pub fn children(self) -> Vec<Expr> {
        with_pool(|p| {
            let mut v = Vec::new();
            p.for_each_child(self.id, |c| v.push(Expr::from_id(c)));
            v
        })
    }

    /// All parameters this expression depends on, by pool parameter index, ascending.
    pub fn params(self) -> Vec<u32> {
        Expr::params_of(&[self])
    }

    /// All parameters any of `roots` depends on, by pool parameter index, ascending.
    pub fn params_of(roots: &[Expr]) -> Vec<u32> {
        let ids = reachable(roots);
        with_pool(|p| {
            let mut v: Vec<u32> = ids
                .iter()
                .filter_map(|&i| match p.node(i) {
                    Node::Param(k) => Some(*k),
                    _ => None,
                })
                .collect();
            v.sort_unstable();
            v
        })
    }

    /// The parameter with pool index `index` as an expression.
    pub fn from_param_index(index: u32) -> Option<Expr> {
        with_pool(|p| {
            if (index as usize) < p.params_len() {
                Some(Expr::from_id(p.param_node(index)))
            } else {
                None
            }
        })
    }

    /// Number of unique nodes reachable from `roots` (the DAG size).
    pub fn dag_size(roots: &[Expr]) -> usize {
        reachable(roots).len()
    }

    /// Counts of the arithmetic operations needed to evaluate `roots` with every unique node
    /// computed once (the cost of straight-line generated code).
    pub fn op_count(roots: &[Expr]) -> OpCount {
        let ids = reachable(roots);
        with_pool(|p| {
            let mut c = OpCount::default();
            for &i in &ids {
                match p.node(i) {
                    Node::Add(..) => {
                        let (c0, pairs) = p.add_parts(i).expect("sum");
                        let n = pairs.len() / 2 + usize::from(c0 != ZERO);
                        c.add += n.saturating_sub(1);
                        for t in pairs.chunks_exact(2) {
                            if t[1] != ONE && t[1] != MINUS_ONE {
                                c.mul += 1;
                            }
                        }
                    }
                    Node::Mul(..) => {
                        let (coef, pairs) = p.mul_parts(i).expect("product");
                        let mut n = pairs.len() / 2 + usize::from(coef != ONE && coef != MINUS_ONE);
                        for t in pairs.chunks_exact(2) {
                            let e = p.rational_of(t[1]).expect("exp");
                            match e.as_small() {
                                Some((k, 1)) if k > 0 => {
                                    c.mul += pow_chain(k as u64) as usize;
                                }
                                Some((-1, 1)) => {
                                    c.div += 1;
                                    n -= 1;
                                }
                                Some((k, 1)) => {
                                    c.div += 1;
                                    n -= 1;
                                    c.mul += pow_chain((-k) as u64) as usize;
                                }
                                Some((1, 2)) => c.func += 1,
                                _ => c.pow += 1,
                            }
                        }
                        c.mul += n.saturating_sub(1);
                    }
                    Node::Pow(..) => c.pow += 1,
                    Node::Func(..) | Node::Atan2(..) => c.func += 1,
                    _ => {}
                }
            }
            c
        })
    }
}

/// Operation counts of straight-line code (see [`Expr::op_count`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Elementary functions and square roots.
    pub func: usize,
    /// General powers.
    pub pow: usize,
}

impl OpCount {
    /// Total number of operations.
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.func + self.pow
    }
}

/// Multiplications of a square-and-multiply chain for `x^k` (k ≥ 1).
fn pow_chain(k: u64) -> u32 {
    if k <= 1 {
        return 0;
    }
    (63 - k.leading_zeros()) + k.count_ones() - 1
}

/// Ids of all nodes reachable from `roots`, ascending (a topological order).
pub(crate) fn reachable(roots: &[Expr]) -> Vec<Id> {
    with_pool(|p| reachable_in(p, roots.iter().map(|e| e.id)))
}

pub(crate) fn reachable_in(p: &ExprPool, roots: impl Iterator<Item = Id>) -> Vec<Id> {
    let mut seen = hashbrown::HashSet::new();
    let mut stack: Vec<Id> = roots.collect();
    let mut out = Vec::new();
    while let Some(i) = stack.pop() {
        if !seen.insert(i) {
            continue;
        }
        out.push(i);
        p.for_each_child(i, |c| {
            if !seen.contains(&c) {
                stack.push(c)
            }
        });
    }
    out.sort_unstable();
    out
}

pub(crate) fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) if c.is_alphabetic() || c == '_' => {}
        _ => return false,
    }
    chars.all(|c| c.is_alphanumeric() || c == '_')
}

impl std::fmt::Debug for Expr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{self}")
    }
}

// ---------------------------------------------------------------- operators

impl Add for Expr {
    type Output = Expr;
    fn add(self, o: Expr) -> Expr {
        Expr::from_id(with_pool(|p| p.add_n(&[self.id, o.id])))
    }
}
impl Sub for Expr {
    type Output = Expr;
    fn sub(self, o: Expr) -> Expr {
        Expr::from_id(with_pool(|p| {
            let n = p.mul_n(&[MINUS_ONE, o.id]);
            p.add_n(&[self.id, n])
        }))
    }
}
impl Mul for Expr {
    type Output = Expr;
    fn mul(self, o: Expr) -> Expr {
        Expr::from_id(with_pool(|p| p.mul_n(&[self.id, o.id])))
    }
}
impl Div for Expr {
    type Output = Expr;
    fn div(self, o: Expr) -> Expr {
        Expr::from_id(with_pool(|p| {
            let r = p.pow_rational(o.id, Rational::MINUS_ONE);
            p.mul_n(&[self.id, r])
        }))
    }
}
impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::from_id(with_pool(|p| p.mul_n(&[MINUS_ONE, self.id])))
    }
}
impl AddAssign for Expr {
    fn add_assign(&mut self, o: Expr) {
        *self = *self + o;
    }
}
impl SubAssign for Expr {
    fn sub_assign(&mut self, o: Expr) {
        *self = *self - o;
    }
}
impl MulAssign for Expr {
    fn mul_assign(&mut self, o: Expr) {
        *self = *self * o;
    }
}
impl DivAssign for Expr {
    fn div_assign(&mut self, o: Expr) {
        *self = *self / o;
    }
}

macro_rules! scalar_ops {
    ($t:ty, $conv:expr) => {
        impl Add<$t> for Expr {
            type Output = Expr;
            fn add(self, o: $t) -> Expr {
                self + $conv(o)
            }
        }
        impl Sub<$t> for Expr {
            type Output = Expr;
            fn sub(self, o: $t) -> Expr {
                self - $conv(o)
            }
        }
        impl Mul<$t> for Expr {
            type Output = Expr;
            fn mul(self, o: $t) -> Expr {
                self * $conv(o)
            }
        }
        impl Div<$t> for Expr {
            type Output = Expr;
            fn div(self, o: $t) -> Expr {
                self / $conv(o)
            }
        }
        impl Add<Expr> for $t {
            type Output = Expr;
            fn add(self, o: Expr) -> Expr {
                $conv(self) + o
            }
        }
        impl Sub<Expr> for $t {
            type Output = Expr;
            fn sub(self, o: Expr) -> Expr {
                $conv(self) - o
            }
        }
        impl Mul<Expr> for $t {
            type Output = Expr;
            fn mul(self, o: Expr) -> Expr {
                $conv(self) * o
            }
        }
        impl Div<Expr> for $t {
            type Output = Expr;
            fn div(self, o: Expr) -> Expr {
                $conv(self) / o
            }
        }
    };
}
scalar_ops!(i64, Expr::int);
scalar_ops!(i32, |x: i32| Expr::int(x as i64));

impl From<i32> for Expr {
    fn from(n: i32) -> Expr {
        Expr::int(n as i64)
    }
}
/// Floats convert like [`Expr::float`]; a non-finite value becomes an invalid node, which model
/// validation reports with the item and field it came from.
impl From<f64> for Expr {
    fn from(x: f64) -> Expr {
        <Expr as crate::scalar::Scalar>::from_f64(x)
    }
}
impl From<i64> for Expr {
    fn from(n: i64) -> Expr {
        Expr::int(n)
    }
}
impl From<Rational> for Expr {
    fn from(r: Rational) -> Expr {
        Expr::from_rational(r)
    }
}

impl std::iter::Sum for Expr {
    fn sum<I: Iterator<Item = Expr>>(iter: I) -> Expr {
        Expr::sum(iter)
    }
}
impl std::iter::Product for Expr {
    fn product<I: Iterator<Item = Expr>>(iter: I) -> Expr {
        Expr::product(iter)
    }
}
