//! [`RigidPoint`]: a holonomic joint at a point: some relative translations and rotations of two bodies are zero.

use super::{ModelScalar, Physics, item};
use crate::assemble::{Assembly, Reaction};
use crate::error::ModelError;
use crate::geometry::Point;
use eom_sym::scalar::Scalar;

item! {
    /// A holonomic joint.
    pub struct RigidPoint<S>: "rigid point", "rigid_point"
        (bodies: point, supports: point.constrains())
    {
        /// Geometry.
        pub point: Point<S> = Point::new() => point(),
    }
    /// A joint between ground and ground (set bodies and directions).
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for RigidPoint<S> {
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
