//! The solver against published AVL tables and against properties any correct lattice
//! has: mesh convergence, invariance under rotation, mirror symmetry, the 2-D limit,
//! Weissinger's one-panel lattice, compressibility by Göthert's rule.

// matrices are compared entry by entry, by (row, column)
#![allow(clippy::needless_range_loop)]

use eom_aero::{Configuration, Derivatives, Reference, Section, SolverOptions, Surface, solve};
use std::f64::consts::PI;

/// The seed paper's fin: a vertical flat plate 1 m high, chord 0.5 m, reference at c/4.
fn seed_fin(nc: usize, ns: usize) -> Configuration {
    Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0])).surface(
        Surface::new("Fin")
            .lattice(nc, 1.0, ns, 1.0)
            .section(Section::new([0.0, 0.0, -0.5], 0.5))
            .section(Section::new([0.0, 0.0, 0.5], 0.5)),
    )
}

/// The same plate lying flat, as one surface from y = −0.5 to 0.5.
fn seed_wing_flat(nc: usize, ns: usize) -> Configuration {
    Configuration::new("wing", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0])).surface(
        Surface::new("Wing")
            .lattice(nc, 1.0, ns, 1.0)
            .section(Section::new([0.0, -0.5, 0.0], 0.5))
            .section(Section::new([0.0, 0.5, 0.0], 0.5)),
    )
}

/// Rectangular flat plate of aspect ratio `ar`, chord 1, mirrored half wing.
fn plate(ar: f64, nc: usize, ns_half: usize) -> Configuration {
    Configuration::new("plate", Reference::new(ar, 1.0, ar, [0.25, 0.0, 0.0]))
        .surface(Surface::wing("W", ar / 2.0, 1.0, 1.0, 0.0, 0.0).lattice(nc, 1.0, ns_half, 1.0))
}

fn derivs(c: &Configuration) -> Derivatives {
    solve(c, &SolverOptions::default()).unwrap().derivatives
}

/// −L entries of the seed paper: L = −(qS/V)·build_mtx, i.e. minus `dimensional()`.
fn seed_l(d: &Derivatives) -> [f64; 4] {
    let m = d.dimensional(1.225, 10.0).unwrap();
    [-m[1][1], -m[1][5], -m[5][1], -m[5][5]]
}

#[test]
fn seed_fin_dimensional_matches_mesh_converged_avl() {
    // AVL, ρ = 1.225, V = 10 m/s: L22, L26, L62, L66
    let avl = [7.57725, -2.04804, 0.153728, 0.223803];
    for (nc, ns) in [(8, 16), (16, 32)] {
        let l = seed_l(&derivs(&seed_fin(nc, ns)));
        for k in 0..4 {
            assert!(
                (l[k] / avl[k] - 1.0).abs() < 0.002,
                "{nc}x{ns} entry {k}: {} vs {}",
                l[k],
                avl[k]
            );
        }
    }
}

#[test]
fn flat_plate_table() {
    // AVL, 16×32 per half, cosine/cosine, about c/4: AR, CLa, x_ac/c, CLq, Cmq, Clp
    let table = [
        (1.0, 1.4602, 0.167, 1.7033, -0.4651, -0.0979),
        (2.0, 2.4744, 0.209, 2.6754, -0.5848, -0.1898),
        (3.0, 3.1451, 0.225, 3.3049, -0.6392, -0.2692),
        (4.0, 3.6120, 0.232, 3.7426, -0.6706, -0.3361),
        (6.0, 4.2146, 0.239, 4.3089, -0.7054, -0.4403),
        (8.0, 4.5860, 0.242, 4.6594, -0.7241, -0.5169),
        (10.0, 4.8384, 0.244, 4.8984, -0.7357, -0.5753),
    ];
    for (ar, cla, xac, clq, cmq, clp) in table {
        let d = derivs(&plate(ar, 8, 16));
        let ours_cla = -d.get("CZw").unwrap();
        let ours_xac = 0.25 - d.get("Cmw").unwrap() / ours_cla;
        let ours = [
            ours_cla,
            -d.get("CZq").unwrap(),
            d.get("Cmq").unwrap(),
            d.get("Clp").unwrap(),
        ];
        for (x, a, name) in [
            (ours[0], cla, "CLa"),
            (ours[1], clq, "CLq"),
            (ours[2], cmq, "Cmq"),
            (ours[3], clp, "Clp"),
        ] {
            assert!((x / a - 1.0).abs() < 0.002, "AR {ar} {name}: {x} vs {a}");
        }
        // x_ac is tabulated to 3 decimals
        assert!(
            (ours_xac - xac).abs() <= 0.0005 + 0.002 * xac,
            "AR {ar} x_ac {ours_xac}"
        );
    }
}

