//! Loading a model file: a chain of 50 bodies (150 items) written as a file by hand-rolled
//! text, parsed, checked and built into a model.

use criterion::{Criterion, criterion_group, criterion_main};
use std::fmt::Write;
use std::hint::black_box;

/// `n` masses in series on sliders, a spring and damper in each link, every number a parameter
/// expression.
fn chain(n: usize) -> String {
    let mut t = String::from(
        "[model]\nname = \"chain\"\n[parameters]\nm = { value = 1, unit = \"kg\", range = \"> 0\" }\n\
         k = { value = 10, unit = \"N/m\", range = \"> 0\" }\nc = { value = 0.1, range = \">= 0\" }\n\
         h = { value = 0.5, unit = \"m\", range = \"> 0\" }\n",
    );
    for i in 1..=n {
        let _ = write!(
            t,
            "[[body]]\nname = \"m{i}\"\nmass = \"m\"\nat = [0, 0, \"{i}*h\"]\n\
             [[rigid_point]]\nname = \"slider{i}\"\nbetween = [\"m{i}\", \"ground\"]\nat = [0, 0, \"{i}*h\"]\n\
             forces = 2\nmoments = 3\naxis = [0, 0, 1]\n\
             [[spring]]\nname = \"link{i}\"\nbetween = [\"m{i}\", \"{}\"]\n\
             ends = [[0, 0, \"{i}*h\"], [0, 0, \"{}*h\"]]\nstiffness = \"k\"\ndamping = \"c\"\n",
            if i == 1 {
                "ground".to_string()
            } else {
                format!("m{}", i - 1)
            },
            i - 1
        );
    }
    t
}

fn load(c: &mut Criterion) {
    let text = chain(50);
    let m = eom_model::file::from_str(&text, "chain50.toml", &[]).expect("loads");
    assert_eq!(m.bodies.len(), 50);
    c.bench_function("file: load and build 50 bodies", |b| {
        b.iter(|| eom_model::file::from_str(black_box(&text), "chain50.toml", &[]).expect("loads"))
    });
}

criterion_group!(benches, load);
criterion_main!(benches);
