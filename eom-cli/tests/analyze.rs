//! `eom analyze` against independent references: the closed-form characteristic cubic of the
//! shimmy model, the published eigenvalues of the bicycle benchmark, the closed-form frequency
//! response of the spring–mass–damper. The shimmy's and the bicycle's reference numbers are
//! those of their sidecars (`models/NAME.ref.toml`, read by `tests::references`).

mod common;
use common::{assert_close, complex, eigenvalues, eom, eom_json};
use num_complex::Complex64;
use tests::references::sidecar;

/// Reference eigenvalues in the order `eom analyze` prints them: by real part, then imaginary.
fn in_printed_order(z: &[Complex64]) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = z.iter().map(|z| (z.re, z.im)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    v
}

/// Roots of `a3 s³ + a2 s² + a1 s + a0` with one real root and a complex pair: the real root
/// by Newton's method, the pair from the deflated quadratic. Sorted by (re, im).
fn cubic_roots(a3: f64, a2: f64, a1: f64, a0: f64) -> Vec<(f64, f64)> {
    let p = |s: f64| ((a3 * s + a2) * s + a1) * s + a0;
    let dp = |s: f64| (3.0 * a3 * s + 2.0 * a2) * s + a1;
    // Start left of every root: the sum of the roots is −a2/a3.
    let mut r = -a2 / a3 - 1.0;
    for _ in 0..100 {
        r -= p(r) / dp(r);
    }
    // a3 s³ + … = (s − r)(a3 s² + b1 s + b0)
    let b1 = a2 + a3 * r;
    let b0 = a1 + b1 * r;
    let disc = b1 * b1 - 4.0 * a3 * b0;
    assert!(disc < 0.0, "the reference cubic has a complex pair");
    let (re, im) = (-b1 / (2.0 * a3), (-disc).sqrt() / (2.0 * a3));
    let mut v = vec![(r, 0.0), (re, -im), (re, im)];
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    v
}

/// The shimmy model's characteristic polynomial (Schwab & Meijaard 2003, the swivel wheel with
/// a no-slip tyre): `(Iz + m a²) s³ + m a u s² + k l² s + k l u`, `a = x l`.
fn shimmy_cubic(m: f64, iz: f64, k: f64, l: f64, x: f64, u: f64) -> Vec<(f64, f64)> {
    let a = x * l;
    cubic_roots(iz + m * a * a, m * a * u, k * l * l, k * l * u)
}

