//! `[[wing]]` in model files: derivatives by name, from AVL's own output files (real AVL 3.32
//! output for the seed paper's fin, `tests/data/README.md`) and from an AVL geometry through
//! the vortex lattice; mirrored wings; errors that name the file, line, item and field.

use eom_model::file::{load, load_str};
use eom_model::{Linearizer, Method, Model};
use num_complex::Complex64;
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The AVL fixtures live once, with eom-aero's tests (its data README says how they were made).
fn aero_data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../eom-aero/tests/data")
        .join(name)
}

fn eigenvalues(model: &Model, at: &[(&str, f64)]) -> Vec<Complex64> {
    let ss = Linearizer::new(model)
        .at(at)
        .method(Method::Numeric)
        .run()
        .expect("linearizes")
        .state_space;
    let mut z = eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues");
    z.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    z
}

#[test]
fn the_file_gives_the_built_in_model() {
    let file = load(&data("shimmy_fin.toml"), &[]).expect("loads").model;
    let builtin = models::build("shimmy_wing", &[]).unwrap();
    for at in [&[][..], &[("x", 0.15), ("u", 4.0)][..]] {
        let (a, b) = (eigenvalues(&file, at), eigenvalues(&builtin, at));
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).norm() <= 1e-12 * y.norm().max(1.0),
                "{a:?} vs {b:?}"
            );
        }
    }
}

/// The entries AVL 3.32 printed in `seed_fin_a0_avl332.sb`.
const AVL_SB: [(&str, f64); 5] = [
    ("CYv", -2.474202),
    ("CYr", 1.337496),
    ("Cnv", -0.050197),
    ("Cnr", -0.146157),
    ("Clp", -0.190622),
];

fn wing_of(model: &Model) -> eom_model::Wing<f64> {
    model
        .nominal()
        .unwrap()
        .wings()
        .next()
        .expect("a wing")
        .clone()
}

fn get(w: &eom_model::Wing<f64>, n: &str) -> f64 {
    let (i, j) = eom_model::items::wing_derivative_index(n).unwrap();
    w.derivatives[i][j]
}

#[test]
fn derivatives_area_chord_and_span_come_from_an_avl_body_axis_file() {
    let loaded = load(&data("shimmy_fin_avl.toml"), &[]).expect("loads");
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let w = wing_of(&loaded.model);
    assert_eq!((w.area, w.chord, w.span), (0.5, 0.5, 1.0));
    for (n, v) in AVL_SB {
        assert_eq!(get(&w, n), v, "{n}");
    }
    // AVL's own lattice is within 0.3 % of the paper's entries (it is −0.29 % in L22).
    let m = loaded.model.nominal().unwrap();
    let l = w.damping(m.airspeed_of(&w));
    for ((i, j), paper) in [
        ((1, 1), 7.59895),
        ((1, 5), -2.05293),
        ((5, 1), 0.153319),
        ((5, 5), 0.224167),
    ] {
        assert!(
            ((l[i][j] - paper) / paper).abs() < 3e-3,
            "L{i}{j} = {}",
            l[i][j]
        );
    }
}

#[test]
fn a_stability_axis_file_gives_the_same_fin_and_says_what_it_cannot() {
    let (path, text) = with_avl_file("seed_fin_a0_avl332.st");
    std::fs::write(&path, &text).unwrap();
    let loaded = load(&path, &[]);
    std::fs::remove_file(&path).ok();
    let loaded = loaded.expect("loads");
    assert!(
        loaded.warnings.iter().any(|w| matches!(
            w,
            eom_model::Warning::AvlFile {
                item,
                warning: eom_aero::AeroWarning::UColumnMissing,
                ..
            } if item.name == "fin"
        )),
        "{:?}",
        loaded.warnings
    );
    let w = wing_of(&loaded.model);
    for (n, v) in AVL_SB {
        assert!((get(&w, n) - v).abs() <= 1e-6, "{n}: {}", get(&w, n));
    }
}

/// The model file's text with its AVL file replaced by `file` of the test data, written to
/// a temporary file (the AVL file by its absolute path).
fn with_avl_file(file: &str) -> (PathBuf, String) {
    let text = std::fs::read_to_string(data("shimmy_fin_avl.toml"))
        .unwrap()
        .replace(
            "\"../../../eom-aero/tests/data/seed_fin_a0_avl332.sb\"",
            &format!("{:?}", aero_data(file)),
        );
    let path = std::env::temp_dir().join(format!("eom-wing-{file}-{}.toml", std::process::id()));
    (path, text)
}