#[test]
fn mesh_convergence() {
    // double chordwise and spanwise panels until the seed fin's five derivatives move by
    // less than 0.1 %
    let names = ["CYv", "CYr", "Cnv", "Cnr", "Clp"];
    let values = |d: &Derivatives| names.map(|n| d.get(n).unwrap());
    let (mut nc, mut ns) = (2, 4);
    let mut last = values(&derivs(&seed_fin(nc, ns)));
    let converged = loop {
        (nc, ns) = (2 * nc, 2 * ns);
        let now = values(&derivs(&seed_fin(nc, ns)));
        let change = (0..5)
            .map(|k| (now[k] / last[k] - 1.0).abs())
            .fold(0.0, f64::max);
        last = now;
        if change < 0.001 {
            break (nc, ns);
        }
        assert!(nc < 32, "not converged at {nc}x{ns}: change {change}");
    };
    println!("converged at {converged:?}: {last:?}");
    // and the converged values agree with the mesh-converged AVL ones
    let l = seed_l(&derivs(&seed_fin(converged.0, converged.1)));
    let avl = [7.57725, -2.04804, 0.1538, 0.223803];
    for k in 0..4 {
        assert!(
            (l[k] / avl[k] - 1.0).abs() < 0.002,
            "{k}: {} vs {}",
            l[k],
            avl[k]
        );
    }
}

#[test]
fn horizontal_wing_and_vertical_fin_give_the_same_dimensional_numbers() {
    let fin = derivs(&seed_fin(8, 16)).dimensional(1.225, 10.0).unwrap();
    let wing = derivs(&seed_wing_flat(8, 16))
        .dimensional(1.225, 10.0)
        .unwrap();
    // Y_v = Z_w, Y_r = −Z_q, N_v = −M_w, N_r = M_q (rotation by 90° about x)
    let pairs = [
        (fin[1][1], wing[2][2]),
        (fin[1][5], -wing[2][4]),
        (fin[5][1], -wing[4][2]),
        (fin[5][5], wing[4][4]),
        (fin[3][3], wing[3][3]),
    ];
    for (k, (f, w)) in pairs.iter().enumerate() {
        assert!((f - w).abs() <= 1e-10 * f.abs(), "pair {k}: {f} vs {w}");
    }
}

fn assert_decoupled(d: &Derivatives, what: &str) {
    // longitudinal rows (CX, CZ, Cm) × lateral columns (v, p, r) and the converse
    let scale = d
        .coefficients
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for i in 0..6 {
        for j in 0..6 {
            let row_lat = matches!(i, 1 | 3 | 5);
            let col_lat = matches!(j, 1 | 3 | 5);
            if row_lat != col_lat {
                let x = d.coefficients[i][j];
                assert!(
                    x.abs() < 1e-12 * scale,
                    "{what} {}: {x}",
                    Derivatives::names()[i][j]
                );
            }
        }
    }
}

#[test]
fn symmetric_configurations_decouple_at_zero_sideslip() {
    let swept = Configuration::new("swept", Reference::new(4.5, 1.0, 6.0, [0.5, 0.0, 0.0]))
        .surface(Surface::wing("W", 3.0, 1.0, 0.5, 30.0, 5.0).lattice(6, 1.0, 12, -2.0))
        .surface(Surface::fin("F", 1.0, 0.8, 0.4, 40.0).translated([3.0, 0.0, 0.0]));
    for alpha in [0.0, 5.0] {
        let s = solve(
            &swept,
            &SolverOptions {
                alpha_deg: alpha,
                ..Default::default()
            },
        )
        .unwrap();
        assert_decoupled(&s.derivatives, &format!("swept wing and fin, α = {alpha}"));
        // the lateral derivatives are nonzero: the test can fail on a wrong mirror
        assert!(s.derivatives.get("Clp").unwrap() < -0.1);
    }
}

