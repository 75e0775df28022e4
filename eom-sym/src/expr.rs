//! [`Expr`]: a handle to a node of an expression pool.

use crate::context::{unify, unify2, with_pool, with_serial};
use crate::error::SymError;
pub use crate::pool::OpCount;
use crate::pool::{
    Assumption, Constant, Func, Id, MINUS_ONE, Node, ONE, ParamInfo, PoolData, Shape, Sign, ZERO,
};
use crate::rational::Rational;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A symbolic expression: an 8-byte handle to a unique node of an expression pool (the node's
/// index and the pool's serial number).
///
/// Expressions are built with ordinary operators and the methods below; the smart
/// constructors keep every node in canonical form (see the [`pool`](crate::pool) module for the
/// identities applied). Within one pool, equal handles mean structurally equal expressions.
///
/// An `Expr` is plain data (`Send + Sync`): operations find its pool wherever they run (see
/// [`context`](crate::context), which also says how long a pool lives).
///
/// ```
/// use eom_sym::Expr;
/// let m = Expr::param("m", 2.0).unwrap();
/// let k = Expr::param("k", 8.0).unwrap();
/// let e = (m * k + k * m) / (Expr::int(2) * m);
/// assert_eq!(e.nominal(), 8.0);
/// ```
#[derive(Clone, Copy)]
pub struct Expr {
    id: Id,
    pool: u32,
}

impl Expr {
    /// The pool part of the identity: the constants 0, 1 and −1 have the same id in every pool
    /// and are equal whatever pool they were built in.
    fn identity(self) -> (Id, u32) {
        if self.id <= MINUS_ONE {
            (self.id, 0)
        } else {
            (self.id, self.pool)
        }
    }
}
impl PartialEq for Expr {
    fn eq(&self, o: &Expr) -> bool {
        self.identity() == o.identity()
    }
}
impl Eq for Expr {}
impl std::hash::Hash for Expr {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        self.identity().hash(h)
    }
}
impl PartialOrd for Expr {
    fn partial_cmp(&self, o: &Expr) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
/// Ids first: within a pool, the order of creation (children before parents).
impl Ord for Expr {
    fn cmp(&self, o: &Expr) -> std::cmp::Ordering {
        self.identity().cmp(&o.identity())
    }
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

impl ExprView {
    /// The expressions this node is built from, in a fixed order: a sum's constant, then its
    /// terms and their coefficients; a product's coefficient, then its bases (exponents are
    /// rationals, not expressions); the arguments of powers and functions.
    pub fn children(&self) -> Vec<Expr> {
        match self {
            ExprView::Sum { constant, terms } => std::iter::once(*constant)
                .chain(terms.iter().flat_map(|&(t, c)| [t, c]))
                .collect(),
            ExprView::Product { coef, factors } => std::iter::once(*coef)
                .chain(factors.iter().map(|f| f.0))
                .collect(),
            ExprView::Pow(a, b) | ExprView::Atan2(a, b) => vec![*a, *b],
            ExprView::Func(_, a) => vec![*a],
            ExprView::Rational(_)
            | ExprView::Float(_)
            | ExprView::Constant(_)
            | ExprView::Param(..)
            | ExprView::Invalid(_) => Vec::new(),
        }
    }

