//! Evaluation: a compiled [`Tape`] for fast repeated `f64` evaluation, and
//! [`eval_generic`] for evaluation in any [`Elementary`] scalar (double-double references,
//! substitution of expressions).
//!
//! A tape is the DAG of a set of roots lowered to a register program of unary and binary
//! instructions over one `f64` work buffer, which holds the parameters, then the constants,
//! then one slot per instruction; every instruction reads earlier slots only. N-ary sums and
//! products are split into binary operations in the order of the recursive evaluator
//! ([`eval_generic`]): `((c₀ + c₁x₁) + c₂x₂) + …` and `((c·f₁)·f₂)·…`, integer powers by
//! the squarings and products `powi` performs, so the tape computes the same values bit for
//! bit. Identical instructions (the same operation on the same slots) are emitted once: a
//! sum that extends another sum term by term in the same order, the `x²` of several
//! products, reuse them, which recovers part of the sharing that canonical flattening hides
//! (`(x+y+z)+w` is a new 4-term sum that does not mention `x+y+z`);
//! [`Tape::new_reassociating`] recovers more by reassociating.
//!
//! The instructions are then scheduled into runs of one operation, each run a
//! tight loop: interpreting instruction by instruction would cost a mispredicted indirect
//! branch on almost every instruction, more than the arithmetic. Evaluation allocates
//! nothing; the work buffer is the caller's ([`Tape::eval_into`]) or kept in a
//! [`TapeWorkspace`].
//!
//! [`NativeTape`] translates a tape to machine code (x86-64 Unix) with the same results bit
//! for bit, about twice as fast; the interpreter remains for other platforms and for tapes
//! evaluated too few times to repay the translation (about 0.25 µs per instruction).

use crate::context::with_serial;
use crate::error::SymError;
use crate::expr::{Expr, reachable};
use crate::pool::{Func, Id, Node, Shape, ShapeBuf};
use crate::rational::Rational;
use crate::scalar::Elementary;
use hashbrown::{HashMap, HashSet};

mod native;
pub use native::NativeTape;

/// The operation of one instruction, on the values of slots `a`, `b` (and `c`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
enum Code {
    /// `a + b`
    Add,
    /// `a − b`
    Sub,
    /// `a + c·b` (a term with a coefficient)
    AddMul,
    /// `a·b`
    Mul,
    /// `a · (1/b)`
    MulRecip,
    /// `1/a`
    Recip,
    /// `−a`
    Neg,
    /// `a²`
    Sq,
    /// `a³` as `a·a·a`
    Cube,
    /// `√a`
    Sqrt,
    /// `aⁿ` by `powi`, `n` (an `i32`) in the `c` field
    Powi,
    /// `a^b` by `powf`
    Pow,
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Abs,
    /// `atan2(a, b)`
    Atan2,
}

/// One instruction. Unary operations have `b == a`; `c` is a slot only for
/// [`Code::AddMul`] (else 0 or the exponent of [`Code::Powi`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Ins {
    code: Code,
    a: u32,
    b: u32,
    c: u32,
}

/// A compiled evaluation program for a set of root expressions.
#[derive(Clone, Debug)]
pub struct Tape {
    params: Vec<u32>,
    param_names: Vec<String>,
    /// Values of the constant slots (after the parameters).
    consts: Vec<f64>,
    /// The program: runs of one operation over consecutive entries of `args`.
    blocks: Vec<Block>,
    args: Vec<Args>,
    outputs: Vec<u32>,
    /// Unique nodes of the DAG compiled (for reporting).
    nodes: usize,
    /// The instructions (positions in `args`) in the order they were compiled, operands
    /// right before their uses: the order [`NativeTape`] emits them in.
    compile_order: Vec<u32>,
}

/// Reusable work buffer for [`Tape::eval`].
#[derive(Clone, Debug, Default)]
pub struct TapeWorkspace {
    work: Vec<f64>,
    /// Structure-of-arrays buffer of [`Tape::eval_batch`]: one slot holds `LANES` points.
    lanes: Vec<[f64; LANES]>,
}

/// Points evaluated together by [`Tape::eval_batch`]: the interpreter's own work (operand
/// indices, block loops) is paid once per chunk, and the arithmetic on contiguous lanes
/// vectorises. (Measured on a 10 000-node DAG: 16 beats 4 and 8; 32 is no better.)
const LANES: usize = 16;

/// What the interpreter computes on: one point (`f64`) or a chunk of points
/// (`[f64; LANES]`), with the same operations per point, so that batch results equal
/// point-by-point ones bit for bit.
trait Lane: Copy {
    fn splat(x: f64) -> Self;
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
    fn zip(self, y: Self, f: impl Fn(f64, f64) -> f64) -> Self;
    fn zip3(self, y: Self, z: Self, f: impl Fn(f64, f64, f64) -> f64) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip(self, y: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        f(self, y)
    }
    #[inline(always)]
    fn zip3(self, y: Self, z: Self, f: impl Fn(f64, f64, f64) -> f64) -> Self {
        f(self, y, z)
    }
}

impl Lane for [f64; LANES] {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        [x; LANES]
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        std::array::from_fn(|l| f(self[l]))
    }
    #[inline(always)]
    fn zip(self, y: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        std::array::from_fn(|l| f(self[l], y[l]))
    }
    #[inline(always)]
    fn zip3(self, y: Self, z: Self, f: impl Fn(f64, f64, f64) -> f64) -> Self {
        std::array::from_fn(|l| f(self[l], y[l], z[l]))
    }
}

/// Operands of one instruction of a [`Block`]: slots `a`, `b` (binary operations), `c`
/// ([`Code::AddMul`]; the exponent of [`Code::Powi`]).
#[derive(Clone, Copy, Debug)]
struct Args {
    a: u32,
    b: u32,
    c: u32,
}

/// A run of instructions with the same operation. Interpreting instruction by instruction
/// costs a mispredicted indirect branch almost every time (the operations of a DAG come in
/// no regular order); the tape is scheduled so that operations of one kind are consecutive
/// where dependencies allow, and each run is a tight loop.
#[derive(Clone, Copy, Debug)]
struct Block {
    code: Code,
    len: u32,
}

