//! The hash-consed expression pool.
//!
//! Every unique node is stored once; an [`Expr`] is the node's index in its pool together with
//! the pool's serial number (how pools are created, shared and freed is the subject of
//! [`context`](crate::context)). Children are stored before their parents, so node ids are a topological
//! order of the DAG — evaluation tapes and derivatives walk ids in increasing order without any
//! sorting.
//!
//! # Canonical forms
//!
//! * **Numbers** are exact rationals ([`Rational`]) or floats (measured data). Arithmetic
//!   between rationals stays exact; a float anywhere makes the result a float.
//! * **Sums** `c₀ + Σ cᵢ·tᵢ` store the numeric constant `c₀` and the terms `tᵢ` sorted by id
//!   with numeric coefficients `cᵢ ≠ 0`. A term is never a number, never a sum (sums are
//!   flattened) and never a product with a coefficient other than 1 (the coefficient is pulled
//!   out). So like terms are collected structurally: `x − x → 0`, `2x + 3x → 5x`.
//! * **Products** `c · Π bᵢ^eᵢ` store a numeric coefficient and bases sorted by id with rational
//!   exponents. Products are flattened; equal bases collect their exponents (`x·x → x²`).
//! * Nothing is ever expanded: `a·(b + c)` stays a product. The one exception is a *numeric*
//!   coefficient times a sum, which is distributed (`2·(a + b) → 2a + 2b`) so that sums have one
//!   canonical form; this never increases the number of unique nodes by more than one.
//!
//! # Identities applied by the smart constructors, and why each is safe
//!
//! "Safe" means: wherever the original expression is defined (real and finite), the result has
//! the same value. Identities that would *remove* a point where the original is undefined are
//! applied only when that point provably cannot occur.
//!
//! | identity | condition |
//! |---|---|
//! | `0 + x → x`, `1·x → x`, `x^1 → x`, `x − x → 0`, `c₁x + c₂x → (c₁+c₂)x` | always |
//! | `0·x → 0` | always (the standard convention of every CAS; `x` is assumed finite) |
//! | `c·sin²x + c·cos²x → c` | always |
//! | `x^a · x^b → x^(a+b)` | `a` and `b` have the same sign (no division is cancelled), **or** `x` is provably nonzero. Otherwise `x²/x` stays `x²·x⁻¹`, so `x/x → 1` only for nonzero constants or parameters declared nonzero/positive. |
//! | `(x·y)^n → xⁿyⁿ`, `(xᵃ)ⁿ → x^(an)` | `n` an integer |
//! | `(xᵃ)^r → x^(ar)`, `(x·y)^r → x^r y^r` | `r` not an integer: only when the bases are provably non-negative; `(x²)^(1/2) → abs(x)` for real `x` |
//! | `x^0 → 1` | always |
//! | numeric folding (`2·3 → 6`, `(4/9)^(1/2) → 2/3`, `sin(0) → 0`, `cos(kπ) → ±1`) | exact; a rational result too wide is an overflow error, never wrapped |
//! | `sin(−x) → −sin(x)`, `tan(−x) → −tan(x)`, `cos(−x) → cos(x)`, `abs(−x) → abs(x)` | always (odd/even functions; only when the argument has a negative numeric coefficient) |
//! | `abs(x) → x` / `−x` | `x` provably non-negative / non-positive |
//! | `exp(ln x) → x`, `ln(exp x) → x` | always (where defined) |
//!
//! Operations that have no real value (division by a structural zero, `ln(0)`, an even root of
//! a negative constant, a rational overflow) produce an *invalid* node that carries the error.
//! Invalid nodes absorb every operation they enter, and evaluation, display and code generation
//! report the error instead of a number: never a panic, never a silent NaN.

mod arith;
mod shape;
mod sign;

pub use shape::OpCount;
pub(crate) use shape::{Shape, ShapeBuf, ShapeRef, power_ops};
pub use sign::Sign;
pub(crate) use sign::pow_sign;

pub(crate) use arith::dyadic;

