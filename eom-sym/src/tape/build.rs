//! From lowered straight-line code ([`lower`](crate::lower)) to the tape's program: every
//! instruction split into binary operations in the order the lowering defines (sums
//! `((c₀ + c₁x₁) + c₂x₂) + …`, products `((c·f₁)·f₂)·…`), identical operations emitted once,
//! unused ones dropped, then scheduled into runs of one operation.

use super::exec::{Args, Block, Code};
use crate::func::Call;
use crate::lower::{Lowered, Operand, Rhs};
use hashbrown::HashMap;

/// Operand references while building: the slot layout (parameters, constants, instructions)
/// is known only at the end, so references carry their kind in the top bits.
pub(super) const REF_INS: u32 = 0;
pub(super) const REF_PARAM: u32 = 1 << 30;
pub(super) const REF_CONST: u32 = 2 << 30;
pub(super) const REF_MASK: u32 = 3 << 30;

/// One instruction. Unary operations have `b == a`; `c` is a slot only for
/// [`Code::AddMul`] (else 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct Ins {
    pub code: Code,
    pub a: u32,
    pub b: u32,
    pub c: u32,
}

impl Ins {
    /// The references read.
    fn reads(&self) -> [u32; 3] {
        let c = if self.code == Code::AddMul {
            self.c
        } else {
            self.b
        };
        [self.a, self.b, c]
    }
}

/// A product being accumulated: still only its coefficient, or a value.
#[derive(Clone, Copy)]
enum Acc {
    Coef(f64),
    Value(u32),
}

/// The program being built.
#[derive(Default)]
pub(super) struct Builder {
    pub consts: Vec<f64>,
    const_at: HashMap<u64, u32>,
    pub code: Vec<Ins>,
    /// Instruction → its reference, for common subexpressions.
    cse: HashMap<Ins, u32>,
    /// Temporaries of the lowered code → references.
    temp: Vec<u32>,
    /// Temporaries that are a reciprocal `1/d`, with `d` (a product with them multiplies by
    /// `1/d` in one instruction).
    recip_of: HashMap<u32, u32>,
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

    fn operand(&mut self, o: Operand) -> u32 {
        match o {
            Operand::Temp(t) => self.temp[t as usize],
            Operand::Param(k) => REF_PARAM | k,
            Operand::Lit(x) => self.konst(x),
        }
    }

    /// The program of `lowered`, and the references of its roots.
    pub(super) fn program(lowered: &Lowered) -> (Builder, Vec<u32>) {
        let mut b = Builder {
            temp: vec![0; lowered.n_temps as usize],
            ..Builder::default()
        };
        for inst in &lowered.insts {
            let def = inst.def as usize;
            let r = match &inst.rhs {
                Rhs::Sum { c0, terms } => {
                    let terms: Vec<(u32, f64)> =
                        terms.iter().map(|&(x, c)| (b.operand(x), c)).collect();
                    b.sum(*c0, &terms)
                }
                Rhs::Prod { coef, num, den } => b.product(*coef, num, den, inst.def),
                Rhs::Call1(f, x) => {
                    let x = b.operand(*x);
                    let code = match f {
                        Call::Func(f) => Code::Func(*f),
                        _ => Code::Sqrt,
                    };
                    b.unary(code, x)
                }
                Rhs::Call2(f, x, y) => {
                    let (x, y) = (b.operand(*x), b.operand(*y));
                    let code = if *f == Call::Atan2 {
                        Code::Atan2
                    } else {
                        Code::Pow
                    };
                    b.emit(code, x, y, 0)
                }
                Rhs::SinCos(x) => {
                    let x = b.operand(*x);
                    let s = b.unary(Code::Func(crate::Func::Sin), x);
                    b.temp[def + 1] = b.unary(Code::Func(crate::Func::Cos), x);
                    s
                }
            };
            b.temp[def] = r;
        }
        let roots = lowered
            .roots
            .iter()
            .map(|&(o, neg)| {
                let r = b.operand(o);
                if neg { b.unary(Code::Neg, r) } else { r }
            })
            .collect();
        (b, roots)
    }

