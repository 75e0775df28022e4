//! The AVL file readers on real AVL 3.32 files (tests/data) and on mutated copies of them
//! made here, one fault at a time.

// matrices are compared entry by entry, by (row, column)
#![allow(clippy::needless_range_loop)]

use eom_aero::{
    AeroError, AeroWarning, AvlOutput, AvlOutputKind, Derivatives, parse_avl, read_avl,
};

fn path(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap()
}

/// Every `name = number` of the file as the file prints it, by a plain split (an
/// independent reading of the same text: the crate's scanner is not used).
fn printed(name: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for line in text(name).lines() {
        if line.contains(" / ") || line.trim_start().starts_with("Configuration") {
            continue;
        }
        let toks: Vec<&str> = line.split_whitespace().collect();
        for k in 1..toks.len().saturating_sub(1) {
            if toks[k] == "=" {
                out.push((toks[k - 1].to_string(), toks[k + 1].to_string()));
            }
        }
    }
    out
}

#[test]
fn sb_values_equal_the_files_digits() {
    for file in ["seed_fin_a0_avl332.sb", "dihedral10_ar6_a5_avl332.sb"] {
        let out = AvlOutput::read(path(file)).unwrap();
        assert_eq!(out.kind, AvlOutputKind::Body);
        let d = out.derivatives().unwrap();
        assert!(d.warnings.is_empty());
        let pairs = printed(file);
        let mut seen = 0;
        for (name, value) in &pairs {
            if let Some(x) = d.derivatives.get(name) {
                assert_eq!(x, value.parse::<f64>().unwrap(), "{file} {name}");
                seen += 1;
            }
        }
        assert_eq!(seen, 36, "{file}");
        let r = out.reference;
        let get = |n: &str| {
            pairs
                .iter()
                .find(|p| p.0 == n)
                .unwrap()
                .1
                .parse::<f64>()
                .unwrap()
        };
        assert_eq!(
            [r.sref, r.cref, r.bref],
            [get("Sref"), get("Cref"), get("Bref")]
        );
        assert_eq!(r.point, [get("Xref"), get("Yref"), get("Zref")]);
        assert_eq!(
            [out.alpha_deg, out.beta_deg, out.mach],
            [get("Alpha"), get("Beta"), get("Mach")]
        );
        assert_eq!(out.run_case, "-unnamed-");
        assert!(out.controls.is_empty());
    }
}

#[test]
fn st_values_equal_the_files_digits() {
    for file in [
        "seed_fin_a0_avl332.st",
        "seed_wing_h_a0_avl332.st",
        "dihedral10_ar6_a5_avl332.st",
    ] {
        let out = AvlOutput::read(path(file)).unwrap();
        assert_eq!(out.kind, AvlOutputKind::Stability);
        let st = out.stability_derivatives().unwrap().unwrap();
        let mut seen = 0;
        for (name, value) in printed(file) {
            if let Some(x) = st.get(&name) {
                assert_eq!(x, value.parse::<f64>().unwrap(), "{file} {name}");
                seen += 1;
            }
        }
        // AVL 3.32 has no CD rows: 25 entries, and Cnb is not overwritten by the
        // spiral-stability line of the dihedral file
        assert_eq!(seen, 25, "{file}");
    }
    let d = AvlOutput::read(path("dihedral10_ar6_a5_avl332.st")).unwrap();
    assert_eq!(
        d.stability_derivatives().unwrap().unwrap().get("Cnb"),
        Some(-0.002178)
    );
}

#[test]
fn seed_fin_sb_equals_its_st_at_alpha_zero() {
    let sb = AvlOutput::read(path("seed_fin_a0_avl332.sb"))
        .unwrap()
        .derivatives()
        .unwrap();
    let st = AvlOutput::read(path("seed_fin_a0_avl332.st"))
        .unwrap()
        .derivatives()
        .unwrap();
    assert!(st.warnings.contains(&AeroWarning::UColumnMissing));
    assert!(st.warnings.contains(&AeroWarning::CxRowNeedsDrag));
    let mut compared = 0;
    for i in 0..6 {
        for j in 0..6 {
            if st.known[i][j] {
                let (a, b) = (
                    st.derivatives.coefficients[i][j],
                    sb.derivatives.coefficients[i][j],
                );
                assert!(
                    (a - b).abs() <= 1e-6,
                    "{}: ST {a} SB {b}",
                    Derivatives::names()[i][j]
                );
                compared += 1;
            } else {
                assert_eq!(st.derivatives.coefficients[i][j], 0.0);
            }
        }
    }
    // rows CY, CZ, Cl, Cm, Cn of columns v, w, p, q, r
    assert_eq!(compared, 25);
}

