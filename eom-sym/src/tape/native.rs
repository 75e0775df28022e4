//! Native code for a [`Tape`]: the same register program translated to x86-64 machine code
//! at run time (a small, single-pass JIT), so that no interpreter dispatch, operand-index
//! load or loop overhead is paid per instruction.
//!
//! The translation is one-to-one: every tape instruction becomes the same IEEE operations in
//! the same order (`a + c·b` as a product then a sum, `a·(1/b)` as a division then a product,
//! `a³` as `(a·a)·a`, the library functions through the very functions the interpreter
//! calls; only the exact rewrites `a + 1·b = a + b`, `a + (−1)·b = a − b`, `1·(1/b) = 1/b`),
//! so a [`NativeTape`] computes what [`Tape::eval_into`] computes, bit for bit; tests check
//! this.
//!
//! * **Order.** Instructions are emitted in the order the compiler produced them (operands
//!   right before their use), not in the interpreter's runs of one operation: without
//!   dispatch there is nothing to gain from grouping, and short distances keep values in
//!   registers. Results get their work-buffer slots in this order, so that most addresses
//!   are a one-byte displacement from a base register that moves forward.
//! * **Registers.** Values live in `xmm2`–`xmm15`; when one must go, it is the one needed
//!   furthest in the future (Belady: the whole program is known). An operation runs in the
//!   register of an operand that dies there. A call (`sin`, `exp`, …) clobbers every `xmm`
//!   register under the System V ABI, so values live across it are read back from memory.
//! * **Stores.** A result is written to the work buffer only if some later use reads it
//!   from memory (or it is an output): a first pass with the same decisions finds which.
//!
//! The 10 000-node benchmark DAG (`benches/core.rs`): 1.83–1.91 ns per node against 4.2–4.4
//! for the interpreter, 136 k instructions per evaluation against 342 k; translation takes
//! about 0.25 µs per instruction.
//!
//! Supported on x86-64 Unix (System V calling convention, `mmap`/`mprotect` for an
//! executable page that is never writable at the same time); elsewhere
//! [`NativeTape::new`] returns [`SymError::Unsupported`] and callers keep the interpreter.

use super::Tape;
use crate::error::SymError;

/// A [`Tape`] compiled to native code. Evaluation has the same contract as
/// [`Tape::eval_into`] and gives identical results, about twice as fast on large tapes.
///
/// ```
/// use eom_sym::{Expr, NativeTape, Tape};
/// let m = Expr::param("m", 2.0).unwrap();
/// let k = Expr::param("k", 8.0).unwrap();
/// let w = (k / m).sqrt();
/// let tape = Tape::new(&[w, w.sin()], &[m, k]).unwrap();
/// match NativeTape::new(&tape) {
///     Ok(native) => {
///         let mut work = vec![0.0; native.work_len()];
///         let mut out = [0.0; 2];
///         native.eval_into(&[2.0, 8.0], &mut out, &mut work).unwrap();
///         assert_eq!(out, [2.0, eom_sym::trig::sin(2.0)]);
///     }
///     // Not on x86-64 Unix: keep the interpreter.
///     Err(e) => println!("{e}"),
/// }
/// ```
#[derive(Clone)]
pub struct NativeTape {
    tape: Tape,
    /// The machine code, shared by clones (it is never written after construction).
    #[cfg(all(target_arch = "x86_64", unix))]
    code: std::sync::Arc<exec::Code>,
    /// The slots the outputs are left in (the native layout differs from the tape's).
    #[cfg(all(target_arch = "x86_64", unix))]
    outputs: Vec<u32>,
}

impl std::fmt::Debug for NativeTape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NativeTape")
            .field("instructions", &self.tape.len())
            .field("code_bytes", &self.code_len())
            .finish()
    }
}

impl NativeTape {
    /// Translate `tape` to machine code (about 20 bytes per instruction; linear time).
    /// [`SymError::Unsupported`] on platforms other than x86-64 Unix, or if the system
    /// refuses an executable mapping.
    pub fn new(tape: &Tape) -> Result<NativeTape, SymError> {
        #[cfg(all(target_arch = "x86_64", unix))]
        {
            // Slots are addressed with 32-bit displacements.
            if tape.work_len() >= (i32::MAX as usize) / 16 {
                return Err(SymError::Unsupported(format!(
                    "native tape: {} work slots exceed the 32-bit displacements of the code",
                    tape.work_len()
                )));
            }
            let (bytes, outputs) = emit::program(tape);
            let code = std::sync::Arc::new(exec::Code::new(&bytes)?);
            Ok(NativeTape {
                tape: tape.clone(),
                code,
                outputs,
            })
        }
        #[cfg(not(all(target_arch = "x86_64", unix)))]
        {
            let _ = tape;
            Err(SymError::Unsupported(
                "native tapes are built for x86-64 Unix only; use the Tape interpreter".into(),
            ))
        }
    }