#[test]
fn large_aspect_ratio_approaches_two_pi() {
    let mut last = 0.0;
    for ar in [20.0, 100.0, 500.0] {
        let cla = -derivs(&plate(ar, 4, 64)).get("CZw").unwrap();
        assert!(cla > last && cla < 2.0 * PI, "AR {ar}: {cla}");
        // Jones' edge-corrected lifting line 2πA/(E·A + 2), E = 1 + 1/A for a rectangle
        let jones = 2.0 * PI * ar / ((1.0 + 1.0 / ar) * ar + 2.0);
        assert!(
            (cla / jones - 1.0).abs() < 0.015,
            "AR {ar}: {cla} vs Jones {jones}"
        );
        last = cla;
    }
    assert!((last / (2.0 * PI) - 1.0).abs() < 0.01, "AR 500: {last}");
}

#[test]
fn one_chordwise_panel_loads_the_quarter_chord() {
    // Weissinger's lattice: all load at c/4, so no yaw moment about c/4 from v or r
    for cspace in [0.0, 1.0] {
        let c = Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0]))
            .surface(
                Surface::new("Fin")
                    .lattice(1, cspace, 16, 1.0)
                    .section(Section::new([0.0, 0.0, -0.5], 0.5))
                    .section(Section::new([0.0, 0.0, 0.5], 0.5)),
            );
        let l = seed_l(&derivs(&c));
        assert!(l[2].abs() < 1e-12 && l[3].abs() < 1e-12, "{l:?}");
        assert!(l[0] > 7.0);
    }
}

#[test]
fn incidence_acts_like_angle_of_attack() {
    // d(lift)/d(Ainc) = CLa for a small incidence, nose up positive
    let cla = -derivs(&plate(6.0, 8, 16)).get("CZw").unwrap();
    let a = 0.1f64;
    let mut c = plate(6.0, 8, 16);
    c.surfaces[0].angle_deg = a;
    let s = solve(&c, &SolverOptions::default()).unwrap();
    let slope = s.totals.lift / a.to_radians();
    assert!((slope / cla - 1.0).abs() < 1e-4, "{slope} vs {cla}");
}

#[test]
fn compressibility_follows_goethert() {
    // at Mach M the wing behaves like the incompressible wing stretched by 1/β in x
    let (mach, beta) = (0.6, 0.8);
    let wing = |chord: f64| {
        Configuration::new("w", Reference::new(6.0, 1.0, 6.0, [0.0; 3]))
            .surface(Surface::wing("W", 3.0, chord, chord, 0.0, 0.0).lattice(8, 1.0, 16, 1.0))
    };
    let compressible = derivs(&wing(1.0).mach(mach)).get("CZw").unwrap();
    let stretched = derivs(&wing(1.0 / beta)).get("CZw").unwrap();
    assert!((compressible / stretched - 1.0).abs() < 1e-10);
    let incompressible = derivs(&wing(1.0)).get("CZw").unwrap();
    assert!(compressible < incompressible * 1.1 && compressible < incompressible);
}

#[test]
fn surfaces_far_apart_add_up() {
    let a = Surface::wing("A", 2.0, 1.0, 0.6, 20.0, 3.0).lattice(6, 1.0, 10, 1.0);
    let b = Surface::fin("B", 1.0, 1.0, 0.5, 30.0).lattice(6, 1.0, 10, 1.0);
    let r = Reference::new(3.0, 1.0, 4.0, [0.0; 3]);
    // far to the side: downstream it would sit in the other surface's wake, which never ends
    let far = [0.0, 1e5, 0.0];
    let alone_a = derivs(&Configuration::new("a", r).surface(a.clone()));
    let mut r_far = r;
    r_far.point = far;
    let alone_b = derivs(&Configuration::new("b", r_far).surface(b.clone().translated(far)));
    // both together, moments about each one's own point are not comparable: use forces
    let both = derivs(
        &Configuration::new("ab", r)
            .surface(a)
            .surface(b.translated(far)),
    );
    for j in 0..6 {
        if j >= 3 {
            continue; // rate columns move the far surface by ω × 1e5
        }
        for i in 0..3 {
            let sum = alone_a.coefficients[i][j] + alone_b.coefficients[i][j];
            assert!(
                (both.coefficients[i][j] - sum).abs() < 1e-6,
                "({i},{j}) {} vs {sum}",
                both.coefficients[i][j]
            );
        }
    }
}

