//! [`Load`]: a constant applied force and moment, dead or following a body.

use super::Validation;
use super::{Body, GROUND, ModelScalar, Name, Physics, Vec3, item, name, zero3};
use crate::assemble::{Assembly, Term};
use crate::error::ModelError;
use crate::geometry::{self, cross, mat_add, mat_mul, scale, skew, sub};
use crate::warning::{ItemRef, Warning};
use eom_sym::scalar::Scalar;

item! {
    /// A constant applied force and moment. `frame` names the body whose axes the direction is
    /// fixed to: the ground for a dead load (gravity), the loaded body itself for a follower
    /// load.
    pub struct Load<S>: "load", "load"
        (bodies: body, supports: false)
    {
        /// Loaded body.
        pub body: Name = name(GROUND) => body(on, "body"),
        /// Point of application.
        pub location: Vec3<S> = zero3() => vector(at, "at", Polar),
        /// Force (global components at the nominal configuration).
        pub force: Vec3<S> = zero3() => vector(force, "force", Polar),
        /// Moment.
        pub moment: Vec3<S> = zero3() => vector(moment, "moment", Axial),
        /// The frame that carries the load's direction: a follower load's direction is fixed
        /// in this body.
        pub frame: Name = name(GROUND) => body(frame, "frame"),
    }
}

impl<S: Scalar> Load<S> {
    /// A zero dead load on `body`.
    pub fn new(n: &str, body: &str) -> Self {
        Self::declared(n).on(body)
    }
    /// Weight of a body: force `m·g` along `−z` (pass a negative `g` for a z-down model),
    /// applied at its mass centre.
    pub fn weight(body: &Body<S>, g: impl Into<S>) -> Self {
        let g = g.into();
        Load {
            name: name(&format!("{} weight", body.name)),
            body: body.name.clone(),
            location: body.location,
            force: [S::zero(), S::zero(), -(body.mass * g)],
            moment: zero3(),
            frame: name(GROUND),
        }
    }
}

impl<S: ModelScalar> Physics<S> for Load<S> {
    /// The frame must be a body or the ground.
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        cx.check_body("load", &self.name, "frame", &self.frame)
    }

    /// The generalized force on the loaded body, and the load stiffness: the force turns
    /// with the frame that carries its direction, and its moment arm with the loaded body.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (Some(p1), p2) = (cx.body(&self.body), cx.body(&self.frame)) else {
            cx.warn(Warning::LoadOnGround {
                item: ItemRef::new("load", &self.name),
            });
            return Ok(());
        };
        let r = sub(&self.location, &cx.mass_centre(Some(p1)));
        let mom = geometry::sub(&self.moment, &scale(-S::one(), &cross(&r, &self.force)));
        for (i, (&f, &m)) in self.force.iter().zip(&mom).enumerate() {
            if !f.is_zero() {
                cx.add_applied(6 * p1 + i, f);
            }
            if !m.is_zero() {
                cx.add_applied(6 * p1 + 3 + i, m);
            }
        }
        if p2 == Some(p1) {
            return Ok(()); // follower load fixed in its own body: the terms cancel exactly
        }
        let f0 = skew(&self.force);
        let rf = mat_add(&mat_mul(&skew(&r), &f0), &skew(&self.moment));
        let p1 = Some(p1);
        cx.add_block(Term::LoadStiffness, (p1, 0), (p1, 3), &f0, -1.0);
        cx.add_block(Term::LoadStiffness, (p1, 0), (p2, 3), &f0, 1.0);
        cx.add_block(Term::LoadStiffness, (p1, 3), (p1, 3), &rf, -1.0);
        cx.add_block(Term::LoadStiffness, (p1, 3), (p2, 3), &rf, 1.0);
        Ok(())
    }
}
