//! Typed errors of the geometry builders and of the solver's inputs.

// matrices are compared entry by entry, by (row, column)
#![allow(clippy::needless_range_loop)]

use eom_aero::{AeroError, Configuration, Reference, Section, SolverOptions, Surface, solve};

fn reference() -> Reference {
    Reference::new(1.0, 1.0, 1.0, [0.0; 3])
}

fn error_of(c: &Configuration) -> AeroError {
    solve(c, &SolverOptions::default()).unwrap_err()
}

#[test]
fn geometry_errors_name_surface_section_and_field() {
    let ok = Surface::new("Tail")
        .section(Section::new([0.0; 3], 1.0))
        .section(Section::new([0.0, 1.0, 0.0], 1.0));
    assert!(
        solve(
            &Configuration::new("c", reference()).surface(ok.clone()),
            &SolverOptions::default()
        )
        .is_ok()
    );

    let cases: Vec<(Surface, &str)> = vec![
        (
            Surface::new("Tail").section(Section::new([0.0; 3], 1.0)),
            "surface `Tail`: sections needs at least 2 sections",
        ),
        (
            ok.clone().section(Section::new([0.0, 2.0, 0.0], 0.0)),
            "surface `Tail`, section 3: chord must be positive",
        ),
        (
            ok.clone().section(Section::new([f64::NAN, 2.0, 0.0], 1.0)),
            "section 3: leading edge must be finite",
        ),
        (
            ok.clone().section(Section::new([1.0, 1.0, 0.0], 1.0)),
            "section 3: leading edge coincides",
        ),
        (
            ok.clone().lattice(0, 1.0, 8, 1.0),
            "surface `Tail`: Nchord/Cspace count must be at least 1",
        ),
        (
            ok.clone().lattice(4, 1.0, 8, 3.5),
            "Nspan/Sspace spacing parameter 3.5",
        ),
        (
            ok.clone().strips_per_section(),
            "section 1: Nspan/Sspace missing",
        ),
        (
            ok.clone().scaled([1.0, 0.0, 1.0]),
            "scale factors must be nonzero",
        ),
        (
            ok.clone()
                .section(Section::new([0.0, 2.0, 0.0], 1.0).incidence_deg(f64::INFINITY)),
            "section 3: incidence must be finite",
        ),
    ];
    for (surface, needle) in cases {
        let e = error_of(&Configuration::new("c", reference()).surface(surface)).to_string();
        assert!(e.contains(needle), "expected `{needle}` in `{e}`");
    }
    // three intervals need at least three strips
    let e = error_of(
        &Configuration::new("c", reference()).surface(
            ok.clone()
                .section(Section::new([0.0, 2.0, 0.0], 1.0))
                .lattice(4, 1.0, 1, 1.0),
        ),
    );
    assert!(
        e.to_string()
            .contains("Nspan 1 strips cannot cover 2 section intervals"),
        "{e}"
    );
}

#[test]
fn configuration_and_option_errors() {
    let s = Surface::wing("W", 1.0, 1.0, 1.0, 0.0, 0.0);
    let bad_ref =
        Configuration::new("c", Reference::new(0.0, 1.0, 1.0, [0.0; 3])).surface(s.clone());
    assert!(
        error_of(&bad_ref)
            .to_string()
            .contains("configuration `c`: Sref must be positive")
    );
    let sonic = Configuration::new("c", reference())
        .surface(s.clone())
        .mach(1.0);
    assert!(
        error_of(&sonic)
            .to_string()
            .contains("Mach must be in 0 ... < 1")
    );
    let mut images = Configuration::new("c", reference()).surface(s.clone());
    images.symmetry.iysym = 1;
    assert!(
        error_of(&images)
            .to_string()
            .contains("iYsym the y image is not supported")
    );
    images.symmetry.iysym = 0;
    images.symmetry.izsym = 2;
    assert!(
        error_of(&images)
            .to_string()
            .contains("iZsym must be -1, 0 or 1")
    );
    let empty = Configuration::new("c", reference());
    assert!(error_of(&empty).to_string().contains("surfaces none given"));
    let c = Configuration::new("c", reference()).surface(s);
    let e = solve(
        &c,
        &SolverOptions {
            alpha_deg: f64::NAN,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            AeroError::Option {
                option: "alpha_deg",
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn a_surface_in_its_own_mirror_plane_is_singular() {
    // a fin at y = 0 duplicated about y = 0 lies on top of itself
    let fin = Surface::fin("F", 1.0, 1.0, 1.0, 0.0).mirrored_about_y(0.0);
    let e = error_of(&Configuration::new("c", reference()).surface(fin));
    assert!(matches!(e, AeroError::Singular { .. }), "{e}");
}
