//! One stability verdict: `eom analyze`, `eom sweep` (its points and stable intervals) and
//! `eom report` judge an eigenvalue by the same rule — marginal only when |Re λ| is within the
//! eigenvalue's error estimate, which they print — on the half car of `models/half_car.toml`
//! with its front damper at 0, whose largest real part is of the order of (I − m a b)². The
//! reference eigenvalues are computed independently (the hand-derived equations in 40-digit
//! arithmetic: `tests/data/half_car_mpmath.py`, its output `half_car_mpmath.json`).

mod common;
use common::{eom, eom_json};
use serde_json::Value;

fn half_car() -> String {
    format!("{}/../models/half_car.toml", env!("CARGO_MANIFEST_DIR"))
}

fn reference() -> Value {
    let text = include_str!("data/half_car_mpmath.json");
    serde_json::from_str(text).expect("the reference is JSON")
}

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) => s.parse().expect("a number"),
        v => v.as_f64().expect("a number"),
    }
}

/// The verdict the rule gives for a real part and its tolerance.
fn rule(re: f64, tol: f64) -> &'static str {
    if re.abs() <= tol {
        "marginal"
    } else if re < 0.0 {
        "stable"
    } else {
        "unstable"
    }
}

#[test]
fn analyze_sweep_and_report_give_one_verdict_by_the_printed_tolerance() {
    let model = half_car();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("verdict");
    std::fs::create_dir_all(&dir).expect("a directory");
    for case in reference()["cases"].as_array().expect("cases") {
        let i = case["I"].as_str().expect("I");
        let exact = num(&case["max_real"]);
        let sets = ["--set", "cf=0", "--set", &format!("I={i}")];
        let mut args = vec!["analyze", model.as_str(), "--format", "json"];
        args.extend_from_slice(&sets);
        let a = eom_json(&args);
        // The mode of largest real part: the estimate bounds its actual error, and its verdict
        // is the rule's with the exact real part.
        let modes = a["modes"].as_array().expect("modes");
        let top = modes
            .iter()
            .max_by(|x, y| num(&x["eigenvalue"]["re"]).total_cmp(&num(&y["eigenvalue"]["re"])))
            .expect("a mode");
        let (re, tol) = (num(&top["eigenvalue"]["re"]), num(&top["tolerance"]));
        assert!(
            tol > 0.0 && (re - exact).abs() <= tol,
            "I = {i}: Re λ = {re:e}, exact {exact:e}, tolerance {tol:e}"
        );
        let want = rule(exact, tol);
        assert_eq!(top["stability"], want, "I = {i}: {top}");
        assert_eq!(a["stability"], want, "I = {i}");

        // The sweep at the same single point: the same verdict, by a tolerance it states.
        let grid = format!("I={i}:{i}:1");
        let mut args = vec![
            "sweep",
            model.as_str(),
            "--param",
            &grid,
            "--format",
            "json",
        ];
        args.extend_from_slice(&sets[..2]);
        let s = eom_json(&args);
        let p = &s["points"][0];
        assert_eq!(p["stability"], want, "I = {i}: {p}");
        let (max, stol) = (num(&p["max_real"]), num(&p["tolerance"]));
        assert!(
            (max - exact).abs() <= stol && rule(max, stol) == want,
            "I = {i}: sweep {max:e} ± {stol:e}, exact {exact:e}"
        );
        let text = eom(&[
            "sweep", &model, "--param", &grid, "--set", "cf=0", "--quiet",
        ])
        .stdout;
        assert!(
            text.contains(&format!("  {want} ")) && text.contains("error estimate"),
            "{text}"
        );

        // The report states the same verdict.
        let out = dir.join(i);
        std::fs::create_dir_all(&out).expect("a directory");
        let mut args = vec!["report", model.as_str(), "-o", out.to_str().expect("UTF-8")];
        args.extend_from_slice(&sets);
        args.push("--quiet");
        assert_eq!(eom(&args).code, 0);
        let html = std::fs::read_to_string(out.join("half_car.html")).expect("the page");
        assert!(html.contains(&format!("; {want} at this point")), "I = {i}");
    }
}

/// A marginal grid point is not inside a stable interval: the intervals end there, as at a
/// boundary (I = m a b = 2016, where the undamped mode's real part is exactly 0).
#[test]
fn stable_intervals_stop_at_a_marginal_point() {
    let s = eom_json(&[
        "sweep",
        &half_car(),
        "--param",
        "I=2015:2017:5",
        "--set",
        "cf=0",
        "--format",
        "json",
    ]);
    let verdicts: Vec<&str> = s["points"]
        .as_array()
        .expect("points")
        .iter()
        .map(|p| p["stability"].as_str().expect("a verdict"))
        .collect();
    assert_eq!(
        verdicts,
        ["stable", "stable", "marginal", "stable", "stable"]
    );
    let intervals: Vec<(f64, f64)> = s["stable_intervals"]
        .as_array()
        .expect("intervals")
        .iter()
        .map(|i| (num(&i[0]), num(&i[1])))
        .collect();
    assert_eq!(intervals, [(2015.0, 2016.0), (2016.0, 2017.0)]);
}
