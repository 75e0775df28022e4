//! [`NhPoint`]: a nonholonomic constraint on the relative velocity at a point (e.g. a tyre that cannot slip).

use super::{ModelScalar, Physics, item};
use crate::assemble::Assembly;
use crate::error::ModelError;
use crate::geometry::Point;
use eom_sym::scalar::Scalar;

item! {
    /// A nonholonomic constraint on relative velocity (e.g. a no-slip tyre).
    pub struct NhPoint<S>: "nh point", "nh_point"
        (bodies: point, supports: point.constrains())
    {
        /// Geometry.
        pub point: Point<S> = Point::new() => point(),
    }
    /// A constraint between ground and ground (set bodies and directions).
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for NhPoint<S> {
    /// One nonholonomic row per constrained direction.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, _) = cx.point(&self.point, "nh point", &self.name);
        cx.nonholonomic(rows);
        Ok(())
    }
}