/// `w[out + k] = f(w[a], w[b])` for the instructions `k` of a block.
///
/// # Safety
/// Every slot read and written is in bounds (see [`exec`]).
#[inline(always)]
unsafe fn binary<T: Lane>(args: &[Args], w: &mut [T], out: usize, f: impl Fn(T, T) -> T) {
    for (k, g) in args.iter().enumerate() {
        // SAFETY: the caller's contract.
        unsafe {
            let v = f(
                *w.get_unchecked(g.a as usize),
                *w.get_unchecked(g.b as usize),
            );
            *w.get_unchecked_mut(out + k) = v;
        }
    }
}

/// `w[out + k] = f(w[a])`.
///
/// # Safety
/// As [`binary`].
#[inline(always)]
unsafe fn unary<T: Lane>(args: &[Args], w: &mut [T], out: usize, f: impl Fn(f64) -> f64) {
    for (k, g) in args.iter().enumerate() {
        // SAFETY: the caller's contract.
        unsafe {
            let v = w.get_unchecked(g.a as usize).map(&f);
            *w.get_unchecked_mut(out + k) = v;
        }
    }
}

/// Run the program on `w`, whose first `base` slots hold the parameters and constants;
/// instruction `i` (counted over all blocks) writes slot `base + i`.
///
/// # Safety
/// `w.len() >= base + args.len()`, the blocks' lengths sum to `args.len()`, and every slot
/// an instruction reads is below its own; [`Tape::new`] checks the latter two once for all.
/// (Unchecked indexing removes two or three bounds checks per instruction from the hottest
/// loop.)
#[inline(always)]
unsafe fn exec<T: Lane>(blocks: &[Block], args: &[Args], w: &mut [T], base: usize) {
    let mut start = 0;
    for blk in blocks {
        let end = start + blk.len as usize;
        // SAFETY: the contract above.
        unsafe {
            let g = args.get_unchecked(start..end);
            let out = base + start;
            match blk.code {
                Code::Add => binary(g, w, out, |x, y| x.zip(y, |a, b| a + b)),
                Code::Sub => binary(g, w, out, |x, y| x.zip(y, |a, b| a - b)),
                Code::AddMul => {
                    for (k, g) in g.iter().enumerate() {
                        let (x, y, c) = (
                            *w.get_unchecked(g.a as usize),
                            *w.get_unchecked(g.b as usize),
                            *w.get_unchecked(g.c as usize),
                        );
                        *w.get_unchecked_mut(out + k) = x.zip3(y, c, |a, b, c| a + c * b);
                    }
                }
                Code::Mul => binary(g, w, out, |x, y| x.zip(y, |a, b| a * b)),
                Code::MulRecip => binary(g, w, out, |x, y| x.zip(y, |a, b| a * (1.0 / b))),
                Code::Recip => unary(g, w, out, |a| 1.0 / a),
                Code::Neg => unary(g, w, out, |a| -a),
                Code::Sq => unary(g, w, out, |a| a * a),
                Code::Cube => unary(g, w, out, |a| a * a * a),
                Code::Sqrt => unary(g, w, out, f64::sqrt),
                Code::Powi => {
                    for (k, g) in g.iter().enumerate() {
                        let n = g.c as i32;
                        *w.get_unchecked_mut(out + k) =
                            w.get_unchecked(g.a as usize).map(|a| a.powi(n));
                    }
                }
                Code::Pow => binary(g, w, out, |x, y| x.zip(y, f64::powf)),
                Code::Sin => unary(g, w, out, crate::trig::sin),
                Code::Cos => unary(g, w, out, crate::trig::cos),
                Code::Tan => unary(g, w, out, f64::tan),
                Code::Exp => unary(g, w, out, f64::exp),
                Code::Ln => unary(g, w, out, f64::ln),
                Code::Abs => unary(g, w, out, f64::abs),
                Code::Atan2 => binary(g, w, out, |x, y| x.zip(y, f64::atan2)),
            }
        }
        start = end;
    }
}

/// Operand references while compiling: the slot layout (parameters, constants, instructions)
/// is known only at the end, so references carry their kind in the top bits.
const REF_INS: u32 = 0;
const REF_PARAM: u32 = 1 << 30;
const REF_CONST: u32 = 2 << 30;
const REF_MASK: u32 = 3 << 30;

/// A sum or product the tape computes, as a candidate for sharing.
struct Shared {
    /// Its value.
    at: u32,
    /// The constant term (sums) or the coefficient (products).
    c: f64,
    /// Its entries in `Builder::items`.
    start: u32,
    len: u32,
}

/// Sums or products indexed by their terms (factors), so that the ones contained in a new
/// node are found by counting: a candidate is contained when every one of its entries is hit.
#[derive(Default)]
struct ShareIndex {
    shared: Vec<Shared>,
    /// Entries of all candidates: `(term, key)`; the key is the coefficient of a term (sums) or
    /// the exponent node of a factor (products, compared exactly, as bits).
    items: Vec<(u32, u64)>,
    /// Term → candidates containing it, with the key of the term there.
    by_term: HashMap<u32, Vec<(u32, u64)>>,
    /// Per-candidate scratch of one lookup: stamp, hits, ratio, still possible.
    stamp: Vec<u32>,
    hits: Vec<u32>,
    ratio: Vec<f64>,
    ok: Vec<bool>,
    now: u32,
}

/// Index entries looked at per term of a lookup: bounds the compile time when a term (a
/// parameter, typically) occurs in thousands of sums; the most recent ones are the likeliest
/// subsets.
const SHARE_SCAN: usize = 256;

impl ShareIndex {
    fn insert(&mut self, at: u32, c: f64, items: &[(u32, u64)]) {
        let k = self.shared.len() as u32;
        self.shared.push(Shared {
            at,
            c,
            start: self.items.len() as u32,
            len: items.len() as u32,
        });
        self.items.extend_from_slice(items);
        for &(t, key) in items {
            self.by_term.entry(t).or_default().push((k, key));
        }
        self.stamp.push(0);
        self.hits.push(0);
        self.ratio.push(0.0);
        self.ok.push(false);
    }