#[test]
fn dihedral_st_at_five_degrees_converts_to_its_sb() {
    let sb = AvlOutput::read(path("dihedral10_ar6_a5_avl332.sb"))
        .unwrap()
        .derivatives()
        .unwrap();
    let st = AvlOutput::read(path("dihedral10_ar6_a5_avl332.st"))
        .unwrap()
        .derivatives()
        .unwrap();
    let names = Derivatives::names();
    let mut compared = 0;
    for i in 0..6 {
        for j in 0..6 {
            if st.known[i][j] {
                let (a, b) = (
                    st.derivatives.coefficients[i][j],
                    sb.derivatives.coefficients[i][j],
                );
                // both files print 6 decimals; the rotation mixes two rounded values
                assert!(
                    (a - b).abs() <= 2e-6,
                    "{}: from ST {a}, SB {b}",
                    names[i][j]
                );
                compared += 1;
            }
        }
    }
    // α ≠ 0 and no CD rows: rows CY, Cl, Cm, Cn of columns v, p, q, r
    assert_eq!(compared, 16);
    // The file's α (5°) in the warnings that need it.
    let at_five = |a: &f64| (a - 5.0).abs() < 1e-3;
    assert!(
        (st.warnings.iter())
            .any(|w| matches!(w, AeroWarning::WColumnMixed { alpha_deg } if at_five(alpha_deg))),
        "{:?}",
        st.warnings
    );
    assert!(
        (st.warnings.iter())
            .any(|w| matches!(w, AeroWarning::CzRowNeedsDrag { alpha_deg } if at_five(alpha_deg))),
        "{:?}",
        st.warnings
    );
}

fn expect_err(text: &str, what: &str) -> AeroError {
    match AvlOutput::parse(text, "mutated.sb").and_then(|o| o.derivatives()) {
        Ok(_) => panic!("{what}: accepted"),
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains("mutated.sb"), "{what}: {msg}");
            e
        }
    }
}

/// Replaces the value of `name` in its first `name = value` pair.
fn replace_value(text: &str, name: &str, value: &str) -> String {
    let key = format!("{name} =");
    let at = text.find(&key).unwrap() + key.len();
    let rest = &text[at..];
    let start = at + (rest.len() - rest.trim_start().len());
    let end = start + text[start..].find(char::is_whitespace).unwrap();
    format!("{}{}{}", &text[..start], value, &text[end..])
}

#[test]
fn overflowed_value_is_an_error_naming_line_and_field() {
    let sb = text("seed_fin_a0_avl332.sb");
    let bad = replace_value(&sb, "CYv", "*********");
    let e = expect_err(&bad, "***");
    let line = sb.lines().position(|l| l.contains("CYv =")).unwrap() + 1;
    match e {
        AeroError::BadValue { line: l, field, .. } => {
            assert_eq!((l, field.as_str()), (line, "CYv"))
        }
        e => panic!("{e}"),
    }
}

#[test]
fn nan_is_an_error() {
    let bad = replace_value(&text("seed_fin_a0_avl332.sb"), "Cnr", "NaN");
    let e = expect_err(&bad, "NaN");
    assert!(
        matches!(e, AeroError::BadValue { ref field, .. } if field == "Cnr"),
        "{e}"
    );
}

#[test]
fn truncated_file_is_an_error() {
    let sb = text("dihedral10_ar6_a5_avl332.sb");
    // cut inside the rate table, right after "CYp ="
    let cut = sb.find("CYp =").unwrap() + "CYp =".len();
    let e = expect_err(&sb[..cut], "truncated after '='");
    assert!(
        matches!(e, AeroError::BadValue { ref field, .. } if field == "CYp"),
        "{e}"
    );
    // cut at a line end: the rest of the table is missing
    let cut = sb.find(" y force CY  |    CYp").unwrap();
    let e = expect_err(&sb[..cut], "truncated at a line");
    assert!(
        matches!(e, AeroError::MissingField { ref field, .. } if field == "CYp"),
        "{e}"
    );
    // cut before the table
    let cut = sb.find(" Geometry-axis").unwrap();
    expect_err(&sb[..cut], "no table");
}