    /// The interpreted tape this was compiled from.
    pub fn tape(&self) -> &Tape {
        &self.tape
    }

    /// Size of the machine code in bytes.
    pub fn code_len(&self) -> usize {
        #[cfg(all(target_arch = "x86_64", unix))]
        {
            self.code.len
        }
        #[cfg(not(all(target_arch = "x86_64", unix)))]
        {
            0
        }
    }

    /// Length of the work buffer [`NativeTape::eval_into`] needs (as [`Tape::work_len`]).
    pub fn work_len(&self) -> usize {
        self.tape.work_len()
    }

    /// Number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.tape.n_outputs()
    }

    /// Number of parameters.
    pub fn n_params(&self) -> usize {
        self.tape.n_params()
    }

    /// The kernel, as [`Tape::eval_into`]: a caller-provided work buffer, no allocation, no
    /// checks on the result; wrong buffer lengths are an error.
    pub fn eval_into(
        &self,
        values: &[f64],
        out: &mut [f64],
        work: &mut [f64],
    ) -> Result<(), SymError> {
        self.tape.check_lengths(values, out, work)?;
        self.tape.load_inputs(values, work);
        #[cfg(all(target_arch = "x86_64", unix))]
        // SAFETY: the code reads and writes slots below `work_len()` only (they are the
        // operands and results of the tape's instructions, whose order `Tape::new` checked),
        // and `work` is at least that long (checked above).
        unsafe {
            self.code.run(work.as_mut_ptr())
        };
        #[cfg(all(target_arch = "x86_64", unix))]
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = work[s as usize];
        }
        Ok(())
    }

    /// Evaluate at many points, as [`Tape::eval_batch`] (same layout, same errors, the same
    /// values bit for bit), one point after the other.
    pub fn eval_batch(
        &self,
        points: &[f64],
        out: &mut [f64],
        ws: &mut super::TapeWorkspace,
    ) -> Result<(), SymError> {
        let (np, no) = (self.n_params(), self.n_outputs());
        let count = self.tape.batch_count(points, out)?;
        if ws.work.len() < self.work_len() {
            ws.work.resize(self.work_len(), 0.0);
        }
        for k in 0..count {
            let o = &mut out[k * no..(k + 1) * no];
            self.eval_into(&points[k * np..(k + 1) * np], o, &mut ws.work)?;
            if let Some(j) = o.iter().position(|v| !v.is_finite()) {
                return Err(SymError::EvalNonFinite {
                    what: format!("output {j} at point {k}"),
                    value: o[j],
                });
            }
        }
        Ok(())
    }

    /// Evaluate, checking that every output is finite, as [`Tape::eval`].
    pub fn eval(
        &self,
        values: &[f64],
        out: &mut [f64],
        ws: &mut super::TapeWorkspace,
    ) -> Result<(), SymError> {
        if ws.work.len() < self.work_len() {
            ws.work.resize(self.work_len(), 0.0);
        }
        self.eval_into(values, out, &mut ws.work)?;
        super::first_non_finite(out)
    }
}

/// The machine-code emitter: a register allocator over the tape's instructions and the
/// encodings of the few SSE2 and integer instructions it needs.
#[cfg(all(target_arch = "x86_64", unix))]
mod emit {
    use super::super::{Code, Tape};

    /// `rbx` holds the work buffer's address plus a moving offset (callee-saved, so it
    /// survives calls); `rax` and `edi` serve calls.
    const RBX: u8 = 3;
    /// Registers the allocator hands out; `xmm0`, `xmm1` carry call arguments and results.
    const FIRST: u8 = 2;
    const N_XMM: usize = 16;
    const NONE: u32 = u32::MAX;

    // SSE2 opcodes (scalar double with prefix F2, packed with 66).
    const ADD: u8 = 0x58;
    const MUL: u8 = 0x59;
    const SUB: u8 = 0x5C;
    const DIV: u8 = 0x5E;
    const SQRT: u8 = 0x51;
    const MOVSD_LOAD: u8 = 0x10;
    const MOVSD_STORE: u8 = 0x11;

    /// Constants of the code, addressed relative to the instruction pointer.
    #[derive(Clone, Copy)]
    enum Konst {
        SignMask,
        AbsMask,
        One,
    }

    /// One operation after the peephole rewrites, on slots of the native layout.
    #[derive(Clone, Copy)]
    enum Op {
        /// `a + b`, `a − b`, `a·b` (`op` the SSE2 opcode)
        Bin(u8, u32, u32),
        /// `a + c·b`: the product, then the sum
        AddMul(u32, u32, u32),
        /// `a·(1/b)`
        MulRecip(u32, u32),
        /// `1/b`
        Recip(u32),
        Neg(u32),
        Abs(u32),
        Cube(u32),
        Sqrt(u32),
        /// A library function of one or two arguments (and an `i32`)
        Call(Lib, u32, Option<u32>, Option<i32>),
    }

