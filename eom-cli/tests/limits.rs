//! Large models and bounded inputs: a long chain's eigenvalues against the closed form, and
//! every size argument refused with a usage error (exit 2) that states its limit.

mod common;

use common::{complex, eom, eom_json};

/// `eom analyze chainN` at m = 1.3, k = 2, c = 0.07 against the closed form: the chain is
/// fixed–free with M = m I, K = k T, C = c T, T = tridiag(−1, 2, −1) except T_NN = 1, whose
/// eigenvalues are μ_j = 4 sin²((2j − 1)π / (2(2N + 1))); each mode solves
/// m s² + c μ s + k μ = 0.
#[test]
fn a_long_chain_matches_its_closed_form() {
    let n = 300;
    let (m, k, c) = (1.3, 2.0, 0.07);
    let j = eom_json(&[
        "analyze",
        &format!("chain{n}"),
        "--set",
        "m=1.3",
        "--set",
        "k=2",
        "--set",
        "c=0.07",
        "--format",
        "json",
    ]);
    let got: Vec<(f64, f64)> = j["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(complex)
        .collect();
    assert_eq!(got.len(), 2 * n);
    let mut want = Vec::new();
    for i in 1..=n {
        let mu = 4.0
            * ((2 * i - 1) as f64 * std::f64::consts::PI / (2.0 * (2 * n + 1) as f64))
                .sin()
                .powi(2);
        let b = c * mu / m;
        let disc = k * mu / m - b * b / 4.0;
        assert!(disc > 0.0, "every mode underdamped at these values");
        want.push((-b / 2.0, disc.sqrt()));
        want.push((-b / 2.0, -disc.sqrt()));
    }
    // Each expected eigenvalue against the nearest printed one, relative to its modulus.
    let mut worst = 0.0f64;
    for &(wr, wi) in &want {
        let err = got
            .iter()
            .map(|&(r, i)| (r - wr).hypot(i - wi))
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(err / wr.hypot(wi));
    }
    assert!(worst < 1e-10, "worst relative error {worst:e}");
}

fn refused(args: &[&str], needles: &[&str]) {
    let r = eom(args);
    assert_eq!(r.code, 2, "eom {args:?}: {}", r.stderr);
    for n in needles {
        assert!(
            r.stderr.contains(n),
            "eom {args:?}: `{n}` not in {}",
            r.stderr
        );
    }
    assert!(r.stderr.len() < 2000, "a short message: {}", r.stderr);
}

#[test]
fn sweep_counts_and_bounds_are_bounded() {
    refused(
        &["sweep", "smd", "--param", "k=1:2:1000001"],
        &["COUNT = 1000001", "limit of 1000000"],
    );
    refused(
        &[
            "sweep",
            "smd",
            "--param",
            "k=1:2:123456789012345678901234567890",
        ],
        &["too large", "1000000"],
    );
    refused(
        &["sweep", "smd", "--param", "k=-1e308:1e308:11"],
        &["-1e308", "overflow"],
    );
}

#[test]
fn frequency_points_are_bounded() {
    refused(
        &["analyze", "smd", "--points", "10000001"],
        &["--points 10000001", "limit of 10000000"],
    );
}

#[test]
fn chain_sizes_are_bounded() {
    refused(&["analyze", "chain1000001"], &["at most", "model file"]);
    refused(&["analyze", "chain99999999999999999999999"], &["at most"]);
}

#[test]
fn values_that_underflow_or_overflow_say_so() {
    refused(
        &["analyze", "smd", "--set", "k=1e-400"],
        &["k=1e-400", "underflows to 0"],
    );
    refused(&["analyze", "smd", "--set", "k=1e400"], &["overflows"]);
    // In short form, not 309 digits.
    let r = eom(&["analyze", "smd", "--set", "k=-1e308"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("-1e308"), "{}", r.stderr);
    assert!(!r.stderr.contains("0000000000"), "{}", r.stderr);
}

#[test]
fn a_very_long_literal_is_refused_quickly() {
    // On the command line (an argument is at most 128 KiB on Linux).
    let long = format!("k={}", "9".repeat(100_000));
    refused(
        &["analyze", "smd", "--set", &long],
        &["100002 characters", "overflows"],
    );
    // In a model file, as an exact literal: four million digits.
    let dir = std::env::temp_dir().join(format!("eom-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let file = dir.join("wide.toml");
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../models/smd.toml"))
        .expect("smd.toml")
        .replace(
            "mass = \"m\"",
            &format!("mass = \"m + {}\"", "7".repeat(4_000_000)),
        );
    std::fs::write(&file, text).expect("model file");
    let t = std::time::Instant::now();
    refused(
        &["analyze", &file.display().to_string()],
        &["4000000 characters", "too wide"],
    );
    assert!(t.elapsed().as_secs_f64() < 20.0, "{:?}", t.elapsed());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn memory_beyond_the_limit_is_refused_before_allocating() {
    let r = std::process::Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(["analyze", "chain300"])
        .env("EOM_MEMORY_LIMIT", "1M")
        .output()
        .expect("eom runs");
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("too large") && stderr.contains("EOM_MEMORY_LIMIT"),
        "{stderr}"
    );
    let r = std::process::Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(["analyze", "smd"])
        .env("EOM_MEMORY_LIMIT", "lots")
        .output()
        .expect("eom runs");
    assert_eq!(r.status.code(), Some(2));
}

#[test]
fn entries_beyond_the_range_of_the_factorisations_are_named() {
    let r = eom(&["analyze", "smd", "--set", "k=1e200"]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(
        r.stderr.contains("entry too large") && r.stderr.contains("1e200"),
        "{}",
        r.stderr
    );
}
