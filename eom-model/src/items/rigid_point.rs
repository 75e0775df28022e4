//! [`RigidPoint`]: a holonomic joint at a point: some relative translations and rotations of two bodies are zero.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::{Assembly, Reaction};
use crate::error::ModelError;
use crate::geometry::{Point, point_builders};
use eom_sym::scalar::Scalar;

/// A holonomic joint.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidPoint<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub point: Point<S>,
}
impl<S: Scalar> RigidPoint<S> {
    /// A joint between ground and ground (set bodies and directions).
    pub fn new(n: &str) -> Self {
        RigidPoint {
            name: name(n),
            point: Point::new(),
        }
    }
}
point_builders!(RigidPoint);

impl<S: Scalar> RigidPoint<S> {
    /// The rigidpoint converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> RigidPoint<T> {
        RigidPoint {
            name: self.name.clone(),
            point: self.point.map(f),
        }
    }
}

impl<S: ModelScalar> Item<S> for RigidPoint<S> {
    fn kind(&self) -> &'static str {
        "rigid point"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        self.point.settings()
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.point.fields(f);
    }

    fn bodies(&self) -> &[Name] {
        &self.point.bodies
    }

    fn supports(&self) -> bool {
        self.point.constrains()
    }

    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.point
            .validate("rigid point", &self.name, &mut |w| cx.warn(w))
    }

    /// One holonomic row per constrained direction; the multipliers are the joint's force and
    /// moment.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.point(&self.point, "rigid point", &self.name);
        cx.holonomic(
            "rigid point",
            &self.name,
            rows,
            Reaction::Point(&self.point, geometry),
        );
        Ok(())
    }
}