    /// The library functions the code calls.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
    pub(super) enum Lib {
        Sin,
        Cos,
        Tan,
        Exp,
        Ln,
        Powi,
        Pow,
        Atan2,
    }

    impl Lib {
        /// The address of the function (`extern "C"`, arguments in `xmm0`, `xmm1`, `edi`).
        fn address(self) -> usize {
            let unary = |f: extern "C" fn(f64) -> f64| f as usize;
            let binary = |f: extern "C" fn(f64, f64) -> f64| f as usize;
            match self {
                Lib::Sin => unary(lib::sin),
                Lib::Cos => unary(lib::cos),
                Lib::Tan => unary(lib::tan),
                Lib::Exp => unary(lib::exp),
                Lib::Ln => unary(lib::ln),
                Lib::Powi => lib::powi as extern "C" fn(f64, i32) -> f64 as usize,
                Lib::Pow => binary(lib::pow),
                Lib::Atan2 => binary(lib::atan2),
            }
        }
    }

    impl Op {
        fn reads(&self) -> ([u32; 3], usize) {
            match *self {
                Op::Bin(_, a, b) | Op::MulRecip(a, b) => ([a, b, 0], 2),
                Op::AddMul(a, b, c) => ([a, b, c], 3),
                Op::Call(_, a, Some(b), _) => ([a, b, 0], 2),
                Op::Recip(a)
                | Op::Neg(a)
                | Op::Abs(a)
                | Op::Cube(a)
                | Op::Sqrt(a)
                | Op::Call(_, a, None, _) => ([a, 0, 0], 1),
            }
        }
    }

    /// The functions the interpreter applies, with the C calling convention.
    mod lib {
        pub extern "C" fn sin(x: f64) -> f64 {
            crate::trig::sin(x)
        }
        pub extern "C" fn cos(x: f64) -> f64 {
            crate::trig::cos(x)
        }
        pub extern "C" fn tan(x: f64) -> f64 {
            x.tan()
        }
        pub extern "C" fn exp(x: f64) -> f64 {
            x.exp()
        }
        pub extern "C" fn ln(x: f64) -> f64 {
            x.ln()
        }
        pub extern "C" fn powi(x: f64, n: i32) -> f64 {
            x.powi(n)
        }
        pub extern "C" fn pow(x: f64, y: f64) -> f64 {
            x.powf(y)
        }
        pub extern "C" fn atan2(y: f64, x: f64) -> f64 {
            y.atan2(x)
        }
    }

    /// The tape's instructions in compile order, on the native slot layout (instruction `j`
    /// of the compile order writes slot `base + j`, so that results are stored at
    /// increasing addresses), with exact peephole rewrites: `a + 1·b` is `a + b`,
    /// `a + (−1)·b` is `a − b`, `1·(1/b)` is `1/b` (the same IEEE results).
    fn lower(tape: &Tape) -> (Vec<Op>, Vec<u32>) {
        let n = tape.args.len();
        let np = tape.params.len();
        let base = tape.base() as u32;
        let mut code_of = vec![Code::Add; n];
        let mut at = 0usize;
        for blk in &tape.blocks {
            code_of[at..at + blk.len as usize].fill(blk.code);
            at += blk.len as usize;
        }
        // Scheduled position → compile index.
        let mut compiled = vec![0u32; n];
        for (j, &k) in tape.compile_order.iter().enumerate() {
            compiled[k as usize] = j as u32;
        }
        let slot = |s: u32| {
            if s >= base {
                base + compiled[(s - base) as usize]
            } else {
                s
            }
        };
        let konst = |s: u32| (s as usize >= np && s < base).then(|| tape.consts[s as usize - np]);
        let ops = tape
            .compile_order
            .iter()
            .map(|&k| {
                let g = tape.args[k as usize];
                let (a, b) = (slot(g.a), slot(g.b));
                match code_of[k as usize] {
                    Code::Add => Op::Bin(ADD, a, b),
                    Code::Sub => Op::Bin(SUB, a, b),
                    Code::Mul => Op::Bin(MUL, a, b),
                    Code::AddMul => match konst(g.c) {
                        Some(1.0) => Op::Bin(ADD, a, b),
                        Some(-1.0) => Op::Bin(SUB, a, b),
                        _ => Op::AddMul(a, b, slot(g.c)),
                    },
                    Code::MulRecip if konst(g.a) == Some(1.0) => Op::Recip(b),
                    Code::MulRecip => Op::MulRecip(a, b),
                    Code::Recip => Op::Recip(a),
                    Code::Neg => Op::Neg(a),
                    Code::Abs => Op::Abs(a),
                    Code::Sq => Op::Bin(MUL, a, a),
                    Code::Cube => Op::Cube(a),
                    Code::Sqrt => Op::Sqrt(a),
                    Code::Powi => Op::Call(Lib::Powi, a, None, Some(g.c as i32)),
                    Code::Pow => Op::Call(Lib::Pow, a, Some(b), None),
                    Code::Sin => Op::Call(Lib::Sin, a, None, None),
                    Code::Cos => Op::Call(Lib::Cos, a, None, None),
                    Code::Tan => Op::Call(Lib::Tan, a, None, None),
                    Code::Exp => Op::Call(Lib::Exp, a, None, None),
                    Code::Ln => Op::Call(Lib::Ln, a, None, None),
                    Code::Atan2 => Op::Call(Lib::Atan2, a, Some(b), None),
                }
            })
            .collect();
        (ops, tape.outputs.iter().map(|&s| slot(s)).collect())
    }

