//! [`Load`]: a constant applied force and moment, dead or following a body.

use super::Validation;
use super::{Body, Field, GROUND, Item, ModelScalar, Name, Vec3, map3, name, visit3, zero3};
use crate::assemble::{Assembly, Term};
use crate::error::ModelError;
use crate::geometry::{self, cross, mat_add, mat_mul, scale, skew, sub};
use crate::warning::{ItemRef, Warning};
use eom_sym::scalar::Scalar;

/// A constant applied force and moment. `frame` names the body whose axes the direction is
/// fixed to: the ground for a dead load (gravity), the loaded body itself for a follower load.
#[derive(Clone, Debug, PartialEq)]
pub struct Load<S> {
    /// Unique name.
    pub name: Name,
    /// Loaded body.
    pub body: Name,
    /// Point of application.
    pub location: Vec3<S>,
    /// Force (global components at the nominal configuration).
    pub force: Vec3<S>,
    /// Moment.
    pub moment: Vec3<S>,
    /// The frame that carries the load's direction.
    pub frame: Name,
}

impl<S: Scalar> Load<S> {
    /// A zero dead load on `body`.
    pub fn new(n: &str, body: &str) -> Self {
        Load {
            name: name(n),
            body: name(body),
            location: zero3(),
            force: zero3(),
            moment: zero3(),
            frame: name(GROUND),
        }
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
    /// Point of application.
    pub fn at(mut self, location: Vec3<S>) -> Self {
        self.location = location;
        self
    }
    /// Force.
    pub fn force(mut self, f: Vec3<S>) -> Self {
        self.force = f;
        self
    }
    /// Moment.
    pub fn moment(mut self, m: Vec3<S>) -> Self {
        self.moment = m;
        self
    }
    /// Make it a follower load whose direction is fixed in `frame` (a body name).
    pub fn frame(mut self, frame: &str) -> Self {
        self.frame = name(frame);
        self
    }
}

impl<S: Scalar> Load<S> {
    /// The load converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Load<T> {
        Load {
            name: self.name.clone(),
            body: self.body.clone(),
            location: map3(&self.location, f),
            force: map3(&self.force, f),
            moment: map3(&self.moment, f),
            frame: self.frame.clone(),
        }
    }
}

impl<S: ModelScalar> Item<S> for Load<S> {
    fn kind(&self) -> &'static str {
        "load"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        vec![
            ("body", super::Setting::Text(self.body.to_string())),
            ("frame", super::Setting::Text(self.frame.to_string())),
        ]
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        visit3(f, "location", &self.location);
        visit3(f, "force", &self.force);
        visit3(f, "moment", &self.moment);
    }

    fn bodies(&self) -> &[Name] {
        std::slice::from_ref(&self.body)
    }

    fn supports(&self) -> bool {
        false
    }

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
