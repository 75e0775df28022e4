//! The wing models and `eom aero` as the user sees them: the seed paper's damping entries of
//! the shimmy's fin under `wings` in `eom analyze`, the reduced-frequency warnings (the stable
//! interval of the shimmy with the fin is a reference answer of `models/shimmy_wing.ref.toml`,
//! checked by tests/references.rs), the spring–mass–damper under
//! a wing in closed form (`eom symbolic`), two sweeps in one plot, and AVL files (real AVL 3.32
//! output of the seed fin, `eom-aero/tests/data`).

#![allow(clippy::excessive_precision)] // reference values as published

mod common;
use common::{eom, eom_json};
use eom_sym::{Scope, Tape};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The seed paper's entries L22, L26, L62, L66 of the fin at ρ = 1.225, V = 10.
const PAPER_L: [((usize, usize), f64); 4] = [
    ((1, 1), 7.59895),
    ((1, 5), -2.05293),
    ((5, 1), 0.153319),
    ((5, 5), 0.224167),
];

fn data(file: &str) -> String {
    format!(
        "{}/../eom-aero/tests/data/{file}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn analyze_reports_the_papers_damping_entries_under_wings() {
    let j = eom_json(&[
        "analyze",
        "shimmy_wing",
        "--set",
        "u=10",
        "--format",
        "json",
    ]);
    let w = &j["wings"][0];
    assert_eq!(w["name"], "fin");
    for ((i, k), want) in PAPER_L {
        let got = w["damping"][i][k].as_f64().expect("a number");
        assert!(
            ((got - want) / want).abs() <= 1e-9,
            "L{}{} = {got}",
            i + 1,
            k + 1
        );
    }
    // Models without wings have no `wings` key.
    let j = eom_json(&["analyze", "shimmy", "--format", "json"]);
    assert!(j.get("wings").is_none());
}

/// β = |Im λ|·c/V: at u = 1 the shimmy's oscillation (ω ≈ 0.72 rad/s) gives β ≈ 0.36, far
/// above 0.1; at u = 10 (x = 0.5) β ≈ 0.035.
#[test]
fn reduced_frequency_warnings_at_low_speed_only() {
    for (u, warned) in [("u=1", true), ("u=10", false)] {
        let j = eom_json(&[
            "analyze",
            "shimmy_wing",
            "--set",
            u,
            "--set",
            "x=0.5",
            "--format",
            "json",
        ]);
        let betas = j["wings"][0]["reduced_frequencies"].as_array().unwrap();
        assert_eq!(betas.len(), 1, "one oscillatory pair");
        let b = &betas[0];
        let im = b["eigenvalue"]["im"].as_f64().unwrap();
        let v: f64 = u[2..].parse().unwrap();
        let beta = b["beta"].as_f64().unwrap();
        assert!(
            (beta - im * 0.5 / v).abs() <= 1e-15 * beta.max(1.0),
            "{beta}"
        );
        assert_eq!(b["too_high"], warned);
        let warnings = j["warnings"].as_array().unwrap();
        assert_eq!(
            warnings.iter().any(|w| {
                w["kind"] == "reduced_frequency_beyond_limit"
                    && w["item"]["kind"] == "wing"
                    && w["item"]["name"] == "fin"
            }),
            warned,
            "{u}: {warnings:?}"
        );
    }
    let text = eom(&["analyze", "shimmy_wing", "--set", "u=1"]).stdout;
    assert!(
        text.contains("TOO HIGH") && text.contains("Wings ("),
        "{text}"
    );
}

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| {
            x["expression"]
                .as_str()
                .or(x.as_str())
                .expect("a string")
                .to_string()
        })
        .collect()
}

