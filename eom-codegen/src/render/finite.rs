//! The finiteness test of the fast path: by magnitude bounds when they exist, else on the
//! values no other tested value depends on.

use eom_sym::lower::{Inst, Operand, Rhs};
use eom_sym::{Call, Func};
use std::collections::HashSet;

/// What the fast path tests instead of the entries when every value's magnitude can be
/// bounded (see [`magnitude_bounds`]).
pub(super) struct Bounds {
    /// Bound on each parameter's magnitude (a power of two), tested on two partial sums.
    pub(super) hi: f64,
    /// Parameters (positions) the function reads.
    pub(super) params: Vec<u32>,
    /// Divisors, each tested `|d| ≥ 1/hi`.
    pub(super) dens: Vec<Operand>,
    /// Square-root arguments, each tested `x ≥ 0`.
    pub(super) roots: Vec<Operand>,
}

/// A finiteness test that waits for no entry, when one exists (`f64` only).
///
/// If every parameter has |p| < 2^M and every divisor |d| ≥ 2^−M (and every square-root
/// argument is ≥ 0, NaN failing every test), then by induction over the instructions every
/// value has |v| ≤ 2^E(v), with E(param) = M, E(c·Π x / Π d) = log₂|c| + Σ E(x) + M·#d,
/// E(c₀ + Σ cᵢ xᵢ) = max(log₂|c₀|, log₂|cᵢ| + E(xᵢ)) + log₂(terms + 1), E(√x) = E(x)/2 and
/// E(sin), E(cos) = 0. When the largest E stays below 1000 (far from 1024; rounding adds
/// at most a few ulps per operation), no value overflows, no divisor is zero and no NaN can
/// arise, so every entry and pivot is finite without testing them — and the tests read
/// parameters and divisors only, which are ready long before the entries. The largest M
/// (from 60 down to 10) that passes is used; `None` (test the entries instead) when none
/// does, or the function calls anything else (`tan`, `exp`, `ln`, powers, `atan2`).
pub(super) fn magnitude_bounds(insts: &[Inst], musts: &[Operand]) -> Option<Bounds> {
    let mut params: Vec<u32> = Vec::new();
    let mut dens: Vec<Operand> = Vec::new();
    let mut roots: Vec<Operand> = Vec::new();
    let note_param = |o: &Operand, params: &mut Vec<u32>| {
        if let Operand::Param(k) = o
            && !params.contains(k)
        {
            params.push(*k);
        }
    };
    for inst in insts {
        match &inst.rhs {
            Rhs::Sum { .. } | Rhs::SinCos(_) => {}
            Rhs::Prod { den, .. } => {
                for d in den {
                    if !matches!(d, Operand::Lit(_)) && !dens.contains(d) {
                        dens.push(*d);
                    }
                }
            }
            Rhs::Call1(Call::Sqrt, x) => {
                if !matches!(x, Operand::Lit(_)) && !roots.contains(x) {
                    roots.push(*x);
                }
            }
            Rhs::Call1(Call::Func(Func::Sin | Func::Cos | Func::Abs), _) => {}
            _ => return None,
        }
        for o in inst.rhs.operands() {
            note_param(&o, &mut params);
        }
    }
    for o in musts {
        note_param(o, &mut params);
    }
    params.sort_unstable();
    let log2 = |c: f64| if c == 0.0 { -1100.0 } else { c.abs().log2() };
    let fits = |m: f64| -> bool {
        let mut e: Vec<f64> = Vec::new();
        let of = |o: &Operand, e: &Vec<f64>| match o {
            Operand::Temp(t) => e.get(*t as usize).copied().unwrap_or(f64::INFINITY),
            Operand::Param(_) => m,
            Operand::Lit(c) => log2(*c),
        };
        for inst in insts {
            let v = match &inst.rhs {
                Rhs::Sum { c0, terms } => {
                    let top = terms
                        .iter()
                        .map(|(x, c)| log2(*c) + of(x, &e))
                        .fold(log2(*c0), f64::max);
                    top + ((terms.len() + 1) as f64).log2()
                }
                Rhs::Prod { coef, num, den } => {
                    log2(*coef) + num.iter().map(|x| of(x, &e)).sum::<f64>() + m * den.len() as f64
                }
                Rhs::Call1(Call::Sqrt, x) => of(x, &e) / 2.0 + 1.0,
                Rhs::Call1(Call::Func(Func::Abs), x) => of(x, &e),
                Rhs::Call1(Call::Func(Func::Sin | Func::Cos), _) | Rhs::SinCos(_) => 0.0,
                _ => return false,
            };
            if v.is_nan() || v > 1000.0 {
                return false;
            }
            for d in 0..inst.rhs.defs() {
                let t = (inst.def + d) as usize;
                if e.len() <= t {
                    e.resize(t + 1, f64::INFINITY);
                }
                e[t] = v;
            }
        }
        true
    };
    let m = [60, 50, 40, 30, 20, 16, 12, 10]
        .into_iter()
        .find(|&m| fits(f64::from(m)))?;
    Some(Bounds {
        hi: 2f64.powi(m),
        params,
        dens,
        roots,
    })
}

/// Which of `musts` (values that must be finite) the fast path has to test: `false` for a
/// value that flows into another tested value through operations that keep a NaN or an
/// infinity, since then the tested value is not finite either.
///
/// The operations that keep them (for every value of the other operands, as IEEE 754
/// arithmetic defines them): `+`, `−`, `·` (∞·0 is NaN), the dividend of `/`, `√`, `sin`,
/// `cos`, `tan`, `ln`, `|·|`, and integer powers (products). Those that may not: the divisor
/// (`x/∞ = 0`), `exp` (`exp(−∞) = 0`), general powers and `atan2`. So if every tested value
/// is finite, so is every value of `musts`: testing fewer values changes no result, it
/// shortens the fast path. Walks the instructions backwards (consumers before producers).
pub(super) fn finiteness_sinks(insts: &[Inst], musts: &[Operand]) -> Vec<bool> {
    use eom_sym::lower::OpKey;
    let must: HashSet<OpKey> = musts.iter().map(|o| o.key()).collect();
    let mut covered: HashSet<OpKey> = HashSet::new();
    let mut tested: HashSet<OpKey> = HashSet::new();
    for inst in insts.iter().rev() {
        let mut live = false;
        for d in 0..inst.rhs.defs() {
            let k = OpKey::Temp(inst.def + d);
            if covered.contains(&k) {
                live = true;
            } else if must.contains(&k) {
                tested.insert(k);
                covered.insert(k);
                live = true;
            }
        }
        if !live {
            continue;
        }
        let keeps: Vec<Operand> = match &inst.rhs {
            Rhs::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
            Rhs::Prod { num, .. } => num.clone(),
            Rhs::Call1(f, x) if f.keeps_non_finite() => vec![*x],
            Rhs::Call1(..) => Vec::new(),
            Rhs::SinCos(x) => vec![*x],
            Rhs::Call2(..) => Vec::new(),
        };
        for o in keeps {
            covered.insert(o.key());
        }
    }
    musts
        .iter()
        .map(|o| match o {
            Operand::Lit(_) => false,
            Operand::Temp(_) => tested.contains(&o.key()),
            // Parameters are defined by no instruction: tested unless a tested value uses them.
            Operand::Param(_) => !covered.contains(&o.key()),
        })
        .collect()
}
