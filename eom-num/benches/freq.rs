//! Frequency response: 1 000 log-spaced points on a 6-state and a 50-state model.
//!
//! * `response` — the full `FrequencyResponse::compute` (balancing, Hessenberg reduction,
//!   1 000 Hessenberg solves, magnitude and unwrapped phase); compare with python-control's
//!   4–16 ms per 1 000 points (measured by hand with python-control on the development machine).
//! * `hessenberg_kernel` — only the 1 000 `evaluate_in` calls, reduction done beforehand.
//! * `batch_kernel` — the same 1 000 points through `evaluate_batch_in` (4 points per call,
//!   the path `FrequencyResponse::compute` uses).
//! * `dense_lu_baseline` — the naive method in the same run: a dense complex LU of
//!   `jωI − A` per frequency (nalgebra), then `C X + D`. The ratio to `response` is the
//!   speed-up of the Hessenberg path.
//!
//! Run: `cargo bench -p eom-num --bench freq`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use eom_num::StateSpace;
use eom_num::freq::{
    FreqOptions, FreqRange, FreqUnit, FrequencyResponse, HessenbergForm, LANES, SolveStatus,
};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// A chain of `k` masses (2k states) on springs and dampers, force inputs on the first and
/// last mass, position outputs of the first, middle and last mass.
fn chain(k: usize) -> StateSpace<f64> {
    let n = 2 * k;
    let mut a = DMatrix::<f64>::zeros(n, n);
    for i in 0..k {
        a[(i, k + i)] = 1.0;
        let m = 1.0 + 0.1 * i as f64;
        let (kk, cc) = (1000.0 + 50.0 * i as f64, 2.0 + 0.05 * i as f64);
        // Spring/damper to the left neighbour (or ground) and to the right neighbour.
        let mut diag_k = kk;
        let mut diag_c = cc;
        if i + 1 < k {
            diag_k += kk;
            diag_c += cc;
            a[(k + i, i + 1)] = kk / m;
            a[(k + i, k + i + 1)] = cc / m;
        }
        if i > 0 {
            a[(k + i, i - 1)] = (1000.0 + 50.0 * (i - 1) as f64) / m;
            a[(k + i, k + i - 1)] = (2.0 + 0.05 * (i - 1) as f64) / m;
        }
        a[(k + i, i)] = -diag_k / m;
        a[(k + i, k + i)] = -diag_c / m;
    }
    let mut b = DMatrix::zeros(n, 2);
    b[(k, 0)] = 1.0;
    b[(n - 1, 1)] = 1.0 / (1.0 + 0.1 * (k - 1) as f64);
    let mut c = DMatrix::zeros(3, n);
    c[(0, 0)] = 1.0;
    c[(1, k / 2)] = 1.0;
    c[(2, k - 1)] = 1.0;
    StateSpace::new(a, b, c, DMatrix::zeros(3, 2)).unwrap()
}

fn omegas() -> Vec<f64> {
    (0..1000)
        .map(|i| 2.0 * std::f64::consts::PI * 10f64.powf(-1.0 + 3.0 * i as f64 / 999.0))
        .collect()
}

/// The naive baseline: dense complex LU of jωI − A per frequency.
fn dense_response(ss: &StateSpace<f64>, w: &[f64]) -> Vec<DMatrix<Complex64>> {
    let n = ss.states();
    let b = ss.b.map(|v| Complex64::new(v, 0.0));
    let c = ss.c.map(|v| Complex64::new(v, 0.0));
    let d = ss.d.map(|v| Complex64::new(v, 0.0));
    w.iter()
        .map(|&w| {
            let m = DMatrix::from_fn(n, n, |i, j| {
                let s = if i == j {
                    Complex64::new(0.0, w)
                } else {
                    Complex64::new(0.0, 0.0)
                };
                s - ss.a[(i, j)]
            });
            let x = m.lu().solve(&b).expect("regular");
            &c * x + &d
        })
        .collect()
}

fn bench(cr: &mut Criterion) {
    let w = omegas();
    let mut group = cr.benchmark_group("freq_1000_points");
    for k in [3usize, 25] {
        let ss = chain(k);
        let n = ss.states();
        let opts = FreqOptions {
            range: FreqRange::Points {
                values: w.clone(),
                unit: FreqUnit::RadPerSec,
            },
            ..Default::default()
        };
        // Sanity: both methods agree before they are timed.
        let fr = FrequencyResponse::compute(&ss, &opts).unwrap();
        let dn = dense_response(&ss, &w);
        // (normwise per frequency: far-end entries of the long chain are ~1e-40 of the rest)
        for (kf, g) in dn.iter().enumerate() {
            let scale = g.iter().fold(0.0f64, |a, z| a.max(z.norm()));
            for i in 0..3 {
                for j in 0..2 {
                    let h = fr.series(i, j)[kf];
                    let err = (h - g[(i, j)]).norm();
                    assert!(
                        err <= 1e-9 * scale,
                        "n = {n}, k = {kf}: {h} vs {}",
                        g[(i, j)]
                    );
                }
            }
        }
        group.bench_with_input(BenchmarkId::new("response", n), &ss, |b, ss| {
            b.iter(|| FrequencyResponse::compute(black_box(ss), &opts).unwrap())
        });
        let form = HessenbergForm::new(&ss).unwrap();
        let mut ws = form.workspace();
        let mut out = vec![Complex64::new(0.0, 0.0); 6];
        group.bench_with_input(BenchmarkId::new("hessenberg_kernel", n), &w, |b, w| {
            b.iter(|| {
                for &wk in w {
                    form.evaluate_in(Complex64::new(0.0, wk), &mut ws, &mut out)
                        .unwrap();
                    black_box(&out);
                }
            })
        });
        let mut bws = form.batch_workspace();
        let mut bout = vec![Complex64::new(0.0, 0.0); 6 * LANES];
        let mut st = [SolveStatus::Regular; LANES];
        group.bench_with_input(BenchmarkId::new("batch_kernel", n), &w, |b, w| {
            b.iter(|| {
                for c in w.chunks_exact(LANES) {
                    let pts: [Complex64; LANES] =
                        std::array::from_fn(|l| Complex64::new(0.0, c[l]));
                    form.evaluate_batch_in(&pts, &mut bws, &mut bout, &mut st)
                        .unwrap();
                    black_box(&bout);
                }
            })
        });
        group.bench_with_input(BenchmarkId::new("dense_lu_baseline", n), &ss, |b, ss| {
            b.iter(|| dense_response(black_box(ss), &w))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