    /// Candidates contained in `items` (sorted, distinct terms) with their ratio, largest
    /// first. `ratio(key of the node, key of the candidate)` is the multiplier that maps the
    /// candidate's entry to the node's, if one is allowed; all entries must agree on it.
    fn contained(
        &mut self,
        items: &[(u32, u64)],
        ratio: impl Fn(u64, u64) -> Option<f64>,
    ) -> Vec<(u32, f64)> {
        self.now += 1;
        let now = self.now;
        let mut touched = Vec::new();
        for &(t, key) in items {
            let Some(list) = self.by_term.get(&t) else {
                continue;
            };
            for &(k, ck) in list.iter().rev().take(SHARE_SCAN) {
                let ku = k as usize;
                if self.shared[ku].len as usize > items.len() {
                    continue;
                }
                let r = ratio(key, ck);
                if self.stamp[ku] != now {
                    self.stamp[ku] = now;
                    self.hits[ku] = 1;
                    self.ratio[ku] = r.unwrap_or(f64::NAN);
                    self.ok[ku] = r.is_some();
                    touched.push(k);
                } else {
                    self.hits[ku] += 1;
                    if r != Some(self.ratio[ku]) {
                        self.ok[ku] = false;
                    }
                }
            }
        }
        let mut found: Vec<(u32, f64)> = touched
            .into_iter()
            .filter(|&k| {
                let ku = k as usize;
                self.ok[ku] && self.hits[ku] == self.shared[ku].len && self.hits[ku] >= 2
            })
            .map(|k| (k, self.ratio[k as usize]))
            .collect();
        // Largest first, then a plain copy (ratio 1) before a scaled one, then oldest.
        found.sort_by_key(|&(k, r)| (std::cmp::Reverse(self.shared[k as usize].len), r != 1.0, k));
        found
    }

    fn entries(&self, k: u32) -> &[(u32, u64)] {
        let s = &self.shared[k as usize];
        &self.items[s.start as usize..(s.start + s.len) as usize]
    }
}

/// Is `x` ±2ᵏ (a multiplier that rounds nothing)?
fn is_power_of_two(x: f64) -> bool {
    x.is_normal() && x.to_bits() & ((1u64 << 52) - 1) == 0
}

/// Compile-time state of [`Tape::new`].
struct Builder {
    consts: Vec<f64>,
    const_at: HashMap<u64, u32>,
    code: Vec<Ins>,
    /// Instruction → its reference, for common subexpressions.
    cse: HashMap<Ins, u32>,
    /// Reassociating sharing ([`Tape::new_reassociating`]), with its indexes.
    share: bool,
    sums: ShareIndex,
    prods: ShareIndex,
}

impl Builder {
    fn konst(&mut self, x: f64) -> u32 {
        let n = self.consts.len() as u32;
        let k = *self.const_at.entry(x.to_bits()).or_insert(n);
        if k == n {
            self.consts.push(x);
        }
        REF_CONST | k
    }

    fn emit(&mut self, code: Code, a: u32, b: u32, c: u32) -> u32 {
        // Commutative operands in a fixed order, so that `x·y` and `y·x` are one instruction.
        let (a, b) = match code {
            Code::Add | Code::Mul if b < a => (b, a),
            _ => (a, b),
        };
        let ins = Ins { code, a, b, c };
        let n = self.code.len() as u32;
        let r = *self.cse.entry(ins).or_insert(REF_INS | n);
        if r == n {
            self.code.push(ins);
        }
        r
    }

    fn unary(&mut self, code: Code, a: u32) -> u32 {
        self.emit(code, a, a, 0)
    }

    /// `c₀ + Σ cᵢ·xᵢ`, accumulated in term order as `((c₀ + c₁x₁) + c₂x₂) + …`.
    fn lin(&mut self, c0: f64, terms: &[(u32, f64)]) -> u32 {
        let (&(x, c), rest) = terms.split_first().expect("a sum has terms");
        let mut acc = if c0 == 0.0 {
            // `0 + c·x` is `c·x` (up to the sign of a zero).
            if c == 1.0 {
                x
            } else if c == -1.0 {
                self.unary(Code::Neg, x)
            } else {
                let k = self.konst(c);
                self.emit(Code::Mul, x, k, 0)
            }
        } else {
            let k0 = self.konst(c0);
            self.add_term(k0, x, c)
        };
        for &(x, c) in rest {
            acc = self.add_term(acc, x, c);
        }
        acc
    }

    /// A sum with sharing: sums the tape computes whose terms are all among ours (with our
    /// coefficients times a power of two) first, then the remaining terms.
    fn shared_sum(&mut self, c0: f64, terms: &[(u32, f64)]) -> u32 {
        let items: Vec<(u32, u64)> = terms.iter().map(|&(t, c)| (t, c.to_bits())).collect();
        let found = self.sums.contained(&items, |s, a| {
            let (s, a) = (f64::from_bits(s), f64::from_bits(a));
            let r = s / a;
            (is_power_of_two(r) && a * r == s).then_some(r)
        });
        let mut pieces = Vec::new();
        let mut covered: HashSet<u32> = HashSet::new();
        let mut c0_left = c0;
        for (k, ratio) in found {
            let sh = &self.sums.shared[k as usize];
            let (sat, sc) = (sh.at, sh.c);
            // A candidate's constant must be all of what is left of ours.
            if sc != 0.0 && sc * ratio != c0_left {
                continue;
            }
            let entries = self.sums.entries(k);
            if entries.iter().any(|e| covered.contains(&e.0)) {
                continue;
            }
            covered.extend(entries.iter().map(|e| e.0));
            if sc != 0.0 {
                c0_left = 0.0;
            }
            pieces.push((sat, ratio));
        }
        pieces.extend(terms.iter().filter(|t| !covered.contains(&t.0)));
        let r = self.lin(c0_left, &pieces);
        self.sums.insert(r, c0, &items);
        r
    }