#[test]
fn missing_derivative_is_an_error() {
    let sb = text("seed_fin_a0_avl332.sb");
    let bad: String = sb
        .lines()
        .filter(|l| !l.contains("CZp ="))
        .map(|l| format!("{l}\n"))
        .collect();
    let e = expect_err(&bad, "missing row");
    assert!(
        matches!(e, AeroError::MissingField { ref field, .. } if field == "CZp"),
        "{e}"
    );
}

#[test]
fn other_layouts_are_refused_with_the_missing_field() {
    let sb = text("seed_fin_a0_avl332.sb");
    // a layout without the orientation line
    let bad: String = sb
        .lines()
        .filter(|l| !l.contains("axis orientation"))
        .map(|l| format!("{l}\n"))
        .collect();
    let e = expect_err(&bad, "no orientation");
    assert!(e.to_string().contains("orientation"), "{e}");
    // a layout with another name for the reference chord
    let e = expect_err(&sb.replace("Cref =", "Cbar ="), "renamed Cref");
    assert!(
        matches!(e, AeroError::MissingField { ref field, .. } if field == "Cref"),
        "{e}"
    );
}

#[test]
fn geometric_axes_are_refused() {
    let sb = text("seed_fin_a0_avl332.sb");
    let bad = sb.replace(
        "Standard axis orientation,  X fwd, Z down",
        "Geometric axis orientation,  X aft, Z up ",
    );
    let e = expect_err(&bad, "geometric axes");
    let line = sb
        .lines()
        .position(|l| l.contains("axis orientation"))
        .unwrap()
        + 1;
    assert!(
        matches!(e, AeroError::Parse { line: l, .. } if l == line),
        "{e}"
    );
}

#[test]
fn controls_are_named_from_the_column_header() {
    // the seed fin's ST file with a control block as AVL 3.4x prints it
    let st = text("seed_fin_a0_avl332.st");
    let block = "\n                  elevator     d01     rudder       d02\n\
                  ----------------    ----------------\n\
 z' force CL |   CLd01 =   0.007971   CLd02 =  -0.000001\n\
 y  force CY |   CYd01 =   0.000006   CYd02 =  -0.000261\n";
    let with = format!("{st}{block}");
    let out = AvlOutput::parse(&with, "controls.st").unwrap();
    assert_eq!(out.controls, ["elevator", "rudder"]);
    assert_eq!(out.value("CYd02").unwrap(), Some(-0.000261));
    assert_eq!(out.value("CXd01").unwrap(), None);
}

#[test]
fn avl_geometry_fixtures_are_read() {
    let fin = read_avl(path("seed_fin.avl")).unwrap();
    assert_eq!(
        fin.title,
        "Seed-paper fin: flat rectangular plate, height 1.0 m, chord 0.5 m, vertical"
    );
    assert_eq!(fin.reference.point, [0.125, 0.0, 0.0]);
    assert_eq!(fin.surfaces.len(), 1);
    let s = &fin.surfaces[0];
    assert_eq!((s.chordwise.count, s.chordwise.parameter), (8, 1.0));
    assert_eq!(s.spanwise.map(|p| (p.count, p.parameter)), Some((16, 1.0)));
    assert_eq!(s.sections[0].leading_edge, [0.0, 0.0, -0.5]);
    assert_eq!(s.sections[1].chord, 0.5);
    let wing = read_avl(path("dihedral10_ar6.avl")).unwrap();
    assert_eq!(wing.surfaces[0].y_duplicate, Some(0.0));
    assert_eq!(
        wing.surfaces[0].sections[1].leading_edge,
        [0.0, 3.0, 0.528982]
    );
    let h = read_avl(path("seed_wing_h.avl")).unwrap();
    assert_eq!(h.reference.sref, 0.5);
}

const HEADER: &str = "Test\n0.0\n0 0 0.0\n1.0 1.0 2.0\n0.25 0 0\n";

fn avl_err(body: &str) -> String {
    parse_avl(&format!("{HEADER}{body}"), "t.avl")
        .unwrap_err()
        .to_string()
}

