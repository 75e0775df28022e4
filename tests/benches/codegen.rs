//! Generated code against the tape interpreter on
//! the same expressions, in the same run:
//! bicycle A..D with all parameters symbolic (libm and std math, f64 and f32), shimmy, chain50,
//! and the generation time. Each iteration evaluates 64 distinct points near nominal (per-call
//! time = iteration time / 64; criterion's throughput line gives calls per second). Also the
//! bicycle's stability verdict, one point at a time and in blocks (4 096 points per iteration).
//!
//! `cargo bench -p tests --bench codegen`
//!
//! PyDy's generated C cannot run here (it needs sympy and a C compiler at bench time); the
//! same-driver comparison with it is a by-hand script: `bench/pydy/README.md`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use eom_codegen::EmitOptions;
use eom_model::{Linearizer, ValidityCheck};
use eom_sym::{SymError, Tape};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

include!(concat!(env!("OUT_DIR"), "/generated.rs"));

fn points(nominal: &[f64], n: usize) -> Vec<Vec<f64>> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    (0..n)
        .map(|_| {
            nominal
                .iter()
                .map(|x| x * rng.random_range(0.95..1.05))
                .collect()
        })
        .collect()
}

/// The tape of what `eval_abcd` computes: the A..D entries and the check expressions.
fn abcd_tape(model: &str) -> Tape {
    let m = models::build(model, &[]).expect("model");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let ss = sym.state_space();
    let mut roots: Vec<eom_sym::Expr> = Vec::new();
    for mat in [&ss.a, &ss.b, &ss.c, &ss.d] {
        roots.extend(mat.iter().filter(|e| !e.is_zero()).copied());
    }
    for c in &sym.reduction.checks {
        match c {
            ValidityCheck::Pivot { value, row, .. } => {
                roots.push(*value);
                roots.extend(row);
            }
            ValidityCheck::Negligible { value, scale, .. } => {
                roots.push(*value);
                roots.extend(scale);
            }
        }
    }
    let params: Vec<eom_sym::Expr> = m.scope.params().to_vec();
    Tape::new(&roots, &params).expect("tape")
}

/// Per call: 64 calls over distinct points per iteration (`Throughput::Elements(64)`), through a
/// function pointer hidden from the optimiser (no inlining into the loop: like calling into a
/// separately compiled object).
macro_rules! bench_abcd {
    ($c:expr, $label:expr, $m:path, $ty:ty) => {
        bench_abcd!($c, $label, $m, $ty, eval_abcd)
    };
    // `eval_abcd_varying` relies on the constant entries written once, before the loop.
    ($c:expr, $label:expr, $m:path, $ty:ty, $kernel:ident) => {{
        use $m as g;
        type Kernel = fn(
            &[$ty; g::N_PARAMS],
            &mut [$ty; g::A_LEN],
            &mut [$ty; g::B_LEN],
            &mut [$ty; g::C_LEN],
            &mut [$ty; g::D_LEN],
            &mut [$ty; g::WORK_LEN],
        ) -> Result<(), g::Error>;
        let pts: Vec<[$ty; g::N_PARAMS]> = points(&g::NOMINAL.map(|x| x as f64), 64)
            .iter()
            .map(|p| core::array::from_fn(|k| p[k] as $ty))
            .collect();
        let mut a = [0.0; g::A_LEN];
        let mut b = [0.0; g::B_LEN];
        let mut c = [0.0; g::C_LEN];
        let mut d = [0.0; g::D_LEN];
        let mut w = [0.0; g::WORK_LEN];
        g::write_abcd_constants(&mut a, &mut b, &mut c, &mut d);
        let f: Kernel = black_box(g::$kernel);
        let mut group = $c.benchmark_group("per call");
        group.throughput(Throughput::Elements(64));
        group.bench_function($label, |bch| {
            bch.iter(|| {
                let mut failures = 0;
                for p in black_box(&pts) {
                    failures += usize::from(f(p, &mut a, &mut b, &mut c, &mut d, &mut w).is_err());
                }
                black_box((&a, &b, &c, &d));
                failures
            })
        });
        group.finish();
    }};
}

