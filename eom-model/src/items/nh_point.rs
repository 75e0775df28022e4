//! [`NhPoint`]: a nonholonomic constraint on the relative velocity at a point (e.g. a tyre that cannot slip).

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::Assembly;
use crate::error::ModelError;
use crate::geometry::{Point, point_builders};
use eom_sym::scalar::Scalar;

/// A nonholonomic constraint on relative velocity (e.g. a no-slip tyre).
#[derive(Clone, Debug, PartialEq)]
pub struct NhPoint<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub point: Point<S>,
}
impl<S: Scalar> NhPoint<S> {
    /// A constraint between ground and ground (set bodies and directions).
    pub fn new(n: &str) -> Self {
        NhPoint {
            name: name(n),
            point: Point::new(),
        }
    }
}
point_builders!(NhPoint);

impl<S: Scalar> NhPoint<S> {
    /// The nhpoint converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> NhPoint<T> {
        NhPoint {
            name: self.name.clone(),
            point: self.point.map(f),
        }
    }
}

impl<S: ModelScalar> Item<S> for NhPoint<S> {
    fn kind(&self) -> &'static str {
        "nh point"
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
            .validate("nh point", &self.name, &mut |w| cx.warn(w))
    }

    /// One nonholonomic row per constrained direction.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, _) = cx.point(&self.point, "nh point", &self.name);
        cx.nonholonomic(rows);
        Ok(())
    }
}
