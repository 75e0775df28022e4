//! The shipped models whose wings carry vortex-lattice derivatives (`shimmy_fin`,
//! `ride_wings`, `aircraft_ground`) hold the numbers that eom-aero's lattice gives for their
//! geometry: every derivative a file gives a wing equals the lattice's at α = 0 (entries below
//! 1e-12 of the largest being the rounding residue of couplings the symmetry makes zero), to
//! 1e-12 of the largest, and every derivative the file leaves out is such a zero. The
//! geometries are those the files' comments describe.

use eom_aero::{Configuration, Derivatives, Reference, Section, SolverOptions, Surface};

/// The seed fin (Minaker et al.) in AVL's geometry axes (x aft, y right, z up): a flat plate
/// from z = −0.5 to 0.5 with a 0.5 m chord, leading edge at x = 0, moment reference at the
/// quarter chord; 8 chordwise × 16 spanwise panels, cosine spacing both ways.
fn seed_fin() -> Configuration {
    Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0])).surface(
        Surface::new("fin")
            .lattice(8, 1.0, 16, 1.0)
            .section(Section::new([0.0, 0.0, -0.5], 0.5))
            .section(Section::new([0.0, 0.0, 0.5], 0.5)),
    )
}

/// A flat rectangular wing of span `span` and chord `chord`, both halves, 8 chordwise × 12
/// spanwise panels per half, cosine spacing; reference at the quarter chord.
fn plate(title: &str, span: f64, chord: f64) -> Configuration {
    Configuration::new(
        title,
        Reference::new(span * chord, chord, span, [0.25 * chord, 0.0, 0.0]),
    )
    .surface(Surface::wing(title, 0.5 * span, chord, chord, 0.0, 0.0).lattice(8, 1.0, 12, 1.0))
}

/// The taildragger's wing: 10.7 m span, 1.6 m chord, 1.5° dihedral, 8 × 16 panels per half;
/// reference at the quarter chord.
fn aircraft_wing() -> Configuration {
    Configuration::new("wing", Reference::new(17.12, 1.6, 10.7, [0.4, 0.0, 0.0]))
        .surface(Surface::wing("wing", 5.35, 1.6, 1.6, 0.0, 1.5).lattice(8, 1.0, 16, 1.0))
}

/// The taildragger's tail: a 3 m × 0.9 m tailplane and a 1.1 m high fin of 0.9 m chord on it,
/// leading edges together; reference: the tailplane's area, chord and span, its quarter chord.
fn aircraft_tail() -> Configuration {
    Configuration::new("tail", Reference::new(2.7, 0.9, 3.0, [0.225, 0.0, 0.0]))
        .surface(Surface::wing("tailplane", 1.5, 0.9, 0.9, 0.0, 0.0).lattice(8, 1.0, 10, 1.0))
        .surface(Surface::fin("fin", 1.1, 0.9, 0.9, 0.0).lattice(8, 1.0, 8, 1.0))
}

/// The derivatives a `[[wing]]` of the file `model` called `wing` gives: its `derivatives`
/// table, each value a number or an expression `float(x)` / `-float(x)`.
fn file_derivatives(model: &str, wing: &str) -> Vec<(String, f64)> {
    let text = models::file_text(model).expect("a shipped model");
    let block = text
        .split("[[wing]]")
        .skip(1)
        .find(|b| b.contains(&format!("name = \"{wing}\"")))
        .unwrap_or_else(|| panic!("{model}: no wing `{wing}`"));
    let line = block
        .lines()
        .find_map(|l| l.strip_prefix("derivatives = {"))
        .unwrap_or_else(|| panic!("{model}, {wing}: no derivatives"));
    line.trim_end_matches('}')
        .split(',')
        .map(|entry| {
            let (k, v) = entry.split_once('=').expect("NAME = VALUE");
            let v = v.trim().trim_matches('"');
            let (sign, v) = match v.strip_prefix('-') {
                Some(rest) => (-1.0, rest),
                None => (1.0, v),
            };
            let v = v.trim_start_matches("float(").trim_end_matches(')');
            let x: f64 = v.parse().unwrap_or_else(|_| panic!("{model}: `{v}`"));
            (k.trim().to_string(), sign * x)
        })
        .collect()
}

fn lattice(config: Configuration) -> Derivatives {
    eom_aero::solve(&config, &SolverOptions::default())
        .expect("the lattice solves")
        .derivatives
}

/// A shipped model, one of its wings and the geometry the wing's derivatives come from.
type Case = (&'static str, &'static str, fn() -> Configuration);

#[test]
fn lattice_wings_in_the_shipped_files_are_the_lattices() {
    let cases: [Case; 5] = [
        ("shimmy_fin", "fin", seed_fin),
        ("ride_wings", "front wing", || {
            plate("front wing", 1.6, 0.35)
        }),
        ("ride_wings", "rear wing", || plate("rear wing", 1.3, 0.4)),
        ("aircraft_ground", "wing", aircraft_wing),
        ("aircraft_ground", "tail", aircraft_tail),
    ];
    for (model, wing, config) in cases {
        let d = lattice(config());
        let largest = d
            .coefficients
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let given = file_derivatives(model, wing);
        for name in Derivatives::names().iter().flatten() {
            let want = d.get(name).expect("a derivative");
            match given.iter().find(|(k, _)| k == name) {
                Some((_, got)) => assert!(
                    (got - want).abs() <= 1e-12 * largest,
                    "{model}, {wing}, {name}: the file has {got}, the lattice {want}"
                ),
                None => assert!(
                    want.abs() < 1e-12 * largest,
                    "{model}, {wing}: the file leaves out {name} = {want}"
                ),
            }
        }
    }
}
