//! Extreme parameter values that used to give answers printed without a warning that were
//! wrong: each case checks what `eom analyze` prints against the closed form or against the
//! other reduction paths.

mod common;
use common::{eom, eom_json};

fn analyze_json(args: &[&str]) -> serde_json::Value {
    let mut a = vec!["analyze"];
    a.extend_from_slice(args);
    a.extend_from_slice(&["--format", "json"]);
    eom_json(&a)
}

/// An inertia tensor that no body has is an error naming the body and the field when its
/// products make it indefinite (IBxz = 1e6 with moments of about 10 kg m²); principal moments
/// violating the triangle inequality (IBzz = 30 > IBxx + IByy = 20.2) are a warning naming them.
#[test]
fn impossible_inertia_tensors_are_errors() {
    let r = eom(&["analyze", "bicycle", "--set", "IBxz=1e6"]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    for needle in [
        "body `rear frame`",
        "field `products`",
        "not positive semidefinite",
    ] {
        assert!(r.stderr.contains(needle), "`{needle}` not in: {}", r.stderr);
    }
    let v = analyze_json(&["bicycle", "--set", "IBzz=30"]);
    // The JSON warning names its kind and item; its message is what the text output prints.
    let warned = v["warnings"].as_array().unwrap().iter().any(|w| {
        w["kind"] == "inertia_triangle"
            && w["item"]["kind"] == "body"
            && w["item"]["name"] == "rear frame"
            && w["message"]
                .as_str()
                .unwrap()
                .starts_with("linearization: ")
    });
    assert!(warned, "{}", v["warnings"]);
    // The published tensor (IBxz = 2.4) is accepted.
    assert_eq!(eom(&["analyze", "bicycle"]).code, 0);
}

/// k = 1e140: s = −c/2m ± i√(k/m − c²/4m²) = −0.05 ± 1e70 i, an oscillatory mode; at
/// k = 1e308 (once −0.05 ± 1e154 i labelled "zero", from a norm that overflowed to infinity)
/// the entry of A is beyond what the factorisations take without overflow (1e150), and the
/// refusal names it.
#[test]
fn a_huge_stiffness_gives_an_oscillatory_mode_or_a_refusal() {
    let v = analyze_json(&["smd", "--set", "k=1e140"]);
    let modes = v["modes"].as_array().expect("modes");
    assert_eq!(modes.len(), 2);
    for m in modes {
        assert_eq!(m["kind"], "oscillatory", "{m}");
        // Re λ = −0.05 is far below the rounding of a matrix of norm 1e140; Im λ is not.
        let im = m["eigenvalue"]["im"].as_f64().unwrap();
        assert!((im.abs() / 1e70 - 1.0).abs() < 1e-12, "{m}");
        let hz = m["natural_frequency_hz"].as_f64().unwrap();
        assert!(
            (hz * 2.0 * std::f64::consts::PI / 1e70 - 1.0).abs() < 1e-12,
            "{m}"
        );
    }
    let r = common::eom(&["analyze", "smd", "--set", "k=1e308"]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(
        r.stderr.contains("A[1, 0]") && r.stderr.contains("too large"),
        "{}",
        r.stderr
    );
}

/// The bicycle at 6.025 m/s, just above the capsize speed (6.0243 m/s): the capsize
/// eigenvalue +1.22e-4 is a real unstable pole on every path (it was taken for a structural
/// zero on the robust path, whose condition numbers near the zero eigenvalues came from the
/// undeflated matrix).
#[test]
fn the_capsize_verdict_does_not_depend_on_the_method() {
    for method in ["numeric", "symbolic", "robust"] {
        let v = analyze_json(&["bicycle", "--set", "v=6.025", "--method", method]);
        assert_eq!(v["stability"], "unstable", "{method}: {}", v["stability"]);
        let capsize: Vec<&serde_json::Value> = v["modes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|m| m["eigenvalue"]["re"].as_f64().unwrap() > 0.0)
            .collect();
        assert_eq!(capsize.len(), 1, "{method}: {capsize:?}");
        let c = capsize[0];
        assert_eq!(c["kind"], "real", "{method}: {c}");
        assert_eq!(c["stability"], "unstable", "{method}: {c}");
        let re = c["eigenvalue"]["re"].as_f64().unwrap();
        assert!((re - 1.2208e-4).abs() < 1e-8, "{method}: {re:e}");
    }
}

/// A stiff chain (k = 1e8): the slowest-decaying mode, −4.84e-5 ± 311 i, is stable with
/// damping ratio 1.6e-7 on every path (the robust path called it marginal, damping 0: its
/// states mixed positions and velocities, so its matrix could not be balanced and the modal
/// tolerances grew 3000-fold).
#[test]
fn a_stiff_chain_is_stable_on_every_path() {
    let mut verdicts = Vec::new();
    for method in ["numeric", "robust"] {
        let v = analyze_json(&["chain50", "--set", "k=1e8", "--method", method]);
        let modes = v["modes"].as_array().unwrap();
        let slow = modes
            .iter()
            .filter(|m| m["kind"] == "oscillatory")
            .max_by(|a, b| {
                let re = |m: &serde_json::Value| m["eigenvalue"]["re"].as_f64().unwrap();
                re(a).total_cmp(&re(b))
            })
            .expect("an oscillatory mode");
        let re = slow["eigenvalue"]["re"].as_f64().unwrap();
        let im = slow["eigenvalue"]["im"].as_f64().unwrap().abs();
        assert!(
            (re + 4.837e-5).abs() < 1e-8 && (im - 311.036).abs() < 1e-2,
            "{method}: {slow}"
        );
        assert_eq!(slow["stability"], "stable", "{method}: {slow}");
        let zeta = slow["damping_ratio"].as_f64().expect("damping ratio");
        assert!(
            (zeta - 4.837e-5 / 311.036).abs() < 1e-9,
            "{method}: {zeta:e}"
        );
        verdicts.push(v["stability"].clone());
    }
    assert_eq!(verdicts[0], "stable");
    assert_eq!(verdicts[0], verdicts[1]);
}

/// k = 1e-100 N/m: the spring is below what A's rounding can tell from none, and the gains
/// say so as at k = 1e-20 (the position integrates the force at 1/c = 10 m/N per s, the
/// velocity settles at F/c), never the 0 m/N and 0 N/N they once printed.
#[test]
fn a_negligible_stiffness_gives_integrating_gains_not_zero() {
    for k in ["1e-20", "1e-100"] {
        let v = analyze_json(&["smd", "--set", &format!("k={k}")]);
        let gains = v["steady_state_gain"].as_array().expect("gains");
        let z = gains.iter().find(|g| g["output"] == "z").expect("z / f");
        let slope = z["integrating"]["coefficient"]
            .as_f64()
            .expect("integrating");
        assert!((slope - 10.0).abs() < 1e-12, "k = {k}: {z}");
        let zdot = gains
            .iter()
            .find(|g| g["output"] == "z dot")
            .expect("z dot / f");
        assert!(
            (zdot["value"].as_f64().expect("finite") - 10.0).abs() < 1e-12,
            "{zdot}"
        );
    }
}
