//! `eom reduce` and `eom analyze --reduce`: the printed Hankel singular values against the
//! independent reference (`tests/data/hankel.json`, SciPy and mpmath, script
//! `tests/data/gen_hankel.py`), the bound against the measured error, the bicycle's exact zeros
//! kept, the reduced matrices' transfer function at DC, usage errors, the plot.

mod common;
use common::{eom, eom_json};

const REFERENCE: &str = include_str!("../../tests/data/hankel.json");

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

#[test]
fn quarter_car_hankel_singular_values_as_printed_match_the_reference() {
    let j = eom_json(&["reduce", "quarter_car", "--order", "2", "--format", "json"]);
    let got = numbers(&j["hankel_singular_values"]);
    let refs: serde_json::Value = serde_json::from_str(REFERENCE).unwrap();
    let case = refs["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["model"] == "quarter_car")
        .unwrap();
    let want = numbers(&case["mpmath"]);
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() <= 1e-8 * w, "{g} against {w}");
    }
    // The bound is 2 Σ σ beyond the order, and the measured error lies below it.
    let bound = j["bound"].as_f64().unwrap();
    assert!((bound - 2.0 * (want[2] + want[3])).abs() <= 1e-8 * bound);
    let measured = j["measured"]["hinf"].as_f64().unwrap();
    assert!(measured > 0.0 && measured <= bound, "{measured} {bound}");
    assert_eq!(j["states"], 2);
    assert_eq!(j["matrices"]["A"].as_array().unwrap().len(), 2);
}

#[test]
fn the_bicycle_keeps_its_zeros_exactly_and_matchdc_keeps_the_steady_state() {
    let j = eom_json(&[
        "reduce", "bicycle", "--set", "v=5", "--order", "5", "--format", "json",
    ]);
    assert_eq!(j["kept_whole"], 2);
    assert_eq!(j["structural_zeros"], 2);
    let zeros = j["modes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|m| m["eigenvalue"]["re"] == 0.0 && m["eigenvalue"]["im"] == 0.0)
        .filter(|m| m["origin"] == "kept whole")
        .count();
    assert_eq!(zeros, 2, "{}", j["modes"]);
    let j = eom_json(&[
        "reduce", "bicycle", "--set", "v=5", "--order", "4", "--method", "matchdc", "--format",
        "json",
    ]);
    let dc = j["measured"]["dc"].as_f64().unwrap();
    let bound = j["bound"].as_f64().unwrap();
    assert!(dc <= 1e-12 * bound, "DC gain error {dc}");
    assert!(j["measured"]["hinf"].as_f64().unwrap() <= bound);
}

#[test]
fn an_order_below_the_kept_modes_is_a_usage_error() {
    let r = eom(&["reduce", "bicycle", "--order", "1"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("kept whole") && r.stderr.contains("at least 2"),
        "{}",
        r.stderr
    );
    let r = eom(&["reduce", "smd", "--method", "modal"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("order or a frequency band"),
        "{}",
        r.stderr
    );
    let r = eom(&["reduce", "smd", "--band", "1:0.5", "--method", "modal"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
}

#[test]
fn plot_and_analyze_reduce() {
    let dir = std::env::temp_dir().join(format!("eom-reduce-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("hsv.svg");
    let r = eom(&[
        "reduce",
        "chain10",
        "--order",
        "6",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("Hankel singular values"));
    assert!(
        r.stdout.contains("bound 2·Σσ beyond the order"),
        "{}",
        r.stdout
    );
    std::fs::remove_dir_all(&dir).ok();
    let j = eom_json(&[
        "analyze",
        "quarter_car",
        "--reduce",
        "2",
        "--format",
        "json",
    ]);
    assert_eq!(j["reduction"]["states"], 2);
    assert!(j["modes"].is_array(), "the analysis is still there");
}