    struct Asm {
        code: Vec<u8>,
        /// (offset of a rel32 field, the constant it addresses)
        fixups: Vec<(usize, Konst)>,
        /// The slot `rbx` points at.
        origin: u32,
    }

    impl Asm {
        /// `prefix [REX] 0F op ModRM`, the `reg` field `reg`, register operand `rm`.
        fn rr(&mut self, prefix: u8, op: u8, reg: u8, rm: u8) {
            self.code.push(prefix);
            let rex = 0x40 | ((reg >> 3) << 2) | (rm >> 3);
            if rex != 0x40 {
                self.code.push(rex);
            }
            self.code
                .extend_from_slice(&[0x0F, op, 0xC0 | ((reg & 7) << 3) | (rm & 7)]);
        }
        /// The same with the memory operand `slot` (`[rbx + disp]`).
        fn rm(&mut self, prefix: u8, op: u8, reg: u8, slot: u32) {
            self.code.push(prefix);
            if reg >= 8 {
                self.code.push(0x44);
            }
            self.code.extend_from_slice(&[0x0F, op]);
            let disp = (slot as i64 - self.origin as i64) * 8;
            if let Ok(d) = i8::try_from(disp) {
                self.code.push(0x40 | ((reg & 7) << 3) | RBX);
                self.code.push(d as u8);
            } else {
                self.code.push(0x80 | ((reg & 7) << 3) | RBX);
                self.code.extend_from_slice(&(disp as i32).to_le_bytes());
            }
        }
        /// The same with a constant of the code (`[rip + rel32]`).
        fn rk(&mut self, prefix: u8, op: u8, reg: u8, k: Konst) {
            self.code.push(prefix);
            if reg >= 8 {
                self.code.push(0x44);
            }
            self.code
                .extend_from_slice(&[0x0F, op, ((reg & 7) << 3) | 0b101]);
            self.fixups.push((self.code.len(), k));
            self.code.extend_from_slice(&[0; 4]);
        }
        fn copy(&mut self, dst: u8, src: u8) {
            if dst != src {
                self.rr(0x66, 0x28, dst, src); // movapd
            }
        }
        /// Store `reg` to `slot`, first moving `rbx` forward when the slot is out of reach
        /// of an 8-bit displacement (results are stored at increasing slots, so most
        /// accesses then take one byte of displacement instead of four).
        fn store(&mut self, reg: u8, slot: u32) {
            let disp = (slot as i64 - self.origin as i64) * 8;
            if i8::try_from(disp).is_err() {
                // Point 16 slots past this one: the next 31 results are in reach.
                let step = (slot as i64 + 16 - self.origin as i64) * 8;
                if let Ok(s) = i8::try_from(step) {
                    self.code.extend_from_slice(&[0x48, 0x83, 0xC3, s as u8]); // add rbx, imm8
                } else {
                    self.code.extend_from_slice(&[0x48, 0x81, 0xC3]); // add rbx, imm32
                    self.code.extend_from_slice(&(step as i32).to_le_bytes());
                }
                self.origin = slot + 16;
            }
            self.rm(0xF2, MOVSD_STORE, reg, slot);
        }
        fn call(&mut self, f: usize) {
            self.code.extend_from_slice(&[0x48, 0xB8]); // mov rax, imm64
            self.code.extend_from_slice(&(f as u64).to_le_bytes());
            self.code.extend_from_slice(&[0xFF, 0xD0]); // call rax
        }
        fn finish(mut self) -> Vec<u8> {
            while !self.code.len().is_multiple_of(16) {
                self.code.push(0xCC);
            }
            let base = self.code.len();
            // 16-byte aligned: `xorpd`/`andpd` read 16 bytes and require alignment.
            let sign = (-0.0f64).to_bits().to_le_bytes();
            let abs = (!(-0.0f64).to_bits()).to_le_bytes();
            for bytes in [sign, sign, abs, abs, 1.0f64.to_bits().to_le_bytes()] {
                self.code.extend_from_slice(&bytes);
            }
            for &(at, k) in &self.fixups {
                let target = base
                    + match k {
                        Konst::SignMask => 0,
                        Konst::AbsMask => 16,
                        Konst::One => 32,
                    };
                let rel = (target as i64 - (at as i64 + 4)) as i32;
                self.code[at..at + 4].copy_from_slice(&rel.to_le_bytes());
            }
            self.code
        }
    }

