//! Model files on the command line: the same JSON as the built-in of the same model, `check`,
//! `new`, `export`, and bad files rejected with exit code 2 naming line and item.

mod common;
use common::{eom, eom_json};

fn models_dir() -> String {
    format!("{}/../models", env!("CARGO_MANIFEST_DIR"))
}

/// The JSON without the model's name (a path for the file, a name for the built-in).
fn without_name(mut v: serde_json::Value) -> serde_json::Value {
    v.as_object_mut().expect("an object").remove("model");
    v
}

#[test]
fn analyze_and_sweep_of_a_file_equal_the_builtin() {
    // Every built-in model read from the catalogue (a family has no file of its own).
    for name in models::names()
        .into_iter()
        .filter(|n| models::file_text(n).is_some())
    {
        let file = format!("{}/{name}.toml", models_dir());
        let a = eom_json(&["analyze", &file, "--format", "json"]);
        let b = eom_json(&["analyze", name, "--format", "json"]);
        assert_eq!(without_name(a), without_name(b), "{name}");
    }
    let file = format!("{}/shimmy.toml", models_dir());
    let a = eom_json(&[
        "sweep", &file, "--param", "x=0:1:21", "--set", "u=1", "--format", "json",
    ]);
    let mut b = eom_json(&[
        "sweep", "shimmy", "--param", "x=0:1:21", "--set", "u=1", "--format", "json",
    ]);
    // The built-in also has the generated stability verdict (the file has no generated code).
    let verdict = b.as_object_mut().expect("an object").remove("verdict");
    assert!(verdict.is_some(), "{b}");
    assert_eq!(without_name(a), without_name(b));
}

#[test]
fn new_check_export_round_trip() {
    let dir = std::env::temp_dir().join(format!("eom-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let starter = eom(&["new", "demo"]);
    assert_eq!(starter.code, 0);
    let path = dir.join("demo.toml");
    std::fs::write(&path, &starter.stdout).expect("write");
    let p = path.to_str().expect("utf-8");
    let check = eom(&["check", p]);
    assert_eq!(check.code, 0, "{}", check.stderr);
    assert!(
        check.stdout.contains("valid") && check.stdout.contains("2 states"),
        "{}",
        check.stdout
    );
    // m z'' + c z' + k z = f with the starter's m = 1, c = 0.1, k = 10.
    let j = eom_json(&["analyze", p, "--format", "json"]);
    let e = &j["eigenvalues"][0];
    assert!((e["re"].as_f64().expect("re") + 0.05).abs() < 1e-12, "{e}");
    let exported = dir.join("bicycle.toml");
    let x = eom(&["export", "bicycle", "-o", exported.to_str().expect("utf-8")]);
    assert_eq!(x.code, 0, "{}", x.stderr);
    let a = eom_json(&[
        "analyze",
        exported.to_str().expect("utf-8"),
        "--set",
        "v=5",
        "--format",
        "json",
    ]);
    let b = eom_json(&["analyze", "bicycle", "--set", "v=5", "--format", "json"]);
    assert_eq!(without_name(a), without_name(b));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_files_exit_2_and_name_the_line_and_item() {
    let dir = std::env::temp_dir().join(format!("eom-badfiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let good = std::fs::read_to_string(format!("{}/shimmy.toml", models_dir())).expect("shimmy");
    let bad = good.replacen(
        "axis = [0, 1, 0]\nstiffness",
        "axis = [0, 1, 0]\nstiffnes",
        1,
    );
    let path = dir.join("bad.toml");
    std::fs::write(&path, bad).expect("write");
    let r = eom(&["analyze", path.to_str().expect("utf-8")]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("bad.toml:") && r.stderr.contains("flex_point `spring`"),
        "{}",
        r.stderr
    );
    assert!(
        r.stderr.contains("did you mean `stiffness`"),
        "{}",
        r.stderr
    );
    let r = eom(&[
        "analyze",
        path.to_str()
            .expect("utf-8")
            .replace("bad", "missing")
            .as_str(),
    ]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("cannot be read"), "{}", r.stderr);
    let r = eom(&[
        "analyze",
        &format!("{}/shimmy.toml", models_dir()),
        "--set",
        "m=-1",
    ]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("outside its range"), "{}", r.stderr);
    std::fs::remove_dir_all(&dir).ok();
}

/// One "did you mean" for every unknown name: a model, a parameter of a built-in model, a
/// parameter in an expression, a key of a model file.
#[test]
fn unknown_names_get_the_likely_one() {
    let r = eom(&["analyze", "bicyle"]);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr.contains("(did you mean `bicycle`?)"),
        "{}",
        r.stderr
    );
    let r = eom(&["analyze", "bicycle", "--set", "vv=5"]);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr.contains("no parameter `vv` (did you mean `v`?)"),
        "{}",
        r.stderr
    );
    // Nothing close: no suggestion.
    let r = eom(&["analyze", "bicycle", "--set", "zzzzzz=5"]);
    assert_eq!(r.code, 2);
    assert!(!r.stderr.contains("did you mean"), "{}", r.stderr);
}
