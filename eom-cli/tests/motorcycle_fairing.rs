//! A motorcycle with a fork-mounted fairing (`models/motorcycle_fairing.toml`,
//! docs/towing-and-fairings.md) against the benchmark bicycle's linear equations (Meijaard et al.
//! 2007, App. A) with the fairing's quasi-steady side force written out by hand
//! (`tests/data/aero/motorcycle_fairing.py` → `motorcycle_fairing.json`):
//!
//! * the eigenvalues at 5 … 40 m/s with and without the fairing (`--set Sf=0`);
//! * the weave and capsize speeds, the stability boundaries of `eom sweep … --param v=…`, with
//!   and without it;
//! * the fairing's added damping and aerodynamic stiffness as first-order perturbation:
//!   `eom analyze --sensitivity` at `Sf = 0` gives ∂λ/∂Sf, which the closed form
//!   uᵀ ΔA v / uᵀ v (ΔA from C_ff = d J Jᵀ, K = d b J e_δᵀ, per unit area) must equal.

mod common;
use common::{complex, eigenvalues, eom_json};
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn model() -> String {
    repo()
        .join("models/motorcycle_fairing.toml")
        .to_str()
        .expect("UTF-8")
        .to_string()
}

fn reference() -> serde_json::Value {
    let p = repo().join("tests/data/aero/motorcycle_fairing.json");
    serde_json::from_str(&std::fs::read_to_string(p).expect("reference")).expect("JSON")
}

fn pairs(v: &serde_json::Value) -> Vec<Vec<f64>> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|r| {
            r.as_array()
                .expect("a row")
                .iter()
                .map(|x| x.as_f64().expect("a number"))
                .collect()
        })
        .collect()
}

/// The index of the eigenvalue of `got` nearest `want`, and its distance.
fn nearest(got: &[(f64, f64)], want: (f64, f64)) -> (usize, f64) {
    got.iter()
        .enumerate()
        .map(|(k, g)| (k, (g.0 - want.0).hypot(g.1 - want.1)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("eigenvalues")
}

#[test]
fn the_modes_are_the_benchmark_equations_with_the_fairing() {
    let r = reference();
    for (speed, data) in r["speeds"].as_object().expect("speeds") {
        // Every reduction path at one speed, the numeric one at all.
        let methods: &[&str] = if speed == "20" {
            &["numeric", "symbolic", "robust"]
        } else {
            &["numeric"]
        };
        let cases = [("with_fairing", "0.4"), ("without", "0")];
        for ((key, sf), method) in cases
            .into_iter()
            .flat_map(|c| methods.iter().map(move |m| (c, *m)))
        {
            let set_v = format!("v={speed}");
            let set_s = format!("Sf={sf}");
            let got = eigenvalues(&eom_json(&[
                "analyze",
                &model(),
                "--set",
                &set_v,
                "--set",
                &set_s,
                "--format",
                "json",
                "--method",
                method,
            ]));
            // The rear contact's lateral position and the heading: two zeros.
            assert_eq!(got.len(), 6, "{got:?}");
            assert_eq!(got.iter().filter(|z| z.0.hypot(z.1) < 1e-9).count(), 2);
            for w in pairs(&data[key]) {
                let (_, d) = nearest(&got, (w[0], w[1]));
                assert!(
                    d <= 1e-8 * w[0].hypot(w[1]).max(1.0),
                    "v = {speed}, {key}, {method}: {w:?} not in {got:?}"
                );
            }
        }
    }
}

#[test]
fn the_weave_and_capsize_speeds_are_the_references() {
    let r = reference();
    for (key, sf) in [
        ("boundaries_with_fairing", "0.4"),
        ("boundaries_without", "0"),
    ] {
        let set_s = format!("Sf={sf}");
        let s = eom_json(&[
            "sweep",
            &model(),
            "--param",
            "v=1:40:79",
            "--set",
            &set_s,
            "--format",
            "json",
            "--quiet",
        ]);
        let got: Vec<f64> = s["boundaries"]
            .as_array()
            .expect("boundaries")
            .iter()
            .map(|b| b["value"].as_f64().expect("a speed"))
            .collect();
        let want: Vec<f64> = r[key]
            .as_array()
            .expect("speeds")
            .iter()
            .map(|x| x.as_f64().expect("a speed"))
            .collect();
        assert_eq!(got.len(), 2, "{key}: weave and capsize, got {got:?}");
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-8 * w, "{key}: {got:?} vs {want:?}");
        }
    }
    // The fairing moves both (the check can tell them apart).
    let (a, b) = (
        r["boundaries_with_fairing"][0].as_f64().expect("weave"),
        r["boundaries_without"][0].as_f64().expect("weave"),
    );
    assert!((a - b).abs() > 0.05, "{a} vs {b}");
}

#[test]
fn the_fairings_first_order_effect_is_the_closed_form() {
    let r = reference();
    for speed in ["5", "20", "40"] {
        let set_v = format!("v={speed}");
        let a = eom_json(&[
            "analyze",
            &model(),
            "--set",
            &set_v,
            "--set",
            "Sf=0",
            "--sensitivity",
            "--format",
            "json",
        ]);
        let sens: Vec<((f64, f64), (f64, f64))> = a["sensitivity"]
            .as_array()
            .expect("sensitivity")
            .iter()
            // The two zeros (a double eigenvalue) are flagged, without derivatives.
            .filter(|s| s["derivatives"]["Sf"]["re"].is_number())
            .map(|s| (complex(&s["eigenvalue"]), complex(&s["derivatives"]["Sf"])))
            .collect();
        assert_eq!(sens.len(), 4, "v = {speed}: {}", a["sensitivity"]);
        let lams: Vec<(f64, f64)> = sens.iter().map(|s| s.0).collect();
        for w in pairs(&r["speeds"][speed]["dlambda_dSf"]) {
            let (k, d) = nearest(&lams, (w[0], w[1]));
            assert!(
                d <= 1e-8 * w[0].hypot(w[1]),
                "v = {speed}: {w:?} in {lams:?}"
            );
            let g = sens[k].1;
            let scale = w[2].hypot(w[3]);
            assert!(
                (g.0 - w[2]).hypot(g.1 - w[3]) <= 1e-6 * scale,
                "v = {speed}, λ = {:?}: ∂λ/∂Sf {g:?}, closed form ({}, {})",
                lams[k],
                w[2],
                w[3]
            );
        }
    }
}