    /// Register allocation with full knowledge of the future (Belady): a value stays in a
    /// register until it is dead or the register is needed for a value used sooner.
    struct Alloc<'a> {
        asm: Asm,
        /// Slot held by each register.
        held: [u32; N_XMM],
        /// Register holding each slot (`u8::MAX`: none).
        reg_of: Vec<u8>,
        /// Uses of each slot (steps, ascending) in `uses[start[s]..start[s+1]]`; `next[s]`
        /// is the first not yet reached.
        start: Vec<u32>,
        uses: Vec<u32>,
        next: Vec<u32>,
        /// Instruction results the code reads from memory (they must be stored).
        read_back: &'a mut [bool],
        base: u32,
    }

    impl Alloc<'_> {
        fn reg(&self, s: u32) -> Option<u8> {
            let r = self.reg_of[s as usize];
            (r != u8::MAX).then_some(r)
        }
        /// The step of the next use of `s` (`u32::MAX`: none).
        fn next_use(&self, s: u32) -> u32 {
            let k = self.next[s as usize];
            if k < self.start[s as usize + 1] {
                self.uses[k as usize]
            } else {
                u32::MAX
            }
        }
        fn free(&mut self, r: u8) {
            let s = self.held[r as usize];
            if s != NONE {
                self.reg_of[s as usize] = u8::MAX;
                self.held[r as usize] = NONE;
            }
        }
        /// A register for a new value: a free one, else the one whose value is needed last.
        fn take(&mut self, keep: &[u8]) -> u8 {
            let r = (FIRST..N_XMM as u8)
                .filter(|r| !keep.contains(r))
                .max_by_key(|&r| match self.held[r as usize] {
                    NONE => (1, 0),
                    s => (0, self.next_use(s)),
                })
                .expect("registers");
            self.free(r);
            r
        }
        fn note_read(&mut self, s: u32) {
            if s >= self.base {
                self.read_back[s as usize] = true;
            }
        }
        /// `op reg, s` with `s` from its register or from memory.
        fn op(&mut self, prefix: u8, op: u8, reg: u8, s: u32) {
            match self.reg(s) {
                Some(r) => self.asm.rr(prefix, op, reg, r),
                None => {
                    self.note_read(s);
                    self.asm.rm(prefix, op, reg, s);
                }
            }
        }
        /// A register to compute into, holding the value of `a`: `a`'s own register when
        /// `a` dies here (`in_place`), else a copy or a load.
        fn dest(&mut self, a: u32, step: u32, in_place: bool, keep: &[u8]) -> u8 {
            match self.reg(a) {
                Some(r) if in_place && self.dies(a, step) => {
                    self.free(r);
                    r
                }
                Some(r) => {
                    let d = self.take(&[keep, &[r]].concat());
                    self.asm.copy(d, r);
                    d
                }
                None => {
                    let d = self.take(keep);
                    self.op(0xF2, MOVSD_LOAD, d, a);
                    d
                }
            }
        }
        /// Whether every remaining use of `s` is at `step`.
        fn dies(&self, s: u32, step: u32) -> bool {
            let (mut k, end) = (self.next[s as usize], self.start[s as usize + 1]);
            while k < end && self.uses[k as usize] == step {
                k += 1;
            }
            k == end
        }

        fn step(&mut self, step: u32, op: Op, out: u32, store: bool) {
            let d = match op {
                Op::Bin(code, a, b) => {
                    let commutes = code != SUB;
                    // Compute in the register of an operand that dies here, if any.
                    let (a, b) = if commutes
                        && !(self.reg(a).is_some() && self.dies(a, step))
                        && self.reg(b).is_some()
                        && (self.dies(b, step) || self.reg(a).is_none())
                    {
                        (b, a)
                    } else {
                        (a, b)
                    };
                    let keep: Vec<u8> = self.reg(b).into_iter().collect();
                    let d = self.dest(a, step, true, &keep);
                    if b == a && self.reg(a).is_none_or(|r| r == d) {
                        self.asm.rr(0xF2, code, d, d);
                    } else {
                        self.op(0xF2, code, d, b);
                    }
                    d
                }
                Op::AddMul(a, b, c) => {
                    let keep: Vec<u8> = [self.reg(a), self.reg(b)].into_iter().flatten().collect();
                    let d = self.dest(c, step, true, &keep);
                    self.op(0xF2, MUL, d, b);
                    self.op(0xF2, ADD, d, a);
                    d
                }
                Op::MulRecip(a, b) => {
                    let keep: Vec<u8> = [self.reg(a), self.reg(b)].into_iter().flatten().collect();
                    let d = self.take(&keep);
                    self.asm.rk(0xF2, MOVSD_LOAD, d, Konst::One);
                    self.op(0xF2, DIV, d, b);
                    self.op(0xF2, MUL, d, a);
                    d
                }
                Op::Recip(b) => {
                    let keep: Vec<u8> = self.reg(b).into_iter().collect();
                    let d = self.take(&keep);
                    self.asm.rk(0xF2, MOVSD_LOAD, d, Konst::One);
                    self.op(0xF2, DIV, d, b);
                    d
                }
                Op::Neg(a) => {
                    let d = self.dest(a, step, true, &[]);
                    self.asm.rk(0x66, 0x57, d, Konst::SignMask); // xorpd
                    d
                }
                Op::Abs(a) => {
                    let d = self.dest(a, step, true, &[]);
                    self.asm.rk(0x66, 0x54, d, Konst::AbsMask); // andpd
                    d
                }
                Op::Cube(a) => {
                    // (a·a)·a: `a` is read after the first product, so never in place.
                    let d = self.dest(a, step, false, &[]);
                    self.op(0xF2, MUL, d, a);
                    self.op(0xF2, MUL, d, a);
                    d
                }
                Op::Sqrt(a) => {
                    let src = self.reg(a);
                    let d = match src {
                        Some(r) if self.dies(a, step) => r,
                        _ => self.take(src.as_slice()),
                    };
                    self.op(0xF2, SQRT, d, a);
                    d
                }
                Op::Call(lib, x, y, n) => {
                    for (k, s) in [Some(x), y].into_iter().flatten().enumerate() {
                        match self.reg(s) {
                            Some(r) => self.asm.copy(k as u8, r),
                            None => {
                                self.note_read(s);
                                self.asm.rm(0xF2, MOVSD_LOAD, k as u8, s);
                            }
                        }
                    }
                    if let Some(n) = n {
                        self.asm.code.push(0xBF); // mov edi, imm32
                        self.asm.code.extend_from_slice(&n.to_le_bytes());
                    }
                    self.asm.call(lib.address());
                    // Every xmm register is caller-saved: values live across the call are
                    // read back from memory.
                    for r in FIRST..N_XMM as u8 {
                        self.free(r);
                    }
                    let d = self.take(&[]);
                    self.asm.copy(d, 0);
                    d
                }
            };
            // Past this step: operands that died free their registers.
            let (reads, n) = op.reads();
            for &s in &reads[..n] {
                let k = &mut self.next[s as usize];
                while *k < self.start[s as usize + 1] && self.uses[*k as usize] == step {
                    *k += 1;
                }
                if self.next_use(s) == u32::MAX
                    && let Some(r) = self.reg(s)
                    && r != d
                {
                    self.free(r);
                }
            }
            if store {
                self.asm.store(d, out);
            }
            if self.next_use(out) != u32::MAX {
                self.free(d);
                self.held[d as usize] = out;
                self.reg_of[out as usize] = d;
            } else if self.held[d as usize] != NONE
                && self.next_use(self.held[d as usize]) == u32::MAX
            {
                self.free(d);
            }
        }
    }

    /// The machine code of `tape` (`extern "C" fn(work: *mut f64)`) and the slots its
    /// outputs are left in.
    ///
    /// (Tried and dropped: batching the library calls, by phases of call depth or one per
    /// call site, through a loop over argument slots. It saves call sites but moves the
    /// arguments and results through memory and, by phases, spreads live ranges; on the
    /// 10 000-node benchmark DAG both took 21.7 µs against 18.6 µs for direct calls.)
    pub(super) fn program(tape: &Tape) -> (Vec<u8>, Vec<u32>) {
        let (ops, outputs) = lower(tape);
        let base = tape.base() as u32;
        let len = tape.work_len();
        // Uses of every slot, by step.
        let mut start = vec![0u32; len + 1];
        for op in &ops {
            let (r, n) = op.reads();
            for &s in &r[..n] {
                start[s as usize + 1] += 1;
            }
        }
        for s in 0..len {
            start[s + 1] += start[s];
        }
        let mut fill = start.clone();
        let mut uses = vec![0u32; start[len] as usize];
        for (t, op) in ops.iter().enumerate() {
            let (r, n) = op.reads();
            for &s in &r[..n] {
                uses[fill[s as usize] as usize] = t as u32;
                fill[s as usize] += 1;
            }
        }
        let mut is_output = vec![false; len];
        for &s in &outputs {
            is_output[s as usize] = true;
        }
        // Two passes with the same decisions: the first finds which results are read back
        // from memory, the second stores only those (and the outputs).
        let mut read_back = vec![false; len];
        let mut code = Vec::new();
        for pass in 0..2 {
            let mut stored = vec![false; len];
            if pass == 1 {
                for s in 0..len {
                    stored[s] = read_back[s] || is_output[s];
                }
            }
            let mut al = Alloc {
                asm: Asm {
                    code: Vec::with_capacity(ops.len() * 8 + 64),
                    fixups: Vec::new(),
                    origin: 0,
                },
                held: [NONE; N_XMM],
                reg_of: vec![u8::MAX; len],
                start: start.clone(),
                uses: uses.clone(),
                next: start[..len].to_vec(),
                read_back: &mut read_back,
                base,
            };
            // push rbx; mov rbx, rdi (the stack is then 16-byte aligned for calls).
            al.asm.code.extend_from_slice(&[0x53, 0x48, 0x89, 0xFB]);
            for (t, op) in ops.iter().enumerate() {
                let out = base + t as u32;
                al.step(t as u32, *op, out, stored[out as usize]);
            }
            al.asm.code.extend_from_slice(&[0x5B, 0xC3]); // pop rbx; ret
            code = al.asm.finish();
        }
        (code, outputs)
    }
}