    /// The same node over the children `f` maps them to, visited in the order of
    /// [`ExprView::children`].
    pub fn map_children(self, mut f: impl FnMut(Expr) -> Expr) -> ExprView {
        match self {
            ExprView::Sum { constant, terms } => ExprView::Sum {
                constant: f(constant),
                terms: terms.into_iter().map(|(t, c)| (f(t), f(c))).collect(),
            },
            ExprView::Product { coef, factors } => ExprView::Product {
                coef: f(coef),
                factors: factors.into_iter().map(|(b, r)| (f(b), r)).collect(),
            },
            ExprView::Pow(a, b) => ExprView::Pow(f(a), f(b)),
            ExprView::Func(g, a) => ExprView::Func(g, f(a)),
            ExprView::Atan2(y, x) => ExprView::Atan2(f(y), f(x)),
            leaf => leaf,
        }
    }
}

impl Expr {
    pub(crate) fn new(id: Id, pool: u32) -> Expr {
        Expr { id, pool }
    }
    /// The serial number of the pool this expression belongs to
    /// ([`ExprPool::find`](crate::ExprPool::find) gives the pool while it is alive).
    pub fn pool_serial(self) -> u32 {
        self.pool
    }
    /// Runs `f` on the data of this expression's pool.
    pub(crate) fn with_pool<R>(self, f: impl FnOnce(&mut PoolData) -> R) -> R {
        with_serial(self.pool, f)
    }
    /// Builds a node of this expression's pool from its id there.
    fn build(self, f: impl FnOnce(&mut PoolData, Id) -> Id) -> Expr {
        self.with_pool(|p| {
            let id = f(p, self.id);
            p.expr(id)
        })
    }
    /// Builds a node from two operands, in their common pool.
    fn build2(self, o: Expr, f: impl FnOnce(&mut PoolData, Id, Id) -> Id) -> Expr {
        let (serial, a, b) = unify2(self, o);
        with_serial(serial, |p| {
            let id = f(p, a, b);
            p.expr(id)
        })
    }
    /// Builds a node from `n` operands, in their common pool.
    fn build_n(items: &[Expr], f: impl FnOnce(&mut PoolData, &[Id]) -> Id) -> Expr {
        let (serial, ids) = unify(items);
        with_serial(serial, |p| {
            let id = f(p, &ids);
            p.expr(id)
        })
    }
    /// A numeric constant or named constant (such nodes move between pools freely).
    pub(crate) fn is_number_or_constant(self) -> bool {
        self.with_pool(|p| {
            matches!(
                p.node(self.id),
                Node::Num(_) | Node::Float(_) | Node::Const(_)
            )
        })
    }
    /// Node `id` of the current pool (for code that entered the pool it works in).
    pub(crate) fn in_current(id: Id) -> Expr {
        with_pool(|p| p.expr(id))
    }
    /// A named constant, in the current pool.
    pub(crate) fn constant(c: Constant) -> Expr {
        with_pool(|p| {
            let id = p.constant(c);
            p.expr(id)
        })
    }
    /// An invalid node carrying `e`, in the current pool.
    pub(crate) fn invalid(e: SymError) -> Expr {
        with_pool(|p| {
            let id = p.invalid(e);
            p.expr(id)
        })
    }
    /// The node id in the pool (ids are a topological order: children before parents).
    pub fn id(self) -> u32 {
        self.id
    }

    // ------------------------------------------------------------ constructors

    /// The constant 0.
    pub fn zero() -> Expr {
        with_pool(|p| p.expr(ZERO))
    }
    /// The constant 1.
    pub fn one() -> Expr {
        with_pool(|p| p.expr(ONE))
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
        with_pool(|p| {
            let id = p.rational(r);
            p.expr(id)
        })
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
        Ok(with_pool(|p| {
            let id = match crate::pool::dyadic(x) {
                Some(r) => p.rational(r),
                None => p.float(x),
            };
            p.expr(id)
        }))
    }
    /// π.
    pub fn pi() -> Expr {
        Expr::constant(Constant::Pi)
    }
    /// Euler's number.
    pub fn e() -> Expr {
        Expr::constant(Constant::E)
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
                name: eom_text::shown(&info.name),
                problem: "a name must start with a letter or `_` and contain only letters, \
                          digits and `_`"
                    .into(),
            });
        }
        if crate::parse::is_reserved(&info.name) {
            return Err(SymError::BadParameter {
                name: info.name,
                problem: format!(
                    "the name is reserved: {} (constants and functions) cannot be parameters: \
                     choose another name",
                    crate::parse::RESERVED.join(", ")
                ),
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
        Ok(with_pool(|p| {
            let id = p.new_param(info);
            p.expr(id)
        }))
    }

    /// `Σ items` as one n-ary sum (faster than repeated `+`).
    pub fn sum<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let items: Vec<Expr> = items.into_iter().collect();
        Expr::build_n(&items, |p, ids| p.add_n(ids))
    }
    /// `Π items` as one n-ary product.
    pub fn product<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let items: Vec<Expr> = items.into_iter().collect();
        Expr::build_n(&items, |p, ids| p.mul_n(ids))
    }

