//! Rigid aircraft in free flight from stability derivatives: the Navion of R. C. Nelson,
//! *Flight Stability and Automatic Control*, 2nd ed. (1998), App. B, at sea level in
//! consistent US units. The reference (the rigid-body flight equations written out by hand,
//! and Nelson's approximate forms) is `tests/data/aero/navion.py`; docs/aero-references.md §4.

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, ParamSpec, p, real};
use eom_model::*;
use eom_sym::Expr;

/// The derivatives of the Navion as parameters: AVL's body-axis names and normalisation, and
/// `Cmwd` = Cm_α̇ per α̇c̄/2V.
const DERIVATIVES: [(&str, f64); 15] = [
    ("CXu", -0.10),
    ("CXw", 0.08),
    ("CZu", -0.82),
    ("CZw", -4.49),
    ("CZq", -3.8),
    ("Cmw", -0.683),
    ("Cmq", -9.96),
    ("Cmwd", -4.36),
    ("CYv", -0.564),
    ("Clv", -0.074),
    ("Cnv", 0.0701),
    ("Clp", -0.410),
    ("Cnp", -0.0575),
    ("Clr", 0.107),
    ("Cnr", -0.125),
];

fn navion_params() -> Vec<ParamSpec> {
    let mut v = vec![
        p("V", 176.0, "ft/s", "airspeed"),
        p("rho", 0.002378, "slug/ft^3", "air density (sea level)"),
        p("g", 32.2, "ft/s^2", "gravity"),
        p("W", 2750.0, "lbf", "weight"),
        p("S", 184.0, "ft^2", "wing area"),
        p("b", 33.4, "ft", "wing span"),
        p("c", 5.7, "ft", "mean aerodynamic chord"),
        p("Ix", 1048.0, "slug ft^2", "roll inertia"),
        p("Iy", 3000.0, "slug ft^2", "pitch inertia"),
        p("Iz", 3530.0, "slug ft^2", "yaw inertia"),
    ];
    v.extend(
        DERIVATIVES
            .iter()
            .map(|(n, x)| real(n, *x, "", "stability derivative (AVL body axes)")),
    );
    v
}

/// The catalogue entries of this module.
pub(crate) fn entries() -> Vec<ModelInfo> {
    vec![ModelInfo::new(
        "navion",
        "the Navion in level free flight (Nelson, App. B): stability derivatives, gravity",
        navion_params(),
        navion,
    )]
}

/// The aircraft flies along +x at V (model axes x forward, y left, z up); its weight is a dead
/// load, the trim lift equal to it a follower load (fixed in the aircraft's axes), thrust
/// equal to drag and constant (neither appears); the wing at the mass centre carries the
/// derivatives, Cm_α̇ as an aerodynamic mass.
fn navion(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [v, rho, g, w, s, b, c, ix, iy, iz] =
        [p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]];
    md.add(
        Body::new("aircraft")
            .mass(w / g)
            .moments(vec3(ix, iy, iz))
            .velocity(vec3(v, 0, 0)),
    );
    md.add(Load::new("weight", "aircraft").force(vec3(0, 0, -w)));
    md.add(
        Load::new("trim lift", "aircraft")
            .force(vec3(0, 0, w))
            .frame("aircraft"),
    );
    let mut wing = Wing::new("wing")
        .on("aircraft")
        .area(s)
        .chord(c)
        .span(b)
        .density(rho);
    for (k, (n, _)) in DERIVATIVES.iter().enumerate() {
        wing = wing.derivative(n, p[10 + k]);
    }
    md.add(wing);
    Ok(())
}