/// An executable mapping of machine code.
#[cfg(all(target_arch = "x86_64", unix))]
mod exec {
    use crate::error::SymError;

    pub(super) struct Code {
        ptr: *mut libc::c_void,
        map_len: usize,
        pub(super) len: usize,
    }

    // SAFETY: the mapping is read-only and executable after construction, never mutated,
    // and the code it holds touches only the buffer passed to each call.
    unsafe impl Send for Code {}
    // SAFETY: as above.
    unsafe impl Sync for Code {}

    impl Code {
        pub(super) fn new(bytes: &[u8]) -> Result<Code, SymError> {
            // SAFETY: sysconf has no preconditions.
            let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(4096) as usize;
            let map_len = bytes.len().div_ceil(page) * page;
            // SAFETY: an anonymous private mapping; the result is checked.
            let ptr = unsafe {
                libc::mmap(
                    std::ptr::null_mut(),
                    map_len,
                    libc::PROT_READ | libc::PROT_WRITE,
                    libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                    -1,
                    0,
                )
            };
            if ptr == libc::MAP_FAILED {
                return Err(SymError::Unsupported(format!(
                    "native tape: mmap of {map_len} bytes failed: {}",
                    std::io::Error::last_os_error()
                )));
            }
            // SAFETY: the mapping is `map_len >= bytes.len()` bytes, writable, ours.
            unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), ptr as *mut u8, bytes.len()) };
            let code = Code {
                ptr,
                map_len,
                len: bytes.len(),
            };
            // W^X: never writable and executable at once.
            // SAFETY: `ptr`/`map_len` is our mapping.
            if unsafe { libc::mprotect(ptr, map_len, libc::PROT_READ | libc::PROT_EXEC) } != 0 {
                return Err(SymError::Unsupported(format!(
                    "native tape: mprotect(PROT_EXEC) refused: {}",
                    std::io::Error::last_os_error()
                )));
            }
            Ok(code)
        }

        /// # Safety
        /// `work` must be valid for the slots the program reads and writes.
        pub(super) unsafe fn run(&self, work: *mut f64) {
            // SAFETY: the mapping holds a complete function with this signature.
            let f: extern "C" fn(*mut f64) = unsafe { std::mem::transmute(self.ptr) };
            f(work)
        }
    }

    impl Drop for Code {
        fn drop(&mut self) {
            // SAFETY: our mapping, unmapped once.
            unsafe { libc::munmap(self.ptr, self.map_len) };
        }
    }
}

