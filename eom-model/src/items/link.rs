//! [`Link`]: an inextensible rigid link between two bodies.

use super::{ModelScalar, Physics, item};
use crate::assemble::{Assembly, Reaction};
use crate::error::ModelError;
use crate::geometry::Line;
use eom_sym::scalar::Scalar;

item! {
    /// An inextensible rigid link.
    pub struct Link<S>: "link", "link"
        (bodies: line, supports: true)
    {
        /// Geometry.
        pub line: Line<S> = Line::new() => line(),
    }
    /// A link between ground and ground (set bodies and ends).
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for Link<S> {
    /// One holonomic row; its multiplier is the tension.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.line(&self.line, "link", &self.name);
        cx.holonomic("link", &self.name, rows, Reaction::Line(geometry));
        Ok(())
    }
}
