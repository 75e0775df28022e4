//! The Navion in free flight (`eom analyze navion`) against the rigid-body flight equations
//! written out by hand (`tests/data/aero/navion.py` → `navion.json`; docs/aero-references.md
//! §4) and against the roots R. C. Nelson prints (*Flight Stability and Automatic Control*,
//! 2nd ed., 1998, App. B and the Navion examples of ch. 4–5) in his form (CZq neglected).

mod common;
use common::{eigenvalues, eom_json};
use std::path::Path;

fn reference() -> serde_json::Value {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/aero/navion.json");
    serde_json::from_str(&std::fs::read_to_string(p).expect("reference")).expect("JSON")
}

fn pair(v: &serde_json::Value) -> (f64, f64) {
    (v["re"].as_f64().expect("re"), v["im"].as_f64().expect("im"))
}

/// The eigenvalues of `eom analyze navion` (with `set`), by the given method.
fn roots(set: &[&str], method: &str) -> Vec<(f64, f64)> {
    let mut args = vec!["analyze", "navion", "--format", "json", "--method", method];
    for s in set {
        args.extend(["--set", s]);
    }
    let j = eom_json(&args);
    assert_eq!(
        j["states"], 12,
        "u v w p q r, φ θ ψ and the positions x y z"
    );
    eigenvalues(&j)
}

/// Whether `want` is among `got` to a relative 1e-6.
fn has(got: &[(f64, f64)], want: (f64, f64)) -> bool {
    got.iter().any(|z| {
        let d = ((z.0 - want.0).powi(2) + (z.1 - want.1).powi(2)).sqrt();
        d <= 1e-6 * want.0.hypot(want.1)
    })
}

#[test]
fn navion_modes_are_the_flight_equations() {
    let r = reference();
    let full = &r["full_equations"];
    for method in ["numeric", "symbolic", "robust"] {
        let got = roots(&[], method);
        for mode in ["short_period", "phugoid", "dutch_roll"] {
            let z = pair(&full[mode]);
            assert!(
                has(&got, z) && has(&got, (z.0, -z.1)),
                "{method} {mode}: {z:?} in {got:?}"
            );
        }
        for mode in ["roll", "spiral"] {
            let z = (full[mode].as_f64().expect("real"), 0.0);
            assert!(has(&got, z), "{method} {mode}: {z:?} in {got:?}");
        }
        // ψ and the positions x, y, z: four zero eigenvalues.
        let zeros = got.iter().filter(|z| z.0.hypot(z.1) < 1e-9).count();
        assert_eq!(zeros, 4, "{method}: {got:?}");
    }
}

/// Nelson neglects CZq (his Z_q): with `--set CZq=0` eom gives his longitudinal roots, and
/// rounded to his digits every root he prints.
#[test]
fn nelsons_printed_roots_to_his_digits() {
    let r = reference();
    let got = roots(&["CZq=0"], "numeric");
    let nf = &r["nelson_form"]["longitudinal_without_Zq"];
    for mode in ["short_period", "phugoid"] {
        let z = pair(&nf[mode]);
        assert!(has(&got, z), "{mode}: {z:?} in {got:?}");
    }
    let printed = &r["nelson_printed"];
    // (root, the printed digits: decimal places of the real and imaginary parts)
    let find = |re: f64, im: f64| {
        got.iter()
            .filter(|z| z.1 >= 0.0)
            .min_by(|a, b| {
                let da = (a.0 - re).hypot(a.1 - im);
                let db = (b.0 - re).hypot(b.1 - im);
                da.total_cmp(&db)
            })
            .copied()
            .expect("a root")
    };
    let round = |x: f64, places: i32| (x * 10f64.powi(places)).round() / 10f64.powi(places);
    let cases: [(&str, i32, i32); 3] = [
        ("short_period", 1, 2),
        ("phugoid", 4, 3),
        ("dutch_roll", 3, 3),
    ];
    for (mode, pr, pi) in cases {
        let p = printed[mode].as_array().expect("re, im");
        let (re, im) = (p[0].as_f64().expect("re"), p[1].as_f64().expect("im"));
        let z = find(re, im);
        assert_eq!((round(z.0, pr), round(z.1, pi)), (re, im), "{mode}: {z:?}");
    }
    for (mode, places) in [("roll", 3), ("spiral", 5)] {
        let want = printed[mode].as_f64().expect("real");
        let z = find(want, 0.0);
        assert_eq!(round(z.0, places), want, "{mode}: {z:?}");
    }
}
