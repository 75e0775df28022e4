//! Flutter from `eom sweep` against independent references (docs/aero-references.md,
//! `tests/data/aero/`): the typical section of Hodges & Pierce and the Goland wing, built from
//! strips with Jones' lag states, against their exact Theodorsen flutter (k-method confirmed by
//! a determinant root) and the same equations with Jones' states and quasi-steady, each
//! computed by the repository's Python scripts.

mod common;
use common::{complex, eigenvalues, eom, eom_json};
use std::path::{Path, PathBuf};

fn reference(file: &str) -> serde_json::Value {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/aero")
        .join(file);
    serde_json::from_str(&std::fs::read_to_string(&p).expect("reference data")).expect("JSON")
}

fn num(v: &serde_json::Value, path: &[&str]) -> f64 {
    let mut x = v;
    for k in path {
        x = &x[*k];
    }
    x.as_f64()
        .unwrap_or_else(|| panic!("no number at {path:?}"))
}

/// The sweep's oscillatory boundaries (value, |Im λ|) and its real ones (value).
fn boundaries(model: &str, grid: &str, set: &[&str]) -> (Vec<(f64, f64)>, Vec<f64>) {
    let mut args = vec![
        "sweep", model, "--param", grid, "--format", "json", "--quiet",
    ];
    for s in set {
        args.extend(["--set", s]);
    }
    let j = eom_json(&args);
    let (mut osc, mut real) = (Vec::new(), Vec::new());
    for b in j["boundaries"].as_array().expect("boundaries") {
        let (re, im) = complex(&b["eigenvalue"]);
        let v = b["value"].as_f64().expect("value");
        assert!(re.abs() < 1e-6 * im.abs().max(1.0), "{b}");
        if im.abs() > 1e-6 {
            osc.push((v, im.abs()));
        } else {
            real.push(v);
        }
    }
    (osc, real)
}

fn rel(got: f64, want: f64) -> f64 {
    (got - want) / want
}

/// U_F/(b ω_θ) and ω_F/ω_θ from the sweep at b = 0.5, ω_θ = 10 (the defaults) and at other b,
/// ω_θ (the ratios do not change: a missing factor b would show): equal to the Jones-state
/// reference (the same equations) to 1e-7, within 1 % of exact Theodorsen; the divergence
/// speed is the closed form U_D = b ω_θ √(μ r²/(1 + 2a)) = √8 b ω_θ.
#[test]
fn typical_section_flutters_where_theodorsen_says() {
    let r = reference("typical_section.json");
    let jones = (
        num(&r, &["jones_states", "U_F_over_b_omega_theta"]),
        num(&r, &["jones_states", "omega_F_over_omega_theta"]),
    );
    let exact = (
        num(&r, &["theodorsen_exact", "U_F_over_b_omega_theta"]),
        num(&r, &["theodorsen_exact", "omega_F_over_omega_theta"]),
    );
    for (b, w, set) in [(0.5, 10.0, vec![]), (1.3, 7.0, vec!["b=1.3", "w_theta=7"])] {
        let bw = b * w;
        let grid = format!("V={}:{}:39", 0.2 * bw, 4.0 * bw);
        let (osc, real) = boundaries("typical_section", &grid, &set);
        assert_eq!(osc.len(), 1, "{osc:?}");
        let (uf, wf) = (osc[0].0 / bw, osc[0].1 / w);
        assert!(
            rel(uf, jones.0).abs() < 1e-7,
            "U_F/(b ω) {uf} vs {}",
            jones.0
        );
        assert!(rel(wf, jones.1).abs() < 1e-7, "ω_F/ω_θ {wf} vs {}", jones.1);
        assert!(
            rel(uf, exact.0).abs() < 0.01,
            "U_F {uf} vs exact {}",
            exact.0
        );
        assert!(
            rel(wf, exact.1).abs() < 0.01,
            "ω_F {wf} vs exact {}",
            exact.1
        );
        assert_eq!(real.len(), 1, "{real:?}");
        assert!(rel(real[0] / bw, 8f64.sqrt()).abs() < 1e-8, "{real:?}");
    }
}

