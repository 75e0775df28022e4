//! The generated code of the towing and fairing models (`models/glider_tow.toml`,
//! `models/motorcycle_fairing.toml`; docs/towing-and-fairings.md): `eom codegen` writes the
//! module, rustc compiles it with a small driver, and its state matrix A at the nominal point and
//! at another point equals the one `eom analyze --format json` prints there.

mod common;
use common::eom_json;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The driver: evaluates the module at its nominal parameters changed by `name=value`
/// arguments and prints A column by column.
const DRIVER: &str = r#"include!("model.rs");
use MODULE as m;
fn main() {
    let mut p = m::NOMINAL;
    for arg in std::env::args().skip(1) {
        let (name, value) = arg.split_once('=').expect("name=value");
        let k = m::PARAM_NAMES.iter().position(|n| *n == name).expect("a parameter");
        p[k] = value.parse().expect("a number");
    }
    let mut s = m::StateSpace::new();
    s.evaluate(&m::Params::from_array(&p)).expect("evaluates");
    for x in s.a() {
        println!("{x:e}");
    }
}
"#;

/// Generates the module of `file` and compiles it with the driver; returns the executable.
fn compile(dir: &Path, file: &str, module: &str) -> PathBuf {
    let code = dir.join("model.rs");
    let r = common::eom(&["codegen", file, "-o", code.to_str().expect("UTF-8")]);
    assert_eq!(r.code, 0, "eom codegen {file}: {}", r.stderr);
    std::fs::write(dir.join("main.rs"), DRIVER.replace("MODULE", module)).expect("driver");
    let exe = dir.join("driver");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let out = Command::new(rustc)
        .args(["--edition", "2021", "-o"])
        .arg(&exe)
        .arg(dir.join("main.rs"))
        .output()
        .expect("rustc runs");
    assert!(
        out.status.success(),
        "{module}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

/// A, column-major, from the compiled driver at the nominal point changed by `set`.
fn generated_a(exe: &Path, set: &[&str]) -> Vec<f64> {
    let out = Command::new(exe)
        .args(set)
        .output()
        .expect("the driver runs");
    assert!(out.status.success(), "{}: the driver failed", exe.display());
    String::from_utf8(out.stdout)
        .expect("UTF-8")
        .lines()
        .map(|l| l.parse().expect("a number"))
        .collect()
}

#[test]
fn generated_code_gives_the_analysed_state_matrix() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let cases: [(&str, &str, &[&str]); 2] = [
        ("glider_tow", "glider_tow", &["EA=5000", "ht=2"]),
        (
            "motorcycle_fairing",
            "motorcycle_fairing",
            &["v=12", "Sf=0.2"],
        ),
    ];
    for (stem, module, other) in cases {
        let file = repo.join(format!("models/{stem}.toml"));
        let file = file.to_str().expect("UTF-8");
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("generated-{stem}"));
        std::fs::create_dir_all(&dir).expect("a directory");
        let exe = compile(&dir, file, module);
        for set in [&[][..], other] {
            let got = generated_a(&exe, set);
            let mut args = vec!["analyze", file, "--format", "json"];
            for s in set {
                args.extend(["--set", s]);
            }
            let j = eom_json(&args);
            let rows = j["matrices"]["A"].as_array().expect("A");
            let n = rows.len();
            assert_eq!(got.len(), n * n, "{stem}");
            let scale = rows
                .iter()
                .flat_map(|r| r.as_array().expect("a row"))
                .fold(0.0f64, |m, x| m.max(x.as_f64().expect("a number").abs()));
            for (i, row) in rows.iter().enumerate() {
                for (k, x) in row.as_array().expect("a row").iter().enumerate() {
                    let want = x.as_f64().expect("a number");
                    let g = got[i + k * n];
                    assert!(
                        (g - want).abs() <= 1e-12 * scale,
                        "{stem} {set:?}: A({i},{k}) generated {g}, analysed {want}"
                    );
                }
            }
        }
    }
}