    // ------------------------------------------------------------ operations

    /// `self ^ e`.
    pub fn pow(self, e: Expr) -> Expr {
        self.build2(e, |p, a, b| p.pow(a, b))
    }
    /// `self ^ n` for an integer `n`.
    pub fn powi(self, n: i64) -> Expr {
        self.build(|p, a| p.pow_rational(a, Rational::int(n)))
    }
    /// `self ^ r` for a rational `r`.
    pub fn pow_rational(self, r: Rational) -> Expr {
        self.build(|p, a| p.pow_rational(a, r))
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
        self.build(|p, a| p.func(f, a))
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
        self.build2(x, |p, a, b| p.atan2(a, b))
    }

    /// `self / o`, with division by a structural zero reported as an error.
    pub fn try_div(self, o: Expr) -> Result<Expr, SymError> {
        (self / o).check()
    }

    /// `Ok(self)` unless this is an invalid node (an operation without a value), in which case
    /// the reason. Invalid nodes absorb every operation, so checking the final result of a
    /// computation is enough.
    pub fn check(self) -> Result<Expr, SymError> {
        self.with_pool(|p| match p.invalid_of(self.id) {
            Some(e) => Err(p.error(e).clone()),
            None => Ok(self),
        })
    }

    // ------------------------------------------------------------ inspection

    /// The value at the nominal point (computed once, when the node was created).
    pub fn nominal(self) -> f64 {
        self.with_pool(|p| p.nominal(self.id))
    }
    /// What is known about the sign.
    pub fn sign(self) -> Sign {
        self.with_pool(|p| p.sign(self.id))
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
        self.with_pool(|p| p.is_number(self.id))
    }
    /// The exact value, if this is a rational constant.
    pub fn as_rational(self) -> Option<Rational> {
        self.with_pool(|p| p.rational_of(self.id).cloned())
    }
    /// The value, if this is a numeric constant (rational or float).
    pub fn as_f64(self) -> Option<f64> {
        self.with_pool(|p| p.number(self.id).map(|n| n.to_f64()))
    }
    /// The parameter metadata, if this is a parameter.
    pub fn param_info(self) -> Option<ParamInfo> {
        self.with_pool(|p| match p.node(self.id) {
            Node::Param(i) => Some(p.param(*i).clone()),
            _ => None,
        })
    }
    /// The parameter index, if this is a parameter.
    pub fn param_index(self) -> Option<u32> {
        self.with_pool(|p| match p.node(self.id) {
            Node::Param(i) => Some(*i),
            _ => None,
        })
    }
    /// Is this an invalid node?
    pub fn is_invalid(self) -> bool {
        self.with_pool(|p| p.invalid_of(self.id).is_some())
    }

    /// The structure of this node.
    pub fn view(self) -> ExprView {
        self.with_pool(|p| {
            let e = |id: Id| p.expr(id);
            let pairs = |a: &[Id]| {
                a[1..]
                    .chunks_exact(2)
                    .map(|t| (t[0], t[1]))
                    .collect::<Vec<_>>()
            };
            match p.shape(self.id) {
                Shape::Num(r) => ExprView::Rational(r.clone()),
                Shape::Float(f) => ExprView::Float(f64::from_bits(f)),
                Shape::Const(c) => ExprView::Constant(c),
                Shape::Param(i) => ExprView::Param(i, p.param(i).clone()),
                Shape::Add(a) => ExprView::Sum {
                    constant: e(a[0]),
                    terms: pairs(a).into_iter().map(|(t, c)| (e(t), e(c))).collect(),
                },
                Shape::Mul(a) => ExprView::Product {
                    coef: e(a[0]),
                    factors: pairs(a)
                        .into_iter()
                        .map(|(b, x)| (e(b), p.exponent(x)))
                        .collect(),
                },
                Shape::Pow([a, b]) => ExprView::Pow(e(a), e(b)),
                Shape::Func(f, [a]) => ExprView::Func(f, e(a)),
                Shape::Atan2([y, x]) => ExprView::Atan2(e(y), e(x)),
                Shape::Invalid(i) => ExprView::Invalid(p.error(i).clone()),
            }
        })
    }

