//! [`Point`]: the shape of the point items (rigid, flexible and nonholonomic points): two
//! bodies, a location, the constrained directions; with its builders and checks.

use super::{GROUND, Name, Vec3, map3, name, zero3};
use crate::error::{Degeneracy, ModelError};
use crate::warning::{ItemRef, Warning};
use eom_sym::scalar::Scalar;

/// Fields shared by the point items (rigid, flexible and nonholonomic points).
#[derive(Clone, Debug, PartialEq)]
pub struct Point<S> {
    /// `[body 1, body 2]`.
    pub bodies: [Name; 2],
    /// The point.
    pub location: Vec3<S>,
    /// Number of constrained translational directions: 3 all, 2 perpendicular to `axis`,
    /// 1 along `axis`, 0 none.
    pub forces: u8,
    /// Number of constrained rotational directions (same meaning).
    pub moments: u8,
    /// Axis for `forces`/`moments` of 1 or 2.
    pub axis: Vec3<S>,
    /// Rolling axis (nonzero: a rolling contact; body 1 rolls on body 2).
    pub rolling_axis: Vec3<S>,
}

impl<S: Scalar> Point<S> {
    pub(crate) fn new() -> Self {
        Point {
            bodies: [name(GROUND), name(GROUND)],
            location: zero3(),
            forces: 0,
            moments: 0,
            axis: zero3(),
            rolling_axis: zero3(),
        }
    }

    /// The point converted with `f`: the location, the axis, the rolling axis.
    pub(crate) fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Point<T> {
        Point {
            bodies: self.bodies.clone(),
            location: map3(&self.location, f),
            forces: self.forces,
            moments: self.moments,
            axis: map3(&self.axis, f),
            rolling_axis: map3(&self.rolling_axis, f),
        }
    }

    /// Whether the point constrains (or supports) anything.
    pub(crate) fn constrains(&self) -> bool {
        self.forces + self.moments > 0
    }

    /// Direction counts in range, an axis where one is needed; a point that constrains
    /// nothing is a warning, given to `warn`.
    pub(crate) fn validate(
        &self,
        kind: &'static str,
        item: &str,
        warn: &mut dyn FnMut(Warning),
    ) -> Result<(), ModelError> {
        for (field, v) in [("forces", self.forces), ("moments", self.moments)] {
            if v > 3 {
                return Err(ModelError::OutOfRange {
                    item: ItemRef::new(kind, item),
                    field: field.into(),
                    value: v.into(),
                    min: 0,
                    max: 3,
                });
            }
        }
        let axis_zero = self.axis.iter().all(|x| x.nominal() == 0.0);
        if axis_zero && (matches!(self.forces, 1 | 2) || matches!(self.moments, 1 | 2)) {
            return Err(ModelError::Degenerate {
                item: ItemRef::new(kind, item),
                field: "axis".into(),
                shape: Degeneracy::ZeroAxis {
                    forces: self.forces,
                    moments: self.moments,
                },
            });
        }
        if !self.constrains() {
            warn(Warning::ConstrainsNothing {
                item: ItemRef::new(kind, item),
            });
        }
        Ok(())
    }
}

/// The builders of a point item (a struct with a `point: Point<S>` field).
macro_rules! point_builders {
    ($t:ident) => {
        impl<S: Scalar> $t<S> {
            /// The two bodies.
            pub fn between(mut self, b1: &str, b2: &str) -> Self {
                self.point.bodies = [$crate::geometry::Name::from(b1), b2.into()];
                self
            }
            /// The point.
            pub fn at(mut self, location: $crate::geometry::Vec3<S>) -> Self {
                self.point.location = location;
                self
            }
            /// Number of constrained translational directions.
            pub fn forces(mut self, n: u8) -> Self {
                self.point.forces = n;
                self
            }
            /// Number of constrained rotational directions.
            pub fn moments(mut self, n: u8) -> Self {
                self.point.moments = n;
                self
            }
            /// Axis for 1- or 2-direction constraints.
            pub fn axis(mut self, a: $crate::geometry::Vec3<S>) -> Self {
                self.point.axis = a;
                self
            }
            /// Rolling axis (makes it a rolling contact).
            pub fn rolling_axis(mut self, a: $crate::geometry::Vec3<S>) -> Self {
                self.point.rolling_axis = a;
                self
            }
        }
    };
}
pub(crate) use point_builders;