    /// The start of a product with sharing: products the tape computes whose factors are all
    /// among ours, with coefficient 1 or ours (so no rounding is added); returns the
    /// accumulator and the factors covered.
    fn shared_factors(&mut self, coef: f64, factors: &[(u32, Id)]) -> (Acc, HashSet<u32>) {
        let items: Vec<(u32, u64)> = factors.iter().map(|&(x, e)| (x, u64::from(e))).collect();
        let found = self.prods.contained(&items, |s, a| (s == a).then_some(1.0));
        let mut covered: HashSet<u32> = HashSet::new();
        let mut coef_left = coef;
        let mut parts = Vec::new();
        for (k, _) in found {
            let sh = &self.prods.shared[k as usize];
            let (sat, sc) = (sh.at, sh.c);
            if sc != 1.0 && sc != coef_left {
                continue;
            }
            let entries = self.prods.entries(k);
            if entries.iter().any(|e| covered.contains(&e.0)) {
                continue;
            }
            covered.extend(entries.iter().map(|e| e.0));
            if sc != 1.0 {
                coef_left = 1.0;
            }
            parts.push(sat);
        }
        let mut acc = Acc::Coef(coef_left);
        for x in parts {
            acc = self.times(acc, x);
        }
        (acc, covered)
    }

    /// `acc + c·x` (`c·x` is exact for `c = ±1`).
    fn add_term(&mut self, acc: u32, x: u32, c: f64) -> u32 {
        if c == 1.0 {
            self.emit(Code::Add, acc, x, 0)
        } else if c == -1.0 {
            self.emit(Code::Sub, acc, x, 0)
        } else {
            let k = self.konst(c);
            self.emit(Code::AddMul, acc, x, k)
        }
    }

    /// `acc · f` for the next factor `f` of a product (`coef · f₁ · f₂ · …` in factor order).
    fn times(&mut self, acc: Acc, f: u32) -> Acc {
        Acc::Value(match acc {
            Acc::Coef(1.0) => f,
            Acc::Coef(-1.0) => self.unary(Code::Neg, f),
            Acc::Coef(c) => {
                let k = self.konst(c);
                self.emit(Code::Mul, k, f, 0)
            }
            Acc::Value(a) => self.emit(Code::Mul, a, f, 0),
        })
    }

    /// `acc · (1/d)`: the rounding of the recursive evaluator (`d⁻¹` then a product).
    fn times_recip(&mut self, acc: Acc, d: u32) -> Acc {
        Acc::Value(match acc {
            Acc::Coef(1.0) => self.unary(Code::Recip, d),
            Acc::Coef(c) => {
                let k = self.konst(c);
                self.emit(Code::MulRecip, k, d, 0)
            }
            Acc::Value(a) => self.emit(Code::MulRecip, a, d, 0),
        })
    }

    /// `xⁿ` for `n ≥ 1`, with the operations of `f64::powi` (binary powering from the low
    /// bit: `r·a` where the bit is set, `a²` between), so results equal `powi`'s bit for bit
    /// and shared partial powers (`x²` of `x⁴` and `x⁶`) are computed once.
    fn int_power(&mut self, x: u32, n: u64) -> u32 {
        let (mut r, mut a, mut n) = (None, x, n);
        loop {
            if n & 1 == 1 {
                r = Some(match r {
                    None => a,
                    Some(r) => self.emit(Code::Mul, r, a, 0),
                });
            }
            n >>= 1;
            if n == 0 {
                break;
            }
            a = self.unary(Code::Sq, a);
        }
        r.expect("n ≥ 1")
    }

    /// `acc · xᵉ`.
    fn factor(&mut self, acc: Acc, x: u32, e: &Rational) -> Acc {
        match e.as_small() {
            Some((1, 1)) => self.times(acc, x),
            Some((-1, 1)) => self.times_recip(acc, x),
            // `x·x·x`, not powi's `x·(x·x)`: the rounding of the previous tape.
            Some((3, 1)) => {
                let f = self.unary(Code::Cube, x);
                self.times(acc, f)
            }
            Some((-2, 1)) => {
                let f = self.unary(Code::Sq, x);
                self.times_recip(acc, f)
            }
            Some((n, 1)) if n > 0 && n <= POWI_UNROLL => {
                let f = self.int_power(x, n as u64);
                self.times(acc, f)
            }
            Some((n, 1)) if n < 0 && -n <= POWI_UNROLL => {
                // powi's reciprocal of the positive power, then the product.
                let f = self.int_power(x, n.unsigned_abs());
                let f = self.unary(Code::Recip, f);
                self.times(acc, f)
            }
            Some((n, 1)) if n.unsigned_abs() < i32::MAX as u64 => {
                let f = self.emit(Code::Powi, x, x, n as i32 as u32);
                self.times(acc, f)
            }
            Some((1, 2)) => {
                let f = self.unary(Code::Sqrt, x);
                self.times(acc, f)
            }
            Some((-1, 2)) => {
                let f = self.unary(Code::Sqrt, x);
                self.times_recip(acc, f)
            }
            _ => {
                let k = self.konst(e.to_f64());
                let f = self.emit(Code::Pow, x, k, 0);
                self.times(acc, f)
            }
        }
    }

    /// The value of a finished product.
    fn value(&mut self, acc: Acc) -> u32 {
        match acc {
            Acc::Value(v) => v,
            // (A product has factors; kept total for safety.)
            Acc::Coef(c) => self.konst(c),
        }
    }
}

/// A product being accumulated: still only its coefficient, or a slot.
#[derive(Clone, Copy)]
enum Acc {
    Coef(f64),
    Value(u32),
}

