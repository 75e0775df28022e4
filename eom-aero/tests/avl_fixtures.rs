//! The solver against real AVL 3.32 output (tests/data, see its README): the `.avl` files
//! are read by the crate's reader, solved, and compared with the `.sb`/`.st` files that AVL
//! wrote for the same geometry.
//!
//! Tolerance: an entry passes if it is within 0.2 % of AVL's value, or within 0.2 % of the
//! largest entry of its row in absolute terms. The second clause is for entries that are
//! small against their row: zeros printed as ±0.000000, and moments about a point close to
//! the aerodynamic centre (Cmw of the AR-6 wing is −0.080 beside Cmq = −0.739; it is the
//! difference of a lift times a short arm, and the lattice's chordwise stations shift that
//! arm by 1e-4 chords).

// matrices are compared entry by entry, by (row, column)
#![allow(clippy::needless_range_loop)]

use eom_aero::{AvlOutput, Derivatives, SolverOptions, read_avl, solve};

fn data(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Largest relative deviation among entries that pass by the relative clause, and the
/// failures.
fn compare(ours: &[[f64; 6]; 6], avl: &[[f64; 6]; 6], what: &str) {
    let names = Derivatives::names();
    let mut worst: (f64, &str) = (0.0, "");
    for i in 0..6 {
        let row_max = avl[i].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..6 {
            let (x, a) = (ours[i][j], avl[i][j]);
            let dev = (x - a).abs();
            let ok = dev <= 0.002 * a.abs() || dev <= 0.002 * row_max;
            assert!(ok, "{what} {}: ours {x:.6}, AVL {a:.6}", names[i][j]);
            if a.abs() > 0.01 * row_max && dev / a.abs() > worst.0 {
                worst = (dev / a.abs(), names[i][j]);
            }
        }
    }
    println!(
        "{what}: largest relative deviation {:.3} % ({})",
        100.0 * worst.0,
        worst.1
    );
}

#[test]
fn seed_fin_matches_avl_sb() {
    let config = read_avl(data("seed_fin.avl")).unwrap();
    let avl = AvlOutput::read(data("seed_fin_a0_avl332.sb")).unwrap();
    let sol = solve(&config, &SolverOptions::default()).unwrap();
    assert_eq!(sol.lattice.vortices, 128);
    assert_eq!(sol.lattice.strips, 16);
    let avl = avl.derivatives().unwrap().derivatives;
    assert_eq!(avl.reference, sol.derivatives.reference);
    compare(
        &sol.derivatives.coefficients,
        &avl.coefficients,
        "seed fin (SB)",
    );
    // the five nonzero values of the seed paper's fin, each to 0.2 %
    for (name, value) in [
        ("CYv", -2.474202),
        ("CYr", 1.337496),
        ("Cnv", -0.050197),
        ("Cnr", -0.146157),
        ("Clp", -0.190622),
    ] {
        let x = sol.derivatives.get(name).unwrap();
        assert!((x / value - 1.0).abs() < 0.002, "{name}: {x} vs {value}");
    }
}

#[test]
fn dihedral_wing_at_five_degrees_matches_avl_sb() {
    let config = read_avl(data("dihedral10_ar6.avl")).unwrap();
    let avl = AvlOutput::read(data("dihedral10_ar6_a5_avl332.sb")).unwrap();
    assert_eq!(avl.alpha_deg, 5.0);
    let options = SolverOptions {
        alpha_deg: avl.alpha_deg,
        ..SolverOptions::default()
    };
    let sol = solve(&config, &options).unwrap();
    assert_eq!(
        (
            sol.lattice.surfaces,
            sol.lattice.strips,
            sol.lattice.vortices
        ),
        (2, 32, 256)
    );
    let avl_d = avl.derivatives().unwrap().derivatives;
    compare(
        &sol.derivatives.coefficients,
        &avl_d.coefficients,
        "AR-6 dihedral, α = 5° (SB)",
    );
    // trim totals, printed by AVL with 5 decimals
    let t = avl.totals().unwrap().unwrap();
    for k in 0..6 {
        assert!(
            (sol.totals.body[k] - t[k]).abs() < 0.002 * 0.365 + 5e-6,
            "total {k}"
        );
    }
    let cl = avl.value("CLtot").unwrap().unwrap();
    let cd = avl.value("CDind").unwrap().unwrap();
    assert!((sol.totals.lift / cl - 1.0).abs() < 0.002);
    assert!((sol.totals.drag - cd).abs() < 0.002 * cd + 5e-6);
}

#[test]
fn trailing_leg_forces_make_the_difference_in_sideslip_of_a_lifting_wing() {
    let config = read_avl(data("dihedral10_ar6.avl")).unwrap();
    let avl = AvlOutput::read(data("dihedral10_ar6_a5_avl332.sb")).unwrap();
    let avl_clv = avl.value("Clv").unwrap().unwrap();
    let off = SolverOptions {
        alpha_deg: 5.0,
        trailing_leg_forces: false,
        ..SolverOptions::default()
    };
    let sol = solve(&config, &off).unwrap();
    // AVL 3.32 loads the legs; without them Clv is off by several percent
    let clv = sol.derivatives.get("Clv").unwrap();
    assert!((clv / avl_clv - 1.0).abs() > 0.02, "{clv} vs {avl_clv}");
}

fn st_compare(ours: &[[f64; 5]; 6], avl: &[[f64; 5]; 6], what: &str) {
    let names = eom_aero::StabilityDerivatives::names();
    // the CD row is absent from AVL 3.32 ST files
    for i in 0..5 {
        let row_max = avl[i].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..5 {
            let (x, a) = (ours[i][j], avl[i][j]);
            let dev = (x - a).abs();
            assert!(
                dev <= 0.002 * a.abs() || dev <= 0.002 * row_max,
                "{what} {}: ours {x:.6}, AVL {a:.6}",
                names[i][j]
            );
        }
    }
}

#[test]
fn dihedral_wing_matches_avl_st_in_stability_axes() {
    let config = read_avl(data("dihedral10_ar6.avl")).unwrap();
    let avl = AvlOutput::read(data("dihedral10_ar6_a5_avl332.st")).unwrap();
    let sol = solve(
        &config,
        &SolverOptions {
            alpha_deg: 5.0,
            ..SolverOptions::default()
        },
    )
    .unwrap();
    let st = sol.stability_derivatives().unwrap();
    let avl_st = avl.stability_derivatives().unwrap().unwrap();
    st_compare(&st.coefficients, &avl_st.coefficients, "AR-6 dihedral (ST)");
}

#[test]
fn seed_wing_horizontal_matches_avl_st() {
    let config = read_avl(data("seed_wing_h.avl")).unwrap();
    let avl = AvlOutput::read(data("seed_wing_h_a0_avl332.st")).unwrap();
    let sol = solve(&config, &SolverOptions::default()).unwrap();
    let st = sol.stability_derivatives().unwrap();
    let avl_st = avl.stability_derivatives().unwrap().unwrap();
    st_compare(
        &st.coefficients,
        &avl_st.coefficients,
        "seed wing, horizontal (ST)",
    );
    for (name, value) in [
        ("CLa", 2.474168),
        ("CLq", 2.674873),
        ("Cma", 0.100354),
        ("Cmq", -0.584575),
    ] {
        let x = st.get(name).unwrap();
        assert!((x / value - 1.0).abs() < 0.002, "{name}: {x} vs {value}");
    }
}

#[test]
fn results_serialize_to_json() {
    let config = read_avl(data("seed_fin.avl")).unwrap();
    let sol = solve(&config, &SolverOptions::default()).unwrap();
    let v = serde_json::to_value(sol).unwrap();
    let cyv = v["derivatives"]["coefficients"][1][1].as_f64().unwrap();
    assert_eq!(cyv, sol.derivatives.get("CYv").unwrap());
    assert_eq!(v["derivatives"]["reference"]["bref"].as_f64(), Some(1.0));
    assert!(v["totals"]["lift"].is_number());
    let out = AvlOutput::read(data("seed_fin_a0_avl332.sb")).unwrap();
    let j = serde_json::to_value(&out).unwrap();
    assert_eq!(j["kind"], "Body");
    assert_eq!(j["run_case"], "-unnamed-");
    assert!(j.get("entries").is_none());
}
