//! Benches of the expression core: interning throughput, tape evaluation, and the recursive
//! evaluators as the baseline in the same run.
//!
//! `cargo bench -p eom-sym --bench core`
//!
//! * `intern/create`: a random program of ~23 000 constructor calls (`+ − · / sin √ xⁿ`, the
//!   mix of `testing::random_dag`) run in a fresh pool, where most nodes are new;
//! * `intern/lookup`: the same program again in the warm pool, where every node exists.
//!
//!   Throughput is in *insertions*: calls that create or look up a node in the hash-consing
//!   table (`PoolStats::interns`). One constructor call makes several — the node itself plus
//!   its numeric coefficients and exponents (one per term of a sum or factor of a product) —
//!   about 6.3 here; the counts (calls, insertions, nodes created) are printed once so that
//!   constructor calls per second can be derived. Target: ≥ 5·10⁶ insertions per second.
//! * `eval/*`: one evaluation of the 50 roots of a random DAG of 10 199 unique nodes over 20
//!   parameters, built with the operation mix of `testing::random_dag` (`testing::random_node`:
//!   `+ − · /(1+b²) sin √(1+a²) powi`) but keeping only nodes whose nominal value lies in
//!   [1e-6, 1e6], so that (nearly) every instruction computes a finite number (`random_dag` itself
//!   overflows to ±inf in about two thirds of its nodes by repeated squaring, which measures
//!   libm's fast paths for inf/NaN rather than the tape). Throughput is in unique DAG nodes
//!   (numbers included), so the time per element is the time per node: `tape_eval_into`
//!   (target ≤ 2 ns per node) against `eval_generic::<f64>` (the recursive reference) and
//!   `eval_generic::<Dd>` (double-double); the tape's instruction count (binary operations
//!   after common subexpressions) is printed once. `tape_reassociating_eval_into`: the same
//!   roots compiled by `Tape::new_reassociating` (fewer instructions; its values differ from
//!   the others in rounding, and by much on this ill-conditioned DAG, which changes the cost
//!   of `sin` too). `tape_eval_batch64` evaluates 64 points per call (in chunks of 16),
//!   throughput in nodes × points: the time per node per point.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use eom_sym::testing::{SplitMix, bounded_dag, params};
use eom_sym::{Dd, Expr, ExprPool, Tape, TapeWorkspace, eval_generic};
use std::hint::black_box;
use std::time::{Duration, Instant};

#[derive(Clone, Copy)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Sin,
    Powi(i64),
    Sqrt,
}

impl Op {
    /// Smart-constructor calls of one step.
    fn calls(self) -> u64 {
        match self {
            Op::Sub | Op::Div => 2,
            _ => 1,
        }
    }
}

/// A deterministic program of constructor calls over a growing list of values, in the style
/// of `testing::random_dag`: operands prefer recent values (depth grows) but reuse old ones.
struct Program {
    steps: Vec<(Op, usize, usize)>,
    calls: u64,
}

fn program(n_steps: usize, seed: u64) -> Program {
    let mut rng = SplitMix(seed);
    let mut steps = Vec::with_capacity(n_steps);
    let mut calls = 0;
    // Operand indices refer to the values list at the time of the step; its length is only
    // known when running (numbers are not kept), so store picks as offsets from the end.
    for _ in 0..n_steps {
        let op = match rng.below(12) {
            0..=3 => Op::Add,
            4 => Op::Sub,
            5..=7 => Op::Mul,
            8 => Op::Div,
            9 => Op::Sin,
            10 => Op::Sqrt,
            _ => Op::Powi(2 + rng.below(2) as i64),
        };
        let pick = |rng: &mut SplitMix| {
            if rng.below(3) == 0 {
                usize::MAX - rng.below(1 << 20)
            } else {
                rng.below(32)
            }
        };
        let (a, b) = (pick(&mut rng), pick(&mut rng));
        calls += op.calls();
        steps.push((op, a, b));
    }
    Program { steps, calls }
}

/// Run the program; returns the values built (so that nothing is optimised away).
fn run(prog: &Program, params: &[Expr]) -> Vec<Expr> {
    let mut vals: Vec<Expr> = params.to_vec();
    vals.reserve(prog.steps.len());
    for &(op, a, b) in &prog.steps {
        let n = vals.len();
        // Offsets: small ones count back from the end, huge ones pick anywhere (uniformly).
        let at = |k: usize| {
            if k < 32 {
                vals[n - 1 - k % n]
            } else {
                vals[(usize::MAX - k) % n]
            }
        };
        let (x, y) = (at(a), at(b));
        let e = match op {
            Op::Add => x + y,
            Op::Sub => x - y,
            Op::Mul => x * y,
            // y is symbolic (numbers are not kept), so never a structural zero.
            Op::Div => x / y,
            Op::Sin => x.sin(),
            Op::Powi(k) => x.powi(k),
            Op::Sqrt => x.sqrt(),
        };
        // Keep only symbolic results: numbers would grow into huge rationals under repeated
        // powers, and invalid nodes (not hash-consed) would make the lookup run create nodes.
        if !e.is_number() && !e.is_invalid() {
            vals.push(e);
        }
    }
    vals
}

const STEPS: usize = 20_000;

