//! `eom list`, `eom codegen` and the help texts.

mod common;
use common::{eom, eom_json};

#[test]
fn list_shows_every_model_and_parameter() {
    let r = eom(&["list"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for m in models::catalogue() {
        assert!(r.stdout.contains(m.name), "{} missing", m.name);
        for p in &m.params {
            assert!(
                r.stdout.contains(&p.description),
                "{}.{} missing",
                m.name,
                p.name
            );
        }
    }
    assert!(r.stdout.contains("chainN (N ≥ 1, e.g. chain10, chain50)"));
    assert!(
        r.stdout
            .contains("chainpN (N ≥ 1, e.g. chainp10, chainp50)")
    );
    for h in ["parameter", "default", "unit", "allowed", "description"] {
        assert!(r.stdout.contains(h));
    }
    let j = eom_json(&["list", "--format", "json"]);
    let shimmy = j
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "shimmy")
        .unwrap();
    assert_eq!(shimmy["pattern"], false);
    let u = shimmy["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "u")
        .unwrap();
    assert_eq!(u["default"].as_f64(), Some(10.0));
    assert_eq!(u["unit"], "m/s");
    let chain = j
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "chainN")
        .unwrap();
    assert_eq!(chain["pattern"], true);
}

#[test]
fn help_describes_the_subcommands() {
    let r = eom(&["--help"]);
    assert_eq!(r.code, 0);
    for s in ["list", "analyze", "sweep", "codegen", "Exit codes"] {
        assert!(r.stdout.contains(s), "{s}: {}", r.stdout);
    }
    let r = eom(&["analyze", "--help"]);
    for s in [
        "--set <NAME=VALUE>",
        "--method",
        "--freq-range <LOW:HIGH>",
        "--points <N>",
        "minimal realization",
    ] {
        assert!(r.stdout.contains(s), "{s}: {}", r.stdout);
    }
    let r = eom(&["sweep", "--help"]);
    assert!(
        r.stdout.contains("--param <NAME=START:STOP:COUNT>"),
        "{}",
        r.stdout
    );
}

#[cfg(feature = "codegen")]
#[test]
fn codegen_writes_a_module() {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("eom_cli_smd.rs");
    let _ = std::fs::remove_file(&path);
    let file = path.to_str().unwrap();
    let r = eom(&["codegen", "smd", "-o", file, "--f32", "--no-std"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    // The summary is a status line: standard error (the output may be `/dev/stdout`).
    assert!(r.stdout.is_empty(), "{}", r.stdout);
    assert!(
        r.stderr.contains("module `smd`") && r.stderr.contains("f32"),
        "{}",
        r.stderr
    );
    let src = std::fs::read_to_string(&path).unwrap();
    assert!(src.contains("pub mod smd"), "{src}");
    assert!(src.contains("f32"));
    // The discrete matrices and the sample-time error only with --discrete (the module
    // without them compiles in tests/tests/codegen, whose match on `Error` and `Matrix` is
    // exhaustive without them).
    let variants = ["SampleTime", "Ad,", "Bd,", "eval_discrete"];
    assert!(variants.iter().all(|v| !src.contains(v)), "{src}");
    let r = eom(&["codegen", "smd", "-o", file, "--discrete"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let src = std::fs::read_to_string(&path).unwrap();
    assert!(variants.iter().all(|v| src.contains(v)), "{src}");
}

#[cfg(not(feature = "codegen"))]
#[test]
fn codegen_says_it_is_not_available() {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("eom_cli_none.rs");
    let r = eom(&["codegen", "smd", "-o", path.to_str().unwrap()]);
    assert_eq!(r.code, 1);
    assert!(
        r.stderr.contains("code generation is not available"),
        "{}",
        r.stderr
    );
    assert!(!path.exists());
}
