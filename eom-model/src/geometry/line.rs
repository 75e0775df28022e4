//! [`Line`]: the shape of the two-point items (links, springs, actuators and sensors): two
//! bodies and an end on each; with its builders and checks.

use super::{GROUND, Name, Vec3, map3, name, zero3};
use crate::error::{Degeneracy, ItemRef, ModelError};
use eom_sym::scalar::Scalar;

/// Fields shared by the two-point ("line") items: links, springs, actuators and sensors.
#[derive(Clone, Debug, PartialEq)]
pub struct Line<S> {
    /// `[body 1, body 2]`.
    pub bodies: [Name; 2],
    /// `[end 1 (on body 1), end 2 (on body 2)]`.
    pub ends: [Vec3<S>; 2],
    /// `false`: acts along the line (force, elongation); `true`: torsional about the line.
    pub twist: bool,
}

impl<S: Scalar> Line<S> {
    pub(crate) fn new() -> Self {
        Line {
            bodies: [name(GROUND), name(GROUND)],
            ends: [zero3(), zero3()],
            twist: false,
        }
    }

    /// The line converted with `f`: end 1, then end 2.
    pub(crate) fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Line<T> {
        Line {
            bodies: self.bodies.clone(),
            ends: [map3(&self.ends[0], f), map3(&self.ends[1], f)],
            twist: self.twist,
        }
    }

    /// The two ends must not coincide (the direction would be undefined).
    pub(crate) fn validate(&self, kind: &'static str, item: &str) -> Result<(), ModelError> {
        let t = super::sub(&self.ends[1], &self.ends[0]);
        let len2: f64 = t.iter().map(|x| x.nominal() * x.nominal()).sum();
        if len2 == 0.0 {
            return Err(ModelError::Degenerate {
                item: ItemRef::new(kind, item),
                field: "ends".into(),
                shape: Degeneracy::CoincidentEnds { direction: true },
            });
        }
        Ok(())
    }
}

/// The builders of a line item (a struct with a `line: Line<S>` field).
macro_rules! line_builders {
    ($t:ident) => {
        impl<S: Scalar> $t<S> {
            /// The two bodies (end 1 on `b1`, end 2 on `b2`).
            pub fn between(mut self, b1: &str, b2: &str) -> Self {
                self.line.bodies = [$crate::geometry::Name::from(b1), b2.into()];
                self
            }
            /// The two end points.
            pub fn ends(
                mut self,
                p1: $crate::geometry::Vec3<S>,
                p2: $crate::geometry::Vec3<S>,
            ) -> Self {
                self.line.ends = [p1, p2];
                self
            }
            /// Act about the line (torsion) instead of along it.
            pub fn twist(mut self) -> Self {
                self.line.twist = true;
                self
            }
        }
    };
}
pub(crate) use line_builders;