    /// The expression of a view, built through the smart constructors (the inverse of
    /// [`Expr::view`]; with [`ExprView::map_children`] it rebuilds a node over new children).
    /// New leaves go to the current pool; a parameter is found there by its metadata, or
    /// declared anew.
    pub fn from_view(view: ExprView) -> Expr {
        match view {
            ExprView::Rational(r) => Expr::from_rational(r),
            ExprView::Float(x) => crate::scalar::Scalar::from_f64(x),
            ExprView::Constant(k) => Expr::constant(k),
            ExprView::Param(_, info) => {
                let found = with_pool(|p| p.find_param(&info).map(|id| p.expr(id)));
                found.unwrap_or_else(|| Expr::new_param(info).unwrap_or_else(Expr::invalid))
            }
            ExprView::Sum { constant, terms } => {
                Expr::sum(std::iter::once(constant).chain(terms.into_iter().map(|(t, k)| k * t)))
            }
            ExprView::Product { coef, factors } => Expr::product(
                std::iter::once(coef).chain(factors.into_iter().map(|(b, r)| b.pow_rational(r))),
            ),
            ExprView::Pow(b, x) => b.pow(x),
            ExprView::Func(f, a) => a.apply(f),
            ExprView::Atan2(y, x) => y.atan2(x),
            ExprView::Invalid(err) => Expr::invalid(err),
        }
    }

    /// The direct children (operands, coefficients and exponents included).
    pub fn children(self) -> Vec<Expr> {
        self.with_pool(|p| {
            p.shape(self.id)
                .children()
                .iter()
                .map(|&c| p.expr(c))
                .collect()
        })
    }

    /// All parameters this expression depends on, by pool parameter index, ascending.
    pub fn params(self) -> Vec<u32> {
        Expr::params_of(&[self])
    }

    /// All parameters any of `roots` depends on, by pool parameter index, ascending.
    pub fn params_of(roots: &[Expr]) -> Vec<u32> {
        let Reach { serial, ids, .. } = reachable(roots);
        with_serial(serial, |p| {
            let mut v: Vec<u32> = ids
                .iter()
                .filter_map(|&i| match p.shape(i) {
                    Shape::Param(k) => Some(k),
                    _ => None,
                })
                .collect();
            v.sort_unstable();
            v
        })
    }

    /// The parameter with index `index` in the pool of this expression (see
    /// [`Expr::params_of`]).
    pub fn param_of_pool(self, index: u32) -> Option<Expr> {
        param_in(self.pool, index)
    }

    /// Number of unique nodes reachable from `roots` (the DAG size).
    pub fn dag_size(roots: &[Expr]) -> usize {
        reachable(roots).ids.len()
    }

    /// Counts of the arithmetic operations needed to evaluate `roots` with every unique node
    /// computed once (the cost of straight-line generated code).
    pub fn op_count(roots: &[Expr]) -> OpCount {
        let Reach { serial, ids, .. } = reachable(roots);
        with_serial(serial, |p| {
            let mut c = OpCount::default();
            for &i in &ids {
                c += p.shape(i).ops(|e| p.exponent(e));
            }
            c
        })
    }
}

/// The nodes reachable from some roots, in the roots' common pool.
pub(crate) struct Reach {
    /// The pool (see [`unify`]).
    pub serial: u32,
    /// The roots' ids in that pool, in the order given.
    pub roots: Vec<Id>,
    /// Every node reachable from them, ascending (a topological order).
    pub ids: Vec<Id>,
}

/// The nodes reachable from `roots` in their common pool.
pub(crate) fn reachable(roots: &[Expr]) -> Reach {
    let (serial, root_ids) = unify(roots);
    let ids = with_serial(serial, |p| reachable_in(p, root_ids.iter().copied()));
    Reach {
        serial,
        roots: root_ids,
        ids,
    }
}

