//! `eom bench accuracy`: on the spring-mass-damper and the bicycle, the printed table and the
//! written CSV hold every method's eigenvalue error within the bounds of the benchmark's smoke
//! test (`tests/tests/work_precision.rs`), the bicycle's generated code within 1e-12 of the
//! published eigenvalues; the rounding error of the entries of A and B is printed and
//! written; the files are written; bad arguments exit 2 naming them.

mod common;
use common::eom;

/// The CSV's rows as maps from column name to field.
fn rows(csv: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().expect("a header").split(',').collect();
    lines
        .map(|l| {
            head.iter()
                .zip(l.split(','))
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn value(row: &std::collections::HashMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|e| panic!("{key} = `{}`: {e} in {row:?}", row[key]))
}

#[test]
fn errors_are_within_the_smoke_test_bounds_and_files_are_written() {
    let dir = std::env::temp_dir().join(format!("eom-bench-accuracy-{}", std::process::id()));
    let r = eom(&[
        "bench",
        "accuracy",
        "smd",
        "bicycle",
        "--points",
        "4",
        "--min-time",
        "5",
        "-o",
        dir.to_str().expect("UTF-8 path"),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for f in [
        "work_precision.csv",
        "work_precision.md",
        "work_precision.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f} not written: {}", r.stderr);
        assert!(r.stderr.contains(f), "no note of {f}: {}", r.stderr);
    }
    let md = std::fs::read_to_string(dir.join("work_precision.md")).expect("md");
    assert_eq!(md, r.stdout, "the printed table is the written one");
    let csv = std::fs::read_to_string(dir.join("work_precision.csv")).expect("csv");
    let rows = rows(&csv);
    let mut seen = 0;
    for row in &rows {
        let (model, method) = (row["model"].as_str(), row["method"].as_str());
        if method.starts_with("reference") {
            assert!(value(row, "published_err") < 1e-14, "{row:?}");
            continue;
        }
        seen += 1;
        assert_eq!(row["points"], "4", "{row:?}");
        assert_eq!(row["failures"], "0", "{row:?}");
        assert!(value(row, "time_ns") > 0.0, "{row:?}");
        let tol = if method.contains("f32") { 1e-4 } else { 1e-10 };
        assert!(value(row, "eig_err") <= tol, "{model} {method}: {row:?}");
        // The printed table has its row.
        let printed = format!("| {model} | {method} |");
        assert!(r.stdout.contains(&printed), "{printed} not printed");
        if model == "bicycle" {
            let tol = if method.contains("f32") { 1e-3 } else { 1e-12 };
            assert!(value(row, "published_err") <= tol, "{method}: {row:?}");
        }
    }
    // smd: numeric, robust, tape, f64, f32; bicycle: the same and the egg variant; both: the
    // two eigensolvers on the reference's A.
    assert_eq!(seen, 15, "{csv}");
    for solver in ["eigenvalues: small kernel", "eigenvalues: faer"] {
        let n = rows.iter().filter(|r| r["method"] == solver).count();
        assert_eq!(n, 2, "{solver}: {csv}");
    }
    let f64_rows = rows
        .iter()
        .filter(|r| r["method"] == "generated f64")
        .count();
    assert_eq!(f64_rows, 2, "{csv}");
    entry_errors_are_printed_and_written(&dir, &r.stdout);
    std::fs::remove_dir_all(&dir).ok();
}

/// The rounding error of the entries of A and B (1024 points by default): every row printed
/// and written, the bicycle's generated code within PyDy's row-scaled error under the same
/// protocol (2.348e-14, `bench/pydy/accuracy.py`; `tests/tests/generated_accuracy.rs`).
fn entry_errors_are_printed_and_written(dir: &std::path::Path, stdout: &str) {
    let csv = std::fs::read_to_string(dir.join("generated_entries.csv")).expect("entries csv");
    let rows = rows(&csv);
    // smd: tape, f64, f32; bicycle: the same and the egg variant.
    assert_eq!(rows.len(), 7, "{csv}");
    for row in &rows {
        let (model, method) = (row["model"].as_str(), row["method"].as_str());
        assert_eq!(row["points"], "1024", "{row:?}");
        let printed = format!("| {model} | {method} |");
        assert!(stdout.contains(&printed), "{printed} not printed");
        let tol = if method.contains("f32") { 1e-4 } else { 1e-12 };
        assert!(value(row, "row_scaled") <= tol, "{row:?}");
        if model == "bicycle" && method == "generated f64" {
            assert!(value(row, "row_scaled") <= 2.348e-14, "{row:?}");
        }
    }
}

#[test]
fn bad_arguments_exit_2_naming_them() {
    for (args, needle) in [
        (
            &["bench", "accuracy", "nosuch", "--points", "4"][..],
            "nosuch",
        ),
        (&["bench", "accuracy", "smd", "--points", "0"], "--points 0"),
        (
            &["bench", "accuracy", "smd", "--entry-points", "0"],
            "--entry-points 0",
        ),
    ] {
        let r = eom(args);
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert!(r.stderr.contains(needle), "{args:?}: {}", r.stderr);
    }
}
