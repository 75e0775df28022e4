//! The Whipple bicycle of the benchmark by Meijaard, Papadopoulos, Ruina & Schwab (2007),
//! "Linearized dynamics equations for the balance and steer of a bicycle: a benchmark and
//! review", Proc. R. Soc. A 463, 1955–1982, with the benchmark's own parameter names and its
//! axes: x forward, y to the right, z down (so the weights point along +z).
//!
//! Four bodies — rear frame B, front fork and handlebar H, wheels R and F — joined by the
//! steer hinge and two axle hinges; each wheel touches the road at a point that is fixed
//! vertically and longitudinally (holonomic) and cannot slip sideways (nonholonomic); the rear
//! frame's forward motion is prescribed. Inputs, as the benchmark's forcing vector
//! f = [T_phi, T_delta]: the lean torque on the rear frame about the roll axis (reacted by the
//! ground) and the steer torque; outputs: steer angle and roll angle. The benchmark's Table 1
//! values are the defaults.

use crate::CatalogueError;
use crate::catalogue::ParamSpec;
use crate::catalogue::{p, real};
use eom_model::*;
use eom_sym::Expr;

/// The 27 benchmark parameters (Table 1) with the forward speed `v`.
pub(crate) fn params() -> Vec<ParamSpec> {
    vec![
        p("w", 1.02, "m", "wheel base"),
        real("c", 0.08, "m", "trail"),
        real(
            "lambda",
            std::f64::consts::PI / 10.0,
            "rad",
            "steer axis tilt (from vertical)",
        ),
        p("g", 9.81, "m/s^2", "gravity"),
        real("v", 5.0, "m/s", "forward speed"),
        p("rR", 0.3, "m", "rear wheel radius"),
        p("mR", 2.0, "kg", "rear wheel mass"),
        p("IRxx", 0.0603, "kg m^2", "rear wheel diametral inertia"),
        p("IRyy", 0.12, "kg m^2", "rear wheel polar inertia"),
        real("xB", 0.3, "m", "rear frame mass centre x"),
        real("zB", -0.9, "m", "rear frame mass centre z (down)"),
        p("mB", 85.0, "kg", "rear frame mass"),
        p("IBxx", 9.2, "kg m^2", "rear frame inertia xx"),
        p("IByy", 11.0, "kg m^2", "rear frame inertia yy"),
        p("IBzz", 2.8, "kg m^2", "rear frame inertia zz"),
        real(
            "IBxz",
            2.4,
            "kg m^2",
            "rear frame inertia xz (tensor entry)",
        ),
        real("xH", 0.9, "m", "front frame mass centre x"),
        real("zH", -0.7, "m", "front frame mass centre z (down)"),
        p("mH", 4.0, "kg", "front frame mass"),
        p("IHxx", 0.05892, "kg m^2", "front frame inertia xx"),
        p("IHyy", 0.06, "kg m^2", "front frame inertia yy"),
        p("IHzz", 0.00708, "kg m^2", "front frame inertia zz"),
        real(
            "IHxz",
            -0.00756,
            "kg m^2",
            "front frame inertia xz (tensor entry)",
        ),
        p("rF", 0.35, "m", "front wheel radius"),
        p("mF", 3.0, "kg", "front wheel mass"),
        p("IFxx", 0.1405, "kg m^2", "front wheel diametral inertia"),
        p("IFyy", 0.28, "kg m^2", "front wheel polar inertia"),
    ]
}

