//! The interpreter: runs of one operation over a work buffer, for one point (`f64`) or for a
//! chunk of points (`[f64; LANES]`) with the same operations per point.

use crate::func::Func;

/// The operation of one instruction, on the values of slots `a`, `b` (and `c`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Code {
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
    /// `√a`
    Sqrt,
    /// `a^b` by `powf`
    Pow,
    /// `atan2(a, b)`
    Atan2,
    /// An elementary function of `a`.
    Func(Func),
}

impl Code {
    /// Number of distinct operations (for the scheduler's queues).
    pub(super) const COUNT: usize = 10 + Func::ALL.len();

    /// A dense index of the operation.
    pub(super) fn index(self) -> usize {
        match self {
            Code::Add => 0,
            Code::Sub => 1,
            Code::AddMul => 2,
            Code::Mul => 3,
            Code::MulRecip => 4,
            Code::Recip => 5,
            Code::Neg => 6,
            Code::Sqrt => 7,
            Code::Pow => 8,
            Code::Atan2 => 9,
            Code::Func(f) => 10 + f as usize,
        }
    }
}

/// Points evaluated together by [`Tape::eval_batch`](super::Tape::eval_batch): the
/// interpreter's own work (operand indices, block loops) is paid once per chunk, and the
/// arithmetic on contiguous lanes vectorises; 16 lanes did better than 4, 8 or 32 in the
/// `eval` bench.
pub(super) const LANES: usize = 16;

/// What the interpreter computes on: one point (`f64`) or a chunk of points
/// (`[f64; LANES]`), with the same operations per point, so that batch results equal
/// point-by-point ones bit for bit.
pub(super) trait Lane: Copy {
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
/// ([`Code::AddMul`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Args {
    pub a: u32,
    pub b: u32,
    pub c: u32,
}

/// A run of instructions with the same operation. Interpreting instruction by instruction
/// costs a mispredicted indirect branch almost every time (the operations of a DAG come in
/// no regular order); the tape is scheduled so that operations of one kind are consecutive
/// where dependencies allow, and each run is a tight loop.
#[derive(Clone, Copy, Debug)]
pub(super) struct Block {
    pub code: Code,
    pub len: u32,
}

/// `w[out + k] = f(w[a], w[b])` for the instructions `k` of a block.
#[inline(always)]
fn binary<T: Lane>(args: &[Args], w: &mut [T], out: usize, f: impl Fn(T, T) -> T) {
    for (k, g) in args.iter().enumerate() {
        w[out + k] = f(w[g.a as usize], w[g.b as usize]);
    }
}

/// `w[out + k] = f(w[a])`.
#[inline(always)]
fn unary<T: Lane>(args: &[Args], w: &mut [T], out: usize, f: impl Fn(f64) -> f64) {
    for (k, g) in args.iter().enumerate() {
        w[out + k] = w[g.a as usize].map(&f);
    }
}

/// Run the program on `w`, whose first `base` slots hold the parameters and constants;
/// instruction `i` (counted over all blocks) writes slot `base + i` and reads earlier slots
/// only.
#[inline(always)]
pub(super) fn exec<T: Lane>(blocks: &[Block], args: &[Args], w: &mut [T], base: usize) {
    let mut start = 0;
    for blk in blocks {
        let end = start + blk.len as usize;
        let g = &args[start..end];
        let out = base + start;
        match blk.code {
            Code::Add => binary(g, w, out, |x, y| x.zip(y, |a, b| a + b)),
            Code::Sub => binary(g, w, out, |x, y| x.zip(y, |a, b| a - b)),
            Code::AddMul => {
                for (k, g) in g.iter().enumerate() {
                    let (x, y, c) = (w[g.a as usize], w[g.b as usize], w[g.c as usize]);
                    w[out + k] = x.zip3(y, c, |a, b, c| a + c * b);
                }
            }
            Code::Mul => binary(g, w, out, |x, y| x.zip(y, |a, b| a * b)),
            Code::MulRecip => binary(g, w, out, |x, y| x.zip(y, |a, b| a * (1.0 / b))),
            Code::Recip => unary(g, w, out, |a| 1.0 / a),
            Code::Neg => unary(g, w, out, |a| -a),
            Code::Sqrt => unary(g, w, out, f64::sqrt),
            Code::Pow => binary(g, w, out, |x, y| x.zip(y, f64::powf)),
            Code::Atan2 => binary(g, w, out, |x, y| x.zip(y, f64::atan2)),
            Code::Func(Func::Abs) => unary(g, w, out, f64::abs),
            Code::Func(f) => unary(g, w, out, f.f64_fn()),
        }
        start = end;
    }
}