use crate::error::SymError;
use crate::expr::Expr;
pub use crate::func::Func;
use crate::rational::Rational;
use hashbrown::HashTable;
use std::hash::{BuildHasher, Hash, Hasher};

pub(crate) type Id = u32;

/// Named mathematical constants.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum Constant {
    /// π.
    Pi,
    /// Euler's number e.
    E,
}

impl Constant {
    /// The name used in text and by the parser.
    pub fn name(self) -> &'static str {
        match self {
            Constant::Pi => "pi",
            Constant::E => "e",
        }
    }
    /// Nearest `f64`.
    pub fn to_f64(self) -> f64 {
        match self {
            Constant::Pi => std::f64::consts::PI,
            Constant::E => std::f64::consts::E,
        }
    }
}

/// What is known about a parameter's sign. Declaring it lets the smart constructors apply
/// identities such as `m/m → 1` that are unsafe for a parameter that may vanish.
#[derive(
    Clone, Copy, PartialEq, Eq, Hash, Debug, Default, serde::Serialize, serde::Deserialize,
)]
pub enum Assumption {
    /// Any real value (the default).
    #[default]
    Real,
    /// Never zero.
    Nonzero,
    /// Strictly positive (masses, lengths, stiffnesses).
    Positive,
    /// Zero or positive.
    Nonnegative,
}

/// A parameter: a symbol with a nominal value, and optionally a unit and a description.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamInfo {
    /// The name as written in expressions (`m`, `IBxx`, `δ`).
    pub name: String,
    /// The nominal value, used for pivot decisions and as the default in evaluations.
    pub nominal: f64,
    /// Unit label (informational).
    pub unit: Option<String>,
    /// Free-text description.
    pub description: Option<String>,
    /// Sign assumption.
    pub assume: Assumption,
}

/// A number: exact rational or float.
#[derive(Clone, Debug, PartialEq)]
pub enum Number {
    /// Exact.
    Rat(Rational),
    /// Floating point (measured data). Always finite.
    Float(f64),
}

impl Number {
    pub(crate) fn to_f64(&self) -> f64 {
        match self {
            Number::Rat(r) => r.to_f64(),
            Number::Float(f) => *f,
        }
    }
    pub(crate) fn is_zero(&self) -> bool {
        match self {
            Number::Rat(r) => r.is_zero(),
            Number::Float(f) => *f == 0.0,
        }
    }
    pub(crate) fn is_one(&self) -> bool {
        match self {
            Number::Rat(r) => r.is_one(),
            Number::Float(f) => *f == 1.0,
        }
    }
    pub(crate) fn is_negative(&self) -> bool {
        match self {
            Number::Rat(r) => r.is_negative(),
            Number::Float(f) => *f < 0.0,
        }
    }
    fn add(&self, o: &Number) -> Result<Number, SymError> {
        match (self, o) {
            (Number::Rat(a), Number::Rat(b)) => a
                .add(b)
                .map(Number::Rat)
                .map_err(|_| SymError::RationalOverflow),
            _ => finite(self.to_f64() + o.to_f64()),
        }
    }
    fn mul(&self, o: &Number) -> Result<Number, SymError> {
        match (self, o) {
            (Number::Rat(a), Number::Rat(b)) => a
                .mul(b)
                .map(Number::Rat)
                .map_err(|_| SymError::RationalOverflow),
            _ => {
                let (a, b) = (self.to_f64(), o.to_f64());
                let p = a * b;
                // A product of nonzero constants that leaves the normal range lost digits
                // (or all of them): not an exact fold.
                if p.abs() < f64::MIN_POSITIVE && a != 0.0 && b != 0.0 {
                    return Err(SymError::Underflow {
                        what: format!("{a:e} × {b:e}"),
                    });
                }
                finite(p)
            }
        }
    }
}

fn finite(x: f64) -> Result<Number, SymError> {
    if x.is_finite() {
        Ok(Number::Float(x))
    } else {
        Err(SymError::NonFinite {
            what: "a floating-point constant".into(),
        })
    }
}