/// A topological order of `code` (indices) that groups equal operations into runs, and the
/// runs: list scheduling that continues with the current operation while one is ready and
/// otherwise switches to the operation with the most ready instructions.
fn schedule(code: &[Ins]) -> (Vec<u32>, Vec<Block>) {
    let n = code.len();
    let deps = |ins: &Ins| {
        let c = if ins.code == Code::AddMul {
            ins.c
        } else {
            ins.b
        };
        [ins.a, ins.b, c]
    };
    // Successors in compressed rows; `pending[i]` counts unfinished predecessors.
    let mut pending = vec![0u32; n];
    let mut count = vec![0u32; n + 1];
    for ins in code {
        let mut d = deps(ins);
        d.sort_unstable();
        for (j, &r) in d.iter().enumerate() {
            if r & REF_MASK == REF_INS && (j == 0 || d[j - 1] != r) {
                count[r as usize + 1] += 1;
            }
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let mut succ = vec![0u32; count[n] as usize];
    let mut fill = count.clone();
    for (i, ins) in code.iter().enumerate() {
        let mut d = deps(ins);
        d.sort_unstable();
        for (j, &r) in d.iter().enumerate() {
            if r & REF_MASK == REF_INS && (j == 0 || d[j - 1] != r) {
                succ[fill[r as usize] as usize] = i as u32;
                fill[r as usize] += 1;
                pending[i] += 1;
            }
        }
    }
    const CODES: usize = Code::Atan2 as usize + 1;
    let mut ready: Vec<std::collections::VecDeque<u32>> = vec![Default::default(); CODES];
    for (i, ins) in code.iter().enumerate() {
        if pending[i] == 0 {
            ready[ins.code as usize].push_back(i as u32);
        }
    }
    let mut order = Vec::with_capacity(n);
    let mut blocks: Vec<Block> = Vec::new();
    while order.len() < n {
        let cur = (0..CODES)
            .max_by_key(|&c| ready[c].len())
            .expect("operations");

        let start = order.len();
        // Last in, first out: a chain (the partial sums of one sum) stays together.
        while let Some(i) = ready[cur].pop_front() {
            order.push(i);
            for &s in &succ[count[i as usize] as usize..count[i as usize + 1] as usize] {
                pending[s as usize] -= 1;
                if pending[s as usize] == 0 {
                    ready[code[s as usize].code as usize].push_back(s);
                }
            }
        }
        blocks.push(Block {
            code: code[order[start] as usize].code,
            len: (order.len() - start) as u32,
        });
    }
    (order, blocks)
}

/// Integer powers up to this are unrolled into squarings and products (as `powi` computes
/// them); larger ones call `powi`.
const POWI_UNROLL: i64 = 64;

impl Tape {
    /// Compile `roots` for evaluation with parameter values supplied in the order of `params`
    /// (which must be parameter expressions). A root that depends on a parameter not in
    /// `params` is an error naming it; so is an invalid root. The tape computes exactly the
    /// values of [`eval_generic`]`::<f64>`.
    pub fn new(roots: &[Expr], params: &[Expr]) -> Result<Tape, SymError> {
        Tape::compile(roots, params, false)
    }

    /// [`Tape::new`] with sharing that reassociates: a sum (product) whose terms (factors)
    /// include all those of a sum (product) the tape already computes starts from that value,
    /// e.g. `x+y+z+w` as `(x+y+z) + w` when `x+y+z` is a node; a sum may use another times a
    /// power of two (exact), a product another with coefficient 1 or its own (no rounding
    /// added). This removes operations that canonical flattening duplicates (about a third
    /// of them on a random 10 000-node DAG; a few percent on the models), at the price of
    /// values that differ from [`eval_generic`]'s in the rounding of sums and products
    /// (within the same error bounds; on an ill-conditioned DAG the difference can be large)
    /// and a slower compilation (a lookup in an index of the sums and products per node).
    pub fn new_reassociating(roots: &[Expr], params: &[Expr]) -> Result<Tape, SymError> {
        Tape::compile(roots, params, true)
    }

    fn compile(roots: &[Expr], params: &[Expr], share: bool) -> Result<Tape, SymError> {
        let mut param_slot: HashMap<u32, u32> = HashMap::new();
        let mut param_index = Vec::with_capacity(params.len());
        let mut param_names = Vec::with_capacity(params.len());
        for (k, p) in params.iter().enumerate() {
            let info = p.param_info().ok_or_else(|| {
                SymError::Dimension(format!("tape parameter {k} (`{p}`) is not a parameter"))
            })?;
            let idx = p.param_index().expect("parameter");
            param_slot.insert(idx, k as u32);
            param_index.push(idx);
            param_names.push(info.name);
        }
        for r in roots {
            r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
        }
        let reach = reachable(roots);
        let ids = &reach.ids;
        let mut b = Builder {
            consts: Vec::new(),
            const_at: HashMap::new(),
            code: Vec::with_capacity(ids.len()),
            cse: HashMap::with_capacity(ids.len()),
            share,
            sums: ShareIndex::default(),
            prods: ShareIndex::default(),
        };
        let outputs = with_serial(reach.serial, |p| {
            // Node → reference; numbers get a constant slot only when an operation reads them
            // (most are coefficients and exponents, folded into the instructions).
            let mut at: HashMap<Id, u32> = HashMap::with_capacity(ids.len());
            let mut number: HashMap<Id, f64> = HashMap::new();
            let operand = |b: &mut Builder, at: &HashMap<Id, u32>, id: Id| match at.get(&id) {
                Some(&r) => r,
                None => {
                    let x = p.nominal(id);
                    b.konst(x)
                }
            };
            for &id in ids {
                let r = match p.node(id) {
                    Node::Num(r) => {
                        number.insert(id, r.to_f64());
                        continue;
                    }
                    Node::Float(f) => {
                        number.insert(id, *f);
                        continue;
                    }
                    Node::Const(c) => b.konst(c.to_f64()),
                    Node::Param(i) => match param_slot.get(i) {
                        Some(&k) => REF_PARAM | k,
                        None => {
                            return Err(SymError::MissingParameter {
                                name: p.param(*i).name.clone(),
                            });
                        }
                    },
                    Node::Add(..) => {
                        let (c0, pairs) = p.add_parts(id).expect("sum");
                        let terms: Vec<(u32, f64)> = pairs
                            .chunks_exact(2)
                            .map(|t| (at[&t[0]], p.number(t[1]).expect("coefficient").to_f64()))
                            .collect();
                        if b.share {
                            b.shared_sum(p.nominal(c0), &terms)
                        } else {
                            b.lin(p.nominal(c0), &terms)
                        }
                    }
                    Node::Mul(..) => {
                        let (c, pairs) = p.mul_parts(id).expect("product");
                        let factors: Vec<(u32, Id)> = pairs
                            .chunks_exact(2)
                            .map(|t| (operand(&mut b, &at, t[0]), t[1]))
                            .collect();
                        let coef = p.nominal(c);
                        let (mut acc, skip) = if b.share {
                            b.shared_factors(coef, &factors)
                        } else {
                            (Acc::Coef(coef), HashSet::new())
                        };
                        for &(x, e) in &factors {
                            if !skip.contains(&x) {
                                let e = p.rational_of(e).expect("exponent");
                                acc = b.factor(acc, x, e);
                            }
                        }
                        let r = b.value(acc);
                        if b.share {
                            let items: Vec<(u32, u64)> =
                                factors.iter().map(|&(x, e)| (x, u64::from(e))).collect();
                            b.prods.insert(r, coef, &items);
                        }
                        r
                    }
                    Node::Pow(x, y) => {
                        let (x, y) = (operand(&mut b, &at, *x), operand(&mut b, &at, *y));
                        b.emit(Code::Pow, x, y, 0)
                    }
                    Node::Func(f, x) => {
                        let x = operand(&mut b, &at, *x);
                        let code = match f {
                            Func::Sin => Code::Sin,
                            Func::Cos => Code::Cos,
                            Func::Tan => Code::Tan,
                            Func::Exp => Code::Exp,
                            Func::Ln => Code::Ln,
                            Func::Abs => Code::Abs,
                        };
                        b.unary(code, x)
                    }
                    Node::Atan2(y, x) => {
                        let (y, x) = (operand(&mut b, &at, *y), operand(&mut b, &at, *x));
                        b.emit(Code::Atan2, y, x, 0)
                    }
                    Node::Invalid(e) => {
                        return Err(SymError::Invalid(Box::new(p.error(*e).clone())));
                    }
                };
                at.insert(id, r);
            }
            Ok(reach
                .roots
                .iter()
                .map(|r| match at.get(r) {
                    Some(&a) => a,
                    None => b.konst(number[r]),
                })
                .collect::<Vec<u32>>())
        })?;
        // Fewer kinds of operation make longer runs (see `Block`): `a ± b` is `a + (±1)·b`
        // and `x²` is `x·x`, `1/x` is `1·(1/x)`, all exactly.
        let (one, minus_one) = (b.konst(1.0), b.konst(-1.0));
        for ins in &mut b.code {
            *ins = match ins.code {
                Code::Add => Ins {
                    code: Code::AddMul,
                    c: one,
                    ..*ins
                },
                Code::Sub => Ins {
                    code: Code::AddMul,
                    c: minus_one,
                    ..*ins
                },
                Code::Sq => Ins {
                    code: Code::Mul,
                    ..*ins
                },
                Code::Recip => Ins {
                    code: Code::MulRecip,
                    a: one,
                    ..*ins
                },
                _ => *ins,
            };
        }
        // Lay out the slots: parameters, constants, instructions in scheduled order.
        let (np, nc) = (params.len() as u32, b.consts.len() as u32);
        let base = np + nc;
        assert!(
            (base as usize + b.code.len()) < REF_PARAM as usize,
            "tape too large"
        );
        let (order, blocks) = schedule(&b.code);
        let mut new_pos = vec![0u32; b.code.len()];
        for (k, &i) in order.iter().enumerate() {
            new_pos[i as usize] = k as u32;
        }
        let slot = |r: u32| match r & REF_MASK {
            REF_PARAM => r & !REF_MASK,
            REF_CONST => np + (r & !REF_MASK),
            _ => base + new_pos[r as usize],
        };
        let args: Vec<Args> = order
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let ins = b.code[i as usize];
                let g = Args {
                    a: slot(ins.a),
                    b: slot(ins.b),
                    c: if ins.code == Code::AddMul {
                        slot(ins.c)
                    } else {
                        ins.c
                    },
                };
                // The invariant that makes `exec` sound: every read is of an earlier slot.
                let own = base + k as u32;
                assert!(g.a < own && g.b < own && (ins.code != Code::AddMul || g.c < own));
                g
            })
            .collect();
        Ok(Tape {
            params: param_index,
            param_names,
            consts: b.consts,
            blocks,
            args,
            outputs: outputs.into_iter().map(slot).collect(),
            nodes: ids.len(),
            compile_order: new_pos,
        })
    }

    /// Number of parameters expected.
    pub fn n_params(&self) -> usize {
        self.params.len()
    }
    /// Names of the parameters, in the order values are expected.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }
    /// Number of outputs (roots).
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// Number of instructions (binary or unary operations).
    pub fn len(&self) -> usize {
        self.args.len()
    }
    /// Does the tape compute nothing (no roots, or roots that are parameters or constants)?
    pub fn is_empty(&self) -> bool {
        self.args.is_empty()
    }
    /// Number of unique nodes of the DAG compiled (numbers included).
    pub fn n_nodes(&self) -> usize {
        self.nodes
    }
    /// Length of the work buffer [`Tape::eval_into`] needs.
    pub fn work_len(&self) -> usize {
        self.base() + self.args.len()
    }

    /// Slots before the first instruction's: parameters and constants.
    fn base(&self) -> usize {
        self.params.len() + self.consts.len()
    }

    /// The kernel: evaluate with a caller-provided work buffer, no allocation, no checks on the
    /// result. `values.len() == n_params()`, `out.len() == n_outputs()`,
    /// `work.len() >= work_len()`; otherwise an error.
    pub fn eval_into(
        &self,
        values: &[f64],
        out: &mut [f64],
        work: &mut [f64],
    ) -> Result<(), SymError> {
        self.check_lengths(values, out, work)?;
        self.run(values, work);
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = work[s as usize];
        }
        Ok(())
    }

    /// The buffer lengths [`Tape::eval_into`] requires, or an error saying which is wrong.
    fn check_lengths(&self, values: &[f64], out: &[f64], work: &[f64]) -> Result<(), SymError> {
        if values.len() != self.params.len() {
            return Err(SymError::Dimension(format!(
                "{} parameter values given, the tape expects {} ({})",
                values.len(),
                self.params.len(),
                self.param_names.join(", ")
            )));
        }
        if out.len() != self.outputs.len() || work.len() < self.work_len() {
            return Err(SymError::Dimension(format!(
                "output buffer {} (expected {}), work buffer {} (expected ≥ {})",
                out.len(),
                self.outputs.len(),
                work.len(),
                self.work_len()
            )));
        }
        Ok(())
    }

    /// The number of points of a batch, or an error if the buffers do not match.
    fn batch_count(&self, points: &[f64], out: &[f64]) -> Result<usize, SymError> {
        let np = self.params.len().max(1);
        let no = self.outputs.len();
        let count = if self.params.is_empty() {
            out.len() / no.max(1)
        } else {
            points.len() / np
        };
        if (!self.params.is_empty() && points.len() != count * np) || out.len() != count * no {
            return Err(SymError::Dimension(format!(
                "batch of {} values / {} outputs does not match {} parameters and {} outputs per point",
                points.len(),
                out.len(),
                self.params.len(),
                no
            )));
        }
        Ok(count)
    }

    /// The parameters and constants into their slots (lengths checked by the callers).
    fn load_inputs(&self, values: &[f64], w: &mut [f64]) {
        let np = self.params.len();
        w[..np].copy_from_slice(values);
        w[np..self.base()].copy_from_slice(&self.consts);
    }

    /// One point; `values` and `w` have the lengths checked by the callers.
    #[inline]
    fn run(&self, values: &[f64], w: &mut [f64]) {
        self.load_inputs(values, w);
        assert!(w.len() >= self.work_len());
        // SAFETY: length asserted above; operand order checked by `Tape::new`.
        unsafe { exec(&self.blocks, &self.args, w, self.base()) }
    }

    /// Evaluate, checking that every output is finite (an error names the first output that is
    /// not). The workspace grows on first use and is reused afterwards.
    pub fn eval(
        &self,
        values: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        if ws.work.len() < self.work_len() {
            ws.work.resize(self.work_len(), 0.0);
        }
        self.eval_into(values, out, &mut ws.work)?;
        first_non_finite(out)
    }

    /// Evaluate into a new vector (allocates; convenient for one-off use).
    pub fn eval_vec(&self, values: &[f64]) -> Result<Vec<f64>, SymError> {
        let mut out = vec![0.0; self.outputs.len()];
        self.eval(values, &mut out, &mut TapeWorkspace::default())?;
        Ok(out)
    }

    /// Evaluate at many points: `points` holds `n_params()` values per point (row-major),
    /// `out` receives `n_outputs()` values per point. Non-finite outputs are an error naming
    /// the point and the output (the first in point order). Points are evaluated in chunks of
    /// 16, each instruction applied to the whole chunk; the results are identical to
    /// [`Tape::eval_into`] point by point, at a fraction of the cost per point.
    pub fn eval_batch(
        &self,
        points: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        let np = self.params.len().max(1);
        let no = self.outputs.len();
        let count = self.batch_count(points, out)?;
        let n_params = self.params.len();
        let (base, len) = (self.base(), self.work_len());
        // Chunks of LANES points; a final remainder of fewer than LANES/4 points is cheaper
        // point by point than padded to a full chunk.
        let chunked = if count % LANES < LANES / 4 {
            count - count % LANES
        } else {
            count
        };
        if chunked > 0 {
            if ws.lanes.len() < len {
                ws.lanes.resize(len, [0.0; LANES]);
            }
            // Constants once for all chunks: instructions never write these slots.
            for (slot, &c) in ws.lanes[n_params..base].iter_mut().zip(&self.consts) {
                *slot = <[f64; LANES]>::splat(c);
            }
        }
        for first in (0..chunked).step_by(LANES) {
            let n = LANES.min(count - first);
            // Transpose the chunk; a partial chunk repeats its last point in the unused lanes.
            for (p, lane) in ws.lanes[..n_params].iter_mut().enumerate() {
                for (l, slot) in lane.iter_mut().enumerate() {
                    *slot = points[(first + l.min(n - 1)) * np + p];
                }
            }
            // SAFETY: `ws.lanes` has `work_len()` slots; operand order checked by `Tape::new`.
            unsafe { exec(&self.blocks, &self.args, &mut ws.lanes[..len], base) };
            for l in 0..n {
                let k = first + l;
                for (j, &s) in self.outputs.iter().enumerate() {
                    let v = ws.lanes[s as usize][l];
                    if !v.is_finite() {
                        return Err(SymError::EvalNonFinite {
                            what: format!("output {j} at point {k}"),
                            value: v,
                        });
                    }
                    out[k * no + j] = v;
                }
            }
        }
        if chunked < count && ws.work.len() < len {
            ws.work.resize(len, 0.0);
        }
        for k in chunked..count {
            let vals = if self.params.is_empty() {
                &[][..]
            } else {
                &points[k * np..(k + 1) * np]
            };
            self.run(vals, &mut ws.work);
            for (j, &s) in self.outputs.iter().enumerate() {
                let v = ws.work[s as usize];
                if !v.is_finite() {
                    return Err(SymError::EvalNonFinite {
                        what: format!("output {j} at point {k}"),
                        value: v,
                    });
                }
                out[k * no + j] = v;
            }
        }
        Ok(())
    }
}

