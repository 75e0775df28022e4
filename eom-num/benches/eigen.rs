//! Eigenvalues on a 6-state and a 50-state model: the allocating `eigenvalues` against the
//! workspace kernel `eigenvalues_in` (the one sweeps call), and modes with vectors; for 4, 6
//! and 16 states the stack kernel `eigenvalues_small` (which `eigenvalues_in` takes up to 16
//! states) against faer's QR algorithm on the same matrix (`eigenvalues_faer_in`).
//!
//! `bicycle`: the stack kernel on the bicycle's 6-state A at its nominal point (two
//! structural zeros, known in advance as in `eom bench throughput`) against faer's QR
//! algorithm: the per-point eigenvalue cost of the throughput target.
//!
//! `estimates`: the eigenvalues with their error estimates (`eigenvalues_with_errors`, what a
//! sweep computes where a verdict could depend on them) on the stack path (vectors by inverse
//! iteration) against faer's eigenvectors (`eigenvalues_with_errors_faer`, the path before),
//! with the eigenvalues alone (`eigenvalues_small`) as the baseline, for 3, 6 and 16 states.
//!
//! Run: `cargo bench -p eom-num --bench eigen`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use eom_num::StateSpace;
use eom_num::modes::{
    EigenvaluesWorkspace, Modes, eigenvalues, eigenvalues_faer_in, eigenvalues_in,
    eigenvalues_with_errors, eigenvalues_with_errors_faer,
};
use eom_num::small_eigen::{KnownZeros, eigenvalues_small, eigenvalues_small_known};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Deterministic non-symmetric test matrix (a damped chain plus a skew coupling).
fn matrix(n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(n, n, |i, j| {
        let d = i as f64 - j as f64;
        if i == j {
            -0.5 - 0.01 * i as f64
        } else {
            (1.3 * d).sin() / (1.0 + d.abs())
        }
    })
}

fn bench(cr: &mut Criterion) {
    let mut group = cr.benchmark_group("eigen");
    for n in [6usize, 50] {
        let a = matrix(n);
        group.bench_with_input(BenchmarkId::new("eigenvalues", n), &a, |b, a| {
            b.iter(|| eigenvalues(black_box(a)).unwrap())
        });
        let mut ws = EigenvaluesWorkspace::new(n);
        let mut out = vec![Complex64::new(0.0, 0.0); n];
        group.bench_with_input(BenchmarkId::new("eigenvalues_in", n), &a, |b, a| {
            b.iter(|| {
                eigenvalues_in(black_box(a), &mut ws, &mut out).unwrap();
                black_box(&out);
            })
        });
        let ss = StateSpace::new(
            a.clone(),
            DMatrix::zeros(n, 1),
            DMatrix::zeros(1, n),
            DMatrix::zeros(1, 1),
        )
        .unwrap();
        group.bench_with_input(BenchmarkId::new("modes", n), &ss, |b, ss| {
            b.iter(|| Modes::compute(black_box(ss)).unwrap())
        });
    }
    for n in [4usize, 6, 16] {
        let a = matrix(n);
        let mut out = vec![Complex64::new(0.0, 0.0); n];
        group.bench_with_input(BenchmarkId::new("small kernel", n), &a, |b, a| {
            b.iter(|| {
                eigenvalues_small(black_box(a.as_slice()), n, &mut out).unwrap();
                black_box(&out);
            })
        });
        let mut ws = EigenvaluesWorkspace::new(n);
        group.bench_with_input(BenchmarkId::new("faer", n), &a, |b, a| {
            b.iter(|| {
                eigenvalues_faer_in(black_box(a), &mut ws, &mut out).unwrap();
                black_box(&out);
            })
        });
    }
    group.finish();
}

/// The bicycle's A at its nominal parameters (v = 5 m/s; `eom analyze bicycle --format
/// json`, `matrices.A`, rows), numeric path.
const BICYCLE_A: [[f64; 6]; 6] = [
    [
        0.0,
        0.0,
        3.6363636363636367,
        1.3636363636363635,
        0.9000000000000001,
        0.021818181818181837,
    ],
    [0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
    [
        0.0,
        0.0,
        -4.545454545454545,
        4.545454545454545,
        -1.0092936587501423e-16,
        0.0727272727272728,
    ],
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
    [
        9.057986811691048e-16,
        9.489774446773552,
        16.12917082099491,
        -16.129170820994915,
        -0.5276122490284544,
        -1.6112497531856478,
    ],
    [
        -7.234739577714723e-15,
        12.020071893447184,
        -33.50179348394859,
        33.50179348394865,
        18.855561440825557,
        -10.878873091711014,
    ],
];

fn bench_bicycle(cr: &mut Criterion) {
    let mut group = cr.benchmark_group("bicycle");
    let a = DMatrix::from_fn(6, 6, |i, j| BICYCLE_A[i][j]);
    let known = KnownZeros::of(a.as_slice(), 6).unwrap();
    let mut out = vec![Complex64::new(0.0, 0.0); 6];
    group.bench_function("small_kernel_known_zeros", |b| {
        b.iter(|| {
            eigenvalues_small_known(black_box(a.as_slice()), 6, &known, &mut out).unwrap();
            black_box(&out);
        })
    });
    let mut ws = EigenvaluesWorkspace::new(6);
    group.bench_function("faer", |b| {
        b.iter(|| {
            eigenvalues_faer_in(black_box(&a), &mut ws, &mut out).unwrap();
            black_box(&out);
        })
    });
    group.finish();
}

fn bench_estimates(cr: &mut Criterion) {
    let mut group = cr.benchmark_group("estimates");
    for n in [3usize, 6, 16] {
        let a = matrix(n);
        let mut out = vec![Complex64::new(0.0, 0.0); n];
        group.bench_with_input(BenchmarkId::new("eigenvalues_only", n), &a, |b, a| {
            b.iter(|| {
                eigenvalues_small(black_box(a.as_slice()), n, &mut out).unwrap();
                black_box(&out);
            })
        });
        group.bench_with_input(BenchmarkId::new("stack", n), &a, |b, a| {
            b.iter(|| black_box(eigenvalues_with_errors(black_box(a)).unwrap()))
        });
        group.bench_with_input(BenchmarkId::new("faer", n), &a, |b, a| {
            b.iter(|| black_box(eigenvalues_with_errors_faer(black_box(a)).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench, bench_bicycle, bench_estimates);
criterion_main!(benches);