#[test]
fn shimmy_json_has_the_required_keys_and_the_closed_form_eigenvalues() {
    let j = eom_json(&["analyze", "shimmy", "--format", "json"]);
    for key in [
        "model",
        "parameters",
        "states",
        "eigenvalues",
        "modes",
        "minimal",
        "steady_state_gain",
        "zeros",
        "warnings",
    ] {
        assert!(j.get(key).is_some(), "key `{key}` missing");
    }
    assert!(j.get("frequency_response").is_none(), "only with --freq");
    assert_eq!(j["model"], "shimmy");
    assert_eq!(j["states"], 3);
    // Every parameter, defaults included.
    let p = j["parameters"].as_object().unwrap();
    for (name, v) in [
        ("m", 5.0),
        ("I", 1.05),
        ("k", 1.5),
        ("l", 1.0),
        ("x", 0.5),
        ("u", 10.0),
    ] {
        assert_eq!(p[name].as_f64(), Some(v), "parameter {name}");
    }
    // The sidecar's digits at the defaults and the cubic solved here agree …
    let reference = in_printed_order(&sidecar("shimmy").eigenvalues_at(&[]).expected());
    assert_close(
        &shimmy_cubic(5.0, 1.05, 1.5, 1.0, 0.5, 10.0),
        &reference,
        1e-12,
    );
    // … and the model reproduces them.
    assert_close(&eigenvalues(&j), &reference, 1e-10);
    let modes = j["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 3);
    assert_eq!(modes[0]["kind"], "real");
    assert_eq!(modes[2]["kind"], "oscillatory");
    assert!(modes.iter().all(|m| m["stable"] == true));
    // A real pole reports its corner frequency, not 0 Hz.
    let f = modes[0]["natural_frequency_hz"].as_f64().unwrap();
    let (real, pair) = (reference[0], reference[2]);
    assert!(real.1 == 0.0 && pair.1 > 0.0, "{reference:?}");
    assert!(
        (f - real.0.abs() / (2.0 * std::f64::consts::PI)).abs() < 1e-9,
        "{f}"
    );
    assert_eq!(modes[0]["period"], serde_json::Value::Null);
    let period = modes[2]["period"].as_f64().unwrap();
    assert!((period - 2.0 * std::f64::consts::PI / pair.1).abs() < 1e-8);
    assert_eq!(j["minimal"]["states"], 3);
}

#[test]
fn set_changes_the_point_of_analysis() {
    // u = 1 at the default a/l = 0.5: a row of the sidecar's table at u = 1.
    let refs = sidecar("shimmy");
    let table = refs.table("tests/data/shimmy_eigs_u1.csv", &[("u", 1.0)]);
    let reference = in_printed_order(&table.row(0.5));
    assert_close(
        &shimmy_cubic(5.0, 1.05, 1.5, 1.0, 0.5, 1.0),
        &reference,
        1e-12,
    );
    for method in ["numeric", "robust", "symbolic"] {
        let j = eom_json(&[
            "analyze", "shimmy", "--set", "u=1", "--method", method, "--format", "json",
        ]);
        assert_eq!(j["parameters"]["u"].as_f64(), Some(1.0));
        assert_eq!(j["method"], method);
        assert_close(&eigenvalues(&j), &reference, 1e-10);
    }
}

/// Meijaard, Papadopoulos, Ruina & Schwab (2007), Proc. R. Soc. A 463, Table 2(b) (the
/// sidecar's published table): the eigenvalues of the benchmark bicycle at v = 5 m/s
/// (castering, weave pair, capsize); the model adds two zero modes (heading and lateral
/// position, which the outputs do not see).
#[test]
fn bicycle_at_5_m_per_s_has_the_published_eigenvalues() {
    let refs = sidecar("bicycle");
    let table = refs.table("tests/data/bicycle_table2.csv", &[]);
    let published = in_printed_order(&table.row(5.0));
    assert_eq!(published.len(), 4);
    for args in [
        &["analyze", "bicycle", "--format", "json"][..],
        &[
            "analyze", "bicycle", "--set", "v=5", "--method", "robust", "--format", "json",
        ],
    ] {
        let j = eom_json(args);
        assert_eq!(j["states"], 6);
        let eig = eigenvalues(&j);
        let (zero, rest): (Vec<_>, Vec<_>) = eig.iter().partition(|z| z.0.hypot(z.1) < 1e-5);
        assert_eq!(zero.len(), 2, "{eig:?}");
        assert_close(&rest, &published, 1e-10);
        let modes = j["modes"].as_array().unwrap();
        assert_eq!(modes.iter().filter(|m| m["kind"] == "zero").count(), 2);
        // The sensors (steer and roll angle) do not see the zero modes: removed, and said so.
        let min = &j["minimal"];
        assert_eq!(min["states"], 4);
        assert_close(&eigenvalues(min), &published, 1e-9);
        let removed = min["removed"].as_array().unwrap();
        assert_eq!(removed.len(), 2);
        for r in removed {
            assert_eq!(r["reason"], "unobservable");
            assert_eq!(r["stability"], "marginal");
            assert_eq!(r["kind"], "zero");
            assert!(complex(&r["eigenvalue"]).0.abs() < 1e-5);
        }
    }
}

/// `m z̈ + c ż + k z = f`: `G(jω) = 1 / (k − m ω² + j c ω)`.
#[test]
fn frequency_response_of_the_spring_mass_damper_is_the_closed_form() {
    let j = eom_json(&[
        "analyze",
        "smd",
        "--freq-range",
        "0.1:10",
        "--points",
        "5",
        "--format",
        "json",
    ]);
    let fr = &j["frequency_response"];
    let f: Vec<f64> = fr["frequency_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(f.len(), 5);
    assert!(
        (f[0] - 0.1).abs() < 1e-12 && (f[4] - 10.0).abs() < 1e-12,
        "{f:?}"
    );
    let pairs = fr["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 3, "outputs z, z dot, kz × input f");
    let z = pairs
        .iter()
        .find(|p| p["output"] == "z" && p["input"] == "f")
        .unwrap();
    let (m, c, k) = (1.0, 0.1, 10.0);
    for (i, &fi) in f.iter().enumerate() {
        let w = 2.0 * std::f64::consts::PI * fi;
        let (re, im) = (k - m * w * w, c * w);
        let mag_db = -20.0 * re.hypot(im).log10();
        let phase = -im.atan2(re).to_degrees();
        let got_db = z["magnitude_db"][i].as_f64().unwrap();
        let got_ph = z["phase_deg"][i].as_f64().unwrap();
        assert!(
            (got_db - mag_db).abs() < 1e-9,
            "f = {fi}: {got_db} dB vs {mag_db}"
        );
        assert!(
            (got_ph - phase).abs() < 1e-9,
            "f = {fi}: {got_ph}° vs {phase}"
        );
    }
    // Static compliance 1/k.
    let g = &j["steady_state_gain"][0];
    assert_eq!(g["output"], "z");
    assert!((g["value"].as_f64().unwrap() - 1.0 / k).abs() < 1e-14);
}

#[test]
fn text_report_has_the_tables() {
    let r = eom(&["analyze", "bicycle"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for h in [
        "Modes of the state-space model (6 states",
        "eigenvalue [1/s]",
        "freq [Hz]",
        "damping",
        "tau [s]",
        "period [s]",
        "kind",
        "stability",
        "zero (rigid-body/integrator)",
        "-0.775342 ± 4.46487i",
        "Modes seen from the inputs and outputs (minimal realization: 4 of 6 states)",
        "Removed by the minimal realization (2)",
        "is unobservable: the outputs cannot see it",
        "Steady-state gains",
        "delta / T_delta",
        "Transmission zeros",
        "Warnings",
    ] {
        assert!(r.stdout.contains(h), "`{h}` missing from:\n{}", r.stdout);
    }
    let r = eom(&["analyze", "smd", "--freq", "--points", "3"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.contains("Frequency response (3 points"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("z/f [dB]"), "{}", r.stdout);
}