#[test]
fn splitting_a_surface_at_a_node_changes_nothing() {
    // the interior section at mid-span falls on the middle node of 16 cosine strips
    let one = seed_fin(8, 16);
    let two = Configuration::new("fin", one.reference).surface(
        Surface::new("Fin")
            .lattice(8, 1.0, 16, 1.0)
            .section(Section::new([0.0, 0.0, -0.5], 0.5))
            .section(Section::new([0.0, 0.0, 0.0], 0.5))
            .section(Section::new([0.0, 0.0, 0.5], 0.5)),
    );
    let (a, b) = (derivs(&one), derivs(&two));
    for i in 0..6 {
        for j in 0..6 {
            assert!((a.coefficients[i][j] - b.coefficients[i][j]).abs() < 1e-12);
        }
    }
}

#[test]
fn mirrored_half_equals_two_explicit_halves() {
    let mirrored = plate(6.0, 6, 10);
    let right = Surface::new("R")
        .lattice(6, 1.0, 10, 1.0)
        .section(Section::new([0.0; 3], 1.0))
        .section(Section::new([0.0, 3.0, 0.0], 1.0));
    let left = Surface::new("L")
        .lattice(6, 1.0, 10, 1.0)
        .section(Section::new([0.0, -3.0, 0.0], 1.0))
        .section(Section::new([0.0; 3], 1.0));
    // the left half's cosine spacing runs from its tip: the same nodes as the mirror
    // One component, as the mirror image is of its surface: AVL's vortex core acts only
    // between components.
    let (mut right, mut left) = (right, left);
    right.component = Some(1);
    left.component = Some(1);
    let explicit = Configuration::new("two", mirrored.reference)
        .surface(right)
        .surface(left);
    let options = SolverOptions {
        alpha_deg: 4.0,
        beta_deg: 2.0,
        ..Default::default()
    };
    let a = solve(&mirrored, &options).unwrap();
    let b = solve(&explicit, &options).unwrap();
    for i in 0..6 {
        for j in 0..6 {
            let (x, y) = (
                a.derivatives.coefficients[i][j],
                b.derivatives.coefficients[i][j],
            );
            assert!(
                (x - y).abs() < 1e-10,
                "{}: {x} vs {y}",
                Derivatives::names()[i][j]
            );
        }
        assert!((a.totals.body[i] - b.totals.body[i]).abs() < 1e-12);
    }
}

#[test]
fn scale_and_translate_keep_coefficients() {
    let base = plate(4.0, 6, 8);
    let mut moved = base.clone();
    moved.surfaces[0].translate = [1.0, 0.0, 2.0];
    moved.reference.point = [1.25, 0.0, 2.0];
    let mut scaled = base.clone();
    scaled.surfaces[0].scale = [2.0, 2.0, 2.0];
    scaled.reference = Reference::new(16.0, 2.0, 8.0, [0.5, 0.0, 0.0]);
    let options = SolverOptions {
        alpha_deg: 3.0,
        ..Default::default()
    };
    let d0 = solve(&base, &options).unwrap().derivatives;
    for c in [moved, scaled] {
        let d = solve(&c, &options).unwrap().derivatives;
        for i in 0..6 {
            for j in 0..6 {
                assert!((d.coefficients[i][j] - d0.coefficients[i][j]).abs() < 1e-10);
            }
        }
    }
}

#[test]
fn noload_surface_far_away_is_not_counted() {
    let wing = plate(6.0, 6, 8);
    let mut with = wing.clone();
    let mut ghost = Surface::wing("G", 3.0, 1.0, 1.0, 0.0, 0.0)
        .lattice(6, 1.0, 8, 1.0)
        .translated([0.0, 0.0, 1e6]);
    ghost.no_load = true;
    with.surfaces.push(ghost);
    let (a, b) = (derivs(&wing), derivs(&with));
    for i in 0..6 {
        for j in 0..6 {
            assert!((a.coefficients[i][j] - b.coefficients[i][j]).abs() < 1e-9);
        }
    }
}

