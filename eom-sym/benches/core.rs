//! Benches of the expression core: interning throughput, tape evaluation, and the recursive
//! evaluators as the baseline in the same run.
//!
//! `cargo bench -p eom-sym --bench core`
//!
//! * `intern/create`: constructor calls per second in a fresh pool (almost every call creates
//!   a node); the number of nodes created per call is printed once.
//! * `intern/lookup`: the same calls again in the warm pool (every call finds its node).
//!
//!   An *insertion* is one smart-constructor call that returns a node (`a + b`, `a·b`,
//!   `sin a`, `aⁿ`, `√a`; `a − b` and `a/b` are two calls each: the negation or the reciprocal,
//!   then the sum or the product). Target: ≥ 5·10⁶ per second.
//! * `eval/*`: one evaluation of the 50 roots of a 10 000-node random DAG over 20 parameters;
//!   throughput in tape instructions (= unique nodes), so the time per element is the time per
//!   node. `tape_eval_into` (target ≤ 2 ns per node) against `eval_generic::<f64>` (the
//!   recursive reference) and `eval_generic::<Dd>` (double-double).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use eom_sym::testing::{SplitMix, params, random_dag};
use eom_sym::{Dd, Expr, ExprPool, Tape, eval_generic};
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
            if rng.below(3) == 0 { usize::MAX - rng.below(1 << 20) } else { rng.below(32) }
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
        let at = |k: usize| if k < 32 { vals[n - 1 - k % n] } else { vals[(usize::MAX - k) % n] };
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
    g.throughput(Throughput::Elements(prog.calls));
    g.measurement_time(Duration::from_secs(8));

    // Fresh pool per iteration: a new thread has a new (thread-local) pool. Only the program
    // run is timed.
    let fresh = |prog: &Program| -> (Duration, usize) {
        std::thread::scope(|s| {
            s.spawn(|| {
                let ps = params(20, 7, false);
                let before = ExprPool::stats().nodes;
                let t = Instant::now();
                let v = run(prog, &ps);
                let dt = t.elapsed();
                black_box(v);
                (dt, ExprPool::stats().nodes - before)
            })
            .join()
            .expect("bench thread")
        })
    };
    let (_, created) = fresh(&prog);
    eprintln!(
        "intern: {} steps, {} constructor calls, {} nodes created in a fresh pool ({:.2} per call)",
        STEPS,
        prog.calls,
        created,
        created as f64 / prog.calls as f64
    );
    g.bench_function("create", |b| {
        b.iter_custom(|iters| (0..iters).map(|_| fresh(&prog).0).sum());
    });

    let ps = params(20, 7, false);
    let first = run(&prog, &ps);
    let before = ExprPool::stats().nodes;
    let again = run(&prog, &ps);
    assert_eq!(first, again, "the program is deterministic");
    assert_eq!(ExprPool::stats().nodes, before, "a second run only finds existing nodes");
    g.bench_function("lookup", |b| b.iter(|| black_box(run(&prog, black_box(&ps)))));
    g.finish();
}

fn eval(c: &mut Criterion) {
    let ps = params(20, 7, true);
    let roots = random_dag(&ps, 10_000, 50, 11);
    let tape = Tape::new(&roots, &ps).expect("tape");
    let values: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
    // eval_generic looks parameters up by pool index.
    let n_pool = ps.iter().map(|p| p.param_index().unwrap()).max().unwrap() as usize + 1;
    let mut by_index = vec![f64::NAN; n_pool];
    for (p, v) in ps.iter().zip(&values) {
        by_index[p.param_index().unwrap() as usize] = *v;
    }
    eprintln!(
        "eval: DAG of {} unique nodes ({} tape instructions), {} roots, {} parameters",
        Expr::dag_size(&roots),
        tape.len(),
        roots.len(),
        ps.len()
    );
    let mut work = vec![0.0; tape.work_len()];
    let mut out = vec![0.0; tape.n_outputs()];
    // The three evaluators agree (the property tests check this in general).
    tape.eval_into(&values, &mut out, &mut work).unwrap();
    let g64 = eval_generic::<f64>(&roots, |i| Some(by_index[i as usize])).unwrap();
    assert!(out.iter().zip(&g64).all(|(a, b)| (a - b).abs() <= 1e-9 * b.abs().max(1.0)));

    let mut g = c.benchmark_group("eval");
    g.throughput(Throughput::Elements(tape.len() as u64));
    g.bench_function("tape_eval_into", |b| {
        b.iter(|| tape.eval_into(black_box(&values), &mut out, &mut work).unwrap())
    });
    g.bench_function("eval_generic_f64", |b| {
        b.iter(|| eval_generic::<f64>(black_box(&roots), |i| Some(by_index[i as usize])).unwrap())
    });
    g.bench_function("eval_generic_dd", |b| {
        b.iter(|| {
            eval_generic::<Dd>(black_box(&roots), |i| Some(Dd::from_f64(by_index[i as usize])))
                .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, intern, eval);
criterion_main!(benches);
