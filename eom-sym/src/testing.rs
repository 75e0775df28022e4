//! Generators of random expressions for property tests and benches (not part of the stable
//! API).

use crate::expr::Expr;
use crate::pool::{Assumption, ParamInfo};

/// A small deterministic generator (SplitMix64), so benches and tests need no dependency.
#[derive(Clone, Debug)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Declare `n` parameters `p0, p1, …` with nominal values in [0.5, 2) (positive ones when
/// `positive`).
pub fn params(n: usize, seed: u64, positive: bool) -> Vec<Expr> {
    let mut rng = SplitMix(seed);
    (0..n)
        .map(|i| {
            Expr::new_param(ParamInfo {
                name: format!("p{i}"),
                nominal: rng.uniform(0.5, 2.0),
                unit: None,
                description: None,
                assume: if positive {
                    Assumption::Positive
                } else {
                    Assumption::Real
                },
            })
            .expect("valid parameter")
        })
        .collect()
}

/// One step of [`random_dag`]: a new node combining entries of `pool`, preferring recent ones
/// so that depth grows while old ones keep being reused (sharing).
pub fn random_node(rng: &mut SplitMix, pool: &[Expr]) -> Expr {
    let pick = |rng: &mut SplitMix| {
        let n = pool.len();
        if rng.below(3) == 0 {
            pool[rng.below(n)]
        } else {
            pool[n - 1 - rng.below(n.min(32))]
        }
    };
    let a = pick(rng);
    let b = pick(rng);
    match rng.below(12) {
        0..=3 => a + b,
        4 => a - b,
        5..=7 => a * b,
        8 => a / (Expr::one() + b * b),
        9 => a.sin(),
        10 => (Expr::one() + a * a).sqrt(),
        _ => a.powi(2 + rng.below(2) as i64),
    }
}

/// A random DAG of about `n_nodes` unique nodes over `params`, with heavy sharing (each new
/// node combines earlier nodes). Returns `n_roots` roots drawn from the last nodes built.
/// Values stay finite at positive parameter values (divisions are by `1 + x²`, roots and logs
/// of `1 + x²`).
pub fn random_dag(params: &[Expr], n_nodes: usize, n_roots: usize, seed: u64) -> Vec<Expr> {
    let mut rng = SplitMix(seed);
    let mut pool: Vec<Expr> = params.to_vec();
    for k in 1..=4 {
        pool.push(Expr::int(k));
    }
    let start = crate::ExprPool::current().stats().nodes;
    let mut guard = 0;
    while crate::ExprPool::current().stats().nodes < start + n_nodes && guard < 20 * n_nodes {
        guard += 1;
        let e = random_node(&mut rng, &pool);
        if e.check().is_ok() && !e.is_number() {
            pool.push(e);
        }
    }
    let n = pool.len();
    (0..n_roots)
        .map(|k| pool[n - 1 - (k * 7) % n.min(200)])
        .collect()
}

/// [`random_dag`] with one change: a new node is kept only if its nominal value lies in
/// [1e-6, 1e6], so that evaluation at the nominal point computes finite numbers nearly
/// throughout (`random_dag` overflows to ±inf in most nodes by repeated squaring; here a
/// partial product may still overflow where a large and a small factor meet: 2 of the
/// 25 258 instructions of the benchmark DAG). Grows until the
/// roots' DAG has `n_nodes` unique nodes. The benchmark DAG of the tape (`benches/core.rs`).
pub fn bounded_dag(params: &[Expr], n_nodes: usize, n_roots: usize, seed: u64) -> Vec<Expr> {
    let mut rng = SplitMix(seed);
    let mut pool: Vec<Expr> = params.to_vec();
    let roots_of = |pool: &Vec<Expr>| -> Vec<Expr> {
        let n = pool.len();
        (0..n_roots)
            .map(|k| pool[n - 1 - (k * 7) % n.min(200)])
            .collect()
    };
    let mut guard = 0;
    while guard < 50 * n_nodes {
        if guard % 256 == 0 && Expr::dag_size(&roots_of(&pool)) >= n_nodes {
            break;
        }
        guard += 1;
        let e = random_node(&mut rng, &pool);
        let v = e.nominal().abs();
        if e.check().is_ok() && !e.is_number() && (1e-6..=1e6).contains(&v) {
            pool.push(e);
        }
    }
    roots_of(&pool)
}
