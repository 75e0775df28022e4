//! The Goland wing as a family: Goland's cantilever wing in `n` beam segments carrying strips
//! (thin-airfoil sections with Theodorsen's apparent mass and R. T. Jones' lag states, or
//! quasi-steady), for the convergence study in the number of segments. The catalogue's
//! `goland_wing` is the shipped file `models/goland_wing.toml` (16 segments, Jones' states);
//! the references — the converged strip-theory flutter of the N-segment lumped model — are in
//! `docs/aero-references.md` and `tests/data/aero/`.

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, param};
use eom_model::file::{ParamRange, ParamSpec};
use eom_model::*;
use eom_sym::Expr;

/// The number of beam segments of the catalogue's `goland_wing`: within 0.4 % in flutter speed
/// and 1.2 % in frequency of the converged strip-theory reference (docs/unsteady-aerodynamics.md).
pub const GOLAND_SEGMENTS: usize = 16;

fn goland_params() -> Vec<ParamSpec> {
    [
        ("V", 100.0, "m/s", "airspeed"),
        ("rho", 1.2256, "kg/m^3", "air density (sea level)"),
        ("L", 6.096, "m", "semispan"),
        ("c", 1.8288, "m", "chord"),
        (
            "ea",
            0.33,
            "",
            "elastic axis, fraction of the chord from the leading edge",
        ),
        (
            "cg",
            0.43,
            "",
            "mass centre, fraction of the chord from the leading edge",
        ),
        ("m", 35.71, "kg/m", "mass per unit span"),
        (
            "I_theta",
            8.64,
            "kg m^2/m",
            "pitch inertia per unit span about the elastic axis",
        ),
        ("EI", 9.77e6, "N m^2", "bending stiffness"),
        ("GJ", 0.987e6, "N m^2", "torsional stiffness"),
    ]
    .into_iter()
    .map(|(name, default, unit, description)| ParamSpec {
        name: name.into(),
        value: default,
        default,
        unit: unit.into(),
        description: description.into(),
        range: ParamRange::Positive,
    })
    .collect()
}

/// The size argument as a number of segments (0: the default).
fn segments(n: usize) -> usize {
    if n == 0 { GOLAND_SEGMENTS } else { n }
}

/// The Goland wing with `n` segments and the given unsteady aerodynamics.
pub fn goland_wing(
    n: usize,
    unsteady: Unsteady,
    overrides: &[(&str, f64)],
) -> Result<Model<Expr>, CatalogueError> {
    let info = ModelInfo::family(
        "goland_wing",
        "",
        goland_params(),
        match unsteady {
            Unsteady::Jones => |md, n| goland_into(md, segments(n), Unsteady::Jones),
            Unsteady::QuasiSteady => |md, n| goland_into(md, segments(n), Unsteady::QuasiSteady),
            Unsteady::Auto => |md, n| goland_into(md, segments(n), Unsteady::Auto),
        },
    );
    info.build(overrides, n, "goland_wing")
}

/// The wing along +y from the clamped root, elastic axis on the y axis, flow from +x: node i
/// at y = iℓ carries the mass, static moment and pitch inertia of its tributary span ℓᵢ (ℓ, ℓ/2
/// at the tip), the rotary inertia mℓᵢ³/12 of its segment about the chordwise axis (so that
/// every bending slope carries inertia) and a strip of width ℓᵢ; Euler–Bernoulli beams (EI)
/// and torsion springs (GJ/ℓ) join neighbouring nodes. In-plane motion is held.
fn goland_into(md: &mut Model<Expr>, n: usize, unsteady: Unsteady) -> Result<(), CatalogueError> {
    let p = |name: &str| param(md, name);
    let (v, rho, span, chord, ea) = (p("V")?, p("rho")?, p("L")?, p("c")?, p("ea")?);
    let (cg, m, i_theta, ei, gj) = (p("cg")?, p("m")?, p("I_theta")?, p("EI")?, p("GJ")?);
    let half = Expr::from(0.5);
    let b = half * chord;
    // a: semichords aft of mid-chord; the mass centre x_cg aft of the elastic axis.
    let a = (ea - half) * chord / b;
    let xcg = (cg - ea) * chord;
    let l = span / Expr::from(n as f64);
    let node = |i: usize| format!("node{i}");
    let at = |i: usize| vec3(0, Expr::from(i as f64) * l, 0);
    for i in 1..=n {
        let li = if i == n { half * l } else { l };
        let y = Expr::from(i as f64) * l;
        let twelfth = Expr::from(1.0) / Expr::from(12.0);
        md.add(
            Body::new(&node(i))
                .at(vec3(-xcg, y, 0))
                .mass(m * li)
                .moments(vec3(
                    twelfth * m * li * li * li,
                    (i_theta - m * xcg * xcg) * li,
                    twelfth * m * li * li * li + (i_theta - m * xcg * xcg) * li,
                )),
        );
        md.add(
            RigidPoint::new(&format!("in plane {i}"))
                .between(&node(i), "ground")
                .at(vec3(-xcg, y, 0))
                .forces(2)
                .moments(1)
                .axis(z_axis()),
        );
        let prev = if i == 1 {
            "ground".to_string()
        } else {
            node(i - 1)
        };
        md.add(
            Beam::new(&format!("bending {i}"))
                .between(&node(i), &prev)
                .ends(at(i), at(i - 1))
                .stiffness(ei, ei)
                .perp(z_axis()),
        );
        md.add(
            Spring::new(&format!("torsion {i}"))
                .between(&node(i), &prev)
                .ends(at(i), at(i - 1))
                .twist()
                .stiffness(gj / l),
        );
        md.add(
            Strip::new(&format!("strip {i}"))
                .on(&node(i))
                .at(at(i))
                .semichord(b)
                .elastic_axis(a)
                .width(li)
                .density(rho)
                .airspeed(v)
                .unsteady(unsteady),
        );
    }
    Ok(())
}
