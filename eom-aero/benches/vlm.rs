//! The vortex-lattice solve of the seed paper's fin (a vertical flat plate, AR 2) at
//! 8×16, 8×32, 16×32 and 16×64 panels (chordwise × spanwise, cosine/cosine): the whole
//! `solve`, from geometry to the 6×6 derivatives. The target is ≤ 5 ms at 8×16; the
//! growth with the panel count N shows the O(N²) influence and force loops and the O(N³)
//! LU. Results go into the crate README.
//!
//! Run: `cargo bench -p eom-aero --bench vlm`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use eom_aero::{Configuration, Reference, Section, SolverOptions, Surface, solve};

fn seed_fin(nc: usize, ns: usize) -> Configuration {
    Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0])).surface(
        Surface::new("Fin")
            .lattice(nc, 1.0, ns, 1.0)
            .section(Section::new([0.0, 0.0, -0.5], 0.5))
            .section(Section::new([0.0, 0.0, 0.5], 0.5)),
    )
}

fn bench(cr: &mut Criterion) {
    let mut group = cr.benchmark_group("vlm_seed_fin");
    group.sample_size(20);
    for (nc, ns) in [(8, 16), (8, 32), (16, 32), (16, 64)] {
        let config = seed_fin(nc, ns);
        let options = SolverOptions::default();
        group.bench_with_input(
            BenchmarkId::new("solve", format!("{nc}x{ns}={}", nc * ns)),
            &config,
            |b, c| b.iter(|| solve(black_box(c), &options).unwrap()),
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
