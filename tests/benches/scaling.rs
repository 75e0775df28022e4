//! How each step of `eom analyze` and `eom sweep` grows with the model: chains of
//! n = 10, 30, 100, 300, 1000 masses (2n states), every step timed separately by criterion,
//! then the fitted exponent `t ∝ n^e` of each step (least squares on log t against log n over
//! the sizes ≥ 30, where the constant overheads no longer dominate).
//!
//! Steps: `reduce` (assembly and the numeric elimination, `Method::Numeric`), `eigenvalues`,
//! `modes` (eigenvectors, condition numbers, mode shapes), `minreal` (minimal realization with
//! its report), `gains` (steady-state gains), `zeros` (transmission zeros of the minimal
//! realization), `freq` (Hessenberg form and 100 frequencies), `sweep` (a 5-point
//! [`eom_num::sweep::Sweep`] of the chain's stiffness).
//!
//! ```text
//! cargo bench -p tests --bench scaling                       # every size and step
//! SCALING_SIZES=10,30,100 cargo bench -p tests --bench scaling -- minreal   # a subset
//! ```
//!
//! The table printed at the end is the one in the performance page (docs/performance.md).

use std::collections::BTreeMap;
use std::hint::black_box;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use criterion::Criterion;
use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use eom_num::freq::{FreqOptions, FreqRange, FreqUnit, FrequencyResponse};
use eom_num::gain::steady_state_gain;
use eom_num::minreal::{MinrealOptions, minimal_realization};
use eom_num::modes::{Modes, eigenvalues};
use eom_num::sweep::Sweep;
use eom_num::zeros::transmission_zeros;
use nalgebra::DMatrix;

/// Best time per call of every (step, n), filled by the measurements.
static BEST: Mutex<BTreeMap<(&'static str, usize), f64>> = Mutex::new(BTreeMap::new());

const STEPS: [&str; 8] = [
    "reduce",
    "eigenvalues",
    "modes",
    "minreal",
    "gains",
    "zeros",
    "freq",
    "sweep",
];

fn sizes() -> Vec<usize> {
    std::env::var("SCALING_SIZES")
        .ok()
        .map(|s| s.split(',').filter_map(|t| t.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![10, 30, 100, 300, 1000])
}

fn record(step: &'static str, n: usize, per_call: f64) {
    let mut b = BEST.lock().unwrap_or_else(|p| p.into_inner());
    let e = b.entry((step, n)).or_insert(f64::INFINITY);
    *e = e.min(per_call);
}

/// Times `f` through criterion, keeping the best time per call for the table. With
/// `SCALING_QUICK=1`, one call timed directly instead (a first look, not a measurement).
fn time<R>(c: &mut Criterion, step: &'static str, n: usize, mut f: impl FnMut() -> R) {
    if std::env::var_os("SCALING_QUICK").is_some() {
        let skip = std::env::var("SCALING_SKIP").unwrap_or_default();
        if skip
            .split(',')
            .any(|s| s == format!("{step}/{n}") || s == step)
        {
            return;
        }
        let t = Instant::now();
        black_box(f());
        let d = t.elapsed().as_secs_f64();
        eprintln!("{step}/chain{n}: {}", fmt_time(d));
        record(step, n, d);
        return;
    }
    c.bench_function(&format!("{step}/chain{n}"), |b| {
        b.iter_custom(|iters| {
            let t = Instant::now();
            for _ in 0..iters {
                black_box(f());
            }
            let d = t.elapsed();
            record(step, n, d.as_secs_f64() / iters as f64);
            d
        })
    });
}

/// The chain's state matrix with every spring and damper scaled by `factor` (the stiffness and
/// damping enter A linearly): the sweep's model function without a symbolic reduction.
fn scaled(ss: &StateSpace<f64>, kc: &DMatrix<f64>, factor: f64) -> DMatrix<f64> {
    &ss.a + kc * (factor - 1.0)
}

fn bench_size(c: &mut Criterion, n: usize) {
    let model = models::build(&format!("chain{n}"), &[]).expect("chain model");
    let lin = || {
        Linearizer::new(&model)
            .method(Method::Numeric)
            .run()
            .expect("reduction")
    };
    time(c, "reduce", n, lin);
    let ss = lin().state_space;
    let a = ss.a.clone();
    time(c, "eigenvalues", n, || {
        eigenvalues(&a).expect("eigenvalues")
    });
    time(c, "modes", n, || Modes::compute(&ss).expect("modes"));
    let opts = MinrealOptions::default();
    time(c, "minreal", n, || {
        minimal_realization(&ss, &opts).expect("minreal")
    });
    time(c, "gains", n, || steady_state_gain(&ss).expect("gains"));
    let (min, _) = minimal_realization(&ss, &opts).expect("minreal");
    time(c, "zeros", n, || transmission_zeros(&min).expect("zeros"));
    let fopts = FreqOptions {
        range: FreqRange::Points {
            values: (0..100).map(|k| 1e-3 * 1.1f64.powi(k)).collect(),
            unit: FreqUnit::Hz,
        },
        ..FreqOptions::default()
    };
    time(c, "freq", n, || {
        FrequencyResponse::compute(&ss, &fopts).expect("frequency response")
    });
    // The rows of A that carry the springs and dampers: A(k) − A(0) by one reduction at k = 0.
    let zero = Linearizer::new(&model)
        .at(&[("k", 0.0), ("c", 0.0)])
        .method(Method::Numeric)
        .run()
        .map(|l| l.state_space.a);
    if let Ok(a0) = zero {
        let kc = &ss.a - a0;
        let sweep = Sweep::linspace(0.5, 2.0, 5).with_param_name("k");
        time(c, "sweep", n, || {
            sweep
                .run(|f| Ok::<_, std::convert::Infallible>(scaled(&ss, &kc, f)))
                .expect("sweep")
        });
    }
}

/// Least-squares slope of log t against log n.
fn exponent(points: &[(usize, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, t)| *n >= 30 && t.is_finite())
        .map(|&(n, t)| ((n as f64).ln(), t.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let k = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / k;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / k;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    Some(sxy / sxx)
}

fn fmt_time(t: f64) -> String {
    if t >= 1.0 {
        format!("{t:.2} s")
    } else if t >= 1e-3 {
        format!("{:.2} ms", t * 1e3)
    } else {
        format!("{:.1} µs", t * 1e6)
    }
}

fn print_table(sizes: &[usize]) {
    let best = BEST.lock().unwrap_or_else(|p| p.into_inner());
    let mut head = String::from("| step |");
    let mut rule = String::from("|---|");
    for n in sizes {
        head.push_str(&format!(" chain{n} ({} states) |", 2 * n));
        rule.push_str("---|");
    }
    head.push_str(" exponent |");
    rule.push_str("---|");
    println!("\n{head}\n{rule}");
    for step in STEPS {
        let pts: Vec<(usize, f64)> = sizes
            .iter()
            .filter_map(|&n| best.get(&(step, n)).map(|&t| (n, t)))
            .collect();
        if pts.is_empty() {
            continue;
        }
        let mut row = format!("| {step} |");
        for n in sizes {
            match best.get(&(step, *n)) {
                Some(&t) => row.push_str(&format!(" {} |", fmt_time(t))),
                None => row.push_str(" – |"),
            }
        }
        match exponent(&pts) {
            Some(e) => row.push_str(&format!(" {e:.2} |")),
            None => row.push_str(" – |"),
        }
        println!("{row}");
    }
}

fn main() {
    let sizes = sizes();
    let mut c = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    for &n in &sizes {
        bench_size(&mut c, n);
    }
    c.final_summary();
    print_table(&sizes);
}
