//! Benches of `eom_sym::simplify`.
//!
//! * `egg/random_dag_2000`: the bounded egg pass on a 36-root random DAG of about 2 000 unique
//!   nodes (`testing::random_dag`), default budget (20 000 e-nodes, 20 iterations, 500 ms,
//!   stall K = 4).
//! * `egg/atba_6x6_joint` and `egg/atba_6x6_entry_by_entry`: `C = AᵀBA` for a sparse 6×6 `A`,
//!   all 36 entries in one e-graph against one pass per entry (the baseline of the same run).
//! * `rational/*`: the rational normal form on the textbook cases and one medium case.
//!
//! Before timing, each egg case prints one line: DAG size, e-nodes, iterations, stop reason
//! and the weighted DAG cost before and after.
//!
//! `cargo bench -p eom-sym --bench simplify`

use criterion::{Criterion, criterion_group, criterion_main};
use eom_sym::simplify::{Simplifier, normalize_rational};
use eom_sym::testing::{SplitMix, params, random_dag};
use eom_sym::{Expr, SparseMatrix};
use std::hint::black_box;

fn atba(seed: u64) -> Vec<Expr> {
    let p = params(16, seed, true);
    let mut rng = SplitMix(seed);
    let n = 6;
    let mut a = SparseMatrix::zeros(n, n);
    let mut b = SparseMatrix::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            if rng.uniform(0.0, 1.0) < 0.55 {
                let x = p[rng.below(16)];
                let y = p[rng.below(16)];
                let v = match rng.below(4) {
                    0 => x,
                    1 => x * y,
                    2 => x + y,
                    _ => -Expr::int(2) * x,
                };
                a.set(i, j, v);
            }
            if j >= i && rng.uniform(0.0, 1.0) < 0.5 {
                let v = p[rng.below(16)];
                b.set(i, j, v);
                b.set(j, i, v);
            }
        }
    }
    let c = a.transpose().mul(&b).expect("6×6").mul(&a).expect("6×6");
    c.iter().map(|e| e.2).collect()
}

fn report(name: &str, roots: &[Expr]) {
    let out = Simplifier::default().run(roots).expect("valid roots");
    eprintln!(
        "{name}: {} roots, DAG {} nodes | e-nodes {}, classes {}, iterations {}, stop {:?} | cost {} -> {} (kept {}) | ops {} -> {} | rewrite {:.1} ms, total {:.1} ms",
        roots.len(),
        Expr::dag_size(roots),
        out.egraph_nodes,
        out.egraph_classes,
        out.iterations,
        out.stop,
        out.cost_before,
        out.cost_after,
        out.kept,
        out.ops_before.total(),
        out.ops_after.total(),
        out.rewrite_time.as_secs_f64() * 1e3,
        out.time.as_secs_f64() * 1e3,
    );
}

fn egg(c: &mut Criterion) {
    let p = params(10, 1, true);
    let big = random_dag(&p, 5000, 36, 1);
    report("egg/random_dag_2000", &big);
    let small = atba(1);
    report("egg/atba_6x6_joint", &small);

    let mut g = c.benchmark_group("egg");
    g.sample_size(20);
    g.bench_function("random_dag_2000", |b| {
        b.iter(|| Simplifier::default().run(black_box(&big)).expect("valid"))
    });
    g.bench_function("atba_6x6_joint", |b| {
        b.iter(|| Simplifier::default().run(black_box(&small)).expect("valid"))
    });
    g.bench_function("atba_6x6_entry_by_entry", |b| {
        b.iter(|| {
            small
                .iter()
                .map(|&e| {
                    Simplifier::default()
                        .run(black_box(&[e]))
                        .expect("valid")
                        .roots[0]
                })
                .collect::<Vec<_>>()
        })
    });
    g.finish();
}

fn rational(c: &mut Criterion) {
    let m = Expr::param("m", 2.0).expect("name");
    let k = Expr::param("k", 8.0).expect("name");
    let a = Expr::param("a", 1.5).expect("name");
    let b = Expr::param("b", 0.5).expect("name");
    let x = Expr::param("x", 0.3).expect("name");
    let cases = [
        ("mk_plus_km_over_2m", (m * k + k * m) / (Expr::int(2) * m)),
        (
            "a2_minus_b2_over_a_minus_b",
            (a.powi(2) - b.powi(2)) / (a - b),
        ),
        ("recip_a_plus_recip_b", a.recip() + b.recip()),
        // medium: (a + b + x)^4 (a − b) / ((a + b + x)^2 (a² − b²)) = (a + b + x)² / (a + b)
        (
            "medium_degree_6",
            (a + b + x).powi(4) * (a - b) / ((a + b + x).powi(2) * (a.powi(2) - b.powi(2))),
        ),
    ];
    for (name, e) in &cases {
        eprintln!(
            "rational/{name}: {e}  ->  {}",
            normalize_rational(*e).expect("valid")
        );
    }
    let mut g = c.benchmark_group("rational");
    for (name, e) in cases {
        g.bench_function(name, |bch| {
            bch.iter(|| normalize_rational(black_box(e)).expect("valid"))
        });
    }
    g.finish();
}

criterion_group!(benches, egg, rational);
criterion_main!(benches);