#[test]
fn an_avl_geometry_is_solved_by_the_vortex_lattice() {
    // Relative paths in a text loaded without a file are relative to the working directory.
    let text = std::fs::read_to_string(data("shimmy_fin_avl.toml")).unwrap();
    let e = load_str(&text, "fin.toml", &[])
        .map(|_| ())
        .expect_err("not found")
        .to_string();
    assert!(e.contains("fin.toml:") && e.contains("field `avl`"), "{e}");
    let (path, text) = with_avl_file("seed_fin.avl");
    std::fs::write(&path, &text).unwrap();
    let loaded = load(&path, &[]);
    std::fs::remove_file(&path).ok();
    let w = wing_of(&loaded.expect("loads").model);
    let v = wing_of(&models::build("shimmy_fin", &[]).unwrap());
    // The same lattice (the built-in model sets the rounding residue of the symmetric plate,
    // below 1e-12 of the largest entry, to zero).
    let largest = v
        .derivatives
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    for (a, b) in w
        .derivatives
        .iter()
        .flatten()
        .zip(v.derivatives.iter().flatten())
    {
        assert!((a - b).abs() <= 1e-12 * largest, "{a} vs {b}");
    }
}

const WING: &str = r#"
[parameters]
u = 20
[[body]]
name = "plane"
mass = 1
moments = [1, 1, 1]
velocity = ["u", 0, 0]
[[rigid_point]]
name = "hold"
between = ["plane", "ground"]
forces = 3
moments = 3
"#;

fn load_wing(extra: &str) -> Result<Model, String> {
    eom_model::file::from_str(&format!("{WING}{extra}"), "w.toml", &[]).map_err(|e| e.to_string())
}

#[test]
fn a_mirrored_wing_changes_the_couplings_of_left_and_right() {
    let m = load_wing(
        r#"
[[wing]]
name = "left wing"
body = "plane"
at = [0, 2, 1]
mirror = "y"
derivatives = { CYv = -0.3, CXv = 0.1, Clw = 0.2, Cnp = -0.05, Cmq = -0.7 }
"#,
    )
    .expect("loads")
    .nominal()
    .unwrap();
    let wings: Vec<_> = m.wings().collect();
    assert_eq!(wings.len(), 2);
    let (l, r) = (wings[0], wings[1]);
    assert_eq!(&*r.name, "right wing");
    assert_eq!(r.location, [0.0, -2.0, 1.0]);
    for (n, sign) in [
        ("CYv", 1.0),
        ("CXv", -1.0),
        ("Clw", -1.0),
        ("Cnp", 1.0),
        ("Cmq", 1.0),
    ] {
        assert_eq!(get(r, n), sign * get(l, n), "{n}");
    }
    // The mirror image of the damping block: entry (i, j) changes sign with the y rows and
    // columns (Y, L, N and v, p, r).
    let s = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
    let (bl, br) = (l.damping(20.0), r.damping(20.0));
    for i in 0..6 {
        for j in 0..6 {
            assert!(
                (br[i][j] - s[i] * s[j] * bl[i][j]).abs() < 1e-12,
                "({i}, {j})"
            );
        }
    }
}

#[test]
fn bad_wings_are_errors_naming_file_line_item_and_field() {
    let cases = [
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\nderivatives = { CYb = -2 }\n",
            "w.toml:17:17",
            "wing `w`, field `derivatives`: unknown derivative `CYb` (did you mean `CYv`? AVL's β derivatives are the v derivatives",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\nderivatives = { CLa = 2 }\n",
            "",
            "(lift derivatives are body-axis z-force ones: at α = 0, CZw = −CLa)",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\navl = \"no-such-file.sb\"\n",
            "",
            "wing `w`, field `avl`",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\navl = \"fin.txt\"\n",
            "",
            "expected an AVL output file (.sb body axes, .st stability axes)",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\nchord = 0\nderivatives = { CZw = -3 }\n",
            "",
            "wing `w`, field `chord`: the reference chord must be positive",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plan\"\n",
            "",
            "no body called `plan`",
        ),
        (
            "[[wing]]\nname = \"w\"\nbody = \"plane\"\nspn = 1\n",
            "",
            "unknown key `spn` (did you mean `span`?)",
        ),
    ];
    for (text, at, want) in cases {
        let e = load_wing(text).expect_err("invalid");
        assert!(e.contains(want), "{e}\nshould contain {want}");
        assert!(e.contains(at), "{e}\nshould be at {at}");
    }
    let avl_and_area = format!(
        "[[wing]]\nname = \"w\"\nbody = \"plane\"\narea = 2\navl = {:?}\n",
        aero_data("seed_fin_a0_avl332.sb")
    );
    let e = load_wing(&avl_and_area).expect_err("both");
    assert!(
        e.contains("field `area`: comes from the AVL file (`avl`)"),
        "{e}"
    );
}