/// An error naming the first output that is not finite.
fn first_non_finite(out: &[f64]) -> Result<(), SymError> {
    match out.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((k, &v)) => Err(SymError::EvalNonFinite {
            what: format!("output {k}"),
            value: v,
        }),
        None => Ok(()),
    }
}

/// Evaluate `roots` in any [`Elementary`] scalar, with `value_of(param_index)` giving the value
/// of each parameter (pool index, see [`Expr::param_index`]); `None` is an error naming the
/// parameter. This is the "recursive" reference evaluation (each node once, memoised).
pub fn eval_generic<S: Elementary>(
    roots: &[Expr],
    value_of: impl Fn(u32) -> Option<S>,
) -> Result<Vec<S>, SymError> {
    for r in roots {
        r.check().map_err(|e| SymError::Invalid(Box::new(e)))?;
    }
    let reach = reachable(roots);
    let pos: HashMap<Id, usize> = reach.ids.iter().enumerate().map(|(k, &i)| (i, k)).collect();
    // The shapes are copied out first: the pool must not be held while the scalar arithmetic
    // runs, since `S` may itself be `Expr`.
    let (shapes, names): (Vec<ShapeBuf>, HashMap<u32, String>) = with_serial(reach.serial, |p| {
        let shapes: Vec<ShapeBuf> = reach.ids.iter().map(|&i| p.shape(i).to_buf()).collect();
        let names = shapes
            .iter()
            .filter_map(|s| match s {
                Shape::Param(i) => Some((*i, p.param(*i).name.clone())),
                _ => None,
            })
            .collect();
        (shapes, names)
    });
    let rat = |c: Id| match &shapes[pos[&c]] {
        Shape::Num(r) => r.clone(),
        _ => unreachable!("product exponents are rational"),
    };
    let mut val: Vec<S> = Vec::with_capacity(shapes.len());
    for shape in &shapes {
        let v = match shape {
            Shape::Param(i) => value_of(*i).ok_or_else(|| SymError::MissingParameter {
                name: names[i].clone(),
            })?,
            _ => shape
                .eval(|c| val[pos[&c]], rat)
                .expect("valid nodes have values"),
        };
        val.push(v);
    }
    Ok(reach.roots.iter().map(|r| val[pos[r]]).collect())
}