#[test]
fn avl_keywords_and_errors() {
    let surface = "SURFACE\nW\n4 1.0 8 1.0\nSECTION\n0 0 0 1 0\nSECTION\n0 1 0 1 0\n";
    // every honoured keyword, abbreviated to four letters where AVL allows it
    let full = format!(
        "{HEADER}# comment\nSURF ! remark\nW\n4 1.0 8 1.0\nCOMPONENT\n3\nYDUP\n0.0\nSCALE\n1 1 1\n\
         TRANSLATE\n0 0 0\nANGLE\n2.0\nNOLOAD\nNOALBE\nSECTION\n0 0 0 1 0\nNACA\n0012\nCLAF\n1.0\n\
         SECTION\n0 1 0 1 0 4 -2.0\n"
    );
    let c = parse_avl(&full, "t.avl").unwrap();
    let s = &c.surfaces[0];
    assert_eq!(s.component, Some(3));
    assert_eq!(s.angle_deg, 2.0);
    assert!(s.no_load && s.no_alpha_beta);
    assert_eq!(s.sections[1].spanwise.map(|p| p.count), Some(4));
    parse_avl(&format!("{HEADER}0.01\n{surface}"), "t.avl")
        .map(|c| assert_eq!(c.cdp, 0.01))
        .unwrap();

    for (body, needle) in [
        (format!("{surface}BODY\nFuse\n"), "t.avl:13: keyword `BODY`"),
        (
            format!("{surface}CONTROL\nelev 1 0.7 0 1 0 1\n"),
            "keyword `CONTROL`",
        ),
        (
            surface.replace("SECTION\n0 1 0 1 0\n", "NACA\n2412\nSECTION\n0 1 0 1 0\n"),
            "t.avl:11: keyword `NACA`",
        ),
        (format!("{surface}AFILE\nx.dat\n"), "keyword `AFILE`"),
        (format!("{surface}CLAF\n1.1\n"), "keyword `CLAF`"),
        (format!("{surface}CDCL\n0 0 0 0 0 0\n"), "keyword `CDCL`"),
        (
            surface.replace("8 1.0\n", "8 1.0\nNOWAKE\n"),
            "t.avl:9: keyword `NOWAKE`",
        ),
        (format!("{surface}FOOBAR\n"), "unknown keyword `FOOBAR`"),
        (
            surface.replace("0 1 0 1 0", "0 1 0 x 0"),
            "t.avl:12: SECTION data: Chord must be a finite number, found `x`",
        ),
        (
            surface.replace("0 1 0 1 0", "0 0 0 1 0"),
            "t.avl:11: surface `W`, section 2: leading edge",
        ),
        (
            surface.replace("0 1 0 1 0", "0 1 0 -1 0"),
            "section 2: chord must be positive",
        ),
        (
            surface.replace("4 1.0 8 1.0", "4 1.0"),
            "t.avl:9: surface `W`, section 1: Nspan/Sspace missing",
        ),
        (
            surface.replace("4 1.0 8 1.0", "0 1.0 8 1.0"),
            "Nchord must be at least 1",
        ),
        ("SECTION\n0 0 0 1 0\n".into(), "SECTION before any SURFACE"),
        (
            "SURFACE\nW\n4 1.0 8 1.0\nSECTION\n0 0 0 1\n".into(),
            "t.avl:10: SECTION data: Ainc must be a finite number, found nothing",
        ),
        (
            "SURFACE\nW\n4 1.0 8 1.0\nSECTION\n".into(),
            "t.avl:9: unexpected end of file: expected SECTION data",
        ),
    ] {
        let e = avl_err(&body);
        assert!(e.contains(needle), "expected `{needle}` in `{e}`");
    }
    let e = parse_avl("T\n0\n1 0 0\n1 1 1\n0 0 0\n", "s.avl")
        .unwrap_err()
        .to_string();
    assert!(e.contains("s.avl:3: keyword `iYsym`"), "{e}");
    let e = parse_avl("T\n0\n0 2 0\n1 1 1\n0 0 0\n", "s.avl")
        .unwrap_err()
        .to_string();
    assert!(e.contains("s.avl:3: iZsym must be -1, 0 or 1"), "{e}");
    let ground = format!("T\n0\n0 1 -0.5\n1 1 2\n0.25 0 0\n{surface}");
    let c = parse_avl(&ground, "g.avl").unwrap();
    assert_eq!((c.symmetry.izsym, c.symmetry.zsym), (1, -0.5));
}
