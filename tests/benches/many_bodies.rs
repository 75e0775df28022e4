//! Models of many identical bodies (issue 27, item 7): `n` bodies, each on its own slider and
//! spring, from the model-file generator `models::generate::identical_bodies`, with no
//! inputs and outputs or with one driven body, against the connected chain of as many
//! masses (`chainN`, the baseline measured in the same run).
//!
//! Steps: `load` (parse the file and build the model), `reduce` (assembly and the numeric
//! elimination), `modes` (eigenvalues and eigenvectors), `minreal` (the minimal realization
//! with its report: the step that took 0.85 s of 0.86 s at n = 100 without inputs, and most
//! of 52.6 s at n = 300, before the structural reduction and the Hessenberg PBH residuals).
//!
//! ```text
//! cargo bench -p tests --bench many_bodies
//! MANY_SIZES=100 cargo bench -p tests --bench many_bodies -- minreal
//! ```

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use eom_model::{Linearizer, Method};
use eom_num::minreal::{MinrealOptions, minimal_realization};
use eom_num::modes::Modes;

fn sizes() -> Vec<usize> {
    std::env::var("MANY_SIZES")
        .ok()
        .map(|s| s.split(',').filter_map(|t| t.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![100, 300])
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("many_bodies");
    g.sample_size(10).warm_up_time(Duration::from_millis(500));
    for n in sizes() {
        for driven in [0, 1] {
            let text = models::generate::identical_bodies(n, driven, false);
            let name = format!("identical{n}_driven{driven}");
            g.bench_function(format!("load/{name}"), |b| {
                b.iter(|| eom_model::file::from_str(black_box(&text), "bench", &[]).unwrap())
            });
            let model = eom_model::file::from_str(&text, "bench", &[]).unwrap();
            g.bench_function(format!("reduce/{name}"), |b| {
                b.iter(|| {
                    Linearizer::new(&model)
                        .method(Method::Numeric)
                        .run()
                        .unwrap()
                })
            });
            let ss = Linearizer::new(&model)
                .method(Method::Numeric)
                .run()
                .unwrap()
                .state_space;
            g.bench_function(format!("minreal/{name}"), |b| {
                b.iter(|| minimal_realization(black_box(&ss), &MinrealOptions::default()).unwrap())
            });
            if driven == 1 {
                g.bench_function(format!("modes/{name}"), |b| {
                    b.iter(|| Modes::compute(black_box(&ss)).unwrap())
                });
            }
        }
        // The baseline: a connected chain of as many masses, one force, one sensor.
        let chain = models::build(&format!("chain{n}"), &[]).unwrap();
        let ss = Linearizer::new(&chain)
            .method(Method::Numeric)
            .run()
            .unwrap()
            .state_space;
        g.bench_function(format!("minreal/chain{n}"), |b| {
            b.iter(|| minimal_realization(black_box(&ss), &MinrealOptions::default()).unwrap())
        });
    }
    g.finish();
}

criterion::criterion_group!(benches, bench);
criterion::criterion_main!(benches);