/// docs/references.md §D: ζ = (ρVS(CLa + CD) + 2c)/(4√(km)), stable exactly when
/// c + ρVS(CLa + CD)/2 > 0.
#[test]
fn symbolic_smd_wing_is_the_closed_form() {
    let j = eom_json(&["symbolic", "smd_wing", "--stability", "--format", "json"]);
    let names = ["m", "k", "c", "rho", "V", "S", "CLa", "CD"];
    let zeta = j["second_order"]["damping_ratio"]
        .as_str()
        .unwrap()
        .to_string();
    let conds = strings(&j["stability"]);
    let mut scope = Scope::new();
    let params: Vec<_> = names
        .iter()
        .map(|n| scope.declare(n, 1.0).unwrap())
        .collect();
    let mut exprs = vec![eom_sym::parse(&zeta, &scope).unwrap()];
    for c in &conds {
        exprs.push(eom_sym::parse(c, &scope).unwrap());
    }
    let tape = Tape::new(&exprs, &params).unwrap();
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..1000 {
        let mut v: Vec<f64> = (0..8).map(|_| 0.1 + 3.0 * rng.random::<f64>()).collect();
        // CLa and CD of either sign (a stalled wing), so that both sides are seen.
        v[6] = 4.0 * rng.random::<f64>() - 3.0;
        v[7] = 0.2 * rng.random::<f64>() - 0.1;
        let (m, k, c, rho, vel, s, cla, cd) = (v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
        let got = tape.eval_vec(&v).unwrap();
        let want = (rho * vel * s * (cla + cd) + 2.0 * c) / (4.0 * (k * m).sqrt());
        assert!(
            (got[0] - want).abs() <= 1e-12 * want.abs().max(1.0),
            "ζ {} vs {want}",
            got[0]
        );
        let margin = c + rho * vel * s * (cla + cd) / 2.0;
        if margin.abs() > 1e-9 {
            assert_eq!(
                got[1..].iter().all(|&x| x > 0.0),
                margin > 0.0,
                "at {v:?}: {conds:?}"
            );
        }
    }
}

#[test]
fn two_models_in_one_sweep_plot() {
    let dir = std::env::temp_dir().join(format!("eom-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("fin.svg");
    let r = eom(&[
        "sweep",
        "shimmy",
        "--compare",
        "shimmy_wing",
        "--param",
        "x=0:1:51",
        "--format",
        "json",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let sweeps = j["sweeps"].as_array().unwrap();
    assert_eq!(sweeps[0]["model"], "shimmy");
    assert_eq!(sweeps[1]["model"], "shimmy_wing");
    let lo = |k: usize| sweeps[k]["stable_intervals"][0][0].as_f64().unwrap();
    assert!((lo(0) - 0.3).abs() < 1e-9 && (lo(1) - 0.1019169433).abs() < 1e-9);
    let text = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert!(text.starts_with("<svg") && text.contains("shimmy vs shimmy_wing"));
    assert!(text.contains("stable: x in [0.3, 0.7]") && text.contains("[0.101917, 0.898083]"));
    let r = eom(&[
        "sweep",
        "shimmy",
        "--compare",
        "shimy",
        "--param",
        "x=0:1:5",
    ]);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr
            .contains("unknown model `shimy` (did you mean `shimmy`?)"),
        "{}",
        r.stderr
    );
}

#[test]
fn aero_prints_the_derivatives_of_avl_files() {
    // Real AVL 3.32 output: the file's own numbers.
    let j = eom_json(&["aero", &data("seed_fin_a0_avl332.sb"), "--format", "json"]);
    assert_eq!(j["derivatives"]["CYv"], -2.474202);
    assert_eq!(j["derivatives"]["Cnr"], -0.146157);
    let dim = j["dimensional"][1][1].as_f64().unwrap();
    assert!(
        (dim - -2.474202 * 0.5 * 1.225 * 10.0 * 0.5).abs() < 1e-12,
        "{dim}"
    );
    // The geometry by the vortex lattice: within 0.1 % of AVL's numbers.
    let g = eom_json(&["aero", &data("seed_fin.avl"), "--format", "json"]);
    for n in ["CYv", "CYr", "Cnv", "Cnr", "Clp"] {
        let (a, b) = (
            g["derivatives"][n].as_f64().unwrap(),
            j["derivatives"][n].as_f64().unwrap(),
        );
        assert!(((a - b) / b).abs() < 1e-3, "{n}: {a} vs {b}");
    }
    let text = eom(&["aero", &data("seed_fin_a0_avl332.st")]).stdout;
    assert!(
        text.contains("CYv = -2.4742") && text.contains("CXu = ?"),
        "{text}"
    );
    // What the ST file cannot give, by kind: the u column always, the CX row without the CD
    // rows (AVL 3.32); at α = 0 the w column comes from the trim totals.
    let st = eom_json(&["aero", &data("seed_fin_a0_avl332.st"), "--format", "json"]);
    let kinds: Vec<&str> = (st["warnings"].as_array().unwrap().iter())
        .map(|w| w["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["st_u_column", "st_cx_row"], "{}", st["warnings"]);
    assert!(
        (st["warnings"][0]["message"].as_str().unwrap()).starts_with("the u column (CXu ... Cnu)"),
        "{}",
        st["warnings"]
    );
    let r = eom(&["aero", &data("seed_fin_a0_avl332.sb"), "--alpha", "3"]);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr.contains("--alpha") && r.stderr.contains(".avl"),
        "{}",
        r.stderr
    );
    let r = eom(&["aero", "no-such-wing.sb"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
}

#[test]
fn the_wing_models_are_listed() {
    let text = eom(&["list"]).stdout;
    // The catalogue's models with wings, found by building each (the families at size 2).
    let winged: Vec<String> = models::catalogue()
        .iter()
        .map(|m| m.name_at(2))
        .filter(|name| {
            let model = models::build(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
            model.wings().next().is_some()
        })
        .collect();
    assert!(winged.len() >= 5, "{winged:?}");
    for m in &winged {
        assert!(text.contains(m.as_str()), "{m} missing:\n{text}");
    }
}

#[test]
fn check_counts_the_wing_of_a_model_file_reading_avl_output() {
    let file = format!(
        "{}/../models/tests/data/shimmy_fin_avl.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let r = eom(&["check", &file]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("1 wing"), "{}", r.stdout);
}
