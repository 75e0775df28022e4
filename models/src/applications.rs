//! Two applications of the wing item, with illustrative parameters (of the order of real
//! vehicles, not taken from any one of them):
//!
//! * `ride_wings`: a car's bounce–pitch ride model (one body on a front and a rear
//!   suspension, road displacements as inputs) with a front and a rear wing. The car is
//!   modelled in the frame that moves with it (at rest, on a road and in an air stream moving
//!   past it at u): its suspension dampers then act on the velocities relative to the road,
//!   and its wings, given the airspeed u, on those relative to the air, including the angle
//!   of attack of the pitch attitude. At speed the wings add heave and pitch damping and,
//!   through that angle of attack, pitch stiffness.
//! * `aircraft_ground`: a light taildragger rolling on its landing gear at constant speed
//!   (main wheels ahead of the mass centre that cannot slip sideways, a castering tail wheel,
//!   vertical gear springs, its weight), with a wing and a tail (tailplane and fin). The main
//!   wheels ahead of the mass centre make the heading unstable on the ground — the ground
//!   loop: a real eigenvalue that grows in proportion to the speed (the tyres' m·xm·u against
//!   the yaw inertia). The fin's yaw damping grows in proportion to the speed too, so it slows
//!   the ground loop by the same fraction at every speed (about a sixth with these values)
//!   but cannot cure it. The gear is of the spring-steel kind, without dampers: heave, pitch
//!   and roll are damped by the wing and tail alone, and the reduced-frequency check marks
//!   those modes as too fast for quasi-steady aerodynamics at taxiing speeds. (The aircraft
//!   moves at its nominal speed, which the tyres need; a damper between it and the ground
//!   would act on its body-axis velocity, which includes the sliding term u·θ of a pitched
//!   body: right for a sliding contact, not for a strut.)
//!
//! The wings' derivatives come from eom-aero's vortex lattice (flat plates, α = 0), computed
//! once per process. Each wing is attached at the model point of its configuration's
//! moment reference (AVL's geometry axes x aft, y right, z up map to the model's −x, −y, z).

use crate::CatalogueError;
use crate::catalogue::ModelInfo;
use crate::catalogue::p;
use crate::wings::lattice_derivatives;
use eom_aero::{Configuration, Derivatives, Reference, Surface};
use eom_model::*;
use eom_sym::Expr;
use std::sync::OnceLock;

/// The catalogue entries of this module.
pub(crate) fn entries() -> Vec<ModelInfo> {
    vec![
        ModelInfo::new(
            "ride_wings",
            "car bounce-pitch ride model with a front and a rear wing (illustrative values)",
            vec![
                p("m", 1200.0, "kg", "mass"),
                p(
                    "Iy",
                    1800.0,
                    "kg m^2",
                    "pitch inertia about the mass centre",
                ),
                p("a", 1.2, "m", "mass centre to front axle"),
                p("b", 1.4, "m", "mass centre to rear axle"),
                p("kf", 35000.0, "N/m", "front suspension stiffness (axle)"),
                p("kr", 38000.0, "N/m", "rear suspension stiffness (axle)"),
                p("cf", 3000.0, "N s/m", "front suspension damping (axle)"),
                p("cr", 3000.0, "N s/m", "rear suspension damping (axle)"),
                p("u", 40.0, "m/s", "forward speed"),
                p("rho", 1.225, "kg/m^3", "air density"),
            ],
            ride_wings,
        ),
        ModelInfo::new(
            "aircraft_ground",
            "light taildragger rolling on its landing gear, with a wing and a tail (illustrative values)",
            vec![
                p("m", 550.0, "kg", "mass"),
                p(
                    "Ixx",
                    1100.0,
                    "kg m^2",
                    "roll inertia about the mass centre",
                ),
                p(
                    "Iyy",
                    1000.0,
                    "kg m^2",
                    "pitch inertia about the mass centre",
                ),
                p("Izz", 1900.0, "kg m^2", "yaw inertia about the mass centre"),
                p("xm", 0.45, "m", "main wheels ahead of the mass centre"),
                p("km", 40000.0, "N/m", "main gear stiffness (each wheel)"),
                p("kt", 15000.0, "N/m", "tail wheel stiffness"),
                p("u", 15.0, "m/s", "ground speed (towed)"),
                p("rho", 1.225, "kg/m^3", "air density"),
                p("g", 9.81, "m/s^2", "gravity"),
            ],
            aircraft_ground,
        ),
    ]
}

