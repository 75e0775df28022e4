//! Sweep benches on real models (issue 4): points per second through the compiled symbolic
//! model for the shimmy (x over 0..1) and the bicycle (v over 0..10, eigenvalues of the
//! minimal realization), and the time to locate the stability boundaries.
//!
//! `cargo bench -p models --bench sweep`

use criterion::{Criterion, criterion_group, criterion_main};
use eom_model::{EvalWorkspace, Linearizer};
use eom_num::minreal::{MinrealOptions, minimal_realization};
use eom_num::sweep::Sweep;
use std::hint::black_box;

fn sweeps(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    g.sample_size(20);
    for (name, param, hi, minimal) in [("shimmy", "x", 1.0, false), ("bicycle", "v", 10.0, true)] {
        let model = models::build(name, &[]).unwrap();
        let sym = Linearizer::new(&model).symbolic().unwrap();
        let compiled = sym.compiled().clone();
        let k = model.scope.names().iter().position(|n| n == param).unwrap();
        let base = model.scope.nominal_values();
        let f = |x: f64| -> Result<nalgebra::DMatrix<f64>, String> {
            let mut v = base.clone();
            v[k] = x;
            let ss = compiled
                .evaluate_with(&v, &mut EvalWorkspace::default())
                .map_err(|e| e.to_string())?;
            if minimal {
                Ok(minimal_realization(&ss, &MinrealOptions::default())
                    .map_err(|e| e.to_string())?
                    .0
                    .a)
            } else {
                Ok(ss.a)
            }
        };
        for points in [101usize, 1001] {
            g.bench_function(format!("{name}: {points} points, grid only"), |b| {
                b.iter(|| {
                    Sweep::linspace(0.0, hi, points)
                        .with_boundaries(false)
                        .run(f)
                        .unwrap()
                })
            });
        }
        g.bench_function(format!("{name}: 101 points + boundaries to 1e-10"), |b| {
            b.iter(|| black_box(Sweep::linspace(0.0, hi, 101).run(f).unwrap()))
        });
        let r = Sweep::linspace(0.0, hi, 101).run(f).unwrap();
        println!(
            "{name}: boundaries {:?} ({} evaluations in all)",
            r.boundaries.iter().map(|b| b.value).collect::<Vec<_>>(),
            r.boundaries.iter().map(|b| b.evaluations).sum::<usize>()
        );
    }
    g.finish();
}

criterion_group!(benches, sweeps);
criterion_main!(benches);
