//! Articulated vehicles in the yaw plane.
//!
//! `truck_trailer`: the linear single-track ("bicycle") model of a truck towing a one-axle
//! trailer, as in Minaker, *Fundamentals of Vehicle Dynamics and Modelling* (Wiley, 2019),
//! whose truck-and-trailer example gives the parameter values used here as defaults. Each
//! axle's tyres are one lateral damper of coefficient `c/u` at the axle: the lateral force
//! `−c·α` of a linear tyre with slip angle `α = v_y/u`. The hitch is a point joint that lets
//! the trailer yaw relative to the truck; the road holds heave, roll and pitch; the truck's
//! forward speed is held. The steer input acts as the front tyres' force `c_f·δ`.
//!
//! The lateral position and heading of the pair are ignorable: two structural zero
//! eigenvalues (a Jordan pair: the heading integrates into the lateral position), seen by no
//! output here. The steady-state gains are finite.

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, p};
use eom_model::*;
use eom_sym::Expr;

/// The catalogue entries of this module.
pub(crate) fn entries() -> Vec<ModelInfo> {
    vec![ModelInfo::new(
        "truck_trailer",
        "truck with a one-axle trailer, linear single-track yaw-plane model (Minaker 2019)",
        vec![
            p("u", 10.0, "m/s", "forward speed"),
            p("m", 1730.3, "kg", "truck mass"),
            p(
                "Iz",
                3508.0,
                "kg m^2",
                "truck yaw inertia about its mass centre",
            ),
            p("a", 1.289, "m", "truck mass centre to front axle"),
            p("b", 1.596, "m", "truck mass centre to rear axle"),
            p("d", 2.7, "m", "truck mass centre to the hitch"),
            p("cf", 80000.0, "N/rad", "front cornering stiffness (axle)"),
            p("cr", 80000.0, "N/rad", "rear cornering stiffness (axle)"),
            p("mt", 2000.0, "kg", "trailer mass"),
            p(
                "It",
                3000.0,
                "kg m^2",
                "trailer yaw inertia about its mass centre",
            ),
            p(
                "et",
                2.7,
                "m",
                "hitch to trailer mass centre (e in the source)",
            ),
            p("h", 0.3, "m", "trailer mass centre to trailer axle"),
            p("ct", 80000.0, "N/rad", "trailer cornering stiffness (axle)"),
        ],
        truck_trailer,
    )]
}

fn truck_trailer(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [u, m, iz, a, b, d, cf, cr, mt, it, e, h, ct] = [
        p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11], p[12],
    ];
    let trailer_x = -(d + e);
    md.add(
        Body::new("truck")
            .mass(m)
            .moments(vec3(0, 0, iz))
            .velocity(vec3(u, 0, 0)),
    );
    md.add(
        Body::new("trailer")
            .mass(mt)
            .at(vec3(trailer_x, 0, 0))
            .moments(vec3(0, 0, it))
            .velocity(vec3(u, 0, 0)),
    );
    for (name, body, x, c) in [
        ("front tyre", "truck", a, cf),
        ("rear tyre", "truck", -b, cr),
        ("trailer tyre", "trailer", trailer_x - h, ct),
    ] {
        md.add(
            FlexPoint::new(name)
                .between(body, "ground")
                .at(vec3(x, 0, 0))
                .forces(1)
                .axis(y_axis())
                .damping(c / u, 0),
        );
    }
    md.add(
        RigidPoint::new("hitch")
            .between("truck", "trailer")
            .at(vec3(-d, 0, 0))
            .forces(3)
            .moments(2)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("road")
            .between("truck", "ground")
            .forces(1)
            .moments(2)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("speed")
            .between("truck", "ground")
            .forces(1)
            .axis(x_axis()),
    );
    md.add(
        Actuator::new("delta_f")
            .between("truck", "ground")
            .ends(vec3(a, 0, 0), vec3(a, -1, 0))
            .gain(cf)
            .units("rad"),
    );
    md.add(
        Sensor::new("r")
            .between("truck", "ground")
            .ends(zero3(), vec3(0, 0, -1))
            .twist()
            .velocity()
            .units("rad/s"),
    );
    md.add(
        Sensor::new("a_y")
            .between("truck", "ground")
            .ends(zero3(), vec3(0, -1, 0))
            .acceleration()
            .local()
            .units("m/s^2"),
    );
    md.add(
        Sensor::new("gamma")
            .between("trailer", "truck")
            .ends(vec3(-d, 0, 0), vec3(-d, 0, -1))
            .twist()
            .units("rad"),
    );
    Ok(())
}
