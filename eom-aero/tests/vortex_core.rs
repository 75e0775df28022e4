//! AVL's finite vortex core against OptVL 2.5.0 (an AVL 3.52-derived core, double
//! precision), on layouts where one surface's root trailing legs run along another
//! surface's root: a wing with dihedral and a fin on the centre line above its root chord,
//! the same wing with a fin three chords aft, and a tailplane with a fin on it. Each with
//! AVL's default core (no `CORE` line: VRCOREC = 0, VRCOREW = 2), with the core off
//! (`CORE 0 0 1`) and with a chord-sized core (`CORE 0.25 0 1`), at α = 0 and 5°, on
//! cosine and on uniform chordwise lattices. Data and script:
//! tests/data/optvl/generate_core.py. OptVL loads no trailing legs, so neither do we here.
//!
//! With uniform chordwise spacing AVL's lattice and ours are the same points, and every
//! core setting agrees to about 6 digits. With cosine spacing the chordwise stations differ
//! (AVL 3.5x: (2j − 1)π/(2N + 1); ours: Lan's (2j − 1)π/2N), which the core hides (≤ 0.05 %)
//! but the singular coreless kernels amplify where a fin's control points sit a few
//! millimetres above a wing's root legs (up to 1.6 % in small entries).

// matrices are compared entry by entry, by (row, column)
#![allow(clippy::needless_range_loop)]

use eom_aero::{Derivatives, SolverOptions, VortexCore, read_avl, solve};
use serde_json::Value;

