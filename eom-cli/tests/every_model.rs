//! Every model through every command: each entry of the built-in catalogue (the chain families
//! at size 2) and each model file under `models/`, found by iterating `models::catalogue()` and
//! the directory (never a typed list), through `analyze` (text and JSON), `sweep` over its
//! first parameter, `symbolic`, `report`, `codegen`, `check` and `export` (the exported file
//! checked back). Each must succeed, and each report must have every part: none may say that
//! it could not be made.

mod common;
use common::eom;
use std::path::{Path, PathBuf};

/// A model as the command line names it, with its first parameter and that parameter's
/// nominal value.
struct Case {
    name: String,
    first: (String, f64),
}

/// Every catalogue entry, a family (`chainN`) at size 2.
fn catalogue() -> Vec<Case> {
    models::catalogue()
        .iter()
        .map(|info| {
            let name = info.name_at(2);
            let model = models::build(&name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
            Case {
                first: first_parameter(&model),
                name,
            }
        })
        .collect()
}

/// Every `models/*.toml` (but the crate's `Cargo.toml` and the sidecars `*.ref.toml`).
fn files() -> Vec<Case> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../models");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the models directory")
        .map(|e| e.expect("a directory entry").path())
        // The directory is also the `models` crate: its manifest is no model, nor are the
        // models' reference answers (`NAME.ref.toml`, docs/model-files.md).
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".toml") && name != "Cargo.toml" && !name.ends_with(".ref.toml")
        })
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no model files in {}", dir.display());
    paths
        .iter()
        .map(|p| {
            let model = eom_model::file::load(p, &[])
                .unwrap_or_else(|e| panic!("{e}"))
                .model;
            Case {
                name: p.to_str().expect("a UTF-8 path").to_string(),
                first: first_parameter(&model),
            }
        })
        .collect()
}

fn first_parameter(m: &eom_model::Model) -> (String, f64) {
    let name = m.scope.names().first().cloned().expect("a parameter");
    (name, m.scope.nominal_values()[0])
}

/// Runs `eom args`, requires success, returns standard output.
fn ok(args: &[&str]) -> String {
    let r = eom(args);
    assert_eq!(r.code, 0, "eom {}: {}", args.join(" "), r.stderr);
    r.stdout
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = ok(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("eom {args:?}: not JSON ({e})"))
}

/// Issue 26 item 2, one verdict: at two grid points of the sweep, `eom analyze` at the same
/// value judges the modes as the sweep judged its branches (the sweep leaves out the neutral
/// branches, identically zero; `eom analyze` calls such modes `zero`): a point is unstable
/// exactly when a mode is, stable only when every mode but the zero ones is, marginal only
/// when one of them is marginal (or every mode is zero); a marginal point states its
/// tolerance.
fn one_verdict(m: &str, p: &str, sweep: &serde_json::Value) {
    for k in [0, 2] {
        let pt = &sweep["points"][k];
        let x = pt["value"].as_f64().expect("a value");
        let set = format!("{p}={x:?}");
        let a = json(&["analyze", m, "--set", &set, "--format", "json"]);
        let modes = a["modes"].as_array().expect("modes");
        let judged = |kind_zero: bool, verdict: &str| {
            modes
                .iter()
                .any(|md| (md["kind"] == "zero") == kind_zero && md["stability"] == verdict)
        };
        let verdict = pt["stability"].as_str().expect("a verdict");
        let all_zero = modes.iter().all(|md| md["kind"] == "zero");
        let any_unstable = judged(false, "unstable") || judged(true, "unstable");
        let ok = match verdict {
            "unstable" => any_unstable,
            "stable" => !any_unstable && !judged(false, "marginal"),
            "marginal" => !any_unstable && (judged(false, "marginal") || all_zero),
            _ => false,
        };
        assert!(
            ok,
            "{m} at {set}: the sweep says {verdict}, eom analyze's modes {:?}",
            modes
                .iter()
                .map(|md| (
                    md["eigenvalue"].to_string(),
                    md["kind"].to_string(),
                    md["stability"].to_string()
                ))
                .collect::<Vec<_>>()
        );
        // A marginal point states the tolerance its real part is within.
        if verdict == "marginal" && pt["max_real"].is_number() {
            assert!(pt["tolerance"].is_number(), "{m} at {set}: {pt}");
        }
    }
}