/// The same section with quasi-steady lift (`unsteady = "quasi-steady"`): the reference's
/// quasi-steady flutter (57 % below the exact speed).
#[test]
fn quasi_steady_typical_section_is_far_off() {
    let r = reference("typical_section.json");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../models/typical_section.toml");
    let text = std::fs::read_to_string(src).expect("model file");
    assert!(text.contains("unsteady = \"jones\""));
    let dir = std::env::temp_dir().join(format!("eom-aeroelastic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a directory");
    let file: PathBuf = dir.join("typical_section_qs.toml");
    std::fs::write(
        &file,
        text.replace("unsteady = \"jones\"", "unsteady = \"quasi-steady\""),
    )
    .expect("written");
    let (osc, _) = boundaries(file.to_str().expect("UTF-8"), "V=1:20:39", &[]);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(osc.len(), 1, "{osc:?}");
    let uf = osc[0].0 / 5.0;
    let wf = osc[0].1 / 10.0;
    let want = (
        num(&r, &["quasi_steady", "U_F_over_b_omega_theta"]),
        num(&r, &["quasi_steady", "omega_F_over_omega_theta"]),
    );
    assert!(rel(uf, want.0).abs() < 1e-7, "{uf} vs {}", want.0);
    assert!(rel(wf, want.1).abs() < 1e-7, "{wf} vs {}", want.1);
    let exact = num(&r, &["theodorsen_exact", "U_F_over_b_omega_theta"]);
    assert!(
        rel(uf, exact) < -0.5,
        "quasi-steady is far below: {uf} vs {exact}"
    );
}

/// The lag states on every path: `eom analyze` by the symbolic, numeric and robust methods
/// gives the same six eigenvalues near flutter.
#[test]
fn every_path_carries_the_lag_states() {
    let run = |m: &str| {
        let j = eom_json(&[
            "analyze",
            "typical_section",
            "--set",
            "V=10.8",
            "--method",
            m,
            "--format",
            "json",
        ]);
        assert_eq!(j["states"], 6, "{m}");
        let mut e = eigenvalues(&j);
        e.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        e
    };
    let numeric = run("numeric");
    for m in ["symbolic", "robust"] {
        let other = run(m);
        for (a, b) in numeric.iter().zip(&other) {
            let d = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
            assert!(d < 1e-9 * (a.0.hypot(a.1)).max(1.0), "{m}: {a:?} vs {b:?}");
        }
    }
    let text = eom(&["analyze", "typical_section"]).stdout;
    assert!(text.contains("airfoil.lag1, airfoil.lag2"), "{text}");
}

/// The Goland wing of the catalogue (16 segments): the reference's 16-segment lumped model
/// with Jones' states to 1e-7, and within 1.5 % of the converged Theodorsen strip-theory
/// flutter (10 + 10 modes) in speed and frequency.
#[test]
fn goland_wing_flutters_where_strip_theory_says() {
    let r = reference("goland.json");
    let row = r["lumped_with_slope_inertia"]
        .as_array()
        .expect("rows")
        .iter()
        .find(|x| x["segments"] == 16)
        .expect("N = 16")
        .clone();
    let modal = r["modal"]
        .as_array()
        .expect("modal rows")
        .last()
        .expect("a converged row")
        .clone();
    let (osc, _) = boundaries("goland_wing", "V=100:180:17", &[]);
    assert_eq!(osc.len(), 1, "{osc:?}");
    let (uf, wf) = osc[0];
    let (uj, wj) = (
        num(&row, &["jones", "U_F_m_s"]),
        num(&row, &["jones", "omega_F_rad_s"]),
    );
    assert!(rel(uf, uj).abs() < 1e-7, "U_F {uf} vs {uj}");
    assert!(rel(wf, wj).abs() < 1e-7, "ω_F {wf} vs {wj}");
    let (ut, wt) = (
        num(&modal, &["theodorsen", "U_F_m_s"]),
        num(&modal, &["theodorsen", "omega_F_rad_s"]),
    );
    assert!(rel(uf, ut).abs() < 0.015, "U_F {uf} vs converged {ut}");
    assert!(rel(wf, wt).abs() < 0.015, "ω_F {wf} vs converged {wt}");
}

/// A copy of a shipped model file with `from` replaced by `to`, in a directory of its own.
fn edited(model: &str, from: &str, to: &str, tag: &str) -> (PathBuf, PathBuf) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../models/{model}.toml"));
    let text = std::fs::read_to_string(src).expect("model file");
    assert!(text.contains(from), "{model}: no `{from}`");
    let dir = std::env::temp_dir().join(format!("eom-aero-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a directory");
    let file = dir.join(format!("{model}.toml"));
    std::fs::write(&file, text.replacen(from, to, 1)).expect("written");
    (dir, file)
}

/// `unsteady = "auto"`: the wing of the spring–mass–damper gets Jones' states where its mode's
/// k = |Im λ|·b/V exceeds 0.05 (V = 10 m/s: k ≈ 0.15) and the output says so, with the same
/// eigenvalues as `"jones"`; at V = 100 m/s (no oscillatory mode) it stays quasi-steady.
#[test]
fn auto_adds_lag_states_where_the_modes_need_them() {
    let from = "density = \"rho\"\n";
    let (d1, auto) = edited(
        "smd_wing",
        from,
        "density = \"rho\"\nunsteady = \"auto\"\n",
        "auto",
    );
    let (d2, jones) = edited(
        "smd_wing",
        from,
        "density = \"rho\"\nunsteady = \"jones\"\n",
        "jones",
    );
    let run = |f: &PathBuf, v: &str| {
        eom_json(&[
            "analyze",
            f.to_str().expect("UTF-8"),
            "--set",
            v,
            "--format",
            "json",
        ])
    };
    let (a, j) = (run(&auto, "V=10"), run(&jones, "V=10"));
    assert_eq!(a["states"], 4);
    let warned = |j: &serde_json::Value, kind: &str| {
        j["warnings"].as_array().unwrap().iter().any(|w| {
            w["kind"] == kind && w["item"]["kind"] == "wing" && w["item"]["name"] == "wing"
        })
    };
    assert!(warned(&a, "auto_lagged"), "{}", a["warnings"]);
    // The reduced frequency that decided it (0.14) is printed in the message.
    assert!(
        a["warnings"].to_string().contains("k = |Im λ|·b/V = 0.14"),
        "{}",
        a["warnings"]
    );
    let (mut ea, mut ej) = (eigenvalues(&a), eigenvalues(&j));
    ea.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
    ej.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
    assert_eq!(ea, ej);
    let q = run(&auto, "V=100");
    assert_eq!(q["states"], 2);
    assert!(warned(&q, "auto_quasi_steady"), "{}", q["warnings"]);
    // The typical section with `auto` flutters where the Jones model does (decided at the
    // nominal V = 8 m/s, where its modes have k ≈ 0.3).
    let (d3, ts) = edited(
        "typical_section",
        "unsteady = \"jones\"",
        "unsteady = \"auto\"",
        "auto-ts",
    );
    let (osc, _) = boundaries(ts.to_str().expect("UTF-8"), "V=1:20:39", &[]);
    let r = reference("typical_section.json");
    assert!(
        rel(
            osc[0].0 / 5.0,
            num(&r, &["jones_states", "U_F_over_b_omega_theta"])
        )
        .abs()
            < 1e-7
    );
    for d in [d1, d2, d3] {
        let _ = std::fs::remove_dir_all(d);
    }
}

/// `[model] unsteady` is the default of the wings and strips that do not set their own; a bad
/// value is an error naming the key and the values allowed.
#[test]
fn the_models_unsteady_is_the_default_of_its_surfaces() {
    let (d1, f) = edited(
        "smd_wing",
        "name = \"smd_wing\"\n",
        "name = \"smd_wing\"\nunsteady = \"auto\"\n",
        "model-auto",
    );
    let j = eom_json(&[
        "analyze",
        f.to_str().expect("UTF-8"),
        "--set",
        "V=10",
        "--format",
        "json",
    ]);
    assert_eq!(j["states"], 4, "{}", j["warnings"]);
    let (d2, bad) = edited(
        "typical_section",
        "unsteady = \"jones\"",
        "unsteady = \"jonse\"",
        "bad",
    );
    let r = eom(&["analyze", bad.to_str().expect("UTF-8")]);
    assert_ne!(r.code, 0);
    assert!(
        r.stderr.contains("strip `airfoil`")
            && r.stderr
                .contains("`jonse`: expected \"quasi-steady\", \"jones\" or \"auto\""),
        "{}",
        r.stderr
    );
    for d in [d1, d2] {
        let _ = std::fs::remove_dir_all(d);
    }
}
