//! Assembly and reduction benches (issue 3): the bicycle by the numeric elimination, the
//! replayed plan and the robust SVD path (all in f64 at the nominal point), the bicycle with
//! all 27 parameters symbolic, and chains of n = 10, 50, 200 masses symbolic, whose sizes are
//! printed with the fitted growth exponent.
//!
//! The `tape` group times the compiled tape of the symbolic models (A, B, C, D, the map to
//! physical coordinates and the validity checks) per call and per unique node: the shape of a
//! real model's DAG (wide and shallow), where eom-sym's random-DAG bench is deep.
//!
//! `cargo bench -p models --bench pipeline`

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use eom_model::{Linearizer, assemble, reduce, reduce_robust};
use eom_sym::Expr;
use std::hint::black_box;
use std::time::Instant;

fn bicycle(c: &mut Criterion) {
    let model = models::build("bicycle", &[]).unwrap();
    let numeric = model.nominal().unwrap();
    let plan = reduce(&assemble(&numeric).unwrap(), None).unwrap().plan;
    let mut g = c.benchmark_group("bicycle");
    g.bench_function("numeric assemble+reduce", |b| {
        b.iter(|| reduce(&assemble(black_box(&numeric)).unwrap(), None).unwrap())
    });
    g.bench_function("numeric assemble+reduce, replayed plan", |b| {
        b.iter(|| reduce(&assemble(black_box(&numeric)).unwrap(), Some(&plan)).unwrap())
    });
    g.bench_function("robust assemble+reduce", |b| {
        b.iter(|| reduce_robust(&assemble(black_box(&numeric)).unwrap()).unwrap())
    });
    g.bench_function("symbolic assemble+reduce (27 parameters)", |b| {
        b.iter(|| reduce(&assemble(black_box(&model)).unwrap(), None).unwrap())
    });
    // The same on a model built anew each time: its expression pool starts empty, as for a
    // user's first reduction (above, the pool already holds the nodes of the earlier runs, so
    // most constructions find their node).
    g.bench_function("symbolic assemble+reduce, fresh pool", |b| {
        b.iter_batched_ref(
            || models::build("bicycle", &[]).unwrap(),
            |m| reduce(&assemble(m).unwrap(), None).unwrap(),
            BatchSize::SmallInput,
        )
    });
    g.finish();
    let r = reduce(&assemble(&model).unwrap(), None).unwrap();
    let ss = &r.state_space;
    let roots: Vec<Expr> =
        ss.a.iter()
            .chain(ss.b.iter())
            .chain(ss.c.iter())
            .chain(ss.d.iter())
            .copied()
            .collect();
    let ops = Expr::op_count(&roots);
    println!(
        "bicycle A..D: {} unique operations ({ops:?}), {} unique nodes; PyDy after CSE: 734",
        ops.total(),
        Expr::dag_size(&roots)
    );
}

fn chains(c: &mut Criterion) {
    let mut g = c.benchmark_group("chain symbolic");
    g.sample_size(20);
    let mut points = Vec::new();
    for n in [10usize, 50, 200] {
        let model = models::build(&format!("chain{n}"), &[]).unwrap();
        g.bench_function(format!("chain{n}"), |b| {
            b.iter(|| reduce(&assemble(black_box(&model)).unwrap(), None).unwrap())
        });
        // Size of the result and a direct timing for the growth fit.
        let t = Instant::now();
        let reps = 5;
        let mut r = None;
        for _ in 0..reps {
            r = Some(reduce(&assemble(&model).unwrap(), None).unwrap());
        }
        let secs = t.elapsed().as_secs_f64() / reps as f64;
        let ss = &r.expect("ran").state_space;
        let roots: Vec<Expr> =
            ss.a.iter()
                .chain(ss.b.iter())
                .chain(ss.c.iter())
                .chain(ss.d.iter())
                .copied()
                .filter(|e| !e.is_zero())
                .collect();
        println!(
            "chain{n}: {secs:.3e} s, {} structural non-zeros in A..D, {} unique operations",
            roots.len(),
            Expr::op_count(&roots).total()
        );
        points.push((n as f64, secs));
    }
    g.finish();
    // Least-squares slope of log(time) against log(n).
    let k = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0.ln(), a.1 + p.1.ln()));
    let (sxx, sxy) = points.iter().fold((0.0, 0.0), |a, p| {
        (a.0 + p.0.ln().powi(2), a.1 + p.0.ln() * p.1.ln())
    });
    let slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    println!("chain symbolic time grows as n^{slope:.2} (target ≤ n^1.5)");
}

fn tape(c: &mut Criterion) {
    let mut g = c.benchmark_group("tape");
    // (The chains share three parameter combinations among all their entries: their tapes are
    // a dozen instructions and a call is the dense copy of the outputs.)
    for name in ["bicycle"] {
        let model = models::build(name, &[]).unwrap();
        let sym = Linearizer::new(&model).symbolic().unwrap();
        let tape = sym.tape();
        let values: Vec<f64> = sym.params.iter().map(|p| p.nominal()).collect();
        let mut work = vec![0.0; tape.work_len()];
        let mut out = vec![0.0; tape.n_outputs()];
        tape.eval_into(&values, &mut out, &mut work).unwrap();
        let t = Instant::now();
        let reps = 2000;
        for _ in 0..reps {
            tape.eval_into(black_box(&values), &mut out, &mut work)
                .unwrap();
        }
        let per_call = t.elapsed().as_secs_f64() / reps as f64;
        println!(
            "tape {name}: {} instructions, {:.2} ns per instruction",
            tape.len(),
            per_call * 1e9 / tape.len() as f64
        );
        g.bench_function(format!("{name} ({} instructions)", tape.len()), |b| {
            b.iter(|| {
                tape.eval_into(black_box(&values), &mut out, &mut work)
                    .unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bicycle, chains, tape);
criterion_main!(benches);