fn data(name: &str) -> String {
    format!("{}/tests/data/optvl/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn cases() -> Vec<Value> {
    let text = std::fs::read_to_string(data("optvl_core.json")).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    let cases = json["cases"].as_array().unwrap().clone();
    assert_eq!(cases.len(), 36);
    cases
}

fn options(alpha_deg: f64) -> SolverOptions {
    SolverOptions {
        alpha_deg,
        trailing_leg_forces: false,
        ..SolverOptions::default()
    }
}

/// The largest deviation of `ours` from the reference, relative to the entry or, for
/// entries below 1 % of their row's largest, to 1 % of that largest; and its name.
fn worst(ours: &Derivatives, reference: &Value) -> (f64, &'static str) {
    let names = Derivatives::names();
    let mut worst = (0.0, "");
    for i in 0..6 {
        let row: Vec<f64> = names[i]
            .iter()
            .map(|n| reference[n].as_f64().unwrap())
            .collect();
        let row_max = row.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..6 {
            let (x, a) = (ours.coefficients[i][j], row[j]);
            let dev = (x - a).abs() / a.abs().max(0.01 * row_max).max(1e-12);
            if dev > worst.0 {
                worst = (dev, names[i][j]);
            }
        }
    }
    worst
}

fn value(case: &Value, name: &str) -> f64 {
    case["derivatives"][name].as_f64().unwrap()
}

#[test]
fn the_core_file_settings_reproduce_avl() {
    for case in &cases() {
        let file = case["file"].as_str().unwrap();
        let alpha = case["alpha_deg"].as_f64().unwrap();
        let (core, chordwise) = (
            case["core"].as_str().unwrap(),
            case["chordwise"].as_str().unwrap(),
        );
        let config = read_avl(data(file)).unwrap();
        let expected_core = match core {
            "default" => None,
            "off" => Some(VortexCore::OFF),
            _ => Some(VortexCore::new(0.25, 0.0)),
        };
        assert_eq!(config.vortex_core, expected_core, "{file}");
        let sol = solve(&config, &options(alpha)).unwrap();
        assert_eq!(
            sol.vortex_core,
            expected_core.unwrap_or(VortexCore::AVL_DEFAULT)
        );
        let (dev, name) = worst(&sol.derivatives, &case["derivatives"]);
        println!("{file} α={alpha}: largest deviation {dev:.1e} ({name})");
        let tolerance = match (chordwise, core) {
            // the same lattice: 6e-9 is AVL's single-precision 1/4π (0.079577472)
            ("uniform", _) => 1e-7,
            // AVL's default and chord-sized cores, on AVL's own chordwise stations
            (_, "default" | "chord") => 2e-3,
            // coreless on different stations: see the module docs
            _ => 2e-2,
        };
        assert!(
            dev <= tolerance,
            "{file} α={alpha} {name}: {dev:e} > {tolerance:e}"
        );
        let lift = case["totals"]["CL"].as_f64().unwrap();
        assert!(
            (sol.totals.lift - lift).abs() <= tolerance.max(1e-5) * lift.abs().max(0.01),
            "{file} CL {} vs {lift}",
            sol.totals.lift
        );
    }
}

#[test]
fn the_core_changes_the_fin_interference_as_in_avl() {
    // The differences the core makes, ours against AVL's, on the identical (uniform) lattice
    // and on the cosine lattice: CYv, Cnv and CYp move by percents (tens of percents where
    // the fin's root sits on the wing's or tailplane's root chord).
    let cases = cases();
    let find = |file: &str, alpha: f64| {
        cases
            .iter()
            .find(|c| c["file"] == file && c["alpha_deg"].as_f64() == Some(alpha))
            .unwrap()
    };
    for layout in ["core_wing_fin", "core_wing_aft_fin", "core_tail_fin"] {
        for lattice in ["", "_uniform"] {
            let (on, off) = (
                find(&format!("{layout}{lattice}_default.avl"), 5.0),
                find(&format!("{layout}{lattice}_off.avl"), 5.0),
            );
            let config = read_avl(data(on["file"].as_str().unwrap())).unwrap();
            let with = solve(&config, &options(5.0)).unwrap().derivatives;
            let without = solve(
                &config,
                &SolverOptions {
                    vortex_core: Some(VortexCore::OFF),
                    ..options(5.0)
                },
            )
            .unwrap()
            .derivatives;
            for name in ["CYv", "Cnv", "CYp"] {
                // the change, relative to the value with the core
                let avl = 1.0 - value(off, name) / value(on, name);
                let ours = 1.0 - without.get(name).unwrap() / with.get(name).unwrap();
                println!(
                    "{layout}{lattice} {name}: the core changes AVL's by {:+.2} %, ours by {:+.2} %",
                    100.0 * avl,
                    100.0 * ours
                );
                assert!(avl.abs() > 0.01, "{layout}{lattice} {name}");
                let tolerance = if lattice.is_empty() { 0.02 } else { 1e-4 };
                assert!(
                    (ours - avl).abs() <= tolerance * avl.abs(),
                    "{layout}{lattice} {name}"
                );
            }
        }
    }
}

#[test]
fn options_override_the_file_and_bad_cores_are_refused() {
    let config = read_avl(data("core_wing_fin_uniform_off.avl")).unwrap();
    assert_eq!(config.vortex_core, Some(VortexCore::OFF));
    let default = read_avl(data("core_wing_fin_uniform_default.avl")).unwrap();
    let reference = solve(&default, &options(0.0)).unwrap().derivatives;
    let overridden = solve(
        &config,
        &SolverOptions {
            vortex_core: Some(VortexCore::AVL_DEFAULT),
            ..options(0.0)
        },
    )
    .unwrap();
    assert_eq!(overridden.derivatives, reference);
    for bad in [VortexCore::new(-1.0, 2.0), VortexCore::new(0.0, f64::NAN)] {
        let e = solve(
            &config,
            &SolverOptions {
                vortex_core: Some(bad),
                ..options(0.0)
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("vortex_core") && e.contains("VRCOREW"), "{e}");
    }
    let text = std::fs::read_to_string(data("core_wing_fin_uniform_off.avl")).unwrap();
    for (line, what) in [("0.0 -2.0 1.0", "not negative"), ("0.0 2.0", "SRCORE")] {
        let e = eom_aero::parse_avl(&text.replace("0.0 0.0 1.0", line), "x.avl")
            .unwrap_err()
            .to_string();
        assert!(e.contains(what) && e.contains("x.avl"), "{e}");
    }
}