pub(crate) fn build(md: &mut Model<Expr>, ps: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let v = |name: &str| md.scope.get(name).expect("declared");
    let _ = ps;
    let (w, c, lambda, g, speed) = (v("w"), v("c"), v("lambda"), v("g"), v("v"));
    let (rr, mr, irxx, iryy) = (v("rR"), v("mR"), v("IRxx"), v("IRyy"));
    let (xb, zb, mb) = (v("xB"), v("zB"), v("mB"));
    let (ibxx, ibyy, ibzz, ibxz) = (v("IBxx"), v("IByy"), v("IBzz"), v("IBxz"));
    let (xh, zh, mh) = (v("xH"), v("zH"), v("mH"));
    let (ihxx, ihyy, ihzz, ihxz) = (v("IHxx"), v("IHyy"), v("IHzz"), v("IHxz"));
    let (rf, mf, ifxx, ifyy) = (v("rF"), v("mF"), v("IFxx"), v("IFyy"));

    let vel = vec3(speed, 0, 0);
    // Products of inertia are positive integrals entering the tensor with a minus sign, so the
    // tensor entry I_xz is minus the `zx` product.
    let frame = Body::new("rear frame")
        .mass(mb)
        .at(vec3(xb, 0, zb))
        .moments(vec3(ibxx, ibyy, ibzz))
        .products(vec3(0, 0, -ibxz))
        .velocity(vel);
    let fork = Body::new("front frame")
        .mass(mh)
        .at(vec3(xh, 0, zh))
        .moments(vec3(ihxx, ihyy, ihzz))
        .products(vec3(0, 0, -ihxz))
        .velocity(vel);
    // Rolling forward along +x with z down: ω_y = −v/r.
    let rear = Body::new("rear wheel")
        .mass(mr)
        .at(vec3(0, 0, -rr))
        .moments(vec3(irxx, iryy, irxx))
        .velocity(vel)
        .angular_velocity(vec3(0, -speed / rr, 0));
    let front = Body::new("front wheel")
        .mass(mf)
        .at(vec3(w, 0, -rf))
        .moments(vec3(ifxx, ifyy, ifxx))
        .velocity(vel)
        .angular_velocity(vec3(0, -speed / rf, 0));
    // z down: a weight m·g along +z is `weight` with a negative gravity argument.
    for b in [&frame, &fork, &rear, &front] {
        md.add(Load::weight(b, -g));
    }
    md.add(frame).add(fork).add(rear).add(front);

    // The steer axis meets the road at x = w + c and leans back by λ: direction
    // (sin λ, 0, cos λ) pointing down and forward. The hinge is placed where it meets the road.
    let axis = vec3(lambda.sin(), 0, lambda.cos());
    let head = vec3(w + c, 0, 0);
    md.add(
        RigidPoint::new("steer hinge")
            .between("rear frame", "front frame")
            .at(head)
            .forces(3)
            .moments(2)
            .axis(axis),
    );
    md.add(
        RigidPoint::new("rear axle")
            .between("rear frame", "rear wheel")
            .at(vec3(0, 0, -rr))
            .forces(3)
            .moments(2)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("front axle")
            .between("front frame", "front wheel")
            .at(vec3(w, 0, -rf))
            .forces(3)
            .moments(2)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("rear contact")
            .between("rear wheel", "ground")
            .forces(2)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("front contact")
            .between("front wheel", "ground")
            .at(vec3(w, 0, 0))
            .forces(2)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("speed")
            .between("rear frame", "ground")
            .at(vec3(xb, 0, zb))
            .forces(1)
            .axis(x_axis()),
    );
    md.add(
        NhPoint::new("rear tyre")
            .between("rear wheel", "ground")
            .forces(1)
            .axis(y_axis()),
    );
    md.add(
        NhPoint::new("front tyre")
            .between("front wheel", "ground")
            .at(vec3(w, 0, 0))
            .forces(1)
            .axis(y_axis()),
    );

    // The lean torque: a couple on the rear frame about the roll axis x, reacted by the ground
    // (collocated with the roll sensor, so a positive T_phi does positive work on phi). Steer
    // torque on the front frame about the steer axis (reaction on the rear frame), and the
    // steer and roll angles (roll positive to the right, as in the benchmark).
    md.add(
        Actuator::new("T_phi")
            .between("rear frame", "ground")
            .ends(vec3(xb, 0, zb), vec3(xb - 1, 0, zb))
            .twist()
            .units("N m"),
    );
    let head_up = [
        head[0] - axis[0] * Expr::rational(1, 4)?,
        Expr::zero(),
        -(axis[2] * Expr::rational(1, 4)?),
    ];
    md.add(
        Actuator::new("T_delta")
            .between("rear frame", "front frame")
            .ends(head_up, head)
            .twist()
            .units("N m"),
    );
    md.add(
        Sensor::new("delta")
            .between("rear frame", "front frame")
            .ends(head_up, head)
            .twist()
            .units("rad"),
    );
    md.add(
        Sensor::new("phi")
            .between("rear frame", "ground")
            .ends(vec3(xb, 0, zb), vec3(xb - 1, 0, zb))
            .twist()
            .units("rad"),
    );
    Ok(())
}