/// Runs `f` with the pool of `roots` current, so that the expressions `f` builds from them
/// (constants included) are made in their pool.
pub(crate) fn in_pool_of<R>(roots: &[Expr], f: impl FnOnce() -> R) -> R {
    if roots.iter().all(|e| e.id <= MINUS_ONE) {
        return f();
    }
    let (serial, _) = unify(roots);
    match crate::ExprPool::find(serial) {
        Some(pool) => pool.enter(f),
        None => f(),
    }
}

pub(crate) fn reachable_in(p: &PoolData, roots: impl Iterator<Item = Id>) -> Vec<Id> {
    let mut seen = hashbrown::HashSet::new();
    let mut stack: Vec<Id> = roots.collect();
    let mut out = Vec::new();
    while let Some(i) = stack.pop() {
        if !seen.insert(i) {
            continue;
        }
        out.push(i);
        stack.extend(p.shape(i).children().iter().filter(|c| !seen.contains(*c)));
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
        self.build2(o, |p, a, b| p.add_n(&[a, b]))
    }
}
impl Sub for Expr {
    type Output = Expr;
    fn sub(self, o: Expr) -> Expr {
        self.build2(o, |p, a, b| {
            let n = p.neg(b);
            p.add_n(&[a, n])
        })
    }
}
impl Mul for Expr {
    type Output = Expr;
    fn mul(self, o: Expr) -> Expr {
        self.build2(o, |p, a, b| p.mul_n(&[a, b]))
    }
}
impl Div for Expr {
    type Output = Expr;
    fn div(self, o: Expr) -> Expr {
        self.build2(o, |p, a, b| {
            let r = p.pow_rational(b, Rational::MINUS_ONE);
            p.mul_n(&[a, r])
        })
    }
}
impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        self.build(|p, a| p.neg(a))
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
    ($t:ty) => {
        impl Add<$t> for Expr {
            type Output = Expr;
            fn add(self, o: $t) -> Expr {
                self + self.int_here(o as i64)
            }
        }
        impl Sub<$t> for Expr {
            type Output = Expr;
            fn sub(self, o: $t) -> Expr {
                self - self.int_here(o as i64)
            }
        }
        impl Mul<$t> for Expr {
            type Output = Expr;
            fn mul(self, o: $t) -> Expr {
                self * self.int_here(o as i64)
            }
        }
        impl Div<$t> for Expr {
            type Output = Expr;
            fn div(self, o: $t) -> Expr {
                self / self.int_here(o as i64)
            }
        }
        impl Add<Expr> for $t {
            type Output = Expr;
            fn add(self, o: Expr) -> Expr {
                o.int_here(self as i64) + o
            }
        }
        impl Sub<Expr> for $t {
            type Output = Expr;
            fn sub(self, o: Expr) -> Expr {
                o.int_here(self as i64) - o
            }
        }
        impl Mul<Expr> for $t {
            type Output = Expr;
            fn mul(self, o: Expr) -> Expr {
                o.int_here(self as i64) * o
            }
        }
        impl Div<Expr> for $t {
            type Output = Expr;
            fn div(self, o: Expr) -> Expr {
                o.int_here(self as i64) / o
            }
        }
    };
}
scalar_ops!(i64);
scalar_ops!(i32);

impl Expr {
    /// The integer `n` in this expression's pool (the scalar operators use it, so that `x * 2`
    /// stays in `x`'s pool whatever pool is current).
    fn int_here(self, n: i64) -> Expr {
        self.with_pool(|p| {
            let id = p.rational(Rational::int(n));
            p.expr(id)
        })
    }
}

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

/// Parameter number `index` of the pool with serial `serial`.
pub(crate) fn param_in(serial: u32, index: u32) -> Option<Expr> {
    with_serial(serial, |p| {
        ((index as usize) < p.params_len()).then(|| p.expr(p.param_node(index)))
    })
}