/// A node of the DAG. Children of sums and products live in the pool's argument arena.
#[derive(Clone, Debug)]
pub(crate) enum Node {
    Num(Rational),
    Float(f64),
    Const(Constant),
    Param(u32),
    /// `args[start] = c₀`, then `(term, coef)` pairs.
    Add(u32, u32),
    /// `args[start] = coef`, then `(base, exponent)` pairs; exponents are rational numbers.
    Mul(u32, u32),
    /// General power with a non-rational exponent.
    Pow(Id, Id),
    Func(Func, Id),
    Atan2(Id, Id),
    /// An operation without a real value; index into the error list.
    Invalid(u32),
}

/// The shape of a stored node (also its key in the hash-consing table).
fn shape_at<'a>(nodes: &'a [Node], args: &'a [u32], id: Id) -> ShapeRef<'a> {
    let slice = |s: u32, l: u32| &args[s as usize..(s + l) as usize];
    match &nodes[id as usize] {
        Node::Num(r) => Shape::Num(r),
        Node::Float(f) => Shape::Float(f.to_bits()),
        Node::Const(c) => Shape::Const(*c),
        Node::Param(p) => Shape::Param(*p),
        Node::Add(s, l) => Shape::Add(slice(*s, *l)),
        Node::Mul(s, l) => Shape::Mul(slice(*s, *l)),
        Node::Pow(a, b) => Shape::Pow([*a, *b]),
        Node::Func(f, a) => Shape::Func(*f, [*a]),
        Node::Atan2(a, b) => Shape::Atan2([*a, *b]),
        Node::Invalid(e) => Shape::Invalid(*e),
    }
}

#[derive(Default, Clone, Copy)]
struct FxBuild;
impl BuildHasher for FxBuild {
    type Hasher = FxHasher;
    fn build_hasher(&self) -> FxHasher {
        FxHasher(0)
    }
}
/// A small multiplicative hasher (the keys are short runs of integers).
struct FxHasher(u64);
impl Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut b = [0u8; 8];
            b[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(b));
        }
    }
    fn write_u8(&mut self, i: u8) {
        self.add(i as u64)
    }
    fn write_u32(&mut self, i: u32) {
        self.add(i as u64)
    }
    fn write_u64(&mut self, i: u64) {
        self.add(i)
    }
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64)
    }
}
impl FxHasher {
    #[inline]
    fn add(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// Statistics of a pool.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PoolStats {
    /// Unique nodes stored.
    pub nodes: usize,
    /// Entries in the children arena.
    pub arena: usize,
    /// Parameters declared.
    pub params: usize,
    /// Interning calls so far: every lookup of a node by its key, whether it found an existing
    /// node or created a new one (for throughput measurements).
    pub interns: u64,
    /// Memory held by the pool's arrays and hash table, in bytes (their capacities; the
    /// parameters' names and the errors' texts are not counted).
    pub bytes: usize,
}

/// The contents of one expression pool: the arena of unique nodes. Reached through an
/// [`ExprPool`](crate::ExprPool) handle (see [`context`](crate::context)).
pub(crate) struct PoolData {
    /// The serial number of the pool, carried by every [`Expr`] of it.
    serial: u32,
    nodes: Vec<Node>,
    args: Vec<u32>,
    nominal: Vec<f64>,
    sign: Vec<Sign>,
    table: HashTable<u32>,
    params: Vec<ParamInfo>,
    param_node: Vec<Id>,
    errors: Vec<SymError>,
    interns: u64,
    /// Hash of each node's key, so that growing the table does not rehash the keys and a probe
    /// compares keys only on a full hash match.
    hashes: Vec<u64>,
    /// Ids of the small rationals `n/1` and `n/2`, `|n| ≤ SMALL` (most coefficients and
    /// exponents), found without hashing; `NONE` until first built.
    small: [[Id; 2 * SMALL as usize + 1]; 2],
    /// Scratch buffers of the sum and product constructors, reused to avoid allocating on every
    /// call (taken with `mem::take`, so a nested call simply gets a fresh one).
    terms_buf: Vec<(Id, Number)>,
    factors_buf: Vec<(Id, Rational)>,
    key_buf: Vec<u32>,
    /// `−a` of each node `a` negated so far (`NONE`: not yet), see [`PoolData::neg`].
    negations: Vec<Id>,
    /// The memo of [`zero`](crate::zero)'s probe evaluations (values per node of this pool).
    probe: Option<Box<crate::zero::Probe>>,
}

/// Range of the direct-mapped small rationals.
const SMALL: i64 = 16;
const NONE: Id = Id::MAX;

pub(crate) const ZERO: Id = 0;
pub(crate) const ONE: Id = 1;
pub(crate) const MINUS_ONE: Id = 2;

impl PoolData {
    pub(crate) fn new(serial: u32) -> Self {
        let mut p = PoolData {
            serial,
            nodes: Vec::new(),
            args: Vec::new(),
            nominal: Vec::new(),
            sign: Vec::new(),
            table: HashTable::new(),
            params: Vec::new(),
            param_node: Vec::new(),
            errors: Vec::new(),
            interns: 0,
            hashes: Vec::new(),
            small: [[NONE; 2 * SMALL as usize + 1]; 2],
            terms_buf: Vec::new(),
            factors_buf: Vec::new(),
            key_buf: Vec::new(),
            negations: Vec::new(),
            probe: None,
        };
        let z = p.rational(Rational::ZERO);
        let o = p.rational(Rational::ONE);
        let m = p.rational(Rational::MINUS_ONE);
        debug_assert_eq!((z, o, m), (ZERO, ONE, MINUS_ONE));
        p
    }