/// A flat rectangular wing of span `span` and chord `chord`, both halves (YDUPLICATE), 8
/// chordwise × 12 spanwise panels per half, cosine spacing; reference at the quarter chord.
fn plate(title: &str, span: f64, chord: f64) -> Configuration {
    Configuration::new(
        title,
        Reference::new(span * chord, chord, span, [0.25 * chord, 0.0, 0.0]),
    )
    .surface(Surface::wing(title, 0.5 * span, chord, chord, 0.0, 0.0).lattice(8, 1.0, 12, 1.0))
}

fn front_wing() -> Configuration {
    plate("front wing", 1.6, 0.35)
}

fn rear_wing() -> Configuration {
    plate("rear wing", 1.3, 0.4)
}

/// A horizontal wing on `body` at `at`, its derivatives `d`, airspeed from the body.
fn wing_item(n: &str, body: &str, at: Vec3<Expr>, d: &Derivatives, rho: Expr) -> Wing<Expr> {
    Wing::from_derivatives(n, d).on(body).at(at).density(rho)
}

/// The same, in an air stream of speed `u` (the body at rest).
fn wing_in_stream(n: &str, at: Vec3<Expr>, d: &Derivatives, rho: Expr, u: Expr) -> Wing<Expr> {
    wing_item(n, "car", at, d, rho).airspeed(u)
}

fn ride_wings(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    static FRONT: OnceLock<Result<Derivatives, String>> = OnceLock::new();
    static REAR: OnceLock<Result<Derivatives, String>> = OnceLock::new();
    let [m, iy, a, b, kf, kr, cf, cr, u, rho] =
        [p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]];
    let h = Expr::float(0.5)?;
    md.add(Body::new("car").mass(m).at(vec3(0, 0, h)).moments(vec3(
        Expr::zero(),
        iy,
        Expr::zero(),
    )));
    // Bounce and pitch only: no x, y, roll or yaw.
    md.add(
        RigidPoint::new("longitudinal and lateral")
            .between("car", "ground")
            .at(vec3(0, 0, h))
            .forces(2)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("no roll or yaw")
            .between("car", "ground")
            .at(vec3(0, 0, h))
            .moments(2)
            .axis(y_axis()),
    );
    for (n, x, k, c) in [("front", a, kf, cf), ("rear", -b, kr, cr)] {
        md.add(
            FlexPoint::new(&format!("{n} suspension"))
                .between("car", "ground")
                .at(vec3(x, 0, 0.3))
                .forces(1)
                .axis(z_axis())
                .stiffness(k, 0)
                .damping(c, 0),
        );
        md.add(
            Actuator::new(&format!("{n} road"))
                .between("car", "ground")
                .ends(vec3(x, 0, 0.3), vec3(x, 0, 0))
                .gain(k)
                .rate_gain(c)
                .units("m"),
        );
    }
    let front = lattice_derivatives(&FRONT, front_wing)?;
    let rear = lattice_derivatives(&REAR, rear_wing)?;
    let ahead = Expr::float(0.7)?;
    let behind = Expr::float(0.4)?;
    md.add(wing_in_stream(
        "front wing",
        vec3(a + ahead, 0, 0.15),
        &front,
        rho,
        u,
    ));
    md.add(wing_in_stream(
        "rear wing",
        vec3(-(b + behind), 0, 1.1),
        &rear,
        rho,
        u,
    ));
    md.add(
        Sensor::new("bounce")
            .between("car", "ground")
            .ends(vec3(0, 0, h), vec3(0, 0, 0)),
    );
    md.add(
        Sensor::new("pitch")
            .between("car", "ground")
            .ends(vec3(0, 0, h), vec3(0, 1, h))
            .twist()
            .units("rad"),
    );
    Ok(())
}

