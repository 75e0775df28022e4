//! The `sin` and `cos` every `f64` path of eom-sym uses (the `libm` crate, a port of musl's
//! math library) against the standard library's (the system's), and eom's double-double (`Dd`)
//! against the maintained `twofloat`, in speed and in accuracy, in the same run. The figures
//! that decided for `libm` and for keeping `Dd` are in `benches/README.md`.
//!
//! `cargo bench -p eom-sym --bench maintained`
//!
//! * `sin_cos/*`: 1024 arguments per iteration, spread like the values of a model's DAG
//!   (angles within ±π, and magnitudes from 10⁻³ to 10⁵ of either sign); the largest error in
//!   ulps against a double-double reference is printed once.
//! * `double_double/*`: a chain of `+ · / √ sin exp ln` per iteration; the largest relative
//!   error of each function against 50-digit values (`data/dd_reference.txt`, written by
//!   `data/dd_reference.py` with mpmath) is printed once. The tests of `Dd` require 10⁻³⁰.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use eom_sym::Dd;
use eom_sym::testing::SplitMix;
use std::hint::black_box;
use twofloat::TwoFloat;

fn arguments() -> Vec<f64> {
    let mut rng = SplitMix(5);
    (0..1024)
        .map(|k| {
            let u = rng.below(1 << 30) as f64 / (1u64 << 30) as f64;
            if k % 2 == 0 {
                (2.0 * u - 1.0) * std::f64::consts::PI
            } else {
                let sign = if rng.below(2) == 0 { -1.0 } else { 1.0 };
                sign * 10f64.powf(-3.0 + 8.0 * u)
            }
        })
        .collect()
}

/// Units in the last place of `got` from the double-double `want`.
fn ulps(got: f64, want: Dd) -> f64 {
    let w = want.to_f64().abs();
    let ulp = f64::from_bits(w.to_bits() + 1) - w;
    ((Dd::from_f64(got) - want).to_f64() / ulp).abs()
}

fn sin_cos(c: &mut Criterion) {
    let xs = arguments();
    let worst = |f: fn(f64) -> f64, r: fn(Dd) -> Dd| {
        xs.iter()
            .map(|&x| ulps(f(x), r(Dd::from_f64(x))))
            .fold(0.0, f64::max)
    };
    eprintln!(
        "sin: largest error libm {:.3} ulp, std {:.3} ulp; cos: libm {:.3} ulp, std {:.3} ulp",
        worst(libm::sin, Dd::sin),
        worst(f64::sin, Dd::sin),
        worst(libm::cos, Dd::cos),
        worst(f64::cos, Dd::cos),
    );
    let mut g = c.benchmark_group("sin_cos");
    g.throughput(Throughput::Elements(xs.len() as u64));
    type F = fn(f64) -> f64;
    let cases: [(&str, F); 4] = [
        ("libm::sin", libm::sin),
        ("std sin", f64::sin),
        ("libm::cos", libm::cos),
        ("std cos", f64::cos),
    ];
    for (name, f) in cases {
        g.bench_function(name, |b| {
            b.iter(|| black_box(&xs).iter().map(|&x| f(x)).sum::<f64>())
        });
    }
    g.finish();
}

/// The reference table: `(function, argument, hi, lo)`.
fn reference() -> Vec<(String, f64, Dd)> {
    include_str!("data/dd_reference.txt")
        .lines()
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let num = |s: &str| s.parse::<f64>().expect("a number");
            let v = Dd::from_f64(num(w[2])) + Dd::from_f64(num(w[3]));
            (w[0].to_string(), num(w[1]), v)
        })
        .collect()
}

fn dd_of(name: &str, x: f64) -> Dd {
    let x = Dd::from_f64(x);
    match name {
        "sin" => x.sin(),
        "cos" => x.cos(),
        "tan" => x.tan(),
        "exp" => x.exp(),
        "ln" => x.abs().ln(),
        "sqrt" => x.abs().sqrt(),
        _ => x.atan2(Dd::from_f64(0.7)),
    }
}

fn twofloat_of(name: &str, x: f64) -> Dd {
    let t = TwoFloat::from(x);
    let v = match name {
        "sin" => t.sin(),
        "cos" => t.cos(),
        "tan" => t.tan(),
        "exp" => t.exp(),
        "ln" => t.abs().ln(),
        "sqrt" => t.abs().sqrt(),
        _ => t.atan2(TwoFloat::from(0.7)),
    };
    Dd::from_f64(v.hi()) + Dd::from_f64(v.lo())
}

fn double_double(c: &mut Criterion) {
    let table = reference();
    for name in ["sin", "cos", "tan", "exp", "ln", "sqrt", "atan2"] {
        let worst = |f: fn(&str, f64) -> Dd| {
            table
                .iter()
                .filter(|r| r.0 == name)
                .map(|(_, x, want)| {
                    let got = f(name, *x);
                    ((got - *want).to_f64() / want.to_f64()).abs()
                })
                .fold(0.0, f64::max)
        };
        eprintln!(
            "{name}: largest relative error Dd {:.2e}, twofloat {:.2e}",
            worst(dd_of),
            worst(twofloat_of)
        );
    }
    let xs: Vec<f64> = arguments()
        .into_iter()
        .take(64)
        .map(|x| x.abs() + 0.5)
        .collect();
    let mut g = c.benchmark_group("double_double");
    g.throughput(Throughput::Elements(xs.len() as u64));
    g.bench_function("Dd", |b| {
        b.iter(|| {
            black_box(&xs).iter().fold(Dd::ONE, |acc, &x| {
                let x = Dd::from_f64(x);
                (acc * x + x.sqrt()) / (x + Dd::ONE) + x.sin() * x.ln() + (-x).exp()
            })
        })
    });
    g.bench_function("twofloat", |b| {
        b.iter(|| {
            black_box(&xs).iter().fold(TwoFloat::from(1.0), |acc, &x| {
                let x = TwoFloat::from(x);
                (acc * x + x.sqrt()) / (x + 1.0) + x.sin() * x.ln() + (-x).exp()
            })
        })
    });
    g.finish();
}

criterion_group!(benches, sin_cos, double_double);
criterion_main!(benches);