    /// The expression handle of node `id` of this pool.
    pub(crate) fn expr(&self, id: Id) -> Expr {
        Expr::new(id, self.serial)
    }

    pub(crate) fn stats(&self) -> PoolStats {
        use std::mem::size_of;
        let bytes = self.nodes.capacity() * size_of::<Node>()
            + self.args.capacity() * size_of::<u32>()
            + self.nominal.capacity() * size_of::<f64>()
            + self.sign.capacity() * size_of::<Sign>()
            + self.hashes.capacity() * size_of::<u64>()
            + self.table.capacity() * (size_of::<u32>() + 1)
            + self.param_node.capacity() * size_of::<Id>()
            + self.params.capacity() * size_of::<ParamInfo>()
            + self.errors.capacity() * size_of::<SymError>()
            + self.negations.capacity() * size_of::<Id>();
        PoolStats {
            nodes: self.nodes.len(),
            arena: self.args.len(),
            params: self.params.len(),
            interns: self.interns,
            bytes,
        }
    }

    /// `−a`, memoized per node. A negation is a product with −1 through the whole product
    /// constructor, and the elimination negates the same entries again and again (a
    /// subtraction negates its right operand). Nodes never change once built, so the memo
    /// is never stale.
    pub(crate) fn neg(&mut self, a: Id) -> Id {
        let i = a as usize;
        if let Some(&n) = self.negations.get(i)
            && n != NONE
        {
            return n;
        }
        let n = self.mul_n(&[MINUS_ONE, a]);
        if self.negations.len() <= i {
            self.negations.resize(self.nodes.len().max(i + 1), NONE);
        }
        self.negations[i] = n;
        n
    }

    /// The probe memo, taken out while it is used with `&self`.
    pub(crate) fn take_probe(&mut self) -> Box<crate::zero::Probe> {
        self.probe.take().unwrap_or_default()
    }
    pub(crate) fn put_probe(&mut self, p: Box<crate::zero::Probe>) {
        self.probe = Some(p);
    }

    pub(crate) fn param_info(&self, index: u32) -> Option<ParamInfo> {
        self.params.get(index as usize).cloned()
    }

    /// A parameter of this pool with the same metadata as `info` (for moving expressions
    /// between pools).
    pub(crate) fn find_param(&self, info: &ParamInfo) -> Option<Id> {
        let k = self.params.iter().position(|p| p == info)?;
        Some(self.param_node[k])
    }

    // ---------------------------------------------------------------- access