#[cfg(all(test, target_arch = "x86_64", unix))]
mod tests {
    use super::*;
    use crate::expr::Expr;
    use crate::testing::params;

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn agree(roots: &[Expr], ps: &[Expr], points: &[Vec<f64>]) {
        for tape in [Tape::new(roots, ps), Tape::new_reassociating(roots, ps)] {
            let tape = tape.unwrap();
            let native = NativeTape::new(&tape).unwrap();
            let mut work = vec![0.0; native.work_len()];
            let (mut a, mut b) = (vec![0.0; tape.n_outputs()], vec![0.0; tape.n_outputs()]);
            for x in points {
                tape.eval_into(x, &mut a, &mut work).unwrap();
                // A dirty work buffer must not matter.
                work.fill(f64::NAN);
                native.eval_into(x, &mut b, &mut work).unwrap();
                for (k, (&t, &n)) in a.iter().zip(&b).enumerate() {
                    assert!(
                        same(t, n),
                        "output {k} at {x:?}: tape {t:e} vs native {n:e}"
                    );
                }
            }
        }
    }

    /// More values live at once than there are registers, and values live across calls
    /// (which clobber every register): evictions and read-backs must keep every value.
    #[test]
    fn register_pressure_and_calls_keep_every_value() {
        let ps = params(4, 5, true);
        let (x, y) = (ps[0], ps[1]);
        // 40 values, all live until the end; then sums in two orders, with sines between.
        let vals: Vec<Expr> = (1..=40)
            .map(|k| x * Expr::int(k) + y.powi(2) * Expr::int(k * k) + ps[2] / Expr::int(k + 1))
            .collect();
        let mut fwd = Expr::zero();
        let mut back = Expr::zero();
        for (k, v) in vals.iter().enumerate() {
            fwd = fwd.sin() + *v;
            back = back * Expr::int(3) - vals[39 - k].sqrt() * ps[3];
        }
        let mut roots = vals.clone();
        roots.extend([fwd, back, fwd * back, (fwd - back).abs(), -fwd, fwd.powi(3)]);
        agree(
            &roots,
            &ps,
            &[vec![0.3, 1.2, -0.7, 2.0], vec![1e3, -2e-3, 5.0, 0.1]],
        );
    }