#[test]
fn derivatives_agree_with_finite_differences_of_the_trim_loads() {
    // the analytic linearisation against central differences of the totals in α and β,
    // on a lifting, swept, dihedral wing with a fin, trailing-leg forces on and off
    let config = Configuration::new("c", Reference::new(4.5, 1.0, 6.0, [0.5, 0.0, 0.1]))
        .surface(
            Surface::wing("W", 3.0, 1.0, 0.5, 25.0, 6.0)
                .lattice(6, 1.0, 10, 1.0)
                .angle_deg(1.5),
        )
        .surface(
            Surface::fin("F", 1.0, 0.8, 0.4, 30.0)
                .lattice(6, 1.0, 8, 1.0)
                .translated([3.0, 0.0, 0.2]),
        );
    for legs in [true, false] {
        let at = |alpha: f64, beta: f64| {
            let o = SolverOptions {
                alpha_deg: alpha,
                beta_deg: beta,
                trailing_leg_forces: legs,
                ..SolverOptions::default()
            };
            solve(&config, &o).unwrap()
        };
        let (alpha, h) = (4.0f64, 1e-3f64);
        let base = at(alpha, 0.0);
        let d = &base.derivatives.coefficients;
        let (sa, ca) = alpha.to_radians().sin_cos();
        let (ap, am) = (at(alpha + h, 0.0), at(alpha - h, 0.0));
        let (bp, bm) = (at(alpha, h), at(alpha, -h));
        let step = 2.0 * h.to_radians();
        for i in 0..6 {
            // at constant speed: ∂/∂α = −sin α ∂/∂û + cos α ∂/∂ŵ, ∂/∂β = ∂/∂v̂ at β = 0
            let fd_alpha = (ap.totals.body[i] - am.totals.body[i]) / step;
            let fd_beta = (bp.totals.body[i] - bm.totals.body[i]) / step;
            let an_alpha = -sa * d[i][0] + ca * d[i][2];
            let an_beta = d[i][1];
            let tol = 1e-6 * (1.0 + an_alpha.abs().max(an_beta.abs()));
            assert!(
                (fd_alpha - an_alpha).abs() < tol,
                "legs {legs} row {i} α: {fd_alpha} vs {an_alpha}"
            );
            assert!(
                (fd_beta - an_beta).abs() < tol,
                "legs {legs} row {i} β: {fd_beta} vs {an_beta}"
            );
        }
    }
}

#[test]
fn sideslip_trim_gives_the_side_force_of_the_derivative() {
    let fin = seed_fin(8, 16);
    let cyv = derivs(&fin).get("CYv").unwrap();
    let beta = 2.0f64;
    let s = solve(
        &fin,
        &SolverOptions {
            beta_deg: beta,
            ..Default::default()
        },
    )
    .unwrap();
    // CY = CYv sin β cos β for a flat plate in linear theory
    let expected = cyv * beta.to_radians().sin() * beta.to_radians().cos();
    assert!(
        (s.totals.body[1] / expected - 1.0).abs() < 1e-9,
        "{} vs {expected}",
        s.totals.body[1]
    );
    assert!(
        s.totals.body[1] < 0.0,
        "wind from the right pushes the fin left"
    );
}

#[test]
fn ground_effect_raises_the_lift_slope_and_vanishes_far_away() {
    let cla = |ground: Option<f64>| {
        let mut c = plate(6.0, 6, 12);
        if let Some(z) = ground {
            c = c.ground_at(z);
        }
        -derivs(&c).get("CZw").unwrap()
    };
    let free = cla(None);
    let far = cla(Some(-1e4));
    assert!((far / free - 1.0).abs() < 1e-6, "{far} vs {free}");
    let heights = [2.0, 1.0, 0.5, 0.25];
    let slopes: Vec<f64> = heights.iter().map(|h| cla(Some(-h))).collect();
    assert!(slopes[0] > free);
    assert!(slopes.windows(2).all(|w| w[1] > w[0]), "{slopes:?}");
}