    pub(crate) fn node(&self, id: Id) -> &Node {
        &self.nodes[id as usize]
    }
    pub(crate) fn nominal(&self, id: Id) -> f64 {
        self.nominal[id as usize]
    }
    pub(crate) fn sign(&self, id: Id) -> Sign {
        self.sign[id as usize]
    }
    pub(crate) fn param(&self, index: u32) -> &ParamInfo {
        &self.params[index as usize]
    }
    pub(crate) fn error(&self, index: u32) -> &SymError {
        &self.errors[index as usize]
    }
    pub(crate) fn args_of(&self, start: u32, len: u32) -> &[u32] {
        &self.args[start as usize..(start + len) as usize]
    }
    /// `(c₀, [(term, coef)])` of a sum.
    pub(crate) fn add_parts(&self, id: Id) -> Option<(Id, &[u32])> {
        match self.nodes[id as usize] {
            Node::Add(s, l) => {
                let a = self.args_of(s, l);
                Some((a[0], &a[1..]))
            }
            _ => None,
        }
    }
    /// `(coef, [(base, exponent)])` of a product.
    pub(crate) fn mul_parts(&self, id: Id) -> Option<(Id, &[u32])> {
        match self.nodes[id as usize] {
            Node::Mul(s, l) => {
                let a = self.args_of(s, l);
                Some((a[0], &a[1..]))
            }
            _ => None,
        }
    }
    pub(crate) fn number(&self, id: Id) -> Option<Number> {
        match &self.nodes[id as usize] {
            Node::Num(r) => Some(Number::Rat(r.clone())),
            Node::Float(f) => Some(Number::Float(*f)),
            _ => None,
        }
    }
    pub(crate) fn rational_of(&self, id: Id) -> Option<&Rational> {
        match &self.nodes[id as usize] {
            Node::Num(r) => Some(r),
            _ => None,
        }
    }
    pub(crate) fn is_number(&self, id: Id) -> bool {
        matches!(self.nodes[id as usize], Node::Num(_) | Node::Float(_))
    }
    pub(crate) fn invalid_of(&self, id: Id) -> Option<u32> {
        match self.nodes[id as usize] {
            Node::Invalid(e) => Some(e),
            _ => None,
        }
    }
    /// The shape of node `id`: its kind and its children (see [`Shape`]).
    pub(crate) fn shape(&self, id: Id) -> ShapeRef<'_> {
        shape_at(&self.nodes, &self.args, id)
    }
    /// The rational exponent of a product's factor.
    pub(crate) fn exponent(&self, id: Id) -> Rational {
        self.rational_of(id)
            .expect("product exponents are rational")
            .clone()
    }

    // ---------------------------------------------------------------- interning

    fn intern(&mut self, key: ShapeRef<'_>) -> Id {
        self.interns += 1;
        let h = FxBuild.hash_one(key);
        let (nodes, args, hashes) = (&self.nodes, &self.args, &self.hashes);
        let found = self.table.find(h, |&id| {
            hashes[id as usize] == h && shape_at(nodes, args, id) == key
        });
        if let Some(&id) = found {
            return id;
        }
        let (nom, sign) = self.analyse(key);
        let id = self.nodes.len() as Id;
        let node = match key {
            Shape::Num(r) => Node::Num(r.clone()),
            Shape::Float(b) => Node::Float(f64::from_bits(b)),
            Shape::Const(c) => Node::Const(c),
            Shape::Param(p) => Node::Param(p),
            Shape::Add(a) | Shape::Mul(a) => {
                let start = self.args.len() as u32;
                self.args.extend_from_slice(a);
                if matches!(key, Shape::Add(_)) {
                    Node::Add(start, a.len() as u32)
                } else {
                    Node::Mul(start, a.len() as u32)
                }
            }
            Shape::Pow([a, b]) => Node::Pow(a, b),
            Shape::Func(f, [a]) => Node::Func(f, a),
            Shape::Atan2([a, b]) => Node::Atan2(a, b),
            Shape::Invalid(e) => Node::Invalid(e),
        };
        self.nodes.push(node);
        self.nominal.push(nom);
        self.sign.push(sign);
        self.hashes.push(h);
        let hashes = &self.hashes;
        self.table.insert_unique(h, id, |&i| hashes[i as usize]);
        id
    }