    /// Every operation, every special value: NaN and infinities propagate exactly as in the
    /// interpreter, signed zeros keep their sign.
    #[test]
    fn every_operation_and_special_value_matches_the_interpreter() {
        let ps = params(3, 2, true);
        let (x, y, z) = (ps[0], ps[1], ps[2]);
        let roots = [
            x + y,
            x - y,
            -x,
            x * y * z,
            x / y,
            y.recip(),
            x.powi(2) + y.powi(3) - z.powi(-2) + x.powi(71),
            x.abs().sqrt(),
            x.sin() * y.cos() + z.tan(),
            x.exp() - y.abs().ln(),
            x.pow(y),
            y.atan2(x),
            (x * Expr::int(2) - y * Expr::int(3) + Expr::int(7)) * Expr::rational(1, 3).unwrap(),
            x.abs(),
        ];
        let special = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e308,
        ];
        let mut points = Vec::new();
        for &a in &special {
            for &b in &special {
                points.push(vec![a, b, 0.75]);
                points.push(vec![b, 1.5, a]);
            }
        }
        agree(&roots, &ps, &points);
    }

    #[test]
    fn clones_share_the_code_and_cross_threads() {
        fn send_sync<T: Send + Sync>(_: &T) {}
        let ps = params(2, 3, true);
        let tape = Tape::new(&[(ps[0] * ps[1]).sin()], &ps).unwrap();
        let native = NativeTape::new(&tape).unwrap();
        send_sync(&native);
        let copy = native.clone();
        drop(native);
        let got = std::thread::spawn(move || {
            let mut out = [0.0];
            copy.eval_into(&[0.5, 3.0], &mut out, &mut vec![0.0; copy.work_len()])
                .unwrap();
            out[0]
        })
        .join()
        .unwrap();
        assert_eq!(got, crate::trig::sin(1.5));
    }

    /// No instructions at all: outputs that are parameters and constants.
    #[test]
    fn tapes_without_instructions() {
        let ps = params(2, 1, true);
        let roots = [ps[1], Expr::int(3), ps[0]];
        let tape = Tape::new(&roots, &ps).unwrap();
        assert_eq!(tape.len(), 0);
        let native = NativeTape::new(&tape).unwrap();
        let mut work = vec![0.0; native.work_len()];
        let mut out = [0.0; 3];
        native.eval_into(&[1.5, -2.0], &mut out, &mut work).unwrap();
        assert_eq!(out, [-2.0, 3.0, 1.5]);
        let constant = Tape::new(&[Expr::int(7)], &[]).unwrap();
        let native = NativeTape::new(&constant).unwrap();
        let mut one = [0.0];
        native
            .eval_into(&[], &mut one, &mut vec![0.0; native.work_len()])
            .unwrap();
        assert_eq!(one, [7.0]);
    }

    #[test]
    fn buffers_of_the_wrong_length_are_errors_and_batches_match() {
        let ps = params(2, 1, true);
        let roots = [ps[0] * ps[1], (ps[0] + ps[1]).sin()];
        let tape = Tape::new(&roots, &ps).unwrap();
        let native = NativeTape::new(&tape).unwrap();
        let mut work = vec![0.0; native.work_len()];
        let mut out = [0.0; 2];
        assert!(native.eval_into(&[1.0], &mut out, &mut work).is_err());
        assert!(
            native
                .eval_into(&[1.0, 2.0], &mut out[..1], &mut work)
                .is_err()
        );
        assert!(
            native
                .eval_into(&[1.0, 2.0], &mut out, &mut work[..1])
                .is_err()
        );
        let pts = [0.5, 2.0, -1.0, 3.0, 4.0, 0.25];
        let (mut a, mut b) = ([0.0; 6], [0.0; 6]);
        let mut ws = crate::TapeWorkspace::default();
        tape.eval_batch(&pts, &mut a, &mut ws).unwrap();
        native.eval_batch(&pts, &mut b, &mut ws).unwrap();
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        let bad = [f64::INFINITY, 0.0, 1.0, 1.0];
        let e = native.eval_batch(&bad, &mut b[..4], &mut ws).unwrap_err();
        assert!(e.to_string().contains("output 0 at point 0"), "{e}");
    }
}
