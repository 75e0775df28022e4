//! Smoke test of the work-precision benchmark (`tests::work_precision`): on the
//! spring-mass-damper and the shimmy, the double-double reference agrees with the closed-form
//! eigenvalues, and every method's eigenvalues agree with the reference; the bicycle against
//! its published benchmark eigenvalues.

use eom_model::Linearizer;
use num_complex::Complex64;
use std::time::Duration;
use tests::work_precision::reference::ReferenceModel;
use tests::work_precision::{Options, points, run_model};

fn quick() -> Options {
    Options {
        points: 6,
        min_time: Duration::from_millis(5),
        ..Options::default()
    }
}

/// Every method on the model: eigenvalue error below 1e-10 (`f32` code: 1e-4), no failure.
fn methods_agree(model: &str) {
    let rows = run_model(model, &quick()).expect("benchmark");
    let methods: Vec<&str> = rows.iter().map(|r| r.method.as_str()).collect();
    for m in [
        "numeric",
        "robust",
        "symbolic (tape)",
        "generated f64",
        "generated f32",
    ] {
        assert!(methods.contains(&m), "{model}: no row for {m}: {methods:?}");
    }
    for r in &rows {
        let tol = if r.method.contains("f32") {
            1e-4
        } else {
            1e-10
        };
        assert_eq!(r.points, 6, "{model} {}: {r:?}", r.method);
        assert_eq!(r.failures, 0, "{model} {}: {r:?}", r.method);
        assert!(
            r.eig_err < tol,
            "{model} {}: eigenvalue error {:e}",
            r.method,
            r.eig_err
        );
        assert!(r.time_ns > 0.0 && r.time_ns.is_finite(), "{r:?}");
    }
}

/// The reference eigenvalues at the benchmark's points against a closed form of the model.
fn reference_matches(model: &str, closed: impl Fn(&[String], &[f64]) -> Vec<Complex64>) {
    let m = models::build(model, &[]).expect("model");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let refm = ReferenceModel::new(&sym);
    let names = m.scope.names();
    let o = quick();
    for p in points(&m.scope.nominal_values(), o.points, o.spread, o.seed) {
        let r = refm.at(&p).expect("reference");
        assert_eq!(r.unrefined, 0, "{model}: unrefined eigenvalues at {p:?}");
        let want = closed(&names, &p);
        let e = tests::max_relative_error(&r.eigenvalues, &want, 1e-300);
        assert!(
            e < 1e-13,
            "{model} at {p:?}: reference {:?} vs closed form {want:?} ({e:e})",
            r.eigenvalues
        );
    }
}

fn value(names: &[String], p: &[f64], n: &str) -> f64 {
    p[names.iter().position(|x| x == n).expect("parameter")]
}

#[test]
fn smd_reference_and_methods() {
    reference_matches("smd", |names, p| {
        let (m, c, k) = (
            value(names, p, "m"),
            value(names, p, "c"),
            value(names, p, "k"),
        );
        let re = -c / (2.0 * m);
        let im = (k / m - c * c / (4.0 * m * m)).sqrt();
        vec![Complex64::new(re, im), Complex64::new(re, -im)]
    });
    methods_agree("smd");
}

/// Roots of `(I + m a²)s³ + m a u s² + k l² s + k l u` (a = x l) by Newton's method from the
/// companion matrix's eigenvalues, polished on the cubic.
fn shimmy_closed(names: &[String], p: &[f64]) -> Vec<Complex64> {
    let v = |n| value(names, p, n);
    let (m, i, k, l, x, u) = (v("m"), v("I"), v("k"), v("l"), v("x"), v("u"));
    let a = x * l;
    let c3 = i + m * a * a;
    let c = [k * l * u / c3, k * l * l / c3, m * a * u / c3];
    let comp = nalgebra::DMatrix::from_row_slice(
        3,
        3,
        &[0.0, 0.0, -c[0], 1.0, 0.0, -c[1], 0.0, 1.0, -c[2]],
    );
    let f = |s: Complex64| ((s + c[2]) * s + c[1]) * s + c[0];
    let df = |s: Complex64| (s * 3.0 + c[2] * 2.0) * s + c[1];
    comp.complex_eigenvalues()
        .iter()
        .map(|&s0| {
            let mut s = s0;
            for _ in 0..4 {
                s -= f(s) / df(s);
            }
            s
        })
        .collect()
}

#[test]
fn shimmy_reference_and_methods() {
    reference_matches("shimmy", shimmy_closed);
    methods_agree("shimmy");
}

/// The bicycle's lean/steer eigenvalues against the benchmark's (Meijaard et al. 2007, Table 2
/// speeds, 17-digit values): the double-double reference to 1e-14, every `f64` method to 1e-12.
#[test]
fn bicycle_against_the_benchmark() {
    let rows = run_model("bicycle", &quick()).expect("benchmark");
    for r in &rows {
        let e = r
            .published_err
            .expect("a published error for every bicycle row");
        let tol = if r.method.starts_with("reference") {
            1e-14
        } else if r.method.contains("f32") {
            1e-3
        } else {
            1e-12
        };
        assert!(
            e < tol,
            "bicycle {}: {e:e} from the published eigenvalues",
            r.method
        );
    }
}
