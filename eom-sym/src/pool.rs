//! The hash-consed expression pool.
//!
//! Every unique node is stored once; an [`Expr`](crate::Expr) is a 4-byte index into the pool of
//! the current thread. Children are stored before their parents, so node ids are a topological
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

use crate::error::SymError;
use crate::rational::Rational;
use hashbrown::HashTable;
use std::cell::RefCell;
use std::hash::{BuildHasher, Hash, Hasher};

pub(crate) type Id = u32;

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

impl Func {
    /// The name used in text and by the parser.
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
    /// Evaluate in `f64`.
    pub fn eval_f64(self, x: f64) -> f64 {
        match self {
            Func::Sin => crate::trig::sin(x),
            Func::Cos => crate::trig::cos(x),
            Func::Tan => x.tan(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
        }
    }
}

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

    fn of(x: f64) -> Sign {
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
    fn neg(self) -> Sign {
        let mut s = self.0 & Self::ZERO;
        if self.0 & Self::NEG != 0 {
            s |= Self::POS;
        }
        if self.0 & Self::POS != 0 {
            s |= Self::NEG;
        }
        Sign(s)
    }
    fn mul(self, o: Sign) -> Sign {
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
    fn add(self, o: Sign) -> Sign {
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
            _ => finite(self.to_f64() * o.to_f64()),
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

/// The lookup key of a stored node.
fn key_at<'a>(nodes: &'a [Node], args: &'a [u32], id: Id) -> Key<'a> {
    let slice = |s: u32, l: u32| &args[s as usize..(s + l) as usize];
    match &nodes[id as usize] {
        Node::Num(r) => Key::Num(r),
        Node::Float(f) => Key::Float(f.to_bits()),
        Node::Const(c) => Key::Const(*c),
        Node::Param(p) => Key::Param(*p),
        Node::Add(s, l) => Key::Add(slice(*s, *l)),
        Node::Mul(s, l) => Key::Mul(slice(*s, *l)),
        Node::Pow(a, b) => Key::Pow(*a, *b),
        Node::Func(f, a) => Key::Func(*f, *a),
        Node::Atan2(a, b) => Key::Atan2(*a, *b),
        Node::Invalid(e) => Key::Invalid(*e),
    }
}

/// Borrowed key used for hashing and lookup without allocation.
#[derive(PartialEq, Hash)]
enum Key<'a> {
    Num(&'a Rational),
    Float(u64),
    Const(Constant),
    Param(u32),
    Add(&'a [u32]),
    Mul(&'a [u32]),
    Pow(Id, Id),
    Func(Func, Id),
    Atan2(Id, Id),
    Invalid(u32),
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
}

/// The expression pool: the arena of unique nodes of one thread.
///
/// Users rarely touch it directly: [`Expr`](crate::Expr) values and their operators use the
/// pool of the current thread. It is exposed for statistics ([`ExprPool::stats`]) and for
/// parameter metadata ([`ExprPool::param_info`]).
pub struct ExprPool {
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
}

/// Range of the direct-mapped small rationals.
const SMALL: i64 = 16;
const NONE: Id = Id::MAX;

thread_local! {
    static POOL: RefCell<ExprPool> = RefCell::new(ExprPool::new());
}

/// Run `f` with the pool of the current thread.
pub(crate) fn with_pool<R>(f: impl FnOnce(&mut ExprPool) -> R) -> R {
    POOL.with(|p| f(&mut p.borrow_mut()))
}

pub(crate) const ZERO: Id = 0;
pub(crate) const ONE: Id = 1;
pub(crate) const MINUS_ONE: Id = 2;

impl ExprPool {
    fn new() -> Self {
        let mut p = ExprPool {
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
        };
        let z = p.rational(Rational::ZERO);
        let o = p.rational(Rational::ONE);
        let m = p.rational(Rational::MINUS_ONE);
        debug_assert_eq!((z, o, m), (ZERO, ONE, MINUS_ONE));
        p
    }

    /// Statistics of the pool of the current thread.
    pub fn stats() -> PoolStats {
        with_pool(|p| PoolStats {
            nodes: p.nodes.len(),
            arena: p.args.len(),
            params: p.params.len(),
            interns: p.interns,
        })
    }

    /// Metadata of parameter number `index` of the current thread's pool.
    pub fn param_info(index: u32) -> Option<ParamInfo> {
        with_pool(|p| p.params.get(index as usize).cloned())
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
    /// Children of a node in a fixed order (for traversals).
    pub(crate) fn for_each_child(&self, id: Id, mut f: impl FnMut(Id)) {
        match self.nodes[id as usize] {
            Node::Add(s, l) | Node::Mul(s, l) => {
                for &c in self.args_of(s, l) {
                    f(c)
                }
            }
            Node::Pow(a, b) | Node::Atan2(a, b) => {
                f(a);
                f(b)
            }
            Node::Func(_, a) => f(a),
            _ => {}
        }
    }

    // ---------------------------------------------------------------- interning

    fn hash_key(key: &Key<'_>) -> u64 {
        FxBuild.hash_one(key)
    }

    fn intern(&mut self, key: Key<'_>) -> Id {
        self.interns += 1;
        let h = Self::hash_key(&key);
        let (nodes, args, hashes) = (&self.nodes, &self.args, &self.hashes);
        let found = self.table.find(h, |&id| {
            hashes[id as usize] == h && key_at(nodes, args, id) == key
        });
        if let Some(&id) = found {
            return id;
        }
        let id = self.nodes.len() as Id;
        let node = match key {
            Key::Num(r) => Node::Num(r.clone()),
            Key::Float(b) => Node::Float(f64::from_bits(b)),
            Key::Const(c) => Node::Const(c),
            Key::Param(p) => Node::Param(p),
            Key::Add(a) | Key::Mul(a) => {
                let start = self.args.len() as u32;
                self.args.extend_from_slice(a);
                if matches!(key, Key::Add(_)) {
                    Node::Add(start, a.len() as u32)
                } else {
                    Node::Mul(start, a.len() as u32)
                }
            }
            Key::Pow(a, b) => Node::Pow(a, b),
            Key::Func(f, a) => Node::Func(f, a),
            Key::Atan2(a, b) => Node::Atan2(a, b),
            Key::Invalid(e) => Node::Invalid(e),
        };
        let (nom, sign) = self.analyse(&node);
        self.nodes.push(node);
        self.nominal.push(nom);
        self.sign.push(sign);
        self.hashes.push(h);
        let hashes = &self.hashes;
        self.table.insert_unique(h, id, |&i| hashes[i as usize]);
        id
    }

    /// Nominal value and sign knowledge of a new node (children already analysed).
    fn analyse(&self, node: &Node) -> (f64, Sign) {
        match node {
            Node::Num(r) => {
                let v = r.to_f64();
                (v, Sign::from_rational(r))
            }
            Node::Float(f) => (*f, Sign::of(*f)),
            Node::Const(c) => (c.to_f64(), Sign::POSITIVE),
            Node::Param(p) => {
                let info = &self.params[*p as usize];
                let s = match info.assume {
                    Assumption::Real => Sign::ANY,
                    Assumption::Nonzero => Sign::NONZERO,
                    Assumption::Positive => Sign::POSITIVE,
                    Assumption::Nonnegative => Sign::NONNEG,
                };
                (info.nominal, s)
            }
            Node::Add(s, l) => {
                let a = self.args_of(*s, *l);
                let mut v = self.nominal(a[0]);
                let mut sg = self.sign(a[0]);
                for p in a[1..].chunks_exact(2) {
                    v += self.nominal(p[1]) * self.nominal(p[0]);
                    sg = sg.add(self.sign(p[1]).mul(self.sign(p[0])));
                }
                (v, sg)
            }
            Node::Mul(s, l) => {
                let a = self.args_of(*s, *l);
                let mut v = self.nominal(a[0]);
                let mut sg = self.sign(a[0]);
                for p in a[1..].chunks_exact(2) {
                    let e = self
                        .rational_of(p[1])
                        .expect("product exponents are rational");
                    v *= pow_f64(self.nominal(p[0]), e);
                    sg = sg.mul(pow_sign(self.sign(p[0]), e));
                }
                (v, sg)
            }
            Node::Pow(a, b) => {
                let v = self.nominal(*a).powf(self.nominal(*b));
                let s = if self.sign(*a).is_positive() {
                    Sign::POSITIVE
                } else {
                    Sign::ANY
                };
                (v, s)
            }
            Node::Func(f, a) => {
                let x = self.nominal(*a);
                let s = match f {
                    Func::Exp => Sign::POSITIVE,
                    Func::Abs if self.sign(*a).is_nonzero() => Sign::POSITIVE,
                    Func::Abs => Sign::NONNEG,
                    _ => Sign::ANY,
                };
                (f.eval_f64(x), s)
            }
            Node::Atan2(a, b) => (self.nominal(*a).atan2(self.nominal(*b)), Sign::ANY),
            Node::Invalid(_) => (f64::NAN, Sign::ANY),
        }
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
            let id = self.intern(Key::Num(&r));
            self.small[(d - 1) as usize][(n + SMALL) as usize] = id;
            return id;
        }
        self.intern(Key::Num(&r))
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
        self.intern(Key::Float(x.to_bits()))
    }

    pub(crate) fn num(&mut self, n: Number) -> Id {
        match n {
            Number::Rat(r) => self.rational(r),
            Number::Float(f) => self.float(f),
        }
    }

    pub(crate) fn constant(&mut self, c: Constant) -> Id {
        self.intern(Key::Const(c))
    }

    pub(crate) fn new_param(&mut self, info: ParamInfo) -> Id {
        let index = self.params.len() as u32;
        self.params.push(info);
        let id = self.intern(Key::Param(index));
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
        self.intern(Key::Invalid(index))
    }

    fn first_invalid(&self, ids: &[Id]) -> Option<Id> {
        ids.iter()
            .copied()
            .find(|&i| matches!(self.nodes[i as usize], Node::Invalid(_)))
    }

    // ---------------------------------------------------------------- sums

    /// `Σ items`, canonical.
    pub(crate) fn add_n(&mut self, items: &[Id]) -> Id {
        if let Some(bad) = self.first_invalid(items) {
            return bad;
        }
        match items {
            [] => return ZERO,
            [a] => return *a,
            [a, b] if *a == ZERO => return *b,
            [a, b] if *b == ZERO => return *a,
            _ => {}
        }
        let mut c0 = Number::Rat(Rational::ZERO);
        let mut terms = std::mem::take(&mut self.terms_buf);
        terms.clear();
        let mut id = None;
        for &it in items {
            if let Err(e) = self.collect_add(it, &Number::Rat(Rational::ONE), &mut c0, &mut terms) {
                id = Some(self.invalid(e));
                break;
            }
        }
        let id = id.unwrap_or_else(|| self.finish_add(c0, &mut terms));
        terms.clear();
        self.terms_buf = terms;
        id
    }

    /// Push `scale·item` into a sum under construction.
    fn collect_add(
        &mut self,
        item: Id,
        scale: &Number,
        c0: &mut Number,
        terms: &mut Vec<(Id, Number)>,
    ) -> Result<(), SymError> {
        match &self.nodes[item as usize] {
            Node::Num(_) | Node::Float(_) => {
                let v = self.number(item).expect("number");
                *c0 = c0.add(&v.mul(scale)?)?;
            }
            Node::Add(s, l) => {
                let (s, l) = (*s, *l);
                let a0 = self.args[s as usize];
                let v = self.number(a0).expect("sum constant");
                *c0 = c0.add(&v.mul(scale)?)?;
                for k in 0..(l as usize - 1) / 2 {
                    let t = self.args[s as usize + 1 + 2 * k];
                    let c = self
                        .number(self.args[s as usize + 2 + 2 * k])
                        .expect("coefficient");
                    terms.push((t, c.mul(scale)?));
                }
            }
            Node::Mul(s, l) => {
                let (s, l) = (*s, *l);
                let coef = self.number(self.args[s as usize]).expect("coefficient");
                if coef.is_one() {
                    terms.push((item, scale.clone()));
                } else {
                    let unit = self.unit_product(item);
                    let _ = l;
                    terms.push((unit, coef.mul(scale)?));
                }
            }
            _ => terms.push((item, scale.clone())),
        }
        Ok(())
    }

    /// `(q, s)` with `b = q·s` and the first coefficient of the sum `s` one, when `b` is an
    /// exact sum (no float coefficients: dividing those would round) whose first coefficient
    /// is not already one.
    fn primitive_sum(&mut self, b: Id) -> Option<(Rational, Id)> {
        let (c0, pairs) = self.add_parts(b)?;
        let q = match &self.nodes[pairs[1] as usize] {
            Node::Num(q) if !q.is_one() => q.clone(),
            _ => return None,
        };
        let exact = matches!(self.nodes[c0 as usize], Node::Num(_))
            && pairs
                .chunks_exact(2)
                .all(|p| matches!(self.nodes[p[1] as usize], Node::Num(_)));
        if !exact {
            return None;
        }
        let inv = Number::Rat(q.recip()?);
        let mut c = Number::Rat(Rational::ZERO);
        let mut terms = Vec::with_capacity(pairs.len() / 2);
        self.collect_add(b, &inv, &mut c, &mut terms).ok()?;
        let s = self.finish_add(c, &mut terms);
        matches!(self.nodes[s as usize], Node::Add(..)).then_some((q, s))
    }

    /// The product with its numeric coefficient replaced by one.
    fn unit_product(&mut self, id: Id) -> Id {
        let (_, pairs) = self.mul_parts(id).expect("product");
        if pairs.len() == 2 && pairs[1] == ONE {
            return pairs[0];
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(ONE);
        key.extend_from_slice(self.mul_parts(id).expect("product").1);
        let id = self.intern(Key::Mul(&key));
        self.key_buf = key;
        id
    }

    /// The canonical sum `c0 + Σ terms`. `terms` is consumed (left in an unspecified state).
    fn finish_add(&mut self, c0: Number, terms: &mut Vec<(Id, Number)>) -> Id {
        // Stable sort: the coefficients of equal terms are added in a fixed order.
        terms.sort_by_key(|t| t.0);
        // Merge equal terms in place.
        let mut w = 0;
        for i in 0..terms.len() {
            if w > 0 && terms[w - 1].0 == terms[i].0 {
                match terms[w - 1].1.add(&terms[i].1) {
                    Ok(s) => terms[w - 1].1 = s,
                    Err(e) => return self.invalid(e),
                }
            } else {
                terms.swap(w, i);
                w += 1;
            }
        }
        terms.truncate(w);
        terms.retain(|(_, c)| !c.is_zero());
        let c0 = match self.pythagoras(terms, c0) {
            Ok(c) => c,
            Err(e) => return self.invalid(e),
        };
        if terms.is_empty() {
            return self.num(c0);
        }
        if c0.is_zero() && terms.len() == 1 {
            let (t, c) = terms.pop().expect("one term");
            return self.scale(t, c);
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(self.num(c0));
        for (t, c) in terms.drain(..) {
            key.push(t);
            let cid = self.num(c);
            key.push(cid);
        }
        let id = self.intern(Key::Add(&key));
        self.key_buf = key;
        id
    }

    /// `c·sin²x + c·cos²x → c` (always safe). Terms are `(sin x)²` / `(cos x)²` products.
    fn pythagoras(
        &mut self,
        terms: &mut Vec<(Id, Number)>,
        mut c0: Number,
    ) -> Result<Number, SymError> {
        let square_of = |p: &Self, t: Id, f: Func| -> Option<Id> {
            let (c, pairs) = p.mul_parts(t)?;
            if c != ONE || pairs.len() != 2 || p.rational_of(pairs[1])?.to_i64() != Some(2) {
                return None;
            }
            match p.node(pairs[0]) {
                Node::Func(g, x) if *g == f => Some(*x),
                _ => None,
            }
        };
        let mut i = 0;
        while i < terms.len() {
            if let Some(x) = square_of(self, terms[i].0, Func::Sin) {
                let cos_term = terms.iter().position(|(t, c)| {
                    *c == terms[i].1 && square_of(self, *t, Func::Cos) == Some(x)
                });
                if let Some(j) = cos_term {
                    c0 = c0.add(&terms[i].1)?;
                    let (hi, lo) = (i.max(j), i.min(j));
                    terms.remove(hi);
                    terms.remove(lo);
                    continue;
                }
            }
            i += 1;
        }
        Ok(c0)
    }

    /// `c·t` for a term `t` of a sum (not a number, not a sum, unit coefficient).
    fn scale(&mut self, t: Id, c: Number) -> Id {
        if c.is_one() {
            return t;
        }
        let cid = self.num(c);
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(cid);
        match self.mul_parts(t) {
            Some((_, pairs)) => key.extend_from_slice(pairs),
            None => {
                key.push(t);
                key.push(ONE);
            }
        }
        let id = self.intern(Key::Mul(&key));
        self.key_buf = key;
        id
    }

    // ---------------------------------------------------------------- products

    /// `Π items`, canonical.
    pub(crate) fn mul_n(&mut self, items: &[Id]) -> Id {
        if let Some(bad) = self.first_invalid(items) {
            return bad;
        }
        match items {
            [] => return ONE,
            [a] => return *a,
            [a, b] if *a == ONE => return *b,
            [a, b] if *b == ONE => return *a,
            _ => {}
        }
        let mut coef = Number::Rat(Rational::ONE);
        let mut factors = std::mem::take(&mut self.factors_buf);
        factors.clear();
        let id = self.mul_items(items, &mut coef, &mut factors);
        let id = id.unwrap_or_else(|| {
            if coef.is_zero() {
                ZERO
            } else {
                self.finish_mul(coef, &mut factors)
            }
        });
        factors.clear();
        self.factors_buf = factors;
        id
    }

    /// Flatten the factors of `items` into `coef` and `factors`; `Some(invalid)` on an error.
    fn mul_items(
        &mut self,
        items: &[Id],
        coef: &mut Number,
        factors: &mut Vec<(Id, Rational)>,
    ) -> Option<Id> {
        for &it in items {
            match &self.nodes[it as usize] {
                Node::Num(_) | Node::Float(_) => {
                    let v = self.number(it).expect("number");
                    match coef.mul(&v) {
                        Ok(c) => *coef = c,
                        Err(e) => return Some(self.invalid(e)),
                    }
                }
                Node::Mul(s, l) => {
                    let (s, l) = (*s as usize, *l as usize);
                    let c = self.number(self.args[s]).expect("coefficient");
                    match coef.mul(&c) {
                        Ok(c) => *coef = c,
                        Err(e) => return Some(self.invalid(e)),
                    }
                    for k in 0..(l - 1) / 2 {
                        let b = self.args[s + 1 + 2 * k];
                        let e = self
                            .rational_of(self.args[s + 2 + 2 * k])
                            .expect("exp")
                            .clone();
                        factors.push((b, e));
                    }
                }
                _ => factors.push((it, Rational::ONE)),
            }
        }
        None
    }

    /// The canonical product `coef·Π factors`. `factors` is consumed (left in an unspecified
    /// state).
    fn finish_mul(&mut self, mut coef: Number, factors: &mut Vec<(Id, Rational)>) -> Id {
        // Sum bases with integer exponents are made primitive (first coefficient one), the
        // content going into the coefficient: `(2a + 2b)·x` and `2·((a + b)·x)` must be the
        // same node although `2·(a + b)` alone is distributed. A lone sum to the first power
        // is left alone: it is distributed below anyway.
        if !(factors.len() == 1 && factors[0].1.is_one()) {
            for f in factors.iter_mut() {
                let Some(k) = f.1.to_i64().filter(|_| f.1.is_integer()) else {
                    continue;
                };
                let Some((q, s)) = self.primitive_sum(f.0) else {
                    continue;
                };
                match q.powi(k) {
                    Some(Ok(qk)) => match coef.mul(&Number::Rat(qk)) {
                        Ok(c) => coef = c,
                        Err(err) => return self.invalid(err),
                    },
                    _ => return self.invalid(SymError::RationalOverflow),
                }
                f.0 = s;
            }
        }
        // Sort by base, positive exponents before negative ones.
        factors.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.signum().cmp(&a.1.signum())));
        // Merge equal bases in place.
        let mut w = 0;
        for i in 0..factors.len() {
            if w > 0 {
                let (b, lb) = (factors[i].0, factors[w - 1].0);
                let same_sign = factors[w - 1].1.signum() == factors[i].1.signum();
                if lb == b && (same_sign || self.sign(b).is_nonzero()) {
                    match factors[w - 1].1.add(&factors[i].1) {
                        Ok(s) => factors[w - 1].1 = s,
                        Err(_) => return self.invalid(SymError::RationalOverflow),
                    }
                    continue;
                }
                // Same base, opposite sign, base may vanish: keep a second entry so that
                // no division is cancelled (see the table in the module docs).
            }
            factors.swap(w, i);
            w += 1;
        }
        factors.truncate(w);
        // Fold numeric bases with integer exponents into the coefficient; drop x^0. The kept
        // factors are compacted in place; expansions (rare) go to `extra`.
        let mut kept = 0;
        let mut extra: Vec<(Id, Rational)> = Vec::new();
        let mut expanded = false;
        for i in 0..factors.len() {
            let b = factors[i].0;
            let e = std::mem::replace(&mut factors[i].1, Rational::ZERO);
            if e.is_zero() {
                continue;
            }
            if e.is_integer() && matches!(self.nodes[b as usize], Node::Mul(..)) {
                // A product base whose fractional powers merged to an integer one, e.g.
                // (2x²)^(1/2)·(2x²)^(1/2) = (2x²)^1: products are flat, so expand it exactly
                // (integer power of a product) and merge again. Without this, a·a and a²
                // were different nodes.
                let p = self.pow_rational(b, e);
                match &self.nodes[p as usize] {
                    Node::Invalid(_) => return p,
                    Node::Num(_) | Node::Float(_) => {
                        let v = self.number(p).expect("number");
                        match coef.mul(&v) {
                            Ok(c) => coef = c,
                            Err(err) => return self.invalid(err),
                        }
                    }
                    Node::Mul(..) => {
                        let (c, pairs) = self.mul_parts(p).expect("product");
                        let pairs: Vec<u32> = pairs.to_vec();
                        match coef.mul(&self.number(c).expect("coefficient")) {
                            Ok(c) => coef = c,
                            Err(err) => return self.invalid(err),
                        }
                        for q in pairs.chunks_exact(2) {
                            extra.push((q[0], self.rational_of(q[1]).expect("exp").clone()));
                        }
                    }
                    _ => extra.push((p, Rational::ONE)),
                }
                expanded = true;
                continue;
            }
            if self.is_number(b) && e.is_integer() {
                let v = self.pow_number(b, &e);
                match v {
                    Ok(v) => match coef.mul(&v) {
                        Ok(c) => coef = c,
                        Err(err) => return self.invalid(err),
                    },
                    Err(err) => return self.invalid(err),
                }
                continue;
            }
            factors[kept] = (b, e);
            kept += 1;
        }
        factors.truncate(kept);
        if expanded {
            // The expansion brought new factors (possibly equal to kept ones): merge again.
            factors.append(&mut extra);
            return self.finish_mul(coef, factors);
        }
        // A second pass may have produced adjacent equal bases with opposite signs whose
        // cancellation is allowed: handled above; re-sort for the canonical order.
        factors.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.signum().cmp(&a.1.signum())));
        let kept = factors;
        if kept.is_empty() {
            return self.num(coef);
        }
        if kept.len() == 1 && kept[0].1.is_one() {
            let b = kept[0].0;
            if coef.is_one() {
                return b;
            }
            if matches!(self.nodes[b as usize], Node::Add(..)) {
                // Distribute a numeric coefficient over a sum (canonical sums).
                let mut c0 = Number::Rat(Rational::ZERO);
                let mut terms = std::mem::take(&mut self.terms_buf);
                terms.clear();
                let id = match self.collect_add(b, &coef, &mut c0, &mut terms) {
                    Ok(()) => self.finish_add(c0, &mut terms),
                    Err(e) => self.invalid(e),
                };
                terms.clear();
                self.terms_buf = terms;
                return id;
            }
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(self.num(coef));
        for (b, e) in kept.drain(..) {
            key.push(b);
            let eid = self.rational(e);
            key.push(eid);
        }
        let id = self.intern(Key::Mul(&key));
        self.key_buf = key;
        id
    }

    /// A numeric base to an integer power.
    fn pow_number(&self, b: Id, e: &Rational) -> Result<Number, SymError> {
        let k = e.to_i64().ok_or(SymError::RationalOverflow)?;
        match self.number(b).expect("number") {
            Number::Rat(r) => match r.powi(k) {
                None => Err(SymError::DivisionByZero {
                    context: "0 to a negative power".into(),
                }),
                Some(Err(_)) => Err(SymError::RationalOverflow),
                Some(Ok(v)) => Ok(Number::Rat(v)),
            },
            Number::Float(f) => {
                if f == 0.0 && k < 0 {
                    return Err(SymError::DivisionByZero {
                        context: "0 to a negative power".into(),
                    });
                }
                finite(f.powi(k.clamp(i32::MIN as i64, i32::MAX as i64) as i32))
            }
        }
    }

    // ---------------------------------------------------------------- powers

    /// `base ^ exp`, canonical.
    pub(crate) fn pow(&mut self, base: Id, exp: Id) -> Id {
        if let Some(bad) = self.first_invalid(&[base, exp]) {
            return bad;
        }
        match &self.nodes[exp as usize] {
            Node::Num(r) => {
                let r = r.clone();
                self.pow_rational(base, r)
            }
            Node::Float(f) => {
                let f = *f;
                if let Some(bv) = self.number(base) {
                    let v = bv.to_f64().powf(f);
                    if v.is_finite() {
                        return self.float(v);
                    }
                    return self.invalid(SymError::NotReal {
                        what: format!("{} ^ {f}", bv.to_f64()),
                    });
                }
                self.intern(Key::Pow(base, exp))
            }
            _ => {
                if base == ONE {
                    return ONE;
                }
                self.intern(Key::Pow(base, exp))
            }
        }
    }

    pub(crate) fn pow_rational(&mut self, base: Id, r: Rational) -> Id {
        // Invalid nodes absorb every operation, `x^0` included: without this, `(1/0)^2`
        // became a valid-looking product over an invalid base that `check` did not see.
        if self.invalid_of(base).is_some() {
            return base;
        }
        if r.is_zero() {
            return ONE;
        }
        if r.is_one() {
            return base;
        }
        if base == ZERO && r.is_negative() {
            return self.invalid(SymError::DivisionByZero {
                context: "division by a structural zero".into(),
            });
        }
        // Numeric base.
        if let Some(bv) = self.number(base) {
            if r.is_integer() {
                return match self.pow_number(base, &r) {
                    Ok(v) => self.num(v),
                    Err(e) => self.invalid(e),
                };
            }
            return match bv {
                Number::Float(f) => {
                    let v = match r.as_small() {
                        // An odd root of a negative number is real: (−a)^(p/q) = (−1)^p·a^(p/q)
                        // for odd q (`powf` would give NaN).
                        Some((p, q)) if f < 0.0 && q % 2 == 1 => {
                            let m = (-f).powf(r.to_f64());
                            if p % 2 == 0 { m } else { -m }
                        }
                        _ => f.powf(r.to_f64()),
                    };
                    if v.is_finite() {
                        self.float(v)
                    } else {
                        self.invalid(SymError::NotReal {
                            what: format!("{f} ^ {r}"),
                        })
                    }
                }
                Number::Rat(b) => {
                    let (p, q) = match r.as_small() {
                        Some(pq) => pq,
                        None => return self.invalid(SymError::RationalOverflow),
                    };
                    if b.is_negative() && q % 2 == 0 {
                        return self.invalid(SymError::NotReal {
                            what: format!("({b}) ^ ({r}), an even root of a negative number"),
                        });
                    }
                    if let Some(root) = u32::try_from(q).ok().and_then(|q| b.exact_root(q)) {
                        let rid = self.rational(root);
                        return self.pow_rational(rid, Rational::int(p));
                    }
                    if b.is_negative() {
                        // An odd root of a negative constant is real (the even case was refused
                        // above): (−a)^(p/q) = (−1)^p·a^(p/q). Written with a positive base so
                        // that evaluation (`powf`), the nominal value and the sign analysis
                        // agree with it; a negative base would evaluate to NaN.
                        let pos = self.rational(b.neg());
                        let m = self.pow_rational(pos, r);
                        return if p % 2 == 0 {
                            m
                        } else {
                            self.mul_n(&[MINUS_ONE, m])
                        };
                    }
                    let e = self.rational(r);
                    self.intern(Key::Mul(&[ONE, base, e]))
                }
            };
        }
        let base_sign = self.sign(base);
        if let Some((coef, pairs)) = self.mul_parts(base) {
            let pairs: Vec<u32> = pairs.to_vec();
            if r.is_integer() {
                // (c·Π bᵢ^eᵢ)^n = cⁿ·Π bᵢ^(eᵢn): exact for integer n.
                let mut items = Vec::with_capacity(pairs.len() / 2 + 1);
                let cp = self.pow_rational(coef, r.clone());
                items.push(cp);
                for p in pairs.chunks_exact(2) {
                    let e = self.rational_of(p[1]).expect("exp").clone();
                    let ne = match e.mul(&r) {
                        Ok(v) => v,
                        Err(_) => return self.invalid(SymError::RationalOverflow),
                    };
                    let f = self.factor(p[0], ne);
                    items.push(f);
                }
                return self.mul_n(&items);
            }
            // Non-integer power of a single power: (b^e)^r.
            if pairs.len() == 2 && coef == ONE {
                let (b, e) = (pairs[0], self.rational_of(pairs[1]).expect("exp").clone());
                let er = match e.mul(&r) {
                    Ok(v) => v,
                    Err(_) => return self.invalid(SymError::RationalOverflow),
                };
                if self.sign(b).is_nonneg() {
                    return self.factor(b, er);
                }
                if e.is_integer() && e.to_i64().is_some_and(|k| k % 2 == 0) {
                    // (b^(2k))^r = |b|^(2k·r) for real b.
                    let ab = self.func(Func::Abs, b);
                    return self.pow_rational(ab, er);
                }
            }
            // (c·Π)^r with every factor non-negative splits.
            if base_sign.is_nonneg()
                && self.number(coef).is_some_and(|c| !c.is_negative())
                && pairs.chunks_exact(2).all(|p| self.sign(p[0]).is_nonneg())
            {
                let mut items = Vec::with_capacity(pairs.len() / 2 + 1);
                let cp = self.pow_rational(coef, r.clone());
                items.push(cp);
                for p in pairs.chunks_exact(2) {
                    let e = self.rational_of(p[1]).expect("exp").clone();
                    let ne = match e.mul(&r) {
                        Ok(v) => v,
                        Err(_) => return self.invalid(SymError::RationalOverflow),
                    };
                    let f = self.factor(p[0], ne);
                    items.push(f);
                }
                return self.mul_n(&items);
            }
        }
        self.factor(base, r)
    }

    /// `b^e` as a one-factor product (no further simplification of `b`).
    fn factor(&mut self, b: Id, e: Rational) -> Id {
        if e.is_zero() {
            return ONE;
        }
        if e.is_one() {
            return b;
        }
        if self.is_number(b) || matches!(self.nodes[b as usize], Node::Mul(..)) {
            // Numbers and products must go through the general rules.
            if self.is_number(b) || e.is_integer() {
                return self.pow_rational(b, e);
            }
        }
        if e.is_integer() {
            // Same canonical form as `finish_mul`: `(2a − 2b)^n = 2ⁿ·(a − b)^n`.
            if let Some((q, s)) = self.primitive_sum(b) {
                let qk = match e.to_i64().and_then(|k| q.powi(k)) {
                    Some(Ok(v)) => v,
                    _ => return self.invalid(SymError::RationalOverflow),
                };
                let mut f = vec![(s, e)];
                return self.finish_mul(Number::Rat(qk), &mut f);
            }
        }
        let eid = self.rational(e);
        self.intern(Key::Mul(&[ONE, b, eid]))
    }

    // ---------------------------------------------------------------- functions

    /// `f(a)`, canonical.
    pub(crate) fn func(&mut self, f: Func, a: Id) -> Id {
        if self.invalid_of(a).is_some() {
            return a;
        }
        // Exact numeric folding.
        if let Some(r) = self.rational_of(a).cloned() {
            match (f, r.is_zero(), r.is_one()) {
                (Func::Sin | Func::Tan, true, _) => return ZERO,
                (Func::Cos | Func::Exp, true, _) => return ONE,
                (Func::Ln, _, true) => return ZERO,
                (Func::Abs, _, _) => return self.rational(r.abs()),
                (Func::Ln, true, _) => {
                    return self.invalid(SymError::NotReal {
                        what: "ln(0)".into(),
                    });
                }
                (Func::Ln, _, _) if r.is_negative() => {
                    return self.invalid(SymError::NotReal {
                        what: format!("ln({r})"),
                    });
                }
                _ => {}
            }
        }
        if let Node::Float(x) = self.nodes[a as usize] {
            let v = f.eval_f64(x);
            if v.is_finite() {
                return self.float(v);
            }
            return self.invalid(SymError::NotReal {
                what: format!("{}({x})", f.name()),
            });
        }
        // Multiples of π.
        if let Some(k) = self.pi_multiple(a)
            && let Some(v) = exact_trig(f, &k)
        {
            return self.rational(v);
        }
        // Odd and even functions of a negated argument.
        if let Some(pos) = self.negated(a) {
            match f {
                Func::Cos | Func::Abs => return self.func(f, pos),
                Func::Sin | Func::Tan => {
                    let v = self.func(f, pos);
                    return self.mul_n(&[MINUS_ONE, v]);
                }
                _ => {}
            }
        }
        match f {
            Func::Abs => {
                let s = self.sign(a);
                if s.is_nonneg() {
                    return a;
                }
                if s.is_nonpos() {
                    return self.mul_n(&[MINUS_ONE, a]);
                }
            }
            Func::Exp => {
                if let Node::Func(Func::Ln, x) = self.nodes[a as usize] {
                    return x;
                }
            }
            Func::Ln => {
                if let Node::Func(Func::Exp, x) = self.nodes[a as usize] {
                    return x;
                }
            }
            _ => {}
        }
        self.intern(Key::Func(f, a))
    }

    /// If `a = k·π` with rational `k`, return `k`.
    fn pi_multiple(&self, a: Id) -> Option<Rational> {
        match &self.nodes[a as usize] {
            Node::Const(Constant::Pi) => Some(Rational::ONE),
            Node::Mul(..) => {
                let (c, pairs) = self.mul_parts(a)?;
                if pairs.len() == 2
                    && pairs[1] == ONE
                    && matches!(self.nodes[pairs[0] as usize], Node::Const(Constant::Pi))
                {
                    self.rational_of(c).cloned()
                } else {
                    None
                }
            }
            _ => None,
        }
    }

    /// If `a` is written with a negative numeric coefficient, return `−a` (cheaply).
    fn negated(&mut self, a: Id) -> Option<Id> {
        let (c, _) = self.mul_parts(a)?;
        let cv = self.number(c)?;
        if cv.is_negative() {
            Some(self.mul_n(&[MINUS_ONE, a]))
        } else {
            None
        }
    }

    /// `atan2(y, x)`.
    pub(crate) fn atan2(&mut self, y: Id, x: Id) -> Id {
        if let Some(bad) = self.first_invalid(&[y, x]) {
            return bad;
        }
        if y == ZERO && self.sign(x).is_positive() {
            return ZERO;
        }
        if let (Node::Float(a), Node::Float(b)) = (&self.nodes[y as usize], &self.nodes[x as usize])
        {
            let v = a.atan2(*b);
            return self.float(v);
        }
        self.intern(Key::Atan2(y, x))
    }
}

/// Exact values of trigonometric functions at rational multiples `k` of π (only the cases that
/// are rational: multiples of π/2 for sin and cos, of π for tan).
fn exact_trig(f: Func, k: &Rational) -> Option<Rational> {
    let (n, d) = k.as_small()?;
    match (f, d) {
        (Func::Sin, 1) | (Func::Tan, 1) => Some(Rational::ZERO),
        (Func::Cos, 1) => Some(if n.rem_euclid(2) == 0 {
            Rational::ONE
        } else {
            Rational::MINUS_ONE
        }),
        (Func::Sin, 2) => Some(if n.rem_euclid(4) == 1 {
            Rational::ONE
        } else {
            Rational::MINUS_ONE
        }),
        (Func::Cos, 2) => Some(Rational::ZERO),
        _ => None,
    }
}

/// Integers and dyadic fractions with a denominator up to 2^20 are exact rationals.
pub(crate) fn dyadic(x: f64) -> Option<Rational> {
    // Every integer-valued double below 2^63 is an exact `i64` (the scaled test below alone
    // left integers above ~8.6e9, such as 1e10, as floats).
    if x.fract() == 0.0 && x.abs() < 9_223_372_036_854_775_808.0 {
        return Some(Rational::int(x as i64));
    }
    let scaled = x * (1u64 << 20) as f64;
    if scaled.fract() == 0.0 && scaled.abs() < 9.0e15 {
        Rational::new(scaled as i64, 1 << 20)
    } else {
        None
    }
}

pub(crate) fn pow_f64(x: f64, e: &Rational) -> f64 {
    match e.as_small() {
        Some((n, 1)) if n.unsigned_abs() <= i32::MAX as u64 => x.powi(n as i32),
        Some((1, 2)) => x.sqrt(),
        Some((-1, 2)) => 1.0 / x.sqrt(),
        _ => x.powf(e.to_f64()),
    }
}

fn pow_sign(s: Sign, e: &Rational) -> Sign {
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
    fn from_rational(r: &Rational) -> Sign {
        match r.signum() {
            1 => Sign::POSITIVE,
            -1 => Sign::NEGATIVE,
            _ => Sign::ZERO_ONLY,
        }
    }
    fn max_nonempty(self, fallback: Sign) -> Sign {
        if self.0 == 0 { fallback } else { self }
    }
}
