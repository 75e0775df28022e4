//! `eom sweep` against independent references: the Routh–Hurwitz boundaries of the shimmy
//! cubic, the fallback to the robust path, and the CSV and text outputs (the bicycle's weave
//! and capsize speeds are reference answers of `models/bicycle.ref.toml`, checked by
//! tests/references.rs).

mod common;
use common::{assert_close, complex, eigenvalues, eom, eom_json};

fn boundaries(j: &serde_json::Value) -> Vec<f64> {
    j["boundaries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["value"].as_f64().unwrap())
        .collect()
}

fn intervals(j: &serde_json::Value) -> Vec<[f64; 2]> {
    j["stable_intervals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| [i[0].as_f64().unwrap(), i[1].as_f64().unwrap()])
        .collect()
}

/// The cubic `(I + m x² l²) s³ + m x l u s² + k l² s + k l u` (all coefficients positive) is
/// Hurwitz iff `a2 a1 > a3 a0`, i.e. `m x l² > I + m x² l²`: between the roots of
/// `x² − x + I/(m l²) = 0`, for every speed u > 0.
#[test]
fn shimmy_is_stable_between_the_hurwitz_roots() {
    let (m, i, l): (f64, f64, f64) = (5.0, 1.05, 1.0);
    let d = (1.0 - 4.0 * i / (m * l * l)).sqrt();
    let (lo, hi) = ((1.0 - d) / 2.0, (1.0 + d) / 2.0);
    assert!((lo - 0.3).abs() < 1e-15 && (hi - 0.7).abs() < 1e-15);
    let j = eom_json(&[
        "sweep",
        "shimmy",
        "--param",
        "x=0:1:101",
        "--format",
        "json",
    ]);
    assert_eq!(j["param"], "x");
    let points = j["points"].as_array().unwrap();
    assert_eq!(points.len(), 101);
    for p in points {
        assert!(p["value"].is_number());
        assert_eq!(p["eigenvalues"].as_array().unwrap().len(), 3);
    }
    let b = boundaries(&j);
    assert_eq!(b.len(), 2, "{b:?}");
    assert!(
        (b[0] - lo).abs() < 1e-9 && (b[1] - hi).abs() < 1e-9,
        "{b:?}"
    );
    let iv = intervals(&j);
    assert_eq!(iv.len(), 1, "{iv:?}");
    assert!(
        (iv[0][0] - lo).abs() < 1e-9 && (iv[0][1] - hi).abs() < 1e-9,
        "{iv:?}"
    );
    // At a boundary the crossing eigenvalue is on the imaginary axis.
    for b in j["boundaries"].as_array().unwrap() {
        let (re, im) = complex(&b["eigenvalue"]);
        assert!(re.abs() < 1e-9 && im.abs() > 0.5, "{re} {im}");
    }
    assert_eq!(j["evaluation"]["method"], "symbolic");
    assert_eq!(j["evaluation"]["fallback"]["count"], 0);
}

/// A grid value where the symbolic pivots (chosen at the default trail c = 0.08) break down
/// — c = −w makes the pivot w + c in the front tyre's constraint vanish — is evaluated by the
/// robust path and reported; its eigenvalues agree with the numeric elimination with pivots
/// chosen there.
#[test]
fn points_outside_the_symbolic_region_fall_back_to_the_robust_path() {
    let j = eom_json(&[
        "sweep",
        "bicycle",
        "--param",
        "c=-1.22:0.18:8",
        "--format",
        "json",
    ]);
    let fb = &j["evaluation"]["fallback"];
    assert_eq!(fb["count"], 1, "{fb}");
    let c = fb["values"][0].as_f64().unwrap();
    assert!((c + 1.02).abs() < 1e-12, "{c}");
    assert!(
        fb["reasons"][0].as_str().unwrap().contains("front tyre"),
        "{fb}"
    );
    let point = j["points"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["value"].as_f64() == Some(c))
        .unwrap();
    let nonzero = |v: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
        let mut v: Vec<_> = v.into_iter().filter(|z| z.0.hypot(z.1) > 1e-3).collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        v
    };
    let got = nonzero(eigenvalues(point));
    let set = format!("c={c:?}");
    let reference = eom_json(&["analyze", "bicycle", "--set", &set, "--format", "json"]);
    assert_close(&got, &nonzero(eigenvalues(&reference)), 1e-9);
    // The text and CSV outputs say so too.
    let r = eom(&["sweep", "bicycle", "--param", "c=-1.22:0.18:8"]);
    assert!(
        r.stdout
            .contains("robust fallback at 1 of 8 grid values (c = -1.02"),
        "{}",
        r.stdout
    );
    let r = eom(&[
        "sweep",
        "bicycle",
        "--param",
        "c=-1.22:0.18:8",
        "--format",
        "csv",
    ]);
    assert!(
        r.stderr.contains("robust fallback at 1 of 8"),
        "{}",
        r.stderr
    );
}

#[test]
fn csv_has_one_row_per_value_and_two_columns_per_eigenvalue() {
    let r = eom(&[
        "sweep",
        "bicycle",
        "--param",
        "v=0:10:101",
        "--format",
        "csv",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 102);
    assert_eq!(
        lines[0],
        "value,re1,im1,re2,im2,re3,im3,re4,im4,re5,im5,re6,im6"
    );
    let rows: Vec<Vec<f64>> = lines[1..]
        .iter()
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    assert!(rows.iter().all(|r| r.len() == 13));
    assert_eq!(rows[0][0], 0.0);
    assert_eq!(rows[100][0], 10.0);
    // v = 5: the published eigenvalues (Table 2(b) of Meijaard et al. 2007,
    // tests/data/bicycle_table2.csv) among the six.
    let row = &rows[50];
    assert_eq!(row[0], 5.0);
    let table = include_str!("../../tests/data/bicycle_table2.csv");
    let p: Vec<f64> = table
        .lines()
        .find(|l| l.starts_with("5.0,"))
        .expect("the row of v = 5")
        .split(',')
        .map(|x| x.parse().expect("a number"))
        .collect();
    let mut eig: Vec<(f64, f64)> = (0..6)
        .map(|k| (row[1 + 2 * k], row[2 + 2 * k]))
        .filter(|z| z.0.hypot(z.1) > 1e-3)
        .collect();
    eig.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let published = [(p[4], 0.0), (p[1], -p[2]), (p[1], p[2]), (p[3], 0.0)];
    assert_close(&eig, &published, 1e-10);
}

#[test]
fn text_report_has_the_table_boundaries_and_intervals() {
    let r = eom(&["sweep", "shimmy", "--param", "x=0:1:11"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for h in [
        "Sweep of x from 0 to 1 (11 values), model shimmy",
        "symbolic model compiled once (pivots chosen at x = 0.5)",
        "stability",
        "max Re λ",
        "eigenvalues [1/s]",
        "Stability boundaries (located to 1e-10 in x)",
        "stabilizing",
        "destabilizing",
        "Stable intervals of x",
    ] {
        assert!(r.stdout.contains(h), "`{h}` missing from:\n{}", r.stdout);
    }
}
