//! [`Spring`]: a spring–damper–inerter along (or, twisted, about) a line.

use super::{ModelScalar, Physics, item};
use crate::assemble::{Assembly, Reaction, Term};
use crate::error::ModelError;
use crate::geometry::Line;
use eom_sym::scalar::Scalar;

item! {
    /// A spring–damper–inerter along (or, twisted, about) a line.
    pub struct Spring<S>: "spring", "spring"
        (bodies: line, supports: true)
    {
        /// Geometry.
        pub line: Line<S> = Line::new() => line(),
        /// Stiffness (N/m, or N·m/rad twisted).
        pub stiffness: S = S::zero() => scalar(stiffness, "stiffness"),
        /// Damping.
        pub damping: S = S::zero() => scalar(damping, "damping"),
        /// Inertance (force proportional to relative acceleration).
        pub inertance: S = S::zero() => scalar(inertance, "inertance"),
        /// Known tension at the given geometry; `None` = solved from equilibrium.
        pub preload: Option<S> = None => optional(preload, "preload"),
    }
    /// A spring with zero properties.
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for Spring<S> {
    /// One elastic row with its stiffness, damping and inertance; its multiplier is the
    /// tension, known when a preload is given.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.line(&self.line, "spring", &self.name);
        cx.add_rows_block(Term::Stiffness, &rows.rows, &[vec![self.stiffness]]);
        cx.add_rows_block(Term::Damping, &rows.rows, &[vec![self.damping]]);
        cx.add_rows_block(Term::ItemMass, &rows.rows, &[vec![self.inertance]]);
        let row = cx.elastic(
            "spring",
            &self.name,
            rows,
            vec![vec![self.stiffness]],
            Reaction::Line(geometry),
        );
        if let Some(p) = self.preload {
            cx.known_preload(row, p, self.stiffness);
        }
        Ok(())
    }
}