    /// `c₀ + Σ cᵢ·xᵢ`, accumulated in term order as `((c₀ + c₁x₁) + c₂x₂) + …`, without `c₀`
    /// when it is 0.
    fn sum(&mut self, c0: f64, terms: &[(u32, f64)]) -> u32 {
        let (&(x, c), rest) = terms.split_first().expect("a sum has terms");
        let mut acc = if c0 == 0.0 {
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

    /// `coef · Π num / Π den` as `((coef·n₁)·n₂)·…·(1/(d₁·d₂·…))`; a factor that is a
    /// reciprocal `1/d` is one instruction `acc·(1/d)`.
    fn product(&mut self, coef: f64, num: &[Operand], den: &[Operand], def: u32) -> u32 {
        if coef == 1.0 && num.is_empty() && den.len() == 1 {
            let d = self.operand(den[0]);
            self.recip_of.insert(def, d);
            return self.unary(Code::Recip, d);
        }
        let mut acc = Acc::Coef(coef);
        for &x in num {
            acc = match x {
                Operand::Temp(t) if self.recip_of.contains_key(&t) => {
                    let d = self.recip_of[&t];
                    self.times_recip(acc, d)
                }
                _ => {
                    let x = self.operand(x);
                    self.times(acc, x)
                }
            };
        }
        if let Some((&d0, rest)) = den.split_first() {
            let mut d = self.operand(d0);
            for &x in rest {
                let x = self.operand(x);
                d = self.emit(Code::Mul, d, x, 0);
            }
            acc = self.times_recip(acc, d);
        }
        match acc {
            Acc::Value(v) => v,
            Acc::Coef(c) => self.konst(c),
        }
    }

    /// `acc · f` for the next factor `f` of a product.
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

    /// `acc · (1/d)`.
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

    /// Drops the instructions no root needs (reciprocals whose every use multiplies by them
    /// directly) and renumbers the rest; returns the new references of `roots`.
    pub(super) fn prune(&mut self, roots: &[u32]) -> Vec<u32> {
        let n = self.code.len();
        let mut live = vec![false; n];
        for &r in roots {
            if r & REF_MASK == REF_INS {
                live[r as usize] = true;
            }
        }
        for i in (0..n).rev() {
            if live[i] {
                for r in self.code[i].reads() {
                    if r & REF_MASK == REF_INS {
                        live[r as usize] = true;
                    }
                }
            }
        }
        let mut new = vec![u32::MAX; n];
        let mut kept = Vec::with_capacity(n);
        for (i, ins) in self.code.iter().enumerate() {
            if live[i] {
                new[i] = kept.len() as u32;
                kept.push(*ins);
            }
        }
        let map = |r: u32| {
            if r & REF_MASK == REF_INS {
                new[r as usize]
            } else {
                r
            }
        };
        for ins in &mut kept {
            ins.a = map(ins.a);
            ins.b = map(ins.b);
            if ins.code == Code::AddMul {
                ins.c = map(ins.c);
            }
        }
        self.code = kept;
        self.cse.clear();
        roots.iter().map(|&r| map(r)).collect()
    }

    /// Fewer kinds of operation make longer runs (see [`Block`]): `a ± b` is `a + (±1)·b` and
    /// `1/x` is `1·(1/x)`, exactly.
    pub(super) fn normalise(&mut self) {
        let (one, minus_one) = (self.konst(1.0), self.konst(-1.0));
        for ins in &mut self.code {
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
                Code::Recip => Ins {
                    code: Code::MulRecip,
                    a: one,
                    ..*ins
                },
                _ => *ins,
            };
        }
    }
}

/// A topological order of `code` (indices) that groups equal operations into runs, and the
/// runs: list scheduling that continues with the current operation while one is ready and
/// otherwise switches to the operation with the most ready instructions.
pub(super) fn schedule(code: &[Ins]) -> (Vec<u32>, Vec<Block>) {
    let n = code.len();
    let distinct = |ins: &Ins| {
        let mut d = ins.reads();
        d.sort_unstable();
        let mut out = [u32::MAX; 3];
        let mut k = 0;
        for (j, &r) in d.iter().enumerate() {
            if r & REF_MASK == REF_INS && (j == 0 || d[j - 1] != r) {
                out[k] = r;
                k += 1;
            }
        }
        (out, k)
    };
    // Successors in compressed rows; `pending[i]` counts unfinished predecessors.
    let mut pending = vec![0u32; n];
    let mut count = vec![0u32; n + 1];
    for ins in code {
        let (d, k) = distinct(ins);
        for &r in &d[..k] {
            count[r as usize + 1] += 1;
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let mut succ = vec![0u32; count[n] as usize];
    let mut fill = count.clone();
    for (i, ins) in code.iter().enumerate() {
        let (d, k) = distinct(ins);
        for &r in &d[..k] {
            succ[fill[r as usize] as usize] = i as u32;
            fill[r as usize] += 1;
            pending[i] += 1;
        }
    }
    let mut ready: Vec<std::collections::VecDeque<u32>> = vec![Default::default(); Code::COUNT];
    for (i, ins) in code.iter().enumerate() {
        if pending[i] == 0 {
            ready[ins.code.index()].push_back(i as u32);
        }
    }
    let mut order = Vec::with_capacity(n);
    let mut blocks: Vec<Block> = Vec::new();
    while order.len() < n {
        let cur = (0..Code::COUNT)
            .max_by_key(|&c| ready[c].len())
            .expect("operations");
        let start = order.len();
        while let Some(i) = ready[cur].pop_front() {
            order.push(i);
            for &s in &succ[count[i as usize] as usize..count[i as usize + 1] as usize] {
                pending[s as usize] -= 1;
                if pending[s as usize] == 0 {
                    ready[code[s as usize].code.index()].push_back(s);
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

/// The operand slots of the scheduled program: parameters first, then constants, then the
/// instructions in `order`.
pub(super) fn layout(
    code: &[Ins],
    order: &[u32],
    n_params: u32,
    n_consts: u32,
) -> (Vec<Args>, impl Fn(u32) -> u32) {
    let base = n_params + n_consts;
    let mut new_pos = vec![0u32; code.len()];
    for (k, &i) in order.iter().enumerate() {
        new_pos[i as usize] = k as u32;
    }
    let slot = move |r: u32| match r & REF_MASK {
        REF_PARAM => r & !REF_MASK,
        REF_CONST => n_params + (r & !REF_MASK),
        _ => base + new_pos[r as usize],
    };
    let args = order
        .iter()
        .map(|&i| {
            let ins = code[i as usize];
            Args {
                a: slot(ins.a),
                b: slot(ins.b),
                c: if ins.code == Code::AddMul {
                    slot(ins.c)
                } else {
                    0
                },
            }
        })
        .collect();
    (args, slot)
}
