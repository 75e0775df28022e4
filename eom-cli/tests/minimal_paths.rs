//! What `eom analyze` shows of the minimal realization: the same order on every reduction
//! path (issue 26, item 3; the orders are argued in closed form in
//! `tests/tests/minreal_paths.rs`), identical bodies reduced to the driven ones, and a model
//! without inputs or outputs told that it has no minimal realization to show instead of
//! listing every mode as removed (issue 27, item 7).

mod common;

use common::{eom, eom_json};

fn data(file: &str) -> String {
    format!("{}/../tests/data/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// A scratch file holding `text`, removed when dropped.
struct Scratch(std::path::PathBuf);

impl Scratch {
    fn new(name: &str, text: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("eom-minimal-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        Scratch(path)
    }

    fn path(&self) -> &str {
        self.0.to_str().unwrap()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

#[test]
fn every_path_gives_the_same_minimal_order() {
    for (file, states, order) in [
        ("string_chain15.toml", 120, 30),
        ("rotor_stator.toml", 14, 10),
    ] {
        for method in ["numeric", "symbolic", "robust"] {
            let what = format!("{file} by {method}");
            let j = eom_json(&[
                "analyze",
                &data(file),
                "--method",
                method,
                "--format",
                "json",
            ]);
            assert_eq!(j["states"], states, "{what}");
            assert_eq!(j["minimal"]["states"], order, "{what}");
            let removed = j["minimal"]["removed"].as_array().unwrap();
            assert_eq!(removed.len(), states - order, "{what}");
            for r in removed {
                assert_eq!(r["reason"], "uncontrollable", "{what}: {r}");
            }
            // Clear decisions: no warning about a rank decision near its tolerance.
            let warnings = j["warnings"].as_array().unwrap();
            assert!(
                warnings
                    .iter()
                    .all(|w| w["kind"] != "fragile_minimal_realization"),
                "{what}: {warnings:?}"
            );
        }
    }
}

#[test]
fn identical_bodies_keep_the_driven_ones() {
    // 2 · driven states of 2n: the derivation is in `models::generate::identical_bodies`.
    for (n, driven) in [(40, 1), (40, 3)] {
        let file = Scratch::new(
            &format!("identical{n}_{driven}.toml"),
            &models::generate::identical_bodies(n, driven, false),
        );
        let j = eom_json(&["analyze", file.path(), "--format", "json"]);
        assert_eq!(j["states"], 2 * n);
        assert_eq!(
            j["minimal"]["states"],
            2 * driven,
            "{n} bodies, {driven} driven"
        );
        assert_eq!(
            j["minimal"]["removed"].as_array().unwrap().len(),
            2 * (n - driven)
        );
    }
}

#[test]
fn a_model_without_inputs_or_outputs_says_why_it_has_no_minimal_realization() {
    let file = Scratch::new(
        "idle.toml",
        &models::generate::identical_bodies(30, 0, false),
    );
    let j = eom_json(&["analyze", file.path(), "--format", "json"]);
    assert_eq!(j["states"], 60);
    assert!(j["minimal"].is_null());
    let note = j["minimal_note"].as_str().unwrap();
    assert!(
        note.contains("no inputs and no outputs") && note.contains("60 states"),
        "{note}"
    );
    assert!(j["warnings"].as_array().unwrap().is_empty(), "{j}");
    let text = eom(&["analyze", file.path()]);
    assert_eq!(text.code, 0, "{}", text.stderr);
    assert!(
        text.stdout
            .contains("Minimal realization: not computed: the model has no inputs and no outputs"),
        "{}",
        text.stdout
    );
    // With the eigenvalues all there.
    assert_eq!(j["eigenvalues"].as_array().unwrap().len(), 60);
}