fn intern(c: &mut Criterion) {
    let prog = program(STEPS, 42);
    let mut g = c.benchmark_group("intern");
    g.measurement_time(Duration::from_secs(8));

    // Fresh pool per iteration (dropped afterwards). Only the program run is timed.
    let fresh = |prog: &Program| -> (Duration, usize, u64) {
        let pool = ExprPool::new();
        pool.enter(|| {
            let ps = params(20, 7, false);
            let before = pool.stats();
            let t = Instant::now();
            let v = run(prog, &ps);
            let dt = t.elapsed();
            black_box(v);
            let after = pool.stats();
            (
                dt,
                after.nodes - before.nodes,
                after.interns - before.interns,
            )
        })
    };
    let (_, created, interns) = fresh(&prog);
    eprintln!(
        "intern: {STEPS} steps, {} constructor calls, {interns} insertions ({:.2} per call), \
         {created} nodes created in a fresh pool",
        prog.calls,
        interns as f64 / prog.calls as f64,
    );
    g.throughput(Throughput::Elements(interns));
    g.bench_function("create", |b| {
        b.iter_custom(|iters| (0..iters).map(|_| fresh(&prog).0).sum());
    });

    let ps = params(20, 7, false);
    let first = run(&prog, &ps);
    let before = ExprPool::current().stats();
    let again = run(&prog, &ps);
    let after = ExprPool::current().stats();
    assert_eq!(first, again, "the program is deterministic");
    assert_eq!(
        after.nodes, before.nodes,
        "a second run only finds existing nodes"
    );
    assert_eq!(
        after.interns - before.interns,
        interns,
        "same insertions as in a fresh pool"
    );
    g.bench_function("lookup", |b| {
        b.iter(|| black_box(run(&prog, black_box(&ps))))
    });
    g.finish();
}

fn eval(c: &mut Criterion) {
    let ps = params(20, 7, true);
    // (`testing::random_dag` overflows to ±inf in most nodes at the nominal point, which
    // measures libm's slow paths rather than the tape: use the bounded variant.)
    let bounded = bounded_dag(&ps, 10_000, 50, 11);
    eval_group(c, "eval", &ps, &bounded);
}

fn eval_group(c: &mut Criterion, name: &str, ps: &[Expr], roots: &[Expr]) {
    let tape = Tape::new(roots, ps).expect("tape");
    let values: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
    // eval_generic looks parameters up by pool index.
    let n_pool = ps.iter().map(|p| p.param_index().unwrap()).max().unwrap() as usize + 1;
    let mut by_index = vec![f64::NAN; n_pool];
    for (p, v) in ps.iter().zip(&values) {
        by_index[p.param_index().unwrap() as usize] = *v;
    }
    let mut work = vec![0.0; tape.work_len()];
    let mut out = vec![0.0; tape.n_outputs()];
    tape.eval_into(&values, &mut out, &mut work).unwrap();
    let non_finite = work.iter().filter(|v| !v.is_finite()).count();
    eprintln!(
        "{name}: DAG of {} unique nodes ({} arithmetic operations; {} tape instructions, \
         {non_finite} work slots non-finite at the nominal point), {} roots, {} parameters",
        Expr::dag_size(roots),
        Expr::op_count(roots).total(),
        tape.len(),
        roots.len(),
        ps.len()
    );
    // The tape keeps the recursive evaluator's order of operations: the same values exactly
    // (this DAG's values are mostly rounding noise, so any reassociation would show).
    let g64 = eval_generic::<f64>(roots, |i| Some(by_index[i as usize])).unwrap();
    for (a, b) in out.iter().zip(&g64) {
        assert!(a.to_bits() == b.to_bits(), "{a} vs {b}");
    }

    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(tape.n_nodes() as u64));
    g.bench_function("tape_eval_into", |b| {
        b.iter(|| {
            tape.eval_into(black_box(&values), &mut out, &mut work)
                .unwrap()
        })
    });
    // The same roots with reassociating sharing: fewer instructions, other rounding (the
    // values differ, by much on this ill-conditioned DAG, so the cost of libm may too).
    let shared = Tape::new_reassociating(roots, ps).expect("tape");
    let mut swork = vec![0.0; shared.work_len()];
    eprintln!(
        "{name}: reassociating tape of {} instructions",
        shared.len()
    );
    g.bench_function("tape_reassociating_eval_into", |b| {
        b.iter(|| {
            shared
                .eval_into(black_box(&values), &mut out, &mut swork)
                .unwrap()
        })
    });
    if out.iter().all(|v| v.is_finite()) {
        const POINTS: usize = 64;
        // The same point 64 times: the random DAG is chaotic (a relative change of 1e-7 in
        // the parameters already overflows some nodes), and the kernel's cost does not depend
        // on the values.
        let batch: Vec<f64> = (0..POINTS).flat_map(|_| values.iter().copied()).collect();
        let mut ws = TapeWorkspace::default();
        let mut bout = vec![0.0; POINTS * tape.n_outputs()];
        tape.eval_batch(&batch, &mut bout, &mut ws)
            .expect("finite batch");
        g.throughput(Throughput::Elements((tape.n_nodes() * POINTS) as u64));
        g.bench_function("tape_eval_batch64", |b| {
            b.iter(|| {
                tape.eval_batch(black_box(&batch), &mut bout, &mut ws)
                    .unwrap()
            })
        });
        g.throughput(Throughput::Elements(tape.n_nodes() as u64));
    }
    g.bench_function("eval_generic_f64", |b| {
        b.iter(|| eval_generic::<f64>(black_box(roots), |i| Some(by_index[i as usize])).unwrap())
    });
    g.bench_function("eval_generic_dd", |b| {
        b.iter(|| {
            eval_generic::<Dd>(black_box(roots), |i| {
                Some(Dd::from_f64(by_index[i as usize]))
            })
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, intern, eval);
criterion_main!(benches);
