//! Running the built `eom` binary and reading its output.

#![allow(dead_code)]

use std::process::Command;

/// Exit code, standard output and standard error of one run.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `eom` with the arguments.
pub fn eom(args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(args)
        .output()
        .expect("the eom binary runs");
    Run {
        code: out.status.code().expect("exited normally, not by a signal"),
        stdout: String::from_utf8(out.stdout).expect("UTF-8 output"),
        stderr: String::from_utf8(out.stderr).expect("UTF-8 errors"),
    }
}

/// Runs `eom`, requires success, parses standard output as JSON.
pub fn eom_json(args: &[&str]) -> serde_json::Value {
    let r = eom(args);
    assert_eq!(r.code, 0, "eom {args:?} failed: {}", r.stderr);
    serde_json::from_str(&r.stdout)
        .unwrap_or_else(|e| panic!("eom {args:?}: not JSON ({e}):\n{}", r.stdout))
}

/// A `{"re", "im"}` object as a pair.
pub fn complex(v: &serde_json::Value) -> (f64, f64) {
    (
        v["re"].as_f64().expect("re is a number"),
        v["im"].as_f64().expect("im is a number"),
    )
}

/// The `eigenvalues` array of a JSON object.
pub fn eigenvalues(v: &serde_json::Value) -> Vec<(f64, f64)> {
    v["eigenvalues"]
        .as_array()
        .expect("eigenvalues is an array")
        .iter()
        .map(complex)
        .collect()
}

/// Asserts that `got` and `want` hold the same numbers (in order) to `tol` each.
pub fn assert_close(got: &[(f64, f64)], want: &[(f64, f64)], tol: f64) {
    assert_eq!(got.len(), want.len(), "got {got:?}, want {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.0 - w.0).abs() <= tol && (g.1 - w.1).abs() <= tol,
            "got {g:?}, want {w:?} (tolerance {tol}); all: {got:?}"
        );
    }
}