fn bench_tape(c: &mut Criterion, label: &str, model: &str) {
    type Kernel<'a> = Box<dyn Fn(&[f64], &mut [f64], &mut [f64]) -> Result<(), SymError> + 'a>;
    let tape = abcd_tape(model);
    let m = models::build(model, &[]).expect("model");
    let pts = points(&m.scope.nominal_values(), 64);
    let mut out = vec![0.0; tape.n_outputs()];
    let mut work = vec![0.0; tape.work_len()];
    let kernels: Vec<(String, Kernel)> = vec![(
        label.to_string(),
        Box::new(|p, o, w| tape.eval_into(p, o, w)),
    )];
    let mut group = c.benchmark_group("per call");
    group.throughput(Throughput::Elements(64));
    for (name, eval) in &kernels {
        group.bench_function(name.as_str(), |b| {
            b.iter(|| {
                for p in black_box(&pts) {
                    eval(p, &mut out, &mut work).expect("eval");
                }
                black_box(&out);
            })
        });
    }
    group.finish();
}

fn evaluation(c: &mut Criterion) {
    bench_abcd!(c, "bicycle/abcd/generated f64 libm", gen64::bicycle, f64);
    bench_abcd!(c, "bicycle/abcd/generated f64 std", gen64::bicycle_std, f64);
    bench_abcd!(
        c,
        "bicycle/abcd/generated f64 simplified",
        gen64::bicycle_simplified,
        f64
    );
    bench_abcd!(
        c,
        "bicycle/abcd/generated f64 chunks of 16",
        gen64::bicycle_chunked,
        f64
    );
    bench_abcd!(
        c,
        "bicycle/abcd/generated f64 libm, varying entries only",
        gen64::bicycle,
        f64,
        eval_abcd_varying
    );
    bench_abcd!(c, "bicycle/abcd/generated f32 libm", gen32::bicycle, f32);
    bench_abcd!(
        c,
        "bicycle/abcd/generated f64 v only",
        gen64::bicycle_speed,
        f64
    );
    bench_tape(c, "bicycle/abcd/tape", "bicycle");
    bench_abcd!(c, "shimmy/abcd/generated f64", gen64::shimmy, f64);
    bench_abcd!(
        c,
        "shimmy/abcd/generated f64 simplified",
        gen64::shimmy_simplified,
        f64
    );
    bench_abcd!(
        c,
        "shimmy/abcd/generated f64 simplified, varying entries only",
        gen64::shimmy_simplified,
        f64,
        eval_abcd_varying
    );
    bench_abcd!(c, "shimmy/abcd/generated f32", gen32::shimmy, f32);
    bench_tape(c, "shimmy/abcd/tape", "shimmy");
    bench_abcd!(c, "chain50/abcd/generated f64", gen64::chain50, f64);
    bench_abcd!(c, "chain50/abcd/generated f32", gen32::chain50, f32);
    bench_tape(c, "chain50/abcd/tape", "chain50");
}

/// The bicycle's stability verdict without eigenvalues (`--stability`), per point: one point
/// at a time (`stability`) and in blocks (`stability_many`), over 4 096 distinct points within
/// ±20 % of nominal, the speed too, so that about half are stable. Distinct random points
/// matter: the verdicts are then as random as the points, as in a sweep, and a branch on
/// them mispredicts (docs/performance.md).
fn verdicts(c: &mut Criterion) {
    use stab::bicycle as g;
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let pts: Vec<[f64; g::N_PARAMS]> = (0..4096)
        .map(|_| g::NOMINAL.map(|x| x * rng.random_range(0.8..1.2)))
        .collect();
    let mut out = vec![Ok(g::Verdict::Undecided); pts.len()];
    let mut group = c.benchmark_group("per verdict");
    group.throughput(Throughput::Elements(pts.len() as u64));
    group.bench_function("bicycle/stability, one point at a time", |b| {
        b.iter(|| {
            for (p, v) in black_box(&pts).iter().zip(out.iter_mut()) {
                *v = g::stability(p);
            }
            black_box(&out);
        })
    });
    group.bench_function("bicycle/stability_many", |b| {
        b.iter(|| g::stability_many(black_box(&pts), &mut out))
    });
    group.finish();
}

fn generation(c: &mut Criterion) {
    for name in ["bicycle", "chain50"] {
        let m = models::build(name, &[]).expect("model");
        c.bench_function(&format!("{name}/generate/symbolic state space"), |b| {
            b.iter(|| Linearizer::new(black_box(&m)).symbolic().expect("symbolic"))
        });
        let sym = Linearizer::new(&m).symbolic().expect("symbolic");
        let opts = EmitOptions::default().model_name(name);
        c.bench_function(&format!("{name}/generate/emit"), |b| {
            b.iter(|| eom_codegen::emit(black_box(&sym), &opts).expect("emit"))
        });
    }
}

criterion_group!(benches, evaluation, verdicts, generation);
criterion_main!(benches);
