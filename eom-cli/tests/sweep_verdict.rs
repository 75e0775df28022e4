//! `eom sweep` with the generated stability verdict (built-in models with `--stability` code):
//! the shimmy's stable interval is 0.3 < x < 0.7 in closed form (`eom symbolic shimmy
//! --stability --solve-for x`: x = 1/2 ± √(1/4 − I/(m l²))), so on the grid x = 0:1:101 the
//! verdict is undecided exactly at the two boundaries, stable strictly between and unstable
//! outside, as the eigenvalues say; the bicycle's agrees with the eigenvalues on v = 0…10; a
//! model file has no generated verdict.

mod common;
use common::eom;

fn verdict(args: &[&str]) -> serde_json::Value {
    let r = eom(args);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
    v["verdict"].clone()
}

#[test]
fn shimmy_boundaries_are_undecided_and_the_rest_agrees() {
    let v = verdict(&[
        "sweep",
        "shimmy",
        "--param",
        "x=0:1:101",
        "--format",
        "json",
    ]);
    let undecided: Vec<f64> = v["undecided"]
        .as_array()
        .expect("undecided values")
        .iter()
        .map(|x| x.as_f64().expect("a value"))
        .collect();
    assert_eq!(undecided.len(), 2, "{v}");
    for (got, want) in undecided.iter().zip([0.3, 0.7]) {
        assert!((got - want).abs() < 1e-12, "{v}");
    }
    // Strictly inside: 0.31 … 0.69, 39 values.
    assert_eq!(v["stable"], 39, "{v}");
    assert_eq!(v["unstable"], 60, "{v}");
    assert!(
        v["disagreements"].as_array().expect("a list").is_empty(),
        "{v}"
    );
    assert!(v["failed"].as_array().expect("a list").is_empty(), "{v}");
}

#[test]
fn bicycle_agrees_with_its_eigenvalues() {
    let v = verdict(&[
        "sweep",
        "bicycle",
        "--param",
        "v=0:10:101",
        "--format",
        "json",
    ]);
    // Stable between the weave (4.29 m/s) and capsize (6.02 m/s) speeds: v = 4.3 … 6.0.
    assert_eq!(v["stable"], 18, "{v}");
    assert!(
        v["disagreements"].as_array().expect("a list").is_empty(),
        "{v}"
    );
    let r = eom(&["sweep", "bicycle", "--param", "v=0:10:11"]);
    assert!(
        r.stdout
            .contains("it agrees with the eigenvalues wherever it decides"),
        "{}",
        r.stdout
    );
}

#[test]
fn a_model_file_has_no_generated_verdict() {
    let dir = std::env::temp_dir().join(format!("eom-sweep-verdict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("smd.toml");
    let r = eom(&["export", "smd"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    std::fs::write(&file, r.stdout).expect("write");
    let path = file.to_str().expect("UTF-8 path");
    let r = eom(&["sweep", path, "--param", "k=1:10:5", "--format", "json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
    assert!(v.get("verdict").is_none(), "{v}");
    let _ = std::fs::remove_dir_all(&dir);
}