    /// Nominal value and sign knowledge of a new node (children already analysed).
    fn analyse(&self, shape: ShapeRef<'_>) -> (f64, Sign) {
        let nominal = match shape {
            Shape::Param(p) => self.params[p as usize].nominal,
            Shape::Invalid(_) => f64::NAN,
            _ => shape
                .eval(|i| self.nominal(i), |i| self.exponent(i))
                .expect("a node with a value"),
        };
        let sign = match shape {
            Shape::Num(r) => Sign::from_rational(r),
            Shape::Float(_) => Sign::of(nominal),
            Shape::Const(_) => Sign::POSITIVE,
            Shape::Param(p) => match self.params[p as usize].assume {
                Assumption::Real => Sign::ANY,
                Assumption::Nonzero => Sign::NONZERO,
                Assumption::Positive => Sign::POSITIVE,
                Assumption::Nonnegative => Sign::NONNEG,
            },
            Shape::Add(a) => a[1..].chunks_exact(2).fold(self.sign(a[0]), |s, t| {
                s.add(self.sign(t[1]).mul(self.sign(t[0])))
            }),
            Shape::Mul(a) => a[1..].chunks_exact(2).fold(self.sign(a[0]), |s, t| {
                s.mul(pow_sign(self.sign(t[0]), &self.exponent(t[1])))
            }),
            Shape::Pow([a, _]) if self.sign(a).is_positive() => Sign::POSITIVE,
            Shape::Func(f, [a]) => f.sign(self.sign(a)),
            Shape::Pow(_) | Shape::Atan2(_) | Shape::Invalid(_) => Sign::ANY,
        };
        (nominal, sign)
    }

    // ---------------------------------------------------------------- leaves

    pub(crate) fn rational(&mut self, r: Rational) -> Id {
        if let Rational::Small(n, d @ (1 | 2)) = r
            && n.abs() <= SMALL
        {
            let slot = &mut self.small[(d - 1) as usize][(n + SMALL) as usize];
            if *slot != NONE {
                self.interns += 1;
                return *slot;
            }
            let id = self.intern(Shape::Num(&r));
            self.small[(d - 1) as usize][(n + SMALL) as usize] = id;
            return id;
        }
        self.intern(Shape::Num(&r))
    }

    pub(crate) fn float(&mut self, x: f64) -> Id {
        if !x.is_finite() {
            return self.invalid(SymError::NonFinite {
                what: format!("the constant {x}"),
            });
        }
        // Integers and short dyadic fractions are exact: store them as rationals, so that
        // float arithmetic that lands on such a value (0.1·10 = 1) folds like exact input.
        if let Some(r) = dyadic(x) {
            return self.rational(r);
        }
        self.intern(Shape::Float(x.to_bits()))
    }

    pub(crate) fn num(&mut self, n: Number) -> Id {
        match n {
            Number::Rat(r) => self.rational(r),
            Number::Float(f) => self.float(f),
        }
    }

    pub(crate) fn constant(&mut self, c: Constant) -> Id {
        self.intern(Shape::Const(c))
    }

    pub(crate) fn new_param(&mut self, info: ParamInfo) -> Id {
        let index = self.params.len() as u32;
        self.params.push(info);
        let id = self.intern(Shape::Param(index));
        self.param_node.push(id);
        id
    }

    pub(crate) fn param_node(&self, index: u32) -> Id {
        self.param_node[index as usize]
    }

    pub(crate) fn params_len(&self) -> usize {
        self.params.len()
    }

    pub(crate) fn invalid(&mut self, e: SymError) -> Id {
        let index = self.errors.len() as u32;
        self.errors.push(e);
        self.intern(Shape::Invalid(index))
    }

    fn first_invalid(&self, ids: &[Id]) -> Option<Id> {
        ids.iter()
            .copied()
            .find(|&i| matches!(self.nodes[i as usize], Node::Invalid(_)))
    }
}
