//! Aeroelastic models built from strips (thin-airfoil sections with Theodorsen's apparent mass
//! and R. T. Jones' lag states): the typical section and the Goland wing. Their references —
//! exact Theodorsen flutter by the k-method confirmed by a determinant root, and the same
//! models with Jones' states and quasi-steady — are in `docs/aero-references.md` and
//! `tests/data/aero/`.

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, ParamSpec, p, real};
use eom_model::*;
use eom_sym::Expr;

/// The number of beam segments of the catalogue's `goland_wing`: within 0.4 % in flutter speed
/// and 1.2 % in frequency of the converged strip-theory reference (docs/unsteady-aerodynamics.md).
pub const GOLAND_SEGMENTS: usize = 16;

fn typical_section_params() -> Vec<ParamSpec> {
    vec![
        p("b", 0.5, "m", "semichord"),
        p("w_theta", 10.0, "rad/s", "uncoupled pitch frequency"),
        p("V", 8.0, "m/s", "airspeed"),
        p("rho", 1.225, "kg/m^3", "air density"),
        p("mu", 20.0, "", "mass ratio m/(pi rho b^2) per unit span"),
        real("a", -0.2, "", "elastic axis, semichords aft of mid-chord"),
        real(
            "x_theta",
            0.1,
            "",
            "mass centre, semichords aft of the elastic axis",
        ),
        p(
            "r2",
            0.24,
            "",
            "squared radius of gyration about the elastic axis, per b^2",
        ),
        p("sigma", 0.4, "", "plunge-to-pitch frequency ratio"),
    ]
}

fn goland_params() -> Vec<ParamSpec> {
    vec![
        p("V", 100.0, "m/s", "airspeed"),
        p("rho", 1.2256, "kg/m^3", "air density (sea level)"),
        p("L", 6.096, "m", "semispan"),
        p("c", 1.8288, "m", "chord"),
        p(
            "ea",
            0.33,
            "",
            "elastic axis, fraction of the chord from the leading edge",
        ),
        p(
            "cg",
            0.43,
            "",
            "mass centre, fraction of the chord from the leading edge",
        ),
        p("m", 35.71, "kg/m", "mass per unit span"),
        p(
            "I_theta",
            8.64,
            "kg m^2/m",
            "pitch inertia per unit span about the elastic axis",
        ),
        p("EI", 9.77e6, "N m^2", "bending stiffness"),
        p("GJ", 0.987e6, "N m^2", "torsional stiffness"),
    ]
}

/// The catalogue entries of this module.
pub(crate) fn entries() -> Vec<ModelInfo> {
    vec![
        ModelInfo::new(
            "typical_section",
            "pitch-plunge typical section (Hodges & Pierce) on a strip with Jones' unsteady lift",
            typical_section_params(),
            |md, p, _| typical_section_into(md, p, Unsteady::Jones),
        ),
        ModelInfo::new(
            "goland_wing",
            "Goland's cantilever wing: 16 beam segments carrying strips with Jones' unsteady lift",
            goland_params(),
            |md, p, n| goland_into(md, p, segments(n), Unsteady::Jones),
        ),
    ]
}

/// The catalogue's size argument as a number of segments (0: the default).
fn segments(n: usize) -> usize {
    if n == 0 { GOLAND_SEGMENTS } else { n }
}

/// The typical section with the given unsteady aerodynamics, parameters at their defaults
/// (overridden by `overrides`).
pub fn typical_section(
    unsteady: Unsteady,
    overrides: &[(&str, f64)],
) -> Result<Model<Expr>, CatalogueError> {
    let info = ModelInfo::new(
        "typical_section",
        "",
        typical_section_params(),
        match unsteady {
            Unsteady::Jones => |md, p, _| typical_section_into(md, p, Unsteady::Jones),
            Unsteady::QuasiSteady => |md, p, _| typical_section_into(md, p, Unsteady::QuasiSteady),
            Unsteady::Auto => |md, p, _| typical_section_into(md, p, Unsteady::Auto),
        },
    );
    info.build(overrides, 0, "typical_section")
}

/// The Goland wing with `n` segments and the given unsteady aerodynamics.
pub fn goland_wing(
    n: usize,
    unsteady: Unsteady,
    overrides: &[(&str, f64)],
) -> Result<Model<Expr>, CatalogueError> {
    let info = ModelInfo::new(
        "goland_wing",
        "",
        goland_params(),
        match unsteady {
            Unsteady::Jones => |md, p, n| goland_into(md, p, segments(n), Unsteady::Jones),
            Unsteady::QuasiSteady => {
                |md, p, n| goland_into(md, p, segments(n), Unsteady::QuasiSteady)
            }
            Unsteady::Auto => |md, p, n| goland_into(md, p, segments(n), Unsteady::Auto),
        },
    );
    info.build(overrides, n, "goland_wing")
}

/// The section: a body pitching about its elastic axis at the origin and plunging along z,
/// springs k_h = m σ² ω_θ² and k_θ = I_θ ω_θ², a strip of width 1 m; flow from +x.
fn typical_section_into(
    md: &mut Model<Expr>,
    p: &[Expr],
    unsteady: Unsteady,
) -> Result<(), CatalogueError> {
    let [b, w, v, rho, mu, a, xt, r2, sigma] =
        [p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]];
    let pi = Expr::pi();
    let m = mu * pi * rho * b * b;
    let i_theta = m * b * b * r2;
    let xcg = xt * b;
    md.add(
        Body::new("section")
            .at(vec3(-xcg, 0, 0))
            .mass(m)
            .moments(vec3(1, i_theta - m * xcg * xcg, 1)),
    );
    md.add(
        RigidPoint::new("in plane")
            .between("section", "ground")
            .forces(2)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("pitch only")
            .between("section", "ground")
            .moments(2)
            .axis(y_axis()),
    );
    md.add(
        FlexPoint::new("plunge spring")
            .between("section", "ground")
            .forces(1)
            .axis(z_axis())
            .stiffness(m * sigma * sigma * w * w, 0),
    );
    md.add(
        FlexPoint::new("pitch spring")
            .between("section", "ground")
            .moments(1)
            .axis(y_axis())
            .stiffness(0, i_theta * w * w),
    );
    md.add(
        Strip::new("airfoil")
            .on("section")
            .semichord(b)
            .elastic_axis(a)
            .width(1)
            .density(rho)
            .airspeed(v)
            .unsteady(unsteady),
    );
    Ok(())
}

/// The wing along +y from the clamped root, elastic axis on the y axis, flow from +x: node i
/// at y = iℓ carries the mass, static moment and pitch inertia of its tributary span ℓᵢ (ℓ, ℓ/2
/// at the tip), the rotary inertia mℓᵢ³/12 of its segment about the chordwise axis (so that
/// every bending slope carries inertia) and a strip of width ℓᵢ; Euler–Bernoulli beams (EI)
/// and torsion springs (GJ/ℓ) join neighbouring nodes. In-plane motion is held.
fn goland_into(
    md: &mut Model<Expr>,
    p: &[Expr],
    n: usize,
    unsteady: Unsteady,
) -> Result<(), CatalogueError> {
    let [v, rho, span, chord, ea, cg, m, i_theta, ei, gj] =
        [p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]];
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