/// The wing: 10.7 m span, 1.6 m chord, 1.5° dihedral, 8 × 16 panels per half; reference at
/// the quarter chord.
fn aircraft_wing() -> Configuration {
    Configuration::new("wing", Reference::new(17.12, 1.6, 10.7, [0.4, 0.0, 0.0]))
        .surface(Surface::wing("wing", 5.35, 1.6, 1.6, 0.0, 1.5).lattice(8, 1.0, 16, 1.0))
}

/// The tail: a 3 m × 0.9 m tailplane and a 1.1 m high fin of 0.9 m chord on it, leading
/// edges together; reference: the tailplane's area, chord and span, its quarter chord.
fn aircraft_tail() -> Configuration {
    Configuration::new("tail", Reference::new(2.7, 0.9, 3.0, [0.225, 0.0, 0.0]))
        .surface(Surface::wing("tailplane", 1.5, 0.9, 0.9, 0.0, 0.0).lattice(8, 1.0, 10, 1.0))
        .surface(Surface::fin("fin", 1.1, 0.9, 0.9, 0.0).lattice(8, 1.0, 8, 1.0))
}

fn aircraft_ground(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    static WING: OnceLock<Result<Derivatives, String>> = OnceLock::new();
    static TAIL: OnceLock<Result<Derivatives, String>> = OnceLock::new();
    let [m, ixx, iyy, izz, xm, km, kt, u, rho, g] =
        [p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]];
    // Mass centre 1 m above the ground; tail wheel 4.6 m behind it; track 1.8 m.
    let h = Expr::one();
    let tail_x = -Expr::float(4.6)?;
    let half_track = Expr::float(0.9)?;
    let body = Body::new("aircraft")
        .mass(m)
        .at(vec3(0, 0, h))
        .moments(vec3(ixx, iyy, izz))
        .velocity(vec3(u, 0, 0));
    md.add(Load::weight(&body, g));
    md.add(body);
    for (n, y) in [("left main", half_track), ("right main", -half_track)] {
        md.add(
            FlexPoint::new(&format!("{n} gear"))
                .between("aircraft", "ground")
                .at(vec3(xm, y, 0))
                .forces(1)
                .axis(z_axis())
                .stiffness(km, 0),
        );
    }
    md.add(
        FlexPoint::new("tail gear")
            .between("aircraft", "ground")
            .at(vec3(tail_x, 0, 0))
            .forces(1)
            .axis(z_axis())
            .stiffness(kt, 0),
    );
    // The main tyres cannot slip sideways (one row for both: their lateral velocities are
    // equal); the tail wheel casters freely.
    md.add(
        NhPoint::new("main tyres")
            .between("aircraft", "ground")
            .at(vec3(xm, 0, 0))
            .forces(1)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("tow")
            .between("aircraft", "ground")
            .at(vec3(0, 0, h))
            .forces(1)
            .axis(x_axis()),
    );
    let wing = lattice_derivatives(&WING, aircraft_wing)?;
    let tail = lattice_derivatives(&TAIL, aircraft_tail)?;
    md.add(wing_item("wing", "aircraft", vec3(0.1, 0, 1.9), &wing, rho));
    md.add(wing_item(
        "tail",
        "aircraft",
        vec3(-4.2, 0, 1.2),
        &tail,
        rho,
    ));
    md.add(
        Actuator::new("side force")
            .between("aircraft", "ground")
            .ends(vec3(0, 0, h), vec3(0, -1, h)),
    );
    md.add(
        Sensor::new("heading")
            .between("aircraft", "ground")
            .ends(vec3(0, 0, h), vec3(0, 0, 2))
            .twist()
            .units("rad"),
    );
    md.add(
        Sensor::new("roll")
            .between("aircraft", "ground")
            .ends(vec3(0, 0, h), vec3(1, 0, h))
            .twist()
            .units("rad"),
    );
    Ok(())
}