/// One model through every command.
fn every_command(case: &Case, dir: &Path) {
    let m = case.name.as_str();
    let text = ok(&["analyze", m]);
    assert!(text.contains("eigenvalue"), "{m}: {text}");
    let a = json(&["analyze", m, "--format", "json"]);
    let n = a["states"].as_u64().expect("states") as usize;
    assert_eq!(
        a["eigenvalues"].as_array().expect("eigenvalues").len(),
        n,
        "{m}"
    );
    for mode in a["modes"].as_array().expect("modes") {
        let s = mode["stability"].as_str().expect("a verdict");
        assert!(["stable", "marginal", "unstable"].contains(&s), "{m}: {s}");
    }

    // The first parameter from 0.9 to 1.1 times its nominal value (signs kept, so declared
    // ranges hold), or from 0 to 0.1 when it is 0.
    let (p, v) = (&case.first.0, case.first.1);
    let (lo, hi) = if v == 0.0 {
        (0.0, 0.1)
    } else {
        (0.9 * v, 1.1 * v)
    };
    let grid = format!("{p}={lo}:{hi}:5");
    let s = json(&["sweep", m, "--param", &grid, "--format", "json", "--quiet"]);
    assert_eq!(s["points"].as_array().expect("points").len(), 5, "{m}");
    one_verdict(m, p, &s);

    let sym = ok(&["symbolic", m]);
    assert!(sym.contains("A ("), "{m}: {sym}");

    let stem = Path::new(m)
        .file_stem()
        .expect("a name")
        .to_string_lossy()
        .into_owned();
    let out = dir.join(&stem);
    std::fs::create_dir_all(&out).expect("a directory");
    let out_s = out.to_str().expect("UTF-8");
    ok(&["report", m, "-o", out_s, "--quiet"]);
    let html = std::fs::read_to_string(out.join(format!("{stem}.html"))).expect("the page");
    assert!(
        !html.contains("could not be made"),
        "{m}: a part of the report could not be made: {}",
        html.split("could not be made")
            .nth(1)
            .map_or("", |t| &t[..t.len().min(300)])
    );
    for id in ["parameters", "modes", "io", "closed"] {
        assert!(html.contains(&format!("<h2 id=\"{id}\">")), "{m}: no {id}");
    }

    let code = out.join(format!("{stem}.rs"));
    ok(&["codegen", m, "-o", code.to_str().expect("UTF-8")]);
    assert!(
        std::fs::read_to_string(&code)
            .expect("code")
            .contains("pub mod")
    );

    let check = ok(&["check", m]);
    assert!(check.contains("valid"), "{m}: {check}");

    let exported = out.join(format!("{stem}-exported.toml"));
    let toml = ok(&["export", m]);
    std::fs::write(&exported, toml).expect("write the export");
    let again = ok(&["check", exported.to_str().expect("UTF-8")]);
    assert!(again.contains("valid"), "{m}: {again}");
}

#[test]
fn every_built_in_model_and_model_file_goes_through_every_command() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("every-model");
    let _ = std::fs::remove_dir_all(&dir);
    let mut cases = catalogue();
    let builtins = cases.len();
    cases.extend(files());
    assert!(
        builtins >= 10 && cases.len() > builtins,
        "{} cases",
        cases.len()
    );
    // Two workers: the CI machine's cores.
    let next = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(case) = cases.get(k) else { break };
                    // Built-in and file of the same name write to different directories.
                    let sub = dir.join(if k < builtins { "builtin" } else { "file" });
                    every_command(case, &sub);
                }
            });
        }
    });
}
