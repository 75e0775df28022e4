//! Models with wings: the seed examples of the wing item (a spring–mass–damper under a
//! horizontal wing, the shimmy with a vertical fin, by given derivatives and by the vortex
//! lattice).
//!
//! The fin of the shimmy is the seed paper's (Minaker et al.): a flat plate 1 m high with a
//! 0.5 m chord, standing vertically at the spring point with its quarter chord there. Its four
//! derivatives are those that give the paper's damping entries at ρ = 1.225 kg/m³ and
//! V = 10 m/s: L22 = 7.59895 N·s/m, L26 = −2.05293 N·s, L62 = 0.153319 N·s,
//! L66 = 0.224167 N·m·s (with `L = −(ρVS/2)·M`, so `CYv = −L22/(ρVS/2)`,
//! `CYr = −L26/(ρVS/2 · b/2)`, `Cnv = −L62/(ρVS/2 · b)`, `Cnr = −L66/(ρVS/2 · b²/2)`).
//! They are in AVL's axes (x forward, y right, z down), the wing item's default orientation:
//! forward +x, down −z, a vertical plate spanning the model's z. Its airspeed is the
//! chassis's speed u (the wing item's default).

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, ParamSpec};
use crate::catalogue::{p, real};
use eom_aero::{Configuration, Derivatives, Reference, Section, SolverOptions, Surface};
use eom_model::*;
use eom_sym::Expr;
use std::sync::OnceLock;

/// The seed fin's CYv (per unit v/V).
pub const FIN_CYV: f64 = -2.4812897959183673;
/// The seed fin's CYr (per unit r·b/2V).
pub const FIN_CYR: f64 = 1.3406889795918367;
/// The seed fin's Cnv (per unit v/V).
pub const FIN_CNV: f64 = -0.05006334693877551;
/// The seed fin's Cnr (per unit r·b/2V).
pub const FIN_CNR: f64 = -0.14639477551020408;

/// The shimmy's parameters (those of the `shimmy` entry) and the air density.
fn shimmy_params() -> Vec<ParamSpec> {
    vec![
        p("m", 5.0, "kg", "mass"),
        p("I", 1.05, "kg m^2", "yaw inertia about the mass centre"),
        p("k", 1.5, "N/m", "lateral spring stiffness"),
        p(
            "l",
            1.0,
            "m",
            "distance from the tyre to the spring (a + b)",
        ),
        real(
            "x",
            0.5,
            "",
            "mass-centre position a/l behind the spring (a = x l, b = (1 - x) l)",
        ),
        real("u", 10.0, "m/s", "forward speed (the fin's airspeed)"),
        p("rho", 1.225, "kg/m^3", "air density"),
    ]
}

/// The catalogue entries of this module.
pub(crate) fn entries() -> Vec<ModelInfo> {
    vec![
        ModelInfo::new(
            "smd_wing",
            "spring-mass-damper under a horizontal wing in an air stream (seed paper eq. 13)",
            vec![
                p("m", 1.0, "kg", "mass"),
                p("k", 50.0, "N/m", "stiffness"),
                p("c", 0.2, "N s/m", "damping"),
                p("rho", 1.225, "kg/m^3", "air density"),
                p("V", 10.0, "m/s", "airspeed"),
                p("S", 0.5, "m^2", "wing area (span 1 m, chord S/1 m)"),
                real("CLa", FIN_CYV.abs(), "1/rad", "lift-curve slope"),
                real("CD", 0.0, "", "drag coefficient"),
            ],
            smd_wing,
        ),
        ModelInfo::new(
            "shimmy_wing",
            "shimmy with the seed paper's vertical fin at the spring point (given derivatives)",
            shimmy_params(),
            shimmy_wing,
        ),
        ModelInfo::new(
            "shimmy_fin",
            "shimmy with the same fin, derivatives from eom-aero's vortex lattice (8x16 cosine)",
            shimmy_params(),
            shimmy_fin,
        ),
    ]
}

/// The spring–mass–damper of the catalogue under a horizontal wing: `CZw = −(CLa + CD)`, so
/// `m z̈ + (c + ρVS(CLa + CD)/2) ż + k z = f`.
fn smd_wing(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    crate::catalogue::smd(md, &p[..3], 0)?;
    let [rho, v, s, cla, cd] = [p[3], p[4], p[5], p[6], p[7]];
    md.add(
        Wing::new("wing")
            .on("block")
            .at(vec3(0, 0, 1))
            .area(s)
            .span(1)
            .chord(s)
            .density(rho)
            .airspeed(v)
            .derivative("CZw", -(cla + cd)),
    );
    Ok(())
}

/// The shimmy of the catalogue; returns the spring's distance `b` ahead of the mass centre.
fn shimmy_body(md: &mut Model<Expr>, p: &[Expr]) -> Result<Expr, CatalogueError> {
    crate::catalogue::shimmy(md, &p[..6], 0)?;
    let (l, x) = (p[3], p[4]);
    Ok(l - x * l)
}

/// The fin at the spring point, with the given numbers for its derivatives.
fn shimmy_wing(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let b = shimmy_body(md, p)?;
    let f = Expr::float;
    md.add(
        Wing::new("fin")
            .on("chassis")
            .at(vec3(b, 0, 0))
            .area(0.5)
            .chord(0.5)
            .span(1)
            .density(p[6])
            .derivative("CYv", f(FIN_CYV)?)
            .derivative("CYr", f(FIN_CYR)?)
            .derivative("Cnv", f(FIN_CNV)?)
            .derivative("Cnr", f(FIN_CNR)?),
    );
    Ok(())
}

/// The seed fin in AVL's geometry axes (x aft, y right, z up): a flat plate from z = −0.5 to
/// 0.5 with a 0.5 m chord, leading edge at x = 0, moment reference at the quarter chord;
/// 8 chordwise × 16 spanwise panels, cosine spacing both ways.
pub fn seed_fin() -> Configuration {
    Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0])).surface(
        Surface::new("fin")
            .lattice(8, 1.0, 16, 1.0)
            .section(Section::new([0.0, 0.0, -0.5], 0.5))
            .section(Section::new([0.0, 0.0, 0.5], 0.5)),
    )
}

/// The derivatives of a configuration by the vortex lattice at α = 0, computed once per
/// process (the geometry is fixed). Entries below 1e-12 of the largest are the rounding
/// residue of couplings that the configuration's symmetry makes zero, and are set to zero
/// (so that they do not clutter the symbolic model).
pub(crate) fn lattice_derivatives(
    cell: &'static OnceLock<Result<Derivatives, String>>,
    config: fn() -> Configuration,
) -> Result<Derivatives, CatalogueError> {
    cell.get_or_init(|| {
        eom_aero::solve(&config(), &SolverOptions::default())
            .map(|s| {
                let mut d = s.derivatives;
                let largest = d
                    .coefficients
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, x| m.max(x.abs()));
                for x in d.coefficients.iter_mut().flatten() {
                    if x.abs() < 1e-12 * largest {
                        *x = 0.0;
                    }
                }
                d
            })
            .map_err(|e| e.to_string())
    })
    .clone()
    .map_err(CatalogueError::Aero)
}

/// The fin at the spring point, its derivatives from the vortex lattice.
fn shimmy_fin(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    static FIN: OnceLock<Result<Derivatives, String>> = OnceLock::new();
    let d = lattice_derivatives(&FIN, seed_fin)?;
    let b = shimmy_body(md, p)?;
    md.add(
        Wing::from_derivatives("fin", &d)
            .on("chassis")
            .at(vec3(b, 0, 0))
            .density(p[6]),
    );
    Ok(())
}