/// Evaluate `roots` at the nominal values of their parameters, in any [`Elementary`] scalar
/// (parameter nominal values are converted from `f64`).
pub fn eval_nominal<S: Elementary>(roots: &[Expr]) -> Result<Vec<S>, SymError> {
    let (serial, _) = crate::context::unify(roots);
    eval_generic(roots, |i| {
        crate::expr::param_in(serial, i).map(|p| S::from_f64(p.nominal()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{params, random_dag};

    /// Values bit for bit (NaN matching NaN).
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn check(roots: &[Expr], ps: &[Expr], points: &[Vec<f64>]) {
        let tape = Tape::new(roots, ps).unwrap();
        let mut work = vec![0.0; tape.work_len()];
        let mut out = vec![0.0; tape.n_outputs()];
        for x in points {
            tape.eval_into(x, &mut out, &mut work).unwrap();
            let index: HashMap<u32, f64> = ps
                .iter()
                .zip(x)
                .map(|(p, &v)| (p.param_index().unwrap(), v))
                .collect();
            let want = eval_generic::<f64>(roots, |i| index.get(&i).copied()).unwrap();
            for (k, (&t, &g)) in out.iter().zip(&want).enumerate() {
                assert!(same(t, g), "output {k}: tape {t:e} vs eval_generic {g:e}");
            }
            #[cfg(all(target_arch = "x86_64", unix))]
            {
                let native = NativeTape::new(&tape).unwrap();
                let mut got = vec![0.0; tape.n_outputs()];
                native.eval_into(x, &mut got, &mut work).unwrap();
                for (k, (&n, &t)) in got.iter().zip(&out).enumerate() {
                    assert!(same(n, t), "output {k}: native {n:e} vs tape {t:e}");
                }
            }
        }
    }

    /// The tape keeps the recursive evaluator's order of operations, so it computes the
    /// same values exactly, even on DAGs whose values are pure rounding noise (repeated
    /// squaring, sines of huge arguments) where any reassociation would show.
    #[test]
    fn tape_equals_the_recursive_evaluator_bit_for_bit() {
        for seed in 1..4 {
            let ps = params(6, seed, seed % 2 == 0);
            let roots = random_dag(&ps, 1500, 20, seed);
            let nominal: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
            let other: Vec<f64> = nominal.iter().map(|v| 1.3 * v - 0.2).collect();
            check(&roots, &ps, &[nominal, other]);
        }
        let ps = params(3, 9, true);
        let (x, y, z) = (ps[0], ps[1], ps[2]);
        let half = Rational::new(1, 2).unwrap();
        let roots = [
            x.powi(-3) * y.powi(5) + z.powi(70) * Expr::int(3) - x.powi(-70),
            (x * y).pow_rational(Rational::new(2, 3).unwrap())
                / (Expr::one() + z).pow_rational(half),
            (x * Expr::int(2) - y * Expr::int(3)).sqrt().recip() - x.pow(y)
                + y.atan2(x - Expr::one()),
            (x.cos() * y.tan() + z.exp() - (x + Expr::one()).ln()).abs() * Expr::pi(),
            -(x * y * z) - (x * y).recip() + Expr::int(5),
            x / (y * z.powi(2)) - x.sin() * Expr::int(7),
        ];
        check(
            &roots,
            &ps,
            &[
                vec![1.2, 0.7, 0.9],
                vec![0.4, 2.5, 1.1],
                vec![-0.3, 0.2, 3.0],
            ],
        );
    }

    /// Sharing by reassociation: sums and products that contain others computed by the tape
    /// start from them (also with a power-of-two multiple), and compute nearly the same values.
    #[test]
    fn reassociating_tape_shares_contained_sums_and_products() {
        let ps = params(5, 3, true);
        let (x, y, z, u, v) = (ps[0], ps[1], ps[2], ps[3], ps[4]);
        let s3 = z + u + v;
        let p3 = z * u * v;
        let roots = [
            s3,
            s3 + x + y,
            s3 * Expr::int(2) + x,
            p3,
            p3 * x * y * Expr::int(3),
            p3.sqrt(),
        ];
        let exact = Tape::new(&roots, &ps).unwrap();
        let shared = Tape::new_reassociating(&roots, &ps).unwrap();
        // x+y+z+u+v from the node z+u+v: 2 additions instead of 4; 2z+2u+2v+x: a
        // multiplication and an addition instead of 3 scaled additions; 3xyzuv: 3
        // multiplications instead of 5.
        assert!(
            shared.len() + 5 <= exact.len(),
            "{} vs {}",
            shared.len(),
            exact.len()
        );
        let pt = [0.3, 1.7, 0.4, 2.2, 0.9];
        let (a, b) = (exact.eval_vec(&pt).unwrap(), shared.eval_vec(&pt).unwrap());
        for (a, b) in a.iter().zip(&b) {
            assert!((a - b).abs() <= 1e-15 * a.abs(), "{a} vs {b}");
        }
        // A large DAG compiles to fewer instructions and evaluates.
        let ps = params(6, 1, true);
        let roots = random_dag(&ps, 1500, 20, 1);
        let (exact, shared) = (
            Tape::new(&roots, &ps).unwrap(),
            Tape::new_reassociating(&roots, &ps).unwrap(),
        );
        assert!(shared.len() < exact.len());
        let nominal: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
        let mut out = vec![0.0; shared.n_outputs()];
        let mut work = vec![0.0; shared.work_len()];
        shared.eval_into(&nominal, &mut out, &mut work).unwrap();
    }
}
