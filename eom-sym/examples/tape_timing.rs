//! Time the tape on the benchmark DAG of `benches/core.rs` (10 033 unique nodes, 50 roots,
//! 20 parameters) as medians of short batches, which this noisy 2-core VM reports far more
//! steadily than criterion's means: 200 batches of 20 evaluations each
//! ([`Tape::eval_into`]), of the exact and of the reassociating tape.
//!
//! `cargo run --release -p eom-sym --example tape_timing`
//!
//! With arguments `exact N` or `reassociating N` it only evaluates that tape `N` times
//! (for instruction counts: run it under `valgrind --tool=callgrind` with two values of `N`
//! and take the difference).

use eom_sym::Tape;
use eom_sym::testing::{bounded_dag, params};
use std::time::Instant;

/// Median and minimum over 200 batches of 20 calls, in seconds per call.
fn time(mut f: impl FnMut()) -> (f64, f64) {
    let mut t: Vec<f64> = (0..200)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..20 {
                f();
            }
            start.elapsed().as_secs_f64() / 20.0
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[100], t[0])
}

fn main() {
    let ps = params(20, 7, true);
    let roots = bounded_dag(&ps, 10_000, 50, 11);
    let values: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [how, n] = &args[..] {
        let n: usize = n.parse().expect("a count");
        let tape = match how.as_str() {
            "reassociating" => Tape::new_reassociating(&roots, &ps).unwrap(),
            _ => Tape::new(&roots, &ps).unwrap(),
        };
        let mut work = vec![0.0; tape.work_len()];
        let mut out = vec![0.0; tape.n_outputs()];
        for _ in 0..n {
            tape.eval_into(&values, &mut out, &mut work).unwrap();
        }
        std::hint::black_box(&out);
        return;
    }
    for (name, tape) in [
        ("exact", Tape::new(&roots, &ps).unwrap()),
        (
            "reassociating",
            Tape::new_reassociating(&roots, &ps).unwrap(),
        ),
    ] {
        let nodes = tape.n_nodes() as f64;
        let mut work = vec![0.0; tape.work_len()];
        let mut out = vec![0.0; tape.n_outputs()];
        println!(
            "{name} tape: {} nodes, {} instructions",
            tape.n_nodes(),
            tape.len()
        );
        for round in 0..3 {
            let (med, min) = time(|| {
                tape.eval_into(std::hint::black_box(&values), &mut out, &mut work)
                    .unwrap()
            });
            println!(
                "  round {round}: {:6.2} µs (min {:6.2}) = {:.2} ns/node",
                med * 1e6,
                min * 1e6,
                med * 1e9 / nodes
            );
        }
    }
}
